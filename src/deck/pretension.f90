module superjoin_deck_pretension
  !! `*PRE-TENSION SECTION, SURFACE=s, NODE=n` (CalculiX/Abaqus bolt
  !! pretension), card and build. The surface is an element face surface
  !! (faces S1.. of solids, edges S1.. of plane and axisymmetric elements)
  !! cutting the bolt; n is a node of no element. The optional data line is the
  !! normal; without it, the mean of the faces' outward normals (pointing away
  !! from the elements whose faces form the surface). As CalculiX does, the
  !! section's nodes are copied, the elements whose faces form the surface take
  !! the copies, and per node pair and translational component c the exact
  !! constraint u_copy,c - u_orig,c - n_c u_n,1 = 0 ties the pair: the gap
  !! across the cut is n times DOF 1 of the pretension node (tangential motions
  !! tied). A *CLOAD on that DOF is the bolt force (positive: tension), a
  !! *BOUNDARY on it the shortening of the bolt. `ELEMENT=e` (a beam bolt, as
  !! CalculiX reads it): the 2-node beam or truss e is removed and its nodes
  !! tied by n.(u_2 - u_1) + u_n,1 = 0 (n: node 1 to node 2 by default).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, equation_t, source_loc_t, substructure_t, find_node, loc_text, &
       ELEMENT_NODE_COUNT, DLOAD_P1, DLOAD_P4, DLOAD_P5, DLOAD_P6
  use superjoin_deck_lexer, only: keyword_line_t, parse_id, TOK_OK, clip, plural
  use superjoin_deck_state, only: deck_state_t, report_loc
  use superjoin_deck_records, only: pretension_b_t, SUBK_PLAIN
  use superjoin_deck_cards_common, only: outside_step, check_params, get_param, field_count, get_reals, &
       set_card, parse_ref, CARD_SKIP, NAME_LEN
  use superjoin_deck_build_common, only: resolve_sub, resolve_items, ref_text
  use superjoin_deck_element_removal, only: remove_element
  use superjoin_model_notes, only: note
  use superjoin_elements_traits, only: element_traits, element_traits_t, FAMILY_SOLID, FAMILY_PLANE, &
       FAMILY_BEAM, FAMILY_TRUSS
  use superjoin_elements_solid_faces, only: solid_face_nodes, solid_face_nodes_ccx
  use superjoin_utils_strings, only: to_upper, itoa, pick
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none (type, external)
  private

  real(wp), parameter :: NORMAL_DROP = 1.0e-10_wp
    !! a component of the bolt normal below this is left out of its equation (CalculiX does the same)

  public :: kw_pretension, data_pretension, build_pretensions

  integer, parameter, public :: CARD_PRETENSION = 205
    !! the card of *PRE-TENSION SECTION's data line (the normal)

  type :: cut_t
    !! A pretension section resolved on one substructure.
     integer :: sub = 0
     logical, allocatable :: elem(:)       !! elements whose faces form the section (they take the copies)
     logical, allocatable :: node(:)       !! nodes of the section
     integer(ip), allocatable :: order(:)  !! the section's nodes in the order their copies are numbered
     integer(ip) :: ncopy = 0              !! how many of order(:) are set
     real(wp) :: area(3) = 0.0_wp          !! sum of the faces' outward area vectors
     integer :: ncomp = 0                  !! translational DOFs per node (2 or 3)
     logical :: unresolved = .false.       !! a face left out: its element has a node in error
  end type cut_t

