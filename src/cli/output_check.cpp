#include "cli/output_check.hpp"

#include "bodt.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace bodt_cli {

namespace {

std::string directory_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

bool writable_file(const std::string& path, std::string& error) {
    struct stat st;
    if (stat(path.c_str(), &st) != 0) {
        if (errno == ENOENT) return true;  // to be created: the directory decides
        error = "cannot write '" + path + "': " + std::strerror(errno);
        return false;
    }
    if (S_ISDIR(st.st_mode)) {
        error = "cannot write '" + path + "': it is a directory";
        return false;
    }
    // access() asks as the real user and knows read-only file systems.
    if (access(path.c_str(), W_OK) != 0) {
        error = "cannot write '" + path + "': " + std::strerror(errno);
        return false;
    }
    return true;
}

}  // namespace

bool output_format(const std::string& path, int format, int& resolved, std::string& error) {
    resolved = format;
    if (format != BODT_FORMAT_AUTO) return true;
    if (bodt_format_from_path(path.c_str(), &resolved) == BODT_OK) return true;
    error = std::string("cannot write ") + bodt_mesh_last_error(nullptr) + ": --format gives it";
    return false;
}

bool writable(const std::string& path, bool tetgen, std::string& error) {
    if (path.empty()) {
        error = "the output file name is empty";
        return false;
    }
    const std::string dir = directory_of(path);
    struct stat st;
    if (stat(dir.c_str(), &st) != 0) {
        error = "cannot write '" + path + "': directory '" + dir + "': " + std::strerror(errno);
        return false;
    }
    if (!S_ISDIR(st.st_mode)) {
        error = "cannot write '" + path + "': '" + dir + "' is not a directory";
        return false;
    }
    if (access(dir.c_str(), W_OK | X_OK) != 0) {
        error = "cannot write '" + path + "': directory '" + dir + "': " + std::strerror(errno);
        return false;
    }
    if (!tetgen) return writable_file(path, error);
    const std::string stem = path.substr(0, path.find_last_of('.'));
    for (const char* ext : {".node", ".ele", ".face"})
        if (!writable_file(stem + ext, error)) return false;
    return true;
}

bool check_mesh_output(const std::string& path, int format, std::string& error) {
    int resolved = BODT_FORMAT_AUTO;
    return output_format(path, format, resolved, error) &&
           writable(path, resolved == BODT_FORMAT_TETGEN, error);
}

}  // namespace bodt_cli
