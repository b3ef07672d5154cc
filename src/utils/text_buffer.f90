module superjoin_utils_text_buffer
  !! Fast buffered text output for large listings: fields are formatted by
  !! integer arithmetic into a memory buffer that is written in large blocks
  !! (unformatted stream), instead of one formatted WRITE per line.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_utils_posix, only: rename_file, remove_file
  use superjoin_utils_process, only: temp_unregister
  implicit none (type, external)
  private

  integer, parameter :: BUFFER_BYTES = 1048576
    !! bytes collected before a block is written
  integer, parameter :: ES_DIGITS = 7
    !! significant digits of put_es (ES14.6E3 layout)
  integer(i8), parameter :: MANTISSA_LOW = 1000000_i8, MANTISSA_HIGH = 10000000_i8
  real(wp), parameter :: TEN = 10.0_wp
  real(wp), parameter :: LOG10_TWO = 0.30102999566398120_wp
  integer, parameter :: MAX_POWER = 300
    !! largest power of ten applied in one step (subnormals need two)
  integer, parameter :: IOMSG_LEN = 256
    !! length of the kept I/O error message

  type, public :: text_buffer_t
    !! A text file being written.
     integer :: unit = -1
     integer :: pos = 0
     logical :: failed = .false.
     character(len=IOMSG_LEN) :: why = ''   !! message of the first failed write
     character(:), allocatable :: path
     integer(i8) :: written = 0             !! bytes handed to the I/O library
     character(len=BUFFER_BYTES) :: buf
  contains
     procedure :: open => tb_open
     procedure :: put => tb_put
     procedure :: put_field => tb_put_field
     procedure :: put_int => tb_put_int
     procedure :: put_es => tb_put_es
     procedure :: line => tb_line
     procedure :: newline => tb_newline
     procedure :: close => tb_close
     procedure :: commit => tb_commit
     procedure :: reason => tb_reason
  end type text_buffer_t

  public :: format_es, check_file_size

