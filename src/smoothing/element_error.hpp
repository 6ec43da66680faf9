// Paper 001's element error, eq. (3.2): the inverse of the stretch quality
// (eq. 3.1), e(T) = (sum_i S_i) max_i L_i / (6 sqrt(6) V).  1 for the regular
// tet, growing without bound as T flattens, +infinity for a tet that is not
// positively oriented (certified).  Header-only so the quasi-Newton's many
// evaluations inline.
#pragma once

#include "quality/tet_geometry.hpp"

#include <limits>

namespace bodt {

inline constexpr double kSixRootSix = 14.696938456699067;  // 6 sqrt(6)

// e(T) and its gradient with respect to corner i.  With A the total face
// area, L the longest edge and V the volume, e = A L / (6 sqrt6 V), so
//   grad e = e (grad A / A + grad L / L - grad V / V),
// where grad S = (b - c) x n / 2 for a face (x, b, c) with unit normal n,
// grad L = (x - y) / L when the longest edge is (x, y) (0 when it does not
// touch corner i; at a tie the first longest edge is taken, a subgradient:
// e is not differentiable there, as the paper notes), and grad(6V) = -N for
// N the outward normal (length twice the area) of the face opposite x.
// Infinite e: the gradient is set to zero.
inline double element_error_gradient(const TetPoints& p, int i, Vec3& grad) {
    const Orientation o = orient(p[0], p[1], p[2], p[3]);
    if (o.sign <= 0) {
        grad.setZero();
        return std::numeric_limits<double>::infinity();
    }
    double area2 = 0.0;
    Vec3 grad_area2 = Vec3::Zero();  // gradient of twice the total area
    Vec3 grad_det6 = Vec3::Zero();
    for (int f = 0; f < 4; ++f) {
        const auto& q = kFaceVertex[f];
        const Vec3 n = (p[q[1]] - p[q[0]]).cross(p[q[2]] - p[q[0]]);
        const double len = n.norm();
        area2 += len;
        if (f == i) {
            grad_det6 = -n;
            continue;
        }
        // The face holds corner i: order it as (x, b, c) keeping its normal.
        const int k = q[0] == i ? 0 : (q[1] == i ? 1 : 2);
        const Vec3& b = p[q[(k + 1) % 3]];
        const Vec3& c = p[q[(k + 2) % 3]];
        if (len > 0.0) grad_area2 += (b - c).cross(n / len);
    }
    double lmax2 = 0.0;
    int longest = 0;
    for (int e = 0; e < 6; ++e) {
        const double l2 = (p[kEdgeVertex[e][1]] - p[kEdgeVertex[e][0]]).squaredNorm();
        if (l2 > lmax2) {
            lmax2 = l2;
            longest = e;
        }
    }
    const double lmax = std::sqrt(lmax2);
    Vec3 grad_l = Vec3::Zero();
    if (kEdgeVertex[longest][0] == i) grad_l = (p[i] - p[kEdgeVertex[longest][1]]) / lmax;
    if (kEdgeVertex[longest][1] == i) grad_l = (p[i] - p[kEdgeVertex[longest][0]]) / lmax;
    const double e = 3.0 * area2 * lmax / (kSixRootSix * o.det6);
    grad = e * (grad_area2 / area2 + grad_l / lmax - grad_det6 / o.det6);
    return e;
}

}  // namespace bodt
