module superjoin_utils_clock
  !! Wall-clock timing of the run's phases, reported on stderr.
  use superjoin_kinds, only: wp, i8
  use, intrinsic :: iso_fortran_env, only: error_unit
  implicit none (type, external)
  private

  type, public :: stopwatch_t
    !! A stopwatch.
     integer(i8) :: t0 = 0
  contains
     procedure :: start => stopwatch_start
     procedure :: seconds => stopwatch_seconds
  end type stopwatch_t

  public :: report_phase

contains

  subroutine stopwatch_start(self)
    !! Start (or restart) the stopwatch.
    class(stopwatch_t), intent(inout) :: self
    call system_clock(self%t0)
  end subroutine stopwatch_start

  function stopwatch_seconds(self) result(s)
    !! Seconds since start.
    class(stopwatch_t), intent(in) :: self
    real(wp) :: s
    integer(i8) :: t, rate
    call system_clock(t, rate)
    s = real(t - self%t0, wp)/real(rate, wp)
  end function stopwatch_seconds

  subroutine report_phase(quiet, phase, seconds, detail)
    !! Print "superjoin: <phase> <seconds> s [detail]" on stderr unless quiet.
    logical, intent(in) :: quiet
    character(*), intent(in) :: phase
    real(wp), intent(in) :: seconds
    character(*), intent(in), optional :: detail
    character(len=32) :: buf
    if (quiet) return
    write (buf, '(f10.3)') seconds
    if (present(detail)) then
       write (error_unit, '(a)') 'superjoin: '//phase//' '//trim(adjustl(buf))//' s  '//detail
    else
       write (error_unit, '(a)') 'superjoin: '//phase//' '//trim(adjustl(buf))//' s'
    end if
    flush (error_unit)
  end subroutine report_phase
end module superjoin_utils_clock
