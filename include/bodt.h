/*
 * bodt.h -- the public C API of libbodt, a tetrahedral mesh improver.
 *
 * libbodt takes a tetrahedral mesh as plain arrays (points, tets, optional
 * region ids, boundary-face markers and fixed vertices), improves it in place
 * through an opaque handle, and gives the arrays back.  The header is plain
 * C99; it is the only header you need.
 *
 * Conventions that hold for every function below:
 *  - Every function returns an int status: BODT_OK (0) or a negative
 *    bodt_status code.  bodt_status_string() names a code;
 *    bodt_mesh_last_error() gives a message naming the offending entity.
 *  - A call that fails leaves the mesh exactly as it was.
 *  - No C++ exception ever leaves the library.  There is no global mutable
 *    state: different handles may be used from different threads at once;
 *    one handle must not be used from two threads at the same time.
 *  - Indices (vertices, tets) are 0- or 1-based, as chosen by the caller in
 *    bodt_mesh_create() (or bodt_mesh_read_ex()); every index the library
 *    takes or gives, in arrays and in messages, uses that base.  The one
 *    exception is a reader's message about the file's text (with its line
 *    or byte offset), which quotes the file's own numbers.
 *  - Output arrays are caller-allocated; each getter takes the array's
 *    capacity in elements and refuses (BODT_ERR_INVALID_ARGUMENT) a capacity
 *    that is too small.
 *  - Structs that may grow start with a size field: set it to sizeof(struct)
 *    before the call; the library fills only what fits in that size.
 */
#ifndef BODT_H
#define BODT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Only the library's own build marks symbols for export; consumers see plain
 * declarations (which keeps the header parseable by cffi after cc -E).  The
 * Python package's cffi_cdef() (bindings/python/bodt/_cdef.py) reads this
 * header's directives itself: #ifdef, #ifndef, #if defined(A) && ...,
 * #else, #endif and object-like #defines; it refuses anything else. */
#if defined(BODT_BUILDING_LIBRARY) && defined(__GNUC__)
#define BODT_API __attribute__((visibility("default")))
#else
#define BODT_API
#endif

/* ---------------------------------------------------------------- version */

#define BODT_VERSION_MAJOR 0
#define BODT_VERSION_MINOR 5
#define BODT_VERSION_PATCH 0
/* MAJOR * 10000 + MINOR * 100 + PATCH, comparable with bodt_version_number() */
#define BODT_VERSION_NUMBER 500

/* The version of the library actually loaded, e.g. "0.1.0". */
BODT_API const char *bodt_version_string(void);
/* Same as BODT_VERSION_NUMBER, for the loaded library. */
BODT_API int bodt_version_number(void);

/* ----------------------------------------------------------------- status */

enum bodt_status {
    BODT_OK = 0,
    BODT_ERR_INVALID_ARGUMENT = -1, /* NULL pointer, bad count, bad key ...  */
    BODT_ERR_BAD_MESH = -2,         /* the mesh data is not a valid mesh    */
    BODT_ERR_OUT_OF_MEMORY = -3,
    BODT_ERR_WRONG_STATE = -4,      /* call not valid for this mesh now     */
    BODT_ERR_NUMERIC = -5,          /* a computation failed (NaN, ...)      */
    BODT_ERR_IO = -6,               /* file missing, unreadable, malformed  */
    BODT_ERR_CANCELLED = -7,        /* the bodt_run callback asked to stop  */
    BODT_ERR_UNSUPPORTED = -8       /* format, mode or feature not built in */
};

/* A static, human-readable name for a status code ("invalid argument"). */
BODT_API const char *bodt_status_string(int status);

/* ------------------------------------------------------------ mesh handle */

typedef struct bodt_mesh bodt_mesh;

/* Flags for bodt_mesh_create_ex() and bodt_mesh_read_ex(). */
enum bodt_create_flag {
    BODT_CREATE_DEFAULT = 0,
    /* Accept inverted tets (for untangling modes); zero-volume tets are
     * still refused. */
    BODT_CREATE_ACCEPT_INVERTED = 1,
    /* bodt_mesh_read_ex() only: the handle counts from 1 (Fortran) instead
     * of 0.  bodt_mesh_create_ex() refuses it: its index_base says. */
    BODT_CREATE_ONE_BASED = 2,
    /* Store the vertices and tets in the caller's order.  By default the
     * library renumbers them internally along a space-filling (Hilbert)
     * curve, so that neighbours lie close in memory: a mesh numbered at
     * random is then created and smoothed as fast as a well-ordered one.
     * The caller never sees that order (see "Internal order" below); this
     * flag only costs speed on badly ordered input. */
    BODT_CREATE_KEEP_ORDER = 4,
    /* bodt_mesh_read_ex() only: the handle counts as the file does (1 for
     * Medit and for Gmsh files whose node tags are 1..n, as its .node says
     * for TetGen, 0 for VTK and other Gmsh files), so that indices and
     * messages match the file.  bodt_mesh_get_index_base() tells which.
     * Not with BODT_CREATE_ONE_BASED. */
    BODT_CREATE_FILE_BASE = 8
};

/*
 * Internal order.  Every index the library takes or gives is the caller's:
 * vertex and tet arrays in and out, the vertices inside tets, faces and
 * edges, vertex parents and tet origins, files written.  Vertices made by
 * operations are appended after the input vertices.  While the
 * connectivity is the input's, tets come back in the caller's order, each
 * with its vertices in the caller's order; after a step that changed it,
 * in the library's order (bodt_mesh_get_tet_origins names the caller's
 * input tets).  Smoothing without connectivity changes gives the same
 * result, bit for bit, in either order (it follows the caller's: vertices
 * are coloured in the caller's order, stars and rings summed in it).
 * What may depend on the internal order: which flips, insertions and
 * collapses a step makes (they visit the bad tets in it), the serial sweep
 * and geometry extraction of BODT_MODE_PHASED_ODT, and the last bits of
 * the sums of bodt_mesh_quality (mean angle and stretch, volume).
 */

