module superjoin_deck_cards_model
  !! Model cards of the deck reader: *HEADING, *SUBSTRUCTURE, *NODE, *ELEMENT
  !! (with the spring elements of *ELEMENT, TYPE=SPRING1|SPRING2|SPRINGA and their
  !! *SPRING cards), *NSET and *ELSET.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: source_loc_t, ELEMENT_TYPE_NAMES, ELEMENT_NODE_COUNT, &
       MAX_ELEMENT_NODES, CONDENSE_AUTO, CONDENSE_YES, CONDENSE_NO
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, is_name, looks_numeric, itoa, clip, &
       split_fields, drop_trailing_empty
  use superjoin_deck_state, only: deck_state_t, report_loc, report_oom, new_sub, find_sub, find_set, &
       new_set, add_chunk, push_pool, add_node, add_element, CH_IDS, CH_GEN, CH_RANGE, CH_REF, &
       spring_elem_b_t, spring_card_b_t, add_spring_elem, add_spring_card, SPRING_1, SPRING_2, &
       SPRING_A, ref_t, ASSEMBLY_SPRINGS, MAIN_NAME
  use superjoin_utils_strings, only: pick
  use superjoin_elements_catalog, only: unsupported_type_message
  use superjoin_elements_traits, only: element_type_of_name
  use superjoin_deck_coupling_cards, only: kw_dcoup_element
  use superjoin_deck_cards_common, only: get_reals
  use superjoin_deck_cards_common, only: outside_step, check_params, param_index, get_param, &
       get_name_param, target_sub, field_count, fld, get_real, get_id, loc_string, CARD_SKIP, &
       CARD_HEADING, CARD_NODE, CARD_ELEMENT, CARD_NSET, CARD_ELSET, CARD_SPRING_ELEMENT, &
       CARD_SPRING, NAME_LEN, parse_ref
  use superjoin_deck_cards_assembly, only: set_home
  implicit none (type, external)
  private

  public :: kw_heading, kw_substructure, kw_end_substructure, kw_node, kw_element, kw_set, &
       data_node, data_element, data_set, data_spring_element, kw_spring, data_spring

  integer, parameter :: NODE_FIELDS_MIN = 1, NODE_FIELDS_MAX = 7, NODE_COORD_FIELDS = 4
    !! id, x, y, z, then (Abaqus) the direction cosines of a shell normal, checked and ignored.
    !! Numbers of fields of data lines.
  integer, parameter :: GEN_FIELDS_MIN = 2, GEN_FIELDS_MAX = 3

