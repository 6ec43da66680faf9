"""The Mesh class: a bodt_mesh handle with numpy arrays in and out."""

import functools
import os
import weakref
from collections.abc import Callable
from ctypes import byref, c_double, c_int, c_int32, c_int64, c_void_p
from typing import Any, NoReturn

import numpy as np
from numpy.typing import ArrayLike, DTypeLike

from ._arrays import checked_int_dtype, float_array, index_array, int32, pointer
from ._library import STEP_CALLBACK, check, lib
from .enums import CreateFlag, Format, Measure, Mode, Param
from .errors import CancelledError
from .results import (
    BoundaryFaces,
    FaceRegions,
    GeometryCounts,
    Quality,
    RecoveryReport,
    ShapeFit,
    StepReport,
    VertexParents,
)
from .structs import DIHEDRAL_BINS, QualityStruct, RecoveryErrorStruct, ShapeFitStruct, StepReportStruct, sized

__all__ = ["INT_PARAMS", "Mesh", "dihedral_bin_edges"]

#: The keys set and read as int (bodt_set_param_int); every other Param is a double.
INT_PARAMS = frozenset(
    {
        Param.BACKTRACK_STEPS,
        Param.NEVER_WORSE,
        Param.OPS,
        Param.KEEP_SURFACE,
        Param.DELAUNAY_FLIPS,
        Param.QN_MAX_ITERATIONS,
        Param.THREADS,
    }
)

_CLOSED = "operation on a closed bodt.Mesh"


@functools.cache
def dihedral_bin_edges() -> np.ndarray:
    """The BODT_DIHEDRAL_BINS + 1 edges, in degrees, of Quality.dihedral_histogram's bins (bodt_dihedral_bin_edges)."""
    edges = np.empty(DIHEDRAL_BINS + 1)
    check(lib.bodt_dihedral_bin_edges(pointer(edges), edges.size), None)
    edges.flags.writeable = False
    return edges


def format_from_path(path: str | os.PathLike[str]) -> Format:
    """The file format ``path``'s extension names, as Mesh.read and Mesh.write choose it (bodt_format_from_path).

    Raises UnsupportedError for an extension that names none: a check of an output path before the work.
    """
    format_ = c_int()
    check(lib.bodt_format_from_path(os.fsencode(path), byref(format_)), None)
    return Format(format_.value)


def _flags(accept_inverted: bool) -> CreateFlag:
    return CreateFlag.ACCEPT_INVERTED if accept_inverted else CreateFlag.DEFAULT


