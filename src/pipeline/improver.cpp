#include "pipeline/improver.hpp"

#include "bodt.h"
#include "common/error.hpp"
#include "quality/mesh_quality.hpp"
#include "smoothing/laplace.hpp"
#include "smoothing/move_guard.hpp"

#include <string>

namespace bodt {

void Improver::set_mode(int mode) {
    if (mode != BODT_MODE_LAPLACE)
        throw Error(BODT_ERR_INVALID_ARGUMENT, "unknown mode " + std::to_string(mode));
    mode_ = mode;
}

void Improver::sweep_laplace(TetMesh& mesh, StepReport& report) const {
    MoveGuard guard({params_.min_stretch, params_.backtrack_steps, params_.never_worse != 0});
    std::vector<int32_t> scratch;
    for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
        if (!mesh.is_interior_free(v)) continue;
        const Vec3 target = laplace_target(mesh, v, scratch);
        double distance = 0.0;
        switch (guard.move(mesh, v, target, distance)) {
            case MoveOutcome::Moved: ++report.vertices_moved; break;
            case MoveOutcome::Shortened:
                ++report.vertices_moved;
                ++report.moves_shortened;
                break;
            case MoveOutcome::Rejected: ++report.moves_rejected; break;
        }
        report.max_move = std::max(report.max_move, distance);
    }
}

StepReport Improver::step(TetMesh& mesh) {
    const std::vector<Vec3> saved = mesh.points;
    StepReport report;
    try {
        sweep_laplace(mesh, report);
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
