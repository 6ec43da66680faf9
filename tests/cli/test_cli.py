#!/usr/bin/python3
"""Tests of the bodt command, run by CTest (see tests/CMakeLists.txt).

    test_cli.py --bodt PATH --data DIR --out DIR CASE

CASE is one of quality_json, improve, improve_ops, exit_codes,
improve_opt_weighted, improve_phased, improve_surface (with TetGen),
surface_without_tetgen (without), compare, convert, convert_formats (needs
the .meshb, .msh, .vtu and .inp writers), param, progress (uses a
pseudo-terminal and a named pipe for a slow read), histogram, help, report,
early_output (named pipes as inputs that must not be read), threads,
improve_json, inverted_message, file_numbering.  Every value checked comes from running the
command; expected mesh quality is recomputed here from the mesh file with
plain Python (no library code).  Every check runs, a failed one is
printed; exits 0 when all passed, else 1.
"""
import argparse
import glob
import json
import math
import os
import struct
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import medit_files  # noqa: E402
from checks import FAILURES, check, exit_status, run  # noqa: E402
from medit_files import write_medit  # noqa: E402


# ------------------------------------------------------------ independent geometry

def read_medit_full(path):
    """Vertices, 0-based tets, tet refs and [(0-based triangle, ref)] of a Medit file."""
    m = medit_files.read_medit(path)
    return m["points"], m["tets"], m["regions"], list(zip(m["triangles"], m["markers"]))


def read_medit(path):
    """Vertices (list of 3-tuples) and tets (0-based 4-tuples) of a Medit file."""
    pts, tets, _, _ = read_medit_full(path)
    return pts, tets


def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def norm(a): return math.sqrt(dot(a, a))


def dihedrals(p):
    """Six interior dihedral angles (degrees) of tet p: at edge (i, j) the
    angle between the other two vertices seen perpendicular to the edge."""
    out = []
    for i in range(4):
        for j in range(i + 1, 4):
            k, l = [m for m in range(4) if m not in (i, j)]
            e = sub(p[j], p[i])
            n1, n2 = cross(e, sub(p[k], p[i])), cross(e, sub(p[l], p[i]))
            c = max(-1.0, min(1.0, dot(n1, n2) / (norm(n1) * norm(n2))))
            out.append(math.degrees(math.acos(c)))
    return out


def stretch(p):
    v = dot(sub(p[1], p[0]), cross(sub(p[2], p[0]), sub(p[3], p[0]))) / 6.0
    area = sum(0.5 * norm(cross(sub(p[b], p[a]), sub(p[c], p[a])))
               for a, b, c in ((1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2)))
    lmax = max(norm(sub(p[j], p[i])) for i in range(4) for j in range(i + 1, 4))
    return 6.0 * math.sqrt(6.0) * v / (area * lmax), v


def quality_of(path):
    pts, tets = read_medit(path)
    angles, stretches, volume = [], [], 0.0
    for t in tets:
        p = [pts[v] for v in t]
        s, v = stretch(p)
        angles += dihedrals(p)
        stretches.append(s)
        volume += v
    return {"vertices": len(pts), "tets": len(tets), "angles": angles, "stretches": stretches, "volume": volume,
            "min_dihedral": min(angles), "max_dihedral": max(angles),
            "mean_dihedral": sum(angles) / len(angles),
            "stretch_min": min(stretches), "stretch_mean": sum(stretches) / len(stretches)}


EDGES = [0, 5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150, 160, 165, 170, 175, 180]


def check_histogram(hist, angles):
    check(len(hist) == len(EDGES) - 1, "histogram has %d bins" % len(hist))
    check(sum(hist) == len(angles), "histogram sums to %d, expected %d" % (sum(hist), len(angles)))
    clear = [0] * (len(EDGES) - 1)
    ambiguous = [0] * len(EDGES)  # angles within round-off of inner edge k
    for a in angles:
        near = [k for k in range(1, len(EDGES) - 1) if abs(a - EDGES[k]) < 1e-9]
        if near:
            ambiguous[near[0]] += 1
            continue
        b = 0
        while b < len(EDGES) - 2 and a >= EDGES[b + 1]:
            b += 1
        clear[b] += 1
    for b in range(len(clear)):
        lo, hi = clear[b], clear[b] + ambiguous[b] + ambiguous[b + 1]
        check(lo <= hist[b] <= hi,
              "bin %d [%g, %g): %d, expected %d..%d" % (b, EDGES[b], EDGES[b + 1], hist[b], lo, hi))


def one_json_object(out, what):
    """The JSON object that `what` printed as its one line of output, or None."""
    lines = [l for l in out.splitlines() if l.strip()]
    check(len(lines) == 1, "%s printed %d lines, expected one: %r" % (what, len(lines), out))
    try:
        obj = json.loads(out)
    except ValueError as e:
        check(False, "%s: not JSON (%s): %r" % (what, e, out))
        return None
    check(isinstance(obj, dict), "%s: the JSON is not an object" % what)
    return obj


def quality_json(args, path):
    code, out, err = run(args.bodt, "quality", path, "--json")
    if not check(code == 0, "bodt quality %s --json exited %d: %s" % (path, code, err)):
        return None
    return one_json_object(out, "quality --json")


# ----------------------------------------------------------------------- cases

def case_quality_json(args):
    path = os.path.join(args.data, "box2.mesh")
    q = quality_json(args, path)
    if q is None:
        return
    for key in ("vertices", "tets", "min_dihedral", "max_dihedral", "min_stretch", "mean_stretch", "inverted",
                "volume", "boundary_faces", "mean_dihedral", "dihedral_histogram", "stretch_min", "stretch_mean"):
        check(key in q, "key %s missing from %s" % (key, sorted(q)))
    if FAILURES:
        return
    # min_stretch and mean_stretch, as bodt_quality and the Python API name
    # them; the deprecated stretch_min and stretch_mean the same values
    check(q["stretch_min"] == q["min_stretch"] and q["stretch_mean"] == q["mean_stretch"],
          "deprecated names differ: %r" % q)
    q["stretch_min"], q["stretch_mean"] = q.pop("min_stretch"), q.pop("mean_stretch")
    # the known numbers of tests/data/box2.mesh (see tests/data/README)
    check(q["vertices"] == 27, "vertices %r" % q["vertices"])
    check(q["tets"] == 48, "tets %r" % q["tets"])
    check(q["boundary_faces"] == 50, "boundary_faces %r" % q["boundary_faces"])
    check(q["inverted"] == 0, "inverted %r" % q["inverted"])
    check(abs(q["volume"] - 8.0) <= 1e-12, "volume %r" % q["volume"])
    check(q.get("mesh") == path, "mesh %r" % q.get("mesh"))
    # recomputed here from the file
    ref = quality_of(path)
    check(abs(ref["volume"] - 8.0) <= 1e-12, "independent volume %r" % ref["volume"])
    for key in ("min_dihedral", "max_dihedral", "mean_dihedral", "stretch_min", "stretch_mean"):
        check(abs(q[key] - ref[key]) <= 1e-6, "%s: bodt %r, recomputed %r" % (key, q[key], ref[key]))
    # and against literal values worked out once from the file with the
    # formulas above (guards the recomputation itself)
    check(abs(ref["min_dihedral"] - 29.054604) < 1e-6, "recomputed min dihedral %r" % ref["min_dihedral"])
    check(abs(ref["stretch_min"] - 0.433519) < 1e-6, "recomputed min stretch %r" % ref["stretch_min"])
    check_histogram(q["dihedral_histogram"], ref["angles"])
    # the table form works too
    code, out, err = run(args.bodt, "quality", path)
    check(code == 0 and "min dihedral" in out and "29.055" in out, "bodt quality (table): %d %r %r" % (code, out, err))


def case_improve(args):
    src = os.path.join(args.data, "box2.mesh")
    os.makedirs(args.out, exist_ok=True)
    dst = os.path.join(args.out, "box2_improved.mesh")
    if os.path.exists(dst):
        os.remove(dst)
    code, out, err = run(args.bodt, "improve", src, dst, "--mode", "laplace", "--iterations", "5")
    check(code == 0, "bodt improve exited %d: %s" % (code, err))
    check("before" in out and "after" in out and ("wrote " + dst) in out, "improve output: %r" % out)
    check(os.path.exists(dst), "%s was not written" % dst)
    if FAILURES:
        return
    before, after = quality_json(args, src), quality_json(args, dst)
    if before is None or after is None:
        return
    check(after["min_dihedral"] >= before["min_dihedral"],
          "min dihedral went down: %r -> %r" % (before["min_dihedral"], after["min_dihedral"]))
    check(after["stretch_min"] >= before["stretch_min"], "min stretch went down")
    for key in ("vertices", "tets", "boundary_faces", "inverted"):
        check(after[key] == before[key], "%s: %r -> %r" % (key, before[key], after[key]))
    check(abs(after["volume"] - 8.0) <= 1e-12, "volume after %r" % after["volume"])
    # only the centre vertex (the one interior vertex) may move
    p0, t0 = read_medit(src)
    p1, t1 = read_medit(dst)
    check(t0 == t1, "the tets changed")
    moved = [v for v in range(len(p0)) if p0[v] != p1[v]]
    check(moved == [13], "moved vertices %r, expected [13]" % moved)
    ref = quality_of(dst)
    check(abs(after["min_dihedral"] - ref["min_dihedral"]) <= 1e-6, "the written file's min dihedral")
    # TetGen output, read back
    node = os.path.join(args.out, "box2_improved.node")
    code, out, err = run(args.bodt, "improve", src, node, "--iterations", "3")
    check(code == 0, "improve to .node exited %d: %s" % (code, err))
    for ext in (".node", ".ele", ".face"):
        check(os.path.exists(node[:-5] + ext), "%s not written" % (node[:-5] + ext))
    q = quality_json(args, node[:-5] + ".ele")
    if q is not None:
        check(q["tets"] == 48 and q["inverted"] == 0 and q["min_dihedral"] >= before["min_dihedral"],
              "the .ele read back: %r" % q)


def read_medit_triangles(path):
    """The Triangles of a Medit file as a sorted list of (sorted 0-based
    vertex triple, ref)."""
    return sorted((tuple(sorted(tri)), ref) for tri, ref in read_medit_full(path)[3])


SUMMARY = re.compile(r"^(\d+) steps: (\d+) flips, (\d+) vertices inserted, (\d+) edges collapsed$", re.M)


