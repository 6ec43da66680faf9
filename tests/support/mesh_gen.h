/*
 * Test meshes made in code: boxes of cubes split into six tets each (the
 * Kuhn / Freudenthal subdivision), optionally with some cubes left out, and
 * with a deterministic jitter of the interior vertices.  Plain C, no library
 * code: the meshes are the tests' independent input.
 */
#ifndef BODT_TEST_MESH_GEN_H
#define BODT_TEST_MESH_GEN_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A 64-bit linear congruential generator (Knuth's MMIX constants); the
 * same seed gives the same numbers on every platform. */
typedef struct tm_rng {
    uint64_t state;
} tm_rng;

void tm_rng_seed(tm_rng *rng, uint64_t seed);
/* Uniform in [0, 1), from the top 53 bits of the state. */
double tm_rng_uniform(tm_rng *rng);

typedef struct test_mesh {
    int32_t nverts;
    int32_t ntets;
    double *xyz;             /* 3 * nverts */
    int32_t *tets;           /* 4 * ntets, 0-based, every tet positively oriented */
    unsigned char *boundary; /* nverts flags: 1 on the boundary of the domain */
} test_mesh;

/* Which cubes (i, j, k in [0, n)) of an n x n x n grid to keep. */
typedef int (*tm_cube_filter)(int i, int j, int k, int n, void *user);

/*
 * The box [0, size]^3 cut into n^3 cubes of side h = size / n, each cube cut
 * into six tets around its main diagonal.  Interior vertices (those whose
 * eight surrounding cubes are all kept) move by up to jitter * h along each
 * axis, drawn from tm_rng seeded with `seed`.  With `keep` non-NULL only the
 * cubes it accepts are meshed and vertices used by no kept cube are left out.
 * Returns 0; -1 when out of memory or no cube was kept; -2 when the jitter
 * inverted a tet (nothing is allocated then).
 */
int tm_make_cubes(test_mesh *m, int n, double size, tm_cube_filter keep, void *user, double jitter,
                  uint64_t seed);
/* tm_make_cubes for the unit box [0, 1]^3 with every cube kept. */
int tm_make_box(test_mesh *m, int n, double jitter, uint64_t seed);
void tm_free(test_mesh *m);

/* Number of interior (not boundary) vertices. */
int32_t tm_count_interior(const test_mesh *m);

/* (b - a) . ((c - a) x (d - a)), six times the signed volume. */
double tm_orient6(const double *a, const double *b, const double *c, const double *d);

#ifdef __cplusplus
}
#endif

#endif /* BODT_TEST_MESH_GEN_H */
