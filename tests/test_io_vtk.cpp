// test_io_vtk: white-box tests of the VTK legacy (.vtk) reader and writer
// (links bodt_core), against the specification in src/io/vtk_legacy.hpp and
// src/io/vtk_cells.hpp.  Usage: test_io_vtk [scratch-dir]; files are
// written there (default: ./test_io_vtk_files, created if missing).
//
//   round trip        a 2x2x2 block of Kuhn cubes (48 tets, base 1) with
//                     regions (also negative), marked triangles (also an
//                     interface and a negative marker), feature edges with
//                     refs (also -1, the tets' filler), vertex refs, fixed
//                     vertices, corners and tet fields through write_vtk /
//                     read_vtk: coordinates bit-exact, all the mesh data back
//                     (base 0); the written file taken apart by this test's
//                     own big-endian parser: "# vtk DataFile Version 4.2",
//                     BINARY, double points, the 4.2 cell layout, the types,
//                     region / marker / fixed / corner / ref arrays of the
//                     right types and the tet fields (NaN on non-tets), their
//                     names %XX-escaped (space, '%', tab, UTF-8); edges
//                     without refs come back with ref 0, with and without
//                     triangles; inconsistent MeshData and unwritable paths
//   hand-written      files as other programs write them, each checked
//                     against the sample's known content (all the cases run,
//                     the failures are listed): Mesquite's ASCII 2.0 (float
//                     `fixed` flags, GLOBAL_ID arrays skipped), also as
//                     versions 1.0 to 4.1; VTK 9's ASCII 5.1 (FIELD data
//                     before POINTS, METADATA blocks, OFFSETS / CONNECTIVITY
//                     vtktypeint64, FIELD arrays in CELL_DATA); binary 4.2
//                     and 5.1 built here byte by byte (float, double, int,
//                     short, vtktypeint64, unsigned_int, unsigned_char data;
//                     bytes '\n' and ' ' inside the data); every skipped
//                     attribute (VECTORS, NORMALS, TENSORS, TENSORS6,
//                     TEXTURE_COORDINATES, COLOR_SCALARS, LOOKUP_TABLE with a
//                     size, GLOBAL_IDS, PEDIGREE_IDS, other SCALARS and FIELD
//                     arrays) in ASCII and binary; lower-case keywords and
//                     type names, an empty title, CRLF line ends; %XX-escaped
//                     names decoded; our names in the other section ignored;
//                     vertex cells ignored (also first); triangles without a
//                     marker array get marker 0; INT32_MIN / INT32_MAX
//   ASCII float       "POINTS n float" values read as floats (as VTK and the
//                     .vtu reader do), "double" ones as doubles
//   VTK 9.1 metadata  VTK's own output with COMPONENT_NAMES holding an empty
//                     name (an empty line inside the METADATA block)
//   meshio            meshio 5.0's ASCII and binary files (vtktypeint32,
//                     one value a line, no final newline); regions and
//                     markers from gmsh:physical, CellEntityIds or
//                     medit:ref, vertex refs from medit:ref, the precedence
//                     of vtk_cells.hpp when several are present, a short
//                     overridden array still refused
//   refusals          POLYDATA, STRUCTURED_GRID, hexahedra, quadratic tets,
//                     the bit type, string arrays, no tets, a second POINTS,
//                     CELLS, CELL_TYPES or DATASET, unsigned 64-bit values
//                     past 32 bits: Error(BODT_ERR_IO) naming the cause
//   malformed         about 100 broken files, ASCII and binary: each an
//                     Error(BODT_ERR_IO) whose message starts with
//                     "<path>:<line>: " (ASCII, and the header of a binary
//                     file; the expected line) or "<path>: byte <offset>: "
//                     (binary data), within the file, and names the cause;
//                     no allocation of more than 16 MB for any of these
//                     small files (huge counts included); all the cases
//                     run, the failures are listed
//   mutations         3000 random changes to valid files: each reads to
//                     consistent MeshData or gives such an error, with no
//                     allocation over 16 MB
#include "common/error.hpp"
#include "io/mesh_io.hpp"
#include "io/vtk_legacy.hpp"

#include "bodt.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core_checks.hpp"
#include "broken_files.hpp"
#include "file_text.hpp"
#include "kuhn_block_data.hpp"

namespace {

using io_test::line_of;
using io_test::read_text;
using io_test::replace;
using io_test::write_text;

std::string g_dir = "test_io_vtk_files";

std::string scratch(const std::string& name) { return g_dir + "/" + name; }

// ------------------------------------------------------------ big-endian bytes (test's own)

// A file built byte by byte: text lines and big-endian values.
struct Bytes {
    std::string s;
    Bytes& text(const std::string& t) {
        s += t;
        return *this;
    }
    template <class T>
    Bytes& be(T value) {
        unsigned char b[sizeof(T)];
        std::memcpy(b, &value, sizeof(T));  // the test machine is little-endian (checked in main)
        for (size_t k = sizeof(T); k-- > 0;) s += static_cast<char>(b[k]);
        return *this;
    }
    template <class T, class U>
    Bytes& all(std::initializer_list<U> values) {
        for (U v : values) be(static_cast<T>(v));
        return *this;
    }
};

template <class T>
T get_be(const std::string& s, size_t at) {
    unsigned char b[sizeof(T)];
    for (size_t k = 0; k < sizeof(T); ++k) b[k] = static_cast<unsigned char>(s[at + sizeof(T) - 1 - k]);
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
}

// VTK's %XX escapes, decoded.
std::string decode_name(const std::string& s) {
    std::string out;
    for (size_t k = 0; k < s.size(); ++k) {
        if (s[k] == '%' && k + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[k + 1])) &&
            std::isxdigit(static_cast<unsigned char>(s[k + 2]))) {
            out += static_cast<char>(std::stoi(s.substr(k + 1, 2), nullptr, 16));
            k += 2;
        } else {
            out += s[k];
        }
    }
    return out;
}

// ------------------------------------------------------------ the written file, taken apart

// What a binary 4.2 file as write_vtk writes it holds: the four header
// lines, POINTS, CELLS, CELL_TYPES, then CELL_DATA / POINT_DATA with SCALARS
// + LOOKUP_TABLE default arrays.  Anything else fails the test.
struct Written {
    std::string header[4];
    std::string points_type;
    std::vector<double> points;
    std::vector<int32_t> cells, types;
    int64_t ncells = -1, cells_size = -1, cell_data = -1, point_data = -1;
    struct Array {
        std::string type;
        std::vector<double> values;
    };
    std::map<std::string, Array> cell_arrays, point_arrays;  // by the name as written
};

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    std::string w;
    while (in >> w) out.push_back(w);
    return out;
}

Written parse_written(const char* what, const std::string& s) {
    Written w;
    size_t at = 0;
    auto line = [&]() {
        const size_t end = s.find('\n', at);
        CHECK(end != std::string::npos, "no end of line after byte %zu", at);
        std::string l = s.substr(at, end - at);
        at = end + 1;
        return l;
    };
    // n values of `type`, big-endian, from `at`; then the newline VTK puts after binary data.
    auto values = [&](const std::string& type, int64_t n) {
        size_t size = 0;
        if (type == "double") size = 8;
        else if (type == "float" || type == "int") size = 4;
        else if (type == "unsigned_char") size = 1;
        CHECK(size > 0, "unexpected type '%s'", type.c_str());
        CHECK(n >= 0 && at + size * static_cast<size_t>(n) <= s.size(), "%lld values of %s past the end",
              static_cast<long long>(n), type.c_str());
        std::vector<double> v;
        for (int64_t k = 0; k < n; ++k, at += size) {
            if (size == 8) v.push_back(get_be<double>(s, at));
            else if (type == "float") v.push_back(get_be<float>(s, at));
            else if (size == 4) v.push_back(get_be<int32_t>(s, at));
            else v.push_back(static_cast<unsigned char>(s[at]));
        }
        CHECK(at < s.size() && s[at] == '\n', "no newline after the %s data at byte %zu", type.c_str(), at);
        ++at;
        return v;
    };
    for (auto& h : w.header) h = line();
    std::map<std::string, Written::Array>* arrays = nullptr;
    int64_t count = 0;
    while (at < s.size()) {
        const std::vector<std::string> f = split(line());
        CHECK(!f.empty(), "an empty line before byte %zu", at);
        if (f[0] == "POINTS") {
            CHECK(f.size() == 3 && w.points.empty(), "POINTS line");
            w.points_type = f[2];
            w.points = values(f[2], 3 * std::stoll(f[1]));
        } else if (f[0] == "CELLS") {
            CHECK(f.size() == 3 && w.ncells < 0, "CELLS line");
            w.ncells = std::stoll(f[1]);
            w.cells_size = std::stoll(f[2]);
            for (double x : values("int", w.cells_size)) w.cells.push_back(static_cast<int32_t>(x));
        } else if (f[0] == "CELL_TYPES") {
            CHECK(f.size() == 2 && w.types.empty(), "CELL_TYPES line");
            for (double x : values("int", std::stoll(f[1]))) w.types.push_back(static_cast<int32_t>(x));
        } else if (f[0] == "CELL_DATA" || f[0] == "POINT_DATA") {
            CHECK(f.size() == 2, "%s line", f[0].c_str());
            count = std::stoll(f[1]);
            const bool cells = f[0] == "CELL_DATA";
            CHECK((cells ? w.cell_data : w.point_data) < 0, "a second %s", f[0].c_str());
            (cells ? w.cell_data : w.point_data) = count;
            arrays = cells ? &w.cell_arrays : &w.point_arrays;
        } else if (f[0] == "SCALARS") {
            CHECK(arrays && (f.size() == 3 || (f.size() == 4 && f[3] == "1")), "SCALARS line");
            CHECK(!arrays->count(f[1]), "array %s twice", f[1].c_str());
            const std::string lut = line();
            CHECK(lut == "LOOKUP_TABLE default", "'%s' after SCALARS %s", lut.c_str(), f[1].c_str());
            (*arrays)[f[1]] = {f[2], values(f[2], count)};
        } else {
            CHECK(false, "unexpected line '%s'", f[0].c_str());
        }
    }
    return w;
}

// ------------------------------------------------------------ test mesh

using io_test::decorate;
using io_test::kuhn_block;
using io_test::sorted_tri;
using io_test::Tri;

// ------------------------------------------------------------ helpers

