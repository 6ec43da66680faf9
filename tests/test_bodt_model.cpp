// test_bodt_model: white-box tests of the B-ODT star model (links bodt_core)
// against paper 000's energy, eq. (5), evaluated exactly in the test:
//
//   Error(x*) = sum over the star's tets (x0 moved to x*) of
//               |tau| * mean of f at the four corners  -  int_tau f,
//   f(x) = |x - x0|^2 with x0 the vertex's old position, and
//   int_tau f = |tau| / 20 * (sum_i |p_i|^2 + |sum_i p_i|^2), p_i = corner - x0.
//
// Random stars, built here:
//   boundary star  x0 on a plane-ish surface, a ring y_1..y_m (m = 5..8,
//                  random radii, angles and small heights) ordered so that
//                  (y_i - x0) x (y_{i+1} - x0) points out of the star, and the
//                  tets (x0, y_{i+1}, y_i, z) to an apex z below; then a
//                  random rotation and shift
//   inner star     x0 inside a perturbed icosahedron or octahedron, one tet
//                  per face
//
//   coefficients  E, F, G, H, I (plane_coefficients) = the printed sums of
//                 Algorithm 2, computed here from the ring and the tets
//   (c) exact     X^T Q X + g.X = Error(x0 + X) - Error(x0) for tangent X
//                 (every X for an inner star), to 1e-12 relative
//   (a) eq. (10)  its (u, v) = a numerical minimisation of the exact energy
//                 on the tangent plane (Newton on finite differences), to
//                 1e-9 of the star size
//   (b) Alg. 3    f = -B / 2A along a random tangent d = the numerical 1-D
//                 minimum; minimize_on with the one column d agrees
//   (d) volume    tangent moves keep the star's volume to 1e-14 relative
//   (e) eq. (3)   minimize_on with the identity = eq. (3) computed here = the
//                 volume-weighted circumcentre average
//   (f) ascent    where moves up the worst tet's worst-angle gradient
//                 (AngleAscent::target, halved up to 16 times, taken when
//                 the star's worst angle rises) are stuck, the steepest
//                 ascent (steepest_target) still raises it, and no unit
//                 direction of 2000 raises the angles within kActiveAngle
//                 of the worst faster to first order
#include "smoothing/bodt_model.hpp"
#include "smoothing/angle_ascent.hpp"

#include "mesh_gen.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "test_util.h"
#include "core_checks.hpp"

namespace {

using bodt::Vec3;
using Mat3 = Eigen::Matrix3d;

// ------------------------------------------------------------ stars

struct Star {
    Vec3 x0;
    std::vector<bodt::TetPoints> tets;  // positively oriented
    std::vector<int> local;             // where x0 is in each tet
    std::vector<Vec3> ring;             // boundary ring y_1..y_m; empty for an inner star
    double radius = 0.0;                // largest |p - x0|
};

double orient6(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).dot((c - a).cross(d - a));
}

// The tet (a, b, c, d) reordered by an even permutation that puts a at
// index `at`: the orientation is kept.
bodt::TetPoints place(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int at, int& local) {
    local = at;
    switch (at) {
        case 0: return {a, b, c, d};
        case 1: return {b, a, d, c};
        case 2: return {c, d, a, b};
        default: return {d, c, b, a};
    }
}

void finish(Star& s) {
    s.radius = 0.0;
    for (const auto& t : s.tets)
        for (const Vec3& p : t) s.radius = std::max(s.radius, (p - s.x0).norm());
    for (const auto& t : s.tets)
        if (!(orient6(t[0], t[1], t[2], t[3]) > 0.0)) fail_msg("a star tet is not positively oriented");
}

