// Which kind of bad tet a tet is (Cheng et al. 1999, "Sliver exudation",
// as used by paper 000 sec. 2.3), and the vertex insertion that breaks it.
//
// Cheng et al. name nine shapes with a dihedral angle near 0 or 180
// degrees.  Six of them (spire, spear, spindle, spike, splinter, wedge)
// owe it to one or more short edges, and ODT/B-ODT smoothing evens edge
// lengths out, so the paper leaves them to smoothing: here they are one
// kind, ShortEdge.  The other three are flat without a short edge and
// get new vertices:
//  - spade: a vertex A projects onto (near) the opposite edge BC: split BC
//    at the projection of A;
//  - cap: a vertex A projects inside the opposite face BCD: split BCD at
//    the projection of A;
//  - sliver: the four vertices project to a convex quadrilateral whose
//    diagonals AC and BD carry the two large dihedral angles: split AC and
//    BD at their closest points.
#pragma once

#include "quality/tet_geometry.hpp"

#include <array>
#include <cstdint>

namespace bodt {

enum class BadTetKind { Good, ShortEdge, Spade, Cap, Sliver };

struct BadTet {
    BadTetKind kind = BadTetKind::Good;
    int apex = -1;                 // spade, cap: local index of A
    std::array<int, 2> edge{};     // spade: B, C; sliver: A, C (local indices)
    std::array<int, 2> edge2{};    // sliver: B, D
    Vec3 point = Vec3::Zero();     // spade, cap: where the new vertex goes; sliver: on AC
    Vec3 point2 = Vec3::Zero();    // sliver: on BD
};

// A positively oriented tet is bad when its worst dihedral angle is below
// `bad_angle_deg` or above 180 - `bad_angle_deg`; an edge is short below
// `short_ratio` times the longest.
BadTet classify_bad_tet(const TetPoints& p, double bad_angle_deg, double short_ratio = 0.25);

}  // namespace bodt
