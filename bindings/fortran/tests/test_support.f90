! test_support.f90: checks, meshes made in code, and the C side (c_side.c)
! for test_bodt_f.
module test_support
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  use bodt
  implicit none
  private
  public :: check, check_near, check_status, check_contains, make_box, signed_volume, box_vertex, pi
  public :: c_side_constants, c_side_fill_quality, c_side_fill_step_report, c_side_fill_shape_fit, &
            c_side_fill_recovery_error, fortran_constants

  real(c_double), parameter :: pi = acos(-1.0_c_double)

  ! In the order of `constants` in c_side.c.
  integer(c_int64_t), parameter :: fortran_constants(*) = [integer(c_int64_t) :: &
    BODT_VERSION_MAJOR, BODT_VERSION_MINOR, BODT_VERSION_PATCH, BODT_MODULE_VERSION_NUMBER, &
    BODT_OK, BODT_ERR_INVALID_ARGUMENT, BODT_ERR_BAD_MESH, BODT_ERR_OUT_OF_MEMORY, BODT_ERR_WRONG_STATE, &
    BODT_ERR_NUMERIC, BODT_ERR_IO, BODT_ERR_CANCELLED, BODT_ERR_UNSUPPORTED, &
    BODT_CREATE_DEFAULT, BODT_CREATE_ACCEPT_INVERTED, BODT_CREATE_ONE_BASED, BODT_CREATE_KEEP_ORDER, &
    BODT_CREATE_FILE_BASE, &
    BODT_VERTEX_INTERIOR, BODT_VERTEX_SURFACE, BODT_VERTEX_FEATURE_LINE, BODT_VERTEX_CORNER, BODT_VERTEX_FIXED, &
    BODT_VERTEX_UNUSED, &
    BODT_DIHEDRAL_BINS, &
    BODT_MEASURE_MIN_DIHEDRAL, BODT_MEASURE_MAX_DIHEDRAL, BODT_MEASURE_STRETCH, BODT_MEASURE_VOLUME, &
    BODT_MODE_LAPLACE, BODT_MODE_ODT, BODT_MODE_BODT_BASIC, BODT_MODE_BODT, BODT_MODE_OPT_WEIGHTED, &
    BODT_MODE_PHASED_ODT, BODT_MODE_NODT, &
    BODT_PARAM_TOLERANCE, BODT_PARAM_BACKTRACK_STEPS, BODT_PARAM_MIN_STRETCH, BODT_PARAM_NEVER_WORSE, &
    BODT_PARAM_FEATURE_ANGLE, BODT_PARAM_EDGE_RATIO, BODT_PARAM_CORNER_RATIO, BODT_PARAM_OPS, &
    BODT_PARAM_KEEP_SURFACE, BODT_PARAM_BAD_ANGLE, BODT_PARAM_DELAUNAY_FLIPS, BODT_PARAM_WEIGHT_C, &
    BODT_PARAM_POOR_QUALITY, BODT_PARAM_QN_EPSILON, BODT_PARAM_QN_MAX_ITERATIONS, BODT_PARAM_QN_INITIAL_STEP, &
    BODT_PARAM_QN_INTERVAL_GROWTH, BODT_PARAM_ODT_STEP, BODT_PARAM_DENSITY_SPLIT, BODT_PARAM_DENSITY_COLLAPSE, &
    BODT_PARAM_FIT_TOLERANCE, BODT_PARAM_THREADS, BODT_PARAM_ASCENT_ANGLE, &
    BODT_OP_SMOOTH, BODT_OP_FLIP, BODT_OP_INSERT, BODT_OP_COLLAPSE, BODT_OPS_MODE_DEFAULT, &
    BODT_GEOMETRY_INTERIOR, BODT_GEOMETRY_SURFACE, BODT_GEOMETRY_SHARP_EDGE, BODT_GEOMETRY_CORNER, &
    BODT_SHAPE_NONE, BODT_SHAPE_PLANE, BODT_SHAPE_CYLINDER, BODT_SHAPE_LINE, BODT_SHAPE_ARC, BODT_SHAPE_CIRCLE, &
    BODT_FORMAT_AUTO, BODT_FORMAT_MEDIT, BODT_FORMAT_MEDIT_BINARY, BODT_FORMAT_TETGEN, BODT_FORMAT_GMSH, &
    BODT_FORMAT_GMSH_BINARY, BODT_FORMAT_GMSH22, BODT_FORMAT_GMSH22_BINARY, BODT_FORMAT_VTU, BODT_FORMAT_ABAQUS]

  interface
    function c_side_constants(values, capacity) bind(c) result(n)
      import :: c_int32_t, c_int64_t
      integer(c_int64_t), intent(out) :: values(*)
      integer(c_int32_t), value :: capacity
      integer(c_int32_t) :: n
    end function c_side_constants
    subroutine c_side_fill_quality(q) bind(c)
      import :: bodt_quality
      type(bodt_quality), intent(out) :: q
    end subroutine c_side_fill_quality
    subroutine c_side_fill_step_report(r) bind(c)
      import :: bodt_step_report
      type(bodt_step_report), intent(out) :: r
    end subroutine c_side_fill_step_report
    subroutine c_side_fill_shape_fit(f) bind(c)
      import :: bodt_shape_fit
      type(bodt_shape_fit), intent(out) :: f
    end subroutine c_side_fill_shape_fit
    subroutine c_side_fill_recovery_error(e) bind(c)
      import :: bodt_recovery_error
      type(bodt_recovery_error), intent(out) :: e
    end subroutine c_side_fill_recovery_error
  end interface

