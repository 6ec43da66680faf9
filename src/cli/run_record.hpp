// How a mesh was made: what `bodt improve` knows of its run (mode,
// parameters, steps and their figures, totals, times, quality before and
// after).  `bodt improve --json` prints it as one JSON object, `--report`
// puts it in the HTML report, and `bodt report --run RUN.json` reads it
// back from that JSON.
#pragma once

#include "bodt.h"
#include "cli/progress.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace bodt_cli {

struct RunRecord {
    std::string version;  // of the library that ran
    std::string input, output, reference, report;
    std::string mode;     // as --mode names it
    std::string ops;      // as --ops takes it: "default" or "smooth,flip"
    int32_t max_steps = 0;
    int32_t threads = 1;
    bool keep_surface = false;
    // Every parameter in effect (param_table's names), its value as written.
    std::vector<std::pair<std::string, std::string>> parameters;
    // The options given that set them, as typed: "--ops smooth", "--param
    // min_stretch=0.1", "--threads 2", "--keep-surface".
    std::vector<std::string> options;
    std::vector<StepFigures> steps;
    int64_t flips = 0, vertices_inserted = 0, edges_collapsed = 0;
    bool converged = false;  // stopped before max_steps: nothing moved or changed
    double seconds[static_cast<int>(Phase::Count)] = {};
    double seconds_total = 0.0;
    bodt_quality before{}, after{};
    bool recovery = false;  // phased: the density and geometric errors
    bodt_recovery_error recovery_before{}, recovery_after{};
};

// One line of JSON, no newline.
std::string run_json(const RunRecord& run);

// The record in the file `path`, the JSON of run_json (as `bodt improve
// --json` printed it, or as any JSON tool rewrote it).  False with `error`
// when the file cannot be read, is not JSON ("line 3, column 7: expected
// ':'") or is not such an object.
bool read_run(const std::string& path, RunRecord& run, std::string& error);

}  // namespace bodt_cli
