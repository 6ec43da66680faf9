// Mesh density and the target density field of paper 002 (sec. 3.2, eq. 3.2
// and eq. 4.1); see density_field.hpp.
#include "pipeline/density_field.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace bodt {

namespace {

// The distinct edges of the mesh's tets, sorted.
std::vector<EdgeKey> distinct_edges(const TetMesh& mesh) {
    std::vector<EdgeKey> edges;
    edges.reserve(6 * mesh.tets.size());
    for (const Tet& t : mesh.tets)
        for (const auto& e : kEdgeVertex) edges.push_back(edge_key(t[e[0]], t[e[1]]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

void check_tet_indices(const TetMesh& mesh) {
    const int32_t n = mesh.num_vertices();
    for (size_t t = 0; t < mesh.tets.size(); ++t)
        for (int32_t v : mesh.tets[t])
            if (v < 0 || v >= n)
                throw Error(BODT_ERR_INVALID_ARGUMENT, "density field: tet " + std::to_string(t) +
                                                           " has vertex " + std::to_string(v) +
                                                           " outside [0, " + std::to_string(n) + ")");
}

bool all_finite(const Vec3& x) { return std::isfinite(x.x()) && std::isfinite(x.y()) && std::isfinite(x.z()); }

const char* axis_name(int a) { return a == 0 ? "x" : (a == 1 ? "y" : "z"); }

}  // namespace

std::vector<double> vertex_density(const TetMesh& mesh) {
    check_tet_indices(mesh);
    const size_t n = mesh.points.size();
    std::vector<double> sum(n, 0.0);
    std::vector<int32_t> count(n, 0);
    for (EdgeKey k : distinct_edges(mesh)) {
        const int32_t a = edge_first(k), b = edge_second(k);
        const double len = (mesh.points[a] - mesh.points[b]).norm();
        const double inv = 1.0 / len;  // +inf for a zero-length edge
        sum[a] += inv;
        sum[b] += inv;
        ++count[a];
        ++count[b];
    }
    for (size_t v = 0; v < n; ++v) sum[v] = count[v] > 0 ? sum[v] / count[v] : 0.0;
    return sum;
}

DensityGrid::DensityGrid(const Vec3& origin, const Vec3& spacing, const std::array<int32_t, 3>& dims,
                         std::vector<double> point_values) {
    for (int a = 0; a < 3; ++a) {
        if (dims[a] < 2)
            throw Error(BODT_ERR_INVALID_ARGUMENT, std::string("density grid: ") + axis_name(a) + " dimension " +
                                                       std::to_string(dims[a]) + " must be at least 2");
        if (!(spacing[a] > 0.0) || !std::isfinite(spacing[a]))
            throw Error(BODT_ERR_INVALID_ARGUMENT, std::string("density grid: ") + axis_name(a) +
                                                       " spacing must be positive and finite");
        if (!std::isfinite(origin[a]))
            throw Error(BODT_ERR_INVALID_ARGUMENT,
                        std::string("density grid: ") + axis_name(a) + " origin must be finite");
    }
    // The number of points, checked against overflow (each factor >= 2).
    const int64_t limit = std::numeric_limits<int64_t>::max();
    int64_t points = 1;
    for (int a = 0; a < 3; ++a) {
        if (points > limit / dims[a])
            throw Error(BODT_ERR_INVALID_ARGUMENT, "density grid: " + std::to_string(dims[0]) + " x " +
                                                       std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
                                                       " points overflow a 64-bit count");
        points *= dims[a];
    }
    if (static_cast<uint64_t>(points) != static_cast<uint64_t>(point_values.size()))
        throw Error(BODT_ERR_INVALID_ARGUMENT, "density grid: " + std::to_string(point_values.size()) +
                                                   " values given for " + std::to_string(dims[0]) + " x " +
                                                   std::to_string(dims[1]) + " x " + std::to_string(dims[2]) +
                                                   " = " + std::to_string(points) + " points");
    origin_ = origin;
    spacing_ = spacing;
    dims_ = dims;
    values_ = std::move(point_values);

    // Cells: the mean of the corners' values that are > 0 and finite.
    const int64_t nx = dims_[0], ny = dims_[1], nz = dims_[2];
    const int64_t cx = nx - 1, cy = ny - 1, cz = nz - 1;
    cells_.assign(static_cast<size_t>(cx * cy * cz), 0.0);
    for (int64_t k = 0; k < cz; ++k)
        for (int64_t j = 0; j < cy; ++j)
            for (int64_t i = 0; i < cx; ++i) {
                double sum = 0.0;
                int used = 0;
                for (int c = 0; c < 8; ++c) {
                    const int64_t p = (i + (c & 1)) + nx * ((j + ((c >> 1) & 1)) + ny * (k + ((c >> 2) & 1)));
                    const double v = values_[static_cast<size_t>(p)];
                    if (v > 0.0 && std::isfinite(v)) {
                        sum += v;
                        ++used;
                    }
                }
                cells_[static_cast<size_t>(i + cx * (j + cy * k))] = used > 0 ? sum / used : 0.0;
            }
}

DensityGrid DensityGrid::interpolate(const TetMesh& deformed, const std::vector<double>& density, double spacing,
                                     int64_t max_points) {
    if (!(spacing > 0.0) || !std::isfinite(spacing))
        throw Error(BODT_ERR_INVALID_ARGUMENT, "density field: the grid spacing must be positive and finite");
    if (max_points < 27)
        throw Error(BODT_ERR_INVALID_ARGUMENT,
                    "density field: max_points " + std::to_string(max_points) +
                        " is below the 27 points of the smallest grid (3 per axis: the mesh padded by half a "
                        "spacing on each side)");
    if (density.size() != deformed.points.size())
        throw Error(BODT_ERR_INVALID_ARGUMENT, "density field: " + std::to_string(density.size()) +
                                                   " densities given for " +
                                                   std::to_string(deformed.points.size()) + " vertices");
    check_tet_indices(deformed);
    if (deformed.tets.empty()) return DensityGrid();

    // Bounding box of the used vertices (those of some tet).
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    for (const Tet& t : deformed.tets)
        for (int32_t v : t) {
            lo = lo.cwiseMin(deformed.points[v]);
            hi = hi.cwiseMax(deformed.points[v]);
        }
    if (!all_finite(lo) || !all_finite(hi))
        throw Error(BODT_ERR_INVALID_ARGUMENT, "density field: the mesh has a non-finite vertex coordinate");

    // Dims for spacing h: the box padded by h / 2 on every side, so
    // ceil(extent / h + 1) + 1 points per axis (3 at least unless flat).
    // The count does not increase with h; when `spacing` gives too many
    // points, the smallest h (to the last bit) that fits is bisected for.
    const Vec3 extent = hi - lo;
    std::array<int32_t, 3> dims{2, 2, 2};
    auto grid_dims = [&](double h, std::array<int32_t, 3>& d) {
        double total = 1.0;
        for (int a = 0; a < 3; ++a) {
            const double n = std::max(2.0, std::ceil(extent[a] / h + 1.0) + 1.0);
            if (!(n <= static_cast<double>(std::numeric_limits<int32_t>::max()))) return false;
            d[a] = static_cast<int32_t>(n);
            total *= n;
        }
        return total <= static_cast<double>(max_points);
    };
    double h = spacing;
    if (!grid_dims(h, dims)) {
        double below = h;  // does not fit
        double above = 2.0 * std::max(spacing, extent.maxCoeff());  // 3 points per axis at most: fits
        for (int it = 0; it < 2000; ++it) {
            const double mid =
                above / below > 4.0 ? std::sqrt(below) * std::sqrt(above) : below + 0.5 * (above - below);
            if (!(mid > below && mid < above)) break;
            std::array<int32_t, 3> d{};
            (grid_dims(mid, d) ? above : below) = mid;
        }
        h = above;
        if (!grid_dims(h, dims))
            throw Error(BODT_ERR_INVALID_ARGUMENT, "density field: no grid spacing fits max_points " +
                                                       std::to_string(max_points));
    }
    const Vec3 origin = lo - Vec3::Constant(0.5 * h);

    const int64_t nx = dims[0], ny = dims[1], nz = dims[2];
    const size_t npoints = static_cast<size_t>(nx * ny * nz);
    std::vector<double> values(npoints, 0.0);
    // The smallest barycentric coordinate of the tet a point was assigned
    // to; the tet with the largest one wins (the first on a tie).
    std::vector<double> best(npoints, -std::numeric_limits<double>::infinity());
    constexpr double kInside = -1e-12;  // barycentric tolerance

    // The index range of grid points in [x0, x1] along axis a, a little
    // widened so that points on the box (within the tolerance) are kept.
    auto index_range = [&](int a, double x0, double x1, int64_t& i0, int64_t& i1) {
        const double pad = 1e-9;
        const double f0 = std::ceil((x0 - origin[a]) / h - pad);
        const double f1 = std::floor((x1 - origin[a]) / h + pad);
        const double last = static_cast<double>(dims[a] - 1);
        i0 = static_cast<int64_t>(std::clamp(f0, 0.0, last));
        i1 = static_cast<int64_t>(std::clamp(f1, 0.0, last));
        return f0 <= f1 && f1 >= 0.0 && f0 <= last;
    };

    for (const Tet& t : deformed.tets) {
        const Vec3& p0 = deformed.points[t[0]];
        const Vec3& p1 = deformed.points[t[1]];
        const Vec3& p2 = deformed.points[t[2]];
        const Vec3& p3 = deformed.points[t[3]];
        const Orientation o = orient(p0, p1, p2, p3);
        if (o.sign <= 0) continue;  // inverted or flat: skipped
        Eigen::Matrix3d m;
        m.col(0) = p1 - p0;
        m.col(1) = p2 - p0;
        m.col(2) = p3 - p0;
        const Eigen::Matrix3d inv = m.inverse();
        const double d0 = density[t[0]], d1 = density[t[1]], d2 = density[t[2]], d3 = density[t[3]];
        const Vec3 bmin = p0.cwiseMin(p1).cwiseMin(p2).cwiseMin(p3);
        const Vec3 bmax = p0.cwiseMax(p1).cwiseMax(p2).cwiseMax(p3);
        int64_t r0[3], r1[3];
        bool any = true;
        for (int a = 0; a < 3; ++a) any = index_range(a, bmin[a], bmax[a], r0[a], r1[a]) && any;
        if (!any) continue;
        for (int64_t k = r0[2]; k <= r1[2]; ++k)
            for (int64_t j = r0[1]; j <= r1[1]; ++j)
                for (int64_t i = r0[0]; i <= r1[0]; ++i) {
                    const Vec3 g(origin.x() + static_cast<double>(i) * h, origin.y() + static_cast<double>(j) * h,
                                 origin.z() + static_cast<double>(k) * h);
                    const Vec3 l = inv * (g - p0);
                    const double l0 = 1.0 - l.x() - l.y() - l.z();
                    const double lmin = std::min(std::min(l0, l.x()), std::min(l.y(), l.z()));
                    if (!(lmin >= kInside)) continue;
                    const size_t p = static_cast<size_t>(i + nx * (j + ny * k));
                    if (!(lmin > best[p])) continue;
                    best[p] = lmin;
                    // Eq. (3.2): the sub-volume ratios |tau^i| / |tau| are the
                    // barycentric coordinates.
                    values[p] = l0 * d0 + l.x() * d1 + l.y() * d2 + l.z() * d3;
                }
    }
    return DensityGrid(origin, Vec3::Constant(h), dims, std::move(values));
}

double DensityGrid::at(const Vec3& x) const {
    if (cells_.empty()) return 0.0;
    int64_t c[3];
    for (int a = 0; a < 3; ++a) {
        const double f = std::floor((x[a] - origin_[a]) / spacing_[a]);
        const int64_t last = dims_[a] - 2;
        if (!(f >= 0.0))
            c[a] = 0;  // below the grid, or NaN
        else if (f >= static_cast<double>(last))
            c[a] = last;
        else
            c[a] = static_cast<int64_t>(f);
    }
    const int64_t cx = dims_[0] - 1, cy = dims_[1] - 1;
    return cells_[static_cast<size_t>(c[0] + cx * (c[1] + cy * c[2]))];
}

DensityError density_error(const TetMesh& mesh, const DensityGrid& grid) {
    check_tet_indices(mesh);
    DensityError r;
    double sum = 0.0;
    for (EdgeKey k : distinct_edges(mesh)) {
        const Vec3& a = mesh.points[edge_first(k)];
        const Vec3& b = mesh.points[edge_second(k)];
        const double len = (a - b).norm();
        if (!(len > 0.0)) continue;  // a collapsed edge has no density
        const double target = grid.at(0.5 * (a + b));
        if (!(target > 0.0) || !std::isfinite(target)) continue;
        const double eps = std::abs(1.0 / len - target) / target;
        sum += eps;
        r.max = std::max(r.max, eps);
        ++r.edges;
    }
    r.mean = r.edges > 0 ? sum / static_cast<double>(r.edges) : 0.0;
    return r;
}

}  // namespace bodt
