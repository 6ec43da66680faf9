// test_phased: white-box tests of paper 002's phased mode (links bodt_core):
// the three ODT phases of PhasedOdt (sec. 3.4.2 - 3.4.4), applied through a
// MoveGuard with the path-following backtracking of sweep_phased, and the
// connectivity changes of PhasedTopology (sec. 3.4.3, 3.5) on small meshes
// built here.  Expected values are the test's own arithmetic.
//
//   chain_line        a box edge whose three inner vertices were slid along
//                     it: CPT (alpha = 1) rounds leave them evenly spaced
//                     (1e-6 relative) and on the line (1e-12) all the way
//   chain_circle      the top circle of a box with a hole, its vertices
//                     turned along it: every vertex of a Circle chain stays
//                     on its fitted circle (1e-9 relative) after every
//                     round; the angle gaps end equal (1e-6 relative)
//   surface_cylinder  the hole's inner vertices moved along the cylinder
//                     (angle and height): surface moves keep them on the
//                     fitted cylinder (1e-9 relative) after every round;
//                     the spread and RMS deviation of the angle gaps and the
//                     height offsets shrink (without flips even spacing is
//                     no fixed point: see the test)
//   surface_plane     the top face of a box jittered in its plane: surface
//                     moves keep it in the plane (1e-12) and raise its
//                     smallest triangle angle by 5 degrees or more
//   interior          a jittered box: interior moves raise the smallest
//                     dihedral angle, the volume stays
//   untangle          a box with an interior vertex pushed out of its star
//                     (inverted tets, accepted): remove_inverted leaves no
//                     tet with stretch <= 0, the volume and the boundary
//                     faces as they were
//   degenerate_sliver, _cap, _spade  the small meshes of test_topology:
//                     remove_degenerate removes the bad tet, the mesh stays
//                     valid with the same volume and boundary area, and no
//                     tet is left below the bad angle (15 degrees)
//   density_split     a uniform box and a grid wanting half the edge length:
//                     recover splits, edges get shorter, the box's faces
//                     stay flat, nothing inverts
//   density_collapse  a grid wanting 3.3 times the edge length, collapses
//                     only: recover collapses, corners stay where they are,
//                     an edge between two corners is never collapsed (a
//                     single cube does not change at all), nothing inverts
//   surface_flip      a box's top-face vertex moved so that a face edge's
//                     opposite angles sum past pi: flip_surface flips that
//                     edge (fewer non-Delaunay top edges), the faces stay in
//                     the box's planes, volume and area stay
#include "common/error.hpp"
#include "features/geometry_model.hpp"
#include "features/shape_fit.hpp"
#include "features/vertex_classes.hpp"
#include "mesh/mesh_builder.hpp"
#include "mesh/tet_mesh.hpp"
#include "pipeline/density_field.hpp"
#include "quality/tet_geometry.hpp"
#include "smoothing/move_guard.hpp"
#include "smoothing/phased_odt.hpp"
#include "topology/editable_mesh.hpp"
#include "topology/phased_topology.hpp"

#include "bodt.h"
#include "mesh_gen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include "test_util.h"
#include "core_checks.hpp"

namespace {

using bodt::EditableMesh;
using bodt::FaceKey;
using bodt::GeometryModel;
using bodt::PhasedOdt;
using bodt::PlannedMove;
using bodt::Shape;
using bodt::ShapeType;
using bodt::Tet;
using bodt::TetMesh;
using bodt::Vec3;
using bodt::VertexClass;

constexpr double kPi = M_PI;
constexpr double kDeg = 180.0 / M_PI;

// ------------------------------------------------------------------ inputs

struct Arrays {
    std::vector<double> xyz;
    std::vector<int32_t> tets;

    Vec3 point(int32_t v) const { return Vec3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]); }
    void set(int32_t v, const Vec3& p) {
        for (int a = 0; a < 3; ++a) xyz[3 * v + a] = p[a];
    }
    int32_t nverts() const { return static_cast<int32_t>(xyz.size() / 3); }
};

Arrays arrays_of(test_mesh& m) {
    Arrays a;
    a.xyz.assign(m.xyz, m.xyz + 3 * m.nverts);
    a.tets.assign(m.tets, m.tets + 4 * m.ntets);
    tm_free(&m);
    return a;
}

Arrays box(int n) {
    test_mesh m{};
    if (tm_make_box(&m, n, 0.0, 1) != 0) fail_msg("tm_make_box(%d)", n);
    return arrays_of(m);
}

Arrays jittered_box(int n, double jitter, uint64_t seed) {
    test_mesh m{};
    if (tm_make_box(&m, n, jitter, seed) != 0) fail_msg("tm_make_box(%d, %g)", n, jitter);
    return arrays_of(m);
}

// Vertex (i, j, k) of tm_make_box(n).
int32_t grid_vertex(int n, int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; }

// The box with a hole of tm_make_box_with_hole.
struct Hole {
    int nr = 2, nt = 16, nz = 2;
    double half_width = 1.0, radius = 0.5, height = 1.0;
    int32_t vertex(int ring, int angle, int layer) const { return (layer * (nr + 1) + ring) * nt + angle; }
    double theta(int angle) const { return -kPi / 4 + 2 * kPi * angle / nt; }
    Arrays make() const {
        test_mesh m{};
        if (tm_make_box_with_hole(&m, nr, nt, nz, half_width, radius, height) != 0) fail_msg("tm_make_box_with_hole");
        return arrays_of(m);
    }
};