Star boundary_star(Rng& rng) {
    const int m = 5 + static_cast<int>(rng.uniform(0, 4));  // 5..8
    std::vector<Vec3> ring;
    for (int i = 0; i < m; ++i) {
        const double angle = 2 * M_PI * (i + rng.uniform(-0.3, 0.3)) / m;
        const double r = rng.uniform(0.6, 1.4);
        ring.emplace_back(r * std::cos(angle), r * std::sin(angle), rng.uniform(-0.15, 0.15));
    }
    const Vec3 x0(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.05, 0.05));
    const Vec3 apex(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), -rng.uniform(0.7, 1.2));
    const Mat3 R = random_rotation(rng);
    const Vec3 shift(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    const auto map = [&](const Vec3& p) -> Vec3 { return R * p + shift; };

    Star s;
    s.x0 = map(x0);
    for (const Vec3& y : ring) s.ring.push_back(map(y));
    const Vec3 z = map(apex);
    for (int i = 0; i < m; ++i) {
        const Vec3 &yi = s.ring[i], &yj = s.ring[(i + 1) % m];
        // the paper's order: (y_i - x0) x (y_{i+1} - x0) points out of the star,
        // away from the apex below
        if (!((yi - s.x0).cross(yj - s.x0).dot(s.x0 - z) > 0.0)) fail_msg("ring triangle %d points into the star", i);
        int local = 0;
        s.tets.push_back(place(s.x0, yj, yi, z, i % 4, local));
        s.local.push_back(local);
    }
    finish(s);
    return s;
}

// The faces of a convex polyhedron whose faces are equilateral triangles:
// the triples at the smallest pairwise distance, oriented outwards.
std::vector<std::array<int, 3>> equilateral_faces(const std::vector<Vec3>& p) {
    double edge = 1e300;
    for (size_t a = 0; a < p.size(); ++a)
        for (size_t b = a + 1; b < p.size(); ++b) edge = std::min(edge, (p[a] - p[b]).norm());
    const auto is_edge = [&](size_t a, size_t b) { return std::fabs((p[a] - p[b]).norm() - edge) < 1e-9; };
    std::vector<std::array<int, 3>> faces;
    for (size_t a = 0; a < p.size(); ++a)
        for (size_t b = a + 1; b < p.size(); ++b)
            for (size_t c = b + 1; c < p.size(); ++c)
                if (is_edge(a, b) && is_edge(b, c) && is_edge(a, c)) {
                    std::array<int, 3> f{int(a), int(b), int(c)};
                    if ((p[b] - p[a]).cross(p[c] - p[a]).dot(p[a] + p[b] + p[c]) < 0) std::swap(f[1], f[2]);
                    faces.push_back(f);
                }
    return faces;
}

Star inner_star(Rng& rng, bool icosahedron) {
    std::vector<Vec3> p;
    if (icosahedron) {
        const double phi = (1 + std::sqrt(5.0)) / 2;
        for (int a = -1; a <= 1; a += 2)
            for (int b = -1; b <= 1; b += 2) {
                p.emplace_back(0, a, b * phi);
                p.emplace_back(a, b * phi, 0);
                p.emplace_back(b * phi, 0, a);
            }
    } else {
        for (int k = 0; k < 3; ++k)
            for (int sgn = -1; sgn <= 1; sgn += 2) p.push_back(sgn * Vec3::Unit(k));
    }
    const auto faces = equilateral_faces(p);
    assert_int_equal(static_cast<int>(faces.size()), icosahedron ? 20 : 8);
    const Mat3 R = random_rotation(rng);
    const Vec3 shift(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    std::vector<Vec3> q;
    for (const Vec3& v : p) {
        const Vec3 dir = (v.normalized() + Vec3(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)))
                             .normalized();
        q.push_back(R * (rng.uniform(0.7, 1.3) * dir) + shift);
    }
    Star s;
    s.x0 = R * Vec3(rng.uniform(-0.15, 0.15), rng.uniform(-0.15, 0.15), rng.uniform(-0.15, 0.15)) + shift;
    for (size_t f = 0; f < faces.size(); ++f) {
        int local = 0;
        s.tets.push_back(place(s.x0, q[faces[f][0]], q[faces[f][1]], q[faces[f][2]], static_cast<int>(f % 4), local));
        s.local.push_back(local);
    }
    finish(s);
    return s;
}

// ------------------------------------------------- the exact energy (5)

