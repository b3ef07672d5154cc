module superjoin_analysis_build_reuse
  !! A joint study's build kept from one value for the next. The values of a
  !! study differ only in their contact stiffnesses (*CHANGE CONTACT: the
  !! links' states and g's; elements, supports and options are the same), so
  !! when the links' states are the same (link_signature: which DOFs are
  !! RIGID, finite, zero or absent) the DOF table is the previous one with
  !! other g's on the links' units (take_table), and when moreover the
  !! forest (rebuilt: it takes the stiffest unit first, so a finite g can
  !! move a unit between tree and loop), the units' states after *LARGE and
  !! the condensed interiors are the same, the Δu transform is the previous
  !! one with other springs on its δ columns (take_transform). The forest
  !! itself is kept when build_forest would take the units in the same
  !! order (take_forest: the same order gives the same forest). All exact:
  !! the same arrays build_dof_table, build_forest and build_transform give.
  !! The boundaries (the DOFs the units touch, per substructure, and the
  !! condensation boundaries) go with the table (take_boundaries).
  !! A transform with loop constraints or form springs is not kept (their
  !! pivots are chosen by the springs).
  !! K_red without its δ springs goes with a kept transform and views
  !! (take_matrix), and with it the groups skip_unloaded_parts found in it.
  use superjoin_kinds, only: wp, i8
  use superjoin_model_types, only: model_t
  use superjoin_model_results, only: run_summary_t
  use superjoin_assembly_dofs, only: dof_table_t, link_signature, refresh_link_springs
  use superjoin_assembly_forest, only: forest_t, same_forest, forest_order
  use superjoin_assembly_transform, only: transform_t
  use superjoin_solvers_sparse, only: sparse_sym_t
  implicit none (type, external)
  private

  type, public :: kept_build_t
    !! The previous value's DOF table (before *LARGE) and transform.
     integer, allocatable :: signature(:, :)  !! link_signature of the model the table was built from
     type(dof_table_t) :: table               !! the table as build_dof_table gave it
     logical :: has_boundaries = .false.
     logical, allocatable :: bnd_c(:)         !! its condensation boundaries (part_boundary)
     integer(i8), allocatable :: sub_dofs(:), sub_boundary(:)  !! its counts (count_boundary)
     logical :: has_transform = .false.
     integer, allocatable :: states(:, :)     !! (3, nunit) the units' states after *LARGE
     type(forest_t) :: forest                 !! the forest the transform was built on
     integer, allocatable :: forest_order(:)  !! the order its units were taken in (forest_order)
     integer, allocatable :: value_order(:)   !! the order of this value's units
     logical, allocatable :: keep(:)          !! the DOFs the transform kept (build_transform's keep)
     type(transform_t) :: tr
     logical :: transform_taken = .false.     !! this value took the previous value's transform
     logical :: has_matrix = .false.
     type(sparse_sym_t) :: k_base             !! the previous value's K_red without the δ springs
     real(wp), allocatable :: f_u0(:)         !! and its load of the prescribed values
     integer(i8), allocatable :: roots(:)     !! skip_unloaded_parts' groups of that K_red's columns
     integer :: tables_reused = 0             !! values that took the previous table
     integer :: transforms_reused = 0         !! values that took the previous transform
     integer :: forests_reused = 0            !! values that took the previous forest
     integer :: matrices_reused = 0           !! values that took the previous K_red
  end type kept_build_t

  public :: take_table, keep_table, take_forest, take_transform, keep_transform, take_boundaries, keep_boundaries
  public :: take_matrix, keep_matrix

contains

  subroutine take_table(kb, model, table, taken)
    !! The kept table with model's g's on its links' units, when model has
    !! the links' signature the table was built with (taken); else nothing.
    type(kept_build_t), intent(inout) :: kb
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(out) :: table
    logical, intent(out) :: taken
    integer, allocatable :: sig(:, :)
    taken = .false.
    if (.not. allocated(kb%signature)) return
    sig = link_signature(model)
    if (any(shape(sig) /= shape(kb%signature))) return
    if (any(sig /= kb%signature)) return
    table = kb%table
    call refresh_link_springs(model, table)
    taken = .true.
    kb%tables_reused = kb%tables_reused + 1
  end subroutine take_table

  subroutine keep_table(kb, model, table)
    !! Keep a table just built from model (before *LARGE) for the next value.
    type(kept_build_t), intent(inout) :: kb
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    kb%signature = link_signature(model)
    kb%table = table
    kb%has_transform = .false.   ! built on another table
    kb%has_boundaries = .false.
  end subroutine keep_table

  subroutine take_boundaries(kb, bnd_c, summary, taken)
    !! The kept table's condensation boundaries and boundary counts (for a
    !! value that took the table: they depend on its units' DOFs only).
    type(kept_build_t), intent(in) :: kb
    logical, allocatable, intent(out) :: bnd_c(:)
    type(run_summary_t), intent(inout) :: summary
    logical, intent(out) :: taken
    taken = kb%has_boundaries
    if (.not. taken) return
    bnd_c = kb%bnd_c
    summary%sub_dofs = kb%sub_dofs
    summary%sub_boundary = kb%sub_boundary
  end subroutine take_boundaries

  subroutine keep_boundaries(kb, bnd_c, summary)
    !! Keep the boundaries and counts found for the kept table.
    type(kept_build_t), intent(inout) :: kb
    logical, intent(in) :: bnd_c(:)
    type(run_summary_t), intent(in) :: summary
    kb%bnd_c = bnd_c
    kb%sub_dofs = summary%sub_dofs
    kb%sub_boundary = summary%sub_boundary
    kb%has_boundaries = .true.
  end subroutine keep_boundaries

  subroutine take_forest(kb, table, links_in_tree, forest, taken)
    !! The kept forest, when the units of table are taken in the same order
    !! as the kept forest's (taken); else nothing (build_forest's arguments).
    type(kept_build_t), intent(inout) :: kb
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: links_in_tree
    type(forest_t), intent(out) :: forest
    logical, intent(out) :: taken
    kb%value_order = forest_order(table, links_in_tree)
    taken = .false.
    if (.not. (kb%has_transform .and. allocated(kb%forest_order))) return
    if (size(kb%value_order) /= size(kb%forest_order)) return
    if (any(kb%value_order /= kb%forest_order)) return
    forest = kb%forest
    taken = .true.
    kb%forests_reused = kb%forests_reused + 1
  end subroutine take_forest

  subroutine take_transform(kb, table, forest, keep, tr, taken)
    !! The kept transform with the springs of table's units, when it was
    !! built on the same units' states, forest and kept DOFs (taken).
    type(kept_build_t), intent(inout) :: kb
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    logical, intent(in) :: keep(:)
    type(transform_t), intent(out) :: tr
    logical, intent(out) :: taken
    taken = .false.
    kb%transform_taken = .false.
    if (.not. kb%has_transform) return
    if (size(keep) /= size(kb%keep) .or. size(kb%states, 2) /= table%nunit) return
    if (any(keep .neqv. kb%keep)) return
    if (any(unit_states(table) /= kb%states)) return
    if (.not. same_forest(forest, kb%forest)) return
    tr = kb%tr
    call tr%refresh_springs(table, taken)
    if (taken) kb%transforms_reused = kb%transforms_reused + 1
    kb%transform_taken = taken
  end subroutine take_transform

  subroutine take_matrix(kb, views_taken, k, f_u0, taken)
    !! The previous value's K_red without its δ springs and its f_u0
    !! (taken), when this value took the previous value's transform
    !! (take_transform: the same columns, maps and prescribed values) and
    !! the previous value's views of its condensed parts (views_taken: the
    !! same K*): assembled again, every item would scatter the same terms
    !! into the same positions in the same order; only the g's on the δ
    !! diagonal differ (add_delta_springs). Else the kept matrix and its
    !! groups are dropped (keep_matrix keeps this value's).
    type(kept_build_t), intent(inout) :: kb
    logical, intent(in) :: views_taken
    type(sparse_sym_t), intent(out) :: k
    real(wp), allocatable, intent(out) :: f_u0(:)
    logical, intent(out) :: taken
    taken = kb%has_matrix .and. kb%transform_taken .and. views_taken
    if (.not. taken) then
       kb%has_matrix = .false.
       if (allocated(kb%roots)) deallocate (kb%roots)
       return
    end if
    k = kb%k_base
    f_u0 = kb%f_u0
    kb%matrices_reused = kb%matrices_reused + 1
  end subroutine take_matrix

  subroutine keep_matrix(kb, k, f_u0)
    !! Keep K_red just assembled without its δ springs, and its f_u0, for
    !! the next value (take_matrix).
    type(kept_build_t), intent(inout) :: kb
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(in) :: f_u0(:)
    kb%k_base = k
    kb%f_u0 = f_u0
    kb%has_matrix = .true.
  end subroutine keep_matrix

  subroutine keep_transform(kb, table, forest, keep, tr)
    !! Keep a transform just built (with its forest, kept DOFs and the
    !! units' states) for the next value, unless it has loop constraints or
    !! form springs.
    type(kept_build_t), intent(inout) :: kb
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    logical, intent(in) :: keep(:)
    type(transform_t), intent(in) :: tr
    kb%has_transform = tr%nconstraints() == 0 .and. tr%nforms() == 0
    if (.not. kb%has_transform) return
    kb%states = unit_states(table)
    kb%forest = forest
    if (allocated(kb%forest_order)) deallocate (kb%forest_order)
    if (allocated(kb%value_order)) kb%forest_order = kb%value_order
    kb%keep = keep
    kb%tr = tr
  end subroutine keep_transform

  pure function unit_states(table) result(s)
    !! The states of every unit's components.
    type(dof_table_t), intent(in) :: table
    integer, allocatable :: s(:, :)
    integer :: iu
    allocate (s(3, table%nunit))
    do iu = 1, table%nunit
       s(:, iu) = table%units(iu)%state
    end do
  end function unit_states
end module superjoin_analysis_build_reuse
