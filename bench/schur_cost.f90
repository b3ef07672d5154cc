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
  !! difference of the two K* relative to sqrt(k_ii k_jj).
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
  real(wp), allocatable :: t(:, :), k1(:, :), k2(:, :), d(:)
  real(wp) :: worst, fl(3)

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
  allocate (t(reps, 5), k1(nb, nb), k2(nb, nb))
  do r = 1, reps
     call new_solver(trim(solver), ni, s, error)
     t(r, 1) = now()
     call s%analyze(aii, error)
     t(r, 5) = now() - t(r, 1)
     call s%factorize(aii, error)
     t(r, 1) = now() - t(r, 1)
     if (allocated(error)) error stop 'factor failed'
     fl(1) = flops(s)
     call s%release()
     deallocate (s)
     call new_solver(trim(solver), ni, s, error)
     t(r, 2) = now()
     call s%schur(a, nb, k1, error)
     t(r, 2) = now() - t(r, 2)
     if (allocated(error)) error stop 'schur failed'
     fl(2) = flops(s)
     call s%release()
     deallocate (s)
     call new_solver(trim(solver), ni, s, error)
     t(r, 3) = now()
     call schur_by_solves(s, a, nb, k2, error)
     t(r, 3) = now() - t(r, 3)
     if (allocated(error)) error stop 'default schur failed'
     call s%release()
     deallocate (s)
     call new_solver(trim(solver), ni, s, error)
     call camd_first_off(s)
     t(r, 4) = now()
     call s%schur(a, nb, k2, error)
     t(r, 4) = now() - t(r, 4)
     if (allocated(error)) error stop 'compare schur failed'
     fl(3) = flops(s)
     call s%release()
     deallocate (s)
     call new_solver(trim(solver), ni, s, error)
     call schur_by_solves(s, a, nb, k2, error)
     call s%release()
     deallocate (s)
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
  if (fl(1) > 0.0_wp) write (*, '(a,3es10.3,a,2f6.2)') 'flops (CHOLMOD): factor a_ii, schur, compare: ', fl, &
       '  ratios ', fl(2)/fl(1), fl(3)/fl(1)
  write (*, '(a,es9.2)') 'max |K*schur - K*default| / sqrt(k_ii k_jj): ', worst

contains

  subroutine camd_first_off(solver)
    class(linear_solver_t), intent(inout) :: solver
    select type (solver)
    type is (cholmod_solver_t)
       solver%camd_first = .false.
    end select
  end subroutine camd_first_off

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

  real(wp) function median(x)
    real(wp), intent(in) :: x(:)
    integer, allocatable :: order(:)
    real(wp), allocatable :: y(:)
    integer :: m, i
    order = [(i, i=1, size(x))]
    call sort_index(x, order)
    y = x(order)
    m = size(y)
    median = 0.5_wp*(y((m + 1)/2) + y(m/2 + 1))
  end function median
end program schur_cost
