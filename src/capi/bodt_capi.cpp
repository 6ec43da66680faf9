// The C API: thin wrappers that check arguments, call the core, and turn
// every exception into a status code and a message.  Nothing here throws.
#include "capi/handle.hpp"

#include "common/error.hpp"
#include "io/mesh_io.hpp"
#include "mesh/mesh_builder.hpp"
#include "pipeline/improver.hpp"
#include "quality/mesh_quality.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

using namespace bodt_capi;

namespace {

bodt_mesh* make_handle(const bodt::MeshArrays& arrays) {
    bodt::BuiltMesh built = (arrays.flags & BODT_CREATE_KEEP_ORDER) ? bodt::build_mesh(arrays)
                                                                     : bodt::build_mesh_in_curve_order(arrays);
    auto* h = new bodt_mesh;
    h->mesh = std::move(built.mesh);
    h->surfaces = std::move(built.surfaces);
    h->index_base = arrays.index_base;
    h->flipped = built.flipped;
    return h;
}

// True when some tet has the three vertices of `k`.
bool is_mesh_face(const bodt::TetMesh& mesh, const bodt::FaceKey& k) {
    for (const int32_t* t = mesh.star_begin(k.v[0]); t != mesh.star_end(k.v[0]); ++t) {
        const bodt::Tet& q = mesh.tets[*t];
        if (bodt::holds(q, k.v[1]) && bodt::holds(q, k.v[2])) return true;
    }
    return false;
}

// New region ids: the region surfaces are rebuilt first, so a failure leaves
// everything as it was.
void apply_regions(bodt_mesh* h, const int32_t* region_ids) {
    require(region_ids != nullptr, "region_ids is NULL");
    std::vector<int32_t> old(h->mesh.tets.size());
    for (int32_t t = 0; t < h->mesh.num_tets(); ++t) old[t] = region_ids[h->mesh.caller_tet(t)];
    h->mesh.regions.swap(old);
    bodt::RegionSurfaces surfaces;
    try {
        surfaces.build(h->mesh, h->index_base, bodt::BoundarySurface::Strictness::Tolerant);
    } catch (...) {
        h->mesh.regions.swap(old);
        throw;
    }
    h->surfaces = std::move(surfaces);
    h->mesh.update_vertex_flags();
    h->improver.mesh_data_changed();
}

// True when some boundary or interface face has the edge (a, b).
bool is_surface_edge(const bodt::TetMesh& mesh, int32_t a, int32_t b) {
    for (const int32_t* t = mesh.star_begin(a); t != mesh.star_end(a); ++t) {
        const bodt::Tet& q = mesh.tets[*t];
        for (int i = 0; i < 4; ++i) {
            if (q[i] == a || q[i] == b || !mesh.is_surface_face(*t, i)) continue;
            if (bodt::holds(q, b)) return true;
        }
    }
    return false;
}

void apply_feature_edges(bodt_mesh* h, int32_t nedges, const int32_t* edges, const int32_t* refs) {
    require(nedges >= 0, "nedges must not be negative");
    require(nedges == 0 || edges != nullptr, "edges is NULL");
    const bodt::TetMesh& mesh = h->mesh;
    const int base = h->index_base;
    bodt::EdgeRefs fresh;
    for (int32_t e = 0; e < nedges; ++e) {
        int32_t c[2], v[2];  // the caller's indices (for messages) and the internal ones
        for (int k = 0; k < 2; ++k) {
            c[k] = edges[2 * static_cast<size_t>(e) + k];
            bodt::check_vertex_index(c[k], mesh.num_vertices(), base, "feature edge", e);
            v[k] = mesh.internal_vertex(c[k] - base);
        }
        if (v[0] == v[1] || !is_surface_edge(mesh, v[0], v[1]))
            throw Error(BODT_ERR_INVALID_ARGUMENT, "feature edge " + std::to_string(e + base) + " (" +
                                                       std::to_string(c[0]) + ", " + std::to_string(c[1]) +
                                                       ") is not an edge of a boundary or interface face");
        const int32_t ref = refs ? refs[e] : 0;
        const auto [it, added] = fresh.emplace(bodt::edge_key(v[0], v[1]), ref);
        if (!added && it->second != ref)
            throw Error(BODT_ERR_INVALID_ARGUMENT, "feature edge " + std::to_string(e + base) + " (" +
                                                       std::to_string(c[0]) + ", " + std::to_string(c[1]) +
                                                       ") is listed before with ref " +
                                                       std::to_string(it->second) + ", now with " +
                                                       std::to_string(ref));
    }
    h->mesh.feature_edges = std::move(fresh);
    h->improver.mesh_data_changed();
}

// The caller's feature edges with their refs, by the caller's vertex
// indices (0-based), sorted by edge.
std::vector<std::pair<bodt::EdgeKey, int32_t>> sorted_feature_edges(const bodt::TetMesh& mesh) {
    std::vector<std::pair<bodt::EdgeKey, int32_t>> edges;
    edges.reserve(mesh.feature_edges.size());
    for (const auto& [k, ref] : mesh.feature_edges)
        edges.push_back(
            {bodt::edge_key(mesh.caller_vertex(bodt::edge_first(k)), mesh.caller_vertex(bodt::edge_second(k))), ref});
    std::sort(edges.begin(), edges.end());
    return edges;
}

void apply_face_markers(bodt_mesh* h, int32_t nfaces, const int32_t* triangles, const int32_t* markers) {
    require(nfaces >= 0, "nfaces must not be negative");
    require(nfaces == 0 || triangles != nullptr, "triangles is NULL");
    const bodt::TetMesh& mesh = h->mesh;
    const int base = h->index_base;
    decltype(h->mesh.face_markers) fresh;
    for (int32_t f = 0; f < nfaces; ++f) {
        int32_t c[3], v[3];  // the caller's indices (for messages) and the internal ones
        for (int k = 0; k < 3; ++k) {
            c[k] = triangles[3 * static_cast<size_t>(f) + k];
            bodt::check_vertex_index(c[k], mesh.num_vertices(), base, "triangle", f);
            v[k] = mesh.internal_vertex(c[k] - base);
        }
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2])
            throw Error(BODT_ERR_INVALID_ARGUMENT, "triangle " + std::to_string(f + base) + " repeats a vertex");
        const auto key = bodt::FaceKey::of(v[0], v[1], v[2]);
        if (!is_mesh_face(mesh, key))
            throw Error(BODT_ERR_INVALID_ARGUMENT, "triangle " + std::to_string(f + base) + " (" +
                                                       std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
                                                       std::to_string(c[2]) + ") is not a face of the mesh");
        if (!fresh.emplace(key, markers ? markers[f] : 1).second)
            throw Error(BODT_ERR_INVALID_ARGUMENT, "triangle " + std::to_string(f + base) + " is listed twice");
    }
    h->mesh.face_markers = std::move(fresh);
    h->mesh.update_vertex_flags();
    h->improver.mesh_data_changed();
}

