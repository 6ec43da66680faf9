/* c_side.c: what a C compiler makes of bodt.h, for test_bodt_f to compare
 * with the module bodt: the value of every constant, and which bytes each
 * struct field occupies (each filler writes field k as the number k). */
#include <stdint.h>

#include "bodt.h"

/* In the order of c_side_constants in test_support.f90. */
static const int64_t constants[] = {
    BODT_VERSION_MAJOR, BODT_VERSION_MINOR, BODT_VERSION_PATCH, BODT_VERSION_NUMBER,
    BODT_OK, BODT_ERR_INVALID_ARGUMENT, BODT_ERR_BAD_MESH, BODT_ERR_OUT_OF_MEMORY, BODT_ERR_WRONG_STATE,
    BODT_ERR_NUMERIC, BODT_ERR_IO, BODT_ERR_CANCELLED, BODT_ERR_UNSUPPORTED,
    BODT_CREATE_DEFAULT, BODT_CREATE_ACCEPT_INVERTED, BODT_CREATE_ONE_BASED, BODT_CREATE_KEEP_ORDER,
    BODT_CREATE_FILE_BASE,
    BODT_VERTEX_INTERIOR, BODT_VERTEX_SURFACE, BODT_VERTEX_FEATURE_LINE, BODT_VERTEX_CORNER, BODT_VERTEX_FIXED,
    BODT_VERTEX_UNUSED,
    BODT_DIHEDRAL_BINS,
    BODT_MEASURE_MIN_DIHEDRAL, BODT_MEASURE_MAX_DIHEDRAL, BODT_MEASURE_STRETCH, BODT_MEASURE_VOLUME,
    BODT_MODE_LAPLACE, BODT_MODE_ODT, BODT_MODE_BODT_BASIC, BODT_MODE_BODT, BODT_MODE_OPT_WEIGHTED,
    BODT_MODE_PHASED_ODT, BODT_MODE_NODT,
    BODT_PARAM_TOLERANCE, BODT_PARAM_BACKTRACK_STEPS, BODT_PARAM_MIN_STRETCH, BODT_PARAM_NEVER_WORSE,
    BODT_PARAM_FEATURE_ANGLE, BODT_PARAM_EDGE_RATIO, BODT_PARAM_CORNER_RATIO, BODT_PARAM_OPS,
    BODT_PARAM_KEEP_SURFACE, BODT_PARAM_BAD_ANGLE, BODT_PARAM_DELAUNAY_FLIPS, BODT_PARAM_WEIGHT_C,
    BODT_PARAM_POOR_QUALITY, BODT_PARAM_QN_EPSILON, BODT_PARAM_QN_MAX_ITERATIONS, BODT_PARAM_QN_INITIAL_STEP,
    BODT_PARAM_QN_INTERVAL_GROWTH, BODT_PARAM_ODT_STEP, BODT_PARAM_DENSITY_SPLIT, BODT_PARAM_DENSITY_COLLAPSE,
    BODT_PARAM_FIT_TOLERANCE, BODT_PARAM_THREADS, BODT_PARAM_ASCENT_ANGLE,
    BODT_OP_SMOOTH, BODT_OP_FLIP, BODT_OP_INSERT, BODT_OP_COLLAPSE, BODT_OPS_MODE_DEFAULT,
    BODT_GEOMETRY_INTERIOR, BODT_GEOMETRY_SURFACE, BODT_GEOMETRY_SHARP_EDGE, BODT_GEOMETRY_CORNER,
    BODT_SHAPE_NONE, BODT_SHAPE_PLANE, BODT_SHAPE_CYLINDER, BODT_SHAPE_LINE, BODT_SHAPE_ARC, BODT_SHAPE_CIRCLE,
    BODT_FORMAT_AUTO, BODT_FORMAT_MEDIT, BODT_FORMAT_MEDIT_BINARY, BODT_FORMAT_TETGEN, BODT_FORMAT_GMSH,
    BODT_FORMAT_GMSH_BINARY, BODT_FORMAT_GMSH22, BODT_FORMAT_GMSH22_BINARY, BODT_FORMAT_VTU, BODT_FORMAT_ABAQUS};

/* Copies the constants; returns how many there are. */
int32_t c_side_constants(int64_t *values, int32_t capacity) {
    const int32_t n = (int32_t)(sizeof constants / sizeof constants[0]);
    for (int32_t i = 0; i < n && i < capacity; ++i) values[i] = constants[i];
    return n;
}

void c_side_fill_quality(bodt_quality *q) {
    q->size = sizeof *q;
    q->num_vertices = 1;
    q->num_tets = 2;
    q->num_boundary_faces = 3;
    q->num_unused_vertices = 4;
    q->num_inverted = 5;
    q->reserved0 = 6;
    q->min_dihedral = 7;
    q->max_dihedral = 8;
    q->mean_dihedral = 9;
    q->min_stretch = 10;
    q->mean_stretch = 11;
    q->volume = 12;
    for (int i = 0; i < BODT_DIHEDRAL_BINS; ++i) q->dihedral_histogram[i] = 13 + i;
}

void c_side_fill_step_report(bodt_step_report *r) {
    r->size = sizeof *r;
    r->step = 1;
    r->vertices_moved = 2;
    r->moves_rejected = 3;
    r->moves_shortened = 4;
    r->not_positive_definite = 5;
    r->reserved0 = 6;
    r->max_move = 7;
    r->min_dihedral = 8;
    r->max_dihedral = 9;
    r->min_stretch = 10;
    r->flips = 11;
    r->vertices_inserted = 12;
    r->edges_collapsed = 13;
    r->reserved1 = 14;
}

void c_side_fill_shape_fit(bodt_shape_fit *f) {
    f->size = sizeof *f;
    f->shape = 1;
    f->reserved0 = 2;
    for (int i = 0; i < 3; ++i) {
        f->point[i] = 3 + i;
        f->axis[i] = 6 + i;
    }
    f->radius = 9;
    f->max_error = 10;
    f->acceptable_error = 11;
}

void c_side_fill_recovery_error(bodt_recovery_error *e) {
    e->size = sizeof *e;
    e->density_mean = 1;
    e->density_max = 2;
    e->density_edges = 3;
    e->geometric_mean = 4;
    e->geometric_max = 5;
    e->geometric_edges = 6;
}
