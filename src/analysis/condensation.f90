module superjoin_analysis_condensation
  !! The condensed substructures in one solve: their condensations (computed
  !! or reused from the cache the solve context keeps), the loads the interface
  !! sees, interior recovery and their k u for the force recovery.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, add_error_line, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, string_t
  use superjoin_assembly_assemble, only: max_element_diagonal, assemble_stiffness, add_delta_springs
  use superjoin_assembly_transform, only: ROLE_PLAIN
  use superjoin_substructure_local_system, only: dof_label
  use superjoin_substructure_cache, only: part_cache_t, part_view_t, acquire_view, k_holder, entry_condense_loads, &
       entry_ku, entry_ku_reads_loads, view_spc_loads, view_turn, entry_recover, view_need_stiffness, take_views, twins_note
  use superjoin_model_results, only: run_summary_t, run_options_t
  use superjoin_model_notes, only: note
  use superjoin_analysis_factor_reuse, only: kept_factor_t
  use superjoin_analysis_build_reuse, only: kept_build_t, take_matrix, keep_matrix
  use superjoin_utils_strings, only: itoa, pick
  use superjoin_analysis_solve_state, only: solve_state_t, solve_strategy_t, plain_strategy_t
  use superjoin_analysis_matrix_export, only: export_condensed
  implicit none (type, external)
  private

  type, public :: solve_context_t
    !! What outlives one solve: the condensations (reused by later solves of
    !! the same structure with other contact stiffnesses), and whether the run
    !! is a joint study (several sets of contact stiffnesses).
     type(part_cache_t) :: cache
     logical :: joint_study = .false.
     type(kept_factor_t) :: factor          !! loads: a factorization kept for a next solve of the same matrix
     type(kept_build_t) :: build            !! a joint study: the previous value's DOF table and transform
     logical :: last = .false.              !! no later solve reuses the condensations: freed once the interiors are recovered
  end type solve_context_t

  type, extends(solve_strategy_t), public :: condensed_strategy_t
    !! Some substructures condensed, one process: each condensed part enters
    !! K_red as its K* (analysis/solve_state's solve_strategy_t).
  contains
     procedure :: set_plan => condensed_plan
     procedure :: condense => condense_all
     procedure :: recover_interiors => recover_all
  end type condensed_strategy_t

  public :: condense_parts, recover_with_ku, part_solver, library_options, acquire_part, interface_matrix

contains

  subroutine condensed_plan(self, st, model, summary)
    !! The elements of the substructures not condensed, and every K* (moved
    !! from its part, not copied: give_back_supers returns them).
    class(condensed_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_summary_t), intent(in) :: summary
    integer :: i
    associate (no_use => self, no_model => model)   ! summary%sub_condensed names the substructures
    end associate
    st%plan%skip_sub = summary%sub_condensed
    allocate (st%plan%supers(size(st%parts)))
    do i = 1, size(st%parts)
       st%plan%supers(i)%pdof = st%parts(i)%se%pdof
       st%plan%supers(i)%same_k = st%parts(i)%k_of
       if (st%parts(i)%k_of == 0) call move_alloc(st%parts(i)%se%k, st%plan%supers(i)%k)
    end do
    st%plan%supers_moved = .true.
  end subroutine condensed_plan

  subroutine give_back_supers(st)
    !! The plan's K* back to their parts where condensed_plan moved them, the plan's copies freed.
    type(solve_state_t), intent(inout) :: st
    integer :: i
    if (.not. allocated(st%plan%supers)) return
    if (st%plan%supers_moved) then
       do i = 1, size(st%parts)
          if (st%parts(i)%k_of == 0) call move_alloc(st%plan%supers(i)%k, st%parts(i)%se%k)
       end do
    end if
    st%plan%supers_moved = .false.
    deallocate (st%plan%supers)
  end subroutine give_back_supers

  subroutine condense_all(self, st, model, opts, cache, summary, notes, error)
    !! condense_parts.
    class(condensed_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(part_cache_t), intent(inout) :: cache
    type(run_summary_t), intent(inout) :: summary
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    associate (no_use => self)
    end associate
    call condense_parts(st, model, opts, cache, summary, notes, error)
  end subroutine condense_all

  subroutine recover_all(self, st, cache, error)
    !! The interiors of every condensed substructure and their k u.
    class(condensed_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(part_cache_t), intent(inout) :: cache
    type(error_t), allocatable, intent(out) :: error
    associate (no_use => self)
    end associate
    call recover_with_ku(cache, st%parts, st%f_phys, st%u, st%ku, error)
  end subroutine recover_all

  subroutine recover_with_ku(cache, parts, f_phys, u, ku, error)
    !! Interior displacements of every condensed substructure from its
    !! boundary (into u), then k u of each with its own assembled stiffness
    !! (a library entry: from the entry, entry_ku) on the physical DOFs, zero
    !! elsewhere (ku): the element forces of the recovery for those
    !! substructures, without forming an element matrix. The substructures
    !! that share a condensation (instances of one part) side by side: their
    !! columns, turned into the condensation's frame, in one multi-column
    !! solve with the shared factor and one product, then turned back. Loads
    !! and displacements are gathered once; k u is taken of the recovered
    !! columns themselves where the view is not turned, of the displacements
    !! turned back and forth where it is (as they are read from u).
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), intent(in) :: parts(:)
    real(wp), intent(in) :: f_phys(:, :)
    real(wp), intent(inout) :: u(:, :)
    real(wp), allocatable, intent(out) :: ku(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fc(:, :), uc(:, :), y(:, :)
    integer, allocatable :: members(:)
    logical, allocatable :: done(:)
    integer :: i, m, ns, c0
    ns = size(u, 2)
    allocate (done(size(parts)), source=.false.)
    do i = 1, size(parts)
       if (done(i)) cycle
       call sharing(parts, i, members, done)
       call gather_turned(parts, members, f_phys, fc)
       call gather_turned(parts, members, u, uc)
       call entry_recover(cache, parts(i)%entry, fc, uc, ns, error)
       if (allocated(error)) return
       ! ku once the first recovery is done: not beside its solve's work
       if (.not. allocated(ku)) allocate (ku(size(u, 1), ns), source=0.0_wp)
       if (.not. entry_ku_reads_loads(cache, parts(i)%entry)) call move_alloc(fc, y)   ! fc's storage takes k u
       if (.not. allocated(y)) allocate (y(size(uc, 1), size(uc, 2)))
       do m = 1, size(members)
          c0 = (m - 1)*ns
          associate (v => parts(members(m)))
            if (v%rotated) then
               call view_turn(v, uc(:, c0 + 1:c0 + ns), .true.)
               u(v%pdof, :) = uc(:, c0 + 1:c0 + ns)
               call view_turn(v, uc(:, c0 + 1:c0 + ns), .false.)   ! u's rows turned again, for k u
            else
               u(v%pdof, :) = uc(:, c0 + 1:c0 + ns)
            end if
          end associate
       end do
       ! fc: a library entry's recovery leaves it as it was (its k u reads it);
       ! the factor's works in its interior rows, which entry_ku does not read then.
       ! Any other entry's k u reads no loads: fc went to y above (uc stands in).
       if (allocated(fc)) then
          call entry_ku(cache, parts(i)%entry, fc, uc, y, ns, error)
       else
          call entry_ku(cache, parts(i)%entry, uc, uc, y, ns, error)
       end if
       if (allocated(error)) return
       do m = 1, size(members)
          c0 = (m - 1)*ns
          associate (v => parts(members(m)))
            call view_turn(v, y(:, c0 + 1:c0 + ns), .true.)
            ku(v%pdof, :) = ku(v%pdof, :) + y(:, c0 + 1:c0 + ns)
          end associate
       end do
       if (allocated(fc)) deallocate (fc)
       deallocate (uc, y)
    end do
    if (.not. allocated(ku)) allocate (ku(size(u, 1), ns), source=0.0_wp)   ! no condensed part
  end subroutine recover_with_ku

  subroutine interface_matrix(ctx, st, model, summary, error)
    !! K_red and f_u0 of a value (the interface of the condensed parts, or
    !! the whole matrix of a run without them): the strategy's plan
    !! (set_plan: the elements of the parts not condensed, every K*),
    !! assembled (assemble_stiffness, its pattern analyzed beside the values
    !! by an early solver, analysis/analysis) and combined. A joint study's
    !! value that took the previous value's transform and views (one
    !! process, no plain units: their stiffness holds their g) takes the
    !! previous value's K_red without its δ springs (analysis/build_reuse:
    !! take_matrix) and adds its own g's, exactly what the assembly gives.
    type(solve_context_t), intent(inout) :: ctx
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_summary_t), intent(in) :: summary
    type(error_t), allocatable, intent(out) :: error
    type(condensed_strategy_t) :: condensed
    type(plain_strategy_t) :: plain
    logical :: keep, taken, same_views
    keep = ctx%joint_study .and. (same_type_as(st%strategy, condensed) .or. same_type_as(st%strategy, plain))
    if (keep) keep = st%tr%count_role(ROLE_PLAIN) == 0
    same_views = ctx%cache%views_taken .or. summary%n_condensed == 0
    taken = .false.
    if (keep) call take_matrix(ctx%build, same_views, st%k, st%f_u0, taken)
    if (taken) then
       if (st%early_solver) call st%solver%analyze_start(st%k)
    else
       if (allocated(ctx%build%roots)) deallocate (ctx%build%roots)   ! the groups of another K_red
       call st%strategy%set_plan(st, model, summary)
       call assemble_stiffness(model, st%table, st%tr, st%plan, st%k, st%f_u0, error, st%solver, &
            springs=.not. keep)
       call give_back_supers(st)
       if (allocated(error)) return
       if (keep .and. .not. ctx%last) call keep_matrix(ctx%build, st%k, st%f_u0)
    end if
    if (keep) call add_delta_springs(st%tr, st%plan, st%k)
    call st%strategy%combine(st, error)
  end subroutine interface_matrix

  subroutine condense_parts(st, model, opts, cache, summary, notes, error)
    !! The condensations of the condensed substructures (st%parts: computed,
    !! or reused from the cache: another instance of the same part, or an
    !! earlier solve of a joint study), and the loads the interface sees:
    !! st%f_eff, st%f_phys with each condensed boundary replaced by f*
    !! (interior rows have no reduced unknown). Boundary: st%bnd_c.
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(part_cache_t), intent(inout) :: cache
    type(run_summary_t), intent(inout) :: summary
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: solver_name
    integer(i8), allocatable :: spc(:)
    logical, allocatable :: loaded(:)
    integer :: isub, ip_, i, computed0, reused0, nrot
    real(wp) :: dmax
    logical :: taken
    ! The elements of the substructures kept in the interface first, so that
    ! a bad element there is reported as a deck error before a condensation
    ! meets its consequences (condensed ones are checked as they are built).
    if (cache%n == 0) then
       call max_element_diagonal(model, st%table, dmax, error, only=.not. summary%sub_condensed)
       if (allocated(error)) return
    end if
    solver_name = part_solver(opts)
    call library_options(cache, opts)
    st%f_eff = st%f_phys
    computed0 = cache%computed
    reused0 = cache%reused
    call take_views(cache, pack([(isub, isub=1, size(model%subs))], summary%sub_condensed), st%parts, taken)
    if (.not. taken) allocate (st%parts(summary%n_condensed))
    nrot = 0
    ip_ = 0
    associate (table => st%table, bnd => st%bnd_c, f_phys => st%f_phys, parts => st%parts)
      do isub = 1, size(model%subs)
         if (.not. summary%sub_condensed(isub)) cycle
         ip_ = ip_ + 1
         if (taken) then   ! the previous value's view (a joint study)
            call need_stiffness(cache, st, model, parts(ip_), error)
         else
            call acquire_part(cache, st, model, isub, solver_name, parts(ip_), error, parts(1:ip_ - 1))
         end if
         if (allocated(error)) return
         if (allocated(parts(ip_)%notes)) notes = [notes, parts(ip_)%notes]
         if (parts(ip_)%rotated) nrot = nrot + 1
         call view_spc_loads(cache, parts(ip_), f_phys, spc, loaded)
         do i = 1, size(spc)
            if (loaded(i)) then
               call add_error_line(error, EXIT_SINGULAR, 'error: load on a DOF without stiffness: '// &
                    dof_label(model, table, spc(i))//pick(parts(ip_)%rotated, ' in the axes of its part '// &
                    '(turned by its placement: the loaded direction is this DOF turned)', ''))
            else if (.not. parts(ip_)%reused) then
               call note(notes, 'AUTOSPC: '//dof_label(model, table, spc(i))//' has no stiffness and no load: dropped')
            end if
         end do
         if (allocated(error)) return
      end do
    end associate
    call condense_all_loads(cache, st%parts, st%f_phys, st%f_eff, error)
    if (allocated(error)) return
    do ip_ = 1, size(st%parts)
       call export_condensed(model, st%table, st%parts(ip_), st%parts(k_holder(st%parts, ip_))%se%k, &
            st%f_eff(st%parts(ip_)%se%pdof, :), error)
       if (allocated(error)) return
    end do
    call note(notes, 'condensations: '//itoa(cache%computed - computed0)//' computed, '// &
         itoa(cache%reused - reused0)//' reused ('//itoa(nrot)//' turned by their instance''s placement)')
    call twins_note(cache, model, notes)
  end subroutine condense_parts

  subroutine library_options(cache, opts)
    !! The condensation library of the run's options (--library, --library-verify)
    !! and whether identical parts are found by their geometry (--twins).
    type(part_cache_t), intent(inout) :: cache
    type(run_options_t), intent(in) :: opts
    if (allocated(opts%library)) cache%library%dir = opts%library
    cache%library%verify = opts%library_verify
    cache%library%copies = opts%twins
    cache%twins = opts%twins
  end subroutine library_options

  subroutine acquire_part(cache, st, model, isub, solver_name, view, error, before)
    !! The condensation of substructure isub (acquire_view, with the loads a
    !! library entry must be able to condense) and, where its boundary has
    !! prescribed values, its own k (full_health forms k u0 with it; a library
    !! entry is loaded without it). before: the views of the same array so
    !! far (an unturned instance then shares an earlier one's K*).
    type(part_cache_t), intent(inout) :: cache
    type(solve_state_t), intent(in) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    character(*), intent(in) :: solver_name
    type(part_view_t), intent(out) :: view
    type(error_t), allocatable, intent(out) :: error
    type(part_view_t), intent(in), optional :: before(:)
    call acquire_view(cache, model, st%table, isub, st%bnd_c, solver_name, view, error, st%f_phys, before)
    if (allocated(error)) return
    call need_stiffness(cache, st, model, view, error)
  end subroutine acquire_part

  subroutine need_stiffness(cache, st, model, view, error)
    !! The view's own k where its boundary has prescribed values (full_health
    !! forms k u0 with it; a library entry is loaded without it).
    type(part_cache_t), intent(inout) :: cache
    type(solve_state_t), intent(in) :: st
    type(model_t), intent(in) :: model
    type(part_view_t), intent(in) :: view
    type(error_t), allocatable, intent(out) :: error
    if (any(st%tr%prescribed(view%pdof) /= 0.0_wp)) &
         call view_need_stiffness(cache, view, model, st%table, st%bnd_c, error)
  end subroutine need_stiffness

  subroutine condense_all_loads(cache, parts, f_phys, f_eff, error)
    !! f* of every condensed substructure into f_eff's boundary rows. The
    !! substructures that share a condensation (instances of one part) have
    !! their loads condensed together: their columns, turned into the
    !! condensation's frame, side by side in one multi-column solve.
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), intent(in) :: parts(:)
    real(wp), intent(in) :: f_phys(:, :)
    real(wp), intent(inout) :: f_eff(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fc(:, :), fstar(:, :)
    integer, allocatable :: members(:)
    logical, allocatable :: done(:)
    integer :: i, m, ns, c0
    ns = size(f_phys, 2)
    allocate (done(size(parts)), source=.false.)
    do i = 1, size(parts)
       if (done(i)) cycle
       call sharing(parts, i, members, done)
       allocate (fstar(parts(i)%nb, ns*size(members)))
       call gather_turned(parts, members, f_phys, fc)
       call entry_condense_loads(cache, parts(i)%entry, fc, fstar, ns, error)
       if (allocated(error)) return
       do m = 1, size(members)
          c0 = (m - 1)*ns
          associate (v => parts(members(m)))
            call view_turn(v, fstar(:, c0 + 1:c0 + ns), .true., v%ni)
            f_eff(v%se%pdof, :) = fstar(:, c0 + 1:c0 + ns)
          end associate
       end do
       deallocate (fc, fstar)
    end do
  end subroutine condense_all_loads

  subroutine sharing(parts, i, members, done)
    !! The views from i on that use the same condensation as parts(i)
    !! (marked done).
    type(part_view_t), intent(in) :: parts(:)
    integer, intent(in) :: i
    integer, allocatable, intent(out) :: members(:)
    logical, intent(inout) :: done(:)
    integer :: j
    members = pack([(j, j=i, size(parts))], parts(i:)%entry == parts(i)%entry)
    done(members) = .true.
  end subroutine sharing

  subroutine gather_turned(parts, members, x, y)
    !! The rows of x (physical DOFs) of each member view, turned into the
    !! condensation's frame, side by side: y(:, (m-1) ns + 1 : m ns).
    type(part_view_t), intent(in) :: parts(:)
    integer, intent(in) :: members(:)
    real(wp), intent(in) :: x(:, :)
    real(wp), allocatable, intent(out) :: y(:, :)
    integer :: m, ns, c0
    ns = size(x, 2)
    allocate (y(size(parts(members(1))%pdof), ns*size(members)))
    do m = 1, size(members)
       c0 = (m - 1)*ns
       y(:, c0 + 1:c0 + ns) = x(parts(members(m))%pdof, :)
       call view_turn(parts(members(m)), y(:, c0 + 1:c0 + ns), .false.)
    end do
  end subroutine gather_turned

  function part_solver(opts) result(name)
    !! The solver of the condensations: the one asked for. Under MPI each
    !! part is condensed by one process alone: a MUMPS part solver is an
    !! instance of that process alone (superjoin_substructure_condensed sets
    !! it so), which forms K* by MUMPS's Schur complement; one process does
    !! the same, so that its results equal those of several.
    type(run_options_t), intent(in) :: opts
    character(:), allocatable :: name
    name = 'auto'
    if (allocated(opts%solver)) name = opts%solver
  end function part_solver
end module superjoin_analysis_condensation
