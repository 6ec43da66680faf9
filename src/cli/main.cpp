// bodt: the command-line face of libbodt.  It uses the public C API only.
#include "bodt.h"
#include "cli/surface_input.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

// Exit codes (documented in --help).
enum Exit { kOk = 0, kUsage = 1, kInput = 2, kImprove = 3, kOutput = 4 };

const char* kUsageText =
    "usage: bodt <command> [options]\n"
    "\n"
    "Improve the quality of tetrahedral meshes for finite-element analysis.\n"
    "\n"
    "commands:\n"
    "  improve IN OUT [--mode MODE] [--iterations N] [--ops LIST] [--keep-surface]\n"
    "                [--reference ORIGINAL]\n"
    "      Read IN, improve it, write OUT, and print the quality before and after.\n"
    "      IN may be a tet mesh (.mesh, .node, .ele) or, when bodt is built with\n"
    "      TetGen, a closed surface (.off, .stl, .ply) or PLC (.poly), which is first\n"
    "      tetrahedralized like `tetgen -p` (no quality refinement).\n"
    "      --mode MODE       bodt (default): B-ODT, paper 000 Algorithms 1-3: ODT\n"
    "                          inside, boundary vertices in their tangent plane,\n"
    "                          feature-line vertices along the line, corners fixed\n"
    "                        bodt-basic: ODT inside, every boundary vertex in its\n"
    "                          tangent plane (Algorithms 1 and 2)\n"
    "                        odt: interior vertices only (Algorithm 1)\n"
    "                        laplace: interior vertices to their neighbours' mean\n"
    "                        opt-weighted: paper 001: interior vertices of poor\n"
    "                          tets minimise a sum of inverse stretch, boundary\n"
    "                          tets weighted by C (quasi-Newton); poor tets whose\n"
    "                          vertices are all on the boundary are swapped away;\n"
    "                          the boundary is kept as it is\n"
    "                        phased: paper 002, for a mesh deformed by a shape\n"
    "                          change (IN may hold inverted tets): inverted and\n"
    "                          degenerate tets removed, density and accuracy\n"
    "                          of ORIGINAL recovered by edge splits and\n"
    "                          collapses, then ODT on the sharp edges, the\n"
    "                          surfaces (fitted planes and cylinders) and the\n"
    "                          inside, in that order\n"
    "                      Boundary moves keep the volume (phased: the fitted\n"
    "                      shapes); no mode inverts a tet.\n"
    "      --iterations N    at most N improvement steps (default 20); stops\n"
    "                        earlier when the vertices stop moving and the\n"
    "                        connectivity stops changing\n"
    "      --ops LIST        what a step does, comma-separated:\n"
    "                          smooth: move vertices (the mode's smoothing)\n"
    "                          flip: edge removal and 2-3 flips around bad tets\n"
    "                          insert: split spades, caps and slivers\n"
    "                          collapse: collapse the short edge of bad tets\n"
    "                        or default: smooth,flip,insert in mode bodt,\n"
    "                        smooth,flip in opt-weighted (flip: around poor tets\n"
    "                        whose vertices are all on the boundary), smooth in\n"
    "                        the other modes.  A change of connectivity is\n"
    "                        kept only if it makes the worst tets it touches\n"
    "                        better; the surface keeps its shape.\n"
    "      --keep-surface    leave every boundary and interface triangle as it is\n"
    "                        (odt, laplace and opt-weighted always do)\n"
    "      --reference ORIGINAL  (phased) the mesh before the deformation, with\n"
    "                        the same vertices: its density and geometric\n"
    "                        accuracy are recovered; the density and geometric\n"
    "                        errors are printed before and after\n"
    "      The summary gives the steps done and the flips, inserted vertices and\n"
    "      collapsed edges in all.\n"
    "  quality MESH [--json]\n"
    "      Print the quality of MESH: dihedral angles, stretch, inverted tets,\n"
    "      volume, counts.  --json prints one JSON object.\n"
    "\n"
    "  --version   print the library version\n"
    "  --help      print this text\n"
    "\n"
    "Mesh files: Medit .mesh (ASCII; tet refs are regions, triangle refs are\n"
    "face markers, RequiredVertices and Corners are fixed), TetGen .node/.ele\n"
    "(+ .face; 0- or 1-based).  A TetGen mesh whose tets are all negatively\n"
    "oriented is read as such; files are written positively oriented.\n"
    "\n"
    "exit status: 0 success, 1 usage error, 2 the input could not be read or is\n"
    "not a valid mesh, 3 the improvement failed, 4 the output could not be written.\n";

