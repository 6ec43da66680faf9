// The surface BODT_MODE_NODT projects its boundary vertices back onto: the
// boundary and interface triangles and the feature lines as they were when
// captured, so that repeated steps do not let the surface drift.
//
// The triangles are grouped into patches: faces that separate the same two
// sides (region and region, or region and outside), joined across the edges
// that are not feature edges; the feature edges into lines, cut at every
// vertex that is not a feature-line vertex (corners, kinks, junctions).  A
// surface vertex projects onto its own patch, a feature-line vertex onto its
// own line, each through a closest-point tree: a vertex near a sharp edge
// cannot be pulled onto the face across it.
//
// The capture is kept as long as the mesh has the same surface faces (with
// the same sides) and the same feature edges; it is taken again when these
// change (new regions, markers or feature edges from the caller, or a
// connectivity change that renumbers the surface).
//
// Faces and edges are held by the caller's vertex indices (TetMesh::caller)
// and the trees built in that order, so that projections do not depend on
// the internal order.
#pragma once

#include "features/vertex_classes.hpp"
#include "mesh/surface_bvh.hpp"
#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace bodt {

class InputSurface {
public:
    // Captures the surface and feature lines of `mesh` as classified by
    // `classes`, unless the faces and feature edges are the captured ones.
    void update(const TetMesh& mesh, const VertexClasses& classes);

    // Whether vertex v of class c has a patch or line to project onto: a
    // feature-line vertex its line (else its patch, for a line found by
    // tensor voting), a surface vertex the one patch its faces lie on.
    bool projects(int32_t v, VertexClass c) const;
    // The point of v's line or patch nearest to p (projects(v, c) holds).
    Vec3 project(int32_t v, VertexClass c, const Vec3& p) const;

private:
    // Each surface face (by the caller's indices) with the index of its
    // pair of sides, sorted: what decides whether the capture still holds,
    // with the feature edges.
    using SidedFaces = std::vector<std::pair<FaceKey, int32_t>>;
    static SidedFaces sided_faces(const TetMesh& mesh);
    void capture_patches(const TetMesh& mesh);
    void capture_lines(const TetMesh& mesh, const VertexClasses& classes);

    bool captured_ = false;
    SidedFaces faces_;
    std::vector<EdgeKey> feature_edges_;  // by the caller's indices, sorted
    std::vector<SurfaceBvh> patches_;
    std::vector<SurfaceBvh> lines_;  // a segment ab as the triangle (a, b, b)
    std::vector<int32_t> patch_of_;  // per vertex: its patch, -1 none, -2 several
    std::vector<int32_t> line_of_;   // per vertex: its line, -1 none
};

}  // namespace bodt