// Sets `flag` (kFixed or kCorner) on the listed vertices only.
void apply_vertex_flag(bodt_mesh* h, int32_t n, const int32_t* vertices, bodt::VertexFlag flag, const char* count,
                       const char* what) {
    if (n < 0) throw Error(BODT_ERR_INVALID_ARGUMENT, std::string(count) + " must not be negative");
    require(n == 0 || vertices != nullptr, "vertices is NULL");
    bodt::TetMesh& mesh = h->mesh;
    for (int32_t k = 0; k < n; ++k) bodt::check_vertex_index(vertices[k], mesh.num_vertices(), h->index_base, what, k);
    for (uint8_t& f : mesh.vflags) f &= static_cast<uint8_t>(~flag);
    for (int32_t k = 0; k < n; ++k) mesh.vflags[mesh.internal_vertex(vertices[k] - h->index_base)] |= flag;
    h->improver.mesh_data_changed();
}

void apply_fixed(bodt_mesh* h, int32_t nfixed, const int32_t* vertices) {
    apply_vertex_flag(h, nfixed, vertices, bodt::kFixed, "nfixed", "fixed vertex");
}

void apply_corners(bodt_mesh* h, int32_t ncorners, const int32_t* vertices) {
    apply_vertex_flag(h, ncorners, vertices, bodt::kCorner, "ncorners", "corner");
}

// Refs are the input vertices': a handle's vertices are all input vertices
// until an operation makes new ones, whose refs then come from their parents.
void apply_vertex_refs(bodt_mesh* h, const int32_t* refs) {
    require(refs != nullptr, "refs is NULL");
    bodt::TetMesh& mesh = h->mesh;
    if (!mesh.new_parents.empty())
        throw Error(BODT_ERR_WRONG_STATE,
                    "vertex refs can be set only before a step made vertices (theirs follow from their parents)");
    mesh.input_vertex_refs.resize(mesh.points.size());
    for (int32_t v = 0; v < mesh.num_vertices(); ++v) mesh.input_vertex_refs[v] = refs[mesh.caller_vertex(v)];
}

