module superjoin_utils_memory
  !! Out-of-memory reporting. Allocations whose size grows with the model use
  !! `stat=`; a failure becomes an EXIT_IO error that says what was being
  !! allocated and how many bytes it needed (`error: out of memory: ...`).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  public :: out_of_memory, oom_message, bytes_text, BYTES_REAL, BYTES_INT, BYTES_I8

  integer(i8), parameter :: BYTES_REAL = storage_size(1.0_wp)/8
    !! Bytes per element of the arrays superjoin allocates.
  integer(i8), parameter :: BYTES_INT = storage_size(1)/8
  integer(i8), parameter :: BYTES_I8 = storage_size(1_i8)/8
  real(wp), parameter :: MIB = 1048576.0_wp       !! bytes per MiB
  real(wp), parameter :: GIB = 1073741824.0_wp    !! bytes per GiB

contains

  subroutine out_of_memory(error, what, nbytes)
    !! EXIT_IO error: `what` could not be allocated, it needed nbytes.
    type(error_t), allocatable, intent(out) :: error
    character(*), intent(in) :: what
    integer(i8), intent(in) :: nbytes
    call fatal_error(error, EXIT_IO, oom_message(what, nbytes))
  end subroutine out_of_memory

  pure function oom_message(what, nbytes) result(msg)
    !! `error: out of memory: WHAT needs N bytes (X MiB)`.
    character(*), intent(in) :: what
    integer(i8), intent(in) :: nbytes
    character(:), allocatable :: msg
    msg = 'error: out of memory: '//what//' needs '//bytes_text(nbytes)
  end function oom_message

  pure function bytes_text(nbytes) result(s)
    !! `N bytes (X.Y MiB)` or `N bytes (X.Y GiB)`.
    integer(i8), intent(in) :: nbytes
    character(:), allocatable :: s
    character(len=32) :: buf
    if (real(nbytes, wp) >= GIB) then
       write (buf, '(f0.1,a)') real(nbytes, wp)/GIB, ' GiB'
    else
       write (buf, '(f0.1,a)') real(nbytes, wp)/MIB, ' MiB'
    end if
    if (buf(1:1) == '.') buf = '0'//buf(1:len(buf) - 1)
    s = itoa(nbytes)//' bytes ('//trim(buf)//')'
  end function bytes_text
end module superjoin_utils_memory
