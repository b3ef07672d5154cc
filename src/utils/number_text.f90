module superjoin_utils_number_text
  !! Numbers as text by integer arithmetic, byte for byte what gfortran's
  !! formatted WRITE gives for the same edit, without an internal WRITE:
  !! - ES14.6E3, the listing's numbers: correctly rounded, ties to even (gfortran
  !!   hands the rounding to the C library's printf), a minus sign also on
  !!   negative zero, NaN and Infinity right-justified. The 7 significant digits
  !!   come from one product a * 10**p (a correctly rounded power of ten) taken
  !!   to an integer; the decade from the binary exponent. A value whose scaled
  !!   fraction lies within TIE_MARGIN of one half (the product's rounding error
  !!   is 1e6 times smaller, but the rounding direction is then not certain) and
  !!   values below 1e-290 (subnormals) take gfortran's own edit: about one value
  !!   in 500 000 of random data.
  !! - I0 of 64-bit integers.
  use, intrinsic :: iso_fortran_env, only: int64
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  integer, parameter, public :: ES_WIDTH = 14
    !! characters of an ES14.6E3 field
  integer, parameter, public :: INT_TEXT_LEN = 20
    !! characters of the longest I0 text of a 64-bit integer

  integer, parameter :: POW10_LOW = -307, POW10_HIGH = 307
    !! range of the table of powers of ten (normal doubles)
  integer :: power_index
    !! implied-do index of POW10's constructor (holds no value)
  real(wp), parameter :: POW10(POW10_LOW:POW10_HIGH) = [(10.0_wp**power_index, power_index = POW10_LOW, POW10_HIGH)]
    !! 10**p correctly rounded (the compiler folds it exactly; test_number_text checks)
  integer, parameter :: SMALLEST_DECADE = -290
    !! decades below this one (and subnormals) take the library's edit
  integer, parameter :: LOG10_2_NUM = 78913, LOG10_2_SHIFT = 18
    !! floor(k log10 2) = (k * 78913) >> 18 for |k| <= 1650
  integer, parameter :: EXP_BIAS = 1023, MANTISSA_BITS = 52
  integer(int64), parameter :: LOW7 = 1000000_int64, HIGH7 = 10000000_int64
    !! range of a 7-digit mantissa
  real(wp), parameter :: HIGH7_REAL = 1.0e7_wp, HALF = 0.5_wp
  real(wp), parameter :: TIE_MARGIN = 1.0e-6_wp
    !! scaled fractions this close to one half are decided by the library
  character(len=200), parameter :: PAIRS = &
       '0001020304050607080910111213141516171819202122232425262728293031323334353637383940414243444546474849'// &
       '5051525354555657585960616263646566676869707172737475767778798081828384858687888990919293949596979899'
    !! two-digit texts of 0 .. 99

  public :: format_es, int_text, int_field, decade_of_binary

contains

  pure subroutine format_es(x, f)
    !! x in the layout of ES14.6E3, as gfortran writes it: sign or blank,
    !! d.dddddd, E, exponent sign, 3 digits (-1.234568E-005).
    real(wp), intent(in) :: x
    character(len=ES_WIDTH), intent(out) :: f
    real(wp) :: a, y, frac
    integer :: e, p, r, hi, mid
    integer(int64) :: m
    logical :: decided

    if (x /= x) then
       f = '           NaN'
       return
    end if
    a = abs(x)
    if (a > huge(a)) then
       f = merge('     -Infinity', '      Infinity', x < 0.0_wp)
       return
    end if
    if (a == 0.0_wp) then
       m = 0
       e = 0
    else
       e = decade_of_binary(int(shiftr(transfer(a, 0_int64), MANTISSA_BITS)) - EXP_BIAS)
       decided = e >= SMALLEST_DECADE
       if (decided) then
          ! e is the decade of a or the one below it
          p = 6 - e
          y = a*POW10(p)
          if (y >= HIGH7_REAL) then
             e = e + 1
             y = a*POW10(p - 1)
          end if
          m = int(y, int64)
          frac = y - real(m, wp)
          decided = abs(frac - HALF) >= TIE_MARGIN
          if (frac > HALF) m = m + 1
          if (m == HIGH7) then   ! 9.9999995 and above: the next decade
             m = LOW7
             e = e + 1
          end if
          decided = decided .and. m >= LOW7 .and. m < HIGH7
       end if
       if (.not. decided) then
          write (f, '(es14.6e3)') x
          return
       end if
    end if
    r = int(m)
    hi = r/1000000
    r = r - 1000000*hi
    mid = r/10000
    r = r - 10000*mid
    f(1:1) = merge('-', ' ', sign(1.0_wp, x) < 0.0_wp)
    f(2:2) = achar(iachar('0') + hi)
    f(3:3) = '.'
    f(4:5) = PAIRS(2*mid + 1:2*mid + 2)
    f(6:7) = PAIRS(2*(r/100) + 1:2*(r/100) + 2)
    f(8:9) = PAIRS(2*mod(r, 100) + 1:2*mod(r, 100) + 2)
    f(10:10) = 'E'
    f(11:11) = merge('-', '+', e < 0)
    r = abs(e)
    f(12:12) = achar(iachar('0') + r/100)
    f(13:14) = PAIRS(2*mod(r, 100) + 1:2*mod(r, 100) + 2)
  end subroutine format_es

  elemental integer function decade_of_binary(k) result(e)
    !! floor(k log10 2) for a binary exponent |k| <= 1650: the decade of
    !! 2**k, so the decade of a value in [2**k, 2**(k+1)) or the one below it.
    integer, intent(in) :: k
    e = shifta(k*LOG10_2_NUM, LOG10_2_SHIFT)
  end function decade_of_binary

  pure subroutine int_text(value, text, n)
    !! value as I0 writes it: text(1:n), a minus sign and the digits.
    integer(i8), intent(in) :: value
    character(len=INT_TEXT_LEN), intent(out) :: text
    integer, intent(out) :: n
    character(len=INT_TEXT_LEN) :: field
    call int_field(value, field, n)
    text(1:n) = field(INT_TEXT_LEN - n + 1:)
  end subroutine int_text

  pure subroutine int_field(value, field, n)
    !! value as I0 writes it, right-justified in field (blanks before it): the
    !! text is field's last n characters. A table's integer column is a
    !! slice of field, one copy instead of int_text's two and a fill.
    integer(i8), intent(in) :: value
    character(len=INT_TEXT_LEN), intent(out) :: field
    integer, intent(out) :: n
    integer(i8) :: v, q
    integer :: k, d
    if (value == -huge(value) - 1) then
       write (field, '(i20)') value   ! 19 digits and the sign fill I20
       n = INT_TEXT_LEN
       return
    end if
    field = ' '
    v = abs(value)
    k = INT_TEXT_LEN
    do
       q = v/100
       d = int(v - 100*q)
       field(k - 1:k) = PAIRS(2*d + 1:2*d + 2)
       k = k - 2
       v = q
       if (v == 0) exit
    end do
    if (d < 10) then   ! the leading pair's zero
       k = k + 1
       field(k:k) = ' '
    end if
    if (value < 0) then
       field(k:k) = '-'
       k = k - 1
    end if
    n = INT_TEXT_LEN - k
  end subroutine int_field
end module superjoin_utils_number_text
