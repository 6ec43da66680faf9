#include "cli/hausdorff.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>

namespace bodt_cli {

namespace {

using V3 = std::array<double, 3>;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V3 add_scaled(const V3& a, const V3& d, double s) { return {a[0] + s * d[0], a[1] + s * d[1], a[2] + s * d[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double dist(const V3& a, const V3& b) { return std::sqrt(dot(sub(a, b), sub(a, b))); }
V3 mid(const V3& a, const V3& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}; }
V3 centroid(const V3& a, const V3& b, const V3& c) {
    return {(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0, (a[2] + b[2] + c[2]) / 3.0};
}

// Squared distance from p to the triangle abc (Ericson 5.1.5, the closest
// point by Voronoi regions of the corners, edges and face).
double point_triangle_dist2(const V3& p, const V3& a, const V3& b, const V3& c) {
    const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    V3 q;
    if (d1 <= 0.0 && d2 <= 0.0) {
        q = a;
    } else {
        const V3 bp = sub(p, b);
        const double d3 = dot(ab, bp), d4 = dot(ac, bp);
        const V3 cp = sub(p, c);
        const double d5 = dot(ab, cp), d6 = dot(ac, cp);
        const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        if (d3 >= 0.0 && d4 <= d3) q = b;
        else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) q = add_scaled(a, ab, d1 / (d1 - d3));
        else if (d6 >= 0.0 && d5 <= d6) q = c;
        else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) q = add_scaled(a, ac, d2 / (d2 - d6));
        else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
            q = add_scaled(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
        else {
            const double sum = va + vb + vc;
            if (!(std::fabs(sum) > 0.0)) {  // degenerate triangle: its edges
                const double e = std::min({point_triangle_dist2(p, a, a, b), point_triangle_dist2(p, b, b, c),
                                           point_triangle_dist2(p, c, c, a)});
                return e;
            }
            q = add_scaled(add_scaled(a, ab, vb / sum), ac, vc / sum);
        }
    }
    const V3 d = sub(p, q);
    return dot(d, d);
}

// Nearest triangle of a surface: a bounding-box tree, median split on the
// longest axis of the centroids, up to 4 triangles per leaf.
class TriangleTree {
public:
    explicit TriangleTree(const TriangleSurface& s) : s_(s) {
        const size_t n = s.triangles.size() / 3;
        order_.resize(n);
        std::iota(order_.begin(), order_.end(), 0);
        cent_.resize(n);
        for (size_t t = 0; t < n; ++t) cent_[t] = centroid(corner(t, 0), corner(t, 1), corner(t, 2));
        if (n > 0) build(0, n);
    }

    V3 corner(size_t t, int k) const {
        const size_t v = static_cast<size_t>(s_.triangles[3 * t + k]);
        return {s_.xyz[3 * v], s_.xyz[3 * v + 1], s_.xyz[3 * v + 2]};
    }

    int32_t vertex(int32_t t, int k) const { return s_.triangles[3 * static_cast<size_t>(t) + k]; }

    // Whether triangles t and u share an edge, lie in one plane and make a
    // convex quadrilateral: then the distance to their union is convex.
    bool convex_flat_pair(int32_t t, int32_t u) const {
        int shared = 0, t_only = -1, u_only = -1;
        for (int k = 0; k < 3; ++k) {
            bool in_u = false, in_t = false;
            for (int j = 0; j < 3; ++j) {
                in_u = in_u || vertex(t, k) == vertex(u, j);
                in_t = in_t || vertex(u, k) == vertex(t, j);
            }
            if (in_u) ++shared;
            else t_only = k;
            if (!in_t) u_only = k;
        }
        if (shared != 2 || t_only < 0 || u_only < 0) return false;
        const V3 a = corner(static_cast<size_t>(t), (t_only + 1) % 3), b = corner(static_cast<size_t>(t), (t_only + 2) % 3);
        const V3 c = corner(static_cast<size_t>(t), t_only), d = corner(static_cast<size_t>(u), u_only);
        const V3 ab = sub(b, a);
        const V3 n = cross(ab, sub(c, a));
        const double nn = std::sqrt(dot(n, n)), len = std::sqrt(dot(ab, ab));
        if (!(nn > 0.0)) return false;
        // d in t's plane (to round-off), and the diagonals ab and cd cross
        if (std::fabs(dot(n, sub(d, a))) > 1e-12 * nn * len) return false;
        const V3 cd = sub(d, c);
        const double s1 = dot(cross(ab, sub(c, a)), n), s2 = dot(cross(ab, sub(d, a)), n);
        const double s3 = dot(cross(cd, sub(a, c)), n), s4 = dot(cross(cd, sub(b, c)), n);
        return s1 * s2 < 0.0 && s3 * s4 < 0.0;
    }

    double distance_to(const V3& p, int32_t t) const {
        const size_t u = static_cast<size_t>(t);
        return std::sqrt(point_triangle_dist2(p, corner(u, 0), corner(u, 1), corner(u, 2)));
    }

    // Distance from p to the surface; `tri` receives the nearest triangle.
    double nearest(const V3& p, int32_t& tri) const {
        double best = std::numeric_limits<double>::infinity();
        tri = -1;
        if (nodes_.empty()) return best;
        size_t stack[128];
        size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (box_dist2(node, p) >= best) continue;
            if (node.count > 0) {
                for (size_t k = node.first; k < node.first + node.count; ++k) {
                    const size_t t = order_[k];
                    const double d2 = point_triangle_dist2(p, corner(t, 0), corner(t, 1), corner(t, 2));
                    if (d2 < best) {
                        best = d2;
                        tri = static_cast<int32_t>(t);
                    }
                }
                continue;
            }
            // Nearer child last, so it is searched first.
            const double dl = box_dist2(nodes_[node.left], p), dr = box_dist2(nodes_[node.right], p);
            if (dl < dr) {
                stack[top++] = node.right;
                stack[top++] = node.left;
            } else {
                stack[top++] = node.left;
                stack[top++] = node.right;
            }
        }
        return std::sqrt(best);
    }

private:
    struct Node {
        V3 lo, hi;
        size_t left = 0, right = 0;  // children, for inner nodes
        size_t first = 0, count = 0; // range of order_, for leaves (count > 0)
    };

    static double box_dist2(const Node& n, const V3& p) {
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double e = p[k] < n.lo[k] ? n.lo[k] - p[k] : p[k] > n.hi[k] ? p[k] - n.hi[k] : 0.0;
            d2 += e * e;
        }
        return d2;
    }

    size_t build(size_t first, size_t last) {
        const size_t index = nodes_.size();
        nodes_.emplace_back();
        Node node;
        node.lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::infinity()};
        node.hi = {-node.lo[0], -node.lo[1], -node.lo[2]};
        V3 clo = node.lo, chi = node.hi;
        for (size_t k = first; k < last; ++k) {
            for (int c = 0; c < 3; ++c) {
                const V3 p = corner(order_[k], c);
                for (int j = 0; j < 3; ++j) {
                    node.lo[j] = std::min(node.lo[j], p[j]);
                    node.hi[j] = std::max(node.hi[j], p[j]);
                }
            }
            for (int j = 0; j < 3; ++j) {
                clo[j] = std::min(clo[j], cent_[order_[k]][j]);
                chi[j] = std::max(chi[j], cent_[order_[k]][j]);
            }
        }
        if (last - first <= 4) {
            node.first = first;
            node.count = last - first;
        } else {
            int axis = 0;
            for (int j = 1; j < 3; ++j)
                if (chi[j] - clo[j] > chi[axis] - clo[axis]) axis = j;
            const size_t middle = first + (last - first) / 2;
            std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(first),
                             order_.begin() + static_cast<std::ptrdiff_t>(middle),
                             order_.begin() + static_cast<std::ptrdiff_t>(last),
                             [&](size_t x, size_t y) { return cent_[x][axis] < cent_[y][axis]; });
            node.left = build(first, middle);
            node.right = build(middle, last);
        }
        nodes_[index] = node;
        return index;
    }

