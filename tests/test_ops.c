/*
 * test_ops: the topology operations of a step (BODT_PARAM_OPS: flips,
 * insertion, collapse; BODT_PARAM_KEEP_SURFACE, BODT_PARAM_BAD_ANGLE) and
 * what the caller sees after the connectivity changed: counts and getters,
 * vertex parents, tet origins, the sized step report.  Through libbodt.so
 * only.
 *
 * The meshes are Kuhn boxes jittered hard (tm_make_cubes_sliding: interior
 * vertices in 3D, face vertices in their face plane, edge vertices along
 * their edge, corners not at all), which makes spades, caps and slivers
 * while the domain stays exactly the box.  Every boundary face gets a marker
 * naming its box side (1 + 2 axis + (high side)), and the interface x = mid
 * of a two-region variant marker 7, so after the steps each marked face can
 * be checked against its plane, and the area of each side summed.  Validity
 * is checked with the test's own orientation test on get_vertices/get_tets.
 *
 *   params        OPS, KEEP_SURFACE, BAD_ANGLE, DELAUNAY_FLIPS: defaults, set/get, range and
 *                 type refusals with a message, refused sets keep the value
 *   default ops   BODT_MODE_BODT, default ops, several bad meshes (some or
 *                 all input vertices fixed, two regions, negatively oriented
 *                 input, no smoothing): after every step no inverted tet,
 *                 volume (and region volumes) to 1e-12, every marked face on
 *                 its plane and outward, area per marker kept, fixed vertices
 *                 bit for bit, counts = input + inserted, report consistent
 *                 with bodt_mesh_quality, extreme angles never worse, regions
 *                 of new tets those of their origin, parents valid; and flips
 *                 and insertions did happen
 *   smooth only   BODT_OP_SMOOTH against the default ops on the same meshes:
 *                 both valid, angles printed
 *   keep surface  KEEP_SURFACE = 1 with FLIP|INSERT (with and without
 *                 SMOOTH), SMOOTH alone in the basic, B-ODT and NODT modes,
 *                 and BODT_MODE_ODT with FLIP|INSERT: the boundary faces
 *                 (triples and markers) and their vertices (bit for bit)
 *                 identical; without it the same runs do change them; the
 *                 phased mode refuses it at bodt_step, the mesh unchanged
 *   parents       base 0 and 1 twins give the same mesh; CSR layout, input
 *                 vertices their own parent, made vertices' weights in [0, 1]
 *                 summing to 1, parents input vertices; origins in range;
 *                 capacity and NULL refusals; the other getters follow the
 *                 new counts
 *   sized report  a report sized up to `flips` gets the old fields and
 *                 nothing is written past it
 *   collapse      ops with BODT_OP_COLLAPSE: valid, boundary kept, counts
 *   no ops        BODT_PARAM_OPS = 0: a step changes nothing
 *   files         the changed mesh written as Medit and TetGen (under
 *                 BODT_TEST_OPS_DIR) and read back unchanged
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

#ifndef BODT_TEST_OPS_DIR
#error "define BODT_TEST_OPS_DIR (a writable directory for test files)"
#endif

enum { NMARK = 8 }; /* markers 1..6: box sides, 7: the interface x = mid */

/* ------------------------------------------------------------- helpers */

static void destroy_mesh(void *p) { bodt_mesh_destroy(p); }

/* A jittered box [0, size]^3, optionally in two regions split at x = mid. */
typedef struct bad_mesh {
    test_mesh *m;
    int32_t *regions; /* per tet */
    double size, mid;
    int two_regions;
    uint64_t seed; /* the seed that gave a valid mesh */
} bad_mesh;

static int region_halves(int i, int j, int k, int n, void *user) {
    (void)j, (void)k, (void)user;
    return 2 * i >= n;
}

/* The first seed from `seed` on whose jitter inverts no tet. */
static bad_mesh make_bad(int n, double size, double jitter, uint64_t seed, int two_regions) {
    bad_mesh b;
    b.m = cleanup_add(calloc(1, sizeof *b.m), cleanup_free_test_mesh);
    assert_non_null(b.m);
    b.size = size;
    b.mid = size * (double)((n + 1) / 2) / n;
    b.two_regions = two_regions;
    for (uint64_t s = seed; s < seed + 500; ++s) {
        const int st = tm_make_cubes_sliding(b.m, n, size, NULL, two_regions ? region_halves : NULL, NULL, jitter,
                                             jitter, s, NULL, &b.regions);
        if (st == -2) continue;
        if (st != 0) fail_msg("tm_make_cubes_sliding: %d", st);
        cleanup_add(b.regions, free);
        b.seed = s;
        return b;
    }
    fail_msg("no seed from %llu gave a valid mesh with jitter %g", (unsigned long long)seed, jitter);
    return b;
}

/* Every array the caller can get, indices turned 0-based. */
typedef struct snap {
    int32_t nv, nt, nb;
    double *xyz;
    int32_t *tets, *regions, *faces, *markers, *fixed, *corners, *refs, *origins;
} snap;

