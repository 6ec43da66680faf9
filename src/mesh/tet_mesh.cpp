#include "mesh/tet_mesh.hpp"

#include "bodt.h"
#include "common/error.hpp"
#include "common/parallel.hpp"
#include "mesh/vertex_colouring.hpp"

#include <algorithm>
#include <optional>
#include <limits>

namespace bodt {

namespace {

std::array<int32_t, 3> face_of(const Tet& t, int i) {
    return {t[kFaceVertex[i][0]], t[kFaceVertex[i][1]], t[kFaceVertex[i][2]]};
}

}  // namespace

void TetMesh::build_incidence() {
    const int32_t nv = num_vertices();
    vt_offset.assign(static_cast<size_t>(nv) + 1, 0);
    for (const Tet& t : tets)
        for (int32_t v : t) ++vt_offset[v + 1];
    for (int32_t v = 0; v < nv; ++v) vt_offset[v + 1] += vt_offset[v];
    vt_tets.resize(tets.size() * 4);
    std::vector<int32_t> fill(vt_offset.begin(), vt_offset.end() - 1);
    for (int32_t t = 0; t < num_tets(); ++t)
        for (int32_t v : tets[t]) vt_tets[fill[v]++] = t;
}

// Smoothing sums over stars, and its results must not depend on the
// internal order.
void TetMesh::order_stars_as_caller() {
    if (!tet_origin.empty() || caller.tet_to_caller.empty()) return;
    const std::vector<int32_t>& rank = caller.tet_to_caller;
    for (int32_t v = 0; v < num_vertices(); ++v)
        std::sort(vt_tets.begin() + vt_offset[v], vt_tets.begin() + vt_offset[v + 1],
                  [&rank](int32_t a, int32_t b) { return rank[a] < rank[b]; });
}

// Faces are matched at their smallest vertex: the faces of the tets around
// vertex v whose smallest vertex is v, keyed by their other two vertices
// and sorted, come in pairs with equal keys, the two sides of one face.
// Each face belongs to one vertex, so the vertices may be shared among
// threads.  A face in three tets, or two tets with the same vertices, is
// reported for the lowest tet that shows it, whatever the number of
// threads: match_face() then names the tets for the message.
namespace {

struct FaceMatch {
    int32_t found = -1, local = -1;  // the neighbour and its vertex opposite the face
    int32_t third = -1;              // a third tet on the face: an error
};

FaceMatch match_face(const TetMesh& mesh, int32_t t, int i) {
    const auto f = face_of(mesh.tets[t], i);
    FaceMatch m;
    for (const int32_t* s = mesh.star_begin(f[0]); s != mesh.star_end(f[0]); ++s) {
        const Tet& q = mesh.tets[*s];
        if (*s == t || !holds(q, f[1]) || !holds(q, f[2]))
            continue;
        if (m.found != -1) {
            m.third = *s;
            return m;
        }
        m.found = *s;
        for (int k = 0; k < 4; ++k)
            if (q[k] != f[0] && q[k] != f[1] && q[k] != f[2]) m.local = k;
    }
    return m;
}

struct OwnedFace {
    uint64_t key;  // the face's two larger vertices
    int32_t side;  // 4 * tet + the local vertex opposite the face
    bool operator<(const OwnedFace& o) const { return key < o.key || (key == o.key && side < o.side); }
};

}  // namespace

void TetMesh::build_neighbors(int base, int threads) {
    const int32_t nt = num_tets(), nv = num_vertices();
    neighbors.assign(tets.size(), Tet{-1, -1, -1, -1});
    // Each thread's lowest tet with a face in more than two tets, or a
    // neighbour on the same side of a shared face.
    std::vector<int32_t> bad(static_cast<size_t>(std::max(1, threads)), nt);
    ChunkCounter chunks(nv, 256);
    on_threads(threads, [&](int me) {
        int32_t& first_bad = bad[static_cast<size_t>(me)];
        std::vector<OwnedFace> faces;
        for (int64_t begin, end; chunks.next(begin, end);)
            for (int32_t v = static_cast<int32_t>(begin); v < end; ++v) {
                faces.clear();
                for (const int32_t* s = star_begin(v); s != star_end(v); ++s) {
                    // v is the smallest vertex of the face opposite corner i
                    // when no other corner but i is smaller than v.
                    const Tet& q = tets[*s];
                    int smaller = 0, below = -1;
                    for (int k = 0; k < 4; ++k)
                        if (q[k] < v) ++smaller, below = k;
                    if (smaller > 1) continue;
                    for (int i = 0; i < 4; ++i) {
                        if (q[i] == v || (smaller == 1 && i != below)) continue;
                        int32_t lo = std::numeric_limits<int32_t>::max(), hi = -1;
                        for (int k = 0; k < 4; ++k)
                            if (k != i && q[k] != v) lo = std::min(lo, q[k]), hi = std::max(hi, q[k]);
                        faces.push_back({(static_cast<uint64_t>(lo) << 32) | static_cast<uint32_t>(hi), 4 * *s + i});
                    }
                }
                std::sort(faces.begin(), faces.end());
                for (size_t a = 0, b; a < faces.size(); a = b) {
                    for (b = a + 1; b < faces.size() && faces[b].key == faces[a].key;) ++b;
                    const int32_t t0 = faces[a].side / 4, i0 = faces[a].side % 4;
                    if (b - a > 2) first_bad = std::min(first_bad, t0);  // sorted: t0 is the group's lowest
                    if (b - a != 2) continue;
                    const int32_t t1 = faces[a + 1].side / 4, i1 = faces[a + 1].side % 4;
                    neighbors[t0][i0] = t1;
                    neighbors[t1][i1] = t0;
                    if (tets[t0][i0] == tets[t1][i1]) first_bad = std::min(first_bad, t0);
                }
            }
    });
    const int32_t first_bad = *std::min_element(bad.begin(), bad.end());
    if (first_bad == nt) return;
    const int32_t t = first_bad;
    for (int i = 0; i < 4; ++i) {
        const FaceMatch m = match_face(*this, t, i);
        const auto f = face_of(tets[t], i);
        if (m.third != -1)
            throw Error(BODT_ERR_BAD_MESH, "face (" + std::to_string(f[0] + base) + ", " + std::to_string(f[1] + base) +
                                               ", " + std::to_string(f[2] + base) + ") is shared by more than two tets: " +
                                               std::to_string(t + base) + ", " + std::to_string(m.found + base) +
                                               " and " + std::to_string(m.third + base));
        if (m.found != -1 && tets[m.found][m.local] == tets[t][i])
            throw Error(BODT_ERR_BAD_MESH, "tets " + std::to_string(t + base) + " and " +
                                               std::to_string(m.found + base) + " have the same vertices");
    }
}

bool TetMesh::is_surface_face(int32_t t, int i) const {
    return is_region_boundary_face(t, i) || is_marked_face(t, i);
}

bool TetMesh::is_marked_face(int32_t t, int i) const {
    if (face_markers.empty()) return false;
    const auto f = face_of(tets[t], i);
    return face_markers.count(FaceKey::of(f[0], f[1], f[2])) != 0;
}

std::vector<uint8_t> TetMesh::marked_face_vertices() const {
    std::vector<uint8_t> marked(points.size(), 0);
    for (const auto& m : face_markers)
        for (const int32_t v : m.first.v) marked[v] = 1;
    return marked;
}

bool TetMesh::is_marked_face(int32_t t, int i, const std::vector<uint8_t>& marked) const {
    const Tet& q = tets[t];
    for (int k = 0; k < 3; ++k)
        if (!marked[q[kFaceVertex[i][k]]]) return false;
    return is_marked_face(t, i);
}

bool TetMesh::is_surface_face(int32_t t, int i, const std::vector<uint8_t>& marked) const {
    return is_region_boundary_face(t, i) || is_marked_face(t, i, marked);
}

// An interior surface face is listed once, from the side it points out of:
// the tet with the smaller region id, or the smaller (caller's) index in
// equal regions.
bool TetMesh::is_listed_face(int32_t t, int i, const std::vector<uint8_t>& marked) const {
    if (!is_surface_face(t, i, marked)) return false;
    const int32_t s = neighbors[t][i];
    return s < 0 || regions[t] < regions[s] || (regions[t] == regions[s] && caller_tet(t) < caller_tet(s));
}

void TetMesh::update_vertex_flags() {
    const int32_t nv = num_vertices();
    vflags.resize(static_cast<size_t>(nv), 0);
    for (int32_t v = 0; v < nv; ++v) {
        vflags[v] &= kPinned;
        if (vt_offset[v] == vt_offset[v + 1]) vflags[v] |= kUnused;
    }
    const std::vector<uint8_t> marked = marked_face_vertices();
    for (int32_t t = 0; t < num_tets(); ++t) {
        for (int i = 0; i < 4; ++i) {
            if (!is_surface_face(t, i, marked)) continue;
            const uint8_t flag = neighbors[t][i] < 0 ? kOnBoundary : kOnInterface;
            for (int k = 0; k < 3; ++k) vflags[tets[t][kFaceVertex[i][k]]] |= flag;
        }
    }
}

void TetMesh::build_topology(int base, int threads) {
    colouring_.reset();
    sweep_order_.reset();
    release_lists_.reset();
    build_incidence();
    build_neighbors(base, threads);  // faster on stars in memory order: ordered after
    order_stars_as_caller();
    update_vertex_flags();
}

void TetMesh::build_topology(std::vector<Tet> known_neighbors) {
    colouring_.reset();
    sweep_order_.reset();
    release_lists_.reset();
    build_incidence();
    neighbors = std::move(known_neighbors);
    order_stars_as_caller();
    update_vertex_flags();
}

std::array<int32_t, 3> TetMesh::outward_face(int32_t t, int i) const {
    auto f = face_of(tets[t], i);
    if (!reversed.empty() && reversed[t]) std::swap(f[1], f[2]);
    return f;
}

void TetMesh::find_reversed_tets(int base) {
    const int32_t nt = num_tets();
    std::vector<int8_t> parity(tets.size(), -1);
    std::vector<int32_t> part;
    for (int32_t seed = 0; seed < nt; ++seed) {
        if (parity[seed] >= 0) continue;
        parity[seed] = 0;
        part.assign(1, seed);
        int32_t flipped = 0;
        for (size_t head = 0; head < part.size(); ++head) {
            const int32_t t = part[head];
            for (int i = 0; i < 4; ++i) {
                const int32_t s = neighbors[t][i];
                if (s < 0) continue;
                int j = 0;
                while (neighbors[s][j] != t) ++j;
                // Same cyclic order of the shared face in both tets means
                // one of them is reversed relative to the other.
                const auto a = face_of(tets[t], i), b = face_of(tets[s], j);
                bool same = false;
                for (int r = 0; r < 3; ++r) same |= a[0] == b[r] && a[1] == b[(r + 1) % 3];
                const int8_t want = static_cast<int8_t>(parity[t] ^ (same ? 1 : 0));
                if (parity[s] < 0) {
                    parity[s] = want;
                    flipped += want;
                    part.push_back(s);
                } else if (parity[s] != want) {
                    throw Error(BODT_ERR_BAD_MESH, "the tets around tet " + std::to_string(s + base) +
                                                       " cannot be oriented consistently");
                }
            }
        }
        const bool majority_flipped = 2 * flipped > static_cast<int32_t>(part.size());
        for (int32_t t : part) parity[t] = static_cast<int8_t>(parity[t] ^ (majority_flipped ? 1 : 0));
    }
    reversed.assign(parity.begin(), parity.end());
}

const VertexColouring& TetMesh::colouring() const {
    if (!colouring_) colouring_ = std::make_shared<const VertexColouring>(colour_vertices(*this));
    return *colouring_;
}

const std::vector<int32_t>& TetMesh::sweep_order() const {
    if (!sweep_order_) sweep_order_ = std::make_shared<const std::vector<int32_t>>(bodt::sweep_order(*this, colouring()));
    return *sweep_order_;
}

const ReleaseLists& TetMesh::release_lists(int threads) const {
    if (!release_lists_) release_lists_ = std::make_shared<const ReleaseLists>(bodt::release_lists(*this, colouring(), threads));
    return *release_lists_;
}

void TetMesh::carry_colouring(const TetMesh& before, const std::vector<int32_t>& changed) {
    if (before.colouring_) colouring_ = std::make_shared<const VertexColouring>(recolour_vertices(*this, *before.colouring_, changed));
    sweep_order_.reset();
    release_lists_.reset();
}

std::vector<SurfaceFace> TetMesh::surface_faces() const {
    std::vector<std::pair<FaceKey, SurfaceFace>> keyed;  // sorted by the caller's vertex indices
    const std::vector<uint8_t> marked = marked_face_vertices();
    for (int32_t t = 0; t < num_tets(); ++t) {
        for (int i = 0; i < 4; ++i) {
            if (!is_listed_face(t, i, marked)) continue;
            const auto f = outward_face(t, i);
            const auto it = face_markers.find(FaceKey::of(f[0], f[1], f[2]));
            keyed.push_back({FaceKey::of(caller_vertex(f[0]), caller_vertex(f[1]), caller_vertex(f[2])),
                             {f, it == face_markers.end() ? 0 : it->second}});
        }
    }
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<SurfaceFace> out;
    out.reserve(keyed.size());
    for (const auto& k : keyed) out.push_back(k.second);
    return out;
}

int32_t TetMesh::count_surface_faces() const {
    int32_t n = 0;
    const std::vector<uint8_t> marked = marked_face_vertices();
    for (int32_t t = 0; t < num_tets(); ++t)
        for (int i = 0; i < 4; ++i) n += is_listed_face(t, i, marked);
    return n;
}

std::vector<int32_t> TetMesh::vertex_refs() const {
    const int32_t ninput = num_input_vertices();
    std::vector<int32_t> refs(static_cast<size_t>(num_vertices()), 0);
    if (input_vertex_refs.empty()) return refs;
    std::copy(input_vertex_refs.begin(), input_vertex_refs.begin() + ninput, refs.begin());
    // A vertex made inside a region from surface vertices (splitting an edge
    // between two boundary vertices) must not take a boundary condition's
    // ref, so only parents on the same side count (and still in the mesh).
    const auto on_surface = [this](int32_t v) { return (vflags[v] & (kOnBoundary | kOnInterface)) != 0; };
    for (int32_t v = ninput; v < num_vertices(); ++v) {
        std::optional<int32_t> shared;
        bool agree = true;
        for (const Parent& p : new_parents[v - ninput]) {
            if ((vflags[p.vertex] & kUnused) || on_surface(p.vertex) != on_surface(v)) continue;
            const int32_t r = input_vertex_refs[p.vertex];
            if (shared && *shared != r) agree = false;
            shared = r;
        }
        refs[v] = agree && shared ? *shared : 0;
    }
    return refs;
}

double TetMesh::bbox_diagonal() const {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    for (int32_t v = 0; v < num_vertices(); ++v) {
        if (vflags[v] & kUnused) continue;
        lo = lo.cwiseMin(points[v]);
        hi = hi.cwiseMax(points[v]);
    }
    return lo.x() <= hi.x() ? (hi - lo).norm() : 0.0;
}

}  // namespace bodt
