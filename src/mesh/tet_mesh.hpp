// The compact tetrahedral mesh at the heart of the library: flat arrays of
// points and tets, vertex->tet incidence in CSR form, tet->tet face
// neighbours, per-vertex flags and face markers.  Every tet is stored
// positively oriented (an accepted inverted tet excepted); the caller's
// convention is restored at the C API.  Vertices and tets are numbered in
// the internal (curve) order; `caller` holds the caller's numbering, which
// the C API gives back.  Smoothing follows the caller's order wherever an
// order changes its results (colours, stars, rings, sums), so it gives the
// same bits in any internal order; the connectivity passes and the phased
// mode's serial sweep visit vertices and tets in the internal order.
#pragma once

#include "mesh/curve_order.hpp"
#include "mesh/element_keys.hpp"
#include "quality/tet_geometry.hpp"

#include <array>
#include <memory>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace bodt {

struct VertexColouring;  // mesh/vertex_colouring.hpp
struct ReleaseLists;

using Tet = std::array<int32_t, 4>;

// v is a vertex of q (without branches: the adjacency scans test this for
// every tet of a star).
inline bool holds(const Tet& q, int32_t v) { return (q[0] == v) | (q[1] == v) | (q[2] == v) | (q[3] == v); }

enum VertexFlag : uint8_t {
    kOnBoundary = 1,   // on a face of one tet
    kOnInterface = 2,  // on a face between regions or a marked interior face
    kFixed = 4,        // fixed by the caller
    kUnused = 8,       // in no tet
    kCorner = 16,      // a corner given by the caller
};
// The caller's bits, which the topology does not decide: such vertices never move.
constexpr uint8_t kPinned = kFixed | kCorner;

// One term of a new vertex's interpolation from the input mesh:
// value(new) = sum of weight * value(vertex) over its parents.
struct Parent {
    int32_t vertex;  // an input vertex
    double weight;
};
using Parents = std::vector<Parent>;

// A face of the mesh that the caller sees: boundary, interface or marked.
struct SurfaceFace {
    std::array<int32_t, 3> v;  // oriented as documented in bodt.h
    int32_t marker;
};

class TetMesh {
public:
    std::vector<Vec3> points;
    std::vector<Tet> tets;
    std::vector<int32_t> regions;            // one per tet
    std::vector<Tet> neighbors;              // across face i of tet t; -1 on the boundary
    // CSR: tets of vertex v are vt_tets[vt_offset[v] .. vt_offset[v+1]), in
    // the caller's order (caller_tet), so sums over a star do not depend on
    // the internal one.
    std::vector<int32_t> vt_offset, vt_tets;
    std::vector<uint8_t> vflags;
    std::unordered_map<FaceKey, int32_t, FaceKeyHash> face_markers;
    EdgeRefs feature_edges;  // given by the caller (or a file's edges), with their refs
    // The caller's vertex refs, for the input vertices (empty: all 0); made
    // vertices take theirs from their parents (vertex_refs()).
    std::vector<int32_t> input_vertex_refs;
    // Tets (accepted as inverted) whose vertex order is reversed against
    // their neighbours'; empty when there are none.  Faces are oriented by
    // the corrected order, so the surfaces stay consistent.
    std::vector<uint8_t> reversed;
    // History since the input, for carrying the caller's fields over: the
    // input tet each tet came from (empty: tet t is input tet t), and the
    // parents of each vertex made by an operation.  Made vertices are the
    // last new_parents.size() ones; input vertices keep their index.
    std::vector<int32_t> tet_origin;
    std::vector<Parents> new_parents;
    // The caller's numbering of the input vertices and tets.
    CallerNumbering caller;

    // Takes over what no connectivity change touches (the caller's
    // numbering and vertex refs) from `from`, which lost its
    // connectivity to a rewritten mesh (EditableMesh::write_to).
    void take_caller_data(TetMesh& from) noexcept {
        caller = std::move(from.caller);
        input_vertex_refs = std::move(from.input_vertex_refs);
    }

    int32_t num_vertices() const { return static_cast<int32_t>(points.size()); }
    int32_t num_tets() const { return static_cast<int32_t>(tets.size()); }
    int32_t num_input_vertices() const { return num_vertices() - static_cast<int32_t>(new_parents.size()); }

    // The caller's index of vertex v, and the inverse.
    int32_t caller_vertex(int32_t v) const { return caller.caller_vertex(v); }
    int32_t internal_vertex(int32_t c) const { return caller.internal_vertex(c); }
    // The caller's index of tet t: its input index while the connectivity
    // is the input's; after a change the caller gets the internal order.
    int32_t caller_tet(int32_t t) const { return tet_origin.empty() ? caller.caller_input_tet(t) : t; }
    // The caller's index of the input tet that tet t came from.
    int32_t caller_origin(int32_t t) const {
        return caller.caller_input_tet(tet_origin.empty() ? t : tet_origin[t]);
    }

