// Greedy distance-1 colouring of the vertices: two vertices of one colour
// share no tet.  A sweep that moves each vertex after its neighbours of
// lower colour and before those of higher colour is a Gauss-Seidel sweep
// in colour order whose result does not depend on anything else: not on
// the number of threads, nor on the order among vertices that share no tet
// (smoothing/coloured_sweep.hpp).
#pragma once

#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <vector>

namespace bodt {

struct VertexColouring {
    std::vector<int32_t> colour;  // per vertex; -1 for an unused vertex
    // Per vertex: the pairs (tet of its star, other vertex of that tet) whose
    // vertex has a lower colour; a sweep may move the vertex once as many
    // such pairs are done.
    std::vector<int32_t> lower;
    int32_t count = 0;  // colours
    int32_t colours() const { return count; }
};

// Each vertex, in the caller's index order (TetMesh::caller), takes the
// smallest colour none of its neighbours (the other vertices of its tets)
// has taken yet: the colours are the same in any internal order.
VertexColouring colour_vertices(const TetMesh& mesh);

// The same colouring after a connectivity change, from the one `before`
// it: `mesh` has every vertex the mesh before had at the same index (new
// ones after them), and `changed` lists every vertex whose tets changed.
// A vertex's greedy colour depends only on the colours of its neighbours
// earlier in the caller's order, so only the changed vertices, and the
// later neighbours of any vertex whose colour changed, are coloured again,
// in that order: the result is colour_vertices(mesh), bit for bit,
// without a pass over every star (or with one, where that is cheaper).
VertexColouring recolour_vertices(const TetMesh& mesh, const VertexColouring& before,
                                  const std::vector<int32_t>& changed);

// The coloured vertices in the order a sweep on one thread visits them
// (smoothing/coloured_sweep.hpp): each right after the last of its
// neighbours of lower colour (depth first), else the next in internal
// order that waits for none, so the sweep runs as a narrow front along the
// curve order.  Any order that visits each vertex after its neighbours of
// lower colour gives the same sweep; this one is kept with the colouring,
// so that a sweep on one thread counts no neighbours down.
std::vector<int32_t> sweep_order(const TetMesh& mesh, const VertexColouring& colouring);

// For a sweep on several threads: per vertex v, each neighbour w of higher
// colour once (in the order its first pair with v comes in v's star) with
// the number of (tet, vertex) pairs of v's star that are w's, so that v's
// visit releases w by one subtraction of that many (VertexColouring::lower).
struct ReleaseLists {
    std::vector<int32_t> offsets;  // v's entries are [offsets[v], offsets[v + 1])
    std::vector<int32_t> vertex;   // w
    std::vector<int32_t> pairs;    // its pairs in v's star
};
// Made on `threads` threads (common/parallel.hpp).
ReleaseLists release_lists(const TetMesh& mesh, const VertexColouring& colouring, int threads);

}  // namespace bodt
