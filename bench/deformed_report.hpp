// deformed_report.hpp -- the measures of one row of bodt_bench_deformed and
// how they are printed: a JSON object per row, a markdown table shaped like
// paper 002's Tables 1-3.
#ifndef BODT_BENCH_DEFORMED_REPORT_HPP
#define BODT_BENCH_DEFORMED_REPORT_HPP

#include "deformed_cases.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// The rows of a case: the reference as it is, the deformed mesh as it is,
// and the deformed mesh after each mode.
enum class RowKind { Original, Deformed, Odt, Phased };
const char* row_name(RowKind k);  // "original", "deformed", "odt", "phased"

// Plain data: a forked child hands it back through a pipe.
struct RowResult {
    char status[16];    // ok, error, crashed, timeout
    char where[64];     // the call that failed
    char message[512];  // bodt_mesh_last_error or our own
    int32_t measured;   // the measures below are valid
    int32_t vertices, tets, inverted;
    double stretch_mean, stretch_min, min_dihedral, max_dihedral;
    // bodt_mesh_recovery_error; edges 0: no target density / no cylinder
    double density_mean, density_max, geometric_mean, geometric_max;
    int64_t density_edges, geometric_edges;
    int32_t geometry_regions, geometry_chains;  // bodt_mesh_get_geometry_counts, -1 unknown
    int32_t steps_done;
    int64_t vertices_moved, flips, inserted, collapsed;  // sums over the steps
    double time_s;            // the steps alone
    double reference_time_s;  // bodt_set_reference_mesh
    double peak_rss_mb;
};
RowResult empty_row_result();
void set_row_status(RowResult& r, const char* status, const std::string& where, const std::string& message);

struct CaseRows {
    const DeformedCase* c;
    std::string note;        // what was made
    std::string prep_error;  // the case could not be made
    std::vector<RowKind> kinds;
    std::vector<RowResult> rows;  // one per kind
};

std::string row_json(const CaseRows& cr, RowKind kind, const RowResult& r, int max_steps);
std::string deformed_markdown(const std::vector<CaseRows>& cases, int max_steps,
                              const std::vector<std::string>& notes, double total_s);

}  // namespace bench

#endif
