// A C++17 consumer of the installed libbodt, found with find_package(bodt).
#include <bodt.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace {

struct MeshDeleter {
    void operator()(bodt_mesh* mesh) const { bodt_mesh_destroy(mesh); }
};
using MeshPtr = std::unique_ptr<bodt_mesh, MeshDeleter>;

int fail(const char* what, int status, const bodt_mesh* mesh) {
    std::fprintf(stderr, "%s: %s: %s\n", what, bodt_status_string(status), bodt_mesh_last_error(mesh));
    return 1;
}

}  // namespace

int main() {
    if (bodt_version_number() != BODT_VERSION_NUMBER) {
        std::fprintf(stderr, "header %d, library %d\n", BODT_VERSION_NUMBER, bodt_version_number());
        return 1;
    }
    // Two tets sharing a face; the interior is empty, so Laplace has nothing
    // to move, but the whole call sequence must work.
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    const std::vector<int32_t> tets = {0, 1, 2, 3, 1, 2, 3, 4};
    bodt_mesh* raw = nullptr;
    int status = bodt_mesh_create(5, xyz.data(), 2, tets.data(), 0, &raw);
    if (status != BODT_OK) return fail("bodt_mesh_create", status, nullptr);
    MeshPtr mesh(raw);

    bodt_quality q{};
    q.size = sizeof q;
    if ((status = bodt_set_mode(mesh.get(), BODT_MODE_LAPLACE)) != BODT_OK) return fail("set_mode", status, mesh.get());
    if ((status = bodt_run(mesh.get(), 5, nullptr, nullptr)) != BODT_OK) return fail("run", status, mesh.get());
    if ((status = bodt_mesh_quality(mesh.get(), &q)) != BODT_OK) return fail("quality", status, mesh.get());

    std::vector<int32_t> out(tets.size());
    if ((status = bodt_mesh_get_tets(mesh.get(), out.data(), out.size())) != BODT_OK)
        return fail("get_tets", status, mesh.get());
    if (out != tets) {
        std::fprintf(stderr, "the tets changed\n");
        return 1;
    }
    std::printf("libbodt %s via find_package: %d tets, min dihedral %.2f\n", bodt_version_string(), q.num_tets,
                q.min_dihedral);
    return q.num_tets == 2 && q.num_inverted == 0 ? 0 : 1;
}
