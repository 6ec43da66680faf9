// test_io_gmsh: the Gmsh .msh reader and writer (src/io/gmsh.cpp), white box.
//
//   test_io_gmsh <data dir> <scratch dir>
//
// <data dir> is tests/data (the Gmsh-made files are in its gmsh/ folder),
// <scratch dir> an existing or creatable directory for the files written here.
//
//   round_trip      a 27-vertex, 48-tet mesh with odd coordinates, regions
//                   (0, 1, 2, -3 interleaved), face markers (0 among them),
//                   feature edges with refs (20, 0, 20, -4: two runs of one
//                   ref) and fixed vertices, written as 4.1 / 2.2, ASCII /
//                   binary, from base 0 and base 1, read back: coordinates
//                   bit-exact, tets, regions, the nonzero markers, feature
//                   edges in their order with their refs, fixed vertices
//                   unchanged; vertex refs and corners are not written;
//                   without edge refs the edges come back with ref 0 and
//                   the file has no physical curve
//   gmsh_files      the four files Gmsh made from tests/data/gmsh/box.geo:
//                   23 vertices, 48 tets, 24 in region 1 and 24 in region
//                   2 of volume 1 each, 8 faces with marker 10 on z = 0, one
//                   feature edge (0,0,0)-(0,0,1) with ref 20, the origin
//                   fixed; the four read the same
//   entity_regions  the two files Gmsh made from box_nophysical.geo (box.geo
//                   without physical groups: every element saved, tagged
//                   with its entity only), 4.1 and 2.2: each tet's region
//                   is its volume's entity tag, 24 tets and volume 1 in
//                   regions 1 and 2, x <= 1 in region 1; each
//                   triangle's marker is its surface's entity tag (11
//                   surfaces, 4 triangles each, the one between the cubes
//                   at x = 1 one of them); the 20 curves' lines are
//                   feature edges with ref 0; no fixed vertex
//   sparse_tags     hand-written files with sparse, unordered node tags,
//                   parametric nodes, skipped quads, unknown 2-D types,
//                   other sections: renumbered in file order, base 0; lines
//                   with and without a physical tag are feature edges (ref
//                   the tag, else 0); a 2.2 line listed for two physical
//                   groups is one edge with the first group's tag
//   model           what the reader keeps beyond the arrays (GmshModel):
//                   box41.msh's names, 45 entities with physical tags,
//                   bounding entities and boxes, the entity of each
//                   element and node; box22.msh's entities from its
//                   elements; box_nophysical41.msh's entity tags as values
//   order           a hand-written 4.1 file with node tags 1..5 in blocks
//                   out of order (vertex i is node i + 1, base 1), element
//                   tags out of order (arrays in tag order), an entity tag
//                   0 and an entity only a node block and elements name;
//                   written in the four variants and read back the same
//   layout_*        the writer's entity recovery (gmsh_layout.hpp): as read,
//                   every element and node where the file had it; after a
//                   simulated step (edge splits with made vertices and
//                   parents, tets from their origins, new markers, refs,
//                   regions and fixed vertices) each element in the entity
//                   it lies in or a new one with a named physical group;
//                   without physical groups, entity tags as values and
//                   physical tag 0 once a group exists; a single surface
//                   without a physical group gets its unmarked faces back
//   malformed       many corruptions of those files (also of $Entities and
//                   $PhysicalNames): each an Error with BODT_ERR_IO naming
//                   the file and a line or byte offset
//   bad_write       the writer refuses a bad version, bad indices and edge
//                   refs that do not match the edges in number
#include "io/gmsh.hpp"
#include "io/gmsh_layout.hpp"
#include "io/gmsh_model.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core_checks.hpp"
#include "file_text.hpp"

using bodt::Error;
using bodt::MeshData;

namespace {

using io_test::read_text;
using io_test::write_text;

std::string g_data, g_scratch;

std::string scratch(const std::string& name) { return g_scratch + "/" + name; }
std::string data(const std::string& name) { return g_data + "/gmsh/" + name; }

// The mesh in `path`; an error reading it fails the case.
MeshData read_or_fail(const char* what, const std::string& path) {
    try {
        return bodt::read_gmsh(path);
    } catch (const Error& e) {
        CHECK(false, "%s", e.what());
    }
    return {};
}

// The mesh of `text`, written to scratch/name and read back.
MeshData read_written(const char* what, const std::string& name, const std::string& text) {
    const std::string path = scratch(name);
    write_text(path, text);
    return read_or_fail(what, path);
}

double tet_volume(const MeshData& d, size_t t) {
    const double* p[4];
    for (int k = 0; k < 4; ++k) p[k] = &d.xyz[3 * static_cast<size_t>(d.tets[4 * t + k] - d.base)];
    double e[3][3];
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) e[i][k] = p[i + 1][k] - p[0][k];
    return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
            e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
           6.0;
}

// The two unit cubes of box.geo (and box_nophysical.geo): 48 tets, 24 in
// region 1 (x <= 1) and 24 in region 2, volume 1 each.
void check_two_cubes(const MeshData& d, const char* what) {
    CHECK(d.tets.size() == 4 * 48 && d.regions.size() == 48, "%zu tets, %zu regions", d.tets.size() / 4,
          d.regions.size());
    double volume[3] = {0, 0, 0};
    for (size_t t = 0; t < 48; ++t) {
        CHECK(d.regions[t] == 1 || d.regions[t] == 2, "tet %zu has region %d", t, d.regions[t]);
        volume[d.regions[t]] += std::fabs(tet_volume(d, t));
        for (int k = 0; k < 4 && d.regions[t] == 1; ++k)
            CHECK(d.xyz[3 * static_cast<size_t>(d.tets[4 * t + k] - d.base)] <= 1.0, "a tet of region 1 beyond x = 1");
    }
    CHECK(std::count(d.regions.begin(), d.regions.end(), 1) == 24, "not 24 tets in region 1");
    CHECK(std::fabs(volume[1] - 1) < 1e-12 && std::fabs(volume[2] - 1) < 1e-12, "volumes %g and %g", volume[1],
          volume[2]);
}

// A 2 x 2 x 2 grid of cubes, six tets each (positively oriented), with
// jittered coordinates that %.6g would not reproduce; regions, markers,
// edges and fixed vertices.
MeshData make_mesh(int base) {
    MeshData d;
    d.base = base;
    const int n = 2;
    auto id = [&](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                d.xyz.push_back(i / 3.0 + 1e-3 * std::sin(1.0 + i + 7 * j + 13 * k));
                d.xyz.push_back(j * 0.7 + 1e-17 * k - 12345.678901234567);
                d.xyz.push_back(std::ldexp(k + 0.1, -30 + 2 * i));
            }
    static const int kuhn[6][4][3] = {
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}}, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {1, 1, 1}},
        {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}}, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {1, 1, 1}},
        {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}}};
    int t = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (const auto& tet : kuhn) {
                    for (const auto& c : tet) d.tets.push_back(id(i + c[0], j + c[1], k + c[2]) + base);
                    static const int32_t regions[] = {1, 1, 2, 0, 2, 2, -3, 1};
                    d.regions.push_back(regions[(t++ / 5) % 8]);
                }
    for (size_t k = 0; k < d.regions.size(); ++k)  // positively oriented, as writers expect
        if (tet_volume(d, k) < 0) std::swap(d.tets[4 * k + 2], d.tets[4 * k + 3]);
    // the bottom faces z = 0, markers 5, 7 and 0 mixed
    int f = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int32_t a = id(i, j, 0) + base, b = id(i + 1, j, 0) + base, c = id(i + 1, j + 1, 0) + base,
                          e = id(i, j + 1, 0) + base;
            d.triangles.insert(d.triangles.end(), {a, c, b, a, e, c});
            static const int32_t markers[] = {5, 7, 0, 5, 5, 7, 7, 0};
            d.tri_markers.push_back(markers[f++]);
            d.tri_markers.push_back(markers[f++]);
        }
    // feature edges along x at y = z = 0 and along z at x = y = 0
    for (int i = 0; i < n; ++i) d.feature_edges.insert(d.feature_edges.end(), {id(i, 0, 0) + base, id(i + 1, 0, 0) + base});
    for (int k = 0; k < n; ++k) d.feature_edges.insert(d.feature_edges.end(), {id(0, 0, k) + base, id(0, 0, k + 1) + base});
    d.edge_refs = {20, 0, 20, -4};
    d.fixed = {id(0, 0, 0) + base, id(n, n, n) + base, id(n, 0, n) + base};
    // Gmsh has no place for these: dropped by a write.
    d.vertex_refs.assign(d.xyz.size() / 3, 6);
    d.corners = {id(n, n, 0) + base};
    return d;
}

