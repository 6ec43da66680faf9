// test_io_meshb: white-box tests of the Medit binary .meshb reader and writer
// (src/io/medit_binary.cpp; links bodt_core).
//
//   round_trip        random meshes (base 0 and 1, with and without regions,
//                     vertex refs and edge refs) written and read back:
//                     coordinates bit for bit, tets, regions, triangles,
//                     markers, vertex refs, fixed vertices, corners, feature
//                     edges and their refs; the header is libMeshb's version
//                     2; Ridges lists every edge, Corners and
//                     RequiredVertices are there only when not empty
//   ascii_vs_binary   write_medit and write_medit_binary of one MeshData read
//                     back (read_medit, read_medit_binary) give the same data
//   versions          files of versions 1 to 4 in both byte orders, built
//                     here byte by byte by a writer independent of the
//                     library's, with keywords the reader must skip (an
//                     unknown code, Normals, empty Quadrilaterals), vertex
//                     refs, Corners, RequiredVertices, Edges (every one a
//                     feature edge, with its ref) and Ridges (checked, adds
//                     nothing), also Ridges before Edges
//   real_file         tests/data/meshb/box2_faces_freefem.meshb, written by
//                     FreeFem++ (libMeshb): the mesh of tests/data/box2.mesh
//                     plus its 48 boundary triangles, marked by box face;
//                     box2_faces_meshio_v3.meshb, the same written by meshio
//                     (version 3)
//   repeated          the sample split as meshio writes a mesh of several
//                     cell blocks: Tetrahedra, Triangles, Edges, Corners
//                     and RequiredVertices sections two or three times
//                     (some empty), in .mesh and in .meshb of versions 1
//                     to 4 in both byte orders: appended in file order,
//                     Ridges numbering the edges of every Edges section; a
//                     second Vertices section refused, naming both bytes;
//                     20000 one-record sections of each kind, each record
//                     in its place
//   malformed         40-odd broken files (truncations, counts, positions,
//                     indices, refs over 32 bits, NaN, Dimension, code,
//                     version, End ...): each an Error(BODT_ERR_IO) naming
//                     the path and the byte; the writer refuses refs that do
//                     not match the vertices or edges in number
//   truncations       the sample cut at every length: an error before End,
//                     the full mesh once End's code is there
//   fuzz              thousands of random byte changes: each file reads or
//                     gives Error(BODT_ERR_IO) with "byte" (run under
//                     AddressSanitizer, no crash, no hang, no huge allocation)
//
// Usage: test_io_meshb DATA_DIR SCRATCH_DIR (tests/data and a writable
// directory, created if missing).  BODT_TEST_VERBOSE=1 prints the
// messages of the malformed files.
#include "io/medit_binary.hpp"
#include "io/mesh_io.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "core_checks.hpp"

namespace {

std::string g_data_dir = "tests/data";
std::string g_scratch = "/tmp/bodt_test_io_meshb";

using Bytes = std::vector<unsigned char>;

// Deterministic 64-bit random numbers (xorshift64*), independent of the core.
struct Bits {
    uint64_t s;
    explicit Bits(uint64_t seed) : s(seed ? seed : 1) {}
    uint64_t next() {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        return s * 0x2545F4914F6CDD1DULL;
    }
    int below(int n) { return static_cast<int>(next() % static_cast<uint64_t>(n)); }
    // A finite double with random bits (any exponent, sign, subnormals).
    double any_double() {
        for (;;) {
            const uint64_t b = next();
            double x;
            std::memcpy(&x, &b, sizeof x);
            if (std::isfinite(x)) return x;
        }
    }
};

std::string scratch(const std::string& name) { return g_scratch + "/" + name; }

void write_bytes(const std::string& path, const Bytes& b) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) fail_msg("cannot write %s", path.c_str());
    if (!b.empty() && std::fwrite(b.data(), 1, b.size(), f) != b.size()) fail_msg("cannot write %s", path.c_str());
    std::fclose(f);
}

void write_text(const std::string& path, const std::string& text) {
    write_bytes(path, Bytes(text.begin(), text.end()));
}

Bytes read_bytes(const std::string& path) {
    Bytes b;
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) fail_msg("cannot read %s", path.c_str());
    int c;
    while ((c = std::fgetc(f)) != EOF) b.push_back(static_cast<unsigned char>(c));
    std::fclose(f);
    return b;
}

// ------------------------------------------------------------------ a .meshb
// writer of the test's own, byte by byte, following libMeshb's layout.

struct Gmf {
    bool big;
    int version;
    Bytes b;
    size_t pending = SIZE_MAX;  // offset of the position to fill with the next keyword's
    std::map<std::string, size_t> marks;

    Gmf(bool big_endian, int ver) : big(big_endian), version(ver) {
        i32(1);
        i32(ver);
    }
    int pos_size() const { return version >= 3 ? 8 : 4; }
    int int_size() const { return version == 4 ? 8 : 4; }
    int real_size() const { return version == 1 ? 4 : 8; }

