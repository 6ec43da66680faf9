// libFuzzer target for the whole library through its public C API
// (include/bodt.h): creation and validation, the setters, every getter,
// bodt_mesh_quality and one bodt_step.  Built from the objects of the
// library targets bodt_core and bodt (tests/fuzz/CMakeLists.txt).
//
// Input layout.  Byte 0 chooses the path and, for Medit, the read flags:
//   bit 0 clear: Medit.  The bytes after byte 0 up to the first NUL are a
//     .mesh text, written to a per-process file and read with
//     bodt_mesh_read_format(BODT_FORMAT_MEDIT); bit 1 adds
//     BODT_CREATE_ACCEPT_INVERTED, bit 2 BODT_CREATE_ONE_BASED, bits 3-7 all
//     set an unknown flag.  The bytes after the NUL are the control stream.
//   bit 0 set: arrays for bodt_mesh_create_ex, then the control stream, from
//     the bytes after byte 0:
//       flags byte   bit 0 ACCEPT_INVERTED; bits 1-2 index base 0, 1, 0,
//                    invalid; bits 3-7 all set: ONE_BASED (refused)
//       nverts byte  % 65; 3 * nverts coordinate bytes (coordinate())
//       ntets byte   % 65; 4 * ntets index bytes (vertex_index())
// Control stream (a read past its end gives 0 bytes):
//   nops byte % 9, then nops operations (operation()): setters, params,
//   mode, reference mesh, target density; then a mode byte (step_mode()) for
//   the one step, done when the mesh has at most kMaxStepTets tets; then an
//   extras byte: bit 0 adds the geometry getters (always in the phased mode).
// The getters and bodt_mesh_quality are checked before and after the step.
//
// Invariants checked (abort() when violated):
//  - a failed call returns a known negative status and a non-empty
//    bodt_mesh_last_error that is not "internal error..." (an exception
//    other than bodt::Error reached the C API); a successful one leaves "";
//  - getters given the right capacity succeed, every index they give is in
//    range in the handle's base (bodt_mesh_get_index_base), flags and enum
//    values are in range, the arrays given to bodt_mesh_create_ex come back
//    as given; quality numbers are finite, ordered and (without inverted
//    tets) positive;
//  - a refused setter or step leaves every getter's output as it was; an
//    accepted one shows what was set (regions, fixed vertices, corners,
//    feature edges with refs, vertex refs, face markers, params, mode);
//  - without BODT_CREATE_ACCEPT_INVERTED, no tet is inverted after the
//    creation and after a successful step.
// BODT_FUZZ_VERBOSE=1 prints each outcome (to check seeds, replay inputs).
#include "bodt.h"
#include "fuzz_check.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace {

constexpr int32_t kMaxStepTets = 256;  // a step on bigger meshes (Medit path) is skipped
constexpr int32_t kMaxCount = 16;      // entries per setter call

bool verbose() {
    static const bool on = [] {
        const char* v = std::getenv("BODT_FUZZ_VERBOSE");
        return v && *v && std::strcmp(v, "0") != 0;
    }();
    return on;
}

#define VERBOSE(...)                                       \
    do {                                                   \
        if (verbose()) std::fprintf(stderr, __VA_ARGS__);  \
    } while (0)

// ------------------------------------------------------------ temp file

void remove_temp_file();

const std::string& temp_file() {
    static const std::string path = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string dir = tmp && *tmp ? tmp : (access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp");
        return dir + "/bodt_fuzz_library_" + std::to_string(getpid()) + ".mesh";
    }();
    static const bool cleanup = (std::atexit(remove_temp_file), true);
    (void)cleanup;
    return path;
}

void remove_temp_file() { std::remove(temp_file().c_str()); }

// ------------------------------------------------------------ decoding

struct Input {
    const uint8_t* data;
    size_t size;
    size_t at = 0;
    uint8_t byte() { return at < size ? data[at++] : 0; }
};

// A lattice of 16 values with step 0.5 (so that valid meshes and duplicate
// points are easy to reach), and rare non-finite or extreme values.
double coordinate(uint8_t b) {
    if (b < 0xF0) return ((b & 15) - 4) * 0.5;
    static const double special[16] = {std::numeric_limits<double>::quiet_NaN(),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       1e300,
                                       -1e300,
                                       1e-300,
                                       0.5 + 1e-12,
                                       1e9,
                                       -0.0,
                                       0.25,
                                       0.75,
                                       1.0 / 3.0,
                                       std::numeric_limits<double>::denorm_min(),
                                       std::numeric_limits<double>::max(),
                                       1e-6,
                                       2.0};
    return special[b & 15];
}

