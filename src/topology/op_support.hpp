// Helpers the topology operations share: the acceptance test for a new tet,
// the input tet a new tet inherits, the parents of a new vertex, and the
// flatness tests that keep the surface's shape.
#pragma once

#include "topology/editable_mesh.hpp"
#include "topology/operations.hpp"

#include <array>
#include <vector>

namespace bodt {

// What a tet replacing `replaced` must reach: positive orientation, a worst
// dihedral sine above `must_exceed`, stretch at least min(rules.min_stretch,
// the worst replaced stretch) and, with rules.never_worse, no dihedral angle
// outside the replaced tets' range.
struct TetLimits {
    double must_exceed;
    double stretch_floor;
    bool keep_range;
    CosineRange range;
};
// limits_for's must_exceed: the worst sine a new tet must exceed.
double sine_floor(const TopologyRules& rules, double must_exceed);
TetLimits limits_for(const EditableMesh& mesh, const std::vector<int32_t>& replaced, const TopologyRules& rules,
                     double must_exceed);
bool acceptable_tet(const TetPoints& p, const TetLimits& limits);
// acceptable_tet without the sine test, for a caller that made it already.
bool acceptable_shape(const TetPoints& p, const TetLimits& limits);

// The tets touching any of `vs`, each once, ascending.
std::vector<int32_t> tets_touching(const EditableMesh& mesh, const std::vector<int32_t>& vs);

// ODT's target for an interior vertex (paper 000 eq. 3): the
// volume-weighted mean of the circumcentres of its star; false for other
// vertices or a star without positive volume.
bool odt_target(const EditableMesh& mesh, int32_t v, Vec3& target);

// Every tet of `tets` has none of `points` strictly inside its circumsphere.
bool all_delaunay(const std::vector<TetPoints>& tets, const std::vector<Vec3>& points);

// The extreme dihedral angles (as cosines) over `tets`; widen adds one tet
// (or its cosines).
CosineRange cosine_range(const EditableMesh& mesh, const std::vector<int32_t>& tets);
void widen(CosineRange& range, const TetPoints& p);
void widen(CosineRange& range, const CosineRange& c);
// `inner` lies within `outer`: its smallest angle no smaller, its largest no larger.
inline bool within(const CosineRange& inner, const CosineRange& outer) {
    return inner.of_min <= outer.of_min && inner.of_max >= outer.of_max;
}

// Barycentric coordinates of x in tet p.
std::array<double, 4> barycentric(const TetPoints& p, const Vec3& x);
// Of `tets`, the index of the one holding x most deeply (largest smallest
// barycentric coordinate), with x's coordinates in it.
size_t deepest_tet(const std::vector<TetPoints>& tets, const Vec3& x, std::array<double, 4>& lambda);

// The input tets new tets came from: for each, the origin of the replaced
// tet that holds its centroid most deeply.
std::vector<int32_t> origins_of(const EditableMesh& mesh, const std::vector<int32_t>& replaced,
                                const std::vector<Tet>& fresh);

// Parents of a point interpolated from mesh vertices vs[i] with weights
// ws[i] (those of weight 0 left out), expressed in input vertices.
Parents blend_parents(const EditableMesh& mesh, std::initializer_list<int32_t> vs, std::initializer_list<double> ws);

// x lies in the plane through p with normal n (not unit), to round-off of
// the mesh's scale `length`.
bool in_plane(const Vec3& n, const Vec3& p, const Vec3& x, double length);

// The least cosine between a surface face's normal before and after a
// change that may bend the surface (TopologyRules::surface_slope): the
// face turns by at most asin(surface_slope); 0 without a slope (the face
// only keeps its side).
double least_turn_cosine(const TopologyRules& rules);

// The outward normal (not unit) of face (a, b, c).
inline Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) { return (b - a).cross(c - a); }

}  // namespace bodt