    void raw(uint64_t v, int size) {
        for (int k = 0; k < size; ++k) {
            const int shift = big ? 8 * (size - 1 - k) : 8 * k;
            b.push_back(static_cast<unsigned char>((v >> shift) & 0xff));
        }
    }
    void put_at(size_t at, uint64_t v, int size) {
        for (int k = 0; k < size; ++k) {
            const int shift = big ? 8 * (size - 1 - k) : 8 * k;
            b[at + k] = static_cast<unsigned char>((v >> shift) & 0xff);
        }
    }
    void i32(int64_t v) { raw(static_cast<uint64_t>(v), 4); }
    void integer(int64_t v) { raw(static_cast<uint64_t>(v), int_size()); }
    void real(double x) {
        if (version == 1) {
            const float f = static_cast<float>(x);
            uint32_t bits;
            std::memcpy(&bits, &f, sizeof bits);
            raw(bits, 4);
        } else {
            uint64_t bits;
            std::memcpy(&bits, &x, sizeof bits);
            raw(bits, 8);
        }
    }
    void close_previous() {
        if (pending != SIZE_MAX) put_at(pending, b.size(), pos_size());
        pending = SIZE_MAX;
    }
    void keyword(int code, const std::string& mark) {
        close_previous();
        marks[mark] = b.size();
        i32(code);
        pending = b.size();
        raw(0, pos_size());
        marks[mark + ".data"] = b.size();
    }
    void end() {
        close_previous();
        marks["End"] = b.size();
        i32(54);
        raw(0, pos_size());
    }
    void mark(const std::string& name) { marks[name] = b.size(); }
};

// The mesh of the sample file, as read_medit_binary must return it.
bodt::MeshData sample_mesh() {
    bodt::MeshData d;
    d.base = 1;
    d.xyz = {0, 0, 0, 1.5, 0, 0, 0, -2.25, 0, 0.125, 0.5, 3, 0.25, 0.75, -1};
    d.tets = {1, 2, 3, 4, 1, 3, 2, 5};
    d.regions = {3, -4};
    d.triangles = {2, 3, 4, 1, 2, 5};
    d.tri_markers = {7, 8};
    d.vertex_refs = {0, 0, 0, 0, 99};
    d.corners = {1};
    d.fixed = {5};
    d.feature_edges = {1, 2, 2, 3, 3, 4};  // every edge; Ridges (3, 1) adds nothing
    d.edge_refs = {0, -7, 5};
    return d;
}

// The start of a .meshb of `version`: Dimension 3, then Vertices at `xyz`
// with vertex refs `refs` (their fields marked x<v> and vref<v>).
Gmf with_vertices(bool big, int version, const std::vector<double>& xyz, const std::vector<int32_t>& refs) {
    Gmf g(big, version);
    g.keyword(3, "Dimension");
    g.i32(3);  // 4 bytes in every version (libMeshb's GmfOpenMesh)
    g.keyword(4, "Vertices");
    g.integer(static_cast<int64_t>(refs.size()));
    for (size_t v = 0; v < refs.size(); ++v) {
        g.mark("x" + std::to_string(v + 1));
        for (size_t c = 0; c < 3; ++c) g.real(xyz[3 * v + c]);
        g.mark("vref" + std::to_string(v + 1));
        g.integer(refs[v]);
    }
    return g;
}

// The sample as a .meshb of `version`, in either byte order, with keywords
// to skip in between.  The marks name the offsets of keywords and fields.
Gmf sample_file(bool big, int version) {
    const bodt::MeshData d = sample_mesh();
    Gmf g = with_vertices(big, version, d.xyz, d.vertex_refs);
    g.keyword(200, "Unknown");  // not a libMeshb keyword: skipped by position
    for (int k = 0; k < 13; ++k) g.raw(0xA5, 1);
    g.keyword(8, "Tetrahedra");
    g.integer(2);
    for (int t = 0; t < 2; ++t) {
        g.mark("tet" + std::to_string(t + 1));
        for (int c = 0; c < 4; ++c) g.integer(d.tets[4 * t + c]);
        g.mark("tetref" + std::to_string(t + 1));
        g.integer(d.regions[t]);
    }
    g.keyword(60, "Normals");  // libMeshb's Normals (dr): skipped
    g.integer(1);
    for (int c = 0; c < 3; ++c) g.real(c == 0 ? 1.0 : 0.0);
    g.keyword(6, "Triangles");
    g.integer(2);
    for (int f = 0; f < 2; ++f) {
        g.mark("tri" + std::to_string(f + 1));
        for (int c = 0; c < 3; ++c) g.integer(d.triangles[3 * f + c]);
        g.integer(d.tri_markers[f]);
    }
    g.keyword(13, "Corners");
    g.integer(1);
    g.mark("corner1");
    g.integer(1);
    g.keyword(5, "Edges");
    g.integer(3);
    for (int e = 0; e < 3; ++e) {
        g.mark("edge" + std::to_string(e + 1));
        for (int c = 0; c < 2; ++c) g.integer(d.feature_edges[2 * e + c]);
        g.mark("edgeref" + std::to_string(e + 1));
        g.integer(d.edge_refs[e]);
    }
    g.keyword(7, "Quadrilaterals");  // empty: skipped
    g.integer(0);
    g.keyword(14, "Ridges");
    g.integer(2);
    g.mark("ridge1");
    g.integer(3);
    g.integer(1);
    g.keyword(15, "RequiredVertices");
    g.integer(1);
    g.mark("required1");
    g.integer(5);
    g.end();
    return g;
}

// ------------------------------------------------------------------ checks

std::vector<int32_t> shifted(const std::vector<int32_t>& v, int by) {
    std::vector<int32_t> r(v);
    for (int32_t& x : r) x += by;
    return r;
}

// Refs as a reader returns them: one per item, 0 for an empty list.
std::vector<int32_t> refs_or_zeros(const std::vector<int32_t>& refs, size_t n) {
    return refs.empty() ? std::vector<int32_t>(n, 0) : refs;
}

