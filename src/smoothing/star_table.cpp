#include "smoothing/star_table.hpp"

namespace bodt {

void StarTable::gather(const TetMesh& mesh, int32_t v) {
    const int32_t* star = mesh.star_begin(v);
    resize(static_cast<size_t>(mesh.star_end(v) - star));
    const size_t n = size_;
    for (size_t s = 0; s < n; ++s) {
        const Tet& q = mesh.tets[star[s]];
        // Without branches: the corner is as good as random from tet to tet.
        const int at = (q[1] == v) + 2 * (q[2] == v) + 3 * (q[3] == v);
        at_[s] = static_cast<double>(at);
        for (int k = 0; k < 3; ++k) {
            const Vec3& c = mesh.points[q[kFaceVertex[at][k]]];
            opposite_[k * n + s] = c.x();
            opposite_[(3 + k) * n + s] = c.y();
            opposite_[(6 + k) * n + s] = c.z();
        }
    }
}

void StarTable::resize(size_t n) {
    size_ = n;
    opposite_.resize(9 * n);
    at_.resize(n);
}

void StarTable::set(size_t s, const TetPoints& p, int at) {
    const size_t n = size_;
    at_[s] = static_cast<double>(at);
    for (int k = 0; k < 3; ++k) {
        const Vec3& c = p[kFaceVertex[at][k]];
        opposite_[k * n + s] = c.x();
        opposite_[(3 + k) * n + s] = c.y();
        opposite_[(6 + k) * n + s] = c.z();
    }
}

}  // namespace bodt
