// bench_util.cpp -- see bench_util.hpp.
#include "bench_util.hpp"

#include <fcntl.h>
#include <ftw.h>
#include <malloc.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>

namespace bench {

std::string fmt(const char* f, ...) {
    va_list ap, ap2;
    va_start(ap, f);
    va_copy(ap2, ap);
    const int n = std::vsnprintf(nullptr, 0, f, ap);
    va_end(ap);
    std::string b(n > 0 ? size_t(n) : 0, '\0');
    if (n > 0) std::vsnprintf(&b[0], size_t(n) + 1, f, ap2);
    va_end(ap2);
    return b;
}

std::string json_str(const std::string& s) {
    std::string o = "\"";
    for (unsigned char ch : s) {
        if (ch == '"' || ch == '\\') o += '\\', o += char(ch);
        else if (ch < 0x20) o += fmt("\\u%04x", ch);
        else o += char(ch);
    }
    return o + "\"";
}

std::string json_num(double v, const char* f) { return std::isfinite(v) ? fmt(f, v) : "null"; }

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool is_dir(const std::string& p) {
    struct stat st;
    return stat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

bool is_file(const std::string& p) {
    struct stat st;
    return stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

bool make_temp_dir(const std::string& prefix, std::string& path) {
    const char* root = std::getenv("TMPDIR");
    path = std::string(root && *root ? root : "/tmp") + "/" + prefix + "-XXXXXX";
    std::vector<char> buf(path.begin(), path.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) return false;
    path = buf.data();
    return true;
}

namespace {
int remove_entry(const char* path, const struct stat*, int, struct FTW*) { return remove(path); }
}  // namespace

void remove_tree(const std::string& dir) { nftw(dir.c_str(), remove_entry, 16, FTW_DEPTH | FTW_PHYS); }

bool write_text_file(const std::string& path, const std::string& text) {
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    std::fputs(text.c_str(), f);
    std::fclose(f);
    return true;
}

std::string read_text_file(const std::string& path) {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return "";
    std::string text;
    char buf[1 << 14];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
    std::fclose(f);
    return text;
}

// ------------------------------------------------------------- meshes

std::vector<int32_t> boundary_triangles(const std::vector<int32_t>& tets, int index_base) {
    // Each face goes to the bucket of its smallest vertex (counting sort),
    // with its other two vertices sorted and the face's code 4 t + f; a face
    // alone in its bucket with its (b, c) is a boundary face.  12 bytes per
    // tet face, so a 1e7-tet mesh takes about 0.5 GB here.
    static const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    const size_t ntets = tets.size() / 4;
    int32_t nv = 0;
    for (int32_t v : tets) nv = std::max(nv, v - index_base + 1);
    std::vector<int64_t> start(size_t(nv) + 1, 0);
    auto face_min = [&](size_t t, const int* f) {
        return std::min({tets[4 * t + size_t(f[0])], tets[4 * t + size_t(f[1])], tets[4 * t + size_t(f[2])]}) -
               index_base;
    };
    for (size_t t = 0; t < ntets; ++t)
        for (const auto& f : kFace) ++start[size_t(face_min(t, f)) + 1];
    for (size_t v = 0; v < size_t(nv); ++v) start[v + 1] += start[v];
    struct Entry {
        int32_t b, c;  // the other two vertices, b < c
        uint32_t code;  // 4 t + f (tets < 2^30)
    };
    std::vector<Entry> entries(4 * ntets);
    std::vector<int64_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < ntets; ++t)
        for (int f = 0; f < 4; ++f) {
            std::array<int32_t, 3> s3 = {tets[4 * t + size_t(kFace[f][0])] - index_base,
                                         tets[4 * t + size_t(kFace[f][1])] - index_base,
                                         tets[4 * t + size_t(kFace[f][2])] - index_base};
            std::sort(s3.begin(), s3.end());
            entries[size_t(fill[size_t(s3[0])]++)] = {s3[1], s3[2], uint32_t(4 * t + size_t(f))};
        }
    std::vector<int32_t> out;
    for (size_t v = 0; v < size_t(nv); ++v) {
        Entry* lo = entries.data() + start[v];
        Entry* hi = entries.data() + start[v + 1];
        std::sort(lo, hi, [](const Entry& x, const Entry& y) { return x.b != y.b ? x.b < y.b : x.c < y.c; });
        for (Entry* e = lo; e < hi;) {
            Entry* g = e + 1;
            while (g < hi && g->b == e->b && g->c == e->c) ++g;
            if (g - e == 1) {
                const size_t t = e->code / 4;
                const int* f = kFace[e->code % 4];
                for (int k = 0; k < 3; ++k) out.push_back(tets[4 * t + size_t(f[k])] - index_base);
            }
            e = g;
        }
    }
    return out;
}

double bbox_largest_side(const std::vector<double>& xyz, const std::vector<int32_t>& triangles) {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int32_t v : triangles)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], xyz[3 * size_t(v) + size_t(k)]);
            hi[k] = std::max(hi[k], xyz[3 * size_t(v) + size_t(k)]);
        }
    return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0.0});
}

// ------------------------------------------------------------- memory

int64_t heap_in_use() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    const struct mallinfo2 mi = mallinfo2();
    return int64_t(mi.uordblks) + int64_t(mi.hblkhd);
#else
    return -1;
