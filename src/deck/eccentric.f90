module superjoin_deck_eccentric
  !! Checks of eccentric contacts (*CONTACT, OFFSET=RIGID) once the model is
  !! built: the slave hangs on a rigid arm from the master, so every master node
  !! must carry rotational DOFs (from a beam or shell element, or a support).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, ELEMENT_NODE_COUNT, LINK_NONE, node_label
  use superjoin_elements, only: element_dof_mask
  use superjoin_deck_state, only: deck_state_t, report_loc
  implicit none (type, external)
  private

  integer, parameter :: ROT_FIRST = 4, ROT_LAST = 6
    !! The rotational DOFs.

  public :: check_offset_masters

contains

  subroutine check_offset_masters(st, model)
    !! One error per OFFSET=RIGID contact pair whose master node lacks a rotational
    !! DOF that the arm needs: (θ × r)_c for the translations c the pair names
    !! (all three under an orientation) takes θ_d wherever r couples c and d.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    logical, allocatable :: rot(:, :)
    logical :: need(3), named(3)
    real(wp) :: r(3)
    integer :: ic, il, isub, c, d
    if (.not. any(model%contacts%rigid_offset)) return
    if (allocated(st%error)) return   ! one error per mistake: the model may be incomplete
    do ic = 1, size(model%contacts)
       if (.not. model%contacts(ic)%rigid_offset) cycle
       isub = model%contacts(ic)%master_sub
       if (isub < 1) cycle
       call rotating_nodes(model, isub, rot)
       do il = 1, size(model%links)
          if (model%links(il)%contact /= ic) cycle
          associate (lk => model%links(il), ct => model%contacts(ic))
            named = lk%state(1:3) /= LINK_NONE
            if (ct%orientation > 0 .and. any(named)) named = .true.
            r = model%subs(ct%slave_sub)%x(:, lk%slave_node) - model%subs(isub)%x(:, lk%master_node)
            need = .false.
            do c = 1, 3
               if (.not. named(c)) cycle
               do d = 1, 3
                  if (c == d) cycle
                  if (r(6 - c - d) /= 0.0_wp) need(d) = .true.   ! the third axis
               end do
            end do
            if (.not. any(rot(:, lk%master_node))) then
               call report_loc(st, lk%loc, 'contact '//ct%name//', OFFSET=RIGID: master node '// &
                    node_label(model, isub, lk%master_node)//' has no rotational DOFs to carry the rigid arm '// &
                    'to slave node '//node_label(model, ct%slave_sub, lk%slave_node)// &
                    ' (an eccentric master must be a beam or shell node)')
            else if (any(need .and. .not. rot(:, lk%master_node))) then
               call report_loc(st, lk%loc, 'contact '//ct%name//', OFFSET=RIGID: the arm from master node '// &
                    node_label(model, isub, lk%master_node)//' to slave node '// &
                    node_label(model, ct%slave_sub, lk%slave_node)//' needs rotations the master does not '// &
                    'carry (a 2D beam node turns about Z only: the arm must lie in the X-Y plane)')
            end if
          end associate
       end do
    end do
  end subroutine check_offset_masters

  subroutine rotating_nodes(model, isub, rot)
    !! rot(d, n): node n of substructure isub carries rotational DOF 3 + d.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    logical, allocatable, intent(out) :: rot(:, :)
    logical :: mask(6)
    integer(ip) :: e
    integer :: a, i
    associate (s => model%subs(isub))
      allocate (rot(3, s%nnode), source=.false.)
      do e = 1, s%nelem
         mask = element_dof_mask(s%elem_type(e))
         if (.not. any(mask(ROT_FIRST:ROT_LAST))) cycle
         do a = 1, ELEMENT_NODE_COUNT(s%elem_type(e))
            if (s%elem_nodes(a, e) < 1 .or. s%elem_nodes(a, e) > s%nnode) cycle
            rot(:, s%elem_nodes(a, e)) = rot(:, s%elem_nodes(a, e)) .or. mask(ROT_FIRST:ROT_LAST)
         end do
      end do
    end associate
    do i = 1, size(model%supports)
       associate (sp => model%supports(i))
         if (sp%sub == isub .and. sp%dof >= ROT_FIRST) rot(sp%dof - 3, sp%node) = .true.
       end associate
    end do
  end subroutine rotating_nodes
end module superjoin_deck_eccentric
