module superjoin_utils_text_buffer
  !! Fast buffered text output for large listings: fields are formatted by
  !! integer arithmetic into a memory buffer that is written in large blocks
  !! (unformatted stream), instead of one formatted WRITE per line. A buffer
  !! opened in memory (open_memory) keeps its text instead, for another
  !! buffer to take (take): text formatted on a second thread.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_utils_posix, only: rename_file, remove_file
  use superjoin_utils_process, only: temp_unregister
  use superjoin_utils_number_text, only: format_es, int_field, ES_WIDTH, INT_TEXT_LEN
  implicit none (type, external)
  private

  integer, parameter :: BUFFER_BYTES = 1048576
    !! bytes collected before a block is written
  integer, parameter :: ES_FIELD = ES_WIDTH + 1
    !! characters of put_es: a blank and an ES14.6E3 field
  integer, parameter :: BLANK_RUN = 64
  character(len=BLANK_RUN), parameter :: BLANKS = repeat(' ', BLANK_RUN)
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
     logical :: in_memory = .false.         !! keeps its text (open_memory) instead of writing it
     character(:), allocatable :: kept      !! in memory: the text of the full blocks so far
     integer(i8) :: kept_len = 0            !! in memory: characters of kept in use
     character(:), allocatable :: buf       !! the block being filled (BUFFER_BYTES, from open or open_memory)
  contains
     procedure :: open => tb_open
     procedure :: open_memory => tb_open_memory
     procedure :: take => tb_take
     procedure :: put => tb_put
     procedure :: put_field => tb_put_field
     procedure :: put_int => tb_put_int
     procedure :: put_row_head => tb_put_row_head
     procedure :: put_es => tb_put_es
     procedure :: put_es_row => tb_put_es_row
     procedure :: put_blanks => tb_put_blanks
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
    if (.not. block_ready(self)) then
       call fatal_error(error, EXIT_IO, 'error: out of memory for the output buffer of '//path)
       return
    end if
    open (newunit=self%unit, file=path, access='stream', form='unformatted', status='replace', &
          action='write', iostat=ios)
    if (ios /= 0) call fatal_error(error, EXIT_IO, 'error: cannot write '//path)
    self%pos = 0
    self%failed = .false.
    self%path = path
    self%written = 0
    self%in_memory = .false.
  end subroutine tb_open

  subroutine tb_open_memory(self)
    !! Begin empty, keeping the text in memory (for take) instead of writing it;
    !! failed when there is no memory for its block (then nothing may be put).
    class(text_buffer_t), intent(inout) :: self
    self%in_memory = .true.
    self%pos = 0
    self%kept_len = 0
    self%failed = .not. block_ready(self)
    if (self%failed) self%why = 'out of memory for the output buffer'
  end subroutine tb_open_memory

  logical function block_ready(self)
    !! Whether the buffer has its block, allocated here if need be. The block
    !! is an allocatable component, not a fixed one: a fixed megabyte would
    !! sit on the stack in every procedure with a buffer of its own (the
    !! library is compiled with -fopenmp, which makes locals automatic; even
    !! ALLOCATE builds the default value on the stack).
    class(text_buffer_t), intent(inout) :: self
    integer :: stat
    stat = 0
    if (.not. allocated(self%buf)) allocate (character(len=BUFFER_BYTES) :: self%buf, stat=stat)
    block_ready = stat == 0
  end function block_ready

  subroutine tb_take(self, other)
    !! Append the text kept by other (opened with open_memory), which is left
    !! empty. A buffer writing a file writes it out directly, after its own
    !! text (no copy into its own block). Nothing is taken from a buffer that
    !! failed (its text is incomplete: the caller formats it again).
    class(text_buffer_t), intent(inout) :: self
    type(text_buffer_t), intent(inout) :: other
    if (other%failed) then
       other%kept_len = 0
       other%pos = 0
       return
    end if
    if (self%in_memory) then
       if (other%kept_len > 0) call append_in_pieces(self, other%kept, other%kept_len)
       call self%put(other%buf(1:other%pos))
    else
       call flush_block(self)
       if (other%kept_len > 0) call write_out(self, other%kept, other%kept_len)
       call write_out(self, other%buf, int(other%pos, i8))
    end if
    other%kept_len = 0
    other%pos = 0
  end subroutine tb_take

  subroutine append_in_pieces(self, text, n)
    !! put text(1:n), a block at a time (put takes a default-integer length).
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    integer(i8), intent(in) :: n
    integer(i8) :: start, chunk
    start = 1
    do while (start <= n)
       chunk = min(n - start + 1, int(BUFFER_BYTES, i8))
       call self%put(text(start:start + chunk - 1))
       start = start + chunk
    end do
  end subroutine append_in_pieces

  subroutine write_out(self, text, n)
    !! text(1:n) written to the file as it is (the buffer is empty).
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    integer(i8), intent(in) :: n
    integer :: ios
    if (n <= 0 .or. self%failed) return
    write (self%unit, iostat=ios, iomsg=self%why) text(1:n)
    if (ios /= 0) self%failed = .true.
    self%written = self%written + n
  end subroutine write_out

  subroutine keep_block(self)
    !! In memory: the buffer's text appended to kept (which grows by doubling).
    class(text_buffer_t), intent(inout) :: self
    character(:), allocatable :: grown
    integer(i8) :: need
    integer :: stat
    need = self%kept_len + self%pos
    stat = 0
    if (.not. allocated(self%kept)) then
       allocate (character(len=max(need, int(BUFFER_BYTES, i8))) :: self%kept, stat=stat)
    else if (len(self%kept, i8) < need) then
       allocate (character(len=max(need, 2*len(self%kept, i8))) :: grown, stat=stat)
       if (stat == 0) then
          grown(1:self%kept_len) = self%kept(1:self%kept_len)
          call move_alloc(grown, self%kept)
       end if
    end if
    if (stat /= 0) then   ! the text is lost: failed tells the taker to format it itself
       self%failed = .true.
       self%why = 'out of memory for the text kept in memory'
       self%pos = 0
       return
    end if
    self%kept(self%kept_len + 1:need) = self%buf(1:self%pos)
    self%kept_len = need
    self%pos = 0
  end subroutine keep_block

  subroutine flush_block(self)
    class(text_buffer_t), intent(inout) :: self
    if (self%pos == 0) return
    if (self%in_memory) then
       call keep_block(self)
       return
    end if
    call write_out(self, self%buf, int(self%pos, i8))
    self%pos = 0
  end subroutine flush_block

  subroutine tb_put(self, text)
    !! Append text.
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    integer :: n, start, chunk
    n = len(text)
    if (self%pos + n <= BUFFER_BYTES) then
       self%buf(self%pos + 1:self%pos + n) = text
       self%pos = self%pos + n
       return
    end if
    start = 1
    do while (start <= n)
       if (self%pos == BUFFER_BYTES) call flush_block(self)
       chunk = min(n - start + 1, BUFFER_BYTES - self%pos)
       self%buf(self%pos + 1:self%pos + chunk) = text(start:start + chunk - 1)
       self%pos = self%pos + chunk
       start = start + chunk
    end do
  end subroutine tb_put

  logical function has_room(self, n)
    !! Whether n more characters fit in the buffer, after writing it out if
    !! they do not (false: n is larger than the whole buffer).
    class(text_buffer_t), intent(inout) :: self
    integer, intent(in) :: n
    if (self%pos + n > BUFFER_BYTES) call flush_block(self)
    has_room = n <= BUFFER_BYTES
  end function has_room

  subroutine tb_put_blanks(self, count)
    !! Append `count` blanks.
    class(text_buffer_t), intent(inout) :: self
    integer, intent(in) :: count
    integer :: left
    if (count <= 0) return
    if (has_room(self, count)) then
       self%buf(self%pos + 1:self%pos + count) = ' '
       self%pos = self%pos + count
       return
    end if
    left = count
    do while (left > 0)
       call self%put(BLANKS(1:min(left, BLANK_RUN)))
       left = left - BLANK_RUN
    end do
  end subroutine tb_put_blanks

  subroutine tb_put_field(self, text, width)
    !! Append text left-justified in a field of `width` characters (cut if longer).
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    integer, intent(in) :: width
    if (width <= 0) return
    if (has_room(self, width)) then
       ! the assignment pads with blanks or cuts
       self%buf(self%pos + 1:self%pos + width) = text
       self%pos = self%pos + width
    else if (len(text) >= width) then
       call self%put(text(1:width))
    else
       call self%put(text)
       call self%put_blanks(width - len(text))
    end if
  end subroutine tb_put_field

  subroutine tb_put_int(self, value, width)
    !! Append an integer right-justified in `width` characters (I format).
    class(text_buffer_t), intent(inout) :: self
    integer(i8), intent(in) :: value
    integer, intent(in) :: width
    character(len=INT_TEXT_LEN) :: field
    integer :: n, w
    call int_field(value, field, n)
    w = max(n, width)
    if (w <= INT_TEXT_LEN .and. has_room(self, w)) then   ! the field's blanks are the padding
       self%buf(self%pos + 1:self%pos + w) = field(INT_TEXT_LEN - w + 1:)
       self%pos = self%pos + w
       return
    end if
    call self%put_blanks(width - n)
    call self%put(field(INT_TEXT_LEN - n + 1:))
  end subroutine tb_put_int

  subroutine tb_put_row_head(self, blanks, text, width, value, value_width, tail)
    !! Append `blanks` blanks, text in a field of `width` characters
    !! (put_field), value right-justified in `value_width` (put_int) and
    !! tail, after one room check instead of one per piece.
    class(text_buffer_t), intent(inout) :: self
    integer, intent(in) :: blanks, width, value_width
    character(*), intent(in) :: text, tail
    integer(i8), intent(in) :: value
    character(len=INT_TEXT_LEN) :: digits
    integer :: n, p, w
    call int_field(value, digits, n)
    w = max(n, value_width)
    if (w > INT_TEXT_LEN .or. .not. has_room(self, max(blanks, 0) + max(width, 0) + w + len(tail))) then
       call self%put_blanks(blanks)
       call self%put_field(text, width)
       call self%put_int(value, value_width)
       call self%put(tail)
       return
    end if
    p = self%pos
    if (blanks > 0) self%buf(p + 1:p + blanks) = ' '
    p = p + max(blanks, 0)
    if (width > 0) self%buf(p + 1:p + width) = text   ! pads with blanks or cuts
    p = p + max(width, 0)
    self%buf(p + 1:p + w) = digits(INT_TEXT_LEN - w + 1:)   ! the field's blanks are the padding
    p = p + w
    self%buf(p + 1:p + len(tail)) = tail
    self%pos = p + len(tail)
  end subroutine tb_put_row_head

  subroutine tb_put_es(self, x)
    !! Append ' ' and x in the layout of ES14.6E3 (15 characters).
    class(text_buffer_t), intent(inout) :: self
    real(wp), intent(in) :: x
    if (has_room(self, ES_FIELD)) then
       self%buf(self%pos + 1:self%pos + 1) = ' '
       call format_es(x, self%buf(self%pos + 2:self%pos + ES_FIELD))
       self%pos = self%pos + ES_FIELD
    end if
  end subroutine tb_put_es

  subroutine tb_put_es_row(self, x)
    !! Append each of x as put_es does.
    class(text_buffer_t), intent(inout) :: self
    real(wp), intent(in) :: x(:)
    integer :: k
    if (.not. has_room(self, ES_FIELD*size(x))) then
       do k = 1, size(x)
          call self%put_es(x(k))
       end do
       return
    end if
    do k = 1, size(x)
       self%buf(self%pos + 1:self%pos + 1) = ' '
       call format_es(x(k), self%buf(self%pos + 2:self%pos + ES_FIELD))
       self%pos = self%pos + ES_FIELD
    end do
  end subroutine tb_put_es_row

  subroutine tb_line(self, text)
    !! Append text and a newline.
    class(text_buffer_t), intent(inout) :: self
    character(*), intent(in) :: text
    call self%put(text)
    call self%newline()
  end subroutine tb_line

  subroutine tb_newline(self)
    !! End the current line.
    class(text_buffer_t), intent(inout) :: self
    if (self%pos == BUFFER_BYTES) call flush_block(self)
    self%pos = self%pos + 1
    self%buf(self%pos:self%pos) = new_line('a')
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

end module superjoin_utils_text_buffer
