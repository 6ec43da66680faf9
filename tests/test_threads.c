/*
 * test_threads: BODT_PARAM_THREADS.  Its range and default, and that every
 * mode gives the same mesh, bit for bit, and the same step reports on 1, 2
 * and 5 threads and the default of 0: the sweeps move the vertices colour by colour, and within a
 * colour no two vertices share a tet, so the order the threads take them in
 * cannot matter.  A race (two threads moving neighbours at once) shows up as
 * a difference here, most surely in the ASan build's slower, more
 * interleaved runs.
 *
 *   settled     B-ODT smoothing skips a vertex whose move was refused
 *               while nothing in its star has moved since (its verdict is
 *               known): 30 steps of BODT (smoothing only) and of ODT on a
 *               jittered box, and of BODT on a slab one cube thick (every
 *               vertex on the boundary), give
 *               the same vertices and extreme angles, bit for bit, as runs
 *               that make the library forget the skips before every step
 *               (BODT_PARAM_THREADS set to its value, which keeps only the
 *               tets no refinement fixed: forgetting those, which stand
 *               for themselves even where their vertices moved, may change
 *               the result, which the threads must not), on 1 and 2 threads, with
 *               fewer trial moves (some skips happened) and the same moves
 *   flip_memory B-ODT with flips and insertion remembers the flips that
 *               failed, and the bad tets no flip or insertion fixed, across
 *               steps while the sweeps report every move: 30 steps on a
 *               lazy mesh (flips in many of them, then none) give the same
 *               vertices, tets and step reports as runs that forget before
 *               every step, on 1 and 2 threads; the memories outlive a
 *               change of the connectivity (some step after flips skips a
 *               vertex); the same on a jittered box with default ops
 */
#include "api_checks.h"
#include "bodt.h"
#include "cleanup.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <stdlib.h>

#define STEPS 3
#define MAX_STEPS 30

static test_mesh *jittered_box(void) {
    test_mesh *m = calloc(1, sizeof *m);
    assert_non_null(m);
    cleanup_add(m, cleanup_free_test_mesh);
    assert_int_equal(tm_make_box(m, 12, 0.25, 77), 0);
    return m;
}

static void test_param(void **state) {
    (void)state;
    bodt_mesh *h = create_cleaned(jittered_box());
    int32_t threads = -7;
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_THREADS, &threads), BODT_OK);
    assert_int_equal(threads, 1); /* opt-in: 0 is OMP_NUM_THREADS or every core */
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_THREADS, 3), BODT_OK);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_THREADS, &threads), BODT_OK);
    assert_int_equal(threads, 3);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_THREADS, -1), BODT_ERR_INVALID_ARGUMENT);
    assert_non_null(strstr(bodt_mesh_last_error(h), "BODT_PARAM_THREADS"));
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_THREADS, 2.0), BODT_ERR_INVALID_ARGUMENT);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_THREADS, &threads), BODT_OK);
    assert_int_equal(threads, 3); /* refused settings change nothing */
}

typedef struct run_result {
    int32_t nverts, ntets;
    double *xyz;
    int32_t *tets;
    bodt_step_report reports[MAX_STEPS];
} run_result;

/* `steps` steps of `mode` with `ops` (-1: the mode's default) on `threads`;
 * with `forget`, BODT_PARAM_THREADS is set again before every step, which
 * makes the library forget what it kept from the sweeps before. */
static run_result run_steps(const test_mesh *m, int mode, int32_t ops, int32_t threads, int steps, int forget) {
    bodt_mesh *h = create_cleaned(m);
    assert_int_equal(bodt_set_mode(h, mode), BODT_OK);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, ops), BODT_OK);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_THREADS, threads), BODT_OK);
    run_result r;
    memset(&r, 0, sizeof r);
    for (int k = 0; k < steps; ++k) {
        if (forget) assert_int_equal(bodt_set_param_int(h, BODT_PARAM_THREADS, threads), BODT_OK);
        r.reports[k].size = sizeof r.reports[k];
        if (bodt_step(h, &r.reports[k]) != BODT_OK) fail_msg("mode %d step %d: %s", mode, k, bodt_mesh_last_error(h));
    }
    assert_int_equal(bodt_mesh_get_counts(h, &r.nverts, &r.ntets, NULL), BODT_OK);
    r.xyz = cleanup_calloc(3 * (size_t)r.nverts * sizeof *r.xyz);
    r.tets = cleanup_calloc(4 * (size_t)r.ntets * sizeof *r.tets);
    assert_int_equal(bodt_mesh_get_vertices(h, r.xyz, 3 * (size_t)r.nverts), BODT_OK);
    assert_int_equal(bodt_mesh_get_tets(h, r.tets, 4 * (size_t)r.ntets), BODT_OK);
    return r;
}