// A vertex index in base `base`: mostly in range (one in nverts + 1 is just
// past the end), rarely negative, huge or off by one at either end.
int32_t vertex_index(uint8_t b, int32_t nverts, int base) {
    if (b < 0xF8) return base + b % (nverts + 1);
    switch (b) {
        case 0xF8: return -1;
        case 0xF9: return base - 1;
        case 0xFA: return std::numeric_limits<int32_t>::min();
        case 0xFB: return std::numeric_limits<int32_t>::max();
        case 0xFC: return base + nverts;
        case 0xFD: return base + nverts + 1000;
        case 0xFE: return base;
        default: return base + nverts - 1;
    }
}

// Region ids, markers, refs: small values mostly.
int32_t small_value(uint8_t b) {
    if (b < 0xFC) return b % 5;
    switch (b) {
        case 0xFC: return -1;
        case 0xFD: return std::numeric_limits<int32_t>::max();
        case 0xFE: return std::numeric_limits<int32_t>::min();
        default: return 1000000;
    }
}

int32_t param_int(uint8_t b) {
    static const int32_t values[16] = {-1, 0, 1, 2, 3, 4, 5, 7, 8, 15, 50, 51, 1000, 1001,
                                       std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::min()};
    return values[b & 15];
}

double param_double(uint8_t b) {
    static const double values[32] = {0.0, 1e-12, 1e-6, 1e-3, 0.05, 0.1, 0.2, 0.5, 2.0 / 3.0, 0.75, 1.0,
                                      1.1, 1.5, 2.0, 10.0, 15.0, 30.0, 45.0, 60.0, 90.0, 100.0, 180.0,
                                      200.0, -1.0, -0.0, 1e-13, 0.1000001, 100.5,
                                      std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(), 0.3};
    return values[b & 31];
}

// All modes, 0 (keep the current one) and invalid ones.
int step_mode(uint8_t b) {
    static const int modes[11] = {0, BODT_MODE_LAPLACE, BODT_MODE_ODT, BODT_MODE_BODT_BASIC, BODT_MODE_BODT,
                                  BODT_MODE_OPT_WEIGHTED, BODT_MODE_PHASED_ODT, BODT_MODE_NODT, 8, -1, 1 << 20};
    return modes[b % 11];
}

bool valid_mode(int mode) { return mode >= BODT_MODE_LAPLACE && mode <= BODT_MODE_NODT; }

// ------------------------------------------------------------ checks

// The outcome of a call on handle h (NULL: a creation or read).
void check_status(int status, const bodt_mesh* h, const char* call) {
    const char* message = bodt_mesh_last_error(h);
    FUZZ_CHECK(message != nullptr);
    if (status == BODT_OK) {
        FUZZ_CHECK(message[0] == '\0');
        return;
    }
    FUZZ_CHECK(status < 0);
    FUZZ_CHECK(status >= BODT_ERR_UNSUPPORTED);
    FUZZ_CHECK(message[0] != '\0');
    if (std::strncmp(message, "internal error", 14) == 0) {
        std::fprintf(stderr, "fuzz_library: %s: an unexpected exception reached the C API: %s\n", call, message);
        std::abort();
    }
}

#define CALL(h, expr) call_checked((expr), (h), #expr)
int call_checked(int status, const bodt_mesh* h, const char* text) {
    check_status(status, h, text);
    return status;
}

// A getter that must succeed.
#define GET(h, expr) FUZZ_CHECK(CALL(h, expr) == BODT_OK)

void check_index(int32_t v, int base, int64_t n) { FUZZ_CHECK(int64_t(v) >= base && int64_t(v) < base + n); }

// What the plain getters give: compared before and after a refused call.
struct Snapshot {
    int base = -1;
    int32_t nverts = 0, ntets = 0, nfaces = 0, nedges = 0;
    int mode = 0;
    std::vector<double> xyz;
    std::vector<int32_t> tets, regions, triangles, markers, fixed, corners, edges, edge_refs, vertex_refs;

    bool operator==(const Snapshot& o) const {
        return std::tie(base, nverts, ntets, nfaces, nedges, mode, tets, regions, triangles, markers, fixed,
                        corners, edges, edge_refs, vertex_refs) ==
                   std::tie(o.base, o.nverts, o.ntets, o.nfaces, o.nedges, o.mode, o.tets, o.regions, o.triangles,
                            o.markers, o.fixed, o.corners, o.edges, o.edge_refs, o.vertex_refs) &&
               xyz.size() == o.xyz.size() &&
               (xyz.empty() || std::memcmp(xyz.data(), o.xyz.data(), xyz.size() * sizeof(double)) == 0);
    }
};