// `got` (read from a file, base 1) holds the data of `want` (any base).
void check_same(const char* what, const bodt::MeshData& got, const bodt::MeshData& want, bool bit_exact) {
    const int s = 1 - want.base;
    CHECK(got.base == 1, "base %d", got.base);
    CHECK(got.xyz.size() == want.xyz.size(), "%zu coordinates, expected %zu", got.xyz.size(), want.xyz.size());
    if (bit_exact)
        CHECK(std::memcmp(got.xyz.data(), want.xyz.data(), want.xyz.size() * sizeof(double)) == 0,
              "coordinates differ in their bits");
    else
        for (size_t k = 0; k < want.xyz.size(); ++k)
            CHECK(got.xyz[k] == want.xyz[k], "coordinate %zu: %.17g, expected %.17g", k, got.xyz[k], want.xyz[k]);
    CHECK(got.tets == shifted(want.tets, s), "tets differ");
    const std::vector<int32_t> regions =
        want.regions.empty() ? std::vector<int32_t>(want.tets.size() / 4, 0) : want.regions;
    CHECK(got.regions == regions, "regions differ");
    CHECK(got.triangles == shifted(want.triangles, s), "triangles differ");
    CHECK(got.tri_markers == want.tri_markers, "markers differ");
    const size_t nv = want.xyz.size() / 3, ne = want.feature_edges.size() / 2;
    CHECK(refs_or_zeros(got.vertex_refs, nv) == refs_or_zeros(want.vertex_refs, nv), "vertex refs differ");
    CHECK(got.fixed == shifted(want.fixed, s), "fixed vertices differ (%zu, expected %zu)", got.fixed.size(),
          want.fixed.size());
    CHECK(got.corners == shifted(want.corners, s), "corners differ (%zu, expected %zu)", got.corners.size(),
          want.corners.size());
    CHECK(got.feature_edges == shifted(want.feature_edges, s), "feature edges differ (%zu, expected %zu)",
          got.feature_edges.size(), want.feature_edges.size());
    CHECK(refs_or_zeros(got.edge_refs, ne) == refs_or_zeros(want.edge_refs, ne), "edge refs differ");
}

// A random mesh: random bits for coordinates, random (not necessarily valid)
// tets; the reader and writer check indices, not geometry.  `refs`: vertex
// and edge refs (any int32), else none.
bodt::MeshData random_mesh(Bits& r, int base, bool regions, bool refs) {
    bodt::MeshData d;
    d.base = base;
    const int nv = 5 + r.below(200), nt = 1 + r.below(300), nf = r.below(100), nfix = r.below(20), ne = r.below(30);
    const int nc = r.below(10);
    for (int k = 0; k < 3 * nv; ++k) d.xyz.push_back(r.below(4) == 0 ? r.any_double() : (r.below(2001) - 1000) / 7.0);
    if (refs)
        for (int v = 0; v < nv; ++v) d.vertex_refs.push_back(r.below(3) == 0 ? static_cast<int32_t>(r.next()) : 0);
    auto vertex = [&] { return static_cast<int32_t>(base + r.below(nv)); };
    for (int t = 0; t < nt; ++t) {
        for (int c = 0; c < 4; ++c) d.tets.push_back(vertex());
        if (regions) d.regions.push_back(static_cast<int32_t>(r.next()));  // any int32, negative too
    }
    for (int f = 0; f < nf; ++f) {
        for (int c = 0; c < 3; ++c) d.triangles.push_back(vertex());
        d.tri_markers.push_back(r.below(9) - 2);
    }
    for (int k = 0; k < nfix; ++k) d.fixed.push_back(vertex());
    for (int k = 0; k < nc; ++k) d.corners.push_back(vertex());
    for (int k = 0; k < 2 * ne; ++k) d.feature_edges.push_back(vertex());
    if (refs)
        for (int e = 0; e < ne; ++e) d.edge_refs.push_back(static_cast<int32_t>(r.next()));
    return d;
}

// The payloads of the keywords of a little-endian file of version 1 or 2
// (32-bit positions), as int32 words after each keyword's header, by code.
std::map<int32_t, std::vector<int32_t>> keyword_words(const Bytes& b) {
    auto word = [&](size_t at) {
        int32_t v;
        std::memcpy(&v, b.data() + at, 4);  // the test machine is little-endian, as in test_versions
        return v;
    };
    std::map<int32_t, std::vector<int32_t>> words;
    for (size_t at = 8; at + 4 <= b.size();) {
        const int32_t code = word(at);
        if (code == 54 || at + 8 > b.size()) break;
        const size_t next = static_cast<size_t>(word(at + 4));
        if (next <= at || next > b.size()) break;
        std::vector<int32_t>& w = words[code];
        for (size_t p = at + 8; p + 4 <= next; p += 4) w.push_back(word(p));
        at = next;
    }
    return words;
}

// Runs `f`, which must throw Error(BODT_ERR_IO) with `path`, "byte" and
// `expect` in its message; returns the message.
std::string expect_io_error(const char* what, const std::string& path, const std::function<void()>& f,
                            const std::string& expect) {
    try {
        f();
    } catch (const bodt::Error& e) {
        const std::string m = e.what();
        CHECK(e.status() == BODT_ERR_IO, "status %d, expected BODT_ERR_IO (%s)", e.status(), m.c_str());
        CHECK(m.find(path) != std::string::npos, "the message does not name the file: %s", m.c_str());
        CHECK(m.find("byte") != std::string::npos, "the message does not name the byte: %s", m.c_str());
        CHECK(m.find(expect) != std::string::npos, "the message lacks '%s': %s", expect.c_str(), m.c_str());
        return m;
    } catch (const std::exception& e) {
        CHECK(false, "not a bodt::Error: %s", e.what());
    }
    CHECK(false, "no error (expected '%s')", expect.c_str());
    return "";
}

// ------------------------------------------------------------------ tests