/*
 * Create a mesh from caller arrays, which are copied.
 *   nverts      number of vertices (> 0)
 *   xyz         3 * nverts coordinates, x0 y0 z0 x1 y1 z1 ...
 *   ntets       number of tets (> 0)
 *   tets        4 * ntets vertex indices in base index_base
 *   index_base  0 (C, Python) or 1 (Fortran)
 *   mesh        receives the handle, or NULL on failure
 *
 * The input is validated: finite coordinates within +-1e30, indices in
 * range and distinct within a tet, no duplicate tets, no face shared by more
 * than two tets, no two tets on the same side of a shared face, a manifold
 * boundary surface, no zero-volume tets (flat within round-off, or less than
 * about 1e-30 across) and (without BODT_CREATE_ACCEPT_INVERTED) no inverted
 * tet.
 * A mesh whose tets are all negatively oriented (the convention of some
 * tools) is not inverted: its orientation is detected, the mesh is handled
 * internally with positive orientation, and output tets come back in the
 * caller's convention.  The convention is the orientation of the majority of
 * the tets.  Vertices used by no tet are kept and counted in bodt_quality.
 *
 * On failure no handle exists; the message is given by
 * bodt_mesh_last_error(NULL) on the same thread.
 */
BODT_API int bodt_mesh_create(int32_t nverts, const double *xyz, int32_t ntets,
                              const int32_t *tets, int index_base,
                              bodt_mesh **mesh);
/* bodt_mesh_create() with bodt_create_flag bits (ACCEPT_INVERTED,
 * KEEP_ORDER). */
BODT_API int bodt_mesh_create_ex(int32_t nverts, const double *xyz,
                                 int32_t ntets, const int32_t *tets,
                                 int index_base, uint32_t flags,
                                 bodt_mesh **mesh);
/* Free a handle; NULL is ignored. */
BODT_API void bodt_mesh_destroy(bodt_mesh *mesh);

/*
 * The message of the last failed call on this handle ("tet 17 uses vertex
 * 1200, but the mesh has 1000 vertices"), or "" if the last call succeeded.
 * With mesh == NULL: the message of the last failed bodt_mesh_create* or
 * bodt_mesh_read on the calling thread.  The string stays valid until the
 * next call on the same handle (or thread, for NULL).
 */
BODT_API const char *bodt_mesh_last_error(const bodt_mesh *mesh);

/* -------------------------------------------------- optional mesh data */

/* One region (material) id per tet; default 0.  Faces between tets of
 * different regions are interfaces, reported with the boundary faces. */
BODT_API int bodt_mesh_set_regions(bodt_mesh *mesh, const int32_t *region_ids);

/*
 * Give markers to faces of the mesh: 3 * nfaces vertex indices and nfaces
 * markers (markers may be NULL: every listed face gets 1).  Each triangle
 * must be a face of the mesh (a boundary face, or an interior face, which
 * then becomes a marked internal surface).  Replaces earlier markers; faces
 * not listed have marker 0.
 */
BODT_API int bodt_mesh_set_boundary_faces(bodt_mesh *mesh, int32_t nfaces,
                                          const int32_t *triangles,
                                          const int32_t *markers);

/* Vertices that no mode may move.  Replaces an earlier list. */
BODT_API int bodt_mesh_set_fixed_vertices(bodt_mesh *mesh, int32_t nfixed,
                                          const int32_t *vertices);

/*
 * Feature edges (sharp CAD edges, ridges): 2 * nedges vertex indices.  Each
 * must be an edge of a boundary or interface face.  In BODT_MODE_BODT and
 * BODT_MODE_NODT their vertices move only along the feature line, and where they end, branch or
 * turn sharply the vertex is a corner; edges found by the feature-angle test
 * are added to these.  Replaces an earlier list.
 */
BODT_API int bodt_mesh_set_feature_edges(bodt_mesh *mesh, int32_t nedges,
                                         const int32_t *edges);
/*
 * bodt_mesh_set_feature_edges() with a reference number per edge (Medit's
 * edge ref, Gmsh's physical curve tag); refs may be NULL (every ref 0).
 * An operation that splits a feature edge gives both halves its ref.
 */
BODT_API int bodt_mesh_set_feature_edges_ex(bodt_mesh *mesh, int32_t nedges,
                                            const int32_t *edges,
                                            const int32_t *refs);

/*
 * Corners the caller knows (Medit's Corners, CAD vertices): vertices where
 * feature lines end.  They do not move in any mode and are classified
 * BODT_VERTEX_CORNER.  Replaces an earlier list.
 */
BODT_API int bodt_mesh_set_corners(bodt_mesh *mesh, int32_t ncorners,
                                   const int32_t *vertices);

/*
 * One reference number per vertex (Medit's vertex ref, TetGen's boundary
 * marker), for the caller's boundary conditions; default 0.  The modes do
 * not read them.  A vertex made by an operation takes the ref shared by
 * those of its parents (bodt_mesh_get_vertex_parents) that lie where it
 * lies, on the surface or inside; 0 when they differ or there are none.
 * Set them before a step makes vertices (BODT_ERR_WRONG_STATE after).
 */
BODT_API int bodt_mesh_set_vertex_refs(bodt_mesh *mesh, const int32_t *refs);

/* ---------------------------------------------------------------- getters */

/*
 * Counts.  Any pointer may be NULL.  Boundary faces are the faces of one tet,
 * plus the faces between tets of different regions, plus marked interior
 * faces.
 */
BODT_API int bodt_mesh_get_counts(const bodt_mesh *mesh, int32_t *nverts,
                                  int32_t *ntets, int32_t *nboundary_faces);

/* 3 * nverts coordinates. */
BODT_API int bodt_mesh_get_vertices(const bodt_mesh *mesh, double *xyz,
                                    size_t capacity);
/* 4 * ntets vertex indices, in the caller's base and orientation. */
BODT_API int bodt_mesh_get_tets(const bodt_mesh *mesh, int32_t *tets,
                                size_t capacity);
