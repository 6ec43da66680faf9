// bodt_bench -- the benchmark of libbodt.
//
// For every case (a tet mesh: TetGen meshes of surfaces, mesh files, a random
// sphere, jittered boxes) and every mode it creates the mesh through the
// public C API, sets the mode, runs a fixed number of bodt_step calls, and
// records the quality before and after, the relative Hausdorff distance of the
// boundary, the wall time of the smoothing alone and the peak memory.  One
// JSON object per case and mode goes to stdout (or --json FILE); a markdown
// summary to --markdown FILE.  Each run happens in a forked child, so a crash
// or a hang of the library is reported and the bench goes on.
//
// Only the public API (bodt.h) is used.  Modes are taken by value (1 laplace,
// 2 odt, 3 bodt-basic, 4 bodt) so the program builds against a header that
// does not name them yet; a mode the library refuses is "unsupported".

#include "bodt.h"

#include "cases.hpp"
#include "surface_distance.hpp"

#include <fcntl.h>
#include <ftw.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <regex>
#include <string>
#include <type_traits>
#include <vector>

#ifndef BODT_BENCH_DEFAULT_SHARED
#define BODT_BENCH_DEFAULT_SHARED ""
#endif

namespace {

using bench::Case;
using bench::PreparedMesh;

struct Mode {
    const char* name;
    int value;
};
const Mode kModes[] = {{"laplace", 1}, {"odt", 2}, {"bodt-basic", 3}, {"bodt", 4}};

// ---------------------------------------------------------------- options

struct Options {
    std::vector<Mode> modes;
    int iterations = 20;
    int never_worse = -1;  // -1: library default
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
    std::fprintf(f,
                 "usage: bodt_bench [options]\n"
                 "  --modes LIST         comma-separated of laplace,odt,bodt-basic,bodt or mode values\n"
                 "                       (default: laplace,odt,bodt-basic,bodt = 1,2,3,4)\n"
                 "  --iterations N       bodt_step calls per run (default 20)\n"
                 "  --never-worse 0|1    set BODT_PARAM_NEVER_WORSE (default: the library's default)\n"
                 "  --json FILE          JSON lines to FILE instead of stdout\n"
                 "  --markdown FILE      write the markdown summary to FILE\n"
                 "  --write-dir DIR      write CASE.input.mesh and CASE.MODE.mesh there (bodt_mesh_write)\n"
                 "  --shared DIR         the shared folder with meshes/ (default %s)\n"
                 "  --no-shared          generated cases only\n"
                 "  --large              add the ~1e5-tet jittered box\n"
                 "  --cases REGEX        only cases whose name matches (ECMAScript regex, searched)\n"
                 "  --surface FILE       add a closed .off/.stl surface (TetGen -pQ and -pqQ)\n"
                 "  --mesh FILE          add a tet mesh file (.mesh, .node/.ele, optionally .gz)\n"
                 "  --timeout SECONDS    per case and mode (default 900; 0 = none)\n"
                 "  --no-fork            run in this process (for debuggers; a crash ends the bench)\n"
                 "  --list               list the cases and exit\n"
                 "  --help\n"
                 "exit status: 0 (also when some runs fail; see their status), 2 usage error\n",
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
            std::string list = value(i);
            o.modes.clear();
            size_t p = 0;
            while (p <= list.size()) {
                size_t q = list.find(',', p);
                if (q == std::string::npos) q = list.size();
                const std::string name = list.substr(p, q - p);
                bool found = false;
                for (const Mode& m : kModes)
                    if (name == m.name) {
                        o.modes.push_back(m);
                        found = true;
                    }
                int mval = 0;
                if (!found && parse_int(name.c_str(), mval) && mval > 0) {  // a mode by its value
                    static std::vector<std::string> names;  // kept alive for Mode::name
                    names.reserve(64);
                    if (names.size() == names.capacity()) usage_error("too many numeric modes");
                    names.push_back("mode" + name);
                    o.modes.push_back({names.back().c_str(), mval});
                    found = true;
                }
                if (!found)
                    usage_error("unknown mode '%s' (laplace, odt, bodt-basic, bodt or a mode value)", name.c_str());
                p = q + 1;
            }
        } else if (a == "--iterations") {
            if (!parse_int(value(i), o.iterations) || o.iterations < 1) usage_error("--iterations needs N >= 1");
        } else if (a == "--never-worse") {
            const std::string v = value(i);
            if (v != "0" && v != "1") usage_error("--never-worse takes 0 or 1");
            o.never_worse = v == "1";
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
    if (o.modes.empty()) o.modes.assign(std::begin(kModes), std::end(kModes));
    return o;
}

// ----------------------------------------------------------------- results

struct Stats {
    int32_t vertices, tets, boundary_faces, lib_boundary_faces;
    int32_t inverted, lt10, gt165;
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
    int32_t has_before, has_after;
    Stats before, after;
    double volume_change_rel;
    double region_volume_change_rel_max;  // max over regions of |dV_r| / |V_r|
    int32_t regions;
    double hausdorff_abs, hausdorff_rel, bbox_side;
    double time_s, hausdorff_time_s;
    int64_t vertices_moved, moves_rejected, moves_shortened;
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
    r.never_worse = -1;
    r.volume_change_rel = r.region_volume_change_rel_max = r.hausdorff_abs = r.hausdorff_rel = NAN;
    return r;
}

// ----------------------------------------------------------- one run

struct MeshHolder {
    bodt_mesh* m = nullptr;
    ~MeshHolder() { bodt_mesh_destroy(m); }
};

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
    bodt_quality q;
    std::memset(&q, 0, sizeof q);
    q.size = sizeof q;
    if ((st = bodt_mesh_quality(m, &q)) != BODT_OK) return where = "bodt_mesh_quality", st;
    s.inverted = q.num_inverted;
    s.min_dihedral = q.min_dihedral;
    s.max_dihedral = q.max_dihedral;
    s.mean_dihedral = q.mean_dihedral;
    s.min_stretch = q.min_stretch;
    s.mean_stretch = q.mean_stretch;
    s.volume = q.volume;
    std::vector<double> v(static_cast<size_t>(nt));
    if ((st = bodt_mesh_tet_quality(m, BODT_MEASURE_MIN_DIHEDRAL, v.data(), v.size())) != BODT_OK)
        return where = "bodt_mesh_tet_quality(MIN_DIHEDRAL)", st;
    s.lt10 = int32_t(std::count_if(v.begin(), v.end(), [](double a) { return a < 10.0; }));
    if ((st = bodt_mesh_tet_quality(m, BODT_MEASURE_MAX_DIHEDRAL, v.data(), v.size())) != BODT_OK)
        return where = "bodt_mesh_tet_quality(MAX_DIHEDRAL)", st;
    s.gt165 = int32_t(std::count_if(v.begin(), v.end(), [](double a) { return a > 165.0; }));
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

std::string errmsg(const bodt_mesh* m, int status) {
    const char* e = bodt_mesh_last_error(m);
    return std::string(bodt_status_string(status)) + (e && *e ? std::string(": ") + e : std::string());
}

RunResult run_one(const Case& c, const PreparedMesh& pm, const Mode& mode, const Options& opt) {
    RunResult r = empty_result();
    auto fail = [&](const char* status, const std::string& where, const std::string& msg) {
        SET(r.status, status);
        SET(r.where, where);
        SET(r.message, msg);
        std::fprintf(stderr, "bodt_bench: %s / %s: %s: %s\n", c.name.c_str(), mode.name, where.c_str(),
                     msg.c_str());
        return r;
    };

    MeshHolder mh;
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

    st = bodt_set_mode(mh.m, mode.value);
    if (st == BODT_ERR_INVALID_ARGUMENT || st == BODT_ERR_UNSUPPORTED) {
        SET(r.status, "unsupported");
        SET(r.where, "bodt_set_mode");
        SET(r.message, errmsg(mh.m, st));
        return r;
    }
    if (st != BODT_OK) return fail("error", "bodt_set_mode", errmsg(mh.m, st));
    if (opt.never_worse >= 0) {
        st = bodt_set_param_int(mh.m, BODT_PARAM_NEVER_WORSE, opt.never_worse);
        if (st != BODT_OK) return fail("error", "bodt_set_param_int(NEVER_WORSE)", errmsg(mh.m, st));
    }
    int32_t nw = -1;
    if (bodt_get_param_int(mh.m, BODT_PARAM_NEVER_WORSE, &nw) == BODT_OK) r.never_worse = nw;

    // The smoothing, and only it, is timed.
    bool step_failed = false;
    std::string step_where, step_msg;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < opt.iterations; ++i) {
        bodt_step_report rep;
        std::memset(&rep, 0, sizeof rep);
        rep.size = sizeof rep;
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
        r.last_max_move = rep.max_move;
    }
    const auto t1 = std::chrono::steady_clock::now();
    r.time_s = std::chrono::duration<double>(t1 - t0).count();
    r.updates_per_s = r.time_s > 0 ? double(r.vertices_moved + r.moves_rejected) / r.time_s : 0.0;

