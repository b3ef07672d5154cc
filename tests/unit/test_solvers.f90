program test_solvers
  !! Unit tests of the linear solvers (CHOLMOD, UMFPACK, LAPACK), the solver
  !! factory, the condition estimate and Matrix Market input/output.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, EXIT_SINGULAR, EXIT_USAGE, EXIT_IO
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, condition_estimate, &
       norm1_sym, cholmod_solver_t, lapack_solver_t, umfpack_solver_t, AUTO_LAPACK_MAX, move_sparse
  use superjoin_solvers_lapack, only: rcm_ordering
  use superjoin_solvers_matrix_market, only: write_matrix_market, read_matrix_market
  use superjoin_solvers_node_graph, only: node_graph
  use superjoin_testing, only: check, check_close, check_rel, finish, temp_dir
  use test_matrices, only: grid_laplacian
  implicit none (type, external)

  character(len=*), parameter :: BACKENDS(3) = [character(len=7) :: 'cholmod', 'umfpack', 'lapack']
  real(wp), parameter :: RES_TOL = 1.0e-13_wp       !! relative residual expected from a direct solve
  integer :: ib
  real(wp) :: logdet_ref
  integer(i8) :: rng_state = 123456789_i8

  logdet_ref = 0.0_wp
  do ib = 1, size(BACKENDS)
     call test_backend(trim(BACKENDS(ib)))
  end do
  call test_factory()
  call test_move_sparse()
  call test_rcm()
  call test_matrix_market()
  call test_large_cholmod()
  call test_node_graph_ordering()
  call test_node_metis_only()
  call test_node_amd_ordering()
  call finish()

