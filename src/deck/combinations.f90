module superjoin_deck_combinations
  !! *LOAD COMBINATION cards (superjoin's extension): resolve the step names of
  !! each combination against the model's steps (after the SWEEP expansion of
  !! *CHANGE CONTACT, so that `STUDY-2` can be named) and fill model%combinations.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: model_t
  use superjoin_deck_state, only: deck_state_t, report_loc
  use superjoin_deck_lexer, only: is_digits
  implicit none (type, external)
  private

  public :: build_combinations

contains

  subroutine build_combinations(st, model)
    !! Check the *LOAD COMBINATION cards and store them in model%combinations:
    !! unique names, distinct from every step name; each data line names a
    !! step of the deck (by name, or by its position when no step has that
    !! name), at most once per combination.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: c, j, k, s
    if (st%ncombo == 0) return
    allocate (model%combinations(st%ncombo))
    do c = 1, st%ncombo
       associate (cb => st%combos(c), mc => model%combinations(c))
         mc%name = cb%name
         mc%loc = cb%loc
         allocate (mc%steps(cb%n), mc%factors(cb%n))
         mc%factors = cb%factors(1:cb%n)
         mc%steps = 0
         do j = 1, c - 1
            if (st%combos(j)%name == cb%name) then
               call report_loc(st, cb%loc, 'duplicate load combination name '//cb%name)
               exit
            end if
         end do
         do s = 1, size(model%steps)
            if (model%steps(s)%name == cb%name) then
               call report_loc(st, cb%loc, 'load combination '//cb%name//' has the name of a step')
               exit
            end if
         end do
         do k = 1, cb%n
            mc%steps(k) = step_index(model, cb%steps(k)%s)
            if (mc%steps(k) == 0) then
               call report_loc(st, cb%line_loc(k), 'unknown step '//cb%steps(k)%s//' in *LOAD COMBINATION '// &
                    cb%name)
               cycle
            end if
            do j = 1, k - 1
               if (mc%steps(j) == mc%steps(k)) then
                  call report_loc(st, cb%line_loc(k), 'step '//cb%steps(k)%s//' appears twice in *LOAD '// &
                       'COMBINATION '//cb%name//' (give it one factor)')
                  exit
               end if
            end do
         end do
       end associate
    end do
  end subroutine build_combinations

  integer function step_index(model, name) result(k)
    !! The step named `name`, else the step at position `name` (digits), else 0.
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    integer :: s, stat
    k = 0
    do s = 1, size(model%steps)
       if (model%steps(s)%name == name) then
          k = s
          return
       end if
    end do
    if (is_digits(name) .and. len(name) <= 9) then
       read (name, *, iostat=stat) s
       if (stat == 0 .and. s >= 1 .and. s <= size(model%steps)) k = s
    end if
  end function step_index
end module superjoin_deck_combinations
