#include "smoothing/quasi_newton.hpp"

#include "smoothing/element_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodt {

void WeightedStar::add(const TetPoints& p, int corner, double weight) {
    // An even permutation of the corners that brings `corner` first keeps
    // the orientation.
    static constexpr int kOrder[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
    const int* o = kOrder[corner];
    Term t{p, corner, weight, p[o[1]], p[o[2]], p[o[3]], Vec3::Zero(), 0.0, 0.0};
    t.n = (t.c - t.b).cross(t.d - t.b);
    t.fixed_area2 = t.n.norm();
    t.fixed_edge2 = std::max({(t.c - t.b).squaredNorm(), (t.d - t.b).squaredNorm(), (t.d - t.c).squaredNorm()});
    terms_.push_back(t);
}

// Eq. (3.4) on the star, each e(T) as in element_error_gradient but from the
// precomputed parts.  A tet whose volume is not positive counts +infinity
// (here without the certified sign: the move guard certifies every move).
double WeightedStar::value(const Vec3& x) const {
    double f = 0.0;
    for (const Term& t : terms_) {
        if (t.weight == 0.0) continue;
        const Vec3 xb = t.b - x, xc = t.c - x, xd = t.d - x;
        const double det6 = t.n.dot(xb);
        if (!(det6 > 0.0)) return std::numeric_limits<double>::infinity();
        const double area2 = t.fixed_area2 + xb.cross(xc).norm() + xc.cross(xd).norm() + xd.cross(xb).norm();
        const double edge2 = std::max({t.fixed_edge2, xb.squaredNorm(), xc.squaredNorm(), xd.squaredNorm()});
        f += t.weight * 3.0 * area2 * std::sqrt(edge2) / (kSixRootSix * det6);
    }
    return f;
}

double WeightedStar::value_gradient(const Vec3& x, Vec3& gradient) const {
    double f = 0.0;
    gradient.setZero();
    for (const Term& t : terms_) {
        if (t.weight == 0.0) continue;
        TetPoints p = t.p;
        p[t.corner] = x;
        Vec3 g;
        f += t.weight * element_error_gradient(p, t.corner, g);
        gradient += t.weight * g;
    }
    return f;
}

double WeightedStar::mean_edge_length() const {
    double sum = 0.0;
    int n = 0;
    for (const Term& t : terms_)
        for (int k = 0; k < 4; ++k)
            if (k != t.corner) {
                sum += (t.p[k] - t.p[t.corner]).norm();
                ++n;
            }
    return n ? sum / n : 0.0;
}

void dfp_update(Eigen::Matrix3d& h, const Vec3& s, const Vec3& y) {
    const double sy = s.dot(y);
    const Vec3 hy = h * y;
    const double yhy = y.dot(hy);
    if (!(sy > 0.0) || !(yhy > 0.0)) return;
    h += s * s.transpose() / sy - hy * hy.transpose() / yhy;
}

QuasiNewtonResult minimize_quasi_newton(const WeightedStar& f, const Vec3& x0, const QuasiNewtonSettings& s) {
    QuasiNewtonResult r{x0, 0.0, 0};
    Vec3 g;
    r.f = f.value_gradient(x0, g);
    const double scale = f.mean_edge_length();
    if (!std::isfinite(r.f) || !(scale > 0.0)) return r;
    const double h0 = s.initial_step * scale;
    const double tolerance = s.epsilon * scale;
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    bool fresh = true;  // H is the identity: the next direction is steepest descent
    for (int k = 0; k < s.max_iterations; ++k) {
        Vec3 d = -h * g;  // step (8): the search direction
        if (!(d.dot(g) < 0.0)) d = -g;  // H lost positive definiteness to round-off
        const double length = d.norm();
        if (!(length > 0.0)) break;
        const Vec3 u = d / length;
        const auto phi = [&](double lambda) { return f.value(r.x + lambda * u); };
        const double lambda = golden_section(phi, search_interval(phi, r.f, h0, s.growth), tolerance);  // steps (3)-(4)
        const Vec3 x1 = r.x + lambda * u;  // step (5)
        Vec3 g1;
        const double f1 = f.value_gradient(x1, g1);
        const bool decreased = f1 < r.f;
        // Step (6).  e is not smooth where the longest edge of a tet
        // changes: there the DFP model can point uphill and the search
        // stalls.  A stalled iteration starts over from steepest descent
        // once before the vertex is taken as converged.
        if (!decreased || r.f - f1 < s.epsilon * r.f) {
            if (decreased) {
                r = {x1, f1, k + 1};
                g = g1;
            }
            if (fresh) break;
            h.setIdentity();
            fresh = true;
            continue;
        }
        const Vec3 step = x1 - r.x, dg = g1 - g;
        r = {x1, f1, k + 1};
        g = g1;
        if (fresh && step.dot(dg) > 0.0) h *= step.dot(dg) / dg.squaredNorm();
        dfp_update(h, step, dg);
        fresh = false;
    }
    return r;
}

}  // namespace bodt