def improve_summary(args, *argv):
    """Runs bodt improve; (exit code, (steps, flips, inserted, collapsed) or None, stdout, stderr)."""
    code, out, err = run(args.bodt, "improve", *argv)
    m = SUMMARY.search(out)
    return code, tuple(int(x) for x in m.groups()) if m else None, out, err


def write_jittered_box(path, n, size, jitter, seed):
    """The box [0, size]^3 in n^3 cubes of six Kuhn tets each, every grid
    coordinate strictly inside (0, size) moved by up to jitter * h (so
    boundary vertices stay on their sides, edges and corners), from the
    first seed from `seed` on that inverts no tet."""
    h = size / n
    idx = lambda i, j, k: (k * (n + 1) + j) * (n + 1) + i
    kuhn = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7)]
    grid = [(i, j, k) for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
    tets = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                c = [idx(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1)) for b in range(8)]
                for q in kuhn:
                    t = [c[x] for x in q]
                    p = [tuple(h * g for g in grid[v]) for v in t]
                    if dot(sub(p[1], p[0]), cross(sub(p[2], p[0]), sub(p[3], p[0]))) < 0:
                        t[0], t[1] = t[1], t[0]
                    tets.append(t)
    for s in range(seed, seed + 200):
        rng = random.Random(s)
        pts = [tuple(h * g + (rng.uniform(-1.0, 1.0) * jitter * h if 0 < g < n else 0.0) for g in gp) for gp in grid]
        if all(dot(sub(pts[t[1]], pts[t[0]]), cross(sub(pts[t[2]], pts[t[0]]), sub(pts[t[3]], pts[t[0]]))) > 0
               for t in tets):
            break
    else:
        raise RuntimeError("no seed gave a valid jittered box")
    write_medit(path, pts, tets)


def check_valid_box(path, what, size=2.0):
    """Every tet of the Medit file positive, volume size^3 (the box [0, size]^3)."""
    q = quality_of(path)
    check(q["stretch_min"] > 0.0, "%s: a tet is inverted or flat (min stretch %r)" % (what, q["stretch_min"]))
    check(abs(q["volume"] - size ** 3) <= 1e-12 * size ** 3, "%s: volume %r" % (what, q["volume"]))
    return q


def case_improve_ops(args):
    """--ops and --keep-surface on box2.mesh with its centre vertex pushed
    towards the top face (tets of 3 degrees; flips have work to do)."""
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.data, "box2.mesh")) as f:
        text = f.read()
    check("\n1.25 0.875 1.125 0\n" in text, "box2.mesh does not have its centre vertex line")
    src = os.path.join(args.out, "box2_pushed.mesh")
    with open(src, "w") as f:
        f.write(text.replace("\n1.25 0.875 1.125 0\n", "\n1 1 1.9 0\n"))
    p0, t0 = read_medit(src)
    q0 = check_valid_box(src, "the input")
    faces0 = None  # the boundary triangles bodt writes for the input connectivity

    # smoothing only: the connectivity stays
    dst = os.path.join(args.out, "box2_ops_smooth.mesh")
    code, summary, out, err = improve_summary(args, src, dst, "--ops", "smooth")
    check(code == 0, "--ops smooth exited %d: %s" % (code, err))
    check(summary is not None, "--ops smooth: no summary line in %r" % out)
    if summary:
        check(summary[0] >= 1 and summary[1:] == (0, 0, 0), "--ops smooth: summary %r" % (summary,))
    check("before" in out and "after" in out and ("wrote " + dst) in out, "--ops smooth output: %r" % out)
    if os.path.exists(dst):
        p1, t1 = read_medit(dst)
        check(t1 == t0, "--ops smooth changed the tets")
        faces0 = read_medit_triangles(dst)
        check(len(faces0) == 50, "--ops smooth wrote %d triangles, expected 50 (48 + 2)" % len(faces0))
        check(p1[13] != p0[13], "--ops smooth did not move the centre vertex")
        q1 = check_valid_box(dst, "--ops smooth")
        check(q1["min_dihedral"] > q0["min_dihedral"], "--ops smooth: min dihedral %r -> %r" %
              (q0["min_dihedral"], q1["min_dihedral"]))

    # flips without smoothing: the tets change, nothing moves, and the
    # summary says how
    dst = os.path.join(args.out, "box2_ops_flip.mesh")
    code, summary, out, err = improve_summary(args, src, dst, "--ops", "flip,insert")
    check(code == 0, "--ops flip,insert exited %d: %s" % (code, err))
    check(summary is not None, "--ops flip,insert: no summary line in %r" % out)
    if summary and os.path.exists(dst):
        p1, t1 = read_medit(dst)
        steps, flips, inserted, collapsed = summary
        check(flips > 0, "--ops flip,insert: %d flips" % flips)
        check(collapsed == 0, "--ops flip,insert: %d collapsed" % collapsed)
        check(len(p1) == len(p0) + inserted, "--ops flip,insert: %d vertices, %d + %d inserted" %
              (len(p1), len(p0), inserted))
        check(sorted(tuple(sorted(t)) for t in t1) != sorted(tuple(sorted(t)) for t in t0),
              "--ops flip,insert reported %d flips but the tets are the same" % flips)
        check(p1[:len(p0)] == p0, "--ops flip,insert moved input vertices")
        q1 = check_valid_box(dst, "--ops flip,insert")
        check(q1["max_dihedral"] <= q0["max_dihedral"] + 1e-9 and q1["min_dihedral"] >= q0["min_dihedral"] - 1e-9,
              "--ops flip,insert: dihedral range [%r, %r] -> [%r, %r]" %
              (q0["min_dihedral"], q0["max_dihedral"], q1["min_dihedral"], q1["max_dihedral"]))

    # all three with the surface kept: the boundary triangles are those of
    # the input, with their markers
    for ops in ("smooth,flip,insert", "default", "flip,insert,collapse,smooth"):
        dst = os.path.join(args.out, "box2_ops_keep.mesh")
        if os.path.exists(dst):
            os.remove(dst)
        code, summary, out, err = improve_summary(args, src, dst, "--ops", ops, "--keep-surface", "--iterations", "10")
        check(code == 0, "--ops %s --keep-surface exited %d: %s" % (ops, code, err))
        check(summary is not None and 1 <= summary[0] <= 10, "--ops %s --keep-surface: summary %r" % (ops, summary))
        if not os.path.exists(dst):
            check(False, "%s not written" % dst)
            continue
        check_valid_box(dst, "--ops %s --keep-surface" % ops)
        check(read_medit_triangles(dst) == faces0, "--ops %s --keep-surface changed the boundary triangles" % ops)

    # a jittered 4 x 4 x 4 box, where flips and insertion do reach the
    # surface unless --keep-surface says no
    src = os.path.join(args.out, "box4_jittered.mesh")
    write_jittered_box(src, 4, 2.0, 0.4, 1)
    check_valid_box(src, "the jittered box")
    base = os.path.join(args.out, "box4_base.mesh")
    code, out, err = run(args.bodt, "improve", src, base, "--ops", "smooth", "--iterations", "1")
    check(code == 0, "jittered box, --ops smooth: exit %d: %s" % (code, err))
    changed = {}
    for keep in (False, True):
        dst = os.path.join(args.out, "box4_keep.mesh" if keep else "box4_flip.mesh")
        extra = ["--keep-surface"] if keep else []
        code, summary, out, err = improve_summary(args, src, dst, "--ops", "flip,insert", *extra)
        what = "jittered box, --ops flip,insert" + (" --keep-surface" if keep else "")
        check(code == 0, "%s: exit %d: %s" % (what, code, err))
        if code != 0 or summary is None or not os.path.exists(base):
            check(False, "%s: no result (%r)" % (what, out))
            continue
        check(summary[1] > 0 and summary[3] == 0, "%s: summary %r, expected flips, no collapse" % (what, summary))
        pts, _ = read_medit(dst)
        check(len(pts) == 125 + summary[2], "%s: %d vertices, 125 + %d inserted" % (what, len(pts), summary[2]))
        check_valid_box(dst, what)
        tris = read_medit_triangles(dst)
        changed[keep] = tris != read_medit_triangles(base)
        # every boundary triangle on one side of the box
        for tri, ref in tris:
            on_side = any(all(abs(pts[v][a] - c) <= 1e-12 for v in tri) for a in range(3) for c in (0.0, 2.0))
            if not check(on_side, "%s: triangle %r is on no side of the box" % (what, tri)):
                break
    check(changed.get(False) is True, "without --keep-surface the surface did not change")
    check(changed.get(True) is False, "--keep-surface changed the boundary triangles")

    # refused: exit status 1 (usage), nothing written
    dst = os.path.join(args.out, "box2_ops_refused.mesh")
    if os.path.exists(dst):
        os.remove(dst)
    for bad in (["--ops", "bogus"], ["--ops", ""], ["--ops", "smooth,,flip"], ["--ops", "smooth,"],
                ["--ops", "default,flip"], ["--ops", "Smooth"], ["--ops"], ["--keep-surface=1"]):
        code, summary, out, err = improve_summary(args, src, dst, *bad)
        check(code == 1, "improve %s: exit %d, expected 1 (usage)" % (" ".join(bad), code))
        check(err.strip() != "", "improve %s: nothing on stderr" % " ".join(bad))
    code, summary, out, err = improve_summary(args, src, dst, "--ops", "bogus")
    check("bogus" in err, "the unknown operation is not named: %r" % err)
    check(not os.path.exists(dst), "a refused --ops wrote %s" % dst)
    # --help documents the options
    code, out, err = run(args.bodt, "help", "improve")
    check(code == 0 and "--ops LIST" in out and "--keep-surface" in out, "--help does not document --ops: %r" % out)


def boundary_triangles(tets):
    """The faces of the tets that belong to one tet only, as sorted triples."""
    count = {}
    for t in tets:
        for f in ((t[1], t[2], t[3]), (t[0], t[2], t[3]), (t[0], t[1], t[3]), (t[0], t[1], t[2])):
            key = tuple(sorted(f))
            count[key] = count.get(key, 0) + 1
    return sorted(k for k, n in count.items() if n == 1)


