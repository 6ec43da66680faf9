// hole_box.hpp -- the box with a cylindrical hole of bodt_bench_deformed
// (paper 002, sec. 4: the DP / RC / PH example) and its dimension-driven
// deformations.
#ifndef BODT_BENCH_HOLE_BOX_HPP
#define BODT_BENCH_HOLE_BOX_HPP

#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// An O-grid box with a vertical hole: the square |x|, |y| <= half_width
// minus the disk of `radius` around the z axis, z in [0, height].  nt
// directions around the hole (a multiple of 4: nt/4 per side of the square),
// nr + 1 rings from the circle (ring 0, the inscribed nt-gon) to the square
// (ring nr, exactly the square), each ring point linear between the two;
// nz + 1 layers.  Vertex (ring i, direction j, layer k) is (k (nr + 1) + i)
// nt + j; each hex cell is cut into the six Kuhn tets of its diagonal from
// (i, j, k) to (i + 1, j + 1, k + 1): 6 nr nt nz tets, all positive.
struct HoleBox {
    int nr = 8, nt = 48, nz = 8;
    double half_width = 1.0, radius = 0.4, height = 0.6;
};

// Makes the mesh (0-based); false with a message on bad arguments or a tet
// that is not positive.
bool make_hole_box(const HoleBox& b, std::vector<double>& xyz, std::vector<int32_t>& tets, std::string& err);

// A dimension-driven deformation of the mesh of make_hole_box(b), made from
// its undeformed coordinates (same numbering and tets, no smoothing):
//  DP: every vertex with x > 0 gets x *= stretch_x (the side x = +half_width
//      moves away from x = -half_width; the sides y = +-half_width stretch);
//  RC, PH: the hole's ring alone (the ring-0 vertices of every layer) is put
//      on the circle of `radius` around (shift_x, shift_y), each vertex in
//      its own direction; this replaces what DP did to it, so the hole stays
//      an exact circular cylinder.  Every other vertex keeps what DP gave it,
//      so where the ring passes ring 1 the tets between them invert.
struct HoleDeformation {
    double stretch_x = 1.0;  // DP
    double radius = 0.4;     // RC (the undeformed radius: no change)
    double shift_x = 0.0, shift_y = 0.0;  // PH
};
std::vector<double> deform_hole_box(const HoleBox& b, const HoleDeformation& d, const std::vector<double>& xyz);

}  // namespace bench

#endif
