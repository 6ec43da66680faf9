/*
 * test_curve_order: the internal order (issue 9).  By default the library
 * stores vertices and tets along a Hilbert curve; BODT_CREATE_KEEP_ORDER
 * stores them as given.  The caller must not be able to tell the two apart
 * through the API, except by speed.  Through libbodt.so only.
 *
 *   same view       a jittered box and a ball (two regions, face markers,
 *                   fixed vertices, corners, vertex refs, feature edges),
 *                   as generated and randomly renumbered: every getter gives
 *                   the same arrays with and without KEEP_ORDER, and the
 *                   renumbered input comes back exactly as given
 *   same smoothing  BODT_PARAM_OPS = BODT_OP_SMOOTH in laplace, odt,
 *                   bodt-basic, bodt (also with feature lines found by
 *                   tensor voting), opt-weighted and nodt: the same step
 *                   reports and vertices, bit for bit, in either order, for
 *                   the generated and the renumbered meshes
 *   one-based       index round trips in base 1: tets (also negatively
 *                   oriented), regions, fixed vertices, corners, refs, faces,
 *                   feature edges, parents, origins; messages naming the
 *                   caller's vertices and tets, also for a refused create
 *   connectivity    the default ops (flips, insertion), and one step of
 *                   flips and insertion alone, on a renumbered bad mesh in
 *                   two regions: a valid mesh, faces outward, fixed vertices
 *                   kept at their index, every tet in its origin's region,
 *                   made vertices where their parents' weights put them
 *   files           a renumbered mesh written with and without KEEP_ORDER
 *                   gives the same file; read back (both ways) it is the
 *                   caller's mesh
 *   reference       bodt_set_reference_mesh between handles stored in
 *                   different orders: the same recovery errors
 */
#include "api_checks.h"
#include "bodt.h"
#include "cleanup.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

#ifndef BODT_TEST_CURVE_DIR
#error "define BODT_TEST_CURVE_DIR (a writable directory for test files)"
#endif

#define STEPS 3

/* ------------------------------------------------------------- meshes */

static test_mesh *new_mesh(void) {
    test_mesh *m = cleanup_add(calloc(1, sizeof *m), cleanup_free_test_mesh);
    assert_non_null(m);
    return m;
}

static test_mesh *jittered_box(int n, double jitter) {
    test_mesh *m = new_mesh();
    for (uint64_t seed = 1; seed < 100; ++seed)
        if (tm_make_box(m, n, jitter, seed) == 0) return m;
    fail_msg("no valid %d^3 box with jitter %g", n, jitter);
    return NULL;
}

static test_mesh *jittered_ball(void) {
    test_mesh *m = new_mesh();
    for (uint64_t seed = 1; seed < 100; ++seed) {
        if (tm_make_cubes(m, 6, 2.0, NULL, NULL, 0.2, seed) != 0) continue;
        if (tm_map_cube_to_ball(m) == 0) return m;
        tm_free(m);
    }
    fail_msg("no valid jittered ball");
    return NULL;
}

/* A uniform index in [0, n). */
static int32_t draw(tm_rng *rng, int32_t n) { return (int32_t)(tm_rng_uniform(rng) * n); }

/* m with its vertices and tets renumbered at random (each tet keeps its
 * vertex order, so its orientation): vertex v of m is vertex vperm[v] of
 * the result, tet t is tet tperm[t]. */
static test_mesh *renumbered(const test_mesh *m, uint64_t seed) {
    test_mesh *r = new_mesh();
    r->nverts = m->nverts;
    r->ntets = m->ntets;
    r->xyz = malloc(3 * (size_t)m->nverts * sizeof *r->xyz);
    r->tets = malloc(4 * (size_t)m->ntets * sizeof *r->tets);
    r->boundary = malloc((size_t)m->nverts);
    int32_t *vperm = cleanup_calloc((size_t)m->nverts * sizeof *vperm);
    int32_t *tperm = cleanup_calloc((size_t)m->ntets * sizeof *tperm);
    assert_true(r->xyz && r->tets && r->boundary);
    tm_rng rng;
    tm_rng_seed(&rng, seed);
    for (int32_t i = 0; i < m->nverts; ++i) vperm[i] = i;
    for (int32_t i = m->nverts - 1; i > 0; --i) {
        const int32_t j = draw(&rng, i + 1), x = vperm[i];
        vperm[i] = vperm[j];
        vperm[j] = x;
    }
    for (int32_t i = 0; i < m->ntets; ++i) tperm[i] = i;
    for (int32_t i = m->ntets - 1; i > 0; --i) {
        const int32_t j = draw(&rng, i + 1), x = tperm[i];
        tperm[i] = tperm[j];
        tperm[j] = x;
    }
    for (int32_t v = 0; v < m->nverts; ++v) {
        memcpy(&r->xyz[3 * (size_t)vperm[v]], &m->xyz[3 * (size_t)v], 3 * sizeof *r->xyz);
        r->boundary[vperm[v]] = m->boundary[v];
    }
    for (int32_t t = 0; t < m->ntets; ++t)
        for (int k = 0; k < 4; ++k) r->tets[4 * (size_t)tperm[t] + k] = vperm[m->tets[4 * (size_t)t + k]];
    return r;
}

