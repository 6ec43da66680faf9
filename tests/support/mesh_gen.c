#include "mesh_gen.h"

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
