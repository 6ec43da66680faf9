"""The bodt package against bodt.h (enums, param types, functions, structs), the command's modes, its library lookup.

BODT_TEST_HEADER is include/bodt.h, BODT_TEST_LIBRARY the built libbodt.so,
BODT_TEST_PACKAGE_DIR the staged package and BODT_TEST_CLI the built bodt
command (set by CTest).
"""

import ctypes
import ctypes.util
import itertools
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

import bodt
import meshes
from bodt import _library, enums, structs

HEADER = os.environ["BODT_TEST_HEADER"]
LIBRARY = os.environ["BODT_TEST_LIBRARY"]
PACKAGE_DIR = os.environ["BODT_TEST_PACKAGE_DIR"]
CLI = os.environ["BODT_TEST_CLI"]


def header_text() -> str:
    with open(HEADER, encoding="utf-8") as f:
        return f.read()


def without_comments(text: str) -> str:
    return re.sub(r"/\*.*?\*/", " ", text, flags=re.S)


def header_enums() -> dict[str, str]:
    """enum name -> its body, comments kept."""
    return dict(re.findall(r"enum (bodt_\w+) \{(.*?)\};", header_text(), flags=re.S))


class TestAgainstHeader(unittest.TestCase):
    # C enum -> (Python enum, how its members' C names start)
    ENUMS = {
        "bodt_status": (bodt.Status, "BODT_ERR_"),
        "bodt_create_flag": (bodt.CreateFlag, "BODT_CREATE_"),
        "bodt_vertex_class": (bodt.VertexClass, "BODT_VERTEX_"),
        "bodt_measure": (bodt.Measure, "BODT_MEASURE_"),
        "bodt_mode": (bodt.Mode, "BODT_MODE_"),
        "bodt_param": (bodt.Param, "BODT_PARAM_"),
        "bodt_op": (bodt.Op, "BODT_OP_"),
        "bodt_geometry_class": (bodt.GeometryClass, "BODT_GEOMETRY_"),
        "bodt_shape": (bodt.Shape, "BODT_SHAPE_"),
        "bodt_format": (bodt.Format, "BODT_FORMAT_"),
    }

    def test_every_enum_member_with_its_value(self):
        enums = header_enums()
        self.assertEqual(set(enums), set(self.ENUMS))
        for c_name, body in enums.items():
            python_enum, prefix = self.ENUMS[c_name]
            in_header = {
                name.replace("BODT_OK", prefix + "OK").removeprefix(prefix): int(value)
                for name, value in re.findall(r"(BODT_\w+)\s*=\s*(-?\d+)", without_comments(body))
            }
            in_python = {name: int(member) for name, member in python_enum.__members__.items()}
            self.assertEqual(in_python, in_header, c_name)

    def test_integer_defines(self):
        defines = dict(re.findall(r"^#define (BODT_\w+) \(?(-?\d+)\)?$", header_text(), flags=re.M))
        self.assertEqual(int(defines["BODT_OPS_MODE_DEFAULT"]), bodt.OPS_MODE_DEFAULT)
        self.assertEqual(int(defines["BODT_DIHEDRAL_BINS"]), structs.DIHEDRAL_BINS)
        version = ".".join(defines[f"BODT_VERSION_{part}"] for part in ("MAJOR", "MINOR", "PATCH"))
        self.assertEqual(bodt.__version__, version)
        self.assertEqual(bodt.library_version(), version)

    def test_int_params_as_documented(self):
        # each key's comment starts with its type
        comment_and_key = r"/\*\s*(int|double)\b.*?\*/\s*(BODT_PARAM_\w+)\s*="
        typed = re.findall(comment_and_key, header_enums()["bodt_param"], flags=re.S)
        documented = {name.removeprefix("BODT_PARAM_"): kind for kind, name in typed}
        self.assertEqual(set(documented), set(bodt.Param.__members__))
        self.assertEqual({bodt.Param[name] for name, kind in documented.items() if kind == "int"}, bodt.INT_PARAMS)

    def test_every_function_declared(self):
        prototypes = re.findall(r"BODT_API\s[^;]*?\b(bodt_\w+)\s*\(([^)]*)\)\s*;", without_comments(header_text()))
        declared = {name: 0 if params.strip() == "void" else params.count(",") + 1 for name, params in prototypes}
        self.assertEqual(set(_library._FUNCTIONS), set(declared))
        for name, (_, argtypes) in _library._FUNCTIONS.items():
            self.assertEqual(len(argtypes), declared[name], name)

    def test_struct_fields(self):
        mirrors = {
            "bodt_quality": structs.QualityStruct,
            "bodt_step_report": structs.StepReportStruct,
            "bodt_shape_fit": structs.ShapeFitStruct,
            "bodt_recovery_error": structs.RecoveryErrorStruct,
        }
        c_types = {"size_t": ctypes.c_size_t, "int32_t": ctypes.c_int32, "int64_t": ctypes.c_int64,
                   "double": ctypes.c_double}
        lengths = {"BODT_DIHEDRAL_BINS": structs.DIHEDRAL_BINS}
        found = re.findall(r"typedef struct (bodt_\w+) \{(.*?)\} \1;", without_comments(header_text()), flags=re.S)
        self.assertEqual({name for name, _ in found}, set(mirrors))
        for name, body in found:
            in_header = [
                (field, c_types[c_type] * int(lengths.get(length, length)) if length else c_types[c_type])
                for c_type, field, length in re.findall(r"(\w+)\s+(\w+)\s*(?:\[(\w+)\])?\s*;", body)
            ]
            in_python = mirrors[name]._fields_
            self.assertEqual([field for field, _ in in_python], [field for field, _ in in_header], name)
            for (field, ours), (_, theirs) in zip(in_python, in_header):
                self.assertEqual(ctypes.sizeof(ours), ctypes.sizeof(theirs), f"{name}.{field}")
                self.assertEqual(getattr(ours, "_type_", ours), getattr(theirs, "_type_", theirs), f"{name}.{field}")