// Error(x0 + X), with f centred at the old x0.
double energy(const Star& s, const Vec3& X) {
    double e = 0.0;
    for (size_t k = 0; k < s.tets.size(); ++k) {
        bodt::TetPoints t = s.tets[k];
        t[s.local[k]] = s.x0 + X;
        const double vol = orient6(t[0], t[1], t[2], t[3]) / 6.0;
        double sum_f = 0.0;
        Vec3 sum_p = Vec3::Zero();
        for (const Vec3& c : t) {
            const Vec3 p = c - s.x0;
            sum_f += p.squaredNorm();
            sum_p += p;
        }
        e += vol * sum_f / 4.0 - vol / 20.0 * (sum_f + sum_p.squaredNorm());
    }
    return e;
}

double star_volume(const Star& s, const Vec3& X) {
    double v = 0.0;
    for (size_t k = 0; k < s.tets.size(); ++k) {
        bodt::TetPoints t = s.tets[k];
        t[s.local[k]] = s.x0 + X;
        v += orient6(t[0], t[1], t[2], t[3]) / 6.0;
    }
    return v;
}

// The library's model of the star: add_star over its tets,
// add_ring_triangle for every ring triangle; returns the ring normal (B.1).
bodt::StarModel model_of(const Star& s, Vec3& normal) {
    bodt::StarModel m;
    bodt::StarTable table;
    table.resize(s.tets.size());
    for (size_t k = 0; k < s.tets.size(); ++k) table.set(k, s.tets[k], s.local[k]);
    std::vector<double> terms;
    bodt::add_star(m, table, s.x0, terms);
    normal = Vec3::Zero();
    const size_t n = s.ring.size();
    for (size_t i = 0; i < n; ++i) normal += bodt::add_ring_triangle(m, s.x0, s.ring[i], s.ring[(i + 1) % n]);
    return m;
}

// Minimises the exact energy on x0 + span(columns of B) by Newton's method
// with central finite differences (gradient and Hessian); the energy is a
// quadratic there, so a few iterations reach round-off.
template <int K>
Eigen::Matrix<double, K, 1> newton_min(const Star& s, const Eigen::Matrix<double, 3, K>& B) {
    using VecK = Eigen::Matrix<double, K, 1>;
    using MatK = Eigen::Matrix<double, K, K>;
    const double h = 1e-2 * s.radius;
    const auto E = [&](const VecK& c) { return energy(s, B * c); };
    VecK c = VecK::Zero();
    for (int iter = 0; iter < 4; ++iter) {
        VecK grad;
        MatK hess;
        const double e0 = E(c);
        for (int a = 0; a < K; ++a) {
            VecK ea = VecK::Zero();
            ea[a] = h;
            grad[a] = (E(c + ea) - E(c - ea)) / (2 * h);
            hess(a, a) = (E(c + ea) - 2 * e0 + E(c - ea)) / (h * h);
            for (int b = a + 1; b < K; ++b) {
                VecK eb = VecK::Zero();
                eb[b] = h;
                hess(a, b) = hess(b, a) = (E(c + ea + eb) - E(c + ea - eb) - E(c - ea + eb) + E(c - ea - eb)) / (4 * h * h);
            }
        }
        c -= hess.ldlt().solve(grad);
    }
    return c;
}

// The coefficients of Algorithm 2, from the printed sums.
struct Coeffs {
    double E, F, G, H, I;
};

