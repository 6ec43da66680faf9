// test_shape_fit: white-box tests of paper 002's shape fits (sec. 3.3) and
// the maps the phased smoothing moves vertices with (links bodt_core).
// Points are sampled here on shapes with random (seeded) poses, at scales
// 1e-3, 1 and 1e3; the fits must give the shapes back.
//
//   complete_frame     (u, w, axis) orthonormal and right-handed for random,
//                      coordinate and nearly coordinate axes; deterministic
//   plane              exact samples: normal (1e-9), point on the plane,
//                      max_error ~0; projection on the plane, idempotent;
//                      noise eta along the normal: max_error ~ eta
//   plane_degenerate   < 3 points, collinear, coincident: None
//   line               exact samples: direction (1e-9), point on the line,
//                      max_error ~0; two points suffice; projection;
//                      < 2 points, coincident: None
//   circle             full circle, 180 and 60 degree arcs: type Arc,
//                      centre, radius (1e-9 relative), normal (1e-9),
//                      max_error ~0; at(angle(x)) = x on the circle and
//                      = project(y) off it; project lands on the circle and
//                      is idempotent; a point on the axis goes to distance r
//   circle_noisy       noise eta: max_error ~ eta, radius within a few eta
//   circle_degenerate  < 3 points, collinear: None
//   cylinder           full cylinder with outward normals, 90 degree patch
//                      (a fillet) with unoriented normals, the patch with
//                      per-face normals (another count), with normals
//                      tilted by ~3 degrees (the Gauss-Newton must fix the
//                      axis), with no normals at all: axis (1e-9), radius
//                      (1e-9 relative), point on the axis at the foot of
//                      the centroid, max_error ~0
//   cylinder_maps      project lands on the cylinder and is idempotent;
//                      at(angle(x), height(x)) = project(x); at() then
//                      angle(), height() round trip; points on the axis
//   cylinder_noisy     noise eta on a 90 degree patch: max_error ~ eta
//   cylinder_degenerate planar points (parallel normals, noisy normals, no
//                      normals), < 5 points: None
//   none_shape         None: project(x) = x, distance 0; angle in (-pi, pi]
#include "features/shape_fit.hpp"

#include "mesh_gen.h"

#include <Eigen/Dense>

#include <cmath>
#include <vector>

#include "test_util.h"
#include "core_checks.hpp"

namespace {

using bodt::Shape;
using bodt::ShapeType;
using bodt::Vec3;
using Mat3 = Eigen::Matrix3d;

const double kScales[] = {1e-3, 1.0, 1e3};

// A random placement at scale s: rotation R, translation up to 5 s.
struct Pose {
    Mat3 R;
    Vec3 t;
    Pose(Rng& rng, double s) : R(random_rotation(rng)), t(rng.point(-5 * s, 5 * s)) {}
    Vec3 map(const Vec3& p) const { return R * p + t; }
    Vec3 dir(const Vec3& d) const { return R * d; }
};

// Unsigned angle-like difference of two unit directions: |a x b|, and the
// two point the same or opposite ways.
void assert_parallel(const Vec3& a, const Vec3& b, double tol) {
    assert_near(a.norm(), 1.0, 1e-14);
    assert_near(a.cross(b).norm(), 0.0, tol);
}

void assert_vec_near(const Vec3& a, const Vec3& b, double tol) {
    if (!((a - b).norm() <= tol))
        fail_msg("(%.17g, %.17g, %.17g) vs (%.17g, %.17g, %.17g): distance %g > %g", a.x(), a.y(), a.z(), b.x(),
                 b.y(), b.z(), (a - b).norm(), tol);
}

void assert_frame(const Shape& s) {
    assert_near(s.u.norm(), 1.0, 1e-14);
    assert_near(s.w.norm(), 1.0, 1e-14);
    assert_near(s.axis.norm(), 1.0, 1e-14);
    assert_near(s.u.dot(s.axis), 0.0, 1e-14);
    assert_near(s.w.dot(s.axis), 0.0, 1e-14);
    assert_near(s.u.dot(s.w), 0.0, 1e-14);
    assert_vec_near(s.u.cross(s.w), s.axis, 1e-14);
}

// Distance of x from the line through p along unit d.
double line_distance(const Vec3& x, const Vec3& p, const Vec3& d) {
    const Vec3 v = x - p;
    return (v - v.dot(d) * d).norm();
}

void test_complete_frame(void**) {
    Rng rng(11);
    std::vector<Vec3> axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), -Vec3::UnitZ(),
                              Vec3(1, 1e-9, 0).normalized(), Vec3(1, 1, 1).normalized()};
    for (int i = 0; i < 100; ++i) axes.push_back(rng.point(-1, 1).normalized());
    for (const Vec3& a : axes) {
        Shape s;
        s.axis = a;
        bodt::complete_frame(a, s.u, s.w);
        assert_frame(s);
        Vec3 u2, w2;
        bodt::complete_frame(a, u2, w2);
        assert_true(u2 == s.u && w2 == s.w);
    }
}

