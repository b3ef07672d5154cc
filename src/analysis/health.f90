module superjoin_analysis_health
  !! Numerical health of a solution: residual, EPSILON, iterative refinement,
  !! MAXRATIO, condition estimate, the whole-system figures of a condensed run,
  !! and the check that no result overflows.
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR, EXIT_IO
  use superjoin_model_types, only: model_t, substructure_t
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_substructure_local_system, only: dof_label
  use superjoin_substructure_cache, only: part_cache_t, part_view_t, view_stiffness_times, k_holder, &
       view_maxratio
  use superjoin_solvers, only: condition_estimate, inverse_norm_bound
  use superjoin_analysis_level_solver, only: cholesky_pivots
  use superjoin_model_results, only: results_t, run_options_t
  use superjoin_analysis_mechanism, only: mechanism_error
  use superjoin_analysis_labels, only: column_label
  use superjoin_model_notes, only: warn, note
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  use superjoin_parallel_comm, only: sum_reals
  use superjoin_analysis_solve_state, only: solve_state_t
  implicit none (type, external)
  private

  real(wp), parameter, public :: REFINE_BERR = 10*epsilon(1.0_wp)
    !! iterative refinement runs while the backward error exceeds this,
  real(wp), parameter, public :: REFINE_RESIDUAL = 1.0e-9_wp
    !! or while the relative residual or |EPSILON| of a step exceeds this, or the round-off floor
    !! eps ||K||_1 ||x||_1 / ||f||_1 of the matrix if larger (a backward-stable solve of a matrix of
    !! condition kappa leaves a relative residual of about eps kappa, which refinement cannot lower),
  real(wp), parameter, public :: REFINE_FLOOR_MAX = 1.0e-7_wp
    !! but never above this (a tenth of RESIDUAL_WARN: a residual the warning would flag is refined),
  real(wp), parameter, public :: REFINE_GAIN = 0.5_wp
    !! and while each step multiplies the largest residual by at most this
  integer, parameter, public :: MAX_REFINE = 3
    !! At most this many refinement steps.
  real(wp), parameter, public :: MAXRATIO_WARN = 1.0e6_wp
    !! MAXRATIO above this is flagged as a loss of accuracy (digits lost ≈ log10):
    !! PENALTY's measured errors reach 10 MAXRATIO ε, so past 1e6 fewer than 8 digits are sure.
  real(wp), parameter :: RATIO_TIE = 1.0e-9_wp
    !! MAXRATIO values of columns this close (relative) are a tie: the first column keeps the
    !! place, so round-off (another build, another BLAS) does not move the place the listing names.
  real(wp), parameter, public :: MAXRATIO_FATAL = 1.0e13_wp
    !! MAXRATIO above this (a pivot within about 1/(45 ε) of total cancellation)
    !! is numerically singular (exit 3): exact mechanisms factor with MAXRATIO
    !! from about 5e13 up, and nothing meaningful is left of an answer above 1e13.
  integer(i8), parameter, public :: COND_FULL_MAX = 20000_i8
    !! Up to this many equations the condition estimate is always Hager-Higham's
    !! (its four to six extra solves cost little there; at 65 088 equations, the
    !! 20-floor building of doc/performance.md, they were 10 % of the run).
  real(wp), parameter, public :: COND_BOUND_LIMIT = 1.0e10_wp
    !! Above it, the free lower bound of the condition number calls for Hager-Higham's estimate.
  real(wp), parameter :: RATIO_CAP = 1.0e300_wp
    !! MAXRATIO reported when K_jj / D_jj would overflow.
  real(wp), parameter, public :: RESIDUAL_WARN = 1.0e-6_wp
    !! A relative residual still above this after refinement is reported as a warning.
  real(wp), parameter, public :: RESIDUAL_WARN_PENALTY = 1.0e-4_wp
    !! The same under PENALTY, whose residual floor is about eps x g / k (the
    !! penalty springs' forces on round-off): 1e-6 to 1e-5 with the default
    !! g = k / sqrt(eps) on the bundled decks, whose displacements then agree with
    !! TRANSFORM to 1.4e-6 relative or better (doc/verification.md).

  public :: check_finite, health, full_health, parts_maxratio, penalty_hint

  type :: health_work_t
    !! Work arrays of health (allocated together, one out-of-memory report).
     real(wp), allocatable :: r(:, :), dq(:, :), q_try(:, :), r_try(:, :), berr(:), berr_try(:), d(:), kd(:)
  end type health_work_t

contains

  subroutine check_finite(model, res, error)
    !! EXIT_SINGULAR error naming the first kind of result that is not finite
    !! (including the surface stresses n/t ± 6 m/t² the listing derives).
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: what
    integer :: is, isub
    if (allocated(res%fields%u)) then
       if (.not. all(ieee_is_finite(res%fields%u))) what = 'displacements'
    end if
    if (.not. allocated(what) .and. allocated(res%fields%elem_force)) then
       if (.not. all(ieee_is_finite(res%fields%elem_force))) what = 'element forces'
    end if
    if (.not. allocated(what) .and. allocated(res%fields%plate)) then
       if (.not. all(ieee_is_finite(res%fields%plate))) what = 'plate resultants'
    end if
    if (.not. allocated(what) .and. allocated(res%fields%plate)) then
       do isub = 1, size(model%subs)
          associate (s => model%subs(isub), off => res%fields%elem_offset(isub))
            if (plate_stresses_overflow(s, res%fields%plate(:, off + 1:off + s%nelem, :))) &
                 what = 'plate stresses'
          end associate
       end do
    end if
    if (.not. allocated(what) .and. allocated(res%fields%steps)) then
       do is = 1, size(res%fields%steps)
          associate (st => res%fields%steps(is))
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

  logical function plate_stresses_overflow(s, p)
    !! Whether the surface stresses n/t ± 6 m/t² of some element of s come
    !! near the overflow threshold (p: the resultants of s's elements, all
    !! finite). too_big grows with |a|, so each section's largest |n| and
    !! |m| over its elements and steps decide for all of them (two
    !! logarithms per section instead of six per element and step).
    type(substructure_t), intent(in) :: s
    real(wp), intent(in) :: p(:, :, :)
    real(wp), allocatable :: big(:, :)
    real(wp) :: t
    integer(ip) :: e
    integer :: k, is
    plate_stresses_overflow = .false.
    if (.not. allocated(s%sections)) return
    allocate (big(2, size(s%sections)), source=0.0_wp)
    do is = 1, size(p, 3)   ! scalar maxima (a section of p per element cost 160 instructions)
       do e = 1, s%nelem
          k = s%elem_section(e)
          if (k == 0) cycle
          big(1, k) = max(big(1, k), abs(p(1, e, is)), abs(p(2, e, is)), abs(p(3, e, is)))
          big(2, k) = max(big(2, k), abs(p(4, e, is)), abs(p(5, e, is)), abs(p(6, e, is)))
       end do
    end do
    do k = 1, size(s%sections)
       t = s%sections(k)%thickness
       if (t <= 0.0_wp) cycle
       if (too_big(big(1, k), t, 1) .or. too_big(6.0_wp*big(2, k), t, 2)) plate_stresses_overflow = .true.
    end do
  end function plate_stresses_overflow

  subroutine health(st, model, opts, res, error)
    !! Residual, EPSILON, iterative refinement (of st%q, in place), MAXRATIO
    !! and condition estimate. Products, diagonal and norm of K are the
    !! strategy's (the sum of the MPI processes' terms under owner terms).
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    type(health_work_t) :: w
    integer :: is, nstep, stat
    real(wp) :: cond, knorm, limit, warn_at
    character(len=32) :: buf

    nstep = size(st%q, 2)
    associate (k => st%k)
      allocate (w%r(k%n, nstep), w%dq(k%n, nstep), w%q_try(k%n, nstep), w%r_try(k%n, nstep), w%berr(nstep), &
           w%berr_try(nstep), w%d(k%n), w%kd(k%n), stat=stat)
      if (stat /= 0) then
         call out_of_memory(error, 'the residual checks', (4*nstep + 2)*k%n*BYTES_REAL)
         return
      end if
    end associate
    call st%strategy%norm1(st%k, knorm, error)
    if (allocated(error)) return
    call residuals(st, knorm, st%q, w%r, w%berr, res, error)
    if (allocated(error)) return
    do is = 1, nstep
       res%fields%steps(is)%residual0 = res%fields%steps(is)%residual
    end do
    ! MAXRATIO = max K_jj / D_jj, first: a numerically singular matrix stops
    ! here, before refinement solves with a factor that is not worth using.
    call maxratio_check(st, model, opts, w%d, w%kd, res, error)
    if (allocated(error)) return
    limit = residual_limit(st, knorm, w%berr, res)
    call refine(st, knorm, limit, w, res, error)
    if (allocated(error)) return

    warn_at = residual_warn_limit(res)
    if (maxval(res%fields%steps(:)%residual) > warn_at) then
       write (buf, '(es10.2e3)') maxval(res%fields%steps(:)%residual)
       call warn(res, 'relative residual '//trim(adjustl(buf))//' after refinement: results are inaccurate', &
            res%fields%steps(:)%residual > warn_at)
       res%log%inaccurate = .true.
    end if
    if (res%summary%maxratio > MAXRATIO_WARN) then
       write (buf, '(es10.2e3)') res%summary%maxratio
       call warn(res, 'MAXRATIO '//trim(adjustl(buf))//' at '//res%summary%maxratio_at// &
            ': about '//itoa(nint(log10(res%summary%maxratio)))//' digits may be lost', every_step(res))
    end if
    call estimate_condition(st, knorm, limit, w%d, res, cond)
    if (.not. ieee_is_finite(cond) .or. cond > huge(cond)) then
       cond = huge(cond)
       call warn(res, 'condition estimate overflows (above 1.8E+308): results are unreliable', every_step(res))
       res%log%inaccurate = .true.
    end if
    res%summary%cond_est = cond
    if (.not. opts%quiet .and. opts%verbose) then
       if (res%summary%cond_bound) then
          write (error_unit, '(a,es10.3,a)') 'superjoin: condition estimate ', cond, ' (a lower bound only)'
       else
          write (error_unit, '(a,es10.3)') 'superjoin: condition estimate ', cond
       end if
    end if
    ! the residual of the final q (refine keeps r with q): a condensed run's full_health starts from it
    if (allocated(st%parts) .and. .not. st%strategy%summed()) call move_alloc(w%r, st%r_red)
  end subroutine health

  function residual_limit(st, knorm, berr, res) result(limit)
    !! The relative residual and |EPSILON| up to which the solution needs no refinement:
    !! REFINE_RESIDUAL, or the round-off floor eps ||K||_1 ||x||_1 / ||f||_1 (eps times a lower
    !! bound of the condition number, from the solutions alone: valid for every backend) when that is
    !! larger, capped at REFINE_FLOOR_MAX. When the floor, not REFINE_RESIDUAL, spares a refinement
    !! (the backward errors berr being small too), a note of the listing says so.
    type(solve_state_t), intent(in) :: st
    real(wp), intent(in) :: knorm, berr(:)
    type(results_t), intent(inout) :: res
    real(wp) :: limit, worst
    character(len=32) :: buf
    limit = min(max(REFINE_RESIDUAL, epsilon(1.0_wp)*knorm*inverse_norm_bound(st%q, st%f_red)), REFINE_FLOOR_MAX)
    worst = max(maxval(res%fields%steps(:)%residual), maxval(abs(res%fields%steps(:)%epsilon)))
    if (worst > REFINE_RESIDUAL .and. worst <= limit .and. all(berr <= REFINE_BERR)) then
       write (buf, '(es10.2e3)') limit
       call note(res%log%notes, 'iterative refinement: not tried, the solve is backward stable and its relative '// &
            'residual below '//trim(adjustl(buf))//', the round-off floor eps ||K|| ||x|| / ||f|| of this matrix '// &
            '(at most 1E-7)')
    end if
  end function residual_limit

  subroutine estimate_condition(st, knorm, limit, d, res, cond)
    !! The condition estimate of the health block. Hager-Higham's 1-norm
    !! estimate (condition_estimate: about four more solves) for every backend
    !! but CHOLMOD, up to COND_FULL_MAX equations, and whenever a cheap
    !! indicator calls for it: MAXRATIO above MAXRATIO_WARN, a relative
    !! residual above limit (residual_limit) after refinement, or the free lower
    !! bound ||K||_1 times inverse_norm_bound (the step solutions, and the
    !! pivots d of the columns AUTOSPC kept) above COND_BOUND_LIMIT.
    !! Otherwise that lower bound is the estimate, and a note of the listing
    !! says so.
    type(solve_state_t), intent(inout) :: st
    real(wp), intent(in) :: knorm, limit, d(:)
    type(results_t), intent(inout) :: res
    real(wp), intent(out) :: cond
    logical :: cheap
    cheap = .false.
    res%summary%cond_bound = .false.
    if (st%k%n > COND_FULL_MAX .and. cholesky_pivots(st%solver)) then
       cond = knorm*inverse_norm_bound(st%q, st%f_red, merge(0.0_wp, d(1:st%k%n), st%spc))
       cheap = cond <= COND_BOUND_LIMIT .and. res%summary%maxratio <= MAXRATIO_WARN .and. &
            maxval(res%fields%steps(:)%residual) <= limit
    end if
    if (cheap) then
       res%summary%cond_bound = .true.
       call note(res%log%notes, 'condition estimate: a lower bound from the solutions and the pivots, '// &
            'not Hager''s estimate (skipped above '//itoa(COND_FULL_MAX)//' equations while MAXRATIO, '// &
            'the residual and this bound are small)')
    else   ! knorm: the strategy's ‖K‖₁, computed once (no second pass over K_red)
       call condition_estimate(st%k, st%solver, cond, anorm_given=knorm)
    end if
  end subroutine estimate_condition

  subroutine maxratio_check(st, model, opts, d, kd, res, error)
    !! MAXRATIO = max K_jj / D_jj over the columns not dropped by AUTOSPC, and
    !! its place; above MAXRATIO_FATAL the structure is numerically singular
    !! (the mechanism's report, EXIT_SINGULAR). d, kd: work of K's size.
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    real(wp), intent(out) :: d(:), kd(:)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: j, jmax
    real(wp) :: ratio
    character(len=32) :: buf
    character(:), allocatable :: backend

    call st%solver%pivots(d)
    call st%strategy%diagonal(st%k, kd, error)
    if (allocated(error)) return
    res%summary%maxratio = 0.0_wp
    jmax = 0
    do j = 1, st%k%n
       if (st%spc(j) .or. d(j) == 0.0_wp) cycle
       ! kd/d guarded against overflow (PENALTY with an absurd g)
       if (abs(d(j)) <= abs(kd(j))/RATIO_CAP) then
          ratio = RATIO_CAP
       else
          ratio = abs(kd(j)/d(j))
       end if
       if (ratio > res%summary%maxratio*(1.0_wp + RATIO_TIE)) then
          res%summary%maxratio = ratio
          jmax = j
       end if
    end do
    res%summary%maxratio_at = 'n/a'
    if (jmax > 0) res%summary%maxratio_at = column_label(model, st%table, st%tr, jmax)
    if (res%summary%maxratio > MAXRATIO_FATAL) then
       backend = 'auto'
       if (allocated(opts%solver)) backend = opts%solver
       call mechanism_error(st%k, backend, model, st%table, st%tr, penalty_hint(res), res%fields%mechanism, error, &
            summed=st%strategy%summed())
       if (allocated(error)) return
       write (buf, '(es10.2e3)') res%summary%maxratio
       call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: stiffness is '// &
            'numerically singular at '//res%summary%maxratio_at//' (MAXRATIO '//trim(adjustl(buf))// &
            '): a mechanism, or a stiffness contrast beyond double precision'//penalty_hint(res))
       return
    end if
  end subroutine maxratio_check

  subroutine refine(st, knorm, limit, w, res, error)
    !! Iterative refinement of st%q with the existing factor, while the
    !! backward error is above a few ulps or the residual or EPSILON above
    !! limit (residual_limit), and each step at least halves the largest residual.
    !! w%r, w%berr: the residuals of q on entry.
    type(solve_state_t), intent(inout) :: st
    real(wp), intent(in) :: knorm, limit
    type(health_work_t), intent(inout) :: w
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(inout) :: error
    real(wp), allocatable :: prev_res(:), prev_eps(:)
    type(error_t), allocatable :: inner
    integer :: it
    associate (q => st%q, r => w%r, dq => w%dq, q_try => w%q_try, r_try => w%r_try, berr => w%berr, &
         berr_try => w%berr_try)
      do it = 1, MAX_REFINE
         if (all(berr <= REFINE_BERR .and. res%fields%steps(:)%residual <= limit .and. &
              abs(res%fields%steps(:)%epsilon) <= limit)) exit
         res%fields%steps(:)%refine_tried = it
         call st%solver%solve(r, dq, inner)
         if (allocated(inner)) exit
         q_try = q - dq
         prev_res = res%fields%steps(:)%residual
         prev_eps = res%fields%steps(:)%epsilon
         r_try = r
         call residuals(st, knorm, q_try, r_try, berr_try, res, error)
         if (allocated(error)) return
         ! keep a step only if it is finite and gains (a NaN residual compares false)
         if (.not. all(ieee_is_finite(q_try)) .or. &
             .not. (maxval(res%fields%steps(:)%residual) <= REFINE_GAIN*maxval(prev_res))) then
            res%fields%steps(:)%residual = prev_res
            res%fields%steps(:)%epsilon = prev_eps
            exit
         end if
         q = q_try
         r = r_try
         berr = berr_try
         res%fields%steps(:)%refinements = it
      end do
    end associate
  end subroutine refine

  subroutine residuals(st, knorm, x, r, berr, res, error)
    !! r = K x - f, the relative residual and EPSILON of every step, and the
    !! backward error ‖r‖∞ / (‖K‖∞ ‖x‖∞ + ‖f‖∞).
    type(solve_state_t), intent(in) :: st
    real(wp), intent(in) :: knorm
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: r(:, :), berr(:)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(inout) :: error
    integer :: s
    call st%strategy%matvec(st%k, x, r, error)
    if (allocated(error)) return
    associate (f_red => st%f_red)
      r = r - f_red
      do s = 1, size(x, 2)
         res%fields%steps(s)%residual = safe_div(norm2(r(:, s)), norm2(f_red(:, s)))
         res%fields%steps(s)%epsilon = energy_error(x(:, s), r(:, s), f_red(:, s))
         berr(s) = safe_div(maxval(abs(r(:, s))), knorm*maxval(abs(x(:, s))) + maxval(abs(f_red(:, s))))
      end do
    end associate
  end subroutine residuals

  subroutine full_health(st, cache, res, error)
    !! Residual and EPSILON of the whole reduced system, as if it had been
    !! solved monolithically, from the recovered displacements and each
    !! condensed substructure's own stiffness (so an error in a condensation
    !! or a recovery shows). Unknowns: the interface columns q, then every
    !! condensed interior u_i. Interface rows: K_if q − f_if plus, for each
    !! part, Mᵀ[(k u − f)_b − (K* u_b − f*)]; interior rows: k_ii u_i + k_ib u_b − f_i.
    !! The loads likewise, with the prescribed values' terms (−k u0).
    !! st%ku: k u of the condensed substructures on the physical DOFs (recover_with_ku).
    !! Owner terms (st%strategy%summed()): k is this MPI process's term of K_red and only the own
    !! substructures (entry > 0) hold K*: each process adds its own terms to
    !! the interface rows, which are summed over the processes.
    !! st%r_red (health's residual of this q), when kept, is taken over (moved).
    type(solve_state_t), intent(inout) :: st
    type(part_cache_t), intent(in) :: cache
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: r(:, :), f(:, :), rl(:, :), u0l(:, :), w(:, :), ks(:, :), ku0(:), &
         rf(:, :), ffull(:, :), qfull(:, :)
    integer :: i, is, nstep
    integer(i8) :: ni, nb, l, ntot, at, bat
    associate (tr => st%tr, k => st%k, parts => st%parts, q => st%q, u => st%u, ku => st%ku, f_red => st%f_red, &
         f_bnd => st%f_bnd, f_phys => st%f_phys)
      nstep = size(q, 2)
      if (allocated(st%r_red)) then   ! health's K_red q − f_red of this q: no second product with K_red
         call move_alloc(st%r_red, r)
         f = f_red
      else
         allocate (r(k%n, nstep))
         call k%matvec(q, r)
         if (st%strategy%summed()) then   ! this process's terms first; f_red once the rows are summed
            allocate (f(k%n, nstep), source=0.0_wp)
         else
            r = r - f_red
            f = f_red
         end if
      end if
      ntot = k%n
      do i = 1, size(parts)
         ntot = ntot + parts(i)%ni
      end do
      allocate (rf(ntot, nstep), ffull(ntot, nstep), qfull(ntot, nstep))   ! every row is written below
      at = k%n
      bat = 0
      do i = 1, size(parts)
         associate (sys => parts(i))
           ni = sys%ni
           nb = sys%nb
           allocate (u0l(ni + nb, 1), w(ni + nb, 1))
           rl = ku(sys%pdof, :) - f_phys(sys%pdof, :)
           u0l = 0.0_wp
           u0l(ni + 1:, 1) = tr%prescribed(sys%pdof(ni + 1:))
           if (parts(i)%entry == 0) then   ! condensed by another MPI process, which sent k u0
              w(:, 1) = parts(i)%ku0
           else if (any(u0l /= 0.0_wp)) then
              call view_stiffness_times(cache, parts(i), u0l, w)
           else
              w = 0.0_wp
           end if
           rf(at + 1:at + ni, :) = rl(1:ni, :)
           do is = 1, nstep
              ffull(at + 1:at + ni, is) = f_phys(sys%pdof(1:ni), is) - w(1:ni, 1)
           end do
           qfull(at + 1:at + ni, :) = u(sys%pdof(1:ni), :)
           at = at + ni
           ! interface rows: K* is with the owner only under owner terms
           if (st%strategy%summed() .and. parts(i)%entry == 0) then
              bat = bat + nb
              deallocate (rl, u0l, w)
              cycle
           end if
           associate (kst => parts(k_holder(parts, i))%se%k)   ! after the cycle: a remote view holds none
             ks = matmul(kst, u(sys%pdof(ni + 1:), :))
             ku0 = matmul(kst, u0l(ni + 1:, 1))
           end associate
           do l = 1, nb   ! f_bnd(bat + l, :): f_eff's row of boundary DOF l (f*)
              associate (pb => sys%pdof(ni + l))
                call tr%reduce_add(pb, rl(ni + l, :) - (ks(l, :) - f_bnd(bat + l, :)), r)
                call tr%reduce_add(pb, (f_phys(pb, :) - w(ni + l, 1)) - (f_bnd(bat + l, :) - ku0(l)), f)
              end associate
           end do
           bat = bat + nb
           deallocate (rl, u0l, w)
         end associate
      end do
      rf(1:k%n, :) = r
      ffull(1:k%n, :) = f
      qfull(1:k%n, :) = q
    end associate
    call whole_residuals(st, r, f, rf, ffull, qfull, res, error)
  end subroutine full_health

  subroutine whole_residuals(st, r, f, rf, ffull, qfull, res, error)
    !! The end of full_health: under owner terms the interface rows
    !! r and loads f of every process's terms summed into rf and ffull; then
    !! the residual and EPSILON of every step from rf, ffull and qfull.
    type(solve_state_t), intent(in) :: st
    real(wp), intent(in) :: r(:, :), f(:, :)
    real(wp), intent(inout) :: rf(:, :), ffull(:, :)
    real(wp), intent(in) :: qfull(:, :)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: rows(:)
    real(wp) :: bad_above
    logical :: ok
    integer :: is
    character(len=32) :: buf
    associate (k => st%k, f_red => st%f_red)
      if (st%strategy%summed()) then
         ! interface rows of every process's terms summed (the interior rows
         ! every process has: ku is summed already, k u0 sent by the owners)
         rows = [reshape(r, [size(r, kind=i8)]), reshape(f, [size(f, kind=i8)])]
         call sum_reals(rows, ok)
         if (.not. ok) then
            call fatal_error(error, EXIT_IO, 'error: MPI sum of the whole-system residual failed')
            return
         end if
         rf(1:k%n, :) = reshape(rows(1:size(r, kind=i8)), shape(r)) - f_red
         ffull(1:k%n, :) = reshape(rows(size(r, kind=i8) + 1:), shape(f)) + f_red
      end if
      do is = 1, size(qfull, 2)
         res%fields%steps(is)%residual = safe_div(norm2(rf(:, is)), norm2(ffull(:, is)))
         res%fields%steps(is)%epsilon = energy_error(qfull(:, is), rf(:, is), ffull(:, is))
      end do
      bad_above = residual_warn_limit(res)
      if (maxval(res%fields%steps(:)%residual) > bad_above) then
         write (buf, '(es10.2e3)') maxval(res%fields%steps(:)%residual)
         call warn(res, 'relative residual '//trim(adjustl(buf))//' of the whole system (condensed '// &
              'substructures recovered): results are inaccurate', res%fields%steps(:)%residual > bad_above)
         res%log%inaccurate = .true.
      end if
    end associate
  end subroutine whole_residuals

  pure real(wp) function residual_warn_limit(res) result(limit)
    !! The relative residual above which results are judged inaccurate:
    !! RESIDUAL_WARN, under PENALTY RESIDUAL_WARN_PENALTY (its floor, eps g/k,
    !! is in the whole system's residual as in the reduced one's).
    type(results_t), intent(in) :: res
    limit = merge(RESIDUAL_WARN_PENALTY, RESIDUAL_WARN, res%summary%formulation == 'PENALTY')
  end function residual_warn_limit

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
       if (ratio <= res%summary%maxratio .or. p == 0) cycle
       res%summary%maxratio = ratio
       res%summary%maxratio_at = dof_label(model, table, p)
       write (buf, '(es10.2e3)') res%summary%maxratio
       if (res%summary%maxratio > MAXRATIO_FATAL) then
          call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: stiffness is '// &
               'numerically singular at '//res%summary%maxratio_at//' (MAXRATIO '//trim(adjustl(buf))// &
               '): a mechanism, or a stiffness contrast beyond double precision')
          return
       end if
       if (res%summary%maxratio > MAXRATIO_WARN) call warn(res, 'MAXRATIO '//trim(adjustl(buf))//' at '// &
            res%summary%maxratio_at//': about '//itoa(nint(log10(res%summary%maxratio)))//' digits may be lost', &
            every_step(res))
    end do
  end subroutine parts_maxratio

  pure function every_step(res) result(steps)
    !! The warning mask of a property of the matrix (MAXRATIO, condition):
    !! every step solved with it.
    type(results_t), intent(in) :: res
    logical, allocatable :: steps(:)
    allocate (steps(size(res%fields%steps)), source=.true.)
  end function every_step

  function penalty_hint(res) result(s)
    !! Under PENALTY a breakdown is usually the contact stiffness, not a mechanism.
    type(results_t), intent(in) :: res
    character(:), allocatable :: s
    s = ''
    if (res%summary%formulation == 'PENALTY') s = ' (unless it is a mechanism: under PENALTY a contact stiffness '// &
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
end module superjoin_analysis_health
