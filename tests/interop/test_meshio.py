#!/usr/bin/python3
"""meshio reads the .vtu and .vtk files the bodt command writes, and the bodt
command reads the ones meshio writes (tests/CMakeLists.txt: interop_meshio).

    test_meshio.py --bodt PATH --data DIR --out DIR

Uses the real meshio (Debian's python3-meshio, 5.0):

  ours -> meshio   a jittered box of Kuhn tets (two regions, boundary
                   markers, a marked edge, vertex refs, a fixed vertex),
                   `bodt convert` to .vtu and .vtk, read by meshio.read:
                   points bit for bit, tets, triangles, lines, and the
                   region, marker, ref and fixed arrays as written
  meshio -> ours   the same mesh as meshio.Mesh with its regions and markers
                   under gmsh:physical, CellEntityIds or medit:ref (vertex
                   refs under medit:ref), written by meshio.write as .vtu
                   (zlib, the default, with header_type UInt32 and UInt64;
                   uncompressed; ASCII) and .vtk (binary, ASCII), and a
                   larger box whose zlib arrays span several blocks; each
                   converted by `bodt convert` to .mesh, which must hold the
                   tets, regions, markers, edge refs and vertex refs;
                   lzma-compressed .vtu refused by name (exit 2)
  meshio Medit -> ours   the sample in cell blocks (one per region, per
                   marker, per edge ref, under medit:ref), written by
                   meshio.write as .mesh and .meshb, a section per block:
                   `bodt convert` reads every section (tets, regions,
                   markers, edge refs, vertex refs) and `bodt improve` takes
                   the file
  Gmsh -> meshio -> ours   tests/data/gmsh/box41.msh read by meshio and
                   written as .vtu, .mesh and .meshb (a Tetrahedra section
                   per physical volume): `bodt convert` gives what it reads
                   from the .msh itself (regions 1 and 2, marker 10, edge
                   ref 20)
"""
import argparse
import functools
import os
import sys

import meshio
import numpy as np

from box_mesh import kuhn_box

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import checks  # noqa: E402
from checks import check  # noqa: E402
from medit_files import read_medit, write_medit  # noqa: E402

run = functools.partial(checks.run, timeout=120)


def sample(n=(3, 2, 2), jitter=0.2):
    """The box with a marked edge, vertex refs and a fixed vertex (vertex 0)."""
    points, tets, regions, triangles, markers = kuhn_box(n, (3.0, 1.0, 1.0), jitter=jitter)
    vertex_refs = [v % 5 - 2 for v in range(len(points))]
    edges, edge_refs = [(0, 1)], [12]  # along y on x = z = 0
    return points, tets, regions, triangles, markers, vertex_refs, edges, edge_refs


def blocks(mesh, cell_type):
    """The indices of meshio's cell blocks of a type."""
    return [k for k, c in enumerate(mesh.cells) if c.type == cell_type]


def cells_and_data(mesh, cell_type, name):
    """All cells of a type (concatenated blocks) and their values of cell data `name`."""
    ks = blocks(mesh, cell_type)
    cells = [tuple(int(v) for v in c) for k in ks for c in mesh.cells[k].data]
    values = [int(x) for k in ks for x in mesh.cell_data[name][k]] if name in mesh.cell_data else None
    return cells, values


def ours_read_by_meshio(args):
    points, tets, regions, triangles, markers, vertex_refs, edges, edge_refs = sample()
    src = os.path.join(args.out, "ours.mesh")
    write_medit(src, points, tets, regions, triangles, markers, vertex_refs, edges, edge_refs)
    with open(src) as f:
        text = f.read()
    with open(src, "w") as f:
        f.write(text.replace("End\n", "RequiredVertices\n1\n1\nEnd\n"))
    # What the library holds (the interfaces between regions become faces
    # with marker 0), as the .mesh it writes.
    ref = os.path.join(args.out, "ours_ref.mesh")
    code, _, err = run(args.bodt, "convert", src, ref, "--quiet")
    if not check(code == 0, "convert to .mesh: %s" % err):
        return
    expect = read_medit(ref)
    expect_tris = {tuple(sorted(t)): m for t, m in zip(expect["triangles"], expect["markers"])}
    check(all(expect_tris.get(tuple(sorted(t))) == m for t, m in zip(triangles, markers)),
          "the library's faces keep the input markers")
    for ext in ("vtu", "vtk"):
        path = os.path.join(args.out, "ours." + ext)
        code, _, err = run(args.bodt, "convert", src, path, "--quiet")
        if not check(code == 0, "convert to .%s: %s" % (ext, err)):
            continue
        try:
            m = meshio.read(path)
        except Exception as e:  # noqa: BLE001 - any failure of meshio is the finding
            check(False, "meshio cannot read our .%s: %s: %s" % (ext, type(e).__name__, e))
            continue
        check(np.array_equal(m.points, np.array(points)), ".%s: points differ" % ext)
        got_tets, got_regions = cells_and_data(m, "tetra", "region")
        check(got_tets == list(tets), ".%s: tets differ" % ext)
        check(got_regions == regions, ".%s: regions differ" % ext)
        got_tris, got_markers = cells_and_data(m, "triangle", "marker")
        check(got_markers is not None and dict(zip((tuple(sorted(t)) for t in got_tris), got_markers)) == expect_tris,
              ".%s: triangles and markers differ" % ext)
        got_lines, got_refs = cells_and_data(m, "line", "marker")
        check(got_lines == edges and got_refs == edge_refs, ".%s: lines %r refs %r" % (ext, got_lines, got_refs))
        check("ref" in m.point_data and [int(x) for x in m.point_data["ref"]] == vertex_refs,
              ".%s: vertex refs" % ext)
        check("fixed" in m.point_data and [int(x) for x in m.point_data["fixed"]] == [1] + [0] * (len(points) - 1),
              ".%s: fixed vertices" % ext)


