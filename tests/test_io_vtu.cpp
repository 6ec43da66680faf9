// test_io_vtu: white-box tests of the .vtu reader/writer and the Abaqus
// .inp writer (links bodt_core).  Usage: test_io_vtu [scratch-dir]; files
// are written there (default: ./test_io_vtu_files, created if missing).
//
//   round trip        a 2x2x2 block of Kuhn cubes (48 tets, base 1) with
//                     regions (also negative), marked triangles (also an
//                     interface and a negative marker), feature edges with
//                     refs (also -1, the tets' filler), vertex refs, fixed
//                     vertices, corners and tet fields: coordinates
//                     bit-exact, all the mesh data back (base 0); the tet
//                     fields decoded from the file by this test's own base64
//                     decoder, NaN on non-tets; edges without refs come back
//                     with ref 0, with and without triangles (marker array
//                     written or not)
//   hand-written      an ASCII file and binary ones as ParaView / meshio write
//                     them (Float32 points, Int64 connectivity, UInt8 types,
//                     UInt32 and UInt64 headers, header and data encoded
//                     together or separately, comments, CDATA, entities);
//                     point data ref (Int16) and corner read, absent arrays
//                     give no vertex refs, no corners, edge ref 0
//   array names       regions, markers and edge refs from region, marker,
//                     gmsh:physical, CellEntityIds, medit:ref in all 32
//                     combinations, vertex refs from ref and medit:ref: the
//                     precedence of vtk_cells.hpp; a short overridden array
//                     still refused
//   refusals          LZ4, LZMA and unknown compressors, big-endian,
//                     hexahedra, quadratic tets, polyhedra, several Pieces
//   malformed         40 broken files (also bad ref, corner and marker
//                     arrays): each an Error(BODT_ERR_IO) whose message
//                     starts with "<path>:<line>: "
//   Abaqus            the .inp parsed back by a small parser here: nodes
//                     exact when their shortest form fits CalculiX's 20
//                     characters (else within 5e-15), element volumes positive, ELSETs = regions,
//                     NSET FIXED, NSET REF_<r> per nonzero vertex ref (none
//                     for 0), NSET NALL, NSET MARKER_<m>_NODES = the nodes of the
//                     triangles marked m, surfaces = the marked triangles
//                     with Abaqus's C3D4 face numbering, <= 16 entries per
//                     line (CalculiX solves from such a file: tests/interop)
#include "common/error.hpp"
#include "io/abaqus.hpp"
#include "io/mesh_io.hpp"
#include "io/vtu.hpp"

#include "bodt.h"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core_checks.hpp"
#include "file_text.hpp"
#include "kuhn_block_data.hpp"
#include "vtu_bytes.hpp"

