"""Meshes from and to meshio: :func:`from_meshio` and ``Mesh.to_meshio()``.

A ``meshio.Mesh`` holds points, blocks of cells of one type each
("tetra", "triangle", "line", "vertex", ...), cell data (name -> one array
per block), point data (name -> one value per point) and field data.
meshio's readers put each cell's tag in their format's cell data: Gmsh's
physical tag in "gmsh:physical" (its entity tag in "gmsh:geometrical"),
Medit's ref in "medit:ref", MED's family in "cell_tags"; VTK files of
other tools often hold "CellEntityIds".

from_meshio reads a mesh as bodt_mesh_read reads these formats (bodt.h):

=========  ================================================================
tetra      the tets; their tags are the region ids (0 without tags)
triangle   the faces with a non-zero tag, marked with it (without tags,
           every triangle, marked 1); each must be a face of the mesh
           (a boundary or interior face), else InvalidArgumentError names it
line       feature edges with their tags as refs (0 without tags); an edge
           listed again (Gmsh 2.2 lists it once per physical group) keeps
           its first ref
vertex     fixed vertices: those with a non-zero tag (without tags, all)
=========  ================================================================

The tags are the first of the cell data "gmsh:physical", "medit:ref",
"cell_tags" and "CellEntityIds" the mesh has, or the one named by
``tags``; the vertex refs are the point data "medit:ref" or the one named
by ``refs``.  Where a Gmsh mesh has no physical tags (Gmsh saves every
element, with its entity tag in "gmsh:geometrical", when no physical
group is set), it is read as bodt_mesh_read reads the file: tets without
any physical tag take their volume's entity tag as region id when they lie
in several volumes, triangles without any physical tag their surface's as
marker when they lie on several surfaces (else no face is marked), and
points outside physical groups are not fixed.  Cells of lower dimension of
other types (quads, second-order triangles) are skipped; other 3-D cells
(hexahedra, second-order tets) raise ValueError.  The field data (Gmsh's
physical names) is kept in the Mesh's ``field_data``.

to_meshio writes what from_meshio reads back, in a form meshio writes to
Gmsh (.msh, 4.1 and 2.2), Medit (.mesh) and VTU (.vtu) files:

=========  ================================================================
tetra      one block per region id, ascending; in each, the tets in
           ``mesh.tets`` order
triangle   one block per non-zero face marker (unmarked boundary faces
           are left out)
line       one block per feature-edge ref: the caller's feature edges
vertex     one block of the fixed vertices, tag 1
=========  ================================================================

with cell data "gmsh:physical" (each cell's tag) and "gmsh:geometrical"
(its block's Gmsh entity, 1, 2, ... per dimension), point data "medit:ref"
(the vertex refs) and "gmsh:dim_tags" (each point's Gmsh entity, which
meshio's Gmsh 4.1 writer needs), and the Mesh's ``field_data``.  Indices
count from 0 and are int64, as in meshio, whatever the Mesh's base and
int_dtype.  Medit files have no place for fixed vertices (meshio warns
that it skips the vertex cells) and take only the first cell data and
point data (meshio warns about the others); no format here keeps the
caller's corners.

What meshio 5.0 does with such a mesh: ``meshio.write("x.msh", m)``
writes ANSYS, ``file_format="gmsh"`` (4.1) or ``"gmsh22"`` Gmsh; a 4.1
file lists the points by entity, so meshio reads them back in another
order (2.2 keeps it); a .mesh or .meshb file gets one section per block,
which meshio and libbodt read (libbodt appends repeated sections in file
order), but libMeshb, Medit's own library, and MMG keep only the last
section of each kind (write .mesh files for them with ``Mesh.write``);
.vtu files are compressed, which libbodt's reader refuses
(``compression=None``) and keep no field data.
"""

from typing import Any, NamedTuple

import numpy as np
from numpy.typing import DTypeLike

from .mesh import Mesh

__all__ = ["from_meshio", "to_meshio"]

_TAG_NAMES = ("gmsh:physical", "medit:ref", "cell_tags", "CellEntityIds")
_REF_NAMES = ("medit:ref",)
_WIDTHS = {"vertex": 1, "line": 2, "triangle": 3, "tetra": 4}
_DIMENSIONS = {"vertex": 0, "line": 1, "triangle": 2, "tetra": 3}


