// Work shared among threads, with std::thread instead of OpenMP's runtime:
// libgomp ends the whole process (exit(1)) when it cannot allocate or start
// a thread, and a library must not end its host.  std::thread throws
// instead, and a thread that does not start leaves its share of the work to
// the others, which claim it in chunks: every caller's result is the same
// on any number of threads.  One thread runs on the caller's, with no thread
// started and nothing allocated.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <thread>
#include <vector>

namespace bodt {

// BODT_PARAM_THREADS = 0: OMP_NUM_THREADS when it names a number (as it did
// when the sweeps ran on OpenMP), else every core.
int default_threads();

// Runs body(me) on `threads` threads, me = 0 on the caller's, and returns
// when all are done.  Fewer run when a thread cannot be started (memory or
// the system's limit), so `body` must share its work through a counter
// (ChunkCounter) rather than by `me`.  An exception thrown by body on any
// thread is rethrown here, after every thread has finished.
template <class Body>
void on_threads(int threads, Body&& body) {
    if (threads <= 1) {
        body(0);
        return;
    }
    std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
    std::vector<std::thread> workers;
    workers.reserve(static_cast<size_t>(threads) - 1);
    const auto guarded = [&errors, &body](int me) noexcept {
        try {
            body(me);
        } catch (...) {
            errors[static_cast<size_t>(me)] = std::current_exception();
        }
    };
    for (int me = 1; me < threads; ++me) {
        try {
            workers.emplace_back(guarded, me);
        } catch (...) {
            break;  // the threads that started share its work
        }
    }
    guarded(0);
    for (std::thread& w : workers) w.join();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

// Hands out [begin, end) ranges of [0, n) in chunks of `chunk`, to threads
// that ask until none is left.
class ChunkCounter {
public:
    ChunkCounter(int64_t n, int64_t chunk) : n_(n), chunk_(std::max<int64_t>(1, chunk)) {}

    bool next(int64_t& begin, int64_t& end) {
        begin = next_.fetch_add(chunk_, std::memory_order_relaxed);
        if (begin >= n_) return false;
        end = std::min(n_, begin + chunk_);
        return true;
    }

private:
    const int64_t n_, chunk_;
    std::atomic<int64_t> next_{0};
};

// body(me, begin, end) over chunks of [0, n) on `threads` threads.
template <class Body>
void for_chunks(int threads, int64_t n, int64_t chunk, Body&& body) {
    ChunkCounter counter(n, chunk);
    on_threads(threads, [&](int me) {
        for (int64_t begin, end; counter.next(begin, end);) body(me, begin, end);
    });
}

}  // namespace bodt