namespace {

using io_test::b64;
using io_test::put_le;
using io_test::read_text;
using io_test::replace;
using io_test::unb64;
using io_test::write_text;

std::string g_dir = "test_io_vtu_files";

std::string scratch(const std::string& name) { return g_dir + "/" + name; }

// A binary DataArray body: header (UInt32 or UInt64) + data, encoded together
// (VTK) or separately (meshio's other convention).
template <class T>
std::string binary_body(const std::vector<T>& values, bool header64, bool separate) {
    std::vector<uint8_t> header, data;
    for (T v : values) put_le(data, v);
    if (header64) put_le(header, static_cast<uint64_t>(data.size()));
    else put_le(header, static_cast<uint32_t>(data.size()));
    if (separate) return b64(header) + b64(data);
    header.insert(header.end(), data.begin(), data.end());
    return b64(header);
}

// ------------------------------------------------------------ test mesh

using io_test::decorate;
using io_test::kuhn_block;
using io_test::sorted_tri;
using io_test::Tri;

// ------------------------------------------------------------ helpers

template <class F>
std::string io_error(const char* what, F f) {
    try {
        f();
    } catch (const bodt::Error& e) {
        CHECK(e.status() == BODT_ERR_IO, "status %d (%s)", e.status(), e.what());
        return e.what();
    }
    CHECK(false, "no error was raised");
    return {};
}

// Reads `text` from scratch/name and expects an IO error "<path>:<line>: ..."
// mentioning `needle`; returns the line.
long expect_malformed(const char* what, const std::string& name, const std::string& text, const char* needle) {
    const std::string path = scratch(name);
    write_text(path, text);
    const std::string msg = io_error(what, [&] { bodt::read_vtu(path); });
    CHECK(msg.compare(0, path.size() + 1, path + ":") == 0, "message '%s' does not start with the path", msg.c_str());
    const char* rest = msg.c_str() + std::min(msg.size(), path.size() + 1);
    char* end = nullptr;
    const long line = std::strtol(rest, &end, 10);
    CHECK(end != rest && line >= 1 && std::strncmp(end, ": ", 2) == 0, "no line number in '%s'", msg.c_str());
    CHECK(msg.find(needle) != std::string::npos, "'%s' does not mention '%s'", msg.c_str(), needle);
    return line;
}

// A ParaView-style ASCII file: two tets, a marked triangle, a line, a vertex
// cell; comments, CDATA and an entity on the way.  The ref and corner arrays
// share the fixed array's line, so that the line numbers the malformed cases
// check stay those of the file without them.
const std::string kAscii = R"(<?xml version="1.0"?>
<!-- hand written, as ParaView would -->
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="5" NumberOfCells="5">
      <PointData Scalars="fixed">
        <DataArray type="Int32" Name="fixed" format="ascii">1 0 0 0 1</DataArray><DataArray type="Int16" Name="ref" format="ascii">0 -5 2 0 7</DataArray><DataArray type="UInt8" Name="corner" format="ascii">0 1 0 0 0</DataArray>
      </PointData>
      <CellData>
        <DataArray type="Int32" Name="region" format="ascii">3 4 -1 -1 -1</DataArray>
        <DataArray type="Int32" Name="marker" format="ascii">-1 -1 7 12 -1</DataArray>
        <DataArray type="Float32" Name="q &amp; a" format="ascii">0.5 0.25 nan nan nan</DataArray>
      </CellData>
      <Points>
        <DataArray type="Float32" Name="Points" NumberOfComponents="3" format="ascii">
          0 0 0  1 0 0  0 1 0
          0 0 1  0.1 0.2 -1
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">
          0 1 2 3 <!-- second tet --> 0 2 1 4
          0 1 3  0 3  4
        </DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii"><![CDATA[4 8 11]]> 13 &#49;4</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10 10 5 3 1</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)";

void check_ascii_mesh(const char* what, const bodt::MeshData& d) {
    const float xyz[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1f, 0.2f, -1};
    CHECK(d.base == 0, "base %d", d.base);
    CHECK(d.xyz.size() == 15, "%zu coordinates", d.xyz.size());
    for (int k = 0; k < 15 && d.xyz.size() == 15; ++k)
        CHECK(d.xyz[k] == static_cast<double>(xyz[k]), "coordinate %d: %.17g", k, d.xyz[k]);
    CHECK((d.tets == std::vector<int32_t>{0, 1, 2, 3, 0, 2, 1, 4}), "tets");
    CHECK((d.regions == std::vector<int32_t>{3, 4}), "regions");
    CHECK((d.triangles == std::vector<int32_t>{0, 1, 3}), "triangles");
    CHECK((d.tri_markers == std::vector<int32_t>{7}), "markers");
    CHECK((d.feature_edges == std::vector<int32_t>{0, 3}), "feature edges");
    CHECK((d.edge_refs == std::vector<int32_t>{12}), "edge refs");
    CHECK((d.fixed == std::vector<int32_t>{0, 4}), "fixed");
    CHECK((d.vertex_refs == std::vector<int32_t>{0, -5, 2, 0, 7}), "vertex refs");
    CHECK((d.corners == std::vector<int32_t>{1}), "corners");
}

// A binary file like ParaView's: Float32 points, Int64 connectivity and
// offsets, UInt8 types; `header64` selects header_type UInt64.
std::string binary_file(bool header64, bool separate) {
    const std::vector<float> pts = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1f, 0.2f, -1};
    const std::vector<int64_t> conn = {0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 3, 0, 3};
    const std::vector<int64_t> offsets = {4, 8, 11, 13};
    const std::vector<uint8_t> types = {10, 10, 5, 3};
    const std::vector<int32_t> region = {3, 4, 0, 0};
    const std::vector<uint8_t> fixed = {1, 0, 0, 0, 1};
    std::string s = std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"") +
                    (header64 ? "1.0\" header_type=\"UInt64\"" : "0.1\"") +
                    " byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"5\" "
                    "NumberOfCells=\"4\">\n<PointData>\n<DataArray type=\"UInt8\" Name=\"fixed\" format=\"binary\">\n" +
                    binary_body(fixed, header64, separate) +
                    "\n</DataArray>\n</PointData>\n<CellData>\n<DataArray type=\"Int32\" Name=\"region\" "
                    "format=\"binary\">" +
                    binary_body(region, header64, separate) +
                    "</DataArray>\n</CellData>\n<Points>\n<DataArray type=\"Float32\" Name=\"Points\" "
                    "NumberOfComponents=\"3\" format=\"binary\">\n  " +
                    binary_body(pts, header64, separate) +
                    "\n</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
                    "format=\"binary\">\n";
    // Wrapped at 20 characters, as some writers do.
    const std::string c = binary_body(conn, header64, separate);
    for (size_t k = 0; k < c.size(); k += 20) s += c.substr(k, 20) + "\n";
    s += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"binary\">" +
         binary_body(offsets, header64, separate) +
         "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"binary\">" +
         binary_body(types, header64, separate) + "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
    return s;
}

// ------------------------------------------------------------ tests

