module superjoin_deck_cards_steps
  !! Steps and loads: *STEP, *END STEP, *STATIC, *CONTROLS, *BOUNDARY, *CLOAD,
  !! *DLOAD, *SURFACE, *DSLOAD, *LOAD COMBINATION and *TEMPERATURE (also
  !! *INITIAL CONDITIONS, TYPE=TEMPERATURE).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: source_loc_t, NDOF_NODE, LINK_RIGID, DLOAD_PX, DLOAD_PY, &
       DLOAD_PZ, DLOAD_P, DLOAD_GRAV, DLOAD_P1, DLOAD_CENTRIF, DLOAD_BX, FORM_TRANSFORM, FORM_PENALTY, DLOAD_P5, DLOAD_P6, &
       DLOAD_TRVEC, DLOAD_TRSHR, RIGID_ELIMINATE, RIGID_LARGE, DIALECT_ABAQUS, DIALECT_CALCULIX
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, parse_real, parse_id, looks_numeric, &
       itoa, clip, TOK_OK
  use superjoin_deck_state, only: deck_state_t, support_b_t, load_b_t, ref_t, report_loc, step_b_t, &
       temp_b_t, surface_b_t, OP_DEFAULT, OP_MOD, OP_NEW, add_support, add_step, add_load, grow
  use superjoin_deck_part_copies, only: instance_surface
  use superjoin_deck_cards_common, only: outside_step, check_params, param_index, get_param, &
       get_name_param, field_count, fld, get_real, real_message, get_dof, parse_ref, loc_string, &
       refused_card, CARD_SKIP, CARD_BOUNDARY, CARD_DLOAD, CARD_STATIC, CARD_COMBINATION, &
       CARD_TEMPERATURE, NAME_LEN, LOAD_FIELDS, GRAV_FIELDS, CARD_SURFACE, CARD_DSLOAD
  use superjoin_deck_matrix_loads, only: CARD_MATRIX_LOAD
  use superjoin_model_notes, only: append_string
  use superjoin_deck_amplitudes, only: amplitude_param
  use superjoin_elements_traits, only: dload_face
  implicit none (type, external)
  private

  integer, parameter :: TRACTION_FIELDS = 6
    !! surface, TRVEC or TRSHR, magnitude, dx, dy, dz

  public :: kw_step, kw_end_step, kw_static, data_static, kw_controls, kw_boundary, data_boundary, &
       kw_load, data_load, kw_surface, data_surface, data_dsload, kw_load_combination, &
       data_combination, kw_temperature, data_temperature

  integer, parameter :: INITIAL_COMBOS = 4         !! *LOAD COMBINATION cards before the first doubling
  integer, parameter :: INITIAL_TERMS = 4          !! terms of one combination before the first doubling
  integer, parameter :: INITIAL_TEMPERATURES = 16  !! *TEMPERATURE lines before the first doubling
  integer, parameter :: INITIAL_SURFACES = 4       !! *SURFACE cards before the first doubling
  integer, parameter :: PROC_STATIC = 1
    !! Procedures of a step (st%step_procedure).
  integer, parameter :: STATIC_FIELDS = 4, STATIC_PERIOD = 2
    !! *STATIC data: initial increment, time period, minimum, maximum increment.
  integer, parameter :: CENTRIF_FIELDS = 9
  integer, parameter :: BOUNDARY_FIELDS_MIN = 2, BOUNDARY_FIELDS_MAX = 4
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

  subroutine kw_step(st, kw, loc)
    !! *STEP[, NAME=s, ...]: opens a step.
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

  subroutine kw_end_step(st, kw, loc)
    !! *END STEP: closes the open *STEP.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    if (st%cur_step == 0) then
       call report_loc(st, loc, '*END STEP without *STEP')
    else
       st%cur_step = 0
    end if
  end subroutine kw_end_step

  subroutine kw_static(st, kw, loc)
    !! *STATIC inside *STEP: linear statics, superjoin's only procedure. The
    !! optional data line (increments and time period) is checked: a linear
    !! static step has one increment, at the end of its time period, where
    !! amplitudes take their value (TIME RESET: the total time does not advance).
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
    st%steps(st%cur_step)%time_reset = param_index(kw, 'TIME RESET') > 0
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
       if (i == STATIC_PERIOD .and. st%cur_step > 0) st%steps(st%cur_step)%period = x   ! amplitudes' time
    end do
  end subroutine data_static

  subroutine kw_controls(st, kw, loc)
    !! *CONTROLS: link formulation, rigid links and condensation of the run, and
    !! the dialect whose reading holds where Abaqus and CalculiX differ.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: value
    logical :: found
    real(wp) :: x
    integer :: stat
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'FORMULATION', 'RIGID', 'LARGE', &
         'POSITION TOLERANCE', 'DIALECT'], &
         [character(NAME_LEN) ::])
    call choose(st, kw, loc, 'FORMULATION', [character(9) :: 'TRANSFORM', 'PENALTY'], &
         [FORM_TRANSFORM, FORM_PENALTY], st%controls%formulation)
    call choose(st, kw, loc, 'RIGID', [character(9) :: 'ELIMINATE', 'LARGE'], [RIGID_ELIMINATE, RIGID_LARGE], &
         st%controls%rigid)
    call choose(st, kw, loc, 'DIALECT', [character(8) :: 'ABAQUS', 'CALCULIX'], [DIALECT_ABAQUS, DIALECT_CALCULIX], &
         st%controls%dialect)
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

  subroutine choose(st, kw, loc, name, words, codes, code)
    !! A parameter NAME=word of a keyword line that takes one of `words`:
    !! code becomes the matching codes(i); another word is reported and code
    !! is left as it was, and so is it when the parameter is absent.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: name, words(:)
    integer, intent(in) :: codes(:)
    integer, intent(inout) :: code
    character(:), allocatable :: value, list
    logical :: found
    integer :: i
    call get_param(st, kw, loc, name, .false., value, found)
    if (.not. found) return
    do i = 1, size(words)
       if (to_upper(value) == trim(words(i))) then
          code = codes(i)
          return
       end if
    end do
    list = trim(words(1))
    do i = 2, size(words) - 1
       list = list//', '//trim(words(i))
    end do
    if (size(words) > 1) list = list//' or '//trim(words(size(words)))
    call report_loc(st, loc, name//' must be '//list//', not '//clip(value))
  end subroutine choose

  subroutine kw_boundary(st, kw, loc)
    !! *BOUNDARY[, OP=MOD|NEW][, FIXED][, AMPLITUDE=a]: model data, or inside *STEP the step's own
    !! boundary conditions (Abaqus/CalculiX history: later steps keep them;
    !! OP=NEW removes every earlier *BOUNDARY condition, model data included).
    !! FIXED (Abaqus, CalculiX): its DOFs held at their displacements at the end
    !! of the previous step (0 in the first step and in model data).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer :: op
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'OP', 'AMPLITUDE'], [character(NAME_LEN) :: 'FIXED'])
    op = op_param(st, kw, loc)
    st%card = CARD_BOUNDARY
    st%card_fixed = param_index(kw, 'FIXED') > 0
    call amplitude_param(st, kw, loc)
    st%card_home = st%cur_sub
    st%card_item = st%cur_step
    if (st%cur_step > 0) then
       st%steps(st%cur_step)%has_boundary = .true.
       st%steps(st%cur_step)%bc_op = max(st%steps(st%cur_step)%bc_op, op)
    else if (op /= OP_DEFAULT) then
       call report_loc(st, loc, 'OP= of *BOUNDARY applies inside *STEP only')
    end if
  end subroutine kw_boundary

  subroutine data_boundary(st, line, loc)
    !! A data line of *BOUNDARY: node, first DOF[, last DOF[, value]] or node, shorthand.
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
    s%held = st%card_fixed
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
       if (s%held) then   ! Abaqus and ccx 2.20 pass over it (measured): said, not silent
          call append_string(st%notes, '*BOUNDARY, FIXED at '//loc_string(st, loc)//': the value '// &
               clip(fld(st, line, 4))//' is not read; the DOFs are held at their displacements at the '// &
               'end of the previous step (as Abaqus and CalculiX do)')
          s%value = 0.0_wp
       end if
    end if
    s%dofs(first:last) = .true.
    call add_support(st, s)
  end subroutine data_boundary

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

  subroutine kw_load(st, kw, loc, card)
    !! *CLOAD, *DLOAD, *DSLOAD or *MATRIX LOAD (card): opens a load card of the current step.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: card
    integer :: op
    if (card == CARD_DSLOAD) then
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'OP', 'AMPLITUDE', 'FOLLOWER', 'CONSTANT RESULTANT'], &
            [character(NAME_LEN) ::])
       call reference_only_param(st, kw, loc, 'FOLLOWER')
       call reference_only_param(st, kw, loc, 'CONSTANT RESULTANT')
    else
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'OP', 'AMPLITUDE'], [character(NAME_LEN) ::])
    end if
    op = op_param(st, kw, loc)
    st%card = CARD_SKIP
    if (card == CARD_MATRIX_LOAD .and. param_index(kw, 'AMPLITUDE') > 0) then
       call report_loc(st, loc, 'AMPLITUDE= of *MATRIX LOAD is not supported (a condensed load has its magnitude)')
    else
       call amplitude_param(st, kw, loc)
    end if
    if (st%cur_step > 0) then
       st%card_item = st%cur_step
       if (card == CARD_MATRIX_LOAD) then
          st%steps(st%cur_step)%mload_op = max(st%steps(st%cur_step)%mload_op, op)
       else
          call record_load_op(st%steps(st%cur_step), card == CARD_DLOAD .or. card == CARD_DSLOAD, op)
       end if
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

  subroutine reference_only_param(st, kw, loc, name)
    !! FOLLOWER= or CONSTANT RESULTANT= of an Abaqus *DSLOAD (Abaqus/CAE writes
    !! them with its surface tractions): YES or NO. In a linear analysis the
    !! loads act on the undeformed surface whatever they say, so both are read
    !! and change nothing.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: name
    character(:), allocatable :: value
    logical :: found
    call get_param(st, kw, loc, name, .false., value, found)
    if (.not. found) return
    select case (to_upper(value))
    case ('YES', 'NO')
    case default
       call report_loc(st, loc, name//' must be YES or NO, not '//clip(value))
    end select
  end subroutine reference_only_param

  subroutine data_load(st, line, loc)
    !! A data line of *CLOAD or *DLOAD.
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
       case ('P1', 'P2', 'P3', 'P4', 'P5', 'P6')
          ld%kind = face_load_kind(typ)
       case ('BX', 'BY', 'BZ')   ! Abaqus's body force per unit volume along a global axis
          ld%kind = DLOAD_BX + index('XYZ', typ(2:2)) - 1
          ld%dir = 0.0_wp
          ld%dir(ld%kind - DLOAD_BX + 1) = 1.0_wp
       case default
          call report_loc(st, loc, unknown_dload(clip(fld(st, line, 2)), typ))
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

  pure integer function face_load_kind(typ) result(kind)
    !! DLOAD_P1 .. DLOAD_P6 of the *DLOAD type 'P1' .. 'P6'.
    character(*), intent(in) :: typ
    kind = DLOAD_P1 + index('1234', typ(2:2)) - 1
    if (typ(2:2) == '5') kind = DLOAD_P5
    if (typ(2:2) == '6') kind = DLOAD_P6
  end function face_load_kind

  subroutine kw_surface(st, kw, loc)
    !! *SURFACE, NAME=name[, TYPE=ELEMENT]: element faces for *DSLOAD and
    !! *TIE; data lines `element or elset, face`. TYPE=NODE: nodes or node
    !! sets, one per data line (the slave side of a *TIE).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name, typ
    logical :: found, nodal
    integer :: k
    st%card = CARD_SKIP
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'TYPE'], [character(NAME_LEN) ::])
    if (.not. outside_step(st, kw, loc)) return
    call get_param(st, kw, loc, 'TYPE', .false., typ, found)
    nodal = .false.
    if (found) then
       nodal = to_upper(typ) == 'NODE'
       if (to_upper(typ) /= 'ELEMENT' .and. .not. nodal) then
          call report_loc(st, loc, '*SURFACE, TYPE='//clip(typ)//' is not supported (element faces, '// &
               'TYPE=ELEMENT, or nodes, TYPE=NODE)')
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
    st%surfaces(st%nsurface)%nodal = nodal
    allocate (st%surfaces(st%nsurface)%refs(0), st%surfaces(st%nsurface)%kinds(0), st%surfaces(st%nsurface)%signs(0))
    st%card = CARD_SURFACE
    st%card_item = st%nsurface
    st%card_home = st%cur_sub
  end subroutine kw_surface

  subroutine data_surface(st, line, loc)
    !! `element or elset, face`: S1 to S4, the edges of a plane element
    !! (CalculiX's faces, as P1 to P4 of *DLOAD), S1 to S6 the faces of a solid,
    !! SPOS or SNEG, the face of a shell along or against its normal.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: face
    integer :: kind
    real(wp) :: sgn
    if (st%surfaces(st%card_item)%nodal) then
       call add_surface_ref(st, line, loc, 0, 1.0_wp)
       return
    end if
    if (.not. field_count(st, loc, 2, 2, 'element or elset, face (S1 to S6, SPOS or SNEG)')) return
    face = to_upper(fld(st, line, 2))
    sgn = 1.0_wp
    select case (face)
    case ('S1', 'S2', 'S3', 'S4', 'S5', 'S6')
       kind = face_load_kind('P'//face(2:2))
    case ('SPOS')
       kind = DLOAD_P
    case ('SNEG')
       kind = DLOAD_P
       sgn = -1.0_wp
    case default
       call report_loc(st, loc, 'unknown face '''//clip(fld(st, line, 2))// &
            ''' (S1 to S4: edges of plane elements; S1 to S6: faces of solids; SPOS, SNEG: faces of shells)')
       return
    end select
    call add_surface_ref(st, line, loc, kind, sgn)
  end subroutine data_surface

  subroutine add_surface_ref(st, line, loc, kind, sgn)
    !! The element (or node, TYPE=NODE: kind 0) reference of a *SURFACE data line.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: kind
    real(wp), intent(in) :: sgn
    type(ref_t) :: ref
    associate (sf => st%surfaces(st%card_item))
      if (sf%nodal) then
         if (.not. field_count(st, loc, 1, 1, 'node or node set')) return
      end if
      if (.not. parse_ref(st, fld(st, line, 1), .not. sf%nodal, st%card_home, loc, ref)) return
      if (sf%n == size(sf%refs)) call grow_surface(sf)
      sf%n = sf%n + 1
      sf%refs(sf%n) = ref
      sf%kinds(sf%n) = kind
      sf%signs(sf%n) = sgn
    end associate
  end subroutine add_surface_ref

  subroutine grow_surface(sf)
    !! Twice the room for a surface's lines (entries 1..n kept).
    type(surface_b_t), intent(inout) :: sf
    type(ref_t), allocatable :: refs(:)
    integer :: k, cap
    cap = 2*size(sf%refs) + 8
    allocate (refs(cap))
    refs(1:sf%n) = sf%refs(1:sf%n)
    call move_alloc(refs, sf%refs)
    sf%kinds = [sf%kinds(1:sf%n), (0, k = sf%n + 1, cap)]
    sf%signs = [sf%signs(1:sf%n), (0.0_wp, k = sf%n + 1, cap)]
  end subroutine grow_surface

  subroutine data_dsload(st, line, loc)
    !! *DSLOAD `surface, P, pressure`: the pressure on every face of an
    !! element surface, as *DLOAD Pk (plane edges) or P (shells, SNEG with the
    !! sign turned) on its elements; `surface, TRVEC|TRSHR, magnitude, dx, dy,
    !! dz` (Abaqus): a traction of that magnitude per unit area along the
    !! direction (TRSHR: its projection onto the surface). The surface may be
    !! `I.S`: instance I's copy of the surface S of its part (CalculiX's and
    !! Abaqus's name).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(load_b_t) :: ld
    type(surface_b_t) :: sf
    character(:), allocatable :: name, typ
    real(wp) :: p, d(3)
    integer :: k, i
    logical :: found
    typ = ''
    if (st%f%n >= 2) typ = to_upper(fld(st, line, 2))
    if (st%f%n >= 2 .and. typ /= 'P' .and. typ /= 'TRVEC' .and. typ /= 'TRSHR') then
       call report_loc(st, loc, 'unknown *DSLOAD type '''//clip(fld(st, line, 2))//''' (P, a uniform pressure; '// &
            'TRVEC, TRSHR, a traction)')
       return
    end if
    if (typ == 'TRVEC' .or. typ == 'TRSHR') then
       if (.not. field_count(st, loc, TRACTION_FIELDS, TRACTION_FIELDS, 'surface, '//typ//', magnitude, dx, dy, dz')) &
            return
       if (.not. traction_direction(st, line, loc, d)) return
    else if (.not. field_count(st, loc, LOAD_FIELDS, LOAD_FIELDS, 'surface, P, pressure')) then
       return
    end if
    if (.not. get_real(st, line, loc, 3, p)) return
    name = to_upper(fld(st, line, 1))
    do k = 1, st%nsurface
       if (st%surfaces(k)%name == name) exit
    end do
    if (k <= st%nsurface) then
       sf = st%surfaces(k)
    else
       call instance_surface(st, name, sf, found)   ! I.S: instance I's copy of its part's surface S
       if (.not. found) then
          call report_loc(st, loc, 'unknown surface '''//clip(fld(st, line, 1))//''' (define it with *SURFACE, '// &
               'TYPE=ELEMENT before the step)')
          return
       end if
    end if
    if (sf%nodal) then
       call report_loc(st, loc, '*DSLOAD on the node surface '//name//' (TYPE=NODE): a '// &
            trim(merge('pressure', 'traction', typ == 'P'))//' needs element faces (*SURFACE, TYPE=ELEMENT)')
       return
    end if
    do i = 1, sf%n
       ld%ref = sf%refs(i)
       ld%kind = sf%kinds(i)
       ld%value = sf%signs(i)*p
       if (typ /= 'P') then   ! a traction: the face, not the side of a shell
          ld%face = dload_face(sf%kinds(i))
          ld%kind = merge(DLOAD_TRVEC, DLOAD_TRSHR, typ == 'TRVEC')
          ld%value = p
          ld%dir = d
       end if
       ld%surface = .true.
       ld%loc = loc
       call add_load(st%steps(st%card_item), ld, .true.)
    end do
  end subroutine data_dsload

  logical function traction_direction(st, line, loc, d) result(ok)
    !! The direction of a *DSLOAD TRVEC or TRSHR (fields 4 to 6), made unit; a
    !! zero vector is an error.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp), intent(out) :: d(3)
    integer :: k
    ok = .false.
    d = 0.0_wp
    do k = 1, 3
       if (.not. get_real(st, line, loc, 3 + k, d(k))) return
    end do
    if (.not. (norm2(d) > 0.0_wp)) then
       call report_loc(st, loc, 'a traction needs a nonzero direction dx, dy, dz')
       return
    end if
    d = d/norm2(d)
    ok = .true.
  end function traction_direction

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
       if (.not. found) then
          call report_loc(st, loc, '*INITIAL CONDITIONS needs TYPE= (superjoin reads TYPE=TEMPERATURE, '// &
               'the initial temperatures)')
          st%cur_mat = prev_mat
          return
       end if
       if (to_upper(typ) /= 'TEMPERATURE') then
          if (refused_card(st, kw, loc, prev_mat, '*INITIAL CONDITIONS, TYPE='//to_upper(typ)//' ('// &
               initial_condition_kind(to_upper(typ))//')', 'TYPE=TEMPERATURE, the initial temperatures, is read')) return
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

  pure function initial_condition_kind(typ) result(what)
    !! What an *INITIAL CONDITIONS of TYPE=typ (upper case) other than
    !! TEMPERATURE sets, as Abaqus and CalculiX name it.
    character(*), intent(in) :: typ
    character(:), allocatable :: what
    select case (typ)
    case ('STRESS')
       what = 'initial stresses'
    case ('PLASTIC STRAIN')
       what = 'initial plastic strains'
    case ('VELOCITY', 'DISPLACEMENT', 'ACCELERATION')
       what = 'initial conditions of a dynamic analysis'
    case ('FLUID VELOCITY', 'MASS FLOW', 'PRESSURE', 'TOTAL PRESSURE', 'TOTAL TEMPERATURE', 'TURBULENCE')
       what = 'initial conditions of a fluid'
    case default
       what = 'initial conditions'
    end select
  end function initial_condition_kind

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

  pure function unknown_dload(name, typ) result(text)
    !! The error for a *DLOAD type name (typ: upper case) superjoin does not
    !! take. CalculiX's PkNP (network pressure: face k takes the pressure of the
    !! fluid node given as the value, a node of a thermo-fluid network) and
    !! PkNUy (a non-uniform pressure from the user subroutine dload) say why.
    character(*), intent(in) :: name, typ
    character(:), allocatable :: text
    text = 'unknown *DLOAD type '''//name//''' (PX, PY, PZ, P, P1 to P6, GRAV, CENTRIF, BX, BY or BZ)'
    if (len(typ) < 4) return
    if (typ(1:1) /= 'P' .or. verify(typ(2:2), '123456') /= 0) return
    if (typ(3:) == 'NP') then
       text = '*DLOAD type '''//name//''' is CalculiX''s network pressure (face '//typ(2:2)// &
            ' takes the pressure of the fluid node given as the value, a node of a thermo-fluid network), '// &
            'which superjoin does not have: give the pressure itself with P'//typ(2:2)
    else if (typ(3:4) == 'NU') then
       text = '*DLOAD type '''//name//''' is a non-uniform pressure from CalculiX''s user subroutine dload, '// &
            'which superjoin cannot call: give the pressure of each element face with P'//typ(2:2)
    end if
  end function unknown_dload
end module superjoin_deck_cards_steps