static snap take(const bodt_mesh *h, int base) {
    snap s;
    assert_int_equal(bodt_mesh_get_counts(h, &s.nv, &s.nt, &s.nb), BODT_OK);
    s.xyz = cleanup_calloc(3 * (size_t)s.nv * sizeof *s.xyz);
    s.tets = cleanup_calloc(4 * (size_t)s.nt * sizeof *s.tets);
    s.regions = cleanup_calloc((size_t)s.nt * sizeof *s.regions);
    s.faces = cleanup_calloc(3 * (size_t)s.nb * sizeof *s.faces);
    s.markers = cleanup_calloc((size_t)s.nb * sizeof *s.markers);
    s.fixed = cleanup_calloc((size_t)s.nv * sizeof *s.fixed);
    s.corners = cleanup_calloc((size_t)s.nv * sizeof *s.corners);
    s.refs = cleanup_calloc((size_t)s.nv * sizeof *s.refs);
    s.origins = cleanup_calloc((size_t)s.nt * sizeof *s.origins);
    assert_int_equal(bodt_mesh_get_vertices(h, s.xyz, 3 * (size_t)s.nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_tets(h, s.tets, 4 * (size_t)s.nt), BODT_OK);
    assert_int_equal(bodt_mesh_get_regions(h, s.regions, (size_t)s.nt), BODT_OK);
    assert_int_equal(bodt_mesh_get_boundary_faces(h, s.faces, s.markers, (size_t)s.nb), BODT_OK);
    assert_int_equal(bodt_mesh_get_fixed_vertices(h, s.fixed, (size_t)s.nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_corners(h, s.corners, (size_t)s.nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_vertex_refs(h, s.refs, (size_t)s.nv), BODT_OK);
    assert_int_equal(bodt_mesh_get_tet_origins(h, s.origins, (size_t)s.nt), BODT_OK);
    for (size_t k = 0; k < 4 * (size_t)s.nt; ++k) {
        s.tets[k] -= base;
        if (s.tets[k] < 0 || s.tets[k] >= s.nv) fail_msg("tet index %d out of range (base %d)", s.tets[k] + base, base);
    }
    for (size_t k = 0; k < 3 * (size_t)s.nb; ++k) {
        s.faces[k] -= base;
        if (s.faces[k] < 0 || s.faces[k] >= s.nv) fail_msg("face index %d out of range", s.faces[k] + base);
    }
    for (int32_t t = 0; t < s.nt; ++t) s.origins[t] -= base;
    return s;
}

static void step_ok(bodt_mesh *h, bodt_step_report *r) {
    memset(r, 0, sizeof *r);
    r->size = sizeof *r;
    const int st = bodt_step(h, r);
    if (st != BODT_OK) fail_msg("bodt_step: %s: %s", bodt_status_string(st), bodt_mesh_last_error(h));
}

static void sub3(const double *a, const double *b, double *out) {
    for (int i = 0; i < 3; ++i) out[i] = a[i] - b[i];
}

static void cross3(const double *a, const double *b, double *out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Twice the area vector of triangle (a, b, c), right-hand rule. */
static void tri_normal(const double *a, const double *b, const double *c, double *n) {
    double u[3], v[3];
    sub3(b, a, u);
    sub3(c, a, v);
    cross3(u, v, n);
}

/* The plane of marker mk: axis and value. */
static void marker_plane(const bad_mesh *b, int mk, int *axis, double *value) {
    if (mk == 7) {
        *axis = 0;
        *value = b->mid;
        return;
    }
    *axis = (mk - 1) / 2;
    *value = (mk - 1) % 2 ? b->size : 0.0;
}

/* The marker of the plane holding triangle `f` (all three vertices on it
 * to 1e-12 of the box size), 0 if none. */
static int plane_of(const bad_mesh *b, const double *xyz, const int32_t *f) {
    const double tol = 1e-12 * b->size;
    for (int mk = 1; mk < NMARK; ++mk) {
        if (mk == 7 && !b->two_regions) continue;
        int a;
        double value;
        marker_plane(b, mk, &a, &value);
        int on = 1;
        for (int i = 0; i < 3; ++i) on &= fabs(xyz[3 * f[i] + a] - value) <= tol;
        if (on) return mk;
    }
    return 0;
}

/* Markers per plane on every boundary face of h (fresh, base `base`). */
static void mark_sides(const bad_mesh *b, bodt_mesh *h, int base) {
    const snap s = take(h, base);
    int32_t *tri = cleanup_calloc(3 * (size_t)s.nb * sizeof *tri);
    int32_t *mk = cleanup_calloc((size_t)s.nb * sizeof *mk);
    for (int32_t f = 0; f < s.nb; ++f) {
        mk[f] = plane_of(b, s.xyz, &s.faces[3 * f]);
        if (mk[f] == 0) fail_msg("input boundary face %d is on no plane", f);
        for (int i = 0; i < 3; ++i) tri[3 * f + i] = s.faces[3 * f + i] + base;
    }
    const int st = bodt_mesh_set_boundary_faces(h, s.nb, tri, mk);
    if (st != BODT_OK) fail_msg("set_boundary_faces: %s", bodt_mesh_last_error(h));
}

/* Each boundary face: marked, on its marker's plane, its normal pointing out
 * of the domain (box sides) or out of region 0 (the interface, +x); the
 * area per marker goes to `area`. */
static void check_boundary(const bad_mesh *b, const snap *s, double area[NMARK], const char *name, int step) {
    for (int k = 0; k < NMARK; ++k) area[k] = 0.0;
    for (int32_t f = 0; f < s->nb; ++f) {
        const int32_t *t = &s->faces[3 * f];
        const int mk = s->markers[f];
        if (!(mk >= 1 && mk < NMARK))
            fail_msg("%s step %d: boundary face %d (%d %d %d) has marker %d", name, step, f, t[0], t[1], t[2], mk);
        int a;
        double value;
        marker_plane(b, mk, &a, &value);
        for (int i = 0; i < 3; ++i)
            if (!(fabs(s->xyz[3 * t[i] + a] - value) <= 1e-12 * b->size))
                fail_msg("%s step %d: face %d with marker %d: vertex %d has coordinate %d = %.17g, not %g", name, step,
                         f, mk, t[i], a, s->xyz[3 * t[i] + a], value);
        double n[3];
        tri_normal(&s->xyz[3 * t[0]], &s->xyz[3 * t[1]], &s->xyz[3 * t[2]], n);
        const double outward = mk == 7 || (mk - 1) % 2 ? n[a] : -n[a];
        if (!(outward > 0.0))
            fail_msg("%s step %d: face %d with marker %d points inwards (normal %g %g %g)", name, step, f, mk, n[0],
                     n[1], n[2]);
        area[mk] += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
}

/* Every tet oriented as `sign` says (+1, or -1 for negatively oriented
 * input), by tm_orient6; the volume of region `region` (any if < 0). */
static double check_tets(const snap *s, int sign, int32_t region, const char *name, int step) {
    double vol = 0.0;
    for (int32_t t = 0; t < s->nt; ++t) {
        const int32_t *c = &s->tets[4 * t];
        const double o = sign * tm_orient6(&s->xyz[3 * c[0]], &s->xyz[3 * c[1]], &s->xyz[3 * c[2]], &s->xyz[3 * c[3]]);
        if (!(o > 0.0))
            fail_msg("%s step %d: tet %d (%d %d %d %d) inverted: %g", name, step, t, c[0], c[1], c[2], c[3], o);
        if (region < 0 || s->regions[t] == region) vol += o / 6.0;
    }
    return vol;
}

/* Parents: CSR layout, input vertices their own parent with weight 1, made
 * vertices' weights in [0, 1] (with `splits_only`) summing to 1, parents
 * input vertices.  Indices in base `base`.  Returns the number of made
 * vertices. */
static int32_t check_parents(const bodt_mesh *h, int base, int32_t nv_in, int splits_only, const char *name) {
    int32_t nv = 0;
    assert_int_equal(bodt_mesh_get_counts(h, &nv, NULL, NULL), BODT_OK);
    int64_t count = -1;
    assert_int_equal(bodt_mesh_get_parent_count(h, &count), BODT_OK);
    assert_true(count >= nv);
    int64_t *off = cleanup_calloc(((size_t)nv + 1) * sizeof *off);
    int32_t *par = cleanup_calloc((size_t)count * sizeof *par);
    double *w = cleanup_calloc((size_t)count * sizeof *w);
    const int st = bodt_mesh_get_vertex_parents(h, off, (size_t)nv + 1, par, w, (size_t)count);
    if (st != BODT_OK) fail_msg("%s: get_vertex_parents: %s", name, bodt_mesh_last_error(h));
    assert_int_equal(off[0], 0);
    assert_int_equal(off[nv], count);
    for (int32_t v = 0; v < nv; ++v) {
        const int64_t n = off[v + 1] - off[v];
        if (!(n >= 1)) fail_msg("%s: vertex %d has %lld parents", name, v, (long long)n);
        if (v < nv_in) {
            if (n != 1 || par[off[v]] != v + base || w[off[v]] != 1.0)
                fail_msg("%s: input vertex %d: %lld parents, first %d weight %g", name, v, (long long)n, par[off[v]],
                         w[off[v]]);
            continue;
        }
        double sum = 0.0;
        for (int64_t k = off[v]; k < off[v + 1]; ++k) {
            if (!(par[k] >= base && par[k] < nv_in + base))
                fail_msg("%s: made vertex %d has parent %d, not an input vertex (base %d, %d input)", name, v, par[k],
                         base, nv_in);
            if (splits_only && !(w[k] >= 0.0 && w[k] <= 1.0))
                fail_msg("%s: made vertex %d: weight %.17g of parent %d", name, v, w[k], par[k]);
            if (!isfinite(w[k])) fail_msg("%s: made vertex %d: weight %g", name, v, w[k]);
            sum += w[k];
        }
        if (!(fabs(sum - 1.0) <= 1e-12)) fail_msg("%s: made vertex %d: weights sum to %.17g", name, v, sum);
    }
    return nv - nv_in;
}

/* The box edge line holding segment (p, q): 4 * axis + which of the four
 * lines along that axis, or -1 if none.  A box edge line has the two other
 * coordinates at 0 or size. */
static int box_line(const bad_mesh *b, const double *p, const double *q) {
    const double tol = 1e-12 * b->size;
    for (int a = 0; a < 3; ++a) {
        int code = 0, on = 1;
        for (int i = 1; i < 3; ++i) {
            const int c = (a + i) % 3;
            const int lo = fabs(p[c]) <= tol && fabs(q[c]) <= tol;
            const int hi = fabs(p[c] - b->size) <= tol && fabs(q[c] - b->size) <= tol;
            on &= lo || hi;
            code = 2 * code + hi;
        }
        if (on) return 4 * a + code;
    }
    return -1;
}

/* 1 for the vertices of the listed (boundary and interface) faces. */
static unsigned char *on_surface(const snap *s) {
    unsigned char *on = cleanup_calloc((size_t)s->nv);
    for (size_t k = 0; k < 3 * (size_t)s->nb; ++k) on[s->faces[k]] = 1;
    return on;
}

/* The box's 8 corner points (every coordinate 0 or size). */
static int is_box_corner(const bad_mesh *b, const double *p) {
    const double tol = 1e-12 * b->size;
    for (int c = 0; c < 3; ++c)
        if (!(fabs(p[c]) <= tol || fabs(p[c] - b->size) <= tol)) return 0;
    return 1;
}

/* Ref of the caller's feature edges on box edge line `line`. */
#define LINE_REF(line) (100 + (line))
/* Vertex refs: boundary-condition style, 1 on the surface, 2 inside. */
enum { REF_SURFACE = 1, REF_INSIDE = 2 };

/* The caller's features: the edges of boundary faces on a box edge, each
 * with its line's ref; the box's corners as corners; vertex refs. */
static void set_box_features(const bad_mesh *b, bodt_mesh *h, int base) {
    const snap s = take(h, base);
    int32_t *e = cleanup_calloc(6 * (size_t)s.nb * sizeof *e);
    int32_t *refs = cleanup_calloc(3 * (size_t)s.nb * sizeof *refs);
    int32_t n = 0;
    for (int32_t f = 0; f < s.nb; ++f)
        for (int i = 0; i < 3; ++i) {
            const int32_t u = s.faces[3 * f + i], v = s.faces[3 * f + (i + 1) % 3];
            const int line = box_line(b, &s.xyz[3 * u], &s.xyz[3 * v]);
            if (u < v && line >= 0) {
                e[2 * n] = u + base;
                e[2 * n + 1] = v + base;
                refs[n++] = LINE_REF(line);
            }
        }
    assert_true(n > 0);
    int st = bodt_mesh_set_feature_edges_ex(h, n, e, refs);
    if (st != BODT_OK) fail_msg("set_feature_edges_ex: %s", bodt_mesh_last_error(h));
    int32_t *corners = cleanup_calloc((size_t)s.nv * sizeof *corners);
    int32_t nc = 0;
    for (int32_t v = 0; v < s.nv; ++v)
        if (is_box_corner(b, &s.xyz[3 * v])) corners[nc++] = v + base;
    assert_int_equal(nc, 8);
    st = bodt_mesh_set_corners(h, nc, corners);
    if (st != BODT_OK) fail_msg("set_corners: %s", bodt_mesh_last_error(h));
    const unsigned char *on = on_surface(&s);
    int32_t *vrefs = cleanup_calloc((size_t)s.nv * sizeof *vrefs);
    for (int32_t v = 0; v < s.nv; ++v) vrefs[v] = on[v] ? REF_SURFACE : REF_INSIDE;
    st = bodt_mesh_set_vertex_refs(h, vrefs);
    if (st != BODT_OK) fail_msg("set_vertex_refs: %s", bodt_mesh_last_error(h));
}

/* After the steps: corners unmoved and classed so; vertex refs as
 * documented (a made vertex takes the ref of its parents on its side of
 * the surface, 0 when it has none there). */
static void check_corners_and_refs(const bad_mesh *b, const bodt_mesh *h, const snap *s0, const snap *s,
                                   const char *name, int step) {
    int32_t *cls = cleanup_calloc((size_t)s->nv * sizeof *cls);
    assert_int_equal(bodt_mesh_get_vertex_classes(h, cls, (size_t)s->nv), BODT_OK);
    const unsigned char *on = on_surface(s);
    for (int32_t v = 0; v < s->nv; ++v) {
        const int corner = v < s0->nv && s0->corners[v];
        if (s->corners[v] != corner)
            fail_msg("%s step %d: vertex %d: corner flag %d, expected %d", name, step, v, s->corners[v], corner);
        if (corner) {
            if (memcmp(&s->xyz[3 * v], &s0->xyz[3 * v], 3 * sizeof(double)) != 0)
                fail_msg("%s step %d: corner %d moved", name, step, v);
            if (cls[v] != BODT_VERTEX_CORNER) fail_msg("%s step %d: corner %d has class %d", name, step, v, cls[v]);
            assert_true(is_box_corner(b, &s->xyz[3 * v]));
        }
        if (cls[v] == BODT_VERTEX_UNUSED) continue;
        const int32_t want = on[v] ? REF_SURFACE : REF_INSIDE;
        if (v < s0->nv ? s->refs[v] != s0->refs[v] : !(s->refs[v] == want || (!on[v] && s->refs[v] == 0)))
            fail_msg("%s step %d: %s vertex %d %s has ref %d", name, step, v < s0->nv ? "input" : "made", v,
                     on[v] ? "on the surface" : "inside", s->refs[v]);
    }
}

/* The caller's feature edges after the steps: each on a box edge line with
 * that line's ref, and each of the 12 lines covered once (their lengths add
 * up to size). */
static void check_feature_edges(const bad_mesh *b, const bodt_mesh *h, const snap *s, const char *name, int step) {
    int32_t n = -1;
    assert_int_equal(bodt_mesh_get_feature_edges_ex(h, &n, NULL, NULL, 0), BODT_OK);
    int32_t *e = cleanup_calloc(2 * (size_t)n * sizeof *e);
    int32_t *refs = cleanup_calloc((size_t)n * sizeof *refs);
    assert_int_equal(bodt_mesh_get_feature_edges_ex(h, &n, e, refs, (size_t)n), BODT_OK);
    double len[12] = {0};
    for (int32_t k = 0; k < n; ++k) {
        const double *p = &s->xyz[3 * e[2 * k]], *q = &s->xyz[3 * e[2 * k + 1]];
        const int line = box_line(b, p, q);
        if (line < 0)
            fail_msg("%s step %d: feature edge %d (%d %d) is on no box edge", name, step, k, e[2 * k], e[2 * k + 1]);
        if (refs[k] != LINE_REF(line))
            fail_msg("%s step %d: feature edge %d (%d %d) has ref %d, its line's is %d", name, step, k, e[2 * k],
                     e[2 * k + 1], refs[k], LINE_REF(line));
        len[line] += fabs(p[line / 4] - q[line / 4]);
    }
    for (int line = 0; line < 12; ++line)
        if (!(fabs(len[line] - b->size) <= 1e-12 * b->size))
            fail_msg("%s step %d: the feature edges on box edge %d add up to %.17g, not %g", name, step, line,
                     len[line], b->size);
}

/* ------------------------------------------------------- checked runs */

enum { FIX_NONE = 0, FIX_SOME = 1, FIX_ALL = 2 };

typedef struct run_opts {
    int mode;
    int32_t ops; /* BODT_PARAM_OPS */
    int keep_surface;
    int fix;     /* FIX_* of the input vertices */
    int negate;  /* give the tets negatively oriented */
    int steps;
    double bad_angle; /* 0: default */
    int features;     /* give the box's 12 edges as caller feature edges */
} run_opts;

typedef struct run_result {
    long flips, inserted, collapsed;
    double min0, max0, min1, max1;
    int32_t nv0, nt0, nb0, nv1, nt1, nb1;
    int faces_changed; /* the boundary triples or markers differ from the input's */
    int boundary_moved; /* a vertex of an input boundary face moved */
    int32_t unused1;   /* vertices in no tet at the end */
} run_result;

static int cmp_face(const void *x, const void *y) {
    const int32_t *a = x, *b = y;
    for (int i = 0; i < 4; ++i)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

/* The boundary faces as sorted (v0 < v1 < v2, marker) quadruples. */
static int32_t *face_set(const snap *s) {
    int32_t *q = cleanup_calloc(4 * (size_t)s->nb * sizeof *q);
    for (int32_t f = 0; f < s->nb; ++f) {
        int32_t *p = &q[4 * f];
        for (int i = 0; i < 3; ++i) p[i] = s->faces[3 * f + i];
        sort3(p);
        p[3] = s->markers[f];
    }
    qsort(q, (size_t)s->nb, 4 * sizeof *q, cmp_face);
    return q;
}

static bodt_mesh *create_handle(const bad_mesh *b, int base, int negate) {
    const test_mesh *m = b->m;
    int32_t *tets = cleanup_calloc(4 * (size_t)m->ntets * sizeof *tets);
    for (int32_t t = 0; t < m->ntets; ++t) {
        const int32_t *c = &m->tets[4 * t];
        int32_t *o = &tets[4 * t];
        o[0] = (negate ? c[1] : c[0]) + base;
        o[1] = (negate ? c[0] : c[1]) + base;
        o[2] = c[2] + base;
        o[3] = c[3] + base;
    }
    bodt_mesh *h = NULL;
    if (bodt_mesh_create(m->nverts, m->xyz, m->ntets, tets, base, &h) != BODT_OK)
        fail_msg("create: %s", bodt_mesh_last_error(NULL));
    cleanup_add(h, destroy_mesh);
    if (b->two_regions) assert_int_equal(bodt_mesh_set_regions(h, b->regions), BODT_OK);
    mark_sides(b, h, base);
    return h;
}

static void setup(bodt_mesh *h, const bad_mesh *b, const run_opts *o, int base) {
    assert_int_equal(bodt_set_mode(h, o->mode), BODT_OK);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, o->ops), BODT_OK);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_KEEP_SURFACE, o->keep_surface), BODT_OK);
    if (o->bad_angle > 0.0) assert_int_equal(bodt_set_param_double(h, BODT_PARAM_BAD_ANGLE, o->bad_angle), BODT_OK);
    if (o->fix != FIX_NONE) {
        int32_t *list = cleanup_calloc((size_t)b->m->nverts * sizeof *list);
        int32_t n = 0;
        for (int32_t v = 0; v < b->m->nverts; ++v)
            if (o->fix == FIX_ALL || v % 4 == 1) list[n++] = v + base;
        assert_int_equal(bodt_mesh_set_fixed_vertices(h, n, list), BODT_OK);
    }
}

/* The effective ops of o (BODT_OPS_MODE_DEFAULT resolved as documented). */
static int32_t effective_ops(const run_opts *o) {
    if (o->ops != BODT_OPS_MODE_DEFAULT) return o->ops;
    return o->mode == BODT_MODE_BODT ? BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT : BODT_OP_SMOOTH;
}

/* Runs o->steps steps on a fresh handle of b and checks everything after
 * each step (see the file comment).  Returns the handle. */
static bodt_mesh *checked_run(const bad_mesh *b, const run_opts *o, const char *name, run_result *res) {
    const int base = 0, sign = o->negate ? -1 : 1;
    const int32_t ops = effective_ops(o);
    const int collapse = ops & BODT_OP_COLLAPSE;
    const int surface_kept = o->keep_surface || o->mode == BODT_MODE_ODT || o->mode == BODT_MODE_LAPLACE;
    bodt_mesh *h = create_handle(b, base, o->negate);
    setup(h, b, o, base);
    if (o->features) set_box_features(b, h, base);
    const snap s0 = take(h, base);
    const int32_t *faces0 = face_set(&s0);
    double area0[NMARK], area[NMARK];
    check_boundary(b, &s0, area0, name, 0);
    const double vol0 = check_tets(&s0, sign, -1, name, 0);
    const double rvol0 = b->two_regions ? check_tets(&s0, sign, 0, name, 0) : 0.0;
    bodt_quality q;
    get_quality(h, &q);
    memset(res, 0, sizeof *res);
    res->min0 = q.min_dihedral;
    res->max0 = q.max_dihedral;
    res->nv0 = s0.nv;
    res->nt0 = s0.nt;
    res->nb0 = s0.nb;
    double prev_min = q.min_dihedral, prev_max = q.max_dihedral;
    int32_t prev_nv = s0.nv;
    for (int k = 1; k <= o->steps; ++k) {
        bodt_step_report r;
        step_ok(h, &r);
        assert_int_equal(r.step, k);
        assert_true(r.flips >= 0 && r.vertices_inserted >= 0 && r.edges_collapsed >= 0);
        if (!(ops & BODT_OP_FLIP)) assert_int_equal(r.flips, 0);
        if (!(ops & BODT_OP_INSERT)) assert_int_equal(r.vertices_inserted, 0);
        if (!collapse) assert_int_equal(r.edges_collapsed, 0);
        res->flips += r.flips;
        res->inserted += r.vertices_inserted;
        res->collapsed += r.edges_collapsed;
        const snap s = take(h, base);
        /* counts: input vertices stay, inserted ones are appended */
        if (!collapse) {
            if (s.nv - s0.nv != res->inserted)
                fail_msg("%s step %d: %d vertices, %d input + %ld inserted", name, k, s.nv, s0.nv, res->inserted);
        } else {
            assert_true(s.nv >= s0.nv && s.nv - s0.nv <= res->inserted);
        }
        if (!collapse && s.nv == prev_nv && r.vertices_inserted > 0)
            fail_msg("%s step %d: %d inserted but the vertex count did not change", name, k, r.vertices_inserted);
        prev_nv = s.nv;
        /* validity and volume, by the test's own orientation */
        const double vol = check_tets(&s, sign, -1, name, k);
        if (!(fabs(vol - vol0) <= 1e-12 * vol0))
            fail_msg("%s step %d: volume %.17g -> %.17g", name, k, vol0, vol);
        if (b->two_regions) {
            const double rvol = check_tets(&s, sign, 0, name, k);
            if (!(fabs(rvol - rvol0) <= 1e-12 * vol0))
                fail_msg("%s step %d: region 0 volume %.17g -> %.17g", name, k, rvol0, rvol);
        }
        /* boundary: every marked face on its plane, outward, areas kept */
        check_boundary(b, &s, area, name, k);
        for (int mk = 1; mk < NMARK; ++mk)
            if (!(fabs(area[mk] - area0[mk]) <= 1e-12 * b->size * b->size))
                fail_msg("%s step %d: area of marker %d: %.17g -> %.17g", name, k, mk, area0[mk], area[mk]);
        if (surface_kept) {
            if (s.nb != s0.nb || memcmp(face_set(&s), faces0, 4 * (size_t)s.nb * sizeof *faces0) != 0)
                fail_msg("%s step %d: the boundary faces changed (%d -> %d faces) with the surface kept", name, k,
                         s0.nb, s.nb);
        }
        /* the vertices of the input's boundary faces: bit for bit with the surface kept */
        for (int32_t f = 0; f < s0.nb; ++f)
            for (int i = 0; i < 3; ++i) {
                const int32_t v = s0.faces[3 * f + i] - base;
                if (memcmp(&s.xyz[3 * v], &s0.xyz[3 * v], 3 * sizeof(double)) == 0) continue;
                if (surface_kept) fail_msg("%s step %d: boundary vertex %d moved with the surface kept", name, k, v);
                res->boundary_moved = 1;
            }
        /* fixed input vertices bit for bit; made vertices are not fixed */
        for (int32_t v = 0; v < s.nv; ++v) {
            const int fixed = v < s0.nv && s0.fixed[v];
            if (s.fixed[v] != fixed)
                fail_msg("%s step %d: vertex %d: fixed flag %d, expected %d", name, k, v, s.fixed[v], fixed);
            if (fixed && memcmp(&s.xyz[3 * v], &s0.xyz[3 * v], 3 * sizeof(double)) != 0)
                fail_msg("%s step %d: fixed vertex %d moved", name, k, v);
        }
        /* origins in range; a tet keeps the region of its origin */
        for (int32_t t = 0; t < s.nt; ++t) {
            const int32_t org = s.origins[t];
            if (!(org >= 0 && org < s0.nt)) fail_msg("%s step %d: tet %d has origin %d", name, k, t, org + base);
            if (s.regions[t] != s0.regions[org])
                fail_msg("%s step %d: tet %d in region %d, its origin %d in %d", name, k, t, s.regions[t], org,
                         s0.regions[org]);
        }
        check_parents(h, base, s0.nv, !collapse, name);
        /* the report is the mesh's quality after the step */
        get_quality(h, &q);
        assert_int_equal(q.num_vertices, s.nv);
        assert_int_equal(q.num_tets, s.nt);
        assert_int_equal(q.num_boundary_faces, s.nb);
        assert_int_equal(q.num_inverted, 0);
        /* vertices in no tet (input vertices a collapse left) are counted
         * and classed as unused; made vertices are never unused */
        unsigned char *used = cleanup_calloc((size_t)s.nv);
        for (size_t i = 0; i < 4 * (size_t)s.nt; ++i) used[s.tets[i]] = 1;
        int32_t unused = 0;
        for (int32_t v = 0; v < s.nv; ++v) {
            unused += !used[v];
            if (!used[v] && v >= s0.nv) fail_msg("%s step %d: made vertex %d is in no tet", name, k, v);
        }
        assert_int_equal(q.num_unused_vertices, unused);
        if (!collapse) assert_int_equal(unused, 0);
        assert_near(r.min_dihedral, q.min_dihedral, 1e-9);
        assert_near(r.max_dihedral, q.max_dihedral, 1e-9);
        /* NEVER_WORSE (default 1): the extreme angles never get worse */
        if (!(q.min_dihedral >= prev_min - 1e-9 && q.max_dihedral <= prev_max + 1e-9))
            fail_msg("%s step %d: dihedral range [%.9g, %.9g] -> [%.9g, %.9g]", name, k, prev_min, prev_max,
                     q.min_dihedral, q.max_dihedral);
        prev_min = q.min_dihedral;
        prev_max = q.max_dihedral;
        /* the per-tet getters follow the new count */
        double *mins = cleanup_calloc((size_t)s.nt * sizeof *mins);
        assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_MIN_DIHEDRAL, mins, (size_t)s.nt), BODT_OK);
        double lo = 180.0;
        for (int32_t t = 0; t < s.nt; ++t) lo = fmin(lo, mins[t]);
        assert_near(lo, q.min_dihedral, 1e-9);
        int32_t *cls = cleanup_calloc((size_t)s.nv * sizeof *cls);
        assert_int_equal(bodt_mesh_get_vertex_classes(h, cls, (size_t)s.nv), BODT_OK);
        for (int32_t v = 0; v < s.nv; ++v) {
            assert_true(cls[v] >= BODT_VERTEX_INTERIOR && cls[v] <= BODT_VERTEX_UNUSED);
            if ((cls[v] == BODT_VERTEX_UNUSED) != !used[v])
                fail_msg("%s step %d: vertex %d in %s tet has class %d", name, k, v, used[v] ? "a" : "no", cls[v]);
        }
        if (o->features) {
            check_feature_edges(b, h, &s, name, k);
            check_corners_and_refs(b, h, &s0, &s, name, k);
        }
        if (!(surface_kept) && (s.nb != s0.nb || memcmp(face_set(&s), faces0, 4 * (size_t)s.nb * sizeof *faces0)))
            res->faces_changed = 1;
    }
    get_quality(h, &q);
    res->unused1 = q.num_unused_vertices;
    res->min1 = q.min_dihedral;
    res->max1 = q.max_dihedral;
    assert_int_equal(bodt_mesh_get_counts(h, &res->nv1, &res->nt1, &res->nb1), BODT_OK);
    print_message("%-34s seed %3llu: %4d -> %4d verts, %4d -> %4d tets, %3d -> %3d faces, %3ld flips, %2ld inserted, "
                  "%2ld collapsed; dihedral [%6.2f, %6.2f] -> [%6.2f, %6.2f]\n",
                  name, (unsigned long long)b->seed, res->nv0, res->nv1, res->nt0, res->nt1, res->nb0, res->nb1,
                  res->flips, res->inserted, res->collapsed, res->min0, res->max0, res->min1, res->max1);
    return h;
}

