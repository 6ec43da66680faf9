// What `bodt improve` is doing, on stderr, from the start: the phases it
// knows (reading, setting up, step k of n, writing) with the time elapsed
// and, from the steps done, an estimate of the time left.
//   quiet:    nothing;
//   normal:   on a terminal (isatty(2)), one live line redrawn in place
//             (a ticker thread updates its clock while the library works);
//             otherwise (a log, a pipe) nothing for a run that ends within
//             kLongRun seconds, and from then on (the ticker wakes once, at
//             kLongRun, to say what the run is doing) a log line for each
//             phase and at most one step line every kLogInterval seconds
//             (plus the last step);
//   verbose:  a log line for each phase and each step, terminal or not.
// Log lines end with the time elapsed in brackets: "reading a.mesh [0.0 s]",
// "step 3/20: min dihedral ..., 0 collapsed [3.5 s; step 1.1 s; about 18 s
// left]".  The estimate assumes every one of the n steps runs (a run stops
// earlier when it converges) at the mean duration of the steps after the
// first (the first also sets the library up).
#pragma once

#include "bodt.h"
#include "cli/args.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace bodt_cli {

// One step as the callback saw it, and how long it took.
struct StepFigures {
    bodt_step_report report{};
    double seconds = 0.0;
};

enum class Phase { Reading, SettingUp, Steps, Writing, Count };

class Progress {
public:
    static constexpr double kLongRun = 5.0;      // seconds
    static constexpr double kLogInterval = 5.0;  // seconds

    explicit Progress(Verbosity verbosity);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // Enters a phase; `label` says what it does ("reading part.mesh").
    void phase(Phase p, const std::string& label);
    // Enters Phase::Steps with at most `max_steps` steps (bodt_run's).
    void start_steps(int32_t max_steps);
    // A bodt_step_callback; user_data is the Progress.
    static int callback(const bodt_step_report* report, void* user_data);
    // The run is over: says so (with the time of each phase), ends the live
    // line and stops the ticker.  Call before printing anything else.
    void done();
    // Ends the live line and stops the ticker without a last word (before an
    // error message).
    void finish();

    // Seconds spent in a phase so far, and since the start.
    double seconds(Phase p) const;
    double elapsed() const;
    const std::vector<StepFigures>& steps() const { return steps_; }
    int64_t flips = 0, inserted = 0, collapsed = 0;

private:
    enum class Style { None, Live, Log, LongLog };
    using Clock = std::chrono::steady_clock;

    void step(const bodt_step_report& r);
    void tick();
    void close_phase(double t);
    // With mutex_ held:
    std::string live_text(double t) const;
    double mean_step() const;
    std::string step_line(double t) const;  // of the last step
    void draw_live(double t);
    void log(const std::string& line);

    Style style_ = Style::None;
    Clock::time_point start_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::thread ticker_;          // Live and LongLog; finish() joins it
    bool stop_ = false;
    bool long_ = false;           // LongLog: the run passed kLongRun
    bool line_open_ = false;      // Live: a line is drawn and not ended
    std::string drawn_;           // Live: what the line shows
    Phase phase_ = Phase::Reading;
    std::string label_;
    double phase_start_ = 0.0;
    double spent_[static_cast<int>(Phase::Count)] = {};
    int32_t max_steps_ = 0;
    double last_log_ = 0.0;       // LongLog: when the last step line was printed
    size_t logged_steps_ = 0;     // LongLog: steps printed so far (the last index + 1)
    std::vector<StepFigures> steps_;
    double steps_start_ = 0.0, last_step_end_ = 0.0;
};

// "3.2 s", "4 min 05 s", "2 h 03 min": a duration for people.
std::string duration_text(double seconds);

}  // namespace bodt_cli
