// The entities of a .msh about to be written, and the entity of every
// element and node: what write_gmsh serialises.
//
// With the GmshModel of the file the mesh was read from (MeshData::gmsh),
// every entity of the model is kept (tag, physical tags, bounding entities,
// box) and each element goes back where it came from:
//   tet       the entity of the input tet it came from (Origins::
//             tet_origins), if that entity has the tet's region;
//   triangle  the entity of the same input triangle, else, among the
//   line      entities with its marker / edge ref, the one its vertices lie
//             on: an input vertex lies on the entities whose input elements
//             hold it, a made vertex on its parents' by their weights
//             (Origins), and the entity with the most wins (the first on a
//             tie);
//   point     a fixed vertex in the physical point entity that held it;
// an element that fits no entity of the model goes into a new one (below).
// Elements the arrays drop but the model held, when their entity has no
// physical group, are written too: the point elements of such point
// entities (while their vertex is in a tet), and the unmarked faces that lie
// on a surface that held triangles without a physical group.
//
// Without a model (a mesh from another format or from arrays), or for what
// the model has no place for: one volume per region, one surface per
// non-zero face marker, one curve per edge ref, with the value as physical
// tag (0 has none), and one point entity per fixed vertex, all in one new
// physical group (tag 1 + the largest physical tag of a point in the model,
// "fixed vertices").  Where the model took entity tags as regions or
// markers (GmshModel::entity_keyed), a new volume or surface takes the value
// as its tag instead, without a physical group.  Marker-0 faces that lie on
// no such surface are not written.  New entities take the next free tags
// of their dimension.
//
// Then, if any entity with elements has a physical tag, every entity with
// elements but without one gets physical tag 0: Gmsh and meshio see all
// elements in physical groups (meshio refuses a file where only some are),
// Gmsh keeps tag 0 when it saves, and read_gmsh reads it as "none" again.
// Physical groups new to the file are named ("region 3", "marker 7", "edge
// ref 20", "fixed vertices"); the model's names are kept as they are.
//
// Nodes: an input vertex stays in the node block of its 4.1 input entity; any
// other vertex goes to the entity of lowest dimension among the written
// elements that hold it, and a vertex in none to the first volume.
#pragma once

#include "io/gmsh_model.hpp"
#include "io/mesh_io.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace bodt {

struct GmshLayout {
    struct Entity {
        int dim = 0;
        int32_t tag = 0;
        std::vector<int32_t> physicals;
        std::vector<int32_t> bounding;  // only entities that are in the layout
        std::array<double, 6> box{};    // min x, y, z, max x, y, z
        std::vector<int32_t> elements;  // its elements (indices in the dimension's list), increasing
    };
    std::vector<Entity> entities;  // by dimension; in each, the model's, then new ones
    // The elements of each dimension: 0 the vertices of `points`, 1
    // MeshData::feature_edges, 2 MeshData::triangles, 3 MeshData::tets.
    // element_entity[dim][k] is element k's entity (an index in `entities`),
    // -1 for one not written.
    std::vector<int32_t> points;  // vertices from 0
    std::array<std::vector<int32_t>, 4> element_entity;
    std::vector<int32_t> node_entity;  // per vertex
    std::vector<GmshPhysicalName> names;
};

// `d` must have passed write_gmsh's checks.
GmshLayout layout_gmsh(const MeshData& d);

}  // namespace bodt