Snapshot snapshot(bodt_mesh* h) {
    Snapshot s;
    GET(h, bodt_mesh_get_index_base(h, &s.base));
    FUZZ_CHECK(s.base == 0 || s.base == 1);
    GET(h, bodt_mesh_get_counts(h, &s.nverts, &s.ntets, &s.nfaces));
    FUZZ_CHECK(s.nverts > 0 && s.ntets > 0 && s.nfaces >= 4);
    GET(h, bodt_get_mode(h, &s.mode));
    FUZZ_CHECK(valid_mode(s.mode));
    const size_t nv = size_t(s.nverts), nt = size_t(s.ntets), nf = size_t(s.nfaces);

    s.xyz.resize(3 * nv);
    GET(h, bodt_mesh_get_vertices(h, s.xyz.data(), s.xyz.size()));
    for (double x : s.xyz) FUZZ_CHECK(std::isfinite(x));
    s.tets.resize(4 * nt);
    GET(h, bodt_mesh_get_tets(h, s.tets.data(), s.tets.size()));
    for (int32_t v : s.tets) check_index(v, s.base, nv);
    for (size_t t = 0; t < nt; ++t) {  // distinct within a tet
        std::set<int32_t> distinct(s.tets.begin() + 4 * t, s.tets.begin() + 4 * t + 4);
        FUZZ_CHECK(distinct.size() == 4);
    }
    s.regions.resize(nt);
    GET(h, bodt_mesh_get_regions(h, s.regions.data(), nt));
    s.triangles.resize(3 * nf);
    s.markers.resize(nf);
    GET(h, bodt_mesh_get_boundary_faces(h, s.triangles.data(), s.markers.data(), nf));
    for (int32_t v : s.triangles) check_index(v, s.base, nv);
    GET(h, bodt_mesh_get_boundary_faces(h, nullptr, nullptr, nf));
    s.fixed.resize(nv);
    GET(h, bodt_mesh_get_fixed_vertices(h, s.fixed.data(), nv));
    s.corners.resize(nv);
    GET(h, bodt_mesh_get_corners(h, s.corners.data(), nv));
    for (size_t v = 0; v < nv; ++v) FUZZ_CHECK((s.fixed[v] == 0 || s.fixed[v] == 1) && (s.corners[v] == 0 || s.corners[v] == 1));
    GET(h, bodt_mesh_get_feature_edges_ex(h, &s.nedges, nullptr, nullptr, 0));
    FUZZ_CHECK(s.nedges >= 0);
    s.edges.resize(2 * size_t(s.nedges) + 2);  // non-empty even without edges
    s.edge_refs.resize(size_t(s.nedges) + 1);
    int32_t nedges = -1;
    GET(h, bodt_mesh_get_feature_edges_ex(h, &nedges, s.edges.data(), s.edge_refs.data(), size_t(s.nedges)));
    FUZZ_CHECK(nedges == s.nedges);
    s.edges.resize(2 * size_t(s.nedges));
    s.edge_refs.resize(size_t(s.nedges));
    for (int32_t v : s.edges) check_index(v, s.base, nv);
    for (int32_t e = 0; e < s.nedges; ++e) FUZZ_CHECK(s.edges[2 * e] != s.edges[2 * e + 1]);
    {  // the plain getter gives the same edges
        std::vector<int32_t> plain(2 * size_t(s.nedges) + 2);
        GET(h, bodt_mesh_get_feature_edges(h, &nedges, plain.data(), size_t(s.nedges)));
        plain.resize(2 * size_t(s.nedges));
        FUZZ_CHECK(nedges == s.nedges && plain == s.edges);
    }
    s.vertex_refs.resize(nv);
    GET(h, bodt_mesh_get_vertex_refs(h, s.vertex_refs.data(), nv));

    // Too small a capacity is refused.
    std::vector<int32_t> small(4 * nt);
    FUZZ_CHECK(CALL(h, bodt_mesh_get_tets(h, small.data(), 4 * nt - 1)) == BODT_ERR_INVALID_ARGUMENT);
    FUZZ_CHECK(CALL(h, bodt_mesh_get_regions(h, small.data(), nt - 1)) == BODT_ERR_INVALID_ARGUMENT);
    return s;
}

// What the input was: tets and vertices of the input stay addressable.
struct Origin {
    int32_t input_verts = 0, input_tets = 0;
    bool accept_inverted = false;
    int base = 0;
};

