/*
 * test_bodt: the B-ODT smoothing modes (BODT_MODE_ODT, BODT_MODE_BODT_BASIC,
 * BODT_MODE_BODT; paper 000, Algorithms 1-3) through libbodt.so only.
 *
 * The meshes are Kuhn boxes (support/mesh_gen.c) whose vertices are jittered
 * only along the axes along which the shape around them is invariant
 * (tm_make_cubes_sliding): face vertices in their face plane, edge vertices
 * along their edge line, corners not at all, interface vertices in the
 * interface plane.  So the exact domain, every region and the expected class
 * of every vertex are known independently of the library:
 *   free axes 3 -> INTERIOR, 2 -> SURFACE, 1 -> FEATURE_LINE, 0 -> CORNER.
 *
 *   volume        one step and 20 steps of BODT_BASIC and BODT keep the total
 *                 volume (1e-12 relative) on a box, an L-shape and a notched
 *                 box, with BODT_PARAM_NEVER_WORSE 0 and 1 (Appendix B)
 *   converged     BODT_PARAM_TOLERANCE: a move shorter than that fraction
 *                 of the star's size is not made (at 1 none is, also on the
 *                 box scaled by 1e-6); at the default the box converges and
 *                 then stays bit for bit, no vertex tried again
 *   angle ascent  BODT_PARAM_ASCENT_ANGLE: default, range; BODT (default
 *                 operations) from its second step on raises the smallest
 *                 angle of a lazy cube beyond what it reaches without (0),
 *                 the first step the same, extremes never worse, volume
 *                 kept; ODT and BODT_BASIC do not read it
 *   odt           ODT moves interior vertices only; boundary bit for bit
 *   features      BODT: corners bit for bit, edge vertices on their lines,
 *                 face vertices on their planes, and they do move, on the
 *                 box 2, 2e-6 and 2e6 across (any unit); BODT_BASIC
 *                 moves corners/edge vertices off their lines
 *   user lines    bodt_mesh_set_feature_edges on a face diagonal: FEATURE_LINE,
 *                 the vertices stay on the diagonal; non-surface edges are
 *                 refused and leave the earlier list
 *   fixed         fixed vertices never move in any mode
 *   classes       box (also with only feature edges or only tensor voting),
 *                 cylinder, ball, the other modes, two regions
 *   flat caps     the cylinder's flat caps stay flat under BODT (the rim's
 *                 feature-line vertices stay in the cap plane)
 *   shallow ridge two flat pieces meeting at 20 degrees, below the feature
 *                 angle: BODT moves the ridge's SURFACE vertices along it
 *                 and keeps every roof vertex on the roof; with the feature
 *                 angle at 50 degrees they leave it
 *   two regions   region volumes (BODT and BODT_BASIC) and the interface
 *                 plane (BODT) kept
 *   robustness    2000 steps mixing modes and NEVER_WORSE, BODT with its
 *                 default flips and insertion: no inverted tet, volume
 *                 kept, consistent reports, extreme angles never worse with
 *                 NEVER_WORSE = 1
 * Every other test sets BODT_PARAM_OPS to BODT_OP_SMOOTH: smoothing only.
 *   non-manifold  regions alternating per tet, and two regions touching
 *                 themselves along a line: BODT still works, volumes stay,
 *                 non-manifold vertices are FIXED and FIXED vertices stay
 */
#include "api_checks.h"
#include "bodt.h"
#include "cleanup.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>

/* ------------------------------------------------------------- helpers */

typedef struct shape {
    test_mesh *m;
    unsigned char *axes; /* free axes per vertex (bit a: free along axis a) */
    int32_t *regions;    /* per tet */
} shape;

static shape make_sliding(int n, double size, tm_cube_filter keep, tm_cube_region region, double jitter,
                          double boundary_jitter, uint64_t seed) {
    shape s;
    s.m = cleanup_add(calloc(1, sizeof *s.m), cleanup_free_test_mesh);
    assert_non_null(s.m);
    const int st = tm_make_cubes_sliding(s.m, n, size, keep, region, NULL, jitter, boundary_jitter, seed, &s.axes,
                                         &s.regions);
    if (st != 0) fail_msg("tm_make_cubes_sliding: %d", st);
    cleanup_add(s.axes, free);
    cleanup_add(s.regions, free);
    return s;
}

/* These tests are about smoothing (create_smoothing): the connectivity
 * stays (test_ops.c and test_robustness below cover the flips and
 * insertion). */

static double *get_xyz(const bodt_mesh *h, int32_t nv) {
    double *xyz = cleanup_calloc(3 * (size_t)nv * sizeof *xyz);
    assert_int_equal(bodt_mesh_get_vertices(h, xyz, 3 * (size_t)nv), BODT_OK);
    return xyz;
}

static int32_t *get_classes(const bodt_mesh *h, int32_t nv) {
    int32_t *c = cleanup_calloc((size_t)nv * sizeof *c);
    assert_int_equal(bodt_mesh_get_vertex_classes(h, c, (size_t)nv), BODT_OK);
    return c;
}

static void step_ok(bodt_mesh *h, bodt_step_report *r) {
    memset(r, 0, sizeof *r);
    r->size = sizeof *r;
    const int st = bodt_step(h, r);
    if (st != BODT_OK) fail_msg("bodt_step: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
}

/* Sum of the signed tet volumes of region `region` (any region if < 0). */
static double region_volume(const bodt_mesh *h, int32_t ntets, int32_t region) {
    double *vol = malloc((size_t)ntets * sizeof *vol);
    int32_t *reg = malloc((size_t)ntets * sizeof *reg);
    assert_non_null(vol);
    assert_non_null(reg);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_VOLUME, vol, (size_t)ntets), BODT_OK);
    assert_int_equal(bodt_mesh_get_regions(h, reg, (size_t)ntets), BODT_OK);
    double sum = 0.0;
    for (int32_t t = 0; t < ntets; ++t)
        if (region < 0 || reg[t] == region) sum += vol[t];
    free(vol);
    free(reg);
    return sum;
}

static double total_volume(const bodt_mesh *h, int32_t ntets) { return region_volume(h, ntets, -1); }

static int popcount3(unsigned char mask) { return (mask & 1) + (mask >> 1 & 1) + (mask >> 2 & 1); }

/* The class a vertex with these free axes must get in BODT_MODE_BODT. */
static int expected_class(unsigned char mask) {
    static const int by_count[4] = {BODT_VERTEX_CORNER, BODT_VERTEX_FEATURE_LINE, BODT_VERTEX_SURFACE,
                                    BODT_VERTEX_INTERIOR};
    return by_count[popcount3(mask)];
}

/* Largest change of a coordinate along a non-free axis (leaving the
 * vertex's plane, line or corner), over the vertices with `nfree` free axes. */
static double max_off_constraint(const shape *s, const double *xyz, int nfree) {
    double worst = 0.0;
    for (int32_t v = 0; v < s->m->nverts; ++v) {
        if (popcount3(s->axes[v]) != nfree) continue;
        for (int a = 0; a < 3; ++a)
            if (!(s->axes[v] >> a & 1)) worst = fmax(worst, fabs(xyz[3 * v + a] - s->m->xyz[3 * v + a]));
    }
    return worst;
}

/* Largest displacement of the vertices with `nfree` free axes. */
static double max_move_of(const shape *s, const double *xyz, int nfree) {
    double worst = 0.0;
    for (int32_t v = 0; v < s->m->nverts; ++v) {
        if (popcount3(s->axes[v]) != nfree) continue;
        const double *p = &xyz[3 * v], *q = &s->m->xyz[3 * v];
        worst = fmax(worst, sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                 (p[2] - q[2]) * (p[2] - q[2])));
    }
    return worst;
}

typedef struct run_log {
    int steps;
    double last_max_move;
} run_log;

static int log_step(const bodt_step_report *r, void *user) {
    run_log *log = user;
    ++log->steps;
    log->last_max_move = r->max_move;
    return 0;
}

/* Vertex index of grid point (i, j, k) of a box made with every cube kept. */
static int32_t grid_vertex(int n, int i, int j, int k) { return (int32_t)(((k * (n + 1)) + j) * (n + 1) + i); }

/* Cube filters and region maps. */
static int keep_l_shape(int i, int j, int k, int n, void *user) {
    (void)k, (void)user;
    return !(2 * i >= n && 2 * j >= n);
}

/* The box without a corner block: a notch with a concave corner. */
static int keep_notch(int i, int j, int k, int n, void *user) {
    (void)user;
    return !(3 * i >= 2 * n && 3 * j >= 2 * n && 3 * k >= 2 * n);
}

