/*
 * test_laplace: guarded Laplacian smoothing (BODT_MODE_LAPLACE), bodt_step
 * and bodt_run, through libbodt.so: validity after every step, quality
 * improves, boundary and fixed vertices stay put bit for bit, step reports
 * add up, convergence stops bodt_run, the callback cancels it, and two
 * handles smoothed in two threads give the same result as one after the
 * other.
 */
#include "api_checks.h"
#include "bodt.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

static bodt_mesh *create_ok(const test_mesh *m) {
    bodt_mesh *h = NULL;
    const int st = bodt_mesh_create(m->nverts, m->xyz, m->ntets, m->tets, 0, &h);
    if (st != BODT_OK) fail_msg("create: %s", bodt_mesh_last_error(NULL));
    assert_int_equal(bodt_set_mode(h, BODT_MODE_LAPLACE), BODT_OK);
    return h;
}

static double *get_xyz(const bodt_mesh *h, int32_t nv) {
    double *xyz = malloc(3 * (size_t)nv * sizeof *xyz);
    assert_non_null(xyz);
    assert_int_equal(bodt_mesh_get_vertices(h, xyz, 3 * (size_t)nv), BODT_OK);
    return xyz;
}

/* A jittered 6 x 6 x 6 box: 343 vertices, 125 interior. */
#define BOX_N 6
#define BOX_JITTER 0.3

/* Every step: valid mesh, consistent report, boundary and fixed vertices
 * unchanged bit for bit, the worst stretch never lower. */
static void test_steps_keep_mesh_valid(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, BOX_N, BOX_JITTER, 1234), 0);
    bodt_mesh *h = create_ok(&m);
    /* fix every fifth interior vertex */
    int32_t *fixed = malloc((size_t)m.nverts * sizeof *fixed);
    int32_t nfixed = 0, interior = 0;
    for (int32_t v = 0; v < m.nverts; ++v)
        if (!m.boundary[v] && interior++ % 5 == 0) fixed[nfixed++] = v;
    assert_int_equal(interior, (BOX_N - 1) * (BOX_N - 1) * (BOX_N - 1));
    assert_int_equal(bodt_mesh_set_fixed_vertices(h, nfixed, fixed), BODT_OK);
    const int32_t movable = interior - nfixed;

    bodt_quality q0;
    get_quality(h, &q0);
    assert_int_equal(q0.num_inverted, 0);
    double prev_min_stretch = q0.min_stretch;
    int moved_total = 0;
    for (int k = 1; k <= 40; ++k) {
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        assert_int_equal(bodt_step(h, &r), BODT_OK);
        assert_int_equal(r.size, sizeof r);
        assert_int_equal(r.step, k);
        assert_int_equal(r.vertices_moved + r.moves_rejected, movable);
        assert_true(r.vertices_moved >= 0 && r.moves_rejected >= 0);
        assert_true(r.moves_shortened >= 0 && r.moves_shortened <= r.vertices_moved);
        assert_true(r.max_move >= 0.0);
        assert_true(r.max_move == 0.0 || r.vertices_moved > 0);
        moved_total += r.vertices_moved;

        bodt_quality q;
        get_quality(h, &q);
        assert_int_equal(q.num_inverted, 0);
        assert_true(q.min_stretch > 0.0);
        /* the report's quality is the mesh's after the step */
        assert_true(r.min_dihedral == q.min_dihedral);
        assert_true(r.max_dihedral == q.max_dihedral);
        assert_true(r.min_stretch == q.min_stretch);
        /* BODT_PARAM_NEVER_WORSE (default 1): the worst tet never gets worse */
        assert_true(q.min_stretch >= prev_min_stretch);
        prev_min_stretch = q.min_stretch;
        /* the domain does not change */
        assert_near(q.volume, 1.0, 1e-12);

        double *xyz = get_xyz(h, m.nverts);
        for (int32_t v = 0; v < m.nverts; ++v)
            if (m.boundary[v]) assert_memory_equal(&xyz[3 * v], &m.xyz[3 * v], 3 * sizeof(double));
        for (int32_t f = 0; f < nfixed; ++f)
            assert_memory_equal(&xyz[3 * fixed[f]], &m.xyz[3 * fixed[f]], 3 * sizeof(double));
        free(xyz);
    }
    assert_true(moved_total > 0);
    /* the fixed flags are still as set */
    int32_t *flags = malloc((size_t)m.nverts * sizeof *flags);
    assert_int_equal(bodt_mesh_get_fixed_vertices(h, flags, (size_t)m.nverts), BODT_OK);
    int32_t count = 0;
    for (int32_t v = 0; v < m.nverts; ++v) count += flags[v];
    assert_int_equal(count, nfixed);
    free(flags);
    free(fixed);
    bodt_mesh_destroy(h);
    tm_free(&m);
}

