#include "features/geometry_model.hpp"

#include "topology/editable_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodt {

namespace {

struct Face {
    std::array<int32_t, 3> v;
    Vec3 normal;  // not unit
};

// The edges of the surface faces, each with the faces on it.
std::unordered_map<EdgeKey, std::vector<int32_t>> edge_faces(const std::vector<Face>& faces) {
    std::unordered_map<EdgeKey, std::vector<int32_t>> out;
    for (int32_t f = 0; f < static_cast<int32_t>(faces.size()); ++f)
        for (int i = 0; i < 3; ++i) out[edge_key(faces[f].v[i], faces[f].v[(i + 1) % 3])].push_back(f);
    return out;
}

// Whether the edge (a, b) runs a -> b in face f.
bool runs_forward(const Face& f, int32_t a, int32_t b) {
    for (int i = 0; i < 3; ++i)
        if (f.v[i] == a && f.v[(i + 1) % 3] == b) return true;
    return false;
}

// Sharp: not shared by exactly two faces (a boundary of an open surface, a
// junction of interfaces), or the two faces' normals, oriented alike
// across the edge, differ by more than the feature angle.
bool is_sharp(const std::vector<Face>& faces, const std::vector<int32_t>& on_edge, int32_t a, int32_t b, double cos_limit,
              bool folds) {
    if (on_edge.size() != 2) return true;
    const Face& f = faces[on_edge[0]];
    const Face& g = faces[on_edge[1]];
    // Consistently oriented neighbours run the shared edge in opposite directions.
    const double sign = runs_forward(f, a, b) == runs_forward(g, a, b) ? -1.0 : 1.0;
    const double den = f.normal.norm() * g.normal.norm();
    if (!(den > 0.0)) return !folds;
    const double c = sign * f.normal.dot(g.normal);
    return c < cos_limit * den && !(folds && c < -cos_limit * den);
}

double extent(const std::vector<Vec3>& pts) {
    Vec3 lo = pts.front(), hi = pts.front();
    for (const Vec3& p : pts) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    return (hi - lo).norm();
}

// A plane if one fits, else a cylinder, else None (sec. 3.3).
Shape fit_region(const std::vector<Vec3>& pts, const std::vector<Vec3>& normals, double tolerance) {
    const double size = extent(pts);
    Shape plane = fit_plane(pts);
    if (plane.type == ShapeType::Plane && plane.max_error <= tolerance * size) return plane;
    Shape cylinder = fit_cylinder(pts, normals);
    if (cylinder.type == ShapeType::Cylinder && cylinder.max_error <= tolerance * size) return cylinder;
    return Shape{};
}

// A line if one fits, else a circle (closed) or an arc, else None.  A chain
// is curved only along a cylinder (sec. 3.3: by the types of the regions
// beside it; two planes meet in a line), and only on four points or more
// (three always lie on a circle).
Shape fit_chain(const std::vector<Vec3>& pts, bool closed, bool along_cylinder, double tolerance) {
    const double size = extent(pts);
    if (!closed) {
        Shape line = fit_line(pts);
        if (line.type == ShapeType::Line && line.max_error <= tolerance * size) return line;
    }
    if (!along_cylinder || pts.size() < 4) return Shape{};
    Shape circle = fit_circle(pts);
    if (circle.type == ShapeType::Arc && circle.max_error <= tolerance * size) {
        if (closed) circle.type = ShapeType::Circle;
        return circle;
    }
    return Shape{};
}

void add_unique(std::vector<int32_t>& list, int32_t x) {
    if (std::find(list.begin(), list.end(), x) == list.end()) list.push_back(x);
}

}  // namespace