// `a` as it should read back: the file's base and no marker-0 faces.
std::vector<int32_t> rebased(const std::vector<int32_t>& v, int from, int to) {
    std::vector<int32_t> out(v);
    for (int32_t& x : out) x = x - from + to;
    return out;
}

void check_same(const MeshData& in, const MeshData& out, const char* what) {
    CHECK(out.xyz.size() == in.xyz.size(), "%zu coordinates, expected %zu", out.xyz.size(), in.xyz.size());
    CHECK(std::memcmp(out.xyz.data(), in.xyz.data(), in.xyz.size() * sizeof(double)) == 0, "coordinates differ");
    const int b = out.base;
    CHECK(b == 1, "base %d, expected 1 (tags 1..n in order)", b);
    CHECK(out.tets == rebased(in.tets, in.base, b), "tets differ");
    CHECK(out.regions == in.regions, "regions differ");
    std::vector<int32_t> tris, markers;
    for (size_t f = 0; f < in.tri_markers.size(); ++f)
        if (in.tri_markers[f] != 0) {
            for (int k = 0; k < 3; ++k) tris.push_back(in.triangles[3 * f + k] - in.base + b);
            markers.push_back(in.tri_markers[f]);
        }
    CHECK(out.triangles == tris, "triangles differ (%zu, expected %zu)", out.triangles.size() / 3, tris.size() / 3);
    CHECK(out.tri_markers == markers, "markers differ");
    CHECK(out.feature_edges == rebased(in.feature_edges, in.base, b), "feature edges differ");
    const std::vector<int32_t> refs =
        in.edge_refs.empty() ? std::vector<int32_t>(in.feature_edges.size() / 2, 0) : in.edge_refs;
    CHECK(out.edge_refs == refs, "edge refs differ");
    CHECK(out.fixed == rebased(in.fixed, in.base, b), "fixed vertices differ");
    CHECK(out.vertex_refs.empty() && out.corners.empty(), "vertex refs or corners from a Gmsh file");
}

struct Variant {
    int version;
    bool binary;
    const char* name;
};
constexpr Variant kVariants[] = {
    {41, false, "41_ascii"}, {41, true, "41_binary"}, {22, false, "22_ascii"}, {22, true, "22_binary"}};

void test_round_trip(void** /*state*/) {
    for (int base = 0; base <= 1; ++base) {
        const MeshData in = make_mesh(base);
        for (const Variant& v : kVariants) {
            char what[80];
            std::snprintf(what, sizeof what, "round trip %s from base %d", v.name, base);
            const std::string path = scratch(std::string("round_") + v.name + "_" + std::to_string(base) + ".msh");
            try {
                bodt::write_gmsh(path, in, v.version, v.binary);
                check_same(in, bodt::read_gmsh(path), what);
                // and again from what was read: the same file
                const std::string again = path + ".again.msh";
                bodt::write_gmsh(again, bodt::read_gmsh(path), v.version, v.binary);
                CHECK(read_text(again) == read_text(path), "rewriting what was read changes the file");
                if (v.version == 41 && !v.binary) {
                    // a curve per edge ref (-4, 0, 20), a physical group per nonzero one
                    const std::string text = read_text(path);
                    CHECK(text.find("$Entities\n3 3 2 4\n") != std::string::npos, "entity counts");
                    CHECK(text.find("\n1 20 \"edge ref 20\"\n") != std::string::npos &&
                              text.find("\n1 -4 \"edge ref -4\"\n") != std::string::npos &&
                              text.find("\n1 0 \"") == std::string::npos,
                          "physical curves");
                }
            } catch (const Error& e) {
                CHECK(false, "%s", e.what());
            }
        }
    }
    // no regions at all: region 0 everywhere, written without a physical group
    const char* what = "round trip without regions";
    MeshData in = make_mesh(0);
    in.regions.clear();
    in.tri_markers.assign(in.tri_markers.size(), 0);
    in.edge_refs.clear();
    for (const Variant& v : kVariants) {
        const std::string path = scratch(std::string("round_plain_") + v.name + ".msh");
        bodt::write_gmsh(path, in, v.version, v.binary);
        const MeshData out = bodt::read_gmsh(path);
        CHECK(out.regions == std::vector<int32_t>(in.tets.size() / 4, 0), "regions are not all 0");
        CHECK(out.triangles.empty() && out.tri_markers.empty(), "marker-0 faces were written");
        CHECK(out.feature_edges == rebased(in.feature_edges, in.base, out.base), "%s: feature edges differ", v.name);
        CHECK(out.edge_refs == std::vector<int32_t>(in.feature_edges.size() / 2, 0), "%s: edge refs are not all 0",
              v.name);
    }
    // Ref-0 edges are in a curve without physical group: the only physical
    // group is the fixed vertices'.
    const std::string text = read_text(scratch("round_plain_41_ascii.msh"));
    CHECK(text.find("$PhysicalNames\n1\n0 1 \"fixed vertices\"\n$EndPhysicalNames") != std::string::npos,
          "physical groups other than the fixed vertices'");
}

void test_gmsh_files(void** /*state*/) {
    const char* names[] = {"box41.msh", "box41_bin.msh", "box22.msh", "box22_bin.msh"};
    MeshData first;
    for (const char* name : names) {
        const char* what = name;
        const MeshData d = read_or_fail(what, data(name));
        CHECK(d.base == 1, "base %d", d.base);
        CHECK(d.xyz.size() == 3 * 23, "%zu vertices", d.xyz.size() / 3);
        check_two_cubes(d, what);
        CHECK(d.tri_markers == std::vector<int32_t>(8, 10), "%zu markers, expected 8 x 10", d.tri_markers.size());
        for (int32_t v : d.triangles) CHECK(d.xyz[3 * (v - 1) + 2] == 0.0, "a marked face vertex off z = 0");
        CHECK(d.feature_edges.size() == 2, "%zu feature edges", d.feature_edges.size() / 2);
        CHECK(d.edge_refs == std::vector<int32_t>{20}, "the edge ref is not the physical curve 20");
        const double* a = &d.xyz[3 * (d.feature_edges[0] - 1)];
        const double* b = &d.xyz[3 * (d.feature_edges[1] - 1)];
        CHECK(a[0] == 0 && a[1] == 0 && b[0] == 0 && b[1] == 0 && a[2] + b[2] == 1 && a[2] * b[2] == 0,
              "the feature edge is not (0,0,0)-(0,0,1)");
        CHECK(d.fixed.size() == 1, "%zu fixed vertices", d.fixed.size());
        const double* o = &d.xyz[3 * (d.fixed[0] - 1)];
        CHECK(o[0] == 0 && o[1] == 0 && o[2] == 0, "the fixed vertex is not the origin");
        if (name == names[0]) {
            first = d;
        } else {
            CHECK(d.xyz == first.xyz && d.tets == first.tets && d.regions == first.regions &&
                      d.triangles == first.triangles && d.feature_edges == first.feature_edges &&
                      d.edge_refs == first.edge_refs && d.fixed == first.fixed,
                  "differs from %s", names[0]);
        }
    }
}

