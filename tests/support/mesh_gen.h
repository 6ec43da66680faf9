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
/* The unit cube's six Kuhn tets, then `npoints` random points inside,
 * each splitting the tet that holds it 1 -> 4 (points closer than a
 * thousandth of the tet's volume to one of its faces are dropped): a
 * "lazy" mesh full of needles and slivers, as the bench's rand.lazy.
 * Returns 0, or -1 when out of memory. */
int tm_make_lazy(test_mesh *m, int npoints, uint64_t seed);
void tm_free(test_mesh *m);

/* Number of interior (not boundary) vertices. */
int32_t tm_count_interior(const test_mesh *m);

/* (b - a) . ((c - a) x (d - a)), six times the signed volume. */
double tm_orient6(const double *a, const double *b, const double *c, const double *d);

#ifdef __cplusplus
}
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* The region id of a kept cube, for tm_make_cubes_sliding. */
typedef int (*tm_cube_region)(int i, int j, int k, int n, void *user);

/*
 * The mesh of tm_make_cubes (same vertices, tets and tet order), with every
 * vertex jittered only along the axes along which the mesh around it looks
 * the same: an axis is free at a grid vertex when its eight surrounding
 * cubes, labelled by region id (or "not kept", also outside the grid), are
 * symmetric under the flip of that axis.  So a vertex inside one region
 * moves along all three axes, a vertex on a flat face of the domain (or on a
 * flat interface between regions) in the face's plane, a vertex on a
 * straight edge of the domain along the edge's line, and a corner not at
 * all: the domain and every region keep their exact shape and volume.
 * Vertices on the domain boundary move by up to boundary_jitter * h along
 * each free axis, the others by up to jitter * h.
 *   region     region id of each kept cube, or NULL (region 0 everywhere)
 *   free_axes  if not NULL, receives a malloc'ed array of nverts bit masks
 *              (bit a: free along axis a; 7 inside a region)
 *   regions    if not NULL, receives a malloc'ed array of ntets region ids
 * Returns 0; -1 when out of memory or no cube was kept; -2 when the jitter
 * inverted a tet (nothing is allocated then).
 */
int tm_make_cubes_sliding(test_mesh *m, int n, double size, tm_cube_filter keep, tm_cube_region region,
                          void *user, double jitter, double boundary_jitter, uint64_t seed,
                          unsigned char **free_axes, int32_t **regions);

/*
 * Maps a mesh of [0, 2]^2 x [0, h] onto the cylinder of radius 1 around the
 * z axis (x, y in [-1, 1] after a shift by -1): the elliptical grid mapping
 * x' = x sqrt(1 - y^2 / 2), y' = y sqrt(1 - x^2 / 2), z unchanged; the square's
 * sides go onto the circle.  Returns 0, or -2 when a tet ended with
 * non-positive volume.
 */
int tm_map_square_to_disk(test_mesh *m);

/*
 * Maps a mesh of [0, 2]^3 onto the unit ball around the origin (coordinates
 * shifted by -1 first) with the analogous cube-to-ball map
 * x' = x sqrt(1 - y^2/2 - z^2/2 + y^2 z^2/3) (and cyclically); the cube's
 * surface goes onto the sphere.  Returns 0, or -2 when a tet ended with
 * non-positive volume.
 */
int tm_map_cube_to_ball(test_mesh *m);

#ifdef __cplusplus
}
#endif

#ifdef __cplusplus
extern "C" {
#endif

/*
 * A box with a round hole, as a structured O-grid: the box
 * [-half_width, half_width]^2 x [0, height] minus the cylinder of radius
 * `radius` (0 < radius < half_width) around the z axis.
 *
 * In each of the nz + 1 layers (z = height * k / nz) there are nt points
 * around (nt >= 4 and divisible by 4) on each of nr + 1 rings.  Point j lies
 * on the ray from the axis in the direction d_j: the square's side q = j /
 * (nt / 4) (0: x = +half_width, 1: y = +half_width, 2: x = -half_width,
 * 3: y = -half_width), at the angle psi = -pi/4 + (pi/2) (j % (nt/4)) / (nt/4)
 * from that side's outward normal.  So angle j = 0 points at the corner
 * (+hw, -hw), the four corners of the square are points j = 0, nt/4, nt/2,
 * 3nt/4 (exactly, +-half_width), and the angle increases counterclockwise
 * (theta_j = -pi/4 + 2 pi j / nt).  Ring 0 is on the circle,
 * radius * (cos theta_j, sin theta_j) (cos and sin of psi, turned by exact
 * quarter turns: coordinates that should be 0 are 0), ring nr on the square
 * (the ray's point with max(|x|, |y|) = half_width), ring i the linear blend
 * (1 - i/nr) * ring 0 + (i/nr) * ring nr.
 *
 * Vertex (ring i, angle j, layer k) has index (k * (nr + 1) + i) * nt + j.
 * Cell (i, j, k) spans rings i..i+1, angles j..j+1 (mod nt, across the seam
 * from j = nt - 1 to 0) and layers k..k+1; its corner bit mask is ring = 1,
 * angle = 2, layer = 4 (a right-handed frame: radial, counterclockwise, up)
 * and it is cut into the six Kuhn tets of tm_make_cubes around its diagonal
 * from corner 0 to corner 7, every tet positively oriented.  Cells are
 * listed in k, j, i order (i fastest), six tets each.  The split of every
 * cell face depends only on its own corners, so neighbouring cells (also
 * across the seam) agree: each interior face is shared by two tets with
 * opposite orientations.  The hole is the inscribed nt-gon of the circle,
 * the outside exactly the square.  boundary[v] is 1 on rings 0 and nr and
 * on layers 0 and nz.
 * Returns 0; -1 when out of memory or an argument is out of range; -2 when
 * a tet came out with non-positive volume (nothing is allocated then).
 */
int tm_make_box_with_hole(test_mesh *m, int nr, int nt, int nz, double half_width, double radius, double height);

/*
 * A "dimension-driven deformation" of a mesh from tm_make_box_with_hole
 * (same nr, nt, nz, half_width, radius), without any smoothing, in place:
 * the vertex numbering and the tets do not change (the result and the
 * undeformed mesh can be reference and deformed mesh of each other).
 * The (x, y) of every vertex is first recomputed from its place in the grid
 * (so earlier changes to m->xyz do not matter and a second call gives the
 * same result); z is kept.  Then, in this order:
 *   (a) every vertex with x > 0 gets x *= stretch_x: the box's side
 *       x = +half_width moves to stretch_x * half_width, the sides
 *       y = +-half_width stay planar (they stretch along x);
 *   (b) the ring-0 vertices alone are put on the circle of radius
 *       new_radius around the original axis (0, 0), in their original
 *       directions: new_radius * (cos theta_j, sin theta_j).  This replaces
 *       what (a) did to them, so the hole stays an exact circular cylinder
 *       (centred where it was) while the box is stretched.
 * All other vertices stay where (a) left them, so where new_radius reaches
 * beyond ring 1 (at radius + (half_width / cos psi - radius) / nr from the
 * axis before (a)) the tets between rings 0 and 1 invert.  The deformed mesh
 * bounds, with signed volumes, ((1 + stretch_x) * 2 * half_width^2 -
 * nt/2 new_radius^2 sin(2 pi / nt)) * height.  Nothing happens when m does
 * not have the vertex count of such a mesh.
 */
void tm_deform_box_with_hole(test_mesh *m, int nr, int nt, int nz, double stretch_x, double new_radius,
                             double half_width, double radius);

#ifdef __cplusplus
}
#endif

#endif /* BODT_TEST_MESH_GEN_H */