// The arrays built into a TetMesh (inverted tets accepted with `flags`),
// inverted tets in the order of their neighbours as the phased step has it.
TetMesh build(const Arrays& a, uint32_t flags = 0) {
    bodt::MeshArrays in;
    in.nverts = a.nverts();
    in.xyz = a.xyz.data();
    in.ntets = static_cast<int32_t>(a.tets.size() / 4);
    in.tets = a.tets.data();
    in.flags = flags;
    TetMesh mesh;
    try {
        bodt::BuiltMesh b = bodt::build_mesh(in);
        if (b.flipped) fail_msg("the test mesh came out negatively oriented");
        mesh = std::move(b.mesh);
        for (size_t t = 0; t < mesh.reversed.size(); ++t)
            if (mesh.reversed[t]) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
        mesh.reversed.clear();
    } catch (const bodt::Error& e) {
        fail_msg("building the test mesh: %s", e.what());
    }
    return mesh;
}

GeometryModel extract(const TetMesh& mesh) { return GeometryModel::extract(mesh, bodt::GeometrySettings{}); }

// The written mesh with its topology built (throws on a broken mesh).
TetMesh written(const EditableMesh& em) {
    TetMesh m;
    em.write_to(m);
    try {
        m.build_topology(0);
    } catch (const bodt::Error& e) {
        fail_msg("the written mesh is broken: %s", e.what());
    }
    return m;
}

// ----------------------------------------------------------- measurements

int32_t count_not_positive(const TetMesh& m) {
    int32_t n = 0;
    for (int32_t t = 0; t < m.num_tets(); ++t) n += !(bodt::stretch(m.tet_points(t)) > 0.0);
    return n;
}

double min_dihedral(const TetMesh& m) {
    double lo = 180.0;
    for (int32_t t = 0; t < m.num_tets(); ++t) {
        const auto p = m.tet_points(t);
        const bool positive = bodt::orient(p[0], p[1], p[2], p[3]).sign > 0;
        lo = std::min(lo, bodt::dihedral_range(p, positive).min);
    }
    return lo;
}

// Tets whose worst dihedral angle is below `deg` or above 180 - `deg`.
int32_t count_bad(const TetMesh& m, double deg) {
    int32_t n = 0;
    for (int32_t t = 0; t < m.num_tets(); ++t) {
        const auto p = m.tet_points(t);
        const bool positive = bodt::orient(p[0], p[1], p[2], p[3]).sign > 0;
        const bodt::AngleRange r = bodt::dihedral_range(p, positive);
        n += r.min < deg || r.max > 180.0 - deg;
    }
    return n;
}

// The faces of one tet, by vertex indices.
std::set<FaceKey> boundary_faces(const TetMesh& m) {
    std::set<FaceKey> once, twice;
    for (const Tet& q : m.tets)
        for (const auto& f : bodt::kFaceVertex) {
            const FaceKey k = FaceKey::of(q[f[0]], q[f[1]], q[f[2]]);
            if (!once.insert(k).second) twice.insert(k);
        }
    std::set<FaceKey> out;
    for (const FaceKey& k : once)
        if (!twice.count(k)) out.insert(k);
    return out;
}

double boundary_area(const TetMesh& m) {
    double a = 0.0;
    for (const FaceKey& f : boundary_faces(m))
        a += 0.5 * (m.points[f.v[1]] - m.points[f.v[0]]).cross(m.points[f.v[2]] - m.points[f.v[0]]).norm();
    return a;
}

