// test_nodt_core: white-box tests of BODT_MODE_NODT's parts (links bodt_core).
//
//   closest point   closest_point_on_triangle on random triangles, slivers
//                   (1e-6 thin), collinear triangles and segments stored as
//                   (a, b, b): the point lies on the triangle and no point of
//                   a dense sampling of the triangle is nearer, to round-off
//                   growing as 1 / the sine of the triangle's angle
//   tree            SurfaceBvh::closest = the nearest of all triangles, by
//                   brute force, on a random triangle soup
//   natural target  NodtSmoother::target on a jittered Kuhn box against the
//                   formula of nodt.hpp computed here from circumcentres
//                   (solved from their linear system): an inner vertex goes
//                   to the volume-weighted mean of its tets' circumcentres
//                   (Chen and Xu), a boundary vertex to that mean minus
//                   1/12 sum_i (|Y_i|^2 + |Y_{i+1}|^2) C_i over its boundary
//                   triangles, divided by the star's volume (to 1e-12 of the
//                   cell size); corners stay; the surface faces handed to
//                   the guard are the vertex's boundary triangles
#include "common/error.hpp"
#include "features/vertex_classes.hpp"
#include "mesh/mesh_builder.hpp"
#include "mesh/surface_bvh.hpp"
#include "smoothing/input_surface.hpp"
#include "smoothing/nodt.hpp"

#include "mesh_gen.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

#include "test_util.h"
#include "core_checks.hpp"

namespace {

using bodt::Vec3;

// ------------------------------------------------------------ closest point

// q lies on triangle abc (in its plane, inside its edges) and no point of a
// 200 x 200 sampling of the triangle is nearer to p, to round-off.
void check_closest(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const char* what) {
    const Vec3 q = bodt::closest_point_on_triangle(p, a, b, c);
    const double scale = std::max({(b - a).norm(), (c - a).norm(), (p - a).norm()});
    const Vec3 n = (b - a).cross(c - a);
    // Round-off grows as the triangle gets thin (1 / sine of the angle at
    // a); below 1e-8 the edges stand in for it, at most half its height off.
    const double sine = n.norm() / ((b - a).norm() * (c - a).norm());
    const double tol = scale * std::max(1e-12, 1e-15 / std::max(sine, 1e-8));
    if (sine > 1e-8) {  // not degenerate: q in the plane, inside every edge
        const double off_plane = std::fabs(n.normalized().dot(q - a));
        CHECK(off_plane <= tol, "closest point %.3g off the triangle's plane", off_plane);
        const Vec3 corner[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) {
            const Vec3 &u = corner[k], &v = corner[(k + 1) % 3];
            CHECK((v - u).cross(q - u).dot(n) >= -tol * (v - u).norm() * n.norm(), "closest point outside edge %d", k);
        }
    }
    const double d = (p - q).norm();
    const int steps = 200;
    for (int i = 0; i <= steps; ++i)
        for (int j = 0; i + j <= steps; ++j) {
            const Vec3 s = a + (double(i) / steps) * (b - a) + (double(j) / steps) * (c - a);
            CHECK((p - s).norm() >= d - tol, "a sample is nearer: %.17g < %.17g", (p - s).norm(), d);
        }
}

void test_closest_point(void** state) {
    (void)state;
    const char* what = "closest point";
    Rng rng(5);
    for (int k = 0; k < 200; ++k) {
        const Vec3 a = rng.point(-1, 1), b = rng.point(-1, 1);
        const Vec3 c = k % 4 == 1 ? Vec3(b)                                    // a segment (a, b, b)
                       : k % 4 == 2 ? Vec3(a + 0.5 * (b - a))                  // collinear
                       : k % 4 == 3 ? Vec3(a + 0.5 * (b - a) + 1e-6 * rng.point(-1, 1))  // a sliver
                                    : rng.point(-1, 1);
        check_closest(rng.point(-2, 2), a, b, c, what);
        check_closest(a + 0.3 * (b - a) + 0.2 * (c - a), a, b, c, what);  // on the triangle: itself
    }
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    CHECK(bodt::closest_point_on_triangle(Vec3(0.2, 0.3, 5), a, b, c).isApprox(Vec3(0.2, 0.3, 0)), "face");
    CHECK(bodt::closest_point_on_triangle(Vec3(2, 2, 1), a, b, c).isApprox(Vec3(0.5, 0.5, 0)), "edge bc");
    CHECK(bodt::closest_point_on_triangle(Vec3(-1, -1, 0), a, b, c) == a, "corner a");
    CHECK(bodt::closest_point_on_triangle(Vec3(3, -1, 0), a, b, b) == b, "segment end");
}

void test_tree(void** state) {
    (void)state;
    const char* what = "tree";
    Rng rng(9);
    std::vector<Vec3> points;
    for (int k = 0; k < 300; ++k) points.push_back(rng.point(0, 1));
    std::vector<std::array<int32_t, 3>> triangles;
    for (int k = 0; k < 500; ++k) {
        const auto pick = [&] { return static_cast<int32_t>(rng.uniform(0, 300)); };
        triangles.push_back({pick(), pick(), pick()});
    }
    const bodt::SurfaceBvh tree(points, triangles);
    CHECK(bodt::SurfaceBvh().closest(Vec3::Zero()).triangle == -1, "an empty tree finds nothing");
    for (int k = 0; k < 500; ++k) {
        const Vec3 p = rng.point(-0.5, 1.5);
        double best = INFINITY;
        for (const auto& t : triangles)
            best = std::min(best, (p - bodt::closest_point_on_triangle(p, points[t[0]], points[t[1]], points[t[2]]))
                                      .squaredNorm());
        const bodt::ClosestPoint q = tree.closest(p);
        CHECK(q.distance2 == best, "tree %.17g, brute force %.17g", q.distance2, best);
        CHECK((p - q.point).squaredNorm() == q.distance2, "the point and its distance disagree");
        CHECK(q.triangle >= 0 && (tree.closest_on(p, q.triangle) - q.point).norm() == 0.0, "the triangle");
    }
}

// ------------------------------------------------------------ natural target

Vec3 circumcentre(const bodt::TetPoints& p) {
    Eigen::Matrix3d m;
    Vec3 rhs;
    for (int k = 0; k < 3; ++k) {
        m.row(k) = (p[k + 1] - p[0]).transpose();
        rhs[k] = 0.5 * (p[k + 1] - p[0]).squaredNorm();
    }
    return p[0] + m.fullPivLu().solve(rhs);
}

// The formula of nodt.hpp, from the mesh's tets and its boundary faces.
Vec3 expected_target(const bodt::TetMesh& mesh, int32_t v, int& boundary_faces) {
    const Vec3& x0 = mesh.points[v];
    double volume = 0.0;
    Vec3 sum = Vec3::Zero();
    boundary_faces = 0;
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        const bodt::Tet& q = mesh.tets[t];
        if (std::find(q.begin(), q.end(), v) == q.end()) continue;
        const bodt::TetPoints p = mesh.tet_points(t);
        const double vol = bodt::signed_volume(p[0], p[1], p[2], p[3]);
        volume += vol;
        sum += vol * circumcentre(p);
        for (int i = 0; i < 4; ++i) {
            if (mesh.neighbors[t][i] >= 0 || q[i] == v) continue;
            // a boundary face through v, oriented out of the mesh, from v
            auto f = mesh.outward_face(t, i);
            while (f[0] != v) std::rotate(f.begin(), f.begin() + 1, f.end());
            const Vec3 yi = mesh.points[f[1]] - x0, yj = mesh.points[f[2]] - x0;
            sum -= (yi.squaredNorm() + yj.squaredNorm()) / 12.0 * yi.cross(yj);
            ++boundary_faces;
        }
    }
    return sum / volume;
}