static void destroy_mesh(void *h) { bodt_mesh_destroy(h); }

/* A handle on m in base `base`, with `flags`, destroyed at teardown. */
static bodt_mesh *create(const test_mesh *m, int base, uint32_t flags) {
    int32_t *tets = cleanup_calloc(4 * (size_t)m->ntets * sizeof *tets);
    for (size_t k = 0; k < 4 * (size_t)m->ntets; ++k) tets[k] = m->tets[k] + base;
    bodt_mesh *h = NULL;
    if (bodt_mesh_create_ex(m->nverts, m->xyz, m->ntets, tets, base, flags, &h) != BODT_OK)
        fail_msg("create (flags %u): %s", flags, bodt_mesh_last_error(NULL));
    return cleanup_add(h, destroy_mesh);
}

/* ------------------------------------------------------- decorations */

/* What the tests set on a handle, in the caller's numbering (0-based). */
typedef struct extras {
    int32_t *regions;
    int32_t nfaces, *faces, *markers;
    int32_t nfixed, fixed[3];
    int32_t ncorners, corners[2];
    int32_t *refs;
    int32_t nedges, edges[4], edge_refs[2];
} extras;

static double centroid_x(const test_mesh *m, int32_t t) {
    double x = 0.0;
    for (int k = 0; k < 4; ++k) x += m->xyz[3 * (size_t)m->tets[4 * (size_t)t + k]];
    return x / 4.0;
}

enum { NINNER = 6 }; /* marked faces inside a region */

/* Two regions split at the mean x; the boundary faces of a handle on m
 * (KEEP_ORDER) each marked 1 + f % 3, and NINNER faces of tets inside, away
 * from the split, marked 9 (their orientation follows the caller's tet
 * order); three fixed vertices; two boundary corners; refs v % 5; the
 * first edges of two boundary faces as feature edges with refs 10, 11. */
static extras make_extras(const test_mesh *m) {
    extras e;
    memset(&e, 0, sizeof e);
    double mid = 0.0;
    for (int32_t v = 0; v < m->nverts; ++v) mid += m->xyz[3 * (size_t)v] / m->nverts;
    e.regions = cleanup_calloc((size_t)m->ntets * sizeof *e.regions);
    for (int32_t t = 0; t < m->ntets; ++t) e.regions[t] = centroid_x(m, t) > mid ? 2 : 1;

    bodt_mesh *h = create(m, 0, BODT_CREATE_KEEP_ORDER);
    int32_t nb = 0;
    assert_int_equal(bodt_mesh_get_counts(h, NULL, NULL, &nb), BODT_OK);
    e.faces = cleanup_calloc(3 * ((size_t)nb + NINNER) * sizeof *e.faces);
    e.markers = cleanup_calloc(((size_t)nb + NINNER) * sizeof *e.markers);
    assert_int_equal(bodt_mesh_get_boundary_faces(h, e.faces, NULL, (size_t)nb), BODT_OK);
    for (int32_t f = 0; f < nb; ++f) e.markers[f] = 1 + f % 3;
    e.nfaces = nb;
    for (int32_t t = 0; t < m->ntets && e.nfaces < nb + NINNER; t += 3) {
        const int32_t *q = &m->tets[4 * (size_t)t];
        if (m->boundary[q[0]] || m->boundary[q[1]] || m->boundary[q[2]] || m->boundary[q[3]] ||
            fabs(centroid_x(m, t) - mid) < 0.15)
            continue;
        memcpy(&e.faces[3 * (size_t)e.nfaces], &q[1], 3 * sizeof *q);
        e.markers[e.nfaces++] = 9;
    }
    assert_int_equal(e.nfaces, nb + NINNER);

    e.nfixed = 3;
    e.fixed[0] = 0;
    e.fixed[1] = m->nverts / 2;
    e.fixed[2] = m->nverts - 1;
    for (int32_t v = 0; v < m->nverts && e.ncorners < 2; v += 7)
        if (m->boundary[v]) e.corners[e.ncorners++] = v;
    e.refs = cleanup_calloc((size_t)m->nverts * sizeof *e.refs);
    for (int32_t v = 0; v < m->nverts; ++v) e.refs[v] = v % 5;
    e.nedges = 2;
    for (int k = 0; k < 2; ++k) {
        const int32_t *f = &e.faces[3 * (size_t)(k * (nb / 2))];
        e.edges[2 * k] = f[0];
        e.edges[2 * k + 1] = f[1];
        e.edge_refs[k] = 10 + k;
    }
    return e;
}