void test_round_trip(void**) {
    const char* what = "round trip";
    bodt::MeshData d = kuhn_block(2, 1);
    decorate(d, 2);
    const size_t nt = d.tets.size() / 4;
    bodt::MeshData::TetField qmin{"min_dihedral", {}}, vol{"volume", {}}, odd{"a<b & \"c\"", {}};
    for (size_t t = 0; t < nt; ++t) {
        qmin.values.push_back(30.0 + static_cast<double>(t) / 3.0);
        vol.values.push_back(std::ldexp(1.0, -static_cast<int>(t)) / 7.0);
        odd.values.push_back(-static_cast<double>(t));
    }
    d.tet_fields = {qmin, vol, odd};
    const std::string path = scratch("round_trip.vtu");
    bodt::write_vtu(path, d);
    const bodt::MeshData r = bodt::read_vtu(path);

    CHECK(r.base == 0, "base %d", r.base);
    CHECK(r.xyz.size() == d.xyz.size(), "%zu coordinates", r.xyz.size());
    CHECK(std::memcmp(r.xyz.data(), d.xyz.data(), d.xyz.size() * sizeof(double)) == 0, "coordinates not bit-exact");
    std::vector<int32_t> tets0 = d.tets;
    for (int32_t& v : tets0) v -= 1;
    CHECK(r.tets == tets0, "tets differ");
    CHECK(r.regions == d.regions, "regions differ");
    std::vector<int32_t> tris0 = d.triangles, edges0 = d.feature_edges;
    for (int32_t& v : tris0) v -= 1;
    for (int32_t& v : edges0) v -= 1;
    CHECK(r.triangles == tris0, "triangles differ");
    CHECK(r.tri_markers == d.tri_markers, "markers differ");
    CHECK(r.feature_edges == edges0, "feature edges differ");
    std::set<int32_t> fixed0;
    for (int32_t v : d.fixed) fixed0.insert(v - 1);
    CHECK(std::set<int32_t>(r.fixed.begin(), r.fixed.end()) == fixed0 && r.fixed.size() == fixed0.size(),
          "fixed differ");
    CHECK(r.edge_refs == d.edge_refs, "edge refs differ");
    CHECK(r.vertex_refs == d.vertex_refs, "vertex refs differ");
    std::set<int32_t> corners0;
    for (int32_t v : d.corners) corners0.insert(v - 1);
    CHECK(r.corners == std::vector<int32_t>(corners0.begin(), corners0.end()), "corners differ (sorted, each once)");
    CHECK(r.tet_fields.empty(), "tet fields are not read back");

    // The tet fields, decoded from the file by this test's own decoder.
    const std::string text = read_text(path);
    const size_t ncells = nt + d.tri_markers.size() + d.feature_edges.size() / 2;
    for (const auto* f : {&qmin, &vol}) {
        const std::string tag = "Name=\"" + f->name + "\" format=\"binary\">";
        const size_t at = text.find(tag);
        CHECK(at != std::string::npos, "no Float64 array %s", f->name.c_str());
        if (at == std::string::npos) continue;
        CHECK(text.rfind("type=\"Float64\"", at) + 30 > at, "%s is not Float64", f->name.c_str());
        const size_t begin = at + tag.size(), end = text.find("</DataArray>", begin);
        const std::vector<uint8_t> bytes = unb64(text.substr(begin, end - begin));
        CHECK(bytes.size() == 8 + 8 * ncells, "%zu bytes", bytes.size());
        uint64_t header;
        std::memcpy(&header, bytes.data(), 8);
        CHECK(header == 8 * ncells, "header %llu", static_cast<unsigned long long>(header));
        for (size_t c = 0; c < ncells && bytes.size() == 8 + 8 * ncells; ++c) {
            double x;
            std::memcpy(&x, &bytes[8 + 8 * c], 8);
            if (c < nt) CHECK(x == f->values[c], "%s of tet %zu: %.17g", f->name.c_str(), c, x);
            else CHECK(std::isnan(x), "%s of non-tet cell %zu is %g, not NaN", f->name.c_str(), c, x);
        }
    }
    CHECK(text.find("Name=\"a&lt;b &amp; &quot;c&quot;\"") != std::string::npos, "field name not escaped");
    CHECK(text.find("Name=\"region\"") != std::string::npos && text.find("Name=\"marker\"") != std::string::npos &&
              text.find("Name=\"fixed\"") != std::string::npos && text.find("Name=\"corner\"") != std::string::npos &&
              text.find("Int32\" Name=\"ref\"") != std::string::npos,
          "region / marker / fixed / corner / ref arrays missing");

    // Writing what was read gives the same file minus the fields; a bare mesh too.
    bodt::MeshData bare;
    bare.xyz = r.xyz;
    bare.tets = r.tets;
    bodt::write_vtu(scratch("bare.vtu"), bare);
    const bodt::MeshData b = bodt::read_vtu(scratch("bare.vtu"));
    CHECK(b.xyz == bare.xyz && b.tets == bare.tets, "bare mesh differs");
    CHECK(b.regions.empty() && b.triangles.empty() && b.fixed.empty() && b.feature_edges.empty() &&
              b.edge_refs.empty() && b.vertex_refs.empty() && b.corners.empty(),
          "bare mesh gained data");

    // Edges without refs: ref 0, whether a marker array is written (for
    // triangles) or not.
    bodt::MeshData plain_edges = r;
    plain_edges.edge_refs.clear();
    for (int with_triangles = 0; with_triangles < 2; ++with_triangles) {
        if (!with_triangles) plain_edges.triangles.clear(), plain_edges.tri_markers.clear();
        bodt::write_vtu(scratch("plain_edges.vtu"), plain_edges);
        const bodt::MeshData e = bodt::read_vtu(scratch("plain_edges.vtu"));
        CHECK(e.feature_edges == plain_edges.feature_edges, "edges without refs differ");
        CHECK(e.edge_refs == std::vector<int32_t>(plain_edges.feature_edges.size() / 2, 0), "edge refs are not 0");
        CHECK(e.tri_markers == plain_edges.tri_markers, "markers differ");
        CHECK((read_text(scratch("plain_edges.vtu")).find("Name=\"marker\"") != std::string::npos) ==
                  !plain_edges.triangles.empty(),
              "marker array written %s triangles", with_triangles ? "with" : "without");
    }

    // Inconsistent MeshData is an argument error.
    bodt::MeshData bad = d;
    bad.tet_fields[0].values.pop_back();
    try {
        bodt::write_vtu(scratch("bad.vtu"), bad);
        CHECK(false, "short tet field accepted");
    } catch (const bodt::Error& e) {
        CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT, "status %d", e.status());
    }
    bad = d;
    bad.tet_fields[1].name = "region";
    try {
        bodt::write_vtu(scratch("bad.vtu"), bad);
        CHECK(false, "field named region accepted");
    } catch (const bodt::Error& e) {
        CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT, "status %d", e.status());
    }
    const auto refused = [&](const bodt::MeshData& m, const char* expect) {
        try {
            bodt::write_vtu(scratch("bad.vtu"), m);
            CHECK(false, "written, expected '%s'", expect);
        } catch (const bodt::Error& e) {
            CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT && std::strstr(e.what(), expect), "%s", e.what());
        }
    };
    bad = d;
    bad.vertex_refs.pop_back();
    refused(bad, "vertex_refs");
    bad = d;
    bad.edge_refs.push_back(3);
    refused(bad, "edge_refs");
    bad = d;
    bad.corners.push_back(0);  // base 1
    refused(bad, "vertex 0 is out of range");
}

