/* Built with $(pkg-config --cflags --libs bodt) against the installed tree. */
#include <bodt.h>
#include <stdio.h>
#include <string.h>

int main(void) {
    const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const int32_t tet[] = {1, 2, 3, 4}; /* Fortran-style, 1-based */
    const int32_t bad[] = {1, 2, 3, 5};
    bodt_mesh *mesh = NULL;
    int32_t nverts = 0, ntets = 0, nfaces = 0;
    int status;

    if (bodt_version_number() != BODT_VERSION_NUMBER) {
        fprintf(stderr, "header %d, library %d\n", BODT_VERSION_NUMBER, bodt_version_number());
        return 1;
    }
    status = bodt_mesh_create(4, xyz, 1, bad, 1, &mesh);
    if (status != BODT_ERR_BAD_MESH || mesh != NULL || strlen(bodt_mesh_last_error(NULL)) == 0) {
        fprintf(stderr, "a bad mesh was not refused: %s\n", bodt_status_string(status));
        return 1;
    }
    status = bodt_mesh_create(4, xyz, 1, tet, 1, &mesh);
    if (status == BODT_OK) status = bodt_mesh_get_counts(mesh, &nverts, &ntets, &nfaces);
    if (status != BODT_OK) {
        fprintf(stderr, "%s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh));
        bodt_mesh_destroy(mesh);
        return 1;
    }
    printf("libbodt %s: %d vertices, %d tet, %d boundary faces\n", bodt_version_string(), nverts, ntets,
           nfaces);
    bodt_mesh_destroy(mesh);
    return nverts == 4 && ntets == 1 && nfaces == 4 ? 0 : 1;
}