void test_natural_target(void** state) {
    (void)state;
    const char* what = "natural target";
    enum { N = 4 };
    test_mesh m;
    unsigned char* axes = nullptr;
    assert_int_equal(tm_make_cubes_sliding(&m, N, 1.0, nullptr, nullptr, nullptr, 0.3, 0.3, 17, &axes, nullptr), 0);
    const bodt::MeshArrays arrays = mesh_arrays(m);
    try {
        const bodt::BuiltMesh built = bodt::build_mesh(arrays);
        const bodt::TetMesh& mesh = built.mesh;
        const bodt::VertexClasses classes = bodt::classify_vertices(mesh, built.surfaces, bodt::FeatureSettings{});
        bodt::InputSurface input;
        input.update(mesh, classes);
        bodt::NodtSmoother smoother(built.surfaces, classes, input, {1e-3, 4, true});
        const double h = 1.0 / N;
        int checked[4] = {0, 0, 0, 0};
        std::vector<bodt::FaceKey> faces;
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            Vec3 target;
            const bodt::Plan plan = smoother.target(mesh, v, target, faces);
            const int free_axes = (axes[v] & 1) + (axes[v] >> 1 & 1) + (axes[v] >> 2 & 1);
            if (free_axes == 0) {
                CHECK(plan == bodt::Plan::Stay, "corner %d does not stay", v);
                ++checked[0];
                continue;
            }
            CHECK(plan == bodt::Plan::Move, "vertex %d: no target", v);
            int boundary_faces = 0;
            const Vec3 expected = expected_target(mesh, v, boundary_faces);
            CHECK((target - expected).norm() <= 1e-12 * h, "vertex %d (%d free axes): off by %.3g", v, free_axes,
                  (target - expected).norm());
            CHECK(static_cast<int>(faces.size()) == boundary_faces, "vertex %d: %d faces for the guard, %d expected",
                  v, static_cast<int>(faces.size()), boundary_faces);
            ++checked[free_axes];
        }
        CHECK(checked[0] == 8 && checked[1] == 12 * (N - 1) && checked[2] == 6 * (N - 1) * (N - 1) &&
                  checked[3] == (N - 1) * (N - 1) * (N - 1),
              "checked %d corners, %d edge, %d face and %d inner vertices", checked[0], checked[1], checked[2],
              checked[3]);
    } catch (const bodt::Error& e) {
        fail_msg("%s: %s", what, e.what());
    }
    free(axes);
    tm_free(&m);
}

}  // namespace

int main() {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closest_point),
        cmocka_unit_test(test_tree),
        cmocka_unit_test(test_natural_target),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