static run_result run(const test_mesh *m, int mode, int32_t ops, int32_t threads) {
    return run_steps(m, mode, ops, threads, STEPS, 0);
}

static void assert_same_reports(const bodt_step_report *a, const bodt_step_report *b, int mode, int32_t threads) {
    for (int k = 0; k < STEPS; ++k) {
        if (a[k].vertices_moved != b[k].vertices_moved || a[k].moves_rejected != b[k].moves_rejected ||
            a[k].moves_shortened != b[k].moves_shortened || a[k].not_positive_definite != b[k].not_positive_definite ||
            a[k].flips != b[k].flips || a[k].vertices_inserted != b[k].vertices_inserted ||
            a[k].edges_collapsed != b[k].edges_collapsed || a[k].max_move != b[k].max_move ||
            a[k].min_dihedral != b[k].min_dihedral || a[k].max_dihedral != b[k].max_dihedral ||
            a[k].min_stretch != b[k].min_stretch)
            fail_msg("mode %d, %d threads: step %d reports differ from 1 thread's (moved %d vs %d, min %.17g vs %.17g)",
                     mode, threads, k + 1, b[k].vertices_moved, a[k].vertices_moved, b[k].min_dihedral,
                     a[k].min_dihedral);
    }
}

static void test_same_result_on_any_number_of_threads(void **state) {
    (void)state;
    const test_mesh *m = jittered_box();
    const struct {
        int mode;
        int32_t ops;
    } runs[] = {{BODT_MODE_LAPLACE, -1},      {BODT_MODE_ODT, -1},
                {BODT_MODE_BODT_BASIC, -1},   {BODT_MODE_BODT, BODT_OP_SMOOTH},
                {BODT_MODE_BODT, -1},         {BODT_MODE_OPT_WEIGHTED, -1},
                {BODT_MODE_PHASED_ODT, -1},   {BODT_MODE_NODT, -1}};
    const int32_t thread_counts[] = {0, 2, 5}; /* 0: OMP_NUM_THREADS or every core */
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; ++i) {
        const run_result one = run(m, runs[i].mode, runs[i].ops, 1);
        int32_t moved = 0;
        for (int k = 0; k < STEPS; ++k) moved += one.reports[k].vertices_moved;
        if (moved == 0) fail_msg("mode %d moved nothing: the comparison would prove nothing", runs[i].mode);
        for (size_t j = 0; j < sizeof thread_counts / sizeof thread_counts[0]; ++j) {
            const run_result many = run(m, runs[i].mode, runs[i].ops, thread_counts[j]);
            assert_same_reports(one.reports, many.reports, runs[i].mode, thread_counts[j]);
            assert_int_equal(many.nverts, one.nverts);
            assert_int_equal(many.ntets, one.ntets);
            if (memcmp(many.xyz, one.xyz, 3 * (size_t)one.nverts * sizeof *one.xyz) != 0)
                fail_msg("mode %d: vertices on %d threads differ from 1 thread's", runs[i].mode, thread_counts[j]);
            assert_memory_equal(many.tets, one.tets, 4 * (size_t)one.ntets * sizeof *one.tets);
        }
    }
}

static int bottom_layer(int i, int j, int k, int n, void *user) {
    (void)i, (void)j, (void)n, (void)user;
    return k == 0;
}

/* One layer of 8 x 8 cubes: every vertex on the boundary.  The vertices
 * inside the top and bottom faces are jittered in their plane by up to
 * 0.2 h, so the surface smoothing has work to do. */
