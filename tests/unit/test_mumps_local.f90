program test_mumps_local
  !! MUMPS with local_input (src/solvers/mumps.f90): each process hands MUMPS
  !! all the entries of its own term of a matrix, the matrix factored being
  !! the sum over the processes (MUMPS sums duplicates). The terms split a 2D
  !! Laplacian: each off-diagonal entry held by one process only (so the
  !! patterns differ), every diagonal entry by all (unequal shares). Checked
  !! against CHOLMOD on the whole matrix: solution, pivots (1/(A^-1)_jj), a
  !! null pivot at its column; and each process hands MUMPS its own entries
  !! only. Run on one process (ctest unit.*) and under mpirun -np 2 (label
  !! mpi). Skipped (status 77) in a build without MUMPS.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, EXIT_SINGULAR
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, mumps_available, norm1_sym
  use superjoin_solvers_mumps, only: mumps_solver_t
  use superjoin_parallel_comm, only: comm_t, comm_world
  use superjoin_parallel_stats, only: mumps_stats_t, mumps_stats
  use superjoin_testing, only: check, finish
  use superjoin_analysis_summed_matrix, only: summed_norm1, summed_matvec, summed_diagonal, summed_groups
  implicit none (type, external)

  integer, parameter :: SKIP = 77
  integer(i8), parameter :: GRID = 12          !! 2D Laplacian GRID x GRID
  integer(i8), parameter :: KBAD = 29          !! the column made singular
  integer, parameter :: NRHS = 3
  real(wp), parameter :: TOL = 1.0e-10_wp      !! against CHOLMOD, relative
  real(wp), parameter :: RES_TOL = 1.0e-13_wp  !! relative residual of a direct solve
  real(wp), parameter :: NORM_TOL = 1.0e-14_wp  !! MUMPS's norm of the summed terms against norm1_sym
  real(wp), parameter :: SHARE = -0.25_wp      !! diagonal share of every process but 0 (negative:
    !! the sum of the terms' absolute values is not the norm of their sum)
  type(comm_t) :: comm

  if (.not. mumps_available()) then
     write (*, '(a)') 'test_mumps_local: built without MUMPS, skipped'
     stop SKIP
  end if
  comm = comm_world()
  call test_solution()
  call test_null_pivot()
  call finish()

contains

  subroutine test_solution()
    !! Solution and pivots of the summed terms equal CHOLMOD's of the whole matrix.
    type(sparse_sym_t) :: a, t
    type(mumps_solver_t) :: s
    class(linear_solver_t), allocatable :: c
    type(error_t), allocatable :: error
    real(wp), allocatable :: b(:, :), x(:, :), xc(:, :), r(:, :), d(:), e(:, :), y(:, :), dg(:)
    integer(i8) :: i, j
    type(mumps_stats_t) :: ms
    integer :: k
    real(wp) :: worst, anorm
    call laplace2d(GRID, a)
    call term(a, t)
    allocate (b(a%n, NRHS), x(a%n, NRHS), xc(a%n, NRHS), r(a%n, NRHS), d(a%n))
    do k = 1, NRHS
       do i = 1, a%n
          b(i, k) = real(mod(7*i + k, 11_i8) - 5, wp)
       end do
    end do
    s%local_input = .true.
    call s%analyze(t, error)
    if (.not. allocated(error)) call s%factorize(t, error)
    if (.not. allocated(error)) call s%solve(b, x, error)
    call check(.not. allocated(error), 'local input: analyze, factorize, solve')
    if (allocated(error)) then
       write (*, '(a)') '   '//error%message
       return
    end if
    call s%pivots(d)
    call s%input_norm(anorm, error)
    call check(.not. allocated(error), 'local input: MUMPS''s norm of the summed matrix (RINFOG(4))')
    ! RINFOG(4) adds the absolute values of duplicate entries: the norm on one
    ! process, an upper bound of it when the terms overlap with opposite signs
    call check(anorm >= (1.0_wp - NORM_TOL)*norm1_sym(a), 'local input: RINFOG(4) bounds the 1-norm of the sum')
    if (comm%size == 1) call check(abs(anorm - norm1_sym(a)) <= NORM_TOL*norm1_sym(a), &
         'local input: RINFOG(4) equals the 1-norm on one process')
    call summed_norm1(t, anorm, error)
    call check(.not. allocated(error) .and. abs(anorm - norm1_sym(a)) <= NORM_TOL*norm1_sym(a), &
         'summed_norm1 of the terms equals the 1-norm of the whole matrix')
    call summed_matvec(t, b, r, error)
    call a%matvec(b, xc)
    call check(.not. allocated(error) .and. maxval(abs(r - xc)) <= NORM_TOL*maxval(abs(xc)), &
         'summed_matvec of the terms equals the whole matrix''s product')
    allocate (dg(a%n))
    call summed_diagonal(t, dg, error)
    call a%diagonal(r(:, 1))
    call check(.not. allocated(error) .and. maxval(abs(dg - r(:, 1))) <= NORM_TOL*maxval(abs(r(:, 1))), &
         'summed_diagonal of the terms equals the whole matrix''s diagonal')
    call test_groups(a, t)
    call s%release()
    ms = mumps_stats()
    if (comm%size > 1) call check(ms%entries == t%nnz(), &
         'local input: each process hands MUMPS its own entries only')
    call new_solver('cholmod', a%n, c, error)
    call c%analyze(a, error)
    call c%factorize(a, error)
    call c%solve(b, xc, error)
    call check(.not. allocated(error), 'cholmod on the whole matrix')
    call check(maxval(abs(x - xc)) <= TOL*maxval(abs(xc)), 'local input: solution equals CHOLMOD''s')
    call a%matvec(x, r)
    call check(norm2(r - b) <= RES_TOL*norm2(b), 'local input: residual of the whole matrix')
    allocate (e(a%n, a%n), source=0.0_wp)
    do j = 1, a%n
       e(j, j) = 1.0_wp
    end do
    allocate (y(a%n, a%n))
    call c%solve(e, y, error)
    worst = 0.0_wp
    do j = 1, a%n
       worst = max(worst, abs(d(j)*y(j, j) - 1.0_wp))
    end do
    call check(worst <= TOL, 'local input: pivots are 1/(A^-1)_jj of the sum')
    call c%release()
  end subroutine test_solution

  subroutine test_null_pivot()
    !! A zero row and column of the sum: EXIT_SINGULAR at that column.
    type(sparse_sym_t) :: a, t
    type(mumps_solver_t) :: s
    type(error_t), allocatable :: error
    integer(i8) :: j, k
    call laplace2d(GRID, a)
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          if (j == KBAD .or. a%rowind(k) == KBAD) a%val(k) = 0.0_wp
       end do
    end do
    call term(a, t)
    s%local_input = .true.
    call s%analyze(t, error)
    call check(.not. allocated(error), 'local input: analyze of the singular sum')
    call s%factorize(t, error)
    call check(allocated(error), 'local input: null pivot detected')
    if (allocated(error)) then
       call check(error%code == EXIT_SINGULAR, 'local input: null pivot -> EXIT_SINGULAR')
       call check(s%info%failed_column == KBAD, 'local input: null pivot at the zero column')
       if (s%info%failed_column /= KBAD) write (*, '(a,i0,1x,a)') '   got column ', s%info%failed_column, error%message
    end if
    call s%release()
  end subroutine test_null_pivot

  subroutine term(a, t)
    !! This process's term of a: the off-diagonal entries (i, j) with
    !! mod(i + j, size) = rank, and a share of every diagonal entry (SHARE on
    !! processes 1.., the rest on process 0), so that the terms sum to a.
    type(sparse_sym_t), intent(in) :: a
    type(sparse_sym_t), intent(out) :: t
    integer(i8) :: j, k, m, i
    t%n = a%n
    allocate (t%colptr(a%n + 1), t%rowind(a%nnz()), t%val(a%nnz()))
    m = 0
    t%colptr(1) = 1
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          i = a%rowind(k)
          if (i == j) then
             m = m + 1
             t%rowind(m) = i
             if (comm%rank == 0) then
                t%val(m) = a%val(k) - SHARE*(comm%size - 1)
             else
                t%val(m) = SHARE
             end if
          else if (mod(i + j, int(comm%size, i8)) == comm%rank) then
             m = m + 1
             t%rowind(m) = i
             t%val(m) = a%val(k)
          end if
       end do
       t%colptr(j + 1) = m + 1
    end do
    t%rowind = t%rowind(1:m)
    t%val = t%val(1:m)
  end subroutine term

  subroutine test_groups(a, t)
    !! summed_groups: the Laplacian is connected; with the entries of one grid
    !! column pair removed from every term it falls in two groups.
    type(sparse_sym_t), intent(in) :: a, t
    type(sparse_sym_t) :: tc
    integer(i8), allocatable :: root(:)
    type(error_t), allocatable :: error
    integer(i8) :: j, pos, cut
    allocate (root(a%n))
    call summed_groups(t, root, error)
    call check(.not. allocated(error) .and. all(root == 1), 'summed_groups: the Laplacian is one group')
    ! unknowns 1..cut (grid columns 1..GRID/2) cut off from the rest
    cut = GRID*(GRID/2)
    tc = t
    do j = 1, tc%n
       do pos = tc%colptr(j), tc%colptr(j + 1) - 1
          if ((tc%rowind(pos) <= cut) .neqv. (j <= cut)) tc%val(pos) = 0.0_wp
       end do
    end do
    call summed_groups(tc, root, error)
    call check(.not. allocated(error) .and. all(root(1:cut) == 1) .and. all(root(cut + 1:) == cut + 1), &
         'summed_groups: two groups once the coupling is cut')
  end subroutine test_groups

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
    a%rowind = a%rowind(1:k)
    a%val = a%val(1:k)
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
end program test_mumps_local
