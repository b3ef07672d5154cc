program schur_cost
  !! Cost of condensing a part against factoring its interior alone (issue 24).
  !!
  !! Usage: schur_cost K.mtx NB [REPS] [SOLVER]
  !! K.mtx: a symmetric matrix (e.g. superjoin --condense no --export-matrix);
  !! its last NB columns are taken as the boundary. For REPS rounds (default
  !! 3), interleaved so that a loaded machine slows all alike, it times with
  !! SOLVER (default cholmod):
  !!   factor   analyze + factorize of a_ii alone
  !!   schur    the solver's schur (its own route, e.g. boundary last)
  !!   default  schur_by_solves (a_ii factored, 2 NB triangular solves)
  !!   compare  (cholmod) schur with camd_first off: the interior's own
  !!            analysis always run and compared with CAMD's (before 2026-11-28)
  !!   analyze  analyze of a_ii alone (part of factor)
  !! and prints the medians and the ratios to factor, and the largest
  !! difference of the two K* relative to sqrt(k_ii k_jj). Each phase is
  !! timed twice: wall clock, and the process's CPU time (user + system,
  !! which a loaded machine does not inflate; run with
  !! OPENBLAS_NUM_THREADS=1 so that spinning BLAS threads do not count).
  !! Build (after the library):
  !!   gfortran -O2 bench/schur_cost.f90 -Ibuild/mod build/libsuperjoin_lib.a \
  !!     -lcholmod -lumfpack -lamd -lcolamd -lcamd -lccolamd -lsuitesparseconfig \
  !!     -lmetis -llapack -lblas -o build/schur_cost
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, cholmod_solver_t
  use superjoin_solvers_solver, only: schur_by_solves, interior_block
  use superjoin_solvers_matrix_market, only: read_matrix_market
  use superjoin_utils_sorting, only: sort_index
  implicit none (type, external)
  type(sparse_sym_t) :: a, aii
  type(error_t), allocatable :: error
  class(linear_solver_t), allocatable :: s
  character(len=512) :: path, arg, solver
  integer(i8) :: nb, ni, i
  integer :: reps, r
  real(wp), allocatable :: t(:, :), c(:, :), k1(:, :), k2(:, :), d(:)
  real(wp) :: worst, fl(3)
  integer, parameter :: MODE_SCHUR = 1, MODE_DEFAULT = 2, MODE_COMPARE = 3

  if (command_argument_count() < 2) then
     write (*, '(a)') 'usage: schur_cost K.mtx NB [REPS] [SOLVER]'
     stop 2
  end if
  call get_command_argument(1, path)
  call get_command_argument(2, arg)
  read (arg, *) nb
  reps = 3
  solver = 'cholmod'
  if (command_argument_count() >= 3) then
     call get_command_argument(3, arg)
     read (arg, *) reps
  end if
  if (command_argument_count() >= 4) call get_command_argument(4, solver)
  call read_matrix_market(trim(path), a, error)
  if (allocated(error)) error stop 'cannot read the matrix'
  ni = a%n - nb
  call interior_block(a, nb, aii)
  allocate (t(reps, 5), c(reps, 5), k1(nb, nb), k2(nb, nb))
  do r = 1, reps
     call new_solver(trim(solver), ni, s, error)
     t(r, 1) = now()
     c(r, 1) = cpu()
     call s%analyze(aii, error)
     t(r, 5) = now() - t(r, 1)
     c(r, 5) = cpu() - c(r, 1)
     call s%factorize(aii, error)
     t(r, 1) = now() - t(r, 1)
     c(r, 1) = cpu() - c(r, 1)
     if (allocated(error)) error stop 'factor failed'
     fl(1) = flops(s)
     call s%release()
     deallocate (s)
     call condense(MODE_SCHUR, k1, t(r, 2), c(r, 2), fl(2))
     call condense(MODE_COMPARE, k2, t(r, 4), c(r, 4), fl(3))
     call condense(MODE_DEFAULT, k2, t(r, 3), c(r, 3))
  end do
  allocate (d(nb))
  d = [(sqrt(max(k2(i, i), tiny(1.0_wp))), i=1, nb)]
  worst = 0.0_wp
  do i = 1, nb
     worst = max(worst, maxval(abs(k1(:, i) - k2(:, i))/(d*d(i))))
  end do
  write (*, '(a,i0,a,i0,a,i0,a,a)') 'n ', a%n, '  nb ', nb, '  rounds ', reps, '  solver ', trim(solver)
  write (*, '(a,3f9.3)') 'medians (s): factor a_ii, schur, default: ', median(t(:, 1)), median(t(:, 2)), median(t(:, 3))
  write (*, '(a,2f7.2)') 'ratios to factor a_ii: schur, default: ', median(t(:, 2))/median(t(:, 1)), &
       median(t(:, 3))/median(t(:, 1))
  write (*, '(a,2f9.3)') 'medians (s): analyze a_ii, schur compare: ', median(t(:, 5)), median(t(:, 4))
  write (*, '(a,3f9.3)') 'CPU medians (s): factor a_ii, schur, default: ', median(c(:, 1)), median(c(:, 2)), &
       median(c(:, 3))
  write (*, '(a,2f7.2)') 'CPU ratios to factor a_ii: schur, default: ', median(c(:, 2))/median(c(:, 1)), &
       median(c(:, 3))/median(c(:, 1))
  write (*, '(a,2f9.3)') 'CPU medians (s): analyze a_ii, schur compare: ', median(c(:, 5)), median(c(:, 4))
  if (fl(1) > 0.0_wp) write (*, '(a,3es10.3,a,2f6.2)') 'flops (CHOLMOD): factor a_ii, schur, compare: ', fl, &
       '  ratios ', fl(2)/fl(1), fl(3)/fl(1)
  write (*, '(a,es9.2)') 'max |K*schur - K*default| / sqrt(k_ii k_jj): ', worst

