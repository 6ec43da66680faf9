/*
 * test_nodt: BODT_MODE_NODT (Natural ODT, Tournois et al. 2009; the
 * comparison of paper 000 Table 1) through libbodt.so only.  Every test runs
 * 10 steps of smoothing only (BODT_PARAM_OPS = SMOOTH, NODT's default).
 *
 *   box          a Kuhn box whose boundary vertices were jittered in their
 *                face plane or along their edge (tm_make_cubes_sliding), so
 *                each vertex's place is known: face vertices stay on their
 *                face plane, edge vertices on their edge line (to 1e-9 of
 *                the bounding-box diagonal), corners and a caller's fixed
 *                vertex and corner bit for bit; no inverted tet; the min
 *                dihedral angle goes up, beyond ODT's; boundary vertices do
 *                move (ODT leaves them bit for bit); the faces are flat, so
 *                the volume stays to 1e-12
 *   ball         a Kuhn box mapped onto the unit ball, boundary vertices
 *                jittered: after the steps every boundary vertex lies on
 *                the INPUT boundary triangles (distance by a brute-force
 *                point-triangle distance, below 1e-9 of the diagonal), which
 *                fails if the surface were captured again each step and
 *                drifted; the min dihedral angle goes up; the volume goes
 *                down (NODT does not keep it), by less than 2 % on this
 *                coarse ball (8 cells across)
 *   two regions  interface vertices stay on the interface plane x = 1/2
 *                and move in it
 */
#include "api_checks.h"
#include "bodt.h"
#include "cleanup.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>

enum { kSteps = 10 };


static void run_steps(bodt_mesh *h) {
    for (int k = 0; k < kSteps; ++k) {
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        const int st = bodt_step(h, &r);
        if (st != BODT_OK) fail_msg("bodt_step: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    }
}

static double *get_xyz(const bodt_mesh *h, int32_t nv) {
    double *xyz = cleanup_calloc(3 * (size_t)nv * sizeof *xyz);
    assert_int_equal(bodt_mesh_get_vertices(h, xyz, 3 * (size_t)nv), BODT_OK);
    return xyz;
}

static bodt_quality quality(const bodt_mesh *h) {
    bodt_quality q;
    memset(&q, 0, sizeof q);
    q.size = sizeof q;
    assert_int_equal(bodt_mesh_quality(h, &q), BODT_OK);
    return q;
}

/* No tet inverted or flat, by the reported count and by every volume. */
static void expect_valid(const bodt_mesh *h, int32_t ntets, const char *name) {
    assert_int_equal(quality(h).num_inverted, 0);
    double *vol = cleanup_calloc((size_t)ntets * sizeof *vol);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_VOLUME, vol, (size_t)ntets), BODT_OK);
    for (int32_t t = 0; t < ntets; ++t)
        if (!(vol[t] > 0.0)) fail_msg("%s: tet %d has volume %g", name, t, vol[t]);
}

static double diagonal(const test_mesh *m) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int32_t v = 0; v < m->nverts; ++v)
        for (int a = 0; a < 3; ++a) {
            lo[a] = fmin(lo[a], m->xyz[3 * v + a]);
            hi[a] = fmax(hi[a], m->xyz[3 * v + a]);
        }
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

static test_mesh *sliding_box(int n, double size, tm_cube_region region, double jitter, double boundary_jitter,
                              uint64_t seed, unsigned char **axes, int32_t **regions) {
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_non_null(m);
    const int st = tm_make_cubes_sliding(m, n, size, NULL, region, NULL, jitter, boundary_jitter, seed, axes, regions);
    if (st != 0) fail_msg("tm_make_cubes_sliding: %d", st);
    cleanup_add(*axes, free);
    if (regions) cleanup_add(*regions, free);
    return m;
}

/* ------------------------------------------------------------------ box */

