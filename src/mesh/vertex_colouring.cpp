#include "mesh/vertex_colouring.hpp"

#include "common/parallel.hpp"

#include <algorithm>

namespace bodt {

namespace {

// The smallest colour that no neighbour u of v with earlier(u) has.
// taken_by[c] == v: such a neighbour has colour c (grown as needed).
template <class Earlier>
int32_t first_free_colour(const TetMesh& mesh, int32_t v, const std::vector<int32_t>& colour,
                          std::vector<int32_t>& taken_by, Earlier earlier) {
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
        for (const int32_t u : mesh.tets[*t]) {
            const int32_t c = colour[u];
            if (c >= 0 && earlier(u)) taken_by[c] = v;
        }
    int32_t c = 0;
    while (c < static_cast<int32_t>(taken_by.size()) && taken_by[c] == v) ++c;
    if (c == static_cast<int32_t>(taken_by.size())) taken_by.push_back(-1);
    return c;
}

int32_t lower_pairs(const TetMesh& mesh, int32_t v, const std::vector<int32_t>& colour) {
    int32_t n = 0;
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
        for (const int32_t u : mesh.tets[*t]) n += colour[u] < colour[v];
    return n;
}

}  // namespace

VertexColouring colour_vertices(const TetMesh& mesh) {
    const int32_t n = mesh.num_vertices();
    VertexColouring out;
    std::vector<int32_t>& colour = out.colour;
    colour.assign(static_cast<size_t>(n), -1);
    std::vector<int32_t> taken_by;
    std::vector<int32_t>& lower = out.lower;
    lower.assign(static_cast<size_t>(n), 0);
    // Greedy in the caller's order, so the colours (and with them the
    // results of a sweep) do not depend on the internal order.  A vertex
    // not coloured yet has colour -1: every coloured one comes earlier.
    // Each (tet, neighbour) pair is counted once, when the later of its
    // two vertices is coloured, for the one of them of higher colour.
    for (int32_t caller = 0; caller < n; ++caller) {
        const int32_t v = mesh.internal_vertex(caller);
        if (mesh.star_begin(v) == mesh.star_end(v)) continue;
        const int32_t c = colour[v] = first_free_colour(mesh, v, colour, taken_by, [](int32_t) { return true; });
        for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
            for (const int32_t u : mesh.tets[*t]) {
                if (u == v || colour[u] < 0) continue;
                ++lower[colour[u] < c ? v : u];
            }
    }
    out.count = static_cast<int32_t>(taken_by.size());
    return out;
}

VertexColouring recolour_vertices(const TetMesh& mesh, const VertexColouring& before,
                                  const std::vector<int32_t>& changed) {
    const int32_t n = mesh.num_vertices();
    VertexColouring out;
    out.colour = before.colour;
    out.colour.resize(static_cast<size_t>(n), -1);
    out.lower = before.lower;
    out.lower.resize(static_cast<size_t>(n), 0);
    std::vector<int32_t>& colour = out.colour;
    // Vertices to colour again, flagged by caller index and taken in that
    // order: a vertex is flagged only by one before it.
    std::vector<uint8_t> queued(static_cast<size_t>(n), 0), recount(static_cast<size_t>(n), 0);
    std::vector<int32_t> counted;
    const auto count_again = [&](int32_t v) {
        if (!recount[v]) counted.push_back(v);
        recount[v] = 1;
    };
    int32_t first = n;
    for (int32_t v : changed) {
        queued[mesh.caller_vertex(v)] = 1;
        first = std::min(first, mesh.caller_vertex(v));
    }
    std::vector<int32_t> taken_by(static_cast<size_t>(before.count), -1);
    int32_t coloured = 0;
    for (int32_t rank = first; rank < n; ++rank) {
        if (!queued[rank]) continue;
        // On a structured mesh a change can shift the colours of most
        // vertices after it; past an eighth of them, a full colouring
        // (the same result) is cheaper than going on.
        if (++coloured > n / 8) return colour_vertices(mesh);
        const int32_t v = mesh.internal_vertex(rank);
        count_again(v);
        const bool used = mesh.star_begin(v) != mesh.star_end(v);
        const auto earlier = [&mesh, rank](int32_t u) { return mesh.caller_vertex(u) < rank; };
        const int32_t c = used ? first_free_colour(mesh, v, colour, taken_by, earlier) : -1;
        if (c == colour[v]) continue;
        colour[v] = c;
        for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
            for (const int32_t u : mesh.tets[*t]) {
                count_again(u);
                if (mesh.caller_vertex(u) > rank) queued[mesh.caller_vertex(u)] = 1;
            }
    }
    out.count = colour.empty() ? 0 : 1 + *std::max_element(colour.begin(), colour.end());
    for (int32_t v : counted) out.lower[v] = lower_pairs(mesh, v, colour);
    return out;
}

std::vector<int32_t> sweep_order(const TetMesh& mesh, const VertexColouring& colouring) {
    const std::vector<int32_t>& colour = colouring.colour;
    const int32_t n = mesh.num_vertices();
    std::vector<int32_t> pending(colouring.lower), ready, order;
    order.reserve(static_cast<size_t>(n));
    for (int32_t s = 0; s < n; ++s) {
        if (colour[s] < 0 || colouring.lower[s] != 0) continue;
        ready.push_back(s);
        while (!ready.empty()) {
            const int32_t v = ready.back();
            ready.pop_back();
            order.push_back(v);
            // Each (tet, vertex) pair of v's star releases its vertex once.
            for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
                for (const int32_t w : mesh.tets[*t])
                    if (colour[w] > colour[v] && --pending[w] == 0) ready.push_back(w);
        }
    }
    return order;
}

namespace {

// v's neighbours of higher colour with their pairs, appended to `out`.
void higher_neighbours(const TetMesh& mesh, const std::vector<int32_t>& colour, int32_t v,
                       std::vector<std::pair<int32_t, int32_t>>& out) {
    out.clear();
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
        for (const int32_t w : mesh.tets[*t]) {
            if (colour[w] <= colour[v]) continue;
            auto it = out.begin();
            while (it != out.end() && it->first != w) ++it;
            if (it == out.end()) out.push_back({w, 1});
            else ++it->second;
        }
}

}  // namespace

ReleaseLists release_lists(const TetMesh& mesh, const VertexColouring& colouring, int threads) {
    const std::vector<int32_t>& colour = colouring.colour;
    const int32_t n = mesh.num_vertices();
    ReleaseLists out;
    out.offsets.assign(static_cast<size_t>(n) + 1, 0);
    // Counted, then filled, vertex by vertex (each independent of the others).
    using Higher = std::vector<std::pair<int32_t, int32_t>>;
    const auto each_vertex = [&](auto&& visit) {
        ChunkCounter chunks(n, 4096);
        on_threads(threads, [&](int) {
            Higher higher;
            for (int64_t begin, end; chunks.next(begin, end);)
                for (int32_t v = static_cast<int32_t>(begin); v < end; ++v) {
                    higher_neighbours(mesh, colour, v, higher);
                    visit(v, higher);
                }
        });
    };
    each_vertex([&](int32_t v, const Higher& higher) {
        out.offsets[static_cast<size_t>(v) + 1] = static_cast<int32_t>(higher.size());
    });
    for (int32_t v = 0; v < n; ++v) out.offsets[v + 1] += out.offsets[v];
    out.vertex.resize(static_cast<size_t>(out.offsets[n]));
    out.pairs.resize(static_cast<size_t>(out.offsets[n]));
    each_vertex([&](int32_t v, const Higher& higher) {
        for (size_t k = 0; k < higher.size(); ++k) {
            out.vertex[static_cast<size_t>(out.offsets[v]) + k] = higher[k].first;
            out.pairs[static_cast<size_t>(out.offsets[v]) + k] = higher[k].second;
        }
    });
    return out;
}

}  // namespace bodt
