#include "cli/report_views.hpp"

#include "cli/report_format.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace bodt_cli {

namespace {

// A view along a coordinate axis: the axes to the right and up on the page,
// and the axis towards the viewer (with its sign).
struct View {
    const char* name;
    const char* caption;
    int right, up, toward;
    double toward_sign;
};

const View kViews[3] = {
    {"top", "Top, seen from +z: x to the right, y up", 0, 1, 2, 1.0},
    {"front", "Front, seen from \xE2\x88\x92y: x to the right, z up", 0, 2, 1, -1.0},
    {"side", "Side, seen from +x: y to the right, z up", 1, 2, 0, 1.0},
};
const char* const kAxisNames[3] = {"x", "y", "z"};

constexpr double kViewPixels = 300.0;  // the bounding box's largest side, in px
constexpr double kMarginPixels = 14.0;
constexpr double kUnit = 10.0;         // SVG units per px: coordinates are whole numbers
constexpr int kShades = 12;
const double kCosCrease = std::cos(30.0 * 3.14159265358979323846 / 180.0);

using Vec = std::array<double, 3>;

Vec sub(const double* a, const double* b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec unit(const Vec& a) {
    const double n = std::sqrt(dot(a, a));
    return n > 0.0 ? Vec{a[0] / n, a[1] / n, a[2] / n} : Vec{0.0, 0.0, 0.0};
}

// Shade `level` (0 dark .. kShades - 1 light) of the boundary's blue grey.
std::string shade_color(int level) {
    const double t = static_cast<double>(level) / (kShades - 1);
    const int dark[3] = {0x4b, 0x58, 0x6e}, light[3] = {0xe9, 0xee, 0xf5};
    char text[8];
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = static_cast<int>(std::lround(dark[k] + t * (light[k] - dark[k])));
    std::snprintf(text, sizeof text, "#%02x%02x%02x", c[0], c[1], c[2]);
    return text;
}

// Page coordinates of a point in one view: X = S (u - U0), Y = S (V0 - v),
// u and v its coordinates along the view's right and up axes.
struct Projector {
    double S, U0, V0;
    int right, up;
    long X(const double* p) const { return std::lround(S * (p[right] - U0)); }
    long Y(const double* p) const { return std::lround(S * (V0 - p[up])); }
};

// The boundary as the views need it: unit normals and the edges with the
// triangles on either side.
struct Surface {
    const MeshSnapshot& m;
    const std::vector<int32_t>& tri;
    std::vector<Vec> normal;
    // Each edge (a < b) with its triangles, sorted by edge.
    struct EdgeFace {
        int32_t a, b, face;
    };
    std::vector<EdgeFace> edges;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};

    Surface(const MeshSnapshot& mesh, const std::vector<int32_t>& boundary) : m(mesh), tri(boundary) {
        const size_t n = tri.size() / 3;
        normal.resize(n);
        for (size_t f = 0; f < n; ++f) {
            const double *a = point(tri[3 * f]), *b = point(tri[3 * f + 1]), *c = point(tri[3 * f + 2]);
            normal[f] = unit(cross(sub(b, a), sub(c, a)));
        }
        for (size_t k = 0; k < tri.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                const double x = point(tri[k])[c];
                lo[c] = k == 0 || x < lo[c] ? x : lo[c];
                hi[c] = k == 0 || x > hi[c] ? x : hi[c];
            }
    }

    const double* point(int32_t v) const { return &m.xyz[3 * static_cast<size_t>(v)]; }

    void build_edges() {
        const size_t n = tri.size() / 3;
        edges.reserve(3 * n);
        for (size_t f = 0; f < n; ++f)
            for (int k = 0; k < 3; ++k) {
                const int32_t a = tri[3 * f + k], b = tri[3 * f + (k + 1) % 3];
                edges.push_back({std::min(a, b), std::max(a, b), static_cast<int32_t>(f)});
            }
        std::sort(edges.begin(), edges.end(), [](const EdgeFace& x, const EdgeFace& y) {
            return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face < y.face;
        });
    }
};

std::string shaded_faces(const Surface& s, const View& v, const Projector& p, const std::vector<size_t>& front) {
    // Light from the upper right, in front.
    Vec light{0.0, 0.0, 0.0};
    light[static_cast<size_t>(v.right)] = 0.45;
    light[static_cast<size_t>(v.up)] = 0.6;
    light[static_cast<size_t>(v.toward)] = v.toward_sign;
    light = unit(light);
    struct Drawn {
        double depth;
        size_t face;
        int level;
    };
    std::vector<Drawn> faces;
    faces.reserve(front.size());
    for (const size_t f : front) {
        double depth = 0.0;
        for (int k = 0; k < 3; ++k) depth += v.toward_sign * s.point(s.tri[3 * f + k])[v.toward];
        const double lit = std::max(0.0, dot(s.normal[f], light));
        faces.push_back({depth, f, std::min(kShades - 1, static_cast<int>(lit * kShades))});
    }
    // Painter's order: the far faces first.
    std::sort(faces.begin(), faces.end(),
              [](const Drawn& a, const Drawn& b) { return a.depth != b.depth ? a.depth < b.depth : a.face < b.face; });
    std::string out = "<g class=\"faces\" stroke=\"#2b3442\" stroke-opacity=\"0.3\" stroke-width=\"4\" "
                      "stroke-linejoin=\"round\">";
    for (size_t k = 0; k < faces.size();) {
        // One path for a run of faces of one shade.
        out += "<path fill=\"" + shade_color(faces[k].level) + "\" d=\"";
        size_t j = k;
        for (; j < faces.size() && faces[j].level == faces[k].level; ++j) {
            const int32_t* t = &s.tri[3 * faces[j].face];
            for (int c = 0; c < 3; ++c) {
                const double* q = s.point(t[c]);
                out += (c ? "L" : "M") + std::to_string(p.X(q)) + " " + std::to_string(p.Y(q));
            }
            out += "Z";
        }
        out += "\"/>";
        k = j;
    }
    return out + "</g>\n";
}

// The outline's edges in the view: the silhouette (between a triangle that
// faces the viewer and one that does not) and the creases between two that
// face it; the kMaxViewEdges longest on the page.  Returns the path and
// sets `candidates` to the number of such edges.
std::string outline(const Surface& s, const View& v, const Projector& p, const std::vector<char>& facing,
                    size_t& candidates) {
    struct Line {
        double length;
        int32_t a, b;
    };
    std::vector<Line> lines;
    const auto& e = s.edges;
    for (size_t k = 0; k < e.size();) {
        size_t j = k;
        bool any_front = false, all_front = true;
        for (; j < e.size() && e[j].a == e[k].a && e[j].b == e[k].b; ++j) {
            any_front = any_front || facing[static_cast<size_t>(e[j].face)];
            all_front = all_front && facing[static_cast<size_t>(e[j].face)];
        }
        bool drawn;
        if (j - k == 2) {
            const bool crease = dot(s.normal[static_cast<size_t>(e[k].face)],
                                    s.normal[static_cast<size_t>(e[k + 1].face)]) < kCosCrease;
            drawn = (any_front && !all_front) || (all_front && crease);
        } else {
            drawn = any_front;  // an open or non-manifold edge
        }
        if (drawn) {
            const double *a = s.point(e[k].a), *b = s.point(e[k].b);
            const double du = a[v.right] - b[v.right], dv = a[v.up] - b[v.up];
            lines.push_back({du * du + dv * dv, e[k].a, e[k].b});
        }
        k = j;
    }
    candidates = lines.size();
    if (lines.size() > kMaxViewEdges) {
        std::nth_element(lines.begin(), lines.begin() + static_cast<std::ptrdiff_t>(kMaxViewEdges), lines.end(),
                         [](const Line& x, const Line& y) { return x.length > y.length; });
        lines.resize(kMaxViewEdges);
    }
    std::string d;
    for (const Line& l : lines) {
        const double *a = s.point(l.a), *b = s.point(l.b);
        d += "M" + std::to_string(p.X(a)) + " " + std::to_string(p.Y(a)) + "L" + std::to_string(p.X(b)) + " " +
             std::to_string(p.Y(b));
    }
    return "<path class=\"outline\" fill=\"none\" stroke=\"#39455a\" stroke-width=\"10\" stroke-linecap=\"round\" "
           "data-edges=\"" + std::to_string(lines.size()) + "\" d=\"" + d + "\"/>\n";
}

std::string marks(const MeshSnapshot& m, const std::vector<size_t>& marked, const Projector& p) {
    std::string out = "<g class=\"marks\">";
    // The worst last, on top.
    for (size_t r = marked.size(); r-- > 0;) {
        const size_t t = marked[r];
        double c[3] = {0.0, 0.0, 0.0};
        for (size_t j = 0; j < 4; ++j) {
            const size_t v = static_cast<size_t>(m.tets[4 * t + j] - m.base);
            for (size_t k = 0; k < 3; ++k) c[k] += 0.25 * m.xyz[3 * v + k];
        }
        const long x = p.X(c), y = p.Y(c);
        out += "<g class=\"mark\" data-rank=\"" + std::to_string(r + 1) + "\" data-tet=\"" +
               std::to_string(t + static_cast<size_t>(m.base)) + "\"><circle cx=\"" + std::to_string(x) +
               "\" cy=\"" + std::to_string(y) + "\" r=\"70\" fill=\"" + kColorMark +
               "\" stroke=\"#fff\" stroke-width=\"15\"/><text x=\"" + std::to_string(x) + "\" y=\"" +
               std::to_string(y + 30) + "\">" + std::to_string(r + 1) + "</text></g>";
    }
    return out + "</g>\n";
}

}  // namespace