static void test_box(void **state) {
    (void)state;
    enum { N = 5 };
    unsigned char *axes = NULL;
    const test_mesh *m = sliding_box(N, 1.0, NULL, 0.3, 0.35, 11, &axes, NULL);
    const double tol = 1e-9 * diagonal(m), h = 1.0 / N;
    bodt_mesh *nodt = create_smoothing(m, BODT_MODE_NODT), *odt = create_smoothing(m, BODT_MODE_ODT);
    /* a face vertex fixed and another one made a corner by the caller */
    int32_t fixed = -1, corner = -1;
    for (int32_t v = 0; v < m->nverts && corner < 0; ++v)
        if (axes[v] == 3) { /* free along x and y: on a face z = const */
            if (fixed < 0) fixed = v;
            else corner = v;
        }
    assert_int_equal(bodt_mesh_set_fixed_vertices(nodt, 1, &fixed), BODT_OK);
    assert_int_equal(bodt_mesh_set_corners(nodt, 1, &corner), BODT_OK);
    const bodt_quality before = quality(nodt);
    run_steps(nodt);
    run_steps(odt);
    expect_valid(nodt, m->ntets, "box");

    const double *xyz = get_xyz(nodt, m->nverts), *odt_xyz = get_xyz(odt, m->nverts);
    int on_boundary = 0, moved = 0;
    double odt_moved = 0.0;
    for (int32_t v = 0; v < m->nverts; ++v) {
        if (axes[v] == 7) continue; /* inside */
        const double *p = &xyz[3 * v], *p0 = &m->xyz[3 * v];
        if (axes[v] == 0 || v == fixed || v == corner) {
            if (memcmp(p, p0, 3 * sizeof *p) != 0) fail_msg("vertex %d (corner or fixed) moved", v);
            continue;
        }
        for (int a = 0; a < 3; ++a) {
            /* not free along a: the coordinate of its face plane or edge line */
            if (!(axes[v] >> a & 1) && !(fabs(p[a] - p0[a]) <= tol))
                fail_msg("vertex %d left its plane or line: coordinate %d %.17g -> %.17g", v, a, p0[a], p[a]);
            if (!(p[a] >= -tol && p[a] <= 1.0 + tol)) fail_msg("vertex %d left the box: %.17g", v, p[a]);
            odt_moved = fmax(odt_moved, fabs(odt_xyz[3 * v + a] - p0[a]));
        }
        ++on_boundary;
        const double d = fabs(p[0] - p0[0]) + fabs(p[1] - p0[1]) + fabs(p[2] - p0[2]);
        moved += d > 1e-3 * h;
    }
    print_message("box: %d of %d boundary vertices moved by more than 1e-3 h\n", moved, on_boundary);
    assert_true(odt_moved == 0.0);     /* ODT keeps them bit for bit ... */
    assert_true(2 * moved > on_boundary); /* ... NODT moves most of them */

    const bodt_quality after = quality(nodt), odt_after = quality(odt);
    print_message("box: min dihedral %.2f -> NODT %.2f, ODT %.2f; volume %.17g\n", before.min_dihedral,
                  after.min_dihedral, odt_after.min_dihedral, after.volume);
    assert_true(after.min_dihedral > before.min_dihedral + 5.0);
    assert_true(after.min_dihedral > odt_after.min_dihedral + 1.0);
    /* flat faces and straight edges: sliding in them keeps the volume */
    assert_near(after.volume, 1.0, 1e-12);
}

/* ----------------------------------------------------------------- ball */

static double segment_distance(const double *p, const double *a, const double *b) {
    double ab[3], ap[3], t = 0.0, len2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        ab[k] = b[k] - a[k];
        ap[k] = p[k] - a[k];
        t += ab[k] * ap[k];
        len2 += ab[k] * ab[k];
    }
    t = len2 > 0.0 ? fmin(1.0, fmax(0.0, t / len2)) : 0.0;
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) d2 += (ap[k] - t * ab[k]) * (ap[k] - t * ab[k]);
    return sqrt(d2);
}

/* Distance from p to triangle abc: to its plane when the foot lies inside
 * (barycentric coordinates by areas), else to the nearest edge. */
static double triangle_distance(const double *p, const double *a, const double *b, const double *c) {
    double u[3], w[3], n[3], ap[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        w[k] = c[k] - a[k];
        ap[k] = p[k] - a[k];
    }
    n[0] = u[1] * w[2] - u[2] * w[1];
    n[1] = u[2] * w[0] - u[0] * w[2];
    n[2] = u[0] * w[1] - u[1] * w[0];
    const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const double h = (ap[0] * n[0] + ap[1] * n[1] + ap[2] * n[2]) / nn;
    double foot[3];
    for (int k = 0; k < 3; ++k) foot[k] = p[k] - h * n[k];
    const double *corner[3] = {a, b, c};
    int inside = 1;
    for (int i = 0; i < 3; ++i) { /* sub-triangle (foot, corner i, corner i+1) oriented like n */
        const double *q = corner[i], *r = corner[(i + 1) % 3];
        double s[3], t[3];
        for (int k = 0; k < 3; ++k) {
            s[k] = q[k] - foot[k];
            t[k] = r[k] - foot[k];
        }
        const double orient = (s[1] * t[2] - s[2] * t[1]) * n[0] + (s[2] * t[0] - s[0] * t[2]) * n[1] +
                              (s[0] * t[1] - s[1] * t[0]) * n[2];
        inside = inside && orient >= 0.0;
    }
    if (inside) return fabs(h) * sqrt(nn);
    return fmin(segment_distance(p, a, b), fmin(segment_distance(p, b, c), segment_distance(p, c, a)));
}

