// bodt_bench -- the benchmark of libbodt.
//
// For every case (a tet mesh: TetGen meshes of surfaces, mesh files, a random
// sphere, jittered boxes) and every variant (a mode plus the operations a step
// does, BODT_PARAM_OPS) it creates the mesh through the public C API, sets the
// mode and the operations, runs a fixed number of bodt_step calls, and records
// the quality before and after, the counts before and after (flips and
// insertions change them), the relative Hausdorff distance of the boundary,
// the wall time of the steps alone and the peak memory.  Everything after the
// run is measured on the mesh the handle holds then (its counts, tets and
// boundary), never on the input arrays.  One JSON object per case and variant
// goes to stdout (or --json FILE); a markdown summary to --markdown FILE.  Each
// run happens in a forked child, so a crash or a hang of the library is
// reported and the bench goes on.
//
// Only the public API (bodt.h) is used.  Modes are taken by value (1 laplace,
// 2 odt, 3 bodt-basic, 4 bodt, 5 opt-weighted); a mode or an operation set the
// library refuses is "unsupported".  --param NAME=VALUE sets any other
// parameter (BODT_PARAM_*) for every variant.

#include "bodt.h"

#include "bench_util.hpp"
#include "cases.hpp"
#include "surface_distance.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <regex>
#include <string>
#include <vector>

#ifndef BODT_BENCH_DEFAULT_SHARED
#define BODT_BENCH_DEFAULT_SHARED ""
#endif

namespace {

using bench::Case;
using bench::errmsg;
using bench::fmt;
using bench::json_num;
using bench::json_str;
using bench::PreparedMesh;

// A variant: a mode (by value) and the operations of a step (BODT_PARAM_OPS;
// kOpsDefault leaves the library's default for the mode, which is
// SMOOTH | FLIP | INSERT for BODT_MODE_BODT, SMOOTH | FLIP for
// BODT_MODE_OPT_WEIGHTED and SMOOTH otherwise).
constexpr int kOpsDefault = -1;
struct Variant {
    std::string name;
    int mode;
    int ops;
};
const Variant kVariants[] = {{"laplace", BODT_MODE_LAPLACE, kOpsDefault},
                             {"odt", BODT_MODE_ODT, kOpsDefault},
                             {"bodt-basic", BODT_MODE_BODT_BASIC, kOpsDefault},
                             {"bodt-smooth", BODT_MODE_BODT, BODT_OP_SMOOTH},
                             {"bodt", BODT_MODE_BODT, kOpsDefault},
                             // paper 001: "improved smoothing" alone, and the
                             // "combined" method (smoothing + Algorithm 4 swaps)
                             {"opt-smooth", BODT_MODE_OPT_WEIGHTED, BODT_OP_SMOOTH},
                             {"opt", BODT_MODE_OPT_WEIGHTED, kOpsDefault}};

// The mode's name as the bodt command spells it (bodt improve --mode).
const char* mode_name(int mode) {
    switch (mode) {
        case BODT_MODE_LAPLACE: return "laplace";
        case BODT_MODE_ODT: return "odt";
        case BODT_MODE_BODT_BASIC: return "bodt-basic";
        case BODT_MODE_BODT: return "bodt";
        case BODT_MODE_OPT_WEIGHTED: return "opt-weighted";
        default: return "unknown";
    }
}

// The operations a step does, as the library documents its default.
int effective_ops(int mode, int ops) {
    if (ops != kOpsDefault) return ops;
    switch (mode) {
        case BODT_MODE_BODT: return BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT;
        case BODT_MODE_OPT_WEIGHTED: return BODT_OP_SMOOTH | BODT_OP_FLIP;
        default: return BODT_OP_SMOOTH;
    }
}

// The library's parameters for --param NAME=VALUE: NAME is the lower-case
// suffix of BODT_PARAM_*, the type that of the key (bodt.h).  BODT_PARAM_OPS
// is not here: it belongs to the variants (--ops).
struct ParamInfo {
    const char* name;
    int key;
    bool is_int;
};
const ParamInfo kParams[] = {
    {"tolerance", BODT_PARAM_TOLERANCE, false},
    {"backtrack_steps", BODT_PARAM_BACKTRACK_STEPS, true},
    {"min_stretch", BODT_PARAM_MIN_STRETCH, false},
    {"never_worse", BODT_PARAM_NEVER_WORSE, true},
    {"feature_angle", BODT_PARAM_FEATURE_ANGLE, false},
    {"edge_ratio", BODT_PARAM_EDGE_RATIO, false},
    {"corner_ratio", BODT_PARAM_CORNER_RATIO, false},
    {"keep_surface", BODT_PARAM_KEEP_SURFACE, true},
    {"bad_angle", BODT_PARAM_BAD_ANGLE, false},
    {"delaunay_flips", BODT_PARAM_DELAUNAY_FLIPS, true},
    {"weight_c", BODT_PARAM_WEIGHT_C, false},
    {"poor_quality", BODT_PARAM_POOR_QUALITY, false},
    {"qn_epsilon", BODT_PARAM_QN_EPSILON, false},
    {"qn_max_iterations", BODT_PARAM_QN_MAX_ITERATIONS, true},
    {"qn_initial_step", BODT_PARAM_QN_INITIAL_STEP, false},
    {"qn_interval_growth", BODT_PARAM_QN_INTERVAL_GROWTH, false},
};
constexpr size_t kNumParams = sizeof kParams / sizeof kParams[0];

size_t param_index(int key) {
    for (size_t i = 0; i < kNumParams; ++i)
        if (kParams[i].key == key) return i;
    return kNumParams;
}

// "BODT_PARAM_WEIGHT_C" for "weight_c".
std::string param_macro(const ParamInfo& p) {
    std::string o = "BODT_PARAM_";
    for (const char* c = p.name; *c; ++c) o += char(std::toupper(static_cast<unsigned char>(*c)));
    return o;
}

// A value as text: an int parameter's value (kept as a double, exact for
// int32) as an integer, a double's as the shortest text that reads back the
// same.  Not finite: "null" (for JSON).
std::string param_value_string(const ParamInfo& p, double v) {
    if (!std::isfinite(v)) return "null";
    char b[40];
    if (p.is_int) {
        std::snprintf(b, sizeof b, "%d", int(v));
        return b;
    }
    if (v == std::floor(v) && std::fabs(v) < 1e15) {  // 20, not 2e+01
        std::snprintf(b, sizeof b, "%.0f", v);
        return b;
    }
    for (int prec = 1; prec <= 17; ++prec) {
        std::snprintf(b, sizeof b, "%.*g", prec, v);
        if (std::strtod(b, nullptr) == v) break;
    }
    return b;
}

// "smooth+flip+insert", "none" for 0, "default" for kOpsDefault.
std::string ops_string(int ops) {
    if (ops == kOpsDefault) return "default";
    if (ops == 0) return "none";
    static const struct {
        int bit;
        const char* name;
    } kBits[] = {{BODT_OP_SMOOTH, "smooth"}, {BODT_OP_FLIP, "flip"}, {BODT_OP_INSERT, "insert"},
                 {BODT_OP_COLLAPSE, "collapse"}};
    std::string o;
    int rest = ops;
    for (const auto& b : kBits)
        if (ops & b.bit) {
            o += (o.empty() ? "" : "+") + std::string(b.name);
            rest &= ~b.bit;
        }
    if (rest) o += (o.empty() ? "" : "+") + std::to_string(rest);
    return o;
}

// ---------------------------------------------------------------- options

// One --param (or --never-worse, --keep-surface, --bad-angle).
struct ParamSetting {
    size_t index;  // into kParams
    double value;  // an int parameter's value as a double
};

struct Options {
    std::vector<Variant> variants;
    int iterations = 20;
    bool ops_override = false;  // --ops given: every variant gets ops
    int ops = kOpsDefault;
    std::vector<ParamSetting> params;  // set for every variant, in this order; one per key
    std::string json_path, markdown_path, write_dir;
    std::string shared_dir = BODT_BENCH_DEFAULT_SHARED;
    bool large = false;
    bool fork_runs = true;
    bool list_only = false;
    int timeout_s = 900;
    std::string case_regex;
    std::vector<std::string> extra_surfaces, extra_meshes;
};

void usage(FILE* f) {
    std::string param_names;
    for (size_t i = 0; i < kNumParams; ++i) {
        if (i % 4 == 0) param_names += i ? ",\n                       " : "\n                       ";
        else param_names += ", ";
        param_names += kParams[i].name;
        param_names += kParams[i].is_int ? " (int)" : "";
    }
    std::fprintf(f,
                 "usage: bodt_bench [options]\n"
                 "  --modes LIST         comma-separated variants: laplace, odt, bodt-basic,\n"
                 "                       bodt-smooth (mode bodt, ops smooth: the 0.2 behaviour),\n"
                 "                       bodt (mode bodt, its default ops smooth+flip+insert),\n"
                 "                       opt-smooth (mode opt-weighted, ops smooth: paper 001's\n"
                 "                       improved smoothing), opt (mode opt-weighted, its default\n"
                 "                       ops smooth+flip: paper 001's combined method),\n"
                 "                       or mode values (1..5, with the mode's default ops)\n"
                 "                       (default: laplace,odt,bodt-basic,bodt-smooth,bodt,opt-smooth,opt)\n"
                 "  --ops LIST           BODT_PARAM_OPS for every variant: 'default', an integer, or\n"
                 "                       '+' or ',' separated of smooth,flip,insert,collapse\n"
                 "  --param NAME=VALUE   set BODT_PARAM_<NAME> for every variant (repeatable), NAME in\n"
                 "                       lower case, one of:%s\n"
                 "                       (ops=LIST is --ops LIST)\n"
                 "  --iterations N       bodt_step calls per run (default 20)\n"
                 "  --never-worse 0|1    = --param never_worse=0|1 (default: the library's default)\n"
                 "  --keep-surface 0|1   = --param keep_surface=0|1\n"
                 "  --bad-angle DEG      = --param bad_angle=DEG\n"
                 "  --json FILE          JSON lines to FILE instead of stdout\n"
                 "  --markdown FILE      write the markdown summary to FILE\n"
                 "  --write-dir DIR      write CASE.input.mesh and CASE.VARIANT.mesh there (bodt_mesh_write)\n"
                 "  --shared DIR         the shared folder with meshes/ (default %s)\n"
                 "  --no-shared          generated cases only\n"
                 "  --large              add the ~1e5-tet jittered box\n"
                 "  --cases REGEX        only cases whose name matches (ECMAScript regex, searched)\n"
                 "  --surface FILE       add a closed .off/.stl surface (TetGen -pQ and -pqQ)\n"
                 "  --mesh FILE          add a tet mesh file (.mesh, .node/.ele, optionally .gz)\n"
                 "  --timeout SECONDS    per case and variant (default 900; 0 = none)\n"
                 "  --no-fork            run in this process (for debuggers; a crash ends the bench)\n"
                 "  --list               list the cases and exit\n"
                 "  --help\n"
                 "exit status: 0 (also when some runs fail; see their status), 2 usage error\n",
                 param_names.c_str(), BODT_BENCH_DEFAULT_SHARED[0] ? BODT_BENCH_DEFAULT_SHARED : "none");
}

[[noreturn]] void usage_error(const char* fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    std::fprintf(stderr, "bodt_bench: ");
    std::vfprintf(stderr, fmt, ap);
    std::fprintf(stderr, "\n");
    va_end(ap);
    usage(stderr);
    std::exit(2);
}

bool parse_int(const char* s, int& out) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s, &end, 10);
    if (errno || end == s || *end || v < INT32_MIN || v > INT32_MAX) return false;
    out = int(v);
    return true;
}