GeometryModel GeometryModel::extract(const TetMesh& mesh, const GeometrySettings& settings,
                                     const std::vector<Vec3>& undeformed) {
    GeometryModel g;
    const int32_t nv = mesh.num_vertices();
    // Where sharpness is judged.
    std::vector<Vec3> at = mesh.points;
    std::copy(undeformed.begin(), undeformed.begin() + std::min<size_t>(undeformed.size(), at.size()), at.begin());
    bool folds = false;
    if (undeformed.empty())
        for (int32_t t = 0; t < mesh.num_tets() && !folds; ++t) {
            const TetPoints p = mesh.tet_points(t);
            folds = signed_volume(p[0], p[1], p[2], p[3]) <= 0.0;
        }
    std::vector<Face> faces;
    for (const SurfaceFace& s : mesh.surface_faces()) {
        const Vec3& a = at[s.v[0]];
        faces.push_back({s.v, (at[s.v[1]] - a).cross(at[s.v[2]] - a)});
    }
    const auto on_edge = edge_faces(faces);

    // Sharp edges, then corners: a vertex on one sharp edge, on three or
    // more, or where its two turn by more than the feature angle.
    const double cos_limit = std::cos(settings.feature_angle_deg * kDegree);
    for (const auto& [key, fs] : on_edge)
        if (is_sharp(faces, fs, edge_first(key), edge_second(key), cos_limit, folds)) g.sharp_.insert(key);
    for (const auto& [key, ref] : mesh.feature_edges)
        if (on_edge.count(key)) g.sharp_.insert(key);
    std::vector<std::vector<int32_t>> along(static_cast<size_t>(nv));
    for (EdgeKey key : g.sharp_) {
        along[edge_first(key)].push_back(edge_second(key));
        along[edge_second(key)].push_back(edge_first(key));
    }
    for (auto& a : along) std::sort(a.begin(), a.end());

    g.cls_.assign(static_cast<size_t>(nv), VertexClass::Interior);
    g.entity_.assign(static_cast<size_t>(nv), -1);
    const double cos_kink = std::cos((180.0 - settings.feature_angle_deg) * kDegree);
    for (const Face& f : faces)
        for (int32_t v : f.v) g.cls_[v] = VertexClass::Surface;
    for (int32_t v = 0; v < nv; ++v) {
        if (along[v].empty()) continue;
        bool corner = along[v].size() != 2 || (mesh.vflags[v] & kCorner);  // the caller's corners end chains
        if (!corner) {
            const Vec3 da = at[along[v][0]] - at[v], db = at[along[v][1]] - at[v];
            corner = da.dot(db) > cos_kink * da.norm() * db.norm();
        }
        g.cls_[v] = corner ? VertexClass::Corner : VertexClass::FeatureLine;
    }

    // Chains: walks along sharp edges from each corner, then the loops left.
    EdgeSet walked;
    std::vector<std::vector<int32_t>> chain_vertices;
    std::vector<char> chain_closed;
    const auto walk = [&](int32_t start, int32_t next) {
        std::vector<int32_t> chain{start};
        int32_t prev = start, cur = next;
        walked.insert(edge_key(start, next));
        while (true) {
            chain.push_back(cur);
            if (cur == start || g.cls_[cur] == VertexClass::Corner) break;
            const int32_t to = along[cur][0] == prev ? along[cur][1] : along[cur][0];
            if (walked.count(edge_key(cur, to))) break;
            walked.insert(edge_key(cur, to));
            prev = cur;
            cur = to;
        }
        const bool closed = chain.front() == chain.back() && g.cls_[start] != VertexClass::Corner;
        if (closed) chain.pop_back();
        chain_vertices.push_back(std::move(chain));
        chain_closed.push_back(closed);
    };
    for (int32_t v = 0; v < nv; ++v)
        if (g.cls_[v] == VertexClass::Corner)
            for (int32_t n : along[v])
                if (!walked.count(edge_key(v, n))) walk(v, n);
    for (int32_t v = 0; v < nv; ++v)
        if (g.cls_[v] == VertexClass::FeatureLine && !walked.count(edge_key(v, along[v][0]))) walk(v, along[v][0]);

    // Regions: faces joined across edges that are not sharp.
    std::vector<int32_t> face_region(faces.size(), -1);
    int32_t nregions = 0;
    for (size_t seed = 0; seed < faces.size(); ++seed) {
        if (face_region[seed] >= 0) continue;
        std::vector<int32_t> stack{static_cast<int32_t>(seed)};
        face_region[seed] = nregions;
        while (!stack.empty()) {
            const Face& f = faces[stack.back()];
            stack.pop_back();
            for (int i = 0; i < 3; ++i) {
                const EdgeKey key = edge_key(f.v[i], f.v[(i + 1) % 3]);
                if (g.sharp_.count(key)) continue;
                for (int32_t h : on_edge.at(key))
                    if (face_region[h] < 0) {
                        face_region[h] = nregions;
                        stack.push_back(h);
                    }
            }
        }
        ++nregions;
    }

    // Fits.
    std::vector<std::vector<Vec3>> rpts(static_cast<size_t>(nregions)), rnormals(static_cast<size_t>(nregions));
    std::vector<std::vector<int32_t>> rverts(static_cast<size_t>(nregions));
    for (size_t f = 0; f < faces.size(); ++f) {
        const int32_t r = face_region[f];
        for (int32_t v : faces[f].v) rverts[r].push_back(v);
        rnormals[r].push_back(faces[f].normal);
    }
    g.regions_.resize(static_cast<size_t>(nregions));
    for (int32_t r = 0; r < nregions; ++r) {
        auto& vs = rverts[r];
        std::sort(vs.begin(), vs.end());
        vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
        for (int32_t v : vs) rpts[r].push_back(mesh.points[v]);
        g.regions_[r].shape = fit_region(rpts[r], rnormals[r], settings.fit_tolerance);
        for (int32_t v : vs) {
            if (g.cls_[v] == VertexClass::Surface) g.entity_[v] = r;
            if (g.cls_[v] == VertexClass::Corner) add_unique(g.corner_regions_[v], r);
        }
    }
    for (size_t f = 0; f < faces.size(); ++f) {
        SurfaceRegion& region = g.regions_[face_region[f]];
        if (region.shape.type != ShapeType::Cylinder) continue;
        for (int i = 0; i < 3; ++i) {
            const Vec3 mid = 0.5 * (mesh.points[faces[f].v[i]] + mesh.points[faces[f].v[(i + 1) % 3]]);
            region.own_error = std::max(region.own_error, region.shape.distance(mid));
        }
        region.acceptable_error = region.own_error;
    }
    for (size_t f = 0; f < faces.size(); ++f) {
        const auto& v = faces[f].v;
        if (g.cls_[v[0]] != VertexClass::Surface && g.cls_[v[1]] != VertexClass::Surface &&
            g.cls_[v[2]] != VertexClass::Surface)
            g.rim_faces_[FaceKey::of(v[0], v[1], v[2])] = face_region[f];
    }
    for (size_t c = 0; c < chain_vertices.size(); ++c) {
        const auto& vs = chain_vertices[c];
        std::vector<Vec3> pts;
        for (int32_t v : vs) pts.push_back(mesh.points[v]);
        SharpChain chain;
        for (size_t i = 0; i + 1 < vs.size() + (chain_closed[c] ? 1 : 0); ++i)
            for (int32_t f : on_edge.at(edge_key(vs[i], vs[(i + 1) % vs.size()]))) add_unique(chain.regions, face_region[f]);
        std::sort(chain.regions.begin(), chain.regions.end());
        bool along_cylinder = false;
        for (int32_t r : chain.regions) along_cylinder = along_cylinder || g.regions_[r].shape.type == ShapeType::Cylinder;
        chain.shape = fit_chain(pts, chain_closed[c], along_cylinder, settings.fit_tolerance);
        const int32_t id = static_cast<int32_t>(g.chains_.size());
        for (int32_t v : vs) {
            if (g.cls_[v] == VertexClass::FeatureLine) g.entity_[v] = id;
            else add_unique(g.corner_chains_[v], id);
        }
        g.chains_.push_back(std::move(chain));
    }
    for (int32_t v = 0; v < nv; ++v)
        if (mesh.vflags[v] & kUnused) g.cls_[v] = VertexClass::Unused;
    return g;
}

