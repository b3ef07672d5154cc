program test_condition_residual
  !! The condition estimate escalates on the residual alone (analysis/health's
  !! estimate_condition): above COND_FULL_MAX equations with CHOLMOD, the free
  !! lower bound stands in for Hager-Higham's estimate only while MAXRATIO,
  !! the bound itself and the relative residual after refinement are all
  !! small. A backward-stable Cholesky leaves no large residual, so the
  !! residual is made here by a fault handed to the pipeline through
  !! its public entry (analysis's solve_group): the factorization kept for the
  !! next solve of the same matrix (solve_context_t's factor) is replaced by
  !! that of c K. A kept factor of c K solves with q = K^-1 f / c; every
  !! refinement step then multiplies the residual by rho = 1 - 1/c, so after
  !! MAX_REFINE steps the relative residual is rho**(MAX_REFINE + 1), chosen
  !! here three times REFINE_RESIDUAL (the refinement limit of this
  !! well-conditioned matrix): above the limit, below the residual warning.
  !!
  !! Cases, all on the same 2-bar chains (K's bound, MAXRATIO small):
  !!  - c = 1 (the kept factor refactored with K itself): the bound, its note;
  !!  - rho**(MAX_REFINE + 1) = 3 REFINE_RESIDUAL: Hager-Higham's estimate,
  !!    no note, no warning (three times the limit, not far above it: a
  !!    clause weakened to ten times the limit takes the bound here);
  !!  - c = 4 (a residual of 1 - 1/c = 0.75, its refinement step rejected):
  !!    Hager-Higham's, the residual warned and the results judged inaccurate.
  !! What the listing prints follows: its health line reads the step's
  !! cond_bound ('a lower bound only (notes)'), its notes res%log%notes.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, CONDENSE_NO
  use superjoin_model_results, only: results_t, run_options_t, LEVELS_NO
  use superjoin_deck_reader, only: read_deck_string
  use superjoin_analysis, only: solve_group, solve_context_t, release_cache
  use superjoin_analysis_health, only: COND_FULL_MAX, REFINE_RESIDUAL, MAX_REFINE, RESIDUAL_WARN, MAXRATIO_WARN, &
       COND_BOUND_LIMIT
  use superjoin_solvers, only: sparse_sym_t
  use superjoin_testing, only: check, finish
  use verification_support, only: fail
  implicit none (type, external)

  character(*), parameter :: NOTE = 'condition estimate: a lower bound'
  integer, parameter :: NCHAIN = int(COND_FULL_MAX/2) + 1   ! two unknowns per chain: above COND_FULL_MAX
  type(model_t) :: model
  type(run_options_t) :: opts
  type(solve_context_t) :: ctx
  type(results_t) :: res
  type(error_t), allocatable :: error
  real(wp) :: rho

  call read_deck_string(chains(NCHAIN), 'chains.deck', model, error)
  call fail(error, 'read')
  opts%quiet = .true.
  opts%solver = 'cholmod'
  opts%condense = CONDENSE_NO
  opts%levels = LEVELS_NO
  ctx%factor%keep = .true.   ! as for steps that differ only in prescribed values (analysis/driver)

  call solve_group(model, opts, ctx, res, error)   ! the factor to be kept
  call fail(error, 'first solve')
  call check(res%summary%neq > COND_FULL_MAX, 'more equations than COND_FULL_MAX')
  call check(allocated(ctx%factor%solver), 'the factorization is kept')

  ! c = 1: the bound, with its note
  call solve_with_factor_of(1.0_wp, 'c = 1')
  call check(res%fields%steps(1)%residual <= REFINE_RESIDUAL, 'c = 1: residual within the limit')
  call check(res%summary%cond_bound, 'c = 1: the free lower bound is the estimate')
  call check(res%fields%steps(1)%cond_bound, 'c = 1: the step''s health line says a lower bound only')
  call check(has_note(res, NOTE), 'c = 1: the note on the lower bound')

  ! a residual three times the limit after refinement, no warning: Hager-Higham's
  rho = (3*REFINE_RESIDUAL)**(1.0_wp/(MAX_REFINE + 1))
  call solve_with_factor_of(1/(1 - rho), 'residual 3 x limit')
  call check(res%fields%steps(1)%residual > 2*REFINE_RESIDUAL .and. res%fields%steps(1)%residual < 5*REFINE_RESIDUAL, &
       'residual 3 x limit: the residual after refinement is rho**(MAX_REFINE + 1)')
  call check(res%fields%steps(1)%refinements == MAX_REFINE, 'residual 3 x limit: every refinement step kept')
  call check(res%fields%steps(1)%residual < RESIDUAL_WARN .and. size(res%log%warnings) == 0 .and. &
       .not. res%log%inaccurate, 'residual 3 x limit: no warning')
  call check(.not. res%summary%cond_bound, 'residual 3 x limit: Hager-Higham''s estimate, not the bound')
  call check(.not. res%fields%steps(1)%cond_bound, 'residual 3 x limit: the health line is not marked a lower bound')
  call check(.not. has_note(res, NOTE), 'residual 3 x limit: no note on the lower bound')
  call check(res%summary%cond_est >= 1.0_wp, 'residual 3 x limit: an estimate')

  ! a residual of 0.75 (refinement rejected): Hager-Higham's, and warned
  call solve_with_factor_of(4.0_wp, 'c = 4')
  call check(abs(res%fields%steps(1)%residual - (1 - 1/4.0_wp)) < 1.0e-6_wp, 'c = 4: residual 1 - 1/c')
  call check(res%log%inaccurate .and. size(res%log%warnings) > 0, 'c = 4: the residual warned')
  call check(.not. res%summary%cond_bound, 'c = 4: Hager-Higham''s estimate, not the bound')
  call check(.not. has_note(res, NOTE), 'c = 4: no note on the lower bound')

  call release_cache(ctx%cache)
  call finish()

contains

  subroutine solve_with_factor_of(c, what)
    !! Refactor the kept factorization with c K (its matrix stays K), solve
    !! the same model again with it, and check the solve took it and that
    !! the bound's other two indicators stay small.
    real(wp), intent(in) :: c
    character(*), intent(in) :: what
    type(sparse_sym_t) :: ck
    integer :: reuses
    ck = ctx%factor%k
    ck%val = c*ck%val
    call ctx%factor%solver%factorize(ck, error)
    call fail(error, what//': factorize c K')
    reuses = ctx%factor%reuses
    call solve_group(model, opts, ctx, res, error)
    call fail(error, what//': solve')
    call check(ctx%factor%reuses == reuses + 1, what//': solved with the kept factor')
    call check(res%summary%maxratio <= MAXRATIO_WARN, what//': MAXRATIO small')
    call check(res%summary%cond_est <= COND_BOUND_LIMIT, what//': the estimate below COND_BOUND_LIMIT')
  end subroutine solve_with_factor_of

  logical function has_note(r, text)
    !! Does a note of the listing begin with text?
    type(results_t), intent(in) :: r
    character(*), intent(in) :: text
    integer :: i
    has_note = .false.
    if (.not. allocated(r%log%notes)) return
    do i = 1, size(r%log%notes)
       if (index(r%log%notes(i)%s, text) == 1) has_note = .true.
    end do
  end function has_note

  function chains(n) result(text)
    !! n chains of two bars (T3D2, EA/L = 1000) along x, fixed at their
    !! first node and loaded at their tip, only the axial DOFs free.
    integer, intent(in) :: n
    character(:), allocatable :: text
    character(len=64) :: line
    integer :: pos, c
    allocate (character(len=200 + 128*n) :: text)
    pos = 0
    call put_line(text, pos, '*NODE, NSET=ALL')
    do c = 1, n
       write (line, '(i0,a,i0)') 3*c - 2, ', 0., ', c
       call put_line(text, pos, line)
       write (line, '(i0,a,i0)') 3*c - 1, ', 1., ', c
       call put_line(text, pos, line)
       write (line, '(i0,a,i0)') 3*c, ', 2., ', c
       call put_line(text, pos, line)
    end do
    call put_line(text, pos, '*ELEMENT, TYPE=T3D2, ELSET=BARS')
    do c = 1, n
       write (line, '(i0,a,i0,a,i0)') 2*c - 1, ', ', 3*c - 2, ', ', 3*c - 1
       call put_line(text, pos, line)
       write (line, '(i0,a,i0,a,i0)') 2*c, ', ', 3*c - 1, ', ', 3*c
       call put_line(text, pos, line)
    end do
    call put_line(text, pos, '*NSET, NSET=ROOTS')
    do c = 1, n
       write (line, '(i0)') 3*c - 2
       call put_line(text, pos, line)
    end do
    call put_line(text, pos, '*NSET, NSET=TIPS')
    do c = 1, n
       write (line, '(i0)') 3*c
       call put_line(text, pos, line)
    end do
    call put_line(text, pos, '*MATERIAL, NAME=M')
    call put_line(text, pos, '*ELASTIC')
    call put_line(text, pos, '1000., 0.3')
    call put_line(text, pos, '*SOLID SECTION, ELSET=BARS, MATERIAL=M')
    call put_line(text, pos, '1.')
    call put_line(text, pos, '*BOUNDARY')
    call put_line(text, pos, 'ROOTS, 1, 1')
    call put_line(text, pos, 'ALL, 2, 3')
    call put_line(text, pos, '*STEP')
    call put_line(text, pos, '*STATIC')
    call put_line(text, pos, '*CLOAD')
    call put_line(text, pos, 'TIPS, 1, 1.')
    call put_line(text, pos, '*END STEP')
    text = text(1:pos)
  end function chains

  subroutine put_line(text, pos, s)
    !! Append s and a new line at text(pos + 1:), pos moved past them.
    character(*), intent(inout) :: text
    integer, intent(inout) :: pos
    character(*), intent(in) :: s
    text(pos + 1:pos + len_trim(s) + 1) = trim(s)//new_line('a')
    pos = pos + len_trim(s) + 1
  end subroutine put_line
end program test_condition_residual
