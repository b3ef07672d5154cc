module superjoin_deck_requests
  !! Validation of the output request cards (*NODE PRINT, *EL PRINT, *NODE FILE,
  !! *EL FILE, *NODE OUTPUT, *ELEMENT OUTPUT): their NSET= / ELSET= are resolved
  !! against the sets of the built model and the requests are stored in
  !! model%requests. A set named without scope is MAIN's, else that of the one
  !! instance that has it (Abaqus assembly-level sets, *NSET, INSTANCE=), as for
  !! loads and supports. A request without variables asks for the CalculiX
  !! default (U for nodes, S for elements).
  use superjoin_model_types, only: model_t, output_request_t
  use superjoin_deck_state, only: deck_state_t, request_b_t, report_loc, MAIN_NAME
  use superjoin_deck_ccx_cards, only: is_node_request
  use superjoin_deck_build_common, only: broken_sub, assembly_set_owner, sub_index, instances_hint
  use superjoin_utils_strings, only: pick
  implicit none (type, external)
  private

  public :: build_requests


contains

  subroutine build_requests(st, model)
    !! Resolve the request cards of `st` into model%requests (errors to st).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: k
    allocate (model%requests(st%nreq))
    do k = 1, st%nreq
       call build_one(st, model, st%requests(k), model%requests(k))
    end do
  end subroutine build_requests

  subroutine build_one(st, model, b, r)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(request_b_t), intent(in) :: b
    type(output_request_t), intent(out) :: r
    logical :: node
    integer :: isub, i, k
    character(:), allocatable :: what, hint
    node = is_node_request(b%kind)
    what = pick(node, 'node', 'element')
    r%kind = b%kind
    r%card = b%card
    r%step = b%step
    r%totals = b%totals
    r%global = b%global
    r%loc = b%loc
    if (b%nvar == 0 .and. b%nignored == 0) then
       allocate (r%vars(1))
       r%vars(1)%s = pick(node, 'U', 'S')
    else
       r%vars = b%vars(1:b%nvar)
    end if
    r%ignored = b%ignored(1:b%nignored)
    if (.not. b%has_set) return
    r%set_name = b%set%set
    isub = 0
    if (allocated(b%set%scope)) then
       isub = sub_index(model, b%set%scope)
       if (isub == 0) then
          call report_loc(st, b%loc, 'unknown substructure '//b%set%scope//' in '// &
               pick(node, 'NSET=', 'ELSET=')//b%set%scope//'.'//b%set%set//' of '//b%card)
          return
       end if
       r%set_name = b%set%scope//'.'//b%set%set
    else if (b%set%home > 0) then
       isub = b%set%home
    else   ! MAIN's set, else the one instance's (an assembly-level *NSET/*ELSET, INSTANCE=)
       isub = assembly_set_owner(model, b%set%set, .not. node, sub_index(model, MAIN_NAME))
    end if
    k = 0
    if (isub > 0) then
       if (broken_sub(st, model%subs(isub)%name)) return   ! its *INSTANCE error was the one message
       associate (sub => model%subs(isub))
         if (node) then
            do i = 1, size(sub%nsets)
               if (sub%nsets(i)%name == b%set%set) k = i
            end do
            if (k > 0) r%items = sub%nsets(k)%items
            if (k > 0) then
               if (allocated(sub%nsets(k)%print_ranges)) r%print_ranges = sub%nsets(k)%print_ranges
            end if
         else
            do i = 1, size(sub%elsets)
               if (sub%elsets(i)%name == b%set%set) k = i
            end do
            if (k > 0) r%items = sub%elsets(k)%items
         end if
       end associate
    end if
    if (k == 0) then
       hint = ''   ! a plain name that several instances hold: say so
       if (.not. allocated(b%set%scope) .and. b%set%home == 0) hint = instances_hint(model, b%set%set, .not. node)
       if (isub > 0) then
          call report_loc(st, b%loc, 'unknown '//what//' set '//b%set%set//' in substructure '// &
               model%subs(isub)%name//' ('//pick(node, 'NSET=', 'ELSET=')//' of '//b%card//')'//hint)
       else
          call report_loc(st, b%loc, 'unknown '//what//' set '//b%set%set//' ('//pick(node, 'NSET=', 'ELSET=')// &
               ' of '//b%card//'; outside *SUBSTRUCTURE blocks write SUB.set)'//hint)
       end if
       return
    end if
    r%sub = isub
  end subroutine build_one
end module superjoin_deck_requests
