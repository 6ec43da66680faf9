/*
 * test_opt_weighted_api: BODT_MODE_OPT_WEIGHTED
 * (paper 001) through libbodt.so only.  Boundary vertices, boundary faces,
 * volume and quality are checked with the test's own arithmetic on what the
 * getters give back.
 *
 *   params         WEIGHT_C, POOR_QUALITY, QN_EPSILON, QN_MAX_ITERATIONS,
 *                  QN_INITIAL_STEP, QN_INTERVAL_GROWTH: documented defaults,
 *                  both ends of each range taken, values outside refused
 *                  (BODT_ERR_INVALID_ARGUMENT, message naming the key, value
 *                  kept), the wrong type refused; set_mode(5) taken and read
 *                  back, OPS reads BODT_OPS_MODE_DEFAULT in this mode
 *   boundary kept  jittered 5x5x5 box, default ops, bodt_run 10 steps: every
 *                  boundary vertex bit for bit, the boundary faces the same
 *                  set, no inverted tet, volume to 1e-12, min stretch and min
 *                  dihedral not worse, interior vertices moved
 *   sliver         a hand-made cube whose bottom is a folded quad: a sliver
 *                  (a, b, c, d) with its four vertices on the boundary, the
 *                  rest coned to one interior vertex.  Smoothing only cannot
 *                  fix it (min dihedral stays below 5 degrees); the default
 *                  ops swap it away (flips > 0, min dihedral far above),
 *                  boundary vertices and faces as they were, volume kept
 *   gamma          POOR_QUALITY = 0: nothing to smooth, nothing moves;
 *                  POOR_QUALITY = 1: vertices move
 *   weights        jittered box with C = 0.5, 0.75, 0.9: min stretch goes
 *                  up with each, and the three results differ
 *   inverted       handles made with BODT_CREATE_ACCEPT_INVERTED (wrongly
 *                  ordered tets; tets inverted by a moved boundary or
 *                  interior vertex): bodt_step and bodt_run in this mode give
 *                  a known status; after an error the mesh is unchanged;
 *                  no more inverted tets than before
 */
#include "api_checks.h"
#include "bodt.h"
#include "cleanup.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>

/* ------------------------------------------------------------- helpers */

static void destroy_mesh(void *p) { bodt_mesh_destroy(p); }

static const double *P(const double *xyz, int32_t v) { return xyz + 3 * (size_t)v; }

/* A jittered box (tm_make_box: interior vertices jittered, boundary ones on
 * the grid), from the first seed from `seed` on that inverts no tet. */
static test_mesh *make_box(int n, double jitter, uint64_t seed) {
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_non_null(m);
    for (uint64_t s = seed; s < seed + 200; ++s) {
        const int st = tm_make_box(m, n, jitter, s);
        if (st == 0) return m;
        if (st != -2) fail_msg("tm_make_box: %d", st);
    }
    fail_msg("no seed gave a valid box");
    return m;
}

static bodt_mesh *create_ok(int32_t nv, const double *xyz, int32_t nt, const int32_t *tets, uint32_t flags) {
    bodt_mesh *h = NULL;
    const int st = bodt_mesh_create_ex(nv, xyz, nt, tets, 0, flags, &h);
    if (st != BODT_OK) fail_msg("create: %s: %s", bodt_status_string(st), bodt_mesh_last_error(NULL));
    cleanup_add(h, destroy_mesh);
    return h;
}

static bodt_mesh *create_mode5(const test_mesh *m) {
    bodt_mesh *h = create_ok(m->nverts, m->xyz, m->ntets, m->tets, 0);
    assert_int_equal(bodt_set_mode(h, BODT_MODE_OPT_WEIGHTED), BODT_OK);
    return h;
}

/* Everything a check below needs, taken through the getters. */
typedef struct snap {
    int32_t nv, nt, nb;
    double *xyz;
    int32_t *tets;
    int32_t *faces; /* each triple sorted, the triples sorted */
    double volume;  /* from the test's own orient6 */
    int32_t inverted;
} snap;