// The getters that compute: classes, parents, quality and, with `geometry`,
// the geometry of paper 002 (its extraction fits cylinders: the slowest part
// of a run, so it is asked for only when the input says so).
void check_derived(bodt_mesh* h, const Snapshot& s, const Origin& o, bool geometry) {
    const size_t nv = size_t(s.nverts), nt = size_t(s.ntets), nf = size_t(s.nfaces);
    FUZZ_CHECK(s.nverts >= o.input_verts);
    FUZZ_CHECK(s.base == o.base);

    std::vector<int32_t> classes(nv);
    if (CALL(h, bodt_mesh_get_vertex_classes(h, classes.data(), nv)) == BODT_OK)
        for (int32_t c : classes) FUZZ_CHECK(c >= BODT_VERTEX_INTERIOR && c <= BODT_VERTEX_UNUSED);

    int64_t count = -1;
    GET(h, bodt_mesh_get_parent_count(h, &count));
    FUZZ_CHECK(count >= s.nverts);
    std::vector<int64_t> offsets(nv + 1);
    std::vector<int32_t> parents(static_cast<size_t>(count));
    std::vector<double> weights(static_cast<size_t>(count));
    GET(h, bodt_mesh_get_vertex_parents(h, offsets.data(), offsets.size(), parents.data(), weights.data(),
                                        size_t(count)));
    FUZZ_CHECK(offsets[0] == 0 && offsets[nv] == count);
    for (size_t v = 0; v < nv; ++v) {
        FUZZ_CHECK(offsets[v] < offsets[v + 1]);
        double sum = 0;
        for (int64_t k = offsets[v]; k < offsets[v + 1]; ++k) {
            check_index(parents[k], s.base, o.input_verts);
            FUZZ_CHECK(std::isfinite(weights[k]));
            sum += weights[k];
        }
        FUZZ_CHECK(std::fabs(sum - 1.0) <= 1e-6);
        if (v < size_t(o.input_verts))
            FUZZ_CHECK(offsets[v + 1] == offsets[v] + 1 && parents[offsets[v]] == int32_t(v) + s.base);
    }
    std::vector<int32_t> origins(nt);
    GET(h, bodt_mesh_get_tet_origins(h, origins.data(), nt));
    for (int32_t t : origins) check_index(t, s.base, o.input_tets);

    bodt_quality q{};
    q.size = sizeof q;
    GET(h, bodt_mesh_quality(h, &q));
    FUZZ_CHECK(q.num_vertices == s.nverts && q.num_tets == s.ntets && q.num_boundary_faces == s.nfaces);
    FUZZ_CHECK(q.num_unused_vertices >= 0 && q.num_unused_vertices < s.nverts);
    FUZZ_CHECK(q.num_inverted >= 0 && q.num_inverted <= s.ntets);
    if (!o.accept_inverted) FUZZ_CHECK(q.num_inverted == 0);
    for (double x : {q.min_dihedral, q.max_dihedral, q.mean_dihedral, q.min_stretch, q.mean_stretch, q.volume})
        FUZZ_CHECK(std::isfinite(x));
    FUZZ_CHECK(q.min_dihedral >= 0 && q.min_dihedral <= q.mean_dihedral + 1e-9 &&
               q.mean_dihedral <= q.max_dihedral + 1e-9 && q.max_dihedral <= 180);
    FUZZ_CHECK(q.min_stretch <= q.mean_stretch + 1e-9 && q.mean_stretch <= 1 + 1e-9);
    for (int64_t n : q.dihedral_histogram) FUZZ_CHECK(n >= 0);
    if (q.num_inverted == 0) FUZZ_CHECK(q.min_stretch > 0 && q.volume > 0);

    std::vector<double> values(nt);
    for (int measure = 0; measure <= 5; ++measure) {
        const int status = CALL(h, bodt_mesh_tet_quality(h, measure, values.data(), nt));
        const bool known = measure >= BODT_MEASURE_MIN_DIHEDRAL && measure <= BODT_MEASURE_VOLUME;
        FUZZ_CHECK(known ? status == BODT_OK : status == BODT_ERR_INVALID_ARGUMENT);
        if (!known) continue;
        for (double x : values) {
            FUZZ_CHECK(std::isfinite(x));
            if (measure == BODT_MEASURE_MIN_DIHEDRAL || measure == BODT_MEASURE_MAX_DIHEDRAL)
                FUZZ_CHECK(x >= 0 && x <= 180);
            if (measure == BODT_MEASURE_STRETCH) FUZZ_CHECK(x <= 1 + 1e-9);
            if (measure == BODT_MEASURE_VOLUME && q.num_inverted == 0) FUZZ_CHECK(x > 0);
        }
    }

    // Geometry (paper 002): extracted on first use; may be refused, cleanly.
    if (!geometry) return;
    int32_t nregions = -1, nchains = -1;
    if (CALL(h, bodt_mesh_get_geometry_counts(h, &nregions, &nchains)) != BODT_OK) return;
    FUZZ_CHECK(nregions >= 0 && nchains >= 0);
    std::vector<int32_t> gclasses(nv);
    if (CALL(h, bodt_mesh_get_geometry_classes(h, gclasses.data(), nv)) == BODT_OK)
        for (int32_t c : gclasses) FUZZ_CHECK(c >= BODT_GEOMETRY_INTERIOR && c <= BODT_GEOMETRY_CORNER);
    std::vector<int32_t> face_regions(nf), shapes(nf);
    if (CALL(h, bodt_mesh_get_face_regions(h, face_regions.data(), shapes.data(), nf)) == BODT_OK)
        for (size_t f = 0; f < nf; ++f) {
            FUZZ_CHECK(face_regions[f] == -1 || (face_regions[f] >= s.base && face_regions[f] < s.base + nregions));
            FUZZ_CHECK(shapes[f] >= BODT_SHAPE_NONE && shapes[f] <= BODT_SHAPE_CIRCLE);
        }
    for (int32_t r = s.base - 1; r <= s.base + std::min(nregions, 8); ++r) {
        bodt_shape_fit fit{};
        fit.size = sizeof fit;
        const int status = CALL(h, bodt_mesh_get_region_shape(h, r, &fit));
        if (r < s.base || r >= s.base + nregions) {
            FUZZ_CHECK(status == BODT_ERR_INVALID_ARGUMENT);
        } else if (status == BODT_OK) {
            FUZZ_CHECK(fit.shape >= BODT_SHAPE_NONE && fit.shape <= BODT_SHAPE_CIRCLE);
        }
    }
    bodt_recovery_error e{};
    e.size = sizeof e;
    if (CALL(h, bodt_mesh_recovery_error(h, &e)) == BODT_OK)
        FUZZ_CHECK(e.density_edges >= 0 && e.geometric_edges >= 0);
}