void test_plane(void**) {
    Rng rng(1);
    for (double s : kScales)
        for (int trial = 0; trial < 5; ++trial) {
            const Pose pose(rng, s);
            const Vec3 normal = pose.dir(Vec3::UnitZ()), origin = pose.map(Vec3::Zero());
            std::vector<Vec3> pts;
            for (int i = 0; i < 20; ++i) pts.push_back(pose.map(Vec3(rng.uniform(-s, s), rng.uniform(-s, s), 0)));
            const Shape p = bodt::fit_plane(pts);
            assert_int_equal(p.type, ShapeType::Plane);
            assert_parallel(p.axis, normal, 1e-9);
            assert_near((p.point - origin).dot(normal), 0.0, 1e-9 * s);
            assert_near(p.max_error, 0.0, 1e-9 * s);
            assert_frame(p);
            for (int i = 0; i < 10; ++i) {
                const Vec3 x = pose.map(rng.point(-2 * s, 2 * s));
                const Vec3 y = p.project(x);
                assert_near((y - origin).dot(normal), 0.0, 1e-9 * s);
                assert_near(p.distance(y), 0.0, 1e-12 * s);
                assert_near(p.distance(x), std::abs((x - origin).dot(normal)), 1e-9 * s);
                assert_vec_near(p.project(y), y, 1e-12 * s);
            }
            // Noise eta along the normal: the fit is off by about eta.
            const double eta = 1e-3 * s;
            for (Vec3& x : pts) x += rng.uniform(-eta, eta) * normal;
            for (int i = 0; i < 80; ++i)
                pts.push_back(pose.map(Vec3(rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-eta, eta))));
            const Shape q = bodt::fit_plane(pts);
            assert_int_equal(q.type, ShapeType::Plane);
            assert_true(q.max_error > 0.5 * eta && q.max_error < 2.0 * eta);
            assert_parallel(q.axis, normal, 1e-2);
        }
}

void test_plane_degenerate(void**) {
    Rng rng(2);
    assert_int_equal(bodt::fit_plane({}).type, ShapeType::None);
    assert_int_equal(bodt::fit_plane({Vec3(0, 0, 0)}).type, ShapeType::None);
    assert_int_equal(bodt::fit_plane({Vec3(0, 0, 0), Vec3(1, 0, 0)}).type, ShapeType::None);
    for (double s : kScales)
        for (int trial = 0; trial < 5; ++trial) {
            const Pose pose(rng, s);
            std::vector<Vec3> line, same;
            for (int i = 0; i < 10; ++i) {
                line.push_back(pose.map(Vec3(rng.uniform(-s, s), 0, 0)));
                same.push_back(pose.map(Vec3(s, s, s)));
            }
            assert_int_equal(bodt::fit_plane(line).type, ShapeType::None);
            assert_int_equal(bodt::fit_plane(same).type, ShapeType::None);
        }
}

