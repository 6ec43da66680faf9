// Closest points on a set of triangles: the exact closest point on one
// triangle (Ericson, Real-Time Collision Detection, 5.1.5) and a
// bounding-box tree over many, for BODT_MODE_NODT's projection onto the
// input surface and for `bodt compare`'s Hausdorff distance.  A segment ab
// may be stored as the triangle (a, b, b): its closest point is exact too.
#pragma once

#include "quality/tet_geometry.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace bodt {

// The point of triangle abc nearest to p; a degenerate triangle (or one
// thinner than 1e-8 of its edges) is the union of its edges.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

struct ClosestPoint {
    Vec3 point = Vec3::Zero();
    double distance2 = 0.0;  // squared distance from the query; infinite ...
    int32_t triangle = -1;   // ... and -1 when the tree is empty
};

// A tree of axis-aligned boxes over the triangles, median split on the
// longest axis of the centroids, up to 4 triangles per leaf.  It owns a copy
// of the points and triangles.
class SurfaceBvh {
public:
    SurfaceBvh() = default;
    SurfaceBvh(std::vector<Vec3> points, std::vector<std::array<int32_t, 3>> triangles);

    int32_t num_triangles() const { return static_cast<int32_t>(triangles_.size()); }
    int32_t vertex(int32_t t, int k) const { return triangles_[t][k]; }
    const Vec3& corner(int32_t t, int k) const { return points_[triangles_[t][k]]; }

    // The nearest point to p on any triangle.
    ClosestPoint closest(const Vec3& p) const;
    // The nearest point to p on triangle t.
    Vec3 closest_on(const Vec3& p, int32_t t) const;

private:
    struct Node {
        Vec3 lo, hi;
        int32_t left = 0, right = 0;  // children, for inner nodes
        int32_t first = 0, count = 0; // range of order_, for leaves (count > 0)
    };

    int32_t build(int32_t first, int32_t last, const std::vector<Vec3>& centroids);
    static double box_distance2(const Node& n, const Vec3& p);

    std::vector<Vec3> points_;
    std::vector<std::array<int32_t, 3>> triangles_;
    std::vector<int32_t> order_;  // triangles, grouped by leaf
    std::vector<Node> nodes_;     // nodes_[0] is the root
};

}  // namespace bodt
