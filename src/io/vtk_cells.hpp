// What the two VTK formats, XML (.vtu) and legacy (.vtk), share: the cells
// that carry a mesh and the arrays that carry its markers.
//
//   cells       every tet (VTK_TETRA, 10; cell i is tet i), then every
//               marked triangle (VTK_TRIANGLE, 5), then every feature edge
//               (VTK_LINE, 3); VTK_VERTEX cells (1) are ignored on reading,
//               any other type is refused
//   cell data   region  the tet's region, -1 on triangle and line cells
//               marker  the triangle's marker, the line's edge ref, -1 on tets
//               one array per MeshData::tet_fields entry, NaN off the tets
//   point data  fixed, corner (1 or 0), ref (the vertex ref)
//
// The reader tells the cells apart by their type, never by the -1 / NaN
// fillers, so any marker or region value (also -1) round-trips.
//
// Readers also take the arrays other programs write for the same data:
// meshio's gmsh:physical (Gmsh's physical groups) and medit:ref (Medit's
// refs), and VTK's CellEntityIds, each one array for the cells of every type.
// When a file has several, the first present in this order is used:
//   regions of tets           region, gmsh:physical, CellEntityIds, medit:ref
//   markers of triangles and
//   refs of lines             marker, gmsh:physical, CellEntityIds, medit:ref
//   vertex refs (point data)  ref, medit:ref
#pragma once

#include "io/mesh_io.hpp"

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace bodt {

inline constexpr uint8_t kVtkVertex = 1, kVtkLine = 3, kVtkTriangle = 5, kVtkTetra = 10;

// "tetra", "hexahedron", ...; nullptr for a type VTK does not have.
const char* vtk_cell_type_name(int64_t type);

// The names of the integer cell / point arrays that readers take (the table
// above, and fixed and corner).
bool vtk_reads_cell_array(const std::string& name);
bool vtk_reads_point_array(const std::string& name);

// A grid as read from a file, every index 0-based.
struct VtkGrid {
    int64_t points = 0;
    std::vector<double> xyz;           // 3 per point, finite
    std::vector<int64_t> offsets;      // one per cell: where its vertices end in `connectivity`
    std::vector<int64_t> connectivity;
    std::vector<int64_t> types;        // one per cell
    // The arrays the file has of those the readers take, by name: one value
    // per cell or per point, checked by the reader to fit in 32 bits.
    std::map<std::string, std::vector<int64_t>> cell_arrays, point_arrays;
};

// Which part of the grid a problem is in, for the reader to say where.
enum class VtkPart { Offsets, Connectivity, Types, Grid };
// Must throw (the reader's Error with its file position).
using VtkFail = std::function<void(VtkPart, const std::string&)>;

// MeshData (base 0) from the grid, as the tables above say: offsets
// increasing and within the connectivity, every index a point, cells of a
// supported type with their number of points, at least one tet.
MeshData mesh_from_vtk(VtkGrid grid, const VtkFail& fail);

// The cells and arrays of `d` to write, in the order of the table above.
// The constructor checks `d` (sizes, indices, tet field names: none twice,
// none empty or called "region" or "marker") and throws
// Error(BODT_ERR_INVALID_ARGUMENT) "writing '<path>': ...".
class VtkCellWriter {
public:
    VtkCellWriter(const std::string& path, const MeshData& d);

    uint64_t points() const { return nv_; }
    uint64_t cells() const { return nt_ + nf_ + ne_; }
    uint64_t connectivity_size() const { return 4 * nt_ + 3 * nf_ + 2 * ne_; }
    int32_t connectivity(uint64_t k) const;  // 0-based vertex
    uint64_t end_offset(uint64_t c) const;   // where cell c ends in the connectivity
    uint8_t type(uint64_t c) const { return c < nt_ ? kVtkTetra : c < nt_ + nf_ ? kVtkTriangle : kVtkLine; }

    bool has_regions() const { return !d_.regions.empty(); }
    int32_t region(uint64_t c) const { return c < nt_ ? d_.regions[c] : -1; }
    // Triangle cells always carry a marker; line cells only when the edges
    // have refs (without the array they read back as ref 0).
    bool has_markers() const { return nf_ > 0 || !d_.edge_refs.empty(); }
    int32_t marker(uint64_t c) const;
    double field(const MeshData::TetField& f, uint64_t c) const;  // NaN off the tets

    // 1 on the listed vertices (fixed, corners), else 0.
    std::vector<uint8_t> flags(const std::vector<int32_t>& vertices) const;

private:
    const MeshData& d_;
    uint64_t nv_, nt_, nf_, ne_;
};

}  // namespace bodt
