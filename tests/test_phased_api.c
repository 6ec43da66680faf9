/*
 * test_phased_api: BODT_MODE_PHASED_ODT (paper 002) and its geometry and
 * reference functions through libbodt.so only.  The meshes are a box with a
 * round hole (tests/support/mesh_gen.c: tm_make_box_with_hole, an O-grid of
 * Kuhn-split cells) and its "dimension-driven deformation"
 * (tm_deform_box_with_hole: the box's x > 0 side stretched, the hole's
 * radius changed without smoothing, which inverts tets); everything is
 * checked with the test's own arithmetic on what the getters give back.
 *
 *   generator      several boxes with a hole: every interior face shared by
 *                  two tets of opposite orientation, the boundary faces where
 *                  the flags say; bodt_mesh_create takes them with no inverted
 *                  tet; ring 0 on the circle to 1e-12, the outside on the
 *                  square, the volume that of the square minus the inscribed
 *                  nt-gon (1e-9 relative)
 *   deformed       the deformation: vertices where the header says; inverted
 *                  tets (the test's own count), so bodt_mesh_create refuses
 *                  the mesh (BODT_ERR_BAD_MESH) and bodt_mesh_create_ex with
 *                  BODT_CREATE_ACCEPT_INVERTED takes it with the same count;
 *                  signed volume that of the stretched box minus the hole
 *   geometry       geometry extraction (sec. 3.3) on the undeformed mesh: 7
 *                  surface regions, 14 sharp-edge chains, vertex classes
 *                  (8 corners), one region per face of the part, the hole a
 *                  cylinder of the radius around the z axis, the rest planes
 *   recovery       THE acceptance case: the deformed mesh with the undeformed
 *                  one as reference, 30 steps of BODT_MODE_PHASED_ODT: no
 *                  inverted tet, the hole's vertices on the fitted cylinder
 *                  (the new radius, along z), plane vertices on their planes,
 *                  the density error (eq. 4.1) smaller than before
 *   bad input      reference of another vertex count, NULL handles, a grid
 *                  of one point, NaN or zero spacing, the new params out of
 *                  range (refused, value kept), the new mode, out-of-range
 *                  region, too small capacity
 *   density grid   a uniform box with a constant target density twice its
 *                  own: a few steps add vertices and lower the density error
 */
#include "api_checks.h"
#include "bodt.h"
#include "cleanup.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>

/* ------------------------------------------------------------- helpers */

static void destroy_mesh(void *p) { bodt_mesh_destroy(p); }

static const double *P(const double *xyz, int32_t v) { return xyz + 3 * (size_t)v; }

typedef struct hole_params {
    int nr, nt, nz;
    double half_width, radius, height;
} hole_params;

/* The mesh of the deformation cases: the hole's
 * radius 0.3 -> 0.5 reaches past ring 1 everywhere on the x < 0 side. */
static const hole_params kHole = {6, 24, 4, 1.0, 0.3, 0.6};
static const double kStretch = 1.5;
static const double kNewRadius = 0.5;

static int ring_of(const hole_params *p, int32_t v) { return (int)(v / p->nt % (p->nr + 1)); }
static int angle_of(const hole_params *p, int32_t v) { return (int)(v % p->nt); }
static int layer_of(const hole_params *p, int32_t v) { return (int)(v / ((int32_t)p->nt * (p->nr + 1))); }

static test_mesh *make_hole(const hole_params *p) {
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_non_null(m);
    const int st = tm_make_box_with_hole(m, p->nr, p->nt, p->nz, p->half_width, p->radius, p->height);
    if (st != 0) fail_msg("tm_make_box_with_hole(%d, %d, %d): %d", p->nr, p->nt, p->nz, st);
    return m;
}

static test_mesh *make_deformed(const hole_params *p, double stretch, double new_radius) {
    test_mesh *m = make_hole(p);
    tm_deform_box_with_hole(m, p->nr, p->nt, p->nz, stretch, new_radius, p->half_width, p->radius);
    return m;
}

/* Volume of the part: a rectangle of area `outer` minus the nt-gon
 * inscribed in the circle of radius r, times the height. */
static double part_volume(const hole_params *p, double outer, double r) {
    const double pi = 3.14159265358979323846;
    return (outer - 0.5 * p->nt * r * r * sin(2.0 * pi / p->nt)) * p->height;
}

static int32_t hole_boundary_faces(const hole_params *p) { return 4 * p->nt * p->nz + 4 * p->nr * p->nt; }

static bodt_mesh *create_ok(const test_mesh *m, uint32_t flags) {
    bodt_mesh *h = NULL;
    const int st = bodt_mesh_create_ex(m->nverts, m->xyz, m->ntets, m->tets, 0, flags, &h);
    if (st != BODT_OK) fail_msg("create: %s: %s", bodt_status_string(st), bodt_mesh_last_error(NULL));
    cleanup_add(h, destroy_mesh);
    return h;
}

static int32_t count_inverted(const test_mesh *m, int32_t *zero) {
    int32_t n = 0;
    *zero = 0;
    for (int32_t t = 0; t < m->ntets; ++t) {
        const int32_t *q = &m->tets[4 * t];
        const double v6 = tm_orient6(P(m->xyz, q[0]), P(m->xyz, q[1]), P(m->xyz, q[2]), P(m->xyz, q[3]));
        n += !(v6 > 0.0);
        *zero += v6 == 0.0;
    }
    return n;
}

