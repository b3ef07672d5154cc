module superjoin_assembly_forest
  !! Maximum spanning forest of the contact units, per DOF block.
  !!
  !! Vertices are the nodes of all substructures plus the ground (vertex 0). The
  !! stiffest units (RIGID first, then by largest g) form the forest; a tree that
  !! contains the ground is rooted there. Each tree unit is transformed with its
  !! child as the dependent side; the other units close loops.
  use superjoin_kinds, only: wp, i8
  use superjoin_model_types, only: LINK_FINITE, LINK_RIGID
  use superjoin_assembly_dofs, only: dof_table_t, unit_t, NBLOCK, GROUND, UNIT_LINK
  use superjoin_utils_sorting, only: sort_index
  use superjoin_utils_union_find, only: find_root
  use superjoin_error, only: error_t
  use superjoin_utils_memory, only: out_of_memory, BYTES_INT, BYTES_I8, BYTES_REAL
  implicit none (type, external)
  private

  type, public :: forest_t
    !! The forest: which units are tree edges, and in which direction.
     logical, allocatable :: tree(:)            !! (nunit) unit is a tree edge
     logical, allocatable :: child_is_a(:)      !! (nunit) the child is side a (master)
     integer, allocatable :: parent_unit(:, :)  !! (NBLOCK, 0:nvertex) tree unit above a vertex, 0 for roots
       !! (freed by forget_parents once the transform is built: order_unit serves the recovery)
     integer(i8), allocatable :: order(:, :)    !! (NBLOCK, max(norder)) vertices with a parent, parents first
     integer, allocatable :: order_unit(:, :)   !! (NBLOCK, max(norder)) the tree unit above order(b, io)
     integer(i8) :: norder(NBLOCK) = 0
  end type forest_t

  public :: build_forest, unit_weight, forget_parents, same_forest, forest_order

