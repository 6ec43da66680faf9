"""bodt.cffi_cdef() through cffi's ABI mode: the declarations the C compiler sees in bodt.h, and they work.

BODT_TEST_HEADER is the bodt.h next to the library, BODT_TEST_LIBRARY that
libbodt.so.<major> and BODT_TEST_CC the C compiler (set by CTest): the
build tree's (python.package) or the installed ones (python.cffi_header).
The reference for the declarations is the header after the C preprocessor,
given only empty <stddef.h> and <stdint.h> (cffi knows size_t and the intN_t
types, and cannot parse the C library's own headers).
"""

import ctypes
import math
import os
import re
import subprocess
import tempfile
import unittest

import cffi

import bodt
from bodt import _cdef, structs

HEADER = os.environ["BODT_TEST_HEADER"]
LIBRARY = os.environ["BODT_TEST_LIBRARY"]
CC = os.environ["BODT_TEST_CC"]


def preprocessed_header() -> str:
    """bodt.h after ``cc -E -P -dD``, with the integer BODT_ #defines and without the others."""
    with tempfile.TemporaryDirectory() as include_dir:
        for name in ("stddef.h", "stdint.h"):
            open(os.path.join(include_dir, name), "w").close()
        environment = {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}  # no ASan runtime in cc
        output = subprocess.run(
            [CC, "-E", "-P", "-dD", "-nostdinc", "-I", include_dir, HEADER],
            env=environment, check=True, capture_output=True, text=True,
        ).stdout
    lines = []
    for line in output.splitlines():
        if line.startswith("#"):
            constant = re.fullmatch(r"#define (BODT_\w+) \(?(-?\d+)\)?\s*", line)
            if constant:
                lines.append(f"#define {constant[1]} {constant[2]}")
        else:
            lines.append(line)
    return "\n".join(lines)


def declared(ffi: cffi.FFI, lib: object) -> dict[str, object]:
    """What an FFI knows: each name on the library (function type or constant), each type's layout."""
    found: dict[str, object] = {}
    for name in dir(lib):
        value = getattr(lib, name)
        found[name] = ffi.typeof(value).cname if isinstance(value, ffi.CData) else value
    typedefs, structs_, unions = ffi.list_types()
    for name in typedefs:
        found[f"typedef {name}"] = ffi.typeof(name).cname
    for name in structs_:
        ctype = ffi.typeof(f"struct {name}")
        fields = ctype.fields or []  # None for the opaque bodt_mesh
        found[f"struct {name}"] = [(field, f.type.cname, f.offset) for field, f in fields]
        if fields:
            found[f"sizeof struct {name}"] = ffi.sizeof(ctype)
    found["unions"] = unions
    return found


class TestDeclarations(unittest.TestCase):
    def test_the_compiler_sees_the_same(self):
        ours, theirs = cffi.FFI(), cffi.FFI()
        ours.cdef(bodt.cffi_cdef())
        theirs.cdef(preprocessed_header())
        mine, reference = declared(ours, ours.dlopen(LIBRARY)), declared(theirs, theirs.dlopen(LIBRARY))
        self.assertEqual(mine, reference)
        self.assertIn("bodt_run", mine)  # the comparison is of something
        self.assertIn("BODT_OPS_MODE_DEFAULT", mine)

    def test_shipped_header_is_this_header(self):
        """cffi_cdef() reads the package's copy of bodt.h (staged, or installed): it must be the header itself."""
        with open(_cdef.HEADER, "rb") as shipped, open(HEADER, "rb") as header:
            self.assertEqual(shipped.read(), header.read())

    def test_conditions_and_macros(self):
        header = """
            #ifndef GUARD
            #define GUARD
            #include <stdint.h>
            #define API
            #define COUNT (3)
            #define NEGATIVE (-2)
            #if defined(GUARD) && defined(__GNUC__)
            int not_this(void);
            #else
            API int32_t kept(int32_t x[COUNT]);  /* #not a directive */
            #endif
            #if defined( GUARD )
            #ifdef __GNUC__
            int nor_this(void);
            #endif
            #else
            int nor_that(void);
            #endif
            #ifdef __cplusplus
            extern "C" {
            #endif
            #endif
        """
        self.assertEqual(
            _cdef.declarations(header).split("\n"),
            ["#define COUNT 3", "#define NEGATIVE -2", "            int32_t kept(int32_t x[COUNT]);", ""],
        )

    def test_refuses_what_it_does_not_know(self):
        for header, message in [
            ("#define MAX(a, b) ((a) > (b) ? (a) : (b))", "does not handle '#define MAX(a, b)"),
            ('#include "other.h"', "does not handle '#include \"other.h\"'"),
            ("#if VERSION > 2\n#endif", "cannot evaluate '#if VERSION > 2'"),
            ("#if (defined(A)\n#endif", "cannot evaluate '#if (defined(A)'"),
            ("#if defined(A) || !defined(B)\n#endif", "cannot evaluate '#if defined(A) || !defined(B)'"),
            ("#ifdef A\n#elif defined(B)\n#endif", "does not handle '#elif defined(B)'"),
            ("#else", "#else without #if"),
            ("#ifdef A", "#if without #endif"),
            ("#endif", "#endif without #if"),
            ("#pragma once", "does not handle '#pragma once'"),
        ]:
            with self.assertRaisesRegex(RuntimeError, re.escape(message)):
                _cdef.declarations(header)