void test_round_trip(void**) {
    const char* what = "round_trip";
    Bits r(12345);
    for (int iter = 0; iter < 24; ++iter) {
        bodt::MeshData d = random_mesh(r, iter % 2, iter % 3 != 0, iter % 4 != 0);
        if (iter == 5) d.corners.clear();
        if (iter == 6) d.fixed.clear(), d.feature_edges.clear(), d.edge_refs.clear();
        const std::string path = scratch("round_trip.meshb");
        bodt::write_medit_binary(path, d);
        const Bytes b = read_bytes(path);
        CHECK(b.size() > 20, "%zu bytes", b.size());
        // Header: code 1, version 2, little-endian; Dimension 3 at byte 8,
        // next keyword at 20.
        const unsigned char head[20] = {1, 0, 0, 0, 2, 0, 0, 0, 3, 0, 0, 0, 20, 0, 0, 0, 3, 0, 0, 0};
        CHECK(std::memcmp(b.data(), head, sizeof head) == 0, "header bytes");
        // End with position 0 closes the file.
        const unsigned char tail[8] = {54, 0, 0, 0, 0, 0, 0, 0};
        CHECK(std::memcmp(b.data() + b.size() - 8, tail, 8) == 0, "End bytes");
        check_same(what, bodt::read_medit_binary(path), d, true);
        // Ridges names every edge (1..n), for tools that read only ridges as
        // feature lines; empty sections are left out.
        const auto words = keyword_words(b);
        const int32_t ne = static_cast<int32_t>(d.feature_edges.size() / 2);
        CHECK(words.count(5) == (ne > 0) && words.count(14) == (ne > 0), "Edges and Ridges written for %d edges", ne);
        if (ne > 0) {
            const std::vector<int32_t>& ridges = words.at(14);
            CHECK(ridges.size() == static_cast<size_t>(ne) + 1 && ridges[0] == ne, "Ridges count");
            for (int32_t e = 1; e < static_cast<int32_t>(ridges.size()); ++e)
                CHECK(ridges[static_cast<size_t>(e)] == e, "ridge %d names edge %d", e, ridges[static_cast<size_t>(e)]);
        }
        CHECK(words.count(13) == !d.corners.empty(), "Corners written for %zu corners", d.corners.size());
        CHECK(words.count(15) == !d.fixed.empty(), "RequiredVertices written for %zu", d.fixed.size());
    }
    // The empty sections of a minimal mesh.
    bodt::MeshData one;
    one.base = 0;
    one.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    one.tets = {0, 1, 2, 3};
    bodt::write_medit_binary(scratch("one.meshb"), one);
    check_same(what, bodt::read_medit_binary(scratch("one.meshb")), one, true);
}

void test_ascii_vs_binary(void**) {
    const char* what = "ascii_vs_binary";
    Bits r(777);
    for (int iter = 0; iter < 8; ++iter) {
        const bodt::MeshData d = random_mesh(r, iter % 2, true, iter % 4 != 1);
        bodt::write_medit(scratch("same.mesh"), d);
        bodt::write_medit_binary(scratch("same.meshb"), d);
        const bodt::MeshData a = bodt::read_medit(scratch("same.mesh"));
        const bodt::MeshData b = bodt::read_medit_binary(scratch("same.meshb"));
        check_same(what, b, a, true);
        check_same(what, a, d, true);
    }
}

// The file build(big_endian, version) gives, for versions 1 to 4 in both
// byte orders, written as <stem><version><le|be>.meshb: each must read as
// `want`.
template <class Build>
void check_every_layout(const char* what, const std::string& stem, Build build, const bodt::MeshData& want) {
    for (int version = 1; version <= 4; ++version)
        for (int big = 0; big < 2; ++big) {
            const std::string path = scratch(stem + std::to_string(version) + (big ? "be" : "le") + ".meshb");
            write_bytes(path, build(big != 0, version).b);
            bodt::MeshData got;
            try {
                got = bodt::read_medit_binary(path);
            } catch (const bodt::Error& e) {
                CHECK(false, "version %d %s: %s", version, big ? "big-endian" : "little-endian", e.what());
            }
            check_same(what, got, want, true);
        }
}

void test_versions(void**) {
    const char* what = "versions";
    check_every_layout(
        what, "v",
        [&](bool big, int version) {
            Gmf g = sample_file(big, version);
            CHECK(g.b[0] == (big ? 0 : 1) && g.b[3] == (big ? 1 : 0), "code bytes");
            return g;
        },
        sample_mesh());
    // Version 1 rounds to float: 0.1 comes back as (double)0.1f.
    bodt::MeshData d = sample_mesh();
    std::vector<double> xyz = d.xyz;
    xyz[4] = 0.1;  // y of vertex 2
    Gmf g = with_vertices(false, 1, xyz, std::vector<int32_t>(5, 0));
    g.keyword(8, "Tetrahedra");
    g.integer(1);
    for (int x : {1, 2, 3, 4, 6}) g.integer(x);
    g.end();
    write_bytes(scratch("v1float.meshb"), g.b);
    const bodt::MeshData got = bodt::read_medit_binary(scratch("v1float.meshb"));
    CHECK(got.xyz[4] == static_cast<double>(0.1f), "0.1 in version 1: %.17g", got.xyz[4]);
    CHECK(got.regions.size() == 1 && got.regions[0] == 6, "region");
    CHECK(got.triangles.empty() && got.fixed.empty() && got.corners.empty() && got.feature_edges.empty() &&
              got.edge_refs.empty(),
          "no other sections");
    CHECK(got.vertex_refs == std::vector<int32_t>(5, 0), "vertex refs");

    // Ridges before Edges: its indices are checked against every edge of
    // the file, not only those read so far.
    g = with_vertices(true, 3, d.xyz, {0, 1, 2, 3, 4});
    g.keyword(14, "Ridges");
    g.integer(1);
    g.integer(2);
    g.keyword(8, "Tetrahedra");
    g.integer(1);
    for (int x : {1, 2, 3, 4, 6}) g.integer(x);
    g.keyword(5, "Edges");
    g.integer(2);
    for (int x : {1, 2, 8, 4, 5, -9}) g.integer(x);
    g.end();
    write_bytes(scratch("ridges_first.meshb"), g.b);
    const bodt::MeshData rf = bodt::read_medit_binary(scratch("ridges_first.meshb"));
    CHECK(rf.feature_edges == (std::vector<int32_t>{1, 2, 4, 5}) && rf.edge_refs == (std::vector<int32_t>{8, -9}),
          "edges after Ridges");
    CHECK(rf.vertex_refs == (std::vector<int32_t>{0, 1, 2, 3, 4}), "vertex refs");
}

