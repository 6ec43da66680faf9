// The guard every vertex move passes through: a move is tried in full, then
// halved up to `backtrack_steps` times, and applied only when no tet around
// the vertex ends inverted, flat or below the stretch floor, and no watched
// surface triangle turns its normal by more than 90 degrees.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <vector>

namespace bodt {

struct GuardSettings {
    double min_stretch;     // floor: a tet may not end below min(floor, its stretch before)
    int backtrack_steps;    // halvings after the full move
    bool never_worse;       // also keep the star's extreme dihedral angles from getting worse
};

enum class MoveOutcome { Moved, Shortened, Rejected };

class MoveGuard {
public:
    explicit MoveGuard(const GuardSettings& s) : settings_(s) {}

    // Moves vertex v of `mesh` towards `target`; `distance` receives the
    // length of the move made (0 when rejected).  `surface_faces` are the
    // boundary/interface triangles around v that must not flip.
    MoveOutcome move(TetMesh& mesh, int32_t v, const Vec3& target, const std::vector<FaceKey>& surface_faces,
                     double& distance);

private:
    bool acceptable(const TetMesh& mesh, int32_t v, const CosineRange& star_before,
                    const std::vector<FaceKey>& surface_faces) const;

    GuardSettings settings_;
    std::vector<double> before_;   // stretch of each star tet before the move (reused)
    std::vector<Vec3> normals_;    // normal of each watched face before the move (reused)
};

}  // namespace bodt
