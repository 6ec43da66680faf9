// The closed surface around the tets of one region as an OpenMesh halfedge
// mesh, for ordered one-rings: the domain boundary when the mesh has one
// region.  It holds connectivity only: positions live in TetMesh::points,
// and the surface's vertices map to tet-mesh vertices.  Faces are oriented
// with their normals pointing out of the region.
#pragma once

#include "mesh/tet_mesh.hpp"

// OpenMesh 9's property code trips GCC 12's -Wmaybe-uninitialized (which
// clang, building the fuzzers, does not have).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include <vector>

namespace bodt {

struct SurfaceTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
};
using SurfaceMesh = OpenMesh::TriMesh_ArrayKernelT<SurfaceTraits>;

class BoundarySurface {
public:
    enum class Strictness { Strict, Tolerant };

    // Builds the surface of the faces of region `region`'s tets that have no
    // neighbour in that region.  Where it is not a manifold surface, Strict
    // throws Error(BODT_ERR_BAD_MESH) naming the vertex or edge (indices in
    // base `base`); Tolerant leaves out the faces around that vertex and
    // lists their vertices, whose rings are then open, in blocked().
    void build(const TetMesh& mesh, int base, int32_t region, Strictness strictness = Strictness::Strict);

    // Neighbours y_1..y_m of tet-mesh vertex v on the surface, ordered so
    // that (y_i - v) x (y_{i+1} - v) points out of the region (paper 000
    // sec. 2.2).  Empty if v is not on the surface.
    void one_ring(int32_t v, std::vector<int32_t>& ring) const;

    bool contains(int32_t v) const { return surface_vertex(v) >= 0; }
    // Tet-mesh vertices on the surface, ascending.
    const std::vector<int32_t>& vertices() const { return to_tet_; }
    // Vertices without a closed ring (Tolerant builds only), ascending.
    const std::vector<int32_t>& blocked() const { return blocked_; }

    int32_t num_faces() const { return static_cast<int32_t>(surface_.n_faces()); }
    const SurfaceMesh& mesh() const { return surface_; }
    int32_t tet_vertex(SurfaceMesh::VertexHandle h) const { return to_tet_[h.idx()]; }

private:
    int32_t surface_vertex(int32_t v) const;  // -1 if v is not on the surface

    SurfaceMesh surface_;
    std::vector<int32_t> to_tet_;  // surface vertex -> tet-mesh vertex, ascending
    std::vector<int32_t> blocked_;
};

}  // namespace bodt
