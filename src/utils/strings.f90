module superjoin_utils_strings
  !! Small string conversions.
  use superjoin_kinds, only: wp, i8
  use superjoin_utils_real_format, only: format_e17
  use superjoin_utils_number_text, only: int_text, INT_TEXT_LEN
  implicit none (type, external)
  private

  interface itoa
    !! Integer to text without blanks.
     module procedure itoa_default, itoa_i8
  end interface itoa

  public :: itoa, rtoa, full_real, pick, to_lower, to_upper
  public :: without_blanks

contains

  pure function itoa_default(i) result(s)
    integer, intent(in) :: i
    character(:), allocatable :: s
    s = itoa_i8(int(i, i8))
  end function itoa_default

  pure function itoa_i8(i) result(s)
    integer(i8), intent(in) :: i
    character(:), allocatable :: s
    character(len=INT_TEXT_LEN) :: buf
    integer :: n
    call int_text(i, buf, n)
    s = buf(1:n)
  end function itoa_i8

  pure function rtoa(x, digits) result(s)
    !! Real to short text: 4 significant digits (or digits, at most 17), exponent form.
    real(wp), intent(in) :: x
    integer, intent(in), optional :: digits
    character(:), allocatable :: s
    character(len=32) :: buf, fmt
    if (present(digits)) then
       write (fmt, '(a,i0,a,i0,a)') '(es', min(max(digits, 1), 17) + 9, '.', min(max(digits, 1), 17) - 1, 'e3)'
       write (buf, fmt) x
    else
       write (buf, '(es11.4)') x
    end if
    s = trim(adjustl(buf))
  end function rtoa

  pure function full_real(x) result(s)
    !! Real to text with 17 significant digits (round-trips exactly).
    real(wp), intent(in) :: x
    character(:), allocatable :: s
    if (x == 0.0_wp) then
       s = '0'
    else
       s = format_e17(x)
    end if
  end function full_real
  pure function to_lower(s) result(t)
    !! s with ASCII letters in lower case.
    character(*), intent(in) :: s
    character(len(s)) :: t
    integer :: k
    t = s
    do k = 1, len(s)
       if (s(k:k) >= 'A' .and. s(k:k) <= 'Z') t(k:k) = achar(iachar(s(k:k)) + 32)
    end do
  end function to_lower

  pure function to_upper(s) result(t)
    !! s with ASCII letters in upper case.
    character(*), intent(in) :: s
    character(len(s)) :: t
    integer :: k
    t = s
    do k = 1, len(s)
       if (s(k:k) >= 'a' .and. s(k:k) <= 'z') t(k:k) = achar(iachar(s(k:k)) - 32)
    end do
  end function to_upper

  pure function pick(cond, a, b) result(s)
    !! `a` when `cond`, else `b` (strings of any lengths).
    logical, intent(in) :: cond
    character(*), intent(in) :: a, b
    character(:), allocatable :: s
    if (cond) then
       s = a
    else
       s = b
    end if
  end function pick

  pure function without_blanks(s) result(t)
    !! s with every blank removed.
    character(*), intent(in) :: s
    character(:), allocatable :: t
    integer :: i, n
    allocate (character(len=len(s)) :: t)
    n = 0
    do i = 1, len(s)
       if (s(i:i) /= ' ') then
          n = n + 1
          t(n:n) = s(i:i)
       end if
    end do
    t = t(1:n)
  end function without_blanks
end module superjoin_utils_strings
