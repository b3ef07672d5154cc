program test_mumps
  !! Unit tests of the MUMPS backend (src/solvers/mumps.f90) against CHOLMOD:
  !! solutions, the pivots it reports (1/(A^-1)_jj), null and negative pivot
  !! detection; the condensation by MUMPS's Schur complement (schur) against
  !! K* formed by solves. Skipped (status 77) in a build without MUMPS.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, EXIT_SINGULAR
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, mumps_available, mumps_solver_t, &
       cholmod_solver_t
  use superjoin_solvers_by_solves, only: by_solves_t
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  integer, parameter :: SKIP = 77
  integer(i8), parameter :: GRID = 12          !! 2D Laplacian GRID x GRID
  integer(i8), parameter :: KBAD = 29          !! the column made singular or negative
  integer(i8), parameter :: FREE = 40          !! schur: an interior column without stiffness
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
  call test_schur('mumps', .true.)
  call test_schur('mumps', .false.)
  call test_schur('mumps-ldlt', .true.)
  call test_schur('mumps-ldlt', .false.)
  call test_schur_breakdown('mumps')
  call test_schur_breakdown('mumps-ldlt')
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
    call laplace2d(GRID, a)
    call zero_column(a, KBAD)
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

  subroutine test_schur(name, alone)
    !! schur by ICNTL(19) against K* formed by CHOLMOD solves, on a floating
    !! part (a graph Laplacian: K* singular, its rows sum to zero), with a
    !! free interior DOF (diagonal 1, as condensed.f90 puts it), with nb = 0
    !! and with no interior; then solve and pivots refer to a_ii.
    character(*), intent(in) :: name
    logical, intent(in) :: alone
    type(sparse_sym_t) :: a, aii
    real(wp), allocatable :: ks(:, :), kref(:, :), b(:, :), x(:, :), xc(:, :), d(:), dref(:)
    integer(i8) :: nb, ni, j, k, other
    character(:), allocatable :: tag
    tag = name//merge(' alone', ' world', alone)//': schur'
    call laplace2d(GRID, a, floating=.true.)
    do j = 1, a%n   ! node FREE cut off (no stiffness, its diagonal 1); the rest still floats
       do k = a%colptr(j), a%colptr(j + 1) - 1
          if (j /= FREE .and. a%rowind(k) /= FREE) cycle
          if (j == a%rowind(k)) then
             a%val(k) = 1.0_wp
          else
             other = merge(j, a%rowind(k), a%rowind(k) == FREE)
             a%val(a%colptr(other + 1) - 1) = a%val(a%colptr(other + 1) - 1) + a%val(k)
             a%val(k) = 0.0_wp
          end if
       end do
    end do
    nb = GRID
    ni = a%n - nb
    call schur_with(name, alone, a, nb, ks, x, d)
    call reference_schur(a, nb, kref)
    call check(maxval(abs(ks - kref)) <= TOL*maxval(abs(kref)), tag//' K* equals K* by solves')
    call check(all(ks == transpose(ks)), tag//' K* in both triangles')
    call check(maxval(abs(sum(ks, dim=2))) <= TOL*maxval(abs(kref)), tag//' K* of a floating part is singular')
    call interior(a, ni, aii)
    allocate (b(ni, 2))
    do j = 1, ni
       b(j, :) = [real(mod(5*j, 7_i8) - 3, wp), 1.0_wp]
    end do
    call solve_with('cholmod', aii, b, xc)
    call check(maxval(abs(x - xc)) <= TOL*maxval(abs(xc)), tag//' solve is a_ii x = b')
    call check(abs(x(FREE, 1) - b(FREE, 1)) <= TOL, tag//' free interior DOF: x = b')
    call mumps_pivots_of(aii, dref)
    call check(maxval(abs(d - dref)) <= TOL*maxval(abs(dref)), tag//' pivots of a_ii')
    ! nb = 0: an ordinary factorization of the whole matrix
    call schur_with(name, alone, aii, 0_i8, ks, x, d)
    call check(size(ks) == 0 .and. maxval(abs(x - xc)) <= TOL*maxval(abs(xc)), tag//' nb = 0')
    ! no interior: K* is the matrix
    call laplace2d(3_i8, a)
    call schur_with(name, alone, a, a%n, ks, x, d)
    call reference_schur(a, a%n, kref)
    call check(all(ks == kref), tag//' no interior: K* = a')
  end subroutine test_schur

  subroutine test_schur_breakdown(name)
    !! A zero row and column inside the interior: EXIT_SINGULAR at that column.
    character(*), intent(in) :: name
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    real(wp), allocatable :: ks(:, :)
    call laplace2d(GRID, a, floating=.true.)
    call zero_column(a, KBAD)
    call new_solver(name, a%n, s, error)
    allocate (ks(GRID, GRID))
    call s%schur(a, GRID, ks, error)
    call check(allocated(error), name//': schur: interior breakdown detected')
    if (allocated(error)) then
       call check(error%code == EXIT_SINGULAR, name//': schur: breakdown -> EXIT_SINGULAR')
       call check(s%info%failed_column == KBAD, name//': schur: breakdown at the zero interior column')
       if (s%info%failed_column /= KBAD) write (*, '(a,i0,1x,a)') '   got column ', s%info%failed_column, error%message
    end if
    call s%release()
  end subroutine test_schur_breakdown

  subroutine zero_column(a, jz)
    !! Row and column jz of a set to zero.
    type(sparse_sym_t), intent(inout) :: a
    integer(i8), intent(in) :: jz
    integer(i8) :: j, k
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          if (j == jz .or. a%rowind(k) == jz) a%val(k) = 0.0_wp
       end do
    end do
  end subroutine zero_column

  subroutine schur_with(name, alone, a, nb, ks, x, d)
    !! K* of a by the named MUMPS solver's schur (alone: on MPI_COMM_SELF),
    !! then x = a_ii^-1 b (b as in test_schur) and the pivots d of a_ii.
    character(*), intent(in) :: name
    logical, intent(in) :: alone
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), allocatable, intent(out) :: ks(:, :), x(:, :), d(:)
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    real(wp), allocatable :: b(:, :)
    integer(i8) :: ni, j
    ni = a%n - nb
    allocate (ks(nb, nb), x(ni, 2), b(ni, 2), d(ni))
    do j = 1, ni
       b(j, :) = [real(mod(5*j, 7_i8) - 3, wp), 1.0_wp]
    end do
    call new_solver(name, a%n, s, error)
    select type (s)
    type is (mumps_solver_t)
       s%alone = alone
    end select
    call s%schur(a, nb, ks, error)
    if (.not. allocated(error) .and. ni > 0) call s%solve(b, x, error)
    call check(.not. allocated(error), name//': schur and solve')
    if (allocated(error)) write (*, '(a)') '   '//error%message
    if (ni > 0) call s%pivots(d)
    call s%release()
  end subroutine schur_with

  subroutine reference_schur(a, nb, ks)
    !! K* by the default route of linear_solver_t (a_ii factored by CHOLMOD,
    !! 2 nb solves), whatever CHOLMOD's own schur is.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), allocatable, intent(out) :: ks(:, :)
    type(by_solves_t) :: s
    type(error_t), allocatable :: error
    allocate (ks(nb, nb))
    allocate (cholmod_solver_t :: s%inner)
    call s%schur(a, nb, ks, error)
    call check(.not. allocated(error), 'cholmod: K* by solves')
    call s%release()
  end subroutine reference_schur

  subroutine interior(a, ni, aii)
    !! aii = the leading ni x ni block of a.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: ni
    type(sparse_sym_t), intent(out) :: aii
    aii%n = ni
    aii%colptr = a%colptr(1:ni + 1)
    aii%rowind = a%rowind(1:a%colptr(ni + 1) - 1)
    aii%val = a%val(1:a%colptr(ni + 1) - 1)
  end subroutine interior

  subroutine mumps_pivots_of(a, d)
    !! pivots() of MUMPS (SPD) factoring a.
    type(sparse_sym_t), intent(in) :: a
    real(wp), allocatable, intent(out) :: d(:)
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    allocate (d(a%n))
    call new_solver('mumps', a%n, s, error)
    call s%analyze(a, error)
    call s%factorize(a, error)
    call s%pivots(d)
    call s%release()
  end subroutine mumps_pivots_of

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

  subroutine laplace2d(m, a, floating)
    !! 5-point Laplacian on an m x m grid (upper triangle, CSC, diagonal last);
    !! floating: the graph Laplacian (diagonal = neighbours), singular, whose
    !! leading block without the last grid line is regular.
    integer(i8), intent(in) :: m
    type(sparse_sym_t), intent(out) :: a
    logical, intent(in), optional :: floating
    integer(i8) :: i, j, col, k
    real(wp) :: diag
    a%n = m*m
    allocate (a%colptr(a%n + 1), a%rowind(3*a%n), a%val(3*a%n))
    k = 0
    a%colptr(1) = 1
    do j = 1, m
       do i = 1, m
          col = (j - 1)*m + i
          if (j > 1) call put(a, k, col - m, -1.0_wp)
          if (i > 1) call put(a, k, col - 1, -1.0_wp)
          diag = 4.0_wp
          if (present(floating)) then
             if (floating) diag = real(merge(1, 0, i > 1) + merge(1, 0, i < m) + merge(1, 0, j > 1) + merge(1, 0, j < m), wp)
          end if
          call put(a, k, col, diag)
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
