// bodt_bench -- the benchmark of libbodt.
//
// For every case (a tet mesh: TetGen meshes of surfaces, mesh files, a random
// sphere, jittered boxes; with --scale the jittered and stretched boxes of
// 1e4 to 1e7 tets, and the jittered ones numbered at random) and every
// variant (a mode plus the operations a step does, BODT_PARAM_OPS, and the
// threads of a sweep, BODT_PARAM_THREADS) it creates the mesh through the
// public C API, sets the mode and the operations, runs a fixed number of
// bodt_step calls, and records the quality before and after, the counts
// before and after (flips and insertions change them), the relative
// Hausdorff distance of the boundary, the wall time of the create and of
// the steps alone, the minimum angle after every step, the memory the mesh
// takes in the library and the peak memory.  Everything after the run is
// measured on the mesh the handle holds then (its counts, tets and
// boundary), never on the input arrays.
//
// The peers -- TetGen's and Gmsh's optimisers (peers.hpp) -- run on the same
// inputs as further variants: the input is written to a file, the peer's
// output read back with bodt_mesh_read and measured by the same code.  From
// the per-step minimum angles comes the time our run needed to beat each
// peer's final minimum angle.
//
// One JSON object per case and variant goes to stdout (or --json FILE), and a
// last line with the targets of the issue (measured value, bar, PASS/FAIL);
// a markdown summary to --markdown FILE.  Each run happens in a forked child,
// so a crash or a hang of the library is reported and the bench goes on.
//
// Only the public API (bodt.h) is used for the runs; the --param table
// (param_table) and the exact Hausdorff distance are the bodt command's
// (src/cli/args.hpp, src/cli/hausdorff.hpp).  Modes are taken by value; a
// mode or an operation set the library refuses is "unsupported".

#include "bodt.h"

#include "bench_util.hpp"
#include "cases.hpp"
#include "cli/args.hpp"
#include "cli/hausdorff.hpp"
#include "peers.hpp"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

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
#include <thread>
#include <utility>
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
using bench::PeerKind;
using bench::PreparedMesh;
using bodt_cli::ParamInfo;

// A variant: a mode (by value) and the operations of a step (BODT_PARAM_OPS;
// kOpsDefault leaves the library's default for the mode, which is
// SMOOTH | FLIP | INSERT for BODT_MODE_BODT, SMOOTH | FLIP for
// BODT_MODE_OPT_WEIGHTED and SMOOTH otherwise), and BODT_PARAM_THREADS
// (kThreadsUnset: the library's default); or a peer.
constexpr int kOpsDefault = -1;
constexpr int kThreadsUnset = -1;
struct Variant {
    std::string name;
    int mode;
    int ops;
    PeerKind peer;
    int threads;
    std::string base;  // the name before any @threads suffix
    Variant(const std::string& n, int m, int o, PeerKind p = PeerKind::None)
        : name(n), mode(m), ops(o), peer(p), threads(kThreadsUnset), base(n) {}
    bool is_peer() const { return peer != PeerKind::None; }
};
const Variant kVariants[] = {{"laplace", BODT_MODE_LAPLACE, kOpsDefault},
                             {"odt", BODT_MODE_ODT, kOpsDefault},
                             {"bodt-basic", BODT_MODE_BODT_BASIC, kOpsDefault},
                             {"bodt-smooth", BODT_MODE_BODT, BODT_OP_SMOOTH},
                             {"bodt", BODT_MODE_BODT, kOpsDefault},
                             // Tournois et al.'s natural ODT (paper 000's comparison)
                             {"nodt", BODT_MODE_NODT, kOpsDefault},
                             // paper 001: "improved smoothing" alone, and the
                             // "combined" method (smoothing + Algorithm 4 swaps)
                             {"opt-smooth", BODT_MODE_OPT_WEIGHTED, BODT_OP_SMOOTH},
                             {"opt", BODT_MODE_OPT_WEIGHTED, kOpsDefault}};
// By name only: paper 002's mode is meant for deformed meshes (bench/run
// --deformed measures it there).
const Variant kOptInVariants[] = {{"phased", BODT_MODE_PHASED_ODT, kOpsDefault}};
const PeerKind kPeers[] = {PeerKind::TetGen, PeerKind::Gmsh, PeerKind::GmshNetgen};

// The mode's name as the bodt command spells it (bodt improve --mode).
const char* mode_name(int mode) {
    switch (mode) {
        case BODT_MODE_LAPLACE: return "laplace";
        case BODT_MODE_ODT: return "odt";
        case BODT_MODE_BODT_BASIC: return "bodt-basic";
        case BODT_MODE_BODT: return "bodt";
        case BODT_MODE_OPT_WEIGHTED: return "opt-weighted";
        case BODT_MODE_PHASED_ODT: return "phased";
        case BODT_MODE_NODT: return "nodt";
        default: return "unknown";
    }
}

// The operations a step does, as the library documents its default.
int effective_ops(int mode, int ops) {
    if (ops != kOpsDefault) return ops;
    switch (mode) {
        case BODT_MODE_BODT:
        case BODT_MODE_PHASED_ODT: return BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT | BODT_OP_COLLAPSE;
        case BODT_MODE_OPT_WEIGHTED: return BODT_OP_SMOOTH | BODT_OP_FLIP;
        default: return BODT_OP_SMOOTH;
    }
}

// The library's parameters for --param NAME=VALUE: the bodt command's table
// (NAME is the lower-case suffix of BODT_PARAM_*, the type that of the key).
// BODT_PARAM_OPS is in it but belongs to the variants (--param ops=LIST is
// --ops LIST).
const std::vector<ParamInfo>& param_list() { return bodt_cli::param_table(); }
constexpr size_t kMaxParams = 48;  // RunResult's fixed array (checked in main)