/* A face of a tet: its vertices sorted, and +-1 for the orientation the
 * tet induces on it relative to that sorted order. */
typedef struct oface {
    int32_t v[3];
    int sign;
} oface;

static int cmp_oface(const void *a, const void *b) {
    const oface *x = a, *y = b;
    for (int k = 0; k < 3; ++k)
        if (x->v[k] != y->v[k]) return x->v[k] < y->v[k] ? -1 : 1;
    return 0;
}

/* +1 for an even permutation of three distinct values into sorted order. */
static int parity3(const int32_t *t) {
    int inversions = (t[0] > t[1]) + (t[0] > t[2]) + (t[1] > t[2]);
    return inversions % 2 ? -1 : 1;
}

/* Every face of the tets is on one tet (a boundary face, all of whose
 * vertices are flagged) or on two with opposite orientations; returns the
 * number of boundary faces. */
static int32_t check_faces_paired(const test_mesh *m) {
    const size_t nf = 4 * (size_t)m->ntets;
    oface *f = cleanup_calloc(nf * sizeof *f);
    for (int32_t t = 0; t < m->ntets; ++t) {
        const int32_t *q = &m->tets[4 * t];
        /* the boundary of (a b c d): (b c d) - (a c d) + (a b d) - (a b c) */
        const int32_t faces[4][3] = {{q[1], q[2], q[3]}, {q[0], q[3], q[2]}, {q[0], q[1], q[3]}, {q[0], q[2], q[1]}};
        for (int k = 0; k < 4; ++k) {
            oface *o = &f[4 * (size_t)t + k];
            memcpy(o->v, faces[k], sizeof o->v);
            o->sign = parity3(o->v);
            sort3(o->v);
        }
    }
    qsort(f, nf, sizeof *f, cmp_oface);
    int32_t boundary = 0;
    for (size_t a = 0; a < nf;) {
        size_t b = a + 1;
        while (b < nf && cmp_oface(&f[a], &f[b]) == 0) ++b;
        if (b - a > 2) fail_msg("face (%d %d %d) on %zu tets", f[a].v[0], f[a].v[1], f[a].v[2], b - a);
        if (b - a == 2 && f[a].sign == f[a + 1].sign)
            fail_msg("face (%d %d %d): both tets on the same side", f[a].v[0], f[a].v[1], f[a].v[2]);
        if (b - a == 1) {
            ++boundary;
            for (int k = 0; k < 3; ++k)
                if (!m->boundary[f[a].v[k]])
                    fail_msg("boundary face (%d %d %d) has unflagged vertex %d", f[a].v[0], f[a].v[1], f[a].v[2],
                             f[a].v[k]);
        }
        a = b;
    }
    return boundary;
}

typedef struct faces {
    int32_t nb;
    int32_t *tri;     /* 3 * nb, as the library lists them */
    int32_t *region;  /* nb */
    int32_t *shape;   /* nb */
} faces;