// Runs f, which must throw bodt::Error(BODT_ERR_IO); returns the message.
template <class F>
std::string io_error(const char* what, F f) {
    try {
        f();
    } catch (const bodt::Error& e) {
        CHECK(e.status() == BODT_ERR_IO, "status %d (%s)", e.status(), e.what());
        return e.what();
    } catch (const std::exception& e) {
        CHECK(false, "not a bodt::Error: %s", e.what());
    }
    CHECK(false, "no error was raised");
    return {};
}

// Where a message says the problem is: "<path>:<line>: " or "<path>: byte <offset>: ".
struct Where {
    enum Kind { Line, Byte, Either } kind;
    long lo, hi;  // for Line: the lines allowed, 0 0 for any
};
Where at_line(long n) { return {Where::Line, n, n}; }
Where at_lines(long lo, long hi) { return {Where::Line, lo, hi}; }
const Where kAnyLine = {Where::Line, 0, 0};
const Where kByte = {Where::Byte, 0, 0};
const Where kEither = {Where::Either, 0, 0};

// Parses the position out of `msg` (which must start with `path`); returns
// false when it has neither form.  `line` / `byte` get the number.
bool position(const std::string& msg, const std::string& path, long* line, long* byte) {
    *line = *byte = -1;
    if (msg.compare(0, path.size(), path) != 0) return false;
    const char* rest = msg.c_str() + path.size();
    char* end = nullptr;
    if (rest[0] == ':' && std::isdigit(static_cast<unsigned char>(rest[1]))) {
        *line = std::strtol(rest + 1, &end, 10);
        return *line >= 1 && std::strncmp(end, ": ", 2) == 0 && end[2] != '\0';
    }
    if (std::strncmp(rest, ": byte ", 7) == 0 && std::isdigit(static_cast<unsigned char>(rest[7]))) {
        *byte = std::strtol(rest + 7, &end, 10);
        return *byte >= 0 && std::strncmp(end, ": ", 2) == 0 && end[2] != '\0';
    }
    return false;
}

// Reads `text` from scratch/name and returns what is wrong with the outcome
// ("" when nothing): it must be an Error(BODT_ERR_IO) at `where` whose
// message contains `needle`, with no allocation over kAllocLimit.
std::string malformed_problem(const std::string& name, const std::string& text, const std::string& needle,
                              Where where) {
    const std::string path = scratch(name);
    std::string msg;
    const std::string refused = io_test::refusal_problem(path, text, bodt::read_vtk, msg);
    if (!refused.empty()) return refused;
    long line, byte;
    if (!position(msg, path, &line, &byte))
        return "'" + msg + "' does not start with '<path>:<line>: ' or '<path>: byte <n>: '";
    const long lines = 1 + static_cast<long>(std::count(text.begin(), text.end(), '\n'));
    if (where.kind == Where::Line && line < 0) return "'" + msg + "': a line number expected";
    if (where.kind == Where::Line && where.lo > 0 && (line < where.lo || line > where.hi))
        return "'" + msg + "': line " + std::to_string(where.lo) +
               (where.hi > where.lo ? "-" + std::to_string(where.hi) : std::string()) + " expected";
    if (line > lines) return "'" + msg + "': a line past the end";
    if (where.kind == Where::Byte && byte < 0) return "'" + msg + "': a byte offset expected";
    if (byte > static_cast<long>(text.size())) return "'" + msg + "': a byte past the end";
    if (msg.find(needle) == std::string::npos) return "'" + msg + "' does not mention '" + needle + "'";
    return "";
}

// malformed_problem, as a check; returns the message.
std::string expect_malformed(const char* what, const std::string& name, const std::string& text,
                             const std::string& needle, Where where) {
    const std::string problem = malformed_problem(name, text, needle, where);
    CHECK(problem.empty(), "%s: %s", name.c_str(), problem.c_str());
    return io_error(what, [&] { bodt::read_vtk(scratch(name)); });
}

// A table of files that must each be refused: every case is tried, the
// failures are printed, and the check fails when there is any.
struct Case {
    std::string name, text, needle;
    Where where;
};

void expect_all_malformed(const char* what, const std::vector<Case>& cases) {
    int failed = 0;
    std::set<std::string> names;
    for (const Case& c : cases) {
        CHECK(names.insert(c.name).second, "case %s twice", c.name.c_str());
        const std::string problem = malformed_problem(c.name, c.text, c.needle, c.where);
        if (problem.empty()) continue;
        ++failed;
        std::printf("%s: %s: %s\n", what, c.name.c_str(), problem.c_str());
    }
    CHECK(failed == 0, "%d of %zu cases failed (listed above)", failed, cases.size());
}

// ------------------------------------------------------------ hand-written files

// The sample mesh of the hand-written files: two tets, a marked triangle, a
// line, a vertex cell (ignored); the float points below.
const float kPts[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.125f, 0.25f, -1};

// What a reading of the sample must give; empty vectors: absent.
struct Expect {
    std::vector<int32_t> regions = {3, 4}, markers = {7}, edge_refs = {12}, fixed = {0, 4}, refs = {0, -5, 2, 0, 7},
                         corners = {1};
    bool triangle = true, edge = true;
};

// What differs between a reading of the sample and `e` ("" when nothing).
std::string sample_problem(const bodt::MeshData& d, const Expect& e) {
    auto list = [](const std::vector<int32_t>& v) {
        std::string out = "{";
        for (int32_t x : v) out += (out.size() > 1 ? " " : "") + std::to_string(x);
        return out + "}";
    };
    if (d.base != 0) return "base " + std::to_string(d.base);
    if (d.xyz.size() != 15) return std::to_string(d.xyz.size()) + " coordinates";
    for (int k = 0; k < 15; ++k)
        if (d.xyz[k] != static_cast<double>(kPts[k])) {
            char buf[100];
            std::snprintf(buf, sizeof buf, "coordinate %d is %.17g, not %.17g", k, d.xyz[k],
                          static_cast<double>(kPts[k]));
            return buf;
        }
    if (d.tets != std::vector<int32_t>{0, 1, 2, 3, 0, 2, 1, 4}) return "tets " + list(d.tets);
    if (d.regions != e.regions) return "regions " + list(d.regions);
    if (d.triangles != (e.triangle ? std::vector<int32_t>{0, 1, 3} : std::vector<int32_t>{}))
        return "triangles " + list(d.triangles);
    if (d.tri_markers != e.markers) return "markers " + list(d.tri_markers);
    if (d.feature_edges != (e.edge ? std::vector<int32_t>{0, 3} : std::vector<int32_t>{}))
        return "feature edges " + list(d.feature_edges);
    if (d.edge_refs != e.edge_refs) return "edge refs " + list(d.edge_refs);
    if (d.fixed != e.fixed) return "fixed " + list(d.fixed);
    if (d.vertex_refs != e.refs) return "vertex refs " + list(d.vertex_refs);
    if (d.corners != e.corners) return "corners " + list(d.corners);
    if (!d.tet_fields.empty()) return "tet fields read";
    return "";
}

// Reads `text` from scratch/name and returns what is wrong ("" when nothing).
std::string read_problem(const std::string& name, const std::string& text, const Expect& e) {
    write_text(scratch(name), text);
    try {
        return sample_problem(bodt::read_vtk(scratch(name)), e);
    } catch (const std::exception& ex) {
        return std::string("not read: ") + ex.what();
    }
}

// ASCII 4.2 with every array of the sample as SCALARS (one a FIELD array),
// and a double array of another name (skipped).
const std::string kAscii42 = R"(# vtk DataFile Version 4.2
hand written, as VTK writes it
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 5 float
0 0 0 1 0 0 0 1 0
0 0 1 0.125 0.25 -1
CELLS 5 19
4 0 1 2 3
4 0 2 1 4
3 0 1 3
2 0 3
1 4

CELL_TYPES 5
10
10
5
3
1

CELL_DATA 5
SCALARS region int 1
LOOKUP_TABLE default
3 4 -1 -1 -1
SCALARS marker int
LOOKUP_TABLE default
-1 -1 7 12 -1
SCALARS q%20a double 1
LOOKUP_TABLE default
0.5 0.25 -1 -1 -1
POINT_DATA 5
SCALARS fixed unsigned_char 1
LOOKUP_TABLE default
1 0 0 0 1
SCALARS ref int 1
LOOKUP_TABLE default
0 -5 2 0 7
FIELD FieldData 1
corner 1 5 unsigned_char
0 1 0 0 0
)";

// ASCII 5.1 as VTK 9 writes it: dataset FIELD data before POINTS, a
// METADATA block after the points, OFFSETS / CONNECTIVITY, cell arrays as
// FIELD arrays; fixed as float, as Mesquite has it.
const std::string kAscii51 = R"(# vtk DataFile Version 5.1
vtk output
ASCII
DATASET UNSTRUCTURED_GRID
FIELD FieldData 1
TIME 1 1 double
0.5 
POINTS 5 float
0 0 0 1 0 0 0 1 0 
0 0 1 0.125 0.25 -1 
METADATA
INFORMATION 0

CELLS 6 14
OFFSETS vtktypeint64
0 4 8 11 13 14 
CONNECTIVITY vtktypeint64
0 1 2 3 0 2 1 4 0 
1 3 0 3 4 
CELL_TYPES 5
10
10
5
3
1

CELL_DATA 5
FIELD FieldData 2
region 1 5 int
3 4 -1 -1 -1 
marker 1 5 int
-1 -1 7 12 -1 
POINT_DATA 5
SCALARS fixed float
LOOKUP_TABLE default
1 0 0 0 1 
SCALARS ref int 1
LOOKUP_TABLE default
0 -5 2 0 7 
SCALARS corner unsigned_char 1
LOOKUP_TABLE default
0 1 0 0 0 
)";

// Mesquite's ASCII 2.0 (MeshImpl::write_vtk): float points, tets only, a
// float `fixed` flag, GLOBAL_ID arrays (skipped).
const std::string kMesquite = R"(# vtk DataFile Version 2.0
Mesquite Mesh
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 5 float
0 0 0
1 0 0
0 1 0
0 0 1
0.125 0.25 -1
CELLS 2 10
4 0 1 2 3
4 0 2 1 4
CELL_TYPES 2
10
10

POINT_DATA 5
SCALARS fixed float
LOOKUP_TABLE default
1
0
0
0
1
SCALARS GLOBAL_ID int 1
LOOKUP_TABLE default
0 1 2 3 4
CELL_DATA 2
SCALARS GLOBAL_ID int 1
LOOKUP_TABLE default
0 1
)";

