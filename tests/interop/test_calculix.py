#!/usr/bin/python3
"""CalculiX solves from the .inp the bodt command writes (tests/CMakeLists.txt:
interop_calculix).

    test_calculix.py --bodt PATH --out DIR

A bar [0, 4] x [0, 1] x [0, 1] of jittered Kuhn tets (two regions, the
halves x < 2 and x > 2; boundary markers 1 on x = 0, 2 on x = 4, 3 on the
sides) is improved by `bodt improve bar.mesh bar.inp`, which must move its
vertices.  A CalculiX job *INCLUDEs bar.inp and uses only the names it
defines: a linear elastic material with Poisson's ratio 0 on the element sets
REGION_1 and REGION_2, every degree of freedom of the node set MARKER_1_NODES
fixed, a pressure p on the surface MARKER_2.  The exact solution is the
uniaxial u_x = -p x / E, u_y = u_z = 0, which linear tets (C3D4) reproduce
exactly: ccx (Debian's calculix-ccx) must solve it, and every node's
displacement in its .dat must match to 1e-6 of the largest.  A missing set
stops ccx; a surface on the wrong element faces, or a node set with the wrong
nodes, gives another displacement.
"""
import argparse
import os
import shutil
import subprocess
import sys

from box_mesh import kuhn_box

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from medit_files import write_medit  # noqa: E402

E = 1000.0     # Young's modulus
P = 2.5        # pressure on x = L, against its outward normal (pushes towards x = 0)
L = 4.0

JOB = """*INCLUDE, INPUT=bar.inp
*MATERIAL, NAME=BAR
*ELASTIC
{E}, 0.
*SOLID SECTION, ELSET=REGION_1, MATERIAL=BAR
*SOLID SECTION, ELSET=REGION_2, MATERIAL=BAR
*STEP
*STATIC
*BOUNDARY
MARKER_1_NODES, 1, 3
*DSLOAD
MARKER_2, P, {P}
*NODE PRINT, NSET=NALL
U
*END STEP
"""


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def read_inp_nodes(path):
    """The *NODE block of an .inp file: {number: (x, y, z)}."""
    nodes, in_nodes = {}, False
    with open(path) as f:
        for line in f:
            if line.startswith("*"):
                in_nodes = line.split(",")[0].strip().upper() == "*NODE"
                continue
            if in_nodes:
                fields = [x.strip() for x in line.split(",")]
                nodes[int(fields[0])] = tuple(float(x) for x in fields[1:4])
    return nodes


def read_dat_displacements(path):
    """The displacements of the .dat's 'displacements (vx,vy,vz)' block: {node: (ux, uy, uz)}."""
    u, in_block = {}, False
    with open(path) as f:
        for line in f:
            if "displacements (vx,vy,vz)" in line:
                in_block = True
                continue
            fields = line.split()
            if in_block and len(fields) == 4:
                u[int(fields[0])] = tuple(float(x) for x in fields[1:])
            elif in_block and fields:
                in_block = False
    return u


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bodt", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    ccx = shutil.which("ccx")
    if not ccx:
        fail("ccx not found (Debian: apt-get install calculix-ccx)")
    os.makedirs(args.out, exist_ok=True)
    for name in os.listdir(args.out):
        os.remove(os.path.join(args.out, name))

    points, tets, regions, triangles, markers = kuhn_box((12, 3, 3), (L, 1.0, 1.0), jitter=0.3)
    src = os.path.join(args.out, "bar.mesh")
    write_medit(src, points, tets, regions, triangles, markers)
    inp = os.path.join(args.out, "bar.inp")
    p = subprocess.run([args.bodt, "improve", src, inp, "--iterations", "5"], stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, universal_newlines=True, timeout=120)
    if p.returncode != 0:
        fail("bodt improve: exit %d: %s" % (p.returncode, p.stderr))

    # The improvement changed the mesh: some vertex moved or was added.
    nodes = read_inp_nodes(inp)
    moved = len(nodes) != len(points) or any(
        max(abs(a - b) for a, b in zip(nodes[v + 1], points[v])) > 1e-9 for v in range(len(points)))
    if not moved:
        fail("bodt improve left the bar as it was")
    if any(not 0 <= x <= L for x, _, _ in nodes.values()):
        fail("a node left the bar")

    with open(os.path.join(args.out, "job.inp"), "w") as f:
        f.write(JOB.format(E=E, P=P))
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1")
    p = subprocess.run([ccx, "-i", "job"], cwd=args.out, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, timeout=300, env=env)
    with open(os.path.join(args.out, "ccx.log"), "w") as f:
        f.write(p.stdout)
    if p.returncode != 0 or "*ERROR" in p.stdout:
        errors = [line for line in p.stdout.splitlines() if "ERROR" in line]
        fail("ccx: exit %d: %s (ccx.log)" % (p.returncode, " | ".join(errors[:5])))

    u = read_dat_displacements(os.path.join(args.out, "job.dat"))
    if sorted(u) != sorted(nodes):
        fail("the .dat has displacements of %d nodes, the mesh %d" % (len(u), len(nodes)))
    largest = P * L / E
    worst = 0.0
    for v, (x, _, _) in nodes.items():
        exact = (-P * x / E, 0.0, 0.0)
        worst = max(worst, max(abs(a - b) for a, b in zip(u[v], exact)))
    print("%d nodes, %d elements after bodt improve; largest |u - exact| = %.3g (|u| up to %.3g)" %
          (len(nodes), count_elements(inp), worst, largest))
    if worst > 1e-6 * largest:
        fail("displacements differ from u_x = -p x / E by up to %.3g (of %.3g)" % (worst, largest))
    print("ok")


def count_elements(inp):
    """The number of element lines of an .inp file."""
    count, in_elements = 0, False
    with open(inp) as f:
        for line in f:
            if line.startswith("*"):
                in_elements = line.split(",")[0].strip().upper() == "*ELEMENT"
            elif in_elements:
                count += 1
    return count


if __name__ == "__main__":
    main()
