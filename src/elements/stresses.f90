module superjoin_elements_stresses
  !! The stresses and strains of one element of a solved step, as the output
  !! asks for them: element_stresses, the stress tensors of a plane or shell
  !! element at its integration points and extrapolated to its nodes;
  !! element_tensor, the single stress or strain tensor of a truss or plane
  !! element. Both gather the element's state of the step (element_state:
  !! coordinates, section, material, DOF values, end forces, resultants,
  !! thermal strains) and leave the physics to the element family's own
  !! routine (membrane_point_stresses, quadratic_point_stresses,
  !! shell_surface_stresses, thick_shell_stresses, s8r_stresses), where a
  !! thermal strain is subtracted. Tensors in global axes, Voigt order xx, yy,
  !! zz, xy, xz, yz (tensor shear components); plane strain has
  !! σzz = ν (σxx + σyy) - E α ΔT.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, section_t, material_t, NDOF_NODE, ELEMENT_NODE_COUNT
  use superjoin_model_results, only: result_fields_t
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_TRUSS, FAMILY_PLANE, FAMILY_SHELL, &
       FAMILY_SOLID
  use superjoin_elements_solid_stress, only: solid_point_tensors, solid_thermal_points, solid_extrapolation
  use superjoin_elements_axisym, only: is_axisym_type, axisym_point_tensors
  use superjoin_elements_shell, only: s8r_stresses, shell_thermal_nodal_stresses, shell_frame, &
       shell_surface_stresses, quadratic_props, thick_shell_stresses, THICK_SURFACES
  use superjoin_elements_shell8, only: shell8_stress_points
  use superjoin_elements_quadratic, only: quadratic_point_stresses
  use superjoin_elements_membrane, only: membrane_point_stresses, initial_strain_t
  use superjoin_elements_thermal, only: thermal_free_field, plane_initial_strains, plane_centroid_remainder
  use superjoin_elements_drill_mask, only: element_drill
  implicit none (type, external)
  private

  integer, parameter, public :: NTENSOR = 6
    !! Components of a stress or strain tensor (Voigt order xx, yy, zz, xy, xz, yz).
  integer, parameter :: TRANSVERSE = 5
    !! Element-frame stress components with the transverse shears (σx, σy, τxy, τxz, τyz).

  type, public :: element_state_t
    !! One element in one solved step, as its stress routines see it.
     integer :: etype = 0                           !! ET_*
     real(wp), allocatable :: x(:, :)               !! (3, nnode) node coordinates
     type(section_t) :: sec                         !! its section
     type(material_t) :: mat                        !! the section's material
     integer :: drill = 0                           !! drilling edge mask (element_drill)
     real(wp), allocatable :: ue(:)                 !! DOF values, global axes, element ordering
     real(wp) :: force(6, 2) = 0.0_wp               !! end forces (trusses and beams)
     real(wp) :: plate(6) = 0.0_wp                  !! resultants nx, ny, nxy, mx, my, mxy
     logical :: heated = .false.                    !! the run has thermal strains of plane and shell elements
     real(wp) :: thermal(2) = 0.0_wp                !! α ΔT and α ∂T/∂n of the element (heated)
     real(wp), allocatable :: thermal_nodal(:)      !! (nnode) nodal remainders of α ΔT, when the run has them
     real(wp), allocatable :: curvature_nodal(:)    !! (nnode) nodal remainders of α ∂T/∂n, when the run has them
  end type element_state_t

  type :: frame_stresses_t
    !! Stresses of a plane or shell element in its own frame, before they turn global.
     real(wp) :: r(3, 3) = 0.0_wp                   !! element frame (rows: local x, y, z)
     real(wp), allocatable :: sp(:, :, :)           !! (3 or 5, point, section point)
     real(wp), allocatable :: sn(:, :, :)           !! (3 or 5, node, section point)
     real(wp), allocatable :: e0p(:), e0n(:)        !! a varying temperature: ε0 at the points and nodes
     real(wp) :: szz0 = 0.0_wp                      !! E α ΔT of the uniform thermal strain
  end type frame_stresses_t

  public :: element_state, element_displacements, element_stresses, element_tensor

