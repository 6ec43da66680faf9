// The improvement pipeline of a mesh handle: the current mode, its
// parameters, the vertex classes the mode works with, and `step`: one
// Gauss-Seidel sweep over the vertices in colour order (coloured_sweep.hpp),
// then flips and vertex insertion where tets are still bad (paper 000
// Fig. 1), or, in BODT_MODE_OPT_WEIGHTED, one round of paper 001's combined
// algorithm (sec. 2): quasi-Newton on the vertices of poor tets, then swaps of the
// poor tets whose vertices all stay put; in BODT_MODE_PHASED_ODT, one round
// of paper 002 (Fig. 3): removal of inverted and degenerate tets, recovery
// of density and geometry, ODT by phases, flips.
#pragma once

#include "bodt.h"
#include "features/geometry_model.hpp"
#include "features/vertex_classes.hpp"
#include "mesh/region_surfaces.hpp"
#include "mesh/tet_mesh.hpp"
#include "pipeline/density_field.hpp"
#include "pipeline/params.hpp"
#include "smoothing/input_surface.hpp"
#include "smoothing/move_guard.hpp"
#include "smoothing/quasi_newton.hpp"
#include "smoothing/settled_vertices.hpp"
#include "topology/topology_pass.hpp"

#include <cstdint>

namespace bodt {

struct StepReport {
    int32_t step = 0;
    int32_t flips = 0, vertices_inserted = 0, edges_collapsed = 0;
    int32_t vertices_moved = 0;
    int32_t moves_rejected = 0;
    int32_t moves_shortened = 0;
    int32_t not_positive_definite = 0;
    double max_move = 0.0;
    double min_dihedral = 0.0, max_dihedral = 0.0, min_stretch = 0.0;
};

class Improver {
public:
    int mode() const { return mode_; }
    void set_mode(int mode);  // throws Error for an unknown mode
    const Params& params() const { return params_; }
    void set_param_int(int key, int32_t value);
    void set_param_double(int key, double value);

    // The classes are computed when first needed and kept until the mesh's
    // regions, markers, fixed vertices or feature edges change (the caller
    // says so here), the mode or a feature parameter does, or a step's
    // connectivity change alters a region surface.
    void mesh_data_changed() {
        classes_valid_ = false;
        geometry_valid_ = false;
        settled_.clear();
        steps_on_data_ = 0;
    }
    const VertexClasses& classes(const TetMesh& mesh, const RegionSurfaces& surfaces) const;

    // Paper 002's geometry (sec. 3.3): extracted from the mesh when first
    // needed, then carried through BODT_MODE_PHASED_ODT's steps; extracted
    // again after the mesh data, a feature parameter or another mode's
    // connectivity change.
    const GeometryModel& geometry(const TetMesh& mesh) const;
    // The undeformed mesh (same input vertices): the target density field
    // and the acceptable geometric errors (sec. 3.2, 3.3).
    void set_reference(const TetMesh& reference, const TetMesh& mesh);
    void set_target_density(DensityGrid grid) { density_ = std::move(grid); }
    void clear_reference();
    const DensityGrid& target_density() const { return density_; }

    // The bodt_op bits a step does: the parameter, or the mode's default.
    int32_t ops() const;

    // One step: a smoothing sweep, then the connectivity changes (which
    // rebuild the mesh's topology and surfaces).  If anything throws, the
    // mesh and surfaces are as they were.
    StepReport step(TetMesh& mesh, RegionSurfaces& surfaces);

private:
    // The classes of the modes other than paper 002's, made anew.
    VertexClasses classify(const TetMesh& mesh, const RegionSurfaces& surfaces) const;
    // The sweeps move no boundary or interface vertex.
    bool surface_stays() const;
    // The creases FlatPieces keeps: cosine at most this (-1: none).
    double crease_cosine() const;
    GuardSettings guard_settings() const;
    // Smoothing sweeps: Gauss-Seidel in colour order (coloured_sweep.hpp),
    // on BODT_PARAM_THREADS threads; `shapes` (tet_shapes() of the mesh as
    // it is, made if empty) is kept up to date by the moves.
    void sweep(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes, StepReport& report);
    void sweep_laplace(TetMesh& mesh, ShapeCache& shapes, StepReport& report) const;
    void sweep_bodt(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes, StepReport& report) const;
    void sweep_opt_weighted(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes,
                            StepReport& report) const;
    void sweep_nodt(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes, StepReport& report);
    QuasiNewtonSettings quasi_newton_settings() const;
    // Returns whether the connectivity changed.  All or nothing: the mesh
    // and surfaces are replaced at the end, or left as they were.
    bool change_topology(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report);
    void sweep_and_change(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report);
    void step_phased_or_restore(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report);
    void step_phased(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report);
    void sweep_phased(TetMesh& mesh, StepReport& report);
    void apply_reference_errors() const;

    int mode_ = BODT_MODE_BODT;
    Params params_;
    int32_t steps_done_ = 0;
    int32_t steps_on_data_ = 0;  // steps done since the mesh data last changed
    // tet_shapes() of the mesh as the last step left it, kept up to date by
    // the guarded sweeps and carried over by the topology passes; emptied
    // by whatever else moves a vertex or changes the connectivity (the
    // phased mode, a rolled-back step).  Only step() moves the vertices of
    // the handle's mesh.
    ShapeCache shapes_;
    mutable SettledVertices settled_;  // B-ODT sweeps: vertices that need no new try
    FailedAttempts failed_;            // flips and bad tets that failed, kept across steps while settled_ keeps time
    mutable VertexClasses classes_;  // a cache: computing it changes no result
    mutable bool classes_valid_ = false;
    mutable GeometryModel geometry_;  // carried state in the phased mode, a cache otherwise
    mutable bool geometry_valid_ = false;
    InputSurface nodt_input_;  // BODT_MODE_NODT projects onto it: the surface as captured
    DensityGrid density_;                  // the target density; empty: none
    std::vector<double> vertex_acceptable_;  // per input vertex: its reference region's acceptable error
    std::vector<Vec3> reference_points_;     // per input vertex: where the reference has it
};

}  // namespace bodt