/* Two regions split by the plane x = size / 2. */
static int region_halves(int i, int j, int k, int n, void *user) {
    (void)j, (void)k, (void)user;
    return 2 * i >= n;
}

/* ------------------------------------------------------------- 1 volume */

/* One step, then 19 more (tolerance 0 so bodt_run keeps going), of
 * BODT_BASIC and BODT with NEVER_WORSE 0 and 1: the volume stays to 1e-12
 * relative while boundary vertices do move. */
static void check_volume_kept(const shape *s, const char *name) {
    const test_mesh *m = s->m;
    static const int modes[2] = {BODT_MODE_BODT_BASIC, BODT_MODE_BODT};
    for (int nw = 0; nw <= 1; ++nw)
        for (int mi = 0; mi < 2; ++mi) {
            bodt_mesh *h = create_smoothing(m, modes[mi]);
            assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, nw), BODT_OK);
            assert_int_equal(bodt_set_param_double(h, BODT_PARAM_TOLERANCE, 0.0), BODT_OK);
            const double v0 = total_volume(h, m->ntets);
            bodt_step_report r;
            step_ok(h, &r);
            assert_true(r.vertices_moved > 0);
            const double v1 = total_volume(h, m->ntets);
            if (!(fabs(v1 - v0) <= 1e-12 * v0))
                fail_msg("%s, mode %d, never_worse %d: one step changed the volume %.17g -> %.17g", name, modes[mi],
                         nw, v0, v1);
            /* not vacuous: boundary vertices moved */
            const double *xyz = get_xyz(h, m->nverts);
            double moved = 0.0;
            for (int32_t v = 0; v < m->nverts; ++v)
                if (m->boundary[v])
                    for (int a = 0; a < 3; ++a) moved = fmax(moved, fabs(xyz[3 * v + a] - m->xyz[3 * v + a]));
            if (!(moved > 1e-6)) fail_msg("%s, mode %d, never_worse %d: no boundary vertex moved", name, modes[mi], nw);

            /* with tolerance 0, bodt_run stops early only when nothing moves */
            run_log log = {0, -1.0};
            assert_int_equal(bodt_run(h, 19, log_step, &log), BODT_OK);
            assert_true(log.steps == 19 || (log.steps < 19 && log.last_max_move == 0.0));
            if (log.steps < 19) print_message("%s, mode %d, never_worse %d: converged after %d steps\n", name,
                                              modes[mi], nw, 1 + log.steps);
            const double v20 = total_volume(h, m->ntets);
            if (!(fabs(v20 - v0) <= 1e-12 * v0))
                fail_msg("%s, mode %d, never_worse %d: 20 steps changed the volume %.17g -> %.17g", name, modes[mi],
                         nw, v0, v20);
            bodt_quality q;
            get_quality(h, &q);
            assert_int_equal(q.num_inverted, 0);
        }
}

static void test_volume_box(void **state) {
    (void)state;
    const shape s = make_sliding(4, 1.0, NULL, NULL, 0.25, 0.25, 11);
    check_volume_kept(&s, "box");
}

static void test_volume_l_shape(void **state) {
    (void)state;
    const shape s = make_sliding(3, 1.0, keep_l_shape, NULL, 0.25, 0.25, 12);
    check_volume_kept(&s, "L-shape");
}

static void test_volume_notch(void **state) {
    (void)state;
    const shape s = make_sliding(3, 2.0, keep_notch, NULL, 0.25, 0.25, 13);
    check_volume_kept(&s, "notched box");
}

/* ---------------------------------------------------------- convergence */

/* BODT_PARAM_TOLERANCE: a vertex whose move would be at most that fraction
 * of its star's size stays.  At the largest tolerance (1) no move on the
 * jittered box is that long: a step moves nothing, and the same holds with
 * the box scaled down by 1e-6 (the size is the star's, not absolute).  At
 * the default the box converges: some step moves no vertex, and from then
 * on the steps leave the mesh bit for bit as it is, trying no vertex
 * again (every one has stayed, and nothing around it moved). */
static void test_converged(void **state) {
    (void)state;
    const shape s = make_sliding(4, 1.0, NULL, NULL, 0.25, 0.25, 11);
    const test_mesh *m = s.m;
    bodt_step_report r;
    for (int scaled = 0; scaled <= 1; ++scaled) {
        test_mesh small = *m;
        double *xyz = cleanup_calloc(3 * (size_t)m->nverts * sizeof *xyz);
        for (int32_t i = 0; i < 3 * m->nverts; ++i) xyz[i] = scaled ? 1e-6 * m->xyz[i] : m->xyz[i];
        small.xyz = xyz;
        bodt_mesh *h = create_smoothing(&small, BODT_MODE_BODT);
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_TOLERANCE, 1.0), BODT_OK);
        step_ok(h, &r);
        if (r.vertices_moved != 0) fail_msg("tolerance 1 (scaled %d): %d vertices moved", scaled, r.vertices_moved);
        if (memcmp(get_xyz(h, m->nverts), xyz, 3 * (size_t)m->nverts * sizeof *xyz) != 0)
            fail_msg("tolerance 1 (scaled %d): the vertices changed", scaled);
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_TOLERANCE, 1e-6), BODT_OK);
        step_ok(h, &r);
        if (!(r.vertices_moved > m->nverts / 4))
            fail_msg("tolerance 1e-6 (scaled %d): only %d vertices moved", scaled, r.vertices_moved);
    }

    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    int still = -1;
    for (int k = 0; k < 500 && still < 0; ++k) {
        step_ok(h, &r);
        if (r.vertices_moved == 0) still = k;
    }
    if (still < 1) fail_msg("the box did not converge in 500 steps (or never moved): %d", still);
    print_message("converged: step %d moved no vertex\n", still + 1);
    const double *before = get_xyz(h, m->nverts);
    for (int k = 0; k < 3; ++k) {
        step_ok(h, &r);
        if (r.vertices_moved != 0 || r.moves_rejected != 0)
            fail_msg("after convergence: %d moved, %d refused", r.vertices_moved, r.moves_rejected);
    }
    if (memcmp(get_xyz(h, m->nverts), before, 3 * (size_t)m->nverts * sizeof *before) != 0)
        fail_msg("after convergence the vertices changed");
}

/* ---------------------------------------------------------- angle ascent */

/* BODT_PARAM_ASCENT_ANGLE: default 30, range [0, 60], a refused value
 * leaves the last.  On a lazy triangulation of a cube (BODT with its
 * default operations, 30 steps): the first step is the same with the
 * ascent as without it (0), bit for bit; from then on the ascent moves
 * inner vertices of bad tets, and the mesh ends with a larger smallest
 * angle; the extremes are never worse than a step before, and the volume
 * stays.  ODT and BODT_BASIC do not read the parameter. */