def _pick(data: dict[str, Any], name: str | None, known: tuple[str, ...], what: str) -> str | None:
    """The data ``name`` asks for (which must exist), else the first of ``known`` there is, else None."""
    if name is not None:
        if name not in data:
            raise ValueError(f"the meshio mesh has no {what} {name!r} (it has {sorted(data)})")
        return name
    return next((candidate for candidate in known if candidate in data), None)


def _integers(values: Any, what: str) -> np.ndarray:
    """``values`` as integers; floats only if each is a whole number (meshio reads some tags as floats)."""
    array = np.asarray(values)
    if array.dtype.kind == "f":
        if not np.all(np.isfinite(array) & (array == np.round(array))):
            raise TypeError(f"{what} must be whole numbers")
        return array.astype(np.int64)
    if array.dtype.kind not in "iu":
        raise TypeError(f"{what} must hold integers, got dtype {array.dtype}")
    return array


class _Cells(NamedTuple):
    """The cells of one type from all blocks, each with its tag and Gmsh entity (None: not in the mesh)."""

    cells: np.ndarray
    tags: np.ndarray | None
    entities: np.ndarray | None


def _cells_by_type(mesh: Any, tag_name: str | None, gmsh: bool) -> dict[str, _Cells]:
    """The blocks of each cell type libbodt takes, joined, with their tags and (``gmsh``) Gmsh entities."""
    numbers: dict[str, list[int]] = {cell_type: [] for cell_type in _WIDTHS}  # each type's blocks
    for k, block in enumerate(mesh.cells):
        if block.type in numbers:
            numbers[block.type].append(k)
        elif block.dim == 3:
            raise ValueError(f"the meshio mesh has {block.type!r} cells: libbodt improves 4-node tets only")
    if not numbers["tetra"]:
        raise ValueError("the meshio mesh has no 'tetra' cells")

    def joined(name: str | None, blocks: list[int]) -> np.ndarray | None:
        if name is None or not blocks:
            return None
        return np.concatenate([_integers(mesh.cell_data[name][k], f"cell data {name!r}") for k in blocks])

    by_type = {}
    for cell_type, blocks in numbers.items():
        width = _WIDTHS[cell_type]
        cells = [np.asarray(mesh.cells[k].data).reshape(-1, width) for k in blocks]
        by_type[cell_type] = _Cells(
            np.concatenate(cells) if cells else np.empty((0, width), np.int64),
            joined(tag_name, blocks),
            joined("gmsh:geometrical" if gmsh else None, blocks),
        )
    return by_type


def _several(values: np.ndarray | None) -> bool:
    return values is not None and values.size > 0 and bool(np.any(values != values[0]))


def from_meshio(
    mesh: Any,
    tags: str | None = None,
    refs: str | None = None,
    base: int = 0,
    accept_inverted: bool = False,
    int_dtype: DTypeLike = np.int64,
) -> Mesh:
    """A :class:`~bodt.Mesh` from a ``meshio.Mesh``: tets, regions, face markers, feature edges, fixed vertices.

    See the module :mod:`bodt._meshio` for what each cell type and data
    becomes.  ``tags`` names the cell data with the cells' tags, ``refs``
    the point data with the vertex refs (by default, each format's).
    ``base``, ``accept_inverted`` and ``int_dtype`` are those of
    :class:`~bodt.Mesh`; meshio's indices count from 0 whatever ``base``.
    """
    tag_name = _pick(mesh.cell_data, tags, _TAG_NAMES, "cell data")
    ref_name = _pick(mesh.point_data, refs, _REF_NAMES, "point data")
    # Gmsh's entity tags, where its physical tags are missing (bodt.h, BODT_FORMAT_GMSH)
    gmsh = tag_name in (None, "gmsh:physical") and "gmsh:geometrical" in mesh.cell_data
    by_type = _cells_by_type(mesh, tag_name, gmsh)
    tets = by_type["tetra"].cells + base
    result = Mesh(mesh.points, tets, base=base, accept_inverted=accept_inverted, int_dtype=int_dtype)
    try:
        _set_cell_data(result, by_type, base)
        if ref_name is not None:
            result.set_vertex_refs(_integers(mesh.point_data[ref_name], f"point data {ref_name!r}"))
    except BaseException:
        result.close()
        raise
    result.field_data = {name: np.array(value) for name, value in mesh.field_data.items()}
    return result


