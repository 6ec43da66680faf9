#include "topology/phased_topology.hpp"

#include "topology/bad_tets.hpp"
#include "topology/op_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace bodt {

namespace {

// What one midpoint split costs a regular tet: the stretch of its halves
// (about 0.71), the most a recovery change may cost the mesh's worst tet.
double regular_split_stretch() {
    static const double halves = [] {
        const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
        return stretch({a, 0.5 * (a + b), c, d}) / stretch({a, b, c, d});
    }();
    return halves;
}

// The distinct edges of the surface faces, in a fixed order.
std::vector<std::array<int32_t, 2>> surface_edges(const EditableMesh& mesh) {
    EdgeSet seen;
    std::vector<std::array<int32_t, 2>> out;
    for (int32_t t = 0; t < mesh.tet_capacity(); ++t) {
        if (!mesh.alive(t)) continue;
        const Tet& q = mesh.tet(t);
        for (const auto& f : kFaceVertex) {
            const FaceKey key = FaceKey::of(q[f[0]], q[f[1]], q[f[2]]);
            if (!mesh.is_surface_face(key)) continue;
            for (int i = 0; i < 3; ++i) {
                const int32_t a = key.v[i], b = key.v[(i + 1) % 3];
                if (seen.insert(edge_key(a, b)).second) out.push_back({std::min(a, b), std::max(a, b)});
            }
        }
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::array<int32_t, 2>> all_edges(const EditableMesh& mesh) {
    std::vector<std::array<int32_t, 2>> out;
    for (int32_t t = 0; t < mesh.tet_capacity(); ++t) {
        if (!mesh.alive(t)) continue;
        const Tet& q = mesh.tet(t);
        for (const auto& e : kEdgeVertex) out.push_back({std::min(q[e[0]], q[e[1]]), std::max(q[e[0]], q[e[1]])});
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// The surface faces on edge (a, b): their third vertices.
std::vector<int32_t> surface_opposites(const EditableMesh& mesh, int32_t a, int32_t b) {
    std::vector<int32_t> out;
    for (int32_t t : mesh.tets_holding({a, b}))
        for (int32_t c : mesh.tet(t))
            if (c != a && c != b && mesh.is_surface_face(FaceKey::of(a, b, c)) &&
                std::find(out.begin(), out.end(), c) == out.end())
                out.push_back(c);
    return out;
}


}  // namespace

PhasedTopology::PhasedTopology(EditableMesh& mesh, GeometryModel& geometry, const PhasedTopologySettings& settings)
    : mesh_(mesh), geometry_(geometry), settings_(settings) {
    settings_.rules.surface_may_change = true;
    settings_.rules.on_curved_shape = [this](const EditableMesh&, std::initializer_list<int32_t> element, const Vec3& x) {
        return on_shape(element, x);
    };
    settings_.rules.snap_to_shape = [this](const EditableMesh&, int32_t v, Vec3& x) {
        if (const Shape* shape = v < geometry_.num_vertices() ? geometry_.shape_of(v) : nullptr) x = shape->project(x);
    };
}

// The shape under a surface face (three vertices) or a sharp edge (two).
const Shape* PhasedTopology::element_shape(std::initializer_list<int32_t> element) const {
    const int32_t* v = element.begin();
    for (const int32_t* u = v; u != element.end(); ++u)
        if (*u >= geometry_.num_vertices()) return nullptr;
    if (element.size() == 2) {
        for (int32_t u : element)
            if (geometry_.vertex_class(u) == VertexClass::FeatureLine) return geometry_.shape_of(u);
        return nullptr;
    }
    const Vec3 centroid = (mesh_.point(v[0]) + mesh_.point(v[1]) + mesh_.point(v[2])) / 3.0;
    const int32_t r = geometry_.face_region(v[0], v[1], v[2], centroid);
    if (r < 0) return nullptr;
    const Shape& s = geometry_.regions()[r].shape;
    return s.type == ShapeType::None ? nullptr : &s;
}

bool PhasedTopology::on_shape(std::initializer_list<int32_t> element, const Vec3& x) const {
    const Shape* s = element_shape(element);
    if (!s || s->type == ShapeType::Plane || s->type == ShapeType::Line) return false;
    const double scale = (mesh_.point(*element.begin()) - x).norm() + s->radius;
    return s->distance(x) <= s->max_error + 1e-9 * scale;
}

bool PhasedTopology::accurate_at(int32_t v) const {
    std::vector<int32_t> around;
    mesh_.neighbors(v, around);
    for (int32_t x : around) {
        if (!mesh_.is_surface_edge(v, x)) continue;
        const Vec3 mid = 0.5 * (mesh_.point(v) + mesh_.point(x));
        for (int32_t c : surface_opposites(mesh_, v, x)) {
            const Shape* s = element_shape({v, x, c});
            if (!s || s->type != ShapeType::Cylinder) continue;
            const int32_t r = geometry_.face_region(v, x, c, (mesh_.point(v) + mesh_.point(x) + mesh_.point(c)) / 3.0);
            const double limit = geometry_.regions()[r].acceptable_error;
            if (limit > 0.0 && s->distance(mid) > limit * (1.0 + 1e-9)) return false;
        }
    }
    return true;
}

// Splits (a, b) at its midpoint.  A vertex on a surface or sharp edge then
// goes onto the fitted shape; an interior one to its ODT position (a few
// rounds, the star kept positive), as the smoothing after the split would.
// Kept if no tet around is worse than the worse of the bad angle and the
// tets it replaced.
int32_t PhasedTopology::split_onto_shape(int32_t a, int32_t b, bool judged_after) {
    const size_t mark = mesh_.checkpoint();
    const std::vector<int32_t> around = mesh_.tets_holding({a, b});
    const double must_exceed =
        judged_after ? 0.0 : std::min(worst_sine(mesh_, around), std::sin(settings_.bad_angle_deg * kDegree));
    const TetLimits limits = limits_for(mesh_, around, settings_.rules, must_exceed);
    const int32_t m = split_edge(mesh_, a, b, 0.5 * (mesh_.point(a) + mesh_.point(b)), settings_.rules, 0.0);
    if (m < 0) return -1;
    // The new vertex's entity: the chain of the split sharp edge, or the
    // region of the faces on the split surface edge.
    const VertexClass cls = mesh_.vertex_class(m);
    int32_t entity = -1;
    if (cls == VertexClass::FeatureLine) {
        for (int32_t u : {a, b})
            if (geometry_.vertex_class(u) == VertexClass::FeatureLine) entity = geometry_.entity(u);
    } else if (cls == VertexClass::Surface) {
        for (int32_t c : surface_opposites(mesh_, a, m))
            if (entity < 0 && c < geometry_.num_vertices())
                entity = geometry_.face_region(a, b, c, (mesh_.point(a) + mesh_.point(b) + mesh_.point(c)) / 3.0);
    }
    geometry_.set(m, cls, entity);
    if (cls != VertexClass::Interior && entity < 0) geometry_.set(m, cls, geometry_.resolve(mesh_, m));
    const std::vector<int32_t> star(mesh_.tets_of(m));
    const auto positive = [&] {
        for (int32_t t : star) {
            const TetPoints p = mesh_.tet_points(t);
            if (orient(p[0], p[1], p[2], p[3]).sign <= 0) return false;
        }
        return true;
    };
    if (const Shape* shape = geometry_.shape_of(m)) {
        mesh_.move_vertex(m, shape->project(mesh_.point(m)));
    } else if (cls == VertexClass::Interior) {
        for (int round = 0; round < 3; ++round) {
            Vec3 sum = Vec3::Zero();
            double volume = 0.0;
            for (int32_t t : star) {
                const TetPoints p = mesh_.tet_points(t);
                const double v = signed_volume(p[0], p[1], p[2], p[3]);
                sum += v * circumcenter(p);
                volume += v;
            }
            const Vec3 from = mesh_.point(m), to = sum / volume;
            if (!to.allFinite()) break;
            mesh_.move_vertex(m, to);
            if (!positive()) {
                mesh_.move_vertex(m, from);
                break;
            }
        }
    }
    for (int32_t t : star)
        if (!acceptable_tet(mesh_.tet_points(t), limits)) {
            mesh_.rollback(mark);
            return -1;
        }
    return m;
}

// Sec. 3.5.1's collapse (collapse_edge: its exclusions and position
// rules, the midpoint snapped to the shape), kept only if the cylinder's
// edges stay accurate.  Returns the kept vertex.
int32_t PhasedTopology::collapse_by_rules(int32_t a, int32_t b) {
    const double must_exceed =
        std::min(worst_sine(mesh_, tets_touching(mesh_, {a, b})), std::sin(settings_.bad_angle_deg * kDegree));
    const size_t mark = mesh_.checkpoint();
    const int32_t kept = collapse_edge(mesh_, a, b, settings_.rules, must_exceed);
    if (kept >= 0 && accurate_at(kept)) return kept;
    mesh_.rollback(mark);
    return -1;
}

namespace {

// How bad a set of tets is: how many are not positive, then the worst
// stretch (negated, so that smaller is better in both).  Tets: a vector
// or a vertex's TetList.
template <class Tets>
std::pair<int32_t, double> badness(const EditableMesh& mesh, const Tets& tets) {
    int32_t count = 0;
    double worst = std::numeric_limits<double>::infinity();
    for (int32_t t : tets) {
        if (!mesh.alive(t)) continue;
        const double s = stretch(mesh.tet_points(t));
        count += s <= 0.0;
        worst = std::min(worst, s);
    }
    return {count, -worst};
}

// A point where every tet of v's star would be positive: each tet asks x
// to lie on the inner side of the plane of its face opposite v.  The most
// violated of those half-spaces is met in turn (a relaxation method for
// linear inequalities, Agmon / Motzkin), aiming at a margin of a tenth of
// the star's shortest edge so the point lies inside, not on, the kernel.
// False when it does not get there.
bool star_kernel_point(const EditableMesh& mesh, int32_t v, Vec3& x) {
    struct Half {
        Vec3 n;  // unit, pointing into the tet's side
        Vec3 a;
    };
    std::vector<Half> halves;
    double shortest = std::numeric_limits<double>::infinity();
    for (int32_t t : mesh.tets_of(v)) {
        const Tet& q = mesh.tet(t);
        int i = 0;
        while (q[i] != v) ++i;
        const Vec3 &a = mesh.point(q[kFaceVertex[i][0]]), &b = mesh.point(q[kFaceVertex[i][1]]),
                   &c = mesh.point(q[kFaceVertex[i][2]]);
        const Vec3 n = -triangle_normal(a, b, c);  // the face's outward normal, reversed
        const double len = n.norm();
        if (!(len > 0.0)) return false;
        halves.push_back({n / len, a});
        shortest = std::min({shortest, (b - a).norm(), (c - b).norm(), (a - c).norm()});
    }
    const double margin = 0.1 * shortest;
    x = mesh.point(v);
    for (int iteration = 0; iteration < 200; ++iteration) {
        const Half* worst = nullptr;
        double lowest = margin;
        for (const Half& h : halves) {
            const double d = h.n.dot(x - h.a);
            if (d < lowest) {
                lowest = d;
                worst = &h;
            }
        }
        if (!worst) return true;
        x += (margin - lowest) * worst->n;
    }
    return false;
}

// The interior vertices within `rings` rings of a tet with stretch <= 0
// relax together towards the mean of their neighbours (Jacobi sweeps, the
// rest held): a deformation that moved a boundary far past the vertices
// inside it is undone as a whole, which no single vertex's move can do.
// Kept only if fewer tets are left with stretch <= 0 (or as many, better).
bool relax_tangled_region(EditableMesh& mesh, int rings, int sweeps) {
    std::vector<int32_t> region;
    std::vector<char> in(static_cast<size_t>(mesh.num_vertices()), 0);
    std::vector<int32_t> bad_tets;
    for (int32_t t = 0; t < mesh.tet_capacity(); ++t)
        if (mesh.alive(t) && stretch(mesh.tet_points(t)) <= 0.0) {
            bad_tets.push_back(t);
            for (int32_t v : mesh.tet(t))
                if (!in[v]) {
                    in[v] = 1;
                    region.push_back(v);
                }
        }
    if (bad_tets.empty()) return false;
    std::vector<int32_t> around;
    for (int ring = 0; ring < rings; ++ring)
        for (size_t k = 0, n = region.size(); k < n; ++k) {
            mesh.neighbors(region[k], around);
            for (int32_t u : around)
                if (!in[u]) {
                    in[u] = 1;
                    region.push_back(u);
                }
        }
    std::vector<int32_t> movers, touched;
    for (int32_t v : region) {
        if (mesh.vertex_class(v) == VertexClass::Interior) movers.push_back(v);
        touched.insert(touched.end(), mesh.tets_of(v).begin(), mesh.tets_of(v).end());
    }
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    const auto before = badness(mesh, touched);
    const size_t mark = mesh.checkpoint();
    std::vector<Vec3> next(movers.size());
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        for (size_t k = 0; k < movers.size(); ++k) {
            mesh.neighbors(movers[k], around);
            Vec3 mean = Vec3::Zero();
            for (int32_t u : around) mean += mesh.point(u);
            next[k] = mean / static_cast<double>(around.size());
        }
        for (size_t k = 0; k < movers.size(); ++k) mesh.move_vertex(movers[k], next[k]);
    }
    if (badness(mesh, touched) < before) return true;
    mesh.rollback(mark);
    return false;
}

}  // namespace

int32_t PhasedTopology::untangle_by_moves() {
    constexpr int kRounds = 50;
    int32_t moves = 0;
    for (int rings : {1, 2, 4})
        if (relax_tangled_region(mesh_, rings, 10 * rings)) ++moves;
    std::vector<int32_t> around, tangled;
    for (int round = 0; round < kRounds; ++round) {
        // The vertices of tets with stretch <= 0, each once.
        tangled.clear();
        for (int32_t t = 0; t < mesh_.tet_capacity(); ++t)
            if (mesh_.alive(t) && stretch(mesh_.tet_points(t)) <= 0.0)
                tangled.insert(tangled.end(), mesh_.tet(t).begin(), mesh_.tet(t).end());
        std::sort(tangled.begin(), tangled.end());
        tangled.erase(std::unique(tangled.begin(), tangled.end()), tangled.end());
        int32_t moved = 0;
        for (int32_t v : tangled) {
            // Interior vertices anywhere; surface and chain vertices on their
            // fitted shape, towards their neighbours on it.
            const VertexClass cls = mesh_.vertex_class(v);
            const Shape* shape = v < geometry_.num_vertices() ? geometry_.shape_of(v) : nullptr;
            const bool on_shape = (cls == VertexClass::Surface || cls == VertexClass::FeatureLine) && shape;
            if (cls != VertexClass::Interior && !on_shape) continue;
            const TetList star = mesh_.tets_of(v);  // moves leave it as it is
            const auto before = badness(mesh_, star);
            if (before.first == 0) continue;
            mesh_.neighbors(v, around);
            Vec3 mean = Vec3::Zero();
            int n = 0;
            for (int32_t u : around) {
                const bool along = cls == VertexClass::Interior ||
                                   (cls == VertexClass::FeatureLine ? mesh_.is_feature_edge(v, u) : mesh_.is_surface_edge(v, u));
                if (!along) continue;
                mean += mesh_.point(u);
                ++n;
            }
            if (n == 0) continue;
            mean /= static_cast<double>(n);
            const Vec3 start = mesh_.point(v);
            bool kept = false;
            Vec3 inside;
            if (cls == VertexClass::Interior && star_kernel_point(mesh_, v, inside)) {
                mesh_.move_vertex(v, inside);
                kept = badness(mesh_, star) < before;
            }
            for (double f = 1.0; f > 0.1 && !kept; f *= 0.5) {
                const Vec3 to = start + f * (mean - start);
                mesh_.move_vertex(v, shape ? shape->project(to) : to);
                kept = badness(mesh_, star) < before;
            }
            if (!kept) mesh_.move_vertex(v, start);
            moved += kept;
        }
        moves += moved;
        if (moved == 0) break;
    }
    return moves;
}

int32_t PhasedTopology::remove_inverted() {
    TopologyRules untangle = settings_.rules;
    untangle.allow_inverted = true;
    // Worst first; the tets a collapse leaves bad join the queue.
    using Entry = std::pair<double, int32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for (int32_t t = 0; t < mesh_.tet_capacity(); ++t) {
        if (!mesh_.alive(t)) continue;
        const double s = stretch(mesh_.tet_points(t));
        if (s <= 0.0) queue.push({s, t});
    }
    int32_t removed = 0;
    while (!queue.empty()) {
        const int32_t worst = queue.top().second;
        queue.pop();
        if (!mesh_.alive(worst) || stretch(mesh_.tet_points(worst)) > 0.0) continue;
        // Of the worst tet's twelve half-edge collapses, the one that leaves
        // the fewest bad tets around the kept vertex, then the best worst
        // stretch there; kept only if that beats the tets it changed.
        const Tet q = mesh_.tet(worst);
        std::pair<int32_t, double> best{INT32_MAX, 0.0};
        int32_t best_gone = -1, best_keep = -1;
        for (const auto& e : kEdgeVertex)
            for (int dir = 0; dir < 2; ++dir) {
                const int32_t gone = q[e[dir]], keep = q[e[1 - dir]];
                const auto before = badness(mesh_, tets_touching(mesh_, {gone, keep}));
                const size_t mark = mesh_.checkpoint();
                if (collapse_half_edge(mesh_, gone, keep, untangle, 0.0)) {
                    const auto after = badness(mesh_, mesh_.tets_of(keep));
                    if (after < before && after < best) {
                        best = after;
                        best_gone = gone;
                        best_keep = keep;
                    }
                }
                mesh_.rollback(mark);
            }
        if (best_gone < 0 || !collapse_half_edge(mesh_, best_gone, best_keep, untangle, 0.0)) continue;
        ++removed;
        for (int32_t t : mesh_.tets_of(best_keep)) {
            const double s = stretch(mesh_.tet_points(t));
            if (s <= 0.0) queue.push({s, t});
        }
    }
    return removed;
}

int32_t PhasedTopology::remove_degenerate() {
    const double bad_sine = std::sin(settings_.bad_angle_deg * kDegree);
    std::vector<std::pair<double, int32_t>> bad;
    for (int32_t t = 0; t < mesh_.tet_capacity(); ++t) {
        if (!mesh_.alive(t)) continue;
        const double s = min_dihedral_sine(mesh_.tet_points(t));
        if (s < bad_sine) bad.push_back({s, t});
    }
    std::sort(bad.begin(), bad.end());
    int32_t removed = 0;
    for (const auto& [sine, t] : bad) {
        if (!mesh_.alive(t)) continue;
        const TetPoints p = mesh_.tet_points(t);
        const BadTet kind = classify_bad_tet(p, settings_.bad_angle_deg);
        const Tet q = mesh_.tet(t);
        const std::vector<int32_t> region = tets_touching(mesh_, {q[0], q[1], q[2], q[3]});
        const double before = worst_sine(mesh_, region);
        const size_t mark = mesh_.checkpoint();
        int32_t kept = -1;
        if (kind.kind == BadTetKind::Sliver) {
            // The two crossing edges split, the new short edge collapsed.
            const int32_t m1 = split_onto_shape(q[kind.edge[0]], q[kind.edge[1]], true);
            const int32_t m2 = m1 < 0 ? -1 : split_onto_shape(q[kind.edge2[0]], q[kind.edge2[1]], true);
            if (m2 >= 0 && mesh_.has_edge(m1, m2)) kept = collapse_by_rules(m1, m2);
        } else if (kind.kind == BadTetKind::Cap || kind.kind == BadTetKind::Spade) {
            // The edge between the largest and the smallest face is split;
            // the smallest face's third vertex and the new one collapse.
            double area[4];
            for (int i = 0; i < 4; ++i)
                area[i] = triangle_normal(p[kFaceVertex[i][0]], p[kFaceVertex[i][1]], p[kFaceVertex[i][2]]).norm();
            const int large = static_cast<int>(std::max_element(area, area + 4) - area);
            const int small = static_cast<int>(std::min_element(area, area + 4) - area);
            if (large != small) {
                int e[2], k = 0;
                for (int i = 0; i < 4; ++i)
                    if (i != large && i != small) e[k++] = i;
                const int32_t apex = q[large];  // in the smallest face, off the edge
                const int32_t m = split_onto_shape(q[e[0]], q[e[1]], true);
                if (m >= 0 && mesh_.has_edge(m, apex)) kept = collapse_by_rules(m, apex);
            }
        }
        std::vector<int32_t> after_region;
        for (int32_t v : q)
            if (!mesh_.tets_of(v).empty()) after_region.insert(after_region.end(), mesh_.tets_of(v).begin(), mesh_.tets_of(v).end());
        if (kept >= 0) after_region.insert(after_region.end(), mesh_.tets_of(kept).begin(), mesh_.tets_of(kept).end());
        if (kept < 0 || mesh_.alive(t) || !(worst_sine(mesh_, after_region) > before)) {
            mesh_.rollback(mark);
            continue;
        }
        ++removed;
    }
    return removed;
}

void PhasedTopology::recover(const DensityGrid* density, PhasedTopologyCounts& counts) {
    if (!settings_.split && !settings_.collapse) return;
    double worst = std::numeric_limits<double>::infinity();
    for (int32_t t = 0; t < mesh_.tet_capacity(); ++t)
        if (mesh_.alive(t)) worst = std::min(worst, stretch(mesh_.tet_points(t)));
    if (!(worst > 0.0)) return;
    const double floor = settings_.rules.min_stretch;
    settings_.rules.min_stretch = std::max(floor, regular_split_stretch() * worst);
    // Geometric accuracy: surface edges of a cylinder too far from it.
    if (settings_.split) {
        for (const auto& [a, b] : surface_edges(mesh_)) {
            if (!mesh_.has_edge(a, b)) continue;
            const Vec3 mid = 0.5 * (mesh_.point(a) + mesh_.point(b));
            double limit = std::numeric_limits<double>::infinity();
            for (int32_t c : surface_opposites(mesh_, a, b)) {
                if (c >= geometry_.num_vertices()) continue;
                const int32_t r = geometry_.face_region(a, b, c, (mesh_.point(a) + mesh_.point(b) + mesh_.point(c)) / 3.0);
                if (r < 0) continue;
                const SurfaceRegion& region = geometry_.regions()[r];
                if (region.shape.type == ShapeType::Cylinder && region.acceptable_error > 0.0 &&
                    region.shape.distance(mid) > region.acceptable_error)
                    limit = std::min(limit, region.acceptable_error);
            }
            if (std::isfinite(limit) && split_onto_shape(a, b) >= 0) ++counts.splits;
        }
    }
    if (!density || density->empty()) {
        settings_.rules.min_stretch = floor;
        return;
    }
    // Density: split sparse edges, collapse dense ones.
    for (const auto& [a, b] : all_edges(mesh_)) {
        if (mesh_.tets_of(a).empty() || mesh_.tets_of(b).empty() || !mesh_.has_edge(a, b)) continue;
        const Vec3 mid = 0.5 * (mesh_.point(a) + mesh_.point(b));
        const double target = density->at(mid);
        if (!(target > 0.0)) continue;
        const double rho = 1.0 / (mesh_.point(a) - mesh_.point(b)).norm();
        if (settings_.split && rho < settings_.split_ratio * target) {
            if (split_onto_shape(a, b) >= 0) ++counts.splits;
        } else if (settings_.collapse && rho > settings_.collapse_ratio * target) {
            if (collapse_by_rules(a, b) >= 0) ++counts.collapses;
        }
    }
    settings_.rules.min_stretch = floor;
}

int32_t PhasedTopology::flip_surface() {
    int32_t flips = 0;
    for (const auto& [a, b] : surface_edges(mesh_)) {
        if (mesh_.is_feature_edge(a, b) || !mesh_.has_edge(a, b)) continue;
        const std::vector<int32_t> opp = surface_opposites(mesh_, a, b);
        if (opp.size() != 2) continue;
        const int32_t c = opp[0], d = opp[1];
        if (!edge_not_delaunay(mesh_.point(a), mesh_.point(b), mesh_.point(c), mesh_.point(d))) continue;
        if (mesh_.has_edge(c, d)) continue;  // the flipped edge exists already
        const std::vector<int32_t> region = tets_touching(mesh_, {a, b, c, d});
        const double before = worst_sine(mesh_, region);
        const size_t mark = mesh_.checkpoint();
        const int32_t m = split_onto_shape(a, b, true);
        bool done = false;
        for (int32_t to : {c, d}) {
            if (done || m < 0) break;
            const size_t inner = mesh_.checkpoint();
            if (collapse_half_edge(mesh_, m, to, settings_.rules, 0.0) && accurate_at(to) &&
                worst_sine(mesh_, tets_touching(mesh_, {a, b, c, d})) >= before)
                done = true;
            else
                mesh_.rollback(inner);
        }
        if (!done) {
            mesh_.rollback(mark);
            continue;
        }
        ++flips;
    }
    return flips;
}

}  // namespace bodt