std::vector<std::array<int32_t, 2>> edges_of(const TetMesh& m) {
    std::vector<std::array<int32_t, 2>> out;
    for (const Tet& q : m.tets)
        for (const auto& e : bodt::kEdgeVertex) out.push_back({std::min(q[e[0]], q[e[1]]), std::max(q[e[0]], q[e[1]])});
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

struct EdgeStats {
    double mean = 0.0, max = 0.0;
    size_t count = 0;
};

EdgeStats edge_stats(const TetMesh& m) {
    EdgeStats s;
    for (const auto& e : edges_of(m)) {
        const double l = (m.points[e[0]] - m.points[e[1]]).norm();
        s.mean += l;
        s.max = std::max(s.max, l);
        ++s.count;
    }
    if (s.count) s.mean /= static_cast<double>(s.count);
    return s;
}

double angle_at(const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 a = q - p, b = r - p;
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

// The smallest angle of the boundary triangles whose three vertices satisfy `in`.
template <class In>
double min_face_angle(const TetMesh& m, In in) {
    double lo = kPi;
    for (const FaceKey& f : boundary_faces(m)) {
        const Vec3 &a = m.points[f.v[0]], &b = m.points[f.v[1]], &c = m.points[f.v[2]];
        if (!in(a) || !in(b) || !in(c)) continue;
        lo = std::min({lo, angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)});
    }
    return lo;
}

// Gaps between consecutive angles of a closed ring (in ring order), in
// (0, 2 pi); their spread max - min.
double gap_spread(const std::vector<double>& angles, double* mean = nullptr) {
    double lo = 1e300, hi = -1e300, sum = 0.0;
    for (size_t i = 0; i < angles.size(); ++i) {
        double g = angles[(i + 1) % angles.size()] - angles[i];
        while (g <= 0.0) g += 2 * kPi;
        while (g > 2 * kPi) g -= 2 * kPi;
        lo = std::min(lo, g);
        hi = std::max(hi, g);
        sum += g;
    }
    if (mean) *mean = sum / static_cast<double>(angles.size());
    return hi - lo;
}

// --------------------------------------------------------------- smoothing

struct Sweep {
    int moved = 0, shortened = 0, rejected = 0;
};

// One move as sweep_phased makes it: the full move, then along the planned
// path (on the circle or cylinder) halved up to four times, each through the
// guard; surface faces of the vertex are watched in phases 1 and 2.
void apply(TetMesh& mesh, bodt::MoveGuard& guard, int32_t v, const PlannedMove& move,
           const std::vector<FaceKey>& faces, Sweep& sweep) {
    double f = 1.0, distance = 0.0;
    for (int attempt = 0; attempt <= 4; ++attempt, f *= 0.5)
        if (guard.move(mesh, v, move.at(f), faces, distance) != bodt::MoveOutcome::Rejected) {
            ++(attempt == 0 ? sweep.moved : sweep.shortened);
            return;
        }
    ++sweep.rejected;
}

bodt::MoveGuard make_guard() { return bodt::MoveGuard({1e-3, 0, false}); }

// ------------------------------------------------------------------ phase 1

void test_chain_line(void**) {
    const char* what = "chain_line";
    const int n = 4;
    Arrays a = box(n);
    // The box edge y = z = 0: corners (0, 0, 0) and (1, 0, 0), vertices
    // 1, 2, 3 between them slid along it.
    const int32_t chain[5] = {grid_vertex(n, 0, 0, 0), grid_vertex(n, 1, 0, 0), grid_vertex(n, 2, 0, 0),
                              grid_vertex(n, 3, 0, 0), grid_vertex(n, 4, 0, 0)};
    const double slid[3] = {0.10, 0.58, 0.64};
    for (int i = 0; i < 3; ++i) a.set(chain[i + 1], Vec3(slid[i], 0.0, 0.0));
    TetMesh mesh = build(a);
    const GeometryModel g = extract(mesh);
    CHECK(g.vertex_class(chain[0]) == VertexClass::Corner && g.vertex_class(chain[4]) == VertexClass::Corner,
          "the edge's ends are not corners");
    const int32_t id = g.entity(chain[1]);
    for (int i = 1; i < 4; ++i) {
        CHECK(g.vertex_class(chain[i]) == VertexClass::FeatureLine && g.entity(chain[i]) == id, "vertex %d", chain[i]);
        CHECK(g.shape_of(chain[i]) && g.shape_of(chain[i])->type == ShapeType::Line, "vertex %d: no line", chain[i]);
    }
    const Shape line = *g.shape_of(chain[1]);

    PhasedOdt odt(g, 1.0);
    bodt::MoveGuard guard = make_guard();
    Sweep sweep;
    int planned = 0;
    for (int round = 0; round < 60; ++round) {
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            if (g.vertex_class(v) != VertexClass::FeatureLine || g.entity(v) != id) continue;
            PlannedMove move;
            if (!odt.chain_move(mesh, v, move)) continue;
            ++planned;
            CHECK(move.curved == nullptr, "a move on a line follows a curve");
            apply(mesh, guard, v, move, odt.faces(), sweep);
        }
        for (int i = 1; i < 4; ++i) {
            const Vec3& p = mesh.points[chain[i]];
            CHECK(std::fabs(p.y()) <= 1e-12 && std::fabs(p.z()) <= 1e-12, "round %d: vertex %d off the edge: %.3g %.3g",
                  round, chain[i], p.y(), p.z());
            CHECK(line.distance(p) <= 1e-12, "round %d: vertex %d %.3g from the fitted line", round, chain[i],
                  line.distance(p));
        }
    }
    CHECK(planned == 60 * 3, "%d moves planned", planned);
    CHECK(sweep.rejected == 0, "%d moves rejected", sweep.rejected);
    for (int i = 0; i < 4; ++i) {
        const double gap = mesh.points[chain[i + 1]].x() - mesh.points[chain[i]].x();
        CHECK(std::fabs(gap - 0.25) <= 1e-6 * 0.25, "gap %d: %.17g, expected 0.25", i, gap);
    }
    CHECK(count_not_positive(mesh) == 0, "inverted tets");
    assert_near(total_volume(mesh), 1.0, 1e-12);
    print_message("chain_line: %d moves (%d shortened), gaps even\n", sweep.moved + sweep.shortened, sweep.shortened);
}

