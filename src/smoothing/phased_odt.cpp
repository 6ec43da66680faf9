#include "smoothing/phased_odt.hpp"

#include <algorithm>
#include <cmath>

namespace bodt {

namespace {

// The angle from a to b, in (-pi, pi].
double turn(double a, double b) {
    double d = b - a;
    while (d > M_PI) d -= 2.0 * M_PI;
    while (d <= -M_PI) d += 2.0 * M_PI;
    return d;
}

// Circumcentre of a triangle in its plane (2-D points work with z = 0).
Vec3 triangle_circumcenter(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a;
    const Vec3 n = ab.cross(ac);
    return a + (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (2.0 * n.squaredNorm());
}

// The vertex opposite edge (a, b) in the other surface face on it; -1 if
// there is none or the edge is sharp (no Delaunay test across a border).
int32_t across(const TetMesh& mesh, const GeometryModel& g, int32_t a, int32_t b, int32_t c) {
    if (g.sharp_edges().count(edge_key(a, b))) return -1;
    for (const int32_t* t = mesh.star_begin(a); t != mesh.star_end(a); ++t) {
        const Tet& q = mesh.tets[*t];
        if (!holds(q, b)) continue;
        for (int i = 0; i < 4; ++i) {
            if (q[i] == a || q[i] == b || !mesh.is_surface_face(*t, i)) continue;
            for (int k = 0; k < 3; ++k) {
                const int32_t d = q[kFaceVertex[i][k]];
                if (d != a && d != b && d != c) return d;
            }
        }
    }
    return -1;
}

// Locally Delaunay across each inner edge: the angles opposite the edge in
// its two triangles sum to at most pi.
bool triangle_delaunay(const TetMesh& mesh, const GeometryModel& g, const FaceKey& f) {
    for (int i = 0; i < 3; ++i) {
        const int32_t a = f.v[i], b = f.v[(i + 1) % 3], c = f.v[(i + 2) % 3];
        const int32_t d = across(mesh, g, a, b, c);
        if (d < 0) continue;
        if (edge_not_delaunay(mesh.points[a], mesh.points[b], mesh.points[c], mesh.points[d])) return false;
    }
    return true;
}

bool on_region_border(const GeometryModel& g, const FaceKey& f) {
    for (int32_t v : f.v)
        if (g.vertex_class(v) != VertexClass::Surface) return true;
    return false;
}

}  // namespace

Vec3 PlannedMove::at(double f) const {
    if (!curved) {
        return start + f * (target - start);
    }
    return curved->at(theta0 + f * (theta1 - theta0), z0 + f * (z1 - z0));
}

bool locally_delaunay(const TetMesh& mesh, int32_t t) {
    const TetPoints p = mesh.tet_points(t);
    for (int i = 0; i < 4; ++i) {
        const int32_t s = mesh.neighbors[t][i];
        if (s < 0) continue;
        const Tet& q = mesh.tets[s];
        for (int32_t x : q)
            if (!holds(mesh.tets[t], x) &&
                in_circumsphere(p, mesh.points[x]))
                return false;
    }
    return true;
}

void PhasedOdt::gather_faces(const TetMesh& mesh, int32_t v) {
    faces_.clear();
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
        for (int i = 0; i < 4; ++i) {
            const Tet& q = mesh.tets[*t];
            if (q[i] == v || !mesh.is_surface_face(*t, i)) continue;
            faces_.push_back(FaceKey::of(q[kFaceVertex[i][0]], q[kFaceVertex[i][1]], q[kFaceVertex[i][2]]));
        }
    std::sort(faces_.begin(), faces_.end());
    faces_.erase(std::unique(faces_.begin(), faces_.end()), faces_.end());
}

// Sec. 3.4.2: CPT on a line (eq. 3.4 with the edge midpoints, weighted by
// length), eq. (3.4) on the central angle on an arc or circle.
bool PhasedOdt::chain_move(const TetMesh& mesh, int32_t v, PlannedMove& move) {
    if (geometry_.vertex_class(v) != VertexClass::FeatureLine || (mesh.vflags[v] & kPinned)) return false;
    const Shape* shape = geometry_.shape_of(v);
    if (!shape) return false;
    scratch_.clear();
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
        for (int32_t u : mesh.tets[*t])
            if (u != v && geometry_.sharp_edges().count(edge_key(u, v))) scratch_.push_back(u);
    std::sort(scratch_.begin(), scratch_.end());
    scratch_.erase(std::unique(scratch_.begin(), scratch_.end()), scratch_.end());
    if (scratch_.size() != 2) return false;
    gather_faces(mesh, v);
    const Vec3& x = mesh.points[v];
    move = PlannedMove{x, x};
    if (shape->type == ShapeType::Line) {
        Vec3 sum = Vec3::Zero();
        double total = 0.0;
        for (int32_t u : scratch_) {
            const double l = (mesh.points[u] - x).norm();
            sum += l * 0.5 * (x + mesh.points[u]);
            total += l;
        }
        if (!(total > 0.0)) return false;
        move.target = shape->project((1.0 - alpha_) * x + alpha_ * sum / total);
        return true;
    }
    const double theta = shape->angle(x);
    double sum = 0.0, total = 0.0;
    for (int32_t u : scratch_) {
        const double d = turn(theta, shape->angle(mesh.points[u]));
        sum += std::abs(d) * 0.5 * d;
        total += std::abs(d);
    }
    if (!(total > 0.0)) return false;
    move.curved = shape;
    move.theta0 = theta;
    move.theta1 = theta + alpha_ * sum / total;
    move.target = move.at(1.0);
    return true;
}

// Sec. 3.4.3: 2-D ODT on a plane, or in the development of a cylinder
// around x's own angle (so the seam never cuts a star).
bool PhasedOdt::surface_move(const TetMesh& mesh, int32_t v, PlannedMove& move) {
    if (geometry_.vertex_class(v) != VertexClass::Surface || (mesh.vflags[v] & kPinned)) return false;
    const Shape* shape = geometry_.shape_of(v);
    if (!shape || (shape->type != ShapeType::Plane && shape->type != ShapeType::Cylinder)) return false;
    gather_faces(mesh, v);
    if (faces_.empty()) return false;
    const Vec3& x = mesh.points[v];
    const bool cylinder = shape->type == ShapeType::Cylinder;
    const double theta = cylinder ? shape->angle(x) : 0.0;
    // A point in the 2-D frame: the development for a cylinder, the
    // points themselves (coplanar) for a plane.
    const auto flat = [&](const Vec3& p) -> Vec3 {
        if (!cylinder) return p;
        return Vec3(shape->radius * turn(theta, shape->angle(p)), shape->height(p), 0.0);
    };
    Vec3 sum = Vec3::Zero();
    double total = 0.0;
    for (const FaceKey& f : faces_) {
        const Vec3 a = flat(mesh.points[f.v[0]]), b = flat(mesh.points[f.v[1]]), c = flat(mesh.points[f.v[2]]);
        const double area = 0.5 * (b - a).cross(c - a).norm();
        const bool bary = on_region_border(geometry_, f) || !triangle_delaunay(mesh, geometry_, f);
        const Vec3 centre = bary ? Vec3((a + b + c) / 3.0) : triangle_circumcenter(a, b, c);
        if (!centre.allFinite()) return false;
        sum += area * centre;
        total += area;
    }
    if (!(total > 0.0)) return false;
    const Vec3 mean = sum / total;
    move = PlannedMove{x, x};
    if (!cylinder) {
        move.target = shape->project((1.0 - alpha_) * x + alpha_ * mean);
        return true;
    }
    const Vec3 here = flat(x);  // (0, z)
    move.curved = shape;
    move.theta0 = theta;
    move.theta1 = theta + alpha_ * mean.x() / shape->radius;
    move.z0 = here.y();
    move.z1 = here.y() + alpha_ * (mean.y() - here.y());
    move.target = move.at(1.0);
    return true;
}

// Sec. 3.4.4: 3-D ODT with circumcentres, barycentres near the surface and
// for tets that are not Delaunay.
bool PhasedOdt::interior_move(const TetMesh& mesh, int32_t v, PlannedMove& move) {
    if (geometry_.vertex_class(v) != VertexClass::Interior || !mesh.is_interior_free(v)) return false;
    Vec3 sum = Vec3::Zero();
    double total = 0.0;
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t) {
        const TetPoints p = mesh.tet_points(*t);
        const double vol = signed_volume(p[0], p[1], p[2], p[3]);
        if (!(vol > 0.0)) return false;
        bool bary = !locally_delaunay(mesh, *t);
        for (int32_t u : mesh.tets[*t]) bary = bary || !mesh.is_interior_free(u);
        const Vec3 centre = bary ? Vec3((p[0] + p[1] + p[2] + p[3]) / 4.0) : circumcenter(p);
        if (!centre.allFinite()) return false;
        sum += vol * centre;
        total += vol;
    }
    if (!(total > 0.0)) return false;
    const Vec3& x = mesh.points[v];
    move = PlannedMove{x, (1.0 - alpha_) * x + alpha_ * sum / total};
    return true;
}

}  // namespace bodt
