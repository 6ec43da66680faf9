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

namespace {

// No face of tet t is on a region surface.
bool inner_tet(const TetMesh& mesh, int32_t t) {
    for (int i = 0; i < 4; ++i)
        if (mesh.is_region_boundary_face(t, i)) return false;
    return true;
}

}  // namespace

// The operations replace a cavity by new tets with the same boundary, so a
// cavity of inner tets leaves every surface face where it was; the new
// tets are checked too.  The surfaces grow in the caller's tet order
// (BoundarySurface), which the tets still there keep unless `before` had
// not left it for the internal one yet.
bool RegionSurfaces::kept_by(const TetMesh& before, const TetMesh& after, const std::vector<int32_t>& written) {
    if (before.tet_origin.empty() && !before.caller.tet_to_caller.empty()) return false;
    int32_t kept = 0;
    for (int32_t t = 0; t < before.num_tets(); ++t) {
        if (written[t] >= 0) ++kept;
        else if (!inner_tet(before, t)) return false;
    }
    for (int32_t t = kept; t < after.num_tets(); ++t)
        if (!inner_tet(after, t)) return false;
    return true;
}

}  // namespace bodt