bool parse_double(const char* s, double& out) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s, &end);
    if (errno || end == s || *end || !std::isfinite(v)) return false;
    out = v;
    return true;
}

// Set (or replace) a parameter for every variant.  The value's type is the
// key's; its range is checked by the library (check_params).
void set_param(Options& o, const std::string& name, const std::string& text, const char* option) {
    size_t idx = kNumParams;
    for (size_t i = 0; i < kNumParams; ++i)
        if (name == kParams[i].name) idx = i;
    if (idx == kNumParams) usage_error("%s: unknown parameter '%s' (see --param below)", option, name.c_str());
    double v = 0;
    if (kParams[idx].is_int) {
        int iv = 0;
        if (!parse_int(text.c_str(), iv))
            usage_error("%s: %s is an int parameter, got '%s'", option, name.c_str(), text.c_str());
        v = iv;
    } else if (!parse_double(text.c_str(), v)) {
        usage_error("%s: %s needs a finite number, got '%s'", option, name.c_str(), text.c_str());
    }
    for (ParamSetting& ps : o.params)
        if (ps.index == idx) {
            ps.value = v;
            return;
        }
    o.params.push_back({idx, v});
}

// --ops LIST (also --param ops=LIST).
void parse_ops(Options& o, const std::string& list);

// Split at any of the characters in seps; empty items are dropped.
std::vector<std::string> split_list(const std::string& list, const char* seps) {
    std::vector<std::string> out;
    size_t p = 0;
    while (p <= list.size()) {
        size_t q = list.find_first_of(seps, p);
        if (q == std::string::npos) q = list.size();
        if (q > p) out.push_back(list.substr(p, q - p));
        p = q + 1;
    }
    return out;
}

Options parse_args(int argc, char** argv) {
    Options o;
    auto value = [&](int& i) -> const char* {
        if (i + 1 >= argc) usage_error("%s needs a value", argv[i]);
        return argv[++i];
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            usage(stdout);
            std::exit(0);
        } else if (a == "--modes") {
            o.variants.clear();
            for (const std::string& name : split_list(value(i), ",")) {
                bool found = false;
                for (const Variant& v : kVariants)
                    if (name == v.name) {
                        o.variants.push_back(v);
                        found = true;
                    }
                int mval = 0;
                if (!found && parse_int(name.c_str(), mval) && mval > 0) {  // a mode by its value
                    o.variants.push_back({"mode" + name, mval, kOpsDefault});
                    found = true;
                }
                if (!found) {
                    std::string known;
                    for (const Variant& v : kVariants) known += v.name + ", ";
                    usage_error("unknown variant '%s' (%sor a mode value)", name.c_str(), known.c_str());
                }
            }
            if (o.variants.empty()) usage_error("--modes needs at least one variant");
        } else if (a == "--ops") {
            parse_ops(o, value(i));
        } else if (a == "--param") {
            const std::string kv = value(i);
            const size_t eq = kv.find('=');
            if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
                usage_error("--param takes NAME=VALUE, got '%s'", kv.c_str());
            const std::string name = kv.substr(0, eq), val = kv.substr(eq + 1);
            if (name == "ops")
                parse_ops(o, val);
            else
                set_param(o, name, val, "--param");
        } else if (a == "--keep-surface") {
            const std::string v = value(i);
            if (v != "0" && v != "1") usage_error("--keep-surface takes 0 or 1");
            set_param(o, "keep_surface", v, "--keep-surface");
        } else if (a == "--bad-angle") {
            const std::string v = value(i);
            double d = 0;
            if (!parse_double(v.c_str(), d) || !(d >= 0)) usage_error("--bad-angle needs degrees >= 0");
            set_param(o, "bad_angle", v, "--bad-angle");
        } else if (a == "--iterations") {
            if (!parse_int(value(i), o.iterations) || o.iterations < 1) usage_error("--iterations needs N >= 1");
        } else if (a == "--never-worse") {
            const std::string v = value(i);
            if (v != "0" && v != "1") usage_error("--never-worse takes 0 or 1");
            set_param(o, "never_worse", v, "--never-worse");
        } else if (a == "--json") {
            o.json_path = value(i);
        } else if (a == "--markdown") {
            o.markdown_path = value(i);
        } else if (a == "--write-dir") {
            o.write_dir = value(i);
        } else if (a == "--shared") {
            o.shared_dir = value(i);
        } else if (a == "--no-shared") {
            o.shared_dir.clear();
        } else if (a == "--large") {
            o.large = true;
        } else if (a == "--cases") {
            o.case_regex = value(i);
            try {
                std::regex re(o.case_regex);
            } catch (const std::regex_error&) {
                usage_error("bad --cases regex '%s'", o.case_regex.c_str());
            }
        } else if (a == "--surface") {
            o.extra_surfaces.push_back(value(i));
        } else if (a == "--mesh") {
            o.extra_meshes.push_back(value(i));
        } else if (a == "--timeout") {
            if (!parse_int(value(i), o.timeout_s) || o.timeout_s < 0) usage_error("--timeout needs seconds >= 0");
        } else if (a == "--no-fork") {
            o.fork_runs = false;
        } else if (a == "--list") {
            o.list_only = true;
        } else {
            usage_error("unknown argument '%s'", a.c_str());
        }
    }
    if (o.variants.empty()) o.variants.assign(std::begin(kVariants), std::end(kVariants));
    if (o.ops_override)
        for (Variant& v : o.variants) v.ops = o.ops;
    return o;
}

