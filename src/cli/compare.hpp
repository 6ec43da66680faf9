// `bodt compare ORIGINAL IMPROVED`: how much an improvement changed a mesh.
#pragma once

#include "bodt.h"
#include "cli/mesh_snapshot.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace bodt_cli {

struct MarkerArea {
    int32_t marker = 0;
    int64_t faces_before = 0, faces_after = 0;
    double area_before = 0.0, area_after = 0.0;
};

struct Comparison {
    bodt_quality before{}, after{};
    double volume_change = 0.0;      // improved minus original (signed volumes)
    double volume_change_rel = 0.0;  // divided by the original's volume
    // Paper 000 sec. 4, Table 2: the Hausdorff distance h between the
    // boundary surfaces divided by L, the largest side of the original's
    // bounding box.  h lies in [hausdorff, hausdorff_upper] (see
    // hausdorff.hpp); the relative values are these over L.
    double bbox_largest_side = 0.0;
    double hausdorff = 0.0, hausdorff_upper = 0.0;
    double hausdorff_rel = 0.0, hausdorff_rel_upper = 0.0;
    int32_t boundary_triangles_before = 0, boundary_triangles_after = 0;
    // Every marker of either mesh (0, unmarked, included), by marker.
    std::vector<MarkerArea> markers;
    // Every nonzero marker of the original is on some face of the improved.
    bool markers_kept = true;
    std::vector<int32_t> markers_lost;
};

void compare_meshes(const MeshSnapshot& original, const MeshSnapshot& improved, Comparison& c);
// The same with the domain boundaries of both (domain_boundary.hpp) given.
void compare_meshes(const MeshSnapshot& original, const MeshSnapshot& improved,
                    const std::vector<int32_t>& original_boundary, const std::vector<int32_t>& improved_boundary,
                    Comparison& c);

// The comparison on stdout: tables, or one JSON object.
void print_comparison(const Comparison& c, const std::string& original_name, const std::string& improved_name,
                      bool json);

}  // namespace bodt_cli
