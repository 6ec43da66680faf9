// test_core: white-box tests of the C++ core (links bodt_core).
//
//   bodt::orient          the certified sign: exactly coplanar points (even
//                         when round-off makes the determinant nonzero) give 0,
//                         clearly oriented ones +1 / -1
//   bodt::dihedral_angles against closed forms, edge by edge
//   TetMesh               neighbours and vertex stars against brute force
//   BoundarySurface       one_ring of every boundary vertex of a box, an
//                         L-shaped (nonconvex) block and a ball: exactly the
//                         boundary neighbours, turning around the outward
//                         normal; build() refuses pinched vertices and
//                         edges, and a Tolerant build's rings there are
//                         open or empty
//   curve_order           a permutation; on a shuffled 8^3 grid consecutive
//                         vertices are grid neighbours (a Hilbert curve);
//                         tets by their first vertex, ties in the caller's
//                         order; bad input left in order; a mesh built in it
//                         gives the caller's points and tets back, and its
//                         stars list tets in the caller's order
//   coloured_sweep        on 1, 2 and 3 threads every coloured vertex is
//                         visited once, after each neighbour of lower colour
//                         was done and never while a neighbour was being
//                         visited (on 1, in the mesh's sweep_order); the
//                         colouring is proper and its counts of lower pairs
//                         are right; an exception in a visit stops the sweep
//                         and comes out of it
//   MoveGuard             against a guard written out here (the full move,
//                         then halved, the first place where every star tet
//                         is positive, above its stretch floor and, with
//                         never-worse, inside the star's extreme angles or
//                         up to the largest angle allowed):
//                         the same outcome, place and distance, bit for bit,
//                         for random moves of every inner vertex of a
//                         jittered box, with and without the shape cache,
//                         and the cache then holds the moved tets' shapes
#include "common/error.hpp"
#include "mesh/boundary_surface.hpp"
#include "mesh/curve_order.hpp"
#include "mesh/mesh_builder.hpp"
#include "mesh/tet_mesh.hpp"
#include "quality/mesh_quality.hpp"
#include "quality/tet_geometry.hpp"
#include "smoothing/move_guard.hpp"
#include "smoothing/coloured_sweep.hpp"

#include "bodt.h"
#include "mesh_gen.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core_checks.hpp"

namespace {

using bodt::Vec3;

constexpr double kDeg = 180.0 / M_PI;

// ------------------------------------------------------------------ orient

void test_orient_clear_signs(void**) {
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(0, 0, 1);
    const auto o = bodt::orient(a, b, c, d);
    assert_int_equal(o.sign, 1);
    assert_true(o.det6 == 1.0);
    assert_int_equal(bodt::orient(a, c, b, d).sign, -1);
    assert_int_equal(bodt::orient(b, a, c, d).sign, -1);
    // tiny but certain: the exact determinant 1e-12 is far above round-off
    assert_int_equal(bodt::orient(a, b, c, Vec3(0.25, 0.25, 1e-12)).sign, 1);
    assert_int_equal(bodt::orient(a, b, c, Vec3(0.25, 0.25, -1e-12)).sign, -1);
    // far from the origin, still clear
    const Vec3 s(1e6, -3e6, 2e6);
    assert_int_equal(bodt::orient(a + s, b + s, c + s, d + s).sign, 1);
}

void test_orient_flat(void**) {
    // exactly flat: determinant 0
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    const auto o = bodt::orient(a, b, c, Vec3(0.3, 0.3, 0));
    assert_int_equal(o.sign, 0);
    assert_true(o.det6 == 0.0);
    // on the plane x + y + z = 1 up to the rounding of the decimal inputs
    const auto p = bodt::orient(Vec3(0.1, 0.2, 0.7), Vec3(0.3, 0.3, 0.4), Vec3(0.7, 0.1, 0.2), Vec3(0.2, 0.6, 0.2));
    assert_int_equal(p.sign, 0);
    assert_true(std::fabs(p.det6) < 1e-14);

    // Exactly coplanar integer points with coordinates up to 2^20: d = b + c
    // - a (or another integer combination) makes the exact determinant 0,
    // while the floating-point one rounds products of up to 2^64.  A sign
    // of +-1 there would be a certification failure.  Points moved off the
    // plane by a unit step must get the exact sign, computed in __int128.
    tm_rng rng;
    tm_rng_seed(&rng, 42);
    const auto rnd = [&rng] { return std::floor((2.0 * tm_rng_uniform(&rng) - 1.0) * 1048576.0); };
    int nonzero_det = 0, certified = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const Vec3 A(rnd(), rnd(), rnd()), B(rnd(), rnd(), rnd()), C(rnd(), rnd(), rnd());
        const int s = 1 + trial % 3, t = 1 - trial % 2;
        const Vec3 D = A + s * (B - A) - t * (C - A) + (trial % 5 == 0 ? Vec3(0, 0, 0) : (C - A));
        const auto on = bodt::orient(A, B, C, D);
        if (on.sign != 0) fail_msg("trial %d: coplanar points got sign %d (det %g)", trial, on.sign, on.det6);
        nonzero_det += on.det6 != 0.0;

        // one unit off the plane
        const Vec3 E = D + Vec3(trial % 2, (trial / 2) % 2, 1);
        __int128 u[3], v[3], w[3];
        for (int k = 0; k < 3; ++k) {
            u[k] = static_cast<__int128>(B[k] - A[k]);
            v[k] = static_cast<__int128>(C[k] - A[k]);
            w[k] = static_cast<__int128>(E[k] - A[k]);
        }
        const __int128 exact = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                               u[2] * (v[0] * w[1] - v[1] * w[0]);
        const int exact_sign = exact > 0 ? 1 : (exact < 0 ? -1 : 0);
        const auto off = bodt::orient(A, B, C, E);
        if (off.sign != 0 && off.sign != exact_sign)
            fail_msg("trial %d: certified sign %d, exact sign %d", trial, off.sign, exact_sign);
        certified += off.sign != 0;
    }
    // round-off did show in the determinant, and most off-plane cases are
    // decided
    assert_true(nonzero_det > 100);
    assert_true(certified > 10000);
}