contains

  pure function unit_weight(u) result(w)
    !! Weight of a unit: RIGID is stiffest, then the largest finite g.
    type(unit_t), intent(in) :: u
    real(wp) :: w
    integer :: k
    w = 0.0_wp
    do k = 1, u%n
       if (u%state(k) == LINK_RIGID) then
          w = huge(1.0_wp)
       else if (u%state(k) == LINK_FINITE) then
          w = max(w, u%g(k))
       end if
    end do
  end function unit_weight

  subroutine build_forest(table, links_in_tree, forest, error)
    !! Build the forest. With `links_in_tree` false (PENALTY), only supports are
    !! transformed and every contact is assembled in plain form.
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: links_in_tree
    type(forest_t), intent(out) :: forest
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: uf(:)
    integer, allocatable :: cand(:)
    real(wp), allocatable :: w(:)
    integer :: b, i, nc, iu, stat
    integer(i8) :: ra, rb

    allocate (forest%tree(table%nunit), forest%child_is_a(table%nunit), source=.false., stat=stat)
    if (stat == 0) allocate (forest%parent_unit(NBLOCK, 0:table%nvertex), source=0, stat=stat)
    if (stat == 0) allocate (forest%order(NBLOCK, table%nvertex), forest%order_unit(NBLOCK, table%nvertex), stat=stat)
    if (stat == 0) allocate (uf(0:table%nvertex), cand(table%nunit), w(table%nunit), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the spanning forest', NBLOCK*(3*table%nvertex + 1)*BYTES_I8 + &
            (table%nvertex + 1)*BYTES_I8 + table%nunit*(3*BYTES_INT + BYTES_REAL))
       return
    end if

    do b = 1, NBLOCK
       call candidates(table, links_in_tree, b, w, cand, nc)
       do i = 0, int(table%nvertex)
          uf(i) = i
       end do
       do i = 1, nc
          iu = cand(i)
          ra = find_root(uf, table%units(iu)%va)
          rb = find_root(uf, table%units(iu)%vb)
          if (ra == rb) cycle
          ! Union towards the smaller root so that the ground (0) stays a root.
          if (ra < rb) then
             uf(rb) = ra
          else
             uf(ra) = rb
          end if
          forest%tree(iu) = .true.
       end do
       call orient_block(table, b, forest)
    end do
    forest%order = forest%order(:, 1:maxval(forest%norder))   ! the vertices with a parent: often few
    forest%order_unit = forest%order_unit(:, 1:maxval(forest%norder))
  end subroutine build_forest

  subroutine candidates(table, links_in_tree, b, w, cand, nc)
    !! The units of block b that may join the forest, cand(1:nc), in the
    !! order build_forest takes them: stiffest first (w: their weights).
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: links_in_tree
    integer, intent(in) :: b
    real(wp), intent(inout) :: w(:)
    integer, intent(inout) :: cand(:)
    integer, intent(out) :: nc
    integer :: i
    nc = 0
    do i = 1, table%nunit
       if (table%units(i)%block /= b) cycle
       if (table%units(i)%kind == UNIT_LINK .and. .not. links_in_tree) cycle
       nc = nc + 1
       cand(nc) = i
       w(i) = unit_weight(table%units(i))
    end do
    call sort_index(-w, cand(1:nc))
  end subroutine candidates

  function forest_order(table, links_in_tree) result(order)
    !! The units in the order build_forest takes them, block after block:
    !! two tables with the same units (but for their g's) and the same
    !! order give the same forest, so a joint study's next value can keep
    !! the previous forest without building it (its vertex arrays are what
    !! costs).
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: links_in_tree
    integer, allocatable :: order(:)
    real(wp), allocatable :: w(:)
    integer, allocatable :: cand(:)
    integer :: b, nc, n
    allocate (order(table%nunit), cand(table%nunit))
    allocate (w(table%nunit), source=0.0_wp)
    n = 0
    do b = 1, NBLOCK
       call candidates(table, links_in_tree, b, w, cand, nc)
       order(n + 1:n + nc) = cand(1:nc)
       n = n + nc
    end do
    order = order(1:n)
  end function forest_order

  subroutine forget_parents(forest)
    !! Free the parent unit of every vertex (NBLOCK integers per vertex of the
    !! model) once nothing looks it up by vertex any more: the recovery walks
    !! order and order_unit.
    type(forest_t), intent(inout) :: forest
    if (allocated(forest%parent_unit)) deallocate (forest%parent_unit)
  end subroutine forget_parents

  pure logical function same_forest(a, b)
    !! The same tree units, oriented alike and ordered alike (parent_unit
    !! follows from these).
    type(forest_t), intent(in) :: a, b
    integer :: k
    integer(i8) :: n
    same_forest = .false.
    if (.not. (allocated(a%tree) .and. allocated(b%tree) .and. allocated(a%order) .and. allocated(b%order))) return
    if (size(a%tree) /= size(b%tree) .or. any(a%norder /= b%norder)) return
    if (any(a%tree .neqv. b%tree) .or. any(a%child_is_a .neqv. b%child_is_a)) return
    do k = 1, NBLOCK   ! beyond norder(k), order holds nothing
       n = a%norder(k)
       if (any(a%order(k, 1:n) /= b%order(k, 1:n)) .or. any(a%order_unit(k, 1:n) /= b%order_unit(k, 1:n))) return
    end do
    same_forest = .true.
  end function same_forest

  subroutine orient_block(table, b, forest)
    !! Root every tree (at the ground if it has it, else at its lowest vertex) and
    !! record parents and a parents-first order.
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: b
    type(forest_t), intent(inout) :: forest
    integer(i8), allocatable :: adj_ptr(:), queue(:)
    integer, allocatable :: adj_unit(:)
    logical, allocatable :: seen(:)
    integer(i8) :: v, w, head, tail, start
    integer :: i, k

    allocate (adj_ptr(0:table%nvertex + 1), source=0_i8)
    do i = 1, table%nunit
       if (.not. forest%tree(i) .or. table%units(i)%block /= b) cycle
       adj_ptr(table%units(i)%va + 1) = adj_ptr(table%units(i)%va + 1) + 1
       adj_ptr(table%units(i)%vb + 1) = adj_ptr(table%units(i)%vb + 1) + 1
    end do
    do v = 1, table%nvertex + 1
       adj_ptr(v) = adj_ptr(v) + adj_ptr(v - 1)
    end do
    allocate (adj_unit(max(adj_ptr(table%nvertex + 1), 1_i8)))
    block
      integer(i8), allocatable :: fill(:)
      allocate (fill(0:table%nvertex))
      fill = adj_ptr(0:table%nvertex)
      do i = 1, table%nunit
         if (.not. forest%tree(i) .or. table%units(i)%block /= b) cycle
         fill(table%units(i)%va) = fill(table%units(i)%va) + 1
         adj_unit(fill(table%units(i)%va)) = i
         fill(table%units(i)%vb) = fill(table%units(i)%vb) + 1
         adj_unit(fill(table%units(i)%vb)) = i
      end do
    end block

    allocate (seen(0:table%nvertex), source=.false.)
    allocate (queue(table%nvertex + 1))
    forest%norder(b) = 0
    do start = GROUND, table%nvertex
       if (seen(start)) cycle
       if (adj_ptr(start + 1) == adj_ptr(start)) cycle
       seen(start) = .true.
       head = 1
       tail = 1
       queue(1) = start
       do while (head <= tail)
          v = queue(head)
          head = head + 1
          do k = int(adj_ptr(v)) + 1, int(adj_ptr(v + 1))
             i = adj_unit(k)
             if (table%units(i)%va == v) then
                w = table%units(i)%vb
             else
                w = table%units(i)%va
             end if
             if (seen(w)) cycle
             seen(w) = .true.
             forest%parent_unit(b, w) = i
             forest%child_is_a(i) = (w == table%units(i)%va)
             tail = tail + 1
             queue(tail) = w
             forest%norder(b) = forest%norder(b) + 1
             forest%order(b, forest%norder(b)) = w
             forest%order_unit(b, forest%norder(b)) = i
          end do
       end do
    end do
  end subroutine orient_block

end module superjoin_assembly_forest
