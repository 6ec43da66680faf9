#include "cli/compare.hpp"

#include "cli/hausdorff.hpp"
#include "cli/quality_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

namespace bodt_cli {

namespace {

struct Arrays {
    int32_t nverts = 0, ntets = 0, nfaces = 0;
    std::vector<double> xyz;
    std::vector<int32_t> tets, faces, markers;
};

bool read_arrays(const bodt_mesh* mesh, Arrays& m, std::string& error) {
    int status = bodt_mesh_get_counts(mesh, &m.nverts, &m.ntets, &m.nfaces);
    if (status == BODT_OK) {
        m.xyz.resize(3 * static_cast<size_t>(m.nverts));
        m.tets.resize(4 * static_cast<size_t>(m.ntets));
        m.faces.resize(3 * static_cast<size_t>(m.nfaces));
        m.markers.resize(static_cast<size_t>(m.nfaces));
        status = bodt_mesh_get_vertices(mesh, m.xyz.data(), m.xyz.size());
    }
    if (status == BODT_OK) status = bodt_mesh_get_tets(mesh, m.tets.data(), m.tets.size());
    if (status == BODT_OK && m.nfaces > 0)
        status = bodt_mesh_get_boundary_faces(mesh, m.faces.data(), m.markers.data(), m.markers.size());
    if (status != BODT_OK) {
        error = bodt_mesh_last_error(mesh);
        return false;
    }
    return true;
}

// The domain boundary: the faces of exactly one tet (interfaces between
// regions and marked internal faces are not part of the shape; paper 000
// compares the surface meshes of the models).  Indices are the handle's,
// 0-based (meshes read by the command are).
TriangleSurface domain_boundary(const Arrays& m) {
    std::vector<std::array<int32_t, 3>> faces;
    faces.reserve(4 * static_cast<size_t>(m.ntets));
    static const int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    for (size_t t = 0; t < static_cast<size_t>(m.ntets); ++t)
        for (const auto& f : kFace) {
            std::array<int32_t, 3> key = {m.tets[4 * t + f[0]], m.tets[4 * t + f[1]], m.tets[4 * t + f[2]]};
            std::sort(key.begin(), key.end());
            faces.push_back(key);
        }
    std::sort(faces.begin(), faces.end());
    TriangleSurface s;
    s.xyz = m.xyz;
    for (size_t k = 0; k < faces.size();) {
        size_t j = k;
        while (j < faces.size() && faces[j] == faces[k]) ++j;
        if (j - k == 1) s.triangles.insert(s.triangles.end(), faces[k].begin(), faces[k].end());
        k = j;
    }
    return s;
}

double triangle_area(const std::vector<double>& xyz, const int32_t* f) {
    const double* a = &xyz[3 * static_cast<size_t>(f[0])];
    const double* b = &xyz[3 * static_cast<size_t>(f[1])];
    const double* c = &xyz[3 * static_cast<size_t>(f[2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

}  // namespace

bool compare_meshes(const bodt_mesh* original, const bodt_mesh* improved, Comparison& c, std::string& error) {
    Arrays a, b;
    if (!read_arrays(original, a, error) || !read_arrays(improved, b, error)) return false;
    c.before = measure(original);
    c.after = measure(improved);
    c.volume_change = c.after.volume - c.before.volume;
    c.volume_change_rel = c.before.volume != 0.0 ? c.volume_change / c.before.volume : 0.0;

    const TriangleSurface sa = domain_boundary(a), sb = domain_boundary(b);
    c.boundary_triangles_before = static_cast<int32_t>(sa.triangles.size() / 3);
    c.boundary_triangles_after = static_cast<int32_t>(sb.triangles.size() / 3);
    // L: the largest side of the original's bounding box (paper 000, the
    // text above Table 2: "L be the largest side length of the bounding box
    // of the original mesh"), over the boundary's vertices.
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const int32_t v : sa.triangles)
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], a.xyz[3 * static_cast<size_t>(v) + k]);
            hi[k] = std::max(hi[k], a.xyz[3 * static_cast<size_t>(v) + k]);
        }
    c.bbox_largest_side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 0.0});
    // Tolerance: 1e-7 L absolute plus 1e-3 of the distance itself (paper
    // 000 gives two significant digits); a budget of distance queries keeps
    // large meshes quick (the upper bound then says how close the value is).
    const int64_t budget = 300000 + 20 * static_cast<int64_t>(sa.triangles.size() + sb.triangles.size()) / 3;
    const HausdorffBounds h = hausdorff_distance(sa, sb, 1e-7 * c.bbox_largest_side, 1e-3, budget);
    // Closest points are computed with round-off (a triangle's centroid is
    // some 1e-16 L off the triangle): distances below 1e-14 L are 0, so a
    // mesh compared with itself, or with a lossless copy, gives exactly 0.
    const double zero = 1e-14 * c.bbox_largest_side;
    c.hausdorff = h.lower <= zero ? 0.0 : h.lower;
    c.hausdorff_upper = h.upper <= zero ? 0.0 : h.upper;
    const double L = c.bbox_largest_side > 0.0 ? c.bbox_largest_side : 1.0;
    c.hausdorff_rel = c.hausdorff / L;
    c.hausdorff_rel_upper = c.hausdorff_upper / L;

    std::map<int32_t, MarkerArea> by_marker;
    for (int32_t f = 0; f < a.nfaces; ++f) {
        MarkerArea& m = by_marker[a.markers[f]];
        ++m.faces_before;
        m.area_before += triangle_area(a.xyz, &a.faces[3 * static_cast<size_t>(f)]);
    }
    for (int32_t f = 0; f < b.nfaces; ++f) {
        MarkerArea& m = by_marker[b.markers[f]];
        ++m.faces_after;
        m.area_after += triangle_area(b.xyz, &b.faces[3 * static_cast<size_t>(f)]);
    }
    c.markers.clear();
    c.markers_lost.clear();
    for (auto& [marker, m] : by_marker) {
        m.marker = marker;
        c.markers.push_back(m);
        if (marker != 0 && m.faces_before > 0 && m.faces_after == 0) c.markers_lost.push_back(marker);
    }
    c.markers_kept = c.markers_lost.empty();
    return true;
}

