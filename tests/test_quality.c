/*
 * test_quality: dihedral angles, stretch, volume and the histogram, through
 * libbodt.so, against values computed here.
 *
 * Expected values come from closed-form formulas derived for each shape (in
 * the comments), and are cross-checked against a direct computation in this
 * file (dihedral angles from face normals, stretch = 6 sqrt(6) V / (sum of
 * face areas * longest edge)); neither uses library code.
 */
#include "bodt.h"
#include "mesh_gen.h"
#include "test_util.h"

#include <stdio.h>
#include <stdlib.h>

#define DEG (180.0 / 3.14159265358979323846)

/* ---------------------------------------------------- independent geometry */

static void sub(const double *a, const double *b, double *out) {
    for (int k = 0; k < 3; ++k) out[k] = a[k] - b[k];
}
static void cross(const double *a, const double *b, double *out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double norm(const double *a) { return sqrt(dot(a, a)); }

/* Interior dihedral angle (degrees) at edge (p, q) of the tet (p, q, r, s):
 * the angle between the normals e x (r - p) and e x (s - p), e = q - p,
 * which are the two faces' normals turned the same way around the edge. */
static double dihedral_at(const double *p, const double *q, const double *r, const double *s) {
    double e[3], u[3], w[3], n1[3], n2[3];
    sub(q, p, e);
    sub(r, p, u);
    sub(s, p, w);
    cross(e, u, n1);
    cross(e, w, n2);
    double c = dot(n1, n2) / (norm(n1) * norm(n2));
    if (c > 1) c = 1;
    if (c < -1) c = -1;
    return acos(c) * DEG;
}

/* The six dihedral angles of tet (a, b, c, d). */
static void dihedrals(const double *x[4], double out[6]) {
    static const int edge[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};
    for (int e = 0; e < 6; ++e) out[e] = dihedral_at(x[edge[e][0]], x[edge[e][1]], x[edge[e][2]], x[edge[e][3]]);
}

static double tri_area(const double *a, const double *b, const double *c) {
    double u[3], v[3], n[3];
    sub(b, a, u);
    sub(c, a, v);
    cross(u, v, n);
    return 0.5 * norm(n);
}

/* 6 sqrt(6) V / (sum of face areas * longest edge), V signed. */
static double stretch_of(const double *x[4]) {
    const double v = tm_orient6(x[0], x[1], x[2], x[3]) / 6.0;
    const double area = tri_area(x[1], x[2], x[3]) + tri_area(x[0], x[2], x[3]) + tri_area(x[0], x[1], x[3]) +
                        tri_area(x[0], x[1], x[2]);
    double lmax = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            double e[3];
            sub(x[j], x[i], e);
            if (norm(e) > lmax) lmax = norm(e);
        }
    return 6.0 * sqrt(6.0) * v / (area * lmax);
}

static double min6(const double a[6]) {
    double m = a[0];
    for (int k = 1; k < 6; ++k) m = a[k] < m ? a[k] : m;
    return m;
}
static double max6(const double a[6]) {
    double m = a[0];
    for (int k = 1; k < 6; ++k) m = a[k] > m ? a[k] : m;
    return m;
}

/* ---------------------------------------------------------------- helpers */

static bodt_mesh *one_tet(const double pts[12]) {
    const int32_t tet[4] = {0, 1, 2, 3};
    bodt_mesh *h = NULL;
    const int st = bodt_mesh_create(4, pts, 1, tet, 0, &h);
    if (st != BODT_OK) fail_msg("create: %s", bodt_mesh_last_error(NULL));
    return h;
}

static double tet_measure(const bodt_mesh *h, int measure) {
    double v = NAN;
    assert_int_equal(bodt_mesh_tet_quality(h, measure, &v, 1), BODT_OK);
    return v;
}

static void get_quality(const bodt_mesh *h, bodt_quality *q) {
    memset(q, 0, sizeof *q);
    q->size = sizeof *q;
    assert_int_equal(bodt_mesh_quality(h, q), BODT_OK);
}

/* Library against expected min/max dihedral (degrees) and stretch, for a
 * one-tet mesh of the positively oriented points `pts`; also against this
 * file's direct computation. */
