#include "smoothing/bodt_model.hpp"

#include <Eigen/Cholesky>

namespace bodt {

namespace {

// Per tet of the star: its volume and its term of g (eq. 7), in columns of
// `terms` (4 rows of n).  Summed by the caller in tet order, so the result
// does not depend on the vector width.
BODT_VECTOR_CLONES
void star_terms(const double* face, size_t n, Coords x0, double* terms) {
#pragma omp simd
    for (size_t s = 0; s < n; ++s) {
        const Coords a{face[s], face[3 * n + s], face[6 * n + s]};
        const Coords b{face[n + s], face[4 * n + s], face[7 * n + s]};
        const Coords c{face[2 * n + s], face[5 * n + s], face[8 * n + s]};
        const Coords normal = cross(b - a, c - a);  // 2 S_tau, pointing away from x0
        const Coords ya = a - x0, yb = b - x0, yc = c - x0;
        const double L = dot(ya, ya) + dot(yb, yb) + dot(yc, yc);  // L_tau
        const double w = -0.5 * (L / 12.0);  // eq. (7): (1/3) S n L over 4, see H in Alg. 2
        terms[s] = dot(ya, normal) / 6.0;
        terms[n + s] = w * normal.x;
        terms[2 * n + s] = w * normal.y;
        terms[3 * n + s] = w * normal.z;
    }
}

}  // namespace

void add_star(StarModel& m, const StarTable& star, const Vec3& x0, std::vector<double>& terms) {
    const size_t n = star.size();
    terms.resize(4 * n);
    star_terms(star.opposite(), n, coords(x0), terms.data());
    double volume = 0.0, gx = m.g.x(), gy = m.g.y(), gz = m.g.z();
    for (size_t s = 0; s < n; ++s) {
        volume += terms[s];
        gx += terms[n + s];
        gy += terms[2 * n + s];
        gz += terms[3 * n + s];
    }
    m.g = Vec3(gx, gy, gz);
    m.volume += volume;
    m.Q.diagonal().array() += 0.25 * volume;  // 1/4 |Omega_0| |X|^2, eq. (6)
}

Vec3 add_ring_triangle(StarModel& m, const Vec3& x0, const Vec3& yi, const Vec3& yj) {
    const Vec3 Yi = yi - x0, Yj = yj - x0;
    const Vec3 C = Yi.cross(Yj);
    const Eigen::Matrix3d outer = (Yi + Yj) * C.transpose();
    m.Q -= (outer + outer.transpose()) / 120.0;  // 1/60 sym(.), eq. (9) quadratic terms
    m.g -= ((Yi.squaredNorm() + Yj.squaredNorm() + Yi.dot(Yj)) / 60.0) * C;  // eq. (9) linear terms
    return 0.5 * C;
}

bool minimize_on(const StarModel& m, const MoveBasis& basis, Vec3& move) {
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
    using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
    const Small Qk = basis.transpose() * m.Q * basis;
    const SmallVec gk = basis.transpose() * m.g;
    const Eigen::LLT<Small> llt(2.0 * Qk);  // the Hessian, Appendix C
    if (llt.info() != Eigen::Success || !(Qk.diagonal().minCoeff() > 0.0)) return false;
    move = basis * llt.solve(-gk);
    return move.allFinite();
}

PlaneCoefficients plane_coefficients(const StarModel& m, const Vec3& s, const Vec3& t) {
    return {s.dot(m.Q * s), t.dot(m.Q * t), 2.0 * s.dot(m.Q * t), s.dot(m.g), t.dot(m.g)};
}

void tangent_basis(const Vec3& n, Vec3& s, Vec3& t) {
    const Vec3 u = n.normalized();
    Eigen::Index axis;
    u.cwiseAbs().minCoeff(&axis);  // the axis least aligned with n
    s = u.cross(Vec3::Unit(axis)).normalized();
    t = u.cross(s);
}

}  // namespace bodt