void test_chain_circle(void**) {
    const char* what = "chain_circle";
    const Hole h;
    Arrays a = h.make();
    // The top circle's vertices turned along it by up to 0.3 of the spacing.
    tm_rng rng;
    tm_rng_seed(&rng, 7);
    const double step = 2 * kPi / h.nt;
    for (int j = 0; j < h.nt; ++j) {
        const double t = h.theta(j) + (2.0 * tm_rng_uniform(&rng) - 1.0) * 0.3 * step;
        a.set(h.vertex(0, j, h.nz), Vec3(h.radius * std::cos(t), h.radius * std::sin(t), h.height));
    }
    TetMesh mesh = build(a);
    const GeometryModel g = extract(mesh);
    const int32_t top = h.vertex(0, 0, h.nz);
    CHECK(g.vertex_class(top) == VertexClass::FeatureLine, "the top ring is class %d", static_cast<int>(g.vertex_class(top)));
    const Shape* circle = g.shape_of(top);
    CHECK(circle && circle->type == ShapeType::Circle, "the top ring is no Circle chain");
    CHECK(std::fabs(circle->radius - h.radius) <= 1e-9 * h.radius, "fitted radius %.17g", circle->radius);
    std::vector<int32_t> ring;
    for (int j = 0; j < h.nt; ++j) {
        ring.push_back(h.vertex(0, j, h.nz));
        CHECK(g.entity(ring.back()) == g.entity(top), "vertex %d on another chain", ring.back());
    }
    const auto angles = [&]() {
        std::vector<double> out;
        for (int32_t v : ring) out.push_back(circle->angle(mesh.points[v]));
        return out;
    };
    double mean = 0.0;
    const double spread0 = gap_spread(angles(), &mean);

    PhasedOdt odt(g, 1.0);
    bodt::MoveGuard guard = make_guard();
    Sweep sweep;
    for (int round = 0; round < 150; ++round) {
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            const Shape* s = g.shape_of(v);
            if (g.vertex_class(v) != VertexClass::FeatureLine || !s || s->type != ShapeType::Circle) continue;
            PlannedMove move;
            if (!odt.chain_move(mesh, v, move)) continue;
            CHECK(move.curved == s, "vertex %d: the move does not follow its circle", v);
            apply(mesh, guard, v, move, odt.faces(), sweep);
        }
        // Every vertex of every Circle chain on its circle, after every round.
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            const Shape* s = g.shape_of(v);
            if (g.vertex_class(v) != VertexClass::FeatureLine || !s || s->type != ShapeType::Circle) continue;
            CHECK(s->distance(mesh.points[v]) <= 1e-9 * s->radius, "round %d: vertex %d %.3g from its circle", round, v,
                  s->distance(mesh.points[v]));
        }
    }
    const double spread = gap_spread(angles(), &mean);
    print_message("chain_circle: %d moves (%d shortened, %d rejected), gap spread %.3g -> %.3g rad\n",
                  sweep.moved + sweep.shortened, sweep.shortened, sweep.rejected, spread0, spread);
    CHECK(spread0 > 0.2 * step, "the perturbation is too small: %g", spread0);
    CHECK(std::fabs(mean - step) <= 1e-12, "mean gap %.17g", mean);
    CHECK(spread <= 1e-6 * step, "gap spread %.3g of %.3g", spread, step);
    CHECK(count_not_positive(mesh) == 0, "inverted tets");
}

// ------------------------------------------------------------------ phase 2

// Without the flips of the phased step the Kuhn diagonals stay: even
// spacing is no fixed point here (a border layer's triangles take
// barycentres, and the diagonals of an even grid sit on the Delaunay switch
// between circumcentre and barycentre), so the gaps even out but do not
// become equal.
void test_surface_cylinder(void**) {
    const char* what = "surface_cylinder";
    Hole h;
    h.nz = 3;
    Arrays a = h.make();
    tm_rng rng;
    tm_rng_seed(&rng, 11);
    const double step = 2 * kPi / h.nt, dz = h.height / h.nz;
    for (int k = 1; k < h.nz; ++k)
        for (int j = 0; j < h.nt; ++j) {
            const double t = h.theta(j) + (2.0 * tm_rng_uniform(&rng) - 1.0) * 0.3 * step;
            const double z = k * dz + (2.0 * tm_rng_uniform(&rng) - 1.0) * 0.2 * dz;
            a.set(h.vertex(0, j, k), Vec3(h.radius * std::cos(t), h.radius * std::sin(t), z));
        }
    TetMesh mesh = build(a);
    const GeometryModel g = extract(mesh);
    const int32_t probe = h.vertex(0, 0, 1);
    CHECK(g.vertex_class(probe) == VertexClass::Surface, "a hole vertex is class %d", static_cast<int>(g.vertex_class(probe)));
    const Shape* cyl = g.shape_of(probe);
    CHECK(cyl && cyl->type == ShapeType::Cylinder, "the hole is no cylinder");
    CHECK(std::fabs(cyl->radius - h.radius) <= 1e-9 * h.radius, "fitted radius %.17g", cyl->radius);
    CHECK(std::fabs(std::fabs(cyl->axis.z()) - 1.0) <= 1e-9, "fitted axis %g %g %g", cyl->axis.x(), cyl->axis.y(), cyl->axis.z());

    // Over the inner layers: the spread of the angle gaps, their RMS
    // deviation from the even gap, the largest height offset from the
    // layer's mean height.
    struct Evenness {
        double spread = 0.0, rms = 0.0, height = 0.0;
    };
    const auto evenness = [&]() {
        Evenness e;
        for (int k = 1; k < h.nz; ++k) {
            std::vector<double> angles;
            double zmean = 0.0;
            for (int j = 0; j < h.nt; ++j) {
                angles.push_back(cyl->angle(mesh.points[h.vertex(0, j, k)]));
                zmean += cyl->height(mesh.points[h.vertex(0, j, k)]) / h.nt;
            }
            e.spread = std::max(e.spread, gap_spread(angles));
            for (int j = 0; j < h.nt; ++j) {
                double gap = angles[(j + 1) % h.nt] - angles[j];
                while (gap <= 0.0) gap += 2 * kPi;
                while (gap > 2 * kPi) gap -= 2 * kPi;
                e.rms += (gap - step) * (gap - step);
                e.height = std::max(e.height, std::fabs(cyl->height(mesh.points[h.vertex(0, j, k)]) - zmean));
            }
        }
        e.rms = std::sqrt(e.rms / (h.nt * (h.nz - 1)));
        return e;
    };
    const Evenness e0 = evenness();

    PhasedOdt odt(g, 1.0);
    bodt::MoveGuard guard = make_guard();
    Sweep sweep;
    for (int round = 0; round < 60; ++round) {
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            if (g.shape_of(v) != cyl || g.vertex_class(v) != VertexClass::Surface) continue;
            PlannedMove move;
            if (!odt.surface_move(mesh, v, move)) continue;
            CHECK(move.curved == cyl, "vertex %d: the move does not follow the cylinder", v);
            apply(mesh, guard, v, move, odt.faces(), sweep);
        }
        for (int32_t v = 0; v < mesh.num_vertices(); ++v)
            if (g.shape_of(v) == cyl)
                CHECK(cyl->distance(mesh.points[v]) <= 1e-9 * cyl->radius, "round %d: vertex %d %.3g from the cylinder",
                      round, v, cyl->distance(mesh.points[v]));
    }
    const Evenness e1 = evenness();
    print_message("surface_cylinder: %d moves (%d shortened, %d rejected); angle gaps: spread %.3g -> %.3g, RMS "
                  "deviation %.3g -> %.3g rad; height offset %.3g -> %.3g\n",
                  sweep.moved + sweep.shortened, sweep.shortened, sweep.rejected, e0.spread, e1.spread, e0.rms, e1.rms,
                  e0.height, e1.height);
    CHECK(sweep.moved > 0, "nothing moved");
    CHECK(e1.spread < 0.6 * e0.spread, "angle gap spread %.3g -> %.3g", e0.spread, e1.spread);
    CHECK(e1.rms < 0.4 * e0.rms, "RMS gap deviation %.3g -> %.3g", e0.rms, e1.rms);
    CHECK(e1.height < 0.5 * e0.height, "height offset %.3g -> %.3g", e0.height, e1.height);
    CHECK(count_not_positive(mesh) == 0, "inverted tets");
}

