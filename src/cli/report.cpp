// `bodt report`: see report.hpp.
//
// Decisions, in short:
//  - The dihedral histograms use 1-degree bins over [0, 180] (the last bin
//    holds 180), like paper 000's figures, with a linear count axis shared by
//    the two meshes.  The six angles of each tet are computed here from the
//    vertex coordinates by the library's header-only kernel (pi minus the
//    angle between the face normals at the edge), in the library's corner
//    order, so the 1-degree counts add up to
//    bodt_quality.dihedral_histogram's 23 bins.  An inverted or flat tet
//    (bodt_mesh_tet_quality gives it 0 and 180 degrees) counts, as in
//    bodt_mesh_quality, two of its angles as 0 and 180 degrees (its first two
//    in the caller's vertex order, which may not be the pair the library
//    picks: only the angles of inverted tets may land in other bins).
//  - Stretch histograms: 20 bins of 0.05 over [0, 1]; inverted and flat tets
//    get their own bar on the left.
//  - The worst tets are ranked by stretch, lowest first (inverted tets
//    first), ties by index; indices in the handle's base.  The first
//    kMarkedCount of them are the numbered dots of the views.
//  - Section order: key figures, quality, where the worst tets are, the
//    boundary (bodt compare's figures), histograms, worst tets, how the mesh
//    was made (long: its table of steps).
//  - Nonzero bars are at least 1.5 px tall, so that the few bad tets in the
//    tails stay visible at linear scale; each bar has a <title> tooltip with
//    its exact count, and every histogram carries its counts in data-counts.
#include "cli/report.hpp"

#include "cli/compare.hpp"
#include "cli/domain_boundary.hpp"
#include "cli/report_format.hpp"
#include "cli/report_sections.hpp"
#include "cli/report_views.hpp"
#include "quality/tet_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace bodt_cli {
namespace {

constexpr int kAngleBins = 180;      // 1-degree bins over [0, 180]
constexpr int kStretchBins = 20;     // 0.05 over [0, 1]
constexpr double kSmallAngle = 10.0; // "tets with an angle below 10 degrees"
constexpr double kLargeAngle = 165.0;
constexpr int kWorstCount = 20;
constexpr size_t kMarkedCount = 10;  // of them marked in the views

const char* const kColorBefore = "#d9822b";
const char* const kColorAfter = "#2f6fde";
const char* const kColorInverted = "#c62828";

// ------------------------------------------------------------- mesh data

// What the report derives from a mesh's snapshot.
struct MeshData {
    explicit MeshData(const MeshSnapshot& snapshot) : m(snapshot) {}
    const MeshSnapshot& m;
    std::vector<int64_t> angle_counts;    // kAngleBins
    std::vector<int64_t> stretch_counts;  // kStretchBins
    int64_t inverted = 0;                 // tets with 0 and 180 degrees
    int64_t small_angle = 0, large_angle = 0;
    int64_t bad_angle = 0;                // either of the two
    std::vector<size_t> worst;            // the kWorstCount worst tets, worst first
};

// The histograms, counts and worst tets of `d`.
bool derive(MeshData& d, std::string& error) {
    const MeshSnapshot& m = d.m;
    const size_t nt = static_cast<size_t>(m.ntets);
    d.angle_counts.assign(kAngleBins, 0);
    d.stretch_counts.assign(kStretchBins, 0);
    // Checked once here; the loops below read the corners freely.
    for (size_t k = 0; k < 4 * nt; ++k)
        if (m.tets[k] - m.base < 0 || m.tets[k] - m.base >= m.nverts) {
            error = "tet " + std::to_string(k / 4 + static_cast<size_t>(m.base)) + " has a vertex index out of range";
            return false;
        }
    const auto corners = [&](size_t t) {
        bodt::TetPoints p;
        for (size_t k = 0; k < 4; ++k) {
            const double* x = &m.xyz[3 * static_cast<size_t>(m.tets[4 * t + k] - m.base)];
            p[k] = bodt::Vec3(x[0], x[1], x[2]);
        }
        return p;
    };
    int64_t negative = 0, positive = 0;
    for (size_t t = 0; t < nt; ++t) {
        const bodt::TetPoints p = corners(t);
        const int sign = bodt::orient(p[0], p[1], p[2], p[3]).sign;
        negative += sign < 0;
        positive += sign > 0;
    }
    // The library holds the tets in the majority's orientation made
    // positive, corners 2 and 3 swapped (mesh_builder.cpp); the angles'
    // last bits, and so their bins, follow the corner order.
    const bool flipped = negative > positive;
    for (size_t t = 0; t < nt; ++t) {
        bodt::TetPoints p = corners(t);
        if (flipped) std::swap(p[2], p[3]);
        auto angles = bodt::dihedral_angles(p);
        const bool inverted = m.min_dihedral[t] <= 0.0 && m.max_dihedral[t] >= 180.0;
        if (inverted) {  // as bodt_mesh_quality: one 0 and one 180 degree angle
            ++d.inverted;
            angles[0] = 0.0;
            angles[1] = 180.0;
        }
        for (double a : angles) {
            int bin = static_cast<int>(std::floor(a));
            bin = std::clamp(bin, 0, kAngleBins - 1);
            ++d.angle_counts[static_cast<size_t>(bin)];
        }
        if (!inverted) {
            int bin = static_cast<int>(std::floor(m.stretch[t] * kStretchBins));
            bin = std::clamp(bin, 0, kStretchBins - 1);
            ++d.stretch_counts[static_cast<size_t>(bin)];
        }
        if (m.min_dihedral[t] < kSmallAngle) ++d.small_angle;
        if (m.max_dihedral[t] > kLargeAngle) ++d.large_angle;
        if (m.min_dihedral[t] < kSmallAngle || m.max_dihedral[t] > kLargeAngle) ++d.bad_angle;
    }
    d.worst.resize(nt);
    for (size_t i = 0; i < nt; ++i) d.worst[i] = i;
    const size_t k = std::min<size_t>(kWorstCount, nt);
    std::partial_sort(d.worst.begin(), d.worst.begin() + static_cast<std::ptrdiff_t>(k), d.worst.end(),
                      [&](size_t x, size_t y) {
                          if (m.stretch[x] != m.stretch[y]) return m.stretch[x] < m.stretch[y];
                          return x < y;
                      });
    d.worst.resize(k);
    return true;
}

// ------------------------------------------------------------- SVG charts

// 1, 2, 5 times a power of ten, at least raw.
double nice_step(double raw) {
    if (raw <= 1.0) return 1.0;
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= raw) return m * p;
    return 10.0 * p;
}

