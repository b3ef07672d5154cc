module superjoin_deck_coupling_build
  !! Validation side of the coupling cards: each *COUPLING (*KINEMATIC,
  !! *DISTRIBUTING), *RIGID BODY and *MPC BEAM becomes linear constraint
  !! equations appended to model%equations, marked `coupling`, which the
  !! transform eliminates exactly like *EQUATION (assembly/transform.f90):
  !! - kinematic (RBE2) and rigid body: every coupled node i follows the
  !!   reference node r rigidly, linearised: u_i = u_r + θ × (x_i - x_r) for the
  !!   translations coupled, θ_i = θ for the rotations coupled where node i has
  !!   rotations. θ is the reference node's rotation (DOFs 4-6), or the
  !!   translations of *RIGID BODY's ROT NODE (CalculiX);
  !! - distributing (RBE3): the reference node moves as the weighted
  !!   least-squares rigid motion of the coupled nodes (weights w_i: their
  !!   areas on the surface, ∫ N_i dA over its faces, as CalculiX): with
  !!   x̄ = Σ w_i x_i / W and ρ_i = x_i - x̄,
  !!     θ_r = J⁻¹ Σ w_i ρ_i × u_i,  J = Σ w_i (|ρ_i|² I - ρ_i ρ_iᵀ),
  !!     u_r = Σ w_i u_i / W + θ_r × (x_r - x̄);
  !!   the reference node's DOFs are the dependent ones, so a force or moment
  !!   on it is distributed to the coupled nodes by the transpose;
  !! - *MPC BEAM, PLANE, STRAIGHT, MEANROT (CalculiX, nonlinear there): their linear forms
  !!   (mpc, mpc_meanrot);
  !! - a DCOUP3D element with its *DISTRIBUTING COUPLING nodes and weights w_i,
  !!   read as its dialect says (dcoup): CalculiX's, the reference node's
  !!   translations are the weighted mean u_r = Σ w_i u_i / W (its position does
  !!   not count); Abaqus's, the distributing coupling above with these weights
  !!   and DOFs 1-6. The listing notes which reading was taken.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, substructure_t, equation_t, source_loc_t, NDOF_NODE, DLOAD_P1, DLOAD_P4, &
       DLOAD_P5, DLOAD_P6, ELEMENT_NODE_COUNT, node_label, DIALECT_CALCULIX
  use superjoin_elements, only: element_dof_mask
  use superjoin_elements_solid_faces, only: solid_face_nodes, solid_pressure_load
  use superjoin_error, only: error_t
  use superjoin_deck_state, only: deck_state_t, report_loc, ref_t, reading_dialect, surface_b_t
  use superjoin_deck_build_common, only: resolve_items, resolve_sub, where
  use superjoin_deck_coupling_records, only: coupling_b_t, COUPLE_NONE, COUPLE_KINEMATIC, &
       COUPLE_DISTRIBUTING, COUPLE_RIGID_BODY, COUPLE_MPC_BEAM, COUPLE_MPC_PLANE, COUPLE_DCOUP, COUPLE_MPC_MEANROT
  use superjoin_model_notes, only: note
  use superjoin_utils_strings, only: itoa, pick
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none (type, external)
  private

  public :: build_couplings

  real(wp), parameter :: SINGULAR_J = 1.0e-10_wp
    !! det J below this fraction of (trace J / 3)^3: the coupled nodes lie on a line
  integer, parameter :: MPC_MIN_NODES(3) = [2, 4, 3]
    !! nodes an *MPC BEAM needs, and at least a PLANE and a STRAIGHT
  real(wp), parameter :: COEF_ZERO = 1.0e-14_wp
    !! coefficients below this fraction of the equation's largest are round-off, left out

  type :: coupled_t
    !! A coupling resolved to local nodes.
     integer :: kind = COUPLE_NONE
     integer :: rsub = 0                   !! reference node
     integer(ip) :: rnode = 0
     integer :: tsub = 0                   !! the node whose DOFs toff+1..toff+3 are θ
     integer(ip) :: tnode = 0
     integer :: toff = 3
     integer :: csub = 0                   !! coupled nodes (all in one substructure)
     integer(ip), allocatable :: nodes(:)
     real(wp), allocatable :: w(:)         !! their weights (distributing)
     logical :: dofs(NDOF_NODE) = .false.
     type(source_loc_t) :: loc
  end type coupled_t

  type :: eq_list_t
    !! Equations built so far.
     type(equation_t), allocatable :: e(:)
     integer :: n = 0
  end type eq_list_t

