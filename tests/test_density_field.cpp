// test_density_field: white-box tests of paper 002's target density field
// (links bodt_core): the vertex density (sec. 3.2), the regular grid of
// eq. (3.2) with its cell means, and the density error of eq. (4.1).  The
// reference values are computed here from the test meshes' raw arrays.
//
//   vertex_density     every vertex of a uniform Kuhn box against the mean of
//                      1/|e| over its neighbours collected here; a corner, a
//                      box-edge vertex and an interior vertex against the
//                      hand-counted edges (h, h sqrt 2, h sqrt 3); an unused
//                      vertex gets 0
//   linear_field       density a + b.x reproduced at every grid point inside
//                      a jittered box with a corner block cut out (1e-12),
//                      0 at every point outside it; grid origin, spacing
//                      and dims as documented
//   aligned_grid       the same on a grid whose points lie on the tets'
//                      shared faces, edges and vertices (the tolerance)
//   inverted_skipped   a grid point inside an inverted tet gets 0, one
//                      inside a positive tet its interpolated value
//   cell_means         at() = mean of the corners > 0 and finite (zeros,
//                      negatives, NaN and inf ignored); 0 for a cell with
//                      none; an empty grid gives 0
//   at_clamps          points outside the grid (and NaN, inf) take the
//                      nearest cell; the grid's upper faces the last cell
//   rejects            the given-grid constructor and interpolate() refuse
//                      bad dims, sizes, spacings, origins, densities and
//                      max_points with BODT_ERR_INVALID_ARGUMENT
//   density_error      eq. (4.1) against a constant grid and a half-empty
//                      grid, mean / max / count computed here over the
//                      mesh's edges; a grid from the mesh's own density
//                      covers every edge
//   max_points         the spacing grows uniformly until the grid fits, the
//                      grid still covers the mesh and interpolates exactly
#include "bodt.h"
#include "common/error.hpp"
#include "mesh/mesh_builder.hpp"
#include "mesh/tet_mesh.hpp"
#include "pipeline/density_field.hpp"

#include "mesh_gen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "test_util.h"

namespace {

using bodt::DensityGrid;
using bodt::TetMesh;
using bodt::Vec3;

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------ meshes

struct Built {
    test_mesh m{};
    TetMesh mesh;
    Built() = default;
    ~Built() { tm_free(&m); }
    Built(const Built&) = delete;
    Built& operator=(const Built&) = delete;
};

void build_from(Built& out, int extra_points = 0) {
    std::vector<double> xyz(out.m.xyz, out.m.xyz + 3 * out.m.nverts);
    for (int i = 0; i < extra_points; ++i) {
        xyz.push_back(5.0 + i);
        xyz.push_back(-7.0);
        xyz.push_back(3.0);
    }
    bodt::MeshArrays a;
    a.nverts = out.m.nverts + extra_points;
    a.xyz = xyz.data();
    a.ntets = out.m.ntets;
    a.tets = out.m.tets;
    try {
        bodt::BuiltMesh b = bodt::build_mesh(a);
        assert_false(b.flipped);
        out.mesh = std::move(b.mesh);
    } catch (const bodt::Error& e) {
        fail_msg("build_mesh: %s", e.what());
    }
}

// tm_make_cubes (retrying seeds when the jitter inverts a tet), built.
void make_cubes(Built& out, int n, double size, tm_cube_filter keep, double jitter, uint64_t seed,
                int extra_points = 0) {
    for (uint64_t s = seed; s < seed + 200; ++s) {
        const int st = tm_make_cubes(&out.m, n, size, keep, nullptr, jitter, s);
        if (st == 0) {
            build_from(out, extra_points);
            return;
        }
        if (st != -2) fail_msg("tm_make_cubes: %d", st);
    }
    fail_msg("no seed gave a valid mesh");
}

Vec3 raw_point(const test_mesh& m, int32_t v) { return Vec3(m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]); }

