module superjoin_deck_cards_common
  !! What the card routines of the deck reader share: the card numbers (what
  !! the current card does with its data lines), the checks of keyword
  !! parameters and the readers of data-line fields (reals, ids, DOFs,
  !! stiffnesses, node and element references), with their messages.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: source_loc_t, NDOF_NODE, LINK_NONE, LINK_FINITE, LINK_RIGID
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, parse_real, parse_id, is_name, is_path, &
       is_digits, looks_numeric, itoa, clip, plural, TOK_OK, TOK_RANGE, TOK_NONFINITE
  use superjoin_deck_state, only: deck_state_t, ref_t, report_loc, new_sub, find_sub, MAIN_NAME
  use superjoin_deck_ccx_cards, only: refused_card_reason
  use superjoin_utils_strings, only: pick
  implicit none (type, external)
  private

  public :: axis_rotation
  public :: set_card, outside_step, check_params, param_index, get_param, get_name_param, &
       target_sub, field_count, fld, get_real, get_reals, real_message, get_id, get_dof, get_dof_range, &
       get_stiffness, parse_ref, parse_set_ref, loc_string, refused_card, CARD_NONE, CARD_SKIP, CARD_NODATA, &
       CARD_HEADING, CARD_NODE, CARD_ELEMENT, CARD_NSET, CARD_ELSET, CARD_SECTION, CARD_ELASTIC, &
       CARD_ORIENTATION, CARD_CONTACT, CARD_SUPPORT, CARD_BOUNDARY, CARD_CLOAD, CARD_DLOAD, &
       CARD_DENSITY, CARD_TSHEAR, CARD_INSTANCE, CARD_CHANGE_CONTACT, CARD_INTERFACE, CARD_STATIC, &
       CARD_REQUEST, CARD_SPRING_ELEMENT, CARD_SPRING, CARD_COMBINATION, CARD_EXPANSION, &
       CARD_TEMPERATURE, CARD_EQUATION, CARD_TRANSFORM, CARD_NODAL_THICKNESS, PARALLEL_TOL, &
       NAME_LEN, ORIENT_VALUES, ELASTIC_FIELDS, VECTOR_FIELDS, CONTACT_FIELDS, LOAD_FIELDS, &
       GRAV_FIELDS, CARD_SURFACE, CARD_DSLOAD, CARD_SECTION_PRINT, CARD_TIE, CARD_COUPLING_DOFS, CARD_MPC, &
       CARD_DCOUP_ELEMENT, CARD_DCOUP_NODES

  integer, parameter :: CARD_NONE = 0, CARD_SKIP = 1, CARD_NODATA = 2, CARD_HEADING = 3, &
       CARD_NODE = 4, CARD_ELEMENT = 5, CARD_NSET = 6, CARD_ELSET = 7, CARD_SECTION = 8, &
       CARD_ELASTIC = 9, CARD_ORIENTATION = 10, CARD_CONTACT = 11, CARD_SUPPORT = 12, &
       CARD_BOUNDARY = 13, CARD_CLOAD = 14, CARD_DLOAD = 15, CARD_DENSITY = 16, &
       CARD_TSHEAR = 17
    !! What the current card does with data lines.
  integer, parameter :: CARD_INSTANCE = 101, CARD_CHANGE_CONTACT = 102, CARD_INTERFACE = 103
    !! Cards of parts, instances and joint studies (superjoin_deck_cards_assembly).
  integer, parameter :: CARD_STATIC = 111, CARD_REQUEST = 112, CARD_SPRING_ELEMENT = 113, CARD_SPRING = 114
    !! CalculiX/Abaqus analysis cards (numbered apart from the model cards).
  integer, parameter :: CARD_COMBINATION = 131, CARD_EXPANSION = 132, CARD_TEMPERATURE = 133
    !! Load cases and combinations (superjoin's *LOAD COMBINATION).
  integer, parameter :: CARD_EQUATION = 121, CARD_TRANSFORM = 122
  integer, parameter :: CARD_NODAL_THICKNESS = 141
    !! Linear constraints, nodal systems and nodal thicknesses (superjoin_deck_equations, _transforms, _nodal_thickness).
    !! Name of the implicit substructure.
  real(wp), parameter :: PARALLEL_TOL = 1.0e-10_wp
    !! Relative size below which orientation vectors count as zero or parallel.
  integer, parameter :: NAME_LEN = 24
  integer, parameter :: ORIENT_VALUES = 6
  integer, parameter :: ELASTIC_FIELDS = 2, VECTOR_FIELDS = 3, CONTACT_FIELDS = 5, LOAD_FIELDS = 3, &
       GRAV_FIELDS = 6
  integer, parameter :: CARD_SURFACE = 151, CARD_DSLOAD = 152
    !! loads: *SURFACE, TYPE=ELEMENT and *DSLOAD (superjoin_deck_cards_steps)
  integer, parameter :: CARD_SECTION_PRINT = 161
    !! *SECTION PRINT (superjoin_deck_cards_output)
  integer, parameter :: CARD_TIE = 171
    !! *TIE (superjoin_deck_tie_build)
  integer, parameter :: CARD_COUPLING_DOFS = 181, CARD_MPC = 182
    !! *KINEMATIC / *DISTRIBUTING and *MPC (superjoin_deck_coupling_cards)
  integer, parameter :: CARD_DCOUP_ELEMENT = 199, CARD_DCOUP_NODES = 200
    !! *ELEMENT, TYPE=DCOUP3D and *DISTRIBUTING COUPLING (superjoin_deck_coupling_cards)

contains

  subroutine set_card(st, card, name, loc)
    !! Make `card` the current card.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: card
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: loc
    st%card = card
    st%card_name = name
    st%card_loc = loc
    st%card_ndata = 0
    st%card_sub = 0
    st%card_set = 0
    st%card_chunk = 0
    st%card_etype = 0
    st%card_item = 0
    st%card_home = 0
    st%card_generate = .false.
    st%card_fixed = .false.
    if (allocated(st%card_amp)) deallocate (st%card_amp)
  end subroutine set_card

  logical function outside_step(st, kw, loc) result(ok)
    !! Report `*KW is not allowed inside *STEP` and skip the card when a step is open.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    ok = st%cur_step == 0
    if (.not. ok) then
       call report_loc(st, loc, '*'//kw%keyword//' is not allowed inside *STEP')
       st%card = CARD_SKIP
    end if
  end function outside_step

  subroutine check_params(st, kw, loc, valued, flags)
    !! Report parameters that are not in `valued` (NAME=VALUE) or `flags` (NAME).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: valued(:), flags(:)
    integer :: i
    do i = 1, kw%nparam
       associate (p => kw%params(i))
         if (any(valued == p%name)) then
            if (.not. p%has_value) call report_loc(st, loc, 'parameter '//p%name//' of *'// &
                 kw%keyword//' needs a value ('//p%name//'=...)')
         else if (any(flags == p%name)) then
            if (p%has_value) call report_loc(st, loc, 'parameter '//p%name//' of *'// &
                 kw%keyword//' takes no value')
         else
            call report_loc(st, loc, 'unknown parameter '//clip(p%name)//' on *'//kw%keyword)
         end if
       end associate
    end do
  end subroutine check_params

  pure integer function param_index(kw, name) result(k)
    !! Index of parameter `name` (0 if absent).
    type(keyword_line_t), intent(in) :: kw
    character(*), intent(in) :: name
    do k = 1, kw%nparam
       if (kw%params(k)%name == name) return
    end do
    k = 0
  end function param_index

  subroutine get_param(st, kw, loc, name, required, value, found)
    !! Value of parameter `name` (with a value); `found` false if absent. When
    !! `required`, its absence is reported.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: name
    logical, intent(in) :: required
    character(:), allocatable, intent(out) :: value
    logical, intent(out) :: found
    integer :: k
    k = param_index(kw, name)
    found = .false.
    if (k > 0) found = kw%params(k)%has_value
    if (found) then
       value = kw%params(k)%value
    else
       value = ''
       if (required .and. k == 0) call report_loc(st, loc, '*'//kw%keyword//' needs parameter '//name//'=')
    end if
  end subroutine get_param

  subroutine get_name_param(st, kw, loc, name, required, value, found)
    !! A name-valued parameter, checked and upper-cased.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: name
    logical, intent(in) :: required
    character(:), allocatable, intent(out) :: value
    logical, intent(out) :: found
    call get_param(st, kw, loc, name, required, value, found)
    if (.not. found) return
    if (.not. is_name(value)) then
       call report_loc(st, loc, 'invalid name '''//clip(value)//''' for '//name//'= (letters, digits, _, - and / only)')
       found = .false.
       return
    end if
    value = to_upper(value)
  end subroutine get_name_param

  integer function target_sub(st, loc) result(k)
    !! Substructure that model cards outside/inside a block write to (MAIN is
    !! created on first use).
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    if (st%cur_sub > 0) then
       k = st%cur_sub
       return
    end if
    k = find_sub(st, MAIN_NAME)
    if (k == 0) call new_sub(st, MAIN_NAME, loc, k)
  end function target_sub

  logical function field_count(st, loc, nmin, nmax, expected) result(ok)
    !! True when the line has nmin..nmax fields; otherwise reported.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: nmin, nmax
    character(*), intent(in) :: expected
    ok = st%f%n >= nmin .and. st%f%n <= nmax
    if (.not. ok) call report_loc(st, loc, 'wrong number of fields on '//st%card_name// &
         ' data line: expected '//expected//', got '//plural(st%f%n, 'field'))
  end function field_count

  pure function fld(st, line, i) result(s)
    !! Field i of the current data line.
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: line
    integer, intent(in) :: i
    character(:), allocatable :: s
    s = line(st%f%first(i):st%f%last(i))
  end function fld

  logical function get_real(st, line, loc, i, x) result(ok)
    !! Real in field i (reported when invalid).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: i
    real(wp), intent(out) :: x
    integer :: stat
    call parse_real(line(st%f%first(i):st%f%last(i)), x, stat)
    ok = stat == TOK_OK
    if (.not. ok) call report_loc(st, loc, real_message(fld(st, line, i), stat))
  end function get_real

  logical function get_reals(st, line, loc, x) result(ok)
    !! Reals in fields 1..size(x), up to the first invalid one (reported).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp), intent(inout) :: x(:)
    integer :: i
    ok = .true.
    do i = 1, size(x)
       ok = get_real(st, line, loc, i, x(i))
       if (.not. ok) return
    end do
  end function get_reals

  function real_message(tok, stat) result(msg)
    !! Message for a real that could not be converted.
    character(*), intent(in) :: tok
    integer, intent(in) :: stat
    character(:), allocatable :: msg
    select case (stat)
    case (TOK_RANGE)
       msg = 'real out of range '''//clip(tok)//''''
    case (TOK_NONFINITE)
       msg = 'invalid real '''//clip(tok)//''' (NaN and Inf are not allowed)'
    case default
       if (len(tok) == 0) then
          msg = 'invalid real: empty field'
       else
          msg = 'invalid real '''//clip(tok)//''''
       end if
    end select
  end function real_message

  logical function get_id(st, line, loc, i, what, id) result(ok)
    !! Id in field i (reported when invalid); `what` names it in messages.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: i
    character(*), intent(in) :: what
    integer(ip), intent(out) :: id
    integer :: stat
    call parse_id(line(st%f%first(i):st%f%last(i)), id, stat)
    ok = stat == TOK_OK
    if (.not. ok) call report_loc(st, loc, id_message(what, fld(st, line, i)))
  end function get_id

  pure function id_message(what, tok) result(msg)
    !! Message for an id that could not be converted.
    character(*), intent(in) :: what, tok
    character(:), allocatable :: msg
    msg = 'invalid '//what//' '''//clip(tok)//''' (ids are positive integers below 2**31)'
  end function id_message

  logical function get_dof(st, line, loc, i, dof) result(ok)
    !! DOF number 1..6 in field i.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: i
    integer, intent(out) :: dof
    integer(ip) :: v
    integer :: stat
    call parse_id(line(st%f%first(i):st%f%last(i)), v, stat)
    ok = stat == TOK_OK
    if (ok) ok = v <= NDOF_NODE
    dof = 0
    if (ok) then
       dof = int(v)
    else
       call report_loc(st, loc, 'invalid DOF '''//clip(fld(st, line, i))//''' (1 to 6)')
    end if
  end function get_dof

  logical function get_dof_range(st, line, loc, i, first, last) result(ok)
    !! DOF range first..last in fields i, i+1.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: i
    integer, intent(out) :: first, last
    ok = get_dof(st, line, loc, i, first)
    if (.not. ok) return
    ok = get_dof(st, line, loc, i + 1, last)
    if (.not. ok) return
    ok = first <= last
    if (.not. ok) call report_loc(st, loc, 'first DOF '//itoa(first)//' is after last DOF '//itoa(last))
  end function get_dof_range

  logical function get_stiffness(st, line, loc, i, state, g) result(ok)
    !! Stiffness in field i: RIGID or a real >= 0.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: i
    integer, intent(out) :: state
    real(wp), intent(out) :: g
    g = 0.0_wp
    if (to_upper(fld(st, line, i)) == 'RIGID') then
       state = LINK_RIGID
       ok = .true.
       return
    end if
    state = LINK_NONE
    ok = get_real(st, line, loc, i, g)
    if (.not. ok) return
    if (g < 0.0_wp) then
       call report_loc(st, loc, 'stiffness must be >= 0 or RIGID, not '//clip(fld(st, line, i)))
       ok = .false.
    else if (g > 0.0_wp) then
       state = LINK_FINITE
    end if
  end function get_stiffness

  logical function parse_ref(st, tok, elem, home, loc, ref) result(ok)
    !! Parse a node or element reference (`id`, `set`, `SUB.id`, `SUB.set`).
    !! `home` is the substructure of plain references (0: MAIN).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: tok
    logical, intent(in) :: elem
    integer, intent(in) :: home
    type(source_loc_t), intent(in) :: loc
    type(ref_t), intent(out) :: ref
    character(:), allocatable :: what, rest
    integer :: dot, stat
    what = pick(elem, 'element', 'node')
    ref%home = home
    ok = .false.
    if (len(tok) == 0) then
       call report_loc(st, loc, 'missing '//what//' reference')
       return
    end if
    if (looks_numeric(tok)) then
       call parse_id(tok, ref%id, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, id_message(what//' id', tok))
          return
       end if
       ok = .true.
       return
    end if
    dot = index(tok, '.', back=.true.)   ! the scope may be an instance path (B.F3.BAY2.12)
    if (dot > 0) then
       rest = tok(dot + 1:)
       if (.not. is_path(tok(1:dot - 1))) then
          call report_loc(st, loc, 'invalid substructure name in '''//clip(tok)//'''')
          return
       end if
       ref%scope = to_upper(tok(1:dot - 1))
    else
       rest = tok
    end if
    if (is_digits(rest)) then
       call parse_id(rest, ref%id, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, id_message(what//' id', tok))
          return
       end if
    else if (is_name(rest)) then
       ref%is_set = .true.
       ref%set = to_upper(rest)
    else
       call report_loc(st, loc, 'invalid '//what//' reference '''//clip(tok)//''' ('//what// &
            ' id, set name, SUB.id or SUB.set)')
       return
    end if
    ok = .true.
  end function parse_ref

  logical function parse_set_ref(st, tok, elem, home, loc, ref) result(ok)
    !! A parameter that always names a set (ELSET=, NSET=): `set`, `SUB.set`.
    !! As in CalculiX and Abaqus, a name of digits only (ELSET=1) is a set
    !! name there; in data lines a field of digits is an id (parse_ref).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: tok
    logical, intent(in) :: elem
    integer, intent(in) :: home
    type(source_loc_t), intent(in) :: loc
    type(ref_t), intent(out) :: ref
    ok = parse_ref(st, tok, elem, home, loc, ref)
    if (.not. ok .or. ref%is_set) return
    ref%is_set = .true.
    ref%set = tok(index(tok, '.', back=.true.) + 1:)
    ref%id = 0
  end function parse_set_ref

  function loc_string(st, loc) result(s)
    !! "file:line" of a location.
    type(deck_state_t), intent(in) :: st
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: s
    s = st%files(loc%file)%s//':'//itoa(loc%line)
  end function loc_string

  logical function refused_card(st, kw, loc, prev_mat, what, hint) result(refused)
    !! A procedure, material behaviour or contact card that linear statics does
    !! not have: one message, its data lines skipped, and the current material
    !! kept so that the material's next cards still find it. what, if given,
    !! names what is refused in place of "*KEYWORD (reason)"; hint, if given,
    !! is added in parentheses (what is read instead).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: prev_mat
    character(*), intent(in), optional :: what, hint
    character(:), allocatable :: reason, text
    reason = refused_card_reason(kw%keyword)
    refused = len(reason) > 0
    if (.not. refused) return
    text = '*'//kw%keyword//' ('//reason//')'
    if (present(what)) text = what
    text = 'superjoin does linear statics; '//text//' is not supported'
    if (present(hint)) text = text//' ('//hint//')'
    call report_loc(st, loc, text)
    st%cur_mat = prev_mat
    if (st%cur_step > 0) then
       st%step_procedure = -1
       st%step_procedure_loc = loc
    end if
  end function refused_card

  pure function axis_rotation(n, angle) result(r)
    !! The rotation by angle degrees about the unit vector n (right hand;
    !! Rodrigues: r = c I + s [n]x + (1 - c) n nᵀ), quarter turns exact (cos 90
    !! degrees is not 0 in floating point).
    real(wp), intent(in) :: n(3), angle
    real(wp) :: r(3, 3), c, s
    real(wp), parameter :: RIGHT_ANGLE = 90.0_wp, HALF_TURN_DEG = 180.0_wp
    integer, parameter :: QUARTER_TURNS = 4
    integer :: i, turns
    if (mod(angle, RIGHT_ANGLE) == 0.0_wp .and. abs(angle) < huge(turns)*RIGHT_ANGLE) then
       turns = modulo(nint(angle/RIGHT_ANGLE), QUARTER_TURNS)
       c = real(merge(1, merge(-1, 0, turns == 2), turns == 0), wp)
       s = real(merge(1, merge(-1, 0, turns == 3), turns == 1), wp)
    else
       c = cos(angle*acos(-1.0_wp)/HALF_TURN_DEG)
       s = sin(angle*acos(-1.0_wp)/HALF_TURN_DEG)
    end if
    do i = 1, 3
       r(:, i) = (1.0_wp - c)*n*n(i)
       r(i, i) = r(i, i) + c
    end do
    r(1, 2) = r(1, 2) - s*n(3)
    r(1, 3) = r(1, 3) + s*n(2)
    r(2, 1) = r(2, 1) + s*n(3)
    r(2, 3) = r(2, 3) - s*n(1)
    r(3, 1) = r(3, 1) - s*n(2)
    r(3, 2) = r(3, 2) + s*n(1)
  end function axis_rotation
end module superjoin_deck_cards_common
