// cases.cpp -- see cases.hpp.
#include "cases.hpp"

#include "bench_util.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <utility>

#ifdef BODT_BENCH_WITH_ZLIB
#include <zlib.h>
#endif

#ifdef BODT_BENCH_WITH_TETGEN
#include "cli/silenced_stdout.hpp"

#include <tetgen.h>
#endif

namespace bench {

namespace {

std::vector<std::string> list_dir(const std::string& dir) {
    std::vector<std::string> out;
    if (DIR* d = opendir(dir.c_str())) {
        while (const dirent* e = readdir(d)) {
            const std::string n = e->d_name;
            if (n != "." && n != "..") out.push_back(n);
        }
        closedir(d);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::string basename_of(const std::string& p) {
    const size_t s = p.rfind('/');
    return s == std::string::npos ? p : p.substr(s + 1);
}

// Case names are used in file names (--write-dir): keep them plain.
std::string safe_name(std::string s) {
    for (char& c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
    return s;
}

// splitmix64: a small generator whose output is the same everywhere (the
// <random> distributions are not), so the generated meshes are reproducible.
class Rng {
public:
    explicit Rng(uint64_t seed) : s_(seed) {}
    uint64_t next() {
        uint64_t z = (s_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    uint64_t s_;
};

double signed_volume6(const double* a, const double* b, const double* c, const double* d) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
           u[2] * (v[0] * w[1] - v[1] * w[0]);
}

// ------------------------------------------------------------ jittered box

// n^3 cubes of the unit cube, each cut into the 6 Kuhn tets around its main
// diagonal; every interior vertex is moved by a uniform random offset of up to
// amplitude * h per coordinate (h = 1/n).  Offsets that would leave a tet
// nearly flat (volume below 2% of the undisturbed Kuhn tet) are halved for
// that tet's vertices until none is, so the mesh is valid.
bool make_jittered_box(int n, double amplitude, uint64_t seed, MeshArrays& m, std::string& note) {
    const int n1 = n + 1;
    const double h = 1.0 / n;
    auto vid = [n1](int i, int j, int k) { return int32_t(i + n1 * (j + n1 * k)); };
    m.xyz.assign(3 * size_t(n1) * n1 * n1, 0.0);
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                double* p = &m.xyz[3 * size_t(vid(i, j, k))];
                p[0] = i * h;
                p[1] = j * h;
                p[2] = k * h;
            }
    static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    m.tets.clear();
    m.tets.reserve(24 * size_t(n) * n * n);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (const auto& p : perms) {
                    int c[3] = {i, j, k};
                    int32_t t[4];
                    t[0] = vid(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[p[s]];
                        t[s + 1] = vid(c[0], c[1], c[2]);
                    }
                    const double* x = m.xyz.data();
                    if (signed_volume6(x + 3 * t[0], x + 3 * t[1], x + 3 * t[2], x + 3 * t[3]) < 0)
                        std::swap(t[2], t[3]);
                    m.tets.insert(m.tets.end(), t, t + 4);
                }
    const std::vector<double> base = m.xyz;
    std::vector<double> offset(m.xyz.size(), 0.0);
    Rng rng(seed);
    for (int k = 1; k < n; ++k)
        for (int j = 1; j < n; ++j)
            for (int i = 1; i < n; ++i)
                for (int c = 0; c < 3; ++c)
                    offset[3 * size_t(vid(i, j, k)) + size_t(c)] = rng.uniform(-amplitude, amplitude) * h;
    const double min_vol6 = 0.02 * h * h * h;  // the Kuhn tet has 6 V = h^3
    int rounds = 0, halved = 0;
    for (;; ++rounds) {
        for (size_t i = 0; i < m.xyz.size(); ++i) m.xyz[i] = base[i] + offset[i];
        std::vector<char> shrink(m.xyz.size() / 3, 0);
        bool any = false;
        const double* x = m.xyz.data();
        for (size_t t = 0; t < m.tets.size(); t += 4) {
            const int32_t* q = &m.tets[t];
            if (signed_volume6(x + 3 * q[0], x + 3 * q[1], x + 3 * q[2], x + 3 * q[3]) < min_vol6) {
                for (int s = 0; s < 4; ++s) shrink[size_t(q[s])] = 1;
                any = true;
            }
        }
        if (!any) break;
        if (rounds == 60) {
            note = "jittered box: could not make all tets valid";
            return false;
        }
        for (size_t v = 0; v < shrink.size(); ++v)
            if (shrink[v]) {
                ++halved;
                for (int c = 0; c < 3; ++c) offset[3 * v + size_t(c)] *= 0.5;
            }
    }
    m.index_base = 0;
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "Kuhn box %d^3 cubes x 6 tets, interior vertices jittered by up to %.2f h (seed %llu); "
                  "%d offset halvings in %d rounds to keep every tet valid",
                  n, amplitude, static_cast<unsigned long long>(seed), halved, rounds);
    note = buf;
    return true;
}

// Renumbers the vertices and the tets of m at random (Fisher-Yates with
// `seed`), each tet keeping its vertex order: the same mesh as a caller with
// no order of its own would give it.
void shuffle_numbering(MeshArrays& m, uint64_t seed) {
    Rng rng(seed);
    const auto permutation = [&rng](size_t n) {
        std::vector<int32_t> p(n);
        for (size_t i = 0; i < n; ++i) p[i] = int32_t(i);
        for (size_t i = n; i > 1; --i) std::swap(p[i - 1], p[size_t(rng.uniform() * double(i))]);
        return p;
    };
    const size_t nv = m.xyz.size() / 3, nt = m.tets.size() / 4;
    const std::vector<int32_t> vp = permutation(nv), tp = permutation(nt);
    std::vector<double> xyz(m.xyz.size());
    for (size_t v = 0; v < nv; ++v)
        for (int c = 0; c < 3; ++c) xyz[3 * size_t(vp[v]) + size_t(c)] = m.xyz[3 * v + size_t(c)];
    std::vector<int32_t> tets(m.tets.size());
    for (size_t t = 0; t < nt; ++t)
        for (int c = 0; c < 4; ++c) tets[4 * size_t(tp[t]) + size_t(c)] = vp[size_t(m.tets[4 * t + size_t(c)])];
    m.xyz.swap(xyz);
    m.tets.swap(tets);
}

// ------------------------------------------------------ lazy triangulation

// Sign of the orientation determinant 6V, certified as the library certifies
// it (src/quality/tet_geometry.hpp: Shewchuk's static bound for orient3d,
// computed from the first vertex): +1 or -1 when the sign is known, 0 when
// round-off could flip it.  The same formula, operand order and bound, so a
// tet this calls positive is positive for bodt_mesh_create too.
struct Orient {
    double det6;
    int sign;
};

Orient orient_certified(const double* a, const double* b, const double* c, const double* d) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    const double m1 = v[1] * w[2], m2 = v[2] * w[1];
    const double m3 = v[2] * w[0], m4 = v[0] * w[2];
    const double m5 = v[0] * w[1], m6 = v[1] * w[0];
    const double det = u[0] * (m1 - m2) + u[1] * (m3 - m4) + u[2] * (m5 - m6);
    const double permanent = std::fabs(u[0]) * (std::fabs(m1) + std::fabs(m2)) +
                             std::fabs(u[1]) * (std::fabs(m3) + std::fabs(m4)) +
                             std::fabs(u[2]) * (std::fabs(m5) + std::fabs(m6));
    constexpr double eps = 1.1102230246251565e-16;  // 2^-53
    constexpr double bound = (7.0 + 56.0 * eps) * eps;
    return {det, det > bound * permanent ? 1 : (det < -bound * permanent ? -1 : 0)};
}

// A lazy triangulation like paper 001's RAND1/RAND2: the unit cube cut into
// the 6 Kuhn tets around its main diagonal, then npoints uniformly random
// points inserted one by one, each by locating the tet that holds it (a
// stochastic visibility walk from a tet made by an earlier point of the same
// grid cell, brute force if the walk takes too long) and splitting that tet
// 1->4.  A point whose smallest
// barycentric coordinate in its tet is below min_bary (it lies within that
// fraction of the tet's height from a face), or one of whose four new tets
// does not have a certified positive orientation, is redrawn.  The result
// depends on the points only (a point strictly inside a tet has one home), so
// it is the same whatever path the walk takes.  Every point is inside: the
// boundary stays the 12 triangles of the cube, with 8 vertices.
bool make_lazy_cube(int npoints, uint64_t seed, double min_bary, MeshArrays& m, std::string& note) {
    m.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};  // vertex = x + 2y + 4z
    m.xyz.reserve(3 * (8 + size_t(npoints)));
    std::vector<std::array<int32_t, 4>> tets;
    std::vector<std::array<int32_t, 4>> nbr;  // nbr[t][i]: the tet across the face opposite vertex i, -1 outside
    tets.reserve(6 + 3 * size_t(npoints));
    nbr.reserve(tets.capacity());
    static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& p : perms) {
        int c[3] = {0, 0, 0};
        std::array<int32_t, 4> t{};
        for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[size_t(s) + 1] = c[0] + 2 * c[1] + 4 * c[2];
        }
        const double* x = m.xyz.data();
        if (orient_certified(x + 3 * t[0], x + 3 * t[1], x + 3 * t[2], x + 3 * t[3]).sign < 0) std::swap(t[2], t[3]);
        tets.push_back(t);
    }
    // adjacency of the 6 Kuhn tets: match their faces
    for (size_t t = 0; t < tets.size(); ++t) {
        std::array<int32_t, 4> n{-1, -1, -1, -1};
        for (int i = 0; i < 4; ++i) {
            std::array<int32_t, 3> f{}, g{};
            for (int k = 0, j = 0; k < 4; ++k)
                if (k != i) f[size_t(j++)] = tets[t][size_t(k)];
            std::sort(f.begin(), f.end());
            for (size_t u = 0; u < tets.size() && n[size_t(i)] < 0; ++u) {
                if (u == t) continue;
                for (int l = 0; l < 4; ++l) {
                    for (int k = 0, j = 0; k < 4; ++k)
                        if (k != l) g[size_t(j++)] = tets[u][size_t(k)];
                    std::sort(g.begin(), g.end());
                    if (f == g) n[size_t(i)] = int32_t(u);
                }
            }
        }
        nbr.push_back(n);
    }

