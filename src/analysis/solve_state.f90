module superjoin_analysis_solve_state
  !! What one solve of a step group holds, filled phase by phase (analysis.f90):
  !! build (DOF table, forest, condensation boundary, Δu transform), assemble
  !! (plan, condensed parts, K, loads, AUTOSPC), factor and solve (solver, q),
  !! recover (u, k u of the condensed parts). The health checks, the
  !! condensations and the recovery take this state instead of its pieces.
  !!
  !! How K_red is assembled is the state's strategy (solve_strategy_t): the
  !! plain one (every substructure's elements, here), the condensed one
  !! (condensed substructures' K*, analysis/condensation) and the distributed
  !! one (several MPI processes, analysis/distributed, the only one that
  !! knows of owner terms). analysis.f90's choose_strategy picks one; a new
  !! way of solving is a new extension of solve_strategy_t and a line there.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, string_t
  use superjoin_model_results, only: run_summary_t, run_options_t
  use superjoin_substructure_cache, only: part_cache_t
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_assembly_forest, only: forest_t
  use superjoin_assembly_transform, only: transform_t
  use superjoin_assembly_assemble, only: assembly_plan_t
  use superjoin_substructure_cache, only: part_view_t
  use superjoin_solvers, only: norm1_sym
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t
  use superjoin_analysis_levels, only: level_plan_t
  implicit none (type, external)
  private

  integer, parameter, public :: PHASE_NONE = 0      !! nothing built yet
  integer, parameter, public :: PHASE_BUILT = 1     !! table, forest, transform
  integer, parameter, public :: PHASE_ASSEMBLED = 2 !! K, loads, AUTOSPC
  integer, parameter, public :: PHASE_SOLVED = 3    !! solver factored, q
  integer, parameter, public :: PHASE_RECOVERED = 4 !! u, results

  type, abstract, public :: solve_strategy_t
    !! How K_red is assembled, and what a product with it means. The
    !! procedures here are the plain strategy's: one process assembles the
    !! elements of every substructure, and nothing is condensed.
  contains
     procedure :: set_plan => plain_plan
       !! the assembly plan (st%plan): which substructures and K* go in
     procedure :: condense => no_condense
       !! the condensations (st%parts) and the loads the interface sees (st%f_eff)
     procedure :: combine => no_combine
       !! after the assembly: what the processes' terms need (owner terms)
     procedure :: recover_interiors => no_interiors
       !! the condensed interiors of st%u, and st%ku
     procedure :: summed => not_summed
       !! is st%k only this process's term of K_red (analysis/summed_matrix)?
     procedure :: matvec => plain_matvec
       !! y = K x
     procedure :: diagonal => plain_diagonal
       !! the diagonal of K
     procedure :: norm1 => plain_norm1
       !! ‖K‖₁
  end type solve_strategy_t

  type, extends(solve_strategy_t), public :: plain_strategy_t
    !! No condensed substructure, one process (see solve_strategy_t).
  end type plain_strategy_t

  public :: keep_boundary_loads

  type, public :: solve_state_t
    !! The solve state of one step group (see the module comment).
     integer :: phase = PHASE_NONE           !! the last phase completed
     integer :: form = 0                     !! FORM_TRANSFORM or FORM_PENALTY
     type(dof_table_t) :: table
     type(forest_t) :: forest
     type(transform_t) :: tr
     logical, allocatable :: bnd_c(:)        !! condensation boundary per physical DOF
     type(part_view_t), allocatable :: parts(:)   !! the condensed substructures
     type(assembly_plan_t) :: plan
     type(sparse_sym_t) :: k                 !! K_red (or this process's term of it: summed)
     real(wp), allocatable :: f_phys(:, :)   !! physical loads (np, nstep)
     real(wp), allocatable :: f_eff(:, :)    !! f_phys with condensed boundaries' f*
     real(wp), allocatable :: f_bnd(:, :)    !! f_eff's rows at the condensed boundaries, part after
                                             !! part (full_health; f_eff freed once reduced)
     real(wp), allocatable :: f_u0(:)        !! reduced load of the prescribed values
     real(wp), allocatable :: f_red(:, :)    !! reduced loads (ncol, nstep)
     logical, allocatable :: spc(:)          !! AUTOSPC columns
     class(linear_solver_t), allocatable :: solver
     logical :: early_solver = .false.       !! solver made before K's values, its analysis begun beside them
     integer(i8), allocatable :: groups(:)   !! the column groups the solver was analyzed with (none: unallocated)
     real(wp), allocatable :: q(:, :)        !! reduced solution (ncol, nstep)
     real(wp), allocatable :: r_red(:, :)    !! K_red q − f_red of the final q (health; not with owner terms)
     real(wp), allocatable :: u(:, :)        !! physical displacements (np, nstep)
     real(wp), allocatable :: ku(:, :)       !! k u of the condensed parts (np, nstep)
     logical :: give_back = .true.           !! the recovery gives the heap's free memory back (malloc_trim):
                                             !! not in a joint study, whose next value would fault it in again
     class(solve_strategy_t), allocatable :: strategy   !! how K_red is assembled (see the module)
     type(level_plan_t), allocatable :: levels   !! parts made of parts, condensed: K_red factored by level
  end type solve_state_t

contains

  subroutine plain_plan(self, st, model, summary)
    !! Every substructure's elements, no K*.
    class(solve_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_summary_t), intent(in) :: summary
    allocate (st%plan%skip_sub(size(model%subs)), source=.false.)
    allocate (st%plan%supers(0))
    associate (no_use => self, no_summary => summary)   ! every substructure goes in
    end associate
  end subroutine plain_plan

  subroutine no_condense(self, st, model, opts, cache, summary, notes, error)
    !! Nothing is condensed.
    class(solve_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(part_cache_t), intent(inout) :: cache
    type(run_summary_t), intent(inout) :: summary
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    associate (no_use => self, no_st => st, no_model => model, no_opts => opts, no_cache => cache, &
         no_summary => summary, no_notes => allocated(notes), no_error => allocated(error))   ! nothing is condensed
    end associate
  end subroutine no_condense

  subroutine no_combine(self, st, error)
    !! One process assembled all of K_red: nothing to combine.
    class(solve_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(inout) :: error
    associate (no_use => self, no_st => st, no_error => allocated(error))   ! one process: nothing to combine
    end associate
  end subroutine no_combine

  subroutine no_interiors(self, st, cache, error)
    !! No condensed interior to recover.
    class(solve_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(part_cache_t), intent(inout) :: cache
    type(error_t), allocatable, intent(out) :: error
    associate (no_use => self, no_st => st, no_cache => cache, no_error => allocated(error))   ! no interior
    end associate
  end subroutine no_interiors

  logical function not_summed(self)
    !! st%k is the whole K_red.
    class(solve_strategy_t), intent(in) :: self
    not_summed = .false.
    associate (no_use => self)
    end associate
  end function not_summed

  subroutine plain_matvec(self, k, x, y, error)
    !! y = K x.
    class(solve_strategy_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: y(:, :)
    type(error_t), allocatable, intent(inout) :: error
    call k%matvec(x, y)
    associate (no_use => self, no_error => allocated(error))   ! the whole matrix: nothing to sum
    end associate
  end subroutine plain_matvec

  subroutine plain_diagonal(self, k, d, error)
    !! d = the diagonal of K.
    class(solve_strategy_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(out) :: d(:)
    type(error_t), allocatable, intent(inout) :: error
    call k%diagonal(d)
    associate (no_use => self, no_error => allocated(error))   ! the whole matrix: nothing to sum
    end associate
  end subroutine plain_diagonal

  subroutine plain_norm1(self, k, knorm, error)
    !! knorm = ‖K‖₁.
    class(solve_strategy_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(out) :: knorm
    type(error_t), allocatable, intent(inout) :: error
    knorm = norm1_sym(k)
    associate (no_use => self, no_error => allocated(error))   ! the whole matrix: nothing to sum
    end associate
  end subroutine plain_norm1

  subroutine keep_boundary_loads(st)
    !! Once the loads are reduced, st%f_eff is read only at the condensed
    !! boundaries (full_health): those rows, part after part, into st%f_bnd,
    !! and f_eff freed (a whole-model array less at the recovery's peak).
    type(solve_state_t), intent(inout) :: st
    integer :: i
    integer(i8) :: at, nb
    if (.not. allocated(st%parts) .or. .not. allocated(st%f_eff)) return
    allocate (st%f_bnd(sum(st%parts%nb), size(st%f_eff, 2)))
    at = 0
    do i = 1, size(st%parts)
       nb = st%parts(i)%nb
       st%f_bnd(at + 1:at + nb, :) = st%f_eff(st%parts(i)%pdof(st%parts(i)%ni + 1:st%parts(i)%ni + nb), :)
       at = at + nb
    end do
    deallocate (st%f_eff)
  end subroutine keep_boundary_loads

end module superjoin_analysis_solve_state
