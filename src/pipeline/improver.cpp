#include "pipeline/improver.hpp"

#include "bodt.h"
#include "common/error.hpp"
#include "quality/mesh_quality.hpp"
#include "smoothing/angle_ascent.hpp"
#include "smoothing/bodt_smoother.hpp"
#include "smoothing/coloured_sweep.hpp"
#include "smoothing/laplace.hpp"
#include "smoothing/move_guard.hpp"
#include "smoothing/nodt.hpp"
#include "smoothing/opt_weighted.hpp"
#include "topology/topology_pass.hpp"

#include <string>

namespace bodt {

namespace {

// TopologyRules::surface_slope (operations.hpp) in the modes whose surface
// may change.
constexpr double kSurfaceSlope = 0.1;

void require_finite(const std::vector<Vec3>& points) {
    for (const Vec3& p : points)
        if (!p.allFinite()) throw Error(BODT_ERR_NUMERIC, "a vertex position became non-finite");
}

void count_outcome(MoveOutcome outcome, double distance, StepReport& report) {
    switch (outcome) {
        case MoveOutcome::Moved: ++report.vertices_moved; break;
        case MoveOutcome::Shortened:
            ++report.vertices_moved;
            ++report.moves_shortened;
            break;
        case MoveOutcome::Rejected: ++report.moves_rejected; break;
    }
    report.max_move = std::max(report.max_move, distance);
}

// One vertex of a B-ODT or NODT sweep: `plan(target)` says where it goes,
// `move(target, distance)` takes it there through the guard.  Returns
// whether it moved.
template <class PlanFn, class MoveFn>
bool smooth_vertex(PlanFn plan, MoveFn move, StepReport& report) {
    Vec3 target;
    switch (plan(target)) {
        case Plan::Stay: return false;
        case Plan::NotPositiveDefinite: ++report.not_positive_definite; return false;
        case Plan::Move: break;
    }
    double distance = 0.0;
    const MoveOutcome outcome = move(target, distance);
    count_outcome(outcome, distance, report);
    return outcome != MoveOutcome::Rejected;
}

// Adds the sweep counters of each thread's report to `report`.
template <class State>
void merge_counts(const std::vector<State>& states, StepReport& report) {
    for (const State& s : states) {
        report.vertices_moved += s.report.vertices_moved;
        report.moves_rejected += s.report.moves_rejected;
        report.moves_shortened += s.report.moves_shortened;
        report.not_positive_definite += s.report.not_positive_definite;
        report.max_move = std::max(report.max_move, s.report.max_move);
    }
}

}  // namespace

void Improver::set_mode(int mode) {
    if (mode != BODT_MODE_LAPLACE && mode != BODT_MODE_ODT && mode != BODT_MODE_BODT_BASIC && mode != BODT_MODE_BODT &&
        mode != BODT_MODE_OPT_WEIGHTED && mode != BODT_MODE_PHASED_ODT && mode != BODT_MODE_NODT)
        throw Error(BODT_ERR_INVALID_ARGUMENT, "unknown mode " + std::to_string(mode));
    mode_ = mode;
    classes_valid_ = false;
    settled_.clear();
    failed_.unrefined.clear();
}

void Improver::set_param_int(int key, int32_t value) {
    bodt::set_param_int(params_, key, value);
    settled_.clear();
    // The tets no refinement fixed are kept while they stand, even where
    // their vertices moved: forgetting them can change the result, which
    // the number of threads must not.
    if (key != BODT_PARAM_THREADS) failed_.unrefined.clear();
}

void Improver::set_param_double(int key, double value) {
    bodt::set_param_double(params_, key, value);
    classes_valid_ = false;
    settled_.clear();
    failed_.unrefined.clear();
    if (key == BODT_PARAM_FEATURE_ANGLE || key == BODT_PARAM_FIT_TOLERANCE) geometry_valid_ = false;
}

const VertexClasses& Improver::classes(const TetMesh& mesh, const RegionSurfaces& surfaces) const {
    if (!classes_valid_ && mode_ == BODT_MODE_PHASED_ODT) {
        classes_ = geometry(mesh).vertex_classes(mesh);
        classes_valid_ = true;
    }
    if (!classes_valid_) {
        classes_ = classify(mesh, surfaces);
        classes_valid_ = true;
    }
    return classes_;
}

VertexClasses Improver::classify(const TetMesh& mesh, const RegionSurfaces& surfaces) const {
    FeatureSettings settings;
    settings.feature_angle_deg = params_.feature_angle;
    settings.edge_ratio = params_.edge_ratio;
    settings.corner_ratio = params_.corner_ratio;
    settings.detect_features = mode_ == BODT_MODE_BODT || mode_ == BODT_MODE_NODT;
    return classify_vertices(mesh, surfaces, settings);
}

// Flat pieces of the surface meeting at half the feature angle or more are
// kept as they are (FlatPieces) in the mode that detects features and may
// move the surface; a cylinder cut into strips (9 to 11 degrees apart in
// `joint` and `rotor`) or a smooth part cut into quads (below 1 degree in
// `fandisk`) is still smoothed as the curved surface it stands for.
double Improver::crease_cosine() const {
    return mode_ == BODT_MODE_BODT ? std::cos(0.5 * params_.feature_angle * kDegree) : -1.0;
}

// ODT moves interior vertices only, and BODT_PARAM_KEEP_SURFACE keeps
// every boundary and interface vertex where it is in the B-ODT and NODT
// sweeps too.
bool Improver::surface_stays() const { return mode_ == BODT_MODE_ODT || params_.keep_surface != 0; }

GuardSettings Improver::guard_settings() const {
    return {params_.min_stretch, params_.backtrack_steps, params_.never_worse != 0};
}

void Improver::sweep_laplace(TetMesh& mesh, ShapeCache& shapes, StepReport& report) const {
    struct State {
        MoveGuard guard;
        std::vector<int32_t> scratch;
        StepReport report;
    };
    const std::vector<FaceKey> no_faces;
    const int threads = sweep_threads(params_.threads, mesh.tets.size());
    const auto states = coloured_sweep(
        mesh, threads, State{MoveGuard(guard_settings(), &shapes), {}, {}}, [&](State& s, int32_t v) {
            if (!mesh.is_interior_free(v)) return;
            const Vec3 target = laplace_target(mesh, v, s.scratch);
            double distance = 0.0;
            const MoveOutcome outcome = s.guard.move(mesh, v, target, no_faces, distance);
            count_outcome(outcome, distance, s.report);
        });
    merge_counts(states, report);
}

// ODT, B-ODT basic and B-ODT: the modes differ only in which vertices move
// (ODT: inner ones) and how the surface vertices were classified.  B-ODT
// adds, from its second step on, the angle ascent (smoothing/angle_ascent.hpp)
// for the vertices of bad tets: the first step is the papers' smoothing and
// connectivity changes alone, which make the large changes the ascent
// would otherwise get in the way of.  A boundary vertex takes the ascent
// only where the boundary keeps its shape (BodtSmoother::ascent_basis) and
// its smoothing move did not move it: ascent moves along the boundary
// while the tangent-plane smoothing still moves it lowered the minimum of
// the jittered boxes (34.0 to 31.7 degrees on box12.jitter).
void Improver::sweep_bodt(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes,
                          StepReport& report) const {
    const VertexClasses& cls = classes(mesh, surfaces);
    struct State {
        BodtSmoother smoother;
        MoveGuard guard;
        std::vector<FaceKey> faces;
        MoveBasis basis;  // a boundary vertex's ascent directions
        StepReport report;
    };
    const bool interior_only = surface_stays();
    const bool ascent = mode_ == BODT_MODE_BODT && params_.ascent_angle > 0.0 && steps_on_data_ > 0;
    // A vertex that stayed in the first step may move with the ascent (a
    // mode or parameter change clears the records itself).
    if (ascent && steps_on_data_ == 1) settled_.clear();
    const AngleAscent ascent_move(params_.ascent_angle);
    const int threads = sweep_threads(params_.threads, mesh.tets.size());
    // An ascent move may trade a star's largest angle for its smallest:
    // the largest may grow up to the mesh's largest when the sweep began,
    // so the mesh's extreme angles still never get worse, and never past
    // 180 degrees - ascent_angle, so no tet turns bad at that end.
    const double ascent_largest_cosine =
        ascent ? std::max(quality_extremes(shapes, threads).cosines.of_max, ascent_move.largest_cosine()) : 1.0;
    settled_.begin_sweep(mesh.points.size(), mesh.colouring().colours());
    const auto states = coloured_sweep(
        mesh, threads, State{BodtSmoother(surfaces, cls, params_.tolerance, crease_cosine()), MoveGuard(guard_settings(), &shapes), {}, {}, {}},
        [&](State& s, int32_t v, int32_t colour) {
            if ((interior_only && cls.cls[v] != VertexClass::Interior) || settled_.settled(mesh, v)) return;
            StarTable& star = s.guard.star();
            star.gather(mesh, v);
            const int32_t refused = s.report.moves_rejected;
            bool moved = smooth_vertex(
                [&](Vec3& target) { return s.smoother.target(mesh, v, star, target, s.faces); },
                [&](const Vec3& target, double& distance) {
                    return s.guard.move_gathered(mesh, v, target, s.faces, distance);
                },
                s.report);
            const bool inner = cls.cls[v] == VertexClass::Interior;
            const size_t worst = ascent && (inner || !moved) ? ascent_move.worst_tet(mesh, v, star, shapes) : star.size();
            const bool along = worst < star.size() && !inner && s.smoother.ascent_basis(mesh, v, s.basis);
            const MoveBasis* basis = inner ? nullptr : &s.basis;
            const auto ascend = [&](bool steepest) {
                Vec3 target;
                if (!(steepest ? ascent_move.steepest_target(mesh, v, star, worst, basis, target)
                               : ascent_move.target(mesh, v, star, worst, basis, target)))
                    return false;
                // The star table holds no point of v: still v's star after an ODT move.
                double distance = 0.0;
                if (s.guard.move_gathered(mesh, v, target, s.faces, distance, ascent_largest_cosine) ==
                    MoveOutcome::Rejected)
                    return false;
                // Counted once, as moved, even when its ODT move was refused.
                if (!moved) {
                    s.report.moves_rejected = refused;
                    ++s.report.vertices_moved;
                }
                s.report.max_move = std::max(s.report.max_move, distance);
                return moved = true;
            };
            if ((inner || along) && worst < star.size() && !ascend(false)) ascend(true);
            if (moved) settled_.moved(v, settled_.tick(colour));
            else settled_.stayed(v, settled_.tick(colour));
        });
    merge_counts(states, report);
}

// Natural ODT (smoothing/nodt.hpp): boundary vertices projected back onto
// the surface captured when NODT first ran on it.
void Improver::sweep_nodt(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes,
                          StepReport& report) {
    const VertexClasses& cls = classes(mesh, surfaces);
    nodt_input_.update(mesh, cls);
    const bool interior_only = surface_stays();
    struct State {
        NodtSmoother smoother;
        std::vector<FaceKey> faces;
        StepReport report;
    };
    const int threads = sweep_threads(params_.threads, mesh.tets.size());
    const auto states = coloured_sweep(
        mesh, threads,
        State{NodtSmoother(surfaces, cls, nodt_input_, guard_settings(), &shapes), {}, {}}, [&](State& s, int32_t v) {
            if (interior_only && cls.cls[v] != VertexClass::Interior) return;
            smooth_vertex([&](Vec3& target) { return s.smoother.target(mesh, v, target, s.faces); },
                          [&](const Vec3& target, double& distance) {
                              return s.smoother.move(mesh, v, target, s.faces, distance);
                          },
                          s.report);
        });
    merge_counts(states, report);
}

QuasiNewtonSettings Improver::quasi_newton_settings() const {
    QuasiNewtonSettings qn;
    qn.epsilon = params_.qn_epsilon;
    qn.max_iterations = params_.qn_max_iterations;
    qn.initial_step = params_.qn_initial_step;
    qn.growth = params_.qn_growth;
    return qn;
}

// Paper 001 sec. 2, steps (2), (3) and (5): the work set is the vertices of
// poor tets; each free one moves to the minimiser of its weighted star
// objective (eq. 3.4), through the guard.
void Improver::sweep_opt_weighted(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes,
                                  StepReport& report) const {
    const VertexClasses& cls = classes(mesh, surfaces);
    struct State {
        OptWeightedSmoother smoother;
        MoveGuard guard;
        StepReport report;
    };
    const std::vector<uint8_t> work = poor_vertices(mesh, params_.poor_quality);
    const std::vector<FaceKey> no_faces;
    const int threads = sweep_threads(params_.threads, mesh.tets.size());
    const auto states = coloured_sweep(
        mesh, threads,
        State{OptWeightedSmoother(cls.cls, ElementWeights::from_c(params_.weight_c), quasi_newton_settings()),
              MoveGuard(guard_settings(), &shapes), {}},
        [&](State& s, int32_t v) {
            Vec3 target;
            if (!work[v] || !s.smoother.target(mesh, v, target)) return;
            double distance = 0.0;
            const MoveOutcome outcome = s.guard.move(mesh, v, target, no_faces, distance);
            count_outcome(outcome, distance, s.report);
        });
    merge_counts(states, report);
}

int32_t Improver::ops() const {
    if (params_.ops >= 0) return params_.ops;
    if (mode_ == BODT_MODE_BODT || mode_ == BODT_MODE_PHASED_ODT)
        return BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT | BODT_OP_COLLAPSE;
    if (mode_ == BODT_MODE_OPT_WEIGHTED) return BODT_OP_SMOOTH | BODT_OP_FLIP;
    return BODT_OP_SMOOTH;
}

namespace {

// write_to's renumbering kept the index of each of the first `vertices`
// vertices (those the mesh had): made vertices only came after them.
bool kept_vertex_indices(const std::vector<int32_t>& renumber, int32_t vertices) {
    for (int32_t v = 0; v < vertices; ++v)
        if (renumber[v] != v) return false;
    return true;
}

// The relocation of paper 001's mode inside a tentative change: the
// quasi-Newton minimiser of the vertex's weighted star objective.
RelocationTarget weighted_relocation(ElementWeights weights, const QuasiNewtonSettings& qn) {
    return [weights, qn](const EditableMesh& mesh, int32_t v, Vec3& target) {
        if (mesh.vertex_class(v) != VertexClass::Interior) return false;
        const auto is_free = [&mesh](int32_t u) { return mesh.vertex_class(u) == VertexClass::Interior; };
        const TetList tets = mesh.tets_of(v);
        WeightedStar star;
        gather_weighted_star(mesh, tets.data(), tets.data() + tets.size(), v, is_free, weights, star);
        const QuasiNewtonResult r = minimize_quasi_newton(star, mesh.point(v), qn);
        target = r.x;
        return r.iterations > 0;
    };
}

}  // namespace

// Flips, insertion and collapse on an editable copy, written back only when
// something changed.  A mesh holding accepted inverted tets is left to the
// modes that repair those.
bool Improver::change_topology(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report) {
    const int32_t bits = ops();
    if (!(bits & (BODT_OP_FLIP | BODT_OP_INSERT | BODT_OP_COLLAPSE))) return false;
    for (uint8_t r : mesh.reversed)
        if (r) return false;
    TopologySettings settings;
    settings.rules.surface_may_change =
        params_.keep_surface == 0 && (mode_ == BODT_MODE_BODT || mode_ == BODT_MODE_BODT_BASIC);
    // Where the surface may change, a short surface edge on a curved part
    // may go, and a tet lying flat on the surface may be taken out: both
    // leave flat tets that no smoothing or insertion breaks.
    if (settings.rules.surface_may_change) {
        settings.rules.surface_slope = kSurfaceSlope;
        settings.rules.crease_cosine = crease_cosine();
    }
    const bool paper_001 = mode_ == BODT_MODE_OPT_WEIGHTED;
    settings.rules.min_stretch = params_.min_stretch;
    settings.rules.never_worse = params_.never_worse != 0;
    settings.rules.delaunay = params_.delaunay_flips != 0;
    settings.bad_angle_deg = params_.bad_angle;
    settings.flip = (bits & BODT_OP_FLIP) && !paper_001;
    settings.swap_all_boundary = (bits & BODT_OP_FLIP) && paper_001;
    settings.poor_stretch = params_.poor_quality;
    if (paper_001)
        settings.relocation_target = weighted_relocation(ElementWeights::from_c(params_.weight_c), quasi_newton_settings());
    settings.insert = bits & BODT_OP_INSERT;
    settings.collapse = bits & BODT_OP_COLLAPSE;
    // Without smoothing only the vertices an operation makes may move, and
    // in the modes that keep the surface only interior ones do anyway.
    settings.relocate_old = bits & BODT_OP_SMOOTH;
    EditableMesh editable(mesh, classes(mesh, surfaces));
    if (!shapes_.empty()) editable.bound_sines(shapes_);  // the sweep kept them up to date
    // The failed attempts of earlier steps stay known while the sweeps in
    // between report every move (the B-ODT sweeps; none without smoothing).
    const bool moves_reported = !(bits & BODT_OP_SMOOTH) || mode_ == BODT_MODE_ODT ||
                                mode_ == BODT_MODE_BODT_BASIC || mode_ == BODT_MODE_BODT;
    const SweepHistory history{&settled_.moved_at(), settled_.now(), settled_.epoch()};
    failed_.begin_pass(editable, moves_reported ? &history : nullptr);
    const TopologyCounts counts = improve_topology(editable, settings, failed_);
    if (!counts.changed()) return false;
    // Written into a new mesh that replaces the caller's only when all of
    // it is built, so that a failure leaves that as it was.  Most of the
    // mesh is as it was: its neighbours and shapes are carried over, and so
    // are the records of the settled vertices.
    const std::vector<int32_t> written = editable.written_tets();
    TetMesh changed;
    const std::vector<int32_t> renumber = editable.write_to(changed);
    require_finite(changed.points);
    changed.build_topology(editable.written_neighbors(mesh.neighbors, written));
    const bool same_indices = kept_vertex_indices(renumber, mesh.num_vertices());
    const bool surfaces_kept = same_indices && RegionSurfaces::kept_by(mesh, changed, written);
    RegionSurfaces rebuilt;  // only when the surfaces changed
    if (!surfaces_kept) rebuilt.build(changed, 0, BoundarySurface::Strictness::Tolerant);
    // shapes_ is written in place: a failure from here on clears it
    // (sweep_and_change), to be made again at the next step.
    editable.write_shapes(written, shapes_, changed);
    changed.take_caller_data(mesh);
    VertexClasses now;
    std::vector<int32_t> touched;
    const bool carry = classes_valid_ && same_indices;
    try {
        // The vertices whose points or tets the change touched.
        std::vector<int32_t> stamped;
        for (int32_t v = 0; v < editable.num_vertices(); ++v)
            if (editable.stamp(v) != 0 && renumber[v] >= 0) stamped.push_back(renumber[v]);
        if (same_indices) changed.carry_colouring(mesh, stamped);
        // Kept surfaces gain the new vertices, which lie on none (for the
        // mesh as it was, entries of vertices it does not have).
        if (surfaces_kept) surfaces.add_vertices(changed.num_vertices());
        if (carry && surfaces_kept) {
            // The classes come from the surfaces, which are as they were;
            // the new vertices are inside (room made here, filled below).
            classes_.cls.reserve(changed.points.size());
            classes_.line.reserve(changed.points.size());
            touched = stamped;
        } else if (carry) {
            // The classes the next sweep would make (the points stay until then).
            now = classify(changed, rebuilt);
            touched = BodtSmoother::read_differently(classes_, surfaces, now, rebuilt);
            touched.insert(touched.end(), stamped.begin(), stamped.end());
        }
        if (carry) {
            settled_.reserve(changed.points.size());
            failed_.tets.reserve(changed.tets.size());
        }
    } catch (...) {
        mesh.take_caller_data(changed);
        throw;
    }
    // Nothing below throws.
    mesh = std::move(changed);
    if (!surfaces_kept) surfaces = std::move(rebuilt);
    geometry_valid_ = false;
    if (carry) {
        if (surfaces_kept) {
            classes_.cls.resize(mesh.points.size(), VertexClass::Interior);  // within the room made
            classes_.line.resize(mesh.points.size(), {-1, -1});
        } else {
            classes_ = std::move(now);
        }
        // The vertices touched count as moved: the records of the failed
        // attempts around them (kept by vertex, or carried by tet) go too.
        settled_.carry_over(mesh.points.size(), touched);
        failed_.tets.carry_over(written, mesh.tets.size());
    } else {
        classes_valid_ = false;
        settled_.clear();
    }
    report.flips = counts.flips;
    report.vertices_inserted = counts.inserted;
    report.edges_collapsed = counts.collapsed;
    return true;
}

void Improver::sweep(TetMesh& mesh, const RegionSurfaces& surfaces, ShapeCache& shapes, StepReport& report) {
    if (shapes.empty()) shapes = tet_shapes(mesh, sweep_threads(params_.threads, mesh.tets.size()));
    if (mode_ == BODT_MODE_LAPLACE) sweep_laplace(mesh, shapes, report);
    else if (mode_ == BODT_MODE_OPT_WEIGHTED) sweep_opt_weighted(mesh, surfaces, shapes, report);
    else if (mode_ == BODT_MODE_NODT) sweep_nodt(mesh, surfaces, shapes, report);
    else sweep_bodt(mesh, surfaces, shapes, report);
}

// Paper 002's round changes the mesh in several passes: the whole mesh is
// kept to roll back to.
void Improver::step_phased_or_restore(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report) {
    TetMesh saved_mesh = mesh;
    RegionSurfaces saved_surfaces = surfaces;
    GeometryModel saved_geometry = geometry_;
    const bool saved_geometry_valid = geometry_valid_;
    shapes_ = ShapeCache();
    try {
        step_phased(mesh, surfaces, report);
        require_finite(mesh.points);
    } catch (...) {
        settled_.clear();
        mesh = std::move(saved_mesh);
        surfaces = std::move(saved_surfaces);
        geometry_ = std::move(saved_geometry);
        geometry_valid_ = saved_geometry_valid;
        classes_valid_ = false;
        throw;
    }
}

// The other modes: the sweep moves only the points, and the connectivity
// changes are written back all at once, at their end (change_topology).
void Improver::sweep_and_change(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report) {
    const bool smooth = ops() & BODT_OP_SMOOTH;
    const std::vector<Vec3> saved_points = smooth ? mesh.points : std::vector<Vec3>();
    try {
        if (smooth) {
            sweep(mesh, surfaces, shapes_, report);
            require_finite(mesh.points);
        }
        change_topology(mesh, surfaces, report);
    } catch (...) {
        shapes_ = ShapeCache();
        settled_.clear();
        classes_valid_ = false;
        if (smooth) mesh.points = saved_points;
        throw;
    }
}

StepReport Improver::step(TetMesh& mesh, RegionSurfaces& surfaces) {
    StepReport report;
    if (mode_ == BODT_MODE_PHASED_ODT && params_.keep_surface != 0)
        throw Error(BODT_ERR_INVALID_ARGUMENT,
                    "BODT_MODE_PHASED_ODT recovers the surface (its untangling, recovery and surface phases change "
                    "it): BODT_PARAM_KEEP_SURFACE must be 0 in that mode");
    if (mode_ == BODT_MODE_PHASED_ODT) {
        step_phased_or_restore(mesh, surfaces, report);
    } else {
        // Made before anything changes, so that nothing after the write-back can fail.
        if (shapes_.empty()) shapes_ = tet_shapes(mesh, sweep_threads(params_.threads, mesh.tets.size()));
        sweep_and_change(mesh, surfaces, report);
    }
    const int threads = sweep_threads(params_.threads, mesh.tets.size());
    if (shapes_.empty()) shapes_ = tet_shapes(mesh, threads);
    const QualityExtremes q = quality_extremes(shapes_, threads);
    report.step = ++steps_done_;
    ++steps_on_data_;
    report.min_dihedral = q.min_dihedral;
    report.max_dihedral = q.max_dihedral;
    report.min_stretch = q.min_stretch;
    return report;
}

}  // namespace bodt
