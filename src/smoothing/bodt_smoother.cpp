#include "smoothing/bodt_smoother.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace bodt {

// The feature line's direction at v: orthogonal to the surface on both of
// its sides, n_a x n_b with n_a, n_b the summed area vectors of the ring
// triangles between the line's two neighbours on either side, so a vertex
// on a curved rim leaves neither face.  Where the two sides are coplanar (a
// line drawn on a flat face) it is the chord between the two neighbours.
Vec3 BodtSmoother::line_direction(const TetMesh& mesh, int32_t v, const std::array<int32_t, 2>& line) {
    const Vec3& x0 = mesh.points[v];
    const Vec3 chord = mesh.points[line[0]] - mesh.points[line[1]];
    const std::vector<int32_t>& ring = first_ring_;  // walked by target() already
    const auto a = std::find(ring.begin(), ring.end(), line[0]);
    const auto b = std::find(ring.begin(), ring.end(), line[1]);
    if (a == ring.end() || b == ring.end()) return chord;
    const size_t m = ring.size(), ia = static_cast<size_t>(a - ring.begin());
    const size_t ib = static_cast<size_t>(b - ring.begin());
    Vec3 side[2] = {Vec3::Zero(), Vec3::Zero()};
    for (size_t i = 0; i < m; ++i) {
        // Triangle (x0, y_i, y_{i+1}) lies on side 0 when i is in [ia, ib) cyclically.
        const bool first = ia < ib ? (i >= ia && i < ib) : (i >= ia || i < ib);
        side[first ? 0 : 1] += (mesh.points[ring[i]] - x0).cross(mesh.points[ring[(i + 1) % m]] - x0);
    }
    const Vec3 d = side[0].cross(side[1]);
    return d.norm() > 1e-6 * side[0].norm() * side[1].norm() ? d : chord;
}

bool BodtSmoother::ascent_basis(const TetMesh& mesh, int32_t v, MoveBasis& basis) {
    const VertexClass c = classes_.cls[v];
    const bool line = c == VertexClass::FeatureLine && classes_.line[v][0] >= 0;
    if (c != VertexClass::Surface && !line) return false;
    const Vec3& x0 = mesh.points[v];
    normals_.clear();
    ring_normals_.clear();
    for (const int32_t* k = surfaces_.begin(v); k != surfaces_.end(v); ++k) {
        std::vector<int32_t>& ring = k == surfaces_.begin(v) ? first_ring_ : ring_;  // as in target()
        surfaces_.surface(*k).one_ring(v, ring);
        FlatPieces pieces(x0);
        Vec3 n = Vec3::Zero();  // the ring normal, as add_ring_triangle sums it
        for (size_t i = 0; i < ring.size(); ++i) {
            const Vec3 &a = mesh.points[ring[i]], &b = mesh.points[ring[(i + 1) % ring.size()]];
            const Vec3 area = 0.5 * (a - x0).cross(b - x0);
            n += area;
            pieces.add(a, b, area);
        }
        if (line) {
            if (pieces.count() > 2) return false;
            normals_.push_back(n);
        } else if (!add_ring_normals(pieces, n) && pieces.count() > 1) {
            return false;  // neither flat nor a crease (along which target() moves v too)
        }
    }
    if (line) {
        const Vec3 a = mesh.points[classes_.line[v][0]] - x0, b = mesh.points[classes_.line[v][1]] - x0;
        if (a.cross(b).norm() > FlatPieces::kFlat * a.norm() * b.norm()) return false;
    }
    return move_basis(mesh, v, basis);
}

// Where the surface around v is faceted, any move off the pieces' common
// line (or a move at all, where three meet at a point) takes v off them and
// the surface off its shape, also at creases below the feature angle (the
// roofs and bevels of `house2` moved by 1.2 % of its size): one normal per
// piece, and the ring's own normal kept aside (move_basis).
bool BodtSmoother::add_ring_normals(const FlatPieces& pieces, const Vec3& n) {
    if (!pieces.faceted(crease_cosine_)) {
        normals_.push_back(n);
        return false;
    }
    normals_.insert(normals_.end(), pieces.normals(), pieces.normals() + pieces.count());
    ring_normals_.push_back(n);
    return true;
}