void get_vertex_flag(const bodt_mesh* h, int32_t* out, size_t capacity, bodt::VertexFlag flag, const char* what) {
    if (!out) throw Error(BODT_ERR_INVALID_ARGUMENT, std::string(what) + " is NULL");
    const bodt::TetMesh& mesh = h->mesh;
    require_capacity(capacity, mesh.vflags.size(), what);
    for (int32_t v = 0; v < mesh.num_vertices(); ++v) out[mesh.caller_vertex(v)] = (mesh.vflags[v] & flag) ? 1 : 0;
}

void fill_step_report(const bodt::StepReport& r, bodt_step_report* out) {
    bodt_step_report full{};
    full.size = sizeof(full);
    full.step = r.step;
    full.vertices_moved = r.vertices_moved;
    full.moves_rejected = r.moves_rejected;
    full.moves_shortened = r.moves_shortened;
    full.not_positive_definite = r.not_positive_definite;
    full.max_move = r.max_move;
    full.min_dihedral = r.min_dihedral;
    full.max_dihedral = r.max_dihedral;
    full.min_stretch = r.min_stretch;
    full.flips = r.flips;
    full.vertices_inserted = r.vertices_inserted;
    full.edges_collapsed = r.edges_collapsed;
    fill_sized(out, full);
}

// The number of parent entries of all vertices: one for each input vertex
// (itself), those of each made vertex.
size_t parent_count(const bodt::TetMesh& m) {
    size_t n = static_cast<size_t>(m.num_input_vertices());
    for (const bodt::Parents& p : m.new_parents) n += p.size();
    return n;
}

// The parents of every vertex by the caller's indices, counted from `base`:
// vertex c stands for parents[offsets[c] .. offsets[c + 1]) with those
// weights, an input vertex for itself with weight 1.  `offsets` holds
// num_vertices() + 1 entries, `parents` and `weights` parent_count() each.
void caller_parents(const bodt::TetMesh& m, int base, int64_t* offsets, int32_t* parents, double* weights) {
    const int32_t input = m.num_input_vertices();
    size_t k = 0;
    for (int32_t c = 0; c < m.num_vertices(); ++c) {  // by the caller's index: made vertices are the last
        offsets[c] = static_cast<int64_t>(k);
        if (c < input) {
            parents[k] = c + base;
            weights[k++] = 1.0;
            continue;
        }
        for (const bodt::Parent& p : m.new_parents[static_cast<size_t>(c - input)]) {
            parents[k] = m.caller_vertex(p.vertex) + base;
            weights[k++] = p.weight;
        }
    }
    offsets[m.num_vertices()] = static_cast<int64_t>(k);
}

// The input tet each tet came from, by the caller's indices, from `base`.
void caller_tet_origins(const bodt::TetMesh& m, int base, int32_t* origins) {
    for (int32_t t = 0; t < m.num_tets(); ++t) origins[m.caller_tet(t)] = m.caller_origin(t) + base;
}

// For a .msh: the Gmsh model of the file the mesh was read from, with what
// the Gmsh writer needs to put the elements back into its entities, the
// parents of the vertices and the input tet of each tet (from 0).  Only
// Gmsh writes take it: the other formats have no place for it.
void add_gmsh_model(const bodt_mesh* h, bodt::MeshData& d) {
    const bodt::TetMesh& mesh = h->mesh;
    d.gmsh = h->gmsh_model;
    bodt::MeshData::Origins& o = d.origins;
    o.input_vertices = mesh.num_input_vertices();
    o.parent_offsets.resize(mesh.points.size() + 1);
    o.parents.resize(parent_count(mesh));
    o.weights.resize(o.parents.size());
    caller_parents(mesh, 0, o.parent_offsets.data(), o.parents.data(), o.weights.data());
    o.tet_origins.resize(mesh.tets.size());
    caller_tet_origins(mesh, 0, o.tet_origins.data());
}

