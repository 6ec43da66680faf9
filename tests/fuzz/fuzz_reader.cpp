// libFuzzer target for the mesh file readers of src/io.  One source, built
// once per reader with -DBODT_FUZZ_FORMAT=<n> (tests/fuzz/CMakeLists.txt):
//   1 read_medit          (.mesh)
//   2 read_medit_binary   (.meshb)
//   3 read_tetgen         (.node/.ele/.face)
//   4 read_gmsh           (.msh)
//   5 read_vtu            (.vtu)
//   6 read_vtk            (.vtk, VTK legacy: ASCII and big-endian binary)
// The readers take a path, so each input is written to a per-process
// temporary directory first.  TetGen reads up to three files: the input is
// split at the first and the second '@' byte (a byte that has no meaning in
// the format) into the .node, the .ele and the optional .face file; without
// a second '@' there is no .face file, without any '@' the .ele is empty.
//
// bodt::Error is the expected outcome of a bad file.  Anything else (another
// exception, a sanitizer report, an allocation past -malloc_limit_mb) is a
// bug.  On success the MeshData must be consistent (sizes, every index in
// [base, base + nverts)), and for Gmsh its model must fit the mesh and the
// writer's layout of it (gmsh_layout.hpp) put every element into an entity
// of its dimension, else abort().
#include "io/gmsh.hpp"
#include "io/gmsh_layout.hpp"
#include "io/gmsh_model.hpp"
#include "io/medit_binary.hpp"
#include "io/mesh_io.hpp"
#include "io/vtk_legacy.hpp"
#include "io/vtu.hpp"

#include "common/error.hpp"
#include "fuzz_check.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#ifndef BODT_FUZZ_FORMAT
#error "compile with -DBODT_FUZZ_FORMAT=1..6"
#endif

namespace {

// BODT_FUZZ_VERBOSE=1: print each outcome (to check seeds and replay inputs).
bool verbose() {
    static const bool on = [] {
        const char* v = std::getenv("BODT_FUZZ_VERBOSE");
        return v && *v && std::strcmp(v, "0") != 0;
    }();
    return on;
}

void remove_temp_dir();

const std::string& temp_dir() {
    static const std::string dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/bodt_fuzz_XXXXXX";
        if (!mkdtemp(&pattern[0])) {
            std::perror("fuzz_reader: mkdtemp");
            std::abort();
        }
        return pattern;
    }();
    static const bool cleanup = (std::atexit(remove_temp_dir), true);
    (void)cleanup;
    return dir;
}

// At a normal exit; a crash leaves the directory (under $TMPDIR) behind.
void remove_temp_dir() {
    for (const char* ext : {".mesh", ".meshb", ".node", ".ele", ".face", ".msh", ".vtu", ".vtk"})
        std::remove((temp_dir() + "/in" + ext).c_str());
    rmdir(temp_dir().c_str());
}

void check_index(int32_t v, int base, size_t nverts) {
    FUZZ_CHECK(int64_t(v) >= base && int64_t(v) < int64_t(base) + int64_t(nverts));
}

#if BODT_FUZZ_FORMAT == 4
// The model fits the arrays, and the writer's layout of the mesh puts every
// element and node into an entity of its dimension.
void check_gmsh(const bodt::MeshData& d) {
    FUZZ_CHECK(d.gmsh && d.gmsh->fits(d.xyz.size() / 3));
    FUZZ_CHECK(d.gmsh->tet_entity.size() == d.tets.size() / 4);
    const bodt::GmshLayout l = bodt::layout_gmsh(d);
    const size_t counts[4] = {l.points.size(), d.feature_edges.size() / 2, d.tri_markers.size(), d.tets.size() / 4};
    for (int dim = 0; dim < 4; ++dim) {
        FUZZ_CHECK(l.element_entity[dim].size() == counts[dim]);
        for (const int32_t e : l.element_entity[dim])
            FUZZ_CHECK(e == -1 || (e >= 0 && size_t(e) < l.entities.size() && l.entities[size_t(e)].dim == dim));
    }
    for (const int32_t e : l.element_entity[3]) FUZZ_CHECK(e >= 0);
    FUZZ_CHECK(l.node_entity.size() == d.xyz.size() / 3);
    for (const int32_t e : l.node_entity) FUZZ_CHECK(e >= 0 && size_t(e) < l.entities.size());
}
#endif

