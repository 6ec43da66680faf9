// Helpers shared by the white-box C++ tests (those linking bodt_core):
// seeded random numbers and rotations, a generated mesh's arrays for
// build_mesh, the host's byte order, and CHECK, a condition check with a
// printf-style message.  Header only; include it after the other headers.
#ifndef BODT_TEST_CORE_CHECKS_HPP
#define BODT_TEST_CORE_CHECKS_HPP

#include "mesh/mesh_builder.hpp"
#include "quality/tet_geometry.hpp"

#include "mesh_gen.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "test_util.h"

// Seeded uniform random numbers (mesh_gen's tm_rng): the same on every platform.
struct Rng {
    tm_rng r;
    explicit Rng(uint64_t seed) { tm_rng_seed(&r, seed); }
    double uniform(double lo, double hi) { return lo + (hi - lo) * tm_rng_uniform(&r); }
    bodt::Vec3 point(double lo, double hi) { return bodt::Vec3(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)); }
};

// The sum of the tets' signed volumes.
inline double total_volume(const bodt::TetMesh& m) {
    double v = 0.0;
    for (int32_t t = 0; t < m.num_tets(); ++t) {
        const auto p = m.tet_points(t);
        v += bodt::signed_volume(p[0], p[1], p[2], p[3]);
    }
    return v;
}

// The arrays of a generated mesh, as the C API passes them to build_mesh.
inline bodt::MeshArrays mesh_arrays(const test_mesh& m) {
    bodt::MeshArrays a;
    a.nverts = m.nverts;
    a.xyz = m.xyz;
    a.ntets = m.ntets;
    a.tets = m.tets;
    return a;
}

// A random rotation (from a random unit quaternion).
inline Eigen::Matrix3d random_rotation(Rng& rng) {
    Eigen::Quaterniond q(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    q.normalize();
    return q.toRotationMatrix();
}

// Whether the host stores the low byte first (the byte builders of the
// reader tests assume it; on other hosts they skip).
inline bool little_endian_host() {
    const uint16_t probe = 1;
    uint8_t first;
    std::memcpy(&first, &probe, 1);
    return first == 1;
}

// Fails the test unless `cond`, with the message (printf arguments), the
// condition and the line, prefixed by `what` (a const char* in scope: the case).
#define CHECK(cond, ...)                                                   \
    do {                                                                   \
        if (!(cond)) {                                                     \
            char msg_[400];                                                \
            std::snprintf(msg_, sizeof msg_, __VA_ARGS__);                 \
            fail_msg("%s: %s (%s, line %d)", what, msg_, #cond, __LINE__); \
        }                                                                  \
    } while (0)

#endif  // BODT_TEST_CORE_CHECKS_HPP