std::string orthographic_views(const MeshSnapshot& m, const std::vector<int32_t>& boundary,
                               const std::vector<size_t>& marked, const std::string& which) {
    Surface s(m, boundary);
    const size_t nfaces = boundary.size() / 3;
    const double L = std::max({s.hi[0] - s.lo[0], s.hi[1] - s.lo[1], s.hi[2] - s.lo[2]});
    // One scale for the three views, in SVG units per mesh unit.
    const double S = kUnit * kViewPixels / (L > 0.0 ? L : 1.0);
    const double margin = kUnit * kMarginPixels / S;  // in mesh units
    std::string out = "<div class=\"views\" id=\"views-" + which + "\" data-mesh=\"" + which + "\">\n";
    for (const View& v : kViews) {
        const Projector p{S, s.lo[v.right] - margin, s.hi[v.up] + margin, v.right, v.up};
        const long width = std::lround(S * (s.hi[v.right] - s.lo[v.right] + 2 * margin));
        const long height = std::lround(S * (s.hi[v.up] - s.lo[v.up] + 2 * margin));
        std::vector<char> facing(nfaces);
        std::vector<size_t> front;
        for (size_t f = 0; f < nfaces; ++f) {
            facing[f] = v.toward_sign * s.normal[f][static_cast<size_t>(v.toward)] > 0.0;
            if (facing[f]) front.push_back(f);
        }
        const bool faces = front.size() <= kMaxViewFaces;
        std::string body;
        size_t drawn = front.size(), of = front.size();
        if (faces) {
            body = shaded_faces(s, v, p, front);
        } else {
            if (s.edges.empty()) s.build_edges();
            body = outline(s, v, p, facing, of);
            drawn = std::min(of, kMaxViewEdges);
        }
        const std::string id = "view-" + which + "-" + v.name;
        out += "<figure class=\"view\"><svg class=\"view\" id=\"" + id + "\" viewBox=\"0 0 " +
               std::to_string(width) + " " + std::to_string(height) + "\" width=\"" +
               fixed(static_cast<double>(width) / kUnit, 1) + "\" height=\"" +
               fixed(static_cast<double>(height) / kUnit, 1) + "\" role=\"img\" aria-labelledby=\"" + id +
               "-t\" data-mesh=\"" + which + "\" data-view=\"" + v.name + "\" data-style=\"" +
               (faces ? "faces" : "outline") + "\" data-drawn=\"" + std::to_string(drawn) + "\" data-of=\"" +
               std::to_string(of) + "\" data-axes=\"" + kAxisNames[v.right] + " " + kAxisNames[v.up] +
               "\" data-map=\"" + exact(S) + " " + exact(p.U0) + " " + exact(p.V0) + "\">\n<title id=\"" + id +
               "-t\">" + escape_html(v.caption) + "</title>\n" + body + marks(m, marked, p) + "</svg>\n" +
               "<figcaption>" + escape_html(v.caption) + "</figcaption></figure>\n";
    }
    return out + "</div>\n";
}

}  // namespace bodt_cli
