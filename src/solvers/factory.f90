module superjoin_solvers
  !! The solver facade: the abstract solver and the sparse matrix type, a
  !! factory choosing a backend by name, and a 1-norm condition estimate that
  !! reuses an existing factorization.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_USAGE, EXIT_IO
  use superjoin_solvers_sparse, only: sparse_sym_t, move_sparse
  use superjoin_solvers_solver, only: linear_solver_t, solver_info_t
  use superjoin_solvers_cholmod, only: cholmod_solver_t
  use superjoin_solvers_umfpack, only: umfpack_solver_t
  use superjoin_solvers_lapack, only: lapack_solver_t
  use superjoin_solvers_mumps, only: mumps_solver_t, MUMPS_SPD, MUMPS_SYMMETRIC, mumps_available
  use superjoin_utils_strings, only: to_lower
  implicit none (type, external)
  private

  public :: linear_solver_t, solver_info_t, sparse_sym_t, move_sparse
  public :: cholmod_solver_t, umfpack_solver_t, lapack_solver_t, mumps_solver_t
  public :: new_solver, condition_estimate, norm1_sym, mumps_available, inverse_norm_bound

  integer(i8), parameter, public :: AUTO_LAPACK_MAX = 1000_i8  !! 'auto': LAPACK up to this n, CHOLMOD above
  integer, parameter :: HAGER_MAX_ITER = 5                      !! iterations of the 1-norm estimator