Coeffs paper_coefficients(const Star& s, const Vec3& sv, const Vec3& tv) {
    double vol = 0.0;
    Vec3 snl = Vec3::Zero();  // sum_tau S_tau n_tau L_tau, n_tau into tau
    for (size_t k = 0; k < s.tets.size(); ++k) {
        const auto& t = s.tets[k];
        vol += orient6(t[0], t[1], t[2], t[3]) / 6.0;
        std::vector<Vec3> o;
        for (int j = 0; j < 4; ++j)
            if (j != s.local[k]) o.push_back(t[j]);
        Vec3 area = 0.5 * (o[1] - o[0]).cross(o[2] - o[0]);
        if (area.dot(s.x0 - o[0]) < 0) area = -area;  // into tau: towards x0
        double L = 0.0;
        for (const Vec3& p : o) L += (p - s.x0).squaredNorm();
        snl += area * L;
    }
    Coeffs c{vol / 4, vol / 4, 0.0, snl.dot(sv) / 12, snl.dot(tv) / 12};
    const size_t m = s.ring.size();
    for (size_t i = 0; i < m; ++i) {
        const Vec3 Yi = s.ring[i] - s.x0, Yj = s.ring[(i + 1) % m] - s.x0;
        const Vec3 C = Yi.cross(Yj), Ysum = Yi + Yj;
        const double q = Yi.squaredNorm() + Yj.squaredNorm() + Yi.dot(Yj);
        c.E -= sv.dot(Ysum) * sv.dot(C) / 60;
        c.F -= tv.dot(Ysum) * tv.dot(C) / 60;
        c.G -= (sv.dot(Ysum) * tv.dot(C) + tv.dot(Ysum) * sv.dot(C)) / 60;
        c.H -= q * sv.dot(C) / 60;
        c.I -= q * tv.dot(C) / 60;
    }
    return c;
}

constexpr int kBoundaryStars = 200;
constexpr int kInnerStars = 100;

// ---------------------------------------------------------------- tests

void test_tangent_basis(void**) {
    Rng rng(5);
    std::vector<Vec3> normals = {Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitZ(), Vec3(1, 1, 0), Vec3(3, -1e-9, 2)};
    for (int k = 0; k < 100; ++k) normals.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    for (const Vec3& n : normals) {
        Vec3 s, t;
        bodt::tangent_basis(n * 3.7, s, t);
        assert_near(s.norm(), 1.0, 1e-15);
        assert_near(t.norm(), 1.0, 1e-15);
        assert_near(s.dot(t), 0.0, 1e-15);
        assert_near(s.dot(n.normalized()), 0.0, 1e-15);
        assert_near(t.dot(n.normalized()), 0.0, 1e-15);
    }
}

// E, F, G, H, I as printed in Algorithm 2.
void test_plane_coefficients(void**) {
    Rng rng(101);
    for (int k = 0; k < kBoundaryStars; ++k) {
        const Star s = boundary_star(rng);
        Vec3 n, sv, tv;
        const bodt::StarModel m = model_of(s, n);
        bodt::tangent_basis(n, sv, tv);
        const bodt::PlaneCoefficients got = bodt::plane_coefficients(m, sv, tv);
        const Coeffs want = paper_coefficients(s, sv, tv);
        const double scale2 = m.volume, scale3 = m.volume * s.radius;  // sizes of E and of H
        if (!(std::fabs(got.E - want.E) <= 1e-13 * scale2 && std::fabs(got.F - want.F) <= 1e-13 * scale2 &&
              std::fabs(got.G - want.G) <= 1e-13 * scale2 && std::fabs(got.H - want.H) <= 1e-13 * scale3 &&
              std::fabs(got.I - want.I) <= 1e-13 * scale3))
            fail_msg("star %d: E F G H I = %g %g %g %g %g, Algorithm 2 gives %g %g %g %g %g", k, got.E, got.F, got.G,
                     got.H, got.I, want.E, want.F, want.G, want.H, want.I);
        assert_near(m.volume, star_volume(s, Vec3::Zero()), 1e-14 * m.volume);
    }
}

// (c): the model is exact for tangent moves (cubic terms vanish, App. C).
void test_model_exact_on_tangent_plane(void**) {
    Rng rng(202);
    double worst = 0.0;
    for (int k = 0; k < kBoundaryStars; ++k) {
        const Star s = boundary_star(rng);
        Vec3 n, sv, tv;
        const bodt::StarModel m = model_of(s, n);
        bodt::tangent_basis(n, sv, tv);
        const double e0 = energy(s, Vec3::Zero()), scale = m.volume * s.radius * s.radius;
        for (int trial = 0; trial < 5; ++trial) {
            const Vec3 X = s.radius * (rng.uniform(-0.3, 0.3) * sv + rng.uniform(-0.3, 0.3) * tv);
            const double predicted = X.dot(m.Q * X) + m.g.dot(X);
            const double exact = energy(s, X) - e0;
            const double err = std::fabs(predicted - exact) / scale;
            worst = std::max(worst, err);
            if (!(err <= 1e-12))
                fail_msg("star %d: model %.17g, eq. (5) %.17g (relative error %g)", k, predicted, exact, err);
        }
        // Off the plane the exact energy has a cubic term the model lacks:
        // the check above can see a difference.
        const Vec3 X = 0.3 * s.radius * n.normalized();
        const double off = std::fabs(X.dot(m.Q * X) + m.g.dot(X) - (energy(s, X) - e0)) / scale;
        if (!(off > 1e-6)) fail_msg("star %d: the model is exact off the tangent plane too (%g)?", k, off);
    }
    print_message("largest relative error of the model on the tangent plane: %.3g\n", worst);
}