static test_mesh *jittered_slab(void) {
    test_mesh *m = calloc(1, sizeof *m);
    assert_non_null(m);
    cleanup_add(m, cleanup_free_test_mesh);
    const int n = 8;
    const double h = 1.0 / n;
    assert_int_equal(tm_make_cubes(m, n, 1.0, bottom_layer, NULL, 0.0, 0), 0);
    tm_rng rng;
    tm_rng_seed(&rng, 12);
    for (int32_t v = 0; v < m->nverts; ++v) {
        double *x = m->xyz + 3 * v;
        if (x[0] > 0.5 * h && x[0] < 1.0 - 0.5 * h && x[1] > 0.5 * h && x[1] < 1.0 - 0.5 * h)
            for (int a = 0; a < 2; ++a) x[a] += 0.4 * h * (tm_rng_uniform(&rng) - 0.5);
    }
    assert_int_equal(tm_count_interior(m), 0);
    return m;
}

/* 30 steps of `mode` (smoothing only) with the skips, without them (the
 * library made to forget before every step) and on 2 threads. */
static void assert_skips_change_nothing(const test_mesh *m, int mode) {
    const run_result kept = run_steps(m, mode, BODT_OP_SMOOTH, 1, MAX_STEPS, 0);
    const run_result forgot = run_steps(m, mode, BODT_OP_SMOOTH, 1, MAX_STEPS, 1);
    const run_result two = run_steps(m, mode, BODT_OP_SMOOTH, 2, MAX_STEPS, 0);
    int64_t tries_kept = 0, tries_forgot = 0;
    for (int k = 0; k < MAX_STEPS; ++k) {
        const bodt_step_report *a = &kept.reports[k], *b = &forgot.reports[k], *c = &two.reports[k];
        if (a->vertices_moved != b->vertices_moved || a->moves_shortened != b->moves_shortened ||
            a->max_move != b->max_move || a->min_dihedral != b->min_dihedral ||
            a->max_dihedral != b->max_dihedral || a->min_stretch != b->min_stretch ||
            a->moves_rejected > b->moves_rejected)
            fail_msg("mode %d step %d: moved %d vs %d, rejected %d vs %d, min %.17g vs %.17g with and without "
                     "the skips",
                     mode, k + 1, a->vertices_moved, b->vertices_moved, a->moves_rejected, b->moves_rejected,
                     a->min_dihedral, b->min_dihedral);
        if (a->vertices_moved != c->vertices_moved || a->moves_rejected != c->moves_rejected ||
            a->min_dihedral != c->min_dihedral)
            fail_msg("mode %d step %d: 2 threads differ from 1 (moved %d vs %d, rejected %d vs %d)", mode, k + 1,
                     c->vertices_moved, a->vertices_moved, c->moves_rejected, a->moves_rejected);
        tries_kept += a->vertices_moved + a->moves_rejected;
        tries_forgot += b->vertices_moved + b->moves_rejected;
    }
    if (!(tries_kept < tries_forgot))
        fail_msg("mode %d: %lld trial moves with the skips, %lld without: nothing was skipped", mode,
                 (long long)tries_kept, (long long)tries_forgot);
    if (memcmp(kept.xyz, forgot.xyz, 3 * (size_t)kept.nverts * sizeof *kept.xyz) != 0)
        fail_msg("mode %d: the vertices differ with and without the skips", mode);
    if (memcmp(kept.xyz, two.xyz, 3 * (size_t)kept.nverts * sizeof *kept.xyz) != 0)
        fail_msg("mode %d: the vertices on 2 threads differ from 1 thread's", mode);
}

static void test_settled(void **state) {
    (void)state;
    const test_mesh *box = jittered_box();
    assert_skips_change_nothing(box, BODT_MODE_BODT);
    assert_skips_change_nothing(box, BODT_MODE_ODT);
    /* no inner vertex: the skips are of surface and feature-line vertices */
    assert_skips_change_nothing(jittered_slab(), BODT_MODE_BODT);
}