static void check_single(const double pts[12], double min_deg, double max_deg, double stretch, double volume) {
    const double *x[4] = {pts, pts + 3, pts + 6, pts + 9};
    assert_true(tm_orient6(x[0], x[1], x[2], x[3]) > 0);
    double a[6];
    dihedrals(x, a);
    /* the direct computation agrees with the closed forms */
    assert_near(min6(a), min_deg, 1e-9);
    assert_near(max6(a), max_deg, 1e-9);
    assert_near(stretch_of(x), stretch, 1e-12);

    bodt_mesh *h = one_tet(pts);
    assert_near(tet_measure(h, BODT_MEASURE_MIN_DIHEDRAL), min_deg, 1e-9);
    assert_near(tet_measure(h, BODT_MEASURE_MAX_DIHEDRAL), max_deg, 1e-9);
    assert_near(tet_measure(h, BODT_MEASURE_STRETCH), stretch, 1e-12);
    assert_near(tet_measure(h, BODT_MEASURE_VOLUME), volume, 1e-14 * fabs(volume));
    bodt_quality q;
    get_quality(h, &q);
    assert_int_equal(q.num_tets, 1);
    assert_int_equal(q.num_vertices, 4);
    assert_int_equal(q.num_boundary_faces, 4);
    assert_int_equal(q.num_inverted, 0);
    assert_int_equal(q.num_unused_vertices, 0);
    assert_near(q.min_dihedral, min_deg, 1e-9);
    assert_near(q.max_dihedral, max_deg, 1e-9);
    assert_near(q.mean_dihedral, (a[0] + a[1] + a[2] + a[3] + a[4] + a[5]) / 6.0, 1e-9);
    assert_near(q.min_stretch, stretch, 1e-12);
    assert_near(q.mean_stretch, stretch, 1e-12);
    assert_near(q.volume, volume, 1e-14 * fabs(volume));
    int64_t total = 0;
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b) total += q.dihedral_histogram[b];
    assert_int_equal(total, 6);
    bodt_mesh_destroy(h);
}

/* ------------------------------------------------------------------ tests */

static void test_bin_edges(void **state) {
    (void)state;
    static const double documented[BODT_DIHEDRAL_BINS + 1] = {0,   5,   10,  15,  20,  25,  30,  40,
                                                              50,  60,  70,  80,  90,  100, 110, 120,
                                                              130, 140, 150, 160, 165, 170, 175, 180};
    double edges[BODT_DIHEDRAL_BINS + 1];
    assert_int_equal(bodt_dihedral_bin_edges(edges, BODT_DIHEDRAL_BINS + 1), BODT_OK);
    for (int k = 0; k <= BODT_DIHEDRAL_BINS; ++k) assert_true(edges[k] == documented[k]);
}

/* The regular tet with vertices at alternate corners of a cube of side 2:
 * edge 2 sqrt(2), volume 8/3 exactly (the cube less four corners of 4/3),
 * every dihedral acos(1/3), stretch 1. */
static void test_regular_tet(void **state) {
    (void)state;
    const double pts[12] = {1, 1, 1, 1, -1, -1, -1, -1, 1, -1, 1, -1};
    const double angle = acos(1.0 / 3.0) * DEG;
    assert_near(angle, 70.528779365509308, 1e-12);
    check_single(pts, angle, angle, 1.0, 8.0 / 3.0);
    bodt_mesh *h = one_tet(pts);
    assert_true(tet_measure(h, BODT_MEASURE_VOLUME) == 8.0 / 3.0);
    bodt_quality q;
    get_quality(h, &q);
    assert_true(q.volume == 8.0 / 3.0);
    assert_near(q.mean_dihedral, angle, 1e-9);
    /* all six angles in the bin [70, 80) */
    double edges[BODT_DIHEDRAL_BINS + 1];
    assert_int_equal(bodt_dihedral_bin_edges(edges, BODT_DIHEDRAL_BINS + 1), BODT_OK);
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b)
        assert_int_equal(q.dihedral_histogram[b], (edges[b] <= angle && angle < edges[b + 1]) ? 6 : 0);
    assert_int_equal(q.dihedral_histogram[10], 6);
    bodt_mesh_destroy(h);
}

/* Sliver: a = (1, 0, 0), b = (-1, 0, 0) on one diagonal of a square, c, d =
 * (0, -+1, h) on the other, lifted by h.
 *   edges ab, cd (length 2): the other two vertices seen across the edge are
 *     (0, +-1, h) from ab, so cos = (h^2 - 1) / (h^2 + 1): angle pi - 2 atan h
 *   the four side edges (length sqrt(2 + h^2)): normals (0, -2h, 2) and
 *     (2h, 0, 2) (edge ac): cos = 1 / (1 + h^2)
 *   volume |det(b - a, c - a, d - a)| / 6 = 4h / 6 = 2h / 3
 *   four congruent faces of area sqrt(1 + h^2) (base 2, height sqrt(1 + h^2))
 *   stretch = 6 sqrt 6 (2h / 3) / (4 sqrt(1 + h^2) * 2) = sqrt 6 h / (2 sqrt(1 + h^2)) */
