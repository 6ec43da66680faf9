"""Medit .mesh files for the Python tests that CTest runs (tests/cli,
tests/interop), in plain Python: write_medit() writes 0-based arrays as a
file the bodt command takes, read_medit() reads back the ones it gives.  No
libbodt code: what the tests compare against is computed with these.
"""


def write_medit(path, points, tets, regions=None, triangles=(), markers=(), vertex_refs=None, edges=(),
                edge_refs=()):
    """A Medit .mesh file (1-based) of 0-based arrays: region 1 and vertex
    ref 0 where none are given, no Triangles or Edges section without any."""
    refs = vertex_refs or [0] * len(points)
    regions = regions or [1] * len(tets)
    with open(path, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % len(points))
        for p, r in zip(points, refs):
            f.write("%.17g %.17g %.17g %d\n" % (p[0], p[1], p[2], r))
        f.write("Tetrahedra\n%d\n" % len(tets))
        for t, r in zip(tets, regions):
            f.write("%d %d %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1, r))
        if triangles:
            f.write("Triangles\n%d\n" % len(triangles))
            for t, m in zip(triangles, markers):
                f.write("%d %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1, m))
        if edges:
            f.write("Edges\n%d\n" % len(edges))
            for e, r in zip(edges, edge_refs):
                f.write("%d %d %d\n" % (e[0] + 1, e[1] + 1, r))
        f.write("End\n")


def read_medit(path):
    """The sections of a Medit .mesh file, 0-based: a dict with points,
    vertex_refs, tets, regions, triangles, markers, edges, edge_refs."""
    tokens = []
    with open(path) as f:
        for line in f:
            tokens += line.split("#", 1)[0].split()
    m = {key: [] for key in ("points", "vertex_refs", "tets", "regions", "triangles", "markers", "edges",
                             "edge_refs")}
    k = 0
    while k < len(tokens):
        t = tokens[k]
        k += 1
        if t == "Vertices":
            n = int(tokens[k]); k += 1
            for _ in range(n):
                m["points"].append(tuple(float(x) for x in tokens[k:k + 3]))
                m["vertex_refs"].append(int(tokens[k + 3]))
                k += 4
        elif t in ("Tetrahedra", "Triangles", "Edges"):
            width = {"Tetrahedra": 4, "Triangles": 3, "Edges": 2}[t]
            cells, refs = {"Tetrahedra": ("tets", "regions"), "Triangles": ("triangles", "markers"),
                           "Edges": ("edges", "edge_refs")}[t]
            n = int(tokens[k]); k += 1
            for _ in range(n):
                m[cells].append(tuple(int(x) - 1 for x in tokens[k:k + width]))
                m[refs].append(int(tokens[k + width]))
                k += width + 1
        elif t in ("RequiredVertices", "Corners", "Ridges"):
            n = int(tokens[k]); k += 1 + n
        elif t in ("Dimension", "MeshVersionFormatted"):
            k += 1
    return m