    Rng rng(seed);
    Rng walk_rng(seed ^ 0x77a1c0ffeeULL);  // face order of the walk; does not change the result
    const double* x = nullptr;
    auto face_det = [&](size_t t, int i, const double* p) {  // 6V of tet t with vertex i replaced by p
        const double* q[4];
        for (int k = 0; k < 4; ++k) q[k] = k == i ? p : x + 3 * tets[t][size_t(k)];
        return orient_certified(q[0], q[1], q[2], q[3]);
    };
    long redrawn = 0, brute = 0;
    // walk starts: per cell of a grid of about 2 points per cell, the last tet
    // made around a point in that cell (tet ids are never removed)
    const int grid = std::max(1, int(std::cbrt(npoints / 2.0)));
    std::vector<int32_t> hint(size_t(grid) * grid * grid, -1);
    auto cell_of = [grid](const double* p) {
        size_t c = 0;
        for (int k = 2; k >= 0; --k) c = c * size_t(grid) + size_t(std::min(grid - 1, std::max(0, int(p[k] * grid))));
        return c;
    };
    for (int n = 0; n < npoints; ++n) {
        for (;;) {
            const double p[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
            x = m.xyz.data();
            // locate: a stochastic visibility walk
            const size_t cell = cell_of(p);
            size_t t = hint[cell] >= 0 ? size_t(hint[cell]) : tets.size() - 1;
            bool found = false;
            const long max_steps = 100 * long(std::cbrt(double(tets.size()))) + 1000;
            for (long step = 0; step < max_steps && !found; ++step) {
                const int start = int(walk_rng.next() & 3);
                found = true;
                for (int k = 0; k < 4; ++k) {
                    const int i = (start + k) & 3;
                    if (face_det(t, i, p).det6 < 0 && nbr[t][size_t(i)] >= 0) {
                        t = size_t(nbr[t][size_t(i)]);
                        found = false;
                        break;
                    }
                }
            }
            if (!found) {  // the walk went round in circles: look at every tet
                ++brute;
                double best = -INFINITY;
                for (size_t u = 0; u < tets.size(); ++u) {
                    double worst = INFINITY;
                    for (int i = 0; i < 4 && worst > best; ++i) worst = std::min(worst, face_det(u, i, p).det6);
                    if (worst > best) best = worst, t = u;
                }
            }
            // too close to a face of t, or a new tet not certified positive: redraw
            const double whole = orient_certified(x + 3 * tets[t][0], x + 3 * tets[t][1], x + 3 * tets[t][2],
                                                  x + 3 * tets[t][3]).det6;
            bool ok = whole > 0;
            for (int i = 0; i < 4 && ok; ++i) {
                const Orient o = face_det(t, i, p);
                ok = o.sign > 0 && o.det6 >= min_bary * whole;
            }
            if (!ok) {
                ++redrawn;
                continue;
            }
            // split t 1->4: tet i is t with vertex i replaced by the new point
            const int32_t v = int32_t(m.xyz.size() / 3);
            m.xyz.insert(m.xyz.end(), p, p + 3);
            const std::array<int32_t, 4> old = tets[t], old_nbr = nbr[t];
            int32_t ids[4] = {int32_t(t), int32_t(tets.size()), int32_t(tets.size()) + 1, int32_t(tets.size()) + 2};
            tets.resize(tets.size() + 3);
            nbr.resize(nbr.size() + 3);
            for (int i = 0; i < 4; ++i) {
                std::array<int32_t, 4> q = old, qn{};
                q[size_t(i)] = v;
                for (int j = 0; j < 4; ++j) qn[size_t(j)] = j == i ? old_nbr[size_t(i)] : ids[j];
                tets[size_t(ids[i])] = q;
                nbr[size_t(ids[i])] = qn;
                const int32_t outside = old_nbr[size_t(i)];
                if (outside >= 0)
                    for (int32_t& back : nbr[size_t(outside)])
                        if (back == int32_t(t)) back = ids[i];
            }
            hint[cell] = ids[0];
            break;
        }
    }
    m.tets.clear();
    m.tets.reserve(4 * tets.size());
    for (const auto& t : tets) m.tets.insert(m.tets.end(), t.begin(), t.end());
    m.index_base = 0;
    m.faces.clear();
    m.markers.clear();
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "lazy triangulation: unit cube (6 Kuhn tets) + %d uniformly random points (seed %llu) each "
                  "inserted by a 1->4 split of its tet: %zu vertices, %zu tets; %ld points redrawn (barycentric "
                  "coordinate < %g or a new tet not certified positive); %ld walks fell back to brute force",
                  npoints, static_cast<unsigned long long>(seed), m.xyz.size() / 3, tets.size(), redrawn, min_bary,
                  brute);
    note = buf;
    return true;
}

