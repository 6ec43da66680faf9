#!/usr/bin/python3
"""The results tables of docs/results.md from bench/run's JSON lines (the
first, the bench set against the peers, is also README.md's).

usage: /usr/bin/python3 bench/readme_table.py bench/results/latest.jsonl [SCALE.jsonl ...]

From the bench set (the first file; the duplicate `file.*_tetgen-*` copies
of the generated TetGen meshes are left out): one row per mesh with the min /
max dihedral angle before and after 20 steps of bodt-smooth, bodt, nodt and
opt (paper 001's combined method) and after the peers (TetGen's and Gmsh's
optimisers), the seconds of each, how long bodt's steps took to pass each
peer's minimum angle, bodt's vertex growth and relative Hausdorff distance.
From each scale series (the further files, e.g. bench/results/scale.jsonl
and scale1e7.jsonl): time, updates per second and bytes per tet per box,
variant and thread count.  Then the targets of all runs (for a target
measured in several, the last file's).
"""
import json
import sys

OURS = ("bodt-smooth", "bodt", "nodt", "opt")
PEERS = (("tetgen-rO9/7", "TetGen"), ("gmsh", "Gmsh"), ("gmsh-netgen", "Gmsh Netgen"))


def angles(d):
    return f'{d["min_dihedral"]:.1f} / {d["max_dihedral"]:.1f}'


def secs(s):
    if s is None:
        return "never"
    return f"{s:.4f}" if 0 < s < 0.01 else f"{s:.2f}"


def load(path):
    rows, order, targets = {}, [], []
    for line in open(path):
        r = json.loads(line)
        if "targets" in r:
            targets = r["targets"]
            continue
        if r["case"] not in rows:
            rows[r["case"]] = {}
            order.append(r["case"])
        rows[r["case"]][r["variant"]] = r
    return rows, order, targets


def bench_table(rows, order):
    ran = lambda v, k: k in v and v[k].get("status") == "ok"
    present = [k for k in OURS if any(ran(rows[c], k) for c in order)]
    peers = [(k, n) for k, n in PEERS if any(ran(rows[c], k) for c in order)]
    head = ["mesh", "tets", "before"] + present + [n for _, n in peers]
    head += [f"{k} s" for k in present] + [f"{n} s" for _, n in peers]
    head += [f"bodt passes {n} at s" for _, n in peers] + ["bodt new vertices", "bodt H"]
    print("| " + " | ".join(head) + " |")
    print("|---|" + "---:|" * (len(head) - 1))
    for case in order:
        v = rows[case]
        if "_tetgen-" in case or not ran(v, "bodt"):
            continue
        b = v["bodt"]
        cells = [case.replace("file.", ""), str(b["tets_in"]), angles(b["before"])]
        for k in present:
            a = angles(v[k]["after"]) if ran(v, k) else v.get(k, {}).get("status", "–")
            cells.append(f"**{a}**" if k == "bodt" else a)
        for k, _ in peers:
            cells.append(angles(v[k]["after"]) if ran(v, k) else v.get(k, {}).get("status", "–"))
        cells += [secs(v[k]["time_s"]) if ran(v, k) else "–" for k in present]
        cells += [secs(v[k]["time_s"]) if ran(v, k) else "–" for k, _ in peers]
        for k, _ in peers:
            if not ran(v, k):
                cells.append("–")
                continue
            t = b.get("time_to_beat_s", {}).get(k)
            mark = "" if t is not None and t < v[k]["time_s"] else " ✗"
            cells.append(("0" if t == 0 else secs(t)) + mark)
        cells += [f'{b["vertex_growth_pct"]:+.1f}%', f'{100 * b["hausdorff_rel"]:.2g}%' if b["hausdorff_rel"] is not None else "–"]
        print("| " + " | ".join(cells) + " |")


def scale_table(rows, order):
    print("| box | tets | variant | threads | create s | s | s per 10k tets | updates/s | updates/s/thread | parallelism | B/tet | peak RSS MB | min / max after |")
    print("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for case in order:
        for name, r in rows[case].items():
            if r.get("peer") or r.get("status") != "ok":
                continue
            create = f'{r["create_s"]:.2f}' if r.get("create_s") is not None else "–"  # older results lack it
            print(f'| {case} | {r["tets_in"]} | {r["variant_base"]} | {r["threads_used"]} | {create} | {r["time_s"]:.2f} '
                  f'| {r["s_per_10k_tets"]:.3g} | {r["vertex_updates_per_s"]:.3g} | {r["updates_per_s_per_thread"]:.3g} '
                  f'| {r["parallelism"]:.2f} | {r["bytes_per_tet"]:.0f} / {r["bytes_per_tet_after"]:.0f} '
                  f'| {r["peak_rss_mb"]:.0f} | {angles(r["after"])} |')


def targets_table(lists):
    merged, order = {}, []
    for targets in lists:
        for t in targets:
            if t["id"] not in merged:
                order.append(t["id"])
            if t["id"] not in merged or t["verdict"] != "NOT RUN":
                merged[t["id"]] = t
    # a placeholder ("c": not measured) goes when its parts ("c.bodt@1.jitter", ...) were measured
    order = [i for i in order if not (merged[i]["verdict"] == "NOT RUN" and any(j.startswith(i + ".") for j in order))]
    order.sort(key=lambda i: i.split(".")[0])  # stable: a, b, c, d
    print("| target | measured | bar | verdict |")
    print("|---|---|---|---|")
    for i in order:
        t = merged[i]
        detail = t.get("detail", "")
        if detail.startswith("missed: ") and " more (" not in detail and detail.count(", ") > 6:  # older runs listed every pair
            parts = detail[len("missed: "):].split(", ")
            detail = "missed: " + ", ".join(parts[:6]) + f" and {len(parts) - 6} more (bench/results/latest.md)"
        value = t["value"] + (" — " + detail if detail else "")
        print(f'| {t["id"]}: {t["what"]} | {value} | {t["bar"]} | **{t["verdict"]}** |')


def main(paths):
    rows, order, targets = load(paths[0])
    bench_table(rows, order)
    all_targets = [targets]
    for path in paths[1:]:
        srows, sorder, stargets = load(path)
        print()
        scale_table(srows, sorder)
        all_targets.append(stargets)
    print()
    targets_table(all_targets)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