// The mesh as the caller numbers it, for a file.
bodt::MeshData to_mesh_data(const bodt_mesh* h) {
    const bodt::TetMesh& mesh = h->mesh;
    bodt::MeshData d;
    d.xyz.resize(mesh.points.size() * 3);
    to_caller_xyz(mesh, d.xyz.data());
    d.tets.resize(mesh.tets.size() * 4);
    to_caller_corners(mesh, false, 0, d.tets.data());  // files hold the positive orientation, 0-based
    d.regions.resize(mesh.regions.size());
    to_caller_tets(mesh, mesh.regions, d.regions.data());
    for (const bodt::SurfaceFace& f : mesh.surface_faces()) {
        for (const int32_t v : f.v) d.triangles.push_back(mesh.caller_vertex(v));
        d.tri_markers.push_back(f.marker);
    }
    for (int32_t c = 0; c < mesh.num_vertices(); ++c) {
        const uint8_t flags = mesh.vflags[mesh.internal_vertex(c)];
        if (flags & bodt::kFixed) d.fixed.push_back(c);
        if (flags & bodt::kCorner) d.corners.push_back(c);
    }
    for (const auto& [k, ref] : sorted_feature_edges(mesh)) {
        d.feature_edges.insert(d.feature_edges.end(), {bodt::edge_first(k), bodt::edge_second(k)});
        d.edge_refs.push_back(ref);
    }
    if (!mesh.input_vertex_refs.empty()) {
        d.vertex_refs.resize(mesh.points.size());
        to_caller_vertices(mesh, mesh.vertex_refs(), d.vertex_refs.data());
    }
    return d;
}

// Per-tet quality as cell data, for viewers (ParaView colours and thresholds
// by it).
void add_quality_fields(const bodt::TetMesh& mesh, bodt::MeshData& data) {
    const std::pair<const char*, bodt::TetMeasure> fields[] = {
        {"min_dihedral", bodt::TetMeasure::MinDihedral},
        {"max_dihedral", bodt::TetMeasure::MaxDihedral},
        {"stretch", bodt::TetMeasure::Stretch},
        {"volume", bodt::TetMeasure::Volume}};
    std::vector<double> values;
    for (const auto& [name, measure] : fields) {
        bodt::tet_measures(mesh, measure, values);
        data.tet_fields.push_back({name, std::vector<double>(values.size())});
        to_caller_tets(mesh, values, data.tet_fields.back().values.data());
    }
}

// The flags bodt_mesh_read_ex() takes, checked before the file is read.
void check_read_flags(uint32_t flags) {
    const uint32_t known = BODT_CREATE_ACCEPT_INVERTED | BODT_CREATE_ONE_BASED | BODT_CREATE_KEEP_ORDER |
                           BODT_CREATE_FILE_BASE;
    require(!(flags & ~known), "unknown flag bits");
    require(!((flags & BODT_CREATE_ONE_BASED) && (flags & BODT_CREATE_FILE_BASE)),
            "BODT_CREATE_ONE_BASED and BODT_CREATE_FILE_BASE exclude each other");
}

// Every vertex index of `d` moved from d.base to `base`.
void rebase(bodt::MeshData& d, int base) {
    const int32_t shift = base - d.base;
    for (std::vector<int32_t>* a : {&d.tets, &d.triangles, &d.fixed, &d.corners, &d.feature_edges})
        for (int32_t& v : *a) v += shift;
    d.base = base;
}

// A handle for a mesh read from a file, counting from 0, from 1 with
// BODT_CREATE_ONE_BASED, or as the file does with BODT_CREATE_FILE_BASE.
// Problems with the mesh itself are BODT_ERR_BAD_MESH, named in that base,
// which the message states (and the file's, when it differs).
bodt_mesh* from_mesh_data(bodt::MeshData&& d, uint32_t flags) {
    const int file_base = d.base;
    const int handle_base = (flags & BODT_CREATE_FILE_BASE)  ? file_base
                            : (flags & BODT_CREATE_ONE_BASED) ? 1
                                                              : 0;
    flags &= ~static_cast<uint32_t>(BODT_CREATE_ONE_BASED | BODT_CREATE_FILE_BASE);
    rebase(d, handle_base);
    if (d.xyz.size() / 3 > INT32_MAX || d.tets.size() / 4 > INT32_MAX)
        throw Error(BODT_ERR_UNSUPPORTED, "the mesh has more than 2^31 - 1 vertices or tets");
    if (d.tets.empty()) throw Error(BODT_ERR_BAD_MESH, "the file has no tets");
    bodt::MeshArrays arrays;
    arrays.nverts = static_cast<int32_t>(d.xyz.size() / 3);
    arrays.xyz = d.xyz.data();
    arrays.ntets = static_cast<int32_t>(d.tets.size() / 4);
    arrays.tets = d.tets.data();
    arrays.index_base = d.base;
    arrays.flags = flags;
    try {
        std::unique_ptr<bodt_mesh> h(make_handle(arrays));
        if (!d.regions.empty()) apply_regions(h.get(), d.regions.data());
        apply_face_markers(h.get(), static_cast<int32_t>(d.tri_markers.size()), d.triangles.data(),
                           d.tri_markers.data());
        apply_fixed(h.get(), static_cast<int32_t>(d.fixed.size()), d.fixed.data());
        apply_corners(h.get(), static_cast<int32_t>(d.corners.size()), d.corners.data());
        apply_feature_edges(h.get(), static_cast<int32_t>(d.feature_edges.size() / 2), d.feature_edges.data(),
                            d.edge_refs.empty() ? nullptr : d.edge_refs.data());
        if (!d.vertex_refs.empty()) apply_vertex_refs(h.get(), d.vertex_refs.data());
        h->gmsh_model = std::move(d.gmsh);
        return h.release();
    } catch (const Error& e) {
        if (e.status() != BODT_ERR_INVALID_ARGUMENT && e.status() != BODT_ERR_BAD_MESH) throw;
        // "(numbered from H)", which some messages carry already, with the
        // file's base when it differs.
        std::string message = e.what();
        const std::string said = "(numbered from " + std::to_string(handle_base) + ")";
        std::string note = said;
        if (file_base != handle_base) note.insert(note.size() - 1, "; the file numbers from " + std::to_string(file_base));
        const size_t at = message.find(said);
        if (at != std::string::npos) message.replace(at, said.size(), note);
        else message += " " + note;
        throw Error(BODT_ERR_BAD_MESH, message);
    }
}

}  // namespace

