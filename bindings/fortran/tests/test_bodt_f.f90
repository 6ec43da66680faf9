! test_bodt_f.f90: the Fortran module bodt against libbodt.  Every check
! compares with values computed here; the first failure stops the program
! (error stop, nonzero exit).  Files go to the working directory (the
! build tree).
module callbacks
  use, intrinsic :: iso_c_binding
  use bodt, only: bodt_step_report
  implicit none
  private
  public :: stop_after_two
  integer(c_int32_t), public :: last_step = 0
contains
  ! Counts its calls in user_data (an integer(c_int)) and stops at the second.
  function stop_after_two(report, user_data) bind(c) result(stop)
    type(bodt_step_report), intent(in) :: report
    type(c_ptr), value :: user_data
    integer(c_int) :: stop
    integer(c_int), pointer :: calls
    call c_f_pointer(user_data, calls)
    calls = calls + 1
    last_step = report%step
    stop = merge(1, 0, calls >= 2)
  end function stop_after_two
end module callbacks

program test_bodt_f
  use, intrinsic :: iso_c_binding
  use bodt
  use test_support
  use callbacks
  implicit none

  call test_constants_and_structs()
  call test_regular_tet()
  call test_index_bases()
  call test_getters()
  call test_modes_and_params()
  call test_step_and_run()
  call test_bodt_improves()
  call test_parents_and_origins()
  call test_bad_input()
  call test_files()
  call test_inverted_input()
  call test_geometry()
  call test_recovery_error()
  print '(a)', 'test_bodt_f: all checks passed'

