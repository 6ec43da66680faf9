#include "smoothing/settled_vertices.hpp"

namespace bodt {

namespace {

// Whether a vertex of the n tets `star` moved at `at` or later.  Every
// tet is read, without a branch: the reads of the star's tets then go out
// together (the gather that follows for a vertex not settled reads the
// same tets), where a loop stopping at the first vertex that moved waited
// for each read in turn.
BODT_VECTOR_CLONES
bool any_moved(const int32_t* star, size_t n, const int32_t* tets, const uint32_t* moved_at, uint32_t at) {
    uint32_t moved = 0;
#pragma omp simd reduction(| : moved)
    for (size_t s = 0; s < n; ++s) {
        const int32_t* q = tets + 4 * static_cast<size_t>(star[s]);
        moved |= static_cast<uint32_t>(moved_at[q[0]] >= at) | static_cast<uint32_t>(moved_at[q[1]] >= at) |
                 static_cast<uint32_t>(moved_at[q[2]] >= at) | static_cast<uint32_t>(moved_at[q[3]] >= at);
    }
    return moved != 0;
}

}  // namespace

bool SettledVertices::moved_since(const TetMesh& mesh, int32_t v, uint32_t at) const {
    const int32_t* star = mesh.star_begin(v);
    static_assert(sizeof(Tet) == 4 * sizeof(int32_t));
    return any_moved(star, static_cast<size_t>(mesh.star_end(v) - star),
                     reinterpret_cast<const int32_t*>(mesh.tets.data()), moved_at_.data(), at);
}

}  // namespace bodt