std::vector<int32_t> GeometryModel::regions_at(int32_t v) const {
    if ((cls_[v] == VertexClass::Surface || cls_[v] == VertexClass::FeatureLine) && entity_[v] < 0) return {};
    switch (cls_[v]) {
        case VertexClass::Surface: return {entity_[v]};
        case VertexClass::FeatureLine: return chains_[entity_[v]].regions;
        default: {
            const auto it = corner_regions_.find(v);
            return it == corner_regions_.end() ? std::vector<int32_t>{} : it->second;
        }
    }
}

int32_t GeometryModel::face_region(int32_t a, int32_t b, int32_t c, const Vec3& centroid) const {
    const auto rim = rim_faces_.find(FaceKey::of(a, b, c));
    if (rim != rim_faces_.end()) return rim->second;
    std::vector<int32_t> common = regions_at(a);
    for (int32_t x : {b, c}) {
        const std::vector<int32_t> rx = regions_at(x);
        common.erase(std::remove_if(common.begin(), common.end(),
                                    [&rx](int32_t r) { return std::find(rx.begin(), rx.end(), r) == rx.end(); }),
                     common.end());
    }
    int32_t best = -1;
    double nearest = std::numeric_limits<double>::infinity();
    for (int32_t r : common) {
        const Shape& s = regions_[r].shape;
        const double d = s.type == ShapeType::None ? std::numeric_limits<double>::max() : s.distance(centroid);
        if (best < 0 || d < nearest) {
            best = r;
            nearest = d;
        }
    }
    return best;
}