#endif
}

int64_t rss_bytes() {
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return -1;
    long size = 0, resident = 0;
    const int n = std::fscanf(f, "%ld %ld", &size, &resident);
    std::fclose(f);
    return n == 2 ? int64_t(resident) * int64_t(sysconf(_SC_PAGESIZE)) : -1;
}

std::string errmsg(const bodt_mesh* m, int status) {
    const char* e = bodt_mesh_last_error(m);
    return std::string(bodt_status_string(status)) + (e && *e ? std::string(": ") + e : std::string());
}

// ------------------------------------------------------ isolated runs

namespace {

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

ChildRun failed(const char* status, const char* where, const std::string& message) {
    ChildRun c;
    c.status = status;
    c.where = where;
    c.message = message;
    return c;
}

}  // namespace

ChildRun run_isolated_bytes(void* result, size_t size, bool fork_runs, int timeout_s,
                            const std::function<void(void*)>& run) {
    ChildRun c;
    if (!fork_runs) {  // for debuggers: a crash ends the bench
        run(result);
        struct rusage ru;
        getrusage(RUSAGE_SELF, &ru);
        c.ok = true;
        c.peak_rss_mb = double(ru.ru_maxrss) / 1024.0;
        return c;
    }
    int fds[2];
    if (pipe(fds) != 0) return failed("error", "pipe", std::strerror(errno));
    std::fflush(stdout);  // or the child prints what is buffered again
    std::fflush(stderr);
    const pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        if (timeout_s > 0) alarm(unsigned(timeout_s));
        run(result);
        const bool ok = write_all(fds[1], result, size);
        std::fflush(stderr);
        _exit(ok ? 0 : 3);
    }
    const int fork_errno = errno;
    close(fds[1]);
    if (pid < 0) {
        close(fds[0]);
        return failed("error", "fork", std::strerror(fork_errno));
    }
    std::vector<char> got(size);  // a partial result must not touch result
    const size_t n = read_all(fds[0], got.data(), size);
    close(fds[0]);
    int wst = 0;
    struct rusage ru;
    std::memset(&ru, 0, sizeof ru);
    while (wait4(pid, &wst, 0, &ru) < 0 && errno == EINTR) {
    }
    if (n == size) {
        std::memcpy(result, got.data(), size);
        c.ok = true;
    } else if (WIFSIGNALED(wst)) {
        const int sig = WTERMSIG(wst);
        c = failed(sig == SIGALRM ? "timeout" : "crashed", "child process",
                   sig == SIGALRM ? "no result after " + std::to_string(timeout_s) + " s"
                                  : std::string("killed by signal ") + std::to_string(sig) + " (" + strsignal(sig) +
                                        ")");
    } else {
        const int code = WIFEXITED(wst) ? WEXITSTATUS(wst) : -1;
        c = failed("crashed", "child process",
                   "child exited with status " + std::to_string(code) + " without a result");
        c.exit_status = code;
    }
    c.peak_rss_mb = double(ru.ru_maxrss) / 1024.0;
    return c;
}

// ------------------------------------------------------ external programs

std::string find_program(const std::string& name) {
    if (name.find('/') != std::string::npos) return access(name.c_str(), X_OK) == 0 ? name : "";
    const char* path = std::getenv("PATH");
    std::string p = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
    size_t a = 0;
    while (a <= p.size()) {
        size_t b = p.find(':', a);
        if (b == std::string::npos) b = p.size();
        const std::string cand = (b > a ? p.substr(a, b - a) : std::string(".")) + "/" + name;
        if (is_file(cand) && access(cand.c_str(), X_OK) == 0) return cand;
        a = b + 1;
    }
    return "";
}

ProcessRun run_process(const std::vector<std::string>& argv, const std::string& output_path, double timeout_s) {
    ProcessRun r;
    if (argv.empty()) {
        r.error = "no program";
        return r;
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::fflush(stdout);
    std::fflush(stderr);
    const auto t0 = std::chrono::steady_clock::now();
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
        r.error = std::string("fork: ") + std::strerror(errno);
        return r;
    }
    if (pid == 0) {
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent) _exit(127);
        const int in = open("/dev/null", O_RDONLY);
        const int out = open(output_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (in >= 0) dup2(in, 0);
        if (out >= 0) {
            dup2(out, 1);
            dup2(out, 2);
        }
        execvp(args[0], args.data());
        std::fprintf(stderr, "cannot run %s: %s\n", args[0], std::strerror(errno));
        _exit(127);
    }
    r.started = true;
    int wst = 0;
    struct rusage ru;
    std::memset(&ru, 0, sizeof ru);
    for (;;) {
        const pid_t w = wait4(pid, &wst, WNOHANG, &ru);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) {
            r.error = std::string("wait4: ") + std::strerror(errno);
            break;
        }
        const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (timeout_s > 0 && el > timeout_s && !r.timed_out) {
            r.timed_out = true;
            kill(pid, SIGKILL);
        }
        usleep(el < 1.0 ? 1000 : 10000);
    }
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (WIFEXITED(wst)) r.exit_code = WEXITSTATUS(wst);
    if (WIFSIGNALED(wst)) r.signal = WTERMSIG(wst);
    r.peak_rss_mb = double(ru.ru_maxrss) / 1024.0;
    return r;
}

}  // namespace bench