#ifdef BODT_BENCH_WITH_TETGEN

using bodt_cli::SilencedStdout;  // TetGen prints to stdout, which carries the JSON

bool run_tetgen(const char* switches_in, tetgenio& in, tetgenio& out, std::string& err) {
    std::string sw = switches_in;
    std::vector<char> switches(sw.begin(), sw.end());
    switches.push_back('\0');
    tetgenbehavior behavior;
    const SilencedStdout quiet;
    if (!behavior.parse_commandline(switches.data())) {
        err = std::string("TetGen rejected the switches ") + switches_in;
        return false;
    }
    try {
        tetrahedralize(&behavior, &in, &out);
    } catch (...) {  // TetGen reports failures by throwing an int
        err = std::string("TetGen failed (switches ") + switches_in + ")";
        return false;
    }
    if (out.numberoftetrahedra <= 0) {
        err = std::string("TetGen made no tets (switches ") + switches_in + ")";
        return false;
    }
    return true;
}

void copy_tetgen_output(const tetgenio& out, MeshArrays& m, bool with_faces) {
    m.xyz.assign(out.pointlist, out.pointlist + 3 * size_t(out.numberofpoints));
    m.tets.resize(4 * size_t(out.numberoftetrahedra));
    for (size_t t = 0; t < size_t(out.numberoftetrahedra); ++t)
        for (size_t c = 0; c < 4; ++c)
            m.tets[4 * t + c] = out.tetrahedronlist[size_t(out.numberofcorners) * t + c];
    m.index_base = out.firstnumber;
    m.faces.clear();
    m.markers.clear();
    if (with_faces && out.numberoftrifaces > 0 && out.trifacelist && out.trifacemarkerlist) {
        m.faces.assign(out.trifacelist, out.trifacelist + 3 * size_t(out.numberoftrifaces));
        m.markers.assign(out.trifacemarkerlist, out.trifacemarkerlist + size_t(out.numberoftrifaces));
    }
}