struct Bar {
    double lo, hi;  // in x units
    int64_t count;
    std::string tip;
};

struct Marker {
    double x;
    std::string label;
    bool left;  // label on the left of the line
};

struct Chart {
    std::string id, measure, mesh, title;
    std::string x_label, y_label;
    double x_min = 0, x_max = 1;
    std::vector<double> major_ticks, minor_ticks;
    int tick_decimals = 0;
    std::string tick_suffix;
    std::vector<std::pair<double, double>> shaded;  // bad ranges
    std::vector<Bar> bars;
    std::string color;
    double bar_gap = 0;  // px between bars
    std::vector<Marker> markers;
    bool has_inverted_bar = false;  // a separate bar left of the axis
    int64_t inverted = 0;
    double y_top = 1, y_step = 1;   // shared scale
    std::vector<int64_t> data_counts;
    double bin_width = 1;
};

std::string num(double v) { return format("%.2f", v); }

std::string render_chart(const Chart& c) {
    const double W = 560, H = 300;
    const double ml = 62, mr = 24, mt = 30, mb = 50;
    const double inv_w = c.has_inverted_bar ? 52 : 0;  // slot for the inverted bar
    const double px0 = ml + inv_w, px1 = W - mr;         // the x axis proper
    const double py0 = H - mb, py1 = mt;                 // bottom, top
    auto X = [&](double x) { return px0 + (x - c.x_min) / (c.x_max - c.x_min) * (px1 - px0); };
    auto Y = [&](double y) { return py0 - y / c.y_top * (py0 - py1); };
    auto bar_h = [&](int64_t n) {
        if (n <= 0) return 0.0;
        return std::max(1.5, py0 - Y(static_cast<double>(n)));
    };

    std::string s;
    s += "<svg id=\"" + c.id + "\" class=\"hist\" viewBox=\"0 0 560 300\" role=\"img\"";
    s += " aria-labelledby=\"" + c.id + "-t\" data-measure=\"" + c.measure + "\" data-mesh=\"" +
         c.mesh + "\" data-bin-width=\"" + exact(c.bin_width) + "\" data-counts=\"";
    for (size_t i = 0; i < c.data_counts.size(); ++i) {
        if (i) s += ' ';
        s += std::to_string(c.data_counts[i]);
    }
    s += "\"";
    if (c.has_inverted_bar) s += " data-inverted=\"" + std::to_string(c.inverted) + "\"";
    s += ">\n<title id=\"" + c.id + "-t\">" + escape_html(c.title) + "</title>\n";

    // Shaded bad ranges.
    for (const auto& r : c.shaded)
        s += "<rect class=\"bad\" x=\"" + num(X(r.first)) + "\" y=\"" + num(py1) + "\" width=\"" +
             num(X(r.second) - X(r.first)) + "\" height=\"" + num(py0 - py1) + "\"/>\n";

    // Horizontal grid and y ticks.
    s += "<g class=\"grid\">";
    for (double y = 0; y <= c.y_top + 0.5 * c.y_step; y += c.y_step) {
        const double yy = Y(y);
        s += "<line x1=\"" + num(ml) + "\" x2=\"" + num(px1) + "\" y1=\"" + num(yy) + "\" y2=\"" +
             num(yy) + "\"/>";
    }
    s += "</g>\n<g class=\"ylab\">";
    for (double y = 0; y <= c.y_top + 0.5 * c.y_step; y += c.y_step)
        s += "<text x=\"" + num(ml - 8) + "\" y=\"" + num(Y(y) + 4) + "\">" +
             grouped(static_cast<int64_t>(std::llround(y))) + "</text>";
    s += "</g>\n";

    // Bars.
    s += "<g fill=\"" + std::string(c.color) + "\">";
    for (const auto& b : c.bars) {
        if (b.count <= 0) continue;
        const double x0 = X(b.lo) + c.bar_gap / 2, x1 = X(b.hi) - c.bar_gap / 2;
        const double h = bar_h(b.count);
        s += "<rect x=\"" + num(x0) + "\" y=\"" + num(py0 - h) + "\" width=\"" +
             num(std::max(0.5, x1 - x0)) + "\" height=\"" + num(h) + "\"><title>" +
             escape_html(b.tip) + "</title></rect>";
    }
    s += "</g>\n";
    if (c.has_inverted_bar) {
        const double x0 = ml + 10, x1 = ml + inv_w - 10;
        const double h = bar_h(c.inverted);
        if (h > 0)
            s += "<rect fill=\"" + std::string(kColorInverted) + "\" x=\"" + num(x0) + "\" y=\"" +
                 num(py0 - h) + "\" width=\"" + num(x1 - x0) + "\" height=\"" + num(h) +
                 "\"><title>inverted or flat: " + grouped(c.inverted) + " tets</title></rect>";
        s += "<text class=\"xlab\" x=\"" + num((x0 + x1) / 2) + "\" y=\"" + num(py0 + 18) +
             "\">inv.</text>";
        s += std::string("<text class=\"count-inv") + (c.inverted ? "" : " none") + "\" x=\"" +
             num((x0 + x1) / 2) + "\" y=\"" + num(py0 - h - 5) + "\">" + grouped(c.inverted) +
             "</text>\n";
        s += "<line class=\"sep\" x1=\"" + num(px0) + "\" x2=\"" + num(px0) + "\" y1=\"" +
             num(py1) + "\" y2=\"" + num(py0) + "\"/>\n";
    }

    // Markers (dashed lines with a label above the plot).
    for (const auto& m : c.markers) {
        const double x = X(m.x);
        s += "<line class=\"marker\" x1=\"" + num(x) + "\" x2=\"" + num(x) + "\" y1=\"" +
             num(py1 - 4) + "\" y2=\"" + num(py0) + "\"/>";
        s += "<text class=\"mlab\" x=\"" + num(m.left ? x - 4 : x + 4) + "\" y=\"" +
             num(py1 - 8) + "\" text-anchor=\"" + (m.left ? "end" : "start") + "\">" +
             escape_html(m.label) + "</text>\n";
    }

    // Axes.
    s += "<g class=\"axis\"><line x1=\"" + num(ml) + "\" x2=\"" + num(px1) + "\" y1=\"" +
         num(py0) + "\" y2=\"" + num(py0) + "\"/><line x1=\"" + num(ml) + "\" x2=\"" + num(ml) +
         "\" y1=\"" + num(py1) + "\" y2=\"" + num(py0) + "\"/>";
    for (double t : c.minor_ticks)
        s += "<line x1=\"" + num(X(t)) + "\" x2=\"" + num(X(t)) + "\" y1=\"" + num(py0) +
             "\" y2=\"" + num(py0 + 3) + "\"/>";
    for (double t : c.major_ticks)
        s += "<line x1=\"" + num(X(t)) + "\" x2=\"" + num(X(t)) + "\" y1=\"" + num(py0) +
             "\" y2=\"" + num(py0 + 6) + "\"/>";
    for (double y = 0; y <= c.y_top + 0.5 * c.y_step; y += c.y_step)
        s += "<line x1=\"" + num(ml - 4) + "\" x2=\"" + num(ml) + "\" y1=\"" + num(Y(y)) +
             "\" y2=\"" + num(Y(y)) + "\"/>";
    s += "</g>\n<g class=\"xlab\">";
    for (double t : c.major_ticks)
        s += "<text x=\"" + num(X(t)) + "\" y=\"" + num(py0 + 18) + "\">" +
             fixed(t, c.tick_decimals) + c.tick_suffix + "</text>";
    s += "</g>\n";
    s += "<text class=\"axis-title\" x=\"" + num((px0 + px1) / 2) + "\" y=\"" + num(H - 8) +
         "\">" + escape_html(c.x_label) + "</text>\n";
    s += "<text class=\"axis-title\" transform=\"translate(16 " + num((py0 + py1) / 2) +
         ") rotate(-90)\">" + escape_html(c.y_label) + "</text>\n";
    s += "</svg>\n";
    return s;
}