void test_surface_plane(void**) {
    const char* what = "surface_plane";
    const int n = 4;
    const double hh = 1.0 / n;
    Arrays a = box(n);
    tm_rng rng;
    tm_rng_seed(&rng, 5);
    for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) {
            const int32_t v = grid_vertex(n, i, j, n);
            const Vec3 p = a.point(v);
            a.set(v, Vec3(p.x() + (2.0 * tm_rng_uniform(&rng) - 1.0) * 0.3 * hh,
                          p.y() + (2.0 * tm_rng_uniform(&rng) - 1.0) * 0.3 * hh, 1.0));
        }
    TetMesh mesh = build(a);
    const GeometryModel g = extract(mesh);
    const int32_t probe = grid_vertex(n, 2, 2, n);
    CHECK(g.vertex_class(probe) == VertexClass::Surface, "the top face's middle is class %d",
          static_cast<int>(g.vertex_class(probe)));
    const Shape* plane = g.shape_of(probe);
    CHECK(plane && plane->type == ShapeType::Plane, "the top face is no plane");
    const int32_t region = g.entity(probe);
    const auto on_top = [](const Vec3& p) { return std::fabs(p.z() - 1.0) <= 1e-9; };
    const double before = min_face_angle(mesh, on_top);

    PhasedOdt odt(g, 1.0);
    bodt::MoveGuard guard = make_guard();
    Sweep sweep;
    for (int round = 0; round < 30; ++round) {
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            if (g.vertex_class(v) != VertexClass::Surface || g.entity(v) != region) continue;
            PlannedMove move;
            if (!odt.surface_move(mesh, v, move)) continue;
            CHECK(move.curved == nullptr, "a move in a plane follows a curve");
            apply(mesh, guard, v, move, odt.faces(), sweep);
        }
        for (int j = 1; j < n; ++j)
            for (int i = 1; i < n; ++i) {
                const Vec3& p = mesh.points[grid_vertex(n, i, j, n)];
                CHECK(std::fabs(p.z() - 1.0) <= 1e-12, "round %d: vertex (%d, %d) at z = %.17g", round, i, j, p.z());
            }
    }
    const double after = min_face_angle(mesh, on_top);
    print_message("surface_plane: %d moves (%d shortened, %d rejected), smallest face angle %.2f -> %.2f degrees\n",
                  sweep.moved + sweep.shortened, sweep.shortened, sweep.rejected, before * kDeg, after * kDeg);
    CHECK(after > before + 5.0 / kDeg, "smallest face angle %.2f -> %.2f degrees", before * kDeg, after * kDeg);
    CHECK(count_not_positive(mesh) == 0, "inverted tets");
    assert_near(total_volume(mesh), 1.0, 1e-12);
}

// ------------------------------------------------------------------ phase 3

void test_interior(void**) {
    const char* what = "interior";
    TetMesh mesh = build(jittered_box(4, 0.35, 3));
    const GeometryModel g = extract(mesh);
    const double before = min_dihedral(mesh);
    PhasedOdt odt(g, 1.0);
    bodt::MoveGuard guard = make_guard();
    const std::vector<FaceKey> no_faces;
    Sweep sweep;
    for (int round = 0; round < 10; ++round)
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            PlannedMove move;
            if (!odt.interior_move(mesh, v, move)) continue;
            CHECK(g.vertex_class(v) == VertexClass::Interior, "vertex %d of class %d moved inside", v,
                  static_cast<int>(g.vertex_class(v)));
            apply(mesh, guard, v, move, no_faces, sweep);
        }
    const double after = min_dihedral(mesh);
    print_message("interior: %d moves (%d shortened, %d rejected), smallest dihedral %.2f -> %.2f degrees\n",
                  sweep.moved + sweep.shortened, sweep.shortened, sweep.rejected, before, after);
    CHECK(sweep.moved > 0, "nothing moved");
    CHECK(after > before + 2.0, "smallest dihedral %.2f -> %.2f", before, after);
    assert_near(total_volume(mesh), 1.0, 1e-12);
}

// -------------------------------------------------------------- topology

