module superjoin_solvers_mumps
  !! Sparse multifrontal LDL^T (MUMPS) behind the linear_solver_t interface,
  !! sequential or over MPI.
  !!
  !! Binding: MUMPS's C interface (dmumps_c) through the C shim
  !! src/solvers/mumps_shim.c, which owns the DMUMPS_STRUC_C and is reached
  !! with bind(c); a build without MUMPS links src/solvers/mumps_stub.c
  !! instead, where creating the solver fails with a message naming the cmake
  !! option. Every procedure is collective over the processes of the run
  !! (superjoin_parallel_comm): all call it in the same order with the same
  !! matrix. Each process contributes the entries of its share of the columns
  !! (contiguous blocks, nodes kept whole, balanced by entries) as MUMPS's
  !! distributed assembled input (ICNTL(18) = 3), or, with local_input, all the
  !! entries of its own term of a matrix that is the sum over the processes
  !! (MUMPS sums duplicates: nobody assembles the whole); right-hand sides and
  !! solutions are centralized on rank 0 and the solution is broadcast, so that
  !! every process continues with the same numbers.
  !!
  !! Matrix type: SYM = 1 (symmetric positive definite, no pivoting) by
  !! default, as CHOLMOD; SYM = 2 (general symmetric, pivoting) for
  !! `--solver mumps-ldlt`. A breakdown is reported as the other backends do
  !! (EXIT_SINGULAR and info%failed_column): MUMPS's null pivot detection
  !! (ICNTL(24) = 1, threshold CNTL(3) = NULL_PIVOT_RELATIVE of the norm of the
  !! scaled matrix) gives the first null pivot's column; with SYM = 1 a
  !! negative pivot (INFOG(12) > 0) means not positive definite. MUMPS does not
  !! give its pivots to the caller: pivots() returns 1/(A^-1)_jj instead (see
  !! there), which makes the health block's MAXRATIO an ordering-independent
  !! upper bound of the usual one.
  !!
  !! Static condensation (schur): one analysis and factorization of the whole
  !! part with MUMPS's Schur complement option, ICNTL(19) = 1 (see
  !! mumps_schur). An instance with `alone` lives on MPI_COMM_SELF: a part
  !! condensed by the one process that owns it, nothing collective.
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, c_int64_t, c_double
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR, EXIT_IO, EXIT_USAGE
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_solver, only: linear_solver_t
  use superjoin_parallel_comm, only: comm_t, comm_world, agree, broadcast, sum_counts, max_reals, fortran_handle, &
       note_agreed_failure, fortran_self_handle
  use superjoin_utils_memory, only: oom_message
  use superjoin_parallel_stats, only: record_mumps_input, record_mumps_memory, record_host_ordering, &
       record_mumps_factor, mumps_order_stats_t
  use superjoin_solvers_mumps_order, only: ordering_choice, host_nested_dissection, ORDER_PTSCOTCH, ORDER_METIS, &
       ORDERING_NO_MEMORY, ORDER_AMD
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  integer, parameter, public :: MUMPS_SPD = 1         !! SYM = 1: symmetric positive definite
  integer, parameter, public :: MUMPS_SYMMETRIC = 2   !! SYM = 2: general symmetric (pivoting)
  real(wp), parameter, public :: NULL_PIVOT_RELATIVE = 1.0e-13_wp
    !! CNTL(3): a pivot row whose norm is below this fraction of the scaled
    !! matrix's norm is null (the reciprocal of the health block's MAXRATIO limit)
  integer(i8), parameter, public :: INVERSE_DIAGONAL_MAX_N = 20000_i8
    !! pivots() computes diag(A^-1) up to this order; above it (n = 1e5: about
    !! 40 times the factorization's time) the pivots are unknown (zeros)
  integer(c_int), parameter :: ORDERING_AMD = 0
    !! ICNTL(7) = 0: AMD, deterministic (SCOTCH through MUMPS gave a different
    !! factor size from run to run, and 60 % more fill on the 1e5 frame)
  integer(c_int), parameter :: ORDERING_GIVEN = 1       !! ICNTL(7) = 1: PERM_IN
  integer(c_int), parameter :: PAR_ORDERING_PTSCOTCH = 1  !! ICNTL(29) = 1
  integer(c_int), parameter :: PAR_ORDERING_PARMETIS = 2  !! ICNTL(29) = 2
  integer(c_int), parameter :: SJ_OK = 0
  integer(c_int), parameter :: SJ_NOMEM = -105        !! shim: malloc failed
  integer(c_int), parameter :: SJ_TOO_LARGE = -106    !! shim: order beyond MUMPS's 32-bit indices
  integer(c_int), parameter :: SJ_NOT_BUILT = -108    !! stub: no MUMPS in this build
  integer(c_int), parameter :: SJ_ORDERING = -109     !! superjoin's METIS ordering (or its gather) failed
  integer(c_int), parameter :: MUMPS_ALLOC_FAILED = -13     !! INFOG(1): allocation failed
  integer(c_int), parameter :: MUMPS_INT_ALLOC_FAILED = -7  !! INFOG(1): integer workspace allocation failed
  integer(c_int), parameter :: MUMPS_WORKSPACE = -9         !! INFOG(1): workspace too small
  integer(c_int), parameter :: MUMPS_SINGULAR = -10         !! INFOG(1): numerically singular
  integer, parameter :: INFOG_ERROR = 1, INFOG_DETAIL = 2, INFOG_ORDERING = 7, INFOG_NEGATIVE = 12, &
       INFOG_FACTOR_ENTRIES = 29, INFOG_FACTOR_ESTIMATE = 20, INFOG_NULL_PIVOTS = 28
  integer, parameter :: RINFOG_FLOPS = 3
  integer, parameter :: INFOG_MB_ESTIMATE_MAX = 21, INFOG_MB_ESTIMATE_TOTAL = 22, INFOG_ANALYSIS = 32
    !! estimated MB (in core) of the largest process and of all; the analysis done (1 sequential, 2 parallel)
  integer, parameter :: PARALLEL_ANALYSIS = 2
  integer, parameter :: INFO_MB_HERE = 16, INFOG_MB_MAX = 18, INFOG_MB_TOTAL = 19
    !! MUMPS's memory in MB allocated by the factorization: this process, the largest, all
  real(wp), parameter :: MBYTE = 1048576.0_wp
  real(wp), parameter :: MILLION = 1.0e6_wp
  integer, parameter :: BYTES_ENTRY = 8                !! a real(wp) factor entry

  type, extends(linear_solver_t), public :: mumps_solver_t
    !! MUMPS multifrontal LDL^T.
     private
     type(c_ptr) :: handle = c_null_ptr
     integer, public :: sym = MUMPS_SPD   !! MUMPS_SPD or MUMPS_SYMMETRIC (set before analyze)
     logical, public :: local_input = .false.
       !! Set before analyze: the matrix each process passes is its own term of
       !! a sum (for example the stiffness of the substructures it owns), all of
       !! whose entries it hands MUMPS; the matrix factored is the sum over the
       !! processes (MUMPS sums duplicate entries). Otherwise every process passes
       !! the same whole matrix and contributes a block of its columns.
     integer(i8) :: n = -1
     logical :: factored = .false.
     real(wp) :: fl = 0.0_wp
     integer, public :: ordering = 0
       !! superjoin_solvers_mumps_order's ORDER_*: the analysis's ordering;
       !! 0 (set before the first analyze): SUPERJOIN_MUMPS_ORDERING or the
       !! default (with alone: AMD, always)
     logical, public :: alone = .false.
       !! Set before analyze: an instance of this process alone (MPI_COMM_SELF),
       !! whose calls are not collective; for a part that one process condenses
     integer(i8) :: nschur = 0
       !! schur: the last nschur columns are condensed (ICNTL(19)); solve,
       !! pivots and info then refer to the first n - nschur
     real(wp), allocatable :: schur_block(:)
       !! the Schur complement of the last factorization, column-major upper triangle
     real(wp), allocatable :: interior_pivots(:)
       !! schur: the pivots of a_ii (up to INVERSE_DIAGONAL_MAX_N columns)
     type(comm_t) :: comm
   contains
     procedure :: analyze => mumps_analyze
     procedure :: factorize => mumps_factorize
     procedure :: solve => mumps_solve
     procedure :: pivots => mumps_pivots
     procedure :: release => mumps_release
     procedure :: schur => mumps_schur
     procedure :: flops => mumps_flops
     procedure :: negative_pivots => mumps_negative_pivots
     procedure, public :: input_norm => mumps_input_norm
     final :: mumps_finalize
  end type mumps_solver_t

  public :: mumps_available

  interface
     function sj_mumps_built() bind(c, name='sj_mumps_built') result(yes)
       import :: c_int
       integer(c_int) :: yes
     end function sj_mumps_built
     function sj_mumps_create(sym, comm, null_threshold, ordering, alone, status) bind(c, name='sj_mumps_create') &
          result(h)
       import :: c_ptr, c_int, c_double
       integer(c_int), value :: sym, comm, ordering, alone
       real(c_double), value :: null_threshold
       integer(c_int), intent(out) :: status
       type(c_ptr) :: h
     end function sj_mumps_create
     function sj_mumps_pattern(h, n, colptr, rowind, c1, c2) bind(c, name='sj_mumps_pattern') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: n, c1, c2
       integer(c_int64_t), intent(in) :: colptr(*), rowind(*)
       integer(c_int) :: status
     end function sj_mumps_pattern
     function sj_mumps_set_ordering(h, ordering, parallel, par_ordering) bind(c, name='sj_mumps_set_ordering') &
          result(status)
       import :: c_ptr, c_int
       type(c_ptr), value :: h
       integer(c_int), value :: ordering, parallel, par_ordering
       integer(c_int) :: status
     end function sj_mumps_set_ordering
     function sj_mumps_perm_in(h, iperm) bind(c, name='sj_mumps_perm_in') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), intent(in) :: iperm(*)
       integer(c_int) :: status
     end function sj_mumps_perm_in
     function sj_mumps_analyze(h) bind(c, name='sj_mumps_analyze') result(status)
       import :: c_ptr, c_int
       type(c_ptr), value :: h
       integer(c_int) :: status
     end function sj_mumps_analyze
     function sj_mumps_factorize(h, val, schur) bind(c, name='sj_mumps_factorize') result(status)
       import :: c_ptr, c_int, c_double
       type(c_ptr), value :: h
       real(c_double), intent(in) :: val(*)
       real(c_double), intent(inout) :: schur(*)
       integer(c_int) :: status
     end function sj_mumps_factorize
     function sj_mumps_set_schur(h, nschur) bind(c, name='sj_mumps_set_schur') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: nschur
       integer(c_int) :: status
     end function sj_mumps_set_schur
     function sj_mumps_solve(h, nrhs, x) bind(c, name='sj_mumps_solve') result(status)
       import :: c_ptr, c_int, c_int64_t, c_double
       type(c_ptr), value :: h
       integer(c_int64_t), value :: nrhs
       real(c_double), intent(inout) :: x(*)
       integer(c_int) :: status
     end function sj_mumps_solve
     function sj_mumps_inverse_diagonal(h, ptr, irow, dinv) bind(c, name='sj_mumps_inverse_diagonal') result(status)
       import :: c_ptr, c_int, c_double
       type(c_ptr), value :: h
       integer(c_int), intent(inout) :: ptr(*), irow(*)
       real(c_double), intent(inout) :: dinv(*)
       integer(c_int) :: status
     end function sj_mumps_inverse_diagonal
     function sj_mumps_input_norm(h, x, anorm) bind(c, name='sj_mumps_input_norm') result(status)
       import :: c_ptr, c_int, c_double
       type(c_ptr), value :: h
       real(c_double), intent(inout) :: x(*)
       real(c_double), intent(out) :: anorm
       integer(c_int) :: status
     end function sj_mumps_input_norm
     function sj_mumps_infog(h, i) bind(c, name='sj_mumps_infog') result(v)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int), value :: i
       integer(c_int64_t) :: v
     end function sj_mumps_infog
     function sj_mumps_info(h, i) bind(c, name='sj_mumps_info') result(v)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int), value :: i
       integer(c_int64_t) :: v
     end function sj_mumps_info
     function sj_mumps_rinfog(h, i) bind(c, name='sj_mumps_rinfog') result(v)
       import :: c_ptr, c_int, c_double
       type(c_ptr), value :: h
       integer(c_int), value :: i
       real(c_double) :: v
     end function sj_mumps_rinfog
     function sj_mumps_null_pivot(h, k) bind(c, name='sj_mumps_null_pivot') result(j)
       import :: c_ptr, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: k
       integer(c_int64_t) :: j
     end function sj_mumps_null_pivot
     subroutine sj_mumps_free(h) bind(c, name='sj_mumps_free')
       import :: c_ptr
       type(c_ptr), value :: h
     end subroutine sj_mumps_free
     subroutine sj_mumps_forget(h) bind(c, name='sj_mumps_forget')
       import :: c_ptr
       type(c_ptr), value :: h
     end subroutine sj_mumps_forget
  end interface