static int cmp_triple(const void *a, const void *b) {
    const int32_t *x = a, *y = b;
    for (int k = 0; k < 3; ++k)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

static snap take(const bodt_mesh *h) {
    snap s;
    assert_int_equal(bodt_mesh_get_counts(h, &s.nv, &s.nt, &s.nb), BODT_OK);
    s.xyz = cleanup_calloc(3 * (size_t)s.nv * sizeof *s.xyz);
    s.tets = cleanup_calloc(4 * (size_t)s.nt * sizeof *s.tets);
    s.faces = cleanup_calloc(3 * (size_t)s.nb * sizeof *s.faces);
    assert_int_equal(bodt_mesh_get_vertices(h, s.xyz, 3 * (size_t)s.nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_tets(h, s.tets, 4 * (size_t)s.nt), BODT_OK);
    assert_int_equal(bodt_mesh_get_boundary_faces(h, s.faces, NULL, (size_t)s.nb), BODT_OK);
    for (int32_t f = 0; f < s.nb; ++f) sort3(&s.faces[3 * f]);
    qsort(s.faces, (size_t)s.nb, 3 * sizeof *s.faces, cmp_triple);
    s.volume = 0.0;
    s.inverted = 0;
    for (int32_t t = 0; t < s.nt; ++t) {
        const int32_t *q = &s.tets[4 * t];
        const double v6 = tm_orient6(P(s.xyz, q[0]), P(s.xyz, q[1]), P(s.xyz, q[2]), P(s.xyz, q[3]));
        s.volume += v6 / 6.0;
        s.inverted += !(v6 > 0.0);
    }
    return s;
}

/* Vertices whose coordinates differ bit for bit; -1 if none. */
static int32_t first_moved(const snap *a, const snap *b, const unsigned char *only) {
    for (int32_t v = 0; v < a->nv && v < b->nv; ++v) {
        if (only && !only[v]) continue;
        if (memcmp(P(a->xyz, v), P(b->xyz, v), 3 * sizeof(double)) != 0) return v;
    }
    return -1;
}

static int32_t count_moved(const snap *a, const snap *b, const unsigned char *skip) {
    int32_t n = 0;
    for (int32_t v = 0; v < a->nv && v < b->nv; ++v)
        if (!(skip && skip[v]) && memcmp(P(a->xyz, v), P(b->xyz, v), 3 * sizeof(double)) != 0) ++n;
    return n;
}

static void expect_same_faces(const snap *a, const snap *b, const char *what) {
    if (a->nb != b->nb) fail_msg("%s: %d boundary faces, %d before", what, b->nb, a->nb);
    for (int32_t f = 0; f < a->nb; ++f)
        if (cmp_triple(&a->faces[3 * f], &b->faces[3 * f]) != 0)
            fail_msg("%s: boundary face (%d %d %d) where (%d %d %d) was", what, b->faces[3 * f], b->faces[3 * f + 1],
                     b->faces[3 * f + 2], a->faces[3 * f], a->faces[3 * f + 1], a->faces[3 * f + 2]);
}

static step_totals run_ok(bodt_mesh *h, int32_t steps) {
    step_totals t = {0, 0, 0, 0, 0};
    const int st = bodt_run(h, steps, add_step_report, &t);
    if (st != BODT_OK) fail_msg("bodt_run: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    return t;
}

/* ------------------------------------------------------------- params */

typedef struct dparam {
    int key;
    const char *name;
    double def, lo, hi;
    double bad[6];
    int nbad;
} dparam;

static void test_params(void **state) {
    (void)state;
    const test_mesh *m = make_box(2, 0.1, 1);
    bodt_mesh *h = create_ok(m->nverts, m->xyz, m->ntets, m->tets, 0);
    const int E = BODT_ERR_INVALID_ARGUMENT;
    int32_t iv = 0;
    double dv = 0.0;
    int mode = 0;

    /* the mode */
    assert_int_equal(bodt_set_mode(h, BODT_MODE_OPT_WEIGHTED), BODT_OK);
    assert_int_equal(bodt_get_mode(h, &mode), BODT_OK);
    assert_int_equal(mode, 5);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, &iv), BODT_OK);
    assert_int_equal(iv, BODT_OPS_MODE_DEFAULT);
    assert_int_equal(bodt_set_mode(h, 8), E);
    assert_int_equal(bodt_set_mode(h, 0), E);
    assert_int_equal(bodt_get_mode(h, &mode), BODT_OK);
    assert_int_equal(mode, BODT_MODE_OPT_WEIGHTED);

    /* the double keys */
    const dparam ds[] = {
        {BODT_PARAM_WEIGHT_C, "BODT_PARAM_WEIGHT_C", 0.75, 0.0, 1.0, {-1e-9, 1.0000001, 2.0, NAN, INFINITY, -INFINITY}, 6},
        {BODT_PARAM_POOR_QUALITY, "BODT_PARAM_POOR_QUALITY", 0.5, 0.0, 1.0, {-0.1, 1.5, NAN, INFINITY}, 4},
        {BODT_PARAM_QN_EPSILON, "BODT_PARAM_QN_EPSILON", 1e-3, 1e-12, 1.0, {0.0, 9e-13, -1e-4, 1.01, NAN, INFINITY}, 6},
        {BODT_PARAM_QN_INITIAL_STEP, "BODT_PARAM_QN_INITIAL_STEP", 0.05, 1e-6, 10.0, {0.0, 9e-7, -0.05, 10.5, NAN}, 5},
        {BODT_PARAM_QN_INTERVAL_GROWTH, "BODT_PARAM_QN_INTERVAL_GROWTH", 2.0, 1.1, 10.0,
         {1.0, 1.09, 0.5, 10.01, NAN, -INFINITY}, 6},
    };
    for (size_t k = 0; k < sizeof ds / sizeof *ds; ++k) {
        const dparam *p = &ds[k];
        assert_int_equal(bodt_get_param_double(h, p->key, &dv), BODT_OK);
        if (dv != p->def) fail_msg("%s: default %.17g, documented %.17g", p->name, dv, p->def);
        const double good[3] = {p->lo, p->hi, 0.5 * (p->lo + p->hi)};
        for (int g = 0; g < 3; ++g) {
            if (bodt_set_param_double(h, p->key, good[g]) != BODT_OK)
                fail_msg("%s = %.17g refused: %s", p->name, good[g], bodt_mesh_last_error(h));
            assert_int_equal(bodt_get_param_double(h, p->key, &dv), BODT_OK);
            assert_true(dv == good[g]);
        }
        for (int b = 0; b < p->nbad; ++b) {
            if (bodt_set_param_double(h, p->key, p->bad[b]) != E) fail_msg("%s = %g taken", p->name, p->bad[b]);
            assert_contains(bodt_mesh_last_error(h), p->name);
            assert_contains(bodt_mesh_last_error(h), "must be in");
            assert_int_equal(bodt_get_param_double(h, p->key, &dv), BODT_OK);
            assert_true(dv == good[2]); /* kept */
            assert_string_equal(bodt_mesh_last_error(h), "");
        }
        /* the wrong type */
        assert_int_equal(bodt_set_param_int(h, p->key, 1), E);
        assert_contains(bodt_mesh_last_error(h), p->name);
        assert_int_equal(bodt_get_param_int(h, p->key, &iv), E);
        assert_contains(bodt_mesh_last_error(h), p->name);
        assert_int_equal(bodt_get_param_double(h, p->key, &dv), BODT_OK);
        assert_true(dv == good[2]);
        assert_int_equal(bodt_set_param_double(h, p->key, p->def), BODT_OK);
    }

    /* QN_MAX_ITERATIONS: int in [1, 1000], default 10 */
    const int K = BODT_PARAM_QN_MAX_ITERATIONS;
    assert_int_equal(bodt_get_param_int(h, K, &iv), BODT_OK);
    assert_int_equal(iv, 10);
    static const int32_t good_it[] = {1, 1000, 37};
    for (size_t k = 0; k < 3; ++k) {
        assert_int_equal(bodt_set_param_int(h, K, good_it[k]), BODT_OK);
        assert_int_equal(bodt_get_param_int(h, K, &iv), BODT_OK);
        assert_int_equal(iv, good_it[k]);
    }
    static const int32_t bad_it[] = {0, -1, 1001, INT32_MAX, INT32_MIN};
    for (size_t k = 0; k < sizeof bad_it / sizeof *bad_it; ++k) {
        assert_int_equal(bodt_set_param_int(h, K, bad_it[k]), E);
        assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_QN_MAX_ITERATIONS");
        assert_contains(bodt_mesh_last_error(h), "[1, 1000]");
        assert_int_equal(bodt_get_param_int(h, K, &iv), BODT_OK);
        assert_int_equal(iv, 37);
    }
    assert_int_equal(bodt_set_param_double(h, K, 5.0), E);
    assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_QN_MAX_ITERATIONS");
    assert_int_equal(bodt_get_param_double(h, K, &dv), E);
    assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_QN_MAX_ITERATIONS");
    /* the message gives the range of a double key readably */
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_QN_EPSILON, 2.0), E);
    assert_contains(bodt_mesh_last_error(h), "[1e-12, 1]");
    /* a step in this mode runs with the values set */
    bodt_step_report r;
    memset(&r, 0, sizeof r);
    r.size = sizeof r;
    assert_int_equal(bodt_step(h, &r), BODT_OK);
    assert_int_equal(r.step, 1);
}