def case_improve_opt_weighted(args):
    """--mode opt-weighted (paper 001) on a jittered 4 x 4 x 4 box: the
    boundary vertices and triangles stay, the worst angle does not get worse,
    interior vertices move; an unknown mode lists opt-weighted."""
    os.makedirs(args.out, exist_ok=True)
    src = os.path.join(args.out, "box4_ow_in.mesh")
    write_jittered_box(src, 4, 2.0, 0.4, 7)
    q0 = check_valid_box(src, "the jittered box")
    p0, t0 = read_medit(src)
    dst = os.path.join(args.out, "box4_ow_out.mesh")
    if os.path.exists(dst):
        os.remove(dst)
    code, summary, out, err = improve_summary(args, src, dst, "--mode", "opt-weighted")
    check(code == 0, "--mode opt-weighted exited %d: %s" % (code, err))
    check(summary is not None, "--mode opt-weighted: no summary line in %r" % out)
    check(os.path.exists(dst), "%s was not written" % dst)
    if code != 0 or not os.path.exists(dst):
        return
    if summary:
        check(summary[0] >= 1 and summary[2] == 0 and summary[3] == 0,
              "--mode opt-weighted: summary %r (no insertion or collapse in this mode)" % (summary,))
    p1, t1 = read_medit(dst)
    check(len(p1) == len(p0), "%d vertices, %d in the input" % (len(p1), len(p0)))
    on_boundary = [v for v, p in enumerate(p0) if any(c == 0.0 or c == 2.0 for c in p)]
    check(len(on_boundary) == 125 - 27, "%d boundary vertices in the input" % len(on_boundary))
    moved = [v for v in on_boundary if p1[v] != p0[v]]
    check(not moved, "boundary vertices moved: %r" % moved[:10])
    check(boundary_triangles(t1) == boundary_triangles(t0), "the boundary triangles changed")
    check(sorted(f for f, _ in read_medit_triangles(dst)) == boundary_triangles(t0),
          "the written Triangles are not the input's boundary triangles")
    interior_moved = [v for v in range(len(p0)) if v not in on_boundary and p1[v] != p0[v]]
    check(len(interior_moved) > 0, "no interior vertex moved")
    q1 = check_valid_box(dst, "--mode opt-weighted")
    check(q1["min_dihedral"] >= q0["min_dihedral"],
          "min dihedral went down: %r -> %r" % (q0["min_dihedral"], q1["min_dihedral"]))
    check(q1["stretch_min"] > q0["stretch_min"],
          "min stretch did not go up: %r -> %r" % (q0["stretch_min"], q1["stretch_min"]))
    print("opt-weighted: summary %r, min dihedral %.3f -> %.3f, min stretch %.4f -> %.4f, %d interior vertices moved"
          % (summary, q0["min_dihedral"], q1["min_dihedral"], q0["stretch_min"], q1["stretch_min"],
             len(interior_moved)))
    # the bodt command's own quality report agrees with the file
    after = quality_json(args, dst)
    if after is not None:
        check(abs(after["min_dihedral"] - q1["min_dihedral"]) <= 1e-6, "quality --json min dihedral %r, file %r" %
              (after["min_dihedral"], q1["min_dihedral"]))
        check(after["inverted"] == 0, "inverted %r" % after["inverted"])
    # an unknown mode: usage error naming the known modes, opt-weighted among them
    bad = os.path.join(args.out, "box4_ow_refused.mesh")
    code, out, err = run(args.bodt, "improve", src, bad, "--mode", "nonsense")
    check(code == 1, "--mode nonsense: exit %d, expected 1" % code)
    check("nonsense" in err and "opt-weighted" in err, "--mode nonsense: stderr %r does not list opt-weighted" % err)
    check(not os.path.exists(bad), "a refused --mode wrote %s" % bad)
    code, out, err = run(args.bodt, "--help")
    check(code == 0 and "opt-weighted" in out, "--help does not document opt-weighted")
    code, out, err = run(args.bodt, "help", "improve")
    check(code == 0 and "opt-weighted: paper 001" in out, "help improve does not document opt-weighted")


def recovery_rows(html):
    """{key: (before, after)} of the report's table of recovery errors."""
    return {k: (float(b), float(a)) for k, b, a in
            re.findall(r'<tr data-key="(\w+)"><th scope="row">[^<]*</th><td data-value="([^"]+)">[^<]*</td>'
                       r'<td data-value="([^"]+)">', html.split('id="run-recovery"', 1)[-1].split("</table>")[0])}


def check_recovery_record(args, deformed, reference):
    """The density and geometric errors of a phased run: in improve --json,
    in the report of improve --report, and in that of report --run after a
    JSON tool rewrote the record."""
    dst = os.path.join(args.out, "box4_ph_json.mesh")
    html = os.path.join(args.out, "box4_ph_report.html")
    code, out, err = run(args.bodt, "improve", deformed, dst, "--mode", "phased", "--reference", reference, "--json",
                         "--report", html)
    j = one_json_object(out, "improve --mode phased --json") if code == 0 else None
    if not check(j is not None and "recovery_before" in j and "recovery_after" in j,
                 "phased --json: exit %d, no recovery_before/after: %r %r" % (code, out[:200], err)):
        return
    keys = ("density_mean", "density_max", "geometric_mean", "geometric_max")
    want = {k: (j["recovery_before"][k], j["recovery_after"][k]) for k in keys}
    check(want["density_mean"][1] < want["density_mean"][0], "density error did not go down: %r" % want)
    check(recovery_rows(open(html).read()) == want, "improve --report: recovery rows %r, JSON %r" %
          (recovery_rows(open(html).read()), want))
    run_file = os.path.join(args.out, "box4_ph_run.json")
    with open(run_file, "w") as f:
        json.dump(j, f, indent=2)
    back = os.path.join(args.out, "box4_ph_back.html")
    code, out, err = run(args.bodt, "report", deformed, dst, "-o", back, "--run", run_file, "-q")
    if check(code == 0, "report --run of a phased run: exit %d %r" % (code, err)):
        check(recovery_rows(open(back).read()) == want, "report --run: recovery rows %r, JSON %r" %
              (recovery_rows(open(back).read()), want))


def case_improve_phased(args):
    """--mode phased --reference (paper 002) on a jittered 4 x 4 x 4 box whose
    side x = 2 was moved to x = 1.2 without moving the inside, so that tets
    invert: the result has none, fills the new box, and its density error
    went down; --reference without --mode phased is a usage error."""
    src = os.path.join(args.out, "box4_ph_original.mesh")
    write_jittered_box(src, 4, 2.0, 0.3, 11)
    pts, tets = read_medit(src)
    moved = [(1.2 if p[0] == 2.0 else p[0], p[1], p[2]) for p in pts]
    deformed = os.path.join(args.out, "box4_ph_deformed.mesh")
    write_medit(deformed, moved, tets)
    inverted = sum(1 for t in tets if dot(sub(moved[t[1]], moved[t[0]]),
                                          cross(sub(moved[t[2]], moved[t[0]]), sub(moved[t[3]], moved[t[0]]))) <= 0)
    check(inverted > 0, "the deformation inverted no tet")
    dst = os.path.join(args.out, "box4_ph_out.mesh")
    if os.path.exists(dst):
        os.remove(dst)
    code, summary, out, err = improve_summary(args, deformed, dst, "--mode", "phased", "--reference", src)
    check(code == 0, "--mode phased exited %d: %s" % (code, err))
    check(os.path.exists(dst), "%s was not written" % dst)
    if code != 0 or not os.path.exists(dst):
        return
    q = quality_of(dst)
    left = sum(1 for s in q["stretches"] if s <= 0.0)
    check(left == 0, "%d tets inverted or flat after the run (min stretch %r)" % (left, q["stretch_min"]))
    check(abs(q["volume"] - 1.2 * 4.0) <= 1e-9 * 4.8, "volume %r, want 4.8 (the deformed box)" % q["volume"])
    p1, t1 = read_medit(dst)
    used = {v for t in t1 for v in t}
    outside = [v for v in used if not all(-1e-12 <= c <= hi + 1e-12 for c, hi in zip(p1[v], (1.2, 2.0, 2.0)))]
    check(not outside, "vertices outside the deformed box: %r" % outside[:5])
    m = re.search(r"density err mean\s+(\S+)\s+(\S+)", out)
    check(m is not None, "no density error row in %r" % out)
    if m:
        check(float(m.group(2)) < float(m.group(1)), "density error did not go down: %s -> %s" % m.groups())
    check_recovery_record(args, deformed, src)
    code, _, err = run(args.bodt, "improve", deformed, dst, "--mode", "odt", "--reference", src)
    check(code == 1 and "--reference" in err, "--reference with --mode odt: exit %d, %r" % (code, err))
    print("phased: %d of %d tets inverted -> %d; summary %r; %s" % (inverted, len(tets), left, summary,
                                                                    m.group(0) if m else "no density row"))


