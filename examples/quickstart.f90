! quickstart.f90: improve a small tet mesh with libbodt's Fortran module (B-ODT).
program quickstart
  use, intrinsic :: iso_c_binding, only: c_double, c_int32_t
  use bodt
  implicit none
  ! An octahedron cut into 8 tets around vertex 7, which sits off-centre.
  real(c_double), parameter :: points(3, 7) = reshape([real(c_double) :: 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, &
      0, 0, 1, 0, 0, -1, 0.45_c_double, 0.3_c_double, 0.2_c_double], [3, 7])
  integer(c_int32_t), parameter :: tets(4, 8) = reshape([7, 1, 3, 5, 7, 3, 2, 5, 7, 4, 1, 5, 7, 2, 4, 5, &
      7, 3, 1, 6, 7, 2, 3, 6, 7, 1, 4, 6, 7, 4, 2, 6], [4, 8])
  type(bodt_mesh_t) :: mesh
  type(bodt_quality) :: before, after
  call bodt_mesh_create(points, tets, mesh)  ! 1-based; a failing call stops with a message
  call bodt_mesh_quality(mesh, before)
  call bodt_run(mesh, 20)  ! B-ODT, the default mode
  call bodt_mesh_quality(mesh, after)
  print '(a, f0.2, a, f0.2, a)', 'min dihedral: ', before%min_dihedral, ' -> ', after%min_dihedral, ' degrees'
  call bodt_mesh_destroy(mesh)
end program quickstart
