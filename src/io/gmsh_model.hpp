// What a Gmsh file holds beyond MeshData's arrays: its physical names, its
// entities, and the entity of each element and node read.  read_gmsh fills
// it; the C API keeps it with the mesh, unchanged by improvement, and hands
// it back to write_gmsh, which puts every element written into the entity it
// came from or lies in (gmsh_layout.hpp).  So a Gmsh mesh read, improved and
// written keeps its names, physical tags and entities.
//
// Vertex indices here count from 0 (the file's vertex index minus
// MeshData::base), as the C API numbers the input vertices; an entity index
// is a position in `entities`, -1 for none.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace bodt {

struct GmshEntity {
    int dim = 0;
    int32_t tag = 0;
    std::vector<int32_t> physicals;  // all of them, in the file's order
    std::vector<int32_t> bounding;   // 4.1: the bounding entities (signed tags)
    // Min x, y, z, then max x, y, z (a point: its coordinates twice), when
    // the 4.1 $Entities gives it (finite); else the writer computes it.
    std::array<double, 6> box{};
    bool has_box = false;
};

struct GmshPhysicalName {
    int dim = 0;
    int32_t tag = 0;
    std::string name;  // without quotes; no '"' or line break
};

struct GmshModel {
    std::vector<GmshEntity> entities;  // $Entities' order, then those only elements name (tags > 0)
    std::vector<GmshPhysicalName> names;
    // Per dimension: the reader took the entity tags as regions (3) or face
    // markers (2), for the file has no physical group there (gmsh.hpp).
    std::array<bool, 4> entity_keyed{};
    // The elements read, each with its entity.
    std::vector<int32_t> tet_entity;  // one per tet of the MeshData read (the input tets)
    std::vector<int32_t> triangles;   // 3 per triangle read, also those not kept as marked faces
    std::vector<int32_t> triangle_entity;
    std::vector<int32_t> lines;  // 2 per line read, one per feature edge
    std::vector<int32_t> line_entity;
    std::vector<int32_t> points;  // the vertex of each point element read
    std::vector<int32_t> point_entity;
    // 4.1: the entity of each vertex's node block; empty for 2.2.
    std::vector<int32_t> node_entity;

    // The region, face marker, edge ref or (dim 0) physical tag the
    // elements of `e` were read with: its first physical tag (0 without
    // any), or its tag where the reader took entity tags instead.
    int32_t key(const GmshEntity& e) const {
        if (entity_keyed[static_cast<size_t>(e.dim)]) return e.tag;
        return e.physicals.empty() ? 0 : e.physicals.front();
    }

    // Every index in range for a mesh of `input_vertices` input vertices,
    // every element's entity of the element's dimension: a model that does
    // not fit the mesh is not used.  (Tets are checked as they are looked
    // up, through their origins.)
    bool fits(size_t input_vertices) const;
};

}  // namespace bodt
