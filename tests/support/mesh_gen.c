#include "mesh_gen.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void tm_rng_seed(tm_rng *rng, uint64_t seed) {
    rng->state = seed ^ 0x853C49E6748FEA9Bull;
}

double tm_rng_uniform(tm_rng *rng) {
    rng->state = rng->state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng->state >> 11) * (1.0 / 9007199254740992.0);
}

double tm_orient6(const double *a, const double *b, const double *c, const double *d) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

/* The six Kuhn tets of a cube: the path 0 -> e_a -> e_a + e_b -> 111 for each
 * permutation (a, b, c) of the axes.  Corners are bit masks (x = 1, y = 2,
 * z = 4).  Odd permutations are listed with their last two corners swapped so
 * that every tet is positively oriented. */
static const int kKuhn[6][4] = {
    {0, 1, 3, 7}, /* x y z (even) */
    {0, 2, 6, 7}, /* y z x (even) */
    {0, 4, 5, 7}, /* z x y (even) */
    {0, 1, 7, 5}, /* x z y (odd: 0 1 5 7 swapped) */
    {0, 2, 7, 3}, /* y x z (odd: 0 2 3 7 swapped) */
    {0, 4, 7, 6}, /* z y x (odd: 0 4 6 7 swapped) */
};

static int keep_all(int i, int j, int k, int n, void *user) {
    (void)i, (void)j, (void)k, (void)n, (void)user;
    return 1;
}

int tm_make_cubes(test_mesh *m, int n, double size, tm_cube_filter keep, void *user, double jitter,
                  uint64_t seed) {
    memset(m, 0, sizeof *m);
    if (!keep) keep = keep_all;
    const int g = n + 1; /* grid points per axis */
    const size_t ng = (size_t)g * g * g;
    const double h = size / n;
    unsigned char *kept = calloc((size_t)n * n * n, 1);
    int32_t *map = malloc(ng * sizeof *map);
    int *cubes_around = calloc(ng, sizeof(int));
    if (!kept || !map || !cubes_around) goto fail;

    size_t nkept = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                if (keep(i, j, k, n, user)) {
                    kept[((size_t)k * n + j) * n + i] = 1;
                    ++nkept;
                    for (int c = 0; c < 8; ++c) {
                        const size_t p = ((size_t)(k + (c >> 2 & 1)) * g + (j + (c >> 1 & 1))) * g + (i + (c & 1));
                        ++cubes_around[p];
                    }
                }
    if (nkept == 0) goto fail;

    int32_t nv = 0;
    for (size_t p = 0; p < ng; ++p) map[p] = cubes_around[p] ? nv++ : -1;
    m->nverts = nv;
    m->ntets = (int32_t)(6 * nkept);
    m->xyz = malloc((size_t)nv * 3 * sizeof(double));
    m->tets = malloc((size_t)m->ntets * 4 * sizeof(int32_t));
    m->boundary = malloc((size_t)nv);
    if (!m->xyz || !m->tets || !m->boundary) goto fail;

    tm_rng rng;
    tm_rng_seed(&rng, seed);
    for (int k = 0; k < g; ++k)
        for (int j = 0; j < g; ++j)
            for (int i = 0; i < g; ++i) {
                const size_t p = ((size_t)k * g + j) * g + i;
                if (map[p] < 0) continue;
                const int32_t v = map[p];
                const int interior = cubes_around[p] == 8;
                const int idx[3] = {i, j, k};
                m->boundary[v] = (unsigned char)!interior;
                for (int a = 0; a < 3; ++a) {
                    double x = idx[a] * h;
                    if (interior && jitter > 0.0) x += (2.0 * tm_rng_uniform(&rng) - 1.0) * jitter * h;
                    m->xyz[3 * v + a] = x;
                }
            }

    size_t t = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                if (!kept[((size_t)k * n + j) * n + i]) continue;
                for (int s = 0; s < 6; ++s) {
                    for (int c = 0; c < 4; ++c) {
                        const int corner = kKuhn[s][c];
                        const size_t p =
                            ((size_t)(k + (corner >> 2 & 1)) * g + (j + (corner >> 1 & 1))) * g + (i + (corner & 1));
                        m->tets[4 * t + c] = map[p];
                    }
                    ++t;
                }
            }
    free(kept);
    free(map);
    free(cubes_around);
    /* too much jitter can invert a tet: refuse rather than hand it out */
    for (int32_t q = 0; q < m->ntets; ++q) {
        const int32_t *v = &m->tets[4 * q];
        if (!(tm_orient6(m->xyz + 3 * v[0], m->xyz + 3 * v[1], m->xyz + 3 * v[2], m->xyz + 3 * v[3]) > 0.0)) {
            tm_free(m);
            return -2;
        }
    }
    return 0;

