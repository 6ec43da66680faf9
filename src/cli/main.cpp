// bodt: the command-line face of libbodt.  It uses the public C API only.
// Subcommands: improve, quality, compare, convert, report, help; see
// `bodt --help` (src/cli/help.cpp) for the manual.
#include "bodt.h"
#include "cli/args.hpp"
#include "cli/compare.hpp"
#include "cli/help.hpp"
#include "cli/mesh_snapshot.hpp"
#include "cli/output_check.hpp"
#include "cli/progress.hpp"
#include "cli/quality_output.hpp"
#include "cli/report.hpp"
#include "cli/run_record.hpp"
#include "cli/surface_input.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace bodt_cli;

namespace {

// Exit codes (documented in --help: EXIT STATUS).
enum Exit { kOk = 0, kUsage = 1, kInput = 2, kImprove = 3, kOutput = 4 };

int usage_error(const std::string& command, const std::string& message) {
    std::fprintf(stderr, "bodt%s%s: %s\n(see bodt help%s%s)\n", command.empty() ? "" : " ", command.c_str(),
                 message.c_str(), command.empty() ? "" : " ", command.c_str());
    return kUsage;
}

// An output that cannot be written, found before any input is read.
int output_error(const std::string& command, const std::string& message) {
    std::fprintf(stderr, "bodt %s: %s\n", command.c_str(), message.c_str());
    return kOutput;
}

// The library's message for a mesh it refused, for a command-line user: the
// C flag that accepts inverted tets is not theirs to set, so the clause
// naming it gives way to `inverted_hint` (what the command offers instead).
std::string for_the_command_line(int status, std::string message, const char* inverted_hint) {
    if (status != BODT_ERR_BAD_MESH || message.find("inverted") == std::string::npos) return message;
    const size_t flag = message.find("BODT_CREATE_ACCEPT_INVERTED");
    if (flag != std::string::npos) {
        const size_t clause = message.rfind("; ", flag);
        message.erase(clause != std::string::npos ? clause : flag);
    }
    return message + (inverted_hint ? std::string("\nbodt: ") + inverted_hint : "");
}

// `flags`: bodt_create_flag bits for a mesh file, which is read in its own
// numbering (BODT_CREATE_FILE_BASE), so that every index the command shows,
// in messages and in the report, is the one the file has; `inverted_hint`:
// see for_the_command_line; `progress`: ended before an error is printed.
bool load(const std::string& path, bodt_mesh** mesh, uint32_t flags, const char* inverted_hint = nullptr,
          Progress* progress = nullptr) {
    std::string message;
    int status;
    if (is_surface_path(path)) {
        status = tetrahedralize_surface(path, mesh, message);
    } else {
        status = bodt_mesh_read_format(path.c_str(), BODT_FORMAT_AUTO, flags | BODT_CREATE_FILE_BASE, mesh);
        if (status != BODT_OK) message = bodt_mesh_last_error(nullptr);
    }
    if (status != BODT_OK) {
        if (progress) progress->finish();
        std::fprintf(stderr, "bodt: %s: %s\n", bodt_status_string(status),
                     for_the_command_line(status, message, inverted_hint).c_str());
        return false;
    }
    return true;
}

// Commands that only look at a mesh (quality, compare, convert, report) read
// it as it is, inverted tets and all: they count them.
constexpr uint32_t kAsItIs = BODT_CREATE_ACCEPT_INVERTED;

// Writes `mesh` to `path` in `format`; false (with the message on stderr,
// after `progress` is ended) when it cannot.
bool save(const bodt_mesh* mesh, const std::string& path, int format, Progress* progress = nullptr) {
    const int status = bodt_mesh_write_format(mesh, path.c_str(), format);
    if (status != BODT_OK) {
        if (progress) progress->finish();
        std::fprintf(stderr, "bodt: %s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh));
        return false;
    }
    return true;
}

// Owns a handle.
struct Mesh {
    bodt_mesh* m = nullptr;
    Mesh() = default;
    Mesh(const Mesh&) = delete;
    Mesh& operator=(const Mesh&) = delete;
    ~Mesh() { bodt_mesh_destroy(m); }
};

// The front matter of every command: parse, --help, verbosity.  Returns -1
// to go on, else the exit code.
int begin(const char* command, const std::vector<std::string>& args, const std::vector<OptionSpec>& spec,
          ParsedArgs& parsed, Verbosity& verbosity) {
    std::string error;
    if (!parse_args(args, spec, parsed, error)) return usage_error(command, error);
    if (parsed.has("--help")) {
        print_help(command);
        return kOk;
    }
    if (!verbosity_of(parsed, verbosity, error)) return usage_error(command, error);
    return -1;
}

bodt_recovery_error recovery_error(const bodt_mesh* mesh) {
    bodt_recovery_error e;
    std::memset(&e, 0, sizeof e);
    e.size = sizeof e;
    bodt_mesh_recovery_error(mesh, &e);
    return e;
}

// Paper 002's measures (eq. 4.1 and sec. 3.3), in the table's columns.
void print_recovery(const bodt_recovery_error& before, const bodt_recovery_error& after) {
    const auto row = [](const char* name, double a, double b, bool any) {
        char x[32] = "-", y[32] = "-";
        if (any) {
            std::snprintf(x, sizeof x, "%.5g", a);
            std::snprintf(y, sizeof y, "%.5g", b);
        }
        print_row(name, x, y);
    };
    row("density err mean", before.density_mean, after.density_mean, before.density_edges > 0);
    row("density err max", before.density_max, after.density_max, before.density_edges > 0);
    row("geom. err mean", before.geometric_mean, after.geometric_mean, before.geometric_edges > 0);
    row("geom. err max", before.geometric_max, after.geometric_max, before.geometric_edges > 0);
}

// Every parameter as the run will use them, by param_table's names; reals
// as the shortest of 15 and 17 digits that reads back as the value.
std::vector<std::pair<std::string, std::string>> parameters_in_effect(const bodt_mesh* mesh) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const ParamInfo& p : param_table()) {
        if (p.is_int) {
            int32_t v = 0;
            if (bodt_get_param_int(mesh, p.key, &v) == BODT_OK) out.emplace_back(p.name, std::to_string(v));
        } else {
            double v = 0.0;
            if (bodt_get_param_double(mesh, p.key, &v) == BODT_OK) out.emplace_back(p.name, json_number(v));
        }
    }
    return out;
}

