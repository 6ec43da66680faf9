#include "io/mesh_io.hpp"

#include "bodt.h"
#include "common/error.hpp"

namespace bodt {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

MeshFormat format_from_path(const std::string& path) {
    if (ends_with(path, ".mesh")) return MeshFormat::Medit;
    if (ends_with(path, ".node") || ends_with(path, ".ele")) return MeshFormat::TetGen;
    throw Error(BODT_ERR_UNSUPPORTED, "'" + path + "': unknown mesh format (expected .mesh, .node or .ele)");
}

MeshData read_mesh_file(const std::string& path) {
    return format_from_path(path) == MeshFormat::Medit ? read_medit(path) : read_tetgen(path);
}

void write_mesh_file(const std::string& path, const MeshData& data) {
    if (format_from_path(path) == MeshFormat::Medit) write_medit(path, data);
    else write_tetgen(path, data);
}

}  // namespace bodt
