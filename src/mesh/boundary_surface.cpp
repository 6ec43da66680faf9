#include "mesh/boundary_surface.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <algorithm>
#include <string>

namespace bodt {

namespace {

struct OrientedFace {
    std::array<int32_t, 3> v;
};

// In the caller's tet order: the surface grows in this order, which decides
// where each one-ring starts, and sums over rings must not depend on the
// internal order.
std::vector<OrientedFace> region_faces(const TetMesh& mesh, int32_t region) {
    std::vector<std::pair<int64_t, OrientedFace>> keyed;  // 4 * caller's tet + face
    for (int32_t t = 0; t < mesh.num_tets(); ++t) {
        if (mesh.regions[t] != region) continue;
        for (int i = 0; i < 4; ++i) {
            if (mesh.is_region_boundary_face(t, i))
                keyed.push_back({4 * static_cast<int64_t>(mesh.caller_tet(t)) + i, {mesh.outward_face(t, i)}});
        }
    }
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<OrientedFace> faces;
    faces.reserve(keyed.size());
    for (const auto& k : keyed) faces.push_back(k.second);
    return faces;
}

// The link of a boundary vertex v is the set of directed edges (a -> b), one
// for each boundary face (v, a, b).  The boundary is a manifold surface at v
// exactly when these edges form a single cycle.
void check_link(int32_t v, std::vector<std::pair<int32_t, int32_t>>& link, int base) {
    const auto name = [base](int32_t x) { return std::to_string(x + base); };
    std::sort(link.begin(), link.end());
    for (size_t k = 1; k < link.size(); ++k)
        if (link[k].first == link[k - 1].first)
            throw Error(BODT_ERR_BAD_MESH, "the boundary is not a manifold surface at edge (" + name(v) + ", " +
                                               name(link[k].first) + "): more than two boundary faces meet there");
    // Follow the cycle from the first edge; it must come back after visiting all.
    size_t steps = 0;
    int32_t at = link[0].first;
    do {
        const auto it = std::lower_bound(link.begin(), link.end(), std::make_pair(at, INT32_MIN));
        if (it == link.end() || it->first != at)
            throw Error(BODT_ERR_BAD_MESH, "the boundary is not a closed manifold surface around vertex " + name(v));
        at = it->second;
        ++steps;
    } while (at != link[0].first && steps <= link.size());
    if (steps != link.size())
        throw Error(BODT_ERR_BAD_MESH, "the boundary is not a manifold surface at vertex " + name(v) +
                                           ": its boundary faces form more than one fan (the domain touches "
                                           "itself there)");
}

}  // namespace

int32_t BoundarySurface::surface_vertex(int32_t v) const {
    const auto it = std::lower_bound(to_tet_.begin(), to_tet_.end(), v);
    return it != to_tet_.end() && *it == v ? static_cast<int32_t>(it - to_tet_.begin()) : -1;
}

void BoundarySurface::build(const TetMesh& mesh, int base, int32_t region, Strictness strictness) {
    const auto faces = region_faces(mesh, region);
    const int32_t nf = static_cast<int32_t>(faces.size());
    const int32_t nv = mesh.num_vertices();
    const bool strict = strictness == Strictness::Strict;

    // Vertex -> faces, for the link check and for the growth order.
    std::vector<int32_t> offset(static_cast<size_t>(nv) + 1, 0), incident;
    for (const auto& f : faces)
        for (int32_t v : f.v) ++offset[v + 1];
    for (int32_t v = 0; v < nv; ++v) offset[v + 1] += offset[v];
    incident.resize(faces.size() * 3);
    {
        std::vector<int32_t> fill(offset.begin(), offset.end() - 1);
        for (int32_t f = 0; f < nf; ++f)
            for (int32_t v : faces[f].v) incident[fill[v]++] = f;
    }
    // Where the surface is not a manifold: refuse, or (tolerant) leave out
    // every face around that vertex.
    std::vector<char> dropped(faces.size(), 0);
    std::vector<std::pair<int32_t, int32_t>> link;
    for (int32_t v = 0; v < nv; ++v) {
        if (offset[v] == offset[v + 1]) continue;
        link.clear();
        for (int32_t k = offset[v]; k < offset[v + 1]; ++k) {
            const auto& f = faces[incident[k]].v;
            const int r = f[0] == v ? 0 : (f[1] == v ? 1 : 2);
            link.emplace_back(f[(r + 1) % 3], f[(r + 2) % 3]);
        }
        try {
            check_link(v, link, base);
        } catch (const Error&) {
            if (strict) throw;
            for (int32_t k = offset[v]; k < offset[v + 1]; ++k) dropped[incident[k]] = 1;
        }
    }

    surface_.clean();
    to_tet_.clear();
    blocked_.clear();
    for (int32_t v = 0; v < nv; ++v)
        if (offset[v] != offset[v + 1]) {
            surface_.add_vertex(SurfaceMesh::Point(0, 0, 0));
            to_tet_.push_back(v);
        }

    // Add faces breadth-first across shared vertices, so each vertex's fan
    // grows from one side and OpenMesh never has to re-link patches.
    std::vector<char> queued(faces.size(), 0);
    std::vector<int32_t> queue;
    for (int32_t seed = 0; seed < nf; ++seed) {
        if (queued[seed]) continue;
        queued[seed] = 1;
        queue.assign(1, seed);
        for (size_t head = 0; head < queue.size(); ++head) {
            const int32_t face = queue[head];
            const auto& f = faces[face].v;
            if (!dropped[face]) {
                const auto fh = surface_.add_face(SurfaceMesh::VertexHandle(surface_vertex(f[0])),
                                                  SurfaceMesh::VertexHandle(surface_vertex(f[1])),
                                                  SurfaceMesh::VertexHandle(surface_vertex(f[2])));
                if (!fh.is_valid()) {
                    if (strict)
                        throw Error(BODT_ERR_BAD_MESH, "the boundary face (" + std::to_string(f[0] + base) + ", " +
                                                           std::to_string(f[1] + base) + ", " +
                                                           std::to_string(f[2] + base) +
                                                           ") does not fit a manifold boundary surface");
                    dropped[face] = 1;
                }
            }
            for (int32_t v : f)
                for (int32_t k = offset[v]; k < offset[v + 1]; ++k)
                    if (!queued[incident[k]]) {
                        queued[incident[k]] = 1;
                        queue.push_back(incident[k]);
                    }
        }
    }
    // A vertex of a left-out face has an open ring.
    for (int32_t f = 0; f < nf; ++f)
        if (dropped[f]) blocked_.insert(blocked_.end(), faces[f].v.begin(), faces[f].v.end());
    std::sort(blocked_.begin(), blocked_.end());
    blocked_.erase(std::unique(blocked_.begin(), blocked_.end()), blocked_.end());
}

void BoundarySurface::one_ring(int32_t v, std::vector<int32_t>& ring) const {
    ring.clear();
    const int32_t sv = surface_vertex(v);
    if (sv < 0) return;
    const SurfaceMesh::VertexHandle vh(sv);
    // For the outgoing halfedge h = (v -> y_i) of face (v, y_i, y_{i+1}), the
    // next outgoing halfedge (v -> y_{i+1}) is opposite(prev(h)).
    const auto start = surface_.halfedge_handle(vh);
    if (!start.is_valid()) return;  // a Tolerant build left out every face around v
    auto h = start;
    do {
        ring.push_back(to_tet_[surface_.to_vertex_handle(h).idx()]);
        h = surface_.opposite_halfedge_handle(surface_.prev_halfedge_handle(h));
    } while (h != start && ring.size() <= surface_.n_vertices());
}

}  // namespace bodt
