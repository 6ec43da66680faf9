// Where paper 000's smoothing wants a vertex: Algorithm 1 (ODT, eq. 3) for
// inner vertices, Algorithm 2 (tangent plane, eq. 10) for surface vertices,
// Algorithm 3 (feature line, f = -B/2A) for feature-line vertices; corners
// and fixed vertices stay.
#pragma once

#include "features/flat_pieces.hpp"
#include "features/vertex_classes.hpp"
#include "mesh/region_surfaces.hpp"
#include "smoothing/bodt_model.hpp"

#include <vector>

namespace bodt {

enum class Plan { Move, Stay, NotPositiveDefinite };

class BodtSmoother {
public:
    // `tolerance`: a vertex whose move would be at most this fraction of
    // its star's size (the cube root of its volume) has converged and stays.
    // A surface or feature-line vertex where the surface is faceted
    // (FlatPieces, with creases of a cosine at most `crease_cosine`) moves
    // only along the pieces' common line, or not at all; -1: none is
    // (paper 000's Algorithm 2 alone, BODT_MODE_BODT_BASIC).
    BodtSmoother(const RegionSurfaces& surfaces, const VertexClasses& classes, double tolerance, double crease_cosine)
        : surfaces_(surfaces), classes_(classes), tolerance_(tolerance), crease_cosine_(crease_cosine) {}

    // The target of vertex v, whose star is in `star`: Stay when v's move
    // is shorter than the tolerance.  `surface_faces` receives the surface
    // triangles around v (for the guard's normal-flip check); empty for
    // inner vertices.
    Plan target(const TetMesh& mesh, int32_t v, const StarTable& star, Vec3& target,
                std::vector<FaceKey>& surface_faces);

    // The directions surface or feature-line vertex v may take the angle
    // ascent along (those of move_basis), when a move along them keeps the
    // boundary's shape: v's rings flat, two planes meeting along a straight
    // feature line, or a crease (FlatPieces).  False elsewhere (curved
    // parts, corners).
    // Walks v's rings again: meant for the few vertices of bad tets.
    bool ascent_basis(const TetMesh& mesh, int32_t v, MoveBasis& basis);

    // The vertices, among those of `before`, whose targets read something
    // besides points that differs between two sets of classes and surfaces
    // of one mesh (whose connectivity changed, every vertex keeping its
    // index): their class, feature-line neighbours, and for a surface or
    // feature-line vertex the surfaces it lies on and its one-ring on each,
    // in order (the order of the sums).
    static std::vector<int32_t> read_differently(const VertexClasses& before, const RegionSurfaces& surfaces_before,
                                                 const VertexClasses& after, const RegionSurfaces& surfaces_after);

private:
    // The directions v may move in without changing any region's volume or
    // leaving its feature line: orthogonal to every ring normal, and along
    // the feature line for a FeatureLine vertex.
    bool move_basis(const TetMesh& mesh, int32_t v, MoveBasis& basis);
    // Adds ring normal n (a surface's sum_i S_i n_i at v) to normals_, or
    // the normals of its pieces where they are faceted (then true, and n
    // goes to ring_normals_).
    bool add_ring_normals(const FlatPieces& pieces, const Vec3& n);
    Vec3 line_direction(const TetMesh& mesh, int32_t v, const std::array<int32_t, 2>& line);
    Plan move_unless_converged(const Vec3& move, const StarModel& model) const;

    const RegionSurfaces& surfaces_;
    const VertexClasses& classes_;
    double tolerance_;
    double crease_cosine_;
    std::vector<int32_t> first_ring_;  // the one-ring of v on its first surface
    std::vector<int32_t> ring_;        // scratch for the others
    std::vector<Vec3> normals_;  // one ring normal sum_i S_i n_i per surface at v (eq. B.1), or its pieces'
    std::vector<Vec3> ring_normals_;  // the ring normals of the faceted rings (a move keeps them too)
    std::vector<FaceKey> faces_;
    std::vector<double> terms_;  // add_star()'s scratch
};

}  // namespace bodt
