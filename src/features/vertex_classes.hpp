// Which way each vertex may move (paper 000 sec. 2.2, Algorithm 3):
// inner vertices anywhere (ODT), surface vertices in their tangent plane,
// feature-line vertices along the line, corners not at all.
//
// Classification combines three sources, strongest class winning:
//  - feature edges: surface edges whose two faces' normals differ by more
//    than the feature angle, edges where more than two surface faces meet
//    (an interface reaching the boundary), and edges the caller marked.  A
//    vertex on two feature edges lies on a feature line, unless the line
//    turns there by more than the feature angle; on one or three or more
//    feature edges it is a corner;
//  - the tensor-voting matrix M = sum_i S_i n_i n_i^T of eq. (11), with
//    eigenvalues mu0 >= mu1 >= mu2: mu1/mu0 above the edge ratio makes a
//    feature line along e2, mu2/mu0 above the corner ratio a corner (the
//    paper's "much greater" and "about equal", made explicit);
//  - the caller's fixed vertices, which never move.
#pragma once

#include "mesh/region_surfaces.hpp"
#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <vector>

namespace bodt {

// Values match enum bodt_vertex_class in bodt.h.
enum class VertexClass : uint8_t { Interior = 0, Surface = 1, FeatureLine = 2, Corner = 3, Fixed = 4, Unused = 5 };

struct FeatureSettings {
    double feature_angle_deg = 30.0;
    double edge_ratio = 0.2;
    double corner_ratio = 0.2;
    bool detect_features = true;  // false: every surface vertex is a Surface vertex (Alg. 2 only)
};

struct VertexClasses {
    std::vector<VertexClass> cls;
    // For a FeatureLine vertex found through its feature edges: the two
    // neighbours along the line (the line's direction is their chord);
    // {-1, -1} when the line came from tensor voting (direction e2).
    std::vector<std::array<int32_t, 2>> line;
    // The feature edges the classes came from (detected and the caller's).
    EdgeSet feature_edges;
};

// The caller's feature edges come from mesh.feature_edges.
VertexClasses classify_vertices(const TetMesh& mesh, const RegionSurfaces& surfaces, const FeatureSettings& settings);

// The eigen-decomposition of eq. (11) over the distinct surface triangles
// around v: eigenvalues descending in `mu`, the matching unit eigenvectors
// as the columns of `e`.  `faces` (by the caller's vertex indices) and
// `ring` are scratch space.
void tensor_voting(const TetMesh& mesh, const RegionSurfaces& surfaces, int32_t v, std::vector<FaceKey>& faces,
                   std::vector<int32_t>& ring, Vec3& mu, Eigen::Matrix3d& e);

}  // namespace bodt