    if ((st = measure(mh.m, r.after, after_surf, tets, index_base, where)) != BODT_OK)
        return fail("error", where, errmsg(mh.m, st));
    r.has_after = 1;
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
        const std::string out_path = opt.write_dir + "/" + c.name + "." + mode.name + ".mesh";
        if ((st = bodt_mesh_write(mh.m, out_path.c_str())) != BODT_OK)
            std::fprintf(stderr, "bodt_bench: %s / %s: bodt_mesh_write %s: %s\n", c.name.c_str(), mode.name,
                         out_path.c_str(), errmsg(mh.m, st).c_str());
    }
    if (step_failed) fail("error", step_where, step_msg);
    return r;
}

bool write_all(int fd, const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    while (n > 0) {
        const ssize_t w = write(fd, c, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        c += w;
        n -= size_t(w);
    }
    return true;
}

size_t read_all(int fd, void* p, size_t n) {
    char* c = static_cast<char*>(p);
    size_t got = 0;
    while (got < n) {
        const ssize_t r = read(fd, c + got, n - got);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        got += size_t(r);
    }
    return got;
}

// Runs run_one in a forked child (so a crash or hang is contained) and takes
// the peak RSS of that child.
RunResult run_isolated(const Case& c, const PreparedMesh& pm, const Mode& mode, const Options& opt) {
    if (!opt.fork_runs) {
        RunResult r = run_one(c, pm, mode, opt);
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        r.peak_rss_mb = double(ru.ru_maxrss) / 1024.0;
        return r;
    }
    int fds[2];
    if (pipe(fds) != 0) {
        RunResult r = empty_result();
        SET(r.status, "error");
        SET(r.where, "pipe");
        SET(r.message, std::strerror(errno));
        return r;
    }
    std::fflush(stdout);
    std::fflush(stderr);
    const pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        if (opt.timeout_s > 0) alarm(unsigned(opt.timeout_s));
        const RunResult r = run_one(c, pm, mode, opt);
        const bool ok = write_all(fds[1], &r, sizeof r);
        std::fflush(stderr);
        _exit(ok ? 0 : 3);
    }
    close(fds[1]);
    RunResult r = empty_result();
    if (pid < 0) {
        close(fds[0]);
        SET(r.status, "error");
        SET(r.where, "fork");
        SET(r.message, std::strerror(errno));
        return r;
    }
    RunResult got = empty_result();
    const size_t n = read_all(fds[0], &got, sizeof got);
    close(fds[0]);
    int wst = 0;
    struct rusage ru;
    std::memset(&ru, 0, sizeof ru);
    while (wait4(pid, &wst, 0, &ru) < 0 && errno == EINTR) {
    }
    if (n == sizeof got) {
        r = got;
    } else if (WIFSIGNALED(wst)) {
        const int sig = WTERMSIG(wst);
        SET(r.status, sig == SIGALRM ? "timeout" : "crashed");
        SET(r.where, "child process");
        SET(r.message, sig == SIGALRM ? "no result after " + std::to_string(opt.timeout_s) + " s"
                                      : std::string("killed by signal ") + std::to_string(sig) + " (" +
                                            strsignal(sig) + ")");
        std::fprintf(stderr, "bodt_bench: %s / %s: %s\n", c.name.c_str(), mode.name, r.message);
    } else {
        SET(r.status, "crashed");
        SET(r.where, "child process");
        SET(r.message, "child exited with status " + std::to_string(WIFEXITED(wst) ? WEXITSTATUS(wst) : -1) +
                           " without a result");
        std::fprintf(stderr, "bodt_bench: %s / %s: %s\n", c.name.c_str(), mode.name, r.message);
    }
    r.peak_rss_mb = double(ru.ru_maxrss) / 1024.0;
    return r;
}