def meshio_mesh(sample_data, name, point_refs):
    """The sample as meshio.Mesh, its regions, markers and edge refs in one
    cell data array `name` (as meshio writes Gmsh's and Medit's)."""
    points, tets, regions, triangles, markers, vertex_refs, edges, edge_refs = sample_data
    cells = [("triangle", np.array(triangles)), ("tetra", np.array(tets)), ("line", np.array(edges))]
    data = {name: [np.array(markers, dtype=np.int32), np.array(regions, dtype=np.int32),
                   np.array(edge_refs, dtype=np.int32)]}
    if name == "gmsh:physical":
        data["gmsh:geometrical"] = [np.ones(len(c[1]), dtype=np.int32) for c in cells]
    point_data = {"medit:ref": np.array(vertex_refs, dtype=np.int32)} if point_refs else {}
    return meshio.Mesh(np.array(points), cells, cell_data=data, point_data=point_data)


def check_read_back(args, path, sample_data, point_refs, tolerance=0.0):
    """`bodt convert` of a file meshio wrote gives the sample (points within
    `tolerance`: meshio's ASCII .vtu has 12 significant digits)."""
    points, tets, regions, triangles, markers, vertex_refs, edges, edge_refs = sample_data
    out = path + ".mesh"
    code, _, err = run(args.bodt, "convert", path, out, "--quiet")
    name = os.path.basename(path)
    if not check(code == 0, "%s: bodt convert: exit %d: %s" % (name, code, err.strip())):
        return
    m = read_medit(out)
    check(len(m["points"]) == len(points) and
          max(abs(a - b) for p, q in zip(m["points"], points) for a, b in zip(p, q)) <= tolerance,
          "%s: points" % name)
    check(m["tets"] == list(tets) and m["regions"] == regions, "%s: tets or regions" % name)
    got = {tuple(sorted(t)): r for t, r in zip(m["triangles"], m["markers"])}
    check(all(got.get(tuple(sorted(t))) == r for t, r in zip(triangles, markers)), "%s: markers" % name)
    check(m["edges"] == edges and m["edge_refs"] == edge_refs, "%s: edges %r %r" % (name, m["edges"], m["edge_refs"]))
    check(m["vertex_refs"] == (vertex_refs if point_refs else [0] * len(points)), "%s: vertex refs" % name)


def meshio_read_by_ours(args):
    data = sample()
    variants = [("vtu", {}), ("vtu", {"header_type": "UInt64"}), ("vtu", {"compression": None}),
                ("vtu", {"binary": False}), ("vtk", {"binary": True}), ("vtk", {"binary": False})]
    for name in ("gmsh:physical", "CellEntityIds", "medit:ref"):
        for k, (ext, kwargs) in enumerate(variants):
            point_refs = name == "medit:ref"
            path = os.path.join(args.out, "meshio_%s_%d.%s" % (name.replace(":", "_"), k, ext))
            meshio.write(path, meshio_mesh(data, name, point_refs), **kwargs)
            check_read_back(args, path, data, point_refs, 1e-10 if ext == "vtu" and "binary" in kwargs else 0.0)
    # zlib arrays of several 32 KiB blocks (2197 points: 52 KiB of coordinates).
    big = sample((12, 12, 12), 0.1)
    path = os.path.join(args.out, "meshio_blocks.vtu")
    meshio.write(path, meshio_mesh(big, "gmsh:physical", False))
    with open(path) as f:
        header = f.read(300)
    check('compressor="vtkZLibDataCompressor"' in header, "meshio_blocks.vtu is not zlib-compressed")
    check_read_back(args, path, big, False)
    # LZMA: refused by name.
    path = os.path.join(args.out, "meshio_lzma.vtu")
    meshio.write(path, meshio_mesh(data, "gmsh:physical", False), compression="lzma")
    code, _, err = run(args.bodt, "convert", path, path + ".mesh")
    check(code == 2 and "vtkLZMADataCompressor is not supported" in err, "lzma: exit %d: %s" % (code, err))


