// The local connectivity changes (papers 000 sec. 2.3, 001 sec. 4, 002
// sec. 3.5).  Each one checks everything first and either changes the mesh
// into a valid one or leaves it untouched and returns false/-1:
//  - every tet it makes is positively oriented (certified) and its worst
//    dihedral sine exceeds `must_exceed`;
//  - region ids, face markers and feature edges follow the change;
//  - boundary and interface faces change only when the rules allow it and
//    the surface keeps its shape: a face is replaced only by faces in its
//    own plane with its own marker, and a split puts its vertex on the
//    split edge or face.
#pragma once

#include "topology/editable_mesh.hpp"

#include <cstdint>
#include <functional>
#include <initializer_list>

namespace bodt {

struct TopologyRules {
    bool surface_may_change = true;  // false: no boundary/interface face is split, flipped or collapsed
    double min_stretch = 1e-3;       // no new tet below min(this, the worst stretch it replaces)
    bool never_worse = false;        // no new tet with an angle outside the range of the tets it replaces
    // Flips (edge removal, 2-3) only under paper 002 sec. 3.4.4: some tet
    // they replace is not Delaunay and every tet they make is (both with
    // respect to the vertices of the tets involved).
    bool delaunay = false;
    // Untangling (paper 002 sec. 3.5.3): a new tet may be inverted, as long
    // as its stretch is no worse than the worst tet it replaces.
    bool allow_inverted = false;
    // Curved surfaces and feature lines (paper 002's fitted cylinders and
    // arcs): true when x lies on the fitted shape under `element` (a surface
    // face's three vertices or a feature edge's two), which then stands in
    // for "x lies in the face's plane" or "the line is straight".  Empty:
    // the surface is flat between feature edges.
    std::function<bool(const EditableMesh& mesh, std::initializer_list<int32_t> element, const Vec3& x)> on_curved_shape;
    // Where a vertex that a change moves (the midpoint of an edge collapse)
    // goes to stay on its fitted shape; empty: where the change puts it.
    std::function<void(const EditableMesh& mesh, int32_t v, Vec3& x)> snap_to_shape;
    // How far an edge collapse may take the surface off its faces: the
    // vertex that stays (or the midpoint) may lie off the plane of each
    // surface face at the vertex v that goes by this much times sqrt(L h),
    // L the collapsed edge's length and h the mean length of v's surface
    // edges (the mean distance of v's two feature-line neighbours, off the
    // chord between them); and no surface face may turn by more than asin
    // of it.  0: the surface keeps its planes and lines exactly (to
    // round-off).  A short edge on a curved part can then go: its collapse
    // moves the surface by about L times the tilt of the faces around it.
    // Bounded by L alone, a short edge among faces tilted more than 6
    // degrees stayed; by h alone, `part1.p` moved its boundary by 1.8 % of
    // its size.  The same bound lets edge removal take out a tet lying flat
    // on the surface by two faces: each face it uncovers is turned by at
    // most asin of it from the face it replaces.
    double surface_slope = 0.0;
    // Where the surface faces at the vertex that goes (or moves) are
    // faceted (FlatPieces, with creases of a cosine at most this), the
    // collapse takes no slope: the pieces keep their planes.  -1: never.
    double crease_cosine = -1.0;
};

// The largest number of tets around an edge that edge removal considers.
inline constexpr int kMaxEdgeRing = 7;

// Edge removal: the k tets around edge (a, b) become 2k - 4 (closed ring)
// or 2k - 2 (an edge on a flat part of the surface), the ring's polygon
// triangulated to maximise the worst new tet (dynamic programming over the
// polygon, Klincsek's O(k^3)).  k = 3 is the 3-2 flip, k = 4 the 4-4 flip,
// and a surface edge with k = 2 the 2-2 flip.  A surface edge in k = 1 tet
// takes that tet out where it is flat along the surface (see
// TopologyRules::surface_slope): its other two faces go on the surface.
bool remove_edge(EditableMesh& mesh, int32_t a, int32_t b, const TopologyRules& rules, double must_exceed);
// The same with the edge's ring known (mesh.edge_ring(a, b, ring) held).
bool remove_edge(EditableMesh& mesh, int32_t a, int32_t b, const EdgeRing& ring, const TopologyRules& rules,
                 double must_exceed);

// The 2-3 flip: the two tets on face (a, b, c) become three around the edge
// joining their apexes.
bool flip_23(EditableMesh& mesh, const FaceKey& face, const TopologyRules& rules, double must_exceed);
// The same with the face's two tets known (mesh.face_tets(face, t) gave 2).
bool flip_23(EditableMesh& mesh, const FaceKey& face, const int32_t t[2], const TopologyRules& rules,
             double must_exceed);

// Edge split: a new vertex at p, every tet around (a, b) split in two.  On a
// surface edge p is first projected onto the segment.  Returns the new
// vertex or -1.
int32_t split_edge(EditableMesh& mesh, int32_t a, int32_t b, Vec3 p, const TopologyRules& rules, double must_exceed);

// Face split (1-3 in each tet on the face): a new vertex at p.  On a surface
// face p is first projected onto its plane.  Returns the new vertex or -1.
int32_t split_face(EditableMesh& mesh, const FaceKey& face, Vec3 p, const TopologyRules& rules, double must_exceed);

// Point insertion, planned then made: a new interior vertex at p, in place
// of a cavity grown from the tet holding p (walked to from `seed`) without
// crossing a surface, interface or marked face.  Delaunay growth
// (Bowyer-Watson) takes the tets whose circumsphere holds p; Star growth
// goes through each face whose tet with p would have a worst dihedral sine
// of at most `star_goal` (on a mesh that is not Delaunay, such as one with
// slivers whose four vertices lie on the boundary, the circumspheres reach
// far and their cavity rarely is star-shaped from p).  No plan unless the
// cavity holds `seed`, p sees every face of its boundary (each new tet
// acceptable under `rules` and `must_exceed`), and no vertex would be left
// inside.
struct CavityPlan {
    std::vector<int32_t> cavity;     // the tets replaced; the first holds p
    std::vector<Tet> fresh;          // the new tets, -1 for the new vertex
    std::array<double, 4> lambda{};  // p's barycentric coordinates in cavity[0]
    Vec3 point = Vec3::Zero();
    bool valid() const { return !fresh.empty(); }
};
enum class CavityGrowth { Delaunay, Star };
CavityPlan plan_cavity(const EditableMesh& mesh, int32_t seed, const Vec3& p, const TopologyRules& rules,
                       double must_exceed, CavityGrowth growth = CavityGrowth::Delaunay, double star_goal = 0.0);
// Makes a valid plan of the mesh as it is; returns the new vertex (-1: no plan).
int32_t insert_planned(EditableMesh& mesh, const CavityPlan& plan);

// Half-edge collapse: v disappears into w.  Corners and fixed vertices are
// never removed; a feature-line vertex goes only along its feature edge, a
// surface vertex only along a surface edge, and only where its surface
// neighbourhood is flat (one plane and one marker apart from feature edges).
bool collapse_half_edge(EditableMesh& mesh, int32_t v, int32_t w, const TopologyRules& rules, double must_exceed);

// Edge collapse with the exclusions and position rules of paper 002 sec.
// 3.5.1: never between two corners (a); never off the feature lines
// between two of their vertices (b) or through the inside between two
// surface vertices (c), which collapse_half_edge's rules refuse; to the
// endpoint of higher class (corner > feature line > surface > interior) if
// the classes differ; to the midpoint (snapped to the shape, see
// TopologyRules) if they are equal.  Returns the surviving vertex or -1.
int32_t collapse_edge(EditableMesh& mesh, int32_t a, int32_t b, const TopologyRules& rules, double must_exceed);

// The worst dihedral sine of live tets (min_dihedral_sine).
double worst_sine(const EditableMesh& mesh, const std::vector<int32_t>& tets);

}  // namespace bodt
