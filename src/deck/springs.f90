module superjoin_deck_springs
  !! Abaqus/CalculiX springs as superjoin's contact elements: at the end of
  !! the input every *SPRING card is turned into cards the reader already has.
  !! - SPRING1 (one node, DOF i, stiffness k): an elastic support, *SUPPORT
  !!   node, i, i, k.
  !! - SPRING2 (two nodes, DOF i at both): a contact element k on DOF i between
  !!   the two nodes (one *CONTACT card per *SPRING card, master and slave the
  !!   substructure of the elements); DOF i to DOF j /= i is refused.
  !! - SPRINGA (axial, along the line of its two nodes): a contact element k on
  !!   DOF 1 of a frame whose axis 1 runs from node 1 to node 2 (one *CONTACT
  !!   card and one *ORIENTATION per element), so that it resists only the
  !!   relative displacement along that line, as a linear SPRINGA does.
  !! The generated cards are named SPRING_<elset> (SPRING2) and
  !! SPRINGA_<elset>_<id> (SPRINGA); their lines point at the *ELEMENT data line.
  !! Springs inside a *PART become these cards once per instance I of the
  !! part, named I.SPRING_<elset> and I.SPRINGA_<elset>_<id>.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: source_loc_t, NDOF_NODE, LINK_FINITE
  use superjoin_deck_state, only: deck_state_t, spring_card_b_t, spring_elem_b_t, support_b_t, &
       contact_b_t, cline_b_t, report_loc, add_support, add_contact, add_cline, add_orientation, file_of, &
       SPRING_1, SPRING_2, SPRING_A, SUBK_PART, SUBK_INSTANCE, SUBK_NESTED
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_sorting, only: sort_index, find_sorted
  implicit none (type, external)
  private

  public :: translate_springs

  type :: id_index_t
    !! The user ids of one substructure's nodes (or elements) in ascending order.
     integer, allocatable :: order(:)      !! local indices sorted by id
  end type id_index_t

  character(len=7), parameter :: SPRING_NAMES(3) = ['SPRING1', 'SPRING2', 'SPRINGA']
  real(wp), parameter :: ZERO_LENGTH_TOL = 1.0e-14_wp
    !! A SPRINGA shorter than this fraction of its node coordinates has no direction.

