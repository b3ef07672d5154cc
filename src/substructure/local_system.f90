module superjoin_substructure_local_system
  !! One substructure on its own: its physical DOFs in a local numbering
  !! (interior first, then boundary) and its stiffness assembled from its
  !! elements alone, k = [k_ii k_ib; k_bi k_bb]. Boundary DOFs are those a
  !! contact element or a support touches; no contact stiffness enters k.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: MAX_ELEMENT_DOFS
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, given_matrix_t, NDOF_NODE
  use superjoin_assembly_dofs, only: dof_table_t, vertex_dofs, unit_dofs, MAX_UNIT_TERMS
  use superjoin_assembly_assemble, only: element_pdofs, element_matrix
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_pattern, only: build_pattern, find_entry, items_of_columns
  use superjoin_utils_sorting, only: sort_unique_i8
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory, BYTES_I8
  implicit none (type, external)
  private

    !! Largest number of DOFs of one element.

  type, public :: local_system_t
    !! A substructure's DOFs and element stiffness in its own numbering.
     integer :: isub = 0
     integer(i8) :: ni = 0                   !! interior DOFs (local 1..ni)
     integer(i8) :: nb = 0                   !! boundary DOFs (local ni+1..ni+nb)
     integer(i8), allocatable :: pdof(:)     !! (ni+nb) physical DOF of each local DOF
     type(sparse_sym_t) :: k                 !! element stiffness, local numbering
   contains
     procedure :: n => local_size
  end type local_system_t

  public :: boundary_dofs, part_boundary, given_boundary, build_local_system, local_numbering, dof_label

