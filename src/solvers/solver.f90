module superjoin_solvers_solver
  !! The abstract linear solver: symbolic (analyze), numeric (factorize) and
  !! solve phases for a symmetric sparse matrix.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers_sparse, only: sparse_sym_t
  implicit none (type, external)
  private

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

  subroutine set_groups(self, first)
    !! Tell the solver that columns come in groups of consecutive columns (the
    !! unknowns of one node): group g holds columns first(g) .. first(g+1)-1.
    !! A solver may order the smaller graph of the groups.
    class(linear_solver_t), intent(inout) :: self
    integer(i8), intent(in) :: first(:)
    self%group_first = first
  end subroutine set_groups
end module superjoin_solvers_solver