void test_real_file(void**) {
    const char* what = "real_file";
    const bodt::MeshData ascii = bodt::read_medit(g_data_dir + "/box2.mesh");
    const bodt::MeshData ff = bodt::read_medit_binary(g_data_dir + "/meshb/box2_faces_freefem.meshb");
    CHECK(ff.xyz == ascii.xyz, "coordinates differ from box2.mesh");
    CHECK(ff.tets == ascii.tets, "tets differ from box2.mesh");
    CHECK(ff.regions == ascii.regions, "regions differ from box2.mesh");
    CHECK(ff.tets.size() == 4 * 48 && ff.xyz.size() == 3 * 27, "27 vertices, 48 tets");
    CHECK(ff.tri_markers.size() == 48 && ff.triangles.size() == 3 * 48, "%zu triangles", ff.tri_markers.size());
    int per_marker[7] = {0, 0, 0, 0, 0, 0, 0};
    for (size_t f = 0; f < ff.tri_markers.size(); ++f) {
        const int m = ff.tri_markers[f];
        CHECK(m >= 1 && m <= 6, "marker %d", m);
        ++per_marker[m];
        // Marker 1 + 2 * axis + side: the face of the box [0, 2]^3 at x_axis = 2 * side.
        const int axis = (m - 1) / 2;
        const double plane = 2.0 * ((m - 1) % 2);
        for (int c = 0; c < 3; ++c) {
            const int32_t v = ff.triangles[3 * f + c];
            CHECK(v >= 1 && v <= 27, "vertex %d", v);
            CHECK(ff.xyz[3 * (v - 1) + axis] == plane, "triangle %zu (marker %d) is off its plane", f, m);
        }
    }
    for (int m = 1; m <= 6; ++m) CHECK(per_marker[m] == 8, "marker %d on %d triangles, expected 8", m, per_marker[m]);
    CHECK(ff.fixed.empty() && ff.feature_edges.empty(), "no fixed vertices or feature edges");
    // The same mesh written by meshio (version 3: 64-bit positions), from a
    // file of this library: the same data, triangles as sets (FreeFem++
    // reorients some).
    const bodt::MeshData mio = bodt::read_medit_binary(g_data_dir + "/meshb/box2_faces_meshio_v3.meshb");
    CHECK(mio.xyz == ascii.xyz && mio.tets == ascii.tets && mio.regions == ascii.regions, "meshio: mesh differs");
    auto faces = [](const bodt::MeshData& d) {
        std::vector<std::array<int32_t, 4>> f;
        for (size_t k = 0; k < d.tri_markers.size(); ++k) {
            std::array<int32_t, 4> t = {d.triangles[3 * k], d.triangles[3 * k + 1], d.triangles[3 * k + 2],
                                        d.tri_markers[k]};
            std::sort(t.begin(), t.begin() + 3);
            f.push_back(t);
        }
        std::sort(f.begin(), f.end());
        return f;
    };
    CHECK(faces(mio) == faces(ff), "meshio and FreeFem++ files differ in their triangles");
    // Written back by the library, it reads the same.
    bodt::write_medit_binary(scratch("ff_again.meshb"), ff);
    check_same(what, bodt::read_medit_binary(scratch("ff_again.meshb")), ff, true);
}

// One section of a Medit file as both writers below write it: its records'
// ints, `fields` per record.
struct Section {
    int code;
    const char* name;
    int fields;
    std::vector<int64_t> ints;
};

// The sample mesh as meshio writes a mesh of several cell blocks: a section
// per block, each kind two or three times, some empty; ridge 3 is in the
// second Edges section.  Read, it is the sample with one more corner (4)
// and fixed vertex (2).
std::vector<Section> repeated_sections() {
    return {
        {8, "Tetrahedra", 5, {1, 2, 3, 4, 3}},
        {6, "Triangles", 4, {2, 3, 4, 7}},
        {5, "Edges", 3, {1, 2, 0}},
        {8, "Tetrahedra", 5, {1, 3, 2, 5, -4}},
        {13, "Corners", 1, {1}},
        {15, "RequiredVertices", 1, {5}},
        {6, "Triangles", 4, {1, 2, 5, 8}},
        {14, "Ridges", 1, {3, 1}},
        {5, "Edges", 3, {2, 3, -7, 3, 4, 5}},
        {13, "Corners", 1, {}},
        {8, "Tetrahedra", 5, {}},
        {13, "Corners", 1, {4}},
        {15, "RequiredVertices", 1, {2}},
    };
}

bodt::MeshData repeated_mesh() {
    bodt::MeshData d = sample_mesh();
    d.corners = {1, 4};
    d.fixed = {5, 2};
    return d;
}

