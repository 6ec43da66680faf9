// A smoothing sweep over the vertices colour by colour (vertex_colouring.hpp),
// each colour's vertices shared among OpenMP threads.  Moves within a colour
// touch disjoint stars, so the result does not depend on the number of
// threads or on how the vertices are shared out.
#pragma once

#include "mesh/vertex_colouring.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <type_traits>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace bodt {

// The threads for `items` units of work (vertices, tets) under
// BODT_PARAM_THREADS = `requested` (0: OpenMP's default, OMP_NUM_THREADS or
// every core): at least 4096 items each, since a barrier costs more than a
// small share of work; 1 without OpenMP.
inline int sweep_threads(int32_t requested, size_t items) {
#ifdef _OPENMP
    const size_t most = std::max<size_t>(1, items / 4096);
    return static_cast<int>(std::min<size_t>(most, requested > 0 ? requested : omp_get_max_threads()));
#else
    (void)requested;
    (void)items;
    return 1;
#endif
}

// Calls body(state, v) for every coloured vertex v, where `state` is the
// calling thread's own copy of `initial` (scratch space and counters), or
// body(state, v, c) with v's colour c when `body` takes one.
// Returns the states, one per thread, for the caller to merge.  An exception
// thrown by `body` stops the sweep after the current colour and is rethrown.
template <class State, class Body>
std::vector<State> coloured_sweep(const VertexColouring& colouring, int threads, const State& initial, Body body) {
    // At least 32 vertices of a mean colour per thread.
    const size_t per_colour = colouring.order.size() / static_cast<size_t>(std::max(1, colouring.colours()));
    threads = std::max(1, std::min(threads, static_cast<int>(per_colour / 32)));
    std::vector<State> states(static_cast<size_t>(threads), initial);
    std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
    bool failed = false;
#pragma omp parallel num_threads(threads)
    {
#ifdef _OPENMP
        const size_t me = static_cast<size_t>(omp_get_thread_num());
#else
        const size_t me = 0;
#endif
        for (int32_t c = 0; c < colouring.colours(); ++c) {
#pragma omp for schedule(dynamic, 64)
            for (int32_t i = colouring.offset[c]; i < colouring.offset[c + 1]; ++i) {
                if (errors[me]) continue;
                try {
                    if constexpr (std::is_invocable_v<Body&, State&, int32_t, int32_t>)
                        body(states[me], colouring.order[i], c);
                    else
                        body(states[me], colouring.order[i]);
                } catch (...) {
                    errors[me] = std::current_exception();
                }
            }
            // The implicit barrier of `omp for` ends the colour; stop on an error.
#pragma omp single
            for (const std::exception_ptr& e : errors) failed = failed || static_cast<bool>(e);
            if (failed) break;
        }
    }
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    return states;
}

}  // namespace bodt