// ------------------------------------------------------------ operations

// A face of the mesh from the snapshot: a boundary face (src 1, 3) or a
// face of a tet (src 2, interior or not), its vertices in any order; raw
// indices otherwise.
void pick_face(Input& in, const Snapshot& s, int32_t out[3]) {
    const uint8_t src = in.byte() % 4;
    if (src == 0) {
        for (int k = 0; k < 3; ++k) out[k] = vertex_index(in.byte(), s.nverts, s.base);
        return;
    }
    if (src == 2) {
        const size_t t = in.byte() % size_t(s.ntets), skip = in.byte() % 4;
        for (size_t k = 0, j = 0; k < 4; ++k)
            if (k != skip) out[j++] = s.tets[4 * t + k];
    } else {
        const size_t f = in.byte() % size_t(s.nfaces);
        for (int k = 0; k < 3; ++k) out[k] = s.triangles[3 * f + k];
    }
    const uint8_t perm = in.byte() % 6;
    if (perm & 1) std::swap(out[0], out[1]);
    if (perm >= 2) std::swap(out[perm >= 4 ? 0 : 1], out[2]);
}

// An edge: of a boundary face (src 1), of a tet (src 2, maybe interior) or
// raw indices (src 0).
void pick_edge(Input& in, const Snapshot& s, int32_t out[2]) {
    const uint8_t src = in.byte() % 3;
    if (src == 0) {
        out[0] = vertex_index(in.byte(), s.nverts, s.base);
        out[1] = vertex_index(in.byte(), s.nverts, s.base);
    } else if (src == 1) {
        const size_t f = in.byte() % size_t(s.nfaces), k = in.byte() % 3;
        out[0] = s.triangles[3 * f + k];
        out[1] = s.triangles[3 * f + (k + 1) % 3];
    } else {
        static const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
        const size_t t = in.byte() % size_t(s.ntets), k = in.byte() % 6;
        out[0] = s.tets[4 * t + pairs[k][0]];
        out[1] = s.tets[4 * t + pairs[k][1]];
    }
    if (in.byte() & 1) std::swap(out[0], out[1]);
}

// A count for a setter: 0..kMaxCount, or -1 (negative), or a positive count
// with a NULL array.
struct Count {
    int32_t n;
    bool null;
};
Count pick_count(Input& in) {
    const uint8_t b = in.byte();
    if (b == 0xFF) return {-1, false};
    if (b == 0xFE) return {0, true};
    if (b == 0xFD) return {3, true};
    return {int32_t(b % (kMaxCount + 1)), false};
}

std::vector<int32_t> flags_of(const std::vector<int32_t>& list, int32_t nverts, int base) {
    std::vector<int32_t> flags(size_t(nverts), 0);
    for (int32_t v : list) flags[size_t(v - base)] = 1;
    return flags;
}

