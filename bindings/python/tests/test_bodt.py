"""The bodt package's Mesh: arrays in and out, quality, params, improve, errors, files, lifetime.

Expected values are closed forms or computed here with numpy (meshes.py),
never taken from the library.
"""

import contextlib
import copy
import gc
import math
import os
import pickle
import tempfile
import unittest

import numpy as np

import bodt
import meshes
from bodt._library import lib

# bodt.h: the edges of the dihedral-angle histogram's bins, in degrees.
BIN_EDGES = [0, 5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150, 160, 165, 170, 175, 180]


class ErrorAssertions(unittest.TestCase):
    @contextlib.contextmanager
    def assertError(self, error_type: type[bodt.Error], status: bodt.Status, *message_parts: str):
        """The block raises exactly ``error_type``, with ``status`` and a message holding each part."""
        with self.assertRaises(error_type) as context:
            yield context
        error = context.exception
        self.assertIs(type(error), error_type)
        self.assertIs(error.status, status)
        for part in message_parts:
            self.assertIn(part, error.message)
        self.assertEqual(str(error), f"{lib.bodt_status_string(status).decode()}: {error.message}")


class TestQuality(unittest.TestCase):
    def test_regular_tet(self):
        points, tets = meshes.regular_tet()
        edge = 2.0 * math.sqrt(2.0)
        dihedral = math.degrees(math.acos(1.0 / 3.0))
        with bodt.Mesh(points, tets) as mesh:
            q = mesh.quality()
            self.assertEqual((q.num_vertices, q.num_tets, q.num_boundary_faces), (4, 1, 4))
            self.assertEqual((q.num_unused_vertices, q.num_inverted), (0, 0))
            for angle in (q.min_dihedral, q.max_dihedral, q.mean_dihedral):
                self.assertAlmostEqual(angle, dihedral, delta=1e-10)
            self.assertAlmostEqual(q.min_stretch, 1.0, delta=1e-12)
            self.assertAlmostEqual(q.mean_stretch, 1.0, delta=1e-12)
            self.assertAlmostEqual(q.volume, edge**3 / (6.0 * math.sqrt(2.0)), delta=1e-12)
            expected = np.zeros(len(BIN_EDGES) - 1, np.int64)
            expected[np.searchsorted(BIN_EDGES, dihedral, side="right") - 1] = 6
            np.testing.assert_array_equal(q.dihedral_histogram, expected)
            np.testing.assert_array_equal(q.dihedral_bin_edges, BIN_EDGES)
            np.testing.assert_array_equal(bodt.dihedral_bin_edges(), BIN_EDGES)
            self.assertFalse(q.dihedral_histogram.flags.writeable)
            with self.assertRaises(AttributeError):
                q.volume = 0.0  # frozen

            by_measure = {
                bodt.Measure.MIN_DIHEDRAL: dihedral,
                bodt.Measure.MAX_DIHEDRAL: dihedral,
                bodt.Measure.STRETCH: 1.0,
                bodt.Measure.VOLUME: edge**3 / (6.0 * math.sqrt(2.0)),
            }
            for measure, value in by_measure.items():
                values = mesh.tet_quality(measure)
                self.assertEqual(values.shape, (1,))
                self.assertAlmostEqual(values[0], value, delta=1e-10, msg=measure.name)

    def test_box_against_numpy(self):
        points, tets = meshes.box(3, jitter=0.3)
        with bodt.Mesh(points, tets) as mesh:
            angles = meshes.dihedral_angles(points, tets)
            volumes = meshes.signed_volumes(points, tets)
            q = mesh.quality()
            self.assertAlmostEqual(q.min_dihedral, angles.min(), delta=1e-9)
            self.assertAlmostEqual(q.max_dihedral, angles.max(), delta=1e-9)
            self.assertAlmostEqual(q.mean_dihedral, angles.mean(), delta=1e-9)
            self.assertAlmostEqual(q.volume, 1.0, delta=1e-12)
            self.assertEqual(q.num_boundary_faces, 6 * 3 * 3 * 2)
            np.testing.assert_allclose(mesh.tet_quality(bodt.Measure.VOLUME), volumes, rtol=1e-12)
            np.testing.assert_allclose(mesh.tet_quality(bodt.Measure.MIN_DIHEDRAL), angles.min(axis=1), atol=1e-9)
            np.testing.assert_allclose(mesh.tet_quality(bodt.Measure.MAX_DIHEDRAL), angles.max(axis=1), atol=1e-9)
            self.assertEqual(q.dihedral_histogram.sum(), angles.size)
            # angles within rounding of a bin edge (the Kuhn tets' 60 and 90 degrees) may fall on either side
            counts, _ = np.histogram(angles, bins=BIN_EDGES)
            near_edge = np.count_nonzero(np.min(np.abs(angles[..., None] - BIN_EDGES), axis=-1) < 1e-9)
            self.assertLessEqual(np.abs(q.dihedral_histogram - counts).sum(), 2 * near_edge)


