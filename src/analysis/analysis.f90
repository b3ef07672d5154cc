module superjoin_analysis
  !! The solution pipeline: DOFs → forest → boundaries and condensation →
  !! Δu transform → assembly (elements, superelements, contacts) → AUTOSPC →
  !! factorization (once for all steps) → solve → health checks → interiors →
  !! recovery. Decisions: analysis/policy; health: analysis/health; condensed
  !! substructures: analysis/condensation (substructure/ underneath).
  !! One solve of a step group (run_phases) fills a solve_state_t phase by
  !! phase: build_phase, assemble_phase, solve_phase, recover_phase; how K_red
  !! is assembled is the state's strategy (choose_strategy: plain, condensed,
  !! distributed; analysis/solve_state). The steps are grouped into solves by
  !! analysis/driver.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, string_t, FORM_TRANSFORM, FORM_PENALTY
  use superjoin_assembly_dofs, only: build_dof_table, dof_table_t
  use superjoin_analysis_build_reuse, only: take_table, keep_table, take_forest, take_transform, keep_transform, &
       take_boundaries, keep_boundaries
  use superjoin_assembly_forest, only: build_forest, forget_parents
  use superjoin_assembly_transform, only: transform_t, build_transform, COL_DELTA
  use superjoin_assembly_assemble, only: assemble_loads
  use superjoin_substructure_local_system, only: boundary_dofs, part_boundary, given_boundary
  use superjoin_substructure_cache, only: release_cache, forget_load_memos, keep_views
  use superjoin_solvers_matrix_market, only: write_matrix_market
  use superjoin_model_results, only: results_t, run_options_t, run_summary_t, PH_ASSEMBLE, PH_ORDER, PH_FACTOR, PH_SOLVE, &
       LEVELS_NO, LEVELS_AUTO
  use superjoin_analysis_recover, only: recover_results
  use superjoin_analysis_mechanism, only: mechanism_error
  use superjoin_model_notes, only: note
  use superjoin_analysis_labels, only: column_label
  use superjoin_analysis_health, only: check_finite, health, full_health, parts_maxratio, penalty_hint
  use superjoin_analysis_policy, only: apply_large, describe_transform, column_groups, count_boundary, &
       choose_condensation, autospc, skip_unloaded_parts, wanted_elements
  use superjoin_analysis_condensation, only: solve_context_t, condensed_strategy_t, interface_matrix
  use superjoin_analysis_levels, only: describe_levels, levels_request_t
  use superjoin_analysis_level_solver, only: make_solver, level_note
  use superjoin_analysis_solve_state, only: solve_state_t, plain_strategy_t, PHASE_BUILT, PHASE_ASSEMBLED, PHASE_SOLVED, &
       PHASE_RECOVERED, keep_boundary_loads
  use superjoin_analysis_factor_reuse, only: take_factor, take_analysis, keep_factor, solve_with
  use superjoin_analysis_distributed, only: plan_distribution, is_distributed, owner_terms, distributed_strategy_t
  use superjoin_solvers, only: mumps_solver_t
  use superjoin_parallel_stats, only: record_matrix_held
  use superjoin_utils_clock, only: stopwatch_t, report_phase
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL, BYTES_INT
  use superjoin_utils_strings, only: itoa
  use, intrinsic :: ieee_exceptions, only: ieee_flag_type, ieee_get_halting_mode, ieee_set_halting_mode, &
       ieee_overflow, ieee_invalid, ieee_divide_by_zero
  implicit none (type, external)
  private

  public :: solve_model, solve_group, release_cache

  public :: solve_context_t

  type(ieee_flag_type), parameter :: HALT_FLAGS(3) = [ieee_overflow, ieee_invalid, ieee_divide_by_zero]
    !! Exceptions whose halting is off while solving (results are checked instead).

