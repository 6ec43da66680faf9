// Abaqus / CalculiX input deck (.inp), write only: the mesh part of a model.
//
//   *HEADING
//   *NODE                               node k+1 = vertex k (counted from
//                                       MeshData::base); coordinates in the
//                                       shortest form that reads back
//                                       exactly when it has at most 20
//                                       characters (CalculiX reads no more);
//                                       else (17 significant digits and a
//                                       '-' below 0.1, or an exponent) the
//                                       most digits that fit, at least 15
//   *ELEMENT, TYPE=C3D4, ELSET=REGION_<id>   one block per region id, in
//                                       increasing order; element t+1 = tet t
//                                       (without regions: one block, ELSET=ALL)
//   *ELSET, ELSET=ALL, GENERATE         every element (with regions)
//   *NSET, NSET=NALL, GENERATE          every node (CalculiX's usual name,
//                                       e.g. for *NODE PRINT, NSET=NALL)
//   *NSET, NSET=FIXED                   the fixed vertices, if any
//   *NSET, NSET=REF_<r>                 per non-zero vertex ref r, its nodes
//                                       (REF_N<r> for a negative r)
//   *NSET, NSET=MARKER_<m>_NODES        per face marker m, the nodes of its
//                                       triangles (for *BOUNDARY; marker 0:
//                                       the faces the mesh marks 0, such as
//                                       region interfaces)
//   *ELSET, ELSET=MARKER_<m>_S<k>       per face marker m and C3D4 face k: the
//   *SURFACE, TYPE=ELEMENT, NAME=MARKER_<m>   elements whose face k is marked m;
//     MARKER_<m>_S<k>, S<k>             the surface lists those sets (for
//                                       *DSLOAD, *DFLUX, *FILM ...)
//
// So a CalculiX or Abaqus job can *INCLUDE the file and use the names:
//   *SOLID SECTION, ELSET=REGION_1, MATERIAL=STEEL   (or ELSET=ALL)
//   *BOUNDARY
//   MARKER_1_NODES, 1, 3
//   *DSLOAD
//   MARKER_2, P, 1.0
//
// C3D4 faces: S1 = nodes 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1.  A marked
// triangle on an interface between two tets goes on the face of the tet
// with the lower number.  Negative ids are spelled with N (REGION_N2,
// MARKER_N2): Abaqus names allow letters, digits and '_' only.  Data lines
// hold at most 16 entries.  Tets must be positively oriented (C3D4 expects
// it; MeshData tets are).
#pragma once

#include "io/mesh_io.hpp"

#include <string>

namespace bodt {

// Throws Error(BODT_ERR_INVALID_ARGUMENT) for inconsistent MeshData (sizes,
// indices) or a marked triangle that is no tet's face, Error(BODT_ERR_IO)
// when the file cannot be written.
void write_abaqus(const std::string& path, const MeshData& data);

}  // namespace bodt