extern "C" {

#define BODT_STR2(x) #x
#define BODT_STR(x) BODT_STR2(x)
const char* bodt_version_string(void) {
    return BODT_STR(BODT_VERSION_MAJOR) "." BODT_STR(BODT_VERSION_MINOR) "." BODT_STR(BODT_VERSION_PATCH);
}

int bodt_version_number(void) { return BODT_VERSION_NUMBER; }

const char* bodt_status_string(int status) {
    switch (status) {
        case BODT_OK: return "ok";
        case BODT_ERR_INVALID_ARGUMENT: return "invalid argument";
        case BODT_ERR_BAD_MESH: return "bad mesh";
        case BODT_ERR_OUT_OF_MEMORY: return "out of memory";
        case BODT_ERR_WRONG_STATE: return "wrong state";
        case BODT_ERR_NUMERIC: return "numeric failure";
        case BODT_ERR_IO: return "input/output error";
        case BODT_ERR_CANCELLED: return "cancelled";
        case BODT_ERR_UNSUPPORTED: return "unsupported";
        default: return "unknown status";
    }
}

int bodt_mesh_create(int32_t nverts, const double* xyz, int32_t ntets, const int32_t* tets, int index_base,
                     bodt_mesh** mesh) {
    return bodt_mesh_create_ex(nverts, xyz, ntets, tets, index_base, BODT_CREATE_DEFAULT, mesh);
}

int bodt_mesh_create_ex(int32_t nverts, const double* xyz, int32_t ntets, const int32_t* tets, int index_base,
                        uint32_t flags, bodt_mesh** mesh) {
    if (!mesh) {
        t_thread_error = "mesh (the output pointer) is NULL";
        return BODT_ERR_INVALID_ARGUMENT;
    }
    *mesh = nullptr;
    bodt_mesh* created = nullptr;
    const int status = guarded(nullptr, [&] {
        require(!(flags & BODT_CREATE_ONE_BASED),
                "BODT_CREATE_ONE_BASED is for bodt_mesh_read_ex; bodt_mesh_create_ex takes index_base");
        bodt::MeshArrays arrays;
        arrays.nverts = nverts;
        arrays.xyz = xyz;
        arrays.ntets = ntets;
        arrays.tets = tets;
        arrays.index_base = index_base;
        arrays.flags = flags;
        created = make_handle(arrays);
    });
    *mesh = created;
    return status;
}

void bodt_mesh_destroy(bodt_mesh* mesh) { delete mesh; }

const char* bodt_mesh_last_error(const bodt_mesh* mesh) { return error_slot(mesh).c_str(); }

int bodt_mesh_set_regions(bodt_mesh* mesh, const int32_t* region_ids) {
    return with_mesh(mesh, [&] { apply_regions(mesh, region_ids); });
}

int bodt_mesh_set_feature_edges(bodt_mesh* mesh, int32_t nedges, const int32_t* edges) {
    return with_mesh(mesh, [&] { apply_feature_edges(mesh, nedges, edges, nullptr); });
}

int bodt_mesh_set_feature_edges_ex(bodt_mesh* mesh, int32_t nedges, const int32_t* edges, const int32_t* refs) {
    return with_mesh(mesh, [&] { apply_feature_edges(mesh, nedges, edges, refs); });
}

int bodt_mesh_set_corners(bodt_mesh* mesh, int32_t ncorners, const int32_t* vertices) {
    return with_mesh(mesh, [&] { apply_corners(mesh, ncorners, vertices); });
}

int bodt_mesh_set_vertex_refs(bodt_mesh* mesh, const int32_t* refs) {
    return with_mesh(mesh, [&] { apply_vertex_refs(mesh, refs); });
}

int bodt_mesh_set_boundary_faces(bodt_mesh* mesh, int32_t nfaces, const int32_t* triangles, const int32_t* markers) {
    return with_mesh(mesh, [&] { apply_face_markers(mesh, nfaces, triangles, markers); });
}

int bodt_mesh_set_fixed_vertices(bodt_mesh* mesh, int32_t nfixed, const int32_t* vertices) {
    return with_mesh(mesh, [&] { apply_fixed(mesh, nfixed, vertices); });
}

int bodt_mesh_get_counts(const bodt_mesh* mesh, int32_t* nverts, int32_t* ntets, int32_t* nboundary_faces) {
    return with_mesh(mesh, [&] {
        if (nverts) *nverts = mesh->mesh.num_vertices();
        if (ntets) *ntets = mesh->mesh.num_tets();
        if (nboundary_faces) *nboundary_faces = mesh->mesh.count_surface_faces();
    });
}

int bodt_mesh_get_vertices(const bodt_mesh* mesh, double* xyz, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(xyz != nullptr, "xyz is NULL");
        require_capacity(capacity, 3 * mesh->mesh.points.size(), "xyz");
        to_caller_xyz(mesh->mesh, xyz);
    });
}

