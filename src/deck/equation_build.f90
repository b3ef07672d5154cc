module superjoin_deck_equation_build
  !! Validation side of `*EQUATION`: node references resolved to (substructure,
  !! node), and the checks that need no stiffness: a DOF that two equations
  !! both make dependent, and a first DOF that appears again in its own equation.
  !! Terms on nodes with a nodal system (*TRANSFORM) are then turned into
  !! global components (equations_to_global).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, equation_t, node_label, frame_of_node
  use superjoin_deck_state, only: deck_state_t, report_loc, file_of
  use superjoin_deck_build_common, only: resolve_items, resolve_sub
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  public :: build_equations, equations_to_global

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

  subroutine equations_to_global(model)
    !! The DOF numbers of an *EQUATION term on a node with a nodal system
    !! (*TRANSFORM) are in that system, as in CalculiX and Abaqus: the term
    !! a u_local(d) = a sum_j q(d, j) u(j) (j over the DOF's block, 1-3 or 4-6)
    !! becomes its global components (exact zeros left out, a DOF met twice
    !! merged). The dependent DOF is then the first term's largest global
    !! component that no earlier equation makes dependent. Run after
    !! build_frames; the equations of *TIE, *COUPLING, *RIGID BODY and *MPC are
    !! written in global axes and stay as they are.
    type(model_t), intent(inout) :: model
    integer :: ie, t
    logical :: framed
    if (.not. allocated(model%frames) .or. .not. allocated(model%equations)) return
    if (size(model%frames) == 0) return
    do ie = 1, size(model%equations)
       associate (e => model%equations(ie))
         if (e%tie > 0 .or. e%coupling) cycle
         framed = .false.
         do t = 1, size(e%coef)
            if (frame_of_node(model, e%sub(t), e%node(t)) > 0) framed = .true.
         end do
       end associate
       if (framed) call equation_to_global(model, ie)
    end do
  end subroutine equations_to_global

  subroutine equation_to_global(model, ie)
    !! Equation ie with its terms in global axes, its dependent DOF first.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: ie
    type(equation_t) :: g
    integer :: t, f, b, d, j, m, best
    real(wp) :: q(3, 3)
    associate (e => model%equations(ie))
      m = 3*size(e%coef)
      allocate (g%sub(m), g%node(m), g%dof(m), g%coef(m))
      g%loc = e%loc
      m = 0
      do t = 1, size(e%coef)
         f = frame_of_node(model, e%sub(t), e%node(t))
         if (f == 0) then
            call add_term(g, m, e%sub(t), e%node(t), e%dof(t), e%coef(t))
            cycle
         end if
         q = model%frames(f)%q
         b = 3*((e%dof(t) - 1)/3)
         d = e%dof(t) - b
         do j = 1, 3
            if (q(d, j) /= 0.0_wp) call add_term(g, m, e%sub(t), e%node(t), b + j, e%coef(t)*q(d, j))
         end do
      end do
      best = 0
      do t = 1, m
         if (g%sub(t) /= e%sub(1) .or. g%node(t) /= e%node(1) .or. g%coef(t) == 0.0_wp) cycle
         if (dependent_before(model, ie, g, t)) cycle
         if (best == 0) then
            best = t
         else if (abs(g%coef(t)) > abs(g%coef(best))) then
            best = t
         end if
      end do
    end associate
    if (best > 1) then
       g%sub([1, best]) = g%sub([best, 1])
       g%node([1, best]) = g%node([best, 1])
       g%dof([1, best]) = g%dof([best, 1])
       g%coef([1, best]) = g%coef([best, 1])
    end if
    g%sub = g%sub(1:m)
    g%node = g%node(1:m)
    g%dof = g%dof(1:m)
    g%coef = g%coef(1:m)
    model%equations(ie) = g
  end subroutine equation_to_global

  subroutine add_term(g, m, isub, node, dof, coef)
    !! Append a term to g (m terms so far), or add it to the term of the same DOF.
    type(equation_t), intent(inout) :: g
    integer, intent(inout) :: m
    integer, intent(in) :: isub, dof
    integer(ip), intent(in) :: node
    real(wp), intent(in) :: coef
    integer :: t
    do t = 1, m
       if (g%sub(t) == isub .and. g%node(t) == node .and. g%dof(t) == dof) then
          g%coef(t) = g%coef(t) + coef
          return
       end if
    end do
    m = m + 1
    g%sub(m) = isub
    g%node(m) = node
    g%dof(m) = dof
    g%coef(m) = coef
  end subroutine add_term

  logical function dependent_before(model, ie, g, t)
    !! Term t of g is the dependent DOF of one of the equations before ie.
    type(model_t), intent(in) :: model
    integer, intent(in) :: ie, t
    type(equation_t), intent(in) :: g
    integer :: j
    dependent_before = .false.
    do j = 1, ie - 1
       if (same_dof(model%equations(j), 1, g, t)) dependent_before = .true.
    end do
  end function dependent_before

end module superjoin_deck_equation_build