contains

  subroutine solve_model(model, opts, res, error)
    !! Solve every step of a validated model with one stiffness (see solve_group).
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    type(solve_context_t) :: ctx
    ctx%last = .true.
    call solve_group(model, opts, ctx, res, error)
    call release_cache(ctx%cache)
  end subroutine solve_model

  subroutine solve_group(model, opts, ctx, res, error)
    !! Solve every step of a validated model whose steps share one stiffness,
    !! reusing the condensations that ctx holds from earlier solves of the
    !! same structure (a joint study). Results that overflow the
    !! floating-point range end the run (EXIT_SINGULAR) instead of printing
    !! Inf or NaN; floating-point halting (the Debug build's -ffpe-trap) is off
    !! meanwhile, so the overflow is detected here rather than trapped.
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    logical :: halting(size(HALT_FLAGS))
    integer :: i
    do i = 1, size(HALT_FLAGS)
       call ieee_get_halting_mode(HALT_FLAGS(i), halting(i))
       call ieee_set_halting_mode(HALT_FLAGS(i), .false.)
    end do
    call run_phases(model, opts, ctx, res, error)
    do i = 1, size(HALT_FLAGS)
       call ieee_set_halting_mode(HALT_FLAGS(i), halting(i))
    end do
    if (allocated(error)) return
    call stamp_matrix_health(res)
    call check_finite(model, res, error)
  end subroutine solve_group

  subroutine stamp_matrix_health(res)
    !! Give every step of this group the MAXRATIO and condition estimate of
    !! the matrix it was solved with, which its NUMERICAL HEALTH block reports:
    !! in a run of several groups (a joint study, steps that change supports)
    !! each group has its own, and the merged summary holds the first group's.
    type(results_t), intent(inout) :: res
    integer :: s
    if (.not. allocated(res%fields%steps)) return
    do s = 1, size(res%fields%steps)
       res%fields%steps(s)%maxratio = res%summary%maxratio
       res%fields%steps(s)%maxratio_at = res%summary%maxratio_at
       res%fields%steps(s)%cond_est = res%summary%cond_est
       res%fields%steps(s)%cond_bound = res%summary%cond_bound
    end do
  end subroutine stamp_matrix_health

  subroutine run_phases(model, opts, ctx, res, error)
    !! The analysis proper (see solve_group), phase by phase on one solve state.
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    type(solve_state_t) :: st
    type(stopwatch_t) :: clock
    type(string_t), allocatable :: notes(:)
    character(len=64) :: buf

    allocate (notes(0), res%log%warnings(0))
    res%summary%maxratio_at = 'n/a (no unknowns)'
    call clock%start()
    call build_phase(st, model, opts, ctx, res, notes, error)
    if (allocated(error)) return
    call assemble_phase(st, model, opts, ctx, res, notes, error)
    if (allocated(error)) return
    res%log%phase_seconds(PH_ASSEMBLE) = clock%seconds()
    write (buf, '(a,i0,a,i0)') 'equations ', res%summary%neq, ', nonzeros ', res%summary%matrix_nnz
    if (st%strategy%summed()) write (buf, '(a,i0,a,i0)') 'equations ', res%summary%neq, ', nonzeros of this process''s term ', &
         st%k%nnz()
    call report_phase(opts%quiet, 'assemble', res%log%phase_seconds(PH_ASSEMBLE), trim(buf))

    if (allocated(opts%export_matrix) .and. .not. st%strategy%summed()) then   ! app/main.f90 refuses it with owner terms
       call write_matrix_market(opts%export_matrix, st%k, error)
       if (allocated(error)) return
    end if
    call solve_phase(st, model, opts, ctx, res, error)
    if (allocated(error)) return
    call recover_phase(st, model, opts, ctx, res, notes, error)
    if (allocated(error)) return
    if (st%strategy%summed()) then
       if (allocated(st%solver)) call st%solver%release()
    else
       call keep_factor(ctx%factor, st%k, st%solver, st%groups)   ! released unless kept (ctx%factor)
    end if
    if (allocated(res%log%notes)) notes = [notes, res%log%notes]   ! the solve phase's (health)
    res%log%notes = notes
  end subroutine run_phases

  subroutine build_phase(st, model, opts, ctx, res, notes, error)
    !! Build: the DOF table (with *LARGE stiffnesses), the forest, the
    !! condensation boundary and choice, and the Δu transform.
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(inout) :: res
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: keep(:)
    logical :: kept
    integer(i8) :: p
    integer :: stat

    st%form = model%controls%formulation
    if (opts%formulation /= 0) st%form = opts%formulation
    res%summary%formulation = merge('TRANSFORM', 'PENALTY  ', st%form == FORM_TRANSFORM)
    res%summary%formulation = trim(res%summary%formulation)

    call build_table(model, ctx, st%table, kept, error)
    if (allocated(error)) return
    if (size(st%table%ignored_links) > 0) call note(notes, itoa(size(st%table%ignored_links))// &
         ' contact element(s) name DOFs that neither node carries; those DOFs are not connected')
    call apply_large(model, st%table, st%form, notes, error)
    if (allocated(error)) return
    call forest_of_value(ctx, st, error)
    if (allocated(error)) return
    call boundaries_of_value(model, ctx, kept, st, res%summary)
    call plan_distribution(model, res%summary, res%log, error)   ! several MPI processes only
    if (allocated(error)) return
    call choose_condensation(model, st%table, opts, ctx, st%bnd_c, res%summary, notes)
    allocate (keep(st%table%np), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the condensation flags', st%table%np*BYTES_INT)
       return
    end if
    do p = 1, st%table%np
       keep(p) = st%bnd_c(p) .or. .not. res%summary%sub_condensed(st%table%p_sub(p))
    end do
    call transform_of_value(model, ctx, st, keep, error)
    if (allocated(error)) return
    call describe_transform(model, st%table, st%tr, st%form, res%summary, notes)
    if (res%summary%n_condensed > 0) &
         call describe_levels(model, st%table, st%forest, st%tr, levels_request(opts, res%summary), notes, st%levels)
    call forget_parents(st%forest)   ! looked up by vertex up to here only
    call choose_strategy(st, res%summary, opts)
    st%phase = PHASE_BUILT
  end subroutine build_phase

  subroutine build_table(model, ctx, table, taken, error)
    !! The DOF table: in a joint study the previous value's with this
    !! value's g's when the links' states are the same (analysis/build_reuse:
    !! taken), else built anew (and kept for the next value).
    type(model_t), intent(in) :: model
    type(solve_context_t), intent(inout) :: ctx
    type(dof_table_t), intent(out) :: table
    logical, intent(out) :: taken
    type(error_t), allocatable, intent(out) :: error
    taken = .false.
    if (ctx%joint_study) call take_table(ctx%build, model, table, taken)
    if (taken) return
    call build_dof_table(model, table, error)
    if (allocated(error)) return
    if (ctx%joint_study) call keep_table(ctx%build, model, table)
  end subroutine build_table

  subroutine boundaries_of_value(model, ctx, kept, st, summary)
    !! The DOFs contacts and supports touch, counted per substructure, and
    !! the condensation boundaries (the instances of a part share theirs):
    !! they depend on the units' DOFs, not on their springs, so a joint
    !! study's value whose table was kept (kept) takes the previous value's.
    type(model_t), intent(in) :: model
    type(solve_context_t), intent(inout) :: ctx
    logical, intent(in) :: kept
    type(solve_state_t), intent(inout) :: st
    type(run_summary_t), intent(inout) :: summary
    logical, allocatable :: bnd(:)
    logical :: taken
    taken = .false.
    if (kept) call take_boundaries(ctx%build, st%bnd_c, summary, taken)
    ctx%cache%same_numbering = taken   ! the condensed parts' views of the previous value fit
    ctx%cache%keep_views = ctx%joint_study .and. .not. ctx%last
    if (taken) return
    call boundary_dofs(st%table, bnd)
    call given_boundary(model, st%table, bnd)
    call count_boundary(model, st%table, bnd, summary)
    call part_boundary(model, st%table, bnd, st%bnd_c)
    if (ctx%joint_study) call keep_boundaries(ctx%build, st%bnd_c, summary)
  end subroutine boundaries_of_value

  subroutine forest_of_value(ctx, st, error)
    !! The forest: in a joint study the previous value's when the units are
    !! taken in the same order (analysis/build_reuse), else built anew.
    type(solve_context_t), intent(inout) :: ctx
    type(solve_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    logical :: taken
    taken = .false.
    if (ctx%joint_study) call take_forest(ctx%build, st%table, st%form == FORM_TRANSFORM, st%forest, taken)
    if (taken) return
    call build_forest(st%table, st%form == FORM_TRANSFORM, st%forest, error)
  end subroutine forest_of_value

  subroutine transform_of_value(model, ctx, st, keep, error)
    !! The Δu transform: in a joint study the previous value's with this
    !! value's springs when the table's units, forest and kept DOFs allow
    !! (analysis/build_reuse), else built anew (and kept for the next value).
    type(model_t), intent(in) :: model
    type(solve_context_t), intent(inout) :: ctx
    type(solve_state_t), intent(inout) :: st
    logical, intent(in) :: keep(:)
    type(error_t), allocatable, intent(out) :: error
    logical :: taken
    taken = .false.
    if (ctx%joint_study) call take_transform(ctx%build, st%table, st%forest, keep, st%tr, taken)
    if (taken) return
    call build_transform(model, st%table, st%forest, st%tr, error, keep)
    if (allocated(error)) return
    if (ctx%joint_study) call keep_transform(ctx%build, st%table, st%forest, keep, st%tr)
  end subroutine transform_of_value

  function levels_request(opts, summary) result(req)
    !! What a condensed run of parts made of parts asks of a condensation by
    !! level: refused when not asked for (--levels no) or with several MPI
    !! processes (their owner terms of K_red: the flat interface system); with
    !! --levels auto (the default) as the counts say (analysis/levels).
    type(run_options_t), intent(in) :: opts
    type(run_summary_t), intent(in) :: summary
    type(levels_request_t) :: req
    req%refusal = ''
    if (is_distributed(summary)) req%refusal = 'several MPI processes'
    if (opts%levels == LEVELS_NO) req%refusal = '--levels no'
    req%auto = opts%levels == LEVELS_AUTO
  end function levels_request

  subroutine choose_strategy(st, summary, opts)
    !! How K_red is assembled (analysis/solve_state): distributed over
    !! several MPI processes (with MUMPS, each process holds and hands MUMPS
    !! its own term of K_red only: owner terms, analysis/summed_matrix),
    !! condensed, or plain. A new way of solving is a new strategy here.
    type(solve_state_t), intent(inout) :: st
    type(run_summary_t), intent(in) :: summary
    type(run_options_t), intent(in) :: opts
    if (is_distributed(summary)) then
       allocate (st%strategy, source=distributed_strategy_t(owned=owner_terms(summary, opts)))
    else if (summary%n_condensed > 0) then
       allocate (condensed_strategy_t :: st%strategy)
    else
       allocate (plain_strategy_t :: st%strategy)
    end if
  end subroutine choose_strategy

  subroutine assemble_phase(st, model, opts, ctx, res, notes, error)
    !! Assemble: the loads, the condensations (if any), K_red and the reduced
    !! loads, AUTOSPC and the parts left out for want of loads; the sizes in
    !! the summary.
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(inout) :: res
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error

    if (res%summary%n_condensed == 0) then
       call early_solver(st, opts, ctx)
       call interface_matrix(ctx, st, model, res%summary, error)
       if (allocated(error)) return
       call assemble_loads(model, st%table, st%f_phys, error)
       if (allocated(error)) return
       call reduce_loads(st%tr, st%f_phys, st%f_u0, st%f_red, error)
    else
       call assemble_loads(model, st%table, st%f_phys, error)
       if (allocated(error)) return
       call st%strategy%condense(st, model, opts, ctx%cache, res%summary, notes, error)
       if (allocated(error)) return
       if (ctx%last) call forget_load_memos(ctx%cache)   ! no later solve condenses these loads again
       call interface_matrix(ctx, st, model, res%summary, error)
       if (allocated(error)) return
       call reduce_loads(st%tr, st%f_eff, st%f_u0, st%f_red, error)
       call keep_boundary_loads(st)
    end if
    if (allocated(error)) return
    deallocate (st%bnd_c)   ! its last users (the condensations) are done
    call autospc(model, st%table, st%tr, st%k, st%f_red, st%spc, notes, error, summed=st%strategy%summed())
    if (allocated(error)) return
    if (ctx%joint_study) then   ! interface_matrix: the groups of a kept K_red
       call skip_unloaded_parts(model, st%table, st%tr, st%k, st%f_red, st%spc, notes, &
            summed=st%strategy%summed(), error=error, roots=ctx%build%roots)
    else
       call skip_unloaded_parts(model, st%table, st%tr, st%k, st%f_red, st%spc, notes, summed=st%strategy%summed(), error=error)
    end if
    if (allocated(error)) return
    res%summary%nphys = st%table%np
    res%summary%ncol = st%tr%ncol()
    res%summary%neq = st%tr%ncol() - count(st%spc, kind=i8)
    res%summary%ndelta = count_delta(st%tr)
    res%summary%matrix_nnz = st%k%nnz()
    call record_matrix_held(st%k%nnz())   ! MPI summary: what this process assembled
    if (st%strategy%summed()) res%summary%matrix_nnz = -1   ! not assembled anywhere: the listing says n/a
    st%phase = PHASE_ASSEMBLED
  end subroutine assemble_phase

  subroutine solve_phase(st, model, opts, ctx, res, error)
    !! Factor and solve (or solve with the factor a previous solve of the
    !! same matrix kept), then the health checks (iterative refinement may
    !! still improve q).
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    type(stopwatch_t) :: clock

    if (st%tr%ncol() > 0) then
       ! loads: the same matrix as the previous solve (not with owner terms:
       ! each process would judge its own term; they refactor instead)
       if (.not. (st%strategy%summed() .or. st%early_solver)) call take_factor(ctx%factor, st%k, st%solver)
       if (allocated(st%solver) .and. .not. st%early_solver) then
          call solve_with(st%solver, st%k%n, st%f_red, opts%quiet, st%q, res, error)
       else
          if (.not. st%early_solver) then
             call column_groups(st%table, st%forest, st%tr, st%groups)
             ! a joint study: the same pattern as the previous value, only refactored
             if (.not. st%strategy%summed()) call take_analysis(ctx%factor, st%k, st%groups, st%solver)
          end if
          call factor_and_solve(st, model, opts, res, error)
       end if
       if (allocated(error)) return
    else
       allocate (st%q(0, size(model%steps)))
       res%summary%solver_name = 'none (no unknowns)'
       res%summary%ordering = 'none'
    end if

    ! Health first: iterative refinement may still improve q.
    allocate (res%fields%steps(size(model%steps)))
    if (st%tr%ncol() > 0) then
       call clock%start()
       call health(st, model, opts, res, error)
       if (allocated(error)) return
       res%log%phase_seconds(PH_SOLVE) = res%log%phase_seconds(PH_SOLVE) + clock%seconds()
       call report_phase(opts%quiet, 'health', clock%seconds())
    end if
    st%phase = PHASE_SOLVED
  end subroutine solve_phase

  subroutine recover_phase(st, model, opts, ctx, res, notes, error)
    !! Recover: the physical displacements, the condensed interiors (their
    !! whole-system health and MAXRATIO), then the element, contact and
    !! support results.
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(inout) :: res
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: wanted(:)
    type(stopwatch_t) :: clock
    integer :: stat

    call clock%start()
    st%give_back = .not. ctx%joint_study
    allocate (st%u(st%table%np, size(model%steps)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the displacements', st%table%np*size(model%steps)*BYTES_REAL)
       return
    end if
    call st%tr%expand(st%q, st%u)
    if (res%summary%n_condensed > 0) then
       call st%strategy%recover_interiors(st, ctx%cache, error)
       if (allocated(error)) return
       if (st%tr%ncol() > 0) call full_health(st, ctx%cache, res, error)
       if (allocated(error)) return
       if (allocated(st%r_red)) deallocate (st%r_red)   ! kept when full_health did not run
       call parts_maxratio(model, st%table, ctx%cache, st%parts, res, error)
       if (allocated(error)) return
       if (ctx%last) call release_cache(ctx%cache)   ! the parts' factors: not needed for the element results
       ! their last users (full_health, parts_maxratio) are done
       if (allocated(st%parts)) call keep_views(ctx%cache, st%parts)   ! for a joint study's next value, else freed
       if (allocated(st%f_bnd)) deallocate (st%f_bnd)
       res%log%phase_seconds(PH_SOLVE) = res%log%phase_seconds(PH_SOLVE) + clock%seconds()
       call report_phase(opts%quiet, 'recover interiors', clock%seconds())
       call clock%start()
    end if
    call st%tr%release_maps()   ! u and the whole-system health are done: the recovery reads no map
    call wanted_elements(model, opts, wanted, notes)
    call recover_results(st, model, wanted, res, error)
    if (allocated(error)) return
    res%log%phase_seconds(PH_SOLVE) = res%log%phase_seconds(PH_SOLVE) + clock%seconds()
    call report_phase(opts%quiet, 'recover', clock%seconds())
    st%phase = PHASE_RECOVERED
  end subroutine recover_phase

  subroutine reduce_loads(tr, f_phys, f_u0, f_red, error)
    !! f_red = Tᵀ f_phys + f_u0 for every step.
    type(transform_t), intent(in) :: tr
    real(wp), intent(in) :: f_phys(:, :), f_u0(:)
    real(wp), allocatable, intent(out) :: f_red(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer :: is, stat
    allocate (f_red(tr%ncol(), size(f_phys, 2)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the reduced loads', tr%ncol()*size(f_phys, 2)*BYTES_REAL)
       return
    end if
    call tr%reduce(f_phys, f_red)
    do is = 1, size(f_phys, 2)
       f_red(:, is) = f_red(:, is) + f_u0
    end do
  end subroutine reduce_loads

  subroutine early_solver(st, opts, ctx)
    !! The solver of K_red made before the assembly of K's values, so that its
    !! analysis of the pattern (the ordering) runs beside them
    !! (assemble_stiffness, analyze_start): the first solve of a matrix
    !! assembled whole by this process (no kept factor or analysis to reuse).
    !! When the solver cannot be made here, factor_and_solve makes it (and
    !! reports why not) as before.
    type(solve_state_t), intent(inout) :: st
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(in) :: ctx
    type(error_t), allocatable :: error
    if (st%strategy%summed() .or. allocated(ctx%factor%solver) .or. st%tr%ncol() == 0) return
    call column_groups(st%table, st%forest, st%tr, st%groups)
    call make_solver(st%levels, chosen_solver(opts), st%tr%ncol(), st%solver, error)
    if (allocated(error)) then
       if (allocated(st%solver)) deallocate (st%solver)
       return
    end if
    if (allocated(st%groups)) call st%solver%set_groups(st%groups)
    st%early_solver = .true.
  end subroutine early_solver

  function chosen_solver(opts) result(name)
    !! The solver asked for (--solver), 'auto' if none.
    type(run_options_t), intent(in) :: opts
    character(:), allocatable :: name
    name = 'auto'
    if (allocated(opts%solver)) name = opts%solver
  end function chosen_solver

  pure function count_delta(tr) result(n)
    !! Number of δ unknowns.
    type(transform_t), intent(in) :: tr
    integer(i8) :: n, j
    n = 0
    do j = 1, tr%ncol()
       if (tr%column_kind(j) == COL_DELTA) n = n + 1
    end do
  end function count_delta

  subroutine factor_and_solve(st, model, opts, res, error)
    !! Analyze (unless st%solver holds a kept analysis of the same pattern),
    !! factorize (mapping a breakdown to its location) and solve all
    !! steps: st%solver and st%q. Owner terms (st%strategy%summed()): k is
    !! this process's term of K_red (MUMPS local input).
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    type(stopwatch_t) :: clock
    character(:), allocatable :: solver_name
    integer(i8) :: jf
    integer :: stat
    character(len=80) :: buf

    solver_name = chosen_solver(opts)
    call clock%start()
    if (allocated(st%solver) .and. .not. st%early_solver) then   ! take_analysis: the pattern analyzed for the previous joint value
       res%log%phase_seconds(PH_ORDER) = 0.0_wp
       call report_phase(opts%quiet, 'order', 0.0_wp, 'reused (same pattern as the previous solve)')
    else
       if (.not. allocated(st%solver)) then
          call make_solver(st%levels, solver_name, st%k%n, st%solver, error)
          if (allocated(error)) return
          if (allocated(st%groups)) call st%solver%set_groups(st%groups)
          if (st%strategy%summed()) then
             select type (s => st%solver)
             type is (mumps_solver_t)
                s%local_input = .true.
             end select
          end if
       end if
       call st%solver%analyze(st%k, error)   ! early_solver: waits for the analysis begun beside the assembly
       if (allocated(error)) return
       res%log%phase_seconds(PH_ORDER) = clock%seconds()
       call report_phase(opts%quiet, 'order', res%log%phase_seconds(PH_ORDER), st%solver%info%ordering)
    end if

    call clock%start()
    call st%solver%factorize(st%k, error)
    if (allocated(error)) then
       if (error%code == EXIT_SINGULAR) then
          jf = st%solver%info%failed_column
          deallocate (error)
          call mechanism_error(st%k, solver_name, model, st%table, st%tr, penalty_hint(res), res%fields%mechanism, error, &
               summed=st%strategy%summed())
          if (allocated(error)) return
          if (jf >= 1 .and. jf <= st%tr%ncol()) then
             call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: '// &
                  'mechanism or singular stiffness at '//column_label(model, st%table, st%tr, jf)//penalty_hint(res))
          else
             call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: '// &
                  'stiffness matrix is singular or not positive definite'//penalty_hint(res))
          end if
       end if
       return
    end if
    res%log%phase_seconds(PH_FACTOR) = clock%seconds()
    call level_note(st%solver, res%log%notes)
    res%summary%solver_name = st%solver%info%name
    res%summary%ordering = st%solver%info%ordering
    res%summary%factor_nnz = st%solver%info%factor_nnz
    res%summary%factor_mbytes = st%solver%info%factor_mbytes
    write (buf, '(a,i0)') 'factor nonzeros ', res%summary%factor_nnz
    call report_phase(opts%quiet, 'factor', res%log%phase_seconds(PH_FACTOR), st%solver%info%name//', '//trim(buf))

    call clock%start()
    allocate (st%q(st%k%n, size(st%f_red, 2)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the solution', st%k%n*size(st%f_red, 2)*BYTES_REAL)
       return
    end if
    call st%solver%solve(st%f_red, st%q, error)
    if (allocated(error)) return
    res%log%phase_seconds(PH_SOLVE) = clock%seconds()
    call report_phase(opts%quiet, 'solve', res%log%phase_seconds(PH_SOLVE))
  end subroutine factor_and_solve

end module superjoin_analysis