contains

  subroutine build_couplings(st, model)
    !! Append the constraint equations of every coupling read to model%equations
    !! (none when the deck has errors already: they are checked once it has none).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(eq_list_t) :: list
    type(halting_t) :: saved
    integer :: k, n0
    if (.not. allocated(st%couplings)) return
    do k = 1, size(st%couplings)
       if (st%couplings(k)%ok .and. st%couplings(k)%kind == COUPLE_NONE) call report_loc(st, st%couplings(k)%loc, &
            '*COUPLING needs *KINEMATIC or *DISTRIBUTING right after it')
    end do
    ! after an error the model may be incomplete (an element on an undefined node): nothing to couple
    if (allocated(st%error)) return
    allocate (list%e(8))
    call halting_off(saved)   ! weights and positions near the range's end: each coupling's equations checked
    do k = 1, size(st%couplings)
       n0 = list%n
       call one_coupling(st, model, st%couplings(k), list)
       if (any_overflow(list, n0)) then
          call report_loc(st, st%couplings(k)%loc, 'the coupling''s equations overflow the floating-point '// &
               'range (beyond 1.8E+308 or undefined): check the weights and the coordinates of its nodes')
          list%n = n0
       end if
    end do
    call halting_restore(saved)
    if (.not. allocated(model%equations)) allocate (model%equations(0))
    model%equations = [model%equations, list%e(1:list%n)]
  end subroutine build_couplings

  logical function any_overflow(list, n0) result(bad)
    !! Whether an equation after the first n0 of list has a coefficient that is not finite.
    type(eq_list_t), intent(in) :: list
    integer, intent(in) :: n0
    integer :: k
    bad = .false.
    do k = n0 + 1, list%n
       bad = .not. all(ieee_is_finite(list%e(k)%coef))
       if (bad) return
    end do
  end function any_overflow

  subroutine one_coupling(st, model, cb, list)
    !! The equations of coupling cb appended to list (build_couplings).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(coupling_b_t), intent(in) :: cb
    type(eq_list_t), intent(inout) :: list
    type(coupled_t) :: cp
    logical :: ok
    if (.not. cb%ok .or. cb%kind == COUPLE_NONE) return
    if (cb%kind == COUPLE_DCOUP) then
       call dcoup(st, model, cb, list)
       return
    end if
    if (cb%kind >= COUPLE_MPC_BEAM) then
       call mpc(st, model, cb, list)
       return
    end if
    call resolve_coupling(st, model, cb, cp, ok)
    if (.not. ok) return
    if (cb%has_rot) then
       if (.not. allocated(model%rot_node)) allocate (model%rot_sub(0), model%rot_node(0))
       model%rot_sub = [model%rot_sub, cp%tsub]
       model%rot_node = [model%rot_node, cp%tnode]
    end if
    if (cp%kind == COUPLE_DISTRIBUTING) then
       call distributing(st, model, cp, list)
    else
       call kinematic(model, cp, list)
    end if
  end subroutine one_coupling

  subroutine resolve_coupling(st, model, cb, cp, ok)
    !! Reference node, rotation node and coupled nodes (with weights) of a coupling.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupling_b_t), intent(in) :: cb
    type(coupled_t), intent(out) :: cp
    logical, intent(out) :: ok
    real(wp), allocatable :: wnode(:)
    integer(ip) :: i
    cp%kind = cb%kind
    cp%loc = cb%loc
    cp%dofs = cb%dofs
    if (.not. cb%dofs_given) then
       cp%dofs(1:3) = .true.
       if (cb%kind /= COUPLE_KINEMATIC) cp%dofs = .true.
    end if
    call one_node(st, model, cb%ref_node, cb%loc, cp%rsub, cp%rnode, ok)
    if (.not. ok) return
    cp%tsub = cp%rsub
    cp%tnode = cp%rnode
    if (cb%has_rot) then
       call one_node(st, model, cb%rot_node, cb%loc, cp%tsub, cp%tnode, ok)
       if (.not. ok) return
       cp%toff = 0
    end if
    if (cb%kind == COUPLE_RIGID_BODY) then
       call set_nodes(st, model, cb, cp%csub, wnode, ok)
    else
       call surface_nodes(st, model, cb, cp%csub, wnode, ok)
    end if
    if (.not. ok) return
    if (cp%csub == cp%rsub) wnode(cp%rnode) = 0.0_wp
    if (cp%csub == cp%tsub .and. cb%has_rot) wnode(cp%tnode) = 0.0_wp
    ! the corners of 8-node faces weigh less than nothing (-A/12): a node is coupled when its weight is not 0
    cp%nodes = pack([(i, i = 1_ip, size(wnode, kind=ip))], wnode /= 0.0_wp)
    cp%w = pack(wnode, wnode /= 0.0_wp)
    ok = size(cp%nodes) > 0
    if (.not. ok) call report_loc(st, cb%loc, 'the coupling has no nodes to couple besides its reference node')
  end subroutine resolve_coupling

  subroutine one_node(st, model, ref, loc, isub, node, ok)
    !! The single node a reference names.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(ref_t), intent(in) :: ref
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: isub
    integer(ip), intent(out) :: node
    logical, intent(out) :: ok
    integer(ip), allocatable :: items(:)
    node = 0
    ok = .false.
    isub = resolve_sub(st, model, ref, loc, 'node')
    if (isub == 0) return
    call resolve_items(st, model, isub, ref, .false., loc, items, ok)
    if (.not. ok) return
    ok = size(items) == 1
    if (ok) then
       node = items(1)
    else
       call report_loc(st, loc, 'a reference node must be one node, not a set of '//itoa(size(items)))
    end if
  end subroutine one_node

  subroutine set_nodes(st, model, cb, isub, wnode, ok)
    !! Nodes of *RIGID BODY's NSET= (or of the elements of ELSET=), weight 1.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupling_b_t), intent(in) :: cb
    integer, intent(out) :: isub
    real(wp), allocatable, intent(out) :: wnode(:)
    logical, intent(out) :: ok
    integer(ip), allocatable :: items(:)
    integer(ip) :: k
    ok = .false.
    isub = resolve_sub(st, model, cb%nodes, cb%loc, pick(cb%by_elements, 'element', 'node'))
    if (isub == 0) return
    call resolve_items(st, model, isub, cb%nodes, cb%by_elements, cb%loc, items, ok)
    if (.not. ok) return
    allocate (wnode(model%subs(isub)%nnode), source=0.0_wp)
    if (.not. cb%by_elements) then
       wnode(items) = 1.0_wp
       return
    end if
    do k = 1, size(items, kind=ip)
       associate (s => model%subs(isub))
         wnode(s%elem_nodes(1:ELEMENT_NODE_COUNT(s%elem_type(items(k))), items(k))) = 1.0_wp
       end associate
    end do
  end subroutine set_nodes

  subroutine surface_nodes(st, model, cb, isub, wnode, ok)
    !! Nodes of *COUPLING's element surface, each weighted by its area on the
    !! surface's faces, ∫ N_a dA (as CalculiX).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupling_b_t), intent(in) :: cb
    integer, intent(out) :: isub
    real(wp), allocatable, intent(out) :: wnode(:)
    logical, intent(out) :: ok
    integer :: k, i, face, s, nc
    integer(ip) :: e
    integer(ip), allocatable :: items(:)
    integer, allocatable :: fn(:)
    isub = 0
    ok = .false.
    do k = 1, st%nsurface
       if (st%surfaces(k)%name == cb%surface) exit
    end do
    if (k > st%nsurface) then
       call report_loc(st, cb%loc, 'unknown surface '''//cb%surface//''' (define it with *SURFACE, TYPE=ELEMENT)')
       return
    end if
    associate (sf => st%surfaces(k))
      if (sf%nodal) then
         call node_surface_nodes(st, model, cb, sf, isub, wnode, ok)
         return
      end if
      do i = 1, sf%n
         s = resolve_sub(st, model, sf%refs(i), sf%loc, 'element')
         if (.not. same_sub(st, model, cb, s, isub, wnode)) return
         call resolve_items(st, model, isub, sf%refs(i), .true., sf%loc, items, ok)
         if (.not. ok) return
         face = face_of(sf%kinds(i))
         do e = 1, size(items, kind=ip)
            call solid_face_nodes(model%subs(isub)%elem_type(items(e)), face, fn, nc)
            if (size(fn) == 0) then
               call report_loc(st, cb%loc, 'surface '//cb%surface//': face S'//itoa(face)//' of element '// &
                    itoa(model%subs(isub)%elem_id(items(e)))//' is not a face of a solid (a coupling takes '// &
                    'the faces of solid elements)')
               ok = .false.
               return
            end if
            call add_face(model%subs(isub), items(e), face, wnode)
         end do
      end do
    end associate
    ok = isub > 0
  end subroutine surface_nodes

  logical function same_sub(st, model, cb, s, isub, wnode) result(ok)
    !! Substructure s of a surface line (0: its error reported) is the
    !! surface's: the first sets isub and allocates the weights wnode; another
    !! is the error of a surface over two substructures.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupling_b_t), intent(in) :: cb
    integer, intent(in) :: s
    integer, intent(inout) :: isub
    real(wp), allocatable, intent(inout) :: wnode(:)
    ok = s /= 0
    if (.not. ok) return
    if (isub == 0) then
       isub = s
       allocate (wnode(model%subs(isub)%nnode), source=0.0_wp)
    else if (s /= isub) then
       call report_loc(st, cb%loc, 'surface '//cb%surface//' spans two substructures (a coupling''s '// &
            'surface must lie in one)')
       ok = .false.
    end if
  end function same_sub

  subroutine node_surface_nodes(st, model, cb, sf, isub, wnode, ok)
    !! The nodes of a node surface (*SURFACE, TYPE=NODE), weight 1: a kinematic
    !! coupling's only (as CalculiX, which refuses it under *DISTRIBUTING: the
    !! distributing coupling's weights are the faces' areas).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupling_b_t), intent(in) :: cb
    type(surface_b_t), intent(in) :: sf
    integer, intent(out) :: isub
    real(wp), allocatable, intent(out) :: wnode(:)
    logical, intent(out) :: ok
    integer(ip), allocatable :: items(:)
    integer :: i, s
    isub = 0
    ok = .false.
    if (cb%kind /= COUPLE_KINEMATIC) then
       call report_loc(st, cb%loc, 'surface '//cb%surface//' is a node surface: *DISTRIBUTING takes an element '// &
            'face surface (*SURFACE, TYPE=ELEMENT; its weights are the faces'' areas), as CalculiX; a node '// &
            'surface couples under *KINEMATIC')
       return
    end if
    do i = 1, sf%n
       s = resolve_sub(st, model, sf%refs(i), sf%loc, 'node')
       if (.not. same_sub(st, model, cb, s, isub, wnode)) return
       call resolve_items(st, model, isub, sf%refs(i), .false., sf%loc, items, ok)
       if (.not. ok) return
       wnode(items) = 1.0_wp
    end do
    ok = isub > 0
  end subroutine node_surface_nodes

  pure integer function face_of(kind)
    !! Face number 1..6 of a surface line's load kind (DLOAD_P1..P6).
    integer, intent(in) :: kind
    if (kind >= DLOAD_P1 .and. kind <= DLOAD_P4) then
       face_of = kind - DLOAD_P1 + 1
    else if (kind == DLOAD_P5) then
       face_of = 5
    else if (kind == DLOAD_P6) then
       face_of = 6
    else
       face_of = 0
    end if
  end function face_of

  subroutine add_face(sub, e, face, wnode)
    !! Add ∫ N_a dA of face `face` of element e to the weight of each of its
    !! nodes a (its consistent nodal area, a pressure's nodal forces along the
    !! normal: A/4 on a flat 4-node face, -A/12 and A/3 on the corners and
    !! mid-sides of an 8-node one).
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: e
    integer, intent(in) :: face
    real(wp), intent(inout) :: wnode(:)
    real(wp), allocatable :: fe(:)
    type(error_t), allocatable :: error
    real(wp) :: normal(3)
    integer :: k, nn
    nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
    call solid_pressure_load(sub%elem_type(e), sub%x(:, sub%elem_nodes(1:nn, e)), face, 1.0_wp, fe, error)
    if (allocated(error)) return
    normal = 0.0_wp
    do k = 1, nn
       normal = normal + fe(3*k - 2:3*k)
    end do
    if (norm2(normal) == 0.0_wp) return
    normal = normal/norm2(normal)
    do k = 1, nn
       wnode(sub%elem_nodes(k, e)) = wnode(sub%elem_nodes(k, e)) + dot_product(fe(3*k - 2:3*k), normal)
    end do
  end subroutine add_face

  subroutine kinematic(model, cp, list)
    !! u_i = u_r + θ × (x_i - x_r) on the coupled translations, θ_i = θ on the
    !! coupled rotations of nodes that have rotations.
    type(model_t), intent(in) :: model
    type(coupled_t), intent(in) :: cp
    type(eq_list_t), intent(inout) :: list
    logical, allocatable :: rot(:)
    integer :: k, d, a, b
    real(wp) :: r(3)
    call rotation_nodes(model, cp%csub, rot)
    do k = 1, size(cp%nodes)
       r = model%subs(cp%csub)%x(:, cp%nodes(k)) - model%subs(cp%rsub)%x(:, cp%rnode)
       do d = 1, 3
          if (.not. cp%dofs(d)) cycle
          a = mod(d, 3) + 1
          b = mod(d + 1, 3) + 1
          ! u_i,d - u_r,d - (θ_a r_b - θ_b r_a) = 0
          call push(list, cp%loc, [cp%csub, cp%rsub, cp%tsub, cp%tsub], [cp%nodes(k), cp%rnode, cp%tnode, cp%tnode], &
               [d, d, cp%toff + a, cp%toff + b], [1.0_wp, -1.0_wp, -r(b), r(a)])
       end do
       if (.not. rot(cp%nodes(k))) cycle
       do d = 4, 6
          if (.not. cp%dofs(d)) cycle
          call push(list, cp%loc, [cp%csub, cp%tsub], [cp%nodes(k), cp%tnode], [d, cp%toff + d - 3], &
               [1.0_wp, -1.0_wp])
       end do
    end do
  end subroutine kinematic

  subroutine rotation_nodes(model, isub, rot)
    !! rot(node): an element of the node gives it rotations.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    logical, allocatable, intent(out) :: rot(:)
    integer(ip) :: e
    logical :: mask(NDOF_NODE)
    associate (s => model%subs(isub))
      allocate (rot(s%nnode), source=.false.)
      do e = 1, s%nelem
         mask = element_dof_mask(s%elem_type(e))
         if (.not. any(mask(4:6))) cycle
         rot(s%elem_nodes(1:ELEMENT_NODE_COUNT(s%elem_type(e)), e)) = .true.
      end do
    end associate
  end subroutine rotation_nodes

  subroutine distributing(st, model, cp, list)
    !! The reference node's coupled DOFs as the weighted least-squares rigid
    !! motion of the coupled nodes' translations (module comment).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupled_t), intent(in) :: cp
    type(eq_list_t), intent(inout) :: list
    real(wp) :: xbar(3), jm(3, 3), jinv(3, 3), dr(3), wsum, det, scale
    real(wp), allocatable :: rho(:, :), c(:, :, :), a(:, :, :)
    integer :: k, n, d
    logical :: need_rot
    n = size(cp%nodes)
    wsum = sum(cp%w)
    if (.not. wsum > 0.0_wp) then
       call report_loc(st, cp%loc, '*DISTRIBUTING: the surface has no area')
       return
    end if
    if (.not. ieee_is_finite(wsum)) then
       call report_loc(st, cp%loc, '*DISTRIBUTING: the sum of the weights overflows the floating-point range '// &
            '(beyond 1.8E+308): check the weights and their units')
       return
    end if
    associate (x => model%subs(cp%csub)%x)
      do d = 1, 3
         xbar(d) = sum(cp%w*x(d, cp%nodes))/wsum
      end do
      allocate (rho(3, n), c(3, 3, n), a(3, 3, n))
      jm = 0.0_wp
      do k = 1, n
         rho(:, k) = x(:, cp%nodes(k)) - xbar
         jm = jm - cp%w(k)*matmul(skew(rho(:, k)), skew(rho(:, k)))
      end do
    end associate
    dr = model%subs(cp%rsub)%x(:, cp%rnode) - xbar
    scale = maxval(abs(rho))
    need_rot = any(cp%dofs(4:6)) .or. maxval(abs(dr)) > 1.0e-12_wp*scale
    det = det3(jm)
    if (need_rot .and. (n < 3 .or. abs(det) <= SINGULAR_J*(max((jm(1, 1) + jm(2, 2) + jm(3, 3))/3.0_wp, &
         tiny(1.0_wp)))**3)) then
       call report_loc(st, cp%loc, '*DISTRIBUTING: the coupled nodes lie on a line, so the rotation about it '// &
            'is undetermined (couple DOFs 1-3 only, with the reference node at their weighted centre)')
       return
    end if
    jinv = 0.0_wp
    if (need_rot) jinv = inv3(jm, det)
    do k = 1, n
       c(:, :, k) = cp%w(k)*matmul(jinv, skew(rho(:, k)))
       a(:, :, k) = -matmul(skew(dr), c(:, :, k))
       do d = 1, 3
          a(d, d, k) = a(d, d, k) + cp%w(k)/wsum
       end do
    end do
    do d = 1, 3
       if (cp%dofs(d)) call push_rbe3(list, cp, d, a(d, :, :))
       if (cp%dofs(d + 3)) call push_rbe3(list, cp, d + 3, c(d, :, :))
    end do
  end subroutine distributing

  subroutine push_rbe3(list, cp, dof, coef)
    !! u_r(dof) - Σ_k Σ_e coef(e, k) u_k,e = 0.
    type(eq_list_t), intent(inout) :: list
    type(coupled_t), intent(in) :: cp
    integer, intent(in) :: dof
    real(wp), intent(in) :: coef(:, :)
    integer :: n, k, e, t
    n = size(cp%nodes)
    block
      integer :: subs(1 + 3*n), dofs(1 + 3*n)
      integer(ip) :: nodes(1 + 3*n)
      real(wp) :: cs(1 + 3*n)
      subs(1) = cp%rsub
      nodes(1) = cp%rnode
      dofs(1) = dof
      cs(1) = 1.0_wp
      t = 1
      do k = 1, n
         do e = 1, 3
            t = t + 1
            subs(t) = cp%csub
            nodes(t) = cp%nodes(k)
            dofs(t) = e
            cs(t) = -coef(e, k)
         end do
      end do
      call push(list, cp%loc, subs, nodes, dofs, cs)
    end block
  end subroutine push_rbe3

  subroutine dcoup(st, model, cb, list)
    !! A DCOUP3D element and its *DISTRIBUTING COUPLING nodes (module comment).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(coupling_b_t), intent(in) :: cb
    type(eq_list_t), intent(inout) :: list
    type(coupled_t) :: cp
    real(wp), allocatable :: wnode(:)
    integer(ip), allocatable :: items(:)
    integer(ip) :: i
    integer :: k, s, d, n
    logical :: ok
    if (size(cb%list) == 0) then
       call report_loc(st, cb%loc, 'the DCOUP3D element of element set '//cb%name// &
            ' has no *DISTRIBUTING COUPLING, ELSET='//cb%name//' (its coupled nodes and weights)')
       return
    end if
    call one_node(st, model, cb%ref_node, cb%loc, cp%rsub, cp%rnode, ok)
    if (.not. ok) return
    do k = 1, size(cb%list)
       s = resolve_sub(st, model, cb%list(k), cb%weights_loc, 'node')
       if (s == 0) return
       if (cp%csub == 0) then
          cp%csub = s
          allocate (wnode(model%subs(s)%nnode), source=0.0_wp)
       else if (s /= cp%csub) then
          call report_loc(st, cb%weights_loc, 'the *DISTRIBUTING COUPLING of element set '//cb%name// &
               ' spans two substructures (its nodes must lie in one)')
          return
       end if
       call resolve_items(st, model, s, cb%list(k), .false., cb%weights_loc, items, ok)
       if (.not. ok) return
       wnode(items) = wnode(items) + cb%weights(k)
    end do
    if (cp%csub == cp%rsub) wnode(cp%rnode) = 0.0_wp
    cp%nodes = pack([(i, i = 1_ip, size(wnode, kind=ip))], wnode /= 0.0_wp)
    cp%w = pack(wnode, wnode /= 0.0_wp)
    n = size(cp%nodes)
    if (n < 2) then
       call report_loc(st, cb%weights_loc, 'the *DISTRIBUTING COUPLING of element set '//cb%name// &
            ' needs at least two nodes besides its reference node')
       return
    end if
    cp%loc = cb%loc
    cp%tsub = cp%rsub
    cp%tnode = cp%rnode
    if (.not. ieee_is_finite(sum(cp%w))) then   ! at the card that gives them
       call report_loc(st, cb%weights_loc, 'the weights of the *DISTRIBUTING COUPLING of element set '//cb%name// &
            ' sum beyond the floating-point range (1.8E+308): check them and their units')
       return
    end if
    if (reading_dialect(st) == DIALECT_CALCULIX) then
       do d = 1, 3
          call push(list, cb%loc, [cp%rsub, spread(cp%csub, 1, n)], [cp%rnode, cp%nodes], [d, spread(d, 1, n)], &
               [1.0_wp, -cp%w/sum(cp%w)])
       end do
       call note(model%notes, 'DCOUP3D at '//where(st, cb%loc)//': read as CalculiX''s distributing coupling, '// &
            'the reference node''s translations the weighted mean of its nodes'' (Abaqus''s also carries '// &
            'moments, from the reference node''s position: *CONTROLS, DIALECT=ABAQUS)')
    else
       cp%kind = COUPLE_DISTRIBUTING
       cp%dofs = .true.
       call distributing(st, model, cp, list)
       call note(model%notes, 'DCOUP3D at '//where(st, cb%loc)//': read as Abaqus''s distributing coupling '// &
            '(forces and moments, DOFs 1-6; CalculiX''s is the weighted mean of the translations alone: '// &
            '*CONTROLS, DIALECT=CALCULIX)')
    end if
  end subroutine dcoup

  subroutine mpc(st, model, cb, list)
    !! *MPC, linearised (x_i, u_i: the i-th node listed):
    !! BEAM a, b: (x_b - x_a)·(u_b - u_a) = 0;
    !! PLANE 1, 2, 3, p...: n·(u_p - u_1) + (b × d)·(u_2 - u_1) + (d × a)·(u_3 - u_1) = 0,
    !!   a = x_2 - x_1, b = x_3 - x_1, n = a × b, d = x_p - x_1 (the variation of d·n);
    !! STRAIGHT 1, 2, p...: (u_p - u_1) × t + d × (u_2 - u_1) = 0 on the two
    !!   components across t = x_2 - x_1, d = x_p - x_1 (the variation of d × t).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupling_b_t), intent(in) :: cb
    type(eq_list_t), intent(inout) :: list
    integer, allocatable :: subs(:)
    integer(ip), allocatable :: nodes(:)
    real(wp), allocatable :: x(:, :)
    integer :: need, k
    logical :: ok
    call mpc_nodes(st, model, cb, subs, nodes, ok)
    if (.not. ok) return
    if (cb%kind == COUPLE_MPC_MEANROT) then
       call mpc_meanrot(st, model, cb%loc, subs, nodes, list)
       return
    end if
    need = MPC_MIN_NODES(cb%kind - COUPLE_MPC_BEAM + 1)
    if (size(nodes) < need .or. (cb%kind == COUPLE_MPC_BEAM .and. size(nodes) /= need)) then
       call report_loc(st, cb%loc, '*MPC: '//mpc_name(cb%kind)//' needs '//trim(merge('exactly ', 'at least', &
            cb%kind == COUPLE_MPC_BEAM))//' '//itoa(need)//' nodes, got '//itoa(size(nodes)))
       return
    end if
    allocate (x(3, size(nodes)))
    do k = 1, size(nodes)
       x(:, k) = model%subs(subs(k))%x(:, nodes(k))
    end do
    if (degenerate(cb%kind, x)) then
       call report_loc(st, cb%loc, '*MPC: the defining nodes of '//mpc_name(cb%kind)//' '// &
            trim(merge('coincide          ', 'lie on a line     ', cb%kind /= COUPLE_MPC_PLANE))// &
            ' (they define no direction)')
       return
    end if
    select case (cb%kind)
    case (COUPLE_MPC_BEAM)
       call mpc_row(list, cb%loc, subs([2, 1]), nodes([2, 1]), reshape([x(:, 2) - x(:, 1), x(:, 1) - x(:, 2)], [3, 2]))
    case (COUPLE_MPC_PLANE)
       call mpc_plane(list, cb%loc, subs, nodes, x)
    case default
       call mpc_straight(list, cb%loc, subs, nodes, x)
    end select
  end subroutine mpc

  pure logical function degenerate(kind, x)
    !! The defining nodes give no direction: BEAM's and STRAIGHT's first two
    !! coincide, PLANE's first three lie on a line (relative to their distances).
    integer, intent(in) :: kind
    real(wp), intent(in) :: x(:, :)
    real(wp) :: a(3), b(3)
    a = x(:, 2) - x(:, 1)
    if (kind == COUPLE_MPC_PLANE) then
       b = x(:, 3) - x(:, 1)
       degenerate = norm2(cross(a, b)) <= 1.0e-12_wp*norm2(a)*norm2(b)
    else
       degenerate = norm2(a) == 0.0_wp
    end if
  end function degenerate

  pure function cross(a, b) result(c)
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross

  pure function mpc_name(kind) result(s)
    integer, intent(in) :: kind
    character(:), allocatable :: s
    select case (kind)
    case (COUPLE_MPC_BEAM)
       s = 'BEAM'
    case (COUPLE_MPC_PLANE)
       s = 'PLANE'
    case (COUPLE_MPC_MEANROT)
       s = 'MEANROT'
    case default
       s = 'STRAIGHT'
    end select
  end function mpc_name

  subroutine mpc_nodes(st, model, cb, subs, nodes, ok)
    !! The nodes an *MPC lists (sets expanded in their order).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(coupling_b_t), intent(in) :: cb
    integer, allocatable, intent(out) :: subs(:)
    integer(ip), allocatable, intent(out) :: nodes(:)
    logical, intent(out) :: ok
    integer(ip), allocatable :: items(:)
    integer :: k, isub
    allocate (subs(0), nodes(0))
    ok = .false.
    do k = 1, size(cb%list)
       isub = resolve_sub(st, model, cb%list(k), cb%loc, 'node')
       if (isub == 0) return
       call resolve_items(st, model, isub, cb%list(k), .false., cb%loc, items, ok)
       if (.not. ok) return
       nodes = [nodes, items]
       subs = [subs, spread(isub, 1, size(items))]
    end do
    ok = .true.
  end subroutine mpc_nodes

  subroutine mpc_meanrot(st, model, loc, subs, nodes, list)
    !! *MPC MEANROT (CalculiX): each participating node listed three times (one
    !! per DOF), then an extra node whose position gives the axis a and whose
    !! DOF 1 is the mean rotation θ about it. Linearised: with c the centroid of
    !! the m participating nodes, r_j = x_j - c, w_j = a × r_j, each node's
    !! rotation about the axis through c is θ_j = w_j·(u_j - ū)/|w_j|² (ū the
    !! mean of the u_j: a translation turns nothing), and θ is their mean over
    !! the m nodes, a node on the axis (w_j = 0) counting with the angle 0, as
    !! ccx 2.20 does (measured on beammrlin with the whole tip face in the MPC):
    !!   Σ_j (g_j - ḡ)·u_j / m - θ = 0,  g_j = w_j/|w_j|² (0 on the axis), ḡ = Σ g_j / m.
    !! A rigid turn by θ about any parallel axis satisfies it; its transpose
    !! spreads a *CLOAD on the extra node's DOF 1 (a torque) over the nodes.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    type(eq_list_t), intent(inout) :: list
    real(wp), allocatable :: x(:, :), g(:, :), c(:, :)
    real(wp) :: a(3), w(3), q, qmax
    integer, allocatable :: order(:)
    integer :: n, m, j, k, first
    n = size(nodes)
    m = (n - 1)/3
    if (n < 4 .or. mod(n - 1, 3) /= 0) then
       call report_loc(st, loc, '*MPC MEANROT lists each node three times (once per DOF), then the node whose '// &
            'position gives the axis and whose DOF 1 is the rotation: got '//itoa(n)//' nodes')
       return
    end if
    do j = 1, m
       if (any(nodes(3*j - 2:3*j) /= nodes(3*j - 2)) .or. any(subs(3*j - 2:3*j) /= subs(3*j - 2))) then
          call report_loc(st, loc, '*MPC MEANROT lists each node three times in a row (once per DOF): entries '// &
               itoa(3*j - 2)//' to '//itoa(3*j)//' differ')
          return
       end if
    end do
    a = model%subs(subs(n))%x(:, nodes(n))
    if (norm2(a) == 0.0_wp) then
       call report_loc(st, loc, '*MPC MEANROT: the last node lies at the origin (its coordinates are the axis)')
       return
    end if
    a = a/norm2(a)
    allocate (x(3, m), g(3, m), source=0.0_wp)
    do j = 1, m
       x(:, j) = model%subs(subs(3*j))%x(:, nodes(3*j))
    end do
    qmax = 0.0_wp
    do j = 1, m
       qmax = max(qmax, sum(cross(a, x(:, j) - sum(x, dim=2)/m)**2))
    end do
    k = 0
    do j = 1, m
       w = cross(a, x(:, j) - sum(x, dim=2)/m)
       q = sum(w**2)
       if (q <= 1.0e-20_wp*qmax .or. q == 0.0_wp) cycle   ! on the axis: no rotation about it
       g(:, j) = w/q
       k = k + 1
    end do
    if (k == 0) then
       call report_loc(st, loc, '*MPC MEANROT: every node lies on the rotation axis (no rotation about it to average)')
       return
    end if
    allocate (c(3, m + 1), source=0.0_wp)
    do j = 1, m
       c(:, j) = (g(:, j) - sum(g, dim=2)/m)/m
    end do
    c(1, m + 1) = -1.0_wp
    ! the dependent DOF: the participating node of largest coefficient first
    first = maxloc([(maxval(abs(c(:, j))), j = 1, m)], 1)
    order = [first, pack([(j, j = 1, m)], [(j /= first, j = 1, m)]), m + 1]
    call mpc_row(list, loc, [subs(3*order(1:m)), subs(n)], [nodes(3*order(1:m)), nodes(n)], c(:, order))
    list%e(list%n)%torque_node = .true.
  end subroutine mpc_meanrot

  subroutine mpc_plane(list, loc, subs, nodes, x)
    !! One equation per node after the third (mpc comment).
    type(eq_list_t), intent(inout) :: list
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(in) :: x(:, :)
    real(wp) :: a(3), b(3), n(3), d(3), c2(3), c3(3)
    integer :: p
    a = x(:, 2) - x(:, 1)
    b = x(:, 3) - x(:, 1)
    n = cross(a, b)
    do p = 4, size(nodes)
       d = x(:, p) - x(:, 1)
       c2 = cross(b, d)
       c3 = cross(d, a)
       call mpc_row(list, loc, subs([p, 1, 2, 3]), nodes([p, 1, 2, 3]), &
            reshape([n, -n - c2 - c3, c2, c3], [3, 4]))
    end do
  end subroutine mpc_plane

  subroutine mpc_straight(list, loc, subs, nodes, x)
    !! Two equations per node after the second (mpc comment): the components
    !! a /= m of the cross products, m the largest component of t.
    type(eq_list_t), intent(inout) :: list
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(in) :: x(:, :)
    real(wp) :: t(3), d(3), st(3, 3), sd(3, 3)
    integer :: p, m, ia
    t = x(:, 2) - x(:, 1)
    m = maxloc(abs(t), 1)
    st = skew(t)
    do p = 3, size(nodes)
       d = x(:, p) - x(:, 1)
       sd = skew(d)
       ! (u_p - u_1) × t = -skew(t) (u_p - u_1); d × (u_2 - u_1) = skew(d) (u_2 - u_1)
       do ia = 1, 3
          if (ia == m) cycle
          call mpc_row(list, loc, subs([p, 1, 2]), nodes([p, 1, 2]), &
               reshape([-st(ia, :), st(ia, :) - sd(ia, :), sd(ia, :)], [3, 3]))
       end do
    end do
  end subroutine mpc_straight

  subroutine mpc_row(list, loc, subs, nodes, c)
    !! Σ_k c(:, k)·u(node k) = 0; the dependent DOF is the first node's
    !! component of largest coefficient.
    type(eq_list_t), intent(inout) :: list
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(in) :: c(:, :)
    integer :: order(3), k, j, n
    n = size(nodes)
    j = maxloc(abs(c(:, 1)), 1)
    order = [j, mod(j, 3) + 1, mod(j + 1, 3) + 1]
    call push(list, loc, [(subs((k - 1)/3 + 1), k = 1, 3*n)], [(nodes((k - 1)/3 + 1), k = 1, 3*n)], &
         [(order, k = 1, n)], [(c(order, k), k = 1, n)])
  end subroutine mpc_row

  subroutine push(list, loc, subs, nodes, dofs, coefs)
    !! Append one equation; terms whose coefficient is round-off are left out
    !! (never the first, the dependent DOF).
    type(eq_list_t), intent(inout) :: list
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: subs(:), dofs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(in) :: coefs(:)
    type(equation_t), allocatable :: tmp(:)
    logical :: keep(size(coefs))
    keep = abs(coefs) > COEF_ZERO*maxval(abs(coefs))
    keep(1) = .true.
    if (list%n == size(list%e)) then
       allocate (tmp(2*list%n))
       tmp(1:list%n) = list%e(1:list%n)
       call move_alloc(tmp, list%e)
    end if
    list%n = list%n + 1
    associate (e => list%e(list%n))
      e%sub = pack(subs, keep)
      e%node = pack(nodes, keep)
      e%dof = pack(dofs, keep)
      e%coef = pack(coefs, keep)
      e%loc = loc
      e%coupling = .true.
    end associate
  end subroutine push

  pure function skew(v) result(s)
    !! The matrix of v × (.).
    real(wp), intent(in) :: v(3)
    real(wp) :: s(3, 3)
    s = reshape([0.0_wp, v(3), -v(2), -v(3), 0.0_wp, v(1), v(2), -v(1), 0.0_wp], [3, 3])
  end function skew

  pure real(wp) function det3(m)
    real(wp), intent(in) :: m(3, 3)
    det3 = m(1, 1)*(m(2, 2)*m(3, 3) - m(2, 3)*m(3, 2)) - m(1, 2)*(m(2, 1)*m(3, 3) - m(2, 3)*m(3, 1)) + &
         m(1, 3)*(m(2, 1)*m(3, 2) - m(2, 2)*m(3, 1))
  end function det3

  pure function inv3(m, det) result(v)
    !! Inverse of a 3 x 3 matrix of determinant det (adjugate).
    real(wp), intent(in) :: m(3, 3), det
    real(wp) :: v(3, 3)
    integer :: i, j, i1, i2, j1, j2
    do i = 1, 3
       do j = 1, 3
          i1 = mod(i, 3) + 1
          i2 = mod(i + 1, 3) + 1
          j1 = mod(j, 3) + 1
          j2 = mod(j + 1, 3) + 1
          v(j, i) = (m(i1, j1)*m(i2, j2) - m(i1, j2)*m(i2, j1))/det
       end do
    end do
  end function inv3

end module superjoin_deck_coupling_build
