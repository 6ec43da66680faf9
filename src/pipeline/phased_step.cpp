// BODT_MODE_PHASED_ODT's side of the Improver (paper 002, Fig. 3): the
// geometry it keeps, the reference it recovers, and its step.
#include "common/error.hpp"
#include "pipeline/improver.hpp"
#include "smoothing/move_guard.hpp"
#include "smoothing/phased_odt.hpp"
#include "topology/phased_topology.hpp"
#include "topology/topology_pass.hpp"

#include <algorithm>
#include <string>

namespace bodt {

namespace {

// The mean edge length over the tets' edges (each edge once per tet that
// holds it: a cell size, not a statistic).
double mean_edge_length(const TetMesh& mesh) {
    double sum = 0.0;
    int64_t n = 0;
    for (const Tet& q : mesh.tets)
        for (const auto& e : kEdgeVertex) {
            sum += (mesh.points[q[e[0]]] - mesh.points[q[e[1]]]).norm();
            ++n;
        }
    return n ? sum / static_cast<double>(n) : 0.0;
}

// Rebuilds a mesh's topology and surfaces after an EditableMesh wrote
// itself back, and the geometry after it.
void write_back(EditableMesh& editable, TetMesh& mesh, RegionSurfaces& surfaces, GeometryModel& geometry) {
    const std::vector<int32_t> renumber = editable.write_to(mesh);
    mesh.build_topology(0);
    RegionSurfaces rebuilt;
    rebuilt.build(mesh, 0, BoundarySurface::Strictness::Tolerant);
    surfaces = std::move(rebuilt);
    geometry.follow(editable, renumber, mesh);
}

GeometrySettings geometry_settings(const Params& params) {
    GeometrySettings settings;
    settings.feature_angle_deg = params.feature_angle;
    settings.fit_tolerance = params.fit_tolerance;
    return settings;
}

// The EditableMesh of a phased pass, with the geometry trimmed to the
// mesh (vertices of changes not written are forgotten).  Inverted tets come
// in the order of their neighbours (negative volume), so that untangling
// sees them as they are; the mesh is copied only when a tet is reversed.
EditableMesh phased_editable(const TetMesh& mesh, GeometryModel& geometry) {
    geometry.truncate(mesh.num_vertices());
    const VertexClasses classes = geometry.vertex_classes(mesh);
    if (std::find(mesh.reversed.begin(), mesh.reversed.end(), uint8_t{1}) == mesh.reversed.end())
        return EditableMesh(mesh, classes);
    TetMesh ordered = mesh;
    for (size_t t = 0; t < ordered.reversed.size(); ++t)
        if (ordered.reversed[t]) std::swap(ordered.tets[t][2], ordered.tets[t][3]);
    ordered.reversed.clear();
    return EditableMesh(ordered, classes);
}

}  // namespace

const GeometryModel& Improver::geometry(const TetMesh& mesh) const {
    if (!geometry_valid_) {
        geometry_ = GeometryModel::extract(mesh, geometry_settings(params_), reference_points_);
        geometry_valid_ = true;
        apply_reference_errors();
    }
    return geometry_;
}

// A cylinder's acceptable error: the largest its own surface vertices
// brought from their reference regions; without a reference, its own.
void Improver::apply_reference_errors() const {
    for (SurfaceRegion& r : geometry_.regions()) r.acceptable_error = vertex_acceptable_.empty() ? r.own_error : 0.0;
    const int32_t n = std::min(geometry_.num_vertices(), static_cast<int32_t>(vertex_acceptable_.size()));
    for (int32_t v = 0; v < n; ++v) {
        if (geometry_.vertex_class(v) != VertexClass::Surface || geometry_.entity(v) < 0) continue;
        SurfaceRegion& r = geometry_.regions()[geometry_.entity(v)];
        if (r.shape.type == ShapeType::Cylinder) r.acceptable_error = std::max(r.acceptable_error, vertex_acceptable_[v]);
    }
}

void Improver::clear_reference() {
    density_ = DensityGrid();
    vertex_acceptable_.clear();
    reference_points_.clear();
    geometry_valid_ = false;
    classes_valid_ = false;
}

// Sec. 3.2: the reference's vertex densities, carried to the vertices of
// this mesh (made vertices through their parents) and interpolated over a
// grid of about one mean edge length; sec. 3.3: per cylinder of the
// reference, the largest distance of an edge midpoint from it.
void Improver::set_reference(const TetMesh& reference, const TetMesh& mesh) {
    if (reference.num_vertices() != mesh.num_input_vertices())
        throw Error(BODT_ERR_INVALID_ARGUMENT, "the reference mesh has " + std::to_string(reference.num_vertices()) +
                                                   " vertices, but this mesh was made with " +
                                                   std::to_string(mesh.num_input_vertices()) +
                                                   ": a reference must have the same vertices, numbered alike");
    // The caller numbers both meshes alike, each may store its own order:
    // every per-vertex value of the reference goes to this mesh's vertex.
    const int32_t n = reference.num_vertices();
    std::vector<int32_t> to_mesh(static_cast<size_t>(n));
    for (int32_t r = 0; r < n; ++r) to_mesh[r] = mesh.internal_vertex(reference.caller_vertex(r));
    const std::vector<double> ref_by_reference = vertex_density(reference);
    std::vector<double> ref_density(ref_by_reference.size());
    for (int32_t r = 0; r < n; ++r) ref_density[to_mesh[r]] = ref_by_reference[r];
    std::vector<double> density(ref_density);
    for (const Parents& parents : mesh.new_parents) {
        double value = 0.0;
        for (const Parent& p : parents) value += p.weight * ref_density[p.vertex];
        density.push_back(value);
    }
    DensityGrid grid = DensityGrid::interpolate(mesh, density, mean_edge_length(mesh));

    // A reference cylinder's own error (as extracted) is the acceptable one.
    const GeometryModel ref = GeometryModel::extract(reference, geometry_settings(params_));
    std::vector<double> acceptable(static_cast<size_t>(n), 0.0);
    std::vector<Vec3> points(static_cast<size_t>(n));
    for (int32_t r = 0; r < n; ++r) {
        if (ref.vertex_class(r) == VertexClass::Surface && ref.entity(r) >= 0)
            acceptable[to_mesh[r]] = ref.regions()[ref.entity(r)].own_error;
        points[to_mesh[r]] = reference.points[r];
    }

    density_ = std::move(grid);
    vertex_acceptable_ = std::move(acceptable);
    reference_points_ = std::move(points);
    geometry_valid_ = false;  // extracted again with the reference's sharp edges
    classes_valid_ = false;
}

// Phases 1, 2, 3 (sec. 3.4.2 - 3.4.4), each vertex through the guard; a
// shortened move follows its path (on the circle or cylinder).
void Improver::sweep_phased(TetMesh& mesh, StepReport& report) {
    PhasedOdt odt(geometry(mesh), params_.odt_step);
    MoveGuard guard({params_.min_stretch, 0, params_.never_worse != 0});
    const std::vector<FaceKey> no_faces;
    for (int phase = 1; phase <= 3; ++phase) {
        for (int32_t v = 0; v < mesh.num_vertices(); ++v) {
            PlannedMove move;
            const bool planned = phase == 1   ? odt.chain_move(mesh, v, move)
                                 : phase == 2 ? odt.surface_move(mesh, v, move)
                                              : odt.interior_move(mesh, v, move);
            if (!planned || !move.target.allFinite()) continue;
            const std::vector<FaceKey>& faces = phase == 3 ? no_faces : odt.faces();
            MoveOutcome outcome = MoveOutcome::Rejected;
            double distance = 0.0;
            double f = 1.0;
            for (int attempt = 0; attempt <= params_.backtrack_steps && outcome == MoveOutcome::Rejected; ++attempt, f *= 0.5)
                if (guard.move(mesh, v, move.at(f), faces, distance) != MoveOutcome::Rejected)
                    outcome = attempt == 0 ? MoveOutcome::Moved : MoveOutcome::Shortened;
            if (outcome != MoveOutcome::Rejected) ++report.vertices_moved;
            if (outcome == MoveOutcome::Shortened) ++report.moves_shortened;
            if (outcome == MoveOutcome::Rejected) ++report.moves_rejected;
            report.max_move = std::max(report.max_move, distance);
        }
    }
}

// Fig. 3: bad tets out, properties back, then ODT by phases, then flips.
void Improver::step_phased(TetMesh& mesh, RegionSurfaces& surfaces, StepReport& report) {
    const int32_t bits = ops();
    this->geometry(mesh);  // extracted if it is not yet
    GeometryModel& geometry = geometry_;
    PhasedTopologySettings settings;
    settings.rules.min_stretch = params_.min_stretch;
    settings.bad_angle_deg = params_.bad_angle;
    settings.split_ratio = params_.density_split;
    settings.collapse_ratio = params_.density_collapse;
    settings.split = bits & BODT_OP_INSERT;
    settings.collapse = bits & BODT_OP_COLLAPSE;
    settings.flip = bits & BODT_OP_FLIP;

    if (settings.split || settings.collapse) {
        EditableMesh editable = phased_editable(mesh, geometry);
        PhasedTopology topology(editable, geometry, settings);
        PhasedTopologyCounts counts;
        counts.untangling_moves = topology.untangle_by_moves();
        if (settings.collapse) counts.inverted_removed = topology.remove_inverted();
        if (settings.split && settings.collapse) counts.degenerate_removed = topology.remove_degenerate();
        topology.recover(density_.empty() ? nullptr : &density_, counts);
        editable.commit();
        if (counts.changed() || counts.untangling_moves > 0) {
            write_back(editable, mesh, surfaces, geometry);
            classes_valid_ = false;
        }
        report.vertices_inserted += counts.splits + counts.degenerate_removed;
        report.edges_collapsed += counts.collapses + counts.inverted_removed + counts.degenerate_removed;
        report.vertices_moved += counts.untangling_moves;
    }
    if (bits & BODT_OP_SMOOTH) sweep_phased(mesh, report);
    if (settings.flip) {
        EditableMesh editable = phased_editable(mesh, geometry);
        PhasedTopology topology(editable, geometry, settings);
        int32_t flips = topology.flip_surface();
        // Sec. 3.4.4: 2-3, 3-2 and 4-4 flips inside, under the Delaunay conditions.
        TopologySettings inside;
        inside.rules.surface_may_change = false;
        inside.rules.min_stretch = params_.min_stretch;
        inside.rules.delaunay = true;
        inside.flip_angle_deg = 90.0;  // sec. 3.4.4: every tet that is not Delaunay
        inside.flip = true;
        inside.insert = inside.collapse = false;
        flips += improve_topology(editable, inside).flips;
        editable.commit();
        if (flips > 0) {
            write_back(editable, mesh, surfaces, geometry);
            classes_valid_ = false;
        }
        report.flips += flips;
    }
}

}  // namespace bodt
