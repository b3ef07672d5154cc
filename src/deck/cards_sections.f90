module superjoin_deck_cards_sections
  !! Sections and materials: *MATERIAL, *ELASTIC, *DENSITY, *EXPANSION,
  !! *SOLID SECTION, *SHELL SECTION, *BEAM SECTION (library shapes),
  !! *BEAM GENERAL SECTION, *TRANSVERSE SHEAR STIFFNESS and *ORIENTATION.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: source_loc_t, SEC_BEAM, SEC_SHELL, MAT_ISO
  use superjoin_deck_cards_materials, only: elastic_kind, data_elastic_aniso
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, parse_real, parse_id, itoa, clip, plural, TOK_OK
  use superjoin_model_notes, only: append_string
  use superjoin_deck_state, only: deck_state_t, sec_b_t, sec_controls_b_t, report_loc, add_material, add_orientation, &
       add_sec_controls, &
       add_section, BEAM_2D_VALUES, BEAM_3D_VALUES, SHAPE_GENERAL
  use superjoin_deck_beam_sections, only: section_props_t, section_properties, shape_index, &
       SHAPE_NONE, SHAPE_L, SHAPE_I, SHAPE_NAMES, SHAPE_DIMS_MIN, SHAPE_DIMS_MAX, SHAPE_DATA, &
       MAX_SHAPE_DIMS
  use superjoin_elements_frame, only: real_text
  use superjoin_utils_strings, only: pick
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use superjoin_deck_cards_common, only: get_reals, axis_rotation
  use superjoin_deck_cards_common, only: outside_step, check_params, param_index, get_param, &
       get_name_param, field_count, fld, get_real, real_message, parse_set_ref, loc_string, CARD_SKIP, &
       CARD_SECTION, CARD_ELASTIC, CARD_ORIENTATION, CARD_DENSITY, CARD_TSHEAR, CARD_EXPANSION, &
       PARALLEL_TOL, NAME_LEN, ORIENT_VALUES, ELASTIC_FIELDS, VECTOR_FIELDS
  implicit none (type, external)
  private

  public :: kw_material, kw_density, kw_elastic, kw_expansion, data_expansion, data_elastic, &
       data_density, kw_section, data_section, kw_transverse_shear, data_transverse_shear, &
       kw_orientation, data_orientation, kw_section_controls

  integer, parameter :: GENERAL_FIELDS = 5
    !! *BEAM GENERAL SECTION, SECTION=GENERAL: A, I11, I12, I22, J.
  real(wp), parameter :: NU_MIN = -1.0_wp, NU_MAX = 0.5_wp
    !! Poisson's ratio bounds (open interval).