void test_hand_written(void**) {
    const char* what = "hand-written files";
    write_text(scratch("ascii.vtu"), kAscii);
    check_ascii_mesh(what, bodt::read_vtu(scratch("ascii.vtu")));
    for (int header64 = 0; header64 < 2; ++header64)
        for (int separate = 0; separate < 2; ++separate) {
            const std::string path = scratch("binary" + std::to_string(header64) + std::to_string(separate) + ".vtu");
            write_text(path, binary_file(header64 != 0, separate != 0));
            const bodt::MeshData d = bodt::read_vtu(path);
            // As the ASCII file, without the vertex cell; triangle has no marker array -> 0.
            const float xyz[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1f, 0.2f, -1};
            CHECK(d.xyz.size() == 15, "%zu coordinates", d.xyz.size());
            for (int k = 0; k < 15 && d.xyz.size() == 15; ++k)
                CHECK(d.xyz[k] == static_cast<double>(xyz[k]), "coordinate %d: %.17g", k, d.xyz[k]);
            CHECK((d.tets == std::vector<int32_t>{0, 1, 2, 3, 0, 2, 1, 4}), "tets (%d %d)", header64, separate);
            CHECK((d.regions == std::vector<int32_t>{3, 4}), "regions");
            CHECK((d.triangles == std::vector<int32_t>{0, 1, 3}), "triangles");
            CHECK((d.tri_markers == std::vector<int32_t>{0}), "markers");
            CHECK((d.feature_edges == std::vector<int32_t>{0, 3}), "feature edges");
            CHECK((d.edge_refs == std::vector<int32_t>{0}), "edge refs without a marker array");
            CHECK((d.fixed == std::vector<int32_t>{0, 4}), "fixed");
            CHECK(d.vertex_refs.empty() && d.corners.empty(), "vertex refs or corners without their arrays");
        }
    // Single-quoted attributes, a BOM, self-closing empty PointData.
    std::string s = "\xEF\xBB\xBF" + replace(what, kAscii, "format=\"ascii\">10 10 5 3 1", "format='ascii'>10 10 5 3 1");
    s = replace(what, s, "<CellData>", "<PointData/><FieldData></FieldData><CellData>");
    s = replace(what, s, "<PointData Scalars=\"fixed\">", "<PointData2>");
    s = replace(what, s, "</PointData>", "</PointData2>");
    write_text(scratch("ascii2.vtu"), s);
    const bodt::MeshData d2 = bodt::read_vtu(scratch("ascii2.vtu"));
    CHECK(d2.fixed.empty(), "fixed from an unknown element");
    CHECK(d2.tets.size() == 8, "tets");
}

// Regions and markers under the names other programs use (vtk_cells.hpp):
// every combination of region, marker, gmsh:physical, CellEntityIds and
// medit:ref present, each with its own values, gives those of the first
// name in the order of precedence; likewise ref and medit:ref.
void test_array_names(void**) {
    const char* what = "array names";
    const char* const names[] = {"region", "marker", "gmsh:physical", "CellEntityIds", "medit:ref"};
    const char* const values[] = {"1 2 -1 -1 -1", "-1 -1 101 102 -1", "11 12 111 112 0", "21 22 121 122 0",
                                  "31 32 131 132 0"};
    const size_t cells_begin = kAscii.find("<CellData>"), cells_end = kAscii.find("</CellData>");
    int failed = 0;
    for (int mask = 0; mask < 32; ++mask)
        for (int point_mask = 1; point_mask < 4; ++point_mask) {
            std::string cell_data = "<CellData>";
            int region = -1, marker = -1;
            for (int k = 0; k < 5; ++k) {
                if (!(mask >> k & 1)) continue;
                cell_data += std::string("<DataArray type=\"Int64\" Name=\"") + names[k] + "\" format=\"ascii\">" +
                             values[k] + "</DataArray>";
                if (k != 1 && region < 0) region = k;
                if (k != 0 && marker < 0) marker = k;
            }
            std::string s = kAscii.substr(0, cells_begin) + cell_data + kAscii.substr(cells_end);
            if (point_mask & 2)
                s = replace(what, s, "<DataArray type=\"UInt8\" Name=\"corner\"",
                            "<DataArray type=\"Int8\" Name=\"medit:ref\" format=\"ascii\">9 9 9 9 9</DataArray>"
                            "<DataArray type=\"UInt8\" Name=\"corner\"");
            if (!(point_mask & 1)) s = replace(what, s, "Name=\"ref\"", "Name=\"reference\"");
            const std::string path = scratch("names.vtu");
            write_text(path, s);
            bodt::MeshData d;
            try {
                d = bodt::read_vtu(path);
            } catch (const bodt::Error& e) {
                CHECK(false, "arrays %d, point arrays %d: %s", mask, point_mask, e.what());
                continue;
            }
            const int32_t r0 = region < 0 ? 0 : region == 0 ? 1 : 10 * (region - 1) + 1;
            const std::vector<int32_t> regions = region < 0 ? std::vector<int32_t>{} : std::vector<int32_t>{r0, r0 + 1};
            const int32_t m0 = marker < 0 ? 0 : 100 + (marker == 1 ? 1 : 10 * (marker - 1) + 1);
            const std::vector<int32_t> refs =
                point_mask & 1 ? std::vector<int32_t>{0, -5, 2, 0, 7} : std::vector<int32_t>{9, 9, 9, 9, 9};
            const bool ok = d.regions == regions && d.tri_markers == std::vector<int32_t>{m0} &&
                            d.edge_refs == std::vector<int32_t>{marker < 0 ? 0 : m0 + 1} && d.vertex_refs == refs;
            if (!ok) {
                ++failed;
                std::printf("%s: arrays %d, point arrays %d: %zu regions, marker %d, edge ref %d, vertex ref %d\n", what,
                            mask, point_mask, d.regions.size(), d.tri_markers.empty() ? -99 : d.tri_markers[0],
                            d.edge_refs.empty() ? -99 : d.edge_refs[0], d.vertex_refs.empty() ? -99 : d.vertex_refs[0]);
            }
        }
    CHECK(failed == 0, "%d of 96 combinations failed (listed above)", failed);
    // Every array read is checked, also one that another overrides.
    expect_malformed(what, "names_short.vtu",
                     replace(what, kAscii, "<CellData>",
                             "<CellData><DataArray type=\"Int32\" Name=\"medit:ref\" format=\"ascii\">1 2</DataArray>"),
                     "the medit:ref array has 2 values for 5 cells");
}