static void test_sliver(void **state) {
    (void)state;
    const double hs[3] = {0.3, 0.02, 1e-4};
    for (int k = 0; k < 3; ++k) {
        const double h = hs[k];
        const double pts[12] = {1, 0, 0, -1, 0, 0, 0, -1, h, 0, 1, h};
        const double min_deg = atan(h * sqrt(2.0 + h * h)) * DEG; /* = acos(1 / (1 + h^2)) */
        const double max_deg = 180.0 - 2.0 * atan(h) * DEG;
        const double stretch = sqrt(6.0) * h / (2.0 * sqrt(1.0 + h * h));
        check_single(pts, min_deg, max_deg, stretch, 2.0 * h / 3.0);
    }
}

/* A regular triangular pyramid: base vertices on the unit circle in z = 0
 * (side sqrt 3, inradius 1/2, area 3 sqrt 3 / 4), apex (0, 0, h) over the
 * centre.
 *   base edges: the apex is 1/2 from the edge and h high: atan(2h)
 *   side edges (from (1, 0, 0) to the apex): normals
 *     (-h sqrt3/2, -3h/2, -sqrt3/2) and (h sqrt3/2, -3h/2, sqrt3/2):
 *     cos = (2h^2 - 1) / (4h^2 + 1)
 *   volume sqrt 3 h / 4; side faces 1/2 sqrt 3 sqrt(1/4 + h^2) each
 *   longest edge max(sqrt 3, sqrt(1 + h^2)).
 * A small h gives a cap (apex just above the base: angles near 0 and 180); a
 * large h gives a spike (a needle: fine angles, poor stretch). */
static void pyramid(double h, double pts[12], double *min_deg, double *max_deg, double *stretch, double *volume) {
    const double s3 = sqrt(3.0);
    const double p[12] = {1, 0, 0, -0.5, s3 / 2, 0, -0.5, -s3 / 2, 0, 0, 0, h};
    memcpy(pts, p, sizeof p);
    const double base = atan(2.0 * h) * DEG;
    const double side = acos((2.0 * h * h - 1.0) / (4.0 * h * h + 1.0)) * DEG;
    *min_deg = base < side ? base : side;
    *max_deg = base > side ? base : side;
    *volume = s3 * h / 4.0;
    const double area = 3.0 * s3 / 4.0 + 3.0 * 0.5 * s3 * sqrt(0.25 + h * h);
    const double lmax = s3 > sqrt(1.0 + h * h) ? s3 : sqrt(1.0 + h * h);
    *stretch = 6.0 * sqrt(6.0) * *volume / (area * lmax);
}

static void test_cap(void **state) {
    (void)state;
    const double hs[3] = {0.05, 0.01, 1e-3};
    for (int k = 0; k < 3; ++k) {
        double pts[12], lo, hi, s, v;
        pyramid(hs[k], pts, &lo, &hi, &s, &v);
        assert_true(lo < 12.0 && hi > 168.0); /* really a cap */
        check_single(pts, lo, hi, s, v);
    }
}

static void test_spike(void **state) {
    (void)state;
    const double hs[3] = {5.0, 40.0, 1000.0};
    for (int k = 0; k < 3; ++k) {
        double pts[12], lo, hi, s, v;
        pyramid(hs[k], pts, &lo, &hi, &s, &v);
        assert_true(lo >= 59.0 && hi <= 90.0 && s < 0.5); /* fine angles, poor stretch */
        check_single(pts, lo, hi, s, v);
    }
    /* scaled down: the measures do not depend on size */
    double pts[12], lo, hi, s, v;
    pyramid(40.0, pts, &lo, &hi, &s, &v);
    for (int k = 0; k < 12; ++k) pts[k] *= 1e-3;
    check_single(pts, lo, hi, s, v * 1e-9);
}

/* An inverted tet (accepted with the flag) has negative stretch and counts as
 * a 0 and a 180 degree angle. */
