#include "smoothing/star_table.hpp"

namespace bodt {

namespace {

// The face opposite v in each of the n tets `star` names, and v's corner
// in each: a loop the compiler vectorises with gathers.  kFaceVertex
// written out as selects: {1,2,3}, {0,3,2}, {0,1,3}, {0,2,1}.
BODT_VECTOR_CLONES
void gather_rows(const int32_t* star, size_t n, const int32_t* tets, const double* points, int32_t v,
                 double* opposite, double* at) {
#pragma omp simd
    for (size_t s = 0; s < n; ++s) {
        const int32_t* q = tets + 4 * static_cast<size_t>(star[s]);
        const int32_t q0 = q[0], q1 = q[1], q2 = q[2], q3 = q[3];
        const bool a1 = q1 == v, a2 = q2 == v, a3 = q3 == v, a0 = !(a1 | a2 | a3);
        const int32_t f0 = a0 ? q1 : q0;
        const int32_t f1 = a0 ? q2 : (a1 ? q3 : (a2 ? q1 : q2));
        const int32_t f2 = a0 ? q3 : (a1 ? q2 : (a2 ? q3 : q1));
        at[s] = a1 ? 1.0 : (a2 ? 2.0 : (a3 ? 3.0 : 0.0));
        const double* p0 = points + 3 * static_cast<size_t>(f0);
        const double* p1 = points + 3 * static_cast<size_t>(f1);
        const double* p2 = points + 3 * static_cast<size_t>(f2);
        opposite[s] = p0[0];
        opposite[n + s] = p1[0];
        opposite[2 * n + s] = p2[0];
        opposite[3 * n + s] = p0[1];
        opposite[4 * n + s] = p1[1];
        opposite[5 * n + s] = p2[1];
        opposite[6 * n + s] = p0[2];
        opposite[7 * n + s] = p1[2];
        opposite[8 * n + s] = p2[2];
    }
}

}  // namespace

void StarTable::gather(const TetMesh& mesh, int32_t v) {
    const int32_t* star = mesh.star_begin(v);
    resize(static_cast<size_t>(mesh.star_end(v) - star));
    static_assert(sizeof(Tet) == 4 * sizeof(int32_t) && sizeof(Vec3) == 3 * sizeof(double));
    gather_rows(star, size_, reinterpret_cast<const int32_t*>(mesh.tets.data()),
                reinterpret_cast<const double*>(mesh.points.data()), v, opposite_.data(), at_.data());
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