void test_refusals(void**) {
    const char* what = "refusals";
    const std::string bin = binary_file(false, false);
    for (const char* compressor : {"vtkLZ4DataCompressor", "vtkLZMADataCompressor"})
        expect_malformed(what, "compressed.vtu",
                         replace(what, bin, "byte_order=", "compressor=\"" + std::string(compressor) + "\" byte_order="),
                         (std::string("compressor ") + compressor + " is not supported").c_str());
    expect_malformed(what, "compressed.vtu", replace(what, bin, "byte_order=", "compressor=\"gzip\" byte_order="),
                     "unknown compressor \"gzip\"");
    expect_malformed(what, "bigendian.vtu", replace(what, bin, "LittleEndian", "BigEndian"), "big-endian");
    const long line = expect_malformed(what, "hexahedron.vtu",
                                       replace(what, kAscii, ">10 10 5 3 1<", ">10 12 5 3 1<"), "(hexahedron)");
    CHECK(line == 26, "hexahedron reported on line %ld", line);
    expect_malformed(what, "quadratic.vtu", replace(what, kAscii, ">10 10 5 3 1<", ">24 10 5 3 1<"),
                     "(quadratic tetra)");
    expect_malformed(what, "polyhedron.vtu",
                     replace(what, kAscii, "</Cells>",
                             "<DataArray type=\"Int64\" Name=\"faces\" format=\"ascii\">0</DataArray></Cells>"),
                     "polyhedron");
    expect_malformed(what, "pieces.vtu",
                     replace(what, kAscii, "</UnstructuredGrid>", "<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\"/></UnstructuredGrid>"),
                     "more than one <Piece>");
    expect_malformed(what, "polydata.vtu", replace(what, kAscii, "\"UnstructuredGrid\"", "\"PolyData\""),
                     "not an UnstructuredGrid");
    expect_malformed(what, "header.vtu", replace(what, bin, "version=\"0.1\"", "header_type=\"UInt16\""),
                     "header_type");
}

