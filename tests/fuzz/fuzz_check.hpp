// What both fuzzers share.  FUZZ_CHECK(cond): the invariant check; a
// violation prints the condition and where it is, then abort()s, which
// libFuzzer reports as a crash and saves the input for.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#define FUZZ_CHECK(cond)                                                                                  \
    do {                                                                                                  \
        if (!(cond)) {                                                                                    \
            std::fprintf(stderr, "invariant violated: %s (%s:%d)\n", #cond, __FILE__, __LINE__);          \
            std::abort();                                                                                 \
        }                                                                                                 \
    } while (0)

// Writes the fuzzer's input to `path`; aborts if it cannot.
inline void write_file(const std::string& path, const uint8_t* data, size_t size) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) {
        std::perror(path.c_str());
        std::abort();
    }
    if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
    if (std::fclose(f) != 0) std::abort();
}
