#include "cli/surface_input.hpp"

#include <vector>

#ifdef BODT_WITH_TETGEN
#include "cli/silenced_stdout.hpp"

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
    return ext == ".off" || ext == ".stl" || ext == ".ply" || ext == ".poly";
}

#ifdef BODT_WITH_TETGEN

namespace {

bool load_surface(tetgenio& in, const std::string& ext, char* name) {
    const SilencedStdout quiet;
    if (ext == ".off") return in.load_off(name);
    if (ext == ".stl") return in.load_stl(name);
    if (ext == ".ply") return in.load_ply(name);
    return in.load_poly(name);
}

}  // namespace

int tetrahedralize_surface(const std::string& path, bodt_mesh** mesh, std::string& message) {
    *mesh = nullptr;
    const std::string ext = extension(path);
    // TetGen's loaders take a writable name; .poly is given without its extension.
    std::string name = ext == ".poly" ? path.substr(0, path.size() - 5) : path;
    std::vector<char> buffer(name.begin(), name.end());
    buffer.push_back('\0');
    tetgenio in, out;
    if (!load_surface(in, ext, buffer.data())) {
        message = "TetGen could not read the surface '" + path + "'";
        return BODT_ERR_IO;
    }
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
