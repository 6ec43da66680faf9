// VTK legacy files (.vtk): the format VTK had before its XML ones, still
// written by many solvers, by Mesquite, by meshio and by VTK itself.
//
// What a written file holds: "# vtk DataFile Version 4.2", BINARY (raw
// big-endian values, as the format prescribes: exact doubles, NaN-safe),
// DATASET UNSTRUCTURED_GRID: POINTS (double), CELLS (int: the count, then
// the indices, per cell) and CELL_TYPES (int), then CELL_DATA and
// POINT_DATA as SCALARS arrays with LOOKUP_TABLE default, holding the
// cells and arrays of vtk_cells.hpp: region, marker (int), one double array
// per tet field, ref (int), fixed, corner (unsigned_char).  Names are
// written with VTK's %XX escapes for a space, '%' and bytes outside
// printable ASCII.  Version 4.2's cell layout, not 5.1's, so that every VTK
// since 4 and every other reader of the format reads it.
//
// The reader takes versions 1.0 to 5.1, ASCII or BINARY:
//   - DATASET UNSTRUCTURED_GRID only (anything else is refused by name);
//   - POINTS of any numeric type; CELLS in the layout of the file's
//     version (before 5: the count, then the indices, per cell; 5 and later:
//     OFFSETS and CONNECTIVITY arrays); CELL_TYPES; cells as vtk_cells.hpp
//     says (tets, triangles, lines, vertices ignored, the rest refused);
//   - in CELL_DATA and POINT_DATA, the arrays of vtk_cells.hpp (region,
//     marker, gmsh:physical, CellEntityIds, medit:ref of the cells; fixed,
//     corner, ref, medit:ref of the points), given as SCALARS (with
//     LOOKUP_TABLE, as VTK requires) or as FIELD arrays (meshio), of one
//     component, of any numeric type whose values are whole numbers that
//     fit in 32 bits (Mesquite writes its `fixed` flags as float; its
//     `fixed` is the vertices its smoother must not move, the meaning of
//     fixed here);
//   - every other attribute (SCALARS, VECTORS, NORMALS, TENSORS, TENSORS6,
//     TEXTURE_COORDINATES, COLOR_SCALARS, LOOKUP_TABLE, GLOBAL_IDS,
//     PEDIGREE_IDS, EDGE_FLAGS, FIELD arrays) is skipped, as are FIELD data
//     of the dataset and 5.x METADATA blocks; names are %XX-decoded.
// Refused: the `bit` type and string arrays, a second POINTS, CELLS or
// CELL_TYPES, counts that do not match, a file without tets.  Keywords and
// type names are case-insensitive, as in VTK.  Indices are 0-based: the
// returned MeshData has base 0.  Nothing is allocated from a count before
// the bytes present are known to hold it.  Every problem is an
// Error(BODT_ERR_IO): "<path>:<line>: ..." in an ASCII file and in the
// header of a binary one, "<path>: byte <offset>: ..." after it.
#pragma once

#include "io/mesh_io.hpp"

#include <string>

namespace bodt {

MeshData read_vtk(const std::string& path);
// Throws Error(BODT_ERR_INVALID_ARGUMENT) for inconsistent MeshData (as
// write_vtu) and Error(BODT_ERR_IO) when the file cannot be written.
void write_vtk(const std::string& path, const MeshData& data);

}  // namespace bodt