void test_line(void**) {
    Rng rng(3);
    assert_int_equal(bodt::fit_line({}).type, ShapeType::None);
    assert_int_equal(bodt::fit_line({Vec3(1, 2, 3)}).type, ShapeType::None);
    for (double s : kScales)
        for (int trial = 0; trial < 5; ++trial) {
            const Pose pose(rng, s);
            const Vec3 dir = pose.dir(Vec3::UnitX()), origin = pose.map(Vec3::Zero());
            std::vector<Vec3> pts;
            for (int i = 0; i < 10; ++i) pts.push_back(pose.map(Vec3(rng.uniform(-s, s), 0, 0)));
            const Shape l = bodt::fit_line(pts);
            assert_int_equal(l.type, ShapeType::Line);
            assert_parallel(l.axis, dir, 1e-9);
            assert_near(line_distance(l.point, origin, dir), 0.0, 1e-9 * s);
            assert_near(l.max_error, 0.0, 1e-9 * s);
            assert_frame(l);
            const Vec3 x = pose.map(rng.point(-s, s));
            const Vec3 y = l.project(x);
            assert_near(line_distance(y, origin, dir), 0.0, 1e-9 * s);
            assert_near(l.distance(x), line_distance(x, origin, dir), 1e-9 * s);
            assert_vec_near(l.project(y), y, 1e-12 * s);
            assert_vec_near(l.at(0.0, l.height(x)), y, 1e-12 * s);

            const Shape two = bodt::fit_line({pts[0], pts[1]});
            assert_int_equal(two.type, ShapeType::Line);
            assert_parallel(two.axis, dir, 1e-9);

            const std::vector<Vec3> same(4, pose.map(Vec3(s, -s, s)));
            assert_int_equal(bodt::fit_line(same).type, ShapeType::None);
        }
}

// Checks a fitted circle against centre c, normal n, radius r.
void check_circle(const Shape& f, const Vec3& c, const Vec3& n, double r, double tol) {
    assert_int_equal(f.type, ShapeType::Arc);
    assert_near(f.radius, r, tol * r);
    assert_vec_near(f.point, c, tol * r);
    assert_parallel(f.axis, n, tol);
    assert_frame(f);
}

void test_circle(void**) {
    Rng rng(4);
    const double spans[] = {2 * M_PI, M_PI, M_PI / 3};
    for (double s : kScales)
        for (double span : spans)
            for (int trial = 0; trial < 4; ++trial) {
                const Pose pose(rng, s);
                const double r = s * rng.uniform(0.5, 2.0), phase = rng.uniform(-M_PI, M_PI);
                const Vec3 c = pose.map(Vec3::Zero()), n = pose.dir(Vec3::UnitZ());
                std::vector<Vec3> pts;
                const int count = 12;
                const bool closed = span == 2 * M_PI;
                for (int i = 0; i < count; ++i) {
                    const double t = phase + span * i / (closed ? count : count - 1);
                    pts.push_back(pose.map(Vec3(r * std::cos(t), r * std::sin(t), 0)));
                }
                const Shape f = bodt::fit_circle(pts);
                check_circle(f, c, n, r, 1e-9);
                assert_near(f.max_error, 0.0, 1e-9 * r);
                for (const Vec3& x : pts) {
                    assert_vec_near(f.at(f.angle(x)), x, 1e-9 * r);
                    assert_vec_near(f.project(x), x, 1e-9 * r);
                }
                for (int i = 0; i < 10; ++i) {
                    const Vec3 y = pts[static_cast<size_t>(i)] + rng.point(-0.3 * r, 0.3 * r);
                    const Vec3 z = f.project(y);
                    assert_near(f.distance(z), 0.0, 1e-12 * r);
                    assert_near((z - c).norm(), r, 1e-9 * r);
                    assert_near((z - c).dot(n), 0.0, 1e-9 * r);
                    assert_vec_near(f.project(z), z, 1e-12 * r);
                    assert_vec_near(f.at(f.angle(y)), z, 1e-12 * r);
                    assert_near(f.distance(y), (y - z).norm(), 1e-12 * r);
                    const double theta = f.angle(y);
                    assert_near(f.angle(f.at(theta)), theta, 1e-12);
                }
                // On the axis every circle point is equally near.
                const Vec3 on_axis = f.point + 0.7 * r * f.axis;
                const Vec3 z = f.project(on_axis);
                assert_near((z - f.point).norm(), r, 1e-12 * r);
                assert_near(f.distance(on_axis), std::hypot(r, 0.7 * r), 1e-12 * r);
            }
}

