#include "mesh/surface_bvh.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace bodt {

namespace {

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double len2 = d.squaredNorm();
    if (!(len2 > 0.0)) return a;
    return a + std::clamp(d.dot(p - a) / len2, 0.0, 1.0) * d;
}

}  // namespace

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a;
    const Vec3 n = ab.cross(ac);
    // Degenerate, or so thin (sine of the angle at a below 1e-8) that its
    // plane is lost to round-off: the nearest of its edges, at most half its
    // height away.
    if (!(n.squaredNorm() > 1e-16 * ab.squaredNorm() * ac.squaredNorm())) {
        const Vec3 q[3] = {closest_point_on_segment(p, a, b), closest_point_on_segment(p, b, c),
                           closest_point_on_segment(p, c, a)};
        int best = 0;
        for (int k = 1; k < 3; ++k)
            if ((p - q[k]).squaredNorm() < (p - q[best]).squaredNorm()) best = k;
        return q[best];
    }
    // The Voronoi regions of the corners, then of the edges, then the face.
    const Vec3 ap = p - a, bp = p - b, cp = p - c;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    // The foot on the plane: better conditioned than Ericson's barycentric
    // coordinates vb, vc over va + vb + vc for thin triangles.
    return p - (n.dot(ap) / n.squaredNorm()) * n;
}

SurfaceBvh::SurfaceBvh(std::vector<Vec3> points, std::vector<std::array<int32_t, 3>> triangles)
    : points_(std::move(points)), triangles_(std::move(triangles)) {
    const int32_t n = num_triangles();
    order_.resize(static_cast<size_t>(n));
    std::iota(order_.begin(), order_.end(), 0);
    std::vector<Vec3> centroids(static_cast<size_t>(n));
    for (int32_t t = 0; t < n; ++t) centroids[t] = (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
    if (n > 0) build(0, n, centroids);
}

int32_t SurfaceBvh::build(int32_t first, int32_t last, const std::vector<Vec3>& centroids) {
    const int32_t index = static_cast<int32_t>(nodes_.size());
    nodes_.emplace_back();
    Node node;
    const double inf = std::numeric_limits<double>::infinity();
    node.lo = Vec3::Constant(inf);
    node.hi = Vec3::Constant(-inf);
    Vec3 clo = node.lo, chi = node.hi;
    for (int32_t k = first; k < last; ++k) {
        const int32_t t = order_[k];
        for (int c = 0; c < 3; ++c) {
            node.lo = node.lo.cwiseMin(corner(t, c));
            node.hi = node.hi.cwiseMax(corner(t, c));
        }
        clo = clo.cwiseMin(centroids[t]);
        chi = chi.cwiseMax(centroids[t]);
    }
    if (last - first <= 4) {
        node.first = first;
        node.count = last - first;
    } else {
        Eigen::Index axis;
        (chi - clo).maxCoeff(&axis);
        const int32_t middle = first + (last - first) / 2;
        std::nth_element(order_.begin() + first, order_.begin() + middle, order_.begin() + last,
                         [&](int32_t x, int32_t y) { return centroids[x][axis] < centroids[y][axis]; });
        node.left = build(first, middle, centroids);
        node.right = build(middle, last, centroids);
    }
    nodes_[index] = node;
    return index;
}

double SurfaceBvh::box_distance2(const Node& n, const Vec3& p) {
    return (n.lo - p).cwiseMax(p - n.hi).cwiseMax(0.0).squaredNorm();
}

Vec3 SurfaceBvh::closest_on(const Vec3& p, int32_t t) const {
    return closest_point_on_triangle(p, corner(t, 0), corner(t, 1), corner(t, 2));
}

ClosestPoint SurfaceBvh::closest(const Vec3& p) const {
    ClosestPoint best;
    best.distance2 = std::numeric_limits<double>::infinity();
    if (nodes_.empty()) return best;
    int32_t stack[128];  // the tree is balanced: depth about log2(n / 4)
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (box_distance2(node, p) >= best.distance2) continue;
        if (node.count > 0) {
            for (int32_t k = node.first; k < node.first + node.count; ++k) {
                const Vec3 q = closest_on(p, order_[k]);
                const double d2 = (p - q).squaredNorm();
                if (d2 < best.distance2) best = {q, d2, order_[k]};
            }
            continue;
        }
        // The nearer child last, so it is searched first.
        const bool left_nearer = box_distance2(nodes_[node.left], p) < box_distance2(nodes_[node.right], p);
        stack[top++] = left_nearer ? node.right : node.left;
        stack[top++] = left_nearer ? node.left : node.right;
    }
    return best;
}

}  // namespace bodt
