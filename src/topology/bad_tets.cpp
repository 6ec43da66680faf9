#include "topology/bad_tets.hpp"

#include <algorithm>

namespace bodt {

namespace {

// How far inside its face a projection must fall to count as inside,
// in barycentric coordinates: below it, the vertex is "on" an edge.
constexpr double kInside = 0.1;
// Where along an edge a split may go (as a fraction of the edge): never so
// near an end that the split makes a new short edge of the wrong kind.
constexpr double kEdgeMargin = 0.1;

// Barycentric coordinates of the projection of x onto the plane of (a, b, c).
std::array<double, 3> projected_barycentric(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a);
    const double area = n.squaredNorm();
    const double la = n.dot((b - x).cross(c - x)) / area;
    const double lb = n.dot((c - x).cross(a - x)) / area;
    return {la, lb, 1.0 - la - lb};
}

// Closest points of segments p0-p1 and q0-q1 as parameters (s, t).
bool closest_parameters(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, double& s, double& t) {
    const Vec3 u = p1 - p0, v = q1 - q0, w = p0 - q0;
    const double a = u.dot(u), b = u.dot(v), c = v.dot(v), d = u.dot(w), e = v.dot(w);
    const double den = a * c - b * b;
    if (!(den > 1e-12 * a * c)) return false;  // parallel
    s = (b * e - c * d) / den;
    t = (a * e - b * d) / den;
    return true;
}

}  // namespace

BadTet classify_bad_tet(const TetPoints& p, double bad_angle_deg, double short_ratio) {
    BadTet out;
    const auto angles = dihedral_angles(p);
    const auto [lo, hi] = std::minmax_element(angles.begin(), angles.end());
    if (*lo >= bad_angle_deg && *hi <= 180.0 - bad_angle_deg) return out;
    double shortest = 1e300, longest = 0.0;
    for (const auto& e : kEdgeVertex) {
        const double len = (p[e[1]] - p[e[0]]).norm();
        shortest = std::min(shortest, len);
        longest = std::max(longest, len);
    }
    if (shortest < short_ratio * longest) {
        out.kind = BadTetKind::ShortEdge;
        return out;
    }
    // Cap or spade: a vertex whose projection falls inside its opposite
    // face, or onto one of that face's edges.
    for (int i = 0; i < 4; ++i) {
        const auto& f = kFaceVertex[i];
        const auto lam = projected_barycentric(p[i], p[f[0]], p[f[1]], p[f[2]]);
        const int low = static_cast<int>(std::min_element(lam.begin(), lam.end()) - lam.begin());
        if (lam[low] >= kInside) {
            out.kind = BadTetKind::Cap;
            out.apex = i;
            out.point = lam[0] * p[f[0]] + lam[1] * p[f[1]] + lam[2] * p[f[2]];
            return out;
        }
        const int b = f[(low + 1) % 3], c = f[(low + 2) % 3];
        if (lam[low] > -kInside && lam[(low + 1) % 3] >= kInside && lam[(low + 2) % 3] >= kInside) {
            const double s = (p[i] - p[b]).dot(p[c] - p[b]) / (p[c] - p[b]).squaredNorm();
            if (s < kEdgeMargin || s > 1.0 - kEdgeMargin) continue;
            out.kind = BadTetKind::Spade;
            out.apex = i;
            out.edge = {b, c};
            out.point = p[b] + s * (p[c] - p[b]);
            return out;
        }
    }
    // Sliver: the pair of opposite edges with the largest dihedral angles
    // crosses; split both where they come closest.
    int best = -1;
    double best_sum = -1.0;
    for (int e = 0; e < 3; ++e) {  // edges e and 5 - e are opposite
        const double sum = angles[e] + angles[5 - e];
        if (sum > best_sum) {
            best_sum = sum;
            best = e;
        }
    }
    const auto& ac = kEdgeVertex[best];
    const auto& bd = kEdgeVertex[5 - best];
    double s = 0.0, t = 0.0;
    if (!closest_parameters(p[ac[0]], p[ac[1]], p[bd[0]], p[bd[1]], s, t)) return out;
    if (s < kEdgeMargin || s > 1.0 - kEdgeMargin || t < kEdgeMargin || t > 1.0 - kEdgeMargin) return out;
    out.kind = BadTetKind::Sliver;
    out.edge = {ac[0], ac[1]};
    out.edge2 = {bd[0], bd[1]};
    out.point = p[ac[0]] + s * (p[ac[1]] - p[ac[0]]);
    out.point2 = p[bd[0]] + t * (p[bd[1]] - p[bd[0]]);
    return out;
}

}  // namespace bodt