// --------------------------------------------------------- dihedral angles

bodt::TetPoints pts(const double (&p)[12]) {
    return {Vec3(p[0], p[1], p[2]), Vec3(p[3], p[4], p[5]), Vec3(p[6], p[7], p[8]), Vec3(p[9], p[10], p[11])};
}

void expect_angles(const bodt::TetPoints& p, const std::array<double, 6>& expected, double tol) {
    const auto a = bodt::dihedral_angles(p);
    for (int e = 0; e < 6; ++e)
        if (!(std::fabs(a[e] - expected[e]) <= tol))
            fail_msg("edge (%d, %d): %.15g degrees, expected %.15g", bodt::kEdgeVertex[e][0], bodt::kEdgeVertex[e][1],
                     a[e], expected[e]);
}

void test_dihedral_angles(void**) {
    // regular: acos(1/3) everywhere
    const double reg = std::acos(1.0 / 3.0) * kDeg;
    expect_angles(pts({1, 1, 1, 1, -1, -1, -1, -1, 1, -1, 1, -1}), {reg, reg, reg, reg, reg, reg}, 1e-10);
    // the Kuhn tet (0,0,0) (1,0,0) (1,1,0) (1,1,1), edges in kEdgeVertex order
    // (0 1) (0 2) (0 3) (1 2) (1 3) (2 3): worked out by projecting the two
    // other vertices onto the plane normal to each edge
    expect_angles(pts({0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 1}), {45, 90, 60, 90, 90, 45}, 1e-10);
    // a sliver (1,0,0) (-1,0,0) (0,-1,h) (0,1,h): pi - 2 atan h at edges (0 1)
    // and (2 3), atan(h sqrt(2 + h^2)) at the four others
    for (double h : {0.5, 0.01, 1e-5}) {
        const double big = 180.0 - 2.0 * std::atan(h) * kDeg;
        const double small = std::atan(h * std::sqrt(2.0 + h * h)) * kDeg;
        expect_angles(pts({1, 0, 0, -1, 0, 0, 0, -1, h, 0, 1, h}), {big, small, small, small, small, big}, 1e-9);
    }
    // a right-angled corner stretched along z: (0,0,0) (1,0,0) (0,1,0)
    // (0,0,L).  The three edges at the origin are 90 degrees; the others lie
    // between a coordinate plane and the slanted face x + y + z / L = 1,
    // whose outward normal is (L, L, 1) / sqrt(2 L^2 + 1)
    const double L = 7.0;
    const auto a = bodt::dihedral_angles(pts({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, L}));
    assert_near(a[0], 90.0, 1e-12);  // (0 1)
    assert_near(a[1], 90.0, 1e-12);  // (0 2)
    assert_near(a[2], 90.0, 1e-12);  // (0 3)
    // edge (1 2): between the base z = 0 and the face through (1,0,0),
    // (0,1,0), (0,0,L), whose normal is (L, L, 1): cos = 1 / sqrt(2 L^2 + 1)
    assert_near(a[3], std::acos(1.0 / std::sqrt(2 * L * L + 1)) * kDeg, 1e-10);
    // edge (1 3): between y = 0 and that face: cos = L / sqrt(2 L^2 + 1)
    assert_near(a[4], std::acos(L / std::sqrt(2 * L * L + 1)) * kDeg, 1e-10);
    assert_near(a[5], std::acos(L / std::sqrt(2 * L * L + 1)) * kDeg, 1e-10);
    // dihedral_range agrees, and gives 0/180 when told the tet is not positive
    const auto r = bodt::dihedral_range(pts({0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 1}), true);
    assert_near(r.min, 45, 1e-10);
    assert_near(r.max, 90, 1e-10);
    const auto bad = bodt::dihedral_range(pts({0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 1}), false);
    assert_true(bad.min == 0.0 && bad.max == 180.0);
}

