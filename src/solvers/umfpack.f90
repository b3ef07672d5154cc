module superjoin_solvers_umfpack
  !! Sparse LU (UMFPACK) behind the linear_solver_t interface.
  !!
  !! The upper triangle is expanded to the full matrix in 0-based CSC (int64),
  !! kept for the whole life of the factor (UMFPACK's iterative refinement in
  !! the solve phase needs A). Factorization P R A Q = L U with the row scaling
  !! R of UMFPACK's defaults. The solver is not copyable (a copy would share
  !! the Symbolic/Numeric objects): use it in place and call release().
  use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_long, &
       c_double, c_loc
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR, EXIT_IO
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_solver, only: linear_solver_t
  implicit none (type, external)
  private

  integer, parameter :: UMFPACK_INFO = 90                 !! size of Info
  integer, parameter :: UMFPACK_CONTROL = 20              !! size of Control
  integer, parameter :: UMFPACK_STATUS = 0                !! Info index: status
  integer, parameter :: UMFPACK_SIZE_OF_UNIT = 3          !! Info index: bytes per Unit
  integer, parameter :: UMFPACK_STRATEGY_USED = 18        !! Info index: strategy
  integer, parameter :: UMFPACK_ORDERING_USED = 19        !! Info index: ordering
  integer, parameter :: UMFPACK_NUMERIC_SIZE = 40         !! Info index: Numeric size (Units)
  integer, parameter :: UMFPACK_FLOPS = 42                !! Info index: flop count
  integer(c_long), parameter :: UMFPACK_A = 0             !! solve A x = b
  integer(c_long), parameter :: UMFPACK_OK = 0
  integer(c_long), parameter :: UMFPACK_WARNING_SINGULAR = 1
  integer(c_long), parameter :: UMFPACK_ERROR_OUT_OF_MEMORY = -1
  integer, parameter :: UMFPACK_STRATEGY_UNSYMMETRIC = 1
  integer, parameter :: UMFPACK_ORDERING_CHOLMOD = 0
  integer, parameter :: UMFPACK_ORDERING_AMD = 1
  integer, parameter :: UMFPACK_ORDERING_GIVEN = 2
  integer, parameter :: UMFPACK_ORDERING_METIS = 3
  integer, parameter :: UMFPACK_ORDERING_BEST = 4
  integer, parameter :: UMFPACK_ORDERING_NONE = 5
  integer, parameter :: UMFPACK_ORDERING_USER = 6
  real(wp), parameter :: MBYTE = 1048576.0_wp             !! bytes per MiB

  type, extends(linear_solver_t), public :: umfpack_solver_t
    !! UMFPACK sparse LU.
     private
     integer(i8) :: n = -1                       !! order of the analyzed matrix (-1: none)
     integer(c_long), allocatable :: ap(:)       !! full CSC column pointers, 0-based (n+1)
     integer(c_long), allocatable :: ai(:)       !! full CSC row indices, 0-based
     real(c_double), allocatable :: ax(:)        !! full CSC values
     real(c_double) :: control(0:UMFPACK_CONTROL - 1) = 0.0_c_double
     real(c_double) :: uinfo(0:UMFPACK_INFO - 1) = 0.0_c_double
     type(c_ptr) :: symbolic = c_null_ptr
     type(c_ptr) :: numeric = c_null_ptr
     logical :: factored = .false.
     real(wp) :: fl = 0.0_wp
   contains
     procedure :: analyze => umf_analyze
     procedure :: factorize => umf_factorize
     procedure :: solve => umf_solve
     procedure :: pivots => umf_pivots
     procedure :: release => umf_release
     procedure :: flops => umf_flops
     final :: umf_finalize
  end type umfpack_solver_t

  interface
     subroutine umfpack_dl_defaults(control) bind(c, name='umfpack_dl_defaults')
       import :: c_double
       real(c_double), intent(out) :: control(*)
     end subroutine umfpack_dl_defaults

     function umfpack_dl_symbolic(n_row, n_col, ap, ai, ax, symbolic, control, info) &
          bind(c, name='umfpack_dl_symbolic') result(status)
       import :: c_long, c_double, c_ptr
       integer(c_long), value :: n_row, n_col
       integer(c_long), intent(in) :: ap(*), ai(*)
       real(c_double), intent(in) :: ax(*)
       type(c_ptr), intent(out) :: symbolic
       real(c_double), intent(in) :: control(*)
       real(c_double), intent(inout) :: info(*)
       integer(c_long) :: status
     end function umfpack_dl_symbolic

     function umfpack_dl_numeric(ap, ai, ax, symbolic, numeric, control, info) &
          bind(c, name='umfpack_dl_numeric') result(status)
       import :: c_long, c_double, c_ptr
       integer(c_long), intent(in) :: ap(*), ai(*)
       real(c_double), intent(in) :: ax(*)
       type(c_ptr), value :: symbolic
       type(c_ptr), intent(out) :: numeric
       real(c_double), intent(in) :: control(*)
       real(c_double), intent(inout) :: info(*)
       integer(c_long) :: status
     end function umfpack_dl_numeric

     function umfpack_dl_solve(sys, ap, ai, ax, x, b, numeric, control, info) &
          bind(c, name='umfpack_dl_solve') result(status)
       import :: c_long, c_double, c_ptr
       integer(c_long), value :: sys
       integer(c_long), intent(in) :: ap(*), ai(*)
       real(c_double), intent(in) :: ax(*)
       real(c_double), intent(out) :: x(*)
       real(c_double), intent(in) :: b(*)
       type(c_ptr), value :: numeric
       real(c_double), intent(in) :: control(*)
       real(c_double), intent(inout) :: info(*)
       integer(c_long) :: status
     end function umfpack_dl_solve

     subroutine umfpack_dl_free_symbolic(symbolic) bind(c, name='umfpack_dl_free_symbolic')
       import :: c_ptr
       type(c_ptr), intent(inout) :: symbolic
     end subroutine umfpack_dl_free_symbolic

     subroutine umfpack_dl_free_numeric(numeric) bind(c, name='umfpack_dl_free_numeric')
       import :: c_ptr
       type(c_ptr), intent(inout) :: numeric
     end subroutine umfpack_dl_free_numeric

     function umfpack_dl_get_lunz(lnz, unz, n_row, n_col, nz_udiag, numeric) &
          bind(c, name='umfpack_dl_get_lunz') result(status)
       import :: c_long, c_ptr
       integer(c_long), intent(out) :: lnz, unz, n_row, n_col, nz_udiag
       type(c_ptr), value :: numeric
       integer(c_long) :: status
     end function umfpack_dl_get_lunz

     function sj_umfpack_get_diagonal(numeric, p, q, dx, do_recip, rs) &
          bind(c, name='sj_umfpack_get_diagonal') result(status)
       !! umfpack_dl_get_numeric without L and U (umfpack_shim.c): the
       !! permutations, the diagonal of U and the row scaling. All array
       !! arguments are pointers so that the unwanted ones can be NULL.
       import :: c_long, c_ptr
       type(c_ptr), value :: numeric, p, q, dx, do_recip, rs
       integer(c_long) :: status
     end function sj_umfpack_get_diagonal
  end interface