/* ntets region ids. */
BODT_API int bodt_mesh_get_regions(const bodt_mesh *mesh, int32_t *region_ids,
                                   size_t capacity);
/*
 * 3 * nboundary_faces vertex indices and nboundary_faces markers (either may
 * be NULL; capacity counts faces).  Faces on the domain boundary are
 * oriented with their normal (right-hand rule) pointing out of the domain;
 * interior faces point out of the tet with the smaller region id, or out of
 * the tet with the smaller index in equal regions.  Listed in a fixed order:
 * sorted by their lowest, then middle, then highest vertex index.
 */
BODT_API int bodt_mesh_get_boundary_faces(const bodt_mesh *mesh,
                                          int32_t *triangles,
                                          int32_t *markers, size_t capacity);
/* nverts flags: 1 where the vertex is fixed by the caller, else 0. */
BODT_API int bodt_mesh_get_fixed_vertices(const bodt_mesh *mesh,
                                          int32_t *is_fixed, size_t capacity);
/* The caller's feature edges: *nedges receives their count; edges (2 per
 * edge, may be NULL to ask for the count) receives them, sorted;
 * capacity counts edges. */
BODT_API int bodt_mesh_get_feature_edges(const bodt_mesh *mesh,
                                         int32_t *nedges, int32_t *edges,
                                         size_t capacity);
/* bodt_mesh_get_feature_edges() with their refs (refs may be NULL). */
BODT_API int bodt_mesh_get_feature_edges_ex(const bodt_mesh *mesh,
                                            int32_t *nedges, int32_t *edges,
                                            int32_t *refs, size_t capacity);
/* nverts flags: 1 where the caller made the vertex a corner, else 0. */
BODT_API int bodt_mesh_get_corners(const bodt_mesh *mesh, int32_t *is_corner,
                                   size_t capacity);
/* nverts vertex refs (see bodt_mesh_set_vertex_refs). */
BODT_API int bodt_mesh_get_vertex_refs(const bodt_mesh *mesh, int32_t *refs,
                                       size_t capacity);
/* The index base (0 or 1) of every index this handle takes and gives. */
BODT_API int bodt_mesh_get_index_base(const bodt_mesh *mesh, int *index_base);

/* How the current mode treats each vertex (bodt_mesh_get_vertex_classes). */
enum bodt_vertex_class {
    BODT_VERTEX_INTERIOR = 0,     /* moves freely (ODT, eq. 3)               */
    BODT_VERTEX_SURFACE = 1,      /* moves in its surface's tangent plane   */
    BODT_VERTEX_FEATURE_LINE = 2, /* moves along a feature line             */
    BODT_VERTEX_CORNER = 3,       /* does not move: a feature corner        */
    BODT_VERTEX_FIXED = 4,        /* does not move: fixed by the caller, or on
                                     a marked interior face of one region   */
    BODT_VERTEX_UNUSED = 5        /* in no tet                              */
};
/* nverts classes (enum bodt_vertex_class).  Feature lines and corners are
 * found in BODT_MODE_BODT and BODT_MODE_NODT only; the other modes see
 * every boundary and interface vertex as BODT_VERTEX_SURFACE.  The caller's
 * corners are BODT_VERTEX_CORNER in every mode. */
BODT_API int bodt_mesh_get_vertex_classes(const bodt_mesh *mesh,
                                          int32_t *classes, size_t capacity);

/*
 * Where the current mesh came from, so a solver can carry its fields over
 * after steps that changed the connectivity.  Vertices of the input (the
 * mesh as created or read) keep their index, also when an operation left
 * them unused; vertices made by operations are appended.
 *
 * Vertex parents: value(v) = sum of weights[k] * value(parents[k]) for k in
 * [offsets[v], offsets[v+1]), parents being input vertices (in the caller's
 * base), weights summing to 1: an input vertex is its own single parent; a
 * made vertex interpolates the mesh as it was before the operation that
 * made it, at the place where that operation left it (moves by later
 * smoothing are not tracked, as for the input vertices).  offsets has nverts + 1
 * entries counted from 0; bodt_mesh_get_parent_count gives offsets[nverts].
 */
BODT_API int bodt_mesh_get_parent_count(const bodt_mesh *mesh, int64_t *count);
BODT_API int bodt_mesh_get_vertex_parents(const bodt_mesh *mesh,
                                          int64_t *offsets,
                                          size_t offsets_capacity,
                                          int32_t *parents, double *weights,
                                          size_t capacity);
/* ntets input tet indices (caller's base): the input tet each tet lies in
 * (for a tet made by a flip, the one that held its centroid). */
BODT_API int bodt_mesh_get_tet_origins(const bodt_mesh *mesh,
                                       int32_t *origins, size_t capacity);

/* ---------------------------------------------------------------- quality */

/*
 * Histogram bins of dihedral angles, in degrees: bin i counts the angles in
 * [BODT_DIHEDRAL_BIN_EDGES[i], BODT_DIHEDRAL_BIN_EDGES[i+1]), the last bin
 * includes 180.  Edges: 0 5 10 15 20 25 30 40 50 60 70 80 90 100 110 120 130
 * 140 150 160 165 170 175 180 (fine at both ends, where bad tets live).
 */
#define BODT_DIHEDRAL_BINS 23
BODT_API int bodt_dihedral_bin_edges(double *edges, size_t capacity);

typedef struct bodt_quality {
    size_t size;                 /* set to sizeof(bodt_quality) */
    int32_t num_vertices;        /* all vertices, used or not */
    int32_t num_tets;
    int32_t num_boundary_faces;
    int32_t num_unused_vertices; /* vertices in no tet */
    int32_t num_inverted;        /* tets with signed volume <= 0 */
    int32_t reserved0;
    /* Dihedral angles in degrees.  An inverted or zero-volume tet counts as
     * having a 0 and a 180 degree angle. */
    double min_dihedral;
    double max_dihedral;
    double mean_dihedral;
    /* Stretch, 6 sqrt(6) V / (sum of face areas * longest edge): 1 for the
     * regular tet, 0 for a flat one, negative for an inverted one (paper
     * 001 eq. 3.1, paper 002 eq. 3.1). */
    double min_stretch;
    double mean_stretch;
    double volume;               /* sum of signed volumes */
    int64_t dihedral_histogram[BODT_DIHEDRAL_BINS];
} bodt_quality;

