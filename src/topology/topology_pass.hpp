// The connectivity half of a step: quality flips (paper 001 Algorithm 4,
// generalised to every bad tet, or as printed: around poor tets whose
// vertices all stay put), vertex insertion for spades, caps and
// slivers (paper 000 sec. 2.3), else at the circumcentre of a bad tet
// (Delaunay refinement, Bowyer-Watson within the region) and, on request,
// collapse of short edges (paper 002 sec. 3.5).  Every change is tentative: it is kept only when
// the worst dihedral sine of the tets it touched went up.
#pragma once

#include "topology/failed_flips.hpp"
#include "topology/stuck_tets.hpp"
#include "topology/operations.hpp"

#include <cstdint>
#include <functional>
#include <vector>

namespace bodt {

// Where the relocation after a tentative change wants vertex v; false: v
// stays.  Empty: ODT (paper 000 eq. 3) for Interior vertices.
using RelocationTarget = std::function<bool(const EditableMesh& mesh, int32_t v, Vec3& target)>;

struct TopologySettings {
    TopologyRules rules;
    double bad_angle_deg = 15.0;  // insertion and collapse work on tets with an angle outside [this, 180 - this]
    double flip_angle_deg = 30.0; // flips work around tets with an angle outside [this, 180 - this]
    bool flip = true, insert = true, collapse = false;
    // Paper 001 Algorithm 4: flips around poor tets (stretch below
    // poor_stretch) whose four vertices all stay put (not Interior), judged
    // after relocating the interior vertices of the tets they make.
    bool swap_all_boundary = false;
    double poor_stretch = 0.5;
    bool relocate_old = true;  // an insertion also relocates the bad tet's vertices (the step smooths)
    RelocationTarget relocation_target;
};

struct TopologyCounts {
    int32_t flips = 0, inserted = 0, collapsed = 0;
    bool changed() const { return flips + inserted + collapsed > 0; }
};

// What a pass knows will fail: the flips (within the pass, and from
// earlier ones) and the bad tets (from earlier ones) that failed.
struct FailedAttempts {
    FailedFlips flips;
    StuckTets tets;
    // The bad tets (sorted vertex quads, ascending) whose circumcentre
    // refinement or inner-edge split failed: not tried again while the tet
    // stands, even if its vertices moved (a failed insertion costs as much
    // as the rest of a step's pass).  Each pass keeps only those of its own
    // bad tets.
    std::vector<Tet> unrefined;

    // Starts a pass over `mesh`; see FailedFlips and StuckTets.
    void begin_pass(const EditableMesh& mesh, const SweepHistory* history) {
        flips.begin_pass(mesh, history);
        tets.begin_pass(mesh, history);
    }
};

TopologyCounts improve_topology(EditableMesh& mesh, const TopologySettings& settings);
// The same with the caller's memory of failed attempts, begun on `mesh`
// (failed.begin_pass), which may hold the failures of earlier passes.
TopologyCounts improve_topology(EditableMesh& mesh, const TopologySettings& settings, FailedAttempts& failed);

}  // namespace bodt