contains

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (ok) return
    write (error_unit, '(2a)') 'FAIL: ', what
    error stop 1
  end subroutine check

  subroutine check_near(got, want, tolerance, what)
    real(c_double), intent(in) :: got, want, tolerance
    character(len=*), intent(in) :: what
    if (abs(got - want) <= tolerance) return
    write (error_unit, '(3a, es25.17, a, es25.17, a, es9.2)') 'FAIL: ', what, ': ', got, ', want ', want, &
      ' within ', tolerance
    error stop 1
  end subroutine check_near

  ! ierr must be `want`; a failure must leave a message, a success none.
  subroutine check_status(ierr, want, what, mesh)
    integer(c_int), intent(in) :: ierr, want
    character(len=*), intent(in) :: what
    type(bodt_mesh_t), intent(in) :: mesh
    if (ierr /= want) then
      write (error_unit, '(3a, i0, 5a)') 'FAIL: ', what, ': status ', ierr, ' (', bodt_status_string(ierr), &
        '), want ', bodt_status_string(want), '; message: ' // bodt_mesh_last_error(mesh)
      error stop 1
    end if
    call check((ierr == BODT_OK) .eqv. (len(bodt_mesh_last_error(mesh)) == 0), &
               what // ': the message ("' // bodt_mesh_last_error(mesh) // '") does not match the status')
  end subroutine check_status

  subroutine check_contains(text, part, what)
    character(len=*), intent(in) :: text, part, what
    call check(index(text, part) > 0, what // ': "' // text // '" does not contain "' // part // '"')
  end subroutine check_contains

  ! The 1-based index of grid point (i, j, k), each in 0..n, of make_box.
  pure integer(c_int32_t) function box_vertex(n, i, j, k)
    integer, intent(in) :: n, i, j, k
    box_vertex = int(1 + i + (n + 1) * (j + (n + 1) * k), c_int32_t)
  end function box_vertex

  ! The unit cube cut into n**3 cubes of 6 positive tets each (the Kuhn
  ! split: every tet runs from a cube's lowest to its highest corner, so
  ! the cubes conform).  jitter > 0 moves each vertex by up to jitter * h
  ! along the axes on which it is not on the boundary: the box stays
  ! exactly the unit cube.  jitter < 0.2 inverts no tet (a Kuhn tet's
  ! lowest height is h / sqrt(2)); beyond, bodt_mesh_create tells.
  subroutine make_box(n, jitter, points, tets)
    integer, intent(in) :: n
    real(c_double), intent(in) :: jitter
    real(c_double), allocatable, intent(out) :: points(:, :)
    integer(c_int32_t), allocatable, intent(out) :: tets(:, :)
    integer, parameter :: perms(3, 6) = reshape([1, 2, 3, 1, 3, 2, 2, 1, 3, 2, 3, 1, 3, 1, 2, 3, 2, 1], [3, 6])
    integer(c_int64_t) :: seed
    integer :: i, j, k, p, a, t, corner(3), ijk(3)
    real(c_double) :: h
    h = 1.0_c_double / n
    allocate (points(3, (n + 1)**3), tets(4, 6 * n**3))
    seed = 12345
    do k = 0, n
      do j = 0, n
        do i = 0, n
          ijk = [i, j, k]
          p = box_vertex(n, i, j, k)
          points(:, p) = h * ijk
          do a = 1, 3
            seed = mod(seed * 1103515245_c_int64_t + 12345, 2147483648_c_int64_t)
            if (ijk(a) > 0 .and. ijk(a) < n) &
              points(a, p) = points(a, p) + jitter * h * (2 * real(seed, c_double) / 2147483648.0_c_double - 1)
          end do
        end do
      end do
    end do
    t = 0
    do k = 0, n - 1
      do j = 0, n - 1
        do i = 0, n - 1
          do p = 1, 6
            t = t + 1
            corner = [i, j, k]
            tets(1, t) = box_vertex(n, corner(1), corner(2), corner(3))
            do a = 1, 3
              corner(perms(a, p)) = corner(perms(a, p)) + 1
              tets(a + 1, t) = box_vertex(n, corner(1), corner(2), corner(3))
            end do
            if (signed_volume(points, tets(:, t)) < 0) tets(3:4, t) = tets([4, 3], t)
          end do
        end do
      end do
    end do
  end subroutine make_box

  ! Signed volume of the tet with 1-based vertex indices tet.
  pure real(c_double) function signed_volume(points, tet)
    real(c_double), intent(in) :: points(:, :)
    integer(c_int32_t), intent(in) :: tet(4)
    real(c_double) :: a(3), b(3), c(3)
    a = points(:, tet(2)) - points(:, tet(1))
    b = points(:, tet(3)) - points(:, tet(1))
    c = points(:, tet(4)) - points(:, tet(1))
    signed_volume = (a(1) * (b(2) * c(3) - b(3) * c(2)) - a(2) * (b(1) * c(3) - b(3) * c(1)) &
                     + a(3) * (b(1) * c(2) - b(2) * c(1))) / 6
  end function signed_volume

end module test_support