class TestCommandModes(unittest.TestCase):
    """Mode.from_name against the command `bodt improve --mode NAME`."""

    def test_the_command_names_the_same_modes(self):
        result = subprocess.run([CLI, "improve", "in.mesh", "out.mesh", "--mode", "no-such-mode"],
                                capture_output=True, text=True)
        self.assertNotEqual(result.returncode, 0)
        known = re.search(r"unknown mode 'no-such-mode' \(known: ([^)]*)\)", result.stderr)
        self.assertIsNotNone(known, result.stderr)
        self.assertEqual(known[1].split(", "), list(enums._MODE_NAMES))

    def test_each_name_improves_as_the_command(self):
        """Two steps of each mode by its name give the command's mesh, bit for bit (and each mode its own)."""
        points, tets = meshes.box(3, jitter=0.3, seed=3)
        with tempfile.TemporaryDirectory() as tmp:
            source = os.path.join(tmp, "in.mesh")
            with bodt.Mesh(points, tets) as mesh:
                mesh.write(source)
            results = {}
            for name in enums._MODE_NAMES:
                target = os.path.join(tmp, f"{name}.mesh")
                subprocess.run([CLI, "improve", source, target, "--mode", name, "--iterations", "2", "--quiet"],
                               check=True, capture_output=True)
                with bodt.Mesh.read(source) as mine, bodt.Mesh.read(target) as theirs:
                    mine.improve(max_steps=2, mode=name)
                    np.testing.assert_array_equal(mine.points, theirs.points, name)
                    np.testing.assert_array_equal(mine.tets, theirs.tets, name)
                    results[name] = mine.points
        for (a, pa), (b, pb) in itertools.combinations(results.items(), 2):
            self.assertFalse(pa.shape == pb.shape and np.array_equal(pa, pb), f"{a} and {b} gave the same mesh")


