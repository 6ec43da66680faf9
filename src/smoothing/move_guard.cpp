#include "smoothing/move_guard.hpp"

#include <algorithm>

namespace bodt {

namespace {

Vec3 face_normal(const TetMesh& mesh, const FaceKey& f) {
    const Vec3& a = mesh.points[f.v[0]];
    return (mesh.points[f.v[1]] - a).cross(mesh.points[f.v[2]] - a);
}

}  // namespace

ShapeCache tet_shapes(const TetMesh& mesh, int threads) {
    ShapeCache shapes(mesh.tets.size());
    const int32_t nt = mesh.num_tets();
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int32_t t = 0; t < nt; ++t) shapes[static_cast<size_t>(t)] = tet_shape(mesh.tet_points(t));
    return shapes;
}

bool MoveGuard::tet_acceptable(const TetMesh& mesh, int32_t t, size_t k, const CosineRange& star_before) {
    const auto p = mesh.tet_points(t);
    if (orient(p[0], p[1], p[2], p[3]).sign <= 0) return false;
    const TetShape shape = after_[k] = tet_shape(p);
    if (shape.stretch < std::min(settings_.min_stretch, before_[k].stretch)) return false;
    return !(settings_.never_worse &&
             (shape.cosines.of_min > star_before.of_min || shape.cosines.of_max < star_before.of_max));
}

bool MoveGuard::acceptable(const TetMesh& mesh, int32_t v, const CosineRange& star_before,
                           const std::vector<FaceKey>& surface_faces) {
    for (size_t k = 0; k < surface_faces.size(); ++k)
        if (!(face_normal(mesh, surface_faces[k]).dot(normals_[k]) > 0.0)) return false;
    // The tets that held the star's extreme angles fail most often: first.
    const int32_t* star = mesh.star_begin(v);
    for (const size_t k : extreme_)
        if (!tet_acceptable(mesh, star[k], k, star_before)) return false;
    for (size_t k = 0; k < before_.size(); ++k)
        if (k != extreme_[0] && k != extreme_[1] && !tet_acceptable(mesh, star[k], k, star_before)) return false;
    return true;
}

MoveOutcome MoveGuard::move(TetMesh& mesh, int32_t v, const Vec3& target, const std::vector<FaceKey>& surface_faces,
                            double& distance) {
    normals_.clear();
    for (const FaceKey& f : surface_faces) normals_.push_back(face_normal(mesh, f));
    before_.clear();
    CosineRange star_before{-1.0, 1.0};  // the star's smallest and largest angle
    extreme_ = {0, 0};
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t) {
        const TetShape shape = cache_ ? (*cache_)[static_cast<size_t>(*t)] : tet_shape(mesh.tet_points(*t));
        if (shape.cosines.of_min > star_before.of_min) {
            star_before.of_min = shape.cosines.of_min;
            extreme_[0] = before_.size();
        }
        if (shape.cosines.of_max < star_before.of_max) {
            star_before.of_max = shape.cosines.of_max;
            extreme_[1] = before_.size();
        }
        before_.push_back(shape);
    }
    after_.resize(before_.size());
    const Vec3 start = mesh.points[v];
    Vec3 step = target - start;
    for (int attempt = 0; attempt <= settings_.backtrack_steps; ++attempt, step *= 0.5) {
        mesh.points[v] = start + step;
        if (acceptable(mesh, v, star_before, surface_faces)) {
            if (cache_) {
                const int32_t* star = mesh.star_begin(v);
                for (size_t k = 0; k < after_.size(); ++k) (*cache_)[static_cast<size_t>(star[k])] = after_[k];
            }
            distance = step.norm();
            return attempt == 0 ? MoveOutcome::Moved : MoveOutcome::Shortened;
        }
    }
    mesh.points[v] = start;
    distance = 0.0;
    return MoveOutcome::Rejected;
}

}  // namespace bodt
