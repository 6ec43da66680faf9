/*
 * Checked calls of the public API that many C tests make: each fails the
 * test (cmocka) when the library does not return BODT_OK.
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

#endif /* BODT_TEST_API_CHECKS_H */
