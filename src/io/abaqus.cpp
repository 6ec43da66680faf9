// Abaqus / CalculiX .inp writer: see abaqus.hpp.  Besides NSET FIXED, one
// node set REF_<r> per nonzero vertex ref r (REF_N<r> for a negative one):
// the nodes a boundary condition given on the Medit / TetGen vertex refs
// applies to.  Ref 0 means "no ref" and gets no set.  Per face marker, a
// node set besides the surface: *BOUNDARY takes nodes, *DSLOAD faces.
#include "io/abaqus.hpp"

#include "io/output_file.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <map>
#include <vector>

namespace bodt {

namespace {

// C3D4 face k (S<k+1>) as local vertex indices.
constexpr int kC3D4Face[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
constexpr int kMaxPerLine = 16;

std::string id_name(int32_t id) {
    return id < 0 ? "N" + std::to_string(-static_cast<int64_t>(id)) : std::to_string(id);
}

// A coordinate in at most 20 characters: CalculiX reads only the first 20
// characters of a number field (silently dropping the rest, or failing on a
// cut exponent).  The shortest representation that reads back exactly
// (std::to_chars, exponent without leading zeros) fits for most values;
// otherwise the most significant digits that fit (at least 15 for any
// finite double).
std::string format_coordinate(double x) {
    auto shorten_exponent = [](std::string s) {
        const size_t e = s.find_first_of("eE");
        if (e == std::string::npos) return s;
        size_t d = e + 1;
        if (d < s.size() && (s[d] == '-' || s[d] == '+')) ++d;
        size_t z = d;
        while (z + 1 < s.size() && s[z] == '0') ++z;
        s.erase(d, z - d);
        if (s[e + 1] == '+') s.erase(e + 1, 1);
        return s;
    };
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    std::string s = shorten_exponent(std::string(buf, r.ptr));
    for (int precision = 16; s.size() > 20 && precision > 0; --precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, x);
        s = shorten_exponent(buf);
    }
    return s;
}

// Writes `ids` (1-based numbers) at most 16 per line.
void write_list(FILE* o, const std::vector<int64_t>& ids) {
    for (size_t k = 0; k < ids.size(); ++k) {
        const bool last_on_line = (k + 1) % kMaxPerLine == 0 || k + 1 == ids.size();
        std::fprintf(o, "%lld%s", static_cast<long long>(ids[k]), last_on_line ? "\n" : ", ");
    }
}

}  // namespace

void write_abaqus(const std::string& path, const MeshData& d) {
    const size_t nv = d.xyz.size() / 3, nt = d.tets.size() / 4, nf = d.triangles.size() / 3;
    auto invalid = [&](const std::string& message) {
        throw Error(BODT_ERR_INVALID_ARGUMENT, "writing '" + path + "': " + message);
    };
    if (d.xyz.size() % 3 || d.tets.size() % 4 || d.triangles.size() % 3)
        invalid("an array size is not a multiple of its record size");
    if (!d.regions.empty() && d.regions.size() != nt) invalid("regions must have one value per tet");
    if (d.tri_markers.size() != nf) invalid("tri_markers must have one value per triangle");
    if (!d.vertex_refs.empty() && d.vertex_refs.size() != nv) invalid("vertex_refs must have one value per vertex");
    const int64_t base = d.base;
    auto node = [&](int32_t v) {
        const int64_t i = static_cast<int64_t>(v) - base;
        if (i < 0 || i >= static_cast<int64_t>(nv)) invalid("vertex " + std::to_string(v) + " is out of range");
        return i + 1;
    };
    for (int32_t v : d.tets) node(v);
    for (int32_t v : d.triangles) node(v);
    for (int32_t v : d.fixed) node(v);

    // For each marked triangle, the first tet (and its face) that has it:
    // marked triangles sorted by their sorted vertices, looked up per tet face.
    using Key = std::array<int32_t, 3>;
    auto key_of = [](int32_t a, int32_t b, int32_t c) {
        Key k = {a, b, c};
        std::sort(k.begin(), k.end());
        return k;
    };
    std::vector<std::pair<Key, size_t>> marked(nf);
    for (size_t f = 0; f < nf; ++f)
        marked[f] = {key_of(d.triangles[3 * f], d.triangles[3 * f + 1], d.triangles[3 * f + 2]), f};
    std::sort(marked.begin(), marked.end());
    std::vector<int64_t> face_elem(nf, 0);  // 1-based element, 0 = not found yet
    std::vector<int> face_side(nf, 0);
    for (size_t t = 0; t < nt && !marked.empty(); ++t) {
        const int32_t* v = &d.tets[4 * t];
        for (int k = 0; k < 4; ++k) {
            const Key key = key_of(v[kC3D4Face[k][0]], v[kC3D4Face[k][1]], v[kC3D4Face[k][2]]);
            auto it = std::lower_bound(marked.begin(), marked.end(), std::make_pair(key, size_t{0}));
            for (; it != marked.end() && it->first == key; ++it) {
                if (face_elem[it->second] != 0) continue;
                face_elem[it->second] = static_cast<int64_t>(t) + 1;
                face_side[it->second] = k;
            }
        }
    }
    for (size_t f = 0; f < nf; ++f)
        if (face_elem[f] == 0)
            invalid("marked triangle " + std::to_string(f) + " (" + std::to_string(d.triangles[3 * f]) + " " +
                    std::to_string(d.triangles[3 * f + 1]) + " " + std::to_string(d.triangles[3 * f + 2]) +
                    ") is not a face of any tet");

    OutputFile out(path);
    FILE* o = out.get();
    std::fprintf(o, "*HEADING\nlibbodt tetrahedral mesh: %zu nodes, %zu C3D4 elements\n", nv, nt);
    std::fprintf(o, "*NODE\n");
    for (size_t v = 0; v < nv; ++v)
        std::fprintf(o, "%zu, %s, %s, %s\n", v + 1, format_coordinate(d.xyz[3 * v]).c_str(),
                     format_coordinate(d.xyz[3 * v + 1]).c_str(), format_coordinate(d.xyz[3 * v + 2]).c_str());

    auto write_element = [&](size_t t) {
        std::fprintf(o, "%zu, %lld, %lld, %lld, %lld\n", t + 1, static_cast<long long>(node(d.tets[4 * t])),
                     static_cast<long long>(node(d.tets[4 * t + 1])), static_cast<long long>(node(d.tets[4 * t + 2])),
                     static_cast<long long>(node(d.tets[4 * t + 3])));
    };
    if (d.regions.empty()) {
        if (nt > 0) std::fprintf(o, "*ELEMENT, TYPE=C3D4, ELSET=ALL\n");
        for (size_t t = 0; t < nt; ++t) write_element(t);
    } else {
        std::map<int32_t, std::vector<size_t>> by_region;
        for (size_t t = 0; t < nt; ++t) by_region[d.regions[t]].push_back(t);
        for (const auto& [region, tets] : by_region) {
            std::fprintf(o, "*ELEMENT, TYPE=C3D4, ELSET=REGION_%s\n", id_name(region).c_str());
            for (size_t t : tets) write_element(t);
        }
        if (nt > 0) std::fprintf(o, "*ELSET, ELSET=ALL, GENERATE\n1, %zu, 1\n", nt);
    }

    if (nv > 0) std::fprintf(o, "*NSET, NSET=NALL, GENERATE\n1, %zu, 1\n", nv);
    if (!d.fixed.empty()) {
        std::vector<int64_t> ids;
        for (int32_t v : d.fixed) ids.push_back(node(v));
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        std::fprintf(o, "*NSET, NSET=FIXED\n");
        write_list(o, ids);
    }
    // Per nonzero vertex ref, its nodes (in increasing order).
    std::map<int32_t, std::vector<int64_t>> by_ref;
    for (size_t v = 0; v < d.vertex_refs.size(); ++v)
        if (d.vertex_refs[v] != 0) by_ref[d.vertex_refs[v]].push_back(static_cast<int64_t>(v) + 1);
    for (const auto& [ref, ids] : by_ref) {
        std::fprintf(o, "*NSET, NSET=REF_%s\n", id_name(ref).c_str());
        write_list(o, ids);
    }

    // Per marker, its nodes, and per face number its elements (sorted, each once).
    std::map<int32_t, std::vector<int64_t>> marker_nodes;
    std::map<int32_t, std::array<std::vector<int64_t>, 4>> surfaces;
    for (size_t f = 0; f < nf; ++f) {
        for (int k = 0; k < 3; ++k) marker_nodes[d.tri_markers[f]].push_back(node(d.triangles[3 * f + k]));
        surfaces[d.tri_markers[f]][face_side[f]].push_back(face_elem[f]);
    }
    for (auto& [m, ids] : marker_nodes) {
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        std::fprintf(o, "*NSET, NSET=MARKER_%s_NODES\n", id_name(m).c_str());
        write_list(o, ids);
    }
    for (auto& [m, sides] : surfaces) {
        const std::string name = "MARKER_" + id_name(m);
        for (int k = 0; k < 4; ++k) {
            std::vector<int64_t>& elems = sides[k];
            if (elems.empty()) continue;
            std::sort(elems.begin(), elems.end());
            elems.erase(std::unique(elems.begin(), elems.end()), elems.end());
            std::fprintf(o, "*ELSET, ELSET=%s_S%d\n", name.c_str(), k + 1);
            write_list(o, elems);
        }
        std::fprintf(o, "*SURFACE, TYPE=ELEMENT, NAME=%s\n", name.c_str());
        for (int k = 0; k < 4; ++k)
            if (!sides[k].empty()) std::fprintf(o, "%s_S%d, S%d\n", name.c_str(), k + 1, k + 1);
    }
    out.close();
}

}  // namespace bodt
