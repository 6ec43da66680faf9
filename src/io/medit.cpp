// Medit .mesh (ASCII): the format of MMG, CGAL and many FEA tools.
//   Vertices     x y z ref        ref -> vertex ref
//   Tetrahedra   a b c d ref      ref -> region id
//   Triangles    a b c ref        ref -> face marker
//   Edges        a b ref          -> feature edges with their refs
//   Ridges       e                -> checked; every edge is a feature edge
//   Corners      v                -> corners
//   RequiredVertices v            -> fixed vertices
// Every listed edge is a feature edge: MMG keeps its reference edges as
// lines as it keeps its ridges, and Gmsh and CGAL list their feature curves
// there.  Other sections of the format are skipped by their known record
// sizes; an unknown keyword is an error.  Indices in the file are 1-based.
//
// A section other than Vertices may come more than once: meshio writes one
// section per cell block (a Tetrahedra section per region, a Triangles
// section per marker).  Repeated sections are appended in file order, and
// Ridges number the edges of all Edges sections in that order.  libMeshb
// (Medit's own library) keeps one file position per keyword, so it reads
// only the last section of each; appending reads meshio's files as meshio
// meant them.  A second Vertices section is an error: the indices after it
// would be ambiguous.
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/text_scanner.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <cstdio>

namespace bodt {

namespace {

// Sections read for their data.
enum class Section { Vertices, Tetrahedra, Triangles, Corners, Required, Edges, Ridges, Skip };

struct Keyword {
    const char* name;
    Section section;
    int fields;  // numbers per record (for skipped sections)
};

constexpr Keyword kKeywords[] = {
    {"Vertices", Section::Vertices, 4},
    {"Tetrahedra", Section::Tetrahedra, 5},
    {"Triangles", Section::Triangles, 4},
    {"Corners", Section::Corners, 1},
    {"RequiredVertices", Section::Required, 1},
    {"Edges", Section::Edges, 3},
    {"Ridges", Section::Ridges, 1},
    {"RequiredEdges", Section::Skip, 1},
    {"RequiredTriangles", Section::Skip, 1},
    {"RequiredTetrahedra", Section::Skip, 1},
    {"Quadrilaterals", Section::Skip, 5},
    {"RequiredQuadrilaterals", Section::Skip, 1},
    {"Prisms", Section::Skip, 7},
    {"Pyramids", Section::Skip, 6},
    {"Hexahedra", Section::Skip, 9},
    {"Normals", Section::Skip, 3},
    {"Tangents", Section::Skip, 3},
    {"NormalAtVertices", Section::Skip, 2},
    {"NormalAtTriangleVertices", Section::Skip, 3},
    {"NormalAtQuadrilateralVertices", Section::Skip, 3},
    {"TangentAtVertices", Section::Skip, 2},
    {"TangentAtEdges", Section::Skip, 3},
};

const Keyword* find_keyword(std::string_view token) {
    for (const Keyword& k : kKeywords)
        if (token == k.name) return &k;
    return nullptr;
}

// A 1-based vertex index from the file, checked against the vertex count.
int32_t read_vertex(TextScanner& in, int64_t nverts, const char* what) {
    const int64_t v = in.read_int(what);
    if (v < 1 || v > nverts)
        in.fail(std::string(what) + " " + std::to_string(v) + " is out of range: the file has " +
                std::to_string(nverts) + " vertices (numbered from 1)");
    return static_cast<int32_t>(v);
}

int32_t read_ref(TextScanner& in, const char* what) {
    const int64_t r = in.read_int(what);
    if (r < INT32_MIN || r > INT32_MAX) in.fail(std::string(what) + " does not fit in 32 bits");
    return static_cast<int32_t>(r);
}

}  // namespace

MeshData read_medit(const std::string& path) {
    TextScanner in(path);
    MeshData d;
    d.base = 1;
    int64_t nverts = -1;
    int64_t vertices_line = 0;  // of the Vertices keyword, once seen
    bool saw_tets = false;
    std::vector<std::pair<int64_t, int64_t>> ridges;  // 1-based index into all edges, line
    std::string_view token;
    if (!in.next(token) || token != "MeshVersionFormatted")
        in.fail("not a Medit mesh: it must start with MeshVersionFormatted");
    const int64_t version = in.read_int("the version");
    if (version < 1 || version > 4) in.fail("unknown MeshVersionFormatted " + std::to_string(version));
    while (in.next(token)) {
        if (token == "End") break;
        if (token == "Dimension") {
            const int64_t dim = in.read_int("the dimension");
            if (dim != 3) in.fail("only 3-D meshes are supported, the file has Dimension " + std::to_string(dim));
            continue;
        }
        const Keyword* key = find_keyword(token);
        if (!key) in.fail("unknown keyword '" + std::string(token) + "'");
        if (key->section == Section::Vertices) {
            if (vertices_line > 0)
                in.fail("a second Vertices section (the first at line " + std::to_string(vertices_line) +
                        "): the vertex indices would be ambiguous");
            vertices_line = in.line();
        }
        const int64_t n = in.read_count(key->name, 2 * key->fields);
        const bool needs_vertices = key->section != Section::Vertices && key->section != Section::Skip;
        if (needs_vertices && nverts < 0) in.fail(std::string(key->name) + " comes before Vertices");
        switch (key->section) {
            case Section::Vertices:
                if (n > INT32_MAX) in.fail("more than 2^31 - 1 vertices");
                nverts = n;
                d.xyz.resize(static_cast<size_t>(3 * n));
                d.vertex_refs.resize(static_cast<size_t>(n));
                for (int64_t v = 0; v < n; ++v) {
                    for (int k = 0; k < 3; ++k) d.xyz[3 * v + k] = in.read_double("a vertex coordinate");
                    d.vertex_refs[v] = read_ref(in, "vertex reference");
                }
                break;
            case Section::Tetrahedra:
                if (n > INT32_MAX - static_cast<int64_t>(d.regions.size())) in.fail("more than 2^31 - 1 tets");
                saw_tets = true;
                for (int64_t t = 0; t < n; ++t) {
                    for (int k = 0; k < 4; ++k) d.tets.push_back(read_vertex(in, nverts, "tet vertex"));
                    d.regions.push_back(read_ref(in, "tet reference"));
                }
                break;
            case Section::Triangles:
                for (int64_t f = 0; f < n; ++f) {
                    for (int k = 0; k < 3; ++k) d.triangles.push_back(read_vertex(in, nverts, "triangle vertex"));
                    d.tri_markers.push_back(read_ref(in, "triangle reference"));
                }
                break;
            case Section::Corners:
                for (int64_t k = 0; k < n; ++k) d.corners.push_back(read_vertex(in, nverts, key->name));
                break;
            case Section::Required:
                for (int64_t k = 0; k < n; ++k) d.fixed.push_back(read_vertex(in, nverts, key->name));
                break;
            case Section::Edges:
                for (int64_t e = 0; e < n; ++e) {
                    d.feature_edges.push_back(read_vertex(in, nverts, "edge vertex"));
                    d.feature_edges.push_back(read_vertex(in, nverts, "edge vertex"));
                    d.edge_refs.push_back(read_ref(in, "edge reference"));
                }
                break;
            case Section::Ridges:
                for (int64_t k = 0; k < n; ++k) {
                    const int64_t r = in.read_int("a ridge");
                    ridges.emplace_back(r, in.line());
                }
                break;
            case Section::Skip:
                for (int64_t k = 0; k < n * key->fields; ++k) in.expect(key->name);
                break;
        }
    }
    if (nverts < 0) in.fail("no Vertices section");
    if (!saw_tets) in.fail("no Tetrahedra section");
    const int64_t nedges = static_cast<int64_t>(d.edge_refs.size());
    for (const auto& [r, line] : ridges)
        if (r < 1 || r > nedges)
            throw Error(BODT_ERR_IO, path + ":" + std::to_string(line) + ": ridge " + std::to_string(r) +
                                         " is not one of the " + std::to_string(nedges) + " edges");
    return d;
}

void write_medit(const std::string& path, const MeshData& d) {
    const int shift = 1 - d.base;  // Medit counts from 1
    OutputFile out(path);
    FILE* o = out.get();
    const size_t nv = d.xyz.size() / 3, nt = d.tets.size() / 4, nf = d.tri_markers.size();
    std::fprintf(o, "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n%zu\n", nv);
    for (size_t v = 0; v < nv; ++v)
        std::fprintf(o, "%.17g %.17g %.17g %d\n", d.xyz[3 * v], d.xyz[3 * v + 1], d.xyz[3 * v + 2],
                     d.vertex_refs.empty() ? 0 : d.vertex_refs[v]);
    std::fprintf(o, "\nTriangles\n%zu\n", nf);
    for (size_t k = 0; k < nf; ++k)
        std::fprintf(o, "%d %d %d %d\n", d.triangles[3 * k] + shift, d.triangles[3 * k + 1] + shift,
                     d.triangles[3 * k + 2] + shift, d.tri_markers[k]);
    std::fprintf(o, "\nTetrahedra\n%zu\n", nt);
    for (size_t t = 0; t < nt; ++t)
        std::fprintf(o, "%d %d %d %d %d\n", d.tets[4 * t] + shift, d.tets[4 * t + 1] + shift, d.tets[4 * t + 2] + shift,
                     d.tets[4 * t + 3] + shift, d.regions.empty() ? 0 : d.regions[t]);
    if (!d.corners.empty()) {
        std::fprintf(o, "\nCorners\n%zu\n", d.corners.size());
        for (int32_t v : d.corners) std::fprintf(o, "%d\n", v + shift);
    }
    if (!d.fixed.empty()) {
        std::fprintf(o, "\nRequiredVertices\n%zu\n", d.fixed.size());
        for (int32_t v : d.fixed) std::fprintf(o, "%d\n", v + shift);
    }
    const size_t ne = d.feature_edges.size() / 2;
    if (ne > 0) {
        std::fprintf(o, "\nEdges\n%zu\n", ne);
        for (size_t e = 0; e < ne; ++e)
            std::fprintf(o, "%d %d %d\n", d.feature_edges[2 * e] + shift, d.feature_edges[2 * e + 1] + shift,
                         d.edge_refs.empty() ? 0 : d.edge_refs[e]);
        std::fprintf(o, "\nRidges\n%zu\n", ne);
        for (size_t e = 0; e < ne; ++e) std::fprintf(o, "%zu\n", e + 1);
    }
    std::fprintf(o, "\nEnd\n");
    out.close();
}

}  // namespace bodt
