"""bodt.from_meshio and Mesh.to_meshio with the real meshio (Debian's python3-meshio): files written and read by it.

BODT_TEST_GMSH_DIR holds the Gmsh files of tests/data/gmsh, written by Gmsh
itself (tests/data/README), which bodt.Mesh.read reads too (set by CTest).
meshio renumbers the points of some files (Gmsh 4.1 lists them by entity),
so meshes are compared through their points' coordinates.
"""

import glob
import os
import subprocess
import sys
import tempfile
import unittest

import meshio
import numpy as np

import bodt
import meshes

GMSH_DIR = os.environ["BODT_TEST_GMSH_DIR"]


def content(mesh: bodt.Mesh) -> dict[str, object]:
    """A mesh's data by coordinates, independent of the vertex and tet order."""
    xyz = [tuple(p) for p in mesh.points]

    def cells(indices: np.ndarray, tags: np.ndarray | None = None) -> list:
        rows = [tuple(sorted(xyz[v - mesh.base] for v in row)) for row in np.atleast_2d(indices)]
        return sorted(zip(rows, [0] * len(rows) if tags is None else tags.tolist()))

    faces = mesh.boundary_faces()
    return {
        "points": sorted(xyz),
        "tets": cells(mesh.tets, mesh.regions),
        "faces": cells(faces.triangles, faces.markers),
        "edges": cells(mesh.feature_edges, mesh.feature_edge_refs),
        "fixed": cells(mesh.fixed_vertices[:, None]),
        "refs": sorted(zip(xyz, mesh.vertex_refs.tolist())),
    }


def marked_box() -> bodt.Mesh:
    """box(3) with two regions, a marker per side of the cube (and one odd triangle), feature edges, data."""
    points, tets = meshes.box(3, jitter=0.2, seed=5)
    mesh = bodt.Mesh(points, tets)
    outer = mesh.boundary_faces().triangles  # the cube's sides, before the regions add their interface
    mesh.set_regions(np.where(points[tets].mean(axis=1)[:, 0] < 0.5, 1, 2))
    centres = points[outer].mean(axis=1)
    axis = np.argmax(np.abs(centres - 0.5), axis=1)
    markers = 10 * (1 + 2 * axis + (centres[np.arange(len(outer)), axis] > 0.5))
    # a triangle of its own marker amid the side x = 0: each of its vertices is on triangles of marker 10 too,
    # so its Gmsh entity has no point of its own unless to_meshio gives it one
    inside = np.all(meshes.grid_boundary_axes(3)[outer] == 1, axis=1)
    markers[np.flatnonzero(inside & (markers == 10))[0]] = 99
    mesh.set_boundary_faces(outer, markers)
    edges, numbers = meshes.cube_edges(3)
    mesh.set_feature_edges(edges, numbers + 100)
    mesh.set_fixed_vertices(np.flatnonzero(meshes.grid_boundary_axes(3) == 3))
    mesh.set_vertex_refs(np.arange(len(points)) % 5)
    mesh.field_data = {"left": np.array([1, 3]), "right": np.array([2, 3]), "odd": np.array([99, 2])}
    return mesh


