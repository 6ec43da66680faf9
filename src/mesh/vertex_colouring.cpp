#include "mesh/vertex_colouring.hpp"

namespace bodt {

VertexColouring colour_vertices(const TetMesh& mesh) {
    const int32_t n = mesh.num_vertices();
    VertexColouring out;
    std::vector<int32_t>& colour = out.colour;
    colour.assign(static_cast<size_t>(n), -1);
    std::vector<int32_t> taken_by;  // taken_by[c] == v: a neighbour of v has colour c
    // Greedy in the caller's order, so the colours (and with them the
    // results of a sweep) do not depend on the internal order.
    for (int32_t caller = 0; caller < n; ++caller) {
        const int32_t v = mesh.internal_vertex(caller);
        if (mesh.star_begin(v) == mesh.star_end(v)) continue;
        for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
            for (const int32_t u : mesh.tets[*t]) {
                const int32_t c = colour[u];
                if (c >= 0) taken_by[c] = v;
            }
        int32_t c = 0;
        while (c < static_cast<int32_t>(taken_by.size()) && taken_by[c] == v) ++c;
        if (c == static_cast<int32_t>(taken_by.size())) taken_by.push_back(-1);
        colour[v] = c;
    }
    out.count = static_cast<int32_t>(taken_by.size());
    out.lower.assign(static_cast<size_t>(n), 0);
    for (int32_t v = 0; v < n; ++v)
        for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
            for (const int32_t u : mesh.tets[*t]) out.lower[v] += colour[u] < colour[v];
    return out;
}

}  // namespace bodt