// Like `tetgen -pQ FILE` / `tetgen -pqQ FILE`.
bool tetgen_surface(const std::string& path, const char* switches, PreparedMesh& pm, std::string& err) {
    std::vector<char> name(path.begin(), path.end());
    name.push_back('\0');
    tetgenio in, out;
    bool ok;
    {
        const SilencedStdout quiet;
        ok = ends_with(path, ".stl") ? in.load_stl(name.data()) : in.load_off(name.data());
    }
    if (!ok) {
        err = "TetGen could not read " + path;
        return false;
    }
    if (!run_tetgen(switches, in, out, err)) return false;
    copy_tetgen_output(out, pm.arrays, true);
    pm.note = "tetgen -" + std::string(switches) + ": " + std::to_string(out.numberofpoints) + " vertices, " +
              std::to_string(out.numberoftetrahedra) + " tets";
    return true;
}

// npts uniformly random points on the unit sphere (fixed seed: 642 points
// keep the seed of the first version, so sphere642 is the same mesh).  With
// refine_bound <= 0: the Delaunay tetrahedralization of the points (`tetgen
// -Q` on the point set): every vertex is on the boundary.  Otherwise the
// convex hull of that tetrahedralization is meshed again as a PLC with
// `-pq<bound>YQ`: the boundary keeps exactly the 642 points (Y) and TetGen's
// quality refinement inserts interior Steiner points, like the 87 interior
// points of paper 000's Random Sphere.
bool random_sphere(int npts, double refine_bound, PreparedMesh& pm, std::string& err) {
    Rng rng(20240000000ULL + uint64_t(npts));
    tetgenio in, out;
    in.firstnumber = 0;
    in.numberofpoints = npts;
    in.pointlist = new REAL[3 * size_t(npts)];
    for (int i = 0; i < npts; ++i) {
        const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * M_PI);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        in.pointlist[3 * i] = r * std::cos(phi);
        in.pointlist[3 * i + 1] = r * std::sin(phi);
        in.pointlist[3 * i + 2] = z;
    }
    if (!run_tetgen("Q", in, out, err)) return false;
    if (refine_bound <= 0) {
        copy_tetgen_output(out, pm.arrays, false);
        pm.note = "Delaunay of " + std::to_string(npts) + " random points on the unit sphere (tetgen -Q): " +
                  std::to_string(out.numberofpoints) + " vertices, " + std::to_string(out.numberoftetrahedra) +
                  " tets, no interior vertex";
        return true;
    }
    std::vector<int32_t> tets(out.tetrahedronlist, out.tetrahedronlist + 4 * size_t(out.numberoftetrahedra));
    const auto hull = boundary_triangles(tets, out.firstnumber);
    tetgenio plc, out2;
    plc.firstnumber = 0;
    plc.numberofpoints = out.numberofpoints;
    plc.pointlist = new REAL[3 * size_t(out.numberofpoints)];
    std::copy(out.pointlist, out.pointlist + 3 * size_t(out.numberofpoints), plc.pointlist);
    plc.numberoffacets = int(hull.size() / 3);
    plc.facetlist = new tetgenio::facet[hull.size() / 3];
    for (size_t f = 0; f < hull.size() / 3; ++f) {
        tetgenio::facet& fa = plc.facetlist[f];
        tetgenio::init(&fa);
        fa.numberofpolygons = 1;
        fa.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&fa.polygonlist[0]);
        fa.polygonlist[0].numberofvertices = 3;
        fa.polygonlist[0].vertexlist = new int[3];
        for (int c = 0; c < 3; ++c) fa.polygonlist[0].vertexlist[c] = hull[3 * f + size_t(c)];
    }
    char sw[64];
    std::snprintf(sw, sizeof sw, "pq%gYQ", refine_bound);
    if (!run_tetgen(sw, plc, out2, err)) return false;
    copy_tetgen_output(out2, pm.arrays, false);
    pm.note = std::to_string(npts) + " random points on the unit sphere, convex hull re-meshed with tetgen -" +
              std::string(sw) + ": " +
              std::to_string(out2.numberofpoints) + " vertices (" + std::to_string(out2.numberofpoints - npts) +
              " interior Steiner points), " + std::to_string(out2.numberoftetrahedra) + " tets";
    return true;
}

