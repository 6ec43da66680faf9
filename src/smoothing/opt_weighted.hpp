// Paper 001's smoothing (sec. 3) on a TetMesh: where the quasi-Newton wants
// each free vertex, and which vertices the combined algorithm of sec. 2
// smooths (the work set Phi: the vertices of poor tets).
//
// What the paper leaves open, decided here:
//  - free vertices are the Interior ones; boundary, interface and fixed
//    vertices stay, as in the paper;
//  - a boundary tet (the set Gamma_2 of eq. 3.4) is a tet with a vertex that
//    stays, which covers the four kinds of boundary elements of Fig. 1 (one
//    to four vertices on the boundary).
#pragma once

#include "features/vertex_classes.hpp"
#include "mesh/tet_mesh.hpp"
#include "smoothing/quasi_newton.hpp"

#include <vector>

namespace bodt {

// The weights of eq. (3.4): 1 - C for interior tets, C for boundary tets.
struct ElementWeights {
    double interior, boundary;
    static ElementWeights from_c(double c) { return {1.0 - c, c}; }
};

// Fills `star` with eq. (3.4) restricted to the tets [first, last) around v
// (the only terms v's position changes).  A tet is a boundary tet when some
// vertex u of it has is_free(u) false.  Mesh: a TetMesh or an EditableMesh
// (anything with tet(t) and tet_points(t)).
template <class Mesh, class IsFree>
void gather_weighted_star(const Mesh& mesh, const int32_t* first, const int32_t* last, int32_t v, IsFree is_free,
                          ElementWeights weights, WeightedStar& star) {
    star.clear();
    for (const int32_t* t = first; t != last; ++t) {
        const Tet& q = mesh.tet(*t);
        const bool boundary = !(is_free(q[0]) && is_free(q[1]) && is_free(q[2]) && is_free(q[3]));
        const int corner = q[0] == v ? 0 : (q[1] == v ? 1 : (q[2] == v ? 2 : 3));
        star.add(mesh.tet_points(*t), corner, boundary ? weights.boundary : weights.interior);
    }
}

class OptWeightedSmoother {
public:
    OptWeightedSmoother(const std::vector<VertexClass>& cls, ElementWeights weights, const QuasiNewtonSettings& qn)
        : cls_(cls), weights_(weights), qn_(qn) {}

    // The minimiser of the weighted star objective of Interior vertex v,
    // from where v is; false (v stays) for other vertices, a star holding a
    // tet that is not positively oriented, or no decrease.
    bool target(const TetMesh& mesh, int32_t v, Vec3& target);

private:
    const std::vector<VertexClass>& cls_;
    ElementWeights weights_;
    QuasiNewtonSettings qn_;
    WeightedStar star_;  // reused
};

// The work set Phi (sec. 2, step 2): 1 for each vertex of a tet whose
// stretch is below `poor`.
std::vector<uint8_t> poor_vertices(const TetMesh& mesh, double poor);

}  // namespace bodt