void test_circle_noisy(void**) {
    Rng rng(5);
    for (double s : kScales)
        for (int trial = 0; trial < 4; ++trial) {
            const Pose pose(rng, s);
            const double r = s * rng.uniform(0.5, 2.0), eta = 1e-3 * r;
            const double span = trial % 2 ? M_PI / 3 : 2 * M_PI;
            std::vector<Vec3> pts;
            for (int i = 0; i < 200; ++i) {
                const double t = rng.uniform(0, span);
                const double rr = r + rng.uniform(-eta, eta);
                pts.push_back(pose.map(Vec3(rr * std::cos(t), rr * std::sin(t), rng.uniform(-eta, eta))));
            }
            const Shape f = bodt::fit_circle(pts);
            assert_int_equal(f.type, ShapeType::Arc);
            assert_true(f.max_error > 0.5 * eta && f.max_error < 2.5 * eta);
            assert_near(f.radius, r, (trial % 2 ? 20 : 2) * eta);  // a short arc constrains r less
        }
}

void test_circle_degenerate(void**) {
    Rng rng(6);
    assert_int_equal(bodt::fit_circle({Vec3(0, 0, 0), Vec3(1, 0, 0)}).type, ShapeType::None);
    for (double s : kScales) {
        const Pose pose(rng, s);
        std::vector<Vec3> line;
        for (int i = 0; i < 6; ++i) line.push_back(pose.map(Vec3(rng.uniform(-s, s), 0, 0)));
        assert_int_equal(bodt::fit_circle(line).type, ShapeType::None);
        assert_int_equal(bodt::fit_circle(std::vector<Vec3>(5, pose.t)).type, ShapeType::None);
    }
}

// Samples of the cylinder x^2 + y^2 = r^2, 0 <= z <= h, angles in
// [t0, t0 + span], under `pose`; outward normals.
struct CylinderSample {
    std::vector<Vec3> points, normals;
};

CylinderSample sample_cylinder(const Pose& pose, double r, double h, double t0, double span, int rings, int per_ring) {
    CylinderSample c;
    const bool closed = span == 2 * M_PI;
    for (int k = 0; k < rings; ++k)
        for (int i = 0; i < per_ring; ++i) {
            const double t = t0 + span * i / (closed ? per_ring : per_ring - 1);
            const double z = h * k / (rings - 1);
            c.points.push_back(pose.map(Vec3(r * std::cos(t), r * std::sin(t), z)));
            c.normals.push_back(pose.dir(Vec3(std::cos(t), std::sin(t), 0)));
        }
    return c;
}

void check_cylinder(const Shape& f, const std::vector<Vec3>& pts, const Pose& pose, double r, double tol) {
    assert_int_equal(f.type, ShapeType::Cylinder);
    const Vec3 axis = pose.dir(Vec3::UnitZ()), origin = pose.map(Vec3::Zero());
    assert_parallel(f.axis, axis, tol);
    assert_near(f.radius, r, tol * r);
    assert_near(line_distance(f.point, origin, axis), 0.0, tol * r);
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& p : pts) centroid += p;
    centroid /= static_cast<double>(pts.size());
    assert_near((centroid - f.point).dot(f.axis), 0.0, tol * r);  // the foot of the centroid
    assert_frame(f);
}