// --------------------------------------------------------------- meshes

struct Built {
    test_mesh m{};
    bodt::BuiltMesh b;
};

void build(Built& out, int n, double size, tm_cube_filter keep, double jitter, uint64_t seed) {
    assert_int_equal(tm_make_cubes(&out.m, n, size, keep, nullptr, jitter, seed), 0);
    const bodt::MeshArrays a = mesh_arrays(out.m);
    try {
        out.b = bodt::build_mesh(a);
    } catch (const bodt::Error& e) {
        fail_msg("build_mesh: %s", e.what());
    }
}

int keep_l_shape(int i, int j, int, int n, void*) { return !(2 * i >= n && 2 * j >= n); }

// Maps the box [0, 2]^3 onto a ball of radius 1 around (1, 1, 1): each point
// moves along its ray from the centre, the cube shell of "radius" r (max
// norm) onto the sphere of radius r.
void to_ball(test_mesh& m) {
    for (int32_t v = 0; v < m.nverts; ++v) {
        double* p = &m.xyz[3 * v];
        double q[3] = {p[0] - 1, p[1] - 1, p[2] - 1};
        const double inf = std::max({std::fabs(q[0]), std::fabs(q[1]), std::fabs(q[2])});
        const double two = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        if (two > 0)
            for (int k = 0; k < 3; ++k) p[k] = q[k] * inf / two;
        else
            for (int k = 0; k < 3; ++k) p[k] = 0;
    }
}

using Key = std::array<int32_t, 3>;

Key sorted(int32_t a, int32_t b, int32_t c) {
    Key k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
}

void test_neighbors_brute_force(void**) {
    for (int shape = 0; shape < 2; ++shape) {
        Built bm;
        build(bm, 4, 1.0, shape ? keep_l_shape : nullptr, 0.25, 17 + shape);
        const bodt::TetMesh& mesh = bm.b.mesh;
        assert_int_equal(mesh.num_tets(), bm.m.ntets);
        // brute force: every face of every tet, by its sorted vertices
        std::map<Key, std::vector<std::pair<int32_t, int>>> faces;
        for (int32_t t = 0; t < mesh.num_tets(); ++t)
            for (int i = 0; i < 4; ++i) {
                std::vector<int32_t> f;
                for (int j = 0; j < 4; ++j)
                    if (j != i) f.push_back(mesh.tets[t][j]);
                faces[sorted(f[0], f[1], f[2])].push_back({t, i});
            }
        int boundary = 0;
        for (int32_t t = 0; t < mesh.num_tets(); ++t)
            for (int i = 0; i < 4; ++i) {
                std::vector<int32_t> f;
                for (int j = 0; j < 4; ++j)
                    if (j != i) f.push_back(mesh.tets[t][j]);
                const auto& owners = faces[sorted(f[0], f[1], f[2])];
                assert_true(owners.size() == 1 || owners.size() == 2);
                int32_t expected = -1;
                for (const auto& o : owners)
                    if (o.first != t) expected = o.first;
                if (mesh.neighbors[t][i] != expected)
                    fail_msg("tet %d face %d: neighbour %d, brute force %d", t, i, mesh.neighbors[t][i], expected);
                boundary += expected < 0;
            }
        // the Kuhn box has 12 n^2 boundary triangles; the L has more
        if (!shape) assert_int_equal(boundary, 12 * 16);
        // vertex stars
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            std::vector<int32_t> star(mesh.star_begin(v), mesh.star_end(v)), expected;
            for (int32_t t = 0; t < mesh.num_tets(); ++t)
                if (std::count(mesh.tets[t].begin(), mesh.tets[t].end(), v)) expected.push_back(t);
            std::sort(star.begin(), star.end());
            assert_true(star == expected);
        }
        // every stored tet is positively oriented
        for (int32_t t = 0; t < mesh.num_tets(); ++t) {
            const auto p = mesh.tet_points(t);
            assert_int_equal(bodt::orient(p[0], p[1], p[2], p[3]).sign, 1);
        }
        tm_free(&bm.m);
    }
}

