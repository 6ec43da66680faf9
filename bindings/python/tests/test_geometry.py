"""Paper 002 through the bodt package: the geometry of a box, reference meshes, target density grids."""

import unittest

import numpy as np

import bodt
import meshes


class TestBoxGeometry(unittest.TestCase):
    def check_box(self, base: int):
        n = 3
        points, tets = meshes.box(n, jitter=0.2)
        with bodt.Mesh(points, tets + base, base=base) as mesh:
            self.assertEqual(mesh.geometry_counts(), bodt.GeometryCounts(regions=6, chains=12))
            expected = np.array([bodt.GeometryClass.INTERIOR, bodt.GeometryClass.SURFACE,
                                 bodt.GeometryClass.SHARP_EDGE, bodt.GeometryClass.CORNER])
            np.testing.assert_array_equal(mesh.geometry_classes, expected[meshes.grid_boundary_axes(n)])

            triangles = mesh.boundary_faces().triangles - base
            regions, shapes = mesh.face_regions()
            self.assertEqual(len(regions), 6 * n * n * 2)
            np.testing.assert_array_equal(shapes, np.full(len(regions), bodt.Shape.PLANE))
            self.assertEqual(set(regions.tolist()), set(range(base, base + 6)))
            for region in range(base, base + 6):
                corners = points[triangles[regions == region]].reshape(-1, 3)
                self.assertEqual(len(corners), 3 * n * n * 2)  # one side of the cube each
                axis = int(np.flatnonzero(np.ptp(corners, axis=0) == 0)[0])
                side = corners[0, axis]
                fit = mesh.region_shape(region)
                self.assertIs(fit.shape, bodt.Shape.PLANE)
                normal = np.zeros(3)
                normal[axis] = 1.0
                np.testing.assert_allclose(np.abs(fit.axis), normal, atol=1e-12)
                self.assertAlmostEqual(fit.point[axis], side, delta=1e-12)
                self.assertLessEqual(fit.max_error, 1e-12)
                self.assertEqual(fit.acceptable_error, 0.0)
            with self.assertRaises(bodt.InvalidArgumentError) as context:
                mesh.region_shape(base + 6)
            self.assertTrue(context.exception.message)

    def test_zero_based(self):
        self.check_box(0)

    def test_one_based(self):
        self.check_box(1)


class TestReference(unittest.TestCase):
    def test_recovery_with_a_reference_mesh(self):
        points, tets = meshes.box(3)
        stretched = points * [1.5, 1.0, 1.0]
        with bodt.Mesh(points, tets) as reference, bodt.Mesh(stretched, tets) as mesh:
            self.assertEqual(mesh.recovery_error().density_edges, 0)  # no target yet
            mesh.set_reference(reference)
            reference.close()  # read, not kept
            mesh.mode = bodt.Mode.PHASED_ODT
            before = mesh.recovery_error()
            self.assertEqual(before.density_edges, len(meshes.edges(tets)))
            self.assertGreater(before.density_mean, 0.0)
            self.assertGreaterEqual(before.density_max, before.density_mean)
            self.assertEqual(before.geometric_edges, 0)  # no cylinder

            mesh.improve(max_steps=10)
            after = mesh.recovery_error()
            quality = mesh.quality()
            self.assertLess(after.density_mean, before.density_mean)
            self.assertEqual(quality.num_inverted, 0)
            self.assertAlmostEqual(quality.volume, 1.5, delta=1e-12)

            mesh.set_reference(None)
            self.assertEqual(mesh.recovery_error().density_edges, 0)

    def test_reference_of_another_mesh(self):
        with bodt.Mesh(*meshes.box(3)) as mesh, bodt.Mesh(*meshes.box(2)) as other:
            with self.assertRaises(bodt.Error) as context:
                mesh.set_reference(other)
            self.assertIn(context.exception.status, (bodt.Status.INVALID_ARGUMENT, bodt.Status.BAD_MESH))
            self.assertTrue(context.exception.message)


class TestTargetDensity(unittest.TestCase):
    # a grid of (3, 4, 5) points whose cells' boundaries miss every edge midpoint of box(2)
    ORIGIN = np.array([-0.8, -0.5, -0.35])
    SPACING = np.array([1.2, 0.6, 0.4])

    def expected_error(self, points: np.ndarray, tets: np.ndarray, values: np.ndarray) -> tuple[float, float, int]:
        """Eq. (4.1) of paper 002 by bodt.h: a cell's density is the mean of its corners' values."""
        pairs = meshes.edges(tets)
        a, b = points[pairs[:, 0]], points[pairs[:, 1]]
        lengths = np.linalg.norm(a - b, axis=1)
        cells = np.floor((0.5 * (a + b) - self.ORIGIN) / self.SPACING).astype(int)
        targets = np.array([values[i:i + 2, j:j + 2, k:k + 2].mean() for i, j, k in cells])
        errors = np.abs(1.0 / lengths - targets) / targets
        return errors.mean(), errors.max(), len(errors)

    def test_grid_indexed_x_y_z(self):
        points, tets = meshes.box(2)
        i, j, k = np.meshgrid(np.arange(3), np.arange(4), np.arange(5), indexing="ij")
        values = 1.0 + i + 3.0 * j + 7.0 * k  # values[i, j, k] at ORIGIN + (i, j, k) * SPACING
        mean, worst, count = self.expected_error(points, tets, values)
        with bodt.Mesh(points, tets) as mesh:
            for layout in (values, np.asfortranarray(values), values.tolist()):
                mesh.set_target_density(self.ORIGIN, self.SPACING, layout)
                got = mesh.recovery_error()
                self.assertEqual(got.density_edges, count)
                self.assertAlmostEqual(got.density_mean, mean, delta=1e-12 * mean)
                self.assertAlmostEqual(got.density_max, worst, delta=1e-12 * worst)
            mesh.set_target_density(None, None, None)
            self.assertEqual(mesh.recovery_error().density_edges, 0)

    def test_bad_grids(self):
        with bodt.Mesh(*meshes.box(2)) as mesh:
            with self.assertRaisesRegex(ValueError, r"values must have shape \(n, n, n\)"):
                mesh.set_target_density(self.ORIGIN, self.SPACING, np.ones((3, 4)))
            with self.assertRaisesRegex(ValueError, r"spacing must have shape \(3,\)"):
                mesh.set_target_density(self.ORIGIN, [1.0, 1.0], np.ones((3, 4, 5)))
            with self.assertRaises(bodt.InvalidArgumentError) as context:
                mesh.set_target_density(self.ORIGIN, self.SPACING, np.ones((1, 4, 5)))
            self.assertIn("dims", context.exception.message)
            with self.assertRaises(bodt.Error) as context:
                mesh.set_target_density(self.ORIGIN, [0.5, np.nan, 0.5], np.ones((3, 4, 5)))
            self.assertTrue(context.exception.message)
            self.assertEqual(mesh.recovery_error().density_edges, 0)  # nothing set


if __name__ == "__main__":
    unittest.main()
