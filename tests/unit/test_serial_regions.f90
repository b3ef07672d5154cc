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
  use test_matrices, only: grid_laplacian
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
     function omp_get_max_threads() bind(c, name='omp_get_max_threads') result(n)
       import :: c_int
       integer(c_int) :: n
     end function omp_get_max_threads
     function sj_serial_regions_count() bind(c, name='sj_serial_regions_count') result(n)
       import :: c_int64_t
       integer(c_int64_t) :: n
     end function sj_serial_regions_count
  end interface

  call test_region(1_c_int, 1, 'one thread')
  call test_region(2_c_int, 0, 'two threads (libgomp)')
  call test_nested()
  call test_default_count()
  call test_cholmod()
  call finish()

contains

  subroutine test_region(nthreads, counted, what)
    !! A region of nthreads threads: nthreads bodies, one on the opening
    !! thread; counted (run without a team) or not.
    integer(c_int), intent(in) :: nthreads
    integer, intent(in) :: counted
    character(*), intent(in) :: what
    integer(c_int) :: runs, on_opener
    integer(c_int64_t) :: before
    before = sj_serial_regions_count()
    call sj_probe_region(nthreads, runs, on_opener)
    call check(runs == nthreads .and. on_opener == 1, what//': the body ran on each thread, one of them the opening one')
    call check(sj_serial_regions_count() == before + counted, what//': run without a team only with one thread')
  end subroutine test_region

  subroutine test_default_count()
    !! A region with no thread count (num_threads 0: CHOLMOD's regions without
    !! an if or num_threads clause) where the default is one thread
    !! (OMP_NUM_THREADS=1, unit.test_serial_regions_one_thread): run without a
    !! team, counted; elsewhere libgomp's, not counted.
    integer(c_int) :: runs, on_opener
    integer(c_int64_t) :: before
    integer :: counted
    counted = merge(1, 0, omp_get_max_threads() == 1)
    before = sj_serial_regions_count()
    call sj_probe_region(0_c_int, runs, on_opener)
    call check(runs == omp_get_max_threads() .and. on_opener == 1, 'no thread count: the default count of bodies')
    call check(sj_serial_regions_count() == before + counted, 'no thread count: run without a team exactly '// &
         'where the default is one thread')
  end subroutine test_default_count

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
    call grid_laplacian(M, 2, a)
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
end program test_serial_regions