void test_untangle(void**) {
    const char* what = "untangle";
    const int n = 3;
    Arrays a = box(n);
    // Kuhn star of an interior vertex: |y_i| <= 1 and |y_i - y_j| <= 1 (in
    // cells); y = (0.9, -0.2, 0.05) is out of it across y_x - y_y = 1.
    const int32_t v = grid_vertex(n, 1, 1, 1);
    a.set(v, a.point(v) + Vec3(0.9, -0.2, 0.05) / n);
    TetMesh mesh = build(a, BODT_CREATE_ACCEPT_INVERTED);
    const int32_t inverted = count_not_positive(mesh);
    CHECK(inverted > 0, "no inverted tet");
    assert_near(total_volume(mesh), 1.0, 1e-12);
    const std::set<FaceKey> faces = boundary_faces(mesh);

    GeometryModel g = extract(mesh);
    EditableMesh em(mesh, g.vertex_classes(mesh));
    bodt::PhasedTopology topo(em, g, bodt::PhasedTopologySettings{});
    const int32_t removed = topo.remove_inverted();
    const TetMesh out = written(em);
    print_message("untangle: %d inverted tets, %d half-edge collapses, %d tets left\n", inverted, removed, out.num_tets());
    CHECK(removed > 0, "nothing collapsed");
    CHECK(count_not_positive(out) == 0, "%d tets with stretch <= 0 left", count_not_positive(out));
    assert_near(total_volume(out), 1.0, 1e-12);
    CHECK(boundary_faces(out) == faces, "the boundary faces changed");
}

struct Small {
    const char* name;
    std::vector<Vec3> points;
    std::vector<Tet> tets;
};

Arrays arrays_of(const Small& s) {
    Arrays a;
    for (const Vec3& p : s.points) a.xyz.insert(a.xyz.end(), {p.x(), p.y(), p.z()});
    for (Tet q : s.tets) {
        const Vec3 &p0 = s.points[q[0]], &p1 = s.points[q[1]], &p2 = s.points[q[2]], &p3 = s.points[q[3]];
        if ((p1 - p0).dot((p2 - p0).cross(p3 - p0)) < 0) std::swap(q[2], q[3]);
        a.tets.insert(a.tets.end(), q.begin(), q.end());
    }
    return a;
}

