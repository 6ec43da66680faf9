// The C API of paper 002: the extracted geometry, the reference mesh or
// target density, and the recovery errors.
#include "capi/handle.hpp"

#include <cmath>

using namespace bodt_capi;

namespace {

bodt_geometry_class geometry_class(bodt::VertexClass c) {
    switch (c) {
        case bodt::VertexClass::Surface: return BODT_GEOMETRY_SURFACE;
        case bodt::VertexClass::FeatureLine: return BODT_GEOMETRY_SHARP_EDGE;
        case bodt::VertexClass::Corner: return BODT_GEOMETRY_CORNER;
        default: return BODT_GEOMETRY_INTERIOR;
    }
}

int32_t region_index(const bodt_mesh* h, int32_t region) {
    const int32_t r = region - h->index_base;
    const auto& regions = h->improver.geometry(h->mesh).regions();
    if (r < 0 || r >= static_cast<int32_t>(regions.size()))
        throw bodt::Error(BODT_ERR_INVALID_ARGUMENT, "region " + std::to_string(region) + " does not exist: there are " +
                                                         std::to_string(regions.size()) + " surface regions" +
                                                         (h->index_base ? " (numbered from 1)" : " (numbered from 0)"));
    return r;
}

}  // namespace

extern "C" {

int bodt_mesh_get_geometry_counts(const bodt_mesh* mesh, int32_t* nregions, int32_t* nchains) {
    return with_mesh(mesh, [&] {
        const bodt::GeometryModel& g = mesh->improver.geometry(mesh->mesh);
        if (nregions) *nregions = static_cast<int32_t>(g.regions().size());
        if (nchains) *nchains = static_cast<int32_t>(g.chains().size());
    });
}

int bodt_mesh_get_geometry_classes(const bodt_mesh* mesh, int32_t* classes, size_t capacity) {
    return with_mesh(mesh, [&] {
        require(classes != nullptr, "classes is NULL");
        require_capacity(capacity, mesh->mesh.points.size(), "classes");
        const bodt::GeometryModel& g = mesh->improver.geometry(mesh->mesh);
        for (int32_t v = 0; v < mesh->mesh.num_vertices(); ++v)
            classes[mesh->mesh.caller_vertex(v)] = geometry_class(g.vertex_class(v));
    });
}

int bodt_mesh_get_face_regions(const bodt_mesh* mesh, int32_t* region_ids, int32_t* shapes, size_t capacity) {
    return with_mesh(mesh, [&] {
        const auto faces = mesh->mesh.surface_faces();
        require_capacity(capacity, faces.size(), "face regions");
        const bodt::GeometryModel& g = mesh->improver.geometry(mesh->mesh);
        for (size_t f = 0; f < faces.size(); ++f) {
            const auto& v = faces[f].v;
            const auto& p = mesh->mesh.points;
            const int32_t r = g.face_region(v[0], v[1], v[2], (p[v[0]] + p[v[1]] + p[v[2]]) / 3.0);
            if (region_ids) region_ids[f] = r < 0 ? -1 : r + mesh->index_base;
            if (shapes) shapes[f] = r < 0 ? BODT_SHAPE_NONE : static_cast<int32_t>(g.regions()[r].shape.type);
        }
    });
}

int bodt_mesh_get_region_shape(const bodt_mesh* mesh, int32_t region, bodt_shape_fit* fit) {
    return with_mesh(mesh, [&] {
        require(fit != nullptr, "fit is NULL");
        const int32_t r = region_index(mesh, region);
        const bodt::SurfaceRegion& s = mesh->improver.geometry(mesh->mesh).regions()[r];
        bodt_shape_fit full{};
        full.size = sizeof(full);
        full.shape = static_cast<int32_t>(s.shape.type);
        for (int k = 0; k < 3; ++k) {
            full.point[k] = s.shape.point[k];
            full.axis[k] = s.shape.axis[k];
        }
        full.radius = s.shape.radius;
        full.max_error = s.shape.max_error;
        full.acceptable_error = s.acceptable_error;
        fill_sized(fit, full);
    });
}

int bodt_set_reference_mesh(bodt_mesh* mesh, const bodt_mesh* reference) {
    return with_mesh(mesh, [&] {
        if (!reference) mesh->improver.clear_reference();
        else mesh->improver.set_reference(reference->mesh, mesh->mesh);
    });
}

int bodt_set_target_density(bodt_mesh* mesh, const double origin[3], const double spacing[3], const int32_t dims[3],
                            const double* values) {
    return with_mesh(mesh, [&] {
        if (!values) {
            mesh->improver.set_target_density(bodt::DensityGrid());
            return;
        }
        require(origin && spacing && dims, "origin, spacing and dims must not be NULL");
        for (int k = 0; k < 3; ++k) require(dims[k] >= 2, "dims must be at least 2 along each axis");
        const int64_t n = int64_t(dims[0]) * dims[1] * dims[2];
        require(n <= (int64_t(1) << 31), "the grid has more than 2^31 points");
        std::vector<double> v(values, values + n);
        mesh->improver.set_target_density(bodt::DensityGrid(bodt::Vec3(origin[0], origin[1], origin[2]),
                                                            bodt::Vec3(spacing[0], spacing[1], spacing[2]),
                                                            {dims[0], dims[1], dims[2]}, std::move(v)));
    });
}

int bodt_mesh_recovery_error(const bodt_mesh* mesh, bodt_recovery_error* error) {
    return with_mesh(mesh, [&] {
        require(error != nullptr, "error is NULL");
        bodt_recovery_error full{};
        full.size = sizeof(full);
        const bodt::DensityGrid& grid = mesh->improver.target_density();
        if (!grid.empty()) {
            const bodt::DensityError d = bodt::density_error(mesh->mesh, grid);
            full.density_mean = d.mean;
            full.density_max = d.max;
            full.density_edges = d.edges;
        }
        const bodt::GeometryModel::GeometricError g = mesh->improver.geometry(mesh->mesh).geometric_error(mesh->mesh);
        full.geometric_mean = g.mean;
        full.geometric_max = g.max;
        full.geometric_edges = g.edges;
        fill_sized(error, full);
    });
}

}  // extern "C"
