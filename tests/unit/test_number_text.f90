program test_number_text
  !! The listing's number texts (superjoin_utils_number_text) against
  !! gfortran's own formatted WRITE of the same edit, byte for byte:
  !! format_es against ES14.6E3 on millions of random values (random bit
  !! patterns over the whole range, random values of the usual magnitudes) and
  !! on the rounding edges (powers of ten and their neighbours, the decades'
  !! 9.9999995, exact ties to even and their neighbours, subnormals, zeros,
  !! huge, tiny, NaN, Infinity); int_text and itoa against I0; the decade of
  !! every binary exponent.
  use, intrinsic :: iso_fortran_env, only: int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
       ieee_negative_inf, ieee_next_after
  use superjoin_kinds, only: wp, i8
  use superjoin_utils_number_text, only: format_es, int_text, int_field, decade_of_binary, ES_WIDTH, INT_TEXT_LEN
  use superjoin_utils_strings, only: itoa
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  integer, parameter :: N_BITS = 1500000, N_USUAL = 1500000
  integer, parameter :: ULPS = 40, NEAR = 3
    !! neighbours each side of an edge value, of a tie
  integer, parameter :: N_TIES = 30000
  integer, parameter :: MAX_SHOWN = 5
  integer :: n_wrong = 0, n_checked = 0
  integer(int64) :: state = 88172645463325252_int64

  call special_values()
  call binary_decades()
  call powers_of_ten()
  call decade_tops()
  call exact_ties()
  call near_ties()
  call random_bits()
  call random_usual()
  write (*, '(a,i0,a)') 'format_es: ', n_checked, ' values compared with ES14.6E3'
  call check(n_wrong == 0, 'format_es equals ES14.6E3 on '//itoa(n_checked)//' values ('// &
       itoa(n_wrong)//' differ)')
  call integers()
  call finish()

contains

  subroutine compare(x)
    !! One value: format_es against the library's ES14.6E3.
    real(wp), intent(in) :: x
    character(len=ES_WIDTH) :: mine, ref
    call format_es(x, mine)
    write (ref, '(es14.6e3)') x
    n_checked = n_checked + 1
    if (mine /= ref) then
       n_wrong = n_wrong + 1
       if (n_wrong <= MAX_SHOWN) write (*, '(a,z16.16,a)') 'differs: bits ', transfer(x, 0_int64), &
            ' gives ['//mine//'] for ['//ref//']'
    end if
  end subroutine compare

  subroutine around(x, neighbours)
    !! x, -x and `neighbours` (default ULPS) neighbours each side of both.
    real(wp), intent(in) :: x
    integer, intent(in), optional :: neighbours
    real(wp) :: up, down
    integer :: k, n
    n = ULPS
    if (present(neighbours)) n = neighbours
    call compare(x)
    call compare(-x)
    up = x
    down = x
    do k = 1, n
       up = ieee_next_after(up, huge(up))
       down = ieee_next_after(down, 0.0_wp)
       call compare(up)
       call compare(down)
       call compare(-up)
       call compare(-down)
    end do
  end subroutine around

  subroutine special_values()
    call compare(0.0_wp)
    call compare(-0.0_wp)
    call compare(ieee_value(1.0_wp, ieee_quiet_nan))
    call compare(-ieee_value(1.0_wp, ieee_quiet_nan))
    call compare(ieee_value(1.0_wp, ieee_positive_inf))
    call compare(ieee_value(1.0_wp, ieee_negative_inf))
    call around(huge(1.0_wp))
    call around(tiny(1.0_wp))
    call around(1.0_wp)
    call around(0.5_wp)
    ! the smallest subnormals and the subnormal range
    call around(ieee_next_after(0.0_wp, 1.0_wp))
    call around(tiny(1.0_wp)/3)
    call around(1.0e-300_wp)
    call around(1.0e-290_wp)
    call around(1.0e-291_wp)
  end subroutine special_values

  subroutine binary_decades()
    !! decade_of_binary(k) = floor(log10(2**k)) for every binary exponent.
    integer :: k, wrong
    real(wp) :: two_k
    wrong = 0
    do k = -1074, 1023
       two_k = scale(1.0_wp, k)
       if (decade_of_binary(k) /= decade_by_text(two_k)) wrong = wrong + 1
       call compare(two_k)
       call compare(ieee_next_after(two_k, 0.0_wp))
    end do
    call check(wrong == 0, 'decade_of_binary(k) is the decade of 2**k for k = -1074 .. 1023')
  end subroutine binary_decades

  integer function decade_by_text(x) result(e)
    !! The decade of x > 0, from its exact decimal digits (ES with 40 digits).
    real(wp), intent(in) :: x
    character(len=60) :: s
    write (s, '(es60.40e4)') x
    read (s(index(s, 'E') + 1:), *) e
  end function decade_by_text

  subroutine powers_of_ten()
    !! 10**k and its neighbours, k = -323 .. 308.
    integer :: k
    real(wp) :: p
    character(len=16) :: s
    do k = -323, 308
       write (s, '(a,i0)') '1e', k
       read (s, *) p
       call around(p)
    end do
  end subroutine powers_of_ten

  subroutine decade_tops()
    !! 9.9999995 and 9.999999499... of every decade: where rounding carries
    !! into the next decade; and 0.99999995 (1 - 5e-8) likewise.
    integer :: k
    real(wp) :: p
    character(len=24) :: s
    do k = -320, 307
       write (s, '(a,i0)') '9.9999995e', k
       read (s, *) p
       call around(p)
       write (s, '(a,i0)') '9.99999949999e', k
       read (s, *) p
       call around(p)
       write (s, '(a,i0)') '9.999999e', k
       read (s, *) p
       call around(p)
    end do
  end subroutine decade_tops

  subroutine exact_ties()
    !! Values exactly halfway between two 7-digit decimals: 8-digit integers
    !! ending in 5 (even and odd 7th digit), multiples of 1/2**j with eight
    !! significant digits, and their neighbours.
    integer :: k, j
    integer(int64) :: n
    real(wp) :: x
    do k = 1, N_TIES
       n = 10000005_int64 + 10_int64*mod(abs(next_random()), 8999999_int64)
       call around(real(n, wp), NEAR)
       call around(real(n, wp)*1.0e3_wp, NEAR)
    end do
    do j = 1, 60
       do k = 1, N_TIES/60
          x = scale(real(1 + 2*int(mod(abs(next_random()), 2_int64**20)), wp), -j)
          call around(x, NEAR)
       end do
    end do
  end subroutine exact_ties

  subroutine near_ties()
    !! The double nearest to (m + 1/2) 10**(e-6) for random m and e: within
    !! an ulp or so of a tie, the hardest values to decide.
    integer :: k, e
    integer(int64) :: m
    real(wp) :: x
    character(len=32) :: s
    do k = 1, N_TIES
       m = 1000000_int64 + mod(abs(next_random()), 9000000_int64)
       e = int(mod(abs(next_random()), 600_int64)) - 300
       write (s, '(i0,a,i0)') 10*m + 5, 'e', e - 7
       read (s, *) x
       call around(x, NEAR)
    end do
  end subroutine near_ties

  subroutine random_bits()
    !! Random bit patterns: every exponent alike, subnormals, NaNs, infinities.
    integer :: k
    integer(int64) :: bits
    integer(int64), parameter :: EXPONENT_BITS = shiftl(2047_int64, 52)
    do k = 1, N_BITS
       bits = next_random()
       ! a NaN pattern made quiet: a signalling NaN would trap in a Debug build
       if (iand(bits, EXPONENT_BITS) == EXPONENT_BITS) bits = ibset(bits, 51)
       call compare(transfer(bits, 1.0_wp))
    end do
  end subroutine random_bits

  subroutine random_usual()
    !! Random values of the magnitudes results have (1e-30 .. 1e30), either sign.
    integer :: k
    real(wp) :: u, v
    do k = 1, N_USUAL
       u = real(shiftr(next_random(), 11), wp)*2.0_wp**(-53)
       v = real(shiftr(next_random(), 11), wp)*2.0_wp**(-53)
       call compare(sign(10.0_wp**(60*u - 30), v - 0.5_wp))
    end do
  end subroutine random_usual

  integer(int64) function next_random() result(r)
    !! xorshift64: a reproducible stream of 64-bit patterns.
    state = ieor(state, shiftl(state, 13))
    state = ieor(state, shiftr(state, 7))
    state = ieor(state, shiftl(state, 17))
    r = state
  end function next_random

  subroutine integers()
    !! int_text, int_field and itoa against I0 (int_field: right-justified,
    !! blanks before, as I20 writes it).
    integer :: k, wrong, n, wrong_field
    integer(i8) :: v
    integer(i8), parameter :: EDGES(*) = [0_i8, 1_i8, -1_i8, 9_i8, 10_i8, 99_i8, 100_i8, -100_i8, &
         2147483647_i8, -2147483648_i8, huge(1_i8), -huge(1_i8), -huge(1_i8) - 1_i8]
    character(len=INT_TEXT_LEN) :: mine
    character(len=24) :: ref
    character(len=INT_TEXT_LEN) :: ref20
    wrong = 0
    wrong_field = 0
    do k = 1, size(EDGES) + 200000
       if (k <= size(EDGES)) then
          v = EDGES(k)
       else
          v = shifta(next_random(), int(mod(abs(next_random()), 64_int64)))
       end if
       call int_text(v, mine, n)
       write (ref, '(i0)') v
       if (mine(1:n) /= trim(ref)) wrong = wrong + 1
       if (itoa(v) /= trim(ref)) wrong = wrong + 1
       call int_field(v, mine, n)
       write (ref20, '(i20)') v
       if (mine /= ref20 .or. n /= len_trim(adjustl(ref20))) wrong_field = wrong_field + 1
       if (v == int(int(v), i8)) then
          if (itoa(int(v)) /= trim(ref)) wrong = wrong + 1
       end if
    end do
    call check(wrong == 0, 'int_text and itoa equal I0 ('//itoa(wrong)//' differ)')
    call check(wrong_field == 0, 'int_field equals I20 and its length ('//itoa(wrong_field)//' differ)')
  end subroutine integers
end program test_number_text