// A shared count scale for two charts.
void shared_scale(Chart& a, Chart& b) {
    int64_t top = 1;
    for (const Chart* c : {&a, &b}) {
        for (const auto& bar : c->bars) top = std::max(top, bar.count);
        top = std::max(top, c->inverted);
    }
    const double step = nice_step(static_cast<double>(top) / 5.0);
    const double y_top = std::ceil(static_cast<double>(top) / step) * step;
    a.y_top = b.y_top = y_top;
    a.y_step = b.y_step = step;
}


Chart dihedral_chart(const MeshData& d, const std::string& which, const char* color) {
    const bodt_quality& q = d.m.quality;
    Chart c;
    c.id = "dihedral-" + which;
    c.measure = "dihedral";
    c.mesh = which;
    c.title = "Dihedral angles of the " + which + " mesh, 1" + kDeg + " bins";
    c.x_label = std::string("Dihedral angle (degrees)");
    c.y_label = "Number of angles";
    c.x_min = 0;
    c.x_max = 180;
    for (int t = 0; t <= 180; t += 30) c.major_ticks.push_back(t);
    for (int t = 0; t <= 180; t += 10)
        if (t % 30) c.minor_ticks.push_back(t);
    c.tick_suffix = kDeg;
    c.shaded = {{0.0, kSmallAngle}, {kLargeAngle, 180.0}};
    for (int i = 0; i < kAngleBins; ++i) {
        const int64_t n = d.angle_counts[static_cast<size_t>(i)];
        c.bars.push_back({double(i), double(i + 1), n,
                          std::to_string(i) + kDash + std::to_string(i + 1) + kDeg + ": " +
                              grouped(n) + (n == 1 ? " angle" : " angles")});
    }
    c.data_counts = d.angle_counts;
    c.color = color;
    c.markers = {{q.min_dihedral, "min " + fixed(q.min_dihedral, 1) + kDeg, false},
                 {q.max_dihedral, "max " + fixed(q.max_dihedral, 1) + kDeg, true}};
    return c;
}

