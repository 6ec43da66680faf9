// bench_util.cpp -- see bench_util.hpp.
#include "bench_util.hpp"

#include <ftw.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
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

}  // namespace bench