static void test_inverted_tet(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, 2, 0.0, 1), 0);
    /* push the bottom-centre vertex (0.5, 0.5, 0) up past the centre */
    m.xyz[3 * 4 + 2] = 0.7;
    bodt_mesh *h = NULL;
    assert_int_equal(bodt_mesh_create_ex(m.nverts, m.xyz, m.ntets, m.tets, 0, BODT_CREATE_ACCEPT_INVERTED, &h),
                     BODT_OK);
    const size_t nt = (size_t)m.ntets;
    double *lo = malloc(nt * sizeof *lo), *hi = malloc(nt * sizeof *hi), *st = malloc(nt * sizeof *st),
           *vol = malloc(nt * sizeof *vol);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_MIN_DIHEDRAL, lo, nt), BODT_OK);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_MAX_DIHEDRAL, hi, nt), BODT_OK);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_STRETCH, st, nt), BODT_OK);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_VOLUME, vol, nt), BODT_OK);
    int inverted = 0;
    double min_stretch = 1.0;
    for (size_t t = 0; t < nt; ++t) {
        const double *x[4];
        for (int k = 0; k < 4; ++k) x[k] = m.xyz + 3 * m.tets[4 * t + k];
        const double v = tm_orient6(x[0], x[1], x[2], x[3]) / 6.0;
        assert_near(vol[t], v, 1e-15);
        assert_near(st[t], stretch_of(x), 1e-12);
        if (st[t] < min_stretch) min_stretch = st[t];
        if (v < 0) {
            ++inverted;
            assert_true(st[t] < 0.0);
            assert_true(lo[t] == 0.0);
            assert_true(hi[t] == 180.0);
        } else {
            double a[6];
            dihedrals(x, a);
            assert_near(lo[t], min6(a), 1e-9);
            assert_near(hi[t], max6(a), 1e-9);
        }
    }
    assert_true(inverted > 0);
    bodt_quality q;
    get_quality(h, &q);
    assert_int_equal(q.num_inverted, inverted);
    assert_true(q.min_dihedral == 0.0);
    assert_true(q.max_dihedral == 180.0);
    assert_near(q.min_stretch, min_stretch, 0.0);
    int64_t total = 0;
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b) total += q.dihedral_histogram[b];
    assert_int_equal(total, 6 * (int64_t)nt);
    assert_true(q.dihedral_histogram[0] >= inverted);                      /* the 0s */
    assert_true(q.dihedral_histogram[BODT_DIHEDRAL_BINS - 1] >= inverted); /* 180 is in the last bin */
    free(lo), free(hi), free(st), free(vol);
    bodt_mesh_destroy(h);
    tm_free(&m);
}

/* Every per-tet measure and the summary of a jittered box against the direct
 * computation; the histogram against one counted here with the library's
 * edges. */