fail:
    free(kept);
    free(map);
    free(cubes_around);
    tm_free(m);
    return -1;
}

int tm_make_box(test_mesh *m, int n, double jitter, uint64_t seed) {
    return tm_make_cubes(m, n, 1.0, NULL, NULL, jitter, seed);
}

int tm_make_lazy(test_mesh *m, int npoints, uint64_t seed) {
    if (tm_make_box(m, 1, 0.0, seed) != 0) return -1;
    double *xyz = realloc(m->xyz, 3 * sizeof *xyz * (size_t)(m->nverts + npoints));
    if (xyz) m->xyz = xyz;
    int32_t *tets = realloc(m->tets, 4 * sizeof *tets * (size_t)(m->ntets + 3 * npoints));
    if (tets) m->tets = tets;
    if (!xyz || !tets) {
        tm_free(m);
        return -1;
    }
    tm_rng rng;
    tm_rng_seed(&rng, seed);
    for (int i = 0; i < npoints; ++i) {
        double p[3];
        for (int a = 0; a < 3; ++a) p[a] = 0.02 + 0.96 * tm_rng_uniform(&rng);
        for (int32_t t = 0; t < m->ntets; ++t) {
            int32_t *q = &m->tets[4 * t];
            const double *x[4] = {m->xyz + 3 * q[0], m->xyz + 3 * q[1], m->xyz + 3 * q[2], m->xyz + 3 * q[3]};
            const double whole = tm_orient6(x[0], x[1], x[2], x[3]);
            double lowest = 1.0; /* p's smallest barycentric coordinate */
            for (int k = 0; k < 4; ++k) {
                const double *y[4] = {x[0], x[1], x[2], x[3]};
                y[k] = p;
                const double l = tm_orient6(y[0], y[1], y[2], y[3]) / whole;
                if (l < lowest) lowest = l;
            }
            if (lowest < 1e-3) continue;
            const int32_t v = m->nverts++;
            memcpy(m->xyz + 3 * v, p, sizeof p);
            const int32_t old[4] = {q[0], q[1], q[2], q[3]};
            for (int k = 0; k < 4; ++k) { /* corner k replaced by p: positive as the old tet */
                int32_t *r = k == 0 ? q : &m->tets[4 * m->ntets++];
                memcpy(r, old, sizeof old);
                r[k] = v;
            }
            break;
        }
    }
    return 0;
}

void tm_free(test_mesh *m) {
    free(m->xyz);
    free(m->tets);
    free(m->boundary);
    memset(m, 0, sizeof *m);
}

int32_t tm_count_interior(const test_mesh *m) {
    int32_t n = 0;
    for (int32_t v = 0; v < m->nverts; ++v) n += !m->boundary[v];
    return n;
}

/* ------------------------------------------------ sliding boundary jitter */

typedef struct sliding_labels {
    int n;
    tm_cube_filter keep;
    tm_cube_region region;
    void *user;
} sliding_labels;

/* -1 for a cube outside the grid or not kept, else its region id. */
static int cube_label(const sliding_labels *L, int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= L->n || j >= L->n || k >= L->n) return -1;
    if (L->keep && !L->keep(i, j, k, L->n, L->user)) return -1;
    return L->region ? L->region(i, j, k, L->n, L->user) : 0;
}

/* Bit a set when the eight cubes around grid vertex (gi, gj, gk) look the
 * same after flipping axis a. */
static unsigned char free_axes_at(const sliding_labels *L, int gi, int gj, int gk) {
    int label[8];
    for (int c = 0; c < 8; ++c) label[c] = cube_label(L, gi - 1 + (c & 1), gj - 1 + (c >> 1 & 1), gk - 1 + (c >> 2 & 1));
    unsigned char mask = 0;
    for (int a = 0; a < 3; ++a) {
        int same = 1;
        for (int c = 0; c < 8; ++c) same &= label[c] == label[c ^ (1 << a)];
        if (same) mask |= (unsigned char)(1u << a);
    }
    return mask;
}

