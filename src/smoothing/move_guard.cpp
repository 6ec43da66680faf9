#include "smoothing/move_guard.hpp"

#include <algorithm>

namespace bodt {

namespace {

Vec3 face_normal(const TetMesh& mesh, const FaceKey& f) {
    const Vec3& a = mesh.points[f.v[0]];
    return (mesh.points[f.v[1]] - a).cross(mesh.points[f.v[2]] - a);
}

}  // namespace

bool MoveGuard::acceptable(const TetMesh& mesh, int32_t v, const CosineRange& star_before,
                           const std::vector<FaceKey>& surface_faces) const {
    for (size_t k = 0; k < surface_faces.size(); ++k)
        if (!(face_normal(mesh, surface_faces[k]).dot(normals_[k]) > 0.0)) return false;
    size_t k = 0;
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t, ++k) {
        const auto p = mesh.tet_points(*t);
        if (orient(p[0], p[1], p[2], p[3]).sign <= 0) return false;
        const TetShape shape = tet_shape(p);
        if (shape.stretch < std::min(settings_.min_stretch, before_[k])) return false;
        if (settings_.never_worse &&
            (shape.cosines.of_min > star_before.of_min || shape.cosines.of_max < star_before.of_max))
            return false;
    }
    return true;
}

MoveOutcome MoveGuard::move(TetMesh& mesh, int32_t v, const Vec3& target, const std::vector<FaceKey>& surface_faces,
                            double& distance) {
    normals_.clear();
    for (const FaceKey& f : surface_faces) normals_.push_back(face_normal(mesh, f));
    before_.clear();
    CosineRange star_before{-1.0, 1.0};  // the star's smallest and largest angle
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t) {
        const TetShape shape = tet_shape(mesh.tet_points(*t));
        before_.push_back(shape.stretch);
        star_before.of_min = std::max(star_before.of_min, shape.cosines.of_min);
        star_before.of_max = std::min(star_before.of_max, shape.cosines.of_max);
    }
    const Vec3 start = mesh.points[v];
    Vec3 step = target - start;
    for (int attempt = 0; attempt <= settings_.backtrack_steps; ++attempt, step *= 0.5) {
        mesh.points[v] = start + step;
        if (acceptable(mesh, v, star_before, surface_faces)) {
            distance = step.norm();
            return attempt == 0 ? MoveOutcome::Moved : MoveOutcome::Shortened;
        }
    }
    mesh.points[v] = start;
    distance = 0.0;
    return MoveOutcome::Rejected;
}

}  // namespace bodt
