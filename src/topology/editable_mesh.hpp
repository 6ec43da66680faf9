// A tet mesh whose connectivity can change: the working copy the topology
// operations edit during a step.  TetMesh keeps compact CSR arrays that are
// rebuilt, not edited; here every vertex keeps a growable list of its tets,
// removed tets leave a hole (compacted by write_to), and every change goes
// through a few primitives that log it, so a tentative operation can be
// rolled back exactly (checkpoint / rollback).
#pragma once

#include "features/vertex_classes.hpp"
#include "mesh/tet_mesh.hpp"

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <vector>

namespace bodt {

// The ref of a feature edge the caller gave; empty for one a mode found.
using CallerRef = std::optional<int32_t>;

// The tets around an edge (a, b), ordered so that (a, b, ring[i], ring[i+1])
// is each tet's positive orientation.  A closed ring has as many vertices as
// tets; an open one (an edge on the boundary) has one more.
struct EdgeRing {
    std::vector<int32_t> ring;
    std::vector<int32_t> tets;
    bool closed = false;
};

// A vertex's tets (EditableMesh::tets_of): good until the mesh's
// connectivity changes.
struct TetList {
    const int32_t* first;
    const int32_t* last;
    const int32_t* begin() const { return first; }
    const int32_t* end() const { return last; }
    const int32_t* data() const { return first; }
    size_t size() const { return static_cast<size_t>(last - first); }
    bool empty() const { return first == last; }
    int32_t front() const { return *first; }
    int32_t operator[](size_t i) const { return first[i]; }
    explicit operator std::vector<int32_t>() const { return {first, last}; }
};

class EditableMesh {
public:
    // Copies the mesh; `classes` gives each vertex's class (new vertices
    // get theirs from the operation that makes them).
    EditableMesh(const TetMesh& mesh, const VertexClasses& classes);

    // Writes the result back: tets compacted in order, vertices of the
    // input kept at their index (unused if an operation removed them),
    // vertices made since the input appended, those no tet uses dropped.
    // The caller rebuilds the mesh's topology afterwards.  Returns each
    // vertex's index in `mesh` (-1: dropped).
    std::vector<int32_t> write_to(TetMesh& mesh) const;
    // Where write_to puts each tet slot: its index in `mesh`, -1 for a
    // removed tet.
    std::vector<int32_t> written_tets() const;
    // The face neighbours of the written tets (TetMesh::neighbors), from
    // `before`, those of the mesh this one was made from, whose tet t is
    // slot t here with the same vertices in the same order.  A face keeps
    // its neighbour while both tets are there; only the faces of new tets
    // and those whose neighbour went are looked up.  Neighbours are unique,
    // so a full build gives the same.
    std::vector<Tet> written_neighbors(const std::vector<Tet>& before, const std::vector<int32_t>& written) const;
    // `shapes`, the shapes of the mesh this one was made from (empty: none
    // known), made tet_shapes() of the written tets in `mesh`, in place: a
    // tet that is still there and none of whose vertices changed (stamp 0)
    // keeps its shape; the others are computed.  In place, since a copy
    // of a large mesh's shapes costs fresh pages at every step.
    void write_shapes(const std::vector<int32_t>& written, std::vector<TetShape>& shapes, const TetMesh& mesh) const;

