#include "cli/report_sections.hpp"

#include "cli/report_format.hpp"

#include <cmath>

namespace bodt_cli {

namespace {

// A card with one figure; `key` and `value` go into data-key and data-value.
std::string figure_card(const char* key, double value, const std::string& label, const std::string& text,
                        const std::string& note) {
    return "<div class=\"card\" data-key=\"" + std::string(key) + "\" data-value=\"" + exact(value) +
           "\"><div class=\"k\">" + label + "</div><div class=\"v\">" + text + "</div><div class=\"n\">" + note +
           "</div></div>\n";
}

std::string row(const char* key, const std::string& label, const std::string& value, const std::string& data) {
    return "<tr data-key=\"" + std::string(key) + "\" data-value=\"" + escape_html(data) + "\"><th scope=\"row\">" +
           label + "</th><td>" + value + "</td></tr>\n";
}

std::string cell(double v, const std::string& text) { return "<td data-value=\"" + exact(v) + "\">" + text + "</td>"; }

// The per-step table shows at most this many rows: the first and last half.
constexpr size_t kMaxStepRows = 200;

std::string step_rows(const RunRecord& run) {
    std::string s;
    const size_t n = run.steps.size();
    for (size_t k = 0; k < n; ++k) {
        if (n > kMaxStepRows && k == kMaxStepRows / 2) {
            s += "<tr class=\"skipped\"><td colspan=\"12\">&hellip; " +
                 grouped(static_cast<int64_t>(n - kMaxStepRows)) +
                 " steps not shown (all are in the JSON of <code>bodt improve --json</code>) &hellip;</td></tr>\n";
            k = n - kMaxStepRows / 2;
        }
        const StepFigures& f = run.steps[k];
        const bodt_step_report& r = f.report;
        s += "<tr data-step=\"" + std::to_string(r.step) + "\">" + cell(r.step, std::to_string(r.step)) +
             cell(f.seconds, fixed(f.seconds, 3)) + cell(r.min_dihedral, fixed(r.min_dihedral, 3) + kDeg) +
             cell(r.max_dihedral, fixed(r.max_dihedral, 3) + kDeg) +
             cell(r.min_stretch, with_minus(fixed(r.min_stretch, 4))) +
             cell(r.vertices_moved, grouped(r.vertices_moved)) + cell(r.moves_rejected, grouped(r.moves_rejected)) +
             cell(r.moves_shortened, grouped(r.moves_shortened)) + cell(r.max_move, general(r.max_move, 3)) +
             cell(r.flips, grouped(r.flips)) + cell(r.vertices_inserted, grouped(r.vertices_inserted)) +
             cell(r.edges_collapsed, grouped(r.edges_collapsed)) + "</tr>\n";
    }
    return s;
}

std::string recovery_rows(const RunRecord& run) {
    const auto r = [](const char* key, const char* label, double before, double after) {
        return "<tr data-key=\"" + std::string(key) + "\"><th scope=\"row\">" + label + "</th>" +
               cell(before, general(before, 5)) + cell(after, general(after, 5)) + "</tr>\n";
    };
    const bodt_recovery_error &a = run.recovery_before, &b = run.recovery_after;
    return r("density_mean", "Density error, mean", a.density_mean, b.density_mean) +
           r("density_max", "Density error, largest", a.density_max, b.density_max) +
           r("geometric_mean", "Geometric error, mean", a.geometric_mean, b.geometric_mean) +
           r("geometric_max", "Geometric error, largest", a.geometric_max, b.geometric_max);
}

}  // namespace

std::string boundary_section(const Comparison& c) {
    std::string s = "<section id=\"boundary\">\n<h2>Boundary</h2>\n<p class=\"note\">What <code>bodt compare</code> "
                    "measures: the change of volume, the Hausdorff distance between the two boundary surfaces "
                    "(exact distances over whole triangles) relative to L, the largest side of the original's "
                    "bounding box, and the face markers.</p>\n<div class=\"cards\">\n";
    s += figure_card("volume_change_rel", c.volume_change_rel, "Volume change", percent(100.0 * c.volume_change_rel),
                     with_minus(general(c.volume_change, 6)) + " in mesh units");
    const bool bounded = c.hausdorff_upper > c.hausdorff * (1.0 + 1e-3) + 1e-7 * c.bbox_largest_side;
    s += figure_card("hausdorff_rel", c.hausdorff_rel, "Boundary distance (Hausdorff / L)",
                     c.hausdorff_rel == 0.0 ? "0" : general(100.0 * c.hausdorff_rel, 3) + "\xE2\x80\x89%",
                     "h = " + general(c.hausdorff, 4) +
                         (bounded ? " (at most " + general(c.hausdorff_upper, 4) + ")" : "") +
                         ", L = " + general(c.bbox_largest_side, 6));
    std::string lost;
    for (const int32_t m : c.markers_lost) lost += (lost.empty() ? "" : ", ") + std::to_string(m);
    int64_t marked = 0;
    for (const MarkerArea& m : c.markers) marked += m.marker != 0 && m.faces_before > 0;
    s += figure_card("markers_kept", c.markers_kept ? 1.0 : 0.0, "Face markers kept",
                     c.markers_kept ? "yes" : "<span class=\"bad\">no</span>",
                     c.markers_kept ? std::to_string(marked) + " nonzero marker" + (marked == 1 ? "" : "s")
                                    : "lost: " + lost);
    s += "</div>\n<h3>Faces and area by marker</h3>\n<div class=\"scroll\"><table class=\"markers\" "
         "id=\"markers-table\">\n<thead><tr><th scope=\"col\">Marker</th><th scope=\"col\">Faces before</th>"
         "<th scope=\"col\">Faces after</th><th scope=\"col\">Area before</th><th scope=\"col\">Area after</th>"
         "<th scope=\"col\">Area change</th></tr></thead>\n<tbody>\n";
    for (const MarkerArea& m : c.markers) {
        const double rel = m.area_before > 0.0 ? (m.area_after - m.area_before) / m.area_before : 0.0;
        const bool gone = m.marker != 0 && m.faces_before > 0 && m.faces_after == 0;
        s += "<tr data-marker=\"" + std::to_string(m.marker) + "\"" + (gone ? " class=\"lost\"" : "") + ">" +
             cell(m.marker, m.marker == 0 ? "0 (none)" : std::to_string(m.marker)) +
             cell(static_cast<double>(m.faces_before), grouped(m.faces_before)) +
             cell(static_cast<double>(m.faces_after), grouped(m.faces_after)) +
             cell(m.area_before, general(m.area_before, 6)) + cell(m.area_after, general(m.area_after, 6)) +
             cell(rel, m.area_before > 0.0 ? (rel == 0.0 ? "=" : percent(100.0 * rel)) : "&ndash;") + "</tr>\n";
    }
    return s + "</tbody></table></div>\n</section>\n";
}

std::string run_section(const RunRecord* run, const bodt_quality& improved) {
    std::string s = "<section id=\"run\">\n<h2>How the mesh was made</h2>\n";
    if (!run) {
        return s + "<p class=\"note\" id=\"run-unknown\">Not recorded: this report compares two mesh files.  "
                   "<code>bodt improve IN OUT --report REPORT.html</code> writes the report with the run's mode, "
                   "parameters and steps; so does <code>bodt report ORIGINAL IMPROVED -o REPORT.html --run "
                   "RUN.json</code>, RUN.json being what <code>bodt improve --json</code> printed.</p>\n</section>\n";
    }
    std::string command = "bodt improve " + run->input + " " + run->output;
    for (const std::string& o : run->options) command += " " + o;
    s += "<p class=\"note\" id=\"run-command\">By <code>" + escape_html(command) + "</code>" +
         (run->version.empty() ? "" : " (bodt " + escape_html(run->version) + ")") + ".</p>\n";
    // The record's quality has six decimals.
    if (improved.num_tets != run->after.num_tets || improved.num_vertices != run->after.num_vertices ||
        improved.num_boundary_faces != run->after.num_boundary_faces ||
        std::fabs(improved.min_dihedral - run->after.min_dihedral) > 1e-5 ||
        std::fabs(improved.max_dihedral - run->after.max_dihedral) > 1e-5)
        s += "<p class=\"note warn\" id=\"run-mismatch\">The run's result had " + grouped(run->after.num_vertices) +
             " vertices, " + grouped(run->after.num_tets) + " tets and a smallest dihedral angle of " +
             fixed(run->after.min_dihedral, 3) + kDeg + "; the improved mesh here has " +
             grouped(improved.num_vertices) + ", " + grouped(improved.num_tets) + " and " +
             fixed(improved.min_dihedral, 3) + kDeg + ": the record may be of another run.</p>\n";
    std::string options;
    for (const std::string& o : run->options) options += (options.empty() ? "" : " ") + o;
    const std::string steps_text = grouped(static_cast<int64_t>(run->steps.size())) + " of at most " +
                                   grouped(run->max_steps) +
                                   (run->converged ? " (converged: nothing moved or changed any more)"
                                                   : " (stopped at the limit)");
    s += "<div class=\"scroll\"><table class=\"run\" id=\"run-summary\">\n<tbody>\n";
    s += row("mode", "Mode", "<code>" + escape_html(run->mode) + "</code>", run->mode);
    s += row("ops", "Operations", "<code>" + escape_html(run->ops) + "</code>", run->ops);
    s += row("options", "Options given", options.empty() ? "none" : "<code>" + escape_html(options) + "</code>",
             options);
    s += row("steps", "Steps", steps_text, std::to_string(run->steps.size()));
    s += row("flips", "Flips", grouped(run->flips), std::to_string(run->flips));
    s += row("vertices_inserted", "Vertices inserted", grouped(run->vertices_inserted),
             std::to_string(run->vertices_inserted));
    s += row("edges_collapsed", "Edges collapsed", grouped(run->edges_collapsed),
             std::to_string(run->edges_collapsed));
    s += row("threads", "Threads", run->threads == 0 ? "every core" : std::to_string(run->threads),
             std::to_string(run->threads));
    s += row("seconds", "Time", fixed(run->seconds_total, 2) + " s: reading " +
                                    fixed(run->seconds[static_cast<int>(Phase::Reading)], 2) + " s, setting up " +
                                    fixed(run->seconds[static_cast<int>(Phase::SettingUp)], 2) + " s, steps " +
                                    fixed(run->seconds[static_cast<int>(Phase::Steps)], 2) + " s, writing " +
                                    fixed(run->seconds[static_cast<int>(Phase::Writing)], 2) + " s",
             exact(run->seconds_total));
    s += "</tbody></table></div>\n";
    s += "<details><summary>Every parameter in effect (" + std::to_string(run->parameters.size()) +
         ")</summary>\n<div class=\"scroll\"><table class=\"run\" id=\"run-parameters\">\n<tbody>\n";
    for (const auto& p : run->parameters)
        s += row(p.first.c_str(), "<code>" + escape_html(p.first) + "</code>", escape_html(p.second), p.second);
    s += "</tbody></table></div>\n</details>\n";
    if (run->recovery)
        s += "<h3>Recovery (phased mode)</h3>\n<div class=\"scroll\"><table class=\"run\" id=\"run-recovery\">\n"
             "<thead><tr><th scope=\"col\"></th><th scope=\"col\">Before</th><th scope=\"col\">After</th></tr>"
             "</thead>\n<tbody>\n" + recovery_rows(*run) + "</tbody></table></div>\n";
    s += "<h3>Steps</h3>\n<p class=\"note\">Each step's figures as <code>bodt_run</code> reported them: the worst "
         "angles and stretch after the step, the vertices moved, refused and moved by a halved step, the largest "
         "move, and the connectivity changes kept.  The first step's time includes the library's setting up.</p>\n"
         "<div class=\"scroll\"><table class=\"steps\" id=\"run-steps\">\n<thead><tr><th scope=\"col\">Step</th>"
         "<th scope=\"col\">Seconds</th><th scope=\"col\">Min angle</th><th scope=\"col\">Max angle</th>"
         "<th scope=\"col\">Min stretch</th><th scope=\"col\">Moved</th><th scope=\"col\">Refused</th>"
         "<th scope=\"col\">Halved</th><th scope=\"col\">Largest move</th><th scope=\"col\">Flips</th>"
         "<th scope=\"col\">Inserted</th><th scope=\"col\">Collapsed</th></tr></thead>\n<tbody>\n" +
         step_rows(*run) + "</tbody></table></div>\n";
    return s + "</section>\n";
}

}  // namespace bodt_cli