class FileTestCase(unittest.TestCase):
    """A test with a temporary directory for its files."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def path(self, name: str) -> str:
        return os.path.join(self.tmp.name, name)


class TestToMeshio(FileTestCase):
    def setUp(self):
        super().setUp()
        self.mesh = marked_box()
        self.addCleanup(self.mesh.close)

    def test_blocks_and_data(self):
        converted = self.mesh.to_meshio()
        self.assertIsInstance(converted, meshio.Mesh)
        np.testing.assert_array_equal(converted.points, self.mesh.points)
        types = [block.type for block in converted.cells]
        self.assertEqual(types, ["tetra"] * 2 + ["triangle"] * 7 + ["line"] * 12 + ["vertex"])
        physical = [tags[0] for tags in converted.cell_data["gmsh:physical"]]
        self.assertEqual(physical, [1, 2, 10, 20, 30, 40, 50, 60, 99] + list(range(101, 113)) + [1])
        geometrical = [tags[0] for tags in converted.cell_data["gmsh:geometrical"]]
        self.assertEqual(geometrical, [1, 2, 1, 2, 3, 4, 5, 6, 7] + list(range(1, 13)) + [1])
        for block in converted.cells:
            self.assertEqual(block.data.dtype, np.int64)
        tets, regions = self.mesh.tets, self.mesh.regions
        for block, region in zip(converted.cells[:2], (1, 2)):
            np.testing.assert_array_equal(block.data, tets[regions == region])  # in the mesh's order
        np.testing.assert_array_equal(converted.cells[-1].data.ravel(), self.mesh.fixed_vertices)
        np.testing.assert_array_equal(converted.point_data["medit:ref"], self.mesh.vertex_refs)
        self.assertEqual(set(converted.field_data), {"left", "right", "odd"})
        # each point in the Gmsh entity of lowest dimension it lies on; every block's entity holds a point
        dim_tags = converted.point_data["gmsh:dim_tags"]
        corners = self.mesh.fixed_vertices
        np.testing.assert_array_equal(dim_tags[corners], [[0, 1]] * 8)
        geometrical = converted.cell_data["gmsh:geometrical"]
        entities = {(block.dim, tags[0]) for block, tags in zip(converted.cells, geometrical)}
        self.assertEqual({tuple(t) for t in dim_tags}, entities)

    def test_one_based_mesh_gives_zero_based_cells(self):
        points, tets = meshes.box(2)
        with bodt.Mesh(points, tets + 1, base=1) as one, bodt.Mesh(points, tets) as zero:
            for mesh in (one, zero):
                mesh.set_fixed_vertices([1 + mesh.base])
            a, b = one.to_meshio(), zero.to_meshio()
        for block_a, block_b in zip(a.cells, b.cells):
            np.testing.assert_array_equal(block_a.data, block_b.data)
        np.testing.assert_array_equal(a.cells[0].data, tets)

    def test_round_trips_through_files(self):
        """meshio writes the mesh as Gmsh 4.1 (binary, ASCII), Gmsh 2.2, Medit and VTU; from_meshio reads it back."""
        expected = content(self.mesh)
        converted = self.mesh.to_meshio()
        everything = set(expected)
        cases = [
            # meshio 5.0 reads a 4.1 file's points by entity, but its point data in the order written
            ("box41.msh", {"file_format": "gmsh"}, everything - {"refs"}, True),
            ("box41_ascii.msh", {"file_format": "gmsh", "binary": False}, everything - {"refs"}, True),
            ("box22.msh", {"file_format": "gmsh22"}, everything, True),
            ("box.mesh", {}, everything - {"fixed"}, False),  # Medit has no place for fixed vertices
            ("box.vtu", {}, everything, False),  # VTU none for field data
        ]
        for name, options, kept, names_kept in cases:
            with self.subTest(name):
                meshio.write(self.path(name), converted, **options)  # Medit: meshio warns what it leaves out
                with bodt.from_meshio(meshio.read(self.path(name))) as back:
                    got = content(back)
                    self.assertEqual({key: got[key] for key in kept}, {key: expected[key] for key in kept})
                    if "fixed" not in kept:
                        self.assertEqual(got["fixed"], [])
                    self.assertEqual(set(back.field_data), {"left", "right", "odd"} if names_kept else set())
                    if names_kept:
                        np.testing.assert_array_equal(back.field_data["odd"], [99, 2])

    def test_gmsh_files_also_for_libbodt(self):
        """The Gmsh files meshio writes from to_meshio read alike by libbodt's own reader."""
        converted = self.mesh.to_meshio()
        for name, file_format in (("box41.msh", "gmsh"), ("box22.msh", "gmsh22")):
            meshio.write(self.path(name), converted, file_format=file_format)
            with bodt.Mesh.read(self.path(name)) as read:
                theirs, ours = content(read), content(self.mesh)
                del theirs["refs"], ours["refs"]  # Gmsh files have no vertex refs
                self.assertEqual(theirs, ours, name)

    def test_improved_mesh_out(self):
        """A mesh improved after from_meshio goes back to meshio with its regions and markers."""
        with bodt.from_meshio(self.mesh.to_meshio()) as mesh:
            before = content(mesh)
            self.assertEqual(before, content(self.mesh))
            mesh.improve(max_steps=5, mode="bodt")
            after = content(mesh)
            self.assertNotEqual(after["points"], before["points"])
            meshio.write(self.path("out.msh"), mesh.to_meshio(), file_format="gmsh22")
            with bodt.from_meshio(meshio.read(self.path("out.msh"))) as back:
                self.assertEqual(content(back), after)


