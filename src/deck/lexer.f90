module superjoin_deck_lexer
  !! Lexical layer of the deck reader: loading files, splitting lines into keyword
  !! lines (keyword and parameters) or data fields, and safe conversion of tokens
  !! to reals, ids and names. Nothing here reports errors itself: every routine
  !! returns a status that the parser turns into a `file:line: error:` message.
  use, intrinsic :: ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_utils_strings, only: itoa, to_upper, without_blanks
  use superjoin_utils_grow, only: grow
  use superjoin_utils_huge_pages, only: advise_huge
  use superjoin_utils_posix, only: size_unknown
  implicit none (type, external)
  private

  integer, parameter, public :: TOK_OK = 0        !! converted
    !! Status of a token conversion.
  integer, parameter, public :: TOK_INVALID = 1   !! not a number / id of the right form
  integer, parameter, public :: TOK_RANGE = 2     !! well formed but out of range (0, >= 2**31, overflow)
  integer, parameter, public :: TOK_NONFINITE = 3 !! NaN or Inf written as a word

  integer(i8), parameter :: MAX_ID = 2147483647_i8
    !! Largest id: ids are positive integers below 2**31.
  integer, parameter :: MAX_ID_DIGITS = 10

  character, parameter :: TAB = achar(9), LF = achar(10), CR = achar(13), BLANK = ' '
    !! Characters.

  integer, parameter :: MAX_DEC_EXP = 308          !! leading digit of huge() is at 10**308
    !! Decimal range of real(wp): beyond these exponents a value overflows or is zero.
  integer, parameter :: MIN_DEC_EXP = -345         !! below every subnormal: reads as zero
  integer, parameter :: MAX_EXP_DIGITS = 7         !! exponent digits kept before clamping
  real(wp), parameter :: HUGE_LEAD = 1.7976931348623_wp  !! leading digits of huge(1.0_wp)
  integer(i8), parameter :: EXACT_MANTISSA = 9007199254740992_i8
    !! Exact fast path (Clinger): mantissa below 2**53 times an exact power of ten.
  integer, parameter :: MAX_EXACT_POW10 = 22
  integer, parameter :: MAX_MANTISSA_DIGITS = 18
  real(wp), parameter :: POW10(0:MAX_EXACT_POW10) = [1.0e0_wp, 1.0e1_wp, 1.0e2_wp, 1.0e3_wp, &
       1.0e4_wp, 1.0e5_wp, 1.0e6_wp, 1.0e7_wp, 1.0e8_wp, 1.0e9_wp, 1.0e10_wp, 1.0e11_wp, &
       1.0e12_wp, 1.0e13_wp, 1.0e14_wp, 1.0e15_wp, 1.0e16_wp, 1.0e17_wp, 1.0e18_wp, &
       1.0e19_wp, 1.0e20_wp, 1.0e21_wp, 1.0e22_wp]

  integer, parameter :: READ_CHUNK = 65536
    !! Chunk size of the formatted fallback reader (a read buffer, not a line limit).
  integer, parameter :: INITIAL_FIELDS = 16

  type, public :: param_t
    !! One parameter of a keyword line: `NAME[=VALUE]`.
     character(:), allocatable :: name     !! upper case, inner blanks collapsed
     character(:), allocatable :: value    !! as written, blanks trimmed, quotes removed
     logical :: has_value = .false.
  end type param_t

  type, public :: keyword_line_t
    !! A keyword line `*KEYWORD, PARAM=VALUE, FLAG`.
     character(:), allocatable :: keyword  !! upper case, inner blanks collapsed, without '*'
     integer :: nparam = 0
     type(param_t), allocatable :: params(:)
  end type keyword_line_t

  type, public :: fields_t
    !! Comma separated fields of a data line, as positions in the line
    !! (blanks trimmed; an empty field has last < first).
     integer :: n = 0
     integer, allocatable :: first(:), last(:)
  end type fields_t

  type :: mantissa_t
    !! The mantissa of a real being read: its first significant digits as an
    !! integer m (sig of them), the power of ten they are scaled by, the
    !! number of mantissa digits, whether nonzero digits were dropped.
     integer(i8) :: m = 0
     integer :: nmant = 0, sig = 0, scale = 0
     logical :: truncated = .false.
  end type mantissa_t

  public :: load_file, next_line, first_nonblank, to_upper, collapse_blanks
  public :: parse_keyword_line, split_fields, drop_trailing_empty
  public :: parse_real, parse_id, is_name, is_digits, looks_numeric, itoa, is_path
  public :: path_dirname, path_join, path_normalize, clip, plural

  integer, parameter :: MAX_SHOWN = 60
    !! Longest piece of user text quoted in a message.
  ! The parameter names of the cards that hold a blank: CalculiX removes the
  ! blanks of a keyword line, so its decks may write them without (REFNODE=).
  character(len=*), parameter :: SPACED_PARAMS(*) = [character(len=21) :: 'CONSTANT RESULTANT', 'CONSTRAINT NAME', &
       'CONTACT ELEMENTS', &
       'CYCLIC SYMMETRY', 'DISTORTION CONTROL', 'ELEMENT CONVERSION', 'ELEMENT DELETION', 'END STEP', 'FILE NAME', &
       'FIXED INTERVAL', 'INITIAL GAP OPENING', 'KINEMATIC SPLIT', 'LAST ITERATIONS', 'LENGTH RATIO', 'MAX DEGRADATION', &
       'NO ROTATION', 'NODAL THICKNESS', 'NUMBER INTERVAL', 'OUTPUT FILE', 'POSITION TOLERANCE', 'REF NODE', 'ROT NODE', &
       'ROTARY INERTIA', 'SECOND ORDER ACCURACY', 'SECTION FORCES', 'SECTION INTEGRATION', 'TIME MARKS', 'TIME POINTS', &
       'TIME RESET', 'WEIGHT FACTOR', 'WEIGHTING METHOD']


