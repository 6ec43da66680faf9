// bodt_bench_deformed -- paper 002's benchmark: deformed meshes improved by
// ODT and by phased ODT (BODT_MODE_PHASED_ODT), measured as in its Tables
// 1-3 (stretch ave/min, density error ave/max, geometric error ave/max,
// inverted tets, time).
//
// For every case (deformed_cases.hpp: a box with a hole deformed like the
// paper's DP / RC / PH examples, shared tet meshes with boundary vertices
// stretched) four rows: the original as it is, the deformed mesh as it is
// (created with BODT_CREATE_ACCEPT_INVERTED, the original as its reference)
// and the deformed mesh after bodt_run in BODT_MODE_ODT and in
// BODT_MODE_PHASED_ODT.  Each row runs in a forked child: a crash or a hang is
// recorded in the row and the bench goes on; a status other than BODT_OK is
// recorded, never fatal.  One JSON object per row to stdout (or --json FILE);
// the markdown table to --markdown FILE.  Only the public API (bodt.h).

#include "bodt.h"

#include "bench_util.hpp"
#include "deformed_cases.hpp"
#include "deformed_report.hpp"

#include <sys/stat.h>

#include <chrono>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <string>
#include <vector>

#ifndef BODT_BENCH_DEFAULT_SHARED
#define BODT_BENCH_DEFAULT_SHARED ""
#endif

