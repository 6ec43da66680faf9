// Gmsh .msh, versions 2.2 and 4.1, ASCII and binary (binary files in the
// byte order of the machine reading them; the other order is refused).
//
// Reading (the version and ASCII/binary come from $MeshFormat):
//   $Nodes      vertices in the file's node order.  Node tags may be sparse
//               and in any order: when the i-th node of the file has tag i
//               (1-based, the usual case), MeshData.base = 1 and indices are
//               the file's tags; otherwise the vertices are renumbered in
//               file order and base = 0.
//   $Elements   type 4 (4-node tet)   -> tets, region = the first physical
//                                        tag of its volume (0 when none);
//                                        in a file without any physical
//                                        volume whose tets lie in several
//                                        volumes (Gmsh saves all elements
//                                        when no physical group is set),
//                                        the volume's entity tag, so the
//                                        surfaces between the volumes stay
//                                        interfaces
//               type 2 (3-node tri)   -> triangles + tri_markers, marker =
//                                        the first physical tag of its
//                                        surface; in a file without any
//                                        physical surface whose triangles
//                                        lie on several surfaces, the
//                                        surface's entity tag; else
//                                        triangles without a physical tag
//                                        are not marked faces and are
//                                        dropped
//               type 1 (2-node line)  -> feature_edges + edge_refs, ref =
//                                        the first physical tag of its
//                                        curve (0 when none); a line a 2.2
//                                        file lists again, once per
//                                        physical group, is kept once with
//                                        the first listing's tag
//               type 15 (point)       -> fixed vertices, when its point
//                                        entity has a physical tag
//               Any other volume element (higher-order tets, hexahedra,
//               prisms, pyramids) is an error; other elements of lower
//               dimension (quads, higher-order lines and triangles) are
//               skipped.  "Physical tag" is the 4.1 $Entities physical tag
//               of the element's entity, or the first element tag in 2.2.
//   $Entities   (4.1) physical tags of the entities.  An element block whose
//               entity is not listed has no physical tag.
//   $PhysicalNames and any other $Section ... $EndSection are skipped.
// Every malformed, truncated or oversized input is Error(BODT_ERR_IO) naming
// the file and the line (ASCII) or byte offset (binary); no count from the
// file is trusted before it is compared with the bytes left.  A tet that a
// 2.2 file lists once per physical group comes back once per listing.
//
// Writing: nodes are tagged 1..n (index - base + 1), elements 1..m in the
// order points, lines, triangles, tets; tets and triangles keep their order.
//   one volume entity per region id, physical tag = the region id (region
//   0: a volume without physical group); one surface entity per nonzero
//   face marker, physical tag = the marker (marker-0 faces are not
//   written); one curve entity per edge ref, physical tag = the ref (ref 0:
//   a curve without physical group), edges in their order; one point entity
//   per fixed vertex, all in physical group 1.  $PhysicalNames names them
//   ("region 3", "marker 7", "edge ref 20", "fixed vertices").
// So regions, face markers, feature edges with their refs and fixed
// vertices survive a
// write -> read round trip; coordinates are bit-exact (%.17g or binary).
// Gmsh itself (checked with Gmsh 4.8.4: -check, and -0 -o to all four
// variants) reads all four; by default it saves only elements in physical
// groups (so it drops region-0 tets unless -save_all), it turns a negative
// physical tag -k into k, and its ASCII output has 16 digits, not 17.
#pragma once

#include "io/mesh_io.hpp"

#include <string>

namespace bodt {

MeshData read_gmsh(const std::string& path);

// version: 41 or 22 (else Error(BODT_ERR_INVALID_ARGUMENT)); binary: the
// binary variant of that version.
void write_gmsh(const std::string& path, const MeshData& data, int version, bool binary);

}  // namespace bodt