// test_topology's sliver (2 3 4 5 in an octahedron), cap (2 just above the
// middle of 3 4 5 in a bipyramid) and spade (2 over the edge 3 4).
std::vector<Small> small_bad_cases() {
    std::vector<Small> out;
    const double h = 0.04;
    out.push_back({"sliver",
                   {Vec3(0.02, 0.01, 1), Vec3(-0.01, 0.02, -1), Vec3(-1, 0, -h), Vec3(0, -1, h), Vec3(1, 0, -h), Vec3(0, 1, h)},
                   {{2, 3, 4, 5}, {0, 3, 5, 2}, {0, 3, 5, 4}, {1, 2, 4, 3}, {1, 2, 4, 5}}});
    Small cap{"cap", {Vec3(0.02, 0, 1), Vec3(0, 0.03, -1), Vec3(0.05, -0.02, 0.06)}, {{2, 3, 4, 5}, {1, 3, 4, 5}, {0, 2, 3, 4}, {0, 2, 4, 5}, {0, 2, 5, 3}}};
    for (int i = 0; i < 3; ++i) cap.points.emplace_back(std::cos(2 * kPi * i / 3), std::sin(2 * kPi * i / 3), 0.0);
    out.push_back(cap);
    out.push_back({"spade",
                   {Vec3(0.03, -0.3, -1), Vec3(-0.02, 0.3, 1), Vec3(0.1, -0.05, 0.06), Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                   {{2, 3, 4, 5}, {0, 3, 4, 5}, {0, 2, 3, 4}, {1, 2, 3, 5}, {1, 2, 4, 5}}});
    return out;
}

// Sec. 3.5.2's split and collapse.  A piece of a sliver split at a crossing
// edge, or of a cap split at its edge between the largest and smallest
// faces, keeps two or more of the bad tet's dihedral angles (the planes at
// those edges do not change), so the intermediate split cannot beat the bad
// tet's worst angle: only the result of split and collapse can.
void check_degenerate_removed(const Small& s) {
    const char* what = s.name;
    const TetMesh mesh = build(arrays_of(s));
    const double volume = total_volume(mesh), area = boundary_area(mesh);
    const int32_t bad0 = count_bad(mesh, 15.0);
    const double worst0 = min_dihedral(mesh);
    CHECK(bad0 > 0, "no bad tet");
    GeometryModel g = extract(mesh);
    EditableMesh em(mesh, g.vertex_classes(mesh));
    bodt::PhasedTopology topo(em, g, bodt::PhasedTopologySettings{});
    const int32_t removed = topo.remove_degenerate();
    const TetMesh out = written(em);
    const int32_t bad = count_bad(out, 15.0);
    print_message("degenerate, %s: %d removed, %d -> %d tets, bad tets %d -> %d, smallest dihedral %.2f -> %.2f\n",
                  s.name, removed, mesh.num_tets(), out.num_tets(), bad0, bad, worst0, min_dihedral(out));
    CHECK(removed > 0, "nothing removed");
    // The bad tet (2 3 4 5) is gone.
    for (const Tet& q : out.tets) {
        std::array<int32_t, 4> sorted = q;
        std::sort(sorted.begin(), sorted.end());
        CHECK(!(sorted == std::array<int32_t, 4>{2, 3, 4, 5}), "the bad tet is still there");
    }
    CHECK(count_not_positive(out) == 0, "inverted or flat tets");
    assert_near(total_volume(out), volume, 1e-12 * volume);
    assert_near(boundary_area(out), area, 1e-12 * area);
    CHECK(min_dihedral(out) > worst0, "smallest dihedral %.3g -> %.3g", worst0, min_dihedral(out));
    CHECK(bad == 0, "%d tets still below 15 degrees", bad);
}

void test_degenerate_sliver(void**) { check_degenerate_removed(small_bad_cases()[0]); }
void test_degenerate_cap(void**) { check_degenerate_removed(small_bad_cases()[1]); }
void test_degenerate_spade(void**) { check_degenerate_removed(small_bad_cases()[2]); }

// Every boundary face of m lies in one of the planes of the unit box's faces (1e-12).
void check_faces_on_unit_box(const TetMesh& m, const char* what) {
    for (const FaceKey& f : boundary_faces(m)) {
        bool flat = false;
        for (int axis = 0; axis < 3 && !flat; ++axis)
            for (double side : {0.0, 1.0}) {
                bool all = true;
                for (int32_t v : f.v) all = all && std::fabs(m.points[v][axis] - side) <= 1e-12;
                flat = flat || all;
            }
        CHECK(flat, "face %d %d %d off the box", f.v[0], f.v[1], f.v[2]);
    }
}

// A grid over [-0.25, 1.25]^3 holding `value` everywhere.
bodt::DensityGrid constant_grid(double value) {
    return bodt::DensityGrid(Vec3::Constant(-0.25), Vec3::Constant(0.75), {3, 3, 3}, std::vector<double>(27, value));
}

void test_density_split(void**) {
    const char* what = "density_split";
    const int n = 2;
    const double hh = 1.0 / n;
    const TetMesh mesh = build(box(n));
    GeometryModel g = extract(mesh);
    EditableMesh em(mesh, g.vertex_classes(mesh));
    bodt::PhasedTopologySettings settings;
    bodt::PhasedTopology topo(em, g, settings);
    const bodt::DensityGrid grid = constant_grid(2.0 / hh);
    bodt::PhasedTopologyCounts counts;
    topo.recover(&grid, counts);
    const TetMesh out = written(em);
    const EdgeStats e0 = edge_stats(mesh), e1 = edge_stats(out);
    print_message("density_split: %d splits, %d collapses; %zu edges, mean length %.4f -> %zu, %.4f; longest %.4f -> %.4f\n",
                  counts.splits, counts.collapses, e0.count, e0.mean, e1.count, e1.mean, e0.max, e1.max);
    CHECK(counts.splits > 0, "no split");
    CHECK(counts.collapses == 0, "%d collapses", counts.collapses);
    CHECK(out.num_vertices() == mesh.num_vertices() + counts.splits, "%d vertices", out.num_vertices());
    CHECK(e1.mean < 0.8 * e0.mean, "mean edge length %.4f -> %.4f", e0.mean, e1.mean);
    CHECK(e1.max <= e0.max * (1.0 + 1e-12), "longest edge %.4f -> %.4f", e0.max, e1.max);
    CHECK(count_not_positive(out) == 0, "inverted tets");
    assert_near(total_volume(out), 1.0, 1e-12);
    assert_near(boundary_area(out), 6.0, 1e-12);
    // The box's faces stay flat: every boundary vertex on one of its planes.
    check_faces_on_unit_box(out, what);
}

void test_density_collapse(void**) {
    {
        // A single cube: every edge joins two corners, nothing collapses.
        const char* what = "density_collapse, one cube";
        const TetMesh mesh = build(box(1));
        GeometryModel g = extract(mesh);
        for (int32_t v = 0; v < mesh.num_vertices(); ++v)
            CHECK(g.vertex_class(v) == VertexClass::Corner, "vertex %d is class %d", v, static_cast<int>(g.vertex_class(v)));
        EditableMesh em(mesh, g.vertex_classes(mesh));
        bodt::PhasedTopology topo(em, g, bodt::PhasedTopologySettings{});
        const bodt::DensityGrid grid = constant_grid(0.3);
        bodt::PhasedTopologyCounts counts;
        topo.recover(&grid, counts);
        const TetMesh out = written(em);
        CHECK(counts.collapses == 0 && counts.splits == 0, "%d collapses, %d splits", counts.collapses, counts.splits);
        CHECK(out.tets == mesh.tets && out.points == mesh.points, "the cube changed");
    }
    const char* what = "density_collapse";
    const int n = 4;
    const double hh = 1.0 / n;
    const TetMesh mesh = build(box(n));
    GeometryModel g = extract(mesh);
    std::vector<int32_t> corners;
    for (int32_t v = 0; v < mesh.num_vertices(); ++v)
        if (g.vertex_class(v) == VertexClass::Corner) corners.push_back(v);
    CHECK(corners.size() == 8, "%zu corners", corners.size());
    EditableMesh em(mesh, g.vertex_classes(mesh));
    // Collapses only: the grid also wants the box's face diagonals (1.41
    // against 0.83) split, which would take corner-corner edges away too.
    bodt::PhasedTopologySettings settings;
    settings.split = false;
    bodt::PhasedTopology topo(em, g, settings);
    const bodt::DensityGrid grid = constant_grid(0.3 / hh);
    int32_t total = 0;
    for (int round = 0; round < 6; ++round) {
        std::vector<std::array<int32_t, 2>> corner_edges;
        for (size_t i = 0; i < corners.size(); ++i)
            for (size_t k = i + 1; k < corners.size(); ++k)
                if (!em.tets_holding({corners[i], corners[k]}).empty()) corner_edges.push_back({corners[i], corners[k]});
        bodt::PhasedTopologyCounts counts;
        topo.recover(&grid, counts);
        CHECK(counts.splits == 0, "round %d: %d splits", round, counts.splits);
        total += counts.collapses;
        for (const auto& e : corner_edges)
            CHECK(!em.tets_holding({e[0], e[1]}).empty(), "round %d: the edge between corners %d and %d went", round, e[0],
                  e[1]);
        for (int32_t c : corners) {
            CHECK(!em.tets_of(c).empty(), "round %d: corner %d went", round, c);
            CHECK(em.point(c) == mesh.points[c], "round %d: corner %d moved", round, c);
        }
        for (int32_t t = 0; t < em.tet_capacity(); ++t)
            if (em.alive(t)) CHECK(bodt::stretch(em.tet_points(t)) > 0.0, "round %d: tet %d inverted", round, t);
        if (counts.collapses == 0) break;
    }
    const TetMesh out = written(em);
    print_message("density_collapse: %d collapses, %d -> %d vertices, %d -> %d tets\n", total, mesh.num_vertices(),
                  out.num_vertices() - static_cast<int32_t>(std::count(out.vflags.begin(), out.vflags.end(), bodt::kUnused)),
                  mesh.num_tets(), out.num_tets());
    CHECK(total > 0, "no collapse");
    CHECK(out.num_tets() < mesh.num_tets(), "%d tets", out.num_tets());
    CHECK(count_not_positive(out) == 0, "inverted tets");
    assert_near(total_volume(out), 1.0, 1e-12);
    assert_near(boundary_area(out), 6.0, 1e-12);
}

// Edges between two triangles of the top face z = 1 whose opposite angles
// sum past pi.
int32_t non_delaunay_top(const TetMesh& m) {
    std::map<std::pair<int32_t, int32_t>, std::vector<double>> opposite;
    for (const FaceKey& f : boundary_faces(m)) {
        bool top = true;
        for (int32_t v : f.v) top = top && std::fabs(m.points[v].z() - 1.0) <= 1e-12;
        if (!top) continue;
        for (int i = 0; i < 3; ++i) {
            const int32_t p = f.v[i], q = f.v[(i + 1) % 3], r = f.v[(i + 2) % 3];
            opposite[{std::min(p, q), std::max(p, q)}].push_back(angle_at(m.points[r], m.points[p], m.points[q]));
        }
    }
    int32_t n = 0;
    for (const auto& [e, angles] : opposite) n += angles.size() == 2 && angles[0] + angles[1] > kPi * (1.0 + 1e-9);
    return n;
}

void test_surface_flip(void**) {
    const char* what = "surface_flip";
    const int n = 2;
    Arrays a = box(n);
    // Top face z = 1: the quad [0.5, 1] x [0, 0.5] is cut along (0.5, 0) -
    // (1, 0.5); its opposite vertices are the corner (1, 0) and the middle
    // (0.5, 0.5), both at 90 degrees.  The middle moved towards the edge
    // opens its angle past 90.
    const int32_t ea = grid_vertex(n, 1, 0, n), eb = grid_vertex(n, 2, 1, n);
    const int32_t c = grid_vertex(n, 1, 1, n), d = grid_vertex(n, 2, 0, n);
    a.set(c, Vec3(0.6, 0.4, 1.0));
    TetMesh mesh = build(a);
    const Vec3 &pa = mesh.points[ea], &pb = mesh.points[eb];
    CHECK(angle_at(mesh.points[c], pa, pb) + angle_at(mesh.points[d], pa, pb) > kPi + 0.1, "the pair is Delaunay");
    GeometryModel g = extract(mesh);
    EditableMesh em(mesh, g.vertex_classes(mesh));
    CHECK(!em.tets_holding({ea, eb}).empty() && em.tets_holding({c, d}).empty(), "unexpected starting edges");
    const double worst0 = min_dihedral(mesh);
    bodt::PhasedTopology topo(em, g, bodt::PhasedTopologySettings{});
    const int32_t flips = topo.flip_surface();
    const TetMesh out = written(em);
    print_message("surface_flip: %d flips, smallest dihedral %.2f -> %.2f\n", flips, worst0, min_dihedral(out));
    CHECK(flips >= 1, "no flip");
    CHECK(em.tets_holding({ea, eb}).empty(), "edge %d-%d is still there", ea, eb);
    CHECK(!em.tets_holding({c, d}).empty(), "edge %d-%d was not made", c, d);
    CHECK(count_not_positive(out) == 0, "inverted tets");
    assert_near(total_volume(out), 1.0, 1e-12);
    assert_near(boundary_area(out), 6.0, 1e-12);
    // Top face still planar, every face on one of the box's planes.
    check_faces_on_unit_box(out, what);
    CHECK(non_delaunay_top(out) < non_delaunay_top(mesh), "non-Delaunay top edges %d -> %d", non_delaunay_top(mesh),
          non_delaunay_top(out));
}

}  // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chain_line),      cmocka_unit_test(test_chain_circle),
        cmocka_unit_test(test_surface_cylinder), cmocka_unit_test(test_surface_plane),
        cmocka_unit_test(test_interior),        cmocka_unit_test(test_untangle),
        cmocka_unit_test(test_degenerate_sliver), cmocka_unit_test(test_degenerate_cap),
        cmocka_unit_test(test_degenerate_spade), cmocka_unit_test(test_density_split),
        cmocka_unit_test(test_density_collapse), cmocka_unit_test(test_surface_flip),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
