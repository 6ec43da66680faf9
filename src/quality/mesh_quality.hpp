// Quality of a whole mesh: dihedral angles, stretch, volume, histogram.
#pragma once

#include "mesh/tet_mesh.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace bodt {

// Bin edges of the dihedral histogram (degrees), as documented in bodt.h and
// used by the meshq yardstick.
inline constexpr int kDihedralBins = 23;
inline constexpr double kDihedralBinEdges[kDihedralBins + 1] = {
    0, 5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150, 160, 165, 170, 175, 180};

struct QualitySummary {
    int32_t num_inverted = 0;
    int32_t num_unused_vertices = 0;
    double min_dihedral = 180.0, max_dihedral = 0.0, mean_dihedral = 0.0;
    double min_stretch = 1.0, mean_stretch = 0.0;
    double volume = 0.0;
    std::array<int64_t, kDihedralBins> histogram{};
};

QualitySummary summarize_quality(const TetMesh& mesh);

// tet_shape() of every tet: what the guards of a sweep share, kept up to
// date by their moves.
using ShapeCache = std::vector<TetShape>;
ShapeCache tet_shapes(const TetMesh& mesh, int threads);

// The extremes of summarize_quality alone (the same values) from the
// mesh's tet_shapes(), without an arc cosine per angle, on `threads`
// threads: what a step reports, and the cosines they come from.
struct QualityExtremes {
    double min_dihedral, max_dihedral, min_stretch;
    CosineRange cosines;
};
QualityExtremes quality_extremes(const ShapeCache& shapes, int threads);

int dihedral_bin(double degrees);

enum class TetMeasure { MinDihedral, MaxDihedral, Stretch, Volume };
void tet_measures(const TetMesh& mesh, TetMeasure measure, std::vector<double>& out);

}  // namespace bodt