// One-rings of every boundary vertex against brute force: the boundary
// faces (faces of one tet, oriented away from the tet's fourth vertex), each
// vertex's outward normal (the sum of its faces' area vectors) and its
// boundary neighbours.
void check_one_rings(const bodt::TetMesh& mesh, const bodt::BoundarySurface& surface, const char* name) {
    std::map<Key, std::vector<std::pair<int32_t, int>>> faces;
    for (int32_t t = 0; t < mesh.num_tets(); ++t)
        for (int i = 0; i < 4; ++i) {
            std::vector<int32_t> f;
            for (int j = 0; j < 4; ++j)
                if (j != i) f.push_back(mesh.tets[t][j]);
            faces[sorted(f[0], f[1], f[2])].push_back({t, i});
        }
    const int32_t nv = mesh.num_vertices();
    std::vector<Vec3> normal(nv, Vec3::Zero());
    std::vector<std::set<int32_t>> nbrs(nv);
    std::set<std::array<int32_t, 3>> oriented;  // (a, b, c) and its rotations
    int nfaces = 0;
    for (const auto& [key, owners] : faces) {
        if (owners.size() != 1) continue;
        ++nfaces;
        const auto [t, i] = owners[0];
        std::array<int32_t, 3> f = key;
        const Vec3& a = mesh.points[f[0]];
        Vec3 n = (mesh.points[f[1]] - a).cross(mesh.points[f[2]] - a);
        if (n.dot(mesh.points[mesh.tets[t][i]] - a) > 0) {
            std::swap(f[1], f[2]);
            n = -n;
        }
        for (int k = 0; k < 3; ++k) {
            normal[f[k]] += n;
            nbrs[f[k]].insert(f[(k + 1) % 3]);
            nbrs[f[k]].insert(f[(k + 2) % 3]);
            oriented.insert({f[k], f[(k + 1) % 3], f[(k + 2) % 3]});
        }
    }
    assert_int_equal(surface.num_faces(), nfaces);
    std::vector<int32_t> ring;
    int checked = 0;
    for (int32_t v = 0; v < nv; ++v) {
        surface.one_ring(v, ring);
        if (nbrs[v].empty()) {
            if (!ring.empty()) fail_msg("%s: interior vertex %d has a ring of %zu", name, v, ring.size());
            continue;
        }
        ++checked;
        const std::set<int32_t> as_set(ring.begin(), ring.end());
        if (as_set.size() != ring.size() || as_set != nbrs[v])
            fail_msg("%s: vertex %d: ring of %zu (%zu distinct), %zu boundary neighbours", name, v, ring.size(),
                     as_set.size(), nbrs[v].size());
        const Vec3& x0 = mesh.points[v];
        for (size_t k = 0; k < ring.size(); ++k) {
            const int32_t y0 = ring[k], y1 = ring[(k + 1) % ring.size()];
            // (v, y_i, y_{i+1}) is an outward boundary face ...
            if (!oriented.count({v, y0, y1}))
                fail_msg("%s: vertex %d: (%d, %d, %d) is not an outward boundary face", name, v, v, y0, y1);
            // ... and turns positively around the outward normal
            const double turn = (mesh.points[y0] - x0).cross(mesh.points[y1] - x0).dot(normal[v]);
            if (!(turn > 0)) fail_msg("%s: vertex %d, ring %zu: turn %g", name, v, k, turn);
        }
    }
    assert_true(checked > 0);
    // not a mesh vertex: empty
    surface.one_ring(-1, ring);
    assert_true(ring.empty());
    surface.one_ring(nv, ring);
    assert_true(ring.empty());
}

void test_one_ring_box(void**) {
    Built bm;
    build(bm, 3, 1.0, nullptr, 0.25, 5);
    check_one_rings(bm.b.mesh, bm.b.surfaces.surface(0), "box");
    tm_free(&bm.m);
}

void test_one_ring_l_shape(void**) {
    Built bm;
    build(bm, 4, 1.0, keep_l_shape, 0.25, 6);
    check_one_rings(bm.b.mesh, bm.b.surfaces.surface(0), "L-shape");
    tm_free(&bm.m);
}