    // ---- queries
    int32_t num_vertices() const { return static_cast<int32_t>(points_.size()); }
    int32_t tet_capacity() const { return static_cast<int32_t>(tets_.size()); }
    bool alive(int32_t t) const { return tets_[t][0] >= 0; }
    const Tet& tet(int32_t t) const { return tets_[t]; }
    int32_t region(int32_t t) const { return regions_[t]; }
    int32_t origin(int32_t t) const { return origin_[t]; }
    const Vec3& point(int32_t v) const { return points_[v]; }
    // In ascending order, but for a rollback, which puts tets back where they were.
    TetList tets_of(int32_t v) const {
        const int32_t* at = vt_pool_.data() + vt_[v].at;
        return {at, at + vt_[v].size};
    }
    VertexClass vertex_class(int32_t v) const { return cls_[v]; }
    bool is_feature_edge(int32_t a, int32_t b) const { return features_.count(edge_key(a, b)) != 0; }
    const EdgeSet& feature_edges() const { return features_; }
    const Parents& parents(int32_t v) const { return v < input_vertices_ ? no_parents_ : parents_[v - input_vertices_]; }
    TetPoints tet_points(int32_t t) const;
    // The smallest dihedral sine of live tet t (min_dihedral_sine), kept
    // until one of its vertices moves: the flip and insertion passes ask
    // for the same tets many times.
    double tet_sine(int32_t t) const;
    // tet_sine(t) >= s, computed only when the bound from bound_sines does
    // not already tell.
    bool sine_at_least(int32_t t, double s) const {
        return (!sine_floor_.empty() && sine_floor_[t] >= s) || tet_sine(t) >= s;
    }
    // Lower bounds of the sines from the shapes of the tets this mesh was
    // made from (shapes[t] of tet t, up to date with the points): the scans
    // for bad tets pass over the good ones without the sine's roots.  A
    // bound is dropped when a vertex of its tet moves.
    void bound_sines(const std::vector<TetShape>& shapes);

    // The tets holding every vertex of `vs` (an edge, a face, a tet).
    std::vector<int32_t> tets_holding(std::initializer_list<int32_t> vs) const;
    // Some tet has the vertices of q (in any order): looked for among the
    // tets of the one of them with the fewest.
    bool has_tet(const Tet& q) const;
    // Tets holding the face; returns how many (0, 1 or 2).
    int face_tets(const FaceKey& f, int32_t out[2]) const;
    // On the boundary, between regions, or marked by the caller.
    bool is_surface_face(const FaceKey& f) const;
    // The face's marker; 0 when it has none.
    int32_t marker(const FaceKey& f) const;
    bool has_marker(const FaceKey& f) const { return may_be_marked(f) && markers_.count(f) != 0; }
    // The edge lies on a surface face.
    bool is_surface_edge(int32_t a, int32_t b) const;
    // False when the tets around the edge do not form one fan (a
    // non-manifold edge) or there are none.
    bool edge_ring(int32_t a, int32_t b, EdgeRing& out) const;
    // Some tet holds both a and b.
    bool has_edge(int32_t a, int32_t b) const;
    // The vertices sharing a tet with v.
    void neighbors(int32_t v, std::vector<int32_t>& out) const;
    // A clock that every change of a vertex's point or tets advances, and
    // the time of v's last change: a test that read only vertices whose
    // stamp is at most an earlier clock() would give the same answer now.
    // A rollback gives the vertices it restores their stamps back (the
    // clock goes on): a test made before the checkpoint still holds.
    uint64_t clock() const { return clock_; }
    uint64_t stamp(int32_t v) const { return stamp_[v]; }
    // Every stamp is 0: nothing changed since the mesh was made, or every
    // change was rolled back.
    bool untouched() const { return stamped_ == 0; }

    // ---- changes (all logged)
    int32_t add_vertex(const Vec3& p, VertexClass cls, Parents parents);
    void move_vertex(int32_t v, const Vec3& p);
    // A made vertex's parents (input vertices are their own parent and
    // have none).
    void set_parents(int32_t v, Parents parents);
    int32_t add_tet(const Tet& t, int32_t region, int32_t origin);
    void remove_tet(int32_t t);
    void set_marker(const FaceKey& f, int32_t marker);
    void erase_marker(const FaceKey& f);
    // Feature edges: `caller` holds the ref of one the caller gave (kept in
    // the output); erase returns the erased edge's, so a split or collapse
    // hands it on.
    void add_feature_edge(int32_t a, int32_t b, CallerRef caller);
    CallerRef erase_feature_edge(int32_t a, int32_t b);

