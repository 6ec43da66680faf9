! Built with $(pkg-config --cflags --libs bodt-fortran) against the installed
! tree: the installed bodt.mod, libbodt_fortran.so and libbodt.so.
program fortran_consumer
  use, intrinsic :: iso_c_binding, only: c_double, c_int, c_int32_t
  use bodt
  implicit none
  real(c_double), parameter :: points(3, 5) = reshape([real(c_double) :: &
    0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.3_c_double, 0.3_c_double, 0.3_c_double], [3, 5])
  integer(c_int32_t), parameter :: tets(4, 4) = reshape([5, 2, 3, 4, 1, 5, 3, 4, 1, 2, 5, 4, 1, 2, 3, 5], [4, 4])
  type(bodt_mesh_t) :: mesh
  type(bodt_quality) :: q
  integer(c_int) :: ierr

  if (bodt_version_number() /= BODT_MODULE_VERSION_NUMBER) error stop 'module and library versions differ'
  call bodt_mesh_create(points, tets + 1, mesh, ierr=ierr)  ! vertex 6 of 5
  if (ierr /= BODT_ERR_BAD_MESH) error stop 'bad mesh not refused'
  if (index(bodt_mesh_last_error(), 'vertex 6') == 0) error stop 'no message for the refused mesh'
  call bodt_mesh_create(points, tets, mesh)
  call bodt_mesh_quality(mesh, q)
  print '(3a, i0, a, i0, a, i0, a)', 'libbodt ', bodt_version_string(), ' from Fortran: ', q%num_vertices, &
    ' vertices, ', q%num_tets, ' tets, ', q%num_boundary_faces, ' boundary faces'
  call bodt_mesh_destroy(mesh)
end program fortran_consumer