const Shape* GeometryModel::shape_of(int32_t v) const {
    const Shape* s = nullptr;
    if (cls_[v] == VertexClass::Surface && entity_[v] >= 0) s = &regions_[entity_[v]].shape;
    if (cls_[v] == VertexClass::FeatureLine && entity_[v] >= 0) s = &chains_[entity_[v]].shape;
    return s && s->type != ShapeType::None ? s : nullptr;
}

GeometryModel::GeometricError GeometryModel::geometric_error(const TetMesh& mesh) const {
    GeometricError out;
    const auto& p = mesh.points;
    EdgeSet seen;
    double sum = 0.0;
    for (const SurfaceFace& f : mesh.surface_faces()) {
        const auto& v = f.v;
        const int32_t r = face_region(v[0], v[1], v[2], (p[v[0]] + p[v[1]] + p[v[2]]) / 3.0);
        if (r < 0 || regions_[r].shape.type != ShapeType::Cylinder) continue;
        for (int i = 0; i < 3; ++i) {
            const int32_t a = v[i], b = v[(i + 1) % 3];
            if (!seen.insert(edge_key(a, b)).second) continue;
            const double e = regions_[r].shape.distance(0.5 * (p[a] + p[b]));
            sum += e;
            out.max = std::max(out.max, e);
            ++out.edges;
        }
    }
    if (out.edges) out.mean = sum / static_cast<double>(out.edges);
    return out;
}

VertexClasses GeometryModel::vertex_classes(const TetMesh& mesh) const {
    VertexClasses out;
    out.cls.assign(cls_.begin(), cls_.begin() + mesh.num_vertices());
    for (int32_t v = 0; v < mesh.num_vertices(); ++v)
        if (mesh.vflags[v] & kCorner) out.cls[v] = VertexClass::Corner;
        else if ((mesh.vflags[v] & kFixed) ||
                 ((cls_[v] == VertexClass::Surface || cls_[v] == VertexClass::FeatureLine) && !shape_of(v)))
            out.cls[v] = VertexClass::Fixed;
    out.line.assign(out.cls.size(), {-1, -1});
    out.feature_edges = sharp_;
    return out;
}

