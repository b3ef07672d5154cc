module superjoin_model_results
  !! What a solved deck produces: counts, notes, per-step results and health.
  use superjoin_kinds, only: wp, i8
  use superjoin_model_types, only: string_t
  implicit none (type, external)
  private

  integer, parameter, public :: NPHASE = 6
  character(len=8), parameter, public :: PHASE_NAMES(NPHASE) = &
       ['read    ', 'assemble', 'order   ', 'factor  ', 'solve   ', 'write   ']
  integer, parameter, public :: PH_READ = 1, PH_ASSEMBLE = 2, PH_ORDER = 3, PH_FACTOR = 4, &
                                PH_SOLVE = 5, PH_WRITE = 6

  integer, parameter, public :: LEVELS_NO = 0, LEVELS_YES = 1, LEVELS_AUTO = 2
    !! run_options_t%levels: condensed parts made of parts flat, by level, or as the counts say (analysis/levels)

  type, public :: run_options_t
    !! Options of one run (from the command line).
     character(:), allocatable :: solver        !! auto | cholmod | umfpack | lapack
     integer :: formulation = 0                 !! 0: as in the deck, else FORM_*
     integer :: condense = -1                   !! -1: as in the deck, else CONDENSE_* for every substructure
     character(:), allocatable :: export_matrix !! Matrix Market path, or unallocated
     character(:), allocatable :: library       !! --library DIR: condensations kept across runs, or unallocated
     logical :: library_verify = .false.        !! --library-verify: a library hit assembles k and checks its hash
     logical :: twins = .true.                  !! --twins: identical parts found by their geometry share a condensation
     integer :: levels = LEVELS_AUTO            !! --levels yes | no | auto: parts made of parts condensed by level, flat, or as the counts say
     logical :: quiet = .false.
     logical :: verbose = .false.
     logical :: accept_inaccurate = .false. !! --accept-inaccurate: exit 0 even when results are judged inaccurate
     logical :: csv = .false.                !! CSV tables will be written (--csv)
     logical :: vtk = .false.                !! VTK files will be written (--vtk or *OUTPUT, VTK=)
     logical :: frd = .false.                !! CalculiX's JOB.frd will be written (superjoin -i JOB)
  end type run_options_t

  type, public :: reaction_t
    !! One support reaction.
     integer :: sub = 0
     integer :: node = 0
     integer :: dof = 0
     real(wp) :: force = 0.0_wp
  end type reaction_t

  type, public :: step_results_t
    !! Results of one step.
     type(reaction_t), allocatable :: reactions(:)
     type(reaction_t), allocatable :: equation_forces(:)  !! forces *EQUATION constraints exert on nodes, global axes
     real(wp), allocatable :: link_delta(:, :)   !! (6, nlink) local axes
     real(wp), allocatable :: link_force(:, :)   !! (6, nlink) on the master, local axes
     real(wp) :: applied(6) = 0.0_wp             !! resultant of loads (forces, moments about origin)
     real(wp) :: reaction(6) = 0.0_wp            !! resultant of reactions
     real(wp) :: residual = 0.0_wp               !! ‖K q - f‖ / ‖f‖
     real(wp) :: epsilon = 0.0_wp                !! qᵀ(K q - f) / (qᵀ f)
     real(wp) :: residual0 = 0.0_wp              !! before iterative refinement
     integer :: refinements = 0                  !! refinement steps kept
     integer :: refine_tried = 0                 !! refinement steps tried
     character(:), allocatable :: failure        !! why the step was not solved (exit 3): its results are zeros
     real(wp) :: maxratio = 0.0_wp               !! MAXRATIO of the matrix this step was solved with
     character(:), allocatable :: maxratio_at    !! where (unallocated: the step was not solved)
     real(wp) :: cond_est = 0.0_wp               !! that matrix's condition estimate (1-norm)
     logical :: cond_bound = .false.             !! cond_est is the free lower bound, not Hager-Higham's
  end type step_results_t

  type, public :: run_summary_t
    !! What the listing's MODEL block reports of the solve: counts, the solver
    !! and formulation chosen; and a group's MAXRATIO and condition estimate,
    !! which its steps carry (step_results_t: the health block prints the step's).
     integer(i8) :: nphys = 0          !! active physical DOFs
     integer(i8) :: ncol = 0           !! reduced unknowns
     integer(i8) :: neq = 0            !! equations solved (reduced unknowns less AUTOSPC)
     integer(i8) :: ndelta = 0         !! δ unknowns
     integer(i8) :: matrix_nnz = 0     !! upper triangle with diagonal
     integer(i8) :: factor_nnz = 0
     integer :: n_tree = 0             !! contact units transformed
     integer :: n_plain = 0            !! contact units assembled plainly
     integer :: n_support_units = 0
     integer(i8), allocatable :: sub_dofs(:)       !! active DOFs per substructure
     integer(i8), allocatable :: sub_boundary(:)   !! of which touched by contacts or supports (k_gg)
     logical, allocatable :: sub_condensed(:)      !! interior condensed (static condensation)
     integer, allocatable :: sub_owner(:)          !! MPI process owning each substructure (unallocated: one process)
     integer :: n_condensed = 0                    !! condensations computed
     character(:), allocatable :: solver_name
     character(:), allocatable :: ordering
     character(:), allocatable :: formulation
     real(wp) :: maxratio = 0.0_wp                 !! of this group's matrix (merged runs: the first group's)
     character(:), allocatable :: maxratio_at
     real(wp) :: cond_est = 0.0_wp                 !! of this group's matrix (merged runs: the first group's)
     logical :: cond_bound = .false.               !! cond_est is the free lower bound (health's estimate_condition)
     real(wp) :: factor_mbytes = 0.0_wp
  end type run_summary_t

  type, public :: warning_t
    !! A warning of the run (listing and stderr) and the steps it belongs to.
     character(:), allocatable :: s         !! the text
     logical, allocatable :: steps(:)       !! (nstep) the steps it arose in, whose NUMERICAL HEALTH
                                            !! blocks list it; unallocated: the model's (listed once, before the steps)
  end type warning_t

  type, public :: run_log_t
    !! What the run says of itself: notes, warnings, the verdict on accuracy,
    !! and the time of each phase.
     type(string_t), allocatable :: notes(:)      !! decisions and warnings for the listing
     type(warning_t), allocatable :: warnings(:)  !! also printed on stderr
     logical :: inaccurate = .false.              !! a warning judges the results inaccurate (exit EXIT_INACCURATE)
     real(wp) :: phase_seconds(NPHASE) = 0.0_wp
     type(string_t), allocatable :: partition(:)  !! PARTITION block of an MPI run on several processes (else unallocated)
  end type run_log_t

  type, public :: result_fields_t
    !! The results proper, per step: displacements, element results, contact
    !! forces, reactions and residuals (what the listing, CSV and VTK write).
     real(wp), allocatable :: mechanism(:, :)     !! (6, nvertex) mechanism mode of an exit-3 run, global axes
     real(wp), allocatable :: u(:, :)             !! (6*nvertex, nstep) displacements per vertex, global axes
     logical, allocatable :: has_dof(:, :)        !! (6, nvertex)
     real(wp), allocatable :: elem_force(:, :, :, :)  !! (6, 2, nelem_total, nstep)
     real(wp), allocatable :: plate(:, :, :)      !! (6, nelem_total, nstep) nx, ny, nxy, mx, my, mxy
                                                  !! at the centroid, element frame (plane and shell elements; 0 otherwise)
     real(wp), allocatable :: thermal(:, :, :)    !! (2, nelem_total, nstep) thermal strain α ΔT and curvature
                                                  !! α ∂T/∂n of plane and shell elements (unallocated: none)
     real(wp), allocatable :: thermal_nodal(:, :, :)  !! (MAX_ELEMENT_NODES, nelem_total, nstep) α ΔT at the nodes
                                                  !! of a plane or shell element minus thermal(1) (unallocated: all uniform)
     real(wp), allocatable :: thermal_curvature_nodal(:, :, :)  !! (MAX_ELEMENT_NODES, nelem_total, nstep) α ∂T/∂n
                                                  !! at the nodes of a shell minus thermal(2) (unallocated: all uniform)
     integer(i8), allocatable :: elem_offset(:)   !! (nsub+1) element numbering over substructures
     integer(i8), allocatable :: vertex_offset(:) !! (nsub+1)
     type(step_results_t), allocatable :: steps(:)
     logical, allocatable :: link_used(:, :)      !! (6, nlink) contact DOFs that connect something
  end type result_fields_t

  type, public :: results_t
    !! Everything a solved deck produces, in three parts.
     type(run_summary_t) :: summary
     type(run_log_t) :: log
     type(result_fields_t) :: fields
  end type results_t
end module superjoin_model_results
