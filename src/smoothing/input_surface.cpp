#include "smoothing/input_surface.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace bodt {

namespace {

// The two sides of a face: region ids, or kOutside beyond the boundary.
using Sides = std::pair<int64_t, int64_t>;
constexpr int64_t kOutside = static_cast<int64_t>(std::numeric_limits<int32_t>::min()) - 1;

// Points and triangles of one closest-point tree, its vertices renumbered
// from the mesh's in order of first use.
class TreeBuilder {
public:
    explicit TreeBuilder(int32_t num_vertices) : local_(static_cast<size_t>(num_vertices), -1) {}

    void add(const TetMesh& mesh, int32_t a, int32_t b, int32_t c) {
        triangles_.push_back({local(mesh, a), local(mesh, b), local(mesh, c)});
    }

    // The tree of what was added; the builder is empty again.
    SurfaceBvh take() {
        for (int32_t v : used_) local_[v] = -1;
        used_.clear();
        SurfaceBvh tree(std::move(points_), std::move(triangles_));
        points_.clear();
        triangles_.clear();
        return tree;
    }

private:
    int32_t local(const TetMesh& mesh, int32_t v) {
        if (local_[v] < 0) {
            local_[v] = static_cast<int32_t>(points_.size());
            points_.push_back(mesh.points[v]);
            used_.push_back(v);
        }
        return local_[v];
    }

