// How the bodt command shows mesh quality: the one table (one column, or
// before / after), the JSON fields, and the dihedral-angle histogram as a
// text bar chart.
#pragma once

#include "bodt.h"

#include <string>

namespace bodt_cli {

// bodt_mesh_quality() with the size field set.
bodt_quality measure(const bodt_mesh* mesh);

// The quality table on stdout: one column, or "before" and "after" columns
// when `before` is given.
void print_table(const bodt_quality* before, const bodt_quality& after);
// A row in the table's layout (for rows other commands add).
void print_row(const char* name, const std::string& before, const std::string& after);

// `text` as a JSON string literal, quotes included.
std::string json_string(const std::string& text);
// A double as a JSON number: the shortest of 15 and 17 significant digits
// that reads back as `v`; null when it is not finite.
std::string json_number(double v);
// The quality as JSON members, without braces: "\"vertices\": 27, ...";
// with `edges`, also "dihedral_bin_edges".  min_stretch and mean_stretch (the
// names of bodt_quality) come again as stretch_min and stretch_mean, the
// deprecated names of earlier versions.
std::string quality_json_members(const bodt_quality& q, bool edges);

// The 23-bin dihedral histogram as a text bar chart on stdout.
void print_histogram(const bodt_quality& q);

}  // namespace bodt_cli
