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
  !! part, named I.SPRING_<elset> and I.SPRINGA_<elset>_<id>. Springs of the
  !! assembly (Abaqus/CAE's Springs/Dashpots) may name instances' nodes I.n:
  !! a SPRING1 is then a support of instance I, a SPRING2 or SPRINGA a
  !! contact element between the two nodes' substructures (one SPRING2 card
  !! per pair of substructures, SPRING_<elset>, then SPRING_<elset>_2, ...).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: source_loc_t, string_t, NDOF_NODE, LINK_FINITE
  use superjoin_deck_state, only: deck_state_t, spring_card_b_t, spring_elem_b_t, support_b_t, &
       contact_b_t, cline_b_t, report_loc, add_support, add_contact, add_cline, add_orientation, file_of, &
       SPRING_1, SPRING_2, SPRING_A, SUBK_PART, SUBK_INSTANCE, SUBK_NESTED, ASSEMBLY_SPRINGS, MAIN_NAME, &
       find_sub, instance_part
  use superjoin_utils_strings, only: itoa
  use superjoin_model_notes, only: append_string
  use superjoin_utils_sorting, only: sort_index, find_sorted
  implicit none (type, external)
  private

  public :: translate_springs

  type :: id_index_t
    !! The user ids of one substructure's nodes (or elements) in ascending order.
     integer, allocatable :: order(:)      !! local indices sorted by id
  end type id_index_t

  type :: spring_pairs_t
    !! The SPRING2 contact cards of one *SPRING card in one home: one per
    !! pair of substructures (master, slave) its elements join.
     type(string_t), allocatable :: master(:), slave(:)
     integer, allocatable :: contact(:)
  end type spring_pairs_t

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
    type(spring_pairs_t) :: pairs
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
    if (card%sub > 0) then
       if (st%subs(card%sub)%kind == SUBK_PART .and. scoped_in_part(st, card)) return
    end if
    call card_data(st, card, kind, dof1, dof2, k, ok)
    if (.not. ok) return
    if (.not. (k > 0.0_wp)) return          ! k = 0: no connection, as a contact g = 0
    call spring_homes(st, card, homes)
    do ih = 1, size(homes)
       if (allocated(pairs%contact)) deallocate (pairs%master, pairs%slave, pairs%contact)
       allocate (pairs%master(0), pairs%slave(0), pairs%contact(0))   ! this home's SPRING2 cards
       do e = first, st%nspring_elem
          associate (se => st%spring_elems(e))
            if (se%sub /= card%sub .or. se%elset /= card%elset .or. se%bad) cycle
            select case (kind)
            case (SPRING_1)
               call spring_support(st, se, homes(ih), dof1, k)
            case (SPRING_2)
               call pair_card(st, card, homes(ih), end_name(st, se, 1, homes(ih)), end_name(st, se, 2, homes(ih)), &
                    pairs, icontact)
               call spring_link(st, se, icontact, dof1, k)
            case (SPRING_A)
               call springa(st, se, card, k, nodes, homes(ih))
            end select
          end associate
       end do
    end do
  end subroutine translate_card

  subroutine pair_card(st, card, home, master, slave, pairs, ic)
    !! The SPRING2 contact card of the pair of substructures (master, slave)
    !! for the springs of card standing in home, made at its first element:
    !! SPRING_<elset>, then SPRING_<elset>_2, ... (I. before them in the copy
    !! of a part's springs in instance I).
    type(deck_state_t), intent(inout) :: st
    type(spring_card_b_t), intent(in) :: card
    integer, intent(in) :: home
    character(*), intent(in) :: master, slave
    type(spring_pairs_t), intent(inout) :: pairs
    integer, intent(out) :: ic
    integer :: j
    character(:), allocatable :: name
    do j = 1, size(pairs%contact)
       if (pairs%master(j)%s == master .and. pairs%slave(j)%s == slave) then
          ic = pairs%contact(j)
          return
       end if
    end do
    name = 'SPRING_'//card%elset
    if (home /= card%sub) name = st%subs(home)%name//'.'//name
    if (size(pairs%contact) > 0) name = name//'_'//itoa(size(pairs%contact) + 1)
    call new_contact(st, name, '', master, slave, card%loc, ic)
    call append_string(pairs%master, master)   ! not [list, string_t(s)]: gfortran leaks the constructor's component
    call append_string(pairs%slave, slave)
    pairs%contact = [pairs%contact, ic]
  end subroutine pair_card

  logical function scoped_in_part(st, card) result(bad)
    !! A spring inside a *PART naming an instance's node I.n (Abaqus allows
    !! I.n in the assembly only): reported once.
    type(deck_state_t), intent(inout) :: st
    type(spring_card_b_t), intent(in) :: card
    integer :: j
    bad = .false.
    do j = 1, st%nspring_elem
       associate (se => st%spring_elems(j))
         if (se%sub /= card%sub .or. se%elset /= card%elset) cycle
         if (len(se%scope(1)%s) == 0 .and. len(se%scope(2)%s) == 0) cycle
         call report_loc(st, se%loc, 'spring element '//itoa(se%id)//' inside *PART '//st%subs(card%sub)%name// &
              ' names a node I.n: a part''s elements join its own nodes (write the spring in the assembly)')
         bad = .true.
         return
       end associate
    end do
  end function scoped_in_part

  pure function end_name(st, se, i, home) result(name)
    !! The substructure of node i of spring element se standing in home: the
    !! instance or substructure of its I.n, else home's.
    type(deck_state_t), intent(in) :: st
    type(spring_elem_b_t), intent(in) :: se
    integer, intent(in) :: i, home
    character(:), allocatable :: name
    name = se%scope(i)%s
    if (len(name) > 0) return
    if (home == ASSEMBLY_SPRINGS) then
       name = MAIN_NAME   ! a plain node id outside the blocks (MAIN made after the springs)
    else
       name = st%subs(home)%name
    end if
  end function end_name

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
    if (card%sub == ASSEMBLY_SPRINGS) then
       homes = [card%sub]
       return
    end if
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
    s%ref%home = max(home, 0)   ! ASSEMBLY_SPRINGS: MAIN by name
    if (len(se%scope(1)%s) > 0) s%ref%scope = se%scope(1)%s   ! I.n: node n of instance I
    s%dofs(dof) = .true.
    s%state = LINK_FINITE
    s%g = k
    s%loc = se%loc
    call add_support(st, s)
  end subroutine spring_support

  subroutine new_contact(st, name, orientation, master, slave, loc, k)
    !! A contact card of spring elements between substructures master and slave (names).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name, orientation, master, slave
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    type(contact_b_t) :: c
    c%name = name
    c%master = master
    c%slave = slave
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
    !! se stands in: its nodes placed, the names prefixed by the instance's);
    !! a node I.n of an instance I of the assembly at its placed position.
    type(deck_state_t), intent(inout) :: st
    type(spring_elem_b_t), intent(in) :: se
    type(spring_card_b_t), intent(in) :: card
    real(wp), intent(in) :: k
    type(id_index_t), intent(inout) :: nodes(:)
    integer, intent(in) :: home
    real(wp) :: x(3, 2), e1(3), e2(3), e3(3), len_a
    integer :: i, io, ic, from, placed
    integer(ip) :: n
    character(:), allocatable :: name
    do i = 1, 2
       call coordinate_source(st, se, i, home, from, placed)
       if (from == 0) return
       if (.not. allocated(nodes(from)%order)) call sort_ids(st%subs(from)%node_id(1:st%subs(from)%nnode), &
            nodes(from)%order)
       n = find_sorted(st%subs(from)%node_id, nodes(from)%order, se%nid(i))
       if (n == 0) then
          call report_loc(st, se%loc, 'SPRINGA element '//itoa(se%id)//' refers to undefined node '// &
               node_text(se, i))
          return
       end if
       x(:, i) = st%subs(from)%x(:, n)
       if (placed > 0) x(:, i) = matmul(st%instances(st%subs(placed)%inst)%rot, x(:, i)) + &
            st%instances(st%subs(placed)%inst)%shift
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
    call new_contact(st, name, name, end_name(st, se, 1, home), end_name(st, se, 2, home), se%loc, ic)
    call spring_link(st, se, ic, 1, k)
  end subroutine springa

  subroutine coordinate_source(st, se, i, home, from, placed)
    !! Where node i of SPRINGA se has its coordinates: substructure from (its
    !! nodes as read), placed by instance placed (0: not placed). A node I.n
    !! names an instance of the assembly or a substructure; an instance path
    !! (an instance inside a part) is refused: its placement is known only
    !! once the parts are unfolded. from = 0: reported.
    type(deck_state_t), intent(inout) :: st
    type(spring_elem_b_t), intent(in) :: se
    integer, intent(in) :: i, home
    integer, intent(out) :: from, placed
    integer :: j
    from = se%sub
    placed = 0
    if (home /= se%sub) placed = home
    if (len(se%scope(i)%s) == 0) then
       if (from /= ASSEMBLY_SPRINGS) return
       from = find_sub(st, MAIN_NAME)   ! a plain node id outside the blocks
       if (from == 0) call report_loc(st, se%loc, 'SPRINGA element '//itoa(se%id)//': node '//node_text(se, i)// &
            ' is not defined (no nodes outside the blocks; an instance''s node is I.n)')
       return
    end if
    from = 0
    do j = 1, st%nsub
       if (st%subs(j)%name /= se%scope(i)%s) cycle
       if (st%subs(j)%kind == SUBK_INSTANCE) then
          placed = j
          from = instance_part(st, j)
       else if (st%subs(j)%kind /= SUBK_NESTED .and. st%subs(j)%kind /= SUBK_PART) then
          from = j
       end if
       exit
    end do
    if (from == 0) call report_loc(st, se%loc, 'SPRINGA element '//itoa(se%id)//': node '//node_text(se, i)// &
         ' is not a node of an instance of the assembly or of a substructure (an instance inside a part '// &
         'is not supported for SPRINGA)')
  end subroutine coordinate_source

  pure function node_text(se, i) result(t)
    !! Node i of spring se as written: n or I.n.
    type(spring_elem_b_t), intent(in) :: se
    integer, intent(in) :: i
    character(:), allocatable :: t
    t = itoa(se%nid(i))
    if (len(se%scope(i)%s) > 0) t = se%scope(i)%s//'.'//t
  end function node_text

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
