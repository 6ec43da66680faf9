#include "cli/progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace bodt_cli {

namespace {

const char* const kPhaseNames[] = {"reading", "setting up", "steps", "writing"};

// Terminal columns of stderr (80 when unknown).
size_t columns() {
    winsize w{};
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &w) == 0 && w.ws_col > 0) return w.ws_col;
    return 80;
}

// `text` cut to `width` bytes, not inside a UTF-8 sequence.
std::string cut(const std::string& text, size_t width) {
    if (text.size() <= width) return text;
    size_t n = width;
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
    return text.substr(0, n);
}

}  // namespace

std::string duration_text(double seconds) {
    char text[32];
    if (seconds < 0.995) {
        std::snprintf(text, sizeof text, "%.2f s", seconds < 0.0 ? 0.0 : seconds);
    } else if (seconds < 59.95) {
        std::snprintf(text, sizeof text, "%.1f s", seconds);
    } else if (seconds < 3600.0) {
        const long s = std::lround(seconds);
        std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
    } else {
        const long m = std::lround(seconds / 60.0);
        std::snprintf(text, sizeof text, "%ld h %02ld min", m / 60, m % 60);
    }
    return text;
}

Progress::Progress(Verbosity verbosity) : start_(Clock::now()) {
    if (verbosity == Verbosity::Verbose) style_ = Style::Log;
    else if (verbosity == Verbosity::Normal) style_ = isatty(STDERR_FILENO) == 1 ? Style::Live : Style::LongLog;
    if (style_ == Style::Live || style_ == Style::LongLog) ticker_ = std::thread([this] { tick(); });
}

Progress::~Progress() { finish(); }

double Progress::elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

double Progress::seconds(Phase p) const {
    std::lock_guard<std::mutex> lock(mutex_);
    double s = spent_[static_cast<int>(p)];
    if (p == phase_ && !stop_) s += elapsed() - phase_start_;
    return s;
}

void Progress::close_phase(double t) {
    spent_[static_cast<int>(phase_)] += t - phase_start_;
    phase_start_ = t;
}

void Progress::phase(Phase p, const std::string& label) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double t = elapsed();
    // A long log shows the last step before the next phase.
    if (style_ == Style::LongLog && long_ && phase_ == Phase::Steps && logged_steps_ < steps_.size()) {
        log(step_line(t));
        logged_steps_ = steps_.size();
    }
    close_phase(t);
    phase_ = p;
    label_ = label;
    if (p == Phase::Steps) steps_start_ = last_step_end_ = t;
    if (style_ == Style::Log || (style_ == Style::LongLog && long_)) log(label + " [" + duration_text(t) + "]");
    if (style_ == Style::Live) draw_live(t);
}

void Progress::start_steps(int32_t max_steps) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        max_steps_ = max_steps;
    }
    phase(Phase::Steps, "improving: at most " + std::to_string(max_steps) + " steps");
}

int Progress::callback(const bodt_step_report* report, void* user_data) {
    static_cast<Progress*>(user_data)->step(*report);
    return 0;
}

void Progress::step(const bodt_step_report& r) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double t = elapsed();
    steps_.push_back({r, t - last_step_end_});
    last_step_end_ = t;
    flips += r.flips;
    inserted += r.vertices_inserted;
    collapsed += r.edges_collapsed;
    if (style_ == Style::Log || (style_ == Style::LongLog && long_ && t - last_log_ >= kLogInterval)) {
        log(step_line(t));
        logged_steps_ = steps_.size();
        last_log_ = t;
    }
    if (style_ == Style::Live) draw_live(t);
}

void Progress::tick() {
    std::unique_lock<std::mutex> lock(mutex_);
    const auto stopped = [this] { return stop_; };
    if (style_ == Style::Live) {
        // The clock on the live line runs while the library works.
        while (!wake_.wait_for(lock, std::chrono::milliseconds(200), stopped)) draw_live(elapsed());
        return;
    }
    // LongLog: one thing to do, at kLongRun if the run is still going: say
    // what it is doing now; phase() and step() log from then on.
    const auto at = start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kLongRun));
    if (wake_.wait_until(lock, at, stopped)) return;
    const double t = elapsed();
    long_ = true;
    last_log_ = t;
    if (phase_ == Phase::Steps && !steps_.empty()) {
        log(step_line(t));
        logged_steps_ = steps_.size();
    } else {
        log(label_ + " [" + duration_text(t) + "]");
    }
}