void parse_ops(Options& o, const std::string& list) {
    o.ops_override = true;
    if (list == "default") {
        o.ops = kOpsDefault;
    } else if (parse_int(list.c_str(), o.ops)) {
        if (o.ops < 0) usage_error("--ops takes a value >= 0 or 'default'");
    } else {
        o.ops = 0;
        for (const std::string& name : split_list(list, ",+")) {
            if (name == "smooth") o.ops |= BODT_OP_SMOOTH;
            else if (name == "flip") o.ops |= BODT_OP_FLIP;
            else if (name == "insert") o.ops |= BODT_OP_INSERT;
            else if (name == "collapse") o.ops |= BODT_OP_COLLAPSE;
            else usage_error("unknown operation '%s' (smooth, flip, insert, collapse)", name.c_str());
        }
    }
}

// The value a --param gave for key, or nullptr.
const ParamSetting* find_param(const Options& o, int key) {
    for (const ParamSetting& ps : o.params)
        if (kParams[ps.index].key == key) return &ps;
    return nullptr;
}

// Refuse, before any case is made, a parameter value the library refuses
// (range, or a key this library does not know): set each on a one-tet mesh.
void check_params(const Options& o) {
    if (o.params.empty()) return;
    const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int32_t tet[4] = {0, 1, 2, 3};
    bodt_mesh* m = nullptr;
    if (bodt_mesh_create(4, xyz, 1, tet, 0, &m) != BODT_OK) return;  // cannot check: the runs will say
    for (const ParamSetting& ps : o.params) {
        const ParamInfo& p = kParams[ps.index];
        const int st = p.is_int ? bodt_set_param_int(m, p.key, int32_t(ps.value))
                                : bodt_set_param_double(m, p.key, ps.value);
        if (st != BODT_OK) {
            const std::string msg = bodt_mesh_last_error(m);
            bodt_mesh_destroy(m);
            usage_error("%s=%s: refused by libbodt: %s", p.name, param_value_string(p, ps.value).c_str(),
                        msg.c_str());
        }
    }
    bodt_mesh_destroy(m);
}

// ----------------------------------------------------------------- results

struct Stats {
    int32_t vertices, tets, boundary_faces, lib_boundary_faces;
    int32_t inverted, unused, lt10, gt165;
    int32_t in30_140;  // tets whose 6 dihedral angles all lie in [30, 140] degrees
    double min_dihedral, max_dihedral, mean_dihedral;
    double min_stretch, mean_stretch, volume;
};

// Plain data, so a forked child can hand it back through a pipe.
struct RunResult {
    char status[16];    // ok, unsupported, error, crashed, timeout
    char where[64];     // the call that failed
    char message[768];  // bodt_mesh_last_error or our own
    int32_t steps_done;
    int32_t never_worse;  // effective value, -1 unknown
    int32_t ops;          // BODT_PARAM_OPS as read back (kOpsDefault = the mode's default)
    int32_t ops_effective;  // the operations a step does (the default resolved), -1 unknown
    int32_t keep_surface;   // effective value, -1 unknown
    double bad_angle;       // effective value, NaN unknown
    double params[kNumParams];  // every parameter of kParams as read back, NaN unknown
    int32_t has_before, has_after;
    Stats before, after;
    double volume_change_rel;
    double region_volume_change_rel_max;  // max over regions of |dV_r| / |V_r|
    int32_t regions;
    double hausdorff_abs, hausdorff_rel, bbox_side;
    double time_s, hausdorff_time_s;
    int64_t vertices_moved, moves_rejected, moves_shortened;
    int64_t flips, inserted, collapsed;  // sums over the steps
    int32_t vertices_changed;
    double last_max_move;
    double updates_per_s;
    double peak_rss_mb;
};

void set_str(char* dst, size_t cap, const std::string& s) {
    std::snprintf(dst, cap, "%s", s.c_str());
}
#define SET(field, s) set_str(field, sizeof(field), s)

RunResult empty_result() {
    RunResult r{};
    SET(r.status, "ok");
    r.never_worse = r.keep_surface = r.ops_effective = -1;
    r.ops = kOpsDefault;
    r.bad_angle = NAN;
    for (double& v : r.params) v = NAN;
    r.volume_change_rel = r.region_volume_change_rel_max = r.hausdorff_abs = r.hausdorff_rel = NAN;
    return r;
}

// ----------------------------------------------------------- one run

// Quality, counts and boundary surface of the mesh as it is now.
// Returns BODT_OK or the status of the call named in where.
int measure(const bodt_mesh* m, Stats& s, bench::Surface& surf, std::vector<int32_t>& tets, int index_base,
            std::string& where) {
    int st;
    int32_t nv = 0, nt = 0, nb = 0;
    if ((st = bodt_mesh_get_counts(m, &nv, &nt, &nb)) != BODT_OK) return where = "bodt_mesh_get_counts", st;
    s.vertices = nv;
    s.tets = nt;
    s.lib_boundary_faces = nb;
    bodt_quality q = bench::sized_struct<bodt_quality>();
    if ((st = bodt_mesh_quality(m, &q)) != BODT_OK) return where = "bodt_mesh_quality", st;
    s.inverted = q.num_inverted;
    s.unused = q.num_unused_vertices;
    s.min_dihedral = q.min_dihedral;
    s.max_dihedral = q.max_dihedral;
    s.mean_dihedral = q.mean_dihedral;
    s.min_stretch = q.min_stretch;
    s.mean_stretch = q.mean_stretch;
    s.volume = q.volume;
    std::vector<double> mn(static_cast<size_t>(nt)), mx(static_cast<size_t>(nt));
    if ((st = bodt_mesh_tet_quality(m, BODT_MEASURE_MIN_DIHEDRAL, mn.data(), mn.size())) != BODT_OK)
        return where = "bodt_mesh_tet_quality(MIN_DIHEDRAL)", st;
    if ((st = bodt_mesh_tet_quality(m, BODT_MEASURE_MAX_DIHEDRAL, mx.data(), mx.size())) != BODT_OK)
        return where = "bodt_mesh_tet_quality(MAX_DIHEDRAL)", st;
    s.lt10 = s.gt165 = s.in30_140 = 0;
    for (size_t t = 0; t < mn.size(); ++t) {
        s.lt10 += mn[t] < 10.0;
        s.gt165 += mx[t] > 165.0;
        s.in30_140 += mn[t] >= 30.0 && mx[t] <= 140.0;
    }
    surf.xyz.resize(3 * size_t(nv));
    if ((st = bodt_mesh_get_vertices(m, surf.xyz.data(), surf.xyz.size())) != BODT_OK)
        return where = "bodt_mesh_get_vertices", st;
    tets.resize(4 * size_t(nt));
    if ((st = bodt_mesh_get_tets(m, tets.data(), tets.size())) != BODT_OK) return where = "bodt_mesh_get_tets", st;
    surf.tris = bench::boundary_triangles(tets, index_base);
    s.boundary_faces = int32_t(surf.tris.size());
    return BODT_OK;
}

