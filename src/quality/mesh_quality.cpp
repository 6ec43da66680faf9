#include "quality/mesh_quality.hpp"

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

QualityExtremes quality_extremes(const TetMesh& mesh, int threads) {
    // dihedral_cosines(), compared before the arc cosine, which is
    // decreasing: acos(largest cosine) is the smallest angle.
    double cos_of_min = -1.0, cos_of_max = 1.0, min_stretch = 1.0;
    const int32_t nt = mesh.num_tets();
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : cos_of_min) \
    reduction(min : cos_of_max, min_stretch)
    for (int32_t t = 0; t < nt; ++t) {
        const auto p = mesh.tet_points(t);
        min_stretch = std::min(min_stretch, stretch(p));
        if (orient(p[0], p[1], p[2], p[3]).sign <= 0) {  // counts as 0 and 180 degrees
            cos_of_min = 1.0;
            cos_of_max = -1.0;
            continue;
        }
        for (const double c : dihedral_cosines(p)) {
            cos_of_min = std::max(cos_of_min, c);
            cos_of_max = std::min(cos_of_max, c);
        }
    }
    constexpr double kDegrees = 180.0 / M_PI;
    return {std::acos(cos_of_min) * kDegrees, std::acos(cos_of_max) * kDegrees, min_stretch};
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