class TestConstruction(ErrorAssertions):
    def test_zero_and_one_based(self):
        points, tets = meshes.box(2)
        with bodt.Mesh(points, tets) as zero, bodt.Mesh(points, tets + 1, base=1) as one:
            self.assertEqual((zero.base, one.base), (0, 1))
            np.testing.assert_array_equal(zero.tets, tets)
            np.testing.assert_array_equal(one.tets, tets + 1)
            np.testing.assert_array_equal(one.points, points)
            faces0, faces1 = zero.boundary_faces(), one.boundary_faces()
            np.testing.assert_array_equal(faces1.triangles, faces0.triangles + 1)
            np.testing.assert_array_equal(one.tet_origins, np.arange(1, len(tets) + 1))
            one.set_fixed_vertices([1, 27])
            np.testing.assert_array_equal(one.fixed_vertices, [1, 27])
            with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT):
                one.set_fixed_vertices([0])
            one.set_corners([3])
            np.testing.assert_array_equal(one.corners, [3])
            with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT):
                one.set_corners([0])
            one.set_feature_edges([[2, 1]], [4])
            np.testing.assert_array_equal(one.feature_edges, [[1, 2]])
            np.testing.assert_array_equal(one.feature_edge_refs, [4])
            self.assertAlmostEqual(one.quality().volume, zero.quality().volume, delta=1e-15)

    def test_dtypes_and_memory_orders(self):
        points, tets = meshes.box(2)
        variants = [
            (points, tets.astype(np.int64)),
            (points, tets.astype(np.int32)),
            (points, tets.astype(np.uint16)),
            (np.asfortranarray(points), np.asfortranarray(tets)),
            (points.tolist(), tets.tolist()),
            (points[::-1][::-1], tets[:, ::-1][:, ::-1]),  # strided views
        ]
        for xyz, ids in variants:
            with bodt.Mesh(xyz, ids) as mesh:
                np.testing.assert_array_equal(mesh.points, points)
                np.testing.assert_array_equal(mesh.tets, tets)
                self.assertEqual(mesh.tets.dtype, np.int64)
                self.assertEqual(mesh.points.dtype, np.float64)

    def test_int_dtype(self):
        """Every integer array out is int64 by default, int32 on request (the earlier default)."""
        points, tets = meshes.box(2, jitter=0.2)
        getters = {
            "tets": lambda m: m.tets,
            "regions": lambda m: m.regions,
            "triangles": lambda m: m.boundary_faces().triangles,
            "markers": lambda m: m.boundary_faces().markers,
            "fixed_vertices": lambda m: m.fixed_vertices,
            "feature_edges": lambda m: m.feature_edges,
            "feature_edge_refs": lambda m: m.feature_edge_refs,
            "corners": lambda m: m.corners,
            "vertex_refs": lambda m: m.vertex_refs,
            "vertex_classes": lambda m: m.vertex_classes,
            "parents": lambda m: m.vertex_parents().parents,
            "tet_origins": lambda m: m.tet_origins,
            "geometry_classes": lambda m: m.geometry_classes,
            "face_regions": lambda m: m.face_regions().regions,
            "face_shapes": lambda m: m.face_regions().shapes,
        }
        with bodt.Mesh(points, tets) as wide, bodt.Mesh(points, tets, int_dtype=np.int32) as narrow:
            for mesh in (wide, narrow):
                mesh.set_fixed_vertices([13])
                mesh.set_feature_edges([[0, 1]], [5])
                mesh.set_corners([0])
                mesh.set_boundary_faces(mesh.boundary_faces().triangles[:2], [3, 4])
            self.assertEqual(wide.int_dtype, np.int64)
            self.assertEqual(narrow.int_dtype, np.int32)
            for name, get in getters.items():
                self.assertEqual(get(wide).dtype, np.int64, name)
                self.assertEqual(get(narrow).dtype, np.int32, name)
                np.testing.assert_array_equal(get(wide), get(narrow), name)
            self.assertEqual(wide.vertex_parents().offsets.dtype, np.int64)  # int64_t in the C API
            wide.int_dtype = "int32"
            self.assertEqual(wide.tets.dtype, np.int32)
            with self.assertRaisesRegex(ValueError, "int_dtype must be numpy.int64 or numpy.int32, got int16"):
                wide.int_dtype = np.int16
        directory = tempfile.TemporaryDirectory()
        self.addCleanup(directory.cleanup)
        path = os.path.join(directory.name, "box.mesh")
        with bodt.Mesh(points, tets) as mesh:
            mesh.write(path)
        with bodt.Mesh.read(path) as wide, bodt.Mesh.read(path, int_dtype=np.int32) as narrow:
            self.assertEqual((wide.tets.dtype, narrow.tets.dtype), (np.int64, np.int32))
        with self.assertRaisesRegex(ValueError, "int_dtype must be numpy.int64 or numpy.int32, got float64"):
            bodt.Mesh(points, tets, int_dtype=float)
        # refused before the file is read (not a FileError), so that no handle is made to leak
        with self.assertRaisesRegex(ValueError, "int_dtype must be numpy.int64 or numpy.int32, got float64"):
            bodt.Mesh.read(os.path.join(directory.name, "missing.mesh"), int_dtype=float)

    def test_shape_errors_before_the_library(self):
        points, tets = meshes.box(1)
        for bad_points in (points[:, :2], points.reshape(-1), points[None], np.zeros((4, 4))):
            with self.assertRaises(ValueError) as context:
                bodt.Mesh(bad_points, tets)
            self.assertIs(type(context.exception), ValueError)
            self.assertIn("points must have shape (n, 3)", str(context.exception))
        for bad_tets in (tets[:, :3], tets.reshape(-1), tets[None]):
            with self.assertRaises(ValueError) as context:
                bodt.Mesh(points, bad_tets)
            self.assertIs(type(context.exception), ValueError)
            self.assertIn("tets must have shape (n, 4)", str(context.exception))
        with self.assertRaisesRegex(TypeError, "tets must hold integers"):
            bodt.Mesh(points, tets.astype(np.float64))
        big = tets.astype(np.int64)
        big[3, 2] = 2**32  # would wrap to 0 in int32
        big[5, 1] = -(2**31) - 1
        with self.assertRaises(ValueError) as context:
            bodt.Mesh(points, big)
        self.assertEqual(
            str(context.exception),
            "tets holds 4294967296 at [3, 2], outside the int32 range of libbodt [-2147483648, 2147483647] "
            "(2 such values)",
        )
        for dtype in (np.uint32, np.uint64):
            wrapped = tets.astype(dtype)
            wrapped[0, 0] = 2**31
            with self.assertRaisesRegex(ValueError, "tets holds 2147483648 at \\[0, 0\\], outside the int32 range"):
                bodt.Mesh(points, wrapped)
        with self.assertRaisesRegex(ValueError, "base = 4294967296 is outside the int32 range"):
            bodt.Mesh(points, tets, base=2**32)

    def assertCreateRefused(self, error_type, status, points, tets, base=0, *message_parts):
        with self.assertError(error_type, status, *message_parts) as context:
            bodt.Mesh(points, tets, base=base)
        # the message is the C library's own, for the failed create on this thread
        self.assertEqual(context.exception.message, lib.bodt_mesh_last_error(None).decode())

    def test_bad_input(self):
        points, tets = meshes.box(2)
        nan_points = points.copy()
        nan_points[5, 1] = np.nan
        self.assertCreateRefused(bodt.BadMeshError, bodt.Status.BAD_MESH, nan_points, tets, 0, "vertex 5", "nan")
        out_of_range = tets.copy()
        out_of_range[3, 2] = 27
        self.assertCreateRefused(
            bodt.BadMeshError, bodt.Status.BAD_MESH, points, out_of_range, 0,
            "tet 3 uses vertex 27, but the mesh has 27 vertices",
        )
        self.assertCreateRefused(
            bodt.BadMeshError, bodt.Status.BAD_MESH, points, out_of_range + 1, 1, "tet 4 uses vertex 28"
        )
        repeated = tets.copy()
        repeated[7, 3] = repeated[7, 1]
        self.assertCreateRefused(bodt.BadMeshError, bodt.Status.BAD_MESH, points, repeated, 0, "tet 7 uses vertex")
        self.assertCreateRefused(bodt.BadMeshError, bodt.Status.BAD_MESH, points, tets, 1, "numbered from 1")
        self.assertCreateRefused(
            bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, points, tets, 2, "index_base must be 0 or 1"
        )
        self.assertCreateRefused(
            bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, points, np.zeros((0, 4), int), 0, "ntets"
        )
        self.assertCreateRefused(
            bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, np.zeros((0, 3)), tets, 0, "nverts"
        )

    def test_inverted_tets(self):
        points, tets = meshes.box(2)
        flipped = tets.copy()
        flipped[0] = flipped[0, [0, 1, 3, 2]]
        self.assertCreateRefused(bodt.BadMeshError, bodt.Status.BAD_MESH, points, flipped, 0, "inverted")
        with bodt.Mesh(points, flipped, accept_inverted=True) as mesh:
            self.assertEqual(mesh.quality().num_inverted, 1)
        # all tets negative: the caller's convention, kept on output
        with bodt.Mesh(points, tets[:, [0, 1, 3, 2]]) as mesh:
            self.assertEqual(mesh.quality().num_inverted, 0)
            np.testing.assert_array_equal(mesh.tets, tets[:, [0, 1, 3, 2]])