// Volume of each region (sum of signed tet volumes by region id).
int region_volumes(const bodt_mesh* m, std::map<int32_t, double>& out, std::string& where) {
    int st;
    int32_t nt = 0;
    if ((st = bodt_mesh_get_counts(m, nullptr, &nt, nullptr)) != BODT_OK) return where = "bodt_mesh_get_counts", st;
    std::vector<int32_t> reg(static_cast<size_t>(nt));
    std::vector<double> vol(static_cast<size_t>(nt));
    if ((st = bodt_mesh_get_regions(m, reg.data(), reg.size())) != BODT_OK) return where = "bodt_mesh_get_regions", st;
    if ((st = bodt_mesh_tet_quality(m, BODT_MEASURE_VOLUME, vol.data(), vol.size())) != BODT_OK)
        return where = "bodt_mesh_tet_quality(VOLUME)", st;
    out.clear();
    for (size_t t = 0; t < reg.size(); ++t) out[reg[t]] += vol[t];
    return BODT_OK;
}

RunResult run_one(const Case& c, const PreparedMesh& pm, const Variant& var, const Options& opt) {
    RunResult r = empty_result();
    auto fail = [&](const char* status, const std::string& where, const std::string& msg) {
        SET(r.status, status);
        SET(r.where, where);
        SET(r.message, msg);
        std::fprintf(stderr, "bodt_bench: %s / %s: %s: %s\n", c.name.c_str(), var.name.c_str(), where.c_str(),
                     msg.c_str());
        return r;
    };

    bench::MeshHandle mh;
    int st;
    int index_base = 0;
    if (pm.from_file) {
        st = bodt_mesh_read(pm.path.c_str(), &mh.m);
        if (st != BODT_OK) return fail("error", "bodt_mesh_read", errmsg(nullptr, st));
    } else {
        const auto& a = pm.arrays;
        index_base = a.index_base;
        st = bodt_mesh_create(int32_t(a.xyz.size() / 3), a.xyz.data(), int32_t(a.tets.size() / 4), a.tets.data(),
                              a.index_base, &mh.m);
        if (st != BODT_OK) return fail("error", "bodt_mesh_create", errmsg(nullptr, st));
        if (!a.faces.empty()) {
            st = bodt_mesh_set_boundary_faces(mh.m, int32_t(a.markers.size()), a.faces.data(), a.markers.data());
            if (st != BODT_OK) return fail("error", "bodt_mesh_set_boundary_faces", errmsg(mh.m, st));
        }
    }

    bench::Surface before_surf, after_surf;
    std::vector<int32_t> tets;
    std::string where;
    if ((st = measure(mh.m, r.before, before_surf, tets, index_base, where)) != BODT_OK)
        return fail("error", where, errmsg(mh.m, st));
    r.has_before = 1;
    std::map<int32_t, double> reg_before, reg_after;
    if ((st = region_volumes(mh.m, reg_before, where)) != BODT_OK) return fail("error", where, errmsg(mh.m, st));
    r.regions = int32_t(reg_before.size());

    if (!opt.write_dir.empty()) {
        const std::string in_path = opt.write_dir + "/" + c.name + ".input.mesh";
        struct stat sb;
        if (stat(in_path.c_str(), &sb) != 0 && (st = bodt_mesh_write(mh.m, in_path.c_str())) != BODT_OK)
            std::fprintf(stderr, "bodt_bench: %s: bodt_mesh_write %s: %s\n", c.name.c_str(), in_path.c_str(),
                         errmsg(mh.m, st).c_str());
    }

    auto unsupported = [&](const char* call) {
        SET(r.status, "unsupported");
        SET(r.where, call);
        SET(r.message, errmsg(mh.m, st));
        return r;
    };
    st = bodt_set_mode(mh.m, var.mode);
    if (st == BODT_ERR_INVALID_ARGUMENT || st == BODT_ERR_UNSUPPORTED) return unsupported("bodt_set_mode");
    if (st != BODT_OK) return fail("error", "bodt_set_mode", errmsg(mh.m, st));
    if (var.ops != kOpsDefault) {
        st = bodt_set_param_int(mh.m, BODT_PARAM_OPS, var.ops);
        if (st == BODT_ERR_INVALID_ARGUMENT || st == BODT_ERR_UNSUPPORTED)
            return unsupported("bodt_set_param_int(OPS)");
        if (st != BODT_OK) return fail("error", "bodt_set_param_int(OPS)", errmsg(mh.m, st));
    }
    // --param (and --never-worse, --keep-surface, --bad-angle), after the mode
    for (const ParamSetting& ps : opt.params) {
        const ParamInfo& p = kParams[ps.index];
        const std::string call = std::string(p.is_int ? "bodt_set_param_int(" : "bodt_set_param_double(") +
                                 param_macro(p).substr(11) + ")";
        st = p.is_int ? bodt_set_param_int(mh.m, p.key, int32_t(ps.value)) : bodt_set_param_double(mh.m, p.key, ps.value);
        if (st != BODT_OK) return fail("error", call, errmsg(mh.m, st));
    }
    // every parameter as the run uses it
    for (size_t i = 0; i < kNumParams; ++i) {
        int32_t iv = 0;
        double dv = NAN;
        if (kParams[i].is_int) {
            if (bodt_get_param_int(mh.m, kParams[i].key, &iv) == BODT_OK) r.params[i] = iv;
        } else if (bodt_get_param_double(mh.m, kParams[i].key, &dv) == BODT_OK) {
            r.params[i] = dv;
        }
    }
    auto read_back = [&](int key) { return r.params[param_index(key)]; };
    if (std::isfinite(read_back(BODT_PARAM_NEVER_WORSE))) r.never_worse = int32_t(read_back(BODT_PARAM_NEVER_WORSE));
    if (std::isfinite(read_back(BODT_PARAM_KEEP_SURFACE)))
        r.keep_surface = int32_t(read_back(BODT_PARAM_KEEP_SURFACE));
    r.bad_angle = read_back(BODT_PARAM_BAD_ANGLE);
    int32_t iv = -1;
    if (bodt_get_param_int(mh.m, BODT_PARAM_OPS, &iv) == BODT_OK) {
        r.ops = iv;
        r.ops_effective = effective_ops(var.mode, iv);
    }

    // The steps, and only they, are timed.
    bool step_failed = false;
    std::string step_where, step_msg;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < opt.iterations; ++i) {
        bodt_step_report rep = bench::sized_struct<bodt_step_report>();
        st = bodt_step(mh.m, &rep);
        if (st != BODT_OK) {
            step_failed = true;
            step_where = "bodt_step (step " + std::to_string(i + 1) + ")";
            step_msg = errmsg(mh.m, st);
            break;
        }
        ++r.steps_done;
        r.vertices_moved += rep.vertices_moved;
        r.moves_rejected += rep.moves_rejected;
        r.moves_shortened += rep.moves_shortened;
        r.flips += rep.flips;
        r.inserted += rep.vertices_inserted;
        r.collapsed += rep.edges_collapsed;
        r.last_max_move = rep.max_move;
    }
    const auto t1 = std::chrono::steady_clock::now();
    r.time_s = std::chrono::duration<double>(t1 - t0).count();
    r.updates_per_s = r.time_s > 0 ? double(r.vertices_moved + r.moves_rejected) / r.time_s : 0.0;

    // From here on only the mesh the handle holds now: the steps may have
    // added vertices (appended; input vertices keep their index), and
    // renumbered, added or removed tets and boundary faces.
    if ((st = measure(mh.m, r.after, after_surf, tets, index_base, where)) != BODT_OK)
        return fail("error", where, errmsg(mh.m, st));
    r.has_after = 1;
    // input vertices whose coordinates changed (appended ones are not counted)
    const size_t common = std::min(before_surf.xyz.size(), after_surf.xyz.size()) / 3;
    for (size_t v = 0; v < common; ++v)
        if (before_surf.xyz[3 * v] != after_surf.xyz[3 * v] || before_surf.xyz[3 * v + 1] != after_surf.xyz[3 * v + 1] ||
            before_surf.xyz[3 * v + 2] != after_surf.xyz[3 * v + 2])
            ++r.vertices_changed;
    r.volume_change_rel = (r.after.volume - r.before.volume) / std::fabs(r.before.volume);
    if ((st = region_volumes(mh.m, reg_after, where)) != BODT_OK) return fail("error", where, errmsg(mh.m, st));
    r.region_volume_change_rel_max = 0.0;
    for (const auto& kv : reg_before) {
        const auto it = reg_after.find(kv.first);
        const double after = it == reg_after.end() ? 0.0 : it->second;
        r.region_volume_change_rel_max =
            std::max(r.region_volume_change_rel_max, std::fabs(after - kv.second) / std::fabs(kv.second));
    }
    const auto h0 = std::chrono::steady_clock::now();
    r.bbox_side = bench::bbox_largest_side(before_surf);
    r.hausdorff_abs = bench::hausdorff_distance(before_surf, after_surf);
    r.hausdorff_rel = r.bbox_side > 0 ? r.hausdorff_abs / r.bbox_side : NAN;
    r.hausdorff_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - h0).count();

    if (!opt.write_dir.empty()) {
        const std::string out_path = opt.write_dir + "/" + c.name + "." + var.name + ".mesh";
        if ((st = bodt_mesh_write(mh.m, out_path.c_str())) != BODT_OK)
            std::fprintf(stderr, "bodt_bench: %s / %s: bodt_mesh_write %s: %s\n", c.name.c_str(), var.name.c_str(),
                         out_path.c_str(), errmsg(mh.m, st).c_str());
    }
    if (step_failed) fail("error", step_where, step_msg);
    return r;
}