BODT_API int bodt_mesh_quality(const bodt_mesh *mesh, bodt_quality *quality);

/* Per-tet measures for bodt_mesh_tet_quality(). */
enum bodt_measure {
    BODT_MEASURE_MIN_DIHEDRAL = 1, /* degrees; 0 for inverted tets   */
    BODT_MEASURE_MAX_DIHEDRAL = 2, /* degrees; 180 for inverted tets */
    BODT_MEASURE_STRETCH = 3,
    BODT_MEASURE_VOLUME = 4        /* signed; > 0 for a valid tet    */
};

/* ntets values of one bodt_measure, in tet order. */
BODT_API int bodt_mesh_tet_quality(const bodt_mesh *mesh, int measure,
                                   double *values, size_t capacity);

/* ------------------------------------------------------- modes and params */

/*
 * Modes.  Every move is guarded (see BODT_PARAM_MIN_STRETCH): no tet ends
 * inverted or flat, no boundary triangle flips.  Boundary and interface
 * vertices move only in BODT_MODE_BODT_BASIC and BODT_MODE_BODT, and then
 * only in their tangent plane or along their feature line, which keeps the
 * volume of every region (paper 000, Appendix B); in BODT_MODE_NODT, which
 * projects them back onto the input surface (the volume changes a little);
 * and in BODT_MODE_PHASED_ODT, on their fitted shapes.
 */
enum bodt_mode {
    /* Guarded Laplacian smoothing: each interior vertex moves towards the
     * mean of its neighbours. */
    BODT_MODE_LAPLACE = 1,
    /* ODT (paper 000, Algorithm 1, eq. 3): interior vertices only. */
    BODT_MODE_ODT = 2,
    /* B-ODT basic: Algorithm 1 inside, Algorithm 2 (tangent plane, eq. 10)
     * on every boundary and interface vertex. */
    BODT_MODE_BODT_BASIC = 3,
    /* B-ODT (the default): Algorithm 1 inside, Algorithm 2 on smooth surface
     * vertices, Algorithm 3 along feature lines, corners fixed; from the
     * second step on, the angle ascent of BODT_PARAM_ASCENT_ANGLE too.
     * Where the surface around a vertex is two or three flat pieces meeting
     * at half BODT_PARAM_FEATURE_ANGLE or more (a CAD part's faces), the
     * vertex moves only along their common line, or stays where three meet
     * at a point, and a collapse keeps the pieces' planes. */
    BODT_MODE_BODT = 4,
    /* Paper 001: each interior vertex of a poor tet (stretch below
     * BODT_PARAM_POOR_QUALITY) minimises f = (1 - C) sum e(T) over interior
     * tets + C sum e(T) over boundary tets (eq. 3.4), e = 1 / stretch
     * (eq. 3.2), by quasi-Newton (DFP) with interval search and golden
     * section (Algorithms 1-3).  A boundary tet is one with a vertex that
     * does not move in this mode: on the boundary or an interface, or fixed.
     * Boundary and interface vertices never move and the surface
     * triangulation is kept.  With BODT_OP_FLIP, poor tets whose four
     * vertices all stay put go to edge removal, edge swap or face swap
     * (Algorithm 4). */
    BODT_MODE_OPT_WEIGHTED = 5,
    /* Paper 002, for meshes deformed by a shape change (the input may hold
     * inverted tets: BODT_CREATE_ACCEPT_INVERTED).  The part is modelled by
     * its sharp edges (dihedral angle past BODT_PARAM_FEATURE_ANGLE), corners,
     * chains fitted as lines, arcs or circles, and surface regions fitted as
     * planes or cylinders (bodt_mesh_get_geometry_classes).  Each step:
     * inverted tets removed by half-edge collapses (sec. 3.5.3), degenerate
     * ones by split + collapse (sec. 3.5.2), then the reference's density
     * and geometric accuracy recovered by edge splits and collapses (sec.
     * 3.5.1, bodt_set_reference_mesh), then ODT by phases (eq. 3.4, step
     * BODT_PARAM_ODT_STEP): vertices of sharp-edge chains along their line
     * or circle, surface vertices on their plane or developed cylinder,
     * interior vertices in space; then surface flips (as split + collapse)
     * and Delaunay flips (sec. 3.4.4).  Surface vertices stay on their
     * fitted shapes; regions fitted by neither shape keep their vertices. */
    BODT_MODE_PHASED_ODT = 6,
    /* Natural ODT (Tournois, Wormser, Alliez, Desbrun 2009; the comparison
     * column of paper 000 Table 1): every vertex moves to eq. (3) over its
     * star as it is, then boundary and interface vertices are projected
     * back onto the input surface (as it was when NODT first ran), each
     * onto its patch between feature edges, feature-line vertices onto
     * their line; corners and fixed vertices stay, classes as in
     * BODT_MODE_BODT.  The volume is NOT kept: on a curved boundary the
     * vertices slide over the input surface's creases. */
    BODT_MODE_NODT = 7
};

BODT_API int bodt_set_mode(bodt_mesh *mesh, int mode);
BODT_API int bodt_get_mode(const bodt_mesh *mesh, int *mode);

/*
 * Parameter keys.  Each key has one type: use the _int or _double setter and
 * getter that matches it (the other is refused).
 */