void test_one_ring_ball(void**) {
    Built bm;
    assert_int_equal(tm_make_cubes(&bm.m, 4, 2.0, nullptr, nullptr, 0.0, 1), 0);
    to_ball(bm.m);
    const bodt::MeshArrays a = mesh_arrays(bm.m);
    try {
        bm.b = bodt::build_mesh(a);
    } catch (const bodt::Error& e) {
        fail_msg("build_mesh (ball): %s", e.what());
    }
    assert_false(bm.b.flipped);
    // every boundary vertex is on the unit sphere
    for (int32_t v = 0; v < bm.m.nverts; ++v)
        if (bm.m.boundary[v]) assert_near(bm.b.mesh.points[v].norm(), 1.0, 1e-12);
    check_one_rings(bm.b.mesh, bm.b.surfaces.surface(0), "ball");
    tm_free(&bm.m);
}

// A mesh given in negative orientation is stored flipped; rings still turn
// around the outward normal.
void test_one_ring_negative_input(void**) {
    test_mesh m{};
    assert_int_equal(tm_make_cubes(&m, 3, 1.0, keep_l_shape, nullptr, 0.2, 9), 0);
    for (int32_t t = 0; t < m.ntets; ++t) std::swap(m.tets[4 * t + 2], m.tets[4 * t + 3]);
    const bodt::MeshArrays a = mesh_arrays(m);
    const bodt::BuiltMesh b = bodt::build_mesh(a);
    assert_true(b.flipped);
    check_one_rings(b.mesh, b.surfaces.surface(0), "negative L-shape");
    tm_free(&m);
}

// ------------------------------------------------------------ pinches

int keep_diagonal_pair(int i, int j, int k, int, void*) {
    return (i == 0 && j == 0 && k == 0) || (i == 1 && j == 1 && k == 1);
}
int keep_edge_pair(int i, int j, int k, int, void*) { return k == 0 && ((i == 0 && j == 0) || (i == 1 && j == 1)); }

void expect_surface_refused(tm_cube_filter keep, const char* part) {
    test_mesh m{};
    assert_int_equal(tm_make_cubes(&m, 2, 2.0, keep, nullptr, 0.0, 1), 0);
    assert_int_equal(m.ntets, 12);
    bodt::TetMesh mesh;
    for (int32_t v = 0; v < m.nverts; ++v) mesh.points.emplace_back(m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]);
    for (int32_t t = 0; t < m.ntets; ++t)
        mesh.tets.push_back({m.tets[4 * t], m.tets[4 * t + 1], m.tets[4 * t + 2], m.tets[4 * t + 3]});
    mesh.regions.assign(mesh.tets.size(), 0);
    mesh.build_topology(0);  // the connectivity itself is fine
    bodt::BoundarySurface surface;
    bool thrown = false;
    try {
        surface.build(mesh, 0, 0);
    } catch (const bodt::Error& e) {
        thrown = true;
        assert_int_equal(e.status(), BODT_ERR_BAD_MESH);
        assert_contains(e.what(), part);
    }
    assert_true(thrown);
    // A Tolerant build leaves out the faces around the pinch: rings there
    // are open, or empty where no face is left, and asking for them is safe.
    surface.build(mesh, 0, 0, bodt::BoundarySurface::Strictness::Tolerant);
    assert_false(surface.blocked().empty());
    std::vector<int32_t> ring;
    int empty = 0;
    for (int32_t v : surface.blocked()) {
        surface.one_ring(v, ring);
        empty += ring.empty();
    }
    assert_true(empty > 0);
    // build_mesh refuses it the same way
    const bodt::MeshArrays a = mesh_arrays(m);
    thrown = false;
    try {
        bodt::build_mesh(a);
    } catch (const bodt::Error& e) {
        thrown = true;
        assert_int_equal(e.status(), BODT_ERR_BAD_MESH);
        assert_contains(e.what(), part);
    }
    assert_true(thrown);
    tm_free(&m);
}

void test_surface_refuses_pinches(void**) {
    // two cubes meeting at one corner: the shared vertex is number 7 (the
    // centre (1,1,1) of the 3 x 3 x 3 grid is the 8th vertex in use)
    expect_surface_refused(keep_diagonal_pair, "not a manifold surface at vertex 7");
    // two cubes meeting along an edge
    expect_surface_refused(keep_edge_pair, "not a manifold surface at edge");
}

// ------------------------------------------------------------ curve order

