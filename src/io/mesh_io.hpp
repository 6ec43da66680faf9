// Mesh files.  Readers fill MeshData from a file and never trust it: every
// malformed, truncated or oversized input is an Error(BODT_ERR_IO) naming the
// file and line.  Writers take MeshData with positively oriented tets.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bodt {

// Plain arrays.  Vertex indices count from `base`: readers keep the file's
// numbering (Medit 1, TetGen 0 or 1), so messages about the mesh in a file
// name what the file says.
struct MeshData {
    int base = 0;
    std::vector<double> xyz;           // 3 per vertex
    std::vector<int32_t> tets;         // 4 per tet
    std::vector<int32_t> regions;      // one per tet, or empty
    std::vector<int32_t> triangles;    // 3 per marked face
    std::vector<int32_t> tri_markers;  // one per marked face
    std::vector<int32_t> fixed;        // fixed vertices
    std::vector<int32_t> feature_edges;  // 2 per feature edge
};

enum class MeshFormat { Medit, TetGen };

// By extension: .mesh -> Medit; .node/.ele -> TetGen.  Throws
// Error(BODT_ERR_UNSUPPORTED) for anything else.
MeshFormat format_from_path(const std::string& path);

MeshData read_mesh_file(const std::string& path);
void write_mesh_file(const std::string& path, const MeshData& data);

MeshData read_medit(const std::string& path);
void write_medit(const std::string& path, const MeshData& data);

// `path` is the .node or the .ele file; the others sit beside it.
MeshData read_tetgen(const std::string& path);
void write_tetgen(const std::string& path, const MeshData& data);

}  // namespace bodt
