#include "smoothing/laplace.hpp"

#include <algorithm>

namespace bodt {

Vec3 laplace_target(const TetMesh& mesh, int32_t v, std::vector<int32_t>& scratch) {
    scratch.clear();
    for (const int32_t* t = mesh.star_begin(v); t != mesh.star_end(v); ++t)
        for (int32_t w : mesh.tets[*t])
            if (w != v) scratch.push_back(w);
    // Summed in the caller's order: the mean's last bits must not depend
    // on the internal one.
    std::sort(scratch.begin(), scratch.end(),
              [&mesh](int32_t a, int32_t b) { return mesh.caller_vertex(a) < mesh.caller_vertex(b); });
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    Vec3 sum = Vec3::Zero();
    for (int32_t w : scratch) sum += mesh.points[w];
    return sum / static_cast<double>(scratch.size());
}

}  // namespace bodt
