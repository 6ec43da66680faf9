// TetGen .node/.ele/.face files, 0- or 1-based (the first node's number sets
// the base for all three files).
//   .node   n 3 nattr nbm, then  i x y z [attrs] [marker]   marker -> vertex ref
//   .ele    n 4 nattr,     then  i a b c d [attrs]    first attr -> region id
//   .face   n nbm,         then  i a b c [marker]     (optional file)
// Tets are read in the file's orientation; bodt_mesh_create detects a file
// whose tets are all negatively oriented (Stellar's convention).  Written
// files are 0-based, with the marker column in .node always (0 for a mesh
// without vertex refs).  The format has no notion of fixed vertices,
// corners or feature edges: they are not written (use Medit's
// RequiredVertices, Corners and Edges to keep them).
#include "io/mesh_io.hpp"
#include "io/output_file.hpp"
#include "io/text_scanner.hpp"

#include <cmath>
#include <fstream>

namespace bodt {

namespace {

std::string stem_of(const std::string& path) {
    const size_t dot = path.rfind('.');
    return path.substr(0, dot);
}

// A node number in the file's numbering, checked against the node count.
int32_t read_index(TextScanner& in, int64_t base, int64_t count, const char* what) {
    const int64_t v = in.read_int(what);
    if (v < base || v >= count + base)
        in.fail(std::string(what) + " " + std::to_string(v) + " is out of range: the .node file has " +
                std::to_string(count) + " nodes numbered from " + std::to_string(base));
    return static_cast<int32_t>(v);
}

// Each record starts with its number: base, base + 1, ...
void read_record_number(TextScanner& in, int64_t expected, const char* what) {
    const int64_t got = in.read_int(what);
    if (got != expected)
        in.fail(std::string(what) + " " + std::to_string(got) + " is out of sequence, expected " +
                std::to_string(expected));
}

int64_t read_nodes(const std::string& path, MeshData& d) {
    TextScanner in(path);
    const int64_t n = in.read_count("the node count", 8);
    if (n > INT32_MAX) in.fail("more than 2^31 - 1 nodes");
    if (in.read_int("the dimension") != 3) in.fail("only 3-D .node files are supported");
    const int64_t nattr = in.read_count("the attribute count", 0);
    const int64_t nbm = in.read_int("the boundary-marker flag");
    if (nattr > 1000 || nbm < 0 || nbm > 1) in.fail("unexpected .node header");
    d.xyz.resize(static_cast<size_t>(3 * n));
    if (nbm) d.vertex_refs.resize(static_cast<size_t>(n));
    int64_t base = 0;
    for (int64_t v = 0; v < n; ++v) {
        if (v == 0) {
            base = in.read_int("the first node number");
            if (base != 0 && base != 1) in.fail("nodes must be numbered from 0 or 1, not " + std::to_string(base));
        } else {
            read_record_number(in, base + v, "node number");
        }
        for (int k = 0; k < 3; ++k) d.xyz[3 * v + k] = in.read_double("a node coordinate");
        for (int64_t a = 0; a < nattr; ++a) in.expect("a node attribute");
        if (nbm) {
            const int64_t marker = in.read_int("a node boundary marker");
            if (marker < INT32_MIN || marker > INT32_MAX) in.fail("the node boundary marker does not fit in 32 bits");
            d.vertex_refs[v] = static_cast<int32_t>(marker);
        }
    }
    return base;
}

void read_elements(const std::string& path, int64_t base, int64_t nverts, MeshData& d) {
    TextScanner in(path);
    const int64_t n = in.read_count("the tet count", 10);
    if (n > INT32_MAX) in.fail("more than 2^31 - 1 tets");
    const int64_t corners = in.read_int("the nodes per tet");
    if (corners != 4) in.fail("only linear tets (4 nodes) are supported, the file has " + std::to_string(corners));
    const int64_t nattr = in.read_count("the attribute count", 0);
    if (nattr > 1000) in.fail("unexpected .ele header");
    d.tets.resize(static_cast<size_t>(4 * n));
    if (nattr > 0) d.regions.resize(static_cast<size_t>(n));
    for (int64_t t = 0; t < n; ++t) {
        read_record_number(in, base + t, "tet number");
        for (int k = 0; k < 4; ++k) d.tets[4 * t + k] = read_index(in, base, nverts, "tet node");
        for (int64_t a = 0; a < nattr; ++a) {
            const double attr = in.read_double("a tet attribute");
            if (a > 0) continue;
            if (attr != std::round(attr) || std::abs(attr) > INT32_MAX)
                in.fail("the region attribute " + std::to_string(attr) + " is not a 32-bit integer");
            d.regions[t] = static_cast<int32_t>(attr);
        }
    }
}

void read_faces(const std::string& path, int64_t base, int64_t nverts, MeshData& d) {
    TextScanner in(path);
    const int64_t n = in.read_count("the face count", 8);
    const int64_t nbm = in.read_int("the boundary-marker flag");
    if (nbm < 0 || nbm > 1) in.fail("unexpected .face header");
    for (int64_t f = 0; f < n; ++f) {
        read_record_number(in, base + f, "face number");
        for (int k = 0; k < 3; ++k) d.triangles.push_back(read_index(in, base, nverts, "face node"));
        const int64_t marker = nbm ? in.read_int("a face marker") : 1;
        if (marker < INT32_MIN || marker > INT32_MAX) in.fail("the face marker does not fit in 32 bits");
        d.tri_markers.push_back(static_cast<int32_t>(marker));
    }
}

}  // namespace

MeshData read_tetgen(const std::string& path) {
    const std::string stem = stem_of(path);
    MeshData d;
    const int64_t base = read_nodes(stem + ".node", d);
    d.base = static_cast<int>(base);
    const int64_t nverts = static_cast<int64_t>(d.xyz.size() / 3);
    read_elements(stem + ".ele", base, nverts, d);
    if (std::ifstream(stem + ".face").good()) read_faces(stem + ".face", base, nverts, d);
    return d;
}

void write_tetgen(const std::string& path, const MeshData& d) {
    const std::string stem = stem_of(path);
    const size_t nv = d.xyz.size() / 3, nt = d.tets.size() / 4, nf = d.tri_markers.size();
    const int shift = -d.base;  // written 0-based
    {
        OutputFile out(stem + ".node");
        std::fprintf(out.get(), "%zu 3 0 1\n", nv);
        for (size_t v = 0; v < nv; ++v)
            std::fprintf(out.get(), "%zu %.17g %.17g %.17g %d\n", v, d.xyz[3 * v], d.xyz[3 * v + 1], d.xyz[3 * v + 2],
                         d.vertex_refs.empty() ? 0 : d.vertex_refs[v]);
        out.close();
    }
    {
        const bool regions = !d.regions.empty();
        OutputFile out(stem + ".ele");
        std::fprintf(out.get(), "%zu 4 %d\n", nt, regions ? 1 : 0);
        for (size_t t = 0; t < nt; ++t) {
            std::fprintf(out.get(), "%zu %d %d %d %d", t, d.tets[4 * t] + shift, d.tets[4 * t + 1] + shift,
                         d.tets[4 * t + 2] + shift, d.tets[4 * t + 3] + shift);
            if (regions) std::fprintf(out.get(), " %d", d.regions[t]);
            std::fputc('\n', out.get());
        }
        out.close();
    }
    {
        OutputFile out(stem + ".face");
        std::fprintf(out.get(), "%zu 1\n", nf);
        for (size_t f = 0; f < nf; ++f)
            std::fprintf(out.get(), "%zu %d %d %d %d\n", f, d.triangles[3 * f] + shift, d.triangles[3 * f + 1] + shift,
                         d.triangles[3 * f + 2] + shift, d.tri_markers[f]);
        out.close();
    }
}

}  // namespace bodt