// The distinct edges of the raw tets, as (smaller, larger) vertex pairs.
std::set<std::pair<int32_t, int32_t>> raw_edges(const test_mesh& m) {
    std::set<std::pair<int32_t, int32_t>> edges;
    for (int32_t t = 0; t < m.ntets; ++t)
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                int32_t a = m.tets[4 * t + i], b = m.tets[4 * t + j];
                if (a > b) std::swap(a, b);
                edges.insert({a, b});
            }
    return edges;
}

int32_t find_vertex(const test_mesh& m, const Vec3& x) {
    for (int32_t v = 0; v < m.nverts; ++v)
        if ((raw_point(m, v) - x).norm() < 1e-12) return v;
    fail_msg("no vertex at (%g, %g, %g)", x.x(), x.y(), x.z());
    return -1;
}

// The status of the Error that f throws (0: none); the message in *msg.
int thrown_status(const std::function<void()>& f, std::string* msg) {
    try {
        f();
    } catch (const bodt::Error& e) {
        if (msg) *msg = e.what();
        return e.status();
    }
    return 0;
}

#define assert_invalid(expr, needle)                                                                   \
    do {                                                                                               \
        std::string m_;                                                                                \
        const int s_ = thrown_status([&] { (void)(expr); }, &m_);                                      \
        if (s_ != BODT_ERR_INVALID_ARGUMENT) fail_msg("%s: status %d, expected %d", #expr, s_,         \
                                                      (int)BODT_ERR_INVALID_ARGUMENT);                 \
        assert_contains(m_.c_str(), needle);                                                           \
    } while (0)

Vec3 grid_point(const DensityGrid& g, int64_t i, int64_t j, int64_t k) {
    return Vec3(g.origin().x() + static_cast<double>(i) * g.spacing().x(),
                g.origin().y() + static_cast<double>(j) * g.spacing().y(),
                g.origin().z() + static_cast<double>(k) * g.spacing().z());
}

int64_t num_points(const DensityGrid& g) {
    return int64_t(g.dims()[0]) * g.dims()[1] * g.dims()[2];
}

// For every grid point: inside(x) says whether x is in the domain (with the
// distance to its boundary in *margin); inside points must hold a + b.x to
// 1e-12, outside ones 0.  Points within 1e-9 of the boundary are not
// checked; returns the number checked inside.
int64_t check_linear(const DensityGrid& g, double a, const Vec3& b,
                     const std::function<bool(const Vec3&, double*)>& inside) {
    assert_int_equal(static_cast<int64_t>(g.point_values().size()), num_points(g));
    int64_t in = 0, out = 0, skipped = 0;
    for (int64_t k = 0; k < g.dims()[2]; ++k)
        for (int64_t j = 0; j < g.dims()[1]; ++j)
            for (int64_t i = 0; i < g.dims()[0]; ++i) {
                const Vec3 x = grid_point(g, i, j, k);
                const double v = g.point_values()[static_cast<size_t>(i + g.dims()[0] * (j + g.dims()[1] * k))];
                double margin = 0.0;
                const bool is_in = inside(x, &margin);
                if (margin < 1e-9) {
                    ++skipped;
                    continue;
                }
                if (is_in) {
                    assert_near(v, a + b.dot(x), 1e-12);
                    ++in;
                } else {
                    if (v != 0.0) fail_msg("point (%g, %g, %g) outside the mesh has %.17g", x.x(), x.y(), x.z(), v);
                    ++out;
                }
            }
    assert_true(in > 0);
    assert_true(out > 0);
    return in;
}

// The unit box minus the open corner block (0.5, 1]^3.
bool in_box_minus_corner(const Vec3& x, double* margin) {
    double m = kInf;
    bool in_box = true, in_block = true;
    for (int a = 0; a < 3; ++a) {
        m = std::min({m, std::abs(x[a]), std::abs(x[a] - 1.0), std::abs(x[a] - 0.5)});
        in_box = in_box && x[a] >= 0.0 && x[a] <= 1.0;
        in_block = in_block && x[a] > 0.5;
    }
    *margin = m;
    return in_box && !in_block;
}

