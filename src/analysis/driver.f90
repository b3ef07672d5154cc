module superjoin_analysis_driver
  !! The driver of a run: every step of a validated model, grouped once by
  !! the supports in effect (*BOUNDARY inside *STEP: which DOFs are fixed and
  !! their prescribed values, the Δu transform carries one vector of them)
  !! and by the contact stiffnesses (*CHANGE CONTACT: the set of link
  !! overrides). Each group is solved as a model of its own (the model with
  !! that group's supports and overrides and only its steps: analysis.f90's
  !! solve_group, one factorization per group) and the results are merged in
  !! the original step order.
  !!
  !! Supports: steps that differ only in their loads share a solve; groups
  !! that fix the same DOFs with other prescribed values are solved one after
  !! the other and reuse the factorization (analysis/factor_reuse: the matrix
  !! is the same). Contact stiffnesses: within one set of supports, the
  !! groups share one solve context, so the condensed parts are condensed
  !! once and reused. Without step-level *BOUNDARY and *CHANGE CONTACT this
  !! is exactly solve_model.
  !!
  !! *BOUNDARY, FIXED (analysis/held_supports): the groups are solved in their
  !! order of first appearance, each after the steps it holds to, and its held
  !! values are filled in from the results merged so far.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, add_error_line, fatal_error, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, support_t, link_override_t, string_t, step_t, link_t, &
       LINK_NONE, LINK_FINITE
  use superjoin_analysis, only: solve_model, solve_group, solve_context_t, release_cache
  use superjoin_analysis_factor_reuse, only: release_factor
  use superjoin_model_results, only: results_t, run_options_t, step_results_t
  use superjoin_model_notes, only: append_string, add_warning
  use superjoin_model_request_notes, only: unproduced_file_variables
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_sorting, only: sort_index
  use superjoin_analysis_step_groups, only: group_steps
  use superjoin_analysis_held_supports, only: has_held, held_sources, fill_held
  implicit none (type, external)
  private

  public :: solve_steps, has_step_boundaries, has_joint_changes, partial_results

  type :: step_grouping_t
    !! The steps grouped once: by supports (their own *BOUNDARY) and by
    !! contact stiffnesses (*CHANGE CONTACT), each numbered over all steps in
    !! order of first appearance.
     integer, allocatable :: supports(:)   !! group of supports of every step
     integer :: nsupports = 1
     integer, allocatable :: joints(:)     !! group of contact stiffnesses of every step
  end type step_grouping_t

  type :: swap_t
    !! What enter_group took out of the model while a group is solved.
     type(step_t), allocatable :: steps(:)
     type(support_t), allocatable :: supports(:)
     type(link_t), allocatable :: links(:)
     logical :: supports_swapped = .false.
     logical :: links_swapped = .false.
  end type swap_t

  type :: failures_t
    !! The groups of steps that could not be solved (exit 3) while the others
    !! go on: the first error, its mechanism mode, the message of every failed step.
     type(error_t), allocatable :: first
     real(wp), allocatable :: mechanism(:, :)
     type(string_t), allocatable :: message(:)   !! (nstep) unallocated text: solved or in r
     logical :: solved = .false.                 !! some group solved: res holds results
  end type failures_t

