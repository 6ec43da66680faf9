// The symmetric Hausdorff distance between two triangle surfaces, for
// `bodt compare`.
//
// H(A, B) = max(sup_{a in A} d(a, B), sup_{b in B} d(b, A)), d(x, S) the
// exact distance from the point x to the nearest triangle of S (the core's
// closest-point tree, bodt::SurfaceBvh in src/mesh/surface_bvh.hpp).
//
// The suprema run over whole triangles, not only vertices: a dent of B may
// lie under the middle of a triangle of A.  They are bounded by branch and
// bound on the triangles of both surfaces, best first:
//  - lower bound: the largest d found at the points evaluated so far (every
//    vertex, every triangle's centroid, then the vertices and centroids of
//    the subtriangles made below): H is at least this, and it is attained;
//  - upper bound of a (sub)triangle T of A: the smaller of
//      min over candidate triangles t of B of  max over the corners p of T
//      of d(p, t)  (d(., t) is convex, so on T it is largest at a corner;
//      the candidates are the triangles nearest to T's evaluated points),
//    the same over two candidates that share an edge, lie in one plane and
//    make a convex quadrilateral (the distance to it is convex too: cells
//    across the edge between them), and the Lipschitz bounds d(q) + max |x - q| over x in T, for q a
//    corner or the centroid (d(., B) is 1-Lipschitz);
//  - the (sub)triangle with the largest upper bound is split in four at
//    its edge midpoints, until that bound is within
//    abs_tolerance + rel_tolerance * (lower bound) of the lower bound, or
//    `max_evaluations` distance queries were made.
// The result gives both bounds: H lies in [lower, upper].  For identical
// surfaces both are 0 at once (each triangle is its own candidate); when
// the distance is attained at a vertex (a moved vertex) `lower` is exact.
#pragma once

#include <cstdint>
#include <vector>

namespace bodt_cli {

struct TriangleSurface {
    std::vector<double> xyz;      // 3 per vertex
    std::vector<int32_t> triangles;  // 3 per triangle, 0-based
};

struct HausdorffBounds {
    double lower = 0.0;
    double upper = 0.0;
    int64_t evaluations = 0;  // point-to-surface distance queries
};

HausdorffBounds hausdorff_distance(const TriangleSurface& a, const TriangleSurface& b, double abs_tolerance,
                                   double rel_tolerance, int64_t max_evaluations);

}  // namespace bodt_cli