    // A mark to roll back to; rollback undoes every change made since.
    size_t checkpoint() const { return journal_.size(); }
    void rollback(size_t mark);
    // Forgets the log: no rollback past this point.
    void commit() {
        journal_.clear();
        old_parents_.clear();
        removed_.clear();
        old_stamps_.clear();
    }

private:
    enum class Change : uint8_t {
        AddVertex, MoveVertex, SetParents, AddTet, RemoveTet, SetMarker, EraseMarker, AddFeature, EraseFeature
    };
    struct Entry {
        Change kind;
        int32_t index;      // vertex or tet
        FaceKey face;       // markers
        int32_t old_marker; // SetMarker: the previous one, or INT32_MIN when there was none
        Vec3 old_point;     // MoveVertex
        EdgeKey edge;       // feature edges
        CallerRef caller;   // feature edges: the caller's ref, if the caller's
    };
    // detach returns where t was in each of its vertices' lists; attach puts
    // it back there (a rollback restores the lists' order too: the order of
    // a vertex's tets decides the order of sums and rings), or, without
    // `at`, at their ends.
    std::array<int32_t, 4> detach(int32_t t);
    void attach(int32_t t, const std::array<int32_t, 4>* at = nullptr);
    // Sets v's point and forgets the sines of its tets.
    void place(int32_t v, const Vec3& p);
    std::array<uint64_t, 4> stamps_of(const Tet& q) const {
        return {stamp_[q[0]], stamp_[q[1]], stamp_[q[2]], stamp_[q[3]]};
    }
    void set_stamp(int32_t v, uint64_t stamp) {
        stamped_ += static_cast<int64_t>(stamp != 0) - static_cast<int64_t>(stamp_[v] != 0);
        stamp_[v] = stamp;
    }
    void restore_stamps(const Tet& q, const std::array<uint64_t, 4>& old) {
        for (int i = 0; i < 4; ++i) set_stamp(q[i], old[i]);
    }

    std::vector<Vec3> points_;
    std::vector<VertexClass> cls_;
    std::vector<uint8_t> pins_;  // the caller's kPinned bits
    std::vector<Parents> parents_;  // of the made vertices (input_vertices_ on)
    Parents no_parents_;            // an input vertex's
    std::vector<Tet> tets_;  // removed: {-1, -1, -1, -1}
    std::vector<int32_t> regions_, origin_;
    mutable std::vector<double> sine_;  // tet_sine, NaN: not known
    std::vector<double> sine_floor_;    // bound_sines, -inf: none (empty: never bounded)
    std::vector<uint64_t> stamp_;       // per vertex, see stamp()
    int64_t stamped_ = 0;               // vertices whose stamp is not 0
    uint64_t clock_ = 0;
    mutable std::vector<std::array<int32_t, 3>> ring_links_;  // edge_ring's scratch
    // Every vertex's tets in one array: vertex v's are vt_pool_[at, at +
    // size), with room up to at + room; a list that outgrows its room moves
    // to the end with twice as much.  One allocation for the whole mesh,
    // not one per vertex.
    struct TetSlot {
        size_t at;
        int32_t size, room;
    };
    std::vector<int32_t> vt_pool_;
    std::vector<TetSlot> vt_;
    std::unordered_map<FaceKey, int32_t, FaceKeyHash> markers_;
    // Per vertex, how many marked faces hold it: a face with a vertex on
    // none is not marked, and most faces the operations ask about (inner
    // ones) are told so without a lookup in markers_.
    std::vector<int32_t> marked_at_;
    bool may_be_marked(const FaceKey& f) const {
        return (marked_at_[f.v[0]] != 0) & (marked_at_[f.v[1]] != 0) & (marked_at_[f.v[2]] != 0);
    }
    void count_marked(const FaceKey& f, int32_t delta) {
        for (int32_t v : f.v) marked_at_[v] += delta;
    }
    EdgeRefs caller_features_;  // the caller's feature edges and refs, kept in the output
    EdgeSet features_;         // every feature edge the classes came from, plus the caller's
    std::vector<Entry> journal_;
    std::vector<Parents> old_parents_;  // SetParents entries, in order
    struct Removed {
        Tet tet;                    // its vertices
        std::array<int32_t, 4> at;  // detach's places
    };
    std::vector<Removed> removed_;  // RemoveTet entries, in order
    std::vector<std::array<uint64_t, 4>> old_stamps_;  // MoveVertex, AddTet, RemoveTet entries, in order
    int32_t input_vertices_;
};

}  // namespace bodt
