// Laplacian smoothing: the target of a vertex is the mean of its neighbours.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <vector>

namespace bodt {

// `scratch` is reused between calls to keep the sweep free of allocations.
Vec3 laplace_target(const TetMesh& mesh, int32_t v, std::vector<int32_t>& scratch);

}  // namespace bodt
