! bodt.f90 -- the Fortran module bodt: libbodt's C API (include/bodt.h) for
! Fortran 2018 programs.  bodt.h documents what each function does; this file
! only says how the Fortran side differs.
!
!   use bodt
!   type(bodt_mesh_t) :: mesh
!   type(bodt_quality) :: q
!   call bodt_mesh_create(points, tets, mesh)   ! points(3, n), tets(4, m)
!   call bodt_run(mesh, 20)
!   call bodt_mesh_quality(mesh, q)
!   call bodt_mesh_destroy(mesh)
!
! Conventions:
!  - Every C function has a wrapper of the same name.  Counts and capacities
!    come from the array shapes: points(3, nverts), tets(4, ntets),
!    triangles(3, nfaces), edges(2, nedges).  Getters allocate their
!    allocatable, intent(out) arrays themselves.
!  - Indices are 1-based by default: bodt_mesh_create and bodt_mesh_read
!    take an optional index_base (default 1, where C has no default for
!    create and reads 0-based; a read with BODT_CREATE_FILE_BASE and no
!    index_base counts as the file does).
!  - Status, in the style of Gmsh's gmsh.f90: every wrapper that can fail
!    ends with an optional `ierr`.  Given, it receives BODT_OK (0) or a
!    negative BODT_ERR_* code and the caller checks it.  Omitted, a failure
!    writes "bodt: <function>: <status>: <message>" to error_unit and stops
!    the program (error stop): a call that passes no ierr never fails
!    silently.  bodt_mesh_last_error(mesh) gives the message, and
!    bodt_mesh_last_error() that of a failed create or read (no handle).
!  - The handle is intent(inout) in every wrapper: besides the C pointer it
!    holds the message of a call the wrapper refused itself (a wrong array
!    shape), so that bodt_mesh_last_error tells about that call too.
!  - The bind(c) structs mirror bodt.h; the wrappers set their size field.
!  - There is no finalizer (a copied handle would be freed twice): call
!    bodt_mesh_destroy.
!  - Strings out are character(len=:), allocatable; paths in are Fortran
!    strings (trailing blanks dropped).
!
! The constants below mirror bodt.h; tests/test_bodt_f.f90 checks every one
! of them, and every struct field, against what the C compiler sees.
module bodt
  use, intrinsic :: iso_c_binding
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none
  private

  ! BODT_VERSION_NUMBER would be the same Fortran name as the function
  ! bodt_version_number(), hence BODT_MODULE_VERSION_NUMBER.
  integer(c_int), parameter, public :: &
    BODT_VERSION_MAJOR = 0, BODT_VERSION_MINOR = 5, BODT_VERSION_PATCH = 0, &
    BODT_MODULE_VERSION_NUMBER = 500

  ! enum bodt_status
  integer(c_int), parameter, public :: &
    BODT_OK = 0, BODT_ERR_INVALID_ARGUMENT = -1, BODT_ERR_BAD_MESH = -2, &
    BODT_ERR_OUT_OF_MEMORY = -3, BODT_ERR_WRONG_STATE = -4, BODT_ERR_NUMERIC = -5, &
    BODT_ERR_IO = -6, BODT_ERR_CANCELLED = -7, BODT_ERR_UNSUPPORTED = -8
  ! enum bodt_create_flag
  integer(c_int32_t), parameter, public :: BODT_CREATE_DEFAULT = 0, BODT_CREATE_ACCEPT_INVERTED = 1, &
    BODT_CREATE_ONE_BASED = 2, BODT_CREATE_KEEP_ORDER = 4, BODT_CREATE_FILE_BASE = 8
  ! enum bodt_vertex_class
  integer(c_int32_t), parameter, public :: &
    BODT_VERTEX_INTERIOR = 0, BODT_VERTEX_SURFACE = 1, BODT_VERTEX_FEATURE_LINE = 2, &
    BODT_VERTEX_CORNER = 3, BODT_VERTEX_FIXED = 4, BODT_VERTEX_UNUSED = 5
  integer(c_int), parameter, public :: BODT_DIHEDRAL_BINS = 23
  ! enum bodt_measure
  integer(c_int), parameter, public :: &
    BODT_MEASURE_MIN_DIHEDRAL = 1, BODT_MEASURE_MAX_DIHEDRAL = 2, &
    BODT_MEASURE_STRETCH = 3, BODT_MEASURE_VOLUME = 4
  ! enum bodt_mode
  integer(c_int), parameter, public :: &
    BODT_MODE_LAPLACE = 1, BODT_MODE_ODT = 2, BODT_MODE_BODT_BASIC = 3, BODT_MODE_BODT = 4, &
    BODT_MODE_OPT_WEIGHTED = 5, BODT_MODE_PHASED_ODT = 6, BODT_MODE_NODT = 7
  ! enum bodt_param
  integer(c_int), parameter, public :: &
    BODT_PARAM_TOLERANCE = 1, BODT_PARAM_BACKTRACK_STEPS = 2, BODT_PARAM_MIN_STRETCH = 3, &
    BODT_PARAM_NEVER_WORSE = 4, BODT_PARAM_FEATURE_ANGLE = 5, BODT_PARAM_EDGE_RATIO = 6, &
    BODT_PARAM_CORNER_RATIO = 7, BODT_PARAM_OPS = 8, BODT_PARAM_KEEP_SURFACE = 9, &
    BODT_PARAM_BAD_ANGLE = 10, BODT_PARAM_DELAUNAY_FLIPS = 11, BODT_PARAM_WEIGHT_C = 12, &
    BODT_PARAM_POOR_QUALITY = 13, BODT_PARAM_QN_EPSILON = 14, BODT_PARAM_QN_MAX_ITERATIONS = 15, &
    BODT_PARAM_QN_INITIAL_STEP = 16, BODT_PARAM_QN_INTERVAL_GROWTH = 17, BODT_PARAM_ODT_STEP = 18, &
    BODT_PARAM_DENSITY_SPLIT = 19, BODT_PARAM_DENSITY_COLLAPSE = 20, BODT_PARAM_FIT_TOLERANCE = 21, &
    BODT_PARAM_THREADS = 22, BODT_PARAM_ASCENT_ANGLE = 23
  ! enum bodt_op (bits of BODT_PARAM_OPS)
  integer(c_int32_t), parameter, public :: &
    BODT_OP_SMOOTH = 1, BODT_OP_FLIP = 2, BODT_OP_INSERT = 4, BODT_OP_COLLAPSE = 8, &
    BODT_OPS_MODE_DEFAULT = -1
  ! enum bodt_geometry_class
  integer(c_int32_t), parameter, public :: &
    BODT_GEOMETRY_INTERIOR = 0, BODT_GEOMETRY_SURFACE = 1, BODT_GEOMETRY_SHARP_EDGE = 2, &
    BODT_GEOMETRY_CORNER = 3
  ! enum bodt_shape
  integer(c_int32_t), parameter, public :: &
    BODT_SHAPE_NONE = 0, BODT_SHAPE_PLANE = 1, BODT_SHAPE_CYLINDER = 2, BODT_SHAPE_LINE = 3, &
    BODT_SHAPE_ARC = 4, BODT_SHAPE_CIRCLE = 5
  ! enum bodt_format
  integer(c_int), parameter, public :: &
    BODT_FORMAT_AUTO = 0, BODT_FORMAT_MEDIT = 1, BODT_FORMAT_MEDIT_BINARY = 2, BODT_FORMAT_TETGEN = 3, &
    BODT_FORMAT_GMSH = 4, BODT_FORMAT_GMSH_BINARY = 5, BODT_FORMAT_GMSH22 = 6, BODT_FORMAT_GMSH22_BINARY = 7, &
    BODT_FORMAT_VTU = 8, BODT_FORMAT_ABAQUS = 9, BODT_FORMAT_VTK = 10

  ! The structs of bodt.h, field for field.
  type, bind(c), public :: bodt_quality
    integer(c_size_t) :: size
    integer(c_int32_t) :: num_vertices, num_tets, num_boundary_faces, num_unused_vertices, &
                          num_inverted, reserved0
    real(c_double) :: min_dihedral, max_dihedral, mean_dihedral, min_stretch, mean_stretch, volume
    integer(c_int64_t) :: dihedral_histogram(BODT_DIHEDRAL_BINS)
  end type bodt_quality

  type, bind(c), public :: bodt_step_report
    integer(c_size_t) :: size
    integer(c_int32_t) :: step, vertices_moved, moves_rejected, moves_shortened, &
                          not_positive_definite, reserved0
    real(c_double) :: max_move, min_dihedral, max_dihedral, min_stretch
    integer(c_int32_t) :: flips, vertices_inserted, edges_collapsed, reserved1
  end type bodt_step_report

  type, bind(c), public :: bodt_shape_fit
    integer(c_size_t) :: size
    integer(c_int32_t) :: shape, reserved0
    real(c_double) :: point(3), axis(3), radius, max_error, acceptable_error
  end type bodt_shape_fit

  type, bind(c), public :: bodt_recovery_error
    integer(c_size_t) :: size
    real(c_double) :: density_mean, density_max
    integer(c_int64_t) :: density_edges
    real(c_double) :: geometric_mean, geometric_max
    integer(c_int64_t) :: geometric_edges
  end type bodt_recovery_error

  ! A mesh handle: a type of its own, so no other C pointer passes for one.
  type, public :: bodt_mesh_t
    type(c_ptr) :: ptr = c_null_ptr
    character(len=:), allocatable, private :: error  ! set by a refused call
  end type bodt_mesh_t

  ! bodt_run's callback: return 0 to go on, anything else to stop.
  abstract interface
    function bodt_step_callback(report, user_data) bind(c) result(stop)
      import :: bodt_step_report, c_ptr, c_int
      type(bodt_step_report), intent(in) :: report
      type(c_ptr), value :: user_data
      integer(c_int) :: stop
    end function bodt_step_callback
  end interface

  public :: bodt_step_callback, bodt_version_number
  public :: bodt_version_string, bodt_status_string, bodt_mesh_last_error
  public :: bodt_mesh_create, bodt_mesh_create_ex, bodt_mesh_destroy
  public :: bodt_mesh_read, bodt_mesh_read_ex, bodt_mesh_read_format, bodt_mesh_write, bodt_mesh_write_format
  public :: bodt_format_from_path
  public :: bodt_mesh_set_regions, bodt_mesh_set_boundary_faces, bodt_mesh_set_fixed_vertices, &
            bodt_mesh_set_feature_edges, bodt_mesh_set_feature_edges_ex, bodt_mesh_set_corners, &
            bodt_mesh_set_vertex_refs
  public :: bodt_mesh_get_counts, bodt_mesh_get_vertices, bodt_mesh_get_tets, bodt_mesh_get_regions, &
            bodt_mesh_get_boundary_faces, bodt_mesh_get_fixed_vertices, bodt_mesh_get_feature_edges, &
            bodt_mesh_get_feature_edges_ex, bodt_mesh_get_corners, bodt_mesh_get_vertex_refs, &
            bodt_mesh_get_index_base, bodt_mesh_get_vertex_classes, bodt_mesh_get_parent_count, &
            bodt_mesh_get_vertex_parents, bodt_mesh_get_tet_origins
  public :: bodt_dihedral_bin_edges, bodt_mesh_quality, bodt_mesh_tet_quality
  public :: bodt_set_mode, bodt_get_mode, bodt_set_param_int, bodt_set_param_double, &
            bodt_get_param_int, bodt_get_param_double
  public :: bodt_step, bodt_run
  public :: bodt_mesh_get_geometry_counts, bodt_mesh_get_geometry_classes, bodt_mesh_get_face_regions, &
            bodt_mesh_get_region_shape, bodt_set_reference_mesh, bodt_set_target_density, &
            bodt_mesh_recovery_error

  ! The C functions.  An optional dummy is passed as NULL when absent
  ! (Fortran 2018), which is how the wrappers give C its optional pointers;
  ! optional output arrays are c_ptr instead, since gfortran 12 does not
  ! pass an absent allocatable array as NULL.
  interface
    function bodt_version_number() bind(c, name='bodt_version_number') result(number)
      import :: c_int
      integer(c_int) :: number
    end function bodt_version_number
    function c_bodt_version_string() bind(c, name='bodt_version_string') result(s)
      import :: c_ptr
      type(c_ptr) :: s
    end function c_bodt_version_string
    function c_bodt_status_string(status) bind(c, name='bodt_status_string') result(s)
      import :: c_int, c_ptr
      integer(c_int), value :: status
      type(c_ptr) :: s
    end function c_bodt_status_string
    function c_bodt_mesh_last_error(mesh) bind(c, name='bodt_mesh_last_error') result(s)
      import :: c_ptr
      type(c_ptr), value :: mesh
      type(c_ptr) :: s
    end function c_bodt_mesh_last_error
    function c_strlen(s) bind(c, name='strlen') result(n)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: n
    end function c_strlen

    function c_bodt_mesh_create_ex(nverts, xyz, ntets, tets, index_base, flags, mesh) &
        bind(c, name='bodt_mesh_create_ex') result(status)
      import :: c_int, c_int32_t, c_double, c_ptr
      integer(c_int32_t), value :: nverts, ntets, flags
      real(c_double), intent(in) :: xyz(*)
      integer(c_int32_t), intent(in) :: tets(*)
      integer(c_int), value :: index_base
      type(c_ptr), intent(out) :: mesh
      integer(c_int) :: status
    end function c_bodt_mesh_create_ex
    subroutine c_bodt_mesh_destroy(mesh) bind(c, name='bodt_mesh_destroy')
      import :: c_ptr
      type(c_ptr), value :: mesh
    end subroutine c_bodt_mesh_destroy
    function c_bodt_mesh_read_format(path, format, flags, mesh) bind(c, name='bodt_mesh_read_format') &
        result(status)
      import :: c_int, c_int32_t, c_char, c_ptr
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: format
      integer(c_int32_t), value :: flags
      type(c_ptr), intent(out) :: mesh
      integer(c_int) :: status
    end function c_bodt_mesh_read_format
    function c_bodt_format_from_path(path, format) bind(c, name='bodt_format_from_path') result(status)
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), intent(out) :: format
      integer(c_int) :: status
    end function c_bodt_format_from_path
    function c_bodt_mesh_write_format(mesh, path, format) bind(c, name='bodt_mesh_write_format') result(status)
      import :: c_int, c_char, c_ptr
      type(c_ptr), value :: mesh
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), value :: format
      integer(c_int) :: status
    end function c_bodt_mesh_write_format

    function c_bodt_mesh_set_boundary_faces(mesh, nfaces, triangles, markers) &
        bind(c, name='bodt_mesh_set_boundary_faces') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: nfaces
      integer(c_int32_t), intent(in) :: triangles(*)
      integer(c_int32_t), intent(in), optional :: markers(*)
      integer(c_int) :: status
    end function c_bodt_mesh_set_boundary_faces
    function c_bodt_mesh_set_fixed_vertices(mesh, nfixed, vertices) &
        bind(c, name='bodt_mesh_set_fixed_vertices') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: nfixed
      integer(c_int32_t), intent(in) :: vertices(*)
      integer(c_int) :: status
    end function c_bodt_mesh_set_fixed_vertices
    function c_bodt_mesh_set_feature_edges_ex(mesh, nedges, edges, refs) &
        bind(c, name='bodt_mesh_set_feature_edges_ex') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: nedges
      integer(c_int32_t), intent(in) :: edges(*)
      integer(c_int32_t), intent(in), optional :: refs(*)
      integer(c_int) :: status
    end function c_bodt_mesh_set_feature_edges_ex
    function c_bodt_mesh_set_corners(mesh, ncorners, vertices) bind(c, name='bodt_mesh_set_corners') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: ncorners
      integer(c_int32_t), intent(in) :: vertices(*)
      integer(c_int) :: status
    end function c_bodt_mesh_set_corners

    function c_bodt_mesh_get_counts(mesh, nverts, ntets, nboundary_faces) &
        bind(c, name='bodt_mesh_get_counts') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out), optional :: nverts, ntets, nboundary_faces
      integer(c_int) :: status
    end function c_bodt_mesh_get_counts
    function c_bodt_mesh_get_vertices(mesh, xyz, capacity) bind(c, name='bodt_mesh_get_vertices') result(status)
      import :: c_int, c_double, c_size_t, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(out) :: xyz(*)
      integer(c_size_t), value :: capacity
      integer(c_int) :: status
    end function c_bodt_mesh_get_vertices
    function c_bodt_mesh_get_boundary_faces(mesh, triangles, markers, capacity) &
        bind(c, name='bodt_mesh_get_boundary_faces') result(status)
      import :: c_int, c_int32_t, c_size_t, c_ptr
      type(c_ptr), value :: mesh
      type(c_ptr), value :: triangles, markers
      integer(c_size_t), value :: capacity
      integer(c_int) :: status
    end function c_bodt_mesh_get_boundary_faces
    function c_bodt_mesh_get_feature_edges_ex(mesh, nedges, edges, refs, capacity) &
        bind(c, name='bodt_mesh_get_feature_edges_ex') result(status)
      import :: c_int, c_int32_t, c_size_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: nedges
      integer(c_int32_t), intent(out), optional :: edges(*), refs(*)
      integer(c_size_t), value :: capacity
      integer(c_int) :: status
    end function c_bodt_mesh_get_feature_edges_ex
    function c_bodt_mesh_get_index_base(mesh, index_base) bind(c, name='bodt_mesh_get_index_base') result(status)
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), intent(out) :: index_base
      integer(c_int) :: status
    end function c_bodt_mesh_get_index_base
    function c_bodt_mesh_get_parent_count(mesh, count) bind(c, name='bodt_mesh_get_parent_count') result(status)
      import :: c_int, c_int64_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int64_t), intent(out) :: count
      integer(c_int) :: status
    end function c_bodt_mesh_get_parent_count
    function c_bodt_mesh_get_vertex_parents(mesh, offsets, offsets_capacity, parents, weights, capacity) &
        bind(c, name='bodt_mesh_get_vertex_parents') result(status)
      import :: c_int, c_int32_t, c_int64_t, c_double, c_size_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int64_t), intent(out) :: offsets(*)
      integer(c_size_t), value :: offsets_capacity, capacity
      integer(c_int32_t), intent(out) :: parents(*)
      real(c_double), intent(out) :: weights(*)
      integer(c_int) :: status
    end function c_bodt_mesh_get_vertex_parents

    function c_bodt_dihedral_bin_edges(edges, capacity) bind(c, name='bodt_dihedral_bin_edges') result(status)
      import :: c_int, c_double, c_size_t
      real(c_double), intent(out) :: edges(*)
      integer(c_size_t), value :: capacity
      integer(c_int) :: status
    end function c_bodt_dihedral_bin_edges
    function c_bodt_mesh_quality(mesh, quality) bind(c, name='bodt_mesh_quality') result(status)
      import :: c_int, c_ptr, bodt_quality
      type(c_ptr), value :: mesh
      type(bodt_quality), intent(inout) :: quality
      integer(c_int) :: status
    end function c_bodt_mesh_quality
    function c_bodt_mesh_tet_quality(mesh, measure, values, capacity) &
        bind(c, name='bodt_mesh_tet_quality') result(status)
      import :: c_int, c_double, c_size_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), value :: measure
      real(c_double), intent(out) :: values(*)
      integer(c_size_t), value :: capacity
      integer(c_int) :: status
    end function c_bodt_mesh_tet_quality

    function c_bodt_set_mode(mesh, mode) bind(c, name='bodt_set_mode') result(status)
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), value :: mode
      integer(c_int) :: status
    end function c_bodt_set_mode
    function c_bodt_get_mode(mesh, mode) bind(c, name='bodt_get_mode') result(status)
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), intent(out) :: mode
      integer(c_int) :: status
    end function c_bodt_get_mode
    function c_bodt_set_param_int(mesh, key, value) bind(c, name='bodt_set_param_int') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), value :: key
      integer(c_int32_t), value :: value
      integer(c_int) :: status
    end function c_bodt_set_param_int
    function c_bodt_set_param_double(mesh, key, value) bind(c, name='bodt_set_param_double') result(status)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), value :: key
      real(c_double), value :: value
      integer(c_int) :: status
    end function c_bodt_set_param_double
    function c_bodt_get_param_int(mesh, key, value) bind(c, name='bodt_get_param_int') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), value :: key
      integer(c_int32_t), intent(out) :: value
      integer(c_int) :: status
    end function c_bodt_get_param_int
    function c_bodt_get_param_double(mesh, key, value) bind(c, name='bodt_get_param_double') result(status)
      import :: c_int, c_double, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int), value :: key
      real(c_double), intent(out) :: value
      integer(c_int) :: status
    end function c_bodt_get_param_double

    function c_bodt_step(mesh, report) bind(c, name='bodt_step') result(status)
      import :: c_int, c_ptr, bodt_step_report
      type(c_ptr), value :: mesh
      type(bodt_step_report), intent(inout), optional :: report
      integer(c_int) :: status
    end function c_bodt_step
    function c_bodt_run(mesh, max_steps, callback, user_data) bind(c, name='bodt_run') result(status)
      import :: c_int, c_int32_t, c_ptr, c_funptr
      type(c_ptr), value :: mesh, user_data
      integer(c_int32_t), value :: max_steps
      type(c_funptr), value :: callback
      integer(c_int) :: status
    end function c_bodt_run

    function c_bodt_mesh_get_geometry_counts(mesh, nregions, nchains) &
        bind(c, name='bodt_mesh_get_geometry_counts') result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out), optional :: nregions, nchains
      integer(c_int) :: status
    end function c_bodt_mesh_get_geometry_counts
    function c_bodt_mesh_get_face_regions(mesh, region_ids, shapes, capacity) &
        bind(c, name='bodt_mesh_get_face_regions') result(status)
      import :: c_int, c_int32_t, c_size_t, c_ptr
      type(c_ptr), value :: mesh
      type(c_ptr), value :: region_ids, shapes
      integer(c_size_t), value :: capacity
      integer(c_int) :: status
    end function c_bodt_mesh_get_face_regions
    function c_bodt_mesh_get_region_shape(mesh, region, fit) bind(c, name='bodt_mesh_get_region_shape') result(status)
      import :: c_int, c_int32_t, c_ptr, bodt_shape_fit
      type(c_ptr), value :: mesh
      integer(c_int32_t), value :: region
      type(bodt_shape_fit), intent(inout) :: fit
      integer(c_int) :: status
    end function c_bodt_mesh_get_region_shape
    function c_bodt_set_reference_mesh(mesh, reference) bind(c, name='bodt_set_reference_mesh') result(status)
      import :: c_int, c_ptr
      type(c_ptr), value :: mesh, reference
      integer(c_int) :: status
    end function c_bodt_set_reference_mesh
    function c_bodt_set_target_density(mesh, origin, spacing, dims, values) &
        bind(c, name='bodt_set_target_density') result(status)
      import :: c_int, c_int32_t, c_double, c_ptr
      type(c_ptr), value :: mesh
      real(c_double), intent(in), optional :: origin(3), spacing(3), values(*)
      integer(c_int32_t), intent(in), optional :: dims(3)
      integer(c_int) :: status
    end function c_bodt_set_target_density
    function c_bodt_mesh_recovery_error(mesh, error) bind(c, name='bodt_mesh_recovery_error') result(status)
      import :: c_int, c_ptr, bodt_recovery_error
      type(c_ptr), value :: mesh
      type(bodt_recovery_error), intent(inout) :: error
      integer(c_int) :: status
    end function c_bodt_mesh_recovery_error
  end interface

  ! The setters of one int32 per tet or vertex, and the getters of one
  ! int32 array: the same C signatures, one helper each.
  abstract interface
    function c_set_ints(mesh, values) bind(c) result(status)
      import :: c_int, c_int32_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(in) :: values(*)
      integer(c_int) :: status
    end function c_set_ints
    function c_get_ints(mesh, values, capacity) bind(c) result(status)
      import :: c_int, c_int32_t, c_size_t, c_ptr
      type(c_ptr), value :: mesh
      integer(c_int32_t), intent(out) :: values(*)
      integer(c_size_t), value :: capacity
      integer(c_int) :: status
    end function c_get_ints
  end interface
  procedure(c_set_ints), bind(c, name='bodt_mesh_set_regions') :: c_bodt_mesh_set_regions
  procedure(c_set_ints), bind(c, name='bodt_mesh_set_vertex_refs') :: c_bodt_mesh_set_vertex_refs
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_tets') :: c_bodt_mesh_get_tets
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_regions') :: c_bodt_mesh_get_regions
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_fixed_vertices') :: c_bodt_mesh_get_fixed_vertices
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_corners') :: c_bodt_mesh_get_corners
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_vertex_refs') :: c_bodt_mesh_get_vertex_refs
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_vertex_classes') :: c_bodt_mesh_get_vertex_classes
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_tet_origins') :: c_bodt_mesh_get_tet_origins
  procedure(c_get_ints), bind(c, name='bodt_mesh_get_geometry_classes') :: c_bodt_mesh_get_geometry_classes

