#include "smoothing/angle_ascent.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace bodt {

AngleAscent::AngleAscent(double angle_deg) : bad_cosine_(std::cos(angle_deg * M_PI / 180.0)) {}

size_t AngleAscent::worst_tet(const TetMesh& mesh, int32_t v, const StarTable& star, const ShapeCache& shapes) const {
    const int32_t* tets = mesh.star_begin(v);
    const size_t n = star.size();
    size_t worst = n;
    double most = bad_cosine_;
    for (size_t k = 0; k < n; ++k) {
        const double b = worst_cosine(shapes[static_cast<size_t>(tets[k])].cosines);
        if (b > most) {
            most = b;
            worst = k;
        }
    }
    return worst;
}

namespace {

// The point of least norm in the convex hull of g[0..m) (Wolfe 1976): the
// hull's nearest point to the origin lies in a face of at most three of the
// points (in 3-D), at the origin's projection onto that face's span, with no
// point of the hull beyond it (g[j] . p >= |p|^2 for every j).  The faces
// are few (m <= kMaxActive), so all are tried, smallest first; false when
// none qualifies (the origin is in the hull, within round-off).
bool least_norm_point(const Vec3* g, size_t m, Vec3& p) {
    double scale = 0.0;
    for (size_t i = 0; i < m; ++i) scale = std::max(scale, g[i].squaredNorm());
    const double slack = 1e-12 * scale;
    const auto optimal = [&](const Vec3& q) {
        const double q2 = q.squaredNorm();
        if (!(q2 > slack)) return false;  // at the origin: no ascent
        for (size_t j = 0; j < m; ++j)
            if (g[j].dot(q) < q2 - slack) return false;
        return true;
    };
    for (size_t i = 0; i < m; ++i)
        if (optimal(g[i])) return p = g[i], true;
    for (size_t i = 0; i < m; ++i)
        for (size_t j = i + 1; j < m; ++j) {
            const Vec3 u = g[j] - g[i];
            const double uu = u.squaredNorm();
            if (!(uu > slack)) continue;
            const double t = -g[i].dot(u) / uu;
            if (t <= 0.0 || t >= 1.0) continue;
            const Vec3 q = g[i] + t * u;
            if (optimal(q)) return p = q, true;
        }
    for (size_t i = 0; i < m; ++i)
        for (size_t j = i + 1; j < m; ++j)
            for (size_t k = j + 1; k < m; ++k) {
                const Vec3 u = g[j] - g[i], w = g[k] - g[i];
                const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w);
                const double det = uu * ww - uw * uw;
                if (!(det > 1e-12 * uu * ww)) continue;
                const double bu = -g[i].dot(u), bw = -g[i].dot(w);
                const double s = (bu * ww - bw * uw) / det, t = (uu * bw - uw * bu) / det;
                if (s <= 0.0 || t <= 0.0 || s + t >= 1.0) continue;
                const Vec3 q = g[i] + s * u + t * w;
                if (optimal(q)) return p = q, true;
            }
    return false;
}

// The shortest edge of star tet `worst` at x0 (its corners other than the vertex).
double shortest_edge(const StarTable& star, size_t worst, const Vec3& x0) {
    const size_t n = star.size();
    const double* f = star.opposite();
    double shortest = std::numeric_limits<double>::infinity();
    for (size_t c = 0; c < 3; ++c) {
        const Vec3 y(f[c * n + worst], f[(3 + c) * n + worst], f[(6 + c) * n + worst]);
        shortest = std::min(shortest, (y - x0).norm());
    }
    return shortest;
}

Vec3 projected(const MoveBasis* basis, const Vec3& gradient) {
    if (!basis) return gradient;
    Vec3 along = Vec3::Zero();  // orthonormal columns
    for (Eigen::Index c = 0; c < basis->cols(); ++c) along += basis->col(c).dot(gradient) * basis->col(c);
    return along;
}

// x0 moved against `gradient` by half the shortest edge.
bool move_against(const Vec3& x0, const Vec3& gradient, double shortest, Vec3& target) {
    const double length = gradient.norm();
    if (!(length > 0.0) || !std::isfinite(length)) return false;
    target = x0 - (0.5 * shortest / length) * gradient;
    return true;
}

}  // namespace

bool AngleAscent::target(const TetMesh& mesh, int32_t v, const StarTable& star, size_t worst, const MoveBasis* basis,
                         Vec3& target) const {
    const size_t n = star.size();
    const Vec3 x0 = mesh.points[v];
    const auto worst_cosine_at = [&](const Vec3& x) {
        return worst_cosine(shape_of(star_tet_kernel(star.opposite(), star.at(), n, worst, coords(x))).cosines);
    };
    // Lowering worst_cosine raises the worst angle's sine.  It is the
    // largest of six smooth functions of x: its gradient by central
    // differences, over a step far below the tet's size and far above
    // round-off.
    const double shortest = shortest_edge(star, worst, x0);
    const double h = 1e-4 * shortest;
    Vec3 gradient;
    for (int i = 0; i < 3; ++i) {
        const Vec3 e = h * Vec3::Unit(i);
        gradient[i] = (worst_cosine_at(x0 + e) - worst_cosine_at(x0 - e)) / (2.0 * h);
    }
    return move_against(x0, projected(basis, gradient), shortest, target);
}

bool AngleAscent::steepest_target(const TetMesh& mesh, int32_t v, const StarTable& star, size_t worst,
                                  const MoveBasis* basis, Vec3& target) const {
    const size_t n = star.size();
    const Vec3 x0 = mesh.points[v];
    const auto kernel_at = [&](size_t k, const Vec3& x) {
        return star_tet_kernel(star.opposite(), star.at(), n, k, coords(x));
    };
    const double shortest = shortest_edge(star, worst, x0);
    const double h = 1e-4 * shortest;  // as in target()
    const double worst_cos = worst_cosine(shape_of(kernel_at(worst, x0)).cosines);
    const double active_cos = std::cos(std::min(M_PI / 2.0, std::acos(std::min(1.0, worst_cos)) + kActiveAngle));
    // The gradients of the active |cosines|, tet by tet.
    std::array<Vec3, kMaxActive> gradients;
    size_t m = 0;
    for (size_t k = 0; k < n && m < kMaxActive; ++k) {
        const TetKernel at_x0 = kernel_at(k, x0);
        if (!(at_x0.positive > 0.0)) continue;
        std::array<size_t, 6> active;
        size_t a = 0;
        for (size_t e = 0; e < 6; ++e)
            if (std::abs(at_x0.cos[e]) >= active_cos) active[a++] = e;
        if (a == 0) continue;
        std::array<Vec3, 6> g;
        for (int i = 0; i < 3; ++i) {
            const Vec3 step = h * Vec3::Unit(i);
            const TetKernel up = kernel_at(k, x0 + step), down = kernel_at(k, x0 - step);
            for (size_t j = 0; j < a; ++j) {
                const size_t e = active[j];
                g[j][i] = std::copysign(1.0, at_x0.cos[e]) * (up.cos[e] - down.cos[e]) / (2.0 * h);
            }
        }
        for (size_t j = 0; j < a && m < kMaxActive; ++j) {
            const Vec3 along = projected(basis, g[j]);
            if (along.allFinite()) gradients[m++] = along;
        }
    }
    // One active angle: target() moved up its gradient already.
    Vec3 ascent;
    return m > 1 && least_norm_point(gradients.data(), m, ascent) && move_against(x0, ascent, shortest, target);
}

}  // namespace bodt
