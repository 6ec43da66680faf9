"""Meshes for the tests of tests/interop, in plain Python.

kuhn_box() makes a box of tets with its boundary triangles (written and read
as Medit files by tests/support/medit_files.py).  No libbodt code: what the
tests compare against is computed here.
"""
import random


def kuhn_box(n, size, jitter=0.0, seed=1):
    """A box [0, size[0]] x [0, size[1]] x [0, size[2]] cut into n[0] x n[1] x n[2]
    cubes of 6 Kuhn tets each, positively oriented.

    Returns (points, tets, regions, triangles, markers): tets 0-based; region 1
    for tets whose centre has x < size[0] / 2, else 2; every boundary triangle,
    marked 1 on x = 0, 2 on x = size[0], 3 on the other sides.  Interior
    vertices are moved by up to `jitter` times the cell size in each direction
    (seeded), so that there is something to improve.
    """
    nx, ny, nz = n
    h = [size[0] / nx, size[1] / ny, size[2] / nz]
    rng = random.Random(seed)

    def vid(i, j, k):
        return (i * (ny + 1) + j) * (nz + 1) + k

    points = []
    for i in range(nx + 1):
        for j in range(ny + 1):
            for k in range(nz + 1):
                # i * size / n: exactly size on the far side
                p = [i * size[0] / nx, j * size[1] / ny, k * size[2] / nz]
                if 0 < i < nx and 0 < j < ny and 0 < k < nz:
                    p = [p[a] + jitter * h[a] * rng.uniform(-1, 1) for a in range(3)]
                points.append(tuple(p))
    # The 6 tets of a cube around its diagonal from corner 0 to corner 7
    # (corner c = (c & 4, c & 2, c & 1) as (i, j, k) offsets).
    paths = [(4, 6), (4, 5), (2, 6), (2, 3), (1, 5), (1, 3)]
    tets, regions = [], []
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                corner = [vid(i + (c >> 2 & 1), j + (c >> 1 & 1), k + (c & 1)) for c in range(8)]
                for a, b in paths:
                    t = [corner[0], corner[a], corner[b], corner[7]]
                    if signed_volume([points[v] for v in t]) < 0:
                        t[1], t[2] = t[2], t[1]
                    tets.append(tuple(t))
                    regions.append(1 if (i + 0.5) * h[0] < size[0] / 2 else 2)
    faces = {}
    for t in tets:
        for f in ((t[0], t[1], t[2]), (t[0], t[3], t[1]), (t[1], t[3], t[2]), (t[2], t[3], t[0])):
            key = tuple(sorted(f))
            faces[key] = None if key in faces else f
    triangles, markers = [], []
    for f in faces.values():
        if f is None:
            continue
        xs = [points[v][0] for v in f]
        triangles.append(f)
        markers.append(1 if max(xs) == 0 else 2 if min(xs) == size[0] else 3)
    return points, tets, regions, triangles, markers


def signed_volume(p):
    a = [p[1][k] - p[0][k] for k in range(3)]
    b = [p[2][k] - p[0][k] for k in range(3)]
    c = [p[3][k] - p[0][k] for k in range(3)]
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