class TestMeshData(ErrorAssertions):
    def setUp(self):
        self.n = 2
        self.points, self.tets = meshes.box(self.n)
        self.mesh = bodt.Mesh(self.points, self.tets)
        self.addCleanup(self.mesh.close)

    def test_counts_points_tets(self):
        self.assertEqual(self.mesh.num_vertices, 27)
        self.assertEqual(self.mesh.num_tets, 48)
        self.assertEqual(self.mesh.num_boundary_faces, 48)
        np.testing.assert_array_equal(self.mesh.points, self.points)
        np.testing.assert_array_equal(self.mesh.tets, self.tets)
        self.assertEqual(repr(self.mesh), "<bodt.Mesh 27 vertices, 48 tets, base 0>")

    def test_regions(self):
        np.testing.assert_array_equal(self.mesh.regions, np.zeros(48))
        ids = np.arange(48) % 3
        self.mesh.set_regions(ids)
        np.testing.assert_array_equal(self.mesh.regions, ids)
        with self.assertRaisesRegex(ValueError, r"region_ids must have shape \(48,\)"):
            self.mesh.set_regions(ids[:-1])

    def test_boundary_faces(self):
        faces = self.mesh.boundary_faces()
        self.assertEqual(faces.triangles.shape, (48, 3))
        np.testing.assert_array_equal(faces.markers, np.zeros(48))
        # on the cube's faces, their normals pointing out of the cube
        p = self.points[faces.triangles]
        normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
        outward = p.mean(axis=1) - 0.5
        self.assertTrue(np.all(np.einsum("ij,ij->i", normals, outward) > 0))
        self.assertTrue(np.all(np.any(np.all((p == 0) | (p == 1), axis=1), axis=1)))

        chosen = faces.triangles[[3, 10, 20]]
        self.mesh.set_boundary_faces(chosen, [7, 8, 9])
        markers = self.mesh.boundary_faces().markers
        np.testing.assert_array_equal(markers[[3, 10, 20]], [7, 8, 9])
        self.assertEqual(np.count_nonzero(markers), 3)
        self.mesh.set_boundary_faces(chosen[:, ::-1])  # markers None: 1
        markers = self.mesh.boundary_faces().markers
        np.testing.assert_array_equal(np.flatnonzero(markers), [3, 10, 20])
        np.testing.assert_array_equal(markers[[3, 10, 20]], [1, 1, 1])
        self.mesh.set_boundary_faces([])
        self.assertEqual(np.count_nonzero(self.mesh.boundary_faces().markers), 0)
        with self.assertRaisesRegex(ValueError, r"markers must have shape \(3,\)"):
            self.mesh.set_boundary_faces(chosen, [1, 2])
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, "face"):
            self.mesh.set_boundary_faces([[0, 1, 26]])

    def test_fixed_vertices(self):
        self.assertEqual(self.mesh.fixed_vertices.shape, (0,))
        self.mesh.set_fixed_vertices(np.array([13, 2, 0], np.int64))
        np.testing.assert_array_equal(self.mesh.fixed_vertices, [0, 2, 13])
        self.mesh.set_fixed_vertices([])
        self.assertEqual(self.mesh.fixed_vertices.shape, (0,))
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, "27"):
            self.mesh.set_fixed_vertices([27])

    def test_feature_edges(self):
        self.assertEqual(self.mesh.feature_edges.shape, (0, 2))
        self.assertEqual(self.mesh.feature_edge_refs.shape, (0,))
        edges = np.array([[1, 0], [2, 1], [9, 0]])  # along the cube's edges x and z from the origin
        self.mesh.set_feature_edges(edges)
        got = self.mesh.feature_edges
        self.assertEqual(got.shape, (3, 2))
        self.assertEqual({tuple(sorted(e)) for e in got.tolist()}, {tuple(sorted(e)) for e in edges.tolist()})
        np.testing.assert_array_equal(self.mesh.feature_edge_refs, [0, 0, 0])  # refs None: 0
        self.mesh.set_feature_edges(edges, np.array([7, 8, 9], np.int64))
        ref_of_edge = dict(zip(map(tuple, self.mesh.feature_edges.tolist()), self.mesh.feature_edge_refs.tolist()))
        self.assertEqual(ref_of_edge, {(0, 1): 7, (1, 2): 8, (0, 9): 9})
        self.mesh.set_feature_edges([])
        self.assertEqual(self.mesh.feature_edges.shape, (0, 2))
        with self.assertRaisesRegex(ValueError, r"refs must have shape \(3,\)"):
            self.mesh.set_feature_edges(edges, [1, 2])
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT):
            self.mesh.set_feature_edges([[0, 26]])  # the cube's diagonal: no surface edge

    def test_corners(self):
        self.assertEqual(self.mesh.corners.shape, (0,))
        middles = [5, 1]  # of two of the cube's edges: feature-line vertices, unless the caller's corners
        self.mesh.set_corners(np.array(middles, np.int64))
        np.testing.assert_array_equal(self.mesh.corners, [1, 5])
        for mode in (bodt.Mode.BODT, bodt.Mode.ODT):
            self.mesh.mode = mode
            np.testing.assert_array_equal(self.mesh.vertex_classes[middles], bodt.VertexClass.CORNER, mode.name)
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, "27"):
            self.mesh.set_corners([4, 27])
        np.testing.assert_array_equal(self.mesh.corners, [1, 5])  # a refused list changes nothing
        self.mesh.set_corners([])
        self.assertEqual(self.mesh.corners.shape, (0,))

    def test_vertex_refs(self):
        np.testing.assert_array_equal(self.mesh.vertex_refs, np.zeros(27))
        refs = np.arange(27) % 4 + 10
        self.mesh.set_vertex_refs(refs)
        np.testing.assert_array_equal(self.mesh.vertex_refs, refs)
        self.assertEqual(self.mesh.vertex_refs.dtype, np.int64)
        with self.assertRaisesRegex(ValueError, r"refs must have shape \(27,\)"):
            self.mesh.set_vertex_refs(refs[:-1])

    def test_refs_carried_over(self):
        # every input vertex ref 7; feature edges on the cube's edges, each with its cube edge's number
        self.mesh.set_vertex_refs(np.full(27, 7))
        edges, numbers = meshes.cube_edges(self.n)
        self.mesh.set_feature_edges(edges, numbers)
        # a target density twice the mesh's: edges are split, also feature edges
        self.mesh.set_target_density([0, 0, 0], [1, 1, 1], np.full((2, 2, 2), 2.0 * self.n))
        self.mesh.improve(max_steps=3, mode=bodt.Mode.PHASED_ODT)
        points, got = self.mesh.points, self.mesh.feature_edges
        self.assertGreater(len(got), len(edges))
        expected = [meshes.cube_edge_number(points[a], points[b]) for a, b in got]
        np.testing.assert_array_equal(self.mesh.feature_edge_refs, expected)  # both halves keep the ref
        refs = self.mesh.vertex_refs
        self.assertEqual(len(refs), self.mesh.num_vertices)
        np.testing.assert_array_equal(refs[:27], 7)
        self.assertTrue(np.all(refs[got] == 7), "made on the surface from surface vertices of ref 7")
        self.assertTrue(np.all((refs == 7) | (refs == 0)), "a made vertex: its parents' shared ref, or 0")

    def test_vertex_classes(self):
        on_faces = meshes.grid_boundary_axes(self.n)
        self.mesh.mode = bodt.Mode.BODT
        expected = np.array([bodt.VertexClass.INTERIOR, bodt.VertexClass.SURFACE, bodt.VertexClass.FEATURE_LINE,
                             bodt.VertexClass.CORNER])[on_faces]
        np.testing.assert_array_equal(self.mesh.vertex_classes, expected)
        self.mesh.mode = bodt.Mode.BODT_BASIC
        self.mesh.set_fixed_vertices([4])
        expected = np.where(on_faces > 0, bodt.VertexClass.SURFACE, bodt.VertexClass.INTERIOR)
        expected[4] = bodt.VertexClass.FIXED
        np.testing.assert_array_equal(self.mesh.vertex_classes, expected)

    def test_history_of_the_input(self):
        parents = self.mesh.vertex_parents()
        np.testing.assert_array_equal(parents.offsets, np.arange(28))
        np.testing.assert_array_equal(parents.parents, np.arange(27))
        np.testing.assert_array_equal(parents.weights, np.ones(27))
        np.testing.assert_array_equal(self.mesh.tet_origins, np.arange(48))


