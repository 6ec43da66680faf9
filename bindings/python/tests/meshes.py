"""Meshes the tests build with numpy, and measures computed without libbodt."""

import numpy as np

# The six Kuhn tets of a cube: the paths 0 -> e_a -> e_a + e_b -> 111 over
# the permutations of the axes, corners as bit masks (x = 1, y = 2, z = 4),
# odd permutations with their last two corners swapped: all positive.
KUHN = np.array([[0, 1, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 1, 7, 5], [0, 2, 7, 3], [0, 4, 7, 6]])


def box(n: int, jitter: float = 0.0, seed: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """The unit cube cut into n^3 cubes of 6 Kuhn tets: (points, tets), 0-based.

    Vertex (i, j, k) of the grid is number (k * (n + 1) + j) * (n + 1) + i, at
    (i, j, k) / n; each interior vertex is moved by up to ``jitter`` times the
    spacing along each axis.
    """
    g = n + 1
    k, j, i = np.meshgrid(np.arange(g), np.arange(g), np.arange(g), indexing="ij")
    grid = np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1)
    points = grid / n
    interior = np.all((grid > 0) & (grid < n), axis=1)
    rng = np.random.default_rng(seed)
    points[interior] += rng.uniform(-jitter, jitter, (interior.sum(), 3)) / n
    ck, cj, ci = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    first = ((ck * g + cj) * g + ci).ravel()
    corner = np.array([(c >> 2 & 1) * g * g + (c >> 1 & 1) * g + (c & 1) for c in range(8)])
    tets = (first[:, None, None] + corner[KUHN][None, :, :]).reshape(-1, 4)
    return points, tets


def grid_boundary_axes(n: int) -> np.ndarray:
    """For box(n)'s vertices: on how many of the cube's faces each one lies (0 inside ... 3 at a corner)."""
    g = n + 1
    k, j, i = np.meshgrid(np.arange(g), np.arange(g), np.arange(g), indexing="ij")
    grid = np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1)
    return np.sum((grid == 0) | (grid == n), axis=1)


def cube_edge_number(p: np.ndarray, q: np.ndarray) -> int:
    """The number, 1 ... 12, of the cube's edge on which segment pq lies: 1 + 4 axis + 2 c1 + c2.

    ``axis`` is the segment's direction and c1, c2 (0 or 1) are its other two coordinates, in axis order.
    """
    axis = int(np.argmax(np.abs(q - p)))
    others = np.delete(np.stack([p, q]), axis, axis=1)
    corner = np.round(others[0])
    assert np.allclose(others, corner, rtol=0, atol=1e-12) and set(corner) <= {0, 1}, f"{p} {q}: off the cube's edges"
    return int(1 + 4 * axis + 2 * corner[0] + corner[1])


def cube_edges(n: int) -> tuple[np.ndarray, np.ndarray]:
    """box(n)'s 12 n edges on the cube's edges, (12 n, 2), and the cube_edge_number of each."""
    points, _ = box(n)
    g = n + 1
    pairs = []
    for axis in range(3):
        others = [g**a for a in range(3) if a != axis]
        for c1 in (0, n):
            for c2 in (0, n):
                first = c1 * others[0] + c2 * others[1]
                pairs += [(first + t * g**axis, first + (t + 1) * g**axis) for t in range(n)]
    pairs = np.array(pairs)
    return pairs, np.array([cube_edge_number(points[a], points[b]) for a, b in pairs])


def regular_tet() -> tuple[np.ndarray, np.ndarray]:
    """A regular tet of edge 2 sqrt(2), positively oriented."""
    points = np.array([[1.0, 1, 1], [1, -1, -1], [-1, -1, 1], [-1, 1, -1]])
    return points, np.array([[0, 1, 2, 3]])


def octahedron() -> tuple[np.ndarray, np.ndarray]:
    """examples/quickstart.c's octahedron: 8 tets around vertex 6, off-centre."""
    points = np.array([[1.0, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1], [0.45, 0.3, 0.2]])
    tets = np.array([[6, 0, 2, 4], [6, 2, 1, 4], [6, 3, 0, 4], [6, 1, 3, 4],
                     [6, 2, 0, 5], [6, 1, 2, 5], [6, 0, 3, 5], [6, 3, 1, 5]])
    return points, tets


def signed_volumes(points: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """Each tet's signed volume."""
    a, b, c, d = (points[tets[:, m]] for m in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


def dihedral_angles(points: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """(ntets, 6) dihedral angles in degrees, from the faces' normals."""
    p = points[tets]
    faces = [(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)]  # opposite vertex 0, 1, 2, 3; outward for positive tets
    normals = [np.cross(p[:, b] - p[:, a], p[:, c] - p[:, a]) for a, b, c in faces]
    normals = [m / np.linalg.norm(m, axis=1, keepdims=True) for m in normals]
    angles = [
        180.0 - np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals[s], normals[t]), -1.0, 1.0)))
        for s in range(4)
        for t in range(s + 1, 4)
    ]
    return np.stack(angles, axis=1)


def edges(tets: np.ndarray) -> np.ndarray:
    """The distinct edges of ``tets``, each (lower, higher), sorted."""
    pairs = tets[:, [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]].reshape(-1, 2)
    return np.unique(np.sort(pairs, axis=1), axis=0)