// What improve sets on a mesh, from its options.
struct Settings {
    int mode = BODT_MODE_BODT;
    int32_t ops = BODT_OPS_MODE_DEFAULT;
    bool keep_surface = false;
    bool threads_given = false;
    int32_t threads = 1;
    std::vector<ParamSetting> params;  // applied last: --param ops=N wins over --ops
};

// Sets `s` on `mesh`.  A value the library refuses is a usage error (1),
// anything else it refuses a failed improvement (3); -1 when all is set.
int apply_settings(bodt_mesh* mesh, const Settings& s, std::string& error) {
    int status = bodt_set_mode(mesh, s.mode);
    if (status == BODT_OK) status = bodt_set_param_int(mesh, BODT_PARAM_OPS, s.ops);
    if (status == BODT_OK && s.keep_surface) status = bodt_set_param_int(mesh, BODT_PARAM_KEEP_SURFACE, 1);
    if (status != BODT_OK) {
        error = std::string(bodt_status_string(status)) + ": " + bodt_mesh_last_error(mesh);
        return kImprove;
    }
    if (s.threads_given && bodt_set_param_int(mesh, BODT_PARAM_THREADS, s.threads) != BODT_OK) {
        error = std::string("--threads: ") + bodt_mesh_last_error(mesh);
        return kUsage;
    }
    if (!apply_params(mesh, s.params, error)) return kUsage;
    int32_t keep = 0;
    bodt_get_param_int(mesh, BODT_PARAM_KEEP_SURFACE, &keep);
    if (s.mode == BODT_MODE_PHASED_ODT && keep != 0) {
        error = "--mode phased recovers the surface: it does not go with --keep-surface (or keep_surface=1)";
        return kUsage;
    }
    return -1;
}

// The settings tried on a mesh of one tet, so that a refused value is found
// before a long read of the input.  Returns -1 or the exit code.
int check_settings(const Settings& s, std::string& error) {
    const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int32_t tet[4] = {0, 1, 2, 3};
    Mesh probe;
    if (bodt_mesh_create(4, xyz, 1, tet, 0, &probe.m) != BODT_OK) return -1;  // the real mesh will say
    return apply_settings(probe.m, s, error);
}

// The options of an improve command line that made its result, as typed
// (for the record of the run).
std::vector<std::string> run_options(const ParsedArgs& parsed) {
    std::vector<std::string> out;
    for (const auto& o : parsed.options) {
        if (o.first == "--json" || o.first == "--report" || o.first == "--quiet" || o.first == "--verbose") continue;
        const bool plain = o.second.find_first_of(" \t'\"") == std::string::npos;
        out.push_back(o.first + (o.second.empty() ? "" : " " + (plain ? o.second : "'" + o.second + "'")));
    }
    return out;
}