class TestParams(ErrorAssertions):
    def setUp(self):
        self.mesh = bodt.Mesh(*meshes.box(2))
        self.addCleanup(self.mesh.close)

    def test_every_param_by_its_type(self):
        for key in bodt.Param:
            value = self.mesh.get_param(key)
            self.assertIs(type(value), int if key in bodt.INT_PARAMS else float, key.name)
            self.mesh.set_param(key, value)
            self.assertEqual(self.mesh.get_param(key), value)

    def test_values_set(self):
        self.mesh.set_param(bodt.Param.TOLERANCE, 1e-9)
        self.assertEqual(self.mesh.get_param(bodt.Param.TOLERANCE), 1e-9)
        self.mesh.set_param(bodt.Param.FEATURE_ANGLE, 45)  # an int for a double key
        self.assertEqual(self.mesh.get_param(bodt.Param.FEATURE_ANGLE), 45.0)
        self.assertEqual(self.mesh.get_param(bodt.Param.OPS), bodt.OPS_MODE_DEFAULT)
        self.mesh.set_param(bodt.Param.OPS, bodt.Op.SMOOTH | bodt.Op.FLIP)
        self.assertEqual(self.mesh.get_param(bodt.Param.OPS), 3)
        self.mesh.set_param(int(bodt.Param.BACKTRACK_STEPS), np.int64(7))
        self.assertEqual(self.mesh.get_param(bodt.Param.BACKTRACK_STEPS), 7)

    def test_refused_values(self):
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT) as context:
            self.mesh.set_param(bodt.Param.TOLERANCE, 2.0)
        self.assertEqual(context.exception.message, "BODT_PARAM_TOLERANCE must be in [0, 1], got 2")
        self.assertEqual(self.mesh.get_param(bodt.Param.TOLERANCE), 1e-6)  # kept
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT) as context:
            self.mesh.set_param(bodt.Param.QN_MAX_ITERATIONS, 0)
        self.assertEqual(context.exception.message, "BODT_PARAM_QN_MAX_ITERATIONS must be in [1, 1000], got 0")
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, "BODT_PARAM_ODT_STEP"):
            self.mesh.set_param(bodt.Param.ODT_STEP, math.nan)
        with self.assertRaisesRegex(TypeError, "Param.BACKTRACK_STEPS must be an integer, got 2.5"):
            self.mesh.set_param(bodt.Param.BACKTRACK_STEPS, 2.5)
        with self.assertRaisesRegex(ValueError, "outside the int32 range"):
            self.mesh.set_param(bodt.Param.BACKTRACK_STEPS, 2**32 + 4)
        with self.assertRaisesRegex(ValueError, "99 is not a valid Param"):
            self.mesh.set_param(99, 1)

    def test_mode(self):
        self.assertIs(self.mesh.mode, bodt.Mode.BODT)
        self.mesh.mode = bodt.Mode.ODT
        self.assertIs(self.mesh.mode, bodt.Mode.ODT)
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT) as context:
            self.mesh.mode = 8
        self.assertEqual(context.exception.message, "unknown mode 8")
        self.assertIs(self.mesh.mode, bodt.Mode.ODT)

    def test_mode_by_the_command_name(self):
        names = {
            "bodt": bodt.Mode.BODT, "bodt-basic": bodt.Mode.BODT_BASIC, "odt": bodt.Mode.ODT,
            "laplace": bodt.Mode.LAPLACE, "opt-weighted": bodt.Mode.OPT_WEIGHTED, "phased": bodt.Mode.PHASED_ODT,
            "nodt": bodt.Mode.NODT,
        }
        for name, mode in names.items():
            self.assertIs(bodt.Mode.from_name(name), mode)
            self.mesh.mode = name
            self.assertIs(self.mesh.mode, mode, name)
        for wrong in ("ODT", "phased_odt", ""):
            with self.assertRaises(ValueError) as context:
                self.mesh.mode = wrong
            self.assertEqual(
                str(context.exception),
                f"unknown mode {wrong!r}: the modes are bodt, bodt-basic, odt, laplace, opt-weighted, phased, nodt",
            )
        self.assertIs(self.mesh.mode, bodt.Mode.NODT)  # a refused name changes nothing