/* --------------------------------------------------- boundary kept */

static void test_boundary_kept(void **state) {
    (void)state;
    const test_mesh *m = make_box(5, 0.4, 3);
    bodt_mesh *h = create_mode5(m);
    bodt_quality q0, q1;
    get_quality(h, &q0);
    const snap s0 = take(h);
    assert_int_equal(s0.nb, 6 * 2 * 25);
    const step_totals t = run_ok(h, 10);
    get_quality(h, &q1);
    const snap s1 = take(h);
    print_message("boundary kept: %d steps, %d moves, %d flips; min dihedral %.3f -> %.3f, min stretch %.4f -> %.4f\n",
                  t.steps, t.moved, t.flips, q0.min_dihedral, q1.min_dihedral, q0.min_stretch, q1.min_stretch);
    assert_int_equal(s1.nv, s0.nv);
    assert_int_equal(t.inserted + t.collapsed, 0);
    const int32_t b = first_moved(&s0, &s1, m->boundary);
    if (b >= 0)
        fail_msg("boundary vertex %d moved: (%.17g %.17g %.17g) -> (%.17g %.17g %.17g)", b, s0.xyz[3 * b],
                 s0.xyz[3 * b + 1], s0.xyz[3 * b + 2], s1.xyz[3 * b], s1.xyz[3 * b + 1], s1.xyz[3 * b + 2]);
    expect_same_faces(&s0, &s1, "boundary kept");
    assert_int_equal(q1.num_inverted, 0);
    assert_int_equal(s1.inverted, 0);
    assert_near(s1.volume, 1.0, 1e-12);
    assert_near(q1.volume, 1.0, 1e-12);
    assert_true(q1.min_stretch >= q0.min_stretch);
    assert_true(q1.min_dihedral >= q0.min_dihedral);
    assert_true(q1.min_stretch > q0.min_stretch); /* this mode's aim */
    assert_true(t.moved > 0);
    assert_true(count_moved(&s0, &s1, m->boundary) > 0);
    assert_true(q1.mean_stretch > q0.mean_stretch);
}