contains

  subroutine umf_analyze(self, a, error)
    !! Expand the pattern to the full matrix and run UMFPACK's symbolic analysis.
    class(umfpack_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_long) :: status

    call umf_release(self)
    self%info%name = 'UMFPACK LU'
    self%info%ordering = 'none'
    self%info%factor_nnz = 0
    self%info%factor_mbytes = 0.0_wp
    self%info%failed_column = 0
    if (a%n < 0 .or. .not. allocated(a%colptr)) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: invalid matrix')
       return
    end if
    call expand_full(a, self%ap, self%ai, self%ax, error)
    if (allocated(error)) return
    call umfpack_dl_defaults(self%control)
    self%uinfo = 0.0_c_double
    self%n = a%n
    if (a%n == 0) then
       self%info%ordering = 'natural'
       return
    end if
    status = umfpack_dl_symbolic(int(a%n, c_long), int(a%n, c_long), self%ap, self%ai, self%ax, &
         self%symbolic, self%control, self%uinfo)
    if (status /= UMFPACK_OK) then
       call umf_status_error(status, 'symbolic analysis', error)
       call umf_release(self)
       return
    end if
    self%info%ordering = ordering_name(nint(self%uinfo(UMFPACK_ORDERING_USED)), &
         nint(self%uinfo(UMFPACK_STRATEGY_USED)))
  end subroutine umf_analyze

  subroutine umf_factorize(self, a, error)
    !! Numeric LU with the values of a (same pattern as analyzed). A singular
    !! matrix gives EXIT_SINGULAR with info%failed_column = the original column
    !! of the first zero pivot of U (0 if none can be identified).
    class(umfpack_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(c_long) :: status, lnz, unz, nrow, ncol, nzud
    character(len=24) :: buf

    self%factored = .false.
    self%info%failed_column = 0
    if (self%n < 0 .or. .not. allocated(self%ap)) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: factorize called before analyze')
       return
    end if
    if (a%n /= self%n) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: matrix pattern differs from the analyzed one')
       return
    end if
    if (c_associated(self%numeric)) call umfpack_dl_free_numeric(self%numeric)
    self%numeric = c_null_ptr
    call refill_values(a, self%ap, self%ai, self%ax, error)
    if (allocated(error)) return
    if (self%n == 0) then
       self%factored = .true.
       return
    end if
    status = umfpack_dl_numeric(self%ap, self%ai, self%ax, self%symbolic, self%numeric, &
         self%control, self%uinfo)
    if (status == UMFPACK_OK .or. status == UMFPACK_WARNING_SINGULAR) then
       self%fl = self%uinfo(UMFPACK_FLOPS)
       self%info%factor_mbytes = self%uinfo(UMFPACK_NUMERIC_SIZE)*self%uinfo(UMFPACK_SIZE_OF_UNIT)/MBYTE
       if (umfpack_dl_get_lunz(lnz, unz, nrow, ncol, nzud, self%numeric) == UMFPACK_OK) &
            self%info%factor_nnz = int(lnz, i8) + int(unz, i8) - self%n
    end if
    if (status == UMFPACK_WARNING_SINGULAR) then
       self%info%failed_column = first_zero_pivot(self)
       if (self%info%failed_column > 0) then
          write (buf, '(i0)') self%info%failed_column
          call fatal_error(error, EXIT_SINGULAR, 'matrix is singular at column '//trim(buf))
       else
          call fatal_error(error, EXIT_SINGULAR, 'matrix is singular')
       end if
       return
    end if
    if (status /= UMFPACK_OK) then
       call umf_status_error(status, 'numeric factorization', error)
       if (c_associated(self%numeric)) call umfpack_dl_free_numeric(self%numeric)
       self%numeric = c_null_ptr
       return
    end if
    self%factored = .true.
  end subroutine umf_factorize

  subroutine umf_solve(self, b, x, error)
    !! x = A^-1 b column by column (UMFPACK_A, with UMFPACK's iterative refinement).
    class(umfpack_solver_t), intent(inout) :: self
    real(wp), intent(in) :: b(:, :)
    real(wp), intent(out) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer(c_long) :: status
    integer :: k
    real(c_double), allocatable :: bk(:), xk(:)

    if (.not. self%factored) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: solve called without a valid factorization')
       return
    end if
    if (size(b, 1, i8) /= self%n .or. size(x, 1, i8) /= self%n .or. size(b, 2) /= size(x, 2)) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: right-hand side and solution shapes do not match the matrix')
       return
    end if
    if (self%n == 0 .or. size(b, 2) == 0) return
    allocate (bk(self%n), xk(self%n))
    do k = 1, size(b, 2)
       bk = b(:, k)
       status = umfpack_dl_solve(UMFPACK_A, self%ap, self%ai, self%ax, xk, bk, self%numeric, &
            self%control, self%uinfo)
       if (status /= UMFPACK_OK .and. status /= UMFPACK_WARNING_SINGULAR) then
          call umf_status_error(status, 'solve', error)
          return
       end if
       x(:, k) = xk
    end do
  end subroutine umf_solve

  subroutine umf_pivots(self, d)
    !! d(j) = U_kk with the row scaling undone, for the original column j = Q(k):
    !! the pivot of column j in the unscaled elimination (0 without a factor).
    class(umfpack_solver_t), intent(inout) :: self
    real(wp), intent(out) :: d(:)
    integer(c_long), allocatable, target :: p(:), q(:)
    real(c_double), allocatable, target :: dx(:), rs(:)
    integer(c_long), target :: do_recip
    integer(i8) :: k, n
    integer(c_long) :: status

    d = 0.0_wp
    n = self%n
    if (n <= 0 .or. .not. c_associated(self%numeric)) return
    if (size(d, kind=i8) < n) return
    allocate (p(n), q(n), dx(n), rs(n))
    status = sj_umfpack_get_diagonal(self%numeric, c_loc(p), c_loc(q), c_loc(dx), c_loc(do_recip), c_loc(rs))
    if (status /= UMFPACK_OK) return
    do k = 1, n
       if (do_recip /= 0) then
          ! row P(k) of A was multiplied by rs: divide it back out
          d(q(k) + 1) = dx(k)/rs(p(k) + 1)
       else
          ! row P(k) of A was divided by rs
          d(q(k) + 1) = dx(k)*rs(p(k) + 1)
       end if
    end do
  end subroutine umf_pivots

  subroutine umf_release(self)
    !! Free the Symbolic and Numeric objects and the expanded matrix.
    class(umfpack_solver_t), intent(inout) :: self
    if (c_associated(self%numeric)) call umfpack_dl_free_numeric(self%numeric)
    if (c_associated(self%symbolic)) call umfpack_dl_free_symbolic(self%symbolic)
    self%numeric = c_null_ptr
    self%symbolic = c_null_ptr
    if (allocated(self%ap)) deallocate (self%ap)
    if (allocated(self%ai)) deallocate (self%ai)
    if (allocated(self%ax)) deallocate (self%ax)
    self%n = -1
    self%factored = .false.
  end subroutine umf_release

  pure function umf_flops(self) result(fl)
    !! Flop count of the last numeric factorization (UMFPACK Info).
    class(umfpack_solver_t), intent(in) :: self
    real(wp) :: fl
    fl = self%fl
  end function umf_flops

  subroutine umf_finalize(self)
    !! Finalizer: free UMFPACK's objects if the caller forgot release().
    type(umfpack_solver_t), intent(inout) :: self
    if (c_associated(self%numeric)) call umfpack_dl_free_numeric(self%numeric)
    if (c_associated(self%symbolic)) call umfpack_dl_free_symbolic(self%symbolic)
    self%numeric = c_null_ptr
    self%symbolic = c_null_ptr
  end subroutine umf_finalize

  ! ---- helpers

  function first_zero_pivot(self) result(col)
    !! Original column (1-based) of the first exactly zero diagonal entry of U, or 0.
    class(umfpack_solver_t), intent(inout) :: self
    integer(i8) :: col
    integer(c_long), allocatable, target :: q(:)
    real(c_double), allocatable, target :: dx(:)
    integer(i8) :: k

    col = 0
    if (self%n <= 0 .or. .not. c_associated(self%numeric)) return
    allocate (q(self%n), dx(self%n))
    if (sj_umfpack_get_diagonal(self%numeric, c_null_ptr, c_loc(q), c_loc(dx), c_null_ptr, c_null_ptr) &
         /= UMFPACK_OK) return
    do k = 1, self%n
       if (dx(k) == 0.0_c_double .or. dx(k) /= dx(k)) then
          col = q(k) + 1
          return
       end if
    end do
  end function first_zero_pivot

  subroutine expand_full(a, ap, ai, ax, error)
    !! Full CSC (0-based) of the symmetric matrix whose upper triangle is a.
    !! Column j: rows i < j from a's column j, the diagonal, then rows i > j
    !! (entries (j, i) of a's columns i > j), all in increasing row order.
    type(sparse_sym_t), intent(in) :: a
    integer(c_long), allocatable, intent(out) :: ap(:), ai(:)
    real(c_double), allocatable, intent(out) :: ax(:)
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: n, j, k, i, nfull
    integer(i8), allocatable :: cnt(:)
    integer :: stat
    logical :: same

    n = a%n
    allocate (ap(n + 1), cnt(n), stat=stat)
    if (stat /= 0) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: out of memory expanding the matrix')
       return
    end if
    ! entries per full column: own upper column plus the transposed off-diagonals
    do j = 1, n
       cnt(j) = a%colptr(j + 1) - a%colptr(j)
    end do
    do j = 1, n
       do k = a%colptr(j), a%colptr(j + 1) - 2
          i = a%rowind(k)
          cnt(i) = cnt(i) + 1
       end do
    end do
    ap(1) = 0
    do j = 1, n
       ap(j + 1) = ap(j) + cnt(j)
    end do
    nfull = ap(n + 1)
    allocate (ai(max(nfull, 1_i8)), ax(max(nfull, 1_i8)), stat=stat)
    if (stat /= 0) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: out of memory expanding the matrix')
       return
    end if
    ai = -1
    ax = 0.0_c_double
    call scatter(a, ap, cnt, ai, ax, same)
  end subroutine expand_full

  subroutine refill_values(a, ap, ai, ax, error)
    !! Refill the values of the full CSC from a, checking that its pattern is
    !! the one expanded by expand_full.
    type(sparse_sym_t), intent(in) :: a
    integer(c_long), intent(in) :: ap(:)
    integer(c_long), intent(inout) :: ai(:)
    real(c_double), intent(inout) :: ax(:)
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: cnt(:)
    integer(i8) :: j, k
    integer :: stat
    logical :: same
    allocate (cnt(a%n), stat=stat)
    if (stat /= 0) then
       call fatal_error(error, EXIT_IO, 'UMFPACK: out of memory')
       return
    end if
    do j = 1, a%n
       cnt(j) = a%colptr(j + 1) - a%colptr(j)
    end do
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 2
          cnt(a%rowind(k)) = cnt(a%rowind(k)) + 1
       end do
    end do
    do j = 1, a%n
       if (ap(j + 1) - ap(j) /= cnt(j)) then
          call fatal_error(error, EXIT_IO, 'UMFPACK: matrix pattern differs from the analyzed one')
          return
       end if
    end do
    call scatter(a, ap, cnt, ai, ax, same)
    if (.not. same) call fatal_error(error, EXIT_IO, 'UMFPACK: matrix pattern differs from the analyzed one')
  end subroutine refill_values

  pure subroutine scatter(a, ap, nxt, ai, ax, same)
    !! Place the entries of a into the full CSC given its column pointers ap;
    !! nxt is workspace of size n; same tells whether the row indices already
    !! in ai were those written.
    type(sparse_sym_t), intent(in) :: a
    integer(c_long), intent(in) :: ap(:)
    integer(i8), intent(out) :: nxt(:)
    integer(c_long), intent(inout) :: ai(:)
    real(c_double), intent(inout) :: ax(:)
    logical, intent(out) :: same
    integer(i8) :: j, k, i, len_up, pos
    integer(c_long) :: row

    same = .true.
    ! first the upper part (with diagonal) of every column, at its start
    do j = 1, a%n
       len_up = a%colptr(j + 1) - a%colptr(j)
       pos = ap(j) + 1
       do k = a%colptr(j), a%colptr(j + 1) - 1
          row = int(a%rowind(k) - 1, c_long)
          if (ai(pos) /= row) same = .false.
          ai(pos) = row
          ax(pos) = a%val(k)
          pos = pos + 1
       end do
       nxt(j) = ap(j) + 1 + len_up
    end do
    ! then the strictly lower part: entry (i, j) of a, i < j, is (j, i) of A;
    ! columns j are visited in increasing order, so rows stay sorted
    do j = 1, a%n
       row = int(j - 1, c_long)
       do k = a%colptr(j), a%colptr(j + 1) - 2
          i = a%rowind(k)
          if (ai(nxt(i)) /= row) same = .false.
          ai(nxt(i)) = row
          ax(nxt(i)) = a%val(k)
          nxt(i) = nxt(i) + 1
       end do
    end do
  end subroutine scatter

  pure function ordering_name(ordering, strategy) result(name)
    !! Name of the ordering UMFPACK used.
    integer, intent(in) :: ordering, strategy
    character(:), allocatable :: name
    select case (ordering)
    case (UMFPACK_ORDERING_AMD)
       if (strategy == UMFPACK_STRATEGY_UNSYMMETRIC) then
          name = 'COLAMD'
       else
          name = 'AMD'
       end if
    case (UMFPACK_ORDERING_METIS)
       name = 'METIS'
    case (UMFPACK_ORDERING_GIVEN)
       name = 'given'
    case (UMFPACK_ORDERING_NONE)
       name = 'natural'
    case (UMFPACK_ORDERING_CHOLMOD)
       name = 'CHOLMOD'
    case (UMFPACK_ORDERING_BEST)
       name = 'best'
    case (UMFPACK_ORDERING_USER)
       name = 'user'
    case default
       name = 'unknown'
    end select
  end function ordering_name

  subroutine umf_status_error(status, phase, error)
    !! Error for a failed UMFPACK call.
    integer(c_long), intent(in) :: status
    character(*), intent(in) :: phase
    type(error_t), allocatable, intent(out) :: error
    character(len=24) :: buf
    if (status == UMFPACK_ERROR_OUT_OF_MEMORY) then
       call fatal_error(error, EXIT_IO, 'UMFPACK '//phase//' failed: out of memory')
    else
       write (buf, '(i0)') status
       call fatal_error(error, EXIT_IO, 'UMFPACK '//phase//' failed: status '//trim(buf))
    end if
  end subroutine umf_status_error
end module superjoin_solvers_umfpack