int cmd_improve(const std::vector<std::string>& args) {
    ParsedArgs parsed;
    Verbosity verbosity;
    const int early = begin("improve", args,
                            {{"--mode", nullptr, true},
                             {"--iterations", nullptr, true},
                             {"--ops", nullptr, true},
                             {"--keep-surface", nullptr, false},
                             {"--param", nullptr, true},
                             {"--threads", nullptr, true},
                             {"--reference", nullptr, true},
                             {"--format", nullptr, true},
                             {"--json", nullptr, false},
                             {"--report", nullptr, true}},
                            parsed, verbosity);
    if (early >= 0) return early;
    std::string error;
    Settings settings;
    int32_t iterations = 20;
    int format = BODT_FORMAT_AUTO;
    if (const std::string* v = parsed.last("--mode"); v && !parse_mode(*v, settings.mode, error))
        return usage_error("improve", error);
    if (const std::string* v = parsed.last("--iterations"); v && !parse_iterations(*v, iterations, error))
        return usage_error("improve", error);
    if (const std::string* v = parsed.last("--ops"); v && !parse_ops(*v, settings.ops, error))
        return usage_error("improve", error);
    if (const std::string* v = parsed.last("--format"); v && !parse_format(*v, format, error))
        return usage_error("improve", error);
    if (const std::string* v = parsed.last("--threads")) {
        if (!parse_threads(*v, settings.threads, error)) return usage_error("improve", error);
        settings.threads_given = true;
    }
    settings.keep_surface = parsed.has("--keep-surface");
    for (const std::string& text : parsed.all("--param")) {
        ParamSetting p;
        if (!parse_param(text, p, error)) return usage_error("improve", error);
        settings.params.push_back(p);
    }
    const std::string reference = parsed.last("--reference") ? *parsed.last("--reference") : "";
    const std::string report = parsed.last("--report") ? *parsed.last("--report") : "";
    if (parsed.has("--report") && report.empty()) return usage_error("improve", "--report needs a file name");
    if (parsed.positional.size() != 2) return usage_error("improve", "give IN and OUT");
    const std::string& in = parsed.positional[0];
    const std::string& out = parsed.positional[1];
    const bool phased = settings.mode == BODT_MODE_PHASED_ODT;
    if (!reference.empty() && !phased) return usage_error("improve", "--reference goes with --mode phased");
    if (const int code = check_settings(settings, error); code == kUsage) {
        return usage_error("improve", error);
    } else if (code >= 0) {
        std::fprintf(stderr, "bodt: improve: %s\n", error.c_str());
        return code;
    }
    // The outputs, before the input is even opened.
    if (!check_mesh_output(out, format, error)) return output_error("improve", error);
    if (!report.empty() && !writable(report, false, error)) return output_error("improve", "--report: " + error);

    Progress progress(verbosity);
    Mesh mesh;
    progress.phase(Phase::Reading, "reading " + in);
    // A deformed mesh may come with inverted tets; the phased mode removes them.
    if (!load(in, &mesh.m, phased ? BODT_CREATE_ACCEPT_INVERTED : BODT_CREATE_DEFAULT,
              "--mode phased reads a mesh with inverted tets and untangles it (bodt improve IN OUT --mode phased)",
              &progress))
        return kInput;
    if (!reference.empty()) {
        progress.phase(Phase::Reading, "reading " + reference);
        Mesh original;
        if (!load(reference, &original.m, BODT_CREATE_DEFAULT, nullptr, &progress)) return kInput;
        const int status = bodt_set_reference_mesh(mesh.m, original.m);
        if (status != BODT_OK) {
            progress.finish();
            std::fprintf(stderr, "bodt: --reference %s: %s: %s\n", reference.c_str(), bodt_status_string(status),
                         bodt_mesh_last_error(mesh.m));
            return kInput;
        }
    }
    progress.phase(Phase::SettingUp, "setting up");
    RunRecord run;
    MeshSnapshot original;
    if (!report.empty() && !take_snapshot(mesh.m, original, error)) {
        progress.finish();
        std::fprintf(stderr, "bodt: improve: %s\n", error.c_str());
        return kImprove;
    }
    run.before = measure(mesh.m);
    if (phased) run.recovery_before = recovery_error(mesh.m);
    if (const int code = apply_settings(mesh.m, settings, error); code >= 0) {
        progress.finish();
        if (code == kUsage) return usage_error("improve", error);
        std::fprintf(stderr, "bodt: improve: %s\n", error.c_str());
        return code;
    }
    run.parameters = parameters_in_effect(mesh.m);
    if (verbosity == Verbosity::Verbose) {
        std::fprintf(stderr, "mode %s\n", mode_name(settings.mode));
        for (const auto& p : run.parameters) std::fprintf(stderr, "  %s = %s\n", p.first.c_str(), p.second.c_str());
    }

    progress.start_steps(iterations);
    int status = bodt_run(mesh.m, iterations, Progress::callback, &progress);
    if (status != BODT_OK) {
        progress.finish();
        std::fprintf(stderr, "bodt: improve: %s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh.m));
        return kImprove;
    }
    progress.phase(Phase::Writing, "writing " + out);
    if (!save(mesh.m, out, format, &progress)) return kOutput;

    run.version = bodt_version_string();
    run.input = in;
    run.output = out;
    run.reference = reference;
    run.report = report;
    run.mode = mode_name(settings.mode);
    int32_t value = 0;
    bodt_get_param_int(mesh.m, BODT_PARAM_OPS, &value);
    run.ops = ops_text(value);
    bodt_get_param_int(mesh.m, BODT_PARAM_THREADS, &run.threads);
    bodt_get_param_int(mesh.m, BODT_PARAM_KEEP_SURFACE, &value);
    run.keep_surface = value != 0;
    run.max_steps = iterations;
    run.options = run_options(parsed);
    run.steps = progress.steps();
    run.flips = progress.flips;
    run.vertices_inserted = progress.inserted;
    run.edges_collapsed = progress.collapsed;
    run.converged = static_cast<int32_t>(run.steps.size()) < iterations;
    run.after = measure(mesh.m);
    run.recovery = phased;
    if (phased) run.recovery_after = recovery_error(mesh.m);
    // The times up to OUT written (the report shows them too).
    for (int p = 0; p < static_cast<int>(Phase::Count); ++p) run.seconds[p] = progress.seconds(Phase(p));
    run.seconds_total = progress.elapsed();
    if (!report.empty()) {
        progress.phase(Phase::Writing, "writing " + report);
        MeshSnapshot improved;
        if (!take_snapshot(mesh.m, improved, error) ||
            !write_report(original, improved, in, out, &run, report, error)) {
            progress.finish();
            std::fprintf(stderr, "bodt: improve: --report: %s\n", error.c_str());
            return kOutput;
        }
    }
    progress.done();

    if (parsed.has("--json")) {
        std::printf("%s\n", run_json(run).c_str());
    } else if (verbosity != Verbosity::Quiet) {
        print_table(&run.before, run.after);
        if (phased) print_recovery(run.recovery_before, run.recovery_after);
        std::printf("%zu steps: %lld flips, %lld vertices inserted, %lld edges collapsed\n", run.steps.size(),
                    static_cast<long long>(run.flips), static_cast<long long>(run.vertices_inserted),
                    static_cast<long long>(run.edges_collapsed));
        std::printf("wrote %s\n", out.c_str());
        if (!report.empty()) std::printf("wrote %s\n", report.c_str());
    }
    return kOk;
}

int cmd_quality(const std::vector<std::string>& args) {
    ParsedArgs parsed;
    Verbosity verbosity;
    const int early = begin("quality", args, {{"--json", nullptr, false}, {"--histogram", nullptr, false}}, parsed,
                            verbosity);
    if (early >= 0) return early;
    if (parsed.positional.size() != 1) return usage_error("quality", "give one mesh");
    const std::string& path = parsed.positional[0];
    Mesh mesh;
    if (!load(path, &mesh.m, kAsItIs)) return kInput;
    const bodt_quality q = measure(mesh.m);
    const bool histogram = parsed.has("--histogram");
    if (parsed.has("--json")) {
        std::printf("{\"mesh\": %s, %s}\n", json_string(path).c_str(), quality_json_members(q, histogram).c_str());
    } else {
        print_table(nullptr, q);
        if (histogram) {
            std::printf("\n");
            print_histogram(q);
        }
    }
    return kOk;
}

// Reads the two meshes ORIGINAL IMPROVED of compare and report.
int load_pair(const char* command, const ParsedArgs& parsed, Mesh& original, Mesh& improved) {
    if (parsed.positional.size() != 2) return usage_error(command, "give ORIGINAL and IMPROVED");
    if (!load(parsed.positional[0], &original.m, kAsItIs)) return kInput;
    if (!load(parsed.positional[1], &improved.m, kAsItIs)) return kInput;
    return -1;
}

// Snapshots of both meshes; false with the message on stderr.
bool snapshots(const char* command, const Mesh& original, const Mesh& improved, MeshSnapshot& a, MeshSnapshot& b) {
    std::string error;
    if (take_snapshot(original.m, a, error) && take_snapshot(improved.m, b, error)) return true;
    std::fprintf(stderr, "bodt %s: %s\n", command, error.c_str());
    return false;
}

int cmd_compare(const std::vector<std::string>& args) {
    ParsedArgs parsed;
    Verbosity verbosity;
    const int early = begin("compare", args, {{"--json", nullptr, false}}, parsed, verbosity);
    if (early >= 0) return early;
    Mesh original, improved;
    if (const int code = load_pair("compare", parsed, original, improved); code >= 0) return code;
    MeshSnapshot a, b;
    if (!snapshots("compare", original, improved, a, b)) return kInput;
    Comparison c;
    compare_meshes(a, b, c);
    print_comparison(c, parsed.positional[0], parsed.positional[1], parsed.has("--json"));
    return kOk;
}

int cmd_convert(const std::vector<std::string>& args) {
    ParsedArgs parsed;
    Verbosity verbosity;
    const int early = begin("convert", args, {{"--format", nullptr, true}}, parsed, verbosity);
    if (early >= 0) return early;
    std::string error;
    int format = BODT_FORMAT_AUTO;
    if (const std::string* v = parsed.last("--format"); v && !parse_format(*v, format, error))
        return usage_error("convert", error);
    if (parsed.positional.size() != 2) return usage_error("convert", "give IN and OUT");
    if (!check_mesh_output(parsed.positional[1], format, error)) return output_error("convert", error);
    Mesh mesh;
    if (!load(parsed.positional[0], &mesh.m, kAsItIs)) return kInput;
    if (!save(mesh.m, parsed.positional[1], format)) return kOutput;
    if (verbosity != Verbosity::Quiet) {
        const bodt_quality q = measure(mesh.m);
        std::printf("wrote %s: %d vertices, %d tets, %d boundary faces\n", parsed.positional[1].c_str(),
                    q.num_vertices, q.num_tets, q.num_boundary_faces);
    }
    return kOk;
}

int cmd_report(const std::vector<std::string>& args) {
    ParsedArgs parsed;
    Verbosity verbosity;
    const int early = begin("report", args, {{"--output", "-o", true}, {"--run", nullptr, true}}, parsed, verbosity);
    if (early >= 0) return early;
    const std::string* out = parsed.last("--output");
    if (!out || out->empty()) return usage_error("report", "give the HTML file to write: -o REPORT.html");
    if (parsed.positional.size() != 2) return usage_error("report", "give ORIGINAL and IMPROVED");
    std::string error;
    if (!writable(*out, false, error)) return output_error("report", error);
    RunRecord run;
    const std::string* run_path = parsed.last("--run");
    if (run_path && !read_run(*run_path, run, error)) {
        std::fprintf(stderr, "bodt report: --run %s: %s\n", run_path->c_str(), error.c_str());
        return kInput;
    }
    Mesh original, improved;
    if (const int code = load_pair("report", parsed, original, improved); code >= 0) return code;
    MeshSnapshot a, b;
    if (!snapshots("report", original, improved, a, b)) return kInput;
    if (!write_report(a, b, parsed.positional[0], parsed.positional[1], run_path ? &run : nullptr, *out, error)) {
        std::fprintf(stderr, "bodt report: %s\n", error.c_str());
        return kOutput;
    }
    if (verbosity != Verbosity::Quiet) std::printf("wrote %s\n", out->c_str());
    return kOk;
}

int cmd_help(const std::vector<std::string>& args) {
    if (args.size() > 1) return usage_error("help", "give at most one command");
    const std::string command = args.empty() ? "" : args[0];
    if (!print_help(command)) return usage_error("help", "unknown command '" + command + "'");
    return kOk;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage_error("", "no command");
    const std::string command = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    if (command == "--help" || command == "-h") return cmd_help({});
    if (command == "help") return cmd_help(args);
    if (command == "--version") {
        std::printf("bodt %s\n", bodt_version_string());
        return kOk;
    }
    if (command == "improve") return cmd_improve(args);
    if (command == "quality") return cmd_quality(args);
    if (command == "compare") return cmd_compare(args);
    if (command == "convert") return cmd_convert(args);
    if (command == "report") return cmd_report(args);
    return usage_error("", "unknown command '" + command + "'");
}