bool in_unit_box(const Vec3& x, double* margin) {
    double m = kInf;
    bool in = true;
    for (int a = 0; a < 3; ++a) {
        m = std::min({m, std::abs(x[a]), std::abs(x[a] - 1.0)});
        in = in && x[a] >= 0.0 && x[a] <= 1.0;
    }
    *margin = m;
    return in;
}

int keep_all_but_corner(int i, int j, int k, int n, void*) { return !(2 * i >= n && 2 * j >= n && 2 * k >= n); }

std::vector<double> linear_density(const TetMesh& mesh, double a, const Vec3& b) {
    std::vector<double> d(mesh.points.size());
    for (size_t v = 0; v < d.size(); ++v) d[v] = a + b.dot(mesh.points[v]);
    return d;
}

// ------------------------------------------------------------ tests

void test_vertex_density(void**) {
    const int n = 3;
    const double h = 1.0 / n;
    Built b;
    make_cubes(b, n, 1.0, nullptr, 0.0, 1, 1);  // one unused vertex appended
    const std::vector<double> d = bodt::vertex_density(b.mesh);
    assert_int_equal(d.size(), b.m.nverts + 1);
    assert_true(d[b.m.nverts] == 0.0);

    // Every vertex against its neighbours collected from the raw tets.
    std::vector<std::set<int32_t>> nb(b.m.nverts);
    for (const auto& e : raw_edges(b.m)) {
        nb[e.first].insert(e.second);
        nb[e.second].insert(e.first);
    }
    for (int32_t v = 0; v < b.m.nverts; ++v) {
        assert_false(nb[v].empty());
        double s = 0.0;
        for (int32_t u : nb[v]) s += 1.0 / (raw_point(b.m, v) - raw_point(b.m, u)).norm();
        assert_near(d[v], s / static_cast<double>(nb[v].size()), 1e-12 * d[v]);
    }

    // By hand.  The Kuhn tets of a cube follow paths 000 -> e_a -> e_a + e_b
    // -> 111, so the face diagonals and the cube diagonal run in the +
    // direction of every axis.
    const double s2 = std::sqrt(2.0), s3 = std::sqrt(3.0);
    // The corners 000 and 111: 3 axis edges, 3 face diagonals, 1 diagonal.
    const double corner = (3.0 / h + 3.0 / (h * s2) + 1.0 / (h * s3)) / 7.0;
    assert_near(d[find_vertex(b.m, Vec3(0, 0, 0))], corner, 1e-12 * corner);
    assert_near(d[find_vertex(b.m, Vec3(1, 1, 1))], corner, 1e-12 * corner);
    // The corner 100: 3 axis edges and the diagonal of the face x = 1.
    const double corner100 = (3.0 / h + 1.0 / (h * s2)) / 4.0;
    assert_near(d[find_vertex(b.m, Vec3(1, 0, 0))], corner100, 1e-12 * corner100);
    // On the box edge y = z = 0, at x = h: 4 axis edges (to x = 0, x = 2h, +y,
    // +z), the 3 face diagonals that start there in the cube at (h, 0, 0)
    // (the cube at 0 only adds its face x = h diagonal, the same +y+z one)
    // and that cube's diagonal.
    const double edge_v = (4.0 / h + 3.0 / (h * s2) + 1.0 / (h * s3)) / 8.0;
    assert_near(d[find_vertex(b.m, Vec3(h, 0, 0))], edge_v, 1e-12 * edge_v);
    // Interior: 6 axis edges, 6 face diagonals, 2 cube diagonals.
    const double interior = (6.0 / h + 6.0 / (h * s2) + 2.0 / (h * s3)) / 14.0;
    assert_near(d[find_vertex(b.m, Vec3(h, h, h))], interior, 1e-12 * interior);
    assert_near(d[find_vertex(b.m, Vec3(2 * h, h, 2 * h))], interior, 1e-12 * interior);

    // Scaling the mesh by s scales the density by 1 / s.
    TetMesh scaled = b.mesh;
    for (Vec3& p : scaled.points) p *= 4.0;
    const std::vector<double> ds = bodt::vertex_density(scaled);
    for (int32_t v = 0; v < b.m.nverts; ++v) assert_near(ds[v], d[v] / 4.0, 1e-12 * d[v]);
}

