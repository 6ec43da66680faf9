#include "topology/op_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodt {

namespace {

// Relative tolerance of "in the plane": far below any feature a mesh
// resolves, far above the round-off of coordinates read from a file.
constexpr double kFlatTolerance = 1e-9;

}  // namespace

double sine_floor(const TopologyRules& rules, double must_exceed) {
    return rules.allow_inverted ? -std::numeric_limits<double>::infinity() : std::max(must_exceed, 0.0);
}

TetLimits limits_for(const EditableMesh& mesh, const std::vector<int32_t>& replaced, const TopologyRules& rules,
                     double must_exceed) {
    TetLimits limits{sine_floor(rules, must_exceed), rules.min_stretch, rules.never_worse, {-1.0, 1.0}};
    for (int32_t t : replaced) {
        const TetShape shape = tet_shape(mesh.tet_points(t));  // one kernel for both limits
        limits.stretch_floor = std::min(limits.stretch_floor, shape.stretch);
        if (rules.never_worse) widen(limits.range, shape.cosines);
    }
    return limits;
}

bool acceptable_tet(const TetPoints& p, const TetLimits& limits) {
    return min_dihedral_sine(p) > limits.must_exceed && acceptable_shape(p, limits);
}

bool acceptable_shape(const TetPoints& p, const TetLimits& limits) {
    const TetShape shape = tet_shape(p);
    return shape.stretch >= limits.stretch_floor && (!limits.keep_range || within(shape.cosines, limits.range));
}

std::vector<int32_t> tets_touching(const EditableMesh& mesh, const std::vector<int32_t>& vs) {
    std::vector<int32_t> out;
    for (int32_t v : vs) out.insert(out.end(), mesh.tets_of(v).begin(), mesh.tets_of(v).end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

bool odt_target(const EditableMesh& mesh, int32_t v, Vec3& target) {
    if (mesh.vertex_class(v) != VertexClass::Interior) return false;
    Vec3 sum = Vec3::Zero();
    double volume = 0.0;
    for (int32_t t : mesh.tets_of(v)) {
        const TetPoints p = mesh.tet_points(t);
        const double vol = signed_volume(p[0], p[1], p[2], p[3]);
        sum += vol * circumcenter(p);
        volume += vol;
    }
    if (!(volume > 0.0)) return false;
    target = sum / volume;
    return true;
}

bool all_delaunay(const std::vector<TetPoints>& tets, const std::vector<Vec3>& points) {
    for (const TetPoints& t : tets)
        for (const Vec3& x : points)
            if (in_circumsphere(t, x)) return false;
    return true;
}

void widen(CosineRange& range, const CosineRange& c) {
    range.of_min = std::max(range.of_min, c.of_min);
    range.of_max = std::min(range.of_max, c.of_max);
}

void widen(CosineRange& range, const TetPoints& p) { widen(range, tet_shape(p).cosines); }

CosineRange cosine_range(const EditableMesh& mesh, const std::vector<int32_t>& tets) {
    CosineRange r{-1.0, 1.0};
    for (int32_t t : tets) widen(r, mesh.tet_points(t));
    return r;
}

std::array<double, 4> barycentric(const TetPoints& p, const Vec3& x) {
    const double whole = signed_volume(p[0], p[1], p[2], p[3]);
    std::array<double, 4> lambda;
    for (int i = 0; i < 4; ++i) {
        TetPoints s = p;
        s[i] = x;
        lambda[i] = signed_volume(s[0], s[1], s[2], s[3]) / whole;
    }
    return lambda;
}

size_t deepest_tet(const std::vector<TetPoints>& tets, const Vec3& x, std::array<double, 4>& lambda) {
    size_t best = 0;
    double best_depth = -std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < tets.size(); ++k) {
        const std::array<double, 4> l = barycentric(tets[k], x);
        const double depth = *std::min_element(l.begin(), l.end());
        if (depth > best_depth) {
            best_depth = depth;
            best = k;
            lambda = l;
        }
    }
    return best;
}

std::vector<int32_t> origins_of(const EditableMesh& mesh, const std::vector<int32_t>& replaced,
                                const std::vector<Tet>& fresh) {
    std::vector<TetPoints> shapes;
    for (int32_t t : replaced) shapes.push_back(mesh.tet_points(t));
    std::vector<int32_t> out;
    for (const Tet& q : fresh) {
        const Vec3 c = 0.25 * (mesh.point(q[0]) + mesh.point(q[1]) + mesh.point(q[2]) + mesh.point(q[3]));
        std::array<double, 4> lambda;
        out.push_back(mesh.origin(replaced[deepest_tet(shapes, c, lambda)]));
    }
    return out;
}

Parents blend_parents(const EditableMesh& mesh, std::initializer_list<int32_t> vs, std::initializer_list<double> ws) {
    Parents out;
    auto w = ws.begin();
    for (int32_t v : vs) {
        const double weight = *w++;
        if (!(weight > 0.0)) continue;  // a vertex the point does not depend on
        if (mesh.parents(v).empty()) {
            out.push_back({v, weight});  // an input vertex
        } else {
            for (const Parent& p : mesh.parents(v)) out.push_back({p.vertex, weight * p.weight});
        }
    }
    std::sort(out.begin(), out.end(), [](const Parent& a, const Parent& b) { return a.vertex < b.vertex; });
    Parents merged;
    for (const Parent& p : out) {
        if (!merged.empty() && merged.back().vertex == p.vertex) merged.back().weight += p.weight;
        else merged.push_back(p);
    }
    return merged;
}

double least_turn_cosine(const TopologyRules& rules) {
    const double slope = std::min(rules.surface_slope, 1.0);
    return slope > 0.0 ? std::sqrt(1.0 - slope * slope) : 0.0;
}

bool in_plane(const Vec3& n, const Vec3& p, const Vec3& x, double length) {
    return std::abs(n.dot(x - p)) <= kFlatTolerance * n.norm() * length;
}

}  // namespace bodt
