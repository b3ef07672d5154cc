module superjoin_testing
  !! Minimal test harness: checks count failures; finish() prints a summary and
  !! stops with a non-zero status when any check failed.
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  integer :: n_pass = 0, n_fail = 0
  logical :: verbose_checked = .false., verbose = .false.
  public :: check, check_close, check_rel, finish, temp_dir

contains

  subroutine check(ok, what)
    !! Record one boolean check.
    logical, intent(in) :: ok
    character(*), intent(in) :: what
    if (ok) then
       n_pass = n_pass + 1
    else
       n_fail = n_fail + 1
       write (*, '(a)') 'FAIL: '//what
    end if
  end subroutine check

  subroutine check_close(a, b, tol, what)
    !! Check |a - b| <= tol.
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

  subroutine check_rel(a, b, tol, what)
    !! Check |a - b| <= tol * max(|b|, tiny). With SUPERJOIN_TEST_VERBOSE=1 in
    !! the environment every such check prints its relative error.
    real(wp), intent(in) :: a, b, tol
    character(*), intent(in) :: what
    integer :: length, stat
    character(len=8) :: value
    if (.not. verbose_checked) then
       call get_environment_variable('SUPERJOIN_TEST_VERBOSE', value, length, stat)
       verbose = stat == 0 .and. value(1:1) == '1'
       verbose_checked = .true.
    end if
    if (verbose) write (*, '(a,es10.2,a,es24.16)') 'relerr ', abs(a - b)/max(abs(b), tiny(1.0_wp)), '  '//what//'  value ', a
    call check_close(a, b, tol*max(abs(b), tiny(1.0_wp)), what)
  end subroutine check_rel

  subroutine finish()
    !! Print 'N passed, N failed' and stop with status 1 on failure (test programs only).
    write (*, '(i0,a,i0,a)') n_pass, ' passed, ', n_fail, ' failed'
    if (n_fail > 0) error stop 1
  end subroutine finish

  function temp_dir() result(dir)
    !! The directory for temporary files: $TMPDIR, else /tmp.
    character(:), allocatable :: dir
    integer :: length, stat
    call get_environment_variable('TMPDIR', length=length, status=stat)
    if (stat == 0 .and. length > 0) then
       allocate (character(len=length) :: dir)
       call get_environment_variable('TMPDIR', dir)
    else
       dir = '/tmp'
    end if
  end function temp_dir
end module superjoin_testing