double Progress::mean_step() const {
    // The steps after the first give the pace (the first also sets up).
    if (steps_.size() < 2) return steps_.empty() ? 0.0 : steps_[0].seconds;
    return (last_step_end_ - steps_start_ - steps_[0].seconds) / static_cast<double>(steps_.size() - 1);
}

std::string Progress::step_line(double t) const {
    const bodt_step_report& r = steps_.back().report;
    const int32_t k = static_cast<int32_t>(steps_.size());
    char text[512];
    std::snprintf(text, sizeof text,
                  "step %d/%d: min dihedral %.3f, max dihedral %.3f, min stretch %.5f, %d vertices moved "
                  "(largest move %.3g), %d flips, %d inserted, %d collapsed [%s; step %s",
                  k, max_steps_, r.min_dihedral, r.max_dihedral, r.min_stretch, r.vertices_moved, r.max_move, r.flips,
                  r.vertices_inserted, r.edges_collapsed, duration_text(t).c_str(),
                  duration_text(steps_.back().seconds).c_str());
    std::string line = text;
    if (k < max_steps_) line += "; about " + duration_text(mean_step() * (max_steps_ - k)) + " left";
    return line + "]";
}

std::string Progress::live_text(double t) const {
    if (phase_ != Phase::Steps) return label_ + "  " + duration_text(t);
    const int32_t k = static_cast<int32_t>(steps_.size());
    constexpr int kWidth = 20;
    const int filled = static_cast<int>(static_cast<int64_t>(kWidth) * k / (max_steps_ > 0 ? max_steps_ : 1));
    std::string bar(kWidth, '.');
    for (int i = 0; i < filled && i < kWidth; ++i) bar[static_cast<size_t>(i)] = '#';
    char text[256];
    if (k == 0) {
        std::snprintf(text, sizeof text, "[%s] step 1/%d running  %s", bar.c_str(), max_steps_,
                      duration_text(t).c_str());
        return text;
    }
    const bodt_step_report& r = steps_.back().report;
    std::snprintf(text, sizeof text, "[%s] step %d/%d  min %.2f deg  max %.2f deg  flips %lld  %s", bar.c_str(), k,
                  max_steps_, r.min_dihedral, r.max_dihedral, static_cast<long long>(flips),
                  duration_text(t).c_str());
    std::string line = text;
    if (k < max_steps_) {
        // Counts down while the next step runs.
        const double left = mean_step() * (max_steps_ - k) - (t - last_step_end_);
        line += ", ~" + duration_text(left > 0.0 ? left : 0.0) + " left";
    }
    return line;
}

void Progress::draw_live(double t) {
    const std::string text = cut(live_text(t), columns() - 1);
    if (text == drawn_ && line_open_) return;
    // \r and "erase to end of line": the line is redrawn in place.
    std::fprintf(stderr, "\r%s\x1b[K", text.c_str());
    std::fflush(stderr);
    drawn_ = text;
    line_open_ = true;
}

void Progress::log(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
}

void Progress::done() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        const double t = elapsed();
        if (style_ == Style::LongLog && long_ && logged_steps_ < steps_.size()) {
            log(step_line(t));
            logged_steps_ = steps_.size();
        }
        close_phase(t);
        std::string text = "done in " + duration_text(t) + " (";
        for (int p = 0; p < static_cast<int>(Phase::Count); ++p) {
            if (p) text += ", ";
            if (p == static_cast<int>(Phase::Steps)) text += std::to_string(steps_.size()) + " ";
            text += std::string(kPhaseNames[p]) + " " + duration_text(spent_[p]);
        }
        text += ")";
        if (style_ == Style::Log || (style_ == Style::LongLog && long_)) log(text);
        if (style_ == Style::Live) {
            std::fprintf(stderr, "\r%s\x1b[K", cut(text, columns() - 1).c_str());
            line_open_ = true;
        }
    }
    finish();
}

void Progress::finish() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_) return;
        close_phase(elapsed());
        stop_ = true;
    }
    wake_.notify_all();
    if (ticker_.joinable()) ticker_.join();
    if (line_open_) {
        std::fputc('\n', stderr);
        std::fflush(stderr);
        line_open_ = false;
    }
}

}  // namespace bodt_cli
