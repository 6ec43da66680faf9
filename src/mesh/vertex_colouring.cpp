#include "mesh/vertex_colouring.hpp"

namespace bodt {

VertexColouring colour_vertices(const TetMesh& mesh) {
    const int32_t n = mesh.num_vertices();
    std::vector<int32_t> colour(static_cast<size_t>(n), -1);
    std::vector<int32_t> taken_by;  // taken_by[c] == v: a neighbour of v has colour c
    std::vector<int32_t> count;
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
        if (c == static_cast<int32_t>(taken_by.size())) {
            taken_by.push_back(-1);
            count.push_back(0);
        }
        colour[v] = c;
        ++count[c];
    }
    VertexColouring out;
    out.offset.assign(count.size() + 1, 0);
    for (size_t c = 0; c < count.size(); ++c) out.offset[c + 1] = out.offset[c] + count[c];
    out.order.resize(static_cast<size_t>(out.offset.back()));
    // Within a colour by internal index: neighbours in memory are swept
    // together (the stars are disjoint, so the order changes no result).
    std::vector<int32_t> next(out.offset.begin(), out.offset.end() - 1);
    for (int32_t v = 0; v < n; ++v)
        if (colour[v] >= 0) out.order[next[colour[v]]++] = v;
    return out;
}

}  // namespace bodt
