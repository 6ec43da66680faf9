/*
 * Small helpers shared by the cmocka tests: double comparisons with a
 * message (cmocka 1.1's assert_float_equal works in float), substring checks,
 * sorting a triple, and cmocka's required includes in the right order.
 */
#ifndef BODT_TEST_UTIL_H
#define BODT_TEST_UTIL_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* cmocka 1.1 declares print_error() and friends without C linkage for C++ */
#ifdef __cplusplus
extern "C" {
#endif
#include <cmocka.h>
#ifdef __cplusplus
}
#endif

/* The three values at t in increasing order. */
static inline void sort3(int32_t *t) {
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2 - i; ++j)
            if (t[j] > t[j + 1]) {
                const int32_t x = t[j];
                t[j] = t[j + 1];
                t[j + 1] = x;
            }
}

/* |a - b| <= tol, or the test fails naming both values. */
#define assert_near(a, b, tol)                                                                         \
    do {                                                                                               \
        const double a_ = (a), b_ = (b), t_ = (tol);                                                   \
        if (!(fabs(a_ - b_) <= t_))                                                                    \
            fail_msg("%s = %.17g, expected %s = %.17g (tolerance %g)", #a, a_, #b, b_, t_);            \
    } while (0)

/* `haystack` contains `needle`, or the test fails showing both. */
#define assert_contains(haystack, needle)                                                              \
    do {                                                                                               \
        const char *h_ = (haystack), *n_ = (needle);                                                   \
        if (!h_ || !strstr(h_, n_)) fail_msg("\"%s\" does not contain \"%s\"", h_ ? h_ : "(null)", n_); \
    } while (0)

#endif /* BODT_TEST_UTIL_H */
