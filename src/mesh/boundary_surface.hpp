// The domain boundary as an OpenMesh halfedge mesh, for ordered one-rings.
// It holds connectivity only: positions live in TetMesh::points, and the
// surface's vertices map to tet-mesh vertices.  Faces are oriented with their
// normals pointing out of the domain.
#pragma once

#include "mesh/tet_mesh.hpp"

// OpenMesh 9's property code trips GCC 12's -Wmaybe-uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#pragma GCC diagnostic pop

#include <vector>

namespace bodt {

struct SurfaceTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
};
using SurfaceMesh = OpenMesh::TriMesh_ArrayKernelT<SurfaceTraits>;

class BoundarySurface {
public:
    // Builds the surface of the faces of one tet.  Throws
    // Error(BODT_ERR_BAD_MESH) naming the vertex or edge where the boundary
    // is not a manifold surface (indices in base `base`).
    void build(const TetMesh& mesh, int base);

    // Boundary neighbours y_1..y_m of tet-mesh vertex v, ordered so that
    // (y_i - v) x (y_{i+1} - v) points out of the domain (paper 000 sec. 2.2).
    // Empty if v is not on the boundary.
    void one_ring(int32_t v, std::vector<int32_t>& ring) const;

    int32_t num_faces() const { return static_cast<int32_t>(surface_.n_faces()); }
    const SurfaceMesh& mesh() const { return surface_; }
    int32_t tet_vertex(SurfaceMesh::VertexHandle h) const { return to_tet_[h.idx()]; }

private:
    SurfaceMesh surface_;
    std::vector<int32_t> to_tet_;    // surface vertex -> tet-mesh vertex
    std::vector<int32_t> from_tet_;  // tet-mesh vertex -> surface vertex, -1 if none
};

}  // namespace bodt