class TestImprove(ErrorAssertions):
    def setUp(self):
        self.points, self.tets = meshes.box(4, jitter=0.35, seed=7)
        self.assertGreater(meshes.signed_volumes(self.points, self.tets).min(), 0.0)
        self.mesh = bodt.Mesh(self.points, self.tets)
        self.addCleanup(self.mesh.close)

    def test_improve_raises_the_min_dihedral(self):
        before = self.mesh.quality()
        reports = self.mesh.improve(max_steps=20)
        after = self.mesh.quality()
        self.assertTrue(1 <= len(reports) <= 20)
        self.assertEqual([r.step for r in reports], list(range(1, len(reports) + 1)))
        self.assertGreater(after.min_dihedral, before.min_dihedral + 5.0)
        self.assertEqual(after.num_inverted, 0)
        self.assertLessEqual(abs(after.volume - 1.0), 1e-12)
        self.assertEqual(reports[-1].min_dihedral, after.min_dihedral)

        # the arrays out, checked without the library
        points, tets = self.mesh.points, self.mesh.tets
        volumes = meshes.signed_volumes(points, tets)
        self.assertGreater(volumes.min(), 0.0)
        self.assertLessEqual(abs(volumes.sum() - 1.0), 1e-12)
        self.assertAlmostEqual(meshes.dihedral_angles(points, tets).min(), after.min_dihedral, delta=1e-9)
        self.assertTrue(np.all((points >= -1e-15) & (points <= 1 + 1e-15)))

        # made vertices interpolate input vertices, weights summing to 1
        offsets, parents, weights = self.mesh.vertex_parents()
        self.assertEqual(len(offsets), len(points) + 1)
        self.assertTrue(np.all(np.diff(offsets) >= 1))
        self.assertTrue(np.all((parents >= 0) & (parents < len(self.points))))
        np.testing.assert_allclose(np.add.reduceat(weights, offsets[:-1]), 1.0, atol=1e-12)
        origins = self.mesh.tet_origins
        self.assertEqual(len(origins), len(tets))
        self.assertTrue(np.all((origins >= 0) & (origins < len(self.tets))))

    def test_nodt_slides_the_boundary_over_the_input_surface(self):
        # Natural ODT: boundary vertices move too, and back onto the cube's faces
        # (here flat, so the volume stays); corners stay where they are
        before = self.mesh.quality()
        reports = self.mesh.improve(max_steps=10, mode=bodt.Mode.NODT, tolerance=0.0)
        self.assertEqual(len(reports), 10)
        self.assertIs(self.mesh.mode, bodt.Mode.NODT)
        after = self.mesh.quality()
        self.assertEqual(after.num_inverted, 0)
        self.assertGreater(after.min_dihedral, before.min_dihedral + 5.0)
        self.assertLessEqual(abs(after.volume - 1.0), 1e-12)
        points = self.mesh.points
        on_face = (self.points == 0.0) | (self.points == 1.0)  # per coordinate
        np.testing.assert_allclose(points[on_face], self.points[on_face], rtol=0, atol=1e-12)
        corners = meshes.grid_boundary_axes(4) == 3
        np.testing.assert_array_equal(points[corners], self.points[corners])
        moved = np.abs(points - self.points).max(axis=1)
        boundary = on_face.any(axis=1) & ~corners
        self.assertGreater(np.count_nonzero(moved[boundary] > 1e-3), boundary.sum() // 2)

    def test_mode_and_params_stay_set(self):
        reports = self.mesh.improve(max_steps=3, mode=bodt.Mode.ODT, tolerance=1e-9, backtrack_steps=2)
        self.assertLessEqual(len(reports), 3)
        self.assertIs(self.mesh.mode, bodt.Mode.ODT)
        self.assertEqual(self.mesh.get_param(bodt.Param.TOLERANCE), 1e-9)
        self.assertEqual(self.mesh.get_param(bodt.Param.BACKTRACK_STEPS), 2)
        np.testing.assert_array_equal(self.mesh.tets, self.tets)  # ODT only moves vertices
        with self.assertRaisesRegex(TypeError, "unknown parameter 'speed'"):
            self.mesh.improve(speed=2)
        with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, "max_steps"):
            self.mesh.improve(max_steps=0)

    def test_step(self):
        first = self.mesh.step()
        second = self.mesh.step()
        self.assertEqual((first.step, second.step), (1, 2))
        self.assertGreater(first.vertices_moved, 0)
        self.assertGreater(first.max_move, 0.0)
        self.assertAlmostEqual(second.min_dihedral, self.mesh.quality().min_dihedral, delta=0.0)

    def test_callback_stops_the_run(self):
        seen: list[bodt.StepReport] = []

        def stop_after_two(report: bodt.StepReport) -> bool:
            seen.append(report)
            return len(seen) == 2

        with self.assertError(bodt.CancelledError, bodt.Status.CANCELLED) as context:
            self.mesh.improve(max_steps=20, callback=stop_after_two)
        self.assertEqual(context.exception.message, "cancelled by the callback after step 2")
        self.assertEqual([r.step for r in seen], [1, 2])
        self.assertEqual(context.exception.reports, seen)  # what improve() would have returned
        self.assertEqual(context.exception.reports[-1].min_dihedral, self.mesh.quality().min_dihedral)
        self.assertEqual(self.mesh.step().step, 3)  # the steps done are kept

    def test_reports_alike_returned_or_cancelled(self):
        """A run stopped by its callback after the step it would have ended with reports what a full run returns."""
        with bodt.Mesh(self.points, self.tets) as twin:
            returned = twin.improve(max_steps=4, mode="odt")
        self.assertEqual(len(returned), 4)
        with self.assertRaises(bodt.CancelledError) as context:
            self.mesh.improve(max_steps=20, mode="odt", callback=lambda report: report.step == 4)
        self.assertEqual(context.exception.reports, returned)
        self.assertIs(self.mesh.mode, bodt.Mode.ODT)

    def test_exception_in_callback_propagates(self):
        class Boom(Exception):
            pass

        def explode(report: bodt.StepReport) -> None:
            raise Boom(f"at step {report.step}")

        with self.assertRaises(Boom) as context:
            self.mesh.improve(max_steps=20, callback=explode)
        self.assertEqual(str(context.exception), "at step 1")
        self.assertEqual(self.mesh.step().step, 2)  # the run stopped after one step; the mesh still works
        self.assertEqual(self.mesh.quality().num_inverted, 0)