void test_entity_regions(void** /*state*/) {
    for (const char* name : {"box_nophysical41.msh", "box_nophysical22.msh"}) {
        const char* what = name;
        const MeshData d = read_or_fail(what, data(name));
        check_two_cubes(d, what);
        CHECK(d.edge_refs == std::vector<int32_t>(20, 0), "%zu feature edges, expected 20 with ref 0",
              d.edge_refs.size());
        // The 11 surfaces (10 outer, 1 between the cubes), 4 triangles each,
        // marked by their entity tags; the one at x = 1 is a single surface.
        CHECK(d.triangles.size() == 3 * 44 && d.tri_markers.size() == 44, "%zu marked faces, expected 44",
              d.tri_markers.size());
        for (int32_t m = 1; m <= 11; ++m)
            CHECK(std::count(d.tri_markers.begin(), d.tri_markers.end(), m) == 4, "marker %d not on 4 faces", m);
        int32_t between = 0;
        for (size_t f = 0; f < d.tri_markers.size(); ++f) {
            bool at_one = true;
            for (int k = 0; k < 3; ++k)
                at_one = at_one && d.xyz[3 * static_cast<size_t>(d.triangles[3 * f + k] - d.base)] == 1.0;
            if (!at_one) continue;
            CHECK(between == 0 || d.tri_markers[f] == between, "the faces at x = 1 carry markers %d and %d", between,
                  d.tri_markers[f]);
            between = d.tri_markers[f];
        }
        CHECK(between != 0, "no marked face at x = 1");
        CHECK(d.fixed.empty(), "%zu fixed vertices", d.fixed.size());
    }
}

// 4.1 ASCII, tags 40, 10, 30, 20, 50 (sparse, unordered), a parametric block,
// other sections, a quad and an unknown 2-D type skipped; a line on curve 5
// (not in $Entities: no physical tag) and one on curve 7 (physical -12).
const char* kSparse41 =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$Comments\nanything $Nodes here\n$EndComments\n"
    "$PhysicalNames\n1\n3 7 \"v $EndPhysicalNames\"\n$EndPhysicalNames\n"
    "$Entities\n1 1 1 1\n"
    "4 0 0 0 1 9\n"
    "7 0 0 0 1 1 1 1 -12 2 4 -4\n"
    "3 0 0 0 1 1 1 1 7 2 1 -2\n"
    "2 0 0 0 1 1 1 2 4 8 1 3\n"
    "$EndEntities\n"
    "$Nodes\n3 5 10 50\n"
    "3 2 0 3\n40\n10\n30\n0 0 0\n1 0 0\n0 1 0\n"
    "2 3 1 1\n20\n0 0 1 0.5 0.5\n"
    "0 4 0 1\n50\n1 1 1\n"
    "$EndNodes\n"
    "$Elements\n7 8 1 9\n"
    "0 4 15 1\n1 50\n"
    "1 5 1 1\n6 10 30\n"
    "1 7 1 1\n7 40 20\n"
    "2 3 2 1\n2 40 10 30\n"
    "2 3 3 1\n3 40 10 30 20\n"
    "2 3 9999 1\n4 1 2 3 and whatever\n"
    "3 2 4 2\n5 40 10 30 20\n9 40 10 20 50\n"
    "$EndElements\n"
    "$NodeData\n1\n\"x\"\n$EndNodeData\n";

// 2.2 ASCII, tags 7, 3, 5, 1 (unordered), a 6-tag tet and a quad; a line
// without tags and one with physical tag 8, listed again (reversed) for its
// second physical group 9.
const char* kSparse22 =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
    "$Nodes\n4\n7 0 0 0\n3 1 0 0\n5 0 1 0\n1 0 0 1\n$EndNodes\n"
    "$Elements\n7\n"
    "1 4 6 3 1 2 1 2 3 7 3 5 1\n"
    "2 2 2 4 1 7 3 5\n"
    "3 3 2 4 1 7 3 5 1\n"
    "4 2 2 0 1 7 5 1\n"
    "5 1 0 7 3\n"
    "6 1 2 8 2 3 5\n"
    "7 1 2 9 2 5 3\n"
    "$EndElements\n";

void test_sparse_tags(void** /*state*/) {
    {
        const char* what = "sparse 4.1";
        const MeshData d = read_written(what, "sparse41.msh", kSparse41);
        CHECK(d.base == 0, "base %d", d.base);
        // file order: 40 10 30 20 50 -> 0 1 2 3 4
        CHECK(d.xyz == (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}), "coordinates");
        CHECK(d.tets == (std::vector<int32_t>{0, 1, 2, 3, 0, 1, 3, 4}), "tets");
        CHECK(d.regions == (std::vector<int32_t>{4, 4}), "regions (first physical tag of volume 2)");
        CHECK(d.triangles == (std::vector<int32_t>{0, 1, 2}) && d.tri_markers == std::vector<int32_t>{7}, "triangle");
        CHECK(d.fixed == std::vector<int32_t>{4}, "fixed");
        CHECK(d.feature_edges == (std::vector<int32_t>{1, 2, 0, 3}), "feature edges");
        CHECK(d.edge_refs == (std::vector<int32_t>{0, -12}), "edge refs: 0 without a physical tag");
    }
    {
        const char* what = "sparse 2.2";
        const MeshData d = read_written(what, "sparse22.msh", kSparse22);
        CHECK(d.base == 0, "base %d", d.base);
        CHECK(d.tets == (std::vector<int32_t>{0, 1, 2, 3}) && d.regions == std::vector<int32_t>{3}, "tet");
        CHECK(d.triangles == (std::vector<int32_t>{0, 1, 2}) && d.tri_markers == std::vector<int32_t>{4},
              "only the physical triangle");
        CHECK(d.feature_edges == (std::vector<int32_t>{0, 1, 1, 2}) && d.edge_refs == (std::vector<int32_t>{0, 8}),
              "both lines once, ref 0 without tags, the first group's tag for the line listed twice");
    }
}

// ---------------------------------------------------------------- the model

// The entity (dim, tag) of a model, or null.
const bodt::GmshEntity* model_entity(const bodt::GmshModel& m, int dim, int32_t tag) {
    for (const bodt::GmshEntity& e : m.entities)
        if (e.dim == dim && e.tag == tag) return &e;
    return nullptr;
}

// The tag of model entity index e (dim checked).
int32_t tag_of(const bodt::GmshModel& m, int32_t e, int dim) {
    if (e < 0 || static_cast<size_t>(e) >= m.entities.size() || m.entities[static_cast<size_t>(e)].dim != dim) return -1;
    return m.entities[static_cast<size_t>(e)].tag;
}

