module superjoin_deck_parser
  !! Card-level parser of the deck reader: walks the lines of a deck (and of the
  !! files it includes), recognizes keyword and data lines and records what they
  !! define in the reader state, by user ids and names. References are resolved
  !! later, by superjoin_deck_validate. The keyword is dispatched here, in
  !! open_card, to the card routines of its family: superjoin_deck_cards_model,
  !! _cards_sections, _cards_steps, _cards_output, _cards_assembly, _equations,
  !! _transforms, _nodal_thickness (helpers shared by them: _cards_common).
  use superjoin_kinds, only: i8
  use superjoin_model_types, only: source_loc_t, SEC_SOLID, SEC_BEAM, SEC_SHELL
  use superjoin_deck_lexer, only: keyword_line_t, next_line, first_nonblank, &
       parse_keyword_line, split_fields, drop_trailing_empty, itoa, clip, path_dirname, path_join, &
       path_normalize
  use superjoin_deck_state, only: deck_state_t, report, report_loc, add_heading, &
       add_step, MAX_INCLUDE_DEPTH, register_file, load_deck_file
  use superjoin_deck_ccx_cards, only: canonical_keyword
  use superjoin_deck_springs, only: translate_springs
  use superjoin_deck_cards_common, only: set_card, check_params, get_param, refused_card, CARD_NONE, &
       CARD_SKIP, CARD_NODATA, CARD_HEADING, CARD_NODE, CARD_ELEMENT, CARD_NSET, CARD_ELSET, &
       CARD_SECTION, CARD_ELASTIC, CARD_ORIENTATION, CARD_CONTACT, CARD_SUPPORT, CARD_BOUNDARY, &
       CARD_CLOAD, CARD_DLOAD, CARD_DENSITY, CARD_TSHEAR, CARD_INSTANCE, CARD_CHANGE_CONTACT, &
       CARD_INTERFACE, CARD_STATIC, CARD_REQUEST, CARD_SPRING_ELEMENT, CARD_SPRING, &
       CARD_COMBINATION, CARD_EXPANSION, CARD_TEMPERATURE, CARD_EQUATION, CARD_TRANSFORM, &
       CARD_NODAL_THICKNESS, NAME_LEN, CARD_SURFACE, CARD_DSLOAD, CARD_SECTION_PRINT, CARD_TIE, CARD_COUPLING_DOFS, CARD_MPC, &
       CARD_DCOUP_ELEMENT, CARD_DCOUP_NODES
  use superjoin_deck_cards_assembly, only: assembly_allows, finish_assembly, kw_assembly, &
       data_instance, kw_interface, data_interface, kw_change_contact, data_change_contact, &
       kw_contact, data_contact, kw_support, data_support
  use superjoin_deck_cards_model, only: kw_heading, kw_substructure, kw_end_substructure, kw_node, &
       kw_element, kw_set, data_node, data_element, data_set, data_spring_element, kw_spring, &
       data_spring
  use superjoin_deck_cards_sections, only: kw_material, kw_density, kw_elastic, kw_expansion, &
       data_expansion, data_elastic, data_density, kw_section, data_section, kw_transverse_shear, &
       data_transverse_shear, kw_orientation, data_orientation, kw_section_controls
  use superjoin_deck_cards_materials, only: end_elastic_card
  use superjoin_deck_cards_steps, only: kw_step, kw_end_step, kw_static, data_static, kw_controls, &
       kw_boundary, data_boundary, kw_load, data_load, kw_surface, data_surface, data_dsload, &
       kw_load_combination, data_combination, kw_temperature, data_temperature
  use superjoin_deck_cards_output, only: kw_output, kw_request, data_request, kw_section_print, data_section_print
  use superjoin_deck_equations, only: kw_equation, data_equation, end_equation_card
  use superjoin_deck_pretension, only: kw_pretension, data_pretension, CARD_PRETENSION
  use superjoin_deck_ties, only: kw_tie, data_tie
  use superjoin_deck_coupling_cards, only: kw_coupling_card, data_coupling_dofs, data_mpc, data_dcoup_element, &
       data_dcoup_nodes
  use superjoin_deck_transforms, only: kw_transform, data_transform
  use superjoin_deck_nodal_thickness, only: kw_nodal_thickness, data_nodal_thickness
  use superjoin_deck_matrix_input, only: kw_matrix_input, kw_matrix_output
  use superjoin_deck_amplitudes, only: kw_amplitude, data_amplitude, record_amp_line, CARD_AMPLITUDE
  use superjoin_deck_matrix_loads, only: data_matrix_load, CARD_MATRIX_LOAD
  implicit none (type, external)
  private

  public :: parse_source, finish_parse, register_file

  character(*), parameter :: BOM = char(239)//char(187)//char(191)
    !! UTF-8 byte order mark, skipped at the start of a file.
  integer(i8), parameter :: MAX_LINE_LENGTH = 1073741824_i8
    !! Longest line accepted (2**30 characters): positions inside a line are
    !! default integers, so a longer line is refused rather than mis-read.

