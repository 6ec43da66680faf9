// The connectivity half of a step: quality flips (paper 001 Algorithm 4,
// generalised to every bad tet), vertex insertion for spades, caps and
// slivers (paper 000 sec. 2.3) and, on request, collapse of short edges
// (paper 002 sec. 3.5).  Every change is tentative: it is kept only when
// the worst dihedral sine of the tets it touched went up.
#pragma once

#include "topology/operations.hpp"

#include <cstdint>

namespace bodt {

struct TopologySettings {
    TopologyRules rules;
    double bad_angle_deg = 15.0;  // insertion and collapse work on tets with an angle outside [this, 180 - this]
    bool flip = true, insert = true, collapse = false;
    bool relocate_old = true;  // an insertion also relocates the bad tet's vertices (the step smooths)
};

struct TopologyCounts {
    int32_t flips = 0, inserted = 0, collapsed = 0;
    bool changed() const { return flips + inserted + collapsed > 0; }
};

TopologyCounts improve_topology(EditableMesh& mesh, const TopologySettings& settings);

}  // namespace bodt
