// The guard every vertex move passes through: a move is tried in full, then
// halved up to `backtrack_steps` times, and applied only when no tet around
// the vertex ends inverted, flat or below the stretch floor, and no watched
// surface triangle turns its normal by more than 90 degrees.
#pragma once

#include "mesh/tet_mesh.hpp"
#include "quality/mesh_quality.hpp"
#include "smoothing/star_table.hpp"

#include <array>
#include <cstdint>
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
    // The same with v's star already in star() (gathered, as the mesh is).
    // With never_worse, the star's largest angle may grow up to the angle
    // whose cosine is `largest_cosine` where that is larger (1: not at all).
    MoveOutcome move_gathered(TetMesh& mesh, int32_t v, const Vec3& target, const std::vector<FaceKey>& surface_faces,
                              double& distance, double largest_cosine = 1.0);
    StarTable& star() { return star_; }

    // How many trial places of one tet, or tets at one place, are checked
    // together (a multiple of the vector width).
    static constexpr size_t kPlaces = 4;

private:
    // Bit a set for each attempt a >= from at which star tet k fails the
    // guard; `step` is attempt from's move from start, halved for each
    // later one.
    uint64_t failing_attempts(size_t k, const Vec3& start, Vec3 step, int from) const;
    // v at `at` (also in mesh.points) passes the guard.
    bool acceptable(const TetMesh& mesh, const Vec3& at, const std::vector<FaceKey>& surface_faces);

    GuardSettings settings_;
    ShapeCache* cache_;
    StarTable star_;
    std::vector<double> floor_;      // each star tet's stretch floor
    std::vector<double> after_;      // 3 rows of star size: each star tet's stretch, cosines of_min, of_max at the place tried
    std::vector<double> failed_;     // first_failing()'s scratch
    size_t last_failed_ = 0;         // a star tet that failed the last try (star size: none)
    std::vector<Vec3> normals_;      // normal of each watched face before the move (reused)
    CosineRange star_before_{-1.0, 1.0};  // the star's smallest and largest angle before
    std::array<size_t, 2> extreme_{};     // star tets with the smallest and the largest angle before
};

}  // namespace bodt