enum bodt_param {
    /* double, default 1e-6: convergence.  In the B-ODT and ODT sweeps
     * (BODT_MODE_ODT, _BODT_BASIC, _BODT) a vertex whose move would be at
     * most this fraction of its star's size (the cube root of the star's
     * volume) has converged and stays where it is; bodt_run stops when the
     * largest move of a step is below this fraction of the bounding-box
     * diagonal. */
    BODT_PARAM_TOLERANCE = 1,
    /* int, default 4: how many times a rejected move is halved and tried
     * again before the vertex is left where it is. */
    BODT_PARAM_BACKTRACK_STEPS = 2,
    /* double, default 1e-3: the guard.  A move is refused if a tet it
     * touches ends with stretch below min(this, that tet's stretch before the
     * move): moves never create inverted, flat or near-flat tets. */
    BODT_PARAM_MIN_STRETCH = 3,
    /* int 0/1, default 1: also refuse (or halve) a move that makes the
     * smallest dihedral angle among the tets the vertex touches smaller, or
     * the largest larger, so no step makes the mesh's extreme angles worse
     * (BODT_MODE_BODT's angle ascent may let the largest grow up to the
     * mesh's largest at the start of the sweep, and at most to 180 degrees
     * minus BODT_PARAM_ASCENT_ANGLE).  0 lets a mode move as its formula
     * says. */
    BODT_PARAM_NEVER_WORSE = 4,
    /* double, degrees, default 30: a surface edge whose two faces' normals
     * differ by more than this is a feature edge (BODT_MODE_BODT); flat
     * pieces of the surface meeting at half of it or more keep their planes
     * there (see BODT_MODE_BODT). */
    BODT_PARAM_FEATURE_ANGLE = 5,
    /* double, default 0.2: tensor voting (paper 000 eq. 11) with eigenvalues
     * mu0 >= mu1 >= mu2 makes a vertex a feature-line vertex when
     * mu1 / mu0 exceeds this ... */
    BODT_PARAM_EDGE_RATIO = 6,
    /* double, default 0.2: ... and a corner when mu2 / mu0 exceeds this. */
    BODT_PARAM_CORNER_RATIO = 7,
    /* int, default BODT_OPS_MODE_DEFAULT: which operations a step does, a
     * bitmask of enum bodt_op.  The mode's default is SMOOTH | FLIP | INSERT
     * | COLLAPSE for BODT_MODE_BODT (paper 000 Fig. 1: insertion where
     * needed, then smoothing, repeated; and the short edges smoothing cannot
     * even out collapsed) and BODT_MODE_PHASED_ODT, SMOOTH | FLIP for
     * BODT_MODE_OPT_WEIGHTED (paper 001 sec. 2) and SMOOTH for the other
     * modes. */
    BODT_PARAM_OPS = 8,
    /* int 0/1, default 0: 1 keeps every boundary and interface triangle as
     * it is: none of their vertices moves and none of them is split,
     * flipped or collapsed (only the tets inside change), as a mesh tied
     * to its neighbours or to boundary conditions by its surface nodes
     * needs.  With 0, BODT_MODE_BODT_BASIC, BODT_MODE_BODT and
     * BODT_MODE_NODT move the surface vertices (within the surface; NODT
     * projects them back onto the input surface), and BODT_MODE_BODT_BASIC
     * and BODT_MODE_BODT change the triangles too: flips retriangulate flat
     * parts of the surface only, with their markers, or take out a tet
     * lying flat on the surface by two faces when neither face it
     * uncovers turns by more than about 6 degrees, splits put new
     * vertices on the split edge or face, and a collapse of a surface edge
     * of length L (BODT_OP_COLLAPSE) may move the surface off the faces
     * around it by at most 0.1 sqrt(L h), h the mean length of the surface
     * edges there, and turn no face by more than about 6 degrees; never
     * across a feature edge or corner.  BODT_MODE_LAPLACE, BODT_MODE_ODT
     * and BODT_MODE_OPT_WEIGHTED never change the surface.
     * BODT_MODE_PHASED_ODT recovers the surface (paper 002): bodt_step
     * refuses 1 there with BODT_ERR_INVALID_ARGUMENT. */
    BODT_PARAM_KEEP_SURFACE = 9,
    /* double, degrees, default 15: a tet with a dihedral angle below this or
     * above 180 minus this is bad: BODT_OP_INSERT breaks bad spades, caps
     * and slivers, and refines the other bad tets with an interior vertex
     * at their circumcentre, BODT_OP_COLLAPSE bad tets with a short edge. */
    BODT_PARAM_BAD_ANGLE = 10,
    /* int 0/1, default 0: 1 adds paper 002's conditions (sec. 3.4.4) to
     * every flip: some tet it replaces is not Delaunay and every tet it
     * makes is (with respect to the vertices involved). */
    BODT_PARAM_DELAUNAY_FLIPS = 11,
    /* double in [0, 1], default 0.75: the boundary weight C of eq. (3.4)
     * (BODT_MODE_OPT_WEIGHTED).  0.5 weighs every tet alike; the paper
     * recommends 0.7 to 0.8. */
    BODT_PARAM_WEIGHT_C = 12,
    /* double in [0, 1], default 0.5: the threshold gamma.  A tet with
     * stretch below it is poor: BODT_MODE_OPT_WEIGHTED smooths the vertices
     * of poor tets and swaps poor all-boundary tets (1 smooths every
     * interior vertex). */
    BODT_PARAM_POOR_QUALITY = 13,
    /* double in [1e-12, 1], default 1e-3: the relative accuracy epsilon of
     * the quasi-Newton.  A vertex stops when f changes by less than epsilon
     * times f (Algorithm 1); the golden section stops when its interval is
     * shorter than epsilon times the vertex's mean edge length (Alg. 2). */
    BODT_PARAM_QN_EPSILON = 14,
    /* int in [1, 1000], default 10: at most N quasi-Newton iterations per
     * vertex and step (Algorithm 1). */
    BODT_PARAM_QN_MAX_ITERATIONS = 15,
    /* double in [1e-6, 10], default 0.05: the first step h0 of the interval
     * search (Algorithm 3), in units of the vertex's mean edge length. */
    BODT_PARAM_QN_INITIAL_STEP = 16,
    /* double in [1.1, 10], default 2: the factor alpha by which the interval
     * search grows its step (Algorithm 3). */
    BODT_PARAM_QN_INTERVAL_GROWTH = 17,
    /* double in (0, 1], default 1: the step alpha of eq. (3.4), paper 002
     * (BODT_MODE_PHASED_ODT): a vertex moves this fraction of the way to
     * its ODT target. */
    BODT_PARAM_ODT_STEP = 18,
    /* double in (0, 1), default 2/3: gamma of paper 002 sec. 3.5.1.  An
     * edge whose density 1/|e| is below gamma times the target density is
     * split (BODT_MODE_PHASED_ODT with a target density). */
    BODT_PARAM_DENSITY_SPLIT = 19,
    /* double in (1, 100], default 3/2: delta of sec. 3.5.1.  An edge whose
     * density exceeds delta times the target is collapsed. */
    BODT_PARAM_DENSITY_COLLAPSE = 20,
    /* double in (0, 0.1], default 1e-5: a surface region is a plane (or a
     * cylinder, a chain a line or circle) when no point of it lies further
     * from the fitted shape than this fraction of the region's size.  The
     * default takes coordinates written with six digits and refuses
     * patches of free-form surfaces (a sphere's), which keep their
     * vertices. */
    BODT_PARAM_FIT_TOLERANCE = 21,
    /* int in [0, 1024], default 1: threads of a smoothing sweep and of the
     * per-tet loops of a step; 0 takes OMP_NUM_THREADS when it is set, else
     * every core.  Plain threads, not OpenMP's runtime (which would end the
     * host process when it cannot start one): a thread that cannot be
     * started leaves its share to the others, with the same result.  Vertices
     * are swept colour by colour, so the result is the same for any number
     * of threads.  One by default: a solver running a process per core (MPI)
     * would otherwise have more threads than cores, and a sweep waits for
     * its slowest thread once per colour. */
    BODT_PARAM_THREADS = 22,
    /* double in [0, 60], default 30: BODT_MODE_BODT's angle ascent, not in
     * the papers.  From the second step on (counted since the mesh data
     * last changed), a sweep also moves each inner vertex of a tet with a
     * dihedral angle outside [this, 180 - this] degrees up the gradient of
     * that tet's worst angle, guarded as every move is: where ODT has
     * converged with a bad tet left, this raises the smallest angle.  When
     * the guard refuses that move (another angle around the vertex, nearly
     * as bad, would fall below the worst), the vertex tries the steepest
     * ascent of all its angles within half a degree of the worst.  These
     * moves may trade the largest angle around the vertex for its smallest:
     * the largest may grow up to the mesh's largest when the sweep began,
     * but not past 180 degrees minus this.  A
     * surface or feature-line vertex moves so too, along its plane or
     * line, where that keeps the boundary's shape (flat around it, or a
     * straight feature line between two planes) and its own smoothing move
     * did not move it.  0 turns it off (the paper's smoothing alone). */
    BODT_PARAM_ASCENT_ANGLE = 23
};