int bodt_mesh_get_tets(const bodt_mesh* mesh, int32_t* tets, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(tets != nullptr, "tets is NULL");
        require_capacity(capacity, 4 * mesh->mesh.tets.size(), "tets");
        to_caller_corners(mesh->mesh, mesh->flipped, mesh->index_base, tets);
    });
}

int bodt_mesh_get_regions(const bodt_mesh* mesh, int32_t* region_ids, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(region_ids != nullptr, "region_ids is NULL");
        const auto& r = mesh->mesh.regions;
        require_capacity(capacity, r.size(), "region_ids");
        to_caller_tets(mesh->mesh, r, region_ids);
    });
}

int bodt_mesh_get_boundary_faces(const bodt_mesh* mesh, int32_t* triangles, int32_t* markers, size_t capacity) {
    return with_mesh(mesh, [&] {
        const auto faces = mesh->mesh.surface_faces();
        require_capacity(capacity, faces.size(), "boundary faces");
        for (size_t f = 0; f < faces.size(); ++f) {
            if (triangles)
                for (int k = 0; k < 3; ++k)
                    triangles[3 * f + k] = mesh->mesh.caller_vertex(faces[f].v[k]) + mesh->index_base;
            if (markers) markers[f] = faces[f].marker;
        }
    });
}

int bodt_mesh_get_fixed_vertices(const bodt_mesh* mesh, int32_t* is_fixed, size_t capacity) {
    return with_mesh(mesh, [&] { get_vertex_flag(mesh, is_fixed, capacity, bodt::kFixed, "is_fixed"); });
}

int bodt_mesh_get_corners(const bodt_mesh* mesh, int32_t* is_corner, size_t capacity) {
    return with_mesh(mesh, [&] { get_vertex_flag(mesh, is_corner, capacity, bodt::kCorner, "is_corner"); });
}

int bodt_mesh_get_vertex_refs(const bodt_mesh* mesh, int32_t* refs, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(refs != nullptr, "refs is NULL");
        require_capacity(capacity, mesh->mesh.points.size(), "refs");
        to_caller_vertices(mesh->mesh, mesh->mesh.vertex_refs(), refs);
    });
}

int bodt_mesh_get_feature_edges(const bodt_mesh* mesh, int32_t* nedges, int32_t* edges, size_t capacity) {
    return bodt_mesh_get_feature_edges_ex(mesh, nedges, edges, nullptr, capacity);
}

int bodt_mesh_get_feature_edges_ex(const bodt_mesh* mesh, int32_t* nedges, int32_t* edges, int32_t* refs,
                                   size_t capacity) {
    return with_mesh(mesh, [&] {
        const auto all = sorted_feature_edges(mesh->mesh);
        if (edges || refs) require_capacity(capacity, all.size(), "feature edges");
        for (size_t e = 0; e < all.size(); ++e) {
            if (edges) {
                edges[2 * e] = bodt::edge_first(all[e].first) + mesh->index_base;
                edges[2 * e + 1] = bodt::edge_second(all[e].first) + mesh->index_base;
            }
            if (refs) refs[e] = all[e].second;
        }
        if (nedges) *nedges = static_cast<int32_t>(all.size());
    });
}

