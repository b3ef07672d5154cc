module superjoin_output_file_selection
  !! What the result files (CSV tables with --csv, VTK arrays with --vtk) hold
  !! when the deck has *NODE FILE / *EL FILE requests (or their *NODE OUTPUT /
  !! *ELEMENT OUTPUT aliases): the node results their variables name (U:
  !! displacements, RF: reactions) for the nodes of their sets, and the element
  !! results (S, E, SF) for the elements of theirs. A deck without requests of
  !! one kind gets all results of that kind. Contact forces are always written.
  use superjoin_kinds, only: i8
  use superjoin_model_types, only: model_t, REQ_NODE_FILE, REQ_EL_FILE
  use superjoin_model_request_masks, only: any_request_of, request_mask, asks_variable
  use superjoin_elements, only: is_plate_type
  implicit none (type, external)
  private

  public :: select_file_output

  integer, parameter, public :: FILE_DISPLACEMENTS = 1, FILE_REACTIONS = 2, FILE_CONTACT_FORCES = 3, &
       FILE_ELEMENT_FORCES = 4, FILE_PLATE_RESULTS = 5
    !! The kinds of results a file holds (the CSV tables, in this order).
  integer, parameter, public :: NUM_FILE_RESULTS = 5

  type, public :: file_selection_t
    !! Which kinds of results, which nodes and which elements (numbered over
    !! the substructures) the result files hold.
     logical :: kind(NUM_FILE_RESULTS) = .true.
     logical, allocatable :: node(:), elem(:)
  end type file_selection_t

contains

  subroutine select_file_output(model, sel)
    !! The selection the deck's file requests make (everything without them).
    type(model_t), intent(in) :: model
    type(file_selection_t), intent(out) :: sel
    if (any_request_of(model, [REQ_NODE_FILE])) then
       call request_mask(model, [REQ_NODE_FILE], .true., sel%node)
       sel%kind(FILE_DISPLACEMENTS) = asks_variable(model, [REQ_NODE_FILE], ['U '])
       sel%kind(FILE_REACTIONS) = asks_variable(model, [REQ_NODE_FILE], ['RF'])
    else
       call request_mask(model, [integer ::], .true., sel%node)
       sel%node = .true.
    end if
    if (any_request_of(model, [REQ_EL_FILE])) then
       call request_mask(model, [REQ_EL_FILE], .false., sel%elem)
       sel%kind(FILE_ELEMENT_FORCES) = asks_variable(model, [REQ_EL_FILE], ['S ', 'E ', 'SF'])
    else
       call request_mask(model, [integer ::], .false., sel%elem)
       sel%elem = .true.
    end if
    sel%kind(FILE_PLATE_RESULTS) = sel%kind(FILE_ELEMENT_FORCES) .and. any_plates(model)
  end subroutine select_file_output

  pure logical function any_plates(model)
    !! True when the model has plane-stress or shell elements.
    type(model_t), intent(in) :: model
    integer :: isub
    any_plates = .false.
    do isub = 1, size(model%subs)
       if (model%subs(isub)%nelem == 0) cycle
       if (any(is_plate_type(model%subs(isub)%elem_type(1:model%subs(isub)%nelem)))) any_plates = .true.
    end do
  end function any_plates
end module superjoin_output_file_selection
