"""Gmsh .msh files that bodt writes, as Gmsh itself (python3-gmsh) and meshio (python3-meshio) read them.

The input is made here with Gmsh's API: two unit cubes side by side
(OpenCASCADE boxes fragmented: 12 points, 20 curves, 11 surfaces, 2
volumes), meshed, its nodes jittered (inside in 3D, on a face in the face's
plane, on an edge along the edge) so that ``bodt improve --ops
flip,insert,collapse`` flips, inserts and collapses, and saved by Gmsh as 4.1
and 2.2.  With physical groups, one per dimension and several surfaces in
one (``bottom``: the two faces at z = 0), named; without any, Gmsh saves
every element, each tagged with its entity only.

Each improved mesh, written in the four variants (4.1 and 2.2, ASCII and
binary), must open in Gmsh with the input's physical groups (dimension,
tag, name, entities), its entities (4.1: all of them; 2.2: those with
elements), an element block per entity that had elements and no other, every
element inside its entity (the entity's box from the OpenCASCADE model) and,
in 4.1, every node inside the entity of its node block; and meshio must read
it with the same tags per block (gmsh:physical, gmsh:geometrical) and the
names (field_data).  Meshes that never were Gmsh files (built from arrays,
with and without regions, markers, feature edges and fixed vertices) must
open in both too, with a physical group per value.
"""

import os
import re
import subprocess
import tempfile
import unittest

import gmsh
import meshio
import numpy as np

import bodt
import meshes

CLI = os.environ["BODT_TEST_CLI"]

# --format name of the bodt command -> Gmsh's version, binary
VARIANTS = {"gmsh": (4.1, False), "gmsh-binary": (4.1, True), "gmsh22": (2.2, False), "gmsh22-binary": (2.2, True)}

# dim, tag, name, entities (by their box: lo, hi) of the input's physical groups
GROUPS = [
    (3, 100, "solid", (-0.1, -0.1, -0.1, 1.1, 1.1, 1.1)),
    (3, 101, "other", (0.9, -0.1, -0.1, 2.1, 1.1, 1.1)),
    (2, 1, "fixed", (-0.1, -0.1, -0.1, 0.1, 1.1, 1.1)),
    (2, 7, "bottom", (-0.1, -0.1, -0.1, 2.1, 1.1, 0.1)),
    (1, 20, "edge", (-0.1, -0.1, -0.1, 0.1, 0.1, 1.1)),
    (0, 31, "corner", (-0.1, -0.1, -0.1, 0.1, 0.1, 0.1)),
]
TET, TRIANGLE, LINE, POINT = 4, 2, 1, 15
TYPE_OF_DIM = {0: POINT, 1: LINE, 2: TRIANGLE, 3: TET}
MESHIO_DIM = {"vertex": 0, "line": 1, "triangle": 2, "tetra": 3}


def setUpModule():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)


def tearDownModule():
    gmsh.finalize()


def make_boxes(directory: str, physical: bool) -> tuple[dict, dict]:
    """The two cubes, jittered, saved by Gmsh as 4.1 and 2.2: {version: path}, and each entity's box."""
    gmsh.clear()
    gmsh.model.add("boxes")
    gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1, 1)
    gmsh.model.occ.addBox(1, 0, 0, 1, 1, 1, 2)
    gmsh.model.occ.fragment([(3, 1)], [(3, 2)])
    gmsh.model.occ.synchronize()
    boxes = {e: gmsh.model.getBoundingBox(*e) for e in gmsh.model.getEntities()}
    if physical:
        for dim, tag, name, box in GROUPS:
            gmsh.model.addPhysicalGroup(dim, [t for _, t in gmsh.model.getEntitiesInBoundingBox(*box, dim)], tag)
            gmsh.model.setPhysicalName(dim, tag, name)
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.35)
    gmsh.model.mesh.generate(3)
    jitter(boxes)
    paths = {}
    for version in (4.1, 2.2):
        gmsh.option.setNumber("Mesh.MshFileVersion", version)
        paths[version] = os.path.join(directory, f"boxes_{'physical' if physical else 'plain'}{version}.msh")
        gmsh.write(paths[version])
    return paths, boxes