static void test_angle_ascent(void **state) {
    (void)state;
    test_mesh *m = cleanup_add(calloc(1, sizeof(test_mesh)), cleanup_free_test_mesh);
    assert_non_null(m);
    assert_int_equal(tm_make_lazy(m, 300, 3), 0);
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    double a = 0.0;
    assert_int_equal(bodt_get_param_double(h, BODT_PARAM_ASCENT_ANGLE, &a), BODT_OK);
    assert_true(a == 30.0);
    const double good[] = {0.0, 60.0, 25.0}, bad[] = {-1.0, 60.5, NAN, INFINITY};
    for (int k = 0; k < 3; ++k) assert_int_equal(bodt_set_param_double(h, BODT_PARAM_ASCENT_ANGLE, good[k]), BODT_OK);
    for (int k = 0; k < 4; ++k) {
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_ASCENT_ANGLE, bad[k]), BODT_ERR_INVALID_ARGUMENT);
        assert_non_null(strstr(bodt_mesh_last_error(h), "BODT_PARAM_ASCENT_ANGLE"));
    }
    assert_int_equal(bodt_get_param_double(h, BODT_PARAM_ASCENT_ANGLE, &a), BODT_OK);
    assert_true(a == 25.0);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_ASCENT_ANGLE, 1), BODT_ERR_INVALID_ARGUMENT);

    enum { STEPS_RUN = 30 };
    double last_min[2] = {0, 0};
    const double *after_first[2] = {NULL, NULL};
    int32_t first_count[2] = {0, 0};
    const double v0 = total_volume(h, m->ntets);
    for (int with = 0; with <= 1; ++with) {
        bodt_mesh *g = create_smoothing(m, BODT_MODE_BODT);
        assert_int_equal(bodt_set_param_int(g, BODT_PARAM_OPS, BODT_OPS_MODE_DEFAULT), BODT_OK);
        assert_int_equal(bodt_set_param_double(g, BODT_PARAM_ASCENT_ANGLE, with ? 30.0 : 0.0), BODT_OK);
        bodt_step_report r, before;
        step_ok(g, &r);
        int32_t nv = 0, nt = 0;
        assert_int_equal(bodt_mesh_get_counts(g, &nv, &nt, NULL), BODT_OK);
        after_first[with] = get_xyz(g, nv);
        first_count[with] = nv;
        for (int k = 1; k < STEPS_RUN; ++k) {
            before = r;
            step_ok(g, &r);
            if (r.min_dihedral < before.min_dihedral || r.max_dihedral > before.max_dihedral)
                fail_msg("ascent %d, step %d: extremes %.6f / %.6f after %.6f / %.6f", with, k + 1, r.min_dihedral,
                         r.max_dihedral, before.min_dihedral, before.max_dihedral);
        }
        last_min[with] = r.min_dihedral;
        assert_int_equal(bodt_mesh_get_counts(g, &nv, &nt, NULL), BODT_OK);
        const double v = total_volume(g, nt);
        if (!(fabs(v - v0) <= 1e-12 * fabs(v0))) fail_msg("ascent %d: volume %.17g, was %.17g", with, v, v0);
    }
    if (first_count[0] != first_count[1] ||
        memcmp(after_first[0], after_first[1], 3 * (size_t)first_count[0] * sizeof(double)) != 0)
        fail_msg("the first step differs with the ascent");
    print_message("smallest angle after %d steps: %.3f without the ascent, %.3f with\n", STEPS_RUN, last_min[0],
                  last_min[1]);
    if (!(last_min[1] > last_min[0] + 0.1)) fail_msg("the ascent did not raise the smallest angle");

    const int others[] = {BODT_MODE_ODT, BODT_MODE_BODT_BASIC};
    for (int o = 0; o < 2; ++o) {
        const double *xyz[2];
        for (int with = 0; with <= 1; ++with) {
            bodt_mesh *g = create_smoothing(m, others[o]);
            assert_int_equal(bodt_set_param_double(g, BODT_PARAM_ASCENT_ANGLE, with ? 30.0 : 0.0), BODT_OK);
            bodt_step_report r;
            for (int k = 0; k < 5; ++k) step_ok(g, &r);
            xyz[with] = get_xyz(g, m->nverts);
        }
        if (memcmp(xyz[0], xyz[1], 3 * (size_t)m->nverts * sizeof(double)) != 0)
            fail_msg("mode %d reads BODT_PARAM_ASCENT_ANGLE", others[o]);
    }
}

/* The ascent moves surface and feature-line vertices too, along their
 * plane or line, where that keeps the boundary's shape.  On a slab one
 * cube thick (every vertex on the boundary, so only they can move) whose
 * vertices slid along their faces and edges, smoothing alone for 20 steps:
 * ascent 30 ends with a larger smallest angle than ascent 0 (24.7 and 34.8
 * degrees when written); with either, no vertex left its plane or line and
 * the volume stayed; the two runs put boundary vertices apart. */
static int keep_slab(int i, int j, int k, int n, void *user) {
    (void)i, (void)j, (void)n, (void)user;
    return k == 0;
}

static void test_angle_ascent_boundary(void **state) {
    (void)state;
    const shape s = make_sliding(4, 1.0, keep_slab, NULL, 0.0, 0.4, 25);
    const test_mesh *m = s.m;
    double last_min[2] = {0, 0};
    const double *xyz[2] = {NULL, NULL};
    for (int with = 0; with <= 1; ++with) {
        bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_ASCENT_ANGLE, with ? 30.0 : 0.0), BODT_OK);
        const double v0 = total_volume(h, m->ntets);
        bodt_step_report r;
        for (int k = 0; k < 20; ++k) step_ok(h, &r);
        last_min[with] = r.min_dihedral;
        xyz[with] = get_xyz(h, m->nverts);
        for (int nfree = 1; nfree <= 2; ++nfree) {
            const double off = max_off_constraint(&s, xyz[with], nfree);
            if (!(off <= 1e-12)) fail_msg("ascent %d: a vertex with %d free axes left them by %g", with, nfree, off);
        }
        const double v = total_volume(h, m->ntets);
        if (!(fabs(v - v0) <= 1e-12 * v0)) fail_msg("ascent %d: volume %.17g, was %.17g", with, v, v0);
    }
    double apart = 0.0; /* boundary vertices: how far the two runs put them apart */
    for (int32_t v = 0; v < m->nverts; ++v)
        if (m->boundary[v])
            for (int a = 0; a < 3; ++a) apart = fmax(apart, fabs(xyz[1][3 * v + a] - xyz[0][3 * v + a]));
    print_message("boundary box: smallest angle %.3f without the ascent, %.3f with; boundary vertices %.3g apart\n",
                  last_min[0], last_min[1], apart);
    if (!(apart > 1e-3)) fail_msg("the ascent moved no boundary vertex");
    if (!(last_min[1] > last_min[0] + 0.1)) fail_msg("the ascent did not raise the smallest angle");
}

/* ---------------------------------------------------------------- 2 ODT */

static void test_odt_moves_interior_only(void **state) {
    (void)state;
    const shape s = make_sliding(5, 1.0, NULL, NULL, 0.3, 0.3, 21);
    const test_mesh *m = s.m;
    bodt_mesh *h = create_smoothing(m, BODT_MODE_ODT);
    const int32_t interior = tm_count_interior(m);
    assert_int_equal(interior, 64);
    for (int k = 0; k < 5; ++k) {
        bodt_step_report r;
        step_ok(h, &r);
        /* ODT works on the interior vertices only */
        assert_true(r.vertices_moved + r.moves_rejected + r.not_positive_definite <= interior);
        assert_true(r.vertices_moved > 0);
    }
    const double *xyz = get_xyz(h, m->nverts);
    int moved = 0;
    for (int32_t v = 0; v < m->nverts; ++v) {
        if (m->boundary[v]) {
            if (memcmp(&xyz[3 * v], &m->xyz[3 * v], 3 * sizeof(double)) != 0)
                fail_msg("ODT moved boundary vertex %d", v);
        } else {
            moved += memcmp(&xyz[3 * v], &m->xyz[3 * v], 3 * sizeof(double)) != 0;
        }
    }
    print_message("ODT: %d of %d interior vertices moved\n", moved, interior);
    assert_true(moved > interior / 2);
}

/* ----------------------------------------------------------- 3 features */

/* BODT on a box: corners bit for bit, edge vertices on their lines, face
 * vertices on their planes, all to 1e-12 of the box size; and edge and face
 * vertices do move. */
static void test_features_box(void **state) {
    (void)state;
    /* The same box in metres, micrometres and kilometres: nothing in the
     * moves may depend on the unit. */
    static const double sizes[] = {2.0, 2e-6, 2e6};
    for (int si = 0; si < 3; ++si) {
        const double size = sizes[si];
        const shape s = make_sliding(4, size, NULL, NULL, 0.25, 0.3, 31);
        const test_mesh *m = s.m;
        /* never_worse 0 and 1; and (variant 2) with the feature angle at 180
         * degrees, so that the lines come from tensor voting (direction e2 of
         * eq. 11) instead of feature edges */
        for (int variant = 0; variant < 3; ++variant) {
            const int nw = variant == 1;
            bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
            assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, nw), BODT_OK);
            if (variant == 2) assert_int_equal(bodt_set_param_double(h, BODT_PARAM_FEATURE_ANGLE, 180.0), BODT_OK);
            for (int k = 0; k < 10; ++k) {
                bodt_step_report r;
                step_ok(h, &r);
                const double *xyz = get_xyz(h, m->nverts);
                for (int32_t v = 0; v < m->nverts; ++v)
                    if (s.axes[v] == 0 && memcmp(&xyz[3 * v], &m->xyz[3 * v], 3 * sizeof(double)) != 0)
                        fail_msg("variant %d, step %d: corner %d moved", variant, k + 1, v);
                const double off_line = max_off_constraint(&s, xyz, 1);
                const double off_plane = max_off_constraint(&s, xyz, 2);
                if (!(off_line <= 1e-12 * size))
                    fail_msg("variant %d: an edge vertex left its line by %g", variant, off_line);
                if (!(off_plane <= 1e-12 * size))
                    fail_msg("variant %d: a face vertex left its plane by %g", variant, off_plane);
            }
            const double *xyz = get_xyz(h, m->nverts);
            const double edge_moved = max_move_of(&s, xyz, 1), face_moved = max_move_of(&s, xyz, 2);
            print_message("BODT, size %g, never_worse %d%s: edge vertices moved up to %.3g, face vertices %.3g\n", size,
                          nw, variant == 2 ? ", tensor voting" : "", edge_moved, face_moved);
            if (!(edge_moved > 1e-6 * size && face_moved > 1e-6 * size))
                fail_msg("size %g, variant %d: edge vertices moved %g, face vertices %g", size, variant, edge_moved,
                         face_moved);
        }
    }

    const double size = 2.0;
    const shape s = make_sliding(4, size, NULL, NULL, 0.25, 0.3, 31);
    const test_mesh *m = s.m;

    /* BODT_BASIC moves every boundary vertex in its tangent plane, also
     * corners and edge vertices: some leave their lines. */
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT_BASIC);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, 0), BODT_OK);
    for (int k = 0; k < 10; ++k) {
        bodt_step_report r;
        step_ok(h, &r);
    }
    const double *xyz = get_xyz(h, m->nverts);
    const double corner_off = max_off_constraint(&s, xyz, 0), line_off = max_off_constraint(&s, xyz, 1);
    print_message("BODT_BASIC: corners moved up to %.3g, edge vertices left their lines by up to %.3g\n", corner_off,
                  line_off);
    assert_true(fmax(corner_off, line_off) > 1e-6);
}

