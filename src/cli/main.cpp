// bodt: the command-line face of libbodt.  It uses the public C API only.
// Subcommands: improve, quality, compare, convert, report, help; see
// `bodt --help` (src/cli/help.cpp) for the manual.
#include "bodt.h"
#include "cli/args.hpp"
#include "cli/compare.hpp"
#include "cli/help.hpp"
#include "cli/progress.hpp"
#include "cli/quality_output.hpp"
#include "cli/report.hpp"
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

// `flags`: bodt_create_flag bits for a mesh file.
bool load(const std::string& path, bodt_mesh** mesh, uint32_t flags = BODT_CREATE_DEFAULT) {
    std::string message;
    int status;
    if (is_surface_path(path)) {
        status = tetrahedralize_surface(path, mesh, message);
    } else {
        status = bodt_mesh_read_format(path.c_str(), BODT_FORMAT_AUTO, flags, mesh);
        if (status != BODT_OK) message = bodt_mesh_last_error(nullptr);
    }
    if (status != BODT_OK) {
        std::fprintf(stderr, "bodt: %s: %s\n", bodt_status_string(status), message.c_str());
        return false;
    }
    return true;
}

// Writes `mesh` to `path` in `format`; false (with the message on stderr)
// when it cannot.
bool save(const bodt_mesh* mesh, const std::string& path, int format) {
    const int status = bodt_mesh_write_format(mesh, path.c_str(), format);
    if (status != BODT_OK) {
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

// --verbose: the mode and every parameter as the run will use them.
void print_parameters(const bodt_mesh* mesh) {
    int mode = 0;
    bodt_get_mode(mesh, &mode);
    std::fprintf(stderr, "mode %s\n", mode_name(mode));
    for (const ParamInfo& p : param_table()) {
        if (p.is_int) {
            int32_t v = 0;
            if (bodt_get_param_int(mesh, p.key, &v) == BODT_OK) std::fprintf(stderr, "  %s = %d\n", p.name, v);
        } else {
            double v = 0.0;
            if (bodt_get_param_double(mesh, p.key, &v) != BODT_OK) continue;
            // The shortest of 15 and 17 digits that reads back as v.
            char text[40];
            std::snprintf(text, sizeof text, "%.15g", v);
            if (std::strtod(text, nullptr) != v) std::snprintf(text, sizeof text, "%.17g", v);
            std::fprintf(stderr, "  %s = %s\n", p.name, text);
        }
    }
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
                             {"--reference", nullptr, true},
                             {"--format", nullptr, true}},
                            parsed, verbosity);
    if (early >= 0) return early;
    std::string error;
    int mode = BODT_MODE_BODT;
    int32_t iterations = 20;
    int32_t ops = BODT_OPS_MODE_DEFAULT;
    int format = BODT_FORMAT_AUTO;
    if (const std::string* v = parsed.last("--mode"); v && !parse_mode(*v, mode, error))
        return usage_error("improve", error);
    if (const std::string* v = parsed.last("--iterations"); v && !parse_iterations(*v, iterations, error))
        return usage_error("improve", error);
    if (const std::string* v = parsed.last("--ops"); v && !parse_ops(*v, ops, error))
        return usage_error("improve", error);
    if (const std::string* v = parsed.last("--format"); v && !parse_format(*v, format, error))
        return usage_error("improve", error);
    std::vector<ParamSetting> params;
    for (const std::string& text : parsed.all("--param")) {
        ParamSetting p;
        if (!parse_param(text, p, error)) return usage_error("improve", error);
        params.push_back(p);
    }
    const std::string reference = parsed.last("--reference") ? *parsed.last("--reference") : "";
    if (parsed.positional.size() != 2) return usage_error("improve", "give IN and OUT");
    const std::string& in = parsed.positional[0];
    const std::string& out = parsed.positional[1];
    const bool phased = mode == BODT_MODE_PHASED_ODT;
    if (!reference.empty() && !phased) return usage_error("improve", "--reference goes with --mode phased");

    Mesh mesh;
    // A deformed mesh may come with inverted tets; the phased mode removes them.
    if (!load(in, &mesh.m, phased ? BODT_CREATE_ACCEPT_INVERTED : BODT_CREATE_DEFAULT)) return kInput;
    if (!reference.empty()) {
        Mesh original;
        if (!load(reference, &original.m)) return kInput;
        const int status = bodt_set_reference_mesh(mesh.m, original.m);
        if (status != BODT_OK) {
            std::fprintf(stderr, "bodt: --reference %s: %s: %s\n", reference.c_str(), bodt_status_string(status),
                         bodt_mesh_last_error(mesh.m));
            return kInput;
        }
    }
    const bodt_quality before = measure(mesh.m);
    const bodt_recovery_error errors_before = recovery_error(mesh.m);
    int status = bodt_set_mode(mesh.m, mode);
    if (status == BODT_OK) status = bodt_set_param_int(mesh.m, BODT_PARAM_OPS, ops);
    if (status == BODT_OK && parsed.has("--keep-surface"))
        status = bodt_set_param_int(mesh.m, BODT_PARAM_KEEP_SURFACE, 1);
    if (status != BODT_OK) {
        std::fprintf(stderr, "bodt: improve: %s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh.m));
        return kImprove;
    }
    if (!apply_params(mesh.m, params, error)) return usage_error("improve", error);
    if (verbosity == Verbosity::Verbose) print_parameters(mesh.m);

    Progress progress(verbosity, iterations);
    status = bodt_run(mesh.m, iterations, Progress::callback, &progress);
    progress.finish();
    if (status != BODT_OK) {
        std::fprintf(stderr, "bodt: improve: %s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh.m));
        return kImprove;
    }
    if (verbosity != Verbosity::Quiet) {
        print_table(&before, measure(mesh.m));
        if (phased) print_recovery(errors_before, recovery_error(mesh.m));
        std::printf("%d steps: %lld flips, %lld vertices inserted, %lld edges collapsed\n", progress.steps,
                    static_cast<long long>(progress.flips), static_cast<long long>(progress.inserted),
                    static_cast<long long>(progress.collapsed));
        std::fflush(stdout);
    }
    if (!save(mesh.m, out, format)) return kOutput;
    if (verbosity != Verbosity::Quiet) std::printf("wrote %s\n", out.c_str());
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
    if (!load(path, &mesh.m)) return kInput;
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
    if (!load(parsed.positional[0], &original.m)) return kInput;
    if (!load(parsed.positional[1], &improved.m)) return kInput;
    return -1;
}

int cmd_compare(const std::vector<std::string>& args) {
    ParsedArgs parsed;
    Verbosity verbosity;
    const int early = begin("compare", args, {{"--json", nullptr, false}}, parsed, verbosity);
    if (early >= 0) return early;
    Mesh original, improved;
    if (const int code = load_pair("compare", parsed, original, improved); code >= 0) return code;
    Comparison c;
    std::string error;
    if (!compare_meshes(original.m, improved.m, c, error)) {
        std::fprintf(stderr, "bodt: compare: %s\n", error.c_str());
        return kInput;
    }
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
    Mesh mesh;
    if (!load(parsed.positional[0], &mesh.m)) return kInput;
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
    const int early = begin("report", args, {{"--output", "-o", true}}, parsed, verbosity);
    if (early >= 0) return early;
    const std::string* out = parsed.last("--output");
    if (!out || out->empty()) return usage_error("report", "give the HTML file to write: -o REPORT.html");
    Mesh original, improved;
    if (const int code = load_pair("report", parsed, original, improved); code >= 0) return code;
    std::string error;
    if (!write_report(original.m, improved.m, parsed.positional[0], parsed.positional[1], *out, error)) {
        std::fprintf(stderr, "bodt: report: %s\n", error.c_str());
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
