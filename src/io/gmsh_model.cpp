#include "io/gmsh_model.hpp"

namespace bodt {

namespace {

// Every value in [lo, n).
bool in_range(const std::vector<int32_t>& values, int32_t lo, size_t n) {
    for (const int32_t v : values)
        if (v < lo || (v >= 0 && static_cast<size_t>(v) >= n)) return false;
    return true;
}

// Every entity index is none or an entity of dimension `dim`.
bool of_dim(const std::vector<GmshEntity>& entities, const std::vector<int32_t>& indices, int dim) {
    for (const int32_t e : indices)
        if (e >= 0 && entities[static_cast<size_t>(e)].dim != dim) return false;
    return true;
}

}  // namespace

bool GmshModel::fits(size_t input_vertices) const {
    const size_t n = entities.size();
    for (const GmshEntity& e : entities)
        if (e.dim < 0 || e.dim > 3) return false;
    if (triangles.size() != 3 * triangle_entity.size() || lines.size() != 2 * line_entity.size() ||
        points.size() != point_entity.size() || (!node_entity.empty() && node_entity.size() != input_vertices))
        return false;
    for (const auto* indices : {&tet_entity, &triangle_entity, &line_entity, &point_entity, &node_entity})
        if (!in_range(*indices, -1, n)) return false;
    for (const auto* vertices : {&triangles, &lines, &points})
        if (!in_range(*vertices, 0, input_vertices)) return false;
    return of_dim(entities, tet_entity, 3) && of_dim(entities, triangle_entity, 2) &&
           of_dim(entities, line_entity, 1) && of_dim(entities, point_entity, 0);
}

}  // namespace bodt
