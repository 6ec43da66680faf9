// Greedy distance-1 colouring of the vertices: two vertices of one colour
// share no tet.  A sweep that moves the vertices colour by colour is a
// Gauss-Seidel sweep whose moves within a colour touch disjoint stars, so
// they may run in any order, on any number of threads, with the same result.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <vector>

namespace bodt {

struct VertexColouring {
    // The vertices of colour c are order[offset[c] .. offset[c + 1]), in
    // ascending (internal) index.  Unused vertices get no colour.
    std::vector<int32_t> offset, order;
    int32_t colours() const { return static_cast<int32_t>(offset.size()) - 1; }
};

// Each vertex, in the caller's index order (TetMesh::caller), takes the
// smallest colour none of its neighbours (the other vertices of its tets)
// has taken yet: the colours are the same in any internal order.
VertexColouring colour_vertices(const TetMesh& mesh);

}  // namespace bodt