def case_exit_codes(args):
    os.makedirs(args.out, exist_ok=True)
    good = os.path.join(args.data, "box2.mesh")
    out = os.path.join(args.out, "exit_out.mesh")
    missing = os.path.join(args.out, "does_not_exist.mesh")
    bad = os.path.join(args.out, "malformed.mesh")
    with open(bad, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\nbogus 0 0 0\n0 0 1 0\n")
    usage = [
        [],
        ["frobnicate"],
        ["quality"],
        ["quality", good, good],
        ["quality", good, "--bogus"],
        ["improve"],
        ["improve", good],
        ["improve", good, out, "extra"],
        ["improve", good, out, "--mode", "nonsense"],
        ["improve", good, out, "--mode"],
        ["improve", good, out, "--iterations", "0"],
        ["improve", good, out, "--iterations", "-2"],
        ["improve", good, out, "--iterations", "12abc"],
        ["improve", good, out, "--iterations"],
        ["improve", good, out, "--frobnicate"],
        ["improve", good, out, "--keep-surface=1"],
        ["improve", good, out, "--format", "nonsense"],
        ["quality", good, "--json", "--histogram", "--frobnicate"],
        ["compare"],
        ["compare", good],
        ["compare", good, good, good],
        ["compare", good, good, "--bogus"],
        ["convert", good],
        ["convert", good, out, "--format"],
        ["report", good, good],
        ["report", good, good, "-o"],
        ["help", "frobnicate"],
        ["help", "improve", "quality"],
    ]
    for argv in usage:
        code, o, e = run(args.bodt, *argv)
        check(code == 1, "bodt %s: exit %d, expected 1 (usage)" % (" ".join(argv), code))
        check(e.strip() != "", "bodt %s: nothing on stderr" % " ".join(argv))
    check(not os.path.exists(out), "a usage error wrote %s" % out)
    unreadable = [
        ["quality", missing],
        ["quality", bad],
        ["quality", os.path.join(args.out, "mesh.xyz")],
        ["improve", missing, out],
        ["improve", bad, out],
        ["compare", good, missing],
        ["compare", bad, good],
        ["convert", missing, out],
        ["report", good, bad, "-o", os.path.join(args.out, "exit_report.html")],
    ]
    for argv in unreadable:
        code, o, e = run(args.bodt, *argv)
        check(code == 2, "bodt %s: exit %d, expected 2 (input)" % (" ".join(argv), code))
        culprit = [a for a in argv if a in (missing, bad) or a.endswith(".xyz")][0]
        check(culprit in e, "bodt %s: stderr does not name the file: %r" % (" ".join(argv), e))
    code, o, e = run(args.bodt, "quality", bad)
    check(bad + ":7:" in e, "the malformed file's line is not named: %r" % e)
    check(not os.path.exists(out), "a failed improve wrote %s" % out)
    # an output that cannot be written
    code, o, e = run(args.bodt, "improve", good, os.path.join(args.out, "no_such_dir", "x.mesh"))
    check(code == 4, "unwritable output: exit %d, expected 4" % code)
    # help and version
    code, o, e = run(args.bodt, "--help")
    check(code == 0 and "SYNOPSIS" in o and "EXIT STATUS" in o, "--help: %d %r" % (code, o))
    header = open(os.path.join(args.data, "..", "..", "include", "bodt.h")).read()
    version = ".".join(re.search(r"#define BODT_VERSION_%s (\d+)" % k, header).group(1)
                       for k in ("MAJOR", "MINOR", "PATCH"))
    code, o, e = run(args.bodt, "--version")
    check(code == 0 and o.strip() == "bodt " + version, "--version: %d %r, expected bodt %s" % (code, o, version))


def case_improve_surface(args):
    os.makedirs(args.out, exist_ok=True)
    src = os.path.join(args.data, "octahedron.off")
    dst = os.path.join(args.out, "octahedron.mesh")
    if os.path.exists(dst):
        os.remove(dst)
    code, out, err = run(args.bodt, "improve", src, dst)
    check(code == 0, "bodt improve %s exited %d: %s" % (src, code, err))
    check(not out.startswith("Opening"), "TetGen's chatter reached stdout: %r" % out[:60])
    q = quality_json(args, dst)
    if q is None:
        return
    check(q["inverted"] == 0, "inverted %r" % q["inverted"])
    check(q["tets"] >= 4, "tets %r" % q["tets"])
    check(q["vertices"] >= 6, "vertices %r" % q["vertices"])
    check(q["boundary_faces"] >= 8, "boundary faces %r" % q["boundary_faces"])
    check(abs(q["volume"] - 4.0 / 3.0) <= 1e-12, "volume %r, expected 4/3" % q["volume"])
    ref = quality_of(dst)
    check(abs(ref["volume"] - 4.0 / 3.0) <= 1e-12, "independent volume %r" % ref["volume"])
    check(abs(q["min_dihedral"] - ref["min_dihedral"]) <= 1e-6,
          "min dihedral %r vs %r" % (q["min_dihedral"], ref["min_dihedral"]))
    # the surface vertices are all there, unmoved
    pts, _ = read_medit(dst)
    for p in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
        check(p in pts, "surface vertex %r missing from the output" % (p,))
    # a surface that is not closed is refused as input
    bad = os.path.join(args.out, "open.off")
    with open(bad, "w") as f:
        f.write("OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n")
    code, out, err = run(args.bodt, "quality", bad)
    check(code == 2, "an open surface: exit %d, expected 2" % code)
    check("not a closed surface" in err, "the open surface's message: %r" % err)
    # the same octahedron as Wavefront OBJ (read by OpenMesh)
    lines = open(src).read().split("\n")
    verts = [l for l in lines[2:8]]
    faces = [[int(i) + 1 for i in l.split()[1:]] for l in lines[8:16]]
    obj = os.path.join(args.out, "octahedron.obj")
    with open(obj, "w") as f:
        f.writelines("v %s\n" % v for v in verts)
        f.writelines("f %d %d %d\n" % tuple(face) for face in faces)
    # ... and as STL (ASCII and binary: one record per triangle, vertices
    # repeated) and PLY (ASCII and binary little-endian)
    xyz = [tuple(float(c) for c in v.split()) for v in verts]
    tris = [[xyz[i - 1] for i in face] for face in faces]
    stl_ascii = os.path.join(args.out, "octahedron_ascii.stl")
    with open(stl_ascii, "w") as f:
        f.write("solid octahedron\n")
        for t in tris:
            f.write("facet normal 0 0 0\nouter loop\n")
            f.writelines("vertex %r %r %r\n" % p for p in t)
            f.write("endloop\nendfacet\n")
        f.write("endsolid octahedron\n")
    stl_binary = os.path.join(args.out, "octahedron_binary.stl")
    with open(stl_binary, "wb") as f:
        f.write(b"binary octahedron".ljust(80, b" ") + struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<12fH", 0, 0, 0, *[c for p in t for c in p], 0))
    ply_header = "ply\nformat %s 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n" \
                 "element face 8\nproperty list uchar int vertex_indices\nend_header\n"
    ply_ascii = os.path.join(args.out, "octahedron_ascii.ply")
    with open(ply_ascii, "w") as f:
        f.write(ply_header % "ascii")
        f.writelines("%s\n" % v for v in verts)
        f.writelines("3 %d %d %d\n" % tuple(i - 1 for i in face) for face in faces)
    ply_binary = os.path.join(args.out, "octahedron_binary.ply")
    with open(ply_binary, "wb") as f:
        f.write((ply_header % "binary_little_endian").encode())
        for p in xyz:
            f.write(struct.pack("<3f", *p))
        for face in faces:
            f.write(struct.pack("<B3i", 3, *[i - 1 for i in face]))
    for surface in (obj, stl_ascii, stl_binary, ply_ascii, ply_binary):
        name = os.path.basename(surface)
        code, out, err = run(args.bodt, "improve", surface, dst)
        check(code == 0, "bodt improve %s exited %d: %s" % (surface, code, err))
        q = quality_json(args, dst)
        if q is None:
            continue
        check(abs(q["volume"] - 4.0 / 3.0) <= 1e-12, "%s: volume %r, expected 4/3" % (name, q["volume"]))
        check(q["inverted"] == 0, "%s: inverted %r" % (name, q["inverted"]))
        check(q["boundary_faces"] == 8, "%s: %r boundary faces, expected the 8 of the input" % (name, q["boundary_faces"]))
        pts, _ = read_medit(dst)
        for p in xyz:
            check(p in pts, "%s: surface vertex %r missing from the output" % (name, p))


def case_surface_without_tetgen(args):
    src = os.path.join(args.data, "octahedron.off")
    code, out, err = run(args.bodt, "quality", src)
    check(code == 2, "exit %d, expected 2" % code)
    check("TetGen" in err, "the message does not say TetGen is missing: %r" % err)


# --------------------------------------------------- compare, convert, report

def side_marker(pts, tri, size=2.0):
    """1..6 for the box sides x=0, x=size, y=0, y=size, z=0, z=size."""
    for axis in range(3):
        for s, value in ((0, 0.0), (1, size)):
            if all(pts[v][axis] == value for v in tri):
                return 1 + 2 * axis + s
    raise ValueError("not on a side: %r" % (tri,))


def write_marked_box(path, pts=None):
    """box2.mesh (regions 1 and 2) with its 48 boundary triangles marked by
    side (1..6), written as Medit; `pts` replaces the vertices.  Returns
    (pts, tets, refs, [(triangle, marker)])."""
    here = os.path.dirname(os.path.abspath(__file__))
    p0, tets, refs, _ = read_medit_full(os.path.join(here, "..", "data", "box2.mesh"))
    tris = [(f, side_marker(p0, f)) for f in boundary_triangles(tets)]
    pts = pts or p0
    write_medit(path, pts, tets, refs, [t for t, _ in tris], [m for _, m in tris])
    return pts, tets, refs, tris


def tri_area(pts, t):
    a, b, c = (pts[v] for v in t)
    return 0.5 * norm(cross(sub(b, a), sub(c, a)))


def compare_json(args, a, b):
    code, out, err = run(args.bodt, "compare", a, b, "--json")
    if not check(code == 0, "bodt compare %s %s --json exited %d: %s" % (a, b, code, err)):
        return None
    try:
        return json.loads(out)
    except ValueError as e:
        check(False, "compare --json: not JSON (%s): %r" % (e, out))
        return None


def check_identical(c, what, markers=(1, 2, 3, 4, 5, 6)):
    """A comparison of a mesh with an unchanged copy of itself."""
    if c is None:
        return
    check(c["volume_change"] == 0.0 and c["volume_change_rel"] == 0.0, "%s: volume change %r" %
          (what, c["volume_change"]))
    check(c["hausdorff"] == 0.0 and c["hausdorff_upper"] == 0.0 and c["hausdorff_rel"] == 0.0,
          "%s: Hausdorff %r .. %r" % (what, c["hausdorff"], c["hausdorff_upper"]))
    check(c["markers_kept"] is True and c["markers_lost"] == [], "%s: markers lost %r" % (what, c["markers_lost"]))
    got = {m["marker"]: m for m in c["markers"]}
    for k in markers:
        m = got.get(k)
        if check(m is not None, "%s: marker %d missing from %r" % (what, k, sorted(got))):
            check(m["faces_before"] == m["faces_after"] == 8 and abs(m["area_before"] - 4.0) < 1e-12 and
                  m["area_before"] == m["area_after"], "%s: marker %d: %r" % (what, k, m))
    for key in ("vertices", "tets", "boundary_faces", "min_dihedral", "max_dihedral", "volume"):
        check(c["quality_before"][key] == c["quality_after"][key], "%s: %s %r -> %r" %
              (what, key, c["quality_before"][key], c["quality_after"][key]))


def case_compare(args):
    """compare: a mesh with itself gives 0; a boundary vertex moved out of
    its side by delta gives Hausdorff delta (attained at that vertex), / L
    = 2, the tent's volume delta * area / 3 and the markers kept with the
    side's area grown; a mesh without markers loses them all."""
    src = os.path.join(args.out, "cmp_box.mesh")
    pts, tets, refs, tris = write_marked_box(src)
    check_identical(compare_json(args, src, src), "a mesh with itself")
    code, out, err = run(args.bodt, "compare", src, src)
    check(code == 0 and "markers kept: yes" in out and "volume change" in out and "Hausdorff" in out,
          "compare (text): %d %r %r" % (code, out, err))
    # the centre of the top side, (1, 1, 2), raised by delta
    top = pts.index((1.0, 1.0, 2.0))
    delta = 0.1
    moved = list(pts)
    moved[top] = (1.0, 1.0, 2.0 + delta)
    dst = os.path.join(args.out, "cmp_box_raised.mesh")
    write_marked_box(dst, moved)
    c = compare_json(args, src, dst)
    if c is not None:
        star = sum(tri_area(pts, t) for t, m in tris if top in t)
        check(abs(c["volume_change"] - delta * star / 3.0) <= 1e-12, "volume change %r, expected %r" %
              (c["volume_change"], delta * star / 3.0))
        check(abs(c["volume_change_rel"] - delta * star / 3.0 / 8.0) <= 1e-12, "relative volume change %r" %
              c["volume_change_rel"])
        check(c["bbox_largest_side"] == 2.0, "L %r, expected 2" % c["bbox_largest_side"])
        check(abs(c["hausdorff"] - delta) <= 1e-12, "Hausdorff %r, expected %r" % (c["hausdorff"], delta))
        check(c["hausdorff_upper"] <= delta * (1 + 1e-3) + 1e-6, "Hausdorff upper bound %r" % c["hausdorff_upper"])
        check(abs(c["hausdorff_rel"] - delta / 2.0) <= 1e-12, "relative Hausdorff %r, expected %r" %
              (c["hausdorff_rel"], delta / 2.0))
        check(c["markers_kept"] is True, "markers not kept: %r" % c["markers_lost"])
        got = {m["marker"]: m for m in c["markers"]}
        grown = sum(tri_area(moved, t) for t, m in tris if m == 6)
        check(abs(got[6]["area_after"] - grown) <= 1e-12 and got[6]["area_before"] == 4.0,
              "top side area %r -> %r, expected 4 -> %r" % (got[6]["area_before"], got[6]["area_after"], grown))
        print("compare: raised vertex: Hausdorff %r (upper %r), volume change %r" %
              (c["hausdorff"], c["hausdorff_upper"], c["volume_change"]))
    # the same, symmetric: the arguments swapped give the same distance
    c = compare_json(args, dst, src)
    if c is not None:
        check(abs(c["hausdorff"] - delta) <= 1e-12, "swapped: Hausdorff %r" % c["hausdorff"])
    # a vertex pushed into the box: the distance is still delta, at the vertex
    moved[top] = (1.0, 1.0, 2.0 - delta)
    dented = os.path.join(args.out, "cmp_box_dented.mesh")
    write_marked_box(dented, moved)
    c = compare_json(args, src, dented)
    if c is not None:
        check(abs(c["hausdorff"] - delta) <= 1e-12, "dent: Hausdorff %r, expected %r" % (c["hausdorff"], delta))
        check(c["volume_change"] < 0, "dent: volume change %r" % c["volume_change"])
    # box2.mesh has no Triangles: every marker is lost
    c = compare_json(args, src, os.path.join(args.data, "box2.mesh"))
    if c is not None:
        check(c["markers_kept"] is False and c["markers_lost"] == [1, 2, 3, 4, 5, 6],
              "markers lost %r" % c["markers_lost"])
        check(c["hausdorff"] == 0.0, "same surface, other markers: Hausdorff %r" % c["hausdorff"])
    code, out, err = run(args.bodt, "compare", src, os.path.join(args.data, "box2.mesh"))
    check(code == 0 and "markers kept: no; lost: 1 2 3 4 5 6" in out, "compare (text), lost markers: %r" % out)


def case_convert(args):
    """convert: .mesh -> .node -> .mesh keeps vertices, tets, regions and
    marked faces (bodt compare says 0, 0, kept); --format; errors."""
    src = os.path.join(args.out, "conv_box.mesh")
    pts, tets, refs, tris = write_marked_box(src)
    node = os.path.join(args.out, "conv_box.node")
    back = os.path.join(args.out, "conv_box_back.mesh")
    for f in (node, back):
        if os.path.exists(f):
            os.remove(f)
    code, out, err = run(args.bodt, "convert", src, node)
    check(code == 0 and ("wrote " + node) in out, "convert to .node: %d %r %r" % (code, out, err))
    for ext in (".node", ".ele", ".face"):
        check(os.path.exists(node[:-5] + ext), "%s not written" % (node[:-5] + ext))
    code, out, err = run(args.bodt, "convert", node, back)
    check(code == 0, "convert back: %d %r" % (code, err))
    if not os.path.exists(back):
        check(False, "%s not written" % back)
        return
    check_identical(compare_json(args, src, back), ".mesh -> .node -> .mesh")
    p1, t1, r1, f1 = read_medit_full(back)
    check(p1 == pts, "the vertices changed")
    check(sorted(zip((tuple(sorted(t)) for t in t1), r1)) == sorted(zip((tuple(sorted(t)) for t in tets), refs)),
          "the tets or their regions changed")
    check(sorted((tuple(sorted(t)), m) for t, m in f1 if m) == sorted((tuple(sorted(t)), m) for t, m in tris),
          "the marked triangles changed")
    # --quiet: nothing printed
    code, out, err = run(args.bodt, "convert", src, back, "--quiet")
    check(code == 0 and out == "" and err == "", "convert --quiet printed %r %r" % (out, err))
    # --format whatever the extension
    txt = os.path.join(args.out, "conv_box.txt")
    code, out, err = run(args.bodt, "convert", src, txt, "--format", "mesh")
    check(code == 0 and os.path.exists(txt) and open(txt).read().startswith("MeshVersionFormatted"),
          "convert --format mesh: %d %r" % (code, err))
    # errors: bad format name (1), unknown output extension (4), input (2)
    code, out, err = run(args.bodt, "convert", src, txt, "--format", "nonsense")
    check(code == 1 and "nonsense" in err and "gmsh22-binary" in err, "--format nonsense: %d %r" % (code, err))
    code, out, err = run(args.bodt, "convert", src, os.path.join(args.out, "conv.xyz"))
    check(code == 4, "convert to .xyz: exit %d, expected 4: %r" % (code, err))
    code, out, err = run(args.bodt, "convert", os.path.join(args.out, "missing.mesh"), back)
    check(code == 2, "convert from a missing file: exit %d" % code)
    code, out, err = run(args.bodt, "convert", src)
    check(code == 1, "convert with one file: exit %d" % code)


def case_convert_formats(args):
    """Every written format read back (.meshb, .msh in four variants, .vtu)
    compares equal to the source; .inp is written with its sections."""
    src = os.path.join(args.out, "fmt_box.mesh")
    write_marked_box(src)
    for ext, fmt in ((".meshb", None), (".msh", None), (".msh", "gmsh-binary"), (".msh", "gmsh22"),
                     (".msh", "gmsh22-binary"), (".vtu", None), (".vtu", "vtu")):
        dst = os.path.join(args.out, "fmt_box_%s%s" % (fmt or "auto", ext))
        argv = ["convert", src, dst] + (["--format", fmt] if fmt else [])
        code, out, err = run(args.bodt, *argv)
        if not check(code == 0, "bodt %s: exit %d %r" % (" ".join(argv), code, err)):
            continue
        c = compare_json(args, src, dst)
        if c is None:
            continue
        check_identical(c, "%s (%s)" % (ext, fmt or "by extension"),
                        markers=() if ext == ".vtu" else (1, 2, 3, 4, 5, 6))
        if ext != ".vtu":
            check(c["markers_kept"], "%s: markers lost %r" % (dst, c["markers_lost"]))
    inp = os.path.join(args.out, "fmt_box.inp")
    code, out, err = run(args.bodt, "convert", src, inp)
    if check(code == 0 and os.path.exists(inp), "convert to .inp: %d %r" % (code, err)):
        text = open(inp).read().upper()
        check("*NODE" in text and "C3D4" in text and "*ELSET" in text, "the .inp lacks its sections")
    code, out, err = run(args.bodt, "quality", inp)
    check(code == 2, ".inp is written only: quality exit %d" % code)


def case_param(args):
    """--param: the value reaches the library (--verbose echoes it; ops=1
    turns the flips of --ops flip,insert off); unknown keys and bad values
    are usage errors listing the keys."""
    src = os.path.join(args.out, "param_pushed.mesh")
    with open(os.path.join(args.data, "box2.mesh")) as f:
        text = f.read()
    with open(src, "w") as f:
        f.write(text.replace("\n1.25 0.875 1.125 0\n", "\n1 1 1.9 0\n"))
    dst = os.path.join(args.out, "param_out.mesh")
    code, out, err = run(args.bodt, "improve", src, dst, "--verbose", "--param", "min_stretch=0.0125",
                         "--param", "feature_angle=40", "--param=backtrack_steps=7")
    check(code == 0, "--param: exit %d %r" % (code, err))
    check("min_stretch = 0.0125\n" in err and "feature_angle = 40\n" in err and "backtrack_steps = 7\n" in err,
          "--verbose does not echo the parameters: %r" % err)
    check("tolerance = 1e-06\n" in err, "--verbose does not list the defaults: %r" % err)
    # the observable effect: --param ops wins over --ops
    code, summary, out, err = improve_summary(args, src, dst, "--ops", "flip,insert")
    check(code == 0 and summary is not None and summary[1] + summary[2] > 0,
          "--ops flip,insert did nothing: %r %r" % (summary, err))
    p0, t0 = read_medit(src)
    code, summary, out, err = improve_summary(args, src, dst, "--ops", "flip,insert", "--param", "ops=1")
    check(code == 0 and summary is not None and summary[1:] == (0, 0, 0),
          "--param ops=1: summary %r %r" % (summary, err))
    if os.path.exists(dst):
        p1, t1 = read_medit(dst)
        check(t1 == t0 and p1[13] != p0[13], "--param ops=1 did not smooth only")
    os.remove(dst)
    for bad, words in ((["--param", "nonsense=1"], ["nonsense", "min_stretch", "qn_max_iterations", "fit_tolerance"]),
                       (["--param", "min_stretch"], ["min_stretch"]),
                       (["--param", "min_stretch=abc"], ["abc"]),
                       (["--param", "ops=1.5"], ["1.5", "whole"]),
                       (["--param", "min_stretch=1e-2x"], ["1e-2x"]),
                       (["--param", "weight_c=2"], ["weight_c"]),      # out of range: the library says no
                       (["--param"], ["--param"])):
        code, out, err = run(args.bodt, "improve", src, dst, *bad)
        check(code == 1, "%s: exit %d, expected 1" % (" ".join(bad), code))
        for w in words:
            check(w in err, "%s: %r not in %r" % (" ".join(bad), w, err))
        check(not os.path.exists(dst), "%s wrote the output" % " ".join(bad))


def run_on_pty(argv, columns=200):
    """Runs argv with stderr on a pseudo-terminal `columns` wide; (code,
    stdout, what the terminal got)."""
    import pty
    import select
    import fcntl
    import termios
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 50, columns, 0, 0))
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=slave, universal_newlines=True)
    os.close(slave)
    chunks = []
    while True:
        r, _, _ = select.select([master], [], [], 60)
        if not r:
            break
        try:
            data = os.read(master, 4096)
        except OSError:  # EIO: the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    out, _ = p.communicate(timeout=60)
    os.close(master)
    return p.returncode, out, b"".join(chunks).decode("utf-8", "replace")


