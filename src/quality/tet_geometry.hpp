// Geometry of one tetrahedron: signed volume with a certified sign, dihedral
// angles and the stretch quality.  Header-only so the compiler can inline the
// kernels into the smoothing sweeps.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace bodt {

using Vec3 = Eigen::Vector3d;

// One degree in radians.
inline constexpr double kDegree = M_PI / 180.0;

// The per-tet kernels are inlined into the loops over tets, whose
// vectorisation depends on it.
#if defined(__GNUC__)
#define BODT_KERNEL inline __attribute__((always_inline))
#else
#define BODT_KERNEL inline
#endif
// A function holding such a loop is built three times on x86-64 Linux, for
// AVX-512, AVX2 and the base instruction set, and the loader picks one.
// None may contract a multiply-add (-ffp-contract=off) or sum across vector
// lanes, so all give the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
    !defined(__SANITIZE_ADDRESS__)
#define BODT_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define BODT_VECTOR_CLONES
#endif

// Local vertex triples of the four faces, face i opposite vertex i, ordered so
// that the right-hand normal points out of a positively oriented tet.
inline constexpr int kFaceVertex[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
// The six edges (i, j) and the two faces (opposite k and l) that meet there.
inline constexpr int kEdgeVertex[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
inline constexpr int kEdgeFaces[6][2] = {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}};


// A point as three plain doubles: what the per-tet kernels work on, so that
// a loop over tets keeps them in registers and vectorises.
struct Coords {
    double x, y, z;
};
BODT_KERNEL Coords operator-(const Coords& a, const Coords& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
BODT_KERNEL Coords cross(const Coords& a, const Coords& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
BODT_KERNEL double dot(const Coords& a, const Coords& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Coords coords(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

// Sign of the orientation determinant 6V = (b-a) . ((c-a) x (d-a)),
// certified by Shewchuk's static error bound for orient3d ("Adaptive
// precision floating-point arithmetic", 1997, errboundA = (7 + 56 eps) eps):
// +1 or -1 when the sign of the exact determinant is known, 0 when round-off
// could flip it.  A tet with sign 0 is treated as flat.
struct Orientation {
    double det6;  // six times the signed volume
    int sign;
};

// The determinant and the permanent its error bound scales with.  The
// tests give bools of double comparisons only, so that a loop over tets
// using them vectorises with one mask width.
struct OrientTerms {
    double det, permanent;

    static constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
    static constexpr double kBound = (7.0 + 56.0 * kEps) * kEps;
    // The bound assumes no underflow, and the quality measures multiply up
    // to eight differences: a tet whose products are this small (less than
    // about 1e-30 across, or a sliver of denormal volume) counts as flat,
    // as does a non-finite determinant.
    static constexpr double kTiny = 1e-90;
    BODT_KERNEL bool usable() const {
        return (permanent >= kTiny) & (permanent <= std::numeric_limits<double>::max());
    }
    BODT_KERNEL bool positive() const { return usable() & (det > kBound * permanent); }
    BODT_KERNEL bool negative() const { return usable() & (det < -kBound * permanent); }
    BODT_KERNEL int sign() const { return positive() ? 1 : (negative() ? -1 : 0); }
};

BODT_KERNEL OrientTerms orient_terms(const Coords& a, const Coords& b, const Coords& c, const Coords& d) {
    const Coords u = b - a, v = c - a, w = d - a;
    const double m1 = v.y * w.z, m2 = v.z * w.y, m3 = v.z * w.x, m4 = v.x * w.z, m5 = v.x * w.y, m6 = v.y * w.x;
    const double det = u.x * (m1 - m2) + u.y * (m3 - m4) + u.z * (m5 - m6);
    const double permanent = std::abs(u.x) * (std::abs(m1) + std::abs(m2)) +
                             std::abs(u.y) * (std::abs(m3) + std::abs(m4)) +
                             std::abs(u.z) * (std::abs(m5) + std::abs(m6));
    return {det, permanent};
}

BODT_KERNEL Orientation orient(const Coords& a, const Coords& b, const Coords& c, const Coords& d) {
    const OrientTerms o = orient_terms(a, b, c, d);
    return {o.det, o.sign()};
}

inline Orientation orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return orient(coords(a), coords(b), coords(c), coords(d));
}

inline double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

using TetPoints = std::array<Vec3, 4>;

// The cosines of a tet's smallest and largest dihedral angle, without acos:
// the extremes the angle guard compares.  A tet that is not positively
// oriented (certified) counts as the worst possible: cosines 1 and -1, the
// 0 and 180 degrees of the quality measures.
struct CosineRange {
    double of_min;  // cos of the smallest angle (the largest cosine)
    double of_max;  // cos of the largest angle (the smallest cosine)
};

// The magnitude of the cosine of the tet's angle farthest from 90 degrees
// (1 for a tet that is not positively oriented): its worst angle's sine is
// sqrt(1 - worst_cosine^2).  The smallest angle is below 90 degrees, so its
// cosine is positive.
inline double worst_cosine(const CosineRange& c) { return std::max(c.of_min, -c.of_max); }

// What the move guard needs of a tet.
struct TetShape {
    double stretch;
    CosineRange cosines;
};

// Orientation, stretch and the six dihedral cosines of the tet with corners
// (x[i], y[i], z[i]), from one set of face normals: the one definition
// behind orient(), tet_shape() and dihedral_cosines(), so the guard, the
// step report and the quality summary agree to the last bit.  Plain doubles
// and selects only, so a loop over tets calling it vectorises (the guard's
// star kernel); no fused multiply-add may be contracted (-ffp-contract=off),
// so every build gives the same bits.
struct TetKernel {
    double det6;     // orient()
    int sign;        // orient()
    // 1 when sign is +1, else 0: a double, so that a vectorised loop over
    // tets that tests it needs no mask of another width (GCC 12 cannot
    // convert them).
    double positive;
    double stretch;  // 6 sqrt(6) V / (sum of face areas * longest edge), eq. 3.1 of papers 001 and 002
    double cos[6];   // interior dihedral cosines in kEdgeVertex order, in [-1, 1]
};

BODT_KERNEL TetKernel tet_kernel(const Coords& p0, const Coords& p1, const Coords& p2, const Coords& p3) {
    TetKernel k;
    const OrientTerms o = orient_terms(p0, p1, p2, p3);
    k.det6 = o.det;
    k.sign = o.sign();
    k.positive = o.positive() ? 1.0 : 0.0;
    // Face normals as kFaceVertex orders them (face i opposite corner i,
    // pointing out of a positive tet), their lengths (twice the face areas)
    // and inverse lengths.
    const Coords n[4] = {cross(p2 - p1, p3 - p1), cross(p3 - p0, p2 - p0), cross(p1 - p0, p3 - p0),
                         cross(p2 - p0, p1 - p0)};
    double len[4], inv[4];
    for (int i = 0; i < 4; ++i) {
        len[i] = std::sqrt(dot(n[i], n[i]));
        inv[i] = 1.0 / len[i];
    }
    const double area2 = len[0] + len[1] + len[2] + len[3];
    // The edges in kEdgeVertex order; the interior angle at an edge is pi
    // minus the angle between the outward normals of its two faces
    // (kEdgeFaces), 0 when one of them has no area.
    const Coords e[6] = {p1 - p0, p2 - p0, p3 - p0, p2 - p1, p3 - p1, p3 - p2};
    double lmax2 = 0.0;
    for (int i = 0; i < 6; ++i) {
        lmax2 = std::max(lmax2, dot(e[i], e[i]));
        const int f = kEdgeFaces[i][0], g = kEdgeFaces[i][1];
        const double c = -dot(n[f], n[g]) * inv[f] * inv[g];
        k.cos[i] = ((len[f] > 0.0) & (len[g] > 0.0)) ? std::min(1.0, std::max(-1.0, c)) : 1.0;
    }
    const double denom = area2 * std::sqrt(lmax2);
    k.stretch = denom > 0.0 ? 2.0 * std::sqrt(6.0) * k.det6 / denom : 0.0;
    return k;
}

// Column s of a corner table: 12 rows of n, x of corners 0..3, then y, then z.
BODT_KERNEL TetKernel tet_kernel(const double* rows, size_t n, size_t s) {
    const auto corner = [rows, n, s](size_t j) -> Coords {
        return {rows[j * n + s], rows[(4 + j) * n + s], rows[(8 + j) * n + s]};
    };
    return tet_kernel(corner(0), corner(1), corner(2), corner(3));
}

inline TetKernel tet_kernel(const TetPoints& p) {
    return tet_kernel(coords(p[0]), coords(p[1]), coords(p[2]), coords(p[3]));
}

// The guard's view of a kernel: stretch and extreme cosines, the worst
// possible for a tet that is not positively oriented.
BODT_KERNEL TetShape shape_of(const TetKernel& k) {
    TetShape s{k.stretch, {-1.0, 1.0}};
    for (int e = 0; e < 6; ++e) {
        s.cosines.of_min = std::max(s.cosines.of_min, k.cos[e]);
        s.cosines.of_max = std::min(s.cosines.of_max, k.cos[e]);
    }
    const bool positive = k.positive > 0.0;
    s.cosines = {positive ? s.cosines.of_min : 1.0, positive ? s.cosines.of_max : -1.0};
    return s;
}

inline TetShape tet_shape(const TetPoints& p) { return shape_of(tet_kernel(p)); }

// Stretch: 1 for the regular tet, 0 when flat, negative when inverted.
inline double stretch(const TetPoints& p) { return tet_shape(p).stretch; }

// The centre of the tet's circumsphere (not finite for a flat tet).
inline Vec3 circumcenter(const TetPoints& p) {
    const Vec3 u = p[1] - p[0], v = p[2] - p[0], w = p[3] - p[0];
    const double den = 2.0 * u.dot(v.cross(w));
    return p[0] + (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / den;
}

// x lies strictly inside the tet's circumsphere (by more than round-off of
// the radius): the tet is not Delaunay with respect to x.
inline bool in_circumsphere(const TetPoints& p, const Vec3& x) {
    const Vec3 c = circumcenter(p);
    return (x - c).squaredNorm() < (p[0] - c).squaredNorm() * (1.0 - 1e-10);
}

// The edge (a, b) shared by triangles (a, b, c) and (b, a, d) is not
// locally Delaunay: the angles opposite it sum to more than pi (beyond
// round-off).
inline bool edge_not_delaunay(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
        const Vec3 u = q - p, w = r - p;
        return std::atan2(u.cross(w).norm(), u.dot(w));
    };
    return angle(c, a, b) + angle(d, a, b) > M_PI * (1.0 + 1e-9);
}

// The sine of the tet's worst dihedral angle, small for angles near 0 and
// near 180 degrees alike: the quality the topology operations maximise.
// sin(theta_e) = 3 V |e| / (2 A_i A_j) for the faces i, j at edge e, which
// with 6V = det and |n| = 2A is det |e| / (|n_i| |n_j|).  Not positively
// oriented (certified): -1.
inline double min_dihedral_sine(const TetPoints& p) {
    const Orientation o = orient(p[0], p[1], p[2], p[3]);
    if (o.sign <= 0) return -1.0;
    std::array<double, 4> n;
    for (int i = 0; i < 4; ++i) {
        const auto& f = kFaceVertex[i];
        n[i] = (p[f[1]] - p[f[0]]).cross(p[f[2]] - p[f[0]]).norm();
    }
    double worst = 1.0;
    for (int e = 0; e < 6; ++e) {
        const double len = (p[kEdgeVertex[e][1]] - p[kEdgeVertex[e][0]]).norm();
        worst = std::min(worst, o.det6 * len / (n[kEdgeFaces[e][0]] * n[kEdgeFaces[e][1]]));
    }
    return worst;
}

// The cosines of the six interior dihedral angles, in kEdgeVertex order,
// in [-1, 1].  The angle at an edge is pi minus the angle between the
// outward normals of the two faces that meet there.  Meaningful for
// positively oriented tets only.
inline std::array<double, 6> dihedral_cosines(const TetPoints& p) {
    const TetKernel k = tet_kernel(p);
    return {k.cos[0], k.cos[1], k.cos[2], k.cos[3], k.cos[4], k.cos[5]};
}

// The six interior dihedral angles in degrees, in kEdgeVertex order.
inline std::array<double, 6> dihedral_angles(const TetPoints& p) {
    std::array<double, 6> out = dihedral_cosines(p);
    for (double& a : out) a = std::acos(a) * (180.0 / M_PI);
    return out;
}

// Smallest and largest dihedral angle.  A tet that is not positively oriented
// counts as the worst possible: 0 and 180 degrees (as the meshq yardstick).
struct AngleRange {
    double min, max;
};

inline AngleRange dihedral_range(const TetPoints& p, bool positive) {
    if (!positive) return {0.0, 180.0};
    const auto a = dihedral_angles(p);
    double lo = a[0], hi = a[0];
    for (int e = 1; e < 6; ++e) {
        lo = std::min(lo, a[e]);
        hi = std::max(hi, a[e]);
    }
    return {lo, hi};
}

}  // namespace bodt