// Runs run_one in a forked child (so a crash or hang is contained) and takes
// the peak RSS of that child.
RunResult run_isolated(const Case& c, const PreparedMesh& pm, const Variant& var, const Options& opt) {
    RunResult r = empty_result();
    const bench::ChildRun child =
        bench::run_isolated(r, opt.fork_runs, opt.timeout_s, [&] { return run_one(c, pm, var, opt); });
    if (!child.ok) {
        SET(r.status, child.status);
        SET(r.where, child.where);
        SET(r.message, child.message);
        if (child.status != "error")  // the child died; pipe and fork failures are only recorded
            std::fprintf(stderr, "bodt_bench: %s / %s: %s\n", c.name.c_str(), var.name.c_str(), r.message);
    }
    r.peak_rss_mb = child.peak_rss_mb;
    return r;
}

// ------------------------------------------------------------------ output

double pct_30_140(const Stats& s) { return s.tets > 0 ? 100.0 * s.in30_140 / s.tets : NAN; }

double growth_pct(const RunResult& r) {
    return r.before.vertices > 0 ? 100.0 * (r.after.vertices - r.before.vertices) / r.before.vertices : NAN;
}

std::string stats_json(const Stats& s) {
    std::string o = "{";
    o += "\"vertices\":" + std::to_string(s.vertices);
    o += ",\"tets\":" + std::to_string(s.tets);
    o += ",\"boundary_faces\":" + std::to_string(s.boundary_faces);
    o += ",\"lib_boundary_faces\":" + std::to_string(s.lib_boundary_faces);
    o += ",\"min_dihedral\":" + json_num(s.min_dihedral, "%.4f");
    o += ",\"max_dihedral\":" + json_num(s.max_dihedral, "%.4f");
    o += ",\"mean_dihedral\":" + json_num(s.mean_dihedral, "%.4f");
    o += ",\"tets_min_dihedral_lt_10\":" + std::to_string(s.lt10);
    o += ",\"tets_max_dihedral_gt_165\":" + std::to_string(s.gt165);
    o += ",\"tets_dihedral_30_140\":" + std::to_string(s.in30_140);
    o += ",\"pct_dihedral_30_140\":" + json_num(pct_30_140(s), "%.3f");
    o += ",\"stretch_min\":" + json_num(s.min_stretch, "%.5f");
    o += ",\"stretch_mean\":" + json_num(s.mean_stretch, "%.5f");
    o += ",\"inverted\":" + std::to_string(s.inverted);
    o += ",\"unused_vertices\":" + std::to_string(s.unused);
    o += ",\"volume\":" + json_num(s.volume, "%.10g");
    return o + "}";
}

