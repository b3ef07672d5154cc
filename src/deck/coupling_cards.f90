module superjoin_deck_coupling_cards
  !! Parser side of the coupling cards (CalculiX/Abaqus):
  !! - `*COUPLING, REF NODE=n, SURFACE=s[, CONSTRAINT NAME=c]` followed by
  !!   `*KINEMATIC` or `*DISTRIBUTING`, whose data lines `first DOF[, last DOF]`
  !!   choose the DOFs coupled (without a data line: 1-3 for *KINEMATIC, 1-6
  !!   for *DISTRIBUTING);
  !! - `*RIGID BODY, NSET=s | ELSET=s, REF NODE=n[, ROT NODE=m]`;
  !! - `*MPC` with data lines `BEAM, a, b`, `PLANE, nodes`, `STRAIGHT, nodes`
  !!   or `MEANROT, nodes` (CalculiX: nonlinear constraints; superjoin's statics
  !!   keep their linear forms); `DIST` (an inequality) is refused;
  !! - `*ELEMENT, TYPE=DCOUP3D, ELSET=e` (data lines `element, reference node`)
  !!   and `*DISTRIBUTING COUPLING, ELSET=e` (data lines `node or node set,
  !!   weight`): a distributing coupling element (Abaqus's and CalculiX's
  !!   readings differ: superjoin_deck_coupling_build).
  !! superjoin_deck_coupling_build turns the records into constraint equations.
  use superjoin_model_types, only: source_loc_t, NDOF_NODE
  use superjoin_deck_lexer, only: keyword_line_t, clip
  use superjoin_utils_strings, only: to_upper
  use superjoin_deck_state, only: deck_state_t, report_loc, ref_t, SUBK_PART
  use superjoin_deck_coupling_records, only: coupling_b_t, COUPLE_KINEMATIC, COUPLE_DISTRIBUTING, &
       COUPLE_RIGID_BODY, COUPLE_MPC_BEAM, COUPLE_MPC_PLANE, COUPLE_MPC_STRAIGHT, COUPLE_DCOUP, COUPLE_MPC_MEANROT
  use superjoin_deck_cards_common, only: outside_step, check_params, get_param, field_count, fld, &
       get_dof, parse_ref, parse_set_ref, get_real, CARD_SKIP, CARD_COUPLING_DOFS, CARD_MPC, CARD_DCOUP_ELEMENT, &
       CARD_DCOUP_NODES, NAME_LEN
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  public :: kw_coupling_card, data_coupling_dofs, data_mpc, kw_dcoup_element, data_dcoup_element, data_dcoup_nodes