contains

  subroutine kw_material(st, kw, loc)
    !! *MATERIAL, NAME=m: opens a material for the cards that follow.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    logical :: found
    integer :: k
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME'], [character(NAME_LEN) ::])
    call get_name_param(st, kw, loc, 'NAME', .true., name, found)
    if (.not. found) then
       st%card = CARD_SKIP
       return
    end if
    do k = 1, st%nmat
       if (st%materials(k)%name == name) then
          call report_loc(st, loc, 'duplicate material name '//name//' (first defined at '// &
               loc_string(st, st%materials(k)%loc)//')')
          exit
       end if
    end do
    call add_material(st, name, loc, k)
    st%cur_mat = k
  end subroutine kw_material

  subroutine kw_density(st, kw, loc, mat)
    !! *DENSITY of the current material (for *DLOAD GRAV).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: mat
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    call material_data_card(st, loc, mat, CARD_DENSITY)
  end subroutine kw_density

  subroutine material_data_card(st, loc, mat, which)
    !! Start a property card of a material (which: CARD_ELASTIC or CARD_DENSITY)
    !! whose data lines go to material mat: there must be a current material
    !! and no earlier card of the same kind, else the card is skipped.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: mat, which
    character(:), allocatable :: card
    logical :: seen
    card = merge('*ELASTIC', '*DENSITY', which == CARD_ELASTIC)
    st%card = CARD_SKIP
    if (mat == 0) then
       call report_loc(st, loc, card//' must follow a *MATERIAL card')
       return
    end if
    associate (m => st%materials(mat))
      seen = merge(m%has_elastic, m%has_density, which == CARD_ELASTIC)
      if (seen) then
         call report_loc(st, loc, 'material '//m%name//' has more than one '//card)
         return
      end if
      if (which == CARD_ELASTIC) then
         m%has_elastic = .true.
      else
         m%has_density = .true.
      end if
    end associate
    st%cur_mat = mat
    st%card = which
    st%card_item = mat
  end subroutine material_data_card

  subroutine kw_elastic(st, kw, loc, mat)
    !! *ELASTIC of the material just opened (prev_mat).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: mat
    character(:), allocatable :: typ
    logical :: found
    integer :: kind
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'TYPE'], [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'TYPE', .false., typ, found)
    kind = MAT_ISO
    if (found) then
       kind = elastic_kind(typ)
       if (kind < 0) then
          call report_loc(st, loc, '*ELASTIC, TYPE='//clip(typ)//' is not supported: superjoin''s materials '// &
               'are TYPE=ISO, ORTHO, ENGINEERING CONSTANTS or ANISO')
          st%card = CARD_SKIP
          st%cur_mat = mat                   ! the material's next cards still find it
          if (mat > 0) st%materials(mat)%has_elastic = .true.   ! and it is not reported again as without *ELASTIC
          return
       end if
    end if
    call material_data_card(st, loc, mat, CARD_ELASTIC)
    if (st%card == CARD_ELASTIC) st%materials(mat)%kind = kind
  end subroutine kw_elastic

  subroutine kw_expansion(st, kw, loc, mat)
    !! *EXPANSION[, TYPE=ISO][, ZERO=t] of the current material: data lines
    !! alpha[, temperature] (a constant coefficient: ZERO= changes nothing; a
    !! table: the secant thermal strain from ZERO=, model/material_table).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: mat
    character(:), allocatable :: typ
    logical :: found
    integer :: stat
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'TYPE', 'ZERO'], [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'TYPE', .false., typ, found)
    if (found) then
       if (to_upper(typ) /= 'ISO' .and. to_upper(typ) /= 'ISOTROPIC') then
          call report_loc(st, loc, '*EXPANSION, TYPE='//clip(typ)//' is not supported (isotropic expansion only)')
          return
       end if
    end if
    if (mat == 0) then
       call report_loc(st, loc, '*EXPANSION must follow a *MATERIAL card')
       return
    end if
    if (st%materials(mat)%has_expansion) then
       call report_loc(st, loc, 'material '//st%materials(mat)%name//' has more than one *EXPANSION')
       return
    end if
    st%materials(mat)%has_expansion = .true.
    call get_param(st, kw, loc, 'ZERO', .false., typ, found)
    if (found) then     ! the temperature of no thermal strain (a table of alpha: the secant strain)
       call parse_real(typ, st%materials(mat)%zero, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, '*EXPANSION, ZERO= needs a number, not '//clip(typ))
          return
       end if
    end if
    st%cur_mat = mat
    st%card = CARD_EXPANSION
    st%card_item = mat
  end subroutine kw_expansion

  subroutine data_expansion(st, line, loc)
    !! The expansion coefficient: alpha[, temperature]; several lines make a
    !! table in temperature (the first line's alpha the material's constant).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: alpha
    if (.not. field_count(st, loc, 1, 2, 'alpha[, temperature]')) return
    if (.not. get_real(st, line, loc, 1, alpha)) return
    if (st%card_ndata == 1) st%materials(st%card_item)%alpha = alpha
    call table_line(st, line, loc, 2, [alpha], st%materials(st%card_item)%expansion_table)
  end subroutine data_expansion

  subroutine table_line(st, line, loc, nfield, values, table)
    !! A line of a temperature table (*ELASTIC, *EXPANSION): values and, in
    !! field nfield, the temperature, appended to table(:, n); every line of a
    !! table of several needs its temperature, in increasing order (the
    !! evaluation: superjoin_model_material_table).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: nfield
    real(wp), intent(in) :: values(:)
    real(wp), allocatable, intent(inout) :: table(:, :)
    real(wp) :: temp
    if (st%f%n < nfield) then
       if (st%card_ndata > 1) call report_loc(st, loc, 'each line of a temperature table needs its temperature (field '// &
            itoa(nfield)//')')
       if (st%card_ndata > 1) st%card = CARD_SKIP
       return
    end if
    if (.not. get_real(st, line, loc, nfield, temp)) return
    if (st%card_ndata == 1) then
       table = reshape([values, temp], [size(values) + 1, 1])
       return
    end if
    if (.not. allocated(table)) then
       call report_loc(st, loc, 'each line of a temperature table needs its temperature (the first line has none)')
       st%card = CARD_SKIP
       return
    end if
    if (.not. (temp > table(nfield, size(table, 2)))) then
       call report_loc(st, loc, 'the temperatures of a table must increase from line to line, not '// &
            fld(st, line, nfield))
       st%card = CARD_SKIP
       return
    end if
    table = reshape([table, values, temp], [size(values) + 1, size(table, 2) + 1])
  end subroutine table_line

  subroutine data_elastic(st, line, loc)
    !! A data line of *ELASTIC: E, nu[, temperature]; several lines make a
    !! table in temperature (the first line's E, nu the material's constants).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: e, nu
    if (st%materials(st%card_item)%kind /= MAT_ISO) then
       call data_elastic_aniso(st, line, loc)    ! TYPE=ORTHO, ENGINEERING CONSTANTS, ANISO
       return
    end if
    if (.not. field_count(st, loc, ELASTIC_FIELDS, ELASTIC_FIELDS + 1, 'E, nu[, temperature]')) return
    if (.not. get_real(st, line, loc, 1, e)) return
    if (.not. get_real(st, line, loc, 2, nu)) return
    if (.not. (e > 0.0_wp)) then
       call report_loc(st, loc, 'Young''s modulus E must be positive, not '//fld(st, line, 1))
       return
    end if
    if (.not. (nu > NU_MIN .and. nu < NU_MAX)) then
       call report_loc(st, loc, 'Poisson''s ratio must be between -1 and 0.5 (exclusive), not '//fld(st, line, 2))
       return
    end if
    ! several lines: a table in temperature (one line: its temperature any value)
    call table_line(st, line, loc, ELASTIC_FIELDS + 1, [e, nu], st%materials(st%card_item)%elastic_table)
    if (st%card_ndata > 1) return
    st%materials(st%card_item)%e = e
    st%materials(st%card_item)%nu = nu
  end subroutine data_elastic

  subroutine data_density(st, line, loc)
    !! The density: one value, >= 0, and optionally its temperature (Abaqus,
    !! CalculiX), read and not used; a table of several lines (a density that
    !! varies with the temperature) is refused.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: rho, temp
    if (st%card_ndata > 1) then
       call report_loc(st, loc, 'too many data lines for *DENSITY: superjoin takes one density (a table in '// &
            'temperature is not supported)')
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, 1, 2, 'density[, temperature]')) return
    if (.not. get_real(st, line, loc, 1, rho)) return
    if (st%f%n == 2) then                     ! the temperature of a one-line table: any value
       if (.not. get_real(st, line, loc, 2, temp)) return
    end if
    if (.not. (rho >= 0.0_wp)) then
       call report_loc(st, loc, 'density must not be negative, not '//fld(st, line, 1))
       return
    end if
    st%materials(st%card_item)%density = rho
  end subroutine data_density

  subroutine kw_section(st, kw, loc, kind)
    !! *SOLID SECTION, *SHELL SECTION, *BEAM SECTION or *BEAM GENERAL SECTION (kind SEC_*).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: kind
    character(:), allocatable :: elset, material, controls
    logical :: found_e, found_m, found_o, found_c
    type(sec_b_t) :: sec
    if (.not. outside_step(st, kw, loc)) return
    if (kind == SEC_BEAM) then
       call beam_section_params(st, kw, loc, sec)
    else if (kind == SEC_SHELL) then
       if (.not. shell_section_params(st, kw, loc)) then
          st%card = CARD_SKIP
          st%section_rejected(kind) = .true.
          return
       end if
    else
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'ELSET', 'MATERIAL', 'OFFSET', 'ORIENTATION', &
            'CONTROLS'], [character(NAME_LEN) :: 'NODAL THICKNESS'])
       call section_offset(st, kw, loc, kind)
       call get_name_param(st, kw, loc, 'ORIENTATION', .false., sec%orientation, found_o)  ! material axes
    end if
    if (kind /= SEC_BEAM) then   ! a *SECTION CONTROLS name (Abaqus), checked once the deck is read
       call get_name_param(st, kw, loc, 'CONTROLS', .false., controls, found_c)
       if (found_c) sec%controls = controls
    end if
    call get_param(st, kw, loc, 'ELSET', .true., elset, found_e)
    call get_name_param(st, kw, loc, 'MATERIAL', .true., material, found_m)
    st%card = CARD_SKIP
    if (.not. (found_e .and. found_m)) then
       ! one mistake: the elements it meant are not reported again as without a section
       st%section_rejected(kind) = .true.
       return
    end if
    if (.not. parse_set_ref(st, elset, .true., st%cur_sub, loc, sec%elset)) then
       st%section_rejected(kind) = .true.
       return
    end if
    sec%kind = kind
    sec%material = material
    sec%loc = loc
    ! CalculiX / Abaqus: the thickness of every node comes from *NODAL THICKNESS (a data line is optional)
    ! (*SOLID SECTION: the plane elements' thickness; *BEAM SECTION refuses the parameter)
    sec%nodal_thickness = kind /= SEC_BEAM .and. param_index(kw, 'NODAL THICKNESS') > 0
    call add_section(st, sec, st%card_item)
    st%card = CARD_SECTION
    if (kind == SEC_BEAM .or. kind == SEC_SHELL) st%cur_beam_sec = st%card_item
  end subroutine kw_section

  logical function shell_points_ok(st, line, loc) result(ok)
    !! Abaqus's second field of a *SHELL SECTION data line: the number of
    !! integration points through the thickness (Simpson's rule, 5 by
    !! default). superjoin integrates the homogeneous elastic section exactly,
    !! as a rule of 3 or more Simpson points (2 or more Gauss points) does, so
    !! any such number is read and changes nothing; 1 point would leave the
    !! section without bending stiffness in Abaqus: refused.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer(ip) :: n
    integer :: stat
    ok = .true.
    if (st%f%n < 2) return
    if (st%f%last(2) < st%f%first(2)) return   ! empty: the default
    call parse_id(fld(st, line, 2), n, stat)
    ok = stat == TOK_OK .and. n >= 2
    if (.not. ok) call report_loc(st, loc, 'the number of integration points through a shell''s thickness '// &
         '(second field) must be an integer of 2 or more, not '//clip(fld(st, line, 2))// &
         ' (superjoin integrates the elastic section exactly; any such number changes nothing)')
  end function shell_points_ok

  subroutine kw_section_controls(st, kw, loc)
    !! *SECTION CONTROLS, NAME=c (Abaqus; Abaqus/CAE writes one for every
    !! reduced-integration solid section, HOURGLASS=ENHANCED): the element
    !! technology of the sections that name it (CONTROLS=c). superjoin's one
    !! choice that it could touch is the C3D8R's hourglass stiffness, which
    !! is always C3D8I's in the hourglass modes (close to Abaqus's ENHANCED);
    !! the rest (element deletion, distortion control, viscosity, the scaling
    !! factors of the data line) concerns nonlinear and explicit analyses. The
    !! card is recorded (CONTROLS= must name one) and said in one listing note.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(sec_controls_b_t) :: c
    character(:), allocatable :: hourglass
    logical :: found
    st%card = CARD_SKIP
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'HOURGLASS', 'ELEMENT DELETION', &
         'DISTORTION CONTROL', 'KINEMATIC SPLIT', 'SECOND ORDER ACCURACY', 'MAX DEGRADATION', 'VISCOSITY', &
         'WEIGHT FACTOR', 'KERNEL', 'LENGTH RATIO', 'INITIAL GAP OPENING', 'ELEMENT CONVERSION'], &
         [character(NAME_LEN) ::])
    call get_name_param(st, kw, loc, 'NAME', .true., c%name, found)
    if (.not. found) return
    c%loc = loc
    call add_sec_controls(st, c)
    call get_param(st, kw, loc, 'HOURGLASS', .false., hourglass, found)
    if (.not. found) hourglass = 'the default'
    call append_string(st%notes, '*SECTION CONTROLS '//c%name//' at '//loc_string(st, loc)//' (HOURGLASS='// &
         to_upper(hourglass)//'): superjoin''s C3D8R has one hourglass stiffness, C3D8I''s in its hourglass '// &
         'modes (close to Abaqus''s ENHANCED); the card''s other settings are for nonlinear and explicit '// &
         'analyses: not used')
  end subroutine kw_section_controls

  logical function shell_section_params(st, kw, loc) result(ok)
    !! Parameters of *SHELL SECTION: ELSET=, MATERIAL=, OFFSET=0 (the mid-surface,
    !! the default; another offset is refused); COMPOSITE (layers) is refused
    !! with one message (false: the card and its data lines are skipped).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(keyword_line_t) :: rest
    real(wp) :: v
    integer :: k, stat
    ok = .true.
    if (param_index(kw, 'COMPOSITE') > 0) then
       call report_loc(st, loc, '*SHELL SECTION, COMPOSITE (a layered section) is not supported: superjoin''s '// &
            'shells have one material and one thickness')
       ok = .false.
       return
    end if
    rest%keyword = kw%keyword
    rest%nparam = 0
    allocate (rest%params(max(kw%nparam, 1)))
    do k = 1, kw%nparam
       associate (p => kw%params(k))
         if (p%name == 'OFFSET' .and. p%has_value) then
            read (p%value, *, iostat=stat) v
            if (stat /= 0 .or. v /= 0.0_wp) call report_loc(st, loc, 'OFFSET='//clip(p%value)// &
                 ' is not supported: superjoin''s shells lie on their mid-surface (OFFSET=0)')
         else
            rest%nparam = rest%nparam + 1
            rest%params(rest%nparam) = p
         end if
       end associate
    end do
    call check_params(st, rest, loc, [character(NAME_LEN) :: 'ELSET', 'MATERIAL', 'OFFSET', 'CONTROLS', &
         'SECTION INTEGRATION'], [character(NAME_LEN) :: 'NODAL THICKNESS'])
  end function shell_section_params

  subroutine beam_section_params(st, kw, loc, sec)
    !! Parameters of *BEAM SECTION / *BEAM GENERAL SECTION: SECTION= picks
    !! superjoin's constants (GENERAL on *BEAM SECTION: A, I or A, Iy, Iz, J),
    !! Abaqus's general section (GENERAL on *BEAM GENERAL SECTION, the default
    !! there: A, I11, I12, I22, J) or a library shape (RECT, CIRC, PIPE, BOX, I,
    !! L); OFFSET1/OFFSET2 (CalculiX) must be 0: the beam acts at the centroid.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(sec_b_t), intent(inout) :: sec
    character(:), allocatable :: value
    logical :: found, general_card
    integer :: k, stat
    real(wp) :: x
    general_card = kw%keyword == 'BEAM GENERAL SECTION'
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'ELSET', 'MATERIAL', 'SECTION', &
         'POISSON', 'TEMPERATURE', 'OFFSET1', 'OFFSET2', 'ORIENTATION', 'DENSITY'], &
         [character(NAME_LEN) :: 'LUMPED', 'ROTARY INERTIA', 'NODAL THICKNESS'])
    if (param_index(kw, 'NODAL THICKNESS') > 0) then
       call report_loc(st, loc, '*'//kw%keyword//', NODAL THICKNESS (the section''s dimensions per node, '// &
            'a tapered beam) is not supported: superjoin''s beams have one cross-section; give its '// &
            'dimensions on the data line')
       st%section_rejected(SEC_BEAM) = .true.   ! the beams' *NODAL THICKNESS lines are not reported again
    end if
    do k = 1, 2
       call get_param(st, kw, loc, 'OFFSET'//itoa(k), .false., value, found)
       if (.not. found) cycle
       call parse_real(value, x, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, real_message(value, stat))
       else if (x /= 0.0_wp) then
          call report_loc(st, loc, 'OFFSET'//itoa(k)//'='//clip(value)//' is not supported: superjoin''s '// &
               'beams act at the centroid of their section (OFFSET'//itoa(k)//'=0)')
       end if
    end do
    call get_param(st, kw, loc, 'SECTION', .false., value, found)
    if (.not. found) value = 'GENERAL'
    value = to_upper(value)
    if (value == 'GENERAL') then
       if (general_card) sec%shape = SHAPE_GENERAL
       return
    end if
    sec%shape = shape_index(value)
    if (sec%shape == SHAPE_NONE) then
       call report_loc(st, loc, 'SECTION='//clip(value)//' is not supported on *'//kw%keyword// &
            ' (GENERAL, RECT, CIRC, PIPE, BOX, I)')
       sec%data_ok = .false.
    else if (sec%shape == SHAPE_L) then
       call report_loc(st, loc, 'SECTION=L is not supported: an angle''s legs are not principal axes '// &
            '(I12 /= 0) and its origin is not its centroid; give its principal constants with SECTION=GENERAL')
       sec%data_ok = .false.
    end if
  end subroutine beam_section_params

  subroutine section_offset(st, kw, loc, kind)
    !! OFFSET= of *SOLID SECTION / *SHELL SECTION (CalculiX): 0 (the mid-surface, the default)
    !! is accepted; another offset of the reference surface is refused.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: kind
    character(:), allocatable :: value
    logical :: found
    integer :: stat
    real(wp) :: x
    call get_param(st, kw, loc, 'OFFSET', .false., value, found)
    if (.not. found) return
    call parse_real(value, x, stat)
    if (stat /= TOK_OK) then
       call report_loc(st, loc, real_message(value, stat))
    else if (x /= 0.0_wp) then
       call report_loc(st, loc, 'OFFSET='//clip(value)//' is not supported: superjoin''s '// &
            pick(kind == SEC_SHELL, 'shells', 'plane elements')//' have their reference surface at the '// &
            'mid-surface (OFFSET=0)')
    end if
  end subroutine section_offset

  subroutine data_section(st, line, loc)
    !! A data line of a section card (thickness, beam values or library shape dimensions).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer :: i
    real(wp) :: v(4)
    if (st%card_ndata == 1 .and. .not. st%sections(st%card_item)%data_ok) then
       st%card = CARD_SKIP                  ! refused on its keyword line: no further messages
       return
    end if
    if (st%sections(st%card_item)%shape /= SHAPE_NONE) then
       call data_beam_shape(st, line, loc)
       return
    end if
    associate (sec => st%sections(st%card_item))
      if (st%card_ndata == 1) sec%data_loc = loc
      if (sec%kind /= SEC_BEAM .and. st%card_ndata > 1 .or. st%card_ndata > 2) then
         call report_loc(st, loc, 'too many data lines for '//st%card_name)
         sec%data_ok = .false.
         st%card = CARD_SKIP
         return
      end if
      if (sec%kind /= SEC_BEAM) then
         ! an empty line (Abaqus/CAE writes `,` under a solid's section): no value, as without the line
         if (st%f%n == 0) return
         if (sec%kind == SEC_SHELL) then
            if (.not. field_count(st, loc, 1, 2, 'thickness[, integration points through it]')) then
               sec%data_ok = .false.
               return
            end if
            if (.not. shell_points_ok(st, line, loc)) then
               sec%data_ok = .false.
               return
            end if
         else if (.not. field_count(st, loc, 1, 1, 'one value (area or thickness)')) then
            sec%data_ok = .false.
            return
         end if
         if (.not. get_real(st, line, loc, 1, v(1))) then
            sec%data_ok = .false.
            return
         end if
         if (.not. (v(1) > 0.0_wp)) then
            if (sec%kind == SEC_SHELL) then
               call report_loc(st, loc, 'shell thickness must be positive, not '//fld(st, line, 1))
            else
               call report_loc(st, loc, 'section area or thickness must be positive, not '//fld(st, line, 1))
            end if
            sec%data_ok = .false.
            return
         end if
         sec%nval = 1
         sec%val(1) = v(1)
      else if (st%card_ndata == 1 .and. st%f%n == GENERAL_FIELDS) then
         ! CalculiX's SECTION=GENERAL: A, I11, I12, I22, J as on *BEAM GENERAL SECTION
         sec%shape = SHAPE_GENERAL
         sec%five_general = .true.
         call data_beam_shape(st, line, loc)
      else if (st%card_ndata == 1) then
         if (.not. field_count(st, loc, BEAM_2D_VALUES, BEAM_3D_VALUES, 'A, I (2D) or A, Iy, Iz, J (3D)')) then
            sec%data_ok = .false.
            return
         end if
         if (st%f%n /= BEAM_2D_VALUES .and. st%f%n /= BEAM_3D_VALUES) then
            call report_loc(st, loc, 'wrong number of fields on *BEAM SECTION data line: expected '// &
                 'A, I (2D) or A, Iy, Iz, J (3D), got '//plural(st%f%n, 'field'))
            sec%data_ok = .false.
            return
         end if
         do i = 1, st%f%n
            if (.not. get_real(st, line, loc, i, v(i))) then
               sec%data_ok = .false.
               return
            end if
            if (.not. (v(i) > 0.0_wp)) then
               call report_loc(st, loc, 'beam section constants (A, I, J) must be positive, not '// &
                    fld(st, line, i))
               sec%data_ok = .false.
               return
            end if
         end do
         sec%nval = st%f%n
         sec%val(1:st%f%n) = v(1:st%f%n)
      else
         if (sec%nval /= BEAM_3D_VALUES) then
            call report_loc(st, loc, 'the orientation vector line is only for 3D beam sections (A, Iy, Iz, J)')
            sec%data_ok = .false.
            return
         end if
         call read_orientation_vector(st, line, loc, 'vx, vy, vz', st%card_item)
      end if
    end associate
  end subroutine data_section

  subroutine read_orientation_vector(st, line, loc, expected, isec)
    !! The orientation-vector data line of beam section `isec` (vx, vy, vz, not
    !! zero) into its v; any problem is reported and marks the section's data bad.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line, expected
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: isec
    real(wp) :: v(VECTOR_FIELDS)
    integer :: i
    logical :: ok
    ok = field_count(st, loc, VECTOR_FIELDS, VECTOR_FIELDS, expected)
    do i = 1, VECTOR_FIELDS
       if (ok) ok = get_real(st, line, loc, i, v(i))
    end do
    if (ok .and. norm2(v) == 0.0_wp) then
       call report_loc(st, loc, 'beam orientation vector is zero')
       ok = .false.
    end if
    if (.not. ok) then
       st%sections(isec)%data_ok = .false.
       return
    end if
    st%sections(isec)%v = v
    st%sections(isec)%has_v = .true.
  end subroutine read_orientation_vector

  subroutine data_beam_shape(st, line, loc)
    !! First data line of a library section (its dimensions, constants computed
    !! by superjoin_deck_beam_sections) or of Abaqus's general section
    !! (A, I11, I12, I22, J); the second line, the direction of axis 1, is the
    !! beam's orientation vector v.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: d(MAX_SHAPE_DIMS)
    type(section_props_t) :: p
    type(halting_t) :: saved
    character(:), allocatable :: problem, expected
    integer :: nmin, nmax
    real(wp), parameter :: CENTROID_TOL = 1.0e-9_wp
    associate (sec => st%sections(st%card_item))
      if (st%card_ndata == 1) sec%data_loc = loc
      if (st%card_ndata > 2) then
         call report_loc(st, loc, 'too many data lines for '//st%card_name)
         sec%data_ok = .false.
         st%card = CARD_SKIP
         return
      end if
      if (st%card_ndata == 2) then
         call read_orientation_vector(st, line, loc, 'vx, vy, vz (direction of section axis 1)', st%card_item)
         return
      end if
      if (sec%shape == SHAPE_GENERAL) then
         nmin = GENERAL_FIELDS
         nmax = GENERAL_FIELDS
         expected = 'A, I11, I12, I22, J'
      else
         nmin = SHAPE_DIMS_MIN(sec%shape)
         nmax = SHAPE_DIMS_MAX(sec%shape)
         expected = trim(SHAPE_DATA(sec%shape))//' for SECTION='//trim(SHAPE_NAMES(sec%shape))
      end if
      if (.not. field_count(st, loc, nmin, nmax, expected)) then
         sec%data_ok = .false.
         return
      end if
      if (.not. get_reals(st, line, loc, d(1:st%f%n))) then
         sec%data_ok = .false.
         return
      end if
      if (sec%shape == SHAPE_GENERAL) then
         if (.not. (d(1) > 0.0_wp .and. d(2) > 0.0_wp .and. d(4) > 0.0_wp .and. d(5) > 0.0_wp)) then
            call report_loc(st, loc, 'beam section constants A, I11, I22, J must be positive')
            sec%data_ok = .false.
         else if (d(3) /= 0.0_wp) then
            call report_loc(st, loc, 'I12 = '//fld(st, line, 3)//' is not supported: superjoin''s beams '// &
                 'need principal axes (I12 = 0); give the principal constants and point v along axis 1')
            sec%data_ok = .false.
         else
            sec%sp = [d(1), d(2), d(4), 0.0_wp, d(5)]
         end if
         return
      end if
      call halting_off(saved)   ! constants up to a dimension's fourth power: overflow is reported
      call section_properties(sec%shape, d(1:st%f%n), p, problem)
      call halting_restore(saved)
      if (len(problem) == 0) then
         if (.not. all(ieee_is_finite([p%area, p%i11, p%i22, p%i12, p%j, p%c]))) then
            problem = 'the section''s constants (area, inertias, torsion constant) overflow the floating-point '// &
                 'range: check the dimensions and their units'
         else if (.not. all([p%area, p%i11, p%i22, p%j] > 0.0_wp)) then
            problem = 'the section''s constants (area, inertias, torsion constant) underflow to zero: '// &
                 'check the dimensions and their units'
         end if
      end if
      if (len(problem) > 0) then
         call report_loc(st, loc, problem//' (SECTION='//trim(SHAPE_NAMES(sec%shape))//')')
         sec%data_ok = .false.
         return
      end if
      if (norm2(p%c) > CENTROID_TOL*maxval(d(1:st%f%n))) then
         call report_loc(st, loc, 'the section''s centroid is not at its origin (offset '// &
              real_text(p%c(1))//', '//real_text(p%c(2))//'): superjoin''s beams act at the centroid'// &
              pick(sec%shape == SHAPE_I, ' (set l to the centroid height)', ''))
         sec%data_ok = .false.
         return
      end if
      sec%sp = [p%area, p%i11, p%i22, p%i12, p%j]
      sec%ndims = st%f%n
      sec%dims(1:st%f%n) = d(1:st%f%n)
    end associate
  end subroutine data_beam_shape

  subroutine kw_transverse_shear(st, kw, loc, isec)
    !! *TRANSVERSE SHEAR STIFFNESS right after the *BEAM SECTION or *SHELL SECTION it applies to.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: isec
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    if (isec == 0) then
       call report_loc(st, loc, '*TRANSVERSE SHEAR STIFFNESS must follow the *BEAM SECTION or *SHELL SECTION '// &
            'it applies to')
       return
    end if
    if (st%sections(isec)%has_ks) then
       call report_loc(st, loc, 'second *TRANSVERSE SHEAR STIFFNESS for the same section')
       return
    end if
    st%sections(isec)%ks_loc = loc
    st%card = CARD_TSHEAR
    st%card_item = isec
    st%cur_beam_sec = isec
  end subroutine kw_transverse_shear

  subroutine data_transverse_shear(st, line, loc)
    !! K23 [, K13 [, slenderness compensation factor]]: shear stiffness in
    !! force units (k G A); the third value is read and not used.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, parameter :: MAX_FIELDS = 3
    integer :: i
    real(wp) :: v(MAX_FIELDS)
    if (st%card_ndata > 1) then
       call report_loc(st, loc, 'too many data lines for '//st%card_name)
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, 1, MAX_FIELDS, 'K23, K13 (and optionally the slenderness compensation factor)')) &
         return
    do i = 1, st%f%n
       if (.not. get_real(st, line, loc, i, v(i))) return
       if (i <= 2 .and. .not. (v(i) > 0.0_wp)) then
          call report_loc(st, loc, 'transverse shear stiffness must be positive, not '//fld(st, line, i))
          return
       end if
    end do
    associate (sec => st%sections(st%card_item))
      sec%nks = min(st%f%n, 2)
      sec%ks(1:sec%nks) = v(1:sec%nks)
      sec%has_ks = .true.
      sec%ks_loc = loc
    end associate
  end subroutine data_transverse_shear

  subroutine kw_orientation(st, kw, loc)
    !! *ORIENTATION, NAME=o: a local system for sections.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    logical :: found
    integer :: k
    logical :: cylindrical
    character(:), allocatable :: system
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'SYSTEM', 'DEFINITION'], [character(NAME_LEN) ::])
    call get_name_param(st, kw, loc, 'NAME', .true., name, found)
    st%card = CARD_SKIP
    if (.not. found) return
    call get_param(st, kw, loc, 'DEFINITION', .false., system, found)   ! Abaqus's; CalculiX warns and goes on
    if (found) then
       if (to_upper(system) /= 'COORDINATES') then
          call report_loc(st, loc, '*ORIENTATION, DEFINITION='//clip(system)//' is not supported: superjoin '// &
               'takes DEFINITION=COORDINATES (the default: the points a and b)')
          return
       end if
    end if
    cylindrical = .false.
    call get_param(st, kw, loc, 'SYSTEM', .false., system, found)
    if (found) then
       select case (to_upper(system))
       case ('RECTANGULAR', 'R')
       case ('CYLINDRICAL', 'C')
          cylindrical = .true.
       case default
          call report_loc(st, loc, '*ORIENTATION SYSTEM must be RECTANGULAR or CYLINDRICAL, not '//clip(system))
          return
       end select
    end if
    do k = 1, st%norient
       if (st%orientations(k)%name == name) then
          call report_loc(st, loc, 'duplicate orientation name '//name//' (first defined at '// &
               loc_string(st, st%orientations(k)%loc)//')')
          return
       end if
    end do
    call add_orientation(st, name, loc, st%card_item)
    st%orientations(st%card_item)%cylindrical = cylindrical
    st%card = CARD_ORIENTATION
  end subroutine kw_orientation

  subroutine data_orientation(st, line, loc)
    !! A data line of *ORIENTATION: the points a and b.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: v(ORIENT_VALUES), a(3), b(3), e1(3), e2(3), e3(3), na, nb, n2
    if (st%card_ndata == 2) then
       call orientation_rotation(st, line, loc)
       return
    end if
    if (st%card_ndata > 2) then
       call report_loc(st, loc, 'too many data lines for *ORIENTATION')
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, ORIENT_VALUES, ORIENT_VALUES, 'ax, ay, az, bx, by, bz')) return
    if (.not. get_reals(st, line, loc, v(1:ORIENT_VALUES))) return
    a = v(1:3)
    b = v(4:6)
    if (st%orientations(st%card_item)%cylindrical) then
       ! SYSTEM=CYLINDRICAL (CalculiX): a and b are two points of the axis; the frame
       ! (radial, tangential, axial) is taken per node pair when the links are built
       if (norm2(b - a) == 0.0_wp) then
          call report_loc(st, loc, '*ORIENTATION, SYSTEM=CYLINDRICAL: points a and b coincide (they define '// &
               'the cylinder''s axis)')
          return
       end if
       st%orientations(st%card_item)%a = a
       st%orientations(st%card_item)%b = b
       return
    end if
    na = norm2(a)
    nb = norm2(b)
    if (na == 0.0_wp) then
       call report_loc(st, loc, 'orientation vector a is zero')
       return
    end if
    if (nb == 0.0_wp) then
       call report_loc(st, loc, 'orientation vector b is zero')
       return
    end if
    e1 = a/na
    e2 = b - dot_product(b, e1)*e1
    n2 = norm2(e2)
    if (n2 <= PARALLEL_TOL*nb) then
       call report_loc(st, loc, 'orientation vectors a and b are parallel')
       return
    end if
    e2 = e2/n2
    e3 = [e1(2)*e2(3) - e1(3)*e2(2), e1(3)*e2(1) - e1(1)*e2(3), e1(1)*e2(2) - e1(2)*e2(1)]
    st%orientations(st%card_item)%q(1, :) = e1
    st%orientations(st%card_item)%q(2, :) = e2
    st%orientations(st%card_item)%q(3, :) = e3
  end subroutine data_orientation

  subroutine orientation_rotation(st, line, loc)
    !! The second data line of *ORIENTATION: axis, angle: the local system turns
    !! by angle degrees about its own axis 1, 2 or 3 (right hand; Abaqus and
    !! CalculiX; rectangular systems only, as CalculiX).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: v(2), n(3)
    integer :: axis
    if (st%orientations(st%card_item)%cylindrical) then
       call report_loc(st, loc, '*ORIENTATION: the additional rotation (second data line) is only for '// &
            'rectangular systems (as CalculiX)')
       return
    end if
    if (.not. field_count(st, loc, 2, 2, 'axis (1, 2 or 3), angle in degrees')) return
    if (.not. get_reals(st, line, loc, v)) return
    axis = nint(v(1))
    if (real(axis, wp) /= v(1) .or. axis < 1 .or. axis > 3) then
       call report_loc(st, loc, '*ORIENTATION: the axis of the additional rotation must be 1, 2 or 3, not '// &
            fld(st, line, 1))
       return
    end if
    associate (q => st%orientations(st%card_item)%q)
      n = q(axis, :)                     ! a contiguous copy (no array temporary)
      q = transpose(matmul(axis_rotation(n, v(2)), transpose(q)))   ! each local axis (a row of q) turned
    end associate
  end subroutine orientation_rotation
end module superjoin_deck_cards_sections
