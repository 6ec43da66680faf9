// Edge removal (with the 3-2, 4-4 and boundary 2-2 flips as its small cases)
// and the 2-3 flip.
#include "topology/op_support.hpp"
#include "topology/operations.hpp"

#include <algorithm>
#include <array>
#include <limits>

namespace bodt {

double worst_sine(const EditableMesh& mesh, const std::vector<int32_t>& tets) {
    double worst = 1.0;
    for (int32_t t : tets) worst = std::min(worst, mesh.tet_sine(t));
    return worst;
}

namespace {

// The tets replacing a cavity: positively oriented vertex quads.
using NewTets = std::vector<Tet>;

// Replaces `old_tets` (one region) by `fresh`, each new tet inheriting the
// origin of the old tet around its centroid.
void replace(EditableMesh& mesh, const std::vector<int32_t>& old_tets, const NewTets& fresh) {
    const int32_t region = mesh.region(old_tets.front());
    const std::vector<int32_t> origins = origins_of(mesh, old_tets, fresh);
    for (int32_t t : old_tets) mesh.remove_tet(t);
    for (size_t i = 0; i < fresh.size(); ++i) mesh.add_tet(fresh[i], region, origins[i]);
}

std::vector<TetPoints> shapes(const EditableMesh& mesh, const NewTets& tets) {
    std::vector<TetPoints> out;
    for (const Tet& q : tets) out.push_back({mesh.point(q[0]), mesh.point(q[1]), mesh.point(q[2]), mesh.point(q[3])});
    return out;
}

// Paper 002 sec. 3.4.4, conditions 1 and 2: the flip replaces a
// configuration that is not Delaunay by one that is.
bool delaunay_flip(const EditableMesh& mesh, const std::vector<int32_t>& old_tets, const NewTets& fresh) {
    std::vector<int32_t> vs;
    NewTets old;
    for (int32_t t : old_tets) {
        old.push_back(mesh.tet(t));
        vs.insert(vs.end(), mesh.tet(t).begin(), mesh.tet(t).end());
    }
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    std::vector<Vec3> points;
    for (int32_t v : vs) points.push_back(mesh.point(v));
    return !all_delaunay(shapes(mesh, old), points) && all_delaunay(shapes(mesh, fresh), points);
}

bool one_region(const EditableMesh& mesh, const std::vector<int32_t>& tets) {
    for (int32_t t : tets)
        if (mesh.region(t) != mesh.region(tets.front())) return false;
    return true;
}

// Triangulating the ring polygon: best[i][j] is the best worst sine over
// the sub-polygon ring[i..j], split[i][j] the apex that reaches it.
struct PolygonTriangulation {
    double best[kMaxEdgeRing + 1][kMaxEdgeRing + 1];
    int split[kMaxEdgeRing + 1][kMaxEdgeRing + 1];
};

void collect(const PolygonTriangulation& dp, int i, int j, const EdgeRing& r, int32_t a, int32_t b, NewTets& out) {
    if (j - i < 2) return;
    const int m = dp.split[i][j];
    out.push_back({a, r.ring[i], r.ring[m], r.ring[j]});
    out.push_back({b, r.ring[j], r.ring[m], r.ring[i]});
    collect(dp, i, m, r, a, b, out);
    collect(dp, m, j, r, a, b, out);
}

// Every face of the new tets is either a face of the tets they replace or
// not in the mesh at all (else three tets would share it).
bool fits_cavity(const EditableMesh& mesh, const std::vector<int32_t>& old_tets, const NewTets& fresh) {
    for (const Tet& q : fresh) {
        for (int i = 0; i < 4; ++i) {
            const FaceKey f = FaceKey::of(q[kFaceVertex[i][0]], q[kFaceVertex[i][1]], q[kFaceVertex[i][2]]);
            int32_t t[2];
            const int n = mesh.face_tets(f, t);
            bool old_face = false;
            for (int k = 0; k < n; ++k) old_face |= std::find(old_tets.begin(), old_tets.end(), t[k]) != old_tets.end();
            if (n > 0 && !old_face) return false;
        }
    }
    return true;
}

// A surface edge (a, b) in one tet (a, b, c, d): the tet lies on the
// surface by two faces, (a, b, c) and (a, b, d), and its removal puts
// (a, c, d) and (b, c, d) there instead -- the surface's 2-2 flip with the
// tet between the two diagonals taken out.  Kept only where the tet is flat
// along the surface: obtuse at (a, b) and at (c, d), and at its four other
// edges, where an old surface face meets a new one, each new face turned
// from the old by an angle whose sine is at most rules.surface_slope (the
// turn an edge collapse may make), so the surface moves by at most that
// times the faces' size.
bool remove_surface_tet(EditableMesh& mesh, int32_t a, int32_t b, const EdgeRing& r, const TopologyRules& rules) {
    if (!(rules.surface_slope > 0.0)) return false;
    const int32_t t = r.tets.front(), c = r.ring.front(), d = r.ring.back();
    if (mesh.is_surface_edge(c, d)) return false;  // it would border four surface faces
    const FaceKey inner[2] = {FaceKey::of(a, c, d), FaceKey::of(b, c, d)};
    for (const FaceKey& f : inner) {
        int32_t pair[2];
        if (mesh.face_tets(f, pair) != 2 || mesh.region(pair[0]) != mesh.region(pair[1]) || mesh.has_marker(f))
            return false;
    }
    const Tet& q = mesh.tet(t);
    const auto cosines = dihedral_cosines(mesh.tet_points(t));
    const double least_cosine = least_turn_cosine(rules);
    for (int e = 0; e < 6; ++e) {
        const int32_t x = q[kEdgeVertex[e][0]], y = q[kEdgeVertex[e][1]];
        const bool diagonal = (x == a || x == b) == (y == a || y == b);  // (a, b) or (c, d)
        if (diagonal ? !(cosines[e] < 0.0) : !(cosines[e] >= least_cosine)) return false;
    }
    const FaceKey f0 = FaceKey::of(a, b, c), f1 = FaceKey::of(a, b, d);
    const bool marked = mesh.has_marker(f0);
    const int32_t marker = mesh.marker(f0);
    mesh.remove_tet(t);
    if (marked) {
        mesh.erase_marker(f0);
        mesh.erase_marker(f1);
        for (const FaceKey& f : inner) mesh.set_marker(f, marker);
    }
    return true;
}

}  // namespace

bool remove_edge(EditableMesh& mesh, int32_t a, int32_t b, const TopologyRules& rules, double must_exceed) {
    EdgeRing r;
    return mesh.edge_ring(a, b, r) && remove_edge(mesh, a, b, r, rules, must_exceed);
}

bool remove_edge(EditableMesh& mesh, int32_t a, int32_t b, const EdgeRing& r, const TopologyRules& rules,
                 double must_exceed) {
    const int n = static_cast<int>(r.ring.size());  // polygon vertices
    if (n > kMaxEdgeRing || n < 2 || (r.closed && n < 3) || !one_region(mesh, r.tets)) return false;
    if (!r.closed && (!rules.surface_may_change || mesh.is_feature_edge(a, b))) return false;
    const FaceKey f0 = FaceKey::of(a, b, r.ring.front()), f1 = FaceKey::of(a, b, r.ring.back());
    if (!r.closed && mesh.marker(f0) != mesh.marker(f1)) return false;
    if (n == 2) return remove_surface_tet(mesh, a, b, r, rules);
    if (!r.closed) {
        // The edge lies on the surface; its two surface faces (a, b, ring[0])
        // and (a, b, ring[n-1]) become (a, ring[n-1], ring[0]) and (b, ...):
        // only in one plane, with one marker.  Tested first: most surface
        // edges fail it, and the triangulation costs more.
        const Vec3& pa = mesh.point(a);
        const Vec3 nrm = triangle_normal(pa, mesh.point(b), mesh.point(r.ring.front()));
        const double length = (mesh.point(b) - pa).norm() + (mesh.point(r.ring.back()) - pa).norm();
        if (!in_plane(nrm, pa, mesh.point(r.ring.back()), length)) return false;
    }
    // The best triangulation by worst sine alone (most calls end here);
    // the other limits are checked on the winner only.
    PolygonTriangulation dp;
    const double floor = std::max(must_exceed, 0.0);
    for (int i = 0; i + 1 < n; ++i) dp.best[i][i + 1] = std::numeric_limits<double>::infinity();
    for (int len = 2; len < n; ++len) {
        for (int i = 0; i + len < n; ++i) {
            const int j = i + len;
            dp.best[i][j] = floor;
            dp.split[i][j] = -1;
            for (int m = i + 1; m < j; ++m) {
                // Only a triangle that could beat the best so far is evaluated.
                const double sub = std::min(dp.best[i][m], dp.best[m][j]);
                if (!(sub > dp.best[i][j])) continue;
                const Vec3 &pi = mesh.point(r.ring[i]), &pm = mesh.point(r.ring[m]), &pj = mesh.point(r.ring[j]);
                // The tet on b's side only if the one on a's side could win.
                double q = std::min(sub, min_dihedral_sine({mesh.point(a), pi, pm, pj}));
                if (!(q > dp.best[i][j])) continue;
                q = std::min(q, min_dihedral_sine({mesh.point(b), pj, pm, pi}));
                if (!(q > dp.best[i][j])) continue;
                dp.best[i][j] = q;
                dp.split[i][j] = m;
            }
        }
    }
    if (dp.split[0][n - 1] < 0) return false;
    NewTets fresh;
    collect(dp, 0, n - 1, r, a, b, fresh);
    const TetLimits limits = limits_for(mesh, r.tets, rules, must_exceed);
    for (const Tet& q : fresh)
        if (!acceptable_tet({mesh.point(q[0]), mesh.point(q[1]), mesh.point(q[2]), mesh.point(q[3])}, limits)) return false;
    // No marked face inside the cavity (the faces around the edge).
    for (int i = 0; i < n; ++i)
        if ((r.closed || (i > 0 && i + 1 < n)) && mesh.has_marker(FaceKey::of(a, b, r.ring[i]))) return false;
    if (!fits_cavity(mesh, r.tets, fresh)) return false;
    if (rules.delaunay && !delaunay_flip(mesh, r.tets, fresh)) return false;
    const bool marked = !r.closed && mesh.has_marker(f0);
    const int32_t marker = mesh.marker(f0);
    replace(mesh, r.tets, fresh);
    if (marked) {
        mesh.erase_marker(f0);
        mesh.erase_marker(f1);
        mesh.set_marker(FaceKey::of(a, r.ring.front(), r.ring.back()), marker);
        mesh.set_marker(FaceKey::of(b, r.ring.front(), r.ring.back()), marker);
    }
    return true;
}

bool flip_23(EditableMesh& mesh, const FaceKey& face, const TopologyRules& rules, double must_exceed) {
    int32_t t[2];
    return mesh.face_tets(face, t) == 2 && flip_23(mesh, face, t, rules, must_exceed);
}

bool flip_23(EditableMesh& mesh, const FaceKey& face, const int32_t t[2], const TopologyRules& rules,
             double must_exceed) {
    if (mesh.region(t[0]) != mesh.region(t[1])) return false;
    // The face as seen out of t[0], and the two apexes.
    const Tet& q0 = mesh.tet(t[0]);
    int i0 = 0;
    while (q0[i0] == face.v[0] || q0[i0] == face.v[1] || q0[i0] == face.v[2]) ++i0;
    const int32_t d = q0[i0];
    const Tet& q1 = mesh.tet(t[1]);
    int32_t e = -1;
    for (int32_t v : q1)
        if (v != face.v[0] && v != face.v[1] && v != face.v[2]) e = v;
    const int32_t f[3] = {q0[kFaceVertex[i0][0]], q0[kFaceVertex[i0][1]], q0[kFaceVertex[i0][2]]};
    // (f_k, f_k+1, f_k+2) points out of t[0], towards e: (f_k, f_k+1, d, e)
    // is positive.  The worst sine first: most flips fail it, and it needs
    // no lookup.
    std::array<TetPoints, 3> p;
    const double floor = sine_floor(rules, must_exceed);
    for (int k = 0; k < 3; ++k) {
        p[k] = {mesh.point(f[k]), mesh.point(f[(k + 1) % 3]), mesh.point(d), mesh.point(e)};
        if (!(min_dihedral_sine(p[k]) > floor)) return false;
    }
    // A marked face stays; the new edge (d, e) must not exist yet.
    if (mesh.has_marker(face) || mesh.has_edge(d, e)) return false;
    const std::vector<int32_t> old{t[0], t[1]};
    const TetLimits limits = limits_for(mesh, old, rules, must_exceed);
    for (const TetPoints& shape : p)
        if (!acceptable_shape(shape, limits)) return false;
    NewTets fresh;
    for (int k = 0; k < 3; ++k) fresh.push_back({f[k], f[(k + 1) % 3], d, e});
    if (!fits_cavity(mesh, old, fresh)) return false;
    if (rules.delaunay && !delaunay_flip(mesh, old, fresh)) return false;
    replace(mesh, old, fresh);
    return true;
}

}  // namespace bodt
