#include "cli/run_record.hpp"

#include "cli/json_value.hpp"
#include "cli/quality_output.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

namespace bodt_cli {

namespace {

const char* const kSecondsKeys[] = {"reading", "setting_up", "steps", "writing"};

std::string integer(int64_t v) { return std::to_string(static_cast<long long>(v)); }

std::string recovery_json(const bodt_recovery_error& e) {
    return "{\"density_mean\": " + json_number(e.density_mean) + ", \"density_max\": " +
           json_number(e.density_max) + ", \"density_edges\": " + integer(e.density_edges) +
           ", \"geometric_mean\": " + json_number(e.geometric_mean) + ", \"geometric_max\": " +
           json_number(e.geometric_max) + ", \"geometric_edges\": " + integer(e.geometric_edges) + "}";
}

std::string step_json(const StepFigures& s) {
    const bodt_step_report& r = s.report;
    return "{\"step\": " + integer(r.step) + ", \"seconds\": " + json_number(s.seconds) +
           ", \"min_dihedral\": " + json_number(r.min_dihedral) + ", \"max_dihedral\": " +
           json_number(r.max_dihedral) + ", \"min_stretch\": " + json_number(r.min_stretch) +
           ", \"vertices_moved\": " + integer(r.vertices_moved) + ", \"moves_rejected\": " +
           integer(r.moves_rejected) + ", \"moves_shortened\": " + integer(r.moves_shortened) +
           ", \"not_positive_definite\": " + integer(r.not_positive_definite) + ", \"max_move\": " +
           json_number(r.max_move) + ", \"flips\": " + integer(r.flips) + ", \"vertices_inserted\": " +
           integer(r.vertices_inserted) + ", \"edges_collapsed\": " + integer(r.edges_collapsed) + "}";
}

std::string optional_string(const std::string& s) { return s.empty() ? "null" : json_string(s); }

// ------------------------------------------------------------ reading back

double number_of(const JsonValue* v, double fallback = 0.0) { return v && v->is_number() ? v->number : fallback; }

// A whole number of type T; 0 for anything else (a hand-edited file may
// hold any number).
template <typename T>
T integer_of(const JsonValue* v) {
    const double x = number_of(v);
    if (!(x >= static_cast<double>(std::numeric_limits<T>::min()) &&
          x <= static_cast<double>(std::numeric_limits<T>::max())))
        return 0;
    return static_cast<T>(x);
}

std::string string_of(const JsonValue* v) { return v && v->is_string() ? v->text : std::string(); }

bool bool_of(const JsonValue* v) { return v && v->type == JsonValue::Type::Bool && v->boolean; }

bodt_quality quality_of(const JsonValue* q) {
    bodt_quality out{};
    out.size = sizeof out;
    if (!q) return out;
    out.num_vertices = integer_of<int32_t>(q->get("vertices"));
    out.num_tets = integer_of<int32_t>(q->get("tets"));
    out.num_boundary_faces = integer_of<int32_t>(q->get("boundary_faces"));
    out.num_unused_vertices = integer_of<int32_t>(q->get("unused_vertices"));
    out.num_inverted = integer_of<int32_t>(q->get("inverted"));
    out.volume = number_of(q->get("volume"));
    out.min_dihedral = number_of(q->get("min_dihedral"));
    out.max_dihedral = number_of(q->get("max_dihedral"));
    out.mean_dihedral = number_of(q->get("mean_dihedral"));
    out.min_stretch = number_of(q->get("min_stretch"), number_of(q->get("stretch_min")));
    out.mean_stretch = number_of(q->get("mean_stretch"), number_of(q->get("stretch_mean")));
    if (const JsonValue* h = q->get("dihedral_histogram"); h && h->type == JsonValue::Type::Array)
        for (size_t b = 0; b < h->items.size() && b < BODT_DIHEDRAL_BINS; ++b)
            out.dihedral_histogram[b] = integer_of<int64_t>(&h->items[b]);
    return out;
}

bodt_recovery_error recovery_of(const JsonValue* e) {
    bodt_recovery_error out{};
    out.size = sizeof out;
    if (!e) return out;
    out.density_mean = number_of(e->get("density_mean"));
    out.density_max = number_of(e->get("density_max"));
    out.density_edges = integer_of<int64_t>(e->get("density_edges"));
    out.geometric_mean = number_of(e->get("geometric_mean"));
    out.geometric_max = number_of(e->get("geometric_max"));
    out.geometric_edges = integer_of<int64_t>(e->get("geometric_edges"));
    return out;
}

}  // namespace

std::string run_json(const RunRecord& run) {
    std::string s = "{\"version\": " + json_string(run.version) + ", \"input\": " + json_string(run.input) +
                    ", \"output\": " + json_string(run.output) + ", \"reference\": " +
                    optional_string(run.reference) + ", \"report\": " + optional_string(run.report) +
                    ", \"mode\": " + json_string(run.mode) + ", \"ops\": " + json_string(run.ops) +
                    ", \"max_steps\": " + integer(run.max_steps) + ", \"threads\": " + integer(run.threads) +
                    ", \"keep_surface\": " + (run.keep_surface ? "true" : "false") + ", \"options\": [";
    for (size_t k = 0; k < run.options.size(); ++k) s += (k ? ", " : "") + json_string(run.options[k]);
    s += "], \"parameters\": {";
    for (size_t k = 0; k < run.parameters.size(); ++k)
        s += (k ? ", " : "") + json_string(run.parameters[k].first) + ": " + run.parameters[k].second;
    s += "}, \"steps\": " + integer(static_cast<int64_t>(run.steps.size())) +
         ", \"converged\": " + (run.converged ? "true" : "false") + ", \"flips\": " + integer(run.flips) +
         ", \"vertices_inserted\": " + integer(run.vertices_inserted) +
         ", \"edges_collapsed\": " + integer(run.edges_collapsed) + ", \"seconds\": {";
    for (int p = 0; p < static_cast<int>(Phase::Count); ++p)
        s += std::string(p ? ", " : "") + "\"" + kSecondsKeys[p] + "\": " + json_number(run.seconds[p]);
    s += ", \"total\": " + json_number(run.seconds_total) + "}, \"quality_before\": {" +
         quality_json_members(run.before, false) + "}, \"quality_after\": {" +
         quality_json_members(run.after, false) + "}";
    if (run.recovery)
        s += ", \"recovery_before\": " + recovery_json(run.recovery_before) +
             ", \"recovery_after\": " + recovery_json(run.recovery_after);
    s += ", \"per_step\": [";
    for (size_t k = 0; k < run.steps.size(); ++k) s += (k ? ", " : "") + step_json(run.steps[k]);
    return s + "]}";
}

namespace {

// The record from the JSON of run_json; false (with `error`) when `root` is
// not such an object.
bool run_from_json(const JsonValue& root, RunRecord& run, std::string& error) {
    const JsonValue* per_step = root.get("per_step");
    if (root.type != JsonValue::Type::Object || !root.get("mode") || !root.get("mode")->is_string() || !per_step ||
        per_step->type != JsonValue::Type::Array) {
        error = "not the JSON of bodt improve --json (it has no \"mode\" or \"per_step\")";
        return false;
    }
    run = RunRecord();
    run.version = string_of(root.get("version"));
    run.input = string_of(root.get("input"));
    run.output = string_of(root.get("output"));
    run.reference = string_of(root.get("reference"));
    run.report = string_of(root.get("report"));
    run.mode = string_of(root.get("mode"));
    run.ops = string_of(root.get("ops"));
    run.max_steps = integer_of<int32_t>(root.get("max_steps"));
    run.threads = integer_of<int32_t>(root.get("threads"));
    run.keep_surface = bool_of(root.get("keep_surface"));
    if (const JsonValue* o = root.get("options"); o && o->type == JsonValue::Type::Array)
        for (const JsonValue& v : o->items)
            if (v.is_string()) run.options.push_back(v.text);
    if (const JsonValue* p = root.get("parameters"); p && p->type == JsonValue::Type::Object)
        for (const auto& m : p->members)
            if (m.second.is_number()) run.parameters.emplace_back(m.first, m.second.text);
    for (const JsonValue& v : per_step->items) {
        StepFigures f;
        bodt_step_report& r = f.report;
        r.size = sizeof r;
        r.step = integer_of<int32_t>(v.get("step"));
        f.seconds = number_of(v.get("seconds"));
        r.min_dihedral = number_of(v.get("min_dihedral"));
        r.max_dihedral = number_of(v.get("max_dihedral"));
        r.min_stretch = number_of(v.get("min_stretch"));
        r.vertices_moved = integer_of<int32_t>(v.get("vertices_moved"));
        r.moves_rejected = integer_of<int32_t>(v.get("moves_rejected"));
        r.moves_shortened = integer_of<int32_t>(v.get("moves_shortened"));
        r.not_positive_definite = integer_of<int32_t>(v.get("not_positive_definite"));
        r.max_move = number_of(v.get("max_move"));
        r.flips = integer_of<int32_t>(v.get("flips"));
        r.vertices_inserted = integer_of<int32_t>(v.get("vertices_inserted"));
        r.edges_collapsed = integer_of<int32_t>(v.get("edges_collapsed"));
        run.steps.push_back(f);
    }
    run.flips = integer_of<int64_t>(root.get("flips"));
    run.vertices_inserted = integer_of<int64_t>(root.get("vertices_inserted"));
    run.edges_collapsed = integer_of<int64_t>(root.get("edges_collapsed"));
    run.converged = bool_of(root.get("converged"));
    if (const JsonValue* t = root.get("seconds")) {
        for (int p = 0; p < static_cast<int>(Phase::Count); ++p) run.seconds[p] = number_of(t->get(kSecondsKeys[p]));
        run.seconds_total = number_of(t->get("total"));
    }
    run.before = quality_of(root.get("quality_before"));
    run.after = quality_of(root.get("quality_after"));
    run.recovery = root.get("recovery_before") != nullptr;
    run.recovery_before = recovery_of(root.get("recovery_before"));
    run.recovery_after = recovery_of(root.get("recovery_after"));
    return true;
}

}  // namespace

bool read_run(const std::string& path, RunRecord& run, std::string& error) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        error = std::strerror(errno);
        return false;
    }
    std::ostringstream text;
    text << file.rdbuf();
    JsonValue root;
    return parse_json(text.str(), root, error) && run_from_json(root, run, error);
}

}  // namespace bodt_cli