namespace {

using bench::CaseRows;
using bench::DeformedCase;
using bench::DeformedMesh;
using bench::errmsg;
using bench::MeshHandle;
using bench::RowKind;
using bench::RowResult;

struct Options {
    int max_steps = 20;
    double stretch = 1.5;  // of the file cases' boundary
    std::string json_path, markdown_path, write_dir, case_regex;
    std::string shared_dir = BODT_BENCH_DEFAULT_SHARED;
    std::vector<std::string> extra_meshes;
    int timeout_s = 900;
    bool fork_runs = true, list_only = false, progress = false;
};

void usage(FILE* f) {
    std::fprintf(f,
                 "usage: bodt_bench_deformed [options]\n"
                 "  --iterations N     at most N steps per mode (bodt_run; default 20)\n"
                 "  --json FILE        JSON lines to FILE instead of stdout\n"
                 "  --markdown FILE    write the markdown table to FILE\n"
                 "  --write-dir DIR    write CASE.ROW.mesh there (bodt_mesh_write)\n"
                 "  --shared DIR       the shared folder with meshes/ (default %s)\n"
                 "  --no-shared        the generated box with a hole only\n"
                 "  --mesh FILE        add a tet mesh file (.mesh, .node/.ele, optionally .gz)\n"
                 "  --stretch F        the file cases' boundary beyond the middle plane x = xmid goes to\n"
                 "                     xmid + F (x - xmid) (default 1.5)\n"
                 "  --cases REGEX      only cases whose name matches (searched)\n"
                 "  --timeout SECONDS  per case and row (default 900; 0 = none)\n"
                 "  --no-fork          run in this process (for debuggers)\n"
                 "  --progress         a line per step on stderr\n"
                 "  --list             list the cases and exit\n"
                 "exit status: 0 (also when some rows fail; see their status), 2 usage error\n",
                 BODT_BENCH_DEFAULT_SHARED[0] ? BODT_BENCH_DEFAULT_SHARED : "none");
}

[[noreturn]] void usage_error(const std::string& msg) {
    std::fprintf(stderr, "bodt_bench_deformed: %s\n", msg.c_str());
    usage(stderr);
    std::exit(2);
}

Options parse_args(int argc, char** argv) {
    Options o;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) usage_error(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    auto number = [&](int& i, int lo) {
        const std::string v = value(i);
        char* end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (v.empty() || *end || n < lo || n > 1000000) usage_error(std::string(argv[i - 1]) + ": bad value " + v);
        return int(n);
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") usage(stdout), std::exit(0);
        else if (a == "--iterations") o.max_steps = number(i, 1);
        else if (a == "--json") o.json_path = value(i);
        else if (a == "--markdown") o.markdown_path = value(i);
        else if (a == "--write-dir") o.write_dir = value(i);
        else if (a == "--shared") o.shared_dir = value(i);
        else if (a == "--no-shared") o.shared_dir.clear();
        else if (a == "--mesh") o.extra_meshes.push_back(value(i));
        else if (a == "--timeout") o.timeout_s = number(i, 0);
        else if (a == "--stretch") {
            const std::string v = value(i);
            char* end = nullptr;
            o.stretch = std::strtod(v.c_str(), &end);
            if (v.empty() || *end || !(o.stretch > 0 && o.stretch < 100)) usage_error("--stretch: bad value " + v);
        }
        else if (a == "--no-fork") o.fork_runs = false;
        else if (a == "--progress") o.progress = true;
        else if (a == "--list") o.list_only = true;
        else if (a == "--cases") {
            o.case_regex = value(i);
            try {
                std::regex re(o.case_regex);
            } catch (const std::regex_error&) {
                usage_error("bad --cases regex " + o.case_regex);
            }
        } else {
            usage_error("unknown argument " + a);
        }
    }
    return o;
}

// ------------------------------------------------------------- one row

// A handle of the case's mesh with the given coordinates, regions and marked
// faces.
int make_handle(const DeformedMesh& dm, const std::vector<double>& xyz, uint32_t flags, MeshHandle& h,
                std::string& where) {
    int st = bodt_mesh_create_ex(int32_t(xyz.size() / 3), xyz.data(), int32_t(dm.tets.size() / 4), dm.tets.data(), 0,
                                 flags, &h.m);
    if (st != BODT_OK) return where = "bodt_mesh_create_ex", st;
    if (!dm.regions.empty() && (st = bodt_mesh_set_regions(h.m, dm.regions.data())) != BODT_OK)
        return where = "bodt_mesh_set_regions", st;
    if (!dm.markers.empty() &&
        (st = bodt_mesh_set_boundary_faces(h.m, int32_t(dm.markers.size()), dm.faces.data(), dm.markers.data())) !=
            BODT_OK)
        return where = "bodt_mesh_set_boundary_faces", st;
    return BODT_OK;
}

// Quality and recovery errors of the mesh as the handle holds it now.
int measure(const bodt_mesh* m, RowResult& r, std::string& where) {
    bodt_quality q = bench::sized_struct<bodt_quality>();
    int st = bodt_mesh_quality(m, &q);
    if (st != BODT_OK) return where = "bodt_mesh_quality", st;
    r.vertices = q.num_vertices - q.num_unused_vertices;
    r.tets = q.num_tets;
    r.inverted = q.num_inverted;
    r.stretch_mean = q.mean_stretch;
    r.stretch_min = q.min_stretch;
    r.min_dihedral = q.min_dihedral;
    r.max_dihedral = q.max_dihedral;
    r.measured = 1;
    if ((st = bodt_mesh_get_geometry_counts(m, &r.geometry_regions, &r.geometry_chains)) != BODT_OK)
        return where = "bodt_mesh_get_geometry_counts", st;
    bodt_recovery_error e = bench::sized_struct<bodt_recovery_error>();
    if ((st = bodt_mesh_recovery_error(m, &e)) != BODT_OK) return where = "bodt_mesh_recovery_error", st;
    r.density_mean = e.density_mean;
    r.density_max = e.density_max;
    r.density_edges = e.density_edges;
    r.geometric_mean = e.geometric_mean;
    r.geometric_max = e.geometric_max;
    r.geometric_edges = e.geometric_edges;
    return BODT_OK;
}

struct StepLog {
    RowResult* r;
    bool print;
    std::string label;
    std::chrono::steady_clock::time_point t0;
};

int on_step(const bodt_step_report* rep, void* user) {
    StepLog& log = *static_cast<StepLog*>(user);
    RowResult& r = *log.r;
    ++r.steps_done;
    r.vertices_moved += rep->vertices_moved;
    r.flips += rep->flips;
    r.inserted += rep->vertices_inserted;
    r.collapsed += rep->edges_collapsed;
    if (!log.print) return 0;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - log.t0).count();
    std::fprintf(stderr, "      %s step %2d: %7.2f s  min stretch %8.4f  dihedral %6.2f/%6.2f  ins %d coll %d flips %d\n",
                 log.label.c_str(), rep->step, s, rep->min_stretch, rep->min_dihedral, rep->max_dihedral,
                 rep->vertices_inserted, rep->edges_collapsed, rep->flips);
    return 0;
}

