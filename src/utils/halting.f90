module superjoin_utils_halting
  !! Floating-point halting off around arithmetic on user data (the Debug build
  !! traps overflow, invalid and division by zero): the caller checks its
  !! results for finiteness instead and reports a deck error.
  use, intrinsic :: ieee_exceptions, only: ieee_flag_type, ieee_get_halting_mode, ieee_set_halting_mode, &
       ieee_overflow, ieee_invalid, ieee_divide_by_zero
  implicit none (type, external)
  private

  type(ieee_flag_type), parameter :: FLAGS(3) = [ieee_overflow, ieee_invalid, ieee_divide_by_zero]

  type, public :: halting_t
    !! Saved halting modes.
     logical :: mode(3) = .false.
  end type halting_t

  public :: halting_off, halting_restore

contains

  subroutine halting_off(saved)
    !! Save the halting modes of overflow, invalid and division by zero, and turn them off.
    type(halting_t), intent(out) :: saved
    integer :: i
    do i = 1, size(FLAGS)
       call ieee_get_halting_mode(FLAGS(i), saved%mode(i))
       call ieee_set_halting_mode(FLAGS(i), .false.)
    end do
  end subroutine halting_off

  subroutine halting_restore(saved)
    !! Restore the halting modes saved by halting_off.
    type(halting_t), intent(in) :: saved
    integer :: i
    do i = 1, size(FLAGS)
       call ieee_set_halting_mode(FLAGS(i), saved%mode(i))
    end do
  end subroutine halting_restore
end module superjoin_utils_halting
