! test_error_stop.f90: a call without ierr that fails must print
! "bodt: <function>: <status>: <message>" and stop the program (CTest
! checks the output; "not reached" fails the test).
program test_error_stop
  use, intrinsic :: iso_c_binding, only: c_double, c_int32_t
  use bodt
  implicit none
  real(c_double), parameter :: points(3, 4) = reshape([real(c_double) :: 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 4])
  type(bodt_mesh_t) :: mesh
  call bodt_mesh_create(points, reshape([1_c_int32_t, 2_c_int32_t, 3_c_int32_t, 4_c_int32_t], [4, 1]), mesh)
  call bodt_set_mode(mesh, 99)
  print '(a)', 'not reached'
end program test_error_stop