RowResult run_row(const DeformedCase& c, const DeformedMesh& dm, RowKind kind, const Options& opt) {
    RowResult r = bench::empty_row_result();
    std::string where;
    auto fail = [&](int st, const bodt_mesh* m) {
        bench::set_row_status(r, "error", where, errmsg(m, st));
        std::fprintf(stderr, "bodt_bench_deformed: %s / %s: %s: %s\n", c.name.c_str(), bench::row_name(kind),
                     r.where, r.message);
        return r;
    };
    MeshHandle orig, h;
    int st = make_handle(dm, dm.original, BODT_CREATE_DEFAULT, orig, where);
    if (st != BODT_OK) return where = "original: " + where, fail(st, orig.m);
    bodt_mesh* m = orig.m;
    if (kind != RowKind::Original) {
        if ((st = make_handle(dm, dm.deformed, BODT_CREATE_ACCEPT_INVERTED, h, where)) != BODT_OK)
            return where = "deformed: " + where, fail(st, h.m);
        m = h.m;
        const auto t0 = std::chrono::steady_clock::now();
        if ((st = bodt_set_reference_mesh(m, orig.m)) != BODT_OK) return where = "bodt_set_reference_mesh", fail(st, m);
        r.reference_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (kind == RowKind::Odt || kind == RowKind::Phased) {
        const int mode = kind == RowKind::Odt ? BODT_MODE_ODT : BODT_MODE_PHASED_ODT;
        if ((st = bodt_set_mode(m, mode)) != BODT_OK) return where = "bodt_set_mode", fail(st, m);
        StepLog log{&r, opt.progress, c.name + " / " + bench::row_name(kind), std::chrono::steady_clock::now()};
        const auto t0 = std::chrono::steady_clock::now();
        st = bodt_run(m, opt.max_steps, on_step, &log);  // the steps, and only they, are timed
        r.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (st != BODT_OK) {
            where = "bodt_run (after " + std::to_string(r.steps_done) + " steps)";
            fail(st, m);  // recorded; the mesh is measured as it is
        }
    }
    std::string mwhere;
    const int mst = measure(m, r, mwhere);
    if (mst != BODT_OK && !std::strcmp(r.status, "ok")) {
        where = mwhere;
        fail(mst, m);
    }
    if (!opt.write_dir.empty()) {
        const std::string path = opt.write_dir + "/" + c.name + "." + bench::row_name(kind) + ".mesh";
        if ((st = bodt_mesh_write(m, path.c_str())) != BODT_OK)
            std::fprintf(stderr, "bodt_bench_deformed: %s: %s\n", path.c_str(), errmsg(m, st).c_str());
    }
    return r;
}

// run_row in a forked child (a crash or a hang is contained); the child's
// peak RSS.
RowResult run_isolated(const DeformedCase& c, const DeformedMesh& dm, RowKind kind, const Options& opt) {
    RowResult r = bench::empty_row_result();
    const bench::ChildRun child =
        bench::run_isolated(r, opt.fork_runs, opt.timeout_s, [&] { return run_row(c, dm, kind, opt); });
    if (!child.ok) {
        bench::set_row_status(r, child.status.c_str(), child.where,
                              child.exit_status >= 0 ? "child exited without a result" : child.message);
        if (child.status != "error")  // the child died; pipe and fork failures are only recorded
            std::fprintf(stderr, "bodt_bench_deformed: %s / %s: %s\n", c.name.c_str(), bench::row_name(kind),
                         r.message);
    }
    r.peak_rss_mb = child.peak_rss_mb;
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse_args(argc, argv);
    FILE* json = stdout;
    if (!opt.json_path.empty() && !(json = std::fopen(opt.json_path.c_str(), "w")))
        usage_error("cannot write " + opt.json_path + ": " + std::strerror(errno));
    if (!opt.write_dir.empty()) mkdir(opt.write_dir.c_str(), 0777);

    std::string temp_dir;
    if (!bench::make_temp_dir("bodt-bench-deformed", temp_dir)) {
        std::fprintf(stderr, "bodt_bench_deformed: cannot make a temp dir %s\n", temp_dir.c_str());
        return 1;
    }

    std::vector<std::string> notes;
    std::string shared = opt.shared_dir;
    if (!shared.empty() && !bench::is_dir(shared)) {
        notes.push_back("shared folder " + shared + " not found: the generated box with a hole only");
        shared.clear();
    }
    std::vector<DeformedCase> cases = bench::make_deformed_cases(shared, opt.extra_meshes, opt.stretch, temp_dir, notes);
    bench::keep_cases_matching(cases, opt.case_regex);
    if (opt.list_only) {
        for (const auto& c : cases) std::printf("%-32s %-9s %s\n", c.name.c_str(), c.kind.c_str(), c.deformation.c_str());
        for (const auto& n : notes) std::printf("# %s\n", n.c_str());
        bench::remove_tree(temp_dir);
        return 0;
    }
    for (const auto& n : notes) std::fprintf(stderr, "bodt_bench_deformed: note: %s\n", n.c_str());

    const RowKind kinds[] = {RowKind::Original, RowKind::Deformed, RowKind::Odt, RowKind::Phased};
    const auto t_start = std::chrono::steady_clock::now();
    std::vector<CaseRows> results;
    for (size_t ci = 0; ci < cases.size(); ++ci) {
        const DeformedCase& c = cases[ci];
        CaseRows cr;
        cr.c = &c;
        cr.kinds.assign(std::begin(kinds), std::end(kinds));
        DeformedMesh dm;
        std::string err;
        bool ok = false;
        try {
            ok = c.prepare(dm, err);
        } catch (const std::exception& e) {
            err = e.what();
        }
        cr.note = dm.note;
        std::fprintf(stderr, "[%zu/%zu] %s: %s\n", ci + 1, cases.size(), c.name.c_str(),
                     ok ? dm.note.c_str() : ("cannot be made: " + err).c_str());
        for (RowKind k : kinds) {
            RowResult r = bench::empty_row_result();
            if (ok) {
                r = run_isolated(c, dm, k, opt);
            } else {
                cr.prep_error = err;
                bench::set_row_status(r, "error", "making the case", err);
            }
            cr.rows.push_back(r);
            std::fprintf(json, "%s\n", bench::row_json(cr, k, r, opt.max_steps).c_str());
            std::fflush(json);
            if (ok)
                std::fprintf(stderr,
                             "    %-8s %-7s %2d steps %8.2f s  T %7d  stretch %.3f/%7.3f  inverted %d\n",
                             bench::row_name(k), r.status, r.steps_done, r.time_s, r.tets, r.stretch_mean,
                             r.stretch_min, r.inverted);
        }
        results.push_back(std::move(cr));
    }
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    bench::remove_tree(temp_dir);
    if (json != stdout) std::fclose(json);
    const std::string md = bench::deformed_markdown(results, opt.max_steps, notes, total_s);
    if (!opt.markdown_path.empty() && !bench::write_text_file(opt.markdown_path, md))
        std::fprintf(stderr, "bodt_bench_deformed: cannot write %s\n", opt.markdown_path.c_str());
    return 0;
}