/* A chain of surface edges along the diagonal x = y of the face z = 0,
 * marked as feature edges: its inner vertices become FEATURE_LINE and stay
 * on the diagonal (without the marks they leave it). */
static void test_user_feature_line(void **state) {
    (void)state;
    enum { N = 5 };
    const double h_grid = 1.0 / N;
    const shape s = make_sliding(N, 1.0, NULL, NULL, 0.25, 0.2, 41);
    test_mesh *m = s.m;
    /* The Kuhn cubes split the face z = 0 along (i, i) -> (i + 1, i + 1).
     * Put the diagonal's inner vertices back on it, jittered along it. */
    tm_rng rng;
    tm_rng_seed(&rng, 4242);
    int32_t diag[N + 1];
    for (int t = 0; t <= N; ++t) {
        diag[t] = grid_vertex(N, t, t, 0);
        if (t == 0 || t == N) continue;
        const double x = (t + 0.4 * (tm_rng_uniform(&rng) - 0.5)) * h_grid;
        m->xyz[3 * diag[t]] = m->xyz[3 * diag[t] + 1] = x;
        assert_true(m->xyz[3 * diag[t] + 2] == 0.0);
    }
    int32_t edges[2 * N];
    for (int t = 0; t < N; ++t) {
        edges[2 * t] = diag[t];
        edges[2 * t + 1] = diag[t + 1];
    }
    for (int marked = 0; marked <= 1; ++marked) {
        bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
        if (marked) assert_int_equal(bodt_mesh_set_feature_edges(h, N, edges), BODT_OK);
        const int32_t *cls = get_classes(h, m->nverts);
        for (int t = 1; t < N; ++t)
            assert_int_equal(cls[diag[t]], marked ? BODT_VERTEX_FEATURE_LINE : BODT_VERTEX_SURFACE);
        assert_int_equal(cls[diag[0]], BODT_VERTEX_CORNER);
        assert_int_equal(cls[diag[N]], BODT_VERTEX_CORNER);
        double off = 0.0, moved = 0.0;
        for (int k = 0; k < 10; ++k) {
            bodt_step_report r;
            step_ok(h, &r);
            const double *xyz = get_xyz(h, m->nverts);
            for (int t = 1; t < N; ++t) {
                const double *p = &xyz[3 * diag[t]];
                off = fmax(off, fmax(fabs(p[0] - p[1]), fabs(p[2])));
                moved = fmax(moved, fabs(p[0] - m->xyz[3 * diag[t]]));
            }
        }
        print_message("diagonal %s: left the line by up to %.3g, moved along it by up to %.3g\n",
                      marked ? "marked" : "not marked", off, moved);
        if (marked) {
            assert_true(off <= 1e-12);
            assert_true(moved > 1e-6);
        } else {
            assert_true(off > 1e-6);
        }
    }
}

/* Edges that are not edges of a boundary face are refused, and the earlier
 * list stays. */
static void test_feature_edges_refused(void **state) {
    (void)state;
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_int_equal(tm_make_box(m, 3, 0.0, 1), 0);
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    const int32_t good[2] = {grid_vertex(3, 0, 0, 0), grid_vertex(3, 1, 1, 0)}; /* a face diagonal */
    assert_int_equal(bodt_mesh_set_feature_edges(h, 1, good), BODT_OK);
    const int32_t refused[][2] = {
        {grid_vertex(3, 0, 0, 0), grid_vertex(3, 1, 1, 1)}, /* a mesh edge into the interior */
        {grid_vertex(3, 1, 1, 1), grid_vertex(3, 2, 2, 2)}, /* between two interior vertices */
        {grid_vertex(3, 1, 0, 0), grid_vertex(3, 0, 1, 0)}, /* boundary vertices, not an edge */
        {grid_vertex(3, 0, 0, 0), grid_vertex(3, 0, 0, 0)}, /* degenerate */
    };
    for (size_t e = 0; e < sizeof refused / sizeof refused[0]; ++e) {
        const int32_t two[4] = {good[0], good[1], refused[e][0], refused[e][1]};
        assert_int_equal(bodt_mesh_set_feature_edges(h, 2, two), BODT_ERR_INVALID_ARGUMENT);
        assert_contains(bodt_mesh_last_error(h), "feature edge 1");
        int32_t count = -1, back[2] = {-1, -1};
        assert_int_equal(bodt_mesh_get_feature_edges(h, &count, back, 1), BODT_OK);
        assert_int_equal(count, 1);
        assert_int_equal(back[0], good[0]);
        assert_int_equal(back[1], good[1]);
    }

    /* A mesh edge joining two boundary vertices through the inside: the main
     * diagonal of a single cube. */
    test_mesh *c = cleanup_add(calloc(1, sizeof *c), cleanup_free_test_mesh);
    assert_int_equal(tm_make_box(c, 1, 0.0, 1), 0);
    bodt_mesh *hc = create_smoothing(c, BODT_MODE_BODT);
    const int32_t diagonal[2] = {0, 7};
    assert_int_equal(bodt_mesh_set_feature_edges(hc, 1, diagonal), BODT_ERR_INVALID_ARGUMENT);
    const int32_t side[2] = {0, 3}; /* the diagonal of the face z = 0 */
    assert_int_equal(bodt_mesh_set_feature_edges(hc, 1, side), BODT_OK);
}

/* Fixed vertices (corner, edge, face and interior ones) never move, in any
 * mode, while others do. */
static void test_fixed_vertices_all_modes(void **state) {
    (void)state;
    enum { N = 4 };
    const shape s = make_sliding(N, 1.0, NULL, NULL, 0.3, 0.3, 51);
    const test_mesh *m = s.m;
    const int32_t fixed[] = {grid_vertex(N, 0, 0, 0), grid_vertex(N, 2, 0, 0), grid_vertex(N, 2, 2, 0),
                             grid_vertex(N, 1, 1, 1), grid_vertex(N, 2, 2, 2), grid_vertex(N, 3, 1, 2),
                             grid_vertex(N, 4, 2, 3)};
    const int nfixed = (int)(sizeof fixed / sizeof fixed[0]);
    static const int modes[5] = {BODT_MODE_LAPLACE, BODT_MODE_ODT, BODT_MODE_BODT_BASIC, BODT_MODE_BODT,
                                 BODT_MODE_NODT};
    for (int mi = 0; mi < 5; ++mi) {
        bodt_mesh *h = create_smoothing(m, modes[mi]);
        assert_int_equal(bodt_mesh_set_fixed_vertices(h, nfixed, fixed), BODT_OK);
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, 0), BODT_OK);
        const int32_t *cls = get_classes(h, m->nverts);
        for (int f = 0; f < nfixed; ++f) assert_int_equal(cls[fixed[f]], BODT_VERTEX_FIXED);
        int others_moved = 0;
        for (int k = 0; k < 10; ++k) {
            bodt_step_report r;
            step_ok(h, &r);
            const double *xyz = get_xyz(h, m->nverts);
            for (int f = 0; f < nfixed; ++f)
                if (memcmp(&xyz[3 * fixed[f]], &m->xyz[3 * fixed[f]], 3 * sizeof(double)) != 0)
                    fail_msg("mode %d: fixed vertex %d moved", modes[mi], fixed[f]);
            for (int32_t v = 0; v < m->nverts; ++v)
                others_moved += memcmp(&xyz[3 * v], &m->xyz[3 * v], 3 * sizeof(double)) != 0;
        }
        assert_true(others_moved > 0);
    }
}

/* ------------------------------------------------------------ 5 classes */

