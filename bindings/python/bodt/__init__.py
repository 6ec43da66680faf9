"""bodt: improve tetrahedral meshes with libbodt (B-ODT and related methods).

A thin layer over libbodt's C API (bodt.h, which documents every call, mode
and parameter) with numpy arrays in and out::

    import bodt
    with bodt.Mesh(points, tets) as mesh:          # (n, 3) floats, (m, 4) indices
        mesh.improve(max_steps=20)                 # B-ODT, the default mode
        print(mesh.quality().min_dihedral)
        points, tets = mesh.points, mesh.tets

Failed calls raise :class:`Error` subclasses carrying the library's status
and message.  :func:`from_meshio` and :meth:`Mesh.to_meshio` convert from
and to meshio (which is imported only then); :func:`cffi_cdef` gives
bodt.h's declarations to cffi, for the C API itself::

    ffi = cffi.FFI()
    ffi.cdef(bodt.cffi_cdef())
    lib = ffi.dlopen(bodt.library_path())

Finding libbodt.so: importing the package loads ``libbodt.so.<major>``,
the first found of

1. the file named by the environment variable ``BODT_LIBRARY`` (only it:
   if it cannot be loaded, the import fails);
2. next to the package: the library directory recorded by the build in
   ``bodt/_paths.py`` (relative to the package, so an installed tree can be
   moved), then the package directory itself;
3. the system library path (``ctypes.CDLL("libbodt.so.<major>")``:
   LD_LIBRARY_PATH, the ld.so cache).

A package installed by pip (``pip install ./bindings/python``) has no
``_paths.py``: it finds the library by 1 or 3 (after ``cmake --install``
into /usr/local and ``ldconfig``, the ld.so cache has it).

The library's major version must be the package's, else ImportError.
"""

from ._cdef import cffi_cdef
from ._library import library_path, library_version
from ._meshio import from_meshio
from ._version import __version__
from .enums import (
    OPS_MODE_DEFAULT,
    CreateFlag,
    Format,
    GeometryClass,
    Measure,
    Mode,
    Op,
    Param,
    Shape,
    Status,
    VertexClass,
)
from .errors import (
    BadMeshError,
    CancelledError,
    Error,
    FileError,
    InvalidArgumentError,
    NumericError,
    OutOfMemoryError,
    UnsupportedError,
    WrongStateError,
)
from .mesh import INT_PARAMS, Mesh, dihedral_bin_edges, format_from_path
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

__all__ = [
    "INT_PARAMS",
    "OPS_MODE_DEFAULT",
    "BadMeshError",
    "BoundaryFaces",
    "CancelledError",
    "CreateFlag",
    "Format",
    "Error",
    "FaceRegions",
    "FileError",
    "GeometryClass",
    "GeometryCounts",
    "InvalidArgumentError",
    "Measure",
    "Mesh",
    "Mode",
    "NumericError",
    "Op",
    "OutOfMemoryError",
    "Param",
    "Quality",
    "RecoveryReport",
    "ShapeFit",
    "Shape",
    "Status",
    "StepReport",
    "UnsupportedError",
    "VertexClass",
    "VertexParents",
    "WrongStateError",
    "__version__",
    "cffi_cdef",
    "dihedral_bin_edges",
    "format_from_path",
    "from_meshio",
    "library_path",
    "library_version",
]
