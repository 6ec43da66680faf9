"""ctypes mirrors of the sized structs of bodt.h, field for field.

Each struct starts with ``size``; :func:`sized` makes an instance with it set,
as bodt.h asks.  These are the package's plumbing: the public results are the
dataclasses of :mod:`bodt.results`.
"""

import ctypes
from typing import TypeVar

__all__ = ["DIHEDRAL_BINS", "QualityStruct", "RecoveryErrorStruct", "ShapeFitStruct", "StepReportStruct", "sized"]

#: BODT_DIHEDRAL_BINS
DIHEDRAL_BINS = 23


class QualityStruct(ctypes.Structure):
    """struct bodt_quality."""

    _fields_ = [
        ("size", ctypes.c_size_t),
        ("num_vertices", ctypes.c_int32),
        ("num_tets", ctypes.c_int32),
        ("num_boundary_faces", ctypes.c_int32),
        ("num_unused_vertices", ctypes.c_int32),
        ("num_inverted", ctypes.c_int32),
        ("reserved0", ctypes.c_int32),
        ("min_dihedral", ctypes.c_double),
        ("max_dihedral", ctypes.c_double),
        ("mean_dihedral", ctypes.c_double),
        ("min_stretch", ctypes.c_double),
        ("mean_stretch", ctypes.c_double),
        ("volume", ctypes.c_double),
        ("dihedral_histogram", ctypes.c_int64 * DIHEDRAL_BINS),
    ]


class StepReportStruct(ctypes.Structure):
    """struct bodt_step_report."""

    _fields_ = [
        ("size", ctypes.c_size_t),
        ("step", ctypes.c_int32),
        ("vertices_moved", ctypes.c_int32),
        ("moves_rejected", ctypes.c_int32),
        ("moves_shortened", ctypes.c_int32),
        ("not_positive_definite", ctypes.c_int32),
        ("reserved0", ctypes.c_int32),
        ("max_move", ctypes.c_double),
        ("min_dihedral", ctypes.c_double),
        ("max_dihedral", ctypes.c_double),
        ("min_stretch", ctypes.c_double),
        ("flips", ctypes.c_int32),
        ("vertices_inserted", ctypes.c_int32),
        ("edges_collapsed", ctypes.c_int32),
        ("reserved1", ctypes.c_int32),
    ]


class ShapeFitStruct(ctypes.Structure):
    """struct bodt_shape_fit."""

    _fields_ = [
        ("size", ctypes.c_size_t),
        ("shape", ctypes.c_int32),
        ("reserved0", ctypes.c_int32),
        ("point", ctypes.c_double * 3),
        ("axis", ctypes.c_double * 3),
        ("radius", ctypes.c_double),
        ("max_error", ctypes.c_double),
        ("acceptable_error", ctypes.c_double),
    ]


class RecoveryErrorStruct(ctypes.Structure):
    """struct bodt_recovery_error."""

    _fields_ = [
        ("size", ctypes.c_size_t),
        ("density_mean", ctypes.c_double),
        ("density_max", ctypes.c_double),
        ("density_edges", ctypes.c_int64),
        ("geometric_mean", ctypes.c_double),
        ("geometric_max", ctypes.c_double),
        ("geometric_edges", ctypes.c_int64),
    ]


S = TypeVar("S", bound=ctypes.Structure)


def sized(struct_type: type[S]) -> S:
    """A zeroed instance of ``struct_type`` with its ``size`` field set."""
    return struct_type(size=ctypes.sizeof(struct_type))
