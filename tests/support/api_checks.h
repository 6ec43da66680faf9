/*
 * Checked calls of the public API that many C tests make: each fails the
 * test (cmocka) when the library does not return BODT_OK.  Also the sums of
 * the step reports of a run.
 */
#ifndef BODT_TEST_API_CHECKS_H
#define BODT_TEST_API_CHECKS_H

#include "bodt.h"
#include "cleanup.h"
#include "mesh_gen.h"
#include "test_util.h"

/* bodt_mesh_quality into a zeroed q with its size set. */
static inline void get_quality(const bodt_mesh *h, bodt_quality *q) {
    memset(q, 0, sizeof *q);
    q->size = sizeof *q;
    assert_int_equal(bodt_mesh_quality(h, q), BODT_OK);
}

static inline void destroy_mesh_handle(void *h) { bodt_mesh_destroy(h); }

/* A handle on test mesh m (0-based), destroyed by the cleanup teardown. */
static inline bodt_mesh *create_cleaned(const test_mesh *m) {
    bodt_mesh *h = NULL;
    if (bodt_mesh_create(m->nverts, m->xyz, m->ntets, m->tets, 0, &h) != BODT_OK)
        fail_msg("create: %s", bodt_mesh_last_error(NULL));
    cleanup_add(h, destroy_mesh_handle);
    return h;
}

/* create_cleaned in `mode`, smoothing only (BODT_PARAM_OPS = SMOOTH): for
 * tests about smoothing, where the connectivity stays. */
static inline bodt_mesh *create_smoothing(const test_mesh *m, int mode) {
    bodt_mesh *h = create_cleaned(m);
    assert_int_equal(bodt_set_mode(h, mode), BODT_OK);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, BODT_OP_SMOOTH), BODT_OK);
    return h;
}

/* What the step reports of a run add up to (see add_step_report). */
typedef struct step_totals {
    int steps;
    int32_t flips, inserted, collapsed, moved;
} step_totals;

/* Adds the report r to the step_totals at user; as a bodt_run callback it
 * never stops the run. */
static inline int add_step_report(const bodt_step_report *r, void *user) {
    step_totals *t = user;
    ++t->steps;
    t->flips += r->flips;
    t->inserted += r->vertices_inserted;
    t->collapsed += r->edges_collapsed;
    t->moved += r->vertices_moved;
    return 0;
}

#endif /* BODT_TEST_API_CHECKS_H */