static run_opts opts(int mode, int32_t ops) {
    run_opts o;
    memset(&o, 0, sizeof o);
    o.mode = mode;
    o.ops = ops;
    o.steps = 5;
    return o;
}

/* --------------------------------------------------------------- params */

static void test_params(void **state) {
    (void)state;
    const bad_mesh b = make_bad(2, 1.0, 0.1, 1, 0);
    bodt_mesh *h = create_handle(&b, 0, 0);
    const int E = BODT_ERR_INVALID_ARGUMENT;
    int32_t iv = 99;
    double dv = 99.0;
    /* defaults */
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, &iv), BODT_OK);
    assert_int_equal(iv, BODT_OPS_MODE_DEFAULT);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_KEEP_SURFACE, &iv), BODT_OK);
    assert_int_equal(iv, 0);
    assert_int_equal(bodt_get_param_double(h, BODT_PARAM_BAD_ANGLE, &dv), BODT_OK);
    assert_true(dv == 15.0);
    /* the mode does not change what OPS says */
    for (int mode = BODT_MODE_LAPLACE; mode <= BODT_MODE_BODT; ++mode) {
        assert_int_equal(bodt_set_mode(h, mode), BODT_OK);
        assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, &iv), BODT_OK);
        assert_int_equal(iv, BODT_OPS_MODE_DEFAULT);
    }
    /* every value in [-1, 15] is taken and given back */
    for (int32_t v = -1; v <= 15; ++v) {
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, v), BODT_OK);
        assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, &iv), BODT_OK);
        assert_int_equal(iv, v);
    }
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, BODT_OP_SMOOTH | BODT_OP_FLIP), BODT_OK);
    static const int32_t bad_ops[] = {-2, 16, 17, 32, 255, INT32_MAX, INT32_MIN};
    for (size_t k = 0; k < sizeof bad_ops / sizeof *bad_ops; ++k) {
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, bad_ops[k]), E);
        assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_OPS");
        assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, &iv), BODT_OK);
        assert_int_equal(iv, BODT_OP_SMOOTH | BODT_OP_FLIP); /* unchanged */
        assert_string_equal(bodt_mesh_last_error(h), "");
    }
    /* KEEP_SURFACE: 0 or 1 */
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_KEEP_SURFACE, 1), BODT_OK);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_KEEP_SURFACE, &iv), BODT_OK);
    assert_int_equal(iv, 1);
    static const int32_t bad_keep[] = {-1, 2, 100, INT32_MIN};
    for (size_t k = 0; k < sizeof bad_keep / sizeof *bad_keep; ++k) {
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_KEEP_SURFACE, bad_keep[k]), E);
        assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_KEEP_SURFACE");
        assert_int_equal(bodt_get_param_int(h, BODT_PARAM_KEEP_SURFACE, &iv), BODT_OK);
        assert_int_equal(iv, 1);
    }
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_KEEP_SURFACE, 0), BODT_OK);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_KEEP_SURFACE, &iv), BODT_OK);
    assert_int_equal(iv, 0);
    /* DELAUNAY_FLIPS: 0 (default) or 1 */
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_DELAUNAY_FLIPS, &iv), BODT_OK);
    assert_int_equal(iv, 0);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_DELAUNAY_FLIPS, 1), BODT_OK);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_DELAUNAY_FLIPS, &iv), BODT_OK);
    assert_int_equal(iv, 1);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_DELAUNAY_FLIPS, 2), E);
    assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_DELAUNAY_FLIPS");
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_DELAUNAY_FLIPS, 1.0), E);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_DELAUNAY_FLIPS, 0), BODT_OK);
    /* BAD_ANGLE: degrees in [0, 60] */
    static const double good_angles[] = {0.0, 60.0, 30.5, 1e-9};
    for (size_t k = 0; k < sizeof good_angles / sizeof *good_angles; ++k) {
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_BAD_ANGLE, good_angles[k]), BODT_OK);
        assert_int_equal(bodt_get_param_double(h, BODT_PARAM_BAD_ANGLE, &dv), BODT_OK);
        assert_true(dv == good_angles[k]);
    }
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_BAD_ANGLE, 20.0), BODT_OK);
    const double bad_angles[] = {-1e-9, -1.0, 60.000001, 90.0, NAN, INFINITY, -INFINITY};
    for (size_t k = 0; k < sizeof bad_angles / sizeof *bad_angles; ++k) {
        assert_int_equal(bodt_set_param_double(h, BODT_PARAM_BAD_ANGLE, bad_angles[k]), E);
        assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_BAD_ANGLE");
        assert_int_equal(bodt_get_param_double(h, BODT_PARAM_BAD_ANGLE, &dv), BODT_OK);
        assert_true(dv == 20.0);
    }
    /* the wrong type is refused, with a message naming the key */
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_OPS, 3.0), E);
    assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_OPS");
    assert_int_equal(bodt_get_param_double(h, BODT_PARAM_OPS, &dv), E);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_KEEP_SURFACE, 1.0), E);
    assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_KEEP_SURFACE");
    assert_int_equal(bodt_get_param_double(h, BODT_PARAM_KEEP_SURFACE, &dv), E);
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_BAD_ANGLE, 10), E);
    assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_BAD_ANGLE");
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_BAD_ANGLE, &iv), E);
    /* and leaves the values */
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, &iv), BODT_OK);
    assert_int_equal(iv, BODT_OP_SMOOTH | BODT_OP_FLIP);
    assert_int_equal(bodt_get_param_double(h, BODT_PARAM_BAD_ANGLE, &dv), BODT_OK);
    assert_true(dv == 20.0);
    /* NULL handle and NULL value */
    assert_int_equal(bodt_set_param_int(NULL, BODT_PARAM_OPS, 1), E);
    assert_int_equal(bodt_get_param_int(NULL, BODT_PARAM_OPS, &iv), E);
    assert_int_equal(bodt_get_param_int(h, BODT_PARAM_OPS, NULL), E);
    assert_int_equal(bodt_get_param_double(h, BODT_PARAM_BAD_ANGLE, NULL), E);
    /* the key after the last is unknown */
    assert_int_equal(bodt_set_param_int(h, BODT_PARAM_QN_INTERVAL_GROWTH + 1, 0), E);
    assert_int_equal(bodt_set_param_double(h, BODT_PARAM_QN_INTERVAL_GROWTH + 1, 0.0), E);
}

