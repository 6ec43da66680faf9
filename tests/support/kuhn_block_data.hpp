// The mesh the VTK reader tests (test_io_vtu, test_io_vtk) round-trip: a
// block of Kuhn cubes with every kind of mesh data a file can carry.
#pragma once

#include "io/mesh_io.hpp"
#include "quality/tet_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace io_test {

// An n x n x n block of unit-ish cubes, each split into 6 Kuhn tets,
// positively oriented, vertex indices from `base`.  Coordinates are not
// short decimals, so a %.6g writer would fail the bit-exact check.
inline bodt::MeshData kuhn_block(int n, int base) {
    bodt::MeshData d;
    d.base = base;
    const int m = n + 1;
    auto vid = [&](int i, int j, int k) { return (i * m + j) * m + k; };
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
            for (int k = 0; k < m; ++k) {
                d.xyz.push_back(i / 3.0 + 1e-9 * j);
                d.xyz.push_back(j * 0.1 + std::sqrt(2.0) * 1e-7 * k);
                d.xyz.push_back(k / 7.0 - 1e300 * 0.0 + std::ldexp(1.0, -40) * i);
            }
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k)
                for (const auto& p : perms) {
                    int c[3] = {i, j, k};
                    std::array<int32_t, 4> t;
                    t[0] = vid(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[p[s]];
                        t[s + 1] = vid(c[0], c[1], c[2]);
                    }
                    const bodt::Vec3 a(&d.xyz[3 * t[0]]), b(&d.xyz[3 * t[1]]), cc(&d.xyz[3 * t[2]]),
                        dd(&d.xyz[3 * t[3]]);
                    if ((b - a).dot((cc - a).cross(dd - a)) < 0) std::swap(t[2], t[3]);
                    for (int32_t v : t) d.tets.push_back(v + base);
                    d.regions.push_back(i == 0 ? -2 : 5 + k);
                }
    return d;
}

using Tri = std::array<int32_t, 3>;
inline Tri sorted_tri(int32_t a, int32_t b, int32_t c) {
    Tri t = {a, b, c};
    std::sort(t.begin(), t.end());
    return t;
}

// Marks the boundary faces (marker by side, x = 0 gets -3) plus one
// interface face (marker 99); feature edges along x at y = z = 0 with refs
// (-1 among them); fixed vertices, corners and vertex refs (negative too).
inline void decorate(bodt::MeshData& d, int n) {
    const int faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    std::map<Tri, std::vector<std::array<int32_t, 3>>> count;
    for (size_t t = 0; t < d.tets.size() / 4; ++t)
        for (const auto& f : faces) {
            const std::array<int32_t, 3> tri = {d.tets[4 * t + f[0]], d.tets[4 * t + f[1]], d.tets[4 * t + f[2]]};
            count[sorted_tri(tri[0], tri[1], tri[2])].push_back(tri);
        }
    bool interface_done = false;
    for (const auto& [key, tris] : count) {
        int g[3][3];  // grid coordinates (i, j, k) of the three vertices
        for (int v = 0; v < 3; ++v) {
            const int id = key[v] - d.base;
            g[v][0] = id / ((n + 1) * (n + 1));
            g[v][1] = id / (n + 1) % (n + 1);
            g[v][2] = id % (n + 1);
        }
        if (tris.size() == 2) {
            if (!interface_done) {
                interface_done = true;
                d.triangles.insert(d.triangles.end(), tris[1].begin(), tris[1].end());
                d.tri_markers.push_back(99);
            }
            continue;
        }
        int marker = 0;
        for (int axis = 0; axis < 3 && marker == 0; ++axis) {
            if (g[0][axis] == 0 && g[1][axis] == 0 && g[2][axis] == 0) marker = axis == 0 ? -3 : 1 + axis;
        }
        if (marker == 0) marker = 10;  // far sides
        d.triangles.insert(d.triangles.end(), tris[0].begin(), tris[0].end());
        d.tri_markers.push_back(marker);
    }
    const int m = n + 1;
    for (int i = 0; i < n; ++i) {
        d.feature_edges.push_back(i * m * m + d.base);
        d.feature_edges.push_back((i + 1) * m * m + d.base);
        d.edge_refs.push_back(i % 2 ? -1 : 40 + i);
    }
    const int32_t nv = static_cast<int32_t>(d.xyz.size() / 3);
    d.fixed = {0 + d.base, nv - 1 + d.base, m - 1 + d.base, 0 + d.base};  // a duplicate on purpose
    d.corners = {n * m * m + d.base, 0 + d.base, n * m * m + d.base};    // a duplicate too
    for (int32_t v = 0; v < nv; ++v) d.vertex_refs.push_back(v % 4 == 0 ? 0 : v % 3 - 1 + 1000 * (v % 2));
}

}  // namespace io_test
