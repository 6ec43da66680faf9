// The tets around one vertex as a table of plain doubles: the face of each
// tet opposite the vertex, one row per corner and coordinate, and the
// vertex's corner in the tet.  What the B-ODT model and the move guard read,
// gathered once per vertex in a layout that their loops over the tets
// vectorise on; the guard puts the vertex at each place it tries as it
// reads a tet (star_tet_kernel), so a trial move writes nothing.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <vector>

namespace bodt {

class StarTable {
public:
    // The star of v in `mesh`.
    void gather(const TetMesh& mesh, int32_t v);
    // Or tet by tet: room for n tets, then tet s with the vertex at corner `at`.
    void resize(size_t n);
    void set(size_t s, const TetPoints& p, int at);

    size_t size() const { return size_; }
    // 9 rows of size(): the face opposite the vertex, its corners in
    // kFaceVertex order (the right-hand normal points away from the vertex):
    // x of corners 0..2, then y, then z.  Row r, tet s is opposite()[r * size() + s].
    const double* opposite() const { return opposite_.data(); }
    // The vertex's corner (0..3) in each tet, as a double: the kernel's
    // selects on it then need no mask of another width to vectorise.
    const double* at() const { return at_.data(); }

private:
    size_t size_ = 0;
    std::vector<double> opposite_;
    std::vector<double> at_;
};

// Tet s of a star table with the vertex at x: its corners in the tet's own
// order, so the kernel gives the bits it gives for the tet in the mesh.
// Corner j != at is the opposite face's corner k with kFaceVertex[at][k] = j.
BODT_KERNEL TetKernel star_tet_kernel(const double* opposite, const double* at, size_t n, size_t s, const Coords& x) {
    const auto face = [opposite, n, s](size_t k) -> Coords {
        return {opposite[k * n + s], opposite[(3 + k) * n + s], opposite[(6 + k) * n + s]};
    };
    const auto pick = [](bool first, const Coords& a, const Coords& b) -> Coords {
        return {first ? a.x : b.x, first ? a.y : b.y, first ? a.z : b.z};
    };
    const Coords f0 = face(0), f1 = face(1), f2 = face(2);
    const double a = at[s];
    const Coords c0 = pick(a == 0.0, x, f0);
    const Coords c1 = pick(a == 1.0, x, pick(a == 0.0, f0, pick(a == 2.0, f1, f2)));
    const Coords c2 = pick(a == 2.0, x, pick(a == 1.0, f2, f1));
    const Coords c3 = pick(a == 3.0, x, pick(a == 1.0, f1, f2));
    return tet_kernel(c0, c1, c2, c3);
}

}  // namespace bodt