#endif  // BODT_BENCH_WITH_TETGEN

// The jittered Kuhn box of side n; stretch != 1: the same box (the same
// jitter) with every x coordinate multiplied by stretch, so its tets are
// anisotropic (the cube becomes stretch x 1 x 1).
constexpr double kBoxStretch = 1.5;

Case box_case(int n, double stretch) {
    Case c;
    const bool stretched = stretch != 1.0;
    c.name = "box" + std::to_string(n) + (stretched ? ".stretch" : ".jitter");
    c.kind = stretched ? "box-stretched" : "box";
    char what[64];
    std::snprintf(what, sizeof what, ", x stretched %gx", stretch);
    c.source = "unit cube, " + std::to_string(n) + "^3 Kuhn cubes (" + std::to_string(6L * n * n * n) +
               " tets), interior vertices jittered" + (stretched ? std::string(what) : std::string());
    c.prepare = [n, stretch, stretched](PreparedMesh& pm, std::string& err) {
        pm.from_file = false;
        if (!make_jittered_box(n, 0.35, 0xb0d7b0c5ULL + uint64_t(n), pm.arrays, pm.note)) {
            err = pm.note;
            return false;
        }
        if (stretched) {
            for (size_t i = 0; i < pm.arrays.xyz.size(); i += 3) pm.arrays.xyz[i] *= stretch;
            char b[64];
            std::snprintf(b, sizeof b, "; then x multiplied by %g", stretch);
            pm.note += b;
        }
        return true;
    };
    return c;
}

