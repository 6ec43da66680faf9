"""`pip install ./bindings/python` as the README gives it for Debian 12, offline: then the package improves a mesh.

The commands, run from the source tree as a user would:

    python3 -m venv --system-site-packages VENV
    VENV/bin/pip install --no-index ./bindings/python

with no pip configuration of this machine (as on a fresh one).  Set by CTest:
BODT_TEST_SOURCE_DIR the source tree, BODT_TEST_VENV where to make the
environment (in the build tree), BODT_TEST_LIBRARY the built libbodt.so,
BODT_TEST_INSTALLED_LIBDIR the library directory consumers.install installed
into (a stand-in for /usr/local/lib after `cmake --install` and ldconfig),
BODT_TEST_PACKAGE_DIR the package as CMake stages it.
"""

import os
import shutil
import subprocess
import sys
import unittest

SOURCE_DIR = os.environ["BODT_TEST_SOURCE_DIR"]
VENV = os.environ["BODT_TEST_VENV"]
LIBRARY = os.environ["BODT_TEST_LIBRARY"]
INSTALLED_LIBDIR = os.environ["BODT_TEST_INSTALLED_LIBDIR"]
PACKAGE_DIR = os.environ["BODT_TEST_PACKAGE_DIR"]
PROJECT = os.path.join(SOURCE_DIR, "bindings", "python")
QUICKSTART_LINE = "min dihedral: 2.89 -> 54.74 degrees\n"


def clean_environment(**extra: str) -> dict[str, str]:
    """This process's environment without pip's settings, the package path and the library choices."""
    dropped = ("PYTHONPATH", "BODT_LIBRARY", "LD_LIBRARY_PATH", "VIRTUAL_ENV")
    environment = {k: v for k, v in os.environ.items() if not k.startswith("PIP_") and k not in dropped}
    environment["PIP_CONFIG_FILE"] = os.devnull  # no pip.conf of this machine either
    environment.update(extra)
    return environment


def tree(directory: str) -> dict[str, float]:
    """Every file under ``directory`` with its modification time."""
    return {
        os.path.join(root, name): os.stat(os.path.join(root, name)).st_mtime
        for root, _, names in os.walk(directory)
        for name in names
    }


class TestPipInstall(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(VENV, ignore_errors=True)
        before = tree(PROJECT)
        subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", VENV],
                       env=clean_environment(), check=True, capture_output=True, text=True)
        pip = [os.path.join(VENV, "bin", "pip"), "install", "--no-index", "./bindings/python"]
        cls.pip = subprocess.run(pip, cwd=SOURCE_DIR, env=clean_environment(), capture_output=True, text=True)
        cls.source_changes = {path for path, mtime in tree(PROJECT).items() if before.get(path) != mtime}
        cls.python = os.path.join(VENV, "bin", "python")

    def run_python(self, *args: str, **env: str) -> subprocess.CompletedProcess:
        return subprocess.run([self.python, *args], cwd=SOURCE_DIR, env=clean_environment(**env),
                              capture_output=True, text=True)

    def test_pip_installed_the_package(self):
        self.assertEqual(self.pip.returncode, 0, self.pip.stdout + self.pip.stderr)
        self.assertIn("Successfully installed bodt-", self.pip.stdout)
        self.assertEqual(self.source_changes, set())  # the build wrote nothing into the source tree

    def test_the_package_as_cmake_stages_it(self):
        """The same files, but for _paths.py (where CMake's build put the library)."""
        code = "import bodt, os; print(os.path.dirname(bodt.__file__)); print(bodt.__version__)"
        result = self.run_python("-c", code, BODT_LIBRARY=LIBRARY)
        self.assertEqual(result.returncode, 0, result.stderr)
        package_dir, version = result.stdout.split()
        self.assertEqual(os.path.commonpath([package_dir, VENV]), VENV)

        def files(directory: str) -> set[str]:
            return {name for name in os.listdir(directory) if name != "__pycache__"}

        self.assertEqual(files(package_dir), files(PACKAGE_DIR) - {"_paths.py"})
        for name in files(package_dir) - {"_version.py"}:
            with open(os.path.join(package_dir, name), "rb") as installed:
                content = installed.read()
            with open(os.path.join(PACKAGE_DIR, name), "rb") as staged:
                self.assertEqual(content, staged.read(), name)
        with open(os.path.join(PACKAGE_DIR, "_version.py")) as staged:
            self.assertIn(f'__version__ = "{version}"\n', staged.read())

    def test_quickstart_with_bodt_library(self):
        result = self.run_python("examples/quickstart.py", BODT_LIBRARY=LIBRARY)
        self.assertEqual((result.returncode, result.stdout), (0, QUICKSTART_LINE), result.stderr)

    def test_cffi_quickstart(self):
        result = self.run_python("examples/quickstart_cffi.py", BODT_LIBRARY=LIBRARY)
        self.assertEqual((result.returncode, result.stdout), (0, QUICKSTART_LINE), result.stderr)

    def test_library_from_the_system_path(self):
        code = "import bodt; print(bodt.library_path())"
        result = self.run_python("-c", code, LD_LIBRARY_PATH=INSTALLED_LIBDIR)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertRegex(result.stdout, r"^libbodt\.so\.\d+\n$")  # the soname: found by the dynamic loader
        result = self.run_python("examples/quickstart.py", LD_LIBRARY_PATH=INSTALLED_LIBDIR)
        self.assertEqual((result.returncode, result.stdout), (0, QUICKSTART_LINE), result.stderr)

    def test_no_library_says_how_to_give_it(self):
        result = self.run_python("-c", "import ctypes.util; print(ctypes.util.find_library('bodt'))")
        if result.stdout.strip() != "None":
            self.skipTest("a libbodt is installed on this system: it would be found")
        result = self.run_python("-c", "import bodt")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("ImportError: bodt: cannot find libbodt.so.", result.stderr)
        self.assertIn("set BODT_LIBRARY to its path", result.stderr)


if __name__ == "__main__":
    unittest.main()
