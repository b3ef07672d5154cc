module superjoin_deck_ties
  !! Parser side of `*TIE` (Abaqus/CalculiX tied contact): parameters NAME=,
  !! POSITION TOLERANCE= (0 or absent: CalculiX's default, 2.5 % of a typical
  !! master face size), ADJUST=YES|NO (YES, the default, moves each tied slave
  !! node onto the master surface), TYPE=NODE TO SURFACE|SURFACE TO SURFACE
  !! (both tie nodes to faces here), NO ROTATION (rotations are never tied);
  !! one data line `slave surface, master surface`. CalculiX's CYCLIC
  !! SYMMETRY, MULTISTAGE, FLUID PERIODIC and FLUID CYCLIC ties are refused.
  !! The ties are resolved to constraint equations by superjoin_deck_tie_build.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: source_loc_t
  use superjoin_deck_lexer, only: keyword_line_t, clip
  use superjoin_deck_state, only: deck_state_t, report_loc, tie_b_t
  use superjoin_deck_cards_common, only: outside_step, check_params, param_index, get_param, field_count, fld, &
       loc_string, CARD_SKIP, CARD_TIE, NAME_LEN
  use superjoin_deck_lexer, only: parse_real, TOK_OK
  use superjoin_utils_strings, only: to_upper
  implicit none (type, external)
  private

  public :: kw_tie, data_tie

  character(NAME_LEN), parameter :: REFUSED(4) = [character(NAME_LEN) :: 'CYCLIC SYMMETRY', 'MULTISTAGE', &
       'FLUID PERIODIC', 'FLUID CYCLIC']

contains

  subroutine kw_tie(st, kw, loc)
    !! *TIE: a slave surface tied to a master surface (model data).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(tie_b_t) :: tie
    character(:), allocatable :: value
    logical :: found
    integer :: k, stat
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'POSITION TOLERANCE', 'ADJUST', 'TYPE'], &
         [character(NAME_LEN) :: 'NO ROTATION', REFUSED])
    do k = 1, size(REFUSED)
       if (param_index(kw, trim(REFUSED(k))) > 0) then
          call report_loc(st, loc, '*TIE, '//trim(REFUSED(k))//' is not supported (superjoin ties a slave '// &
               'surface to a master surface of the same structure: tied contact)')
          return
       end if
    end do
    call get_param(st, kw, loc, 'NAME', .false., value, found)
    tie%name = ''
    if (found) tie%name = to_upper(value)
    call get_param(st, kw, loc, 'POSITION TOLERANCE', .false., value, found)
    if (found) then
       call parse_real(value, tie%tolerance, stat)
       if (stat /= TOK_OK .or. .not. (tie%tolerance >= 0.0_wp)) then
          call report_loc(st, loc, '*TIE: POSITION TOLERANCE must be a length of 0 or more, not '//clip(value))
          return
       end if
    end if
    call get_param(st, kw, loc, 'ADJUST', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('YES')
          tie%adjust = .true.
       case ('NO')
          tie%adjust = .false.
       case default
          call report_loc(st, loc, '*TIE: ADJUST='//clip(value)//' (YES or NO; a length is not supported)')
          return
       end select
    end if
    call get_param(st, kw, loc, 'TYPE', .false., value, found)
    if (found) then
       if (to_upper(value) /= 'NODE TO SURFACE' .and. to_upper(value) /= 'SURFACE TO SURFACE') then
          call report_loc(st, loc, '*TIE: TYPE='//clip(value)//' (NODE TO SURFACE or SURFACE TO SURFACE)')
          return
       end if
    end if
    if (.not. unique_name(st, tie%name, loc)) return
    tie%loc = loc
    tie%home = st%cur_sub
    if (.not. allocated(st%ties)) allocate (st%ties(0))
    st%ties = [st%ties, tie]
    st%card = CARD_TIE
    st%card_item = size(st%ties)
  end subroutine kw_tie

  logical function unique_name(st, name, loc) result(ok)
    !! A *TIE name not used by an earlier *TIE (reported otherwise).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: loc
    integer :: k
    ok = .true.
    if (len(name) == 0 .or. .not. allocated(st%ties)) return
    do k = 1, size(st%ties)
       if (st%ties(k)%name == name) then
          call report_loc(st, loc, '*TIE '//name//' is already defined (at '//loc_string(st, st%ties(k)%loc)//')')
          ok = .false.
       end if
    end do
  end function unique_name

  subroutine data_tie(st, line, loc)
    !! The data line of *TIE: slave surface, master surface (one line only).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    associate (tie => st%ties(st%card_item))
      if (tie%has_line) then
         call report_loc(st, loc, '*TIE takes one data line (slave surface, master surface): write one *TIE '// &
              'per pair of surfaces')
         st%card = CARD_SKIP
         return
      end if
      tie%has_line = .true.
      tie%line_loc = loc
      if (.not. field_count(st, loc, 2, 2, 'slave surface, master surface')) then
         tie%slave = ''
         tie%master = ''
         return
      end if
      tie%slave = to_upper(fld(st, line, 1))
      tie%master = to_upper(fld(st, line, 2))
    end associate
  end subroutine data_tie
end module superjoin_deck_ties