// (a): eq. (10) = the minimum of the exact energy on the tangent plane.
void test_eq10_is_the_minimum(void**) {
    Rng rng(303);
    double worst = 0.0;
    for (int k = 0; k < kBoundaryStars; ++k) {
        const Star s = boundary_star(rng);
        Vec3 n, sv, tv;
        const bodt::StarModel m = model_of(s, n);
        bodt::tangent_basis(n, sv, tv);
        const bodt::PlaneCoefficients c = bodt::plane_coefficients(m, sv, tv);
        const double det = 4 * c.E * c.F - c.G * c.G;
        if (!(det > 0 && c.E > 0)) fail_msg("star %d: eq. (10) is not positive definite (4EF - G^2 = %g)", k, det);
        // [2E G; G 2F] [u v]^T = [-H -I]^T
        const double u = (-c.H * 2 * c.F + c.I * c.G) / det, v = (-c.I * 2 * c.E + c.H * c.G) / det;
        Eigen::Matrix<double, 3, 2> B;
        B << sv, tv;
        const Eigen::Vector2d uv = newton_min<2>(s, B);
        const double err = std::hypot(u - uv[0], v - uv[1]) / s.radius;
        worst = std::max(worst, err);
        if (!(err <= 1e-9))
            fail_msg("star %d: eq. (10) gives (%.12g, %.12g), the exact energy's minimum is (%.12g, %.12g)", k, u, v,
                     uv[0], uv[1]);
        // minimize_on with the basis (s, t) is the same move
        bodt::MoveBasis basis(3, 2);
        basis << sv, tv;
        Vec3 move;
        assert_true(bodt::minimize_on(m, basis, move));
        if (!((move - (u * sv + v * tv)).norm() <= 1e-12 * s.radius))
            fail_msg("star %d: minimize_on moves by (%g %g %g), eq. (10) by (%g %g %g)", k, move.x(), move.y(),
                     move.z(), (u * sv + v * tv).x(), (u * sv + v * tv).y(), (u * sv + v * tv).z());
        // and the minimum is a minimum of the exact energy: no nearby point is lower
        const double e_min = energy(s, move);
        for (int d = 0; d < 8; ++d) {
            const double a = 2 * M_PI * d / 8;
            const Vec3 probe = move + 1e-3 * s.radius * (std::cos(a) * sv + std::sin(a) * tv);
            assert_true(energy(s, probe) > e_min);
        }
    }
    print_message("largest distance between eq. (10) and the numerical minimum: %.3g of the star size\n", worst);
}