/* --------------------------------------------------- all-boundary sliver */

enum { SLIVER_NV = 9 };

typedef struct sliver_mesh {
    double xyz[3 * SLIVER_NV];
    int32_t tets[4 * 16];
    int32_t nt;
} sliver_mesh;

/* Adds (p, q, r, s) positively oriented. */
static void add_tet(sliver_mesh *s, int32_t p, int32_t q, int32_t r, int32_t t) {
    int32_t *out = &s->tets[4 * s->nt++];
    out[0] = p, out[1] = q, out[2] = r, out[3] = t;
    const double v6 = tm_orient6(P(s->xyz, p), P(s->xyz, q), P(s->xyz, r), P(s->xyz, t));
    assert_true(v6 != 0.0);
    if (v6 < 0) out[2] = t, out[3] = r;
    assert_true(tm_orient6(P(s->xyz, out[0]), P(s->xyz, out[1]), P(s->xyz, out[2]), P(s->xyz, out[3])) > 0.0);
}

/* The unit cube with the bottom corner d = (0, 1, 0) raised to eps: the
 * bottom is the folded quad abc + acd (the lower hull), and (a, b, c, d) is a
 * sliver whose upper faces abd and bcd face the inside.  Everything else is
 * coned to m = (0.5, 0.5, 0.5): the 10 triangles of the four planar sides and
 * the top, and abd, bcd. */
static sliver_mesh make_sliver(double eps) {
    enum { A, B, C, D, A1, B1, C1, D1, M };
    const double pts[SLIVER_NV][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, eps}, {0, 0, 1},
                                      {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 0.5}};
    sliver_mesh s;
    memcpy(s.xyz, pts, sizeof pts);
    s.nt = 0;
    add_tet(&s, A, B, C, D); /* the sliver */
    assert_true(s.tets[0] == A && s.tets[1] == B && s.tets[2] == C && s.tets[3] == D); /* as given: positive */
    static const int32_t tris[12][3] = {
        {A, B, B1}, {A, B1, A1},  /* y = 0 */
        {B, C, C1}, {B, C1, B1},  /* x = 1 */
        {C, D, D1}, {C, D1, C1},  /* y = 1 */
        {D, A, A1}, {D, A1, D1},  /* x = 0 */
        {A1, B1, C1}, {A1, C1, D1}, /* z = 1 */
        {A, B, D}, {B, C, D},     /* the sliver's upper faces */
    };
    for (int k = 0; k < 12; ++k) add_tet(&s, M, tris[k][0], tris[k][1], tris[k][2]);
    return s;
}

