#include "mesh/region_surfaces.hpp"

#include <algorithm>

namespace bodt {

void RegionSurfaces::build(const TetMesh& mesh, int base, BoundarySurface::Strictness strictness) {
    std::vector<int32_t> regions = mesh.regions;
    std::sort(regions.begin(), regions.end());
    regions.erase(std::unique(regions.begin(), regions.end()), regions.end());
    surfaces_.assign(regions.size(), BoundarySurface());
    blocked_.clear();
    for (size_t k = 0; k < regions.size(); ++k) {
        surfaces_[k].build(mesh, base, regions[k], strictness);
        for (int32_t v : surfaces_[k].blocked()) {
            blocked_.resize(mesh.points.size(), 0);
            blocked_[v] = 1;
        }
    }

    const int32_t nv = mesh.num_vertices();
    offset_.assign(static_cast<size_t>(nv) + 1, 0);
    for (const BoundarySurface& s : surfaces_)
        for (int32_t v : s.vertices()) ++offset_[v + 1];
    for (int32_t v = 0; v < nv; ++v) offset_[v + 1] += offset_[v];
    at_.resize(static_cast<size_t>(offset_[nv]));
    std::vector<int32_t> fill(offset_.begin(), offset_.end() - 1);
    for (int32_t k = 0; k < count(); ++k)
        for (int32_t v : surfaces_[k].vertices()) at_[fill[v]++] = k;
}

}  // namespace bodt