// (b): Algorithm 3 along a random tangent direction.
void test_feature_line_minimum(void**) {
    Rng rng(404);
    double worst = 0.0;
    for (int k = 0; k < kBoundaryStars; ++k) {
        const Star s = boundary_star(rng);
        Vec3 n, sv, tv;
        const bodt::StarModel m = model_of(s, n);
        bodt::tangent_basis(n, sv, tv);
        const double phi = rng.uniform(0, 2 * M_PI);
        const Vec3 d = std::cos(phi) * sv + std::sin(phi) * tv;
        // A and B of Algorithm 3, as printed (E and H of Algorithm 2 with s = d)
        const Vec3 other = n.normalized().cross(d);
        const Coeffs paper = paper_coefficients(s, d, other);
        const double A = paper.E, Bc = paper.H;
        assert_true(A > 0);
        const double f = -Bc / (2 * A);
        const Eigen::Matrix<double, 1, 1> num = newton_min<1>(s, Eigen::Matrix<double, 3, 1>(d));
        const double err = std::fabs(f - num[0]) / s.radius;
        worst = std::max(worst, err);
        if (!(err <= 1e-9)) fail_msg("star %d: f = -B/2A = %.12g, the 1-D minimum is at %.12g", k, f, num[0]);
        bodt::MoveBasis basis(3, 1);
        basis << d;
        Vec3 move;
        assert_true(bodt::minimize_on(m, basis, move));
        if (!((move - f * d).norm() <= 1e-12 * s.radius))
            fail_msg("star %d: minimize_on along d moves by %g, Algorithm 3 by %g", k, move.dot(d), f);
    }
    print_message("largest distance between -B/2A and the 1-D minimum: %.3g of the star size\n", worst);
}

// (d): tangent moves keep the star's volume (Appendix B).
void test_tangent_moves_keep_volume(void**) {
    Rng rng(505);
    double worst = 0.0;
    for (int k = 0; k < kBoundaryStars; ++k) {
        const Star s = boundary_star(rng);
        Vec3 n, sv, tv;
        const bodt::StarModel m = model_of(s, n);
        bodt::tangent_basis(n, sv, tv);
        // B.4: the ring's area vector is the sum of the opposite faces' S_tau n_tau
        Vec3 opposite = Vec3::Zero();
        for (size_t q = 0; q < s.tets.size(); ++q) {
            std::vector<Vec3> o;
            for (int j = 0; j < 4; ++j)
                if (j != s.local[q]) o.push_back(s.tets[q][j]);
            Vec3 area = 0.5 * (o[1] - o[0]).cross(o[2] - o[0]);
            if (area.dot(s.x0 - o[0]) < 0) area = -area;
            opposite += area;
        }
        assert_true((opposite - n).norm() <= 1e-13 * n.norm());
        const double v0 = star_volume(s, Vec3::Zero());
        assert_near(m.volume, v0, 1e-14 * v0);
        for (int trial = 0; trial < 5; ++trial) {
            const Vec3 X = s.radius * (rng.uniform(-0.3, 0.3) * sv + rng.uniform(-0.3, 0.3) * tv);
            const double err = std::fabs(star_volume(s, X) - v0) / v0;
            worst = std::max(worst, err);
            if (!(err <= 1e-14)) fail_msg("star %d: a tangent move changed the volume by %g relative", k, err);
        }
        // a move along the normal does change it
        assert_true(std::fabs(star_volume(s, 0.1 * s.radius * n.normalized()) - v0) > 1e-3 * v0);
    }
    print_message("largest relative volume change of a tangent move: %.3g\n", worst);
}

// Volume-weighted circumcentre average of an inner star.
Vec3 circumcentre_average(const Star& s) {
    Vec3 sum = Vec3::Zero();
    double vol = 0.0;
    for (const auto& t : s.tets) {
        Mat3 A;
        Vec3 b;
        for (int i = 0; i < 3; ++i) {
            A.row(i) = 2 * (t[i + 1] - t[0]).transpose();
            b[i] = t[i + 1].squaredNorm() - t[0].squaredNorm();
        }
        const Vec3 c = A.fullPivLu().solve(b);
        const double v = orient6(t[0], t[1], t[2], t[3]) / 6.0;
        sum += v * c;
        vol += v;
    }
    return sum / vol;
}

