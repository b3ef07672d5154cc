program test_deck_include
  !! Unit tests of the deck reader on files: *INCLUDE (relative paths, data
  !! lines continued across files, nesting limit, cycles, missing files) and
  !! files with CR LF line ends. Files are written under a fresh directory in /tmp.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_model_types, only: model_t, find_node
  use superjoin_deck_reader, only: read_deck, read_deck_string
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  character, parameter :: LF = achar(10), CR = achar(13)
  integer, parameter :: DEPTH_CHAIN = 18
  character(:), allocatable :: dir
  character(*), parameter :: MAT = '*MATERIAL, NAME=STEEL'//LF//'*ELASTIC'//LF//'2.0e11, 0.3'//LF

  call make_dir()
  call test_nested()
  call test_errors_in_includes()
  call test_depth()
  call test_crlf_file()
  call execute_command_line('rm -rf '//dir)
  deallocate (dir)
  call finish()

contains

  subroutine make_dir()
    real :: r
    integer :: values(8), stat
    character(len=32) :: buf
    call random_init(.false., .false.)
    call random_number(r)
    call date_and_time(values=values)
    write (buf, '(i0,a,i0)') int(r*1.0e8), '_', values(7)*1000 + values(8)
    dir = '/tmp/superjoin_test_deck_'//trim(buf)
    call execute_command_line('mkdir -p '//dir//'/sub', exitstat=stat)
    call check(stat == 0, 'temporary directory created')
  end subroutine make_dir

  subroutine write_file(path, text)
    !! Write text to a file byte for byte.
    character(*), intent(in) :: path, text
    integer :: u
    open (newunit=u, file=path, access='stream', form='unformatted', status='replace', action='write')
    write (u) text
    close (u)
  end subroutine write_file

  subroutine expect_error(path, expect, what)
    character(*), intent(in) :: path, expect, what
    type(model_t) :: m
    type(error_t), allocatable :: error
    logical :: ok
    call read_deck(path, m, error)
    ok = allocated(error)
    if (ok) ok = index(error%message, expect) > 0 .and. error%code == EXIT_DECK
    call check(ok, what//': error "'//expect//'"')
    if (.not. ok) then
       if (allocated(error)) then
          write (*, '(a)') '  got: '//error%message
       else
          write (*, '(a)') '  got no error'
       end if
    end if
  end subroutine expect_error

  subroutine test_nested()
    type(model_t) :: m
    type(error_t), allocatable :: error
    integer(ip) :: k
    call write_file(dir//'/main.deck', '*HEADING'//LF//'main'//LF//'*INCLUDE, INPUT=mat.inc'//LF// &
         '*NODE'//LF//'*INCLUDE, INPUT="sub/nodes.inc"'//LF//'3, 2, 0'//LF// &
         '*ELEMENT, TYPE=T2D2, ELSET=E'//LF//'1, 1, 2'//LF//'2, 2, 3'//LF// &
         '*INCLUDE, INPUT=./sub/../sec.inc'//LF//'*include, input=sec2.inc'//LF)
    call write_file(dir//'/mat.inc', MAT)
    call write_file(dir//'/sub/nodes.inc', '1, 0, 0'//LF//'** comment'//LF//'*INCLUDE, INPUT=more.inc'//LF)
    call write_file(dir//'/sub/more.inc', '2, 1, 0')
    call write_file(dir//'/sec.inc', '*SOLID SECTION, ELSET=E, MATERIAL=STEEL'//LF//'1.0'//LF)
    call write_file(dir//'/sec2.inc', '*CLOAD'//LF//'3, 1, 5'//LF)
    call read_deck(dir//'/main.deck', m, error)
    call check(.not. allocated(error), 'nested includes read')
    if (allocated(error)) then
       write (*, '(a)') error%message
       return
    end if
    call check(size(m%files) == 6, 'every file listed once')
    call check(m%files(1)%s == dir//'/main.deck', 'deck path as given')
    call check(m%files(2)%s == dir//'/mat.inc', 'include relative to the deck')
    call check(m%files(3)%s == dir//'/sub/nodes.inc', 'quoted include path')
    call check(m%files(4)%s == dir//'/sub/more.inc', 'include relative to the including file')
    call check(m%files(5)%s == dir//'/sec.inc', 'normalized include path')
    call check(m%subs(1)%nnode == 3, '*NODE data continued across includes')
    k = find_node(m%subs(1), 2_ip)
    call check(k > 0, 'node 2 exists')
    if (k > 0) call check(m%subs(1)%x(1, k) == 1.0_wp, 'node 2 coordinates')
    call check(m%subs(1)%elem_section(1) == 1 .and. m%subs(1)%elem_section(2) == 1, 'section from an include')
    call check(m%materials(1)%loc%file == 2 .and. m%materials(1)%loc%line == 1, 'material location')
    call check(size(m%steps) == 1, 'loads from an include')
    if (size(m%steps) == 1) call check(m%steps(1)%cloads(1)%loc%file == 6 .and. &
         m%steps(1)%cloads(1)%loc%line == 2, 'load location in an include')
    ! the same file included twice is not a cycle
    call write_file(dir//'/twice.deck', '*NODE'//LF//'1, 0, 0'//LF//'*INCLUDE, INPUT=mat.inc'//LF// &
         '*MATERIAL, NAME=OTHER'//LF//'*ELASTIC'//LF//'1, 0'//LF//'*INCLUDE, INPUT=sub/../twice.inc'//LF// &
         '*INCLUDE, INPUT=twice.inc'//LF)
    call write_file(dir//'/twice.inc', '** nothing but a comment'//LF)
    call read_deck(dir//'/twice.deck', m, error)
    call check(.not. allocated(error), 'same file included twice')
    if (.not. allocated(error)) call check(size(m%files) == 3, 'a file included twice is listed once')
    ! read_deck_string resolves includes relative to the directory of `name`
    call read_deck_string('*NODE'//LF//'9, 0, 0'//LF//'*INCLUDE, INPUT=mat.inc'//LF, dir//'/virtual.deck', m, error)
    call check(.not. allocated(error), 'include from a deck in memory')
    if (.not. allocated(error)) call check(size(m%materials) == 1, 'material included from memory deck')
  end subroutine test_nested

  subroutine test_errors_in_includes()
    call write_file(dir//'/bad.inc', '*NODE'//LF//'1, 0, x'//LF)
    call write_file(dir//'/with_bad.deck', '** header'//LF//'*INCLUDE, INPUT=bad.inc'//LF)
    call expect_error(dir//'/with_bad.deck', dir//'/bad.inc:2: error: invalid real ''x''', 'error inside an include')

    call write_file(dir//'/missing.deck', '*NODE'//LF//'1, 0, 0'//LF//'*INCLUDE, INPUT=nope.inc'//LF)
    call expect_error(dir//'/missing.deck', dir//'/missing.deck:3: error: cannot open include file '''// &
         dir//'/nope.inc''', 'missing include')

    call write_file(dir//'/cycle.deck', '*NODE'//LF//'1, 0, 0'//LF//'*INCLUDE, INPUT=a.inc'//LF)
    call write_file(dir//'/a.inc', '** a'//LF//'*INCLUDE, INPUT=sub/b.inc'//LF)
    call write_file(dir//'/sub/b.inc', '*INCLUDE, INPUT=../a.inc'//LF)
    call expect_error(dir//'/cycle.deck', dir//'/sub/b.inc:1: error: include cycle: '//dir//'/a.inc -> '// &
         dir//'/sub/b.inc -> '//dir//'/a.inc', 'include cycle')

    call write_file(dir//'/self.deck', '*NODE'//LF//'1, 0, 0'//LF//'*INCLUDE, INPUT=self.deck'//LF)
    call expect_error(dir//'/self.deck', 'self.deck:3: error: include cycle: '//dir//'/self.deck -> '// &
         dir//'/self.deck', 'deck including itself')

    call write_file(dir//'/noinput.deck', '*NODE'//LF//'1, 0, 0'//LF//'*INCLUDE'//LF)
    call expect_error(dir//'/noinput.deck', 'noinput.deck:3: error: *INCLUDE needs parameter INPUT=', &
         'include without INPUT')
  end subroutine test_errors_in_includes

  subroutine test_depth()
    integer :: i
    character(len=16) :: a, b
    call write_file(dir//'/deep.deck', '*NODE'//LF//'1, 0, 0'//LF//'*INCLUDE, INPUT=d1.inc'//LF)
    do i = 1, DEPTH_CHAIN
       write (a, '(a,i0,a)') 'd', i, '.inc'
       write (b, '(a,i0,a)') 'd', i + 1, '.inc'
       call write_file(dir//'/'//trim(a), '** level'//LF//'*INCLUDE, INPUT='//trim(b)//LF)
    end do
    call write_file(dir//'/d19.inc', '** bottom'//LF)
    call expect_error(dir//'/deep.deck', dir//'/d16.inc:2: error: includes nested deeper than 16 levels', &
         'include depth limit')
    ! 16 levels are fine
    call write_file(dir//'/d16.inc', '** level 16: the last one'//LF)
    block
      type(model_t) :: m
      type(error_t), allocatable :: error
      call read_deck(dir//'/deep.deck', m, error)
      call check(.not. allocated(error), '16 nested includes are allowed')
      if (.not. allocated(error)) call check(size(m%files) == 17, '17 files')
    end block
  end subroutine test_depth

  subroutine test_crlf_file()
    type(model_t) :: m
    type(error_t), allocatable :: error
    call write_file(dir//'/crlf.deck', '*HEADING'//CR//LF//'Title'//CR//LF//'*NODE'//CR//LF//'1, 0, 0'//CR//LF// &
         '2, 1.5, 0'//CR//LF//'*NSET, NSET=A'//CR//LF//'1, 2,'//CR//LF)
    call read_deck(dir//'/crlf.deck', m, error)
    call check(.not. allocated(error), 'CR LF file')
    if (allocated(error)) return
    call check(m%heading(1)%s == 'Title', 'CR removed from heading')
    call check(m%subs(1)%x(1, 2) == 1.5_wp, 'CR LF coordinates')
    call check(size(m%subs(1)%nsets(1)%items) == 2, 'CR LF set line')
    call write_file(dir//'/empty.deck', '')
    call expect_error(dir//'/empty.deck', 'empty.deck:1: error: the deck defines no nodes', 'empty file')
  end subroutine test_crlf_file
end program test_deck_include
