// Half-edge and edge collapse (paper 002 sec. 3.5.1).
#include "features/flat_pieces.hpp"
#include "topology/op_support.hpp"
#include "topology/operations.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

namespace bodt {

namespace {

// The faces at a vertex, and which of them are on the surface (a
// boundary, an interface or a marked face), read off its star alone: each
// face at v lies in one or two of v's tets.  A collapse asks about the
// faces at its two ends many times; a walk per question
// (EditableMesh::is_surface_face) made it quadratic in the star.
class FacesAt {
public:
    FacesAt(const EditableMesh& mesh, int32_t v) {
        std::vector<std::pair<FaceKey, int32_t>> seen;  // face, its tet's region
        for (int32_t t : mesh.tets_of(v)) {
            const Tet& q = mesh.tet(t);
            for (int i = 0; i < 4; ++i)
                if (q[i] != v)
                    seen.push_back({FaceKey::of(q[kFaceVertex[i][0]], q[kFaceVertex[i][1]], q[kFaceVertex[i][2]]), mesh.region(t)});
        }
        std::sort(seen.begin(), seen.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        for (size_t i = 0; i < seen.size();) {
            size_t j = i + 1;
            while (j < seen.size() && seen[j].first == seen[i].first) ++j;
            const FaceKey& f = seen[i].first;
            all_.push_back(f);
            if (j - i == 1 || (j - i == 2 && seen[i].second != seen[i + 1].second) || mesh.has_marker(f))
                surface_.push_back(f);
            i = j;
        }
    }
    bool has(const FaceKey& f) const { return std::binary_search(all_.begin(), all_.end(), f); }
    bool on_surface(const FaceKey& f) const { return std::binary_search(surface_.begin(), surface_.end(), f); }
    // The edge from the vertex to x is on the surface.
    bool surface_edge_to(int32_t x) const {
        return std::any_of(surface_.begin(), surface_.end(), [x](const FaceKey& f) { return holds3(f, x); });
    }
    // The mean length of the surface edges at v (0 without any).
    double mean_surface_edge(const EditableMesh& mesh, int32_t v) const {
        std::vector<int32_t> ends;
        for (const FaceKey& f : surface_)
            for (int32_t x : f.v)
                if (x != v) ends.push_back(x);
        std::sort(ends.begin(), ends.end());
        ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
        double sum = 0.0;
        for (int32_t x : ends) sum += (mesh.point(x) - mesh.point(v)).norm();
        return ends.empty() ? 0.0 : sum / static_cast<double>(ends.size());
    }
    // The slope a collapse of v may take its surface by (TopologyRules::
    // surface_slope): none where v's surface faces are faceted
    // (TopologyRules::crease_cosine), where any would take the surface off
    // its shape.
    double slope(const EditableMesh& mesh, int32_t v, const TopologyRules& rules) const {
        if (!(rules.surface_slope > 0.0 && rules.crease_cosine >= 0.0)) return rules.surface_slope;
        FlatPieces pieces(mesh.point(v));
        for (const FaceKey& f : surface_) {
            const int k = f.v[0] == v ? 0 : (f.v[1] == v ? 1 : 2);
            pieces.add(mesh.point(f.v[(k + 1) % 3]), mesh.point(f.v[(k + 2) % 3]));
        }
        return pieces.faceted(rules.crease_cosine) ? 0.0 : rules.surface_slope;
    }

private:
    static bool holds3(const FaceKey& f, int32_t x) { return f.v[0] == x || f.v[1] == x || f.v[2] == x; }
    std::vector<FaceKey> all_, surface_;
};

// The link condition (Dey et al.), with the outside of the domain as one
// more vertex: the vertices and edges that v and w both see are exactly
// those around the edge (v, w), so the collapse glues nothing together.
// `nv`: v's neighbours (EditableMesh::neighbors).
bool link_condition(const EditableMesh& mesh, int32_t v, int32_t w, const FacesAt& at_v, const FacesAt& at_w,
                    const std::vector<int32_t>& nv) {
    std::vector<int32_t> nw, common;
    mesh.neighbors(w, nw);
    std::set_intersection(nv.begin(), nv.end(), nw.begin(), nw.end(), std::back_inserter(common));
    for (int32_t x : common) {
        if (!at_v.has(FaceKey::of(v, w, x))) return false;
        // Both (v, x) and (w, x) on the surface: (v, w, x) must be a surface face.
        if (at_v.surface_edge_to(x) && at_w.surface_edge_to(x) && !at_v.on_surface(FaceKey::of(v, w, x))) return false;
    }
    for (size_t i = 0; i < common.size(); ++i)
        for (size_t j = i + 1; j < common.size(); ++j) {
            const int32_t x = common[i], y = common[j];
            const FaceKey fv = FaceKey::of(v, x, y), fw = FaceKey::of(w, x, y);
            if (at_v.has(fv) && at_w.has(fw) && !mesh.has_tet({v, w, x, y})) return false;
            // The triangle (x, y, outside) in both links: the two surface
            // faces would be glued into one inner face with no tet on either
            // side (a lone tet collapsed to nothing).  Where the surface
            // keeps its planes, w never lies in the plane of (v, x, y), and
            // the position rules refuse this already.
            if (at_v.on_surface(fv) && at_w.on_surface(fw)) return false;
        }
    return true;
}

// x lies in the plane through p with normal n, to round-off of `length`
// (in_plane), or within `tolerance` of it.
bool near_plane(const Vec3& n, const Vec3& p, const Vec3& x, double length, double tolerance) {
    return in_plane(n, p, x, length) || std::abs(n.dot(x - p)) <= tolerance * n.norm();
}

// A surface face's normal before and after a collapse: it keeps its side,
// and within rules.surface_slope turns by at most asin(surface_slope).
bool turns_little(const Vec3& before, const Vec3& after, const TopologyRules& rules) {
    return after.dot(before) > least_turn_cosine(rules) * after.norm() * before.norm();
}

// Where v may go along its feature edges: to w, over a feature edge, with
// the line straight at v (or v off the chord of its two line neighbours by
// at most `slope` times their mean distance) so that it keeps its shape.
// On a curved feature line (rules.on_curved_shape) v may go to w when w
// lies on the line's fitted shape.
// `around`: v's neighbours.
bool feature_lines_allow(const EditableMesh& mesh, int32_t v, int32_t w, double length, const TopologyRules& rules,
                         double slope, const std::vector<int32_t>& around) {
    std::vector<int32_t> along;
    for (int32_t x : around)
        if (mesh.is_feature_edge(v, x)) along.push_back(x);
    if (along.empty()) return mesh.vertex_class(v) != VertexClass::FeatureLine;
    if (along.size() != 2 || !mesh.is_feature_edge(v, w)) return false;
    if (rules.on_curved_shape && rules.on_curved_shape(mesh, {v, w}, mesh.point(w))) return true;
    const int32_t u = along[0] == w ? along[1] : along[0];
    const Vec3 d = mesh.point(w) - mesh.point(u);
    const Vec3 off = (mesh.point(v) - mesh.point(u)).cross(d);
    const double tolerance = slope * std::sqrt(length * 0.5 * ((mesh.point(v) - mesh.point(u)).norm() + length));
    return off.norm() <= std::max(1e-9 * length, tolerance) * d.norm() && (mesh.point(v) - mesh.point(u)).dot(d) > 0.0;
}

// collapse_half_edge, with w's faces known (at_w) or not (null): the
// midpoint collapse has them.
bool collapse_half_edge_with(EditableMesh& mesh, int32_t v, int32_t w, const TopologyRules& rules, double must_exceed,
                             const FacesAt* at_w) {
    const VertexClass cv = mesh.vertex_class(v);
    if (v == w || cv == VertexClass::Corner || cv == VertexClass::Fixed || cv == VertexClass::Unused) return false;
    std::vector<int32_t> star(mesh.tets_of(v));
    if (std::none_of(star.begin(), star.end(), [&](int32_t t) { return holds(mesh.tet(t), w); })) return false;
    const bool v_on_surface = cv != VertexClass::Interior;
    const FacesAt at_v(mesh, v);
    if (v_on_surface && (!rules.surface_may_change || !at_v.surface_edge_to(w))) return false;
    const double length = (mesh.point(w) - mesh.point(v)).norm();
    std::vector<int32_t> around;
    mesh.neighbors(v, around);
    const double slope = v_on_surface ? at_v.slope(mesh, v, rules) : 0.0;
    if (!feature_lines_allow(mesh, v, w, length, rules, slope, around)) return false;
    std::optional<FacesAt> own_at_w;
    if (!link_condition(mesh, v, w, at_v, at_w ? *at_w : own_at_w.emplace(mesh, w), around)) return false;
    const double off_surface = slope * std::sqrt(length * at_v.mean_surface_edge(mesh, v));

    // The surface faces at v: w must lie in each one's plane (or within
    // off_surface of it), the renamed face must keep its side (and turn
    // little), and the faces on each side of a non-feature
    // edge at v must carry one marker (so markers change only across
    // feature edges, whose lines stay where they are).
    struct Renamed {
        FaceKey from, to;
        bool marked;
        int32_t marker;
    };
    std::vector<Renamed> renamed;
    std::vector<std::pair<FaceKey, bool>> dropped;  // faces on (v, w)
    if (v_on_surface) {
        std::unordered_map<int32_t, int32_t> marker_at;  // non-feature edge (v, x) -> marker of its faces
        const auto one_marker = [&](int32_t x, int32_t marker) {
            if (mesh.is_feature_edge(v, x)) return true;
            const auto [it, fresh] = marker_at.emplace(x, marker);
            return fresh || it->second == marker;
        };
        for (int32_t t : star) {
            const Tet& q = mesh.tet(t);
            for (int i = 0; i < 4; ++i) {
                if (q[i] == v) continue;
                const int32_t a = q[kFaceVertex[i][0]], b = q[kFaceVertex[i][1]], c = q[kFaceVertex[i][2]];
                const FaceKey f = FaceKey::of(a, b, c);
                if (!at_v.on_surface(f)) continue;
                const int32_t marker = mesh.marker(f);
                const int32_t x = a == v ? b : a, y = c == v ? b : c;  // v's two neighbours on f
                if (!one_marker(x, marker) || !one_marker(y, marker)) return false;
                if (a == w || b == w || c == w) {
                    dropped.push_back({f, mesh.has_marker(f)});
                    continue;
                }
                const Vec3 n = triangle_normal(mesh.point(a), mesh.point(b), mesh.point(c));
                const bool on_shape = rules.on_curved_shape && rules.on_curved_shape(mesh, {a, b, c}, mesh.point(w));
                if (!on_shape && !near_plane(n, mesh.point(v), mesh.point(w), length, off_surface)) return false;
                const Vec3 pa = a == v ? mesh.point(w) : mesh.point(a), pb = b == v ? mesh.point(w) : mesh.point(b),
                           pc = c == v ? mesh.point(w) : mesh.point(c);
                if (!turns_little(n, triangle_normal(pa, pb, pc), rules)) return false;
                renamed.push_back({f, FaceKey::of(a == v ? w : a, b == v ? w : b, c == v ? w : c), mesh.has_marker(f), marker});
            }
        }
        // A surface face seen from two tets (an interface) is listed twice.
        std::sort(renamed.begin(), renamed.end(), [](const Renamed& x, const Renamed& y) { return x.from < y.from; });
        renamed.erase(std::unique(renamed.begin(), renamed.end(), [](const Renamed& x, const Renamed& y) { return x.from == y.from; }),
                      renamed.end());
    }

    const TetLimits limits = limits_for(mesh, star, rules, must_exceed);
    struct Moved {
        Tet q;
        int32_t region, origin;
    };
    std::vector<Moved> moved;
    for (int32_t t : star) {
        Tet q = mesh.tet(t);
        if (holds(q, w)) continue;
        std::replace(q.begin(), q.end(), v, w);
        const TetPoints p{mesh.point(q[0]), mesh.point(q[1]), mesh.point(q[2]), mesh.point(q[3])};
        if (!acceptable_tet(p, limits) || mesh.has_tet(q)) return false;
        moved.push_back({q, mesh.region(t), mesh.origin(t)});
    }

    // Apply.
    for (int32_t t : star) mesh.remove_tet(t);
    for (const Moved& m : moved) mesh.add_tet(m.q, m.region, m.origin);
    for (const auto& [f, marked] : dropped)
        if (marked) mesh.erase_marker(f);
    for (const Renamed& r : renamed) {
        if (!r.marked) continue;
        mesh.erase_marker(r.from);
        mesh.set_marker(r.to, r.marker);
    }
    mesh.neighbors(w, around);  // v's former neighbours are now w's
    for (int32_t x : around) {
        if (!mesh.is_feature_edge(v, x)) continue;
        const CallerRef caller = mesh.erase_feature_edge(v, x);
        mesh.add_feature_edge(w, x, caller);
    }
    if (mesh.is_feature_edge(v, w)) mesh.erase_feature_edge(v, w);
    return true;
}

}  // namespace

bool collapse_half_edge(EditableMesh& mesh, int32_t v, int32_t w, const TopologyRules& rules, double must_exceed) {
    return collapse_half_edge_with(mesh, v, w, rules, must_exceed, nullptr);
}

int32_t collapse_edge(EditableMesh& mesh, int32_t a, int32_t b, const TopologyRules& rules, double must_exceed) {
    const auto rank = [&mesh](int32_t v) {
        switch (mesh.vertex_class(v)) {
            case VertexClass::Interior: return 0;
            case VertexClass::Surface: return 1;
            case VertexClass::FeatureLine: return 2;
            default: return 3;
        }
    };
    const int ra = rank(a), rb = rank(b);
    if (ra == 3 && rb == 3) return -1;  // rule (a): never between two corners
    if (ra != rb) {
        const int32_t keep = ra > rb ? a : b, gone = ra > rb ? b : a;
        return collapse_half_edge(mesh, gone, keep, rules, must_exceed) ? keep : -1;
    }
    // Equal classes: both go to the midpoint (rule d).  Move b there, check
    // its own tets and surface faces, then collapse a into it.
    const size_t mark = mesh.checkpoint();
    const Vec3 old_b = mesh.point(b);
    Vec3 mid = 0.5 * (mesh.point(a) + old_b);
    if (rules.snap_to_shape && rank(b) > 0) rules.snap_to_shape(mesh, b, mid);
    const double length = (mesh.point(a) - old_b).norm();
    const std::vector<int32_t> star(mesh.tets_of(b));
    const TetLimits limits = limits_for(mesh, star, rules, must_exceed);
    const FacesAt at_b(mesh, b);
    const double slope = rank(b) > 0 ? at_b.slope(mesh, b, rules) : 0.0;
    const double off_surface = slope * std::sqrt(length * at_b.mean_surface_edge(mesh, b));
    mesh.move_vertex(b, mid);
    bool ok = true;
    for (int32_t t : star) {
        const Tet& q = mesh.tet(t);
        if (holds(q, a)) continue;
        ok = ok && acceptable_tet(mesh.tet_points(t), limits);
        for (int i = 0; ok && i < 4 && rank(b) > 0; ++i) {
            if (q[i] == b) continue;
            const FaceKey f = FaceKey::of(q[kFaceVertex[i][0]], q[kFaceVertex[i][1]], q[kFaceVertex[i][2]]);
            if (!at_b.on_surface(f)) continue;
            const Vec3 n = triangle_normal(f.v[0] == b ? old_b : mesh.point(f.v[0]), f.v[1] == b ? old_b : mesh.point(f.v[1]),
                                           f.v[2] == b ? old_b : mesh.point(f.v[2]));
            const Vec3 moved = triangle_normal(mesh.point(f.v[0]), mesh.point(f.v[1]), mesh.point(f.v[2]));
            ok = (near_plane(n, old_b, mid, length, off_surface) && turns_little(n, moved, rules)) ||
                 (rules.on_curved_shape && rules.on_curved_shape(mesh, {f.v[0], f.v[1], f.v[2]}, mid));
        }
    }
    if (ok && rank(b) > 0) {
        std::vector<int32_t> around;
        mesh.neighbors(b, around);
        ok = rules.surface_may_change && feature_lines_allow(mesh, b, a, length, rules, slope, around);
    }
    // b's faces are as they were: only its point moved.
    if (ok && collapse_half_edge_with(mesh, a, b, rules, must_exceed, &at_b)) return b;
    mesh.rollback(mark);
    return -1;
}

}  // namespace bodt