// The jittered box of box_case(n, 1) with its vertices and tets numbered
// at random (a fixed seed): what the library's internal order is for.
constexpr uint64_t kShuffleSeed = 0x5eed5b0c;

Case shuffled_box_case(int n) {
    Case c = box_case(n, 1.0);
    c.name = "box" + std::to_string(n) + ".shuffled";
    c.kind = "box-shuffled";
    c.source += ", vertices and tets numbered at random";
    const auto make = c.prepare;
    c.prepare = [make](PreparedMesh& pm, std::string& err) {
        if (!make(pm, err)) return false;
        shuffle_numbering(pm.arrays, kShuffleSeed);
        pm.note += "; vertices and tets renumbered at random (seed " + std::to_string(kShuffleSeed) + ")";
        return true;
    };
    return c;
}

// A tet mesh file for bodt_mesh_read.
bool prepare_file(const std::string& path, const std::string& temp_dir, PreparedMesh& pm, std::string& err) {
    pm.from_file = true;
    return readable_mesh_path(path, temp_dir, pm.path, err);
}

}  // namespace

bool readable_mesh_path(const std::string& path, const std::string& temp_dir, std::string& out, std::string& err) {
    if (!ends_with(path, ".gz")) {
        out = path;
        return true;
    }
    const std::string plain = path.substr(0, path.size() - 3);
    const std::string dest = temp_dir + "/" + basename_of(plain);
    if (ends_with(plain, ".ele") || ends_with(plain, ".node")) {
        const std::string stem = plain.substr(0, plain.rfind('.'));
        const std::string dstem = dest.substr(0, dest.rfind('.'));
        for (const char* ext : {".node", ".ele", ".face"}) {
            const std::string src = stem + ext + ".gz";
            if (is_file(src)) {
                if (!gunzip_file(src, dstem + ext, err)) return false;
            } else if (is_file(stem + ext)) {
                if (!gunzip_file(stem + ext, dstem + ext, err)) return false;  // not gzipped: copy
            }
        }
        out = dstem + ".ele";
        return true;
    }
    if (!gunzip_file(path, dest, err)) return false;
    out = dest;
    return true;
}