    const TriangleSurface& s_;
    std::vector<size_t> order_;
    std::vector<V3> cent_;
    std::vector<Node> nodes_;
};

constexpr int kMaxCandidates = 12;

// A (sub)triangle of one surface, with the distances of its corners to the
// other surface and the other's triangles that bound it.
struct Cell {
    V3 p[3];
    double d[3];
    int32_t near[3];  // the other surface's triangle nearest to each corner
    std::array<int32_t, kMaxCandidates> cand;
    int ncand = 0;
    int side = 0;     // 0: a cell of A measured against B; 1: the reverse
    double upper = 0.0;
    bool operator<(const Cell& o) const { return upper < o.upper; }
};

class Search {
public:
    Search(const TriangleSurface& a, const TriangleSurface& b) : trees_{TriangleTree(b), TriangleTree(a)} {}

    double eval(int side, const V3& p, int32_t& tri) {
        ++result.evaluations;
        const double d = trees_[side].nearest(p, tri);
        result.lower = std::max(result.lower, d);
        return d;
    }

    static void add_candidate(Cell& c, int32_t t) {
        if (t < 0) return;
        for (int k = 0; k < c.ncand; ++k)
            if (c.cand[k] == t) return;
        if (c.ncand < kMaxCandidates) c.cand[c.ncand++] = t;
    }

