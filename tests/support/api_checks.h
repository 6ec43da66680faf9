/*
 * Checked calls of the public API that many C tests make: each fails the
 * test (cmocka) when the library does not return BODT_OK.  Also the sums of
 * the step reports of a run.
 */
#ifndef BODT_TEST_API_CHECKS_H
#define BODT_TEST_API_CHECKS_H

#include "bodt.h"
#include "test_util.h"

/* bodt_mesh_quality into a zeroed q with its size set. */
static inline void get_quality(const bodt_mesh *h, bodt_quality *q) {
    memset(q, 0, sizeof *q);
    q->size = sizeof *q;
    assert_int_equal(bodt_mesh_quality(h, q), BODT_OK);
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
