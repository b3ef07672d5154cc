module superjoin_deck_axisym_supports
  !! Supports on DOFs that a node of axisymmetric elements only (CAX*) does not
  !! carry: such a node has DOFs 1 (r) and 2 (z). A support on its DOF 3 holds
  !! nothing (CalculiX 2.20 ignores it silently, the results unchanged): a
  !! warning in the listing's notes, once per data line with a count and the
  !! first node. A support on its DOFs 4-6 is an error (CalculiX 2.20 stops on
  !! it with a floating point exception).
  use superjoin_kinds, only: ip
  use superjoin_model_types, only: model_t, support_t, source_loc_t, string_t, node_label, NUM_ELEMENT_TYPES
  use superjoin_elements_traits, only: element_traits_t, all_element_traits
  use superjoin_model_notes, only: note
  use superjoin_deck_state, only: deck_state_t, report_loc
  use superjoin_deck_build_common, only: where
  use superjoin_utils_strings, only: itoa, pick
  implicit none (type, external)
  private

  public :: check_axisymmetric_supports

  integer, parameter :: DOF_OUT_OF_PLANE = 3   !! the first DOF an axisymmetric node does not carry

  type :: axis_nodes_t
    !! Per substructure: its nodes that belong to axisymmetric elements only.
     logical, allocatable :: only(:)
  end type axis_nodes_t

contains

  subroutine check_axisymmetric_supports(st, model)
    !! Warn of, or refuse, supports on DOFs 3-6 of nodes of CAX elements only
    !! (model data and every step's own supports; each data line once).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(axis_nodes_t), allocatable :: axis(:)
    type(source_loc_t), allocatable :: seen(:)
    type(string_t), allocatable :: warnings(:)
    integer :: s
    ! after an error the model may be incomplete (an element on an undefined node): nothing to check
    if (allocated(st%error)) return
    if (.not. axis_nodes(model, axis)) return
    allocate (seen(0))
    if (allocated(model%supports)) call check_list(st, model, axis, model%supports, seen, warnings)
    do s = 1, size(model%steps)
       if (allocated(model%steps(s)%supports)) call check_list(st, model, axis, model%steps(s)%supports, seen, warnings)
    end do
    if (.not. allocated(warnings)) return
    do s = 1, size(warnings)
       call note(model%notes, warnings(s)%s)
    end do
  end subroutine check_axisymmetric_supports

  logical function axis_nodes(model, axis) result(any_axis)
    !! axis(isub)%only(n): node n belongs to at least one axisymmetric element and to no other.
    type(model_t), intent(in) :: model
    type(axis_nodes_t), allocatable, intent(out) :: axis(:)
    logical, allocatable :: other(:)
    type(element_traits_t) :: traits(NUM_ELEMENT_TYPES)
    integer(ip) :: e
    integer :: isub, k
    any_axis = .false.
    traits = all_element_traits()   ! once per type, not per element
    allocate (axis(size(model%subs)))
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         allocate (axis(isub)%only(sub%nnode))
         axis(isub)%only = .false.
         if (.not. any(traits(sub%elem_type(1:sub%nelem))%axisymmetric)) cycle   ! no CAX: no node loop
         allocate (other(sub%nnode))
         other = .false.
         do e = 1, sub%nelem
            associate (tr => traits(sub%elem_type(e)))
              do k = 1, tr%nodes
                 if (sub%elem_nodes(k, e) < 1 .or. sub%elem_nodes(k, e) > sub%nnode) cycle
                 if (tr%axisymmetric) then
                    axis(isub)%only(sub%elem_nodes(k, e)) = .true.
                 else
                    other(sub%elem_nodes(k, e)) = .true.
                 end if
              end do
            end associate
         end do
         axis(isub)%only = axis(isub)%only .and. .not. other
         any_axis = any_axis .or. any(axis(isub)%only)
         deallocate (other)
       end associate
    end do
  end function axis_nodes

  subroutine check_list(st, model, axis, list, seen, warnings)
    !! The supports of one list whose data line was not met before.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(axis_nodes_t), intent(in) :: axis(:)
    type(support_t), intent(in) :: list(:)
    type(source_loc_t), allocatable, intent(inout) :: seen(:)
    type(string_t), allocatable, intent(inout) :: warnings(:)
    character(:), allocatable :: card
    integer :: i, j, count, first, rot
    do i = 1, size(list)
       if (list(i)%dof < DOF_OUT_OF_PLANE .or. .not. axis(list(i)%sub)%only(list(i)%node)) cycle
       if (any(seen%file == list(i)%loc%file .and. seen%line == list(i)%loc%line)) cycle
       seen = [seen, list(i)%loc]
       count = 0
       first = 0
       rot = 0
       do j = i, size(list)
          if (list(j)%loc%file /= list(i)%loc%file .or. list(j)%loc%line /= list(i)%loc%line) cycle
          if (.not. axis(list(j)%sub)%only(list(j)%node)) cycle
          if (list(j)%dof > DOF_OUT_OF_PLANE .and. rot == 0) rot = j
          if (list(j)%dof /= DOF_OUT_OF_PLANE) cycle
          count = count + 1
          if (first == 0) first = j
       end do
       card = pick(list(i)%from_boundary, '*BOUNDARY', '*SUPPORT')
       if (rot > 0) call report_loc(st, list(rot)%loc, card//': DOF '//itoa(list(rot)%dof)//' of node '// &
              node_label(model, list(rot)%sub, list(rot)%node)//', a node of axisymmetric elements (CAX*) only, '// &
              'which carry DOFs 1 (r) and 2 (z): DOFs 4-6 cannot be supported there (CalculiX stops on them)')
       if (count > 0) call note(warnings, 'warning: '//card//' at '//where(st, list(i)%loc)// &
              ' holds DOF 3 of '//itoa(count)//' node(s) of axisymmetric elements (CAX*) only, the first '// &
              node_label(model, list(first)%sub, list(first)%node)//': such nodes carry DOFs 1 (r) and 2 (z) '// &
              'only, so it holds nothing (CalculiX ignores it too)')
    end do
  end subroutine check_list
end module superjoin_deck_axisym_supports