def _set_cell_data(mesh: Mesh, by_type: dict[str, _Cells], base: int) -> None:
    """Regions, face markers, feature edges and fixed vertices from the cells, their tags and Gmsh entities."""
    tets, triangles, lines, vertices = (by_type[t] for t in ("tetra", "triangle", "line", "vertex"))
    if tets.tags is not None and np.any(tets.tags):
        mesh.set_regions(tets.tags)
    elif _several(tets.entities):
        mesh.set_regions(tets.entities)

    if triangles.tags is not None and np.any(triangles.tags):
        marked, markers = triangles.tags != 0, triangles.tags
    elif triangles.entities is not None:
        marked = np.full(len(triangles.cells), _several(triangles.entities))
        markers = triangles.entities
    else:  # no tags: each triangle is there to be marked; tags all 0: none is
        marked = np.full(len(triangles.cells), triangles.tags is None)
        markers = np.ones(len(triangles.cells), np.int64)
    if np.any(marked):
        mesh.set_boundary_faces(triangles.cells[marked] + base, markers[marked])

    if lines.cells.size:
        # the first listing of each edge, in the order given
        _, first = np.unique(np.sort(lines.cells, axis=1), axis=0, return_index=True)
        first.sort()
        mesh.set_feature_edges(lines.cells[first] + base, None if lines.tags is None else lines.tags[first])

    if vertices.tags is not None:
        fixed = vertices.cells[vertices.tags != 0]
    else:  # Gmsh's points outside physical groups are not fixed
        fixed = vertices.cells[:0] if vertices.entities is not None else vertices.cells
    if fixed.size:
        mesh.set_fixed_vertices(fixed.ravel() + base)


def _node_entities(npoints: int, blocks: list[tuple[str, np.ndarray, int]], entities: list[int]) -> np.ndarray:
    """(npoints, 2) Gmsh (dimension, entity) of each point, for meshio's Gmsh 4.1 writer.

    Gmsh puts a node in the entity of lowest dimension it lies on.  meshio
    writes only the entities that hold a node (and fails to read back the
    elements of any other), so an entity left without a node of its own
    takes one from an entity holding several.  A point in no cell joins
    the first volume.
    """
    owner = np.zeros(npoints, np.int64)  # the block whose entity holds each point
    by_dimension = sorted(range(len(blocks)), key=lambda k: _DIMENSIONS[blocks[k][0]])
    for k in reversed(by_dimension):
        owner[blocks[k][1].ravel()] = k
    counts = np.bincount(owner, minlength=len(blocks))
    for k in by_dimension:
        if counts[k] == 0:
            nodes = np.unique(blocks[k][1])
            donors = nodes[counts[owner[nodes]] > 1]
            if donors.size:
                counts[owner[donors[0]]] -= 1
                owner[donors[0]] = k
                counts[k] = 1
    dimensions = np.array([_DIMENSIONS[cell_type] for cell_type, _, _ in blocks])
    return np.stack([dimensions[owner], np.asarray(entities)[owner]], axis=1)


def to_meshio(mesh: Mesh) -> Any:
    """``mesh`` as a ``meshio.Mesh``, as described in the module's docstring."""
    import meshio

    def zero_based(indices: np.ndarray) -> np.ndarray:
        return np.asarray(indices, np.int64) - mesh.base

    blocks: list[tuple[str, np.ndarray, int]] = []  # (cell type, cells from 0, tag)
    entities: list[int] = []  # each block's Gmsh entity: 1, 2, ... per dimension

    def add(cell_type: str, cells: np.ndarray, tags: np.ndarray) -> None:
        for entity, tag in enumerate(np.unique(tags), 1):
            blocks.append((cell_type, zero_based(cells[tags == tag]), int(tag)))
            entities.append(entity)

    add("tetra", mesh.tets, mesh.regions)
    faces = mesh.boundary_faces()
    marked = faces.markers != 0
    add("triangle", faces.triangles[marked], faces.markers[marked])
    edges, edge_refs = mesh._feature_edges()
    add("line", edges, edge_refs)
    fixed = mesh.fixed_vertices
    add("vertex", fixed[:, None], np.ones(len(fixed), np.int64))

    points = mesh.points
    return meshio.Mesh(
        points,
        [(cell_type, cells) for cell_type, cells, _ in blocks],
        point_data={
            "medit:ref": np.asarray(mesh.vertex_refs, np.int64),
            "gmsh:dim_tags": _node_entities(len(points), blocks, entities),
        },
        cell_data={
            "gmsh:physical": [np.full(len(cells), tag, np.int64) for _, cells, tag in blocks],
            "gmsh:geometrical": [np.full(len(block[1]), entity, np.int64) for block, entity in zip(blocks, entities)],
        },
        field_data={name: np.array(value) for name, value in mesh.field_data.items()},
    )