void test_model(void** /*state*/) {
    {
        const char* what = "box41.msh's model";
        const MeshData d = bodt::read_gmsh(data("box41.msh"));
        CHECK(d.gmsh != nullptr, "no model");
        const bodt::GmshModel& m = *d.gmsh;
        CHECK(m.names.size() == 5 && m.names[0].dim == 0 && m.names[0].tag == 30 && m.names[0].name == "corner" &&
                  m.names[4].dim == 3 && m.names[4].tag == 2 && m.names[4].name == "right",
              "physical names");
        int per_dim[4] = {0, 0, 0, 0};
        for (const bodt::GmshEntity& e : m.entities) ++per_dim[e.dim];
        CHECK(per_dim[0] == 12 && per_dim[1] == 20 && per_dim[2] == 11 && per_dim[3] == 2, "entities %d %d %d %d",
              per_dim[0], per_dim[1], per_dim[2], per_dim[3]);
        const bodt::GmshEntity* s5 = model_entity(m, 2, 5);
        CHECK(s5 && s5->physicals == std::vector<int32_t>{10} && m.key(*s5) == 10 &&
                  s5->bounding == (std::vector<int32_t>{4, 11, -8, -9}) && s5->has_box && s5->box[5] < 1e-6,
              "surface 5");
        const bodt::GmshEntity* p2 = model_entity(m, 0, 2);
        CHECK(p2 && p2->physicals == std::vector<int32_t>{30} && p2->box[0] == 0 && p2->box[3] == 0, "point 2");
        CHECK(!m.entity_keyed[2] && !m.entity_keyed[3], "entity tags taken as values");
        CHECK(m.tet_entity.size() == 48, "%zu tet entities", m.tet_entity.size());
        for (size_t t = 0; t < 48; ++t)
            CHECK(tag_of(m, m.tet_entity[t], 3) == d.regions[t], "tet %zu in volume %d, region %d", t,
                  tag_of(m, m.tet_entity[t], 3), d.regions[t]);
        CHECK(m.triangle_entity.size() == 8 && m.triangles.size() == 24, "%zu triangles", m.triangle_entity.size());
        for (size_t f = 0; f < 8; ++f) {
            const int32_t s = tag_of(m, m.triangle_entity[f], 2);
            for (int k = 0; k < 3; ++k) {
                const double x = d.xyz[3 * static_cast<size_t>(m.triangles[3 * f + k])];
                CHECK(s == 5 ? x <= 1 : s == 10 && x >= 1, "triangle %zu in surface %d has x = %g", f, s, x);
            }
        }
        CHECK(m.lines == (std::vector<int32_t>{1, 0}) && tag_of(m, m.line_entity[0], 1) == 1, "the line on curve 1");
        CHECK(m.points == std::vector<int32_t>{1} && tag_of(m, m.point_entity[0], 0) == 2, "the point");
        // nodes: tag 2 (the origin) on point 2, tag 17 (0.5, 0.5, 0) on surface 5, tag 23 on surface 11
        CHECK(m.node_entity.size() == 23 && tag_of(m, m.node_entity[1], 0) == 2 &&
                  tag_of(m, m.node_entity[16], 2) == 5 && tag_of(m, m.node_entity[22], 2) == 11,
              "node entities");
    }
    {
        const char* what = "box22.msh's model";
        const MeshData d = bodt::read_gmsh(data("box22.msh"));
        const bodt::GmshModel& m = *d.gmsh;
        CHECK(m.names.size() == 5 && m.node_entity.empty(), "names or node entities");
        // 2.2: the entities that hold elements, with the physical tags of their elements
        CHECK(m.entities.size() == 6, "%zu entities", m.entities.size());
        const bodt::GmshEntity* s10 = model_entity(m, 2, 10);
        CHECK(s10 && s10->physicals == std::vector<int32_t>{10} && !s10->has_box, "surface 10");
        CHECK(model_entity(m, 3, 1) && model_entity(m, 3, 1)->physicals == std::vector<int32_t>{1}, "volume 1");
    }
    {
        const char* what = "box_nophysical41.msh's model";
        const MeshData d = bodt::read_gmsh(data("box_nophysical41.msh"));
        const bodt::GmshModel& m = *d.gmsh;
        CHECK(m.names.empty() && m.entity_keyed[3] && m.entity_keyed[2] && !m.entity_keyed[1], "entity keyed");
        for (const bodt::GmshEntity& e : m.entities)
            CHECK(e.physicals.empty() && m.key(e) == (e.dim >= 2 ? e.tag : 0), "entity (%d, %d) key %d", e.dim, e.tag,
                  m.key(e));
        CHECK(m.points.size() == 12 && m.triangle_entity.size() == 44 && m.line_entity.size() == 20,
              "%zu points, %zu triangles, %zu lines", m.points.size(), m.triangle_entity.size(),
              m.line_entity.size());
        CHECK(d.fixed.empty(), "points without a physical group fixed");
    }
}

// Node tags 1..5 in blocks out of order, element tags out of order, a
// point entity with tag 0 in $Entities (no entity), and a node block and an
// element block on an entity $Entities does not list.
const char* kShuffled41 =
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    "$PhysicalNames\n2\n3 4 \"a name with spaces\"\n2 6 \"\"\n$EndPhysicalNames\n"
    "$Entities\n1 0 1 1\n"
    "0 9 9 9 1 1\n"
    "3 0 0 0 1 1 1 1 6 0\n"
    "2 0 0 0 1 1 1 1 4 1 3\n"
    "$EndEntities\n"
    "$Nodes\n3 5 1 5\n"
    "2 3 0 2\n4\n2\n0 0 1\n1 0 0\n"
    "2 7 0 1\n5\n1 1 1\n"
    "3 2 0 2\n1\n3\n0 0 0\n0 1 0\n"
    "$EndNodes\n"
    "$Elements\n4 5 1 9\n"
    "2 3 2 1\n8 1 2 3\n"
    "0 0 15 1\n1 5\n"
    "3 2 4 2\n9 1 2 3 5\n2 1 2 3 4\n"
    "2 7 2 1\n5 2 3 4\n"
    "$EndElements\n";

void test_order(void** /*state*/) {
    const char* what = "shuffled 4.1";
    const MeshData d = read_written(what, "shuffled41.msh", kShuffled41);
    // vertex i is the node tagged i + 1, whatever block holds it
    CHECK(d.base == 1, "base %d", d.base);
    CHECK(d.xyz == (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1}), "coordinates");
    // elements by tag: tet 2 before tet 9, triangle 5 (surface 7) before 8 (surface 3)
    CHECK(d.tets == (std::vector<int32_t>{1, 2, 3, 4, 1, 2, 3, 5}), "tets");
    CHECK(d.regions == (std::vector<int32_t>{4, 4}), "regions");
    CHECK(d.triangles == (std::vector<int32_t>{1, 2, 3}) && d.tri_markers == std::vector<int32_t>{6},
          "only the physical triangle");
    CHECK(d.fixed.empty(), "the point without an entity fixes nothing");
    const bodt::GmshModel& m = *d.gmsh;
    CHECK(m.names.size() == 2 && m.names[0].name == "a name with spaces" && m.names[1].name.empty(), "names");
    CHECK(m.triangles == (std::vector<int32_t>{1, 2, 3, 0, 1, 2}), "model triangles in tag order");
    CHECK(tag_of(m, m.triangle_entity[0], 2) == 7 && tag_of(m, m.triangle_entity[1], 2) == 3, "triangle entities");
    CHECK(model_entity(m, 2, 7) && model_entity(m, 2, 7)->physicals.empty(), "the unlisted surface 7");
    CHECK(!model_entity(m, 0, 0) && m.point_entity == std::vector<int32_t>{-1}, "entity tag 0");
    // nodes 4 and 2 (vertices 3 and 1) on surface 3, 1 and 3 on volume 2;
    // node 5's block is on surface 7, which only elements make an entity
    CHECK(tag_of(m, m.node_entity[3], 2) == 3 && tag_of(m, m.node_entity[1], 2) == 3 &&
              m.node_entity[4] == -1 && tag_of(m, m.node_entity[0], 3) == 2 && tag_of(m, m.node_entity[2], 3) == 2,
          "node entities");
    // written and read again: the same arrays and names
    for (const Variant& v : kVariants) {
        const std::string again = scratch(std::string("shuffled_again_") + v.name + ".msh");
        bodt::write_gmsh(again, d, v.version, v.binary);
        const MeshData back = bodt::read_gmsh(again);
        CHECK(back.xyz == d.xyz && back.tets == d.tets && back.regions == d.regions && back.triangles == d.triangles &&
                  back.tri_markers == d.tri_markers,
              "%s: arrays differ", v.name);
        CHECK(back.gmsh->names.size() == 2 && back.gmsh->names[0].name == "a name with spaces", "%s: names", v.name);
    }
}

// ---------------------------------------------------------------- layout

// The layout entity (dim, tag): its index, -1 if none.
int32_t layout_index(const bodt::GmshLayout& l, int dim, int32_t tag) {
    for (size_t k = 0; k < l.entities.size(); ++k)
        if (l.entities[k].dim == dim && l.entities[k].tag == tag) return static_cast<int32_t>(k);
    return -1;
}

