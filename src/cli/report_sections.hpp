// `bodt report`: the sections on the boundary (the figures of `bodt
// compare`) and on how the improved mesh was made (the run of `bodt
// improve`).
#pragma once

#include "bodt.h"
#include "cli/compare.hpp"
#include "cli/run_record.hpp"

#include <string>

namespace bodt_cli {

// Volume change, relative Hausdorff distance of the boundaries and the face
// markers kept, as cards and a table of markers.
std::string boundary_section(const Comparison& c);

// The run's mode, options, parameters, totals, times and per-step figures;
// without a run (nullptr), how to get them.  `improved` is the quality of
// the mesh the report shows, to flag a run that made another mesh.
std::string run_section(const RunRecord* run, const bodt_quality& improved);

}  // namespace bodt_cli