    std::vector<int32_t> local_, used_;
    std::vector<Vec3> points_;
    std::vector<std::array<int32_t, 3>> triangles_;
};

// Union-find: the root of x's set, halving the path on the way.
int32_t find_root(std::vector<int32_t>& parent, int32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

// The members of each set, sets in the order of their first member.
std::vector<std::vector<int32_t>> group_by_root(std::vector<int32_t>& parent) {
    std::vector<int32_t> group(parent.size(), -1);
    std::vector<std::vector<int32_t>> groups;
    for (int32_t x = 0; x < static_cast<int32_t>(parent.size()); ++x) {
        int32_t& g = group[find_root(parent, x)];
        if (g < 0) {
            g = static_cast<int32_t>(groups.size());
            groups.emplace_back();
        }
        groups[g].push_back(x);
    }
    return groups;
}

}  // namespace

InputSurface::SidedFaces InputSurface::sided_faces(const TetMesh& mesh) {
    std::vector<std::pair<FaceKey, Sides>> found;
    for (int32_t t = 0; t < mesh.num_tets(); ++t)
        for (int i = 0; i < 4; ++i) {
            if (!mesh.is_surface_face(t, i)) continue;
            const int32_t s = mesh.neighbors[t][i];
            // A marked face inside one region (its vertices never move), or
            // an interface face already seen from the other side.
            if (s >= 0 && (mesh.regions[s] == mesh.regions[t] || s < t)) continue;
            const Tet& q = mesh.tets[t];
            const auto caller = [&mesh, &q, i](int k) { return mesh.caller_vertex(q[kFaceVertex[i][k]]); };
            const int64_t a = mesh.regions[t], b = s < 0 ? kOutside : mesh.regions[s];
            found.push_back({FaceKey::of(caller(0), caller(1), caller(2)), {std::min(a, b), std::max(a, b)}});
        }
    // The pairs of sides numbered in order.
    std::vector<Sides> pairs;
    for (const auto& f : found) pairs.push_back(f.second);
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    SidedFaces faces;
    faces.reserve(found.size());
    for (const auto& [key, sides] : found)
        faces.push_back(
            {key, static_cast<int32_t>(std::lower_bound(pairs.begin(), pairs.end(), sides) - pairs.begin())});
    std::sort(faces.begin(), faces.end());
    return faces;
}

void InputSurface::update(const TetMesh& mesh, const VertexClasses& classes) {
    SidedFaces faces = sided_faces(mesh);
    std::vector<EdgeKey> features;
    features.reserve(classes.feature_edges.size());
    for (const EdgeKey e : classes.feature_edges)
        features.push_back(edge_key(mesh.caller_vertex(edge_first(e)), mesh.caller_vertex(edge_second(e))));
    std::sort(features.begin(), features.end());
    if (captured_ && faces == faces_ && features == feature_edges_) return;
    faces_ = std::move(faces);
    feature_edges_ = std::move(features);
    capture_patches(mesh);
    capture_lines(mesh, classes);
    captured_ = true;
}

void InputSurface::capture_patches(const TetMesh& mesh) {
    // Faces on the same sides joined across their edges that are not
    // feature edges.
    const int32_t nf = static_cast<int32_t>(faces_.size());
    std::vector<int32_t> parent(static_cast<size_t>(nf));
    std::iota(parent.begin(), parent.end(), 0);
    std::unordered_map<EdgeKey, int32_t> first_face;
    for (int32_t f = 0; f < nf; ++f) {
        const auto& v = faces_[f].first.v;
        for (int k = 0; k < 3; ++k) {
            const EdgeKey e = edge_key(v[k], v[(k + 1) % 3]);
            if (std::binary_search(feature_edges_.begin(), feature_edges_.end(), e)) continue;
            const auto [seen, fresh] = first_face.emplace(e, f);
            if (!fresh && faces_[seen->second].second == faces_[f].second)
                parent[find_root(parent, f)] = find_root(parent, seen->second);
        }
    }
    const std::vector<std::vector<int32_t>> members = group_by_root(parent);
    patch_of_.assign(mesh.points.size(), -1);
    patches_.clear();
    TreeBuilder builder(mesh.num_vertices());
    for (int32_t k = 0; k < static_cast<int32_t>(members.size()); ++k) {
        for (int32_t f : members[k]) {
            const auto& c = faces_[f].first.v;
            const int32_t v[3] = {mesh.internal_vertex(c[0]), mesh.internal_vertex(c[1]), mesh.internal_vertex(c[2])};
            builder.add(mesh, v[0], v[1], v[2]);
            for (int32_t u : v) patch_of_[u] = patch_of_[u] == -1 || patch_of_[u] == k ? k : -2;
        }
        patches_.push_back(builder.take());
    }
}

void InputSurface::capture_lines(const TetMesh& mesh, const VertexClasses& classes) {
    line_of_.assign(mesh.points.size(), -1);
    lines_.clear();
    // Feature edges joined through the feature-line vertices between them.
    const auto index = [this, &mesh](int32_t a, int32_t b) {
        const EdgeKey e = edge_key(mesh.caller_vertex(a), mesh.caller_vertex(b));
        return static_cast<int32_t>(std::lower_bound(feature_edges_.begin(), feature_edges_.end(), e) -
                                    feature_edges_.begin());
    };
    std::vector<int32_t> parent(feature_edges_.size());
    std::iota(parent.begin(), parent.end(), 0);
    const int32_t nv = mesh.num_vertices();
    for (int32_t v = 0; v < nv; ++v) {
        const auto& line = classes.line[v];
        if (classes.cls[v] == VertexClass::FeatureLine && line[0] >= 0)
            parent[find_root(parent, index(v, line[0]))] = find_root(parent, index(v, line[1]));
    }
    const std::vector<std::vector<int32_t>> members = group_by_root(parent);
    std::vector<int32_t> line_of_edge(feature_edges_.size());
    TreeBuilder builder(nv);
    for (int32_t k = 0; k < static_cast<int32_t>(members.size()); ++k) {
        for (int32_t e : members[k]) {
            const int32_t a = mesh.internal_vertex(edge_first(feature_edges_[e]));
            const int32_t b = mesh.internal_vertex(edge_second(feature_edges_[e]));
            builder.add(mesh, a, b, b);
            line_of_edge[e] = k;
        }
        lines_.push_back(builder.take());
    }
    for (int32_t v = 0; v < nv; ++v) {
        const auto& line = classes.line[v];
        if (classes.cls[v] == VertexClass::FeatureLine && line[0] >= 0)
            line_of_[v] = line_of_edge[index(v, line[0])];
    }
}

bool InputSurface::projects(int32_t v, VertexClass c) const {
    if (v >= static_cast<int32_t>(patch_of_.size())) return false;
    return (c == VertexClass::FeatureLine && line_of_[v] >= 0) || patch_of_[v] >= 0;
}

Vec3 InputSurface::project(int32_t v, VertexClass c, const Vec3& p) const {
    if (c == VertexClass::FeatureLine && line_of_[v] >= 0) return lines_[line_of_[v]].closest(p).point;
    return patches_[patch_of_[v]].closest(p).point;
}

}  // namespace bodt