void test_linear_field(void**) {
    Built b;
    make_cubes(b, 4, 1.0, keep_all_but_corner, 0.25, 11);
    // The jitter moved interior vertices only.
    bool moved = false;
    for (int32_t v = 0; v < b.m.nverts; ++v) {
        const Vec3 p = raw_point(b.m, v) * 4.0;
        moved = moved || (p - p.array().round().matrix()).norm() > 1e-3;
    }
    assert_true(moved);

    const double a = 2.0;
    const Vec3 slope(0.3, -0.5, 0.7);
    const double h = 0.07;
    const DensityGrid g = DensityGrid::interpolate(b.mesh, linear_density(b.mesh, a, slope), h);
    assert_false(g.empty());
    for (int ax = 0; ax < 3; ++ax) {
        assert_true(g.spacing()[ax] == h);
        assert_near(g.origin()[ax], -h / 2, 1e-15);
        // ceil((1 + h) / h) + 1 = ceil(15.29) + 1
        assert_int_equal(g.dims()[ax], 17);
    }
    const int64_t in = check_linear(g, a, slope, in_box_minus_corner);
    // Points inside: 14 per axis in [0, 1] (0.035 ... 0.945), minus those in
    // the cut block (0.525 ... 0.945: 7 per axis).
    assert_int_equal(in, 14 * 14 * 14 - 7 * 7 * 7);

    // at(): a cell whose corners are all inside holds their mean, which for
    // a linear field is the value at the cell centre.
    const Vec3 x(0.2, 0.3, 0.1);
    const Vec3 c0 = grid_point(g, static_cast<int64_t>(std::floor((x.x() + h / 2) / h)),
                               static_cast<int64_t>(std::floor((x.y() + h / 2) / h)),
                               static_cast<int64_t>(std::floor((x.z() + h / 2) / h)));
    assert_near(g.at(x), a + slope.dot(c0 + Vec3::Constant(h / 2)), 1e-12);
}

void test_aligned_grid(void**) {
    // Spacing 1/8 on a box of cubes of side 1/4: grid points at odd
    // multiples of 1/16, many on the cubes' diagonals, i.e. on faces and
    // edges shared by several tets.
    Built b;
    make_cubes(b, 4, 1.0, nullptr, 0.0, 1);
    const double a = 1.0;
    const Vec3 slope(0.25, 0.5, -0.125);
    const DensityGrid g = DensityGrid::interpolate(b.mesh, linear_density(b.mesh, a, slope), 0.125);
    for (int ax = 0; ax < 3; ++ax) assert_int_equal(g.dims()[ax], 10);
    const int64_t in = check_linear(g, a, slope, in_unit_box);
    assert_int_equal(in, 8 * 8 * 8);
    // A uniform density is reproduced exactly everywhere inside.
    const DensityGrid u = DensityGrid::interpolate(b.mesh, std::vector<double>(b.mesh.points.size(), 3.5), 0.125);
    check_linear(u, 3.5, Vec3::Zero(), in_unit_box);
}

void test_inverted_skipped(void**) {
    // Two disjoint unit corner tets; the second with its order reversed.
    TetMesh mesh;
    mesh.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                   Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1)};
    mesh.tets = {{0, 1, 2, 3}, {4, 5, 7, 6}};
    const std::vector<double> dens = {1, 2, 3, 4, 5, 6, 7, 8};
    const double h = 0.1;
    const DensityGrid g = DensityGrid::interpolate(mesh, dens, h);
    int64_t in_first = 0, in_second = 0;
    for (int64_t k = 0; k < g.dims()[2]; ++k)
        for (int64_t j = 0; j < g.dims()[1]; ++j)
            for (int64_t i = 0; i < g.dims()[0]; ++i) {
                const Vec3 x = grid_point(g, i, j, k);
                const double v = g.point_values()[static_cast<size_t>(i + g.dims()[0] * (j + g.dims()[1] * k))];
                const Vec3 y = x - Vec3(2, 0, 0);
                if (x.minCoeff() > 1e-9 && x.sum() < 1 - 1e-9) {  // inside the first
                    ++in_first;
                    assert_near(v, 1 + x.x() * (2 - 1) + x.y() * (3 - 1) + x.z() * (4 - 1), 1e-12);
                } else if (y.minCoeff() > 1e-9 && y.sum() < 1 - 1e-9) {  // inside the inverted one
                    ++in_second;
                    assert_true(v == 0.0);
                } else if (x.minCoeff() < -1e-9 || x.sum() > 1 + 1e-9) {
                    if (y.minCoeff() < -1e-9 || y.sum() > 1 + 1e-9) assert_true(v == 0.0);
                }
            }
    assert_true(in_first > 0);
    assert_true(in_second > 0);
}

