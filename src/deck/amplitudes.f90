module superjoin_deck_amplitudes
  !! *AMPLITUDE (Abaqus, CalculiX) and AMPLITUDE= on *CLOAD, *DLOAD, *DSLOAD
  !! and *BOUNDARY inside a step. A linear static step has one increment, at
  !! the end of the step, so what such a card writes is scaled by the value of
  !! its amplitude there: at the step time (the time period of *STATIC's data
  !! line, 1 without one) or, with TIME=TOTAL TIME, at the total time (the
  !! periods of the steps so far; a step with *STATIC, TIME RESET does not
  !! advance it; build_steps' step_times), as ccx 2.20 does (measured). A load that a later step keeps
  !! (OP=MOD) keeps its amplitude and takes its value at that step's time.
  !!
  !! The cards' data lines are recorded as they are read (record_amp_line);
  !! once the steps' loads and supports are built and their history applied,
  !! apply_amplitudes scales each by the amplitude of the line that wrote it.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: model_t, source_loc_t, DLOAD_THERMAL
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, clip, itoa, parse_real, TOK_OK
  use superjoin_deck_state, only: deck_state_t, report_loc, amplitude_b_t, amp_use_b_t, grow
  use superjoin_deck_records, only: AMP_TABULAR, AMP_EQUALLY_SPACED, AMP_SMOOTH_STEP
  use superjoin_deck_cards_common, only: check_params, get_param, param_index, get_real, real_message, &
       loc_string, CARD_SKIP, NAME_LEN
  use superjoin_model_notes, only: note
  use superjoin_utils_strings, only: rtoa
  implicit none (type, external)
  private

  public :: kw_amplitude, data_amplitude, amplitude_param, record_amp_line, apply_amplitudes, amplitude_at

  integer, parameter, public :: CARD_AMPLITUDE = 211
    !! The data lines of *AMPLITUDE.
  integer, parameter :: INITIAL_USES = 16
    !! recorded data lines before the first doubling
  character(len=14), parameter :: DEFINITIONS(3) = ['TABULAR       ', 'EQUALLY SPACED', 'SMOOTH STEP   ']
    !! DEFINITION= values, in the order of AMP_TABULAR, AMP_EQUALLY_SPACED, AMP_SMOOTH_STEP

  type :: line_map_t
    !! The amplitude (0: none) of each line of one file.
     integer, allocatable :: amp(:)
  end type line_map_t

contains

  subroutine kw_amplitude(st, kw, loc)
    !! *AMPLITUDE, NAME=a[, TIME=STEP TIME|TOTAL TIME][, DEFINITION=TABULAR|
    !! EQUALLY SPACED|SMOOTH STEP][, VALUE=RELATIVE][, FIXED INTERVAL=dt][, BEGIN=t0].
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(amplitude_b_t) :: amp
    character(:), allocatable :: v
    logical :: found
    integer :: k, stat
    st%card = CARD_SKIP
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'TIME', 'DEFINITION', 'VALUE', &
         'FIXED INTERVAL', 'BEGIN'], [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'NAME', .true., v, found)
    if (.not. found) return
    amp%name = to_upper(v)
    amp%loc = loc
    if (allocated(st%amps)) then
       do k = 1, size(st%amps)
          if (st%amps(k)%name /= amp%name) cycle
          call report_loc(st, loc, 'amplitude '//amp%name//' is defined twice (first at '// &
               loc_string(st, st%amps(k)%loc)//')')
          return
       end do
    end if
    call get_param(st, kw, loc, 'TIME', .false., v, found)
    if (found) then
       select case (to_upper(v))
       case ('STEP TIME')
       case ('TOTAL TIME')
          amp%total_time = .true.
       case default
          call report_loc(st, loc, 'TIME= of *AMPLITUDE must be STEP TIME or TOTAL TIME, not '//clip(v))
          return
       end select
    end if
    call get_param(st, kw, loc, 'DEFINITION', .false., v, found)
    if (found) then
       amp%definition = findloc(DEFINITIONS, to_upper(v), dim=1)
       if (amp%definition == 0) then
          call report_loc(st, loc, 'DEFINITION='//clip(v)//' of *AMPLITUDE is not supported: superjoin''s '// &
               'amplitudes are TABULAR, EQUALLY SPACED or SMOOTH STEP')
          return
       end if
    end if
    call get_param(st, kw, loc, 'VALUE', .false., v, found)
    if (found) then
       if (to_upper(v) /= 'RELATIVE') then
          call report_loc(st, loc, 'VALUE='//clip(v)//' of *AMPLITUDE is not supported: an amplitude scales '// &
               'the values its cards write (VALUE=RELATIVE)')
          return
       end if
    end if
    if (amp%definition == AMP_EQUALLY_SPACED) then
       call get_param(st, kw, loc, 'FIXED INTERVAL', .true., v, found)
       if (.not. found) return
       call parse_real(v, amp%interval, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, real_message(v, stat))
          return
       else if (.not. (amp%interval > 0.0_wp)) then
          call report_loc(st, loc, 'FIXED INTERVAL= of *AMPLITUDE must be a positive real, not '//clip(v))
          return
       end if
       call get_param(st, kw, loc, 'BEGIN', .false., v, found)
       if (found) then
          call parse_real(v, amp%begin, stat)
          if (stat /= TOK_OK) then
             call report_loc(st, loc, real_message(v, stat))
             return
          end if
       end if
    else if (param_index(kw, 'FIXED INTERVAL') > 0 .or. param_index(kw, 'BEGIN') > 0) then
       call report_loc(st, loc, 'FIXED INTERVAL= and BEGIN= of *AMPLITUDE go with DEFINITION=EQUALLY SPACED')
       return
    end if
    allocate (amp%t(0), amp%a(0))
    if (allocated(st%amps)) then
       st%amps = [st%amps, amp]
    else
       st%amps = [amp]
    end if
    st%card = CARD_AMPLITUDE
    st%card_item = size(st%amps)
  end subroutine kw_amplitude

  subroutine data_amplitude(st, line, loc)
    !! A data line of *AMPLITUDE: pairs `time, value` (EQUALLY SPACED: values),
    !! the times in increasing order.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp), allocatable :: x(:)
    integer :: i, n
    st%amps(st%card_item)%nlines = st%amps(st%card_item)%nlines + 1
    n = st%f%n
    allocate (x(n))
    do i = 1, n
       if (.not. get_real(st, line, loc, i, x(i))) return
    end do
    associate (amp => st%amps(st%card_item))
      if (amp%definition == AMP_EQUALLY_SPACED) then
         amp%t = [amp%t, amp%begin + amp%interval*real([(size(amp%a) + i - 1, i=1, n)], wp)]
         amp%a = [amp%a, x]
         return
      end if
      if (mod(n, 2) /= 0) then
         call report_loc(st, loc, '*AMPLITUDE data lines hold pairs: time, value (got '//itoa(n)//' fields)')
         return
      end if
      do i = 1, n, 2
         if (size(amp%t) > 0) then
            if (x(i) < amp%t(size(amp%t))) then
               call report_loc(st, loc, 'the times of *AMPLITUDE '//amp%name//' must not decrease ('// &
                    rtoa(x(i), 7)//' after '//rtoa(amp%t(size(amp%t)), 7)//')')
               return
            end if
         end if
         amp%t = [amp%t, x(i)]
         amp%a = [amp%a, x(i + 1)]
      end do
    end associate
  end subroutine data_amplitude

  subroutine amplitude_param(st, kw, loc)
    !! AMPLITUDE= of the load or *BOUNDARY card kw: the data lines that follow
    !! are recorded with it (record_amp_line). Inside *STEP only.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer :: k
    k = param_index(kw, 'AMPLITUDE')
    if (k == 0) return
    if (.not. kw%params(k)%has_value) return   ! check_params said so
    if (st%cur_step == 0) then
       call report_loc(st, loc, 'AMPLITUDE= of *'//kw%keyword//' applies inside *STEP only')
       return
    end if
    st%card_amp = to_upper(trim(kw%params(k)%value))
  end subroutine amplitude_param

  subroutine record_amp_line(st, loc)
    !! The data line at loc of a card with AMPLITUDE=: what it writes is scaled.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    call grow(st%amp_uses, st%namp_use, INITIAL_USES)
    st%namp_use = st%namp_use + 1
    st%amp_uses(st%namp_use)%line = loc
    st%amp_uses(st%namp_use)%card = st%card_loc
    st%amp_uses(st%namp_use)%name = st%card_amp
  end subroutine record_amp_line

  subroutine apply_amplitudes(st, model)
    !! Scale the loads and prescribed values of every step written on lines
    !! of cards with AMPLITUDE= by that amplitude at the end of the step (its
    !! step time or the total time); one listing note per amplitude and step.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(line_map_t), allocatable :: maps(:)
    integer, allocatable :: idx(:)
    logical, allocatable :: used(:, :)
    real(wp), allocatable :: factor(:)
    real(wp) :: tstep, ttotal
    integer :: u, s, k, a
    if (allocated(st%amps)) then
       do a = 1, size(st%amps)
          if (st%amps(a)%nlines == 0) call report_loc(st, st%amps(a)%loc, '*AMPLITUDE '//st%amps(a)%name// &
               ' has no points (data lines: time, value)')
       end do
    end if
    allocate (idx(st%namp_use), source=0)
    do u = 1, st%namp_use
       associate (use => st%amp_uses(u))
         if (allocated(st%amps)) idx(u) = findloc([(st%amps(a)%name == use%name, a=1, size(st%amps))], .true., dim=1)
         if (idx(u) > 0) cycle
         if (u > 1) then   ! one error per card: its lines are recorded one after the other
            if (st%amp_uses(u - 1)%card%file == use%card%file .and. st%amp_uses(u - 1)%card%line == use%card%line) cycle
         end if
         call report_loc(st, use%card, 'unknown amplitude '//use%name//' (no *AMPLITUDE, NAME='//use%name//')')
       end associate
    end do
    if (any(idx == 0) .or. allocated(st%error)) return   ! an amplitude without points: reported
    if (st%namp_use == 0) return
    call map_lines(st, idx, maps)
    allocate (used(size(st%amps), size(model%steps)), source=.false.)
    allocate (factor(size(st%amps)))
    do s = 1, size(model%steps)
       tstep = model%steps(s)%period        ! step_times (build_steps)
       ttotal = model%steps(s)%total_time
       do a = 1, size(st%amps)
          factor(a) = amplitude_at(st%amps(a), merge(ttotal, tstep, st%amps(a)%total_time))
       end do
       associate (step => model%steps(s))
         if (allocated(step%cloads)) then
            do k = 1, size(step%cloads)
               a = amp_of(maps, step%cloads(k)%loc)
               if (a == 0) cycle
               step%cloads(k)%value = factor(a)*step%cloads(k)%value
               used(a, s) = .true.
            end do
         end if
         if (allocated(step%dloads)) then
            do k = 1, size(step%dloads)
               if (step%dloads(k)%kind == DLOAD_THERMAL) cycle
               a = amp_of(maps, step%dloads(k)%loc)
               if (a == 0) cycle
               step%dloads(k)%value = factor(a)*step%dloads(k)%value
               used(a, s) = .true.
            end do
         end if
         if (allocated(step%supports)) then
            do k = 1, size(step%supports)
               if (step%supports(k)%held_from > 0) cycle   ! *BOUNDARY, FIXED: the driver's
               a = amp_of(maps, step%supports(k)%loc)
               if (a == 0) cycle
               step%supports(k)%value = factor(a)*step%supports(k)%value
               used(a, s) = .true.
            end do
         end if
       end associate
       do a = 1, size(st%amps)
          if (.not. used(a, s)) cycle
          call note(model%notes, 'amplitude '//st%amps(a)%name//' (*AMPLITUDE at '//loc_string(st, st%amps(a)%loc)// &
               '): the values of its cards in step '//st%steps(s)%name//' times '//rtoa(factor(a), 7)// &
               ', its value at the end of the step ('//merge('total time ', 'step time  ', st%amps(a)%total_time)// &
               rtoa(merge(ttotal, tstep, st%amps(a)%total_time), 7)//')')
          call note_perturbation_time(st, model, s, a)
       end do
    end do
  end subroutine apply_amplitudes

  subroutine note_perturbation_time(st, model, s, a)
    !! Amplitude a used in step s where Abaqus and CalculiX count time
    !! differently: Abaqus gives a linear perturbation step no time of its own
    !! and never adds its step time to the total time; ccx 2.20 gives it its
    !! *STATIC time period and adds it (measured: a perturbation step of period
    !! 1.5 after a step of 1 prints time 2.5 and scales its loads by a(1.5)).
    !! superjoin counts as ccx does and says so: in a PERTURBATION step, and
    !! for a TIME=TOTAL TIME amplitude after one.
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(inout) :: model
    integer, intent(in) :: s, a
    integer :: p
    character(:), allocatable :: head
    head = 'warning: amplitude '//st%amps(a)%name//' in step '//st%steps(s)%name
    if (st%steps(s)%perturbation) then
       call note(model%notes, head//', a PERTURBATION step: read at the step''s time period, as ccx 2.20 '// &
            'reads it; Abaqus gives a linear perturbation step no time period of its own (check this load '// &
            'in an Abaqus deck)')
       return
    end if
    if (.not. st%amps(a)%total_time) return
    do p = 1, s - 1
       if (.not. st%steps(p)%perturbation .or. st%steps(p)%time_reset) cycle   ! TIME RESET: not added
       call note(model%notes, head//': its total time counts the time period of PERTURBATION step '// &
            st%steps(p)%name//', as ccx 2.20 counts it; Abaqus never adds a perturbation step''s time to '// &
            'the total time')
       return
    end do
  end subroutine note_perturbation_time

  subroutine map_lines(st, idx, maps)
    !! maps(f)%amp(l): the amplitude of line l of file f (0: none), from the
    !! recorded lines and their amplitudes idx.
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: idx(:)
    type(line_map_t), allocatable, intent(out) :: maps(:)
    integer :: u, f
    allocate (maps(maxval(st%amp_uses(1:st%namp_use)%line%file)))
    do f = 1, size(maps)
       allocate (maps(f)%amp(max(0, maxval(st%amp_uses(1:st%namp_use)%line%line, &
            mask=st%amp_uses(1:st%namp_use)%line%file == f, dim=1))), source=0)
    end do
    do u = 1, st%namp_use
       maps(st%amp_uses(u)%line%file)%amp(st%amp_uses(u)%line%line) = idx(u)
    end do
  end subroutine map_lines

  pure integer function amp_of(maps, loc) result(a)
    !! The amplitude of the line at loc (0: none).
    type(line_map_t), intent(in) :: maps(:)
    type(source_loc_t), intent(in) :: loc
    a = 0
    if (loc%file < 1 .or. loc%file > size(maps)) return
    if (loc%line < 1 .or. loc%line > size(maps(loc%file)%amp)) return
    a = maps(loc%file)%amp(loc%line)
  end function amp_of

  pure real(wp) function amplitude_at(amp, t) result(v)
    !! a(t): the first value before the first point, the last after the last;
    !! between two points linear (TABULAR, EQUALLY SPACED) or the smooth step
    !! a_i + (a_i+1 - a_i) x^3 (10 - 15 x + 6 x^2), x = (t - t_i)/(t_i+1 - t_i).
    type(amplitude_b_t), intent(in) :: amp
    real(wp), intent(in) :: t
    real(wp) :: x
    integer :: i, n
    n = size(amp%t)
    if (t <= amp%t(1)) then
       v = amp%a(1)
       return
    end if
    if (t >= amp%t(n)) then
       v = amp%a(n)
       return
    end if
    i = 1
    do while (amp%t(i + 1) <= t)
       i = i + 1
    end do
    x = (t - amp%t(i))/(amp%t(i + 1) - amp%t(i))
    if (amp%definition == AMP_SMOOTH_STEP) x = x**3*(10.0_wp - 15.0_wp*x + 6.0_wp*x**2)
    v = amp%a(i) + (amp%a(i + 1) - amp%a(i))*x
  end function amplitude_at
end module superjoin_deck_amplitudes