contains

  logical function partial_results(res)
    !! Whether res holds the results of some steps and failures of others
    !! (the listing and CSV are written, the run exits 3).
    type(results_t), intent(in) :: res
    integer :: s
    partial_results = .false.
    if (.not. allocated(res%fields%steps)) return
    do s = 1, size(res%fields%steps)
       if (allocated(res%fields%steps(s)%failure)) partial_results = .true.
    end do
  end function partial_results

  logical function keep_going(fail, members, nstep, r, res, error) result(going)
    !! After a group's error: a mechanism or singular stiffness (exit 3) is
    !! recorded against the group's steps (r: a nested solve's own partial
    !! results, merged) and the other groups go on; any other error ends the run.
    type(failures_t), intent(inout) :: fail
    integer, intent(in) :: members(:), nstep
    type(results_t), intent(in) :: r
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(inout) :: error
    integer :: k
    going = error%code == EXIT_SINGULAR
    if (.not. going) return
    if (.not. allocated(fail%message)) allocate (fail%message(nstep))
    if (partial_results(r)) then
       call merge_results(r, members, nstep, .not. fail%solved, res)
       fail%solved = .true.
    else
       do k = 1, size(members)
          fail%message(members(k))%s = error%message
       end do
    end if
    if (.not. allocated(fail%first)) then
       call move_alloc(error, fail%first)
       if (allocated(r%fields%mechanism)) fail%mechanism = r%fields%mechanism
    else
       deallocate (error)
    end if
  end function keep_going

  subroutine finish_failures(fail, res, error)
    !! The failed steps into res (zero results, their message) and the first
    !! error back; with no step solved, only the error (as a single solve).
    type(failures_t), intent(inout) :: fail
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(inout) :: error
    type(step_results_t) :: zero
    integer :: s
    if (.not. allocated(fail%first)) return
    call move_alloc(fail%first, error)
    if (.not. fail%solved) return
    do s = 1, size(res%fields%steps)
       if (.not. allocated(res%fields%steps(s)%failure) .and. .not. allocated(fail%message(s)%s)) zero = res%fields%steps(s)
    end do
    if (allocated(zero%link_delta)) zero%link_delta = 0.0_wp
    if (allocated(zero%link_force)) zero%link_force = 0.0_wp
    if (allocated(zero%reactions)) zero%reactions%force = 0.0_wp
    zero%applied = 0.0_wp
    zero%reaction = 0.0_wp
    zero%residual = 0.0_wp
    zero%epsilon = 0.0_wp
    zero%residual0 = 0.0_wp
    zero%refinements = 0
    zero%refine_tried = 0
    zero%maxratio = 0.0_wp   ! not solved: no matrix of its own
    zero%cond_est = 0.0_wp
    zero%cond_bound = .false.
    if (allocated(zero%maxratio_at)) deallocate (zero%maxratio_at)
    do s = 1, size(res%fields%steps)
       if (.not. allocated(fail%message(s)%s)) cycle
       res%fields%steps(s) = zero
       res%fields%steps(s)%failure = fail%message(s)%s
    end do
    if (allocated(fail%mechanism)) res%fields%mechanism = fail%mechanism
  end subroutine finish_failures

  pure logical function has_step_boundaries(model)
    !! Whether the steps carry supports of their own (a *BOUNDARY inside *STEP).
    type(model_t), intent(in) :: model
    has_step_boundaries = .false.
    if (.not. allocated(model%steps)) return
    if (size(model%steps) == 0) return
    has_step_boundaries = allocated(model%steps(1)%supports)
  end function has_step_boundaries

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

  subroutine solve_steps(model, opts, res, error)
    !! Solve every step of a validated model with the supports and contact
    !! stiffnesses in effect in it (one factorization per distinct set).
    !! Each group is solved on model itself, its steps, supports and links
    !! swapped for the group's meanwhile (no copy of the model): model ends
    !! as it came.
    type(model_t), intent(inout) :: model
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    type(step_grouping_t) :: grouping
    type(swap_t) :: swap
    integer :: s, nsupported
    type(link_t), allocatable :: links(:)

    call group_once(model, grouping)
    if (.not. has_step_boundaries(model)) then
       call solve_joint_groups(model, grouping%joints, opts, res, error)
    else if (grouping%nsupports == 1) then
       call enter_group(model, [(s, s=1, size(model%steps))], swap, supports=.true.)
       nsupported = size(model%supports)
       call solve_joint_groups(model, grouping%joints, opts, res, error)
       call leave_group(model, swap)
       if (allocated(error)) return
       call append_string(res%log%notes, 'boundary conditions (*BOUNDARY in steps): the same in every step, '// &
            itoa(nsupported)//' supported DOFs')
    else
       if (has_joint_changes(model)) then
          ! DOFs named by the steps of other sets of supports too (see keep_named_dofs)
          links = model%links
          call keep_named_dofs(model%steps, model)
       end if
       call solve_support_groups(model, grouping, opts, res, error)
       if (allocated(links)) call move_alloc(links, model%links)
    end if
    if (allocated(error)) return
    if (len(unproduced_file_variables(model)) > 0) call append_string(res%log%notes, unproduced_file_variables(model))
    if (allocated(model%notes)) then   ! the reader's (which reading of a card it took)
       do s = 1, size(model%notes)
          call append_string(res%log%notes, model%notes(s)%s)
       end do
    end if
  end subroutine solve_steps

  subroutine enter_group(model, members, swap, supports, links)
    !! model becomes the model of the steps members: only those steps, with
    !! supports the first one's (supports) or with the first one's contact
    !! overrides applied to the links and none left in the steps (links).
    !! What it replaces goes to swap, for leave_group.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: members(:)
    type(swap_t), intent(out) :: swap
    logical, intent(in), optional :: supports, links
    type(link_override_t), allocatable :: overrides(:)
    integer :: s
    call move_alloc(model%steps, swap%steps)
    model%steps = swap%steps(members)
    swap%supports_swapped = .false.
    if (present(supports)) swap%supports_swapped = supports
    if (swap%supports_swapped) then
       call move_alloc(model%supports, swap%supports)
       model%supports = model%steps(1)%supports
    end if
    swap%links_swapped = .false.
    if (present(links)) swap%links_swapped = links
    if (swap%links_swapped) then
       swap%links = model%links
       if (allocated(model%steps(1)%link_overrides)) then
          overrides = model%steps(1)%link_overrides
          call apply_overrides(overrides, model)
       end if
       call keep_named_dofs(swap%steps, model)
       do s = 1, size(model%steps)
          if (allocated(model%steps(s)%link_overrides)) deallocate (model%steps(s)%link_overrides)
       end do
    end if
  end subroutine enter_group

  subroutine leave_group(model, swap)
    !! model as it was before enter_group.
    type(model_t), intent(inout) :: model
    type(swap_t), intent(inout) :: swap
    call move_alloc(swap%steps, model%steps)
    if (swap%supports_swapped) call move_alloc(swap%supports, model%supports)
    if (swap%links_swapped) call move_alloc(swap%links, model%links)
  end subroutine leave_group

  subroutine group_once(model, grouping)
    !! The steps' groups of supports and of contact stiffnesses.
    type(model_t), intent(in) :: model
    type(step_grouping_t), intent(out) :: grouping
    logical, allocatable :: same_s(:, :), same_j(:, :)
    integer :: s, t, nstep, njoint
    nstep = size(model%steps)
    allocate (same_s(nstep, nstep), same_j(nstep, nstep), source=.false.)
    do s = 1, nstep
       do t = 1, s - 1
          if (has_step_boundaries(model)) &
               same_s(s, t) = same_supports(model%steps(s)%supports, model%steps(t)%supports)
          same_j(s, t) = same_overrides(model%steps(s)%link_overrides, model%steps(t)%link_overrides)
       end do
    end do
    if (has_step_boundaries(model)) then
       call group_steps(same_s, grouping%supports, grouping%nsupports)
    else
       allocate (grouping%supports(nstep), source=1)
    end if
    call group_steps(same_j, grouping%joints, njoint)
  end subroutine group_once

  subroutine solve_support_groups(model, grouping, opts, res, error)
    !! Several sets of supports: each group of steps solved with its own, in
    !! an order that puts the groups fixing the same DOFs next to each other
    !! (their matrices are the same, and each solve keeps its factorization
    !! for the next; not with *CHANGE CONTACT, whose groups share the
    !! condensations instead).
    type(model_t), intent(inout) :: model
    type(step_grouping_t), intent(in) :: grouping
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: members(:), order(:)
    integer :: s, g, k, nstep, ngroup
    type(swap_t) :: swap
    type(results_t) :: r
    character(:), allocatable :: text
    type(results_t) :: r0   ! no results: a group whose held displacements are missing
    type(solve_context_t) :: ctx
    logical :: joint, held
    type(failures_t) :: fail

    nstep = size(model%steps)
    ngroup = grouping%nsupports
    held = has_held(model)
    if (held) then   ! *BOUNDARY, FIXED: each group after the steps it holds to
       order = [(g, g=1, ngroup)]
    else
       order = fixed_set_order(model, grouping%supports, ngroup)
    end if
    joint = has_joint_changes(model)
    ctx%factor%keep = .not. joint
    do k = 1, ngroup
       g = order(k)
       members = pack([(s, s=1, nstep)], grouping%supports == g)
       if (held) then
          call hold_group(model, members, fail, res, error)
          if (allocated(error)) then
             if (keep_going(fail, members, nstep, r0, res, error)) cycle
             call release_factor(ctx%factor)
             call release_cache(ctx%cache)
             return
          end if
       end if
       call enter_group(model, members, swap, supports=.true.)
       text = ': '//itoa(size(model%supports))//' supported DOFs'//prescribed_text(model%supports)
       if (joint) then
          call solve_joint_groups(model, grouping%joints(members), opts, r, error)
       else
          ctx%last = k == ngroup
          call solve_group(model, opts, ctx, r, error)
       end if
       call leave_group(model, swap)
       if (allocated(error)) then
          call release_factor(ctx%factor)
          call add_error_line(error, error%code, '  (while solving '//step_list(model, members, .false.)// &
               ' with their boundary conditions, *BOUNDARY)')
          if (keep_going(fail, members, nstep, r, res, error)) cycle
          call release_cache(ctx%cache)
          return
       end if
       call merge_results(r, members, nstep, .not. fail%solved, res)
       fail%solved = .true.
       call append_string(res%log%notes, step_list(model, members, .false.)//text)
    end do
    call finish_failures(fail, res, error)
    call release_factor(ctx%factor)
    call release_cache(ctx%cache)
    call append_string(res%log%notes, 'boundary conditions (*BOUNDARY in steps): '//itoa(ngroup)// &
         ' sets of supports, '//itoa(ngroup - ctx%factor%reuses)//' factorizations ('// &
         itoa(ctx%factor%reuses)//' reused: only prescribed values changed); the counts above are the '// &
         'largest over them, each step''s NUMERICAL HEALTH that of its own factorization')
  end subroutine solve_support_groups

  subroutine solve_joint_groups(model, joints, opts, res, error)
    !! Solve every step of model (one set of supports), steps with *CHANGE
    !! CONTACT with their own contact stiffnesses: joints(s) is the group of
    !! contact stiffnesses of step s (numbered over the whole run). One
    !! context for all groups: the parts are condensed once and reused.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: joints(:)
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: group(:), members(:)
    logical, allocatable :: related(:, :)
    integer :: ngroup, s, t, g, nstep
    type(swap_t) :: swap
    type(results_t) :: r
    type(solve_context_t) :: ctx
    type(failures_t) :: fail

    if (.not. has_joint_changes(model)) then
       call solve_model(model, opts, res, error)
       return
    end if
    nstep = size(model%steps)
    allocate (related(nstep, nstep), source=.false.)
    do s = 1, nstep
       do t = 1, s - 1
          related(s, t) = joints(s) == joints(t)
       end do
    end do
    call group_steps(related, group, ngroup)   ! numbered over these steps

    ctx%joint_study = ngroup > 1
    ctx%factor%keep_analysis = ngroup > 1   ! each value refactors the previous one's analysis (same pattern)
    do g = 1, ngroup
       members = pack([(s, s=1, nstep)], group == g)
       call enter_group(model, members, swap, links=.true.)
       call solve_group(model, opts, ctx, r, error)
       call leave_group(model, swap)
       if (allocated(error)) then
          call add_error_line(error, error%code, '  (while solving '//step_list(model, members, .true.)// &
               ' with their contact stiffnesses, *CHANGE CONTACT)')
          if (keep_going(fail, members, nstep, r, res, error)) cycle
          call release_factor(ctx%factor)
          call release_cache(ctx%cache)
          return
       end if
       call merge_results(r, members, nstep, .not. fail%solved, res)
       fail%solved = .true.
       call note_group(model, members, res)
    end do
    call release_factor(ctx%factor)
    call release_cache(ctx%cache)
    call finish_failures(fail, res, error)
    call append_string(res%log%notes, 'joint study (*CHANGE CONTACT): '//itoa(ngroup)// &
         ' sets of contact stiffnesses, '//itoa(ngroup)//' interface factorizations, '// &
         itoa(ctx%cache%computed)//' condensations computed and reused '//itoa(ctx%cache%reused)// &
         ' times; the counts above are the largest over them, each step''s NUMERICAL HEALTH that of its own '// &
         'factorization')
  end subroutine solve_joint_groups

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
    call sort_index(list%dof, order)
    call sort_index(list%node, order)
    call sort_index(list%sub, order)
  end subroutine dof_order

  pure logical function same_support(a, b, with_values)
    type(support_t), intent(in) :: a, b
    logical, intent(in) :: with_values
    same_support = a%sub == b%sub .and. a%node == b%node .and. a%dof == b%dof .and. &
         a%state == b%state .and. a%g == b%g
    if (with_values) same_support = same_support .and. a%value == b%value .and. a%held_from == b%held_from
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

  subroutine keep_named_dofs(steps, model)
    !! A contact DOF that some step's *CHANGE CONTACT names and that this
    !! group leaves unconnected (g = 0) stays in the links as a finite g = 0:
    !! the DOF keeps its unit, force 0, and its true delta is listed.
    type(step_t), intent(in) :: steps(:)
    type(model_t), intent(inout) :: model
    integer :: s, i, d
    do s = 1, size(steps)
       if (.not. allocated(steps(s)%link_overrides)) cycle
       do i = 1, size(steps(s)%link_overrides)
          associate (o => steps(s)%link_overrides(i), l => model%links(steps(s)%link_overrides(i)%link))
            do d = 1, size(o%dofs)
               if (.not. o%dofs(d)) cycle
               if (l%state(d) /= LINK_NONE) cycle
               l%state(d) = LINK_FINITE
               l%g(d) = 0.0_wp
            end do
          end associate
       end do
    end do
  end subroutine keep_named_dofs

  subroutine merge_results(r, members, nstep, first, res)
    !! Put the results r of the steps `members` into res (nstep steps in all).
    type(results_t), intent(in) :: r
    integer, intent(in) :: members(:), nstep
    logical, intent(in) :: first
    type(results_t), intent(inout) :: res
    integer :: k, i
    if (first) then
       res = r
       if (allocated(res%log%warnings)) deallocate (res%log%warnings)
       allocate (res%log%warnings(0))   ! r's, with their steps numbered over the run: merge_warnings
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
       ! MAXRATIO and the condition estimate: each step holds its group's (stamp_matrix_health)
       res%log%phase_seconds = res%log%phase_seconds + r%log%phase_seconds
       res%summary%factor_mbytes = max(res%summary%factor_mbytes, r%summary%factor_mbytes)
       do i = 1, size(r%log%notes)
          if (.not. any_string(res%log%notes, r%log%notes(i)%s)) call append_string(res%log%notes, r%log%notes(i)%s)
       end do
       res%log%inaccurate = res%log%inaccurate .or. r%log%inaccurate   ! any group's doubt is the run's (exit 5)
    end if
    call merge_warnings(r, members, nstep, res)
    do k = 1, size(members)
       if (allocated(r%fields%u)) res%fields%u(:, members(k)) = r%fields%u(:, k)
       if (allocated(r%fields%elem_force)) res%fields%elem_force(:, :, :, members(k)) = r%fields%elem_force(:, :, :, k)
       if (allocated(r%fields%plate)) res%fields%plate(:, :, members(k)) = r%fields%plate(:, :, k)
       res%fields%steps(members(k)) = r%fields%steps(k)
    end do
  end subroutine merge_results

  subroutine merge_warnings(r, members, nstep, res)
    !! The warnings of r, which solved the steps members, into res (nstep
    !! steps): each warning's steps numbered over the run (r's step k is
    !! members(k)); a warning res has already gains r's steps.
    type(results_t), intent(in) :: r
    integer, intent(in) :: members(:), nstep
    type(results_t), intent(inout) :: res
    logical, allocatable :: steps(:)
    integer :: i
    if (.not. allocated(r%log%warnings)) return
    do i = 1, size(r%log%warnings)
       associate (w => r%log%warnings(i))
         if (.not. allocated(w%steps)) then
            call add_warning(res%log%warnings, w%s)
            cycle
         end if
         allocate (steps(nstep), source=.false.)
         steps(members) = w%steps
         call add_warning(res%log%warnings, w%s, steps)
         deallocate (steps)
       end associate
    end do
  end subroutine merge_warnings

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
    text = step_list(model, members, .true.)
    if (n == 0) then
       text = text//': contact stiffnesses as defined'
    else
       text = text//': *CHANGE CONTACT on '//itoa(n)//' contact element(s)'
    end if
    call append_string(res%log%notes, text)
  end subroutine note_group

  subroutine hold_group(model, members, fail, res, error)
    !! *BOUNDARY, FIXED: the held values of the supports of the group's steps
    !! members, from the merged results res of the steps they hold to; an
    !! error (exit 3: these steps go unsolved, the others on) when one of
    !! those steps was not solved.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: members(:)
    type(failures_t), intent(in) :: fail
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: src(:)
    integer :: k
    character(:), allocatable :: verb
    allocate (src, source=held_sources(model%steps(members(1))%supports))   ! source=: no -Wuninitialized false positive
    do k = 1, size(src)
       if (solved(src(k))) cycle
       verb = ' holds'
       if (size(members) > 1) verb = ' hold'
       call fatal_error(error, EXIT_SINGULAR, 'error: '//step_list(model, members, .false.)//verb// &
            ' DOFs at the displacements of step '//model%steps(src(k))%name// &
            ' (*BOUNDARY, FIXED), which was not solved')
       return
    end do
    call fill_held(model, members, res)
  contains
    logical function solved(t)
      integer, intent(in) :: t
      solved = fail%solved
      if (.not. solved) return
      if (allocated(fail%message)) then
         if (allocated(fail%message(t)%s)) solved = .false.
      end if
      if (allocated(res%fields%steps(t)%failure)) solved = .false.
    end function solved
  end subroutine hold_group

  function step_list(model, members, plural) result(text)
    !! 'steps A B C' for messages ('step A' for one, unless plural).
    type(model_t), intent(in) :: model
    integer, intent(in) :: members(:)
    logical, intent(in) :: plural
    character(:), allocatable :: text
    integer :: k
    text = merge('steps', 'step ', plural .or. size(members) > 1)
    text = trim(text)
    do k = 1, size(members)
       text = text//' '//model%steps(members(k))%name
    end do
  end function step_list
end module superjoin_analysis_driver