/*
 * Operations a step may do (BODT_PARAM_OPS).  Each connectivity change is
 * kept only if it raises the worst dihedral angle of the tets it touches
 * (after a few guarded moves of the new vertices and, with BODT_OP_SMOOTH,
 * of the bad tet's own interior vertices: ODT moves, quasi-Newton ones in
 * BODT_MODE_OPT_WEIGHTED, where the interior vertices of the tets a flip
 * makes move too): a step never makes the mesh's worst tet worse.  Without
 * BODT_OP_SMOOTH no input vertex moves.
 */
enum bodt_op {
    BODT_OP_SMOOTH = 1,   /* move vertices (the mode's smoothing)           */
    BODT_OP_FLIP = 2,     /* edge removal and 2-3 flips around tets with an
                             angle outside [30, 150] degrees (paper 001
                             Algorithm 4, for every bad tet); in
                             BODT_MODE_OPT_WEIGHTED around poor tets whose
                             vertices all stay put, as in the paper        */
    BODT_OP_INSERT = 4,   /* split spades, caps and slivers (paper 000
                             sec. 2.3), conforming: every tet on the split
                             edge or face is split; else, in a bad tet with
                             an interior vertex, insert its circumcentre
                             (Bowyer-Watson, within its region), and in one
                             with its four vertices on the boundary (and no
                             short edge), split an edge through the inside
                             at its midpoint                                */
    BODT_OP_COLLAPSE = 8  /* collapse the shortest edge of a bad tet with a
                             short edge (paper 002 sec. 3.5.1 position
                             rules; on the surface see
                             BODT_PARAM_KEEP_SURFACE)                      */
};
#define BODT_OPS_MODE_DEFAULT (-1)

BODT_API int bodt_set_param_int(bodt_mesh *mesh, int key, int32_t value);
BODT_API int bodt_set_param_double(bodt_mesh *mesh, int key, double value);
BODT_API int bodt_get_param_int(const bodt_mesh *mesh, int key,
                                int32_t *value);
BODT_API int bodt_get_param_double(const bodt_mesh *mesh, int key,
                                   double *value);

/* ---------------------------------------------------------- improvement */

typedef struct bodt_step_report {
    size_t size;            /* set to sizeof(bodt_step_report) */
    int32_t step;           /* 1 for the first step on this handle, ...  */
    int32_t vertices_moved;
    /* Vertices whose every trial move was refused.  The B-ODT sweeps do
     * not try again a vertex whose move was refused while nothing
     * around it has moved since (the verdict is known): it is not counted. */
    int32_t moves_rejected;
    int32_t moves_shortened;/* vertices moved by a halved step            */
    /* vertices left in place because their local problem has no minimum
     * (B-ODT: 4EF <= G^2 or E <= 0 in eq. 10, A <= 0 in Algorithm 3) */
    int32_t not_positive_definite;
    int32_t reserved0;
    double max_move;        /* largest displacement, in mesh units        */
    double min_dihedral;    /* after the step, degrees                    */
    double max_dihedral;
    double min_stretch;
    /* In BODT_MODE_PHASED_ODT: flips counts surface and Delaunay flips,
     * vertices_inserted the recovery splits and degenerate tets removed,
     * edges_collapsed the recovery and untangling collapses and the
     * degenerate tets removed. */
    int32_t flips;              /* edge removals and 2-3 flips kept        */
    int32_t vertices_inserted;  /* by BODT_OP_INSERT                       */
    int32_t edges_collapsed;    /* by BODT_OP_COLLAPSE                     */
    int32_t reserved1;
} bodt_step_report;

