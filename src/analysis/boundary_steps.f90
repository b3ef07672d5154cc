module superjoin_analysis_boundary_steps
  !! Steps with boundary conditions of their own (*BOUNDARY inside *STEP).
  !!
  !! A wrapper around solve_joint_steps that does not touch the analysis
  !! itself: the steps are grouped by the supports in effect (which DOFs are
  !! fixed and their prescribed values: the Δu transform carries one vector of
  !! prescribed values); each group is solved as a model of its own (the model
  !! with that group's supports and only its steps), one factorization per
  !! group and per set of contact stiffnesses; the results are merged in the
  !! original step order. Steps that differ only in their loads share a
  !! solve; groups that fix the same DOFs with other prescribed values are
  !! solved one after the other and reuse the factorization (analysis/
  !! factor_reuse: the matrix is the same). Without a step-level *BOUNDARY
  !! this is exactly solve_joint_steps.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, add_error_line
  use superjoin_model_types, only: model_t, support_t
  use superjoin_analysis_joint_steps, only: solve_joint_steps, merge_results, has_joint_changes
  use superjoin_analysis, only: solve_group, solve_context_t, release_cache
  use superjoin_analysis_factor_reuse, only: release_factor
  use superjoin_model_results, only: results_t, run_options_t
  use superjoin_model_notes, only: append_string
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_sorting, only: stable_argsort
  use superjoin_analysis_step_groups, only: group_steps
  implicit none (type, external)
  private

  public :: solve_steps, has_step_boundaries, same_supports

contains

  pure logical function has_step_boundaries(model)
    !! Whether the steps carry supports of their own (a *BOUNDARY inside *STEP).
    type(model_t), intent(in) :: model
    has_step_boundaries = .false.
    if (.not. allocated(model%steps)) return
    if (size(model%steps) == 0) return
    has_step_boundaries = allocated(model%steps(1)%supports)
  end function has_step_boundaries

  subroutine solve_steps(model, opts, res, error)
    !! Solve every step of a validated model with the supports in effect in it
    !! (one factorization per distinct set of supports and contact stiffnesses).
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: group(:), members(:), order(:)
    logical, allocatable :: related(:, :)
    integer :: ngroup, s, t, g, nstep, k
    type(model_t) :: sub
    type(results_t) :: r
    type(solve_context_t) :: ctx
    logical :: joint

    if (.not. has_step_boundaries(model)) then
       call solve_joint_steps(model, opts, res, error)
       return
    end if
    nstep = size(model%steps)
    allocate (related(nstep, nstep), source=.false.)
    do s = 1, nstep
       do t = 1, s - 1
          related(s, t) = same_supports(model%steps(s)%supports, model%steps(t)%supports)
       end do
    end do
    call group_steps(related, group, ngroup)
    if (ngroup == 1) then
       sub = model
       sub%supports = model%steps(1)%supports
       call solve_joint_steps(sub, opts, res, error)
       if (allocated(error)) return
       call append_string(res%log%notes, 'boundary conditions (*BOUNDARY in steps): the same in every step, '// &
            itoa(size(sub%supports))//' supported DOFs')
       return
    end if

    ! Groups that fix the same DOFs (other prescribed values) one after the
    ! other: their matrices are the same, and each solve keeps its
    ! factorization for the next (without *CHANGE CONTACT, whose own
    ! grouping runs inside solve_joint_steps).
    order = fixed_set_order(model, group, ngroup)
    joint = has_joint_changes(model)
    ctx%factor%keep = .not. joint
    do k = 1, ngroup
       g = order(k)
       members = pack([(s, s=1, nstep)], group == g)
       sub = model
       sub%supports = model%steps(members(1))%supports
       sub%steps = model%steps(members)
       if (joint) then
          call solve_joint_steps(sub, opts, r, error)
       else
          call solve_group(sub, opts, ctx, r, error)
       end if
       if (allocated(error)) then
          call release_factor(ctx%factor)
          call release_cache(ctx%cache)
          call add_error_line(error, error%code, '  (while solving '//step_list(model, members)// &
               ' with their boundary conditions, *BOUNDARY)')
          return
       end if
       call merge_results(r, members, nstep, k == 1, res)
       call append_string(res%log%notes, step_list(model, members)//': '//itoa(size(sub%supports))// &
            ' supported DOFs'//prescribed_text(sub%supports))
    end do
    call release_factor(ctx%factor)
    call release_cache(ctx%cache)
    call append_string(res%log%notes, 'boundary conditions (*BOUNDARY in steps): '//itoa(ngroup)// &
         ' sets of supports, '//itoa(ngroup - ctx%factor%reuses)//' factorizations ('// &
         itoa(ctx%factor%reuses)//' reused: only prescribed values changed); the counts above and '// &
         'MAXRATIO are the largest over them')
  end subroutine solve_steps

  function fixed_set_order(model, group, ngroup) result(order)
    !! The groups in an order that puts those fixing the same DOFs (in the same
    !! states, with other prescribed values) next to each other, by first appearance.
    type(model_t), intent(in) :: model
    integer, intent(in) :: group(:), ngroup
    integer :: order(ngroup)
    integer :: first(ngroup), cls(ngroup), g, h, n, c
    do g = 1, ngroup
       first(g) = findloc(group, g, dim=1)
    end do
    do g = 1, ngroup
       cls(g) = g
       do h = 1, g - 1
          if (same_supports(model%steps(first(g))%supports, model%steps(first(h))%supports, &
               values=.false.)) then
             cls(g) = cls(h)
             exit
          end if
       end do
    end do
    n = 0
    do c = 1, ngroup
       do g = 1, ngroup
          if (cls(g) /= c) cycle
          n = n + 1
          order(n) = g
       end do
    end do
  end function fixed_set_order

  logical function same_supports(a, b, values)
    !! Two lists of supports are the same constraint (same DOFs, states,
    !! stiffnesses and, unless values is false, prescribed values; in any order:
    !! the lists of consecutive steps mostly share their order, else both are
    !! sorted by substructure, node and DOF).
    type(support_t), intent(in) :: a(:), b(:)
    logical, intent(in), optional :: values
    integer, allocatable :: oa(:), ob(:)
    integer :: i
    logical :: with_values
    with_values = .true.
    if (present(values)) with_values = values
    same_supports = size(a) == size(b)
    if (.not. same_supports) return
    do i = 1, size(a)
       if (.not. same_support(a(i), b(i), with_values)) exit
    end do
    if (i > size(a)) return
    call dof_order(a, oa)
    call dof_order(b, ob)
    do i = 1, size(a)
       if (.not. same_support(a(oa(i)), b(ob(i)), with_values)) then
          same_supports = .false.
          return
       end if
    end do
  end function same_supports

  subroutine dof_order(list, order)
    !! Indices that sort list by substructure, node and DOF (stable sorts from
    !! the last key to the first).
    type(support_t), intent(in) :: list(:)
    integer, allocatable, intent(out) :: order(:)
    integer :: i
    order = [(i, i=1, size(list))]
    call stable_argsort(real(list%dof, wp), order)
    call stable_argsort(real(list%node, wp), order)
    call stable_argsort(real(list%sub, wp), order)
  end subroutine dof_order

  pure logical function same_support(a, b, with_values)
    type(support_t), intent(in) :: a, b
    logical, intent(in) :: with_values
    same_support = a%sub == b%sub .and. a%node == b%node .and. a%dof == b%dof .and. &
         a%state == b%state .and. a%g == b%g
    if (with_values) same_support = same_support .and. a%value == b%value
  end function same_support

  function prescribed_text(list) result(text)
    !! ', n with prescribed displacements' when some supports prescribe one.
    type(support_t), intent(in) :: list(:)
    character(:), allocatable :: text
    integer :: n
    n = count(list%value /= 0.0_wp)
    text = ''
    if (n > 0) text = ', '//itoa(n)//' with prescribed displacements'
  end function prescribed_text

  function step_list(model, members) result(text)
    !! 'steps A B C' for messages.
    type(model_t), intent(in) :: model
    integer, intent(in) :: members(:)
    character(:), allocatable :: text
    integer :: k
    text = merge('steps', 'step ', size(members) > 1)
    text = trim(text)
    do k = 1, size(members)
       text = text//' '//model%steps(members(k))%name
    end do
  end function step_list
end module superjoin_analysis_boundary_steps