void test_cell_means(void**) {
    // dims 3 x 2 x 2, x fastest: value index i + 3 (j + 2 k).
    std::vector<double> v(12, 0.0);
    auto at_ijk = [&](int i, int j, int k) -> double& { return v[static_cast<size_t>(i + 3 * (j + 2 * k))]; };
    at_ijk(0, 0, 0) = 4.0;
    at_ijk(0, 1, 0) = 0.0;
    at_ijk(0, 0, 1) = -1.0;
    at_ijk(0, 1, 1) = kNaN;
    at_ijk(1, 0, 0) = kInf;
    at_ijk(1, 1, 0) = 6.0;
    at_ijk(1, 0, 1) = 0.0;
    at_ijk(1, 1, 1) = -3.0;
    // x index 2: all 0
    const DensityGrid g(Vec3(0, 0, 0), Vec3(1, 2, 0.5), {3, 2, 2}, v);
    assert_false(g.empty());
    assert_true(g.dims()[0] == 3 && g.dims()[1] == 2 && g.dims()[2] == 2);
    assert_true(g.spacing() == Vec3(1, 2, 0.5));
    assert_int_equal(g.point_values().size(), 12);
    assert_true(g.point_values()[0] == 4.0);
    // Cell 0: the corners 4 and 6 count.
    assert_near(g.at(Vec3(0.5, 1, 0.25)), 5.0, 0);
    // Cell 1: only 6 counts.
    assert_near(g.at(Vec3(1.5, 1, 0.25)), 6.0, 0);
    assert_near(g.at(Vec3(1.0, 0.0, 0.0)), 6.0, 0);  // on the shared face: the upper cell

    // A cell without a positive finite corner.
    const DensityGrid z(Vec3(-1, -1, -1), Vec3(2, 2, 2), {2, 2, 2}, {0, -1, kNaN, kInf, 0, 0, -kInf, -2});
    assert_true(z.at(Vec3(0, 0, 0)) == 0.0);
    // Every corner positive: the plain mean.
    const DensityGrid p(Vec3(0, 0, 0), Vec3(1, 1, 1), {2, 2, 2}, {1, 2, 3, 4, 5, 6, 7, 8});
    assert_near(p.at(Vec3(0.5, 0.5, 0.5)), 4.5, 1e-15);

    const DensityGrid e;
    assert_true(e.empty());
    assert_true(e.at(Vec3(0, 0, 0)) == 0.0);
}

