// The guard every vertex move passes through: a move is tried in full, then
// halved up to `backtrack_steps` times, and applied only when no tet around
// the vertex ends inverted, flat or below the stretch floor.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <vector>

namespace bodt {

struct GuardSettings {
    double min_stretch;     // floor: a tet may not end below min(floor, its stretch before)
    int backtrack_steps;    // halvings after the full move
    bool never_worse;       // also keep the star's smallest stretch from dropping
};

enum class MoveOutcome { Moved, Shortened, Rejected };

class MoveGuard {
public:
    explicit MoveGuard(const GuardSettings& s) : settings_(s) {}

    // Moves vertex v of `mesh` towards `target`; `distance` receives the
    // length of the move made (0 when rejected).
    MoveOutcome move(TetMesh& mesh, int32_t v, const Vec3& target, double& distance);

private:
    bool acceptable(const TetMesh& mesh, int32_t v, double star_min_before) const;

    GuardSettings settings_;
    std::vector<double> before_;  // stretch of each star tet before the move (reused)
};

}  // namespace bodt
