// Paper 002 sec. 3.4: ODT smoothing by phases, from the boundary inwards.
// Every phase moves a vertex by eq. (3.4),
//   x' = (1 - alpha) x + alpha sum_j |tau_j| c_j / sum_j |tau_j|,
// in its own dimension:
//  1. sharp-edge chains: c_j the midpoints of the vertex's two chain edges
//     (CPT) on a line, the mid-angles on an arc or circle (sec. 3.4.2);
//  2. surface regions: c_j the circumcentres of the vertex's triangles, or
//     their barycentres where a triangle touches the region's border or is
//     not Delaunay; on a cylinder in its development (r theta, z) (3.4.3);
//  3. interior: c_j the circumcentres of the vertex's tets, barycentres for
//     tets touching the surface or not Delaunay (3.4.4).
// A planned move is a path: straight in space, or along the angle of a
// circle or cylinder, so that a shortened move stays on the shape.
#pragma once

#include "features/geometry_model.hpp"
#include "mesh/tet_mesh.hpp"

#include <vector>

namespace bodt {

struct PlannedMove {
    Vec3 start, target;
    const Shape* curved = nullptr;  // Arc, Circle, Cylinder: move in (theta, z)
    double theta0 = 0, theta1 = 0, z0 = 0, z1 = 0;
    // The point at fraction f of the way (f = 1: the target), on the shape.
    Vec3 at(double f) const;
};

class PhasedOdt {
public:
    PhasedOdt(const GeometryModel& geometry, double alpha) : geometry_(geometry), alpha_(alpha) {}

    // Phase 1 (FeatureLine vertices), 2 (Surface), 3 (Interior); false when
    // v does not move in this phase.
    bool chain_move(const TetMesh& mesh, int32_t v, PlannedMove& move);
    bool surface_move(const TetMesh& mesh, int32_t v, PlannedMove& move);
    bool interior_move(const TetMesh& mesh, int32_t v, PlannedMove& move);

    // The surface faces around v (the ones a move must not flip).
    const std::vector<FaceKey>& faces() const { return faces_; }

private:
    void gather_faces(const TetMesh& mesh, int32_t v);

    const GeometryModel& geometry_;
    double alpha_;
    std::vector<FaceKey> faces_;
    std::vector<int32_t> scratch_;
};

// A tet is Delaunay when no vertex of a face neighbour lies inside its
// circumsphere (the local test of sec. 3.4.4).
bool locally_delaunay(const TetMesh& mesh, int32_t t);

}  // namespace bodt
