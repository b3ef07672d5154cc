module superjoin_deck_cards_materials
  !! The orthotropic and anisotropic forms of *ELASTIC (Abaqus's and
  !! CalculiX's), read into material_t%d:
  !!
  !! - TYPE=ORTHO (or ORTHOTROPIC): D1111, D1122, D2222, D1133, D2233, D3333,
  !!   D1212, D1313 on the first line, D2323[, temperature] on the second;
  !! - TYPE=ENGINEERING CONSTANTS: E1, E2, E3, ν12, ν13, ν23, G12, G13 /
  !!   G23[, temperature]; D is the inverse of their compliance;
  !! - TYPE=ANISO (or ANISOTROPIC): the 21 terms of D's upper triangle by
  !!   columns, D1111, D1122, D2222, D1133, D2233, D3333, D1112, D2212, D3312,
  !!   D1212, D1113, D2213, D3313, D1213, D1313, D1123, D2223, D3323, D1223,
  !!   D1323, D2323: eight, eight, and five[, temperature] per line.
  !!
  !! One set of constants (a temperature, if given, is read and not used: a
  !! second set, a temperature table, is refused). D must be positive definite
  !! (a stable material): otherwise the card's last line is a deck error.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: source_loc_t, MAT_ISO, MAT_ORTHO, MAT_ENGINEERING, MAT_ANISO
  use superjoin_deck_lexer, only: to_upper, itoa
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use superjoin_deck_state, only: deck_state_t, report_loc
  use superjoin_deck_cards_common, only: field_count, get_real, CARD_SKIP, CARD_ELASTIC
  use superjoin_elements_materials, only: ortho_stiffness, aniso_stiffness, engineering_compliance, &
       leading_minor_failure, spd_solve
  implicit none (type, external)
  private

  public :: elastic_kind, data_elastic_aniso, end_elastic_card, ELASTIC_TYPE_NAMES

  integer, parameter :: LINE_VALUES = 8
    !! Constants on every line of a set but its last (Abaqus's and CalculiX's layout).
  character(len=21), parameter :: ELASTIC_TYPE_NAMES(0:3) = [character(len=21) :: 'ISO', 'ORTHO', &
       'ENGINEERING CONSTANTS', 'ANISO']
    !! The TYPE= of each material kind (MAT_*), for messages.

contains

  pure integer function elastic_kind(typ) result(kind)
    !! The material kind (MAT_*) of *ELASTIC, TYPE=typ, or -1 when superjoin
    !! does not take that type.
    character(*), intent(in) :: typ
    character(:), allocatable :: t
    integer :: i
    t = ''
    do i = 1, len(typ)
       if (typ(i:i) /= ' ') t = t//to_upper(typ(i:i))
    end do
    select case (t)
    case ('ISO', 'ISOTROPIC')
       kind = MAT_ISO
    case ('ORTHO', 'ORTHOTROPIC')
       kind = MAT_ORTHO
    case ('ENGINEERINGCONSTANTS')
       kind = MAT_ENGINEERING
    case ('ANISO', 'ANISOTROPIC')
       kind = MAT_ANISO
    case default
       kind = -1
    end select
  end function elastic_kind

  pure integer function set_lines(kind) result(n)
    !! Data lines of one set of constants of material kind `kind`.
    integer, intent(in) :: kind
    n = merge(3, 2, kind == MAT_ANISO)
  end function set_lines

  pure function expected_fields(kind, k) result(text)
    !! What line k of a set of constants of kind `kind` holds (for messages).
    integer, intent(in) :: kind, k
    character(:), allocatable :: text
    if (k == set_lines(kind)) then
       text = 'G23[, temperature]'
       if (kind == MAT_ORTHO) text = 'D2323[, temperature]'
       if (kind == MAT_ANISO) text = 'constants 17 to 21 of 21[, temperature]'
    else
       text = 'E1, E2, E3, nu12, nu13, nu23, G12, G13'
       if (kind == MAT_ORTHO) text = 'D1111, D1122, D2222, D1133, D2233, D3333, D1212, D1313'
       if (kind == MAT_ANISO) text = 'constants '//itoa(8*k - 7)//' to '//itoa(8*k)//' of 21'
    end if
  end function expected_fields

  subroutine data_elastic_aniso(st, line, loc)
    !! A data line of *ELASTIC, TYPE=ORTHO, ENGINEERING CONSTANTS or ANISO: its
    !! constants into the material's `given`; the last line of the set builds D.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    integer :: k, kind, n, i
    real(wp) :: temp
    logical :: last
    kind = st%materials(st%card_item)%kind
    k = st%card_ndata
    if (k > set_lines(kind)) then
       call report_loc(st, loc, 'too many data lines for *ELASTIC, TYPE='//trim(ELASTIC_TYPE_NAMES(kind))// &
            ': superjoin takes one set of constants (a temperature table is not supported)')
       st%card = CARD_SKIP
       return
    end if
    last = k == set_lines(kind)
    n = LINE_VALUES
    if (last) n = merge(5, 1, kind == MAT_ANISO)
    if (.not. field_count(st, loc, n, merge(n + 1, n, last), expected_fields(kind, k))) then
       st%card = CARD_SKIP                    ! one message for the set
       return
    end if
    do i = 1, n
       if (.not. get_real(st, line, loc, i, st%materials(st%card_item)%given(LINE_VALUES*(k - 1) + i))) then
          st%card = CARD_SKIP
          return
       end if
    end do
    if (st%f%n > n) then                      ! the temperature of a one-set table: any value
       if (.not. get_real(st, line, loc, n + 1, temp)) return
    end if
    if (last) call build_stiffness(st, loc)
  end subroutine data_elastic_aniso

  subroutine end_elastic_card(st)
    !! At the end of an *ELASTIC card: an orthotropic or anisotropic set of
    !! constants left incomplete is reported (a card without data lines is
    !! reported by the parser).
    type(deck_state_t), intent(inout) :: st
    integer :: kind
    if (st%card /= CARD_ELASTIC .or. st%card_ndata == 0) return
    kind = st%materials(st%card_item)%kind
    if (kind == MAT_ISO .or. st%card_ndata >= set_lines(kind)) return
    call report_loc(st, st%card_loc, '*ELASTIC, TYPE='//trim(ELASTIC_TYPE_NAMES(kind))//' needs '// &
         itoa(set_lines(kind))//' data lines ('//itoa(merge(21, 9, kind == MAT_ANISO))// &
         ' constants, eight per line), got '//itoa(st%card_ndata))
  end subroutine end_elastic_card

  subroutine build_stiffness(st, loc)
    !! D of the constants just read, checked finite and positive definite
    !! (reported at loc, the set's last line, when it is not); formed with
    !! floating-point halting off (constants near the range's end overflow).
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    type(halting_t) :: saved
    call halting_off(saved)
    call checked_stiffness(st, loc)
    call halting_restore(saved)
  end subroutine build_stiffness

  subroutine checked_stiffness(st, loc)
    !! build_stiffness with halting off.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    real(wp) :: d(6, 6), eye(6, 6)
    integer :: k, i
    character(:), allocatable :: problem
    associate (m => st%materials(st%card_item))
      select case (m%kind)
      case (MAT_ORTHO)
         d = ortho_stiffness(m%given(1:9))
      case (MAT_ANISO)
         d = aniso_stiffness(m%given)
      case default
         problem = engineering_problem(m%given(1:9))
         if (len(problem) > 0) then
            call report_loc(st, loc, '*ELASTIC, TYPE=ENGINEERING CONSTANTS: '//problem)
            return
         end if
         eye = 0.0_wp
         do i = 1, 6
            eye(i, i) = 1.0_wp
         end do
         d = spd_solve(engineering_compliance(m%given(1:9)), eye)
         d = 0.5_wp*(d + transpose(d))
      end select
      if (.not. all(ieee_is_finite(d))) then
         call report_loc(st, loc, '*ELASTIC, TYPE='//trim(ELASTIC_TYPE_NAMES(m%kind))//' of material '// &
              m%name//': D overflows the floating-point range (beyond 1.8E+308 or undefined): check the '// &
              'constants and their units')
         return
      end if
      k = leading_minor_failure(d)
      if (k > 0) then
         call report_loc(st, loc, '*ELASTIC, TYPE='//trim(ELASTIC_TYPE_NAMES(m%kind))//' of material '// &
              m%name//': D is not positive definite (its leading '//itoa(k)//'x'//itoa(k)// &
              ' minor is not positive): not a stable elastic material')
         return
      end if
      m%d = d
    end associate
  end subroutine checked_stiffness

  pure function engineering_problem(c) result(problem)
    !! Why the engineering constants c = E1, E2, E3, ν12, ν13, ν23, G12, G13,
    !! G23 are not those of a stable material ('' when they are): moduli
    !! positive, ν_ij² E_j/E_i < 1 for each pair, and
    !! 1 - ν12 ν21 - ν23 ν32 - ν13 ν31 - 2 ν21 ν32 ν13 > 0 (the compliance
    !! positive definite; Lekhnitskii, Jones ch. 2.4).
    real(wp), intent(in) :: c(9)
    character(:), allocatable :: problem
    character(len=4), parameter :: MODULI(6) = [character(len=4) :: 'E1', 'E2', 'E3', 'G12', 'G13', 'G23']
    integer, parameter :: AT(6) = [1, 2, 3, 7, 8, 9]
    real(wp) :: n21, n31, n32
    integer :: i
    problem = ''
    do i = 1, 6
       if (.not. (c(AT(i)) > 0.0_wp)) then
          problem = trim(MODULI(i))//' must be positive'
          return
       end if
    end do
    if (.not. (c(4)**2*c(2)/c(1) < 1.0_wp)) problem = 'nu12**2 E2/E1 must be below 1'
    if (.not. (c(5)**2*c(3)/c(1) < 1.0_wp)) problem = 'nu13**2 E3/E1 must be below 1'
    if (.not. (c(6)**2*c(3)/c(2) < 1.0_wp)) problem = 'nu23**2 E3/E2 must be below 1'
    if (len(problem) > 0) then
       problem = problem//' (not a stable material)'
       return
    end if
    n21 = c(4)*c(2)/c(1)
    n31 = c(5)*c(3)/c(1)
    n32 = c(6)*c(3)/c(2)
    if (.not. (1.0_wp - c(4)*n21 - c(6)*n32 - c(5)*n31 - 2.0_wp*n21*n32*c(5) > 0.0_wp)) &
         problem = '1 - nu12 nu21 - nu23 nu32 - nu13 nu31 - 2 nu21 nu32 nu13 must be positive '// &
         '(not a stable material)'
  end function engineering_problem
end module superjoin_deck_cards_materials