void test_malformed(void**) {
    const char* what = "malformed";
    const std::string bin = binary_file(false, false);
    int n = 0;
    auto bad = [&](const char* name, const std::string& text, const char* needle) {
        ++n;
        return expect_malformed(what, name, text, needle);
    };
    bad("empty.vtu", "", "no element");
    bad("truncated.vtu", kAscii.substr(0, kAscii.find("<Points>")), "is not closed");
    bad("truncated_tag.vtu", kAscii.substr(0, kAscii.find("NumberOfCells") + 3), "unexpected end of file");
    bad("truncated_attr.vtu", kAscii.substr(0, kAscii.find("NumberOfCells=\"5") + 16), "unexpected end of file");
    long line = bad("mismatch.vtu", replace(what, kAscii, "</Points>", "</Point>"), "does not match <Points>");
    CHECK(line == 19, "mismatch on line %ld", line);
    bad("second_root.vtu", kAscii + "<VTKFile/>", "second root");
    bad("text_after.vtu", kAscii + "junk", "text outside");
    bad("entity.vtu", replace(what, kAscii, "q &amp; a", "q &nbsp; a"), "unknown entity");
    bad("not_vtk.vtu", "<?xml version=\"1.0\"?>\n<html><body/></html>\n", "not a VTK XML file");
    bad("more_points.vtu", replace(what, kAscii, "NumberOfPoints=\"5\"", "NumberOfPoints=\"6\""),
        "NumberOfPoints is 6");
    bad("huge_points.vtu", replace(what, kAscii, "NumberOfPoints=\"5\"", "NumberOfPoints=\"99999999999999\""),
        "too large");
    bad("negative_cells.vtu", replace(what, kAscii, "NumberOfCells=\"5\"", "NumberOfCells=\"-5\""),
        "not a non-negative integer");
    bad("more_cells.vtu", replace(what, kAscii, "NumberOfCells=\"5\"", "NumberOfCells=\"6\""), "NumberOfCells is 6");
    // base64 garbage, reported on its own line.
    std::string garbage = bin;
    const size_t at = garbage.find("Name=\"Points\"");
    const size_t body = garbage.find('\n', at) + 5;
    garbage[body] = '!';
    line = bad("b64_garbage.vtu", garbage, "invalid character '!'");
    CHECK(line == 15, "base64 garbage on line %ld", line);
    bad("b64_truncated.vtu",
        replace(what, bin, binary_body(std::vector<uint8_t>{10, 10, 5, 3}, false, false), "BAAAAAoK BQ  "),
        "truncated data");
    bad("b64_short.vtu", replace(what, bin, binary_body(std::vector<uint8_t>{10, 10, 5, 3}, false, false), "BAAAAAoKBQ"),
        "the header says 4 bytes of data, but at most 2 follow");
    bad("b64_long.vtu",
        replace(what, bin, binary_body(std::vector<uint8_t>{10, 10, 5, 3}, false, false), b64({3, 0, 0, 0, 10, 10, 5, 3})),
        "more base64 data follows the data its header gives");
    bad("b64_header.vtu",
        replace(what, bin, binary_body(std::vector<uint8_t>{10, 10, 5, 3}, false, false),
                b64({9, 0, 0, 0, 10, 10, 5, 3})),
        "header says 9 bytes");
    bad("b64_pad.vtu",
        replace(what, bin, binary_body(std::vector<uint8_t>{10, 10, 5, 3}, false, false), "BAAAAAoKBQM=A==="),
        "misplaced '='");
    bad("offsets_down.vtu", replace(what, kAscii, "13 &#49;4", "10 14"), "not increasing");
    bad("offsets_beyond.vtu", replace(what, kAscii, "13 &#49;4", "13 15"), "beyond the 14 connectivity");
    bad("offsets_short.vtu", replace(what, kAscii, "0 3  4\n", "0 3  4 4\n"), "offsets use 14 of the 15");
    bad("cell_size.vtu", replace(what, kAscii, ">10 10 5 3 1<", ">10 10 10 3 1<"), "has 3 points instead of 4");
    bad("conn_range.vtu", replace(what, kAscii, "0 2 1 4", "0 2 1 5"), "out of range for 5 points");
    bad("conn_negative.vtu", replace(what, kAscii, "0 2 1 4", "0 2 -1 4"), "is -1, out of range");
    line = bad("nan_ascii.vtu", replace(what, kAscii, "0.1 0.2 -1", "0.1 nan -1"), "not finite");
    CHECK(line == 15, "NaN on line %ld", line);
    {
        const std::vector<float> pts = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1f, 0.2f, -1};
        std::vector<float> nan_pts = pts;
        nan_pts[7] = std::nanf("");
        bad("nan_binary.vtu", replace(what, bin, binary_body(pts, false, false), binary_body(nan_pts, false, false)),
            "coordinate 1 of point 2 is not finite");
    }
    line = bad("ascii_token.vtu", replace(what, kAscii, "0 3  4\n", "0 3  x4\n"), "expected an integer, found 'x4'");
    CHECK(line == 23, "bad token on line %ld", line);
    bad("ascii_range.vtu", replace(what, kAscii, ">10 10 5 3 1<", ">10 10 5 3 300<"), "does not fit in UInt8");
    bad("no_connectivity.vtu", replace(what, kAscii, "Name=\"connectivity\"", "Name=\"conn\""),
        "no DataArray connectivity");
    bad("no_format.vtu", replace(what, kAscii, "Name=\"types\" format=\"ascii\"", "Name=\"types\""), "has no format");
    bad("bad_type.vtu", replace(what, kAscii, "type=\"UInt8\"", "type=\"Bit\""), "unsupported type 'Bit'");
    bad("region_size.vtu", replace(what, kAscii, "3 4 -1 -1 -1", "3 4 -1 -1"), "region array has 4 values");
    bad("float_conn.vtu", replace(what, kAscii, "type=\"Int64\" Name=\"connectivity\"", "type=\"Float64\" Name=\"connectivity\""),
        "must be integers");
    bad("no_tets.vtu", replace(what, kAscii, ">10 10 5 3 1<", ">9 9 5 3 1<"), "(quad)");
    bad("two_points.vtu",
        replace(what, kAscii, "</Points>", "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\"/></Points>"),
        "more than one DataArray");
    bad("comment.vtu", kAscii.substr(0, kAscii.find("<!-- second") + 8), "unterminated comment");
    bad("doctype.vtu", "<!DOCTYPE x>\n" + kAscii, "DOCTYPE");
    bad("tuples.vtu", replace(what, kAscii, "Name=\"fixed\"", "Name=\"fixed\" NumberOfTuples=\"4\""),
        "NumberOfTuples 4");
    bad("ref_size.vtu", replace(what, kAscii, "0 -5 2 0 7", "0 -5 2 0"), "ref array has 4 values for 5 points");
    bad("ref_float.vtu", replace(what, kAscii, "type=\"Int16\" Name=\"ref\"", "type=\"Float32\" Name=\"ref\""),
        "ref array must be of an integer type");
    bad("ref_64bit.vtu",
        replace(what, replace(what, kAscii, "type=\"Int16\" Name=\"ref\"", "type=\"Int64\" Name=\"ref\""),
                "0 -5 2 0 7", "0 -5 4294967296 0 7"),
        "ref value 4294967296 does not fit in 32 bits");
    bad("ref_range.vtu", replace(what, kAscii, "0 -5 2 0 7", "0 -5 2 0 40000"), "does not fit in Int16");
    bad("ref_twice.vtu",
        replace(what, kAscii, "</PointData>", "<DataArray type=\"Int32\" Name=\"ref\" format=\"ascii\"/></PointData>"),
        "a second DataArray ref");
    bad("corner_components.vtu",
        replace(what, kAscii, "Name=\"corner\"", "Name=\"corner\" NumberOfComponents=\"5\""),
        "corner array must have 1 component");
    bad("corner_word.vtu", replace(what, kAscii, "0 1 0 0 0", "0 1 0 x 0"), "expected an integer, found 'x'");
    bad("marker_size.vtu", replace(what, kAscii, "-1 -1 7 12 -1", "-1 -1 7 12"), "marker array has 4 values");
    bad("marker_64bit.vtu",
        replace(what, replace(what, kAscii, "type=\"Int32\" Name=\"marker\"", "type=\"Int64\" Name=\"marker\""),
                "-1 -1 7 12 -1", "-1 -1 7 -2147483649 -1"),
        "marker value -2147483649 does not fit in 32 bits");
    CHECK(n >= 12, "only %d malformed cases", n);

    // A missing file: an IO error naming it.
    const std::string missing = scratch("does_not_exist.vtu");
    const std::string msg = io_error(what, [&] { bodt::read_vtu(missing); });
    CHECK(msg.find(missing) != std::string::npos, "'%s'", msg.c_str());
}

// ------------------------------------------------------------ Abaqus

struct Inp {
    std::map<long, std::array<double, 3>> nodes;
    std::map<long, std::array<long, 4>> elements;
    std::map<std::string, std::vector<long>> elsets, nsets;
    std::map<std::string, std::vector<std::pair<std::string, std::string>>> surfaces;
};

std::vector<std::string> split_commas(const std::string& line) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : line) {
        if (c == ',') {
            out.push_back(cur);
            cur.clear();
        } else if (c != ' ' && c != '\r') {
            cur += c;
        }
    }
    out.push_back(cur);
    return out;
}