contains

  subroutine element_displacements(model, fields, is, isub, ie, ue)
    !! The DOF values of one element in step `is`, global axes, in the element
    !! ordering of element_stiffness (node-major, element_node_dofs order).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    real(wp), allocatable, intent(out) :: ue(:)
    type(element_traits_t) :: t
    integer :: a, d, nn, k
    integer(i8) :: vx
    associate (sub => model%subs(isub))
      t = element_traits(sub%elem_type(ie))
      nn = ELEMENT_NODE_COUNT(sub%elem_type(ie))
      allocate (ue(nn*count(t%dofs)))
      k = 0
      do a = 1, nn
         vx = fields%vertex_offset(isub) + sub%elem_nodes(a, ie)
         do d = 1, NDOF_NODE
            if (.not. t%dofs(d)) cycle
            k = k + 1
            ue(k) = fields%u(NDOF_NODE*(vx - 1) + d, is)
         end do
      end do
    end associate
  end subroutine element_displacements

  subroutine element_state(model, fields, is, isub, ie, el, ok)
    !! The state of element ie of substructure isub in step is; ok false (el
    !! incomplete) for an element without a section.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    type(element_state_t), intent(out) :: el
    logical, intent(out) :: ok
    integer(i8) :: iel
    integer :: nn
    associate (sub => model%subs(isub))
      ok = sub%elem_section(ie) > 0
      if (.not. ok) return
      el%etype = sub%elem_type(ie)
      nn = ELEMENT_NODE_COUNT(el%etype)
      allocate (el%x(3, nn))   ! allocated first: gfortran's reallocation check of an unallocated
      el%x = sub%x(:, sub%elem_nodes(1:nn, ie))   ! intent(out) component overflowed under -fsanitize=undefined
      el%sec = sub%sections(sub%elem_section(ie))
      el%mat = model%materials(el%sec%material)
      el%drill = element_drill(sub, ie)
      call element_displacements(model, fields, is, isub, ie, el%ue)
      iel = fields%elem_offset(isub) + ie
      if (allocated(fields%elem_force)) el%force = fields%elem_force(:, :, iel, is)
      if (allocated(fields%plate)) el%plate = fields%plate(:, iel, is)
      el%heated = allocated(fields%thermal)
      if (el%heated) el%thermal = fields%thermal(:, iel, is)
      if (allocated(fields%thermal_nodal)) el%thermal_nodal = fields%thermal_nodal(1:nn, iel, is)
      if (allocated(fields%thermal_curvature_nodal)) el%curvature_nodal = fields%thermal_curvature_nodal(1:nn, iel, is)
    end associate
  end subroutine element_state

  subroutine element_stresses(model, fields, is, isub, ie, points, nodes, ok, strain, mechanical)
    !! Stress tensors of plane, shell or solid element ie of substructure isub in
    !! step is: points(6, npoint, nsurf) at its integration points,
    !! nodes(6, nnode, nsurf) extrapolated to its nodes; nsurf = 1 for plane
    !! and solid elements, 2 for thin shells (1: bottom surface z = -t/2, 2: top, z along
    !! the element normal), 3 for thick shells (bottom, top, mid-surface). ok
    !! false (and empty arrays) for other element types or an element that
    !! cannot be evaluated. The S8R returns global tensors at its section
    !! points (s8r_stresses), its thermal strain subtracted in its routine.
    !! strain (present and true): the strains (tensor shears) instead, solids only;
    !! with mechanical (present and true) the mechanical strains ε - ε_th.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    real(wp), allocatable, intent(out) :: points(:, :, :), nodes(:, :, :)
    logical, intent(out) :: ok
    logical, intent(in), optional :: strain, mechanical
    type(element_state_t) :: el
    type(element_traits_t) :: t
    type(frame_stresses_t) :: fs
    type(error_t), allocatable :: error
    logical :: want_strain, want_mechanical
    ok = .false.
    want_mechanical = .false.
    if (present(mechanical)) want_mechanical = mechanical
    allocate (points(NTENSOR, 0, 1), nodes(NTENSOR, 0, 1))
    t = element_traits(model%subs(isub)%elem_type(ie))
    want_strain = .false.
    if (present(strain)) want_strain = strain
    if (t%family /= FAMILY_PLANE .and. t%family /= FAMILY_SHELL .and. t%family /= FAMILY_SOLID) return
    if (want_strain .and. t%family /= FAMILY_SOLID) return
    call element_state(model, fields, is, isub, ie, el, ok)
    if (.not. ok) return
    ok = .false.
    if (t%family == FAMILY_SOLID) then
       call solid_element_tensors(el, want_strain, want_mechanical, points, nodes, ok)
       return
    end if
    if (t%family == FAMILY_SHELL .and. t%quadratic) then
       call s8r_element_stresses(el, points, nodes, ok)
       return
    end if
    call frame_stresses(el, t, fs, error)
    if (allocated(error)) return
    deallocate (points, nodes)
    call global_stresses(el%mat, t%plane_strain, fs, points, nodes)
    ok = .true.
  end subroutine element_stresses

  subroutine solid_element_tensors(el, strain, mechanical, points, nodes, ok)
    !! element_stresses of a solid (superjoin_elements_solid_stress; axisymmetric: superjoin_elements_axisym,
    !! xx = r, yy = z, zz = θ): points(6, npoint, 1),
    !! nodes(6, nnode, 1), stresses or (strain) strains, total or (mechanical) less the thermal strains.
    type(element_state_t), intent(in) :: el
    logical, intent(in) :: strain, mechanical
    real(wp), allocatable, intent(inout) :: points(:, :, :), nodes(:, :, :)
    logical, intent(out) :: ok
    real(wp), allocatable :: sp(:, :), sn(:, :)
    type(error_t), allocatable :: error
    if (is_axisym_type(el%etype) .and. allocated(el%thermal_nodal)) then   ! loads: α ΔT at its nodes
       call axisym_point_tensors(el%etype, el%x, el%mat, el%ue, strain, sp, sn, error, el%thermal_nodal, mechanical)
    else if (is_axisym_type(el%etype)) then
       call axisym_point_tensors(el%etype, el%x, el%mat, el%ue, strain, sp, sn, error)
    else if (allocated(el%thermal_nodal)) then   ! loads: α ΔT at its nodes (thermal(1) is 0 on solids)
       call solid_point_tensors(el%etype, el%x, el%mat, el%ue, strain, sp, sn, error, el%sec%axes, el%thermal_nodal)
       if (strain .and. mechanical .and. .not. allocated(error)) call take_thermal_points(el, sp, sn, error)
    else
       call solid_point_tensors(el%etype, el%x, el%mat, el%ue, strain, sp, sn, error, el%sec%axes)
    end if
    ok = .not. allocated(error)
    if (.not. ok) return
    points = reshape(sp, [NTENSOR, size(sp, 2), 1])
    nodes = reshape(sn, [NTENSOR, size(sn, 2), 1])
  end subroutine solid_element_tensors

  pure subroutine take_thermal_points(el, sp, sn, error)
    !! The mechanical strains of a heated 3D solid: its thermal strains off the
    !! normal strains at the points sp(6, npoint), and the nodal values sn again.
    type(element_state_t), intent(in) :: el
    real(wp), intent(inout) :: sp(:, :)
    real(wp), allocatable, intent(inout) :: sn(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: e(:)
    integer :: k
    call solid_thermal_points(el%etype, el%x, el%mat, el%thermal_nodal, e, error)
    if (allocated(error)) return
    do k = 1, 3
       sp(k, :) = sp(k, :) - e
    end do
    sn = matmul(sp, transpose(solid_extrapolation(el%etype)))
  end subroutine take_thermal_points

  subroutine s8r_element_stresses(el, points, nodes, ok)
    !! element_stresses of an S8R, S8 or S6 (superjoin_elements_shell8, shell8_stresses):
    !! points(6, 4, 3) at the 2×2 points (S6 points(6, 3, 3)), nodes(6, n, 3), section points
    !! bottom, top, mid-surface, global axes; the element's thermal strain
    !! and curvature of the step (if any) subtracted.
    type(element_state_t), intent(in) :: el
    real(wp), allocatable, intent(inout) :: points(:, :, :), nodes(:, :, :)
    logical, intent(out) :: ok
    real(wp) :: rem(2, size(el%x, 2))
    type(error_t), allocatable :: error
    ok = .false.
    rem = 0.0_wp   ! loads: a temperature varying over the element, the nodes' remainders
    if (allocated(el%thermal_nodal)) rem(1, :) = el%thermal_nodal
    if (allocated(el%curvature_nodal)) rem(2, :) = el%curvature_nodal
    deallocate (points, nodes)
    allocate (points(NTENSOR, shell8_stress_points(size(el%x, 2)), THICK_SURFACES), &
         nodes(NTENSOR, size(el%x, 2), THICK_SURFACES))
    if (any(rem /= 0.0_wp)) then
       call s8r_stresses(el%x, el%sec, el%mat, el%ue, points, nodes, error, el%thermal, rem)
    else
       call s8r_stresses(el%x, el%sec, el%mat, el%ue, points, nodes, error, el%thermal)
    end if
    if (allocated(error)) then
       deallocate (points, nodes)
       allocate (points(NTENSOR, 0, 1), nodes(NTENSOR, 0, 1))
       return
    end if
    ok = .true.
  end subroutine s8r_element_stresses

  subroutine frame_stresses(el, t, fs, error)
    !! The element-frame stresses of a plane element or a three- or four-node
    !! shell: loads: σ = D (ε - ε0), the free thermal expansion taken off u.
    type(element_state_t), intent(in) :: el
    type(element_traits_t), intent(in) :: t
    type(frame_stresses_t), intent(out) :: fs
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ue(:), u0(:), sp3_rem(:, :, :), sn3_rem(:, :, :), tn(:)
    ue = el%ue
    fs%szz0 = 0.0_wp
    if (el%heated) then
       call thermal_free_field(el%etype, el%x, el%mat%nu, el%thermal(1), el%thermal(2), u0, error)
       if (allocated(error)) return
       ue = ue - u0
       fs%szz0 = el%mat%e*el%thermal(1)
    end if
    if (t%family == FAMILY_PLANE) then
       call plane_frame_stresses(el, t, ue, fs, error)
    else if (t%shear_flexible) then
       call thick_shell_stresses(el%etype, el%x, el%sec, el%mat, ue, fs%r, fs%sp, fs%sn, error, el%drill)
    else
       call shell_surface_stresses(el%x, el%sec, el%mat, ue, fs%r, fs%sp, fs%sn, error, el%drill)
    end if
    if (allocated(error)) return
    if (t%family /= FAMILY_PLANE .and. allocated(el%curvature_nodal)) then
       ! loads: a shell whose temperature varies, the nodal remainders interpolated to the points
       allocate (tn(size(el%x, 2)), source=0.0_wp)
       if (allocated(el%thermal_nodal)) tn = el%thermal_nodal
       if (any(tn /= 0.0_wp) .or. any(el%curvature_nodal /= 0.0_wp)) then
          call shell_thermal_nodal_stresses(el%etype, el%x, el%sec, el%mat, tn, el%curvature_nodal, &
               sp3_rem, sn3_rem, error, el%drill)
          if (allocated(error)) return
          fs%sp = fs%sp + sp3_rem
          fs%sn = fs%sn + sn3_rem
       end if
    end if
  end subroutine frame_stresses

  subroutine plane_frame_stresses(el, t, ue, fs, error)
    !! The element-frame stresses (σx, σy, τxy) of a plane element from its
    !! DOF values ue (the free thermal expansion taken off), with the nodal
    !! remainder of a temperature that varies over it.
    type(element_state_t), intent(in) :: el
    type(element_traits_t), intent(in) :: t
    real(wp), intent(in) :: ue(:)
    type(frame_stresses_t), intent(inout) :: fs
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: xl(2, size(el%x, 2)), h(size(el%x, 2))
    real(wp), allocatable :: ul(:), sp(:, :), sn(:, :)
    type(initial_strain_t) :: eps0
    integer :: a, nn
    logical :: varying
    nn = size(el%x, 2)
    call shell_frame(el%x, fs%r, xl, h, error)
    if (allocated(error)) return
    allocate (ul(2*nn))
    do a = 1, nn
       ul(2*a - 1) = fs%r(1, 1)*ue(2*a - 1) + fs%r(1, 2)*ue(2*a)
       ul(2*a) = fs%r(2, 1)*ue(2*a - 1) + fs%r(2, 2)*ue(2*a)
    end do
    varying = .false.
    if (allocated(el%thermal_nodal)) varying = any(el%thermal_nodal /= 0.0_wp)
    if (varying) then   ! loads: the nodal remainder of the temperature, interpolated to the points
       call plane_initial_strains(el%etype, el%mat%nu, el%thermal_nodal, eps0%nodal)
       if (t%quadratic) then
          call quadratic_point_stresses(xl, quadratic_props(el%etype, el%sec, el%mat), ul, sp, sn, error, eps0)
       else
          call membrane_point_stresses(xl, el%mat%e, el%mat%nu, t%plane_strain, ul, sp, sn, error, eps0)
       end if
       if (allocated(eps0%points)) call move_alloc(eps0%points, fs%e0p)
       if (allocated(eps0%nodes)) call move_alloc(eps0%nodes, fs%e0n)
    else if (t%quadratic) then
       call quadratic_point_stresses(xl, quadratic_props(el%etype, el%sec, el%mat), ul, sp, sn, error)
    else
       call membrane_point_stresses(xl, el%mat%e, el%mat%nu, t%plane_strain, ul, sp, sn, error)
    end if
    if (allocated(error)) return
    fs%sp = reshape(sp, [3, size(sp, 2), 1])
    fs%sn = reshape(sn, [3, size(sn, 2), 1])
  end subroutine plane_frame_stresses

  pure subroutine global_stresses(mat, strain, fs, points, nodes)
    !! The element-frame stresses fs as global tensors at the points and
    !! nodes; plane strain (strain) adds σzz, less E α ΔT of the uniform and
    !! the varying thermal strain.
    type(material_t), intent(in) :: mat
    logical, intent(in) :: strain
    type(frame_stresses_t), intent(in) :: fs
    real(wp), allocatable, intent(out) :: points(:, :, :), nodes(:, :, :)
    real(wp) :: szz_here
    integer :: a, k
    allocate (points(NTENSOR, size(fs%sp, 2), size(fs%sp, 3)), nodes(NTENSOR, size(fs%sn, 2), size(fs%sn, 3)))
    szz_here = 0.0_wp
    do k = 1, size(fs%sp, 3)
       do a = 1, size(fs%sp, 2)
          ! plane strain: σzz takes -E α ΔT of the remainder there, (1 + ν) α ΔT being e0
          if (allocated(fs%e0p)) szz_here = mat%e*fs%e0p(a)/(1.0_wp + mat%nu)
          points(:, a, k) = to_global(fs%sp(:, a, k))
       end do
       do a = 1, size(fs%sn, 2)
          if (allocated(fs%e0n)) szz_here = mat%e*fs%e0n(a)/(1.0_wp + mat%nu)
          nodes(:, a, k) = to_global(fs%sn(:, a, k))
       end do
    end do
  contains
    pure function to_global(s) result(t)
      !! (σx, σy, τxy[, τxz, τyz]) of the element frame as a global tensor, Voigt order.
      real(wp), intent(in) :: s(:)
      real(wp) :: t(NTENSOR)
      real(wp) :: m(3, 3), szz, e1(3), e2(3), e3(3)
      szz = 0.0_wp
      if (strain) szz = mat%nu*(s(1) + s(2)) - fs%szz0 - szz_here
      e1 = fs%r(1, :)
      e2 = fs%r(2, :)
      e3 = fs%r(3, :)
      m = s(1)*outer(e1, e1) + s(2)*outer(e2, e2) + s(3)*(outer(e1, e2) + outer(e2, e1)) + szz*outer(e3, e3)
      if (size(s) == TRANSVERSE) m = m + s(4)*(outer(e1, e3) + outer(e3, e1)) + s(5)*(outer(e2, e3) + outer(e3, e2))
      t = voigt(m)
    end function to_global
  end subroutine global_stresses

  subroutine element_tensor(model, fields, is, isub, ie, strain, t, ok)
    !! Stress (or strain) tensor of one element in global axes, Voigt order
    !! xx, yy, zz, xy, xz, yz (tensor shear components): trusses from the axial
    !! force (uniaxial stress state), plane elements from their resultants
    !! (the centroid); ok false for element types without one (beams, shells).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    logical, intent(in) :: strain
    real(wp), intent(out) :: t(NTENSOR)
    logical, intent(out) :: ok
    type(element_state_t) :: el
    type(element_traits_t) :: tr
    type(error_t), allocatable :: error
    real(wp) :: sig(3, 3), eth
    t = 0.0_wp
    call element_state(model, fields, is, isub, ie, el, ok)
    if (.not. ok) return
    ok = .false.
    eth = el%thermal(1)                                ! free thermal strain α ΔT of the element
    ! a temperature varying over a plane element: its value at the centroid
    if (allocated(el%thermal_nodal)) eth = eth + plane_centroid_remainder(el%etype, el%x, el%thermal_nodal)
    tr = element_traits(el%etype)
    select case (tr%family)
    case (FAMILY_TRUSS)
       call truss_tensor(el, strain, sig)
    case (FAMILY_PLANE)
       call plane_tensor(el, tr%plane_strain, strain, eth, sig, error)
       if (allocated(error)) return
    case default
       return
    end select
    t = voigt(sig)
    ok = .true.
  end subroutine element_tensor

  pure subroutine truss_tensor(el, strain, sig)
    !! The uniaxial stress (or strain) tensor of a bar, from its axial force.
    type(element_state_t), intent(in) :: el
    logical, intent(in) :: strain
    real(wp), intent(out) :: sig(3, 3)
    real(wp) :: a(3), s, nu, id(3, 3)
    integer :: j
    nu = el%mat%nu
    a = el%x(:, 2) - el%x(:, 1)
    a = a/norm2(a)
    s = el%force(1, 2)/el%sec%area
    if (strain) then
       s = s/el%mat%e
       id = 0.0_wp
       do j = 1, 3
          id(j, j) = 1.0_wp
       end do
       sig = -nu*s*id + (1.0_wp + nu)*s*outer(a, a)
    else
       sig = s*outer(a, a)
    end if
  end subroutine truss_tensor

  pure subroutine plane_tensor(el, plane_strain, strain, eth, sig, error)
    !! The stress (or total strain: elastic + α ΔT) tensor of a plane element
    !! from its resultants; plane strain: sz = ν (sx + sy) - E α ΔT, ez = 0.
    type(element_state_t), intent(in) :: el
    logical, intent(in) :: plane_strain, strain
    real(wp), intent(in) :: eth
    real(wp), intent(out) :: sig(3, 3)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), xl(2, size(el%x, 2)), h(size(el%x, 2)), ex(3), ey(3), ez(3), e, nu, sl(3), el3(3)
    sig = 0.0_wp
    e = el%mat%e
    nu = el%mat%nu
    call shell_frame(el%x, r, xl, h, error)
    if (allocated(error)) return
    ex = r(1, :)
    ey = r(2, :)
    ez = r(3, :)
    sl = el%plate(1:3)/el%sec%thickness             ! sx, sy, txy in the element frame
    if (.not. plane_strain) then
       if (strain) then                              ! total strain: elastic + α ΔT
          el3(1) = (sl(1) - nu*sl(2))/e + eth
          el3(2) = (sl(2) - nu*sl(1))/e + eth
          el3(3) = (1.0_wp + nu)*sl(3)/e       ! tensor shear strain = gamma/2
          sig = el3(1)*outer(ex, ex) + el3(2)*outer(ey, ey) + el3(3)*(outer(ex, ey) + outer(ey, ex)) &
               + (eth - nu*(sl(1) + sl(2))/e)*outer(ez, ez)
       else
          sig = sl(1)*outer(ex, ex) + sl(2)*outer(ey, ey) + sl(3)*(outer(ex, ey) + outer(ey, ex))
       end if
    else if (strain) then
       el3(1) = (1.0_wp + nu)*((1.0_wp - nu)*sl(1) - nu*sl(2))/e + (1.0_wp + nu)*eth
       el3(2) = (1.0_wp + nu)*((1.0_wp - nu)*sl(2) - nu*sl(1))/e + (1.0_wp + nu)*eth
       el3(3) = (1.0_wp + nu)*sl(3)/e
       sig = el3(1)*outer(ex, ex) + el3(2)*outer(ey, ey) + el3(3)*(outer(ex, ey) + outer(ey, ex))
    else
       sig = sl(1)*outer(ex, ex) + sl(2)*outer(ey, ey) + sl(3)*(outer(ex, ey) + outer(ey, ex)) &
            + (nu*(sl(1) + sl(2)) - e*eth)*outer(ez, ez)
    end if
  end subroutine plane_tensor

  pure function outer(p, q) result(o)
    !! The outer product p qᵀ.
    real(wp), intent(in) :: p(3), q(3)
    real(wp) :: o(3, 3)
    o = spread(p, 2, 3)*spread(q, 1, 3)
  end function outer

  pure function voigt(m) result(t)
    !! A symmetric tensor in Voigt order xx, yy, zz, xy, xz, yz.
    real(wp), intent(in) :: m(3, 3)
    real(wp) :: t(NTENSOR)
    t = [m(1, 1), m(2, 2), m(3, 3), m(1, 2), m(1, 3), m(2, 3)]
  end function voigt
end module superjoin_elements_stresses
