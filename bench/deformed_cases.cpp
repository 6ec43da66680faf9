// deformed_cases.cpp -- see deformed_cases.hpp.
#include "deformed_cases.hpp"

#include "bench_util.hpp"
#include "bodt.h"
#include "cases.hpp"
#include "hole_box.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

namespace bench {

namespace {

double orient6(const double* x, const int32_t* t) {
    const double *a = x + 3 * t[0], *b = x + 3 * t[1], *c = x + 3 * t[2], *d = x + 3 * t[3];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// Tets whose orientation differs from the original's majority orientation.
int32_t count_inverted(const DeformedMesh& m) {
    size_t pos = 0;
    const size_t nt = m.tets.size() / 4;
    for (size_t t = 0; t < nt; ++t) pos += orient6(m.original.data(), &m.tets[4 * t]) > 0;
    const double sign = 2 * pos >= nt ? 1.0 : -1.0;
    int32_t inv = 0;
    for (size_t t = 0; t < nt; ++t) inv += sign * orient6(m.deformed.data(), &m.tets[4 * t]) <= 0;
    return inv;
}

// ----------------------------------------------------------- box with a hole

bool prepare_hole(const HoleBox& b, const HoleDeformation& d, DeformedMesh& m, std::string& err) {
    if (!make_hole_box(b, m.original, m.tets, err)) return false;
    m.deformed = deform_hole_box(b, d, m.original);
    m.inverted = count_inverted(m);
    char buf[256];
    std::snprintf(buf, sizeof buf, "%zu vertices, %zu tets; %d tets inverted by the deformation",
                  m.original.size() / 3, m.tets.size() / 4, m.inverted);
    m.note = buf;
    return true;
}

// ------------------------------------------------------------- mesh files

// Reads the mesh, then moves its boundary vertices (faces of one tet) beyond
// the middle plane x = xmid of the bounding box to xmid + stretch (x - xmid).
bool prepare_file(const std::string& path, const std::string& temp_dir, double stretch, DeformedMesh& m,
                  std::string& err) {
    std::string p;
    if (!readable_mesh_path(path, temp_dir, p, err)) return false;
    MeshHandle h;
    int st = bodt_mesh_read(p.c_str(), &h.m);
    if (st != BODT_OK) return err = "bodt_mesh_read " + path + ": " + errmsg(nullptr, st), false;
    int32_t nv = 0, nt = 0, nb = 0;
    bodt_mesh_get_counts(h.m, &nv, &nt, &nb);
    m.original.resize(3 * size_t(nv));
    m.tets.resize(4 * size_t(nt));
    m.regions.resize(size_t(nt));
    std::vector<int32_t> faces(3 * size_t(nb)), markers(static_cast<size_t>(nb));
    if ((st = bodt_mesh_get_vertices(h.m, m.original.data(), m.original.size())) != BODT_OK ||
        (st = bodt_mesh_get_tets(h.m, m.tets.data(), m.tets.size())) != BODT_OK ||
        (st = bodt_mesh_get_regions(h.m, m.regions.data(), m.regions.size())) != BODT_OK ||
        (st = bodt_mesh_get_boundary_faces(h.m, faces.data(), markers.data(), size_t(nb))) != BODT_OK)
        return err = path + ": " + errmsg(h.m, st), false;
    for (size_t f = 0; f < markers.size(); ++f)
        if (markers[f] != 0) {
            m.faces.insert(m.faces.end(), &faces[3 * f], &faces[3 * f] + 3);
            m.markers.push_back(markers[f]);
        }
    const int32_t lo_region = nt ? *std::min_element(m.regions.begin(), m.regions.end()) : 0;
    const int32_t hi_region = nt ? *std::max_element(m.regions.begin(), m.regions.end()) : 0;
    if (lo_region == 0 && hi_region == 0) m.regions.clear();

    double lo = m.original[0], hi = m.original[0];
    for (size_t v = 0; v < size_t(nv); ++v) {
        lo = std::min(lo, m.original[3 * v]);
        hi = std::max(hi, m.original[3 * v]);
    }
    const double mid = 0.5 * (lo + hi);
    std::vector<char> on_boundary(size_t(nv), 0);
    for (int32_t v : boundary_triangles(m.tets, 0)) on_boundary[size_t(v)] = 1;
    m.deformed = m.original;
    int32_t moved = 0;
    for (size_t v = 0; v < size_t(nv); ++v)
        if (on_boundary[v] && m.original[3 * v] > mid) {
            m.deformed[3 * v] = mid + stretch * (m.original[3 * v] - mid);
            ++moved;
        }
    m.inverted = count_inverted(m);
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "%d vertices, %d tets, %zu region(s); %d boundary vertices moved; %d tets inverted by the "
                  "deformation",
                  nv, nt, m.regions.empty() ? size_t(1) : size_t(hi_region - lo_region + 1), moved, m.inverted);
    m.note = buf;
    return true;
}

}  // namespace

std::vector<DeformedCase> make_deformed_cases(const std::string& shared_dir, const std::vector<std::string>& extra_meshes,
                                              double file_stretch, const std::string& temp_dir,
                                              std::vector<std::string>& notes) {
    std::vector<DeformedCase> cases;
    const HoleBox box;  // 8 rings x 48 directions x 8 layers: 18 432 tets
    char src[200];
    std::snprintf(src, sizeof src,
                  "O-grid box %gx%gx%g with a hole of radius %g: %d rings x %d directions x %d layers x 6 Kuhn tets",
                  2 * box.half_width, 2 * box.half_width, box.height, box.radius, box.nr, box.nt, box.nz);
    struct Hole {
        const char* name;
        const char* what;
        HoleDeformation d;
    };
    const Hole holes[] = {
        {"hole.dp", "DP: x > 0 stretched by 1.5 (the hole stays)", {1.5, 0.4, 0.0, 0.0}},
        {"hole.rc", "RC: hole radius 0.4 -> 0.48 (its ring alone moves)", {1.0, 0.48, 0.0, 0.0}},
        {"hole.dp-rc-ph", "DP+RC+PH: x > 0 stretched by 1.5, hole radius 0.4 -> 0.44, hole moved by (0, 0.04)",
         {1.5, 0.44, 0.0, 0.04}},
    };
    for (const Hole& h : holes) {
        const HoleDeformation d = h.d;
        cases.push_back({h.name, "hole-box", src, h.what, [box, d](DeformedMesh& m, std::string& err) {
                             return prepare_hole(box, d, m, err);
                         }});
    }

    std::vector<std::string> files;
    if (!shared_dir.empty())
        for (const char* f : {"tet/cgal_tetremesh_sphere.mesh", "tet/sfepy_elbow.mesh",
                              "tet/tetgen_generated/netgen_hinge_tetgen-pq.ele.gz", "tet/mmg_torus.mesh"}) {
            const std::string p = shared_dir + "/meshes/" + f;
            if (is_file(p)) files.push_back(p);
            else notes.push_back("mesh " + p + " not found");
        }
    files.insert(files.end(), extra_meshes.begin(), extra_meshes.end());
    const double stretch = file_stretch;
    char what[160];
    std::snprintf(what, sizeof what,
                  "boundary vertices with x beyond the bounding box's middle stretched away from it by %g "
                  "(interior vertices stay)",
                  stretch);
    for (const std::string& path : files)
        cases.push_back({mesh_case_name(path), "file", path, what,
                         [path, temp_dir, stretch](DeformedMesh& m, std::string& err) {
                             return prepare_file(path, temp_dir, stretch, m, err);
                         }});
    return cases;
}

}  // namespace bench