contains

  subroutine new_solver(name, n, solver, error)
    !! Allocate the solver called name ('auto', 'cholmod', 'umfpack', 'lapack',
    !! 'mumps' (MUMPS LDL^T, SPD) or 'mumps-ldlt' (MUMPS LDL^T with pivoting);
    !! case and surrounding blanks ignored) for a matrix of order n. 'auto'
    !! takes LAPACK for n <= AUTO_LAPACK_MAX and CHOLMOD otherwise. A MUMPS
    !! solver in a build without MUMPS fails in analyze (EXIT_USAGE).
    !! Unknown name: error with code EXIT_USAGE.
    character(*), intent(in) :: name
    integer(i8), intent(in) :: n
    class(linear_solver_t), allocatable, intent(out) :: solver
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: key

    key = to_lower(trim(adjustl(name)))
    select case (key)
    case ('auto')
       if (n <= AUTO_LAPACK_MAX) then
          allocate (lapack_solver_t :: solver)
       else
          allocate (cholmod_solver_t :: solver)
       end if
    case ('cholmod')
       allocate (cholmod_solver_t :: solver)
    case ('umfpack')
       allocate (umfpack_solver_t :: solver)
    case ('lapack')
       allocate (lapack_solver_t :: solver)
    case ('mumps', 'mumps-ldlt')
       allocate (mumps_solver_t :: solver)
       select type (solver)
       type is (mumps_solver_t)
          solver%sym = merge(MUMPS_SPD, MUMPS_SYMMETRIC, key == 'mumps')
       end select
    case default
       call fatal_error(error, EXIT_USAGE, "unknown solver '"//trim(adjustl(name))// &
            "' (expected auto, cholmod, umfpack, lapack, mumps or mumps-ldlt)")
    end select
  end subroutine new_solver

  pure function norm1_sym(a) result(anorm)
    !! 1-norm of the symmetric matrix whose upper triangle is a (max column sum).
    type(sparse_sym_t), intent(in) :: a
    real(wp) :: anorm
    real(wp), allocatable :: colsum(:)
    integer(i8) :: j, k, i
    anorm = 0.0_wp
    if (a%n <= 0) return
    allocate (colsum(a%n))
    colsum = 0.0_wp
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          i = a%rowind(k)
          colsum(j) = colsum(j) + abs(a%val(k))
          if (i /= j) colsum(i) = colsum(i) + abs(a%val(k))
       end do
    end do
    anorm = maxval(colsum)
  end function norm1_sym

  subroutine condition_estimate(a, solver, cond1, anorm1, inv_norm1, error, anorm_given)
    !! 1-norm condition number estimate cond1 = ||A||_1 ||A^-1||_1 of the
    !! symmetric matrix a, with solver holding its factorization. ||A^-1||_1 is
    !! estimated with Hager's method as refined by Higham (LAPACK's dlacon:
    !! at most HAGER_MAX_ITER steps, two solves each, plus one solve with an
    !! alternating-sign vector); A^-T = A^-1 since A is symmetric. The
    !! estimate is a lower bound of the true value, usually within a small
    !! factor. anorm1 and inv_norm1 (optional) return the two factors. If a
    !! solve fails, cond1 = 0 (unknown) and error (optional) tells why.
    !! anorm_given: ||A||_1 computed by the caller (health has it already; under
    !! owner terms a is only one MPI process's term of A, whose norm is not A's):
    !! a is then not read, only its order.
    type(sparse_sym_t), intent(in) :: a
    class(linear_solver_t), intent(inout) :: solver
    real(wp), intent(out) :: cond1
    real(wp), intent(out), optional :: anorm1, inv_norm1
    type(error_t), allocatable, intent(out), optional :: error
    real(wp), intent(in), optional :: anorm_given
    type(error_t), allocatable :: err
    real(wp) :: anorm, ainv

    if (present(anorm_given)) then   ! no pass over a for a norm the caller has
       anorm = anorm_given
    else
       anorm = norm1_sym(a)
    end if
    call estimate(a%n, solver, ainv, err)
    cond1 = anorm*ainv
    if (allocated(err)) then
       cond1 = 0.0_wp
       ainv = 0.0_wp
    end if
    if (present(anorm1)) anorm1 = anorm
    if (present(inv_norm1)) inv_norm1 = ainv
    if (present(error)) then
       if (allocated(err)) call move_alloc(err, error)
    end if
  end subroutine condition_estimate

  subroutine estimate(n, solver, inv_norm1, error)
    !! The Hager-Higham estimate of ||A^-1||_1 (A of order n, factored in solver).
    integer(i8), intent(in) :: n
    class(linear_solver_t), intent(inout) :: solver
    real(wp), intent(out) :: inv_norm1
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:, :), y(:, :), xi(:), xi_old(:)
    real(wp) :: est, estold, alt
    integer(i8) :: i, jmax, jold
    integer :: iter, stat

    inv_norm1 = 0.0_wp
    if (n <= 0) return
    allocate (x(n, 2), y(n, 2), xi(n), xi_old(n), stat=stat)
    if (stat /= 0) then
       call fatal_error(error, EXIT_IO, 'condition estimate: out of memory')
       return
    end if
    ! first solve together with Higham's alternating-sign vector
    x(:, 1) = 1.0_wp/real(n, wp)
    do i = 1, n
       x(i, 2) = real(1 - 2*mod(i - 1, 2_i8), wp)*(1.0_wp + real(i - 1, wp)/real(max(n - 1, 1_i8), wp))
    end do
    call solver%solve(x, y, error)
    if (allocated(error)) return
    alt = 2.0_wp*sum(abs(y(:, 2)))/(3.0_wp*real(n, wp))
    est = sum(abs(y(:, 1)))
    if (n > 1) then
       xi = sign_of(y(:, 1))
       ! z = A^-T xi, stored in x(:, 1)
       call solver%solve(reshape(xi, [n, 1_i8]), x(:, 1:1), error)
       if (allocated(error)) return
       jmax = maxloc(abs(x(:, 1)), dim=1, kind=i8)
       do iter = 2, HAGER_MAX_ITER
          ! y = A^-1 e_jmax
          x(:, 2) = 0.0_wp
          x(jmax, 2) = 1.0_wp
          call solver%solve(x(:, 2:2), y(:, 1:1), error)
          if (allocated(error)) return
          estold = est
          est = max(est, sum(abs(y(:, 1))))
          xi_old = xi
          xi = sign_of(y(:, 1))
          ! repeated sign vector (converged) or no growth (cycling)
          if (all(xi == xi_old) .or. est <= estold) exit
          call solver%solve(reshape(xi, [n, 1_i8]), x(:, 1:1), error)
          if (allocated(error)) return
          jold = jmax
          jmax = maxloc(abs(x(:, 1)), dim=1, kind=i8)
          if (abs(x(jold, 1)) == abs(x(jmax, 1))) exit
       end do
    end if
    inv_norm1 = max(est, alt)
  end subroutine estimate

  pure function inverse_norm_bound(x, b, d) result(bound)
    !! A lower bound of ||A^-1||_1 from what a solve already has, at no
    !! further solve: ||x_s||_1 / ||b_s||_1 for every column of A x = b, and
    !! 1 / d_j for the pivots d of an LL^T or LDL^T factorization of an SPD
    !! A without 2x2 pivots ((A^-1)_jj >= 1 / D_jj; d <= 0 skipped: columns
    !! a factorization did not reach, or unknown pivots).
    real(wp), intent(in) :: x(:, :), b(:, :)
    real(wp), intent(in), optional :: d(:)
    real(wp) :: bound, bnorm
    integer :: s
    bound = 0.0_wp
    do s = 1, min(size(x, 2), size(b, 2))
       bnorm = sum(abs(b(:, s)))
       if (bnorm > 0.0_wp) bound = max(bound, sum(abs(x(:, s)))/bnorm)
    end do
    if (present(d)) then
       if (any(d > 0.0_wp)) bound = max(bound, 1.0_wp/minval(d, mask=d > 0.0_wp))
    end if
  end function inverse_norm_bound

  pure function sign_of(v) result(s)
    !! Elementwise sign (+1 for zero).
    real(wp), intent(in) :: v(:)
    real(wp) :: s(size(v))
    where (v >= 0.0_wp)
       s = 1.0_wp
    elsewhere
       s = -1.0_wp
    end where
  end function sign_of
end module superjoin_solvers