// ------------------------------------------------------------------ output

std::string json_str(const std::string& s) {
    std::string o = "\"";
    for (unsigned char ch : s) {
        if (ch == '"' || ch == '\\') {
            o += '\\';
            o += char(ch);
        } else if (ch < 0x20) {
            char b[8];
            std::snprintf(b, sizeof b, "\\u%04x", ch);
            o += b;
        } else {
            o += char(ch);
        }
    }
    return o + "\"";
}

std::string json_num(double v, const char* fmt = "%.6g") {
    if (!std::isfinite(v)) return "null";
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    return b;
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
    o += ",\"stretch_min\":" + json_num(s.min_stretch, "%.5f");
    o += ",\"stretch_mean\":" + json_num(s.mean_stretch, "%.5f");
    o += ",\"inverted\":" + std::to_string(s.inverted);
    o += ",\"volume\":" + json_num(s.volume, "%.10g");
    return o + "}";
}

std::string result_json(const Case& c, const std::string& note, const Mode& mode, const RunResult& r,
                        const Options& opt) {
    std::string o = "{";
    o += "\"case\":" + json_str(c.name);
    o += ",\"kind\":" + json_str(c.kind);
    o += ",\"source\":" + json_str(c.source);
    if (!note.empty()) o += ",\"note\":" + json_str(note);
    o += ",\"mode\":" + json_str(mode.name);
    o += ",\"mode_value\":" + std::to_string(mode.value);
    o += ",\"status\":" + json_str(r.status);
    if (r.where[0]) o += ",\"where\":" + json_str(r.where);
    if (r.message[0]) o += ",\"message\":" + json_str(r.message);
    o += ",\"library\":" + json_str(bodt_version_string());
    o += ",\"iterations\":" + std::to_string(opt.iterations);
    o += ",\"steps_done\":" + std::to_string(r.steps_done);
    o += ",\"never_worse\":" + (r.never_worse >= 0 ? std::to_string(r.never_worse) : std::string("null"));
    if (r.has_before) {
        o += ",\"vertices\":" + std::to_string(r.before.vertices);
        o += ",\"tets\":" + std::to_string(r.before.tets);
        o += ",\"boundary_faces\":" + std::to_string(r.before.boundary_faces);
        o += ",\"before\":" + stats_json(r.before);
    }
    if (r.has_after) {
        o += ",\"after\":" + stats_json(r.after);
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

static_assert(std::is_trivially_copyable<RunResult>::value, "RunResult goes through a pipe");

struct Row {
    const Case* c;
    std::string note;
    std::string prep_error;
    std::vector<RunResult> runs;  // one per mode, in opt.modes order
};

std::string fmt(const char* f, ...) {
    char b[256];
    va_list ap;
    va_start(ap, f);
    std::vsnprintf(b, sizeof b, f, ap);
    va_end(ap);
    return b;
}

std::string markdown(const std::vector<Row>& rows, const Options& opt, const std::vector<std::string>& notes,
                     double total_s) {
    std::string md;
    char date[64];
    const std::time_t now = std::time(nullptr);
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M", std::localtime(&now));
    md += "# bodt_bench\n\n";
    md += fmt("libbodt %s, %d bodt_step calls per case and mode, BODT_PARAM_NEVER_WORSE %s; %s; total %.0f s.\n\n",
              bodt_version_string(), opt.iterations,
              opt.never_worse < 0 ? "= library default" : (opt.never_worse ? "= 1" : "= 0"), date, total_s);
    md += "Angles in degrees (after the run); `<10/>165` = tets with min dihedral < 10 / max dihedral > 165; "
          "H = relative Hausdorff distance of the boundary, in % of the largest bounding-box side; "
          "s = wall time of the smoothing alone; `!` marks an angle worse than before. "
          "Last row: medians of the angles and of H over the cases that ran, sums of the counts and times.\n\n";

    // A mode the library refused on every case gets one column.
    std::vector<bool> all_unsupported(opt.modes.size(), true);
    for (size_t m = 0; m < opt.modes.size(); ++m)
        for (const Row& row : rows)
            if (m < row.runs.size() && std::strcmp(row.runs[m].status, "unsupported") != 0)
                all_unsupported[m] = false;
    if (rows.empty()) all_unsupported.assign(opt.modes.size(), false);

    md += "| case | V / T / bF | before min/max | before <10/>165 |";
    std::string sep = "|---|---:|---:|---:|";
    for (size_t m = 0; m < opt.modes.size(); ++m) {
        const char* n = opt.modes[m].name;
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
        const RunResult* b = nullptr;
        for (const auto& r : row.runs)
            if (r.has_before) {
                b = &r;
                break;
            }
        md += "| " + row.c->name + " | ";
        if (b)
            md += fmt("%d / %d / %d | %.2f/%.2f | %d/%d |", b->before.vertices, b->before.tets,
                      b->before.boundary_faces, b->before.min_dihedral, b->before.max_dihedral, b->before.lt10,
                      b->before.gt165);
        else
            md += "– | – | – |";
        for (size_t m = 0; m < opt.modes.size(); ++m) {
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
                const double h = r.hausdorff_rel * 100.0;
                md += fmt(" %s%.2f%s/%.2f%s | %d/%d | %s | %.2f |", err ? "(error) " : "", r.after.min_dihedral,
                          r.after.min_dihedral < r.before.min_dihedral ? "!" : "", r.after.max_dihedral,
                          r.after.max_dihedral > r.before.max_dihedral ? "!" : "", r.after.lt10, r.after.gt165,
                          !std::isfinite(h) ? "–" : (h == 0 ? "0" : fmt("%.3g", h).c_str()), r.time_s);
            } else {
                md += fmt(" %s | – | – | – |", r.status);
            }
        }
        md += "\n";
    }
    if (!rows.empty()) {
        auto median = [](std::vector<double> v) {
            if (v.empty()) return double(NAN);
            std::sort(v.begin(), v.end());
            const size_t n = v.size();
            return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
        };
        std::vector<double> bmin, bmax;
        long blt = 0, bgt = 0;
        for (const Row& row : rows)
            for (const auto& r : row.runs)
                if (r.has_before) {
                    bmin.push_back(r.before.min_dihedral);
                    bmax.push_back(r.before.max_dihedral);
                    blt += r.before.lt10;
                    bgt += r.before.gt165;
                    break;
                }
        md += fmt("| **median / sum** (%zu cases) | | %.2f/%.2f | %ld/%ld |", rows.size(), median(bmin), median(bmax),
                  blt, bgt);
        for (size_t m = 0; m < opt.modes.size(); ++m) {
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
            const double hm = median(hs);
            if (mn.empty()) {
                md += " – | – | – | – |";
                continue;
            }
            md += fmt(" %.2f/%.2f (%zu) | %ld/%ld | %s | %.1f |", median(mn), median(mx), mn.size(), lt, gt,
                      !std::isfinite(hm) ? "–" : (hm == 0 ? "0" : fmt("%.3g", hm).c_str()), secs);
        }
        md += "\n";
    }

    std::vector<std::string> lines;
    for (const Row& row : rows) {
        if (!row.note.empty()) lines.push_back("`" + row.c->name + "`: " + row.note + ".");
        if (!row.prep_error.empty()) lines.push_back("`" + row.c->name + "`: could not be made: " + row.prep_error);
        for (size_t m = 0; m < row.runs.size(); ++m) {
            const RunResult& r = row.runs[m];
            if (r.has_after && r.region_volume_change_rel_max > 1e-9)
                lines.push_back(fmt("`%s` / %s: the volume of a region changed by %.3g (relative)", row.c->name.c_str(),
                                    opt.modes[m].name, r.region_volume_change_rel_max));
            if (r.has_after && r.after.inverted > r.before.inverted)
                lines.push_back(fmt("`%s` / %s: %d inverted tets after, %d before", row.c->name.c_str(),
                                    opt.modes[m].name, r.after.inverted, r.before.inverted));
            if (std::strcmp(r.status, "ok") != 0 && !(all_unsupported[m] && !std::strcmp(r.status, "unsupported")))
                lines.push_back("`" + row.c->name + "` / " + opt.modes[m].name + ": " + r.status + " in " + r.where +
                                ": " + r.message);
        }
    }
    for (size_t m = 0; m < opt.modes.size(); ++m)
        if (all_unsupported[m] && !rows.empty() && !rows[0].runs.empty())
            lines.push_back(fmt("mode %s (%d): unsupported by this library (bodt_set_mode: %s)", opt.modes[m].name,
                                opt.modes[m].value, rows[0].runs[m].message));
    for (const auto& n : notes) lines.push_back(n);
    if (!lines.empty()) {
        md += "\nNotes:\n\n";
        for (const auto& l : lines) md += "- " + l + "\n";
    }
    return md;
}

// ------------------------------------------------------------------ temp dir

int rm_entry(const char* path, const struct stat*, int, struct FTW*) { return remove(path); }

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse_args(argc, argv);

    FILE* json = stdout;
    if (!opt.json_path.empty()) {
        json = std::fopen(opt.json_path.c_str(), "w");
        if (!json) usage_error("cannot write %s: %s", opt.json_path.c_str(), std::strerror(errno));
    }
    if (!opt.write_dir.empty()) {
        mkdir(opt.write_dir.c_str(), 0777);
        struct stat sb;
        if (stat(opt.write_dir.c_str(), &sb) != 0 || !S_ISDIR(sb.st_mode))
            usage_error("cannot create --write-dir %s", opt.write_dir.c_str());
    }

    const char* tmp_root = std::getenv("TMPDIR");
    std::string tmpl = std::string(tmp_root && *tmp_root ? tmp_root : "/tmp") + "/bodt-bench-XXXXXX";
    std::vector<char> tbuf(tmpl.begin(), tmpl.end());
    tbuf.push_back('\0');
    const char* tdir = mkdtemp(tbuf.data());
    if (!tdir) {
        std::fprintf(stderr, "bodt_bench: cannot make a temp dir %s: %s\n", tmpl.c_str(), std::strerror(errno));
        return 1;
    }
    const std::string temp_dir = tdir;

    bench::CaseOptions copt;
    struct stat sb;
    std::vector<std::string> notes;
    if (!opt.shared_dir.empty() && stat(opt.shared_dir.c_str(), &sb) == 0 && S_ISDIR(sb.st_mode)) {
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
    if (!opt.case_regex.empty()) {
        const std::regex re(opt.case_regex);
        cases.erase(std::remove_if(cases.begin(), cases.end(),
                                   [&](const Case& c) { return !std::regex_search(c.name, re); }),
                    cases.end());
    }
    if (opt.list_only) {
        for (const auto& c : cases) std::printf("%-36s %-15s %s\n", c.name.c_str(), c.kind.c_str(), c.source.c_str());
        for (const auto& n : notes) std::printf("# %s\n", n.c_str());
        nftw(temp_dir.c_str(), rm_entry, 16, FTW_DEPTH | FTW_PHYS);
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
            for (const Mode& m : opt.modes) {
                RunResult r = empty_result();
                SET(r.status, "error");
                SET(r.where, "making the case");
                SET(r.message, err);
                row.runs.push_back(r);
                std::fprintf(json, "%s\n", result_json(c, pm.note, m, r, opt).c_str());
            }
            std::fflush(json);
            rows.push_back(std::move(row));
            continue;
        }
        for (const Mode& m : opt.modes) {
            const RunResult r = run_isolated(c, pm, m, opt);
            row.runs.push_back(r);
            std::fprintf(json, "%s\n", result_json(c, pm.note, m, r, opt).c_str());
            std::fflush(json);
            if (r.has_after)
                std::fprintf(stderr, "    %-10s %-7s %2d steps %8.3f s  min %6.2f -> %6.2f  max %6.2f -> %6.2f  H %.2e\n",
                             m.name, r.status, r.steps_done, r.time_s, r.before.min_dihedral, r.after.min_dihedral,
                             r.before.max_dihedral, r.after.max_dihedral, r.hausdorff_rel);
            else
                std::fprintf(stderr, "    %-10s %s\n", m.name, r.status);
        }
        rows.push_back(std::move(row));
        // the decompressed copy is not needed any more
        if (pm.from_file && pm.path.compare(0, temp_dir.size(), temp_dir) == 0) {
            nftw(temp_dir.c_str(), rm_entry, 16, FTW_DEPTH | FTW_PHYS);
            mkdir(temp_dir.c_str(), 0700);
        }
    }
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    nftw(temp_dir.c_str(), rm_entry, 16, FTW_DEPTH | FTW_PHYS);

    if (json != stdout) std::fclose(json);
    if (!opt.markdown_path.empty()) {
        FILE* f = std::fopen(opt.markdown_path.c_str(), "w");
        if (!f) {
            std::fprintf(stderr, "bodt_bench: cannot write %s: %s\n", opt.markdown_path.c_str(), std::strerror(errno));
        } else {
            std::fputs(markdown(rows, opt, notes, total_s).c_str(), f);
            std::fclose(f);
        }
    }
    return 0;
}
