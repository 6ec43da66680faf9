// Least-squares fits of the shapes paper 002 (sec. 3.3) models a part with:
// planes and cylinders for surface regions, lines, circular arcs and
// circles for sharp-edge chains; and the maps the phased smoothing moves
// vertices with (sec. 3.4.2, 3.4.3): projection, the central angle on a
// circle, the development (r theta, z) of a cylinder.
#pragma once

#include "quality/tet_geometry.hpp"

#include <vector>

namespace bodt {

enum class ShapeType : int {
    None = 0,      // not fitted (too few points, or no model fits): vertices stay
    Plane = 1,
    Cylinder = 2,
    Line = 3,
    Arc = 4,       // part of a circle
    Circle = 5     // a closed chain on a circle
};

// One fitted shape.  Plane: point and unit normal `axis`.  Cylinder: a
// point on the axis, unit axis direction, radius.  Line: a point, unit
// direction `axis`.  Arc and circle: centre, unit normal of the circle's
// plane, radius.  `u` and `w` complete `axis` to a right-handed orthonormal
// frame (u, w, axis): the angle theta of a cylinder or circle is measured
// from u towards w.  `max_error`: the largest distance of a fitted point
// from the shape.
struct Shape {
    ShapeType type = ShapeType::None;
    Vec3 point = Vec3::Zero();
    Vec3 axis = Vec3::UnitZ();
    Vec3 u = Vec3::UnitX(), w = Vec3::UnitY();
    double radius = 0.0;
    double max_error = 0.0;

    // The nearest point of the shape (x itself for None).
    Vec3 project(const Vec3& x) const;
    // Distance from the shape (0 for None).
    double distance(const Vec3& x) const;

    // Cylinder, arc, circle: the angle of x about the axis, in (-pi, pi].
    double angle(const Vec3& x) const;
    // Cylinder: the coordinate of x along the axis.
    double height(const Vec3& x) const;
    // Cylinder: the point at angle theta and height z.  Arc, circle: the
    // point at angle theta (z ignored).
    Vec3 at(double theta, double z = 0.0) const;
};

// Fits over points sampled on a shape.  Each returns a shape with type
// None when there are too few points or the points are degenerate for it
// (collinear points for a plane, ...); max_error tells how well it fits.
Shape fit_plane(const std::vector<Vec3>& points);
// Normals (one per point or per face, any length, oriented or not) give the
// starting axis: the direction most perpendicular to them.  The fit then
// minimises the sum of squared distances |dist to axis - r|^2 (Gauss-Newton).
Shape fit_cylinder(const std::vector<Vec3>& points, const std::vector<Vec3>& normals);
Shape fit_line(const std::vector<Vec3>& points);
// A circle in 3-D (the points' best plane, then a circle in it); type Arc.
Shape fit_circle(const std::vector<Vec3>& points);

// The right-handed orthonormal frame (u, w, axis) for a unit axis.
void complete_frame(const Vec3& axis, Vec3& u, Vec3& w);

}  // namespace bodt