int usage_error(const std::string& message) {
    std::fprintf(stderr, "bodt: %s\n(see bodt --help)\n", message.c_str());
    return kUsage;
}

// `flags`: bodt_create_flag bits for a mesh file.
bool load(const std::string& path, bodt_mesh** mesh, uint32_t flags = BODT_CREATE_DEFAULT) {
    std::string message;
    int status;
    if (bodt_cli::is_surface_path(path)) {
        status = bodt_cli::tetrahedralize_surface(path, mesh, message);
    } else {
        status = bodt_mesh_read_ex(path.c_str(), flags, mesh);
        if (status != BODT_OK) message = bodt_mesh_last_error(nullptr);
    }
    if (status != BODT_OK) {
        std::fprintf(stderr, "bodt: %s: %s\n", bodt_status_string(status), message.c_str());
        return false;
    }
    return true;
}

bodt_quality measure(const bodt_mesh* mesh) {
    bodt_quality q;
    std::memset(&q, 0, sizeof q);
    q.size = sizeof q;
    bodt_mesh_quality(mesh, &q);
    return q;
}

void print_json(const char* path, const bodt_quality& q) {
    std::printf("{\"mesh\": \"");
    for (const char* c = path; *c; ++c) {
        if (*c == '"' || *c == '\\') std::putchar('\\');
        std::putchar(*c);
    }
    std::printf(
        "\", \"vertices\": %d, \"tets\": %d, \"boundary_faces\": %d, \"unused_vertices\": %d, "
        "\"inverted\": %d, \"volume\": %.17g, \"min_dihedral\": %.6f, \"max_dihedral\": %.6f, "
        "\"mean_dihedral\": %.6f, \"stretch_min\": %.6f, \"stretch_mean\": %.6f, \"dihedral_histogram\": [",
        q.num_vertices, q.num_tets, q.num_boundary_faces, q.num_unused_vertices, q.num_inverted, q.volume,
        q.min_dihedral, q.max_dihedral, q.mean_dihedral, q.min_stretch, q.mean_stretch);
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b)
        std::printf("%s%lld", b ? ", " : "", static_cast<long long>(q.dihedral_histogram[b]));
    std::printf("]}\n");
}

void print_table(const bodt_quality* before, const bodt_quality& after) {
    const auto row_i = [&](const char* name, int32_t bodt_quality::*field) {
        if (before) std::printf("%-16s %14d %14d\n", name, before->*field, after.*field);
        else std::printf("%-16s %14d\n", name, after.*field);
    };
    const auto row_d = [&](const char* name, double bodt_quality::*field, const char* fmt) {
        char a[32], b[32];
        std::snprintf(b, sizeof b, fmt, after.*field);
        if (before) {
            std::snprintf(a, sizeof a, fmt, before->*field);
            std::printf("%-16s %14s %14s\n", name, a, b);
        } else {
            std::printf("%-16s %14s\n", name, b);
        }
    };
    if (before) std::printf("%-16s %14s %14s\n", "", "before", "after");
    row_i("vertices", &bodt_quality::num_vertices);
    row_i("tets", &bodt_quality::num_tets);
    row_i("boundary faces", &bodt_quality::num_boundary_faces);
    row_d("min dihedral", &bodt_quality::min_dihedral, "%.3f");
    row_d("max dihedral", &bodt_quality::max_dihedral, "%.3f");
    row_d("mean dihedral", &bodt_quality::mean_dihedral, "%.3f");
    row_d("min stretch", &bodt_quality::min_stretch, "%.5f");
    row_d("mean stretch", &bodt_quality::mean_stretch, "%.5f");
    row_i("inverted", &bodt_quality::num_inverted);
    row_d("volume", &bodt_quality::volume, "%.8g");
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
        if (any) std::printf("%-16s %14.5g %14.5g\n", name, a, b);
        else std::printf("%-16s %14s %14s\n", name, "-", "-");
    };
    row("density err mean", before.density_mean, after.density_mean, before.density_edges > 0);
    row("density err max", before.density_max, after.density_max, before.density_edges > 0);
    row("geom. err mean", before.geometric_mean, after.geometric_mean, before.geometric_edges > 0);
    row("geom. err max", before.geometric_max, after.geometric_max, before.geometric_edges > 0);
}

