// The improvement pipeline of a mesh handle: the current mode, its
// parameters, and `step`, one Gauss-Seidel sweep over the movable vertices.
#pragma once

#include "mesh/tet_mesh.hpp"
#include "pipeline/params.hpp"

#include <cstdint>

namespace bodt {

struct StepReport {
    int32_t step = 0;
    int32_t vertices_moved = 0;
    int32_t moves_rejected = 0;
    int32_t moves_shortened = 0;
    double max_move = 0.0;
    double min_dihedral = 0.0, max_dihedral = 0.0, min_stretch = 0.0;
};

class Improver {
public:
    int mode() const { return mode_; }
    void set_mode(int mode);  // throws Error for an unknown mode
    Params& params() { return params_; }
    const Params& params() const { return params_; }

    // One sweep.  If anything throws, the mesh is restored as it was.
    StepReport step(TetMesh& mesh);

private:
    void sweep_laplace(TetMesh& mesh, StepReport& report) const;

    int mode_ = 1;  // BODT_MODE_LAPLACE
    Params params_;
    int32_t steps_done_ = 0;
};

}  // namespace bodt