std::string mesh_case_name(const std::string& path) {
    std::string stem = basename_of(path);
    if (ends_with(stem, ".gz")) stem = stem.substr(0, stem.size() - 3);
    stem = stem.substr(0, stem.rfind('.'));
    return safe_name("file." + stem);
}

bool gunzip_file(const std::string& src, const std::string& dest, std::string& err) {
#ifdef BODT_BENCH_WITH_ZLIB
    gzFile in = gzopen(src.c_str(), "rb");  // also reads plain files
    if (!in) {
        err = "cannot open " + src;
        return false;
    }
    FILE* out = std::fopen(dest.c_str(), "wb");
    if (!out) {
        gzclose(in);
        err = "cannot write " + dest;
        return false;
    }
    std::vector<char> buf(1 << 16);
    int n;
    bool ok = true;
    while ((n = gzread(in, buf.data(), unsigned(buf.size()))) > 0)
        if (std::fwrite(buf.data(), 1, size_t(n), out) != size_t(n)) ok = false;
    if (n < 0) ok = false;
    gzclose(in);
    if (std::fclose(out) != 0) ok = false;
    if (!ok) err = "cannot decompress " + src + " to " + dest;
    return ok;
#else
    auto quote = [](const std::string& s) {
        std::string q = "'";
        for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
        return q + "'";
    };
    const std::string cmd = "gzip -dc " + quote(src) + " > " + quote(dest);
    if (std::system(cmd.c_str()) != 0) {
        err = "gzip -dc failed on " + src;
        return false;
    }
    return true;
#endif
}

std::vector<int> scale_box_sizes(double max_tets) {
    std::vector<int> out;
    for (int n : {12, 26, 55, 119})
        if (6.0 * n * n * n <= 1.02 * max_tets) out.push_back(n);
    return out;
}