def jitter(boxes: dict) -> None:
    """Moves each node by up to 0.4 times the mesh size, within its entity; a tet that would turn keeps its nodes."""
    tags, xyz, _ = gmsh.model.mesh.getNodes()
    index = {t: i for i, t in enumerate(tags)}
    start = xyz.reshape(-1, 3)
    moved = start.copy()
    rng = np.random.default_rng(7)
    for dim, tag in gmsh.model.getEntities():
        if dim == 0:
            continue
        flat = [k for k in range(3) if boxes[(dim, tag)][3 + k] - boxes[(dim, tag)][k] < 1e-6]
        for node in gmsh.model.mesh.getNodes(dim, tag)[0]:
            step = rng.uniform(-0.14, 0.14, 3)
            step[flat] = 0.0
            moved[index[node]] += step
    tets = np.array([index[n] for n in gmsh.model.mesh.getElements(3)[2][0]]).reshape(-1, 4)

    def volumes(x):
        a, b, c = (x[tets[:, k]] - x[tets[:, 0]] for k in (1, 2, 3))
        return np.einsum("ij,ij->i", a, np.cross(b, c))

    sign = np.sign(volumes(start))
    for _ in range(50):
        turned = np.flatnonzero(volumes(moved) * sign <= 1e-9)
        if len(turned) == 0:
            break
        moved[tets[turned].ravel()] = start[tets[turned].ravel()]
    for node, i in index.items():
        gmsh.model.mesh.setNode(node, list(moved[i]), [])


def gmsh_view(path: str) -> dict:
    """What Gmsh's API says of a file: entities, physical groups, element blocks, nodes by entity."""
    gmsh.clear()
    gmsh.open(path)
    node_tags, xyz, _ = gmsh.model.mesh.getNodes()
    where = dict(zip(node_tags, xyz.reshape(-1, 3)))
    with open(path, "rb") as f:
        version = float(f.read(40).split()[1])
    view = {"version": version, "entities": sorted(gmsh.model.getEntities()), "groups": {}, "blocks": {},
            "nodes": {}, "xyz": where}
    for dim, tag in gmsh.model.getPhysicalGroups():
        entities = sorted(gmsh.model.getEntitiesForPhysicalGroup(dim, tag))
        view["groups"][(dim, tag)] = (gmsh.model.getPhysicalName(dim, tag), entities)
    for dim, tag in view["entities"]:
        types, _, nodes = gmsh.model.mesh.getElements(dim, tag)
        for t, n in zip(types, nodes):
            view["blocks"][(dim, tag, int(t))] = n.reshape(-1, {POINT: 1, LINE: 2, TRIANGLE: 3, TET: 4}[int(t)])
        view["nodes"][(dim, tag)] = gmsh.model.mesh.getNodes(dim, tag)[0]
    return view


def inside(points: np.ndarray, box, tol: float = 1e-6) -> bool:
    return bool(np.all(points >= np.array(box[:3]) - tol) and np.all(points <= np.array(box[3:]) + tol))


def improve(source: str, target: str, fmt: str) -> dict:
    """``bodt improve`` with every connectivity change; the summary's counts."""
    run = subprocess.run(
        [CLI, "improve", source, target, "--format", fmt, "--ops", "flip,insert,collapse"],
        capture_output=True, text=True, check=False,
    )
    if run.returncode != 0:
        raise AssertionError(f"bodt improve {source}: {run.returncode}\n{run.stdout}{run.stderr}")
    m = re.search(r"(\d+) flips, (\d+) vertices inserted, (\d+) edges collapsed", run.stdout)
    assert m, run.stdout
    return dict(zip(("flips", "inserted", "collapsed"), map(int, m.groups())))


class GmshChecks(unittest.TestCase):
    def check_meshio(self, path: str, view: dict, names: dict):
        """meshio reads the file with Gmsh's tags for every cell, and the names."""
        mesh = meshio.read(path)
        physical = mesh.cell_data.get("gmsh:physical")
        geometrical = mesh.cell_data["gmsh:geometrical"]
        self.assertEqual(len(geometrical), len(mesh.cells))
        if view["version"] == 4.1:  # a 2.2 element always has a physical tag, 0 for none
            self.assertEqual(physical is not None, bool(view["groups"]))
        groups_of = {}
        for (dim, tag), (_, entities) in view["groups"].items():
            for entity in entities:
                groups_of.setdefault((dim, entity), set()).add(tag)
        counts = {}
        for k, block in enumerate(mesh.cells):
            dim = MESHIO_DIM[block.type]
            for i in range(len(block.data)):
                entity = int(geometrical[k][i])
                counts[(dim, entity)] = counts.get((dim, entity), 0) + 1
                if physical is not None:
                    self.assertIn(int(physical[k][i]), groups_of.get((dim, entity), {0}), (path, dim, entity))
        expected = {(d, t): len(n) for (d, t, _), n in view["blocks"].items()}
        self.assertEqual(counts, expected, path)
        self.assertEqual({n: (int(v[0]), int(v[1])) for n, v in mesh.field_data.items()}, names, path)
        return mesh