static void set_extras(bodt_mesh *h, const extras *e) {
    assert_int_equal(bodt_mesh_set_regions(h, e->regions), BODT_OK);
    assert_int_equal(bodt_mesh_set_boundary_faces(h, e->nfaces, e->faces, e->markers), BODT_OK);
    assert_int_equal(bodt_mesh_set_fixed_vertices(h, e->nfixed, e->fixed), BODT_OK);
    assert_int_equal(bodt_mesh_set_corners(h, e->ncorners, e->corners), BODT_OK);
    assert_int_equal(bodt_mesh_set_vertex_refs(h, e->refs), BODT_OK);
    if (bodt_mesh_set_feature_edges_ex(h, e->nedges, e->edges, e->edge_refs) != BODT_OK)
        fail_msg("feature edges: %s", bodt_mesh_last_error(h));
}

/* ------------------------------------------------- what the caller sees */

/* Every array a getter gives (in the handle's base). */
typedef struct view {
    int32_t nv, nt, nb, ne;
    int64_t nparents;
    double *xyz, *quality[4];
    int32_t *tets, *regions, *faces, *markers, *fixed, *corners, *refs, *classes, *edges, *edge_refs, *parents,
        *origins;
    int64_t *offsets;
    double *weights;
} view;

static view take(const bodt_mesh *h) {
    view s;
    memset(&s, 0, sizeof s);
    assert_int_equal(bodt_mesh_get_counts(h, &s.nv, &s.nt, &s.nb), BODT_OK);
    const size_t nv = (size_t)s.nv, nt = (size_t)s.nt, nb = (size_t)s.nb;
    s.xyz = cleanup_calloc(3 * nv * sizeof *s.xyz);
    s.tets = cleanup_calloc(4 * nt * sizeof *s.tets);
    s.regions = cleanup_calloc(nt * sizeof *s.regions);
    s.faces = cleanup_calloc(3 * nb * sizeof *s.faces);
    s.markers = cleanup_calloc(nb * sizeof *s.markers);
    s.fixed = cleanup_calloc(nv * sizeof *s.fixed);
    s.corners = cleanup_calloc(nv * sizeof *s.corners);
    s.refs = cleanup_calloc(nv * sizeof *s.refs);
    s.classes = cleanup_calloc(nv * sizeof *s.classes);
    s.origins = cleanup_calloc(nt * sizeof *s.origins);
    assert_int_equal(bodt_mesh_get_vertices(h, s.xyz, 3 * nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_tets(h, s.tets, 4 * nt), BODT_OK);
    assert_int_equal(bodt_mesh_get_regions(h, s.regions, nt), BODT_OK);
    assert_int_equal(bodt_mesh_get_boundary_faces(h, s.faces, s.markers, nb), BODT_OK);
    assert_int_equal(bodt_mesh_get_fixed_vertices(h, s.fixed, nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_corners(h, s.corners, nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_vertex_refs(h, s.refs, nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_vertex_classes(h, s.classes, nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_tet_origins(h, s.origins, nt), BODT_OK);
    assert_int_equal(bodt_mesh_get_feature_edges_ex(h, &s.ne, NULL, NULL, 0), BODT_OK);
    s.edges = cleanup_calloc(2 * (size_t)s.ne * sizeof *s.edges);
    s.edge_refs = cleanup_calloc((size_t)s.ne * sizeof *s.edge_refs);
    assert_int_equal(bodt_mesh_get_feature_edges_ex(h, &s.ne, s.edges, s.edge_refs, (size_t)s.ne), BODT_OK);
    const int measures[4] = {BODT_MEASURE_MIN_DIHEDRAL, BODT_MEASURE_MAX_DIHEDRAL, BODT_MEASURE_STRETCH,
                             BODT_MEASURE_VOLUME};
    for (int k = 0; k < 4; ++k) {
        s.quality[k] = cleanup_calloc(nt * sizeof *s.quality[k]);
        assert_int_equal(bodt_mesh_tet_quality(h, measures[k], s.quality[k], nt), BODT_OK);
    }
    assert_int_equal(bodt_mesh_get_parent_count(h, &s.nparents), BODT_OK);
    s.offsets = cleanup_calloc((nv + 1) * sizeof *s.offsets);
    s.parents = cleanup_calloc((size_t)s.nparents * sizeof *s.parents);
    s.weights = cleanup_calloc((size_t)s.nparents * sizeof *s.weights);
    assert_int_equal(bodt_mesh_get_vertex_parents(h, s.offsets, nv + 1, s.parents, s.weights, (size_t)s.nparents),
                     BODT_OK);
    return s;
}

#define SAME_ARRAY(a, b, n, what, label)                                                   \
    do {                                                                                   \
        if ((n) > 0 && memcmp((a), (b), (size_t)(n) * sizeof *(a)) != 0)                  \
            fail_msg("%s: %s differ between the internal orders", (label), (what));        \
    } while (0)

/* a and b, of the same mesh stored in two orders, look the same. */
static void assert_same_view(const view *a, const view *b, const char *label) {
    assert_int_equal(a->nv, b->nv);
    assert_int_equal(a->nt, b->nt);
    assert_int_equal(a->nb, b->nb);
    assert_int_equal(a->ne, b->ne);
    assert_true(a->nparents == b->nparents);
    SAME_ARRAY(a->xyz, b->xyz, 3 * a->nv, "vertices", label);
    SAME_ARRAY(a->tets, b->tets, 4 * a->nt, "tets", label);
    SAME_ARRAY(a->regions, b->regions, a->nt, "regions", label);
    SAME_ARRAY(a->faces, b->faces, 3 * a->nb, "boundary faces", label);
    SAME_ARRAY(a->markers, b->markers, a->nb, "face markers", label);
    SAME_ARRAY(a->fixed, b->fixed, a->nv, "fixed vertices", label);
    SAME_ARRAY(a->corners, b->corners, a->nv, "corners", label);
    SAME_ARRAY(a->refs, b->refs, a->nv, "vertex refs", label);
    SAME_ARRAY(a->classes, b->classes, a->nv, "vertex classes", label);
    SAME_ARRAY(a->origins, b->origins, a->nt, "tet origins", label);
    SAME_ARRAY(a->edges, b->edges, 2 * a->ne, "feature edges", label);
    SAME_ARRAY(a->edge_refs, b->edge_refs, a->ne, "feature edge refs", label);
    for (int k = 0; k < 4; ++k) SAME_ARRAY(a->quality[k], b->quality[k], a->nt, "per-tet quality", label);
    SAME_ARRAY(a->offsets, b->offsets, a->nv + 1, "parent offsets", label);
    SAME_ARRAY(a->parents, b->parents, a->nparents, "parents", label);
    SAME_ARRAY(a->weights, b->weights, a->nparents, "parent weights", label);
}

static void assert_same_report(const bodt_step_report *a, const bodt_step_report *b, const char *label, int step) {
    if (a->vertices_moved != b->vertices_moved || a->moves_rejected != b->moves_rejected ||
        a->moves_shortened != b->moves_shortened || a->not_positive_definite != b->not_positive_definite ||
        a->flips != b->flips || a->vertices_inserted != b->vertices_inserted ||
        a->edges_collapsed != b->edges_collapsed || a->max_move != b->max_move ||
        a->min_dihedral != b->min_dihedral || a->max_dihedral != b->max_dihedral ||
        a->min_stretch != b->min_stretch)
        fail_msg("%s, step %d: reports differ between the internal orders (moved %d vs %d, max move %.17g vs %.17g, "
                 "min angle %.17g vs %.17g)",
                 label, step, a->vertices_moved, b->vertices_moved, a->max_move, b->max_move, a->min_dihedral,
                 b->min_dihedral);
}

/* ------------------------------------------------------------ the tests */

/* The feature angle 100 leaves the box's edges to tensor voting, whose
 * directions the feature-line moves then take. */
static const struct {
    int mode;
    const char *name;
    double feature_angle; /* 0: the default */
} smoothing_modes[] = {{BODT_MODE_LAPLACE, "laplace", 0},
                       {BODT_MODE_ODT, "odt", 0},
                       {BODT_MODE_BODT_BASIC, "bodt-basic", 0},
                       {BODT_MODE_BODT, "bodt", 0},
                       {BODT_MODE_BODT, "bodt, lines by tensor voting", 100},
                       {BODT_MODE_OPT_WEIGHTED, "opt-weighted", 0},
                       {BODT_MODE_NODT, "nodt", 0}};

/* m (with its extras) in either order: the same view, and the same STEPS
 * smoothing steps in every mode. */
static void check_same_smoothing(const test_mesh *m, const char *name) {
    const extras e = make_extras(m);
    for (size_t i = 0; i < sizeof smoothing_modes / sizeof smoothing_modes[0]; ++i) {
        char label[96];
        snprintf(label, sizeof label, "%s, %s", name, smoothing_modes[i].name);
        bodt_mesh *keep = create(m, 0, BODT_CREATE_KEEP_ORDER), *curve = create(m, 0, BODT_CREATE_DEFAULT);
        int32_t moved = 0;
        for (int j = 0; j < 2; ++j) {
            bodt_mesh *h = j ? curve : keep;
            set_extras(h, &e);
            assert_int_equal(bodt_set_mode(h, smoothing_modes[i].mode), BODT_OK);
            assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, BODT_OP_SMOOTH), BODT_OK);
            if (smoothing_modes[i].feature_angle > 0)
                assert_int_equal(bodt_set_param_double(h, BODT_PARAM_FEATURE_ANGLE, smoothing_modes[i].feature_angle),
                                 BODT_OK);
        }
        if (i == 0) {
            const view a = take(keep), b = take(curve);
            assert_same_view(&a, &b, name);
            assert_memory_equal(a.xyz, m->xyz, 3 * (size_t)m->nverts * sizeof *m->xyz);
            assert_memory_equal(a.tets, m->tets, 4 * (size_t)m->ntets * sizeof *m->tets);
        }
        for (int k = 0; k < STEPS; ++k) {
            bodt_step_report ra = {.size = sizeof ra}, rb = {.size = sizeof rb};
            if (bodt_step(keep, &ra) != BODT_OK || bodt_step(curve, &rb) != BODT_OK)
                fail_msg("%s: %s / %s", label, bodt_mesh_last_error(keep), bodt_mesh_last_error(curve));
            assert_same_report(&ra, &rb, label, k + 1);
            moved += ra.vertices_moved;
        }
        if (moved == 0) fail_msg("%s: nothing moved: the comparison would prove nothing", label);
        const view a = take(keep), b = take(curve);
        assert_same_view(&a, &b, label);
    }
}

static void test_same_smoothing_as_generated(void **state) {
    (void)state;
    check_same_smoothing(jittered_box(7, 0.25), "box");
    check_same_smoothing(jittered_ball(), "ball");
}

static void test_same_smoothing_renumbered(void **state) {
    (void)state;
    check_same_smoothing(renumbered(jittered_box(7, 0.25), 11), "renumbered box");
    check_same_smoothing(renumbered(jittered_ball(), 12), "renumbered ball");
}

/* Sorted copies of 2-vertex edges, for comparing edge lists. */
static int cmp_pair(const void *x, const void *y) {
    const int32_t *a = x, *b = y;
    return a[0] != b[0] ? (a[0] > b[0]) - (a[0] < b[0]) : (a[1] > b[1]) - (a[1] < b[1]);
}

static void test_one_based_round_trips(void **state) {
    (void)state;
    const test_mesh *m = renumbered(jittered_box(5, 0.2), 21);
    const int32_t nv = m->nverts, nt = m->ntets;
    bodt_mesh *h = create(m, 1, BODT_CREATE_DEFAULT), *keep = create(m, 1, BODT_CREATE_KEEP_ORDER);
    view s = take(h);
    assert_memory_equal(s.xyz, m->xyz, 3 * (size_t)nv * sizeof *s.xyz);
    for (size_t k = 0; k < 4 * (size_t)nt; ++k) assert_int_equal(s.tets[k], m->tets[k] + 1);
    for (int32_t v = 0; v < nv; ++v) {
        assert_true(s.offsets[v] == v);
        assert_int_equal(s.parents[v], v + 1);
    }
    for (int32_t t = 0; t < nt; ++t) assert_int_equal(s.origins[t], t + 1);
    const view sk = take(keep);
    SAME_ARRAY(s.faces, sk.faces, 3 * s.nb, "boundary faces", "base 1");

    /* Setters take, getters give, the caller's indices. */
    int32_t *regions = cleanup_calloc((size_t)nt * sizeof *regions), *refs = cleanup_calloc((size_t)nv * sizeof *refs);
    for (int32_t t = 0; t < nt; ++t) regions[t] = t % 3;
    for (int32_t v = 0; v < nv; ++v) refs[v] = (7 * v) % 11;
    const int32_t fixed[3] = {1, nv / 3, nv}, corners[2] = {nv / 2, 2};
    assert_int_equal(bodt_mesh_set_regions(h, regions), BODT_OK);
    assert_int_equal(bodt_mesh_set_vertex_refs(h, refs), BODT_OK);
    assert_int_equal(bodt_mesh_set_fixed_vertices(h, 3, fixed), BODT_OK);
    assert_int_equal(bodt_mesh_set_corners(h, 2, corners), BODT_OK);
    int32_t nb = 0;
    assert_int_equal(bodt_mesh_get_counts(h, NULL, NULL, &nb), BODT_OK);
    int32_t *faces = cleanup_calloc(3 * (size_t)nb * sizeof *faces);
    int32_t *markers = cleanup_calloc((size_t)nb * sizeof *markers);
    assert_int_equal(bodt_mesh_get_boundary_faces(h, faces, NULL, (size_t)nb), BODT_OK);
    for (int32_t f = 0; f < nb; ++f) markers[f] = 100 + f;
    assert_int_equal(bodt_mesh_set_boundary_faces(h, nb, faces, markers), BODT_OK);
    int32_t edges[4] = {faces[0], faces[1], faces[3 * (nb - 1) + 2], faces[3 * (nb - 1)]};
    const int32_t edge_refs[2] = {5, 6};
    assert_int_equal(bodt_mesh_set_feature_edges_ex(h, 2, edges, edge_refs), BODT_OK);

    s = take(h);
    assert_memory_equal(s.regions, regions, (size_t)nt * sizeof *regions);
    assert_memory_equal(s.refs, refs, (size_t)nv * sizeof *refs);
    for (int32_t v = 0; v < nv; ++v) {
        assert_int_equal(s.fixed[v], v + 1 == fixed[0] || v + 1 == fixed[1] || v + 1 == fixed[2]);
        assert_int_equal(s.corners[v], v + 1 == corners[0] || v + 1 == corners[1]);
    }
    assert_int_equal(s.ne, 2);
    for (int k = 0; k < 2; ++k)
        if (edges[2 * k] > edges[2 * k + 1]) {
            const int32_t x = edges[2 * k];
            edges[2 * k] = edges[2 * k + 1];
            edges[2 * k + 1] = x;
        }
    int32_t sorted[4];
    memcpy(sorted, edges, sizeof sorted);
    qsort(sorted, 2, 2 * sizeof *sorted, cmp_pair);
    assert_memory_equal(s.edges, sorted, sizeof sorted);
    for (int k = 0; k < 2; ++k) assert_int_equal(s.edge_refs[k], sorted[2 * k] == edges[0] ? 5 : 6);
    /* Every face set before has its marker, in the caller's numbering. */
    for (int32_t f = 0; f < nb; ++f) {
        int found = 0;
        for (int32_t g = 0; g < s.nb && !found; ++g)
            found = memcmp(&s.faces[3 * (size_t)g], &faces[3 * (size_t)f], 3 * sizeof *faces) == 0 &&
                    s.markers[g] == markers[f];
        if (!found)
            fail_msg("face %d (%d %d %d) lost its marker", f + 1, faces[3 * f], faces[3 * f + 1], faces[3 * f + 2]);
    }

    /* Messages name the caller's indices. */
    const int32_t bad_fixed[1] = {0};
    assert_int_equal(bodt_mesh_set_fixed_vertices(h, 1, bad_fixed), BODT_ERR_INVALID_ARGUMENT);
    assert_contains(bodt_mesh_last_error(h), "uses vertex 0");
    int32_t not_face[3] = {m->tets[0] + 1, m->tets[1] + 1, 0};
    for (int32_t v = 0; v < nv && !not_face[2]; ++v) {
        const double *p = &m->xyz[3 * (size_t)v], *q = &m->xyz[3 * (size_t)m->tets[0]];
        if (fabs(p[0] - q[0]) + fabs(p[1] - q[1]) + fabs(p[2] - q[2]) > 0.9) not_face[2] = v + 1;
    }
    assert_int_equal(bodt_mesh_set_boundary_faces(h, 1, not_face, NULL), BODT_ERR_INVALID_ARGUMENT);
    char expect[96];
    snprintf(expect, sizeof expect, "triangle 1 (%d, %d, %d) is not a face", not_face[0], not_face[1], not_face[2]);
    assert_contains(bodt_mesh_last_error(h), expect);

    /* A refused create names the caller's tets, as it does in kept order:
     * tet nt + 1 repeats tet 8. */
    int32_t *tets = cleanup_calloc(4 * ((size_t)nt + 1) * sizeof *tets);
    for (size_t k = 0; k < 4 * (size_t)nt; ++k) tets[k] = m->tets[k] + 1;
    memcpy(&tets[4 * (size_t)nt], &tets[4 * 7], 4 * sizeof *tets);
    bodt_mesh *refused = NULL;
    char kept[256];
    assert_int_equal(bodt_mesh_create_ex(nv, m->xyz, nt + 1, tets, 1, BODT_CREATE_KEEP_ORDER, &refused),
                     BODT_ERR_BAD_MESH);
    snprintf(kept, sizeof kept, "%s", bodt_mesh_last_error(NULL));
    assert_int_equal(bodt_mesh_create(nv, m->xyz, nt + 1, tets, 1, &refused), BODT_ERR_BAD_MESH);
    assert_null(refused);
    assert_string_equal(bodt_mesh_last_error(NULL), kept);
    snprintf(expect, sizeof expect, "tets: 8, ");
    assert_contains(kept, expect);
    snprintf(expect, sizeof expect, " and %d", nt + 1);
    assert_contains(kept, expect);

    /* Negatively oriented input comes back as given. */
    for (int32_t t = 0; t < nt; ++t) {
        const int32_t x = tets[4 * (size_t)t + 2];
        tets[4 * (size_t)t + 2] = tets[4 * (size_t)t + 3];
        tets[4 * (size_t)t + 3] = x;
    }
    bodt_mesh *negative = NULL;
    assert_int_equal(bodt_mesh_create(nv, m->xyz, nt, tets, 1, &negative), BODT_OK);
    cleanup_add(negative, destroy_mesh);
    const view sn = take(negative);
    assert_memory_equal(sn.tets, tets, 4 * (size_t)nt * sizeof *tets);
}

/* 6 times the signed volume of tet q of view s. */
static double volume6(const view *s, const int32_t *q) {
    return tm_orient6(&s->xyz[3 * (size_t)q[0]], &s->xyz[3 * (size_t)q[1]], &s->xyz[3 * (size_t)q[2]],
                      &s->xyz[3 * (size_t)q[3]]);
}

/* The default ops (smoothing, flips, insertion), and flips and insertion
 * alone for one step, where no input vertex moves and a made vertex lies
 * where its parents' weights put it. */
static void test_connectivity_changes(void **state) {
    (void)state;
    test_mesh *g = new_mesh();
    for (uint64_t seed = 1;; ++seed) {
        assert_true(seed < 500);
        if (tm_make_cubes_sliding(g, 5, 1.0, NULL, NULL, NULL, 0.4, 0.4, seed, NULL, NULL) == 0) break;
    }
    const test_mesh *m = renumbered(g, 31);
    const int32_t nv = m->nverts, nt = m->ntets;
    const int32_t fixed[2] = {nv / 4, (3 * nv) / 4};
    int32_t *regions = cleanup_calloc((size_t)nt * sizeof *regions);
    for (int32_t t = 0; t < nt; ++t) regions[t] = centroid_x(m, t) > 0.5;
    for (int j = 0; j < 4; ++j) {
        const int curve = j & 1, smooth = j < 2;
        char name[64];
        snprintf(name, sizeof name, "%s, %s", curve ? "curve order" : "kept order",
                 smooth ? "default ops" : "flips and insertion");
        bodt_mesh *h = create(m, 0, curve ? BODT_CREATE_DEFAULT : BODT_CREATE_KEEP_ORDER);
        assert_int_equal(bodt_mesh_set_fixed_vertices(h, 2, fixed), BODT_OK);
        assert_int_equal(bodt_mesh_set_regions(h, regions), BODT_OK);
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_BAD_ANGLE, 25.0), BODT_OK); /* more insertion */
        if (!smooth) assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, BODT_OP_FLIP | BODT_OP_INSERT), BODT_OK);
        step_totals totals = {0};
        assert_int_equal(bodt_run(h, smooth ? 4 : 1, add_step_report, &totals), BODT_OK);
        if (totals.flips == 0 || totals.inserted == 0)
            fail_msg("%s: %d flips, %d insertions: not both tested", name, totals.flips, totals.inserted);
        const view s = take(h);
        assert_int_equal(s.nv, nv + totals.inserted);
        double volume = 0.0;
        for (int32_t t = 0; t < s.nt; ++t) {
            const int32_t *q = &s.tets[4 * (size_t)t];
            for (int k = 0; k < 4; ++k) assert_true(q[k] >= 0 && q[k] < s.nv);
            const double v6 = volume6(&s, q);
            if (!(v6 > 0.0)) fail_msg("%s: tet %d is inverted or flat (6V = %g)", name, t, v6);
            volume += v6 / 6.0;
            if (s.origins[t] < 0 || s.origins[t] >= nt) fail_msg("%s: tet %d has origin %d", name, t, s.origins[t]);
            if (s.regions[t] != regions[s.origins[t]])
                fail_msg("%s: tet %d is in region %d, its origin %d in %d", name, t, s.regions[t], s.origins[t],
                         regions[s.origins[t]]);
        }
        assert_near(volume, 1.0, 1e-12);
        /* The fixed vertices stay, at their index. */
        for (int k = 0; k < 2; ++k) {
            assert_memory_equal(&s.xyz[3 * (size_t)fixed[k]], &m->xyz[3 * (size_t)fixed[k]], 3 * sizeof *s.xyz);
            assert_int_equal(s.fixed[fixed[k]], 1);
        }
        /* Input vertices are their own parents; made ones interpolate
         * input ones (exactly where no vertex moved after). */
        for (int32_t v = 0; v < s.nv; ++v) {
            double sum = 0.0, at[3] = {0.0, 0.0, 0.0};
            for (int64_t k = s.offsets[v]; k < s.offsets[v + 1]; ++k) {
                assert_true(s.parents[k] >= 0 && s.parents[k] < nv);
                sum += s.weights[k];
                for (int a = 0; a < 3; ++a) at[a] += s.weights[k] * m->xyz[3 * (size_t)s.parents[k] + a];
            }
            assert_near(sum, 1.0, 1e-12);
            if (v < nv) {
                assert_true(s.offsets[v + 1] - s.offsets[v] == 1);
                assert_int_equal(s.parents[s.offsets[v]], v);
            } else if (!smooth) {
                for (int a = 0; a < 3; ++a) assert_near(at[a], s.xyz[3 * (size_t)v + a], 1e-12);
            }
        }
        /* Every boundary face is a face of a tet it points out of, and an
         * interface face points out of the smaller region. */
        for (int32_t f = 0; f < s.nb; ++f) {
            const int32_t *tri = &s.faces[3 * (size_t)f];
            int32_t out_region = -1, in_region = -1;
            for (int32_t t = 0; t < s.nt; ++t) {
                const int32_t *q = &s.tets[4 * (size_t)t];
                int hits = 0, other = -1;
                for (int k = 0; k < 4; ++k) {
                    const int in = q[k] == tri[0] || q[k] == tri[1] || q[k] == tri[2];
                    hits += in;
                    if (!in) other = q[k];
                }
                if (hits < 3) continue;
                const int32_t quad[4] = {tri[0], tri[1], tri[2], other};
                *(volume6(&s, quad) < 0.0 ? &out_region : &in_region) = s.regions[t]; /* opposite vertex inside */
            }
            if (out_region < 0 || (in_region >= 0 && in_region < out_region))
                fail_msg("%s: boundary face %d points out of region %d, into %d", name, f, out_region, in_region);
        }
    }
}

