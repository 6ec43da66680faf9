// The tets around one vertex as a table of plain doubles, one row per corner
// and coordinate: what the B-ODT model and the move guard read, gathered
// once per vertex in a layout that their loops over the tets vectorise on.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <cstdint>
#include <vector>

namespace bodt {

class StarTable {
public:
    // The star of v in `mesh`, each tet's corners in the tet's own order.
    void gather(const TetMesh& mesh, int32_t v);
    // Or tet by tet: room for n tets, then tet s with the vertex at corner `at`.
    void resize(size_t n);
    void set(size_t s, const TetPoints& p, int at);
    // Puts the vertex at x in every tet of the star.
    void place(const Vec3& x);

    size_t size() const { return size_; }
    // 12 rows of size(): x of corners 0..3, then y, then z.  Row r, tet s
    // is corners()[r * size() + s].
    const double* corners() const { return corners_.data(); }
    // 9 rows of size(): the face opposite the vertex, its corners in
    // kFaceVertex order (the right-hand normal points away from the vertex):
    // x of corners 0..2, then y, then z.
    const double* opposite() const { return opposite_.data(); }

private:
    size_t size_ = 0;
    std::vector<double> corners_, opposite_;
    std::vector<uint8_t> at_;  // the vertex's corner in each tet
};

}  // namespace bodt