def feed_later(fifo, path, delay):
    """Writes the file `path` into the named pipe `fifo` after `delay`
    seconds, from a thread: a reader of the FIFO sees a read that slow."""
    import threading

    def feed():
        time.sleep(delay)
        with open(fifo, "w") as f:
            f.write(open(path).read())
    t = threading.Thread(target=feed)
    t.start()
    return t


def case_progress(args):
    """Progress on stderr: on a terminal a live line from the start (reading,
    its clock running; steps with the time left; done); in a log nothing for
    a short run, lines from the 5th second of a long one; --verbose a line
    per phase and step; --quiet nothing."""
    src = pushed_box2(args, "progress_pushed.mesh")
    dst = os.path.join(args.out, "progress_out.mesh")
    # not a terminal, a short run: stderr stays empty
    code, summary, out, err = improve_summary(args, src, dst, "--iterations", "4")
    check(code == 0 and summary is not None, "improve: %d %r" % (code, err))
    check(err == "", "a short run in a log printed %r" % err)
    # a terminal: the phases, then the bar redrawn in place, with the angles
    code, out, term = run_on_pty([args.bodt, "improve", src, dst, "--iterations", "4"])
    check(code == 0, "improve on a pty: exit %d %r" % (code, term))
    m = SUMMARY.search(out)
    check(m is not None, "improve on a pty: no summary on stdout %r" % out)
    check(term.startswith("\rreading " + src + "  "), "the live line does not start with reading: %r" % term[:60])
    check("\rsetting up  " in term and "\rwriting " + dst + "  " in term, "phases missing: %r" % term)
    bars = re.findall(r"\r\[[#.]{20}\] step (\d+)/4  min (\d+\.\d\d) deg  max (\d+\.\d\d) deg  flips (\d+)  "
                      r"(\d+\.\d+) s(, ~(\d+\.\d+) s left)?", term)
    check(len(bars) >= 1, "no progress bar on the terminal: %r" % term)
    if m and bars:
        steps = sorted({int(b[0]) for b in bars})
        check(steps == list(range(1, int(m.group(1)) + 1)), "bar steps %r for %s steps" % (steps, m.group(1)))
        check(int(bars[-1][3]) == int(m.group(2)), "the bar's flips %s, the summary's %s" % (bars[-1][3], m.group(2)))
        check(all((b[5] != "") == (int(b[0]) < 4) for b in bars), "the time left shows before the last step only: %r"
              % bars)
        clock = [float(b[4]) for b in bars]
        check(clock == sorted(clock), "the clock went back: %r" % clock)
    if os.path.exists(dst) and bars:
        q = quality_of(dst)
        check(abs(float(bars[-1][1]) - q["min_dihedral"]) <= 0.006, "the bar's last min %s, the file's %r" %
              (bars[-1][1], q["min_dihedral"]))
    check(re.search(r"\rdone in \d+\.\d+ s \(reading \S+ s, setting up \S+ s, \d+ steps \S+ s, writing \S+ s\)"
                    r"\x1b\[K\r?\n$", term) is not None, "the line does not end with done: %r" % term[-120:])
    # a narrow terminal: the line is cut to its width (a wrapped line could
    # not be redrawn in place)
    code, out, term = run_on_pty([args.bodt, "improve", src, dst, "--iterations", "4"], columns=50)
    drawn = [re.sub(r"\x1b\[K", "", d) for d in term.rstrip("\r\n").split("\r") if d]
    check(code == 0 and drawn and max(len(d) for d in drawn) <= 49, "lines wider than 49 columns: %r" % drawn)
    # a slow read (the input through a FIFO, 1.5 s late): the clock runs
    fifo = make_fifo(os.path.join(args.out, "progress_slow.mesh"))
    feeder = feed_later(fifo, src, 1.5)
    code, out, term = run_on_pty([args.bodt, "improve", fifo, dst, "--iterations", "4"])
    feeder.join()
    ticks = sorted({float(t) for t in re.findall(r"\rreading " + re.escape(fifo) + r"  (\d+\.\d+) s", term)})
    check(code == 0 and len(ticks) >= 4 and ticks[-1] >= 1.0, "reading's clock on the terminal: %r" % ticks)
    # an error on a terminal starts a line of its own
    code, out, term = run_on_pty([args.bodt, "improve", os.path.join(args.out, "missing.mesh"), dst])
    check(code == 2 and re.search(r"\x1b\[K\r?\nbodt: .*missing\.mesh", term) is not None,
          "the error does not follow the live line on a line of its own: %r" % term)
    # --quiet on a terminal: nothing at all
    code, out, term = run_on_pty([args.bodt, "improve", src, dst, "--iterations", "4", "--quiet"])
    check(code == 0 and out == "" and term == "", "--quiet printed %r / %r" % (out, term))
    code, out, err = run(args.bodt, "improve", src, dst, "-q")
    check(code == 0 and out == "" and err == "" and os.path.exists(dst), "-q: %d %r %r" % (code, out, err))
    # --verbose without a terminal: a line per phase and per step
    code, summary, out, err = improve_summary(args, src, dst, "--iterations", "4", "--verbose")
    lines = re.findall(r"^step (\d+)/4: min dihedral (\S+), max dihedral (\S+), .*\[(\d+\.\d+) s; step (\d+\.\d+) s"
                       r"(; about (\d+\.\d+) s left)?\]$", err, re.M)
    check(summary is not None and len(lines) == summary[0], "--verbose: %d step lines for %r: %r" %
          (len(lines), summary, err))
    for phase in ("reading " + src, "setting up", "improving: at most 4 steps", "writing " + dst):
        check(re.search("^" + re.escape(phase) + r" \[\d+\.\d+ s\]$", err, re.M) is not None,
              "--verbose: no line for %r in %r" % (phase, err))
    check(re.search(r"^done in \S+ s \(", err, re.M) is not None, "--verbose: no done line: %r" % err)
    code, out, err = run(args.bodt, "improve", src, dst, "--quiet", "--verbose")
    check(code == 1 and "exclude" in err, "--quiet --verbose: %d %r" % (code, err))
    # a long run in a log (the input 6.5 s late): from 5 s on, a line for each
    # phase and the last step, each with the time
    feeder = feed_later(fifo, src, 6.5)
    code, summary, out, err = improve_summary(args, fifo, dst, "--iterations", "4")
    feeder.join()
    check(code == 0 and summary is not None, "the long run: %d %r" % (code, err))
    got = err.splitlines()
    pattern = [r"reading %s \[5\.\d s\]" % re.escape(fifo), r"setting up \[6\.\d s\]",
               r"improving: at most 4 steps \[6\.\d s\]",
               r"step %d/4: min dihedral .* \[6\.\d s; step \d\.\d\d s(; about \d\.\d\d s left)?\]"
               % (summary[0] if summary else 0),
               r"writing %s \[6\.\d s\]" % re.escape(dst), r"done in 6\.\d s \(reading 6\.\d s, .*\)"]
    check(len(got) == len(pattern) and all(re.match(p_ + "$", g) for p_, g in zip(pattern, got)),
          "the long run's log:\n%s" % err)


