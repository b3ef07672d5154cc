module superjoin_analysis_carried_loads
  !! A superjoin step is a load case: its loads are the ones its own cards
  !! write (the deck contract). CalculiX and Abaqus instead keep a step's loads
  !! in force in the next step unless that step says OP=NEW. A deck written for
  !! CalculiX (its steps have a procedure card, *STATIC) that relies on that
  !! would get other answers here without a word; so, for such a step, when
  !! loads of the previous step are neither carried (OP=MOD) nor replaced by
  !! loads of the step on the same node and DOF (element and load type), nor
  !! dismissed with OP=NEW, the deck is warned, once per step and kind.
  use superjoin_model_types, only: model_t, string_t, loc_text, dload_t, DLOAD_THERMAL
  use superjoin_model_history, only: cload_replaced, dload_replaced
  use superjoin_utils_strings, only: itoa
  use superjoin_analysis_notes, only: append_string
  implicit none (type, external)
  private

  public :: check_carried_loads

contains

  subroutine check_carried_loads(model, warnings)
    !! Append a warning for every CalculiX-style step (with *STATIC) whose
    !! *CLOAD or *DLOAD loads differ from what CalculiX would apply because the
    !! previous step's loads of that kind are not carried into it.
    type(model_t), intent(in) :: model
    type(string_t), allocatable, intent(inout) :: warnings(:)
    integer :: s, ndrop
    do s = 2, size(model%steps)
       associate (now => model%steps(s), prev => model%steps(s - 1))
         if (.not. now%procedure_card .or. now%combination /= 0 .or. prev%combination /= 0) cycle
         if (.not. now%cload_op_given .and. allocated(prev%cloads) .and. allocated(now%cloads)) then
            ndrop = count(.not. cload_replaced(prev%cloads, now%cloads))
            if (ndrop > 0) call append_string(warnings, message(model, s, ndrop, '*CLOAD', 'concentrated load', &
                 'Write *CLOAD, OP=MOD to carry them, or OP=NEW to start from none and silence this warning'))
         end if
         if (allocated(prev%dloads) .and. allocated(now%dloads)) then
            if (.not. now%dload_op_given) then
               ndrop = dropped(prev%dloads, now%dloads, .false.)
               if (ndrop > 0) call append_string(warnings, message(model, s, ndrop, '*DLOAD', 'distributed load', &
                    'Write *DLOAD, OP=MOD to carry them, or OP=NEW to start from none and silence this warning'))
            end if
            ndrop = dropped(prev%dloads, now%dloads, .true.)
            if (ndrop > 0) call append_string(warnings, message(model, s, ndrop, '*TEMPERATURE', &
                 'element temperature change', 'Give those nodes their temperature in this step '// &
                 '(a node without one is at its initial temperature here)'))
         end if
       end associate
    end do
  end subroutine check_carried_loads

  integer function dropped(prev, now, thermal)
    !! Distributed loads of the previous step (thermal ones, or the others)
    !! that no load of this step on the same element and load type replaces.
    type(dload_t), intent(in) :: prev(:), now(:)
    logical, intent(in) :: thermal
    type(dload_t), allocatable :: p(:), n(:)
    p = pack(prev, (prev%kind == DLOAD_THERMAL) .eqv. thermal)
    n = pack(now, (now%kind == DLOAD_THERMAL) .eqv. thermal)
    dropped = count(.not. dload_replaced(p, n))
  end function dropped

  function message(model, s, ndrop, card, what, advice) result(text)
    !! The warning for step s: how many loads of step s-1 it leaves out.
    type(model_t), intent(in) :: model
    integer, intent(in) :: s, ndrop
    character(*), intent(in) :: card, what, advice
    character(:), allocatable :: text
    text = 'step '//model%steps(s)%name//' ('//loc_text(model, model%steps(s)%loc)//') does not apply '// &
         itoa(ndrop)//' '//what//'(s) of step '//model%steps(s - 1)%name//' ('//card// &
         '; a superjoin step is a load case); CalculiX and Abaqus would keep them in force. '//advice
  end function message
end module superjoin_analysis_carried_loads
