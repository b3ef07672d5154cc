!> Minimal test harness: checks count failures; finish() prints a summary and
!> stops with a non-zero status when any check failed.
module superjoin_testing
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  integer :: n_pass = 0, n_fail = 0
  public :: check, check_close, check_rel, finish

contains

  !> Record one boolean check.
  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(*), intent(in) :: what
    if (ok) then
       n_pass = n_pass + 1
    else
       n_fail = n_fail + 1
       write (*, '(a)') 'FAIL: '//what
    end if
  end subroutine check

  !> Check |a - b| <= tol.
  subroutine check_close(a, b, tol, what)
    real(wp), intent(in) :: a, b, tol
    character(*), intent(in) :: what
    character(len=120) :: buf
    if (abs(a - b) <= tol .and. a == a .and. b == b) then
       n_pass = n_pass + 1
    else
       n_fail = n_fail + 1
       write (buf, '(3(a,es23.15))') ' got ', a, ' want ', b, ' tol ', tol
       write (*, '(a)') 'FAIL: '//what//trim(buf)
    end if
  end subroutine check_close

  !> Check |a - b| <= tol * max(|b|, tiny).
  subroutine check_rel(a, b, tol, what)
    real(wp), intent(in) :: a, b, tol
    character(*), intent(in) :: what
    call check_close(a, b, tol*max(abs(b), tiny(1.0_wp)), what)
  end subroutine check_rel

  !> Print 'N passed, N failed' and stop with status 1 on failure (test programs only).
  subroutine finish()
    write (*, '(i0,a,i0,a)') n_pass, ' passed, ', n_fail, ' failed'
    if (n_fail > 0) error stop 1
  end subroutine finish
end module superjoin_testing
