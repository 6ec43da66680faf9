// deformed_report.cpp -- see deformed_report.hpp.
#include "deformed_report.hpp"

#include "bench_util.hpp"
#include "bodt.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>

namespace bench {

namespace {

// A recovery error: "–" without edges to measure (no target density, or no
// cylindrical region).
std::string err_cell(double v, int64_t edges, const char* f) { return edges > 0 ? fmt(f, v) : "–"; }

}  // namespace

const char* row_name(RowKind k) {
    switch (k) {
        case RowKind::Original: return "original";
        case RowKind::Deformed: return "deformed";
        case RowKind::Odt: return "odt";
        case RowKind::Phased: return "phased";
    }
    return "?";
}

RowResult empty_row_result() {
    RowResult r;
    std::memset(&r, 0, sizeof r);
    std::snprintf(r.status, sizeof r.status, "ok");
    r.geometry_regions = r.geometry_chains = -1;
    r.stretch_mean = r.stretch_min = r.min_dihedral = r.max_dihedral = NAN;
    r.density_mean = r.density_max = r.geometric_mean = r.geometric_max = NAN;
    return r;
}

void set_row_status(RowResult& r, const char* status, const std::string& where, const std::string& message) {
    std::snprintf(r.status, sizeof r.status, "%s", status);
    std::snprintf(r.where, sizeof r.where, "%s", where.c_str());
    std::snprintf(r.message, sizeof r.message, "%s", message.c_str());
}

std::string row_json(const CaseRows& cr, RowKind kind, const RowResult& r, int max_steps) {
    const DeformedCase& c = *cr.c;
    std::string o = "{";
    o += "\"case\":" + json_str(c.name);
    o += ",\"kind\":" + json_str(c.kind);
    o += ",\"source\":" + json_str(c.source);
    o += ",\"deformation\":" + json_str(c.deformation);
    if (!cr.note.empty()) o += ",\"note\":" + json_str(cr.note);
    o += ",\"row\":" + json_str(row_name(kind));
    o += ",\"mode\":" + json_str(kind == RowKind::Odt ? "odt" : kind == RowKind::Phased ? "phased-odt" : "none");
    o += ",\"status\":" + json_str(r.status);
    if (r.where[0]) o += ",\"where\":" + json_str(r.where);
    if (r.message[0]) o += ",\"message\":" + json_str(r.message);
    o += ",\"library\":" + json_str(bodt_version_string());
    o += ",\"max_steps\":" + std::to_string(kind == RowKind::Odt || kind == RowKind::Phased ? max_steps : 0);
    o += ",\"steps_done\":" + std::to_string(r.steps_done);
    if (r.measured) {
        o += ",\"vertices\":" + std::to_string(r.vertices);
        o += ",\"tets\":" + std::to_string(r.tets);
        o += ",\"inverted\":" + std::to_string(r.inverted);
        o += ",\"stretch_mean\":" + json_num(r.stretch_mean, "%.5f");
        o += ",\"stretch_min\":" + json_num(r.stretch_min, "%.5f");
        o += ",\"density_error_mean\":" + (r.density_edges ? json_num(r.density_mean, "%.5g") : "null");
        o += ",\"density_error_max\":" + (r.density_edges ? json_num(r.density_max, "%.5g") : "null");
        o += ",\"density_edges\":" + std::to_string(r.density_edges);
        o += ",\"geometric_error_mean\":" + (r.geometric_edges ? json_num(r.geometric_mean, "%.5g") : "null");
        o += ",\"geometric_error_max\":" + (r.geometric_edges ? json_num(r.geometric_max, "%.5g") : "null");
        o += ",\"geometric_edges\":" + std::to_string(r.geometric_edges);
        o += ",\"min_dihedral\":" + json_num(r.min_dihedral, "%.4f");
        o += ",\"max_dihedral\":" + json_num(r.max_dihedral, "%.4f");
    }
    if (r.geometry_regions >= 0) o += ",\"geometry_regions\":" + std::to_string(r.geometry_regions);
    if (r.geometry_chains >= 0) o += ",\"geometry_chains\":" + std::to_string(r.geometry_chains);
    o += ",\"vertices_moved\":" + std::to_string(r.vertices_moved);
    o += ",\"flips\":" + std::to_string(r.flips);
    o += ",\"inserted\":" + std::to_string(r.inserted);
    o += ",\"collapsed\":" + std::to_string(r.collapsed);
    o += ",\"time_s\":" + json_num(r.time_s, "%.4f");
    o += ",\"reference_time_s\":" + json_num(r.reference_time_s, "%.4f");
    o += ",\"peak_rss_mb\":" + json_num(r.peak_rss_mb, "%.1f");
    return o + "}";
}

std::string deformed_markdown(const std::vector<CaseRows>& cases, int max_steps, const std::vector<std::string>& notes,
                              double total_s) {
    std::string md = "# bodt_bench_deformed\n\n";
    char date[64];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M", std::localtime(&now));
    md += fmt("libbodt %s; rows `odt` (BODT_MODE_ODT) and `phased` (BODT_MODE_PHASED_ODT): bodt_run with at most "
              "%d steps, library defaults; %s; total %.0f s.\n\n",
              bodt_version_string(), max_steps, date, total_s);
    md += "Shaped like paper 002's Tables 1-3.  `original` = the reference mesh, `deformed` = the deformed mesh "
          "as it is, then the deformed mesh after each mode; every row but `original` is measured against the "
          "original as reference (bodt_set_reference_mesh).  Stretch = 6√6 V / (Σ face areas · longest edge), "
          "negative when inverted; density error = eq. (4.1) over the edges, |1/|e| − ρ'| / ρ'; geometric error = "
          "distance of the midpoints of the edges on fitted cylinders from the cylinder, in mesh units "
          "(bodt_mesh_recovery_error; – = nothing to measure); inv = inverted tets; dihedral angles in degrees; "
          "s = wall time of the steps alone.\n\n";
    md += "| case | row | V | T | stretch ave | stretch min | density err ave | density err max | geom err ave | "
          "geom err max | inv | min/max dihedral | steps | s |\n";
    md += "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const CaseRows& cr : cases) {
        for (size_t k = 0; k < cr.kinds.size() && k < cr.rows.size(); ++k) {
            const RowResult& r = cr.rows[k];
            const bool stepped = cr.kinds[k] == RowKind::Odt || cr.kinds[k] == RowKind::Phased;
            const bool ok = !std::strcmp(r.status, "ok");
            md += "| " + cr.c->name + " | " + row_name(cr.kinds[k]) + (ok ? "" : fmt(" (**%s**)", r.status)) + " |";
            if (!r.measured) {
                md += " – | – | – | – | – | – | – | – | – | – |";
            } else {
                md += fmt(" %d | %d | %.3f | %.3f | %s | %s | %s | %s | %s | %.2f/%.2f |", r.vertices, r.tets,
                          r.stretch_mean, r.stretch_min, err_cell(r.density_mean, r.density_edges, "%.3f").c_str(),
                          err_cell(r.density_max, r.density_edges, "%.3f").c_str(),
                          err_cell(r.geometric_mean, r.geometric_edges, "%.3g").c_str(),
                          err_cell(r.geometric_max, r.geometric_edges, "%.3g").c_str(),
                          r.inverted > 0 ? fmt("**%d**", r.inverted).c_str() : "0", r.min_dihedral, r.max_dihedral);
            }
            md += !stepped ? std::string(" | |\n") : !r.measured ? std::string(" – | – |\n")
                                                             : fmt(" %d | %.2f |\n", r.steps_done, r.time_s);
        }
    }
    md += "\nPaper 002's bar (Table 3, DP+RC+PH, compare `hole.dp-rc-ph`): deformed stretch ave/min 0.450/−0.216 "
          "with 19 inverted tets → phased ODT 0.700/0.190 with 0 inverted (13 238 tets in, 18 282 out; density "
          "error ave/max 0.311/5.990 → 0.156/1.713; geometric error ave/max 0.121/0.359 → 0.067/0.391), 37 s "
          "(Core i7 2.8 GHz); plain ODT smoothing: 0.522/−0.281, still 19 inverted.\n";