// One fuzz-chosen call that may change the handle.  A refused call must
// leave the getters' output as it was; an accepted one must show in it.
void operation(Input& in, bodt_mesh* h) {
    const Snapshot before = snapshot(h);
    Snapshot expected = before;  // after a refused call, or one that leaves the mesh alone
    const int32_t nv = before.nverts, nt = before.ntets;
    const int base = before.base;
    const uint8_t op = in.byte() % 10;
    int status = BODT_OK;
    bool changes_mesh = true;  // else only params / mode / reference
    switch (op) {
        case 0: {  // regions
            const bool null = in.byte() == 0xFF;
            std::vector<int32_t> regions(static_cast<size_t>(nt));
            for (int32_t& r : regions) r = small_value(in.byte());
            status = CALL(h, bodt_mesh_set_regions(h, null ? nullptr : regions.data()));
            if (status == BODT_OK) FUZZ_CHECK(snapshot(h).regions == regions);
            break;
        }
        case 1: {  // boundary faces with markers
            const Count c = pick_count(in);
            const bool null_markers = in.byte() & 1;
            std::vector<int32_t> tris(3 * size_t(std::max(c.n, 0)) + 3), markers(size_t(std::max(c.n, 0)) + 1);
            for (int32_t f = 0; f < c.n; ++f) {
                pick_face(in, before, &tris[3 * size_t(f)]);
                markers[size_t(f)] = small_value(in.byte());
            }
            status = CALL(h, bodt_mesh_set_boundary_faces(h, c.n, c.null ? nullptr : tris.data(),
                                                          null_markers ? nullptr : markers.data()));
            if (status == BODT_OK) {
                FUZZ_CHECK(c.n >= 0 && !(c.n > 0 && c.null));
                std::map<std::vector<int32_t>, int32_t> listed;
                for (int32_t f = 0; f < c.n; ++f) {
                    std::vector<int32_t> key(&tris[3 * size_t(f)], &tris[3 * size_t(f)] + 3);
                    std::sort(key.begin(), key.end());
                    listed[key] = null_markers ? 1 : markers[size_t(f)];
                }
                const Snapshot after = snapshot(h);
                std::set<std::vector<int32_t>> present;
                for (int32_t f = 0; f < after.nfaces; ++f) {
                    std::vector<int32_t> key(&after.triangles[3 * size_t(f)], &after.triangles[3 * size_t(f)] + 3);
                    std::sort(key.begin(), key.end());
                    FUZZ_CHECK(present.insert(key).second);  // no face twice
                    const auto it = listed.find(key);
                    FUZZ_CHECK(after.markers[size_t(f)] == (it == listed.end() ? 0 : it->second));
                }
                for (const auto& [key, marker] : listed)
                    if (marker != 0) FUZZ_CHECK(present.count(key) == 1);
            }
            break;
        }
        case 2:    // fixed vertices
        case 3: {  // corners
            const Count c = pick_count(in);
            std::vector<int32_t> list(size_t(std::max(c.n, 0)) + 1);
            for (int32_t k = 0; k < c.n; ++k) list[size_t(k)] = vertex_index(in.byte(), nv, base);
            const int32_t* p = c.null ? nullptr : list.data();
            status = op == 2 ? CALL(h, bodt_mesh_set_fixed_vertices(h, c.n, p))
                             : CALL(h, bodt_mesh_set_corners(h, c.n, p));
            if (status == BODT_OK) {
                list.resize(size_t(c.n));
                const Snapshot after = snapshot(h);
                FUZZ_CHECK((op == 2 ? after.fixed : after.corners) == flags_of(list, nv, base));
                FUZZ_CHECK((op == 2 ? after.corners : after.fixed) == (op == 2 ? before.corners : before.fixed));
            }
            break;
        }
        case 4: {  // feature edges with refs
            const Count c = pick_count(in);
            const uint8_t how = in.byte();
            std::vector<int32_t> edges(2 * size_t(std::max(c.n, 0)) + 2), refs(size_t(std::max(c.n, 0)) + 1);
            for (int32_t e = 0; e < c.n; ++e) {
                pick_edge(in, before, &edges[2 * size_t(e)]);
                refs[size_t(e)] = small_value(in.byte());
            }
            const int32_t* r = (how & 1) ? nullptr : refs.data();
            status = (how & 2) ? CALL(h, bodt_mesh_set_feature_edges(h, c.n, c.null ? nullptr : edges.data()))
                               : CALL(h, bodt_mesh_set_feature_edges_ex(h, c.n, c.null ? nullptr : edges.data(), r));
            if (status == BODT_OK) {
                const bool no_refs = (how & 2) || r == nullptr;
                std::map<std::pair<int32_t, int32_t>, int32_t> listed;
                for (int32_t e = 0; e < c.n; ++e) {
                    const int32_t a = edges[2 * size_t(e)], b = edges[2 * size_t(e) + 1];
                    listed[{std::min(a, b), std::max(a, b)}] = no_refs ? 0 : refs[size_t(e)];
                }
                const Snapshot after = snapshot(h);
                FUZZ_CHECK(size_t(after.nedges) == listed.size());
                size_t e = 0;
                for (const auto& [key, ref] : listed) {  // sorted, like the getter's
                    FUZZ_CHECK(std::min(after.edges[2 * e], after.edges[2 * e + 1]) == key.first);
                    FUZZ_CHECK(std::max(after.edges[2 * e], after.edges[2 * e + 1]) == key.second);
                    FUZZ_CHECK(after.edge_refs[e] == ref);
                    ++e;
                }
            }
            break;
        }
        case 5: {  // vertex refs
            const bool null = in.byte() == 0xFF;
            std::vector<int32_t> refs(static_cast<size_t>(nv));
            for (int32_t& r : refs) r = small_value(in.byte());
            status = CALL(h, bodt_mesh_set_vertex_refs(h, null ? nullptr : refs.data()));
            if (status == BODT_OK) FUZZ_CHECK(snapshot(h).vertex_refs == refs);
            break;
        }
        case 6: {  // a parameter
            changes_mesh = false;
            const int key = in.byte() % 25;  // 0, 23, 24: unknown
            if (in.byte() & 1) {
                const int32_t value = param_int(in.byte());
                int32_t old = 0, now = 0;
                const bool known = bodt_get_param_int(h, key, &old) == BODT_OK;
                status = CALL(h, bodt_set_param_int(h, key, value));
                if (status == BODT_OK) {
                    FUZZ_CHECK(known);
                    GET(h, bodt_get_param_int(h, key, &now));
                    FUZZ_CHECK(now == value);
                } else if (known) {
                    GET(h, bodt_get_param_int(h, key, &now));
                    FUZZ_CHECK(now == old);
                }
            } else {
                const double value = param_double(in.byte());
                double old = 0, now = 0;
                const bool known = bodt_get_param_double(h, key, &old) == BODT_OK;
                status = CALL(h, bodt_set_param_double(h, key, value));
                if (status == BODT_OK) {
                    FUZZ_CHECK(known && std::isfinite(value));
                    GET(h, bodt_get_param_double(h, key, &now));
                    FUZZ_CHECK(now == value);
                } else if (known) {
                    GET(h, bodt_get_param_double(h, key, &now));
                    FUZZ_CHECK(std::memcmp(&now, &old, sizeof now) == 0);
                }
            }
            break;
        }
        case 7: {  // mode
            changes_mesh = false;
            const int mode = step_mode(in.byte());
            status = CALL(h, bodt_set_mode(h, mode));
            FUZZ_CHECK((status == BODT_OK) == valid_mode(mode));
            if (status == BODT_OK) expected.mode = mode;
            break;
        }
        case 8: {  // the mesh itself as its reference, or none
            changes_mesh = false;
            status = CALL(h, bodt_set_reference_mesh(h, (in.byte() & 1) ? h : nullptr));
            break;
        }
        default: {  // a target density on a small grid, or none
            changes_mesh = false;
            const uint8_t how = in.byte();
            double origin[3], spacing[3];
            int32_t dims[3];
            for (int k = 0; k < 3; ++k) {
                origin[k] = coordinate(in.byte());
                spacing[k] = coordinate(in.byte());
                dims[k] = 1 + in.byte() % 4;
            }
            std::vector<double> values(64);
            for (double& v : values) v = coordinate(in.byte());
            status = CALL(h, bodt_set_target_density(h, origin, spacing, dims, (how & 1) ? nullptr : values.data()));
            break;
        }
    }
    static const char* const names[10] = {"set_regions",        "set_boundary_faces", "set_fixed_vertices",
                                          "set_corners",        "set_feature_edges",  "set_vertex_refs",
                                          "set_param",          "set_mode",           "set_reference_mesh",
                                          "set_target_density"};
    VERBOSE("fuzz_library: %s: %s\n", names[op], status == BODT_OK ? "ok" : bodt_mesh_last_error(h));
    const Snapshot after = snapshot(h);
    if (status != BODT_OK || !changes_mesh) FUZZ_CHECK(after == expected);
}

