// The part's geometry as paper 002 (sec. 3.3) extracts it from a mesh:
// sharp mesh edges (dihedral angle past the feature angle), corners where
// chains of them end, meet or turn, the chains (between corners, or loops),
// the surface regions they bound, and the shape fitted to each: a plane or
// a cylinder per region, a line, arc or circle per chain.
//
// Extracted once from a mesh, then carried through connectivity changes:
// every vertex knows its entity (the region of a surface vertex, the chain
// of a sharp-edge vertex), and a vertex an operation made learns its own
// from its neighbours (resolve).
#pragma once

#include "features/shape_fit.hpp"
#include "features/vertex_classes.hpp"
#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace bodt {

class EditableMesh;

struct SurfaceRegion {
    Shape shape;
    // Sec. 3.3, cylinders: the largest distance of an edge midpoint from the
    // cylinder, in the mesh as extracted (own) and the one to keep
    // (acceptable: the reference's when there is one, else own).
    double own_error = 0.0;
    double acceptable_error = 0.0;
};

struct SharpChain {
    Shape shape;                     // Line, Arc, Circle or None
    std::vector<int32_t> regions;    // the surface regions along it
};

struct GeometrySettings {
    double feature_angle_deg = 30.0;
    double fit_tolerance = 1e-5;  // max distance from the shape / size of the fitted part
};

class GeometryModel {
public:
    // Sec. 3.3 on the mesh's boundary and interface faces.  The caller's
    // feature edges are sharp too; fixed vertices stay Fixed.  Sharp edges
    // and corners are judged at `undeformed` positions where given (the
    // reference mesh's, per input vertex: a deformed mesh's folded faces
    // would make false ones), the shapes fitted at the mesh's own.  Without
    // them, in a mesh with inverted tets, two faces turned against each
    // other by more than 180 degrees minus the feature angle are a fold,
    // not a sharp edge.
    static GeometryModel extract(const TetMesh& mesh, const GeometrySettings& settings,
                                 const std::vector<Vec3>& undeformed = {});

    const std::vector<SurfaceRegion>& regions() const { return regions_; }
    std::vector<SurfaceRegion>& regions() { return regions_; }
    const std::vector<SharpChain>& chains() const { return chains_; }

    // Where v lies: Interior, Surface (in a region), FeatureLine (on a
    // chain), Corner or Unused; a fixed vertex too.  Which vertices stay is
    // vertex_classes' business.
    VertexClass vertex_class(int32_t v) const { return cls_[v]; }
    // The region of a Surface vertex, the chain of a FeatureLine vertex; -1
    // otherwise.
    int32_t entity(int32_t v) const { return entity_[v]; }
    int32_t num_vertices() const { return static_cast<int32_t>(cls_.size()); }
    const EdgeSet& sharp_edges() const { return sharp_; }

    // The regions vertex v touches (one for a Surface vertex).
    std::vector<int32_t> regions_at(int32_t v) const;
    // The region of surface face (a, b, c): the region all three touch; for
    // a face with no vertex inside a region, its region as extracted, else
    // the nearest by shape of those they all touch; -1 if none.
    int32_t face_region(int32_t a, int32_t b, int32_t c, const Vec3& centroid) const;
    // The shape a vertex moves on: its region's or chain's; nullptr for
    // corners, fixed and interior vertices.
    const Shape* shape_of(int32_t v) const;

    // Sec. 3.3's geometric error of `mesh`: the distance of the midpoint of
    // each edge of a face on a cylinder from that cylinder (each edge once).
    struct GeometricError {
        double mean = 0.0, max = 0.0;
        int64_t edges = 0;
    };
    GeometricError geometric_error(const TetMesh& mesh) const;

    // The classes the topology operations work with, one per vertex of
    // `mesh` (the model may hold more: vertices of changes not kept): Fixed
    // where the caller fixed a vertex or it lies in a region or chain that
    // nothing fits (it must not move).
    VertexClasses vertex_classes(const TetMesh& mesh) const;

    // After an EditableMesh (made with vertex_classes()) changed the
    // connectivity and wrote itself back with `renumber` (old index -> new,
    // -1 when dropped): classes follow the editable mesh, entities the
    // renumbering, and made vertices take theirs from their neighbours.
    void follow(const EditableMesh& edited, const std::vector<int32_t>& renumber, const TetMesh& written);

    // Entity for a vertex an operation made (class from the editable mesh):
    // the region or chain of its neighbours whose shape lies nearest.
    int32_t resolve(const EditableMesh& mesh, int32_t v) const;
    // Records v's entity (growing the arrays for a made vertex).
    void set(int32_t v, VertexClass cls, int32_t entity);
    // Forgets the vertices from `n` on: those of changes that were rolled
    // back or never written, whose indices a new change may reuse.
    void truncate(int32_t n);

private:
    std::vector<SurfaceRegion> regions_;
    std::vector<SharpChain> chains_;
    std::vector<VertexClass> cls_;
    std::vector<int32_t> entity_;
    // Corners: the regions around them, the chains at them.
    std::unordered_map<int32_t, std::vector<int32_t>> corner_regions_;
    std::unordered_map<int32_t, std::vector<int32_t>> corner_chains_;
    // Faces with no vertex inside a region (all on chains, at corners or
    // fixed): their region as extracted, which their vertices cannot tell.
    std::unordered_map<FaceKey, int32_t, FaceKeyHash> rim_faces_;
    EdgeSet sharp_;
};

}  // namespace bodt