Chart stretch_chart(const MeshData& d, const std::string& which, const char* color) {
    const bodt_quality& q = d.m.quality;
    Chart c;
    c.id = "stretch-" + which;
    c.measure = "stretch";
    c.mesh = which;
    c.title = "Stretch of the tets of the " + which + " mesh, bins of 0.05";
    c.x_label = "Stretch (1 = regular tet)";
    c.y_label = "Number of tets";
    c.x_min = 0;
    c.x_max = 1;
    for (int t = 0; t <= 10; t += 2) c.major_ticks.push_back(t / 10.0);
    for (int t = 1; t < 10; t += 2) c.minor_ticks.push_back(t / 10.0);
    c.tick_decimals = 1;
    for (int i = 0; i < kStretchBins; ++i) {
        const int64_t n = d.stretch_counts[static_cast<size_t>(i)];
        const double lo = i / double(kStretchBins), hi = (i + 1) / double(kStretchBins);
        c.bars.push_back({lo, hi, n,
                          fixed(lo, 2) + kDash + fixed(hi, 2) + ": " + grouped(n) +
                              (n == 1 ? " tet" : " tets")});
    }
    c.bar_gap = 1.5;
    c.data_counts = d.stretch_counts;
    c.has_inverted_bar = true;
    c.inverted = d.inverted;
    c.color = color;
    const double ms = std::max(0.0, q.min_stretch);
    c.markers = {{ms, "min " + with_minus(fixed(q.min_stretch, 3)), ms > 0.6}};
    return c;
}

// ------------------------------------------------------------- tables

struct Row {
    const char* key;
    std::string label;
    double before, after;
    int decimals;     // -1: integer count
    int better;       // +1 higher is better, -1 lower is better, 0 neutral
    std::string unit;
};

std::string value_text(double v, int decimals, const std::string& unit) {
    if (decimals < 0) return grouped(static_cast<int64_t>(std::llround(v)));
    if (decimals >= 100) return general(v, decimals - 100) + unit;  // significant digits
    return with_minus(fixed(v, decimals)) + unit;
}

std::string quality_row(const Row& r) {
    std::string s = "<tr data-key=\"" + std::string(r.key) + "\"><th scope=\"row\">" + r.label +
                    "</th>";
    s += "<td data-value=\"" + exact(r.before) + "\">" + value_text(r.before, r.decimals, r.unit) +
         "</td>";
    s += "<td data-value=\"" + exact(r.after) + "\">" + value_text(r.after, r.decimals, r.unit) +
         "</td>";
    // Change.
    std::string cls = "same", text;
    if (std::string(r.key) == "volume") {
        const double rel = r.before != 0.0 ? (r.after - r.before) / std::fabs(r.before) : 0.0;
        text = rel == 0.0 ? "=" : percent(100.0 * rel);
        s += "<td class=\"change " + cls + "\" data-value=\"" + exact(rel) + "\">" + text +
             "</td></tr>\n";
        return s;
    }
    const double diff = r.after - r.before;
    const double shown_eps = r.decimals < 0 ? 0.5 : 0.5 * std::pow(10.0, -r.decimals);
    if (std::fabs(diff) < shown_eps) {
        text = diff == 0.0 ? "=" : "\xE2\x89\x88 0";  // approximately
    } else {
        text = (diff > 0 ? "+" : "") + value_text(diff, r.decimals, r.unit);
        if (r.better != 0) cls = (diff > 0) == (r.better > 0) ? "better" : "worse";
    }
    s += "<td class=\"change " + cls + "\" data-value=\"" + exact(diff) + "\">" + text +
         "</td></tr>\n";
    return s;
}

