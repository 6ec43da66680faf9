// surface_distance.cpp -- see surface_distance.hpp.
#include "surface_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bench {

namespace {

struct Vec3 {
    double x, y, z;
};
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

inline Vec3 vertex(const Surface& s, int32_t i) {
    return {s.xyz[3 * size_t(i)], s.xyz[3 * size_t(i) + 1], s.xyz[3 * size_t(i) + 2]};
}

// Squared distance from p to triangle abc, exact up to round-off (Ericson,
// Real-Time Collision Detection, 5.1.5: closest point by Voronoi regions).
double point_triangle_dist2(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    Vec3 q;
    if (d1 <= 0 && d2 <= 0) {
        q = a;
    } else {
        const Vec3 bp = p - b;
        const double d3 = dot(ab, bp), d4 = dot(ac, bp);
        const Vec3 cp = p - c;
        const double d5 = dot(ab, cp), d6 = dot(ac, cp);
        const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
        if (d3 >= 0 && d4 <= d3) {
            q = b;
        } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
            q = a + (d1 / (d1 - d3)) * ab;
        } else if (d6 >= 0 && d5 <= d6) {
            q = c;
        } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
            q = a + (d2 / (d2 - d6)) * ac;
        } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
            q = b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
        } else {
            const double den = va + vb + vc;
            if (!(den > 0)) {  // degenerate triangle: nearest of its three edges' ends/sides
                double best = std::numeric_limits<double>::infinity();
                const Vec3 e[3][2] = {{a, b}, {b, c}, {c, a}};
                for (const auto& s : e) {
                    const Vec3 d = s[1] - s[0];
                    const double l2 = dot(d, d);
                    double t = l2 > 0 ? dot(p - s[0], d) / l2 : 0;
                    t = std::min(1.0, std::max(0.0, t));
                    const Vec3 r = p - (s[0] + t * d);
                    best = std::min(best, dot(r, r));
                }
                return best;
            }
            q = a + (vb / den) * ab + (vc / den) * ac;
        }
    }
    const Vec3 r = p - q;
    return dot(r, r);
}

struct Box {
    double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
    double hi[3] = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                    -std::numeric_limits<double>::infinity()};
    void add(Vec3 p) {
        const double v[3] = {p.x, p.y, p.z};
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], v[k]);
            hi[k] = std::max(hi[k], v[k]);
        }
    }
    void add(const Box& b) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.lo[k]);
            hi[k] = std::max(hi[k], b.hi[k]);
        }
    }
    double dist2(Vec3 p) const {
        const double v[3] = {p.x, p.y, p.z};
        double d2 = 0;
        for (int k = 0; k < 3; ++k) {
            const double d = v[k] < lo[k] ? lo[k] - v[k] : (v[k] > hi[k] ? v[k] - hi[k] : 0.0);
            d2 += d * d;
        }
        return d2;
    }
};

// A bounding-volume hierarchy over the triangles of one surface: binary,
// split at the median centroid along the longest axis, leaves of <= 4.
class TriangleBvh {
public:
    explicit TriangleBvh(const Surface& s) : s_(s) {
        const size_t n = s.tris.size();
        order_.resize(n);
        boxes_.resize(n);
        cent_.resize(n);
        for (size_t i = 0; i < n; ++i) {
            order_[i] = int32_t(i);
            const auto& t = s.tris[i];
            const Vec3 a = vertex(s, t[0]), b = vertex(s, t[1]), c = vertex(s, t[2]);
            boxes_[i].add(a);
            boxes_[i].add(b);
            boxes_[i].add(c);
            cent_[i] = (1.0 / 3.0) * (a + b + c);
        }
        if (n > 0) {
            nodes_.reserve(2 * n / kLeaf + 2);
            nodes_.emplace_back();
            build_into(0, 0, int32_t(n));
        }
    }

    // Squared distance from p to the nearest triangle, searching only below
    // the bound best2 (returned unchanged if nothing is nearer).
    double nearest2(Vec3 p, double best2) const {
        if (nodes_.empty()) return best2;
        int32_t stack[128];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& nd = nodes_[size_t(stack[--top])];
            if (nd.box.dist2(p) >= best2) continue;
            if (nd.count > 0) {
                for (int32_t i = nd.first; i < nd.first + nd.count; ++i) {
                    const auto& t = s_.tris[size_t(order_[size_t(i)])];
                    const double d2 =
                        point_triangle_dist2(p, vertex(s_, t[0]), vertex(s_, t[1]), vertex(s_, t[2]));
                    best2 = std::min(best2, d2);
                }
                continue;
            }
            const int32_t l = nd.first, r = nd.first + 1;  // children are adjacent
            const double dl = nodes_[size_t(l)].box.dist2(p), dr = nodes_[size_t(r)].box.dist2(p);
            // push the farther child first so the nearer one is searched first
            if (dl <= dr) {
                if (dr < best2) stack[top++] = r;
                if (dl < best2) stack[top++] = l;
            } else {
                if (dl < best2) stack[top++] = l;
                if (dr < best2) stack[top++] = r;
            }
        }
        return best2;
    }

