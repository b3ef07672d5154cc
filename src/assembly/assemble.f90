module superjoin_assembly_assemble
  !! Assembly of the reduced stiffness K_red = Tᵀ K_phys T + diag(g on δ) and of
  !! the reduced loads, without forming T: every element and plain contact is
  !! scattered through the maps of its physical DOFs.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: MAX_ELEMENT_DOFS
  use superjoin_error, only: error_t, add_error_line, EXIT_DECK, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, ELEMENT_NODE_COUNT, LINK_FINITE, loc_text
  use superjoin_elements, only: element_dof_mask, element_stiffness, distributed_load
  use superjoin_assembly_dofs, only: dof_table_t, vertex_dofs, GROUND, block_dof, unit_dofs, unit_terms, MAX_UNIT_TERMS
  use superjoin_assembly_transform, only: transform_t, form_spring_t, ROLE_PLAIN
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_solver, only: linear_solver_t
  use superjoin_solvers_pattern, only: build_pattern, find_entry, items_of_columns, zero_values
  use superjoin_utils_strings, only: itoa
  use superjoin_assembly_scatter_map, only: scatter_map_t, build_scatter_map, scatter_item
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL, BYTES_I8
  use superjoin_utils_huge_pages, only: advise_huge
  use superjoin_elements_drill_mask, only: element_drill
  implicit none (type, external)
  private

  integer, parameter :: MAX_ITEM_DOFS = MAX_ELEMENT_DOFS
    !! Largest number of physical DOFs one item (element or contact) touches.

  type, public :: superelement_t
    !! A condensed substructure as the interface sees it: a dense symmetric
    !! stiffness K* on physical (boundary) DOFs, in their physical numbering.
     integer(i8), allocatable :: pdof(:)      !! (nb) physical DOFs
     real(wp), allocatable :: k(:, :)         !! (nb, nb)
     integer :: same_k = 0
       !! > 0: k is not held here but is that superelement's of the same
       !! plan (an instance sharing its part's condensation, unturned)
  end type superelement_t

  type, public :: assembly_plan_t
    !! What goes into the reduced matrix besides contacts and springs.
     logical, allocatable :: skip_sub(:)      !! (nsub) elements left out (condensed substructures)
     type(superelement_t), allocatable :: supers(:)  !! their condensed stiffness instead
     logical :: supers_moved = .false.
       !! supers(i)%k moved from the condensed parts, not copied: moved back after
       !! the assembly (analysis/condensation)
     logical :: shared = .true.
       !! the terms that belong to no substructure (plain contact units, loop
       !! springs, g of the δ columns) go in; .false. for a term of K_red that
       !! is summed with others (one process's share under MPI)
  end type assembly_plan_t

  type :: item_columns_t
    !! The reduced columns of the items of K_red (elements, superelements,
    !! plain units, form springs), item after item: item i's columns are
    !! col(ptr(i):ptr(i+1)-1).
     integer(i8), allocatable :: ptr(:)     !! (items + 1)
     integer(i8), allocatable :: col(:)     !! grows by doubling
     integer(i8) :: n = 0                   !! items listed so far
     integer(i8) :: supers_after = 0        !! items before the superelements (scattered densely, no map)
  end type item_columns_t

  public :: element_matrix
  public :: assemble_stiffness, assemble_loads, element_pdofs, unit_pdofs, unit_plain_stiffness, &
       max_element_diagonal, add_delta_springs

contains

  subroutine element_pdofs(model, table, isub, e, pd, n)
    !! Physical DOFs of element e of substructure isub, in element ordering.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    integer(i8), intent(out) :: pd(:)
    integer, intent(out) :: n
    logical :: mask(6)
    integer :: a, d
    integer(i8) :: pv(6)
    associate (s => model%subs(isub))
      mask = element_dof_mask(s%elem_type(e))
      n = 0
      do a = 1, ELEMENT_NODE_COUNT(s%elem_type(e))
         call vertex_dofs(table, table%vertex_offset(isub) + s%elem_nodes(a, e), pv)
         do d = 1, 6
            if (.not. mask(d)) cycle
            n = n + 1
            pd(n) = pv(d)
         end do
      end do
    end associate
  end subroutine element_pdofs

  subroutine unit_pdofs(table, iu, pd, n)
    !! Physical DOFs of a unit assembled in plain form: side a's components, side
    !! b's, then side a's rotations for an eccentric unit (OFFSET=RIGID).
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: iu
    integer(i8), intent(out) :: pd(:)
    integer, intent(out) :: n
    integer(i8) :: p(MAX_UNIT_TERMS)
    call unit_dofs(table, table%units(iu), p, n)
    pd(1:n) = p(1:n)
  end subroutine unit_pdofs

  subroutine unit_plain_stiffness(table, iu, ke, n)
    !! Plain stiffness of a unit's finite components over unit_pdofs ordering:
    !! Σ_k g_k w_k w_kᵀ with δ_k = w_kᵀ u (S = qsᵀ G qs, [S -S; -S S], or S
    !! alone against the ground, for a concentric unit).
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: iu
    real(wp), intent(out) :: ke(:, :)
    integer, intent(out) :: n
    integer(i8) :: p(MAX_UNIT_TERMS)
    real(wp) :: w(MAX_UNIT_TERMS)
    integer :: i, j, k
    associate (u => table%units(iu))
      call unit_dofs(table, u, p, n)
      ke(1:n, 1:n) = 0.0_wp
      do k = 1, u%n
         if (u%state(k) /= LINK_FINITE) cycle
         call unit_terms(table, u, k, p, w, n)
         do j = 1, n
            do i = 1, n
               ke(i, j) = ke(i, j) + w(i)*u%g(k)*w(j)
            end do
         end do
      end do
    end associate
  end subroutine unit_plain_stiffness

  subroutine max_element_diagonal(model, table, dmax, error, only)
    !! Largest diagonal entry of the physical stiffness of the elements alone
    !! (the scale for RIGID=LARGE); with `only`, of the substructures it marks
    !! (and their element errors first, in deck order).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    real(wp), intent(out) :: dmax
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: only(:)
    real(wp), allocatable :: diag(:), ke(:, :)
    integer(i8) :: pd(MAX_ITEM_DOFS)
    integer :: isub, n, a
    integer(ip) :: e
    integer :: stat
    allocate (diag(table%np), source=0.0_wp, stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the element diagonal', table%np*BYTES_REAL)
       return
    end if
    do isub = 1, size(model%subs)
       if (present(only)) then
          if (.not. only(isub)) cycle
       end if
       associate (s => model%subs(isub))
         do e = 1, s%nelem
            call element_matrix(model, isub, e, ke, error)
            if (allocated(error)) return
            call element_pdofs(model, table, isub, e, pd, n)
            do a = 1, n
               diag(pd(a)) = diag(pd(a)) + ke(a, a)
            end do
         end do
       end associate
    end do
    dmax = 0.0_wp
    if (table%np > 0) dmax = maxval(diag)
  end subroutine max_element_diagonal

  subroutine element_matrix(model, isub, e, ke, error, x)
    !! Element stiffness in global axes, with the deck location on errors.
    !! x: the substructure's nodes at these coordinates instead of its own.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: x(:, :)
    type(error_t), allocatable :: inner
    integer :: nn
    associate (s => model%subs(isub))
      nn = ELEMENT_NODE_COUNT(s%elem_type(e))
      if (present(x)) then
         call element_stiffness(s%elem_type(e), x(:, s%elem_nodes(1:nn, e)), &
              s%sections(s%elem_section(e)), model%materials(s%sections(s%elem_section(e))%material), &
              ke, inner, element_drill(s, e))
      else
         call element_stiffness(s%elem_type(e), s%x(:, s%elem_nodes(1:nn, e)), &
              s%sections(s%elem_section(e)), model%materials(s%sections(s%elem_section(e))%material), &
              ke, inner, element_drill(s, e))
      end if
      if (allocated(inner)) call add_error_line(error, EXIT_DECK, element_where(model, isub, e)// &
           ': error: element '//itoa(int(s%elem_id(e)))//': '//inner%message)
    end associate
  end subroutine element_matrix

  function element_where(model, isub, e) result(text)
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    character(:), allocatable :: text
    if (allocated(model%subs(isub)%elem_loc)) then
       text = loc_text(model, model%subs(isub)%elem_loc(e))
    else
       text = loc_text(model, model%subs(isub)%loc)
    end if
  end function element_where

  subroutine assemble_stiffness(model, table, tr, plan, k, f_u0, error, solver, springs)
    !! Assemble K_red (pattern and values) and the reduced load of the
    !! prescribed values, f_u0 = -Tᵀ K_phys u0: the elements of every
    !! substructure the plan does not skip, the plan's superelements, plain
    !! contact units, loop springs, and g on the diagonal of every δ (these
    !! three only if plan%shared). With solver: its analysis of K's pattern
    !! begins once the pattern is known (analyze_start), beside the values.
    !! springs = .false.: without the g's of the δ columns (add_delta_springs
    !! adds them: a joint study keeps K_red without them for its next value).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(assembly_plan_t), intent(in) :: plan
    type(sparse_sym_t), intent(out) :: k
    real(wp), allocatable, intent(out) :: f_u0(:)
    type(error_t), allocatable, intent(out) :: error
    class(linear_solver_t), intent(inout), optional :: solver
    logical, intent(in), optional :: springs
    type(item_columns_t) :: items
    type(scatter_map_t) :: map
    integer(i8), allocatable :: col_ptr(:), col_item(:)
    logical, allocatable :: mapped(:)
    integer :: stat

    ! Pass 1: column lists of all items.
    call list_item_columns(model, table, tr, plan, items, error)
    if (allocated(error)) return

    ! Transpose: items of each column.
    call items_of_columns(tr%ncol(), items%ptr(1:items%n + 1), items%col, col_ptr, col_item, error)
    if (allocated(error)) return

    call build_pattern(tr%ncol(), items%ptr, items%col, col_ptr, col_item, k, error, values=.false.)
    if (allocated(error)) return
    if (present(solver)) call solver%analyze_start(k)
    call zero_values(k, error)   ! beside the analysis: nnz zeros, off its path
    if (allocated(error)) return
    allocate (mapped(items%n), source=.true.)
    mapped(items%supers_after + 1:items%supers_after + size(plan%supers)) = .false.   ! scatter_dense
    call build_scatter_map(k, items%ptr(1:items%n + 1), items%col, col_ptr, col_item, mapped, map, error)
    if (allocated(error)) return
    deallocate (col_ptr, col_item)

    ! Pass 2: values.
    allocate (f_u0(tr%ncol()), source=0.0_wp, stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the reduced load', tr%ncol()*BYTES_REAL)
       return
    end if
    call scatter_items(model, table, tr, plan, items, map, k, f_u0, error)
    if (allocated(error)) return
    if (present(springs)) then
       if (.not. springs) return
    end if
    call add_delta_springs(tr, plan, k)
  end subroutine assemble_stiffness

  subroutine add_delta_springs(tr, plan, k)
    !! The δ springs (if plan%shared): g on the diagonal of their own column,
    !! nowhere else.
    type(transform_t), intent(in) :: tr
    type(assembly_plan_t), intent(in) :: plan
    type(sparse_sym_t), intent(inout) :: k
    integer(i8) :: j
    real(wp) :: g
    do j = 1, merge(tr%ncol(), 0_i8, plan%shared)
       g = tr%column_g(j)
       if (g /= 0.0_wp) k%val(k%colptr(j + 1) - 1) = k%val(k%colptr(j + 1) - 1) + g
    end do
  end subroutine add_delta_springs

  pure function shared_forms(tr, plan) result(nforms)
    !! Number of loop springs (form springs) the plan assembles.
    type(transform_t), intent(in) :: tr
    type(assembly_plan_t), intent(in) :: plan
    integer :: nforms
    nforms = 0
    if (plan%shared) nforms = tr%nforms()
  end function shared_forms

  subroutine list_item_columns(model, table, tr, plan, items, error)
    !! The reduced columns of every item the plan assembles, in this order:
    !! elements of every substructure not skipped, superelements, plain
    !! units, form springs (the order of scatter_items).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(assembly_plan_t), intent(in) :: plan
    type(item_columns_t), intent(out) :: items
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: cols(:)
    integer(i8) :: pd(MAX_ITEM_DOFS), nitem
    integer :: isub, n, nc, iu, i, nforms, stat
    integer(ip) :: e
    type(form_spring_t) :: fs

    nforms = shared_forms(tr, plan)
    nitem = nforms + size(plan%supers)
    do isub = 1, size(model%subs)
       if (plan%skip_sub(isub)) cycle
       nitem = nitem + model%subs(isub)%nelem
    end do
    if (plan%shared) nitem = nitem + tr%count_role(ROLE_PLAIN)
    allocate (items%ptr(nitem + 1), cols(64), items%col(max(16_i8, 12*nitem)), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the column lists of the elements', (13*nitem + 1)*BYTES_I8)
       return
    end if
    call advise_huge(items%col)
    items%ptr(1) = 1
    items%n = 0
    do isub = 1, size(model%subs)
       if (plan%skip_sub(isub)) cycle
       do e = 1, model%subs(isub)%nelem
          call element_pdofs(model, table, isub, e, pd, n)
          call tr%element_columns(pd, n, cols, nc)
          call append_item(items, cols(1:nc), error)
          if (allocated(error)) return
       end do
    end do
    items%supers_after = items%n
    do i = 1, size(plan%supers)
       call tr%element_columns(plan%supers(i)%pdof, size(plan%supers(i)%pdof), cols, nc)
       call append_item(items, cols(1:nc), error)
       if (allocated(error)) return
    end do
    do iu = 1, table%nunit
       if (tr%unit_role(iu) /= ROLE_PLAIN .or. .not. plan%shared) cycle
       call unit_pdofs(table, iu, pd, n)
       call tr%element_columns(pd, n, cols, nc)
       call append_item(items, cols(1:nc), error)
       if (allocated(error)) return
    end do
    do i = 1, nforms
       fs = tr%form(i)
       call append_item(items, fs%col, error)
       if (allocated(error)) return
    end do
  end subroutine list_item_columns

  subroutine append_item(items, c, error)
    !! The columns c of the next item at the end of items (the column list
    !! doubles when full).
    type(item_columns_t), intent(inout) :: items
    integer(i8), intent(in) :: c(:)
    type(error_t), allocatable, intent(inout) :: error
    integer(i8), allocatable :: tmp(:)
    integer(i8) :: need, cap
    integer :: stat
    items%n = items%n + 1
    associate (it => items%n)
      need = items%ptr(it) + size(c) - 1
      if (need > size(items%col, kind=i8)) then
         cap = max(2*size(items%col, kind=i8), need)
         allocate (tmp(cap), stat=stat)
         if (stat /= 0) then
            call out_of_memory(error, 'the column lists of the elements', cap*BYTES_I8)
            return
         end if
         tmp(1:items%ptr(it) - 1) = items%col(1:items%ptr(it) - 1)
         call move_alloc(tmp, items%col)
      end if
      items%col(items%ptr(it):need) = c
      items%ptr(it + 1) = need + 1
    end associate
  end subroutine append_item

  subroutine scatter_items(model, table, tr, plan, items, map, k, f_u0, error)
    !! Add the stiffness of every item of list_item_columns to the values of
    !! k (pattern built from items, positions from map) and its
    !! prescribed-value load to f_u0.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(assembly_plan_t), intent(in) :: plan
    type(item_columns_t), intent(in) :: items
    type(scatter_map_t), intent(in) :: map
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(inout) :: f_u0(:)
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: pd(MAX_ITEM_DOFS), it
    integer :: isub, n, iu, i
    integer(ip) :: e
    real(wp), allocatable :: ke(:, :)
    type(form_spring_t) :: fs

    it = 0
    do isub = 1, size(model%subs)
       if (plan%skip_sub(isub)) cycle
       do e = 1, model%subs(isub)%nelem
          it = it + 1
          call element_matrix(model, isub, e, ke, error)
          if (allocated(error)) return
          call element_pdofs(model, table, isub, e, pd, n)
          call scatter_item(tr, pd(1:n), ke, items%col(items%ptr(it):items%ptr(it + 1) - 1), &
               it, map, k, f_u0)
       end do
    end do
    do i = 1, size(plan%supers)
       it = it + 1
       associate (own => plan%supers(merge(plan%supers(i)%same_k, i, plan%supers(i)%same_k > 0)))
         call tr%scatter_dense(plan%supers(i)%pdof, own%k, k, f_u0)
       end associate
    end do
    if (.not. allocated(ke)) allocate (ke(MAX_UNIT_TERMS, MAX_UNIT_TERMS))
    if (size(ke, 1) < MAX_UNIT_TERMS .or. size(ke, 2) < MAX_UNIT_TERMS) then
       deallocate (ke)
       allocate (ke(MAX_UNIT_TERMS, MAX_UNIT_TERMS))
    end if
    do iu = 1, table%nunit
       if (tr%unit_role(iu) /= ROLE_PLAIN .or. .not. plan%shared) cycle
       it = it + 1
       call unit_pdofs(table, iu, pd, n)
       call unit_plain_stiffness(table, iu, ke, n)
       call scatter_item(tr, pd(1:n), ke(1:n, 1:n), items%col(items%ptr(it):items%ptr(it + 1) - 1), &
            it, map, k, f_u0)
    end do
    do i = 1, shared_forms(tr, plan)
       it = it + 1
       fs = tr%form(i)
       call scatter_form(fs%col, fs%coef, fs%g, fs%const, k, f_u0)
    end do
  end subroutine scatter_items


  subroutine scatter_form(col, coef, g, c, k, f_u0)
    !! Add g a aᵀ to k and -g a c to f_u0 for a spring on aᵀq + c.
    integer(i8), intent(in) :: col(:)
    real(wp), intent(in) :: coef(:), g, c
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(inout) :: f_u0(:)
    integer :: a, b
    integer(i8) :: pos
    do b = 1, size(col)
       do a = 1, size(col)
          if (col(a) > col(b)) cycle
          pos = find_entry(k, col(a), col(b))
          k%val(pos) = k%val(pos) + g*coef(a)*coef(b)
       end do
       f_u0(col(b)) = f_u0(col(b)) - g*coef(b)*c
    end do
  end subroutine scatter_form

  subroutine assemble_loads(model, table, f_phys, error)
    !! Physical loads of every step, f_phys(np, nstep), and the local distributed
    !! load of each loaded beam (for element forces): see dload_local.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    real(wp), allocatable, intent(out) :: f_phys(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer :: is, i, n, a, nn
    integer(i8) :: p, pd(MAX_ITEM_DOFS)
    real(wp), allocatable :: fe(:)
    real(wp) :: ql(3)
    type(error_t), allocatable :: inner

    integer :: stat

    allocate (f_phys(table%np, size(model%steps)), source=0.0_wp, stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the loads of '//itoa(size(model%steps))//' steps', &
            table%np*size(model%steps)*BYTES_REAL)
       return
    end if
    do is = 1, size(model%steps)
       associate (st => model%steps(is))
         do i = 1, size(st%cloads)
            associate (cl => st%cloads(i))
              p = table%dof(cl%dof, table%vertex_offset(cl%sub) + cl%node)
              if (p == 0) then
                 call add_error_line(error, EXIT_SINGULAR, loc_text(model, cl%loc)// &
                      ': error: load on DOF '//itoa(cl%dof)//' of a node that has no such DOF '// &
                      '(no element, contact or support gives it)')
                 cycle
              end if
              f_phys(p, is) = f_phys(p, is) + cl%value
            end associate
         end do
         if (allocated(st%dloads)) then
            do i = 1, size(st%dloads)
               associate (dl => st%dloads(i), s => model%subs(st%dloads(i)%sub))
                 nn = ELEMENT_NODE_COUNT(s%elem_type(dl%elem))
                 call distributed_load(model, dl, fe, ql, inner)
                 if (allocated(inner)) then
                    call add_error_line(error, EXIT_DECK, loc_text(model, dl%loc)//': error: '//inner%message)
                    deallocate (inner)
                    cycle
                 end if
                 call element_pdofs(model, table, dl%sub, dl%elem, pd, n)
                 do a = 1, n
                    f_phys(pd(a), is) = f_phys(pd(a), is) + fe(a)
                 end do
               end associate
            end do
         end if
       end associate
    end do
  end subroutine assemble_loads
end module superjoin_assembly_assemble
