#include "smoothing/opt_weighted.hpp"

namespace bodt {

bool OptWeightedSmoother::target(const TetMesh& mesh, int32_t v, Vec3& target) {
    if (cls_[v] != VertexClass::Interior) return false;
    const auto is_free = [this](int32_t u) { return cls_[u] == VertexClass::Interior; };
    gather_weighted_star(mesh, mesh.star_begin(v), mesh.star_end(v), v, is_free, weights_, star_);
    const QuasiNewtonResult r = minimize_quasi_newton(star_, mesh.points[v], qn_);
    if (r.iterations == 0) return false;
    target = r.x;
    return true;
}

std::vector<uint8_t> poor_vertices(const TetMesh& mesh, double poor) {
    std::vector<uint8_t> in(mesh.points.size(), 0);
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        if (stretch(mesh.tet_points(t)) >= poor) continue;
        for (int32_t u : mesh.tets[t]) in[u] = 1;
    }
    return in;
}

}  // namespace bodt
