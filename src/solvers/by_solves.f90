module superjoin_solvers_by_solves
  !! A solver whose schur is the default route of linear_solver_t (a_ii
  !! factored, K* by 2 nb triangular solves) over any backend, also one that
  !! overrides schur: the reference of the tests of an override and the
  !! "by solves" side of bench/schur_parts.f90. Every other call goes to the
  !! wrapped solver.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_solver, only: linear_solver_t
  implicit none (type, external)
  private

  type, extends(linear_solver_t), public :: by_solves_t
    !! The wrapped solver (allocate it, and set it up, before the first call).
     class(linear_solver_t), allocatable :: inner
   contains
     procedure :: analyze => wrapped_analyze
     procedure :: factorize => wrapped_factorize
     procedure :: solve => wrapped_solve
     procedure :: pivots => wrapped_pivots
     procedure :: release => wrapped_release
  end type by_solves_t

contains

  subroutine wrapped_analyze(self, a, error)
    !! The inner solver's analyze; its info is self's.
    class(by_solves_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    call self%inner%analyze(a, error)
    self%info = self%inner%info
  end subroutine wrapped_analyze

  subroutine wrapped_factorize(self, a, error)
    !! The inner solver's factorize; its info is self's.
    class(by_solves_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    call self%inner%factorize(a, error)
    self%info = self%inner%info
  end subroutine wrapped_factorize

  subroutine wrapped_solve(self, b, x, error)
    !! The inner solver's solve.
    class(by_solves_t), intent(inout) :: self
    real(wp), intent(in) :: b(:, :)
    real(wp), intent(out) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    call self%inner%solve(b, x, error)
  end subroutine wrapped_solve

  subroutine wrapped_pivots(self, d)
    !! The inner solver's pivots.
    class(by_solves_t), intent(inout) :: self
    real(wp), intent(out) :: d(:)
    call self%inner%pivots(d)
  end subroutine wrapped_pivots

  subroutine wrapped_release(self)
    !! The inner solver's release.
    class(by_solves_t), intent(inout) :: self
    if (allocated(self%inner)) call self%inner%release()
  end subroutine wrapped_release
end module superjoin_solvers_by_solves