// ------------------------------------------------------------ creation

bodt_mesh* create_from_arrays(Input& in, Origin& o) {
    const uint8_t flag_byte = in.byte();
    uint32_t flags = (flag_byte & 1) ? BODT_CREATE_ACCEPT_INVERTED : 0;
    if ((flag_byte & 0xF8) == 0xF8) flags |= BODT_CREATE_ONE_BASED;  // refused by create_ex
    static const int bases[4] = {0, 1, 0, 2};
    int base = bases[(flag_byte >> 1) & 3];
    if (base == 2 && (flag_byte & 8)) base = -1;
    const int32_t nverts = in.byte() % 65;
    std::vector<double> xyz(3 * size_t(nverts) + 3);
    for (int32_t k = 0; k < 3 * nverts; ++k) xyz[size_t(k)] = coordinate(in.byte());
    const int32_t ntets = in.byte() % 65;
    std::vector<int32_t> tets(4 * size_t(ntets) + 4);
    const int index_base = base == 0 || base == 1 ? base : 0;
    for (int32_t k = 0; k < 4 * ntets; ++k) tets[size_t(k)] = vertex_index(in.byte(), nverts, index_base);

    bodt_mesh* h = reinterpret_cast<bodt_mesh*>(&in);  // must become NULL on failure
    const int status = CALL(nullptr, bodt_mesh_create_ex(nverts, xyz.data(), ntets, tets.data(), base, flags, &h));
    VERBOSE("fuzz_library: create %d vertices, %d tets, base %d, flags %u: %s\n", nverts, ntets, base, flags,
            status == BODT_OK ? "ok" : bodt_mesh_last_error(nullptr));
    if (status != BODT_OK) {
        FUZZ_CHECK(h == nullptr);
        return nullptr;
    }
    FUZZ_CHECK(h != nullptr && nverts > 0 && ntets > 0 && (base == 0 || base == 1));
    FUZZ_CHECK(!(flags & BODT_CREATE_ONE_BASED));
    o.input_verts = nverts;
    o.input_tets = ntets;
    o.accept_inverted = flags & BODT_CREATE_ACCEPT_INVERTED;
    o.base = base;
    // The arrays come back as given (orientation included), in the base given.
    const Snapshot s = snapshot(h);
    FUZZ_CHECK(s.nverts == nverts && s.ntets == ntets && s.base == base);
    FUZZ_CHECK(std::memcmp(s.xyz.data(), xyz.data(), 3 * size_t(nverts) * sizeof(double)) == 0);
    FUZZ_CHECK(std::equal(s.tets.begin(), s.tets.end(), tets.begin()));
    return h;
}

