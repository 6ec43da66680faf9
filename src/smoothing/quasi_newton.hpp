// Paper 001 sec. 3: the objective of one free vertex and its minimisation.
//
// WeightedStar is eq. (3.4) restricted to the tets around the vertex, the
// only terms its position changes: f(x) = sum_T w_T e(T), w_T = C for a
// boundary tet and 1 - C for an interior one.
//
// minimize_quasi_newton is Algorithm 1 with the update sign corrected: the
// printed update adds the second DFP term, which must be subtracted.  Its
// line search is Algorithm 3 (bracket) then Algorithm 2 (golden section)
// along the unit search direction.  Two choices make the result independent
// of the objective's scale, so that C = 0.5 moves every vertex exactly as
// the unweighted eq. (3.3) does: the stopping rule is relative
// (|f_{k+1} - f_k| < epsilon f_k), and the first inverse Hessian is scaled
// by s.y / y.y before the first update (Nocedal and Wright eq. 6.20).
#pragma once

#include "quality/tet_geometry.hpp"

#include <Eigen/Core>

#include <vector>

namespace bodt {

class WeightedStar {
public:
    void clear() { terms_.clear(); }
    // A tet of the star: its corners with the free vertex at `corner`.
    void add(const TetPoints& p, int corner, double weight);
    bool empty() const { return terms_.empty(); }

    double value(const Vec3& x) const;
    double value_gradient(const Vec3& x, Vec3& gradient) const;
    // The mean length of the edges at the free vertex (the local scale).
    double mean_edge_length() const;

private:
    // The tet as (x, b, c, d), positively oriented, with what does not
    // depend on x computed once: the line search evaluates f many times.
    struct Term {
        TetPoints p;
        int corner;
        double weight;
        Vec3 b, c, d;
        Vec3 n;              // (c - b) x (d - b): 6V = n . (b - x)
        double fixed_area2;  // |n|, twice the area of the face opposite x
        double fixed_edge2;  // the longest squared edge among b, c, d
    };
    std::vector<Term> terms_;
};

struct QuasiNewtonSettings {
    double epsilon = 1e-3;      // relative accuracy (Algorithms 1 and 2)
    int max_iterations = 10;    // N (Algorithm 1)
    double initial_step = 0.05; // h0 of Algorithm 3, in mean edge lengths
    double growth = 2.0;        // alpha of Algorithm 3
};

// An interval [a, b] of the line parameter that holds a minimum.
struct Bracket {
    double a, b;
};

// Algorithm 3: from lambda = 0 (value phi0) steps h0, h0 alpha, h0 alpha^2,
// ... while phi decreases; if the first step does not, the same the other
// way.  If neither first step decreases phi, the minimum is within
// [-h0, h0] (the printed algorithm would loop forever there).  After 64
// steps that all went down the search gives up and returns the last
// interval, which then need not hold the minimum.
template <class Phi>
Bracket search_interval(const Phi& phi, double phi0, double h0, double growth) {
    constexpr int kMaxSteps = 64;
    double h = h0, previous = 0.0, current = 0.0, f_current = phi0;
    bool reversed = false;
    for (int j = 0; j < kMaxSteps; ++j) {
        const double next = current + h;
        const double f_next = phi(next);
        if (f_next < f_current) {  // step (6): go on, further
            previous = current;
            current = next;
            f_current = f_next;
            h *= growth;
            continue;
        }
        if (current != 0.0) return {std::min(previous, next), std::max(previous, next)};  // step (8)
        if (reversed) return {-h0, h0};
        h = -h;  // step (7): the other way
        reversed = true;
    }
    return {std::min(previous, current), std::max(previous, current)};
}

// Algorithm 2: golden-section search on [a, b] until the two trial points
// are closer than `tolerance`; returns their midpoint.
template <class Phi>
double golden_section(const Phi& phi, Bracket br, double tolerance) {
    constexpr double kLow = 0.3819660112501051;  // (3 - sqrt 5) / 2
    constexpr int kMaxSteps = 200;
    double a = br.a, b = br.b;
    double mu = a + kLow * (b - a), nu = a + (1.0 - kLow) * (b - a);
    double f_mu = phi(mu), f_nu = phi(nu);
    for (int i = 0; i < kMaxSteps && std::abs(nu - mu) >= tolerance; ++i) {
        if (f_mu < f_nu) {  // step (7): the minimum is in [a, nu]
            b = nu;
            nu = mu;
            f_nu = f_mu;
            mu = a + kLow * (b - a);
            f_mu = phi(mu);
        } else {  // the symmetric case: [mu, b]
            a = mu;
            mu = nu;
            f_mu = f_nu;
            nu = a + (1.0 - kLow) * (b - a);
            f_nu = phi(nu);
        }
    }
    return 0.5 * (mu + nu);
}

// The DFP update of the inverse Hessian H for the step s and the gradient
// change y: H + s s^T / (s^T y) - H y y^T H / (y^T H y).  H is left as it
// is when s^T y <= 0 (the curvature condition fails and the update would
// lose positive definiteness).
void dfp_update(Eigen::Matrix3d& h, const Vec3& s, const Vec3& y);

struct QuasiNewtonResult {
    Vec3 x;
    double f;
    int iterations;
};

// Algorithm 1 from x0.  The result is never worse than x0.  An iteration
// that decreases f by less than epsilon f (or not at all) restarts from
// steepest descent (H = I); a stalled steepest-descent iteration ends the
// search, as do N iterations.
QuasiNewtonResult minimize_quasi_newton(const WeightedStar& f, const Vec3& x0, const QuasiNewtonSettings& settings);

}  // namespace bodt