void test_at_clamps(void**) {
    // 4 x 3 x 2 points (3 x 2 x 1 cells) with value 1 + i + 10 j + 100 k, all
    // positive: the mean of cell (i, j, 0) is 1 + (i + .5) + 10 (j + .5) + 50.
    const std::array<int32_t, 3> dims{4, 3, 2};
    std::vector<double> v;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 4; ++i) v.push_back(1.0 + i + 10.0 * j + 100.0 * k);
    const Vec3 o(-1, 2, 5), s(0.5, 0.25, 2);
    const DensityGrid g(o, s, dims, v);
    auto cell = [](int i, int j) { return 1.0 + (i + 0.5) + 10.0 * (j + 0.5) + 50.0; };
    // Inside.
    assert_near(g.at(Vec3(-0.9, 2.3, 6)), cell(0, 1), 1e-12);
    assert_near(g.at(Vec3(0.2, 2.1, 6)), cell(2, 0), 1e-12);
    // Outside, below and above each axis: the nearest cell.
    assert_near(g.at(Vec3(-50, 2.3, 6)), cell(0, 1), 1e-12);
    assert_near(g.at(Vec3(50, 2.3, 6)), cell(2, 1), 1e-12);
    assert_near(g.at(Vec3(-0.9, -50, 6)), cell(0, 0), 1e-12);
    assert_near(g.at(Vec3(-0.9, 50, 6)), cell(0, 1), 1e-12);
    assert_near(g.at(Vec3(-0.9, 2.3, -1e9)), cell(0, 1), 1e-12);
    assert_near(g.at(Vec3(-0.9, 2.3, 1e9)), cell(0, 1), 1e-12);
    assert_near(g.at(Vec3(1e300, -1e300, 0)), cell(2, 0), 1e-12);
    assert_near(g.at(Vec3(kInf, kInf, kInf)), cell(2, 1), 1e-12);
    assert_near(g.at(Vec3(-kInf, kNaN, 0)), cell(0, 0), 1e-12);
    // The upper faces of the grid belong to the last cells.
    assert_near(g.at(Vec3(0.5, 2.5, 9)), cell(2, 1), 1e-12);
    assert_near(g.at(Vec3(-1, 2, 5)), cell(0, 0), 1e-12);
}

void test_rejects(void**) {
    const Vec3 o(0, 0, 0), s(1, 1, 1);
    const std::vector<double> v8(8, 1.0);
    using D = std::array<int32_t, 3>;
    assert_invalid(DensityGrid(o, s, D{1, 2, 2}, std::vector<double>(4, 1.0)), "x dimension 1");
    assert_invalid(DensityGrid(o, s, D{2, 0, 2}, v8), "y dimension 0");
    assert_invalid(DensityGrid(o, s, D{2, 2, -3}, v8), "z dimension -3");
    assert_invalid(DensityGrid(o, s, D{2, 2, 2}, std::vector<double>(7, 1.0)), "7 values given for 2 x 2 x 2 = 8");
    assert_invalid(DensityGrid(o, s, D{2, 2, 2}, std::vector<double>(9, 1.0)), "9 values");
    assert_invalid(DensityGrid(o, s, D{2, 2, 2}, std::vector<double>()), "0 values");
    assert_invalid(DensityGrid(o, Vec3(0, 1, 1), D{2, 2, 2}, v8), "x spacing");
    assert_invalid(DensityGrid(o, Vec3(1, -1, 1), D{2, 2, 2}, v8), "y spacing");
    assert_invalid(DensityGrid(o, Vec3(1, 1, kNaN), D{2, 2, 2}, v8), "z spacing");
    assert_invalid(DensityGrid(o, Vec3(kInf, 1, 1), D{2, 2, 2}, v8), "x spacing");
    assert_invalid(DensityGrid(Vec3(kNaN, 0, 0), s, D{2, 2, 2}, v8), "x origin");
    assert_invalid(DensityGrid(Vec3(0, 0, -kInf), s, D{2, 2, 2}, v8), "z origin");
    const int32_t big = std::numeric_limits<int32_t>::max();
    assert_invalid(DensityGrid(o, s, D{big, big, big}, v8), "overflow");
    assert_invalid(DensityGrid(o, s, D{1 << 21, 1 << 21, 1 << 21}, v8), "overflow");  // 2^63
    assert_invalid(DensityGrid(o, s, D{1 << 16, 1 << 16, 1 << 16}, v8), "8 values given");
    // Accepted: the smallest grid.
    assert_int_equal(thrown_status([&] { DensityGrid g(o, s, D{2, 2, 2}, v8); }, nullptr), 0);

    Built b;
    make_cubes(b, 1, 1.0, nullptr, 0.0, 1);
    const std::vector<double> d(b.mesh.points.size(), 1.0);
    assert_invalid(DensityGrid::interpolate(b.mesh, d, 0.0), "spacing");
    assert_invalid(DensityGrid::interpolate(b.mesh, d, -0.1), "spacing");
    assert_invalid(DensityGrid::interpolate(b.mesh, d, kNaN), "spacing");
    assert_invalid(DensityGrid::interpolate(b.mesh, d, kInf), "spacing");
    assert_invalid(DensityGrid::interpolate(b.mesh, d, 0.1, 26), "max_points 26");
    assert_invalid(DensityGrid::interpolate(b.mesh, d, 0.1, 0), "max_points 0");
    assert_invalid(DensityGrid::interpolate(b.mesh, std::vector<double>(d.size() - 1, 1.0), 0.1),
                   "densities given for 8 vertices");
    assert_int_equal(thrown_status([&] { (void)DensityGrid::interpolate(b.mesh, d, 0.1, 27); }, nullptr), 0);
}