int cmd_quality(const std::vector<std::string>& args) {
    std::string path;
    bool json = false;
    for (const std::string& a : args) {
        if (a == "--json") json = true;
        else if (a.rfind("--", 0) == 0) return usage_error("quality: unknown option " + a);
        else if (path.empty()) path = a;
        else return usage_error("quality takes one mesh");
    }
    if (path.empty()) return usage_error("quality: which mesh?");
    bodt_mesh* mesh = nullptr;
    if (!load(path, &mesh)) return kInput;
    const bodt_quality q = measure(mesh);
    if (json) print_json(path.c_str(), q);
    else print_table(nullptr, q);
    bodt_mesh_destroy(mesh);
    return kOk;
}

struct ModeName {
    const char* name;
    int mode;
};
constexpr ModeName kModes[] = {
    {"bodt", BODT_MODE_BODT}, {"bodt-basic", BODT_MODE_BODT_BASIC}, {"odt", BODT_MODE_ODT},
    {"laplace", BODT_MODE_LAPLACE}, {"opt-weighted", BODT_MODE_OPT_WEIGHTED}, {"phased", BODT_MODE_PHASED_ODT}};

struct OpName {
    const char* name;
    int op;
};
constexpr OpName kOps[] = {
    {"smooth", BODT_OP_SMOOTH}, {"flip", BODT_OP_FLIP}, {"insert", BODT_OP_INSERT}, {"collapse", BODT_OP_COLLAPSE}};

// Parses --ops: "default", or a comma-separated list of kOps names.  False
// (with `error` set) for anything else.
bool parse_ops(const std::string& value, int32_t& ops, std::string& error) {
    if (value == "default") {
        ops = BODT_OPS_MODE_DEFAULT;
        return true;
    }
    ops = 0;
    size_t start = 0;
    while (true) {
        const size_t comma = value.find(',', start);
        const std::string item = value.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const OpName* found = nullptr;
        for (const OpName& o : kOps)
            if (item == o.name) found = &o;
        if (!found) {
            error = "--ops: unknown operation '" + item +
                    "' (known: smooth, flip, insert, collapse, separated by commas; or default alone)";
            return false;
        }
        ops |= found->op;
        if (comma == std::string::npos) return true;
        start = comma + 1;
    }
}

// Totals over the steps of bodt_run, from its callback.
struct RunTotals {
    int32_t steps = 0;
    int64_t flips = 0, inserted = 0, collapsed = 0;
};

int count_step(const bodt_step_report* r, void* user) {
    RunTotals& t = *static_cast<RunTotals*>(user);
    ++t.steps;
    t.flips += r->flips;
    t.inserted += r->vertices_inserted;
    t.collapsed += r->edges_collapsed;
    return 0;
}