static void test_run_improves_min_dihedral(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, BOX_N, BOX_JITTER, 99), 0);
    bodt_mesh *h = create_ok(&m);
    bodt_quality before, after;
    get_quality(h, &before);
    assert_int_equal(bodt_run(h, 30, NULL, NULL), BODT_OK);
    assert_string_equal(bodt_mesh_last_error(h), "");
    get_quality(h, &after);
    assert_int_equal(after.num_inverted, 0);
    assert_true(after.min_dihedral > before.min_dihedral);
    assert_true(after.min_stretch > before.min_stretch);
    assert_true(after.mean_stretch > before.mean_stretch);
    /* the interior of the box is close to the regular Kuhn grid again */
    print_message("min dihedral %.3f -> %.3f, min stretch %.4f -> %.4f\n", before.min_dihedral, after.min_dihedral,
                  before.min_stretch, after.min_stretch);
    bodt_mesh_destroy(h);
    tm_free(&m);
}

/* The guard with BODT_PARAM_NEVER_WORSE = 0: every tet ends a step with
 * stretch >= min(BODT_PARAM_MIN_STRETCH, its stretch before the step).  On a
 * graded, jittered box (z -> z^3), where unguarded Laplacian moves do lower
 * the stretch of thin tets (see test_never_worse). */
static void test_guard_floor_per_tet(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, 5, 0.2, 3), 0);
    for (int32_t v = 0; v < m.nverts; ++v) {
        const double z = m.xyz[3 * v + 2];
        m.xyz[3 * v + 2] = z * z * z;
    }
    bodt_mesh *h = create_ok(&m);
    const double floor = 0.5;
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, 0), BODT_OK);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_MIN_STRETCH, floor), BODT_OK);
    const size_t nt = (size_t)m.ntets;
    double *before = malloc(nt * sizeof *before), *after = malloc(nt * sizeof *after);
    int moved = 0, lowered = 0;
    for (int k = 0; k < 10; ++k) {
        assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_STRETCH, before, nt), BODT_OK);
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        assert_int_equal(bodt_step(h, &r), BODT_OK);
        moved += r.vertices_moved;
        assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_STRETCH, after, nt), BODT_OK);
        for (size_t t = 0; t < nt; ++t) {
            const double bound = before[t] < floor ? before[t] : floor;
            if (!(after[t] >= bound))
                fail_msg("step %d, tet %zu: stretch %.17g -> %.17g, floor %g", k + 1, t, before[t], after[t], floor);
            lowered += after[t] < before[t];
        }
    }
    assert_true(moved > 0);
    assert_true(lowered > 0); /* tets above the floor may get worse, down to it */
    free(before);
    free(after);
    bodt_mesh_destroy(h);
    tm_free(&m);
}

/* BODT_PARAM_NEVER_WORSE on a graded, jittered box (z -> z^3: thin layers
 * near z = 0) where plain Laplacian smoothing lowers the worst stretch in
 * later steps: with 0 some step does lower it, with 1 (the default) no step
 * does, though vertices still move. */
static void test_never_worse(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, 5, 0.2, 3), 0);
    for (int32_t v = 0; v < m.nverts; ++v) {
        const double z = m.xyz[3 * v + 2];
        m.xyz[3 * v + 2] = z * z * z;
    }
    for (int never_worse = 0; never_worse <= 1; ++never_worse) {
        bodt_mesh *h = create_ok(&m);
        int32_t value = -1;
        assert_int_equal(bodt_get_param_int(h, BODT_PARAM_NEVER_WORSE, &value), BODT_OK);
        assert_int_equal(value, 1);
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_NEVER_WORSE, never_worse), BODT_OK);
        bodt_quality q;
        get_quality(h, &q);
        double prev = q.min_stretch;
        int moved = 0, lowered = 0;
        for (int k = 0; k < 6; ++k) {
            bodt_step_report r;
            memset(&r, 0, sizeof r);
            r.size = sizeof r;
            assert_int_equal(bodt_step(h, &r), BODT_OK);
            moved += r.vertices_moved;
            get_quality(h, &q);
            assert_int_equal(q.num_inverted, 0);
            lowered += q.min_stretch < prev;
            prev = q.min_stretch;
        }
        assert_true(moved > 0);
        if (never_worse) assert_int_equal(lowered, 0);
        else assert_true(lowered > 0); /* without the guard the worst tet does get worse */
        bodt_mesh_destroy(h);
    }
    tm_free(&m);
}

