// Point insertion into a cavity confined to one region, grown from the tet
// holding the point without crossing a surface or interface face, and
// replaced by the point joined to the cavity's boundary faces: the Delaunay
// cavity (Bowyer 1981, Watson 1981), the tets whose circumsphere holds the
// point, or a star cavity, grown where a face would make a poor tet.
#include "topology/op_support.hpp"
#include "topology/operations.hpp"

#include <algorithm>

namespace bodt {

namespace {

// A walk or a cavity larger than this is not a local change.
constexpr int kMaxWalk = 8;
constexpr size_t kMaxCavity = 48;
// How far from the seed's centroid the point may be, in its longest edges.
constexpr double kMaxReach = 2.0;

// The tet across face i of tet t (opposite its vertex i), or -1 when that
// face is on the surface, on an interface or marked.
int32_t across(const EditableMesh& mesh, int32_t t, int i) {
    const Tet& q = mesh.tet(t);
    const auto& f = kFaceVertex[i];
    const FaceKey face = FaceKey::of(q[f[0]], q[f[1]], q[f[2]]);
    int32_t pair[2];
    if (mesh.face_tets(face, pair) != 2) return -1;
    const int32_t n = pair[0] == t ? pair[1] : pair[0];
    if (mesh.region(n) != mesh.region(t) || mesh.has_marker(face)) return -1;
    return n;
}

// The tet holding p, walked to from `start` towards p; -1 if the walk
// leaves the region.
int32_t locate(const EditableMesh& mesh, int32_t start, const Vec3& p, std::array<double, 4>& lambda) {
    int32_t t = start;
    for (int step = 0; step < kMaxWalk && t >= 0; ++step) {
        lambda = barycentric(mesh.tet_points(t), p);
        const int i = static_cast<int>(std::min_element(lambda.begin(), lambda.end()) - lambda.begin());
        if (lambda[i] >= 0.0) return t;
        t = across(mesh, t, i);
    }
    return -1;
}

}  // namespace

CavityPlan plan_cavity(const EditableMesh& mesh, int32_t seed, const Vec3& p, const TopologyRules& rules,
                       double must_exceed, CavityGrowth growth, double star_goal) {
    CavityPlan plan;
    if (!p.allFinite()) return plan;
    // A point far from the seed (the circumcentre of a flat tet) makes a
    // cavity too large to hold it, or one that leaves the region.
    const TetPoints s = mesh.tet_points(seed);
    double reach = 0.0;
    for (const auto& e : kEdgeVertex) reach = std::max(reach, (s[e[1]] - s[e[0]]).squaredNorm());
    if ((p - 0.25 * (s[0] + s[1] + s[2] + s[3])).squaredNorm() > kMaxReach * kMaxReach * reach) return plan;
    const int32_t home = locate(mesh, seed, p, plan.lambda);
    if (home < 0) return plan;
    // The cavity, breadth first, with each member's four neighbours.
    std::vector<int32_t>& cavity = plan.cavity;
    std::vector<std::array<int32_t, 4>> next;
    const auto member = [&cavity](int32_t n) { return std::find(cavity.begin(), cavity.end(), n) != cavity.end(); };
    // Star growth: through a face whose tet with p would not beat star_goal.
    const auto poor_with_p = [&](int32_t t, int i) {
        TetPoints pts = mesh.tet_points(t);
        pts[i] = p;
        return min_dihedral_sine(pts) <= star_goal;
    };
    cavity.push_back(home);
    for (size_t k = 0; k < cavity.size(); ++k) {
        next.push_back({});
        for (int i = 0; i < 4; ++i) {
            const int32_t n = next[k][i] = across(mesh, cavity[k], i);
            if (n < 0 || member(n)) continue;
            if (growth == CavityGrowth::Delaunay ? !in_circumsphere(mesh.tet_points(n), p) : !poor_with_p(cavity[k], i))
                continue;
            if (cavity.size() == kMaxCavity) return {};
            cavity.push_back(n);
        }
    }
    if (!member(seed)) return {};
    // Each boundary face joined to p: the tet with that face's opposite
    // vertex replaced by p (-1 here), which keeps the orientation when p
    // sees the face from inside the cavity.
    std::vector<int32_t> kept;  // the cavity vertices on its boundary
    const TetLimits limits = limits_for(mesh, cavity, rules, must_exceed);
    for (size_t k = 0; k < cavity.size(); ++k)
        for (int i = 0; i < 4; ++i) {
            if (next[k][i] >= 0 && member(next[k][i])) continue;
            Tet q = mesh.tet(cavity[k]);
            TetPoints pts = mesh.tet_points(cavity[k]);
            pts[i] = p;
            if (!acceptable_tet(pts, limits)) return {};
            for (int j = 0; j < 4; ++j)
                if (j != i) kept.push_back(q[j]);
            q[i] = -1;
            plan.fresh.push_back(q);
        }
    // No vertex may be left inside the cavity without tets.
    std::sort(kept.begin(), kept.end());
    for (int32_t c : cavity)
        for (int32_t v : mesh.tet(c))
            if (!std::binary_search(kept.begin(), kept.end(), v)) return {};
    plan.point = p;
    return plan;
}

int32_t insert_planned(EditableMesh& mesh, const CavityPlan& plan) {
    if (!plan.valid()) return -1;
    const Tet h = mesh.tet(plan.cavity.front());
    const int32_t region = mesh.region(plan.cavity.front());
    const auto& l = plan.lambda;  // all >= 0: cavity[0] holds the point
    const int32_t m = mesh.add_vertex(plan.point, VertexClass::Interior,
                                      blend_parents(mesh, {h[0], h[1], h[2], h[3]}, {l[0], l[1], l[2], l[3]}));
    std::vector<Tet> placed = plan.fresh;
    for (Tet& q : placed) std::replace(q.begin(), q.end(), -1, m);
    const std::vector<int32_t> origins = origins_of(mesh, plan.cavity, placed);
    for (int32_t c : plan.cavity) mesh.remove_tet(c);
    for (size_t k = 0; k < placed.size(); ++k) mesh.add_tet(placed[k], region, origins[k]);
    return m;
}

}  // namespace bodt
