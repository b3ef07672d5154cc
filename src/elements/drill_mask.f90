module superjoin_elements_drill_mask
  !! Where the drilling membrane of superjoin_elements_drilling may carry its
  !! edge bubbles: only on edges whose two end nodes are flat, a flat node being
  !! one where every attached three- or four-node shell (S3, S4, S3R, S4R) lies
  !! in the same plane (element normals parallel within FLAT_ANGLE_TOL, either
  !! sense). Elsewhere the edges stay straight, and an element without any
  !! bubble is the CST / QM6 with soft drilling springs. The same mask gives
  !! the S3/S3R triangles (superjoin_elements_opt_triangle) their α_b edge
  !! terms and the corners of their higher-order stiffness.
  !!
  !! Why: where the facets of a curved surface meet at an angle, part of a
  !! node's bending rotation is the θz of the neighbouring facets, and the
  !! bubbles (driven by θz differences along an edge) then stiffen bending:
  !! the coarse pinched hemisphere locks (doc/verification.md, "Drilling
  !! membranes"). On a flat region θz is the in-plane rotation and the bubbles
  !! give the in-plane bending the 4-node membrane lacks.
  !!
  !! Conformity: the mask is a property of the edge (its two nodes), so the two
  !! elements sharing an edge both carry its bubble or both leave it straight,
  !! and the bubble amplitude (θⱼ - θᵢ) l/8 along the normal is the same from
  !! both sides: the nodal field stays conforming. The constant-stress patch
  !! test holds with any mask (a linear field with θ = its rotation makes every
  !! bubble amplitude zero; the consistent edge moments of an interior edge
  !! cancel between its two elements because both carry the bubble or neither).
  !! An S8R at a node counts as not flat (its rotations are those of a curved
  !! shell); beams and other elements do not count.
  !!
  !! Restrained edges: an edge whose two end nodes both have the translation
  !! normal to the edge in the shell plane fixed (*BOUNDARY or a rigid
  !! *SUPPORT, model data or any step, in global axes or the node's *TRANSFORM
  !! axes) stays straight too. The boundary condition u_n = 0 (or the
  !! prescribed values) then holds along the whole edge, not only at its
  !! nodes; with the bubble, θz left free at such nodes (a symmetry plane
  !! modelled with translations only, enough for the springs of the CST/QM6)
  !! would let the edge bow off its plane between the nodes by (θⱼ - θᵢ) l/8.
  !! Removing a bubble is always admissible (the edge is then shared by its
  !! elements as a straight edge), so the rule needs no step of its own.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: substructure_t, ELEMENT_NODE_COUNT, ET_S3, ET_S4, ET_S3R, ET_S4R
  use superjoin_elements_traits, only: is_shell8
  use superjoin_model_types, only: model_t, support_t, LINK_RIGID, LINK_NONE
  use superjoin_elements_shell, only: shell_frame, DRILL_ALL_EDGES
  use superjoin_elements_frame, only: cross
  implicit none (type, external)
  private

  public :: drill_edge_masks, element_drill, mark_drilling_edges, FLAT_ANGLE_TOL
  public :: restraint_t, node_flatness

  real(wp), parameter :: FLAT_ANGLE_TOL = 1.0e-6_wp
    !! Largest angle (rad) between the normals of two shells at a flat node,
    !! and between an edge's in-plane normal and the restrained translations.
  integer, parameter :: NTRANS = 3

  type :: restraint_t
    !! The fixed translations of the nodes of one substructure.
     logical, allocatable :: fixed(:, :)
       !! (3, nnode): translation d fixed (along axis d of the node's frame)
     integer, allocatable :: frame(:)
       !! (nnode): index into q of the node's *TRANSFORM axes, 0 for global axes
     real(wp), allocatable :: q(:, :, :)
       !! (3, 3, nframe): rows the local axes
  end type restraint_t

  type :: flatness_t
    !! Per node of one substructure: flat, and the first shell normal seen.
     logical, allocatable :: flat(:), seen(:)
     real(wp), allocatable :: first(:, :)
  end type flatness_t

contains

  subroutine mark_drilling_edges(model)
    !! Set model%subs(:)%elem_drill (drill_edge_masks) from the mesh and the
    !! rigid translational supports of the model data and of every step.
    type(model_t), intent(inout) :: model
    type(restraint_t), allocatable :: rest(:)
    type(flatness_t), allocatable :: fl(:)
    real(wp), allocatable :: q(:, :, :)
    integer :: isub, k, is
    allocate (fl(size(model%subs)), rest(size(model%subs)))
    do isub = 1, size(model%subs)
       call node_flatness(model%subs(isub), fl(isub)%flat, fl(isub)%seen, fl(isub)%first)
       allocate (rest(isub)%fixed(NTRANS, model%subs(isub)%nnode), source=.false.)
       allocate (rest(isub)%frame(model%subs(isub)%nnode), source=0)
    end do
    if (allocated(model%links)) call join_flatness(model, fl)
    allocate (q(3, 3, 0))
    if (allocated(model%frames)) then
       q = reshape([(model%frames(k)%q, k=1, size(model%frames))], [3, 3, size(model%frames)])
       do k = 1, size(model%frames)
          rest(model%frames(k)%sub)%frame(model%frames(k)%node) = k
       end do
    end if
    if (allocated(model%supports)) call add_fixed(model%supports, rest)
    if (allocated(model%steps)) then
       do is = 1, size(model%steps)
          if (allocated(model%steps(is)%supports)) call add_fixed(model%steps(is)%supports, rest)
       end do
    end if
    do isub = 1, size(model%subs)
       call move_alloc(q, rest(isub)%q)
       model%subs(isub)%elem_drill = drill_edge_masks(model%subs(isub), fl(isub)%flat, rest(isub))
       call move_alloc(rest(isub)%q, q)
       deallocate (rest(isub)%fixed, rest(isub)%frame)
    end do
  end subroutine mark_drilling_edges

  pure subroutine join_flatness(model, fl)
    !! Nodes joined by a contact element (any DOF) are one node for the
    !! flatness: not flat unless both are and their shells are coplanar (a
    !! fold split between two substructures is a fold). Repeated until nothing
    !! changes, so that a chain of joined nodes agrees.
    type(model_t), intent(in) :: model
    type(flatness_t), intent(inout) :: fl(:)
    integer :: k, ms, ss, a, b
    logical :: both, changed
    changed = .true.
    do while (changed)
       changed = .false.
       do k = 1, size(model%links)
          if (all(model%links(k)%state == LINK_NONE)) cycle
          ms = model%contacts(model%links(k)%contact)%master_sub
          ss = model%contacts(model%links(k)%contact)%slave_sub
          a = int(model%links(k)%master_node)
          b = int(model%links(k)%slave_node)
          if (ms < 1 .or. ss < 1 .or. a < 1 .or. b < 1) cycle
          if (.not. (fl(ms)%flat(a) .or. fl(ss)%flat(b))) cycle
          both = fl(ms)%flat(a) .and. fl(ss)%flat(b)
          if (both .and. fl(ms)%seen(a) .and. fl(ss)%seen(b)) &
               both = norm2(cross(fl(ms)%first(:, a), fl(ss)%first(:, b))) <= sin(FLAT_ANGLE_TOL)
          if (.not. both) then
             fl(ms)%flat(a) = .false.
             fl(ss)%flat(b) = .false.
             changed = .true.
          end if
       end do
    end do
  end subroutine join_flatness

  pure subroutine add_fixed(list, rest)
    !! Mark the rigid translational supports of list in rest(sub).
    type(support_t), intent(in) :: list(:)
    type(restraint_t), intent(inout) :: rest(:)
    integer :: k
    do k = 1, size(list)
       if (list(k)%state /= LINK_RIGID .or. list(k)%dof > NTRANS) cycle
       rest(list(k)%sub)%fixed(list(k)%dof, list(k)%node) = .true.
    end do
  end subroutine add_fixed

  pure subroutine node_flatness(sub, flat, seen, first)
    !! Per node of sub: flat (every attached S3/S4/S3R/S4R coplanar, no S8R),
    !! seen (some such shell attached) and first(:, node) the first normal.
    type(substructure_t), intent(in) :: sub
    logical, allocatable, intent(out) :: flat(:), seen(:)
    real(wp), allocatable, intent(out) :: first(:, :)
    integer(ip) :: e
    integer :: nn, k, a
    real(wp) :: nrm(3)
    logical :: ok
    allocate (flat(sub%nnode), seen(sub%nnode), source=.true.)
    seen = .false.
    allocate (first(3, sub%nnode), source=0.0_wp)
    do e = 1, sub%nelem
       if (is_shell8(sub%elem_type(e))) then
          flat(sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e)) = .false.
          cycle
       end if
       if (.not. is_flat_shell(sub%elem_type(e))) cycle
       nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
       call normal_of(sub%x(:, sub%elem_nodes(1:nn, e)), nrm, ok)
       if (.not. ok) cycle
       do k = 1, nn
          a = int(sub%elem_nodes(k, e))
          if (.not. seen(a)) then
             seen(a) = .true.
             first(:, a) = nrm
          else if (norm2(cross(first(:, a), nrm)) > sin(FLAT_ANGLE_TOL)) then
             flat(a) = .false.
          end if
       end do
    end do
  end subroutine node_flatness

  pure function drill_edge_masks(sub, flat, rest) result(masks)
    !! The edge mask (bit k - 1: edge k from corner k to k + 1 carries its
    !! bubble) of every element of sub from the node flags flat
    !! (node_flatness): an edge has its bubble when both its nodes are flat;
    !! 0 for elements that are not flat shells. rest (optional): the fixed
    !! translations; an edge whose two nodes fix its in-plane normal gets none.
    type(substructure_t), intent(in) :: sub
    logical, intent(in) :: flat(:)
    type(restraint_t), intent(in), optional :: rest
    integer, allocatable :: masks(:)
    integer(ip) :: e
    integer :: nn, k, a, b
    real(wp) :: nrm(3), m(3)
    logical :: ok
    allocate (masks(sub%nelem), source=0)
    do e = 1, sub%nelem
       if (.not. is_flat_shell(sub%elem_type(e))) cycle
       nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
       call normal_of(sub%x(:, sub%elem_nodes(1:nn, e)), nrm, ok)
       if (.not. ok) cycle
       do k = 1, nn
          a = int(sub%elem_nodes(k, e))
          b = int(sub%elem_nodes(modulo(k, nn) + 1, e))
          if (.not. (flat(a) .and. flat(b))) cycle
          if (present(rest)) then
             ! in-plane normal of the edge
             m = cross(sub%x(:, b) - sub%x(:, a), nrm)
             if (norm2(m) > 0.0_wp) m = m/norm2(m)
             if (holds(rest, a, m) .and. holds(rest, b, m)) cycle
          end if
          masks(e) = ibset(masks(e), k - 1)
       end do
    end do
  end function drill_edge_masks

  pure logical function holds(rest, node, m)
    !! True when the fixed translations of node include the direction m.
    type(restraint_t), intent(in) :: rest
    integer, intent(in) :: node
    real(wp), intent(in) :: m(3)
    real(wp) :: axes(3, 3), d(3, 2)
    integer :: i, c
    axes = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
    if (rest%frame(node) > 0) axes = rest%q(:, :, rest%frame(node))
    c = 0
    d = 0.0_wp
    do i = 1, NTRANS
       if (.not. rest%fixed(i, node)) cycle
       c = c + 1
       if (c <= 2) d(:, c) = axes(i, :)
    end do
    select case (c)
    case (NTRANS)
       holds = .true.
    case (2)
       holds = abs(dot_product(m, cross(d(:, 1), d(:, 2)))) <= sin(FLAT_ANGLE_TOL)
    case (1)
       holds = norm2(cross(m, d(:, 1))) <= sin(FLAT_ANGLE_TOL)
    case default
       holds = .false.
    end select
  end function holds

  pure integer function element_drill(sub, e) result(mask)
    !! The edge mask of element e of sub (drill_edge_masks), DRILL_ALL_EDGES when
    !! sub has none (a model built without superjoin_deck_validate).
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: e
    mask = DRILL_ALL_EDGES
    if (allocated(sub%elem_drill)) mask = sub%elem_drill(e)
  end function element_drill

  pure logical function is_flat_shell(etype)
    !! The three- and four-node flat shells.
    integer, intent(in) :: etype
    is_flat_shell = etype == ET_S3 .or. etype == ET_S4 .or. etype == ET_S3R .or. etype == ET_S4R
  end function is_flat_shell

  pure subroutine normal_of(x, nrm, ok)
    !! The unit normal of a flat shell (shell_frame's local z); ok false for a
    !! degenerate element (reported where its stiffness is formed).
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: nrm(3)
    logical, intent(out) :: ok
    type(error_t), allocatable :: error
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    call shell_frame(x, r, xl, h, error)
    ok = .not. allocated(error)
    nrm = r(3, :)
  end subroutine normal_of
end module superjoin_elements_drill_mask