def in_blocks(cells, values):
    """meshio's cell blocks of cells grouped by value, ascending, each in the given order: [(value, cells)]."""
    return [(v, [c for c, w in zip(cells, values) if w == v]) for v in sorted(set(values))]


def medit_blocks_read_by_ours(args):
    points, tets, regions, triangles, markers, vertex_refs, edges, edge_refs = sample()
    edges, edge_refs = edges + [(0, 9)], edge_refs + [13]  # (0, 9) along x on y = z = 0: another block
    cells, refs = [], []
    for cell_type, blocks in (("tetra", in_blocks(tets, regions)), ("triangle", in_blocks(triangles, markers)),
                              ("line", in_blocks(edges, edge_refs))):
        for value, block in blocks:
            cells.append((cell_type, np.array(block)))
            refs.append(np.full(len(block), value, dtype=np.int32))
    mesh = meshio.Mesh(np.array(points), cells, cell_data={"medit:ref": refs},
                       point_data={"medit:ref": np.array(vertex_refs, dtype=np.int32)})
    # The sample in block order, as `bodt convert` must give it.
    ordered = in_blocks(tets, regions)
    expected = (points, [t for _, block in ordered for t in block], [v for v, block in ordered for _ in block],
                triangles, markers, vertex_refs, edges, edge_refs)
    for ext in ("mesh", "meshb"):
        path = os.path.join(args.out, "meshio_sections." + ext)
        meshio.write(path, mesh)
        if ext == "mesh":
            with open(path) as f:
                text = f.read()
            check([text.count("\n%s\n" % name) for name in ("Tetrahedra", "Triangles", "Edges")] == [2, 3, 2],
                  "meshio_sections.mesh: not a section per block")
        check_read_back(args, path, expected, True)
        out = os.path.join(args.out, "meshio_sections_improved." + ext)
        code, _, err = run(args.bodt, "improve", path, out, "--quiet")
        if check(code == 0, "bodt improve %s: exit %d: %s" % (os.path.basename(path), code, err.strip())):
            code, _, err = run(args.bodt, "convert", out, out + ".mesh", "--quiet")
            m = read_medit(out + ".mesh")
            check(code == 0 and set(m["regions"]) == {1, 2} and set(m["markers"]) - {0} == {1, 2, 3}
                  and sorted(m["edge_refs"]) == [12, 13], "%s improved: regions, markers or edge refs" % ext)


def gmsh_through_meshio(args):
    msh = os.path.join(args.data, "gmsh", "box41.msh")
    direct = os.path.join(args.out, "gmsh_direct.mesh")
    code, _, err = run(args.bodt, "convert", msh, direct, "--quiet")
    if not check(code == 0, "convert box41.msh: %s" % err):
        return
    mesh = meshio.read(msh)
    # meshio 5.0 cannot turn Gmsh's cell sets into VTU cell data (an
    # IndexError in Mesh.cell_sets_to_data); the physical groups are in
    # gmsh:physical anyway.
    mesh.cell_sets = {}
    # Its Medit writer takes the first integer point data as the vertex
    # refs, here gmsh:dim_tags (two a point), and fails on it.
    del mesh.point_data["gmsh:dim_tags"]
    for ext in ("vtu", "mesh", "meshb"):
        written = os.path.join(args.out, "gmsh_meshio." + ext)
        meshio.write(written, mesh)  # Medit: meshio warns that it skips the vertex cells and gmsh:geometrical
        via = written + ".mesh"
        code, _, err = run(args.bodt, "convert", written, via, "--quiet")
        if check(code == 0, "convert meshio's .%s of box41.msh: %s" % (ext, err)):
            compare_gmsh_via_meshio(direct, via, ext)


def compare_gmsh_via_meshio(direct, via, ext):
    """The .mesh of box41.msh read directly and through meshio's file of extension `ext`."""
    a, b = read_medit(direct), read_medit(via)
    check(sorted(a["regions"]) == [1] * 24 + [2] * 24, "box41.msh: regions %r" % sorted(set(a["regions"])))
    check(sorted(m for m in b["markers"] if m) == [10] * 8 and b["edge_refs"] == [20],
          "via meshio's .%s: markers %r, edge refs %r" % (ext, sorted(set(b["markers"])), b["edge_refs"]))

    def by_position(m):
        """Tets (with region) and marked triangles by their vertices' coordinates."""
        key = lambda cell: tuple(sorted(m["points"][v] for v in cell))
        return ({key(t): r for t, r in zip(m["tets"], m["regions"])},
                {key(t): r for t, r in zip(m["triangles"], m["markers"])})
    check(by_position(a) == by_position(b),
          "box41.msh via meshio's .%s: tets, regions or markers differ from the .msh read directly" % ext)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bodt", required=True)
    parser.add_argument("--data", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    ours_read_by_meshio(args)
    meshio_read_by_ours(args)
    medit_blocks_read_by_ours(args)
    gmsh_through_meshio(args)
    return checks.exit_status("ok (meshio %s)" % meshio.__version__)


if __name__ == "__main__":
    sys.exit(main())