size_t param_index(int key) {
    for (size_t i = 0; i < param_list().size(); ++i)
        if (param_list()[i].key == key) return i;
    return param_list().size();
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

// The threads a sweep uses for BODT_PARAM_THREADS = requested, as the
// library documents it: 0 is OMP_NUM_THREADS when set, or else every
// core.  (Whether the sweeps really share the work shows in the CPU time:
// `parallelism` = CPU seconds / wall seconds of the steps.)
int threads_for(int requested) {
    if (requested > 0) return requested;
    if (const char* e = std::getenv("OMP_NUM_THREADS")) {
        const int n = std::atoi(e);
        if (n > 0) return n;
    }
    const unsigned hc = std::thread::hardware_concurrency();
    return hc > 0 ? int(hc) : 1;
}

// "@1", "@all" (0), "@4".
std::string threads_suffix(int t) { return t == 0 ? "@all" : "@" + std::to_string(t); }

// ---------------------------------------------------------------- options

// One --param (or --never-worse, --keep-surface, --bad-angle).
struct ParamSetting {
    size_t index;  // into param_list()
    double value;  // an int parameter's value as a double
};

struct Options {
    std::vector<Variant> variants;
    bool modes_given = false;
    bool no_peers = false;
    int iterations = 20;
    bool ops_override = false;  // --ops given: every variant gets ops
    int ops = kOpsDefault;
    std::vector<ParamSetting> params;  // set for every variant, in this order; one per key
    std::vector<int> threads;          // --threads: every variant once per value
    std::string json_path, markdown_path, write_dir;
    std::string shared_dir = BODT_BENCH_DEFAULT_SHARED;
    bool large = false;
    bool scale = false;
    double scale_max = 1e6;
    bool hausdorff = true;
    bool fork_runs = true;
    // Runs of a variant on a case below kRepeatBelowTets tets: the median
    // time of this many is kept (0: 5 with --scale, else 1).
    int repeat_small = 0;
    bool list_only = false;
    int timeout_s = 900;
    int peer_timeout_s = 300;
    std::string case_regex;
    std::vector<std::string> extra_surfaces, extra_meshes;
    std::string temp_dir;  // set by main: where peers write their files
};

void usage(FILE* f) {
    std::string param_names;
    size_t k = 0;
    for (const ParamInfo& p : param_list()) {
        if (p.key == BODT_PARAM_OPS) continue;
        if (k % 4 == 0) param_names += k ? ",\n                       " : "\n                       ";
        else param_names += ", ";
        param_names += p.name;
        param_names += p.is_int ? " (int)" : "";
        ++k;
    }
    std::fprintf(f,
                 "usage: bodt_bench [options]\n"
                 "  --modes LIST         comma-separated variants: laplace, odt, bodt-basic,\n"
                 "                       bodt-smooth (mode bodt, ops smooth: the 0.2 behaviour),\n"
                 "                       bodt (mode bodt, its default ops smooth+flip+insert+collapse),\n"
                 "                       nodt (natural ODT), opt-smooth (mode opt-weighted, ops\n"
                 "                       smooth: paper 001's improved smoothing), opt (mode\n"
                 "                       opt-weighted, its default ops smooth+flip: paper 001's\n"
                 "                       combined method), phased (paper 002's mode; not in the\n"
                 "                       default list), or mode values (with the mode's default\n"
                 "                       ops); and the peers tetgen-rO9/7 (tetgen %s),\n"
                 "                       gmsh (Gmsh's default optimiser), gmsh-netgen (Gmsh's\n"
                 "                       Netgen optimiser)\n"
                 "                       (default: laplace,odt,bodt-basic,bodt-smooth,bodt,nodt,\n"
                 "                       opt-smooth,opt and the peers found here; with --scale:\n"
                 "                       bodt-smooth,bodt)\n"
                 "  --no-peers           leave the peers out of the default list\n"
                 "  --ops LIST           BODT_PARAM_OPS for every variant: 'default', an integer, or\n"
                 "                       '+' or ',' separated of smooth,flip,insert,collapse\n"
                 "  --threads LIST       run every variant once per value of BODT_PARAM_THREADS\n"
                 "                       (comma-separated, 0 = every core), named VARIANT@1,\n"
                 "                       VARIANT@all, ... (default: not set; with --scale: 1,0)\n"
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
                 "  --large              add the ~1e5-tet jittered box, the ~1.5e5-tet lazy cube and the\n"
                 "                       6420-point random sphere\n"
                 "  --scale              the scale series instead: jittered and stretched (x 1.5) Kuhn\n"
                 "                       boxes of ~1e4, 1e5, 1e6 (and 1e7) tets, and up to 1e6 tets\n"
                 "                       the jittered ones numbered at random (.shuffled)\n"
                 "  --scale-max TETS     largest box of --scale (default 1e6; 1e7 adds the 1e7-tet box)\n"
                 "  --no-hausdorff       skip the Hausdorff distance (null in the output)\n"
                 "  --cases REGEX        only cases whose name matches (ECMAScript regex, searched)\n"
                 "  --surface FILE       add a closed .off/.stl surface (TetGen -pQ and -pqQ)\n"
                 "  --mesh FILE          add a tet mesh file (.mesh, .node/.ele, .vtk, .vtu, .msh, optionally .gz)\n"
                 "  --timeout SECONDS    per case and variant (default 900, with --scale 3600; 0 = none)\n"
                 "  --peer-timeout SECONDS  a peer's process is killed after this (default 300, at most\n"
                 "                       --timeout - 30; 0 = --timeout - 30)\n"
                 "  --repeat-small N     run each variant N times on a case below 2e5 tets and keep\n"
                 "                       the run of median time (default 5 with --scale, else 1;\n"
                 "                       the peers run once)\n"
                 "  --no-fork            run in this process (for debuggers; a crash ends the bench)\n"
                 "  --list               list the cases and exit\n"
                 "  --help\n"
                 "exit status: 0 (also when some runs fail or a target is missed; see their status), 2 usage "
                 "error\n",
                 bench::kTetGenSwitches, param_names.c_str(),
                 BODT_BENCH_DEFAULT_SHARED[0] ? BODT_BENCH_DEFAULT_SHARED : "none");
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
    size_t idx = param_list().size();
    for (size_t i = 0; i < param_list().size(); ++i)
        if (name == param_list()[i].name && param_list()[i].key != BODT_PARAM_OPS) idx = i;
    if (idx == param_list().size())
        usage_error("%s: unknown parameter '%s' (see --param below)", option, name.c_str());
    double v = 0;
    if (param_list()[idx].is_int) {
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

Variant peer_variant(PeerKind k) { return Variant(bench::peer_name(k), 0, kOpsDefault, k); }

Options parse_args(int argc, char** argv) {
    Options o;
    bool timeout_given = false;
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
            o.modes_given = true;
            for (const std::string& name : split_list(value(i), ",")) {
                bool found = false;
                for (const Variant& v : kVariants)
                    if (name == v.name) o.variants.push_back(v), found = true;
                for (const Variant& v : kOptInVariants)
                    if (name == v.name) o.variants.push_back(v), found = true;
                for (PeerKind k : kPeers)
                    if (name == bench::peer_name(k)) o.variants.push_back(peer_variant(k)), found = true;
                int mval = 0;
                if (!found && parse_int(name.c_str(), mval) && mval > 0) {  // a mode by its value
                    o.variants.push_back({"mode" + name, mval, kOpsDefault});
                    found = true;
                }
                if (!found) {
                    std::string known;
                    for (const Variant& v : kVariants) known += v.name + ", ";
                    for (const Variant& v : kOptInVariants) known += v.name + ", ";
                    for (PeerKind k : kPeers) known += std::string(bench::peer_name(k)) + ", ";
                    usage_error("unknown variant '%s' (%sor a mode value)", name.c_str(), known.c_str());
                }
            }
            if (o.variants.empty()) usage_error("--modes needs at least one variant");
        } else if (a == "--no-peers") {
            o.no_peers = true;
        } else if (a == "--ops") {
            parse_ops(o, value(i));
        } else if (a == "--threads") {
            o.threads.clear();
            for (const std::string& t : split_list(value(i), ",")) {
                int n = 0;
                if (!parse_int(t.c_str(), n) || n < 0) usage_error("--threads takes counts >= 0, got '%s'", t.c_str());
                if (std::find(o.threads.begin(), o.threads.end(), n) == o.threads.end()) o.threads.push_back(n);
            }
            if (o.threads.empty()) usage_error("--threads needs at least one count");
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
        } else if (a == "--scale") {
            o.scale = true;
        } else if (a == "--scale-max") {
            if (!parse_double(value(i), o.scale_max) || o.scale_max < 1e4)
                usage_error("--scale-max needs a tet count >= 1e4 (e.g. 1e7)");
        } else if (a == "--no-hausdorff") {
            o.hausdorff = false;
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
            timeout_given = true;
        } else if (a == "--peer-timeout") {
            if (!parse_int(value(i), o.peer_timeout_s) || o.peer_timeout_s < 0)
                usage_error("--peer-timeout needs seconds >= 0");
        } else if (a == "--repeat-small") {
            if (!parse_int(value(i), o.repeat_small) || o.repeat_small < 1 || o.repeat_small > 99)
                usage_error("--repeat-small needs a whole number from 1 to 99");
        } else if (a == "--no-fork") {
            o.fork_runs = false;
        } else if (a == "--list") {
            o.list_only = true;
        } else {
            usage_error("unknown argument '%s'", a.c_str());
        }
    }
    if (o.variants.empty()) {
        if (o.scale) {
            for (const Variant& v : kVariants)
                if (v.name == "bodt-smooth" || v.name == "bodt") o.variants.push_back(v);
        } else {
            o.variants.assign(std::begin(kVariants), std::end(kVariants));
            if (!o.no_peers)
                for (PeerKind k : kPeers) o.variants.push_back(peer_variant(k));
        }
    }
    if (o.no_peers) {
        std::vector<Variant> kept;
        for (const Variant& v : o.variants)
            if (!v.is_peer()) kept.push_back(v);
        o.variants.swap(kept);
        if (o.variants.empty()) usage_error("--no-peers leaves no variant");
    }
    if (o.scale && o.threads.empty()) o.threads = {1, 0};
    if (o.scale && !timeout_given) o.timeout_s = 3600;  // the 1e7-tet runs
    for (Variant& v : o.variants) {
        v.base = v.name;
        if (o.ops_override && !v.is_peer()) v.ops = o.ops;
    }
    if (!o.threads.empty()) {  // every variant of ours once per thread count
        std::vector<Variant> expanded;
        for (const Variant& v : o.variants) {
            if (v.is_peer()) {
                expanded.push_back(v);
                continue;
            }
            for (int t : o.threads) {
                Variant w = v;
                w.threads = t;
                w.name = v.name + threads_suffix(t);
                expanded.push_back(w);
            }
        }
        o.variants.swap(expanded);
    }
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
        if (param_list()[ps.index].key == key) return &ps;
    return nullptr;
}

// Refuse, before any case is made, a parameter value the library refuses
// (range, or a key this library does not know): set each on a one-tet mesh.
void check_params(const Options& o) {
    if (o.params.empty() && o.threads.empty()) return;
    const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int32_t tet[4] = {0, 1, 2, 3};
    bodt_mesh* m = nullptr;
    if (bodt_mesh_create(4, xyz, 1, tet, 0, &m) != BODT_OK) return;  // cannot check: the runs will say
    for (const ParamSetting& ps : o.params) {
        const ParamInfo& p = param_list()[ps.index];
        const int st = p.is_int ? bodt_set_param_int(m, p.key, int32_t(ps.value))
                                : bodt_set_param_double(m, p.key, ps.value);
        if (st != BODT_OK) {
            const std::string msg = bodt_mesh_last_error(m);
            bodt_mesh_destroy(m);
            usage_error("%s=%s: refused by libbodt: %s", p.name, param_value_string(p, ps.value).c_str(),
                        msg.c_str());
        }
    }
    for (int t : o.threads)
        if (bodt_set_param_int(m, BODT_PARAM_THREADS, t) != BODT_OK) {
            const std::string msg = bodt_mesh_last_error(m);
            bodt_mesh_destroy(m);
            usage_error("--threads %d: refused by libbodt: %s", t, msg.c_str());
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

// Steps whose minimum angle and cumulative time are kept (for time_to_beat).
constexpr int kMaxTrace = 256;

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
    double params[kMaxParams];  // every parameter of param_list() as read back, NaN unknown
    int32_t threads_requested;  // BODT_PARAM_THREADS set (kThreadsUnset: not set)
    int32_t threads_used;       // threads_for() of the value read back
    int32_t has_before, has_after;
    Stats before, after;
    double volume_change_rel;
    double region_volume_change_rel_max;  // max over regions of |dV_r| / |V_r|
    int32_t regions;
    double hausdorff_abs, hausdorff_rel, hausdorff_rel_upper, bbox_side;
    double time_s, cpu_s, hausdorff_time_s;
    int32_t repeats;  // runs made, the one kept of median time_s
    double create_s;  // bodt_mesh_create (with the boundary faces) or bodt_mesh_read, NaN for a peer
    int64_t vertices_moved, moves_rejected, moves_shortened;
    int64_t flips, inserted, collapsed;  // sums over the steps
    int32_t vertices_changed;            // -1: not comparable (a peer renumbered)
    double last_max_move;
    double updates_per_s;
    // memory: heap growth (bytes) across bodt_mesh_create / _read, and that
    // plus the growth from bodt_set_mode to the end of the steps; RSS growth
    // across the create (NaN unknown)
    double lib_bytes_create, lib_bytes_after, rss_bytes_create;
    double peak_rss_mb;
    // the minimum dihedral angle after each step and the time of the steps
    // up to it (min(steps, kMaxTrace) entries)
    int32_t trace_n;
    double trace_min[kMaxTrace];
    double trace_t[kMaxTrace];
    // peers
    char peer_command[512];
    char time_source[96];
    double peer_refine_s, peer_process_s;
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
    r.threads_requested = kThreadsUnset;
    r.threads_used = -1;
    r.bad_angle = NAN;
    for (double& v : r.params) v = NAN;
    r.volume_change_rel = r.region_volume_change_rel_max = r.hausdorff_abs = r.hausdorff_rel = NAN;
    r.hausdorff_rel_upper = r.bbox_side = NAN;
    r.cpu_s = r.create_s = r.lib_bytes_create = r.lib_bytes_after = r.rss_bytes_create = NAN;
    r.peer_refine_s = r.peer_process_s = NAN;
    return r;
}

// ----------------------------------------------------------- one run

// Quality, counts and boundary surface (faces of one tet, 0-based, with all
// the mesh's vertices) of the mesh as it is now.  Returns BODT_OK or the
// status of the call named in where.
int measure(const bodt_mesh* m, Stats& s, bodt_cli::TriangleSurface& surf, std::vector<int32_t>& tets, int index_base,
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
    {
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
    }
    surf.xyz.resize(3 * size_t(nv));
    if ((st = bodt_mesh_get_vertices(m, surf.xyz.data(), surf.xyz.size())) != BODT_OK)
        return where = "bodt_mesh_get_vertices", st;
    tets.resize(4 * size_t(nt));
    if ((st = bodt_mesh_get_tets(m, tets.data(), tets.size())) != BODT_OK) return where = "bodt_mesh_get_tets", st;
    surf.triangles = bench::boundary_triangles(tets, index_base);
    s.boundary_faces = int32_t(surf.triangles.size() / 3);
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

// A file name for a case or variant name ("tetgen-rO9/7" has a slash).
std::string file_safe(std::string s) {
    for (char& c : s)
        if (c == '/' || c == ' ') c = '_';
    return s;
}

// The comparison of the mesh after a run (ours or a peer's) with the input:
// counts, volumes, the Hausdorff distance of the boundary, the vertices that
// moved.  before_surf and reg_before describe the input.
int compare_with_input(const bodt_mesh* after_mesh, RunResult& r, const bodt_cli::TriangleSurface& before_surf,
                       const std::map<int32_t, double>& reg_before, int index_base, const Options& opt,
                       std::string& where) {
    bodt_cli::TriangleSurface after_surf;
    std::vector<int32_t> tets;
    int st;
    if ((st = measure(after_mesh, r.after, after_surf, tets, index_base, where)) != BODT_OK) return st;
    r.has_after = 1;
    // input vertices whose coordinates changed (appended ones are not
    // counted); a peer's output with another vertex count is not comparable
    // vertex by vertex
    r.vertices_changed = 0;
    if (r.peer_command[0] && after_surf.xyz.size() != before_surf.xyz.size()) {
        r.vertices_changed = -1;
    } else {
        const size_t common = std::min(before_surf.xyz.size(), after_surf.xyz.size()) / 3;
        for (size_t v = 0; v < common; ++v)
            if (before_surf.xyz[3 * v] != after_surf.xyz[3 * v] ||
                before_surf.xyz[3 * v + 1] != after_surf.xyz[3 * v + 1] ||
                before_surf.xyz[3 * v + 2] != after_surf.xyz[3 * v + 2])
                ++r.vertices_changed;
    }
    r.volume_change_rel = (r.after.volume - r.before.volume) / std::fabs(r.before.volume);
    std::map<int32_t, double> reg_after;
    if ((st = region_volumes(after_mesh, reg_after, where)) != BODT_OK) return st;
    bool same_regions = reg_after.size() == reg_before.size();
    for (const auto& kv : reg_before) same_regions = same_regions && reg_after.count(kv.first);
    r.region_volume_change_rel_max = same_regions ? 0.0 : NAN;  // a peer may drop the region ids
    if (same_regions)
        for (const auto& kv : reg_before)
            r.region_volume_change_rel_max = std::max(
                r.region_volume_change_rel_max, std::fabs(reg_after.at(kv.first) - kv.second) / std::fabs(kv.second));
    // The symmetric Hausdorff distance of the boundaries as `bodt compare`
    // measures it (exact branch and bound, src/cli/hausdorff.hpp): tolerance
    // 1e-7 L + 1e-3 H, the same budget of distance queries, distances below
    // 1e-14 L are 0; L = the largest side of the input boundary's box.
    r.bbox_side = bench::bbox_largest_side(before_surf.xyz, before_surf.triangles);
    if (opt.hausdorff) {
        const auto h0 = std::chrono::steady_clock::now();
        const int64_t budget =
            300000 + 20 * int64_t(before_surf.triangles.size() + after_surf.triangles.size()) / 3;
        const bodt_cli::HausdorffBounds h =
            bodt_cli::hausdorff_distance(before_surf, after_surf, 1e-7 * r.bbox_side, 1e-3, budget);
        const double zero = 1e-14 * r.bbox_side;
        r.hausdorff_abs = h.lower <= zero ? 0.0 : h.lower;
        const double upper = h.upper <= zero ? 0.0 : h.upper;
        r.hausdorff_rel = r.bbox_side > 0 ? r.hausdorff_abs / r.bbox_side : NAN;
        r.hausdorff_rel_upper = r.bbox_side > 0 ? upper / r.bbox_side : NAN;
        r.hausdorff_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - h0).count();
    }
    return BODT_OK;
}

double cpu_seconds() {
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

// release_inputs: free the input arrays once the handle holds the mesh (in a
// forked child, whose copy they are), so the child's memory is the
// library's and the measurement's.
RunResult run_one(const Case& c, PreparedMesh& pm, const Variant& var, const Options& opt, bool release_inputs) {
    RunResult r = empty_result();
    r.threads_requested = var.threads;
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
    const int64_t heap0 = bench::heap_in_use(), rss0 = bench::rss_bytes();
    const auto create0 = std::chrono::steady_clock::now();
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
    const double create_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - create0).count();
    const int64_t heap1 = bench::heap_in_use(), rss1 = bench::rss_bytes();
    if (!var.is_peer()) r.create_s = create_s;
    if (heap0 >= 0 && heap1 >= 0) r.lib_bytes_create = double(heap1 - heap0);
    if (rss0 >= 0 && rss1 >= 0) r.rss_bytes_create = double(rss1 - rss0);
    if (release_inputs) {
        std::vector<double>().swap(pm.arrays.xyz);
        std::vector<int32_t>().swap(pm.arrays.tets);
        std::vector<int32_t>().swap(pm.arrays.faces);
        std::vector<int32_t>().swap(pm.arrays.markers);
    }

    bodt_cli::TriangleSurface before_surf;
    std::string where;
    {
        std::vector<int32_t> tets;
        if ((st = measure(mh.m, r.before, before_surf, tets, index_base, where)) != BODT_OK)
            return fail("error", where, errmsg(mh.m, st));
    }
    r.has_before = 1;
    std::map<int32_t, double> reg_before;
    if ((st = region_volumes(mh.m, reg_before, where)) != BODT_OK) return fail("error", where, errmsg(mh.m, st));
    r.regions = int32_t(reg_before.size());

    if (!opt.write_dir.empty()) {
        const std::string in_path = opt.write_dir + "/" + c.name + ".input.mesh";
        struct stat sb;
        if (stat(in_path.c_str(), &sb) != 0 && (st = bodt_mesh_write(mh.m, in_path.c_str())) != BODT_OK)
            std::fprintf(stderr, "bodt_bench: %s: bodt_mesh_write %s: %s\n", c.name.c_str(), in_path.c_str(),
                         errmsg(mh.m, st).c_str());
    }

    // ---- a peer: its own process on the mesh written to a file
    if (var.is_peer()) {
        const std::string dir = opt.temp_dir + "/peer-" + std::to_string(getpid());
        mkdir(dir.c_str(), 0700);
        // the peer's own limit, below the child's (which would leave no result)
        double timeout = opt.timeout_s <= 0 ? 0.0 : opt.timeout_s > 60 ? opt.timeout_s - 30.0 : 0.8 * opt.timeout_s;
        if (opt.peer_timeout_s > 0 && (timeout <= 0 || opt.peer_timeout_s < timeout)) timeout = opt.peer_timeout_s;
        const bench::PeerOutcome po = bench::run_peer(var.peer, mh.m, dir, timeout);
        SET(r.peer_command, po.command.empty() ? std::string(bench::peer_name(var.peer)) : po.command);
        SET(r.time_source, po.time_source);
        r.peer_process_s = po.process_s;
        r.peer_refine_s = po.refine_s >= 0 ? po.refine_s : NAN;
        r.peak_rss_mb = po.peak_rss_mb;  // the peer's process (run_isolated keeps it)
        if (po.status != "ok") {
            bench::remove_tree(dir);
            if (po.status == "unsupported") {
                SET(r.status, "unsupported");
                SET(r.where, po.where);
                SET(r.message, po.message);
                return r;
            }
            return fail(po.status.c_str(), po.where, po.message);
        }
        r.time_s = po.time_s;
        bench::MeshHandle out;
        st = bodt_mesh_read(po.output_path.c_str(), &out.m);
        if (st != BODT_OK) {
            const std::string msg = errmsg(nullptr, st);
            bench::remove_tree(dir);
            return fail("error", "bodt_mesh_read (the peer's output)", msg);
        }
        bench::remove_tree(dir);
        if ((st = compare_with_input(out.m, r, before_surf, reg_before, 0, opt, where)) != BODT_OK)
            return fail("error", where, errmsg(out.m, st));
        if (!opt.write_dir.empty()) {
            const std::string out_path = opt.write_dir + "/" + c.name + "." + file_safe(var.name) + ".mesh";
            if ((st = bodt_mesh_write(out.m, out_path.c_str())) != BODT_OK)
                std::fprintf(stderr, "bodt_bench: %s / %s: bodt_mesh_write %s: %s\n", c.name.c_str(),
                             var.name.c_str(), out_path.c_str(), errmsg(out.m, st).c_str());
        }
        return r;
    }

    auto unsupported = [&](const char* call) {
        SET(r.status, "unsupported");
        SET(r.where, call);
        SET(r.message, errmsg(mh.m, st));
        return r;
    };
    const int64_t heap_p0 = bench::heap_in_use();
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
        const ParamInfo& p = param_list()[ps.index];
        const std::string call = std::string(p.is_int ? "bodt_set_param_int(" : "bodt_set_param_double(") +
                                 param_macro(p).substr(11) + ")";
        st = p.is_int ? bodt_set_param_int(mh.m, p.key, int32_t(ps.value)) : bodt_set_param_double(mh.m, p.key, ps.value);
        if (st != BODT_OK) return fail("error", call, errmsg(mh.m, st));
    }
    if (var.threads != kThreadsUnset && (st = bodt_set_param_int(mh.m, BODT_PARAM_THREADS, var.threads)) != BODT_OK)
        return fail("error", "bodt_set_param_int(THREADS)", errmsg(mh.m, st));
    // every parameter as the run uses it
    for (size_t i = 0; i < param_list().size() && i < kMaxParams; ++i) {
        int32_t iv = 0;
        double dv = NAN;
        if (param_list()[i].is_int) {
            if (bodt_get_param_int(mh.m, param_list()[i].key, &iv) == BODT_OK) r.params[i] = iv;
        } else if (bodt_get_param_double(mh.m, param_list()[i].key, &dv) == BODT_OK) {
            r.params[i] = dv;
        }
    }
    auto read_back = [&](int key) {
        const size_t i = param_index(key);
        return i < kMaxParams ? r.params[i] : double(NAN);
    };
    if (std::isfinite(read_back(BODT_PARAM_NEVER_WORSE))) r.never_worse = int32_t(read_back(BODT_PARAM_NEVER_WORSE));
    if (std::isfinite(read_back(BODT_PARAM_KEEP_SURFACE)))
        r.keep_surface = int32_t(read_back(BODT_PARAM_KEEP_SURFACE));
    r.bad_angle = read_back(BODT_PARAM_BAD_ANGLE);
    const double threads_back = read_back(BODT_PARAM_THREADS);
    r.threads_used = threads_for(std::isfinite(threads_back) ? int(threads_back)
                                                              : (var.threads == kThreadsUnset ? 0 : var.threads));
    int32_t iv = -1;
    if (bodt_get_param_int(mh.m, BODT_PARAM_OPS, &iv) == BODT_OK) {
        r.ops = iv;
        r.ops_effective = effective_ops(var.mode, iv);
    }

    // The steps, and only they, are timed; each step's report carries the
    // minimum angle after it (computed inside the step), so the trace costs
    // no extra time.  A report without it (NaN) is completed by
    // bodt_mesh_quality outside the timed region.
    bool step_failed = false;
    std::string step_where, step_msg;
    const double cpu0 = cpu_seconds();
    double elapsed = 0.0;
    for (int i = 0; i < opt.iterations; ++i) {
        bodt_step_report rep = bench::sized_struct<bodt_step_report>();
        const auto t0 = std::chrono::steady_clock::now();
        st = bodt_step(mh.m, &rep);
        elapsed += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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
        if (r.trace_n < kMaxTrace) {
            double mn = rep.min_dihedral;
            if (!std::isfinite(mn)) {
                bodt_quality q = bench::sized_struct<bodt_quality>();
                mn = bodt_mesh_quality(mh.m, &q) == BODT_OK ? q.min_dihedral : NAN;
            }
            r.trace_min[r.trace_n] = mn;
            r.trace_t[r.trace_n] = elapsed;
            ++r.trace_n;
        }
    }
    r.cpu_s = cpu_seconds() - cpu0;
    const int64_t heap_e = bench::heap_in_use();
    if (std::isfinite(r.lib_bytes_create) && heap_p0 >= 0 && heap_e >= 0)
        r.lib_bytes_after = r.lib_bytes_create + double(heap_e - heap_p0);
    r.time_s = elapsed;
    r.updates_per_s = r.time_s > 0 ? double(r.vertices_moved + r.moves_rejected) / r.time_s : 0.0;

    // From here on only the mesh the handle holds now: the steps may have
    // added vertices (appended; input vertices keep their index), and
    // renumbered, added or removed tets and boundary faces.
    if ((st = compare_with_input(mh.m, r, before_surf, reg_before, index_base, opt, where)) != BODT_OK)
        return fail("error", where, errmsg(mh.m, st));

    if (!opt.write_dir.empty()) {
        const std::string out_path = opt.write_dir + "/" + c.name + "." + file_safe(var.name) + ".mesh";
        if ((st = bodt_mesh_write(mh.m, out_path.c_str())) != BODT_OK)
            std::fprintf(stderr, "bodt_bench: %s / %s: bodt_mesh_write %s: %s\n", c.name.c_str(), var.name.c_str(),
                         out_path.c_str(), errmsg(mh.m, st).c_str());
    }
    if (step_failed) fail("error", step_where, step_msg);
    return r;
}

// Runs run_one in a forked child (so a crash or hang is contained) and takes
// the peak RSS of that child (of the peer's process for a peer).
RunResult run_isolated(const Case& c, PreparedMesh& pm, const Variant& var, const Options& opt) {
    RunResult r = empty_result();
    const bench::ChildRun child = bench::run_isolated(r, opt.fork_runs, opt.timeout_s,
                                                      [&] { return run_one(c, pm, var, opt, opt.fork_runs); });
    if (!child.ok) {
        SET(r.status, child.status);
        SET(r.where, child.where);
        SET(r.message, child.message);
        if (child.status != "error")  // the child died; pipe and fork failures are only recorded
            std::fprintf(stderr, "bodt_bench: %s / %s: %s\n", c.name.c_str(), var.name.c_str(), r.message);
    }
    if (!var.is_peer() || !child.ok) r.peak_rss_mb = child.peak_rss_mb;
    return r;
}

// ------------------------------------------------------------------ output

double pct_30_140(const Stats& s) { return s.tets > 0 ? 100.0 * s.in30_140 / s.tets : NAN; }

double growth_pct(const RunResult& r) {
    return r.before.vertices > 0 ? 100.0 * (r.after.vertices - r.before.vertices) / r.before.vertices : NAN;
}

double bytes_per_tet(const RunResult& r) { return r.before.tets > 0 ? r.lib_bytes_create / r.before.tets : NAN; }
double bytes_per_tet_after(const RunResult& r) {
    return r.has_after && r.after.tets > 0 ? r.lib_bytes_after / r.after.tets : NAN;
}
double updates_per_thread(const RunResult& r) {
    return r.threads_used > 0 && r.time_s > 0 ? r.updates_per_s / r.threads_used : NAN;
}
double parallelism(const RunResult& r) { return r.time_s > 0 ? r.cpu_s / r.time_s : NAN; }

bool ran_ok(const RunResult& r) { return r.has_after && !std::strcmp(r.status, "ok"); }

// A run of a few tens of milliseconds varies by a fifth from run to run on
// a shared machine, and in target c's slope a 1e4-tet run weighs as much as
// a 1e6-tet one: below this many tets a variant runs opt.repeat_small
// times and the run of median time is kept (the runs differ only in their
// times: every result is deterministic).
constexpr int32_t kRepeatBelowTets = 200000;

int repeats_wanted(const Options& opt) { return opt.repeat_small > 0 ? opt.repeat_small : opt.scale ? 5 : 1; }

RunResult run_timed(const Case& c, PreparedMesh& pm, const Variant& var, const Options& opt) {
    std::vector<RunResult> runs{run_isolated(c, pm, var, opt)};
    const int wanted = repeats_wanted(opt);
    if (!var.is_peer() && ran_ok(runs[0]) && runs[0].before.tets < kRepeatBelowTets)
        while (static_cast<int>(runs.size()) < wanted) {
            runs.push_back(run_isolated(c, pm, var, opt));
            if (!ran_ok(runs.back())) {
                RunResult failed = runs.back();
                failed.repeats = static_cast<int32_t>(runs.size());
                return failed;
            }
        }
    std::sort(runs.begin(), runs.end(), [](const RunResult& a, const RunResult& b) { return a.time_s < b.time_s; });
    RunResult r = runs[runs.size() / 2];
    r.repeats = static_cast<int32_t>(runs.size());
    return r;
}

// When our run's minimum angle first exceeded the peer's final one: the
// time of the steps up to then; 0 when the input's already did; +inf when no
// step's did (within the steps traced); NaN when either did not run.
double time_to_beat(const RunResult& us, const RunResult& peer) {
    if (!ran_ok(us) || !ran_ok(peer)) return NAN;
    const double bar = peer.after.min_dihedral;
    if (us.before.min_dihedral > bar) return 0.0;
    for (int i = 0; i < us.trace_n; ++i)
        if (us.trace_min[i] > bar) return us.trace_t[i];
    return INFINITY;
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

struct Row {
    const Case* c;
    std::string note;
    std::string prep_error;
    std::vector<RunResult> runs;  // one per variant, in opt.variants order
};

std::string result_json(const Row& row, size_t m, const Options& opt) {
    const Case& c = *row.c;
    const Variant& var = opt.variants[m];
    const RunResult& r = row.runs[m];
    std::string o = "{";
    o += "\"case\":" + json_str(c.name);
    o += ",\"kind\":" + json_str(c.kind);
    o += ",\"source\":" + json_str(c.source);
    if (!row.note.empty()) o += ",\"note\":" + json_str(row.note);
    o += ",\"variant\":" + json_str(var.name);
    o += ",\"variant_base\":" + json_str(var.base);
    o += std::string(",\"peer\":") + (var.is_peer() ? "true" : "false");
    if (var.is_peer()) {
        o += ",\"mode\":\"peer\",\"mode_value\":null,\"ops_requested\":null,\"ops\":null,\"ops_names\":null";
        o += ",\"command\":" + json_str(r.peer_command);
        o += ",\"time_source\":" + json_str(r.time_source);
        o += ",\"peer_refine_s\":" + json_num(r.peer_refine_s, "%.4f");
        o += ",\"peer_process_s\":" + json_num(r.peer_process_s, "%.4f");
    } else {
        o += ",\"mode\":" + json_str(mode_name(var.mode));
        o += ",\"mode_value\":" + std::to_string(var.mode);
        o += ",\"ops_requested\":" + (var.ops == kOpsDefault ? std::string("null") : std::to_string(var.ops));
        o += ",\"ops\":" + (r.ops_effective >= 0 ? std::to_string(r.ops_effective) : std::string("null"));
        o += ",\"ops_names\":" + json_str(r.ops_effective >= 0 ? ops_string(r.ops_effective) : "unknown");
        o += ",\"threads\":" + (var.threads == kThreadsUnset ? std::string("null") : std::to_string(var.threads));
        o += ",\"threads_used\":" + (r.threads_used > 0 ? std::to_string(r.threads_used) : std::string("null"));
    }
    o += ",\"status\":" + json_str(r.status);
    if (r.where[0]) o += ",\"where\":" + json_str(r.where);
    if (r.message[0]) o += ",\"message\":" + json_str(r.message);
    o += ",\"library\":" + json_str(bodt_version_string());
    o += ",\"iterations\":" + std::to_string(opt.iterations);
    o += ",\"steps_done\":" + std::to_string(r.steps_done);
    if (!var.is_peer()) {
        o += ",\"never_worse\":" + (r.never_worse >= 0 ? std::to_string(r.never_worse) : std::string("null"));
        o += ",\"keep_surface\":" + (r.keep_surface >= 0 ? std::to_string(r.keep_surface) : std::string("null"));
        o += ",\"bad_angle\":" + json_num(r.bad_angle);
        // what --param asked for, and every parameter as the run used it
        o += ",\"params\":{";
        for (size_t i = 0; i < opt.params.size(); ++i) {
            const ParamInfo& p = param_list()[opt.params[i].index];
            o += (i ? "," : "") + json_str(p.name) + ":" + param_value_string(p, opt.params[i].value);
        }
        o += "}";
        bool any_effective = false;
        for (double v : r.params) any_effective = any_effective || std::isfinite(v);
        if (any_effective) {
            o += ",\"params_effective\":{";
            for (size_t i = 0; i < param_list().size() && i < kMaxParams; ++i)
                o += (i ? "," : "") + json_str(param_list()[i].name) + ":" +
                     param_value_string(param_list()[i], r.params[i]);
            o += "}";
        }
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
        o += ",\"hausdorff_rel_upper\":" + json_num(r.hausdorff_rel_upper, "%.4e");
        o += ",\"hausdorff_abs\":" + json_num(r.hausdorff_abs, "%.4e");
        o += ",\"bbox_largest_side\":" + json_num(r.bbox_side);
        o += ",\"time_s\":" + json_num(r.time_s, "%.4f");
        o += ",\"repeats\":" + std::to_string(r.repeats);
        o += ",\"s_per_10k_tets\":" + json_num(r.before.tets > 0 ? r.time_s * 1e4 / r.before.tets : NAN, "%.4g");
        o += ",\"vertices_changed\":" + (r.vertices_changed >= 0 ? std::to_string(r.vertices_changed) : "null");
        o += ",\"hausdorff_time_s\":" + json_num(r.hausdorff_time_s, "%.3f");
        if (!var.is_peer()) {
            o += ",\"create_s\":" + json_num(r.create_s, "%.4f");
            o += ",\"cpu_time_s\":" + json_num(r.cpu_s, "%.4f");
            o += ",\"parallelism\":" + json_num(parallelism(r), "%.3f");
            o += ",\"vertices_moved\":" + std::to_string(r.vertices_moved);
            o += ",\"moves_rejected\":" + std::to_string(r.moves_rejected);
            o += ",\"moves_shortened\":" + std::to_string(r.moves_shortened);
            o += ",\"vertex_updates_per_s\":" + json_num(r.updates_per_s, "%.4g");
            o += ",\"updates_per_s_per_thread\":" + json_num(updates_per_thread(r), "%.4g");
            o += ",\"last_max_move\":" + json_num(r.last_max_move, "%.3e");
            o += ",\"lib_bytes_create\":" + json_num(r.lib_bytes_create, "%.0f");
            o += ",\"lib_bytes_after\":" + json_num(r.lib_bytes_after, "%.0f");
            o += ",\"rss_bytes_create\":" + json_num(r.rss_bytes_create, "%.0f");
            o += ",\"bytes_per_tet\":" + json_num(bytes_per_tet(r), "%.1f");
            o += ",\"bytes_per_tet_after\":" + json_num(bytes_per_tet_after(r), "%.1f");
            o += ",\"step_min_dihedral\":[";
            for (int i = 0; i < r.trace_n; ++i) o += (i ? "," : "") + json_num(r.trace_min[i], "%.4f");
            o += "],\"step_time_s\":[";
            for (int i = 0; i < r.trace_n; ++i) o += (i ? "," : "") + json_num(r.trace_t[i], "%.4f");
            o += "]";
            // the time to beat every peer that ran on this case (null: not
            // within the steps)
            std::string beat;
            for (size_t k = 0; k < row.runs.size() && k < opt.variants.size(); ++k) {
                if (!opt.variants[k].is_peer() || !ran_ok(row.runs[k])) continue;
                const double t = time_to_beat(r, row.runs[k]);
                beat += (beat.empty() ? "" : ",") + json_str(opt.variants[k].name) + ":" +
                        (std::isfinite(t) ? json_num(t, "%.4f") : std::string("null"));
            }
            o += ",\"time_to_beat_s\":{" + beat + "}";
        }
    }
    o += ",\"peak_rss_mb\":" + json_num(r.peak_rss_mb, "%.1f");
    return o + "}";
}

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

// The variant the peers are compared with: the first `bodt` (any threads),
// else the first of ours; nvar when there is none.
size_t main_variant(const Options& opt) {
    for (size_t m = 0; m < opt.variants.size(); ++m)
        if (opt.variants[m].base == "bodt") return m;
    for (size_t m = 0; m < opt.variants.size(); ++m)
        if (!opt.variants[m].is_peer()) return m;
    return opt.variants.size();
}

bool is_shared_case(const Case& c) { return c.kind == "tetgen-surface" || c.kind == "file"; }
bool is_box_case(const Case& c) { return c.kind == "box" || c.kind == "box-stretched" || c.kind == "box-shuffled"; }

// The scale series of a kind of box: its target id's suffix and what its boxes are.
std::pair<std::string, std::string> box_series(const std::string& kind) {
    if (kind == "box") return {"jitter", "jittered"};
    if (kind == "box-stretched") return {"stretch", "stretched"};
    return {"shuffled", "shuffled"};
}

std::string secs_cell(double s) {
    if (!std::isfinite(s)) return s > 0 ? "never" : "–";
    return s < 0.01 && s > 0 ? fmt("%.4f", s) : fmt("%.2f", s);
}

// ----------------------------------------------------------------- targets

struct Target {
    std::string id, what, value, bar, verdict, detail;
    double number = NAN;
};

std::string json_target(const Target& t) {
    return "{\"id\":" + json_str(t.id) + ",\"what\":" + json_str(t.what) + ",\"value\":" + json_str(t.value) +
           ",\"number\":" + json_num(t.number, "%.6g") + ",\"bar\":" + json_str(t.bar) +
           ",\"verdict\":" + json_str(t.verdict) + (t.detail.empty() ? "" : ",\"detail\":" + json_str(t.detail)) + "}";
}

constexpr double kUpdatesBar = 2e6;      // guarded B-ODT vertex updates / s / core on a 1M-tet mesh
constexpr double kBytesPerTetBar = 150;  // memory of a mesh in the library
constexpr double kSlopeBar = 1.10;       // time ~ tets^slope over the scale series

// The targets of the issue, measured in this run (those this run has no
// input for say so).  table receives the per-mesh table of target (d).
std::vector<Target> targets(const std::vector<Row>& rows, const Options& opt, std::string& scale_table,
                            std::string& beat_table) {
    std::vector<Target> out;
    const size_t nvar = opt.variants.size();

    // (a) guarded B-ODT vertex updates per second per core on the ~1M-tet box
    {
        const Row* box = nullptr;
        for (const Row& row : rows)
            if (row.c->kind == "box" && before_run(row) && before_run(row)->before.tets >= 500000 &&
                before_run(row)->before.tets <= 2000000)
                box = &row;
        for (int all = 0; all < 2; ++all) {
            Target t;
            t.id = all ? "a.all" : "a.1";
            t.what = std::string("B-ODT smoothing (bodt-smooth) vertex updates per second per thread on the ~1M-tet "
                                 "jittered box, ") + (all ? "all cores" : "1 thread");
            t.bar = ">= 2.0e6";
            const RunResult* r = nullptr;
            int threads_used = 0;
            if (box)
                for (size_t m = 0; m < nvar && m < box->runs.size(); ++m) {
                    const Variant& v = opt.variants[m];
                    if (v.base != "bodt-smooth" || !ran_ok(box->runs[m])) continue;
                    const bool one = v.threads == 1 || v.threads == kThreadsUnset;  // the library's default: 1
                    const bool every = v.threads == 0;
                    if ((all && every) || (!all && one)) {
                        r = &box->runs[m];
                        threads_used = r->threads_used;
                    }
                }
            if (!r) {
                t.value = "not measured";
                t.verdict = "NOT RUN";
                t.detail = "needs bodt-smooth on the ~1e6-tet box with --threads 1,0 (bench/run --scale)";
            } else {
                t.number = updates_per_thread(*r);
                t.value = fmt("%.3g updates/s/thread (%s, %d thread%s, %.3g updates/s, parallelism %.2f)", t.number,
                              box->c->name.c_str(), threads_used, threads_used == 1 ? "" : "s", r->updates_per_s,
                              parallelism(*r));
                t.verdict = t.number >= kUpdatesBar ? "PASS" : "FAIL";
            }
            out.push_back(t);
        }
    }

    // (b) bytes per tet of the largest mesh in the library
    {
        Target t;
        t.id = "b";
        t.what = "memory of a mesh in the library, bytes per tet, on the largest mesh of this run";
        t.bar = "<= 150";
        const Row* big = nullptr;
        for (const Row& row : rows) {
            bool ours = false;
            for (size_t m = 0; m < nvar && m < row.runs.size(); ++m)
                ours = ours || (!opt.variants[m].is_peer() && ran_ok(row.runs[m]) &&
                                std::isfinite(bytes_per_tet(row.runs[m])));
            if (ours && (!big || before_run(row)->before.tets > before_run(*big)->before.tets)) big = &row;
        }
        if (!big) {
            t.value = "not measured";
            t.verdict = "NOT RUN";
        } else {
            double create = 0, after = 0;
            for (size_t m = 0; m < nvar && m < big->runs.size(); ++m) {
                const RunResult& r = big->runs[m];
                if (opt.variants[m].is_peer() || !ran_ok(r)) continue;
                create = std::max(create, bytes_per_tet(r));
                if (std::isfinite(bytes_per_tet_after(r))) after = std::max(after, bytes_per_tet_after(r));
            }
            t.number = std::max(create, after);
            t.value = fmt("%.0f B/tet (%s, %d tets: %.0f after bodt_mesh_%s, at most %.0f after the steps of any "
                          "variant)",
                          t.number, big->c->name.c_str(), before_run(*big)->before.tets, create,
                          big->c->kind == "file" ? "read" : "create", after);
            t.verdict = t.number <= kBytesPerTetBar ? "PASS" : "FAIL";
        }
        out.push_back(t);
    }

    // (c) time linear in size: per variant and kind of box, a least-squares
    // slope of log(time) over log(tets) and the ratio of the s per 10k tets
    // at the largest size to those at the smallest
    {
        std::map<std::string, std::vector<std::pair<double, double>>> series;  // "variant|kind" -> (tets, s)
        std::vector<std::string> order;
        for (const Row& row : rows) {
            if (!is_box_case(*row.c)) continue;
            for (size_t m = 0; m < nvar && m < row.runs.size(); ++m) {
                const RunResult& r = row.runs[m];
                if (opt.variants[m].is_peer() || !ran_ok(r) || !(r.time_s > 0)) continue;
                const std::string key = opt.variants[m].name + "|" + row.c->kind;
                if (!series.count(key)) order.push_back(key);
                series[key].push_back({double(r.before.tets), r.time_s});
            }
        }
        bool any = false;
        scale_table.clear();
        for (const std::string& key : order) {
            auto pts = series[key];
            if (pts.size() < 2) continue;
            std::sort(pts.begin(), pts.end());
            any = true;
            double sx = 0, sy = 0, sxx = 0, sxy = 0;
            for (const auto& p : pts) {
                const double x = std::log(p.first), y = std::log(p.second);
                sx += x, sy += y, sxx += x * x, sxy += x * y;
            }
            const double n = double(pts.size());
            const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
            const double r_small = pts.front().second * 1e4 / pts.front().first;
            const double r_large = pts.back().second * 1e4 / pts.back().first;
            Target t;
            const std::string variant = key.substr(0, key.find('|')), kind = key.substr(key.find('|') + 1);
            t.id = "c." + variant + "." + box_series(kind).first;
            t.what = "time linear in size: " + variant + " on the " + box_series(kind).second + " boxes";
            t.number = slope;
            t.bar = fmt("log-log slope <= %.2f over 1e4..1e7 tets", kSlopeBar);
            t.value = fmt("slope %.3f over %.3g..%.3g tets; s per 10k tets %.3g -> %.3g (ratio %.2f)", slope,
                          pts.front().first, pts.back().first, r_small, r_large, r_large / r_small);
            t.verdict = slope <= kSlopeBar ? "PASS" : "FAIL";
            if (pts.back().first < 9e6) t.verdict += fmt(" (to %.3g tets only)", pts.back().first);
            out.push_back(t);
        }
        if (!any) {
            Target t;
            t.id = "c";
            t.what = "time linear in size from 1e4 to 1e7 tets";
            t.bar = fmt("log-log slope <= %.2f", kSlopeBar);
            t.value = "not measured";
            t.verdict = "NOT RUN";
            t.detail = "needs the scale series (bench/run --scale, --scale-max 1e7 for the 1e7-tet box)";
            out.push_back(t);
        }
        // the table: every box case and variant of ours
        std::string tb;
        for (const Row& row : rows) {
            if (!is_box_case(*row.c)) continue;
            for (size_t m = 0; m < nvar && m < row.runs.size(); ++m) {
                const RunResult& r = row.runs[m];
                if (opt.variants[m].is_peer()) continue;
                if (!ran_ok(r)) {
                    tb += fmt("| %s | %s | %s | | | | | | | | | | |\n", row.c->name.c_str(),
                              opt.variants[m].name.c_str(), r.status);
                    continue;
                }
                tb += fmt("| %s | %s | %d | %d | %.2f | %.2f | %.3g | %.3g | %.3g | %.2f | %.0f / %.0f | %.0f | "
                          "%.2f/%.2f |\n",
                          row.c->name.c_str(), opt.variants[m].name.c_str(), r.before.tets, r.threads_used, r.create_s,
                          r.time_s,
                          r.time_s * 1e4 / r.before.tets, r.updates_per_s, updates_per_thread(r), parallelism(r),
                          bytes_per_tet(r), bytes_per_tet_after(r), r.peak_rss_mb, r.after.min_dihedral,
                          r.after.max_dihedral);
            }
        }
        if (!tb.empty())
            scale_table = "| case | variant | tets | threads | create s | s | s / 10k tets | updates/s | "
                          "updates/s/thread | parallelism | B/tet create / after | peak RSS MB | min/max after |\n"
                          "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n" +
                          tb;
    }

    // (d) on every shared mesh, bodt reaches a better minimum angle than each
    // peer's final one in less time than the peer took
    {
        const size_t mv = main_variant(opt);
        int pairs = 0, passed = 0;
        std::string failed, unfinished;
        beat_table.clear();
        if (mv < nvar)
            for (const Row& row : rows) {
                if (!is_shared_case(*row.c) || mv >= row.runs.size()) continue;
                for (size_t k = 0; k < nvar && k < row.runs.size(); ++k) {
                    if (!opt.variants[k].is_peer()) continue;
                    if (!ran_ok(row.runs[k])) {
                        if (std::strcmp(row.runs[k].status, "unsupported") != 0)
                            unfinished += (unfinished.empty() ? "" : ", ") + row.c->name + " " +
                                          opt.variants[k].name + " " + row.runs[k].status;
                        continue;
                    }
                    const RunResult& p = row.runs[k];
                    const RunResult& us = row.runs[mv];
                    const double t = time_to_beat(us, p);
                    const bool ok = std::isfinite(t) && t < p.time_s;
                    ++pairs;
                    passed += ok;
                    if (!ok && pairs - passed <= 6)
                        failed += (failed.empty() ? "" : ", ") + row.c->name + " vs " + opt.variants[k].name;
                    beat_table += fmt("| %s | %s | %.2f | %.2f | %s | %s | %s | %s |\n", row.c->name.c_str(),
                                      opt.variants[k].name.c_str(), us.before.min_dihedral, p.after.min_dihedral,
                                      secs_cell(p.time_s).c_str(),
                                      ran_ok(us) ? fmt("%.2f", us.after.min_dihedral).c_str() : us.status,
                                      t == 0 ? "0 (the input)" : secs_cell(t).c_str(), ok ? "PASS" : "FAIL");
                }
            }
        if (!beat_table.empty()) {
            const std::string n = mv < nvar ? opt.variants[mv].name : "bodt";
            beat_table = "| mesh | peer | min before | peer's min | peer s | " + n + " min after | " + n +
                         " s to beat | |\n|---|---|---:|---:|---:|---:|---:|---|\n" + beat_table;
        }
        Target t;
        t.id = "d";
        t.what = "on every shared mesh, less time than each peer to reach a better minimum angle (" +
                 (mv < nvar ? opt.variants[mv].name : std::string("bodt")) + ")";
        t.bar = "every (mesh, peer) pair";
        if (pairs == 0) {
            t.value = "not measured";
            t.verdict = "NOT RUN";
            t.detail = "needs the shared meshes, bodt and a peer (tetgen, python3-gmsh)";
        } else {
            t.number = double(passed) / pairs;
            t.value = fmt("%d of %d (mesh, peer) pairs", passed, pairs);
            t.verdict = passed == pairs ? "PASS" : "FAIL";
            if (!failed.empty())
                t.detail = "missed: " + failed +
                           (pairs - passed > 6 ? fmt(" and %d more (the table below)", pairs - passed - 6) : "");
        }
        if (!unfinished.empty())
            t.detail += (t.detail.empty() ? "" : "; ") + std::string("not counted, the peer did not finish: ") + unfinished;
        out.push_back(t);
    }
    return out;
}

std::string markdown(const std::vector<Row>& rows, const Options& opt, const std::vector<std::string>& notes,
                     double total_s, const std::vector<Target>& tg, const std::string& scale_table,
                     const std::string& beat_table) {
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
        if (param_list()[ps.index].key != BODT_PARAM_NEVER_WORSE)
            md += fmt(", %s = %s", param_macro(param_list()[ps.index]).c_str(),
                      param_value_string(param_list()[ps.index], ps.value).c_str());
    if (!opt.threads.empty()) {
        md += ", BODT_PARAM_THREADS =";
        for (size_t i = 0; i < opt.threads.size(); ++i)
            md += fmt("%s %d%s", i ? "," : "", opt.threads[i], opt.threads[i] == 0 ? " (all cores)" : "");
    }
    md += fmt("; %u cores; %s; total %.0f s.\n\n", std::thread::hardware_concurrency(), date, total_s);

    // The operations each variant did (as read back from the library).
    std::vector<int> ops(nvar);
    for (size_t m = 0; m < nvar; ++m) {
        if (vars[m].is_peer()) {
            ops[m] = 0;
            continue;
        }
        ops[m] = effective_ops(vars[m].mode, vars[m].ops);
        for (const Row& row : rows)
            if (m < row.runs.size() && row.runs[m].ops_effective >= 0) {
                ops[m] = row.runs[m].ops_effective;
                break;
            }
    }
    md += "Variants:";
    for (size_t m = 0, k = 0; m < nvar; ++m) {
        if (vars[m].is_peer() || (m > 0 && vars[m].base == vars[m - 1].base)) continue;
        md += fmt("%s `%s` = mode %s, ops %s", k++ ? ";" : "", vars[m].base.c_str(), mode_name(vars[m].mode),
                  ops_string(ops[m]).c_str());
    }
    md += ".";
    if (!opt.threads.empty())
        md += " `@1`, `@all`: BODT_PARAM_THREADS = 1, 0 (all cores), `@N`: N.";
    bool any_peer = false;
    for (size_t m = 0; m < nvar; ++m)
        if (vars[m].is_peer()) {
            md += std::string(any_peer ? "" : " Peers:") + " `" + vars[m].name + "` = " +
                  bench::peer_description(vars[m].peer) + ";";
            any_peer = true;
        }
    if (any_peer) md.back() = '.';
    md += "\n\n";

    md += "Angles in degrees (after the run); `<10/>165` = tets with min dihedral < 10 / max dihedral > 165; "
          "H = relative Hausdorff distance of the boundary, in % of the largest bounding-box side; "
          "s = wall time of the bodt_step calls alone (a peer's: its own optimisation time); `!` marks an angle "
          "worse than before. "
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
        if (vars[m].is_peer()) continue;
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

    // ---- table 3: side by side with the peers
    const size_t mv = main_variant(opt);
    std::vector<size_t> peers;
    for (size_t m = 0; m < nvar; ++m)
        if (vars[m].is_peer() && !all_unsupported[m]) peers.push_back(m);
    if (!rows.empty() && !peers.empty() && mv < nvar) {
        const char* n = vars[mv].name.c_str();
        md += fmt("\n## Side by side with the peers\n\nMin/max dihedral after the run and seconds (ours: the %d "
                  "steps; a peer: its own optimisation time); ΔV = vertex growth in %% of the input vertices; `%s "
                  "beats` = seconds of %s's steps until its minimum angle first exceeded the peer's final one (0: the "
                  "input's already did; never: not within the steps).\n\n",
                  opt.iterations, n, n);
        md += fmt("| case | tets | before | %s | %s s |", n, n);
        std::string sep3 = "|---|---:|---:|---:|---:|";
        for (size_t k : peers) {
            const char* p = vars[k].name.c_str();
            md += fmt(" %s | %s s | %s ΔV %% | %s beats |", p, p, p, n);
            sep3 += "---:|---:|---:|---:|";
        }
        md += "\n" + sep3 + "\n";
        for (const Row& row : rows) {
            const RunResult* b = before_run(row);
            if (!b || mv >= row.runs.size()) continue;
            const RunResult& us = row.runs[mv];
            md += fmt("| %s | %d | %.2f/%.2f |", row.c->name.c_str(), b->before.tets, b->before.min_dihedral,
                      b->before.max_dihedral);
            md += ran_ok(us) ? fmt(" %.2f/%.2f | %.2f |", us.after.min_dihedral, us.after.max_dihedral, us.time_s)
                             : fmt(" %s | – |", us.status);
            for (size_t k : peers) {
                const RunResult& p = row.runs[k];
                if (!ran_ok(p)) {
                    md += fmt(" %s | – | – | – |", p.status);
                    continue;
                }
                const double t = time_to_beat(us, p);
                md += fmt(" %.2f/%.2f | %s | %+.1f | %s%s |", p.after.min_dihedral, p.after.max_dihedral,
                          secs_cell(p.time_s).c_str(), growth_pct(p), t == 0 ? "0" : secs_cell(t).c_str(),
                          std::isfinite(t) && t < p.time_s ? "" : " ✗");
            }
            md += "\n";
        }
        md += fmt("\n✗: %s did not beat the peer's minimum angle in less time than the peer took.\n", n);
    }

    // ---- table 4: size and speed
    if (!scale_table.empty()) {
        const int repeats = repeats_wanted(opt);
        const std::string kept = repeats > 1 ? fmt(" (below 2e5 tets, the run of median time of %d)", repeats) : "";
        md += "\n## Size and speed\n\nThe box cases (.shuffled: the jittered box numbered at random): create s = "
              "the wall time of bodt_mesh_create; s = the steps' wall time" + kept + "; updates = vertices moved + moves "
              "rejected (guarded vertex updates); threads = BODT_PARAM_THREADS as used (0 resolved to the library's "
              "default); parallelism = CPU seconds / wall seconds of the steps; B/tet = heap growth across "
              "bodt_mesh_create per input tet, and that plus the growth from bodt_set_mode to the end of the steps "
              "per output tet; peak RSS of the child that ran it (the input arrays included until the create).\n\n";
        md += scale_table;
    }

    // ---- targets
    md += "\n## Targets\n\n| target | measured | bar | verdict |\n|---|---|---|---|\n";
    for (const Target& t : tg)
        md += "| " + t.id + ": " + t.what + " | " + t.value + (t.detail.empty() ? "" : " — " + t.detail) + " | " +
              t.bar + " | **" + t.verdict + "** |\n";
    if (!beat_table.empty()) md += "\nTarget d, per mesh and peer:\n\n" + beat_table;

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
            if (!r.has_after || vars[m].is_peer() || ops[m] == BODT_OP_SMOOTH || !std::isfinite(r.hausdorff_rel))
                continue;
            for (size_t k = 0; k < row.runs.size() && k < nvar; ++k) {
                const RunResult& s = row.runs[k];
                if (k == m || vars[k].is_peer() || vars[k].mode != vars[m].mode || ops[k] != BODT_OP_SMOOTH ||
                    vars[k].threads != vars[m].threads || !s.has_after ||
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
            lines.push_back(vars[m].is_peer()
                                ? fmt("peer %s: unsupported here (%s: %s)", vars[m].name.c_str(),
                                      rows[0].runs[m].where, rows[0].runs[m].message)
                                : fmt("variant %s (mode %d, ops %s): unsupported by this library (%s: %s)",
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
    if (param_list().size() > kMaxParams) {
        std::fprintf(stderr, "bodt_bench: param_table() has %zu keys, more than kMaxParams = %zu\n",
                     param_list().size(), kMaxParams);
        return 1;
    }
    Options opt = parse_args(argc, argv);
    check_params(opt);

    std::vector<std::string> notes;
    if (!opt.list_only) {  // peers that cannot run here are left out, with a note
        std::vector<Variant> kept;
        std::map<int, bool> available;
        for (const Variant& v : opt.variants) {
            if (v.is_peer()) {
                const int key = v.peer == PeerKind::GmshNetgen ? int(PeerKind::Gmsh) : int(v.peer);
                if (!available.count(key)) {
                    std::string why, version;
                    available[key] = bench::peer_available(v.peer, why, version);
                    notes.push_back(available[key] ? "peer " + std::string(bench::peer_name(v.peer)) + ": " + version
                                                   : "peers " + std::string(key == int(PeerKind::TetGen)
                                                                                ? "tetgen-rO9/7"
                                                                                : "gmsh, gmsh-netgen") +
                                                         " left out: " + why);
                }
                if (!available[key]) continue;
            }
            kept.push_back(v);
        }
        if (kept.empty()) usage_error("no variant can run (peers missing: see the notes)");
        opt.variants.swap(kept);
    }

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
    const std::string peer_dir = temp_dir + "/peers";  // kept apart from the decompressed meshes
    mkdir(peer_dir.c_str(), 0700);
    opt.temp_dir = peer_dir;
    const std::string mesh_dir = temp_dir + "/meshes";
    mkdir(mesh_dir.c_str(), 0700);

    bench::CaseOptions copt;
    if (!opt.shared_dir.empty() && bench::is_dir(opt.shared_dir)) {
        copt.shared_dir = opt.shared_dir;
    } else if (!opt.scale) {
        notes.push_back(opt.shared_dir.empty() ? "no shared folder: generated meshes only"
                                               : "shared folder " + opt.shared_dir +
                                                     " not found: generated meshes only");
    }
    copt.large = opt.large;
    copt.scale = opt.scale;
    copt.scale_max = opt.scale_max;
    copt.temp_dir = mesh_dir;
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
            for (size_t m = 0; m < opt.variants.size(); ++m) {
                RunResult r = empty_result();
                SET(r.status, "error");
                SET(r.where, "making the case");
                SET(r.message, err);
                row.runs.push_back(r);
            }
        } else {
            for (const Variant& v : opt.variants) {
                const RunResult r = run_timed(c, pm, v, opt);
                row.runs.push_back(r);
                if (r.has_after)
                    std::fprintf(stderr,
                                 "    %-14s %-7s %2d steps %8.3f s  min %6.2f -> %6.2f  max %6.2f -> %6.2f  H %.2e"
                                 "  V %d -> %d  flips %" PRId64 " ins %" PRId64 " coll %" PRId64 "\n",
                                 v.name.c_str(), r.status, r.steps_done, r.time_s, r.before.min_dihedral,
                                 r.after.min_dihedral, r.before.max_dihedral, r.after.max_dihedral, r.hausdorff_rel,
                                 r.before.vertices, r.after.vertices, r.flips, r.inserted, r.collapsed);
                else
                    std::fprintf(stderr, "    %-14s %s\n", v.name.c_str(), r.status);
            }
        }
        // the JSON lines of a case once all its variants ran (time_to_beat_s
        // needs the peers' results)
        for (size_t m = 0; m < row.runs.size(); ++m) std::fprintf(json, "%s\n", result_json(row, m, opt).c_str());
        std::fflush(json);
        rows.push_back(std::move(row));
        // the decompressed copy is not needed any more
        if (pm.from_file && pm.path.compare(0, mesh_dir.size(), mesh_dir) == 0) {
            bench::remove_tree(mesh_dir);
            mkdir(mesh_dir.c_str(), 0700);
        }
    }
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    bench::remove_tree(temp_dir);

    std::string scale_table, beat_table;
    const std::vector<Target> tg = targets(rows, opt, scale_table, beat_table);
    std::string tj = "{\"targets\":[";
    for (size_t i = 0; i < tg.size(); ++i) tj += (i ? "," : "") + json_target(tg[i]);
    tj += "],\"library\":" + json_str(bodt_version_string()) + ",\"total_s\":" + json_num(total_s, "%.1f") +
          ",\"cores\":" + std::to_string(std::thread::hardware_concurrency()) + "}";
    std::fprintf(json, "%s\n", tj.c_str());
    for (const Target& t : tg)
        std::fprintf(stderr, "target %s: %s: %s (bar %s)\n", t.id.c_str(), t.verdict.c_str(), t.value.c_str(),
                     t.bar.c_str());

    if (json != stdout) std::fclose(json);
    if (!opt.markdown_path.empty() &&
        !bench::write_text_file(opt.markdown_path, markdown(rows, opt, notes, total_s, tg, scale_table, beat_table)))
        std::fprintf(stderr, "bodt_bench: cannot write %s: %s\n", opt.markdown_path.c_str(), std::strerror(errno));
    return 0;
}
