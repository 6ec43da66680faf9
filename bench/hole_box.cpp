// hole_box.cpp -- see hole_box.hpp.
#include "hole_box.hpp"

#include <cmath>
#include <utility>

namespace bench {

namespace {

// The Kuhn tets of a cell, as corner bit masks (ring = 1, direction = 2,
// layer = 4: radial, counterclockwise, up is a right-handed frame).
const int kKuhn[6][4] = {{0, 1, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 1, 7, 5}, {0, 2, 7, 3}, {0, 4, 7, 6}};

// Direction j: the unit vector d on the circle and the point s of the unit
// square on the same ray.  Made for the side x = +1 and turned by exact
// quarter turns, so the square's corners are exactly +-1.
void direction(int j, int nt, double d[2], double s[2]) {
    const int per_side = nt / 4, q = j / per_side, m = j % per_side;
    const double psi = -0.25 * M_PI + 0.5 * M_PI * double(m) / per_side;
    d[0] = std::cos(psi);
    d[1] = std::sin(psi);
    s[0] = 1.0;
    s[1] = m == 0 ? -1.0 : d[1] / d[0];
    for (int turn = 0; turn < q; ++turn) {
        std::swap(d[0], d[1]);
        d[0] = -d[0];
        std::swap(s[0], s[1]);
        s[0] = -s[0];
    }
}

double orient6(const double* a, const double* b, const double* c, const double* d) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

}  // namespace

bool make_hole_box(const HoleBox& b, std::vector<double>& xyz, std::vector<int32_t>& tets, std::string& err) {
    if (b.nr < 1 || b.nz < 1 || b.nt < 4 || b.nt % 4 || !(b.radius > 0) || !(b.half_width > b.radius) ||
        !(b.height > 0) || 6.0 * b.nr * b.nt * b.nz > 2e9) {
        err = "box with a hole: bad arguments";
        return false;
    }
    const int rings = b.nr + 1;
    xyz.assign(3 * size_t(b.nt) * rings * (b.nz + 1), 0.0);
    for (int k = 0; k <= b.nz; ++k)
        for (int i = 0; i <= b.nr; ++i)
            for (int j = 0; j < b.nt; ++j) {
                double d[2], s[2];
                direction(j, b.nt, d, s);
                const double t = double(i) / b.nr;
                double* p = &xyz[3 * ((size_t(k) * rings + i) * b.nt + j)];
                for (int a = 0; a < 2; ++a)
                    p[a] = i == 0 ? b.radius * d[a] : i == b.nr ? b.half_width * s[a]
                                                               : (1 - t) * b.radius * d[a] + t * b.half_width * s[a];
                p[2] = k == b.nz ? b.height : b.height * k / b.nz;
            }
    tets.clear();
    tets.reserve(24 * size_t(b.nr) * b.nt * b.nz);
    for (int k = 0; k < b.nz; ++k)
        for (int j = 0; j < b.nt; ++j)
            for (int i = 0; i < b.nr; ++i)
                for (const auto& kt : kKuhn) {
                    int32_t t[4];
                    for (int c = 0; c < 4; ++c) {
                        const int ci = i + (kt[c] & 1), cj = (j + (kt[c] >> 1 & 1)) % b.nt, ck = k + (kt[c] >> 2 & 1);
                        t[c] = int32_t((size_t(ck) * rings + ci) * b.nt + cj);
                    }
                    const double* x = xyz.data();
                    if (!(orient6(x + 3 * t[0], x + 3 * t[1], x + 3 * t[2], x + 3 * t[3]) > 0)) {
                        err = "box with a hole: a tet is not positive";
                        return false;
                    }
                    tets.insert(tets.end(), t, t + 4);
                }
    return true;
}

std::vector<double> deform_hole_box(const HoleBox& b, const HoleDeformation& d, const std::vector<double>& xyz) {
    std::vector<double> out = xyz;
    const size_t nv = xyz.size() / 3;
    for (size_t v = 0; v < nv; ++v) {
        double* p = &out[3 * v];
        if (p[0] > 0) p[0] *= d.stretch_x;  // DP
        if ((v / size_t(b.nt)) % size_t(b.nr + 1) == 0) {  // ring 0: RC, PH
            double dir[2], s[2];
            direction(int(v % size_t(b.nt)), b.nt, dir, s);
            p[0] = d.shift_x + d.radius * dir[0];
            p[1] = d.shift_y + d.radius * dir[1];
        }
    }
    return out;
}

}  // namespace bench