def case_histogram(args):
    """quality --histogram: the text bars and the JSON sum to 6 x tets and
    agree with the independent count."""
    path = os.path.join(args.data, "box2.mesh")
    ref = quality_of(path)
    code, out, err = run(args.bodt, "quality", path, "--histogram")
    check(code == 0, "quality --histogram: %d %r" % (code, err))
    rows = re.findall(r"^\[\s*(\d+),\s*(\d+)([)\]])\s+(\d+) \|(#*)$", out, re.M)
    check(len(rows) == 23, "%d histogram rows in %r" % (len(rows), out))
    if len(rows) == 23:
        check([int(r[0]) for r in rows] == EDGES[:-1] and [int(r[1]) for r in rows] == EDGES[1:],
              "bin edges %r" % rows)
        counts = [int(r[3]) for r in rows]
        check(sum(counts) == 6 * 48, "the bars sum to %d, expected %d" % (sum(counts), 6 * 48))
        check_histogram(counts, ref["angles"])
        top = max(counts)
        for r in rows:
            n = int(r[3])
            check((len(r[4]) > 0) == (n > 0) and (n != top or len(r[4]) == 50), "bar %r" % (r,))
    check("min dihedral" in out, "the table is missing: %r" % out)
    code, out, err = run(args.bodt, "quality", path, "--histogram", "--json")
    q = json.loads(out) if code == 0 else None
    if check(q is not None, "quality --histogram --json: %d %r" % (code, err)):
        check(sum(q["dihedral_histogram"]) == 6 * q["tets"], "JSON histogram sums to %d" % sum(q["dihedral_histogram"]))
        check(q.get("dihedral_bin_edges") == EDGES, "dihedral_bin_edges %r" % q.get("dihedral_bin_edges"))
        check_histogram(q["dihedral_histogram"], ref["angles"])


