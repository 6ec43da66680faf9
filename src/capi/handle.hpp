// What every C API file shares: the handle behind the opaque bodt_mesh,
// and the wrappers that check arguments and turn every exception into a
// status code and a message.  The core numbers vertices and tets in its own
// (curve) order; every index crosses the API through TetMesh::caller_vertex,
// internal_vertex and caller_tet, so the caller sees only theirs.
#pragma once

#include "bodt.h"

#include "common/error.hpp"
#include "mesh/region_surfaces.hpp"
#include "mesh/tet_mesh.hpp"
#include "pipeline/improver.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <new>
#include <string>

namespace bodt {
struct GmshModel;
}

struct bodt_mesh {
    bodt::TetMesh mesh;
    bodt::RegionSurfaces surfaces;
    bodt::Improver improver;
    int index_base = 0;
    bool flipped = false;
    // The structure of the Gmsh file the mesh was read from (names,
    // entities), kept unchanged for writing it back to a .msh
    // (io/gmsh_model.hpp; other formats ignore it); null for any other source.
    std::shared_ptr<const bodt::GmshModel> gmsh_model;
    mutable std::string last_error;
};

namespace bodt_capi {

using bodt::Error;

// Message of the last failed creation (or call on a NULL handle) on this
// thread: per-thread, so threads never share it.
inline thread_local std::string t_thread_error;

inline std::string& error_slot(const bodt_mesh* m) { return m ? m->last_error : t_thread_error; }

// Runs `f`, translating exceptions; the message goes to the handle (or to the
// thread's slot when there is no handle yet).
template <class F>
int guarded(const bodt_mesh* m, F&& f) {
    std::string& slot = error_slot(m);
    try {
        f();
        slot.clear();
        return BODT_OK;
    } catch (const Error& e) {
        slot = e.what();
        return e.status();
    } catch (const std::bad_alloc&) {
        slot = "out of memory";
        return BODT_ERR_OUT_OF_MEMORY;
    } catch (const std::exception& e) {
        slot = std::string("internal error: ") + e.what();
        return BODT_ERR_NUMERIC;
    } catch (...) {
        slot = "internal error";
        return BODT_ERR_NUMERIC;
    }
}

// For functions taking a handle: refuse NULL before anything else.
template <class F>
int with_mesh(const bodt_mesh* m, F&& f) {
    if (!m) {
        t_thread_error = "mesh is NULL";
        return BODT_ERR_INVALID_ARGUMENT;
    }
    return guarded(m, std::forward<F>(f));
}

inline void require(bool ok, const char* message) {
    if (!ok) throw Error(BODT_ERR_INVALID_ARGUMENT, message);
}

inline void require_capacity(size_t capacity, size_t needed, const char* what) {
    if (capacity < needed)
        throw Error(BODT_ERR_INVALID_ARGUMENT, std::string(what) + " needs capacity " + std::to_string(needed) +
                                                   ", got " + std::to_string(capacity));
}

// Per-tet values in the caller's tet order (TetMesh::caller_tet): out must
// hold values.size() elements.
template <class T>
void to_caller_tets(const bodt::TetMesh& mesh, const std::vector<T>& values, T* out) {
    for (int32_t t = 0; t < mesh.num_tets(); ++t) out[mesh.caller_tet(t)] = values[static_cast<size_t>(t)];
}

// Per-vertex values in the caller's vertex order: out must hold
// values.size() elements.
template <class T>
void to_caller_vertices(const bodt::TetMesh& mesh, const std::vector<T>& values, T* out) {
    for (int32_t v = 0; v < mesh.num_vertices(); ++v) out[mesh.caller_vertex(v)] = values[static_cast<size_t>(v)];
}

// The coordinates in the caller's vertex order: out holds 3 per vertex.
inline void to_caller_xyz(const bodt::TetMesh& mesh, double* out) {
    for (int32_t v = 0; v < mesh.num_vertices(); ++v)
        for (int k = 0; k < 3; ++k) out[3 * static_cast<size_t>(mesh.caller_vertex(v)) + k] = mesh.points[v][k];
}

// The tets in the caller's order, by the caller's vertex indices plus
// `base`, corners 2 and 3 swapped when `flipped` (the caller's orientation
// restored): out holds 4 per tet.
inline void to_caller_corners(const bodt::TetMesh& mesh, bool flipped, int base, int32_t* out) {
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        bodt::Tet q = mesh.tets[t];
        if (flipped) std::swap(q[2], q[3]);
        int32_t* o = out + 4 * static_cast<size_t>(mesh.caller_tet(t));
        for (int k = 0; k < 4; ++k) o[k] = mesh.caller_vertex(q[k]) + base;
    }
}

// Copies `full` into a caller struct of `size` bytes whose first member is
// that size: the caller gets what fits, the rest is zeroed.
template <class T>
void fill_sized(T* out, const T& full) {
    require(out != nullptr, "output struct is NULL");
    const size_t size = out->size;
    require(size >= sizeof(size_t), "set the struct's size field to sizeof(struct) before the call");
    std::memset(static_cast<void*>(out), 0, size);
    std::memcpy(static_cast<void*>(out), &full, std::min(size, sizeof(T)));
    out->size = size;
}

}  // namespace bodt_capi
