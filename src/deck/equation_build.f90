module superjoin_deck_equation_build
  !! Validation side of `*EQUATION`: node references resolved to (substructure,
  !! node), and the checks that need no stiffness: a DOF that two equations
  !! both make dependent, and a first DOF that appears again in its own equation.
  use superjoin_kinds, only: ip
  use superjoin_model_types, only: model_t, equation_t, node_label
  use superjoin_deck_state, only: deck_state_t, report_loc, file_of
  use superjoin_deck_build_common, only: resolve_items, resolve_sub
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  public :: build_equations

contains

  subroutine build_equations(st, model)
    !! model%equations from the equations read (those with a reading error are left out).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(equation_t), allocatable :: list(:)
    integer(ip), allocatable :: nodes(:)
    integer :: k, t, n, isub, j
    logical :: ok, good

    allocate (list(st%nequation))
    n = 0
    do k = 1, st%nequation
       associate (eb => st%equations(k))
         if (.not. eb%ok) cycle
         n = n + 1
         list(n) = equation_t()
         allocate (list(n)%sub(eb%nterm), list(n)%node(eb%nterm), list(n)%dof(eb%nterm), list(n)%coef(eb%nterm))
         list(n)%loc = eb%loc
         good = .true.
         do t = 1, eb%nterm
            isub = resolve_sub(st, model, eb%node(t), eb%term_loc(t), 'node')
            if (isub == 0) then
               good = .false.
               cycle
            end if
            call resolve_items(st, model, isub, eb%node(t), .false., eb%term_loc(t), nodes, ok)
            if (.not. ok) then
               good = .false.
               cycle
            end if
            list(n)%sub(t) = isub
            list(n)%node(t) = nodes(1)
            list(n)%dof(t) = eb%dof(t)
            list(n)%coef(t) = eb%coef(t)
         end do
         if (.not. good) then
            n = n - 1
            cycle
         end if
         do t = 2, eb%nterm
            if (same_dof(list(n), 1, list(n), t)) then
               call report_loc(st, eb%term_loc(t), '*EQUATION: the dependent DOF '//dof_name(model, list(n), 1)// &
                    ' appears again as term '//itoa(t)//' (write each DOF once)')
               good = .false.
               exit
            end if
         end do
         do j = 1, n - 1
            if (.not. good) exit
            if (same_dof(list(j), 1, list(n), 1)) then
               call report_loc(st, eb%loc, '*EQUATION: DOF '//dof_name(model, list(n), 1)// &
                    ' is already the dependent DOF of the equation at '//file_of(st, list(j)%loc%file)//':'//itoa(list(j)%loc%line)// &
                    ' (a DOF can be eliminated once; start this equation with another DOF)')
               good = .false.
            end if
         end do
         if (.not. good) n = n - 1
       end associate
    end do
    model%equations = list(1:n)
  end subroutine build_equations

  pure logical function same_dof(a, i, b, j)
    type(equation_t), intent(in) :: a, b
    integer, intent(in) :: i, j
    same_dof = a%sub(i) == b%sub(j) .and. a%node(i) == b%node(j) .and. a%dof(i) == b%dof(j)
  end function same_dof

  function dof_name(model, e, t) result(text)
    !! "node N DOF d" of term t.
    type(model_t), intent(in) :: model
    type(equation_t), intent(in) :: e
    integer, intent(in) :: t
    character(:), allocatable :: text
    text = 'node '//node_label(model, e%sub(t), e%node(t))//' DOF '//itoa(e%dof(t))
  end function dof_name

end module superjoin_deck_equation_build