// (e) and (c) for inner stars.
void test_inner_star_odt(void**) {
    Rng rng(606);
    double worst = 0.0;
    for (int k = 0; k < kInnerStars; ++k) {
        const Star s = inner_star(rng, k % 2 == 0);
        Vec3 n;
        const bodt::StarModel m = model_of(s, n);  // no ring: n = 0
        assert_true(n == Vec3::Zero());
        // eq. (3), computed here
        double vol = 0.0;
        Vec3 sum = Vec3::Zero();
        for (size_t q = 0; q < s.tets.size(); ++q) {
            const auto& t = s.tets[q];
            vol += orient6(t[0], t[1], t[2], t[3]) / 6.0;
            std::vector<Vec3> o;
            for (int j = 0; j < 4; ++j)
                if (j != s.local[q]) o.push_back(t[j]);
            Vec3 normal = (o[1] - o[0]).cross(o[2] - o[0]);
            const double S = 0.5 * normal.norm();
            normal.normalize();
            if (normal.dot(s.x0 - o[0]) < 0) normal = -normal;  // into tau
            double L = 0.0;
            for (const Vec3& p : o) L += (p - s.x0).squaredNorm();
            sum += S * normal * L / 3.0;
        }
        const Vec3 eq3 = s.x0 - sum / (2 * vol);
        bodt::MoveBasis basis = Mat3::Identity();
        Vec3 move;
        assert_true(bodt::minimize_on(m, basis, move));
        const Vec3 lib = s.x0 + move;
        const Vec3 cc = circumcentre_average(s);
        const double e1 = (lib - eq3).norm() / s.radius, e2 = (eq3 - cc).norm() / s.radius;
        worst = std::max({worst, e1, e2});
        if (!(e1 <= 1e-10 && e2 <= 1e-10))
            fail_msg("inner star %d: minimize_on (%.12g %.12g %.12g), eq. (3) (%.12g %.12g %.12g), circumcentres "
                     "(%.12g %.12g %.12g)",
                     k, lib.x(), lib.y(), lib.z(), eq3.x(), eq3.y(), eq3.z(), cc.x(), cc.y(), cc.z());
        // the model is exact for every move of an inner vertex
        const double e0 = energy(s, Vec3::Zero()), scale = m.volume * s.radius * s.radius;
        for (int trial = 0; trial < 5; ++trial) {
            const Vec3 X = 0.3 * s.radius * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
            const double err = std::fabs(X.dot(m.Q * X) + m.g.dot(X) - (energy(s, X) - e0)) / scale;
            if (!(err <= 1e-12)) fail_msg("inner star %d: the model is off eq. (5) by %g relative", k, err);
        }
        // and eq. (3) is the numerical minimum of the exact energy
        const Vec3 num = newton_min<3>(s, Mat3::Identity());
        if (!((num - move).norm() <= 1e-9 * s.radius))
            fail_msg("inner star %d: the numerical minimum is %g away from eq. (3)", k, (num - move).norm());
    }
    print_message("inner stars: largest distance between minimize_on, eq. (3) and the circumcentre average: %.3g\n",
                  worst);
}

// minimize_on refuses a model that is not positive definite on the basis.
void test_minimize_on_refuses_indefinite(void**) {
    bodt::StarModel m;
    m.Q = Mat3::Identity();
    m.Q(2, 2) = -1.0;
    m.g = Vec3(1, 2, 3);
    Vec3 move(7, 7, 7);
    bodt::MoveBasis plane(3, 2);
    plane << Vec3::UnitX(), Vec3::UnitY();
    assert_true(bodt::minimize_on(m, plane, move));
    assert_true((move - Vec3(-0.5, -1, 0)).norm() < 1e-15);
    bodt::MoveBasis line(3, 1);
    line << Vec3::UnitZ();
    assert_false(bodt::minimize_on(m, line, move));
    bodt::MoveBasis all = Mat3::Identity();
    assert_false(bodt::minimize_on(m, all, move));
}


// The star's worst |cosine| (worst_cosine of its worst tet) with x0 at x.
double star_worst_cosine(const Star& s, const Vec3& x) {
    double worst = 0.0;
    for (size_t k = 0; k < s.tets.size(); ++k) {
        bodt::TetPoints t = s.tets[k];
        t[s.local[k]] = x;
        worst = std::max(worst, bodt::worst_cosine(bodt::tet_shape(t).cosines));
    }
    return worst;
}