void assert_inverse(const bodt::CallerNumbering& c, size_t nverts, size_t ntets) {
    assert_int_equal(c.vertex_to_caller.size(), nverts);
    assert_int_equal(c.vertex_from_caller.size(), nverts);
    assert_int_equal(c.tet_to_caller.size(), ntets);
    for (size_t v = 0; v < nverts; ++v) assert_int_equal(c.vertex_from_caller[c.vertex_to_caller[v]], v);
    std::vector<int32_t> tets = c.tet_to_caller;
    std::sort(tets.begin(), tets.end());
    for (size_t t = 0; t < ntets; ++t) assert_int_equal(tets[t], t);
}

// The points of an 8^3 grid, numbered by a scrambling bijection: along the
// curve each point is a grid neighbour of the one before.
void test_curve_order_hilbert(void**) {
    const int32_t n = 512;
    std::vector<double> xyz(3 * n);
    for (int32_t g = 0; g < n; ++g) {
        const int32_t v = (g * 7919) % n;  // 7919 is odd: a bijection of [0, 512)
        xyz[3 * v] = g % 8;
        xyz[3 * v + 1] = (g / 8) % 8;
        xyz[3 * v + 2] = g / 64;
    }
    const int32_t tet[4] = {1, 2, 3, 4};
    const bodt::CallerNumbering c = bodt::curve_order(n, xyz.data(), 1, tet, 1);
    assert_inverse(c, n, 1);
    for (int32_t v = 1; v < n; ++v) {
        const double* a = &xyz[3 * c.vertex_to_caller[v - 1]];
        const double* b = &xyz[3 * c.vertex_to_caller[v]];
        const double step = std::fabs(a[0] - b[0]) + std::fabs(a[1] - b[1]) + std::fabs(a[2] - b[2]);
        if (step != 1.0) fail_msg("curve step %d jumps by %g", v, step);
    }
}

void test_curve_order_tets(void**) {
    test_mesh m{};
    assert_int_equal(tm_make_cubes(&m, 4, 1.0, nullptr, nullptr, 0.2, 3), 0);
    const bodt::CallerNumbering c = bodt::curve_order(m.nverts, m.xyz, m.ntets, m.tets, 0);
    assert_inverse(c, static_cast<size_t>(m.nverts), static_cast<size_t>(m.ntets));
    const auto first = [&](int32_t caller) {
        int32_t f = m.nverts;
        for (int k = 0; k < 4; ++k) f = std::min(f, c.vertex_from_caller[m.tets[4 * caller + k]]);
        return f;
    };
    for (int32_t t = 1; t < m.ntets; ++t) {
        const int32_t a = c.tet_to_caller[t - 1], b = c.tet_to_caller[t];
        assert_true(first(a) < first(b) || (first(a) == first(b) && a < b));
    }
    // Deterministic: the same input, the same order.
    const bodt::CallerNumbering again = bodt::curve_order(m.nverts, m.xyz, m.ntets, m.tets, 0);
    assert_true(again.vertex_to_caller == c.vertex_to_caller && again.tet_to_caller == c.tet_to_caller);
    // Input the validation must name in the caller's order stays in it.
    m.tets[5] = m.nverts;
    assert_true(bodt::curve_order(m.nverts, m.xyz, m.ntets, m.tets, 0).is_identity());
    m.tets[5] = 0;
    m.xyz[4] = NAN;
    assert_true(bodt::curve_order(m.nverts, m.xyz, m.ntets, m.tets, 0).is_identity());
    tm_free(&m);
}

void test_curve_order_mesh(void**) {
    test_mesh m{};
    assert_int_equal(tm_make_cubes(&m, 4, 1.0, nullptr, nullptr, 0.2, 3), 0);
    const bodt::MeshArrays a = mesh_arrays(m);
    const bodt::BuiltMesh b = bodt::build_mesh_in_curve_order(a);
    const bodt::TetMesh& mesh = b.mesh;
    assert_false(mesh.caller.is_identity());
    bool moved = false;
    for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
        const int32_t c = mesh.caller_vertex(v);
        assert_int_equal(mesh.internal_vertex(c), v);
        moved = moved || c != v;
        for (int k = 0; k < 3; ++k) assert_true(mesh.points[v][k] == m.xyz[3 * c + k]);
        for (const int32_t* t = mesh.star_begin(v) + 1; t < mesh.star_end(v); ++t)
            assert_true(mesh.caller_tet(t[-1]) < mesh.caller_tet(t[0]));
    }
    assert_true(moved);
    for (int32_t t = 0; t < mesh.num_tets(); ++t)
        for (int k = 0; k < 4; ++k)
            assert_int_equal(mesh.caller_vertex(mesh.tets[t][k]), m.tets[4 * mesh.caller_tet(t) + k]);
    tm_free(&m);
}


