module superjoin_deck_eccentric
  !! Checks of eccentric contacts (*CONTACT, OFFSET=RIGID) once the model is
  !! built: the slave hangs on a rigid arm from the master, so every master node
  !! must carry rotational DOFs (from a beam or shell element, or a support).
  use superjoin_kinds, only: ip
  use superjoin_model_types, only: model_t, ELEMENT_NODE_COUNT, node_label
  use superjoin_elements, only: element_dof_mask
  use superjoin_deck_state, only: deck_state_t, report_loc
  implicit none (type, external)
  private

  integer, parameter :: ROT_FIRST = 4, ROT_LAST = 6
    !! The rotational DOFs.

  public :: check_offset_masters

contains

  subroutine check_offset_masters(st, model)
    !! One error per OFFSET=RIGID contact pair whose master node has no rotational DOF.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    logical, allocatable :: rot(:)
    integer :: ic, il, isub
    if (.not. any(model%contacts%rigid_offset)) return
    do ic = 1, size(model%contacts)
       if (.not. model%contacts(ic)%rigid_offset) cycle
       isub = model%contacts(ic)%master_sub
       if (isub < 1) cycle
       call rotating_nodes(model, isub, rot)
       do il = 1, size(model%links)
          if (model%links(il)%contact /= ic) cycle
          associate (lk => model%links(il), ct => model%contacts(ic))
            if (rot(lk%master_node)) cycle
            call report_loc(st, lk%loc, 'contact '//ct%name//', OFFSET=RIGID: master node '// &
                 node_label(model, isub, lk%master_node)//' has no rotational DOFs to carry the rigid arm '// &
                 'to slave node '//node_label(model, ct%slave_sub, lk%slave_node)// &
                 ' (an eccentric master must be a beam or shell node)')
          end associate
       end do
    end do
  end subroutine check_offset_masters

  subroutine rotating_nodes(model, isub, rot)
    !! rot(n): node n of substructure isub carries a rotational DOF.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    logical, allocatable, intent(out) :: rot(:)
    logical :: mask(6)
    integer(ip) :: e
    integer :: a, i
    associate (s => model%subs(isub))
      allocate (rot(s%nnode), source=.false.)
      do e = 1, s%nelem
         mask = element_dof_mask(s%elem_type(e))
         if (.not. any(mask(ROT_FIRST:ROT_LAST))) cycle
         do a = 1, ELEMENT_NODE_COUNT(s%elem_type(e))
            rot(s%elem_nodes(a, e)) = .true.
         end do
      end do
    end associate
    do i = 1, size(model%supports)
       associate (sp => model%supports(i))
         if (sp%sub == isub .and. sp%dof >= ROT_FIRST) rot(sp%node) = .true.
       end associate
    end do
  end subroutine rotating_nodes
end module superjoin_deck_eccentric
