#include "quality/mesh_quality.hpp"

#include "common/parallel.hpp"

#include <algorithm>

namespace bodt {

int dihedral_bin(double degrees) {
    const double* hi = std::upper_bound(kDihedralBinEdges + 1, kDihedralBinEdges + kDihedralBins, degrees);
    return static_cast<int>(hi - (kDihedralBinEdges + 1));
}

QualitySummary summarize_quality(const TetMesh& mesh) {
    QualitySummary q;
    double angle_sum = 0.0, stretch_sum = 0.0;
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        const auto p = mesh.tet_points(t);
        const bool positive = orient(p[0], p[1], p[2], p[3]).sign > 0;
        const double s = stretch(p);
        q.volume += signed_volume(p[0], p[1], p[2], p[3]);
        q.min_stretch = std::min(q.min_stretch, s);
        stretch_sum += s;
        auto angles = dihedral_angles(p);
        if (!positive) {  // counts as one 0 and one 180 degree angle
            ++q.num_inverted;
            angles[0] = 0.0;
            angles[1] = 180.0;
        }
        for (double a : angles) {
            q.min_dihedral = std::min(q.min_dihedral, a);
            q.max_dihedral = std::max(q.max_dihedral, a);
            angle_sum += a;
            ++q.histogram[dihedral_bin(a)];
        }
    }
    const double nt = static_cast<double>(mesh.num_tets());
    q.mean_dihedral = angle_sum / (6.0 * nt);
    q.mean_stretch = stretch_sum / nt;
    for (uint8_t f : mesh.vflags) q.num_unused_vertices += (f & kUnused) != 0;
    return q;
}

namespace {

// tet_shape() of tets [first, first + n) to out[0 .. n): their corners
// gathered into a table (12 rows of n: x of corners 0..3, then y, then z)
// for a loop that vectorises.
constexpr size_t kBlock = 256;

BODT_VECTOR_CLONES
void block_shapes(const double* rows, size_t n, TetShape* out) {
#pragma omp simd
    for (size_t s = 0; s < n; ++s) {
        out[s] = shape_of(tet_kernel(rows, n, s));
    }
}

void shapes_of(const TetMesh& mesh, int32_t first, size_t n, double* rows, TetShape* out) {
    for (size_t s = 0; s < n; ++s) {
        const Tet& q = mesh.tets[static_cast<size_t>(first) + s];
        for (size_t j = 0; j < 4; ++j) {
            const Vec3& p = mesh.points[q[j]];
            rows[j * n + s] = p.x();
            rows[(4 + j) * n + s] = p.y();
            rows[(8 + j) * n + s] = p.z();
        }
    }
    block_shapes(rows, n, out);
}

}  // namespace

ShapeCache tet_shapes(const TetMesh& mesh, int threads) {
    ShapeCache shapes(mesh.tets.size());
    const int64_t nt = mesh.num_tets();
    // Chunks of whole blocks, so every block is the same on any number of threads.
    for_chunks(threads, nt, 64 * static_cast<int64_t>(kBlock), [&](int, int64_t begin, int64_t end) {
        double rows[12 * kBlock];
        for (int64_t first = begin; first < end; first += static_cast<int64_t>(kBlock)) {
            const size_t n = std::min(kBlock, static_cast<size_t>(end - first));
            shapes_of(mesh, static_cast<int32_t>(first), n, rows, shapes.data() + first);
        }
    });
    return shapes;
}

QualityExtremes quality_extremes(const ShapeCache& shapes, int threads) {
    // tet_shape() counts a tet that is not positively oriented as 0 and 180
    // degrees, as summarize_quality does; cosines are compared before the
    // arc cosine, which is decreasing: acos(largest cosine) is the smallest angle.
    struct Extremes {
        double cos_of_min = -1.0, cos_of_max = 1.0, min_stretch = 1.0;
    };
    std::vector<Extremes> partial(static_cast<size_t>(std::max(1, threads)));
    for_chunks(threads, static_cast<int64_t>(shapes.size()), 1 << 16, [&](int me, int64_t begin, int64_t end) {
        Extremes& e = partial[static_cast<size_t>(me)];
        for (int64_t t = begin; t < end; ++t) {
            const TetShape& s = shapes[static_cast<size_t>(t)];
            e.cos_of_min = std::max(e.cos_of_min, s.cosines.of_min);
            e.cos_of_max = std::min(e.cos_of_max, s.cosines.of_max);
            e.min_stretch = std::min(e.min_stretch, s.stretch);
        }
    });
    double cos_of_min = -1.0, cos_of_max = 1.0, min_stretch = 1.0;
    for (const Extremes& e : partial) {
        cos_of_min = std::max(cos_of_min, e.cos_of_min);
        cos_of_max = std::min(cos_of_max, e.cos_of_max);
        min_stretch = std::min(min_stretch, e.min_stretch);
    }
    constexpr double kDegrees = 180.0 / M_PI;
    return {std::acos(cos_of_min) * kDegrees, std::acos(cos_of_max) * kDegrees, min_stretch, {cos_of_min, cos_of_max}};
}

void tet_measures(const TetMesh& mesh, TetMeasure measure, std::vector<double>& out) {
    out.resize(mesh.tets.size());
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        const auto p = mesh.tet_points(t);
        switch (measure) {
            case TetMeasure::MinDihedral:
            case TetMeasure::MaxDihedral: {
                const auto r = dihedral_range(p, orient(p[0], p[1], p[2], p[3]).sign > 0);
                out[t] = measure == TetMeasure::MinDihedral ? r.min : r.max;
                break;
            }
            case TetMeasure::Stretch: out[t] = stretch(p); break;
            case TetMeasure::Volume: out[t] = signed_volume(p[0], p[1], p[2], p[3]); break;
        }
    }
}

}  // namespace bodt
