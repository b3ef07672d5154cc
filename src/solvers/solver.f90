module superjoin_solvers_solver
  !! The abstract linear solver: symbolic (analyze), numeric (factorize) and
  !! solve phases for a symmetric sparse matrix.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  implicit none (type, external)
  private

  public :: interior_block, boundary_block, schur_by_solves, boundary_shift, unshift, subtract_bi, subtract_ib

  integer(i8), parameter :: SCHUR_BLOCK = 64
    !! Columns of a_ib solved together by the default schur.

  type, public :: solver_info_t
    !! What a solver reports about itself after analyze/factorize.
     character(:), allocatable :: name       !! e.g. 'CHOLMOD supernodal LL^T'
     character(:), allocatable :: ordering   !! e.g. 'METIS', 'AMD', 'natural'
     integer(i8) :: factor_nnz = 0           !! entries in the factor (L, or L+U)
     real(wp) :: factor_mbytes = 0.0_wp      !! memory held by the factor
     integer(i8) :: failed_column = 0        !! original column where factorization broke down (0: none)
  end type solver_info_t

  type, abstract, public :: linear_solver_t
    !! A direct solver for K x = b, K symmetric.
     type(solver_info_t) :: info
     integer(i8), allocatable :: group_first(:)
       !! optional: columns come in groups (nodes), group g = first(g)..first(g+1)-1
   contains
     procedure(analyze_i), deferred :: analyze
     procedure(factorize_i), deferred :: factorize
     procedure(solve_i), deferred :: solve
     procedure(pivots_i), deferred :: pivots
     procedure(release_i), deferred :: release
     procedure :: set_groups
     procedure :: analyze_start
     procedure :: solve_leading
     procedure :: schur => schur_by_solves
     procedure :: half_loads
     procedure :: half_recover
  end type linear_solver_t

  abstract interface
     subroutine analyze_i(self, a, error)
       !! Symbolic phase: ordering and fill from the pattern of a.
       import :: linear_solver_t, sparse_sym_t, error_t
       class(linear_solver_t), intent(inout) :: self
       type(sparse_sym_t), intent(in) :: a
       type(error_t), allocatable, intent(out) :: error
     end subroutine analyze_i
     subroutine factorize_i(self, a, error)
       !! Numeric phase. On breakdown: error%code = EXIT_SINGULAR and
       !! self%info%failed_column = the original column index.
       import :: linear_solver_t, sparse_sym_t, error_t
       class(linear_solver_t), intent(inout) :: self
       type(sparse_sym_t), intent(in) :: a
       type(error_t), allocatable, intent(out) :: error
     end subroutine factorize_i
     subroutine solve_i(self, b, x, error)
       !! Solve with the factor: x(n, nrhs) = K^-1 b(n, nrhs).
       import :: linear_solver_t, wp, error_t
       class(linear_solver_t), intent(inout) :: self
       real(wp), intent(in) :: b(:, :)
       real(wp), intent(out) :: x(:, :)
       type(error_t), allocatable, intent(out) :: error
     end subroutine solve_i
     subroutine pivots_i(self, d)
       !! Pivot of each original column: D_jj such that K_jj / D_jj is the
       !! diagonal decay ratio (LL^T: L_jj^2; LU: U_jj with scaling undone).
       import :: linear_solver_t, wp
       class(linear_solver_t), intent(inout) :: self
       real(wp), intent(out) :: d(:)
     end subroutine pivots_i
     subroutine release_i(self)
       !! Free everything the solver holds.
       import :: linear_solver_t
       class(linear_solver_t), intent(inout) :: self
     end subroutine release_i
  end interface