/* ----------------------------------------------------------- default ops */

/* The bad meshes of the tests below. */
#define BAD_N 5
#define BAD_SIZE 2.0
#define BAD_JITTER 0.4

static void test_default_ops(void **state) {
    (void)state;
    long flips = 0, inserted = 0;
    int surface_changed = 0;
    run_result res;
    for (int variant = 0; variant < 6; ++variant) {
        const int two_regions = variant == 2 || variant == 5;
        const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 1 + 40 * (uint64_t)variant, two_regions);
        run_opts o = opts(BODT_MODE_BODT, BODT_OPS_MODE_DEFAULT);
        const char *name = "";
        switch (variant) {
            case 0: name = "default ops"; break;
            case 1: o.fix = FIX_SOME, name = "default ops, some fixed"; break;
            case 2: o.negate = 1, name = "default ops, 2 regions, negative"; break;
            case 3: o.fix = FIX_ALL, name = "default ops, input fixed"; break;
            case 4: o.ops = BODT_OP_FLIP | BODT_OP_INSERT, o.fix = FIX_ALL, name = "flip|insert, input fixed"; break;
            case 5:
                o.ops = BODT_OP_FLIP | BODT_OP_INSERT, o.bad_angle = 25.0, o.features = 1;
                name = "flip|insert, bad 25, 2 regions, lines";
                break;
        }
        checked_run(&b, &o, name, &res);
        flips += res.flips;
        inserted += res.inserted;
        surface_changed |= res.faces_changed;
        assert_true(res.min1 >= res.min0);
    }
    print_message("default ops: %ld flips, %ld vertices inserted in all\n", flips, inserted);
    /* not vacuous: the operations did change the meshes, also their surface */
    assert_true(flips > 0);
    assert_true(inserted > 0);
    assert_true(surface_changed);
}

