module superjoin_analysis
  !! The solution pipeline: DOFs → forest → boundaries and condensation →
  !! Δu transform → assembly (elements, superelements, contacts) → AUTOSPC →
  !! factorization (once for all steps) → solve → health checks → interiors →
  !! recovery. Decisions: analysis/policy; health: analysis/health; condensed
  !! substructures: analysis/condensation (substructure/ underneath).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, string_t, FORM_TRANSFORM, FORM_PENALTY
  use superjoin_assembly_dofs, only: dof_table_t, build_dof_table
  use superjoin_assembly_forest, only: forest_t, build_forest
  use superjoin_assembly_transform, only: transform_t, build_transform, COL_DELTA
  use superjoin_assembly_assemble, only: assemble_stiffness, assemble_loads, assembly_plan_t
  use superjoin_substructure_local_system, only: boundary_dofs, part_boundary
  use superjoin_substructure_cache, only: release_cache, part_view_t
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver
  use superjoin_solvers_matrix_market, only: write_matrix_market
  use superjoin_model_results, only: results_t, run_options_t, PH_ASSEMBLE, PH_ORDER, PH_FACTOR, PH_SOLVE
  use superjoin_analysis_recover, only: recover_results
  use superjoin_analysis_mechanism, only: mechanism_error
  use superjoin_model_notes, only: note
  use superjoin_analysis_labels, only: column_label
  use superjoin_analysis_health, only: check_finite, health, full_health, parts_maxratio, penalty_hint
  use superjoin_analysis_policy, only: apply_large, describe_transform, column_groups, count_boundary, &
       choose_condensation, autospc, skip_unloaded_parts, wanted_elements
  use superjoin_analysis_condensation, only: solve_context_t, condense_parts, recover_parts, parts_ku
  use superjoin_analysis_factor_reuse, only: take_factor, keep_factor, solve_with
  use superjoin_analysis_distributed, only: plan_distribution, is_distributed, condense_distributed, &
       recover_distributed, parts_ku_distributed, owner_terms, owner_plan, sum_owner_loads, agreed
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
    call solve_steps(model, opts, ctx, res, error)
    do i = 1, size(HALT_FLAGS)
       call ieee_set_halting_mode(HALT_FLAGS(i), halting(i))
    end do
    if (allocated(error)) return
    call check_finite(model, res, error)
  end subroutine solve_group

  subroutine solve_steps(model, opts, ctx, res, error)
    !! The analysis proper (see solve_group).
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(out) :: res
    type(error_t), allocatable, intent(out) :: error
    type(dof_table_t) :: table
    type(forest_t) :: forest
    type(transform_t) :: tr
    type(sparse_sym_t) :: k
    real(wp), allocatable :: f_u0(:), f_phys(:, :), f_red(:, :), q(:, :)
    integer(i8), allocatable :: groups(:)
    logical, allocatable :: spc(:)
    class(linear_solver_t), allocatable :: solver
    type(stopwatch_t) :: clock
    type(string_t), allocatable :: notes(:)
    integer :: form
    character(len=64) :: buf
    logical, allocatable :: bnd(:), bnd_c(:), keep(:), wanted(:)
    type(assembly_plan_t) :: plan
    type(part_view_t), allocatable :: parts(:)
    real(wp), allocatable :: f_eff(:, :), u(:, :), ku(:, :)
    integer(i8) :: p
    integer :: i, stat
    logical :: owned

    allocate (notes(0), res%log%warnings(0))
    res%summary%maxratio_at = 'n/a (no unknowns)'
    call clock%start()
    form = model%controls%formulation
    if (opts%formulation /= 0) form = opts%formulation
    res%summary%formulation = merge('TRANSFORM', 'PENALTY  ', form == FORM_TRANSFORM)
    res%summary%formulation = trim(res%summary%formulation)

    call build_dof_table(model, table, error)
    if (allocated(error)) return
    if (size(table%ignored_links) > 0) call note(notes, itoa(size(table%ignored_links))// &
         ' contact element(s) name DOFs that neither node carries; those DOFs are not connected')
    call apply_large(model, table, form, notes, error)
    if (allocated(error)) return
    call build_forest(table, form == FORM_TRANSFORM, forest, error)
    if (allocated(error)) return
    call boundary_dofs(table, bnd)
    call count_boundary(model, table, bnd, res%summary)
    call plan_distribution(model, res%summary, res%log, error)   ! several MPI processes only
    if (allocated(error)) return
    ! Condensation boundaries: the instances of a part share theirs.
    call part_boundary(model, table, bnd, bnd_c)
    call choose_condensation(model, table, opts, ctx, bnd_c, res%summary, notes)
    allocate (keep(table%np), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the condensation flags', table%np*BYTES_INT)
       return
    end if
    do p = 1, table%np
       keep(p) = bnd_c(p) .or. .not. res%summary%sub_condensed(table%p_sub(p))
    end do
    call build_transform(model, table, forest, tr, error, keep)
    if (allocated(error)) return
    call describe_transform(model, table, tr, form, res%summary, notes)
    ! several MPI processes with MUMPS: each process holds and hands MUMPS its
    ! own term of K_red only (analysis/distributed, analysis/summed_matrix)
    owned = owner_terms(res%summary, opts)

    if (res%summary%n_condensed == 0) then
       if (owned) then
          allocate (parts(0))
          call owner_plan(model, res%summary, parts, plan)
       else
          allocate (plan%skip_sub(size(model%subs)), source=.false.)
          allocate (plan%supers(0))
       end if
       call assemble_stiffness(model, table, tr, plan, k, f_u0, error)
       if (owned) call agreed(error)
       if (allocated(error)) return
       if (owned) call sum_owner_loads(f_u0, error)
       if (allocated(error)) return
       call assemble_loads(model, table, f_phys, error)
       if (allocated(error)) return
       call reduce_loads(tr, f_phys, f_u0, f_red, error)
    else
       call assemble_loads(model, table, f_phys, error)
       if (allocated(error)) return
       if (is_distributed(res%summary)) then   ! several MPI processes: each condenses its own parts
          call condense_distributed(model, table, tr, bnd_c, opts, f_phys, ctx%cache, res%summary, notes, &
               parts, f_eff, error, owned)
       else
          call condense_parts(model, table, bnd_c, opts, f_phys, ctx%cache, res%summary, notes, parts, f_eff, error)
       end if
       if (allocated(error)) return
       if (owned) then
          call owner_plan(model, res%summary, parts, plan)
       else
          plan%skip_sub = res%summary%sub_condensed
          allocate (plan%supers(size(parts)))
          do i = 1, size(parts)
             plan%supers(i) = parts(i)%se
          end do
       end if
       call assemble_stiffness(model, table, tr, plan, k, f_u0, error)
       if (owned) call agreed(error)
       if (allocated(error)) return
       deallocate (plan%supers)
       if (owned) call sum_owner_loads(f_u0, error)
       if (allocated(error)) return
       call reduce_loads(tr, f_eff, f_u0, f_red, error)
    end if
    if (allocated(error)) return
    call autospc(model, table, tr, k, f_red, spc, notes, error, summed=owned)
    if (allocated(error)) return
    call skip_unloaded_parts(model, table, tr, k, f_red, spc, notes, summed=owned, error=error)
    if (allocated(error)) return
    res%summary%nphys = table%np
    res%summary%ncol = tr%ncol()
    res%summary%neq = tr%ncol() - count(spc, kind=i8)
    res%summary%ndelta = count_delta(tr)
    res%summary%matrix_nnz = k%nnz()
    call record_matrix_held(k%nnz())   ! MPI summary: what this process assembled
    if (owned) res%summary%matrix_nnz = -1   ! not assembled anywhere: the listing says n/a
    res%log%phase_seconds(PH_ASSEMBLE) = clock%seconds()
    write (buf, '(a,i0,a,i0)') 'equations ', res%summary%neq, ', nonzeros ', res%summary%matrix_nnz
    if (owned) write (buf, '(a,i0,a,i0)') 'equations ', res%summary%neq, ', nonzeros of this process''s term ', &
         k%nnz()
    call report_phase(opts%quiet, 'assemble', res%log%phase_seconds(PH_ASSEMBLE), trim(buf))

    if (allocated(opts%export_matrix) .and. .not. owned) then   ! app/main.f90 refuses it with owner terms
       call write_matrix_market(opts%export_matrix, k, error)
       if (allocated(error)) return
    end if

    if (tr%ncol() > 0) then
       ! loads: the same matrix as the previous solve (not with owner terms:
       ! each process would judge its own term; they refactor instead)
       if (.not. owned) call take_factor(ctx%factor, k, solver)
       if (allocated(solver)) then
          call solve_with(solver, k%n, f_red, opts%quiet, q, res, error)
       else
          call column_groups(table, forest, tr, groups)
          call factor_and_solve(model, table, tr, k, f_red, opts, groups, solver, q, res, error, owned)
       end if
       if (allocated(error)) return
    else
       allocate (q(0, size(model%steps)))
       res%summary%solver_name = 'none (no unknowns)'
       res%summary%ordering = 'none'
    end if

    ! Health first: iterative refinement may still improve q.
    allocate (res%fields%steps(size(model%steps)))
    if (tr%ncol() > 0) then
       call clock%start()
       call health(k, q, f_red, spc, solver, model, table, tr, res, opts, error, summed=owned)
       if (allocated(error)) return
       res%log%phase_seconds(PH_SOLVE) = res%log%phase_seconds(PH_SOLVE) + clock%seconds()
       call report_phase(opts%quiet, 'health', clock%seconds())
    end if
    call clock%start()
    allocate (u(table%np, size(model%steps)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the displacements', table%np*size(model%steps)*BYTES_REAL)
       return
    end if
    call tr%expand(q, u)
    if (res%summary%n_condensed > 0) then
       if (is_distributed(res%summary)) then
          call recover_distributed(ctx%cache, parts, f_phys, u, error)
          if (allocated(error)) return
          call parts_ku_distributed(ctx%cache, parts, u, ku, error)
       else
          call recover_parts(ctx%cache, parts, f_phys, u, error)
          if (allocated(error)) return
          call parts_ku(ctx%cache, parts, u, ku)
       end if
       if (allocated(error)) return
       if (tr%ncol() > 0) call full_health(ctx%cache, tr, k, parts, q, u, ku, f_red, f_eff, f_phys, res, &
            summed=owned, error=error)
       if (allocated(error)) return
       call parts_maxratio(model, table, ctx%cache, parts, res, error)
       if (allocated(error)) return
       res%log%phase_seconds(PH_SOLVE) = res%log%phase_seconds(PH_SOLVE) + clock%seconds()
       call report_phase(opts%quiet, 'recover interiors', clock%seconds())
       call clock%start()
    end if
    call wanted_elements(model, opts, wanted, notes)
    if (res%summary%n_condensed > 0) then
       call recover_results(model, table, forest, tr, q, u, f_phys, res, error, wanted, ku)
    else
       call recover_results(model, table, forest, tr, q, u, f_phys, res, error, wanted)
    end if
    if (allocated(error)) return
    res%log%phase_seconds(PH_SOLVE) = res%log%phase_seconds(PH_SOLVE) + clock%seconds()
    call report_phase(opts%quiet, 'recover', clock%seconds())
    if (owned) then
       if (allocated(solver)) call solver%release()
    else
       call keep_factor(ctx%factor, k, solver)   ! released unless ctx%factor%keep
    end if
    res%log%notes = notes
  end subroutine solve_steps

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

  pure function count_delta(tr) result(n)
    !! Number of δ unknowns.
    type(transform_t), intent(in) :: tr
    integer(i8) :: n, j
    n = 0
    do j = 1, tr%ncol()
       if (tr%column_kind(j) == COL_DELTA) n = n + 1
    end do
  end function count_delta

  subroutine factor_and_solve(model, table, tr, k, f_red, opts, groups, solver, q, res, error, owned)
    !! Analyze, factorize (mapping a breakdown to its location) and solve all
    !! steps. owned: k is this process's term of K_red (MUMPS local input).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(in) :: f_red(:, :)
    type(run_options_t), intent(in) :: opts
    integer(i8), allocatable, intent(in) :: groups(:)
    class(linear_solver_t), allocatable, intent(out) :: solver
    real(wp), allocatable, intent(out) :: q(:, :)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in) :: owned
    type(stopwatch_t) :: clock
    character(:), allocatable :: solver_name
    integer(i8) :: jf
    integer :: stat
    character(len=80) :: buf

    solver_name = 'auto'
    if (allocated(opts%solver)) solver_name = opts%solver
    call clock%start()
    call new_solver(solver_name, k%n, solver, error)
    if (allocated(error)) return
    if (allocated(groups)) call solver%set_groups(groups)
    if (owned) then
       select type (solver)
       type is (mumps_solver_t)
          solver%local_input = .true.
       end select
    end if
    call solver%analyze(k, error)
    if (allocated(error)) return
    res%log%phase_seconds(PH_ORDER) = clock%seconds()
    call report_phase(opts%quiet, 'order', res%log%phase_seconds(PH_ORDER), solver%info%ordering)

    call clock%start()
    call solver%factorize(k, error)
    if (allocated(error)) then
       if (error%code == EXIT_SINGULAR) then
          jf = solver%info%failed_column
          deallocate (error)
          call mechanism_error(k, solver_name, model, table, tr, penalty_hint(res), res%fields%mechanism, error, &
               summed=owned)
          if (allocated(error)) return
          if (jf >= 1 .and. jf <= tr%ncol()) then
             call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: '// &
                  'mechanism or singular stiffness at '//column_label(model, table, tr, jf)//penalty_hint(res))
          else
             call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: '// &
                  'stiffness matrix is singular or not positive definite'//penalty_hint(res))
          end if
       end if
       return
    end if
    res%log%phase_seconds(PH_FACTOR) = clock%seconds()
    res%summary%solver_name = solver%info%name
    res%summary%ordering = solver%info%ordering
    res%summary%factor_nnz = solver%info%factor_nnz
    res%summary%factor_mbytes = solver%info%factor_mbytes
    write (buf, '(a,i0)') 'factor nonzeros ', res%summary%factor_nnz
    call report_phase(opts%quiet, 'factor', res%log%phase_seconds(PH_FACTOR), solver%info%name//', '//trim(buf))

    call clock%start()
    allocate (q(k%n, size(f_red, 2)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the solution', k%n*size(f_red, 2)*BYTES_REAL)
       return
    end if
    call solver%solve(f_red, q, error)
    if (allocated(error)) return
    res%log%phase_seconds(PH_SOLVE) = clock%seconds()
    call report_phase(opts%quiet, 'solve', res%log%phase_seconds(PH_SOLVE))
  end subroutine factor_and_solve

end module superjoin_analysis