contains

  subroutine translate_springs(st)
    !! Turn the *SPRING cards into supports and contact elements; report spring
    !! elements without a *SPRING card.
    type(deck_state_t), intent(inout) :: st
    integer :: c, e
    logical, allocatable :: used(:)
    type(id_index_t), allocatable :: nodes(:)
    if (st%nspring_elem == 0 .and. st%nspring_card == 0) return
    allocate (used(st%nspring_elem), nodes(st%nsub))
    used = .false.
    call check_ids(st)
    do c = 1, st%nspring_card
       call translate_card(st, st%spring_cards(c), used, nodes)
    end do
    do e = 1, st%nspring_elem
       if (.not. used(e)) call report_loc(st, st%spring_elems(e)%loc, trim(SPRING_NAMES(st%spring_elems(e)%kind))// &
            ' element '//itoa(st%spring_elems(e)%id)//' has no *SPRING card (its stiffness)')
    end do
  end subroutine translate_springs

  subroutine translate_card(st, card, used, nodes)
    type(deck_state_t), intent(inout) :: st
    type(spring_card_b_t), intent(in) :: card
    logical, intent(inout) :: used(:)
    type(id_index_t), intent(inout) :: nodes(:)
    integer :: e, kind, first, dof1, dof2, icontact, ih
    integer, allocatable :: homes(:)
    real(wp) :: k
    logical :: ok
    kind = 0
    first = 0
    do e = 1, st%nspring_elem
       associate (se => st%spring_elems(e))
         if (se%sub /= card%sub .or. se%elset /= card%elset) cycle
         if (used(e) .and. .not. card%refused) then
            call report_loc(st, card%loc, 'spring element '//itoa(se%id)//' already has a *SPRING card')
            return
         end if
         if (kind == 0) then
            kind = se%kind
            first = e
         else if (se%kind /= kind) then
            call report_loc(st, card%loc, '*SPRING, ELSET='//card%elset//' mixes '// &
                 trim(SPRING_NAMES(kind))//' and '//trim(SPRING_NAMES(se%kind))//' elements')
            return
         end if
       end associate
    end do
    if (kind == 0) then
       call report_loc(st, card%loc, '*SPRING, ELSET='//card%elset//': no SPRING1, SPRING2 or SPRINGA '// &
            'elements in that set (*ELEMENT, TYPE=SPRING..., ELSET='//card%elset//')')
       return
    end if
    do e = 1, st%nspring_elem    ! used, even when the card is refused (no second message)
       if (st%spring_elems(e)%sub == card%sub .and. st%spring_elems(e)%elset == card%elset) used(e) = .true.
    end do
    if (card%refused) return
    call card_data(st, card, kind, dof1, dof2, k, ok)
    if (.not. ok) return
    if (.not. (k > 0.0_wp)) return          ! k = 0: no connection, as a contact g = 0
    call spring_homes(st, card, homes)
    do ih = 1, size(homes)
       icontact = 0
       do e = first, st%nspring_elem
          associate (se => st%spring_elems(e))
            if (se%sub /= card%sub .or. se%elset /= card%elset) cycle
            select case (kind)
            case (SPRING_1)
               call spring_support(st, se, homes(ih), dof1, k)
            case (SPRING_2)
               if (icontact == 0) call new_contact(st, prefix(homes(ih))//'SPRING_'//card%elset, '', homes(ih), &
                    card%loc, icontact)
               call spring_link(st, se, icontact, dof1, k)
            case (SPRING_A)
               if (.not. allocated(nodes(se%sub)%order)) call sort_ids(st%subs(se%sub)%node_id(1:st%subs(se%sub)%nnode), &
                    nodes(se%sub)%order)
               call springa(st, se, card, k, nodes(se%sub), homes(ih))
            end select
          end associate
       end do
    end do
  contains
    function prefix(h) result(p)
      !! 'I.' for the copy in instance h of a part's spring, '' for the block's own.
      integer, intent(in) :: h
      character(:), allocatable :: p
      p = ''
      if (h /= card%sub) p = st%subs(h)%name//'.'
    end function prefix
  end subroutine translate_card

  subroutine spring_homes(st, card, homes)
    !! The substructures a *SPRING card's elements stand in: its block, or for
    !! springs inside a *PART each instance of the part (Abaqus copies a part's
    !! elements to every instance; the stiffness, SPRINGA's line and its frame
    !! are the instance's, placed). A part that an instance inside another part
    !! places is refused (its copies exist only when the parts are unfolded).
    type(deck_state_t), intent(inout) :: st
    type(spring_card_b_t), intent(in) :: card
    integer, allocatable, intent(out) :: homes(:)
    integer :: k, n
    logical, allocatable :: mine(:)
    if (st%subs(card%sub)%kind /= SUBK_PART) then
       homes = [card%sub]
       return
    end if
    allocate (mine(st%nsub), source=.false.)
    do k = 1, st%nsub
       if (st%subs(k)%inst <= 0) cycle
       if (st%instances(st%subs(k)%inst)%part /= st%subs(card%sub)%name) cycle
       mine(k) = st%subs(k)%kind == SUBK_INSTANCE
       if (st%subs(k)%kind /= SUBK_NESTED) cycle
       call report_loc(st, card%loc, 'spring elements inside *PART '//st%subs(card%sub)%name//', which an '// &
            '*INSTANCE inside another part places, are not supported (write them as *SUPPORT or *CONTACT cards '// &
            'in the assembly, with the instances'' nodes I.n)')
       allocate (homes(0))
       return
    end do
    allocate (homes(count(mine)))
    n = 0
    do k = 1, st%nsub
       if (.not. mine(k)) cycle
       n = n + 1
       homes(n) = k
    end do
  end subroutine spring_homes

  subroutine card_data(st, card, kind, dof1, dof2, k, ok)
    !! The DOF line (SPRING1: i; SPRING2: i, j) and the stiffness line; a
    !! SPRINGA has only the stiffness (its first, empty line is a blank line).
    type(deck_state_t), intent(inout) :: st
    type(spring_card_b_t), intent(in) :: card
    integer, intent(in) :: kind
    integer, intent(out) :: dof1, dof2
    real(wp), intent(out) :: k
    logical, intent(out) :: ok
    integer :: kline, nwant
    ok = .false.
    dof1 = 0
    dof2 = 0
    k = 0.0_wp
    if (kind == SPRING_A) then
       if (card%ndata /= 1) then
          call report_loc(st, card%loc, '*SPRING for SPRINGA elements takes one data line, the stiffness '// &
               '(after an empty line), not '//itoa(card%ndata))
          return
       end if
       kline = 1
    else
       if (card%ndata /= 2) then
          call report_loc(st, card%loc, '*SPRING for '//trim(SPRING_NAMES(kind))//' elements takes two data '// &
               'lines: the DOF'//trim(merge('  ', 's ', kind == SPRING_1))//', then the stiffness')
          return
       end if
       nwant = merge(1, 2, kind == SPRING_1)
       if (card%nfield(1) /= nwant) then
          call report_loc(st, card%data_loc(1), 'the first *SPRING line of '//trim(SPRING_NAMES(kind))// &
               ' elements holds '//trim(merge('the DOF i       ', 'the DOFs i, j   ', kind == SPRING_1)))
          return
       end if
       if (.not. dof_value(card%v(1, 1), dof1)) return
       if (kind == SPRING_2) then
          if (.not. dof_value(card%v(2, 1), dof2)) return
          if (dof1 /= dof2) then
             call report_loc(st, card%data_loc(1), 'SPRING2 from DOF '//itoa(dof1)//' to DOF '//itoa(dof2)// &
                  ' is not supported: superjoin''s contact elements join equal DOFs (i = j; for a spring '// &
                  'along a line use SPRINGA)')
             return
          end if
       end if
       kline = 2
    end if
    if (card%nfield(kline) /= 1) then
       call report_loc(st, card%data_loc(kline), 'the *SPRING stiffness line holds one value, the stiffness '// &
            '(tables of a NONLINEAR spring are not supported)')
       return
    end if
    k = card%v(1, kline)
    if (k < 0.0_wp) then
       call report_loc(st, card%data_loc(kline), 'spring stiffness must be >= 0')
       return
    end if
    ok = .true.
  contains
    logical function dof_value(x, dof) result(good)
      real(wp), intent(in) :: x
      integer, intent(out) :: dof
      good = x >= 1.0_wp .and. x <= real(NDOF_NODE, wp) .and. x == aint(x)
      dof = 0
      if (good) then
         dof = int(x)
      else
         call report_loc(st, card%data_loc(1), 'invalid *SPRING DOF (1 to 6)')
      end if
    end function dof_value
  end subroutine card_data

  subroutine spring_support(st, se, home, dof, k)
    !! SPRING1 element se in substructure home: an elastic support.
    type(deck_state_t), intent(inout) :: st
    type(spring_elem_b_t), intent(in) :: se
    integer, intent(in) :: home, dof
    real(wp), intent(in) :: k
    type(support_b_t) :: s
    s%ref%id = se%nid(1)
    s%ref%home = home
    s%dofs(dof) = .true.
    s%state = LINK_FINITE
    s%g = k
    s%loc = se%loc
    call add_support(st, s)
  end subroutine spring_support

  subroutine new_contact(st, name, orientation, sub, loc, k)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name, orientation
    integer, intent(in) :: sub
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    type(contact_b_t) :: c
    c%name = name
    c%master = st%subs(sub)%name
    c%slave = st%subs(sub)%name
    if (len(orientation) > 0) c%orientation = orientation
    c%loc = loc
    c%remote = .true.
    call add_contact(st, c, k)
  end subroutine new_contact

  subroutine spring_link(st, se, icontact, dof, k)
    type(deck_state_t), intent(inout) :: st
    type(spring_elem_b_t), intent(in) :: se
    integer, intent(in) :: icontact, dof
    real(wp), intent(in) :: k
    type(cline_b_t) :: c
    c%contact = icontact
    c%master%id = se%nid(1)
    c%slave%id = se%nid(2)
    c%first = dof
    c%last = dof
    c%state = LINK_FINITE
    c%g = k
    c%loc = se%loc
    call add_cline(st, c)
  end subroutine spring_link

  subroutine springa(st, se, card, k, nodes, home)
    !! An axial spring: a frame with axis 1 along node 1 -> node 2 and a
    !! contact k on its DOF 1, in substructure home (an instance of the part
    !! se stands in: its nodes placed, the names prefixed by the instance's).
    type(deck_state_t), intent(inout) :: st
    type(spring_elem_b_t), intent(in) :: se
    type(spring_card_b_t), intent(in) :: card
    real(wp), intent(in) :: k
    type(id_index_t), intent(in) :: nodes
    integer, intent(in) :: home
    real(wp) :: x(3, 2), e1(3), e2(3), e3(3), len_a
    integer :: i, io, ic
    integer(ip) :: n
    character(:), allocatable :: name
    do i = 1, 2
       n = find_sorted(st%subs(se%sub)%node_id, nodes%order, se%nid(i))
       if (n == 0) then
          call report_loc(st, se%loc, 'SPRINGA element '//itoa(se%id)//' refers to undefined node '//itoa(se%nid(i)))
          return
       end if
       x(:, i) = st%subs(se%sub)%x(:, n)
       if (home /= se%sub) x(:, i) = matmul(st%instances(st%subs(home)%inst)%rot, x(:, i)) + &
            st%instances(st%subs(home)%inst)%shift
    end do
    e1 = x(:, 2) - x(:, 1)
    len_a = norm2(e1)
    if (len_a <= ZERO_LENGTH_TOL*max(maxval(abs(x)), tiny(1.0_wp))) then
       call report_loc(st, se%loc, 'SPRINGA element '//itoa(se%id)//' has coincident nodes: its axis is undefined')
       return
    end if
    e1 = e1/len_a
    e2 = 0.0_wp
    e2(minloc(abs(e1), dim=1)) = 1.0_wp          ! the global axis farthest from e1
    e2 = e2 - dot_product(e2, e1)*e1
    e2 = e2/norm2(e2)
    e3 = [e1(2)*e2(3) - e1(3)*e2(2), e1(3)*e2(1) - e1(1)*e2(3), e1(1)*e2(2) - e1(2)*e2(1)]
    name = 'SPRINGA_'//card%elset//'_'//itoa(se%id)
    if (home /= se%sub) name = st%subs(home)%name//'.'//name
    call add_orientation(st, name, se%loc, io)
    st%orientations(io)%q(1, :) = e1
    st%orientations(io)%q(2, :) = e2
    st%orientations(io)%q(3, :) = e3
    call new_contact(st, name, name, home, se%loc, ic)
    call spring_link(st, se, ic, 1, k)
  end subroutine springa

  subroutine sort_ids(ids, order)
    !! Local indices of `ids` in ascending order of id.
    integer(ip), intent(in) :: ids(:)
    integer, allocatable, intent(out) :: order(:)
    integer :: i
    order = [(i, i = 1, size(ids))]
    call sort_index(ids, order)
  end subroutine sort_ids

  subroutine check_ids(st)
    !! A spring element id must be unique in its substructure, among the
    !! springs and the finite elements.
    type(deck_state_t), intent(inout) :: st
    integer :: isub, e, k
    integer, allocatable :: elems(:), springs(:), by_id(:)
    integer(ip), allocatable :: sid(:)
    do isub = 1, st%nsub
       if (.not. any(st%spring_elems(1:st%nspring_elem)%sub == isub)) cycle
       call springs_of(st, isub, springs, sid)
       call sort_ids(st%subs(isub)%elem_id(1:st%subs(isub)%nelem), elems)
       call sort_ids(sid, by_id)        ! stable: a repeated id reports its later definitions
       do k = 1, size(springs)
          associate (se => st%spring_elems(springs(by_id(k))))
            e = find_sorted(st%subs(isub)%elem_id, elems, se%id)
            if (e > 0) then
               call report_loc(st, se%loc, 'duplicate element id '//itoa(se%id)//' (also defined at '// &
                    loc_text(st, st%subs(isub)%elem_loc(e))//')')
            else if (k > 1) then
               if (sid(by_id(k - 1)) == se%id) call report_loc(st, se%loc, 'duplicate spring element id '// &
                    itoa(se%id)//' (also defined at '//loc_text(st, st%spring_elems(springs(by_id(k - 1)))%loc)//')')
            end if
          end associate
       end do
    end do
  end subroutine check_ids

  subroutine springs_of(st, isub, springs, sid)
    !! The spring elements of substructure isub (indices into st%spring_elems,
    !! in their order) and their ids; a loop, not pack over the component
    !! sections (which gfortran passes through temporaries).
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: isub
    integer, allocatable, intent(out) :: springs(:)
    integer(ip), allocatable, intent(out) :: sid(:)
    integer :: e, k
    k = 0
    do e = 1, st%nspring_elem
       if (st%spring_elems(e)%sub == isub) k = k + 1
    end do
    allocate (springs(k), sid(k))
    k = 0
    do e = 1, st%nspring_elem
       if (st%spring_elems(e)%sub /= isub) cycle
       k = k + 1
       springs(k) = e
       sid(k) = st%spring_elems(e)%id
    end do
  end subroutine springs_of

  function loc_text(st, loc) result(s)
    type(deck_state_t), intent(in) :: st
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: s
    s = file_of(st, loc%file)//':'//itoa(loc%line)
  end function loc_text
end module superjoin_deck_springs
