"""What the Mesh methods return: frozen dataclasses and named tuples.

The fields are those of the C structs in bodt.h (without ``size`` and the
reserved ones), which documents what each one means.  Arrays are read-only
numpy arrays.
"""

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .enums import Shape
from .structs import QualityStruct, RecoveryErrorStruct, ShapeFitStruct, StepReportStruct

__all__ = [
    "BoundaryFaces",
    "FaceRegions",
    "GeometryCounts",
    "Quality",
    "RecoveryReport",
    "ShapeFit",
    "StepReport",
    "VertexParents",
]


def _frozen(values: object, dtype: type) -> np.ndarray:
    array = np.array(values, dtype=dtype)
    array.flags.writeable = False
    return array


@dataclass(frozen=True, eq=False)
class Quality:
    """struct bodt_quality, from Mesh.quality().

    ``dihedral_histogram[i]`` counts the dihedral angles in
    [``dihedral_bin_edges[i]``, ``dihedral_bin_edges[i + 1]``) degrees.
    """

    num_vertices: int
    num_tets: int
    num_boundary_faces: int
    num_unused_vertices: int
    num_inverted: int
    min_dihedral: float
    max_dihedral: float
    mean_dihedral: float
    min_stretch: float
    mean_stretch: float
    volume: float
    dihedral_histogram: np.ndarray
    dihedral_bin_edges: np.ndarray

    @classmethod
    def from_struct(cls, q: QualityStruct, bin_edges: np.ndarray) -> "Quality":
        return cls(
            num_vertices=q.num_vertices,
            num_tets=q.num_tets,
            num_boundary_faces=q.num_boundary_faces,
            num_unused_vertices=q.num_unused_vertices,
            num_inverted=q.num_inverted,
            min_dihedral=q.min_dihedral,
            max_dihedral=q.max_dihedral,
            mean_dihedral=q.mean_dihedral,
            min_stretch=q.min_stretch,
            mean_stretch=q.mean_stretch,
            volume=q.volume,
            dihedral_histogram=_frozen(q.dihedral_histogram, np.int64),
            dihedral_bin_edges=bin_edges,
        )


@dataclass(frozen=True)
class StepReport:
    """struct bodt_step_report: what one improvement step did."""

    step: int
    vertices_moved: int
    moves_rejected: int
    moves_shortened: int
    not_positive_definite: int
    max_move: float
    min_dihedral: float
    max_dihedral: float
    min_stretch: float
    flips: int
    vertices_inserted: int
    edges_collapsed: int

    @classmethod
    def from_struct(cls, r: StepReportStruct) -> "StepReport":
        return cls(
            step=r.step,
            vertices_moved=r.vertices_moved,
            moves_rejected=r.moves_rejected,
            moves_shortened=r.moves_shortened,
            not_positive_definite=r.not_positive_definite,
            max_move=r.max_move,
            min_dihedral=r.min_dihedral,
            max_dihedral=r.max_dihedral,
            min_stretch=r.min_stretch,
            flips=r.flips,
            vertices_inserted=r.vertices_inserted,
            edges_collapsed=r.edges_collapsed,
        )


@dataclass(frozen=True, eq=False)
class ShapeFit:
    """struct bodt_shape_fit: the shape fitted to a surface region."""

    shape: Shape
    point: np.ndarray
    axis: np.ndarray
    radius: float
    max_error: float
    acceptable_error: float

    @classmethod
    def from_struct(cls, f: ShapeFitStruct) -> "ShapeFit":
        return cls(
            shape=Shape(f.shape),
            point=_frozen(f.point, np.float64),
            axis=_frozen(f.axis, np.float64),
            radius=f.radius,
            max_error=f.max_error,
            acceptable_error=f.acceptable_error,
        )


@dataclass(frozen=True)
class RecoveryReport:
    """struct bodt_recovery_error: how far the mesh is from its target density and fitted geometry."""

    density_mean: float
    density_max: float
    density_edges: int
    geometric_mean: float
    geometric_max: float
    geometric_edges: int

    @classmethod
    def from_struct(cls, e: RecoveryErrorStruct) -> "RecoveryReport":
        return cls(
            density_mean=e.density_mean,
            density_max=e.density_max,
            density_edges=e.density_edges,
            geometric_mean=e.geometric_mean,
            geometric_max=e.geometric_max,
            geometric_edges=e.geometric_edges,
        )


class BoundaryFaces(NamedTuple):
    """Mesh.boundary_faces(): (nfaces, 3) vertex indices and nfaces markers."""

    triangles: np.ndarray
    markers: np.ndarray


class VertexParents(NamedTuple):
    """Mesh.vertex_parents(): vertex v's parents are parents[offsets[v]:offsets[v + 1]], with weights."""

    offsets: np.ndarray
    parents: np.ndarray
    weights: np.ndarray


class GeometryCounts(NamedTuple):
    """Mesh.geometry_counts(): surface regions and sharp-edge chains."""

    regions: int
    chains: int


class FaceRegions(NamedTuple):
    """Mesh.face_regions(): per boundary face its surface region and that region's Shape."""

    regions: np.ndarray
    shapes: np.ndarray
