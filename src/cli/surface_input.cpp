#include "cli/surface_input.hpp"

#include <vector>

#ifdef BODT_WITH_TETGEN
#include "cli/silenced_stdout.hpp"

// OpenMesh 9's property code trips GCC 12's -Wmaybe-uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#pragma GCC diagnostic pop
#include <tetgen.h>
#endif

namespace bodt_cli {

namespace {

std::string extension(const std::string& path) {
    const size_t dot = path.rfind('.');
    return dot == std::string::npos ? "" : path.substr(dot);
}

}  // namespace

bool is_surface_path(const std::string& path) {
    const std::string ext = extension(path);
    return ext == ".off" || ext == ".obj" || ext == ".stl" || ext == ".ply" || ext == ".poly";
}

#ifdef BODT_WITH_TETGEN

namespace {

using SurfaceMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// A closed triangle surface read by OpenMesh (.off, .obj, .stl, .ply; polygons
// are triangulated) as TetGen's PLC: its points and one triangle per facet.
// Returns "" or what is wrong.
std::string load_with_openmesh(tetgenio& in, const std::string& path) {
    SurfaceMesh surface;
    OpenMesh::IO::Options options;
    if (!OpenMesh::IO::read_mesh(surface, path, options)) return "cannot read the surface '" + path + "'";
    if (surface.n_faces() == 0) return "'" + path + "' has no faces";
    for (const auto h : surface.halfedges())
        if (surface.is_boundary(h)) return "'" + path + "' is not a closed surface (it has boundary edges)";
    in.firstnumber = 0;
    in.numberofpoints = static_cast<int>(surface.n_vertices());
    in.pointlist = new REAL[3 * surface.n_vertices()];
    for (const auto v : surface.vertices())
        for (int k = 0; k < 3; ++k) in.pointlist[3 * v.idx() + k] = surface.point(v)[k];
    in.numberoffacets = static_cast<int>(surface.n_faces());
    in.facetlist = new tetgenio::facet[surface.n_faces()];
    for (const auto f : surface.faces()) {
        tetgenio::facet& facet = in.facetlist[f.idx()];
        tetgenio::init(&facet);
        facet.numberofpolygons = 1;
        facet.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&facet.polygonlist[0]);
        facet.polygonlist[0].numberofvertices = 3;
        facet.polygonlist[0].vertexlist = new int[3];
        int k = 0;
        for (const auto v : surface.fv_range(f)) facet.polygonlist[0].vertexlist[k++] = v.idx();
    }
    return "";
}

// Loads the surface or PLC at `path` into `in`; returns "" or what is wrong.
std::string load_surface(tetgenio& in, const std::string& path, const std::string& ext) {
    if (ext != ".poly") return load_with_openmesh(in, path);
    // TetGen's loader takes a writable name without the extension.
    std::string name = path.substr(0, path.size() - 5);
    std::vector<char> buffer(name.begin(), name.end());
    buffer.push_back('\0');
    const SilencedStdout quiet;
    return in.load_poly(buffer.data()) ? "" : "TetGen could not read the PLC '" + path + "'";
}

}  // namespace

int tetrahedralize_surface(const std::string& path, bodt_mesh** mesh, std::string& message) {
    *mesh = nullptr;
    tetgenio in, out;
    message = load_surface(in, path, extension(path));
    if (!message.empty()) return BODT_ERR_IO;
    tetgenbehavior behavior;
    char switches[] = "pQ";  // PLC, quiet; numbering follows out.firstnumber
    if (!behavior.parse_commandline(switches)) {
        message = "TetGen rejected its switches";
        return BODT_ERR_NUMERIC;
    }
    try {
        tetrahedralize(&behavior, &in, &out);
    } catch (...) {  // TetGen reports failures (e.g. self-intersections) by throwing an int
        message = "TetGen could not tetrahedralize '" + path + "' (is it a closed surface without self-intersections?)";
        return BODT_ERR_BAD_MESH;
    }
    if (out.numberoftetrahedra <= 0) {
        message = "TetGen made no tets from '" + path + "'";
        return BODT_ERR_BAD_MESH;
    }
    std::vector<int32_t> tets(out.tetrahedronlist, out.tetrahedronlist + 4 * out.numberoftetrahedra);
    int status = bodt_mesh_create(out.numberofpoints, out.pointlist, out.numberoftetrahedra, tets.data(),
                                  out.firstnumber, mesh);
    if (status != BODT_OK) {
        message = bodt_mesh_last_error(nullptr);
        return status;
    }
    if (out.numberoftrifaces > 0 && out.trifacemarkerlist) {
        std::vector<int32_t> faces(out.trifacelist, out.trifacelist + 3 * out.numberoftrifaces);
        std::vector<int32_t> markers(out.trifacemarkerlist, out.trifacemarkerlist + out.numberoftrifaces);
        status = bodt_mesh_set_boundary_faces(*mesh, out.numberoftrifaces, faces.data(), markers.data());
        if (status != BODT_OK) {
            message = bodt_mesh_last_error(*mesh);
            bodt_mesh_destroy(*mesh);
            *mesh = nullptr;
        }
    }
    return status;
}

#else

int tetrahedralize_surface(const std::string& path, bodt_mesh** mesh, std::string& message) {
    *mesh = nullptr;
    message = "'" + path + "' is a surface, and this bodt was built without TetGen (BODT_WITH_TETGEN=OFF)";
    return BODT_ERR_UNSUPPORTED;
}

#endif

}  // namespace bodt_cli
