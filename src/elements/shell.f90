module superjoin_elements_shell
  !! Plane-stress elements CPS3/CPS4 and plane-strain elements CPE3/CPE4 (XY
  !! plane, DOFs 1, 2, the same elements with another elasticity matrix), their
  !! second-order relatives CPS6/CPS8/CPS8R and CPE6/CPE8/CPE8R
  !! (superjoin_elements_quadratic), and flat shells
  !! S3/S4 (DOFs 1-6): the element frame, the membrane (superjoin_elements_membrane)
  !! and plate bending (superjoin_elements_plate) parts put together, rotated
  !! to global axes. The thick shells S4R/S3R are the same with the thin plate
  !! replaced by the Reissner-Mindlin MITC4/MITC3 plate (superjoin_elements_mindlin),
  !! with the transverse shear stiffness of the section (shear_k, K11 and K22 of
  !! *TRANSVERSE SHEAR STIFFNESS) or 5/6 G t.
  !!
  !! Element frame (deck contract, section 8): local z is the normal by the
  !! right-hand rule on the node order (S4: along the cross product of the
  !! diagonals), local x runs from node 1 towards node 2 in the plane, y = z × x.
  !! A warped S4 is projected onto its mean plane (through the centroid, normal
  !! to the diagonals); the flat element acts on the projected points, which are
  !! tied to the real nodes by rigid offsets h along the normal (rigid-link warp
  !! correction: u_p = u + θ × (-h n)).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, ET_CPS3, ET_CPS4, ET_S3, ET_S4, &
       ET_CPE3, ET_CPE4, ELEMENT_NODE_COUNT, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R
  use superjoin_model_types, only: ET_S4R, ET_S3R
  use superjoin_model_types, only: ET_S8R, ET_S8, ET_S6
  use superjoin_elements_traits, only: is_shell8
  use superjoin_elements_shell8, only: shell8_props_t, shell8_stiffness, shell8_resultants, shell8_area_shares, &
       shell8_pressure_load
  use superjoin_elements_shell8, only: shell8_stresses, shell8_surface_load
  use superjoin_elements_traction, only: surface_load_t, point_force
  use superjoin_elements_membrane, only: membrane_stiffness, membrane_drill_stiffness, membrane_resultants, &
       plane_strain_stiffness, plane_strain_resultants
  use superjoin_elements_plate, only: plate_stiffness, plate_moments, plate_pressure_load, plate_moment_operator
  use superjoin_elements_plate, only: plate_point_moments
  use superjoin_elements_membrane, only: membrane_point_stresses, initial_strain_t, membrane_forces, make_symmetric
  use superjoin_elements_frame, only: cross
  use superjoin_elements_quadratic, only: plane_props_t, quadratic_stiffness, quadratic_resultants, &
       quadratic_shape_integrals
  use superjoin_elements_mindlin, only: mindlin_stiffness, mindlin_resultants, default_shear_stiffness
  use superjoin_elements_mindlin, only: mindlin_point_resultants
  use superjoin_elements_drilling, only: drilling_stiffness, drilling_resultants, drilling_point_stresses, &
       drilling_result_operator
  use superjoin_elements_opt_triangle, only: opt_stiffness, opt_resultants, opt_point_stresses, opt_thermal_load

  use superjoin_elements_drilling, only: drilling_thermal_load, drilling_thermal_stresses
  use superjoin_elements_membrane, only: membrane_thermal_load, membrane_result_operator
  use superjoin_elements_plate, only: plate_thermal_load, corner_functions, bending_rigidity
  use superjoin_elements_mindlin, only: mindlin_thermal_load
  implicit none (type, external)
  private

  public :: is_thick_shell_type, shell_shear_stiffness, quadratic_props
  public :: is_plate_type, is_plane_type, is_plane_strain_type, is_quadratic_plane_type, shell_frame, shell_stiffness, shell_resultants, shell_forces, shell_pressure_load, &
       shell_result_operator, &
       shell_area_load, shell_traction_load
  public :: shell_surface_stresses, thick_shell_stresses, THICK_SURFACES
  public :: has_drilling_membrane, drilling_edges, DRILL_ALL_EDGES
  public :: s8r_stresses
  public :: shell8_props
  public :: shell_thermal_nodal_load, shell_thermal_nodal_resultants, shell_thermal_nodal_stresses

  integer, parameter :: MEMBRANE_DOFS(3) = [1, 2, 6]
    !! Local shell DOFs (u, v, w, θx, θy, θz) of the membrane (u, v, θz).
  integer, parameter :: PLATE_DOFS(3) = [3, 4, 5]
    !! Local shell DOFs of plate bending (w, θx, θy).
  integer, parameter :: THICK_SURFACES = 3
    !! Section points of thick_shell_stresses: 1 bottom, 2 top, 3 mid-surface.
  real(wp), parameter :: PARABOLIC_SHEAR_PEAK = 1.5_wp
    !! τ(z = 0) = 1.5 q / t, the peak of the parabolic transverse shear stress of a homogeneous section.
  integer, parameter :: DRILLING_MEMBRANE_TYPES(*) = [ET_S4, ET_S4R, ET_S3, ET_S3R]
    !! Shell types with the drilling membrane (has_drilling_membrane): S4 and
    !! S4R take the Ibrahimbegovic-Taylor-Wilson membrane of
    !! superjoin_elements_drilling with the edge bubbles of flat, unrestrained
    !! edges only (superjoin_elements_drill_mask; with bubbles on every edge
    !! the coarse pinched hemisphere locks, 4x4: 0.479 against QM6's 1.042);
    !! an element without any is QM6 with soft drilling springs. S3 and S3R
    !! take Felippa's OPT triangle (superjoin_elements_opt_triangle) with the
    !! α_b terms of the same edges, the CST with soft drilling springs when
    !! none of its edges qualifies (doc/verification.md, "Drilling membranes").
  integer, parameter :: DRILL_ALL_EDGES = 15
    !! Edge mask of a drilling membrane with every edge's bubble (bit k - 1:
    !! edge k from node k to k + 1); the default of the optional `drill`
    !! arguments below (superjoin_elements_drill_mask computes the mask of
    !! each element of a mesh).
  real(wp), parameter :: PLANE_TOL = 1.0e-8_wp
    !! Largest |z| spread of a plane-stress element relative to its size.

  type :: shell_local_t
    !! A three- or four-node shell in its own frame, as its stress routines share it.
     real(wp) :: r(3, 3) = 0.0_wp         !! element frame (rows: local x, y, z)
     real(wp), allocatable :: xl(:, :)    !! (2, n) local coordinates
     real(wp), allocatable :: ub(:)       !! (3n) plate DOFs w, θx, θy per node, local axes
  end type shell_local_t

