// The bad tets that no flip or no insertion could fix, remembered from one
// step's topology pass to the next.  Every test of a flip around tet t
// (its edges' rings, its faces' neighbours, the faces and edges the new
// tets would make) reads only the tets that share an edge with t, their
// points, and the connectivity around their vertices; an insertion for t
// (the tets it cuts, the stars of the vertices it relocates) reads the
// tets that share a vertex with t.  While none of their vertices has moved
// or changed since, the attempt fails again, and the pass can pass over t.
// On a mesh whose connectivity has settled this is most of a pass's work:
// the sweeps move a few vertices, and the bad tets far from them keep
// failing.
//
// A record is a tet's index and the sweeps' clock: a connectivity change
// carries it to the tet's new index (carry_over), a new epoch
// (SweepHistory) forgets them all, and so does a pass without a history.
#pragma once

#include "topology/editable_mesh.hpp"
#include "topology/sweep_history.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace bodt {

class StuckTets {
public:
    enum Attempt : uint32_t { kFlips = 1, kInsertion = 2 };

    // Starts a pass over `mesh` (a new EditableMesh: every stamp 0).
    void begin_pass(const EditableMesh& mesh, const SweepHistory* history) {
        // Without a history nothing is kept, and no room is made for records.
        const bool keep = history && history->epoch == epoch_ && records_.size() == static_cast<size_t>(mesh.tet_capacity());
        if (!keep) records_.assign(history ? static_cast<size_t>(mesh.tet_capacity()) : 0, 0);
        history_ = history ? *history : SweepHistory{nullptr, 0, 0};
        epoch_ = history_.epoch;
        find_last_moves_near(mesh, keep);
    }

    // After a connectivity change that kept every vertex's index: the
    // record of tet slot t goes to written[t] (EditableMesh::written_tets:
    // the tets still there first, in order), one of `tets` now; new tets
    // have none.  The owner counts every vertex the change touched as moved
    // (SettledVertices::carry_over), so the records around them no longer
    // hold.  With reserve() first, this does not allocate.
    void reserve(size_t tets) { records_.reserve(tets); }
    void carry_over(const std::vector<int32_t>& written, size_t tets) {
        if (records_.empty()) return;
        size_t kept = 0;  // the tets still there keep their order, first
        for (size_t t = 0; t < records_.size(); ++t)
            if (written[t] >= 0) records_[kept++] = records_[t];
        records_.resize(kept);
        records_.resize(tets, 0);
    }

    // The attempt on t failed in an earlier pass, and since then no vertex
    // of a tet sharing an edge (flips) or a vertex (insertion) with t moved
    // (sweeps) or changed (this pass).  A record of this pass is not read:
    // repeats within a pass are FailedFlips' (per edge and face, cheaper
    // than a walk around t).  A record found to hold while this pass has
    // changed nothing is brought up to now, so that on a settled mesh the
    // next pass finds it without looking around t.
    bool stuck(const EditableMesh& mesh, int32_t t, Attempt attempt) {
        if (static_cast<size_t>(t) >= records_.size() || !(records_[t] & attempt)) return false;
        const uint32_t tick = records_[t] >> kBits;
        if (tick >= history_.now) return false;  // this pass's own: the stamps alone cannot tell
        // Nothing changed in this pass and no vertex of a tet sharing a
        // vertex with t moved since: the walk below would find nothing.
        if (mesh.untouched() && last_move_near(mesh.tet(t)) <= tick) return true;
        const uint32_t holding = attempts_holding(mesh, t, tick);
        if (mesh.untouched() && history_.now <= kMaxTick) records_[t] = (history_.now - 1) << kBits | holding;
        return (holding & attempt) != 0;
    }
    // The attempt on t failed now.  The other attempt's record, if it holds
    // (stuck, or made in this pass), holds now too: both keep the new time.
    // A pass that changes anything starts a new epoch, so a record made
    // before a change in its own pass is never read.
    void failed(const EditableMesh& mesh, int32_t t, Attempt attempt) {
        if (history_.now >= kMaxTick || static_cast<size_t>(t) >= records_.size()) return;
        const Attempt other = attempt == kFlips ? kInsertion : kFlips;
        const bool other_holds = (records_[t] >> kBits == history_.now) ? (records_[t] & other) != 0 : stuck(mesh, t, other);
        records_[t] = history_.now << kBits | (other_holds ? uint32_t{other} : 0u) | attempt;
    }

private:
    // The attempts recorded for t at `tick` that still hold: the flips
    // while no tet sharing an edge with t changed, the insertion while no
    // tet sharing a vertex did.
    uint32_t attempts_holding(const EditableMesh& mesh, int32_t t, uint32_t tick) const {
        bool edges = true, vertices = (records_[t] & kInsertion) != 0;
        const Tet& q = mesh.tet(t);
        for (int32_t v : q)
            for (int32_t s : mesh.tets_of(v)) {
                const Tet& n = mesh.tet(s);
                const bool shares_edge = shared_vertices(q, n) >= 2;
                if (!shares_edge && !vertices) continue;
                for (int32_t u : n)
                    if (mesh.stamp(u) != 0 || history_.moved_after(u, tick)) {
                        vertices = false;
                        edges = edges && !shares_edge;
                        break;
                    }
                if (!edges) return 0;  // the edge set is in the vertex set
            }
        return (records_[t] & (edges ? kFlips : 0u)) | (vertices ? uint32_t{kInsertion} : 0u);
    }

    // last_near_[v]: the last time a vertex of a tet around v moved (0:
    // never), made at the start of a pass that keeps records from the one
    // before, where a few moves in the sweeps between would otherwise send
    // every record on a walk around its tet.  One pass over the tets.
    void find_last_moves_near(const EditableMesh& mesh, bool keep) {
        last_near_.clear();
        if (!keep || !history_.moved_at) return;
        last_near_.assign(static_cast<size_t>(mesh.num_vertices()), 0);
        for (int32_t t = 0; t < mesh.tet_capacity(); ++t) {
            if (!mesh.alive(t)) continue;
            const Tet& q = mesh.tet(t);
            uint32_t last = 0;
            for (int32_t v : q)
                if (static_cast<size_t>(v) < history_.moved_at->size()) last = std::max(last, (*history_.moved_at)[v]);
            for (int32_t v : q) last_near_[v] = std::max(last_near_[v], last);
        }
    }
    // The last move of a vertex of a tet sharing a vertex with q (a pass
    // with records from before has the table; without it, a time no record
    // is older than).
    uint32_t last_move_near(const Tet& q) const {
        if (last_near_.empty()) return std::numeric_limits<uint32_t>::max();
        uint32_t last = 0;
        for (int32_t v : q) last = std::max(last, last_near_[v]);
        return last;
    }

    static int shared_vertices(const Tet& a, const Tet& b) {
        int n = 0;
        for (int32_t v : b) n += holds(a, v);
        return n;
    }

    static constexpr int kBits = 2;
    static constexpr uint32_t kMaxTick = uint32_t{1} << (32 - kBits);

    std::vector<uint32_t> records_;  // per tet: the sweeps' clock << kBits | the attempts that failed then
    std::vector<uint32_t> last_near_;  // per vertex, see find_last_moves_near (empty: none)
    SweepHistory history_{nullptr, 0, 0};
    uint64_t epoch_ = 0;
};

}  // namespace bodt
