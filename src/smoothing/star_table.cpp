#include "smoothing/star_table.hpp"

#include <algorithm>

namespace bodt {

void StarTable::gather(const TetMesh& mesh, int32_t v) {
    const int32_t* star = mesh.star_begin(v);
    resize(static_cast<size_t>(mesh.star_end(v) - star));
    for (size_t s = 0; s < size_; ++s) {
        const Tet& q = mesh.tets[star[s]];
        set(s, mesh.tet_points(star[s]), static_cast<int>(std::find(q.begin(), q.end(), v) - q.begin()));
    }
}

void StarTable::resize(size_t n) {
    size_ = n;
    corners_.resize(12 * n);
    opposite_.resize(9 * n);
    at_.resize(n);
}

void StarTable::set(size_t s, const TetPoints& p, int at) {
    const size_t n = size_;
    for (int j = 0; j < 4; ++j) {
        corners_[j * n + s] = p[j].x();
        corners_[(4 + j) * n + s] = p[j].y();
        corners_[(8 + j) * n + s] = p[j].z();
    }
    at_[s] = static_cast<uint8_t>(at);
    for (int k = 0; k < 3; ++k) {
        const Vec3& c = p[kFaceVertex[at][k]];
        opposite_[k * n + s] = c.x();
        opposite_[(3 + k) * n + s] = c.y();
        opposite_[(6 + k) * n + s] = c.z();
    }
}

void StarTable::place(const Vec3& x) {
    const size_t n = size_;
    for (size_t s = 0; s < n; ++s) {
        corners_[at_[s] * n + s] = x.x();
        corners_[(4 + at_[s]) * n + s] = x.y();
        corners_[(8 + at_[s]) * n + s] = x.z();
    }
}

}  // namespace bodt
