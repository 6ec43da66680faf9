// A move for a vertex of a bad tet that the ODT update leaves bad:
// up the gradient of that tet's worst dihedral angle.  ODT (eq. 3 of paper
// 000) minimises the interpolation error, not the worst angle; where it has
// converged a tet with an angle outside [a, 180 - a] may still be fixed by
// moving one of its vertices away from it -- what optimisation-based
// smoothing (Freitag and Ollivier-Gooch 1997) does for the worst tet of a
// star.  Not in the three papers: BODT_MODE_BODT adds it from its second
// step on (BODT_PARAM_ASCENT_ANGLE).
#pragma once

#include "mesh/tet_mesh.hpp"
#include "quality/mesh_quality.hpp"
#include "smoothing/bodt_model.hpp"
#include "smoothing/star_table.hpp"

#include <cstdint>

namespace bodt {

class AngleAscent {
public:
    // Tets with an angle outside [angle_deg, 180 - angle_deg] are bad.
    explicit AngleAscent(double angle_deg);

    // The index in v's star (`star`, the shapes of the mesh's tets in
    // `shapes`) of its worst tet if that is bad, else star.size().
    size_t worst_tet(const TetMesh& mesh, int32_t v, const StarTable& star, const ShapeCache& shapes) const;

    // Where v goes to raise the worst angle of its star tet `worst` (from
    // worst_tet): false if the gradient vanishes.  The move is half as long
    // as the shortest edge of that tet at v; the guard shortens it.  An
    // inner vertex has no `basis`; a boundary vertex moves in the span of
    // its orthonormal columns (BodtSmoother::ascent_basis), up the
    // gradient projected onto it.
    bool target(const TetMesh& mesh, int32_t v, const StarTable& star, size_t worst, const MoveBasis* basis,
                Vec3& target) const;
    // Where to try when the guard refused that move (another angle of the
    // star, nearly as bad, would have fallen below the worst): along the
    // steepest ascent of the star's nearly worst angles together, as long
    // and in the same span.  False when there is none, or only one such
    // angle.
    bool steepest_target(const TetMesh& mesh, int32_t v, const StarTable& star, size_t worst, const MoveBasis* basis,
                         Vec3& target) const;

    // The cosine of 180 degrees - angle_deg: a tet with a larger angle is bad.
    double largest_cosine() const { return -bad_cosine_; }

    // Dihedral angles within this of the star's worst (radians) count as
    // active in the ascent; at most kMaxActive of them.
    static constexpr double kActiveAngle = 0.5 * M_PI / 180.0;
    static constexpr size_t kMaxActive = 12;

private:
    double bad_cosine_;  // cos a: a tet is bad when its worst_cosine exceeds it
};

}  // namespace bodt
