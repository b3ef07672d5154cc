module superjoin_solvers_cholmod
  !! Sparse supernodal Cholesky (CHOLMOD) behind the linear_solver_t interface.
  !!
  !! CHOLMOD is driven through the C shim src/solvers/cholmod_shim.c, which
  !! owns the cholmod_common and the factor; this module only holds an opaque
  !! handle. The solver is not copyable (a copy would share the handle): use it
  !! in place, and call release() (or let it be finalized) when done.
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_int, &
       c_int64_t, c_double, c_char, c_null_char
  use superjoin_kinds, only: wp, i8
  use superjoin_solvers_blas, only: dsyrk
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR, EXIT_IO
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_solver, only: linear_solver_t, interior_block, schur_by_solves, &
       boundary_shift, unshift
  use superjoin_solvers_node_graph, only: node_graph
  use superjoin_utils_memory, only: oom_message, bytes_text, out_of_memory, BYTES_REAL
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  integer(c_int), parameter :: SJ_OK = 0           !! shim status: success
  integer(c_int), parameter :: SJ_NOT_POSDEF = 1   !! shim status: not positive definite
  integer(c_int), parameter :: SJ_TRY_INTERIOR = 2 !! schur_camd: CAMD fills much, analyze the interior
  integer(c_int), parameter :: CHOLMOD_OUT_OF_MEMORY = -2
  integer(c_int), parameter :: SJ_E_NOMEM = -105     !! malloc failed in the shim itself
  integer(c_int), parameter :: CHOLMOD_TOO_LARGE = -3
  integer, parameter :: NAME_LEN = 64              !! buffer for the ordering name
  integer(i8), parameter, public :: NODE_GRAPH_MIN_COLUMNS = 20000_i8
    !! from this size on, METIS on the node graph competes with CHOLMOD's AMD
  integer(i8), parameter, public :: NODE_AMD_MIN_COLUMNS = 100000_i8
    !! from this size on, AMD orders the node graph instead of the columns
    !! (far above the test decks, whose orderings stay column AMD's)
  integer, parameter :: MESSAGE_LEN = 256          !! buffer for shim messages
  real(wp), parameter :: MBYTE = 1048576.0_wp      !! bytes per MiB

  type, extends(linear_solver_t), public :: cholmod_solver_t
    !! CHOLMOD supernodal LL^T.
     private
     type(c_ptr) :: handle = c_null_ptr
     integer(i8) :: n = -1          !! order of the analyzed matrix (-1: none)
     integer(i8), public :: node_graph_min = NODE_GRAPH_MIN_COLUMNS
     integer(i8), public :: node_amd_min = NODE_AMD_MIN_COLUMNS
       !! AMD on the node graph from this many columns on (negative: never)
     logical, public :: force_node_metis = .false.
       !! offer the node-graph METIS ordering even where AMD's fill is low (tests)
     logical, public :: node_metis_only = .false.
       !! order by node-graph METIS alone, without CHOLMOD's AMD candidate (when
       !! groups are set; AMD if METIS fails): the level solver's top system
     logical, public :: camd_first = .true.
       !! schur: CAMD alone where its fill is low (.false.: always compare with
       !! the interior's own ordering, as before; bench/schur_cost)
       !! order the node graph (when groups are set) from this many columns on
     logical :: factored = .false.
     logical :: started = .false.   !! an analysis runs beside the caller (analyze_start)
     real(wp) :: fl = 0.0_wp        !! flop count of the factorization
     real(wp) :: peak = 0.0_wp      !! CHOLMOD's peak memory, bytes
     integer(i8) :: stored = 0      !! entries of L as stored (with amalgamation zeros)
     integer(i8) :: nb_halves = 0
       !! after schur: the boundary columns of the whole part's factor (ordered
       !! last), whose halves half_loads and half_recover take; 0: none
   contains
     procedure :: analyze => cholmod_analyze
     procedure :: analyze_start => cholmod_analyze_start
     procedure :: factorize => cholmod_factorize
     procedure :: solve => cholmod_solve
     procedure :: solve_leading => cholmod_solve_leading
     procedure :: pivots => cholmod_pivots
     procedure :: release => cholmod_release
     procedure :: flops => cholmod_flops
     procedure :: peak_mbytes => cholmod_peak_mbytes
     procedure :: stored_nnz => cholmod_stored_nnz
     procedure :: schur => cholmod_schur
     procedure :: half_loads => cholmod_half_loads
     procedure :: half_recover => cholmod_half_recover
     final :: cholmod_finalize
  end type cholmod_solver_t

  interface
     function sj_cholmod_create() bind(c, name='sj_cholmod_create') result(h)
       import :: c_ptr
       type(c_ptr) :: h
     end function sj_cholmod_create

     subroutine sj_cholmod_free(h) bind(c, name='sj_cholmod_free')
       import :: c_ptr
       type(c_ptr), value :: h
     end subroutine sj_cholmod_free

     function sj_cholmod_set_node_graph(h, ngroup, first, xadj, adjncy) &
          bind(c, name='sj_cholmod_set_node_graph') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: ngroup
       integer(c_int64_t), intent(in) :: first(*), xadj(*), adjncy(*)
       integer(c_int) :: status
     end function sj_cholmod_set_node_graph
     function sj_cholmod_force_node_metis(h, flag) bind(c, name='sj_cholmod_force_node_metis') result(status)
       import :: c_ptr, c_int
       type(c_ptr), value :: h
       integer(c_int), value :: flag
       integer(c_int) :: status
     end function sj_cholmod_force_node_metis
     function sj_cholmod_set_node_amd_min(h, min) bind(c, name='sj_cholmod_set_node_amd_min') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: min
       integer(c_int) :: status
     end function sj_cholmod_set_node_amd_min
     function sj_cholmod_analyze(h, n, colptr, rowind) bind(c, name='sj_cholmod_analyze') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: n
       integer(c_int64_t) :: colptr(*), rowind(*)
         !! shifted to 0-based during the call and back (the shim keeps no copy)
       integer(c_int) :: status
     end function sj_cholmod_analyze

     function sj_cholmod_can_overlap() bind(c, name='sj_cholmod_can_overlap') result(yes)
       import :: c_int
       integer(c_int) :: yes
     end function sj_cholmod_can_overlap

     function sj_cholmod_analyze_start(h, n, colptr, rowind) bind(c, name='sj_cholmod_analyze_start') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: n
       integer(c_int64_t), intent(in) :: colptr(*), rowind(*)   !! copied (0-based) during the call
       integer(c_int) :: status
     end function sj_cholmod_analyze_start

     function sj_cholmod_analyze_finish(h) bind(c, name='sj_cholmod_analyze_finish') result(status)
       import :: c_ptr, c_int
       type(c_ptr), value :: h
       integer(c_int) :: status
     end function sj_cholmod_analyze_finish

     function sj_cholmod_factorize(h, n, colptr, rowind, val, failed) &
          bind(c, name='sj_cholmod_factorize') result(status)
       import :: c_ptr, c_int, c_int64_t, c_double
       type(c_ptr), value :: h
       integer(c_int64_t), value :: n
       integer(c_int64_t) :: colptr(*), rowind(*)   !! as in sj_cholmod_analyze
       real(c_double), intent(in) :: val(*)
       integer(c_int64_t), intent(out) :: failed
       integer(c_int) :: status
     end function sj_cholmod_factorize

     function sj_cholmod_solve(h, nrhs, b, x) bind(c, name='sj_cholmod_solve') result(status)
       import :: c_ptr, c_int, c_int64_t, c_double
       type(c_ptr), value :: h
       integer(c_int64_t), value :: nrhs
       real(c_double), intent(in) :: b(*)
       real(c_double), intent(out) :: x(*)
       integer(c_int) :: status
     end function sj_cholmod_solve

     function sj_cholmod_solve_ld(h, nrhs, b, ldb, x, ldx) bind(c, name='sj_cholmod_solve_ld') result(status)
       import :: c_ptr, c_int, c_int64_t, c_double
       type(c_ptr), value :: h
       integer(c_int64_t), value :: nrhs, ldb, ldx
       real(c_double), intent(in) :: b(*)
       real(c_double), intent(inout) :: x(*)
       integer(c_int) :: status
     end function sj_cholmod_solve_ld

     function sj_cholmod_pivots(h, d) bind(c, name='sj_cholmod_pivots') result(status)
       import :: c_ptr, c_int, c_double
       type(c_ptr), value :: h
       real(c_double), intent(out) :: d(*)
       integer(c_int) :: status
     end function sj_cholmod_pivots

     function sj_cholmod_info(h, factor_nnz, factor_bytes, flops, peak_bytes, lnz) &
          bind(c, name='sj_cholmod_info') result(status)
       import :: c_ptr, c_int, c_int64_t, c_double
       type(c_ptr), value :: h
       integer(c_int64_t), intent(out) :: factor_nnz
       real(c_double), intent(out) :: factor_bytes, flops, peak_bytes, lnz
       integer(c_int) :: status
     end function sj_cholmod_info

     function sj_cholmod_ordering(h, buf, len) bind(c, name='sj_cholmod_ordering') result(status)
       import :: c_ptr, c_int, c_int64_t, c_char
       type(c_ptr), value :: h
       character(kind=c_char), intent(out) :: buf(*)
       integer(c_int64_t), value :: len
       integer(c_int) :: status
     end function sj_cholmod_ordering

     function sj_cholmod_memory(h, failed_request, inuse) bind(c, name='sj_cholmod_memory') result(status)
       import :: c_ptr, c_int, c_double
       type(c_ptr), value :: h
       real(c_double), intent(out) :: failed_request, inuse
       integer(c_int) :: status
     end function sj_cholmod_memory

     function sj_cholmod_message(h, buf, len) bind(c, name='sj_cholmod_message') result(status)
       import :: c_ptr, c_int, c_int64_t, c_char
       type(c_ptr), value :: h
       character(kind=c_char), intent(out) :: buf(*)
       integer(c_int64_t), value :: len
       integer(c_int) :: status
     end function sj_cholmod_message
  end interface

  interface
     function sj_cholmod_schur_analyze(h, n, nb, colptr, rowind) &
          bind(c, name='sj_cholmod_schur_analyze') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: n, nb
       integer(c_int64_t) :: colptr(*), rowind(*)   !! as in sj_cholmod_analyze
       integer(c_int) :: status
     end function sj_cholmod_schur_analyze

     function sj_cholmod_schur_camd(h, n, nb, colptr, rowind) &
          bind(c, name='sj_cholmod_schur_camd') result(status)
       import :: c_ptr, c_int, c_int64_t
       type(c_ptr), value :: h
       integer(c_int64_t), value :: n, nb
       integer(c_int64_t) :: colptr(*), rowind(*)   !! as in sj_cholmod_analyze
       integer(c_int) :: status
     end function sj_cholmod_schur_camd

     function sj_cholmod_schur_half(h, backward, nrhs, in, ldin, bnd, out, ldout) &
          bind(c, name='sj_cholmod_schur_half') result(status)
       import :: c_ptr, c_int, c_int64_t, c_double
       type(c_ptr), value :: h
       integer(c_int), value :: backward
       integer(c_int64_t), value :: nrhs, ldin, ldout
       real(c_double), intent(in) :: in(*)
       real(c_double), intent(inout) :: bnd(*), out(*)
       integer(c_int) :: status
     end function sj_cholmod_schur_half

     function sj_cholmod_schur_block(h, nb, lbb) bind(c, name='sj_cholmod_schur_block') result(status)
       import :: c_ptr, c_int, c_int64_t, c_double
       type(c_ptr), value :: h
       integer(c_int64_t), value :: nb
       real(c_double), intent(out) :: lbb(*)
       integer(c_int) :: status
     end function sj_cholmod_schur_block
  end interface