// Written by VTK 9.1's vtkUnstructuredGridWriter (default version 5.1) for
// one tet whose points and velocity have a component name and a range:
// METADATA with COMPONENT_NAMES (empty names are empty lines) and
// INFORMATION.
const std::string kVtk91 =
    "# vtk DataFile Version 5.1\nvtk output\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
    "0 0 0 1 0 0 0 1 0 \n0 0 1 \nMETADATA\nCOMPONENT_NAMES\nX\n\n\nINFORMATION 1\n"
    "NAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1 \n\n"
    "CELLS 2 4\nOFFSETS vtktypeint64\n0 4 \nCONNECTIVITY vtktypeint64\n0 1 2 3 \nCELL_TYPES 1\n10\n\n"
    "POINT_DATA 4\nVECTORS velocity double\n0 0 1 1 0 1 2 0 1 \n3 0 1 \nMETADATA\nCOMPONENT_NAMES\n\nvy\n\n"
    "INFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 1 3.16228 \n\n";

// Every attribute the reader skips, in ASCII (3.0): SCALARS of other names
// and of 3 components, VECTORS, NORMALS, TENSORS, TENSORS6, GLOBAL_IDS,
// COLOR_SCALARS (floats in ASCII), LOOKUP_TABLE with a size (4 floats per
// entry), TEXTURE_COORDINATES, PEDIGREE_IDS, FIELD arrays; the region as
// whole doubles, a %XX-escaped name.
const std::string kAttributes = R"(# vtk DataFile Version 3.0
every attribute
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 5 double
0 0 0 1 0 0 0 1 0 0 0 1 0.125 0.25 -1
CELLS 5 19
4 0 1 2 3 4 0 2 1 4 3 0 1 3 2 0 3 1 4
CELL_TYPES 5
10 10 5 3 1
CELL_DATA 5
SCALARS re%67ion double 1
LOOKUP_TABLE default
3.0 4e0 -1 -1 -1
VECTORS velocity float
1 2 3 4 5 6 7 8 9 10 11 12 13 14 15
NORMALS normals double
0 0 1 0 0 1 0 0 1 0 0 1 0 0 1
TENSORS stress float
1 0 0 0 1 0 0 0 1
1 0 0 0 1 0 0 0 1
1 0 0 0 1 0 0 0 1
1 0 0 0 1 0 0 0 1
1 0 0 0 1 0 0 0 1
TENSORS6 strain float
1 2 3 4 5 6 1 2 3 4 5 6 1 2 3 4 5 6 1 2 3 4 5 6 1 2 3 4 5 6
GLOBAL_IDS cell_ids int
0 1 2 3 4
SCALARS marker short 1
LOOKUP_TABLE default
-1 -1 7 12 -1
SCALARS regionx int 1
LOOKUP_TABLE default
9 9 9 9 9
POINT_DATA 5
COLOR_SCALARS colors 3
0 0.5 1 1 1 1 0 0 0 0.25 0.5 0.75 1 0 1
LOOKUP_TABLE my_table 2
0 0 0 1 1 1 1 1
TEXTURE_COORDINATES uv 2 float
0 0 1 0 0 1 1 1 0.5 0.5
PEDIGREE_IDS point_ids int
10 11 12 13 14
SCALARS fixed int 1
LOOKUP_TABLE my_table
1 0 0 0 1
SCALARS flow float 3
LOOKUP_TABLE default
0 0 0 1 1 1 2 2 2 3 3 3 4 4 4
FIELD FieldData 3
corner 1 5 int
0 1 0 0 0
other 3 5 float
0 0 0 1 1 1 2 2 2 3 3 3 4 4 4
ref 1 5 long
0 -5 2 0 7
)";

// kAscii42 in lower case: keywords, type names, ASCII, the dataset type
// (VTK's reader lower-cases them all); the title is empty.
const std::string kLower = R"(# vtk DataFile Version 4.2

ascii
dataset unstructured_grid
points 5 FLOAT
0 0 0 1 0 0 0 1 0
0 0 1 0.125 0.25 -1
cells 5 19
4 0 1 2 3
4 0 2 1 4
3 0 1 3
2 0 3
1 4
cell_types 5
10 10 5 3 1
cell_data 5
scalars region Int 1
lookup_table default
3 4 -1 -1 -1
field FieldData 1
marker 1 5 INT
-1 -1 7 12 -1
point_data 5
scalars fixed unsigned_char
lookup_table default
1 0 0 0 1
scalars ref int 1
lookup_table default
0 -5 2 0 7
scalars corner double 1
lookup_table default
0 1 0 0 0
)";

// Binary 4.2, as VTK writes it: float points, int cells and types; region
// as SCALARS, no marker array (the triangle gets marker 0, the line ref 0),
// fixed as unsigned_char with a named table, corner as a FIELD array; every
// skipped attribute in binary.  '\n' and ' ' bytes inside the data.
std::string bin42() {
    Bytes b;
    b.text("# vtk DataFile Version 4.2\nbuilt byte by byte\nBINARY\nDATASET UNSTRUCTURED_GRID\n");
    b.text("FIELD FieldData 1\nTIME 1 1 double\n").be(std::ldexp(1.0, -1000) * 0x0a0a).text("\n");
    b.text("POINTS 5 float\n");
    for (float x : kPts) b.be(x);
    b.text("\nCELLS 5 19\n").all<int32_t>({4, 0, 1, 2, 3, 4, 0, 2, 1, 4, 3, 0, 1, 3, 2, 0, 3, 1, 4});
    b.text("\nCELL_TYPES 5\n").all<int32_t>({10, 10, 5, 3, 1});
    b.text("\nCELL_DATA 5\nSCALARS region int 1\nLOOKUP_TABLE default\n").all<int32_t>({3, 2570, -1, -1, -1});
    b.text("\nVECTORS velocity float\n");
    for (int k = 0; k < 15; ++k) b.be(k % 2 ? 2.3125f : -9.1e-30f);  // 0x40140000, 0x8a...
    b.text("\nNORMALS normals double\n");
    for (int k = 0; k < 15; ++k) b.be(k % 3 == 2 ? 1.0 : 0.0);
    b.text("\nTENSORS stress double\n");
    for (int k = 0; k < 45; ++k) b.be(static_cast<double>(0x0a200a20 + k));
    b.text("\nTENSORS6 strain float\n");
    for (int k = 0; k < 30; ++k) b.be(static_cast<float>(k));
    b.text("\nGLOBAL_IDS ids int\n").all<int32_t>({0x0a0a0a0a, 0x20202020, 2, 3, 4});
    b.text("\nPOINT_DATA 5\nCOLOR_SCALARS rgba 4\n");
    for (int k = 0; k < 20; ++k) b.be(static_cast<uint8_t>(k % 2 ? '\n' : ' '));
    b.text("\nSCALARS fixed unsigned_char\nLOOKUP_TABLE flags\n").all<uint8_t>({1, 0, 0, 0, 1});
    b.text("\nLOOKUP_TABLE flags 2\n").all<uint8_t>({10, 32, 10, 32, 13, 10, 0, 255});
    b.text("\nTEXTURE_COORDINATES uv 2 float\n");
    for (int k = 0; k < 10; ++k) b.be(static_cast<float>(k) / 8);
    b.text("\nPEDIGREE_IDS pids int\n").all<int32_t>({10, 11, 12, 13, 14});
    b.text("\nFIELD FieldData 2\nweight 2 5 double\n");
    for (int k = 0; k < 10; ++k) b.be(k * 0.75);
    b.text("\ncorner 1 5 unsigned_char\n").all<uint8_t>({0, 1, 0, 0, 0});
    b.text("\n");
    return b.s;
}

// Binary 5.1, as VTK 9 writes it: double points followed by a METADATA
// block, vtktypeint64 OFFSETS and CONNECTIVITY, int types; region
// (vtktypeint64) and marker (whole doubles) as FIELD arrays, ref as short,
// fixed as float, corner as unsigned_int SCALARS.
std::string bin51() {
    Bytes b;
    b.text("# vtk DataFile Version 5.1\nvtk output\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n");
    for (float x : kPts) b.be(static_cast<double>(x));
    b.text("\nMETADATA\nINFORMATION 0\n\n");
    b.text("CELLS 6 14\nOFFSETS vtktypeint64\n").all<int64_t>({0, 4, 8, 11, 13, 14});
    b.text("\nCONNECTIVITY vtktypeint64\n").all<int64_t>({0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 3, 0, 3, 4});
    b.text("\nCELL_TYPES 5\n").all<int32_t>({10, 10, 5, 3, 1});
    b.text("\nCELL_DATA 5\nFIELD FieldData 2\nregion 1 5 vtktypeint64\n").all<int64_t>({3, 4, -1, -1, -1});
    b.text("\nmarker 1 5 double\n").all<double>({-1, -1, 7, 12, -1});
    b.text("\nPOINT_DATA 5\nSCALARS ref short 1\nLOOKUP_TABLE default\n").all<int16_t>({0, -5, 2, 0, 7});
    b.text("\nSCALARS fixed float\nLOOKUP_TABLE default\n").all<float>({1, 0, 0, 0, 1});
    b.text("\nSCALARS corner unsigned_int 1\nLOOKUP_TABLE default\n").all<uint32_t>({0, 1, 0, 0, 0});
    b.text("\n");
    return b.s;
}

// Written by meshio 5.0.0 (Debian 12's python3-meshio: meshio.write(path,
// mesh, binary=False)) for the sample without its vertex cell, with fixed
// as int64 and ref as int32: one value a line, vtktypeint32, point data
// before cell data, no newline at the end.
const std::string kMeshio =
    "# vtk DataFile Version 5.1\nwritten by meshio v5.0.0\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n"
    "0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 0.125 0.25 -1.0\n"
    "CELLS 5 13\nOFFSETS vtktypeint64\n0\n4\n8\n11\n13\nCONNECTIVITY vtktypeint64\n0\n1\n2\n3\n0\n2\n1\n4\n0\n1\n3\n"
    "0\n3\nCELL_TYPES 4\n10\n10\n5\n3\nPOINT_DATA 5\nFIELD FieldData 2\nfixed 1 5 vtktypeint64\n1 0 0 0 1\n"
    "ref 1 5 vtktypeint32\n0 -5 2 0 7\nCELL_DATA 4\nFIELD FieldData 2\nregion 1 4 vtktypeint64\n3 4 -1 -1\n"
    "marker 1 4 vtktypeint64\n-1 -1 7 12";

