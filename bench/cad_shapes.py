#!/usr/bin/python3
"""Meshes of seven CAD shapes, none in the bench set, for a check on meshes
the library was not tuned on: Gmsh (Debian python3-gmsh) meshes each
OpenCASCADE shape without its own optimiser and writes DIR/NAME.mesh, and a
finer surface of four of them as DIR/NAME.stl, for TetGen -pQ / -pqQ.
With --creases, five shapes whose flat faces meet at shallow creases
instead (prisms of 16, 20 and 40 sides, gable roofs of 10 and 20 degrees'
pitch), each with its surface.

    /usr/bin/python3 bench/cad_shapes.py [--creases] DIR
    bench/build/bodt_bench --no-shared --modes bodt,bodt-smooth --no-peers \\
        $(for f in DIR/*.mesh; do echo --mesh $f; done) \\
        $(for f in DIR/*.stl; do echo --surface $f; done)
"""
import math
import os
import sys

import gmsh

occ = None


def cylinder_with_hole():
    c = occ.addCylinder(0, 0, 0, 0, 0, 2, 1)
    h = occ.addCylinder(0.3, 0, -1, 0, 0, 4, 0.3)
    occ.cut([(3, c)], [(3, h)])


def torus():
    occ.addTorus(0, 0, 0, 1, 0.35)


def bracket():  # an L of two boxes
    a = occ.addBox(0, 0, 0, 2, 0.4, 1)
    b = occ.addBox(0, 0, 0, 0.4, 2, 1)
    occ.fuse([(3, a)], [(3, b)])


def cone():
    occ.addCone(0, 0, 0, 0, 0, 2, 1, 0.2)


def box_with_ball_hole():
    a = occ.addBox(0, 0, 0, 1, 1, 1)
    s = occ.addSphere(0.5, 0.5, 0.5, 0.3)
    occ.cut([(3, a)], [(3, s)])


def wedge():
    occ.addWedge(0, 0, 0, 2, 1, 1)


def notched_disc():  # a disc with six square notches in its rim
    c = occ.addCylinder(0, 0, 0, 0, 0, 0.5, 1)
    for i in range(6):
        x, y = 0.9 * math.cos(i * math.pi / 3), 0.9 * math.sin(i * math.pi / 3)
        b = occ.addBox(x - 0.15, y - 0.15, -0.1, 0.3, 0.3, 0.7)
        c = occ.cut([(3, c)], [(3, b)])[0][0][1]


def prism(sides):  # a regular prism of unit radius and height
    def build():
        corners = [occ.addPoint(math.cos(2 * math.pi * k / sides), math.sin(2 * math.pi * k / sides), 0)
                   for k in range(sides)]
        lines = [occ.addLine(corners[k], corners[(k + 1) % sides]) for k in range(sides)]
        occ.extrude([(2, occ.addPlaneSurface([occ.addCurveLoop(lines)]))], 0, 0, 1)
    return build


def gable(pitch_deg):  # a 2 x 1.5 x 1 house whose roof rises at pitch_deg to a ridge
    def build():
        rise = math.tan(math.radians(pitch_deg))
        outline = [(0, 0, 0), (2, 0, 0), (2, 0, 1), (1, 0, 1 + rise), (0, 0, 1)]
        corners = [occ.addPoint(*p) for p in outline]
        lines = [occ.addLine(corners[k], corners[(k + 1) % 5]) for k in range(5)]
        occ.extrude([(2, occ.addPlaneSurface([occ.addCurveLoop(lines)]))], 0, 1.5, 0)
    return build


# name, shape, element size of the tet mesh, of the surface (None: no surface)
SHAPES = [
    ("cylhole", cylinder_with_hole, 0.25, 0.15),
    ("torus", torus, 0.2, None),
    ("bracket", bracket, 0.2, 0.12),
    ("cone", cone, 0.25, None),
    ("boxsph", box_with_ball_hole, 0.15, 0.1),
    ("wedge", wedge, 0.25, None),
    ("gear", notched_disc, 0.15, 0.1),
]
CREASE_SHAPES = [
    ("prism16", prism(16), 0.15, 0.15),
    ("prism20", prism(20), 0.15, 0.15),
    ("prism40", prism(40), 0.15, 0.15),
    ("roof10", gable(10), 0.12, 0.12),
    ("roof20", gable(20), 0.12, 0.12),
]


def write(path, build, size, dim):
    global occ
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(os.path.basename(path))
    occ = gmsh.model.occ
    build()
    occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.Optimize", 0)
    gmsh.model.mesh.generate(dim)
    gmsh.write(path)
    gmsh.finalize()


def main():
    args = sys.argv[1:]
    creases = args[:1] == ["--creases"]
    if len(args) != 1 + creases:
        sys.exit(__doc__)
    out = args[-1]
    os.makedirs(out, exist_ok=True)
    for name, build, size, surface in CREASE_SHAPES if creases else SHAPES:
        write(os.path.join(out, name + ".mesh"), build, size, 3)
        if surface:
            write(os.path.join(out, name + ".stl"), build, surface, 2)


if __name__ == "__main__":
    main()