int bodt_mesh_get_index_base(const bodt_mesh* mesh, int* index_base) {
    return with_mesh(mesh, [&] {
        require(index_base != nullptr, "index_base is NULL");
        *index_base = mesh->index_base;
    });
}

int bodt_mesh_get_vertex_classes(const bodt_mesh* mesh, int32_t* classes, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(classes != nullptr, "classes is NULL");
        require_capacity(capacity, mesh->mesh.points.size(), "classes");
        const bodt::VertexClasses& c = mesh->improver.classes(mesh->mesh, mesh->surfaces);
        for (int32_t v = 0; v < mesh->mesh.num_vertices(); ++v)
            classes[mesh->mesh.caller_vertex(v)] = static_cast<int32_t>(c.cls[v]);
    });
}

int bodt_mesh_get_parent_count(const bodt_mesh* mesh, int64_t* count) {
    return with_mesh(mesh, [&] {
        require(count != nullptr, "count is NULL");
        *count = static_cast<int64_t>(parent_count(mesh->mesh));
    });
}

int bodt_mesh_get_vertex_parents(const bodt_mesh* mesh, int64_t* offsets, size_t offsets_capacity, int32_t* parents,
                                 double* weights, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(offsets != nullptr && parents != nullptr && weights != nullptr, "offsets, parents or weights is NULL");
        const bodt::TetMesh& m = mesh->mesh;
        require_capacity(offsets_capacity, m.points.size() + 1, "offsets");
        require_capacity(capacity, parent_count(m), "parents");
        caller_parents(m, mesh->index_base, offsets, parents, weights);
    });
}

int bodt_mesh_get_tet_origins(const bodt_mesh* mesh, int32_t* origins, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(origins != nullptr, "origins is NULL");
        require_capacity(capacity, mesh->mesh.tets.size(), "origins");
        caller_tet_origins(mesh->mesh, mesh->index_base, origins);
    });
}

int bodt_dihedral_bin_edges(double* edges, size_t capacity) {
    if (!edges || capacity < bodt::kDihedralBins + 1) return BODT_ERR_INVALID_ARGUMENT;
    std::copy(std::begin(bodt::kDihedralBinEdges), std::end(bodt::kDihedralBinEdges), edges);
    return BODT_OK;
}

int bodt_mesh_quality(const bodt_mesh* mesh, bodt_quality* quality) {
    return with_mesh(mesh, [&] {
        require(quality != nullptr, "quality is NULL");
        const bodt::QualitySummary s = bodt::summarize_quality(mesh->mesh);
        bodt_quality full{};
        full.size = sizeof(full);
        full.num_vertices = mesh->mesh.num_vertices();
        full.num_tets = mesh->mesh.num_tets();
        full.num_boundary_faces = mesh->mesh.count_surface_faces();
        full.num_unused_vertices = s.num_unused_vertices;
        full.num_inverted = s.num_inverted;
        full.min_dihedral = s.min_dihedral;
        full.max_dihedral = s.max_dihedral;
        full.mean_dihedral = s.mean_dihedral;
        full.min_stretch = s.min_stretch;
        full.mean_stretch = s.mean_stretch;
        full.volume = s.volume;
        std::copy(s.histogram.begin(), s.histogram.end(), full.dihedral_histogram);
        fill_sized(quality, full);
    });
}

int bodt_mesh_tet_quality(const bodt_mesh* mesh, int measure, double* values, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(values != nullptr, "values is NULL");
        require_capacity(capacity, mesh->mesh.tets.size(), "values");
        bodt::TetMeasure m;
        switch (measure) {
            case BODT_MEASURE_MIN_DIHEDRAL: m = bodt::TetMeasure::MinDihedral; break;
            case BODT_MEASURE_MAX_DIHEDRAL: m = bodt::TetMeasure::MaxDihedral; break;
            case BODT_MEASURE_STRETCH: m = bodt::TetMeasure::Stretch; break;
            case BODT_MEASURE_VOLUME: m = bodt::TetMeasure::Volume; break;
            default: throw Error(BODT_ERR_INVALID_ARGUMENT, "unknown measure " + std::to_string(measure));
        }
        std::vector<double> out;
        bodt::tet_measures(mesh->mesh, m, out);
        to_caller_tets(mesh->mesh, out, values);
    });
}

int bodt_set_mode(bodt_mesh* mesh, int mode) {
    return with_mesh(mesh, [&] { mesh->improver.set_mode(mode); });
}