    std::vector<std::string> lines;
    for (const CaseRows& cr : cases) {
        lines.push_back(fmt("`%s`: %s; %s.", cr.c->name.c_str(), cr.c->deformation.c_str(),
                            cr.note.empty() ? cr.c->source.c_str() : cr.note.c_str()));
        if (!cr.prep_error.empty()) lines.push_back("`" + cr.c->name + "`: could not be made: " + cr.prep_error);
        for (size_t k = 0; k < cr.kinds.size() && k < cr.rows.size(); ++k) {
            const RowResult& r = cr.rows[k];
            const bool stepped = cr.kinds[k] == RowKind::Odt || cr.kinds[k] == RowKind::Phased;
            if (stepped && r.measured && r.inverted > 0)
                lines.push_back(fmt("**`%s` / %s: %d inverted tets after %d steps**", cr.c->name.c_str(),
                                    row_name(cr.kinds[k]), r.inverted, r.steps_done));
            if (std::strcmp(r.status, "ok") != 0 && cr.prep_error.empty())
                lines.push_back(fmt("**`%s` / %s: %s in %s: %s**", cr.c->name.c_str(), row_name(cr.kinds[k]),
                                    r.status, r.where, r.message));
        }
    }
    for (const auto& n : notes) lines.push_back(n);
    if (!lines.empty()) {
        md += "\nNotes:\n\n";
        for (const auto& l : lines) md += "- " + l + "\n";
    }
    return md;
}

}  // namespace bench