static void expect_classes_by_axes(const shape *s, const int32_t *cls, const char *name) {
    int count[6] = {0};
    for (int32_t v = 0; v < s->m->nverts; ++v) {
        const int want = expected_class(s->axes[v]);
        if (cls[v] != want)
            fail_msg("%s: vertex %d (%.4f %.4f %.4f, free axes %d) has class %d, expected %d", name, v,
                     s->m->xyz[3 * v], s->m->xyz[3 * v + 1], s->m->xyz[3 * v + 2], s->axes[v], cls[v], want);
        ++count[cls[v]];
    }
    print_message("%s: %d interior, %d surface, %d feature-line, %d corner\n", name, count[0], count[1], count[2],
                  count[3]);
}

static void test_classes_box(void **state) {
    (void)state;
    enum { N = 5 };
    const shape s = make_sliding(N, 1.0, NULL, NULL, 0.25, 0.25, 61);
    const test_mesh *m = s.m;
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    const int32_t *cls = get_classes(h, m->nverts);
    expect_classes_by_axes(&s, cls, "box");
    int count[6] = {0};
    for (int32_t v = 0; v < m->nverts; ++v) ++count[cls[v]];
    assert_int_equal(count[BODT_VERTEX_CORNER], 8);
    assert_int_equal(count[BODT_VERTEX_FEATURE_LINE], 12 * (N - 1));
    assert_int_equal(count[BODT_VERTEX_SURFACE], 6 * (N - 1) * (N - 1));
    assert_int_equal(count[BODT_VERTEX_INTERIOR], (N - 1) * (N - 1) * (N - 1));

    /* The other modes find no features: every boundary vertex is SURFACE. */
    static const int others[3] = {BODT_MODE_LAPLACE, BODT_MODE_ODT, BODT_MODE_BODT_BASIC};
    for (int k = 0; k < 3; ++k) {
        assert_int_equal(bodt_set_mode(h, others[k]), BODT_OK);
        const int32_t *c = get_classes(h, m->nverts);
        for (int32_t v = 0; v < m->nverts; ++v)
            assert_int_equal(c[v], m->boundary[v] ? BODT_VERTEX_SURFACE : BODT_VERTEX_INTERIOR);
    }
    /* NODT classifies as BODT does; and back */
    assert_int_equal(bodt_set_mode(h, BODT_MODE_NODT), BODT_OK);
    expect_classes_by_axes(&s, get_classes(h, m->nverts), "box, NODT");
    assert_int_equal(bodt_set_mode(h, BODT_MODE_BODT), BODT_OK);
    expect_classes_by_axes(&s, get_classes(h, m->nverts), "box again");

    /* Either detector alone finds the same: feature edges (90 degrees > the
     * feature angle) with tensor voting off (ratios 1), ... */
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_EDGE_RATIO, 1.0), BODT_OK);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_CORNER_RATIO, 1.0), BODT_OK);
    expect_classes_by_axes(&s, get_classes(h, m->nverts), "box, feature edges only");
    /* ... and tensor voting, eq. (11), with no feature edge (angle 180). */
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_EDGE_RATIO, 0.2), BODT_OK);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_CORNER_RATIO, 0.2), BODT_OK);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_FEATURE_ANGLE, 180.0), BODT_OK);
    expect_classes_by_axes(&s, get_classes(h, m->nverts), "box, tensor voting only");
    /* a feature angle above 90 degrees and no tensor voting: no feature at all */
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_EDGE_RATIO, 1.0), BODT_OK);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_CORNER_RATIO, 1.0), BODT_OK);
    const int32_t *none = get_classes(h, m->nverts);
    for (int32_t v = 0; v < m->nverts; ++v)
        assert_int_equal(none[v], m->boundary[v] ? BODT_VERTEX_SURFACE : BODT_VERTEX_INTERIOR);
}

/* A cylinder of radius 1 and height 2: a 6^3 Kuhn box on [0, 2]^3 mapped
 * by the elliptical grid mapping. */
static test_mesh *make_cylinder(void) {
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_non_null(m);
    assert_int_equal(tm_make_cubes(m, 6, 2.0, NULL, NULL, 0.0, 1), 0);
    assert_int_equal(tm_map_square_to_disk(m), 0);
    return m;
}

static int on_cap(const test_mesh *m, int32_t v) {
    const double z = m->xyz[3 * v + 2];
    return m->boundary[v] && (z == 0.0 || z == 2.0);
}

static int on_side(const test_mesh *m, int32_t v) {
    const double *p = &m->xyz[3 * v];
    return m->boundary[v] && fabs(sqrt(p[0] * p[0] + p[1] * p[1]) - 1.0) < 1e-12;
}

/* The cylinder's two rims (90 degree edges) are feature lines; the side and
 * the caps are smooth surfaces; no corners (the rim turns by at most 17
 * degrees from vertex to vertex).  BODT steps keep the volume. */
static void test_classes_cylinder(void **state) {
    (void)state;
    enum { N = 6 };
    const test_mesh *m = make_cylinder();
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    const int32_t *cls = get_classes(h, m->nverts);
    int rim = 0, side = 0, cap = 0;
    for (int32_t v = 0; v < m->nverts; ++v) {
        const double *p = &m->xyz[3 * v];
        int want;
        if (!m->boundary[v]) want = BODT_VERTEX_INTERIOR;
        else if (on_cap(m, v) && on_side(m, v)) want = BODT_VERTEX_FEATURE_LINE, ++rim;
        else want = BODT_VERTEX_SURFACE, side += on_side(m, v), cap += on_cap(m, v);
        assert_true(!m->boundary[v] || on_cap(m, v) || on_side(m, v));
        if (cls[v] != want)
            fail_msg("cylinder: vertex %d (%.4f %.4f %.4f) has class %d, expected %d", v, p[0], p[1], p[2], cls[v],
                     want);
    }
    assert_int_equal(rim, 2 * 4 * N);
    assert_int_equal(side, 4 * N * (N - 1));
    assert_int_equal(cap, 2 * (N - 1) * (N - 1));
    print_message("cylinder: %d rim, %d side, %d cap vertices\n", rim, side, cap);

    const double v0 = total_volume(h, m->ntets);
    for (int k = 0; k < 5; ++k) {
        bodt_step_report r;
        step_ok(h, &r);
        assert_true(r.vertices_moved > 0);
    }
    assert_near(total_volume(h, m->ntets), v0, 1e-12 * v0);
}

/* The cylinder's caps are flat faces: BODT moves its rim vertices along the
 * rim and its cap vertices in the cap plane, so every cap vertex, rim
 * vertices included, keeps z = 0 or z = 2 -- as the box's faces keep their
 * planes.  (A move along n_cap x n_side keeps the volume and the cap.) */
static void test_cylinder_caps_stay_flat(void **state) {
    (void)state;
    const test_mesh *m = make_cylinder();
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    const int32_t *cls = get_classes(h, m->nverts);
    for (int k = 0; k < 5; ++k) {
        bodt_step_report r;
        step_ok(h, &r);
    }
    const double *xyz = get_xyz(h, m->nverts);
    double rim_off = 0.0, cap_off = 0.0, cap_moved = 0.0;
    int32_t worst = -1;
    for (int32_t v = 0; v < m->nverts; ++v) {
        if (!on_cap(m, v)) continue;
        const double off = fabs(xyz[3 * v + 2] - m->xyz[3 * v + 2]);
        if (cls[v] == BODT_VERTEX_FEATURE_LINE) {
            if (off > rim_off) rim_off = off, worst = v;
        } else {
            cap_off = fmax(cap_off, off);
        }
        cap_moved = fmax(cap_moved, fabs(xyz[3 * v] - m->xyz[3 * v]) + fabs(xyz[3 * v + 1] - m->xyz[3 * v + 1]));
    }
    print_message("cylinder: rim vertices left their cap plane by up to %.3g (vertex %d), cap vertices by %.3g\n",
                  rim_off, worst, cap_off);
    assert_true(cap_moved > 1e-6);
    if (!(rim_off <= 1e-12 && cap_off <= 1e-12))
        fail_msg("after 5 BODT steps a rim vertex is %.3g and a cap vertex %.3g off its flat cap", rim_off, cap_off);
}

/* A box whose top is a roof: two flat pieces rising 10 degrees to a ridge
 * along x = 1, so they meet at 20 degrees, below the feature angle (30).
 * The ridge vertices are SURFACE vertices; BODT moves them along the ridge
 * only, and every roof vertex stays on the roof (FlatPieces: creases from
 * half the feature angle are kept), as the volume is.  With the feature
 * angle at 50 degrees (creases from 25) the ridge is smoothed over as a
 * curved surface would be: a ridge vertex leaves the roof. */
static double roof_height(double x, double slope) { return 2.0 + slope * fmin(x, 2.0 - x); }

