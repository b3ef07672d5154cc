module superjoin_model_notes
  !! Notes and warnings of a run: lines for the listing (and, warnings, stderr).
  use superjoin_model_types, only: string_t
  use superjoin_model_results, only: results_t, warning_t
  implicit none (type, external)
  private

  public :: note, warn, append_string, add_warning, model_warnings_first

contains

  subroutine note(notes, text)
    !! Append a line to the listing's notes.
    type(string_t), allocatable, intent(inout) :: notes(:)
    character(*), intent(in) :: text
    call append_string(notes, text)
  end subroutine note

  subroutine warn(res, text, steps)
    !! Append a warning (listing and stderr) that arose in the steps marked in
    !! steps (the NUMERICAL HEALTH blocks that list it).
    type(results_t), intent(inout) :: res
    character(*), intent(in) :: text
    logical, intent(in) :: steps(:)
    call add_warning(res%log%warnings, text, steps)
  end subroutine warn

  subroutine add_warning(list, text, steps)
    !! Grow a list of warnings by one; steps absent: a warning on the model
    !! (listed once, before the steps). A warning whose text is in the list
    !! already only adds its steps to that one's.
    type(warning_t), allocatable, intent(inout) :: list(:)
    character(*), intent(in) :: text
    logical, intent(in), optional :: steps(:)
    type(warning_t), allocatable :: tmp(:)
    integer :: i, n
    n = 0
    if (allocated(list)) n = size(list)
    do i = 1, n
       if (list(i)%s /= text) cycle
       if (allocated(list(i)%steps) .and. present(steps)) list(i)%steps = list(i)%steps .or. steps
       return
    end do
    allocate (tmp(n + 1))
    do i = 1, n
       call move_alloc(list(i)%s, tmp(i)%s)
       if (allocated(list(i)%steps)) call move_alloc(list(i)%steps, tmp(i)%steps)
    end do
    tmp(n + 1)%s = text
    if (present(steps)) tmp(n + 1)%steps = steps
    call move_alloc(tmp, list)
  end subroutine add_warning

  subroutine model_warnings_first(texts, list)
    !! Put the warnings texts on the model itself (the deck's checks: listed
    !! once, before the steps) ahead of those of the solve in list.
    type(string_t), intent(in) :: texts(:)
    type(warning_t), allocatable, intent(inout) :: list(:)
    type(warning_t), allocatable :: merged(:)
    integer :: i
    if (size(texts) == 0) return
    allocate (merged(0))
    do i = 1, size(texts)
       call add_warning(merged, texts(i)%s)
    end do
    if (allocated(list)) then
       do i = 1, size(list)
          call add_warning(merged, list(i)%s, list(i)%steps)
       end do
    end if
    call move_alloc(merged, list)
  end subroutine model_warnings_first

  subroutine append_string(list, text)
    !! Grow a list of strings by one, moving the old entries (no copies).
    type(string_t), allocatable, intent(inout) :: list(:)
    character(*), intent(in) :: text
    type(string_t), allocatable :: tmp(:)
    integer :: i, n
    n = 0
    if (allocated(list)) n = size(list)
    allocate (tmp(n + 1))
    do i = 1, n
       call move_alloc(list(i)%s, tmp(i)%s)
    end do
    tmp(n + 1)%s = text
    call move_alloc(tmp, list)
  end subroutine append_string
end module superjoin_model_notes
