// A smoothing sweep in colour order (vertex_colouring.hpp): each vertex is
// visited after its neighbours of lower colour and before those of higher
// colour, which is all a Gauss-Seidel sweep colour by colour depends on, so
// the result is that of a sweep colour by colour, on any number of threads.
// The visits follow the data instead of the colours: a vertex is visited as
// soon as its last neighbour of lower colour is done, by the thread that did
// it, so the sweep runs as a narrow front along the internal (curve) order
// and finds the stars it reads in the cache, where a sweep colour by colour
// streams the whole mesh once per colour.  On one thread that order is
// the mesh's sweep_order(); on several, each visit releases the
// neighbours in its release list: both are made once per connectivity.
#pragma once

#include "common/parallel.hpp"
#include "mesh/tet_mesh.hpp"
#include "mesh/vertex_colouring.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace bodt {

// The threads for `items` units of work (vertices, tets) under
// BODT_PARAM_THREADS = `requested` (0: default_threads()): at least 4096
// items each, since starting a thread costs more than a small share of work.
inline int sweep_threads(int32_t requested, size_t items) {
    const size_t most = std::max<size_t>(1, items / 4096);
    return static_cast<int>(std::min<size_t>(most, requested > 0 ? requested : default_threads()));
}

namespace detail {

template <class State, class Body>
void visit_vertex(Body& body, State& state, int32_t v, int32_t colour) {
    if constexpr (std::is_invocable_v<Body&, State&, int32_t, int32_t>) body(state, v, colour);
    else body(state, v);
}

// Visits source vertex v (no neighbour of lower colour), then, depth
// first, every vertex its visits make ready.  After u's visit, each vertex
// w of higher colour around u is released by its pairs with u (its entry
// in u's release list): `release(w, pairs)` says whether those were w's
// last ones (VertexColouring::lower); w then goes on `ready`.
template <class State, class Body, class Release>
void visit_from(const std::vector<int32_t>& colour, const ReleaseLists& lists, int32_t v, Body& body, State& state,
                std::vector<int32_t>& ready, Release release) {
    ready.push_back(v);
    while (!ready.empty()) {
        const int32_t u = ready.back();
        ready.pop_back();
        visit_vertex(body, state, u, colour[u]);
        for (int32_t k = lists.offsets[u]; k < lists.offsets[u + 1]; ++k)
            if (release(lists.vertex[k], lists.pairs[k])) ready.push_back(lists.vertex[k]);
    }
}

}  // namespace detail

// Calls body(state, v) for every coloured vertex v of `mesh`, where `state`
// is the calling thread's own copy of `initial` (scratch space and counters),
// or body(state, v, c) with v's colour c when `body` takes one.  A vertex
// whose neighbours of lower colour are all done is visited next (the last
// one it became ready by, depth first), else the next vertex in internal
// order that waits for none.  Returns the states, one per thread, for the
// caller to merge.  An exception thrown by `body` stops the sweep and is
// rethrown; the vertices not visited yet are left as they are.
template <class State, class Body>
std::vector<State> coloured_sweep(const TetMesh& mesh, int threads, const State& initial, Body body) {
    const VertexColouring& colouring = mesh.colouring();
    const std::vector<int32_t>& colour = colouring.colour;
    const std::vector<int32_t>& lower = colouring.lower;
    const int32_t n = mesh.num_vertices();
    // Each thread takes runs of this many vertices (in internal order) to
    // start from; at least a few runs per thread.
    constexpr int32_t kRun = 1024;
    threads = std::max(1, std::min(threads, n / (4 * kRun)));
    std::vector<State> states(static_cast<size_t>(threads), initial);
    if (threads == 1) {
        for (const int32_t v : mesh.sweep_order()) detail::visit_vertex(body, states[0], v, colour[v]);
        return states;
    }

    const ReleaseLists& lists = mesh.release_lists(threads);
    // The thread whose release takes a vertex's count to 0 visits it: it
    // saw every write of the vertices before it (acquire-release).
    std::unique_ptr<std::atomic<int32_t>[]> pending(new std::atomic<int32_t>[static_cast<size_t>(n)]);
    for (int32_t v = 0; v < n; ++v) pending[v].store(lower[v], std::memory_order_relaxed);
    const auto release = [&pending](int32_t w, int32_t k) {
        return pending[w].fetch_sub(k, std::memory_order_acq_rel) == k;
    };
    ChunkCounter runs(n, kRun);
    std::atomic<bool> failed{false};
    on_threads(threads, [&](int me) {
        std::vector<int32_t> ready;
        try {
            for (int64_t begin, end; !failed.load(std::memory_order_relaxed) && runs.next(begin, end);)
                for (int32_t v = static_cast<int32_t>(begin); v < end && !failed.load(std::memory_order_relaxed); ++v)
                    if (colour[v] >= 0 && lower[v] == 0)
                        detail::visit_from(colour, lists, v, body, states[static_cast<size_t>(me)], ready, release);
        } catch (...) {
            failed.store(true, std::memory_order_relaxed);
            throw;
        }
    });
    return states;
}

}  // namespace bodt