static void test_shallow_ridge(void **state) {
    (void)state;
    const double slope = tan(10.0 * acos(-1.0) / 180.0);
    const shape s = make_sliding(4, 2.0, NULL, NULL, 0.25, 0.3, 47);
    test_mesh *m = s.m;
    unsigned char *ridge = cleanup_calloc((size_t)m->nverts);
    for (int32_t v = 0; v < m->nverts; ++v) {
        double *p = &m->xyz[3 * v];
        const int roof = p[2] == 2.0;
        /* The top vertices of the grid line x = 1 go back onto it, so no
         * roof triangle crosses the ridge; then z is scaled up to the roof. */
        if (roof && fabs(p[0] - 1.0) < 0.25) {
            p[0] = 1.0;
            ridge[v] = p[1] > 0.0 && p[1] < 2.0;
        }
        p[2] *= roof_height(p[0], slope) / 2.0;
    }
    for (int variant = 0; variant < 2; ++variant) {
        bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
        if (variant == 1) assert_int_equal(bodt_set_param_double(h, BODT_PARAM_FEATURE_ANGLE, 50.0), BODT_OK);
        const double volume = total_volume(h, m->ntets);
        const int32_t *cls = get_classes(h, m->nverts);
        for (int k = 0; k < 10; ++k) {
            bodt_step_report r;
            step_ok(h, &r);
        }
        const double *xyz = get_xyz(h, m->nverts);
        double off_roof = 0.0, off_ridge = 0.0, along_ridge = 0.0, roof_moved = 0.0;
        int ridge_count = 0;
        for (int32_t v = 0; v < m->nverts; ++v) {
            const double *p = &xyz[3 * v], *p0 = &m->xyz[3 * v];
            if (p0[2] != roof_height(p0[0], slope)) continue;
            off_roof = fmax(off_roof, fabs(p[2] - roof_height(p[0], slope)));
            roof_moved = fmax(roof_moved, fabs(p[0] - p0[0]) + fabs(p[1] - p0[1]));
            if (!ridge[v]) continue;
            ++ridge_count;
            assert_int_equal(cls[v], BODT_VERTEX_SURFACE);
            off_ridge = fmax(off_ridge, fabs(p[0] - 1.0));
            along_ridge = fmax(along_ridge, fabs(p[1] - p0[1]));
        }
        print_message("roof, feature angle %d: %d ridge vertices; off the roof by up to %.3g, off the ridge by %.3g, "
                      "along it %.3g; roof vertices moved up to %.3g\n",
                      variant ? 50 : 30, ridge_count, off_roof, off_ridge, along_ridge, roof_moved);
        assert_int_equal(ridge_count, 3);
        assert_near(total_volume(h, m->ntets), volume, 1e-12 * volume);
        if (variant == 0) {
            if (!(off_roof <= 1e-12 && off_ridge <= 1e-12))
                fail_msg("a roof vertex left the roof by %g, a ridge vertex the ridge by %g", off_roof, off_ridge);
            assert_true(along_ridge > 1e-6 && roof_moved > 1e-6);
        } else {
            assert_true(off_roof > 1e-6);
        }
    }
}

/* The unit ball (a 6^3 Kuhn box mapped onto it): with the default feature
 * angle and ratios no feature is found, every boundary vertex is SURFACE. */
static void test_classes_ball(void **state) {
    (void)state;
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_int_equal(tm_make_cubes(m, 6, 2.0, NULL, NULL, 0.0, 1), 0);
    assert_int_equal(tm_map_cube_to_ball(m), 0);
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    const int32_t *cls = get_classes(h, m->nverts);
    int nb = 0;
    for (int32_t v = 0; v < m->nverts; ++v) {
        const double *p = &m->xyz[3 * v];
        if (m->boundary[v]) assert_near(p[0] * p[0] + p[1] * p[1] + p[2] * p[2], 1.0, 1e-12);
        nb += m->boundary[v];
        assert_int_equal(cls[v], m->boundary[v] ? BODT_VERTEX_SURFACE : BODT_VERTEX_INTERIOR);
    }
    assert_int_equal(nb, 6 * 6 * 6 + 2);
}

/* Two regions split by the plane x = 1/2: interface vertices are SURFACE
 * inside the box, FEATURE_LINE where the interface meets a face, CORNER
 * where it meets an edge; BODT steps keep both regions' volumes and the
 * interface vertices on the interface plane (in fact every vertex on its
 * plane, line or corner). */
static void test_two_regions(void **state) {
    (void)state;
    enum { N = 6 };
    const shape s = make_sliding(N, 1.0, NULL, region_halves, 0.25, 0.25, 71);
    const test_mesh *m = s.m;
    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    assert_int_equal(bodt_mesh_set_regions(h, s.regions), BODT_OK);
    int32_t nbf = 0;
    assert_int_equal(bodt_mesh_get_counts(h, NULL, NULL, &nbf), BODT_OK);
    assert_int_equal(nbf, 6 * 2 * N * N + 2 * N * N); /* boundary + interface triangles */
    const int32_t *cls = get_classes(h, m->nverts);
    expect_classes_by_axes(&s, cls, "two regions");
    /* the interface: free axes without x, at x = 1/2 */
    int interface_count[4] = {0};
    for (int32_t v = 0; v < m->nverts; ++v)
        if (!(s.axes[v] & 1) && fabs(m->xyz[3 * v] - 0.5) < 1e-12) ++interface_count[cls[v]];
    assert_int_equal(interface_count[BODT_VERTEX_SURFACE], (N - 1) * (N - 1));
    assert_int_equal(interface_count[BODT_VERTEX_FEATURE_LINE], 4 * (N - 1));
    assert_int_equal(interface_count[BODT_VERTEX_CORNER], 4);

    /* BODT_BASIC: no feature lines or corners, but an interface vertex on
     * the boundary has two ring normals and moves along the one direction
     * that keeps both regions' volumes.  (Nothing else is kept in this mode:
     * box edges and corners move, and with them the interface.) */
    {
        bodt_mesh *basic = create_smoothing(m, BODT_MODE_BODT_BASIC);
        assert_int_equal(bodt_mesh_set_regions(basic, s.regions), BODT_OK);
        assert_int_equal(bodt_set_param_int(basic, BODT_PARAM_NEVER_WORSE, 0), BODT_OK);
        const double b0 = region_volume(basic, m->ntets, 0), b1 = region_volume(basic, m->ntets, 1);
        for (int k = 0; k < 5; ++k) {
            bodt_step_report r;
            step_ok(basic, &r);
            const double a = region_volume(basic, m->ntets, 0), b = region_volume(basic, m->ntets, 1);
            if (!(fabs(a - b0) <= 1e-12 * b0 && fabs(b - b1) <= 1e-12 * b1))
                fail_msg("BODT_BASIC, step %d: region volumes %.17g %.17g -> %.17g %.17g", k + 1, b0, b1, a, b);
        }
        const double *xyz = get_xyz(basic, m->nverts);
        double moved = 0.0;
        for (int32_t v = 0; v < m->nverts; ++v)
            if (!(s.axes[v] & 1) && popcount3(s.axes[v]) == 1 && fabs(m->xyz[3 * v] - 0.5) < 1e-12)
                moved = fmax(moved, fabs(xyz[3 * v + 1] - m->xyz[3 * v + 1]) + fabs(xyz[3 * v + 2] - m->xyz[3 * v + 2]));
        print_message("two regions, BODT_BASIC: interface vertices on the box faces moved by up to %.3g\n", moved);
        assert_true(moved > 1e-6);
    }

    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, 0), BODT_OK);
    const double r0 = region_volume(h, m->ntets, 0), r1 = region_volume(h, m->ntets, 1);
    assert_near(r0, 0.5, 1e-12);
    for (int k = 0; k < 10; ++k) {
        bodt_step_report r;
        step_ok(h, &r);
        const double a = region_volume(h, m->ntets, 0), b = region_volume(h, m->ntets, 1);
        if (!(fabs(a - r0) <= 1e-12 * r0 && fabs(b - r1) <= 1e-12 * r1))
            fail_msg("step %d: region volumes %.17g %.17g -> %.17g %.17g", k + 1, r0, r1, a, b);
        const double *xyz = get_xyz(h, m->nverts);
        for (int nfree = 0; nfree <= 2; ++nfree) {
            const double off = max_off_constraint(&s, xyz, nfree);
            if (!(off <= 1e-12)) fail_msg("step %d: a vertex with %d free axes left its place by %g", k + 1, nfree, off);
        }
    }
    const double *xyz = get_xyz(h, m->nverts);
    double interface_moved = 0.0;
    for (int32_t v = 0; v < m->nverts; ++v)
        if (!(s.axes[v] & 1) && s.axes[v] && fabs(m->xyz[3 * v] - 0.5) < 1e-12)
            interface_moved = fmax(interface_moved, fabs(xyz[3 * v + 1] - m->xyz[3 * v + 1]) +
                                                        fabs(xyz[3 * v + 2] - m->xyz[3 * v + 2]));
    print_message("two regions: interface vertices moved up to %.3g\n", interface_moved);
    assert_true(interface_moved > 1e-6);
}

