// The domain boundary of a mesh: the faces of exactly one tet.  Interfaces
// between regions and marked internal faces are not part of the shape
// (paper 000 compares the surface meshes of the models).
#pragma once

#include "cli/mesh_snapshot.hpp"

#include <cstdint>
#include <vector>

namespace bodt_cli {

// 3 vertex indices (0-based) per triangle, ordered so that the right-hand
// normal points out of the tet the face belongs to; sorted by their vertex
// triples.
std::vector<int32_t> domain_boundary(const MeshSnapshot& m);

}  // namespace bodt_cli