std::string result_json(const Case& c, const std::string& note, const Variant& var, const RunResult& r,
                        const Options& opt) {
    std::string o = "{";
    o += "\"case\":" + json_str(c.name);
    o += ",\"kind\":" + json_str(c.kind);
    o += ",\"source\":" + json_str(c.source);
    if (!note.empty()) o += ",\"note\":" + json_str(note);
    o += ",\"variant\":" + json_str(var.name);
    o += ",\"mode\":" + json_str(mode_name(var.mode));
    o += ",\"mode_value\":" + std::to_string(var.mode);
    o += ",\"ops_requested\":" + (var.ops == kOpsDefault ? std::string("null") : std::to_string(var.ops));
    o += ",\"ops\":" + (r.ops_effective >= 0 ? std::to_string(r.ops_effective) : std::string("null"));
    o += ",\"ops_names\":" + json_str(r.ops_effective >= 0 ? ops_string(r.ops_effective) : "unknown");
    o += ",\"status\":" + json_str(r.status);
    if (r.where[0]) o += ",\"where\":" + json_str(r.where);
    if (r.message[0]) o += ",\"message\":" + json_str(r.message);
    o += ",\"library\":" + json_str(bodt_version_string());
    o += ",\"iterations\":" + std::to_string(opt.iterations);
    o += ",\"steps_done\":" + std::to_string(r.steps_done);
    o += ",\"never_worse\":" + (r.never_worse >= 0 ? std::to_string(r.never_worse) : std::string("null"));
    o += ",\"keep_surface\":" + (r.keep_surface >= 0 ? std::to_string(r.keep_surface) : std::string("null"));
    o += ",\"bad_angle\":" + json_num(r.bad_angle);
    // what --param asked for, and every parameter as the run used it
    o += ",\"params\":{";
    for (size_t i = 0; i < opt.params.size(); ++i) {
        const ParamInfo& p = kParams[opt.params[i].index];
        o += (i ? "," : "") + json_str(p.name) + ":" + param_value_string(p, opt.params[i].value);
    }
    o += "}";
    bool any_effective = false;
    for (double v : r.params) any_effective = any_effective || std::isfinite(v);
    if (any_effective) {
        o += ",\"params_effective\":{";
        for (size_t i = 0; i < kNumParams; ++i)
            o += (i ? "," : "") + json_str(kParams[i].name) + ":" + param_value_string(kParams[i], r.params[i]);
        o += "}";
    }
    if (r.has_before) {
        o += ",\"vertices\":" + std::to_string(r.before.vertices);
        o += ",\"tets\":" + std::to_string(r.before.tets);
        o += ",\"boundary_faces\":" + std::to_string(r.before.boundary_faces);
        o += ",\"before\":" + stats_json(r.before);
    }
    if (r.has_after) {
        o += ",\"after\":" + stats_json(r.after);
        o += ",\"vertices_in\":" + std::to_string(r.before.vertices);
        o += ",\"vertices_out\":" + std::to_string(r.after.vertices);
        o += ",\"tets_in\":" + std::to_string(r.before.tets);
        o += ",\"tets_out\":" + std::to_string(r.after.tets);
        o += ",\"vertex_growth_pct\":" + json_num(growth_pct(r), "%.3f");
        o += ",\"flips\":" + std::to_string(r.flips);
        o += ",\"inserted\":" + std::to_string(r.inserted);
        o += ",\"collapsed\":" + std::to_string(r.collapsed);
        o += ",\"pct_dihedral_30_140\":" + json_num(pct_30_140(r.after), "%.3f");
        o += ",\"pct_dihedral_30_140_before\":" + json_num(pct_30_140(r.before), "%.3f");
        o += std::string(",\"min_dihedral_worse\":") + (r.after.min_dihedral < r.before.min_dihedral ? "true" : "false");
        o += std::string(",\"max_dihedral_worse\":") + (r.after.max_dihedral > r.before.max_dihedral ? "true" : "false");
        o += std::string(",\"stretch_min_worse\":") + (r.after.min_stretch < r.before.min_stretch ? "true" : "false");
        o += ",\"volume_change_rel\":" + json_num(r.volume_change_rel, "%.3e");
        o += ",\"regions\":" + std::to_string(r.regions);
        o += ",\"region_volume_change_rel_max\":" + json_num(r.region_volume_change_rel_max, "%.3e");
        o += ",\"hausdorff_rel\":" + json_num(r.hausdorff_rel, "%.4e");
        o += ",\"hausdorff_abs\":" + json_num(r.hausdorff_abs, "%.4e");
        o += ",\"bbox_largest_side\":" + json_num(r.bbox_side);
        o += ",\"time_s\":" + json_num(r.time_s, "%.4f");
        o += ",\"s_per_10k_tets\":" + json_num(r.before.tets > 0 ? r.time_s * 1e4 / r.before.tets : NAN, "%.4g");
        o += ",\"vertices_moved\":" + std::to_string(r.vertices_moved);
        o += ",\"moves_rejected\":" + std::to_string(r.moves_rejected);
        o += ",\"moves_shortened\":" + std::to_string(r.moves_shortened);
        o += ",\"vertex_updates_per_s\":" + json_num(r.updates_per_s, "%.4g");
        o += ",\"vertices_changed\":" + std::to_string(r.vertices_changed);
        o += ",\"last_max_move\":" + json_num(r.last_max_move, "%.3e");
        o += ",\"hausdorff_time_s\":" + json_num(r.hausdorff_time_s, "%.3f");
    }
    o += ",\"peak_rss_mb\":" + json_num(r.peak_rss_mb, "%.1f");
    return o + "}";
}

struct Row {
    const Case* c;
    std::string note;
    std::string prep_error;
    std::vector<RunResult> runs;  // one per variant, in opt.variants order
};

std::string pct_cell(double h) {
    return !std::isfinite(h) ? "–" : (h == 0 ? "0" : fmt("%.3g", h));
}

