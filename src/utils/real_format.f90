module superjoin_utils_real_format
  !! Binding to real_format.c: 17-significant-digit text of a real (exact round
  !! trip), in the layout of ES24.16E3.
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_double
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  public :: format_e17

  integer, parameter :: E17_LEN = 32
    !! room for sign, 17 digits, point, exponent

  interface
     pure subroutine sj_format_e17(x, out, n) bind(c, name='sj_format_e17')
       import :: c_int, c_char, c_double
       real(c_double), value :: x
       character(kind=c_char), intent(out) :: out(*)
       integer(c_int), intent(out) :: n
     end subroutine sj_format_e17
  end interface

contains

  pure function format_e17(x) result(s)
    !! x as -1.2345678901234567E-003 (no blanks).
    real(wp), intent(in) :: x
    character(:), allocatable :: s
    character(kind=c_char) :: buf(E17_LEN)
    integer(c_int) :: n
    integer :: i
    call sj_format_e17(real(x, c_double), buf, n)
    allocate (character(len=n) :: s)
    do i = 1, n
       s(i:i) = buf(i)
    end do
  end function format_e17
end module superjoin_utils_real_format