contains

  subroutine condense(mode, kstar, seconds, cpu_seconds, fl)
    !! One condensation by a fresh solver: its K*, wall and CPU time and flop count.
    integer, intent(in) :: mode
    real(wp), intent(out) :: kstar(:, :), seconds, cpu_seconds
    real(wp), intent(out), optional :: fl
    class(linear_solver_t), allocatable :: c
    call new_solver(trim(solver), ni, c, error)
    select type (c)
    type is (cholmod_solver_t)
       c%camd_first = mode /= MODE_COMPARE
    end select
    seconds = now()
    cpu_seconds = cpu()
    if (mode == MODE_DEFAULT) then
       call schur_by_solves(c, a, nb, kstar, error)
    else
       call c%schur(a, nb, kstar, error)
    end if
    seconds = now() - seconds
    cpu_seconds = cpu() - cpu_seconds
    if (allocated(error)) error stop 'condensation failed'
    if (present(fl)) fl = flops(c)
    call c%release()
  end subroutine condense

  real(wp) function flops(solver)
    class(linear_solver_t), intent(in) :: solver
    flops = 0.0_wp
    select type (solver)
    type is (cholmod_solver_t)
       flops = solver%flops()
    end select
  end function flops

  real(wp) function now()
    integer(i8) :: c, rate
    call system_clock(c, rate)
    now = real(c, wp)/real(rate, wp)
  end function now

  real(wp) function cpu()
    !! CPU time of the process so far (user + system), seconds.
    call cpu_time(cpu)
  end function cpu

  real(wp) function median(x)
    real(wp), intent(in) :: x(:)
    integer, allocatable :: order(:)
    real(wp), allocatable :: y(:)
    integer :: m, i
    allocate (order(size(x)))
    do i = 1, size(x)
       order(i) = i
    end do
    call sort_index(x, order)
    y = x(order)
    m = size(y)
    median = 0.5_wp*(y((m + 1)/2) + y(m/2 + 1))
  end function median
end program schur_cost