class TestFiles(ErrorAssertions):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)

    def test_medit_round_trip(self):
        points, tets = meshes.box(2, jitter=0.2)
        path = os.path.join(self.dir.name, "box.mesh")
        with bodt.Mesh(points, tets + 1, base=1) as mesh:
            mesh.set_regions(np.arange(48) // 24 + 1)
            faces = mesh.boundary_faces().triangles
            mesh.set_boundary_faces(faces[:4], [5, 6, 7, 8])
            mesh.set_fixed_vertices([14])
            mesh.set_feature_edges([[1, 2], [2, 3]], [3, 4])
            mesh.set_corners([1])
            mesh.set_vertex_refs(np.arange(27) % 5)
            mesh.write(path)
        with bodt.Mesh.read(path) as read:
            self.assertEqual(read.base, 0)
            np.testing.assert_array_equal(read.points, points)
            np.testing.assert_array_equal(read.tets, tets)
            np.testing.assert_array_equal(read.regions, np.arange(48) // 24 + 1)
            read_faces = read.boundary_faces()
            np.testing.assert_array_equal(read_faces.triangles, faces - 1)
            np.testing.assert_array_equal(read_faces.markers[:4], [5, 6, 7, 8])
            np.testing.assert_array_equal(read.fixed_vertices, [13])
            np.testing.assert_array_equal(read.feature_edges, [[0, 1], [1, 2]])
            np.testing.assert_array_equal(read.feature_edge_refs, [3, 4])
            np.testing.assert_array_equal(read.corners, [0])
            np.testing.assert_array_equal(read.vertex_refs, np.arange(27) % 5)
        with bodt.Mesh.read(path, base=1) as read:
            self.assertEqual(read.base, 1)
            np.testing.assert_array_equal(read.tets, tets + 1)
            np.testing.assert_array_equal(read.boundary_faces().triangles, faces)
            np.testing.assert_array_equal(read.fixed_vertices, [14])
            np.testing.assert_array_equal(read.feature_edges, [[1, 2], [2, 3]])
            np.testing.assert_array_equal(read.corners, [1])
        with bodt.Mesh.read(path, base="file") as read:  # Medit counts from 1
            self.assertEqual(read.base, 1)
            np.testing.assert_array_equal(read.tets, tets + 1)
        with self.assertRaisesRegex(ValueError, "base is 2, not 0, 1 or 'file'"):
            bodt.Mesh.read(path, base=2)

    def test_format_from_path(self):
        self.assertEqual(bodt.format_from_path("a/b.MSH"), bodt.Format.GMSH)
        self.assertEqual(bodt.format_from_path("b.ele"), bodt.Format.TETGEN)
        with self.assertError(bodt.UnsupportedError, bodt.Status.UNSUPPORTED, "'b.xyz': unknown mesh format"):
            bodt.format_from_path("b.xyz")

    def test_formats_chosen_explicitly(self):
        points, tets = meshes.box(2, jitter=0.2)
        with bodt.Mesh(points, tets) as mesh:
            mesh.set_regions(np.arange(48) // 24 + 1)
            for fmt in (bodt.Format.MEDIT_BINARY, bodt.Format.GMSH_BINARY, bodt.Format.GMSH22, bodt.Format.VTU):
                path = os.path.join(self.dir.name, f"box.{fmt.name.lower()}")  # the extension says nothing
                mesh.write(path, format=fmt)
                read_format = bodt.Format.GMSH if fmt in (bodt.Format.GMSH_BINARY, bodt.Format.GMSH22) else fmt
                with bodt.Mesh.read(path, format=read_format) as read:
                    np.testing.assert_array_equal(read.points, points, fmt.name)
                    np.testing.assert_array_equal(read.tets, tets, fmt.name)
                    np.testing.assert_array_equal(read.regions, np.arange(48) // 24 + 1, fmt.name)
            with self.assertError(bodt.InvalidArgumentError, bodt.Status.INVALID_ARGUMENT, "unknown format 42"):
                mesh.write(os.path.join(self.dir.name, "x.mesh"), format=42)
        inp = os.path.join(self.dir.name, "box.inp")
        with bodt.Mesh(points, tets) as mesh:
            mesh.write(inp)
        with self.assertError(bodt.UnsupportedError, bodt.Status.UNSUPPORTED, "written, not read"):
            bodt.Mesh.read(inp)

    def test_tetgen_round_trip(self):
        points, tets = meshes.box(2)
        path = os.path.join(self.dir.name, "box.node")
        with bodt.Mesh(points, tets) as mesh:
            mesh.write(path)
        for name in ("box.node", "box.ele", "box.face"):
            self.assertTrue(os.path.isfile(os.path.join(self.dir.name, name)), name)
        with bodt.Mesh.read(os.path.join(self.dir.name, "box.ele")) as read:
            np.testing.assert_array_equal(read.points, points)
            np.testing.assert_array_equal(read.tets, tets)

    def test_file_errors(self):
        missing = os.path.join(self.dir.name, "missing.mesh")
        with self.assertError(bodt.FileError, bodt.Status.IO, missing):
            bodt.Mesh.read(missing)
        garbage = os.path.join(self.dir.name, "garbage.mesh")
        with open(garbage, "w") as f:
            f.write("MeshVersionFormatted 1\nDimension 3\nVertices\nthree\n")
        with self.assertError(bodt.FileError, bodt.Status.IO, "garbage.mesh:4:"):
            bodt.Mesh.read(garbage)
        with bodt.Mesh(*meshes.box(1)) as mesh:
            with self.assertError(bodt.FileError, bodt.Status.IO):
                mesh.write(os.path.join(self.dir.name, "no", "such", "dir.mesh"))

    def test_inverted_file(self):
        points, tets = meshes.box(2)
        tets[0] = tets[0, [0, 1, 3, 2]]
        path = os.path.join(self.dir.name, "inverted.mesh")
        with bodt.Mesh(points, tets, accept_inverted=True) as mesh:
            mesh.write(path)
        with self.assertError(bodt.BadMeshError, bodt.Status.BAD_MESH, "inverted"):
            bodt.Mesh.read(path)
        with bodt.Mesh.read(path, accept_inverted=True) as read:
            self.assertEqual(read.quality().num_inverted, 1)


class TestLifetime(unittest.TestCase):
    def test_context_manager_closes(self):
        with bodt.Mesh(*meshes.octahedron()) as mesh:
            self.assertFalse(mesh.closed)
            self.assertEqual(mesh.num_tets, 8)
        self.assertTrue(mesh.closed)
        self.assertEqual(repr(mesh), "<bodt.Mesh (closed)>")
        for use in (lambda: mesh.points, mesh.quality, mesh.step, mesh.improve, lambda: mesh.mode,
                    lambda: mesh.set_param(bodt.Param.TOLERANCE, 1e-3), lambda: mesh.write("never.mesh")):
            with self.assertRaisesRegex(ValueError, "closed bodt.Mesh"):
                use()
        with self.assertRaisesRegex(ValueError, "closed bodt.Mesh"):
            with mesh:
                pass
        mesh.close()  # again: nothing happens
        self.assertTrue(mesh.closed)

    def test_closed_on_exception_and_as_reference(self):
        with self.assertRaises(KeyError):
            with bodt.Mesh(*meshes.octahedron()) as mesh:
                raise KeyError("out")
        self.assertTrue(mesh.closed)
        with bodt.Mesh(*meshes.octahedron()) as other:
            with self.assertRaisesRegex(ValueError, "closed bodt.Mesh"):
                other.set_reference(mesh)
            with self.assertRaisesRegex(TypeError, "reference must be a bodt.Mesh"):
                other.set_reference("mesh")

    def test_garbage_collection_frees_the_handle(self):
        mesh = bodt.Mesh(*meshes.box(2))
        mesh.step()
        finalizer = mesh._finalizer
        self.assertTrue(finalizer.alive)
        del mesh
        gc.collect()
        self.assertFalse(finalizer.alive)

    def test_no_copies(self):
        with bodt.Mesh(*meshes.octahedron()) as mesh:
            for duplicate in (copy.copy, copy.deepcopy, pickle.dumps):
                with self.assertRaisesRegex(TypeError, "cannot be copied or pickled"):
                    duplicate(mesh)


if __name__ == "__main__":
    unittest.main()