// The tag of the entity element k of `dim` is in.
int32_t placed(const bodt::GmshLayout& l, int dim, size_t k) {
    const int32_t e = l.element_entity[dim][k];
    return e < 0 ? -1 : l.entities[static_cast<size_t>(e)].tag;
}

const std::vector<int32_t>& physicals_of(const bodt::GmshLayout& l, int dim, int32_t tag) {
    static const std::vector<int32_t> none{-99};
    const int32_t k = layout_index(l, dim, tag);
    return k < 0 ? none : l.entities[static_cast<size_t>(k)].physicals;
}

bool named(const bodt::GmshLayout& l, int dim, int32_t tag, const std::string& name) {
    for (const bodt::GmshPhysicalName& n : l.names)
        if (n.dim == dim && n.tag == tag) return n.name == name;
    return false;
}

// A vertex made by a step, with its parents (1-based tags, as in box41.msh).
int32_t add_made_vertex(MeshData& d, std::initializer_list<std::pair<int32_t, double>> parents) {
    MeshData::Origins& o = d.origins;
    if (o.parent_offsets.empty()) {  // the input vertices stand for themselves
        o.input_vertices = static_cast<int32_t>(d.xyz.size() / 3);
        o.parent_offsets.push_back(0);
        for (int32_t v = 0; v < o.input_vertices; ++v) {
            o.parents.push_back(v);
            o.weights.push_back(1.0);
            o.parent_offsets.push_back(v + 1);
        }
    }
    double p[3] = {0, 0, 0};
    for (const auto& [tag, w] : parents) {
        o.parents.push_back(tag - 1);
        o.weights.push_back(w);
        for (int k = 0; k < 3; ++k) p[k] += w * d.xyz[3 * static_cast<size_t>(tag - 1) + k];
    }
    o.parent_offsets.push_back(static_cast<int64_t>(o.parents.size()));
    d.xyz.insert(d.xyz.end(), p, p + 3);
    return static_cast<int32_t>(d.xyz.size() / 3);  // its tag (base 1)
}

// Replaces the triangle (a, b, c) (in any order, tags) by `by`.
void replace_triangle(MeshData& d, std::array<int32_t, 3> old, std::vector<std::array<int32_t, 4>> by) {
    std::sort(old.begin(), old.end());
    for (size_t f = 0; f < d.tri_markers.size(); ++f) {
        std::array<int32_t, 3> t{d.triangles[3 * f], d.triangles[3 * f + 1], d.triangles[3 * f + 2]};
        std::sort(t.begin(), t.end());
        if (t != old) continue;
        d.triangles.erase(d.triangles.begin() + static_cast<std::ptrdiff_t>(3 * f),
                          d.triangles.begin() + static_cast<std::ptrdiff_t>(3 * f + 3));
        d.tri_markers.erase(d.tri_markers.begin() + static_cast<std::ptrdiff_t>(f));
        for (const auto& n : by) {
            d.triangles.insert(d.triangles.end(), {n[0], n[1], n[2]});
            d.tri_markers.push_back(n[3]);
        }
        return;
    }
    fail_msg("no triangle %d %d %d", old[0], old[1], old[2]);
}

void test_layout_as_read(void** /*state*/) {
    const char* what = "layout of box41.msh as read";
    const MeshData d = bodt::read_gmsh(data("box41.msh"));
    const bodt::GmshLayout l = bodt::layout_gmsh(d);
    CHECK(l.entities.size() == d.gmsh->entities.size(), "%zu entities", l.entities.size());
    for (size_t k = 0; k < l.entities.size(); ++k) {
        const bodt::GmshEntity& m = d.gmsh->entities[k];
        const bodt::GmshLayout::Entity& e = l.entities[k];
        CHECK(e.dim == m.dim && e.tag == m.tag && e.physicals == m.physicals && e.bounding == m.bounding &&
                  e.box == m.box,
              "entity %zu differs from the model's", k);
    }
    for (size_t f = 0; f < 8; ++f)
        CHECK(placed(l, 2, f) == tag_of(*d.gmsh, d.gmsh->triangle_entity[f], 2), "triangle %zu", f);
    for (size_t t = 0; t < 48; ++t) CHECK(placed(l, 3, t) == d.regions[t], "tet %zu", t);
    CHECK(placed(l, 1, 0) == 1 && l.points == std::vector<int32_t>{1} && placed(l, 0, 0) == 2, "line and point");
    for (size_t v = 0; v < 23; ++v)
        CHECK(l.node_entity[v] == d.gmsh->node_entity[v], "node %zu moved to another entity", v + 1);
    CHECK(l.names.size() == 5 && named(l, 2, 10, "bottom"), "names");
}