Inp parse_inp(const char* what, const std::string& path) {
    Inp inp;
    std::ifstream in(path);
    std::string line, mode, set;
    bool generate = false;
    int lines = 0;
    while (std::getline(in, line)) {
        ++lines;
        CHECK(line.size() <= 256, "line %d is %zu characters", lines, line.size());
        if (line.compare(0, 2, "**") == 0) continue;
        const std::vector<std::string> f = split_commas(line);
        if (line[0] == '*') {
            mode = f[0];
            set.clear();
            generate = false;
            for (size_t k = 1; k < f.size(); ++k) {
                const size_t eq = f[k].find('=');
                const std::string key = f[k].substr(0, eq), value = eq == std::string::npos ? "" : f[k].substr(eq + 1);
                if (key == "ELSET" || key == "NSET" || key == "NAME") set = value;
                if (key == "GENERATE") generate = true;
                if (key == "TYPE" && mode == "*ELEMENT") CHECK(value == "C3D4", "element type %s", value.c_str());
                if (key == "TYPE" && mode == "*SURFACE") CHECK(value == "ELEMENT", "surface type %s", value.c_str());
            }
            if (mode == "*ELSET") CHECK(!inp.elsets.count(set), "ELSET %s twice", set.c_str());
            continue;
        }
        CHECK(f.size() <= 16, "line %d has %zu entries", lines, f.size());
        if (mode == "*HEADING") continue;
        if (mode == "*NODE") {
            CHECK(f.size() == 4, "node line %d", lines);
            for (const std::string& x : f) CHECK(x.size() <= 20, "node field '%s' is over 20 characters", x.c_str());
            inp.nodes[std::stol(f[0])] = {std::strtod(f[1].c_str(), nullptr), std::strtod(f[2].c_str(), nullptr),
                                          std::strtod(f[3].c_str(), nullptr)};
        } else if (mode == "*ELEMENT") {
            CHECK(f.size() == 5, "element line %d", lines);
            const long id = std::stol(f[0]);
            CHECK(!inp.elements.count(id), "element %ld twice", id);
            inp.elements[id] = {std::stol(f[1]), std::stol(f[2]), std::stol(f[3]), std::stol(f[4])};
            if (!set.empty()) inp.elsets[set].push_back(id);
        } else if (mode == "*ELSET" || mode == "*NSET") {
            auto& sets = mode == "*ELSET" ? inp.elsets : inp.nsets;
            if (generate) {
                CHECK(f.size() == 3, "GENERATE line %d", lines);
                for (long k = std::stol(f[0]); k <= std::stol(f[1]); k += std::stol(f[2])) sets[set].push_back(k);
            } else {
                for (const std::string& s : f) sets[set].push_back(std::stol(s));
            }
        } else if (mode == "*SURFACE") {
            CHECK(f.size() == 2, "surface line %d", lines);
            inp.surfaces[set].emplace_back(f[0], f[1]);
        } else {
            CHECK(false, "unexpected keyword %s", mode.c_str());
        }
    }
    return inp;
}

std::string abaqus_id(int32_t id) { return id < 0 ? "N" + std::to_string(-id) : std::to_string(id); }

