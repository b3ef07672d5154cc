program test_mumps
  !! Unit tests of the MUMPS backend (src/solvers/mumps.f90) against CHOLMOD:
  !! solutions, the pivots it reports (1/(A^-1)_jj), null and negative pivot
  !! detection. Skipped (status 77) in a build without MUMPS.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, EXIT_SINGULAR
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, mumps_available
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  integer, parameter :: SKIP = 77
  integer(i8), parameter :: GRID = 12          !! 2D Laplacian GRID x GRID
  integer(i8), parameter :: KBAD = 29          !! the column made singular or negative
  real(wp), parameter :: TOL = 1.0e-10_wp      !! MUMPS against CHOLMOD, relative
  real(wp), parameter :: RES_TOL = 1.0e-13_wp  !! relative residual of a direct solve

  if (.not. mumps_available()) then
     write (*, '(a)') 'test_mumps: built without MUMPS, skipped'
     stop SKIP
  end if
  call test_against_cholmod('mumps')
  call test_against_cholmod('mumps-ldlt')
  call test_pivots()
  call test_null_pivot('mumps')
  call test_null_pivot('mumps-ldlt')
  call test_negative_pivot()
  call finish()

contains

  subroutine test_against_cholmod(name)
    !! The solution of a 2D Laplacian with 3 right-hand sides equals CHOLMOD's.
    character(*), intent(in) :: name
    type(sparse_sym_t) :: a
    real(wp), allocatable :: b(:, :), x(:, :), xc(:, :), r(:, :)
    integer(i8) :: i
    integer :: k
    call laplace2d(GRID, a)
    allocate (b(a%n, 3), r(a%n, 3))
    do k = 1, 3
       do i = 1, a%n
          b(i, k) = real(mod(7*i + k, 11_i8) - 5, wp)
       end do
    end do
    call solve_with(name, a, b, x)
    call solve_with('cholmod', a, b, xc)
    call check(maxval(abs(x - xc)) <= TOL*maxval(abs(xc)), name//': solution equals CHOLMOD''s')
    call a%matvec(x, r)
    call check(norm2(r - b) <= RES_TOL*norm2(b), name//': residual')
  end subroutine test_against_cholmod

  subroutine test_pivots()
    !! pivots() returns 1/(A^-1)_jj: checked against CHOLMOD solves with unit vectors.
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    real(wp), allocatable :: d(:), e(:, :), y(:, :)
    integer(i8) :: j
    real(wp) :: worst
    call laplace2d(GRID, a)
    call new_solver('mumps', a%n, s, error)
    call s%analyze(a, error)
    call s%factorize(a, error)
    call check(.not. allocated(error), 'mumps: factorize for pivots')
    allocate (d(a%n))
    call s%pivots(d)
    call s%release()
    allocate (e(a%n, a%n))
    e = 0.0_wp
    do j = 1, a%n
       e(j, j) = 1.0_wp
    end do
    call solve_with('cholmod', a, e, y)
    worst = 0.0_wp
    do j = 1, a%n
       worst = max(worst, abs(d(j)*y(j, j) - 1.0_wp))
    end do
    call check(worst <= TOL, 'mumps: pivots are 1/(A^-1)_jj')
    ! the bound: never above CHOLMOD's own pivots (positive definite matrix)
    call new_solver('cholmod', a%n, s, error)
    call s%analyze(a, error)
    call s%factorize(a, error)
    call s%pivots(e(:, 1))
    call check(all(d <= e(:, 1)*(1.0_wp + TOL)), 'mumps: pivots bound CHOLMOD''s from below')
  end subroutine test_pivots

  subroutine test_null_pivot(name)
    !! A zero row and column: EXIT_SINGULAR at that column (null pivot detection).
    character(*), intent(in) :: name
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    integer(i8) :: j, k
    call laplace2d(GRID, a)
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          if (j == KBAD .or. a%rowind(k) == KBAD) a%val(k) = 0.0_wp
       end do
    end do
    call new_solver(name, a%n, s, error)
    call s%analyze(a, error)
    call check(.not. allocated(error), name//': analyze of the singular matrix')
    call s%factorize(a, error)
    call check(allocated(error), name//': null pivot detected')
    if (allocated(error)) then
       call check(error%code == EXIT_SINGULAR, name//': null pivot -> EXIT_SINGULAR')
       call check(s%info%failed_column == KBAD, name//': null pivot at the zero column')
       if (s%info%failed_column /= KBAD) write (*, '(a,i0,1x,a)') '   got column ', s%info%failed_column, error%message
    end if
    call s%release()
  end subroutine test_null_pivot

  subroutine test_negative_pivot()
    !! A negative diagonal: refused by the SPD variant, solved by mumps-ldlt
    !! (one negative pivot, INFOG(12)).
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    real(wp), allocatable :: b(:, :), x(:, :), r(:, :)
    call laplace2d(GRID, a)
    a%val(a%colptr(KBAD + 1) - 1) = -10.0_wp
    call new_solver('mumps', a%n, s, error)
    call s%analyze(a, error)
    call s%factorize(a, error)
    call check(allocated(error), 'mumps: indefinite matrix refused')
    if (allocated(error)) call check(error%code == EXIT_SINGULAR, 'mumps: indefinite -> EXIT_SINGULAR')
    call s%release()
    allocate (b(a%n, 1), r(a%n, 1))
    b = 1.0_wp
    call solve_with('mumps-ldlt', a, b, x)
    call a%matvec(x, r)
    call check(norm2(r - b) <= RES_TOL*norm2(b), 'mumps-ldlt: indefinite residual')
  end subroutine test_negative_pivot

  subroutine solve_with(name, a, b, x)
    !! x = A^-1 b with the named backend; any error fails the check.
    character(*), intent(in) :: name
    type(sparse_sym_t), intent(in) :: a
    real(wp), intent(in) :: b(:, :)
    real(wp), allocatable, intent(out) :: x(:, :)
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    allocate (x(a%n, size(b, 2)))
    x = 0.0_wp
    call new_solver(name, a%n, s, error)
    if (.not. allocated(error)) call s%analyze(a, error)
    if (.not. allocated(error)) call s%factorize(a, error)
    if (.not. allocated(error)) call s%solve(b, x, error)
    call check(.not. allocated(error), name//': analyze, factorize, solve')
    if (allocated(error)) write (*, '(a)') '   '//error%message
    call s%release()
  end subroutine solve_with

  subroutine laplace2d(m, a)
    !! 5-point Laplacian on an m x m grid (upper triangle, CSC, diagonal last).
    integer(i8), intent(in) :: m
    type(sparse_sym_t), intent(out) :: a
    integer(i8) :: i, j, col, k
    a%n = m*m
    allocate (a%colptr(a%n + 1), a%rowind(3*a%n), a%val(3*a%n))
    k = 0
    a%colptr(1) = 1
    do j = 1, m
       do i = 1, m
          col = (j - 1)*m + i
          if (j > 1) call put(a, k, col - m, -1.0_wp)
          if (i > 1) call put(a, k, col - 1, -1.0_wp)
          call put(a, k, col, 4.0_wp)
          a%colptr(col + 1) = k + 1
       end do
    end do
  end subroutine laplace2d

  subroutine put(a, k, row, v)
    !! Append one entry to the column being built.
    type(sparse_sym_t), intent(inout) :: a
    integer(i8), intent(inout) :: k
    integer(i8), intent(in) :: row
    real(wp), intent(in) :: v
    k = k + 1
    a%rowind(k) = row
    a%val(k) = v
  end subroutine put
end program test_mumps