static double max_abs(const double *a, const double *b, size_t n) {
    double w = 0.0;
    for (size_t k = 0; k < n; ++k) w = fmax(w, fabs(a[k] - b[k]));
    return w;
}

static void test_sliver(void **state) {
    (void)state;
    const double eps = 0.02;
    const sliver_mesh sm = make_sliver(eps);
    assert_int_equal(sm.nt, 13);
    double vol = 0.0;
    for (int32_t t = 0; t < sm.nt; ++t) {
        const int32_t *q = &sm.tets[4 * t];
        vol += tm_orient6(P(sm.xyz, q[0]), P(sm.xyz, q[1]), P(sm.xyz, q[2]), P(sm.xyz, q[3])) / 6.0;
    }
    /* the cube less the wedge under the folded bottom: 1 - eps / 6 (the
     * wedge is the tet a c d (0, 1, 0)) */
    assert_near(vol, 1.0 - eps / 6.0, 1e-15);
    unsigned char boundary[SLIVER_NV] = {1, 1, 1, 1, 1, 1, 1, 1, 0};

    double before_smooth = 0.0, after_smooth = 0.0, after_flip = 0.0;
    /* pass 0: smoothing only; pass 1: smoothing only with gamma = 1 (m is
     * in the work set even if its tets are not poor); pass 2: the mode's
     * default ops (smooth | flip) */
    for (int pass = 0; pass < 3; ++pass) {
        bodt_mesh *h = create_ok(SLIVER_NV, sm.xyz, sm.nt, sm.tets, 0);
        assert_int_equal(bodt_set_mode(h, BODT_MODE_OPT_WEIGHTED), BODT_OK);
        int32_t cls[SLIVER_NV];
        assert_int_equal(bodt_mesh_get_vertex_classes(h, cls, SLIVER_NV), BODT_OK);
        for (int v = 0; v < SLIVER_NV; ++v)
            assert_int_equal(cls[v], boundary[v] ? BODT_VERTEX_SURFACE : BODT_VERTEX_INTERIOR);
        bodt_quality q0, q1;
        get_quality(h, &q0);
        const snap s0 = take(h);
        assert_int_equal(s0.nb, 12); /* 10 side and top triangles, abc, acd */
        assert_near(q0.volume, vol, 1e-15);
        if (pass < 2) assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, BODT_OP_SMOOTH), BODT_OK);
        if (pass == 1) assert_int_equal(bodt_set_param_double(h, BODT_PARAM_POOR_QUALITY, 1.0), BODT_OK);
        const step_totals t = run_ok(h, 20);
        get_quality(h, &q1);
        const snap s1 = take(h);
        static const char *const names[3] = {"sliver, smoothing only", "sliver, smoothing only, gamma 1",
                                              "sliver, default ops"};
        const char *what = names[pass];
        print_message("%s: m (0.5 0.5 0.5) -> (%.6f %.6f %.6f)\n", what, s1.xyz[24], s1.xyz[25], s1.xyz[26]);
        print_message("%s: %d steps, %d flips, %d moves; min dihedral %.3f -> %.3f, max %.3f -> %.3f, min stretch "
                      "%.4f -> %.4f, %d -> %d tets\n",
                      what, t.steps, t.flips, t.moved, q0.min_dihedral, q1.min_dihedral, q0.max_dihedral,
                      q1.max_dihedral, q0.min_stretch, q1.min_stretch, s0.nt, s1.nt);
        /* common: boundary vertices and faces, volume, validity */
        assert_int_equal(s1.nv, SLIVER_NV);
        const int32_t b = first_moved(&s0, &s1, boundary);
        if (b >= 0) fail_msg("%s: boundary vertex %d moved", what, b);
        expect_same_faces(&s0, &s1, what);
        assert_int_equal(q1.num_inverted, 0);
        assert_int_equal(s1.inverted, 0);
        assert_near(s1.volume, vol, 1e-12 * vol);
        assert_true(q1.min_dihedral >= q0.min_dihedral);
        if (pass < 2) {
            before_smooth = q0.min_dihedral;
            after_smooth = fmax(after_smooth, q1.min_dihedral);
            assert_int_equal(t.flips, 0);
            assert_int_equal(s1.nt, s0.nt);
            assert_memory_equal(s1.tets, s0.tets, 4 * (size_t)s0.nt * sizeof(int32_t));
            assert_true(q1.min_dihedral < 5.0);
            if (pass == 1) assert_true(t.moved > 0 && count_moved(&s0, &s1, NULL) == 1); /* m did move */
        } else {
            after_flip = q1.min_dihedral;
            assert_true(t.flips > 0);
            /* observed: 45 degrees, max 120.3, stretch 0.551 */
            assert_true(q1.min_dihedral > 30.0);
            assert_true(q1.max_dihedral < 150.0);
            assert_true(q1.min_stretch > 0.45);
            /* the sliver is gone: no tet has the four vertices a, b, c, d */
            for (int32_t k = 0; k < s1.nt; ++k) {
                int low = 0;
                for (int j = 0; j < 4; ++j) low += s1.tets[4 * k + j] <= 3;
                assert_true(low < 4);
            }
        }
    }
    print_message("sliver: min dihedral %.3f; smoothing only %.3f; default ops %.3f\n", before_smooth, after_smooth,
                  after_flip);
    assert_true(before_smooth < 5.0);
}