static void test_box_measures_and_histogram(void **state) {
    (void)state;
    test_mesh m;
    assert_int_equal(tm_make_box(&m, 4, 0.3, 77), 0);
    bodt_mesh *h = NULL;
    assert_int_equal(bodt_mesh_create(m.nverts, m.xyz, m.ntets, m.tets, 0, &h), BODT_OK);
    const size_t nt = (size_t)m.ntets;
    double *lo = malloc(nt * sizeof *lo), *hi = malloc(nt * sizeof *hi), *st = malloc(nt * sizeof *st),
           *vol = malloc(nt * sizeof *vol);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_MIN_DIHEDRAL, lo, nt), BODT_OK);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_MAX_DIHEDRAL, hi, nt), BODT_OK);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_STRETCH, st, nt), BODT_OK);
    assert_int_equal(bodt_mesh_tet_quality(h, BODT_MEASURE_VOLUME, vol, nt), BODT_OK);
    double edges[BODT_DIHEDRAL_BINS + 1];
    assert_int_equal(bodt_dihedral_bin_edges(edges, BODT_DIHEDRAL_BINS + 1), BODT_OK);
    int64_t hist[BODT_DIHEDRAL_BINS] = {0};        /* angles clearly inside a bin */
    int64_t ambiguous[BODT_DIHEDRAL_BINS + 1] = {0}; /* angles on inner edge k */
    double min_deg = 180, max_deg = 0, sum_deg = 0, min_st = 1, sum_st = 0, sum_vol = 0;
    for (size_t t = 0; t < nt; ++t) {
        const double *x[4];
        for (int k = 0; k < 4; ++k) x[k] = m.xyz + 3 * m.tets[4 * t + k];
        double a[6];
        dihedrals(x, a);
        assert_near(lo[t], min6(a), 1e-9);
        assert_near(hi[t], max6(a), 1e-9);
        assert_near(st[t], stretch_of(x), 1e-12);
        assert_near(vol[t], tm_orient6(x[0], x[1], x[2], x[3]) / 6.0, 1e-16);
        for (int e = 0; e < 6; ++e) {
            /* an angle within round-off of an inner edge (the exact 90
             * degrees between two sides of the box) may go either way */
            int near_edge = 0;
            for (int k = 1; k < BODT_DIHEDRAL_BINS; ++k)
                if (fabs(a[e] - edges[k]) < 1e-9) near_edge = k;
            if (near_edge) {
                ++ambiguous[near_edge];
            } else {
                int b = 0;
                while (b < BODT_DIHEDRAL_BINS - 1 && a[e] >= edges[b + 1]) ++b;
                ++hist[b];
            }
            sum_deg += a[e];
        }
        min_deg = fmin(min_deg, min6(a));
        max_deg = fmax(max_deg, max6(a));
        min_st = fmin(min_st, st[t]);
        sum_st += st[t];
        sum_vol += vol[t];
    }
    bodt_quality q;
    get_quality(h, &q);
    assert_int_equal(q.num_vertices, m.nverts);
    assert_int_equal(q.num_tets, m.ntets);
    assert_int_equal(q.num_boundary_faces, 12 * 4 * 4);
    assert_int_equal(q.num_inverted, 0);
    assert_near(q.min_dihedral, min_deg, 1e-9);
    assert_near(q.max_dihedral, max_deg, 1e-9);
    assert_near(q.mean_dihedral, sum_deg / (6.0 * (double)nt), 1e-9);
    assert_near(q.min_stretch, min_st, 0.0);
    assert_near(q.mean_stretch, sum_st / (double)nt, 1e-12);
    assert_near(q.volume, 1.0, 1e-12);
    assert_near(q.volume, sum_vol, 1e-12);
    /* bin b holds the clear angles of [edges[b], edges[b+1]) and some of the
     * ones on its two edges; the count below each inner edge k is fixed up to
     * the angles on that edge */
    int64_t total = 0, clear_below = 0, amb_below = 0;
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b) {
        const int64_t got = q.dihedral_histogram[b];
        if (got < hist[b] || got > hist[b] + ambiguous[b] + ambiguous[b + 1])
            fail_msg("bin %d [%g, %g): library %lld, expected %lld (+ up to %lld on its edges)", b, edges[b],
                     edges[b + 1], (long long)got, (long long)hist[b], (long long)(ambiguous[b] + ambiguous[b + 1]));
        total += got;
        clear_below += hist[b];
        if (b + 1 < BODT_DIHEDRAL_BINS) {
            assert_true(total >= clear_below + amb_below && total <= clear_below + amb_below + ambiguous[b + 1]);
            amb_below += ambiguous[b + 1];
        }
    }
    assert_int_equal(total, 6 * (int64_t)nt);
    assert_true(hist[BODT_DIHEDRAL_BINS / 2] > 0); /* most angles are clear */
    free(lo), free(hi), free(st), free(vol);
    bodt_mesh_destroy(h);
    tm_free(&m);
}

/* The unjittered Kuhn tet: angles 45 (x2), 60 (x2), 90 (x2) degrees exactly
 * in closed form (its faces are right triangles of the cube). */
static void test_kuhn_tet(void **state) {
    (void)state;
    const double pts[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 1};
    /* volume 1/6; faces: two of area 1/2, two of area sqrt 2 / 2; longest
     * edge sqrt 3 */
    const double stretch = 6.0 * sqrt(6.0) * (1.0 / 6.0) / ((1.0 + sqrt(2.0)) * sqrt(3.0));
    check_single(pts, 45.0, 90.0, stretch, 1.0 / 6.0);
}

static void test_unknown_measure(void **state) {
    (void)state;
    const double pts[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    bodt_mesh *h = one_tet(pts);
    double v = -42.0;
    const int bad[4] = {0, 5, -1, 1000};
    for (int k = 0; k < 4; ++k) {
        assert_int_equal(bodt_mesh_tet_quality(h, bad[k], &v, 1), BODT_ERR_INVALID_ARGUMENT);
        assert_contains(bodt_mesh_last_error(h), "measure");
        assert_true(v == -42.0);
    }
    bodt_mesh_destroy(h);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bin_edges),
        cmocka_unit_test(test_regular_tet),
        cmocka_unit_test(test_kuhn_tet),
        cmocka_unit_test(test_sliver),
        cmocka_unit_test(test_cap),
        cmocka_unit_test(test_spike),
        cmocka_unit_test(test_inverted_tet),
        cmocka_unit_test(test_box_measures_and_histogram),
        cmocka_unit_test(test_unknown_measure),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
