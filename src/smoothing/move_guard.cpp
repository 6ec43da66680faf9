#include "smoothing/move_guard.hpp"

#include <algorithm>

namespace bodt {

bool MoveGuard::acceptable(const TetMesh& mesh, int32_t v, double star_min_before) const {
    double star_min_after = 1.0;
    size_t k = 0;
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t, ++k) {
        const auto p = mesh.tet_points(*t);
        if (orient(p[0], p[1], p[2], p[3]).sign <= 0) return false;
        const double s = stretch(p);
        if (s < std::min(settings_.min_stretch, before_[k])) return false;
        star_min_after = std::min(star_min_after, s);
    }
    return !settings_.never_worse || star_min_after >= star_min_before;
}

MoveOutcome MoveGuard::move(TetMesh& mesh, int32_t v, const Vec3& target, double& distance) {
    before_.clear();
    double star_min_before = 1.0;
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t) {
        before_.push_back(stretch(mesh.tet_points(*t)));
        star_min_before = std::min(star_min_before, before_.back());
    }
    const Vec3 start = mesh.points[v];
    Vec3 step = target - start;
    for (int attempt = 0; attempt <= settings_.backtrack_steps; ++attempt, step *= 0.5) {
        mesh.points[v] = start + step;
        if (acceptable(mesh, v, star_min_before)) {
            distance = step.norm();
            return attempt == 0 ? MoveOutcome::Moved : MoveOutcome::Shortened;
        }
    }
    mesh.points[v] = start;
    distance = 0.0;
    return MoveOutcome::Rejected;
}

}  // namespace bodt