// The sample's vertices, then `sections`, as a .mesh.
std::string medit_text(const std::vector<Section>& sections) {
    const bodt::MeshData d = sample_mesh();
    std::string t = "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n";
    char line[128];
    for (int v = 0; v < 5; ++v) {
        std::snprintf(line, sizeof line, "%.17g %.17g %.17g %d\n", d.xyz[3 * v], d.xyz[3 * v + 1], d.xyz[3 * v + 2],
                      d.vertex_refs[v]);
        t += line;
    }
    for (const Section& s : sections) {
        t += std::string(s.name) + "\n" + std::to_string(s.ints.size() / s.fields) + "\n";
        for (size_t k = 0; k < s.ints.size(); ++k)
            t += std::to_string(s.ints[k]) + ((k + 1) % s.fields == 0 ? "\n" : " ");
    }
    return t + "End\n";
}

// The same as a .meshb.
Gmf medit_binary(const std::vector<Section>& sections, bool big, int version) {
    const bodt::MeshData d = sample_mesh();
    Gmf g = with_vertices(big, version, d.xyz, d.vertex_refs);
    for (const Section& s : sections) {
        g.keyword(s.code, s.name);
        g.integer(static_cast<int64_t>(s.ints.size()) / s.fields);
        for (int64_t x : s.ints) g.integer(x);
    }
    g.end();
    return g;
}

void test_repeated(void**) {
    const char* what = "repeated";
    const std::vector<Section> sections = repeated_sections();
    const std::string text = scratch("repeated.mesh");
    write_text(text, medit_text(sections));
    check_same(what, bodt::read_medit(text), repeated_mesh(), true);
    check_every_layout(
        what, "repeated_v", [&](bool big, int version) { return medit_binary(sections, big, version); },
        repeated_mesh());

    // A second Vertices keyword: refused at its byte, naming the first's.
    Gmf g = medit_binary({sections[0]}, false, 2);
    g.b.resize(g.marks.at("End"));              // End cut off,
    g.pending = g.marks.at("Tetrahedra") + 4;  // Tetrahedra's next position to fill again
    g.keyword(4, "Vertices again");
    g.integer(0);
    g.end();
    const std::string path = scratch("two_vertices.meshb");
    write_bytes(path, g.b);
    expect_io_error(
        what, path, [&] { bodt::read_medit_binary(path); },
        "byte " + std::to_string(g.marks.at("Vertices again")) + ": a second Vertices section (the first at byte " +
            std::to_string(g.marks.at("Vertices")) + ")");

    // Many small sections, each record in its place.
    std::vector<Section> small;
    const int many = 20000;
    for (int k = 0; k < many; ++k) {
        small.push_back({8, "Tetrahedra", 5, {1, 2, 3, 4, k}});
        small.push_back({6, "Triangles", 4, {2, 3, 4, k}});
        small.push_back({5, "Edges", 3, {1, 2, k}});
        small.push_back({13, "Corners", 1, {1 + k % 5}});
    }
    for (bool binary : {true, false}) {
        const std::string file = scratch(binary ? "many.meshb" : "many.mesh");
        if (binary)
            write_bytes(file, medit_binary(small, false, 2).b);
        else
            write_text(file, medit_text(small));
        const bodt::MeshData d = binary ? bodt::read_medit_binary(file) : bodt::read_medit(file);
        const size_t n = static_cast<size_t>(many);
        CHECK(d.regions.size() == n && d.tets.size() == 4 * n && d.tri_markers.size() == n &&
                  d.edge_refs.size() == n && d.corners.size() == n,
              "%zu tets, %zu triangles, %zu edges, %zu corners", d.regions.size(), d.tri_markers.size(),
              d.edge_refs.size(), d.corners.size());
        for (int k = 0; k < many; ++k)
            CHECK(d.regions[k] == k && d.tri_markers[k] == k && d.edge_refs[k] == k && d.corners[k] == 1 + k % 5,
                  "record %d out of order", k);
    }
}

// A broken copy of a sample file.
struct Broken {
    const char* name;
    bool big;
    int version;
    std::function<void(Gmf&)> mutate;
    const char* expect;  // a part of the message
};

