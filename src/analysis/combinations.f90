module superjoin_analysis_combinations
  !! Load combinations (*LOAD COMBINATION, superjoin's extension, as Nastran's
  !! SUBCOM): the results of a combination are Σ factor × results of solved
  !! steps, with no new solve (linear statics superposes exactly). Each
  !! combination becomes one more step of the model and of the results, after
  !! the solved steps, so that the listing, the CSV and VTK files and the
  !! output requests treat it as a step; model%steps(k)%combination says which.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: model_t, step_t
  use superjoin_model_results, only: results_t, step_results_t, reaction_t
  use superjoin_model_notes, only: append_string
  use superjoin_analysis_health, only: check_finite
  use superjoin_error, only: error_t
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use superjoin_analysis_body_loads, only: superpose_thermal
  implicit none (type, external)
  private

  public :: add_combinations, combination_text

contains

  subroutine add_combinations(model, res, error)
    !! Append the results of every load combination of the model as steps;
    !! results that overflow the floating-point range end the run
    !! (EXIT_SINGULAR, as for a solved step; halting on overflow is off meanwhile).
    type(model_t), intent(inout) :: model
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    type(halting_t) :: saved
    if (.not. allocated(model%combinations)) return
    if (size(model%combinations) == 0) return
    call halting_off(saved)
    call superpose(model, res)
    call halting_restore(saved)
    call check_finite(model, res, error)
  end subroutine add_combinations

  subroutine superpose(model, res)
    !! The work of add_combinations.
    type(model_t), intent(inout) :: model
    type(results_t), intent(inout) :: res
    type(step_t), allocatable :: steps(:)
    type(step_results_t), allocatable :: sres(:)
    real(wp), allocatable :: u(:, :), ef(:, :, :, :), pl(:, :, :)
    integer :: ns, nc, c, k, j
    if (.not. allocated(model%combinations)) return
    nc = size(model%combinations)
    if (nc == 0) return
    ns = size(model%steps)
    allocate (steps(ns + nc), sres(ns + nc))
    steps(1:ns) = model%steps
    sres(1:ns) = res%fields%steps(1:ns)
    if (allocated(res%fields%u)) then
       allocate (u(size(res%fields%u, 1), ns + nc), source=0.0_wp)
       u(:, 1:ns) = res%fields%u
    end if
    if (allocated(res%fields%elem_force)) then
       allocate (ef(size(res%fields%elem_force, 1), size(res%fields%elem_force, 2), size(res%fields%elem_force, 3), ns + nc), source=0.0_wp)
       ef(:, :, :, 1:ns) = res%fields%elem_force
    end if
    if (allocated(res%fields%plate)) then
       allocate (pl(size(res%fields%plate, 1), size(res%fields%plate, 2), ns + nc), source=0.0_wp)
       pl(:, :, 1:ns) = res%fields%plate
    end if
    do c = 1, nc
       associate (cb => model%combinations(c))
         steps(ns + c)%name = cb%name
         steps(ns + c)%loc = cb%loc
         steps(ns + c)%combination = c
         allocate (steps(ns + c)%cloads(0), steps(ns + c)%dloads(0))
         call combine_step(res%fields%steps, cb%steps, cb%factors, sres(ns + c))
         do k = 1, size(cb%steps)
            j = cb%steps(k)
            if (allocated(res%fields%steps(j)%failure) .and. .not. allocated(sres(ns + c)%failure)) &
                 sres(ns + c)%failure = 'error: step '//model%steps(j)%name//' of this combination was not solved'
            if (allocated(u)) u(:, ns + c) = u(:, ns + c) + cb%factors(k)*u(:, j)
            if (allocated(ef)) ef(:, :, :, ns + c) = ef(:, :, :, ns + c) + cb%factors(k)*ef(:, :, :, j)
            if (allocated(pl)) pl(:, :, ns + c) = pl(:, :, ns + c) + cb%factors(k)*pl(:, :, j)
         end do
         call append_string(res%log%notes, 'load combination '//cb%name//' = '//combination_text(model, c)// &
              ' (results superposed, no solve)')
       end associate
    end do
    call combine_warnings(model, ns, res)
    call move_alloc(steps, model%steps)
    call move_alloc(sres, res%fields%steps)
    if (allocated(u)) call move_alloc(u, res%fields%u)
    if (allocated(ef)) call move_alloc(ef, res%fields%elem_force)
    if (allocated(pl)) call move_alloc(pl, res%fields%plate)
    call superpose_thermal(model%combinations, ns, res%fields%thermal)
    call superpose_thermal(model%combinations, ns, res%fields%thermal_nodal)
    call superpose_thermal(model%combinations, ns, res%fields%thermal_curvature_nodal)
  end subroutine superpose

  subroutine combine_warnings(model, ns, res)
    !! A combination inherits the warnings of its steps (its health figures
    !! are theirs): each warning on steps gets one flag per combination, set
    !! when it concerns one of the combination's steps (the ns solved ones).
    type(model_t), intent(in) :: model
    integer, intent(in) :: ns
    type(results_t), intent(inout) :: res
    integer :: i, c
    if (.not. allocated(res%log%warnings)) return
    do i = 1, size(res%log%warnings)
       associate (w => res%log%warnings(i))
         if (.not. allocated(w%steps)) cycle
         w%steps = [w%steps(1:ns), (any(w%steps(model%combinations(c)%steps)), c=1, size(model%combinations))]
       end associate
    end do
  end subroutine combine_warnings

  function combination_text(model, c) result(text)
    !! '1.35 G + 1.5 Q' for combination c (factors in shortest exact form).
    type(model_t), intent(in) :: model
    integer, intent(in) :: c
    character(:), allocatable :: text
    integer :: k
    text = ''
    associate (cb => model%combinations(c))
      do k = 1, size(cb%steps)
         if (k == 1) then
            if (cb%factors(k) < 0.0_wp) text = '-'
         else
            text = text//merge(' - ', ' + ', cb%factors(k) < 0.0_wp)
         end if
         text = text//short_real(abs(cb%factors(k)))//' '//model%steps(cb%steps(k))%name
      end do
    end associate
  end function combination_text

  function short_real(x) result(t)
    !! The shortest text of x that reads back as x ('1.35', '2', '1.5E-08').
    real(wp), intent(in) :: x
    character(:), allocatable :: t
    character(len=40) :: buf, fmt
    real(wp) :: y
    integer :: d, stat, last
    do d = 1, 17
       write (fmt, '(a,i0,a,i0,a)') '(es', d + 8, '.', d - 1, 'e3)'
       write (buf, fmt) x
       read (buf, *, iostat=stat) y
       if (stat == 0 .and. y == x) exit
    end do
    t = trim(adjustl(buf))
    if (x >= 1.0e-3_wp .and. x < 1.0e7_wp) then
       ! the same digits in fixed notation, without trailing zeros
       do d = 0, 17
          write (fmt, '(a,i0,a)') '(f0.', d, ')'
          write (buf, fmt) x
          read (buf, *, iostat=stat) y
          if (stat == 0 .and. y == x) exit
       end do
       t = trim(adjustl(buf))
       if (t(1:1) == '.') t = '0'//t
       last = len(t)
       if (t(last:last) == '.') t = t(1:last - 1)
    end if
  end function short_real

  subroutine combine_step(steps, idx, factors, out)
    !! The per-step results of a combination: reactions (union of the
    !! constituents' supports, by node and DOF), contact deltas and forces, load
    !! and reaction resultants superposed; the health figures (residuals,
    !! EPSILON, MAXRATIO and condition estimate) are the largest of the
    !! constituents'.
    type(step_results_t), intent(in) :: steps(:)
    integer, intent(in) :: idx(:)
    real(wp), intent(in) :: factors(:)
    type(step_results_t), intent(out) :: out
    integer :: k
    allocate (out%reactions(0))
    do k = 1, size(idx)
       associate (st => steps(idx(k)))
         call add_reactions(out%reactions, st%reactions, factors(k))
         if (allocated(st%equation_forces)) then
            if (.not. allocated(out%equation_forces)) allocate (out%equation_forces(0))
            call add_reactions(out%equation_forces, st%equation_forces, factors(k))
         end if
         if (allocated(st%link_delta)) then
            if (.not. allocated(out%link_delta)) then
               allocate (out%link_delta, mold=st%link_delta)
               allocate (out%link_force, mold=st%link_force)
               out%link_delta = 0.0_wp
               out%link_force = 0.0_wp
            end if
            out%link_delta = out%link_delta + factors(k)*st%link_delta
            out%link_force = out%link_force + factors(k)*st%link_force
         end if
         out%applied = out%applied + factors(k)*st%applied
         out%reaction = out%reaction + factors(k)*st%reaction
         out%residual = max(out%residual, st%residual)
         out%residual0 = max(out%residual0, st%residual0)
         out%epsilon = max(out%epsilon, abs(st%epsilon))
         if (allocated(st%maxratio_at) .and. (st%maxratio > out%maxratio .or. .not. allocated(out%maxratio_at))) then
            out%maxratio = st%maxratio
            out%maxratio_at = st%maxratio_at
         end if
         out%cond_est = max(out%cond_est, st%cond_est)
         out%cond_bound = out%cond_bound .or. st%cond_bound   ! a bound among them: the largest is no estimate
       end associate
    end do
  end subroutine combine_step

  subroutine add_reactions(list, add, factor)
    !! list += factor × add, matching reactions by substructure, node and DOF.
    type(reaction_t), allocatable, intent(inout) :: list(:)
    type(reaction_t), intent(in) :: add(:)
    real(wp), intent(in) :: factor
    type(reaction_t), allocatable :: extra(:)
    integer :: i, j, n
    logical :: found
    if (size(list) == size(add)) then
       if (all(list%sub == add%sub .and. list%node == add%node .and. list%dof == add%dof)) then
          list%force = list%force + factor*add%force
          return
       end if
    end if
    allocate (extra(size(add)))
    n = 0
    do i = 1, size(add)
       found = .false.
       do j = 1, size(list)
          if (list(j)%sub == add(i)%sub .and. list(j)%node == add(i)%node .and. list(j)%dof == add(i)%dof) then
             list(j)%force = list(j)%force + factor*add(i)%force
             found = .true.
             exit
          end if
       end do
       if (.not. found) then
          n = n + 1
          extra(n) = add(i)
          extra(n)%force = factor*add(i)%force
       end if
    end do
    if (n > 0) list = [list, extra(1:n)]
  end subroutine add_reactions
end module superjoin_analysis_combinations
