// Mesh density and the target density field of paper 002 (sec. 3.2): the
// density of a vertex is the mean of the reciprocal lengths of its edges;
// the target field is a regular grid over the deformed mesh whose points
// interpolate the original vertex densities barycentrically in the
// deformed tet that holds them (eq. 3.2), and whose cells take the mean of
// their corners' non-zero values.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace bodt {

// Per vertex: the mean of 1/|e| over the edges at v (0 for an unused vertex).
std::vector<double> vertex_density(const TetMesh& mesh);

class DensityGrid {
public:
    DensityGrid() = default;

    // A grid given by the caller: values at dims[0] * dims[1] * dims[2]
    // points, x fastest; a value <= 0 (or not finite) marks a point without
    // one.  Throws Error(BODT_ERR_INVALID_ARGUMENT) for dims < 2, spacing
    // not > 0 or a non-finite origin.
    DensityGrid(const Vec3& origin, const Vec3& spacing, const std::array<int32_t, 3>& dims,
                std::vector<double> point_values);

    // Eq. (3.2): a grid over `deformed`'s bounding box (a little larger) with
    // cells of about `spacing` (enlarged if the grid would pass
    // `max_points`), each point holding the barycentric interpolation of
    // `density` (per vertex of `deformed`) in the deformed tet that contains
    // it; points in no tet get 0.  Inverted tets are skipped.
    static DensityGrid interpolate(const TetMesh& deformed, const std::vector<double>& density, double spacing,
                                   int64_t max_points = int64_t(1) << 21);

    bool empty() const { return values_.empty(); }
    // rho'_e: the density of the cell that holds x (sec. 3.2: the mean of
    // its corners' non-zero values); points outside the grid take the
    // nearest cell.  0 when that cell has no non-zero corner.
    double at(const Vec3& x) const;

    const Vec3& origin() const { return origin_; }
    const Vec3& spacing() const { return spacing_; }
    const std::array<int32_t, 3>& dims() const { return dims_; }
    const std::vector<double>& point_values() const { return values_; }

private:
    Vec3 origin_ = Vec3::Zero(), spacing_ = Vec3::Ones();
    std::array<int32_t, 3> dims_{0, 0, 0};
    std::vector<double> values_;  // per point, x fastest
    std::vector<double> cells_;   // per cell, x fastest: mean of the non-zero corners
};

// Eq. (4.1) over the edges of `mesh`: |rho_e - rho'_e| / rho'_e with
// rho_e = 1/|e| and rho'_e the grid's density at the edge's midpoint
// (edges where the grid has no density are skipped).
struct DensityError {
    double mean = 0.0, max = 0.0;
    int64_t edges = 0;
};
DensityError density_error(const TetMesh& mesh, const DensityGrid& grid);

}  // namespace bodt