void test_cylinder(void**) {
    Rng rng(7);
    for (double s : kScales)
        for (int trial = 0; trial < 3; ++trial) {
            const Pose pose(rng, s);
            const double r = s * rng.uniform(0.5, 2.0), t0 = rng.uniform(-M_PI, M_PI);

            // Full cylinder, outward normals, and without normals.
            const CylinderSample full = sample_cylinder(pose, r, 2.5 * r, t0, 2 * M_PI, 5, 12);
            Shape f = bodt::fit_cylinder(full.points, full.normals);
            check_cylinder(f, full.points, pose, r, 1e-9);
            assert_near(f.max_error, 0.0, 1e-9 * r);
            f = bodt::fit_cylinder(full.points, {});
            check_cylinder(f, full.points, pose, r, 1e-9);
            const CylinderSample ring = sample_cylinder(pose, r, 0.4 * r, t0, 2 * M_PI, 3, 12);
            f = bodt::fit_cylinder(ring.points, {});
            check_cylinder(f, ring.points, pose, r, 1e-9);

            // A 90 degree fillet, normals of either orientation.
            CylinderSample patch = sample_cylinder(pose, r, 3 * r, t0, M_PI / 2, 6, 7);
            for (Vec3& nrm : patch.normals)
                if (rng.uniform(0, 1) < 0.5) nrm = -nrm;
            f = bodt::fit_cylinder(patch.points, patch.normals);
            check_cylinder(f, patch.points, pose, r, 1e-9);
            assert_near(f.max_error, 0.0, 1e-9 * r);

            // Per-face normals: another count than the points, not unit.
            std::vector<Vec3> faces;
            for (int i = 0; i < 9; ++i) {
                const double t = t0 + M_PI / 2 * (i + 0.5) / 9;
                faces.push_back(pose.dir(Vec3(std::cos(t), std::sin(t), 0)) * rng.uniform(0.1, 10.0));
            }
            f = bodt::fit_cylinder(patch.points, faces);
            check_cylinder(f, patch.points, pose, r, 1e-9);

            // Normals tilted a few degrees: only a start, the points decide.
            std::vector<Vec3> tilted;
            for (const Vec3& nrm : patch.normals) tilted.push_back((nrm + rng.point(-0.05, 0.05)).normalized());
            f = bodt::fit_cylinder(patch.points, tilted);
            check_cylinder(f, patch.points, pose, r, 1e-9);
            assert_near(f.max_error, 0.0, 1e-9 * r);
        }
}

void test_cylinder_maps(void**) {
    Rng rng(8);
    for (double s : kScales) {
        const Pose pose(rng, s);
        const double r = s * rng.uniform(0.5, 2.0);
        const CylinderSample c = sample_cylinder(pose, r, 2 * r, 0.3, 2 * M_PI, 4, 10);
        const Shape f = bodt::fit_cylinder(c.points, c.normals);
        check_cylinder(f, c.points, pose, r, 1e-9);
        const Vec3 axis = pose.dir(Vec3::UnitZ()), origin = pose.map(Vec3::Zero());
        for (int i = 0; i < 50; ++i) {
            const Vec3 x = pose.map(rng.point(-2 * r, 2 * r));
            const Vec3 y = f.project(x);
            assert_near(line_distance(y, origin, axis), r, 1e-9 * r);
            assert_near(f.distance(y), 0.0, 1e-12 * r);
            assert_near(f.distance(x), (x - y).norm(), 1e-12 * r);
            assert_vec_near(f.project(y), y, 1e-12 * r);
            assert_vec_near(f.at(f.angle(x), f.height(x)), y, 1e-12 * r);
            const double theta = rng.uniform(-M_PI, M_PI), z = rng.uniform(-r, r);
            const Vec3 p = f.at(theta, z);
            assert_near(f.distance(p), 0.0, 1e-12 * r);
            assert_near(f.angle(p), theta, 1e-12);
            assert_near(f.height(p), z, 1e-12 * r);
        }
        // On the axis: along u, at the same height.
        const Vec3 on_axis = f.point + 0.6 * r * f.axis;
        assert_vec_near(f.project(on_axis), on_axis + r * f.u, 1e-12 * r);
        assert_near(f.distance(on_axis), r, 1e-12 * r);
    }
}

