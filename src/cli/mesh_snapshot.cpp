#include "cli/mesh_snapshot.hpp"

namespace bodt_cli {

namespace {

bool api(int status, const bodt_mesh* mesh, const char* what, std::string& error) {
    if (status == BODT_OK) return true;
    error = std::string(what) + " failed: " + bodt_status_string(status);
    const char* msg = bodt_mesh_last_error(mesh);
    if (msg && *msg) error += std::string(" (") + msg + ")";
    return false;
}

}  // namespace

bool take_snapshot(const bodt_mesh* mesh, MeshSnapshot& s, std::string& error) {
    if (!mesh) {
        error = "no mesh";
        return false;
    }
    if (!api(bodt_mesh_get_counts(mesh, &s.nverts, &s.ntets, &s.nfaces), mesh, "bodt_mesh_get_counts", error) ||
        !api(bodt_mesh_get_index_base(mesh, &s.base), mesh, "bodt_mesh_get_index_base", error))
        return false;
    s.quality = bodt_quality{};
    s.quality.size = sizeof s.quality;
    if (!api(bodt_mesh_quality(mesh, &s.quality), mesh, "bodt_mesh_quality", error)) return false;
    const size_t nv = static_cast<size_t>(s.nverts), nt = static_cast<size_t>(s.ntets),
                 nf = static_cast<size_t>(s.nfaces);
    s.xyz.resize(3 * nv);
    s.tets.resize(4 * nt);
    s.faces.resize(3 * nf);
    s.markers.resize(nf);
    for (auto* v : {&s.min_dihedral, &s.max_dihedral, &s.stretch, &s.volume}) v->resize(nt);
    return api(bodt_mesh_get_vertices(mesh, s.xyz.data(), s.xyz.size()), mesh, "bodt_mesh_get_vertices", error) &&
           api(bodt_mesh_get_tets(mesh, s.tets.data(), s.tets.size()), mesh, "bodt_mesh_get_tets", error) &&
           (nf == 0 || api(bodt_mesh_get_boundary_faces(mesh, s.faces.data(), s.markers.data(), nf), mesh,
                           "bodt_mesh_get_boundary_faces", error)) &&
           api(bodt_mesh_tet_quality(mesh, BODT_MEASURE_MIN_DIHEDRAL, s.min_dihedral.data(), nt), mesh,
               "bodt_mesh_tet_quality", error) &&
           api(bodt_mesh_tet_quality(mesh, BODT_MEASURE_MAX_DIHEDRAL, s.max_dihedral.data(), nt), mesh,
               "bodt_mesh_tet_quality", error) &&
           api(bodt_mesh_tet_quality(mesh, BODT_MEASURE_STRETCH, s.stretch.data(), nt), mesh,
               "bodt_mesh_tet_quality", error) &&
           api(bodt_mesh_tet_quality(mesh, BODT_MEASURE_VOLUME, s.volume.data(), nt), mesh,
               "bodt_mesh_tet_quality", error);
}

}  // namespace bodt_cli