void check(const bodt::MeshData& d) {
    FUZZ_CHECK(d.base == 0 || d.base == 1);
    FUZZ_CHECK(d.xyz.size() % 3 == 0);
    FUZZ_CHECK(d.tets.size() % 4 == 0);
    FUZZ_CHECK(d.triangles.size() % 3 == 0);
    FUZZ_CHECK(d.feature_edges.size() % 2 == 0);
    const size_t nverts = d.xyz.size() / 3, ntets = d.tets.size() / 4;
    FUZZ_CHECK(d.regions.empty() || d.regions.size() == ntets);
    FUZZ_CHECK(d.tri_markers.size() == d.triangles.size() / 3);
    FUZZ_CHECK(d.vertex_refs.empty() || d.vertex_refs.size() == nverts);
    FUZZ_CHECK(d.edge_refs.empty() || d.edge_refs.size() == d.feature_edges.size() / 2);
    for (double x : d.xyz) FUZZ_CHECK(std::isfinite(x));
    for (int32_t v : d.tets) check_index(v, d.base, nverts);
    for (int32_t v : d.triangles) check_index(v, d.base, nverts);
    for (int32_t v : d.fixed) check_index(v, d.base, nverts);
    for (int32_t v : d.corners) check_index(v, d.base, nverts);
    for (int32_t v : d.feature_edges) check_index(v, d.base, nverts);
    // tet_fields are written, never read back.
    FUZZ_CHECK(d.tet_fields.empty());
#if BODT_FUZZ_FORMAT == 4
    check_gmsh(d);
#else
    FUZZ_CHECK(!d.gmsh);
#endif
}

bodt::MeshData read(const uint8_t* data, size_t size) {
    const std::string stem = temp_dir() + "/in";
#if BODT_FUZZ_FORMAT == 1
    write_file(stem + ".mesh", data, size);
    return bodt::read_medit(stem + ".mesh");
#elif BODT_FUZZ_FORMAT == 2
    write_file(stem + ".meshb", data, size);
    return bodt::read_medit_binary(stem + ".meshb");
#elif BODT_FUZZ_FORMAT == 3
    const uint8_t* end = data + size;
    const uint8_t* at1 = size ? static_cast<const uint8_t*>(std::memchr(data, '@', size)) : nullptr;
    const uint8_t* at2 = at1 ? static_cast<const uint8_t*>(std::memchr(at1 + 1, '@', size_t(end - at1 - 1))) : nullptr;
    const uint8_t* node_end = at1 ? at1 : end;
    const uint8_t* ele_begin = at1 ? at1 + 1 : end;
    const uint8_t* ele_end = at2 ? at2 : end;
    write_file(stem + ".node", data, size_t(node_end - data));
    write_file(stem + ".ele", ele_begin, size_t(ele_end - ele_begin));
    if (at2)
        write_file(stem + ".face", at2 + 1, size_t(end - at2 - 1));
    else
        std::remove((stem + ".face").c_str());
    return bodt::read_tetgen(stem + ".node");
#elif BODT_FUZZ_FORMAT == 4
    write_file(stem + ".msh", data, size);
    return bodt::read_gmsh(stem + ".msh");
#elif BODT_FUZZ_FORMAT == 5
    write_file(stem + ".vtu", data, size);
    return bodt::read_vtu(stem + ".vtu");
#elif BODT_FUZZ_FORMAT == 6
    write_file(stem + ".vtk", data, size);
    return bodt::read_vtk(stem + ".vtk");
#else
#error "BODT_FUZZ_FORMAT must be 1..6"
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    bodt::MeshData d;
    try {
        d = read(data, size);
    } catch (const bodt::Error& e) {
        // Expected for a bad file; the message must name something.
        FUZZ_CHECK(e.what()[0] != '\0');
        if (verbose()) std::fprintf(stderr, "fuzz_reader: error %d: %s\n", e.status(), e.what());
        return 0;
    }
    check(d);
    if (verbose())
        std::fprintf(stderr, "fuzz_reader: read %zu vertices, %zu tets, %zu triangles, base %d\n", d.xyz.size() / 3,
                     d.tets.size() / 4, d.tri_markers.size(), d.base);
    return 0;
}