/* --------------------------------------------------- gamma */

static void test_gamma(void **state) {
    (void)state;
    const test_mesh *m = make_box(4, 0.4, 21);
    for (int g = 0; g < 2; ++g) {
        bodt_mesh *h = create_mode5(m);
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, BODT_OP_SMOOTH), BODT_OK);
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_POOR_QUALITY, g ? 1.0 : 0.0), BODT_OK);
        const snap s0 = take(h);
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        assert_int_equal(bodt_step(h, &r), BODT_OK);
        const snap s1 = take(h);
        if (g == 0) {
            assert_int_equal(r.vertices_moved, 0);
            assert_true(r.max_move == 0.0);
            assert_memory_equal(s1.xyz, s0.xyz, 3 * (size_t)s0.nv * sizeof(double));
        } else {
            assert_true(r.vertices_moved > 0 && r.max_move > 0.0);
            assert_int_equal(count_moved(&s0, &s1, NULL), r.vertices_moved);
            assert_int_equal(first_moved(&s0, &s1, m->boundary), -1);
        }
    }
}

/* --------------------------------------------------- weights */

static void test_weights(void **state) {
    (void)state;
    const test_mesh *m = make_box(5, 0.4, 31);
    const double cs[3] = {0.5, 0.75, 0.9};
    snap out[3];
    for (int k = 0; k < 3; ++k) {
        bodt_mesh *h = create_mode5(m);
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_WEIGHT_C, cs[k]), BODT_OK);
        bodt_quality q0, q1;
        get_quality(h, &q0);
        const snap s0 = take(h);
        const step_totals t = run_ok(h, 10);
        get_quality(h, &q1);
        out[k] = take(h);
        print_message("C = %.2f: %d steps, %d flips; min stretch %.4f -> %.4f, mean %.4f -> %.4f, min dihedral %.3f "
                      "-> %.3f\n",
                      cs[k], t.steps, t.flips, q0.min_stretch, q1.min_stretch, q0.mean_stretch, q1.mean_stretch,
                      q0.min_dihedral, q1.min_dihedral);
        assert_true(q1.min_stretch > q0.min_stretch);
        assert_true(q1.min_dihedral >= q0.min_dihedral);
        assert_int_equal(q1.num_inverted, 0);
        assert_near(out[k].volume, 1.0, 1e-12);
        assert_int_equal(first_moved(&s0, &out[k], m->boundary), -1);
        expect_same_faces(&s0, &out[k], "weights");
    }
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b) {
            assert_int_equal(out[a].nv, out[b].nv);
            const double d = max_abs(out[a].xyz, out[b].xyz, 3 * (size_t)out[a].nv);
            print_message("C = %.2f vs %.2f: largest coordinate difference %.3g\n", cs[a], cs[b], d);
            assert_true(d > 1e-6);
        }
}

/* --------------------------------------------------- inverted input */