bool BodtSmoother::move_basis(const TetMesh& mesh, int32_t v, MoveBasis& basis) {
    // The directions that keep every region's volume: the complement of the
    // span of the ring normals (one normal for a boundary or interface
    // vertex, two independent ones where an interface meets the boundary).
    Eigen::Matrix3d span = Eigen::Matrix3d::Zero();
    for (const Vec3& n : normals_) {
        const double len = n.norm();
        if (!(len > 0.0)) return false;
        span += n * n.transpose() / (len * len);
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(span);
    const Vec3 lambda = solver.eigenvalues();  // ascending
    const double floor = 1e-12 * lambda[2];
    const int free_dims = (lambda[0] <= floor) + (lambda[1] <= floor);
    if (free_dims == 0) return false;
    // The tangent-plane normal: a lone ring normal as it is (eq. B.1).
    const auto plane_normal = [this](const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>& s) -> Vec3 {
        return normals_.size() == 1 ? Vec3(normals_[0].normalized()) : Vec3(s.eigenvectors().col(2));
    };

    if (classes_.cls[v] == VertexClass::FeatureLine || free_dims == 1) {
        Vec3 d;
        double whole = 1.0;  // |d| before the projection: the test below is relative, as d scales with the mesh
        if (free_dims == 1) {
            d = solver.eigenvectors().col(0);  // the only free direction
        } else {
            const auto& line = classes_.line[v];
            if (line[0] >= 0) {
                d = line_direction(mesh, v, line);
            } else {
                Vec3 mu;
                Eigen::Matrix3d e;
                tensor_voting(mesh, surfaces_, v, faces_, ring_, mu, e);
                d = e.col(2);  // e2 of eq. (11)
            }
            const Vec3 n = plane_normal(solver);
            whole = d.norm();
            d -= d.dot(n) * n;  // keep the volume: stay in the tangent plane (a no-op for n_a x n_b)
        }
        // Faceted pieces are flat only to FlatPieces::kFlat (an STL's float
        // coordinates): d is also made orthogonal to each such ring's own
        // normal, so that the volume is kept to round-off.
        for (const Vec3& n : ring_normals_) d -= d.dot(n) / n.squaredNorm() * n;
        const double len = d.norm();
        if (!(len > 1e-12 * whole)) return false;
        basis.resize(3, 1);
        basis.col(0) = d / len;
        return true;
    }
    Vec3 s, t;
    tangent_basis(plane_normal(solver), s, t);
    basis.resize(3, 2);
    basis.col(0) = s;
    basis.col(1) = t;
    return true;
}

Plan BodtSmoother::target(const TetMesh& mesh, int32_t v, const StarTable& star, Vec3& target,
                          std::vector<FaceKey>& surface_faces) {
    surface_faces.clear();
    const VertexClass c = classes_.cls[v];
    if (c != VertexClass::Interior && c != VertexClass::Surface && c != VertexClass::FeatureLine) return Plan::Stay;

    const Vec3& x0 = mesh.points[v];
    StarModel model;
    add_star(model, star, x0, terms_);
    if (c == VertexClass::Interior) {
        // Algorithm 1, eq. (3): x* = x0 - 1/(2|Omega_0|) sum (1/3) S n L = x0 - 2 g / |Omega_0|.
        if (!(model.volume > 0.0)) return Plan::NotPositiveDefinite;
        target = x0 - (2.0 / model.volume) * model.g;
        return move_unless_converged(target - x0, model);
    }

    normals_.clear();
    ring_normals_.clear();
    for (const int32_t* k = surfaces_.begin(v); k != surfaces_.end(v); ++k) {
        // The first surface's ring is kept for line_direction.
        std::vector<int32_t>& ring = k == surfaces_.begin(v) ? first_ring_ : ring_;
        surfaces_.surface(*k).one_ring(v, ring);
        Vec3 n = Vec3::Zero();
        FlatPieces pieces(x0);
        const bool creases = crease_cosine_ >= 0.0;  // else none is faceted
        const size_t m = ring.size();
        for (size_t i = 0; i < m; ++i) {
            const int32_t a = ring[i], b = ring[(i + 1) % m];
            const Vec3 area = add_ring_triangle(model, x0, mesh.points[a], mesh.points[b]);
            n += area;
            if (creases) pieces.add(mesh.points[a], mesh.points[b], area);
            surface_faces.push_back(FaceKey::of(v, a, b));
        }
        add_ring_normals(pieces, n);
    }
    std::sort(surface_faces.begin(), surface_faces.end());
    surface_faces.erase(std::unique(surface_faces.begin(), surface_faces.end()), surface_faces.end());

    MoveBasis basis;
    if (!move_basis(mesh, v, basis)) return Plan::Stay;
    Vec3 move;
    if (!minimize_on(model, basis, move)) return Plan::NotPositiveDefinite;
    target = x0 + move;
    return move_unless_converged(move, model);
}

// The fixed-point iteration converges geometrically: without this, vertices
// go on moving by round-off for ever, and every such move makes the
// vertices and bad tets around them be tried again (SettledVertices,
// StuckTets).  Relative to the star, so a fine part of a graded mesh is
// smoothed as a coarse one is.
Plan BodtSmoother::move_unless_converged(const Vec3& move, const StarModel& model) const {
    return move.norm() <= tolerance_ * std::cbrt(model.volume) ? Plan::Stay : Plan::Move;
}

std::vector<int32_t> BodtSmoother::read_differently(const VertexClasses& before, const RegionSurfaces& surfaces_before,
                                                    const VertexClasses& after, const RegionSurfaces& surfaces_after) {
    std::vector<int32_t> out, ring_before, ring_after;
    for (int32_t v = 0; v < static_cast<int32_t>(before.cls.size()); ++v) {
        bool same = before.cls[v] == after.cls[v] && before.line[v] == after.line[v];
        // Only a surface or feature-line vertex reads its rings (target()).
        const bool rings = before.cls[v] == VertexClass::Surface || before.cls[v] == VertexClass::FeatureLine;
        same = same && (!rings || std::equal(surfaces_before.begin(v), surfaces_before.end(v), surfaces_after.begin(v),
                                             surfaces_after.end(v)));
        for (const int32_t* k = surfaces_before.begin(v); same && rings && k != surfaces_before.end(v); ++k) {
            surfaces_before.surface(*k).one_ring(v, ring_before);
            surfaces_after.surface(*k).one_ring(v, ring_after);
            same = ring_before == ring_after;
        }
        if (!same) out.push_back(v);
    }
    return out;
}

}  // namespace bodt