def case_help(args):
    """Each command's manual page: same text by `bodt help CMD` and `bodt
    CMD --help`, with the sections of a man page and the exit codes."""
    sections = ["NAME", "SYNOPSIS", "DESCRIPTION", "OPTIONS", "FILES", "EXIT STATUS", "EXAMPLES"]
    for cmd, must in (("improve", ["--mode", "--iterations", "--ops", "--keep-surface", "--param", "min_stretch",
                                   "--quiet", "--verbose", "--format", "--threads N", "--json", "per_step",
                                   "--report FILE", "PROGRESS", "left"]),
                      ("quality", ["--json", "--histogram", "min_stretch, mean_stretch", "deprecated"]),
                      ("compare", ["Hausdorff", "largest side", "markers kept"]),
                      ("convert", ["--format", "gmsh22-binary", "abaqus"]),
                      ("report", ["-o", "--run RUN.json", "worst tets", "Hausdorff"])):
        code, page, err = run(args.bodt, "help", cmd)
        check(code == 0, "help %s: exit %d" % (cmd, code))
        code2, page2, _ = run(args.bodt, cmd, "--help")
        check(code2 == 0 and page2 == page, "%s --help differs from help %s" % (cmd, cmd))
        code3, page3, _ = run(args.bodt, cmd, "-h")
        check(code3 == 0 and page3 == page, "%s -h differs" % cmd)
        pos = [page.find("\n" + s + "\n") if s != "NAME" else (0 if page.startswith("NAME\n") else -1)
               for s in sections]
        check(all(p >= 0 for p in pos) and pos == sorted(pos), "help %s: sections %r" % (cmd, pos))
        check(("bodt " + cmd) in page, "help %s does not name the command" % cmd)
        for w in must:
            check(w in page, "help %s lacks %r" % (cmd, w))
        for code_line in ("0  success", "1  usage error", "2  an input", "3  the improvement failed",
                          "4  the output could not be written"):
            check(code_line in page, "help %s: exit status %r missing" % (cmd, code_line))
        check(max(len(l) for l in page.splitlines()) <= 80, "help %s: a line is wider than 80 columns" % cmd)
    code, page, err = run(args.bodt, "--help")
    check(code == 0 and all(("  " + c + " ") in page for c in ("improve", "quality", "compare", "convert", "report")),
          "--help does not list every command: %r" % page)
    code, page2, err = run(args.bodt, "help")
    check(code == 0 and page2 == page, "bodt help differs from bodt --help")
    code, _, err = run(args.bodt, "help", "nonsense")
    check(code == 1 and "nonsense" in err, "help nonsense: %d %r" % (code, err))


def case_report(args):
    """report: writes an HTML page; -o is required; exit codes."""
    src = os.path.join(args.data, "box2.mesh")
    dst = os.path.join(args.out, "report_improved.mesh")
    code, out, err = run(args.bodt, "improve", src, dst, "--mode", "laplace", "--iterations", "3", "-q")
    check(code == 0, "improve: %d %r" % (code, err))
    html = os.path.join(args.out, "report.html")
    if os.path.exists(html):
        os.remove(html)
    code, out, err = run(args.bodt, "report", src, dst, "-o", html)
    check(code == 0 and ("wrote " + html) in out, "report: %d %r %r" % (code, out, err))
    if check(os.path.exists(html), "%s not written" % html):
        text = open(html).read()
        check("<html" in text.lower() and "</html>" in text.lower(), "not an HTML page")
        check("box2.mesh" in text and "report_improved.mesh" in text, "the report does not name the meshes")
    code, out, err = run(args.bodt, "report", src, dst, "--output=" + html, "--quiet")
    check(code == 0 and out == "" and err == "", "report --quiet: %d %r %r" % (code, out, err))
    code, out, err = run(args.bodt, "report", src, dst)
    check(code == 1 and "-o" in err, "report without -o: %d %r" % (code, err))
    code, out, err = run(args.bodt, "report", src, "-o", html)
    check(code == 1, "report with one mesh: %d" % code)
    code, out, err = run(args.bodt, "report", src, os.path.join(args.out, "missing.mesh"), "-o", html)
    check(code == 2 and "missing.mesh" in err, "report of a missing mesh: %d %r" % (code, err))
    code, out, err = run(args.bodt, "report", src, dst, "-o", os.path.join(args.out, "no_such_dir", "r.html"))
    check(code == 4, "report to an unwritable path: exit %d, expected 4" % code)


# ------------------------------------------- issue 39: output first, threads, JSON

def run_timed(argv, timeout, preexec_fn=None, env=None):
    """(code, stdout, stderr), or None when argv did not end within timeout s."""
    try:
        p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                           timeout=timeout, preexec_fn=preexec_fn, env=env)
    except subprocess.TimeoutExpired:
        return None
    return p.returncode, p.stdout, p.stderr


def make_fifo(path):
    """A named pipe nobody writes to: opening it for reading blocks, so a
    command that exits at once given it as input never read it."""
    if os.path.exists(path):
        os.remove(path)
    os.mkfifo(path)
    return path


def as_nobody():
    """preexec_fn dropping root (who may write anywhere) to nobody."""
    os.setgroups([])
    os.setgid(65534)
    os.setuid(65534)