static void write_path(char *path, size_t size, const char *name) {
    if (mkdir(BODT_TEST_CURVE_DIR, 0755) != 0 && errno != EEXIST)
        fail_msg("cannot create %s: %s", BODT_TEST_CURVE_DIR, strerror(errno));
    snprintf(path, size, "%s/%s", BODT_TEST_CURVE_DIR, name);
}

static char *slurp(const char *path, long *size) {
    FILE *f = fopen(path, "rb");
    if (!f) fail_msg("cannot read %s", path);
    fseek(f, 0, SEEK_END);
    *size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = cleanup_calloc((size_t)*size + 1);
    assert_int_equal(fread(text, 1, (size_t)*size, f), (size_t)*size);
    fclose(f);
    return text;
}

static void test_files(void **state) {
    (void)state;
    const test_mesh *m = renumbered(jittered_box(5, 0.2), 41);
    const extras e = make_extras(m);
    char keep_path[256], curve_path[256];
    write_path(keep_path, sizeof keep_path, "keep.mesh");
    write_path(curve_path, sizeof curve_path, "curve.mesh");
    bodt_mesh *keep = create(m, 0, BODT_CREATE_KEEP_ORDER), *curve = create(m, 0, BODT_CREATE_DEFAULT);
    set_extras(keep, &e);
    set_extras(curve, &e);
    assert_int_equal(bodt_mesh_write(keep, keep_path), BODT_OK);
    assert_int_equal(bodt_mesh_write(curve, curve_path), BODT_OK);
    long nk = 0, nc = 0;
    const char *tk = slurp(keep_path, &nk), *tc = slurp(curve_path, &nc);
    if (nk != nc || memcmp(tk, tc, (size_t)nk) != 0) fail_msg("the two orders write different files");

    const view want = take(curve);
    const uint32_t flags[2] = {BODT_CREATE_DEFAULT, BODT_CREATE_KEEP_ORDER};
    for (int j = 0; j < 2; ++j) {
        bodt_mesh *back = NULL;
        if (bodt_mesh_read_ex(curve_path, flags[j], &back) != BODT_OK)
            fail_msg("read %s: %s", curve_path, bodt_mesh_last_error(NULL));
        cleanup_add(back, destroy_mesh);
        const view got = take(back);
        assert_same_view(&want, &got, j ? "read back in kept order" : "read back in curve order");
        assert_memory_equal(got.tets, m->tets, 4 * (size_t)m->ntets * sizeof *m->tets);
    }
}