/* ------------------------------------------------------- 6 robustness */

/* 10 jittered 3^3 meshes (boxes, L-shapes, notched boxes, two-region boxes,
 * half of them graded) x 200 steps, switching between ODT, BODT_BASIC and
 * BODT and between NEVER_WORSE 0 and 1: no tet ever inverts, the volume
 * stays, the reports add up, and with NEVER_WORSE = 1 the extreme dihedral
 * angles never get worse. */
static void test_robustness(void **state) {
    (void)state;
    static const int modes[3] = {BODT_MODE_ODT, BODT_MODE_BODT_BASIC, BODT_MODE_BODT};
    int total_steps = 0;
    long moved = 0, npd = 0, rejected = 0, flips = 0, inserted = 0;
    for (int mesh = 0; mesh < 10; ++mesh) {
        const tm_cube_filter keep = mesh % 3 == 1 ? keep_l_shape : mesh % 3 == 2 ? keep_notch : NULL;
        const tm_cube_region region = mesh % 4 == 3 ? region_halves : NULL;
        const double size = 1.0 + mesh;
        /* strong jitter, half of the meshes graded along one axis (thin
         * tets; planes stay planes): the first seed that inverts no tet */
        test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
        int32_t *regions = NULL;
        for (uint64_t seed = 1000 + 100 * (uint64_t)mesh;; ++seed) {
            const int st = tm_make_cubes_sliding(m, 3, size, keep, region, NULL, 0.3, 0.3, seed, NULL, &regions);
            if (st == -2) continue;
            assert_int_equal(st, 0);
            if (mesh % 2) {
                const int axis = mesh % 3;
                for (int32_t v = 0; v < m->nverts; ++v)
                    m->xyz[3 * v + axis] = size * pow(m->xyz[3 * v + axis] / size, 2.0);
            }
            int ok = 1;
            for (int32_t t = 0; t < m->ntets; ++t) {
                const int32_t *c = &m->tets[4 * t];
                ok &= tm_orient6(&m->xyz[3 * c[0]], &m->xyz[3 * c[1]], &m->xyz[3 * c[2]], &m->xyz[3 * c[3]]) > 0.0;
            }
            if (ok) break;
            tm_free(m);
            free(regions);
        }
        cleanup_add(regions, free);
        bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, BODT_OPS_MODE_DEFAULT), BODT_OK);
        if (region) assert_int_equal(bodt_mesh_set_regions(h, regions), BODT_OK);
        bodt_quality q;
        get_quality(h, &q);
        const double v0 = q.volume;
        double prev_min = q.min_dihedral, prev_max = q.max_dihedral;
        for (int k = 0; k < 200; ++k) {
            const int mode = modes[(k / 7 + mesh) % 3], nw = (k / 11 + mesh) % 2;
            assert_int_equal(bodt_set_mode(h, mode), BODT_OK);
            assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, nw), BODT_OK);
            bodt_step_report r;
            step_ok(h, &r);
            ++total_steps;
            assert_int_equal(r.step, k + 1);
            assert_true(r.vertices_moved >= 0 && r.moves_rejected >= 0 && r.not_positive_definite >= 0);
            assert_true(r.moves_shortened >= 0 && r.moves_shortened <= r.vertices_moved);
            int32_t nverts_now = 0;
            assert_int_equal(bodt_mesh_get_counts(h, &nverts_now, NULL, NULL), BODT_OK);
            if (!(r.vertices_moved + r.moves_rejected + r.not_positive_definite <= nverts_now))
                fail_msg("mesh %d step %d: %d moved + %d rejected + %d not positive definite > %d vertices", mesh,
                         k + 1, r.vertices_moved, r.moves_rejected, r.not_positive_definite, nverts_now);
            /* (a vertex at its target already counts as moved, by a distance of 0) */
            if (!(r.max_move >= 0.0 && (r.max_move == 0.0 || r.vertices_moved > 0)))
                fail_msg("mesh %d step %d (mode %d): max_move %g with %d vertices moved (%d shortened)", mesh, k + 1,
                         mode, r.max_move, r.vertices_moved, r.moves_shortened);
            /* every tet positive, by the test's own orientation test; the
             * volume kept (the report carries the mesh's quality after the
             * step, checked against bodt_mesh_quality every 10 steps).  In
             * BODT_MODE_BODT the connectivity changes: read it back. */
            int32_t nv = 0, nt = 0;
            assert_int_equal(bodt_mesh_get_counts(h, &nv, &nt, NULL), BODT_OK);
            double *xyz = malloc(3 * (size_t)nv * sizeof *xyz);
            int32_t *tets = malloc(4 * (size_t)nt * sizeof *tets);
            assert_int_equal(bodt_mesh_get_vertices(h, xyz, 3 * (size_t)nv), BODT_OK);
            assert_int_equal(bodt_mesh_get_tets(h, tets, 4 * (size_t)nt), BODT_OK);
            double vol = 0.0;
            for (int32_t t = 0; t < nt; ++t) {
                const int32_t *c = &tets[4 * t];
                const double o = tm_orient6(&xyz[3 * c[0]], &xyz[3 * c[1]], &xyz[3 * c[2]], &xyz[3 * c[3]]);
                if (!(o > 0.0)) fail_msg("mesh %d step %d (mode %d): tet %d inverted (%g)", mesh, k + 1, mode, t, o);
                vol += o / 6.0;
            }
            free(xyz);
            free(tets);
            if (!(r.min_stretch > 0.0)) fail_msg("mesh %d step %d: min stretch %g", mesh, k + 1, r.min_stretch);
            if (!(fabs(vol - v0) <= 1e-12 * v0))
                fail_msg("mesh %d step %d (mode %d): volume %.17g -> %.17g", mesh, k + 1, mode, v0, vol);
            if (k % 10 == 9) {
                get_quality(h, &q);
                assert_int_equal(q.num_inverted, 0);
                assert_true(q.min_stretch > 0.0);
                assert_true(r.min_stretch == q.min_stretch && r.min_dihedral == q.min_dihedral &&
                            r.max_dihedral == q.max_dihedral);
            }
            if (nw && (r.min_dihedral < prev_min - 1e-9 || r.max_dihedral > prev_max + 1e-9))
                fail_msg("mesh %d step %d (mode %d, never_worse): dihedral range [%.12g, %.12g] -> [%.12g, %.12g]",
                         mesh, k + 1, mode, prev_min, prev_max, r.min_dihedral, r.max_dihedral);
            prev_min = r.min_dihedral;
            prev_max = r.max_dihedral;
            moved += r.vertices_moved;
            rejected += r.moves_rejected;
            npd += r.not_positive_definite;
            flips += r.flips;
            inserted += r.vertices_inserted;
        }
    }
    print_message("%d steps, %ld vertex moves, %ld rejected, %ld not positive definite, %ld flips, %ld inserted\n",
                  total_steps, moved, rejected, npd, flips, inserted);
    assert_int_equal(total_steps, 2000);
}

/* ------------------------------------------------------ 7 checkerboard */

typedef struct face_rec {
    int32_t v[3]; /* sorted */
    int32_t tet, opposite;
} face_rec;

static int cmp_face(const void *a, const void *b) {
    const face_rec *x = a, *y = b;
    for (int k = 0; k < 3; ++k)
        if (x->v[k] != y->v[k]) return x->v[k] < y->v[k] ? -1 : 1;
    return 0;
}

/* Vertices where the surface of some region (the faces of its tets with no
 * neighbour in the region) is not a manifold: the link edges (a, b) of the
 * faces (v, a, b) around v do not form one cycle (every link vertex on
 * exactly two link edges, and the link connected).  Independent of the
 * library. */
enum { MAX_LINK = 256 };

static int link_index(int32_t *verts, int *n, int32_t x) {
    for (int k = 0; k < *n; ++k)
        if (verts[k] == x) return k;
    assert_true(*n < 2 * MAX_LINK);
    verts[*n] = x;
    return (*n)++;
}

static int link_root(int *parent, int k) {
    while (parent[k] != k) k = parent[k];
    return k;
}

