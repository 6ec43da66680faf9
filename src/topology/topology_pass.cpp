#include "topology/topology_pass.hpp"

#include "topology/bad_tets.hpp"
#include "topology/op_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace bodt {

namespace {

// A change must raise the worst sine by more than round-off.
constexpr double kGain = 1e-12;
// ODT relocation is one fixed-point step per round: a few rounds let the
// new vertices settle together.  A custom target (a full minimisation)
// gets one.
constexpr int kOdtRelocationRounds = 3;

// One guarded move of vertex v to the settings' relocation target, halved
// until no tet of its star ends worse than the star's worst before.
// Returns whether v moved.
bool relocate(EditableMesh& mesh, int32_t v, const TopologySettings& s) {
    Vec3 target;
    if (!(s.relocation_target ? s.relocation_target(mesh, v, target) : odt_target(mesh, v, target))) return false;
    if (!target.allFinite()) return false;
    const std::vector<int32_t> star(mesh.tets_of(v));
    const Vec3 start = mesh.point(v);
    const TetLimits limits = limits_for(mesh, star, s.rules, worst_sine(mesh, star));
    for (double f = 1.0; f > 0.05; f *= 0.5) {
        mesh.move_vertex(v, start + f * (target - start));
        bool ok = true;
        for (int32_t t : star) ok = ok && acceptable_tet(mesh.tet_points(t), limits);
        if (ok) return true;
    }
    mesh.move_vertex(v, start);
    return false;
}

// Tries one edge removal or 2-3 flip among the edges and faces of t that
// raises the worst sine of the tets involved.
bool flip_around(EditableMesh& mesh, int32_t t, const TopologyRules& rules, EdgeRing& ring, FailedFlips& failed) {
    const Tet q = mesh.tet(t);
    for (const auto& e : kEdgeVertex) {
        const int32_t a = q[e[0]], b = q[e[1]];
        if (failed.repeats(mesh, a, b)) continue;
        const bool built = mesh.edge_ring(a, b, ring) && static_cast<int>(ring.tets.size()) <= kMaxEdgeRing;
        if (built && remove_edge(mesh, a, b, ring, rules, worst_sine(mesh, ring.tets) + kGain)) return true;
        failed.record(mesh, a, b, built ? &ring : nullptr);
    }
    for (const auto& f : kFaceVertex) {
        const FaceKey face = FaceKey::of(q[f[0]], q[f[1]], q[f[2]]);
        if (failed.repeats(mesh, face)) continue;
        int32_t pair[2];
        const bool inner = mesh.face_tets(face, pair) == 2;
        if (inner && flip_23(mesh, face, pair, rules, worst_sine(mesh, {pair[0], pair[1]}) + kGain)) return true;
        failed.record(mesh, face, inner ? pair : nullptr);
    }
    return false;
}

// No vertex of a face neighbour of t lies inside t's circumsphere.
bool locally_delaunay(const EditableMesh& mesh, int32_t t) {
    const Tet& q = mesh.tet(t);
    const TetPoints p = mesh.tet_points(t);
    for (const auto& f : kFaceVertex) {
        int32_t pair[2];
        const int n = mesh.face_tets(FaceKey::of(q[f[0]], q[f[1]], q[f[2]]), pair);
        for (int k = 0; k < n; ++k)
            for (int32_t x : mesh.tet(pair[k]))
                if (!holds(q, x) && in_circumsphere(p, mesh.point(x))) return false;
    }
    return true;
}

// One sweep over the tets with an angle outside [flip angle, 180 - it]
// (with the Delaunay rule, only those that are not Delaunay: every flip
// must replace one); the tets a flip makes are appended, so the sweep
// reaches them too and goes on until no bad tet it meets can flip.  Every
// flip raises a local minimum, so this ends; the cap only bounds the time
// on a pathological mesh.
int32_t flip_pass(EditableMesh& mesh, const TopologyRules& rules, double flip_angle_deg, FailedAttempts& failed) {
    const double below = std::sin(flip_angle_deg * kDegree);
    int32_t flips = 0;
    const int32_t cap = 2 * mesh.tet_capacity();
    EdgeRing ring;
    for (int32_t t = 0; t < mesh.tet_capacity() && flips < cap; ++t) {
        if (!mesh.alive(t) || mesh.sine_at_least(t, below)) continue;
        if (rules.delaunay && locally_delaunay(mesh, t)) continue;
        if (failed.tets.stuck(mesh, t, StuckTets::kFlips)) continue;
        if (flip_around(mesh, t, rules, ring, failed.flips)) ++flips;
        else failed.tets.failed(mesh, t, StuckTets::kFlips);
    }
    return flips;
}

// Inserts the vertices that break bad tet t (spade, cap, sliver); returns
// the new vertices, none if an operation was refused.
std::vector<int32_t> insert_for(EditableMesh& mesh, int32_t t, const BadTet& bad, const TopologyRules& rules) {
    const Tet q = mesh.tet(t);
    std::vector<int32_t> made;
    const auto keep = [&made](int32_t v) {
        if (v >= 0) made.push_back(v);
        return v >= 0;
    };
    switch (bad.kind) {
        case BadTetKind::Spade: keep(split_edge(mesh, q[bad.edge[0]], q[bad.edge[1]], bad.point, rules, 0.0)); break;
        case BadTetKind::Cap: {
            const auto& f = kFaceVertex[bad.apex];
            keep(split_face(mesh, FaceKey::of(q[f[0]], q[f[1]], q[f[2]]), bad.point, rules, 0.0));
            break;
        }
        case BadTetKind::Sliver:
            if (keep(split_edge(mesh, q[bad.edge[0]], q[bad.edge[1]], bad.point, rules, 0.0)) &&
                !keep(split_edge(mesh, q[bad.edge2[0]], q[bad.edge2[1]], bad.point2, rules, 0.0)))
                made.clear();
            break;
        default: break;
    }
    return made;
}

// What a change that makes or keeps one vertex v (-1: refused) hands to
// try_change.
std::vector<int32_t> made_vertex(int32_t v) { return v >= 0 ? std::vector<int32_t>{v} : std::vector<int32_t>{}; }

Tet sorted(Tet q) {
    std::sort(q.begin(), q.end());
    return q;
}

// Refinement at the circumcentre is for tets with an interior vertex: one
// whose four vertices all lie on the boundary is flat against it, its
// circumcentre outside the region or far from the tet (the plan fails,
// after a costly walk), and is left to the flips, which may change the
// surface's triangulation, and to the split of an inner edge.
bool has_interior_vertex(const EditableMesh& mesh, int32_t t) {
    for (int32_t v : mesh.tet(t))
        if (mesh.vertex_class(v) == VertexClass::Interior) return true;
    return false;
}

// The edges of tet t through the inside (not on the surface), longest
// first, as vertex pairs.
std::vector<std::array<int32_t, 2>> inner_edges(const EditableMesh& mesh, int32_t t) {
    const Tet q = mesh.tet(t);
    std::vector<std::array<int32_t, 2>> out;
    for (const auto& e : kEdgeVertex)
        if (!mesh.is_surface_edge(q[e[0]], q[e[1]])) out.push_back({q[e[0]], q[e[1]]});
    const auto length = [&](const std::array<int32_t, 2>& e) { return (mesh.point(e[1]) - mesh.point(e[0])).squaredNorm(); };
    std::sort(out.begin(), out.end(), [&](const auto& x, const auto& y) { return length(x) > length(y); });
    return out;
}

// Worst tets first, so that a fix is not spent on a tet a neighbour's fix
// would have removed anyway.
std::vector<int32_t> bad_tets_by_quality(const EditableMesh& mesh, double bad_sine) {
    std::vector<std::pair<double, int32_t>> bad;
    for (int32_t t = 0; t < mesh.tet_capacity(); ++t) {
        if (!mesh.alive(t) || mesh.sine_at_least(t, bad_sine)) continue;
        bad.push_back({mesh.tet_sine(t), t});
    }
    std::sort(bad.begin(), bad.end());
    std::vector<int32_t> out;
    for (const auto& b : bad) out.push_back(b.second);
    return out;
}

// Applies `change` to bad tet t, relocates the vertices involved, and keeps
// the result if the worst sine of the tets that changed went up (and, with
// rules.never_worse, their angles stayed within the range the replaced
// ones had); else rolls it back.  Tets that did not change are left out of
// the comparison: an unrelated bad neighbour must not veto a fix.
template <class Change>
bool try_change(EditableMesh& mesh, int32_t t, const TopologySettings& settings, Change&& change) {
    const TopologyRules& rules = settings.rules;
    const Tet q = mesh.tet(t);
    std::vector<int32_t> involved(q.begin(), q.end());
    const std::vector<int32_t> region = tets_touching(mesh, involved);
    std::vector<TetPoints> shapes_before;
    std::vector<Tet> quads_before;
    for (int32_t s : region) {
        shapes_before.push_back(mesh.tet_points(s));
        quads_before.push_back(mesh.tet(s));
    }
    const int32_t old_capacity = mesh.tet_capacity();
    const int32_t old_vertices = mesh.num_vertices();
    const size_t mark = mesh.checkpoint();
    const std::vector<int32_t> made = change();
    if (made.empty()) {
        mesh.rollback(mark);
        return false;
    }
    // The new vertices move (and, when the step smooths, the old ones involved).
    std::vector<int32_t> fresh, movers;
    for (int32_t v : made) (v >= old_vertices ? fresh : movers).push_back(v);
    if (settings.relocate_old) movers.insert(movers.end(), q.begin(), q.end());
    else movers.clear();
    movers.insert(movers.begin(), fresh.begin(), fresh.end());
    involved.insert(involved.end(), made.begin(), made.end());
    // A new tet none of whose vertices will move keeps its shape; if it is
    // no better than the worst tet around, the change cannot pass the test
    // below (which compares with a subset of those tets), so skip the
    // relocation.
    const auto moves = [&](int32_t v) {
        return mesh.vertex_class(v) == VertexClass::Interior && std::count(movers.begin(), movers.end(), v);
    };
    double fixed_after = 1.0;
    for (int32_t s = old_capacity; s < mesh.tet_capacity(); ++s) {
        if (!mesh.alive(s)) continue;
        const Tet& n = mesh.tet(s);
        if (!moves(n[0]) && !moves(n[1]) && !moves(n[2]) && !moves(n[3]))
            fixed_after = std::min(fixed_after, min_dihedral_sine(mesh.tet_points(s)));
    }
    if (fixed_after < 1.0) {
        double region_worst = 1.0;
        for (const TetPoints& p : shapes_before) region_worst = std::min(region_worst, min_dihedral_sine(p));
        if (!(fixed_after > region_worst + kGain)) {
            mesh.rollback(mark);
            return false;
        }
    }
    // A round in which no vertex moved leaves the next one the same start.
    const int rounds = settings.relocation_target ? 1 : kOdtRelocationRounds;
    for (int round = 0, moved = 1; round < rounds && moved; ++round) {
        moved = 0;
        for (int32_t v : movers)
            if (!mesh.tets_of(v).empty()) moved |= relocate(mesh, v, settings);
    }
    // A tet changed if it is gone, new, or has moved.  The worst sine
    // after only falls as tets are added: the test fails at the first that
    // takes it to the bar (most changes fail), and the angle ranges are
    // only made for a change that passed that.
    const auto changed = [&](size_t k) { return !mesh.alive(region[k]) || !(mesh.tet_points(region[k]) == shapes_before[k]); };
    double before = 1.0, after = 1.0;
    for (size_t k = 0; k < region.size(); ++k)
        if (changed(k)) before = std::min(before, min_dihedral_sine(shapes_before[k]));
    CosineRange range_before{-1.0, 1.0}, range_after{-1.0, 1.0};
    bool passes = true;
    for (int32_t s : tets_touching(mesh, involved)) {
        const auto k = std::lower_bound(region.begin(), region.end(), s) - region.begin();
        const bool old = s < old_capacity && k < static_cast<long>(region.size()) && region[k] == s;
        if (old && !changed(static_cast<size_t>(k))) continue;
        const TetPoints p = mesh.tet_points(s);
        after = std::min(after, min_dihedral_sine(p));
        passes = after > before + kGain;
        if (!passes) break;
        if (rules.never_worse) widen(range_after, p);
    }
    if (passes && rules.never_worse) {
        for (size_t k = 0; k < region.size(); ++k)
            if (changed(k)) widen(range_before, shapes_before[k]);
        passes = within(range_after, range_before);
    }
    if (!passes) {
        mesh.rollback(mark);
        return false;
    }
    // A new vertex interpolates the mesh as it was, where the vertex ended.
    for (int32_t v : fresh) {
        if (mesh.tets_of(v).empty()) continue;
        std::array<double, 4> best_lambda;
        const size_t best = deepest_tet(shapes_before, mesh.point(v), best_lambda);
        double sum = 0.0;
        for (double& l : best_lambda) sum += (l = std::max(l, 0.0));
        for (double& l : best_lambda) l /= sum;
        const Tet& o = quads_before[best];
        mesh.set_parents(v, blend_parents(mesh, {o[0], o[1], o[2], o[3]},
                                          {best_lambda[0], best_lambda[1], best_lambda[2], best_lambda[3]}));
    }
    return true;
}

// The vertices of the tets made since tet slot `first` (a flip appends its
// tets): the vertices whose relocation may improve them.
std::vector<int32_t> vertices_of_tets_from(const EditableMesh& mesh, int32_t first) {
    std::vector<int32_t> out;
    for (int32_t t = first; t < mesh.tet_capacity(); ++t)
        if (mesh.alive(t)) out.insert(out.end(), mesh.tet(t).begin(), mesh.tet(t).end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Paper 001 Algorithm 4.  A poor tet whose four vertices all stay put is
// beyond smoothing; it goes by edge removal (an edge in 3 tets), edge swap
// (4 to kMaxEdgeRing tets) or face swap (2-3 on a face shared with another
// tet), whichever is first kept by try_change after the interior vertices of
// the new tets moved.  The paper keeps a swap even when it does not improve
// the tets, trusting the smoothing after it; judging after the relocation
// keeps that intent without ever making the worst tet worse.
int32_t all_boundary_pass(EditableMesh& mesh, const TopologySettings& s, const TopologyRules& loose) {
    std::vector<std::pair<double, int32_t>> poor;
    for (int32_t t = 0; t < mesh.tet_capacity(); ++t) {
        if (!mesh.alive(t)) continue;
        bool all_boundary = true;
        for (int32_t v : mesh.tet(t)) all_boundary = all_boundary && mesh.vertex_class(v) != VertexClass::Interior;
        const double q = stretch(mesh.tet_points(t));
        if (all_boundary && q < s.poor_stretch) poor.push_back({q, t});
    }
    std::sort(poor.begin(), poor.end());
    int32_t swaps = 0;
    EdgeRing ring;
    for (const auto& entry : poor) {
        const int32_t t = entry.second;
        if (!mesh.alive(t)) continue;
        const Tet q = mesh.tet(t);
        const auto swap = [&](auto&& op) {
            return try_change(mesh, t, s, [&] {
                const int32_t first = mesh.tet_capacity();
                return op() ? vertices_of_tets_from(mesh, first) : std::vector<int32_t>{};
            });
        };
        bool done = false;
        for (const auto& e : kEdgeVertex) {
            if (done) break;
            const int32_t a = q[e[0]], b = q[e[1]];
            if (!mesh.edge_ring(a, b, ring)) continue;
            const size_t k = ring.tets.size();
            if (k < 3 || k > static_cast<size_t>(kMaxEdgeRing)) continue;
            done = swap([&] { return remove_edge(mesh, a, b, ring, loose, 0.0); });
        }
        for (const auto& f : kFaceVertex) {
            if (done) break;
            const FaceKey face = FaceKey::of(q[f[0]], q[f[1]], q[f[2]]);
            int32_t pair[2];
            if (mesh.face_tets(face, pair) != 2) continue;
            done = swap([&] { return flip_23(mesh, face, pair, loose, 0.0); });
        }
        swaps += done;
    }
    return swaps;
}

}  // namespace

TopologyCounts improve_topology(EditableMesh& mesh, const TopologySettings& s) {
    FailedAttempts failed;
    failed.begin_pass(mesh, nullptr);
    return improve_topology(mesh, s, failed);
}

TopologyCounts improve_topology(EditableMesh& mesh, const TopologySettings& s, FailedAttempts& failed) {
    TopologyCounts counts;
    // The operations inside try_change make tets that only the relocation
    // after them improves: they are judged as a whole, there.
    TopologyRules loose = s.rules;
    loose.never_worse = false;
    const double bad_sine = std::sin(s.bad_angle_deg * kDegree);
    if (s.flip) counts.flips += flip_pass(mesh, s.rules, s.flip_angle_deg, failed);
    if (s.swap_all_boundary) counts.flips += all_boundary_pass(mesh, s, loose);
    if (s.insert || s.collapse) {
        std::vector<Tet> unrefined;  // this pass's, for failed.unrefined
        for (int32_t t : bad_tets_by_quality(mesh, bad_sine)) {
            if (!mesh.alive(t)) continue;
            const TetPoints p = mesh.tet_points(t);
            const BadTet bad = classify_bad_tet(p, s.bad_angle_deg);
            // A collapse for t reads what an insertion does (the tets
            // sharing a vertex with t): one record for both.
            const Tet quad = sorted(mesh.tet(t));
            const bool unrefinable = std::binary_search(failed.unrefined.begin(), failed.unrefined.end(), quad);
            if (failed.tets.stuck(mesh, t, StuckTets::kInsertion)) {
                if (unrefinable) unrefined.push_back(quad);  // still standing
                continue;
            }
            if (bad.kind == BadTetKind::ShortEdge && s.collapse) {
                // The shortest edge, collapsed by the position rules.
                int shortest = 0;
                for (int e = 1; e < 6; ++e)
                    if ((p[kEdgeVertex[e][1]] - p[kEdgeVertex[e][0]]).squaredNorm() <
                        (p[kEdgeVertex[shortest][1]] - p[kEdgeVertex[shortest][0]]).squaredNorm())
                        shortest = e;
                const Tet q = mesh.tet(t);
                if (try_change(mesh, t, s, [&] {
                        return made_vertex(collapse_edge(mesh, q[kEdgeVertex[shortest][0]], q[kEdgeVertex[shortest][1]], loose, 0.0));
                    })) {
                    ++counts.collapsed;
                    continue;
                }
            }
            if (!s.insert) continue;
            int32_t made = 0;
            const auto insert = [&](auto&& op) {
                return try_change(mesh, t, s, [&] {
                    const std::vector<int32_t> v = op();
                    made = static_cast<int32_t>(v.size());
                    return v;
                });
            };
            const bool shaped = bad.kind == BadTetKind::Spade || bad.kind == BadTetKind::Cap || bad.kind == BadTetKind::Sliver;
            // Else, or if that did not pass, the circumcentre (Delaunay
            // refinement), planned first: most plans fail, and cheaply.
            const auto refine = [&] {
                if (!unrefinable) {
                    const CavityPlan plan = plan_cavity(mesh, t, circumcenter(p), loose, 0.0);
                    if (plan.valid() && insert([&] { return made_vertex(insert_planned(mesh, plan)); }))
                        return true;
                }
                unrefined.push_back(quad);
                return false;
            };
            // A tet whose four vertices lie on the boundary cannot be mended
            // by moving them: an interior vertex, which the relocation in
            // try_change moves, goes in at its centroid, into the star
            // cavity of the tets it would not beat, or else at the midpoint
            // of an edge of it through the inside.  Tried once while the tet
            // stands, as the circumcentre: tried again every step, the
            // splits doubled the time of the coarse `-p` meshes' steps.
            const auto split_inner = [&] {
                if (!unrefinable) {
                    const Vec3 centroid = 0.25 * (p[0] + p[1] + p[2] + p[3]);
                    const CavityPlan plan =
                        plan_cavity(mesh, t, centroid, loose, 0.0, CavityGrowth::Star, mesh.tet_sine(t));
                    if (plan.valid() && insert([&] { return made_vertex(insert_planned(mesh, plan)); })) return true;
                    for (const auto& e : inner_edges(mesh, t))
                        if (insert([&] {
                                const Vec3 mid = 0.5 * (mesh.point(e[0]) + mesh.point(e[1]));
                                return made_vertex(split_edge(mesh, e[0], e[1], mid, loose, 0.0));
                            }))
                            return true;
                }
                unrefined.push_back(quad);
                return false;
            };
            const bool inner = has_interior_vertex(mesh, t);
            if ((shaped && insert([&] { return insert_for(mesh, t, bad, loose); })) || (inner && refine()) ||
                (!inner && split_inner()))
                counts.inserted += made;
            else
                failed.tets.failed(mesh, t, StuckTets::kInsertion);
        }
        std::sort(unrefined.begin(), unrefined.end());
        failed.unrefined = std::move(unrefined);
        if (s.flip && counts.inserted + counts.collapsed > 0)
            counts.flips += flip_pass(mesh, s.rules, s.flip_angle_deg, failed);
    }
    mesh.commit();
    return counts;
}

}  // namespace bodt