// ---------------------------------------------------------- coloured sweep

// The other vertices of v's tets.
std::set<int32_t> neighbours_of(const bodt::TetMesh& mesh, int32_t v) {
    std::set<int32_t> out;
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
        for (const int32_t u : mesh.tets[*t])
            if (u != v) out.insert(u);
    return out;
}

void test_coloured_sweep_order(void**) {
    test_mesh m{};
    assert_int_equal(tm_make_box(&m, 24, 0.2, 5), 0);  // 15625 vertices: room for 3 threads
    const bodt::BuiltMesh b = bodt::build_mesh_in_curve_order(mesh_arrays(m));
    const bodt::TetMesh& mesh = b.mesh;
    const bodt::VertexColouring& colouring = mesh.colouring();
    const int32_t n = mesh.num_vertices();
    for (int32_t v = 0; v < n; ++v) {
        int32_t lower = 0;
        for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
            for (const int32_t u : mesh.tets[*t]) lower += colouring.colour[u] < colouring.colour[v];
        assert_int_equal(colouring.lower[v], lower);
        assert_true(colouring.colour[v] >= 0 && colouring.colour[v] < colouring.colours());
        for (const int32_t u : neighbours_of(mesh, v)) assert_int_not_equal(colouring.colour[u], colouring.colour[v]);
    }
    for (const int threads : {1, 2, 3}) {
        // Each visit takes a ticket when it starts and marks its vertex busy
        // until it ends; the threads record what they saw, checked after.
        std::unique_ptr<std::atomic<int32_t>[]> ticket(new std::atomic<int32_t>[n]);
        std::unique_ptr<std::atomic<int32_t>[]> busy(new std::atomic<int32_t>[n]);
        for (int32_t v = 0; v < n; ++v) ticket[v] = -1, busy[v] = 0;
        std::atomic<int32_t> next{0}, visits{0}, overlaps{0};
        struct State {
            int32_t visited = 0;
        };
        const auto states = bodt::coloured_sweep(mesh, threads, State{}, [&](State& s, int32_t v, int32_t c) {
            assert_true(c == colouring.colour[v]);
            busy[v] = 1;
            ticket[v] = next++;
            ++visits;
            ++s.visited;
            for (const int32_t u : neighbours_of(mesh, v)) overlaps += busy[u].load();
            busy[v] = 0;
        });
        assert_true(states.size() == static_cast<size_t>(threads));  // n allows them all
        int32_t visited = 0;
        for (const State& s : states) visited += s.visited;
        assert_int_equal(visited, n);
        assert_int_equal(visits.load(), n);
        assert_int_equal(overlaps.load(), 0);
        for (int32_t v = 0; v < n; ++v) {
            assert_true(ticket[v] >= 0);
            for (const int32_t u : neighbours_of(mesh, v))
                if (colouring.colour[u] < colouring.colour[v]) assert_true(ticket[u] < ticket[v]);
        }
        // A visit that throws stops the sweep; the error comes out.
        std::atomic<int32_t> after{0};
        bool thrown = false;
        try {
            bodt::coloured_sweep(mesh, threads, State{}, [&](State&, int32_t v) {
                if (v == n / 2) throw std::runtime_error("stop");
                ++after;
            });
        } catch (const std::runtime_error& e) {
            thrown = std::string(e.what()) == "stop";
        }
        assert_true(thrown);
        assert_true(after.load() < n - 1);
    }
    tm_free(&m);
}


// ------------------------------------------------------------- move guard

struct GuardVerdict {
    bodt::MoveOutcome outcome;
    Vec3 at;
    double distance;
};