bodt_mesh* read_medit(uint8_t selector, const uint8_t* text, size_t size, Origin& o) {
    uint32_t flags = 0;
    if (selector & 2) flags |= BODT_CREATE_ACCEPT_INVERTED;
    if (selector & 4) flags |= BODT_CREATE_ONE_BASED;
    if ((selector & 0xF8) == 0xF8) flags |= 64;  // unknown: refused
    write_file(temp_file(), text, size);
    bodt_mesh* h = reinterpret_cast<bodt_mesh*>(&o);  // must become NULL on failure
    const int status = CALL(nullptr, bodt_mesh_read_format(temp_file().c_str(), BODT_FORMAT_MEDIT, flags, &h));
    VERBOSE("fuzz_library: read (flags %u): %s\n", flags, status == BODT_OK ? "ok" : bodt_mesh_last_error(nullptr));
    if (status != BODT_OK) {
        FUZZ_CHECK(h == nullptr);
        return nullptr;
    }
    FUZZ_CHECK(h != nullptr && !(flags & 64));
    const Snapshot s = snapshot(h);
    o.input_verts = s.nverts;
    o.input_tets = s.ntets;
    o.accept_inverted = flags & BODT_CREATE_ACCEPT_INVERTED;
    o.base = (flags & BODT_CREATE_ONE_BASED) ? 1 : 0;
    FUZZ_CHECK(s.base == o.base);
    return h;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    Origin origin;
    bodt_mesh* h = nullptr;
    Input control{nullptr, 0};
    if (data[0] & 1) {
        control = Input{data + 1, size - 1};
        h = create_from_arrays(control, origin);
    } else {
        const uint8_t* text = data + 1;
        const uint8_t* end = data + size;
        const uint8_t* nul = static_cast<const uint8_t*>(std::memchr(text, 0, size_t(end - text)));
        const uint8_t* text_end = nul ? nul : end;
        h = read_medit(data[0], text, size_t(text_end - text), origin);
        if (nul) control = Input{nul + 1, size_t(end - nul - 1)};
    }
    if (!h) return 0;

    // Few iterations, so that a run stays fast; the operations may change them.
    GET(h, bodt_set_param_int(h, BODT_PARAM_QN_MAX_ITERATIONS, 3));
    GET(h, bodt_set_param_int(h, BODT_PARAM_BACKTRACK_STEPS, 2));

    const int nops = control.byte() % 9;
    for (int k = 0; k < nops; ++k) operation(control, h);
    const Snapshot s = snapshot(h);

    const int mode = step_mode(control.byte());
    // Geometry getters: in the phased mode (whose step extracts it anyway)
    // or when the extras byte says so.
    const bool geometry = mode == BODT_MODE_PHASED_ODT || (control.byte() & 1);
    const bool step = s.ntets <= kMaxStepTets;
    check_derived(h, s, origin, geometry && !step);
    if (mode != 0) FUZZ_CHECK((CALL(h, bodt_set_mode(h, mode)) == BODT_OK) == valid_mode(mode));
    if (step) {
        const Snapshot before = snapshot(h);
        bodt_step_report report{};
        report.size = sizeof report;
        const int status = CALL(h, bodt_step(h, &report));
        const Snapshot after = snapshot(h);
        VERBOSE("fuzz_library: step (mode %d) on %d vertices, %d tets: %s; now %d vertices, %d tets\n", before.mode,
                before.nverts, before.ntets, status == BODT_OK ? "ok" : bodt_mesh_last_error(h), after.nverts,
                after.ntets);
        // num_inverted == 0 unless created with ACCEPT_INVERTED
        check_derived(h, after, origin, geometry);
        if (status == BODT_OK) {
            FUZZ_CHECK(report.step == 1);
            FUZZ_CHECK(report.vertices_moved >= 0 && report.flips >= 0 && report.vertices_inserted >= 0 &&
                       report.edges_collapsed >= 0);
            FUZZ_CHECK(std::isfinite(report.max_move) && report.max_move >= 0);
            // Vertex refs follow from the parents once a step made vertices.
            std::vector<int32_t> refs(size_t(after.nverts), 0);
            const int refs_status = CALL(h, bodt_mesh_set_vertex_refs(h, refs.data()));
            FUZZ_CHECK(refs_status == (after.nverts > origin.input_verts ? BODT_ERR_WRONG_STATE : BODT_OK));
        } else {
            FUZZ_CHECK(after == before);
        }
    }
    bodt_mesh_destroy(h);
    return 0;
}