contains

  subroutine kw_pretension(st, kw, loc)
    !! *PRE-TENSION SECTION, SURFACE=, NODE= (model data).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(pretension_b_t) :: p
    character(:), allocatable :: value
    logical :: found
    integer :: stat
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'SURFACE', 'NODE', 'ELEMENT'], [character(NAME_LEN) ::])
    if (.not. section_param(st, kw, loc, p)) return
    call get_param(st, kw, loc, 'NODE', .true., value, found)
    if (.not. found) return
    call parse_id(value, p%node, stat)
    if (stat /= TOK_OK) then
       call report_loc(st, loc, '*PRE-TENSION SECTION: NODE= must be a node id, not '//clip(value))
       return
    end if
    p%loc = loc
    if (.not. allocated(st%pretensions)) allocate (st%pretensions(0))
    st%pretensions = [st%pretensions, p]
    call set_card(st, CARD_PRETENSION, '*PRE-TENSION SECTION', loc)
    st%card_item = size(st%pretensions)
  end subroutine kw_pretension

  logical function section_param(st, kw, loc, p) result(ok)
    !! SURFACE= or ELEMENT= (one of them): the section, or the element of a beam bolt.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(pretension_b_t), intent(inout) :: p
    character(:), allocatable :: surface, element
    logical :: has_surface, has_element
    integer :: home
    ok = .false.
    call get_param(st, kw, loc, 'SURFACE', .false., surface, has_surface)
    call get_param(st, kw, loc, 'ELEMENT', .false., element, has_element)
    if (has_surface .eqv. has_element) then
       call report_loc(st, loc, '*PRE-TENSION SECTION takes one of SURFACE= (a solid bolt) and ELEMENT= '// &
            '(a beam bolt)')
       return
    end if
    if (has_surface) then
       p%surface = to_upper(surface)
       ok = .true.
       return
    end if
    p%surface = ''
    p%by_element = .true.
    home = 0
    if (st%cur_sub > 0) then
       if (st%subs(st%cur_sub)%kind /= SUBK_PLAIN) then
          call report_loc(st, loc, '*PRE-TENSION SECTION, ELEMENT= inside *PART is not supported (write it '// &
               'in the assembly: ELEMENT=I.e, NODE=n)')
          return
       end if
       home = st%cur_sub
    end if
    ok = parse_ref(st, element, .true., home, loc, p%element)
  end function section_param

  subroutine data_pretension(st, line, loc)
    !! The data line of *PRE-TENSION SECTION: the normal nx, ny, nz (one line).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: n(3)
    associate (p => st%pretensions(st%card_item))
      if (p%has_normal) then
         call report_loc(st, loc, '*PRE-TENSION SECTION takes one data line (the normal nx, ny, nz)')
         return
      end if
      if (.not. field_count(st, loc, 1, 3, 'the normal nx, ny, nz')) return
      n = 0.0_wp
      if (.not. get_reals(st, line, loc, n(1:st%f%n))) return
      if (.not. (norm2(n) > 0.0_wp)) then
         call report_loc(st, loc, '*PRE-TENSION SECTION: the normal is zero')
         return
      end if
      p%has_normal = .true.
      p%normal = n/norm2(n)
    end associate
  end subroutine data_pretension

  subroutine build_pretensions(st, model)
    !! Every *PRE-TENSION SECTION: copies of the section's nodes in the
    !! elements of its surface and the equations that tie each pair.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: k
    if (.not. allocated(st%pretensions)) return
    do k = 1, size(st%pretensions)
       if (.not. st%pretensions(k)%by_element) call build_one(st, model, st%pretensions(k))
    end do
    ! beam bolts last: removing their elements renumbers the elements after them
    do k = 1, size(st%pretensions)
       if (st%pretensions(k)%by_element) call build_beam_bolt(st, model, st%pretensions(k))
    end do
  end subroutine build_pretensions

  subroutine build_beam_bolt(st, model, p)
    !! ELEMENT=e, as CalculiX does: the bolt element e (2 nodes, beam or
    !! truss) is removed and its nodes are tied by the exact equation
    !! n.(u_2 - u_1) + u_n,1 = 0, n the normal (default: node 1 to node 2 of e).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(pretension_b_t), intent(in) :: p
    type(element_traits_t) :: tr
    integer(ip), allocatable :: items(:)
    integer(ip) :: pnode, ends(2)
    real(wp) :: n(3)
    integer :: s, ndropped
    logical :: ok
    s = resolve_sub(st, model, p%element, p%loc, 'element')
    if (s == 0) return
    call resolve_items(st, model, s, p%element, .true., p%loc, items, ok)
    if (.not. ok) return
    if (size(items) /= 1) then
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: ELEMENT='//ref_text(p%element)//' holds '// &
            itoa(size(items))//' elements (it takes one: the bolt)')
       return
    end if
    tr = element_traits(model%subs(s)%elem_type(items(1)))
    if ((tr%family /= FAMILY_BEAM .and. tr%family /= FAMILY_TRUSS) .or. tr%nodes /= 2) then
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: element '//itoa(model%subs(s)%elem_id(items(1)))// &
            ' is a '//trim(tr%name)//' (ELEMENT= takes a 2-node beam or truss element: the bolt)')
       return
    end if
    pnode = pretension_node(st, model%subs(s), p)
    if (pnode == 0) return
    ends = model%subs(s)%elem_nodes(1:2, items(1))
    if (any(ends <= 0)) return   ! a node in error, reported
    n = model%subs(s)%x(:, ends(2)) - model%subs(s)%x(:, ends(1))
    if (p%has_normal) n = p%normal
    n(count(tr%dofs(1:3)) + 1:) = 0.0_wp   ! a planar bolt: the normal in its plane, then unit
    if (.not. norm2(n) > 0.0_wp) then
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: element '//itoa(model%subs(s)%elem_id(items(1)))// &
            pick(p%has_normal, ': the normal has no component in the model''s plane', &
            ' has coincident nodes: give the normal on the data line'))
       return
    end if
    n = n/norm2(n)
    call add_bolt_equation(model, s, ends, pnode, n(1:count(tr%dofs(1:3))), p%loc)
    call remove_element(model, s, items(1), ndropped)
    call note(model%notes, '*PRE-TENSION SECTION, ELEMENT='//ref_text(p%element)//' ('// &
         loc_text(model, p%loc)//'): the bolt element is removed and its two nodes tied by an '// &
         'equation, as CalculiX does (Abaqus keeps it: a prescribed shortening then also stretches it)'// &
         pick(ndropped > 0, '; its '//plural(ndropped, 'distributed load')//' (*DLOAD, temperature) '// &
         'went with it', ''))
  end subroutine build_beam_bolt

  subroutine add_bolt_equation(model, s, ends, pnode, n, loc)
    !! n.(u_2 - u_1) + u_pnode,1 = 0; the first term (node 2, the largest
    !! component of n) is the dependent one. Every translation of both ends is
    !! a term (0 where n has no component, as CalculiX drops those below NORMAL_DROP):
    !! the ends keep their translations once the element is gone, as in CalculiX.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: s
    integer(ip), intent(in) :: ends(2), pnode
    real(wp), intent(in) :: n(:)
    type(source_loc_t), intent(in) :: loc
    type(equation_t) :: eq
    integer :: c, k, order(size(n))
    order = [(c, c = 1, size(n))]
    order(1:maxloc(abs(n), 1)) = cshift(order(1:maxloc(abs(n), 1)), -1)   ! the largest component first
    allocate (eq%node(0), eq%dof(0), eq%coef(0))
    do k = 1, size(order)
       c = order(k)
       eq%node = [eq%node, ends(2), ends(1)]
       eq%dof = [eq%dof, c, c]
       eq%coef = [eq%coef, merge(n(c), 0.0_wp, abs(n(c)) > NORMAL_DROP)*[1.0_wp, -1.0_wp]]
    end do
    eq%node = [eq%node, pnode]
    eq%dof = [eq%dof, 1]
    eq%coef = [eq%coef, 1.0_wp]
    allocate (eq%sub(size(eq%node)), source=s)
    eq%loc = loc
    eq%coupling = .true.
    if (.not. allocated(model%equations)) allocate (model%equations(0))
    model%equations = [model%equations, eq]
  end subroutine add_bolt_equation

  integer(ip) function pretension_node(st, sub, p) result(pnode)
    !! The local index of NODE= in sub (0 and reported when it is undefined or
    !! a node of an element).
    type(deck_state_t), intent(inout) :: st
    type(substructure_t), intent(in) :: sub
    type(pretension_b_t), intent(in) :: p
    pnode = find_node(sub, p%node)
    if (pnode == 0) then
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: node '//itoa(p%node)//' (NODE=) is not defined')
    else if (in_element(sub, pnode)) then
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: node '//itoa(p%node)//' (NODE=) belongs to an element '// &
            '(the pretension node must be a node of no element)')
       pnode = 0
    end if
  end function pretension_node

  subroutine build_one(st, model, p)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(pretension_b_t), intent(in) :: p
    type(cut_t) :: cut
    integer(ip) :: pnode
    integer(ip), allocatable :: map(:)
    real(wp) :: n(3)
    logical :: ok
    type(halting_t) :: saved
    call halting_off(saved)   ! the faces' area vectors from the coordinates: checked below
    call section_faces(st, model, p, cut, ok)
    call halting_restore(saved)
    if (.not. ok) return
    if (.not. all(ieee_is_finite(cut%area))) then
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: the area vector of the faces of surface '//p%surface// &
            ' overflows the floating-point range (beyond 1.8E+308 or undefined): check the coordinates of their nodes')
       return
    end if
    pnode = pretension_node(st, model%subs(cut%sub), p)
    if (pnode == 0) return
    if (p%has_normal) then
       n = p%normal
    else if (norm2(cut%area) > 0.0_wp) then
       n = cut%area/norm2(cut%area)
    else
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: the faces of surface '//p%surface// &
            ' have no mean normal (give it on the data line)')
       return
    end if
    call split_nodes(model, cut, map)
    call add_equations(model, cut, map, pnode, n, p%loc)
  end subroutine build_one

  subroutine section_faces(st, model, p, cut, ok)
    !! The elements, nodes and mean outward normal of the section's surface.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(pretension_b_t), intent(in) :: p
    type(cut_t), intent(out) :: cut
    logical, intent(out) :: ok
    integer :: k, i, s
    integer(ip) :: e
    integer(ip), allocatable :: items(:)
    ok = .false.
    k = surface_index(st, p%surface)
    if (k == 0) then
       call report_loc(st, p%loc, '*PRE-TENSION SECTION: unknown surface '''//p%surface// &
            ''' (define it with *SURFACE, TYPE=ELEMENT)')
       return
    end if
    associate (sf => st%surfaces(k))
      if (sf%nodal) then
         call report_loc(st, p%loc, '*PRE-TENSION SECTION: surface '//p%surface//' is a node surface (it takes '// &
              'an element face surface, *SURFACE, TYPE=ELEMENT)')
         return
      end if
      do i = 1, sf%n
         s = resolve_sub(st, model, sf%refs(i), sf%loc, 'element')
         if (s == 0) return
         if (cut%sub == 0) then
            cut%sub = s
            allocate (cut%elem(model%subs(s)%nelem), source=.false.)
            allocate (cut%node(model%subs(s)%nnode), source=.false.)
            allocate (cut%order(model%subs(s)%nnode))
         else if (s /= cut%sub) then
            call report_loc(st, p%loc, '*PRE-TENSION SECTION: surface '//p%surface//' spans two substructures')
            return
         end if
         call resolve_items(st, model, s, sf%refs(i), .true., sf%loc, items, ok)
         if (.not. ok) return
         do e = 1, size(items, kind=ip)
            call add_face(model%subs(s), items(e), face_of(sf%kinds(i)), cut, ok)
            if (.not. ok) then
               call report_loc(st, p%loc, '*PRE-TENSION SECTION: surface '//p%surface//': element '// &
                    itoa(model%subs(s)%elem_id(items(e)))//' has no face S'//itoa(face_of(sf%kinds(i)))// &
                    ' (the section takes faces of solid, plane or axisymmetric elements)')
               return
            end if
         end do
      end do
    end associate
    ok = cut%sub > 0
    if (ok) ok = any(cut%elem) .and. .not. cut%unresolved
    if (.not. ok .and. .not. cut%unresolved) &
         call report_loc(st, p%loc, '*PRE-TENSION SECTION: surface '//p%surface//' has no faces')
  end subroutine section_faces

  integer function surface_index(st, name) result(k)
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    do k = 1, st%nsurface
       if (st%surfaces(k)%name == name) return
    end do
    k = 0
  end function surface_index

  pure integer function face_of(kind) result(face)
    !! Face number S1..S6 of a *SURFACE line's load form (0: none).
    integer, intent(in) :: kind
    face = 0
    if (kind >= DLOAD_P1 .and. kind <= DLOAD_P4) face = kind - DLOAD_P1 + 1
    if (kind == DLOAD_P5) face = 5
    if (kind == DLOAD_P6) face = 6
  end function face_of

  subroutine add_face(sub, e, face, cut, ok)
    !! Element e's face `face` into the section: its element, nodes and outward area vector.
    !! A node met for the first time takes the next copy number, its face's nodes in CalculiX's
    !! order (the surface's faces in turn), as ccx numbers them: the copies' ids do not depend
    !! on the order of the *NODE lines.
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: e
    integer, intent(in) :: face
    type(cut_t), intent(inout) :: cut
    logical, intent(out) :: ok
    type(element_traits_t) :: tr
    integer, allocatable :: local(:)
    integer :: nc, k, j
    real(wp) :: a(3), c(3), xe(3)
    tr = element_traits(sub%elem_type(e))
    call face_nodes(tr, sub%elem_type(e), face, local, nc)
    ok = nc > 0
    if (.not. ok) return
    ! A node of the element left unresolved (0) has had its error already: the face is left out.
    if (any(sub%elem_nodes(1:tr%nodes, e) <= 0)) then
       cut%unresolved = .true.
       return
    end if
    a = 0.0_wp
    associate (x => sub%x(:, sub%elem_nodes(local(1:nc), e)))
      if (nc == 2) then
         a = [x(2, 2) - x(2, 1), x(1, 1) - x(1, 2), 0.0_wp]
      else
         do k = 1, nc      ! Newell: twice the area vector of the polygon of the corners
            j = mod(k, nc) + 1
            a = a + [(x(2, k) - x(2, j))*(x(3, k) + x(3, j)), (x(3, k) - x(3, j))*(x(1, k) + x(1, j)), &
                     (x(1, k) - x(1, j))*(x(2, k) + x(2, j))]
         end do
      end if
      c = sum(x, 2)/nc
    end associate
    xe = sum(sub%x(:, sub%elem_nodes(1:tr%nodes, e)), 2)/tr%nodes
    if (dot_product(a, c - xe) < 0.0_wp) a = -a
    cut%area = cut%area + a
    cut%elem(e) = .true.
    if (tr%family == FAMILY_SOLID .and. tr%dofs(3)) call solid_face_nodes_ccx(sub%elem_type(e), face, local)
    do k = 1, size(local)
       j = sub%elem_nodes(local(k), e)
       if (cut%node(j)) cycle
       cut%node(j) = .true.
       cut%ncopy = cut%ncopy + 1
       cut%order(cut%ncopy) = j
    end do
    cut%ncomp = max(cut%ncomp, count(tr%dofs(1:3)))
  end subroutine add_face

  subroutine face_nodes(tr, etype, face, local, nc)
    !! Local nodes of a face (corners first): a solid's face, or the edge of a
    !! plane or axisymmetric element (nc = 2); nc = 0 when it has none.
    type(element_traits_t), intent(in) :: tr
    integer, intent(in) :: etype, face
    integer, allocatable, intent(out) :: local(:)
    integer, intent(out) :: nc
    integer :: m
    nc = 0
    if (tr%family == FAMILY_SOLID .and. tr%dofs(3)) then
       call solid_face_nodes(etype, face, local, nc)
    else if (tr%family == FAMILY_SOLID .or. tr%family == FAMILY_PLANE) then
       m = tr%corners
       if (m == 0) m = tr%nodes
       allocate (local(0))
       if (face < 1 .or. face > m) return
       local = [face, mod(face, m) + 1]
       if (tr%nodes > m) local = [local, m + face]
       nc = 2
    else
       allocate (local(0))
    end if
  end subroutine face_nodes

  logical function in_element(sub, node)
    !! Whether a node is a node of some element.
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: node
    integer(ip) :: e
    in_element = .false.
    do e = 1, sub%nelem
       in_element = any(sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e) == node)
       if (in_element) return
    end do
  end function in_element

  subroutine split_nodes(model, cut, map)
    !! Copy the section's nodes (new ids after the largest, in the order of
    !! cut%order) and give the copies to the section's elements; map(i) is the
    !! copy of node i (0: none). The copies take their originals' temperatures.
    type(model_t), intent(inout) :: model
    type(cut_t), intent(in) :: cut
    integer(ip), allocatable, intent(out) :: map(:)
    integer(ip) :: nold, nnew, i, j, e, maxid
    integer(ip), allocatable :: ids(:)
    real(wp), allocatable :: x(:, :)
    integer :: is, k
    associate (s => model%subs(cut%sub))
      nold = s%nnode
      nnew = cut%ncopy
      maxid = maxval(s%node_id(1:nold))
      allocate (map(nold), source=0_ip)
      allocate (ids(nold + nnew), x(3, nold + nnew))
      ids(1:nold) = s%node_id(1:nold)
      x(:, 1:nold) = s%x(:, 1:nold)
      do j = 1, nnew
         i = cut%order(j)
         map(i) = nold + j
         ids(nold + j) = maxid + j
         x(:, nold + j) = s%x(:, i)
      end do
      call move_alloc(ids, s%node_id)
      call move_alloc(x, s%x)
      s%node_order = [s%node_order(1:nold), (i, i = nold + 1, nold + nnew)]
      s%nnode = nold + nnew
      do e = 1, s%nelem
         if (.not. cut%elem(e)) cycle
         do k = 1, ELEMENT_NODE_COUNT(s%elem_type(e))
            if (map(s%elem_nodes(k, e)) > 0) s%elem_nodes(k, e) = map(s%elem_nodes(k, e))
         end do
      end do
    end associate
    if (.not. allocated(model%steps)) return
    do is = 1, size(model%steps)
       if (.not. allocated(model%steps(is)%temperature)) cycle
       associate (t => model%steps(is)%temperature(cut%sub))
         if (allocated(t%v)) t%v = [t%v(1:nold), t%v(cut%order(1:nnew))]
       end associate
    end do
  end subroutine split_nodes

  subroutine add_equations(model, cut, map, pnode, n, loc)
    !! Per node pair and component c: u_copy,c - u_orig,c - n_c u_pnode,1 = 0.
    type(model_t), intent(inout) :: model
    type(cut_t), intent(in) :: cut
    integer(ip), intent(in) :: map(:), pnode
    real(wp), intent(in) :: n(3)
    type(source_loc_t), intent(in) :: loc
    type(equation_t), allocatable :: list(:)
    type(equation_t) :: eq
    integer(ip) :: i, j
    integer :: c, m
    allocate (list(cut%ncopy*cut%ncomp))
    m = 0
    do j = 1, cut%ncopy   ! in the copies' order
       i = cut%order(j)
       do c = 1, cut%ncomp
          eq = equation_t()
          eq%node = [map(i), i]
          eq%dof = [c, c]
          eq%coef = [1.0_wp, -1.0_wp]
          if (n(c) /= 0.0_wp) then
             eq%node = [eq%node, pnode]
             eq%dof = [eq%dof, 1]
             eq%coef = [eq%coef, -n(c)]
          end if
          allocate (eq%sub(size(eq%node)), source=cut%sub)
          eq%loc = loc
          eq%coupling = .true.
          m = m + 1
          list(m) = eq
       end do
    end do
    if (.not. allocated(model%equations)) allocate (model%equations(0))
    model%equations = [model%equations, list(1:m)]
  end subroutine add_equations
end module superjoin_deck_pretension