/* ------------------------------------------------------- smoothing only */

static void test_smooth_only_vs_default(void **state) {
    (void)state;
    for (int k = 0; k < 3; ++k) {
        const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 200 + 50 * (uint64_t)k, 0);
        run_result smooth, deflt;
        run_opts o = opts(BODT_MODE_BODT, BODT_OP_SMOOTH);
        o.steps = 8;
        checked_run(&b, &o, "smooth only", &smooth);
        assert_int_equal(smooth.nv1, smooth.nv0);
        assert_int_equal(smooth.nt1, smooth.nt0);
        o.ops = BODT_OPS_MODE_DEFAULT;
        checked_run(&b, &o, "default ops", &deflt);
        print_message("seed %llu: smoothing only [%.2f, %.2f], default ops [%.2f, %.2f] (from [%.2f, %.2f])\n",
                      (unsigned long long)b.seed, smooth.min1, smooth.max1, deflt.min1, deflt.max1, smooth.min0,
                      smooth.max0);
    }
}

/* -------------------------------------------------------- keep surface */

static void test_keep_surface(void **state) {
    (void)state;
    const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 1, 0);
    run_result res;
    /* the same run without KEEP_SURFACE changes the surface */
    run_opts o = opts(BODT_MODE_BODT, BODT_OP_FLIP | BODT_OP_INSERT);
    o.fix = FIX_ALL;
    o.bad_angle = 25.0;
    checked_run(&b, &o, "flip|insert", &res);
    assert_true(res.faces_changed);
    /* and smoothing moves the boundary vertices */
    o.ops = BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT;
    o.fix = FIX_NONE;
    checked_run(&b, &o, "smooth|flip|insert", &res);
    assert_true(res.boundary_moved);
    /* KEEP_SURFACE = 1 (checked_run compares the faces and their vertices
     * after each step) */
    o.ops = BODT_OP_FLIP | BODT_OP_INSERT;
    o.fix = FIX_ALL;
    o.keep_surface = 1;
    checked_run(&b, &o, "flip|insert, keep surface", &res);
    assert_true(res.flips + res.inserted > 0);
    o.ops = BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT;
    o.fix = FIX_NONE;
    checked_run(&b, &o, "smooth|flip|insert, keep surface", &res);
    assert_true(res.flips + res.inserted > 0);
    const int smoothing[3] = {BODT_MODE_BODT_BASIC, BODT_MODE_BODT, BODT_MODE_NODT};
    const char *smoothing_names[3] = {"basic smooth, keep surface", "B-ODT smooth, keep surface",
                                      "NODT smooth, keep surface"};
    for (int k = 0; k < 3; ++k) {
        o = opts(smoothing[k], BODT_OP_SMOOTH);
        o.keep_surface = 1;
        checked_run(&b, &o, smoothing_names[k], &res);
    }
    /* the phased mode recovers the surface: refused, the mesh as it was */
    {
        bodt_mesh *h = create_handle(&b, 0, 0);
        const snap s0 = take(h, 0);
        assert_int_equal(bodt_set_mode(h, BODT_MODE_PHASED_ODT), BODT_OK);
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_KEEP_SURFACE, 1), BODT_OK);
        bodt_step_report r;
        memset(&r, 0, sizeof r);
        r.size = sizeof r;
        assert_int_equal(bodt_step(h, &r), BODT_ERR_INVALID_ARGUMENT);
        assert_contains(bodt_mesh_last_error(h), "BODT_PARAM_KEEP_SURFACE");
        const snap s1 = take(h, 0);
        assert_int_equal(s1.nv, s0.nv);
        assert_int_equal(s1.nt, s0.nt);
        assert_memory_equal(s1.xyz, s0.xyz, 3 * (size_t)s0.nv * sizeof(double));
        assert_memory_equal(s1.tets, s0.tets, 4 * (size_t)s0.nt * sizeof(int32_t));
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_KEEP_SURFACE, 0), BODT_OK);
        step_ok(h, &r);
    }
    /* ODT keeps the surface without being told */
    for (int fix = FIX_NONE; fix <= FIX_ALL; fix += FIX_ALL) {
        o = opts(BODT_MODE_ODT, BODT_OP_FLIP | BODT_OP_INSERT);
        o.fix = fix;
        o.bad_angle = 25.0;
        checked_run(&b, &o, fix ? "ODT flip|insert, input fixed" : "ODT flip|insert", &res);
        assert_true(res.flips + res.inserted > 0);
        o.ops = BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT;
        checked_run(&b, &o, fix ? "ODT smooth|flip|insert, input fixed" : "ODT smooth|flip|insert", &res);
    }
    o = opts(BODT_MODE_LAPLACE, BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT);
    checked_run(&b, &o, "Laplace smooth|flip|insert", &res);
}