/* BODT_PARAM_BACKTRACK_STEPS = 0: no move is ever shortened. */
static void test_no_backtracking(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, 4, 0.35, 8), 0);
    bodt_mesh *h = create_ok(&m);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_BACKTRACK_STEPS, 0), BODT_OK);
    for (int k = 0; k < 5; ++k) {
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        assert_int_equal(bodt_step(h, &r), BODT_OK);
        assert_int_equal(r.moves_shortened, 0);
        assert_int_equal(r.vertices_moved + r.moves_rejected, 27);
    }
    bodt_mesh_destroy(h);
    tm_free(&m);
}

typedef struct run_log {
    int calls;
    int stop_after; /* return nonzero at this step; 0 never */
    int32_t last_step;
    double max_moves[1000];
    int bad_report;
} run_log;

static int log_step(const bodt_step_report *r, void *user) {
    run_log *log = user;
    if (r->size != sizeof(bodt_step_report) || r->step != log->calls + 1) log->bad_report = 1;
    if (log->calls < 1000) log->max_moves[log->calls] = r->max_move;
    ++log->calls;
    log->last_step = r->step;
    return log->stop_after && r->step >= log->stop_after;
}

static void test_run_stops_when_converged(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, 4, 0.3, 31), 0);
    const double diagonal = sqrt(3.0); /* the boundary does not move */

    /* a large tolerance: the first step converges */
    bodt_mesh *h = create_ok(&m);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_TOLERANCE, 0.5), BODT_OK);
    run_log log = {0};
    assert_int_equal(bodt_run(h, 50, log_step, &log), BODT_OK);
    assert_int_equal(log.calls, 1);
    assert_false(log.bad_report);
    assert_true(log.max_moves[0] > 0.0 && log.max_moves[0] <= 0.5 * diagonal);
    bodt_mesh_destroy(h);

    /* a moderate tolerance: steps go on while the largest move is above it,
     * and stop at the first one below */
    h = create_ok(&m);
    const double tol = 1e-3;
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_TOLERANCE, tol), BODT_OK);
    memset(&log, 0, sizeof log);
    assert_int_equal(bodt_run(h, 500, log_step, &log), BODT_OK);
    assert_false(log.bad_report);
    assert_true(log.calls > 1 && log.calls < 500);
    for (int k = 0; k + 1 < log.calls; ++k) assert_true(log.max_moves[k] > tol * diagonal);
    assert_true(log.max_moves[log.calls - 1] <= tol * diagonal);
    /* the step counter goes on from there */
    bodt_step_report r;
    memset(&r, 0, sizeof r);
    r.size = sizeof r;
    assert_int_equal(bodt_step(h, &r), BODT_OK);
    assert_int_equal(r.step, log.calls + 1);
    bodt_mesh_destroy(h);

    /* tolerance 0: all max_steps are done */
    h = create_ok(&m);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_TOLERANCE, 0.0), BODT_OK);
    memset(&log, 0, sizeof log);
    assert_int_equal(bodt_run(h, 4, log_step, &log), BODT_OK);
    assert_int_equal(log.calls, 4);
    /* max_steps must be positive */
    assert_int_equal(bodt_run(h, 0, NULL, NULL), BODT_ERR_INVALID_ARGUMENT);
    assert_int_equal(bodt_run(h, -3, NULL, NULL), BODT_ERR_INVALID_ARGUMENT);
    bodt_mesh_destroy(h);
    tm_free(&m);
}