/* One improvement sweep in the current mode.  report may be NULL. */
BODT_API int bodt_step(bodt_mesh *mesh, bodt_step_report *report);

/*
 * Called after each step of bodt_run with its report; return 0 to go on,
 * anything else to stop (bodt_run then returns BODT_ERR_CANCELLED, and the
 * mesh keeps the steps done so far, each of them complete).
 */
typedef int (*bodt_step_callback)(const bodt_step_report *report,
                                  void *user_data);

/* Steps until a step leaves the connectivity as it was and moves no vertex
 * further than BODT_PARAM_TOLERANCE (converged), or max_steps were done.
 * callback may be NULL. */
BODT_API int bodt_run(bodt_mesh *mesh, int32_t max_steps,
                      bodt_step_callback callback, void *user_data);

/* ------------------------------------- geometry and reference (paper 002) */

/* What the geometry extraction of paper 002 (sec. 3.3) makes of a vertex. */
enum bodt_geometry_class {
    BODT_GEOMETRY_INTERIOR = 0,   /* not on the boundary or an interface  */
    BODT_GEOMETRY_SURFACE = 1,    /* inside one surface region            */
    BODT_GEOMETRY_SHARP_EDGE = 2, /* on a chain of sharp edges            */
    BODT_GEOMETRY_CORNER = 3      /* where a chain ends or chains meet    */
};
/* The shape fitted to a surface region or a sharp-edge chain. */
enum bodt_shape {
    BODT_SHAPE_NONE = 0,     /* no plane or cylinder fits: its vertices stay */
    BODT_SHAPE_PLANE = 1,
    BODT_SHAPE_CYLINDER = 2,
    BODT_SHAPE_LINE = 3,
    BODT_SHAPE_ARC = 4,
    BODT_SHAPE_CIRCLE = 5
};

/*
 * The geometry the phased mode works with, extracted from the mesh when
 * first asked for (with BODT_PARAM_FEATURE_ANGLE and BODT_PARAM_FIT_TOLERANCE)
 * and then kept, and carried along, by BODT_MODE_PHASED_ODT's steps.
 * nregions and nchains may be NULL.
 */
BODT_API int bodt_mesh_get_geometry_counts(const bodt_mesh *mesh,
                                           int32_t *nregions,
                                           int32_t *nchains);
/* nverts classes (enum bodt_geometry_class). */
BODT_API int bodt_mesh_get_geometry_classes(const bodt_mesh *mesh,
                                            int32_t *classes,
                                            size_t capacity);
/* Per boundary face, in bodt_mesh_get_boundary_faces order: its surface
 * region (numbered from the index base) and that region's enum bodt_shape.
 * Either array may be NULL; capacity counts faces. */
BODT_API int bodt_mesh_get_face_regions(const bodt_mesh *mesh,
                                        int32_t *region_ids,
                                        int32_t *shapes, size_t capacity);

typedef struct bodt_shape_fit {
    size_t size;       /* set to sizeof(bodt_shape_fit) */
    int32_t shape;     /* enum bodt_shape */
    int32_t reserved0;
    /* Plane: a point and the unit normal.  Cylinder: a point on the axis and
     * its unit direction.  Line: a point and the unit direction.  Arc,
     * circle: the centre and the unit normal of its plane. */
    double point[3];
    double axis[3];
    double radius;     /* cylinder, arc, circle */
    double max_error;  /* largest distance of the region's vertices from it */
    /* Cylinders: the geometric error BODT_MODE_PHASED_ODT keeps to, the
     * largest distance of an edge midpoint from the fitted cylinder (sec.
     * 3.3) in the reference mesh, or without one in this mesh as extracted;
     * 0 for other shapes. */
    double acceptable_error;
} bodt_shape_fit;
/* The shape fitted to surface region `region` (numbered from the index
 * base). */
BODT_API int bodt_mesh_get_region_shape(const bodt_mesh *mesh, int32_t region,
                                        bodt_shape_fit *fit);

/*
 * The undeformed mesh the handle's mesh was deformed from: the same
 * vertices, numbered alike (the tets may differ).  It gives (paper 002 sec.
 * 3.2, 3.3) the target density field (the reference's vertex densities
 * interpolated over a grid on this mesh, eq. 3.2) and, per cylindrical
 * region, the acceptable geometric error; BODT_MODE_PHASED_ODT then splits
 * and collapses edges to recover both.  NULL clears it.  The reference is
 * read, not kept: it may be destroyed after the call.
 */
BODT_API int bodt_set_reference_mesh(bodt_mesh *mesh,
                                     const bodt_mesh *reference);
/*
 * A target density (1 / edge length) given directly: values at the
 * dims[0] * dims[1] * dims[2] points of a regular grid, x fastest, point
 * (i, j, k) at origin + (i, j, k) * spacing; a value <= 0 means none there.
 * A cell's density is the mean of its corners' positive values (sec. 3.2).
 * values == NULL clears it.  Replaces a reference mesh's density.
 */
BODT_API int bodt_set_target_density(bodt_mesh *mesh, const double origin[3],
                                     const double spacing[3],
                                     const int32_t dims[3],
                                     const double *values);

