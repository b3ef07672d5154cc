module superjoin_deck_equations
  !! Parser side of `*EQUATION` (Abaqus/CalculiX): each equation is a line with
  !! its number of terms n, then n terms `node, dof, coefficient`, up to four
  !! per line, continuing on the following lines:
  !!     sum_i a_i u(node_i, dof_i) = 0,
  !! the first term's DOF being the dependent one. Nodes are written as
  !! elsewhere (`id`, `SUB.id`); node sets are not accepted. The equations are
  !! resolved to DOFs by superjoin_deck_equation_build and eliminated exactly
  !! by the transform.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: source_loc_t
  use superjoin_deck_lexer, only: keyword_line_t, parse_id, itoa, clip, plural, TOK_OK
  use superjoin_deck_state, only: deck_state_t, report_loc, grow, equation_b_t
  use superjoin_deck_cards_common, only: outside_step, check_params, field_count, fld, get_real, &
       get_dof, parse_ref, loc_string, CARD_SKIP, CARD_EQUATION, NAME_LEN
  implicit none (type, external)
  private

  public :: kw_equation, data_equation, end_equation_card

  integer, parameter :: TERM_FIELDS = 3
    !! node, dof, coefficient
  integer, parameter :: MAX_TERMS_PER_LINE = 4
    !! as Abaqus and CalculiX (12 fields)
  integer, parameter :: MAX_TERMS = 100000
    !! a sanity bound on the number of terms of one equation

contains

  subroutine kw_equation(st, kw, loc)
    !! *EQUATION: linear constraints between DOFs (Abaqus/CalculiX form).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    st%card = CARD_EQUATION
    st%card_home = st%cur_sub
    st%card_item = 0
  end subroutine kw_equation

  subroutine data_equation(st, line, loc)
    !! A data line of *EQUATION: a number of terms, or node, dof, coefficient triples.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer :: n, k, t
    integer(ip) :: v
    integer :: stat
    type(equation_b_t) :: eq

    if (st%card_item == 0) then
       ! A new equation: its number of terms.
       if (.not. field_count(st, loc, 1, 1, 'the number of terms of the equation')) return
       call parse_id(fld(st, line, 1), v, stat)
       if (stat /= TOK_OK .or. v < 1 .or. v > MAX_TERMS) then
          call report_loc(st, loc, 'invalid number of terms '''//clip(fld(st, line, 1))// &
               ''' (*EQUATION: a line with the number of terms, then node, dof, coefficient per term)')
          st%card = CARD_SKIP
          return
       end if
       eq%nterm = int(v)
       eq%loc = loc
       allocate (eq%node(eq%nterm), eq%dof(eq%nterm), eq%coef(eq%nterm), eq%term_loc(eq%nterm))
       call push_equation(st, eq)
       st%card_item = st%nequation
       return
    end if
    associate (e => st%equations(st%card_item))
      n = st%f%n
      if (mod(n, TERM_FIELDS) /= 0 .or. n > TERM_FIELDS*MAX_TERMS_PER_LINE) then
         call report_loc(st, loc, 'wrong number of fields on *EQUATION data line: expected node, dof, '// &
              'coefficient for each of up to 4 terms, got '//plural(n, 'field'))
         e%ok = .false.
         st%card = CARD_SKIP
         return
      end if
      if (e%n + n/TERM_FIELDS > e%nterm) then
         call report_loc(st, loc, '*EQUATION has more terms than the '//itoa(e%nterm)// &
              ' its first line announces (at '//loc_string(st, e%loc)//')')
         e%ok = .false.
         st%card = CARD_SKIP
         return
      end if
      do k = 1, n/TERM_FIELDS
         t = e%n + 1
         e%n = t
         e%term_loc(t) = loc
         if (.not. parse_ref(st, fld(st, line, TERM_FIELDS*(k - 1) + 1), .false., st%card_home, loc, e%node(t))) then
            e%ok = .false.
            cycle
         end if
         if (e%node(t)%is_set) then
            call report_loc(st, loc, '*EQUATION takes nodes, not the node set '//e%node(t)%set)
            e%ok = .false.
            cycle
         end if
         if (.not. get_dof(st, line, loc, TERM_FIELDS*(k - 1) + 2, e%dof(t))) then
            e%ok = .false.
            cycle
         end if
         if (.not. get_real(st, line, loc, TERM_FIELDS*k, e%coef(t))) then
            e%ok = .false.
            cycle
         end if
         if (t == 1 .and. e%coef(t) == 0.0_wp) then
            call report_loc(st, loc, '*EQUATION: the first coefficient is zero (the first term''s DOF is '// &
                 'the one eliminated, so its coefficient must not be 0)')
            e%ok = .false.
         end if
      end do
      if (e%n == e%nterm) st%card_item = 0
    end associate
  end subroutine data_equation

  subroutine end_equation_card(st)
    !! End of an *EQUATION card: the last equation must have all its terms.
    type(deck_state_t), intent(inout) :: st
    if (st%card_item == 0) return
    associate (e => st%equations(st%card_item))
      call report_loc(st, e%loc, '*EQUATION announces '//itoa(e%nterm)//' terms but has '//itoa(e%n))
      e%ok = .false.
    end associate
    st%card_item = 0
  end subroutine end_equation_card

  subroutine push_equation(st, eq)
    !! Append an equation to the deck state.
    type(deck_state_t), intent(inout) :: st
    type(equation_b_t), intent(in) :: eq
    integer, parameter :: INITIAL_EQUATIONS = 8
    call grow(st%equations, st%nequation, INITIAL_EQUATIONS)
    st%nequation = st%nequation + 1
    st%equations(st%nequation) = eq
  end subroutine push_equation
end module superjoin_deck_equations