static void test_callback_cancels(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, 4, 0.3, 32), 0);
    bodt_mesh *h = create_ok(&m);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_TOLERANCE, 0.0), BODT_OK);
    run_log log = {0};
    log.stop_after = 2;
    assert_int_equal(bodt_run(h, 10, log_step, &log), BODT_ERR_CANCELLED);
    assert_int_equal(log.calls, 2);
    assert_false(log.bad_report);
    assert_true(strlen(bodt_mesh_last_error(h)) > 0);

    /* exactly two complete steps were kept: same as two bodt_step calls */
    bodt_mesh *twin = create_ok(&m);
    assert_int_equal(bodt_step(twin, NULL), BODT_OK);
    assert_int_equal(bodt_step(twin, NULL), BODT_OK);
    double *a = get_xyz(h, m.nverts), *b = get_xyz(twin, m.nverts);
    assert_memory_equal(a, b, 3 * (size_t)m.nverts * sizeof *a);
    free(a);
    free(b);
    bodt_step_report r;
    memset(&r, 0, sizeof r);
    r.size = sizeof r;
    assert_int_equal(bodt_step(h, &r), BODT_OK);
    assert_int_equal(r.step, 3);
    bodt_quality q;
    get_quality(h, &q);
    assert_int_equal(q.num_inverted, 0);
    bodt_mesh_destroy(twin);
    bodt_mesh_destroy(h);
    tm_free(&m);
}

/* ------------------------------------------------------------- threads */

typedef struct job {
    bodt_mesh *mesh;
    int steps;
    int status;
} job;

static void *run_job(void *arg) {
    job *j = arg;
    j->status = bodt_run(j->mesh, j->steps, NULL, NULL);
    if (j->status == BODT_OK) {
        bodt_quality q;
        memset(&q, 0, sizeof q);
        q.size = sizeof q;
        j->status = bodt_mesh_quality(j->mesh, &q);
    }
    return NULL;
}

static void test_two_threads_match_sequential(void **state) {
    (void)state;
    test_mesh m1, m2;
    assert_int_equal(tm_make_box(&m1, BOX_N, 0.25, 501), 0);
    assert_int_equal(tm_make_box(&m2, BOX_N - 1, 0.25, 502), 0);
    for (int round = 0; round < 3; ++round) {
        bodt_mesh *seq1 = create_ok(&m1), *seq2 = create_ok(&m2);
        bodt_mesh *par1 = create_ok(&m1), *par2 = create_ok(&m2);
        const int32_t fixed[2] = {60, 61};
        assert_int_equal(bodt_mesh_set_fixed_vertices(seq1, 2, fixed), BODT_OK);
        assert_int_equal(bodt_mesh_set_fixed_vertices(par1, 2, fixed), BODT_OK);
        assert_int_equal(bodt_set_param_double(seq2, BODT_PARAM_TOLERANCE, 0.0), BODT_OK);
        assert_int_equal(bodt_set_param_double(par2, BODT_PARAM_TOLERANCE, 0.0), BODT_OK);

        job s1 = {seq1, 12, -100}, s2 = {seq2, 15, -100};
        run_job(&s1);
        run_job(&s2);
        assert_int_equal(s1.status, BODT_OK);
        assert_int_equal(s2.status, BODT_OK);

        job p1 = {par1, 12, -100}, p2 = {par2, 15, -100};
        pthread_t t1, t2;
        assert_int_equal(pthread_create(&t1, NULL, run_job, &p1), 0);
        assert_int_equal(pthread_create(&t2, NULL, run_job, &p2), 0);
        assert_int_equal(pthread_join(t1, NULL), 0);
        assert_int_equal(pthread_join(t2, NULL), 0);
        assert_int_equal(p1.status, BODT_OK);
        assert_int_equal(p2.status, BODT_OK);

        double *a = get_xyz(seq1, m1.nverts), *b = get_xyz(par1, m1.nverts);
        assert_memory_equal(a, b, 3 * (size_t)m1.nverts * sizeof *a);
        assert_true(memcmp(a, m1.xyz, 3 * (size_t)m1.nverts * sizeof *a) != 0); /* something moved */
        free(a);
        free(b);
        a = get_xyz(seq2, m2.nverts);
        b = get_xyz(par2, m2.nverts);
        assert_memory_equal(a, b, 3 * (size_t)m2.nverts * sizeof *a);
        free(a);
        free(b);
        bodt_mesh_destroy(seq1);
        bodt_mesh_destroy(seq2);
        bodt_mesh_destroy(par1);
        bodt_mesh_destroy(par2);
    }
    tm_free(&m1);
    tm_free(&m2);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_steps_keep_mesh_valid),
        cmocka_unit_test(test_run_improves_min_dihedral),
        cmocka_unit_test(test_guard_floor_per_tet),
        cmocka_unit_test(test_never_worse),
        cmocka_unit_test(test_no_backtracking),
        cmocka_unit_test(test_run_stops_when_converged),
        cmocka_unit_test(test_callback_cancels),
        cmocka_unit_test(test_two_threads_match_sequential),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