contains

  function mumps_available() result(yes)
    !! Is MUMPS built into this superjoin (cmake -DSUPERJOIN_MUMPS=ON or -DSUPERJOIN_MPI=ON)?
    logical :: yes
    yes = sj_mumps_built() /= 0
  end function mumps_available

  subroutine mumps_analyze(self, a, error)
    !! Start MUMPS (first call), hand in this process's share of the pattern
    !! and run the analysis (the ordering of self%ordering, see
    !! superjoin_solvers_mumps_order; symbolic factorization).
    class(mumps_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    call analyze_schur(self, a, 0_i8, error)
  end subroutine mumps_analyze

  subroutine analyze_schur(self, a, nschur, error)
    !! The analysis of mumps_analyze, the last nschur columns of a kept for
    !! a Schur complement (ICNTL(19) = 1; 0: none).
    class(mumps_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nschur
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status
    integer(i8) :: c1, c2, one(1), gathered_bytes
    integer(i8), allocatable :: iperm(:)
    real(wp) :: seconds
    integer :: host_status, stat

    self%factored = .false.
    self%n = -1
    self%nschur = 0
    if (self%sym == MUMPS_SPD) then
       self%info%name = 'MUMPS multifrontal LDL^T (SPD)'
    else
       self%info%name = 'MUMPS multifrontal LDL^T (symmetric, pivoting)'
    end if
    self%info%ordering = 'none'
    self%info%factor_nnz = 0
    self%info%factor_mbytes = 0.0_wp
    self%info%failed_column = 0
    if (a%n < 0 .or. .not. allocated(a%colptr) .or. nschur < 0 .or. nschur > max(a%n, 0_i8)) then
       call fatal_error(error, EXIT_IO, 'MUMPS: invalid matrix')
       return
    end if
    call open_instance(self, a, error)
    if (allocated(error)) return
    call share(self, a, c1, c2)
    one = 1
    if (a%nnz() > 0) then
       status = sj_mumps_pattern(self%handle, a%n, a%colptr, a%rowind, c1, c2)
    else
       status = sj_mumps_pattern(self%handle, a%n, a%colptr, one, 1_i8, 0_i8)
    end if
    if (status == SJ_OK) status = sj_mumps_set_schur(self%handle, int(nschur, c_int64_t))
    if (allocated(self%schur_block)) deallocate (self%schur_block)
    allocate (self%schur_block(max(1_i8, nschur*nschur)), stat=stat)
    if (status == SJ_OK .and. stat /= 0) status = SJ_NOMEM
    gathered_bytes = 0
    seconds = 0.0_wp
    if (status == SJ_OK) status = set_ordering(self%handle, self%ordering)
    if (self%ordering == ORDER_METIS) then
       ! collective (the gather of the terms' patterns) whatever this process's status
       call host_nested_dissection(a, self%local_input, iperm, gathered_bytes, seconds, host_status)
       if (status == SJ_OK .and. host_status == ORDERING_NO_MEMORY) status = SJ_NOMEM
       if (status == SJ_OK .and. host_status /= 0) status = SJ_ORDERING
       if (status == SJ_OK) status = sj_mumps_perm_in(self%handle, iperm)
    end if
    if (.not. self%alone) call record_host_ordering(gathered_bytes, seconds)
    call agreed(self, status, 'analyze', error)
    if (allocated(error)) return
    status = sj_mumps_analyze(self%handle)
    if (status < 0) then
       call status_error(self, status, 'analyze', error)
       return
    end if
    self%n = a%n
    self%nschur = nschur
    self%info%ordering = ordering_name(int(sj_mumps_infog(self%handle, INFOG_ORDERING)), &
         sj_mumps_infog(self%handle, INFOG_ANALYSIS) == PARALLEL_ANALYSIS)
    if (self%comm%size > 1) self%info%ordering = self%info%ordering//'; '//distribution(self, a, c1, c2)
    self%info%factor_nnz = entries(sj_mumps_infog(self%handle, INFOG_FACTOR_ESTIMATE))
  end subroutine analyze_schur

  subroutine open_instance(self, a, error)
    !! The communicator, the ordering choice and (first call) the MUMPS
    !! instance; with local_input on several processes, a check that every
    !! process's term has the order of a. Collective unless alone.
    class(mumps_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status
    integer :: comm_handle
    real(wp) :: orders(2)
    logical :: ok
    self%comm = comm_world()
    comm_handle = 0
    if (self%alone) then
       self%comm%rank = 0
       self%comm%size = 1
       if (self%ordering == 0 .or. self%ordering == ORDER_METIS) self%ordering = ORDER_AMD
    end if
    call agreed(self, SJ_OK, 'start', error)
    if (allocated(error)) return
    if (self%ordering == 0) then
       ! collective, where every process is (the value of process 0, the same verdict everywhere)
       self%ordering = ordering_choice(error)
       if (allocated(error)) return
    end if
    if (self%local_input .and. self%comm%size > 1) then
       ! every process's term must have the same order: the largest n and the
       ! largest -n agree (the same verdict on every process)
       orders = [real(a%n, wp), -real(a%n, wp)]
       call max_reals(orders, ok)
       if (.not. ok .or. orders(1) /= -orders(2)) then
          call fatal_error(error, EXIT_IO, 'MUMPS: the processes'' terms of the matrix differ in order')
          return
       end if
    end if
    if (c_associated(self%handle)) return
    if (self%alone) then
       comm_handle = fortran_self_handle()
    else
       comm_handle = fortran_handle()
    end if
    self%handle = sj_mumps_create(int(self%sym, c_int), int(comm_handle, c_int), &
         real(NULL_PIVOT_RELATIVE, c_double), ORDERING_AMD, merge(1_c_int, 0_c_int, self%alone), status)
    if (status == SJ_NOT_BUILT) then
       call fatal_error(error, EXIT_USAGE, 'solver mumps: this superjoin is built without MUMPS '// &
            '(configure with cmake -DSUPERJOIN_MUMPS=ON or -DSUPERJOIN_MPI=ON)')
       return
    end if
    if (status /= SJ_OK) call status_error(self, status, 'start', error)
  end subroutine open_instance

  subroutine mumps_factorize(self, a, error)
    !! Numeric factorization. A null pivot (or, SPD, a negative one): error
    !! with EXIT_SINGULAR and info%failed_column (0 when MUMPS does not say).
    class(mumps_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status
    integer(i8) :: nnull, nneg
    real(wp) :: first(1)
    real(wp) :: zero(1)
    logical :: ok

    self%factored = .false.
    self%info%failed_column = 0
    if (.not. c_associated(self%handle) .or. self%n < 0) then
       call fatal_error(error, EXIT_IO, 'MUMPS: factorize called before analyze')
       return
    end if
    if (a%n /= self%n) then
       call fatal_error(error, EXIT_IO, 'MUMPS: matrix order differs from the analyzed one')
       return
    end if
    call agreed(self, SJ_OK, 'factorize', error)
    if (allocated(error)) return
    zero = 0.0_wp
    if (.not. allocated(self%schur_block)) allocate (self%schur_block(max(1_i8, self%nschur*self%nschur)))
    if (a%nnz() > 0) then
       status = sj_mumps_factorize(self%handle, a%val, self%schur_block)
    else
       status = sj_mumps_factorize(self%handle, zero, self%schur_block)
    end if
    self%fl = sj_mumps_rinfog(self%handle, RINFOG_FLOPS)
    if (status == MUMPS_SINGULAR) then
       ! SYM = 1 stops at a zero pivot without naming it: the pivoting
       ! variant, with null pivot detection, finds the column
       if (self%sym == MUMPS_SPD) self%info%failed_column = null_column(self, a)
       call fatal_error(error, EXIT_SINGULAR, 'matrix is numerically singular (MUMPS)')
       return
    end if
    if (status < 0) then
       call status_error(self, status, 'factorize', error)
       return
    end if
    self%info%factor_nnz = entries(sj_mumps_infog(self%handle, INFOG_FACTOR_ENTRIES))
    if (.not. self%alone) then
       call record_factor(self)
       call record_mumps_memory(sj_mumps_info(self%handle, INFO_MB_HERE), sj_mumps_infog(self%handle, INFOG_MB_MAX), &
            sj_mumps_infog(self%handle, INFOG_MB_TOTAL))
    end if
    self%info%factor_mbytes = real(self%info%factor_nnz, wp)*BYTES_ENTRY/MBYTE
    nnull = sj_mumps_infog(self%handle, INFOG_NULL_PIVOTS)
    if (nnull > 0) then
       ! the list is on the host only: every process must report the same column
       first(1) = real(sj_mumps_null_pivot(self%handle, 1_c_int64_t), wp)
       if (.not. self%alone) call broadcast(first, 0, ok)
       self%info%failed_column = int(first(1), i8)
       call fatal_error(error, EXIT_SINGULAR, 'matrix is singular: '//itoa(nnull)// &
            ' null pivot(s), the first at column '//itoa(self%info%failed_column))
       return
    end if
    nneg = sj_mumps_infog(self%handle, INFOG_NEGATIVE)
    if (self%sym == MUMPS_SPD .and. nneg > 0) then
       call fatal_error(error, EXIT_SINGULAR, 'matrix is not positive definite: '//itoa(nneg)//' negative pivot(s)')
       return
    end if
    self%factored = .true.
  end subroutine mumps_factorize

  subroutine mumps_solve(self, b, x, error)
    !! x = A^-1 b for every column of b, on every process.
    class(mumps_solver_t), intent(inout) :: self
    real(wp), intent(in) :: b(:, :)
    real(wp), intent(out) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status
    real(wp), allocatable :: work(:)
    integer :: stat, c
    integer(i8) :: ni, n
    logical :: ok

    if (.not. self%factored) then
       call fatal_error(error, EXIT_IO, 'MUMPS: solve called without a valid factorization')
       return
    end if
    ni = self%n - self%nschur
    if (size(b, 1, i8) /= ni .or. size(x, 1, i8) /= ni .or. size(b, 2) /= size(x, 2)) then
       call fatal_error(error, EXIT_IO, 'MUMPS: right-hand side and solution shapes do not match the matrix')
       return
    end if
    if (ni == 0 .or. size(b, 2) == 0) return
    ! with a Schur complement MUMPS takes vectors of order n and, with
    ! ICNTL(26) = 0, solves a_ii x_i = b_i, its x_b set to zero
    n = self%n
    allocate (work(n*size(b, 2)), stat=stat)
    call agreed(self, merge(SJ_OK, SJ_NOMEM, stat == 0), 'solve', error)
    if (allocated(error)) return
    work = 0.0_wp
    do c = 1, size(b, 2)
       work((c - 1)*n + 1:(c - 1)*n + ni) = b(:, c)
    end do
    status = sj_mumps_solve(self%handle, int(size(b, 2), c_int64_t), work)
    if (status < 0) then
       call status_error(self, status, 'solve', error)
       return
    end if
    if (.not. self%alone) then
       call broadcast(work, 0, ok)
       if (.not. ok) then
          call fatal_error(error, EXIT_IO, 'MUMPS solve: the solution could not be sent to every process')
          return
       end if
    end if
    do c = 1, size(b, 2)
       x(:, c) = work((c - 1)*n + 1:(c - 1)*n + ni)
    end do
  end subroutine mumps_solve

  subroutine mumps_pivots(self, d)
    !! MUMPS does not give its pivots to the caller. Instead d(j) = 1/(A^-1)_jj,
    !! the pivot column j would have if it were eliminated last (MUMPS's
    !! selected entries of the inverse, ICNTL(30)). For a positive definite
    !! matrix that is the smallest pivot j can have in any elimination order,
    !! so K_jj/d(j) bounds the diagonal decay ratio of every ordering from
    !! above: the health block's MAXRATIO is then an upper bound, independent
    !! of the ordering (and of the number of processes). d = 0 (unknown, the
    !! health block's MAXRATIO is then n/a) above INVERSE_DIAGONAL_MAX_N
    !! unknowns or if the computation fails. Collective unless alone.
    !! After schur: the pivots of a_ii that schur found (see pivots_of_interior).
    class(mumps_solver_t), intent(inout) :: self
    real(wp), intent(out) :: d(:)
    integer(c_int), allocatable :: ptr(:), irow(:)
    real(wp), allocatable :: dinv(:)
    integer(c_int) :: status
    integer :: stat, worst, first
    logical :: ok

    d = 0.0_wp
    if (.not. self%factored .or. self%n <= 0 .or. size(d, kind=i8) < self%n - self%nschur) return
    if (self%n - self%nschur > INVERSE_DIAGONAL_MAX_N) return
    if (self%nschur > 0) then
       if (allocated(self%interior_pivots)) d(1:self%n - self%nschur) = self%interior_pivots
       return
    end if
    allocate (ptr(self%n + 1), irow(self%n), dinv(self%n), stat=stat)
    worst = merge(0, EXIT_IO, stat == 0)
    if (.not. self%alone) call agree(merge(0, EXIT_IO, stat == 0), worst, first)
    if (worst /= 0) return
    dinv = 0.0_wp
    status = sj_mumps_inverse_diagonal(self%handle, ptr, irow, dinv)
    if (status < 0) return
    if (.not. self%alone) then
       call broadcast(dinv, 0, ok)
       if (.not. ok) return
    end if
    where (dinv /= 0.0_wp) d(1:self%n) = 1.0_wp/dinv
  end subroutine mumps_pivots

  subroutine pivots_of_interior(self, a, ni, error)
    !! schur's pivots of a_ii: 1/(a_ii^-1)_jj (MUMPS refuses the entries of
    !! the inverse after a Schur factorization, INFOG(1) = -48) from an
    !! instance of a_ii alone (the same sym, communicator and ordering),
    !! factored for them and released. This is also schur's check of a_ii:
    !! with SYM = 1 MUMPS detects no null pivot, and a singular a_ii can leave
    !! a round-off pivot in the Schur factorization; this factorization of
    !! a_ii then fails as the default route's would (error, failed_column).
    class(mumps_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: ni
    type(error_t), allocatable, intent(out) :: error
    type(mumps_solver_t) :: probe
    type(sparse_sym_t) :: aii
    aii%n = ni
    aii%colptr = a%colptr(1:ni + 1)
    aii%rowind = a%rowind(1:a%colptr(ni + 1) - 1)
    aii%val = a%val(1:a%colptr(ni + 1) - 1)
    probe%sym = self%sym
    probe%alone = self%alone
    probe%local_input = self%local_input
    probe%ordering = self%ordering
    call probe%analyze(aii, error)
    if (.not. allocated(error)) call probe%factorize(aii, error)
    if (allocated(error)) then
       self%info%failed_column = probe%info%failed_column
    else
       allocate (self%interior_pivots(ni))
       call probe%pivots(self%interior_pivots)
    end if
    call probe%release()
  end subroutine pivots_of_interior

  subroutine mumps_schur(self, a, nb, kstar, error)
    !! Static condensation (the contract: linear_solver_t%schur) by MUMPS's
    !! Schur complement: one analysis and factorization of the whole part
    !! with ICNTL(19) = 1 and the last nb variables as LISTVAR_SCHUR. The
    !! value 1 (centralized on the host) because kstar is wanted whole on the
    !! caller's process: 2 and 3 distribute it over a process grid (3 for a
    !! symmetric matrix in both triangles, 2 in one). With SYM = 1 or 2 MUMPS
    !! computes one triangle (its fronts are symmetric), returned by rows as
    !! the lower triangle, i.e. the upper triangle of the column-major array;
    !! it is mirrored here. MUMPS then keeps the factor of a_ii: its solve
    !! with ICNTL(26) = 0 solves a_ii x_i = b_i (mumps_solve). A breakdown's
    !! null pivot is an interior column (the Schur variables are not
    !! eliminated). On several processes (not alone) kstar is sent to all.
    !! Up to INVERSE_DIAGONAL_MAX_N interior columns the pivots of a_ii are
    !! computed here (pivots_of_interior: also the check of a singular a_ii
    !! that SYM = 1 needs); above, pivots are unknown (zeros), as for any
    !! MUMPS matrix of that order.
    class(mumps_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(out) :: kstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: ni, i, j
    logical :: ok
    ni = a%n - nb
    if (allocated(self%interior_pivots)) deallocate (self%interior_pivots)
    if (ni == 0) then   ! K* = a: nothing to factor
       kstar = 0.0_wp
       do j = 1, nb
          kstar(a%rowind(a%colptr(j):a%colptr(j + 1) - 1), j) = a%val(a%colptr(j):a%colptr(j + 1) - 1)
       end do
       kstar = kstar + transpose(kstar)
       do j = 1, nb
          kstar(j, j) = 0.5_wp*kstar(j, j)
       end do
       return
    end if
    call analyze_schur(self, a, nb, error)
    if (allocated(error)) return
    call self%factorize(a, error)
    if (allocated(error)) return
    if (nb == 0) return
    if (.not. self%alone .and. self%comm%size > 1) then
       call broadcast(self%schur_block, 0, ok)
       if (.not. ok) then
          call fatal_error(error, EXIT_IO, 'MUMPS: the Schur complement could not be sent to every process')
          return
       end if
    end if
    do j = 1, nb
       do i = 1, j
          kstar(i, j) = self%schur_block(i + (j - 1)*nb)
          kstar(j, i) = kstar(i, j)
       end do
    end do
    deallocate (self%schur_block)
    if (ni <= INVERSE_DIAGONAL_MAX_N) call pivots_of_interior(self, a, ni, error)
  end subroutine mumps_schur

  subroutine mumps_input_norm(self, anorm, error)
    !! The 1-norm (= infinity norm, the matrix is symmetric) of the matrix
    !! MUMPS factored, with local_input the sum of the processes' terms that no
    !! process holds: RINFOG(4) of one extra solve with MUMPS's main error
    !! statistics (ICNTL(11) = 2). The same on every process. Collective.
    class(mumps_solver_t), intent(inout) :: self
    real(wp), intent(out) :: anorm
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:)
    integer(c_int) :: status
    integer :: stat
    real(c_double) :: a
    anorm = 0.0_wp
    if (.not. self%factored) then
       call fatal_error(error, EXIT_IO, 'MUMPS: input_norm called without a valid factorization')
       return
    end if
    if (self%n == 0) return
    allocate (x(self%n), stat=stat)
    call agreed(self, merge(SJ_OK, SJ_NOMEM, stat == 0), 'solve', error)
    if (allocated(error)) return
    x = 1.0_wp
    status = sj_mumps_input_norm(self%handle, x, a)
    if (status < 0) then
       call status_error(self, status, 'solve', error)
       return
    end if
    anorm = a
  end subroutine mumps_input_norm

  subroutine mumps_release(self)
    !! End the MUMPS instance (collective) and free the shim.
    class(mumps_solver_t), intent(inout) :: self
    if (c_associated(self%handle)) call sj_mumps_free(self%handle)
    self%handle = c_null_ptr
    if (allocated(self%schur_block)) deallocate (self%schur_block)
    if (allocated(self%interior_pivots)) deallocate (self%interior_pivots)
    self%nschur = 0
    self%n = -1
    self%factored = .false.
  end subroutine mumps_release

  pure function mumps_flops(self) result(fl)
    !! Floating-point operations of the last factorization (RINFOG(3), all processes).
    class(mumps_solver_t), intent(in) :: self
    real(wp) :: fl
    fl = self%fl
  end function mumps_flops

  function mumps_negative_pivots(self) result(nneg)
    !! Negative pivots of the last factorization (INFOG(12)): the inertia for SYM = 2.
    class(mumps_solver_t), intent(in) :: self
    integer(i8) :: nneg
    nneg = 0
    if (c_associated(self%handle)) nneg = sj_mumps_infog(self%handle, INFOG_NEGATIVE)
  end function mumps_negative_pivots

  subroutine mumps_finalize(self)
    !! Finalizer: free the shim's own arrays only, without ending the MUMPS
    !! instance (JOB = -2 is collective, and a finalizer also runs on the way
    !! out of an error that only this process had: it must not wait for the
    !! others). Normal paths call release(); this leaks MUMPS's memory only
    !! when a run ends on an error.
    type(mumps_solver_t), intent(inout) :: self
    if (c_associated(self%handle)) call sj_mumps_forget(self%handle)
    self%handle = c_null_ptr
  end subroutine mumps_finalize

  ! ---- helpers

  subroutine share(self, a, c1, c2)
    !! This process's columns c1..c2: contiguous blocks holding about
    !! nnz/size entries each, ending on a node boundary when groups are set.
    class(mumps_solver_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(out) :: c1, c2
    integer(i8) :: j, target_lo, target_hi, nz
    c1 = 1
    c2 = a%n
    if (self%local_input .or. self%comm%size <= 1 .or. a%n == 0) return
    nz = a%nnz()
    target_lo = nz*self%comm%rank/self%comm%size
    target_hi = nz*(self%comm%rank + 1)/self%comm%size
    c1 = boundary(target_lo) + 1
    c2 = boundary(target_hi)
    if (self%comm%rank == self%comm%size - 1) c2 = a%n
  contains
    function boundary(t) result(jb)
      !! Last column whose entries end at or before position t, moved to a node end.
      integer(i8), intent(in) :: t
      integer(i8) :: jb, g
      jb = 0
      do j = 1, a%n
         if (a%colptr(j + 1) - 1 > t) exit
         jb = j
      end do
      if (allocated(self%group_first) .and. jb > 0 .and. jb < a%n) then
         do g = 1, size(self%group_first, kind=i8) - 1
            if (self%group_first(g + 1) - 1 >= jb) then
               jb = self%group_first(g + 1) - 1
               exit
            end if
         end do
         jb = min(jb, a%n)
      end if
    end function boundary
  end subroutine share

  function null_column(self, a) result(j)
    !! The first null pivot column of a (with local_input: of the sum of the
    !! processes' a; after schur: of a_ii) as found by MUMPS with pivoting
    !! (SYM = 2, null pivot detection); 0 if none is found. Collective
    !! unless alone.
    class(mumps_solver_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8) :: j
    type(mumps_solver_t) :: probe
    type(error_t), allocatable :: error
    j = 0
    probe%sym = MUMPS_SYMMETRIC
    probe%local_input = self%local_input
    probe%alone = self%alone
    probe%ordering = self%ordering
    call analyze_schur(probe, a, self%nschur, error)
    if (allocated(error)) return
    call probe%factorize(a, error)
    j = probe%info%failed_column
    call probe%release()
  end function null_column

  function distribution(self, a, c1, c2) result(text)
    !! 'N processes, matrix entries per process n0 n1 ..' (collective).
    class(mumps_solver_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: c1, c2
    character(:), allocatable :: text
    integer(i8), allocatable :: counts(:)
    integer :: r
    logical :: ok
    allocate (counts(0:self%comm%size - 1))
    counts = 0
    if (c2 >= c1) counts(self%comm%rank) = a%colptr(c2 + 1) - a%colptr(c1)
    call record_mumps_input(counts(self%comm%rank))
    call sum_counts(counts, ok)
    text = itoa(int(self%comm%size, i8))//' processes, matrix entries per process'
    do r = 0, self%comm%size - 1
       text = text//' '//itoa(counts(r))
    end do
  end function distribution

  subroutine agreed(self, status, phase, error)
    !! Collective, before every MUMPS phase: each process says whether it is
    !! ready (status SJ_OK, or the shim status of its own failure). If one is
    !! not, every process returns an error with the agreed exit status: the
    !! process that failed first with its own message (it prints it), the
    !! others with a note (silent, see superjoin_parallel_comm).
    class(mumps_solver_t), intent(in) :: self
    integer(c_int), intent(in) :: status
    character(*), intent(in) :: phase
    type(error_t), allocatable, intent(out) :: error
    integer :: worst, first, mine
    mine = 0
    if (status /= SJ_OK) then
       call status_error(self, status, phase, error)
       mine = error%code
    end if
    if (self%alone) return
    call agree(mine, worst, first)
    if (worst == 0) return
    call note_agreed_failure(first)
    if (allocated(error)) then
       error%code = worst
    else
       call fatal_error(error, worst, 'MUMPS '//phase//': process '//itoa(int(first, i8))//' failed')
    end if
  end subroutine agreed

  subroutine status_error(self, status, phase, error)
    !! Error for a failed shim or MUMPS call (INFOG(1) < 0).
    class(mumps_solver_t), intent(in) :: self
    integer(c_int), intent(in) :: status
    character(*), intent(in) :: phase
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: detail
    detail = 0
    if (c_associated(self%handle)) detail = sj_mumps_infog(self%handle, INFOG_DETAIL)
    select case (status)
    case (SJ_NOMEM)
       call fatal_error(error, EXIT_IO, 'error: out of memory: MUMPS '//phase)
    case (SJ_ORDERING)
       call fatal_error(error, EXIT_IO, 'MUMPS '//phase//': the METIS ordering of the matrix''s graph failed')
    case (SJ_TOO_LARGE)
       call fatal_error(error, EXIT_IO, 'MUMPS '//phase//': the matrix is too large for MUMPS''s 32-bit indices')
    case (MUMPS_INT_ALLOC_FAILED)
       call fatal_error(error, EXIT_IO, 'error: out of memory: MUMPS '//phase//' could not allocate its '// &
            'integer workspace (MUMPS INFOG(1) = '//itoa(int(status, i8))//', INFOG(2) = '//itoa(detail)//')')
    case (MUMPS_ALLOC_FAILED, MUMPS_WORKSPACE)
       call fatal_error(error, EXIT_IO, oom_message('MUMPS '//phase, entries(int(detail, c_int64_t))*BYTES_ENTRY)// &
            ' (MUMPS INFOG(1) = '//itoa(int(status, i8))//', INFOG(2) = '//itoa(detail)//')')
    case default
       call fatal_error(error, EXIT_IO, 'MUMPS '//phase//' failed: INFOG(1) = '//itoa(int(status, i8))// &
            ', INFOG(2) = '//itoa(detail))
    end select
  end subroutine status_error

  pure function entries(v) result(n)
    !! A MUMPS count: negative values are millions.
    integer(c_int64_t), intent(in) :: v
    integer(i8) :: n
    if (v < 0) then
       n = int(-real(v, wp)*MILLION, i8)
    else
       n = v
    end if
  end function entries

  function set_ordering(handle, choice) result(status)
    !! Set ICNTL(7), ICNTL(28), ICNTL(29) for an ORDER_* choice (local).
    type(c_ptr), intent(in) :: handle
    integer, intent(in) :: choice
    integer(c_int) :: status
    select case (choice)
    case (ORDER_PTSCOTCH)
       status = sj_mumps_set_ordering(handle, ORDERING_AMD, 1_c_int, PAR_ORDERING_PTSCOTCH)
    case (ORDER_METIS)
       status = sj_mumps_set_ordering(handle, ORDERING_GIVEN, 0_c_int, PAR_ORDERING_PTSCOTCH)
    case default
       status = sj_mumps_set_ordering(handle, ORDERING_AMD, 0_c_int, PAR_ORDERING_PTSCOTCH)
    end select
  end function set_ordering

  subroutine record_factor(self)
    !! The factorization's figures for the ordering line on stderr (superjoin_parallel_stats).
    class(mumps_solver_t), intent(in) :: self
    type(mumps_order_stats_t) :: figures
    figures%ordering = self%info%ordering
    figures%factor_entries = entries(sj_mumps_infog(self%handle, INFOG_FACTOR_ENTRIES))
    figures%estimate = entries(sj_mumps_infog(self%handle, INFOG_FACTOR_ESTIMATE))
    figures%flops = self%fl
    figures%mb_estimate_max = sj_mumps_infog(self%handle, INFOG_MB_ESTIMATE_MAX)
    figures%mb_estimate_total = sj_mumps_infog(self%handle, INFOG_MB_ESTIMATE_TOTAL)
    call record_mumps_factor(figures)
  end subroutine record_factor

  pure function ordering_name(code, parallel) result(name)
    !! The ordering MUMPS used (INFOG(7); after a parallel analysis, INFOG(32)
    !! = 2, coded as ICNTL(29)).
    integer, intent(in) :: code
    logical, intent(in) :: parallel
    character(:), allocatable :: name
    if (parallel) then
       select case (code)
       case (PAR_ORDERING_PTSCOTCH)
          name = 'PT-SCOTCH (MUMPS, parallel analysis)'
       case (PAR_ORDERING_PARMETIS)
          name = 'ParMETIS (MUMPS, parallel analysis)'
       case default
          name = 'MUMPS parallel ordering '//itoa(int(code, i8))
       end select
       return
    end if
    select case (code)
    case (0)
       name = 'AMD (MUMPS)'
    case (1)
       name = 'METIS nested dissection (superjoin)'
    case (2)
       name = 'AMF (MUMPS)'
    case (3)
       name = 'SCOTCH (MUMPS)'
    case (4)
       name = 'PORD (MUMPS)'
    case (5)
       name = 'METIS (MUMPS)'
    case (6)
       name = 'QAMD (MUMPS)'
    case default
       name = 'MUMPS ordering '//itoa(int(code, i8))
    end select
  end function ordering_name
end module superjoin_solvers_mumps