double median(std::vector<double> v) {
    if (v.empty()) return double(NAN);
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The first run of a row that measured the input.
const RunResult* before_run(const Row& row) {
    for (const auto& r : row.runs)
        if (r.has_before) return &r;
    return nullptr;
}

std::string markdown(const std::vector<Row>& rows, const Options& opt, const std::vector<std::string>& notes,
                     double total_s) {
    const std::vector<Variant>& vars = opt.variants;
    const size_t nvar = vars.size();
    std::string md;
    char date[64];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M", std::localtime(&now));
    md += "# bodt_bench\n\n";
    const ParamSetting* nw = find_param(opt, BODT_PARAM_NEVER_WORSE);
    md += fmt("libbodt %s, %d bodt_step calls per case and variant, BODT_PARAM_NEVER_WORSE %s", bodt_version_string(),
              opt.iterations, !nw ? "= library default" : (nw->value != 0 ? "= 1" : "= 0"));
    for (const ParamSetting& ps : opt.params)  // --param, --keep-surface, --bad-angle, in the order given
        if (kParams[ps.index].key != BODT_PARAM_NEVER_WORSE)
            md += fmt(", %s = %s", param_macro(kParams[ps.index]).c_str(),
                      param_value_string(kParams[ps.index], ps.value).c_str());
    md += fmt("; %s; total %.0f s.\n\n", date, total_s);

    // The operations each variant did (as read back from the library).
    std::vector<int> ops(nvar);
    for (size_t m = 0; m < nvar; ++m) {
        ops[m] = effective_ops(vars[m].mode, vars[m].ops);
        for (const Row& row : rows)
            if (m < row.runs.size() && row.runs[m].ops_effective >= 0) {
                ops[m] = row.runs[m].ops_effective;
                break;
            }
    }
    md += "Variants:";
    for (size_t m = 0; m < nvar; ++m)
        md += fmt("%s `%s` = mode %s, ops %s", m ? ";" : "", vars[m].name.c_str(), mode_name(vars[m].mode),
                  ops_string(ops[m]).c_str());
    md += ".\n\n";

    md += "Angles in degrees (after the run); `<10/>165` = tets with min dihedral < 10 / max dihedral > 165; "
          "H = relative Hausdorff distance of the boundary, in % of the largest bounding-box side; "
          "s = wall time of the bodt_step calls alone; `!` marks an angle worse than before. "
          "Last row: medians of the angles and of H over the cases that ran, sums of the counts and times.\n\n";

    // A variant the library refused on every case gets one column.
    std::vector<bool> all_unsupported(nvar, true);
    for (size_t m = 0; m < nvar; ++m)
        for (const Row& row : rows)
            if (m < row.runs.size() && std::strcmp(row.runs[m].status, "unsupported") != 0)
                all_unsupported[m] = false;
    if (rows.empty()) all_unsupported.assign(nvar, false);

    // ---- table 1: quality, boundary distance, time
    md += "| case | V / T / bF | before min/max | before <10/>165 |";
    std::string sep = "|---|---:|---:|---:|";
    for (size_t m = 0; m < nvar; ++m) {
        const char* n = vars[m].name.c_str();
        if (all_unsupported[m]) {
            md += fmt(" %s |", n);
            sep += "---|";
        } else {
            md += fmt(" %s min/max | %s <10/>165 | %s H %% | %s s |", n, n, n, n);
            sep += "---:|---:|---:|---:|";
        }
    }
    md += "\n" + sep + "\n";
    for (const Row& row : rows) {
        const RunResult* b = before_run(row);
        md += "| " + row.c->name + " | ";
        if (b)
            md += fmt("%d / %d / %d | %.2f/%.2f | %d/%d |", b->before.vertices, b->before.tets,
                      b->before.boundary_faces, b->before.min_dihedral, b->before.max_dihedral, b->before.lt10,
                      b->before.gt165);
        else
            md += "– | – | – |";
        for (size_t m = 0; m < nvar; ++m) {
            if (!row.prep_error.empty() || m >= row.runs.size()) {
                md += all_unsupported[m] ? " error |" : " error | – | – | – |";
                continue;
            }
            const RunResult& r = row.runs[m];
            if (all_unsupported[m]) {
                md += " unsupported |";
            } else if (!std::strcmp(r.status, "unsupported")) {
                md += " unsupported | – | – | – |";
            } else if (r.has_after) {
                const bool err = std::strcmp(r.status, "ok") != 0;
                md += fmt(" %s%.2f%s/%.2f%s | %d/%d | %s | %.2f |", err ? "(error) " : "", r.after.min_dihedral,
                          r.after.min_dihedral < r.before.min_dihedral ? "!" : "", r.after.max_dihedral,
                          r.after.max_dihedral > r.before.max_dihedral ? "!" : "", r.after.lt10, r.after.gt165,
                          pct_cell(r.hausdorff_rel * 100.0).c_str(), r.time_s);
            } else {
                md += fmt(" %s | – | – | – |", r.status);
            }
        }
        md += "\n";
    }
    if (!rows.empty()) {
        std::vector<double> bmin, bmax;
        long blt = 0, bgt = 0;
        for (const Row& row : rows)
            if (const RunResult* b = before_run(row)) {
                bmin.push_back(b->before.min_dihedral);
                bmax.push_back(b->before.max_dihedral);
                blt += b->before.lt10;
                bgt += b->before.gt165;
            }
        md += fmt("| **median / sum** (%zu cases) | | %.2f/%.2f | %ld/%ld |", rows.size(), median(bmin), median(bmax),
                  blt, bgt);
        for (size_t m = 0; m < nvar; ++m) {
            if (all_unsupported[m]) {
                md += " |";
                continue;
            }
            std::vector<double> mn, mx, hs;
            long lt = 0, gt = 0;
            double secs = 0;
            for (const Row& row : rows)
                if (m < row.runs.size() && row.runs[m].has_after) {
                    const RunResult& r = row.runs[m];
                    mn.push_back(r.after.min_dihedral);
                    mx.push_back(r.after.max_dihedral);
                    if (std::isfinite(r.hausdorff_rel)) hs.push_back(r.hausdorff_rel * 100.0);
                    lt += r.after.lt10;
                    gt += r.after.gt165;
                    secs += r.time_s;
                }
            if (mn.empty()) {
                md += " – | – | – | – |";
                continue;
            }
            md += fmt(" %.2f/%.2f (%zu) | %ld/%ld | %s | %.1f |", median(mn), median(mx), mn.size(), lt, gt,
                      pct_cell(median(hs)).c_str(), secs);
        }
        md += "\n";
    }

    // ---- table 2: share of good tets for every variant, and what the
    // connectivity-changing operations did for the variants that have them
    std::vector<size_t> shown, pipe;
    bool any_collapse = false;
    for (size_t m = 0; m < nvar; ++m) {
        if (all_unsupported[m]) continue;
        shown.push_back(m);
        bool changes = (ops[m] & ~BODT_OP_SMOOTH) != 0;
        for (const Row& row : rows)
            if (m < row.runs.size() && (row.runs[m].flips || row.runs[m].inserted || row.runs[m].collapsed ||
                                        row.runs[m].after.vertices != row.runs[m].before.vertices ||
                                        row.runs[m].after.tets != row.runs[m].before.tets))
                changes = true;
        if (changes) pipe.push_back(m);
        if (ops[m] & BODT_OP_COLLAPSE) any_collapse = true;
        for (const Row& row : rows)
            if (m < row.runs.size() && row.runs[m].collapsed) any_collapse = true;
    }
    if (!rows.empty() && !shown.empty()) {
        md += "\n% in [30,140] = share of the tets whose six dihedral angles all lie in [30°, 140°] (after the run). ";
        if (!pipe.empty())
            md += fmt("For the variants that change the connectivity: ΔV = vertex growth in %% of the input "
                      "vertices, flips and ins(erted vertices)%s summed over the steps. ",
                      any_collapse ? ", coll(apsed edges)" : "");
        md += "Last row: medians of the percentages, sums of the counts.\n\n";
        md += "| case | before % in [30,140] |";
        std::string sep2 = "|---|---:|";
        for (size_t m : shown) {
            md += fmt(" %s %% |", vars[m].name.c_str());
            sep2 += "---:|";
        }
        for (size_t m : pipe) {
            const char* n = vars[m].name.c_str();
            md += fmt(" %s ΔV %% | %s flips | %s ins |", n, n, n);
            sep2 += "---:|---:|---:|";
            if (any_collapse) {
                md += fmt(" %s coll |", n);
                sep2 += "---:|";
            }
        }
        md += "\n" + sep2 + "\n";
        const std::string dash_pipe = any_collapse ? " – | – | – | – |" : " – | – | – |";
        for (const Row& row : rows) {
            const RunResult* b = before_run(row);
            md += "| " + row.c->name + " | " + (b ? fmt("%.1f", pct_30_140(b->before)) : std::string("–")) + " |";
            for (size_t m : shown) {
                const bool ran = row.prep_error.empty() && m < row.runs.size() && row.runs[m].has_after;
                md += ran ? fmt(" %.1f |", pct_30_140(row.runs[m].after)) : std::string(" – |");
            }
            for (size_t m : pipe) {
                if (!(row.prep_error.empty() && m < row.runs.size() && row.runs[m].has_after)) {
                    md += dash_pipe;
                    continue;
                }
                const RunResult& r = row.runs[m];
                md += fmt(" %+.1f | %" PRId64 " | %" PRId64 " |", growth_pct(r), r.flips, r.inserted);
                if (any_collapse) md += fmt(" %" PRId64 " |", r.collapsed);
            }
            md += "\n";
        }
        std::vector<double> bp;
        for (const Row& row : rows)
            if (const RunResult* b = before_run(row)) bp.push_back(pct_30_140(b->before));
        md += fmt("| **median / sum** (%zu cases) | %.1f |", rows.size(), median(bp));
        for (size_t m : shown) {
            std::vector<double> p;
            for (const Row& row : rows)
                if (m < row.runs.size() && row.runs[m].has_after) p.push_back(pct_30_140(row.runs[m].after));
            md += p.empty() ? std::string(" – |") : fmt(" %.1f |", median(p));
        }
        for (size_t m : pipe) {
            std::vector<double> g;
            int64_t fl = 0, in = 0, co = 0;
            for (const Row& row : rows)
                if (m < row.runs.size() && row.runs[m].has_after) {
                    const RunResult& r = row.runs[m];
                    g.push_back(growth_pct(r));
                    fl += r.flips;
                    in += r.inserted;
                    co += r.collapsed;
                }
            if (g.empty()) {
                md += dash_pipe;
                continue;
            }
            md += fmt(" %+.1f | %" PRId64 " | %" PRId64 " |", median(g), fl, in);
            if (any_collapse) md += fmt(" %" PRId64 " |", co);
        }
        md += "\n";
    }

    // ---- notes: anything that needs a look
    std::vector<std::string> lines;
    for (const Row& row : rows) {
        if (!row.note.empty()) lines.push_back("`" + row.c->name + "`: " + row.note + ".");
        if (!row.prep_error.empty()) lines.push_back("`" + row.c->name + "`: could not be made: " + row.prep_error);
        for (size_t m = 0; m < row.runs.size() && m < nvar; ++m) {
            const RunResult& r = row.runs[m];
            const char* vn = vars[m].name.c_str();
            if (r.has_after && std::fabs(r.volume_change_rel) > 1e-10)
                lines.push_back(fmt("**`%s` / %s: the volume changed by %.3g (relative)**", row.c->name.c_str(), vn,
                                    r.volume_change_rel));
            if (r.has_after && r.region_volume_change_rel_max > 1e-10)
                lines.push_back(fmt("**`%s` / %s: the volume of a region changed by %.3g (relative)**",
                                    row.c->name.c_str(), vn, r.region_volume_change_rel_max));
            if (r.has_after && r.after.inverted > 0)
                lines.push_back(fmt("**`%s` / %s: %d inverted tets after, %d before**", row.c->name.c_str(), vn,
                                    r.after.inverted, r.before.inverted));
            if (std::strcmp(r.status, "ok") != 0 && !(all_unsupported[m] && !std::strcmp(r.status, "unsupported")))
                lines.push_back("`" + row.c->name + "` / " + vars[m].name + ": " + r.status + " in " + r.where + ": " +
                                r.message);
            // A variant with connectivity changes against the smoothing-only
            // variant of the same mode: is the boundary much farther away?
            if (!r.has_after || ops[m] == BODT_OP_SMOOTH || !std::isfinite(r.hausdorff_rel)) continue;
            for (size_t k = 0; k < row.runs.size() && k < nvar; ++k) {
                const RunResult& s = row.runs[k];
                if (k == m || vars[k].mode != vars[m].mode || ops[k] != BODT_OP_SMOOTH || !s.has_after ||
                    !std::isfinite(s.hausdorff_rel))
                    continue;
                if (r.hausdorff_rel > 1.25 * s.hausdorff_rel && r.hausdorff_rel - s.hausdorff_rel > 1e-4)
                    lines.push_back(fmt("**`%s` / %s: H %.3g %% against %.3g %% for %s**", row.c->name.c_str(), vn,
                                        r.hausdorff_rel * 100.0, s.hausdorff_rel * 100.0, vars[k].name.c_str()));
            }
        }
    }
    for (size_t m = 0; m < nvar; ++m)
        if (all_unsupported[m] && !rows.empty() && m < rows[0].runs.size())
            lines.push_back(fmt("variant %s (mode %d, ops %s): unsupported by this library (%s: %s)",
                                vars[m].name.c_str(), vars[m].mode, ops_string(vars[m].ops).c_str(),
                                rows[0].runs[m].where, rows[0].runs[m].message));
    for (const auto& n : notes) lines.push_back(n);
    if (!lines.empty()) {
        md += "\nNotes:\n\n";
        for (const auto& l : lines) md += "- " + l + "\n";
    }
    return md;
}

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse_args(argc, argv);
    check_params(opt);

    FILE* json = stdout;
    if (!opt.json_path.empty()) {
        json = std::fopen(opt.json_path.c_str(), "w");
        if (!json) usage_error("cannot write %s: %s", opt.json_path.c_str(), std::strerror(errno));
    }
    if (!opt.write_dir.empty()) {
        mkdir(opt.write_dir.c_str(), 0777);
        if (!bench::is_dir(opt.write_dir))
            usage_error("cannot create --write-dir %s", opt.write_dir.c_str());
    }

    std::string temp_dir;
    if (!bench::make_temp_dir("bodt-bench", temp_dir)) {
        std::fprintf(stderr, "bodt_bench: cannot make a temp dir %s: %s\n", temp_dir.c_str(), std::strerror(errno));
        return 1;
    }

    bench::CaseOptions copt;
    std::vector<std::string> notes;
    if (!opt.shared_dir.empty() && bench::is_dir(opt.shared_dir)) {
        copt.shared_dir = opt.shared_dir;
    } else {
        notes.push_back(opt.shared_dir.empty() ? "no shared folder: generated meshes only"
                                               : "shared folder " + opt.shared_dir +
                                                     " not found: generated meshes only");
    }
    copt.large = opt.large;
    copt.temp_dir = temp_dir;
    copt.extra_surfaces = opt.extra_surfaces;
    copt.extra_meshes = opt.extra_meshes;
    std::vector<Case> cases = bench::make_cases(copt, notes);
    bench::keep_cases_matching(cases, opt.case_regex);
    if (opt.list_only) {
        for (const auto& c : cases) std::printf("%-36s %-15s %s\n", c.name.c_str(), c.kind.c_str(), c.source.c_str());
        for (const auto& n : notes) std::printf("# %s\n", n.c_str());
        bench::remove_tree(temp_dir);
        return 0;
    }
    for (const auto& n : notes) std::fprintf(stderr, "bodt_bench: note: %s\n", n.c_str());

    const auto t_start = std::chrono::steady_clock::now();
    std::vector<Row> rows;
    for (size_t ci = 0; ci < cases.size(); ++ci) {
        const Case& c = cases[ci];
        Row row;
        row.c = &c;
        PreparedMesh pm;
        std::string err;
        const auto p0 = std::chrono::steady_clock::now();
        bool ok = false;
        try {
            ok = c.prepare(pm, err);
        } catch (const std::exception& e) {
            err = e.what();
        }
        const double prep_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - p0).count();
        row.note = pm.note;
        std::fprintf(stderr, "[%zu/%zu] %s (%s, %.1f s to make)%s%s\n", ci + 1, cases.size(), c.name.c_str(),
                     c.kind.c_str(), prep_s, ok ? "" : ": cannot be made: ", ok ? "" : err.c_str());
        if (!ok) {
            row.prep_error = err;
            for (const Variant& v : opt.variants) {
                RunResult r = empty_result();
                SET(r.status, "error");
                SET(r.where, "making the case");
                SET(r.message, err);
                row.runs.push_back(r);
                std::fprintf(json, "%s\n", result_json(c, pm.note, v, r, opt).c_str());
            }
            std::fflush(json);
            rows.push_back(std::move(row));
            continue;
        }
        for (const Variant& v : opt.variants) {
            const RunResult r = run_isolated(c, pm, v, opt);
            row.runs.push_back(r);
            std::fprintf(json, "%s\n", result_json(c, pm.note, v, r, opt).c_str());
            std::fflush(json);
            if (r.has_after)
                std::fprintf(stderr,
                             "    %-11s %-7s %2d steps %8.3f s  min %6.2f -> %6.2f  max %6.2f -> %6.2f  H %.2e"
                             "  V %d -> %d  flips %" PRId64 " ins %" PRId64 " coll %" PRId64 "\n",
                             v.name.c_str(), r.status, r.steps_done, r.time_s, r.before.min_dihedral,
                             r.after.min_dihedral, r.before.max_dihedral, r.after.max_dihedral, r.hausdorff_rel,
                             r.before.vertices, r.after.vertices, r.flips, r.inserted, r.collapsed);
            else
                std::fprintf(stderr, "    %-11s %s\n", v.name.c_str(), r.status);
        }
        rows.push_back(std::move(row));
        // the decompressed copy is not needed any more
        if (pm.from_file && pm.path.compare(0, temp_dir.size(), temp_dir) == 0) {
            bench::remove_tree(temp_dir);
            mkdir(temp_dir.c_str(), 0700);
        }
    }
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    bench::remove_tree(temp_dir);

    if (json != stdout) std::fclose(json);
    if (!opt.markdown_path.empty() && !bench::write_text_file(opt.markdown_path, markdown(rows, opt, notes, total_s)))
        std::fprintf(stderr, "bodt_bench: cannot write %s: %s\n", opt.markdown_path.c_str(), std::strerror(errno));
    return 0;
}