static unsigned char *non_manifold_vertices(const test_mesh *m, const int32_t *regions) {
    const size_t nf = 4 * (size_t)m->ntets;
    face_rec *f = malloc(nf * sizeof *f);
    assert_non_null(f);
    for (int32_t t = 0; t < m->ntets; ++t)
        for (int i = 0; i < 4; ++i) {
            face_rec *r = &f[4 * (size_t)t + i];
            int k = 0;
            for (int j = 0; j < 4; ++j)
                if (j != i) r->v[k++] = m->tets[4 * t + j];
            for (int a = 0; a < 3; ++a) /* sort the three */
                for (int b = a + 1; b < 3; ++b)
                    if (r->v[b] < r->v[a]) {
                        const int32_t x = r->v[a];
                        r->v[a] = r->v[b];
                        r->v[b] = x;
                    }
            r->tet = t;
            r->opposite = -1;
        }
    qsort(f, nf, sizeof *f, cmp_face);
    for (size_t k = 0; k + 1 < nf; ++k)
        if (cmp_face(&f[k], &f[k + 1]) == 0) {
            f[k].opposite = f[k + 1].tet;
            f[k + 1].opposite = f[k].tet;
        }
    unsigned char *bad = cleanup_calloc((size_t)m->nverts);
    int32_t rmax = 0;
    for (int32_t t = 0; t < m->ntets; ++t) rmax = regions[t] > rmax ? regions[t] : rmax;
    for (int32_t region = 0; region <= rmax; ++region)
        for (int32_t v = 0; v < m->nverts; ++v) {
            int32_t verts[2 * MAX_LINK];
            int deg[2 * MAX_LINK], parent[2 * MAX_LINK];
            int nv = 0, nlink = 0;
            for (size_t k = 0; k < nf; ++k) {
                const face_rec *r = &f[k];
                if (regions[r->tet] != region) continue;
                if (r->opposite >= 0 && regions[r->opposite] == region) continue;
                if (r->v[0] != v && r->v[1] != v && r->v[2] != v) continue;
                int ab[2], q = 0;
                for (int j = 0; j < 3; ++j)
                    if (r->v[j] != v) {
                        const int before = nv;
                        ab[q] = link_index(verts, &nv, r->v[j]);
                        if (nv > before) deg[ab[q]] = 0, parent[ab[q]] = ab[q];
                        ++deg[ab[q]];
                        ++q;
                    }
                parent[link_root(parent, ab[0])] = link_root(parent, ab[1]);
                ++nlink;
                assert_true(nlink < MAX_LINK);
            }
            if (nlink == 0) continue;
            int ok = 1;
            for (int k = 0; k < nv; ++k) ok &= deg[k] == 2 && link_root(parent, k) == link_root(parent, 0);
            if (!ok) bad[v] = 1;
        }
    free(f);
    return bad;
}

/* BODT after bodt_mesh_set_regions with regions whose surfaces are not
 * manifolds: BODT_OK, no tet inverts, the total and each region's volume
 * stay, the vertices where a region's surface is not a manifold are FIXED,
 * and FIXED vertices do not move.  Returns the number of vertex moves. */
static int check_non_manifold_regions(const shape *s, const int32_t *regions, const char *name) {
    const test_mesh *m = s->m;
    const unsigned char *bad = non_manifold_vertices(m, regions);
    int nbad = 0;
    for (int32_t v = 0; v < m->nverts; ++v) nbad += bad[v];
    assert_true(nbad > 0);

    bodt_mesh *h = create_smoothing(m, BODT_MODE_BODT);
    assert_int_equal(bodt_mesh_set_regions(h, regions), BODT_OK);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, 0), BODT_OK);
    const int32_t *cls = get_classes(h, m->nverts);
    int count[6] = {0};
    for (int32_t v = 0; v < m->nverts; ++v) {
        ++count[cls[v]];
        if (bad[v] && cls[v] != BODT_VERTEX_FIXED)
            fail_msg("%s: vertex %d: a region surface is not a manifold there, but its class is %d", name, v, cls[v]);
    }
    print_message("%s: %d non-manifold vertices; classes: %d interior, %d surface, %d line, %d corner, %d fixed\n",
                  name, nbad, count[0], count[1], count[2], count[3], count[4]);
    const double v0 = total_volume(h, m->ntets);
    const double r0 = region_volume(h, m->ntets, 0), r1 = region_volume(h, m->ntets, 1);
    int moved = 0;
    for (int k = 0; k < 5; ++k) {
        bodt_step_report r;
        step_ok(h, &r);
        moved += r.vertices_moved;
        bodt_quality q;
        get_quality(h, &q);
        assert_int_equal(q.num_inverted, 0);
        assert_true(q.min_stretch > 0.0);
        assert_near(total_volume(h, m->ntets), v0, 1e-12 * v0);
        assert_near(region_volume(h, m->ntets, 0), r0, 1e-12 * v0);
        assert_near(region_volume(h, m->ntets, 1), r1, 1e-12 * v0);
        const double *xyz = get_xyz(h, m->nverts);
        for (int32_t v = 0; v < m->nverts; ++v)
            if (cls[v] == BODT_VERTEX_FIXED && memcmp(&xyz[3 * v], &m->xyz[3 * v], 3 * sizeof(double)) != 0)
                fail_msg("%s, step %d: FIXED vertex %d moved", name, k + 1, v);
    }
    print_message("%s: %d vertex moves in 5 steps\n", name, moved);
    return moved;
}

/* Regions alternating tet by tet: every region surface is pinched almost
 * everywhere. */
static void test_checkerboard_regions(void **state) {
    (void)state;
    const shape s = make_sliding(4, 1.0, NULL, NULL, 0.25, 0.25, 81);
    const test_mesh *m = s.m;
    /* the independent check finds nothing on one region */
    int32_t *regions = cleanup_calloc((size_t)m->ntets * sizeof *regions);
    const unsigned char *none = non_manifold_vertices(m, regions);
    for (int32_t v = 0; v < m->nverts; ++v) assert_int_equal(none[v], 0);
    for (int32_t t = 0; t < m->ntets; ++t) regions[t] = t % 2;
    check_non_manifold_regions(&s, regions, "tet checkerboard");
}

/* Two regions of two diagonal quadrant columns each: their surfaces touch
 * themselves along the box's vertical centre line only.  Those vertices are
 * FIXED; the others keep moving. */
static int region_quadrants(int i, int j, int k, int n, void *user) {
    (void)k, (void)user;
    return (2 * i >= n) != (2 * j >= n);
}

static void test_pinched_regions(void **state) {
    (void)state;
    enum { N = 4 };
    const shape s = make_sliding(N, 1.0, NULL, region_quadrants, 0.25, 0.25, 82);
    const unsigned char *bad = non_manifold_vertices(s.m, s.regions);
    for (int32_t v = 0; v < s.m->nverts; ++v) {
        const int centre = fabs(s.m->xyz[3 * v] - 0.5) < 1e-12 && fabs(s.m->xyz[3 * v + 1] - 0.5) < 1e-12;
        assert_int_equal(bad[v], centre);
    }
    assert_true(check_non_manifold_regions(&s, s.regions, "quadrants") > 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_volume_box, cleanup_teardown),
        cmocka_unit_test_teardown(test_volume_l_shape, cleanup_teardown),
        cmocka_unit_test_teardown(test_volume_notch, cleanup_teardown),
        cmocka_unit_test_teardown(test_converged, cleanup_teardown),
        cmocka_unit_test_teardown(test_angle_ascent, cleanup_teardown),
        cmocka_unit_test_teardown(test_angle_ascent_boundary, cleanup_teardown),
        cmocka_unit_test_teardown(test_odt_moves_interior_only, cleanup_teardown),
        cmocka_unit_test_teardown(test_features_box, cleanup_teardown),
        cmocka_unit_test_teardown(test_user_feature_line, cleanup_teardown),
        cmocka_unit_test_teardown(test_feature_edges_refused, cleanup_teardown),
        cmocka_unit_test_teardown(test_fixed_vertices_all_modes, cleanup_teardown),
        cmocka_unit_test_teardown(test_classes_box, cleanup_teardown),
        cmocka_unit_test_teardown(test_classes_cylinder, cleanup_teardown),
        cmocka_unit_test_teardown(test_cylinder_caps_stay_flat, cleanup_teardown),
        cmocka_unit_test_teardown(test_shallow_ridge, cleanup_teardown),
        cmocka_unit_test_teardown(test_classes_ball, cleanup_teardown),
        cmocka_unit_test_teardown(test_two_regions, cleanup_teardown),
        cmocka_unit_test_teardown(test_robustness, cleanup_teardown),
        cmocka_unit_test_teardown(test_checkerboard_regions, cleanup_teardown),
        cmocka_unit_test_teardown(test_pinched_regions, cleanup_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