contains

  ! ------------------------------------------------------------ helpers

  ! Every wrapper ends here: the status goes to ierr, or a failure stops the
  ! program with its message.  `refused` is the message of a call the
  ! wrapper refused before reaching C; otherwise C's message stands.
  subroutine finish(status, name, mesh, ierr, refused)
    integer(c_int), intent(in) :: status
    character(len=*), intent(in) :: name
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(out), optional :: ierr
    character(len=*), intent(in), optional :: refused
    if (present(refused)) then
      mesh%error = refused
    else if (allocated(mesh%error)) then
      deallocate (mesh%error)
    end if
    if (present(ierr)) then
      ierr = status
    else if (status /= BODT_OK) then
      ! The message first: flushed before the runtime's "ERROR STOP" and
      ! backtrace, which go to standard error unbuffered.
      write (error_unit, '(6a)') 'bodt: ', name, ': ', bodt_status_string(status), ': ', &
        bodt_mesh_last_error(mesh)
      flush (error_unit)
      error stop
    end if
  end subroutine finish

  ! A C string (NULL gives '').
  function f_string(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: i
    if (.not. c_associated(p)) then
      s = ''
      return
    end if
    call c_f_pointer(p, chars, [c_strlen(p)])
    allocate (character(len=size(chars)) :: s)
    do i = 1, size(chars)
      s(i:i) = chars(i)
    end do
  end function f_string

  function c_path(path)
    character(len=*), intent(in) :: path
    character(kind=c_char, len=:), allocatable :: c_path
    c_path = trim(path) // c_null_char
  end function c_path

  ! "name has shape (a, b)", to refuse an array.
  function shape_text(name, dims) result(s)
    character(len=*), intent(in) :: name
    integer, intent(in) :: dims(2)
    character(len=:), allocatable :: s
    character(len=64) :: buffer
    write (buffer, '(a, i0, a, i0, a)') ' has shape (', dims(1), ', ', dims(2), ')'
    s = name // trim(buffer)
  end function shape_text

  ! ------------------------------------------------------------ strings

  function bodt_version_string() result(version)
    character(len=:), allocatable :: version
    version = f_string(c_bodt_version_string())
  end function bodt_version_string

  function bodt_status_string(status) result(name)
    integer(c_int), intent(in) :: status
    character(len=:), allocatable :: name
    name = f_string(c_bodt_status_string(status))
  end function bodt_status_string

  ! The message of the last failed call on mesh ('' after a success); for a
  ! handle that bodt_mesh_create or _read did not make, that call's message.
  ! Without mesh (C's NULL): the message of the last failed create or read
  ! on this thread.
  function bodt_mesh_last_error(mesh) result(message)
    type(bodt_mesh_t), intent(in), optional :: mesh
    character(len=:), allocatable :: message
    if (.not. present(mesh)) then
      message = f_string(c_bodt_mesh_last_error(c_null_ptr))
    else if (allocated(mesh%error)) then
      message = mesh%error
    else
      message = f_string(c_bodt_mesh_last_error(mesh%ptr))
    end if
  end function bodt_mesh_last_error

  ! ------------------------------------------------------ create, files

  ! points(3, nverts), tets(4, ntets) in base index_base (default 1).
  subroutine bodt_mesh_create(points, tets, mesh, index_base, ierr)
    real(c_double), intent(in) :: points(:, :)
    integer(c_int32_t), intent(in) :: tets(:, :)
    type(bodt_mesh_t), intent(out) :: mesh
    integer(c_int), intent(in), optional :: index_base
    integer(c_int), intent(out), optional :: ierr
    call create('bodt_mesh_create', points, tets, BODT_CREATE_DEFAULT, mesh, index_base, ierr)
  end subroutine bodt_mesh_create

  subroutine bodt_mesh_create_ex(points, tets, flags, mesh, index_base, ierr)
    real(c_double), intent(in) :: points(:, :)
    integer(c_int32_t), intent(in) :: tets(:, :)
    integer(c_int32_t), intent(in) :: flags
    type(bodt_mesh_t), intent(out) :: mesh
    integer(c_int), intent(in), optional :: index_base
    integer(c_int), intent(out), optional :: ierr
    call create('bodt_mesh_create_ex', points, tets, flags, mesh, index_base, ierr)
  end subroutine bodt_mesh_create_ex

  subroutine create(name, points, tets, flags, mesh, index_base, ierr)
    character(len=*), intent(in) :: name
    real(c_double), intent(in) :: points(:, :)
    integer(c_int32_t), intent(in) :: tets(:, :)
    integer(c_int32_t), intent(in) :: flags
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in), optional :: index_base
    integer(c_int), intent(out), optional :: ierr
    integer(c_int) :: base
    if (size(points, 1) /= 3) then
      call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, &
                  shape_text('points', shape(points)) // ', not (3, nverts)')
    else if (size(tets, 1) /= 4) then
      call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, &
                  shape_text('tets', shape(tets)) // ', not (4, ntets)')
    else
      base = 1
      if (present(index_base)) base = index_base
      call finish(c_bodt_mesh_create_ex(size(points, 2), points, size(tets, 2), tets, base, flags, mesh%ptr), &
                  name, mesh, ierr)
    end if
  end subroutine create

  ! Frees the handle and nulls it; a null handle is ignored.
  subroutine bodt_mesh_destroy(mesh)
    type(bodt_mesh_t), intent(inout) :: mesh
    call c_bodt_mesh_destroy(mesh%ptr)
    mesh%ptr = c_null_ptr
    if (allocated(mesh%error)) deallocate (mesh%error)
  end subroutine bodt_mesh_destroy

  ! The handle counts from index_base (default 1, where C reads 0-based).
  subroutine bodt_mesh_read(path, mesh, index_base, ierr)
    character(len=*), intent(in) :: path
    type(bodt_mesh_t), intent(out) :: mesh
    integer(c_int), intent(in), optional :: index_base
    integer(c_int), intent(out), optional :: ierr
    call read_file('bodt_mesh_read', path, BODT_FORMAT_AUTO, BODT_CREATE_DEFAULT, mesh, index_base, ierr)
  end subroutine bodt_mesh_read

  subroutine bodt_mesh_read_ex(path, flags, mesh, index_base, ierr)
    character(len=*), intent(in) :: path
    integer(c_int32_t), intent(in) :: flags
    type(bodt_mesh_t), intent(out) :: mesh
    integer(c_int), intent(in), optional :: index_base
    integer(c_int), intent(out), optional :: ierr
    call read_file('bodt_mesh_read_ex', path, BODT_FORMAT_AUTO, flags, mesh, index_base, ierr)
  end subroutine bodt_mesh_read_ex

  subroutine bodt_mesh_read_format(path, format, flags, mesh, index_base, ierr)
    character(len=*), intent(in) :: path
    integer(c_int), intent(in) :: format
    integer(c_int32_t), intent(in) :: flags
    type(bodt_mesh_t), intent(out) :: mesh
    integer(c_int), intent(in), optional :: index_base
    integer(c_int), intent(out), optional :: ierr
    call read_file('bodt_mesh_read_format', path, format, flags, mesh, index_base, ierr)
  end subroutine bodt_mesh_read_format

  ! Base 1 is BODT_CREATE_ONE_BASED; any base but 0 and 1 is refused here, as
  ! bodt_mesh_create refuses it.  Without index_base the base is 1, but with
  ! BODT_CREATE_FILE_BASE the file's (bodt_mesh_get_index_base tells which).
  subroutine read_file(name, path, format, flags, mesh, index_base, ierr)
    character(len=*), intent(in) :: name, path
    integer(c_int), intent(in) :: format
    integer(c_int32_t), intent(in) :: flags
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in), optional :: index_base
    integer(c_int), intent(out), optional :: ierr
    logical :: one_based
    character(len=12) :: text
    one_based = iand(flags, BODT_CREATE_FILE_BASE) == 0
    if (present(index_base)) then
      if (index_base /= 0 .and. index_base /= 1) then
        write (text, '(i0)') index_base
        call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, 'index_base is ' // trim(text) // ', not 0 or 1')
        return
      end if
      one_based = index_base == 1
    end if
    call finish(c_bodt_mesh_read_format(c_path(path), format, &
                                        merge(ior(flags, BODT_CREATE_ONE_BASED), flags, one_based), mesh%ptr), &
                name, mesh, ierr)
  end subroutine read_file

  subroutine bodt_mesh_write(mesh, path, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    character(len=*), intent(in) :: path
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_write_format(mesh%ptr, c_path(path), BODT_FORMAT_AUTO), 'bodt_mesh_write', mesh, ierr)
  end subroutine bodt_mesh_write

  ! The BODT_FORMAT_* that path's extension names; the message of a failure
  ! in bodt_mesh_last_error().
  subroutine bodt_format_from_path(path, format, ierr)
    character(len=*), intent(in) :: path
    integer(c_int), intent(out) :: format
    integer(c_int), intent(out), optional :: ierr
    type(bodt_mesh_t) :: none
    call finish(c_bodt_format_from_path(c_path(path), format), 'bodt_format_from_path', none, ierr)
  end subroutine bodt_format_from_path

  subroutine bodt_mesh_write_format(mesh, path, format, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    character(len=*), intent(in) :: path
    integer(c_int), intent(in) :: format
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_write_format(mesh%ptr, c_path(path), format), 'bodt_mesh_write_format', mesh, ierr)
  end subroutine bodt_mesh_write_format

  ! ---------------------------------------------------- optional mesh data

  ! values(ntets) or values(nverts), named `label` in the refusal of
  ! another size, to the C setter `set`.
  subroutine set_ints(set, name, label, per_tet, mesh, values, ierr)
    procedure(c_set_ints) :: set
    character(len=*), intent(in) :: name, label
    logical, intent(in) :: per_tet
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: values(:)
    integer(c_int), intent(out), optional :: ierr
    integer(c_int32_t) :: nverts, ntets
    character(len=80) :: text
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, nverts, ntets)
    if (status == BODT_OK .and. size(values) /= merge(ntets, nverts, per_tet)) then
      if (per_tet) then
        write (text, '(2a, i0, a, i0, a)') label, ' has ', size(values), ' values for ', ntets, ' tets'
      else
        write (text, '(2a, i0, a, i0, a)') label, ' has ', size(values), ' values for ', nverts, ' vertices'
      end if
      call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, trim(text))
    else
      if (status == BODT_OK) status = set(mesh%ptr, values)
      call finish(status, name, mesh, ierr)
    end if
  end subroutine set_ints

  ! One region id per tet.
  subroutine bodt_mesh_set_regions(mesh, region_ids, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: region_ids(:)
    integer(c_int), intent(out), optional :: ierr
    call set_ints(c_bodt_mesh_set_regions, 'bodt_mesh_set_regions', 'region_ids', .true., mesh, region_ids, ierr)
  end subroutine bodt_mesh_set_regions

  ! triangles(3, nfaces); markers(nfaces), absent: every face gets 1.
  subroutine bodt_mesh_set_boundary_faces(mesh, triangles, markers, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: triangles(:, :)
    integer(c_int32_t), intent(in), optional :: markers(:)
    integer(c_int), intent(out), optional :: ierr
    character(len=*), parameter :: name = 'bodt_mesh_set_boundary_faces'
    if (size(triangles, 1) /= 3) then
      call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, &
                  shape_text('triangles', shape(triangles)) // ', not (3, nfaces)')
      return
    end if
    if (present(markers)) then
      if (size(markers) /= size(triangles, 2)) then
        call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, &
                    shape_text('triangles', shape(triangles)) // ', but markers has another number of faces')
        return
      end if
    end if
    call finish(c_bodt_mesh_set_boundary_faces(mesh%ptr, size(triangles, 2), triangles, markers), name, mesh, ierr)
  end subroutine bodt_mesh_set_boundary_faces

  subroutine bodt_mesh_set_fixed_vertices(mesh, vertices, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: vertices(:)
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_set_fixed_vertices(mesh%ptr, size(vertices), vertices), &
                'bodt_mesh_set_fixed_vertices', mesh, ierr)
  end subroutine bodt_mesh_set_fixed_vertices

  ! edges(2, nedges).
  subroutine bodt_mesh_set_feature_edges(mesh, edges, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: edges(:, :)
    integer(c_int), intent(out), optional :: ierr
    call set_feature_edges('bodt_mesh_set_feature_edges', mesh, edges, ierr=ierr)
  end subroutine bodt_mesh_set_feature_edges

  ! edges(2, nedges); refs(nedges), absent: every ref 0.
  subroutine bodt_mesh_set_feature_edges_ex(mesh, edges, refs, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: edges(:, :)
    integer(c_int32_t), intent(in), optional :: refs(:)
    integer(c_int), intent(out), optional :: ierr
    call set_feature_edges('bodt_mesh_set_feature_edges_ex', mesh, edges, refs, ierr)
  end subroutine bodt_mesh_set_feature_edges_ex

  subroutine set_feature_edges(name, mesh, edges, refs, ierr)
    character(len=*), intent(in) :: name
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: edges(:, :)
    integer(c_int32_t), intent(in), optional :: refs(:)
    integer(c_int), intent(out), optional :: ierr
    if (size(edges, 1) /= 2) then
      call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, &
                  shape_text('edges', shape(edges)) // ', not (2, nedges)')
      return
    end if
    if (present(refs)) then
      if (size(refs) /= size(edges, 2)) then
        call finish(BODT_ERR_INVALID_ARGUMENT, name, mesh, ierr, &
                    shape_text('edges', shape(edges)) // ', but refs has another number of edges')
        return
      end if
    end if
    call finish(c_bodt_mesh_set_feature_edges_ex(mesh%ptr, size(edges, 2), edges, refs), name, mesh, ierr)
  end subroutine set_feature_edges

  subroutine bodt_mesh_set_corners(mesh, vertices, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: vertices(:)
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_set_corners(mesh%ptr, size(vertices), vertices), 'bodt_mesh_set_corners', mesh, ierr)
  end subroutine bodt_mesh_set_corners

  ! One ref per vertex.
  subroutine bodt_mesh_set_vertex_refs(mesh, refs, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: refs(:)
    integer(c_int), intent(out), optional :: ierr
    call set_ints(c_bodt_mesh_set_vertex_refs, 'bodt_mesh_set_vertex_refs', 'refs', .false., mesh, refs, ierr)
  end subroutine bodt_mesh_set_vertex_refs


  ! -------------------------------------------------------------- getters
  ! Each getter allocates its arrays to the sizes bodt_mesh_get_counts gives.

  subroutine bodt_mesh_get_counts(mesh, nverts, ntets, nboundary_faces, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(out), optional :: nverts, ntets, nboundary_faces
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_get_counts(mesh%ptr, nverts, ntets, nboundary_faces), 'bodt_mesh_get_counts', mesh, ierr)
  end subroutine bodt_mesh_get_counts

  ! points(3, nverts).
  subroutine bodt_mesh_get_vertices(mesh, points, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    real(c_double), allocatable, intent(out) :: points(:, :)
    integer(c_int), intent(out), optional :: ierr
    integer(c_int32_t) :: nverts
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, nverts=nverts)
    if (status == BODT_OK) then
      allocate (points(3, nverts))
      status = c_bodt_mesh_get_vertices(mesh%ptr, points, size(points, kind=c_size_t))
    end if
    call finish(status, 'bodt_mesh_get_vertices', mesh, ierr)
  end subroutine bodt_mesh_get_vertices

  ! tets(4, ntets).
  subroutine bodt_mesh_get_tets(mesh, tets, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: tets(:, :)
    integer(c_int), intent(out), optional :: ierr
    integer(c_int32_t) :: ntets
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, ntets=ntets)
    if (status == BODT_OK) then
      allocate (tets(4, ntets))
      status = c_bodt_mesh_get_tets(mesh%ptr, tets, size(tets, kind=c_size_t))
    end if
    call finish(status, 'bodt_mesh_get_tets', mesh, ierr)
  end subroutine bodt_mesh_get_tets

  ! values(ntets) or values(nverts) from the C getter `get`.
  subroutine get_ints(get, name, per_tet, mesh, values, ierr)
    procedure(c_get_ints) :: get
    character(len=*), intent(in) :: name
    logical, intent(in) :: per_tet
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: values(:)
    integer(c_int), intent(out), optional :: ierr
    integer(c_int32_t) :: nverts, ntets
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, nverts, ntets)
    if (status == BODT_OK) then
      allocate (values(merge(ntets, nverts, per_tet)))
      status = get(mesh%ptr, values, size(values, kind=c_size_t))
    end if
    call finish(status, name, mesh, ierr)
  end subroutine get_ints

  ! region_ids(ntets).
  subroutine bodt_mesh_get_regions(mesh, region_ids, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: region_ids(:)
    integer(c_int), intent(out), optional :: ierr
    call get_ints(c_bodt_mesh_get_regions, 'bodt_mesh_get_regions', .true., mesh, region_ids, ierr)
  end subroutine bodt_mesh_get_regions

  ! triangles(3, nboundary_faces), markers(nboundary_faces); either may be
  ! left out.
  subroutine bodt_mesh_get_boundary_faces(mesh, triangles, markers, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, target, intent(out), optional :: triangles(:, :), markers(:)
    integer(c_int), intent(out), optional :: ierr
    type(c_ptr) :: c_triangles, c_markers
    integer(c_int32_t) :: nfaces
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, nboundary_faces=nfaces)
    if (status == BODT_OK) then
      c_triangles = c_null_ptr
      if (present(triangles)) then
        allocate (triangles(3, nfaces))
        c_triangles = c_loc(triangles)
      end if
      c_markers = c_null_ptr
      if (present(markers)) then
        allocate (markers(nfaces))
        c_markers = c_loc(markers)
      end if
      status = c_bodt_mesh_get_boundary_faces(mesh%ptr, c_triangles, c_markers, int(nfaces, c_size_t))
    end if
    call finish(status, 'bodt_mesh_get_boundary_faces', mesh, ierr)
  end subroutine bodt_mesh_get_boundary_faces

  ! is_fixed(nverts): 1 where the caller fixed the vertex, else 0.
  subroutine bodt_mesh_get_fixed_vertices(mesh, is_fixed, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: is_fixed(:)
    integer(c_int), intent(out), optional :: ierr
    call get_ints(c_bodt_mesh_get_fixed_vertices, 'bodt_mesh_get_fixed_vertices', .false., mesh, is_fixed, ierr)
  end subroutine bodt_mesh_get_fixed_vertices

  ! edges(2, nedges): the caller's feature edges, sorted.
  subroutine bodt_mesh_get_feature_edges(mesh, edges, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: edges(:, :)
    integer(c_int), intent(out), optional :: ierr
    call get_feature_edges('bodt_mesh_get_feature_edges', mesh, edges, ierr=ierr)
  end subroutine bodt_mesh_get_feature_edges

  ! edges(2, nedges) and refs(nedges); refs may be left out.
  subroutine bodt_mesh_get_feature_edges_ex(mesh, edges, refs, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: edges(:, :)
    integer(c_int32_t), allocatable, intent(out), optional :: refs(:)
    integer(c_int), intent(out), optional :: ierr
    call get_feature_edges('bodt_mesh_get_feature_edges_ex', mesh, edges, refs, ierr)
  end subroutine bodt_mesh_get_feature_edges_ex

  subroutine get_feature_edges(name, mesh, edges, refs, ierr)
    character(len=*), intent(in) :: name
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: edges(:, :)
    integer(c_int32_t), allocatable, intent(out), optional :: refs(:)
    integer(c_int), intent(out), optional :: ierr
    integer(c_int32_t) :: nedges
    integer(c_int) :: status
    status = c_bodt_mesh_get_feature_edges_ex(mesh%ptr, nedges, capacity=0_c_size_t)
    if (status == BODT_OK) then
      allocate (edges(2, nedges))
      if (present(refs)) then
        allocate (refs(nedges))
        status = c_bodt_mesh_get_feature_edges_ex(mesh%ptr, nedges, edges, refs, size(edges, 2, kind=c_size_t))
      else
        status = c_bodt_mesh_get_feature_edges_ex(mesh%ptr, nedges, edges, capacity=size(edges, 2, kind=c_size_t))
      end if
    end if
    call finish(status, name, mesh, ierr)
  end subroutine get_feature_edges

  ! is_corner(nverts): 1 where the caller made the vertex a corner, else 0.
  subroutine bodt_mesh_get_corners(mesh, is_corner, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: is_corner(:)
    integer(c_int), intent(out), optional :: ierr
    call get_ints(c_bodt_mesh_get_corners, 'bodt_mesh_get_corners', .false., mesh, is_corner, ierr)
  end subroutine bodt_mesh_get_corners

  ! refs(nverts).
  subroutine bodt_mesh_get_vertex_refs(mesh, refs, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: refs(:)
    integer(c_int), intent(out), optional :: ierr
    call get_ints(c_bodt_mesh_get_vertex_refs, 'bodt_mesh_get_vertex_refs', .false., mesh, refs, ierr)
  end subroutine bodt_mesh_get_vertex_refs

  ! 1 for a handle created or read with the default index_base.
  subroutine bodt_mesh_get_index_base(mesh, index_base, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(out) :: index_base
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_get_index_base(mesh%ptr, index_base), 'bodt_mesh_get_index_base', mesh, ierr)
  end subroutine bodt_mesh_get_index_base

  ! classes(nverts), BODT_VERTEX_* values.
  subroutine bodt_mesh_get_vertex_classes(mesh, classes, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: classes(:)
    integer(c_int), intent(out), optional :: ierr
    call get_ints(c_bodt_mesh_get_vertex_classes, 'bodt_mesh_get_vertex_classes', .false., mesh, classes, ierr)
  end subroutine bodt_mesh_get_vertex_classes

  subroutine bodt_mesh_get_parent_count(mesh, count, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int64_t), intent(out) :: count
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_get_parent_count(mesh%ptr, count), 'bodt_mesh_get_parent_count', mesh, ierr)
  end subroutine bodt_mesh_get_parent_count

  ! offsets(nverts + 1), counted from 0 as in C: the parents of vertex v
  ! are parents(offsets(v) + 1 : offsets(v + 1)), with their weights.
  subroutine bodt_mesh_get_vertex_parents(mesh, offsets, parents, weights, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int64_t), allocatable, intent(out) :: offsets(:)
    integer(c_int32_t), allocatable, intent(out) :: parents(:)
    real(c_double), allocatable, intent(out) :: weights(:)
    integer(c_int), intent(out), optional :: ierr
    integer(c_int32_t) :: nverts
    integer(c_int64_t) :: count
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, nverts=nverts)
    if (status == BODT_OK) status = c_bodt_mesh_get_parent_count(mesh%ptr, count)
    if (status == BODT_OK) then
      allocate (offsets(nverts + 1), parents(count), weights(count))
      status = c_bodt_mesh_get_vertex_parents(mesh%ptr, offsets, size(offsets, kind=c_size_t), parents, weights, &
                                              size(parents, kind=c_size_t))
    end if
    call finish(status, 'bodt_mesh_get_vertex_parents', mesh, ierr)
  end subroutine bodt_mesh_get_vertex_parents

  ! origins(ntets): input tet indices.
  subroutine bodt_mesh_get_tet_origins(mesh, origins, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: origins(:)
    integer(c_int), intent(out), optional :: ierr
    call get_ints(c_bodt_mesh_get_tet_origins, 'bodt_mesh_get_tet_origins', .true., mesh, origins, ierr)
  end subroutine bodt_mesh_get_tet_origins

  ! -------------------------------------------------------------- quality

  ! edges(BODT_DIHEDRAL_BINS + 1), degrees.
  subroutine bodt_dihedral_bin_edges(edges, ierr)
    real(c_double), allocatable, intent(out) :: edges(:)
    integer(c_int), intent(out), optional :: ierr
    type(bodt_mesh_t) :: none
    allocate (edges(BODT_DIHEDRAL_BINS + 1))
    call finish(c_bodt_dihedral_bin_edges(edges, size(edges, kind=c_size_t)), 'bodt_dihedral_bin_edges', none, ierr)
  end subroutine bodt_dihedral_bin_edges

  subroutine bodt_mesh_quality(mesh, quality, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    type(bodt_quality), intent(out) :: quality
    integer(c_int), intent(out), optional :: ierr
    quality%size = c_sizeof(quality)
    call finish(c_bodt_mesh_quality(mesh%ptr, quality), 'bodt_mesh_quality', mesh, ierr)
  end subroutine bodt_mesh_quality

  ! values(ntets) of one BODT_MEASURE_*.
  subroutine bodt_mesh_tet_quality(mesh, measure, values, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in) :: measure
    real(c_double), allocatable, intent(out) :: values(:)
    integer(c_int), intent(out), optional :: ierr
    integer(c_int32_t) :: ntets
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, ntets=ntets)
    if (status == BODT_OK) then
      allocate (values(ntets))
      status = c_bodt_mesh_tet_quality(mesh%ptr, measure, values, size(values, kind=c_size_t))
    end if
    call finish(status, 'bodt_mesh_tet_quality', mesh, ierr)
  end subroutine bodt_mesh_tet_quality

  ! ------------------------------------------------------ modes and params

  subroutine bodt_set_mode(mesh, mode, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in) :: mode
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_set_mode(mesh%ptr, mode), 'bodt_set_mode', mesh, ierr)
  end subroutine bodt_set_mode

  subroutine bodt_get_mode(mesh, mode, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(out) :: mode
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_get_mode(mesh%ptr, mode), 'bodt_get_mode', mesh, ierr)
  end subroutine bodt_get_mode

  subroutine bodt_set_param_int(mesh, key, value, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in) :: key
    integer(c_int32_t), intent(in) :: value
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_set_param_int(mesh%ptr, key, value), 'bodt_set_param_int', mesh, ierr)
  end subroutine bodt_set_param_int

  subroutine bodt_set_param_double(mesh, key, value, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in) :: key
    real(c_double), intent(in) :: value
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_set_param_double(mesh%ptr, key, value), 'bodt_set_param_double', mesh, ierr)
  end subroutine bodt_set_param_double

  subroutine bodt_get_param_int(mesh, key, value, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in) :: key
    integer(c_int32_t), intent(out) :: value
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_get_param_int(mesh%ptr, key, value), 'bodt_get_param_int', mesh, ierr)
  end subroutine bodt_get_param_int

  subroutine bodt_get_param_double(mesh, key, value, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int), intent(in) :: key
    real(c_double), intent(out) :: value
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_get_param_double(mesh%ptr, key, value), 'bodt_get_param_double', mesh, ierr)
  end subroutine bodt_get_param_double

  ! ---------------------------------------------------------- improvement

  subroutine bodt_step(mesh, report, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    type(bodt_step_report), intent(out), optional :: report
    integer(c_int), intent(out), optional :: ierr
    if (present(report)) report%size = c_sizeof(report)
    call finish(c_bodt_step(mesh%ptr, report), 'bodt_step', mesh, ierr)
  end subroutine bodt_step

  ! callback: a bind(c) function of interface bodt_step_callback, given
  ! user_data (say c_loc of a target variable) after each step.
  subroutine bodt_run(mesh, max_steps, callback, user_data, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: max_steps
    procedure(bodt_step_callback), optional :: callback
    type(c_ptr), intent(in), optional :: user_data
    integer(c_int), intent(out), optional :: ierr
    type(c_funptr) :: c_callback
    type(c_ptr) :: c_user_data
    c_callback = c_null_funptr
    if (present(callback)) c_callback = c_funloc(callback)
    c_user_data = c_null_ptr
    if (present(user_data)) c_user_data = user_data
    call finish(c_bodt_run(mesh%ptr, max_steps, c_callback, c_user_data), 'bodt_run', mesh, ierr)
  end subroutine bodt_run

  ! ------------------------------------- geometry and reference (paper 002)

  subroutine bodt_mesh_get_geometry_counts(mesh, nregions, nchains, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(out), optional :: nregions, nchains
    integer(c_int), intent(out), optional :: ierr
    call finish(c_bodt_mesh_get_geometry_counts(mesh%ptr, nregions, nchains), 'bodt_mesh_get_geometry_counts', &
                mesh, ierr)
  end subroutine bodt_mesh_get_geometry_counts

  ! classes(nverts), BODT_GEOMETRY_* values.
  subroutine bodt_mesh_get_geometry_classes(mesh, classes, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, intent(out) :: classes(:)
    integer(c_int), intent(out), optional :: ierr
    call get_ints(c_bodt_mesh_get_geometry_classes, 'bodt_mesh_get_geometry_classes', .false., mesh, classes, ierr)
  end subroutine bodt_mesh_get_geometry_classes

  ! region_ids(nboundary_faces), shapes(nboundary_faces); either may be
  ! left out.
  subroutine bodt_mesh_get_face_regions(mesh, region_ids, shapes, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), allocatable, target, intent(out), optional :: region_ids(:), shapes(:)
    integer(c_int), intent(out), optional :: ierr
    type(c_ptr) :: c_region_ids, c_shapes
    integer(c_int32_t) :: nfaces
    integer(c_int) :: status
    status = c_bodt_mesh_get_counts(mesh%ptr, nboundary_faces=nfaces)
    if (status == BODT_OK) then
      c_region_ids = c_null_ptr
      if (present(region_ids)) then
        allocate (region_ids(nfaces))
        c_region_ids = c_loc(region_ids)
      end if
      c_shapes = c_null_ptr
      if (present(shapes)) then
        allocate (shapes(nfaces))
        c_shapes = c_loc(shapes)
      end if
      status = c_bodt_mesh_get_face_regions(mesh%ptr, c_region_ids, c_shapes, int(nfaces, c_size_t))
    end if
    call finish(status, 'bodt_mesh_get_face_regions', mesh, ierr)
  end subroutine bodt_mesh_get_face_regions

  subroutine bodt_mesh_get_region_shape(mesh, region, fit, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    integer(c_int32_t), intent(in) :: region
    type(bodt_shape_fit), intent(out) :: fit
    integer(c_int), intent(out), optional :: ierr
    fit%size = c_sizeof(fit)
    call finish(c_bodt_mesh_get_region_shape(mesh%ptr, region, fit), 'bodt_mesh_get_region_shape', mesh, ierr)
  end subroutine bodt_mesh_get_region_shape

  ! Without reference: clears it.
  subroutine bodt_set_reference_mesh(mesh, reference, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    type(bodt_mesh_t), intent(in), optional :: reference
    integer(c_int), intent(out), optional :: ierr
    type(c_ptr) :: c_reference
    c_reference = c_null_ptr
    if (present(reference)) c_reference = reference%ptr
    call finish(c_bodt_set_reference_mesh(mesh%ptr, c_reference), 'bodt_set_reference_mesh', mesh, ierr)
  end subroutine bodt_set_reference_mesh

  ! values(nx, ny, nz): the grid's dims are its shape (x fastest, as in C).
  ! Without values: clears the density.
  subroutine bodt_set_target_density(mesh, origin, spacing, values, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    real(c_double), intent(in), optional :: origin(3), spacing(3)
    real(c_double), intent(in), optional :: values(:, :, :)
    integer(c_int), intent(out), optional :: ierr
    if (present(values)) then
      call finish(c_bodt_set_target_density(mesh%ptr, origin, spacing, shape(values, kind=c_int32_t), values), &
                  'bodt_set_target_density', mesh, ierr)
    else
      call finish(c_bodt_set_target_density(mesh%ptr, origin, spacing), 'bodt_set_target_density', mesh, ierr)
    end if
  end subroutine bodt_set_target_density

  subroutine bodt_mesh_recovery_error(mesh, error, ierr)
    type(bodt_mesh_t), intent(inout) :: mesh
    type(bodt_recovery_error), intent(out) :: error
    integer(c_int), intent(out), optional :: ierr
    error%size = c_sizeof(error)
    call finish(c_bodt_mesh_recovery_error(mesh%ptr, error), 'bodt_mesh_recovery_error', mesh, ierr)
  end subroutine bodt_mesh_recovery_error

end module bodt