void test_layout_after_steps(void** /*state*/) {
    const char* what = "layout of box41.msh after steps";
    const MeshData in = bodt::read_gmsh(data("box41.msh"));
    MeshData d = in;
    // An edge split inside surface 5 (x <= 1): (2, 17) at its middle.
    const int32_t m5 = add_made_vertex(d, {{2, 0.5}, {17, 0.5}});
    replace_triangle(d, {2, 4, 17}, {{2, 4, m5, 10}, {m5, 4, 17, 10}});
    replace_triangle(d, {5, 2, 17}, {{5, 2, m5, 10}, {5, m5, 17, 10}});
    // A vertex made in surface 10 (x >= 1), then a triangle on the curve
    // x = 1 between the two surfaces with it: it lies on 10.
    const int32_t m10 = add_made_vertex(d, {{12, 0.25}, {22, 0.75}});
    replace_triangle(d, {5, 8, 22}, {{5, 8, m10, 10}, {5, m10, 22, 10}});
    // The feature edge (2, 1) split; an edge with a new ref; one with none.
    const int32_t m1 = add_made_vertex(d, {{1, 0.5}, {2, 0.5}});
    d.feature_edges = {2, m1, m1, 1, 4, 8, 8, 7};
    d.edge_refs = {20, 20, 99, 0};
    // A face with a new marker, an unmarked face.
    d.triangles.insert(d.triangles.end(), {1, 3, 13, 3, 4, 13});
    d.tri_markers.insert(d.tri_markers.end(), {44, 0});
    // Tets (geometry aside): from their input tets, one moved to region 2,
    // one in a new region 7.
    const size_t nt = d.tets.size() / 4;
    for (size_t t = 0; t < nt; ++t) d.origins.tet_origins.push_back(static_cast<int32_t>(nt - 1 - t));
    std::vector<int32_t> regions(nt);
    for (size_t t = 0; t < nt; ++t) regions[t] = in.regions[nt - 1 - t];
    d.tets.clear();
    for (size_t t = 0; t < nt; ++t)
        d.tets.insert(d.tets.end(), in.tets.begin() + 4 * static_cast<std::ptrdiff_t>(nt - 1 - t),
                      in.tets.begin() + 4 * static_cast<std::ptrdiff_t>(nt - t));
    const size_t in_one = static_cast<size_t>(std::find(regions.begin(), regions.end(), 1) - regions.begin());
    regions[in_one] = 2;
    regions[0] = 7;
    d.regions = regions;
    // The origin still fixed; vertex 4 fixed by the caller.
    d.fixed = {2, 4};

    const bodt::GmshLayout l = bodt::layout_gmsh(d);
    // every entity of the model kept; new: a point, two curves, a surface, a volume
    int per_dim[4] = {0, 0, 0, 0};
    for (const auto& e : l.entities) ++per_dim[e.dim];
    CHECK(per_dim[0] == 13 && per_dim[1] == 22 && per_dim[2] == 12 && per_dim[3] == 3, "entities %d %d %d %d",
          per_dim[0], per_dim[1], per_dim[2], per_dim[3]);
    const size_t nf = d.tri_markers.size();
    for (size_t f = 0; f < nf; ++f) {
        const int32_t s = placed(l, 2, f);
        if (d.tri_markers[f] == 44) {
            CHECK(s == 44 && physicals_of(l, 2, 44) == std::vector<int32_t>{44} && named(l, 2, 44, "marker 44"),
                  "the new marker's surface is %d", s);
            continue;
        }
        if (d.tri_markers[f] == 0) {
            CHECK(s == -1, "an unmarked face written in surface %d", s);
            continue;
        }
        bool has_m10 = false, right = false, left = false;
        for (int k = 0; k < 3; ++k) {
            const int32_t v = d.triangles[3 * f + k];
            has_m10 = has_m10 || v == m10;
            right = right || d.xyz[3 * static_cast<size_t>(v - 1)] > 1;
            left = left || d.xyz[3 * static_cast<size_t>(v - 1)] < 1;
        }
        CHECK(s == (right || has_m10 ? 10 : 5) && !(left && right), "triangle %zu in surface %d", f, s);
    }
    CHECK(placed(l, 1, 0) == 1 && placed(l, 1, 1) == 1, "the split line is not on curve 1");
    // new entities take their value as tag when it is free, else the next free one
    CHECK(placed(l, 1, 2) == 99 && physicals_of(l, 1, 99) == std::vector<int32_t>{99} && named(l, 1, 99, "edge ref 99"),
          "the new ref's curve");
    CHECK(placed(l, 1, 3) == 100 && physicals_of(l, 1, 100) == std::vector<int32_t>{0}, "the ref-0 curve");
    for (size_t t = 0; t < nt; ++t) {
        const int32_t want = t == in_one ? 2 : regions[t];
        CHECK(placed(l, 3, t) == want, "tet %zu in volume %d, not %d", t, placed(l, 3, t), want);
    }
    CHECK(physicals_of(l, 3, 7) == std::vector<int32_t>{7} && named(l, 3, 7, "region 7"), "the new region's volume");
    CHECK(l.points == (std::vector<int32_t>{1, 3}) && placed(l, 0, 0) == 2 && placed(l, 0, 1) == 13 &&
              physicals_of(l, 0, 13) == std::vector<int32_t>{31} && named(l, 0, 31, "fixed vertices"),
          "points");
    // nodes: made vertices on the lowest entity that holds them
    const auto node_tag = [&](int32_t v) { return l.entities[static_cast<size_t>(l.node_entity[v - 1])]; };
    CHECK(node_tag(m1).dim == 1 && node_tag(m1).tag == 1, "the made vertex on curve 1");
    CHECK(node_tag(m5).dim == 2 && node_tag(m5).tag == 5, "the made vertex in surface 5");
    CHECK(node_tag(m10).dim == 2 && node_tag(m10).tag == 10, "the made vertex in surface 10");
    CHECK(node_tag(17).dim == 2 && node_tag(17).tag == 5 && node_tag(2).dim == 0, "input vertices");
    // without the model: an entity per value
    MeshData plain = d;
    plain.gmsh = nullptr;
    const bodt::GmshLayout p = bodt::layout_gmsh(plain);
    CHECK(p.names.size() == 8 && named(p, 3, 7, "region 7") && named(p, 2, 10, "marker 10") &&
              named(p, 0, 1, "fixed vertices"),
          "%zu names", p.names.size());
    CHECK(layout_index(p, 3, 1) >= 0 && layout_index(p, 3, 2) >= 0 && layout_index(p, 3, 7) >= 0 &&
              layout_index(p, 2, 44) >= 0 && layout_index(p, 1, 20) >= 0,
          "entity tags are not the values");
}

// A model that took entity tags as regions and markers; points and curves
// without physical groups; a single unmarked surface.
void test_layout_without_groups(void** /*state*/) {
    {
        const char* what = "layout of box_nophysical41.msh";
        MeshData d = bodt::read_gmsh(data("box_nophysical41.msh"));
        bodt::GmshLayout l = bodt::layout_gmsh(d);
        for (const auto& e : l.entities) CHECK(e.physicals.empty(), "entity (%d, %d) has a physical tag", e.dim, e.tag);
        CHECK(l.names.empty() && l.points.size() == 12, "names or points");
        for (size_t f = 0; f < d.tri_markers.size(); ++f) CHECK(placed(l, 2, f) == d.tri_markers[f], "triangle %zu", f);
        // a new marker is a new surface of that tag; a fixed vertex brings
        // a physical group, and then every entity with elements gets 0
        d.tri_markers[0] = 50;
        d.fixed = {d.tets[0]};
        l = bodt::layout_gmsh(d);
        CHECK(placed(l, 2, 0) == 50 && physicals_of(l, 2, 50) == std::vector<int32_t>{0}, "the new marker's surface");
        CHECK(physicals_of(l, 3, 1) == std::vector<int32_t>{0} && physicals_of(l, 1, 1) == std::vector<int32_t>{0} &&
                  named(l, 0, 1, "fixed vertices") && l.names.size() == 1,
              "physical tags");
    }
    {
        const char* what = "a single surface without a physical group";
        const std::string path = scratch("one_surface.msh");
        write_text(path,
             "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
             "$Entities\n0 0 1 1\n4 0 0 0 1 1 1 0 0\n1 0 0 0 1 1 1 0 1 4\n$EndEntities\n"
             "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n"
             "$Elements\n2 5 1 5\n2 4 2 4\n1 1 3 2\n2 1 2 4\n3 2 3 4\n4 1 4 3\n3 1 4 1\n5 1 2 3 4\n$EndElements\n");
        MeshData d = bodt::read_gmsh(path);
        CHECK(d.triangles.empty(), "a single surface marks faces");
        // the faces as the C API gives them: all, marker 0
        d.triangles = {1, 3, 2, 1, 2, 4, 2, 3, 4, 1, 4, 3};
        d.tri_markers.assign(4, 0);
        const bodt::GmshLayout l = bodt::layout_gmsh(d);
        for (size_t f = 0; f < 4; ++f) CHECK(placed(l, 2, f) == 4, "face %zu in surface %d", f, placed(l, 2, f));
        CHECK(l.names.empty() && physicals_of(l, 2, 4).empty(), "physical groups");
    }
}

// ---------------------------------------------------------------- malformed

// `path` must fail to read with BODT_ERR_IO and a message naming the path and
// a line ("path:12:") or byte offset ("path: at byte 345:").
void expect_io_error(const char* what, const std::string& path) {
    try {
        bodt::read_gmsh(path);
    } catch (const Error& e) {
        const std::string m = e.what();
        if (std::getenv("BODT_TEST_VERBOSE")) std::printf("%-32s %s\n", what, m.c_str());
        CHECK(e.status() == BODT_ERR_IO, "status %d (%s)", e.status(), m.c_str());
        CHECK(m.compare(0, path.size(), path) == 0, "the message does not start with the path: %s", m.c_str());
        std::string rest = m.substr(std::min(path.size(), m.size()));
        if (rest.compare(0, 10, ": at byte ") == 0)
            rest = rest.substr(10);
        else if (!rest.empty() && rest[0] == ':')
            rest = rest.substr(1);
        else
            rest.clear();
        const size_t digits = rest.find_first_not_of("0123456789");
        CHECK(digits > 0 && digits != std::string::npos && rest[digits] == ':',
              "no line number or byte offset after the path: %s", m.c_str());
        return;
    }
    CHECK(false, "%s was read without an error", path.c_str());
}

// `text` with the first `from` replaced by `to` (which must be there).
std::string replaced(const std::string& text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at == std::string::npos) fail_msg("'%s' is not in the file", from.c_str());
    return text.substr(0, at) + to + text.substr(at + from.size());
}

template <class T>
std::string patched(std::string text, size_t offset, T value) {
    if (offset + sizeof value > text.size()) fail_msg("patch beyond the end");
    std::memcpy(&text[offset], &value, sizeof value);
    return text;
}