void test_abaqus(void**) {
    const char* what = "abaqus";
    bodt::MeshData d = kuhn_block(3, 1);  // 162 tets: ALL has more than 16 members per set line
    decorate(d, 3);
    // Negative coordinates below 0.1 and tiny ones: some need 21+ characters.
    for (size_t k = 0; k < d.xyz.size(); k += 3) {
        d.xyz[k] -= 0.0537;
        d.xyz[k + 2] -= 1.3e-5;
    }
    const std::string path = scratch("mesh.inp");
    bodt::write_abaqus(path, d);
    const Inp inp = parse_inp(what, path);
    const size_t nv = d.xyz.size() / 3, nt = d.tets.size() / 4;

    CHECK(inp.nodes.size() == nv, "%zu nodes", inp.nodes.size());
    int exact = 0, rounded = 0;
    for (size_t v = 0; v < nv; ++v) {
        auto it = inp.nodes.find(static_cast<long>(v) + 1);
        CHECK(it != inp.nodes.end(), "node %zu missing", v + 1);
        if (it == inp.nodes.end()) continue;
        for (int k = 0; k < 3; ++k) {
            // Exact when the shortest exact form fits CalculiX's 20 characters.
            const double x = d.xyz[3 * v + k];
            char buf[64];
            std::string s(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
            const size_t e = s.find('e');
            if (e != std::string::npos) {
                size_t z = e + 1 + (s[e + 1] == '-' || s[e + 1] == '+');
                while (z + 1 < s.size() && s[z] == '0') s.erase(z, 1);
                if (s[e + 1] == '+') s.erase(e + 1, 1);
            }
            if (s.size() <= 20) {
                ++exact;
                CHECK(it->second[k] == x, "node %zu coordinate %d: %.17g for %.17g", v + 1, k, it->second[k], x);
            } else {
                ++rounded;
                CHECK(std::abs(it->second[k] - x) <= 5e-15 * std::abs(x), "node %zu coordinate %d: %.17g for %.17g",
                      v + 1, k, it->second[k], x);
            }
        }
    }
    CHECK(exact > 0 && rounded > 0, "%d exact and %d rounded coordinates: both cases expected", exact, rounded);
    CHECK(inp.elements.size() == nt, "%zu elements", inp.elements.size());
    for (size_t t = 0; t < nt; ++t) {
        auto it = inp.elements.find(static_cast<long>(t) + 1);
        CHECK(it != inp.elements.end(), "element %zu missing", t + 1);
        if (it == inp.elements.end()) continue;
        bodt::Vec3 p[4];
        for (int k = 0; k < 4; ++k) {
            CHECK(it->second[k] == d.tets[4 * t + k], "element %zu node %d", t + 1, k);  // base 1 = node numbers
            const auto& c = inp.nodes.at(it->second[k]);
            p[k] = bodt::Vec3(c[0], c[1], c[2]);
        }
        CHECK((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) > 0, "element %zu is not positive", t + 1);
    }
    // ELSETs: one per region, plus ALL.
    std::map<std::string, std::vector<long>> expect;
    for (size_t t = 0; t < nt; ++t) expect["REGION_" + abaqus_id(d.regions[t])].push_back(static_cast<long>(t) + 1);
    for (size_t t = 0; t < nt; ++t) expect["ALL"].push_back(static_cast<long>(t) + 1);
    for (const auto& [name, elems] : expect) {
        auto it = inp.elsets.find(name);
        CHECK(it != inp.elsets.end(), "no ELSET %s", name.c_str());
        if (it == inp.elsets.end()) continue;
        std::vector<long> got = it->second;
        std::sort(got.begin(), got.end());
        CHECK(got == elems, "ELSET %s differs", name.c_str());
    }
    CHECK(inp.elsets.count("REGION_N2"), "negative region name");
    // FIXED.
    std::vector<long> fixed;
    for (int32_t v : d.fixed) fixed.push_back(v);
    std::sort(fixed.begin(), fixed.end());
    fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
    CHECK(inp.nsets.count("FIXED") && inp.nsets.at("FIXED") == fixed, "NSET FIXED");
    // REF_<r>: the nodes of each nonzero vertex ref; MARKER_<m>_NODES: the
    // nodes of each marker's triangles (sorted, each once); no other node set.
    std::map<std::string, std::vector<long>> ref_sets, marker_sets;
    for (size_t v = 0; v < nv; ++v)
        if (d.vertex_refs[v] != 0) ref_sets["REF_" + abaqus_id(d.vertex_refs[v])].push_back(static_cast<long>(v) + 1);
    CHECK(ref_sets.size() >= 3 && ref_sets.count("REF_N1"), "test mesh lacks vertex refs, a negative one among them");
    for (size_t f = 0; f < d.tri_markers.size(); ++f) {
        std::vector<long>& set = marker_sets["MARKER_" + abaqus_id(d.tri_markers[f]) + "_NODES"];
        for (int k = 0; k < 3; ++k) set.push_back(d.triangles[3 * f + k]);  // base 1 = node numbers
    }
    for (auto& [name, nodes] : marker_sets) {
        std::sort(nodes.begin(), nodes.end());
        nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    }
    CHECK(marker_sets.size() >= 3 && marker_sets.count("MARKER_N3_NODES"), "test mesh lacks markers");
    CHECK(inp.nsets.size() == ref_sets.size() + marker_sets.size() + 2,
          "%zu node sets for %zu refs, %zu markers, FIXED and NALL", inp.nsets.size(), ref_sets.size(),
          marker_sets.size());
    std::vector<long> all(nv);
    for (size_t v = 0; v < nv; ++v) all[v] = static_cast<long>(v) + 1;
    CHECK(inp.nsets.count("NALL") && inp.nsets.at("NALL") == all, "NSET NALL");
    for (const auto* sets : {&ref_sets, &marker_sets})
        for (const auto& [name, nodes] : *sets)
            CHECK(inp.nsets.count(name) && inp.nsets.at(name) == nodes, "NSET %s", name.c_str());
    // Surfaces: each face's nodes (Abaqus C3D4 numbering) are a marked triangle.
    const int face_nodes[4][3] = {{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}};
    std::map<int32_t, std::set<Tri>> marked;
    for (size_t f = 0; f < d.tri_markers.size(); ++f)
        marked[d.tri_markers[f]].insert(sorted_tri(d.triangles[3 * f], d.triangles[3 * f + 1], d.triangles[3 * f + 2]));
    CHECK(marked.count(99) && marked.count(-3), "test mesh lacks the interface or negative marker");
    CHECK(inp.surfaces.size() == marked.size(), "%zu surfaces for %zu markers", inp.surfaces.size(), marked.size());
    for (const auto& [m, tris] : marked) {
        const std::string name = "MARKER_" + abaqus_id(m);
        auto it = inp.surfaces.find(name);
        CHECK(it != inp.surfaces.end(), "no surface %s", name.c_str());
        if (it == inp.surfaces.end()) continue;
        std::multiset<Tri> got;
        for (const auto& [set, side] : it->second) {
            CHECK(side.size() == 2 && side[0] == 'S' && side[1] >= '1' && side[1] <= '4', "face %s", side.c_str());
            const int k = side[1] - '1';
            CHECK(inp.elsets.count(set), "surface set %s undefined", set.c_str());
            if (!inp.elsets.count(set)) continue;
            for (long e : inp.elsets.at(set)) {
                const auto& el = inp.elements.at(e);
                got.insert(sorted_tri(static_cast<int32_t>(el[face_nodes[k][0] - 1]),
                                      static_cast<int32_t>(el[face_nodes[k][1] - 1]),
                                      static_cast<int32_t>(el[face_nodes[k][2] - 1])));
            }
        }
        CHECK(got == std::multiset<Tri>(tris.begin(), tris.end()), "surface %s: %zu faces for %zu triangles",
              name.c_str(), got.size(), tris.size());
    }
    // Without regions: one block, ELSET=ALL; a marked triangle that is no face is refused.
    bodt::MeshData plain = kuhn_block(1, 0);
    plain.regions.clear();
    bodt::write_abaqus(scratch("plain.inp"), plain);
    const Inp p2 = parse_inp(what, scratch("plain.inp"));
    CHECK(p2.elsets.size() == 1 && p2.elsets.count("ALL") && p2.elsets.at("ALL").size() == 6, "plain ELSET ALL");
    plain.triangles = {1, 2, 4};  // every Kuhn tet has vertex 0 or 7 on each face
    plain.tri_markers = {1};
    try {
        bodt::write_abaqus(scratch("plain.inp"), plain);
        CHECK(false, "a marked triangle that is no face was accepted");
    } catch (const bodt::Error& e) {
        CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT, "status %d", e.status());
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 1) g_dir = argv[1];
    mkdir(g_dir.c_str(), 0777);
    if (!little_endian_host()) {
        std::printf("test_io_vtu: big-endian host, skipped (the hand-written binaries assume little-endian)\n");
        return 0;
    }
    const CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_hand_written),
        cmocka_unit_test(test_array_names),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_malformed),
        cmocka_unit_test(test_abaqus),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