class TestFromMeshio(unittest.TestCase):
    def test_gmsh_files_read_as_libbodt_reads_them(self):
        """Gmsh's own files (4.1, 2.2, ASCII, binary, with and without physical groups): as bodt.Mesh.read."""
        paths = sorted(glob.glob(os.path.join(GMSH_DIR, "*.msh")))
        self.assertEqual(len(paths), 6)
        for path in paths:
            with self.subTest(os.path.basename(path)):
                with bodt.from_meshio(meshio.read(path)) as ours, bodt.Mesh.read(path) as theirs:
                    self.assertEqual(content(ours), content(theirs))
                    if "nophysical" in path:
                        self.assertEqual(ours.field_data, {})
                        np.testing.assert_array_equal(np.unique(ours.regions), [1, 2])  # the volumes
                        self.assertEqual(set(ours.boundary_faces().markers.tolist()), set(range(1, 12)))  # the surfaces
                    else:
                        self.assertEqual(set(ours.field_data), {"left", "right", "bottom", "edge", "corner"})
                        np.testing.assert_array_equal(ours.field_data["corner"], [30, 0])
                        self.assertEqual(len(ours.fixed_vertices), 1)

    def test_without_cell_data(self):
        """No tags: regions 0, each triangle marked 1, each vertex cell fixed, feature edges of ref 0."""
        points, tets = meshes.box(2)
        with bodt.Mesh(points, tets) as mesh:
            triangles = mesh.boundary_faces().triangles[:3]
        plain = meshio.Mesh(points, [("tetra", tets), ("triangle", triangles), ("line", [[0, 1], [1, 0]]),
                                     ("vertex", [[13]]), ("quad", [[0, 1, 4, 3]])])
        with bodt.from_meshio(plain, int_dtype=np.int32) as mesh:
            np.testing.assert_array_equal(mesh.regions, np.zeros(48))
            faces = mesh.boundary_faces()
            self.assertEqual(faces.markers.dtype, np.int32)
            self.assertEqual(np.count_nonzero(faces.markers), 3)
            self.assertEqual(sorted(map(tuple, np.sort(faces.triangles[faces.markers == 1], axis=1))),
                             sorted(map(tuple, np.sort(triangles, axis=1))))
            np.testing.assert_array_equal(mesh.feature_edges, [[0, 1]])  # listed twice, kept once
            np.testing.assert_array_equal(mesh.feature_edge_refs, [0])
            np.testing.assert_array_equal(mesh.fixed_vertices, [13])

    def test_tags_and_refs_named(self):
        points, tets = meshes.box(2)
        data = meshio.Mesh(points, [("tetra", tets[:24]), ("tetra", tets[24:])],
                           cell_data={"material": [np.full(24, 4), np.full(24, 5.0)]},
                           point_data={"bc": np.arange(27) % 3})
        with bodt.from_meshio(data, tags="material", refs="bc", base=1) as mesh:
            self.assertEqual(mesh.base, 1)
            np.testing.assert_array_equal(mesh.tets, tets + 1)
            np.testing.assert_array_equal(mesh.regions, [4] * 24 + [5] * 24)
            np.testing.assert_array_equal(mesh.vertex_refs, np.arange(27) % 3)
        with self.assertRaisesRegex(ValueError, r"no cell data 'gmsh:physical' \(it has \['material'\]\)"):
            bodt.from_meshio(data, tags="gmsh:physical")
        with self.assertRaisesRegex(ValueError, "the meshio mesh has no point data 'medit:ref'"):
            bodt.from_meshio(data, refs="medit:ref")
        data.cell_data["material"][1][0] = 5.5
        with self.assertRaisesRegex(TypeError, "cell data 'material' must be whole numbers"):
            bodt.from_meshio(data, tags="material")

    def test_refused(self):
        points, tets = meshes.box(2)
        with self.assertRaisesRegex(ValueError, "the meshio mesh has no 'tetra' cells"):
            bodt.from_meshio(meshio.Mesh(points, [("triangle", [[0, 1, 2]])]))
        with self.assertRaisesRegex(ValueError, "'hexahedron' cells: libbodt improves 4-node tets only"):
            bodt.from_meshio(meshio.Mesh(points, [("tetra", tets), ("hexahedron", [list(range(8))])]))
        not_a_face = meshio.Mesh(points, [("tetra", tets), ("triangle", [[0, 1, 26]])],
                                 cell_data={"medit:ref": [np.zeros(48, int), [7]]})
        with self.assertRaises(bodt.InvalidArgumentError) as context:
            bodt.from_meshio(not_a_face)
        self.assertIn("triangle 0 (0, 1, 26) is not a face of the mesh", str(context.exception))
        big = meshio.Mesh(points, [("tetra", tets.astype(np.int64) + 2**32)])
        with self.assertRaisesRegex(ValueError, "outside the int32 range of libbodt"):
            bodt.from_meshio(big)


