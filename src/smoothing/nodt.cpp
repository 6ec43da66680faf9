#include "smoothing/nodt.hpp"

#include "smoothing/bodt_model.hpp"

#include <algorithm>

namespace bodt {

NodtSmoother::NodtSmoother(const RegionSurfaces& surfaces, const VertexClasses& classes, const InputSurface& input,
                           const GuardSettings& guard, ShapeCache* shapes)
    : surfaces_(surfaces),
      classes_(classes),
      input_(input),
      guard_({guard.min_stretch, 0, guard.never_worse}, shapes),
      halvings_(guard.backtrack_steps) {}

Plan NodtSmoother::target(const TetMesh& mesh, int32_t v, Vec3& target, std::vector<FaceKey>& surface_faces) {
    surface_faces.clear();
    const VertexClass c = classes_.cls[v];
    if (c != VertexClass::Interior && c != VertexClass::Surface && c != VertexClass::FeatureLine) return Plan::Stay;
    if (c != VertexClass::Interior && !input_.projects(v, c)) return Plan::Stay;

    StarTable& star = guard_.star();  // move() uses it as gathered here
    star.gather(mesh, v);
    StarModel model;
    add_star(model, star, mesh.points[v], terms_);
    if (!(model.volume > 0.0)) return Plan::NotPositiveDefinite;
    target = mesh.points[v] - (2.0 / model.volume) * model.g;  // eq. (3) over the star as it is

    for (const int32_t* k = surfaces_.begin(v); k != surfaces_.end(v); ++k) {
        surfaces_.surface(*k).one_ring(v, ring_);
        for (size_t i = 0; i < ring_.size(); ++i)
            surface_faces.push_back(FaceKey::of(v, ring_[i], ring_[(i + 1) % ring_.size()]));
    }
    std::sort(surface_faces.begin(), surface_faces.end());
    surface_faces.erase(std::unique(surface_faces.begin(), surface_faces.end()), surface_faces.end());
    return Plan::Move;
}

MoveOutcome NodtSmoother::move(TetMesh& mesh, int32_t v, const Vec3& target,
                               const std::vector<FaceKey>& surface_faces, double& distance) {
    const VertexClass c = classes_.cls[v];
    const Vec3 start = mesh.points[v];
    double f = 1.0;
    for (int attempt = 0; attempt <= halvings_; ++attempt, f *= 0.5) {
        Vec3 at = start + f * (target - start);
        if (c != VertexClass::Interior) at = input_.project(v, c, at);
        if (guard_.move_gathered(mesh, v, at, surface_faces, distance) != MoveOutcome::Rejected)
            return attempt == 0 ? MoveOutcome::Moved : MoveOutcome::Shortened;
    }
    return MoveOutcome::Rejected;
}

}  // namespace bodt