// Eq. (4.1) computed here from the raw edges; target(mid) gives rho'
// (<= 0: skipped).
bodt::DensityError expected_error(const test_mesh& m, const std::function<double(const Vec3&)>& target) {
    bodt::DensityError r;
    double sum = 0.0;
    for (const auto& e : raw_edges(m)) {
        const Vec3 a = raw_point(m, e.first), b = raw_point(m, e.second);
        const double t = target(0.5 * (a + b));
        if (t <= 0.0) continue;
        const double eps = std::abs(1.0 / (a - b).norm() - t) / t;
        sum += eps;
        r.max = std::max(r.max, eps);
        ++r.edges;
    }
    r.mean = r.edges ? sum / static_cast<double>(r.edges) : 0.0;
    return r;
}

void test_density_error(void**) {
    Built b;
    make_cubes(b, 2, 1.0, nullptr, 0.0, 1);
    const size_t nedges = raw_edges(b.m).size();
    // 3 * 3 * 2 * 3 axis edges, 3 * 3 * 2 * 2 face diagonals, 8 cube diagonals.
    assert_int_equal(nedges, 54 + 36 + 8);

    // A constant grid c: with h = 1/2, eps = |2 - c| / c, |sqrt2 - c| / c,
    // |2/sqrt3 - c| / c for the three kinds of edges.
    const double c = 2.5;
    const DensityGrid g(Vec3::Constant(-0.1), Vec3::Constant(0.6), {3, 3, 3}, std::vector<double>(27, c));
    const bodt::DensityError r = bodt::density_error(b.mesh, g);
    const bodt::DensityError x = expected_error(b.m, [&](const Vec3&) { return c; });
    assert_int_equal(r.edges, static_cast<int64_t>(nedges));
    assert_int_equal(x.edges, r.edges);
    assert_near(r.mean, x.mean, 1e-12);
    assert_near(r.max, x.max, 1e-12);
    const double e1 = std::abs(2.0 - c) / c, e2 = std::abs(std::sqrt(2.0) - c) / c,
                 e3 = std::abs(2.0 / std::sqrt(3.0) - c) / c;
    assert_near(r.mean, (54 * e1 + 36 * e2 + 8 * e3) / 98.0, 1e-12);
    assert_near(r.max, std::max({e1, e2, e3}), 1e-12);

    // A grid with values only at x = 0: the cells with x in [0, 0.5) hold 3,
    // the others none; edges with midpoint x >= 0.5 are skipped.
    std::vector<double> v(27, 0.0);
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) v[static_cast<size_t>(3 * (j + 3 * k))] = 3.0;
    const DensityGrid half(Vec3::Zero(), Vec3::Constant(0.5), {3, 3, 3}, v);
    const bodt::DensityError rh = bodt::density_error(b.mesh, half);
    const bodt::DensityError xh = expected_error(b.m, [](const Vec3& m) { return m.x() < 0.5 ? 3.0 : 0.0; });
    assert_true(xh.edges > 0 && xh.edges < static_cast<int64_t>(nedges));
    assert_int_equal(rh.edges, xh.edges);
    assert_near(rh.mean, xh.mean, 1e-12);
    assert_near(rh.max, xh.max, 1e-12);

    // No grid: nothing counted.
    const bodt::DensityError re = bodt::density_error(b.mesh, DensityGrid());
    assert_true(re.edges == 0 && re.mean == 0.0 && re.max == 0.0);

    // The mesh's own density field covers every edge of a jittered box.
    Built j;
    make_cubes(j, 4, 1.0, nullptr, 0.1, 5);
    const DensityGrid own = DensityGrid::interpolate(j.mesh, bodt::vertex_density(j.mesh), 0.25);
    const bodt::DensityError ro = bodt::density_error(j.mesh, own);
    assert_int_equal(ro.edges, static_cast<int64_t>(raw_edges(j.m).size()));
    assert_true(std::isfinite(ro.mean) && ro.mean >= 0.0 && ro.max >= ro.mean && ro.max < 1.0);
}