contains

  recursive subroutine parse_source(st, text, file)
    !! Parse the lines of `text`, which is file number `file` (recursive through *INCLUDE).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text
    integer, intent(in) :: file
    integer(i8) :: pos, first, last
    integer :: line
    logical :: found
    pos = 1
    if (len(text) >= len(BOM)) then
       if (text(1:len(BOM)) == BOM) pos = len(BOM) + 1
    end if
    line = 0
    do
       call next_line(text, pos, first, last, found)
       if (.not. found) exit
       if (line == huge(line)) then
          call report(st, file, line, 'more than '//itoa(huge(line))//' lines in one file')
          st%aborted = .true.
          exit
       end if
       line = line + 1
       if (last - first + 1 > MAX_LINE_LENGTH) then
          call report(st, file, line, 'line of '//itoa(last - first + 1)//' characters (at most '// &
               itoa(MAX_LINE_LENGTH)//')')
          st%aborted = .true.
          exit
       end if
       call process_line(st, text(first:last), file, line)
       if (st%aborted) exit
    end do
  end subroutine parse_source

  recursive subroutine process_line(st, line, file, lineno)
    !! One line: comment, blank, keyword or data.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    integer, intent(in) :: file, lineno
    integer :: p
    type(source_loc_t) :: loc
    p = first_nonblank(line)
    if (p == 0) return
    if (len(line) >= p + 1) then
       if (line(p:p + 1) == '**') return
    end if
    loc%file = file
    loc%line = lineno
    if (line(p:p) == '*') then
       call keyword_line(st, line(p:), loc)
    else
       call data_line(st, line, loc)
    end if
  end subroutine process_line

  subroutine finish_parse(st)
    !! End of the input: close the last card and check that blocks were closed.
    type(deck_state_t), intent(inout) :: st
    integer :: k
    type(source_loc_t) :: loc
    call end_card(st)
    call finish_assembly(st)
    call translate_springs(st)
    if (st%cur_sub > 0) call report_loc(st, st%subs(st%cur_sub)%loc, &
         '*SUBSTRUCTURE '//st%subs(st%cur_sub)%name//' has no *END SUBSTRUCTURE')
    if (st%cur_step > 0) call report_loc(st, st%steps(st%cur_step)%loc, &
         '*STEP '//st%steps(st%cur_step)%name//' has no *END STEP')
    st%cur_sub = 0
    st%cur_step = 0
    if (st%nstep == 0) then
       loc%file = 1
       loc%line = 0
       call add_step(st, '1', loc, k)
    end if
  end subroutine finish_parse

  recursive subroutine keyword_line(st, line, loc)
    !! A keyword line: closes the current card, then opens the card it names
    !! (*INCLUDE is read at once).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(keyword_line_t) :: kw
    character(:), allocatable :: msg
    integer :: prev_mat, prev_beam_sec, prev_coupling

    call parse_keyword_line(line, kw, msg)
    if (allocated(msg)) then
       call end_card(st)
       call report_loc(st, loc, msg)
       call set_card(st, CARD_SKIP, '*', loc)
       return
    end if
    ! CalculiX and Abaqus ignore blanks in keywords (*SOLIDSECTION, *NODEPRINT)
    kw%keyword = canonical_keyword(kw%keyword)
    if (kw%keyword == 'INCLUDE') then
       call do_include(st, kw, loc)
       return
    end if
    call end_card(st)
    prev_mat = st%cur_mat
    st%cur_mat = 0
    prev_beam_sec = st%cur_beam_sec
    st%cur_beam_sec = 0
    prev_coupling = st%open_coupling
    st%open_coupling = 0
    call set_card(st, CARD_NODATA, '*'//kw%keyword, loc)
    if (.not. assembly_allows(st, kw, loc)) return
    call open_card(st, kw, loc, prev_mat, prev_beam_sec, prev_coupling)
  end subroutine keyword_line

  subroutine open_card(st, kw, loc, prev_mat, prev_beam_sec, prev_coupling)
    !! The one dispatch on the keyword: the card routine of each keyword.
    !! prev_mat, prev_beam_sec and prev_coupling are the *MATERIAL, *BEAM
    !! SECTION and *COUPLING that the previous card opened (0: none), for the
    !! cards that continue them.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: prev_mat, prev_beam_sec, prev_coupling
    select case (kw%keyword)
    case ('HEADING')
       call kw_heading(st, kw, loc)
    case ('MATERIAL')
       call kw_material(st, kw, loc)
    case ('ELASTIC')
       call kw_elastic(st, kw, loc, prev_mat)
    case ('DENSITY')
       call kw_density(st, kw, loc, prev_mat)
    case ('SUBSTRUCTURE')
       call kw_substructure(st, kw, loc)
    case ('END SUBSTRUCTURE')
       call kw_end_substructure(st, kw, loc)
    case ('NODE')
       call kw_node(st, kw, loc)
    case ('ELEMENT')
       call kw_element(st, kw, loc)
    case ('NSET', 'ELSET')
       call kw_set(st, kw, loc, kw%keyword == 'ELSET')
    case ('SOLID SECTION')
       call kw_section(st, kw, loc, SEC_SOLID)
    case ('SECTION CONTROLS')
       call kw_section_controls(st, kw, loc)
    case ('BEAM SECTION', 'BEAM GENERAL SECTION')
       call kw_section(st, kw, loc, SEC_BEAM)
    case ('SHELL SECTION')
       call kw_section(st, kw, loc, SEC_SHELL)
    case ('TRANSVERSE SHEAR STIFFNESS')
       call kw_transverse_shear(st, kw, loc, prev_beam_sec)
    case ('ORIENTATION')
       call kw_orientation(st, kw, loc)
    case ('CONTACT')
       call kw_contact(st, kw, loc)
    case ('SUPPORT')
       call kw_support(st, kw, loc)
    case ('BOUNDARY')
       call kw_boundary(st, kw, loc)
    case ('STEP')
       call kw_step(st, kw, loc)
    case ('END STEP')
       call kw_end_step(st, kw, loc)
    case ('STATIC')
       call kw_static(st, kw, loc)
    case ('SPRING')
       call kw_spring(st, kw, loc)
    case ('NODE PRINT', 'EL PRINT', 'NODE FILE', 'EL FILE', 'NODE OUTPUT', 'ELEMENT OUTPUT', 'CONTACT PRINT', &
         'CONTACT FILE', 'CONTACT OUTPUT')
       call kw_request(st, kw, loc)
    case ('CLOAD', 'DLOAD', 'DSLOAD', 'MATRIX LOAD')
       call kw_load(st, kw, loc, load_card(kw%keyword))
    case ('SURFACE')
       call kw_surface(st, kw, loc)
    case ('SECTION PRINT')
       call kw_section_print(st, kw, loc)
    case ('LOAD COMBINATION')
       call kw_load_combination(st, kw, loc)
    case ('EXPANSION')
       call kw_expansion(st, kw, loc, prev_mat)
    case ('INITIAL CONDITIONS', 'TEMPERATURE')
       call kw_temperature(st, kw, loc, prev_mat)
    case ('CONTROLS')
       call kw_controls(st, kw, loc)
    case ('OUTPUT', 'PREPRINT', 'RESTART')   ! the job cards: kw_job_output
       call kw_output(st, kw, loc)
    case ('PART', 'END PART', 'ASSEMBLY', 'END ASSEMBLY', 'INSTANCE', 'END INSTANCE')
       call kw_assembly(st, kw, loc)
    case ('CHANGE CONTACT')
       call kw_change_contact(st, kw, loc)
    case ('INTERFACE')
       call kw_interface(st, kw, loc)
    case ('EQUATION', 'TIE', 'PRE-TENSION SECTION')
       call kw_tie_or_equation(st, kw, loc)
    case ('TRANSFORM')
       call kw_transform(st, kw, loc)
    case ('COUPLING', 'KINEMATIC', 'DISTRIBUTING', 'RIGID BODY', 'MPC', 'DISTRIBUTING COUPLING')
       call kw_coupling_card(st, kw, loc, prev_coupling)
    case ('MATRIX INPUT')
       call kw_matrix_input(st, kw, loc)
    case ('SUBSTRUCTURE MATRIX OUTPUT')
       call kw_matrix_output(st, kw, loc)
    case ('NODAL THICKNESS')
       call kw_nodal_thickness(st, kw, loc)
    case ('AMPLITUDE')
       call kw_amplitude(st, kw, loc)
    case default
       if (.not. refused_card(st, kw, loc, prev_mat)) call report_loc(st, loc, 'unknown keyword *'//clip(kw%keyword))
       st%card = CARD_SKIP
    end select
  end subroutine open_card

  pure integer function load_card(keyword) result(card)
    !! The card of a load keyword: *CLOAD, *DLOAD, *DSLOAD or *MATRIX LOAD.
    character(*), intent(in) :: keyword
    select case (keyword)
    case ('CLOAD')
       card = CARD_CLOAD
    case ('DLOAD')
       card = CARD_DLOAD
    case ('DSLOAD')
       card = CARD_DSLOAD
    case default
       card = CARD_MATRIX_LOAD
    end select
  end function load_card

  subroutine kw_tie_or_equation(st, kw, loc)
    !! *EQUATION (superjoin_deck_equations), *TIE (superjoin_deck_ties) or *PRE-TENSION
    !! SECTION (superjoin_deck_pretension): exact constraints.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    if (kw%keyword == 'TIE') then
       call kw_tie(st, kw, loc)
    else if (kw%keyword == 'PRE-TENSION SECTION') then
       call kw_pretension(st, kw, loc)
    else
       call kw_equation(st, kw, loc)
    end if
  end subroutine kw_tie_or_equation

  subroutine end_card(st)
    !! Checks when a card ends (next keyword or end of input): data it needed.
    type(deck_state_t), intent(inout) :: st
    select case (st%card)
    case (CARD_ELASTIC, CARD_ORIENTATION, CARD_DENSITY, CARD_TSHEAR, CARD_TRANSFORM)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name//' needs a data line')
       call end_elastic_card(st)      ! an orthotropic or anisotropic set left incomplete
    case (CARD_SECTION)
       ! *SOLID SECTION of plane elements may omit the thickness (1, as Abaqus);
       ! the element types are known when the model is built (validate).
       if (st%card_ndata == 0 .and. st%sections(st%card_item)%kind /= SEC_SOLID .and. &
            .not. st%sections(st%card_item)%nodal_thickness) then
          call report_loc(st, st%card_loc, st%card_name//' needs a data line')
          st%sections(st%card_item)%data_ok = .false.
       end if
    case (CARD_ELEMENT)
       if (allocated(st%elem_pending)) then
          call report_loc(st, st%card_loc, '*ELEMENT: the data line '''//clip(st%elem_pending)// &
               ''' ends with a comma, but no line continues it')
          deallocate (st%elem_pending)
       end if
    case (CARD_COMBINATION)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name//' needs a data line (step, factor)')
    case (CARD_EXPANSION)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name//' needs a data line')
    case (CARD_SURFACE)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name// &
            ' needs a data line (element or elset, face)')
    case (CARD_MPC)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name//' needs a data line (BEAM, a, b)')
    case (CARD_EQUATION)
       call end_equation_card(st)
    end select
    st%card = CARD_NONE
  end subroutine end_card

  recursive subroutine do_include(st, kw, loc)
    !! *INCLUDE, INPUT=file: parses the file at once (cycles and depth checked).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: rel, path, chain, text
    logical :: found, ok
    integer :: k, j, idx
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'INPUT'], [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'INPUT', .true., rel, found)
    if (.not. found) return
    path = path_normalize(path_join(path_dirname(st%files(loc%file)%s), rel))
    do k = 0, st%depth
       if (st%norm_files(st%stack(k))%s == path) then
          chain = ''
          do j = k, st%depth
             chain = chain//st%files(st%stack(j))%s//' -> '
          end do
          call report_loc(st, loc, 'include cycle: '//chain//path)
          return
       end if
    end do
    if (st%depth >= MAX_INCLUDE_DEPTH) then
       call report_loc(st, loc, 'includes nested deeper than '//itoa(MAX_INCLUDE_DEPTH)//' levels')
       return
    end if
    call load_deck_file(st, loc, path, 'include', text, ok)
    if (.not. ok) return
    call register_file(st, path, path, idx)
    st%depth = st%depth + 1
    st%stack(st%depth) = idx
    call parse_source(st, text, idx)
    st%depth = st%depth - 1
  end subroutine do_include

  logical function card_takes_data(st, line, loc) result(takes)
    !! Whether the current card reads data lines through its routine: not
    !! when it skips them, has none (reported once) or is the heading (kept).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    takes = .false.
    select case (st%card)
    case (CARD_SKIP)
    case (CARD_NONE)
       call report_loc(st, loc, 'data line without a keyword line before it')
       st%card = CARD_SKIP
    case (CARD_NODATA)
       call report_loc(st, loc, st%card_name//' takes no data lines')
       st%card = CARD_SKIP
    case (CARD_HEADING)
       call add_heading(st, line)
    case default
       takes = .true.
    end select
  end function card_takes_data

  subroutine data_line(st, line, loc)
    !! A data line: given to the routine of the current card.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc

    if (.not. card_takes_data(st, line, loc)) return
    st%card_ndata = st%card_ndata + 1
    call split_fields(line, st%f)
    call drop_trailing_empty(st%f)
    if (allocated(st%card_amp)) call record_amp_line(st, loc)   ! AMPLITUDE= of a load or *BOUNDARY card
    select case (st%card)
    case (CARD_NODE)
       call data_node(st, line, loc)
    case (CARD_ELEMENT)
       call data_element(st, line, loc)
    case (CARD_NSET, CARD_ELSET)
       call data_set(st, line, loc, st%card == CARD_ELSET)
    case (CARD_SECTION)
       call data_section(st, line, loc)
    case (CARD_ELASTIC)
       call data_elastic(st, line, loc)
    case (CARD_DENSITY)
       call data_density(st, line, loc)
    case (CARD_TSHEAR)
       call data_transverse_shear(st, line, loc)
    case (CARD_ORIENTATION)
       call data_orientation(st, line, loc)
    case (CARD_CONTACT)
       call data_contact(st, line, loc)
    case (CARD_SUPPORT)
       call data_support(st, line, loc)
    case (CARD_BOUNDARY)
       call data_boundary(st, line, loc)
    case (CARD_CLOAD, CARD_DLOAD)
       call data_load(st, line, loc)
    case (CARD_INSTANCE)
       call data_instance(st, line, loc)
    case (CARD_CHANGE_CONTACT)
       call data_change_contact(st, line, loc)
    case (CARD_INTERFACE)
       call data_interface(st, line, loc)
    case (CARD_EQUATION)
       call data_equation(st, line, loc)
    case (CARD_TIE)
       call data_tie(st, line, loc)
    case (CARD_TRANSFORM)
       call data_transform(st, line, loc)
    case (CARD_COUPLING_DOFS)
       call data_coupling_dofs(st, line, loc)
    case (CARD_MPC)
       call data_mpc(st, line, loc)
    case (CARD_DCOUP_ELEMENT)
       call data_dcoup_element(st, line, loc)
    case (CARD_DCOUP_NODES)
       call data_dcoup_nodes(st, line, loc)
    case (CARD_NODAL_THICKNESS)
       call data_nodal_thickness(st, line, loc)
    case (CARD_STATIC)
       call data_static(st, line, loc)
    case (CARD_SPRING_ELEMENT)
       call data_spring_element(st, line, loc)
    case (CARD_SPRING)
       call data_spring(st, line, loc)
    case (CARD_REQUEST)
       call data_request(st, line, loc)
    case (CARD_COMBINATION)
       call data_combination(st, line, loc)
    case (CARD_EXPANSION)
       call data_expansion(st, line, loc)
    case (CARD_TEMPERATURE)
       call data_temperature(st, line, loc)
    case (CARD_SURFACE)
       call data_surface(st, line, loc)
    case (CARD_DSLOAD)
       call data_dsload(st, line, loc)
    case (CARD_SECTION_PRINT)
       call data_section_print(st, line, loc)
    case (CARD_PRETENSION)
       call data_pretension(st, line, loc)
    case (CARD_MATRIX_LOAD)
       call data_matrix_load(st, line, loc)
    case (CARD_AMPLITUDE)
       call data_amplitude(st, line, loc)
    end select
  end subroutine data_line
end module superjoin_deck_parser