// The same mesh as meshio 5.0.0 writes it with binary=True (its bytes,
// rebuilt here).
std::string meshio_binary() {
    Bytes b;
    b.text("# vtk DataFile Version 5.1\nwritten by meshio v5.0.0\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n");
    for (float x : kPts) b.be(x);
    b.text("\nCELLS 5 13\nOFFSETS vtktypeint64\n").all<int64_t>({0, 4, 8, 11, 13});
    b.text("\nCONNECTIVITY vtktypeint64\n").all<int64_t>({0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 3, 0, 3});
    b.text("\nCELL_TYPES 4\n").all<int32_t>({10, 10, 5, 3});
    b.text("\nPOINT_DATA 5\nFIELD FieldData 2\nfixed 1 5 vtktypeint64\n").all<int64_t>({1, 0, 0, 0, 1});
    b.text("\nref 1 5 vtktypeint32\n").all<int32_t>({0, -5, 2, 0, 7});
    b.text("\nCELL_DATA 4\nFIELD FieldData 2\nregion 1 4 vtktypeint64\n").all<int64_t>({3, 4, -1, -1});
    b.text("\nmarker 1 4 vtktypeint64\n").all<int64_t>({-1, -1, 7, 12});
    b.text("\n");
    return b.s;
}

// A file's bytes with the `index`-th big-endian T after `keyword_line`
// replaced by `value`.
template <class T>
std::string patch_be(const char* what, std::string s, const std::string& keyword_line, int index, T value) {
    const size_t at = s.find(keyword_line);
    CHECK(at != std::string::npos, "'%s' not in the file", keyword_line.c_str());
    Bytes b;
    b.be(value);
    s.replace(at + keyword_line.size() + static_cast<size_t>(index) * sizeof(T), sizeof(T), b.s);
    return s;
}

// ------------------------------------------------------------ tests

void test_round_trip(void**) {
    const char* what = "round trip";
    bodt::MeshData d = kuhn_block(2, 1);
    decorate(d, 2);
    const size_t nt = d.tets.size() / 4, nf = d.tri_markers.size(), ne = d.feature_edges.size() / 2,
                 nv = d.xyz.size() / 3;
    bodt::MeshData::TetField qmin{"min_dihedral", {}}, vol{"volume", {}}, spaced{"q value", {}},
        percent{"100% a\tb", {}}, utf8{"\xC3\xA9t\xC3\xA9", {}};
    for (size_t t = 0; t < nt; ++t) {
        qmin.values.push_back(30.0 + static_cast<double>(t) / 3.0);
        vol.values.push_back(std::ldexp(1.0, -static_cast<int>(t)) / 7.0);
        spaced.values.push_back(-static_cast<double>(t));
        percent.values.push_back(t % 2 ? std::numeric_limits<double>::infinity() : 1e-310);
        utf8.values.push_back(static_cast<double>(t * t));
    }
    d.tet_fields = {qmin, vol, spaced, percent, utf8};
    const std::string path = scratch("round_trip.vtk");
    bodt::write_vtk(path, d);
    const bodt::MeshData r = bodt::read_vtk(path);

    CHECK(r.base == 0, "base %d", r.base);
    CHECK(r.xyz.size() == d.xyz.size(), "%zu coordinates", r.xyz.size());
    CHECK(r.xyz.size() == d.xyz.size() && std::memcmp(r.xyz.data(), d.xyz.data(), d.xyz.size() * sizeof(double)) == 0,
          "coordinates not bit-exact");
    std::vector<int32_t> tets0 = d.tets, tris0 = d.triangles, edges0 = d.feature_edges;
    for (int32_t& v : tets0) v -= 1;
    for (int32_t& v : tris0) v -= 1;
    for (int32_t& v : edges0) v -= 1;
    CHECK(r.tets == tets0, "tets differ");
    CHECK(r.regions == d.regions, "regions differ");
    CHECK(r.triangles == tris0, "triangles differ");
    CHECK(r.tri_markers == d.tri_markers, "markers differ");
    CHECK(r.feature_edges == edges0, "feature edges differ");
    CHECK(r.edge_refs == d.edge_refs, "edge refs differ");
    CHECK(r.vertex_refs == d.vertex_refs, "vertex refs differ");
    std::set<int32_t> fixed0, corners0;
    for (int32_t v : d.fixed) fixed0.insert(v - 1);
    for (int32_t v : d.corners) corners0.insert(v - 1);
    CHECK(r.fixed == std::vector<int32_t>(fixed0.begin(), fixed0.end()), "fixed differ (sorted, each once)");
    CHECK(r.corners == std::vector<int32_t>(corners0.begin(), corners0.end()), "corners differ (sorted, each once)");
    CHECK(r.tet_fields.empty(), "tet fields are not read back");

    // The file, taken apart by this test's own parser.
    const std::string text = read_text(path);
    CHECK(text.compare(0, 27, "# vtk DataFile Version 4.2\n") == 0, "first line '%s'",
          text.substr(0, text.find('\n')).c_str());
    const Written w = parse_written(what, text);
    CHECK(w.header[2] == "BINARY", "format line '%s'", w.header[2].c_str());
    CHECK(w.header[3] == "DATASET UNSTRUCTURED_GRID", "dataset line '%s'", w.header[3].c_str());
    CHECK(w.header[1].size() <= 256, "title of %zu characters", w.header[1].size());
    CHECK(w.points_type == "double", "points of type %s", w.points_type.c_str());
    CHECK(w.points.size() == d.xyz.size() &&
              std::memcmp(w.points.data(), d.xyz.data(), d.xyz.size() * sizeof(double)) == 0,
          "written points are not the coordinates");
    const size_t ncells = nt + nf + ne;
    CHECK(w.ncells == static_cast<int64_t>(ncells) && w.cells_size == static_cast<int64_t>(5 * nt + 4 * nf + 3 * ne),
          "CELLS %lld %lld", static_cast<long long>(w.ncells), static_cast<long long>(w.cells_size));
    std::vector<int32_t> cells, types;
    for (size_t t = 0; t < nt; ++t) {
        cells.push_back(4);
        cells.insert(cells.end(), tets0.begin() + 4 * t, tets0.begin() + 4 * t + 4);
        types.push_back(10);
    }
    for (size_t f = 0; f < nf; ++f) {
        cells.push_back(3);
        cells.insert(cells.end(), tris0.begin() + 3 * f, tris0.begin() + 3 * f + 3);
        types.push_back(5);
    }
    for (size_t e = 0; e < ne; ++e) {
        cells.push_back(2);
        cells.insert(cells.end(), edges0.begin() + 2 * e, edges0.begin() + 2 * e + 2);
        types.push_back(3);
    }
    CHECK(w.cells == cells, "the cells (4.2 layout: count, then 0-based indices) differ");
    CHECK(w.types == types, "the cell types differ");
    CHECK(w.cell_data == static_cast<int64_t>(ncells), "CELL_DATA %lld", static_cast<long long>(w.cell_data));
    CHECK(w.point_data == static_cast<int64_t>(nv), "POINT_DATA %lld", static_cast<long long>(w.point_data));

    auto array = [&](const std::map<std::string, Written::Array>& arrays, const char* name,
                     const char* type) -> const std::vector<double>* {
        auto it = arrays.find(name);
        CHECK(it != arrays.end(), "no array %s", name);
        CHECK(it->second.type == type, "%s of type %s, not %s", name, it->second.type.c_str(), type);
        return &it->second.values;
    };
    const std::vector<double>* region = array(w.cell_arrays, "region", "int");
    const std::vector<double>* marker = array(w.cell_arrays, "marker", "int");
    for (size_t c = 0; c < ncells; ++c) {
        const double rv = c < nt ? d.regions[c] : -1;
        const double mv = c < nt ? -1 : c < nt + nf ? d.tri_markers[c - nt] : d.edge_refs[c - nt - nf];
        CHECK((*region)[c] == rv, "region of cell %zu: %g, not %g", c, (*region)[c], rv);
        CHECK((*marker)[c] == mv, "marker of cell %zu: %g, not %g", c, (*marker)[c], mv);
    }
    const std::vector<double>* fixed = array(w.point_arrays, "fixed", "unsigned_char");
    const std::vector<double>* corner = array(w.point_arrays, "corner", "unsigned_char");
    const std::vector<double>* ref = array(w.point_arrays, "ref", "int");
    for (size_t v = 0; v < nv; ++v) {
        const int32_t id = static_cast<int32_t>(v);
        CHECK((*fixed)[v] == (fixed0.count(id) ? 1 : 0), "fixed flag of vertex %zu: %g", v, (*fixed)[v]);
        CHECK((*corner)[v] == (corners0.count(id) ? 1 : 0), "corner flag of vertex %zu: %g", v, (*corner)[v]);
        CHECK((*ref)[v] == d.vertex_refs[v], "ref of vertex %zu: %g", v, (*ref)[v]);
    }
    // The tet fields: doubles, bit-exact on tets, NaN elsewhere, names
    // escaped (no space, no stray '%', nothing outside printable ASCII) and
    // decoding to the field's name.
    CHECK(w.cell_arrays.size() == 2 + d.tet_fields.size(), "%zu cell arrays", w.cell_arrays.size());
    CHECK(w.cell_arrays.count("q%20value"), "the name 'q value' is not written as q%%20value");
    for (const auto& f : d.tet_fields) {
        const Written::Array* found = nullptr;
        for (const auto& [raw, a] : w.cell_arrays) {
            if (decode_name(raw) != f.name) continue;
            found = &a;
            for (size_t k = 0; k < raw.size(); ++k) {
                const unsigned char ch = static_cast<unsigned char>(raw[k]);
                CHECK(ch > ' ' && ch < 127, "byte %d in the written name of '%s'", ch, f.name.c_str());
                if (ch == '%')
                    CHECK(k + 2 < raw.size() && std::isxdigit(static_cast<unsigned char>(raw[k + 1])) &&
                              std::isxdigit(static_cast<unsigned char>(raw[k + 2])),
                          "a '%%' that is no escape in '%s'", raw.c_str());
            }
        }
        CHECK(found, "no array whose name decodes to '%s'", f.name.c_str());
        CHECK(found->type == "double", "field %s of type %s", f.name.c_str(), found->type.c_str());
        for (size_t c = 0; c < ncells; ++c) {
            const double x = found->values[c];
            if (c < nt)
                CHECK(std::memcmp(&x, &f.values[c], sizeof x) == 0, "%s of tet %zu: %.17g", f.name.c_str(), c, x);
            else CHECK(std::isnan(x), "%s of non-tet cell %zu is %g, not NaN", f.name.c_str(), c, x);
        }
    }

    // A bare mesh reads back bare.
    bodt::MeshData bare;
    bare.xyz = r.xyz;
    bare.tets = r.tets;
    bodt::write_vtk(scratch("bare.vtk"), bare);
    const bodt::MeshData b = bodt::read_vtk(scratch("bare.vtk"));
    CHECK(b.xyz == bare.xyz && b.tets == bare.tets, "bare mesh differs");
    CHECK(b.regions.empty() && b.triangles.empty() && b.fixed.empty() && b.feature_edges.empty() &&
              b.edge_refs.empty() && b.vertex_refs.empty() && b.corners.empty(),
          "bare mesh gained data");
    CHECK(parse_written(what, read_text(scratch("bare.vtk"))).cell_arrays.empty(), "bare mesh with cell arrays");

    // Edges without refs: ref 0, with a marker array (for the triangles) or without.
    bodt::MeshData plain_edges = r;
    plain_edges.edge_refs.clear();
    for (int with_triangles = 1; with_triangles >= 0; --with_triangles) {
        if (!with_triangles) plain_edges.triangles.clear(), plain_edges.tri_markers.clear();
        bodt::write_vtk(scratch("plain_edges.vtk"), plain_edges);
        const bodt::MeshData e = bodt::read_vtk(scratch("plain_edges.vtk"));
        CHECK(e.feature_edges == plain_edges.feature_edges, "edges without refs differ");
        CHECK(e.edge_refs == std::vector<int32_t>(plain_edges.feature_edges.size() / 2, 0), "edge refs are not 0");
        CHECK(e.tri_markers == plain_edges.tri_markers && e.triangles == plain_edges.triangles, "triangles differ");
        const Written pw = parse_written(what, read_text(scratch("plain_edges.vtk")));
        CHECK(pw.cell_arrays.count("marker") == static_cast<size_t>(with_triangles),
              "marker array written %s triangles", with_triangles ? "with" : "without");
    }

    // Inconsistent MeshData is an argument error; an unwritable path an IO error.
    const auto refused = [&](const bodt::MeshData& m, const char* expect) {
        try {
            bodt::write_vtk(scratch("bad.vtk"), m);
            CHECK(false, "written, expected '%s'", expect);
        } catch (const bodt::Error& e) {
            CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT && std::strstr(e.what(), expect), "%s", e.what());
        }
    };
    bodt::MeshData bad = d;
    bad.tet_fields[0].values.pop_back();
    refused(bad, "min_dihedral");
    bad = d;
    bad.tet_fields[1].name = "region";
    refused(bad, "region");
    bad = d;
    bad.vertex_refs.pop_back();
    refused(bad, "vertex_refs");
    bad = d;
    bad.corners.push_back(0);  // base 1
    refused(bad, "vertex 0 is out of range");
    const std::string unwritable = scratch("no_such_dir/out.vtk");
    const std::string msg = io_error(what, [&] { bodt::write_vtk(unwritable, d); });
    CHECK(msg.find(unwritable) != std::string::npos, "'%s' does not name the path", msg.c_str());
}

