#include "features/vertex_classes.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace bodt {

namespace {

Vec3 face_normal(const TetMesh& mesh, const BoundarySurface& s, SurfaceMesh::FaceHandle f) {
    Vec3 p[3];
    int k = 0;
    for (auto vh : s.mesh().fv_range(f)) p[k++] = mesh.points[s.tet_vertex(vh)];
    return (p[1] - p[0]).cross(p[2] - p[0]);
}

FaceKey face_key(const BoundarySurface& s, SurfaceMesh::FaceHandle f) {
    int32_t v[3];
    int k = 0;
    for (auto vh : s.mesh().fv_range(f)) v[k++] = s.tet_vertex(vh);
    return FaceKey::of(v[0], v[1], v[2]);
}

// Feature edges of the surfaces: sharp (normals differ by more than the
// feature angle) or junctions (more than two distinct faces meet).
EdgeSet detect_feature_edges(const TetMesh& mesh, const RegionSurfaces& surfaces, double feature_angle_deg) {
    const double cos_limit = std::cos(feature_angle_deg * kDegree);
    struct Seen {
        FaceKey a, b;
    };
    std::unordered_map<EdgeKey, Seen> seen;
    EdgeSet features;
    for (int32_t k = 0; k < surfaces.count(); ++k) {
        const BoundarySurface& s = surfaces.surface(k);
        for (auto eh : s.mesh().edges()) {
            const auto h = eh.h0();
            if (!h.face().is_valid() || !h.opp().face().is_valid()) continue;  // an open ring
            const EdgeKey key = edge_key(s.tet_vertex(h.from()), s.tet_vertex(h.to()));
            const Vec3 n1 = face_normal(mesh, s, h.face()), n2 = face_normal(mesh, s, h.opp().face());
            const double den = n1.norm() * n2.norm();
            if (den > 0.0 && n1.dot(n2) < cos_limit * den) features.insert(key);
            FaceKey fa = face_key(s, h.face()), fb = face_key(s, h.opp().face());
            if (fb < fa) std::swap(fa, fb);
            const auto [it, fresh] = seen.emplace(key, Seen{fa, fb});
            if (!fresh && !(it->second.a == fa && it->second.b == fb)) features.insert(key);
        }
    }
    return features;
}

// Vertices on a marked interior face inside one region (a "fin"): no
// tangent plane is defined for them, so they stay where they are.
std::vector<char> fin_vertices(const TetMesh& mesh) {
    std::vector<char> fin(mesh.points.size(), 0);
    if (mesh.face_markers.empty()) return fin;
    const std::vector<uint8_t> marked = mesh.marked_face_vertices();
    for (int32_t t = 0; t < mesh.num_tets(); ++t)
        for (int i = 0; i < 4; ++i) {
            if (mesh.is_region_boundary_face(t, i)) continue;
            const Tet& q = mesh.tets[t];
            const int32_t a = q[kFaceVertex[i][0]], b = q[kFaceVertex[i][1]], c = q[kFaceVertex[i][2]];
            if (mesh.is_marked_face(t, i, marked)) fin[a] = fin[b] = fin[c] = 1;
        }
    return fin;
}

}  // namespace

void tensor_voting(const TetMesh& mesh, const RegionSurfaces& surfaces, int32_t v, std::vector<FaceKey>& faces,
                   std::vector<int32_t>& ring, Vec3& mu, Eigen::Matrix3d& e) {
    // The faces by the caller's vertex indices, so that the sum (and each
    // face's normal) does not depend on the internal order.
    faces.clear();
    const auto caller = [&mesh](int32_t u) { return mesh.caller_vertex(u); };
    for (const int32_t* k = surfaces.begin(v); k != surfaces.end(v); ++k) {
        surfaces.surface(*k).one_ring(v, ring);
        for (size_t i = 0; i < ring.size(); ++i)
            faces.push_back(FaceKey::of(caller(v), caller(ring[i]), caller(ring[(i + 1) % ring.size()])));
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for (const FaceKey& f : faces) {
        const Vec3& a = mesh.points[mesh.internal_vertex(f.v[0])];
        const Vec3& b = mesh.points[mesh.internal_vertex(f.v[1])];
        const Vec3 c = (b - a).cross(mesh.points[mesh.internal_vertex(f.v[2])] - a);
        const double len = c.norm();
        if (len > 0.0) M += c * c.transpose() / (2.0 * len);  // S_i n_i n_i^T, eq. (11)
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(M);
    mu = solver.eigenvalues().reverse();
    e = solver.eigenvectors().rowwise().reverse();
}

VertexClasses classify_vertices(const TetMesh& mesh, const RegionSurfaces& surfaces, const FeatureSettings& settings) {
    const int32_t nv = mesh.num_vertices();
    VertexClasses out;
    out.cls.assign(static_cast<size_t>(nv), VertexClass::Interior);
    out.line.assign(static_cast<size_t>(nv), {-1, -1});
    const std::vector<char> fin = fin_vertices(mesh);

    EdgeSet features;
    if (settings.detect_features) {
        features = detect_feature_edges(mesh, surfaces, settings.feature_angle_deg);
        for (const auto& [key, ref] : mesh.feature_edges) features.insert(key);
    }
    std::vector<int32_t> count(static_cast<size_t>(nv), 0);
    for (EdgeKey key : features) {
        const int32_t a = edge_first(key), b = edge_second(key);
        for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
            if (count[x] < 2) out.line[x][count[x]] = y;
            ++count[x];
        }
    }

    const double cos_kink = std::cos((180.0 - settings.feature_angle_deg) * kDegree);
    std::vector<FaceKey> scratch;
    std::vector<int32_t> ring;
    for (int32_t v = 0; v < nv; ++v) {
        const uint8_t flags = mesh.vflags[v];
        VertexClass& c = out.cls[v];
        if (flags & kUnused) c = VertexClass::Unused;
        else if (flags & kCorner) c = VertexClass::Corner;
        else if (flags & kFixed) c = VertexClass::Fixed;
        else if (fin[v] || surfaces.blocked(v) ||
                 ((flags & (kOnBoundary | kOnInterface)) && surfaces.begin(v) == surfaces.end(v)))
            c = VertexClass::Fixed;
        else if (surfaces.begin(v) == surfaces.end(v)) c = VertexClass::Interior;
        else if (!settings.detect_features) c = VertexClass::Surface;
        else {
            // Feature edges at v.
            if (count[v] == 0) c = VertexClass::Surface;
            else if (count[v] == 2) {
                const Vec3 da = mesh.points[out.line[v][0]] - mesh.points[v];
                const Vec3 db = mesh.points[out.line[v][1]] - mesh.points[v];
                const bool kink = da.dot(db) > cos_kink * da.norm() * db.norm();
                c = kink ? VertexClass::Corner : VertexClass::FeatureLine;
            } else {
                c = VertexClass::Corner;
            }
            // Tensor voting, eq. (11).
            Vec3 mu;
            Eigen::Matrix3d e;
            tensor_voting(mesh, surfaces, v, scratch, ring, mu, e);
            if (mu[0] > 0.0) {
                if (mu[2] > settings.corner_ratio * mu[0]) c = VertexClass::Corner;
                else if (mu[1] > settings.edge_ratio * mu[0] && c == VertexClass::Surface) c = VertexClass::FeatureLine;
            }
        }
        if (c != VertexClass::FeatureLine || count[v] != 2) out.line[v] = {-1, -1};
    }
    out.feature_edges = std::move(features);
    return out;
}

}  // namespace bodt
