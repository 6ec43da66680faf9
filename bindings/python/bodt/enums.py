"""The enums of bodt.h as Python enums, with the C values.

Each member is named like its C constant without the prefix
(``BODT_MODE_BODT`` is ``Mode.BODT``, ``BODT_ERR_BAD_MESH`` is
``Status.BAD_MESH``).  What each one means is documented in bodt.h.
"""

from enum import IntEnum, IntFlag

__all__ = [
    "OPS_MODE_DEFAULT",
    "CreateFlag",
    "Format",
    "GeometryClass",
    "Measure",
    "Mode",
    "Op",
    "Param",
    "Shape",
    "Status",
    "VertexClass",
]


class Status(IntEnum):
    """enum bodt_status: what a C call returned."""

    OK = 0
    INVALID_ARGUMENT = -1
    BAD_MESH = -2
    OUT_OF_MEMORY = -3
    WRONG_STATE = -4
    NUMERIC = -5
    IO = -6
    CANCELLED = -7
    UNSUPPORTED = -8


class CreateFlag(IntFlag):
    """enum bodt_create_flag: bits for bodt_mesh_create_ex and bodt_mesh_read_ex."""

    DEFAULT = 0
    ACCEPT_INVERTED = 1
    ONE_BASED = 2
    KEEP_ORDER = 4
    FILE_BASE = 8


class VertexClass(IntEnum):
    """enum bodt_vertex_class: how the current mode treats a vertex."""

    INTERIOR = 0
    SURFACE = 1
    FEATURE_LINE = 2
    CORNER = 3
    FIXED = 4
    UNUSED = 5


class Measure(IntEnum):
    """enum bodt_measure: a per-tet quality measure."""

    MIN_DIHEDRAL = 1
    MAX_DIHEDRAL = 2
    STRETCH = 3
    VOLUME = 4


class Mode(IntEnum):
    """enum bodt_mode: the improvement method a step uses.

    :meth:`from_name` takes the names of the command's ``--mode``.
    """

    LAPLACE = 1
    ODT = 2
    BODT_BASIC = 3
    BODT = 4
    OPT_WEIGHTED = 5
    PHASED_ODT = 6
    NODT = 7

    @classmethod
    def from_name(cls, name: str) -> "Mode":
        """The mode that ``bodt improve --mode NAME`` names: "bodt", "bodt-basic", "odt", "laplace", ..."""
        try:
            return _MODE_NAMES[name]
        except (KeyError, TypeError):
            raise ValueError(f"unknown mode {name!r}: the modes are {', '.join(_MODE_NAMES)}") from None


# The command's --mode names (src/cli/args.cpp), in its order.
_MODE_NAMES = {
    "bodt": Mode.BODT,
    "bodt-basic": Mode.BODT_BASIC,
    "odt": Mode.ODT,
    "laplace": Mode.LAPLACE,
    "opt-weighted": Mode.OPT_WEIGHTED,
    "phased": Mode.PHASED_ODT,
    "nodt": Mode.NODT,
}


class Param(IntEnum):
    """enum bodt_param: parameter keys (each one int or double, see bodt.h)."""

    TOLERANCE = 1
    BACKTRACK_STEPS = 2
    MIN_STRETCH = 3
    NEVER_WORSE = 4
    FEATURE_ANGLE = 5
    EDGE_RATIO = 6
    CORNER_RATIO = 7
    OPS = 8
    KEEP_SURFACE = 9
    BAD_ANGLE = 10
    DELAUNAY_FLIPS = 11
    WEIGHT_C = 12
    POOR_QUALITY = 13
    QN_EPSILON = 14
    QN_MAX_ITERATIONS = 15
    QN_INITIAL_STEP = 16
    QN_INTERVAL_GROWTH = 17
    ODT_STEP = 18
    DENSITY_SPLIT = 19
    DENSITY_COLLAPSE = 20
    FIT_TOLERANCE = 21
    THREADS = 22
    ASCENT_ANGLE = 23


class Op(IntFlag):
    """enum bodt_op: the operations a step may do (the bits of Param.OPS)."""

    SMOOTH = 1
    FLIP = 2
    INSERT = 4
    COLLAPSE = 8


#: BODT_OPS_MODE_DEFAULT: Param.OPS value meaning "the mode's default operations".
OPS_MODE_DEFAULT = -1


class GeometryClass(IntEnum):
    """enum bodt_geometry_class: what paper 002's geometry makes of a vertex."""

    INTERIOR = 0
    SURFACE = 1
    SHARP_EDGE = 2
    CORNER = 3


class Shape(IntEnum):
    """enum bodt_shape: the shape fitted to a surface region or an edge chain."""

    NONE = 0
    PLANE = 1
    CYLINDER = 2
    LINE = 3
    ARC = 4
    CIRCLE = 5


class Format(IntEnum):
    """enum bodt_format: mesh file formats (AUTO: by the extension)."""

    AUTO = 0
    MEDIT = 1
    MEDIT_BINARY = 2
    TETGEN = 3
    GMSH = 4
    GMSH_BINARY = 5
    GMSH22 = 6
    GMSH22_BINARY = 7
    VTU = 8
    ABAQUS = 9
    VTK = 10
