// The connectivity changes of paper 002's phased mode (sec. 3.4.3, 3.5),
// on an EditableMesh whose vertices carry the GeometryModel's entities.
// A vertex made on a surface edge or sharp edge goes onto that region's or
// chain's fitted shape; nothing is kept that leaves a tet inverted or flat
// (untangling excepted, which only ever raises the worst stretch).
#pragma once

#include "features/geometry_model.hpp"
#include "pipeline/density_field.hpp"
#include "topology/operations.hpp"

#include <cstdint>

namespace bodt {

struct PhasedTopologySettings {
    TopologyRules rules;          // base rules (min stretch); on_curved_shape is set here
    double bad_angle_deg = 15.0;  // degenerate: an angle outside [this, 180 - this] (sec. 3.5.2)
    double split_ratio = 2.0 / 3.0;     // gamma (sec. 3.5.1)
    double collapse_ratio = 1.5;        // delta
    bool split = true, collapse = true, flip = true;
};

struct PhasedTopologyCounts {
    int32_t untangling_moves = 0;   // vertex moves before them
    int32_t inverted_removed = 0;   // half-edge collapses (sec. 3.5.3)
    int32_t degenerate_removed = 0; // split + collapse (sec. 3.5.2)
    int32_t splits = 0, collapses = 0;  // density and geometric recovery (sec. 3.5.1)
    int32_t flips = 0;              // surface flips as split + collapse (sec. 3.4.3)
    bool changed() const { return inverted_removed + degenerate_removed + splits + collapses + flips > 0; }
};

class PhasedTopology {
public:
    PhasedTopology(EditableMesh& mesh, GeometryModel& geometry, const PhasedTopologySettings& settings);

    // Before sec. 3.5.3: the vertices of tets with stretch <= 0 moved into
    // the kernel of their star (interior ones, when it has one) or to the
    // mean of their neighbours (surface and chain vertices: of those on
    // their region or chain, then onto its fitted shape), each move kept
    // only if it leaves fewer such tets around the vertex (or as many,
    // better): what a deformation left behind its moved boundary is pulled
    // back without losing vertices.  Returns the moves kept.
    int32_t untangle_by_moves();
    // Sec. 3.5.3: while a tet has stretch <= 0, the half-edge collapse of one
    // of the worst tet's edges that leaves the best worst stretch around the
    // kept vertex, if that beats the worst before.
    int32_t remove_inverted();
    // Sec. 3.5.2: a sliver's two crossing edges are split and the new short
    // edge collapsed; a cap's or spade's edge between its largest and
    // smallest faces is split and the new short edge collapsed.
    int32_t remove_degenerate();
    // Sec. 3.5.1: surface edges of a cylinder further from it than the
    // region's acceptable error are split onto it; edges are split where
    // 1/|e| < gamma rho' and collapsed where 1/|e| > delta rho'.  Only on
    // a mesh without inverted or flat tets, and no tet made is below the
    // mesh's worst stretch times what a midpoint split costs a regular tet
    // (about 0.71), or below the tets it replaces.
    void recover(const DensityGrid* density, PhasedTopologyCounts& counts);
    // Sec. 3.4.3: surface edges that are not locally Delaunay flipped by a
    // split and the collapse of the new vertex into an opposite one.
    int32_t flip_surface();

private:
    // `judged_after`: part of a larger change judged as a whole (degenerate
    // removal, surface flips), so only held to validity here.
    int32_t split_onto_shape(int32_t a, int32_t b, bool judged_after = false);
    int32_t collapse_by_rules(int32_t a, int32_t b);
    bool on_shape(std::initializer_list<int32_t> element, const Vec3& x) const;
    // Every surface edge at v on a cylinder is within the region's
    // acceptable geometric error (sec. 3.5.1): a collapse or flip must not
    // undo what the geometric splits recover.
    bool accurate_at(int32_t v) const;
    const Shape* element_shape(std::initializer_list<int32_t> element) const;

    EditableMesh& mesh_;
    GeometryModel& geometry_;
    PhasedTopologySettings settings_;
};

}  // namespace bodt
