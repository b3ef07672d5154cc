module superjoin_deck_requests
  !! Validation of the output request cards (*NODE PRINT, *EL PRINT, *NODE FILE,
  !! *EL FILE, *NODE OUTPUT, *ELEMENT OUTPUT): their NSET= / ELSET= are resolved
  !! against the sets of the built model and the requests are stored in
  !! model%requests. A set named without scope is MAIN's, else an assembly-level
  !! set (*NSET or *ELSET, INSTANCE=): over several instances, one request per
  !! instance, in the order of the set's cards (without TOTALS=); else the one
  !! instance's that has it, as for loads and supports. A request without
  !! variables asks for the CalculiX default (U for nodes, S for elements).
  use superjoin_model_types, only: model_t, output_request_t, TOTALS_NO
  use superjoin_deck_lexer, only: itoa
  use superjoin_deck_state, only: deck_state_t, request_b_t, report_loc, MAIN_NAME
  use superjoin_deck_ccx_cards, only: is_node_request
  use superjoin_deck_build_common, only: broken_sub, plain_set_subs, sub_index, instances_hint
  use superjoin_utils_strings, only: pick
  implicit none (type, external)
  private

  interface grow
     !! Make room for element n + 1 of an allocatable array (grow_template.inc).
     module procedure grow_request
  end interface grow

  public :: build_requests


contains

  subroutine build_requests(st, model)
    !! Resolve the request cards of `st` into model%requests (errors to st): one
    !! request per card, one per member instance for a set over several.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(output_request_t), allocatable :: each(:), all(:)
    integer :: k, j, n
    allocate (all(st%nreq))
    n = 0
    do k = 1, st%nreq
       call build_one(st, model, st%requests(k), each)
       do j = 1, size(each)
          call grow(all, n, max(st%nreq, 1))
          n = n + 1
          all(n) = each(j)
       end do
    end do
    allocate (model%requests(n))
    model%requests(:) = all(1:n)
  end subroutine build_requests

  subroutine build_one(st, model, b, rs)
    !! The requests of card b: one, or one per member instance of an
    !! assembly-level set over several instances (plain_set_subs), in order.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(request_b_t), intent(in) :: b
    type(output_request_t), allocatable, intent(out) :: rs(:)
    type(output_request_t) :: r
    logical :: node
    integer :: m
    integer, allocatable :: subs(:)
    if (b%has_set .and. b%set%home < 0) then   ! in a part that was not placed: its error was reported
       allocate (rs(0))
       return
    end if
    node = is_node_request(b%kind)
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
    allocate (rs(1))
    rs(1) = r
    if (.not. b%has_set) return
    r%set_name = b%set%set
    rs(1)%set_name = r%set_name
    if (allocated(b%set%scope)) then
       subs = [sub_index(model, b%set%scope)]
       if (subs(1) == 0) then
          call report_loc(st, b%loc, 'unknown substructure '//b%set%scope//' in '// &
               pick(node, 'NSET=', 'ELSET=')//b%set%scope//'.'//b%set%set//' of '//b%card)
          return
       end if
       r%set_name = b%set%scope//'.'//b%set%set
       rs(1)%set_name = r%set_name
    else if (b%set%home > 0) then
       subs = [b%set%home]
    else   ! MAIN's set, else an assembly-level *NSET or *ELSET, INSTANCE= (the union of its instances')
       subs = plain_set_subs(st, model, b%set%set, .not. node, sub_index(model, MAIN_NAME))
    end if
    if (size(subs) == 0) then
       call take_set(st, model, 0, b, rs(1))
       return
    end if
    if (size(subs) > 1 .and. b%totals /= TOTALS_NO) then
       call report_loc(st, b%loc, 'TOTALS= of '//b%card//' over '//pick(node, 'node', 'element')//' set '// &
            b%set%set//', which spans '//itoa(size(subs))//' substructures (an assembly-level set over '// &
            'several instances): the totals of such a set are not summed across them; request each '// &
            'instance''s, as '//model%subs(subs(1))%name//'.'//b%set%set)
       return
    end if
    deallocate (rs)
    allocate (rs(size(subs)))
    do m = 1, size(subs)
       rs(m) = r
       call take_set(st, model, subs(m), b, rs(m))
    end do
  end subroutine build_one

  subroutine take_set(st, model, isub, b, r)
    !! r takes the members of b's set in substructure isub (0: none found;
    !! reported, with the instances that hold a set of that name).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(request_b_t), intent(in) :: b
    type(output_request_t), intent(inout) :: r
    logical :: node
    integer :: i, k
    character(:), allocatable :: what, hint
    node = is_node_request(b%kind)
    what = pick(node, 'node', 'element')
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
  end subroutine take_set

#define GROW_NAME grow_request
#define GROW_TYPE type(output_request_t)
#include "grow_template.inc"

end module superjoin_deck_requests
