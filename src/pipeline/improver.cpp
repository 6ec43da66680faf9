#include "pipeline/improver.hpp"

#include "bodt.h"
#include "common/error.hpp"
#include "quality/mesh_quality.hpp"
#include "smoothing/bodt_smoother.hpp"
#include "smoothing/laplace.hpp"
#include "smoothing/move_guard.hpp"

#include <string>

namespace bodt {

namespace {

void count_outcome(MoveOutcome outcome, double distance, StepReport& report) {
    switch (outcome) {
        case MoveOutcome::Moved: ++report.vertices_moved; break;
        case MoveOutcome::Shortened:
            ++report.vertices_moved;
            ++report.moves_shortened;
            break;
        case MoveOutcome::Rejected: ++report.moves_rejected; break;
    }
    report.max_move = std::max(report.max_move, distance);
}

}  // namespace

void Improver::set_mode(int mode) {
    if (mode != BODT_MODE_LAPLACE && mode != BODT_MODE_ODT && mode != BODT_MODE_BODT_BASIC && mode != BODT_MODE_BODT)
        throw Error(BODT_ERR_INVALID_ARGUMENT, "unknown mode " + std::to_string(mode));
    mode_ = mode;
    invalidate_classes();
}

void Improver::set_param_int(int key, int32_t value) {
    bodt::set_param_int(params_, key, value);
}

void Improver::set_param_double(int key, double value) {
    bodt::set_param_double(params_, key, value);
    invalidate_classes();
}

const VertexClasses& Improver::classes(const TetMesh& mesh, const RegionSurfaces& surfaces) const {
    if (!classes_valid_) {
        FeatureSettings settings;
        settings.feature_angle_deg = params_.feature_angle;
        settings.edge_ratio = params_.edge_ratio;
        settings.corner_ratio = params_.corner_ratio;
        settings.detect_features = mode_ == BODT_MODE_BODT;
        classes_ = classify_vertices(mesh, surfaces, settings);
        classes_valid_ = true;
    }
    return classes_;
}

void Improver::sweep_laplace(TetMesh& mesh, StepReport& report) const {
    MoveGuard guard({params_.min_stretch, params_.backtrack_steps, params_.never_worse != 0});
    std::vector<int32_t> scratch;
    const std::vector<FaceKey> no_faces;
    for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
        if (!mesh.is_interior_free(v)) continue;
        const Vec3 target = laplace_target(mesh, v, scratch);
        double distance = 0.0;
        const MoveOutcome outcome = guard.move(mesh, v, target, no_faces, distance);
        count_outcome(outcome, distance, report);
    }
}

// ODT, B-ODT basic and B-ODT: the modes differ only in which vertices move
// (ODT: inner ones) and how the surface vertices were classified.
void Improver::sweep_bodt(TetMesh& mesh, const RegionSurfaces& surfaces, StepReport& report) const {
    const VertexClasses& cls = classes(mesh, surfaces);
    BodtSmoother smoother(surfaces, cls);
    MoveGuard guard({params_.min_stretch, params_.backtrack_steps, params_.never_worse != 0});
    std::vector<FaceKey> faces;
    for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
        if (mode_ == BODT_MODE_ODT && cls.cls[v] != VertexClass::Interior) continue;
        Vec3 target;
        switch (smoother.target(mesh, v, target, faces)) {
            case Plan::Stay: continue;
            case Plan::NotPositiveDefinite: ++report.not_positive_definite; continue;
            case Plan::Move: break;
        }
        double distance = 0.0;
        const MoveOutcome outcome = guard.move(mesh, v, target, faces, distance);
        count_outcome(outcome, distance, report);
    }
}

StepReport Improver::step(TetMesh& mesh, const RegionSurfaces& surfaces) {
    const std::vector<Vec3> saved = mesh.points;
    StepReport report;
    try {
        if (mode_ == BODT_MODE_LAPLACE) sweep_laplace(mesh, report);
        else sweep_bodt(mesh, surfaces, report);
        for (const Vec3& p : mesh.points)
            if (!p.allFinite()) throw Error(BODT_ERR_NUMERIC, "a vertex position became non-finite");
    } catch (...) {
        mesh.points = saved;
        throw;
    }
    const QualitySummary q = summarize_quality(mesh);
    report.step = ++steps_done_;
    report.min_dihedral = q.min_dihedral;
    report.max_dihedral = q.max_dihedral;
    report.min_stretch = q.min_stretch;
    return report;
}

}  // namespace bodt
