#include "cli/hausdorff.hpp"

#include "mesh/surface_bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>

namespace bodt_cli {

namespace {

using bodt::SurfaceBvh;
using bodt::Vec3;

double dist(const Vec3& a, const Vec3& b) { return (a - b).norm(); }
Vec3 mid(const Vec3& a, const Vec3& b) { return 0.5 * (a + b); }
Vec3 centroid(const Vec3& a, const Vec3& b, const Vec3& c) { return (a + b + c) / 3.0; }

// The surface's closest-point tree (the core's, which BODT_MODE_NODT
// projects with).
SurfaceBvh make_tree(const TriangleSurface& s) {
    std::vector<Vec3> points(s.xyz.size() / 3);
    for (size_t v = 0; v < points.size(); ++v) points[v] = Vec3(s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]);
    std::vector<std::array<int32_t, 3>> triangles(s.triangles.size() / 3);
    for (size_t t = 0; t < triangles.size(); ++t)
        triangles[t] = {s.triangles[3 * t], s.triangles[3 * t + 1], s.triangles[3 * t + 2]};
    return SurfaceBvh(std::move(points), std::move(triangles));
}

double distance_to(const SurfaceBvh& tree, const Vec3& p, int32_t t) { return dist(p, tree.closest_on(p, t)); }

// Whether triangles t and u share an edge, lie in one plane and make a
// convex quadrilateral: then the distance to their union is convex.
bool convex_flat_pair(const SurfaceBvh& tree, int32_t t, int32_t u) {
    int shared = 0, t_only = -1, u_only = -1;
    for (int k = 0; k < 3; ++k) {
        bool in_u = false, in_t = false;
        for (int j = 0; j < 3; ++j) {
            in_u = in_u || tree.vertex(t, k) == tree.vertex(u, j);
            in_t = in_t || tree.vertex(u, k) == tree.vertex(t, j);
        }
        if (in_u) ++shared;
        else t_only = k;
        if (!in_t) u_only = k;
    }
    if (shared != 2 || t_only < 0 || u_only < 0) return false;
    const Vec3& a = tree.corner(t, (t_only + 1) % 3);
    const Vec3& b = tree.corner(t, (t_only + 2) % 3);
    const Vec3& c = tree.corner(t, t_only);
    const Vec3& d = tree.corner(u, u_only);
    const Vec3 ab = b - a;
    const Vec3 n = ab.cross(c - a);
    const double nn = n.norm(), len = ab.norm();
    if (!(nn > 0.0)) return false;
    // d in t's plane (to round-off), and the diagonals ab and cd cross
    if (std::fabs(n.dot(d - a)) > 1e-12 * nn * len) return false;
    const Vec3 cd = d - c;
    const double s1 = ab.cross(c - a).dot(n), s2 = ab.cross(d - a).dot(n);
    const double s3 = cd.cross(a - c).dot(n), s4 = cd.cross(b - c).dot(n);
    return s1 * s2 < 0.0 && s3 * s4 < 0.0;
}

constexpr int kMaxCandidates = 12;

// A (sub)triangle of one surface, with the distances of its corners to the
// other surface and the other's triangles that bound it.
struct Cell {
    Vec3 p[3];
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
    Search(const TriangleSurface& a, const TriangleSurface& b) : trees_{make_tree(b), make_tree(a)} {}

    double eval(int side, const Vec3& p, int32_t& tri) {
        ++result.evaluations;
        const bodt::ClosestPoint q = trees_[side].closest(p);
        tri = q.triangle;
        const double d = std::sqrt(q.distance2);
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
        const Vec3 g = centroid(c.p[0], c.p[1], c.p[2]);
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
        const SurfaceBvh& tree = trees_[c.side];
        double dc[kMaxCandidates][3];
        for (int k = 0; k < c.ncand; ++k) {
            double m = 0.0;
            for (int j = 0; j < 3; ++j) m = std::max(m, dc[k][j] = distance_to(tree, c.p[j], c.cand[k]));
            ub = std::min(ub, m);
        }
        // Two coplanar candidates making a convex quadrilateral: the
        // distance to it is convex too (a cell across their shared edge).
        for (int k = 0; k < c.ncand && ub > 0.0; ++k)
            for (int l = k + 1; l < c.ncand; ++l) {
                const double m = std::max({std::min(dc[k][0], dc[l][0]), std::min(dc[k][1], dc[l][1]),
                                           std::min(dc[k][2], dc[l][2])});
                if (m < ub && convex_flat_pair(tree, c.cand[k], c.cand[l])) ub = m;
            }
        c.upper = std::max(ub, std::max({c.d[0], c.d[1], c.d[2], dg}));
    }

    HausdorffBounds result;
    SurfaceBvh trees_[2];
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
                c.p[k] = Vec3(s.xyz[3 * v], s.xyz[3 * v + 1], s.xyz[3 * v + 2]);
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
        Vec3 m[3];
        double dm[3];
        int32_t tm[3];
        for (int k = 0; k < 3; ++k) {
            m[k] = mid(c.p[k], c.p[(k + 1) % 3]);  // m[k] on edge k, k+1
            dm[k] = search.eval(c.side, m[k], tm[k]);
        }
        // corners as (point, distance, nearest) triples: 0..2 corners, 3..5 midpoints
        const Vec3 pts[6] = {c.p[0], c.p[1], c.p[2], m[0], m[1], m[2]};
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
