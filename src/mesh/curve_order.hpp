// The internal order of a mesh's vertices and tets (issue 9): vertices
// along a Hilbert curve through their bounding box, tets by their first
// vertex on that curve.  Neighbours then lie close together in memory, so
// building the topology and sweeping the vertices do not jump about a mesh
// the caller numbered at random.  The caller never sees this order:
// CallerNumbering takes every index back to theirs at the C API.
#pragma once

#include <cstdint>
#include <vector>

namespace bodt {

// The caller's numbering of a mesh stored in the internal order.  The maps
// cover the input; vertices made by operations are appended in both
// numberings, so past the input vertices a vertex's index is the same in
// both.  Empty maps: the internal order is the caller's (the creation flag
// BODT_CREATE_KEEP_ORDER, or an input that could not be ordered).
struct CallerNumbering {
    std::vector<int32_t> vertex_to_caller;    // input vertex: internal index -> caller's index
    std::vector<int32_t> vertex_from_caller;  // the inverse
    std::vector<int32_t> tet_to_caller;       // input tet: internal index -> caller's index

    bool is_identity() const { return vertex_to_caller.empty() && tet_to_caller.empty(); }
    int32_t caller_vertex(int32_t v) const {
        return v < static_cast<int32_t>(vertex_to_caller.size()) ? vertex_to_caller[v] : v;
    }
    int32_t internal_vertex(int32_t c) const {
        return c < static_cast<int32_t>(vertex_from_caller.size()) ? vertex_from_caller[c] : c;
    }
    int32_t caller_input_tet(int32_t t) const {
        return t < static_cast<int32_t>(tet_to_caller.size()) ? tet_to_caller[t] : t;
    }
};

// The curve order of nverts points (xyz, 3 each) and ntets tets (tets, 4
// vertex indices each in base `base`).  Vertices are sorted by the Hilbert
// key of their coordinates quantised to 21 bits per axis over the bounding
// box, tets by their smallest internal vertex index; ties go by the
// caller's index, so the order is a function of the input alone.  Returns
// the identity (empty maps) when an index is out of range or a coordinate
// is not finite: the validation, in the caller's order, then names it.
CallerNumbering curve_order(int32_t nverts, const double* xyz, int32_t ntets, const int32_t* tets, int base);

// The input in the internal order of `numbering` (not the identity): the
// coordinates of internal vertex v at xyz_out[3v..3v+2], internal tet t at
// tets_out[4t..4t+3] with its vertices renamed (in base `base`, in the
// caller's order within the tet, so orientation and corners are kept).
void renumber_input(const CallerNumbering& numbering, const double* xyz, const int32_t* tets, int base,
                    std::vector<double>& xyz_out, std::vector<int32_t>& tets_out);

}  // namespace bodt
