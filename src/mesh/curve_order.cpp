#include "mesh/curve_order.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace bodt {

namespace {

constexpr int kBits = 21;  // per axis: three axes fill a 63-bit key

// The index along the Hilbert curve of order kBits of the grid point
// (x[0], x[1], x[2]): J. Skilling, "Programming the Hilbert curve", AIP
// Conf. Proc. 707 (2004), axes to transpose, then the transpose's bits
// interleaved (x[0]'s most significant at each level).
uint64_t hilbert_key(uint32_t x[3]) {
    const uint32_t top = 1u << (kBits - 1);
    for (uint32_t q = top; q > 1; q >>= 1) {
        const uint32_t p = q - 1;
        for (int i = 0; i < 3; ++i) {
            if (x[i] & q) {
                x[0] ^= p;  // invert
            } else {
                const uint32_t t = (x[0] ^ x[i]) & p;  // exchange
                x[0] ^= t;
                x[i] ^= t;
            }
        }
    }
    x[1] ^= x[0];  // Gray encode
    x[2] ^= x[1];
    uint32_t t = 0;
    for (uint32_t q = top; q > 1; q >>= 1)
        if (x[2] & q) t ^= q - 1;
    uint64_t key = 0;
    for (int b = kBits - 1; b >= 0; --b)
        for (int i = 0; i < 3; ++i) key = (key << 1) | (((x[i] ^ t) >> b) & 1u);
    return key;
}

// The smallest cube around the points, as its low corner and the factor
// that takes its side to 2^kBits; false when a coordinate or the side is
// not finite.
bool bounding_cube(int32_t nverts, const double* xyz, double lo[3], double& scale) {
    double hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = hi[k] = xyz[k];
    for (size_t i = 0; i < 3 * static_cast<size_t>(nverts); ++i) {
        const double c = xyz[i];
        if (!std::isfinite(c)) return false;
        lo[i % 3] = std::min(lo[i % 3], c);
        hi[i % 3] = std::max(hi[i % 3], c);
    }
    const double side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (!std::isfinite(side)) return false;
    scale = side > 0.0 ? std::ldexp(1.0, kBits) / side : 0.0;
    return true;
}

}  // namespace

CallerNumbering curve_order(int32_t nverts, const double* xyz, int32_t ntets, const int32_t* tets, int base) {
    CallerNumbering out;
    double lo[3], scale = 0.0;
    if (nverts <= 0 || ntets <= 0 || !bounding_cube(nverts, xyz, lo, scale)) return out;
    for (size_t i = 0; i < 4 * static_cast<size_t>(ntets); ++i)
        if (tets[i] < base || static_cast<int64_t>(tets[i]) - base >= nverts) return out;

    // Vertices by (key, caller's index).
    const uint32_t last = (1u << kBits) - 1;
    std::vector<std::pair<uint64_t, int32_t>> keyed(static_cast<size_t>(nverts));
    for (int32_t v = 0; v < nverts; ++v) {
        uint32_t q[3];
        for (int k = 0; k < 3; ++k)
            q[k] = std::min(last, static_cast<uint32_t>((xyz[3 * static_cast<size_t>(v) + k] - lo[k]) * scale));
        keyed[v] = {hilbert_key(q), v};
    }
    std::sort(keyed.begin(), keyed.end());
    out.vertex_to_caller.resize(keyed.size());
    out.vertex_from_caller.resize(keyed.size());
    for (int32_t v = 0; v < nverts; ++v) {
        out.vertex_to_caller[v] = keyed[v].second;
        out.vertex_from_caller[keyed[v].second] = v;
    }

    // Tets by their smallest internal vertex, a counting sort that keeps
    // the caller's order among tets with the same one.
    std::vector<int32_t> first(static_cast<size_t>(ntets));
    std::vector<int32_t> start(static_cast<size_t>(nverts) + 1, 0);
    for (int32_t t = 0; t < ntets; ++t) {
        const int32_t* q = tets + 4 * static_cast<size_t>(t);
        int32_t m = nverts;
        for (int k = 0; k < 4; ++k) m = std::min(m, out.vertex_from_caller[q[k] - base]);
        first[t] = m;
        ++start[m + 1];
    }
    for (int32_t v = 0; v < nverts; ++v) start[v + 1] += start[v];
    out.tet_to_caller.resize(static_cast<size_t>(ntets));
    for (int32_t t = 0; t < ntets; ++t) out.tet_to_caller[start[first[t]]++] = t;
    return out;
}

void renumber_input(const CallerNumbering& numbering, const double* xyz, const int32_t* tets, int base,
                    std::vector<double>& xyz_out, std::vector<int32_t>& tets_out) {
    const size_t nverts = numbering.vertex_to_caller.size(), ntets = numbering.tet_to_caller.size();
    xyz_out.resize(3 * nverts);
    for (size_t v = 0; v < nverts; ++v) {
        const size_t c = static_cast<size_t>(numbering.vertex_to_caller[v]);
        for (int k = 0; k < 3; ++k) xyz_out[3 * v + k] = xyz[3 * c + k];
    }
    tets_out.resize(4 * ntets);
    for (size_t t = 0; t < ntets; ++t) {
        const size_t c = static_cast<size_t>(numbering.tet_to_caller[t]);
        for (int k = 0; k < 4; ++k) tets_out[4 * t + k] = numbering.vertex_from_caller[tets[4 * c + k] - base] + base;
    }
}

}  // namespace bodt