/* Runs a and b did the same; b may have tried more moves (a skipped some:
 * a skipped vertex is not counted as rejected) when `fewer_tries`. */
static void assert_same_run(const run_result *a, const run_result *b, int fewer_tries, const char *what) {
    for (int k = 0; k < MAX_STEPS; ++k) {
        const bodt_step_report *x = &a->reports[k], *y = &b->reports[k];
        const int tries_differ = fewer_tries ? x->moves_rejected > y->moves_rejected : x->moves_rejected != y->moves_rejected;
        if (x->vertices_moved != y->vertices_moved || tries_differ || x->moves_shortened != y->moves_shortened ||
            x->max_move != y->max_move ||
            x->flips != y->flips || x->vertices_inserted != y->vertices_inserted ||
            x->min_dihedral != y->min_dihedral || x->max_dihedral != y->max_dihedral ||
            x->min_stretch != y->min_stretch)
            fail_msg("step %d: %s (flips %d vs %d, inserted %d vs %d, min %.17g vs %.17g)", k + 1, what, x->flips,
                     y->flips, x->vertices_inserted, y->vertices_inserted, x->min_dihedral, y->min_dihedral);
    }
    assert_int_equal(a->nverts, b->nverts);
    assert_int_equal(a->ntets, b->ntets);
    if (memcmp(a->xyz, b->xyz, 3 * (size_t)a->nverts * sizeof *a->xyz) != 0) fail_msg("vertices: %s", what);
    if (memcmp(a->tets, b->tets, 4 * (size_t)a->ntets * sizeof *a->tets) != 0) fail_msg("tets: %s", what);
}

static void test_flip_memory(void **state) {
    (void)state;
    test_mesh *m = calloc(1, sizeof *m);
    assert_non_null(m);
    cleanup_add(m, cleanup_free_test_mesh);
    assert_int_equal(tm_make_lazy(m, 300, 3), 0);
    const run_result kept = run_steps(m, BODT_MODE_BODT, -1, 1, MAX_STEPS, 0);
    const run_result forgot = run_steps(m, BODT_MODE_BODT, -1, 1, MAX_STEPS, 1);
    const run_result two = run_steps(m, BODT_MODE_BODT, -1, 2, MAX_STEPS, 0);
    int steps_with_flips = 0;
    for (int k = 1; k < MAX_STEPS; ++k) steps_with_flips += kept.reports[k].flips > 0;
    if (steps_with_flips < 3) fail_msg("flips after the first step in %d steps: too few to test the memory", steps_with_flips);
    assert_same_run(&kept, &forgot, 1, "differ with and without the memories of the steps before");
    assert_same_run(&kept, &two, 0, "differ on 2 threads from 1 thread");
    /* The memories outlive a change of the connectivity: a step after one
     * with flips skips vertices. */
    int skipped_after_flips = 0;
    for (int k = 1; k < MAX_STEPS; ++k)
        skipped_after_flips += kept.reports[k - 1].flips > 0 && kept.reports[k].moves_rejected < forgot.reports[k].moves_rejected;
    if (skipped_after_flips == 0) fail_msg("no step after one with flips skipped a vertex");
    /* The same on the jittered box, whose flips reach its surface. */
    const test_mesh *box = jittered_box();
    const run_result box_kept = run_steps(box, BODT_MODE_BODT, -1, 1, MAX_STEPS, 0);
    const run_result box_forgot = run_steps(box, BODT_MODE_BODT, -1, 1, MAX_STEPS, 1);
    int box_flips = 0;
    for (int k = 0; k < MAX_STEPS; ++k) box_flips += box_kept.reports[k].flips;
    if (box_flips == 0) fail_msg("no flip on the jittered box");
    assert_same_run(&box_kept, &box_forgot, 1, "jittered box: differ with and without the memories of the steps before");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_param, cleanup_teardown),
        cmocka_unit_test_teardown(test_same_result_on_any_number_of_threads, cleanup_teardown),
        cmocka_unit_test_teardown(test_settled, cleanup_teardown),
        cmocka_unit_test_teardown(test_flip_memory, cleanup_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