static void swap_last_two(int32_t *tets, int32_t t) {
    const int32_t x = tets[4 * t + 2];
    tets[4 * t + 2] = tets[4 * t + 3];
    tets[4 * t + 3] = x;
}

static void try_inverted(const char *what, int32_t nv, const double *xyz, int32_t nt, const int32_t *tets) {
    bodt_mesh *h = create_ok(nv, xyz, nt, tets, BODT_CREATE_ACCEPT_INVERTED);
    bodt_quality q0, q1;
    get_quality(h, &q0);
    assert_true(q0.num_inverted > 0);
    assert_int_equal(bodt_set_mode(h, BODT_MODE_OPT_WEIGHTED), BODT_OK);
    for (int call = 0; call < 2; ++call) {
        const snap s0 = take(h);
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        const int st = call == 0 ? bodt_step(h, &r) : bodt_run(h, 10, NULL, NULL);
        print_message("%s: %s -> %s (%s)\n", what, call == 0 ? "bodt_step" : "bodt_run", bodt_status_string(st),
                      bodt_mesh_last_error(h));
        assert_true(st == BODT_OK || st == BODT_ERR_WRONG_STATE || st == BODT_ERR_NUMERIC ||
                    st == BODT_ERR_UNSUPPORTED || st == BODT_ERR_BAD_MESH);
        const snap s1 = take(h);
        get_quality(h, &q1);
        if (st != BODT_OK) {
            assert_true(strlen(bodt_mesh_last_error(h)) > 0);
            assert_int_equal(s1.nv, s0.nv);
            assert_int_equal(s1.nt, s0.nt);
            assert_memory_equal(s1.xyz, s0.xyz, 3 * (size_t)s0.nv * sizeof(double));
            assert_memory_equal(s1.tets, s0.tets, 4 * (size_t)s0.nt * sizeof(int32_t));
        } else {
            assert_string_equal(bodt_mesh_last_error(h), "");
        }
        assert_true(q1.num_inverted <= q0.num_inverted);
        assert_near(s1.volume, s0.volume, 1e-12 * fabs(s0.volume));
    }
}

static void test_inverted_input(void **state) {
    (void)state;
    /* tets given in the wrong order inside a 3 x 3 x 3 box (as test_capi) */
    test_mesh *m = make_box(3, 0.15, 9);
    int32_t *t = cleanup_add(malloc(4 * (size_t)m->ntets * sizeof *t), free);
    memcpy(t, m->tets, 4 * (size_t)m->ntets * sizeof *t);
    swap_last_two(t, 78);
    swap_last_two(t, 80);
    try_inverted("wrongly ordered tets", m->nverts, m->xyz, m->ntets, t);

    /* a boundary vertex pushed inside (the bottom centre of a 2 x 2 x 2 box) */
    test_mesh *b = make_box(2, 0.0, 1);
    assert_true(b->xyz[3 * 4] == 0.5 && b->xyz[3 * 4 + 1] == 0.5 && b->xyz[3 * 4 + 2] == 0.0);
    b->xyz[3 * 4 + 2] = 0.7;
    try_inverted("boundary vertex pushed in", b->nverts, b->xyz, b->ntets, b->tets);

    /* an interior vertex of a 4 x 4 x 4 box pushed past its neighbours */
    test_mesh *c = make_box(4, 0.2, 5);
    int32_t v = -1;
    for (int32_t k = 0; k < c->nverts && v < 0; ++k)
        if (!c->boundary[k] && fabs(c->xyz[3 * k] - 0.5) < 0.1 && fabs(c->xyz[3 * k + 1] - 0.5) < 0.1 &&
            fabs(c->xyz[3 * k + 2] - 0.5) < 0.1)
            v = k;
    assert_true(v >= 0);
    c->xyz[3 * v] += 0.31;
    c->xyz[3 * v + 1] += 0.047;
    c->xyz[3 * v + 2] -= 0.023;
    try_inverted("interior vertex pushed out", c->nverts, c->xyz, c->ntets, c->tets);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_params, cleanup_teardown),
        cmocka_unit_test_teardown(test_boundary_kept, cleanup_teardown),
        cmocka_unit_test_teardown(test_sliver, cleanup_teardown),
        cmocka_unit_test_teardown(test_gamma, cleanup_teardown),
        cmocka_unit_test_teardown(test_weights, cleanup_teardown),
        cmocka_unit_test_teardown(test_inverted_input, cleanup_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