// The guard as its header states it, tet by tet.
GuardVerdict reference_guard(const bodt::TetMesh& mesh, int32_t v, const Vec3& target, const bodt::GuardSettings& s,
                             double largest_cosine) {
    std::vector<bodt::TetShape> before;
    double of_min = -1.0, of_max = 1.0;
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t) {
        before.push_back(bodt::tet_shape(mesh.tet_points(*t)));
        of_min = std::max(of_min, before.back().cosines.of_min);
        of_max = std::min(of_max, before.back().cosines.of_max);
    }
    of_max = std::min(of_max, largest_cosine);  // the largest angle allowed
    const Vec3 start = mesh.points[v];
    Vec3 step = target - start;
    for (int attempt = 0; attempt <= s.backtrack_steps; ++attempt, step *= 0.5) {
        const Vec3 x = start + step;
        bool ok = true;
        size_t k = 0;
        for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v) && ok; ++t, ++k) {
            bodt::TetPoints p = mesh.tet_points(*t);
            for (Vec3& c : p)
                if (c == start) c = x;
            const bodt::TetKernel kernel = bodt::tet_kernel(p);
            const bodt::TetShape shape = bodt::shape_of(kernel);
            ok = kernel.sign > 0 && !(shape.stretch < std::min(s.min_stretch, before[k].stretch)) &&
                 !(s.never_worse && (shape.cosines.of_min > of_min || shape.cosines.of_max < of_max));
        }
        if (ok) return {attempt == 0 ? bodt::MoveOutcome::Moved : bodt::MoveOutcome::Shortened, x, step.norm()};
    }
    return {bodt::MoveOutcome::Rejected, start, 0.0};
}

void test_move_guard_reference(void**) {
    test_mesh m{};
    assert_int_equal(tm_make_box(&m, 8, 0.3, 17), 0);
    const bodt::BuiltMesh built = bodt::build_mesh_in_curve_order(mesh_arrays(m));
    tm_rng rng;
    tm_rng_seed(&rng, 99);
    int counts[3] = {0, 0, 0};
    for (const bool never_worse : {true, false})
        for (const bool cached : {true, false}) {
            bodt::TetMesh mesh = built.mesh;
            const bodt::GuardSettings settings{1e-3, 6, never_worse};
            bodt::ShapeCache shapes = bodt::tet_shapes(mesh, 1);
            bodt::MoveGuard guard(settings, cached ? &shapes : nullptr);
            const std::vector<bodt::FaceKey> no_faces;
            for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
                const Vec3 p = mesh.points[v];
                if ((p.array() < 1e-12).any() || (p.array() > 1.0 - 1e-12).any()) continue;  // the box's surface
                // Up to 1.5 cube sizes (1/8) in a random direction: many
                // moves are shortened or refused.
                const Vec3 d(tm_rng_uniform(&rng) - 0.5, tm_rng_uniform(&rng) - 0.5, tm_rng_uniform(&rng) - 0.5);
                const Vec3 target = p + (1.5 / 8.0) * tm_rng_uniform(&rng) * d.normalized();
                // Every other move may let the star's largest angle grow to 100..150 degrees.
                const double largest = v % 2 ? 1.0 : std::cos((100.0 + 50.0 * tm_rng_uniform(&rng)) / kDeg);
                const GuardVerdict want = reference_guard(mesh, v, target, settings, largest);
                double distance = -1.0;
                guard.star().gather(mesh, v);
                const bodt::MoveOutcome got = guard.move_gathered(mesh, v, target, no_faces, distance, largest);
                assert_int_equal(static_cast<int>(got), static_cast<int>(want.outcome));
                assert_true(mesh.points[v] == want.at);
                assert_true(distance == want.distance);
                ++counts[static_cast<int>(got)];
                if (cached)
                    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t) {
                        const bodt::TetShape now = bodt::tet_shape(mesh.tet_points(*t));
                        const bodt::TetShape& kept = shapes[static_cast<size_t>(*t)];
                        assert_true(kept.stretch == now.stretch && kept.cosines.of_min == now.cosines.of_min &&
                                    kept.cosines.of_max == now.cosines.of_max);
                    }
            }
        }
    print_message("guard: %d moved, %d shortened, %d refused\n", counts[0], counts[1], counts[2]);
    for (const int c : counts) assert_true(c > 50);
    tm_free(&m);
}

}  // namespace

int main() {
    const CMUnitTest tests[] = {
        cmocka_unit_test(test_orient_clear_signs),
        cmocka_unit_test(test_orient_flat),
        cmocka_unit_test(test_dihedral_angles),
        cmocka_unit_test(test_neighbors_brute_force),
        cmocka_unit_test(test_one_ring_box),
        cmocka_unit_test(test_one_ring_l_shape),
        cmocka_unit_test(test_one_ring_ball),
        cmocka_unit_test(test_one_ring_negative_input),
        cmocka_unit_test(test_surface_refuses_pinches),
        cmocka_unit_test(test_curve_order_hilbert),
        cmocka_unit_test(test_curve_order_tets),
        cmocka_unit_test(test_curve_order_mesh),
        cmocka_unit_test(test_coloured_sweep_order),
        cmocka_unit_test(test_move_guard_reference),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
