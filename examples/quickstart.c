/* quickstart.c: improve a small tet mesh with libbodt's C API (B-ODT). */
#include <stdio.h>
#include "bodt.h"

int main(void) {
    /* An octahedron cut into 8 tets around vertex 6, which sits off-centre. */
    const double xyz[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0.45, 0.3, 0.2};
    const int32_t tets[] = {6, 0, 2, 4, 6, 2, 1, 4, 6, 3, 0, 4, 6, 1, 3, 4,
                            6, 2, 0, 5, 6, 1, 2, 5, 6, 0, 3, 5, 6, 3, 1, 5};
    bodt_quality before = {.size = sizeof(bodt_quality)}, after = before;
    bodt_mesh *mesh = NULL;
    int status = bodt_mesh_create(7, xyz, 8, tets, 0, &mesh);
    if (status == BODT_OK) status = bodt_mesh_quality(mesh, &before);
    if (status == BODT_OK) status = bodt_run(mesh, 20, NULL, NULL); /* B-ODT, the default mode */
    if (status == BODT_OK) status = bodt_mesh_quality(mesh, &after);
    if (status != BODT_OK)
        fprintf(stderr, "%s: %s\n", bodt_status_string(status), bodt_mesh_last_error(mesh));
    else
        printf("min dihedral: %.2f -> %.2f degrees\n", before.min_dihedral, after.min_dihedral);
    bodt_mesh_destroy(mesh);
    return status != BODT_OK;
}
