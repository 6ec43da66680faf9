"""quickstart_cffi.py: libbodt's C API from Python through cffi (ABI mode), declared by the bodt package."""
import cffi

import bodt

ffi = cffi.FFI()
ffi.cdef(bodt.cffi_cdef())  # bodt.h's types, enums, functions and integer #defines
lib = ffi.dlopen(bodt.library_path())  # the libbodt.so the package loaded

# An octahedron cut into 8 tets around vertex 6, which sits off-centre.
points = [1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0.45, 0.3, 0.2]
tets = [6, 0, 2, 4, 6, 2, 1, 4, 6, 3, 0, 4, 6, 1, 3, 4, 6, 2, 0, 5, 6, 1, 2, 5, 6, 0, 3, 5, 6, 3, 1, 5]
mesh = ffi.new("bodt_mesh **")
if lib.bodt_mesh_create(7, ffi.new("double[]", points), 8, ffi.new("int32_t[]", tets), 0, mesh) != lib.BODT_OK:
    raise SystemExit(ffi.string(lib.bodt_mesh_last_error(ffi.NULL)).decode())
quality = ffi.new("bodt_quality *", {"size": ffi.sizeof("bodt_quality")})
lib.bodt_mesh_quality(mesh[0], quality)
before = quality.min_dihedral
status = lib.bodt_run(mesh[0], 20, ffi.NULL, ffi.NULL)  # B-ODT, the default mode
if status != lib.BODT_OK:
    raise SystemExit(ffi.string(lib.bodt_mesh_last_error(mesh[0])).decode())
lib.bodt_mesh_quality(mesh[0], quality)
print(f"min dihedral: {before:.2f} -> {quality.min_dihedral:.2f} degrees")
lib.bodt_mesh_destroy(mesh[0])