int tm_make_cubes_sliding(test_mesh *m, int n, double size, tm_cube_filter keep, tm_cube_region region,
                          void *user, double jitter, double boundary_jitter, uint64_t seed,
                          unsigned char **free_axes, int32_t **regions) {
    if (free_axes) *free_axes = NULL;
    if (regions) *regions = NULL;
    const int st = tm_make_cubes(m, n, size, keep, user, 0.0, seed);
    if (st != 0) return st;
    const sliding_labels L = {n, keep, region, user};
    const double h = size / n;
    unsigned char *axes = malloc((size_t)m->nverts);
    int32_t *reg = malloc((size_t)m->ntets * sizeof *reg);
    if (!axes || !reg) {
        free(axes);
        free(reg);
        tm_free(m);
        return -1;
    }
    tm_rng rng;
    tm_rng_seed(&rng, seed);
    for (int32_t v = 0; v < m->nverts; ++v) {
        int g[3];
        for (int a = 0; a < 3; ++a) { /* unjittered: exactly idx * h */
            const double q = m->xyz[3 * v + a] / h;
            g[a] = (int)(q + 0.5);
        }
        axes[v] = free_axes_at(&L, g[0], g[1], g[2]);
        const double amp = (m->boundary[v] ? boundary_jitter : jitter) * h;
        for (int a = 0; a < 3; ++a) {
            const double r = 2.0 * tm_rng_uniform(&rng) - 1.0; /* drawn for every axis: same stream */
            if (axes[v] >> a & 1) m->xyz[3 * v + a] += r * amp;
        }
    }
    /* the tets of tm_make_cubes: six per kept cube, cubes in k, j, i order */
    int32_t t = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int label = cube_label(&L, i, j, k);
                if (label < 0) continue;
                for (int s = 0; s < 6; ++s) reg[t++] = label;
            }
    for (int32_t q = 0; q < m->ntets; ++q) {
        const int32_t *v = &m->tets[4 * q];
        if (!(tm_orient6(m->xyz + 3 * v[0], m->xyz + 3 * v[1], m->xyz + 3 * v[2], m->xyz + 3 * v[3]) > 0.0)) {
            free(axes);
            free(reg);
            tm_free(m);
            return -2;
        }
    }
    if (free_axes) *free_axes = axes;
    else free(axes);
    if (regions) *regions = reg;
    else free(reg);
    return 0;
}

/* ----------------------------------------------------------- shape maps */

static int all_positive(const test_mesh *m) {
    for (int32_t q = 0; q < m->ntets; ++q) {
        const int32_t *v = &m->tets[4 * q];
        if (!(tm_orient6(m->xyz + 3 * v[0], m->xyz + 3 * v[1], m->xyz + 3 * v[2], m->xyz + 3 * v[3]) > 0.0))
            return 0;
    }
    return 1;
}

int tm_map_square_to_disk(test_mesh *m) {
    for (int32_t v = 0; v < m->nverts; ++v) {
        double *p = &m->xyz[3 * v];
        const double x = p[0] - 1.0, y = p[1] - 1.0;
        p[0] = x * sqrt(fmax(0.0, 1.0 - 0.5 * y * y));
        p[1] = y * sqrt(fmax(0.0, 1.0 - 0.5 * x * x));
    }
    return all_positive(m) ? 0 : -2;
}

int tm_map_cube_to_ball(test_mesh *m) {
    for (int32_t v = 0; v < m->nverts; ++v) {
        double *p = &m->xyz[3 * v];
        const double x = p[0] - 1.0, y = p[1] - 1.0, z = p[2] - 1.0;
        const double x2 = x * x, y2 = y * y, z2 = z * z;
        p[0] = x * sqrt(fmax(0.0, 1.0 - 0.5 * y2 - 0.5 * z2 + y2 * z2 / 3.0));
        p[1] = y * sqrt(fmax(0.0, 1.0 - 0.5 * z2 - 0.5 * x2 + z2 * x2 / 3.0));
        p[2] = z * sqrt(fmax(0.0, 1.0 - 0.5 * x2 - 0.5 * y2 + x2 * y2 / 3.0));
    }
    return all_positive(m) ? 0 : -2;
}

/* ---------------------------------------------------- box with a hole */

/* Direction j of tm_make_box_with_hole: the unit vector d_j on ring 0 and
 * the point s_j of the square of half width 1 on the same ray.  Computed for
 * the side x = +1 and turned by exact quarter turns (x, y) -> (-y, x), so
 * zeros stay zeros and the square's corners are exactly +-1. */
