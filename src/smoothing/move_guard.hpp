// The guard every vertex move passes through: a move is tried in full, then
// halved up to `backtrack_steps` times, and applied only when no tet around
// the vertex ends inverted, flat or below the stretch floor, and no watched
// surface triangle turns its normal by more than 90 degrees.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <array>
#include <vector>

namespace bodt {

struct GuardSettings {
    double min_stretch;     // floor: a tet may not end below min(floor, its stretch before)
    int backtrack_steps;    // halvings after the full move
    bool never_worse;       // also keep the star's extreme dihedral angles from getting worse
};

enum class MoveOutcome { Moved, Shortened, Rejected };

// tet_shape() of every tet, for a sweep's guards to share (tet_shapes()).
using ShapeCache = std::vector<TetShape>;
ShapeCache tet_shapes(const TetMesh& mesh, int threads);

class MoveGuard {
public:
    // With a cache (of the mesh as it is, kept up to date by the moves), a
    // move reads the shapes of the tets around the vertex there instead of
    // computing them; the guards of one sweep may share it when their
    // vertices share no tet.
    explicit MoveGuard(const GuardSettings& s, ShapeCache* cache = nullptr) : settings_(s), cache_(cache) {}

    // Moves vertex v of `mesh` towards `target`; `distance` receives the
    // length of the move made (0 when rejected).  `surface_faces` are the
    // boundary/interface triangles around v that must not flip.
    MoveOutcome move(TetMesh& mesh, int32_t v, const Vec3& target, const std::vector<FaceKey>& surface_faces,
                     double& distance);

private:
    bool acceptable(const TetMesh& mesh, int32_t v, const CosineRange& star_before,
                    const std::vector<FaceKey>& surface_faces);
    // Star tet t (the k-th around the vertex) passes the guard; its shape
    // goes to after_[k].
    bool tet_acceptable(const TetMesh& mesh, int32_t t, size_t k, const CosineRange& star_before);

    GuardSettings settings_;
    ShapeCache* cache_;
    std::vector<TetShape> before_, after_;  // of each star tet (reused)
    std::vector<Vec3> normals_;    // normal of each watched face before the move (reused)
    std::array<size_t, 2> extreme_{};  // star tets with the smallest and the largest angle before
};

}  // namespace bodt