int cmd_improve(const std::vector<std::string>& args) {
    std::vector<std::string> files;
    int mode = BODT_MODE_BODT;
    long iterations = 20;
    int32_t ops = BODT_OPS_MODE_DEFAULT;
    bool keep_surface = false;
    std::string reference;
    for (size_t k = 0; k < args.size(); ++k) {
        const std::string& a = args[k];
        if (a == "--keep-surface") {
            keep_surface = true;
        } else if (a == "--mode" || a == "--iterations" || a == "--ops" || a == "--reference") {
            if (k + 1 == args.size()) return usage_error(a + " needs a value");
            const std::string value = args[++k];
            if (a == "--reference") {
                reference = value;
            } else if (a == "--ops") {
                std::string error;
                if (!parse_ops(value, ops, error)) return usage_error(error);
            } else if (a == "--mode") {
                const ModeName* found = nullptr;
                for (const ModeName& m : kModes)
                    if (value == m.name) found = &m;
                if (!found)
                    return usage_error("unknown mode '" + value +
                                       "' (known: bodt, bodt-basic, odt, laplace, opt-weighted, phased)");
                mode = found->mode;
            } else {
                char* end = nullptr;
                iterations = std::strtol(value.c_str(), &end, 10);
                if (*end != '\0' || iterations < 1 || iterations > 1000000)
                    return usage_error("--iterations must be a whole number from 1 to 1000000");
            }
        } else if (a.rfind("--", 0) == 0) {
            return usage_error("improve: unknown option " + a);
        } else {
            files.push_back(a);
        }
    }
    if (files.size() != 2) return usage_error("improve takes IN and OUT");
    const bool phased = mode == BODT_MODE_PHASED_ODT;
    if (!reference.empty() && !phased) return usage_error("--reference goes with --mode phased");
    bodt_mesh* mesh = nullptr;
    // A deformed mesh may come with inverted tets; the phased mode removes them.
    if (!load(files[0], &mesh, phased ? BODT_CREATE_ACCEPT_INVERTED : BODT_CREATE_DEFAULT)) return kInput;
    if (!reference.empty()) {
        bodt_mesh* original = nullptr;
        if (!load(reference, &original)) {
            bodt_mesh_destroy(mesh);
            return kInput;
        }
        const int status = bodt_set_reference_mesh(mesh, original);
        bodt_mesh_destroy(original);
        if (status != BODT_OK) {
            std::fprintf(stderr, "bodt: --reference %s: %s: %s\n", reference.c_str(), bodt_status_string(status),
                         bodt_mesh_last_error(mesh));
            bodt_mesh_destroy(mesh);
            return kInput;
        }
    }
    const bodt_quality before = measure(mesh);
    const bodt_recovery_error errors_before = recovery_error(mesh);
    int status = bodt_set_mode(mesh, mode);
    if (status == BODT_OK) status = bodt_set_param_int(mesh, BODT_PARAM_OPS, ops);
    if (status == BODT_OK && keep_surface) status = bodt_set_param_int(mesh, BODT_PARAM_KEEP_SURFACE, 1);
    RunTotals totals;
    if (status == BODT_OK) status = bodt_run(mesh, static_cast<int32_t>(iterations), count_step, &totals);
    if (status != BODT_OK) {
        std::fprintf(stderr, "bodt: improve: %s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh));
        bodt_mesh_destroy(mesh);
        return kImprove;
    }
    print_table(&before, measure(mesh));
    if (phased) print_recovery(errors_before, recovery_error(mesh));
    std::printf("%d steps: %lld flips, %lld vertices inserted, %lld edges collapsed\n", totals.steps,
                static_cast<long long>(totals.flips), static_cast<long long>(totals.inserted),
                static_cast<long long>(totals.collapsed));
    status = bodt_mesh_write(mesh, files[1].c_str());
    if (status != BODT_OK) {
        std::fprintf(stderr, "bodt: %s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh));
        bodt_mesh_destroy(mesh);
        return kOutput;
    }
    std::printf("wrote %s\n", files[1].c_str());
    bodt_mesh_destroy(mesh);
    return kOk;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage_error("no command");
    const std::string command = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    if (command == "--help" || command == "-h" || command == "help") {
        std::fputs(kUsageText, stdout);
        return kOk;
    }
    if (command == "--version") {
        std::printf("bodt %s\n", bodt_version_string());
        return kOk;
    }
    if (command == "improve") return cmd_improve(args);
    if (command == "quality") return cmd_quality(args);
    return usage_error("unknown command '" + command + "'");
}