    // Fills the cell's upper bound (evaluating its centroid).
    void bound(Cell& c) {
        const V3 g = centroid(c.p[0], c.p[1], c.p[2]);
        int32_t tg;
        const double dg = eval(c.side, g, tg);
        // The candidates: the triangles nearest to its centroid and corners
        // first, then those inherited.
        Cell fresh = c;
        fresh.ncand = 0;
        add_candidate(fresh, tg);
        for (int k = 0; k < 3; ++k) add_candidate(fresh, c.near[k]);
        for (int k = 0; k < c.ncand; ++k) add_candidate(fresh, c.cand[k]);
        c.cand = fresh.cand;
        c.ncand = fresh.ncand;
        double ub = dg + std::max({dist(g, c.p[0]), dist(g, c.p[1]), dist(g, c.p[2])});
        for (int k = 0; k < 3; ++k)
            ub = std::min(ub, c.d[k] + std::max(dist(c.p[k], c.p[(k + 1) % 3]), dist(c.p[k], c.p[(k + 2) % 3])));
        const TriangleTree& tree = trees_[c.side];
        double dc[kMaxCandidates][3];
        for (int k = 0; k < c.ncand; ++k) {
            double m = 0.0;
            for (int j = 0; j < 3; ++j) m = std::max(m, dc[k][j] = tree.distance_to(c.p[j], c.cand[k]));
            ub = std::min(ub, m);
        }
        // Two coplanar candidates making a convex quadrilateral: the
        // distance to it is convex too (a cell across their shared edge).
        for (int k = 0; k < c.ncand && ub > 0.0; ++k)
            for (int l = k + 1; l < c.ncand; ++l) {
                const double m = std::max({std::min(dc[k][0], dc[l][0]), std::min(dc[k][1], dc[l][1]),
                                           std::min(dc[k][2], dc[l][2])});
                if (m < ub && tree.convex_flat_pair(c.cand[k], c.cand[l])) ub = m;
            }
        c.upper = std::max(ub, std::max({c.d[0], c.d[1], c.d[2], dg}));
    }

    HausdorffBounds result;
    TriangleTree trees_[2];
};

}  // namespace

HausdorffBounds hausdorff_distance(const TriangleSurface& a, const TriangleSurface& b, double abs_tolerance,
                                   double rel_tolerance, int64_t max_evaluations) {
    if (a.triangles.empty() || b.triangles.empty()) {
        HausdorffBounds none;
        none.lower = none.upper = a.triangles.empty() && b.triangles.empty() ? 0.0
                                                                              : std::numeric_limits<double>::infinity();
        return none;
    }
    Search search(a, b);
    const TriangleSurface* surf[2] = {&a, &b};
    std::priority_queue<Cell> queue;
    for (int side = 0; side < 2; ++side) {
        const TriangleSurface& s = *surf[side];
        const size_t nv = s.xyz.size() / 3;
        std::vector<double> dv(nv, -1.0);
        std::vector<int32_t> tv(nv, -1);
        for (size_t t = 0; 3 * t < s.triangles.size(); ++t) {
            Cell c;
            c.side = side;
            for (int k = 0; k < 3; ++k) {
                const size_t v = static_cast<size_t>(s.triangles[3 * t + k]);
                c.p[k] = {s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]};
                if (dv[v] < 0.0) dv[v] = search.eval(side, c.p[k], tv[v]);
                c.d[k] = dv[v];
                c.near[k] = tv[v];
            }
            search.bound(c);
            queue.push(c);
        }
    }
    // Best first: split the cell with the largest upper bound until every
    // bound is within the tolerance of the lower bound.
    double upper = search.result.lower;
    while (!queue.empty()) {
        const Cell c = queue.top();
        const double lower = search.result.lower;
        if (c.upper <= lower + abs_tolerance + rel_tolerance * lower) {
            upper = std::max(upper, c.upper);
            break;
        }
        if (search.result.evaluations >= max_evaluations) {
            upper = std::max(upper, c.upper);
            break;
        }
        queue.pop();
        V3 m[3];
        double dm[3];
        int32_t tm[3];
        for (int k = 0; k < 3; ++k) {
            m[k] = mid(c.p[k], c.p[(k + 1) % 3]);  // m[k] on edge k, k+1
            dm[k] = search.eval(c.side, m[k], tm[k]);
        }
        // corners as (point, distance, nearest) triples: 0..2 corners, 3..5 midpoints
        const V3 pts[6] = {c.p[0], c.p[1], c.p[2], m[0], m[1], m[2]};
        const double ds[6] = {c.d[0], c.d[1], c.d[2], dm[0], dm[1], dm[2]};
        const int32_t ts[6] = {c.near[0], c.near[1], c.near[2], tm[0], tm[1], tm[2]};
        static const int kChildren[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
        for (const auto& ch : kChildren) {
            Cell child;
            child.side = c.side;
            for (int k = 0; k < 3; ++k) {
                child.p[k] = pts[ch[k]];
                child.d[k] = ds[ch[k]];
                child.near[k] = ts[ch[k]];
            }
            child.cand = c.cand;
            child.ncand = c.ncand;
            search.bound(child);
            queue.push(child);
        }
    }
    if (queue.empty()) upper = search.result.lower;
    HausdorffBounds r = search.result;
    r.upper = std::max(upper, r.lower);
    return r;
}

}  // namespace bodt_cli