class Mesh:
    """A tetrahedral mesh held by libbodt, improved in place.

    ``Mesh(points, tets, base=0, accept_inverted=False)`` copies ``points``
    ((n, 3) coordinates) and ``tets`` ((m, 4) vertex indices, any integer
    dtype and memory order) into a new handle (bodt_mesh_create_ex).
    ``base`` (0 or 1) is the index base of every vertex, tet and region index
    the mesh takes and gives, in arrays and in error messages.  A wrong array
    shape, or an integer outside the int32 range of the C API, raises
    ValueError before the library sees it; data the library refuses raises
    the :class:`~bodt.Error` subclass of its status, with its message.

    bodt.h documents what each method does: each one is a C call, named in
    its docstring.  Getters return new numpy arrays: float64 values, and
    integers (indices, ids, refs, classes) in ``int_dtype``: numpy.int64 by
    default, as numpy and meshio use, or numpy.int32, as the C API gives
    them and earlier versions of the package did.  The handle is freed by
    :meth:`close`, on leaving a ``with`` block, or when the Mesh is garbage
    collected; a closed Mesh raises ValueError.  As with the C handle, one
    Mesh must not be used from two threads at the same time.

    ``field_data`` maps names to tags as meshio's ``field_data`` does
    (Gmsh's physical names: name -> [tag, dimension]); the library does not
    read it: :func:`~bodt.from_meshio` fills it and :meth:`to_meshio` gives
    it back.
    """

    def __init__(
        self,
        points: ArrayLike,
        tets: ArrayLike,
        base: int = 0,
        accept_inverted: bool = False,
        int_dtype: DTypeLike = np.int64,
    ) -> None:
        dtype = checked_int_dtype(int_dtype)
        xyz = float_array(points, (None, 3), "points")
        vertices = index_array(tets, (None, 4), "tets")
        base = int32(base, "base")
        handle = c_void_p()
        status = lib.bodt_mesh_create_ex(
            int32(len(xyz), "the number of points"),
            pointer(xyz),
            int32(len(vertices), "the number of tets"),
            pointer(vertices),
            base,
            _flags(accept_inverted),
            byref(handle),
        )
        check(status, None)
        self._own(handle.value, dtype)

    @classmethod
    def read(
        cls,
        path: str | os.PathLike[str],
        accept_inverted: bool = False,
        base: int | str = 0,
        format: Format = Format.AUTO,  # noqa: A002 (bodt.h's name)
        int_dtype: DTypeLike = np.int64,
    ) -> "Mesh":
        """A mesh from a file (bodt_mesh_read_format), counting from ``base``: 0, 1, or "file" for the
        file's own numbering (Medit 1, VTK 0; ``mesh.base`` then tells which).

        The format is the extension's (.mesh, .meshb, .node/.ele, .msh, .vtu, .vtk) unless ``format`` says.
        """
        bases = {0: CreateFlag.DEFAULT, 1: CreateFlag.ONE_BASED, "file": CreateFlag.FILE_BASE}
        if base not in bases:
            raise ValueError(f"base is {base!r}, not 0, 1 or 'file'")
        flags = _flags(accept_inverted) | bases[base]
        dtype = checked_int_dtype(int_dtype)  # before the read: a refusal after it would leak the handle
        handle = c_void_p()
        check(lib.bodt_mesh_read_format(os.fsencode(path), int32(format, "format"), flags, byref(handle)), None)
        mesh = cls.__new__(cls)
        mesh._own(handle.value, dtype)
        return mesh

    @property
    def int_dtype(self) -> np.dtype:
        """The dtype of the integer arrays this mesh gives: numpy.int64 (the default) or numpy.int32."""
        return self._int_dtype

    @int_dtype.setter
    def int_dtype(self, value: DTypeLike) -> None:
        self._int_dtype = checked_int_dtype(value)

    def _own(self, handle: int, int_dtype: np.dtype) -> None:
        """Take ``handle`` (freed with this Mesh) and set up what every Mesh has besides it."""
        self._handle_value = handle
        self._finalizer = weakref.finalize(self, lib.bodt_mesh_destroy, handle)
        self._int_dtype = int_dtype
        self.field_data: dict[str, Any] = {}

    # ------------------------------------------------------------ lifetime

    def close(self) -> None:
        """Free the handle (bodt_mesh_destroy); closing again does nothing."""
        self._finalizer()

    @property
    def closed(self) -> bool:
        return not self._finalizer.alive

    def __enter__(self) -> "Mesh":
        if self.closed:
            raise ValueError(_CLOSED)
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def __reduce__(self) -> NoReturn:
        # a copy would share the handle, and use it once the original freed it
        raise TypeError("a bodt.Mesh cannot be copied or pickled: make a new one from its arrays")

    def __repr__(self) -> str:
        if self.closed:
            return "<bodt.Mesh (closed)>"
        return f"<bodt.Mesh {self.num_vertices} vertices, {self.num_tets} tets, base {self.base}>"

    @property
    def _handle(self) -> int:
        if self.closed:
            raise ValueError(_CLOSED)
        return self._handle_value

    def _check(self, status: int) -> None:
        check(status, self._handle_value)

    # ------------------------------------------------------------- counts

    @property
    def base(self) -> int:
        """The index base (0 or 1) of every index in and out (bodt_mesh_get_index_base)."""
        base = c_int()
        self._check(lib.bodt_mesh_get_index_base(self._handle, byref(base)))
        return base.value

    def _counts(self) -> tuple[int, int, int]:
        nverts, ntets, nfaces = c_int32(), c_int32(), c_int32()
        self._check(lib.bodt_mesh_get_counts(self._handle, byref(nverts), byref(ntets), byref(nfaces)))
        return nverts.value, ntets.value, nfaces.value

    @property
    def num_vertices(self) -> int:
        return self._counts()[0]

    @property
    def num_tets(self) -> int:
        return self._counts()[1]

    @property
    def num_boundary_faces(self) -> int:
        return self._counts()[2]

    # ------------------------------------------------------------ getters

    def _ints(self, array: np.ndarray) -> np.ndarray:
        """An int32 array from the C API in this mesh's int_dtype."""
        return array.astype(self._int_dtype, copy=False)

    def _fetch(self, function: Callable[..., int], shape: tuple[int, ...]) -> np.ndarray:
        """An integer array filled by ``function``, in int_dtype."""
        out = np.empty(shape, np.int32)
        self._check(function(self._handle, pointer(out), out.size))
        return self._ints(out)

    @property
    def points(self) -> np.ndarray:
        """(nverts, 3) coordinates (bodt_mesh_get_vertices)."""
        xyz = np.empty((self.num_vertices, 3))
        self._check(lib.bodt_mesh_get_vertices(self._handle, pointer(xyz), xyz.size))
        return xyz

    @property
    def tets(self) -> np.ndarray:
        """(ntets, 4) vertex indices, in the caller's orientation (bodt_mesh_get_tets)."""
        return self._fetch(lib.bodt_mesh_get_tets, (self.num_tets, 4))

    @property
    def regions(self) -> np.ndarray:
        """ntets region ids (bodt_mesh_get_regions)."""
        return self._fetch(lib.bodt_mesh_get_regions, (self.num_tets,))

    def boundary_faces(self) -> BoundaryFaces:
        """(nfaces, 3) triangles and nfaces markers (bodt_mesh_get_boundary_faces)."""
        nfaces = self.num_boundary_faces
        triangles = np.empty((nfaces, 3), np.int32)
        markers = np.empty(nfaces, np.int32)
        self._check(lib.bodt_mesh_get_boundary_faces(self._handle, pointer(triangles), pointer(markers), nfaces))
        return BoundaryFaces(self._ints(triangles), self._ints(markers))

    def _flagged(self, function: Callable[..., int]) -> np.ndarray:
        flags = self._fetch(function, (self.num_vertices,))
        return self._ints(np.flatnonzero(flags) + self.base)

    @property
    def fixed_vertices(self) -> np.ndarray:
        """The fixed vertices' indices, ascending (from bodt_mesh_get_fixed_vertices' flags)."""
        return self._flagged(lib.bodt_mesh_get_fixed_vertices)

    def _feature_edges(self) -> tuple[np.ndarray, np.ndarray]:
        nedges = c_int32()
        self._check(lib.bodt_mesh_get_feature_edges_ex(self._handle, byref(nedges), None, None, 0))
        edges = np.empty((nedges.value, 2), np.int32)
        refs = np.empty(nedges.value, np.int32)
        self._check(
            lib.bodt_mesh_get_feature_edges_ex(self._handle, byref(nedges), pointer(edges), pointer(refs), len(edges))
        )
        return self._ints(edges), self._ints(refs)

    @property
    def feature_edges(self) -> np.ndarray:
        """(nedges, 2) vertex indices of the caller's feature edges, sorted (bodt_mesh_get_feature_edges_ex)."""
        return self._feature_edges()[0]

    @property
    def feature_edge_refs(self) -> np.ndarray:
        """nedges refs of the caller's feature edges, in feature_edges' order (bodt_mesh_get_feature_edges_ex)."""
        return self._feature_edges()[1]

    @property
    def corners(self) -> np.ndarray:
        """The caller's corners' indices, ascending (from bodt_mesh_get_corners' flags)."""
        return self._flagged(lib.bodt_mesh_get_corners)

    @property
    def vertex_refs(self) -> np.ndarray:
        """nverts vertex refs (bodt_mesh_get_vertex_refs)."""
        return self._fetch(lib.bodt_mesh_get_vertex_refs, (self.num_vertices,))

    @property
    def vertex_classes(self) -> np.ndarray:
        """nverts :class:`~bodt.VertexClass` values (bodt_mesh_get_vertex_classes)."""
        return self._fetch(lib.bodt_mesh_get_vertex_classes, (self.num_vertices,))

    def vertex_parents(self) -> VertexParents:
        """Each vertex's parents among the input vertices, and their weights (bodt_mesh_get_vertex_parents).

        ``offsets`` (nverts + 1, counted from 0) delimit each vertex's
        entries in ``parents`` (indices in the mesh's base) and ``weights``.
        """
        total = c_int64()
        self._check(lib.bodt_mesh_get_parent_count(self._handle, byref(total)))
        offsets = np.empty(self.num_vertices + 1, np.int64)
        parents = np.empty(total.value, np.int32)
        weights = np.empty(total.value, np.float64)
        self._check(
            lib.bodt_mesh_get_vertex_parents(
                self._handle, pointer(offsets), offsets.size, pointer(parents), pointer(weights), parents.size
            )
        )
        return VertexParents(offsets, self._ints(parents), weights)

    @property
    def tet_origins(self) -> np.ndarray:
        """ntets indices of the input tet each tet lies in (bodt_mesh_get_tet_origins)."""
        return self._fetch(lib.bodt_mesh_get_tet_origins, (self.num_tets,))

    # ------------------------------------------------------------ setters

    def set_regions(self, region_ids: ArrayLike) -> None:
        """One region id per tet (bodt_mesh_set_regions)."""
        ids = index_array(region_ids, (self.num_tets,), "region_ids")
        self._check(lib.bodt_mesh_set_regions(self._handle, pointer(ids)))

    def set_boundary_faces(self, triangles: ArrayLike, markers: ArrayLike | None = None) -> None:
        """Mark faces: (nfaces, 3) triangles, nfaces markers or None for all 1 (bodt_mesh_set_boundary_faces)."""
        faces = index_array(triangles, (None, 3), "triangles")
        marks = None if markers is None else index_array(markers, (len(faces),), "markers")
        self._check(
            lib.bodt_mesh_set_boundary_faces(
                self._handle, int32(len(faces), "the number of triangles"), pointer(faces), pointer(marks)
            )
        )

    def set_fixed_vertices(self, vertices: ArrayLike) -> None:
        """The vertices no mode may move, replacing earlier ones (bodt_mesh_set_fixed_vertices)."""
        fixed = index_array(vertices, (None,), "vertices")
        self._check(
            lib.bodt_mesh_set_fixed_vertices(self._handle, int32(len(fixed), "the number of vertices"), pointer(fixed))
        )

    def set_feature_edges(self, edges: ArrayLike, refs: ArrayLike | None = None) -> None:
        """(nedges, 2) feature edges, nedges refs or None for all 0 (bodt_mesh_set_feature_edges_ex).

        Replaces earlier feature edges.
        """
        pairs = index_array(edges, (None, 2), "edges")
        numbers = None if refs is None else index_array(refs, (len(pairs),), "refs")
        self._check(
            lib.bodt_mesh_set_feature_edges_ex(
                self._handle, int32(len(pairs), "the number of edges"), pointer(pairs), pointer(numbers)
            )
        )

    def set_corners(self, vertices: ArrayLike) -> None:
        """The caller's corners, which no mode moves, replacing earlier ones (bodt_mesh_set_corners)."""
        corners = index_array(vertices, (None,), "vertices")
        self._check(
            lib.bodt_mesh_set_corners(self._handle, int32(len(corners), "the number of vertices"), pointer(corners))
        )

    def set_vertex_refs(self, refs: ArrayLike) -> None:
        """One ref per vertex (bodt_mesh_set_vertex_refs)."""
        numbers = index_array(refs, (self.num_vertices,), "refs")
        self._check(lib.bodt_mesh_set_vertex_refs(self._handle, pointer(numbers)))

    # ------------------------------------------------------------ quality

    def quality(self) -> Quality:
        """The mesh's quality summary (bodt_mesh_quality)."""
        summary = sized(QualityStruct)
        self._check(lib.bodt_mesh_quality(self._handle, byref(summary)))
        return Quality.from_struct(summary, dihedral_bin_edges())

    def tet_quality(self, measure: Measure | int) -> np.ndarray:
        """ntets values of one :class:`~bodt.Measure`, in tet order (bodt_mesh_tet_quality)."""
        values = np.empty(self.num_tets)
        self._check(lib.bodt_mesh_tet_quality(self._handle, int32(measure, "measure"), pointer(values), values.size))
        return values

    # --------------------------------------------------- mode and params

    @property
    def mode(self) -> Mode:
        """The :class:`~bodt.Mode` of the next steps (bodt_get_mode, bodt_set_mode).

        Set it to a Mode, its value, or the name the command's ``--mode``
        takes ("bodt", "bodt-basic", "odt", "laplace", "opt-weighted",
        "phased", "nodt"; :meth:`Mode.from_name`).
        """
        mode = c_int()
        self._check(lib.bodt_get_mode(self._handle, byref(mode)))
        return Mode(mode.value)

    @mode.setter
    def mode(self, mode: Mode | int | str) -> None:
        if isinstance(mode, str):
            mode = Mode.from_name(mode)
        self._check(lib.bodt_set_mode(self._handle, int32(mode, "mode")))

    def set_param(self, key: Param | int, value: float) -> None:
        """Set a parameter (bodt_set_param_int for the keys in INT_PARAMS, else bodt_set_param_double)."""
        param = Param(key)
        if param in INT_PARAMS:
            self._check(lib.bodt_set_param_int(self._handle, param, int32(value, f"Param.{param.name}")))
        else:
            self._check(lib.bodt_set_param_double(self._handle, param, float(value)))

    def get_param(self, key: Param | int) -> int | float:
        """A parameter's value: an int for the keys in INT_PARAMS, else a float."""
        param = Param(key)
        if param in INT_PARAMS:
            number = c_int32()
            self._check(lib.bodt_get_param_int(self._handle, param, byref(number)))
        else:
            number = c_double()
            self._check(lib.bodt_get_param_double(self._handle, param, byref(number)))
        return number.value

    # -------------------------------------------------------- improvement

    def step(self) -> StepReport:
        """One improvement sweep in the current mode (bodt_step)."""
        report = sized(StepReportStruct)
        self._check(lib.bodt_step(self._handle, byref(report)))
        return StepReport.from_struct(report)

    def improve(
        self,
        max_steps: int = 20,
        mode: Mode | int | str | None = None,
        callback: Callable[[StepReport], Any] | None = None,
        **params: float,
    ) -> list[StepReport]:
        """Step until converged or ``max_steps`` were done (bodt_run); the reports of the steps done.

        ``mode`` (a :class:`~bodt.Mode` or the command's name for it,
        ``mode="odt"``: see :attr:`mode`) and ``params`` (keyword names of
        :class:`~bodt.Param` members in lower case: ``tolerance=1e-8``,
        ``ops=Op.SMOOTH``) are set on the mesh first and stay set.
        ``callback`` gets each step's :class:`~bodt.StepReport`; a true
        result stops the run with :class:`~bodt.CancelledError`, whose
        ``reports`` are the steps' reports this call would have returned,
        and an exception it raises stops the run and is raised again here.
        The steps done are kept either way.
        """
        keys = {}
        for name, value in params.items():
            if name.upper() not in Param.__members__:
                raise TypeError(f"improve() got an unknown parameter {name!r}: see bodt.Param")
            keys[Param[name.upper()]] = value
        if mode is not None:
            self.mode = mode
        for key, value in keys.items():
            self.set_param(key, value)

        reports: list[StepReport] = []
        raised: list[BaseException] = []

        def on_step(report: Any, _user_data: int | None) -> int:
            reports.append(StepReport.from_struct(report.contents))
            if callback is None:
                return 0
            try:
                return 1 if callback(reports[-1]) else 0
            except BaseException as error:  # raised again below, once bodt_run has returned
                raised.append(error)
                return 1

        status = lib.bodt_run(self._handle, int32(max_steps, "max_steps"), STEP_CALLBACK(on_step), None)
        if raised:
            raise raised[0]
        try:
            self._check(status)
        except CancelledError as cancelled:
            cancelled.reports = reports
            raise
        return reports

    # ----------------------------------------- geometry and reference (paper 002)

    def geometry_counts(self) -> GeometryCounts:
        """The numbers of surface regions and sharp-edge chains (bodt_mesh_get_geometry_counts)."""
        regions, chains = c_int32(), c_int32()
        self._check(lib.bodt_mesh_get_geometry_counts(self._handle, byref(regions), byref(chains)))
        return GeometryCounts(regions.value, chains.value)

    @property
    def geometry_classes(self) -> np.ndarray:
        """nverts :class:`~bodt.GeometryClass` values (bodt_mesh_get_geometry_classes)."""
        return self._fetch(lib.bodt_mesh_get_geometry_classes, (self.num_vertices,))

    def face_regions(self) -> FaceRegions:
        """Per boundary face, in boundary_faces() order, its region and :class:`~bodt.Shape`.

        Regions are numbered from the mesh's base (bodt_mesh_get_face_regions).
        """
        nfaces = self.num_boundary_faces
        regions = np.empty(nfaces, np.int32)
        shapes = np.empty(nfaces, np.int32)
        self._check(lib.bodt_mesh_get_face_regions(self._handle, pointer(regions), pointer(shapes), nfaces))
        return FaceRegions(self._ints(regions), self._ints(shapes))

    def region_shape(self, region: int) -> ShapeFit:
        """The shape fitted to a surface region, numbered from the base (bodt_mesh_get_region_shape)."""
        fit = sized(ShapeFitStruct)
        self._check(lib.bodt_mesh_get_region_shape(self._handle, int32(region, "region"), byref(fit)))
        return ShapeFit.from_struct(fit)

    def set_reference(self, reference: "Mesh | None") -> None:
        """The undeformed mesh this one was deformed from, or None to clear it (bodt_set_reference_mesh).

        The reference is read, not kept: it may be closed afterwards.
        """
        if reference is not None and not isinstance(reference, Mesh):
            raise TypeError(f"reference must be a bodt.Mesh or None, got {type(reference).__name__}")
        self._check(lib.bodt_set_reference_mesh(self._handle, None if reference is None else reference._handle))

    def set_target_density(self, origin: ArrayLike | None, spacing: ArrayLike | None, values: ArrayLike | None) -> None:
        """A target density on a regular grid, or ``values=None`` to clear it (bodt_set_target_density).

        ``values`` has shape (nx, ny, nz): ``values[i, j, k]`` is the density
        at ``origin + (i, j, k) * spacing``.  (The package hands it to the
        library with x fastest, as bodt.h asks.)  ``origin`` and ``spacing``
        are 3-vectors, ignored when clearing.
        """
        if values is None:
            self._check(lib.bodt_set_target_density(self._handle, None, None, None, None))
            return
        corner = float_array(origin, (3,), "origin")
        step = float_array(spacing, (3,), "spacing")
        grid = float_array(values, (None, None, None), "values")
        dims = np.array([int32(n, "a grid dimension") for n in grid.shape], np.int32)
        x_fastest = np.ascontiguousarray(grid.transpose())
        self._check(
            lib.bodt_set_target_density(self._handle, pointer(corner), pointer(step), pointer(dims), pointer(x_fastest))
        )

    def recovery_error(self) -> RecoveryReport:
        """How far the mesh is from its target density and fitted geometry (bodt_mesh_recovery_error)."""
        error = sized(RecoveryErrorStruct)
        self._check(lib.bodt_mesh_recovery_error(self._handle, byref(error)))
        return RecoveryReport.from_struct(error)

    # ------------------------------------------------------------- meshio

    def to_meshio(self) -> Any:
        """This mesh as a ``meshio.Mesh`` (needs meshio); :func:`bodt.from_meshio` reads it back.

        See :mod:`bodt._meshio` for the cells and data it holds.
        """
        from ._meshio import to_meshio  # meshio is imported only when asked for

        return to_meshio(self)

    # -------------------------------------------------------------- files

    def write(self, path: str | os.PathLike[str], format: Format = Format.AUTO) -> None:  # noqa: A002
        """Write to a file (bodt_mesh_write_format), in the extension's format unless ``format`` says."""
        self._check(lib.bodt_mesh_write_format(self._handle, os.fsencode(path), int32(format, "format")))
