module superjoin_model_request_masks
  !! What the output requests of a deck (*NODE PRINT, *EL PRINT, *NODE FILE,
  !! *EL FILE and their *NODE OUTPUT / *ELEMENT OUTPUT aliases) ask for, as
  !! masks over the model's nodes and elements: the analysis computes element
  !! results only where somebody reads them, the CSV tables hold only what the
  !! file requests name. A deck without any request asks for everything.
  !!
  !! Nodes and elements are numbered over the substructures in order (node n of
  !! substructure s is sum(nnode(1:s-1)) + n), as the results arrays are.
  use superjoin_kinds, only: i8
  use superjoin_model_types, only: model_t, output_request_t
  implicit none (type, external)
  private

  public :: has_requests, any_request_of, request_mask, asks_variable

contains

  pure logical function has_requests(model)
    !! True when the deck has at least one output request card.
    type(model_t), intent(in) :: model
    has_requests = .false.
    if (allocated(model%requests)) has_requests = size(model%requests) > 0
  end function has_requests

  pure logical function any_request_of(model, kinds)
    !! True when the deck has a request of one of `kinds` (REQ_*), in any step.
    type(model_t), intent(in) :: model
    integer, intent(in) :: kinds(:)
    integer :: k
    any_request_of = .false.
    if (.not. allocated(model%requests)) return
    do k = 1, size(model%requests)
       if (any(kinds == model%requests(k)%kind)) any_request_of = .true.
    end do
  end function any_request_of

  pure logical function asks_variable(model, kinds, names)
    !! True when a request of one of `kinds` names one of the variables `names`
    !! (upper case, e.g. ['U '] or ['S ', 'E ', 'SF']).
    type(model_t), intent(in) :: model
    integer, intent(in) :: kinds(:)
    character(*), intent(in) :: names(:)
    integer :: k, j
    asks_variable = .false.
    if (.not. allocated(model%requests)) return
    do k = 1, size(model%requests)
       associate (r => model%requests(k))
         if (.not. any(kinds == r%kind)) cycle
         if (.not. allocated(r%vars)) cycle
         do j = 1, size(r%vars)
            if (any(trim(r%vars(j)%s) == names)) asks_variable = .true.
         end do
       end associate
    end do
  end function asks_variable

  subroutine request_mask(model, kinds, of_nodes, mask)
    !! mask(global node or element) = .true. where a request of one of `kinds`
    !! (in any step) covers it: its set, or the whole model for a request
    !! without a set. of_nodes selects nodes (else elements).
    type(model_t), intent(in) :: model
    integer, intent(in) :: kinds(:)
    logical, intent(in) :: of_nodes
    logical, allocatable, intent(out) :: mask(:)
    integer(i8), allocatable :: offset(:)
    integer :: isub, k

    allocate (offset(size(model%subs) + 1))
    offset(1) = 0
    do isub = 1, size(model%subs)
       if (of_nodes) then
          offset(isub + 1) = offset(isub) + model%subs(isub)%nnode
       else
          offset(isub + 1) = offset(isub) + model%subs(isub)%nelem
       end if
    end do
    allocate (mask(offset(size(model%subs) + 1)), source=.false.)
    if (.not. allocated(model%requests)) return
    do k = 1, size(model%requests)
       associate (r => model%requests(k))
         if (.not. any(kinds == r%kind)) cycle
         if (r%sub > 0 .and. allocated(r%items)) then
            mask(offset(r%sub) + int(r%items, i8)) = .true.
         else
            mask = .true.
         end if
       end associate
    end do
  end subroutine request_mask

end module superjoin_model_request_masks