void test_cylinder_noisy(void**) {
    Rng rng(9);
    for (double s : kScales)
        for (int trial = 0; trial < 3; ++trial) {
            const Pose pose(rng, s);
            const double r = s * rng.uniform(0.5, 2.0), eta = 1e-3 * r, t0 = rng.uniform(-M_PI, M_PI);
            std::vector<Vec3> pts, normals;
            for (int i = 0; i < 200; ++i) {
                const double t = t0 + rng.uniform(0, M_PI / 2), rr = r + rng.uniform(-eta, eta);
                pts.push_back(pose.map(Vec3(rr * std::cos(t), rr * std::sin(t), rng.uniform(0, 2 * r))));
                normals.push_back((pose.dir(Vec3(std::cos(t), std::sin(t), 0)) + rng.point(-0.02, 0.02)));
            }
            const Shape f = bodt::fit_cylinder(pts, normals);
            assert_int_equal(f.type, ShapeType::Cylinder);
            assert_true(f.max_error > 0.5 * eta && f.max_error < 2.0 * eta);
            assert_near(f.radius, r, 0.05 * r);
            assert_parallel(f.axis, pose.dir(Vec3::UnitZ()), 0.02);
        }
}

void test_cylinder_degenerate(void**) {
    Rng rng(10);
    for (double s : kScales) {
        const Pose pose(rng, s);
        const Vec3 normal = pose.dir(Vec3::UnitZ());
        std::vector<Vec3> pts, same, noisy, noisy_pts;
        for (int i = 0; i < 30; ++i) {
            pts.push_back(pose.map(Vec3(rng.uniform(-s, s), rng.uniform(-s, s), 0)));
            same.push_back(i % 2 ? normal : -normal);
            noisy.push_back(normal + rng.point(-0.01, 0.01));
            noisy_pts.push_back(pts.back() + rng.uniform(-1e-6, 1e-6) * s * normal);
        }
        assert_int_equal(bodt::fit_cylinder(pts, same).type, ShapeType::None);
        assert_int_equal(bodt::fit_cylinder(pts, noisy).type, ShapeType::None);
        assert_int_equal(bodt::fit_cylinder(pts, {}).type, ShapeType::None);
        assert_int_equal(bodt::fit_cylinder(noisy_pts, same).type, ShapeType::None);
        // A planar patch with slightly non-parallel normals: any cylinder
        // found is a huge one or is rejected.
        const Shape f = bodt::fit_cylinder(noisy_pts, noisy);
        assert_true(f.type == ShapeType::None || f.radius > 100 * s);

        const CylinderSample c = sample_cylinder(pose, s, s, 0.0, M_PI, 2, 2);
        assert_int_equal(bodt::fit_cylinder(c.points, c.normals).type, ShapeType::None);  // 4 points
    }
}

void test_none_shape(void**) {
    const Shape none;
    assert_int_equal(none.type, ShapeType::None);
    const Vec3 x(1.5, -2, 3);
    assert_true(none.project(x) == x);
    assert_true(none.distance(x) == 0.0);

    Shape c;
    c.type = ShapeType::Circle;
    c.radius = 2.0;
    assert_near(c.angle(Vec3(-1, -0.0, 0)), M_PI, 0.0);
    assert_near(c.angle(Vec3(-1, 0, 0)), M_PI, 0.0);
    assert_near(c.angle(Vec3(0, -1, 5)), -M_PI / 2, 1e-15);
    assert_vec_near(c.project(Vec3(0, -1, 5)), Vec3(0, -2, 0), 1e-15);
    assert_vec_near(c.at(M_PI / 2, 7.0), Vec3(0, 2, 0), 1e-15);
}

}  // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_complete_frame),   cmocka_unit_test(test_plane),
        cmocka_unit_test(test_plane_degenerate), cmocka_unit_test(test_line),
        cmocka_unit_test(test_circle),           cmocka_unit_test(test_circle_noisy),
        cmocka_unit_test(test_circle_degenerate), cmocka_unit_test(test_cylinder),
        cmocka_unit_test(test_cylinder_maps),    cmocka_unit_test(test_cylinder_noisy),
        cmocka_unit_test(test_cylinder_degenerate), cmocka_unit_test(test_none_shape),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