contains

  pure function local_size(sys) result(n)
    !! Number of local DOFs.
    class(local_system_t), intent(in) :: sys
    integer(i8) :: n
    n = sys%ni + sys%nb
  end function local_size

  subroutine boundary_dofs(table, bnd)
    !! bnd(p): physical DOF p is touched by a contact element or a support.
    type(dof_table_t), intent(in) :: table
    logical, allocatable, intent(out) :: bnd(:)
    integer(i8) :: p(MAX_UNIT_TERMS)
    integer :: iu, c, n
    allocate (bnd(table%np), source=.false.)
    do iu = 1, table%nunit
       ! Both sides, and the master's rotations of an eccentric unit (OFFSET=RIGID).
       call unit_dofs(table, table%units(iu), p, n)
       do c = 1, n
          if (p(c) > 0) bnd(p(c)) = .true.
       end do
    end do
    ! The DOFs of *EQUATION constraints are eliminated in the reduced system.
    do iu = 1, size(table%equations)
       bnd(table%equations(iu)%p) = .true.
    end do
  end subroutine boundary_dofs

  subroutine local_numbering(table, isub, bnd, pdof, ni)
    !! Substructure isub's physical DOFs in local order: interior first, then
    !! boundary, each in physical order; ni interior DOFs.
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    logical, intent(in) :: bnd(:)
    integer(i8), allocatable, intent(out) :: pdof(:)
    integer(i8), intent(out) :: ni
    integer(i8) :: v, p, p_lo, n, l, pv(NDOF_NODE)
    integer :: d
    ! The substructure's physical DOFs are consecutive (numbered substructure by substructure).
    n = 0
    p_lo = 0
    do v = table%vertex_offset(isub) + 1, table%vertex_offset(isub + 1)
       call vertex_dofs(table, v, pv)
       do d = 1, NDOF_NODE
          p = pv(d)
          if (p == 0) cycle
          if (n == 0) p_lo = p
          n = n + 1
       end do
    end do
    allocate (pdof(n))
    ni = count(.not. bnd(p_lo:p_lo + n - 1), kind=i8)
    l = 0
    do p = p_lo, p_lo + n - 1
       if (bnd(p)) cycle
       l = l + 1
       pdof(l) = p
    end do
    do p = p_lo, p_lo + n - 1
       if (.not. bnd(p)) cycle
       l = l + 1
       pdof(l) = p
    end do
  end subroutine local_numbering

  subroutine part_boundary(model, table, bnd, bnd_part)
    !! The boundary of every instance of a part is the union of its instances'
    !! boundaries (by local node and DOF), so that one condensation serves them
    !! all; other substructures keep their own. bnd_part(p) for every DOF.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    logical, allocatable, intent(out) :: bnd_part(:)
    type :: marks_t
       logical, allocatable :: m(:, :)     ! (6, nnode)
    end type marks_t
    type(marks_t), allocatable :: marks(:)
    integer(i8) :: p
    integer :: isub, ipart
    bnd_part = bnd
    if (.not. allocated(model%parts)) return
    if (size(model%parts) == 0) return
    allocate (marks(size(model%parts)))
    do isub = 1, size(model%subs)
       ipart = model%subs(isub)%part
       if (ipart == 0) cycle
       if (.not. allocated(marks(ipart)%m)) allocate (marks(ipart)%m(NDOF_NODE, model%subs(isub)%nnode), &
            source=.false.)
    end do
    do p = 1, table%np
       ipart = model%subs(table%p_sub(p))%part
       if (ipart == 0 .or. .not. bnd(p)) cycle
       marks(ipart)%m(table%p_dof(p), table%p_node(p)) = .true.
    end do
    do p = 1, table%np
       ipart = model%subs(table%p_sub(p))%part
       if (ipart == 0) cycle
       bnd_part(p) = marks(ipart)%m(table%p_dof(p), table%p_node(p))
    end do
  end subroutine part_boundary

  subroutine given_boundary(model, table, bnd)
    !! Every DOF of a substructure with a given stiffness (*MATRIX INPUT) is on
    !! its condensation boundary: its interior is empty and K* is the matrix.
    !! So are the DOFs of the nodes an export retains (*SUBSTRUCTURE MATRIX
    !! OUTPUT, RETAIN=).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(inout) :: bnd(:)
    integer(i8) :: p
    integer :: k, d
    integer(ip) :: i
    do p = 1, table%np
       if (allocated(model%subs(table%p_sub(p))%given)) bnd(p) = .true.
    end do
    if (.not. allocated(model%exports)) return
    do k = 1, size(model%exports)
       if (.not. allocated(model%exports(k)%retain)) cycle
       associate (x => model%exports(k))
         do i = 1, size(x%retain)
            do d = 1, NDOF_NODE
               p = table%dof(d, table%vertex_offset(x%sub) + x%retain(i))
               if (p > 0) bnd(p) = .true.
            end do
         end do
       end associate
    end do
  end subroutine given_boundary

  subroutine build_local_system(model, table, isub, bnd, sys, error)
    !! Number substructure isub's DOFs (see local_numbering) and assemble its
    !! element stiffness.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    logical, intent(in) :: bnd(:)
    type(local_system_t), intent(out) :: sys
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: local(:), item_ptr(:), item_col(:), col_ptr(:), col_item(:)
    integer(i8) :: p_lo, n, l, pd(MAX_ELEMENT_DOFS), cols(MAX_ELEMENT_DOFS)
    integer(i8) :: it, nitem, ng
    integer(i8), allocatable :: pg(:)
    integer(ip) :: e
    integer :: nd, a, b, nc, stat
    real(wp), allocatable :: ke(:, :)
    integer(i8) :: pos

    sys%isub = isub
    call local_numbering(table, isub, bnd, sys%pdof, sys%ni)
    n = size(sys%pdof, kind=i8)
    sys%nb = n - sys%ni
    p_lo = 1
    if (n > 0) p_lo = minval(sys%pdof)
    allocate (local(n), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the local numbering of substructure '//model%subs(isub)%name, n*BYTES_I8)
       return
    end if
    do l = 1, n
       local(sys%pdof(l) - p_lo + 1) = l
    end do

    ! Pattern from the elements' local columns.
    associate (s => model%subs(isub))
      nitem = s%nelem
      ng = 0
      if (allocated(s%given)) then
         call given_pdofs(table, isub, s%given, pg)
         ng = size(pg, kind=i8)
      end if
      allocate (item_ptr(nitem + 2), item_col(max(1_i8, MAX_ELEMENT_DOFS*nitem + ng)), stat=stat)
      if (stat /= 0) then
         call out_of_memory(error, 'the element lists of substructure '//s%name, &
              (MAX_ELEMENT_DOFS + 1)*nitem*BYTES_I8)
         return
      end if
      item_ptr(1) = 1
      do e = 1, s%nelem
         call element_pdofs(model, table, isub, e, pd, nd)
         cols(1:nd) = local(pd(1:nd) - p_lo + 1)
         call sort_unique_i8(cols(1:nd), nc)
         item_col(item_ptr(e):item_ptr(e) + nc - 1) = cols(1:nc)
         item_ptr(e + 1) = item_ptr(e) + nc
      end do
      if (ng > 0) then   ! the given stiffness: one dense item
         nitem = nitem + 1
         item_col(item_ptr(nitem):item_ptr(nitem) + ng - 1) = local(pg - p_lo + 1)
         call sort_unique_i8(item_col(item_ptr(nitem):item_ptr(nitem) + ng - 1), nc)
         item_ptr(nitem + 1) = item_ptr(nitem) + nc
      end if
      call items_of_columns(n, item_ptr(1:nitem + 1), item_col, col_ptr, col_item, error)
      if (allocated(error)) return
      call build_pattern(n, item_ptr(1:nitem + 1), item_col, col_ptr, col_item, sys%k, error)
      if (allocated(error)) return
      deallocate (item_ptr, item_col, col_ptr, col_item)
      if (ng > 0) call add_given(sys%k, local(pg - p_lo + 1), s%given%k)

      do it = 1, s%nelem
         e = int(it, ip)
         call element_matrix(model, isub, e, ke, error)
         if (allocated(error)) return
         call element_pdofs(model, table, isub, e, pd, nd)
         do b = 1, nd
            do a = 1, nd
               if (local(pd(a) - p_lo + 1) > local(pd(b) - p_lo + 1)) cycle
               pos = find_entry(sys%k, local(pd(a) - p_lo + 1), local(pd(b) - p_lo + 1))
               sys%k%val(pos) = sys%k%val(pos) + ke(a, b)
            end do
         end do
      end do
    end associate
  end subroutine build_local_system

  subroutine given_pdofs(table, isub, g, pg)
    !! The physical DOF of each row of a given stiffness (*MATRIX INPUT).
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    type(given_matrix_t), intent(in) :: g
    integer(i8), allocatable, intent(out) :: pg(:)
    integer :: r
    allocate (pg(size(g%dof)))
    do r = 1, size(g%dof)
       pg(r) = table%dof(g%dof(r), table%vertex_offset(isub) + g%node(r))
    end do
  end subroutine given_pdofs

  subroutine add_given(k, lg, g)
    !! k += g on the local DOFs lg (upper triangle of the local numbering).
    type(sparse_sym_t), intent(inout) :: k
    integer(i8), intent(in) :: lg(:)
    real(wp), intent(in) :: g(:, :)
    integer :: a, b
    integer(i8) :: pos
    do b = 1, size(lg)
       do a = 1, size(lg)
          if (lg(a) > lg(b)) cycle
          pos = find_entry(k, lg(a), lg(b))
          k%val(pos) = k%val(pos) + g(a, b)
       end do
    end do
  end subroutine add_given

  function dof_label(model, table, p) result(label)
    !! "substructure S node N DOF d" of physical DOF p.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer(i8), intent(in) :: p
    character(:), allocatable :: label
    label = 'substructure '//model%subs(table%p_sub(p))%name//' node '// &
         itoa(int(model%subs(table%p_sub(p))%node_id(table%p_node(p))))//' DOF '//itoa(int(table%p_dof(p)))
  end function dof_label
end module superjoin_substructure_local_system
