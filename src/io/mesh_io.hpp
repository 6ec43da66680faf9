// Mesh files.  Readers fill MeshData from a file and never trust it: every
// malformed, truncated or oversized input is an Error(BODT_ERR_IO) naming the
// file and line.  Writers take MeshData with positively oriented tets.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bodt {

struct GmshModel;  // io/gmsh_model.hpp

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
    std::vector<int32_t> vertex_refs;  // one per vertex, or empty (all 0)
    std::vector<int32_t> fixed;        // fixed vertices
    std::vector<int32_t> corners;      // the caller's corners
    std::vector<int32_t> feature_edges;  // 2 per feature edge
    std::vector<int32_t> edge_refs;    // one per feature edge, or empty (all 0)
    // Per-tet values that formats with cell data (VTU) write for viewers:
    // a name and one value per tet.  Never read back.
    struct TetField {
        std::string name;
        std::vector<double> values;
    };
    std::vector<TetField> tet_fields;
    // What a Gmsh file holds beyond these arrays (names, entities, the
    // entity of each element), from read_gmsh; null for other sources.
    // write_gmsh writes the mesh back into those entities; other writers
    // ignore it, and the C API hands it (and the origins) to Gmsh writes only.
    std::shared_ptr<const GmshModel> gmsh;
    // Where the vertices and tets came from when the mesh is the one read
    // after steps that changed its connectivity, for write_gmsh to place
    // the elements into the model's entities.  Vertex indices count from 0.
    struct Origins {
        // Without parent offsets every vertex is an input vertex; with them,
        // vertices from `input_vertices` on were made by steps, and vertex v
        // stands for the input vertices parents[offsets[v] .. offsets[v + 1])
        // with those weights (an input vertex for itself, weight 1), as
        // bodt_mesh_get_vertex_parents gives them.
        int32_t input_vertices = 0;
        std::vector<int64_t> parent_offsets;
        std::vector<int32_t> parents;
        std::vector<double> weights;
        std::vector<int32_t> tet_origins;  // per tet, the input tet it came from (empty: tet t is input tet t)
    };
    Origins origins;
};

// The values are those of enum bodt_format (bodt.h).
enum class MeshFormat {
    Medit = 1,         // .mesh
    MeditBinary = 2,   // .meshb
    TetGen = 3,        // .node / .ele / .face
    Gmsh = 4,          // .msh: reads 2.2 and 4.1, ASCII and binary; writes 4.1 ASCII
    GmshBinary = 5,    // writes 4.1 binary
    Gmsh22 = 6,        // writes 2.2 ASCII
    Gmsh22Binary = 7,  // writes 2.2 binary
    Vtu = 8,           // .vtu (VTK XML unstructured grid)
    Abaqus = 9,        // .inp (write only)
    Vtk = 10           // .vtk (VTK legacy)
};

// The .msh variants: those that MeshData::gmsh and ::origins are for.
inline bool is_gmsh(MeshFormat f) {
    return f == MeshFormat::Gmsh || f == MeshFormat::GmshBinary || f == MeshFormat::Gmsh22 ||
           f == MeshFormat::Gmsh22Binary;
}

// By extension: .mesh, .meshb, .node/.ele, .msh, .vtu, .vtk, .inp.  Throws
// Error(BODT_ERR_UNSUPPORTED) for anything else.
MeshFormat format_from_path(const std::string& path);
// An enum bodt_format value; BODT_FORMAT_AUTO goes by the path.  Throws
// Error(BODT_ERR_INVALID_ARGUMENT) for a value that is none.
MeshFormat format_from_code(int code, const std::string& path);

// Throws Error(BODT_ERR_UNSUPPORTED) for a format that is only written.
MeshData read_mesh_file(const std::string& path, MeshFormat format);
void write_mesh_file(const std::string& path, const MeshData& data, MeshFormat format);

MeshData read_medit(const std::string& path);
void write_medit(const std::string& path, const MeshData& data);

// `path` is the .node or the .ele file; the others sit beside it.
MeshData read_tetgen(const std::string& path);
void write_tetgen(const std::string& path, const MeshData& data);

}  // namespace bodt