class TestImprovedGmshMeshes(GmshChecks):
    """A Gmsh mesh read, improved with flips, insertions and collapses, and written keeps its structure."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.inputs = {}
        for physical in (True, False):
            paths, cls.boxes = make_boxes(cls.tmp.name, physical)
            cls.inputs[physical] = {v: (p, gmsh_view(p)) for v, p in paths.items()}

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def check_elements_inside(self, view: dict, where: str):
        """Every element inside its entity's box; every 4.1 node inside its block's entity."""
        for (dim, tag, _), nodes in view["blocks"].items():
            xyz = np.array([view["xyz"][n] for n in nodes.ravel()])
            self.assertTrue(inside(xyz, self.boxes[(dim, tag)]), f"{where}: an element outside entity {(dim, tag)}")

    def check_improved(self, physical: bool, version: float, fmt: str):
        source, before = self.inputs[physical][version]
        where = f"{os.path.basename(source)} -> {fmt}"
        target = os.path.join(self.tmp.name, f"improved_{physical}_{version}_{fmt}.msh")
        counts = improve(source, target, fmt)
        # the connectivity did change: flips, new vertices and collapsed edges
        self.assertTrue(all(n > 0 for n in counts.values()), f"{where}: {counts}")
        after = gmsh_view(target)
        out_version, _ = VARIANTS[fmt]
        with_elements = sorted({(d, t) for d, t, _ in before["blocks"]})
        # entities: 4.1 lists all of the model's; 2.2 has those with elements
        self.assertEqual(after["entities"], before["entities"] if out_version == 4.1 else with_elements, where)
        self.assertEqual(after["groups"], before["groups"], where)
        if physical:
            self.assertEqual({g: n for g, (n, _) in after["groups"].items()},
                             {(d, t): n for d, t, n, _ in GROUPS}, where)
            self.assertEqual(len(after["groups"][(2, 7)][1]), 2, where)  # bottom: two surfaces
            corner = gmsh.model.mesh.getNodesForPhysicalGroup(0, 31)[1]
            np.testing.assert_array_equal(corner, [0.0, 0.0, 0.0])
        else:
            self.assertEqual(after["groups"], {}, where)
        # one block per entity that had elements, of the same type
        self.assertEqual(sorted(after["blocks"]), sorted(before["blocks"]), where)
        self.check_elements_inside(after, where)
        if out_version == 4.1:
            for entity, nodes in after["nodes"].items():
                xyz = np.array([after["xyz"][n] for n in nodes]).reshape(-1, 3)
                self.assertTrue(inside(xyz, self.boxes[entity]), f"{where}: a node outside entity {entity}")
        with bodt.Mesh.read(target) as mesh:
            tets = sum(len(n) for (d, _, _), n in after["blocks"].items() if d == 3)
            self.assertEqual(tets, mesh.num_tets, where)
            # the vertices collapsed away stay in the file, unused: Gmsh keeps them in 4.1, drops them in 2.2
            used = len(np.unique(mesh.tets))
            self.assertEqual(used, len(before["xyz"]) + counts["inserted"] - counts["collapsed"], where)
            self.assertEqual(len(after["xyz"]), mesh.num_vertices if out_version == 4.1 else used, where)
        names = {n: (t, d) for d, t, n, _ in GROUPS} if physical else {}
        self.check_meshio(target, after, names)
        return target, after

    def test_physical_groups(self):
        for version in (4.1, 2.2):
            for fmt in VARIANTS:
                with self.subTest(input=version, output=fmt):
                    self.check_improved(True, version, fmt)

    def test_without_physical_groups(self):
        for version in (4.1, 2.2):
            for fmt in VARIANTS:
                with self.subTest(input=version, output=fmt):
                    self.check_improved(False, version, fmt)

    def test_written_again(self):
        """A file bodt wrote, read and written again, is the same to Gmsh."""
        for physical in (True, False):
            first, view = self.check_improved(physical, 4.1, "gmsh")
            again = first + ".again.msh"
            run = subprocess.run([CLI, "convert", first, again], capture_output=True, text=True, check=False)
            self.assertEqual(run.returncode, 0, run.stderr)
            second = gmsh_view(again)
            for key in ("entities", "groups"):
                self.assertEqual(second[key], view[key])
            self.assertEqual(sorted(second["blocks"]), sorted(view["blocks"]))
            for block, nodes in view["blocks"].items():
                np.testing.assert_array_equal(second["blocks"][block], nodes)
            with open(first, "rb") as a, open(again, "rb") as b:
                self.assertEqual(a.read(), b.read())


class TestMeshesFromArrays(GmshChecks):
    """Meshes that were never Gmsh files: a physical group per value, or none at all."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def test_decorated(self):
        points, tets = meshes.box(4, jitter=0.35, seed=3)  # flips, insertions, a collapse
        with bodt.Mesh(points, tets) as mesh:
            centres = points[tets].mean(axis=1)
            mesh.set_regions(np.where(centres[:, 0] < 0.5, 2, 0))  # region 0 among others
            faces = mesh.boundary_faces().triangles
            face_centres = points[faces].mean(axis=1)
            markers = np.where(face_centres[:, 2] < 1e-9, 5, np.where(face_centres[:, 0] < 1e-9, 6, 0))
            mesh.set_boundary_faces(faces[markers != 0], markers[markers != 0])
            on_edge = np.flatnonzero((points[:, 0] == 0) & (points[:, 1] == 0))
            on_edge = on_edge[np.argsort(points[on_edge, 2])]
            edges = np.column_stack([on_edge[:-1], on_edge[1:]])
            mesh.set_feature_edges(edges, np.array([20] + [0] * (len(edges) - 1)))
            mesh.set_fixed_vertices([0, len(points) - 1])
            reports = mesh.improve(5, ops=bodt.Op.FLIP | bodt.Op.INSERT | bodt.Op.COLLAPSE)
            for done in ("flips", "vertices_inserted", "edges_collapsed"):
                self.assertGreater(sum(getattr(r, done) for r in reports), 0, done)
            regions = mesh.regions
            marked = mesh.boundary_faces().markers
            for fmt, (version, _) in VARIANTS.items():
                with self.subTest(output=fmt):
                    path = os.path.join(self.tmp.name, f"decorated_{fmt}.msh")
                    mesh.write(path, bodt.Format[fmt.upper().replace("-", "_")])
                    view = gmsh_view(path)
                    named = {g: n for g, (n, _) in view["groups"].items() if g[1] != 0}
                    self.assertEqual(named, {(3, 2): "region 2", (2, 5): "marker 5", (2, 6): "marker 6",
                                             (1, 20): "edge ref 20", (0, 1): "fixed vertices"})
                    # tag 0: the elements of no group, a group Gmsh reads from 4.1 (2.2 has no place for it)
                    zero = {g for g in view["groups"] if g[1] == 0}
                    self.assertEqual(zero, {(3, 0), (1, 0)} if version == 4.1 else set())

                    def count(dim, group):
                        return sum(len(view["blocks"].get((dim, e, TYPE_OF_DIM[dim]), ()))
                                   for e in view["groups"][(dim, group)][1])

                    self.assertEqual(count(3, 2), np.count_nonzero(regions == 2))
                    self.assertEqual(count(2, 5), np.count_nonzero(marked == 5))
                    self.assertEqual(count(2, 6), np.count_nonzero(marked == 6))
                    self.assertEqual(count(1, 20), 1)
                    self.assertEqual(count(0, 1), 2)
                    self.assertEqual(sum(len(n) for (d, _, _), n in view["blocks"].items() if d == 3), mesh.num_tets)
                    names = {"region 2": (2, 3), "marker 5": (5, 2), "marker 6": (6, 2), "edge ref 20": (20, 1),
                             "fixed vertices": (1, 0)}
                    self.check_meshio(path, view, names)

    def test_plain(self):
        points, tets = meshes.box(2)
        with bodt.Mesh(points, tets) as mesh:
            for fmt in VARIANTS:
                with self.subTest(output=fmt):
                    path = os.path.join(self.tmp.name, f"plain_{fmt}.msh")
                    mesh.write(path, bodt.Format[fmt.upper().replace("-", "_")])
                    view = gmsh_view(path)
                    self.assertEqual(view["groups"], {})
                    self.assertEqual([k for k in view["blocks"]], [(3, 1, TET)])
                    m = self.check_meshio(path, view, {})
                    self.assertEqual(np.count_nonzero(m.cell_data.get("gmsh:physical", [[]])[0]), 0)
                    self.assertEqual(len(m.cells), 1)


if __name__ == "__main__":
    unittest.main()
