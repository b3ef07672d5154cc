module superjoin_model_notes
  !! Notes and warnings of a run: lines for the listing (and, warnings, stderr).
  use superjoin_model_types, only: string_t
  use superjoin_model_results, only: results_t
  implicit none (type, external)
  private

  public :: note, warn, append_string

contains

  subroutine note(notes, text)
    !! Append a line to the listing's notes.
    type(string_t), allocatable, intent(inout) :: notes(:)
    character(*), intent(in) :: text
    call append_string(notes, text)
  end subroutine note

  subroutine warn(res, text)
    !! Append a warning (listing and stderr).
    type(results_t), intent(inout) :: res
    character(*), intent(in) :: text
    call append_string(res%log%warnings, text)
  end subroutine warn

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