void test_max_points(void**) {
    Built b;
    make_cubes(b, 2, 1.0, nullptr, 0.0, 1);
    const double a = 1.5;
    const Vec3 slope(-0.2, 0.4, 0.1);
    const std::vector<double> d = linear_density(b.mesh, a, slope);

    // Unlimited (the default 2^21): the spacing as asked.
    const DensityGrid fine = DensityGrid::interpolate(b.mesh, d, 0.01);
    assert_true(fine.spacing() == Vec3::Constant(0.01));
    assert_true(num_points(fine) > 1000000 && num_points(fine) <= (int64_t(1) << 21));
    check_linear(fine, a, slope, in_unit_box);

    for (int64_t maxp : {int64_t(1000), int64_t(100), int64_t(30), int64_t(27)}) {
        const DensityGrid g = DensityGrid::interpolate(b.mesh, d, 0.01, maxp);
        const double h = g.spacing().x();
        assert_true(g.spacing().y() == h && g.spacing().z() == h);  // uniform
        assert_true(h > 0.01);
        assert_true(num_points(g) <= maxp);
        for (int ax = 0; ax < 3; ++ax) {
            assert_true(g.dims()[ax] >= 2);
            // Padded by half a spacing, covering the mesh.
            assert_near(g.origin()[ax], -h / 2, 1e-12);
            assert_true(g.origin()[ax] + (g.dims()[ax] - 1) * h >= 1.0 + h / 2 - 1e-12);
        }
        if (maxp < 64) {
            // 3 points per axis: the padded box needs more than 2.
            for (int ax = 0; ax < 3; ++ax) assert_int_equal(g.dims()[ax], 3);
        } else {
            // Not grown beyond what fits: a spacing 1% smaller would not.
            const double h2 = h * 0.99;
            double total = 1.0;
            for (int ax = 0; ax < 3; ++ax) total *= std::ceil((1.0 + h2) / h2) + 1.0;
            assert_true(total > static_cast<double>(maxp));
        }
        // Asking for a spacing just below the result gives the same grid.
        const DensityGrid g2 = DensityGrid::interpolate(b.mesh, d, h * (1 - 1e-9), maxp);
        assert_near(g2.spacing().x(), h, 1e-14 * h);
        // Points inside still hold the linear field.
        int64_t inside = 0;
        for (int64_t k = 0; k < g.dims()[2]; ++k)
            for (int64_t j = 0; j < g.dims()[1]; ++j)
                for (int64_t i = 0; i < g.dims()[0]; ++i) {
                    const Vec3 x = grid_point(g, i, j, k);
                    double margin = 0.0;
                    if (!in_unit_box(x, &margin) || margin < 1e-9) continue;
                    ++inside;
                    assert_near(g.point_values()[static_cast<size_t>(i + g.dims()[0] * (j + g.dims()[1] * k))],
                                a + slope.dot(x), 1e-12);
                }
        assert_true(inside > 0);
    }
}

}  // namespace

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vertex_density), cmocka_unit_test(test_linear_field),
        cmocka_unit_test(test_aligned_grid),   cmocka_unit_test(test_inverted_skipped),
        cmocka_unit_test(test_cell_means),     cmocka_unit_test(test_at_clamps),
        cmocka_unit_test(test_rejects),        cmocka_unit_test(test_density_error),
        cmocka_unit_test(test_max_points),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
