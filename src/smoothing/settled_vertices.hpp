// The vertices a B-ODT sweep need not try again.  A vertex that stayed
// where it was at its last visit (the guard refused every trial move, or
// the model had no minimum) stays again while no vertex of its star has
// moved since: the same star gives the same target and the same verdict, so
// skipping it changes no result.  An inner vertex's target (eq. 3) reads
// its star; a boundary vertex's (eqs. 5-10) its star, its surface one-rings
// and their normals (ring vertices are star vertices), and its feature-line
// neighbours (star vertices too).  Time is counted in colours of
// the sweeps (one tick per colour; vertices of one colour share no tet), so
// the answer does not depend on the threads.  The owner clears it whenever
// the mesh data, the mode or a parameter changes, and carries it over a
// connectivity change.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <limits>
#include <vector>

namespace bodt {

class SettledVertices {
public:
    void clear() {
        moved_at_.clear();
        stayed_at_.clear();
        clock_ = 0;
        ++epoch_;
    }

    // Starts a sweep of a mesh with `vertices` vertices in `colours` colours.
    void begin_sweep(size_t vertices, int32_t colours) {
        const uint32_t ticks = static_cast<uint32_t>(colours) + 1;
        if (moved_at_.size() != vertices || clock_ > std::numeric_limits<uint32_t>::max() - ticks) {
            moved_at_.assign(vertices, 0);
            stayed_at_.assign(vertices, 0);
            clock_ = 0;
            ++epoch_;
        }
        base_ = clock_;
        clock_ += ticks;
    }
    // The time of colour c in the current sweep.
    uint32_t tick(int32_t colour) const { return base_ + static_cast<uint32_t>(colour) + 1; }

    // v stayed at its last visit and no vertex of its star moved since.
    bool settled(const TetMesh& mesh, int32_t v) const {
        const uint32_t at = stayed_at_[v];
        return at != 0 && !moved_since(mesh, v, at);
    }

    void reserve(size_t vertices) {
        moved_at_.reserve(vertices);
        stayed_at_.reserve(vertices);
    }
    // After a connectivity change that kept every vertex's index (made
    // vertices come after): the records stay, and the vertices in
    // `changed` (whose star changed, which moved, or whose target reads
    // something else that changed) count as moved now, so that they and
    // the vertices around them are tried again.
    void carry_over(size_t vertices, const std::vector<int32_t>& changed) {
        if (moved_at_.empty() || clock_ == std::numeric_limits<uint32_t>::max()) return clear();
        moved_at_.resize(vertices, 0);
        stayed_at_.resize(vertices, 0);
        ++clock_;
        for (int32_t v : changed) moved(v, clock_);
    }

    // Every vertex that moves, inner or not, must be reported.
    void moved(int32_t v, uint32_t tick) {
        moved_at_[v] = tick;
        stayed_at_[v] = 0;
    }
    void stayed(int32_t v, uint32_t tick) { stayed_at_[v] = tick; }

    // For other memories of the sweeps' work (FailedFlips): when each
    // vertex last moved (0: never), the time now, and a number that
    // changes whenever the times start again.
    const std::vector<uint32_t>& moved_at() const { return moved_at_; }
    uint32_t now() const { return clock_; }
    uint64_t epoch() const { return epoch_; }

private:
    // A vertex of v's star moved at `at` or later.
    bool moved_since(const TetMesh& mesh, int32_t v, uint32_t at) const;

    std::vector<uint32_t> moved_at_, stayed_at_;  // 0: never
    uint32_t clock_ = 0, base_ = 0;
    uint64_t epoch_ = 0;
};

}  // namespace bodt