contains

  subroutine kw_heading(st, kw, loc)
    !! *HEADING: its data lines are the title of the model.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    st%card = CARD_HEADING
  end subroutine kw_heading

  subroutine kw_substructure(st, kw, loc)
    !! *SUBSTRUCTURE, NAME=s: opens a substructure block.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name, value
    logical :: found
    integer :: k
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'CONDENSE'], [character(NAME_LEN) ::])
    if (st%cur_sub > 0) then
       call report_loc(st, loc, '*SUBSTRUCTURE inside *SUBSTRUCTURE '//st%subs(st%cur_sub)%name// &
            ' (missing *END SUBSTRUCTURE?)')
       st%cur_sub = 0
    end if
    call get_name_param(st, kw, loc, 'NAME', .true., name, found)
    if (.not. found) name = '?'
    k = find_sub(st, name)
    if (k > 0 .and. found) call report_loc(st, loc, 'duplicate substructure name '//name// &
         ' (first defined at '//loc_string(st, st%subs(k)%loc)//')')
    call new_sub(st, name, loc, k)
    st%cur_sub = k
    call get_param(st, kw, loc, 'CONDENSE', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('AUTO')
          st%subs(k)%condense = CONDENSE_AUTO
       case ('YES')
          st%subs(k)%condense = CONDENSE_YES
       case ('NO')
          st%subs(k)%condense = CONDENSE_NO
       case default
          call report_loc(st, loc, 'CONDENSE must be YES, NO or AUTO, not '//clip(value))
       end select
    end if
  end subroutine kw_substructure

  subroutine kw_end_substructure(st, kw, loc)
    !! *END SUBSTRUCTURE: closes the open *SUBSTRUCTURE block.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    if (st%cur_sub == 0) then
       call report_loc(st, loc, '*END SUBSTRUCTURE without *SUBSTRUCTURE')
    else
       st%cur_sub = 0
    end if
  end subroutine kw_end_substructure

  subroutine kw_node(st, kw, loc)
    !! *NODE[, NSET=n]: its data lines define nodes.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: nset
    logical :: found
    integer :: isub, iset
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NSET'], [character(NAME_LEN) ::])
    isub = target_sub(st, loc)
    st%card = CARD_NODE
    st%card_sub = isub
    call get_name_param(st, kw, loc, 'NSET', .false., nset, found)
    if (found) then
       associate (sub => st%subs(isub))
         iset = find_set(sub, nset, .false.)
         if (iset == 0) call new_set(sub, nset, .false., loc, iset)
         call add_chunk(sub, iset, .false., CH_RANGE, loc, st%card_chunk)
         sub%chunks(st%card_chunk)%start = sub%nnode + 1
       end associate
    end if
  end subroutine kw_node

  subroutine kw_element(st, kw, loc)
    !! *ELEMENT, TYPE=t[, ELSET=e]: its data lines define elements (spring types go to kw_spring_element).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: typ, elset
    logical :: found
    integer :: isub, iset
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'TYPE', 'ELSET'], [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'TYPE', .true., typ, found)
    st%card = CARD_SKIP
    if (.not. found) return
    typ = to_upper(typ)
    if (spring_type(typ) > 0) then
       call kw_spring_element(st, kw, loc, spring_type(typ))
       return
    end if
    if (typ == 'DCOUP3D') then
       call declare_elset(st, kw, loc)
       call kw_dcoup_element(st, kw, loc)
       return
    end if
    st%card_etype = element_type_of_name(typ)
    if (allocated(st%elem_pending)) deallocate (st%elem_pending)
    if (st%card_etype == 0) then
       call report_loc(st, loc, unsupported_type_message(clip(typ)))
       st%elements_refused = .true.
       call declare_elset(st, kw, loc)
       return
    end if
    isub = target_sub(st, loc)
    st%card = CARD_ELEMENT
    st%card_sub = isub
    st%nelem_cards = st%nelem_cards + 1
    st%card_item = st%nelem_cards
    call get_name_param(st, kw, loc, 'ELSET', .false., elset, found)
    if (found) then
       associate (sub => st%subs(isub))
         iset = find_set(sub, elset, .true.)
         if (iset == 0) call new_set(sub, elset, .true., loc, iset)
         call add_chunk(sub, iset, .true., CH_RANGE, loc, st%card_chunk)
         sub%chunks(st%card_chunk)%start = sub%nelem + 1
       end associate
    end if
  end subroutine kw_element

  subroutine declare_elset(st, kw, loc)
    !! The ELSET of a rejected *ELEMENT card still exists (empty), so that the
    !! cards naming it do not each report it as unknown: one error per mistake.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: elset
    logical :: found
    integer :: isub, iset
    call get_name_param(st, kw, loc, 'ELSET', .false., elset, found)
    if (.not. found) return
    isub = target_sub(st, loc)
    iset = find_set(st%subs(isub), elset, .true.)
    if (iset == 0) call new_set(st%subs(isub), elset, .true., loc, iset)
  end subroutine declare_elset

  subroutine kw_set(st, kw, loc, elem)
    !! *NSET or *ELSET (elem), NSET=|ELSET=n[, GENERATE]: its data lines list the members.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    logical, intent(in) :: elem
    character(:), allocatable :: name, pname, prefix
    logical :: found
    integer :: isub, iset
    if (.not. outside_step(st, kw, loc)) return
    if (elem) then
       pname = 'ELSET'
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'ELSET', 'INSTANCE'], &
            [character(NAME_LEN) :: 'GENERATE', 'UNSORTED', 'INTERNAL'])   ! INTERNAL: Abaqus/CAE's own sets
    else
       pname = 'NSET'
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'NSET', 'INSTANCE'], &
            [character(NAME_LEN) :: 'GENERATE', 'UNSORTED', 'INTERNAL'])
    end if
    call get_name_param(st, kw, loc, pname, .true., name, found)
    st%card = CARD_SKIP
    if (.not. found) return
    call set_home(st, kw, loc, isub, prefix)
    if (isub == 0) return
    name = prefix//name
    iset = find_set(st%subs(isub), name, elem)
    if (iset == 0) then
       call new_set(st%subs(isub), name, elem, loc, iset)
       if (param_index(kw, 'INSTANCE') > 0) call rank_assembly_set(st, isub, iset, elem)
    end if
    st%card = merge(CARD_ELSET, CARD_NSET, elem)
    st%card_sub = isub
    st%card_set = iset
    st%card_generate = param_index(kw, 'GENERATE') > 0
  end subroutine kw_set

  subroutine rank_assembly_set(st, isub, iset, elem)
    !! Set iset of entry isub, just begun by a card with INSTANCE=: its rank among
    !! the assembly-level sets, the order of the members of a set over several
    !! instances (superjoin_deck_build_common's plain_set_subs).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: isub, iset
    logical, intent(in) :: elem
    st%nassembly_sets = st%nassembly_sets + 1
    if (elem) then
       st%subs(isub)%elsets(iset)%order = st%nassembly_sets
    else
       st%subs(isub)%nsets(iset)%order = st%nassembly_sets
    end if
  end subroutine rank_assembly_set

  subroutine data_node(st, line, loc)
    !! A data line of *NODE: id[, x[, y[, z[, nx, ny, nz]]]].
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer(ip) :: id
    real(wp) :: x(3), normal
    integer :: i
    integer(i8) :: failed_bytes
    st%subs(st%card_sub)%node_lines = st%subs(st%card_sub)%node_lines + 1
    if (.not. field_count(st, loc, NODE_FIELDS_MIN, NODE_FIELDS_MAX, 'id[, x[, y[, z[, nx, ny, nz]]]]')) return
    if (.not. get_id(st, line, loc, 1, 'node id', id)) return
    x = 0.0_wp
    do i = 2, st%f%n
       if (st%f%last(i) < st%f%first(i)) cycle    ! an omitted coordinate is 0, as in Abaqus
       if (i <= NODE_COORD_FIELDS) then
          if (.not. get_real(st, line, loc, i, x(i - 1))) return
       else
          if (.not. get_real(st, line, loc, i, normal)) return
       end if
    end do
    associate (sub => st%subs(st%card_sub))
      call add_node(sub, id, x, loc, failed_bytes)
      if (failed_bytes > 0) then
         call too_many(st, loc, 'nodes', sub%nnode, failed_bytes)
         return
      end if
      if (st%card_chunk > 0) sub%chunks(st%card_chunk)%count = sub%chunks(st%card_chunk)%count + 1
    end associate
  end subroutine data_node

  subroutine data_element(st, line0, loc)
    !! A data line of *ELEMENT: id and the nodes of the card's element type. A
    !! line that ends with a comma before all the nodes are given continues on
    !! the next line (Abaqus writes at most 16 fields per line: C3D20). Fields
    !! after the nodes are ignored, as CalculiX does (beampsensfreq, dloadlinI:
    !! C3D8 and C3D8I lines with two more node numbers).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line0
    type(source_loc_t), intent(in) :: loc
    integer(ip) :: id, nid(MAX_ELEMENT_NODES)
    integer :: i, nn
    integer(i8) :: failed_bytes
    character(:), allocatable :: line
    nn = ELEMENT_NODE_COUNT(st%card_etype)
    line = line0
    if (allocated(st%elem_pending)) then
       line = st%elem_pending//line0
       deallocate (st%elem_pending)
       call split_fields(line, st%f)
       call drop_trailing_empty(st%f)
    end if
    if (st%f%n < nn + 1 .and. len_trim(line) > 0) then
       if (line(len_trim(line):len_trim(line)) == ',') then
          st%elem_pending = trim(line)
          return
       end if
    end if
    ! fields after the nodes are ignored, as CalculiX reads the line (its first id and nodes);
    ! the message is built only for a short line (not once per element)
    if (st%f%n < nn + 1) then
       if (.not. field_count(st, loc, nn + 1, nn + 1, 'id and '//itoa(nn)//' nodes for type '// &
            trim(ELEMENT_TYPE_NAMES(st%card_etype)))) return
    end if
    if (.not. get_id(st, line, loc, 1, 'element id', id)) return
    nid = 0
    do i = 1, nn
       if (.not. get_id(st, line, loc, i + 1, 'node id', nid(i))) return
    end do
    associate (sub => st%subs(st%card_sub))
      call add_element(sub, id, st%card_etype, nid, loc, st%card_item, failed_bytes)
      if (failed_bytes > 0) then
         call too_many(st, loc, 'elements', sub%nelem, failed_bytes)
         return
      end if
      if (st%card_chunk > 0) sub%chunks(st%card_chunk)%count = sub%chunks(st%card_chunk)%count + 1
    end associate
  end subroutine data_element

  subroutine too_many(st, loc, what, count, failed_bytes)
    !! A substructure cannot take one more node or element: more than
    !! huge(count) of them (a deck error), or out of memory (EXIT_IO).
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: what
    integer(ip), intent(in) :: count
    integer(i8), intent(in) :: failed_bytes
    if (count == huge(count)) then
       call report_loc(st, loc, 'more than '//itoa(huge(count))//' '//what//' in one substructure')
       st%aborted = .true.
    else
       call report_oom(st, loc, 'the '//what//' of substructure '//st%subs(st%card_sub)%name// &
            ' ('//itoa(2_i8*count)//')', failed_bytes)
    end if
  end subroutine too_many

  subroutine data_set(st, line, loc, elem)
    !! A data line of *NSET or *ELSET (elem): ids, set names, or first, last[, step] with GENERATE.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    logical, intent(in) :: elem
    character(:), allocatable :: what, tok
    integer(ip) :: id, gen(3)
    integer :: i, ck, k
    what = pick(elem, 'element id', 'node id')
    associate (sub => st%subs(st%card_sub))
      if (st%card_generate) then
         if (.not. field_count(st, loc, GEN_FIELDS_MIN, GEN_FIELDS_MAX, 'first, last[, increment]')) return
         gen(3) = 1
         do i = 1, st%f%n
            if (.not. get_id(st, line, loc, i, what, gen(i))) return
         end do
         if (gen(1) > gen(2)) then
            call report_loc(st, loc, 'GENERATE range '//itoa(gen(1))//' to '//itoa(gen(2))// &
                 ': first is after last')
            return
         end if
         call add_chunk(sub, st%card_set, elem, CH_GEN, loc, k)
         sub%chunks(k)%gen = gen
         return
      end if
      ck = 0
      do i = 1, st%f%n
         tok = fld(st, line, i)
         if (len(tok) == 0) cycle
         if (looks_numeric(tok)) then
            if (.not. get_id(st, line, loc, i, what, id)) cycle
            if (ck == 0) then
               call add_chunk(sub, st%card_set, elem, CH_IDS, loc, ck)
               sub%chunks(ck)%start = sub%npool + 1
            end if
            call push_pool(sub, id)
            sub%chunks(ck)%count = sub%chunks(ck)%count + 1
         else if (is_name(tok)) then
            call add_chunk(sub, st%card_set, elem, CH_REF, loc, k)
            sub%chunks(k)%ref = to_upper(tok)
            ck = 0
         else
            call report_loc(st, loc, 'invalid entry '''//clip(tok)//''' in '//st%card_name// &
                 ' (expected '//what//' or set name)')
         end if
      end do
    end associate
  end subroutine data_set

  pure integer function spring_type(name) result(kind)
    !! SPRING_* of an element type name, 0 for the others.
    character(*), intent(in) :: name
    select case (name)
    case ('SPRING1')
       kind = SPRING_1
    case ('SPRING2')
       kind = SPRING_2
    case ('SPRINGA')
       kind = SPRING_A
    case default
       kind = 0
    end select
  end function spring_type

  subroutine kw_spring_element(st, kw, loc, kind)
    !! *ELEMENT, TYPE=SPRING1 | SPRING2 | SPRINGA: spring elements, turned into
    !! supports and contact elements by their *SPRING card (superjoin_deck_springs).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: kind
    character(:), allocatable :: elset
    logical :: found
    call get_name_param(st, kw, loc, 'ELSET', .false., elset, found)
    if (.not. found) elset = ''
    st%spring_elset = elset
    st%card = CARD_SPRING_ELEMENT
    st%card_sub = spring_sub(st, loc)
    st%card_etype = kind
  end subroutine kw_spring_element

  integer function spring_sub(st, loc, elset) result(k)
    !! The substructure of spring elements and of their *SPRING card: the
    !! block's, MAIN outside the blocks; outside the blocks before any node
    !! made MAIN (Abaqus's assembly, springs between instances' nodes I.n)
    !! ASSEMBLY_SPRINGS, so that no empty MAIN is made. A *SPRING card
    !! (elset present) follows its elements.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in), optional :: elset
    integer :: e
    if (st%cur_sub == 0 .and. find_sub(st, MAIN_NAME) == 0) then
       k = ASSEMBLY_SPRINGS
       return
    end if
    if (st%cur_sub == 0 .and. present(elset)) then
       do e = 1, st%nspring_elem
          if (st%spring_elems(e)%sub == ASSEMBLY_SPRINGS .and. st%spring_elems(e)%elset == elset) then
             k = ASSEMBLY_SPRINGS
             return
          end if
       end do
    end if
    k = target_sub(st, loc)
  end function spring_sub

  subroutine data_spring_element(st, line, loc)
    !! id, node (SPRING1) or id, node 1, node 2 (SPRING2, SPRINGA).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(spring_elem_b_t) :: e
    type(ref_t) :: ref
    integer :: nn, i
    nn = merge(1, 2, st%card_etype == SPRING_1)
    if (.not. field_count(st, loc, nn + 1, nn + 1, 'id and '//itoa(nn)//' node'//pick(nn == 1, '', 's')// &
         ' for a spring')) return
    if (.not. get_id(st, line, loc, 1, 'element id', e%id)) return
    e%scope(1)%s = ''   ! both, also a SPRING1's second (read by the checks of every spring)
    e%scope(2)%s = ''
    do i = 1, nn   ! a node id, or I.n: node n of instance (or substructure) I, as Abaqus's assembly writes it
       if (.not. parse_ref(st, fld(st, line, i + 1), .false., st%card_sub, loc, ref)) then
          e%bad = .true.   ! kept, so that its *SPRING card finds it: one message
          cycle
       end if
       if (ref%is_set) then
          call report_loc(st, loc, 'a spring element joins nodes, not sets: '''//clip(fld(st, line, i + 1))// &
               ''' (a node id or I.n)')
          e%bad = .true.
          cycle
       end if
       e%nid(i) = ref%id
       if (allocated(ref%scope)) e%scope(i)%s = ref%scope
    end do
    e%kind = st%card_etype
    e%sub = st%card_sub
    e%elset = st%spring_elset
    e%loc = loc
    call add_spring_elem(st, e)
  end subroutine data_spring_element

  subroutine kw_spring(st, kw, loc)
    !! *SPRING, ELSET=e: the DOF line (SPRING1, SPRING2) and the stiffness line.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(spring_card_b_t) :: c
    logical :: found
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'ELSET', 'ORIENTATION'], [character(NAME_LEN) :: 'NONLINEAR'])
    if (param_index(kw, 'NONLINEAR') > 0) then
       call report_loc(st, loc, 'superjoin does linear statics; *SPRING, NONLINEAR (a nonlinear spring) '// &
            'is not supported')
       c%refused = .true.
    else if (param_index(kw, 'ORIENTATION') > 0) then
       call report_loc(st, loc, '*SPRING, ORIENTATION= is not supported: a SPRING1/SPRING2 acts on global '// &
            'DOFs (for an oriented joint use *CONTACT, ORIENTATION=)')
       c%refused = .true.
    end if
    call get_name_param(st, kw, loc, 'ELSET', .true., c%elset, found)
    if (.not. found) return
    c%sub = spring_sub(st, loc, c%elset)
    c%loc = loc
    call add_spring_card(st, c, st%card_item)
    if (.not. c%refused) st%card = CARD_SPRING
  end subroutine kw_spring

  subroutine data_spring(st, line, loc)
    !! A data line of *SPRING: the stiffness.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    associate (c => st%spring_cards(st%card_item))
      if (st%card_ndata > 2) then
         call report_loc(st, loc, 'too many data lines for *SPRING (DOF line, stiffness line)')
         st%card = CARD_SKIP
         return
      end if
      if (.not. field_count(st, loc, 1, 2, 'DOF(s) or stiffness')) return
      if (.not. get_reals(st, line, loc, c%v(1:st%f%n, st%card_ndata))) return
      c%ndata = st%card_ndata
      c%nfield(st%card_ndata) = st%f%n
      c%data_loc(st%card_ndata) = loc
    end associate
  end subroutine data_spring
end module superjoin_deck_cards_model
