/*
 * Things a test frees in its cmocka teardown.  A failed check longjmps out of
 * the test, past its own free() calls; tests that are expected to fail until
 * a library bug is fixed register their allocations here so that the
 * sanitizer build reports the failure and no leak on top of it.
 */
#ifndef BODT_TEST_CLEANUP_H
#define BODT_TEST_CLEANUP_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Registers p to be released by fn(p) at teardown; returns p. */
void *cleanup_add(void *p, void (*fn)(void *));
/* calloc (at least 1 byte) registered with the teardown; aborts when out of
 * memory. */
void *cleanup_calloc(size_t bytes);
/* For cleanup_add: tm_free()s and frees a calloc'ed test_mesh. */
void cleanup_free_test_mesh(void *mesh);
/* A cmocka teardown: releases everything registered, newest first. */
int cleanup_teardown(void **state);

#ifdef __cplusplus
}
#endif

#endif /* BODT_TEST_CLEANUP_H */