int32_t GeometryModel::resolve(const EditableMesh& mesh, int32_t v) const {
    const VertexClass cls = mesh.vertex_class(v);
    if (cls != VertexClass::Surface && cls != VertexClass::FeatureLine) return -1;
    std::vector<int32_t> around, candidates;
    mesh.neighbors(v, around);
    for (int32_t n : around) {
        if (n >= num_vertices() || cls_[n] == VertexClass::Interior) continue;
        if (cls == VertexClass::FeatureLine) {
            if (!mesh.is_feature_edge(v, n)) continue;
            if (cls_[n] == VertexClass::FeatureLine) add_unique(candidates, entity_[n]);
            const auto it = corner_chains_.find(n);
            if (it != corner_chains_.end())
                for (int32_t c : it->second) add_unique(candidates, c);
        } else if (mesh.is_surface_edge(v, n)) {
            for (int32_t r : regions_at(n)) add_unique(candidates, r);
        }
    }
    int32_t best = -1;
    double nearest = std::numeric_limits<double>::infinity();
    for (int32_t e : candidates) {
        if (e < 0) continue;
        const Shape& s = cls == VertexClass::FeatureLine ? chains_[e].shape : regions_[e].shape;
        const double d = s.type == ShapeType::None ? std::numeric_limits<double>::max() : s.distance(mesh.point(v));
        if (best < 0 || d < nearest) {
            best = e;
            nearest = d;
        }
    }
    return best;
}

void GeometryModel::set(int32_t v, VertexClass cls, int32_t entity) {
    if (v >= num_vertices()) {
        cls_.resize(static_cast<size_t>(v) + 1, VertexClass::Unused);
        entity_.resize(static_cast<size_t>(v) + 1, -1);
    }
    cls_[v] = cls;
    entity_[v] = entity;
}

void GeometryModel::truncate(int32_t n) {
    if (n >= num_vertices()) return;
    cls_.resize(static_cast<size_t>(n));
    entity_.resize(static_cast<size_t>(n));
}

void GeometryModel::follow(const EditableMesh& edited, const std::vector<int32_t>& renumber, const TetMesh& written) {
    for (int32_t v = num_vertices(); v < edited.num_vertices(); ++v) set(v, edited.vertex_class(v), resolve(edited, v));
    std::vector<VertexClass> cls(static_cast<size_t>(written.num_vertices()), VertexClass::Unused);
    std::vector<int32_t> entity(cls.size(), -1);
    for (int32_t v = 0; v < edited.num_vertices(); ++v) {
        const int32_t to = renumber[v];
        if (to < 0) continue;
        // A vertex the editable mesh held Fixed keeps its geometric class.
        cls[to] = edited.vertex_class(v) == VertexClass::Fixed ? cls_[v] : edited.vertex_class(v);
        entity[to] = entity_[v];
    }
    for (int32_t v = 0; v < written.num_vertices(); ++v)
        if (written.vflags[v] & kUnused) cls[v] = VertexClass::Unused;
    cls_ = std::move(cls);
    entity_ = std::move(entity);
    EdgeSet sharp;
    for (EdgeKey k : edited.feature_edges()) {
        const int32_t a = renumber[edge_first(k)], b = renumber[edge_second(k)];
        if (a >= 0 && b >= 0) sharp.insert(edge_key(a, b));
    }
    sharp_ = std::move(sharp);
    std::unordered_map<int32_t, std::vector<int32_t>> corner_regions, corner_chains;
    for (auto& [v, rs] : corner_regions_)
        if (renumber[v] >= 0) corner_regions[renumber[v]] = rs;
    for (auto& [v, cs] : corner_chains_)
        if (renumber[v] >= 0) corner_chains[renumber[v]] = cs;
    corner_regions_ = std::move(corner_regions);
    corner_chains_ = std::move(corner_chains);
    std::unordered_map<FaceKey, int32_t, FaceKeyHash> rim_faces;
    for (const auto& [f, r] : rim_faces_) {
        const int32_t a = renumber[f.v[0]], b = renumber[f.v[1]], c = renumber[f.v[2]];
        if (a >= 0 && b >= 0 && c >= 0) rim_faces[FaceKey::of(a, b, c)] = r;
    }
    rim_faces_ = std::move(rim_faces);
}

}  // namespace bodt