// A table of files that must read as the sample: every case is tried, the
// failures are printed, and the check fails when there is any.
struct Good {
    std::string name, text;
    Expect expect;
};

void expect_all_read(const char* what, const std::vector<Good>& cases) {
    int failed = 0;
    for (const Good& c : cases) {
        const std::string problem = read_problem(c.name, c.text, c.expect);
        if (problem.empty()) continue;
        ++failed;
        std::printf("%s: %s: %s\n", what, c.name.c_str(), problem.c_str());
    }
    CHECK(failed == 0, "%d of %zu files failed (listed above)", failed, cases.size());
}

void test_hand_written(void**) {
    const char* what = "hand-written files";
    const Expect all;
    // Binary 4.2: region 2570 (bytes 00 00 0a 0a), no marker array, no refs.
    Expect b42;
    b42.regions = {3, 2570};
    b42.markers = b42.edge_refs = {0};
    b42.refs = {};
    // Mesquite: the float flags are the fixed vertices; GLOBAL_ID ignored.
    Expect mq;
    mq.regions = mq.markers = mq.edge_refs = mq.refs = mq.corners = {};
    mq.triangle = mq.edge = false;
    // %XX names decode: fi%78ed is fixed; "region " (region%20) is another array.
    Expect esc = all;
    esc.fixed = {1, 2};
    esc.regions = {};
    std::string escaped = replace(what, kAscii42, "SCALARS fixed unsigned_char 1\nLOOKUP_TABLE default\n1 0 0 0 1",
                                  "SCALARS fi%78ed unsigned_char 1\nLOOKUP_TABLE default\n0 1 1 0 0");
    escaped = replace(what, escaped, "SCALARS region int 1", "SCALARS region%20 int 1");
    // Without the marker array: the triangle marker 0, the line ref 0.
    Expect nomark = all;
    nomark.markers = nomark.edge_refs = {0};
    // The vertex cell first: still ignored, the other cells in order.
    std::string first = replace(what, kAscii51, "0 4 8 11 13 14", "0 1 5 9 12 14");
    first = replace(what, first, "0 1 2 3 0 2 1 4 0 \n1 3 0 3 4", "4 0 1 2 3 0 2 1 4 0 \n1 3 0 3");
    first = replace(what, first, "10\n10\n5\n3\n1\n", "1\n10\n10\n5\n3\n");
    first = replace(what, first, "3 4 -1 -1 -1", "-1 3 4 -1 -1");
    first = replace(what, first, "-1 -1 7 12 -1", "-1 -1 -1 7 12");
    // The extremes of 32 bits, from a 64-bit array.
    std::string extreme = replace(what, kAscii42, "3 4 -1 -1 -1", "-2147483648 2147483647 -1 -1 -1");
    extreme = replace(what, extreme, "SCALARS region int 1", "SCALARS region vtktypeint64 1");
    Expect ext = all;
    ext.regions = {INT32_MIN, INT32_MAX};
    // Our names in the other section, or in the dataset's FIELD data: ignored.
    std::string elsewhere = replace(what, kAscii42, "DATASET UNSTRUCTURED_GRID\n",
                                    "DATASET UNSTRUCTURED_GRID\nFIELD FieldData 2\nregion 1 1 int\n7\n"
                                    "fixed 1 5 int\n1 1 1 1 1\n");
    elsewhere = replace(what, elsewhere, "CELL_DATA 5\n",
                        "CELL_DATA 5\nSCALARS fixed int\nLOOKUP_TABLE default\n1 1 1 1 1\n"
                        "FIELD FieldData 1\nref 1 5 int\n9 9 9 9 9\n");
    elsewhere = replace(what, elsewhere, "POINT_DATA 5\n",
                        "POINT_DATA 5\nSCALARS region int\nLOOKUP_TABLE default\n8 8 8 8 8\n"
                        "FIELD FieldData 1\nmarker 1 5 int\n9 9 9 9 9\n");
    // METADATA with every component named (no empty line inside) after
    // VECTORS, and after a FIELD array.
    const std::string meta =
        replace(what,
                replace(what, kAscii51, "POINT_DATA 5\n",
                        "POINT_DATA 5\nVECTORS velocity double\n0 0 1 1 0 1 2 0 1 \n3 0 1 4 0 1 \nMETADATA\n"
                        "COMPONENT_NAMES\nvx\nvy\nvz\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\n"
                        "DATA 2 1 4.12311 \n\n"),
                "-1 -1 7 12 -1 \n", "-1 -1 7 12 -1 \nMETADATA\nINFORMATION 0\n\n");

    std::vector<Good> cases = {
        {"ascii42.vtk", kAscii42, all},
        {"ascii51.vtk", kAscii51, all},
        {"lower.vtk", kLower, all},
        {"attributes.vtk", kAttributes, all},
        {"binary51.vtk", bin51(), all},
        {"binary42.vtk", bin42(), b42},
        {"mesquite.vtk", kMesquite, mq},
        {"escaped.vtk", escaped, esc},
        {"escaped51.vtk", replace(what, bin51(), "\nregion 1 5 vtktypeint64", "\n%72egion 1 5 vtktypeint64"), all},
        {"no_marker.vtk", replace(what, kAscii42, "SCALARS marker int\nLOOKUP_TABLE default\n-1 -1 7 12 -1\n", ""),
         nomark},
        {"vertex_first.vtk", first, all},
        {"extreme.vtk", extreme, ext},
        {"elsewhere.vtk", elsewhere, all},
        {"metadata.vtk", meta, all},
        {"crlf.vtk",
         [&] {
             std::string crlf;
             for (char c : kAscii42) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
             return crlf;
         }(),
         all},
    };
    // Versions 1.0 to 4.2 share the layout.
    for (const char* version : {"1.0", "3.0", "4.0", "4.1"})
        cases.push_back({std::string("version") + version + ".vtk",
                         replace(what, kMesquite, "Version 2.0", std::string("Version ") + version), mq});
    expect_all_read(what, cases);
}

// ASCII values of a float array are floats, as VTK (and the .vtu reader)
// reads them: the same points as the binary file of the same data.
void test_ascii_float_points(void**) {
    const char* what = "ASCII float points";
    const std::string text = replace(what, kAscii42, "0 0 1 0.125 0.25 -1", "0 0 1 0.1 0.2 -1");
    write_text(scratch("float_points.vtk"), text);
    const bodt::MeshData f = bodt::read_vtk(scratch("float_points.vtk"));
    write_text(scratch("double_points.vtk"), replace(what, text, "POINTS 5 float", "POINTS 5 double"));
    const bodt::MeshData d = bodt::read_vtk(scratch("double_points.vtk"));
    CHECK(d.xyz.size() == 15 && d.xyz[12] == 0.1 && d.xyz[13] == 0.2, "double points: %.17g %.17g", d.xyz[12],
          d.xyz[13]);
    CHECK(f.xyz.size() == 15 && f.xyz[12] == static_cast<double>(0.1f) && f.xyz[13] == static_cast<double>(0.2f),
          "float points read as %.17g %.17g, not as the floats %.17g %.17g", f.xyz[12], f.xyz[13],
          static_cast<double>(0.1f), static_cast<double>(0.2f));
}

// VTK 9.1's own file: METADATA with COMPONENT_NAMES where a component has
// no name (an empty line inside the block, which VTK reads as that name).
void test_vtk91_metadata(void**) {
    const char* what = "VTK 9.1 metadata";
    write_text(scratch("vtk91.vtk"), kVtk91);
    bodt::MeshData v;
    try {
        v = bodt::read_vtk(scratch("vtk91.vtk"));
    } catch (const std::exception& e) {
        CHECK(false, "%s", e.what());
    }
    CHECK((v.xyz == std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}), "points");
    CHECK((v.tets == std::vector<int32_t>{0, 1, 2, 3}), "tets");
    CHECK(v.regions.empty() && v.fixed.empty() && v.triangles.empty(), "data from nowhere");
}

