module superjoin_deck_cards_output
  !! Output requests: *OUTPUT and the CalculiX/Abaqus *NODE PRINT, *EL PRINT,
  !! *NODE FILE, *EL FILE, *NODE OUTPUT, *ELEMENT OUTPUT, *SECTION PRINT; and
  !! the job cards *PREPRINT and *RESTART.
  use superjoin_kinds, only: ip
  use superjoin_model_types, only: source_loc_t, TOTALS_NO, TOTALS_YES, TOTALS_ONLY, section_print_t
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, parse_id, clip, path_dirname, path_join, &
       TOK_OK
  use superjoin_deck_state, only: deck_state_t, report_loc, request_b_t, add_request, &
       add_request_var
  use superjoin_deck_ccx_cards, only: request_kind, is_node_request, classify_variable, VAR_UNKNOWN, &
       VAR_PRODUCED, variable_hint
  use superjoin_utils_strings, only: pick
  use superjoin_model_output_paths, only: vtk_path_problem
  use superjoin_model_notes, only: append_string
  use superjoin_deck_cards_common, only: check_params, param_index, get_param, fld, parse_set_ref, &
       loc_string, CARD_SKIP, CARD_REQUEST, NAME_LEN, get_name_param, CARD_SECTION_PRINT
  implicit none (type, external)
  private

  public :: kw_output, kw_request, data_request, kw_section_print, data_section_print