contains

  elemental logical function is_plate_type(etype)
    !! True for the plane (stress and strain) and shell element types.
    integer, intent(in) :: etype
    is_plate_type = is_plane_type(etype) .or. etype == ET_S3 .or. etype == ET_S4 .or. is_thick_shell_type(etype) &
         .or. is_shell8(etype)
  end function is_plate_type

  elemental logical function has_drilling_membrane(etype)
    !! True for the shells whose membrane is the drilling-rotation element of
    !! superjoin_elements_drilling (Allman triangle, Ibrahimbegovic-Taylor-Wilson
    !! quadrilateral) instead of the CST / QM6 with soft drilling springs.
    integer, intent(in) :: etype
    has_drilling_membrane = any(etype == DRILLING_MEMBRANE_TYPES)
  end function has_drilling_membrane

  pure function drilling_edges(etype, n, drill) result(edges)
    !! The edges of an n-node element of type etype whose bubble the drilling
    !! membrane carries under the edge mask drill (absent: DRILL_ALL_EDGES);
    !! all false unless has_drilling_membrane(etype). An element without any
    !! is the CST / QM6 with soft drilling springs.
    integer, intent(in) :: etype, n
    integer, intent(in), optional :: drill
    logical :: edges(n)
    integer :: mask, k
    mask = DRILL_ALL_EDGES
    if (present(drill)) mask = drill
    do k = 1, n
       edges(k) = has_drilling_membrane(etype) .and. btest(mask, k - 1)
    end do
  end function drilling_edges

  elemental logical function is_thick_shell_type(etype)
    !! True for the thick (Reissner-Mindlin) shells S4R, S3R.
    integer, intent(in) :: etype
    is_thick_shell_type = etype == ET_S4R .or. etype == ET_S3R
  end function is_thick_shell_type

  pure function shell_shear_stiffness(sec, mat) result(ks)
    !! Transverse shear stiffness per unit length of a thick shell along its
    !! local x, y: the section's K11, K22 (*TRANSVERSE SHEAR STIFFNESS) when
    !! given, else 5/6 G t.
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp) :: ks(2)
    if (all(sec%shear_k > 0.0_wp)) then
       ks = sec%shear_k
    else
       ks = default_shear_stiffness(sec%thickness, mat%e, mat%nu)
    end if
  end function shell_shear_stiffness

  elemental logical function is_plane_type(etype)
    !! True for the plane-stress (CPS3, CPS4, CPS6, CPS8, CPS8R) and plane-strain
    !! (CPE3, CPE4, CPE6, CPE8, CPE8R) types.
    integer, intent(in) :: etype
    is_plane_type = etype == ET_CPS3 .or. etype == ET_CPS4 .or. etype == ET_CPE3 .or. etype == ET_CPE4 &
         .or. is_quadratic_plane_type(etype)
  end function is_plane_type

  elemental logical function is_plane_strain_type(etype)
    !! True for the plane-strain types CPE3, CPE4, CPE6, CPE8, CPE8R.
    integer, intent(in) :: etype
    select case (etype)
    case (ET_CPE3, ET_CPE4, ET_CPE6, ET_CPE8, ET_CPE8R)
       is_plane_strain_type = .true.
    case default
       is_plane_strain_type = .false.
    end select
  end function is_plane_strain_type

  elemental logical function is_quadratic_plane_type(etype)
    !! True for the second-order plane types CPS6, CPS8, CPS8R, CPE6, CPE8, CPE8R.
    integer, intent(in) :: etype
    select case (etype)
    case (ET_CPS6, ET_CPS8, ET_CPS8R, ET_CPE6, ET_CPE8, ET_CPE8R)
       is_quadratic_plane_type = .true.
    case default
       is_quadratic_plane_type = .false.
    end select
  end function is_quadratic_plane_type

  pure function quadratic_props(etype, sec, mat) result(props)
    !! Data of a second-order plane element.
    integer, intent(in) :: etype
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(plane_props_t) :: props
    props = plane_props_t(t=sec%thickness, e=mat%e, nu=mat%nu, strain=is_plane_strain_type(etype), &
         reduced=etype == ET_CPS8R .or. etype == ET_CPE8R)
  end function quadratic_props

  pure subroutine shell_frame(x, r, xl, h, error)
    !! Element frame of a 3- or 4-node element with nodes x(3, n): rows of r
    !! are the local x, y, z axes; xl(2, n) the local coordinates of the nodes
    !! projected onto the mean plane, h(n) their offsets along z (0 unless warped).
    !! A 6- or 8-node element takes the frame of its corners (the first 3 or 4 nodes).
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: r(3, 3)
    real(wp), intent(out) :: xl(2, size(x, 2)), h(size(x, 2))
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: c(3), nrm(3), p(3, size(x, 2)), ex(3), size_e
    integer :: n, i
    logical :: flat
    n = size(x, 2)
    r = 0.0_wp
    xl = 0.0_wp
    h = 0.0_wp
    if (n == 4 .or. n == 8) then
       nrm = cross(x(:, 3) - x(:, 1), x(:, 4) - x(:, 2))
    else
       nrm = cross(x(:, 2) - x(:, 1), x(:, 3) - x(:, 1))
    end if
    size_e = node_extent(x, 3)
    ! |n| <= eps size², compared without squaring the size (coordinates near
    ! the top of the floating-point range would overflow)
    flat = size_e > 0.0_wp
    if (flat) flat = norm2(nrm)/size_e > epsilon(1.0_wp)*size_e
    if (.not. flat) then
       call fatal_error(error, EXIT_DECK, 'zero area (collinear or coincident nodes)')
       return
    end if
    nrm = nrm/norm2(nrm)
    c = sum(x, dim=2)/real(n, wp)
    do i = 1, n
       h(i) = dot_product(x(:, i) - c, nrm)
       p(:, i) = x(:, i) - h(i)*nrm
    end do
    if (n == 3 .or. n == 6) h = 0.0_wp
    ex = p(:, 2) - p(:, 1)
    if (norm2(ex) <= epsilon(1.0_wp)*size_e) then
       call fatal_error(error, EXIT_DECK, 'nodes 1 and 2 coincide')
       return
    end if
    ex = ex/norm2(ex)
    r(1, :) = ex
    r(3, :) = nrm
    r(2, :) = cross(nrm, ex)
    do i = 1, n
       xl(1, i) = dot_product(p(:, i) - c, r(1, :))
       xl(2, i) = dot_product(p(:, i) - c, r(2, :))
    end do
  end subroutine shell_frame

  pure subroutine shell_stiffness(etype, x, sec, mat, ke, error, drill)
    !! Stiffness in global axes, node-major: CPS3/CPS4 (ux, uy per node),
    !! S3/S4 (ux, uy, uz, rx, ry, rz per node). drill: the element's edge
    !! mask for a drilling membrane (drilling_edges; absent: every edge).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp), allocatable :: kf(:, :)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))

    if (is_shell8(etype)) then
       call setup(etype, x, r, xl, h, error)
       if (allocated(error)) return
       call shell8_stiffness(x, [r(1, 1), r(1, 2), r(1, 3)], shell8_props(sec, mat, etype), ke, error)
       return
    end if
    call flat_stiffness(etype, x, sec, mat, kf, r, xl, h, error, drilling_edges(etype, size(x, 2), drill))
    if (allocated(error)) return
    call to_global(kf, node_maps(etype, r, h), ke)
  end subroutine shell_stiffness

  pure function shell8_props(sec, mat, etype) result(props)
    !! Section and material data of an S8R or S6, or of an S8 (full integration) if etype is ET_S8.
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    integer, intent(in), optional :: etype
    type(shell8_props_t) :: props
    props = shell8_props_t(t=sec%thickness, e=mat%e, nu=mat%nu, ks=shell_shear_stiffness(sec, mat))
    if (present(etype)) props%full = etype == ET_S8
    if (allocated(sec%node_thickness)) then
       ! equal nodal thicknesses: the untapered element (its formulas, bit for bit)
       if (size(sec%node_thickness) <= size(props%tn)) then
          if (any(sec%node_thickness /= sec%node_thickness(1))) then
             props%tapered = .true.
             props%tn(1:size(sec%node_thickness)) = sec%node_thickness
          end if
       end if
    end if
  end function shell8_props

  pure subroutine shell8_forces(etype, x, sec, mat, ue, res, fg, forces, error)
    !! shell_forces of an S8R or S8: resultants at the centre (lamina frame) and K_e u_e.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:, :)
    real(wp), intent(inout) :: res(:, :), fg(:, :)
    logical, intent(in) :: forces
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ke(:, :)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), q(2)
    integer :: is
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    if (forces) then
       call shell8_stiffness(x, [r(1, 1), r(1, 2), r(1, 3)], shell8_props(sec, mat, etype), ke, error)
       if (allocated(error)) return
    end if
    do is = 1, size(ue, 2)
       if (forces) fg(:, is) = matmul(ke, ue(:, is))
       call shell8_resultants(x, [r(1, 1), r(1, 2), r(1, 3)], shell8_props(sec, mat), ue(:, is), res(:, is), q, error)
       if (allocated(error)) return
    end do
  end subroutine shell8_forces

  pure subroutine shell_forces(etype, x, sec, mat, ue, res, fg, error, with_forces, drill)
    !! For every step (columns of ue, element displacements in global axes):
    !! the resultants res(6, step) as shell_resultants, and the forces the nodes
    !! exert on the element fg(:, step) = K_e u_e (global axes), the element
    !! matrix being formed once, in the element frame. With with_forces =
    !! .false. only the resultants (fg = 0, no element matrix formed). drill
    !! as shell_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:, :)
    real(wp), intent(out) :: res(:, :), fg(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: with_forces
    integer, intent(in), optional :: drill
    real(wp), allocatable :: kf(:, :), maps(:, :, :), d(:)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    integer :: is
    logical :: forces, edges(size(x, 2))

    res = 0.0_wp
    fg = 0.0_wp
    forces = .true.
    if (present(with_forces)) forces = with_forces
    if (is_shell8(etype)) then
       call shell8_forces(etype, x, sec, mat, ue, res, fg, forces, error)
       return
    end if
    if (is_plane_type(etype) .and. .not. is_quadratic_plane_type(etype)) then
       call plane_forces(etype, x, sec, mat, ue, res, fg, forces, error)
       return
    end if
    edges = drilling_edges(etype, size(x, 2), drill)
    if (forces) then
       call flat_stiffness(etype, x, sec, mat, kf, r, xl, h, error, edges)
    else
       call setup(etype, x, r, xl, h, error)
    end if
    if (allocated(error)) return
    maps = node_maps(etype, r, h)
    ! d allocated before the loop: gfortran's reallocation check on an
    ! unallocated d reads its undefined bounds (UBSan saw the overflow).
    allocate (d(size(ue, 1)))
    do is = 1, size(ue, 2)
       d = to_local(maps, ue(:, is))
       if (forces) fg(:, is) = to_global_vector(maps, matmul(kf, d))
       call local_resultants(etype, xl, sec, mat, d, res(:, is), error, edges)
       if (allocated(error)) return
    end do
  end subroutine shell_forces

  pure subroutine plane_forces(etype, x, sec, mat, ue, res, fg, forces, error)
    !! shell_forces of a CPS3, CPS4, CPE3 or CPE4: the element frame, checks
    !! and matrices formed once for the stiffness and the resultants of all
    !! steps (membrane_forces).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:, :)
    real(wp), intent(inout) :: res(:, :), fg(:, :)
    logical, intent(in) :: forces
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: kf(:, :), maps(:, :, :), d(:, :)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    integer :: is
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    maps = node_maps(etype, r, h)
    allocate (d(size(ue, 1), size(ue, 2)))
    do is = 1, size(ue, 2)
       d(:, is) = to_local(maps, ue(:, is))
    end do
    call membrane_forces(xl, sec%thickness, mat%e, mat%nu, is_plane_strain_type(etype), d, kf, res(1:3, :), error)
    if (allocated(error) .or. .not. forces) return
    do is = 1, size(ue, 2)
       fg(:, is) = to_global_vector(maps, matmul(kf, d(:, is)))
    end do
  end subroutine plane_forces

  pure subroutine shell_result_operator(etype, x, sec, mat, op, error, drill)
    !! The resultants' operator of an element: op(6, ndof) with res = op ue
    !! for element displacements ue in global axes (shell_forces' res of one
    !! step, element_stiffness ordering), formed once for all steps and all
    !! instances of a part. The element-frame operator (local_result_operator)
    !! turned by the node maps; S8R/S8 and the second-order plane types as
    !! shell_forces of the unit displacements. drill as shell_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: op(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp), allocatable :: opl(:, :), maps(:, :, :), eye(:, :), fg(:, :)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    integer :: n, i, m
    if (is_shell8(etype) .or. is_quadratic_plane_type(etype)) then
       n = size(x, 2)*merge(2, 6, is_plane_type(etype))
       allocate (eye(n, n), source=0.0_wp)
       do i = 1, n
          eye(i, i) = 1.0_wp
       end do
       allocate (op(6, n), fg(n, n))
       call shell_forces(etype, x, sec, mat, eye, op, fg, error, with_forces=.false., drill=drill)
       return
    end if
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    call local_result_operator(etype, xl, sec, mat, drilling_edges(etype, size(x, 2), drill), opl, error)
    if (allocated(error)) return
    maps = node_maps(etype, r, h)
    m = size(maps, 1)
    allocate (op(6, size(opl, 2)))
    do i = 1, size(x, 2)
       op(:, m*(i - 1) + 1:m*i) = matmul(opl(:, m*(i - 1) + 1:m*i), maps(:, :, i))
    end do
  end subroutine shell_result_operator

  pure subroutine local_result_operator(etype, xl, sec, mat, edges, opl, error)
    !! The operator of local_resultants, opl(6, ndof) with res = opl d for the
    !! element-frame DOFs d (flat_stiffness ordering) of a 3- or 4-node plane
    !! or shell element: the membrane's (membrane_result_operator,
    !! drilling_result_operator) and the thin plate's (plate_moment_operator)
    !! put together; the thick shells and the OPT triangle as local_resultants
    !! of the unit DOFs. edges as flat_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: xl(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    logical, intent(in) :: edges(:)
    real(wp), allocatable, intent(out) :: opl(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: om(:, :), ob(:, :)
    real(wp) :: d(6*size(xl, 2))
    integer :: n, j
    n = size(xl, 2)
    if (is_plane_type(etype)) then
       call membrane_result_operator(xl, sec%thickness, mat%e, mat%nu, is_plane_strain_type(etype), om, error)
       if (allocated(error)) return
       allocate (opl(6, 2*n), source=0.0_wp)
       opl(1:3, :) = om
       return
    end if
    allocate (opl(6, 6*n), source=0.0_wp)
    if (is_thick_shell_type(etype) .or. (any(edges) .and. n == 3)) then
       do j = 1, 6*n
          d = 0.0_wp
          d(j) = 1.0_wp
          call local_resultants(etype, xl, sec, mat, d, opl(:, j), error, edges)
          if (allocated(error)) return
       end do
       return
    end if
    if (any(edges)) then
       call drilling_result_operator(xl, sec%thickness, mat%e, mat%nu, om, error, edges)
       if (allocated(error)) return
       call put_columns(om, 1, MEMBRANE_DOFS, opl)
    else
       call membrane_result_operator(xl, sec%thickness, mat%e, mat%nu, .false., om, error)
       if (allocated(error)) return
       call put_columns(om, 1, MEMBRANE_DOFS(1:2), opl)
    end if
    call plate_moment_operator(xl, sec%thickness, mat%e, mat%nu, ob, error)
    if (allocated(error)) return
    call put_columns(ob, 4, PLATE_DOFS, opl)
  end subroutine local_result_operator

  pure subroutine put_columns(part, row, dofs, opl)
    !! Rows row..row+2 of the 6-DOF-per-node operator opl from a part's
    !! operator with size(dofs) DOFs per node: its column of node i, DOF k
    !! goes to local DOF dofs(k) of node i.
    real(wp), intent(in) :: part(:, :)
    integer, intent(in) :: row, dofs(:)
    real(wp), intent(inout) :: opl(:, :)
    integer :: i, k, m
    m = size(dofs)
    do i = 1, size(part, 2)/m
       do k = 1, m
          opl(row:row + 2, 6*(i - 1) + dofs(k)) = part(:, m*(i - 1) + k)
       end do
    end do
  end subroutine put_columns

  pure subroutine shell_resultants(etype, x, sec, mat, ue, res, error, drill)
    !! Resultants per unit length at the centroid in the element frame,
    !! res = nx, ny, nxy, mx, my, mxy (plane stress: moments 0), from the
    !! element displacements ue in global axes (element_stiffness ordering);
    !! drill as shell_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: res(6)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), q(2)

    res = 0.0_wp
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    if (is_shell8(etype)) then
       call shell8_resultants(x, [r(1, 1), r(1, 2), r(1, 3)], shell8_props(sec, mat), ue, res, q, error)
       return
    end if
    call local_resultants(etype, xl, sec, mat, to_local(node_maps(etype, r, h), ue), res, error, &
         drilling_edges(etype, size(x, 2), drill))
  end subroutine shell_resultants

  pure subroutine flat_stiffness(etype, x, sec, mat, kf, r, xl, h, error, edges)
    !! The element matrix in the element frame (plane stress: u, v per node;
    !! shells: u, v, w, θx, θy, θz per node at the projected points), with the
    !! frame r, local coordinates xl and warp offsets h; edges: the bubbles of
    !! the drilling membrane (drilling_edges; none: CST / QM6 with springs).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: kf(:, :)
    real(wp), intent(out) :: r(3, 3), xl(:, :), h(:)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in) :: edges(:)
    real(wp), allocatable :: km(:, :), kb(:, :)
    integer :: n

    n = size(x, 2)
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    if (is_quadratic_plane_type(etype)) then
       call quadratic_stiffness(xl, quadratic_props(etype, sec, mat), kf, error)
       return
    end if
    if (etype == ET_CPS3 .or. etype == ET_CPS4) then
       call membrane_stiffness(xl, sec%thickness, mat%e, mat%nu, kf, error)
       return
    end if
    if (etype == ET_CPE3 .or. etype == ET_CPE4) then
       call plane_strain_stiffness(xl, sec%thickness, mat%e, mat%nu, kf, error)
       return
    end if
    if (any(edges) .and. n == 3) then
       call opt_stiffness(xl, sec%thickness, mat%e, mat%nu, km, error, edges)
    else if (any(edges)) then
       call drilling_stiffness(xl, sec%thickness, mat%e, mat%nu, km, error, edges)
    else
       call membrane_drill_stiffness(xl, sec%thickness, mat%e, mat%nu, km, error)
    end if
    if (allocated(error)) return
    if (is_thick_shell_type(etype)) then
       call mindlin_stiffness(xl, sec%thickness, mat%e, mat%nu, shell_shear_stiffness(sec, mat), kb, error)
    else
       call plate_stiffness(xl, sec%thickness, mat%e, mat%nu, kb, error)
    end if
    if (allocated(error)) return
    allocate (kf(6*n, 6*n), source=0.0_wp)
    call scatter(km, MEMBRANE_DOFS, n, kf)
    call scatter(kb, PLATE_DOFS, n, kf)
  end subroutine flat_stiffness

  pure subroutine local_resultants(etype, xl, sec, mat, d, res, error, edges)
    !! Resultants from the element-frame DOFs d (flat_stiffness ordering);
    !! edges as flat_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: xl(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: d(:)
    real(wp), intent(out) :: res(6)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in) :: edges(:)
    real(wp) :: um(2*size(xl, 2)), ub(3*size(xl, 2)), q(2), ud(3*size(xl, 2))
    integer :: i
    res = 0.0_wp
    if (is_quadratic_plane_type(etype)) then
       call quadratic_resultants(xl, quadratic_props(etype, sec, mat), d, res(1:3), error)
       return
    end if
    if (etype == ET_CPS3 .or. etype == ET_CPS4) then
       call membrane_resultants(xl, sec%thickness, mat%e, mat%nu, d, res(1:3), error)
       return
    end if
    if (etype == ET_CPE3 .or. etype == ET_CPE4) then
       call plane_strain_resultants(xl, sec%thickness, mat%e, mat%nu, d, res(1:3), error)
       return
    end if
    do i = 1, size(xl, 2)
       um(2*i - 1:2*i) = d(6*(i - 1) + MEMBRANE_DOFS(1:2))
       ud(3*i - 2:3*i) = d(6*(i - 1) + MEMBRANE_DOFS)
       ub(3*i - 2:3*i) = d(6*(i - 1) + PLATE_DOFS)
    end do
    if (any(edges) .and. size(xl, 2) == 3) then
       call opt_resultants(xl, sec%thickness, mat%e, mat%nu, ud, res(1:3), error, edges)
    else if (any(edges)) then
       call drilling_resultants(xl, sec%thickness, mat%e, mat%nu, ud, res(1:3), error, edges)
    else
       call membrane_resultants(xl, sec%thickness, mat%e, mat%nu, um, res(1:3), error)
    end if
    if (allocated(error)) return
    if (is_thick_shell_type(etype)) then
       call mindlin_resultants(xl, sec%thickness, mat%e, mat%nu, shell_shear_stiffness(sec, mat), ub, res(4:6), q, &
            error)
    else
       call plate_moments(xl, sec%thickness, mat%e, mat%nu, ub, res(4:6), error)
    end if
  end subroutine local_resultants

  pure function node_maps(etype, r, h) result(maps)
    !! Per node, the matrix taking its global DOFs to its element-frame DOFs:
    !! maps(:, :, node), 2 x 2 for plane stress, 6 x 6 for shells (rotation and
    !! rigid warp offset: u_p = u + θ × (-h e_z), i.e. u_p -= h θy, v_p += h θx).
    integer, intent(in) :: etype
    real(wp), intent(in) :: r(3, 3), h(:)
    real(wp), allocatable :: maps(:, :, :)
    real(wp) :: off(3, 3)
    integer :: i
    if (is_plane_type(etype)) then
       allocate (maps(2, 2, size(h)))
       do i = 1, size(h)
          maps(:, :, i) = r(1:2, 1:2)
       end do
       return
    end if
    allocate (maps(6, 6, size(h)), source=0.0_wp)
    do i = 1, size(h)
       maps(1:3, 1:3, i) = r
       maps(4:6, 4:6, i) = r
       off = 0.0_wp
       off(1, 2) = -h(i)
       off(2, 1) = h(i)
       maps(1:3, 4:6, i) = matmul(off, r)
    end do
  end function node_maps

  pure subroutine to_global(kf, maps, ke)
    !! K = Aᵀ Kf A with A block diagonal (maps), one node pair at a time
    !! (each sum in the order of the matrix products it spells out), made
    !! exactly symmetric: (K + Kᵀ)/2.
    real(wp), intent(in) :: kf(:, :), maps(:, :, :)
    real(wp), allocatable, intent(out) :: ke(:, :)
    real(wp) :: t(size(maps, 1), size(maps, 1)), c
    integer :: m, i, j, ri, rj, a, b, k
    m = size(maps, 1)
    allocate (ke(size(kf, 1), size(kf, 2)))
    do j = 1, size(maps, 3)
       rj = m*(j - 1)
       do i = 1, size(maps, 3)
          ri = m*(i - 1)
          if (m == 2) then
             call turn_block2(kf, maps, i, j, ke)
             cycle
          end if
          do b = 1, m
             do a = 1, m
                c = 0.0_wp
                do k = 1, m
                   c = c + kf(ri + a, rj + k)*maps(k, b, j)
                end do
                t(a, b) = c
             end do
          end do
          do b = 1, m
             do a = 1, m
                c = 0.0_wp
                do k = 1, m
                   c = c + maps(k, a, i)*t(k, b)
                end do
                ke(ri + a, rj + b) = c
             end do
          end do
       end do
    end do
    call make_symmetric(ke)
  end subroutine to_global

  pure subroutine turn_block2(kf, maps, i, j, ke)
    !! to_global's plane case, the 2 × 2 block (i, j): ke_ij = maps_iᵀ kf_ij
    !! maps_j, its sums of two products written out.
    real(wp), intent(in) :: kf(:, :), maps(:, :, :)
    integer, intent(in) :: i, j
    real(wp), intent(inout) :: ke(:, :)
    real(wp) :: t11, t21, t12, t22
    integer :: ri, rj
    ri = 2*(i - 1)
    rj = 2*(j - 1)
    t11 = kf(ri + 1, rj + 1)*maps(1, 1, j) + kf(ri + 1, rj + 2)*maps(2, 1, j)
    t21 = kf(ri + 2, rj + 1)*maps(1, 1, j) + kf(ri + 2, rj + 2)*maps(2, 1, j)
    t12 = kf(ri + 1, rj + 1)*maps(1, 2, j) + kf(ri + 1, rj + 2)*maps(2, 2, j)
    t22 = kf(ri + 2, rj + 1)*maps(1, 2, j) + kf(ri + 2, rj + 2)*maps(2, 2, j)
    ke(ri + 1, rj + 1) = maps(1, 1, i)*t11 + maps(2, 1, i)*t21
    ke(ri + 2, rj + 1) = maps(1, 2, i)*t11 + maps(2, 2, i)*t21
    ke(ri + 1, rj + 2) = maps(1, 1, i)*t12 + maps(2, 1, i)*t22
    ke(ri + 2, rj + 2) = maps(1, 2, i)*t12 + maps(2, 2, i)*t22
  end subroutine turn_block2

  pure real(wp) function node_extent(x, m) result(size_e)
    !! The size of an element: the largest |x(k, i) - x(k, 1)| over its nodes
    !! i and the first m coordinates k.
    real(wp), intent(in) :: x(:, :)
    integer, intent(in) :: m
    integer :: i, k
    size_e = 0.0_wp
    do i = 1, size(x, 2)
       do k = 1, m
          size_e = max(size_e, abs(x(k, i) - x(k, 1)))
       end do
    end do
  end function node_extent

  pure function to_local(maps, u) result(d)
    !! Element-frame DOFs d = A u.
    real(wp), intent(in) :: maps(:, :, :), u(:)
    real(wp) :: d(size(u))
    integer :: m, i
    m = size(maps, 1)
    do i = 1, size(maps, 3)
       d(m*(i - 1) + 1:m*i) = matmul(maps(:, :, i), u(m*(i - 1) + 1:m*i))
    end do
  end function to_local

  pure function to_global_vector(maps, f) result(g)
    !! Global forces g = Aᵀ f.
    real(wp), intent(in) :: maps(:, :, :), f(:)
    real(wp) :: g(size(f))
    integer :: m, i
    m = size(maps, 1)
    do i = 1, size(maps, 3)
       if (m == 2) then   ! sums of two terms, in either order the same
          g(2*i - 1) = maps(1, 1, i)*f(2*i - 1) + maps(2, 1, i)*f(2*i)
          g(2*i) = maps(1, 2, i)*f(2*i - 1) + maps(2, 2, i)*f(2*i)
       else
          g(m*(i - 1) + 1:m*i) = matmul(transpose(maps(:, :, i)), f(m*(i - 1) + 1:m*i))
       end if
    end do
  end function to_global_vector

  pure subroutine shell_pressure_load(etype, x, p, fe, p_local, error)
    !! Nodal loads fe (global axes, element ordering) of a uniform pressure p on
    !! a shell, positive against the element normal; p_local is the load per
    !! unit area along local z (= -p). Translations only (see superjoin_elements_plate).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(in) :: p
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: p_local
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fb(:), ff(:)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    integer :: n, i

    p_local = -p
    n = size(x, 2)
    if (etype /= ET_S3 .and. etype /= ET_S4 .and. .not. is_thick_shell_type(etype) .and. .not. is_shell8(etype)) then
       call fatal_error(error, EXIT_DECK, 'pressure P applies to shells (S3, S4, S3R, S4R, S8R) only')
       return
    end if
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    if (is_shell8(etype)) then
       call shell8_pressure_load(x, p, fe, error)
       return
    end if
    call plate_pressure_load(xl, p_local, fb)
    allocate (ff(6*n), source=0.0_wp)
    do i = 1, n
       ff(6*(i - 1) + PLATE_DOFS) = fb(3*i - 2:3*i)
    end do
    fe = to_global_vector(node_maps(etype, r, h), ff)
  end subroutine shell_pressure_load

  pure subroutine shell_area_load(etype, x, w, fe, error)
    !! Nodal loads fe (global axes, element ordering) of a uniform load w(3) per
    !! unit area in global axes (self weight: density × thickness × acceleration):
    !! each node gets w times the integral of its shape function, on its
    !! translations. Plane-stress elements take only an in-plane (XY) load.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(in) :: w(3)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fb(:)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    integer :: n, i
    n = size(x, 2)
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    if (is_quadratic_plane_type(etype)) then
       allocate (fb(3*n), source=0.0_wp)
       call quadratic_shape_integrals(xl, fb(1:3*n:3))
    else if (is_shell8(etype)) then
       allocate (fb(3*n), source=0.0_wp)
       block
         real(wp) :: shares(n)
         call shell8_area_shares(x, shares, error)
         if (allocated(error)) return
         fb(1:3*n:3) = shares
       end block
    else
       ! plate_pressure_load with p = 1 gives the integrals of the shape functions
       call plate_pressure_load(xl, 1.0_wp, fb)
    end if
    if (is_plane_type(etype)) then
       if (w(3) /= 0.0_wp) then
          call fatal_error(error, EXIT_DECK, 'load along Z on a plane element (XY plane)')
          return
       end if
       allocate (fe(2*n))
       do i = 1, n
          fe(2*i - 1:2*i) = fb(3*i - 2)*w(1:2)
       end do
    else
       allocate (fe(6*n), source=0.0_wp)
       do i = 1, n
          fe(6*i - 5:6*i - 3) = fb(3*i - 2)*w
       end do
    end if
  end subroutine shell_area_load

  pure subroutine shell_traction_load(etype, x, ld, fe, error)
    !! Nodal loads fe (global axes, element ordering) of a uniform traction ld
    !! (TRVEC, TRSHR: superjoin_elements_traction) on a shell's translations:
    !! shell_area_load times the traction, TRSHR projected onto the element's
    !! plane (S8R, S8, S6: onto the tangent plane at each point, shell8_surface_load).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(surface_load_t), intent(in) :: ld
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), f(3)
    if (is_shell8(etype)) then
       call shell8_surface_load(x, ld, fe, error)
       return
    end if
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    call point_force(ld, [r(3, 1), r(3, 2), r(3, 3)], f, error)   ! per unit area: the frame's unit normal
    if (allocated(error)) return
    call shell_area_load(etype, x, f, fe, error)
  end subroutine shell_traction_load

  pure subroutine setup(etype, x, r, xl, h, error)
    !! Element frame with the checks of the node count and, for plane stress,
    !! of the XY plane.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: r(3, 3), xl(:, :), h(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: size_e
    if (size(x, 2) /= ELEMENT_NODE_COUNT(etype)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodes')
       return
    end if
    if (is_plane_type(etype)) then
       size_e = node_extent(x, 2)
       if (maxval(abs(x(3, :))) > PLANE_TOL*size_e) then
          call fatal_error(error, EXIT_DECK, 'plane element out of the XY plane (z must be 0)')
          return
       end if
    end if
    call shell_frame(x, r, xl, h, error)
  end subroutine setup

  pure subroutine scatter(kp, dofs, n, kf)
    !! Add a part matrix with 3 DOFs per node into the 6-DOF flat matrix.
    real(wp), intent(in) :: kp(:, :)
    integer, intent(in) :: dofs(3), n
    real(wp), intent(inout) :: kf(:, :)
    integer :: i, j, a, b
    do i = 1, n
       do a = 1, 3
          do j = 1, n
             do b = 1, 3
                kf(6*(i - 1) + dofs(a), 6*(j - 1) + dofs(b)) = kf(6*(i - 1) + dofs(a), 6*(j - 1) + dofs(b)) + &
                     kp(3*(i - 1) + a, 3*(j - 1) + b)
             end do
          end do
       end do
    end do
  end subroutine scatter

  pure subroutine shell_surface_stresses(x, sec, mat, ue, r, sig_points, sig_nodes, error, drill)
    !! Stresses (σx, σy, τxy) in the element frame r of an S3 or S4 from its
    !! displacements ue (global axes, element ordering) on the bottom (surface 1,
    !! z = -t/2) and top (surface 2, z = +t/2) surfaces, σ = n/t ∓ 6 m/t²:
    !! sig_points(3, point, surface) at the points of membrane_point_stresses
    !! and plate_point_moments (S3: the centroid; S4: 2×2 Gauss, point k next
    !! to node k), sig_nodes(3, node, surface) extrapolated to the nodes;
    !! drill as shell_stiffness.
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: r(3, 3)
    real(wp), allocatable, intent(out) :: sig_points(:, :, :), sig_nodes(:, :, :)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    type(shell_local_t) :: loc
    real(wp) :: t
    real(wp), allocatable :: sp(:, :), sn(:, :), mp(:, :), mn(:, :)
    integer :: n, etype
    n = size(x, 2)
    etype = ET_S4
    if (n == 3) etype = ET_S3
    call membrane_part(etype, x, mat, ue, loc, sp, sn, error, drilling_edges(etype, n, drill))
    r = loc%r
    if (allocated(error)) return
    t = sec%thickness
    call plate_point_moments(loc%xl, t, mat%e, mat%nu, loc%ub, mp, mn, error)
    if (allocated(error)) return
    allocate (sig_points(3, size(sp, 2), 2), sig_nodes(3, n, 2))
    sig_points(:, :, 1) = sp - 6*mp/t**2
    sig_points(:, :, 2) = sp + 6*mp/t**2
    sig_nodes(:, :, 1) = sn - 6*mn/t**2
    sig_nodes(:, :, 2) = sn + 6*mn/t**2
  end subroutine shell_surface_stresses

  pure subroutine membrane_part(etype, x, mat, ue, loc, sp, sn, error, edges)
    !! What the shell stress routines share: the element frame loc%r and local
    !! coordinates loc%xl, the plate DOFs loc%ub (w, θx, θy per node) of the
    !! local displacements, and the membrane stresses at the points (sp) and
    !! nodes (sn) of the element's membrane (drilling with the bubbles of
    !! edges, or QM6/CST when there are none).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    type(shell_local_t), intent(out) :: loc
    real(wp), allocatable, intent(out) :: sp(:, :), sn(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in) :: edges(:)
    real(wp) :: h(size(x, 2)), d(size(ue)), um(2*size(x, 2)), ud(3*size(x, 2))
    integer :: i
    allocate (loc%xl(2, size(x, 2)), loc%ub(3*size(x, 2)))
    call setup(etype, x, loc%r, loc%xl, h, error)
    if (allocated(error)) return
    d = to_local(node_maps(etype, loc%r, h), ue)
    do i = 1, size(x, 2)
       um(2*i - 1:2*i) = d(6*(i - 1) + MEMBRANE_DOFS(1:2))
       ud(3*i - 2:3*i) = d(6*(i - 1) + MEMBRANE_DOFS)
       loc%ub(3*i - 2:3*i) = d(6*(i - 1) + PLATE_DOFS)
    end do
    if (any(edges) .and. size(x, 2) == 3) then
       call opt_point_stresses(loc%xl, mat%e, mat%nu, ud, sp, sn, error, edges)
    else if (any(edges)) then
       call drilling_point_stresses(loc%xl, mat%e, mat%nu, ud, sp, sn, error, edges)
    else
       call membrane_point_stresses(loc%xl, mat%e, mat%nu, .false., um, sp, sn, error)
    end if
  end subroutine membrane_part

  pure subroutine thick_shell_stresses(etype, x, sec, mat, ue, r, sig_points, sig_nodes, error, drill)
    !! Stresses (σx, σy, τxy, τxz, τyz) in the element frame r of an S4R or S3R
    !! from its displacements ue (global axes, element ordering) at three
    !! section points: bottom (1, z = -t/2), top (2, z = +t/2) and the
    !! mid-surface (3): σ = n/t - 6 m/t², n/t + 6 m/t², n/t, with the transverse
    !! shear stresses 0 on the faces and 1.5 q/t on the mid-surface (the peak of
    !! the parabolic distribution of a homogeneous section). sig_points(5,
    !! point, surface) at the points of membrane_point_stresses (or
    !! drilling_point_stresses, same order, for a drilling membrane) and
    !! mindlin_point_resultants (S3R: the centroid; S4R: 2×2 Gauss, point k next
    !! to node k), sig_nodes(5, node, surface) extrapolated to the nodes.
    !! The thick eight-node shell S8R (catalog type 15) gets its own routine
    !! with the same result layout, called from superjoin_elements_stresses.
    !! drill as shell_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: r(3, 3)
    real(wp), allocatable, intent(out) :: sig_points(:, :, :), sig_nodes(:, :, :)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    type(shell_local_t) :: loc
    real(wp) :: t
    real(wp), allocatable :: sp(:, :), sn(:, :), rp(:, :), rn(:, :)
    call membrane_part(etype, x, mat, ue, loc, sp, sn, error, drilling_edges(etype, size(x, 2), drill))
    r = loc%r
    if (allocated(error)) return
    t = sec%thickness
    call mindlin_point_resultants(loc%xl, t, mat%e, mat%nu, shell_shear_stiffness(sec, mat), loc%ub, rp, rn, error)
    if (allocated(error)) return
    call surfaces(sp, rp, sig_points)
    call surfaces(sn, rn, sig_nodes)
  contains
    pure subroutine surfaces(sm, res, sig)
      !! Section point stresses from membrane stresses sm(3, k) and bending and
      !! shear resultants res(5, k) (mx, my, mxy, qx, qy).
      real(wp), intent(in) :: sm(:, :), res(:, :)
      real(wp), allocatable, intent(out) :: sig(:, :, :)
      allocate (sig(5, size(sm, 2), THICK_SURFACES), source=0.0_wp)
      sig(1:3, :, 1) = sm - 6*res(1:3, :)/t**2
      sig(1:3, :, 2) = sm + 6*res(1:3, :)/t**2
      sig(1:3, :, 3) = sm
      sig(4:5, :, 3) = PARABOLIC_SHEAR_PEAK*res(4:5, :)/t
    end subroutine surfaces
  end subroutine thick_shell_stresses
  pure subroutine s8r_stresses(x, sec, mat, ue, sig_points, sig_nodes, error, thermal, thermal_nodal)
    !! shell8_stresses of an S8R, S8 or S6 with its section and material: global
    !! stress tensors sig_points(6, np, 3) at its stress points (the 2×2 points;
    !! S6 three) and sig_nodes(6, n, 3) at the nodes, section points bottom,
    !! top, mid-surface; thermal (optional): α ΔT and α ∂T/∂n, subtracted as a
    !! free thermal strain; thermal_nodal (optional, 2 × n): the nodes'
    !! remainders of both, interpolated.
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: sig_points(:, :, :), sig_nodes(:, :, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: thermal(2)
    real(wp), intent(in), optional :: thermal_nodal(:, :)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    call setup(merge(ET_S6, ET_S8R, size(x, 2) == ELEMENT_NODE_COUNT(ET_S6)), x, r, xl, h, error)
    if (allocated(error)) return
    call shell8_stresses(x, [r(1, 1), r(1, 2), r(1, 3)], shell8_props(sec, mat), ue, sig_points, sig_nodes, &
         error, thermal, thermal_nodal)
  end subroutine s8r_stresses
  pure subroutine shell_thermal_nodal_load(etype, x, sec, mat, strain, curvature, fe, error, drill, self_energy)
    !! Consistent nodal loads fe(6n) (global axes, element ordering) of the
    !! thermal strain and curvature of an S3, S4, S3R or S4R given at its
    !! nodes, strain(n) = α ΔT and curvature(n) = α ∂T/∂n, interpolated with
    !! the corner functions to the integration points of the element's own
    !! membrane and bending parts: ∫ Bᵀ D ε0(ξ) dA with the membrane's B (CST,
    !! QM6 with its incompatible modes, or the drilling membrane under the
    !! edge mask drill) and ∫ Bbᵀ D_b κ0(ξ) dA with the plate's (DKT/DKQ
    !! discrete Kirchhoff curvatures, MITC3/MITC4 bending rows). self_energy:
    !! the constant of the element's energy of its mechanical strains,
    !! ½ uᵀ K u - uᵀ fe + self_energy (the membrane's and the plate's, each by
    !! the rule of its load).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain(:), curvature(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp), intent(out), optional :: self_energy
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), cm, cb
    real(wp), allocatable :: fm(:), fb(:), fl(:)
    logical :: edges(size(x, 2))
    integer :: n, i
    n = size(x, 2)
    if (is_plane_type(etype) .or. is_shell8(etype) .or. size(strain) /= n .or. size(curvature) /= n) then
       call fatal_error(error, EXIT_DECK, 'nodal thermal strains of a shell: S3, S4, S3R, S4R with a value per node')
       return
    end if
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    edges = drilling_edges(etype, n, drill)
    allocate (fl(6*n), source=0.0_wp)
    if (any(edges)) then
       ! the membrane of the stiffness: OPT (triangle) or the drilling quadrilateral
       if (n == 3) then
          call opt_thermal_load(xl, sec%thickness, mat%e, mat%nu, strain, fm, error, edges, cm)
       else
          call drilling_thermal_load(xl, sec%thickness, mat%e, mat%nu, strain, fm, error, edges, cm)
       end if
       if (allocated(error)) return
       do i = 1, n
          fl(6*(i - 1) + MEMBRANE_DOFS) = fm(3*i - 2:3*i)
       end do
    else
       call membrane_thermal_load(xl, sec%thickness, mat%e, mat%nu, .false., strain, fm, error, cm)
       if (allocated(error)) return
       do i = 1, n
          fl(6*(i - 1) + MEMBRANE_DOFS(1:2)) = fm(2*i - 1:2*i)
       end do
    end if
    if (is_thick_shell_type(etype)) then
       call mindlin_thermal_load(xl, sec%thickness, mat%e, mat%nu, shell_shear_stiffness(sec, mat), curvature, fb, &
            error, cb)
    else
       call plate_thermal_load(xl, sec%thickness, mat%e, mat%nu, curvature, fb, error, cb)
    end if
    if (allocated(error)) return
    do i = 1, n
       fl(6*(i - 1) + PLATE_DOFS) = fb(3*i - 2:3*i)
    end do
    fe = to_global_vector(node_maps(etype, r, h), fl)
    if (present(self_energy)) self_energy = cm + cb
  end subroutine shell_thermal_nodal_load

  pure subroutine shell_thermal_nodal_resultants(etype, x, sec, mat, strain, curvature, res0, error, drill)
    !! The resultants res0 (nx, ny, nxy, mx, my, mxy at the centre, element
    !! frame, as shell_resultants) to be taken off those of the displacements
    !! for the nodal thermal strains and curvatures of shell_thermal_nodal_load:
    !! minus the resultants of that initial strain at zero displacement
    !! (N = D (ε - ε0), the membrane's incompatible modes included).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain(:), curvature(:)
    real(wp), intent(out) :: res0(6)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), nres(3), kc
    real(wp), allocatable :: sp(:, :), sn(:, :)
    logical :: edges(size(x, 2))
    integer :: n
    res0 = 0.0_wp
    n = size(x, 2)
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    edges = drilling_edges(etype, n, drill)
    if (any(edges)) then
       call drilling_thermal_stresses(xl, sec%thickness, mat%e, mat%nu, strain, nres, sp, sn, error, edges)
    else
       call membrane_resultants(xl, sec%thickness, mat%e, mat%nu, spread(0.0_wp, 1, 2*n), nres, error, strain)
    end if
    if (allocated(error)) return
    res0(1:3) = -nres
    ! the plate parts take their moments at the centroid (triangle) or ξ = η = 0
    kc = sum(curvature)/n
    res0(4:6) = matmul(bending_rigidity(sec%thickness, mat%e, mat%nu), kc*[1.0_wp, 1.0_wp, 0.0_wp])
  end subroutine shell_thermal_nodal_resultants

  pure subroutine shell_thermal_nodal_stresses(etype, x, sec, mat, strain, curvature, sig_points, sig_nodes, error, &
       drill)
    !! What the nodal thermal strains and curvatures of shell_thermal_nodal_load
    !! add to the stresses of shell_surface_stresses (S3, S4) or
    !! thick_shell_stresses (S3R, S4R), same layout: the stresses of the initial
    !! strain at zero displacement, σ = D (ε - ε0(ξ)) with ε0 interpolated to
    !! each point (the membrane's modes included; extrapolated to the nodes as
    !! those routines extrapolate).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain(:), curvature(:)
    real(wp), allocatable, intent(out) :: sig_points(:, :, :), sig_nodes(:, :, :)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp), parameter :: GAUSS_2 = 0.57735026918962576451_wp
    real(wp), parameter :: XI_CORNER(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], ETA_CORNER(4) = [-1.0_wp, -1.0_wp, &
         1.0_wp, 1.0_wp]
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), nres(3), db(3, 3), t
    real(wp), allocatable :: sp(:, :), sn(:, :), kp(:)
    type(initial_strain_t) :: eps0
    logical :: edges(size(x, 2))
    integer :: n, k, ncomp, nsurf
    n = size(x, 2)
    call setup(etype, x, r, xl, h, error)
    if (allocated(error)) return
    edges = drilling_edges(etype, n, drill)
    if (any(edges)) then
       call drilling_thermal_stresses(xl, sec%thickness, mat%e, mat%nu, strain, nres, sp, sn, error, edges)
    else
       eps0%nodal = strain
       call membrane_point_stresses(xl, mat%e, mat%nu, .false., spread(0.0_wp, 1, 2*n), sp, sn, error, eps0)
    end if
    if (allocated(error)) return
    ! the initial curvature at the points of the plate parts (triangle: centroid; quadrilateral: 2×2 Gauss)
    if (n == 3) then
       kp = [sum(curvature)/3]
    else
       allocate (kp(4))
       do k = 1, 4
          kp(k) = dot_product(corner_functions(4, GAUSS_2*XI_CORNER(k), GAUSS_2*ETA_CORNER(k)), curvature)
       end do
    end if
    t = sec%thickness
    db = bending_rigidity(t, mat%e, mat%nu)
    ncomp = 3
    nsurf = 2
    if (is_thick_shell_type(etype)) then
       ncomp = 5
       nsurf = THICK_SURFACES
    end if
    allocate (sig_points(ncomp, size(sp, 2), nsurf), sig_nodes(ncomp, n, nsurf), source=0.0_wp)
    ! m = -D_b κ0: the surface stresses ∓ 6 m/t² (the transverse shear takes no initial strain)
    do k = 1, size(sp, 2)
       call surfaces(sig_points(:, k, :), sp(:, k), -kp(k)*matmul(db, [1.0_wp, 1.0_wp, 0.0_wp]))
    end do
    do k = 1, n
       call surfaces(sig_nodes(:, k, :), sn(:, k), -curvature(k)*matmul(db, [1.0_wp, 1.0_wp, 0.0_wp]))
    end do
  contains
    pure subroutine surfaces(sig, sm, m)
      !! Section point stresses from the membrane stresses sm(3) and the moments m(3).
      real(wp), intent(inout) :: sig(:, :)
      real(wp), intent(in) :: sm(3), m(3)
      sig(1:3, 1) = sm - 6*m/t**2
      sig(1:3, 2) = sm + 6*m/t**2
      if (size(sig, 2) == THICK_SURFACES) sig(1:3, 3) = sm
    end subroutine surfaces
  end subroutine shell_thermal_nodal_stresses
end module superjoin_elements_shell
