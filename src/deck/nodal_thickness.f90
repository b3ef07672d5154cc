module superjoin_deck_nodal_thickness
  !! Parser side of `*NODAL THICKNESS` (CalculiX): the thickness of shell and
  !! plane elements given at their nodes, in place of the section's. Data
  !! lines `node or nset, t[, t2]`; t2 (the second thickness of beams in
  !! CalculiX) is read and must be absent, empty or 0 here. The values are
  !! applied per element by superjoin_deck_thickness_build.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: source_loc_t, SEC_BEAM
  use superjoin_deck_lexer, only: keyword_line_t
  use superjoin_deck_state, only: deck_state_t, report_loc, grow, nthick_b_t
  use superjoin_deck_cards_common, only: outside_step, check_params, field_count, fld, get_real, &
       parse_ref, CARD_SKIP, CARD_NODAL_THICKNESS, NAME_LEN
  implicit none (type, external)
  private

  public :: kw_nodal_thickness, data_nodal_thickness

contains

  subroutine kw_nodal_thickness(st, kw, loc)
    !! *NODAL THICKNESS (CalculiX): shell and plane element thickness given at the nodes.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    st%card = CARD_SKIP
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    st%card = CARD_NODAL_THICKNESS
    st%card_home = st%cur_sub
  end subroutine kw_nodal_thickness

  subroutine data_nodal_thickness(st, line, loc)
    !! A data line of *NODAL THICKNESS: node or node set, thickness[, second thickness].
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer, parameter :: INITIAL_LINES = 8, MAX_FIELDS = 3
    type(nthick_b_t) :: d
    real(wp) :: t2
    if (.not. field_count(st, loc, 2, MAX_FIELDS, 'node or nset, thickness')) return
    if (.not. parse_ref(st, fld(st, line, 1), .false., st%card_home, loc, d%node)) return
    if (.not. get_real(st, line, loc, 2, d%t)) return
    if (.not. (d%t > 0.0_wp)) then
       call report_loc(st, loc, 'nodal thickness must be positive, not '//fld(st, line, 2))
       return
    end if
    if (st%f%n == MAX_FIELDS) then
       if (len(fld(st, line, MAX_FIELDS)) > 0) then
          if (.not. get_real(st, line, loc, MAX_FIELDS, t2)) return
          if (t2 /= 0.0_wp) then
             ! after a refused *BEAM SECTION, NODAL THICKNESS (reported) the line is dropped quietly
             if (.not. st%section_rejected(SEC_BEAM)) call report_loc(st, loc, &
                  '*NODAL THICKNESS: a second thickness (beams in CalculiX) is not supported')
             return
          end if
       end if
    end if
    d%loc = loc
    call grow(st%nthicks, st%nnthick, INITIAL_LINES)
    st%nnthick = st%nnthick + 1
    st%nthicks(st%nnthick) = d
  end subroutine data_nodal_thickness
end module superjoin_deck_nodal_thickness
