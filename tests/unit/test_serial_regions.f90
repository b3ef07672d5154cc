program test_serial_regions
  !! OpenMP regions that ask for one thread run on the calling thread without
  !! a team (src/solvers/serial_regions.c defines GCC's GOMP_parallel):
  !! - a region of one thread runs its body once, on the thread that opened
  !!   it, and is counted;
  !! - a region of two threads goes to libgomp: two bodies, one of them on the
  !!   opening thread, not counted;
  !! - a region of one thread opened by each thread of a two-thread team gets
  !!   a team of its own: its body sees one thread, itself thread 0;
  !! - CHOLMOD's supernodal factorization, a shared library's code, comes
  !!   through the program's definition: its serial regions are counted, and
  !!   the solution is right.
  use, intrinsic :: iso_c_binding, only: c_int, c_int64_t
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  interface
     subroutine sj_probe_region(num_threads, runs, on_opener) bind(c, name='sj_probe_region')
       import :: c_int
       integer(c_int), value :: num_threads
       integer(c_int), intent(out) :: runs, on_opener
     end subroutine sj_probe_region
     subroutine sj_probe_nested(runs, alone) bind(c, name='sj_probe_nested')
       import :: c_int
       integer(c_int), intent(out) :: runs, alone
     end subroutine sj_probe_nested
     function sj_serial_regions_count() bind(c, name='sj_serial_regions_count') result(n)
       import :: c_int64_t
       integer(c_int64_t) :: n
     end function sj_serial_regions_count
  end interface

  call test_one_thread()
  call test_two_threads()
  call test_nested()
  call test_cholmod()
  call finish()

contains

  subroutine test_one_thread()
    integer(c_int) :: runs, on_opener
    integer(c_int64_t) :: before
    before = sj_serial_regions_count()
    call sj_probe_region(1_c_int, runs, on_opener)
    call check(runs == 1 .and. on_opener == 1, 'one thread: the body ran once, on the opening thread')
    call check(sj_serial_regions_count() == before + 1, 'one thread: the region ran without a team (counted)')
  end subroutine test_one_thread

  subroutine test_two_threads()
    integer(c_int) :: runs, on_opener
    integer(c_int64_t) :: before
    before = sj_serial_regions_count()
    call sj_probe_region(2_c_int, runs, on_opener)
    call check(runs == 2 .and. on_opener == 1, 'two threads: libgomp ran two bodies, one on the opening thread')
    call check(sj_serial_regions_count() == before, 'two threads: not run without a team')
  end subroutine test_two_threads

  subroutine test_nested()
    integer(c_int) :: runs, alone
    call sj_probe_nested(runs, alone)
    call check(runs == 2, 'nested: the outer region ran on two threads')
    call check(alone == 2, 'nested: each inner one-thread region saw a team of one, itself thread 0')
  end subroutine test_nested

  subroutine test_cholmod()
    !! A 2D Laplacian of 3 600 unknowns, CHOLMOD supernodal LL^T: every
    !! supernode opens regions whose if clause is false for a small one.
    integer(i8), parameter :: M = 60
    type(sparse_sym_t) :: a
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    real(wp), allocatable :: xt(:, :), b(:, :), x(:, :)
    integer(c_int64_t) :: before
    integer :: j
    call laplacian(M, a)
    allocate (xt(a%n, 1), b(a%n, 1), x(a%n, 1))
    xt(:, 1) = [(real(mod(7*j + 3, 11), wp) - 5.0_wp, j = 1, int(a%n))]
    call a%matvec(xt, b)
    call new_solver('cholmod', a%n, s, error)
    before = sj_serial_regions_count()
    if (.not. allocated(error)) call s%analyze(a, error)
    if (.not. allocated(error)) call s%factorize(a, error)
    if (.not. allocated(error)) call s%solve(b, x, error)
    call check(.not. allocated(error), 'cholmod: factorized and solved')
    if (allocated(error)) return
    call check(sj_serial_regions_count() > before, 'cholmod: its one-thread regions came through the program''s GOMP_parallel')
    call check(maxval(abs(x - xt)) <= 1.0e-10_wp*maxval(abs(xt)), 'cholmod: the solution')
    call s%release()
  end subroutine test_cholmod

  subroutine laplacian(m, a)
    !! 5-point Laplacian on an m x m grid, upper triangle, rows sorted.
    integer(i8), intent(in) :: m
    type(sparse_sym_t), intent(out) :: a
    integer(i8) :: j, k, n
    n = m*m
    a%n = n
    allocate (a%colptr(n + 1), a%rowind(3*n), a%val(3*n))
    k = 0
    a%colptr(1) = 1
    do j = 1, n
       if (j > m) then
          k = k + 1
          a%rowind(k) = j - m
          a%val(k) = -1.0_wp
       end if
       if (mod(j - 1, m) > 0) then
          k = k + 1
          a%rowind(k) = j - 1
          a%val(k) = -1.0_wp
       end if
       k = k + 1
       a%rowind(k) = j
       a%val(k) = 4.0_wp
       a%colptr(j + 1) = k + 1
    end do
    a%rowind = a%rowind(1:k)
    a%val = a%val(1:k)
  end subroutine laplacian
end program test_serial_regions