contains

  subroutine cholmod_analyze(self, a, error)
    !! Symbolic analysis: fill-reducing ordering (AMD or METIS, the best kept)
    !! and supernodal structure of L from the pattern of a. After
    !! analyze_start (the same pattern): waits for that analysis.
    class(cholmod_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status
    integer(i8) :: one(1)

    if (self%started) then
       self%started = .false.
       status = sj_cholmod_analyze_finish(self%handle)
    else
       if (.not. start_handle(self)) then
          call fatal_error(error, EXIT_IO, 'CHOLMOD: cannot start (out of memory)')
          return
       end if
       if (a%n < 0 .or. .not. allocated(a%colptr)) then
          call fatal_error(error, EXIT_IO, 'CHOLMOD: invalid matrix')
          return
       end if
       status = offer_node_graph(self, a)
       if (status /= SJ_OK) then
          call status_error(self, status, 'analyze', error)
          return
       end if
       one = 1
       if (a%nnz() > 0) then
          status = sj_cholmod_analyze(self%handle, a%n, a%colptr, a%rowind)
       else
          status = sj_cholmod_analyze(self%handle, a%n, a%colptr, one)
       end if
    end if
    if (status /= SJ_OK) then
       call status_error(self, status, 'analyze', error)
       return
    end if
    self%n = a%n
    call update_info(self)
  end subroutine cholmod_analyze

  subroutine cholmod_analyze_start(self, a)
    !! Begin the symbolic analysis of a's pattern on a second thread (the
    !! shim's copy of it) where that may run (sj_cholmod_can_overlap: not
    !! under OMP_NUM_THREADS=1); analyze, with the same pattern, waits for it.
    !! Otherwise, or when it cannot start, nothing happens: analyze does it all.
    class(cholmod_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    if (self%started .or. sj_cholmod_can_overlap() == 0) return
    if (a%n <= 0 .or. a%nnz() <= 0 .or. .not. allocated(a%colptr)) return
    if (.not. start_handle(self)) return
    if (offer_node_graph(self, a) /= SJ_OK) return
    self%started = sj_cholmod_analyze_start(self%handle, a%n, a%colptr, a%rowind) == SJ_OK
  end subroutine cholmod_analyze_start

  function offer_node_graph(self, a) result(status)
    !! Give the shim the node graph of a's columns (set_groups), from
    !! node_graph_min columns on, or take away the previous one; the shim's
    !! status.
    class(cholmod_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(c_int) :: status
    integer(i8) :: one(1), ngroup
    integer(i8), allocatable :: xadj(:), adjncy(:)
    one = 1
    ngroup = 0
    if (allocated(self%group_first)) then
       if (a%n >= self%node_graph_min .and. size(self%group_first, kind=i8) > 1) then
          if (self%group_first(size(self%group_first)) == a%n + 1) ngroup = size(self%group_first, kind=i8) - 1
       end if
    end if
    status = sj_cholmod_force_node_metis(self%handle, metis_mode(self))
    if (status == SJ_OK) status = sj_cholmod_set_node_amd_min(self%handle, self%node_amd_min)
    if (status /= SJ_OK) return
    if (ngroup > 0) then
       call node_graph(a, self%group_first, xadj, adjncy)
       if (size(adjncy) == 0) adjncy = [1_i8]
       status = sj_cholmod_set_node_graph(self%handle, ngroup, self%group_first, xadj, adjncy)
    else
       status = sj_cholmod_set_node_graph(self%handle, 0_c_int64_t, one, one, one)
    end if
  end function offer_node_graph

  pure integer(c_int) function metis_mode(self)
    !! The shim's node-graph METIS mode: 2 alone, 1 offered whatever AMD's fill, 0 as CHOLMOD's test says.
    class(cholmod_solver_t), intent(in) :: self
    metis_mode = 0_c_int
    if (self%force_node_metis) metis_mode = 1_c_int
    if (self%node_metis_only) metis_mode = 2_c_int
  end function metis_mode

  subroutine cholmod_factorize(self, a, error)
    !! Numeric factorization with the values of a (same pattern as analyzed).
    !! Not positive definite: error%code = EXIT_SINGULAR, info%failed_column set.
    class(cholmod_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status
    integer(c_int64_t) :: failed
    integer(i8) :: one(1)
    real(wp) :: zero(1)
    character(len=24) :: buf

    self%factored = .false.
    self%nb_halves = 0   ! a schur's halves belong to its own factor
    self%info%failed_column = 0
    if (.not. c_associated(self%handle) .or. self%n < 0) then
       call fatal_error(error, EXIT_IO, 'CHOLMOD: factorize called before analyze')
       return
    end if
    if (a%n /= self%n) then
       call fatal_error(error, EXIT_IO, 'CHOLMOD: matrix order differs from the analyzed one')
       return
    end if
    one = 1
    zero = 0.0_wp
    if (a%nnz() > 0) then
       status = sj_cholmod_factorize(self%handle, a%n, a%colptr, a%rowind, a%val, failed)
    else
       status = sj_cholmod_factorize(self%handle, a%n, a%colptr, one, zero, failed)
    end if
    call update_info(self)
    if (status == SJ_NOT_POSDEF) then
       self%info%failed_column = failed
       write (buf, '(i0)') failed
       call fatal_error(error, EXIT_SINGULAR, 'matrix is not positive definite at column '//trim(buf))
       return
    end if
    if (status /= SJ_OK) then
       call status_error(self, status, 'factorize', error)
       return
    end if
    self%factored = .true.
  end subroutine cholmod_factorize

  subroutine cholmod_solve(self, b, x, error)
    !! x = A^-1 b for every column of b (shape (n, nrhs)).
    class(cholmod_solver_t), intent(inout) :: self
    real(wp), intent(in) :: b(:, :)
    real(wp), intent(out) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status

    call check_factored(self, error)
    if (allocated(error)) return
    if (size(b, 1, i8) /= self%n .or. size(x, 1, i8) /= self%n .or. size(b, 2) /= size(x, 2)) then
       call fatal_error(error, EXIT_IO, 'CHOLMOD: right-hand side and solution shapes do not match the matrix')
       return
    end if
    if (self%n == 0 .or. size(b, 2) == 0) return
    status = sj_cholmod_solve(self%handle, int(size(b, 2), c_int64_t), b, x)
    if (status /= SJ_OK) call status_error(self, status, 'solve', error)
  end subroutine cholmod_solve

  subroutine cholmod_solve_leading(self, n, b, x, error)
    !! x(1:n, :) = A^-1 b(1:n, :), b and x read and written in place with
    !! their own leading dimensions (no copies of the columns).
    class(cholmod_solver_t), intent(inout) :: self
    integer(i8), intent(in) :: n
    real(wp), contiguous, intent(in) :: b(:, :)
    real(wp), contiguous, intent(inout) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(c_int) :: status

    call check_factored(self, error)
    if (allocated(error)) return
    if (n /= self%n .or. size(b, 1, i8) < n .or. size(x, 1, i8) < n .or. size(b, 2) /= size(x, 2)) then
       call fatal_error(error, EXIT_IO, 'CHOLMOD: right-hand side and solution shapes do not match the matrix')
       return
    end if
    if (self%n == 0 .or. size(b, 2) == 0) return
    status = sj_cholmod_solve_ld(self%handle, int(size(b, 2), c_int64_t), b, int(size(b, 1), c_int64_t), &
         x, int(size(x, 1), c_int64_t))
    if (status /= SJ_OK) call status_error(self, status, 'solve', error)
  end subroutine cholmod_solve_leading

  subroutine check_factored(self, error)
    !! The error of a solve called without a valid factorization.
    class(cholmod_solver_t), intent(in) :: self
    type(error_t), allocatable, intent(out) :: error
    if (.not. self%factored) call fatal_error(error, EXIT_IO, 'CHOLMOD: solve called without a valid factorization')
  end subroutine check_factored

  subroutine cholmod_pivots(self, d)
    !! d(j) = L_jj^2 of original column j (0 for columns a failed factorization
    !! did not reach, including the failing one).
    class(cholmod_solver_t), intent(inout) :: self
    real(wp), intent(out) :: d(:)
    integer(c_int) :: status
    real(wp), allocatable :: tmp(:)

    d = 0.0_wp
    if (.not. c_associated(self%handle) .or. self%n <= 0) return
    if (size(d, kind=i8) < self%n) return
    allocate (tmp(self%n))
    status = sj_cholmod_pivots(self%handle, tmp)
    if (status == SJ_OK) d(1:self%n) = tmp
  end subroutine cholmod_pivots

  subroutine cholmod_release(self)
    !! Free the factor, the pattern copy and CHOLMOD's workspace.
    class(cholmod_solver_t), intent(inout) :: self
    if (c_associated(self%handle)) call sj_cholmod_free(self%handle)   ! after a started analysis ends
    self%handle = c_null_ptr
    self%n = -1
    self%factored = .false.
    self%started = .false.
    self%nb_halves = 0
  end subroutine cholmod_release

  pure function cholmod_flops(self) result(fl)
    !! Flop count of the LL^T factorization (CHOLMOD's estimate from the analysis).
    class(cholmod_solver_t), intent(in) :: self
    real(wp) :: fl
    fl = self%fl
  end function cholmod_flops

  pure function cholmod_peak_mbytes(self) result(mb)
    !! CHOLMOD's peak memory use (MiB) since the solver was created.
    class(cholmod_solver_t), intent(in) :: self
    real(wp) :: mb
    mb = self%peak/MBYTE
  end function cholmod_peak_mbytes

  pure function cholmod_stored_nnz(self) result(nz)
    !! Entries of L as stored by the supernodal factor, including the explicit
    !! zeros of relaxed supernode amalgamation (info%factor_nnz is the
    !! fundamental count nnz(L) of the ordering).
    class(cholmod_solver_t), intent(in) :: self
    integer(i8) :: nz
    nz = self%stored
  end function cholmod_stored_nnz

  subroutine cholmod_finalize(self)
    !! Finalizer: free the C side if the caller forgot release().
    type(cholmod_solver_t), intent(inout) :: self
    if (c_associated(self%handle)) call sj_cholmod_free(self%handle)
    self%handle = c_null_ptr
  end subroutine cholmod_finalize

  ! ---- helpers

  subroutine update_info(self)
    !! Refresh info (ordering, factor size) and statistics from the shim.
    class(cholmod_solver_t), intent(inout) :: self
    integer(c_int) :: status
    integer(c_int64_t) :: fnnz
    real(c_double) :: fbytes, fl, peak, lnz
    character(kind=c_char) :: buf(NAME_LEN)

    status = sj_cholmod_info(self%handle, fnnz, fbytes, fl, peak, lnz)
    if (status == SJ_OK) then
       self%info%factor_nnz = int(lnz, i8)
       self%stored = fnnz
       self%info%factor_mbytes = fbytes/MBYTE
       self%fl = fl
       self%peak = peak
    end if
    status = sj_cholmod_ordering(self%handle, buf, int(NAME_LEN, c_int64_t))
    if (status == SJ_OK) self%info%ordering = from_c(buf)
  end subroutine update_info

  subroutine status_error(self, status, phase, error)
    !! Error for a failed shim call: message from the shim, code by status.
    class(cholmod_solver_t), intent(in) :: self
    integer(c_int), intent(in) :: status
    character(*), intent(in) :: phase
    type(error_t), allocatable, intent(out) :: error
    character(kind=c_char) :: buf(MESSAGE_LEN)
    character(:), allocatable :: msg
    character(len=12) :: code

    msg = ''
    if (sj_cholmod_message(self%handle, buf, int(MESSAGE_LEN, c_int64_t)) == SJ_OK) msg = from_c(buf)
    if (status == CHOLMOD_OUT_OF_MEMORY .or. status == SJ_E_NOMEM) then
       call memory_error(self, phase, error)
       return
    else if (status == CHOLMOD_TOO_LARGE) then
       if (len(msg) == 0) msg = 'problem too large'
    else if (len(msg) == 0) then
       write (code, '(i0)') status
       msg = 'status '//trim(code)
    end if
    call fatal_error(error, EXIT_IO, 'CHOLMOD '//phase//' failed: '//msg)
  end subroutine status_error

  subroutine memory_error(self, phase, error)
    !! EXIT_IO error for CHOLMOD out of memory: the request that failed, what
    !! CHOLMOD already held, and (after the analysis) the size of the factor.
    class(cholmod_solver_t), intent(in) :: self
    character(*), intent(in) :: phase
    type(error_t), allocatable, intent(out) :: error
    real(c_double) :: request, inuse
    integer(c_int) :: status
    character(:), allocatable :: msg
    status = sj_cholmod_memory(self%handle, request, inuse)
    if (status /= SJ_OK) then
       request = 0.0_wp
       inuse = 0.0_wp
    end if
    if (request > 0.0_wp) then
       msg = oom_message('CHOLMOD '//phase, int(request, i8) + int(inuse, i8))// &
            ' (an allocation of '//bytes_text(int(request, i8))//' failed with '// &
            bytes_text(int(inuse, i8))//' in use)'
    else
       msg = oom_message('CHOLMOD '//phase, int(inuse, i8))//' or more'
    end if
    if (phase == 'factorize' .and. self%info%factor_mbytes > 0.0_wp) &
         msg = msg//'; the factor alone needs '//bytes_text(int(self%info%factor_mbytes*MBYTE, i8))
    call fatal_error(error, EXIT_IO, msg)
  end subroutine memory_error

  pure function from_c(buf) result(s)
    !! Fortran string from a NUL-terminated C buffer.
    character(kind=c_char), intent(in) :: buf(:)
    character(:), allocatable :: s
    integer :: i, n
    n = size(buf)
    do i = 1, size(buf)
       if (buf(i) == c_null_char) then
          n = i - 1
          exit
       end if
    end do
    allocate (character(len=n) :: s)
    do i = 1, n
       s(i:i) = buf(i)
    end do
  end function from_c

  ! ---- static condensation with the boundary ordered last (issue 24)

  subroutine cholmod_schur(self, a, nb, kstar, error)
    !! K* = a_bb − a_bi a_ii⁻¹ a_ib from one factorization of the whole part
    !! (the contract of linear_solver_t%schur). The interior is ordered as
    !! analyze orders any matrix (a_ii alone), the boundary appended last, and
    !! a + D factored, D = diag(a_bb) on the boundary (1 where a column has no
    !! stiffness): K* + D is positive definite even when the part floats. Then
    !! K* = L_bb L_bbᵀ − D, with an added error of order ε·√(d_i d_j) per
    !! entry, the scale of the cancellation already in a_bb − a_bi a_ii⁻¹ a_ib.
    !! The interior block L_ii is the factor of a_ii: solve and pivots use it.
    !! A breakdown in the boundary block (a not semi-definite) falls back to
    !! the default route.
    class(cholmod_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(out) :: kstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: val(:), shift(:)
    integer(c_int) :: status
    integer(c_int64_t) :: failed
    integer(i8) :: ni

    ni = a%n - nb
    call boundary_shift(a, nb, val, shift)
    if (ni == 0 .or. nb == 0 .or. .not. allocated(val)) then
       call schur_by_solves(self, a, nb, kstar, error)
       return
    end if
    call schur_order(self, a, nb, status, error)
    if (allocated(error)) return
    if (status /= SJ_OK) then
       call status_error(self, status, 'analyze', error)
       return
    end if
    self%n = a%n
    status = sj_cholmod_factorize(self%handle, a%n, a%colptr, a%rowind, val, failed)
    call update_info(self)
    if (status == SJ_NOT_POSDEF .and. failed > ni) then
       call schur_by_solves(self, a, nb, kstar, error)
       return
    else if (status == SJ_NOT_POSDEF) then
       self%info%failed_column = failed
       call fatal_error(error, EXIT_SINGULAR, 'matrix is not positive definite at column '//itoa(failed))
       return
    else if (status /= SJ_OK) then
       call status_error(self, status, 'factorize', error)
       return
    end if
    self%n = ni
    self%factored = .true.
    call trailing_product(self, nb, shift, kstar, error)
  end subroutine cholmod_schur

  subroutine schur_order(self, a, nb, status, error)
    !! The boundary-last analysis of a: CAMD on the whole part alone where its
    !! fill is low by CHOLMOD's test (no analysis of the interior, whose
    !! ordering would then be AMD's); otherwise the interior analyzed as any
    !! matrix and the cheaper of its ordering and CAMD's kept.
    class(cholmod_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    integer(c_int), intent(out) :: status
    type(error_t), allocatable, intent(out) :: error
    type(sparse_sym_t) :: aii

    status = SJ_TRY_INTERIOR
    if (self%camd_first) then
       if (start_handle(self)) status = sj_cholmod_schur_camd(self%handle, a%n, nb, a%colptr, a%rowind)
    end if
    if (status /= SJ_TRY_INTERIOR) return
    call interior_block(a, nb, aii)
    call self%analyze(aii, error)
    if (allocated(error)) return
    status = sj_cholmod_schur_analyze(self%handle, a%n, nb, a%colptr, a%rowind)
  end subroutine schur_order

  logical function start_handle(self) result(ok)
    !! Reset the analysis' info and create the shim's handle if there is none;
    !! .false. when CHOLMOD cannot start.
    class(cholmod_solver_t), intent(inout) :: self
    self%factored = .false.
    self%n = -1
    self%nb_halves = 0
    self%info%name = 'CHOLMOD supernodal LL^T'
    self%info%ordering = 'none'
    self%info%factor_nnz = 0
    self%info%factor_mbytes = 0.0_wp
    self%info%failed_column = 0
    if (.not. c_associated(self%handle)) self%handle = sj_cholmod_create()
    ok = c_associated(self%handle)
  end function start_handle

  subroutine trailing_product(self, nb, shift, kstar, error)
    !! kstar = L_bb L_bbᵀ − diag(shift), both triangles (unshift).
    class(cholmod_solver_t), intent(inout) :: self
    integer(i8), intent(in) :: nb
    real(wp), intent(in) :: shift(:)
    real(wp), intent(out) :: kstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: lbb(:, :)
    integer(c_int) :: status
    integer :: stat
    allocate (lbb(nb, nb), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the boundary block of the condensation', nb*nb*BYTES_REAL)
       return
    end if
    status = sj_cholmod_schur_block(self%handle, nb, lbb)
    if (status /= SJ_OK) then
       call status_error(self, status, 'factorize', error)
       return
    end if
    kstar = 0.0_wp
    call dsyrk('L', 'N', int(nb), int(nb), 1.0_wp, lbb, int(nb), 0.0_wp, kstar, int(nb))
    call unshift(shift, kstar)
    self%nb_halves = nb
  end subroutine trailing_product

  subroutine cholmod_half_loads(self, f, y, fstar, done, error)
    !! f* = f_b − a_bi a_ii⁻¹ f_i from the forward half of a solve with the
    !! whole part's boundary-last factor (P A P' = L L', A's boundary block
    !! shifted by D): z = L⁻¹ P f, whose boundary rows are L_bb⁻¹ P_b f*
    !! (L_bi L_iiᵀ = a_bi, D only in L_bb), so f* = L_bb z_b, L_bb read in
    !! the factor (sj_cholmod_schur_half); y keeps z's interior rows (P's
    !! order) for half_recover. done = .false. without such a factor (schur
    !! fell back to solves) or for other shapes.
    class(cholmod_solver_t), intent(inout) :: self
    real(wp), contiguous, intent(in) :: f(:, :)
    real(wp), allocatable, intent(inout) :: y(:, :)
    real(wp), intent(inout) :: fstar(:, :)
    logical, intent(out) :: done
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: ni, n
    integer(c_int) :: status
    done = .false.
    if (self%nb_halves <= 0 .or. .not. self%factored) return
    ni = self%n
    n = ni + self%nb_halves
    if (size(f, 1, i8) /= n .or. size(fstar, 1, i8) /= self%nb_halves .or. size(fstar, 2) /= size(f, 2)) return
    done = .true.
    if (allocated(y)) deallocate (y)
    allocate (y(ni, size(f, 2)))
    if (size(f, 2) == 0) return
    status = sj_cholmod_schur_half(self%handle, 0_c_int, int(size(f, 2), c_int64_t), f, int(n, c_int64_t), &
         fstar, y, int(ni, c_int64_t))
    if (status /= SJ_OK) call status_error(self, status, 'solve', error)
  end subroutine cholmod_half_loads

  subroutine cholmod_half_recover(self, y, ub, x, done, error)
    !! x(1:ni, :) = a_ii⁻¹ (f_i − a_ib u_b) from y of half_loads (the same f)
    !! and ub: the backward half of the solve on [y; L_bbᵀ P_b u_b], whose
    !! boundary rows come back as P_b u_b and whose interior rows are
    !! L_ii⁻ᵀ (y − L_biᵀ P_b u_b) = P_i a_ii⁻¹ (f_i − a_ib u_b).
    class(cholmod_solver_t), intent(inout) :: self
    real(wp), contiguous, intent(in) :: y(:, :), ub(:, :)
    real(wp), contiguous, intent(inout) :: x(:, :)
    logical, intent(out) :: done
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: b(:, :)
    integer(i8) :: ni
    integer(c_int) :: status
    done = .false.
    if (self%nb_halves <= 0 .or. .not. self%factored) return
    ni = self%n
    if (size(y, 1, i8) /= ni .or. size(ub, 1, i8) /= self%nb_halves .or. size(x, 1, i8) < ni .or. &
        size(y, 2) /= size(ub, 2) .or. size(x, 2) /= size(y, 2)) return
    done = .true.
    if (size(y, 2) == 0) return
    b = ub   ! (the shim's bnd argument is read-write)
    status = sj_cholmod_schur_half(self%handle, 1_c_int, int(size(y, 2), c_int64_t), y, int(ni, c_int64_t), &
         b, x, int(size(x, 1), c_int64_t))
    if (status /= SJ_OK) call status_error(self, status, 'solve', error)
  end subroutine cholmod_half_recover
end module superjoin_solvers_cholmod
