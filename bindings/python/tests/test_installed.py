"""The installed bodt package finds the installed libbodt through its _paths.py, and works.

BODT_TEST_PREFIX is the scratch prefix consumers.install installed into,
BODT_TEST_LIBDIR its library directory, BODT_TEST_SOVERSION the major version.
"""

import os
import unittest

import bodt
import meshes
from bodt import _paths

PREFIX = os.path.realpath(os.environ["BODT_TEST_PREFIX"])
LIBDIR = os.environ["BODT_TEST_LIBDIR"]
SOVERSION = os.environ["BODT_TEST_SOVERSION"]


class TestInstalled(unittest.TestCase):
    def test_imported_from_the_prefix(self):
        package_dir = os.path.realpath(os.path.dirname(bodt.__file__))
        self.assertEqual(os.path.commonpath([package_dir, PREFIX]), PREFIX, package_dir)
        self.assertNotIn("BODT_LIBRARY", os.environ)
        self.assertFalse(os.path.isabs(_paths.LIBRARY_DIR))
        library = os.path.join(package_dir, _paths.LIBRARY_DIR, f"libbodt.so.{SOVERSION}")
        self.assertEqual(os.path.normpath(bodt.library_path()), os.path.normpath(library))
        self.assertTrue(os.path.samefile(bodt.library_path(), os.path.join(LIBDIR, f"libbodt.so.{SOVERSION}")))
        self.assertEqual(bodt.library_version(), bodt.__version__)

    def test_improve_the_quickstart_mesh(self):
        with bodt.Mesh(*meshes.octahedron()) as mesh:
            before = mesh.quality()
            mesh.improve(max_steps=20)
            after = mesh.quality()
        self.assertEqual(f"{before.min_dihedral:.2f} -> {after.min_dihedral:.2f}", "2.89 -> 54.74")
        self.assertEqual(after.num_inverted, 0)
        self.assertAlmostEqual(after.volume, 4.0 / 3.0, delta=1e-12)  # the octahedron |x| + |y| + |z| <= 1


if __name__ == "__main__":
    unittest.main()
