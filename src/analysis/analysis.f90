module superjoin_analysis
  !! The solution pipeline: DOFs → forest → Δu transform → assembly → AUTOSPC →
  !! factorization (once for all steps) → solve → health checks → recovery.
  use, intrinsic :: iso_fortran_env, only: error_unit
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, add_error_line, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, string_t, FORM_TRANSFORM, FORM_PENALTY, RIGID_LARGE, DEFAULT_PENALTY_LARGE, &
       LINK_FINITE, LINK_RIGID, node_label, CONDENSE_YES, CONDENSE_NO, CONDENSE_AUTO
  use superjoin_assembly_dofs, only: dof_table_t, build_dof_table, UNIT_LINK, UNIT_SUPPORT, GROUND, block_dof
  use superjoin_assembly_forest, only: forest_t, build_forest
  use superjoin_assembly_transform, only: transform_t, constraint_t, build_transform, COL_PHYS, COL_DELTA, ROLE_TREE, &
       ROLE_PLAIN, CONS_REDUNDANT, CONS_ELIMINATED
  use superjoin_assembly_assemble, only: assemble_stiffness, assemble_loads, max_element_diagonal, &
       assembly_plan_t, superelement_t
  use superjoin_substructure_local_system, only: boundary_dofs, part_boundary, dof_label
  use superjoin_substructure_cache, only: release_cache, part_cache_t, part_view_t, acquire_view, view_condense_loads, &
       view_recover, view_residual, view_stiffness_times, view_maxratio, view_spc
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, condition_estimate, norm1_sym
  use superjoin_output_matrix_market, only: write_matrix_market
  use superjoin_analysis_results, only: results_t, run_options_t, PH_ASSEMBLE, PH_ORDER, PH_FACTOR, PH_SOLVE
  use superjoin_analysis_recover, only: recover_results
  use superjoin_analysis_penalty, only: apply_penalty_default, penalty_default_note
  use superjoin_analysis_mechanism, only: mechanism_error
  use superjoin_utils_clock, only: stopwatch_t, report_phase
  use superjoin_utils_union_find, only: find_root
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: ieee_exceptions, only: ieee_flag_type, ieee_get_halting_mode, ieee_set_halting_mode, &
       ieee_overflow, ieee_invalid, ieee_divide_by_zero
  implicit none (type, external)
  private

  real(wp), parameter, public :: REFINE_BERR = 10*epsilon(1.0_wp)
    !! iterative refinement runs while the backward error exceeds this,
  real(wp), parameter, public :: REFINE_RESIDUAL = 1.0e-9_wp
    !! or while the relative residual or |EPSILON| of a step exceeds this
  real(wp), parameter, public :: REFINE_GAIN = 0.5_wp
    !! and while each step multiplies the largest residual by at most this
  integer, parameter, public :: MAX_REFINE = 3
    !! At most this many refinement steps.
  real(wp), parameter, public :: MAXRATIO_WARN = 1.0e6_wp
    !! MAXRATIO above this is flagged as a loss of accuracy (digits lost ≈ log10):
    !! PENALTY's measured errors reach 10 MAXRATIO ε, so past 1e6 fewer than 8 digits are sure.
  real(wp), parameter, public :: MAXRATIO_FATAL = 1.0e13_wp
    !! MAXRATIO above this (a pivot within about 1/(45 ε) of total cancellation)
    !! is numerically singular (exit 3): exact mechanisms factor with MAXRATIO
    !! from about 5e13 up, and nothing meaningful is left of an answer above 1e13.
  real(wp), parameter :: RATIO_CAP = 1.0e300_wp
    !! MAXRATIO reported when K_jj / D_jj would overflow.
  real(wp), parameter :: AUTO_KSTAR_BYTES = 2.0_wp*2.0_wp**30
    !! CONDENSE=AUTO condenses no part whose dense K* would exceed this (2 GiB).
  real(wp), parameter, public :: RESIDUAL_WARN = 1.0e-6_wp
    !! A relative residual still above this after refinement is reported as a warning.
  real(wp), parameter, public :: RESIDUAL_WARN_PENALTY = 1.0e-4_wp
    !! The same under PENALTY, whose residual floor is about eps x g / k (the
    !! penalty springs' forces on round-off): 1e-6 to 1e-5 with the default
    !! g = k / sqrt(eps) on the bundled decks, whose displacements then agree with
    !! TRANSFORM to 1.4e-6 relative or better (doc/verification.md).

  public :: solve_model, solve_group, release_cache

  type, public :: solve_context_t
    !! What outlives one solve: the condensations (reused by later solves of
    !! the same structure with other contact stiffnesses), and whether the run
    !! is a joint study (several sets of contact stiffnesses).
     type(part_cache_t) :: cache
     logical :: joint_study = .false.
  end type solve_context_t

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

  subroutine check_finite(model, res, error)
    !! EXIT_SINGULAR error naming the first kind of result that is not finite
    !! (including the surface stresses n/t ± 6 m/t² the listing derives).
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: what
    integer :: is, isub
    integer(ip) :: e
    real(wp) :: t
    if (allocated(res%u)) then
       if (.not. all(ieee_is_finite(res%u))) what = 'displacements'
    end if
    if (.not. allocated(what) .and. allocated(res%elem_force)) then
       if (.not. all(ieee_is_finite(res%elem_force))) what = 'element forces'
    end if
    if (.not. allocated(what) .and. allocated(res%plate)) then
       if (.not. all(ieee_is_finite(res%plate))) what = 'plate resultants'
    end if
    if (.not. allocated(what) .and. allocated(res%plate)) then
       do isub = 1, size(model%subs)
          do e = 1, model%subs(isub)%nelem
             if (model%subs(isub)%elem_section(e) == 0) cycle
             t = model%subs(isub)%sections(model%subs(isub)%elem_section(e))%thickness
             if (t <= 0.0_wp) cycle
             associate (p => res%plate(:, res%elem_offset(isub) + e, :))
               if (any(too_big(p(1:3, :), t, 1)) .or. any(too_big(6.0_wp*p(4:6, :), t, 2))) &
                    what = 'plate stresses'
             end associate
          end do
       end do
    end if
    if (.not. allocated(what) .and. allocated(res%steps)) then
       do is = 1, size(res%steps)
          associate (st => res%steps(is))
            if (allocated(st%reactions)) then
               if (.not. all(ieee_is_finite(st%reactions(:)%force))) what = 'support reactions'
            end if
            if (allocated(st%link_force)) then
               if (.not. (all(ieee_is_finite(st%link_force)) .and. all(ieee_is_finite(st%link_delta)))) &
                    what = 'contact forces'
            end if
            if (.not. (all(ieee_is_finite(st%applied)) .and. all(ieee_is_finite(st%reaction)))) &
                 what = 'equilibrium resultants'
            if (.not. (ieee_is_finite(st%residual) .and. ieee_is_finite(st%epsilon))) what = 'residuals'
          end associate
          if (allocated(what)) exit
       end do
    end if
    if (.not. allocated(what)) return
    call fatal_error(error, EXIT_SINGULAR, 'error: the '//what//' overflow the floating-point range '// &
         '(beyond 1.8E+308 or undefined): check the magnitudes and units of loads, stiffnesses, '// &
         'contact g and coordinates')
  end subroutine check_finite

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
    logical, allocatable :: bnd(:), bnd_c(:), keep(:)
    type(assembly_plan_t) :: plan
    type(part_view_t), allocatable :: parts(:)
    real(wp), allocatable :: f_eff(:, :), u(:, :), ku(:, :)
    integer(i8) :: p
    integer :: i, stat

    allocate (notes(0), res%warnings(0))
    res%maxratio_at = 'n/a (no unknowns)'
    call clock%start()
    form = model%controls%formulation
    if (opts%formulation /= 0) form = opts%formulation
    res%formulation = merge('TRANSFORM', 'PENALTY  ', form == FORM_TRANSFORM)
    res%formulation = trim(res%formulation)

    call build_dof_table(model, table, error)
    if (allocated(error)) return
    if (size(table%ignored_links) > 0) call note(notes, itoa(size(table%ignored_links))// &
         ' contact element(s) name DOFs that neither node carries; those DOFs are not connected')
    call apply_large(model, table, form, notes, error)
    if (allocated(error)) return
    call build_forest(table, form == FORM_TRANSFORM, forest, error)
    if (allocated(error)) return
    call boundary_dofs(table, bnd)
    call count_boundary(model, table, bnd, res)
    ! Condensation boundaries: the instances of a part share theirs.
    call part_boundary(model, table, bnd, bnd_c)
    call choose_condensation(model, table, opts, ctx, bnd_c, res, notes)
    allocate (keep(table%np))
    do p = 1, table%np
       keep(p) = bnd_c(p) .or. .not. res%sub_condensed(table%p_sub(p))
    end do
    call build_transform(model, table, forest, tr, error, keep)
    if (allocated(error)) return
    call describe_transform(model, table, tr, form, res, notes)

    if (res%n_condensed == 0) then
       allocate (plan%skip_sub(size(model%subs)), source=.false.)
       allocate (plan%supers(0))
       call assemble_stiffness(model, table, tr, plan, k, f_u0, error)
       if (allocated(error)) return
       call assemble_loads(model, table, f_phys, error)
       if (allocated(error)) return
       call reduce_loads(tr, f_phys, f_u0, f_red, error)
    else
       call assemble_loads(model, table, f_phys, error)
       if (allocated(error)) return
       call condense_parts(model, table, bnd_c, opts, f_phys, ctx%cache, res, notes, parts, f_eff, error)
       if (allocated(error)) return
       plan%skip_sub = res%sub_condensed
       allocate (plan%supers(size(parts)))
       do i = 1, size(parts)
          plan%supers(i) = parts(i)%se
       end do
       call assemble_stiffness(model, table, tr, plan, k, f_u0, error)
       if (allocated(error)) return
       deallocate (plan%supers)
       call reduce_loads(tr, f_eff, f_u0, f_red, error)
    end if
    if (allocated(error)) return
    call autospc(model, table, tr, k, f_red, spc, notes, error)
    if (allocated(error)) return
    call skip_unloaded_parts(model, table, tr, k, f_red, spc, notes)
    res%nphys = table%np
    res%ncol = tr%ncol()
    res%neq = tr%ncol() - count(spc, kind=i8)
    res%ndelta = count_delta(tr)
    res%matrix_nnz = k%nnz()
    res%phase_seconds(PH_ASSEMBLE) = clock%seconds()
    write (buf, '(a,i0,a,i0)') 'equations ', res%neq, ', nonzeros ', res%matrix_nnz
    call report_phase(opts%quiet, 'assemble', res%phase_seconds(PH_ASSEMBLE), trim(buf))

    if (allocated(opts%export_matrix)) then
       call write_matrix_market(opts%export_matrix, k, error)
       if (allocated(error)) return
    end if

    if (tr%ncol() > 0) then
       call column_groups(table, forest, tr, groups)
       call factor_and_solve(model, table, tr, k, f_red, opts, groups, solver, q, res, error)
       if (allocated(error)) return
    else
       allocate (q(0, size(model%steps)))
       res%solver_name = 'none (no unknowns)'
       res%ordering = 'none'
    end if

    ! Health first: iterative refinement may still improve q.
    allocate (res%steps(size(model%steps)))
    if (tr%ncol() > 0) then
       call clock%start()
       call health(k, q, f_red, spc, solver, model, table, tr, res, opts, error)
       if (allocated(error)) return
       res%phase_seconds(PH_SOLVE) = res%phase_seconds(PH_SOLVE) + clock%seconds()
       call report_phase(opts%quiet, 'health', clock%seconds())
    end if
    call clock%start()
    allocate (u(table%np, size(model%steps)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the displacements', table%np*size(model%steps)*BYTES_REAL)
       return
    end if
    call tr%expand(q, u)
    if (res%n_condensed > 0) then
       call recover_parts(ctx%cache, parts, f_phys, u, error)
       if (allocated(error)) return
       if (tr%ncol() > 0) call full_health(ctx%cache, tr, k, parts, q, u, f_red, f_eff, f_phys, res)
       call parts_maxratio(model, table, ctx%cache, parts, res, error)
       if (allocated(error)) return
       res%phase_seconds(PH_SOLVE) = res%phase_seconds(PH_SOLVE) + clock%seconds()
       call report_phase(opts%quiet, 'recover interiors', clock%seconds())
       call clock%start()
    end if
    if (res%n_condensed > 0) then
       call parts_ku(ctx%cache, parts, u, ku)
       call recover_results(model, table, forest, tr, q, u, f_phys, res, error, ku)
    else
       call recover_results(model, table, forest, tr, q, u, f_phys, res, error)
    end if
    if (allocated(error)) return
    res%phase_seconds(PH_SOLVE) = res%phase_seconds(PH_SOLVE) + clock%seconds()
    call report_phase(opts%quiet, 'recover', clock%seconds())
    if (allocated(solver)) call solver%release()
    res%notes = notes
  end subroutine solve_steps

  subroutine apply_large(model, table, form, notes, error)
    !! RIGID contacts become g = LARGE × (largest element diagonal) under
    !! RIGID=LARGE, and under PENALTY (which has no exact elimination).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    integer, intent(in) :: form
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: dmax, glarge
    integer :: iu
    logical :: any_rigid
    character(len=32) :: buf

    if (model%controls%rigid /= RIGID_LARGE .and. form /= FORM_PENALTY) return
    any_rigid = .false.
    do iu = 1, table%nunit
       if (table%units(iu)%kind == UNIT_LINK) any_rigid = any_rigid .or. &
            any(table%units(iu)%state(1:table%units(iu)%n) == LINK_RIGID)
    end do
    if (.not. any_rigid) return
    if (form == FORM_PENALTY .and. .not. model%controls%large_given) then
       call apply_penalty_default(model, table, DEFAULT_PENALTY_LARGE, dmax, glarge, error)
       if (.not. allocated(error)) call note(notes, penalty_default_note(dmax, glarge))
       return
    end if
    call max_element_diagonal(model, table, dmax, error)
    if (allocated(error)) return
    if (dmax <= 0.0_wp) dmax = 1.0_wp
    glarge = model%controls%large*dmax
    do iu = 1, table%nunit
       associate (u => table%units(iu))
         if (u%kind /= UNIT_LINK) cycle
         where (u%state(1:u%n) == LINK_RIGID)
            u%g(1:u%n) = glarge
            u%state(1:u%n) = LINK_FINITE
         end where
       end associate
    end do
    write (buf, '(es10.3)') glarge
    call note(notes, 'RIGID contacts use g = LARGE x largest element diagonal = '//trim(adjustl(buf)))
  end subroutine apply_large

  subroutine describe_transform(model, table, tr, form, res, notes)
    !! Notes on what was transformed and what was assembled plainly.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    integer, intent(in) :: form
    type(results_t), intent(inout) :: res
    type(string_t), allocatable, intent(inout) :: notes(:)
    integer :: iu, i
    type(constraint_t) :: cs
    res%n_tree = 0
    res%n_plain = 0
    res%n_support_units = 0
    do iu = 1, table%nunit
       associate (u => table%units(iu))
         if (u%kind == UNIT_SUPPORT) then
            res%n_support_units = res%n_support_units + 1
            if (tr%unit_role(iu) == ROLE_PLAIN) call note(notes, 'support at '//vertex_label(model, table, u%vb)// &
                 ' '//block_name(u%block)//' closes a loop through the ground: assembled plainly')
         else if (tr%unit_role(iu) == ROLE_TREE) then
            res%n_tree = res%n_tree + 1
         else
            res%n_plain = res%n_plain + 1
            if (form == FORM_TRANSFORM) call note(notes, 'contact '//model%contacts(model%links(u%source)%contact)%name// &
                 ' '//vertex_label(model, table, u%va)//' - '//vertex_label(model, table, u%vb)//' '// &
                 block_name(u%block)//': closes a loop, assembled plainly')
         end if
       end associate
       do i = 1, tr%nconstraints()
          cs = tr%constraint(i)
          if (cs%unit /= iu) cycle
          associate (u => table%units(iu))
            if (cs%status == CONS_REDUNDANT) then
               call note(notes, '  RIGID '//local_name(u%block, u%lcomp(cs%k))//' of that unit is redundant '// &
                    '(already implied by the tree); its force is carried by the tree')
            else if (cs%status == CONS_ELIMINATED) then
               call note(notes, '  RIGID '//local_name(u%block, u%lcomp(cs%k))//' of that unit is enforced exactly '// &
                    'by eliminating one unknown')
            end if
          end associate
       end do
    end do
  end subroutine describe_transform

  subroutine column_groups(table, forest, tr, first)
    !! Columns grouped by node (a node's own DOFs and the δ of the contact
    !! above it are numbered together): first(g) is the first column of group g.
    !! Unallocated when the columns of a node are not consecutive.
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(in) :: tr
    integer(i8), allocatable, intent(out) :: first(:)
    integer(i8), allocatable :: vert(:)
    integer(i8) :: j, p, ng
    integer :: iu
    allocate (vert(tr%ncol()))
    do j = 1, tr%ncol()
       if (tr%column_kind(j) == COL_PHYS) then
          p = tr%column_ref(j)
          vert(j) = table%vertex_offset(table%p_sub(p)) + table%p_node(p)
       else
          iu = int(tr%column_ref(j))
          if (forest%child_is_a(iu)) then
             vert(j) = table%units(iu)%va
          else
             vert(j) = table%units(iu)%vb
          end if
       end if
       if (j > 1) then
          if (vert(j) < vert(j - 1)) return
       end if
    end do
    ng = 0
    do j = 1, tr%ncol()
       if (j == 1) then
          ng = 1
       else if (vert(j) /= vert(j - 1)) then
          ng = ng + 1
       end if
    end do
    allocate (first(ng + 1))
    ng = 0
    do j = 1, tr%ncol()
       if (j == 1) then
          ng = 1
          first(1) = 1
       else if (vert(j) /= vert(j - 1)) then
          ng = ng + 1
          first(ng) = j
       end if
    end do
    first(ng + 1) = tr%ncol() + 1
  end subroutine column_groups

  subroutine count_boundary(model, table, bnd, res)
    !! Active and boundary DOFs per substructure: the boundary DOFs (those a
    !! contact or support touches) form k_bb, the others k_ii.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    type(results_t), intent(inout) :: res
    integer(i8) :: p
    integer :: isub
    allocate (res%sub_dofs(size(model%subs)), res%sub_boundary(size(model%subs)), source=0_i8)
    do p = 1, table%np
       isub = table%p_sub(p)
       res%sub_dofs(isub) = res%sub_dofs(isub) + 1
       if (bnd(p)) res%sub_boundary(isub) = res%sub_boundary(isub) + 1
    end do
  end subroutine count_boundary

  subroutine choose_condensation(model, table, opts, ctx, bnd, res, notes)
    !! Which substructures are condensed. CONDENSE=YES (deck or --condense)
    !! condenses a substructure that has both interior and boundary DOFs.
    !! AUTO condenses where a condensation is reused: an instance of a part
    !! placed more than once (one condensation for all its instances), and
    !! every substructure of a joint study (the parts are condensed once, each
    !! further set of contact stiffnesses factors only the interface), provided
    !! its K* (n_b² doubles) stays within AUTO_KSTAR_BYTES and its boundary is
    !! smaller than its interior. Otherwise AUTO keeps the part in the one
    !! sparse matrix: for a single factorization a fill-reducing ordering of
    !! the whole model already exploits the cut. NO never condenses.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(in) :: ctx
    logical, intent(in) :: bnd(:)              !! condensation boundary
    type(results_t), intent(inout) :: res
    type(string_t), allocatable, intent(inout) :: notes(:)
    integer :: isub, mode, ninst
    integer(i8) :: nb, ni, p
    integer(i8), allocatable :: nbs(:)
    character(:), allocatable :: why, small
    small = ''
    allocate (res%sub_condensed(size(model%subs)), source=.false.)
    allocate (nbs(size(model%subs)), source=0_i8)
    do p = 1, table%np
       if (bnd(p)) nbs(table%p_sub(p)) = nbs(table%p_sub(p)) + 1
    end do
    res%n_condensed = 0
    do isub = 1, size(model%subs)
       mode = model%subs(isub)%condense
       if (opts%condense >= 0) mode = opts%condense
       nb = nbs(isub)
       ni = res%sub_dofs(isub) - nb
       if (mode == CONDENSE_NO) cycle
       if (mode == CONDENSE_AUTO) then
          ninst = 0
          if (model%subs(isub)%part > 0) ninst = count(model%subs(:)%part == model%subs(isub)%part)
          if (ninst > 1) then
             why = 'AUTO: one of '//itoa(ninst)//' instances of part '//model%parts(model%subs(isub)%part)%s
          else if (ctx%joint_study) then
             why = 'AUTO: joint study'
          else
             cycle
          end if
          if (nb == 0 .or. ni == 0) cycle
          if (nb >= ni) then
             small = small//' '//model%subs(isub)%name
             cycle
          end if
          if (real(nb, wp)**2*BYTES_REAL > AUTO_KSTAR_BYTES) then
             call note(notes, 'substructure '//model%subs(isub)%name//' not condensed ('//why// &
                  '): its K* would take '//itoa(nb*nb*BYTES_REAL/2**20)//' MiB')
             cycle
          end if
       else
          why = 'CONDENSE=YES'
       end if
       if (nb == 0) then
          call note(notes, 'substructure '//model%subs(isub)%name//' not condensed: no contact or support '// &
               'touches it (a separate system)')
       else if (ni == 0) then
          call note(notes, 'substructure '//model%subs(isub)%name//' not condensed: every DOF is on its boundary')
       else
          res%sub_condensed(isub) = .true.
          res%n_condensed = res%n_condensed + 1
          call note(notes, 'substructure '//model%subs(isub)%name//' condensed ('//why//'): '// &
               itoa(ni)//' interior DOFs eliminated, K* of order '//itoa(nb)//' on its boundary')
       end if
    end do
    if (len(small) > 0) call note(notes, 'CONDENSE=AUTO: not condensed, the boundary being no smaller '// &
         'than the interior:'//small)
  end subroutine choose_condensation

  subroutine condense_parts(model, table, bnd, opts, f_phys, cache, res, notes, parts, f_eff, error)
    !! The condensations of the condensed substructures (computed, or reused
    !! from the cache: another instance of the same part, or an earlier solve
    !! of a joint study), and the loads the interface sees: f_phys with each
    !! condensed boundary replaced by f* (interior rows have no reduced unknown).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    type(run_options_t), intent(in) :: opts
    real(wp), intent(in) :: f_phys(:, :)
    type(part_cache_t), intent(inout) :: cache
    type(results_t), intent(inout) :: res
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(part_view_t), allocatable, intent(out) :: parts(:)
    real(wp), allocatable, intent(out) :: f_eff(:, :)
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: solver_name
    real(wp), allocatable :: fstar(:, :)
    integer(i8), allocatable :: spc(:)
    integer :: isub, ip_, i, computed0, reused0, nrot
    real(wp) :: dmax
    ! The elements of the substructures kept in the interface first, so that
    ! a bad element there is reported as a deck error before a condensation
    ! meets its consequences (condensed ones are checked as they are built).
    if (cache%n == 0) then
       call max_element_diagonal(model, table, dmax, error, only=.not. res%sub_condensed)
       if (allocated(error)) return
    end if
    solver_name = 'auto'
    if (allocated(opts%solver)) solver_name = opts%solver
    allocate (parts(res%n_condensed))
    f_eff = f_phys
    computed0 = cache%computed
    reused0 = cache%reused
    nrot = 0
    ip_ = 0
    do isub = 1, size(model%subs)
       if (.not. res%sub_condensed(isub)) cycle
       ip_ = ip_ + 1
       call acquire_view(cache, model, table, isub, bnd, solver_name, parts(ip_), error)
       if (allocated(error)) return
       if (parts(ip_)%rotated) nrot = nrot + 1
       call view_spc(cache, parts(ip_), spc)
       do i = 1, size(spc)
          if (any(f_phys(spc(i), :) /= 0.0_wp)) then
             call add_error_line(error, EXIT_SINGULAR, 'error: load on a DOF without stiffness: '// &
                  dof_label(model, table, spc(i)))
          else if (.not. parts(ip_)%reused) then
             call note(notes, 'AUTOSPC: '//dof_label(model, table, spc(i))//' has no stiffness and no load: dropped')
          end if
       end do
       if (allocated(error)) return
       allocate (fstar(parts(ip_)%nb, size(f_phys, 2)))
       call view_condense_loads(cache, parts(ip_), f_phys(parts(ip_)%pdof, :), fstar, error)
       if (allocated(error)) return
       f_eff(parts(ip_)%se%pdof, :) = fstar
       deallocate (fstar)
    end do
    call note(notes, 'condensations: '//itoa(cache%computed - computed0)//' computed, '// &
         itoa(cache%reused - reused0)//' reused ('//itoa(nrot)//' turned by their instance''s placement)')
  end subroutine condense_parts

  subroutine recover_parts(cache, parts, f_phys, u, error)
    !! Interior displacements of every condensed substructure from its boundary.
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), intent(in) :: parts(:)
    real(wp), intent(in) :: f_phys(:, :)
    real(wp), intent(inout) :: u(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ul(:, :)
    integer :: i
    do i = 1, size(parts)
       ul = u(parts(i)%pdof, :)
       call view_recover(cache, parts(i), f_phys(parts(i)%pdof, :), ul, error)
       if (allocated(error)) return
       u(parts(i)%pdof, :) = ul
    end do
  end subroutine recover_parts

  subroutine parts_ku(cache, parts, u, ku)
    !! k u of every condensed substructure, with its own assembled stiffness,
    !! on the physical DOFs (zero elsewhere): the element forces of the
    !! recovery for those substructures, without forming an element matrix.
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: parts(:)
    real(wp), intent(in) :: u(:, :)
    real(wp), allocatable, intent(out) :: ku(:, :)
    real(wp), allocatable :: y(:, :)
    integer :: i
    allocate (ku(size(u, 1), size(u, 2)), source=0.0_wp)
    do i = 1, size(parts)
       allocate (y(size(parts(i)%pdof), size(u, 2)))
       call view_stiffness_times(cache, parts(i), u(parts(i)%pdof, :), y)
       ku(parts(i)%pdof, :) = ku(parts(i)%pdof, :) + y
       deallocate (y)
    end do
  end subroutine parts_ku

  subroutine full_health(cache, tr, k, parts, q, u, f_red, f_eff, f_phys, res)
    !! Residual and EPSILON of the whole reduced system, as if it had been
    !! solved monolithically, from the recovered displacements and each
    !! condensed substructure's own stiffness (so an error in a condensation
    !! or a recovery shows). Unknowns: the interface columns q, then every
    !! condensed interior u_i. Interface rows: K_if q − f_if plus, for each
    !! part, Mᵀ[(k u − f)_b − (K* u_b − f*)]; interior rows: k_ii u_i + k_ib u_b − f_i.
    !! The loads likewise, with the prescribed values' terms (−k u0).
    type(part_cache_t), intent(in) :: cache
    type(transform_t), intent(in) :: tr
    type(sparse_sym_t), intent(in) :: k
    type(part_view_t), intent(in) :: parts(:)
    real(wp), intent(in) :: q(:, :), u(:, :), f_red(:, :), f_eff(:, :), f_phys(:, :)
    type(results_t), intent(inout) :: res
    real(wp), allocatable :: r(:, :), f(:, :), rl(:, :), u0l(:, :), w(:, :), ks(:, :), ku0(:), &
         rf(:, :), ffull(:, :), qfull(:, :)
    integer :: i, is, nstep
    integer(i8) :: ni, nb, l, ntot, at
    character(len=32) :: buf
    nstep = size(q, 2)
    allocate (r(k%n, nstep))
    call k%matvec(q, r)
    r = r - f_red
    f = f_red
    ntot = k%n
    do i = 1, size(parts)
       ntot = ntot + parts(i)%ni
    end do
    allocate (rf(ntot, nstep), ffull(ntot, nstep), qfull(ntot, nstep))
    at = k%n
    do i = 1, size(parts)
       associate (sys => parts(i), kst => parts(i)%se%k)
         ni = sys%ni
         nb = sys%nb
         allocate (rl(ni + nb, nstep), u0l(ni + nb, 1), w(ni + nb, 1))
         call view_residual(cache, parts(i), u(sys%pdof, :), f_phys(sys%pdof, :), rl)
         u0l = 0.0_wp
         u0l(ni + 1:, 1) = tr%prescribed(sys%pdof(ni + 1:))
         if (any(u0l /= 0.0_wp)) then
            call view_stiffness_times(cache, parts(i), u0l, w)
         else
            w = 0.0_wp
         end if
         ks = matmul(kst, u(sys%pdof(ni + 1:), :))
         ku0 = matmul(kst, u0l(ni + 1:, 1))
         rf(at + 1:at + ni, :) = rl(1:ni, :)
         do is = 1, nstep
            ffull(at + 1:at + ni, is) = f_phys(sys%pdof(1:ni), is) - w(1:ni, 1)
         end do
         qfull(at + 1:at + ni, :) = u(sys%pdof(1:ni), :)
         at = at + ni
         do l = 1, nb
            associate (pb => sys%pdof(ni + l))
              call tr%reduce_add(pb, rl(ni + l, :) - (ks(l, :) - f_eff(pb, :)), r)
              call tr%reduce_add(pb, (f_phys(pb, :) - w(ni + l, 1)) - (f_eff(pb, :) - ku0(l)), f)
            end associate
         end do
         deallocate (rl, u0l, w)
       end associate
    end do
    rf(1:k%n, :) = r
    ffull(1:k%n, :) = f
    qfull(1:k%n, :) = q
    do is = 1, nstep
       res%steps(is)%residual = safe_div(norm2(rf(:, is)), norm2(ffull(:, is)))
       res%steps(is)%epsilon = energy_error(qfull(:, is), rf(:, is), ffull(:, is))
    end do
    if (maxval(res%steps(:)%residual) > RESIDUAL_WARN) then
       write (buf, '(es10.2e3)') maxval(res%steps(:)%residual)
       call warn(res, 'relative residual '//trim(adjustl(buf))//' of the whole system (condensed '// &
            'substructures recovered): results are inaccurate')
    end if
  end subroutine full_health

  subroutine parts_maxratio(model, table, cache, parts, res, error)
    !! MAXRATIO over the interior factors of the condensed substructures:
    !! the largest of them and the interface's is reported, with its place.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: parts(:)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    character(len=32) :: buf
    real(wp) :: ratio
    integer(i8) :: p
    integer :: i
    do i = 1, size(parts)
       call view_maxratio(cache, parts(i), ratio, p)
       if (ratio <= res%maxratio .or. p == 0) cycle
       res%maxratio = ratio
       res%maxratio_at = dof_label(model, table, p)
       write (buf, '(es10.2e3)') res%maxratio
       if (res%maxratio > MAXRATIO_FATAL) then
          call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: stiffness is '// &
               'numerically singular at '//res%maxratio_at//' (MAXRATIO '//trim(adjustl(buf))// &
               '): a mechanism, or a stiffness contrast beyond double precision')
          return
       end if
       if (res%maxratio > MAXRATIO_WARN) call warn(res, 'MAXRATIO '//trim(adjustl(buf))//' at '// &
            res%maxratio_at//': about '//itoa(nint(log10(res%maxratio)))//' digits may be lost')
    end do
  end subroutine parts_maxratio

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

  subroutine autospc(model, table, tr, k, f_red, spc, notes, error)
    !! Unknowns with no stiffness at all: dropped (diagonal 1, load 0) when
    !! unloaded, reported; a loaded one is an error (exit 3).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(inout) :: f_red(:, :)
    logical, allocatable, intent(out) :: spc(:)
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: nz(:)
    integer(i8) :: j, pos
    allocate (nz(tr%ncol()), source=.false.)
    allocate (spc(tr%ncol()), source=.false.)
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) /= 0.0_wp) then
             nz(j) = .true.
             nz(k%rowind(pos)) = .true.
          end if
       end do
    end do
    do j = 1, tr%ncol()
       if (nz(j)) cycle
       if (any(f_red(j, :) /= 0.0_wp)) then
          call add_error_line(error, EXIT_SINGULAR, 'error: load on a DOF without stiffness: '// &
               column_label(model, table, tr, j))
          cycle
       end if
       spc(j) = .true.
       k%val(k%colptr(j + 1) - 1) = 1.0_wp
       call note(notes, 'AUTOSPC: '//column_label(model, table, tr, j)//' has no stiffness and no load: dropped')
    end do
  end subroutine autospc

  subroutine skip_unloaded_parts(model, table, tr, k, f_red, spc, notes)
    !! Groups of unknowns coupled to nothing else and loaded in no step have a
    !! zero solution: they are taken out of the factorization (identity rows)
    !! and reported, so an unloaded free part is not a mechanism.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(in) :: f_red(:, :)
    logical, intent(inout) :: spc(:)
    type(string_t), allocatable, intent(inout) :: notes(:)
    integer(i8), allocatable :: root(:)
    logical, allocatable :: loaded(:), skip(:), named(:)
    integer(i8) :: j, pos, a, b, nskip
    integer :: isub
    character(:), allocatable :: subs

    if (k%n == 0) return
    allocate (root(0:k%n))
    do j = 0, k%n
       root(j) = j
    end do
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) == 0.0_wp) cycle
          a = find_root(root, k%rowind(pos))
          b = find_root(root, j)
          if (a /= b) root(max(a, b)) = min(a, b)
       end do
    end do
    allocate (loaded(k%n), source=.false.)
    do j = 1, k%n
       root(j) = find_root(root, j)
       if (any(f_red(j, :) /= 0.0_wp)) loaded(root(j)) = .true.
    end do
    allocate (skip(k%n))
    nskip = 0
    do j = 1, k%n
       skip(j) = .not. loaded(root(j)) .and. .not. spc(j)
       if (skip(j)) nskip = nskip + 1
    end do
    if (nskip == 0) return
    allocate (named(size(model%subs)), source=.false.)
    do j = 1, k%n
       if (.not. skip(j)) cycle
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          k%val(pos) = 0.0_wp
       end do
       k%val(k%colptr(j + 1) - 1) = 1.0_wp
       spc(j) = .true.
       if (tr%column_kind(j) == COL_PHYS) named(table%p_sub(tr%column_ref(j))) = .true.
    end do
    ! Entries above the diagonal in other columns that belong to skipped rows.
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 2
          if (skip(k%rowind(pos))) k%val(pos) = 0.0_wp
       end do
    end do
    subs = ''
    do isub = 1, size(model%subs)
       if (named(isub)) subs = subs//' '//model%subs(isub)%name
    end do
    if (len(subs) == 0) subs = ' (contact and support unknowns)'
    if (subs(1:2) /= ' (') subs = ' (in substructures'//subs//')'
    call note(notes, itoa(int(nskip))//' unknowns'//subs//' are coupled to no load: zero displacement, not solved')
  end subroutine skip_unloaded_parts

  subroutine factor_and_solve(model, table, tr, k, f_red, opts, groups, solver, q, res, error)
    !! Analyze, factorize (mapping a breakdown to its location) and solve all steps.
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
    call solver%analyze(k, error)
    if (allocated(error)) return
    res%phase_seconds(PH_ORDER) = clock%seconds()
    call report_phase(opts%quiet, 'order', res%phase_seconds(PH_ORDER), solver%info%ordering)

    call clock%start()
    call solver%factorize(k, error)
    if (allocated(error)) then
       if (error%code == EXIT_SINGULAR) then
          jf = solver%info%failed_column
          deallocate (error)
          call mechanism_error(k, solver_name, model, table, tr, penalty_hint(res), res%mechanism, error)
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
    res%phase_seconds(PH_FACTOR) = clock%seconds()
    res%solver_name = solver%info%name
    res%ordering = solver%info%ordering
    res%factor_nnz = solver%info%factor_nnz
    res%factor_mbytes = solver%info%factor_mbytes
    write (buf, '(a,i0)') 'factor nonzeros ', res%factor_nnz
    call report_phase(opts%quiet, 'factor', res%phase_seconds(PH_FACTOR), solver%info%name//', '//trim(buf))

    call clock%start()
    allocate (q(k%n, size(f_red, 2)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the solution', k%n*size(f_red, 2)*BYTES_REAL)
       return
    end if
    call solver%solve(f_red, q, error)
    if (allocated(error)) return
    res%phase_seconds(PH_SOLVE) = clock%seconds()
    call report_phase(opts%quiet, 'solve', res%phase_seconds(PH_SOLVE))
  end subroutine factor_and_solve

  subroutine health(k, q, f_red, spc, solver, model, table, tr, res, opts, error)
    !! Residual, EPSILON, iterative refinement, MAXRATIO and condition estimate.
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(inout) :: q(:, :)
    real(wp), intent(in) :: f_red(:, :)
    logical, intent(in) :: spc(:)
    class(linear_solver_t), intent(inout) :: solver
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(results_t), intent(inout) :: res
    type(run_options_t), intent(in) :: opts
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: r(:, :), dq(:, :), d(:), kd(:), q_try(:, :), r_try(:, :), berr(:), berr_try(:), &
         prev_res(:), prev_eps(:)
    type(error_t), allocatable :: inner
    integer :: is, it, nstep, stat
    integer(i8) :: j, jmax
    real(wp) :: ratio, cond, knorm
    character(len=32) :: buf
    character(:), allocatable :: backend

    nstep = size(q, 2)
    allocate (r(k%n, nstep), dq(k%n, nstep), q_try(k%n, nstep), r_try(k%n, nstep), berr(nstep), &
         berr_try(nstep), d(k%n), kd(k%n), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the residual checks', (4*nstep + 2)*k%n*BYTES_REAL)
       return
    end if
    knorm = norm1_sym(k)
    call residuals(q, r, berr)
    do is = 1, nstep
       res%steps(is)%residual0 = res%steps(is)%residual
    end do
    ! MAXRATIO = max K_jj / D_jj, first: a numerically singular matrix stops
    ! here, before refinement solves with a factor that is not worth using.
    call solver%pivots(d)
    call k%diagonal(kd)
    res%maxratio = 0.0_wp
    jmax = 0
    do j = 1, k%n
       if (spc(j) .or. d(j) == 0.0_wp) cycle
       ! kd/d guarded against overflow (PENALTY with an absurd g)
       if (abs(d(j)) <= abs(kd(j))/RATIO_CAP) then
          ratio = RATIO_CAP
       else
          ratio = abs(kd(j)/d(j))
       end if
       if (ratio > res%maxratio) then
          res%maxratio = ratio
          jmax = j
       end if
    end do
    res%maxratio_at = 'n/a'
    if (jmax > 0) res%maxratio_at = column_label(model, table, tr, jmax)
    if (res%maxratio > MAXRATIO_FATAL) then
       backend = 'auto'
       if (allocated(opts%solver)) backend = opts%solver
       call mechanism_error(k, backend, model, table, tr, penalty_hint(res), res%mechanism, error)
       if (allocated(error)) return
       write (buf, '(es10.2e3)') res%maxratio
       call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: stiffness is '// &
            'numerically singular at '//res%maxratio_at//' (MAXRATIO '//trim(adjustl(buf))// &
            '): a mechanism, or a stiffness contrast beyond double precision'//penalty_hint(res))
       return
    end if
    ! Iterative refinement with the existing factor, while the backward error
    ! is above a few ulps or the residual or EPSILON above REFINE_RESIDUAL, and
    ! each step at least halves the largest residual.
    do it = 1, MAX_REFINE
       if (all(berr <= REFINE_BERR .and. res%steps(:)%residual <= REFINE_RESIDUAL .and. &
            abs(res%steps(:)%epsilon) <= REFINE_RESIDUAL)) exit
       res%steps(:)%refine_tried = it
       call solver%solve(r, dq, inner)
       if (allocated(inner)) exit
       q_try = q - dq
       prev_res = res%steps(:)%residual
       prev_eps = res%steps(:)%epsilon
       r_try = r
       call residuals(q_try, r_try, berr_try)
       ! keep a step only if it is finite and gains (a NaN residual compares false)
       if (.not. all(ieee_is_finite(q_try)) .or. &
           .not. (maxval(res%steps(:)%residual) <= REFINE_GAIN*maxval(prev_res))) then
          res%steps(:)%residual = prev_res
          res%steps(:)%epsilon = prev_eps
          exit
       end if
       q = q_try
       r = r_try
       berr = berr_try
       res%steps(:)%refinements = it
    end do

    if (maxval(res%steps(:)%residual) > merge(RESIDUAL_WARN_PENALTY, RESIDUAL_WARN, res%formulation == 'PENALTY')) then
       write (buf, '(es10.2e3)') maxval(res%steps(:)%residual)
       call warn(res, 'relative residual '//trim(adjustl(buf))//' after refinement: results are inaccurate')
       res%inaccurate = .true.
    end if
    if (res%maxratio > MAXRATIO_WARN) then
       write (buf, '(es10.2e3)') res%maxratio
       call warn(res, 'MAXRATIO '//trim(adjustl(buf))//' at '//res%maxratio_at// &
            ': about '//itoa(nint(log10(res%maxratio)))//' digits may be lost')
    end if
    call condition_estimate(k, solver, cond)
    if (.not. ieee_is_finite(cond) .or. cond > huge(cond)) then
       cond = huge(cond)
       call warn(res, 'condition estimate overflows (above 1.8E+308): results are unreliable')
       res%inaccurate = .true.
    end if
    res%cond_est = cond
    if (.not. opts%quiet .and. opts%verbose) then
       write (error_unit, '(a,es10.3)') 'superjoin: condition estimate ', cond
    end if
  contains
    subroutine residuals(x, r, berr)
      !! r = K x - f, the relative residual and EPSILON of every step, and the
      !! backward error ‖r‖∞ / (‖K‖∞ ‖x‖∞ + ‖f‖∞).
      real(wp), intent(in) :: x(:, :)
      real(wp), intent(out) :: r(:, :), berr(:)
      integer :: s
      call k%matvec(x, r)
      r = r - f_red
      do s = 1, nstep
         res%steps(s)%residual = safe_div(norm2(r(:, s)), norm2(f_red(:, s)))
         res%steps(s)%epsilon = energy_error(x(:, s), r(:, s), f_red(:, s))
         berr(s) = safe_div(maxval(abs(r(:, s))), knorm*maxval(abs(x(:, s))) + maxval(abs(f_red(:, s))))
      end do
    end subroutine residuals
  end subroutine health

  function penalty_hint(res) result(s)
    !! Under PENALTY a breakdown is usually the contact stiffness, not a mechanism.
    type(results_t), intent(in) :: res
    character(:), allocatable :: s
    s = ''
    if (res%formulation == 'PENALTY') s = ' (unless it is a mechanism: under PENALTY a contact stiffness '// &
         'beyond about 1/epsilon times the structure''s breaks the factorization; TRANSFORM does not)'
  end function penalty_hint

  pure function energy_error(x, r, f) result(eps)
    !! EPSILON = xᵀr / xᵀf, with x, r and f scaled by powers of two first so
    !! that the dot products cannot overflow (the ratio does not change).
    real(wp), intent(in) :: x(:), r(:), f(:)
    real(wp) :: eps, sx, sf
    sx = scale_of(x)
    sf = max(scale_of(f), scale_of(r))
    eps = safe_div(dot_product(x/sx, r/sf), dot_product(x/sx, f/sf))
  end function energy_error

  pure function scale_of(v) result(s)
    !! A power of two near max|v| (1 for a zero or empty vector).
    real(wp), intent(in) :: v(:)
    real(wp) :: s, m
    s = 1.0_wp
    if (size(v) == 0) return
    m = maxval(abs(v))
    if (m > 0.0_wp .and. m <= huge(m)) s = set_exponent(1.0_wp, exponent(m))
  end function scale_of

  elemental logical function too_big(a, t, power)
    !! Whether |a| / t**power would come near the overflow threshold (tested on
    !! logarithms, so that the test itself cannot overflow or divide by zero).
    real(wp), intent(in) :: a, t
    integer, intent(in) :: power
    real(wp), parameter :: MARGIN = 1.0_wp   !! decades kept below huge()
    too_big = .false.
    if (a == 0.0_wp .or. t <= 0.0_wp) return
    too_big = log10(abs(a)) - power*log10(t) > log10(huge(a)) - MARGIN
  end function too_big

  pure function safe_div(a, b) result(c)
    real(wp), intent(in) :: a, b
    real(wp) :: c
    if (b == 0.0_wp) then
       c = 0.0_wp
       if (a /= 0.0_wp) c = huge(1.0_wp)
    else
       c = a/b
    end if
  end function safe_div

  function column_label(model, table, tr, j) result(label)
    !! Human name of a reduced unknown: substructure, node and DOF, or the
    !! contact/support and the component of its Δ.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: j
    character(:), allocatable :: label
    integer(i8) :: p
    integer :: iu, k
    select case (tr%column_kind(j))
    case (COL_PHYS)
       p = tr%column_ref(j)
       label = 'substructure '//model%subs(table%p_sub(p))%name//' node '// &
            itoa(int(model%subs(table%p_sub(p))%node_id(table%p_node(p))))//' DOF '//itoa(table%p_dof(p))
    case (COL_DELTA)
       iu = int(tr%column_ref(j))
       k = tr%column_comp(j)
       associate (u => table%units(iu))
         if (u%kind == UNIT_LINK) then
            label = 'contact '//model%contacts(model%links(u%source)%contact)%name//' ('// &
                 vertex_label(model, table, u%va)//' - '//vertex_label(model, table, u%vb)//') relative DOF '// &
                 itoa(block_dof(u%block, u%lcomp(k)))
         else
            label = 'elastic support at '//vertex_label(model, table, u%vb)//' DOF '// &
                 itoa(block_dof(u%block, u%comp(k)))
         end if
       end associate
    case default
       label = 'unknown '//itoa(int(j))
    end select
  end function column_label

  function vertex_label(model, table, v) result(label)
    !! "SUB.id" of a vertex (ground: "ground").
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer(i8), intent(in) :: v
    character(:), allocatable :: label
    integer :: isub
    if (v == GROUND) then
       label = 'ground'
       return
    end if
    do isub = 1, size(model%subs)
       if (v <= table%vertex_offset(isub + 1)) exit
    end do
    label = node_label(model, isub, int(v - table%vertex_offset(isub), kind(model%subs(1)%nnode)))
  end function vertex_label

  pure function block_name(b) result(s)
    integer, intent(in) :: b
    character(:), allocatable :: s
    if (b == 1) then
       s = 'translations'
    else
       s = 'rotations'
    end if
  end function block_name

  pure function local_name(b, c) result(s)
    integer, intent(in) :: b, c
    character(:), allocatable :: s
    s = 'DOF '//itoa(block_dof(b, c))
  end function local_name

  subroutine note(notes, text)
    !! Append a line to the listing's notes.
    type(string_t), allocatable, intent(inout) :: notes(:)
    character(*), intent(in) :: text
    call append_string(notes, text)
  end subroutine note

  subroutine warn(res, text)
    !! Append a warning (listing and stderr).
    type(results_t), intent(inout) :: res
    character(*), intent(in) :: text
    call append_string(res%warnings, text)
  end subroutine warn

  subroutine append_string(list, text)
    !! Grow a list of strings by one, moving the old entries (no copies).
    type(string_t), allocatable, intent(inout) :: list(:)
    character(*), intent(in) :: text
    type(string_t), allocatable :: tmp(:)
    integer :: i, n
    n = 0
    if (allocated(list)) n = size(list)
    allocate (tmp(n + 1))
    do i = 1, n
       call move_alloc(list(i)%s, tmp(i)%s)
    end do
    tmp(n + 1)%s = text
    call move_alloc(tmp, list)
  end subroutine append_string
end module superjoin_analysis
