module superjoin_analysis_solve_state
  !! What one solve of a step group holds, filled phase by phase (analysis.f90):
  !! build (DOF table, forest, condensation boundary, Δu transform), assemble
  !! (plan, condensed parts, K, loads, AUTOSPC), factor and solve (solver, q),
  !! recover (u, k u of the condensed parts). The health checks, the
  !! condensations and the recovery take this state instead of its pieces.
  use superjoin_kinds, only: wp
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_assembly_forest, only: forest_t
  use superjoin_assembly_transform, only: transform_t
  use superjoin_assembly_assemble, only: assembly_plan_t
  use superjoin_substructure_cache, only: part_view_t
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t
  implicit none (type, external)
  private

  integer, parameter, public :: PHASE_NONE = 0      !! nothing built yet
  integer, parameter, public :: PHASE_BUILT = 1     !! table, forest, transform
  integer, parameter, public :: PHASE_ASSEMBLED = 2 !! K, loads, AUTOSPC
  integer, parameter, public :: PHASE_SOLVED = 3    !! solver factored, q
  integer, parameter, public :: PHASE_RECOVERED = 4 !! u, results

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
     real(wp), allocatable :: f_u0(:)        !! reduced load of the prescribed values
     real(wp), allocatable :: f_red(:, :)    !! reduced loads (ncol, nstep)
     logical, allocatable :: spc(:)          !! AUTOSPC columns
     class(linear_solver_t), allocatable :: solver
     real(wp), allocatable :: q(:, :)        !! reduced solution (ncol, nstep)
     real(wp), allocatable :: u(:, :)        !! physical displacements (np, nstep)
     real(wp), allocatable :: ku(:, :)       !! k u of the condensed parts (np, nstep)
     logical :: summed = .false.
       !! k is this MPI process's term of K_red (owner terms, analysis/distributed):
       !! what needs the whole matrix is computed from the terms (analysis/summed_matrix)
  end type solve_state_t

end module superjoin_analysis_solve_state
