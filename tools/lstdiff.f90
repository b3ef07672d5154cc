program lstdiff
  !! lstdiff: compare two listings token by token; numbers may differ by
  !! |a - b| <= atol + rtol * max(|a|, |b|). Exit 0 when equal, 1 otherwise.
  !! usage: lstdiff [--rtol R] [--atol A] [--scale-atol F] REFERENCE OUTPUT
  !! (--scale-atol: the absolute tolerance is at least F times the largest number in REFERENCE)
  !! [--health-rtol H [--health-floor F]]: the numbers of the NUMERICAL HEALTH
  !! lines (relative residual, residual before refinement, EPSILON, MAXRATIO,
  !! condition estimate) are compared with the relative tolerance H alone, never
  !! with an absolute one; two values both at or below F in magnitude (default
  !! 1e-10: round-off, which differs between builds) count as equal.
  !! A step's name right after a real number (with a point or an exponent)
  !! is not compared when that number differs between the files, is zero but
  !! for round-off in both (at most ROUND_OFF_ZERO times the largest number
  !! of the reference outside its NUMERICAL HEALTH lines, and within the
  !! absolute tolerance) and both files name a step of the reference there
  !! ("STEP n  NAME" lines): the step of an envelope's extreme over values
  !! that are all zero but for round-off, which round-off decides and which
  !! differs between CPUs' kernels. Any other word is compared, and so is a
  !! step's name after an integer, after a value above that bound, or after
  !! a number printed alike in both files (the envelope's first-on-a-tie rule).
  use, intrinsic :: iso_fortran_env, only: real64, error_unit
  implicit none (type, external)
  integer, parameter :: wp = real64
  integer, parameter :: MAX_REPORTED = 20
  real(wp) :: rtol = 1.0e-6_wp, atol = 1.0e-9_wp, scale_atol = 0.0_wp
  real(wp) :: health_rtol = 0.0_wp, health_floor = 1.0e-10_wp
  real(wp), parameter :: ROUND_OFF_ZERO = 1.0e-13_wp
    !! A result at most this times the reference's largest is zero but for round-off.
  real(wp) :: zero_bound = 0.0_wp
    !! ROUND_OFF_ZERO times the largest result of the reference, at most atol.
  character(len=*), parameter :: HEALTH_LABELS(5) = [character(len=27) :: 'relative residual', &
       'residual before refinement', 'EPSILON (energy error)', 'MAXRATIO', 'condition estimate']
    !! Lines of the NUMERICAL HEALTH block (compared relatively with --health-rtol).
  integer, parameter :: NAME_LEN = 64
  character(len=NAME_LEN), allocatable :: step_names(:)
    !! The names of the reference's steps (its "STEP n  NAME" lines).
  integer :: status

  call compare_files(status)
  if (status /= 0) stop status, quiet=.true.

contains

  subroutine compare_files(status)
    !! Compare the two files named on the command line; status 0 equal, 1 differ, 2 usage.
    integer, intent(out) :: status
    character(:), allocatable :: ref, out, a, b, arg, val
    integer :: ua, ub, ia, ib, lineno, nbad, i, n
    logical :: ea, eb
    status = 0
  n = command_argument_count()
  i = 0
  do while (i < n)
     i = i + 1
     arg = get_arg(i)
     select case (arg)
     case ('--rtol')
        i = i + 1
        val = get_arg(i)
        read (val, *) rtol
     case ('--atol')
        i = i + 1
        val = get_arg(i)
        read (val, *) atol
     case ('--scale-atol')
        i = i + 1
        val = get_arg(i)
        read (val, *) scale_atol
     case ('--health-rtol')
        i = i + 1
        val = get_arg(i)
        read (val, *) health_rtol
     case ('--health-floor')
        i = i + 1
        val = get_arg(i)
        read (val, *) health_floor
     case default
        if (.not. allocated(ref)) then
           ref = arg
        else
           out = arg
        end if
     end select
  end do
  if (.not. allocated(out)) then
     write (error_unit, '(a)') 'usage: lstdiff [--rtol R] [--atol A] [--scale-atol F] '// &
          '[--health-rtol H] [--health-floor F] REFERENCE OUTPUT'
     status = 2
     return
  end if
  open (newunit=ua, file=ref, status='old', action='read', iostat=ia)
  open (newunit=ub, file=out, status='old', action='read', iostat=ib)
  if (ia /= 0 .or. ib /= 0) then
     write (error_unit, '(a)') 'lstdiff: cannot open '//ref//' or '//out
     status = 2
     return
  end if
  ! An absolute floor proportional to the largest number of the reference.
  if (scale_atol > 0.0_wp) then
     atol = max(atol, scale_atol*largest_number(ua, .false.))
     rewind (ua)
  end if
  zero_bound = min(atol, ROUND_OFF_ZERO*largest_number(ua, .true.))
  rewind (ua)
  call collect_step_names(ua)
  rewind (ua)
  lineno = 0
  nbad = 0
  do
     call read_line(ua, a, ea)
     call read_line(ub, b, eb)
     lineno = lineno + 1
     if (ea .and. eb) exit
     if (ea .neqv. eb) then
        write (error_unit, '(a,i0,a)') 'line ', lineno, ': files have different lengths'
        nbad = nbad + 1
        exit
     end if
     if (.not. same_line(a, b, health_rtol > 0.0_wp .and. is_health_line(a))) then
        nbad = nbad + 1
        if (nbad <= MAX_REPORTED) then
           write (error_unit, '(a,i0)') 'line ', lineno
           write (error_unit, '(a)') '< '//a
           write (error_unit, '(a)') '> '//b
        end if
     end if
  end do
  close (ua)
  close (ub)
  deallocate (step_names)
  if (nbad > 0) then
     write (error_unit, '(i0,a)') nbad, ' line(s) differ'
     status = 1
  end if
  end subroutine compare_files

  function largest_number(u, results_only) result(big)
    !! Largest absolute value of the numeric tokens of an open file (outside
    !! its NUMERICAL HEALTH lines when results_only).
    integer, intent(in) :: u
    logical, intent(in) :: results_only
    real(wp) :: big, x
    character(:), allocatable :: line, tok
    logical :: eof, ok
    integer :: p
    big = 0.0_wp
    do
       call read_line(u, line, eof)
       if (eof) exit
       if (results_only .and. is_health_line(line)) cycle
       p = 1
       do
          call next_token(line, p, tok)
          if (len(tok) == 0) exit
          call as_number(tok, x, ok)
          if (ok) big = max(big, abs(x))
       end do
    end do
  end function largest_number

  subroutine collect_step_names(u)
    !! step_names: the third token of the lines "STEP n  NAME" of an open file.
    integer, intent(in) :: u
    character(:), allocatable :: line, t1, t2, t3
    character(len=NAME_LEN), allocatable :: grown(:)
    logical :: eof
    integer :: p, n
    allocate (step_names(16))
    n = 0
    do
       call read_line(u, line, eof)
       if (eof) exit
       if (index(line, 'STEP ') /= 1) cycle
       p = 1
       call next_token(line, p, t1)
       call next_token(line, p, t2)
       call next_token(line, p, t3)
       if (len(t2) == 0 .or. verify(t2, '0123456789') /= 0 .or. len(t3) == 0) cycle
       if (n == size(step_names)) then
          allocate (grown(2*n))
          grown(1:n) = step_names
          call move_alloc(grown, step_names)
       end if
       n = n + 1
       step_names(n) = t3
    end do
    allocate (grown(n))
    grown = step_names(1:n)
    call move_alloc(grown, step_names)
  end subroutine collect_step_names

  logical function is_step_name(tok)
    !! tok is the name of one of the reference's steps.
    character(*), intent(in) :: tok
    is_step_name = len(tok) <= NAME_LEN .and. any(step_names == tok)
  end function is_step_name

  logical function is_real_text(tok)
    !! tok is written as a real number (with a point or an exponent), not an integer.
    character(*), intent(in) :: tok
    is_real_text = scan(tok, '.eEdD') > 0
  end function is_real_text

  function get_arg(i) result(s)
    integer, intent(in) :: i
    character(:), allocatable :: s
    integer :: length
    call get_command_argument(i, length=length)
    allocate (character(len=length) :: s)
    if (length > 0) call get_command_argument(i, s)
  end function get_arg

  subroutine read_line(u, line, eof)
    integer, intent(in) :: u
    character(:), allocatable, intent(out) :: line
    logical, intent(out) :: eof
    character(len=512) :: buf
    integer :: ios, sz
    line = ''
    eof = .false.
    do
       read (u, '(a)', advance='no', iostat=ios, size=sz) buf
       line = line//buf(1:sz)
       if (is_iostat_eor(ios)) exit
       if (is_iostat_end(ios)) then
          eof = len(line) == 0
          exit
       end if
       if (ios /= 0) then
          eof = .true.
          exit
       end if
    end do
  end subroutine read_line

  logical function is_health_line(line)
    !! Whether a listing line is one of the NUMERICAL HEALTH values.
    character(*), intent(in) :: line
    integer :: k
    is_health_line = .false.
    do k = 1, size(HEALTH_LABELS)
       if (index(adjustl(line), trim(HEALTH_LABELS(k))) == 1) is_health_line = .true.
    end do
  end function is_health_line

  logical function same_line(a, b, health)
    !! Lines match when their tokens match (numbers within tolerance; health
    !! values relatively, above the round-off floor; a step's name after a
    !! round-off zero is not compared, see the program's header).
    character(*), intent(in) :: a, b
    logical, intent(in) :: health
    integer :: pa, pb
    character(:), allocatable :: ta, tb
    real(wp) :: xa, xb
    logical :: na, nb, zero_before
    same_line = .true.
    pa = 1
    pb = 1
    zero_before = .false.
    do
       call next_token(a, pa, ta)
       call next_token(b, pb, tb)
       if (len(ta) == 0 .and. len(tb) == 0) return
       call as_number(ta, xa, na)
       call as_number(tb, xb, nb)
       if (ta == tb) then
          zero_before = .false.
          cycle
       end if
       if (zero_before .and. is_step_name(ta) .and. is_step_name(tb)) then   ! the step of a round-off extreme
          zero_before = .false.
          cycle
       end if
       zero_before = na .and. nb .and. is_real_text(ta) .and. is_real_text(tb) .and. max(abs(xa), abs(xb)) <= zero_bound
       if (.not. (na .and. nb)) then
          same_line = .false.
          return
       end if
       if (health) then
          if (max(abs(xa), abs(xb)) <= health_floor) cycle
          if (abs(xa - xb) > health_rtol*max(abs(xa), abs(xb))) then
             same_line = .false.
             return
          end if
       else if (abs(xa - xb) > atol + rtol*max(abs(xa), abs(xb))) then
          same_line = .false.
          return
       end if
    end do
  end function same_line

  subroutine next_token(s, p, tok)
    character(*), intent(in) :: s
    integer, intent(inout) :: p
    character(:), allocatable, intent(out) :: tok
    integer :: q
    do while (p <= len(s))
       if (s(p:p) /= ' ' .and. s(p:p) /= ',') exit
       p = p + 1
    end do
    q = p
    do while (q <= len(s))
       if (s(q:q) == ' ' .or. s(q:q) == ',') exit
       q = q + 1
    end do
    tok = s(p:q - 1)
    p = q
  end subroutine next_token

  subroutine as_number(tok, x, ok)
    character(*), intent(in) :: tok
    real(wp), intent(out) :: x
    logical, intent(out) :: ok
    integer :: ios, k
    ok = .false.
    x = 0.0_wp
    if (len(tok) == 0) return
    if (verify(tok, '0123456789+-.eEdD') /= 0) return
    do k = 1, len(tok)
       if (index('0123456789', tok(k:k)) > 0) exit
    end do
    if (k > len(tok)) return
    read (tok, *, iostat=ios) x
    ok = ios == 0
  end subroutine as_number
end program lstdiff
