// The largest single allocation since the last reset, for the reader tests
// (test_io_vtk, test_io_vtu_compressed): a reader must not allocate from a
// count in a file before the bytes present are known to hold it.  Replaces
// the global operator new and delete: include it in one file per program.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace io_test {

inline std::atomic<size_t> g_largest_alloc{0};

// The limit the tests hold the readers to for their small files.
constexpr size_t kAllocLimit = size_t{16} << 20;

// Out of line, so that g++ does not see malloc and free meet new and delete
// (-Wmismatched-new-delete).
[[gnu::noinline]] inline void* probe_alloc(size_t n) {
    size_t seen = g_largest_alloc.load(std::memory_order_relaxed);
    while (n > seen && !g_largest_alloc.compare_exchange_weak(seen, n, std::memory_order_relaxed)) {
    }
    void* p = std::malloc(n ? n : 1);
    if (!p) throw std::bad_alloc();
    return p;
}
[[gnu::noinline]] inline void probe_free(void* p) noexcept { std::free(p); }

}  // namespace io_test

void* operator new(size_t n) { return io_test::probe_alloc(n); }
void* operator new[](size_t n) { return io_test::probe_alloc(n); }
void operator delete(void* p) noexcept { io_test::probe_free(p); }
void operator delete[](void* p) noexcept { io_test::probe_free(p); }
void operator delete(void* p, size_t) noexcept { io_test::probe_free(p); }
void operator delete[](void* p, size_t) noexcept { io_test::probe_free(p); }
