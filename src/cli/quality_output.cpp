#include "cli/quality_output.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace bodt_cli {

bodt_quality measure(const bodt_mesh* mesh) {
    bodt_quality q;
    std::memset(&q, 0, sizeof q);
    q.size = sizeof q;
    bodt_mesh_quality(mesh, &q);
    return q;
}

void print_row(const char* name, const std::string& before, const std::string& after) {
    if (before.empty()) std::printf("%-16s %14s\n", name, after.c_str());
    else std::printf("%-16s %14s %14s\n", name, before.c_str(), after.c_str());
}

namespace {

std::string format(const char* fmt, double value) {
    char text[64];
    std::snprintf(text, sizeof text, fmt, value);
    return text;
}

}  // namespace

void print_table(const bodt_quality* before, const bodt_quality& after) {
    const auto row_i = [&](const char* name, int32_t bodt_quality::*field) {
        print_row(name, before ? std::to_string(before->*field) : "", std::to_string(after.*field));
    };
    const auto row_d = [&](const char* name, double bodt_quality::*field, const char* fmt) {
        print_row(name, before ? format(fmt, before->*field) : "", format(fmt, after.*field));
    };
    if (before) print_row("", "before", "after");
    row_i("vertices", &bodt_quality::num_vertices);
    row_i("tets", &bodt_quality::num_tets);
    row_i("boundary faces", &bodt_quality::num_boundary_faces);
    row_d("min dihedral", &bodt_quality::min_dihedral, "%.3f");
    row_d("max dihedral", &bodt_quality::max_dihedral, "%.3f");
    row_d("mean dihedral", &bodt_quality::mean_dihedral, "%.3f");
    row_d("min stretch", &bodt_quality::min_stretch, "%.5f");
    row_d("mean stretch", &bodt_quality::mean_stretch, "%.5f");
    row_i("inverted", &bodt_quality::num_inverted);
    row_d("volume", &bodt_quality::volume, "%.8g");
}

std::string json_string(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char esc[8];
            std::snprintf(esc, sizeof esc, "\\u%04x", c);
            out += esc;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

std::string json_number(double v) {
    if (!std::isfinite(v)) return "null";
    char text[40];
    std::snprintf(text, sizeof text, "%.15g", v);
    if (std::strtod(text, nullptr) != v) std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

std::string quality_json_members(const bodt_quality& q, bool edges) {
    char text[1024];
    std::snprintf(text, sizeof text,
                  "\"vertices\": %d, \"tets\": %d, \"boundary_faces\": %d, \"unused_vertices\": %d, "
                  "\"inverted\": %d, \"volume\": %.17g, \"min_dihedral\": %.6f, \"max_dihedral\": %.6f, "
                  "\"mean_dihedral\": %.6f, \"min_stretch\": %.6f, \"mean_stretch\": %.6f, \"stretch_min\": %.6f, "
                  "\"stretch_mean\": %.6f, \"dihedral_histogram\": [",
                  q.num_vertices, q.num_tets, q.num_boundary_faces, q.num_unused_vertices, q.num_inverted, q.volume,
                  q.min_dihedral, q.max_dihedral, q.mean_dihedral, q.min_stretch, q.mean_stretch, q.min_stretch,
                  q.mean_stretch);
    std::string out = text;
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b)
        out += (b ? ", " : "") + std::to_string(static_cast<long long>(q.dihedral_histogram[b]));
    out += "]";
    if (edges) {
        double e[BODT_DIHEDRAL_BINS + 1];
        bodt_dihedral_bin_edges(e, BODT_DIHEDRAL_BINS + 1);
        out += ", \"dihedral_bin_edges\": [";
        for (int b = 0; b <= BODT_DIHEDRAL_BINS; ++b) out += (b ? ", " : "") + format("%g", e[b]);
        out += "]";
    }
    return out;
}

void print_histogram(const bodt_quality& q) {
    double e[BODT_DIHEDRAL_BINS + 1];
    bodt_dihedral_bin_edges(e, BODT_DIHEDRAL_BINS + 1);
    long long total = 0, top = 0;
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b) {
        const long long n = q.dihedral_histogram[b];
        total += n;
        if (n > top) top = n;
    }
    constexpr long long kWidth = 50;
    std::printf("dihedral angles (degrees): %lld = 6 x %d tets\n", total, q.num_tets);
    for (int b = 0; b < BODT_DIHEDRAL_BINS; ++b) {
        const long long n = q.dihedral_histogram[b];
        // A bin with any angle shows at least one mark.
        const long long len = top > 0 ? (n * kWidth + top - 1) / top : 0;
        std::printf("[%3g, %3g%c %10lld |%s\n", e[b], e[b + 1], b + 1 == BODT_DIHEDRAL_BINS ? ']' : ')', n,
                    std::string(static_cast<size_t>(len), '#').c_str());
    }
}

}  // namespace bodt_cli