contains

  subroutine kw_coupling_card(st, kw, loc, prev_coupling)
    !! The keyword lines of the coupling cards; prev_coupling is the *COUPLING
    !! card the previous keyword line opened (0: none), for *KINEMATIC and *DISTRIBUTING.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: prev_coupling
    if (st%cur_sub > 0 .and. kw%keyword == 'DISTRIBUTING COUPLING') then
       if (st%subs(st%cur_sub)%kind == SUBK_PART) then
          call report_loc(st, loc, '*'//kw%keyword//' is not allowed inside *PART '//st%subs(st%cur_sub)%name// &
               ' (it would not be copied to each instance: write it in the assembly, with the instances'' '// &
               'nodes I.n and a *SURFACE of their elements I.e)')
          st%card = CARD_SKIP
          return
       end if
    end if
    select case (kw%keyword)
    case ('COUPLING')
       call kw_coupling(st, kw, loc)
    case ('KINEMATIC')
       call kw_coupling_kind(st, kw, loc, COUPLE_KINEMATIC, prev_coupling)
    case ('DISTRIBUTING')
       call kw_coupling_kind(st, kw, loc, COUPLE_DISTRIBUTING, prev_coupling)
    case ('RIGID BODY')
       call kw_rigid_body(st, kw, loc)
    case ('DISTRIBUTING COUPLING')
       call kw_dcoup_nodes(st, kw, loc)
    case default
       call kw_mpc(st, kw, loc)
    end select
  end subroutine kw_coupling_card

  subroutine kw_coupling(st, kw, loc)
    !! *COUPLING, REF NODE=n, SURFACE=s[, CONSTRAINT NAME=c]: a reference node and an element surface.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(coupling_b_t) :: c
    character(:), allocatable :: v
    logical :: found
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'REF NODE', 'SURFACE', 'CONSTRAINT NAME', &
         'ORIENTATION'], [character(NAME_LEN) ::])
    c%loc = loc
    call get_param(st, kw, loc, 'ORIENTATION', .false., v, found)
    if (found) then
       call report_loc(st, loc, '*COUPLING, ORIENTATION= is not supported (the coupled DOFs are global)')
       c%ok = .false.
    end if
    call get_param(st, kw, loc, 'CONSTRAINT NAME', .false., v, found)
    c%name = to_upper(v)
    call get_param(st, kw, loc, 'SURFACE', .true., v, found)
    c%surface = to_upper(v)
    if (.not. found) c%ok = .false.
    call get_param(st, kw, loc, 'REF NODE', .true., v, found)
    if (found) then
       if (.not. parse_ref(st, v, .false., st%cur_sub, loc, c%ref_node)) c%ok = .false.
    else
       c%ok = .false.
    end if
    call push_coupling(st, c)
    st%open_coupling = size(st%couplings)
  end subroutine kw_coupling

  subroutine kw_coupling_kind(st, kw, loc, kind, n)
    !! *KINEMATIC or *DISTRIBUTING: the kind of the *COUPLING card n just above (0: none).
    !! *DISTRIBUTING, WEIGHTING METHOD=UNIFORM (Abaqus/CAE writes it): the
    !! nodes' areas are their weights, as superjoin and CalculiX weigh them;
    !! Abaqus's weights that fall off with the distance are refused.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: kind, n
    character(:), allocatable :: method
    logical :: found
    st%card = CARD_SKIP
    if (kind == COUPLE_DISTRIBUTING) then
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'WEIGHTING METHOD'], [character(NAME_LEN) ::])
       call get_param(st, kw, loc, 'WEIGHTING METHOD', .false., method, found)
       if (found) then
          if (to_upper(method) /= 'UNIFORM') call report_loc(st, loc, '*DISTRIBUTING, WEIGHTING METHOD='// &
               clip(method)//' is not supported: superjoin weighs each node by its area on the surface '// &
               '(WEIGHTING METHOD=UNIFORM)')
       end if
    else
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    end if
    if (n == 0) then
       call report_loc(st, loc, '*'//kw%keyword//' must follow a *COUPLING card')
       return
    end if
    st%couplings(n)%kind = kind
    st%card = CARD_COUPLING_DOFS
    st%card_item = n
  end subroutine kw_coupling_kind

  subroutine data_coupling_dofs(st, line, loc)
    !! `first DOF[, last DOF]` of *KINEMATIC / *DISTRIBUTING.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer :: first, last
    if (.not. field_count(st, loc, 1, 2, 'first DOF[, last DOF]')) return
    if (.not. get_dof(st, line, loc, 1, first)) return
    last = first
    if (st%f%n == 2) then
       if (.not. get_dof(st, line, loc, 2, last)) return
    end if
    if (last < first) then
       call report_loc(st, loc, 'last DOF '//clip(fld(st, line, 2))//' is before the first DOF')
       return
    end if
    associate (c => st%couplings(st%card_item))
      c%dofs(first:last) = .true.
      c%dofs_given = .true.
    end associate
  end subroutine data_coupling_dofs

  subroutine kw_rigid_body(st, kw, loc)
    !! *RIGID BODY, NSET=s | ELSET=s, REF NODE=n[, ROT NODE=m].
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(coupling_b_t) :: c
    character(:), allocatable :: v, e
    logical :: found, efound
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NSET', 'ELSET', 'REF NODE', 'ROT NODE'], &
         [character(NAME_LEN) ::])
    c%kind = COUPLE_RIGID_BODY
    c%loc = loc
    c%dofs = .true.
    call get_param(st, kw, loc, 'NSET', .false., v, found)
    call get_param(st, kw, loc, 'ELSET', .false., e, efound)
    if (found .eqv. efound) then
       call report_loc(st, loc, '*RIGID BODY needs one of NSET= and ELSET= (the nodes of the body)')
       c%ok = .false.
    else if (found) then
       if (.not. parse_set_ref(st, v, .false., st%cur_sub, loc, c%nodes)) c%ok = .false.
    else
       c%by_elements = .true.
       if (.not. parse_set_ref(st, e, .true., st%cur_sub, loc, c%nodes)) c%ok = .false.
    end if
    call get_param(st, kw, loc, 'REF NODE', .false., v, found)
    if (.not. found) then
       call report_loc(st, loc, '*RIGID BODY needs REF NODE= (superjoin does not generate a reference node: '// &
            'define one with *NODE)')
       c%ok = .false.
    else if (.not. parse_ref(st, v, .false., st%cur_sub, loc, c%ref_node)) then
       c%ok = .false.
    end if
    call get_param(st, kw, loc, 'ROT NODE', .false., v, found)
    if (found) then
       c%has_rot = .true.
       if (.not. parse_ref(st, v, .false., st%cur_sub, loc, c%rot_node)) c%ok = .false.
    end if
    call push_coupling(st, c)
  end subroutine kw_rigid_body

  subroutine kw_mpc(st, kw, loc)
    !! *MPC: data lines `type, nodes...` (BEAM, PLANE, STRAIGHT, MEANROT).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    st%card = CARD_MPC
  end subroutine kw_mpc

  subroutine data_mpc(st, line, loc)
    !! `BEAM, a, b`, `PLANE, nodes...`, `STRAIGHT, nodes...` or `MEANROT,
    !! nodes...` (nodes or node sets); a line that does not start with a name
    !! continues the last MPC's node list (CalculiX).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(coupling_b_t) :: c
    type(ref_t) :: ref
    character(:), allocatable :: name
    integer :: first, i
    name = to_upper(fld(st, line, 1))
    first = 1
    if (len(name) == 0) then
       call report_loc(st, loc, '*MPC: empty first field (the MPC''s name or a node)')
       st%card = CARD_SKIP
       return
    end if
    if (verify(name(1:1), '0123456789') /= 0) then
       select case (name)
       case ('BEAM')
          c%kind = COUPLE_MPC_BEAM
       case ('PLANE')
          c%kind = COUPLE_MPC_PLANE
       case ('STRAIGHT')
          c%kind = COUPLE_MPC_STRAIGHT
       case ('MEANROT')
          c%kind = COUPLE_MPC_MEANROT
       case ('DIST')
          call report_loc(st, loc, '*MPC DIST is an inequality (the distance of two nodes may not exceed a bound, '// &
               'free below it): a one-sided condition that a linear solve cannot hold; model it with a contact '// &
               '(*CONTACT with a gap) instead')
          st%card = CARD_SKIP
          return
       case default
          call report_loc(st, loc, '*MPC '''//clip(fld(st, line, 1))//''' is not supported (BEAM, PLANE, '// &
               'STRAIGHT, MEANROT, linearised)')
          st%card = CARD_SKIP
          return
       end select
       c%loc = loc
       allocate (c%list(0))
       call push_coupling(st, c)
       st%card_item = size(st%couplings)
       first = 2
    else if (st%card_item == 0) then
       call report_loc(st, loc, '*MPC: the first data line starts with the MPC''s name (BEAM, PLANE, STRAIGHT, '// &
            'MEANROT)')
       st%card = CARD_SKIP
       return
    end if
    associate (m => st%couplings(st%card_item))
      do i = first, st%f%n
         if (len(fld(st, line, i)) == 0) cycle
         if (.not. parse_ref(st, fld(st, line, i), .false., st%cur_sub, loc, ref)) then
            m%ok = .false.
            cycle
         end if
         m%list = [m%list, ref]
      end do
    end associate
  end subroutine data_mpc

  subroutine kw_dcoup_element(st, kw, loc)
    !! *ELEMENT, TYPE=DCOUP3D, ELSET=e: distributing coupling elements (the
    !! ELSET names them for *DISTRIBUTING COUPLING; the caller declared it).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: v
    logical :: found
    st%card = CARD_SKIP
    call get_param(st, kw, loc, 'ELSET', .false., v, found)
    if (.not. found) then
       call report_loc(st, loc, '*ELEMENT, TYPE=DCOUP3D needs ELSET= (the set its *DISTRIBUTING COUPLING names)')
       return
    end if
    st%card = CARD_DCOUP_ELEMENT
    st%dcoup_set = to_upper(v)
  end subroutine kw_dcoup_element

  subroutine data_dcoup_element(st, line, loc)
    !! `element, reference node` of a DCOUP3D card: one coupling record each.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(coupling_b_t) :: c
    if (.not. field_count(st, loc, 2, 2, 'element, reference node')) return
    c%kind = COUPLE_DCOUP
    c%name = st%dcoup_set
    c%loc = loc
    allocate (c%list(0), c%weights(0))
    if (.not. parse_ref(st, fld(st, line, 2), .false., st%cur_sub, loc, c%ref_node)) c%ok = .false.
    call push_coupling(st, c)
  end subroutine data_dcoup_element

  subroutine kw_dcoup_nodes(st, kw, loc)
    !! *DISTRIBUTING COUPLING, ELSET=e: the coupled nodes of the DCOUP3D elements of e.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: v
    logical :: found
    integer :: k
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'ELSET'], [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'ELSET', .true., v, found)
    if (.not. found) return
    v = to_upper(v)
    st%card_item = 0
    if (allocated(st%couplings)) then
       do k = 1, size(st%couplings)
          if (st%couplings(k)%kind /= COUPLE_DCOUP) cycle
          if (st%couplings(k)%name /= v) cycle
          if (size(st%couplings(k)%list) > 0) then
             call report_loc(st, loc, 'element set '//v//' has a *DISTRIBUTING COUPLING already')
             return
          end if
          st%card_item = k
          st%couplings(k)%weights_loc = loc
       end do
    end if
    if (st%card_item == 0) then
       call report_loc(st, loc, '*DISTRIBUTING COUPLING: no *ELEMENT, TYPE=DCOUP3D, ELSET='//v// &
            ' above it (the element set is named on the DCOUP3D element card)')
       return
    end if
    st%card = CARD_DCOUP_NODES
    st%dcoup_set = v
  end subroutine kw_dcoup_nodes

  subroutine data_dcoup_nodes(st, line, loc)
    !! `node or node set, weight` of *DISTRIBUTING COUPLING, for every DCOUP3D element of the set.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(ref_t) :: ref
    real(wp) :: w
    integer :: k
    if (.not. field_count(st, loc, 2, 2, 'node or node set, weight')) return
    if (.not. parse_ref(st, fld(st, line, 1), .false., st%cur_sub, loc, ref)) return
    if (.not. get_real(st, line, loc, 2, w)) return
    if (.not. (w > 0.0_wp)) then
       call report_loc(st, loc, 'a distributing coupling weight must be positive, not '//clip(fld(st, line, 2)))
       return
    end if
    do k = 1, size(st%couplings)
       if (st%couplings(k)%kind /= COUPLE_DCOUP) cycle
       if (st%couplings(k)%name /= st%dcoup_set) cycle
       st%couplings(k)%list = [st%couplings(k)%list, ref]
       st%couplings(k)%weights = [st%couplings(k)%weights, w]
    end do
  end subroutine data_dcoup_nodes

  subroutine push_coupling(st, c)
    !! Append a coupling record.
    type(deck_state_t), intent(inout) :: st
    type(coupling_b_t), intent(in) :: c
    integer :: n
    if (.not. allocated(st%couplings)) allocate (st%couplings(0))
    st%couplings = [st%couplings, c]
    n = size(st%couplings)
    if (c%kind /= COUPLE_DCOUP) st%couplings(n)%home = st%cur_sub   ! a part's: copied per instance
  end subroutine push_coupling

end module superjoin_deck_coupling_cards
