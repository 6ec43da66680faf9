// The flat pieces the surface around a vertex is made of: the planes
// through the vertex that its surface triangles lie in.  Where there are two
// or three, some holding more than one triangle, and they meet at creases
// (angles of at least the crease angle), the surface is faceted there, as
// on a CAD part's faces: a move of the vertex keeps the surface's shape only
// along the pieces' common line (none where three meet at a point), and a
// collapse only into a vertex in every piece.  On a curved part every
// triangle has its own plane, or (a cylinder cut into strips, a sphere into
// quads) the pieces meet at small angles.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <algorithm>
#include <cmath>

namespace bodt {

class FlatPieces {
public:
    // More pieces than this are "many": a curved part.
    static constexpr int kMost = 3;

    explicit FlatPieces(const Vec3& x0) : x0_(x0) {}

    // Adds the surface triangle (x0, a, b).
    void add(const Vec3& a, const Vec3& b) { add(a, b, (a - x0_).cross(b - x0_)); }
    // The same with its normal n, (a - x0) x (b - x0) times any positive
    // number, known (the ring's sums have it).
    void add(const Vec3& a, const Vec3& b, const Vec3& n) {
        ++triangles_;
        if (count_ > kMost) return;
        const Vec3 u = a - x0_, w = b - x0_;
        if (!(n.norm() > 0.0)) {
            count_ = kMost + 1;
            return;
        }
        // In piece k when both corners are: their heights over it are small.
        const double tolerance = kFlat * std::max(u.norm(), w.norm());
        int k = 0;
        while (k < count_ && !(std::abs(u.dot(normal_[k])) <= tolerance && std::abs(w.dot(normal_[k])) <= tolerance)) ++k;
        if (k == count_ && count_++ < kMost) normal_[k] = n.normalized();
    }

    // The number of pieces, kMost + 1 for more (or a degenerate triangle).
    int count() const { return count_; }
    // Two or three pieces, fewer than the triangles, every two of them at
    // an angle whose cosine is at most `crease_cosine` (either way round:
    // a sharper fold is a feature edge).
    bool faceted(double crease_cosine) const {
        if (count_ < 2 || count_ > kMost || count_ == triangles_) return false;
        for (int i = 0; i < count_; ++i)
            for (int j = i + 1; j < count_; ++j)
                if (std::abs(normal_[i].dot(normal_[j])) > crease_cosine) return false;
        return true;
    }
    // Their unit normals (count() of them up to kMost).
    const Vec3* normals() const { return normal_; }

    // Relative to a length, how far a point may be off a plane and still
    // count as on it: far above round-off, far below anything a
    // finite-element solution could tell.
    static constexpr double kFlat = 1e-6;

private:
    Vec3 x0_;
    int count_ = 0;
    int triangles_ = 0;
    Vec3 normal_[kMost];
};

}  // namespace bodt