contains

  ! ------------------------------------------------------------------ backends

  subroutine test_backend(name)
    character(*), intent(in) :: name
    type(sparse_sym_t) :: a
    integer :: m

    write (*, '(a)') '--- '//name
    ! n = 1
    call from_dense(reshape([3.0_wp], [1, 1]), a)
    call solve_and_check(name, a, 1, 'n=1')
    ! 1D Laplacians
    do m = 2, 3
       call laplace1d(10_i8**m, a)
       call solve_and_check(name, a, 1, '1D Laplacian')
    end do
    call laplace1d(7_i8, a)
    call solve_and_check(name, a, 3, '1D Laplacian, 3 rhs')
    ! 2D Laplacians
    call laplace2d(5_i8, a)
    call solve_and_check(name, a, 2, '2D Laplacian 5x5')
    call laplace2d(30_i8, a)
    call solve_and_check(name, a, 4, '2D Laplacian 30x30')
    if (name /= 'lapack') then
       call laplace2d(100_i8, a)
       call solve_and_check(name, a, 1, '2D Laplacian 100x100')
    else
       call laplace2d(60_i8, a)
       call solve_and_check(name, a, 1, '2D Laplacian 60x60 (banded)')
    end if
    ! random SPD
    call random_spd(150, 0.05_wp, a)
    call solve_and_check(name, a, 2, 'random SPD n=150')
    call random_spd(40, 0.5_wp, a)
    call solve_and_check(name, a, 1, 'random SPD n=40 dense-ish')

    call test_empty(name)
    call test_refactorize(name)
    call test_not_posdef(name)
    call test_pivots(name)
    call test_condition(name)
    call test_misuse(name)
  end subroutine test_backend

  subroutine solve_and_check(name, a, nrhs, what)
    !! Analyze, factorize, solve with nrhs known solutions; check the residual.
    character(*), intent(in) :: name
    type(sparse_sym_t), intent(in) :: a
    integer, intent(in) :: nrhs
    character(*), intent(in) :: what
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    real(wp), allocatable :: xt(:, :), b(:, :), x(:, :), r(:, :)
    integer(i8) :: i
    integer :: k
    character(len=160) :: tag

    write (tag, '(a,a,a,a,i0,a)') name, ': ', what, ' (n=', a%n, ')'
    call new_solver(name, a%n, s, error)
    call check(.not. allocated(error), trim(tag)//' new_solver')
    if (allocated(error)) return
    allocate (xt(a%n, nrhs), b(a%n, nrhs), x(a%n, nrhs), r(a%n, nrhs))
    do k = 1, nrhs
       do i = 1, a%n
          xt(i, k) = sin(0.37_wp*real(i*k, wp)) + 0.5_wp*real(k, wp)
       end do
    end do
    call a%matvec(xt, b)
    call s%analyze(a, error)
    call check(.not. allocated(error), trim(tag)//' analyze')
    if (allocated(error)) then
       write (*, '(a)') '   '//error%message
       return
    end if
    call s%factorize(a, error)
    call check(.not. allocated(error), trim(tag)//' factorize')
    if (allocated(error)) then
       write (*, '(a)') '   '//error%message
       return
    end if
    call s%solve(b, x, error)
    call check(.not. allocated(error), trim(tag)//' solve')
    if (allocated(error)) return
    call a%matvec(x, r)
    r = r - b
    do k = 1, nrhs
       call check(norm2(r(:, k)) <= RES_TOL*norm2(b(:, k)), trim(tag)//' residual')
    end do
    call check(len(s%info%name) > 0 .and. len(s%info%ordering) > 0, trim(tag)//' info names')
    call check(s%info%factor_nnz >= a%n, trim(tag)//' factor_nnz')
    call check(s%info%factor_mbytes > 0.0_wp, trim(tag)//' factor_mbytes')
    call check(s%info%failed_column == 0, trim(tag)//' failed_column 0')
    if (a%n >= 100) write (*, '(3a,i0,5a)') '   ', trim(tag), ': factor nnz ', s%info%factor_nnz, &
         ', ', s%info%name, ', ordering ', s%info%ordering
    call s%release()
  end subroutine solve_and_check

  subroutine test_empty(name)
    !! n = 0 (every unknown constrained) goes through all phases.
    character(*), intent(in) :: name
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    real(wp), allocatable :: b(:, :), x(:, :), d(:)
    real(wp) :: cond

    a%n = 0
    allocate (a%colptr(1), a%rowind(0), a%val(0), b(0, 1), x(0, 1), d(0))
    a%colptr = 1
    call new_solver(name, a%n, s, error)
    call s%analyze(a, error)
    call check(.not. allocated(error), name//': n=0 analyze')
    call s%factorize(a, error)
    call check(.not. allocated(error), name//': n=0 factorize')
    call s%solve(b, x, error)
    call check(.not. allocated(error), name//': n=0 solve')
    call s%pivots(d)
    call condition_estimate(a, s, cond)
    call check(cond == 0.0_wp, name//': n=0 condition')
    call s%release()
  end subroutine test_empty

  subroutine test_refactorize(name)
    !! One analysis, two factorizations with different values.
    character(*), intent(in) :: name
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    real(wp), allocatable :: xt(:, :), b(:, :), x(:, :), r(:, :)
    integer(i8) :: j
    integer :: pass

    call laplace2d(12_i8, a)
    call new_solver(name, a%n, s, error)
    call s%analyze(a, error)
    call check(.not. allocated(error), name//': refactorize analyze')
    allocate (xt(a%n, 1), b(a%n, 1), x(a%n, 1), r(a%n, 1))
    xt(:, 1) = [(real(j, wp), j=1, a%n)]
    do pass = 1, 2
       if (pass == 2) then
          ! new values on the same pattern: stiffer diagonal, scaled couplings
          a%val = 3.0_wp*a%val
          do j = 1, a%n
             a%val(a%colptr(j + 1) - 1) = a%val(a%colptr(j + 1) - 1) + real(j, wp)
          end do
       end if
       call a%matvec(xt, b)
       call s%factorize(a, error)
       call check(.not. allocated(error), name//': refactorize factorize')
       if (allocated(error)) return
       call s%solve(b, x, error)
       call check(.not. allocated(error), name//': refactorize solve')
       if (allocated(error)) return
       call a%matvec(x, r)
       call check(norm2(r - b) <= RES_TOL*norm2(b), name//': refactorize residual')
       call check(maxval(abs(x - xt)) <= 1.0e-9_wp*maxval(abs(xt)), name//': refactorize solution')
    end do
    call s%release()
  end subroutine test_refactorize

  subroutine test_not_posdef(name)
    !! Breakdowns with a known failing column.
    character(*), intent(in) :: name
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    integer(i8), parameter :: M = 8, KBAD = 29
    integer(i8) :: j, k, fc
    real(wp), allocatable :: d(:), xt(:, :), b(:, :), x(:, :), r(:, :)
    real(wp), allocatable :: ad(:, :)

    ! (1) zero row and column KBAD (entries kept as explicit zeros)
    call laplace2d(M, a)
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          if (j == KBAD .or. a%rowind(k) == KBAD) a%val(k) = 0.0_wp
       end do
    end do
    call new_solver(name, a%n, s, error)
    call s%analyze(a, error)
    call s%factorize(a, error)
    call check(allocated(error), name//': zero row detected')
    if (allocated(error)) then
       call check(error%code == EXIT_SINGULAR, name//': zero row -> EXIT_SINGULAR')
       call check(s%info%failed_column == KBAD, name//': zero row failed column')
       if (s%info%failed_column /= KBAD) write (*, '(a,i0)') '   got column ', s%info%failed_column
       if (name /= 'umfpack') call check(error%message == 'matrix is not positive definite at column 29', &
            name//': zero row message')
    end if
    ! solve after a failed factorization is refused
    allocate (b(a%n, 1), x(a%n, 1))
    b = 1.0_wp
    call s%solve(b, x, error)
    call check(allocated(error), name//': solve refused after breakdown')
    deallocate (b, x)
    call s%release()

    ! (2) negative diagonal at KBAD: every other principal submatrix is PD,
    ! so the breakdown is at KBAD whatever the ordering
    call laplace2d(M, a)
    a%val(a%colptr(KBAD + 1) - 1) = -10.0_wp
    call new_solver(name, a%n, s, error)
    call s%analyze(a, error)
    call s%factorize(a, error)
    if (name == 'umfpack') then
       ! LU factorizes the indefinite matrix
       call check(.not. allocated(error), name//': indefinite matrix factorized')
       allocate (xt(a%n, 1), b(a%n, 1), x(a%n, 1), r(a%n, 1), d(a%n))
       xt = 1.0_wp
       call a%matvec(xt, b)
       call s%solve(b, x, error)
       call a%matvec(x, r)
       call check(norm2(r - b) <= RES_TOL*norm2(b), name//': indefinite residual')
       call s%pivots(d)
       call check(d(KBAD) < 0.0_wp .and. count(d < 0.0_wp) == 1, name//': one negative pivot, at KBAD')
       deallocate (xt, b, x, r, d)
    else
       call check(allocated(error), name//': negative pivot detected')
       if (allocated(error)) then
          call check(error%code == EXIT_SINGULAR, name//': negative pivot -> EXIT_SINGULAR')
          call check(s%info%failed_column == KBAD, name//': negative pivot failed column')
          if (s%info%failed_column /= KBAD) write (*, '(a,i0)') '   got column ', s%info%failed_column
       end if
       ! pivots: columns not reached are 0, the others positive
       allocate (d(a%n))
       call s%pivots(d)
       call check(d(KBAD) == 0.0_wp .and. all(d >= 0.0_wp), name//': pivots after breakdown')
       deallocate (d)
       ! the same analysis factorizes the repaired matrix
       a%val(a%colptr(KBAD + 1) - 1) = 4.0_wp
       call s%factorize(a, error)
       call check(.not. allocated(error), name//': refactorize after breakdown')
       call check(s%info%failed_column == 0, name//': failed_column reset')
       allocate (xt(a%n, 1), b(a%n, 1), x(a%n, 1), r(a%n, 1))
       xt = 1.0_wp
       call a%matvec(xt, b)
       call s%solve(b, x, error)
       call check(.not. allocated(error), name//': solve after refactorize')
       call a%matvec(x, r)
       call check(norm2(r - b) <= RES_TOL*norm2(b), name//': residual after refactorize')
       deallocate (xt, b, x, r)
    end if
    call s%release()

    ! (3) a supported grid plus a floating chain of 5 nodes (free-free
    ! springs): singular, the failing column is in the floating block
    allocate (ad(25 + 5, 25 + 5))
    ad = 0.0_wp
    call dense_laplace2d(5, ad(1:25, 1:25))
    do j = 26, 29
       ad(j, j) = ad(j, j) + 1.0_wp
       ad(j + 1, j + 1) = ad(j + 1, j + 1) + 1.0_wp
       ad(j, j + 1) = -1.0_wp
       ad(j + 1, j) = -1.0_wp
    end do
    call from_dense(ad, a)
    call new_solver(name, a%n, s, error)
    call s%analyze(a, error)
    call s%factorize(a, error)
    call check(allocated(error), name//': floating block detected')
    if (allocated(error)) then
       call check(error%code == EXIT_SINGULAR, name//': floating block -> EXIT_SINGULAR')
       fc = s%info%failed_column
       call check(fc >= 26 .and. fc <= 30, name//': floating block failed column in the block')
       if (fc < 26 .or. fc > 30) write (*, '(a,i0)') '   got column ', fc
    end if
    call s%release()
  end subroutine test_not_posdef

  subroutine test_pivots(name)
    !! Pivots: diagonal matrix, 2x2 matrix, and log det equal across backends.
    character(*), intent(in) :: name
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a
    real(wp), allocatable :: ad(:, :), d(:)
    real(wp) :: a11, a12, a22, logdet
    logical :: order12, order21
    integer :: i

    ! diagonal matrix: d = diag
    allocate (ad(6, 6))
    ad = 0.0_wp
    do i = 1, 6
       ad(i, i) = real(i*i, wp) + 0.5_wp
    end do
    call from_dense(ad, a)
    call factor(name, a, s, error)
    allocate (d(6))
    call s%pivots(d)
    do i = 1, 6
       call check_rel(d(i), ad(i, i), 4.0_wp*epsilon(1.0_wp), name//': pivots of a diagonal matrix')
    end do
    call s%release()
    deallocate (ad, d)

    ! 2x2 [a11 a12; a12 a22]: the pivots depend on the elimination order
    a11 = 4.0_wp
    a12 = 2.0_wp
    a22 = 3.0_wp
    call from_dense(reshape([a11, a12, a12, a22], [2, 2]), a)
    call factor(name, a, s, error)
    allocate (d(2))
    call s%pivots(d)
    order12 = abs(d(1) - a11) <= 1.0e-14_wp*a11 .and. abs(d(2) - (a22 - a12**2/a11)) <= 1.0e-14_wp*a22
    order21 = abs(d(2) - a22) <= 1.0e-14_wp*a22 .and. abs(d(1) - (a11 - a12**2/a22)) <= 1.0e-14_wp*a11
    call check(order12 .or. order21, name//': pivots of a 2x2 matrix')
    if (name == 'lapack') call check(order12, name//': 2x2 natural order')
    if (.not. (order12 .or. order21)) write (*, '(a,2es24.16)') '   got ', d
    call s%release()
    deallocate (d)

    ! product of the pivots = det(A) whatever the ordering
    call laplace2d(10_i8, a)
    a%val(1) = a%val(1) + 1.0_wp
    call factor(name, a, s, error)
    allocate (d(a%n))
    call s%pivots(d)
    call check(all(d > 0.0_wp), name//': Laplacian pivots positive')
    logdet = sum(log(d))
    if (logdet_ref == 0.0_wp) logdet_ref = logdet
    call check_rel(logdet, logdet_ref, 1.0e-12_wp, name//': sum(log(pivots)) = log det, same for all backends')
    ! K_jj / D_jj >= 1 for an SPD matrix (pivots only decrease)
    call check(all(diag_of(a)/d >= 1.0_wp - 1.0e-12_wp), name//': pivot ratios >= 1')
    call s%release()
  end subroutine test_pivots

  subroutine test_condition(name)
    !! Condition estimate within a factor 3 of the true 1-norm condition number.
    character(*), intent(in) :: name
    type(sparse_sym_t) :: a
    integer :: icase

    do icase = 1, 4
       select case (icase)
       case (1)
          call laplace1d(50_i8, a)
       case (2)
          call laplace2d(9_i8, a)
       case (3)
          call random_spd(80, 0.1_wp, a)
       case (4)
          call random_spd(30, 0.3_wp, a)
          ! make it badly scaled
          a%val(a%colptr(5):a%colptr(6) - 1) = 1.0e4_wp*a%val(a%colptr(5):a%colptr(6) - 1)
          a%val(a%colptr(6) - 1) = 1.0e8_wp*a%val(a%colptr(6) - 1)
       end select
       call check_condition(name, a, icase)
    end do
  end subroutine test_condition

  subroutine check_condition(name, a, icase)
    character(*), intent(in) :: name
    type(sparse_sym_t), intent(in) :: a
    integer, intent(in) :: icase
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    real(wp), allocatable :: eye(:, :), ainv(:, :)
    real(wp) :: cond_true, cond_est, anorm, ainvnorm
    integer(i8) :: i
    character(len=80) :: tag

    write (tag, '(a,a,i0)') name, ': condition estimate case ', icase
    call factor(name, a, s, error)
    if (allocated(error)) then
       call check(.false., trim(tag)//' factor')
       return
    end if
    allocate (eye(a%n, a%n), ainv(a%n, a%n))
    eye = 0.0_wp
    do i = 1, a%n
       eye(i, i) = 1.0_wp
    end do
    call s%solve(eye, ainv, error)
    cond_true = norm1_sym(a)*maxval(sum(abs(ainv), dim=1))
    call condition_estimate(a, s, cond_est, anorm, ainvnorm, error)
    call check(.not. allocated(error), trim(tag)//' no error')
    call check(cond_est <= cond_true*(1.0_wp + 1.0e-8_wp) .and. cond_est >= cond_true/3.0_wp, trim(tag))
    call check_rel(anorm, norm1_sym(a), 1.0e-15_wp, trim(tag)//' anorm')
    call check_rel(cond_est, anorm*ainvnorm, 1.0e-15_wp, trim(tag)//' product')
    if (name == 'cholmod') write (*, '(a,a,2es12.4)') '   ', trim(tag)//': estimate, true ', cond_est, cond_true
    ! the short form used by the analysis
    call condition_estimate(a, s, cond_true)
    call check_rel(cond_true, cond_est, 1.0e-12_wp, trim(tag)//' short form')
    call s%release()
  end subroutine check_condition

  subroutine test_misuse(name)
    !! Wrong call orders and shapes give errors, never crashes.
    character(*), intent(in) :: name
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(sparse_sym_t) :: a, a2
    real(wp) :: b(5, 1), x(5, 1), x4(4, 1)

    call laplace1d(5_i8, a)
    call new_solver(name, a%n, s, error)
    b = 1.0_wp
    call s%solve(b, x, error)
    call check(allocated(error), name//': solve before factorize refused')
    call s%factorize(a, error)
    call check(allocated(error), name//': factorize before analyze refused')
    call s%analyze(a, error)
    call s%factorize(a, error)
    call check(.not. allocated(error), name//': factorize ok')
    call s%solve(b, x4, error)
    call check(allocated(error), name//': wrong solution shape refused')
    call laplace1d(6_i8, a2)
    call s%factorize(a2, error)
    call check(allocated(error), name//': factorize with another order refused')
    ! the analysis is still usable afterwards
    call s%factorize(a, error)
    call s%solve(b, x, error)
    call check(.not. allocated(error), name//': usable after a refused call')
    call s%release()
    call s%release()   ! twice is harmless
  end subroutine test_misuse

  ! ------------------------------------------------------------------ factory

  subroutine test_factory()
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error

    call new_solver('auto', 10_i8, s, error)
    call check(.not. allocated(error), 'factory: auto')
    select type (s)
    type is (lapack_solver_t)
       call check(.true., 'factory: auto small -> lapack')
    class default
       call check(.false., 'factory: auto small -> lapack')
    end select
    call new_solver('auto', AUTO_LAPACK_MAX + 1, s, error)
    select type (s)
    type is (cholmod_solver_t)
       call check(.true., 'factory: auto large -> cholmod')
    class default
       call check(.false., 'factory: auto large -> cholmod')
    end select
    call new_solver(' UMFPACK ', 10_i8, s, error)
    select type (s)
    type is (umfpack_solver_t)
       call check(.true., 'factory: case-insensitive name')
    class default
       call check(.false., 'factory: case-insensitive name')
    end select
    call new_solver('pardiso', 10_i8, s, error)
    call check(allocated(error), 'factory: unknown name refused')
    if (allocated(error)) then
       call check(error%code == EXIT_USAGE, 'factory: unknown name -> EXIT_USAGE')
       call check(index(error%message, 'pardiso') > 0, 'factory: message names the solver')
    end if
    call check(.not. allocated(s), 'factory: no solver on error')
  end subroutine test_factory

  subroutine test_move_sparse()
    !! A matrix moved out is left empty (n = 0, no arrays): nothing that
    !! reads n afterwards (nnz, a product) meets arrays that are gone.
    type(sparse_sym_t) :: a, b
    a%n = 2
    a%colptr = [1_i8, 2_i8, 4_i8]
    a%rowind = [1_i8, 1_i8, 2_i8]
    a%val = [4.0_wp, 1.0_wp, 3.0_wp]
    call move_sparse(a, b)
    call check(b%n == 2 .and. b%nnz() == 3 .and. b%val(3) == 3.0_wp, 'move_sparse: the target holds the matrix')
    call check(a%n == 0 .and. a%nnz() == 0 .and. .not. allocated(a%val), 'move_sparse: the source is left empty')
  end subroutine test_move_sparse

  ! ------------------------------------------------------------------ RCM

  subroutine test_rcm()
    type(sparse_sym_t) :: a, b
    integer(i8), parameter :: M = 20
    integer(i8), allocatable :: p(:), perm(:), iperm(:)
    real(wp), allocatable :: ad(:, :), bd(:, :)
    integer(i8) :: i, j, n, bw
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    real(wp) :: u

    ! a 2D grid with a random numbering: RCM brings the band back to about M
    n = M*M
    allocate (ad(n, n), bd(n, n), p(n), perm(n), iperm(n))
    ad = 0.0_wp
    call dense_laplace2d(int(M), ad)
    p = [(i, i=1, n)]
    do i = n, 2, -1
       u = rand01()
       j = 1 + int(u*real(i, wp), i8)
       j = min(j, i)
       p([i, j]) = p([j, i])
    end do
    bd = ad(p, p)
    call from_dense(bd, b)
    call rcm_ordering(b, perm)
    call check(is_permutation(perm), 'rcm: permutation')
    do i = 1, n
       iperm(perm(i)) = i
    end do
    bw = 0
    do j = 1, n
       do i = 1, n
          if (bd(i, j) /= 0.0_wp) bw = max(bw, abs(iperm(i) - iperm(j)))
       end do
    end do
    write (*, '(a,i0,a,i0,a,i0)') '   rcm: bandwidth of a shuffled ', M, 'x', M, ' grid: ', bw
    call check(bw <= 2*M, 'rcm: bandwidth of a shuffled grid')
    call new_solver('lapack', n, s, error)
    call s%analyze(b, error)
    call check(s%info%ordering == 'RCM', 'lapack: banded storage uses RCM')
    select type (s)
    type is (lapack_solver_t)
       call check(s%bandwidth() == bw, 'lapack: bandwidth reported')
    end select
    call s%release()
    ! 1D chain: band 1
    call laplace1d(100_i8, a)
    call s%analyze(a, error)
    call check(s%info%name == 'LAPACK dpbtrf (band 1)', 'lapack: 1D chain is banded with band 1')
    ! dense-ish: dpotrf, natural
    call random_spd(40, 0.5_wp, a)
    call s%analyze(a, error)
    call check(s%info%name == 'LAPACK dpotrf' .and. s%info%ordering == 'natural', 'lapack: dense storage')
    ! disconnected graph (isolated nodes) is a permutation too
    call from_dense(reshape([2.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 4.0_wp], [3, 3]), a)
    deallocate (perm)
    allocate (perm(3))
    call rcm_ordering(a, perm)
    call check(is_permutation(perm), 'rcm: disconnected graph')
    call s%release()
  end subroutine test_rcm

  ! ------------------------------------------------------------------ Matrix Market

  subroutine test_matrix_market()
    type(sparse_sym_t) :: a, b
    type(error_t), allocatable :: error
    character(:), allocatable :: dir, path
    integer :: unit, ios, nlower, nentry
    integer(i8) :: row, col
    character(len=200) :: line
    logical :: exists

    dir = temp_dir()
    path = dir//'/superjoin_test_solvers.mtx'
    call random_spd(60, 0.1_wp, a)
    ! awkward values: thirds, extremes, subnormal, negative zero
    a%val(1) = 1.0_wp/3.0_wp
    a%val(2) = -1.0e-300_wp
    a%val(3) = 1.7976931348623157e308_wp
    a%val(4) = 4.9406564584124654e-324_wp
    a%val(5) = -0.0_wp
    a%val(7) = 0.1_wp + 0.2_wp
    call write_matrix_market(path, a, error)
    call check(.not. allocated(error), 'mm: write')
    inquire (file=path//'.tmp', exist=exists)
    call check(.not. exists, 'mm: no temporary left')
    call read_matrix_market(path, b, error)
    call check(.not. allocated(error), 'mm: read')
    if (allocated(error)) then
       write (*, '(a)') '   '//error%message
    else
       call check(b%n == a%n, 'mm: round trip n')
       call check(all(b%colptr == a%colptr), 'mm: round trip colptr')
       call check(all(b%rowind == a%rowind), 'mm: round trip rowind')
       call check(all(b%val == a%val), 'mm: round trip values exact')
       call check(all(sign(1.0_wp, b%val) == sign(1.0_wp, a%val)), 'mm: round trip signs')
    end if
    ! a "symmetric" Matrix Market file stores the lower triangle: row >= column
    ! on every entry line (the reader accepts either, so read the text)
    nlower = 0
    nentry = 0
    open (newunit=unit, file=path, status='old', action='read', iostat=ios)
    read (unit, '(a)', iostat=ios) line      ! banner
    read (unit, '(a)', iostat=ios) line      ! comment
    read (unit, '(a)', iostat=ios) line      ! sizes
    do
       read (unit, '(a)', iostat=ios) line
       if (ios /= 0) exit
       read (line, *, iostat=ios) row, col
       if (ios /= 0) cycle
       nentry = nentry + 1
       if (row >= col) nlower = nlower + 1
    end do
    close (unit)
    call check(nentry == a%nnz() .and. nlower == nentry, 'mm: every entry in the lower triangle')

    ! a hand-written file: comments, upper and lower entries, duplicates,
    ! a missing diagonal, integer field
    open (newunit=unit, file=path, status='replace', action='write', iostat=ios)
    write (unit, '(a)') '%%MatrixMarket matrix coordinate integer symmetric'
    write (unit, '(a)') '% a comment'
    write (unit, '(a)') ''
    write (unit, '(a)') '  3 3 5'
    write (unit, '(a)') '1 1 4'
    write (unit, '(a)') '2 1 -1'
    write (unit, '(a)') '1 2 -2'
    write (unit, '(a)') '3 3 7'
    write (unit, '(a)') '3 1 5'
    close (unit)
    call read_matrix_market(path, b, error)
    call check(.not. allocated(error), 'mm: read hand-written file')
    if (.not. allocated(error)) then
       call check(b%n == 3, 'mm: hand-written n')
       call check(all(b%colptr == [1_i8, 2_i8, 4_i8, 6_i8]), 'mm: hand-written colptr')
       call check(all(b%rowind == [1_i8, 1_i8, 2_i8, 1_i8, 3_i8]), 'mm: hand-written rowind')
       call check(all(b%val == [4.0_wp, -3.0_wp, 0.0_wp, 5.0_wp, 7.0_wp]), 'mm: hand-written values')
    end if

    ! errors
    open (newunit=unit, file=path, status='replace', action='write', iostat=ios)
    write (unit, '(a)') '%%MatrixMarket matrix coordinate real general'
    write (unit, '(a)') '2 2 1'
    write (unit, '(a)') '1 1 1.0'
    close (unit)
    call read_matrix_market(path, b, error)
    call check(allocated(error), 'mm: general matrix refused')
    open (newunit=unit, file=path, status='replace', action='write', iostat=ios)
    write (unit, '(a)') '%%MatrixMarket matrix coordinate real symmetric'
    write (unit, '(a)') '2 2 2'
    write (unit, '(a)') '1 1 1.0'
    write (unit, '(a)') '3 1 1.0'
    close (unit)
    call read_matrix_market(path, b, error)
    call check(allocated(error), 'mm: out-of-range entry refused')
    open (newunit=unit, file=path, status='replace', action='write', iostat=ios)
    write (unit, '(a)') '%%MatrixMarket matrix coordinate real symmetric'
    write (unit, '(a)') '2 2 2'
    write (unit, '(a)') '1 1 1.0'
    close (unit)
    call read_matrix_market(path, b, error)
    call check(allocated(error), 'mm: truncated file refused')
    open (newunit=unit, file=path, status='old', iostat=ios)
    close (unit, status='delete')

    call read_matrix_market(dir//'/no/such/file.mtx', b, error)
    call check(allocated(error), 'mm: missing file')
    if (allocated(error)) then
       call check(error%code == EXIT_IO, 'mm: missing file -> EXIT_IO')
       call check(index(error%message, 'no/such/file.mtx') > 0, 'mm: missing file message has the path')
    end if
    call write_matrix_market(dir//'/no/such/dir/out.mtx', a, error)
    call check(allocated(error), 'mm: unwritable path')
    if (allocated(error)) then
       call check(error%code == EXIT_IO, 'mm: unwritable path -> EXIT_IO')
       call check(index(error%message, 'no/such/dir/out.mtx') > 0, 'mm: unwritable path message has the path')
    end if
  end subroutine test_matrix_market

  ! ------------------------------------------------------------------ size

  subroutine test_large_cholmod()
    !! A 2D Laplacian of about 1e5 unknowns through CHOLMOD: ordering and time.
    type(sparse_sym_t) :: a
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    real(wp), allocatable :: xt(:, :), b(:, :), x(:, :), r(:, :)
    integer(i8) :: t0, t1, t2, t3, rate
    real(wp) :: cond

    call laplace2d(316_i8, a)
    call new_solver('cholmod', a%n, s, error)
    allocate (xt(a%n, 1), b(a%n, 1), x(a%n, 1), r(a%n, 1))
    xt = 1.0_wp
    call a%matvec(xt, b)
    call system_clock(t0, rate)
    call s%analyze(a, error)
    call system_clock(t1)
    call s%factorize(a, error)
    call system_clock(t2)
    call check(.not. allocated(error), 'cholmod: 2D Laplacian n=99856')
    if (allocated(error)) return
    call s%solve(b, x, error)
    call system_clock(t3)
    call a%matvec(x, r)
    call check(norm2(r - b) <= RES_TOL*norm2(b), 'cholmod: 2D Laplacian n=99856 residual')
    call check(s%info%ordering == 'AMD' .or. s%info%ordering == 'METIS', 'cholmod: ordering AMD or METIS')
    write (*, '(a,i0,4a)') '   cholmod 2D Laplacian n=', a%n, ': ordering ', s%info%ordering, ', ', s%info%name
    write (*, '(a,3(f8.3,a))') '   analyze ', real(t1 - t0, wp)/real(rate, wp), ' s, factorize ', &
         real(t2 - t1, wp)/real(rate, wp), ' s, solve ', real(t3 - t2, wp)/real(rate, wp), ' s'
    select type (s)
    type is (cholmod_solver_t)
       write (*, '(a,i0,a,i0,a,f8.2,a,es10.3,a,f8.2,a)') '   nnz(L) ', s%info%factor_nnz, ' (stored ', &
            s%stored_nnz(), '), L ', s%info%factor_mbytes, ' MiB, flops ', s%flops(), ', CHOLMOD peak ', s%peak_mbytes(), ' MiB'
    end select
    call system_clock(t0)
    call condition_estimate(a, s, cond)
    call system_clock(t1)
    write (*, '(a,es10.3,a,f8.3,a)') '   condition estimate ', cond, ' (', real(t1 - t0, wp)/real(rate, wp), ' s)'
    call s%release()
  end subroutine test_large_cholmod

  ! ------------------------------------------------------------------ helpers

  subroutine factor(name, a, s, error)
    !! Factor a with backend name (asserting success).
    character(*), intent(in) :: name
    type(sparse_sym_t), intent(in) :: a
    class(linear_solver_t), allocatable, intent(out) :: s
    type(error_t), allocatable, intent(out) :: error
    call new_solver(name, a%n, s, error)
    if (allocated(error)) return
    call s%analyze(a, error)
    if (allocated(error)) return
    call s%factorize(a, error)
    call check(.not. allocated(error), name//': factor helper')
  end subroutine factor

  subroutine laplace1d(n, a)
    !! 1D Laplacian (2 on the diagonal, -1 off) of order n.
    integer(i8), intent(in) :: n
    type(sparse_sym_t), intent(out) :: a
    integer(i8) :: j, k
    a%n = n
    allocate (a%colptr(n + 1), a%rowind(2*n - 1), a%val(2*n - 1))
    k = 0
    a%colptr(1) = 1
    do j = 1, n
       if (j > 1) then
          k = k + 1
          a%rowind(k) = j - 1
          a%val(k) = -1.0_wp
       end if
       k = k + 1
       a%rowind(k) = j
       a%val(k) = 2.0_wp
       a%colptr(j + 1) = k + 1
    end do
  end subroutine laplace1d

  subroutine laplace2d(m, a)
    !! 2D 5-point Laplacian on an m x m grid (Dirichlet boundary).
    integer(i8), intent(in) :: m
    type(sparse_sym_t), intent(out) :: a
    call grid_laplacian(m, 2, a)
  end subroutine laplace2d

  subroutine laplace3d(m, a)
    !! 3D 7-point Laplacian on an m x m x m grid (Dirichlet boundary).
    integer(i8), intent(in) :: m
    type(sparse_sym_t), intent(out) :: a
    call grid_laplacian(m, 3, a)
  end subroutine laplace3d

  subroutine expand_two_dofs(l, a)
    !! Two unknowns per node: every entry of l becomes a 2x2 SPD block (upper triangle).
    type(sparse_sym_t), intent(in) :: l
    type(sparse_sym_t), intent(out) :: a
    call expand_dofs(l, 2, a)
  end subroutine expand_two_dofs

  subroutine expand_dofs(l, k, a)
    !! k unknowns per node: every entry of l becomes a k x k SPD block (2 on
    !! its diagonal, 1 elsewhere: eigenvalues 1 and k + 1; upper triangle).
    type(sparse_sym_t), intent(in) :: l
    integer, intent(in) :: k
    type(sparse_sym_t), intent(out) :: a
    integer(i8) :: jn, pos, in, nz, c
    integer :: ca, ra
    a%n = k*l%n
    allocate (a%colptr(a%n + 1), a%rowind(k*k*l%nnz()), a%val(k*k*l%nnz()))
    nz = 0
    a%colptr(1) = 1
    do jn = 1, l%n
       do ca = 1, k
          c = k*(jn - 1) + ca
          do pos = l%colptr(jn), l%colptr(jn + 1) - 1
             in = l%rowind(pos)
             do ra = 1, k
                if (in == jn .and. ra > ca) cycle
                nz = nz + 1
                a%rowind(nz) = k*(in - 1) + ra
                a%val(nz) = merge(2.0_wp, 1.0_wp, ra == ca)*l%val(pos)
             end do
          end do
          a%colptr(c + 1) = nz + 1
       end do
    end do
    a%rowind = a%rowind(1:nz)
    a%val = a%val(1:nz)
  end subroutine expand_dofs

  function node_groups(nnode, k) result(first)
    !! First column of each of nnode groups of k consecutive columns, and n + 1.
    integer(i8), intent(in) :: nnode
    integer, intent(in) :: k
    integer(i8), allocatable :: first(:)
    integer(i8) :: g
    first = [(k*(g - 1) + 1, g=1, nnode + 1)]
  end function node_groups

  subroutine dense_laplace2d(m, ad)
    !! Dense 2D Laplacian of an m x m grid into ad(m*m, m*m).
    integer, intent(in) :: m
    real(wp), intent(inout) :: ad(:, :)
    type(sparse_sym_t) :: a
    call laplace2d(int(m, i8), a)
    call to_dense(a, ad)
  end subroutine dense_laplace2d

  subroutine random_spd(n, density, a)
    !! Random sparse SPD matrix: random symmetric couplings in (-1, 1) with the
    !! given density, diagonal = 1 + sum of |couplings| (diagonally dominant).
    integer, intent(in) :: n
    real(wp), intent(in) :: density
    type(sparse_sym_t), intent(out) :: a
    real(wp), allocatable :: ad(:, :)
    integer :: i, j
    allocate (ad(n, n))
    ad = 0.0_wp
    do j = 2, n
       do i = 1, j - 1
          if (rand01() < density) then
             ad(i, j) = 2.0_wp*rand01() - 1.0_wp
             ad(j, i) = ad(i, j)
          end if
       end do
    end do
    do i = 1, n
       ad(i, i) = 1.0_wp + sum(abs(ad(:, i))) + rand01()
    end do
    call from_dense(ad, a)
  end subroutine random_spd

  subroutine from_dense(ad, a)
    !! Upper-triangle CSC of a dense symmetric matrix (zeros dropped except the diagonal).
    real(wp), intent(in) :: ad(:, :)
    type(sparse_sym_t), intent(out) :: a
    integer(i8) :: n, i, j, k
    n = size(ad, 1, i8)
    a%n = n
    k = 0
    do j = 1, n
       do i = 1, j
          if (ad(i, j) /= 0.0_wp .or. i == j) k = k + 1
       end do
    end do
    allocate (a%colptr(n + 1), a%rowind(k), a%val(k))
    k = 0
    a%colptr(1) = 1
    do j = 1, n
       do i = 1, j
          if (ad(i, j) /= 0.0_wp .or. i == j) then
             k = k + 1
             a%rowind(k) = i
             a%val(k) = ad(i, j)
          end if
       end do
       a%colptr(j + 1) = k + 1
    end do
  end subroutine from_dense

  subroutine to_dense(a, ad)
    !! Dense copy of the symmetric matrix a.
    type(sparse_sym_t), intent(in) :: a
    real(wp), intent(out) :: ad(:, :)
    integer(i8) :: j, k
    ad = 0.0_wp
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          ad(a%rowind(k), j) = a%val(k)
          ad(j, a%rowind(k)) = a%val(k)
       end do
    end do
  end subroutine to_dense

  function diag_of(a) result(d)
    type(sparse_sym_t), intent(in) :: a
    real(wp), allocatable :: d(:)
    allocate (d(a%n))
    call a%diagonal(d)
  end function diag_of

  logical function is_permutation(p)
    integer(i8), intent(in) :: p(:)
    logical, allocatable :: seen(:)
    integer(i8) :: i
    allocate (seen(size(p)))
    seen = .false.
    is_permutation = .false.
    do i = 1, size(p, kind=i8)
       if (p(i) < 1 .or. p(i) > size(p, kind=i8)) return
       if (seen(p(i))) return
       seen(p(i)) = .true.
    end do
    is_permutation = .true.
  end function is_permutation

  real(wp) function rand01()
    !! Deterministic uniform numbers in (0, 1) (Park-Miller minimal standard).
    integer(i8), parameter :: MULT = 48271_i8, MODULUS = 2147483647_i8
    rng_state = mod(rng_state*MULT, MODULUS)
    rand01 = real(rng_state, wp)/real(MODULUS, wp)
  end function rand01

  subroutine test_node_graph_ordering()
    !! Two unknowns per node (a 2D Laplacian times a 2x2 SPD block): the node
    !! graph has the Laplacian's adjacency, and CHOLMOD ordering it (METIS on
    !! the nodes against its own AMD) still solves to round-off.
    integer(i8), parameter :: M = 40
    type(sparse_sym_t) :: l, a
    type(cholmod_solver_t) :: s
    type(error_t), allocatable :: error
    integer(i8), allocatable :: first(:), xadj(:), adjncy(:)
    real(wp), allocatable :: x(:, :), b(:, :), r(:, :)
    integer(i8) :: g, deg

    call laplace2d(M, l)
    call expand_two_dofs(l, a)
    allocate (first(l%n + 1))
    do g = 1, l%n + 1
       first(g) = 2*g - 1
    end do

    call node_graph(a, first, xadj, adjncy)
    call check(size(xadj, kind=i8) == l%n + 1, 'node graph: one vertex per node')
    ! Interior node of the grid: 4 neighbours; corner: 2.
    deg = xadj(M + 2) - xadj(M + 1)
    call check(xadj(2) - xadj(1) == 2, 'node graph: corner has 2 neighbours')
    call check(deg == 3, 'node graph: edge node has 3 neighbours')
    call check(xadj(M*M + 1) - 1 == 2*(2*M*(M - 1)), 'node graph: edge count')
    call check(all(adjncy >= 1 .and. adjncy <= l%n), 'node graph: neighbours in range')

    s%node_graph_min = 0
    s%node_amd_min = 0        ! two columns per node: below the node-AMD group size, column AMD
    call s%set_groups(first)
    call s%analyze(a, error)
    call check(.not. allocated(error), 'node-graph ordering: analyze')
    if (allocated(error)) return
    call check(s%info%ordering == 'AMD' .or. s%info%ordering == 'METIS (node graph)', &
         'node-graph ordering: ordering is AMD or METIS (node graph), got '//s%info%ordering)
    call s%factorize(a, error)
    call check(.not. allocated(error), 'node-graph ordering: factorize')
    if (allocated(error)) return
    allocate (x(a%n, 1), b(a%n, 1), r(a%n, 1))
    b = 1.0_wp
    call s%solve(b, x, error)
    call a%matvec(x, r)
    call check(norm2(r - b)/norm2(b) < RES_TOL, 'node-graph ordering: residual at round-off')
    call s%release()

    ! A 3D grid (two unknowns per node), where nested dissection beats AMD:
    ! with the node-graph candidate forced, CHOLMOD keeps it, and the solve
    ! through that permutation is at round-off.
    block
      type(cholmod_solver_t) :: sm
      type(sparse_sym_t) :: l3, a3
      integer(i8), parameter :: M3 = 14
      real(wp), allocatable :: x3(:, :), b3(:, :), r3(:, :)
      call laplace3d(M3, l3)
      call expand_two_dofs(l3, a3)
      deallocate (first)
      allocate (first(l3%n + 1))
      do g = 1, l3%n + 1
         first(g) = 2*g - 1
      end do
      sm%node_graph_min = 0
      sm%force_node_metis = .true.
      call sm%set_groups(first)
      call sm%analyze(a3, error)
      call check(.not. allocated(error), 'forced node-graph METIS: analyze')
      if (allocated(error)) return
      call check(sm%info%ordering == 'METIS (node graph)', &
           'forced node-graph METIS: kept on a 3D grid, got '//sm%info%ordering)
      call sm%factorize(a3, error)
      call check(.not. allocated(error), 'forced node-graph METIS: factorize')
      if (allocated(error)) return
      allocate (x3(a3%n, 1), b3(a3%n, 1), r3(a3%n, 1))
      b3 = 1.0_wp
      call sm%solve(b3, x3, error)
      call a3%matvec(x3, r3)
      call check(norm2(r3 - b3)/norm2(b3) < RES_TOL, 'forced node-graph METIS: residual at round-off')
      call sm%release()
    end block
  end subroutine test_node_graph_ordering

  subroutine test_node_metis_only()
    !! A chain of nodes (two unknowns each), where AMD has no fill and CHOLMOD's
    !! own test keeps it: node_metis_only (the level solver's top system) takes
    !! the node graph's METIS permutation without AMD's candidate, and the
    !! solve through it is at round-off.
    integer(i8), parameter :: M = 60
    type(sparse_sym_t) :: l, a
    type(cholmod_solver_t) :: s
    type(error_t), allocatable :: error
    integer(i8), allocatable :: first(:)
    real(wp), allocatable :: x(:, :), b(:, :), r(:, :)
    integer(i8) :: g
    logical :: only
    call grid_laplacian(M, 1, l)
    call expand_two_dofs(l, a)
    first = [(2*g - 1, g=1, l%n + 1)]
    allocate (x(a%n, 1), b(a%n, 1), r(a%n, 1))
    b = 1.0_wp
    do g = 1, 2
       only = g == 2
       s%node_graph_min = 0
       s%node_metis_only = only
       call s%set_groups(first)
       call s%analyze(a, error)
       call check(.not. allocated(error), 'node METIS only: analyze')
       if (allocated(error)) return
       call check(s%info%ordering == merge('METIS (node graph)', 'AMD               ', only), &
            'node METIS only ('//merge('yes', 'no ', only)//'): ordering, got '//s%info%ordering)
       call s%factorize(a, error)
       call check(.not. allocated(error), 'node METIS only: factorize')
       if (allocated(error)) return
       call s%solve(b, x, error)
       call a%matvec(x, r)
       call check(norm2(r - b)/norm2(b) < RES_TOL, 'node METIS only: residual at round-off')
       call s%release()
    end do
  end subroutine test_node_metis_only
  subroutine test_node_amd_ordering()
    !! Six unknowns per node (a 2D Laplacian times a 6x6 SPD block): AMD on the
    !! node graph (node_amd_min = 0) in place of AMD on the columns, its fill
    !! within 5 % of column AMD's, the solve at round-off; on a 3D grid with the
    !! node-graph METIS forced, METIS is compared with node AMD and kept.
    integer(i8), parameter :: M = 30, M3 = 10
    integer, parameter :: K = 6
    type(sparse_sym_t) :: l, a
    type(cholmod_solver_t) :: s, sc, sm
    type(error_t), allocatable :: error
    real(wp), allocatable :: x(:, :), b(:, :), r(:, :)

    call laplace2d(M, l)
    call expand_dofs(l, K, a)
    sc%node_graph_min = 0
    sc%node_amd_min = -1
    call sc%set_groups(node_groups(l%n, K))
    call sc%analyze(a, error)
    call check(.not. allocated(error), 'node AMD: column AMD analyze')
    if (allocated(error)) return
    call check(sc%info%ordering == 'AMD', 'node AMD: node_amd_min < 0 orders the columns, got '//sc%info%ordering)
    s%node_graph_min = 0
    s%node_amd_min = 0
    call s%set_groups(node_groups(l%n, K))
    call s%analyze(a, error)
    call check(.not. allocated(error), 'node AMD: analyze')
    if (allocated(error)) return
    call check(s%info%ordering == 'AMD (node graph)', 'node AMD: ordering, got '//s%info%ordering)
    call check(s%info%factor_nnz <= (105*sc%info%factor_nnz)/100, 'node AMD: fill within 5 % of column AMD''s')
    call s%factorize(a, error)
    call check(.not. allocated(error), 'node AMD: factorize')
    if (allocated(error)) return
    allocate (x(a%n, 1), b(a%n, 1), r(a%n, 1))
    b = 1.0_wp
    call s%solve(b, x, error)
    call a%matvec(x, r)
    call check(norm2(r - b)/norm2(b) < RES_TOL, 'node AMD: residual at round-off')
    call s%release()
    call sc%release()

    call laplace3d(M3, l)
    call expand_dofs(l, K, a)
    sm%node_graph_min = 0
    sm%node_amd_min = 0
    sm%force_node_metis = .true.
    call sm%set_groups(node_groups(l%n, K))
    call sm%analyze(a, error)
    call check(.not. allocated(error), 'node AMD, forced METIS: analyze')
    if (allocated(error)) return
    call check(sm%info%ordering == 'METIS (node graph)', &
         'node AMD, forced METIS: kept on a 3D grid, got '//sm%info%ordering)
    call sm%release()
  end subroutine test_node_amd_ordering
end program test_solvers
