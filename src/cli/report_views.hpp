// `bodt report`: where the worst tets are.  Three orthographic views of a
// mesh's boundary (top: seen from +z; front: from -y; side: from +x), drawn
// to one scale as inline SVG, with the worst tets marked at their centroids
// by numbered dots (the ranks of the report's table of worst tets).
//
// A view draws the boundary triangles that face it, shaded by their normal,
// far ones first (painter's order), when there are at most kMaxViewFaces of
// them; else, to keep the page small for big meshes, it draws the outline:
// the silhouette and the edges where the surface bends by more than 30
// degrees, the kMaxViewEdges longest on the page at most (no hidden-line
// removal).  A page with the views of two meshes of a million tets stays
// within a few MB.
#pragma once

#include "cli/mesh_snapshot.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bodt_cli {

constexpr size_t kMaxViewFaces = 6000;
constexpr size_t kMaxViewEdges = 8000;
const char* const kColorMark = "#d81b60";  // the dots of the worst tets

// The three views of mesh `m` (`boundary`: its domain_boundary), with the
// tets `marked` (0-based, worst first) numbered 1, 2, ...; `which` is
// "original" or "improved" (element ids and data-mesh).
std::string orthographic_views(const MeshSnapshot& m, const std::vector<int32_t>& boundary,
                               const std::vector<size_t>& marked, const std::string& which);

}  // namespace bodt_cli