static void hole_direction(int j, int nt, double d[2], double s[2]) {
    const int per_side = nt / 4;
    const int q = j / per_side, m = j % per_side;
    const double pi = 3.14159265358979323846;
    const double psi = -0.25 * pi + 0.5 * pi * (double)m / per_side;
    d[0] = cos(psi);
    d[1] = sin(psi);
    s[0] = 1.0;
    s[1] = m == 0 ? -1.0 : d[1] / d[0]; /* tan(-pi/4) = -1 exactly */
    for (int turn = 0; turn < q; ++turn) {
        double x = d[0];
        d[0] = -d[1];
        d[1] = x;
        x = s[0];
        s[0] = -s[1];
        s[1] = x;
    }
}

/* (x, y) of vertex (ring i, angle j) of the undeformed mesh. */
static void hole_point(int i, int j, int nr, int nt, double half_width, double radius, double p[2]) {
    double d[2], s[2];
    hole_direction(j, nt, d, s);
    const double t = (double)i / nr;
    for (int a = 0; a < 2; ++a) {
        const double inner = radius * d[a], outer = half_width * s[a];
        p[a] = i == 0 ? inner : i == nr ? outer : (1.0 - t) * inner + t * outer;
    }
}

static int hole_args_ok(int nr, int nt, int nz, double half_width, double radius) {
    return nr >= 1 && nz >= 1 && nt >= 4 && nt % 4 == 0 && radius > 0.0 && half_width > radius &&
           (double)nt * (nr + 1) * (nz + 1) < 2e9 && 6.0 * nr * nt * nz < 2e9;
}

int tm_make_box_with_hole(test_mesh *m, int nr, int nt, int nz, double half_width, double radius, double height) {
    memset(m, 0, sizeof *m);
    if (!hole_args_ok(nr, nt, nz, half_width, radius) || !(height > 0.0)) return -1;
    const int rings = nr + 1;
    m->nverts = (int32_t)nt * rings * (nz + 1);
    m->ntets = (int32_t)6 * nr * nt * nz;
    m->xyz = malloc((size_t)m->nverts * 3 * sizeof(double));
    m->tets = malloc((size_t)m->ntets * 4 * sizeof(int32_t));
    m->boundary = malloc((size_t)m->nverts);
    if (!m->xyz || !m->tets || !m->boundary) {
        tm_free(m);
        return -1;
    }
    for (int k = 0; k <= nz; ++k)
        for (int i = 0; i <= nr; ++i)
            for (int j = 0; j < nt; ++j) {
                const size_t v = ((size_t)k * rings + i) * nt + j;
                double p[2];
                hole_point(i, j, nr, nt, half_width, radius, p);
                m->xyz[3 * v] = p[0];
                m->xyz[3 * v + 1] = p[1];
                m->xyz[3 * v + 2] = k == nz ? height : height * k / nz;
                m->boundary[v] = (unsigned char)(i == 0 || i == nr || k == 0 || k == nz);
            }
    size_t t = 0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < nt; ++j)
            for (int i = 0; i < nr; ++i)
                for (int s = 0; s < 6; ++s) {
                    for (int c = 0; c < 4; ++c) {
                        const int corner = kKuhn[s][c];
                        const int ci = i + (corner & 1), cj = (j + (corner >> 1 & 1)) % nt, ck = k + (corner >> 2 & 1);
                        m->tets[4 * t + c] = (int32_t)(((size_t)ck * rings + ci) * nt + cj);
                    }
                    ++t;
                }
    if (!all_positive(m)) {
        tm_free(m);
        return -2;
    }
    return 0;
}

void tm_deform_box_with_hole(test_mesh *m, int nr, int nt, int nz, double stretch_x, double new_radius,
                             double half_width, double radius) {
    if (!hole_args_ok(nr, nt, nz, half_width, radius) || m->nverts != (int32_t)nt * (nr + 1) * (nz + 1)) return;
    for (int32_t v = 0; v < m->nverts; ++v) {
        const int j = v % nt, i = v / nt % (nr + 1);
        double p[2];
        hole_point(i, j, nr, nt, half_width, radius, p);
        if (p[0] > 0.0) p[0] *= stretch_x; /* (a) */
        if (i == 0) {                      /* (b) */
            double d[2], s[2];
            hole_direction(j, nt, d, s);
            p[0] = new_radius * d[0];
            p[1] = new_radius * d[1];
        }
        m->xyz[3 * v] = p[0];
        m->xyz[3 * v + 1] = p[1];
    }
}
