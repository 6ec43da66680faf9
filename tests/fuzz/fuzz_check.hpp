// FUZZ_CHECK(cond): the fuzzers' invariant check.  A violation prints the
// condition and where it is, then abort()s, which libFuzzer reports as a
// crash and saves the input for.
#pragma once

#include <cstdio>
#include <cstdlib>

#define FUZZ_CHECK(cond)                                                                                  \
    do {                                                                                                  \
        if (!(cond)) {                                                                                    \
            std::fprintf(stderr, "invariant violated: %s (%s:%d)\n", #cond, __FILE__, __LINE__);          \
            std::abort();                                                                                 \
        }                                                                                                 \
    } while (0)