// meshio 5.0: vtktypeint64 / vtktypeint32 FIELD arrays, no final newline;
// its names for Gmsh's physical groups and Medit's refs (one array for every
// cell), VTK's CellEntityIds, and the precedence of vtk_cells.hpp.
void test_meshio(void**) {
    const char* what = "meshio";
    Expect mio;
    mio.corners = {};
    const std::string ours = "region 1 4 vtktypeint64\n3 4 -1 -1\nmarker 1 4 vtktypeint64\n-1 -1 7 12";
    auto cells = [&](const std::string& arrays, int n) {
        return replace(what, replace(what, kMeshio, ours, arrays), "CELL_DATA 4\nFIELD FieldData 2",
                       "CELL_DATA 4\nFIELD FieldData " + std::to_string(n));
    };
    const std::string geometrical = "gmsh:geometrical 1 4 vtktypeint32\n1 2 3 4";
    std::vector<Good> cases = {{"meshio.vtk", kMeshio, mio}, {"meshio_binary.vtk", meshio_binary(), mio}};
    for (const char* name : {"gmsh:physical", "CellEntityIds", "medit:ref"})
        cases.push_back({std::string("meshio_") + name + ".vtk",
                         cells(std::string(name) + " 1 4 vtktypeint32\n3 4 7 12\n" + geometrical, 2), mio});
    // medit:ref of the points: the vertex refs.
    cases.push_back({"meshio_point_ref.vtk",
                     replace(what, kMeshio, "ref 1 5 vtktypeint32", "medit:ref 1 5 vtktypeint32"), mio});
    // region and marker before gmsh:physical, gmsh:physical before
    // CellEntityIds, CellEntityIds before medit:ref; ref before medit:ref.
    const std::string physical = "gmsh:physical 1 4 vtktypeint32\n13 14 17 22\n";
    const std::string ids = "CellEntityIds 1 4 vtktypeint32\n23 24 27 32\n";
    const std::string medit = "medit:ref 1 4 vtktypeint32\n33 34 37 42\n";
    cases.push_back({"meshio_ours_first.vtk", cells(medit + ids + physical + ours, 5), mio});
    Expect p = mio;
    p.regions = {13, 14}, p.markers = {17}, p.edge_refs = {22};
    cases.push_back({"meshio_physical_first.vtk", cells(medit + ids + physical + geometrical, 4), p});
    Expect i = mio;
    i.regions = {23, 24}, i.markers = {27}, i.edge_refs = {32};
    cases.push_back({"meshio_ids_first.vtk", cells(medit + ids + geometrical, 3), i});
    Expect mixed = mio;
    mixed.regions = {13, 14};
    cases.push_back({"meshio_marker_physical.vtk",
                     cells(physical + "marker 1 4 vtktypeint64\n-1 -1 7 12", 2), mixed});
    cases.push_back({"meshio_both_refs.vtk",
                     replace(what, kMeshio, "FIELD FieldData 2\nfixed",
                             "FIELD FieldData 3\nmedit:ref 1 5 vtktypeint32\n9 9 9 9 9\nfixed"),
                     mio});
    expect_all_read(what, cases);
    // Each array read is checked, also one that another one overrides.
    expect_malformed(what, "meshio_short_physical.vtk", cells(ours + "\ngmsh:physical 1 3 vtktypeint32\n1 2 3", 3),
                     "the gmsh:physical array has 3 tuples for 4 cells", kAnyLine);
}

void test_refusals(void**) {
    const char* what = "refusals";
    const std::string a = kAscii42, b = bin42(), b5 = bin51();
    const std::string sg = expect_malformed(what, "structured.vtk",
                                            replace(what, a, "DATASET UNSTRUCTURED_GRID", "DATASET STRUCTURED_GRID"),
                                            "STRUCTURED_GRID", at_line(4));
    bool named = false;  // "STRUCTURED_GRID" itself, not only as part of UNSTRUCTURED_GRID
    for (size_t at = sg.find("STRUCTURED_GRID"); at != std::string::npos; at = sg.find("STRUCTURED_GRID", at + 1))
        named |= at < 2 || sg.compare(at - 2, 2, "UN") != 0;
    CHECK(named, "'%s' does not name STRUCTURED_GRID", sg.c_str());

    std::string hex = replace(what, a, "CELLS 5 19\n4 0 1 2 3", "CELLS 5 23\n8 0 1 2 3 4 0 1 2");
    hex = replace(what, hex, "CELL_TYPES 5\n10", "CELL_TYPES 5\n12");
    std::string quad = replace(what, a, "CELLS 5 19\n4 0 1 2 3", "CELLS 5 25\n10 0 1 2 3 4 0 1 2 3 4");
    quad = replace(what, quad, "CELL_TYPES 5\n10", "CELL_TYPES 5\n24");
    std::string no_tets = replace(what, a, "CELLS 5 19\n4 0 1 2 3\n4 0 2 1 4", "CELLS 4 13\n3 0 1 2");
    no_tets = replace(what, no_tets, "CELL_TYPES 5\n10\n10\n", "CELL_TYPES 4\n5\n");
    no_tets = no_tets.substr(0, no_tets.find("CELL_DATA"));
    const std::string pts = "POINTS 5 float\n0 0 0 1 0 0 0 1 0\n0 0 1 0.125 0.25 -1\n";
    const std::string cells = "CELLS 5 19\n4 0 1 2 3\n4 0 2 1 4\n3 0 1 3\n2 0 3\n1 4\n";
    const long cell_data = line_of(what, a, "CELL_DATA 5");
    const size_t meta = b5.find("\nMETADATA"), points = b5.find("POINTS 5 double");
    const std::string b5_points = b5.substr(points, meta + 1 - points);
    const Where types_line = at_line(line_of(what, a, "CELL_TYPES"));
    expect_all_malformed(
        what,
        {
            {"polydata.vtk", replace(what, a, "DATASET UNSTRUCTURED_GRID", "DATASET POLYDATA"),
             "DATASET POLYDATA is not supported", at_line(4)},
            {"polydata_bin.vtk", replace(what, b, "DATASET UNSTRUCTURED_GRID", "DATASET POLYDATA"),
             "DATASET POLYDATA is not supported", kEither},
            {"hexahedron.vtk", hex, "(hexahedron)", types_line},
            {"quadratic.vtk", quad, "(quadratic tetra)", types_line},
            {"hexahedron_bin.vtk", patch_be<int32_t>(what, b, "CELL_TYPES 5\n", 1, 12), "(hexahedron)", kByte},
            {"bit.vtk", replace(what, a, "SCALARS fixed unsigned_char 1", "SCALARS fixed bit 1"), "type bit",
             at_line(line_of(what, a, "SCALARS fixed"))},
            {"bit_other.vtk",
             replace(what, a, "SCALARS q%20a double 1\nLOOKUP_TABLE default\n0.5 0.25 -1 -1 -1",
                     "SCALARS flags bit 1\nLOOKUP_TABLE default\n0 1 1 0 1"),
             "type bit", at_line(line_of(what, a, "SCALARS q%20a"))},
            {"bit_points.vtk", replace(what, a, "POINTS 5 float", "POINTS 5 bit"), "type bit", at_line(5)},
            {"string.vtk", replace(what, a, "FIELD FieldData 1\n", "FIELD FieldData 2\nnames 1 2 string\nab\ncd\n"),
             "type string", at_line(line_of(what, a, "FIELD FieldData") + 1)},
            {"utf8_string.vtk",
             replace(what, a, "FIELD FieldData 1\n", "FIELD FieldData 2\nnames 1 2 utf8_string\nab\ncd\n"),
             "type utf8_string", at_line(line_of(what, a, "FIELD FieldData") + 1)},
            {"string_bin.vtk", replace(what, b, "FIELD FieldData 2\n", "FIELD FieldData 3\nnames 1 1 string\nab\n"),
             "type string", kByte},
            {"no_tets.vtk", no_tets, "no tetrahedra", kAnyLine},
            {"two_points.vtk", replace(what, a, "CELL_DATA 5\n", pts + "CELL_DATA 5\n"), "a second POINTS",
             at_line(cell_data)},
            {"two_cells.vtk", replace(what, a, "CELL_DATA 5\n", cells + "CELL_DATA 5\n"), "a second CELLS",
             at_line(cell_data)},
            {"two_types.vtk", replace(what, a, "CELL_DATA 5\n", "CELL_TYPES 5\n10 10 5 3 1\nCELL_DATA 5\n"),
             "a second CELL_TYPES", at_line(cell_data)},
            {"two_points_bin.vtk", replace(what, b5, "CELL_DATA 5\n", b5_points + "CELL_DATA 5\n"), "a second POINTS",
             kByte},
            {"two_datasets.vtk", replace(what, a, "CELL_DATA 5\n", "DATASET UNSTRUCTURED_GRID\nCELL_DATA 5\n"),
             "DATASET", at_line(cell_data)},
            // An unsigned 64-bit value that does not fit in 32 bits (nor in int64).
            {"region_uint64.vtk",
             replace(what, patch_be<uint64_t>(what, b5, "region 1 5 vtktypeint64\n", 1, ~uint64_t{0}),
                     "region 1 5 vtktypeint64", "region 1 5 vtktypeuint64"),
             "not a whole number of 32 bits", kByte},
            {"region_ulong.vtk",
             replace(what, patch_be<uint64_t>(what, b5, "region 1 5 vtktypeint64\n", 1, ~uint64_t{0}),
                     "region 1 5 vtktypeint64", "region 1 5 unsigned_long"),
             "not a whole number of 32 bits", kByte},
        });
}

