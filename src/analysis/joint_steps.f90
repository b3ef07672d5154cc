module superjoin_analysis_joint_steps
  !! Joint studies: steps whose contact stiffnesses differ (*CHANGE CONTACT).
  !!
  !! A wrapper around solve_model that does not touch the analysis itself: the
  !! steps are grouped by their set of link overrides; each group is solved as a
  !! model of its own (the model with the overrides applied to its links and only
  !! that group's steps), one factorization per group; the per-group results are
  !! merged into one results_t in the original step order. Without any
  !! *CHANGE CONTACT this is exactly solve_model.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, add_error_line
  use superjoin_model_types, only: model_t, link_override_t, string_t
  use superjoin_analysis, only: solve_model, solve_group, solve_context_t, release_cache
  use superjoin_model_results, only: results_t, run_options_t
  use superjoin_utils_strings, only: itoa
  use superjoin_model_notes, only: append_string
  use superjoin_analysis_step_groups, only: group_steps
  implicit none (type, external)
  private

  public :: solve_joint_steps, has_joint_changes, merge_results

contains

  pure logical function has_joint_changes(model)
    !! Whether some step changes contact stiffnesses.
    type(model_t), intent(in) :: model
    integer :: s
    has_joint_changes = .false.
    if (.not. allocated(model%steps)) return
    do s = 1, size(model%steps)
       if (allocated(model%steps(s)%link_overrides)) then
          if (size(model%steps(s)%link_overrides) > 0) has_joint_changes = .true.
       end if
    end do
  end function has_joint_changes

  subroutine solve_joint_steps(model, opts, res, error)
    !! Solve every step of a validated model, steps with *CHANGE CONTACT with
    !! their own contact stiffnesses (one factorization per distinct set).
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: group(:), members(:)
    logical, allocatable :: related(:, :)
    integer :: ngroup, s, t, g, nstep
    type(model_t) :: sub
    type(results_t) :: r
    type(solve_context_t) :: ctx

    if (.not. has_joint_changes(model)) then
       call solve_model(model, opts, res, error)
       return
    end if
    nstep = size(model%steps)
    allocate (related(nstep, nstep), source=.false.)
    do s = 1, nstep
       do t = 1, s - 1
          related(s, t) = same_overrides(model%steps(s)%link_overrides, model%steps(t)%link_overrides)
       end do
    end do
    call group_steps(related, group, ngroup)

    ! One context for all groups: the parts are condensed once and reused.
    ctx%joint_study = ngroup > 1
    do g = 1, ngroup
       members = pack([(s, s=1, nstep)], group == g)
       sub = model
       sub%steps = model%steps(members)
       do s = 1, size(sub%steps)
          if (allocated(sub%steps(s)%link_overrides)) deallocate (sub%steps(s)%link_overrides)
       end do
       call apply_overrides(model%steps(members(1))%link_overrides, sub)
       call solve_group(sub, opts, ctx, r, error)
       if (allocated(error)) then
          call release_cache(ctx%cache)
          call add_error_line(error, error%code, '  (while solving '//step_list(model, members)// &
               ' with their contact stiffnesses, *CHANGE CONTACT)')
          return
       end if
       call merge_results(r, members, nstep, g == 1, res)
       call note_group(model, members, res)
    end do
    call release_cache(ctx%cache)
    call append_string(res%log%notes, 'joint study (*CHANGE CONTACT): '//itoa(ngroup)// &
         ' sets of contact stiffnesses, '//itoa(ngroup)//' interface factorizations, '// &
         itoa(ctx%cache%computed)//' condensations computed and reused '//itoa(ctx%cache%reused)// &
         ' times; the counts above and MAXRATIO are the largest over them')
  end subroutine solve_joint_steps

  pure logical function same_overrides(a, b)
    !! Two steps change the same links to the same states.
    type(link_override_t), allocatable, intent(in) :: a(:), b(:)
    integer :: na, nb, i
    na = 0
    nb = 0
    if (allocated(a)) na = size(a)
    if (allocated(b)) nb = size(b)
    same_overrides = na == nb
    if (.not. same_overrides) return
    do i = 1, na
       if (a(i)%link /= b(i)%link .or. any(a(i)%dofs .neqv. b(i)%dofs) .or. &
            any(a(i)%state /= b(i)%state) .or. any(a(i)%g /= b(i)%g)) then
          same_overrides = .false.
          return
       end if
    end do
  end function same_overrides

  subroutine apply_overrides(list, sub)
    !! The links of sub with the overrides of list.
    type(link_override_t), allocatable, intent(in) :: list(:)
    type(model_t), intent(inout) :: sub
    integer :: i, d
    if (.not. allocated(list)) return
    do i = 1, size(list)
       associate (l => sub%links(list(i)%link))
         do d = 1, size(list(i)%dofs)
            if (.not. list(i)%dofs(d)) cycle
            l%state(d) = list(i)%state(d)
            l%g(d) = list(i)%g(d)
         end do
       end associate
    end do
  end subroutine apply_overrides

  subroutine merge_results(r, members, nstep, first, res)
    !! Put the results r of the steps `members` into res (nstep steps in all).
    type(results_t), intent(in) :: r
    integer, intent(in) :: members(:), nstep
    logical, intent(in) :: first
    type(results_t), intent(inout) :: res
    integer :: k, i
    if (first) then
       res = r
       if (allocated(r%fields%u)) then
          deallocate (res%fields%u)
          allocate (res%fields%u(size(r%fields%u, 1), nstep))
          res%fields%u = 0.0_wp
       end if
       if (allocated(r%fields%elem_force)) then
          deallocate (res%fields%elem_force)
          allocate (res%fields%elem_force(size(r%fields%elem_force, 1), size(r%fields%elem_force, 2), size(r%fields%elem_force, 3), nstep))
          res%fields%elem_force = 0.0_wp
       end if
       if (allocated(r%fields%plate)) then
          deallocate (res%fields%plate)
          allocate (res%fields%plate(size(r%fields%plate, 1), size(r%fields%plate, 2), nstep))
          res%fields%plate = 0.0_wp
       end if
       deallocate (res%fields%steps)
       allocate (res%fields%steps(nstep))
    else
       res%summary%nphys = max(res%summary%nphys, r%summary%nphys)
       res%summary%ncol = max(res%summary%ncol, r%summary%ncol)
       res%summary%neq = max(res%summary%neq, r%summary%neq)
       res%summary%ndelta = max(res%summary%ndelta, r%summary%ndelta)
       res%summary%matrix_nnz = max(res%summary%matrix_nnz, r%summary%matrix_nnz)
       res%summary%factor_nnz = max(res%summary%factor_nnz, r%summary%factor_nnz)
       res%summary%n_tree = max(res%summary%n_tree, r%summary%n_tree)
       res%summary%n_plain = max(res%summary%n_plain, r%summary%n_plain)
       res%summary%n_support_units = max(res%summary%n_support_units, r%summary%n_support_units)
       res%summary%sub_dofs = max(res%summary%sub_dofs, r%summary%sub_dofs)
       res%summary%sub_boundary = max(res%summary%sub_boundary, r%summary%sub_boundary)
       res%fields%has_dof = res%fields%has_dof .or. r%fields%has_dof
       res%fields%link_used = res%fields%link_used .or. r%fields%link_used
       if (r%summary%maxratio > res%summary%maxratio) then
          res%summary%maxratio = r%summary%maxratio
          res%summary%maxratio_at = r%summary%maxratio_at
       end if
       res%summary%cond_est = max(res%summary%cond_est, r%summary%cond_est)
       res%log%phase_seconds = res%log%phase_seconds + r%log%phase_seconds
       res%summary%factor_mbytes = max(res%summary%factor_mbytes, r%summary%factor_mbytes)
       do i = 1, size(r%log%notes)
          if (.not. any_string(res%log%notes, r%log%notes(i)%s)) call append_string(res%log%notes, r%log%notes(i)%s)
       end do
       do i = 1, size(r%log%warnings)
          if (.not. any_string(res%log%warnings, r%log%warnings(i)%s)) call append_string(res%log%warnings, r%log%warnings(i)%s)
       end do
    end if
    do k = 1, size(members)
       if (allocated(r%fields%u)) res%fields%u(:, members(k)) = r%fields%u(:, k)
       if (allocated(r%fields%elem_force)) res%fields%elem_force(:, :, :, members(k)) = r%fields%elem_force(:, :, :, k)
       if (allocated(r%fields%plate)) res%fields%plate(:, :, members(k)) = r%fields%plate(:, :, k)
       res%fields%steps(members(k)) = r%fields%steps(k)
    end do
  end subroutine merge_results

  pure logical function any_string(list, s)
    type(string_t), allocatable, intent(in) :: list(:)
    character(*), intent(in) :: s
    integer :: i
    any_string = .false.
    if (.not. allocated(list)) return
    do i = 1, size(list)
       if (list(i)%s == s) any_string = .true.
    end do
  end function any_string

  subroutine note_group(model, members, res)
    !! A listing note naming the steps of one group and what they change.
    type(model_t), intent(in) :: model
    integer, intent(in) :: members(:)
    type(results_t), intent(inout) :: res
    character(:), allocatable :: text
    integer :: n
    n = 0
    if (allocated(model%steps(members(1))%link_overrides)) n = size(model%steps(members(1))%link_overrides)
    text = step_list(model, members)
    if (n == 0) then
       text = text//': contact stiffnesses as defined'
    else
       text = text//': *CHANGE CONTACT on '//itoa(n)//' contact element(s)'
    end if
    call append_string(res%log%notes, text)
  end subroutine note_group

  function step_list(model, members) result(text)
    !! 'steps A B C' for messages.
    type(model_t), intent(in) :: model
    integer, intent(in) :: members(:)
    character(:), allocatable :: text
    integer :: k
    text = 'steps'
    do k = 1, size(members)
       text = text//' '//model%steps(members(k))%name
    end do
  end function step_list
end module superjoin_analysis_joint_steps