contains

  ! ------------------------------------------------------------------ files and lines

  subroutine load_file(path, text, ok, need)
    !! Read a whole file into `text` (any size, any line length). `ok` is false
    !! when the file cannot be opened or read; `need` > 0 when it could not be
    !! held in memory (the bytes it needs).
    character(*), intent(in) :: path
    character(:), allocatable, intent(out) :: text
    logical, intent(out) :: ok
    integer(i8), intent(out) :: need
    integer :: unit, ios, stat
    integer(i8) :: nbytes
    logical :: exists

    ok = .false.
    need = 0
    inquire (file=path, exist=exists)
    if (.not. exists) return
    if (size_unknown(path)) then   ! a FIFO or a pipe: opened once and read to its end
       call load_formatted(path, text, ok)
       return
    end if
    open (newunit=unit, file=path, access='stream', form='unformatted', action='read', &
         status='old', iostat=ios)
    if (ios /= 0) return
    inquire (unit=unit, size=nbytes)
    if (nbytes < 0) then
       close (unit)
       call load_formatted(path, text, ok)
       return
    end if
    allocate (character(len=nbytes) :: text, stat=stat)
    if (stat /= 0) then
       close (unit)
       need = nbytes
       return
    end if
    call advise_huge(text)   ! a large deck: read into huge pages, fewer page faults
    ios = 0
    if (nbytes > 0) read (unit, iostat=ios) text
    close (unit)
    ok = (ios == 0)
  end subroutine load_file

  subroutine load_formatted(path, text, ok)
    !! Fallback for files whose size is unknown: formatted non-advancing reads
    !! into a growing buffer, one LF appended per record.
    character(*), intent(in) :: path
    character(:), allocatable, intent(out) :: text
    logical, intent(out) :: ok
    character(len=READ_CHUNK) :: chunk
    character(:), allocatable :: buf
    integer(i8) :: n
    integer :: unit, ios, got
    ok = .false.
    open (newunit=unit, file=path, action='read', status='old', iostat=ios)
    if (ios /= 0) return
    allocate (character(len=READ_CHUNK) :: buf)
    n = 0
    do
       read (unit, '(a)', advance='no', iostat=ios, size=got) chunk
       if (is_iostat_end(ios)) exit
       if (ios /= 0 .and. .not. is_iostat_eor(ios)) then
          close (unit)
          return
       end if
       call append(chunk(1:got))
       if (is_iostat_eor(ios)) call append(LF)
    end do
    close (unit)
    text = buf(1:n)
    ok = .true.
  contains
    subroutine append(s)
      character(*), intent(in) :: s
      character(:), allocatable :: tmp
      if (n + len(s) > len(buf, kind=i8)) then
         allocate (character(len=max(2*len(buf, kind=i8), n + len(s))) :: tmp)
         tmp(1:n) = buf(1:n)
         call move_alloc(tmp, buf)
      end if
      buf(n + 1:n + len(s)) = s
      n = n + len(s)
    end subroutine append
  end subroutine load_formatted

  pure subroutine next_line(text, pos, first, last, found)
    !! Find the line starting at `pos` in `text`: it spans `first:last` (CR and
    !! LF excluded; LF, CR LF and a lone CR all end a line) and `pos` moves to the
    !! next line. `found` is false at the end of the text.
    character(*), intent(in) :: text
    integer(i8), intent(inout) :: pos
    integer(i8), intent(out) :: first, last
    logical, intent(out) :: found
    integer(i8) :: k, n
    n = len(text, kind=i8)
    found = pos <= n
    first = pos
    last = pos - 1
    if (.not. found) return
    k = pos
    do while (k <= n)
       if (text(k:k) == LF .or. text(k:k) == CR) exit
       k = k + 1
    end do
    last = k - 1
    pos = min(k, n) + 1
    if (k < n) then   ! CR LF
       if (text(k:k) == CR .and. text(pos:pos) == LF) pos = pos + 1
    end if
  end subroutine next_line

  pure integer function first_nonblank(s) result(k)
    !! Position of the first character that is not a blank or tab (0 if none).
    character(*), intent(in) :: s
    do k = 1, len(s)
       if (s(k:k) /= BLANK .and. s(k:k) /= TAB) return
    end do
    k = 0
  end function first_nonblank

  ! ------------------------------------------------------------------ text helpers

  pure function collapse_blanks(s) result(t)
    !! s with tabs made blanks, leading/trailing blanks removed and inner runs
    !! of blanks collapsed to one.
    character(*), intent(in) :: s
    character(:), allocatable :: t
    character(len(s)) :: buf
    integer :: k, n
    logical :: pending
    n = 0
    pending = .false.
    do k = 1, len(s)
       if (s(k:k) == BLANK .or. s(k:k) == TAB) then
          pending = n > 0
       else
          if (pending) then
             n = n + 1
             buf(n:n) = BLANK
             pending = .false.
          end if
          n = n + 1
          buf(n:n) = s(k:k)
       end if
    end do
    t = buf(1:n)
  end function collapse_blanks

  pure function spaced_param(name) result(spaced)
    !! A parameter name written without its blank (REFNODE, as CalculiX
    !! reads it: it removes every blank of a keyword line) in its spaced form
    !! (REF NODE); any other name as it is.
    character(*), intent(in) :: name
    character(:), allocatable :: spaced
    integer :: k
    spaced = name
    if (index(name, BLANK) > 0) return
    do k = 1, size(SPACED_PARAMS)
       if (name == without_blanks(trim(SPACED_PARAMS(k)))) then
          spaced = trim(SPACED_PARAMS(k))
          return
       end if
    end do
  end function spaced_param

  pure function clip(s) result(t)
    !! s for quoting in a message: cut to MAX_SHOWN characters ('...' appended).
    character(*), intent(in) :: s
    character(:), allocatable :: t
    if (len(s) > MAX_SHOWN) then
       t = s(1:MAX_SHOWN)//'...'
    else
       t = s
    end if
  end function clip

  pure function plural(n, noun) result(s)
    !! "1 field", "3 fields": a count and a noun.
    integer, intent(in) :: n
    character(*), intent(in) :: noun
    character(:), allocatable :: s
    s = itoa(n)//' '//noun
    if (n /= 1) s = s//'s'
  end function plural


  ! ------------------------------------------------------------------ keyword lines

  pure subroutine parse_keyword_line(line, kw, msg)
    !! Split a keyword line (its first character is '*') into the keyword and its
    !! parameters. On a malformed line `msg` is allocated with the reason.
    character(*), intent(in) :: line
    type(keyword_line_t), intent(out) :: kw
    character(:), allocatable, intent(out) :: msg
    type(fields_t) :: f
    type(param_t), allocatable :: tmp(:)
    character(:), allocatable :: seg, name, value
    integer :: i, j, eq, nv

    call split_fields(line(2:), f)
    kw%keyword = to_upper(collapse_blanks(line(1 + f%first(1):1 + f%last(1))))
    if (len(kw%keyword) == 0) then
       msg = 'empty keyword after ''*'''
       return
    end if
    allocate (kw%params(f%n - 1))
    kw%nparam = 0
    do i = 2, f%n
       seg = line(1 + f%first(i):1 + f%last(i))
       if (len(seg) == 0) cycle
       eq = index(seg, '=')
       param: block
         type(param_t) :: p
         if (eq == 0) then
            name = to_upper(collapse_blanks(seg))
            p%has_value = .false.
            p%value = ''
         else
            name = to_upper(collapse_blanks(seg(1:eq - 1)))
            value = collapse_blanks(seg(eq + 1:))
            nv = len(value)
            if (nv >= 2) then
               if (value(1:1) == '"' .and. value(nv:nv) == '"') value = value(2:nv - 1)
            end if
            if (len(value) == 0) then
               msg = 'parameter '//name//'= has no value'
               return
            end if
            p%has_value = .true.
            p%value = value
         end if
         if (len(name) == 0) then
            msg = 'empty parameter name in '''//seg//''''
            return
         end if
         name = spaced_param(name)
         do j = 1, kw%nparam
            if (kw%params(j)%name == name) then
               msg = 'parameter '//name//' given twice'
               return
            end if
         end do
         p%name = name
         kw%nparam = kw%nparam + 1
         kw%params(kw%nparam) = p
       end block param
    end do
    if (kw%nparam < size(kw%params)) then
       tmp = kw%params(1:kw%nparam)
       call move_alloc(tmp, kw%params)
    end if
  end subroutine parse_keyword_line

  ! ------------------------------------------------------------------ data fields

  pure subroutine split_fields(line, f)
    !! Split a line at commas into fields (positions, blanks trimmed). Reuses the
    !! arrays of `f`, growing them as needed. An empty line gives one empty field.
    character(*), intent(in) :: line
    type(fields_t), intent(inout) :: f
    integer :: start, c, e, a, b, n
    f%n = 0
    start = 1
    n = len(line)
    do
       c = start   ! the comma that ends the field, n + 1 at the end of the line
       do while (c <= n)
          if (line(c:c) == ',') exit
          c = c + 1
       end do
       e = c - 1
       a = start
       b = e
       do while (a <= b)
          if (line(a:a) /= BLANK .and. line(a:a) /= TAB) exit
          a = a + 1
       end do
       do while (b >= a)
          if (line(b:b) /= BLANK .and. line(b:b) /= TAB) exit
          b = b - 1
       end do
       if (.not. allocated(f%first) .or. .not. allocated(f%last)) then
          call grow(f%first, f%n, INITIAL_FIELDS)
          call grow(f%last, f%n, INITIAL_FIELDS)
       else if (f%n >= min(size(f%first), size(f%last))) then
          call grow(f%first, f%n, INITIAL_FIELDS)
          call grow(f%last, f%n, INITIAL_FIELDS)
       end if
       f%n = f%n + 1
       f%first(f%n) = a
       f%last(f%n) = b
       if (c > n) exit
       start = c + 1
    end do
  end subroutine split_fields

  pure subroutine drop_trailing_empty(f)
    !! Forget empty fields at the end of the line (a trailing comma).
    type(fields_t), intent(inout) :: f
    do while (f%n > 0)
       if (f%last(f%n) >= f%first(f%n)) exit
       f%n = f%n - 1
    end do
  end subroutine drop_trailing_empty

  ! ------------------------------------------------------------------ tokens

  pure logical function is_name(s)
    !! True when s is a name: one or more letters, digits, '_', '-' or '/'
    !! (Abaqus/CAE names its spring sets Springs/Dashpots-1-spring).
    character(*), intent(in) :: s
    integer :: k
    is_name = len(s) > 0
    do k = 1, len(s)
       select case (s(k:k))
       case ('A':'Z', 'a':'z', '0':'9', '_', '-', '/')
       case default
          is_name = .false.
          return
       end select
    end do
  end function is_name

  pure logical function is_digits(s)
    !! True when s is one or more decimal digits.
    character(*), intent(in) :: s
    integer :: k
    is_digits = len(s) > 0
    do k = 1, len(s)
       if (s(k:k) < '0' .or. s(k:k) > '9') then
          is_digits = .false.
          return
       end if
    end do
  end function is_digits

  pure logical function looks_numeric(s)
    !! True when s is made only of digits, signs and dots (so it was meant as a
    !! number, not a name).
    character(*), intent(in) :: s
    integer :: k
    looks_numeric = len(s) > 0
    do k = 1, len(s)
       select case (s(k:k))
       case ('0':'9', '+', '-', '.')
       case default
          looks_numeric = .false.
          return
       end select
    end do
  end function looks_numeric

  pure subroutine parse_id(s, id, stat)
    !! Convert an id: digits only, value in 1 .. 2**31-1.
    character(*), intent(in) :: s
    integer(ip), intent(out) :: id
    integer, intent(out) :: stat
    integer :: k, first
    integer(i8) :: v
    id = 0
    if (.not. is_digits(s)) then
       stat = TOK_INVALID
       return
    end if
    first = len(s) + 1
    do k = 1, len(s)
       if (s(k:k) /= '0') then
          first = k
          exit
       end if
    end do
    if (first > len(s) .or. len(s) - first + 1 > MAX_ID_DIGITS) then
       stat = TOK_RANGE
       return
    end if
    v = 0
    do k = first, len(s)
       v = 10*v + (iachar(s(k:k)) - iachar('0'))
    end do
    if (v > MAX_ID) then
       stat = TOK_RANGE
       return
    end if
    id = int(v, ip)
    stat = TOK_OK
  end subroutine parse_id

  subroutine parse_real(s, x, stat)
    !! Convert a real written in Fortran or C form: [sign] digits [. digits]
    !! [(e|E|d|D) [sign] digits], at least one mantissa digit. The characters are
    !! checked here first; values that overflow real(wp) are TOK_RANGE; words such
    !! as NaN and Inf are TOK_NONFINITE. No Fortran I/O error can escape.
    character(*), intent(in) :: s
    real(wp), intent(out) :: x
    integer, intent(out) :: stat
    integer :: i, expo
    logical :: negative, ok
    type(mantissa_t) :: mant

    x = 0.0_wp
    stat = TOK_INVALID
    if (len(s) == 0) return
    i = 1
    negative = .false.
    if (s(1:1) == '+' .or. s(1:1) == '-') then
       negative = s(1:1) == '-'
       i = 2
    end if
    if (i <= len(s)) then   ! a word only when it starts with a letter (or a second sign)
       if (is_letter(s(i:i)) .or. s(i:i) == '+' .or. s(i:i) == '-') then
          if (is_nonfinite_word(to_upper(s(i:)))) then
             stat = TOK_NONFINITE
             return
          end if
       end if
    end if
    call scan_mantissa(s, i, mant, ok)
    if (.not. ok) return
    call scan_exponent(s, i, expo, ok)
    if (.not. ok) return
    call decimal_value(s, negative, mant, expo, x, stat)
  end subroutine parse_real

  pure subroutine scan_mantissa(s, i, mant, ok)
    !! The mantissa digits of s from position i on (i: the first character
    !! after them): its first MAX_MANTISSA_DIGITS significant digits as an
    !! integer, their decimal scale, whether digits were dropped; not ok for a
    !! second '.' or no digit.
    character(*), intent(in) :: s
    integer, intent(inout) :: i
    type(mantissa_t), intent(out) :: mant
    logical, intent(out) :: ok
    logical :: after_dot, started
    character :: c
    ok = .false.
    after_dot = .false.
    started = .false.
    do while (i <= len(s))
       c = s(i:i)
       if (c == '.') then
          if (after_dot) return
          after_dot = .true.
       else if (c >= '0' .and. c <= '9') then
          mant%nmant = mant%nmant + 1
          if (c /= '0') started = .true.
          if (started) then
             if (mant%sig < MAX_MANTISSA_DIGITS) then
                mant%m = 10*mant%m + (iachar(c) - iachar('0'))
                mant%sig = mant%sig + 1
                if (after_dot) mant%scale = mant%scale - 1
             else
                if (.not. after_dot) mant%scale = mant%scale + 1
                if (c /= '0') mant%truncated = .true.
             end if
          else if (after_dot) then
             mant%scale = mant%scale - 1
          end if
       else
          exit
       end if
       i = i + 1
    end do
    ok = mant%nmant > 0
  end subroutine scan_mantissa

  pure subroutine scan_exponent(s, i, expo, ok)
    !! The exponent (e|E|d|D) [sign] digits of s from position i to its end
    !! (0 when there is none); not ok for anything else.
    character(*), intent(in) :: s
    integer, intent(inout) :: i
    integer, intent(out) :: expo
    logical, intent(out) :: ok
    integer :: n, expsign
    character :: c
    n = len(s)
    expo = 0
    ok = .true.
    if (i > n) return
    ok = .false.
    c = s(i:i)
    if (c /= 'e' .and. c /= 'E' .and. c /= 'd' .and. c /= 'D') return
    i = i + 1
    expsign = 1
    if (i <= n) then
       if (s(i:i) == '+' .or. s(i:i) == '-') then
          if (s(i:i) == '-') expsign = -1
          i = i + 1
       end if
    end if
    if (i > n) return
    if (.not. is_digits(s(i:n))) return
    do while (i <= n)
       if (expo < 10**(MAX_EXP_DIGITS - 1)) expo = 10*expo + (iachar(s(i:i)) - iachar('0'))
       i = i + 1
    end do
    expo = expsign*expo
    ok = .true.
  end subroutine scan_exponent

  subroutine decimal_value(s, negative, mant, expo, x, stat)
    !! The value of the checked real s (mantissa mant, exponent expo): exact
    !! when the mantissa and the power of ten are, else by the library
    !! conversion; TOK_RANGE beyond real(wp), 0 below its range.
    character(*), intent(in) :: s
    logical, intent(in) :: negative
    type(mantissa_t), intent(in) :: mant
    integer, intent(in) :: expo
    real(wp), intent(out) :: x
    integer, intent(out) :: stat
    integer :: lead_exp, ios
    real(wp) :: lead
    type(ieee_status_type) :: fp_status
    x = 0.0_wp
    stat = TOK_OK
    if (mant%m == 0) then
       x = 0.0_wp
       if (negative) x = -x
       return
    end if
    ! decimal exponent of the leading digit
    lead_exp = mant%sig - 1 + mant%scale + expo
    if (lead_exp > MAX_DEC_EXP) then
       stat = TOK_RANGE
       return
    end if
    if (lead_exp == MAX_DEC_EXP) then
       lead = real(mant%m, wp)/10.0_wp**(mant%sig - 1)
       if (lead >= HUGE_LEAD) then
          stat = TOK_RANGE
          return
       end if
    end if
    if (lead_exp < MIN_DEC_EXP) then
       x = 0.0_wp
       if (negative) x = -x
       return
    end if
    if (.not. mant%truncated .and. mant%m <= EXACT_MANTISSA .and. abs(mant%scale + expo) <= MAX_EXACT_POW10) then
       if (mant%scale + expo >= 0) then
          x = real(mant%m, wp)*POW10(mant%scale + expo)
       else
          x = real(mant%m, wp)/POW10(-(mant%scale + expo))
       end if
       if (negative) x = -x
       return
    end if
    ! the library conversion may raise underflow/inexact flags: keep the caller's flags
    call ieee_get_status(fp_status)
    read (s, *, iostat=ios) x
    call ieee_set_status(fp_status)
    if (ios /= 0) then
       stat = TOK_INVALID
    else if (x /= x .or. abs(x) > huge(x)) then
       stat = TOK_RANGE
    end if
  end subroutine decimal_value

  elemental logical function is_letter(c)
    !! True for an ASCII letter.
    character, intent(in) :: c
    is_letter = (c >= 'A' .and. c <= 'Z') .or. (c >= 'a' .and. c <= 'z')
  end function is_letter

  pure logical function is_nonfinite_word(u)
    character(*), intent(in) :: u
    select case (u)
    case ('NAN', 'INF', 'INFINITY', 'NAN()', '+INF', '-INF')
       is_nonfinite_word = .true.
    case default
       is_nonfinite_word = len(u) >= 4 .and. index(u, 'NAN(') == 1
    end select
  end function is_nonfinite_word

  ! ------------------------------------------------------------------ paths

  pure function path_dirname(path) result(dir)
    !! Directory part of a path ('' when there is none).
    character(*), intent(in) :: path
    character(:), allocatable :: dir
    integer :: k
    k = index(path, '/', back=.true.)
    if (k == 0) then
       dir = ''
    else if (k == 1) then
       dir = '/'
    else
       dir = path(1:k - 1)
    end if
  end function path_dirname

  pure function path_join(dir, rel) result(path)
    !! `rel` relative to directory `dir` (absolute `rel` is kept).
    character(*), intent(in) :: dir, rel
    character(:), allocatable :: path
    if (len(rel) > 0) then
       if (rel(1:1) == '/') then
          path = rel
          return
       end if
    end if
    if (len(dir) == 0) then
       path = rel
    else if (dir(len(dir):len(dir)) == '/') then
       path = dir//rel
    else
       path = dir//'/'//rel
    end if
  end function path_join

  pure function path_normalize(path) result(norm)
    !! Path with '.' components, repeated slashes and 'dir/..' pairs removed.
    character(*), intent(in) :: path
    character(:), allocatable :: norm
    integer, allocatable :: cs(:), ce(:)
    integer :: n, start, k, e
    logical :: absolute
    absolute = .false.
    if (len(path) > 0) absolute = path(1:1) == '/'
    allocate (cs(len(path) + 1), ce(len(path) + 1))
    n = 0
    start = 1
    do while (start <= len(path))
       k = index(path(start:), '/')
       if (k == 0) then
          e = len(path)
       else
          e = start + k - 2
       end if
       if (e >= start) then
          if (path(start:e) == '.') then
             continue
          else if (path(start:e) == '..') then
             if (n > 0) then
                if (path(cs(n):ce(n)) /= '..') then
                   n = n - 1
                else
                   n = n + 1
                   cs(n) = start
                   ce(n) = e
                end if
             else if (.not. absolute) then
                n = n + 1
                cs(n) = start
                ce(n) = e
             end if
          else
             n = n + 1
             cs(n) = start
             ce(n) = e
          end if
       end if
       if (k == 0) exit
       start = start + k
    end do
    norm = ''
    if (absolute) norm = '/'
    do k = 1, n
       if (k > 1) norm = norm//'/'
       norm = norm//path(cs(k):ce(k))
    end do
    if (len(norm) == 0) norm = '.'
  end function path_normalize

  pure logical function is_path(s)
    !! True when s is an instance path: names joined by '.' (`B`, `B.F3.BAY2`).
    character(*), intent(in) :: s
    integer :: a, dot
    a = 1
    do
       dot = index(s(a:), '.')
       if (dot == 0) exit
       is_path = is_name(s(a:a + dot - 2))
       if (.not. is_path) return
       a = a + dot
    end do
    is_path = is_name(s(a:))
  end function is_path
end module superjoin_deck_lexer
