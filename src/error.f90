module superjoin_error
  !! Error reporting: an allocatable error_t travels up through the last argument.
  implicit none (type, external)
  private

  integer, parameter, public :: EXIT_OK = 0        !! solved
  integer, parameter, public :: EXIT_DECK = 1      !! deck error
  integer, parameter, public :: EXIT_USAGE = 2     !! usage error
  integer, parameter, public :: EXIT_SINGULAR = 3  !! structure cannot be solved
  integer, parameter, public :: EXIT_IO = 4        !! input/output or resource failure
  integer, parameter, public :: EXIT_INACCURATE = 5 !! solved, listing written, but the results are judged inaccurate

  type, public :: error_t
    !! An error: its exit status and one or more message lines (already formatted).
     integer :: code = EXIT_DECK
     character(:), allocatable :: message
  end type error_t

  public :: fatal_error, add_error_line

contains

  pure subroutine fatal_error(error, code, message)
    !! Allocate error with an exit code and a message.
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in) :: code
    character(*), intent(in) :: message
    allocate (error)
    error%code = code
    error%message = message
  end subroutine fatal_error

  pure subroutine add_error_line(error, code, message)
    !! Append one line to error (allocating it if needed), keeping the first code.
    type(error_t), allocatable, intent(inout) :: error
    integer, intent(in) :: code
    character(*), intent(in) :: message
    if (.not. allocated(error)) then
       allocate (error)
       error%code = code
       error%message = message
    else
       error%message = error%message//new_line('a')//message
    end if
  end subroutine add_error_line
end module superjoin_error
