#include "smoothing/bodt_model.hpp"

#include <Eigen/Cholesky>

namespace bodt {

void add_star_tet(StarModel& m, const TetPoints& tet, int local) {
    const Vec3& x0 = tet[local];
    const auto& f = kFaceVertex[local];  // face opposite x0, normal pointing away from x0
    const Vec3 area_in = -0.5 * (tet[f[1]] - tet[f[0]]).cross(tet[f[2]] - tet[f[0]]);  // S_tau n_tau
    double L = 0.0;  // L_tau
    for (int j = 0; j < 4; ++j)
        if (j != local) L += (tet[j] - x0).squaredNorm();
    const double vol = signed_volume(tet[0], tet[1], tet[2], tet[3]);
    m.volume += vol;
    m.Q.diagonal().array() += 0.25 * vol;  // 1/4 |Omega_0| |X|^2, eq. (6)
    m.g += (L / 12.0) * area_in;           // eq. (7): (1/3) S n L over 4, see H in Alg. 2
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
