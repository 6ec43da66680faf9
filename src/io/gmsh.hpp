// Gmsh .msh, versions 2.2 and 4.1, ASCII and binary (binary files in the
// byte order of the machine reading them; the other order is refused).
//
// Reading (the version and ASCII/binary come from $MeshFormat):
//   $Nodes      vertices.  When the node tags are 1..n in any order (Gmsh's,
//               and bodt's own files, whose 4.1 node blocks follow the
//               entities), MeshData.base = 1 and vertex i is the node
//               tagged i; any other tags (sparse, gaps) are renumbered in
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
//                                        are not marked faces (the model
//                                        below keeps them)
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
//               4.1 elements of each dimension come in the order of their
//               element tags (the file order in Gmsh's files).
//   $Entities   (4.1) the entities: tags, physical tags, bounding entities,
//               boxes.  An element block whose entity is not listed has no
//               physical tag; an entity tag that is not positive names no
//               entity.
//   $PhysicalNames  the names of the physical groups.
//   Any other $Section ... $EndSection is skipped.
// What the arrays cannot hold goes into MeshData.gmsh (gmsh_model.hpp): the
// physical names, every entity, the entity of each element read (also the
// triangles and point elements not kept as marked faces or fixed vertices)
// and, for 4.1, of each node.
// Every malformed, truncated or oversized input is Error(BODT_ERR_IO) naming
// the file and the line (ASCII) or byte offset (binary); no count from the
// file is trusted before it is compared with the bytes left.  A tet that a
// 2.2 file lists once per physical group comes back once per listing.
//
// Writing: the entities and the entity of each element and node come from
// layout_gmsh (gmsh_layout.hpp): a mesh read from a .msh goes back into the
// file's entities, with its physical tags and names, also after steps that
// changed its connectivity (MeshData.origins); any other mesh gets an
// entity per region, face marker, edge ref and fixed vertex, with the value
// as physical tag and a generated name ("region 3", "marker 7", "edge ref
// 20", "fixed vertices").  Marker-0 faces are written only where the file
// had triangles without a physical group.  In a file with physical groups,
// the elements of no group are in physical group 0 (unnamed), so that
// meshio, which refuses a file where only some element blocks have a
// physical tag, reads every file written here.
//   4.1  $PhysicalNames, $Entities (every entity: tag, box, physical tags,
//        bounding entities), $Nodes in a block per entity (tags 1..n: the
//        vertex index - base + 1), $Elements in a block per entity, element
//        tags numbering the points, lines, triangles and tets in that order
//        and each in the order of its array, so that reading gives the
//        arrays back in their order.
//   2.2  $PhysicalNames, $Nodes 1..n, $Elements: points, lines, triangles,
//        tets, each in its array's order, with two tags: the first physical
//        tag of its entity (0 for none: 2.2 cannot tell group 0 from none)
//        and the entity.  An entity in several physical groups is written in
//        its first only; entities without elements are not in a 2.2 file.
// So regions, face markers, feature edges with their refs and fixed
// vertices survive a write -> read round trip, as do the physical names,
// the entities and (4.1) the node blocks; coordinates are bit-exact (%.17g or
// binary).  Gmsh 4.8 and meshio (Debian 12's python3-gmsh and
// python3-meshio) read all four variants, with and without physical groups
// (bindings/python/tests/test_gmsh_files.py).  Gmsh by default saves only
// elements in physical groups, turns a negative physical tag -k into k, drops
// the nodes no element uses when it reads 2.2, and its ASCII output has 16
// digits, not 17.
#pragma once

#include "io/mesh_io.hpp"

#include <string>

namespace bodt {

MeshData read_gmsh(const std::string& path);

// version: 41 or 22 (else Error(BODT_ERR_INVALID_ARGUMENT)); binary: the
// binary variant of that version.
void write_gmsh(const std::string& path, const MeshData& data, int version, bool binary);

}  // namespace bodt