void test_malformed(void** /*state*/) {
    const std::string a41 = read_text(data("box41.msh")), b41 = read_text(data("box41_bin.msh"));
    const std::string a22 = read_text(data("box22.msh")), b22 = read_text(data("box22_bin.msh"));
    struct Case {
        std::string name, content;
    };
    std::vector<Case> cases;
    auto add = [&](const std::string& name, const std::string& content) { cases.push_back({name, content}); };

    // truncations at many points of each file (every one must fail: the
    // last section is $Elements, and a cut inside it loses $EndElements)
    const std::pair<const char*, const std::string*> files[] = {
        {"a41", &a41}, {"b41", &b41}, {"a22", &a22}, {"b22", &b22}};
    for (const auto& [name, text] : files) {
        const size_t n = text->size();
        const size_t cuts[] = {0, 5, 20, n / 8, n / 4, n / 3, n / 2, 2 * n / 3, 3 * n / 4, 7 * n / 8, n - 30, n - 14, n - 2};
        for (size_t cut : cuts) add(std::string("cut_") + name + "_" + std::to_string(cut), text->substr(0, cut));
        // cut just inside the binary nodes and elements
        const size_t nodes = text->find("$Nodes\n"), elements = text->find("$Elements\n");
        for (size_t extra : {10, 15, 40, 61})
            add(std::string("cut_nodes_") + name + "_" + std::to_string(extra), text->substr(0, nodes + extra));
        for (size_t extra : {12, 19, 45, 70})
            add(std::string("cut_elements_") + name + "_" + std::to_string(extra), text->substr(0, elements + extra));
    }
    // versions, file type, data size
    add("version_40", replaced(a41, "4.1 0 8", "4.0 0 8"));
    add("version_30", replaced(a41, "4.1 0 8", "3 0 8"));
    add("version_garbage", replaced(a22, "2.2 0 8", "x 0 8"));
    add("file_type_2", replaced(a41, "4.1 0 8", "4.1 2 8"));
    add("data_size_4", replaced(a22, "2.2 0 8", "2.2 0 4"));
    // counts
    add("nodes_count_huge", replaced(a41, "$Nodes\n26 23 1 23", "$Nodes\n26 2300000000000 1 23"));
    add("nodes_count_negative", replaced(a41, "$Nodes\n26 23 1 23", "$Nodes\n26 -23 1 23"));
    add("nodes_count_small", replaced(a41, "$Nodes\n26 23 1 23", "$Nodes\n26 22 1 23"));
    add("nodes_count_large", replaced(a41, "$Nodes\n26 23 1 23", "$Nodes\n26 24 1 23"));
    add("node_blocks_negative", replaced(a41, "$Nodes\n26 23 1 23", "$Nodes\n-26 23 1 23"));
    add("elements_count_huge", replaced(a41, "$Elements\n6 58 1 58", "$Elements\n6 9999999999 1 58"));
    add("elements_count_wrong", replaced(a41, "$Elements\n6 58 1 58", "$Elements\n6 57 1 58"));
    add("nodes22_count_huge", replaced(a22, "$Nodes\n23\n", "$Nodes\n230000000\n"));
    add("nodes22_count_negative", replaced(a22, "$Nodes\n23\n", "$Nodes\n-1\n"));
    add("elements22_count_large", replaced(a22, "$Elements\n58\n", "$Elements\n59\n"));
    add("elements22_count_negative", replaced(a22, "$Elements\n58\n", "$Elements\n-58\n"));
    add("entities_count_huge", replaced(a41, "$Entities\n12 20 11 2", "$Entities\n12 20 1100000 2"));
    // tags and coordinates
    add("node_tag_outside_header", replaced(a41, "\n0 1 0 1\n1\n", "\n0 1 0 1\n24\n"));
    add("node_tag_duplicate22", replaced(a22, "\n2 0 0 0\n", "\n1 0 0 0\n"));
    add("element_node_out_of_range41", replaced(a41, "\n3 1 4 24\n11 ", "\n3 1 4 24\n11 99 "));
    add("element_node_out_of_range22", replaced(a22, "\n2 1 2 20 1 2 1\n", "\n2 1 2 20 1 2 1000\n"));
    add("element_node_zero22", replaced(a22, "\n2 1 2 20 1 2 1\n", "\n2 1 2 20 1 0 1\n"));
    add("nan_coordinate41", replaced(a41, "\n0 0 1\n", "\nnan 0 1\n"));
    add("inf_coordinate22", replaced(a22, "\n1 0 0 1\n", "\n1 0 inf 1\n"));
    add("garbage_coordinate22", replaced(a22, "\n1 0 0 1\n", "\n1 0 0x 1\n"));
    // sections
    add("missing_end_nodes41", replaced(a41, "$EndNodes\n", ""));
    add("missing_end_nodes22", replaced(a22, "$EndNodes\n", ""));
    add("missing_end_elements", replaced(a41, "$EndElements\n", ""));
    add("missing_end_physical_names", replaced(a41, "$EndPhysicalNames\n", ""));
    add("missing_nodes", a41.substr(0, a41.find("$Nodes")));
    add("elements_before_nodes", replaced(a22, "$Nodes", "$Elements\n0\n$EndElements\n$Nodes"));
    add("not_gmsh", "MeshVersionFormatted 2\nDimension 3\n");
    add("binary_garbage", std::string("\x00\x01\xff\xfe$Nodes\n", 11));
    add("empty", "");
    add("stray_token", replaced(a41, "$Elements", "hello\n$Elements"));
    add("no_tets", a22.substr(0, a22.find("$Elements")) + "$Elements\n1\n1 15 2 30 2 2\n$EndElements\n");
    // element types
    add("second_order_tet41", replaced(a41, "\n3 1 4 24\n", "\n3 1 11 24\n"));
    add("hex41", replaced(a41, "\n3 1 4 24\n", "\n3 1 5 24\n"));
    add("tet_in_surface41", replaced(a41, "\n3 1 4 24\n", "\n2 1 4 24\n"));
    add("unknown_volume_type41", replaced(a41, "\n3 1 4 24\n", "\n3 1 200 24\n"));
    add("unknown_type22", replaced(a22, "\n1 15 2 30", "\n1 99 2 30"));
    add("second_order_tet22", replaced(a22, " 4 2 1 ", " 11 2 1 "));
    add("element_tags_huge22", replaced(a22, " 4 2 1 ", " 4 200000 1 "));
    // the line element (a feature edge)
    add("line_node_out_of_range41", replaced(a41, "\n1 1 1 1\n2 2 1 \n", "\n1 1 1 1\n2 2 99 \n"));
    add("line_node_missing41", replaced(a41, "\n1 1 1 1\n2 2 1 \n", "\n1 1 1 1\n2 2\n"));
    add("line_in_volume_block41", replaced(a41, "\n1 1 1 1\n", "\n3 1 1 1\n"));
    add("line_physical_tag_huge22", replaced(a22, "\n2 1 2 20 1 2 1\n", "\n2 1 2 9999999999 1 2 1\n"));
    add("line_physical_tag_word22", replaced(a22, "\n2 1 2 20 1 2 1\n", "\n2 1 2 x20 1 2 1\n"));
    add("curve_physical_tag_huge41", replaced(a41, "1.0000001 1 20 2 2 -1", "1.0000001 1 4294967316 2 2 -1"));
    add("curve_physical_count_huge41", replaced(a41, "1.0000001 1 20 2 2 -1", "1.0000001 999999999 20 2 2 -1"));
    add("curve_bounding_count_huge41", replaced(a41, "1.0000001 1 20 2 2 -1", "1.0000001 1 20 2000000000 2 -1"));
    add("curve_bounding_tag_word41", replaced(a41, "1.0000001 1 20 2 2 -1", "1.0000001 1 20 2 2 x1"));
    add("entity_tag_word41", replaced(a41, "\n1 -1e-07 -1e-07", "\nx -1e-07 -1e-07"));
    add("entity_box_word41", replaced(a41, "\n1 -1e-07 -1e-07", "\n1 -1e-07 y"));
    add("entity_twice41", replaced(a41, "\n2 0 0 0 1 30 \n", "\n1 0 0 0 1 30 \n"));
    // $PhysicalNames
    for (const auto& [name, text] : {std::make_pair("a41", &a41), std::make_pair("b41", &b41),
                                     std::make_pair("a22", &a22), std::make_pair("b22", &b22)}) {
        const std::string n(name);
        add("names_count_huge_" + n, replaced(*text, "$PhysicalNames\n5\n", "$PhysicalNames\n5000000\n"));
        add("names_count_negative_" + n, replaced(*text, "$PhysicalNames\n5\n", "$PhysicalNames\n-5\n"));
        add("names_count_large_" + n, replaced(*text, "$PhysicalNames\n5\n", "$PhysicalNames\n6\n"));
        add("names_dim_" + n, replaced(*text, "\n0 30 \"corner\"", "\n4 30 \"corner\""));
        add("names_tag_word_" + n, replaced(*text, "\n0 30 \"corner\"", "\n0 x30 \"corner\""));
        add("names_tag_huge_" + n, replaced(*text, "\n0 30 \"corner\"", "\n0 3000000000 \"corner\""));
        add("names_unquoted_" + n, replaced(*text, "\n0 30 \"corner\"", "\n0 30 corner"));
        add("names_unterminated_" + n, replaced(*text, "\n0 30 \"corner\"", "\n0 30 \"corner"));
        add("names_missing_" + n, replaced(*text, "\n0 30 \"corner\"", "\n0 30"));
        add("names_twice_" + n, replaced(*text, "$EndPhysicalNames\n", "$EndPhysicalNames\n$PhysicalNames\n0\n$EndPhysicalNames\n"));
    }

    // binary files: patch values at known offsets
    {
        const size_t one = b41.find("4.1 1 8\n") + 8;
        add("b41_endianness", patched<uint32_t>(b41, one, 0x01000000u));
        add("b41_endianness_garbage", patched<uint32_t>(b41, one, 7u));
        const size_t nodes = b41.find("$Nodes\n") + 7;
        add("b41_nodes_count_huge", patched<uint64_t>(b41, nodes + 8, uint64_t{1} << 50));
        add("b41_nodes_count_size_t_max", patched<uint64_t>(b41, nodes + 8, ~uint64_t{0}));
        add("b41_node_blocks_huge", patched<uint64_t>(b41, nodes, uint64_t{1} << 40));
        add("b41_node_block_dim", patched<int32_t>(b41, nodes + 32, 7));
        add("b41_node_block_count_huge", patched<uint64_t>(b41, nodes + 44, uint64_t{1} << 33));
        add("b41_node_tag_zero", patched<uint64_t>(b41, nodes + 52, 0));
        add("b41_nan", patched<double>(b41, nodes + 60, std::nan("")));
        const size_t elements = b41.find("$Elements\n") + 10;
        add("b41_elements_count_huge", patched<uint64_t>(b41, elements + 8, uint64_t{1} << 60));
        add("b41_element_type", patched<int32_t>(b41, elements + 40, 1234));
        add("b41_element_block_huge", patched<uint64_t>(b41, elements + 44, uint64_t{1} << 45));
        add("b41_element_node_out_of_range", patched<uint64_t>(b41, elements + 60, 1000));
        // the line block: header at +68, element tag at +88, nodes at +96
        add("b41_line_type_in_curve", patched<int32_t>(b41, elements + 76, 2));
        add("b41_line_node_out_of_range", patched<uint64_t>(b41, elements + 96, 24));
        add("b41_line_node_zero", patched<uint64_t>(b41, elements + 104, 0));
        const size_t entities = b41.find("$Entities\n") + 10;
        add("b41_entities_count_huge", patched<uint64_t>(b41, entities, uint64_t{1} << 40));
        add("b41_missing_end", b41.substr(0, b41.rfind("$EndElements")));

        const size_t one22 = b22.find("2.2 1 8\n") + 8;
        add("b22_endianness", patched<uint32_t>(b22, one22, 0x01000000u));
        const size_t nodes22 = b22.find("$Nodes\n23\n") + 10;
        add("b22_node_tag_negative", patched<int32_t>(b22, nodes22, -5));
        add("b22_inf", patched<double>(b22, nodes22 + 4 + 16, HUGE_VAL));
        add("b22_nodes_count_large", replaced(b22, "$Nodes\n23\n", "$Nodes\n24\n"));
        const size_t el22 = b22.find("$Elements\n58\n") + 13;
        add("b22_follow_zero", patched<int32_t>(b22, el22 + 4, 0));
        add("b22_follow_too_many", patched<int32_t>(b22, el22 + 4, 59));
        add("b22_ntags_negative", patched<int32_t>(b22, el22 + 8, -1));
        add("b22_ntags_huge", patched<int32_t>(b22, el22 + 8, 1 << 30));
        add("b22_type_unknown", patched<int32_t>(b22, el22, 77));
        add("b22_element_node_out_of_range", patched<int32_t>(b22, el22 + 12 + 12, 24));
        add("b22_elements_count_large", replaced(b22, "$Elements\n58\n", "$Elements\n60\n"));
    }

    for (const Case& c : cases) {
        const std::string path = scratch("bad_" + c.name + ".msh");
        write_text(path, c.content);
        expect_io_error(c.name.c_str(), path);
    }
    const char* what = "malformed";
    CHECK(cases.size() >= 15, "only %zu cases", cases.size());
    std::printf("malformed: %zu corrupted files refused\n", cases.size());

    // a missing file
    try {
        bodt::read_gmsh(scratch("no_such_file.msh"));
        CHECK(false, "a missing file was read");
    } catch (const Error& e) {
        CHECK(e.status() == BODT_ERR_IO && std::strstr(e.what(), "no_such_file.msh"), "%s", e.what());
    }
}

