// surface_distance.hpp -- boundary surfaces of tet meshes and the sampled
// symmetric Hausdorff distance between two triangle surfaces (bodt_bench).
#ifndef BODT_BENCH_SURFACE_DISTANCE_HPP
#define BODT_BENCH_SURFACE_DISTANCE_HPP

#include <array>
#include <cstdint>
#include <vector>

namespace bench {

struct Surface {
    std::vector<double> xyz;                     // 3 per vertex (all mesh vertices)
    std::vector<std::array<int32_t, 3>> tris;    // 0-based vertex indices
};

// The faces that belong to exactly one tet (the domain boundary; faces
// between two tets of different regions are NOT included).  tets holds
// 4 * ntets indices in base index_base; the result is 0-based and sorted.
std::vector<std::array<int32_t, 3>> boundary_triangles(const std::vector<int32_t>& tets, int index_base);

// Largest over the samples of A (its vertices, edge midpoints and triangle
// centroids) of the exact distance to the nearest triangle of B (a BVH over
// B's triangles makes this fast).  0 if A has no triangles, +inf if B has none.
double one_sided_distance(const Surface& a, const Surface& b);

// max(one_sided(a, b), one_sided(b, a)); exactly 0 without any search when
// both surfaces have the same triangles and the same coordinates at their
// vertices.
double hausdorff_distance(const Surface& a, const Surface& b);

// Largest side of the axis-aligned bounding box of all vertices in s.xyz
// (as meshq.py and paper 000, Table 2: the input mesh's box).
double bbox_largest_side(const Surface& s);

}  // namespace bench

#endif