/* ------------------------------------------------------ parents, origins */

static void test_parents_and_origins(void **state) {
    (void)state;
    const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 1, 0);
    const int E = BODT_ERR_INVALID_ARGUMENT;
    run_opts o = opts(BODT_MODE_BODT, BODT_OP_FLIP | BODT_OP_INSERT);
    o.fix = FIX_ALL;
    o.bad_angle = 25.0;

    /* before any step: identity */
    bodt_mesh *h0 = create_handle(&b, 0, 0);
    int64_t count = -1;
    assert_int_equal(bodt_mesh_get_parent_count(h0, &count), BODT_OK);
    assert_int_equal(count, b.m->nverts);
    assert_int_equal(check_parents(h0, 0, b.m->nverts, 1, "fresh"), 0);
    int32_t *org = cleanup_calloc((size_t)b.m->ntets * sizeof *org);
    assert_int_equal(bodt_mesh_get_tet_origins(h0, org, (size_t)b.m->ntets), BODT_OK);
    for (int32_t t = 0; t < b.m->ntets; ++t) assert_int_equal(org[t], t);

    /* base 0 and base 1 twins do the same steps */
    bodt_mesh *h[2];
    for (int base = 0; base < 2; ++base) {
        h[base] = create_handle(&b, base, 0);
        setup(h[base], &b, &o, base);
        for (int k = 0; k < 4; ++k) {
            bodt_step_report r;
            step_ok(h[base], &r);
        }
    }
    const snap s0 = take(h[0], 0), s1 = take(h[1], 1);
    assert_int_equal(s0.nv, s1.nv);
    assert_int_equal(s0.nt, s1.nt);
    assert_int_equal(s0.nb, s1.nb);
    assert_true(s0.nv > b.m->nverts); /* vertices were made */
    assert_memory_equal(s0.xyz, s1.xyz, 3 * (size_t)s0.nv * sizeof(double));
    assert_memory_equal(s0.tets, s1.tets, 4 * (size_t)s0.nt * sizeof(int32_t));
    assert_memory_equal(s0.faces, s1.faces, 3 * (size_t)s0.nb * sizeof(int32_t));
    assert_memory_equal(s0.origins, s1.origins, (size_t)s0.nt * sizeof(int32_t));
    int32_t *o1 = cleanup_calloc((size_t)s1.nt * sizeof *o1);
    assert_int_equal(bodt_mesh_get_tet_origins(h[1], o1, (size_t)s1.nt), BODT_OK);
    for (int32_t t = 0; t < s1.nt; ++t) assert_true(o1[t] >= 1 && o1[t] <= b.m->ntets);
    const int32_t made0 = check_parents(h[0], 0, b.m->nverts, 1, "base 0");
    const int32_t made1 = check_parents(h[1], 1, b.m->nverts, 1, "base 1");
    assert_int_equal(made0, s0.nv - b.m->nverts);
    assert_int_equal(made1, made0);
    /* the base-1 parents are the base-0 ones plus 1, same weights */
    int64_t n0 = 0, n1 = 0;
    assert_int_equal(bodt_mesh_get_parent_count(h[0], &n0), BODT_OK);
    assert_int_equal(bodt_mesh_get_parent_count(h[1], &n1), BODT_OK);
    assert_int_equal(n0, n1);
    assert_true(n0 > s0.nv);
    int64_t *off[2];
    int32_t *par[2];
    double *w[2];
    for (int base = 0; base < 2; ++base) {
        off[base] = cleanup_calloc(((size_t)s0.nv + 1) * sizeof *off[base]);
        par[base] = cleanup_calloc((size_t)n0 * sizeof *par[base]);
        w[base] = cleanup_calloc((size_t)n0 * sizeof *w[base]);
        assert_int_equal(bodt_mesh_get_vertex_parents(h[base], off[base], (size_t)s0.nv + 1, par[base], w[base],
                                                      (size_t)n0),
                         BODT_OK);
    }
    assert_memory_equal(off[0], off[1], ((size_t)s0.nv + 1) * sizeof(int64_t));
    assert_memory_equal(w[0], w[1], (size_t)n0 * sizeof(double));
    for (int64_t k = 0; k < n0; ++k) assert_int_equal(par[1][k], par[0][k] + 1);
    /* where the made vertices are against where their parents put them:
     * the input did not move (every input vertex is fixed), so the parents'
     * interpolation must give each made vertex's place (the library
     * re-derives the weights after the ODT relocation of an insertion) */
    double worst = 0.0;
    for (int32_t v = b.m->nverts; v < s0.nv; ++v) {
        double p[3] = {0, 0, 0};
        for (int64_t k = off[0][v]; k < off[0][v + 1]; ++k)
            for (int i = 0; i < 3; ++i) p[i] += w[0][k] * b.m->xyz[3 * par[0][k] + i];
        double d = 0.0;
        for (int i = 0; i < 3; ++i) d += (p[i] - s0.xyz[3 * v + i]) * (p[i] - s0.xyz[3 * v + i]);
        worst = fmax(worst, sqrt(d));
    }
    print_message("%d made vertices, %lld parent entries; made vertices lie up to %.3g from their parents' "
                  "interpolation (box size %g)\n",
                  made0, (long long)n0, worst, b.size);
    if (!(worst <= 1e-12 * b.size)) fail_msg("a made vertex lies %g from its parents' interpolation", worst);

    /* refusals: too small capacities, NULL pointers, NULL handle */
    bodt_mesh *g = h[0];
    const size_t nv = (size_t)s0.nv, nt = (size_t)s0.nt, n = (size_t)n0;
    assert_int_equal(bodt_mesh_get_parent_count(g, NULL), E);
    assert_int_equal(bodt_mesh_get_parent_count(NULL, &count), E);
    assert_int_equal(bodt_mesh_get_vertex_parents(g, off[0], nv, par[0], w[0], n), E);
    assert_contains(bodt_mesh_last_error(g), "offsets");
    assert_int_equal(bodt_mesh_get_vertex_parents(g, off[0], nv + 1, par[0], w[0], n - 1), E);
    assert_contains(bodt_mesh_last_error(g), "parents");
    assert_int_equal(bodt_mesh_get_vertex_parents(g, NULL, nv + 1, par[0], w[0], n), E);
    assert_int_equal(bodt_mesh_get_vertex_parents(g, off[0], nv + 1, NULL, w[0], n), E);
    assert_int_equal(bodt_mesh_get_vertex_parents(g, off[0], nv + 1, par[0], NULL, n), E);
    assert_int_equal(bodt_mesh_get_vertex_parents(NULL, off[0], nv + 1, par[0], w[0], n), E);
    /* capacities of the input counts are too small now */
    assert_int_equal(bodt_mesh_get_vertex_parents(g, off[0], (size_t)b.m->nverts + 1, par[0], w[0], n), E);
    assert_int_equal(bodt_mesh_get_tet_origins(g, o1, nt - 1), E);
    assert_contains(bodt_mesh_last_error(g), "origins");
    assert_int_equal(bodt_mesh_get_tet_origins(g, NULL, nt), E);
    assert_int_equal(bodt_mesh_get_tet_origins(NULL, o1, nt), E);
    assert_int_equal(bodt_mesh_get_tet_origins(g, o1, nt), BODT_OK);
    assert_string_equal(bodt_mesh_last_error(g), "");
    double *xyz = cleanup_calloc(3 * nv * sizeof *xyz);
    int32_t *ints = cleanup_calloc(4 * nt * sizeof *ints);
    assert_int_equal(bodt_mesh_get_vertices(g, xyz, 3 * (size_t)b.m->nverts), E);
    assert_int_equal(bodt_mesh_get_tets(g, ints, 4 * (size_t)b.m->ntets), E);
    assert_int_equal(bodt_mesh_get_fixed_vertices(g, ints, (size_t)b.m->nverts), E);
    assert_int_equal(bodt_mesh_get_vertex_classes(g, ints, (size_t)b.m->nverts), E);
    assert_int_equal(bodt_mesh_get_regions(g, ints, nt - 1), E);
    assert_int_equal(bodt_mesh_tet_quality(g, BODT_MEASURE_VOLUME, xyz, nt - 1), E);
    assert_int_equal(bodt_mesh_get_boundary_faces(g, ints, NULL, (size_t)s0.nb - 1), E);
}

