module superjoin_assembly_transform
  !! The Δu transform: reduced unknowns q and the affine map u = T q + u0.
  !!
  !! Every physical DOF keeps a short list of (column, coefficient) pairs. An
  !! ordinary DOF is its own column. The child of a tree unit is its parent plus
  !! the unit's relative displacements: u_b(C) = u_a(C) + qsᵀ δ, where each finite
  !! or free component of δ is a column of its own (its g sits on that column's
  !! diagonal and nowhere else) and a RIGID component is exactly its prescribed
  !! value (0 for contacts). A RIGID component of a unit that closes a loop is a
  !! linear constraint on q: redundant when it holds identically, otherwise one
  !! column is eliminated exactly by substitution.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, add_error_line, EXIT_DECK
  use superjoin_model_types, only: model_t, equation_t, frame_of_node, NDOF_NODE, LINK_NONE, LINK_FINITE, LINK_RIGID, loc_text, node_label
  use superjoin_assembly_dofs, only: dof_table_t, vertex_dofs, unit_t, NBLOCK, GROUND, block_dof, unit_terms, arm_matrix, &
       MAX_UNIT_TERMS, equation_terms_t, unit_where, unit_nodes
  use superjoin_assembly_forest, only: forest_t
  use superjoin_utils_strings, only: rtoa
  use superjoin_utils_sorting, only: sort_unique_i8
  use superjoin_assembly_column_terms, only: merge_terms, locate
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_pattern, only: find_entry
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL, BYTES_INT, BYTES_I8
  use superjoin_utils_huge_pages, only: advise_huge
  use, intrinsic :: ieee_arithmetic, only: ieee_is_negative
  implicit none (type, external)
  private

  integer, parameter :: INITIAL_CONS = 4   !! constraint and spring-form slots before the first doubling

  interface grow
     !! Make room for element n + 1 of an allocatable array (grow_template.inc).
     module procedure grow_constraint, grow_form_spring
  end interface grow

  integer, parameter, public :: COL_PHYS = 1, COL_DELTA = 2, COL_DEAD = 3
    !! Column kinds.
  integer, parameter, public :: ROLE_TREE = 1, ROLE_PLAIN = 2
    !! Unit roles.
  integer, parameter, public :: CONS_REDUNDANT = 1, CONS_ELIMINATED = 2
    !! Constraint outcomes for RIGID components that close a loop.
  real(wp), parameter :: CONS_ZERO = 1.0e-12_wp
    !! Coefficients of a loop constraint below this (relative) are round-off.
  real(wp), parameter :: PIVOT_FRACTION = 0.5_wp
    !! A pivot for elimination must be at least this fraction of the largest coefficient.

  type, public :: form_spring_t
    !! A spring on a linear form of the unknowns: energy ½ g (aᵀq + c)².
     integer(i8), allocatable :: col(:)
     real(wp), allocatable :: coef(:)
     real(wp) :: const = 0.0_wp
     real(wp) :: g = 0.0_wp
     integer :: unit = 0                   !! unit and component whose δ it is
     integer :: k = 0
  end type form_spring_t

  type, public :: constraint_t
    !! A RIGID component of a loop-closing unit.
     integer :: unit = 0
     integer :: k = 0                      !! row of the unit's qs
     integer :: status = 0                 !! CONS_REDUNDANT or CONS_ELIMINATED
     integer(i8) :: col = 0                !! eliminated column (before compaction)
     integer :: col_unit = 0               !! what the eliminated column was (unit, comp) or 0
     integer :: col_k = 0
     real(wp) :: pivot = 0.0_wp            !! its coefficient in the constraint
     real(wp) :: g = 0.0_wp                !! spring that sat on the eliminated column
     integer :: form = 0                   !! form spring that replaced it (0: none)
     integer :: equation = 0               !! an *EQUATION (index into the table's equations), unit 0
     integer(i8), allocatable :: fp_p(:)   !! footprint of the eliminated column: physical DOFs
     real(wp), allocatable :: fp_c(:)      !! and their coefficients
  end type constraint_t

  type, public :: transform_t
    !! The reduced system's unknowns and the map from them to physical DOFs.
    !! Its data are private: use the operations (expand, reduce, scatter) and
    !! the queries below.
     private
     integer(i8) :: ncol_ = 0
     integer, allocatable :: col_kind(:)   !! COL_PHYS or COL_DELTA
     integer(i8), allocatable :: col_ref(:)  !! physical DOF (COL_PHYS) or unit (COL_DELTA)
     integer, allocatable :: col_k(:)      !! row of the unit's qs (COL_DELTA)
     real(wp), allocatable :: col_g(:)     !! spring on the diagonal (COL_DELTA)
     integer(i8), allocatable :: map_start(:)  !! (np) first pool entry; once built (np + 1): the map
                                               !! of p is pool entries map_start(p) .. map_start(p + 1) - 1
     integer, allocatable :: map_len(:)        !! (np) while the maps are built
     integer(i8), allocatable :: pool_col(:)
     real(wp), allocatable :: pool_coef(:)
     integer(i8) :: pool_n = 0
     real(wp), allocatable :: u0(:)        !! (np) prescribed part of each DOF
     integer, allocatable :: role(:)       !! (nunit) ROLE_TREE or ROLE_PLAIN
     integer(i8), allocatable :: dcol(:, :)  !! (3, nunit) δ column of each component, 0 if none
     type(form_spring_t), allocatable :: forms(:)
     integer :: nform = 0
     type(constraint_t), allocatable :: cons(:)
     integer :: ncons = 0
   contains
     procedure :: expand => transform_expand
     procedure :: reduce => transform_reduce
     procedure :: reduce_add => transform_reduce_add
     procedure :: columns_of => transform_columns_of
     procedure :: element_columns => transform_element_columns
     procedure :: scatter_dense => transform_scatter_dense
     procedure :: ncol => transform_ncol
     procedure :: column_kind => transform_column_kind
     procedure :: column_ref => transform_column_ref
     procedure :: column_comp => transform_column_comp
     procedure :: column_g => transform_column_g
     procedure :: unit_role => transform_unit_role
     procedure :: count_role => transform_count_role
     procedure :: delta_column => transform_delta_column
     procedure :: prescribed => transform_prescribed
     procedure :: nforms => transform_nforms
     procedure :: form => transform_form
     procedure :: nconstraints => transform_nconstraints
     procedure :: constraint => transform_constraint
     procedure :: release_maps => transform_release_maps
     procedure :: refresh_springs => transform_refresh_springs
  end type transform_t

  public :: build_transform

contains

  subroutine build_transform(model, table, forest, tr, error, keep)
    !! Build columns, maps and loop constraints from the DOF table and the forest.
    !! With `keep`, a physical DOF that no contact touches and whose keep(p) is
    !! false gets no column at all (the interior of a condensed substructure:
    !! it is eliminated part by part, outside the reduced system).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(out) :: tr
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: keep(:)
    integer :: stat

    allocate (tr%role(table%nunit), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the contact unit roles', table%nunit*BYTES_INT)
       return
    end if
    where (forest%tree)
       tr%role = ROLE_TREE
    elsewhere
       tr%role = ROLE_PLAIN
    end where
    call number_columns(table, forest, tr, error, keep)
    if (allocated(error)) return
    call build_maps(table, forest, tr, error)
    if (allocated(error)) return
    call close_loops(model, table, tr, error)
    if (allocated(error)) return
    call apply_equations(model, table, tr, error)
    if (allocated(error)) return
    call compact_columns(tr, error)
    if (allocated(error)) return
    call fit_storage(tr)
  end subroutine build_transform

  subroutine fit_storage(tr)
    !! Fit the column table and the pool to what they hold: both are sized
    !! for the worst case while they are built, and a condensed model keeps
    !! few columns (its interiors have none). u0 goes when nothing is
    !! prescribed (every entry +0: u0_of answers 0 without it).
    type(transform_t), intent(inout) :: tr
    if (size(tr%col_kind, kind=i8) > tr%ncol_) then
       tr%col_kind = tr%col_kind(1:tr%ncol_)
       tr%col_ref = tr%col_ref(1:tr%ncol_)
       tr%col_k = tr%col_k(1:tr%ncol_)
       tr%col_g = tr%col_g(1:tr%ncol_)
    end if
    call pack_maps(tr)
    if (all(tr%u0 == 0.0_wp .and. .not. ieee_is_negative(tr%u0))) deallocate (tr%u0)
  end subroutine fit_storage

  subroutine pack_maps(tr)
    !! The maps in the order of the physical DOFs, the pool fitted to them
    !! (it grew by doubling, and rewritten maps left their old entries
    !! behind): map_start gets np + 1 entries, map_len goes (nmap).
    type(transform_t), intent(inout) :: tr
    integer(i8), allocatable :: start(:), col(:)
    real(wp), allocatable :: coef(:)
    integer(i8) :: p, np
    np = size(tr%map_len, kind=i8)
    allocate (start(np + 1))
    start(1) = 1
    do p = 1, np
       start(p + 1) = start(p) + tr%map_len(p)
    end do
    allocate (col(start(np + 1) - 1), coef(start(np + 1) - 1))
    call advise_huge(col)
    call advise_huge(coef)
    do p = 1, np
       col(start(p):start(p + 1) - 1) = tr%pool_col(tr%map_start(p):tr%map_start(p) + tr%map_len(p) - 1)
       coef(start(p):start(p + 1) - 1) = tr%pool_coef(tr%map_start(p):tr%map_start(p) + tr%map_len(p) - 1)
    end do
    deallocate (tr%map_len)
    call move_alloc(start, tr%map_start)
    call move_alloc(col, tr%pool_col)
    call move_alloc(coef, tr%pool_coef)
    tr%pool_n = size(tr%pool_col, kind=i8)
  end subroutine pack_maps

  elemental integer function nmap(tr, p)
    !! Length of the map of physical DOF p (once the maps are packed).
    type(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: p
    nmap = int(tr%map_start(p + 1) - tr%map_start(p))
  end function nmap

  elemental real(wp) function u0_of(tr, p)
    !! The prescribed part of physical DOF p (0 when nothing is prescribed).
    type(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: p
    u0_of = 0.0_wp
    if (allocated(tr%u0)) u0_of = tr%u0(p)
  end function u0_of

  subroutine number_columns(table, forest, tr, error, keep)
    !! Columns node by node: first the δ of the unit above the node, then the
    !! node's own DOFs that no tree unit makes dependent (and that `keep` keeps).
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(inout) :: tr
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: keep(:)
    integer(i8) :: v, p, cap, pv(NDOF_NODE)
    integer :: b, c, k, pu, stat
    logical :: dep

    cap = table%np + 3*table%nunit
    allocate (tr%col_kind(cap), tr%col_ref(cap), tr%col_k(cap), tr%col_g(cap), stat=stat)
    if (stat == 0) allocate (tr%dcol(3, table%nunit), source=0_i8, stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the column table', cap*(2*BYTES_INT + BYTES_I8 + BYTES_REAL) + &
            3*table%nunit*BYTES_I8)
       return
    end if
    tr%ncol_ = 0
    do v = 1, table%nvertex
       call vertex_dofs(table, v, pv)
       do b = 1, NBLOCK
          pu = forest%parent_unit(b, v)
          if (pu > 0) then
             associate (u => table%units(pu))
               do k = 1, u%n
                  if (u%state(k) == LINK_RIGID) cycle
                  tr%ncol_ = tr%ncol_ + 1
                  tr%col_kind(tr%ncol_) = COL_DELTA
                  tr%col_ref(tr%ncol_) = pu
                  tr%col_k(tr%ncol_) = k
                  tr%col_g(tr%ncol_) = merge(u%g(k), 0.0_wp, u%state(k) == LINK_FINITE)
                  tr%dcol(k, pu) = tr%ncol_
               end do
             end associate
          end if
          do c = 1, 3
             p = pv(block_dof(b, c))
             if (p == 0) cycle
             dep = .false.
             if (pu > 0) dep = any(table%units(pu)%comp(1:table%units(pu)%n) == c)
             if (dep) cycle
             if (present(keep)) then
                if (.not. keep(p)) cycle
             end if
             tr%ncol_ = tr%ncol_ + 1
             tr%col_kind(tr%ncol_) = COL_PHYS
             tr%col_ref(tr%ncol_) = p
             tr%col_k(tr%ncol_) = 0
             tr%col_g(tr%ncol_) = 0.0_wp
          end do
       end do
    end do
  end subroutine number_columns

  subroutine build_maps(table, forest, tr, error)
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(inout) :: tr
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: j, p, v, w, pw, io, cap
    integer :: b, ib, c, k, pu, stat
    real(wp) :: sgn, coef
    logical :: eccentric

    cap = table%np + 4*table%nunit + 16
    allocate (tr%map_start(table%np), source=0_i8, stat=stat)
    if (stat == 0) allocate (tr%map_len(table%np), source=0, stat=stat)
    if (stat == 0) allocate (tr%u0(table%np), source=0.0_wp, stat=stat)
    if (stat == 0) allocate (tr%pool_col(cap), tr%pool_coef(cap), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the maps of the physical DOFs', table%np*(BYTES_I8 + BYTES_INT + BYTES_REAL) + &
            cap*(BYTES_I8 + BYTES_REAL))
       return
    end if
    call advise_huge(tr%pool_col)
    call advise_huge(tr%pool_coef)
    tr%pool_n = 0
    do j = 1, tr%ncol_
       if (tr%col_kind(j) /= COL_PHYS) cycle
       p = tr%col_ref(j)
       call pool_push(tr, j, 1.0_wp)
       tr%map_start(p) = tr%pool_n
       tr%map_len(p) = 1
    end do
    ! Rotations first when a unit is eccentric: its translations take the
    ! master's rotations through the arm (rotations never take translations).
    eccentric = .false.
    do pu = 1, table%nunit
       if (table%units(pu)%eccentric) eccentric = .true.
    end do
    do ib = 1, NBLOCK
       b = ib
       if (eccentric) b = NBLOCK + 1 - ib
       do io = 1, forest%norder(b)
          v = forest%order(b, io)
          pu = forest%order_unit(b, io)
          associate (u => table%units(pu))
            if (forest%child_is_a(pu)) then
               w = u%vb
               sgn = -1.0_wp
            else
               w = u%va
               sgn = 1.0_wp
            end if
            do c = 1, u%n
               p = table%dof(block_dof(b, u%comp(c)), v)
               tr%map_start(p) = tr%pool_n + 1
               tr%map_len(p) = 0
               if (w /= GROUND) then
                  pw = table%dof(block_dof(b, u%comp(c)), w)
                  do j = tr%map_start(pw), tr%map_start(pw) + tr%map_len(pw) - 1
                     call pool_push(tr, tr%pool_col(j), tr%pool_coef(j))
                  end do
                  tr%map_len(p) = tr%map_len(pw)
                  tr%u0(p) = tr%u0(pw)
               end if
               do k = 1, u%n
                  coef = sgn*u%qs(k, c)
                  if (coef == 0.0_wp) cycle
                  if (tr%dcol(k, pu) > 0) then
                     call pool_push(tr, tr%dcol(k, pu), coef)
                     tr%map_len(p) = tr%map_len(p) + 1
                  else if (u%state(k) == LINK_RIGID) then
                     tr%u0(p) = tr%u0(p) + coef*u%value(k)
                  end if
               end do
               if (u%eccentric) call add_arm(table, tr, u, c, sgn, p)
            end do
          end associate
       end do
    end do
  end subroutine build_maps

  subroutine add_arm(table, tr, u, c, sgn, p)
    !! Append sgn (theta_a x r)_c to the map of p (the last one in the pool),
    !! theta_a the master's rotations (their maps are complete), then merge
    !! repeated columns so that each column appears once in a map.
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(inout) :: tr
    type(unit_t), intent(in) :: u
    integer, intent(in) :: c
    real(wp), intent(in) :: sgn
    integer(i8), intent(in) :: p
    real(wp) :: a(3, 3), coef
    integer(i8) :: pr, j
    integer(i8), allocatable :: col(:)
    real(wp), allocatable :: cf(:)
    integer :: d

    a = arm_matrix(u%arm)
    do d = 1, 3
       coef = sgn*a(u%comp(c), d)
       if (coef == 0.0_wp) cycle
       pr = table%dof(3 + d, u%va)
       if (pr == 0) cycle
       do j = tr%map_start(pr), tr%map_start(pr) + tr%map_len(pr) - 1
          call pool_push(tr, tr%pool_col(j), coef*tr%pool_coef(j))
       end do
       tr%map_len(p) = tr%map_len(p) + tr%map_len(pr)
       tr%u0(p) = tr%u0(p) + coef*tr%u0(pr)
    end do
    col = tr%pool_col(tr%map_start(p):tr%map_start(p) + tr%map_len(p) - 1)
    cf = tr%pool_coef(tr%map_start(p):tr%map_start(p) + tr%map_len(p) - 1)
    call merge_terms(col, cf)
    tr%map_len(p) = size(col)
    tr%pool_col(tr%map_start(p):tr%map_start(p) + size(col) - 1) = col
    tr%pool_coef(tr%map_start(p):tr%map_start(p) + size(col) - 1) = cf
    tr%pool_n = tr%map_start(p) + size(col) - 1
  end subroutine add_arm

  subroutine pool_push(tr, col, coef)
    type(transform_t), intent(inout) :: tr
    integer(i8), intent(in) :: col
    real(wp), intent(in) :: coef
    integer(i8), allocatable :: ic(:)
    real(wp), allocatable :: rc(:)
    if (tr%pool_n == size(tr%pool_col, kind=i8)) then
       allocate (ic(2*tr%pool_n), rc(2*tr%pool_n))
       call advise_huge(ic)
       call advise_huge(rc)
       ic(1:tr%pool_n) = tr%pool_col(1:tr%pool_n)
       rc(1:tr%pool_n) = tr%pool_coef(1:tr%pool_n)
       call move_alloc(ic, tr%pool_col)
       call move_alloc(rc, tr%pool_coef)
    end if
    tr%pool_n = tr%pool_n + 1
    tr%pool_col(tr%pool_n) = col
    tr%pool_coef(tr%pool_n) = coef
  end subroutine pool_push

  subroutine unit_form(table, tr, u, k, col, coef, const)
    !! Linear form of δ_k of unit u in the unknowns: aᵀq + const.
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(unit_t), intent(in) :: u
    integer, intent(in) :: k
    integer(i8), allocatable, intent(out) :: col(:)
    real(wp), allocatable, intent(out) :: coef(:)
    real(wp), intent(out) :: const
    integer(i8) :: pt(MAX_UNIT_TERMS), p, j, n
    real(wp) :: wt(MAX_UNIT_TERMS)
    integer :: i, nt

    call unit_terms(table, u, k, pt, wt, nt)
    n = 0
    do i = 1, nt
       n = n + tr%map_len(pt(i))
    end do
    allocate (col(n), coef(n))
    n = 0
    const = -u%value(k)
    do i = 1, nt
       p = pt(i)
       const = const + wt(i)*tr%u0(p)
       do j = tr%map_start(p), tr%map_start(p) + tr%map_len(p) - 1
          n = n + 1
          col(n) = tr%pool_col(j)
          coef(n) = wt(i)*tr%pool_coef(j)
       end do
    end do
    call merge_terms(col, coef)
  end subroutine unit_form

  subroutine close_loops(model, table, tr, error)
    !! Rigid components of loop-closing units: redundant or eliminated.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(inout) :: tr
    type(error_t), allocatable, intent(inout) :: error
    integer :: iu, k, best
    integer(i8), allocatable :: col(:)
    real(wp), allocatable :: coef(:)
    real(wp) :: const, amax, scale
    type(constraint_t) :: cs

    allocate (tr%cons(INITIAL_CONS), tr%forms(INITIAL_CONS))
    do iu = 1, table%nunit
       if (tr%role(iu) /= ROLE_PLAIN) cycle
       do k = 1, table%units(iu)%n
          if (table%units(iu)%state(k) /= LINK_RIGID) cycle
          call unit_form(table, tr, table%units(iu), k, col, coef, const)
          scale = maxval(abs(table%units(iu)%qs(k, 1:table%units(iu)%n)))
          amax = 0.0_wp
          if (size(coef) > 0) amax = maxval(abs(coef))
          cs = constraint_t()
          cs%unit = iu
          cs%k = k
          if (amax <= CONS_ZERO*scale) then
             if (abs(const) > CONS_ZERO*max(maxval(abs(tr%u0)), abs(table%units(iu)%value(k)), tiny(1.0_wp)) &
                 .and. abs(const) > 0.0_wp) then
                call add_error_line(error, EXIT_DECK, unit_where(model, table%units(iu))// &
                     ': error: RIGID loop with conflicting prescribed values at '// &
                     unit_nodes(model, table, table%units(iu), k)//' (mismatch '//rtoa(const)//')')
                cycle
             end if
             cs%status = CONS_REDUNDANT
          else
             best = choose_pivot(tr, col, coef, amax)
             call eliminate(tr, col, coef, const, best, cs)
             cs%status = CONS_ELIMINATED
          end if
          call push_constraint(tr, cs)
       end do
    end do
  end subroutine close_loops

  subroutine apply_equations(model, table, tr, error)
    !! *EQUATION constraints, in deck order: the first term's DOF is eliminated
    !! (its own column is substituted everywhere by the others), so chains of
    !! equations and contacts compose. Its DOF must still be its own column: a
    !! DOF made dependent by a contact or a support cannot be, and a DOF that
    !! comes back through the other terms (through earlier equations: a cycle)
    !! cannot either.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(inout) :: tr
    type(error_t), allocatable, intent(inout) :: error
    integer :: ie, best, i
    integer(i8) :: p1, jstar, j
    integer(i8), allocatable :: col(:)
    real(wp), allocatable :: coef(:)
    real(wp) :: const, amax, scale
    type(constraint_t) :: cs
    character(:), allocatable :: head

    do ie = 1, size(table%equations)
       associate (te => table%equations(ie), e => model%equations(table%equations(ie)%source))
         head = loc_text(model, e%loc)//': error: *EQUATION: '
         p1 = te%p(1)
         jstar = 0
         if (tr%map_len(p1) == 1) then
            j = tr%pool_col(tr%map_start(p1))
            if (tr%col_kind(j) == COL_PHYS .and. tr%col_ref(j) == p1 .and. &
                tr%pool_coef(tr%map_start(p1)) == 1.0_wp .and. tr%u0(p1) == 0.0_wp) jstar = j
         end if
         if (jstar == 0 .and. e%tie > 0) cycle   ! a tie's slave DOF already dependent: no tie there (CalculiX)
         if (e%coupling) then
            call apply_coupling_equation(model, tr, te, e, jstar, ie, error)
            cycle
         end if
         if (jstar == 0) then
            call add_error_line(error, EXIT_DECK, head//'the dependent DOF '//dof_text(e, 1)// &
                 ' is already dependent (a contact slave, a support or an earlier equation makes it so); '// &
                 'start the equation with another of its DOFs')
            cycle
         end if
         call equation_form(tr, te, col, coef, const)
         scale = maxval(abs(te%a))
         amax = 0.0_wp
         if (size(coef) > 0) amax = maxval(abs(coef))
         if (amax <= CONS_ZERO*scale) then
            call add_error_line(error, EXIT_DECK, head//'its terms cancel (after the contacts, supports '// &
                 'and earlier equations are substituted, nothing is left to constrain)')
            cycle
         end if
         best = 0
         do i = 1, size(col)
            if (col(i) == jstar) best = i
         end do
         if (e%tie > 0 .and. best == 0) cycle   ! a cycle of ties: this one is already implied
         if (best == 0) then
            call add_error_line(error, EXIT_DECK, head//'the dependent DOF '//dof_text(e, 1)// &
                 ' cancels out of its own equation (through the other terms and earlier equations: a cycle)')
            cycle
         end if
         ! an equation written in nodal systems (*TRANSFORM) couples its dependent DOF with its node's other
         ! global DOFs: their substitution changes its coefficient, a cycle only when that leaves it small
         if (abs(coef(best) - te%a(1)) > CONS_ZERO*scale .and. &
             .not. (in_node_frames(model, e) .and. abs(coef(best)) >= PIVOT_FRACTION*amax)) then
            if (e%tie > 0) cycle
            call add_error_line(error, EXIT_DECK, head//'the dependent DOF '//dof_text(e, 1)// &
                 ' comes back through the other terms (an earlier equation or contact expresses one of them '// &
                 'in it: a cycle)')
            cycle
         end if
         cs = constraint_t()
         cs%equation = ie
         call eliminate(tr, col, coef, const, best, cs)
         cs%status = CONS_ELIMINATED
         call push_constraint(tr, cs)
       end associate
    end do
  contains
    function dof_text(e, t) result(text)
      type(equation_t), intent(in) :: e
      integer, intent(in) :: t
      character(:), allocatable :: text
      character(len=12) :: buf
      write (buf, '(i0)') e%dof(t)
      text = node_label(model, e%sub(t), e%node(t))//' DOF '//trim(buf)
    end function dof_text
  end subroutine apply_equations

  pure logical function in_node_frames(model, e)
    !! Some term of *EQUATION e is on a node with a nodal system (its terms were
    !! turned into global axes, superjoin_deck_equation_build).
    type(model_t), intent(in) :: model
    type(equation_t), intent(in) :: e
    integer :: t
    in_node_frames = .false.
    if (e%tie > 0 .or. e%coupling) return
    do t = 1, size(e%sub)
       if (frame_of_node(model, e%sub(t), e%node(t)) > 0) in_node_frames = .true.
    end do
  end function in_node_frames

  subroutine apply_coupling_equation(model, tr, te, e, jstar, ie, error)
    !! A coupling constraint (*COUPLING, *RIGID BODY, *MPC): its first DOF is
    !! eliminated when it is still its own column (jstar) and large enough in the
    !! substituted form; otherwise (a coupled node held by a support, a contact
    !! or another constraint) another column is, as for a RIGID loop. A form
    !! that cancels is redundant when its prescribed part is zero, else a conflict.
    type(model_t), intent(in) :: model
    type(transform_t), intent(inout) :: tr
    type(equation_terms_t), intent(in) :: te
    type(equation_t), intent(in) :: e
    integer(i8), intent(in) :: jstar
    integer, intent(in) :: ie
    type(error_t), allocatable, intent(inout) :: error
    integer(i8), allocatable :: col(:)
    real(wp), allocatable :: coef(:)
    real(wp) :: const, amax
    integer :: best, i
    type(constraint_t) :: cs
    call equation_form(tr, te, col, coef, const)
    amax = 0.0_wp
    if (size(coef) > 0) amax = maxval(abs(coef))
    if (amax <= CONS_ZERO*maxval(abs(te%a))) then
       if (abs(const) > CONS_ZERO*max(maxval(abs(tr%u0)), tiny(1.0_wp)) .and. abs(const) > 0.0_wp) &
            call add_error_line(error, EXIT_DECK, loc_text(model, e%loc)//': error: coupling constraint at node '// &
            node_label(model, e%sub(1), e%node(1))//': prescribed displacements conflict with it (mismatch '// &
            rtoa(const)//')')
       return
    end if
    best = 0
    do i = 1, size(col)
       if (col(i) == jstar .and. jstar > 0 .and. abs(coef(i)) >= PIVOT_FRACTION*amax) best = i
    end do
    if (best == 0) best = choose_pivot(tr, col, coef, amax)
    cs = constraint_t()
    cs%equation = ie
    call eliminate(tr, col, coef, const, best, cs)
    cs%status = CONS_ELIMINATED
    call push_constraint(tr, cs)
  end subroutine apply_coupling_equation

  subroutine equation_form(tr, te, col, coef, const)
    !! The equation sum_i a_i u(p_i) = 0 as aᵀq + const over the current maps.
    type(transform_t), intent(in) :: tr
    type(equation_terms_t), intent(in) :: te
    integer(i8), allocatable, intent(out) :: col(:)
    real(wp), allocatable, intent(out) :: coef(:)
    real(wp), intent(out) :: const
    integer(i8) :: p, j, n
    integer :: i
    n = 0
    do i = 1, size(te%p)
       n = n + tr%map_len(te%p(i))
    end do
    allocate (col(n), coef(n))
    n = 0
    const = 0.0_wp
    do i = 1, size(te%p)
       p = te%p(i)
       const = const + te%a(i)*tr%u0(p)
       do j = tr%map_start(p), tr%map_start(p) + tr%map_len(p) - 1
          n = n + 1
          col(n) = tr%pool_col(j)
          coef(n) = te%a(i)*tr%pool_coef(j)
       end do
    end do
    call merge_terms(col, coef)
  end subroutine equation_form

  pure function choose_pivot(tr, col, coef, amax) result(best)
    !! Pivot among the terms whose coefficient is large enough: a δ column
    !! first (the softest spring), then any column; ties by lowest column.
    type(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: col(:)
    real(wp), intent(in) :: coef(:), amax
    integer :: best, i
    best = 0
    do i = 1, size(col)
       if (abs(coef(i)) < PIVOT_FRACTION*amax) cycle
       if (best == 0) then
          best = i
       else if (better(i, best)) then
          best = i
       end if
    end do
  contains
    pure logical function better(i, j)
      integer, intent(in) :: i, j
      logical :: di, dj
      di = tr%col_kind(col(i)) == COL_DELTA
      dj = tr%col_kind(col(j)) == COL_DELTA
      if (di .neqv. dj) then
         better = di
      else
         better = tr%col_g(col(i)) < tr%col_g(col(j))
      end if
    end function better
  end function choose_pivot

  subroutine eliminate(tr, col, coef, const, best, cs)
    !! Eliminate column col(best) using aᵀq + const = 0 in every map and form.
    type(transform_t), intent(inout) :: tr
    integer(i8), intent(in) :: col(:)
    real(wp), intent(in) :: coef(:), const
    integer, intent(in) :: best
    type(constraint_t), intent(inout) :: cs
    integer(i8) :: jstar, p, j, nfp
    real(wp) :: piv, c
    integer(i8), allocatable :: ncol(:)
    real(wp), allocatable :: ncoef(:)
    integer :: i
    type(form_spring_t) :: fs

    jstar = col(best)
    piv = coef(best)
    cs%col = jstar
    cs%pivot = piv
    cs%g = tr%col_g(jstar)
    if (tr%col_kind(jstar) == COL_DELTA) then
       cs%col_unit = int(tr%col_ref(jstar))
       cs%col_k = tr%col_k(jstar)
    end if
    ! Footprint of the column before it goes.
    nfp = 0
    do p = 1, size(tr%map_len, kind=i8)
       do j = tr%map_start(p), tr%map_start(p) + tr%map_len(p) - 1
          if (tr%pool_col(j) == jstar) nfp = nfp + 1
       end do
    end do
    allocate (cs%fp_p(nfp), cs%fp_c(nfp))
    nfp = 0
    do p = 1, size(tr%map_len, kind=i8)
       do j = tr%map_start(p), tr%map_start(p) + tr%map_len(p) - 1
          if (tr%pool_col(j) /= jstar) cycle
          nfp = nfp + 1
          cs%fp_p(nfp) = p
          cs%fp_c(nfp) = tr%pool_coef(j)
       end do
    end do
    ! Substitute q_j* = -(Σ_{j≠j*} a_j q_j + const) / a_j* into the maps.
    do i = 1, int(nfp)
       p = cs%fp_p(i)
       c = cs%fp_c(i)
       call substitute(tr%pool_col(tr%map_start(p):tr%map_start(p) + tr%map_len(p) - 1), &
            tr%pool_coef(tr%map_start(p):tr%map_start(p) + tr%map_len(p) - 1), &
            jstar, col, coef, piv, ncol, ncoef)
       tr%u0(p) = tr%u0(p) - c*const/piv
       tr%map_start(p) = tr%pool_n + 1
       tr%map_len(p) = size(ncol)
       do j = 1, size(ncol, kind=i8)
          call pool_push(tr, ncol(j), ncoef(j))
       end do
    end do
    ! Substitute into existing form springs.
    do i = 1, tr%nform
       c = 0.0_wp
       do j = 1, size(tr%forms(i)%col, kind=i8)
          if (tr%forms(i)%col(j) == jstar) c = tr%forms(i)%coef(j)
       end do
       if (c == 0.0_wp) cycle
       call substitute(tr%forms(i)%col, tr%forms(i)%coef, jstar, col, coef, piv, ncol, ncoef)
       tr%forms(i)%col = ncol
       tr%forms(i)%coef = ncoef
       tr%forms(i)%const = tr%forms(i)%const - c*const/piv
    end do
    ! A spring that sat on the eliminated δ now acts on its expression.
    if (tr%col_g(jstar) > 0.0_wp) then
       fs%g = tr%col_g(jstar)
       fs%unit = cs%col_unit
       fs%k = cs%col_k
       fs%col = pack(col, col /= jstar)
       fs%coef = -pack(coef, col /= jstar)/piv
       fs%const = -const/piv
       call push_form(tr, fs)
       cs%form = tr%nform
    end if
    tr%col_kind(jstar) = COL_DEAD
  end subroutine eliminate

  subroutine substitute(mcol, mcoef, jstar, col, coef, piv, ncol, ncoef)
    !! Terms (mcol, mcoef) with column jstar replaced by -(Σ a_j q_j)/a_j*.
    integer(i8), intent(in) :: mcol(:)
    real(wp), intent(in) :: mcoef(:)
    integer(i8), intent(in) :: jstar
    integer(i8), intent(in) :: col(:)
    real(wp), intent(in) :: coef(:), piv
    integer(i8), allocatable, intent(out) :: ncol(:)
    real(wp), allocatable, intent(out) :: ncoef(:)
    real(wp) :: c
    integer :: i, n
    c = 0.0_wp
    do i = 1, size(mcol)
       if (mcol(i) == jstar) c = c + mcoef(i)
    end do
    allocate (ncol(size(mcol) + size(col)), ncoef(size(mcol) + size(col)))
    n = 0
    do i = 1, size(mcol)
       if (mcol(i) == jstar) cycle
       n = n + 1
       ncol(n) = mcol(i)
       ncoef(n) = mcoef(i)
    end do
    do i = 1, size(col)
       if (col(i) == jstar) cycle
       n = n + 1
       ncol(n) = col(i)
       ncoef(n) = -c*coef(i)/piv
    end do
    ncol = ncol(1:n)
    ncoef = ncoef(1:n)
    call merge_terms(ncol, ncoef)
  end subroutine substitute

  subroutine compact_columns(tr, error)
    !! Drop eliminated columns and renumber maps, δ columns and forms.
    type(transform_t), intent(inout) :: tr
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: newc(:)
    integer(i8) :: j, n
    integer :: i, k, stat
    allocate (newc(tr%ncol_), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the column renumbering', tr%ncol_*BYTES_I8)
       return
    end if
    n = 0
    do j = 1, tr%ncol_
       if (tr%col_kind(j) == COL_DEAD) then
          newc(j) = 0
       else
          n = n + 1
          newc(j) = n
          tr%col_kind(n) = tr%col_kind(j)
          tr%col_ref(n) = tr%col_ref(j)
          tr%col_k(n) = tr%col_k(j)
          tr%col_g(n) = tr%col_g(j)
       end if
    end do
    if (n == tr%ncol_) return
    tr%ncol_ = n
    do j = 1, tr%pool_n
       tr%pool_col(j) = newc(tr%pool_col(j))
    end do
    do i = 1, size(tr%dcol, 2)
       do k = 1, 3
          if (tr%dcol(k, i) > 0) tr%dcol(k, i) = newc(tr%dcol(k, i))
       end do
    end do
    do i = 1, tr%nform
       tr%forms(i)%col = newc(tr%forms(i)%col)
    end do
  end subroutine compact_columns

  subroutine push_constraint(tr, cs)
    type(transform_t), intent(inout) :: tr
    type(constraint_t), intent(in) :: cs
    call grow(tr%cons, tr%ncons, INITIAL_CONS)
    tr%ncons = tr%ncons + 1
    tr%cons(tr%ncons) = cs
  end subroutine push_constraint

  subroutine push_form(tr, fs)
    type(transform_t), intent(inout) :: tr
    type(form_spring_t), intent(in) :: fs
    call grow(tr%forms, tr%nform, INITIAL_CONS)
    tr%nform = tr%nform + 1
    tr%forms(tr%nform) = fs
  end subroutine push_form

  subroutine transform_expand(tr, q, u, linear)
    !! u = T q + u0 over the physical DOFs (DOFs without a column: u0 only);
    !! with linear = .true., u = T q (a mode shape, no prescribed values).
    class(transform_t), intent(in) :: tr
    real(wp), intent(in) :: q(:, :)          !! (ncol, nrhs)
    real(wp), intent(out) :: u(:, :)         !! (np, nrhs)
    logical, intent(in), optional :: linear
    integer(i8) :: p, j
    integer :: is
    logical :: with_u0
    real(wp) :: s
    with_u0 = .true.
    if (present(linear)) with_u0 = .not. linear
    with_u0 = with_u0 .and. allocated(tr%u0)   ! else u0 is 0 (u0_of)
    do is = 1, size(q, 2)   ! a column at a time, each sum in a scalar (the same terms in the same order)
       do p = 1, size(tr%map_start, kind=i8) - 1
          s = 0.0_wp
          if (with_u0) s = tr%u0(p)
          do j = tr%map_start(p), tr%map_start(p + 1) - 1
             s = s + tr%pool_coef(j)*q(tr%pool_col(j), is)
          end do
          u(p, is) = s
       end do
    end do
  end subroutine transform_expand

  subroutine transform_reduce(tr, f, fr)
    !! fr = Tᵀ f (physical DOFs without a column contribute nothing).
    class(transform_t), intent(in) :: tr
    real(wp), intent(in) :: f(:, :)          !! (np, nrhs)
    real(wp), intent(out) :: fr(:, :)        !! (ncol, nrhs)
    integer(i8) :: p
    fr = 0.0_wp
    do p = 1, size(f, 1, kind=i8)
       if (all(f(p, :) == 0.0_wp)) cycle
       call tr%reduce_add(p, f(p, :), fr)
    end do
  end subroutine transform_reduce

  subroutine transform_reduce_add(tr, p, fp, fr)
    !! fr += Tᵀ e_p fpᵀ: the reduced image of a value on physical DOF p.
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: p
    real(wp), intent(in) :: fp(:)            !! (nrhs)
    real(wp), intent(inout) :: fr(:, :)      !! (ncol, nrhs)
    integer(i8) :: j
    do j = tr%map_start(p), tr%map_start(p + 1) - 1
       fr(tr%pool_col(j), :) = fr(tr%pool_col(j), :) + tr%pool_coef(j)*fp
    end do
  end subroutine transform_reduce_add

  subroutine transform_columns_of(tr, p, col, coef, n)
    !! The map of physical DOF p: u_p = Σ coef(k) q(col(k)) + u0(p), k = 1..n.
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: p
    integer(i8), intent(out) :: col(:)
    real(wp), intent(out) :: coef(:)
    integer, intent(out) :: n
    n = nmap(tr, p)
    col(1:n) = tr%pool_col(tr%map_start(p):tr%map_start(p) + n - 1)
    coef(1:n) = tr%pool_coef(tr%map_start(p):tr%map_start(p) + n - 1)
  end subroutine transform_columns_of
  pure function transform_ncol(tr) result(n)
    !! Number of reduced unknowns (columns).
    class(transform_t), intent(in) :: tr
    integer(i8) :: n
    n = tr%ncol_
  end function transform_ncol

  pure integer function transform_column_kind(tr, j)
    !! COL_PHYS or COL_DELTA.
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: j
    transform_column_kind = tr%col_kind(j)
  end function transform_column_kind

  pure function transform_column_ref(tr, j) result(r)
    !! Physical DOF of a COL_PHYS column, unit of a COL_DELTA column.
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: j
    integer(i8) :: r
    r = tr%col_ref(j)
  end function transform_column_ref

  pure integer function transform_column_comp(tr, j)
    !! Component (row of the unit's qs) of a COL_DELTA column.
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: j
    transform_column_comp = tr%col_k(j)
  end function transform_column_comp

  pure real(wp) function transform_column_g(tr, j)
    !! Spring stiffness on the diagonal of column j (0 for none).
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: j
    transform_column_g = tr%col_g(j)
  end function transform_column_g

  pure integer function transform_unit_role(tr, iu)
    !! ROLE_TREE (transformed) or ROLE_PLAIN (assembled as an element).
    class(transform_t), intent(in) :: tr
    integer, intent(in) :: iu
    transform_unit_role = tr%role(iu)
  end function transform_unit_role

  pure integer function transform_count_role(tr, role)
    !! Number of units with the given role.
    class(transform_t), intent(in) :: tr
    integer, intent(in) :: role
    transform_count_role = count(tr%role == role)
  end function transform_count_role

  pure function transform_delta_column(tr, k, iu) result(j)
    !! Column of δ_k of tree unit iu, or 0 (rigid, or not a tree unit).
    class(transform_t), intent(in) :: tr
    integer, intent(in) :: k, iu
    integer(i8) :: j
    j = tr%dcol(k, iu)
  end function transform_delta_column

  elemental real(wp) function transform_prescribed(tr, p)
    !! The prescribed part u0 of physical DOF p.
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: p
    transform_prescribed = u0_of(tr, p)
  end function transform_prescribed

  pure integer function transform_nforms(tr)
    !! Number of springs on linear forms (left by loop eliminations).
    class(transform_t), intent(in) :: tr
    transform_nforms = tr%nform
  end function transform_nforms

  function transform_form(tr, i) result(fs)
    !! Form spring i.
    class(transform_t), intent(in) :: tr
    integer, intent(in) :: i
    type(form_spring_t) :: fs
    fs = tr%forms(i)
  end function transform_form

  pure integer function transform_nconstraints(tr)
    !! Number of RIGID loop constraints (redundant or eliminated).
    class(transform_t), intent(in) :: tr
    transform_nconstraints = tr%ncons
  end function transform_nconstraints

  function transform_constraint(tr, i) result(cs)
    !! Loop constraint i.
    class(transform_t), intent(in) :: tr
    integer, intent(in) :: i
    type(constraint_t) :: cs
    cs = tr%cons(i)
  end function transform_constraint

  subroutine transform_release_maps(tr)
    !! Free the maps of the physical DOFs (u = T q + u0: map_start, the
    !! pool, u0) once their last user is done: after the expansion of u
    !! and the health of the whole system. What stays (columns, δ columns,
    !! roles, forms, constraints) is what the force recovery reads; expand,
    !! reduce, scatter, columns_of and prescribed may not be called after.
    class(transform_t), intent(inout) :: tr
    if (allocated(tr%map_start)) deallocate (tr%map_start)
    if (allocated(tr%pool_col)) deallocate (tr%pool_col)
    if (allocated(tr%pool_coef)) deallocate (tr%pool_coef)
    if (allocated(tr%u0)) deallocate (tr%u0)
    tr%pool_n = 0
  end subroutine transform_release_maps

  subroutine transform_refresh_springs(tr, table, ok)
    !! The springs on the δ columns taken again from the units of table: the
    !! same units with other finite g's (a joint study's next value, the
    !! forest and the units' states unchanged). Exact only without loop
    !! constraints and form springs (a loop's pivot is chosen by its spring,
    !! choose_pivot): then ok is false and tr is left as it was.
    class(transform_t), intent(inout) :: tr
    type(dof_table_t), intent(in) :: table
    logical, intent(out) :: ok
    integer(i8) :: j
    ok = tr%ncons == 0 .and. tr%nform == 0
    if (.not. ok) return
    do j = 1, tr%ncol_
       if (tr%col_kind(j) /= COL_DELTA) cycle
       associate (u => table%units(tr%col_ref(j)), k => tr%col_k(j))
         tr%col_g(j) = merge(u%g(k), 0.0_wp, u%state(k) == LINK_FINITE)
       end associate
    end do
  end subroutine transform_refresh_springs

  subroutine transform_element_columns(tr, pd, n, cols, nc)
    !! Reduced columns of a list of physical DOFs (sorted, unique) into cols(1:nc).
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: pd(:)
    integer, intent(in) :: n
    integer(i8), allocatable, intent(inout) :: cols(:)
    integer, intent(out) :: nc
    integer :: a, m
    integer(i8) :: j
    m = 0
    do a = 1, n
       m = m + nmap(tr, pd(a))
    end do
    if (size(cols) < m) then
       deallocate (cols)
       allocate (cols(2*m))
    end if
    m = 0
    do a = 1, n
       do j = tr%map_start(pd(a)), tr%map_start(pd(a) + 1) - 1
          m = m + 1
          cols(m) = tr%pool_col(j)
       end do
    end do
    call sort_unique_i8(cols(1:m), nc)
  end subroutine transform_element_columns

  subroutine transform_scatter_dense(tr, pd, ke, k, f_u0)
    !! Add Mᵀ ke M to k and -Mᵀ ke u0 to f_u0 for a large dense item (a
    !! superelement), entry by entry over the maps, with no dense M.
    class(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: pd(:)
    real(wp), intent(in) :: ke(:, :)
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(inout) :: f_u0(:)
    integer(i8), allocatable :: col(:, :)
    real(wp), allocatable :: coef(:, :), u0e(:), t(:, :)
    integer, allocatable :: nm(:)
    integer(i8), allocatable :: at(:)
    integer :: n, a, b, ia, ib, mmax
    integer(i8) :: pos, j
    n = size(pd)
    mmax = 1
    do a = 1, n
       mmax = max(mmax, nmap(tr, pd(a)))
    end do
    allocate (col(mmax, n), coef(mmax, n), nm(n), u0e(n))
    do a = 1, n
       call tr%columns_of(pd(a), col(:, a), coef(:, a), nm(a))
       u0e(a) = u0_of(tr, pd(a))
    end do
    ! at(row): the row's position in column col(ib, b) of k (its pattern
    ! spread once per column instead of a search per entry)
    allocate (at(k%n), source=0_i8)
    do b = 1, n
       do ib = 1, nm(b)
          j = col(ib, b)
          do pos = k%colptr(j), k%colptr(j + 1) - 1
             at(k%rowind(pos)) = pos
          end do
          do a = 1, n
             if (ke(a, b) == 0.0_wp) cycle
             do ia = 1, nm(a)
                if (col(ia, a) > j) cycle
                pos = at(col(ia, a))
                k%val(pos) = k%val(pos) + coef(ia, a)*coef(ib, b)*ke(a, b)
             end do
          end do
          at(k%rowind(k%colptr(j):k%colptr(j + 1) - 1)) = 0
       end do
    end do
    if (any(u0e /= 0.0_wp)) then
       t = matmul(ke, reshape(u0e, [n, 1]))
       do a = 1, n
          do ia = 1, nm(a)
             f_u0(col(ia, a)) = f_u0(col(ia, a)) - coef(ia, a)*t(a, 1)
          end do
       end do
    end if
  end subroutine transform_scatter_dense

  ! ------------------------------------------------------------------ growing arrays

#define GROW_NAME grow_constraint
#define GROW_TYPE type(constraint_t)
#include "grow_template.inc"

#define GROW_NAME grow_form_spring
#define GROW_TYPE type(form_spring_t)
#include "grow_template.inc"

end module superjoin_assembly_transform
