#include "cli/domain_boundary.hpp"

#include <algorithm>
#include <array>

namespace bodt_cli {

namespace {

// A face of tet `tet`: its sorted vertices (16 bytes: a mesh of a million
// tets sorts four million of them).
struct TetFace {
    std::array<int32_t, 3> key;
    int32_t tet;
};

const int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

}  // namespace

std::vector<int32_t> domain_boundary(const MeshSnapshot& m) {
    std::vector<TetFace> faces;
    faces.reserve(4 * static_cast<size_t>(m.ntets));
    for (size_t t = 0; t < static_cast<size_t>(m.ntets); ++t)
        for (int i = 0; i < 4; ++i) {
            TetFace f;
            for (int k = 0; k < 3; ++k) f.key[k] = m.tets[4 * t + kFace[i][k]];
            std::sort(f.key.begin(), f.key.end());
            f.tet = static_cast<int32_t>(t);
            faces.push_back(f);
        }
    std::sort(faces.begin(), faces.end(), [](const TetFace& a, const TetFace& b) { return a.key < b.key; });
    const auto point = [&](int32_t v) { return &m.xyz[3 * static_cast<size_t>(v)]; };
    std::vector<int32_t> out;
    for (size_t k = 0; k < faces.size();) {
        size_t j = k;
        while (j < faces.size() && faces[j].key == faces[k].key) ++j;
        if (j - k == 1) {
            const size_t t = static_cast<size_t>(faces[k].tet);
            // The face is opposite the tet's vertex that is not in it.
            size_t i = 0;
            while (std::binary_search(faces[k].key.begin(), faces[k].key.end(), m.tets[4 * t + i])) ++i;
            std::array<int32_t, 3> f;
            for (int c = 0; c < 3; ++c) f[c] = m.tets[4 * t + kFace[i][c]] - m.base;
            // Outward: the fourth vertex lies behind the face.
            const double *a = point(f[0]), *b = point(f[1]), *c = point(f[2]), *d = point(m.tets[4 * t + i] - m.base);
            const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
            if (n[0] * (d[0] - a[0]) + n[1] * (d[1] - a[1]) + n[2] * (d[2] - a[2]) > 0.0) std::swap(f[1], f[2]);
            out.insert(out.end(), f.begin(), f.end());
        }
        k = j;
    }
    return out;
}

}  // namespace bodt_cli