/* ------------------------------------------------------- sized report */

typedef struct run_totals {
    int steps;
    long changes;
} run_totals;

static int sum_report(const bodt_step_report *r, void *user) {
    run_totals *t = user;
    assert_int_equal(r->size, sizeof(bodt_step_report));
    assert_int_equal(r->reserved1, 0);
    ++t->steps;
    t->changes += r->flips + r->vertices_inserted + r->edges_collapsed;
    return 0;
}

static void test_sized_report(void **state) {
    (void)state;
    const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 1, 0);
    run_opts o = opts(BODT_MODE_BODT, BODT_OPS_MODE_DEFAULT);
    o.fix = FIX_ALL;
    o.bad_angle = 25.0;
    bodt_mesh *h = create_handle(&b, 0, 0), *twin = create_handle(&b, 0, 0);
    setup(h, &b, &o, 0);
    setup(twin, &b, &o, 0);
    const size_t prefix = offsetof(bodt_step_report, flips);
    unsigned char buf[sizeof(bodt_step_report) + 64];
    bodt_step_report *r = (bodt_step_report *)(void *)buf;
    long changes = 0;
    for (int k = 1; k <= 3; ++k) {
        bodt_step_report full;
        step_ok(twin, &full);
        changes += full.flips + full.vertices_inserted;
        memset(buf, 0xCD, sizeof buf);
        r->size = prefix;
        assert_int_equal(bodt_step(h, r), BODT_OK);
        assert_int_equal(r->size, prefix);
        assert_int_equal(r->step, k);
        assert_int_equal(r->vertices_moved, full.vertices_moved);
        assert_int_equal(r->moves_rejected, full.moves_rejected);
        assert_int_equal(r->not_positive_definite, full.not_positive_definite);
        assert_true(r->max_move == full.max_move);
        assert_true(r->min_dihedral == full.min_dihedral);
        assert_true(r->max_dihedral == full.max_dihedral);
        assert_true(r->min_stretch == full.min_stretch);
        for (size_t i = prefix; i < sizeof buf; ++i)
            if (buf[i] != 0xCD) fail_msg("step %d: byte %zu of a report of size %zu written", k, i, prefix);
    }
    assert_true(changes > 0); /* the steps did change the connectivity */
    /* and the two handles hold the same mesh */
    const snap a = take(h, 0), c = take(twin, 0);
    assert_int_equal(a.nv, c.nv);
    assert_int_equal(a.nt, c.nt);
    assert_memory_equal(a.xyz, c.xyz, 3 * (size_t)a.nv * sizeof(double));
    assert_memory_equal(a.tets, c.tets, 4 * (size_t)a.nt * sizeof(int32_t));
    /* the full struct in a bigger buffer: nothing past it */
    memset(buf, 0xCD, sizeof buf);
    r->size = sizeof(bodt_step_report);
    assert_int_equal(bodt_step(h, r), BODT_OK);
    assert_int_equal(r->reserved1, 0);
    for (size_t i = sizeof(bodt_step_report); i < sizeof buf; ++i) assert_int_equal(buf[i], 0xCD);
    /* the callback of bodt_run gets the full report */
    run_totals t = {0, 0};
    assert_int_equal(bodt_run(h, 3, sum_report, &t), BODT_OK);
    assert_true(t.steps >= 1);
}

