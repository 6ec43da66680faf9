// Progress of `bodt improve` on stderr, and the totals of the run.
//   quiet:   nothing;
//   normal:  a one-line bar redrawn after each step, only when stderr is a
//            terminal (isatty(2)); nothing otherwise (logs stay clean);
//   verbose: a line per step, terminal or not.
#pragma once

#include "bodt.h"
#include "cli/args.hpp"

#include <cstdint>

namespace bodt_cli {

class Progress {
public:
    Progress(Verbosity verbosity, int32_t max_steps);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // A bodt_step_callback; user_data is the Progress.
    static int callback(const bodt_step_report* report, void* user_data);
    // Ends the bar's line (call before printing anything else).
    void finish();

    int32_t steps = 0;
    int64_t flips = 0, inserted = 0, collapsed = 0;

private:
    void step(const bodt_step_report& r);

    bool bar_ = false;
    bool lines_ = false;
    bool bar_drawn_ = false;
    int32_t max_steps_;
};

}  // namespace bodt_cli