void test_malformed(void**) {
    const char* what = "malformed";
    const std::string a = kAscii42, a5 = kAscii51, b = bin42(), b5 = bin51();
    auto L = [&](const std::string& text, const std::string& marker) { return at_line(line_of(what, text, marker)); };
    const long cell_data_line = line_of(what, a, "CELL_DATA"), point_data_line = line_of(what, a, "POINT_DATA");
    const std::string no_lut =
        replace(what, a, "SCALARS region int 1\nLOOKUP_TABLE default\n", "SCALARS region int 1\n");
    const size_t bpoints = b.find("POINTS 5 float\n") + 15, bcells = b.find("CELLS 5 19\n") + 11;
    const size_t b5conn = b5.find("CONNECTIVITY vtktypeint64\n") + 26;
    // CELL_DATA / POINT_DATA whose count differs from the cells' / points',
    // with no array to run into the next keyword: the count check itself.
    const std::string cell_count = replace(what, a.substr(0, a.find("SCALARS region")) + a.substr(a.find("POINT_DATA")),
                                           "CELL_DATA 5", "CELL_DATA 4");
    const std::string point_count = replace(what, a.substr(0, a.find("SCALARS fixed")), "POINT_DATA 5", "POINT_DATA 6");
    expect_all_malformed(
        what,
        {
            // The header.
            {"empty.vtk", "", "version line", at_line(1)},
            {"not_vtk.vtk", "hello\n" + a.substr(a.find('\n') + 1), "not a VTK legacy file", at_line(1)},
            {"bad_version.vtk", replace(what, a, "Version 4.2", "Version four"), "no version number", at_line(1)},
            {"future_version.vtk", replace(what, a, "Version 4.2", "Version 6.0"),
             "version 6.0 is not one this reader knows", at_line(1)},
            {"header_only.vtk", "# vtk DataFile Version 4.2\n", "the title", at_line(2)},
            {"no_format.vtk", replace(what, a, "ASCII\n", ""), "must be ASCII or BINARY, not 'DATASET", at_line(3)},
            {"bad_format.vtk", replace(what, a, "ASCII\n", "TEXT\n"), "must be ASCII or BINARY, not 'TEXT'",
             at_line(3)},
            {"no_dataset.vtk", replace(what, a, "DATASET UNSTRUCTURED_GRID\n", ""), "expected DATASET, found 'POINTS'",
             at_line(4)},
            {"bin_bad_version.vtk", replace(what, b, "Version 4.2", "Version x"), "no version number", at_line(1)},
            {"bin_bad_format.vtk", replace(what, b, "BINARY\n", "BINARY ASCII\n"), "not 'BINARY ASCII'", at_line(3)},
            // POINTS.
            {"points_word.vtk", replace(what, a, "POINTS 5 float", "POINTS five float"),
             "number of points 'five' is not a non-negative integer", at_line(5)},
            {"points_negative.vtk", replace(what, a, "POINTS 5 float", "POINTS -5 float"), "'-5' is not a non-negative",
             at_line(5)},
            {"points_type.vtk", replace(what, a, "POINTS 5 float", "POINTS 5 quad"), "unknown data type 'quad'",
             at_line(5)},
            {"points_no_type.vtk", replace(what, a, "POINTS 5 float", "POINTS 5"), "unknown data type '0'",
             at_lines(5, 6)},
            {"points_more.vtk", replace(what, a, "POINTS 5 float", "POINTS 6 float"), "'CELLS' is not a number",
             at_line(8)},
            {"points_huge.vtk", replace(what, a, "POINTS 5 float", "POINTS 2000000000000 float"),
             "more than 2^31 - 1 points", at_line(5)},
            {"points_many.vtk", replace(what, a, "POINTS 5 float", "POINTS 200000000 float"), "cannot fit",
             at_lines(5, 6)},
            {"points_nan.vtk", replace(what, a, "0.125 0.25 -1", "0.125 nan -1"),
             "coordinate 1 of point 4 is not finite", at_lines(5, 7)},
            {"points_inf.vtk", replace(what, a, "0.125 0.25 -1", "0.125 0.25 -inf"),
             "coordinate 2 of point 4 is not finite", at_lines(5, 7)},
            {"points_overflow.vtk", replace(what, a, "0.125 0.25 -1", "0.125 1e999 -1"), "'1e999'", at_line(7)},
            {"points_word_value.vtk", replace(what, a, "0.125 0.25 -1", "0.125 0.25x -1"), "'0.25x' is not a number",
             at_line(7)},
            {"no_points.vtk", replace(what, a, "POINTS 5 float\n0 0 0 1 0 0 0 1 0\n0 0 1 0.125 0.25 -1\n", ""),
             "no POINTS", kAnyLine},
            // CELLS and CELL_TYPES, the layout before 5.
            {"cells_size_less.vtk", replace(what, a, "CELLS 5 19", "CELLS 5 18"), "cell 4 has 1 points, beyond",
             L(a, "CELLS")},
            {"cells_size_more.vtk", replace(what, a, "CELLS 5 19", "CELLS 5 20"), "'CELL_TYPES' is not an integer",
             L(a, "CELL_TYPES")},
            {"cells_overrun.vtk", replace(what, a, "\n1 4\n", "\n9 4\n"), "cell 4 has 9 points, beyond the cell list",
             L(a, "CELLS")},
            {"cells_count_zero.vtk", replace(what, a, "\n2 0 3\n1 4\n", "\n0\n2 0 3 4\n"), "cell 3 has 0 points",
             L(a, "CELLS")},
            {"cells_count_negative.vtk", replace(what, a, "\n1 4\n", "\n-1 4\n"), "cell 4 has -1 points",
             L(a, "CELLS")},
            {"cells_negative.vtk", replace(what, a, "CELLS 5 19", "CELLS -5 19"), "'-5' is not a non-negative integer",
             L(a, "CELLS")},
            {"cells_too_many.vtk", replace(what, a, "CELLS 5 19", "CELLS 20 19"), "20 cells cannot fit", L(a, "CELLS")},
            {"cells_huge.vtk", replace(what, a, "CELLS 5 19", "CELLS 1000000000 4000000000"), "cannot fit",
             L(a, "CELLS")},
            {"cells_word.vtk", replace(what, a, "4 0 1 2 3", "4 0 x 2 3"), "'x' is not an integer", L(a, "4 0 1 2 3")},
            {"index_range.vtk", replace(what, a, "4 0 2 1 4", "4 0 2 1 5"), "is 5, out of range for 5 points",
             L(a, "CELLS")},
            {"index_negative.vtk", replace(what, a, "4 0 2 1 4", "4 0 2 -1 4"), "is -1, out of range", L(a, "CELLS")},
            {"cell_size.vtk", replace(what, a, "10\n10\n5\n3\n1", "10\n10\n10\n3\n1"), "has 3 points instead of 4",
             kAnyLine},
            {"types_less.vtk", replace(what, a, "CELL_TYPES 5", "CELL_TYPES 4"), "unknown keyword '1'",
             at_line(line_of(what, a, "CELL_TYPES") + 5)},
            {"types_more.vtk", replace(what, a, "CELL_TYPES 5", "CELL_TYPES 6"), "'CELL_DATA' is not an integer",
             at_line(cell_data_line)},
            {"types_count.vtk", replace(what, a, "CELL_TYPES 5\n10\n10\n5\n3\n1\n", "CELL_TYPES 4\n10\n10\n5\n3\n"),
             "CELL_TYPES has 4 types for 5 cells", L(a, "CELL_TYPES")},
            {"types_word.vtk", replace(what, a, "10\n10\n5\n3\n1", "10\n10\nfive\n3\n1"), "'five' is not an integer",
             kAnyLine},
            {"no_types.vtk", a.substr(0, a.find("CELL_TYPES")), "no CELL_TYPES", kAnyLine},
            {"no_cells.vtk", a.substr(0, a.find("CELLS")), "no CELLS", kAnyLine},
            // CELLS in 5.x: OFFSETS and CONNECTIVITY.
            {"offsets_down.vtk", replace(what, a5, "0 4 8 11 13 14", "0 4 3 11 13 14"), "not increasing",
             L(a5, "CELLS")},
            {"offsets_start.vtk", replace(what, a5, "0 4 8 11 13 14", "1 4 8 11 13 14"), "the first offset is 1, not 0",
             L(a5, "CELLS")},
            {"offsets_beyond.vtk", replace(what, a5, "0 4 8 11 13 14", "0 4 8 11 13 15"), "beyond the 14",
             L(a5, "CELLS")},
            {"offsets_short.vtk", replace(what, a5, "0 4 8 11 13 14", "0 4 8 11 12 13"), "use 13 of the 14",
             L(a5, "CELLS")},
            {"offsets_type.vtk", replace(what, a5, "OFFSETS vtktypeint64", "OFFSETS float"),
             "offsets must be of an integer type", L(a5, "OFFSETS")},
            {"offsets_count.vtk", replace(what, a5, "CELLS 6 14", "CELLS 5 14"), "expected CONNECTIVITY, found '14'",
             L(a5, "0 4 8 11 13 14")},
            {"offsets_none.vtk", replace(what, a5, "CELLS 6 14", "CELLS 0 14"), "expected CONNECTIVITY, found '0'",
             L(a5, "0 4 8 11 13 14")},
            {"old_layout_51.vtk",
             replace(what, a5, "OFFSETS vtktypeint64\n0 4 8 11 13 14 \nCONNECTIVITY vtktypeint64\n", ""),
             "expected OFFSETS, found '0'", L(a5, "OFFSETS")},
            {"no_connectivity.vtk", replace(what, a5, "CONNECTIVITY vtktypeint64", "OFFSETS vtktypeint64"),
             "expected CONNECTIVITY, found 'OFFSETS'", L(a5, "CONNECTIVITY")},
            {"connectivity_more.vtk", replace(what, a5, "CELLS 6 14", "CELLS 6 15"), "'CELL_TYPES' is not an integer",
             L(a5, "CELL_TYPES")},
            {"metadata_open.vtk", a5.substr(0, a5.find("\nCELLS") - 1), "no CELLS", kAnyLine},
            // Cell and point data.
            {"cell_data_count.vtk", cell_count, "CELL_DATA has 4 values for 5 cells", at_line(cell_data_line)},
            {"point_data_count.vtk", point_count, "POINT_DATA has 6 values for 5 points", at_line(point_data_line)},
            {"cell_data_short.vtk", replace(what, a, "CELL_DATA 5", "CELL_DATA 4"), "unknown keyword '-1'",
             L(a, "3 4 -1 -1 -1")},
            {"cell_data_word.vtk", replace(what, a, "CELL_DATA 5", "CELL_DATA all"), "'all' is not a non-negative",
             at_line(cell_data_line)},
            {"no_lookup_table.vtk", no_lut, "expected LOOKUP_TABLE after SCALARS, found '3'",
             L(no_lut, "3 4 -1 -1 -1")},
            {"no_lookup_table2.vtk", replace(what, no_lut, "SCALARS region int 1", "SCALARS region int"),
             "expected LOOKUP_TABLE after SCALARS, found '4'", L(no_lut, "3 4 -1 -1 -1")},
            {"scalars_components.vtk", replace(what, a, "SCALARS region int 1", "SCALARS region int 3"),
             "the region array must have 1 component",
             at_lines(line_of(what, a, "SCALARS region"), line_of(what, a, "SCALARS region") + 1)},
            {"scalars_components5.vtk", replace(what, a, "SCALARS q%20a double 1", "SCALARS q%20a double 5"),
             "(1 to 4)", L(a, "SCALARS q%20a")},
            {"scalars_type.vtk", replace(what, a, "SCALARS region int 1", "SCALARS region quux 1"),
             "unknown data type 'quux'", L(a, "SCALARS region")},
            {"scalars_short.vtk", replace(what, a, "3 4 -1 -1 -1", "3 4 -1 -1"), "'SCALARS' is not an integer",
             L(a, "SCALARS marker")},
            {"scalars_outside.vtk", replace(what, a, "CELL_DATA 5\n", ""), "SCALARS outside", L(a, "CELL_DATA")},
            {"region_fraction.vtk",
             replace(what, replace(what, a, "SCALARS region int 1", "SCALARS region double 1"), "3 4 -1 -1 -1",
                     "3 4.5 -1 -1 -1"),
             "region value 4.5", kAnyLine},
            {"region_float_int.vtk", replace(what, a, "3 4 -1 -1 -1", "3 4.0 -1 -1 -1"), "'4.0' is not an integer",
             L(a, "3 4 -1 -1 -1")},
            {"region_64bit.vtk",
             replace(what, replace(what, a, "SCALARS region int 1", "SCALARS region double 1"), "3 4 -1 -1 -1",
                     "3 4294967296 -1 -1 -1"),
             "region value 4294967296", kAnyLine},
            {"marker_64bit.vtk",
             replace(what, replace(what, a, "SCALARS marker int", "SCALARS marker vtktypeint64"), "-1 -1 7 12 -1",
                     "-1 -1 7 -2147483649 -1"),
             "marker value -2147483649", kAnyLine},
            {"region_int_range.vtk", replace(what, a, "3 4 -1 -1 -1", "3 2147483648 -1 -1 -1"),
             "region value 2147483648", kAnyLine},
            {"fixed_fraction.vtk", replace(what, kMesquite, "1\n0\n0\n0\n1\n", "1\n0\n0.5\n0\n1\n"), "fixed value 0.5",
             kAnyLine},
            {"ref_nan.vtk",
             replace(what, replace(what, a, "SCALARS ref int 1", "SCALARS ref float 1"), "0 -5 2 0 7", "0 -5 nan 0 7"),
             "ref value nan", kAnyLine},
            {"field_components.vtk", replace(what, a, "corner 1 5 unsigned_char", "corner 2 5 unsigned_char"),
             "the corner array must have 1 component", kAnyLine},
            {"field_tuples.vtk",
             replace(what, a, "corner 1 5 unsigned_char\n0 1 0 0 0", "corner 1 4 unsigned_char\n0 1 0 0"),
             "the corner array has 4 tuples for 5 points", L(a, "corner 1 5")},
            {"field_count.vtk", replace(what, a, "FIELD FieldData 1", "FIELD FieldData -1"),
             "'-1' is not a non-negative integer", L(a, "FIELD")},
            {"field_more.vtk", replace(what, a, "FIELD FieldData 1", "FIELD FieldData 2"), "end of file", kAnyLine},
            {"twice.vtk", replace(what, a, "SCALARS marker int", "SCALARS region int"), "a second region array",
             at_lines(line_of(what, a, "SCALARS marker"), line_of(what, a, "SCALARS marker") + 1)},
            {"two_cell_data.vtk", replace(what, a, "POINT_DATA 5", "CELL_DATA 5"), "a second CELL_DATA",
             L(a, "POINT_DATA")},
            {"garbage_keyword.vtk", replace(what, a, "POINT_DATA 5", "POINT_DATUM 5"), "unknown keyword 'POINT_DATUM'",
             L(a, "POINT_DATA")},
            {"garbage_top.vtk", replace(what, a, "CELLS 5 19", "CELLZ 5 19"), "unknown keyword 'CELLZ'", L(a, "CELLS")},
            {"lookup_short.vtk",
             replace(what, kAttributes, "LOOKUP_TABLE my_table 2\n0 0 0 1 1 1 1 1",
                     "LOOKUP_TABLE my_table 3\n0 0 0 1 1 1 1 1"),
             "'TEXTURE_COORDINATES' is not a number (table entries)", kAnyLine},
            {"color_short.vtk", replace(what, kAttributes, "COLOR_SCALARS colors 3", "COLOR_SCALARS colors 4"),
             "'LOOKUP_TABLE' is not a number (colour values)", kAnyLine},
            {"vectors_outside.vtk", replace(what, a, "CELL_DATA 5\n", "VECTORS v float\n0 0 0\nCELL_DATA 5\n"),
             "VECTORS outside", L(a, "CELL_DATA")},
            {"texture_dim.vtk",
             replace(what, kAttributes, "TEXTURE_COORDINATES uv 2 float", "TEXTURE_COORDINATES uv x float"),
             "'x' is not a non-negative integer", L(kAttributes, "TEXTURE_COORDINATES")},
            // Binary data.
            {"bin_points_cut.vtk", b.substr(0, bpoints + 30), "need 15 x 4 bytes, but only 30", kByte},
            {"bin_cells_cut.vtk", b.substr(0, bcells + 41), "need 19 x 4 bytes, but only 41", kByte},
            {"bin_end_cut.vtk", b.substr(0, b.size() - 3), "need 5 x 1 bytes, but only 3", kByte},
            {"bin_points_nan.vtk", patch_be<float>(what, b, "POINTS 5 float\n", 7, std::nanf("")),
             "coordinate 1 of point 2 is not finite", kByte},
            {"bin_points_inf.vtk", patch_be<float>(what, b, "POINTS 5 float\n", 14, -INFINITY),
             "coordinate 2 of point 4 is not finite", kByte},
            {"bin_cell_overrun.vtk", patch_be<int32_t>(what, b, "CELLS 5 19\n", 17, 99), "cell 4 has 99 points", kByte},
            {"bin_cell_count_negative.vtk", patch_be<int32_t>(what, b, "CELLS 5 19\n", 0, -4), "cell 0 has -4 points",
             kByte},
            {"bin_index_range.vtk", patch_be<int32_t>(what, b, "CELLS 5 19\n", 3, 5), "out of range for 5 points",
             kByte},
            {"bin_points_huge.vtk", replace(what, b, "POINTS 5 float", "POINTS 100000000 float"),
             "need 300000000 x 4 bytes", kByte},
            {"bin_cells_huge.vtk", replace(what, b, "CELLS 5 19", "CELLS 5 1900000000"), "need 1900000000 x 4 bytes",
             kByte},
            {"bin_lookup_huge.vtk", replace(what, b, "LOOKUP_TABLE flags 2", "LOOKUP_TABLE flags 200000000"),
             "need 800000000 x 1 bytes", kByte},
            {"bin_count_overflow.vtk",
             replace(what, replace(what, b, "CELL_DATA 5", "CELL_DATA 4000000000000000000"), "SCALARS region int 1",
                     "SCALARS other int 4"),
             "too many", kByte},
            {"bin_field_cut.vtk", b.substr(0, b.find("weight 2 5 double\n") + 30), "need 10 x 8 bytes, but only 12",
             kByte},
            {"bin_cell_data_short.vtk", replace(what, b, "CELL_DATA 5", "CELL_DATA 4"), "unknown keyword", kByte},
            {"bin_marker_fraction.vtk", patch_be<double>(what, b5, "marker 1 5 double\n", 2, 7.5), "marker value 7.5",
             kByte},
            {"bin_fixed_nan.vtk",
             patch_be<float>(what, b5, "SCALARS fixed float\nLOOKUP_TABLE default\n", 1, std::nanf("")),
             "fixed value nan", kByte},
            {"bin_offsets_start.vtk", patch_be<int64_t>(what, b5, "OFFSETS vtktypeint64\n", 0, 1),
             "the first offset is 1, not 0", kByte},
            {"bin_offsets_down.vtk", patch_be<int64_t>(what, b5, "OFFSETS vtktypeint64\n", 2, 3), "not increasing",
             kByte},
            {"bin_conn_range.vtk", patch_be<int64_t>(what, b5, "CONNECTIVITY vtktypeint64\n", 5, int64_t{1} << 40),
             "is 1099511627776, out of range", kByte},
            {"bin_conn_cut.vtk", b5.substr(0, b5conn + 20), "need 14 x 8 bytes, but only 20", kByte},
            {"bin_region_64bit.vtk", patch_be<int64_t>(what, b5, "region 1 5 vtktypeint64\n", 1, int64_t{1} << 33),
             "region value 8589934592", kByte},
            {"bin_keyword_junk.vtk", replace(what, b, "POINTS 5 float\n", "POINTS 5 float junk\n"), "unexpected 'j'",
             kEither},
        });

    // A missing file: an IO error naming it.
    const std::string missing = scratch("does_not_exist.vtk");
    const std::string msg = io_error(what, [&] { bodt::read_vtk(missing); });
    CHECK(msg.find(missing) != std::string::npos, "'%s'", msg.c_str());
}