void print_comparison(const Comparison& c, const std::string& original_name, const std::string& improved_name,
                      bool json) {
    if (json) {
        std::printf("{\"original\": %s, \"improved\": %s, \"volume_before\": %.17g, \"volume_after\": %.17g, "
                    "\"volume_change\": %.17g, \"volume_change_rel\": %.17g, \"bbox_largest_side\": %.17g, "
                    "\"hausdorff\": %.17g, \"hausdorff_upper\": %.17g, \"hausdorff_rel\": %.17g, "
                    "\"hausdorff_rel_upper\": %.17g, \"boundary_triangles\": [%d, %d], \"markers\": [",
                    json_string(original_name).c_str(), json_string(improved_name).c_str(), c.before.volume,
                    c.after.volume, c.volume_change, c.volume_change_rel, c.bbox_largest_side, c.hausdorff,
                    c.hausdorff_upper, c.hausdorff_rel, c.hausdorff_rel_upper, c.boundary_triangles_before,
                    c.boundary_triangles_after);
        for (size_t k = 0; k < c.markers.size(); ++k) {
            const MarkerArea& m = c.markers[k];
            std::printf("%s{\"marker\": %d, \"faces_before\": %lld, \"faces_after\": %lld, \"area_before\": %.17g, "
                        "\"area_after\": %.17g}",
                        k ? ", " : "", m.marker, static_cast<long long>(m.faces_before),
                        static_cast<long long>(m.faces_after), m.area_before, m.area_after);
        }
        std::printf("], \"markers_kept\": %s, \"markers_lost\": [", c.markers_kept ? "true" : "false");
        for (size_t k = 0; k < c.markers_lost.size(); ++k) std::printf("%s%d", k ? ", " : "", c.markers_lost[k]);
        std::printf("], \"quality_before\": {%s}, \"quality_after\": {%s}}\n",
                    quality_json_members(c.before, false).c_str(), quality_json_members(c.after, false).c_str());
        return;
    }
    std::printf("original: %s\nimproved: %s\n\n", original_name.c_str(), improved_name.c_str());
    print_table(&c.before, c.after);
    std::printf("\nvolume change     %.6g (%+.6g %%)\n", c.volume_change, 100.0 * c.volume_change_rel);
    std::printf("Hausdorff dist.   %.6g (boundary surfaces, %d and %d triangles)\n", c.hausdorff,
                c.boundary_triangles_before, c.boundary_triangles_after);
    if (c.hausdorff_upper > c.hausdorff * (1.0 + 1e-3) + 1e-7 * c.bbox_largest_side)
        std::printf("                  at most %.6g (the search stopped at its budget)\n", c.hausdorff_upper);
    std::printf("relative          %.6g %% of L = %.6g, the largest side of the original's bounding box\n",
                100.0 * c.hausdorff_rel, c.bbox_largest_side);
    std::printf("\n%-8s %12s %12s %16s %16s\n", "marker", "faces before", "faces after", "area before", "area after");
    for (const MarkerArea& m : c.markers)
        std::printf("%-8d %12lld %12lld %16.8g %16.8g\n", m.marker, static_cast<long long>(m.faces_before),
                    static_cast<long long>(m.faces_after), m.area_before, m.area_after);
    if (c.markers_kept) {
        std::printf("markers kept: yes\n");
    } else {
        std::printf("markers kept: no; lost:");
        for (const int32_t m : c.markers_lost) std::printf(" %d", m);
        std::printf("\n");
    }
}

}  // namespace bodt_cli
