// The text of the reader tests' files (test_io_gmsh, test_io_vtk,
// test_io_vtu, test_io_vtu_compressed): a file read or written whole, a
// piece of a template replaced, the line a marker is on.  Their failures
// fail the case (CHECK and fail_msg do not return).
#pragma once

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "core_checks.hpp"

namespace io_test {

inline std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail_msg("cannot read %s", path.c_str());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_text(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) fail_msg("cannot write %s", path.c_str());
}

// `s` with its first `from` replaced by `to`; `from` must be there.
inline std::string replace(const char* what, std::string s, const std::string& from, const std::string& to) {
    const size_t at = s.find(from);
    CHECK(at != std::string::npos, "'%s' not in the template", from.c_str());
    return s.replace(at, from.size(), to);
}

// The 1-based line of the first `marker` in `text`; `marker` must be there.
inline long line_of(const char* what, const std::string& text, const std::string& marker) {
    const size_t at = text.find(marker);
    CHECK(at != std::string::npos, "'%s' not in the file", marker.c_str());
    return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

}  // namespace io_test