void test_mutations(void**) {
    const char* what = "mutations";
    bodt::MeshData d = kuhn_block(1, 0);
    decorate(d, 1);
    d.tet_fields = {{"q", std::vector<double>(d.tets.size() / 4, 0.5)}};
    bodt::write_vtk(scratch("mutate_src.vtk"), d);
    const std::vector<std::string> seeds = {kAscii42,    kAscii51, kMesquite,      kLower,
                                            kAttributes, kVtk91,   kMeshio,        read_text(scratch("mutate_src.vtk")),
                                            bin42(),     bin51(),  meshio_binary()};
    const std::string path = scratch("mutated.vtk");
    const char* tokens[] = {"-1", "0", "4294967296", "1e300", "nan", "\n", " ", "99999999999", "%", "\0"};
    const auto positioned = [&](const std::string& m) {
        long line, byte;
        return position(m, path, &line, &byte);
    };
    io_test::Bits r{2024 * 2685821657736338717ull + 1};  // the state seed 2024 has always given
    int ok = 0, errors = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        std::string s = seeds[static_cast<size_t>(iter) % seeds.size()];
        io_test::mutate(s, r, tokens);
        if (io_test::check_mutant(what, iter, path, s, bodt::read_vtk, positioned)) ++ok;
        else ++errors;
    }
    CHECK(ok > 100 && errors > 100, "%d read, %d errors", ok, errors);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 1) g_dir = argv[1];
    mkdir(g_dir.c_str(), 0777);
    if (!little_endian_host()) {
        std::printf("test_io_vtk: big-endian host, skipped (the byte builder assumes little-endian)\n");
        return 0;
    }
    const CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_hand_written),
        cmocka_unit_test(test_ascii_float_points),
        cmocka_unit_test(test_vtk91_metadata),
        cmocka_unit_test(test_meshio),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_malformed),
        cmocka_unit_test(test_mutations),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
