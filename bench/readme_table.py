#!/usr/bin/python3
"""The README's results table from bench/run's JSON lines.

usage: /usr/bin/python3 bench/readme_table.py bench/results/latest.jsonl

One row per case (the duplicate `file.*_tetgen-*` copies of the generated
TetGen meshes are left out): min / max dihedral angle before and after 20
steps of bodt-smooth, bodt and opt (paper 001's combined method), the share
of tets with every angle in [30, 140] degrees before and after bodt, bodt's
vertex growth and relative Hausdorff distance, and the times of bodt and opt.
"""
import json
import sys


def angles(d):
    return f'{d["min_dihedral"]:.1f} / {d["max_dihedral"]:.1f}'


def main(path):
    rows, order = {}, []
    for line in open(path):
        r = json.loads(line)
        if r.get("status") != "ok" or "_tetgen-" in r["case"]:
            continue
        if r["case"] not in rows:
            rows[r["case"]] = {}
            order.append(r["case"])
        rows[r["case"]][r["variant"]] = r
    print("| mesh | tets | before | bodt-smooth | bodt | opt | in [30°,140°] before → bodt | new vertices | bodt H | bodt s | opt s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for case in order:
        v = rows[case]
        if not all(k in v for k in ("bodt", "bodt-smooth", "opt")):
            continue
        b, s, o = v["bodt"], v["bodt-smooth"], v["opt"]
        print(f'| {case.replace("file.", "")} | {b["tets_in"]} | {angles(b["before"])} | {angles(s["after"])} '
              f'| **{angles(b["after"])}** | {angles(o["after"])} '
              f'| {b["pct_dihedral_30_140_before"]:.1f}% → {b["pct_dihedral_30_140"]:.1f}% '
              f'| {b["vertex_growth_pct"]:+.1f}% | {100 * b["hausdorff_rel"]:.2g}% | {b["time_s"]:.2f} | {o["time_s"]:.2f} |')


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
