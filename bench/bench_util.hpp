// bench_util.hpp -- helpers shared by bodt_bench and bodt_bench_deformed:
// printf into a string, JSON values, files and folders, the boundary of a
// tet mesh, memory in use, bodt handles and sized structs, a run in a
// forked child with a timeout, and an external program with a timeout.
#ifndef BODT_BENCH_UTIL_HPP
#define BODT_BENCH_UTIL_HPP

#include "bodt.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <regex>
#include <string>
#include <type_traits>
#include <vector>

namespace bench {

// ------------------------------------------------------------------- text

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
std::string fmt(const char* f, ...);

std::string json_str(const std::string& s);                    // quoted and escaped
std::string json_num(double v, const char* f = "%.6g");       // "null" when not finite

// --------------------------------------------------------- files, folders

bool ends_with(const std::string& s, const std::string& suffix);
bool is_dir(const std::string& p);
bool is_file(const std::string& p);

// A fresh folder $TMPDIR/PREFIX-XXXXXX (TMPDIR unset: /tmp).  path is the
// folder, or on failure (errno set) the template that was tried.
bool make_temp_dir(const std::string& prefix, std::string& path);
void remove_tree(const std::string& dir);

// false with errno set when path cannot be opened.
bool write_text_file(const std::string& path, const std::string& text);

// Keeps the cases whose name matches regex (searched); "" keeps all.
template <class C>
void keep_cases_matching(std::vector<C>& cases, const std::string& regex) {
    if (regex.empty()) return;
    const std::regex re(regex);
    std::vector<C> kept;
    for (auto& c : cases)
        if (std::regex_search(c.name, re)) kept.push_back(c);
    cases.swap(kept);
}

// ------------------------------------------------------------- meshes

// The faces that belong to exactly one tet (the domain boundary; faces
// between two tets of different regions are NOT included), 3 indices per
// triangle, 0-based, oriented as the tet's outward face for a positive tet,
// in a fixed order.  tets holds 4 indices per tet in base index_base.
std::vector<int32_t> boundary_triangles(const std::vector<int32_t>& tets, int index_base);

// Largest side of the axis-aligned bounding box of the vertices of the
// triangles (0-based, 3 per triangle) in xyz (3 per vertex); 0 without any.
double bbox_largest_side(const std::vector<double>& xyz, const std::vector<int32_t>& triangles);

// ------------------------------------------------------------- memory

// Bytes the C/C++ heap hands out now (glibc mallinfo2: uordblks + hblkhd,
// which includes mmap'ed blocks); -1 where it is not known.
int64_t heap_in_use();
// Resident set size of this process now (/proc/self/statm), -1 unknown.
int64_t rss_bytes();

// ------------------------------------------------------------------- bodt

// "BODT_ERR_...: the mesh's last error" for a status.
std::string errmsg(const bodt_mesh* m, int status);

struct MeshHandle {
    bodt_mesh* m = nullptr;
    MeshHandle() = default;
    MeshHandle(const MeshHandle&) = delete;
    MeshHandle& operator=(const MeshHandle&) = delete;
    ~MeshHandle() { bodt_mesh_destroy(m); }
};

// bodt's extensible structs (bodt_quality, bodt_step_report, ...) zeroed with
// their size set, so the library fills only what both sides know.
template <class T>
T sized_struct() {
    T t;
    std::memset(&t, 0, sizeof t);
    t.size = sizeof t;
    return t;
}

// ------------------------------------------------------ isolated runs

// What became of a run_isolated call.  A crash or a hang of the library in
// the child is reported here and the bench goes on.
struct ChildRun {
    bool ok = false;          // the result came back
    std::string status;       // otherwise "error" (pipe, fork), "timeout" or "crashed"
    std::string where;        // "pipe", "fork" or "child process"
    std::string message;
    int exit_status = -1;     // the child exited (without a result) with this
    double peak_rss_mb = 0;   // of the child (of this process without fork), 0 when it did not run
};

ChildRun run_isolated_bytes(void* result, size_t size, bool fork_runs, int timeout_s,
                            const std::function<void(void*)>& run);

// result = run(), in a forked child (fork_runs) that gets SIGALRM after
// timeout_s seconds (0: never); the result comes back through a pipe, so it
// must be plain data.  result is left as it is when the child gives nothing.
template <class Result, class Run>
ChildRun run_isolated(Result& result, bool fork_runs, int timeout_s, Run run) {
    static_assert(std::is_trivially_copyable<Result>::value, "the result goes through a pipe");
    return run_isolated_bytes(&result, sizeof result, fork_runs, timeout_s,
                              [&](void* out) { *static_cast<Result*>(out) = run(); });
}

// ------------------------------------------------------ external programs

struct ProcessRun {
    bool started = false;     // fork + exec worked
    bool timed_out = false;   // killed after timeout_s
    int exit_code = -1;       // when it exited
    int signal = 0;           // when a signal ended it
    double wall_s = 0;        // from fork to its end
    double peak_rss_mb = 0;   // its ru_maxrss
    std::string error;        // why it did not start
};

// Runs argv[0] (searched in PATH) with stdin from /dev/null and stdout and
// stderr into output_path; kills it (SIGKILL) after timeout_s seconds (<= 0:
// never).  It dies with the calling process (PR_SET_PDEATHSIG).
ProcessRun run_process(const std::vector<std::string>& argv, const std::string& output_path, double timeout_s);

// argv[0] found in PATH (or a path that exists): the full path, else "".
std::string find_program(const std::string& name);

// The whole file, "" if it cannot be read.
std::string read_text_file(const std::string& path);

}  // namespace bench

#endif