std::vector<Case> make_cases(const CaseOptions& opt, std::vector<std::string>& notes) {
    std::vector<Case> cases;
    const std::string temp_dir = opt.temp_dir;

    if (opt.scale) {  // the scale series alone: jittered, stretched, then shuffled boxes
        const std::vector<int> sizes = scale_box_sizes(opt.scale_max);
        if (sizes.empty()) notes.push_back("--scale-max below the smallest box (10368 tets): no case");
        for (double stretch : {1.0, kBoxStretch})
            for (int n : sizes) cases.push_back(box_case(n, stretch));
        for (int n : scale_box_sizes(std::min(opt.scale_max, 1e6))) cases.push_back(shuffled_box_case(n));
        return cases;
    }

    // (a) TetGen meshes of surfaces, like `tetgen -pQ` and `tetgen -pqQ`.
    std::vector<std::string> surfaces;
    if (!opt.shared_dir.empty()) {
        const std::string dir = opt.shared_dir + "/meshes/surface";
        for (const char* s : {"cgal_fandisk.off", "cgal_eight.off", "cgal_joint.off", "cgal_rotor.off",
                              "netgen_hinge.stl"}) {
            if (is_file(dir + "/" + s))
                surfaces.push_back(dir + "/" + s);
            else
                notes.push_back(std::string("surface ") + s + " not found in " + dir);
        }
    }
    for (const auto& s : opt.extra_surfaces) surfaces.push_back(s);
    for (const auto& path : surfaces) {
        std::string stem = basename_of(path);
        stem = stem.substr(0, stem.rfind('.'));
        for (const char* sw : {"pQ", "pqQ"}) {
            Case c;
            c.name = safe_name(stem + "." + sw);
            c.kind = "tetgen-surface";
            c.source = path;
#ifdef BODT_BENCH_WITH_TETGEN
            const std::string switches = sw;
            c.prepare = [path, switches](PreparedMesh& pm, std::string& err) {
                return tetgen_surface(path, switches.c_str(), pm, err);
            };
            cases.push_back(c);
#else
            notes.push_back("skipped " + c.name + ": bodt_bench was built without TetGen");
#endif
        }
    }

    // (b) tet mesh files that bodt_mesh_read reads.
    std::vector<std::string> files;
    if (!opt.shared_dir.empty()) {
        for (const std::string& dir : {opt.shared_dir + "/meshes/tet", opt.shared_dir + "/meshes/tet/tetgen_generated"}) {
            if (!is_dir(dir)) {
                notes.push_back("no directory " + dir);
                continue;
            }
            for (const auto& f : list_dir(dir)) {
                const std::string p = dir + "/" + f;
                if (!is_file(p)) continue;
                for (const char* ext : {".mesh", ".ele", ".vtk", ".vtu", ".msh"})
                    if (ends_with(f, ext) || ends_with(f, std::string(ext) + ".gz")) files.push_back(p);
            }
        }
    }
    for (const auto& f : opt.extra_meshes) files.push_back(f);
    for (const auto& path : files) {
        Case c;
        c.name = mesh_case_name(path);
        c.kind = "file";
        c.source = path;
        c.prepare = [path, temp_dir](PreparedMesh& pm, std::string& err) {
            return prepare_file(path, temp_dir, pm, err);
        };
        cases.push_back(c);
    }

    // (c) the random sphere of paper 000.
#ifdef BODT_BENCH_WITH_TETGEN
    {
        Case c;
        c.name = "sphere642.Q";
        c.kind = "random-sphere";
        c.source = "642 random points on the unit sphere, Delaunay (tetgen -Q)";
        c.prepare = [](PreparedMesh& pm, std::string& err) { return random_sphere(642, 0.0, pm, err); };
        cases.push_back(c);
        // The bound 7 gives 85 interior Steiner points (the paper's mesh: 87).
        Case r;
        r.name = "sphere642.pq7Y";
        r.kind = "random-sphere";
        r.source = "642 random points on the unit sphere, hull re-meshed with tetgen -pq7YQ";
        r.prepare = [](PreparedMesh& pm, std::string& err) { return random_sphere(642, 7.0, pm, err); };
        cases.push_back(r);
        if (opt.large) {  // ten times the points: a larger random sphere
            Case l;
            l.name = "sphere6420.pq7Y";
            l.kind = "random-sphere";
            l.source = "6420 random points on the unit sphere, hull re-meshed with tetgen -pq7YQ";
            l.prepare = [](PreparedMesh& pm, std::string& err) { return random_sphere(6420, 7.0, pm, err); };
            cases.push_back(l);
        }
    }
#else
    notes.push_back("skipped the random sphere: bodt_bench was built without TetGen");
#endif

    // (d) lazy triangulations of random points in the unit cube (paper 001's
    // RAND2: 5086 vertices, i.e. the 8 corners and 5078 points).
    std::vector<std::pair<std::string, int>> lazies = {{"rand.lazy", 5078}};
    if (opt.large) lazies.push_back({"rand.lazy.large", 50780});
    for (const auto& lz : lazies) {
        const int npoints = lz.second;
        const uint64_t seed = 0x1a2b0001ULL + uint64_t(npoints);
        Case c;
        c.name = lz.first;
        c.kind = "random-lazy";
        c.source = "unit cube, 6 Kuhn tets + " + std::to_string(npoints) +
                   " random points inserted one by one by 1->4 splits (" + std::to_string(8 + npoints) +
                   " vertices, " + std::to_string(6 + 3 * npoints) + " tets)";
        c.prepare = [npoints, seed](PreparedMesh& pm, std::string& err) {
            pm.from_file = false;
            return make_lazy_cube(npoints, seed, 1e-6, pm.arrays, pm.note) || (err = pm.note, false);
        };
        cases.push_back(c);
    }

    // (e) jittered Kuhn boxes.
    const std::vector<int> boxes = opt.large ? std::vector<int>{12, 26} : std::vector<int>{12};  // 10368, 105456 tets
    for (int n : boxes) cases.push_back(box_case(n, 1.0));
    return cases;
}

}  // namespace bench
