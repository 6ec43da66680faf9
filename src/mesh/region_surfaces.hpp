// The surfaces the boundary-aware smoothing works on: for every region
// (material id), the closed surface around its tets, as an OpenMesh
// halfedge mesh with faces oriented out of the region.  In a one-region mesh
// this is the domain boundary; in a multi-region mesh an interface face is
// in the surfaces of both regions it separates, once for each side.
#pragma once

#include "mesh/boundary_surface.hpp"

#include <vector>

namespace bodt {

class RegionSurfaces {
public:
    // A region's surface need not be a manifold (a region may touch itself
    // along an edge or at a vertex): with Tolerant, the vertices where it is
    // not have no closed one-ring and are reported as blocked; with Strict
    // (the domain boundary of a new mesh) that is an Error.  `base` is the
    // index base for messages.
    void build(const TetMesh& mesh, int base, BoundarySurface::Strictness strictness);

    // Whether a connectivity change from `before` to `after` kept every
    // face of the region surfaces, in the order the surfaces grow from
    // (the tets' order), so that a build on `after` makes the surfaces of
    // `before` again: no tet with a face on a region surface went or came.
    // `written` maps each tet of `before` to its index in `after`, -1 if
    // it went (EditableMesh::written_tets: those still there come first,
    // in their order, the new ones after them).
    static bool kept_by(const TetMesh& before, const TetMesh& after, const std::vector<int32_t>& written);
    // The vertices of a mesh grown to `nv` vertices by a change that kept
    // every surface face (the new vertices lie on none).  The mesh before
    // the change reads the surfaces as before: it has no vertex past its own.
    void add_vertices(int32_t nv) {
        const int32_t end = offset_.back();
        offset_.resize(static_cast<size_t>(nv) + 1, end);
        if (!blocked_.empty()) blocked_.resize(static_cast<size_t>(nv), 0);
    }

    // True when some surface has no closed ring around v: v cannot move.
    bool blocked(int32_t v) const { return !blocked_.empty() && blocked_[v]; }

    int32_t count() const { return static_cast<int32_t>(surfaces_.size()); }
    const BoundarySurface& surface(int32_t k) const { return surfaces_[k]; }

    // Indices of the surfaces vertex v lies on.
    const int32_t* begin(int32_t v) const { return at_.data() + offset_[v]; }
    const int32_t* end(int32_t v) const { return at_.data() + offset_[v + 1]; }

private:
    std::vector<BoundarySurface> surfaces_;
    std::vector<int32_t> offset_, at_;  // CSR: vertex -> surfaces
    std::vector<char> blocked_;         // per vertex; empty when none is
};

}  // namespace bodt