// (f) on inner stars with x0 pushed off centre.
void test_steepest_ascent(void**) {
    Rng rng(808);
    const bodt::AngleAscent ascent(30.0);
    int stuck = 0, raised = 0;
    for (int k = 0; k < kInnerStars; ++k) {
        Star s = inner_star(rng, k % 2 == 0);
        bodt::StarTable table;
        table.resize(s.tets.size());
        for (size_t q = 0; q < s.tets.size(); ++q) table.set(q, s.tets[q], s.local[q]);
        bodt::TetMesh mesh;  // target() reads only v's point
        mesh.points = {s.x0 + 0.5 * s.radius * Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1))};
        const auto worst_tet = [&](const Vec3& x) {
            size_t worst = 0;
            double most = -1.0;
            for (size_t q = 0; q < s.tets.size(); ++q) {
                bodt::TetPoints t = s.tets[q];
                t[s.local[q]] = x;
                const double b = bodt::worst_cosine(bodt::tet_shape(t).cosines);
                if (b > most) most = b, worst = q;
            }
            return worst;
        };
        if (star_worst_cosine(s, mesh.points[0]) >= 1.0) continue;  // pushed out of its star
        // Up the single gradient until no halving of its move raises the worst angle.
        for (int iter = 0; iter < 500; ++iter) {
            const Vec3 x = mesh.points[0];
            Vec3 target;
            bool better = false;
            if (ascent.target(mesh, 0, table, worst_tet(x), nullptr, target)) {
                Vec3 step = target - x;
                for (int h = 0; h <= 16 && !better; ++h, step *= 0.5)
                    better = star_worst_cosine(s, x + step) < star_worst_cosine(s, x);
                if (better) mesh.points[0] = x + 2.0 * step;  // undo the last halving
            }
            if (!better) break;
        }
        const Vec3 x = mesh.points[0];
        const double f0 = star_worst_cosine(s, x);
        Vec3 target;
        if (!ascent.steepest_target(mesh, 0, table, worst_tet(x), nullptr, target)) continue;
        ++stuck;
        // The dihedral angles within kActiveAngle of the star's worst, and
        // the slope of the largest of their |cosines| along a unit
        // direction (each by its own difference quotient).
        const double active = std::cos(std::acos(f0) + bodt::AngleAscent::kActiveAngle);
        const double eps = 1e-7 * s.radius;
        const auto slope = [&](const Vec3& w) {
            double most = -1e300;
            for (size_t q = 0; q < s.tets.size(); ++q) {
                bodt::TetPoints t = s.tets[q], moved = t;
                t[s.local[q]] = x;
                moved[s.local[q]] = x + eps * w;
                const bodt::TetKernel a = bodt::tet_kernel(t), b = bodt::tet_kernel(moved);
                for (int e = 0; e < 6; ++e)
                    if (std::fabs(a.cos[e]) >= active)
                        most = std::max(most, (std::fabs(b.cos[e]) - std::fabs(a.cos[e])) / eps);
            }
            return most;
        };
        const Vec3 u = (target - x).normalized();
        const double steepest = slope(u);
        if (steepest < 0.0 && star_worst_cosine(s, x + eps * u) < f0) ++raised;
        else print_message("star %d: slope %g along the steepest ascent\n", k, steepest);
        for (int d = 0; d < 2000; ++d) {
            const Vec3 w = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)).normalized();
            const double other = slope(w);
            if (other < steepest - 1e-4 * std::fabs(steepest))
                fail_msg("star %d: direction %d descends at %g, the steepest ascent at %g", k, d, other, steepest);
        }
    }
    print_message("stuck stars with a steepest ascent %d, raised %d of %d\n", stuck, raised, kInnerStars);
    assert_true(stuck >= kInnerStars / 5);
    assert_int_equal(raised, stuck);
}

}  // namespace

int main() {
    const CMUnitTest tests[] = {
        cmocka_unit_test(test_tangent_basis),
        cmocka_unit_test(test_plane_coefficients),
        cmocka_unit_test(test_model_exact_on_tangent_plane),
        cmocka_unit_test(test_eq10_is_the_minimum),
        cmocka_unit_test(test_feature_line_minimum),
        cmocka_unit_test(test_tangent_moves_keep_volume),
        cmocka_unit_test(test_inner_star_odt),
        cmocka_unit_test(test_minimize_on_refuses_indefinite),
        cmocka_unit_test(test_steepest_ascent),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