contains

  subroutine half_loads(self, f, y, fstar, done, error)
    !! After schur: f* = f_b − a_bi a_ii⁻¹ f_i for the columns of f (the
    !! part's rows, interior then boundary; fstar holds f_b on entry) from
    !! half a solve, y what half_recover needs of it. This default does
    !! nothing (done = .false., fstar and y untouched: the caller solves with
    !! a_ii); a solver that keeps the whole part's boundary-last factor
    !! overrides it (CHOLMOD).
    class(linear_solver_t), intent(inout) :: self
    real(wp), contiguous, intent(in) :: f(:, :)
    real(wp), allocatable, intent(inout) :: y(:, :)
    real(wp), intent(inout) :: fstar(:, :)
    logical, intent(out) :: done
    type(error_t), allocatable, intent(out) :: error
    done = .false.
    associate (no_use => self, no_f => f, no_y => allocated(y), no_fstar => fstar)   ! the caller solves
    end associate
  end subroutine half_loads

  subroutine half_recover(self, y, ub, x, done, error)
    !! After half_loads(f, y, ...): x(1:ni, :) = a_ii⁻¹ (f_i − a_ib u_b) for
    !! the boundary values ub (nb rows) from the other half of the solve.
    !! This default does nothing (done = .false., x untouched).
    class(linear_solver_t), intent(inout) :: self
    real(wp), contiguous, intent(in) :: y(:, :), ub(:, :)
    real(wp), contiguous, intent(inout) :: x(:, :)
    logical, intent(out) :: done
    type(error_t), allocatable, intent(out) :: error
    done = .false.
    associate (no_use => self, no_y => y, no_ub => ub, no_x => x)   ! the caller solves
    end associate
  end subroutine half_recover

  subroutine solve_leading(self, n, b, x, error)
    !! x(1:n, :) = K⁻¹ b(1:n, :) for a solver of order n whose columns are the
    !! leading rows of longer arrays (a part's interior rows above its
    !! boundary rows); the other rows of x are left alone. This default
    !! copies them into arrays of n rows for solve; a solver that reads and
    !! writes with a leading dimension overrides it without the copies
    !! (CHOLMOD).
    class(linear_solver_t), intent(inout) :: self
    integer(i8), intent(in) :: n
    real(wp), contiguous, intent(in) :: b(:, :)
    real(wp), contiguous, intent(inout) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: bn(:, :), xn(:, :)
    bn = b(1:n, :)
    allocate (xn(n, size(b, 2)))
    call self%solve(bn, xn, error)
    if (allocated(error)) return
    x(1:n, :) = xn
  end subroutine solve_leading

  subroutine schur_by_solves(self, a, nb, kstar, error)
    !! Static condensation: a is the whole symmetric matrix of a part (order
    !! n, upper triangle), its last nb columns the boundary. On return
    !!     kstar(nb, nb) = a_bb − a_bi a_ii⁻¹ a_ib   (both triangles)
    !! and self is a solver of the interior block a_ii (order ni = n − nb):
    !! solve, pivots and info refer to a_ii; on breakdown error%code =
    !! EXIT_SINGULAR and info%failed_column is a column 1..ni of a.
    !! This default analyzes and factors a_ii and forms kstar with 2 nb
    !! triangular solves, SCHUR_BLOCK columns of a_ib at a time; a solver
    !! that can form kstar from one factorization of a overrides it (CHOLMOD,
    !! LAPACK; UMFPACK keeps this one).
    class(linear_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(out) :: kstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(sparse_sym_t) :: aii
    real(wp), allocatable :: rhs(:, :), x(:, :)
    integer(i8) :: ni, j0, j1, nblk, c, pos, r, w
    integer :: stat
    ni = a%n - nb
    call boundary_block(a, nb, kstar)
    if (ni == 0) return
    call interior_block(a, nb, aii)
    call self%analyze(aii, error)
    if (allocated(error)) return
    call self%factorize(aii, error)
    if (allocated(error)) return
    w = min(SCHUR_BLOCK, max(nb, 1_i8))
    allocate (rhs(ni, w), x(ni, w), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the condensation by solves', 2*ni*w*BYTES_REAL)
       return
    end if
    do j0 = 1, nb, SCHUR_BLOCK
       j1 = min(nb, j0 + SCHUR_BLOCK - 1)
       nblk = j1 - j0 + 1
       rhs(:, 1:nblk) = 0.0_wp
       do c = j0, j1
          do pos = a%colptr(ni + c), a%colptr(ni + c + 1) - 1
             r = a%rowind(pos)
             if (r > ni) exit
             rhs(r, c - j0 + 1) = a%val(pos)
          end do
       end do
       call self%solve(rhs(:, 1:nblk), x(:, 1:nblk), error)
       if (allocated(error)) return
       call subtract_bi(a, nb, x(:, 1:nblk), kstar(:, j0:j1))
    end do
    ! Symmetric in exact arithmetic: take the mean of the two triangles.
    kstar = 0.5_wp*(kstar + transpose(kstar))
  end subroutine schur_by_solves

  subroutine interior_block(a, nb, aii)
    !! aii = a_ii, the leading n − nb columns of a (upper triangle).
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    type(sparse_sym_t), intent(out) :: aii
    integer(i8) :: ni
    ni = a%n - nb
    aii%n = ni
    aii%colptr = a%colptr(1:ni + 1)
    aii%rowind = a%rowind(1:a%colptr(ni + 1) - 1)
    aii%val = a%val(1:a%colptr(ni + 1) - 1)
  end subroutine interior_block

  subroutine boundary_block(a, nb, kbb)
    !! kbb = a_bb, both triangles (a's last nb columns and rows).
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(out) :: kbb(:, :)
    integer(i8) :: ni, j, pos, r
    ni = a%n - nb
    kbb = 0.0_wp
    do j = ni + 1, a%n
       do pos = a%colptr(j), a%colptr(j + 1) - 1
          r = a%rowind(pos)
          if (r <= ni) cycle
          kbb(r - ni, j - ni) = a%val(pos)
          kbb(j - ni, r - ni) = a%val(pos)
       end do
    end do
  end subroutine boundary_block

  subroutine subtract_bi(a, nb, x, y)
    !! y -= a_bi x (a_bi = a_ibᵀ, read from the boundary columns of a).
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(inout) :: y(:, :)
    integer(i8) :: ni, j, pos, r
    ni = a%n - nb
    do j = 1, nb
       do pos = a%colptr(ni + j), a%colptr(ni + j + 1) - 1
          r = a%rowind(pos)
          if (r > ni) exit
          y(j, :) = y(j, :) - a%val(pos)*x(r, :)
       end do
    end do
  end subroutine subtract_bi

  subroutine subtract_ib(a, nb, xb, y)
    !! y −= a_ib xb (a_ib: the interior rows of a's boundary columns; xb: the
    !! boundary rows alone).
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(in) :: xb(:, :)
    real(wp), intent(inout) :: y(:, :)
    integer(i8) :: ni, j, pos, r
    ni = a%n - nb
    do j = 1, nb
       do pos = a%colptr(ni + j), a%colptr(ni + j + 1) - 1
          r = a%rowind(pos)
          if (r > ni) exit
          y(r, :) = y(r, :) - a%val(pos)*xb(j, :)
       end do
    end do
  end subroutine subtract_ib

  subroutine boundary_shift(a, nb, val, shift)
    !! For a factorization of the whole part with the boundary last (K* from
    !! its trailing block, K* + D positive definite even for a floating part):
    !! val = the values of a with d_j added to the diagonal of boundary column
    !! j: shift(j) = d_j = its own diagonal, or shift(j) = 0 and d_j = 1 where
    !! that is zero (no stiffness). val stays unallocated when a boundary
    !! column has no diagonal entry stored.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), allocatable, intent(out) :: val(:), shift(:)
    integer(i8) :: ni, j, pos
    ni = a%n - nb
    allocate (shift(nb))
    do j = 1, nb
       pos = a%colptr(ni + j + 1) - 1
       if (pos < a%colptr(ni + j)) return
       if (a%rowind(pos) /= ni + j) return
       shift(j) = abs(a%val(pos))
    end do
    val = a%val
    do j = 1, nb
       pos = a%colptr(ni + j + 1) - 1
       val(pos) = val(pos) + merge(shift(j), 1.0_wp, shift(j) > 0.0_wp)
    end do
  end subroutine boundary_shift

  subroutine unshift(shift, kstar)
    !! kstar(:, j) −= shift(j) e_j from its lower triangle (a trailing block
    !! product of a factor of a with boundary_shift's shift), then both
    !! triangles; the rows and columns of boundary DOFs without stiffness
    !! (shift 0: a zero diagonal, so a zero row in a semi-definite a) exactly zero.
    real(wp), intent(in) :: shift(:)
    real(wp), intent(inout) :: kstar(:, :)
    integer :: j
    do j = 1, size(shift)
       if (shift(j) == 0.0_wp) then
          kstar(j:, j) = 0.0_wp
          kstar(j, 1:j) = 0.0_wp
       else
          kstar(j, j) = kstar(j, j) - shift(j)
       end if
       kstar(j, j + 1:) = kstar(j + 1:, j)
    end do
  end subroutine unshift

  subroutine analyze_start(self, a)
    !! Begin the symbolic phase of a's pattern (its values are not read) beside
    !! the caller's work, where the solver can; a later analyze of the same
    !! pattern completes it. This default does nothing: analyze does it all.
    class(linear_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    associate (no_use => self, no_a => a)   ! analyzed by analyze
    end associate
  end subroutine analyze_start

  subroutine set_groups(self, first)
    !! Tell the solver that columns come in groups of consecutive columns (the
    !! unknowns of one node): group g holds columns first(g) .. first(g+1)-1.
    !! A solver may order the smaller graph of the groups.
    class(linear_solver_t), intent(inout) :: self
    integer(i8), intent(in) :: first(:)
    self%group_first = first
  end subroutine set_groups
end module superjoin_solvers_solver