class TestCffiHeader(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.ffi = cffi.FFI()
        cls.ffi.cdef(bodt.cffi_cdef())
        cls.lib = cls.ffi.dlopen(bodt.library_path())

    def test_the_library_the_package_loaded(self):
        self.assertTrue(os.path.samefile(bodt.library_path(), LIBRARY))

    def message(self, mesh) -> str:
        return self.ffi.string(self.lib.bodt_mesh_last_error(mesh)).decode()

    def create(self, points: list[float], tets: list[int]):
        ffi, lib = self.ffi, self.lib
        handle = ffi.new("bodt_mesh **")
        status = lib.bodt_mesh_create(len(points) // 3, ffi.new("double[]", points), len(tets) // 4,
                                      ffi.new("int32_t[]", tets), 0, handle)
        return status, handle[0]

    def quality(self, mesh):
        q = self.ffi.new("bodt_quality *", {"size": self.ffi.sizeof("bodt_quality")})
        self.assertEqual(self.lib.bodt_mesh_quality(mesh, q), self.lib.BODT_OK, self.message(mesh))
        return q

    def test_version(self):
        lib = self.lib
        self.assertEqual(lib.BODT_VERSION_NUMBER, lib.bodt_version_number())
        self.assertEqual(lib.BODT_VERSION_NUMBER,
                         lib.BODT_VERSION_MAJOR * 10000 + lib.BODT_VERSION_MINOR * 100 + lib.BODT_VERSION_PATCH)
        self.assertEqual(self.ffi.string(lib.bodt_version_string()).decode(),
                         f"{lib.BODT_VERSION_MAJOR}.{lib.BODT_VERSION_MINOR}.{lib.BODT_VERSION_PATCH}")

    def test_status_strings(self):
        lib = self.lib
        self.assertEqual(self.ffi.string(lib.bodt_status_string(lib.BODT_OK)), b"ok")
        self.assertEqual(self.ffi.string(lib.bodt_status_string(lib.BODT_ERR_BAD_MESH)), b"bad mesh")
        self.assertEqual(self.ffi.string(lib.bodt_status_string(lib.BODT_ERR_CANCELLED)), b"cancelled")

    def test_create_step_quality_run(self):
        ffi, lib = self.ffi, self.lib
        points = [1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0.45, 0.3, 0.2]
        tets = [6, 0, 2, 4, 6, 2, 1, 4, 6, 3, 0, 4, 6, 1, 3, 4, 6, 2, 0, 5, 6, 1, 2, 5, 6, 0, 3, 5, 6, 3, 1, 5]
        status, mesh = self.create(points, tets)
        self.assertEqual(status, lib.BODT_OK, self.message(ffi.NULL))
        self.addCleanup(lib.bodt_mesh_destroy, mesh)
        before = self.quality(mesh)
        self.assertEqual((before.num_vertices, before.num_tets, before.num_boundary_faces), (7, 8, 8))
        self.assertAlmostEqual(before.volume, 4.0 / 3.0, delta=1e-12)
        self.assertEqual(sum(before.dihedral_histogram), 6 * 8)
        self.assertEqual(len(before.dihedral_histogram), lib.BODT_DIHEDRAL_BINS)

        report = ffi.new("bodt_step_report *", {"size": ffi.sizeof("bodt_step_report")})
        self.assertEqual(lib.bodt_step(mesh, report), lib.BODT_OK, self.message(mesh))
        self.assertEqual(report.step, 1)
        self.assertEqual(report.vertices_moved, 1)
        after = self.quality(mesh)
        self.assertGreater(after.min_dihedral, before.min_dihedral)
        self.assertEqual(report.min_dihedral, after.min_dihedral)

        steps = []

        @ffi.callback("bodt_step_callback")
        def stop(step_report, user_data):
            steps.append(step_report.step)
            return 1

        self.assertEqual(lib.bodt_run(mesh, 20, stop, ffi.NULL), lib.BODT_ERR_CANCELLED)
        self.assertEqual(steps, [2])
        self.assertEqual(self.message(mesh), "cancelled by the callback after step 2")

    def test_error_message(self):
        lib = self.lib
        points = [1, 1, 1, 1, -1, -1, -1, -1, 1, -1, 1, -1]
        status, mesh = self.create(points, [0, 1, 2, 4])
        self.assertEqual(status, lib.BODT_ERR_BAD_MESH)
        self.assertEqual(mesh, self.ffi.NULL)
        self.assertEqual(
            self.message(self.ffi.NULL), "tet 0 uses vertex 4, but the mesh has 4 vertices (numbered from 0)"
        )
        status, mesh = self.create(points, [0, 1, 2, 3])
        self.assertEqual(status, lib.BODT_OK)
        self.addCleanup(lib.bodt_mesh_destroy, mesh)
        self.assertAlmostEqual(self.quality(mesh).min_dihedral, math.degrees(math.acos(1.0 / 3.0)), delta=1e-10)
        self.assertEqual(lib.bodt_set_param_double(mesh, lib.BODT_PARAM_OPS, 1.0), lib.BODT_ERR_INVALID_ARGUMENT)
        self.assertIn("BODT_PARAM_OPS is an int parameter", self.message(mesh))

    def test_the_package_agrees_with_cffi(self):
        """The bodt package's enums and struct mirrors, against cffi's reading of the header."""
        prefixes = {
            bodt.Status: "BODT_ERR_", bodt.CreateFlag: "BODT_CREATE_", bodt.VertexClass: "BODT_VERTEX_",
            bodt.Measure: "BODT_MEASURE_", bodt.Mode: "BODT_MODE_", bodt.Param: "BODT_PARAM_", bodt.Op: "BODT_OP_",
            bodt.GeometryClass: "BODT_GEOMETRY_", bodt.Shape: "BODT_SHAPE_", bodt.Format: "BODT_FORMAT_",
        }
        for enum, prefix in prefixes.items():
            for name, member in enum.__members__.items():
                c_name = "BODT_OK" if member is bodt.Status.OK else prefix + name
                self.assertEqual(getattr(self.lib, c_name), member, c_name)
        self.assertEqual(self.lib.BODT_OPS_MODE_DEFAULT, bodt.OPS_MODE_DEFAULT)
        mirrors = {
            "bodt_quality": structs.QualityStruct,
            "bodt_step_report": structs.StepReportStruct,
            "bodt_shape_fit": structs.ShapeFitStruct,
            "bodt_recovery_error": structs.RecoveryErrorStruct,
        }
        for c_name, mirror in mirrors.items():
            self.assertEqual(ctypes.sizeof(mirror), self.ffi.sizeof(c_name), c_name)
            for field, _ in mirror._fields_:
                self.assertEqual(getattr(mirror, field).offset, self.ffi.offsetof(c_name, field), f"{c_name}.{field}")


if __name__ == "__main__":
    unittest.main()