contains

  subroutine kw_output(st, kw, loc)
    !! *OUTPUT, VTK=path[, FIELD]: VTK files of every step, path relative to the
    !! directory of the file that holds the card. Allowed anywhere, once.
    !! *PREPRINT and *RESTART: kw_job_output.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: value, problem
    logical :: found
    if (kw%keyword /= 'OUTPUT') then
       call kw_job_output(st, kw, loc)
       return
    end if
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'VTK', 'FREQUENCY', 'VARIABLE'], &
         [character(NAME_LEN) :: 'FIELD', 'HISTORY'])
    if (param_index(kw, 'VTK') == 0 .and. (param_index(kw, 'FIELD') > 0 .or. param_index(kw, 'HISTORY') > 0)) return
    call get_param(st, kw, loc, 'VTK', .true., value, found)
    if (.not. found) return
    problem = vtk_path_problem(value)
    if (len(problem) > 0) then
       call report_loc(st, loc, problem)
    else if (allocated(st%vtk_path)) then
       call report_loc(st, loc, '*OUTPUT, VTK= given twice (first at '//loc_string(st, st%vtk_loc)//')')
    else
       st%vtk_path = path_join(path_dirname(st%files(loc%file)%s), value)
       st%vtk_loc = loc
    end if
  end subroutine kw_output

  subroutine kw_request(st, kw, loc)
    !! *NODE PRINT, *EL PRINT, *NODE FILE, *EL FILE, *NODE OUTPUT, *ELEMENT OUTPUT:
    !! NSET= or ELSET= (a set, resolved later), TOTALS=, FREQUENCY= and the
    !! CalculiX flags; the variables follow as data lines. *CONTACT PRINT,
    !! *CONTACT FILE, *CONTACT OUTPUT: kw_contact_output.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(request_b_t) :: r
    character(:), allocatable :: value, pset
    character(len=NAME_LEN) :: set_param
    logical :: found, node
    integer(ip) :: n
    integer :: stat
    st%card = CARD_SKIP
    if (index(kw%keyword, 'CONTACT ') == 1) then
       call kw_contact_output(st, kw, loc)
       return
    end if
    r%kind = request_kind(kw%keyword)
    r%card = '*'//kw%keyword
    node = is_node_request(r%kind)
    pset = pick(node, 'NSET', 'ELSET')
    set_param = pset
    call check_params(st, kw, loc, [character(NAME_LEN) :: set_param, 'TOTALS', 'FREQUENCY', 'FREQUENCYF', &
         'GLOBAL', 'OUTPUT', 'TIME POINTS', 'VARIABLE', 'DIRECTIONS', 'POSITION'], &
         [character(NAME_LEN) :: 'SECTION FORCES', 'LAST ITERATIONS', 'CONTACT ELEMENTS'])
    call get_param(st, kw, loc, 'TOTALS', .false., value, found)
    r%totals = TOTALS_NO
    if (found) then
       select case (to_upper(value))
       case ('YES')
          r%totals = TOTALS_YES
       case ('ONLY')
          r%totals = TOTALS_ONLY
       case ('NO')
          r%totals = TOTALS_NO
       case default
          call report_loc(st, loc, 'TOTALS must be YES, ONLY or NO, not '//clip(value))
       end select
    end if
    call get_param(st, kw, loc, 'GLOBAL', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('YES')
          r%global = .true.
       case ('NO')
          r%global = .false.
       case default
          call report_loc(st, loc, 'GLOBAL must be YES or NO, not '//clip(value))
       end select
    end if
    call get_param(st, kw, loc, 'FREQUENCY', .false., value, found)
    if (found .and. value /= '0') then
       call parse_id(value, n, stat)
       if (stat /= TOK_OK) call report_loc(st, loc, 'FREQUENCY= must be an integer >= 0, not '//clip(value))
    end if
    call get_param(st, kw, loc, 'VARIABLE', .false., value, found)
    if (found) then
       if (to_upper(value) /= 'PRESELECT' .and. to_upper(value) /= 'ALL') call report_loc(st, loc, &
            'VARIABLE= must be PRESELECT or ALL, not '//clip(value))
    end if
    call get_param(st, kw, loc, pset, .false., value, found)
    if (found) then
       if (.not. parse_set_ref(st, value, .not. node, st%cur_sub, loc, r%set)) return
       r%has_set = .true.
    end if
    r%step = st%cur_step
    r%loc = loc
    call add_request(st, r, st%card_item)
    st%card = CARD_REQUEST
  end subroutine kw_request

  subroutine kw_contact_output(st, kw, loc)
    !! *CONTACT PRINT, *CONTACT FILE, *CONTACT OUTPUT: CalculiX's output of its
    !! contact pairs (CDIS, CSTR, CELS, CNUM at the active slave nodes).
    !! superjoin has no contact pairs (*CONTACT PAIR is refused), so the card
    !! requests nothing: accepted, its data lines passed over, a note in the
    !! listing (superjoin's joints: the CONTACT FORCES table).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'FREQUENCY', 'TIME POINTS', 'TOTALS', 'VARIABLE', &
         'NSET', 'OUTPUT'], [character(NAME_LEN) :: 'LAST ITERATIONS', 'CONTACT ELEMENTS'])
    call append_string(st%notes, '*'//kw%keyword//' at '//loc_string(st, loc)// &
         ': CalculiX''s output of contact pairs, which the deck cannot have (*CONTACT PAIR is refused): '// &
         'nothing to write (joints: CONTACT FORCES)')
    st%card = CARD_SKIP
  end subroutine kw_contact_output

  subroutine kw_job_output(st, kw, loc)
    !! *PREPRINT (Abaqus: what its .dat file echoes of the input, YES or NO
    !! per part) and *RESTART (Abaqus, CalculiX): accepted, nothing written.
    !! WRITE asks for restart data every FREQUENCY increments (FREQUENCY=0,
    !! as Abaqus/CAE writes it into every step: none); superjoin keeps none (a
    !! linear run is repeated from its deck): a listing note when some is
    !! asked for, as for a *PREPRINT with a YES. READ (a run that continues
    !! an earlier one from its restart data) is refused: there are none.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: value
    logical :: found
    integer :: k
    st%card = CARD_SKIP
    if (kw%keyword == 'PREPRINT') then
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'CONTACT', 'ECHO', 'HISTORY', 'MASSPROP', 'MODEL', &
            'PARSUBSTRUCTURE', 'PARVARREF'], [character(NAME_LEN) ::])
       do k = 1, kw%nparam
          if (.not. kw%params(k)%has_value) cycle
          if (to_upper(kw%params(k)%value) /= 'YES') cycle
          call append_string(st%notes, '*PREPRINT at '//loc_string(st, loc)//': Abaqus''s echo of the input '// &
               'in its .dat file; superjoin does not echo the deck (the listing''s MODEL block sums it up)')
          return
       end do
       return
    end if
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'FREQUENCY', 'NUMBER INTERVAL', 'TIME MARKS', &
         'STEP', 'INC', 'ITERATION'], [character(NAME_LEN) :: 'READ', 'WRITE', 'OVERLAY', 'END STEP'])
    if (param_index(kw, 'READ') > 0) then
       call report_loc(st, loc, '*RESTART, READ continues an earlier run from its restart data, which superjoin '// &
            'does not keep: run the whole deck (a linear analysis is repeated from its deck)')
       st%restart_read = .true.   ! the deck holds only what changes: its model is not checked
       return
    end if
    if (param_index(kw, 'WRITE') == 0) then
       call report_loc(st, loc, '*RESTART needs READ or WRITE')
       return
    end if
    call get_param(st, kw, loc, 'FREQUENCY', .false., value, found)
    if (found) then
       if (len_trim(value) > 0 .and. verify(trim(value), '0') == 0) return   ! FREQUENCY=0: none asked for
    end if
    call append_string(st%notes, '*RESTART, WRITE at '//loc_string(st, loc)//': no restart data written '// &
         '(superjoin repeats a linear run from its deck)')
  end subroutine kw_job_output

  subroutine data_request(st, line, loc)
    !! Variable names of an output request, several per line.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    integer :: i, what
    associate (r => st%requests(st%card_item))
      do i = 1, st%f%n
         name = to_upper(fld(st, line, i))
         if (len(name) == 0) cycle
         what = classify_variable(r%kind, name)
         if (what == VAR_UNKNOWN) then
            call report_loc(st, loc, 'unknown output variable '''//clip(fld(st, line, i))//''' for '// &
                 r%card//' (superjoin produces '//pick(is_node_request(r%kind), 'U, RF, CF', 'S, E, SF')//')'// &
                 variable_hint(name))
         else
            call add_request_var(r, name, what == VAR_PRODUCED)
         end if
      end do
    end associate
  end subroutine data_request

  subroutine kw_section_print(st, kw, loc)
    !! *SECTION PRINT, SURFACE=surface, NAME=name: the resultant force and
    !! moment of the stresses over the faces of an element surface (CalculiX);
    !! the surface is resolved when the model is built, the variables (SOF,
    !! SOM, SOAREA) follow as data lines.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(section_print_t) :: sp
    character(:), allocatable :: value
    logical :: found
    st%card = CARD_SKIP
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'SURFACE', 'NAME', 'FREQUENCYF', 'TIME POINTS'], &
         [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'SURFACE', .true., value, found)   ! a name or I.S (an instance's copy)
    if (.not. found) return
    sp%surface = to_upper(value)
    call get_name_param(st, kw, loc, 'NAME', .true., value, found)
    if (.not. found) return
    sp%name = value
    sp%step = st%cur_step
    sp%loc = loc
    if (.not. allocated(st%section_prints)) allocate (st%section_prints(0))
    st%section_prints = [st%section_prints, sp]
    st%card = CARD_SECTION_PRINT
  end subroutine kw_section_print

  subroutine data_section_print(st, line, loc)
    !! The variables of a *SECTION PRINT: SOF, SOM, SOAREA (each asks for the
    !! whole block, as CalculiX prints it).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    integer :: i
    do i = 1, st%f%n
       name = to_upper(fld(st, line, i))
       if (len(name) == 0) cycle
       if (name /= 'SOF' .and. name /= 'SOM' .and. name /= 'SOAREA') call report_loc(st, loc, &
            'unknown output variable '''//clip(fld(st, line, i))//''' for *SECTION PRINT (SOF, SOM, SOAREA)')
    end do
  end subroutine data_section_print
end module superjoin_deck_cards_output