    // Every vertex's ref: an input vertex's own; a made vertex's is the one
    // shared by those of its parents that lie where it lies (on the surface
    // or inside), 0 when they differ or there are none.
    std::vector<int32_t> vertex_refs() const;

    const Tet& tet(int32_t t) const { return tets[t]; }
    TetPoints tet_points(int32_t t) const {
        const Tet& q = tets[t];
        return {points[q[0]], points[q[1]], points[q[2]], points[q[3]]};
    }
    const int32_t* star_begin(int32_t v) const { return vt_tets.data() + vt_offset[v]; }
    const int32_t* star_end(int32_t v) const { return vt_tets.data() + vt_offset[v + 1]; }

    // Interior = may be moved by interior smoothing: used, not on the
    // boundary or an interface, not fixed.
    bool is_interior_free(int32_t v) const { return vflags[v] == 0; }

    // Rebuild incidence, neighbours and vertex flags from points, tets,
    // regions and markers (the neighbours on `threads` threads).
    // Throws Error(BODT_ERR_BAD_MESH) with a message using index base
    // `base` when the connectivity is not a valid mesh.
    void build_topology(int base, int threads = 1);
    // The same with the face neighbours known already (from the editable
    // mesh that wrote the tets: EditableMesh::written_neighbors), for a
    // mesh whose connectivity is valid by construction.
    void build_topology(std::vector<Tet> known_neighbors);

    // The colouring of mesh/vertex_colouring.hpp, made when first asked for
    // and kept until build_topology (a copy of the mesh shares it).  Not to
    // be called from several threads at once.
    const VertexColouring& colouring() const;
    // sweep_order(*this, colouring()), made when first asked for and kept
    // with the colouring (the same rules).
    const std::vector<int32_t>& sweep_order() const;
    // release_lists(*this, colouring(), threads), the same way.
    const ReleaseLists& release_lists(int threads) const;
    // After a connectivity change that kept the index of every vertex of
    // `before` (EditableMesh::write_to; made vertices after them): the
    // colouring of `before`, if it made one, brought up to date around the
    // vertices whose tets changed (recolour_vertices), instead of made
    // anew when first asked for.  Call it after build_topology.
    void carry_colouring(const TetMesh& before, const std::vector<int32_t>& changed);

    // Recompute the boundary, interface and unused bits of vflags (the fixed
    // bit is kept), after regions or markers changed.
    void update_vertex_flags();

    // Face i of tet t (opposite local vertex i), oriented out of the tet by
    // its corrected vertex order.
    std::array<int32_t, 3> outward_face(int32_t t, int i) const;

    // Fills `reversed` for a mesh with inverted tets: walks across shared
    // faces, which must appear with opposite orientations in their two tets,
    // and takes each connected part's majority order as the right one.
    // Throws Error(BODT_ERR_BAD_MESH) if the mesh cannot be oriented.
    void find_reversed_tets(int base);

    // The faces the caller sees, in the documented order and orientation
    // (both by the caller's numbering; the vertices are internal).
    std::vector<SurfaceFace> surface_faces() const;
    int32_t count_surface_faces() const;

    // Axis-aligned bounding-box diagonal of the used vertices.
    double bbox_diagonal() const;

    // Face i of tet t is on the domain boundary or between regions: on the
    // surface of t's region (RegionSurfaces).
    bool is_region_boundary_face(int32_t t, int i) const {
        const int32_t s = neighbors[t][i];
        return s < 0 || regions[s] != regions[t];
    }
    // Face i of tet t is on the domain boundary, between regions, or marked.
    bool is_surface_face(int32_t t, int i) const;
    // Face i of tet t carries a marker.
    bool is_marked_face(int32_t t, int i) const;
    // For loops over every face: 1 for each vertex of a marked face, so
    // that the marker table is searched only for faces whose three vertices
    // all have it.
    std::vector<uint8_t> marked_face_vertices() const;
    // is_marked_face(t, i), without the table's lookup when a vertex of the
    // face is not in `marked` (marked_face_vertices()).
    bool is_marked_face(int32_t t, int i, const std::vector<uint8_t>& marked) const;

private:
    // is_surface_face() with marked_face_vertices() at hand.
    bool is_surface_face(int32_t t, int i, const std::vector<uint8_t>& marked) const;
    void build_incidence();
    void build_neighbors(int base, int threads);
    void order_stars_as_caller();
    bool is_listed_face(int32_t t, int i, const std::vector<uint8_t>& marked) const;

    mutable std::shared_ptr<const VertexColouring> colouring_;  // a cache of the connectivity
    mutable std::shared_ptr<const std::vector<int32_t>> sweep_order_;  // of colouring_
    mutable std::shared_ptr<const ReleaseLists> release_lists_;        // of colouring_
};

}  // namespace bodt
