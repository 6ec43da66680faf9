#include "smoothing/angle_ascent.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodt {

AngleAscent::AngleAscent(double angle_deg) : bad_cosine_(std::cos(angle_deg * M_PI / 180.0)) {}

size_t AngleAscent::worst_tet(const TetMesh& mesh, int32_t v, const StarTable& star, const ShapeCache& shapes) const {
    const int32_t* tets = mesh.star_begin(v);
    const size_t n = star.size();
    size_t worst = n;
    double most = bad_cosine_;
    for (size_t k = 0; k < n; ++k) {
        const double b = worst_cosine(shapes[static_cast<size_t>(tets[k])].cosines);
        if (b > most) {
            most = b;
            worst = k;
        }
    }
    return worst;
}

bool AngleAscent::target(const TetMesh& mesh, int32_t v, const StarTable& star, size_t worst, const MoveBasis* basis,
                         Vec3& target) const {
    const size_t n = star.size();
    const Vec3 x0 = mesh.points[v];
    const auto worst_cosine_at = [&](const Vec3& x) {
        return worst_cosine(shape_of(star_tet_kernel(star.opposite(), star.at(), n, worst, coords(x))).cosines);
    };
    // Lowering worst_cosine raises the worst angle's sine.  It is the
    // largest of six smooth functions of x: its gradient by central
    // differences, over a step far below the tet's size and far above
    // round-off.
    double shortest = std::numeric_limits<double>::infinity();
    for (size_t c = 0; c < 3; ++c) {
        const double* f = star.opposite();
        const Vec3 y(f[c * n + worst], f[(3 + c) * n + worst], f[(6 + c) * n + worst]);
        shortest = std::min(shortest, (y - x0).norm());
    }
    const double h = 1e-4 * shortest;
    Vec3 gradient;
    for (int i = 0; i < 3; ++i) {
        const Vec3 e = h * Vec3::Unit(i);
        gradient[i] = (worst_cosine_at(x0 + e) - worst_cosine_at(x0 - e)) / (2.0 * h);
    }
    if (basis) {  // orthonormal columns
        Vec3 along = Vec3::Zero();
        for (Eigen::Index c = 0; c < basis->cols(); ++c) along += basis->col(c).dot(gradient) * basis->col(c);
        gradient = along;
    }
    const double length = gradient.norm();
    if (!(length > 0.0) || !std::isfinite(length)) return false;
    target = x0 - (0.5 * shortest / length) * gradient;
    return true;
}

}  // namespace bodt
