// Broken files for the tests of the readers (test_io_vtk,
// test_io_vtu_compressed): what a reader must make of one (a
// bodt::Error(BODT_ERR_IO), with no allocation over kAllocLimit), and random
// changes to valid files, which must read to consistent MeshData or give
// such an error that says where.  Includes alloc_probe.hpp, so it too goes
// in one file per program.
#pragma once

#include "common/error.hpp"
#include "io/mesh_io.hpp"

#include "bodt.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>

#include "core_checks.hpp"
#include "file_text.hpp"

#include "alloc_probe.hpp"

namespace io_test {

// Writes `text` to `path` and reads it with read(path), which must refuse it
// with a bodt::Error(BODT_ERR_IO) and allocate no more than kAllocLimit:
// returns what is wrong ("" when nothing), and the error's message in
// `message`.
template <class Read>
std::string refusal_problem(const std::string& path, const std::string& text, Read read, std::string& message) {
    write_text(path, text);
    g_largest_alloc = 0;
    try {
        read(path);
        return "read without an error";
    } catch (const bodt::Error& e) {
        message = e.what();
        if (e.status() != BODT_ERR_IO) return "status " + std::to_string(e.status()) + ": " + message;
    } catch (const std::exception& e) {
        return std::string("not a bodt::Error: ") + e.what();
    }
    const size_t largest = g_largest_alloc;
    if (largest > kAllocLimit)
        return "an allocation of " + std::to_string(largest) + " bytes for a file of " + std::to_string(text.size());
    return {};
}

// ------------------------------------------------------------ mutations

// xorshift64*: the same sequence everywhere.
struct Bits {
    uint64_t s;  // the state, not 0
    uint64_t next() {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        return s * 2685821657736338717ull;
    }
    size_t below(size_t n) { return static_cast<size_t>(next() % n); }
};

// 1 to 3 changes to `s` at random places: a byte made random or a digit, the
// text cut there, 1 to 8 bytes erased, or one of `tokens` inserted (at least
// one byte, so that "\0" inserts a NUL).
template <size_t N>
void mutate(std::string& s, Bits& r, const char* const (&tokens)[N]) {
    const size_t changes = 1 + r.below(3);
    for (size_t k = 0; k < changes && !s.empty(); ++k) {
        const size_t at = r.below(s.size());
        switch (r.below(5)) {
            case 0: s[at] = static_cast<char>(r.next()); break;
            case 1: s[at] = static_cast<char>('0' + r.below(10)); break;
            case 2: s.resize(at); break;
            case 3: s.erase(at, 1 + r.below(8)); break;
            default: {
                const char* t = tokens[r.below(N)];
                s.insert(at, t, std::max<size_t>(1, std::strlen(t)));
            }
        }
    }
}

// A MeshData a reader returned is consistent: base 0, whole points and tets
// (at least one), one region per tet or none, one marker per triangle, one
// ref per feature edge, one ref per vertex or none, every vertex index in
// range, every coordinate finite.
inline void check_read_mesh(const char* what, const bodt::MeshData& m, int iter) {
    const int64_t nv = static_cast<int64_t>(m.xyz.size() / 3);
    CHECK(m.base == 0 && m.xyz.size() % 3 == 0 && m.tets.size() % 4 == 0 && !m.tets.empty(), "iteration %d: sizes",
          iter);
    CHECK(m.regions.empty() || m.regions.size() == m.tets.size() / 4, "iteration %d: regions", iter);
    CHECK(m.tri_markers.size() * 3 == m.triangles.size(), "iteration %d: markers", iter);
    CHECK(m.edge_refs.size() * 2 == m.feature_edges.size(), "iteration %d: edge refs", iter);
    CHECK(m.vertex_refs.empty() || static_cast<int64_t>(m.vertex_refs.size()) == nv, "iteration %d: refs", iter);
    for (const auto* list : {&m.tets, &m.triangles, &m.feature_edges, &m.fixed, &m.corners})
        for (int32_t v : *list) CHECK(v >= 0 && v < nv, "iteration %d: vertex %d of %lld", iter, v, (long long)nv);
    for (double x : m.xyz) CHECK(std::isfinite(x), "iteration %d: coordinate %g", iter, x);
}

// Writes `text` to `path` and reads it with read(path): it must give a
// MeshData that passes check_read_mesh or throw a bodt::Error(BODT_ERR_IO)
// whose message positioned(message) accepts (it says where in the file), with
// no allocation over kAllocLimit.  True when the file was read.
template <class Read, class Positioned>
bool check_mutant(const char* what, int iter, const std::string& path, const std::string& text, Read read,
                  Positioned positioned) {
    write_text(path, text);
    g_largest_alloc = 0;
    bool was_read = false;
    try {
        check_read_mesh(what, read(path), iter);
        was_read = true;
    } catch (const bodt::Error& e) {
        const std::string m = e.what();
        CHECK(e.status() == BODT_ERR_IO, "iteration %d: status %d: %s", iter, e.status(), m.c_str());
        CHECK(positioned(m), "iteration %d: no position in '%s'", iter, m.c_str());
    } catch (const std::exception& e) {
        CHECK(false, "iteration %d: not a bodt::Error: %s", iter, e.what());
    }
    CHECK(g_largest_alloc <= kAllocLimit, "iteration %d: an allocation of %zu bytes", iter,
          static_cast<size_t>(g_largest_alloc));
    return was_read;
}

}  // namespace io_test
