// Paper 000's objective around one vertex x0 (eq. 5, with eq. 7 and eq. 9 /
// Appendix A for the moving boundary) as a quadratic in X = x* - x0:
//
//   Error(X) = X^T Q X + g . X + const,
//   Q = 1/4 |Omega_0| I - 1/60 sum_i sym((Y_i + Y_{i+1}) C_i^T),
//   g = 1/12 sum_tau S_tau n_tau L_tau - 1/60 sum_i (Y_i^2 + Y_{i+1}^2 + Y_i.Y_{i+1}) C_i,
//
// with C_i = Y_i x Y_{i+1} over the vertex's boundary ring (empty for an
// inner vertex).  The cubic terms of eq. (9) vanish on the tangent plane
// (Appendix C), so the model is exact for every move the library makes.
//   - inner vertex, 3-D:          X = -g / (2 * 1/4 |Omega_0|)   = eq. (3)
//   - tangent plane (s, t), 2-D:  E = s.Qs, F = t.Qt, G = 2 s.Qt, H = s.g,
//                                 I = t.g, solve eq. (10)        = Alg. 2
//   - feature line d, 1-D:        A = d.Qd, B = d.g, f = -B/2A   = Alg. 3
// A vertex on the surface between regions gets one ring per region; their
// models add up, and the move must keep every region's volume (it stays
// orthogonal to each region's ring normal, Appendix B).
#pragma once

#include "mesh/tet_mesh.hpp"
#include "smoothing/star_table.hpp"

#include <Eigen/Core>

#include <vector>

namespace bodt {

// Up to three orthonormal columns spanning the directions a vertex may move
// in; fixed maximum size, so no heap allocation per vertex.
using MoveBasis = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3>;

struct StarModel {
    Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
    Vec3 g = Vec3::Zero();
    double volume = 0.0;  // |Omega_0|
};

// Adds the tets of the star of x0 (Alg. 1 step 1): |Omega_0|, and for each
// tet tau the term of g with S_tau n_tau the area vector of the face
// opposite x0, pointing into the tet, and L_tau the sum of squared edge
// lengths from x0.  `terms` is scratch space.
void add_star(StarModel& m, const StarTable& star, const Vec3& x0, std::vector<double>& terms);

// Adds one boundary-ring triangle (x0, y_i, y_{i+1}), ordered so that
// (y_i - x0) x (y_{i+1} - x0) points out of the star (paper 000 sec. 2.2).
// Returns C_i / 2 = S_i n_i, the ring triangle's area vector (eq. B.1).
Vec3 add_ring_triangle(StarModel& m, const Vec3& x0, const Vec3& yi, const Vec3& yj);

// The minimiser of the model on the span of the orthonormal columns of
// `basis` (1, 2 or 3 columns).  Returns false when the model is not
// positive definite there (4EF <= G^2, E <= 0, or A <= 0): the vertex must
// not move.
bool minimize_on(const StarModel& m, const MoveBasis& basis, Vec3& move);

// The five coefficients of Algorithm 2 for the tangent plane (s, t).
struct PlaneCoefficients {
    double E, F, G, H, I;
};
PlaneCoefficients plane_coefficients(const StarModel& m, const Vec3& s, const Vec3& t);

// Two unit vectors s, t spanning the plane orthogonal to n (Alg. 2 step 1).
void tangent_basis(const Vec3& n, Vec3& s, Vec3& t);

}  // namespace bodt
