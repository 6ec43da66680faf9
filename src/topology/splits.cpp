// Edge split and face split: a new vertex, and every tet on the split edge
// or face cut into two or three, so the mesh stays conforming.
#include "topology/op_support.hpp"
#include "topology/operations.hpp"

#include <algorithm>

namespace bodt {

namespace {

// Each tet of `old_tets` with one vertex of `cut` replaced by the new
// vertex p, for every vertex of `cut` it holds: the pieces keep the tet's
// orientation, region and origin.  False (nothing changed) if a piece is
// not acceptable.
bool cut_tets(EditableMesh& mesh, const std::vector<int32_t>& old_tets, std::initializer_list<int32_t> cut,
              const Vec3& p, const TetLimits& limits, int32_t& new_vertex, VertexClass cls, Parents parents) {
    struct Piece {
        Tet q;
        int32_t region, origin;
    };
    std::vector<Piece> pieces;
    for (int32_t t : old_tets) {
        for (int32_t c : cut) {
            Tet q = mesh.tet(t);
            TetPoints pts = mesh.tet_points(t);
            const int k = static_cast<int>(std::find(q.begin(), q.end(), c) - q.begin());
            pts[k] = p;
            if (!acceptable_tet(pts, limits)) return false;
            q[k] = -1;  // the new vertex, numbered below
            pieces.push_back({q, mesh.region(t), mesh.origin(t)});
        }
    }
    new_vertex = mesh.add_vertex(p, cls, std::move(parents));
    for (int32_t t : old_tets) mesh.remove_tet(t);
    for (Piece& piece : pieces) {
        std::replace(piece.q.begin(), piece.q.end(), -1, new_vertex);
        mesh.add_tet(piece.q, piece.region, piece.origin);
    }
    return true;
}

}  // namespace

int32_t split_edge(EditableMesh& mesh, int32_t a, int32_t b, Vec3 p, const TopologyRules& rules, double must_exceed) {
    const std::vector<int32_t> old = mesh.tets_holding({a, b});
    if (old.empty()) return -1;
    const Vec3 &pa = mesh.point(a), &pb = mesh.point(b);
    const double s = std::clamp((p - pa).dot(pb - pa) / (pb - pa).squaredNorm(), 0.0, 1.0);
    const bool on_surface = mesh.is_surface_edge(a, b);
    if (on_surface) {
        if (!rules.surface_may_change) return -1;
        p = pa + s * (pb - pa);
    }
    if (!(s > 0.0 && s < 1.0)) return -1;
    const bool feature = mesh.is_feature_edge(a, b);
    const VertexClass cls = feature ? VertexClass::FeatureLine : on_surface ? VertexClass::Surface : VertexClass::Interior;
    // The surface faces on the edge, and their markers.
    std::vector<std::pair<FaceKey, int32_t>> marked;
    for (int32_t t : old)
        for (int32_t c : mesh.tet(t)) {
            const FaceKey f = FaceKey::of(a, b, c);
            if (c != a && c != b && mesh.has_marker(f)) marked.push_back({f, mesh.marker(f)});
        }
    std::sort(marked.begin(), marked.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    marked.erase(std::unique(marked.begin(), marked.end(), [](const auto& x, const auto& y) { return x.first == y.first; }),
                 marked.end());
    int32_t m = -1;
    if (!cut_tets(mesh, old, {a, b}, p, limits_for(mesh, old, rules, must_exceed), m, cls,
                  blend_parents(mesh, {a, b}, {1.0 - s, s})))
        return -1;
    for (const auto& [f, marker] : marked) {
        int32_t c = f.v[0] + f.v[1] + f.v[2] - a - b;
        mesh.erase_marker(f);
        mesh.set_marker(FaceKey::of(a, m, c), marker);
        mesh.set_marker(FaceKey::of(m, b, c), marker);
    }
    if (mesh.is_feature_edge(a, b)) {
        const CallerRef caller = mesh.erase_feature_edge(a, b);
        mesh.add_feature_edge(a, m, caller);
        mesh.add_feature_edge(m, b, caller);
    }
    return m;
}

int32_t split_face(EditableMesh& mesh, const FaceKey& face, Vec3 p, const TopologyRules& rules, double must_exceed) {
    const int32_t a = face.v[0], b = face.v[1], c = face.v[2];
    const std::vector<int32_t> old = mesh.tets_holding({a, b, c});
    if (old.empty()) return -1;
    const Vec3 &pa = mesh.point(a), &pb = mesh.point(b), &pc = mesh.point(c);
    const Vec3 n = triangle_normal(pa, pb, pc);
    if (!(n.squaredNorm() > 0.0)) return -1;
    if (mesh.is_surface_face(face)) {
        if (!rules.surface_may_change) return -1;
        p -= n * (n.dot(p - pa) / n.squaredNorm());
    }
    // Barycentric coordinates of p's projection: the interpolation weights.
    const double area = n.squaredNorm();
    const double wa = n.dot(triangle_normal(p, pb, pc)) / area, wb = n.dot(triangle_normal(pa, p, pc)) / area;
    const double wc = 1.0 - wa - wb;
    if (!(wa > 0.0 && wb > 0.0 && wc > 0.0)) return -1;
    const bool surface = mesh.is_surface_face(face);
    const bool marked = mesh.has_marker(face);
    const int32_t marker = mesh.marker(face);
    int32_t m = -1;
    if (!cut_tets(mesh, old, {a, b, c}, p, limits_for(mesh, old, rules, must_exceed), m,
                  surface ? VertexClass::Surface : VertexClass::Interior, blend_parents(mesh, {a, b, c}, {wa, wb, wc})))
        return -1;
    if (marked) {
        mesh.erase_marker(face);
        mesh.set_marker(FaceKey::of(m, b, c), marker);
        mesh.set_marker(FaceKey::of(a, m, c), marker);
        mesh.set_marker(FaceKey::of(a, b, m), marker);
    }
    return m;
}

}  // namespace bodt