def case_early_output(args):
    """The outputs are checked before the input is opened: a FIFO that nobody
    writes to as IN would block any read, yet each bad OUT ends the command
    at once with exit status 4 (bad options with 1), and nothing is written."""
    fifo = make_fifo(os.path.join(args.out, "never_written.mesh"))
    # the control: reading the FIFO does block (so the checks below can fail)
    r = run_timed([args.bodt, "quality", fifo], 2)
    check(r is None, "bodt quality FIFO did not block: %r" % (r,))
    good = os.path.join(args.out, "early_ok.mesh")
    if os.path.exists(good):
        os.remove(good)
    missing_dir = os.path.join(args.out, "no_such_dir")
    a_dir = os.path.join(args.out, "early_a_dir.mesh")
    os.makedirs(a_dir, exist_ok=True)
    a_file = os.path.join(args.out, "early_a_file.txt")
    with open(a_file, "w") as f:
        f.write("x")
    cases = [
        (["improve", fifo, os.path.join(args.out, "early.xyz")], 4, [".xyz", "--format"]),
        (["improve", fifo, os.path.join(args.out, "early_noext")], 4, ["no extension"]),
        (["improve", fifo, os.path.join(missing_dir, "x.mesh")], 4, ["no_such_dir", "No such file"]),
        (["improve", fifo, os.path.join(a_file, "x.mesh")], 4, ["not a directory"]),
        (["improve", fifo, a_dir], 4, ["is a directory"]),
        (["improve", fifo, os.path.join(missing_dir, "x.node")], 4, ["no_such_dir"]),
        (["improve", fifo, good, "--report", os.path.join(missing_dir, "r.html")], 4, ["--report", "no_such_dir"]),
        (["convert", fifo, os.path.join(args.out, "early.xyz")], 4, [".xyz"]),
        (["convert", fifo, os.path.join(missing_dir, "x.msh")], 4, ["no_such_dir"]),
        (["report", fifo, fifo, "-o", os.path.join(missing_dir, "r.html")], 4, ["no_such_dir"]),
        # options the library refuses, found on a mesh of one tet before IN is read
        (["improve", fifo, good, "--param", "weight_c=2"], 1, ["weight_c"]),
        (["improve", fifo, good, "--threads", "-1"], 1, ["--threads"]),
        (["improve", fifo, good, "--threads", "two"], 1, ["--threads", "two"]),
        (["improve", fifo, good, "--mode", "phased", "--keep-surface"], 1, ["--keep-surface"]),
        (["improve", fifo, good, "--report"], 1, ["--report"]),
    ]
    for argv, want, words in cases:
        r = run_timed([args.bodt] + argv, 10)
        what = "bodt " + " ".join(argv)
        if not check(r is not None, "%s read the input (blocked on the FIFO)" % what):
            continue
        code, out, err = r
        check(code == want, "%s: exit %d, expected %d: %r" % (what, code, want, err))
        for w in words:
            check(w in err, "%s: %r not in %r" % (what, w, err))
    check(not os.path.exists(good), "a refused command wrote %s" % good)
    check(not os.path.exists(missing_dir), "%s was created" % missing_dir)
    # a directory the user may not write to, and an existing OUT that is
    # read-only: root may write anywhere, so as root the command runs as the
    # user nobody, from a copy of it and of libbodt in a temporary directory
    # that user may enter (the build tree may lie under /root, where it may not)
    sandbox = tempfile.mkdtemp(prefix="bodt_early_")
    try:
        os.chmod(sandbox, 0o755)
        bodt = os.path.join(sandbox, "bodt")
        shutil.copy2(args.bodt, bodt)
        for lib in glob.glob(os.path.join(os.path.dirname(args.bodt), "libbodt.so*")):
            shutil.copy2(lib, sandbox, follow_symlinks=True)
        env = dict(os.environ, LD_LIBRARY_PATH=sandbox)
        in_fifo = make_fifo(os.path.join(sandbox, "never_written.mesh"))
        os.chmod(in_fifo, 0o644)
        ro = os.path.join(sandbox, "read_only")
        os.mkdir(ro, 0o555)
        os.chmod(ro, 0o555)
        locked = os.path.join(sandbox, "locked.mesh")
        with open(locked, "w") as f:
            f.write("locked\n")
        os.chmod(locked, 0o444)
        drop = as_nobody if os.geteuid() == 0 else None
        for out_path in (os.path.join(ro, "x.mesh"), locked):
            r = run_timed([bodt, "improve", in_fifo, out_path], 10, preexec_fn=drop, env=env)
            if not check(r is not None, "improve to %s read the input" % out_path):
                continue
            check(r[0] == 4 and "Permission denied" in r[2], "improve to %s: exit %d %r" % (out_path, r[0], r[2]))
        check(os.listdir(ro) == [] and open(locked).read() == "locked\n", "an unwritable output was written")
        os.chmod(ro, 0o755)
    finally:
        shutil.rmtree(sandbox, ignore_errors=True)  # as root, or after the checks made ro writable again
    # the usual case is not refused: a good OUT, and IN fed to the FIFO
    src = os.path.join(args.data, "box2.mesh")
    p = subprocess.Popen([args.bodt, "improve", fifo, good, "-q"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         universal_newlines=True)
    with open(fifo, "w") as f:
        f.write(open(src).read())
    out, err = p.communicate(timeout=60)
    check(p.returncode == 0 and os.path.exists(good), "improve from the FIFO: %d %r" % (p.returncode, err))


def pushed_box2(args, name):
    """box2.mesh with its centre vertex pushed towards the top (bad tets)."""
    src = os.path.join(args.out, name)
    with open(os.path.join(args.data, "box2.mesh")) as f:
        text = f.read()
    with open(src, "w") as f:
        f.write(text.replace("\n1.25 0.875 1.125 0\n", "\n1 1 1.9 0\n"))
    return src


def case_threads(args):
    """--threads N is --param threads=N; the result does not depend on it."""
    src = os.path.join(args.out, "threads_box.mesh")
    write_jittered_box(src, 6, 2.0, 0.35, 3)
    outputs = {}
    for label, extra in (("default", []), ("t1", ["--threads", "1"]), ("t2", ["--threads", "2"]),
                         ("t3", ["--threads=3"]), ("all", ["--threads", "0"]), ("p2", ["--param", "threads=2"]),
                         ("t3p1", ["--threads", "3", "--param", "threads=1"])):
        dst = os.path.join(args.out, "threads_%s.mesh" % label)
        code, out, err = run(args.bodt, "improve", src, dst, "--iterations", "6", "--json", *extra)
        if not check(code == 0, "improve %s: exit %d %r" % (" ".join(extra), code, err)):
            continue
        j = json.loads(out)
        want = {"default": 1, "t1": 1, "t2": 2, "t3": 3, "all": 0, "p2": 2, "t3p1": 1}[label]
        check(j["threads"] == want and j["parameters"]["threads"] == want,
              "%s: threads %r / %r, expected %d" % (label, j["threads"], j["parameters"]["threads"], want))
        outputs[label] = open(dst, "rb").read()
    base = outputs.get("default")
    check(base is not None and len(outputs) == 7, "not every run wrote its output")
    for label, data in outputs.items():
        check(data == base, "--threads changed the result: %s differs from the default run" % label)
    code, out, err = run(args.bodt, "improve", src, os.path.join(args.out, "threads_v.mesh"), "--threads", "2",
                         "--verbose", "--iterations", "1")
    check(code == 0 and "  threads = 2\n" in err, "--verbose does not show threads = 2: %r" % err)
    code, page, err = run(args.bodt, "help", "improve")
    check("--threads N" in page, "help improve does not document --threads")


def case_improve_json(args):
    """improve --json: one JSON object whose figures agree with bodt quality
    --json of the input and of the written file, and with its own steps."""
    src = pushed_box2(args, "json_pushed.mesh")
    dst = os.path.join(args.out, "json_out.mesh")
    if os.path.exists(dst):
        os.remove(dst)
    code, out, err = run(args.bodt, "improve", src, dst, "--iterations", "8", "--ops", "flip,insert", "--json")
    check(code == 0, "improve --json: exit %d %r" % (code, err))
    j = one_json_object(out, "improve --json")
    if j is None:
        return
    for key in ("version", "input", "output", "mode", "ops", "max_steps", "threads", "options", "parameters",
                "steps", "converged", "flips", "vertices_inserted", "edges_collapsed", "seconds", "quality_before",
                "quality_after", "per_step", "keep_surface", "reference", "report"):
        check(key in j, "improve --json lacks %s" % key)
    if FAILURES:
        return
    check(j["input"] == src and j["output"] == dst and j["mode"] == "bodt" and j["ops"] == "flip,insert",
          "input/output/mode/ops: %r" % ({k: j[k] for k in ("input", "output", "mode", "ops")},))
    check(j["max_steps"] == 8 and j["options"] == ["--iterations 8", "--ops flip,insert"],
          "max_steps/options: %r %r" % (j["max_steps"], j["options"]))
    check(j["reference"] is None and j["report"] is None and j["keep_surface"] is False, "reference/report")
    check(len(j["parameters"]) == 23 and j["parameters"]["tolerance"] == 1e-6 and j["parameters"]["ops"] == 6,
          "parameters: %r" % j["parameters"])
    steps = j["per_step"]
    check(len(steps) == j["steps"] and 1 <= j["steps"] <= 8, "%d per-step records, steps %r" % (len(steps), j["steps"]))
    check(j["converged"] == (j["steps"] < 8), "converged %r with %d of 8 steps" % (j["converged"], j["steps"]))
    check([s["step"] for s in steps] == list(range(1, len(steps) + 1)), "step numbers %r" % [s["step"] for s in steps])
    for key, total in (("flips", "flips"), ("vertices_inserted", "vertices_inserted"),
                       ("edges_collapsed", "edges_collapsed")):
        check(sum(s[key] for s in steps) == j[total], "per-step %s sum to %d, total %d" %
              (key, sum(s[key] for s in steps), j[total]))
    check(j["flips"] > 0, "no flips on the pushed box: %r" % j["flips"])
    for s_ in steps:
        for key in ("seconds", "min_dihedral", "max_dihedral", "min_stretch", "vertices_moved", "moves_rejected",
                    "moves_shortened", "not_positive_definite", "max_move"):
            check(key in s_, "per_step lacks %s" % key)
    t = j["seconds"]
    check(all(t[k] >= 0 for k in ("reading", "setting_up", "steps", "writing", "total")) and
          t["total"] >= t["reading"] + t["setting_up"] + t["steps"] + t["writing"] - 1e-3 and
          abs(sum(s_["seconds"] for s_ in steps) - t["steps"]) <= 0.05 + 0.2 * t["steps"],
          "seconds %r" % t)
    before, after = quality_json(args, src), quality_json(args, dst)
    if before is None or after is None:
        return
    for name, mine, file_q in (("before", j["quality_before"], before), ("after", j["quality_after"], after)):
        for key in ("vertices", "tets", "boundary_faces", "inverted", "unused_vertices"):
            check(mine[key] == file_q[key], "quality_%s %s: %r, the file's %r" % (name, key, mine[key], file_q[key]))
        for key in ("min_dihedral", "max_dihedral", "mean_dihedral", "min_stretch", "mean_stretch", "volume"):
            check(abs(mine[key] - file_q[key]) <= 2e-6, "quality_%s %s: %r, the file's %r" %
                  (name, key, mine[key], file_q[key]))
    last = steps[-1]
    check(abs(last["min_dihedral"] - after["min_dihedral"]) <= 1e-6 and
          abs(last["max_dihedral"] - after["max_dihedral"]) <= 1e-6 and
          abs(last["min_stretch"] - after["min_stretch"]) <= 1e-6,
          "the last step's figures %r are not the written file's %r" % (last, after))
    # --quiet leaves the JSON (it is the command's answer) and silences the rest
    code, out, err = run(args.bodt, "improve", src, dst, "--json", "-q")
    check(code == 0 and json.loads(out)["output"] == dst and err == "", "--json -q: %d %r %r" % (code, out, err))


def case_inverted_message(args):
    """A mesh with an inverted tet: improve refuses it and points to --mode
    phased (not to the C flag); phased takes it; quality counts it."""
    pts, tets, _, _ = read_medit_full(os.path.join(args.data, "box2.mesh"))
    bad = os.path.join(args.out, "inverted_box.mesh")
    # the side x = 2 moved to x = 1.1, past the centre vertex (x = 1.25)
    moved = [(1.1 if p[0] == 2.0 else p[0], p[1], p[2]) for p in pts]
    write_medit(bad, moved, tets)
    n_inv = sum(1 for t in tets if dot(sub(moved[t[1]], moved[t[0]]),
                                       cross(sub(moved[t[2]], moved[t[0]]), sub(moved[t[3]], moved[t[0]]))) < 0)
    check(0 < n_inv < len(tets) / 2, "%d tets inverted" % n_inv)
    dst = os.path.join(args.out, "inverted_out.mesh")
    code, out, err = run(args.bodt, "improve", bad, dst)
    check(code == 2, "improve of a mesh with inverted tets: exit %d" % code)
    check("inverted" in err and "--mode phased" in err, "the message does not point to --mode phased: %r" % err)
    check("BODT_CREATE" not in err, "the message names the C flag: %r" % err)
    check(bad in err, "the message does not name the file: %r" % err)
    q = quality_json(args, bad)
    if q is not None:
        check(q["inverted"] == n_inv, "quality counts %r inverted tets, expected %d" % (q["inverted"], n_inv))
    code, out, err = run(args.bodt, "improve", bad, dst, "--mode", "phased", "-q")
    check(code == 0, "--mode phased on it: exit %d %r" % (code, err))
    q = quality_json(args, dst)
    if q is not None:
        check(q["inverted"] == 0, "phased left %r inverted tets" % q["inverted"])



def case_file_numbering(args):
    """The command numbers as the file does: a bad Medit file's message names
    its tet and vertex from 1, and the report says each mesh's numbering
    (Medit from 1, VTK from 0) and lists the worst tets in it."""
    bad = os.path.join(args.out, "repeated_vertex.mesh")
    with open(bad, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
                "0 0 1 0\n1 1 1 0\nTetrahedra\n2\n1 2 3 4 0\n2 3 3 5 0\nEnd\n")
    code, out, err = run(args.bodt, "quality", bad)
    check(code == 2, "quality of a bad mesh: exit %d" % code)
    check("tet 2 uses vertex 3 twice (numbered from 1)" in err,
          "the message is not in the file's numbering: %r" % err)
    src = os.path.join(args.data, "box2.mesh")
    vtk = os.path.join(args.out, "numbering_improved.vtk")
    code, out, err = run(args.bodt, "improve", src, vtk, "--iterations", "2", "-q")
    check(code == 0, "improve to .vtk: %d %r" % (code, err))
    html = os.path.join(args.out, "numbering.html")
    code, out, err = run(args.bodt, "report", src, vtk, "-o", html, "-q")
    if check(code == 0, "report: %d %r" % (code, err)):
        text = open(html).read()
        check("the improved mesh's from 0, the original's from 1" in text,
              "the report does not say each file's numbering")
        n_tets = len(read_medit(src)[1])
        rows = re.findall(r'id="worst-original" data-base="1".*?</table>', text, re.S)
        ids = [int(x) for x in re.findall(r'<tr data-tet="(\d+)"', rows[0])] if rows else []
        check(ids and min(ids) >= 1 and max(ids) <= n_tets,
              "the original's worst tets are not numbered from 1 to %d: %r" % (n_tets, ids))



def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bodt", required=True)
    ap.add_argument("--data", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("case", choices=["quality_json", "improve", "improve_ops", "exit_codes", "improve_surface",
                                     "surface_without_tetgen", "improve_opt_weighted", "improve_phased",
                                     "compare", "convert", "convert_formats", "param", "progress", "histogram",
                                     "help", "report", "early_output", "threads", "improve_json",
                                     "inverted_message", "file_numbering"])
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    globals()["case_" + args.case](args)
    return exit_status()


if __name__ == "__main__":
    sys.exit(main())