static faces take_faces(const bodt_mesh *h) {
    faces f;
    assert_int_equal(bodt_mesh_get_counts(h, NULL, NULL, &f.nb), BODT_OK);
    f.tri = cleanup_calloc(3 * (size_t)f.nb * sizeof *f.tri);
    f.region = cleanup_calloc((size_t)f.nb * sizeof *f.region);
    f.shape = cleanup_calloc((size_t)f.nb * sizeof *f.shape);
    assert_int_equal(bodt_mesh_get_boundary_faces(h, f.tri, NULL, (size_t)f.nb), BODT_OK);
    const int st = bodt_mesh_get_face_regions(h, f.region, f.shape, (size_t)f.nb);
    if (st != BODT_OK) fail_msg("bodt_mesh_get_face_regions: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    return f;
}

static double *take_vertices(const bodt_mesh *h, int32_t *nv) {
    assert_int_equal(bodt_mesh_get_counts(h, nv, NULL, NULL), BODT_OK);
    double *xyz = cleanup_calloc(3 * (size_t)*nv * sizeof *xyz);
    assert_int_equal(bodt_mesh_get_vertices(h, xyz, 3 * (size_t)*nv), BODT_OK);
    return xyz;
}

static bodt_shape_fit region_shape(const bodt_mesh *h, int32_t region) {
    bodt_shape_fit fit;
    memset(&fit, 0, sizeof fit);
    fit.size = sizeof fit;
    const int st = bodt_mesh_get_region_shape(h, region, &fit);
    if (st != BODT_OK)
        fail_msg("bodt_mesh_get_region_shape(%d): %s: %s", region, bodt_status_string(st), bodt_mesh_last_error(h));
    return fit;
}

static bodt_recovery_error recovery(const bodt_mesh *h) {
    bodt_recovery_error e;
    memset(&e, 0, sizeof e);
    e.size = sizeof e;
    const int st = bodt_mesh_recovery_error(h, &e);
    if (st != BODT_OK) fail_msg("bodt_mesh_recovery_error: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    return e;
}

/* Distance of p from the line through a with unit direction u. */
static double line_distance(const double *p, const double *a, const double *u) {
    const double d[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double t = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    const double r[3] = {d[0] - t * u[0], d[1] - t * u[1], d[2] - t * u[2]};
    return sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
}

static double plane_distance(const double *p, const double *a, const double *n) {
    return fabs((p[0] - a[0]) * n[0] + (p[1] - a[1]) * n[1] + (p[2] - a[2]) * n[2]);
}

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/* The fitted cylinder: along z through the z axis, of radius r (rel_tol). */
static void expect_z_cylinder(const bodt_shape_fit *fit, double r, double rel_tol, const char *what) {
    if (fit->shape != BODT_SHAPE_CYLINDER) fail_msg("%s: shape %d, not a cylinder", what, fit->shape);
    if (!(fabs(fit->radius - r) <= rel_tol * r))
        fail_msg("%s: radius %.17g, expected %.17g (relative tolerance %g)", what, fit->radius, r, rel_tol);
    if (!(fabs(norm3(fit->axis) - 1.0) <= 1e-12 && fabs(fit->axis[2]) >= 1.0 - 1e-9))
        fail_msg("%s: axis (%.17g %.17g %.17g) is not the unit z", what, fit->axis[0], fit->axis[1], fit->axis[2]);
    const double origin[3] = {0.0, 0.0, 0.0};
    const double off = line_distance(origin, fit->point, fit->axis);
    if (!(off <= 1e-9 * r))
        fail_msg("%s: axis through (%.17g %.17g %.17g), %.3g from the z axis", what, fit->point[0], fit->point[1],
                 fit->point[2], off);
}

/* ------------------------------------------------------------- generator */

static void test_generator(void **state) {
    (void)state;
    const hole_params ps[] = {
        {6, 24, 4, 1.0, 0.3, 0.6}, {2, 16, 3, 1.5, 0.5, 1.0}, {3, 8, 2, 2.0, 1.9, 0.25}, {1, 4, 1, 1.0, 0.5, 1.0},
    };
    for (size_t c = 0; c < sizeof ps / sizeof *ps; ++c) {
        const hole_params *p = &ps[c];
        const test_mesh *m = make_hole(p);
        assert_int_equal(m->nverts, p->nt * (p->nr + 1) * (p->nz + 1));
        assert_int_equal(m->ntets, 6 * p->nr * p->nt * p->nz);
        assert_int_equal(check_faces_paired(m), hole_boundary_faces(p));
        for (int32_t v = 0; v < m->nverts; ++v) {
            const int i = ring_of(p, v), k = layer_of(p, v);
            assert_int_equal(m->boundary[v], i == 0 || i == p->nr || k == 0 || k == p->nz);
        }

        /* plain bodt_mesh_create: no inverted tet to accept */
        bodt_mesh *h = NULL;
        const int st = bodt_mesh_create(m->nverts, m->xyz, m->ntets, m->tets, 0, &h);
        if (st != BODT_OK) fail_msg("create: %s: %s", bodt_status_string(st), bodt_mesh_last_error(NULL));
        cleanup_add(h, destroy_mesh);
        bodt_quality q;
        get_quality(h, &q);
        assert_int_equal(q.num_inverted, 0);
        assert_int_equal(q.num_unused_vertices, 0);
        assert_int_equal(q.num_boundary_faces, hole_boundary_faces(p));
        assert_true(q.min_stretch > 0.0);
        const double hw = p->half_width;
        const double expected = part_volume(p, 4.0 * hw * hw, p->radius);
        assert_near(q.volume, expected, 1e-9 * expected);

        int32_t nv = 0;
        const double *xyz = take_vertices(h, &nv);
        assert_int_equal(nv, m->nverts);
        int32_t corners = 0;
        for (int32_t v = 0; v < nv; ++v) {
            const double *x = P(xyz, v);
            const int i = ring_of(p, v), k = layer_of(p, v);
            const double z = k == p->nz ? p->height : p->height * k / p->nz;
            if (x[2] != z) fail_msg("vertex %d: z %.17g, layer %d at %.17g", v, x[2], k, z);
            if (i == 0) assert_near(hypot(x[0], x[1]), p->radius, 1e-12);
            if (i == p->nr) {
                assert_near(fmax(fabs(x[0]), fabs(x[1])), hw, 1e-15 * hw);
                corners += fabs(x[0]) == hw && fabs(x[1]) == hw;
                if (angle_of(p, v) % (p->nt / 4) == 0 && !(fabs(x[0]) == hw && fabs(x[1]) == hw))
                    fail_msg("vertex %d (angle %d) is not a corner: (%.17g %.17g)", v, angle_of(p, v), x[0], x[1]);
            }
        }
        assert_int_equal(corners, 4 * (p->nz + 1));
        print_message("box with hole %d x %d x %d: %d vertices, %d tets, volume %.15g, min stretch %.4f\n", p->nr,
                      p->nt, p->nz, m->nverts, m->ntets, q.volume, q.min_stretch);
    }
}

/* ------------------------------------------------------------- deformed */

static void test_deformed(void **state) {
    (void)state;
    const hole_params *p = &kHole;
    const test_mesh *m0 = make_hole(p);
    test_mesh *m = make_deformed(p, kStretch, kNewRadius);
    assert_int_equal(m->nverts, m0->nverts);
    assert_int_equal(m->ntets, m0->ntets);
    assert_memory_equal(m->tets, m0->tets, 4 * (size_t)m->ntets * sizeof(int32_t));
    for (int32_t v = 0; v < m->nverts; ++v) {
        const double *a = P(m0->xyz, v), *b = P(m->xyz, v);
        if (b[2] != a[2]) fail_msg("vertex %d: z moved", v);
        if (ring_of(p, v) == 0) {
            assert_near(hypot(b[0], b[1]), kNewRadius, 1e-12);
            assert_near(b[0] * a[1] - b[1] * a[0], 0.0, 1e-15); /* radially */
            assert_true(b[0] * a[0] + b[1] * a[1] > 0.0);
        } else {
            const double x = a[0] > 0.0 ? a[0] * kStretch : a[0];
            if (b[0] != x || b[1] != a[1])
                fail_msg("vertex %d: (%.17g %.17g) -> (%.17g %.17g)", v, a[0], a[1], b[0], b[1]);
        }
    }
    /* a second call recomputes from the grid: the same mesh */
    double *again = cleanup_calloc(3 * (size_t)m->nverts * sizeof *again);
    memcpy(again, m->xyz, 3 * (size_t)m->nverts * sizeof *again);
    tm_deform_box_with_hole(m, p->nr, p->nt, p->nz, kStretch, kNewRadius, p->half_width, p->radius);
    assert_memory_equal(again, m->xyz, 3 * (size_t)m->nverts * sizeof *again);

    int32_t zero = 0;
    const int32_t inverted = count_inverted(m, &zero);
    assert_int_equal(zero, 0); /* zero-volume tets are refused even with the flag */
    assert_true(inverted > 0);

    bodt_mesh *h = NULL;
    assert_int_equal(bodt_mesh_create(m->nverts, m->xyz, m->ntets, m->tets, 0, &h), BODT_ERR_BAD_MESH);
    assert_null(h);
    assert_true(strlen(bodt_mesh_last_error(NULL)) > 0);
    print_message("deformed: %d of %d tets inverted; bodt_mesh_create: %s\n", inverted, m->ntets,
                  bodt_mesh_last_error(NULL));

    h = create_ok(m, BODT_CREATE_ACCEPT_INVERTED);
    bodt_quality q;
    get_quality(h, &q);
    assert_int_equal(q.num_inverted, inverted);
    assert_true(q.min_stretch < 0.0);
    const double hw = p->half_width;
    const double expected = part_volume(p, (1.0 + kStretch) * 2.0 * hw * hw, kNewRadius);
    assert_near(q.volume, expected, 1e-9 * expected);
}

/* ------------------------------------------------------------- geometry */

/* The class extraction should give vertex v of the undeformed box. */
static int expected_class(const hole_params *p, int32_t v) {
    const int i = ring_of(p, v), k = layer_of(p, v);
    const int cap = k == 0 || k == p->nz;                    /* top or bottom */
    const int edge_dir = angle_of(p, v) % (p->nt / 4) == 0;  /* towards a box corner */
    if (i == 0) return cap ? BODT_GEOMETRY_SHARP_EDGE : BODT_GEOMETRY_SURFACE;
    if (i == p->nr) {
        if (edge_dir) return cap ? BODT_GEOMETRY_CORNER : BODT_GEOMETRY_SHARP_EDGE;
        return cap ? BODT_GEOMETRY_SHARP_EDGE : BODT_GEOMETRY_SURFACE;
    }
    return cap ? BODT_GEOMETRY_SURFACE : BODT_GEOMETRY_INTERIOR;
}

/* Which surface of the part an (undeformed) boundary face is on: 0 the hole,
 * 1 bottom, 2 top, 3 x = +hw, 4 y = +hw, 5 x = -hw, 6 y = -hw. */
static int part_surface(const hole_params *p, const double *xyz, const int32_t *tri) {
    int all_ring0 = 1;
    for (int k = 0; k < 3; ++k) all_ring0 &= ring_of(p, tri[k]) == 0;
    if (all_ring0) return 0;
    const double *a = P(xyz, tri[0]), *b = P(xyz, tri[1]), *c = P(xyz, tri[2]);
    const double hw = p->half_width;
    if (a[2] == 0.0 && b[2] == 0.0 && c[2] == 0.0) return 1;
    if (a[2] == p->height && b[2] == p->height && c[2] == p->height) return 2;
    if (a[0] == hw && b[0] == hw && c[0] == hw) return 3;
    if (a[1] == hw && b[1] == hw && c[1] == hw) return 4;
    if (a[0] == -hw && b[0] == -hw && c[0] == -hw) return 5;
    if (a[1] == -hw && b[1] == -hw && c[1] == -hw) return 6;
    fail_msg("boundary face (%d %d %d) is on no surface of the part", tri[0], tri[1], tri[2]);
    return -1;
}

static void test_geometry(void **state) {
    (void)state;
    const hole_params *p = &kHole;
    const test_mesh *m = make_hole(p);
    bodt_mesh *h = create_ok(m, 0);

    int32_t nregions = -1, nchains = -1;
    const int st = bodt_mesh_get_geometry_counts(h, &nregions, &nchains);
    if (st != BODT_OK)
        fail_msg("bodt_mesh_get_geometry_counts: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    print_message("geometry: %d regions, %d chains\n", nregions, nchains);
    /* 4 sides, top, bottom, the hole; 4 + 4 square edges, 4 vertical
     * edges, the hole's 2 circles (loops without corners) */
    assert_int_equal(nregions, 7);
    assert_int_equal(nchains, 14);

    int32_t *classes = cleanup_calloc((size_t)m->nverts * sizeof *classes);
    assert_int_equal(bodt_mesh_get_geometry_classes(h, classes, (size_t)m->nverts), BODT_OK);
    int32_t corners = 0;
    for (int32_t v = 0; v < m->nverts; ++v) {
        corners += classes[v] == BODT_GEOMETRY_CORNER;
        const int want = expected_class(p, v);
        if (classes[v] != want)
            fail_msg("vertex %d (ring %d, angle %d, layer %d): class %d, expected %d", v, ring_of(p, v), angle_of(p, v),
                     layer_of(p, v), classes[v], want);
    }
    assert_int_equal(corners, 8);

    const faces f = take_faces(h);
    assert_int_equal(f.nb, hole_boundary_faces(p));
    int32_t region_of_surface[7];
    for (int s = 0; s < 7; ++s) region_of_surface[s] = -1;
    for (int32_t k = 0; k < f.nb; ++k) {
        const int32_t *tri = &f.tri[3 * k];
        const int s = part_surface(p, m->xyz, tri);
        const int32_t r = f.region[k];
        if (r < 0 || r >= nregions) fail_msg("face %d: region %d of %d", k, r, nregions);
        if (region_of_surface[s] < 0) region_of_surface[s] = r;
        if (region_of_surface[s] != r)
            fail_msg("face (%d %d %d) of surface %d in region %d, other faces there in %d", tri[0], tri[1], tri[2], s,
                     r, region_of_surface[s]);
        const int want = s == 0 ? BODT_SHAPE_CYLINDER : BODT_SHAPE_PLANE;
        if (f.shape[k] != want)
            fail_msg("face (%d %d %d) of surface %d: shape %d", tri[0], tri[1], tri[2], s, f.shape[k]);
    }
    for (int s = 0; s < 7; ++s) {
        assert_true(region_of_surface[s] >= 0);
        for (int t = 0; t < s; ++t)
            if (region_of_surface[s] == region_of_surface[t])
                fail_msg("surfaces %d and %d share region %d", t, s, region_of_surface[s]);
    }

    /* the fitted shapes */
    const bodt_shape_fit hole = region_shape(h, region_of_surface[0]);
    expect_z_cylinder(&hole, p->radius, 1e-9, "hole");
    assert_true(hole.max_error <= 1e-9 * p->radius);
    /* no reference mesh: the acceptable error is the mesh's own, the
     * sagitta of a chord of 2 pi / nt */
    const double sagitta = p->radius * (1.0 - cos(acos(-1.0) / p->nt));
    if (!(fabs(hole.acceptable_error - sagitta) <= 1e-9 * p->radius))
        fail_msg("hole acceptable error %.17g, want the sagitta %.17g", hole.acceptable_error, sagitta);
    const double hw = p->half_width;
    const struct {
        int axis;
        double at;
    } planes[6] = {{2, 0.0}, {2, p->height}, {0, hw}, {1, hw}, {0, -hw}, {1, -hw}};
    for (int s = 1; s < 7; ++s) {
        const bodt_shape_fit fit = region_shape(h, region_of_surface[s]);
        if (fit.shape != BODT_SHAPE_PLANE) fail_msg("surface %d: shape %d, not a plane", s, fit.shape);
        const int a = planes[s - 1].axis;
        if (!(fabs(norm3(fit.axis) - 1.0) <= 1e-12 && fabs(fit.axis[a]) >= 1.0 - 1e-12))
            fail_msg("surface %d: normal (%.17g %.17g %.17g)", s, fit.axis[0], fit.axis[1], fit.axis[2]);
        assert_near(fit.point[a], planes[s - 1].at, 1e-12);
        assert_true(fit.max_error <= 1e-12);
    }
}

/* ------------------------------------------------------------- recovery */

static void test_recovery(void **state) {
    (void)state;
    const hole_params *p = &kHole;
    const test_mesh *m0 = make_hole(p);
    const test_mesh *m = make_deformed(p, kStretch, kNewRadius);
    bodt_mesh *ref = NULL;
    assert_int_equal(bodt_mesh_create(m0->nverts, m0->xyz, m0->ntets, m0->tets, 0, &ref), BODT_OK);
    bodt_mesh *h = create_ok(m, BODT_CREATE_ACCEPT_INVERTED);
    bodt_quality q0, q1;
    get_quality(h, &q0);
    assert_true(q0.num_inverted > 0);

    int st = bodt_set_reference_mesh(h, ref);
    bodt_mesh_destroy(ref); /* read, not kept */
    if (st != BODT_OK) fail_msg("bodt_set_reference_mesh: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    st = bodt_set_mode(h, BODT_MODE_PHASED_ODT);
    if (st != BODT_OK) fail_msg("bodt_set_mode(PHASED_ODT): %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    const bodt_recovery_error e0 = recovery(h);
    assert_true(e0.density_edges > 0);
    assert_true(e0.density_mean > 0.0);

    step_totals t = {0, 0, 0, 0, 0};
    st = bodt_run(h, 30, add_step_report, &t);
    if (st != BODT_OK) fail_msg("bodt_run: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    get_quality(h, &q1);
    const bodt_recovery_error e1 = recovery(h);
    print_message("recovery: %d steps, %d moves, %d flips, %d inserted, %d collapsed; inverted %d -> %d, min stretch "
                  "%.4f -> %.4f, mean %.4f -> %.4f; density error mean %.4f -> %.4f (max %.3f -> %.3f); geometric "
                  "error mean %.3g -> %.3g\n",
                  t.steps, t.moved, t.flips, t.inserted, t.collapsed, q0.num_inverted, q1.num_inverted,
                  q0.min_stretch, q1.min_stretch, q0.mean_stretch, q1.mean_stretch, e0.density_mean, e1.density_mean,
                  e0.density_max, e1.density_max, e0.geometric_mean, e1.geometric_mean);
    assert_int_equal(q1.num_inverted, 0);
    assert_true(q1.min_stretch > 0.0);

    /* the test's own look at the result */
    int32_t nv = 0, nt = 0;
    assert_int_equal(bodt_mesh_get_counts(h, &nv, &nt, NULL), BODT_OK);
    const double *xyz = take_vertices(h, &nv);
    int32_t *tets = cleanup_calloc(4 * (size_t)nt * sizeof *tets);
    assert_int_equal(bodt_mesh_get_tets(h, tets, 4 * (size_t)nt), BODT_OK);
    for (int32_t k = 0; k < nt; ++k) {
        const int32_t *q = &tets[4 * k];
        if (!(tm_orient6(P(xyz, q[0]), P(xyz, q[1]), P(xyz, q[2]), P(xyz, q[3])) > 0.0))
            fail_msg("tet %d (%d %d %d %d) not positive", k, q[0], q[1], q[2], q[3]);
    }
    const double hw = p->half_width, tol = 1e-9;
    /* vertices an operation removed keep their index, unused (bodt.h) */
    unsigned char *used = cleanup_calloc((size_t)nv);
    for (int64_t k = 0; k < 4 * (int64_t)nt; ++k) used[tets[k]] = 1;
    for (int32_t v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        const double *x = P(xyz, v);
        if (!(x[0] >= -hw - tol && x[0] <= kStretch * hw + tol && fabs(x[1]) <= hw + tol && x[2] >= -tol &&
              x[2] <= p->height + tol && hypot(x[0], x[1]) >= 0.9 * kNewRadius))
            fail_msg("vertex %d (%.17g %.17g %.17g) is outside the part", v, x[0], x[1], x[2]);
    }

    /* the hole: its faces' vertices on the fitted cylinder, of the new
     * radius; the other regions' vertices on their planes */
    const faces f = take_faces(h);
    int32_t hole_region = -1, hole_faces = 0;
    for (int32_t k = 0; k < f.nb; ++k) {
        if (f.shape[k] != BODT_SHAPE_CYLINDER) continue;
        ++hole_faces;
        if (hole_region < 0) hole_region = f.region[k];
        if (f.region[k] != hole_region) fail_msg("two cylindrical regions: %d and %d", hole_region, f.region[k]);
    }
    assert_true(hole_faces > 0);
    int32_t *classes = cleanup_calloc((size_t)nv * sizeof *classes);
    assert_int_equal(bodt_mesh_get_geometry_classes(h, classes, (size_t)nv), BODT_OK);
    int32_t on_circles = 0;
    for (int32_t k = 0; k < f.nb; ++k) {
        if (f.shape[k] != BODT_SHAPE_CYLINDER) continue;
        for (int c = 0; c < 3; ++c) {
            const int32_t cl = classes[f.tri[3 * k + c]];
            if (cl != BODT_GEOMETRY_SURFACE && cl != BODT_GEOMETRY_SHARP_EDGE)
                fail_msg("hole vertex %d: geometry class %d", f.tri[3 * k + c], cl);
            on_circles += cl == BODT_GEOMETRY_SHARP_EDGE;
        }
    }
    assert_true(on_circles > 0); /* the hole's top and bottom circles */
    const bodt_shape_fit hole = region_shape(h, hole_region);
    expect_z_cylinder(&hole, kNewRadius, 1e-6, "hole after the run");
    double worst_cyl = 0.0, worst_plane = 0.0;
    for (int32_t k = 0; k < f.nb; ++k) {
        const int32_t *tri = &f.tri[3 * k];
        if (f.shape[k] == BODT_SHAPE_CYLINDER) {
            for (int c = 0; c < 3; ++c) {
                const double d = fabs(line_distance(P(xyz, tri[c]), hole.point, hole.axis) - hole.radius);
                if (d > worst_cyl) worst_cyl = d;
                if (!(d <= 1e-9 * kNewRadius))
                    fail_msg("hole vertex %d (%.17g %.17g %.17g) is %.3g off the cylinder", tri[c], P(xyz, tri[c])[0],
                             P(xyz, tri[c])[1], P(xyz, tri[c])[2], d);
            }
        } else if (f.shape[k] == BODT_SHAPE_PLANE) {
            const bodt_shape_fit fit = region_shape(h, f.region[k]);
            for (int c = 0; c < 3; ++c) {
                const double d = plane_distance(P(xyz, tri[c]), fit.point, fit.axis);
                if (d > worst_plane) worst_plane = d;
                if (!(d <= 1e-9)) fail_msg("vertex %d is %.3g off the plane of region %d", tri[c], d, f.region[k]);
            }
        } else {
            fail_msg("face %d: shape %d (neither plane nor cylinder)", k, f.shape[k]);
        }
    }
    print_message("recovery: %d vertices, %d tets; hole radius %.12g, worst vertex off the cylinder %.3g, off a plane "
                  "%.3g\n",
                  nv, nt, hole.radius, worst_cyl, worst_plane);
    assert_true(e1.density_mean < e0.density_mean);
}

/* ------------------------------------------------------------- bad input */

typedef struct dparam {
    int key;
    const char *name;
    double def, good[3], bad[5];
    int nbad;
} dparam;

static void test_bad_input(void **state) {
    (void)state;
    const hole_params small = {2, 8, 2, 1.0, 0.4, 0.5};
    const hole_params other = {3, 8, 2, 1.0, 0.4, 0.5};
    const test_mesh *m = make_hole(&small);
    const test_mesh *mo = make_hole(&other);
    bodt_mesh *h = create_ok(m, 0);
    bodt_mesh *ho = create_ok(mo, 0);
    const int E = BODT_ERR_INVALID_ARGUMENT;
    int32_t iv = 0;
    double dv = 0.0;
    int mode = 0;

    /* the mode */
    int st = bodt_set_mode(h, BODT_MODE_PHASED_ODT);
    if (st != BODT_OK) fail_msg("bodt_set_mode(PHASED_ODT): %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    assert_int_equal(bodt_get_mode(h, &mode), BODT_OK);
    assert_int_equal(mode, 6);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, &iv), BODT_OK);
    assert_int_equal(iv, BODT_OPS_MODE_DEFAULT);
    assert_int_equal(bodt_set_mode(h, 8), E);
    assert_int_equal(bodt_get_mode(h, &mode), BODT_OK);
    assert_int_equal(mode, BODT_MODE_PHASED_ODT);

    /* the new params: documented defaults, ranges, values kept on refusal */
    const dparam ds[] = {
        {BODT_PARAM_ODT_STEP, "BODT_PARAM_ODT_STEP", 1.0, {1.0, 1e-9, 0.5}, {0.0, 1.5, -0.5, NAN, INFINITY}, 5},
        {BODT_PARAM_DENSITY_SPLIT, "BODT_PARAM_DENSITY_SPLIT", 2.0 / 3.0, {1e-9, 0.999, 0.5}, {1.0, 0.0, -0.1, NAN}, 4},
        {BODT_PARAM_DENSITY_COLLAPSE, "BODT_PARAM_DENSITY_COLLAPSE", 1.5, {100.0, 1.000001, 2.0},
         {0.9, 1.0, 100.5, NAN, INFINITY}, 5},
        {BODT_PARAM_FIT_TOLERANCE, "BODT_PARAM_FIT_TOLERANCE", 1e-5, {0.1, 1e-9, 0.01}, {0.0, -1e-3, 0.2, NAN}, 4},
    };
    for (size_t k = 0; k < sizeof ds / sizeof *ds; ++k) {
        const dparam *p = &ds[k];
        st = bodt_get_param_double(h, p->key, &dv);
        if (st != BODT_OK) fail_msg("%s: get: %s: %s", p->name, bodt_status_string(st), bodt_mesh_last_error(h));
        if (!(fabs(dv - p->def) <= 1e-15 * p->def))
            fail_msg("%s: default %.17g, documented %.17g", p->name, dv, p->def);
        for (int g = 0; g < 3; ++g) {
            if (bodt_set_param_double(h, p->key, p->good[g]) != BODT_OK)
                fail_msg("%s = %.17g refused: %s", p->name, p->good[g], bodt_mesh_last_error(h));
            assert_int_equal(bodt_get_param_double(h, p->key, &dv), BODT_OK);
            assert_true(dv == p->good[g]);
        }
        for (int b = 0; b < p->nbad; ++b) {
            if (bodt_set_param_double(h, p->key, p->bad[b]) != E) fail_msg("%s = %g taken", p->name, p->bad[b]);
            assert_contains(bodt_mesh_last_error(h), p->name);
            assert_int_equal(bodt_get_param_double(h, p->key, &dv), BODT_OK);
            assert_true(dv == p->good[2]); /* kept */
        }
        assert_int_equal(bodt_set_param_int(h, p->key, 1), E); /* the wrong type */
        assert_contains(bodt_mesh_last_error(h), p->name);
        assert_int_equal(bodt_set_param_double(h, p->key, p->def), BODT_OK);
    }


    /* no target density yet: no edges measured */
    bodt_recovery_error e = recovery(h);
    assert_int_equal(e.density_edges, 0);

    /* a reference with another vertex count */
    st = bodt_set_reference_mesh(h, ho);
    print_message("reference of %d vertices for a mesh of %d: %s (%s)\n", mo->nverts, m->nverts, bodt_status_string(st),
                  bodt_mesh_last_error(h));
    assert_true(st == BODT_ERR_INVALID_ARGUMENT || st == BODT_ERR_BAD_MESH);
    assert_true(strlen(bodt_mesh_last_error(h)) > 0);
    e = recovery(h);
    assert_int_equal(e.density_edges, 0); /* nothing set */
    assert_int_equal(bodt_set_reference_mesh(NULL, ho), E);
    assert_int_equal(bodt_set_reference_mesh(h, NULL), BODT_OK); /* clears */
    assert_string_equal(bodt_mesh_last_error(h), "");

    /* target density grids */
    const double origin[3] = {-1.5, -1.5, -0.5};
    const double spacing[3] = {0.5, 0.5, 0.5};
    const int32_t dims[3] = {7, 7, 4};
    double *values = cleanup_calloc(7 * 7 * 4 * sizeof *values);
    for (int k = 0; k < 7 * 7 * 4; ++k) values[k] = 5.0;
    const int32_t one[3] = {1, 1, 1};
    st = bodt_set_target_density(h, origin, spacing, one, values);
    assert_true(st != BODT_OK);
    print_message("a grid of one point: %s (%s)\n", bodt_status_string(st), bodt_mesh_last_error(h));
    assert_true(strlen(bodt_mesh_last_error(h)) > 0);
    const double nan_spacing[3] = {0.5, NAN, 0.5};
    st = bodt_set_target_density(h, origin, nan_spacing, dims, values);
    assert_true(st != BODT_OK);
    assert_true(strlen(bodt_mesh_last_error(h)) > 0);
    const double zero_spacing[3] = {0.5, 0.5, 0.0};
    assert_true(bodt_set_target_density(h, origin, zero_spacing, dims, values) != BODT_OK);
    assert_int_equal(bodt_set_target_density(NULL, origin, spacing, dims, values), E);
    e = recovery(h);
    assert_int_equal(e.density_edges, 0); /* the refused grids left nothing */
    st = bodt_set_target_density(h, origin, spacing, dims, values);
    if (st != BODT_OK) fail_msg("a good grid refused: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    e = recovery(h);
    assert_true(e.density_edges > 0);
    assert_int_equal(bodt_set_target_density(h, origin, spacing, dims, NULL), BODT_OK); /* clears */
    e = recovery(h);
    assert_int_equal(e.density_edges, 0);

    /* getters: NULL handle, bad region, small capacity */
    int32_t nregions = 0;
    assert_int_equal(bodt_mesh_get_geometry_counts(NULL, &nregions, NULL), E);
    assert_int_equal(bodt_mesh_get_geometry_counts(h, &nregions, NULL), BODT_OK);
    assert_true(nregions > 0);
    bodt_shape_fit fit;
    memset(&fit, 0, sizeof fit);
    fit.size = sizeof fit;
    assert_int_equal(bodt_mesh_get_region_shape(h, -1, &fit), E);
    assert_int_equal(bodt_mesh_get_region_shape(h, nregions, &fit), E);
    assert_int_equal(bodt_mesh_get_region_shape(h, 0, NULL), E);
    int32_t *classes = cleanup_calloc((size_t)m->nverts * sizeof *classes);
    assert_int_equal(bodt_mesh_get_geometry_classes(h, classes, (size_t)m->nverts - 1), E);
    assert_int_equal(bodt_mesh_recovery_error(h, NULL), E);
}

/* ------------------------------------------------------------- density grid */

static void test_density_grid(void **state) {
    (void)state;
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_non_null(m);
    assert_int_equal(tm_make_box(m, 6, 0.0, 1), 0);
    bodt_mesh *h = create_ok(m, 0);
    int st = bodt_set_mode(h, BODT_MODE_PHASED_ODT);
    if (st != BODT_OK) fail_msg("bodt_set_mode(PHASED_ODT): %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));

    /* density 1 / h = 6 on the grid's axis edges: ask for twice that,
     * on a grid reaching past the unit box */
    const double target = 2.0 * 6.0;
    const double origin[3] = {-0.25, -0.25, -0.25};
    const double spacing[3] = {0.25, 0.25, 0.25};
    const int32_t dims[3] = {7, 7, 7};
    double *values = cleanup_calloc(7 * 7 * 7 * sizeof *values);
    for (int k = 0; k < 7 * 7 * 7; ++k) values[k] = target;
    st = bodt_set_target_density(h, origin, spacing, dims, values);
    if (st != BODT_OK) fail_msg("bodt_set_target_density: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
    const bodt_recovery_error e0 = recovery(h);
    assert_true(e0.density_edges > 0);
    assert_true(e0.density_mean >= 0.5 - 1e-12); /* every edge at most half as dense as asked */

    step_totals t = {0, 0, 0, 0, 0};
    for (int s = 0; s < 3; ++s) {
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        st = bodt_step(h, &r);
        if (st != BODT_OK) fail_msg("bodt_step: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
        add_step_report(&r, &t);
    }
    bodt_quality q;
    get_quality(h, &q);
    const bodt_recovery_error e1 = recovery(h);
    print_message("density grid: %d -> %d vertices, %d inserted, %d collapsed; density error mean %.4f -> %.4f, max "
                  "%.3f -> %.3f; min stretch %.4f\n",
                  m->nverts, q.num_vertices, t.inserted, t.collapsed, e0.density_mean, e1.density_mean, e0.density_max,
                  e1.density_max, q.min_stretch);
    assert_true(q.num_vertices > m->nverts);
    assert_true(e1.density_mean < e0.density_mean);
    assert_int_equal(q.num_inverted, 0);
    assert_near(q.volume, 1.0, 1e-12);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_generator, cleanup_teardown),
        cmocka_unit_test_teardown(test_deformed, cleanup_teardown),
        cmocka_unit_test_teardown(test_geometry, cleanup_teardown),
        cmocka_unit_test_teardown(test_recovery, cleanup_teardown),
        cmocka_unit_test_teardown(test_bad_input, cleanup_teardown),
        cmocka_unit_test_teardown(test_density_grid, cleanup_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