/* ------------------------------------------------------------ collapse */

static void test_collapse(void **state) {
    (void)state;
    long collapsed = 0;
    run_result res;
    for (int k = 0; k < 3; ++k) {
        const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 1 + 40 * (uint64_t)k, k == 2);
        run_opts o = opts(BODT_MODE_BODT, BODT_OP_SMOOTH | BODT_OP_FLIP | BODT_OP_INSERT | BODT_OP_COLLAPSE);
        if (k == 1) o.ops = BODT_OP_COLLAPSE, o.bad_angle = 30.0, o.features = 1;
        if (k == 2) o.ops = BODT_OP_FLIP | BODT_OP_COLLAPSE, o.fix = FIX_SOME, o.bad_angle = 30.0;
        checked_run(&b, &o, k == 0 ? "all ops" : k == 1 ? "collapse only" : "flip|collapse, some fixed", &res);
        collapsed += res.collapsed;
    }
    print_message("%ld edges collapsed\n", collapsed);
    assert_true(collapsed > 0);
}

/* ------------------------------------------------------------ files */

/* A mesh whose connectivity changed (and with an input vertex a collapse
 * left unused) written as Medit and TetGen and read back: the same
 * vertices, tets, regions, marked faces and fixed vertices. */
static void test_files_after_ops(void **state) {
    (void)state;
    if (mkdir(BODT_TEST_OPS_DIR, 0755) != 0 && errno != EEXIST)
        fail_msg("cannot create %s: %s", BODT_TEST_OPS_DIR, strerror(errno));
    const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 223, 1);
    run_opts o = opts(BODT_MODE_BODT, BODT_OP_FLIP | BODT_OP_INSERT | BODT_OP_COLLAPSE);
    o.bad_angle = 25.0;
    o.fix = FIX_SOME;
    o.steps = 3;
    run_result res;
    bodt_mesh *h = checked_run(&b, &o, "flip|insert|collapse, files", &res);
    assert_true(res.inserted > 0);
    print_message("%d vertices in no tet\n", res.unused1);
    assert_true(res.unused1 > 0);
    const snap s = take(h, 0);
    static const char *const names[2] = {"after_ops.mesh", "after_ops.node"};
    for (int k = 0; k < 2; ++k) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", BODT_TEST_OPS_DIR, names[k]);
        const int st = bodt_mesh_write(h, path);
        if (st != BODT_OK) fail_msg("write %s: %s", path, bodt_mesh_last_error(h));
        bodt_mesh *back = NULL;
        if (bodt_mesh_read(path, &back) != BODT_OK) fail_msg("read %s: %s", path, bodt_mesh_last_error(NULL));
        cleanup_add(back, destroy_mesh);
        const snap r = take(back, 0);
        assert_int_equal(r.nv, s.nv);
        assert_int_equal(r.nt, s.nt);
        assert_int_equal(r.nb, s.nb);
        assert_memory_equal(r.xyz, s.xyz, 3 * (size_t)s.nv * sizeof(double));
        assert_memory_equal(r.tets, s.tets, 4 * (size_t)s.nt * sizeof(int32_t));
        assert_memory_equal(r.regions, s.regions, (size_t)s.nt * sizeof(int32_t));
        assert_memory_equal(r.faces, s.faces, 3 * (size_t)s.nb * sizeof(int32_t));
        assert_memory_equal(r.markers, s.markers, (size_t)s.nb * sizeof(int32_t));
        if (k == 0) assert_memory_equal(r.fixed, s.fixed, (size_t)s.nv * sizeof(int32_t)); /* TetGen has none */
    }
}

/* --------------------------------------------------------------- no ops */

static void test_no_ops(void **state) {
    (void)state;
    const bad_mesh b = make_bad(BAD_N, BAD_SIZE, BAD_JITTER, 1, 0);
    for (int mode = BODT_MODE_LAPLACE; mode <= BODT_MODE_BODT; ++mode) {
        bodt_mesh *h = create_handle(&b, 0, 0);
        assert_int_equal(bodt_set_mode(h, mode), BODT_OK);
        assert_int_equal(bodt_set_param_int(h, BODT_PARAM_OPS, 0), BODT_OK);
        const snap s0 = take(h, 0);
        bodt_step_report r;
        step_ok(h, &r);
        assert_int_equal(r.vertices_moved, 0);
        assert_int_equal(r.flips, 0);
        assert_int_equal(r.vertices_inserted, 0);
        assert_int_equal(r.edges_collapsed, 0);
        assert_true(r.max_move == 0.0);
        const snap s = take(h, 0);
        assert_int_equal(s.nv, s0.nv);
        assert_int_equal(s.nt, s0.nt);
        assert_memory_equal(s.xyz, s0.xyz, 3 * (size_t)s.nv * sizeof(double));
        assert_memory_equal(s.tets, s0.tets, 4 * (size_t)s.nt * sizeof(int32_t));
        /* bodt_run stops at once: nothing moves */
        assert_int_equal(bodt_run(h, 5, NULL, NULL), BODT_OK);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_params, cleanup_teardown),
        cmocka_unit_test_teardown(test_default_ops, cleanup_teardown),
        cmocka_unit_test_teardown(test_smooth_only_vs_default, cleanup_teardown),
        cmocka_unit_test_teardown(test_keep_surface, cleanup_teardown),
        cmocka_unit_test_teardown(test_parents_and_origins, cleanup_teardown),
        cmocka_unit_test_teardown(test_sized_report, cleanup_teardown),
        cmocka_unit_test_teardown(test_collapse, cleanup_teardown),
        cmocka_unit_test_teardown(test_no_ops, cleanup_teardown),
        cmocka_unit_test_teardown(test_files_after_ops, cleanup_teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