typedef struct bodt_recovery_error {
    size_t size;             /* set to sizeof(bodt_recovery_error) */
    /* Eq. (4.1) of paper 002 over the edges: |1/|e| - rho'| / rho', with
     * rho' the target density at the edge's midpoint.  0 edges without a
     * target density. */
    double density_mean;
    double density_max;
    int64_t density_edges;
    /* Distance of the midpoints of the surface edges of cylindrical regions
     * from the region's fitted cylinder (sec. 3.3).  0 edges without any. */
    double geometric_mean;
    double geometric_max;
    int64_t geometric_edges;
} bodt_recovery_error;
/* How far the mesh is from its target density and its fitted geometry. */
BODT_API int bodt_mesh_recovery_error(const bodt_mesh *mesh,
                                      bodt_recovery_error *error);

/* ----------------------------------------------------------------- files */

/* File formats (bodt_mesh_read_format, bodt_mesh_write_format). */
enum bodt_format {
    BODT_FORMAT_AUTO = 0,           /* by the extension, as below              */
    /* .mesh, Medit ASCII: Vertices (ref = vertex ref), Tetrahedra (ref =
     * region id), Triangles (ref = face marker), Edges (feature edges with
     * their refs; written with Ridges naming them all), Corners (corners),
     * RequiredVertices (fixed vertices); other known sections are skipped.
     * A section other than Vertices may come more than once (meshio writes
     * one per cell block): repeated sections are appended in file order;
     * a second Vertices section is an error. */
    BODT_FORMAT_MEDIT = 1,
    BODT_FORMAT_MEDIT_BINARY = 2,   /* .meshb, the same sections in binary    */
    /* .node / .ele (give either; the other and an optional .face with
     * markers are found beside it; a write makes all three).  0- and
     * 1-based files; the .node boundary markers are the vertex refs.  No
     * fixed vertices, corners or feature edges. */
    BODT_FORMAT_TETGEN = 3,
    /* .msh, Gmsh: reads 2.2 and 4.1, ASCII and binary; physical tags of
     * volumes are region ids (without any physical volume, the tets of
     * several volumes take their volume's entity tag), of surfaces face
     * markers (likewise), of curves feature edge refs (line elements are
     * feature edges), of points fixed vertices.  No vertex refs or
     * corners.  A mesh read from a .msh is written back with the file's
     * physical names and tags and its entities (an element block per
     * entity, each element in the entity it came from or lies in), also
     * after steps changed its connectivity; any other mesh gets an entity
     * and a named physical group per region, marker, edge ref and the
     * fixed vertices.  In a file with physical groups, elements of none
     * are in physical group 0.  Gmsh and meshio read every variant
     * written.  Writes 4.1 ASCII; the next three write the other
     * variants. */
    BODT_FORMAT_GMSH = 4,
    BODT_FORMAT_GMSH_BINARY = 5,    /* writes 4.1 binary                      */
    BODT_FORMAT_GMSH22 = 6,         /* writes 2.2 ASCII                       */
    BODT_FORMAT_GMSH22_BINARY = 7,  /* writes 2.2 binary                      */
    /* .vtu, VTK XML unstructured grid (ParaView): tets (cell data
     * "region"), marked faces as triangle cells and feature edges as line
     * cells (cell data "marker": face marker, edge ref); point data "ref",
     * "fixed" and "corner".  A write adds per-tet minimum and maximum
     * dihedral angle, stretch and volume as cell data. */
    BODT_FORMAT_VTU = 8,
    /* .inp, Abaqus / CalculiX (write only): C3D4 elements, an element set
     * per region, a node set of the fixed vertices and one per non-zero
     * vertex ref, an element surface per face marker. */
    BODT_FORMAT_ABAQUS = 9,
    /* .vtk, VTK legacy unstructured grid, ASCII or binary, versions up to
     * 5.1 (VTK, ParaView, Mesquite, meshio): the same cells and arrays as
     * .vtu; float-typed flags (Mesquite's "fixed") are read too.  Writes
     * version 4.2 binary with the per-tet quality of .vtu. */
    BODT_FORMAT_VTK = 10
};

/*
 * Read a mesh from a file, in the format its extension says (enum
 * bodt_format).  The handle's index base is 0 (1 with bodt_mesh_read_ex and
 * BODT_CREATE_ONE_BASED, the file's with BODT_CREATE_FILE_BASE).  On
 * failure, bodt_mesh_last_error(NULL) says why: BODT_ERR_IO for a file that
 * cannot be read or parsed (with the line number or byte offset, and the
 * file's own numbers), BODT_ERR_BAD_MESH for a parsed mesh that is not
 * valid (naming the entities in the handle's base, which the message
 * states, with the file's when it differs: "... tet 113 (numbered from 0; the
 * file numbers from 1)"),
 * BODT_ERR_UNSUPPORTED for an unknown extension or a format that cannot be
 * read.
 */
BODT_API int bodt_mesh_read(const char *path, bodt_mesh **mesh);
/* bodt_mesh_read() with bodt_create_flag bits (ACCEPT_INVERTED, ONE_BASED
 * or FILE_BASE, KEEP_ORDER: the file's order is the caller's). */
BODT_API int bodt_mesh_read_ex(const char *path, uint32_t flags,
                               bodt_mesh **mesh);
/* bodt_mesh_read_ex() in the given enum bodt_format, whatever the
 * extension (BODT_FORMAT_AUTO: by the extension). */
BODT_API int bodt_mesh_read_format(const char *path, int format,
                                   uint32_t flags, bodt_mesh **mesh);

/*
 * The enum bodt_format that `path`'s extension names (".mesh": MEDIT, ".ele":
 * TETGEN, ...), as bodt_mesh_read and bodt_mesh_write choose it, so that a
 * program can check an output path before the work; BODT_ERR_UNSUPPORTED
 * for any other, with the message in bodt_mesh_last_error(NULL).
 */
BODT_API int bodt_format_from_path(const char *path, int *format);

/* Write to a file, format by extension as for bodt_mesh_read. */
BODT_API int bodt_mesh_write(const bodt_mesh *mesh, const char *path);
/* bodt_mesh_write() in the given enum bodt_format. */
BODT_API int bodt_mesh_write_format(const bodt_mesh *mesh, const char *path,
                                    int format);

#ifdef __cplusplus
}
#endif

#endif /* BODT_H */