int bodt_get_mode(const bodt_mesh* mesh, int* mode) {
    return with_mesh(mesh, [&] {
        require(mode != nullptr, "mode is NULL");
        *mode = mesh->improver.mode();
    });
}

int bodt_set_param_int(bodt_mesh* mesh, int key, int32_t value) {
    return with_mesh(mesh, [&] { mesh->improver.set_param_int(key, value); });
}

int bodt_set_param_double(bodt_mesh* mesh, int key, double value) {
    return with_mesh(mesh, [&] { mesh->improver.set_param_double(key, value); });
}

int bodt_get_param_int(const bodt_mesh* mesh, int key, int32_t* value) {
    return with_mesh(mesh, [&] {
        require(value != nullptr, "value is NULL");
        *value = bodt::get_param_int(mesh->improver.params(), key);
    });
}

int bodt_get_param_double(const bodt_mesh* mesh, int key, double* value) {
    return with_mesh(mesh, [&] {
        require(value != nullptr, "value is NULL");
        *value = bodt::get_param_double(mesh->improver.params(), key);
    });
}

int bodt_step(bodt_mesh* mesh, bodt_step_report* report) {
    return with_mesh(mesh, [&] {
        if (report) require(report->size >= sizeof(size_t), "set report->size to sizeof(bodt_step_report)");
        const bodt::StepReport r = mesh->improver.step(mesh->mesh, mesh->surfaces);
        if (report) fill_step_report(r, report);
    });
}

int bodt_run(bodt_mesh* mesh, int32_t max_steps, bodt_step_callback callback, void* user_data) {
    return with_mesh(mesh, [&] {
        require(max_steps > 0, "max_steps must be positive");
        const double scale = mesh->mesh.bbox_diagonal();
        for (int32_t k = 0; k < max_steps; ++k) {
            const bodt::StepReport r = mesh->improver.step(mesh->mesh, mesh->surfaces);
            if (callback) {
                bodt_step_report report{};
                report.size = sizeof(report);
                fill_step_report(r, &report);
                if (callback(&report, user_data) != 0)
                    throw Error(BODT_ERR_CANCELLED, "cancelled by the callback after step " + std::to_string(r.step));
            }
            const bool reconnected = r.flips + r.vertices_inserted + r.edges_collapsed > 0;
            if (!reconnected && r.max_move <= mesh->improver.params().tolerance * scale) break;
        }
    });
}

int bodt_mesh_read(const char* path, bodt_mesh** mesh) { return bodt_mesh_read_ex(path, BODT_CREATE_DEFAULT, mesh); }

int bodt_mesh_read_ex(const char* path, uint32_t flags, bodt_mesh** mesh) {
    return bodt_mesh_read_format(path, BODT_FORMAT_AUTO, flags, mesh);
}

int bodt_mesh_read_format(const char* path, int format, uint32_t flags, bodt_mesh** mesh) {
    if (!mesh) {
        t_thread_error = "mesh (the output pointer) is NULL";
        return BODT_ERR_INVALID_ARGUMENT;
    }
    *mesh = nullptr;
    bodt_mesh* created = nullptr;
    const int status = guarded(nullptr, [&] {
        require(path != nullptr, "path is NULL");
        check_read_flags(flags);
        bodt::MeshData data = bodt::read_mesh_file(path, bodt::format_from_code(format, path));
        try {
            created = from_mesh_data(std::move(data), flags);
        } catch (const Error& e) {
            throw Error(e.status(), std::string(path) + ": " + e.what());
        }
    });
    *mesh = created;
    return status;
}

int bodt_format_from_path(const char* path, int* format) {
    return guarded(nullptr, [&] {
        require(path != nullptr, "path is NULL");
        require(format != nullptr, "format is NULL");
        *format = static_cast<int>(bodt::format_from_path(path));
    });
}

int bodt_mesh_write(const bodt_mesh* mesh, const char* path) {
    return bodt_mesh_write_format(mesh, path, BODT_FORMAT_AUTO);
}

int bodt_mesh_write_format(const bodt_mesh* mesh, const char* path, int format) {
    return with_mesh(mesh, [&] {
        require(path != nullptr, "path is NULL");
        const bodt::MeshFormat f = bodt::format_from_code(format, path);
        bodt::MeshData data = to_mesh_data(mesh);
        if (f == bodt::MeshFormat::Vtu || f == bodt::MeshFormat::Vtk) add_quality_fields(mesh->mesh, data);
        if (mesh->gmsh_model && bodt::is_gmsh(f)) add_gmsh_model(mesh, data);
        bodt::write_mesh_file(path, data, f);
    });
}

}  // extern "C"
