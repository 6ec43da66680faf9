// Natural ODT (Tournois, Wormser, Alliez, Desbrun 2009; the NODT column of
// paper 000, Table 1, described in its sec. 3): every vertex, inner
// or on the boundary, moves to paper 000's eq. (3) over its star as it is,
//
//   x* = x0 - 1/(2|Omega_0|) sum_tau (1/3) S_tau n_tau L_tau = x0 - 2 g / |Omega_0|,
//
// g the star model's eq. (7) terms (bodt_model.hpp), with no tangent-plane
// constraint and no term for the moving boundary.  For an inner vertex x*
// is the volume-weighted mean of the circumcentres c_tau of its tets; for a
// boundary vertex the open star adds a weighted sum of its ring triangles'
// normals to that mean (paper 000, sec. 3):
//
//   x* = (sum_tau |tau| c_tau - 1/12 sum_i (|Y_i|^2 + |Y_{i+1}|^2) C_i) / |Omega_0|,
//
// C_i = Y_i x Y_{i+1} over the boundary ring, pointing out.  A boundary
// vertex is then projected back onto the input surface (input_surface.hpp):
// a surface or interface vertex onto its patch, a feature-line vertex onto
// its line; corners and fixed vertices stay.  A move the guard refuses is
// halved and projected again.  The projection does not keep the volume.
#pragma once

#include "features/vertex_classes.hpp"
#include "mesh/region_surfaces.hpp"
#include "smoothing/bodt_smoother.hpp"
#include "smoothing/input_surface.hpp"
#include "smoothing/move_guard.hpp"

#include <vector>

namespace bodt {

class NodtSmoother {
public:
    // `guard` and `shapes` as for the other modes (move_guard.hpp): the
    // backtrack steps are the halvings of the natural move, each projected
    // before the guard sees it.
    NodtSmoother(const RegionSurfaces& surfaces, const VertexClasses& classes, const InputSurface& input,
                 const GuardSettings& guard, ShapeCache* shapes = nullptr);

    // The natural ODT position of v, not yet projected; `surface_faces`
    // receives the surface triangles around v (empty for an inner vertex).
    Plan target(const TetMesh& mesh, int32_t v, Vec3& target, std::vector<FaceKey>& surface_faces);

    // Moves v towards `target` through the guard, projected onto the input
    // surface; `distance` receives the length of the move made.  Follows
    // target() for the same v, whose star it reuses.
    MoveOutcome move(TetMesh& mesh, int32_t v, const Vec3& target, const std::vector<FaceKey>& surface_faces,
                     double& distance);

private:
    const RegionSurfaces& surfaces_;
    const VertexClasses& classes_;
    const InputSurface& input_;
    MoveGuard guard_;  // tries one position: the halving is done here
    int halvings_;
    std::vector<int32_t> ring_;
    std::vector<double> terms_;  // add_star()'s scratch
};

}  // namespace bodt
