#include "io/mesh_io.hpp"

#include "io/abaqus.hpp"
#include "io/gmsh.hpp"
#include "io/medit_binary.hpp"
#include "io/vtk_legacy.hpp"
#include "io/vtu.hpp"

#include "bodt.h"
#include "common/error.hpp"

#include <algorithm>
#include <cctype>

namespace bodt {

namespace {

// The extension in lower case ("mesh"), or "" without one.
std::string extension(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

MeshFormat format_from_path(const std::string& path) {
    const std::string ext = extension(path);
    if (ext == "mesh") return MeshFormat::Medit;
    if (ext == "meshb") return MeshFormat::MeditBinary;
    if (ext == "node" || ext == "ele") return MeshFormat::TetGen;
    if (ext == "msh") return MeshFormat::Gmsh;
    if (ext == "vtu") return MeshFormat::Vtu;
    if (ext == "vtk") return MeshFormat::Vtk;
    if (ext == "inp") return MeshFormat::Abaqus;
    throw Error(BODT_ERR_UNSUPPORTED, "'" + path + "': unknown mesh format " +
                                          (ext.empty() ? std::string("(no extension)") : "'." + ext + "'") +
                                          " (expected .mesh, .meshb, .node, .ele, .msh, .vtu, .vtk or .inp, or "
                                          "give the format)");
}

MeshFormat format_from_code(int code, const std::string& path) {
    if (code == BODT_FORMAT_AUTO) return format_from_path(path);
    if (code < BODT_FORMAT_MEDIT || code > BODT_FORMAT_VTK)
        throw Error(BODT_ERR_INVALID_ARGUMENT, "unknown format " + std::to_string(code));
    return static_cast<MeshFormat>(code);
}

MeshData read_mesh_file(const std::string& path, MeshFormat format) {
    switch (format) {
        case MeshFormat::Medit: return read_medit(path);
        case MeshFormat::MeditBinary: return read_medit_binary(path);
        case MeshFormat::TetGen: return read_tetgen(path);
        case MeshFormat::Gmsh:
        case MeshFormat::GmshBinary:
        case MeshFormat::Gmsh22:
        case MeshFormat::Gmsh22Binary: return read_gmsh(path);
        case MeshFormat::Vtu: return read_vtu(path);
        case MeshFormat::Vtk: return read_vtk(path);
        case MeshFormat::Abaqus: break;
    }
    throw Error(BODT_ERR_UNSUPPORTED, "'" + path + "': Abaqus .inp files are written, not read");
}

void write_mesh_file(const std::string& path, const MeshData& data, MeshFormat format) {
    switch (format) {
        case MeshFormat::Medit: return write_medit(path, data);
        case MeshFormat::MeditBinary: return write_medit_binary(path, data);
        case MeshFormat::TetGen: return write_tetgen(path, data);
        case MeshFormat::Gmsh: return write_gmsh(path, data, 41, false);
        case MeshFormat::GmshBinary: return write_gmsh(path, data, 41, true);
        case MeshFormat::Gmsh22: return write_gmsh(path, data, 22, false);
        case MeshFormat::Gmsh22Binary: return write_gmsh(path, data, 22, true);
        case MeshFormat::Vtu: return write_vtu(path, data);
        case MeshFormat::Vtk: return write_vtk(path, data);
        case MeshFormat::Abaqus: return write_abaqus(path, data);
    }
}

}  // namespace bodt
