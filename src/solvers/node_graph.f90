module superjoin_solvers_node_graph
  !! The node graph of a symmetric matrix whose columns come in groups of
  !! consecutive columns (the unknowns of one node): the graph that fill-reducing
  !! orderings work on in structural codes, several times smaller than the
  !! column graph.
  use superjoin_kinds, only: i8
  use superjoin_solvers_sparse, only: sparse_sym_t
  implicit none (type, external)
  private

  public :: node_graph

contains

  subroutine node_graph(a, first, xadj, adjncy)
    !! Adjacency (1-based CSR, no self loops) of the groups: group g holds
    !! columns first(g) .. first(g+1)-1; two groups are adjacent when some
    !! entry of a couples their columns.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: first(:)
    integer(i8), allocatable, intent(out) :: xadj(:), adjncy(:)
    integer(i8), allocatable :: gid(:), mark(:), lptr(:), lcol(:), tmp(:), fill(:)
    integer(i8) :: ng, g, h, j, pos, nl, cap

    ng = size(first, kind=i8) - 1
    allocate (gid(a%n))
    do g = 1, ng
       gid(first(g):first(g + 1) - 1) = g
    end do
    ! Lower neighbours of each group (groups of the rows above its columns).
    allocate (mark(ng), source=0_i8)
    allocate (lptr(ng + 1))
    cap = max(16_i8, 4*ng)
    allocate (lcol(cap))
    nl = 0
    lptr(1) = 1
    do g = 1, ng
       mark(g) = g
       do j = first(g), first(g + 1) - 1
          do pos = a%colptr(j), a%colptr(j + 1) - 1
             h = gid(a%rowind(pos))
             if (mark(h) == g) cycle
             mark(h) = g
             if (nl == cap) then
                cap = 2*cap
                allocate (tmp(cap))
                tmp(1:nl) = lcol(1:nl)
                call move_alloc(tmp, lcol)
             end if
             nl = nl + 1
             lcol(nl) = h
          end do
       end do
       lptr(g + 1) = nl + 1
    end do
    ! Symmetric adjacency: each lower pair (g, h) in both lists.
    allocate (xadj(ng + 1), source=0_i8)
    do g = 1, ng
       do pos = lptr(g), lptr(g + 1) - 1
          h = lcol(pos)
          xadj(g + 1) = xadj(g + 1) + 1
          xadj(h + 1) = xadj(h + 1) + 1
       end do
    end do
    xadj(1) = 1
    do g = 1, ng
       xadj(g + 1) = xadj(g + 1) + xadj(g)
    end do
    allocate (adjncy(xadj(ng + 1) - 1), fill(ng))
    fill = xadj(1:ng)
    do g = 1, ng
       do pos = lptr(g), lptr(g + 1) - 1
          h = lcol(pos)
          adjncy(fill(g)) = h
          fill(g) = fill(g) + 1
          adjncy(fill(h)) = g
          fill(h) = fill(h) + 1
       end do
    end do
  end subroutine node_graph
end module superjoin_solvers_node_graph