contains

  ! The module's constants and structs are those of bodt.h (c_side.c).
  subroutine test_constants_and_structs()
    integer(c_int64_t) :: c_values(200)
    integer(c_int32_t) :: n, i
    type(bodt_quality) :: q
    type(bodt_step_report) :: r
    type(bodt_shape_fit) :: f
    type(bodt_recovery_error) :: e
    character(len=32) :: version
    character(len=:), allocatable :: ok_name

    n = c_side_constants(c_values, size(c_values))
    call check(n == size(fortran_constants), 'as many constants in c_side.c as in test_support.f90')
    do i = 1, n
      if (c_values(i) /= fortran_constants(i)) then
        write (version, '(i0)') i
        call check(.false., 'constant ' // trim(version) // ' of the list differs between C and Fortran')
      end if
    end do
    call check(bodt_version_number() == BODT_MODULE_VERSION_NUMBER, 'library version = module version')
    write (version, '(i0, ".", i0, ".", i0)') BODT_VERSION_MAJOR, BODT_VERSION_MINOR, BODT_VERSION_PATCH
    call check(bodt_version_string() == trim(version), 'version string ' // bodt_version_string())
    ok_name = bodt_status_string(BODT_OK)
    call check(ok_name /= '', 'status string of BODT_OK')
    call check(bodt_status_string(BODT_ERR_IO) /= ok_name, 'status strings differ')

    ! C writes field k as k: each Fortran field must read its own number.
    call c_side_fill_quality(q)
    call check(q%size == c_sizeof(q), 'sizeof(bodt_quality)')
    call check(all([q%num_vertices, q%num_tets, q%num_boundary_faces, q%num_unused_vertices, q%num_inverted, &
                    q%reserved0] == [1, 2, 3, 4, 5, 6]), 'bodt_quality int fields')
    call check(all(nint([q%min_dihedral, q%max_dihedral, q%mean_dihedral, q%min_stretch, q%mean_stretch, &
                         q%volume]) == [7, 8, 9, 10, 11, 12]), 'bodt_quality double fields')
    call check(all(q%dihedral_histogram == [(12 + i, i = 1, BODT_DIHEDRAL_BINS)]), 'bodt_quality histogram')
    call c_side_fill_step_report(r)
    call check(r%size == c_sizeof(r), 'sizeof(bodt_step_report)')
    call check(all([r%step, r%vertices_moved, r%moves_rejected, r%moves_shortened, r%not_positive_definite, &
                    r%reserved0, r%flips, r%vertices_inserted, r%edges_collapsed, r%reserved1] &
                   == [1, 2, 3, 4, 5, 6, 11, 12, 13, 14]), 'bodt_step_report int fields')
    call check(all(nint([r%max_move, r%min_dihedral, r%max_dihedral, r%min_stretch]) == [7, 8, 9, 10]), &
               'bodt_step_report double fields')
    call c_side_fill_shape_fit(f)
    call check(f%size == c_sizeof(f), 'sizeof(bodt_shape_fit)')
    call check(f%shape == 1 .and. f%reserved0 == 2, 'bodt_shape_fit int fields')
    call check(all(nint([f%point, f%axis, f%radius, f%max_error, f%acceptable_error]) == [(i, i = 3, 11)]), &
               'bodt_shape_fit double fields')
    call c_side_fill_recovery_error(e)
    call check(e%size == c_sizeof(e), 'sizeof(bodt_recovery_error)')
    call check(all(nint([e%density_mean, e%density_max, e%geometric_mean, e%geometric_max]) == [1, 2, 4, 5]) &
               .and. e%density_edges == 3 .and. e%geometric_edges == 6, 'bodt_recovery_error fields')
  end subroutine test_constants_and_structs

  ! A regular tet: every dihedral angle acos(1/3), stretch 1, its volume.
  subroutine test_regular_tet()
    real(c_double), parameter :: points(3, 4) = reshape([real(c_double) :: &
      1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1], [3, 4])
    integer(c_int32_t), parameter :: tets(4, 1) = reshape([1, 2, 4, 3], [4, 1])
    type(bodt_mesh_t) :: mesh
    type(bodt_quality) :: q
    real(c_double), allocatable :: edges(:), values(:)
    real(c_double) :: angle, volume
    integer :: bin

    angle = acos(1.0_c_double / 3) * 180 / pi
    volume = signed_volume(points, tets(:, 1))
    call check_near(volume, 8.0_c_double / 3, 1e-15_c_double, 'the test tet is positive')
    call bodt_mesh_create(points, tets, mesh)
    call bodt_mesh_quality(mesh, q)
    call check(q%num_vertices == 4 .and. q%num_tets == 1 .and. q%num_boundary_faces == 4 .and. &
               q%num_unused_vertices == 0 .and. q%num_inverted == 0, 'regular tet counts')
    call check_near(q%min_dihedral, angle, 1e-12_c_double, 'regular tet min dihedral')
    call check_near(q%max_dihedral, angle, 1e-12_c_double, 'regular tet max dihedral')
    call check_near(q%mean_dihedral, angle, 1e-12_c_double, 'regular tet mean dihedral')
    call check_near(q%min_stretch, 1.0_c_double, 1e-12_c_double, 'regular tet stretch')
    call check_near(q%volume, volume, 1e-14_c_double, 'regular tet volume')
    call bodt_dihedral_bin_edges(edges)
    call check(size(edges) == BODT_DIHEDRAL_BINS + 1, 'bin edges count')
    call check(nint(edges(1)) == 0 .and. nint(edges(size(edges))) == 180, 'bin edges from 0 to 180')
    bin = count(edges(:BODT_DIHEDRAL_BINS) <= angle)
    call check(q%dihedral_histogram(bin) == 6 .and. sum(q%dihedral_histogram) == 6, &
               'the six angles in the bin of 70.5 degrees')
    call bodt_mesh_tet_quality(mesh, BODT_MEASURE_MIN_DIHEDRAL, values)
    call check(size(values) == 1, 'tet_quality: one value per tet')
    call check_near(values(1), angle, 1e-12_c_double, 'tet_quality min dihedral')
    call bodt_mesh_tet_quality(mesh, BODT_MEASURE_VOLUME, values)
    call check_near(values(1), volume, 1e-14_c_double, 'tet_quality volume')
    call bodt_mesh_tet_quality(mesh, BODT_MEASURE_STRETCH, values)
    call check_near(values(1), 1.0_c_double, 1e-12_c_double, 'tet_quality stretch')
    call bodt_mesh_destroy(mesh)
    call check(.not. c_associated(mesh%ptr), 'bodt_mesh_destroy nulls the handle')
    call bodt_mesh_destroy(mesh)  ! a null handle is ignored
  end subroutine test_regular_tet

  ! 1-based (the default) and 0-based arrays give the same mesh, each
  ! handle answering in its own base.
  subroutine test_index_bases()
    real(c_double), allocatable :: points(:, :), got_points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :), got(:, :), faces1(:, :), faces0(:, :)
    type(bodt_mesh_t) :: one, zero
    integer(c_int32_t) :: nverts, ntets, nfaces
    integer(c_int) :: ierr, base

    call make_box(1, 0.0_c_double, points, tets)
    call bodt_mesh_create(points, tets, one, ierr=ierr)
    call check_status(ierr, BODT_OK, 'create 1-based', one)
    call bodt_mesh_create(points, tets - 1, zero, index_base=0, ierr=ierr)
    call check_status(ierr, BODT_OK, 'create 0-based', zero)
    call bodt_mesh_get_index_base(one, base)
    call check(base == 1, 'index base 1 by default')
    call bodt_mesh_get_index_base(zero, base, ierr)
    call check_status(ierr, BODT_OK, 'get_index_base', zero)
    call check(base == 0, 'index base 0 with index_base=0')
    call bodt_mesh_get_counts(one, nverts, ntets, nfaces)
    call check(nverts == 8 .and. ntets == 6 .and. nfaces == 12, 'counts of a cube')
    call bodt_mesh_get_counts(zero, nboundary_faces=nfaces)
    call check(nfaces == 12, 'counts: only the asked one')
    call bodt_mesh_get_vertices(one, got_points)
    call check(all(shape(got_points) == [3, 8]) .and. all(abs(got_points - points) <= 0), 'vertices round trip')
    call bodt_mesh_get_tets(one, got)
    call check(all(got == tets), 'tets round trip, 1-based')
    call bodt_mesh_get_tets(zero, got)
    call check(all(got == tets - 1), 'tets round trip, 0-based')
    call bodt_mesh_get_boundary_faces(one, faces1)
    call bodt_mesh_get_boundary_faces(zero, faces0)
    call check(all(shape(faces1) == [3, 12]) .and. minval(faces1) == 1 .and. maxval(faces1) == 8, &
               'boundary faces 1-based')
    call check(all(faces0 == faces1 - 1), 'boundary faces 0-based')
    call bodt_mesh_destroy(one)
    call bodt_mesh_destroy(zero)
  end subroutine test_index_bases

  ! Regions, face markers, fixed vertices, feature edges with their refs,
  ! corners, vertex refs and vertex classes set and read back, 1-based.
  subroutine test_getters()
    integer, parameter :: n = 2
    real(c_double), allocatable :: points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :), regions(:), got(:), faces(:, :), again(:, :), markers(:), &
                                       fixed(:), edges(:, :), refs(:), is_corner(:), vertex_refs(:), classes(:)
    type(bodt_mesh_t) :: mesh
    integer(c_int32_t) :: t, v, nfaces, centre, corner, face_centre, edge_middle
    integer(c_int) :: ierr

    call make_box(n, 0.0_c_double, points, tets)
    call bodt_mesh_create(points, tets, mesh)
    ! region 1 for x < 1/2, 2 beyond: 2 n**2 interface triangles
    allocate (regions(size(tets, 2)))
    do t = 1, size(tets, 2)
      regions(t) = merge(1, 2, sum(points(1, tets(:, t))) < 2)
    end do
    call bodt_mesh_set_regions(mesh, regions)
    call bodt_mesh_get_regions(mesh, got)
    call check(all(got == regions), 'regions round trip')
    call bodt_mesh_get_counts(mesh, nboundary_faces=nfaces)
    call check(nfaces == 6 * 2 * n**2 + 2 * n**2, 'boundary faces: the box and the interface')

    call bodt_mesh_get_boundary_faces(mesh, faces, markers)
    call check(all(markers == 0), 'no markers yet')
    call bodt_mesh_set_boundary_faces(mesh, faces(:, 2:4), [7, 8, 9])
    call bodt_mesh_get_boundary_faces(mesh, again, markers)
    call check(all(again == faces), 'marking keeps the face list')
    call check(all(markers(2:4) == [7, 8, 9]) .and. count(markers /= 0) == 3, 'markers round trip')
    call bodt_mesh_set_boundary_faces(mesh, faces(:, 5:5))
    call bodt_mesh_get_boundary_faces(mesh, markers=markers)
    call check(markers(5) == 1 .and. count(markers /= 0) == 1, 'faces without markers get 1')

    centre = box_vertex(n, 1, 1, 1)
    call bodt_mesh_set_fixed_vertices(mesh, [1, centre])
    call bodt_mesh_get_fixed_vertices(mesh, fixed)
    call check(size(fixed) == (n + 1)**3 .and. fixed(1) == 1 .and. fixed(centre) == 1 .and. sum(fixed) == 2, &
               'fixed vertices round trip')

    ! two box edges along x and y from vertex 1, given unsorted
    call bodt_mesh_set_feature_edges(mesh, reshape([box_vertex(n, 1, 0, 0), 1, 1, box_vertex(n, 0, 1, 0)], [2, 2]))
    call bodt_mesh_get_feature_edges(mesh, edges)
    call check(all(shape(edges) == [2, 2]), 'two feature edges')
    call check(all(edges == reshape([1, box_vertex(n, 1, 0, 0), 1, box_vertex(n, 0, 1, 0)], [2, 2])), &
               'feature edges sorted')
    call bodt_mesh_get_feature_edges_ex(mesh, edges, refs)
    call check(all(shape(edges) == [2, 2]) .and. all(refs == 0), 'feature edges set without refs have ref 0')

    ! the same edges with refs: each ref stays with its edge through the sort
    call bodt_mesh_set_feature_edges_ex(mesh, reshape([1, box_vertex(n, 0, 1, 0), box_vertex(n, 1, 0, 0), 1], &
                                                      [2, 2]), [6, 5], ierr)
    call check_status(ierr, BODT_OK, 'feature edges with refs', mesh)
    call bodt_mesh_get_feature_edges_ex(mesh, edges, refs)
    call check(all(edges == reshape([1, box_vertex(n, 1, 0, 0), 1, box_vertex(n, 0, 1, 0)], [2, 2])), &
               'feature edges with refs sorted')
    call check(size(refs) == 2 .and. all(refs == [5, 6]), 'feature edge refs round trip')
    call bodt_mesh_get_feature_edges_ex(mesh, again)
    call check(all(again == edges), 'feature edges without asking for their refs')
    call bodt_mesh_get_feature_edges(mesh, again)
    call check(all(again == edges), 'feature edges set with refs, read without')

    ! a corner in the middle of a box edge (a feature-line vertex otherwise)
    edge_middle = box_vertex(n, 0, n, 1)
    call bodt_mesh_get_corners(mesh, is_corner)
    call check(size(is_corner) == (n + 1)**3 .and. all(is_corner == 0), 'no corners yet')
    call bodt_mesh_set_corners(mesh, [edge_middle])
    call bodt_mesh_get_corners(mesh, is_corner)
    call check(is_corner(edge_middle) == 1 .and. sum(is_corner) == 1, 'corners round trip')

    call bodt_mesh_get_vertex_refs(mesh, vertex_refs)
    call check(size(vertex_refs) == (n + 1)**3 .and. all(vertex_refs == 0), 'vertex refs 0 by default')
    call bodt_mesh_set_vertex_refs(mesh, [(mod(v, 4) + 10, v = 1, (n + 1)**3)])
    call bodt_mesh_get_vertex_refs(mesh, vertex_refs)
    call check(all(vertex_refs == [(mod(v, 4) + 10, v = 1, (n + 1)**3)]), 'vertex refs round trip')

    corner = box_vertex(n, n, 0, 0)
    face_centre = box_vertex(n, 0, 1, 1)
    call bodt_mesh_get_vertex_classes(mesh, classes)
    call check(size(classes) == (n + 1)**3, 'a class per vertex')
    call check(classes(1) == BODT_VERTEX_FIXED .and. classes(centre) == BODT_VERTEX_FIXED, 'fixed vertex class')
    call check(classes(corner) == BODT_VERTEX_CORNER, 'box corner class (B-ODT)')
    call check(classes(edge_middle) == BODT_VERTEX_CORNER, 'the caller''s corner class (B-ODT)')
    call check(classes(face_centre) == BODT_VERTEX_SURFACE, 'face centre class')
    call bodt_set_mode(mesh, BODT_MODE_ODT, ierr)
    call check_status(ierr, BODT_OK, 'set ODT', mesh)
    call bodt_mesh_get_vertex_classes(mesh, classes)
    call check(classes(corner) == BODT_VERTEX_SURFACE, 'box corner class (ODT: no corners)')
    call check(classes(edge_middle) == BODT_VERTEX_CORNER, 'the caller''s corner class (ODT)')
    call bodt_mesh_destroy(mesh)
  end subroutine test_getters

  subroutine test_modes_and_params()
    real(c_double), allocatable :: points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :)
    type(bodt_mesh_t) :: mesh
    integer(c_int) :: mode, ierr
    integer(c_int32_t) :: ivalue
    real(c_double) :: dvalue

    call make_box(1, 0.0_c_double, points, tets)
    call bodt_mesh_create(points, tets, mesh)
    call bodt_get_mode(mesh, mode)
    call check(mode == BODT_MODE_BODT, 'default mode B-ODT')
    call bodt_set_mode(mesh, BODT_MODE_LAPLACE)
    call bodt_get_mode(mesh, mode)
    call check(mode == BODT_MODE_LAPLACE, 'mode set')
    call bodt_set_mode(mesh, 99, ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'unknown mode refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), '99', 'unknown mode message')
    call bodt_get_mode(mesh, mode, ierr)
    call check_status(ierr, BODT_OK, 'a success clears the message', mesh)
    call check(mode == BODT_MODE_LAPLACE, 'a refused mode changes nothing')

    call bodt_get_param_int(mesh, BODT_PARAM_BACKTRACK_STEPS, ivalue)
    call check(ivalue == 4, 'default backtrack steps')
    call bodt_set_param_int(mesh, BODT_PARAM_BACKTRACK_STEPS, 6)
    call bodt_get_param_int(mesh, BODT_PARAM_BACKTRACK_STEPS, ivalue)
    call check(ivalue == 6, 'int param set')
    call bodt_get_param_double(mesh, BODT_PARAM_MIN_STRETCH, dvalue)
    call check_near(dvalue, 1e-3_c_double, 0.0_c_double, 'default min stretch')
    call bodt_set_param_double(mesh, BODT_PARAM_MIN_STRETCH, 2e-3_c_double)
    call bodt_get_param_double(mesh, BODT_PARAM_MIN_STRETCH, dvalue)
    call check_near(dvalue, 2e-3_c_double, 0.0_c_double, 'double param set')

    call bodt_set_param_int(mesh, 999, 1, ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'unknown key refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), '999', 'unknown key message')
    call bodt_set_param_int(mesh, BODT_PARAM_MIN_STRETCH, 1, ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'int setter on a double key refused', mesh)
    call bodt_set_param_double(mesh, BODT_PARAM_QN_EPSILON, 2.0_c_double, ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'out-of-range value refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'must be in', 'out-of-range message')
    call bodt_get_param_double(mesh, BODT_PARAM_QN_EPSILON, dvalue, ierr)
    call check_status(ierr, BODT_OK, 'get after a refused set', mesh)
    call check_near(dvalue, 1e-3_c_double, 0.0_c_double, 'a refused value changes nothing')
    call bodt_mesh_destroy(mesh)
  end subroutine test_modes_and_params

  subroutine test_step_and_run()
    real(c_double), allocatable :: points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :)
    type(bodt_mesh_t) :: mesh
    type(bodt_step_report) :: report
    type(bodt_quality) :: q
    integer(c_int), target :: calls
    integer(c_int) :: ierr

    call make_box(3, 0.15_c_double, points, tets)
    call bodt_mesh_create(points, tets, mesh)
    call bodt_step(mesh, report)
    call bodt_mesh_quality(mesh, q)
    call check(report%size == c_sizeof(report) .and. report%step == 1, 'first step report')
    call check(report%vertices_moved > 0 .and. report%max_move > 0, 'the first step moves vertices')
    call check_near(report%min_dihedral, q%min_dihedral, 1e-12_c_double, 'report min dihedral = quality')
    call check_near(report%min_stretch, q%min_stretch, 1e-12_c_double, 'report min stretch = quality')
    call bodt_step(mesh)
    call bodt_step(mesh, report)
    call check(report%step == 3, 'steps counted on the handle')

    calls = 0
    call bodt_run(mesh, 50, stop_after_two, c_loc(calls), ierr)
    call check_status(ierr, BODT_ERR_CANCELLED, 'the callback cancels bodt_run', mesh)
    call check(calls == 2 .and. last_step == 5, 'two callbacks, after steps 4 and 5')
    call bodt_mesh_get_counts(mesh, ierr=ierr)
    call check_status(ierr, BODT_OK, 'the mesh is usable after a cancel', mesh)
    call bodt_mesh_destroy(mesh)
  end subroutine test_step_and_run

  ! B-ODT raises the worst angle of a jittered box and keeps its volume.
  subroutine test_bodt_improves()
    real(c_double), allocatable :: points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :)
    type(bodt_mesh_t) :: mesh
    type(bodt_quality) :: before, after

    call make_box(3, 0.15_c_double, points, tets)
    call bodt_mesh_create(points, tets, mesh)
    call bodt_mesh_quality(mesh, before)
    call check_near(before%volume, 1.0_c_double, 1e-12_c_double, 'the jittered box has volume 1')
    call bodt_run(mesh, 30)
    call bodt_mesh_quality(mesh, after)
    print '(a, f0.3, a, f0.3)', 'B-ODT on a jittered box: min dihedral ', before%min_dihedral, ' -> ', &
      after%min_dihedral
    call check(after%min_dihedral > before%min_dihedral + 1, 'B-ODT raises the min dihedral')
    call check(after%num_inverted == 0, 'no inverted tet')
    call check_near(after%volume, before%volume, 1e-12_c_double * before%volume, 'B-ODT keeps the volume')
    call bodt_mesh_destroy(mesh)
  end subroutine test_bodt_improves

  ! Input vertices and tets are their own parents and origins; vertices
  ! made by insertion interpolate input vertices.
  subroutine test_parents_and_origins()
    real(c_double), allocatable :: points(:, :), weights(:)
    integer(c_int32_t), allocatable :: tets(:, :), parents(:), origins(:), refs(:)
    integer(c_int64_t), allocatable :: offsets(:)
    integer(c_int64_t) :: count
    type(bodt_mesh_t) :: mesh
    integer(c_int32_t) :: nverts, ntets, nv0, nt0, v
    integer(c_int64_t) :: first, last

    call make_box(4, 0.35_c_double, points, tets)
    nv0 = size(points, 2)
    nt0 = size(tets, 2)
    call bodt_mesh_create(points, tets, mesh)
    call bodt_mesh_get_parent_count(mesh, count)
    call check(count == nv0, 'parent count of a fresh mesh')
    call bodt_mesh_get_vertex_parents(mesh, offsets, parents, weights)
    call check(all(offsets == [(int(v, c_int64_t), v = 0, nv0)]), 'offsets of a fresh mesh')
    call check(all(parents == [(v, v = 1, nv0)]) .and. all(abs(weights - 1) <= 0), 'own parents, weight 1')
    call bodt_mesh_get_tet_origins(mesh, origins)
    call check(all(origins == [(v, v = 1, nt0)]), 'own origins')

    ! a hard jitter and insertion only (no smoothing first): vertices are made
    call bodt_mesh_set_vertex_refs(mesh, [(7_c_int32_t, v = 1, nv0)])
    call bodt_set_param_int(mesh, BODT_PARAM_OPS, BODT_OP_INSERT)
    call bodt_run(mesh, 5)
    call bodt_mesh_get_counts(mesh, nverts, ntets)
    call check(nverts > nv0 .and. ntets > nt0, 'insertion made vertices and tets')
    call bodt_mesh_get_vertex_refs(mesh, refs)
    call check(size(refs) == nverts .and. all(refs(:nv0) == 7), 'input vertices keep their refs')
    call check(all(refs(nv0 + 1:) == 7 .or. refs(nv0 + 1:) == 0), 'made vertices: their parents'' ref or 0')
    call bodt_mesh_get_vertex_parents(mesh, offsets, parents, weights)
    call check(size(offsets) == nverts + 1 .and. offsets(1) == 0 .and. offsets(nverts + 1) == size(parents), &
               'offsets after insertion')
    do v = 1, nverts
      first = offsets(v) + 1
      last = offsets(v + 1)
      if (v <= nv0) then
        call check(last == first .and. parents(first) == v, 'an input vertex is its own parent')
      else
        call check(last >= first, 'a made vertex has parents')
        call check(all(parents(first:last) >= 1 .and. parents(first:last) <= nv0), 'parents are input vertices')
        call check_near(sum(weights(first:last)), 1.0_c_double, 1e-12_c_double, 'parent weights sum to 1')
      end if
    end do
    call bodt_mesh_get_tet_origins(mesh, origins)
    call check(size(origins) == ntets .and. all(origins >= 1 .and. origins <= nt0), 'origins are input tets')
    call bodt_mesh_destroy(mesh)
  end subroutine test_parents_and_origins

  ! Refused input: the status, a message in the caller's numbering, and
  ! nothing changed.
  subroutine test_bad_input()
    real(c_double), allocatable :: points(:, :)
    real(c_double), allocatable :: values(:)
    integer(c_int32_t), allocatable :: tets(:, :), bad(:, :), regions(:), is_corner(:)
    type(bodt_mesh_t) :: mesh
    integer(c_int) :: ierr, mode

    call make_box(1, 0.0_c_double, points, tets)
    bad = tets
    bad(3, 2) = 9
    call bodt_mesh_create(points, bad, mesh, ierr=ierr)
    call check_status(ierr, BODT_ERR_BAD_MESH, 'out-of-range vertex', mesh)
    call check(.not. c_associated(mesh%ptr), 'no handle after a failed create')
    call check_contains(bodt_mesh_last_error(mesh), 'tet 2 uses vertex 9, but the mesh has 8 vertices', &
                        '1-based message')
    call check_contains(bodt_mesh_last_error(), 'tet 2 uses vertex 9, but the mesh has 8 vertices', &
                        'the failed create''s message without a handle')
    call bodt_mesh_create(points, bad - 1, mesh, index_base=0, ierr=ierr)
    call check_contains(bodt_mesh_last_error(mesh), 'tet 1 uses vertex 8', '0-based message')

    call bodt_mesh_create(points(1:2, :), tets, mesh, ierr=ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'points(2, n) refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'points has shape (2, 8)', 'points shape message')
    call bodt_mesh_create(points, tets(1:3, :), mesh, ierr=ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'tets(3, m) refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'tets has shape (3, 6)', 'tets shape message')

    call bodt_mesh_create(points, tets, mesh)
    allocate (regions(5), source=1_c_int32_t)
    call bodt_mesh_set_regions(mesh, regions, ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, '5 regions for 6 tets refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'region_ids has 5 values for 6 tets', 'regions message')
    call bodt_get_mode(mesh, mode, ierr)
    call check(len(bodt_mesh_last_error(mesh)) == 0, 'the next success clears a refused call''s message')
    call bodt_mesh_set_boundary_faces(mesh, reshape([1, 2, 3, 4], [2, 2]), ierr=ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'triangles(2, k) refused', mesh)
    call bodt_mesh_set_boundary_faces(mesh, reshape([1, 2, 3], [3, 1]), [1, 2], ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, '2 markers for 1 triangle refused', mesh)
    call bodt_mesh_set_feature_edges(mesh, reshape([1, 2, 3], [3, 1]), ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'edges(3, k) refused', mesh)
    call bodt_mesh_set_feature_edges_ex(mesh, reshape([1, 2, 3], [3, 1]), [1], ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'edges(3, k) with refs refused', mesh)
    call bodt_mesh_set_feature_edges_ex(mesh, reshape([1, 2], [2, 1]), [1, 2], ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, '2 refs for 1 edge refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'edges has shape (2, 1), but refs has another number of edges', &
                        'edge refs message')
    call bodt_mesh_set_corners(mesh, [1, 9], ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'corner 9 of 8 vertices refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'corner 2 uses vertex 9', 'corner message')
    call bodt_mesh_get_corners(mesh, is_corner)
    call check(all(is_corner == 0), 'a refused corner list sets no corner')
    call bodt_mesh_set_vertex_refs(mesh, [1, 2, 3], ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, '3 vertex refs for 8 vertices refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'refs has 3 values for 8 vertices', 'vertex refs message')
    call bodt_mesh_set_fixed_vertices(mesh, [3, 0], ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'fixed vertex 0 refused', mesh)
    call check_contains(bodt_mesh_last_error(mesh), 'fixed vertex 2 uses vertex 0', 'fixed vertex message')
    call bodt_mesh_tet_quality(mesh, 0, values, ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'unknown measure refused', mesh)
    call bodt_mesh_destroy(mesh)
    call bodt_mesh_get_counts(mesh, ierr=ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'a destroyed handle refused', mesh)
  end subroutine test_bad_input

  ! A Medit file written and read back, into a 1-based handle by default.
  subroutine test_files()
    character(len=*), parameter :: path = 'test_bodt_f.mesh'
    real(c_double), allocatable :: points(:, :), got_points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :), got(:, :), regions(:), faces(:, :), markers(:), &
                                       got_markers(:), fixed(:), got_fixed(:), edges(:, :), refs(:), &
                                       is_corner(:), vertex_refs(:)
    type(bodt_mesh_t) :: mesh, back
    integer(c_int) :: ierr, base
    integer(c_int32_t) :: t, v

    call make_box(2, 0.15_c_double, points, tets)
    call bodt_mesh_create(points, tets, mesh)
    regions = [(mod(t, 3) + 1, t = 1, int(size(tets, 2), c_int32_t))]
    call bodt_mesh_set_regions(mesh, regions)
    call bodt_mesh_get_boundary_faces(mesh, faces)
    call bodt_mesh_set_boundary_faces(mesh, faces(:, 1:2), [5, 6])
    call bodt_mesh_set_fixed_vertices(mesh, [2, 3])
    call bodt_mesh_set_feature_edges_ex(mesh, reshape([1, 2], [2, 1]), [4])
    call bodt_mesh_set_corners(mesh, [1])
    call bodt_mesh_set_vertex_refs(mesh, [(mod(v, 5), v = 1, int(size(points, 2), c_int32_t))])
    call bodt_mesh_write(mesh, path)

    call bodt_mesh_read(path, back, index_base=0)
    call bodt_mesh_get_index_base(back, base)
    call check(base == 0, 'index base of a file read with index_base=0')
    call bodt_mesh_get_tets(back, got)
    call check(all(got + 1 == tets), 'tets through the file, read 0-based')
    call bodt_mesh_destroy(back)
    call bodt_mesh_read(path, back, index_base=2, ierr=ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'a read with index_base 2 refused', back)
    call check_contains(bodt_mesh_last_error(back), 'index_base is 2, not 0 or 1', 'the message of index_base 2')

    call bodt_mesh_read(path, back)
    call bodt_mesh_get_vertices(back, got_points)
    call check(all(abs(got_points - points) <= 0), 'vertices through the file, exactly')
    call bodt_mesh_get_tets(back, got)
    call check(all(got == tets), 'tets through the file (read: 1-based by default)')
    call bodt_mesh_get_regions(back, got_markers)
    call check(all(got_markers == regions), 'regions through the file')
    call bodt_mesh_get_boundary_faces(mesh, faces, markers)
    call bodt_mesh_get_boundary_faces(back, got, got_markers)
    call check(all(got == faces) .and. all(got_markers == markers), 'faces and markers through the file')
    call bodt_mesh_get_fixed_vertices(mesh, fixed)
    call bodt_mesh_get_fixed_vertices(back, got_fixed)
    call check(all(got_fixed == fixed), 'fixed vertices through the file')
    call bodt_mesh_get_feature_edges_ex(back, edges, refs)
    call check(all(shape(edges) == [2, 1]) .and. all(edges(:, 1) == [1, 2]), 'feature edges through the file')
    call check(all(refs == [4]), 'feature edge refs through the file')
    call bodt_mesh_get_corners(back, is_corner)
    call check(is_corner(1) == 1 .and. sum(is_corner) == 1, 'corners through the file')
    call bodt_mesh_get_vertex_refs(mesh, vertex_refs)
    call bodt_mesh_get_vertex_refs(back, got_markers)
    call check(all(got_markers == vertex_refs), 'vertex refs through the file')
    call bodt_mesh_get_index_base(back, base)
    call check(base == 1, 'index base of a file read: 1 by default')
    call bodt_mesh_destroy(back)

    ! BODT_CREATE_FILE_BASE without index_base: the file's own base (VTU's 0)
    call bodt_mesh_write(mesh, 'test_bodt_f.vtu')
    call bodt_mesh_read_ex('test_bodt_f.vtu', BODT_CREATE_FILE_BASE, back)
    call bodt_mesh_get_index_base(back, base)
    call check(base == 0, 'index base of a VTU file read with BODT_CREATE_FILE_BASE')
    call bodt_mesh_get_tets(back, got)
    call check(all(got + 1 == tets), 'tets through the VTU file, in its base')
    call bodt_mesh_destroy(back)

    ! Gmsh 4.1 binary, chosen explicitly (the name says nothing)
    call bodt_mesh_write_format(mesh, 'test_bodt_f_gmsh.bin', BODT_FORMAT_GMSH_BINARY)
    call bodt_mesh_read_format('test_bodt_f_gmsh.bin', BODT_FORMAT_GMSH, BODT_CREATE_DEFAULT, back)
    call bodt_mesh_get_vertices(back, got_points)
    call bodt_mesh_get_tets(back, got)
    call check(all(abs(got_points - points) <= 0) .and. all(got == tets), 'vertices and tets through Gmsh binary')
    call bodt_mesh_get_regions(back, got_markers)
    call check(all(got_markers == regions), 'regions through Gmsh binary')
    call bodt_mesh_destroy(back)
    call bodt_mesh_write_format(mesh, 'test_bodt_f.dat', 99, ierr)
    call check_status(ierr, BODT_ERR_INVALID_ARGUMENT, 'an unknown format refused', mesh)
    call bodt_mesh_destroy(mesh)

    call bodt_format_from_path('part.ELE', base)
    call check(base == BODT_FORMAT_TETGEN, 'bodt_format_from_path: .ELE is TetGen')
    call bodt_format_from_path('part.xyz', base, ierr=ierr)
    call check(ierr == BODT_ERR_UNSUPPORTED, 'bodt_format_from_path: .xyz refused')
    call check_contains(bodt_mesh_last_error(), 'unknown mesh format', 'bodt_format_from_path message')

    call bodt_mesh_read('no such dir/missing.mesh  ', back, ierr=ierr)
    call check_status(ierr, BODT_ERR_IO, 'a missing file', back)
    call check_contains(bodt_mesh_last_error(back), "'no such dir/missing.mesh'", &
                        'the message names the file, without the trailing blanks')
    call check_contains(bodt_mesh_last_error(), "'no such dir/missing.mesh'", &
                        'the failed read''s message without a handle')
  end subroutine test_files

  ! Inverted tets: refused, unless BODT_CREATE_ACCEPT_INVERTED (create_ex,
  ! read_ex).
  subroutine test_inverted_input()
    character(len=*), parameter :: path = 'test_bodt_f_inverted.mesh'
    real(c_double), allocatable :: points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :)
    type(bodt_mesh_t) :: mesh, back
    type(bodt_quality) :: q
    integer(c_int) :: ierr, t, inverted

    call make_box(2, 0.0_c_double, points, tets)
    ! the centre, a vertex of every tet, pushed out through the top: the
    ! tets on the top side invert
    points(:, box_vertex(2, 1, 1, 1)) = [0.5_c_double, 0.5_c_double, 1.25_c_double]
    inverted = count([(signed_volume(points, tets(:, t)) < 0, t = 1, size(tets, 2))])
    call check(inverted > 0 .and. 2 * inverted < size(tets, 2), 'a minority of the tets inverted')
    call bodt_mesh_create(points, tets, mesh, ierr=ierr)
    call check_status(ierr, BODT_ERR_BAD_MESH, 'inverted tets refused', mesh)
    call bodt_mesh_create_ex(points, tets, BODT_CREATE_ACCEPT_INVERTED, mesh, ierr=ierr)
    call check_status(ierr, BODT_OK, 'inverted tets accepted', mesh)
    call bodt_mesh_quality(mesh, q)
    call check(q%num_inverted == inverted, 'the inverted tets counted')
    call bodt_mesh_write(mesh, path)
    call bodt_mesh_destroy(mesh)

    call bodt_mesh_read(path, back, ierr=ierr)
    call check_status(ierr, BODT_ERR_BAD_MESH, 'a file with inverted tets refused', back)
    call bodt_mesh_read_ex(path, BODT_CREATE_ACCEPT_INVERTED, back, ierr=ierr)
    call check_status(ierr, BODT_OK, 'a file with inverted tets accepted', back)
    call bodt_mesh_quality(back, q)
    call check(q%num_inverted == inverted, 'the inverted tets read back')
    call bodt_mesh_destroy(back)
  end subroutine test_inverted_input

  ! The geometry of paper 002 of a box: 6 planes, 12 sharp edges, 8 corners.
  subroutine test_geometry()
    integer, parameter :: n = 3
    real(c_double), allocatable :: points(:, :)
    integer(c_int32_t), allocatable :: tets(:, :), classes(:), faces(:, :), region_ids(:), shapes(:)
    type(bodt_mesh_t) :: mesh
    type(bodt_shape_fit) :: fit
    ! by the number of sides of the box the vertex is on
    integer(c_int32_t), parameter :: class_by_sides(0:3) = [BODT_GEOMETRY_INTERIOR, BODT_GEOMETRY_SURFACE, &
                                                             BODT_GEOMETRY_SHARP_EDGE, BODT_GEOMETRY_CORNER]
    integer(c_int32_t) :: nregions, nchains, side_region(6), v, f, side, axis
    integer :: i, j, k
    logical :: on(3)

    call make_box(n, 0.15_c_double, points, tets)
    call bodt_mesh_create(points, tets, mesh)
    call bodt_mesh_get_geometry_counts(mesh, nregions, nchains)
    call check(nregions == 6 .and. nchains == 12, 'a box: 6 surface regions, 12 chains')
    call bodt_mesh_get_geometry_classes(mesh, classes)
    do k = 0, n
      do j = 0, n
        do i = 0, n
          v = box_vertex(n, i, j, k)
          on = [i, j, k] == 0 .or. [i, j, k] == n
          call check(classes(v) == class_by_sides(count(on)), 'geometry class from the position')
        end do
      end do
    end do

    ! each side of the box is one plane region, numbered from 1
    call bodt_mesh_get_boundary_faces(mesh, faces)
    call bodt_mesh_get_face_regions(mesh, region_ids, shapes)
    call check(size(region_ids) == size(faces, 2) .and. all(shapes == BODT_SHAPE_PLANE), 'every face on a plane')
    side_region = 0
    do f = 1, size(faces, 2)
      side = box_side(points(:, faces(:, f)))
      if (side_region(side) == 0) side_region(side) = region_ids(f)
      call check(region_ids(f) == side_region(side), 'one region per side')
    end do
    call check(all(side_region >= 1 .and. side_region <= 6), 'regions numbered from 1')
    do side = 1, 6
      call check(count(side_region == side_region(side)) == 1, 'a region per side')
      call bodt_mesh_get_region_shape(mesh, side_region(side), fit)
      axis = (side + 1) / 2
      call check(fit%shape == BODT_SHAPE_PLANE, 'region shape: plane')
      call check_near(abs(fit%axis(axis)), 1.0_c_double, 1e-12_c_double, 'plane normal along its axis')
      call check_near(fit%point(axis), real(mod(side + 1, 2), c_double), 1e-12_c_double, 'plane position')
      call check(fit%max_error <= 1e-12_c_double, 'plane fit error')
    end do
    call bodt_mesh_destroy(mesh)
  end subroutine test_geometry

  ! The side of the unit box a boundary triangle lies on: 1, 2 for x = 0,
  ! 1; 3, 4 for y; 5, 6 for z.
  integer(c_int32_t) function box_side(corners) result(side)
    real(c_double), intent(in) :: corners(:, :)
    integer :: axis
    do axis = 1, 3
      do side = 2 * axis - 1, 2 * axis
        if (all(abs(corners(axis, :) - (side - 2 * axis + 1)) <= 0)) return
      end do
    end do
    call check(.false., 'a boundary face off the box')
  end function box_side

  ! recovery_error against a target density computed here, and with a
  ! reference mesh.
  subroutine test_recovery_error()
    integer, parameter :: n = 2
    real(c_double), allocatable :: points(:, :), jittered(:, :), density(:, :, :)
    integer(c_int32_t), allocatable :: tets(:, :)
    type(bodt_mesh_t) :: mesh, reference
    type(bodt_recovery_error) :: e
    real(c_double) :: h, face_error, body_error
    integer(c_int64_t) :: axis_edges, face_edges, body_edges

    call make_box(n, 0.0_c_double, points, tets)
    call bodt_mesh_create(points, tets, mesh)
    call bodt_mesh_recovery_error(mesh, e)
    call check(e%size == c_sizeof(e) .and. e%density_edges == 0 .and. e%geometric_edges == 0, &
               'no target, no cylinder: no edges measured')

    ! density 1/h everywhere: axis edges are exact, face and body diagonals
    ! are off by 1 - 1/sqrt(2) and 1 - 1/sqrt(3)
    h = 1.0_c_double / n
    allocate (density(2, 2, 2), source=1 / h)
    call bodt_set_target_density(mesh, [0.0_c_double, 0.0_c_double, 0.0_c_double], &
                                 [1.0_c_double, 1.0_c_double, 1.0_c_double], density)
    call bodt_mesh_recovery_error(mesh, e)
    axis_edges = 3 * n * (n + 1)**2
    face_edges = 3 * n**2 * (n + 1)
    body_edges = n**3
    face_error = 1 - 1 / sqrt(2.0_c_double)
    body_error = 1 - 1 / sqrt(3.0_c_double)
    call check(e%density_edges == axis_edges + face_edges + body_edges, 'every edge measured')
    call check_near(e%density_max, body_error, 1e-12_c_double, 'density error max')
    call check_near(e%density_mean, (face_edges * face_error + body_edges * body_error) / e%density_edges, &
                    1e-12_c_double, 'density error mean')
    call bodt_set_target_density(mesh)
    call bodt_mesh_recovery_error(mesh, e)
    call check(e%density_edges == 0, 'target density cleared')

    ! the jittered box against the regular one as reference
    call bodt_mesh_create(points, tets, reference)
    call bodt_mesh_destroy(mesh)
    call make_box(n, 0.15_c_double, jittered, tets)
    call bodt_mesh_create(jittered, tets, mesh)
    call bodt_set_reference_mesh(mesh, reference)
    call bodt_mesh_destroy(reference)  ! read, not kept
    call bodt_mesh_recovery_error(mesh, e)
    call check(e%density_edges == axis_edges + face_edges + body_edges .and. e%density_mean > 0, &
               'density error against the reference')
    call check(e%geometric_edges == 0, 'no cylinder, no geometric error')
    call bodt_set_reference_mesh(mesh)
    call bodt_mesh_recovery_error(mesh, e)
    call check(e%density_edges == 0, 'reference cleared')
    call bodt_mesh_destroy(mesh)
  end subroutine test_recovery_error

end program test_bodt_f
