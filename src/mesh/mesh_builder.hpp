// Builds a TetMesh from caller arrays, validating everything on the way:
// every refusal is an Error with a status and a message that names the
// offending entities in the caller's index base.
#pragma once

#include "mesh/region_surfaces.hpp"
#include "mesh/tet_mesh.hpp"

#include <cstdint>

namespace bodt {

struct MeshArrays {
    int32_t nverts = 0;
    const double* xyz = nullptr;
    int32_t ntets = 0;
    const int32_t* tets = nullptr;
    int index_base = 0;
    uint32_t flags = 0;  // bodt_create_flag bits
};

struct BuiltMesh {
    TetMesh mesh;
    RegionSurfaces surfaces;  // one region until the caller sets regions
    bool flipped = false;        // the caller's tets are negatively oriented
    int32_t num_inverted = 0;    // accepted inverted tets (with the flag)
};

// The mesh as given: vertex v and tet t of `in` are the mesh's v and t.
BuiltMesh build_mesh(const MeshArrays& in);
// The mesh stored in the curve order of mesh/curve_order.hpp, mesh.caller
// holding the caller's numbering; messages name the caller's vertices and
// tets all the same.
BuiltMesh build_mesh_in_curve_order(const MeshArrays& in);

// Converts caller-based vertex indices to 0-based ones, checking the range;
// `what` names the array in messages ("triangle", "fixed vertex").
void check_vertex_index(int32_t value, int32_t nverts, int base, const char* what, int64_t item);

}  // namespace bodt