class TestLibraryLookup(unittest.TestCase):
    """Imports of a copy of the package in a fresh interpreter."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def copy_package(self, with_paths: bool) -> str:
        """A copy of the staged package in a temporary directory; its parent directory."""
        ignored = ["__pycache__"] + ([] if with_paths else ["_paths.py"])
        shutil.copytree(PACKAGE_DIR, os.path.join(self.tmp.name, "bodt"), ignore=shutil.ignore_patterns(*ignored))
        return self.tmp.name

    def run_import(self, python_path: str, **env: str) -> subprocess.CompletedProcess:
        """``import bodt`` in a new interpreter; prints the package's and the library's paths."""
        environment = {k: v for k, v in os.environ.items() if k not in ("BODT_LIBRARY", "LD_LIBRARY_PATH")}
        environment.update(PYTHONPATH=python_path, **env)
        code = "import bodt; print(bodt.__file__); print(bodt.library_path())"
        return subprocess.run([sys.executable, "-c", code], env=environment, capture_output=True, text=True)

    def assertImported(self, result: subprocess.CompletedProcess, package_dir: str, library: str) -> None:
        self.assertEqual(result.returncode, 0, result.stderr)
        package_file, library_path = result.stdout.split()
        self.assertTrue(os.path.samefile(os.path.dirname(package_file), package_dir))
        self.assertEqual(library_path, library)

    def assertImportError(self, result: subprocess.CompletedProcess, message: str) -> None:
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(f"ImportError: {message}", result.stderr)

    def test_this_process_found_the_build_tree(self):
        self.assertTrue(os.path.samefile(os.path.dirname(bodt.__file__), PACKAGE_DIR))
        self.assertTrue(os.path.samefile(bodt.library_path(), LIBRARY))

    def test_environment_variable_first(self):
        parent = self.copy_package(with_paths=True)
        self.assertImported(self.run_import(parent, BODT_LIBRARY=LIBRARY), os.path.join(parent, "bodt"), LIBRARY)
        missing = os.path.join(self.tmp.name, "nowhere", "libbodt.so.0")
        self.assertImportError(
            self.run_import(parent, BODT_LIBRARY=missing),
            f"bodt: cannot load {missing} (from the environment variable BODT_LIBRARY)",
        )

    def test_paths_next_to_the_package(self):
        parent = os.path.dirname(PACKAGE_DIR)
        result = self.run_import(parent)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertTrue(os.path.samefile(result.stdout.split()[1], LIBRARY))

    def test_library_in_the_package_directory(self):
        parent = self.copy_package(with_paths=False)
        inside = os.path.join(parent, "bodt", _library.SONAME)
        shutil.copy(LIBRARY, inside)
        self.assertImported(self.run_import(parent), os.path.join(parent, "bodt"), inside)

    def test_system_library_path_last(self):
        parent = self.copy_package(with_paths=False)
        result = self.run_import(parent, LD_LIBRARY_PATH=os.path.dirname(LIBRARY))
        self.assertImported(result, os.path.join(parent, "bodt"), _library.SONAME)
        if ctypes.util.find_library("bodt"):
            self.skipTest("a libbodt is installed on this system: it would be found")
        self.assertImportError(self.run_import(parent), f"bodt: cannot find {_library.SONAME}")

    def test_major_version_checked(self):
        parent = self.copy_package(with_paths=True)
        with open(os.path.join(parent, "bodt", "_version.py"), "w") as f:
            f.write('__version__ = "99.0.0"\n')
        self.assertImportError(
            self.run_import(parent, BODT_LIBRARY=LIBRARY),
            f"bodt: the package 99.0.0 needs libbodt 99.x, but {LIBRARY} is libbodt {bodt.library_version()}",
        )


if __name__ == "__main__":
    unittest.main()
