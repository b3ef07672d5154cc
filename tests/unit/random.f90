module test_random
  !! Reproducible pseudo-random numbers for the unit tests (Park-Miller
  !! minimal standard generator: the same sequence on every machine).
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private
  public :: set_seed, rnd, rnd_in

  integer :: seed = 1
  integer(8), parameter :: MULTIPLIER = 48271_8, MODULUS = 2147483647_8

contains

  subroutine set_seed(s)
    !! Start the sequence at s (1 .. 2147483646).
    integer, intent(in) :: s
    seed = s
  end subroutine set_seed

  real(wp) function rnd()
    !! Uniform number in (0, 1).
    seed = int(mod(MULTIPLIER*int(seed, 8), MODULUS))
    rnd = real(seed, wp)/real(MODULUS, wp)
  end function rnd

  real(wp) function rnd_in(a, b)
    !! Uniform number in (a, b).
    real(wp), intent(in) :: a, b
    rnd_in = a + (b - a)*rnd()
  end function rnd_in
end module test_random