class TestMeditFilesOfMeshio(FileTestCase):
    """meshio writes a Medit section per cell block; bodt.Mesh.read appends repeated sections in file order."""

    def test_two_blocks_of_tets_and_of_triangles(self):
        """Two tetra and two triangle blocks with medit:ref, as .mesh and .meshb: regions and markers by block."""
        points, tets = meshes.box(2)
        with bodt.Mesh(points, tets) as mesh:
            outer = mesh.boundary_faces().triangles
        left = points[tets].mean(axis=1)[:, 0] < 0.5
        height = points[outer].mean(axis=1)[:, 2]
        bottom, top = outer[height < 1e-12], outer[height > 1 - 1e-12]
        blocks = [("tetra", tets[left]), ("triangle", bottom), ("tetra", tets[~left]), ("triangle", top)]
        refs = [np.full(len(tets[left]), 3), np.full(len(bottom), 10), np.full(len(tets[~left]), 4),
                np.full(len(top), 20)]
        written = meshio.Mesh(points, blocks, cell_data={"medit:ref": refs})
        expected_markers = {**{tuple(sorted(t)): 10 for t in bottom}, **{tuple(sorted(t)): 20 for t in top}}
        for name in ("blocks.mesh", "blocks.meshb"):
            with self.subTest(name):
                meshio.write(self.path(name), written)
                if name.endswith(".mesh"):
                    with open(self.path(name)) as f:
                        text = f.read()
                    self.assertEqual((text.count("\nTetrahedra\n"), text.count("\nTriangles\n")), (2, 2))
                with bodt.Mesh.read(self.path(name)) as read:
                    np.testing.assert_array_equal(read.points, points)
                    np.testing.assert_array_equal(read.tets, np.concatenate([tets[left], tets[~left]]))
                    np.testing.assert_array_equal(read.regions, [3] * int(left.sum()) + [4] * int((~left).sum()))
                    faces = read.boundary_faces()
                    markers = {tuple(sorted(t)): m for t, m in zip(faces.triangles.tolist(), faces.markers.tolist())}
                    self.assertEqual({t: m for t, m in markers.items() if m}, expected_markers)

    def test_to_meshio_round_trip(self):
        """Mesh.to_meshio (a block per region, marker and edge ref), written by meshio as .mesh and .meshb, read
        by bodt.Mesh.read: everything a Medit file holds (not the fixed vertices: meshio skips vertex cells)."""
        with marked_box() as mesh:
            expected = content(mesh)
            converted = mesh.to_meshio()
        self.assertGreater(sum(block.type == "tetra" for block in converted.cells), 1)
        for name in ("box.mesh", "box.meshb"):
            with self.subTest(name):
                meshio.write(self.path(name), converted)  # meshio warns what it leaves out
                with bodt.Mesh.read(self.path(name)) as read:
                    got = content(read)
                self.assertEqual(got["fixed"], [])
                self.assertEqual({k: v for k, v in got.items() if k != "fixed"},
                                 {k: v for k, v in expected.items() if k != "fixed"})


class TestImport(unittest.TestCase):
    def test_meshio_only_when_asked_for(self):
        code = "import sys, bodt; print('meshio' in sys.modules)"
        result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
        self.assertEqual(result.stdout.strip(), "False")


if __name__ == "__main__":
    unittest.main()