void test_malformed(void**) {
    const char* what = "malformed";
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    auto set_int = [](Gmf& g, const std::string& mark, int64_t v) {
        g.put_at(g.marks.at(mark), static_cast<uint64_t>(v), g.int_size());
    };
    auto set_i32 = [](Gmf& g, size_t at, int64_t v) { g.put_at(at, static_cast<uint64_t>(v), 4); };
    auto set_next = [](Gmf& g, const std::string& kw, int64_t v) {
        g.put_at(g.marks.at(kw) + 4, static_cast<uint64_t>(v), g.pos_size());
    };
    auto set_real = [](Gmf& g, const std::string& mark, int c, double x) {
        uint64_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        g.put_at(g.marks.at(mark) + 8 * c, bits, 8);
    };
    auto cut = [](Gmf& g, size_t n) { g.b.resize(n); };
    const std::vector<Broken> cases = {
        {"empty file", false, 2, [&](Gmf& g) { cut(g, 0); }, "truncated"},
        {"cut in the header", false, 2, [&](Gmf& g) { cut(g, 6); }, "truncated"},
        {"cut in Dimension", false, 2, [&](Gmf& g) { cut(g, 14); }, "truncated"},
        {"cut in the vertices", false, 2, [&](Gmf& g) { cut(g, g.marks.at("x3") + 5); }, "past the end"},
        {"cut in a keyword code", false, 3, [&](Gmf& g) { cut(g, g.marks.at("Tetrahedra") + 2); }, "truncated"},
        {"cut in a position", true, 3, [&](Gmf& g) { cut(g, g.marks.at("Triangles") + 9); }, "truncated"},
        {"cut before End", false, 2, [&](Gmf& g) { cut(g, g.marks.at("End")); }, "no End"},
        {"huge vertex count", false, 2, [&](Gmf& g) { set_int(g, "Vertices.data", INT32_MAX); }, "does not fit"},
        {"huge count, version 4", false, 4, [&](Gmf& g) { set_int(g, "Tetrahedra.data", INT64_MAX); }, "does not fit"},
        {"huge count, big-endian", true, 2, [&](Gmf& g) { set_int(g, "Triangles.data", 0x40000000); }, "does not fit"},
        {"negative count", false, 2, [&](Gmf& g) { set_int(g, "Tetrahedra.data", -1); }, "negative count"},
        {"count one too many", false, 2, [&](Gmf& g) { set_int(g, "Ridges.data", 3); }, "does not fit"},
        {"backward next position", false, 2, [&](Gmf& g) { set_next(g, "Tetrahedra", 8); }, "does not move forward"},
        {"next position on itself", false, 3,
         [&](Gmf& g) { set_next(g, "Triangles", static_cast<int64_t>(g.marks.at("Triangles"))); },
         "does not move forward"},
        {"next position negative", false, 2, [&](Gmf& g) { set_next(g, "Vertices", -100); }, "does not move forward"},
        {"next position past the end", false, 2,
         [&](Gmf& g) { set_next(g, "Corners", static_cast<int64_t>(g.b.size()) + 1); }, "past the end"},
        {"next position 2^40", true, 4, [&](Gmf& g) { set_next(g, "Unknown", int64_t{1} << 40); }, "past the end"},
        {"next position 0 before End", false, 2, [&](Gmf& g) { set_next(g, "Edges", 0); }, "no End"},
        {"tet vertex past the last", false, 2, [&](Gmf& g) { set_int(g, "tet2", 6); }, "out of range"},
        {"tet vertex 0", true, 1, [&](Gmf& g) { set_int(g, "tet1", 0); }, "out of range"},
        {"triangle vertex negative", false, 2, [&](Gmf& g) { set_int(g, "tri2", -3); }, "out of range"},
        {"corner out of range", false, 4, [&](Gmf& g) { set_int(g, "corner1", int64_t{1} << 33); }, "out of range"},
        {"ridge out of range", false, 2, [&](Gmf& g) { set_int(g, "ridge1", 4); }, "ridge 4"},
        {"ridge 0", true, 4, [&](Gmf& g) { set_int(g, "ridge1", 0); }, "ridge 0"},
        {"edge vertex past the last", false, 2, [&](Gmf& g) { set_int(g, "edge3", 6); }, "edge vertex 6"},
        {"edge vertex 0", true, 3, [&](Gmf& g) { set_int(g, "edge2", 0); }, "edge vertex 0"},
        {"required vertex out of range", false, 1, [&](Gmf& g) { set_int(g, "required1", 7); }, "RequiredVertices 7"},
        {"vertex reference over 32 bits", false, 4, [&](Gmf& g) { set_int(g, "vref3", int64_t{1} << 35); },
         "vertex reference"},
        {"negative vertex reference over 32 bits", true, 4,
         [&](Gmf& g) { set_int(g, "vref5", -(int64_t{1} << 40)); }, "does not fit in 32 bits"},
        {"edge reference over 32 bits", true, 4, [&](Gmf& g) { set_int(g, "edgeref2", int64_t{1} << 32); },
         "edge reference"},
        {"tet reference over 32 bits", false, 4, [&](Gmf& g) { set_int(g, "tetref2", int64_t{1} << 40); }, "32 bits"},
        {"NaN coordinate", false, 2, [&](Gmf& g) { set_real(g, "x2", 1, nan); }, "not finite"},
        {"infinite coordinate", false, 3, [&](Gmf& g) { set_real(g, "x5", 2, -inf); }, "not finite"},
        {"Dimension 2", false, 2, [&](Gmf& g) { set_i32(g, g.marks.at("Dimension.data"), 2); }, "Dimension 2"},
        {"first keyword not Dimension", false, 2, [&](Gmf& g) { set_i32(g, 8, 4); }, "not Dimension"},
        {"bad code", false, 2, [&](Gmf& g) { set_i32(g, 0, 2); }, "not a Medit binary mesh"},
        {"ASCII mesh named .meshb", false, 2,
         [&](Gmf& g) {
             const char text[] = "MeshVersionFormatted 2\nDimension 3\nVertices\n0\nEnd\n";
             g.b.assign(text, text + sizeof text - 1);
         },
         "not a Medit binary mesh"},
        {"version 5", false, 2, [&](Gmf& g) { set_i32(g, 4, 5); }, "version 5"},
        {"version 0, big-endian", true, 2, [&](Gmf& g) { set_i32(g, 4, 0); }, "version 0"},
        {"no Tetrahedra", false, 2, [&](Gmf& g) { set_i32(g, g.marks.at("Tetrahedra"), 201); }, "no Tetrahedra"},
        {"no Vertices", false, 2, [&](Gmf& g) { set_i32(g, g.marks.at("Vertices"), 201); }, "no Vertices"},
        {"two Vertices sections", false, 2, [&](Gmf& g) { set_i32(g, g.marks.at("Unknown"), 4); },
         "second Vertices"},
        {"Dimension with no room for its value", false, 2,
         [&](Gmf& g) { set_next(g, "Dimension", static_cast<int64_t>(g.marks.at("Dimension.data")) + 2); }, "no room"},
        {"Ridges with no room for its count", true, 4,
         [&](Gmf& g) {
             // Ridges' next position 2 bytes after its header: the rest of
             // the file is shifted so that the chain goes on from there.
             const size_t data = g.marks.at("Ridges.data");
             set_next(g, "Ridges", static_cast<int64_t>(data) + 2);
             Bytes tail(g.b.begin() + static_cast<std::ptrdiff_t>(g.marks.at("RequiredVertices")), g.b.end());
             g.b.resize(data + 2);
             g.b.insert(g.b.end(), tail.begin(), tail.end());
             // RequiredVertices' position moved with it.
             const size_t rv = data + 2;
             g.put_at(rv + 4, rv + 4 + 8 + 8 + 8, 8);
         },
         "no room"},
    };
    for (const Broken& c : cases) {
        Gmf g = sample_file(c.big, c.version);
        c.mutate(g);
        const std::string path = scratch("broken.meshb");
        write_bytes(path, g.b);
        const std::string m = expect_io_error(
            c.name, path, [&] { bodt::read_medit_binary(path); }, c.expect);
        if (std::getenv("BODT_TEST_VERBOSE")) std::printf("%-36s %s\n", c.name, m.c_str());
    }
    // A missing file: an I/O error naming it.
    const std::string missing = scratch("no_such_file.meshb");
    std::remove(missing.c_str());
    try {
        bodt::read_medit_binary(missing);
        CHECK(false, "no error for a missing file");
    } catch (const bodt::Error& e) {
        CHECK(e.status() == BODT_ERR_IO && std::string(e.what()).find(missing) != std::string::npos, "%s", e.what());
    }
    // The writer refuses what the reader would refuse.
    auto refused = [&](const bodt::MeshData& d, const char* expect) {
        try {
            bodt::write_medit_binary(scratch("refused.meshb"), d);
            CHECK(false, "written, expected an error with '%s'", expect);
        } catch (const bodt::Error& e) {
            CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT && std::strstr(e.what(), expect), "%s", e.what());
        }
    };
    bodt::MeshData bad = sample_mesh();
    bad.tets[5] = 6;
    refused(bad, "vertex index 6");
    bad = sample_mesh();
    bad.base = 0;  // index 5 is then past the last vertex
    refused(bad, "vertex index 5");
    bad = sample_mesh();
    bad.tri_markers.pop_back();
    refused(bad, "do not match");
    bad = sample_mesh();
    bad.vertex_refs.pop_back();
    refused(bad, "do not match");
    bad = sample_mesh();
    bad.edge_refs.push_back(1);
    refused(bad, "do not match");
    bad = sample_mesh();
    bad.corners.push_back(6);
    refused(bad, "vertex index 6");
    // An unwritable path.
    try {
        bodt::write_medit_binary(scratch("no_dir/x.meshb"), sample_mesh());
        CHECK(false, "no error for an unwritable path");
    } catch (const bodt::Error& e) {
        CHECK(e.status() == BODT_ERR_IO, "%s", e.what());
    }
}