void test_bad_write(void** /*state*/) {
    const char* what = "bad write";
    const MeshData d = make_mesh(0);
    for (int version : {0, 2, 4, 40, 23}) {
        try {
            bodt::write_gmsh(scratch("bad_version.msh"), d, version, false);
            CHECK(false, "version %d accepted", version);
        } catch (const Error& e) {
            CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT, "status %d", e.status());
        }
    }
    MeshData bad = d;
    bad.tets[5] = 27;
    try {
        bodt::write_gmsh(scratch("bad_index.msh"), bad, 41, false);
        CHECK(false, "an out-of-range tet vertex accepted");
    } catch (const Error& e) {
        CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT, "status %d", e.status());
    }
    bad = d;
    bad.edge_refs.pop_back();
    try {
        bodt::write_gmsh(scratch("bad_refs.msh"), bad, 22, true);
        CHECK(false, "edge refs that do not match the edges accepted");
    } catch (const Error& e) {
        CHECK(e.status() == BODT_ERR_INVALID_ARGUMENT && std::strstr(e.what(), "one ref per feature edge"), "%s",
              e.what());
    }
    try {
        bodt::write_gmsh(g_scratch + "/no/such/dir/x.msh", d, 41, false);
        CHECK(false, "writing into a missing directory succeeded");
    } catch (const Error& e) {
        CHECK(e.status() == BODT_ERR_IO, "status %d", e.status());
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s <tests/data dir> <scratch dir>\n", argv[0]);
        return 2;
    }
    g_data = argv[1];
    g_scratch = argv[2];
    mkdir(g_scratch.c_str(), 0755);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip), cmocka_unit_test(test_gmsh_files),
        cmocka_unit_test(test_entity_regions), cmocka_unit_test(test_sparse_tags),
        cmocka_unit_test(test_model), cmocka_unit_test(test_order),
        cmocka_unit_test(test_layout_as_read), cmocka_unit_test(test_layout_after_steps),
        cmocka_unit_test(test_layout_without_groups),
        cmocka_unit_test(test_malformed), cmocka_unit_test(test_bad_write),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
