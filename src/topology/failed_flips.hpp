// The flips that failed, each with the vertices whose points and tets the
// attempt read: while none of those changed, the attempt would fail again.
// Bad tets cluster, so most edges and faces come up from several of them
// in one pass; and a bad tet that no flip fixed comes up again in the next
// step's pass, where the sweep in between may have left its vertices
// where they were.
//
// A direct-mapped cache, not a map: a record is overwritten by the next one
// hashing to its slot.  Within a pass the repeats come from neighbouring
// bad tets, which the pass visits close together (tets are stored in curve
// order), so a fixed table catches most of them without allocating; a map
// grew to millions of nodes on a large mesh and cost more than the repeats
// it saved.
#pragma once

#include "topology/editable_mesh.hpp"
#include "topology/operations.hpp"
#include "topology/sweep_history.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace bodt {

class FailedFlips {
public:
    // Starts a pass over `mesh` (a new EditableMesh: every stamp 0).  With
    // `history`, records of earlier passes in the same epoch are kept;
    // without, everything is forgotten.
    void begin_pass(const EditableMesh& mesh, const SweepHistory* history) {
        const bool keep = history && remembers_ && history->epoch == epoch_;
        if (!keep) {
            bits_ = 8;
            // A slot per four tets, 256 to 32768 of them: bad tets are few,
            // and the table is kept from step to step.
            while (bits_ < 15 && (int64_t{4} << bits_) < mesh.tet_capacity()) ++bits_;
            slots_.assign(size_t{1} << bits_, Slot());
        }
        history_ = history ? *history : SweepHistory{nullptr, 0, 0};
        epoch_ = history_.epoch;
        remembers_ = history != nullptr;
        ++pass_;
    }

    // Edge (a, b), directed: edge removal's tests on a surface edge are
    // made from a's side.  Keyed as (a, b, -1); a face by its sorted vertices.
    bool repeats(const EditableMesh& mesh, int32_t a, int32_t b) const { return repeats(mesh, FaceKey{{a, b, -1}}); }
    bool repeats(const EditableMesh& mesh, const FaceKey& face) const {
        const Slot& x = slots_[slot(face)];
        if (x.pass == 0 || !(x.key == face)) return false;
        if (x.pass == pass_) {
            for (int i = 0; i < x.n; ++i)
                if (mesh.stamp(x.read[i]) > x.clock) return false;
            return true;
        }
        // An earlier pass: untouched in this one, unmoved by the sweeps since.
        for (int i = 0; i < x.n; ++i) {
            const int32_t v = x.read[i];
            if (mesh.stamp(v) != 0 || history_.moved_after(v, x.tick)) return false;
        }
        return true;
    }
    // An edge: its ring's vertices too when edge_ring built it.
    void record(const EditableMesh& mesh, int32_t a, int32_t b, const EdgeRing* ring) {
        Slot& x = fill(mesh, FaceKey{{a, b, -1}});
        x.read[x.n++] = a;
        x.read[x.n++] = b;
        if (ring)
            for (int32_t v : ring->ring) x.read[x.n++] = v;
    }
    // A face: the apexes of its tets too (pair: those tets, or null).
    void record(const EditableMesh& mesh, const FaceKey& face, const int32_t* pair) {
        Slot& x = fill(mesh, face);
        for (int32_t v : face.v) x.read[x.n++] = v;
        for (int k = 0; pair && k < 2; ++k)
            for (int32_t v : mesh.tet(pair[k]))
                if (v != face.v[0] && v != face.v[1] && v != face.v[2]) x.read[x.n++] = v;
    }

private:
    struct Slot {
        FaceKey key;
        uint32_t pass = 0;  // 0: empty
        uint32_t tick = 0;  // the sweeps' clock then
        int n = 0;
        uint64_t clock = 0;  // the mesh's clock then (within its pass)
        std::array<int32_t, kMaxEdgeRing + 3> read;  // an edge and its ring (one more vertex when open)
    };
    size_t slot(const FaceKey& k) const { return (FaceKeyHash()(k) * 0x9E3779B97F4A7C15ull) >> (64 - bits_); }
    Slot& fill(const EditableMesh& mesh, const FaceKey& k) {
        Slot& x = slots_[slot(k)];
        x.key = k;
        x.pass = pass_;
        x.tick = history_.now;
        x.n = 0;
        x.clock = mesh.clock();
        return x;
    }

    int bits_ = 8;
    std::vector<Slot> slots_;
    uint32_t pass_ = 0;
    uint64_t epoch_ = 0;
    bool remembers_ = false;  // the last pass had a history: its records may outlive it
    SweepHistory history_{nullptr, 0, 0};
};

}  // namespace bodt