void test_truncations(void**) {
    const char* what = "truncations";
    for (int version = 1; version <= 4; ++version) {
        const Gmf full = sample_file(version % 2 == 0, version);
        const size_t end_at = full.marks.at("End");
        const std::string path = scratch("cut.meshb");
        for (size_t n = 0; n < full.b.size(); ++n) {
            Bytes b(full.b.begin(), full.b.begin() + static_cast<std::ptrdiff_t>(n));
            write_bytes(path, b);
            if (n < end_at + 4) {
                expect_io_error(
                    what, path, [&] { bodt::read_medit_binary(path); }, "");
            } else {
                // End's code is there: the position after it (0) is not needed.
                check_same(what, bodt::read_medit_binary(path), sample_mesh(), true);
            }
        }
    }
}

void test_fuzz(void**) {
    const char* what = "fuzz";
    Bits r(2024);
    int ok = 0, errors = 0;
    const std::string path = scratch("fuzz.meshb");
    for (int iter = 0; iter < 4000; ++iter) {
        const int version = 1 + iter % 4;
        Gmf g = sample_file(iter % 8 >= 4, version);
        const int changes = 1 + r.below(4);
        for (int k = 0; k < changes && !g.b.empty(); ++k) {
            const size_t at = static_cast<size_t>(r.below(static_cast<int>(g.b.size())));
            switch (r.below(4)) {
                case 0:
                    g.b[at] = static_cast<unsigned char>(r.next());
                    break;
                case 1:
                    g.b[at] ^= static_cast<unsigned char>(1u << r.below(8));
                    break;
                case 2:
                    g.b[at] = r.below(2) ? 0xff : 0;
                    break;
                default:
                    g.b.resize(at);
                    break;
            }
        }
        write_bytes(path, g.b);
        try {
            const bodt::MeshData d = bodt::read_medit_binary(path);
            const int64_t nv = static_cast<int64_t>(d.xyz.size() / 3);
            for (int32_t v : d.tets)
                CHECK(v >= 1 && v <= nv, "iteration %d: vertex %d of %lld", iter, v, (long long)nv);
            for (double x : d.xyz) CHECK(std::isfinite(x), "iteration %d: coordinate %g", iter, x);
            ++ok;
        } catch (const bodt::Error& e) {
            const std::string m = e.what();
            CHECK(e.status() == BODT_ERR_IO, "iteration %d: status %d: %s", iter, e.status(), m.c_str());
            CHECK(m.find("byte") != std::string::npos && m.find(path) != std::string::npos, "iteration %d: %s", iter,
                  m.c_str());
            ++errors;
        }
    }
    CHECK(ok > 0 && errors > 0, "%d read, %d errors", ok, errors);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 1) g_data_dir = argv[1];
    if (argc > 2) g_scratch = argv[2];
    mkdir(g_scratch.c_str(), 0777);  // may exist
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip), cmocka_unit_test(test_ascii_vs_binary), cmocka_unit_test(test_versions),
        cmocka_unit_test(test_real_file),  cmocka_unit_test(test_repeated),        cmocka_unit_test(test_malformed),
        cmocka_unit_test(test_truncations),
        cmocka_unit_test(test_fuzz),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
