// VTK XML UnstructuredGrid (.vtu), the format ParaView reads natively.
//
// What a written file holds (one Piece, inline base64 "binary" arrays,
// header_type UInt64, LittleEndian, no compression; version 1.0): Points
// (Float64 x 3), Cells (connectivity Int32, offsets Int32 or Int64 past
// 2^31 - 1 entries, types UInt8), and the cells, cell data (region, marker
// Int32, tet fields Float64) and point data (fixed, corner UInt8, ref Int32)
// of vtk_cells.hpp.  NaN keeps the non-tet cells out of ParaView's
// Threshold on a quality field and out of its colour range; "Extract Cells
// By Type" keeps only the tets.  Binary rather than ASCII: exact for doubles
// by construction and about half the size of %.17g text.
//
// The reader takes what the writer writes and what ParaView, VTK and meshio
// write: ASCII, inline base64 ("binary") and appended (raw or base64)
// DataArrays, uncompressed or compressed with vtkZLibDataCompressor
// (ParaView's and meshio's default; vtu_binary.hpp), header_type UInt32 or
// UInt64, header and data encoded together or separately; Float32 or
// Float64 points, any integer type for cells and for the arrays of
// vtk_cells.hpp (region, marker, fixed, corner, ref, and meshio's and VTK's
// gmsh:physical, medit:ref and CellEntityIds, with the precedence given
// there); VTK's InformationKey elements in a DataArray are skipped.  Cells
// of type 10, 5 and 3 are read as above (triangles without a marker array
// get marker 0), VTK_VERTEX cells are ignored; anything else (hexahedra,
// quadratic tets, polygons ...) is refused, as are the LZ4 and LZMA
// compressors (by name), big-endian files, more than one Piece and a file
// without tets.  Without a region array, regions stay empty; lines get
// their edge ref from the marker array (0 without one); `fixed` and
// `corner` come back sorted, each vertex once.  Other arrays are ignored
// (tet_fields are not read back).  Indices are 0-based: the returned
// MeshData has base 0.  Every problem is an Error(BODT_ERR_IO)
// "<path>:<line>: ...", the line of the element at fault (for appended
// data, its DataArray's, with the offset in the appended data).
#pragma once

#include "io/mesh_io.hpp"

#include <string>

namespace bodt {

MeshData read_vtu(const std::string& path);
// Throws Error(BODT_ERR_INVALID_ARGUMENT) for inconsistent MeshData (array
// sizes, a tet field named like one of the arrays above or twice) and
// Error(BODT_ERR_IO) when the file cannot be written.
void write_vtu(const std::string& path, const MeshData& data);

}  // namespace bodt