contains

  subroutine tb_open(self, path, error)
    !! Open (replace) path for writing.
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    integer :: ios
    open (newunit=self%unit, file=path, access='stream', form='unformatted', status='replace', &
          action='write', iostat=ios)
    if (ios /= 0) call fatal_error(error, EXIT_IO, 'error: cannot write '//path)
    self%pos = 0
    self%failed = .false.
    self%path = path
    self%written = 0
  end subroutine tb_open

  subroutine flush_block(self)
    class(text_buffer_t), intent(inout) :: self
    integer :: ios
    if (self%pos == 0) return
    if (.not. self%failed) then
       write (self%unit, iostat=ios, iomsg=self%why) self%buf(1:self%pos)
       if (ios /= 0) self%failed = .true.
       self%written = self%written + self%pos
    end if
    self%pos = 0
  end subroutine flush_block

  subroutine tb_put(self, text)
    !! Append text.
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    integer :: n, start, chunk
    n = len(text)
    start = 1
    do while (start <= n)
       if (self%pos == BUFFER_BYTES) call flush_block(self)
       chunk = min(n - start + 1, BUFFER_BYTES - self%pos)
       self%buf(self%pos + 1:self%pos + chunk) = text(start:start + chunk - 1)
       self%pos = self%pos + chunk
       start = start + chunk
    end do
  end subroutine tb_put

  subroutine tb_put_field(self, text, width)
    !! Append text left-justified in a field of `width` characters (cut if longer).
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    integer, intent(in) :: width
    character(len=width) :: f
    f = text
    call self%put(f)
  end subroutine tb_put_field

  subroutine tb_put_int(self, value, width)
    !! Append an integer right-justified in `width` characters (I format).
    class(text_buffer_t), intent(inout) :: self
    integer(i8), intent(in) :: value
    integer, intent(in) :: width
    character(len=24) :: digits
    integer :: n
    call int_digits(value, digits, n)
    if (n < width) call self%put(repeat(' ', width - n))
    call self%put(digits(1:n))
  end subroutine tb_put_int

  subroutine tb_put_es(self, x)
    !! Append ' ' and x in the layout of ES14.6E3 (15 characters).
    class(text_buffer_t), intent(inout) :: self
    real(wp), intent(in) :: x
    character(len=14) :: f
    call format_es(x, f)
    call self%put(' '//f)
  end subroutine tb_put_es

  subroutine tb_line(self, text)
    !! Append text and a newline.
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    call self%put(text)
    call self%put(new_line('a'))
  end subroutine tb_line

  subroutine tb_newline(self)
    !! End the current line.
    class(text_buffer_t), intent(inout) :: self
    call self%put(new_line('a'))
  end subroutine tb_newline

  subroutine tb_close(self, ok)
    !! Write what is left and close; ok is false if any write failed.
    class(text_buffer_t), intent(inout) :: self
    logical, intent(out) :: ok
    integer :: ios
    character(len=IOMSG_LEN) :: why
    call flush_block(self)
    close (self%unit, iostat=ios, iomsg=why)
    if (ios /= 0 .and. .not. self%failed) then
       self%failed = .true.
       self%why = why
    end if
    if (.not. self%failed) call check_file_size(self%path, self%written, self%failed, self%why)
    ok = .not. self%failed
    self%unit = -1
  end subroutine tb_close

  subroutine check_file_size(path, expected, failed, why)
    !! The I/O library may drop the error of its last buffer flush (gfortran
    !! does, on CLOSE): check that every byte written reached the file.
    character(*), intent(in) :: path
    integer(i8), intent(in) :: expected
    logical, intent(out) :: failed
    character(*), intent(inout) :: why
    integer(i8) :: size
    character(len=24) :: got, want
    inquire (file=path, size=size)
    failed = size /= expected
    if (failed) then
       write (got, '(i0)') max(size, 0_i8)
       write (want, '(i0)') expected
       why = 'only '//trim(got)//' of '//trim(want)//' bytes reached the file (disk full or file size limit?)'
    end if
  end subroutine check_file_size

  subroutine tb_commit(self, tmp, path, what, error)
    !! Close the temporary file tmp and rename it to path; on any failure the
    !! temporary file goes and error says 'failed writing <what><path>'. The
    !! temporary name is unregistered (it was registered before opening).
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: tmp, path, what
    type(error_t), allocatable, intent(out) :: error
    logical :: ok
    call self%close(ok)
    if (.not. ok) then
       call remove_file(tmp)
       call temp_unregister()
       call fatal_error(error, EXIT_IO, 'error: failed writing '//what//path//': '//self%reason())
       return
    end if
    call rename_file(tmp, path, error)
    if (allocated(error)) call remove_file(tmp)
    call temp_unregister()
  end subroutine tb_commit

  function tb_reason(self) result(why)
    !! Why writing failed (the I/O library's message).
    class(text_buffer_t), intent(in) :: self
    character(:), allocatable :: why
    why = trim(self%why)
    if (len(why) == 0) why = 'write failed'
  end function tb_reason

  pure subroutine int_digits(value, digits, n)
    integer(i8), intent(in) :: value
    character(len=24), intent(out) :: digits
    integer, intent(out) :: n
    character(len=24) :: rev
    integer(i8) :: v
    integer :: k
    v = abs(value)
    n = 0
    do
       n = n + 1
       rev(n:n) = achar(iachar('0') + int(mod(v, 10_i8)))
       v = v/10
       if (v == 0) exit
    end do
    if (value < 0) then
       n = n + 1
       rev(n:n) = '-'
    end if
    do k = 1, n
       digits(k:k) = rev(n - k + 1:n - k + 1)
    end do
  end subroutine int_digits

  pure subroutine format_es(x, f)
    !! x in the layout of ES14.6E3: sign or blank, d.dddddd, E, exponent sign, 3 digits.
    !! Non-finite values print as the Fortran words.
    real(wp), intent(in) :: x
    character(len=14), intent(out) :: f
    real(wp) :: a
    integer :: e, k
    integer(i8) :: m
    character(len=7) :: md
    character(len=3) :: ed
    f = ' '
    if (x /= x) then
       f(12:14) = 'NaN'
       return
    end if
    if (abs(x) > huge(x)) then
       f = merge('     -Infinity', '      Infinity', x < 0.0_wp)
       return
    end if
    a = abs(x)
    if (a == 0.0_wp) then
       e = 0
       m = 0
    else
       ! floor(log10(a)) or one less, from the binary exponent (the checks
       ! below settle the decade as they did for a rounded log10)
       e = floor((exponent(a) - 1)*LOG10_TWO)
       m = nint(scale10(a, ES_DIGITS - 1 - e), i8)
       if (m >= MANTISSA_HIGH) then
          e = e + 1
          m = nint(scale10(a, ES_DIGITS - 1 - e), i8)
       else if (m < MANTISSA_LOW) then
          e = e - 1
          m = nint(scale10(a, ES_DIGITS - 1 - e), i8)
       end if
       if (m >= MANTISSA_HIGH) then
          m = MANTISSA_LOW
          e = e + 1
       end if
    end if
    do k = 7, 1, -1
       md(k:k) = achar(iachar('0') + int(mod(m, 10_i8)))
       m = m/10
    end do
    write_exp: block
      integer :: ae
      ae = abs(e)
      ed(1:1) = achar(iachar('0') + ae/100)
      ed(2:2) = achar(iachar('0') + mod(ae/10, 10))
      ed(3:3) = achar(iachar('0') + mod(ae, 10))
    end block write_exp
    f(1:1) = merge('-', ' ', x < 0.0_wp)
    f(2:2) = md(1:1)
    f(3:3) = '.'
    f(4:9) = md(2:7)
    f(10:10) = 'E'
    f(11:11) = merge('-', '+', e < 0)
    f(12:14) = ed
  end subroutine format_es

  pure function scale10(a, p) result(y)
    !! a * 10**p, exact powers for |p| <= 22.
    real(wp), intent(in) :: a
    integer, intent(in) :: p
    real(wp) :: y
    if (p > MAX_POWER) then
       y = (a*TEN**MAX_POWER)*TEN**(p - MAX_POWER)
    else if (p >= 0) then
       y = a*TEN**p
    else
       y = a/TEN**(-p)
    end if
  end function scale10
end module superjoin_utils_text_buffer