private:
    static constexpr int32_t kLeaf = 4;
    struct Node {
        Box box;
        int32_t first = 0;  // leaf: first index in order_; inner: index of the left child
        int32_t count = 0;  // > 0 for a leaf
    };

    // Build the subtree of [begin, end) into the already reserved slot.
    void build_into(int32_t slot, int32_t begin, int32_t end) {
        Box box, cbox;
        for (int32_t i = begin; i < end; ++i) {
            box.add(boxes_[size_t(order_[size_t(i)])]);
            cbox.add(cent_[size_t(order_[size_t(i)])]);
        }
        nodes_[size_t(slot)].box = box;
        if (end - begin <= kLeaf) {
            nodes_[size_t(slot)].first = begin;
            nodes_[size_t(slot)].count = end - begin;
            return;
        }
        int axis = 0;
        for (int k = 1; k < 3; ++k)
            if (cbox.hi[k] - cbox.lo[k] > cbox.hi[axis] - cbox.lo[axis]) axis = k;
        const int32_t mid = begin + (end - begin) / 2;
        auto key = [&](int32_t t) {
            const Vec3& c = cent_[size_t(t)];
            return axis == 0 ? c.x : (axis == 1 ? c.y : c.z);
        };
        std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                         [&](int32_t a, int32_t b) { return key(a) < key(b); });
        const int32_t left = int32_t(nodes_.size());
        nodes_.emplace_back();
        nodes_.emplace_back();
        nodes_[size_t(slot)].first = left;
        nodes_[size_t(slot)].count = 0;
        build_into(left, begin, mid);
        build_into(left + 1, mid, end);
    }

    const Surface& s_;
    std::vector<int32_t> order_;
    std::vector<Box> boxes_;
    std::vector<Vec3> cent_;
    std::vector<Node> nodes_;
};

}  // namespace

std::vector<std::array<int32_t, 3>> boundary_triangles(const std::vector<int32_t>& tets, int index_base) {
    static const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    const size_t ntets = tets.size() / 4;
    struct Key {
        std::array<int32_t, 3> sorted;
        std::array<int32_t, 3> face;
    };
    std::vector<Key> keys;
    keys.reserve(4 * ntets);
    for (size_t t = 0; t < ntets; ++t) {
        for (const auto& f : kFace) {
            std::array<int32_t, 3> face = {tets[4 * t + size_t(f[0])] - index_base,
                                           tets[4 * t + size_t(f[1])] - index_base,
                                           tets[4 * t + size_t(f[2])] - index_base};
            std::array<int32_t, 3> s = face;
            std::sort(s.begin(), s.end());
            keys.push_back({s, face});
        }
    }
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) { return a.sorted < b.sorted; });
    std::vector<std::array<int32_t, 3>> out;
    for (size_t i = 0; i < keys.size();) {
        size_t j = i + 1;
        while (j < keys.size() && keys[j].sorted == keys[i].sorted) ++j;
        if (j - i == 1) out.push_back(keys[i].face);
        i = j;
    }
    return out;
}

double one_sided_distance(const Surface& a, const Surface& b) {
    if (a.tris.empty()) return 0.0;
    if (b.tris.empty()) return std::numeric_limits<double>::infinity();
    const TriangleBvh bvh(b);
    double worst2 = 0.0;
    auto query = [&](Vec3 p) {
        const double d2 = bvh.nearest2(p, std::numeric_limits<double>::infinity());
        worst2 = std::max(worst2, d2);
    };
    // vertices used by A's triangles, each once
    std::vector<char> used(a.xyz.size() / 3, 0);
    for (const auto& t : a.tris)
        for (int32_t v : t) used[size_t(v)] = 1;
    for (size_t v = 0; v < used.size(); ++v)
        if (used[v]) query(vertex(a, int32_t(v)));
    // edge midpoints, each edge once
    std::vector<std::pair<int32_t, int32_t>> edges;
    edges.reserve(3 * a.tris.size());
    for (const auto& t : a.tris)
        for (int k = 0; k < 3; ++k) {
            int32_t u = t[size_t(k)], w = t[size_t((k + 1) % 3)];
            edges.emplace_back(std::min(u, w), std::max(u, w));
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& e : edges) query(0.5 * (vertex(a, e.first) + vertex(a, e.second)));
    // centroids
    for (const auto& t : a.tris)
        query((1.0 / 3.0) * (vertex(a, t[0]) + vertex(a, t[1]) + vertex(a, t[2])));
    return std::sqrt(worst2);
}

double hausdorff_distance(const Surface& a, const Surface& b) {
    if (a.tris.size() == b.tris.size()) {
        auto sorted = [](std::vector<std::array<int32_t, 3>> t) {
            for (auto& f : t) std::sort(f.begin(), f.end());
            std::sort(t.begin(), t.end());
            return t;
        };
        const auto ta = sorted(a.tris), tb = sorted(b.tris);
        if (ta == tb) {
            bool same = true;
            for (const auto& f : ta)
                for (int32_t v : f)
                    for (int k = 0; k < 3 && same; ++k)
                        if (a.xyz[3 * size_t(v) + size_t(k)] != b.xyz[3 * size_t(v) + size_t(k)]) same = false;
            if (same) return 0.0;
        }
    }
    return std::max(one_sided_distance(a, b), one_sided_distance(b, a));
}

double bbox_largest_side(const Surface& s) {
    Box box;
    for (size_t v = 0; 3 * v + 2 < s.xyz.size(); ++v) box.add(vertex(s, int32_t(v)));
    if (s.xyz.empty()) return 0.0;
    return std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
}

}  // namespace bench
