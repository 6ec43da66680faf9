#include "cli/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace bodt_cli {

Progress::Progress(Verbosity verbosity, int32_t max_steps) : max_steps_(max_steps) {
    lines_ = verbosity == Verbosity::Verbose;
    bar_ = verbosity == Verbosity::Normal && isatty(STDERR_FILENO) == 1;
}

Progress::~Progress() { finish(); }

int Progress::callback(const bodt_step_report* report, void* user_data) {
    static_cast<Progress*>(user_data)->step(*report);
    return 0;
}

void Progress::step(const bodt_step_report& r) {
    ++steps;
    flips += r.flips;
    inserted += r.vertices_inserted;
    collapsed += r.edges_collapsed;
    if (lines_) {
        std::fprintf(stderr,
                     "step %d/%d: min dihedral %.3f, max dihedral %.3f, min stretch %.5f, %d vertices moved "
                     "(largest move %.3g), %d flips, %d inserted, %d collapsed\n",
                     steps, max_steps_, r.min_dihedral, r.max_dihedral, r.min_stretch, r.vertices_moved, r.max_move,
                     r.flips, r.vertices_inserted, r.edges_collapsed);
    } else if (bar_) {
        constexpr int kWidth = 20;
        const int filled = static_cast<int>(static_cast<int64_t>(kWidth) * steps / (max_steps_ > 0 ? max_steps_ : 1));
        char bar[kWidth + 1];
        for (int k = 0; k < kWidth; ++k) bar[k] = k < filled ? '#' : '.';
        bar[kWidth] = '\0';
        // \r and "erase to end of line": the bar is redrawn in place.
        std::fprintf(stderr, "\r[%s] step %d/%d  min %.2f deg  max %.2f deg  flips %lld\x1b[K", bar, steps,
                     max_steps_, r.min_dihedral, r.max_dihedral, static_cast<long long>(flips));
        std::fflush(stderr);
        bar_drawn_ = true;
    }
}

void Progress::finish() {
    if (bar_drawn_) {
        std::fputc('\n', stderr);
        bar_drawn_ = false;
    }
}

}  // namespace bodt_cli
