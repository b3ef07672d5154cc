module superjoin_deck_parser
  !! Card-level parser of the deck reader: walks the lines of a deck (and of the
  !! files it includes), recognizes keyword and data lines and records what they
  !! define in the reader state, by user ids and names. References are resolved
  !! later, by superjoin_deck_validate.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: source_loc_t, string_t, ELEMENT_TYPE_NAMES, ELEMENT_NODE_COUNT, &
       NUM_ELEMENT_TYPES, MAX_ELEMENT_NODES, NDOF_NODE, SEC_SOLID, SEC_BEAM, SEC_SHELL, &
       LINK_NONE, LINK_FINITE, LINK_RIGID, DLOAD_PX, DLOAD_PY, DLOAD_PZ, DLOAD_P, DLOAD_GRAV, DLOAD_P1, DLOAD_CENTRIF, &
       FORM_TRANSFORM, FORM_PENALTY, RIGID_ELIMINATE, RIGID_LARGE, CONDENSE_AUTO, CONDENSE_YES, CONDENSE_NO
  use superjoin_deck_lexer, only: keyword_line_t, load_file, next_line, first_nonblank, to_upper, &
       parse_keyword_line, split_fields, drop_trailing_empty, parse_real, parse_id, is_name, &
       is_digits, looks_numeric, itoa, clip, plural, path_dirname, path_join, path_normalize, &
       TOK_OK, TOK_RANGE, TOK_NONFINITE
  use superjoin_deck_state, only: deck_state_t, sec_b_t, contact_b_t, cline_b_t, support_b_t, &
       load_b_t, ref_t, report, report_loc, report_oom, new_sub, find_sub, find_set, new_set, add_chunk, &
       override_b_t, SUBK_PART, SUBK_INSTANCE, step_b_t, combo_b_t, temp_b_t, OP_DEFAULT, OP_MOD, OP_NEW, &
       surface_b_t, &
       push_pool, add_node, add_element, add_heading, add_material, add_orientation, &
       add_section, add_contact, add_cline, add_support, add_step, add_load, &
       MAX_INCLUDE_DEPTH, CH_IDS, CH_GEN, CH_RANGE, CH_REF, BEAM_2D_VALUES, BEAM_3D_VALUES
  use superjoin_deck_state, only: request_b_t, add_request, add_request_var, grow
  use superjoin_deck_ccx_cards, only: refused_card_reason, request_kind, is_node_request, &
       classify_variable, VAR_UNKNOWN, VAR_PRODUCED
  use superjoin_model_types, only: TOTALS_NO, TOTALS_YES, TOTALS_ONLY
  use superjoin_model_types, only: ET_B32
  use superjoin_deck_beam_sections, only: section_props_t, section_properties, shape_index, SHAPE_NONE, &
       SHAPE_L, SHAPE_I, SHAPE_NAMES, SHAPE_DIMS_MIN, SHAPE_DIMS_MAX, SHAPE_DATA, MAX_SHAPE_DIMS
  use superjoin_deck_state, only: SHAPE_GENERAL
  use superjoin_elements_frame, only: real_text
  use superjoin_deck_state, only: spring_elem_b_t, spring_card_b_t, add_spring_elem, add_spring_card, &
       SPRING_1, SPRING_2, SPRING_A
  use superjoin_deck_springs, only: translate_springs
  use superjoin_utils_strings, only: pick
  use superjoin_output_vtk, only: vtk_path_problem
  use superjoin_elements_catalog, only: unsupported_type_message
  use superjoin_deck_ccx_cards, only: canonical_keyword
  implicit none (type, external)
  private

  integer, parameter :: INITIAL_COMBOS = 4         !! *LOAD COMBINATION cards before the first doubling
  integer, parameter :: INITIAL_TERMS = 4          !! terms of one combination before the first doubling
  integer, parameter :: INITIAL_TEMPERATURES = 16  !! *TEMPERATURE lines before the first doubling
  integer, parameter :: INITIAL_SURFACES = 4       !! *SURFACE cards before the first doubling

  public :: parse_source, finish_parse, register_file
  public :: outside_step, check_params, param_index, get_param, get_name_param, field_count, fld, get_real, &
       real_message, get_dof_range, get_stiffness, parse_ref, loc_string, target_sub, get_dof
    !! Card helpers, public only because the submodule superjoin_deck_parts calls
    !! them: gfortran 12 does not export private module procedures to submodules.

  integer, parameter :: CARD_NONE = 0, CARD_SKIP = 1, CARD_NODATA = 2, CARD_HEADING = 3, &
       CARD_NODE = 4, CARD_ELEMENT = 5, CARD_NSET = 6, CARD_ELSET = 7, CARD_SECTION = 8, &
       CARD_ELASTIC = 9, CARD_ORIENTATION = 10, CARD_CONTACT = 11, CARD_SUPPORT = 12, &
       CARD_BOUNDARY = 13, CARD_CLOAD = 14, CARD_DLOAD = 15, CARD_DENSITY = 16, &
       CARD_TSHEAR = 17
    !! What the current card does with data lines.
  integer, parameter :: CARD_INSTANCE = 101, CARD_CHANGE_CONTACT = 102, CARD_INTERFACE = 103
    !! Cards of parts, instances and joint studies (submodule superjoin_deck_parts).
  integer, parameter :: CARD_STATIC = 111, CARD_REQUEST = 112, CARD_SPRING_ELEMENT = 113, CARD_SPRING = 114
    !! CalculiX/Abaqus analysis cards (numbered apart from the model cards).
  integer, parameter :: CARD_COMBINATION = 131, CARD_EXPANSION = 132, CARD_TEMPERATURE = 133
    !! Load cases and combinations (superjoin's *LOAD COMBINATION).
  integer, parameter :: CARD_EQUATION = 121, CARD_TRANSFORM = 122
  integer, parameter :: CARD_NODAL_THICKNESS = 141
    !! Linear constraints and nodal systems (submodules superjoin_deck_equations, _transforms).
  integer, parameter :: PROC_STATIC = 1
    !! Procedures of a step (st%step_procedure).
  integer, parameter :: STATIC_FIELDS = 4
  integer, parameter :: GENERAL_FIELDS = 5
    !! *BEAM GENERAL SECTION, SECTION=GENERAL: A, I11, I12, I22, J.
    !! *STATIC data: initial increment, time period, minimum, maximum increment.

  character(*), parameter :: MAIN_NAME = 'MAIN'
    !! Name of the implicit substructure.
  character(*), parameter :: BOM = char(239)//char(187)//char(191)
    !! UTF-8 byte order mark, skipped at the start of a file.
  integer(i8), parameter :: MAX_LINE_LENGTH = 1073741824_i8
    !! Longest line accepted (2**30 characters): positions inside a line are
    !! default integers, so a longer line is refused rather than mis-read.
  real(wp), parameter :: NU_MIN = -1.0_wp, NU_MAX = 0.5_wp
    !! Poisson's ratio bounds (open interval).
  real(wp), parameter :: PARALLEL_TOL = 1.0e-10_wp
    !! Relative size below which orientation vectors count as zero or parallel.
  integer, parameter :: NAME_LEN = 24
  integer, parameter :: ORIENT_VALUES = 6
  integer, parameter :: NODE_FIELDS_MIN = 1, NODE_FIELDS_MAX = 7, NODE_COORD_FIELDS = 4
    !! id, x, y, z, then (Abaqus) the direction cosines of a shell normal, checked and ignored.
    !! Numbers of fields of data lines.
  integer, parameter :: GEN_FIELDS_MIN = 2, GEN_FIELDS_MAX = 3
  integer, parameter :: ELASTIC_FIELDS = 2, VECTOR_FIELDS = 3, CONTACT_FIELDS = 5, LOAD_FIELDS = 3, &
       GRAV_FIELDS = 6
  integer, parameter :: SUPPORT_FIELDS_MIN = 3, SUPPORT_FIELDS_MAX = 4
  integer, parameter :: CENTRIF_FIELDS = 9
  integer, parameter :: CARD_SURFACE = 151, CARD_DSLOAD = 152
    !! loads: *SURFACE, TYPE=ELEMENT and *DSLOAD (superjoin_deck_surfaces)
  integer, parameter :: BOUNDARY_FIELDS_MIN = 2, BOUNDARY_FIELDS_MAX = 4

  interface
    !! Parts, assembly, instances and joint studies: submodule superjoin_deck_parts (parts.f90).
     module subroutine kw_assembly(st, kw, loc)
       !! *PART, *END PART, *ASSEMBLY, *END ASSEMBLY, *INSTANCE, *END INSTANCE.
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end subroutine kw_assembly
     module logical function assembly_allows(st, kw, loc) result(ok)
       !! False (card skipped, reported) when a keyword may not stand where it stands
       !! (a load inside *PART, a card inside *INSTANCE, ...).
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end function assembly_allows
     module subroutine data_instance(st, line, loc)
       !! Data lines of *INSTANCE: translation, then rotation (Abaqus form).
       type(deck_state_t), intent(inout) :: st
       character(*), intent(in) :: line
       type(source_loc_t), intent(in) :: loc
     end subroutine data_instance
     module integer function set_home(st, kw, loc) result(isub)
       !! Substructure a *NSET/*ELSET card writes to: the instance of INSTANCE=
       !! (Abaqus assembly-level sets), else the open block or MAIN (0: reported).
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end function set_home
     module subroutine finish_assembly(st)
       !! End of input: report unclosed *PART, *INSTANCE and *ASSEMBLY blocks.
       type(deck_state_t), intent(inout) :: st
     end subroutine finish_assembly
     module subroutine contact_pair_params(st, kw, loc, c)
       !! PAIR= and TOL= of *CONTACT.
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
       type(contact_b_t), intent(inout) :: c
     end subroutine contact_pair_params
     module subroutine contact_offset_param(st, kw, loc, c)
       !! OFFSET=RIGID | NONE of *CONTACT.
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
       type(contact_b_t), intent(inout) :: c
     end subroutine contact_offset_param
     module subroutine kw_equation(st, kw, loc)
       !! *EQUATION: linear constraints between DOFs (Abaqus/CalculiX form).
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end subroutine kw_equation
     module subroutine data_equation(st, line, loc)
       !! A data line of *EQUATION: a number of terms, or node, dof, coefficient triples.
       type(deck_state_t), intent(inout) :: st
       character(*), intent(in) :: line
       type(source_loc_t), intent(in) :: loc
     end subroutine data_equation
     module subroutine end_equation_card(st)
       !! End of an *EQUATION card: the last equation must have all its terms.
       type(deck_state_t), intent(inout) :: st
     end subroutine end_equation_card
     module subroutine kw_transform(st, kw, loc)
       !! *TRANSFORM, NSET=n[, TYPE=R|C]: nodal systems (CalculiX).
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end subroutine kw_transform
     module subroutine data_transform(st, line, loc)
       !! The data line of *TRANSFORM: ax, ay, az, bx, by, bz.
       type(deck_state_t), intent(inout) :: st
       character(*), intent(in) :: line
       type(source_loc_t), intent(in) :: loc
     end subroutine data_transform
     module subroutine kw_nodal_thickness(st, kw, loc)
       !! *NODAL THICKNESS (CalculiX): shell and plane element thickness given at the nodes.
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end subroutine kw_nodal_thickness
     module subroutine data_nodal_thickness(st, line, loc)
       !! A data line of *NODAL THICKNESS: node or node set, thickness[, second thickness].
       type(deck_state_t), intent(inout) :: st
       character(*), intent(in) :: line
       type(source_loc_t), intent(in) :: loc
     end subroutine data_nodal_thickness
     module subroutine kw_interface(st, kw, loc)
       !! *INTERFACE, NAME=j, MASTER=s1, SLAVE=s2, KN=kn, KT=kt[, TOL=t].
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end subroutine kw_interface
     module subroutine data_interface(st, line, loc)
       !! The data line of *INTERFACE: master nset, slave nset.
       type(deck_state_t), intent(inout) :: st
       character(*), intent(in) :: line
       type(source_loc_t), intent(in) :: loc
     end subroutine data_interface
     module subroutine kw_change_contact(st, kw, loc)
       !! *CHANGE CONTACT, NAME=j[, G=values] inside *STEP.
       type(deck_state_t), intent(inout) :: st
       type(keyword_line_t), intent(in) :: kw
       type(source_loc_t), intent(in) :: loc
     end subroutine kw_change_contact
     module subroutine data_change_contact(st, line, loc)
       !! A data line of *CHANGE CONTACT (the form of *CONTACT's).
       type(deck_state_t), intent(inout) :: st
       character(*), intent(in) :: line
       type(source_loc_t), intent(in) :: loc
     end subroutine data_change_contact
  end interface

  integer, parameter :: NUM_BC_TYPES = 8
    !! Abaqus *BOUNDARY shorthands and the DOFs they fix.
  character(len=8), parameter :: BC_TYPE_NAMES(NUM_BC_TYPES) = ['ENCASTRE', 'PINNED  ', &
       'XSYMM   ', 'YSYMM   ', 'ZSYMM   ', 'XASYMM  ', 'YASYMM  ', 'ZASYMM  ']
  logical, parameter :: BC_TYPE_DOFS(NDOF_NODE, NUM_BC_TYPES) = reshape([ &
       .true., .true., .true., .true., .true., .true., &
       .true., .true., .true., .false., .false., .false., &
       .true., .false., .false., .false., .true., .true., &
       .false., .true., .false., .true., .false., .true., &
       .false., .false., .true., .true., .true., .false., &
       .false., .true., .true., .true., .false., .false., &
       .true., .false., .true., .false., .true., .false., &
       .true., .true., .false., .false., .false., .true.], [NDOF_NODE, NUM_BC_TYPES])

contains

  ! ================================================================== driving

  subroutine register_file(st, path, norm, k)
    !! Index of file `path` in the state's file list (added if new); `norm` is
    !! the normalized path used to detect include cycles.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: path, norm
    integer, intent(out) :: k
    integer, parameter :: INITIAL_FILES = 4
    do k = 1, st%nfile
       if (st%norm_files(k)%s == norm) return
    end do
    call grow(st%files, st%nfile, INITIAL_FILES)
    call grow(st%norm_files, st%nfile, INITIAL_FILES)
    st%nfile = st%nfile + 1
    k = st%nfile
    st%files(k)%s = path
    st%norm_files(k)%s = norm
  end subroutine register_file

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

  ! ================================================================== keyword lines

  recursive subroutine keyword_line(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(keyword_line_t) :: kw
    character(:), allocatable :: msg
    integer :: prev_mat, prev_beam_sec

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
    call set_card(st, CARD_NODATA, '*'//kw%keyword, loc)
    if (.not. assembly_allows(st, kw, loc)) return

    select case (kw%keyword)
    case ('HEADING')
       if (.not. outside_step(st, kw, loc)) return
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
       st%card = CARD_HEADING
    case ('MATERIAL')
       call kw_material(st, kw, loc)
    case ('ELASTIC')
       call kw_elastic(st, kw, loc, prev_mat)
    case ('DENSITY')
       call kw_density(st, kw, loc, prev_mat)
    case ('SUBSTRUCTURE')
       call kw_substructure(st, kw, loc)
    case ('END SUBSTRUCTURE')
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
       if (st%cur_sub == 0) then
          call report_loc(st, loc, '*END SUBSTRUCTURE without *SUBSTRUCTURE')
       else
          st%cur_sub = 0
       end if
    case ('NODE')
       call kw_node(st, kw, loc)
    case ('ELEMENT')
       call kw_element(st, kw, loc)
    case ('NSET')
       call kw_set(st, kw, loc, .false.)
    case ('ELSET')
       call kw_set(st, kw, loc, .true.)
    case ('SOLID SECTION')
       call kw_section(st, kw, loc, SEC_SOLID)
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
       if (.not. outside_step(st, kw, loc)) return
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
       st%card = CARD_SUPPORT
       st%card_home = st%cur_sub
    case ('BOUNDARY')
       call kw_boundary(st, kw, loc)
    case ('STEP')
       call kw_step(st, kw, loc)
    case ('END STEP')
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
       if (st%cur_step == 0) then
          call report_loc(st, loc, '*END STEP without *STEP')
       else
          st%cur_step = 0
       end if
    case ('STATIC')
       call kw_static(st, kw, loc)
    case ('SPRING')
       call kw_spring(st, kw, loc)
    case ('NODE PRINT', 'EL PRINT', 'NODE FILE', 'EL FILE', 'NODE OUTPUT', 'ELEMENT OUTPUT')
       call kw_request(st, kw, loc)
    case ('CLOAD')
       call kw_load(st, kw, loc, CARD_CLOAD)
    case ('DLOAD')
       call kw_load(st, kw, loc, CARD_DLOAD)
    case ('SURFACE')
       call kw_surface(st, kw, loc)
    case ('DSLOAD')
       call kw_load(st, kw, loc, CARD_DSLOAD)
    case ('LOAD COMBINATION')
       call kw_load_combination(st, kw, loc)
    case ('EXPANSION')
       call kw_expansion(st, kw, loc, prev_mat)
    case ('INITIAL CONDITIONS', 'TEMPERATURE')
       call kw_temperature(st, kw, loc, prev_mat)
    case ('CONTROLS')
       call kw_controls(st, kw, loc)
    case ('OUTPUT')
       call kw_output(st, kw, loc)
    case ('PART', 'END PART', 'ASSEMBLY', 'END ASSEMBLY', 'INSTANCE', 'END INSTANCE')
       call kw_assembly(st, kw, loc)
    case ('CHANGE CONTACT')
       call kw_change_contact(st, kw, loc)
    case ('INTERFACE')
       call kw_interface(st, kw, loc)
    case ('EQUATION')
       call kw_equation(st, kw, loc)
    case ('TRANSFORM')
       call kw_transform(st, kw, loc)
    case ('NODAL THICKNESS')
       call kw_nodal_thickness(st, kw, loc)
    case default
       if (.not. refused_card(st, kw, loc, prev_mat)) call report_loc(st, loc, 'unknown keyword *'//clip(kw%keyword))
       st%card = CARD_SKIP
    end select
  end subroutine keyword_line

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
  end subroutine set_card

  subroutine end_card(st)
    !! Checks when a card ends (next keyword or end of input): data it needed.
    type(deck_state_t), intent(inout) :: st
    select case (st%card)
    case (CARD_ELASTIC, CARD_ORIENTATION, CARD_DENSITY, CARD_TSHEAR, CARD_TRANSFORM)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name//' needs a data line')
    case (CARD_SECTION)
       ! *SOLID SECTION of plane elements may omit the thickness (1, as Abaqus);
       ! the element types are known when the model is built (validate).
       if (st%card_ndata == 0 .and. st%sections(st%card_item)%kind /= SEC_SOLID .and. &
            .not. st%sections(st%card_item)%nodal_thickness) then
          call report_loc(st, st%card_loc, st%card_name//' needs a data line')
          st%sections(st%card_item)%data_ok = .false.
       end if
    case (CARD_COMBINATION)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name//' needs a data line (step, factor)')
    case (CARD_EXPANSION)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name//' needs a data line')
    case (CARD_SURFACE)
       if (st%card_ndata == 0) call report_loc(st, st%card_loc, st%card_name// &
            ' needs a data line (element or elset, face)')
    case (CARD_EQUATION)
       call end_equation_card(st)
    end select
    st%card = CARD_NONE
  end subroutine end_card

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
       call report_loc(st, loc, 'invalid name '''//clip(value)//''' for '//name//'= (letters, digits, _ and - only)')
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

  ! ------------------------------------------------------------------ *INCLUDE

  recursive subroutine do_include(st, kw, loc)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: rel, path, chain, text
    logical :: found, ok
    integer :: k, j, idx
    integer(i8) :: need
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
    call load_file(path, text, ok, need)
    if (need > 0) then
       call report_oom(st, loc, 'reading include file '''//path//'''', need)
       return
    end if
    if (.not. ok) then
       call report_loc(st, loc, 'cannot open include file '''//path//'''')
       return
    end if
    call register_file(st, path, path, idx)
    st%depth = st%depth + 1
    st%stack(st%depth) = idx
    call parse_source(st, text, idx)
    st%depth = st%depth - 1
  end subroutine do_include

  ! ------------------------------------------------------------------ model cards

  subroutine kw_material(st, kw, loc)
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
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: mat
    character(:), allocatable :: typ
    logical :: found
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'TYPE'], [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'TYPE', .false., typ, found)
    if (found) then
       if (to_upper(typ) /= 'ISOTROPIC' .and. to_upper(typ) /= 'ISO') then
          call report_loc(st, loc, '*ELASTIC, TYPE='//clip(typ)//' is not supported: superjoin''s materials '// &
               'are isotropic (TYPE=ISO)')
          st%card = CARD_SKIP
          st%cur_mat = mat                   ! the material's next cards still find it
          if (mat > 0) st%materials(mat)%has_elastic = .true.   ! and it is not reported again as without *ELASTIC
          return
       end if
    end if
    call material_data_card(st, loc, mat, CARD_ELASTIC)
  end subroutine kw_elastic

  subroutine kw_substructure(st, kw, loc)
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

  subroutine kw_node(st, kw, loc)
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
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: typ, elset
    logical :: found
    integer :: isub, iset, k
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
    st%card_etype = 0
    do k = 1, NUM_ELEMENT_TYPES
       if (len_trim(ELEMENT_TYPE_NAMES(k)) > 0 .and. trim(ELEMENT_TYPE_NAMES(k)) == typ) st%card_etype = k
    end do
    ! CalculiX's B32R (reduced integration) is superjoin's B32, which has the
    ! reduced two-point rule (doc/verification.md, CalculiX test decks)
    if (typ == 'B32R') st%card_etype = ET_B32
    if (st%card_etype == 0) then
       call report_loc(st, loc, unsupported_type_message(clip(typ)))
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
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    logical, intent(in) :: elem
    character(:), allocatable :: name, pname
    logical :: found
    integer :: isub, iset
    if (.not. outside_step(st, kw, loc)) return
    if (elem) then
       pname = 'ELSET'
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'ELSET', 'INSTANCE'], &
            [character(NAME_LEN) :: 'GENERATE', 'UNSORTED'])
    else
       pname = 'NSET'
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'NSET', 'INSTANCE'], &
            [character(NAME_LEN) :: 'GENERATE', 'UNSORTED'])
    end if
    call get_name_param(st, kw, loc, pname, .true., name, found)
    st%card = CARD_SKIP
    if (.not. found) return
    isub = set_home(st, kw, loc)
    if (isub == 0) return
    iset = find_set(st%subs(isub), name, elem)
    if (iset == 0) call new_set(st%subs(isub), name, elem, loc, iset)
    st%card = merge(CARD_ELSET, CARD_NSET, elem)
    st%card_sub = isub
    st%card_set = iset
    st%card_generate = param_index(kw, 'GENERATE') > 0
  end subroutine kw_set

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
    call check_params(st, rest, loc, [character(NAME_LEN) :: 'ELSET', 'MATERIAL', 'OFFSET'], &
         [character(NAME_LEN) :: 'NODAL THICKNESS'])
  end function shell_section_params

  subroutine kw_section(st, kw, loc, kind)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: kind
    character(:), allocatable :: elset, material
    logical :: found_e, found_m
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
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'ELSET', 'MATERIAL', 'OFFSET'], [character(NAME_LEN) ::])
       call section_offset(st, kw, loc, kind)
    end if
    call get_param(st, kw, loc, 'ELSET', .true., elset, found_e)
    call get_name_param(st, kw, loc, 'MATERIAL', .true., material, found_m)
    st%card = CARD_SKIP
    if (.not. (found_e .and. found_m)) then
       ! one mistake: the elements it meant are not reported again as without a section
       st%section_rejected(kind) = .true.
       return
    end if
    if (.not. parse_ref(st, elset, .true., st%cur_sub, loc, sec%elset)) then
       st%section_rejected(kind) = .true.
       return
    end if
    if (.not. sec%elset%is_set) then
       call report_loc(st, loc, 'ELSET='//clip(elset)//' must name an element set')
       st%section_rejected(kind) = .true.
       return
    end if
    sec%kind = kind
    sec%material = material
    sec%loc = loc
    ! CalculiX / Abaqus: the thickness of every node comes from *NODAL THICKNESS (a data line is optional)
    sec%nodal_thickness = kind == SEC_SHELL .and. param_index(kw, 'NODAL THICKNESS') > 0
    call add_section(st, sec, st%card_item)
    st%card = CARD_SECTION
    if (kind == SEC_BEAM .or. kind == SEC_SHELL) st%cur_beam_sec = st%card_item
  end subroutine kw_section

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
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    logical :: found
    integer :: k
    logical :: cylindrical
    character(:), allocatable :: system
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'SYSTEM'], [character(NAME_LEN) ::])
    call get_name_param(st, kw, loc, 'NAME', .true., name, found)
    st%card = CARD_SKIP
    if (.not. found) return
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

  subroutine kw_contact(st, kw, loc)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(contact_b_t) :: c
    logical :: f1, f2, f3, f4
    integer :: k
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'MASTER', 'SLAVE', 'ORIENTATION', &
         'PAIR', 'TOL', 'OFFSET'], [character(NAME_LEN) ::])
    call contact_pair_params(st, kw, loc, c)
    call contact_offset_param(st, kw, loc, c)
    call get_name_param(st, kw, loc, 'NAME', .true., c%name, f1)
    call get_name_param(st, kw, loc, 'MASTER', .true., c%master, f2)
    call get_name_param(st, kw, loc, 'SLAVE', .true., c%slave, f3)
    call get_name_param(st, kw, loc, 'ORIENTATION', .false., c%orientation, f4)
    st%card = CARD_SKIP
    if (.not. (f1 .and. f2 .and. f3)) return
    do k = 1, st%ncontact
       if (st%contacts(k)%name == c%name) then
          call report_loc(st, loc, 'duplicate contact name '//c%name//' (first defined at '// &
               loc_string(st, st%contacts(k)%loc)//')')
          return
       end if
    end do
    c%loc = loc
    call add_contact(st, c, st%card_item)
    st%card = CARD_CONTACT
  end subroutine kw_contact

  subroutine kw_step(st, kw, loc)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    logical :: found
    integer :: k
    call step_params(st, kw, loc)
    if (st%cur_sub > 0) then
       call report_loc(st, loc, '*STEP inside *SUBSTRUCTURE '//st%subs(st%cur_sub)%name// &
            ' (missing *END SUBSTRUCTURE?)')
       st%cur_sub = 0
    end if
    if (st%cur_step > 0) then
       call report_loc(st, loc, '*STEP inside *STEP '//st%steps(st%cur_step)%name//' (missing *END STEP?)')
       st%cur_step = 0
    end if
    st%nstep_cards = st%nstep_cards + 1
    if (st%loose_step > 0 .and. .not. st%mix_reported) then
       call report_loc(st, loc, '*STEP cannot be mixed with loads outside *STEP (first at '// &
            loc_string(st, st%loose_loc)//')')
       st%mix_reported = .true.
    end if
    call get_name_param(st, kw, loc, 'NAME', .false., name, found)
    if (.not. found) name = itoa(st%nstep + 1)
    call add_step(st, name, loc, k)
    st%cur_step = k
    st%steps(k)%perturbation = param_index(kw, 'PERTURBATION') > 0
  end subroutine kw_step

  subroutine kw_load(st, kw, loc, card)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: card
    integer :: op
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'OP'], [character(NAME_LEN) ::])
    op = op_param(st, kw, loc)
    st%card = CARD_SKIP
    if (st%cur_step > 0) then
       st%card_item = st%cur_step
       call record_load_op(st%steps(st%cur_step), card == CARD_DLOAD .or. card == CARD_DSLOAD, op)
    else
       if (op /= OP_DEFAULT) call report_loc(st, loc, 'OP= of *'//kw%keyword//' applies inside *STEP only')
       if (st%nstep_cards > 0) then
          if (.not. st%mix_reported) call report_loc(st, loc, '*'//kw%keyword// &
               ' outside *STEP cannot be mixed with *STEP cards')
          st%mix_reported = .true.
          return
       end if
       if (st%loose_step == 0) then
          call add_step(st, '1', loc, st%loose_step)
          st%loose_loc = loc
       end if
       st%card_item = st%loose_step
    end if
    st%card = card
    st%card_home = st%cur_sub
  end subroutine kw_load

  subroutine kw_controls(st, kw, loc)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: value
    logical :: found
    real(wp) :: x
    integer :: stat
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'FORMULATION', 'RIGID', 'LARGE', &
         'POSITION TOLERANCE'], &
         [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'FORMULATION', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('TRANSFORM')
          st%controls%formulation = FORM_TRANSFORM
       case ('PENALTY')
          st%controls%formulation = FORM_PENALTY
       case default
          call report_loc(st, loc, 'FORMULATION must be TRANSFORM or PENALTY, not '//clip(value))
       end select
    end if
    call get_param(st, kw, loc, 'RIGID', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('ELIMINATE')
          st%controls%rigid = RIGID_ELIMINATE
       case ('LARGE')
          st%controls%rigid = RIGID_LARGE
       case default
          call report_loc(st, loc, 'RIGID must be ELIMINATE or LARGE, not '//clip(value))
       end select
    end if
    call get_param(st, kw, loc, 'LARGE', .false., value, found)
    if (found) then
       call parse_real(value, x, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, real_message(value, stat))
       else if (.not. (x > 1.0_wp)) then
          call report_loc(st, loc, 'LARGE must be greater than 1, not '//clip(value))
       else
          st%controls%large = x
          st%controls%large_given = .true.
       end if
    end if
    call get_param(st, kw, loc, 'POSITION TOLERANCE', .false., value, found)
    if (found) then
       call parse_real(value, x, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, real_message(value, stat))
       else if (.not. (x >= 0.0_wp)) then
          call report_loc(st, loc, 'POSITION TOLERANCE must be 0 or more, not '//clip(value))
       else
          st%controls%position_tolerance = x
       end if
    end if
  end subroutine kw_controls

  subroutine kw_output(st, kw, loc)
    !! *OUTPUT, VTK=path[, FIELD]: VTK files of every step, path relative to the
    !! directory of the file that holds the card. Allowed anywhere, once.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: value, problem
    logical :: found
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

  ! ================================================================== data lines

  subroutine data_line(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc

    select case (st%card)
    case (CARD_SKIP)
       return
    case (CARD_NONE)
       call report_loc(st, loc, 'data line without a keyword line before it')
       st%card = CARD_SKIP
       return
    case (CARD_NODATA)
       call report_loc(st, loc, st%card_name//' takes no data lines')
       st%card = CARD_SKIP
       return
    case (CARD_HEADING)
       call add_heading(st, line)
       return
    end select

    st%card_ndata = st%card_ndata + 1
    call split_fields(line, st%f)
    call drop_trailing_empty(st%f)
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
    case (CARD_TRANSFORM)
       call data_transform(st, line, loc)
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
    end select
  end subroutine data_line

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
    dot = index(tok, '.')
    if (dot > 0) then
       rest = tok(dot + 1:)
       if (.not. is_name(tok(1:dot - 1))) then
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

  subroutine data_node(st, line, loc)
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

  subroutine data_element(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer(ip) :: id, nid(MAX_ELEMENT_NODES)
    integer :: i, nn
    integer(i8) :: failed_bytes
    nn = ELEMENT_NODE_COUNT(st%card_etype)
    if (.not. field_count(st, loc, nn + 1, nn + 1, 'id and '//itoa(nn)//' nodes for type '// &
         trim(ELEMENT_TYPE_NAMES(st%card_etype)))) return
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

  subroutine data_section(st, line, loc)
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
         if (.not. field_count(st, loc, 1, 1, 'one value (area or thickness)')) then
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

  subroutine data_elastic(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: e, nu, temp
    if (st%card_ndata > 1) then
       call report_loc(st, loc, 'too many data lines for *ELASTIC')
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, ELASTIC_FIELDS, ELASTIC_FIELDS + 1, 'E, nu[, temperature]')) return
    if (.not. get_real(st, line, loc, 1, e)) return
    if (.not. get_real(st, line, loc, 2, nu)) return
    if (st%f%n > ELASTIC_FIELDS) then      ! the temperature of a one-line table: any value
       if (.not. get_real(st, line, loc, ELASTIC_FIELDS + 1, temp)) return
    end if
    if (.not. (e > 0.0_wp)) then
       call report_loc(st, loc, 'Young''s modulus E must be positive, not '//fld(st, line, 1))
       return
    end if
    if (.not. (nu > NU_MIN .and. nu < NU_MAX)) then
       call report_loc(st, loc, 'Poisson''s ratio must be between -1 and 0.5 (exclusive), not '//fld(st, line, 2))
       return
    end if
    st%materials(st%card_item)%e = e
    st%materials(st%card_item)%nu = nu
  end subroutine data_elastic

  subroutine data_density(st, line, loc)
    !! The density: one value, >= 0.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: rho
    if (st%card_ndata > 1) then
       call report_loc(st, loc, 'too many data lines for *DENSITY')
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, 1, 1, 'density')) return
    if (.not. get_real(st, line, loc, 1, rho)) return
    if (.not. (rho >= 0.0_wp)) then
       call report_loc(st, loc, 'density must not be negative, not '//fld(st, line, 1))
       return
    end if
    st%materials(st%card_item)%density = rho
  end subroutine data_density

  subroutine data_orientation(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: v(ORIENT_VALUES), a(3), b(3), e1(3), e2(3), e3(3), na, nb, n2
    integer :: i
    if (st%card_ndata > 1) then
       call report_loc(st, loc, 'too many data lines for *ORIENTATION')
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, ORIENT_VALUES, ORIENT_VALUES, 'ax, ay, az, bx, by, bz')) return
    do i = 1, ORIENT_VALUES
       if (.not. get_real(st, line, loc, i, v(i))) return
    end do
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

  subroutine data_contact(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(cline_b_t) :: c
    character(:), allocatable :: master, slave
    if (.not. field_count(st, loc, CONTACT_FIELDS, CONTACT_FIELDS, 'master, slave, first dof, last dof, g')) return
    master = st%contacts(st%card_item)%master
    slave = st%contacts(st%card_item)%slave
    if (.not. contact_ref(master, 'master', 1, c%master)) return
    if (.not. contact_ref(slave, 'slave', 2, c%slave)) return
    if (.not. get_dof_range(st, line, loc, 3, c%first, c%last)) return
    if (.not. get_stiffness(st, line, loc, 5, c%state, c%g)) return
    c%contact = st%card_item
    c%loc = loc
    call add_cline(st, c)
  contains
    logical function contact_ref(subname, role, i, ref) result(ok)
      character(*), intent(in) :: subname, role
      integer, intent(in) :: i
      type(ref_t), intent(out) :: ref
      ok = parse_ref(st, fld(st, line, i), .false., 0, loc, ref)
      if (.not. ok) return
      if (allocated(ref%scope)) then
         if (ref%scope /= subname) then
            call report_loc(st, loc, 'node '''//clip(fld(st, line, i))//''' is not in the '//role// &
                 ' substructure '//subname)
            ok = .false.
         end if
      end if
    end function contact_ref
  end subroutine data_contact

  subroutine data_support(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(support_b_t) :: s
    integer :: first, last
    if (.not. field_count(st, loc, SUPPORT_FIELDS_MIN, SUPPORT_FIELDS_MAX, 'node or nset, first dof, last dof[, g]')) return
    if (.not. parse_ref(st, fld(st, line, 1), .false., st%card_home, loc, s%ref)) return
    if (.not. get_dof_range(st, line, loc, 2, first, last)) return
    s%state = LINK_RIGID
    if (st%f%n == SUPPORT_FIELDS_MAX) then
       if (.not. get_stiffness(st, line, loc, 4, s%state, s%g)) return
       if (s%state == LINK_NONE) return
    end if
    s%dofs(first:last) = .true.
    s%loc = loc
    call add_support(st, s)
  end subroutine data_support

  subroutine data_boundary(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(support_b_t) :: s
    character(:), allocatable :: tok
    integer :: first, last, k
    if (.not. field_count(st, loc, BOUNDARY_FIELDS_MIN, BOUNDARY_FIELDS_MAX, 'node or nset, first dof[, last dof[, value]]')) return
    if (.not. parse_ref(st, fld(st, line, 1), .false., st%card_home, loc, s%ref)) return
    s%state = LINK_RIGID
    s%loc = loc
    s%step = st%card_item
    s%boundary = .true.
    tok = to_upper(fld(st, line, 2))
    if (.not. looks_numeric(tok) .and. len(tok) > 0) then
       do k = 1, NUM_BC_TYPES
          if (trim(BC_TYPE_NAMES(k)) == tok) then
             if (st%f%n /= BOUNDARY_FIELDS_MIN) then
                call report_loc(st, loc, '*BOUNDARY type '//tok//' takes no further fields')
                return
             end if
             s%dofs = BC_TYPE_DOFS(:, k)
             call add_support(st, s)
             return
          end if
       end do
       call report_loc(st, loc, 'invalid DOF '''//clip(fld(st, line, 2))//''' (1 to 6 or a *BOUNDARY type such as ENCASTRE)')
       return
    end if
    if (.not. get_dof(st, line, loc, 2, first)) return
    last = first
    if (st%f%n >= 3) then
       if (st%f%last(3) >= st%f%first(3)) then
          if (.not. get_dof(st, line, loc, 3, last)) return
       end if
    end if
    if (first > last) then
       call report_loc(st, loc, 'first DOF '//itoa(first)//' is after last DOF '//itoa(last))
       return
    end if
    if (st%f%n == BOUNDARY_FIELDS_MAX) then
       if (.not. get_real(st, line, loc, 4, s%value)) return
    end if
    s%dofs(first:last) = .true.
    call add_support(st, s)
  end subroutine data_boundary

  subroutine data_load(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(load_b_t) :: ld
    logical :: dload
    character(:), allocatable :: typ
    real(wp) :: dnorm
    integer :: k
    dload = st%card == CARD_DLOAD
    if (dload) then
       if (st%f%n >= 2) typ = to_upper(fld(st, line, 2))
       if (st%f%n >= 2 .and. typ == 'CENTRIF') then
          call data_centrif(st, line, loc)
          return
       end if
       if (st%f%n >= 2 .and. typ == 'GRAV') then
          if (.not. field_count(st, loc, GRAV_FIELDS, GRAV_FIELDS, &
               'element or elset (empty: the whole model), GRAV, acceleration, dx, dy, dz')) return
          ld%kind = DLOAD_GRAV
          do k = 1, 3
             if (.not. get_real(st, line, loc, 3 + k, ld%dir(k))) return
          end do
          dnorm = norm2(ld%dir)
          if (.not. (dnorm > 0.0_wp)) then
             call report_loc(st, loc, 'GRAV needs a nonzero direction dx, dy, dz')
             return
          end if
          ld%dir = ld%dir/dnorm
          if (.not. get_real(st, line, loc, 3, ld%value)) return
          ld%loc = loc
          if (len(fld(st, line, 1)) == 0) then
             ld%whole_model = .true.
             ld%home = st%card_home
          else
             if (.not. parse_ref(st, fld(st, line, 1), dload, st%card_home, loc, ld%ref)) return
          end if
          call add_load(st%steps(st%card_item), ld, dload)
          return
       end if
       if (.not. field_count(st, loc, LOAD_FIELDS, LOAD_FIELDS, 'element or elset, load type, value')) return
    else
       if (.not. field_count(st, loc, LOAD_FIELDS, LOAD_FIELDS, 'node or nset, dof, value')) return
    end if
    if (.not. parse_ref(st, fld(st, line, 1), dload, st%card_home, loc, ld%ref)) return
    if (dload) then
       select case (typ)
       case ('PX')
          ld%kind = DLOAD_PX
       case ('PY')
          ld%kind = DLOAD_PY
       case ('PZ')
          ld%kind = DLOAD_PZ
       case ('P')
          ld%kind = DLOAD_P
       case ('P1', 'P2', 'P3', 'P4')
          ld%kind = face_load_kind(typ)
       case default
          call report_loc(st, loc, 'unknown *DLOAD type '''//clip(fld(st, line, 2))// &
               ''' (PX, PY, PZ, P, P1 to P4, GRAV or CENTRIF)')
          return
       end select
    else
       if (.not. get_dof(st, line, loc, 2, ld%dof)) return
    end if
    if (.not. get_real(st, line, loc, 3, ld%value)) return
    ld%loc = loc
    call add_load(st%steps(st%card_item), ld, dload)
  end subroutine data_load

  subroutine data_centrif(st, line, loc)
    !! *DLOAD `elset, CENTRIF, omega^2, px, py, pz, ax, ay, az` (CalculiX): the
    !! centrifugal load of a rotation at the angular velocity omega about the
    !! axis through p along a; an empty first field loads the whole model (or
    !! the substructure block), as GRAV.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(load_b_t) :: ld
    real(wp) :: anorm
    integer :: k
    if (.not. field_count(st, loc, CENTRIF_FIELDS, CENTRIF_FIELDS, &
         'element or elset, CENTRIF, omega^2, point x, y, z, axis ax, ay, az')) return
    ld%kind = DLOAD_CENTRIF
    if (.not. get_real(st, line, loc, 3, ld%value)) return
    do k = 1, 3
       if (.not. get_real(st, line, loc, 3 + k, ld%point(k))) return
       if (.not. get_real(st, line, loc, 6 + k, ld%dir(k))) return
    end do
    anorm = norm2(ld%dir)
    if (.not. (anorm > 0.0_wp)) then
       call report_loc(st, loc, 'CENTRIF needs a nonzero axis direction ax, ay, az')
       return
    end if
    if (ld%value < 0.0_wp) then
       call report_loc(st, loc, 'CENTRIF takes omega^2, which cannot be negative')
       return
    end if
    ld%dir = ld%dir/anorm
    ld%loc = loc
    if (len(fld(st, line, 1)) == 0) then
       ld%whole_model = .true.
       ld%home = st%card_home
    else
       if (.not. parse_ref(st, fld(st, line, 1), .true., st%card_home, loc, ld%ref)) return
    end if
    call add_load(st%steps(st%card_item), ld, .true.)
  end subroutine data_centrif


  ! ================================================================== CalculiX/Abaqus analysis cards

  logical function refused_card(st, kw, loc, prev_mat) result(refused)
    !! A procedure, material behaviour or contact card that linear statics does
    !! not have: one message, its data lines skipped, and the current material
    !! kept so that the material's next cards still find it.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: prev_mat
    character(:), allocatable :: reason
    reason = refused_card_reason(kw%keyword)
    refused = len(reason) > 0
    if (.not. refused) return
    call report_loc(st, loc, 'superjoin does linear statics; *'//kw%keyword//' ('//reason// &
         ') is not supported')
    st%cur_mat = prev_mat
    if (st%cur_step > 0) then
       st%step_procedure = -1
       st%step_procedure_loc = loc
    end if
  end function refused_card

  subroutine step_params(st, kw, loc)
    !! Parameters of *STEP: NAME=, NLGEOM=NO (NLGEOM and NLGEOM=YES refused),
    !! PERTURBATION, INC=, INCF=, AMPLITUDE=RAMP|STEP; THERMAL NETWORK refused.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(keyword_line_t) :: rest
    integer :: k, stat
    integer(ip) :: n
    st%step_procedure = 0
    rest%keyword = kw%keyword
    rest%nparam = 0
    allocate (rest%params(max(kw%nparam, 1)))
    do k = 1, kw%nparam
       associate (p => kw%params(k))
         select case (p%name)
         case ('NLGEOM')
            if (.not. p%has_value) then
               call report_loc(st, loc, 'superjoin does linear statics; *STEP, NLGEOM (geometric '// &
                    'nonlinearity) is not supported (NLGEOM=NO is accepted)')
            else if (to_upper(p%value) == 'YES') then
               call report_loc(st, loc, 'superjoin does linear statics; *STEP, NLGEOM=YES (geometric '// &
                    'nonlinearity) is not supported (NLGEOM=NO is accepted)')
            else if (to_upper(p%value) /= 'NO') then
               call report_loc(st, loc, 'NLGEOM must be YES or NO, not '//clip(p%value))
            end if
         case ('INC', 'INCF')
            if (.not. p%has_value) then
               call report_loc(st, loc, 'parameter '//p%name//' of *STEP needs a value ('//p%name//'=...)')
            else
               call parse_id(p%value, n, stat)
               if (stat /= TOK_OK) call report_loc(st, loc, p%name//'= of *STEP must be a positive '// &
                    'integer, not '//clip(p%value))
            end if
         case ('AMPLITUDE')
            if (.not. p%has_value) then
               call report_loc(st, loc, 'parameter AMPLITUDE of *STEP needs a value (AMPLITUDE=...)')
            else if (to_upper(p%value) /= 'RAMP' .and. to_upper(p%value) /= 'STEP') then
               call report_loc(st, loc, 'AMPLITUDE= of *STEP must be RAMP or STEP, not '//clip(p%value))
            end if
         case ('THERMAL NETWORK')
            call report_loc(st, loc, 'superjoin does linear statics; *STEP, THERMAL NETWORK (heat '// &
                 'transfer) is not supported')
         case default
            rest%nparam = rest%nparam + 1
            rest%params(rest%nparam) = p
         end select
       end associate
    end do
    call check_params(st, rest, loc, [character(NAME_LEN) :: 'NAME'], [character(NAME_LEN) :: 'PERTURBATION'])
  end subroutine step_params

  subroutine kw_static(st, kw, loc)
    !! *STATIC inside *STEP: linear statics, superjoin's only procedure. The
    !! optional data line (increments and time period) is checked and ignored:
    !! a linear static step has one increment.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    st%card = CARD_SKIP
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'SOLVER'], &
         [character(NAME_LEN) :: 'DIRECT', 'TIME RESET', 'EXPLICIT'])
    if (param_index(kw, 'EXPLICIT') > 0) then
       call report_loc(st, loc, 'superjoin does linear statics; *STATIC, EXPLICIT is not supported')
       return
    end if
    if (st%cur_step == 0) then
       call report_loc(st, loc, '*STATIC must stand inside *STEP')
       return
    end if
    if (st%step_procedure /= 0) then
       call report_loc(st, loc, 'a step has one procedure: *STATIC after the one at '// &
            loc_string(st, st%step_procedure_loc))
       return
    end if
    st%step_procedure = PROC_STATIC
    st%step_procedure_loc = loc
    st%steps(st%cur_step)%has_procedure = .true.
    st%card = CARD_STATIC
  end subroutine kw_static

  subroutine data_static(st, line, loc)
    !! initial increment, time period, minimum increment, maximum increment:
    !! each optional, a real > 0 when given.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer :: i
    real(wp) :: x
    if (st%card_ndata > 1) then
       call report_loc(st, loc, 'too many data lines for *STATIC')
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, 0, STATIC_FIELDS, &
         'initial increment, time period, minimum increment, maximum increment')) return
    do i = 1, st%f%n
       if (st%f%last(i) < st%f%first(i)) cycle
       if (.not. get_real(st, line, loc, i, x)) return
       if (.not. (x > 0.0_wp)) then
          call report_loc(st, loc, '*STATIC increments and time period must be positive, not '//fld(st, line, i))
          return
       end if
    end do
  end subroutine data_static

  subroutine kw_request(st, kw, loc)
    !! *NODE PRINT, *EL PRINT, *NODE FILE, *EL FILE, *NODE OUTPUT, *ELEMENT OUTPUT:
    !! NSET= or ELSET= (a set, resolved later), TOTALS=, FREQUENCY= and the
    !! CalculiX flags; the variables follow as data lines.
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
       if (.not. parse_ref(st, value, .not. node, st%cur_sub, loc, r%set)) return
       if (.not. r%set%is_set) then
          call report_loc(st, loc, pset//'='//clip(value)//' must name a '//pick(node, 'node', 'element')//' set')
          return
       end if
       r%has_set = .true.
    end if
    r%step = st%cur_step
    r%loc = loc
    call add_request(st, r, st%card_item)
    st%card = CARD_REQUEST
  end subroutine kw_request

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
                 r%card//' (superjoin produces '//pick(is_node_request(r%kind), 'U, RF, CF', 'S, E, SF')//')')
         else
            call add_request_var(r, name, what == VAR_PRODUCED)
         end if
      end do
    end associate
  end subroutine data_request

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
         [character(NAME_LEN) :: 'LUMPED', 'ROTARY INERTIA'])
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
    character(:), allocatable :: problem, expected
    integer :: i, nmin, nmax
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
      do i = 1, st%f%n
         if (.not. get_real(st, line, loc, i, d(i))) then
            sec%data_ok = .false.
            return
         end if
      end do
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
      call section_properties(sec%shape, d(1:st%f%n), p, problem)
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
    st%card_sub = target_sub(st, loc)
    st%card_etype = kind
  end subroutine kw_spring_element

  subroutine data_spring_element(st, line, loc)
    !! id, node (SPRING1) or id, node 1, node 2 (SPRING2, SPRINGA).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(spring_elem_b_t) :: e
    integer :: nn, i
    nn = merge(1, 2, st%card_etype == SPRING_1)
    if (.not. field_count(st, loc, nn + 1, nn + 1, 'id and '//itoa(nn)//' node'//pick(nn == 1, '', 's')// &
         ' for a spring')) return
    if (.not. get_id(st, line, loc, 1, 'element id', e%id)) return
    do i = 1, nn
       if (.not. get_id(st, line, loc, i + 1, 'node id', e%nid(i))) return
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
    c%sub = target_sub(st, loc)
    c%loc = loc
    call add_spring_card(st, c, st%card_item)
    if (.not. c%refused) st%card = CARD_SPRING
  end subroutine kw_spring

  subroutine data_spring(st, line, loc)
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer :: i
    associate (c => st%spring_cards(st%card_item))
      if (st%card_ndata > 2) then
         call report_loc(st, loc, 'too many data lines for *SPRING (DOF line, stiffness line)')
         st%card = CARD_SKIP
         return
      end if
      if (.not. field_count(st, loc, 1, 2, 'DOF(s) or stiffness')) return
      do i = 1, st%f%n
         if (.not. get_real(st, line, loc, i, c%v(i, st%card_ndata))) return
      end do
      c%ndata = st%card_ndata
      c%nfield(st%card_ndata) = st%f%n
      c%data_loc(st%card_ndata) = loc
    end associate
  end subroutine data_spring

  ! ================================================================== step history (OP=)

  subroutine kw_boundary(st, kw, loc)
    !! *BOUNDARY[, OP=MOD|NEW]: model data, or inside *STEP the step's own
    !! boundary conditions (Abaqus/CalculiX history: later steps keep them;
    !! OP=NEW removes every earlier *BOUNDARY condition, model data included).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer :: op
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'OP'], [character(NAME_LEN) ::])
    op = op_param(st, kw, loc)
    st%card = CARD_BOUNDARY
    st%card_home = st%cur_sub
    st%card_item = st%cur_step
    if (st%cur_step > 0) then
       st%steps(st%cur_step)%has_boundary = .true.
       st%steps(st%cur_step)%bc_op = max(st%steps(st%cur_step)%bc_op, op)
    else if (op /= OP_DEFAULT) then
       call report_loc(st, loc, 'OP= of *BOUNDARY applies inside *STEP only')
    end if
  end subroutine kw_boundary

  integer function op_param(st, kw, loc) result(op)
    !! OP= of a *BOUNDARY, *CLOAD, *DLOAD or *TEMPERATURE card: OP_MOD, OP_NEW or OP_DEFAULT
    !! (not written; a wrong value is reported).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer :: k
    op = OP_DEFAULT
    k = param_index(kw, 'OP')
    if (k == 0) return
    if (.not. kw%params(k)%has_value) return   ! reported by check_params
    select case (to_upper(kw%params(k)%value))
    case ('MOD')
       op = OP_MOD
    case ('NEW')
       op = OP_NEW
    case default
       call report_loc(st, loc, 'OP= of *'//kw%keyword//' must be MOD or NEW, not '//clip(kw%params(k)%value))
    end select
  end function op_param

  pure integer function face_load_kind(typ) result(kind)
    !! DLOAD_P1 .. DLOAD_P4 of the *DLOAD type 'P1' .. 'P4'.
    character(*), intent(in) :: typ
    kind = DLOAD_P1 + index('1234', typ(2:2)) - 1
  end function face_load_kind

  pure subroutine record_load_op(step, dload, op)
    !! Remember OP= of a load card of a step (NEW wins over MOD).
    type(step_b_t), intent(inout) :: step
    logical, intent(in) :: dload
    integer, intent(in) :: op
    if (dload) then
       step%dload_op = max(step%dload_op, op)
    else
       step%cload_op = max(step%cload_op, op)
    end if
  end subroutine record_load_op

  ! ================================================================== load combinations

  subroutine kw_load_combination(st, kw, loc)
    !! *LOAD COMBINATION, NAME=c (superjoin): outside *STEP; data lines
    !! `step, factor` (step by name or position).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    logical :: found
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME'], [character(NAME_LEN) ::])
    call get_name_param(st, kw, loc, 'NAME', .true., name, found)
    if (.not. found) return
    call grow(st%combos, st%ncombo, INITIAL_COMBOS)
    st%ncombo = st%ncombo + 1
    st%combos(st%ncombo)%name = name
    st%combos(st%ncombo)%loc = loc
    st%card = CARD_COMBINATION
    st%card_item = st%ncombo
  end subroutine kw_load_combination

  subroutine data_combination(st, line, loc)
    !! A data line of *LOAD COMBINATION: step (name or position), factor.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: factor
    if (.not. field_count(st, loc, 2, 2, 'step, factor')) return
    if (len(fld(st, line, 1)) == 0) then
       call report_loc(st, loc, 'empty step name on *LOAD COMBINATION data line')
       return
    end if
    if (.not. get_real(st, line, loc, 2, factor)) return
    associate (c => st%combos(st%card_item))
      call grow(c%steps, c%n, INITIAL_TERMS)
      call grow(c%factors, c%n, INITIAL_TERMS)
      call grow(c%line_loc, c%n, INITIAL_TERMS)
      c%n = c%n + 1
      c%steps(c%n)%s = to_upper(fld(st, line, 1))
      c%factors(c%n) = factor
      c%line_loc(c%n) = loc
    end associate
  end subroutine data_combination

  ! ================================================================== temperature

  subroutine kw_expansion(st, kw, loc, mat)
    !! *EXPANSION[, TYPE=ISO][, ZERO=t] of the current material: one data line
    !! alpha[, temperature] (a constant coefficient, so ZERO= changes nothing).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: mat
    character(:), allocatable :: typ
    logical :: found
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
    st%cur_mat = mat
    st%card = CARD_EXPANSION
    st%card_item = mat
  end subroutine kw_expansion

  subroutine data_expansion(st, line, loc)
    !! The expansion coefficient: alpha[, temperature]; one line (a coefficient
    !! that depends on temperature is refused).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: alpha
    if (st%card_ndata > 1) then
       call report_loc(st, loc, 'superjoin takes one *EXPANSION line (a coefficient that depends on '// &
            'temperature is not supported)')
       st%card = CARD_SKIP
       return
    end if
    if (.not. field_count(st, loc, 1, 2, 'alpha[, temperature]')) return
    if (.not. get_real(st, line, loc, 1, alpha)) return
    st%materials(st%card_item)%alpha = alpha
  end subroutine data_expansion

  subroutine kw_temperature(st, kw, loc, prev_mat)
    !! *INITIAL CONDITIONS, TYPE=TEMPERATURE (model data) and *TEMPERATURE[,
    !! OP=MOD|NEW] (inside *STEP): data lines `node or nset, temperature`.
    !! Other TYPE= of *INITIAL CONDITIONS are refused as before.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: prev_mat
    character(:), allocatable :: typ
    logical :: found
    st%card = CARD_SKIP
    if (kw%keyword == 'INITIAL CONDITIONS') then
       call get_param(st, kw, loc, 'TYPE', .false., typ, found)
       if (.not. found) typ = ''
       if (to_upper(typ) /= 'TEMPERATURE') then
          if (refused_card(st, kw, loc, prev_mat)) return
       end if
       if (.not. outside_step(st, kw, loc)) return
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'TYPE'], [character(NAME_LEN) ::])
       st%card_item = 0
    else
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'OP'], [character(NAME_LEN) ::])
       if (st%cur_step == 0) then
          call report_loc(st, loc, '*TEMPERATURE stands inside *STEP (the initial temperatures: '// &
               '*INITIAL CONDITIONS, TYPE=TEMPERATURE)')
          return
       end if
       st%card_item = st%cur_step
       st%steps(st%cur_step)%temp_op = max(st%steps(st%cur_step)%temp_op, op_param(st, kw, loc))
    end if
    st%card = CARD_TEMPERATURE
    st%card_home = st%cur_sub
  end subroutine kw_temperature

  subroutine data_temperature(st, line, loc)
    !! `node or nset, temperature[, gradient[, gradient 1]]`: CalculiX's third
    !! field, the temperature gradient along the normal of a shell or along a
    !! beam's 2-direction, and its fourth, the gradient along a beam's
    !! 1-direction.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(temp_b_t) :: t
    if (.not. field_count(st, loc, 2, 4, 'node or nset, temperature[, gradient[, gradient 1]]')) return
    if (.not. parse_ref(st, fld(st, line, 1), .false., st%card_home, loc, t%ref)) return
    if (.not. get_real(st, line, loc, 2, t%value)) return
    if (st%f%n >= 3) then
       if (.not. get_real(st, line, loc, 3, t%grad)) return
    end if
    if (st%f%n == 4) then
       if (.not. get_real(st, line, loc, 4, t%grad1)) return
    end if
    t%step = st%card_item
    t%loc = loc
    call grow(st%temps, st%ntemp, INITIAL_TEMPERATURES)
    st%ntemp = st%ntemp + 1
    st%temps(st%ntemp) = t
  end subroutine data_temperature

  ! ================================================================== surfaces

  subroutine kw_surface(st, kw, loc)
    !! *SURFACE, NAME=name[, TYPE=ELEMENT]: element faces for *DSLOAD; data
    !! lines `element or elset, face`. Node surfaces (TYPE=NODE), which only
    !! contact and ties use, are refused.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name, typ
    logical :: found
    integer :: k
    st%card = CARD_SKIP
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'TYPE'], [character(NAME_LEN) ::])
    if (.not. outside_step(st, kw, loc)) return
    call get_param(st, kw, loc, 'TYPE', .false., typ, found)
    if (found) then
       if (to_upper(typ) /= 'ELEMENT') then
          call report_loc(st, loc, '*SURFACE, TYPE='//clip(typ)//' is not supported (element faces, '// &
               'TYPE=ELEMENT, for *DSLOAD)')
          return
       end if
    end if
    call get_param(st, kw, loc, 'NAME', .true., name, found)
    if (.not. found) return
    name = to_upper(name)
    do k = 1, st%nsurface
       if (st%surfaces(k)%name == name) then
          call report_loc(st, loc, 'surface '//name//' is already defined (at '// &
               loc_string(st, st%surfaces(k)%loc)//')')
          return
       end if
    end do
    call grow(st%surfaces, st%nsurface, INITIAL_SURFACES)
    st%nsurface = st%nsurface + 1
    st%surfaces(st%nsurface)%name = name
    st%surfaces(st%nsurface)%loc = loc
    allocate (st%surfaces(st%nsurface)%refs(0), st%surfaces(st%nsurface)%kinds(0), st%surfaces(st%nsurface)%signs(0))
    st%card = CARD_SURFACE
    st%card_item = st%nsurface
    st%card_home = st%cur_sub
  end subroutine kw_surface

  subroutine data_surface(st, line, loc)
    !! `element or elset, face`: S1 to S4, the edges of a plane element
    !! (CalculiX's faces, as P1 to P4 of *DLOAD), SPOS or SNEG, the face of a
    !! shell along or against its normal.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(ref_t) :: ref
    character(:), allocatable :: face
    integer :: kind
    real(wp) :: sgn
    if (.not. field_count(st, loc, 2, 2, 'element or elset, face (S1 to S4, SPOS or SNEG)')) return
    face = to_upper(fld(st, line, 2))
    sgn = 1.0_wp
    select case (face)
    case ('S1', 'S2', 'S3', 'S4')
       kind = face_load_kind('P'//face(2:2))
    case ('SPOS')
       kind = DLOAD_P
    case ('SNEG')
       kind = DLOAD_P
       sgn = -1.0_wp
    case default
       call report_loc(st, loc, 'unknown face '''//clip(fld(st, line, 2))// &
            ''' (S1 to S4: edges of plane elements; SPOS, SNEG: faces of shells)')
       return
    end select
    if (.not. parse_ref(st, fld(st, line, 1), .true., st%card_home, loc, ref)) return
    associate (sf => st%surfaces(st%card_item))
      sf%n = sf%n + 1
      sf%refs = [sf%refs, ref]
      sf%kinds = [sf%kinds, kind]
      sf%signs = [sf%signs, sgn]
    end associate
  end subroutine data_surface

  subroutine data_dsload(st, line, loc)
    !! *DSLOAD `surface, P, pressure`: the pressure on every face of an
    !! element surface, as *DLOAD Pk (plane edges) or P (shells, SNEG with the
    !! sign turned) on its elements.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(load_b_t) :: ld
    character(:), allocatable :: name
    real(wp) :: p
    integer :: k, i
    if (.not. field_count(st, loc, LOAD_FIELDS, LOAD_FIELDS, 'surface, P, pressure')) return
    if (to_upper(fld(st, line, 2)) /= 'P') then
       call report_loc(st, loc, 'unknown *DSLOAD type '''//clip(fld(st, line, 2))//''' (P, a uniform pressure)')
       return
    end if
    if (.not. get_real(st, line, loc, 3, p)) return
    name = to_upper(fld(st, line, 1))
    do k = 1, st%nsurface
       if (st%surfaces(k)%name == name) exit
    end do
    if (k > st%nsurface) then
       call report_loc(st, loc, 'unknown surface '''//clip(fld(st, line, 1))//''' (define it with *SURFACE, '// &
            'TYPE=ELEMENT before the step)')
       return
    end if
    do i = 1, st%surfaces(k)%n
       ld%ref = st%surfaces(k)%refs(i)
       ld%kind = st%surfaces(k)%kinds(i)
       ld%value = st%surfaces(k)%signs(i)*p
       ld%surface = .true.
       ld%loc = loc
       call add_load(st%steps(st%card_item), ld, .true.)
    end do
  end subroutine data_dsload

  function loc_string(st, loc) result(s)
    !! "file:line" of a location.
    type(deck_state_t), intent(in) :: st
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: s
    s = st%files(loc%file)%s//':'//itoa(loc%line)
  end function loc_string
end module superjoin_deck_parser