static void test_reference_mesh(void **state) {
    (void)state;
    /* The reference: the box unjittered, graded along x (so its density
     * varies and a misplaced vertex would show); the mesh: jittered,
     * numbered alike. */
    test_mesh *graded = new_mesh();
    assert_int_equal(tm_make_box(graded, 5, 0.0, 1), 0);
    for (int32_t v = 0; v < graded->nverts; ++v) {
        double *x = &graded->xyz[3 * (size_t)v];
        *x = 0.5 * *x * (1.0 + *x);
    }
    const test_mesh *reference = renumbered(graded, 51), *m = renumbered(jittered_box(5, 0.25), 51);
    bodt_recovery_error err[3];
    const uint32_t orders[3][2] = {{BODT_CREATE_KEEP_ORDER, BODT_CREATE_KEEP_ORDER},
                                   {BODT_CREATE_DEFAULT, BODT_CREATE_DEFAULT},
                                   {BODT_CREATE_DEFAULT, BODT_CREATE_KEEP_ORDER}};
    for (int j = 0; j < 3; ++j) {
        bodt_mesh *h = create(m, 0, orders[j][0]), *r = create(reference, 0, orders[j][1]);
        assert_int_equal(bodt_set_mode(h, BODT_MODE_PHASED_ODT), BODT_OK);
        assert_int_equal(bodt_set_reference_mesh(h, r), BODT_OK);
        memset(&err[j], 0, sizeof err[j]);
        err[j].size = sizeof err[j];
        assert_int_equal(bodt_mesh_recovery_error(h, &err[j]), BODT_OK);
        assert_true(err[j].density_edges > 0);
    }
    for (int j = 1; j < 3; ++j) {
        assert_true(err[j].density_edges == err[0].density_edges);
        assert_near(err[j].density_mean, err[0].density_mean, 1e-12 * err[0].density_mean);
        assert_near(err[j].density_max, err[0].density_max, 1e-12 * err[0].density_max);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_same_smoothing_as_generated, cleanup_teardown),
        cmocka_unit_test_teardown(test_same_smoothing_renumbered, cleanup_teardown),
        cmocka_unit_test_teardown(test_one_based_round_trips, cleanup_teardown),
        cmocka_unit_test_teardown(test_connectivity_changes, cleanup_teardown),
        cmocka_unit_test_teardown(test_files, cleanup_teardown),
        cmocka_unit_test_teardown(test_reference_mesh, cleanup_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