std::string quality_table(const MeshData& a, const MeshData& b) {
    const std::string deg = kDeg;
    const bodt_quality &qa = a.m.quality, &qb = b.m.quality;
    const std::vector<Row> rows = {
        {"vertices", "Vertices", double(qa.num_vertices), double(qb.num_vertices), -1, 0, ""},
        {"tets", "Tets", double(qa.num_tets), double(qb.num_tets), -1, 0, ""},
        {"boundary_faces", "Boundary faces", double(qa.num_boundary_faces),
         double(qb.num_boundary_faces), -1, 0, ""},
        {"min_dihedral", "Smallest dihedral angle", qa.min_dihedral, qb.min_dihedral, 2, 1, deg},
        {"max_dihedral", "Largest dihedral angle", qa.max_dihedral, qb.max_dihedral, 2, -1, deg},
        {"mean_dihedral", "Mean dihedral angle", qa.mean_dihedral, qb.mean_dihedral, 2, 0, deg},
        {"min_stretch", "Smallest stretch", qa.min_stretch, qb.min_stretch, 4, 1, ""},
        {"mean_stretch", "Mean stretch", qa.mean_stretch, qb.mean_stretch, 4, 1, ""},
        {"num_inverted", "Inverted tets", double(qa.num_inverted), double(qb.num_inverted), -1,
         -1, ""},
        {"below_10", "Tets with an angle below 10" + deg, double(a.small_angle),
         double(b.small_angle), -1, -1, ""},
        {"above_165", "Tets with an angle above 165" + deg, double(a.large_angle),
         double(b.large_angle), -1, -1, ""},
        {"volume", "Volume", qa.volume, qb.volume, 106, 0, ""},
    };
    std::string s =
        "<div class=\"scroll\"><table class=\"quality\" id=\"quality-table\">\n"
        "<thead><tr><th scope=\"col\"></th><th scope=\"col\"><span class=\"dot before\"></span>"
        "Original</th><th scope=\"col\"><span class=\"dot after\"></span>Improved</th>"
        "<th scope=\"col\">Change</th></tr></thead>\n<tbody>\n";
    for (const auto& r : rows) s += quality_row(r);
    s += "</tbody></table></div>\n";
    return s;
}

std::string worst_table(const MeshData& d, const std::string& which) {
    const MeshSnapshot& m = d.m;
    const std::vector<size_t>& order = d.worst;
    const size_t k = order.size();
    std::string s = "<div class=\"scroll\"><table class=\"worst\" id=\"worst-" + which +
                    "\" data-base=\"" + std::to_string(m.base) + "\">\n<thead><tr>"
                    "<th scope=\"col\">#</th><th scope=\"col\">Tet</th>"
                    "<th scope=\"col\">Min angle</th><th scope=\"col\">Max angle</th>"
                    "<th scope=\"col\">Stretch</th><th scope=\"col\">Volume</th>"
                    "<th scope=\"col\" class=\"centroid\">Centroid (x, y, z)</th>"
                    "</tr></thead>\n<tbody>\n";
    for (size_t r = 0; r < k; ++r) {
        const size_t t = order[r];
        double c[3] = {0, 0, 0};
        for (size_t j = 0; j < 4; ++j) {
            const size_t v = static_cast<size_t>(m.tets[4 * t + j] - m.base);
            for (size_t x = 0; x < 3; ++x) c[x] += 0.25 * m.xyz[3 * v + x];
        }
        const bool inv = m.min_dihedral[t] <= 0.0 && m.max_dihedral[t] >= 180.0;
        s += "<tr data-tet=\"" + std::to_string(t + static_cast<size_t>(m.base)) + "\"" +
             (inv ? " class=\"inverted\"" : "") + ">";
        s += "<td class=\"rank\">" + std::string(r < kMarkedCount ? "<span class=\"markdot\"></span>" : "") +
             std::to_string(r + 1) + "</td>";
        s += "<td class=\"idx\">" + std::to_string(t + static_cast<size_t>(m.base)) + "</td>";
        s += std::string("<td data-value=\"") + exact(m.min_dihedral[t]) + "\"" +
             (m.min_dihedral[t] < kSmallAngle ? " class=\"bad\"" : "") + ">" + fixed(m.min_dihedral[t], 2) +
             kDeg + "</td>";
        s += std::string("<td data-value=\"") + exact(m.max_dihedral[t]) + "\"" +
             (m.max_dihedral[t] > kLargeAngle ? " class=\"bad\"" : "") + ">" + fixed(m.max_dihedral[t], 2) +
             kDeg + "</td>";
        s += "<td data-value=\"" + exact(m.stretch[t]) + "\"" +
             (m.stretch[t] <= 0.0 ? " class=\"bad\"" : "") + ">" +
             with_minus(fixed(m.stretch[t], 4)) + "</td>";
        s += "<td data-value=\"" + exact(m.volume[t]) + "\">" + general(m.volume[t], 4) + "</td>";
        s += "<td class=\"centroid\" data-value=\"" + exact(c[0]) + " " + exact(c[1]) + " " +
             exact(c[2]) + "\">" + general(c[0], 5) + ", " + general(c[1], 5) + ", " +
             general(c[2], 5) + "</td></tr>\n";
    }
    s += "</tbody></table></div>\n";
    return s;
}

// ------------------------------------------------------------- page

