// Test driver for bodt_cli::write_report (tests/cli/test_report.py).
//
//   report_driver ORIGINAL IMPROVED REPORT.html
//       reads both meshes and writes the report;
//   report_driver --improve N ORIGINAL IMPROVED REPORT.html
//       reads ORIGINAL, improves a copy with N steps of B-ODT (bodt_run),
//       writes that copy to IMPROVED, then writes the report;
//   report_driver --accept-inverted ORIGINAL IMPROVED REPORT.html
//       reads both meshes with BODT_CREATE_ACCEPT_INVERTED.
// (A report with a run is `bodt report --run` or `bodt improve --report`.)
//
// Prints on stdout one JSON object with what the library says about both
// meshes (bodt_mesh_quality, the per-tet measures, vertices and tets), for
// the test to compare with the page.  Exit status 0 on success, 1 on a usage
// error, 2 on a failed library call or report.
#include "bodt.h"
#include "cli/mesh_snapshot.hpp"
#include "cli/report.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

bool ok(int status, const bodt_mesh* mesh, const char* what) {
    if (status == BODT_OK) return true;
    std::fprintf(stderr, "report_driver: %s: %s (%s)\n", what, bodt_status_string(status),
                 bodt_mesh_last_error(mesh));
    return false;
}

void print_doubles(const char* key, const std::vector<double>& v) {
    std::printf("\"%s\": [", key);
    for (size_t i = 0; i < v.size(); ++i) std::printf("%s%.17g", i ? ", " : "", v[i]);
    std::printf("]");
}

template <typename T>
void print_ints(const char* key, const T* v, size_t n) {
    std::printf("\"%s\": [", key);
    for (size_t i = 0; i < n; ++i) std::printf("%s%lld", i ? ", " : "", static_cast<long long>(v[i]));
    std::printf("]");
}

bool print_mesh(const char* key, const bodt_mesh* m) {
    int32_t nv = 0, nt = 0, nf = 0;
    bodt_quality q{};
    q.size = sizeof q;
    if (!ok(bodt_mesh_get_counts(m, &nv, &nt, &nf), m, "bodt_mesh_get_counts") ||
        !ok(bodt_mesh_quality(m, &q), m, "bodt_mesh_quality"))
        return false;
    const size_t n = static_cast<size_t>(nt);
    std::vector<double> mind(n), maxd(n), stretch(n), volume(n), xyz(3 * static_cast<size_t>(nv));
    std::vector<int32_t> tets(4 * n);
    if (!ok(bodt_mesh_tet_quality(m, BODT_MEASURE_MIN_DIHEDRAL, mind.data(), n), m, "min") ||
        !ok(bodt_mesh_tet_quality(m, BODT_MEASURE_MAX_DIHEDRAL, maxd.data(), n), m, "max") ||
        !ok(bodt_mesh_tet_quality(m, BODT_MEASURE_STRETCH, stretch.data(), n), m, "stretch") ||
        !ok(bodt_mesh_tet_quality(m, BODT_MEASURE_VOLUME, volume.data(), n), m, "volume") ||
        !ok(bodt_mesh_get_vertices(m, xyz.data(), xyz.size()), m, "vertices") ||
        !ok(bodt_mesh_get_tets(m, tets.data(), tets.size()), m, "tets"))
        return false;
    std::printf("\"%s\": {\"vertices\": %d, \"tets\": %d, \"boundary_faces\": %d, "
                "\"num_inverted\": %d, \"num_unused_vertices\": %d, \"min_dihedral\": %.17g, "
                "\"max_dihedral\": %.17g, \"mean_dihedral\": %.17g, \"min_stretch\": %.17g, "
                "\"mean_stretch\": %.17g, \"volume\": %.17g, ",
                key, q.num_vertices, q.num_tets, q.num_boundary_faces, q.num_inverted,
                q.num_unused_vertices, q.min_dihedral, q.max_dihedral, q.mean_dihedral,
                q.min_stretch, q.mean_stretch, q.volume);
    print_ints("dihedral_histogram", q.dihedral_histogram, BODT_DIHEDRAL_BINS);
    std::printf(", ");
    print_doubles("tet_min_dihedral", mind);
    std::printf(", ");
    print_doubles("tet_max_dihedral", maxd);
    std::printf(", ");
    print_doubles("tet_stretch", stretch);
    std::printf(", ");
    print_doubles("tet_volume", volume);
    std::printf(", ");
    print_doubles("xyz", xyz);
    std::printf(", ");
    print_ints("tets_indices", tets.data(), tets.size());
    std::printf("}");
    return true;
}

int usage() {
    std::fprintf(stderr,
                 "usage: report_driver [--improve N | --accept-inverted] ORIGINAL IMPROVED REPORT.html\n");
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    int improve = -1;
    uint32_t flags = BODT_CREATE_DEFAULT;
    if (!args.empty() && args[0] == "--accept-inverted") {
        flags = BODT_CREATE_ACCEPT_INVERTED;
        args.erase(args.begin());
    } else if (!args.empty() && args[0] == "--improve") {
        if (args.size() < 2) return usage();
        improve = std::atoi(args[1].c_str());
        if (improve < 1) return usage();
        args.erase(args.begin(), args.begin() + 2);
    }
    if (args.size() != 3) return usage();
    const std::string& original_path = args[0];
    const std::string& improved_path = args[1];
    const std::string& report_path = args[2];

    bodt_mesh* original = nullptr;
    bodt_mesh* improved = nullptr;
    int rc = 2;
    if (!ok(bodt_mesh_read_ex(original_path.c_str(), flags, &original), nullptr, "bodt_mesh_read"))
        goto done;
    if (improve > 0) {
        if (!ok(bodt_mesh_read(original_path.c_str(), &improved), nullptr, "bodt_mesh_read") ||
            !ok(bodt_set_mode(improved, BODT_MODE_BODT), improved, "bodt_set_mode") ||
            !ok(bodt_run(improved, improve, nullptr, nullptr), improved, "bodt_run") ||
            !ok(bodt_mesh_write(improved, improved_path.c_str()), improved, "bodt_mesh_write"))
            goto done;
    } else if (!ok(bodt_mesh_read_ex(improved_path.c_str(), flags, &improved), nullptr,
                   "bodt_mesh_read")) {
        goto done;
    }
    {
        std::string error;
        bodt_cli::MeshSnapshot a, b;
        if (!bodt_cli::take_snapshot(original, a, error) || !bodt_cli::take_snapshot(improved, b, error) ||
            !bodt_cli::write_report(a, b, original_path, improved_path, nullptr, report_path, error)) {
            std::fprintf(stderr, "report_driver: %s\n", error.c_str());
            goto done;
        }
    }
    std::printf("{\"version\": \"%s\", ", bodt_version_string());
    if (!print_mesh("original", original)) goto done;
    std::printf(", ");
    if (!print_mesh("improved", improved)) goto done;
    std::printf("}\n");
    rc = 0;
done:
    bodt_mesh_destroy(original);
    bodt_mesh_destroy(improved);
    return rc;
}
