module test_text_rows_source
  !! A table for the test: item k's row is "row k" and, for every seventh
  !! item, nothing (rows skipped, as the listing's tables skip items of other
  !! kinds); with long rows, each row is padded with blanks to LONG_ROW
  !! characters (the memory buffer then fills its 1 MB block and keeps it).
  use superjoin_kinds, only: i8
  use superjoin_model_types, only: model_t
  use superjoin_model_results, only: results_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_rows, only: row_source_t
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_number_text, only: int_text, INT_TEXT_LEN
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none (type, external)
  private

  integer, parameter :: LONG_ROW = 700
    !! characters of a long row: a chunk's second half (2048 items, 6 of 7
    !! printed) then takes 1.2 MB, more than the memory buffer's 1 MB block

  logical, public :: seen_parallel = .false.
    !! a chunk kept in memory was formatted inside a parallel region (put_rows)
  integer(i8), public :: items_direct = 0
    !! items formatted into a buffer writing a file (only that buffer's thread counts them)
  integer(i8), public :: items_in_memory = 0
    !! items formatted into a buffer in memory (only that buffer's thread counts them)

  type, extends(row_source_t), public :: counting_rows_t
    !! The test's table (see the module).
     logical :: long = .false.   !! rows padded to LONG_ROW characters
   contains
     procedure :: put_rows => counting_put_rows
  end type counting_rows_t

  public :: row_text

  interface
     function omp_in_parallel() bind(c, name='omp_in_parallel') result(yes)
       !! libgomp's (the tests are not compiled with -fopenmp: no omp_lib module)
       import :: c_int
       integer(c_int) :: yes
     end function omp_in_parallel
  end interface

contains

  recursive subroutine counting_put_rows(self, tb, model, res, first, last)
    !! The rows of items first..last (recursive: it runs on two threads at
    !! once, and -fcheck=recursion says so of a procedure not marked so; the
    !! library's are, being compiled with -fopenmp). No function returning a deferred-length
    !! text is called here (row_text is for the expected text only): gfortran
    !! 12 keeps such a result's length in a static variable, which two threads
    !! share (output/rows says so to every table).
    class(counting_rows_t), intent(in) :: self
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    integer(i8) :: k
    character(len=INT_TEXT_LEN) :: digits
    integer :: n
    if (.false.) print *, model%controls%rigid, allocated(res%fields%u)   ! the interface's arguments, unused here
    ! only the thread of the chunk kept in memory writes the flag: no race
    if (tb%in_memory .and. omp_in_parallel() /= 0) seen_parallel = .true.
    if (tb%in_memory) then
       items_in_memory = items_in_memory + (last - first + 1)
    else
       items_direct = items_direct + (last - first + 1)
    end if
    do k = first, last
       if (mod(k, 7_i8) == 0) cycle
       call int_text(k, digits, n)
       call tb%put('row ')
       call tb%put(digits(1:n))
       if (self%long) call tb%put_blanks(LONG_ROW - 4 - n)
       call tb%newline()
    end do
  end subroutine counting_put_rows

  function row_text(k, long) result(text)
    !! The row of item k.
    integer(i8), intent(in) :: k
    logical, intent(in) :: long
    character(:), allocatable :: text
    text = 'row '//itoa(k)
    if (long) text = text//repeat(' ', LONG_ROW - len(text))
  end function row_text
end module test_text_rows_source

program test_text_rows
  !! The listing's tables formatted a range at a time (output/rows): every
  !! row once, in order, whatever the count against the chunk (one item, a
  !! chunk's worth and one more, many pairs and an odd remainder), with short
  !! rows and rows long enough that the memory buffer keeps a full block
  !! (1.2 MB of a chunk); that the chunks went to two threads exactly where a
  !! second may run; the text buffer in memory (open_memory, take) alone, and
  !! taken into a buffer in memory; owner_of with empty substructures. Run twice by ctest: as the machine allows (two threads
  !! where it has two CPUs) and under OMP_NUM_THREADS=1 (one thread), each
  !! against the same expected text.
  use superjoin_kinds, only: i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t
  use superjoin_model_results, only: results_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_utils_process, only: second_thread_allowed
  use superjoin_output_rows, only: write_rows, owner_of
  use superjoin_utils_strings, only: itoa
  use superjoin_testing, only: check, finish, temp_dir
  use test_text_rows_source, only: counting_rows_t, row_text, seen_parallel, items_direct, items_in_memory
  use, intrinsic :: iso_c_binding, only: c_int, c_long_long
  implicit none (type, external)

  interface   ! data_limit.c
     function sj_memory_checker() bind(c) result(yes)
       import :: c_int
       integer(c_int) :: yes
     end function sj_memory_checker
     function sj_data_limit_prepare() bind(c) result(status)
       import :: c_int
       integer(c_int) :: status
     end function sj_data_limit_prepare
     function sj_data_limit_set(headroom) bind(c) result(status)
       import :: c_int, c_long_long
       integer(c_long_long), value :: headroom
       integer(c_int) :: status
     end function sj_data_limit_set
     function sj_data_available(bytes) bind(c) result(yes)
       import :: c_int, c_long_long
       integer(c_long_long), value :: bytes
       integer(c_int) :: yes
     end function sj_data_available
     function sj_data_limit_restore() bind(c) result(status)
       import :: c_int
       integer(c_int) :: status
     end function sj_data_limit_restore
  end interface

  integer(c_long_long), parameter :: NO_ROOM = 256*1024
    !! headroom of the out-of-memory run where no 1 MB block can be had
  integer(c_long_long), parameter :: ONE_BLOCK_ROOM = 1536*1024
    !! headroom where one 1 MB block can be had, not a second
  integer(c_long_long), parameter :: PROBE_EXTRA = 512*1024
    !! a block this much larger than the headroom must be refused under the limit
  integer(i8), parameter :: OOM_COUNT = 9000
    !! long rows of the out-of-memory run: four pairs of chunks, each second chunk 1.2 MB

  integer(i8), parameter :: COUNTS(6) = [1_i8, 2048_i8, 2049_i8, 4097_i8, 20000_i8, 61_i8*2048 + 5]
  integer :: k, st
  character(len=8) :: env

  character(:), allocatable :: run   ! this run's files: the ctest runs may run at once

  run = merge('two', 'one', second_thread_allowed())
  call get_environment_variable('SJ_TEST_RUN', env, status=st)
  if (st == 0) run = run//'_'//trim(env)
  call get_environment_variable('SJ_TEST_OOM', env, status=st)
  if (st == 0 .and. env == 'yes') then
     call out_of_memory()
     deallocate (run)
     call finish()
     stop
  end if
  write (*, '(a,l1)') 'second thread allowed: ', second_thread_allowed()
  ! where the ctest says whether a second thread may run (SJ_EXPECT_SECOND_THREAD=yes or
  ! no: OMP_NUM_THREADS=1, a list whose first value is 1, one CPU under taskset)
  call get_environment_variable('SJ_EXPECT_SECOND_THREAD', env, status=st)
  if (st == 0) call check(second_thread_allowed() .eqv. (env == 'yes'), 'a second thread allowed: '// &
       merge('yes', 'no ', second_thread_allowed())//', expected: '//trim(env))
  do k = 1, size(COUNTS)
     call rows_in_order(COUNTS(k), .false.)
  end do
  call rows_in_order(9000_i8, .true.)
  ! the pairs of chunks are formatted on two threads exactly where a second may run
  call check(seen_parallel .eqv. second_thread_allowed(), 'rows formatted in a parallel region: '// &
       merge('yes', 'no ', seen_parallel)//', a second thread allowed: '//merge('yes', 'no ', second_thread_allowed()))
  call memory_buffer()
  call owners()
  deallocate (run)   ! LeakSanitizer counts a main program's allocatables held at the end
  call finish()

contains

  subroutine rows_in_order(count, long, headroom, what)
    !! write_rows of count items gives each kept row once, in order; with
    !! headroom, under a data limit of that many bytes beyond what the process
    !! holds (what names the case), the limit checked to have held.
    integer(i8), intent(in) :: count
    logical, intent(in) :: long
    integer(c_long_long), intent(in), optional :: headroom
    character(*), intent(in), optional :: what
    type(counting_rows_t) :: rows
    type(model_t) :: model
    type(results_t) :: res
    type(text_buffer_t), allocatable :: lu
    type(error_t), allocatable :: error
    character(:), allocatable :: path, got, want, label
    logical :: limited, held, restored
    rows%long = long
    path = temp_dir()//'/superjoin_test_text_rows_'//run//'.txt'
    want = expected(count, long)   ! before any limit
    allocate (lu)
    call lu%open(path, error)
    call check(.not. allocated(error), 'open '//path)
    call lu%line('head')
    label = ''
    if (present(headroom)) then
       label = what//': '
       limited = sj_data_limit_set(headroom) == 0
       held = .false.
       restored = .false.
       if (limited) then
          call write_rows(lu, rows, model, res, count)
          held = sj_data_available(headroom + PROBE_EXTRA) == 0
          restored = sj_data_limit_restore() == 0
       end if
       call check(limited .and. restored, label//'data limit set and restored')
       call check(held, label//'the data limit held')
    else
       call write_rows(lu, rows, model, res, count)
    end if
    call lu%line('tail')
    call commit(lu, path)
    got = file_text(path)
    if (got /= want) call show_difference(got, want)
    call check(got == want, label//'rows 1..'//itoa(int(count))//merge(' (long)', '       ', long)// &
         ' once each, in order ('//itoa(len(got))//' of '//itoa(len(want))//' characters)')
  end subroutine rows_in_order

  function expected(count, long) result(want)
    !! head, the rows of items 1..count but every seventh, tail.
    integer(i8), intent(in) :: count
    logical, intent(in) :: long
    character(:), allocatable :: want, row
    integer(i8) :: i, n
    allocate (character(len=count*720 + 20) :: want)   ! rows of at most LONG_ROW + 1
    want(1:5) = 'head'//new_line('a')
    n = 5
    do i = 1, count
       if (mod(i, 7_i8) == 0) cycle
       row = row_text(i, long)//new_line('a')
       want(n + 1:n + len(row)) = row
       n = n + len(row)
    end do
    want(n + 1:n + 5) = 'tail'//new_line('a')
    want = want(1:n + 5)
  end function expected

  subroutine show_difference(got, want)
    !! Where got first differs from want.
    character(*), intent(in) :: got, want
    integer :: i
    do i = 1, min(len(got), len(want))
       if (got(i:i) /= want(i:i)) exit
    end do
    write (*, '(a,i0,a)') 'first difference at character ', i, ':'
    write (*, '(a)') '  got:  '//got(max(1, i - 40):min(len(got), i + 40))
    write (*, '(a)') '  want: '//want(max(1, i - 40):min(len(want), i + 40))
  end subroutine show_difference

  subroutine memory_buffer()
    !! 2.5 MB into a buffer in memory (two full blocks kept and a part), taken
    !! into a file buffer; then another 2.5 MB taken first into a second
    !! buffer in memory and from there into the file buffer: the same text
    !! each time, each memory buffer empty after its take.
    type(text_buffer_t), allocatable :: lu, side, mid
    type(error_t), allocatable :: error
    character(:), allocatable :: path, piece, want
    integer :: i, j
    path = temp_dir()//'/superjoin_test_text_memory_'//run//'.txt'
    allocate (lu, side, mid)
    call lu%open(path, error)
    call mid%open_memory()
    want = ''
    do j = 1, 2
       call side%open_memory()
       allocate (character(len=25000*100) :: piece)
       do i = 1, 25000
          piece(100*i - 99:100*i) = repeat(achar(iachar('a') + mod(i + j, 26)), 99)//new_line('a')
       end do
       call side%put(piece)
       if (j == 1) then
          call lu%take(side)
       else
          call mid%take(side)
          call lu%take(mid)
          call check(mid%pos == 0 .and. mid%kept_len == 0, 'the second memory buffer is empty after take')
       end if
       call check(side%pos == 0 .and. side%kept_len == 0, 'the memory buffer is empty after take')
       want = want//piece
       deallocate (piece)
    end do
    call commit(lu, path)
    call check(file_text(path) == want, 'text taken from memory: 2 x 2.5 MB as put (directly, and through memory)')
    call check(.not. (side%failed .or. mid%failed), 'the memory buffers did not fail')
  end subroutine memory_buffer

  subroutine out_of_memory()
    !! Where memory runs out (SJ_TEST_OOM=yes; skipped, status 77, under a
    !! memory checker, or where the data limit cannot be set or does not hold):
    !! the listing's rows are still every row once, in order, when the second
    !! chunk's text cannot be kept (formatted again by the listing's thread)
    !! and when the memory buffer cannot have its block at all (one thread
    !! formats them all); a buffer in memory that runs out says so and gives
    !! nothing to take; a file buffer without its block is an error naming the
    !! file, which is not created.
    logical :: held
    if (sj_memory_checker() /= 0) call skip('a memory checker allocates here')
    if (sj_data_limit_prepare() /= 0) call skip('malloc''s thresholds cannot be set')
    if (sj_data_limit_set(NO_ROOM) /= 0) call skip('the data limit cannot be set')
    held = sj_data_available(NO_ROOM + PROBE_EXTRA) == 0
    call check(sj_data_limit_restore() == 0, 'data limit restored')
    if (.not. held) call skip('the data limit does not hold')
    call rows_in_order(OOM_COUNT, .true.)   ! the second thread started, as it would be
    if (second_thread_allowed()) then
       items_direct = 0
       items_in_memory = 0
       call rows_in_order(OOM_COUNT, .true., ONE_BLOCK_ROOM, 'the second chunk''s text not kept')
       call check(items_in_memory > 0 .and. items_direct == OOM_COUNT, &
            'the second chunks formatted in memory, lost, and again into the listing: '// &
            itoa(int(items_in_memory))//' and '//itoa(int(items_direct))//' items')
    end if
    items_direct = 0
    items_in_memory = 0
    call rows_in_order(OOM_COUNT, .true., NO_ROOM, 'no memory buffer')
    call check(items_in_memory == 0 .and. items_direct == OOM_COUNT, 'one thread formats every item once: '// &
         itoa(int(items_in_memory))//' and '//itoa(int(items_direct))//' items')
    call memory_buffer_short()
    call open_short()
  end subroutine out_of_memory

  subroutine skip(why)
    character(*), intent(in) :: why
    write (*, '(a)') 'skipped: '//why
    if (allocated(run)) deallocate (run)   ! LeakSanitizer counts a main program's allocatables held at the end
    stop 77
  end subroutine skip

  subroutine memory_buffer_short()
    !! A buffer in memory with its block and no room to keep it when full:
    !! failed, with its reason; a file buffer takes nothing from it.
    type(text_buffer_t), allocatable :: lu, side
    type(error_t), allocatable :: error
    character(:), allocatable :: path, piece
    logical :: limited, restored
    path = temp_dir()//'/superjoin_test_text_short_'//run//'.txt'
    allocate (lu, side)
    call lu%open(path, error)
    call lu%line('head')
    call side%open_memory()
    call check(.not. side%failed, 'a buffer in memory with room for its block')
    piece = repeat('x', 1536*1024)
    limited = sj_data_limit_set(NO_ROOM) == 0
    restored = .false.
    if (limited) then
       call side%put(piece)
       restored = sj_data_limit_restore() == 0
    end if
    call check(limited .and. restored, 'buffer in memory: data limit set and restored')
    call check(side%failed .and. side%why == 'out of memory for the text kept in memory', &
         'a buffer in memory without room to keep its block failed: '//trim(side%why))
    call lu%take(side)
    call check(side%pos == 0 .and. side%kept_len == 0, 'the failed buffer is empty after take')
    call commit(lu, path)
    call check(file_text(path) == 'head'//new_line('a'), 'nothing taken from the failed buffer')
  end subroutine memory_buffer_short

  subroutine open_short()
    !! A file buffer opened where its block cannot be had: an error naming
    !! the file, which is not created.
    type(text_buffer_t), allocatable :: lu
    type(error_t), allocatable :: error
    character(:), allocatable :: path
    logical :: limited, restored, exists
    integer :: unit
    path = temp_dir()//'/superjoin_test_text_open_'//run//'.txt'
    open (newunit=unit, file=path, status='replace')   ! none left by an earlier run
    close (unit, status='delete')
    allocate (lu)
    limited = sj_data_limit_set(NO_ROOM) == 0
    restored = .false.
    if (limited) then
       call lu%open(path, error)
       restored = sj_data_limit_restore() == 0
    end if
    call check(limited .and. restored, 'open: data limit set and restored')
    call check(allocated(error), 'open without memory for the block: an error')
    if (allocated(error)) call check(error%message == 'error: out of memory for the output buffer of '//path, &
         'the error names the file: '//error%message)
    inquire (file=path, exist=exists)
    call check(.not. exists, 'the file is not created')
  end subroutine open_short

  subroutine owners()
    !! owner_of over offsets with empty substructures (2 and 4 have no items).
    integer(i8), parameter :: OFF(6) = [0_i8, 3_i8, 3_i8, 5_i8, 5_i8, 9_i8]
    integer, parameter :: WANT(9) = [1, 1, 1, 3, 3, 5, 5, 5, 5]
    integer(i8) :: item
    logical :: ok
    ok = .true.
    do item = 1, 9
       ok = ok .and. owner_of(OFF, item) == WANT(item)
    end do
    call check(ok, 'owner_of: the substructure of each item, empty ones skipped')
  end subroutine owners

  subroutine commit(lu, path)
    type(text_buffer_t), intent(inout) :: lu
    character(*), intent(in) :: path
    logical :: ok
    call lu%close(ok)
    call check(ok, 'close '//path)
  end subroutine commit

  function file_text(path) result(text)
    !! The whole file as one text.
    character(*), intent(in) :: path
    character(:), allocatable :: text
    integer :: unit, size_bytes
    inquire (file=path, size=size_bytes)
    allocate (character(len=max(size_bytes, 0)) :: text)
    open (newunit=unit, file=path, access='stream', form='unformatted', action='read', status='old')
    if (size_bytes > 0) read (unit) text
    close (unit, status='delete')
  end function file_text
end program test_text_rows
