#include "cli/compare.hpp"

#include "cli/domain_boundary.hpp"
#include "cli/hausdorff.hpp"
#include "cli/quality_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

namespace bodt_cli {

namespace {

// The area of boundary face `f` of `m`.
double face_area(const MeshSnapshot& m, int32_t f) {
    const auto corner = [&](int k) {
        return &m.xyz[3 * static_cast<size_t>(m.faces[3 * static_cast<size_t>(f) + k] - m.base)];
    };
    const double *a = corner(0), *b = corner(1), *c = corner(2);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

}  // namespace

void compare_meshes(const MeshSnapshot& a, const MeshSnapshot& b, Comparison& c) {
    compare_meshes(a, b, domain_boundary(a), domain_boundary(b), c);
}

void compare_meshes(const MeshSnapshot& a, const MeshSnapshot& b, const std::vector<int32_t>& boundary_a,
                    const std::vector<int32_t>& boundary_b, Comparison& c) {
    c.before = a.quality;
    c.after = b.quality;
    c.volume_change = c.after.volume - c.before.volume;
    c.volume_change_rel = c.before.volume != 0.0 ? c.volume_change / c.before.volume : 0.0;

    TriangleSurface sa, sb;
    sa.xyz = a.xyz;
    sa.triangles = boundary_a;
    sb.xyz = b.xyz;
    sb.triangles = boundary_b;
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
        m.area_before += face_area(a, f);
    }
    for (int32_t f = 0; f < b.nfaces; ++f) {
        MarkerArea& m = by_marker[b.markers[f]];
        ++m.faces_after;
        m.area_after += face_area(b, f);
    }
    c.markers.clear();
    c.markers_lost.clear();
    for (auto& [marker, m] : by_marker) {
        m.marker = marker;
        c.markers.push_back(m);
        if (marker != 0 && m.faces_before > 0 && m.faces_after == 0) c.markers_lost.push_back(marker);
    }
    c.markers_kept = c.markers_lost.empty();
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
