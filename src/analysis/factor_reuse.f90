module superjoin_analysis_factor_reuse
  !! A factorization kept from one solve for the next solve of the same matrix
  !! (steps whose supports differ only in their prescribed values: the Δu
  !! transform carries one vector of prescribed values, so such steps are
  !! solved apart, but their reduced stiffness is the same). The kept factor is
  !! reused only when the next assembled matrix is identical, entry for entry
  !! (pattern and values): a change of the AUTOSPC decisions or anything else
  !! that touches the matrix simply factors again.
  !!
  !! A joint study (*CHANGE CONTACT) keeps the analysis instead (keep_analysis):
  !! a finite g sits on its own Δu diagonal, so another finite g gives the
  !! interface matrix the same pattern and only the numeric factorization is
  !! repeated (take_analysis). A g = 0 or RIGID in one value and not in the
  !! other changes which unknowns exist, hence the pattern: analyzed again.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, move_sparse
  use superjoin_model_results, only: results_t, PH_ORDER, PH_FACTOR, PH_SOLVE
  use superjoin_utils_clock, only: stopwatch_t, report_phase
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  implicit none (type, external)
  private

  type, public :: kept_factor_t
    !! The factorization of the last solve and its matrix (with keep set).
     logical :: keep = .false.                        !! keep each solve's factorization for the next
     class(linear_solver_t), allocatable :: solver
     type(sparse_sym_t) :: k
     integer :: reuses = 0                            !! solves that reused a kept factorization
     logical :: keep_analysis = .false.               !! keep the solver for a next matrix of the same pattern
     integer(i8), allocatable :: groups(:)            !! the column groups the kept solver was analyzed with
     integer :: analyses_reused = 0                   !! solves that refactored a kept analysis
  end type kept_factor_t

  public :: take_factor, take_analysis, keep_factor, release_factor, solve_with

contains

  subroutine take_factor(kf, k, solver)
    !! Hand over the kept factorization when it factors exactly k (else none).
    type(kept_factor_t), intent(inout) :: kf
    type(sparse_sym_t), intent(in) :: k
    class(linear_solver_t), allocatable, intent(inout) :: solver
    if (.not. (kf%keep .and. allocated(kf%solver))) return
    if (.not. same_matrix(kf%k, k)) return
    call move_alloc(kf%solver, solver)
    kf%reuses = kf%reuses + 1
  end subroutine take_factor

  subroutine take_analysis(kf, k, groups, solver)
    !! Hand over the kept solver when its analysis fits k (the same pattern
    !! and column groups; kf%keep_analysis): the caller factors k with it
    !! without analyzing again. Else none.
    type(kept_factor_t), intent(inout) :: kf
    type(sparse_sym_t), intent(in) :: k
    integer(i8), allocatable, intent(in) :: groups(:)
    class(linear_solver_t), allocatable, intent(inout) :: solver
    if (.not. (kf%keep_analysis .and. allocated(kf%solver))) return
    if (.not. (same_pattern(kf%k, k) .and. same_groups(kf%groups, groups))) return
    call move_alloc(kf%solver, solver)
    kf%analyses_reused = kf%analyses_reused + 1
  end subroutine take_analysis

  subroutine keep_factor(kf, k, solver, groups)
    !! At the end of a solve: keep its factorization (and matrix, moved out
    !! of k, and the column groups it was analyzed with) when kf%keep or
    !! kf%keep_analysis, release it otherwise.
    type(kept_factor_t), intent(inout) :: kf
    type(sparse_sym_t), intent(inout) :: k
    class(linear_solver_t), allocatable, intent(inout) :: solver
    integer(i8), allocatable, intent(in), optional :: groups(:)
    if (.not. allocated(solver)) return
    if (allocated(kf%groups)) deallocate (kf%groups)
    if (present(groups)) then
       if (allocated(groups)) kf%groups = groups
    end if
    if (.not. (kf%keep .or. kf%keep_analysis)) then
       call solver%release()
       deallocate (solver)
       return
    end if
    call release_factor(kf)
    call move_alloc(solver, kf%solver)
    call move_sparse(k, kf%k)   ! moved, not copied: the solve is done with k (k is left empty)
  end subroutine keep_factor

  subroutine release_factor(kf)
    !! Free the kept factorization.
    type(kept_factor_t), intent(inout) :: kf
    if (allocated(kf%solver)) then
       call kf%solver%release()
       deallocate (kf%solver)
    end if
  end subroutine release_factor

  subroutine solve_with(solver, n, f_red, quiet, q, res, error)
    !! Solve every step with a kept factorization (no analysis, no factorization).
    class(linear_solver_t), intent(inout) :: solver
    integer(i8), intent(in) :: n
    real(wp), intent(in) :: f_red(:, :)
    logical, intent(in) :: quiet
    real(wp), allocatable, intent(out) :: q(:, :)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    type(stopwatch_t) :: clock
    integer :: stat
    res%summary%solver_name = solver%info%name
    res%summary%ordering = solver%info%ordering
    res%summary%factor_nnz = solver%info%factor_nnz
    res%summary%factor_mbytes = solver%info%factor_mbytes
    res%log%phase_seconds(PH_ORDER) = 0.0_wp
    res%log%phase_seconds(PH_FACTOR) = 0.0_wp
    call report_phase(quiet, 'factor', 0.0_wp, 'reused (same stiffness as the previous solve)')
    call clock%start()
    allocate (q(n, size(f_red, 2)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the solution', n*size(f_red, 2)*BYTES_REAL)
       return
    end if
    call solver%solve(f_red, q, error)
    if (allocated(error)) return
    res%log%phase_seconds(PH_SOLVE) = clock%seconds()
    call report_phase(quiet, 'solve', res%log%phase_seconds(PH_SOLVE))
  end subroutine solve_with

  pure logical function same_matrix(a, b)
    !! Identical pattern and values.
    type(sparse_sym_t), intent(in) :: a, b
    same_matrix = same_pattern(a, b)
    if (same_matrix) same_matrix = all(a%val == b%val)
  end function same_matrix

  pure logical function same_groups(a, b)
    !! The same column groups (or none on both sides).
    integer(i8), allocatable, intent(in) :: a(:), b(:)
    same_groups = allocated(a) .eqv. allocated(b)
    if (.not. (same_groups .and. allocated(a))) return
    same_groups = size(a) == size(b)
    if (same_groups) same_groups = all(a == b)
  end function same_groups

  pure logical function same_pattern(a, b)
    !! Identical order and pattern (the values may differ).
    type(sparse_sym_t), intent(in) :: a, b
    same_pattern = .false.
    if (a%n /= b%n) return
    if (.not. (allocated(a%colptr) .and. allocated(b%colptr))) return
    if (size(a%rowind) /= size(b%rowind)) return
    if (any(a%colptr /= b%colptr)) return
    same_pattern = all(a%rowind == b%rowind)
  end function same_pattern
end module superjoin_analysis_factor_reuse