const char* const kStyle = R"CSS(
:root { --before: #d9822b; --after: #2f6fde; --bad: #c62828; --good: #1b7f3b;
  --ink: #1d2330; --muted: #5b6475; --line: #dde2ea; --soft: #f5f7fa; }
* { box-sizing: border-box; }
html { -webkit-text-size-adjust: 100%; }
body { margin: 0; color: var(--ink); background: #fff;
  font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", "DejaVu Sans", Arial, sans-serif; }
main, header > .wrap { max-width: 1160px; margin: 0 auto; padding: 0 24px; }
header { background: #1f2a3c; color: #fff; padding: 26px 0 22px; }
header h1 { margin: 0; font-size: 26px; font-weight: 650; letter-spacing: -0.01em; }
header .sub { margin: 2px 0 18px; color: #b8c2d3; font-size: 14px; }
.meshes { display: grid; grid-template-columns: repeat(auto-fit, minmax(min(100%, 280px), 1fr)); gap: 12px; }
.mesh { background: rgba(255,255,255,0.07); border-radius: 8px; padding: 10px 14px;
  border-left: 5px solid var(--before); min-width: 0; }
.mesh.after { border-left-color: var(--after); }
.mesh .role { font-size: 12px; text-transform: uppercase; letter-spacing: 0.08em; color: #b8c2d3; }
.mesh .path { display: block; font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace;
  font-size: 14px; overflow-wrap: anywhere; margin: 1px 0 3px; }
.mesh .counts { font-size: 13px; color: #d5dce8; }
section { margin: 30px 0 10px; }
h2 { font-size: 20px; margin: 0 0 4px; font-weight: 650; }
h3 { font-size: 15px; margin: 18px 0 6px; font-weight: 600; }
p.note { margin: 0 0 14px; color: var(--muted); font-size: 14px; max-width: 80ch; }
.cards { display: grid; grid-template-columns: repeat(auto-fit, minmax(min(100%, 200px), 1fr)); gap: 12px; }
.card { border: 1px solid var(--line); border-radius: 8px; padding: 12px 14px; background: var(--soft); }
.card .k { font-size: 13px; color: var(--muted); }
.card .v { font-size: 20px; font-weight: 600; font-variant-numeric: tabular-nums; white-space: nowrap; }
.card .v .arrow { color: var(--muted); font-weight: 400; padding: 0 4px; }
.card .v .b { color: var(--before); }
.card .v .a { color: var(--after); }
.scroll { overflow-x: auto; -webkit-overflow-scrolling: touch; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; font-size: 14px; }
th, td { padding: 6px 12px; border-bottom: 1px solid var(--line); white-space: nowrap; }
thead th { text-align: right; font-weight: 600; color: var(--muted); font-size: 13px;
  border-bottom: 2px solid #c6cdd8; }
tbody th { text-align: left; font-weight: 500; }
td { text-align: right; }
table.quality { min-width: min(100%, 640px); }
table.quality tbody tr:nth-child(3) td, table.quality tbody tr:nth-child(3) th,
table.quality tbody tr:nth-child(8) td, table.quality tbody tr:nth-child(8) th,
table.quality tbody tr:nth-child(11) td, table.quality tbody tr:nth-child(11) th
  { border-bottom: 2px solid #c6cdd8; }
td.change { color: var(--muted); }
td.change.better { color: var(--good); font-weight: 600; }
td.change.worse { color: var(--bad); font-weight: 600; }
.dot { display: inline-block; width: 10px; height: 10px; border-radius: 2px; margin-right: 6px;
  vertical-align: baseline; }
.dot.before { background: var(--before); }
.dot.after { background: var(--after); }
.pair { display: grid; grid-template-columns: repeat(auto-fit, minmax(min(100%, 420px), 1fr)); gap: 18px; }
figure { margin: 0; border: 1px solid var(--line); border-radius: 8px; padding: 10px 10px 4px;
  min-width: 0; overflow-x: auto; }
figcaption { font-size: 14px; font-weight: 600; padding: 0 4px 2px; overflow-wrap: anywhere; }
figcaption .path { font-weight: 400; color: var(--muted); font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 12px; }
svg.hist { display: block; width: 100%; min-width: 380px; height: auto; font-size: 12px; }
svg.hist text { fill: #3d4556; }
svg.hist .grid line { stroke: #e8ebf0; stroke-width: 1; shape-rendering: crispEdges; }
svg.hist .axis line { stroke: #4a5263; stroke-width: 1; shape-rendering: crispEdges; }
svg.hist .ylab text { text-anchor: end; }
svg.hist .xlab text, svg.hist text.xlab { text-anchor: middle; }
svg.hist .axis-title { text-anchor: middle; font-size: 13px; fill: #1d2330; }
svg.hist rect.bad { fill: #fdecec; }
svg.hist .marker { stroke: #1d2330; stroke-width: 1; stroke-dasharray: 4 3; }
svg.hist .mlab { font-size: 12px; font-weight: 600; fill: #1d2330; }
svg.hist .sep { stroke: #c6cdd8; stroke-dasharray: 2 3; }
svg.hist .count-inv { text-anchor: middle; font-size: 11px; fill: var(--bad); font-weight: 600; }
svg.hist .count-inv.none { fill: #8a93a3; font-weight: 400; }
.legend { font-size: 13px; color: var(--muted); margin: 8px 0 0; }
.legend .swatch { display: inline-block; width: 14px; height: 10px; background: #fdecec;
  border: 1px solid #f2c4c4; vertical-align: baseline; margin-right: 5px; }
table.worst td.rank { color: var(--muted); }
table.worst td.idx { font-weight: 600; }
table.worst td.bad { color: var(--bad); font-weight: 600; }
table.worst tr.inverted td { background: #fdecec; }
table.worst td.centroid, table.worst th.centroid { text-align: left; }
.views { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; }
figure.view { flex: 0 1 auto; padding: 6px; }
svg.view { display: block; max-width: 100%; height: auto; }
svg.view .marks text { fill: #fff; font: 700 80px system-ui, "DejaVu Sans", Arial, sans-serif; text-anchor: middle; }
figure.view figcaption { font-weight: 400; font-size: 13px; color: var(--muted); }
.markdot { display: inline-block; width: 9px; height: 9px; border-radius: 50%; background: #d81b60;
  margin-right: 5px; vertical-align: baseline; }
.card .n { font-size: 13px; color: var(--muted); overflow-wrap: anywhere; }
.card .v .bad, tr.lost td { color: var(--bad); }
table.run th { text-align: left; font-weight: 500; }
table.run td { text-align: left; white-space: normal; }
details { margin: 10px 0; }
summary { cursor: pointer; color: var(--muted); font-size: 14px; }
p.warn { color: var(--bad); }
tr.skipped td { text-align: center; color: var(--muted); }
footer { margin: 36px 0 28px; padding-top: 12px; border-top: 1px solid var(--line);
  color: var(--muted); font-size: 13px; }
@media (max-width: 600px) {
  body { font-size: 14px; }
  main, header > .wrap { padding: 0 12px; }
  header h1 { font-size: 22px; }
  th, td { padding: 5px 7px; }
  table { font-size: 13px; }
  tbody th { white-space: normal; min-width: 6.5em; }
  td.change { white-space: normal; }
  figure { padding: 8px 4px 2px; }
  svg.hist { min-width: 0; font-size: 17px; }
  svg.hist .axis-title { font-size: 18px; }
  svg.hist .mlab { font-size: 16px; }
  svg.hist .count-inv { font-size: 15px; }
}
)CSS";

std::string mesh_counts(const MeshData& d) {
    return grouped(d.m.nverts) + " vertices &middot; " + grouped(d.m.ntets) + " tets &middot; " +
           grouped(d.m.nfaces) + " boundary faces";
}

std::string card(const std::string& key, const std::string& before, const std::string& after) {
    return "<div class=\"card\"><div class=\"k\">" + key + "</div><div class=\"v\"><span class=\"b\">" +
           before + "</span><span class=\"arrow\">&rarr;</span><span class=\"a\">" + after +
           "</span></div></div>\n";
}

}  // namespace

bool render_report(const MeshSnapshot& original, const MeshSnapshot& improved, const std::string& original_name,
                   const std::string& improved_name, const RunRecord* run, std::string& html, std::string& error) {
    MeshData a(original), b(improved);
    if (!derive(a, error) || !derive(b, error)) return false;
    const std::vector<int32_t> boundary_a = domain_boundary(original), boundary_b = domain_boundary(improved);
    Comparison comparison;
    compare_meshes(original, improved, boundary_a, boundary_b, comparison);
    const std::string version = bodt_version_string();
    const std::string na = escape_html(original_name), nb = escape_html(improved_name);
    const std::string deg = kDeg;

    std::string& s = html;
    s.clear();
    s += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         "<meta name=\"generator\" content=\"bodt " + escape_html(version) + "\">\n"
         "<title>Mesh quality report: " + na + " &rarr; " + nb + "</title>\n<style>" + kStyle +
         "</style>\n</head>\n<body>\n";

    // Header.
    s += "<header><div class=\"wrap\">\n<h1>Mesh quality report</h1>\n"
         "<p class=\"sub\">bodt " + escape_html(version) +
         " &middot; original mesh and improved mesh</p>\n<div class=\"meshes\">\n";
    s += "<div class=\"mesh before\" id=\"mesh-original\"><div class=\"role\">Original</div>"
         "<span class=\"path\">" + na + "</span><span class=\"counts\">" + mesh_counts(a) +
         "</span></div>\n";
    s += "<div class=\"mesh after\" id=\"mesh-improved\"><div class=\"role\">Improved</div>"
         "<span class=\"path\">" + nb + "</span><span class=\"counts\">" + mesh_counts(b) +
         "</span></div>\n";
    s += "</div>\n</div></header>\n<main>\n";

    // Key figures.
    s += "<section id=\"summary\">\n<div class=\"cards\">\n";
    s += card("Smallest dihedral angle", fixed(original.quality.min_dihedral, 2) + deg,
              fixed(improved.quality.min_dihedral, 2) + deg);
    s += card("Largest dihedral angle", fixed(original.quality.max_dihedral, 2) + deg,
              fixed(improved.quality.max_dihedral, 2) + deg);
    s += card("Smallest stretch", with_minus(fixed(original.quality.min_stretch, 3)),
              with_minus(fixed(improved.quality.min_stretch, 3)));
    s += card("Tets with an angle &lt; 10" + deg + " or &gt; 165" + deg, grouped(a.bad_angle),
              grouped(b.bad_angle));
    s += "</div>\n</section>\n";

    // Quality table.
    s += "<section id=\"quality\">\n<h2>Quality</h2>\n<p class=\"note\">Dihedral angles, stretch "
         "and volume as reported by <code>bodt_mesh_quality</code>; the counts of tets with a "
         "small or large angle from the per-tet minimum and maximum dihedral angle.  Stretch is "
         "6&radic;6&nbsp;V / (sum of face areas &times; longest edge): 1 for the regular tet, 0 "
         "for a flat one, negative for an inverted one.</p>\n";
    s += quality_table(a, b);
    s += "</section>\n";

    // Where the worst tets are.
    {
        const auto marked = [](const MeshData& d) {
            return std::vector<size_t>(d.worst.begin(), d.worst.begin() + static_cast<std::ptrdiff_t>(
                                                                             std::min(kMarkedCount, d.worst.size())));
        };
        s += "<section id=\"where\">\n<h2>Where the worst tets are</h2>\n<p class=\"note\">The boundary seen "
             "from three sides, to one scale, with the " + std::to_string(kMarkedCount) + " worst tets of the table "
             "below marked at their centroids by numbered dots (<span class=\"markdot\"></span>, seen through "
             "the mesh).  Up to " + grouped(static_cast<int64_t>(kMaxViewFaces)) + " faces a view are drawn "
             "shaded, far ones first; beyond, the outline: silhouette and edges where the surface bends by more "
             "than 30" + deg + ".</p>\n";
        s += "<h3><span class=\"dot after\"></span>Improved mesh</h3>\n" +
             orthographic_views(improved, boundary_b, marked(b), "improved");
        s += "<h3><span class=\"dot before\"></span>Original mesh</h3>\n" +
             orthographic_views(original, boundary_a, marked(a), "original");
        s += "</section>\n";
    }

    s += boundary_section(comparison);

    // Dihedral histograms.
    {
        Chart ca = dihedral_chart(a, "original", kColorBefore);
        Chart cb = dihedral_chart(b, "improved", kColorAfter);
        shared_scale(ca, cb);
        s += "<section id=\"dihedral\">\n<h2>Dihedral angles</h2>\n<p class=\"note\">All six "
             "dihedral angles of every tet, in 1" + deg + " bins; both charts share the count "
             "scale.  Dashed lines mark the smallest and the largest angle.  An inverted tet "
             "counts as one 0" + deg + " and one 180" + deg + " angle.</p>\n<div class=\"pair\">\n";
        s += "<figure><figcaption><span class=\"dot before\"></span>Original <span "
             "class=\"path\">" + na + "</span></figcaption>\n" + render_chart(ca) + "</figure>\n";
        s += "<figure><figcaption><span class=\"dot after\"></span>Improved <span "
             "class=\"path\">" + nb + "</span></figcaption>\n" + render_chart(cb) + "</figure>\n";
        s += "</div>\n<p class=\"legend\"><span class=\"swatch\"></span>angles below 10" + deg +
             " and above 165" + deg + "</p>\n</section>\n";
    }

    // Stretch histograms.
    {
        Chart ca = stretch_chart(a, "original", kColorBefore);
        Chart cb = stretch_chart(b, "improved", kColorAfter);
        shared_scale(ca, cb);
        s += "<section id=\"stretch\">\n<h2>Stretch</h2>\n<p class=\"note\">One value per tet, "
             "in bins of 0.05; inverted and flat tets in their own bar (inv.).  Both charts "
             "share the count scale; the dashed line marks the smallest stretch.</p>\n"
             "<div class=\"pair\">\n";
        s += "<figure><figcaption><span class=\"dot before\"></span>Original <span "
             "class=\"path\">" + na + "</span></figcaption>\n" + render_chart(ca) + "</figure>\n";
        s += "<figure><figcaption><span class=\"dot after\"></span>Improved <span "
             "class=\"path\">" + nb + "</span></figcaption>\n" + render_chart(cb) + "</figure>\n";
        s += "</div>\n</section>\n";
    }

    // Worst tets.
    s += "<section id=\"worst\">\n<h2>Worst tets</h2>\n<p class=\"note\">The " +
         std::to_string(kWorstCount) + " tets with the lowest stretch, worst first; the first " +
         std::to_string(kMarkedCount) + " (<span class=\"markdot\"></span>) are marked in the views above.  Tets "
         "and vertices are numbered as in each file: the improved mesh's from " + std::to_string(improved.base) +
         ", the original's from " + std::to_string(original.base) + "; angles below 10" + deg + " or above 165" + deg +
         " in red.</p>\n";
    s += "<h3><span class=\"dot after\"></span>Improved mesh</h3>\n" + worst_table(b, "improved");
    s += "<h3><span class=\"dot before\"></span>Original mesh</h3>\n" + worst_table(a, "original");
    s += "</section>\n";

    s += run_section(run, improved.quality);

    s += "<footer>Generated by bodt " + escape_html(version) +
         ".  A self-contained page: no script, no external resource.</footer>\n</main>\n"
         "</body>\n</html>\n";
    return true;
}

bool write_report(const MeshSnapshot& original, const MeshSnapshot& improved, const std::string& original_name,
                  const std::string& improved_name, const RunRecord* run, const std::string& out_path,
                  std::string& error) {
    std::string html;
    if (!render_report(original, improved, original_name, improved_name, run, html, error)) return false;
    std::ofstream out(out_path, std::ios::binary | std::ios::trunc);
    if (!out) {
        error = "cannot write " + out_path;
        return false;
    }
    out.write(html.data(), static_cast<std::streamsize>(html.size()));
    out.close();
    if (!out) {
        error = "cannot write " + out_path;
        return false;
    }
    return true;
}

}  // namespace bodt_cli