static void test_ball(void **state) {
    (void)state;
    unsigned char *axes = NULL;
    test_mesh *m = sliding_box(8, 2.0, NULL, 0.15, 0.25, 5, &axes, NULL);
    assert_int_equal(tm_map_cube_to_ball(m), 0);
    const double tol = 1e-9 * diagonal(m);
    bodt_mesh *h = create_smoothing(m, BODT_MODE_NODT);
    int32_t nb = 0;
    assert_int_equal(bodt_mesh_get_counts(h, NULL, NULL, &nb), BODT_OK);
    int32_t *tris = cleanup_calloc(3 * (size_t)nb * sizeof *tris);
    assert_int_equal(bodt_mesh_get_boundary_faces(h, tris, NULL, (size_t)nb), BODT_OK);
    const bodt_quality before = quality(h);
    run_steps(h);
    expect_valid(h, m->ntets, "ball");

    const double *xyz = get_xyz(h, m->nverts);
    double worst = 0.0, moved = 0.0;
    for (int32_t v = 0; v < m->nverts; ++v) {
        if (!m->boundary[v]) continue;
        const double *p = &xyz[3 * v];
        double d = INFINITY;
        for (int32_t f = 0; f < nb; ++f)
            d = fmin(d, triangle_distance(p, &m->xyz[3 * tris[3 * f]], &m->xyz[3 * tris[3 * f + 1]],
                                          &m->xyz[3 * tris[3 * f + 2]]));
        worst = fmax(worst, d);
        moved = fmax(moved, fabs(p[0] - m->xyz[3 * v]) + fabs(p[1] - m->xyz[3 * v + 1]) +
                                fabs(p[2] - m->xyz[3 * v + 2]));
    }
    const bodt_quality after = quality(h);
    const double change = fabs(after.volume - before.volume) / before.volume;
    print_message("ball: boundary vertices moved up to %.3g, off the input surface by up to %.3g; "
                  "min dihedral %.2f -> %.2f; volume %.6f -> %.6f (relative change %.3g)\n",
                  moved, worst, before.min_dihedral, after.min_dihedral, before.volume, after.volume, change);
    if (!(worst <= tol)) fail_msg("a boundary vertex is %.3g off the input surface", worst);
    assert_true(moved > 0.01);
    assert_true(after.min_dihedral > before.min_dihedral);
    /* Not kept: the boundary vertices leave the input's vertices, which lie
     * on the sphere, for its flat triangles (the input is convex: the
     * volume goes down).  At most 2 % here, with 8 x 8 cells across. */
    assert_true(after.volume < before.volume - 1e-9);
    assert_true(change < 2e-2);
}

/* ---------------------------------------------------------- two regions */

static int region_halves(int i, int j, int k, int n, void *user) {
    (void)j, (void)k, (void)user;
    return 2 * i >= n;
}

static void test_two_regions(void **state) {
    (void)state;
    unsigned char *axes = NULL;
    int32_t *regions = NULL;
    const test_mesh *m = sliding_box(6, 1.0, region_halves, 0.3, 0.35, 31, &axes, &regions);
    const double tol = 1e-9 * diagonal(m);
    bodt_mesh *h = create_smoothing(m, BODT_MODE_NODT);
    assert_int_equal(bodt_mesh_set_regions(h, regions), BODT_OK);
    run_steps(h);
    expect_valid(h, m->ntets, "two regions");
    const double *xyz = get_xyz(h, m->nverts);
    double moved = 0.0;
    for (int32_t v = 0; v < m->nverts; ++v) {
        if ((axes[v] & 1) || fabs(m->xyz[3 * v] - 0.5) > 1e-12) continue; /* on the interface x = 1/2 */
        if (!(fabs(xyz[3 * v] - 0.5) <= tol)) fail_msg("interface vertex %d left x = 1/2: %.17g", v, xyz[3 * v]);
        moved = fmax(moved, fabs(xyz[3 * v + 1] - m->xyz[3 * v + 1]) + fabs(xyz[3 * v + 2] - m->xyz[3 * v + 2]));
    }
    print_message("two regions: interface vertices moved in their plane by up to %.3g\n", moved);
    assert_true(moved > 1e-3);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_box, cleanup_teardown),
        cmocka_unit_test_teardown(test_ball, cleanup_teardown),
        cmocka_unit_test_teardown(test_two_regions, cleanup_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
