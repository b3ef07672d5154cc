program test_deck
  !! Unit tests of the deck reader: lexer, token conversion, cards, sets,
  !! sections, contacts, supports, steps and error reporting.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t, EXIT_DECK, EXIT_IO
  use superjoin_model_types, only: model_t, find_node, find_elem, LINK_NONE, LINK_FINITE, LINK_RIGID, &
       SEC_SOLID, SEC_BEAM, SEC_SHELL, ET_T2D2, DLOAD_PY, DLOAD_P, &
       FORM_PENALTY, RIGID_LARGE, FORM_TRANSFORM, RIGID_ELIMINATE
  use superjoin_deck_reader, only: read_deck, read_deck_string
  use superjoin_deck_lexer, only: parse_real, parse_id, is_name, TOK_OK, TOK_INVALID, TOK_RANGE, &
       TOK_NONFINITE
  use superjoin_testing, only: check, check_close, finish
  implicit none (type, external)

  character, parameter :: LF = achar(10), CR = achar(13)
  character(*), parameter :: MAT = '*MATERIAL, NAME=STEEL'//LF//'*ELASTIC'//LF//'2.0e11, 0.3'//LF
  integer, parameter :: L = 100

  call test_reals()
  call test_ids_names()
  call test_lexical()
  call test_long_line()
  call test_nodes_elements()
  call test_sets()
  call test_sections()
  call test_orientation()
  call test_contacts()
  call test_supports()
  call test_steps()
  call test_controls()
  call test_errors()
  call test_error_cap()
  call finish()

contains

  ! ------------------------------------------------------------------ helpers

  function join(lines) result(text)
    !! Lines joined with LF (trailing blanks of each line dropped).
    character(*), intent(in) :: lines(:)
    character(:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(lines)
       text = text//trim(lines(i))//LF
    end do
  end function join

  subroutine read_ok(text, model, what)
    character(*), intent(in) :: text, what
    type(model_t), intent(out) :: model
    type(error_t), allocatable :: error
    call read_deck_string(text, 'inline.deck', model, error)
    call check(.not. allocated(error), what//': reads without error')
    if (allocated(error)) write (*, '(a)') '  got: '//error%message
  end subroutine read_ok

  subroutine read_bad(text, expect, what)
    !! Expect an error whose message contains `expect`.
    character(*), intent(in) :: text, expect, what
    type(model_t) :: model
    type(error_t), allocatable :: error
    logical :: ok
    call read_deck_string(text, 'inline.deck', model, error)
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
  end subroutine read_bad

  integer function count_lines(s) result(n)
    character(*), intent(in) :: s
    integer :: i
    n = 1
    do i = 1, len(s)
       if (s(i:i) == LF) n = n + 1
    end do
  end function count_lines

  integer function sub_of(model, name) result(k)
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    do k = 1, size(model%subs)
       if (model%subs(k)%name == name) return
    end do
    k = 0
  end function sub_of

  integer function uid(model, isub, k)
    !! User id of local node k of substructure isub.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: k
    uid = model%subs(isub)%node_id(k)
  end function uid

  ! ------------------------------------------------------------------ tokens

  subroutine test_reals()
    real(wp) :: x
    integer :: stat
    call pr('1', 1.0_wp)
    call pr('-.5', -0.5_wp)
    call pr('+.5', 0.5_wp)
    call pr('2.1e11', 2.1e11_wp)
    call pr('2.1D11', 2.1e11_wp)
    call pr('2.1d-3', 2.1e-3_wp)
    call pr('1.e3', 1000.0_wp)
    call pr('1.', 1.0_wp)
    call pr('0.1', 0.1_wp)
    call pr('-0', 0.0_wp)
    call pr('1E+2', 100.0_wp)
    call pr('0.3333333333333333', 0.3333333333333333_wp)
    call pr('1.2345678901234567e-5', 1.2345678901234567e-5_wp)
    call pr('123456789012345678901234567890', 123456789012345678901234567890.0_wp)
    call pr('1e300', 1.0e300_wp)
    call pr('1.5e-310', 1.5e-310_wp)
    call pr('1e-999', 0.0_wp)
    call pr('000123.4500', 123.45_wp)
    call pr('0.000000000000000000000000001', 1.0e-27_wp)
    call bad_real('NaN', TOK_NONFINITE)
    call bad_real('-Inf', TOK_NONFINITE)
    call bad_real('infinity', TOK_NONFINITE)
    call bad_real('1e999', TOK_RANGE)
    call bad_real('-2e308', TOK_RANGE)
    call bad_real('1.2.3', TOK_INVALID)
    call bad_real('abc', TOK_INVALID)
    call bad_real('1e', TOK_INVALID)
    call bad_real('1e+', TOK_INVALID)
    call bad_real('', TOK_INVALID)
    call bad_real('.', TOK_INVALID)
    call bad_real('-', TOK_INVALID)
    call bad_real('e5', TOK_INVALID)
    call bad_real('1+5', TOK_INVALID)
    call bad_real('0x10', TOK_INVALID)
    call bad_real('1 2', TOK_INVALID)
    call bad_real('1.0q5', TOK_INVALID)
    call parse_real('1.7e308', x, stat)
    call check(stat == TOK_OK .and. x > 1.0e308_wp, 'real 1.7e308 accepted')
  end subroutine test_reals

  subroutine pr(s, want)
    character(*), intent(in) :: s
    real(wp), intent(in) :: want
    real(wp) :: x
    integer :: stat
    call parse_real(s, x, stat)
    call check(stat == TOK_OK, 'real '''//s//''' accepted')
    call check(x == want, 'real '''//s//''' exact value')
  end subroutine pr

  subroutine bad_real(s, want)
    character(*), intent(in) :: s
    integer, intent(in) :: want
    real(wp) :: x
    integer :: stat
    call parse_real(s, x, stat)
    call check(stat == want, 'real '''//s//''' rejected with the right status')
  end subroutine bad_real

  subroutine test_ids_names()
    call pid('1', 1_ip)
    call pid('007', 7_ip)
    call pid('2147483647', huge(1_ip))
    call bad_id('0', TOK_RANGE)
    call bad_id('0000', TOK_RANGE)
    call bad_id('2147483648', TOK_RANGE)
    call bad_id('99999999999999999999', TOK_RANGE)
    call bad_id('-3', TOK_INVALID)
    call bad_id('+3', TOK_INVALID)
    call bad_id('1.5', TOK_INVALID)
    call bad_id('', TOK_INVALID)
    call bad_id('1e3', TOK_INVALID)
    call check(is_name('Edge_1-b'), 'name with letters, digits, _ and -')
    call check(.not. is_name('a.b'), 'name with a dot rejected')
    call check(.not. is_name(''), 'empty name rejected')
    call check(.not. is_name('a b'), 'name with a blank rejected')
  end subroutine test_ids_names

  subroutine pid(s, want)
    character(*), intent(in) :: s
    integer(ip), intent(in) :: want
    integer(ip) :: id
    integer :: stat
    call parse_id(s, id, stat)
    call check(stat == TOK_OK .and. id == want, 'id '''//s//''' accepted')
  end subroutine pid

  subroutine bad_id(s, want)
    character(*), intent(in) :: s
    integer, intent(in) :: want
    integer(ip) :: id
    integer :: stat
    call parse_id(s, id, stat)
    call check(stat == want, 'id '''//s//''' rejected with the right status')
  end subroutine bad_id

  ! ------------------------------------------------------------------ lexical rules

  subroutine test_lexical()
    type(model_t) :: m
    character(:), allocatable :: text
    character, parameter :: TAB = achar(9)
    ! comments, blank lines, case, blanks and tabs, CR LF, trailing commas, BOM
    text = char(239)//char(187)//char(191)//'** a comment'//CR//LF// &
         '*heading'//CR//LF//'  Mixed Case Title, kept verbatim'//CR//LF// &
         CR//LF//'   '//CR//LF// &
         '*Material,  name = Steel'//CR//LF//'*elastic'//CR//LF//' 2.0E11 ,'//TAB//'0.3 '//CR//LF// &
         '** another comment'//LF// &
         '*node'//LF//'1,0,0'//LF//' 2 , 1.0 , 0.0 , '//LF// &
         '*element , type = t2d2 , elset = bars'//LF//'1, 1, 2,'//LF// &
         '  *Solid   Section, Elset=BARS, material=steel'//LF//'1.0e-4'//LF
    call read_ok(text, m, 'lexical rules')
    if (size(m%subs) /= 1) return
    call check(size(m%heading) == 1, 'one heading line')
    if (size(m%heading) == 1) call check(m%heading(1)%s == '  Mixed Case Title, kept verbatim', &
         'heading verbatim')
    call check(m%materials(1)%name == 'STEEL', 'names upper-cased')
    call check(m%materials(1)%has_elastic .and. m%materials(1)%e == 2.0e11_wp .and. &
         m%materials(1)%nu == 0.3_wp, 'elastic constants')
    call check(m%subs(1)%name == 'MAIN', 'implicit substructure MAIN')
    call check(m%subs(1)%nnode == 2 .and. m%subs(1)%nelem == 1, 'node and element counts')
    call check(m%subs(1)%elem_type(1) == ET_T2D2, 'element type case-insensitive')
    call check(m%subs(1)%elem_section(1) == 1, 'section assigned')
    call check(m%subs(1)%elsets(1)%name == 'BARS', 'elset name upper-cased')
    call check(size(m%files) == 1, 'one file')
    if (size(m%files) == 1) call check(m%files(1)%s == 'inline.deck', 'file name kept')
    call check(m%subs(1)%elem_loc(1)%line == 14 .and. m%subs(1)%elem_loc(1)%file == 1, 'element source line')

    ! lone CR line ends
    text = MAT//'*NODE'//CR//'1, 0, 0'//CR//'2, 1, 0'//CR
    call read_ok(text, m, 'lone CR line ends')
    if (size(m%subs) == 1) call check(m%subs(1)%nnode == 2, 'lone CR: two nodes')
    ! no final newline
    call read_ok('*NODE'//LF//'5, 1, 2, 3', m, 'no final newline')
    if (size(m%subs) == 1) call check_close(m%subs(1)%x(3, 1), 3.0_wp, 0.0_wp, 'z from last line')
    ! z defaults to 0
    call read_ok('*NODE'//LF//'5, 1, 2', m, 'z default')
    if (size(m%subs) == 1) call check(all(m%subs(1)%x(:, 1) == [1.0_wp, 2.0_wp, 0.0_wp]), 'z defaults to 0')
  end subroutine test_lexical

  subroutine test_long_line()
    type(model_t) :: m
    character(:), allocatable :: text, nodes, set
    integer :: i
    integer, parameter :: N = 20000
    character(len=12) :: buf
    integer :: nn, ns
    ! a 150 kB set line and a 4 MB heading line, built in buffers (no quadratic concatenation)
    allocate (character(len=32*N) :: nodes, set)
    nn = 0
    ns = 0
    call put(nodes, nn, '*NODE'//LF)
    do i = 1, N
       write (buf, '(i0)') i
       call put(nodes, nn, trim(buf)//', '//trim(buf)//'.0, 0'//LF)
       call put(set, ns, trim(buf)//', ')
    end do
    text = '*HEADING'//LF//repeat('x', 4*1024*1024)//LF//nodes(1:nn)//'*NSET, NSET=ALL'//LF//set(1:ns)//LF
    call read_ok(text, m, 'long lines')
    if (size(m%subs) /= 1) return
    call check(len(m%heading(1)%s) == 4*1024*1024, 'long heading line kept')
    call check(size(m%subs(1)%nsets(1)%items) == N, 'long set line: all ids')
  end subroutine test_long_line

  subroutine put(buffer, n, s)
    !! Append s at position n of a preallocated buffer.
    character(*), intent(inout) :: buffer
    integer, intent(inout) :: n
    character(*), intent(in) :: s
    buffer(n + 1:n + len(s)) = s
    n = n + len(s)
  end subroutine put

  ! ------------------------------------------------------------------ nodes and elements

  subroutine test_nodes_elements()
    type(model_t) :: m
    integer(ip) :: k
    ! sparse and unsorted ids, elements before their nodes
    call read_ok(join([character(L) :: MAT, '*ELEMENT, TYPE=T2D2, ELSET=E', '10, 2147483647, 5', &
         '3, 5, 900000000', '*SOLID SECTION, ELSET=E, MATERIAL=STEEL', '1.0', '*NODE', &
         '900000000, 2, 0', '5, 1, 0', '2147483647, 0, 0']), m, 'sparse ids')
    if (size(m%subs) /= 1) return
    associate (s => m%subs(1))
      call check(all(s%node_order == [2, 1, 3]), 'node_order sorts ids')
      call check(all(s%elem_order == [2, 1]), 'elem_order sorts ids')
      k = find_node(s, 2147483647_ip)
      call check(k == 3, 'find_node of 2**31-1')
      call check(find_node(s, 6_ip) == 0, 'find_node of a missing id')
      call check(find_elem(s, 3_ip) == 2, 'find_elem')
      call check(all(s%elem_nodes(1:2, 1) == [3, 2]), 'element nodes resolved to local indices')
      call check(all(s%elem_nodes(3:, 1) == 0), 'unused node slots are 0')
    end associate
    ! the implicit MAIN appears only when used
    call read_ok(join([character(L) :: '*SUBSTRUCTURE, NAME=A', '*NODE', '1, 0, 0', '*END SUBSTRUCTURE', &
         '*SUPPORT', 'A.1, 1, 2']), m, 'no MAIN')
    call check(size(m%subs) == 1, 'only the declared substructure')
    ! *NODE, NSET=
    call read_ok(join([character(L) :: '*NODE, NSET=ALL', '1, 0, 0', '2, 1, 0', '*NODE', '3, 2, 0', &
         '*NODE, NSET=ALL', '4, 3, 0']), m, '*NODE, NSET=')
    if (size(m%subs) == 1) call check(all(m%subs(1)%nsets(1)%items == [1, 2, 4]), 'NSET= on *NODE')
  end subroutine test_nodes_elements

  ! ------------------------------------------------------------------ sets

  subroutine test_sets()
    type(model_t) :: m
    integer :: k
    call read_ok(join([character(L) :: '*NODE', '1,0,0', '2,0,0', '3,0,0', '4,0,0', '5,0,0', '7,0,0', &
         '10,0,0', '1000000000,0,0', &
         '*NSET, NSET=G, GENERATE', '1, 10, 3', &
         '*NSET, NSET=SPARSE, GENERATE', '2, 2147483647, 1', '*NSET, NSET=ODD, GENERATE', '1, 10, 2', &
         '*NSET, NSET=A', '5, 3', '*NSET, NSET=B', '1, A, 3, 2,', '*NSET, NSET=a', '7', &
         '*NSET, NSET=C, UNSORTED', 'B, G', '*NSET, nset=EMPTYREF', 'D', '*NSET, NSET=D', '10', &
         '*ELEMENT, TYPE=T2D2, ELSET=E1', '1, 1, 2', '2, 2, 3', '*ELEMENT, TYPE=T2D2', '3, 3, 4', &
         '*ELSET, ELSET=E1', '3', '*ELSET, ELSET=GE, GENERATE', '1, 3', &
         '*SOLID SECTION, ELSET=E1, MATERIAL=STEEL', '1.0', MAT]), m, 'sets')
    if (size(m%subs) /= 1) return
    associate (s => m%subs(1))
      k = set_index(m, 'G')
      if (k > 0) call check(all(uids(m, s%nsets(k)%items) == [1, 4, 7, 10]), 'GENERATE with increment')
      k = set_index(m, 'SPARSE')
      if (k > 0) call check(all(uids(m, s%nsets(k)%items) == [2, 3, 4, 5, 7, 10, 1000000000]), &
           'huge sparse GENERATE range takes the existing ids')
      if (k > 0) call check(allocated(s%nsets(k)%print_ranges), 'huge sparse GENERATE range: .dat rows kept')
      if (k > 0 .and. allocated(s%nsets(k)%print_ranges)) call check(all(shape(s%nsets(k)%print_ranges) == [3, 1]) &
           .and. all(s%nsets(k)%print_ranges(:, 1) == [2_ip, 1000000000_ip, 1_ip]), &
           'huge sparse GENERATE range: .dat rows as one range up to the largest id, not expanded')
      k = set_index(m, 'ODD')
      if (k > 0) call check(all(uids(m, s%nsets(k)%items) == [1, 3, 5, 7]), 'GENERATE with gaps: the defined ids')
      if (k > 0) call check(allocated(s%nsets(k)%print_ranges), 'GENERATE with gaps: .dat rows kept')
      if (k > 0 .and. allocated(s%nsets(k)%print_ranges)) call check(all(shape(s%nsets(k)%print_ranges) == [3, 1]) &
           .and. all(s%nsets(k)%print_ranges(:, 1) == [1_ip, 10_ip, 2_ip]), 'GENERATE with gaps: .dat rows 1, 3, .., 9')
      k = set_index(m, 'A')
      if (k > 0) call check(all(uids(m, s%nsets(k)%items) == [5, 3, 7]), 'set extended by a second card')
      k = set_index(m, 'B')
      if (k > 0) call check(all(uids(m, s%nsets(k)%items) == [1, 5, 3, 7, 2]), &
           'set reference inside a set, repeats dropped, order of definition')
      k = set_index(m, 'C')
      if (k > 0) call check(all(uids(m, s%nsets(k)%items) == [1, 5, 3, 7, 2, 4, 10]), 'sets of sets')
      k = set_index(m, 'EMPTYREF')
      if (k > 0) call check(all(uids(m, s%nsets(k)%items) == [10]), 'reference to a set defined later')
      call check(size(s%elsets) == 2, 'two element sets')
      call check(all(s%elsets(1)%items == [1, 2, 3]), 'ELSET= on *ELEMENT extended by *ELSET')
      call check(all(s%elsets(2)%items == [1, 2, 3]), 'element GENERATE')
    end associate
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*NSET, NSET=A', 'B', '*NSET, NSET=B', 'A']), &
         'cycle', 'set reference cycle')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*NSET, NSET=A', '1, 2']), &
         'inline.deck:4: error: node set A: undefined node 2', 'undefined node in a set')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*NSET, NSET=A', 'NOPE']), &
         'inline.deck:4: error: node set A refers to unknown node set NOPE', 'unknown set in a set')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*NSET, NSET=A, GENERATE', '5, 2']), &
         'inline.deck:4: error: GENERATE range 5 to 2', 'GENERATE first after last')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*NSET, NSET=A, GENERATE', '5, 9, 2']), &
         'matches no defined id', 'GENERATE matching nothing')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*NSET, NSET=A', '1, x.y']), &
         'inline.deck:4: error: invalid entry ''x.y''', 'bad set entry')
  end subroutine test_sets

  integer function set_index(m, name) result(k)
    type(model_t), intent(in) :: m
    character(*), intent(in) :: name
    do k = 1, size(m%subs(1)%nsets)
       if (m%subs(1)%nsets(k)%name == name) return
    end do
    call check(.false., 'set '//name//' exists')
    k = 0
  end function set_index

  function uids(m, items) result(ids)
    type(model_t), intent(in) :: m
    integer(ip), intent(in) :: items(:)
    integer(ip) :: ids(size(items))
    ids = m%subs(1)%node_id(items)
  end function uids

  ! ------------------------------------------------------------------ sections

  subroutine test_sections()
    type(model_t) :: m
    type(error_t), allocatable :: error
    call read_ok(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '3,1,1', '4,0,1', &
         '*ELEMENT, TYPE=B23, ELSET=B2', '1, 1, 2', '*ELEMENT, TYPE=B33, ELSET=B3', '2, 2, 3', &
         '*ELEMENT, TYPE=CPS4, ELSET=P', '3, 1, 2, 3, 4', '*ELEMENT, TYPE=S4, ELSET=SH', '4, 1, 2, 3, 4', &
         '*ELEMENT, TYPE=T3D2, ELSET=T', '5, 1, 3', &
         '*BEAM SECTION, ELSET=B2, MATERIAL=STEEL, SECTION=GENERAL', '1e-2, 2e-5', &
         '*BEAM SECTION, ELSET=B3, MATERIAL=STEEL', '1e-2, 2e-5, 3e-5, 4e-5', '0, 1, 0', &
         '*SOLID SECTION, ELSET=P, MATERIAL=STEEL', '0.01', '*SHELL SECTION, ELSET=SH, MATERIAL=STEEL', '0.02', &
         '*SOLID SECTION, ELSET=T, MATERIAL=STEEL', '5e-4']), m, 'sections')
    if (size(m%subs) /= 1) return
    associate (s => m%subs(1))
      call check(all(s%elem_section == [1, 2, 3, 4, 5]), 'element to section')
      call check(s%sections(1)%kind == SEC_BEAM .and. s%sections(1)%area == 1.0e-2_wp .and. &
           s%sections(1)%iz == 2.0e-5_wp .and. s%sections(1)%iy == 0.0_wp, '2D beam: I in iz')
      call check(.not. s%sections(1)%has_v, '2D beam without v')
      call check(s%sections(2)%iy == 2.0e-5_wp .and. s%sections(2)%iz == 3.0e-5_wp .and. &
           s%sections(2)%j == 4.0e-5_wp, '3D beam constants')
      call check(s%sections(2)%has_v .and. all(s%sections(2)%v == [0.0_wp, 1.0_wp, 0.0_wp]), '3D beam v')
      call check(s%sections(3)%kind == SEC_SOLID .and. s%sections(3)%thickness == 0.01_wp, 'CPS thickness')
      call check(s%sections(4)%kind == SEC_SHELL .and. s%sections(4)%thickness == 0.02_wp, 'shell thickness')
      call check(s%sections(5)%area == 5.0e-4_wp, 'truss area')
      call check(s%sections(1)%material == 1 .and. s%sections(1)%elset == 1, 'material and elset indices')
      call check(s%sections(1)%loc%line == 20, 'section source line')
    end associate

    ! sections inside a substructure block and an elset named with scope from outside
    call read_ok(join([character(L) :: MAT, '*SUBSTRUCTURE, NAME=X', '*NODE', '1,0,0', '2,1,0', &
         '*ELEMENT, TYPE=T2D2, ELSET=E', '1, 1, 2', '*END SUBSTRUCTURE', &
         '*SOLID SECTION, ELSET=X.E, MATERIAL=STEEL', '1.0']), m, 'scoped elset on a section')
    if (size(m%subs) == 1) call check(m%subs(1)%elem_section(1) == 1, 'scoped elset assigned')

    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=B23, ELSET=B', &
         '1, 1, 2', '*BEAM SECTION, ELSET=B, MATERIAL=STEEL', '1e-2, 2e-5, 3e-5, 4e-5']), &
         'inline.deck:11: error: *BEAM SECTION of 2D beams (B23) needs A, I', '2D beam with 3D data')
    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=B33, ELSET=B', &
         '1, 1, 2', '*BEAM SECTION, ELSET=B, MATERIAL=STEEL', '1e-2, 2e-5']), &
         'needs A, Iy, Iz, J', '3D beam with 2D data')
    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=B33, ELSET=B', &
         '1, 1, 2', '*ELEMENT, TYPE=B23, ELSET=B', '2, 1, 2', '*BEAM SECTION, ELSET=B, MATERIAL=STEEL', &
         '1e-2, 2e-5']), 'mixes B23 and B33', 'beam types mixed')
    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=B23, ELSET=B', &
         '1, 1, 2', '*SOLID SECTION, ELSET=B, MATERIAL=STEEL', '1.0']), &
         'inline.deck:10: error: *SOLID SECTION on element set B: element 1 is of type B23, which needs *BEAM SECTION', &
         'section kind mismatch')
    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=T2D2, ELSET=B', &
         '1, 1, 2', '*SOLID SECTION, ELSET=B, MATERIAL=STEEL', '1.0', '*SOLID SECTION, ELSET=B, MATERIAL=STEEL', &
         '2.0']), 'inline.deck:12: error: element 1 of element set B already has a section (at inline.deck:10)', &
         'element in two sections')
    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=T2D2, ELSET=B', &
         '1, 1, 2', '*SOLID SECTION, ELSET=B, MATERIAL=STEEL', '-1.0']), &
         'inline.deck:11: error: section area or thickness must be positive', 'negative area')
    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=T2D2, ELSET=B', &
         '1, 1, 2', '*SOLID SECTION, ELSET=B, MATERIAL=IRON', '1.0']), &
         'inline.deck:10: error: unknown material IRON', 'unknown material')
    call read_bad(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '*ELEMENT, TYPE=T2D2, ELSET=B', &
         '1, 1, 2', '*SOLID SECTION, ELSET=C, MATERIAL=STEEL', '1.0']), &
         'inline.deck:10: error: unknown element set C in substructure MAIN', 'unknown elset')
    ! "no section" is said once per *ELEMENT card
    call read_deck_string(join([character(L) :: '*NODE', '1,0,0', '2,1,0', '3,1,1', '4,0,1', '*ELEMENT, TYPE=T2D2', &
         '1, 1, 2', '2, 1, 2', '3, 1, 2', '*ELEMENT, TYPE=CPS4', '4, 1, 2, 3, 4']), 'inline.deck', m, error)
    call check(allocated(error), 'elements without section')
    if (allocated(error)) then
       call check(count_lines(error%message) == 2, 'no-section message once per card')
       call check(index(error%message, 'inline.deck:7: error: element 1 (T2D2) has no section: '// &
            'no *SOLID SECTION covers it (and 2 more of this *ELEMENT card)') > 0, 'no-section message text')
    end if
  end subroutine test_sections

  ! ------------------------------------------------------------------ orientation

  subroutine test_orientation()
    type(model_t) :: m
    real(wp) :: c, s
    c = sqrt(3.0_wp)/2.0_wp
    s = 0.5_wp
    call read_ok(join([character(L) :: '*NODE', '1,0,0', '*ORIENTATION, NAME=TILT', &
         '2.0, 0, 0, 0.0, 0.8660254037844386, 0.5', '*ORIENTATION, NAME=SKEW', '0, 0, 3, 1, 1, 5']), m, 'orientation')
    if (size(m%orientations) /= 2) return
    associate (q => m%orientations(1)%q)
      call check_close(q(1, 1), 1.0_wp, 1.0e-15_wp, 'e1 x')
      call check_close(norm2(q(1, :) - [1.0_wp, 0.0_wp, 0.0_wp]), 0.0_wp, 1.0e-15_wp, 'e1 = a/|a|')
      call check_close(norm2(q(2, :) - [0.0_wp, c, s]), 0.0_wp, 1.0e-15_wp, 'e2 in the a-b plane')
      call check_close(norm2(q(3, :) - [0.0_wp, -s, c]), 0.0_wp, 1.0e-15_wp, 'e3 = e1 x e2')
    end associate
    associate (q => m%orientations(2)%q)
      call check_close(norm2(q(1, :) - [0.0_wp, 0.0_wp, 1.0_wp]), 0.0_wp, 1.0e-15_wp, 'skew e1')
      call check_close(norm2(q(2, :) - [1.0_wp, 1.0_wp, 0.0_wp]/sqrt(2.0_wp)), 0.0_wp, 1.0e-15_wp, &
           'skew e2 = b without its e1 part')
      call check_close(norm2(matmul(q, transpose(q)) - reshape([1, 0, 0, 0, 1, 0, 0, 0, 1]*1.0_wp, [3, 3])), &
           0.0_wp, 1.0e-15_wp, 'q orthonormal')
    end associate
    call check(m%orientations(1)%name == 'TILT', 'orientation name')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*ORIENTATION, NAME=O', '0,0,0, 1,0,0']), &
         'inline.deck:4: error: orientation vector a is zero', 'zero a')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*ORIENTATION, NAME=O', '1,1,0, -2,-2,0']), &
         'inline.deck:4: error: orientation vectors a and b are parallel', 'parallel a b')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*ORIENTATION, NAME=O']), &
         'inline.deck:3: error: *ORIENTATION needs a data line', 'orientation without data')
  end subroutine test_orientation

  ! ------------------------------------------------------------------ contacts

  subroutine test_contacts()
    type(model_t) :: m
    integer :: i1, i2
    character(:), allocatable :: parts
    parts = join([character(L) :: '*SUBSTRUCTURE, NAME=I', '*NODE', '5,0,0', '6,0,1', '7,0,2', '8,0,3', &
         '*NSET, NSET=EDGEI', '7, 5, 6', '*NSET, NSET=ONE', '8', '*END SUBSTRUCTURE', &
         '*SUBSTRUCTURE, NAME=II', '*NODE', '1,0,0', '2,0,1', '3,0,2', '4,0,3', '*NSET, NSET=EDGEII', &
         '3, 1, 2', '*END SUBSTRUCTURE'])
    call read_ok(parts//join([character(L) :: '*CONTACT, NAME=J1, MASTER=I, SLAVE=II', &
         ' 7, 3, 1, 2, RIGID', ' I.7, II.3, 6, 6, 4.0e6', ' edgeI, edgeII, 3, 3, 1.0e9', &
         ' 8, 4, 4, 4, 0', ' ONE, 4, 5, 5, rigid', &
         '*CONTACT, NAME=HINGE, MASTER=I, SLAVE=I', ' 5, 6, 1, 2, RIGID']), m, 'contacts')
    if (size(m%contacts) /= 2) return
    i1 = sub_of(m, 'I')
    i2 = sub_of(m, 'II')
    call check(m%contacts(1)%master_sub == i1 .and. m%contacts(1)%slave_sub == i2, 'contact substructures')
    call check(m%contacts(1)%orientation == 0, 'no orientation')
    call check(size(m%links) == 5, 'links merged per node pair')
    if (size(m%links) /= 5) return
    ! first appearance order: (7,3), (5,1), (6,2), (8,4), hinge (5,6)
    call check(uid(m, i1, m%links(1)%master_node) == 7 .and. uid(m, i2, m%links(1)%slave_node) == 3, 'link 1 pair')
    call check(uid(m, i1, m%links(2)%master_node) == 5 .and. uid(m, i2, m%links(2)%slave_node) == 1, &
         'nsets paired in order of definition')
    call check(uid(m, i1, m%links(3)%master_node) == 6 .and. uid(m, i2, m%links(3)%slave_node) == 2, 'link 3 pair')
    call check(uid(m, i1, m%links(4)%master_node) == 8 .and. uid(m, i2, m%links(4)%slave_node) == 4, &
         'node with a one-node set')
    associate (k => m%links(1))
      call check(all(k%state == [LINK_RIGID, LINK_RIGID, LINK_FINITE, LINK_NONE, LINK_NONE, LINK_FINITE]), &
           'merged states (one line per DOF)')
      call check(k%g(3) == 1.0e9_wp .and. k%g(6) == 4.0e6_wp, 'finite g of their lines')
      call check(k%loc%line == 22, 'link at its first line')
    end associate
    associate (k => m%links(4))
      call check(all(k%state == [LINK_NONE, LINK_NONE, LINK_NONE, LINK_NONE, LINK_RIGID, LINK_NONE]), &
           'g = 0 leaves the DOF, RIGID through a one-node set')
    end associate
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J1, MASTER=I, SLAVE=II', ' 7, 3, 1, 6, RIGID', &
         ' I.7, II.3, 6, 6, 2.0e7']), 'inline.deck:23: error: DOF 6 of contact J1 is given twice between '// &
         'the same nodes (first at inline.deck:22): one line per DOF', 'a DOF given twice in one *CONTACT')
    call check(m%links(5)%contact == 2 .and. m%contacts(2)%master_sub == m%contacts(2)%slave_sub, &
         'contact inside one substructure')

    call read_ok(parts//join([character(L) :: '*ORIENTATION, NAME=O', '1,0,0, 0,1,0', &
         '*CONTACT, NAME=J, MASTER=I, SLAVE=II, ORIENTATION=o', '5, 1, 1, 1, 0']), m, 'all-zero link kept')
    call check(size(m%links) == 1, 'all-zero link kept')
    if (size(m%links) == 1) call check(all(m%links(1)%state == LINK_NONE), 'all DOFs none')
    call check(m%contacts(1)%orientation == 1, 'orientation index')

    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', 'EDGEI, 1, 1, 1, RIGID']), &
         'inline.deck:22: error: node 1 is paired with node set EDGEI of 3 nodes', 'node with a 3-node set')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=K, MASTER=I, SLAVE=I', 'EDGEI, ONE, 1, 1, RIGID']), &
         'node sets EDGEI (3 nodes) and ONE (1 node) differ in size', 'nset sizes differ')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=I', '5, 5, 1, 1, RIGID']), &
         'inline.deck:22: error: node 5 of substructure I is in contact with itself', 'self contact')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', 'II.5, 1, 1, 1, RIGID']), &
         'inline.deck:22: error: node ''II.5'' is not in the master substructure I', 'scope of another substructure')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', '5, 1, 3, 2, RIGID']), &
         'first DOF 3 is after last DOF 2', 'first > last')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', '5, 1, 0, 2, RIGID']), &
         'invalid DOF ''0''', 'DOF 0')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', '5, 1, 1, 7, RIGID']), &
         'invalid DOF ''7''', 'DOF 7')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', '5, 1, 1, 2, -5']), &
         'stiffness must be >= 0 or RIGID', 'negative g')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=III', '5, 1, 1, 2, 5']), &
         'inline.deck:21: error: unknown substructure III in SLAVE=', 'unknown slave')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II, ORIENTATION=Q', &
         '5, 1, 1, 2, 5']), 'unknown orientation Q', 'unknown orientation')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', &
         '*CONTACT, NAME=j, MASTER=I, SLAVE=II']), 'inline.deck:22: error: duplicate contact name J', &
         'duplicate contact name')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', '5, 99, 1, 2, 5']), &
         'inline.deck:22: error: undefined node 99 in substructure II', 'undefined slave node')
    call read_bad(parts//join([character(L) :: '*CONTACT, NAME=J, MASTER=I, SLAVE=II', '5, 1, 1, 2']), &
         'wrong number of fields on *CONTACT data line', 'contact field count')
  end subroutine test_contacts

  ! ------------------------------------------------------------------ supports

  subroutine test_supports()
    type(model_t) :: m
    integer :: k
    call read_ok(join([character(L) :: '*NODE', '1,0,0', '2,1,0', '3,2,0', '*NSET, NSET=ENDS', '1, 3', &
         '*SUBSTRUCTURE, NAME=S', '*NODE', '7,0,0', '*NSET, NSET=N', '7', '*SUPPORT', 'N, 6, 6', &
         '*END SUBSTRUCTURE', &
         '*SUPPORT', '1, 1, 2', 'ENDS, 3, 3, 5.0e7', '2, 1, 1, 0', '2, 2, 2, rigid', 'S.7, 1, 1', 'S.N, 2, 2, 1.0', &
         '*BOUNDARY', '2, 1, 3', '3, 2', '3, 4, , 0.25', '3, 5, 6, -1e-3', 'S.7, ENCASTRE']), m, 'supports')
    call check(size(m%supports) == 1 + 2 + 2 + 1 + 1 + 1 + 3 + 1 + 1 + 2 + 6, 'one support per node and DOF')
    if (size(m%supports) /= 21) return
    k = sub_of(m, 'S')
    call check(m%supports(1)%sub == k .and. m%supports(1)%dof == 6, 'plain name inside a block')
    call check(m%supports(2)%sub == sub_of(m, 'MAIN') .and. m%supports(2)%dof == 1 .and. &
         m%supports(2)%state == LINK_RIGID, 'rigid by default')
    call check(m%supports(4)%state == LINK_FINITE .and. m%supports(4)%g == 5.0e7_wp .and. &
         m%supports(5)%node == 3, 'finite support on a set')
    call check(m%supports(6)%node == 2 .and. m%supports(6)%dof == 2 .and. m%supports(6)%state == LINK_RIGID, &
         'g = 0 skipped, RIGID word')
    call check(m%supports(7)%sub == k, 'scoped node')
    call check(m%supports(8)%g == 1.0_wp, 'scoped set')
    call check(all(m%supports(9:11)%dof == [1, 2, 3]), '*BOUNDARY range')
    call check(m%supports(12)%dof == 2 .and. m%supports(12)%value == 0.0_wp, '*BOUNDARY first only')
    call check(m%supports(13)%dof == 4 .and. m%supports(13)%value == 0.25_wp, '*BOUNDARY empty last, value')
    call check(m%supports(15)%value == -1.0e-3_wp .and. m%supports(15)%state == LINK_RIGID, 'prescribed value')
    call check(all(m%supports(16:21)%dof == [1, 2, 3, 4, 5, 6]), 'ENCASTRE')
    call check(m%supports(2)%loc%line == 16, 'support line')

    call read_bad(join([character(L) :: '*SUBSTRUCTURE, NAME=S', '*NODE', '7,0,0', '*END SUBSTRUCTURE', &
         '*SUPPORT', '7, 1, 1']), 'inline.deck:6: error: node 7 is not in a substructure', 'plain id without MAIN')
    call read_bad(join([character(L) :: '*NODE', '7,0,0', '*SUPPORT', 'Q.7, 1, 1']), &
         'inline.deck:4: error: unknown substructure Q in Q.7', 'unknown scope')
    call read_bad(join([character(L) :: '*NODE', '7,0,0', '*SUPPORT', 'NS, 1, 1']), &
         'inline.deck:4: error: unknown node set NS in substructure MAIN', 'unknown nset')
    call read_bad(join([character(L) :: '*NODE', '7,0,0', '*SUPPORT', '7, 1, 1, -1']), &
         'stiffness must be >= 0', 'negative support g')
    call read_bad(join([character(L) :: '*NODE', '7,0,0', '*STEP', '*SUPPORT', '7, 1, 1', '*END STEP']), &
         'inline.deck:4: error: *SUPPORT is not allowed inside *STEP', 'support in a step')
    call read_bad(join([character(L) :: '*NODE', '7,0,0', '*BOUNDARY', '7, 1, 1, x']), &
         'inline.deck:4: error: invalid real ''x''', 'bad boundary value')
  end subroutine test_supports

  ! ------------------------------------------------------------------ steps

  subroutine test_steps()
    type(model_t) :: m
    character(:), allocatable :: base
    base = join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '3,2,0', '*NSET, NSET=ALL', '1,2,3', &
         '*ELEMENT, TYPE=B23, ELSET=B', '1, 1, 2', '2, 2, 3', '*BEAM SECTION, ELSET=B, MATERIAL=STEEL', '1,1'])
    call read_ok(base, m, 'no loads')
    call check(size(m%steps) == 1, 'one step without loads')
    if (size(m%steps) == 1) call check(m%steps(1)%name == '1' .and. size(m%steps(1)%cloads) == 0 .and. &
         size(m%steps(1)%dloads) == 0, 'step 1 without loads')

    call read_ok(base//join([character(L) :: '*CLOAD', 'ALL, 2, -5', '*DLOAD', 'B, PY, -1', '*CLOAD', '3, 1, 2']), &
         m, 'loose loads')
    call check(size(m%steps) == 1, 'loose loads: one step')
    if (size(m%steps) == 1) then
       call check(m%steps(1)%name == '1', 'loose loads: step 1')
       call check(size(m%steps(1)%cloads) == 4 .and. size(m%steps(1)%dloads) == 2, 'loose load counts')
       call check(m%steps(1)%cloads(4)%node == 3 .and. m%steps(1)%cloads(4)%dof == 1 .and. &
            m%steps(1)%cloads(4)%value == 2.0_wp, 'cload fields')
       call check(m%steps(1)%dloads(2)%elem == 2 .and. m%steps(1)%dloads(2)%kind == DLOAD_PY, 'dload fields')
    end if

    call read_ok(base//join([character(L) :: '*STEP', '*CLOAD', '3, 2, 1', '*END STEP', '*Step, Name=Tip', &
         '*CLOAD', '3, 2, 2', '*END STEP', '*STEP', '*END STEP']), m, 'named and unnamed steps')
    call check(size(m%steps) == 3, 'three steps')
    if (size(m%steps) == 3) then
       call check(m%steps(1)%name == '1' .and. m%steps(2)%name == 'TIP' .and. m%steps(3)%name == '3', &
            'step names')
       call check(size(m%steps(3)%cloads) == 0 .and. m%steps(2)%cloads(1)%value == 2.0_wp, 'step contents')
       call check(m%steps(2)%loc%line == 20, 'step line')
    end if

    call read_ok(join([character(L) :: MAT, '*NODE', '1,0,0', '2,1,0', '3,1,1', '4,0,1', &
         '*ELEMENT, TYPE=S4, ELSET=PL', '1, 1, 2, 3, 4', '*SHELL SECTION, ELSET=PL, MATERIAL=STEEL', '0.01', &
         '*STEP', '*DLOAD', 'pl, p, 1e3', '1, P, 2e3', '*END STEP']), m, 'pressure on shells')
    if (size(m%steps) == 1) call check(size(m%steps(1)%dloads) == 2 .and. m%steps(1)%dloads(1)%kind == DLOAD_P, &
         'shell pressure')

    call read_ok(base//join([character(L) :: '*SUBSTRUCTURE, NAME=S', '*NODE', '5, 0, 0', '*CLOAD', '5, 1, 7', &
         '*END SUBSTRUCTURE', '*CLOAD', 'S.5, 2, 8', '3, 2, 9']), m, 'loose loads inside a block')
    if (size(m%steps) == 1) then
       call check(size(m%steps(1)%cloads) == 3, 'loose loads inside a block: count')
       if (size(m%steps(1)%cloads) == 3) call check(m%steps(1)%cloads(1)%sub == 2 .and. &
            m%steps(1)%cloads(2)%sub == 2 .and. m%steps(1)%cloads(3)%sub == 1, 'plain ids inside a block')
    end if

    call read_bad(base//join([character(L) :: '*CLOAD', '1, 2, 1', '*STEP', '*END STEP']), &
         'inline.deck:18: error: *STEP cannot be mixed with loads outside *STEP', 'loose loads then *STEP')
    call read_bad(base//join([character(L) :: '*STEP', '*END STEP', '*CLOAD', '1, 2, 1']), &
         'inline.deck:18: error: *CLOAD outside *STEP cannot be mixed with *STEP cards', '*STEP then loose loads')
    call read_bad(base//join([character(L) :: '*STEP, NAME=A', '*END STEP', '*STEP, NAME=a', '*END STEP']), &
         'inline.deck:18: error: duplicate step name A', 'duplicate step names')
    call read_bad(base//join([character(L) :: '*STEP', '*DLOAD', 'B, P, 1', '*END STEP']), &
         '*DLOAD P does not apply to element 1 of type B23', 'pressure on beams')
    call read_bad(base//join([character(L) :: '*STEP', '*DLOAD', 'B, PZ, 1', '*END STEP']), &
         '*DLOAD PZ does not apply to element 1 of type B23', 'PZ on 2D beams')
    call read_bad(base//join([character(L) :: '*STEP', '*DLOAD', 'B, PQ, 1', '*END STEP']), &
         'unknown *DLOAD type ''PQ''', 'unknown dload type')
    call read_bad(base//join([character(L) :: '*STEP', '*CLOAD', '1, 7, 1', '*END STEP']), &
         'invalid DOF ''7''', 'cload dof')
    call read_bad(base//join([character(L) :: '*STEP', '*CLOAD', '1, 1, 1']), &
         'inline.deck:16: error: *STEP 1 has no *END STEP', 'missing *END STEP')
    call read_bad(base//join([character(L) :: '*STEP', '*STEP', '*END STEP']), &
         'inline.deck:17: error: *STEP inside *STEP', 'nested step')
    call read_bad(base//join([character(L) :: '*END STEP']), '*END STEP without *STEP', 'end step alone')
    call read_bad(base//join([character(L) :: '*STEP', '*NODE', '9, 0, 0', '*END STEP']), &
         '*NODE is not allowed inside *STEP', 'model data inside a step')
  end subroutine test_steps

  subroutine test_controls()
    type(model_t) :: m
    call read_ok(join([character(L) :: '*NODE', '1,0,0']), m, 'default controls')
    call check(m%controls%formulation == FORM_TRANSFORM .and. m%controls%rigid == RIGID_ELIMINATE, &
         'default controls')
    call read_ok(join([character(L) :: '*NODE', '1,0,0', '*CONTROLS, FORMULATION=penalty, RIGID=LARGE, LARGE=1e8']), &
         m, 'controls')
    call check(m%controls%formulation == FORM_PENALTY .and. m%controls%rigid == RIGID_LARGE .and. &
         m%controls%large == 1.0e8_wp, 'controls set')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*CONTROLS, LARGE=0.5']), &
         'inline.deck:3: error: LARGE must be greater than 1', 'LARGE <= 1')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*CONTROLS, FORMULATION=MAGIC']), &
         'FORMULATION must be TRANSFORM or PENALTY', 'bad formulation')
  end subroutine test_controls

  ! ------------------------------------------------------------------ errors

  subroutine test_errors()
    type(model_t) :: m
    type(error_t), allocatable :: error
    call read_bad(join([character(L) :: '*NODE', '1, 0, abc']), "inline.deck:2: error: invalid real 'abc'", &
         'invalid real')
    call read_bad(join([character(L) :: '*NODE', '1, 0, nan']), 'NaN and Inf are not allowed', 'NaN')
    call read_bad(join([character(L) :: '*NODE', '1, 0, 1e999']), "real out of range '1e999'", 'overflow')
    call read_bad(join([character(L) :: '*MATERIAL, NAME=M', '*ELASTIC', ', 0.3']), 'invalid real: empty field', &
         'empty real')
    call read_bad(join([character(L) :: '*NODE', '0, 0, 0']), "inline.deck:2: error: invalid node id '0'", 'id 0')
    call read_bad(join([character(L) :: '*NODE', '2147483648, 0, 0']), "invalid node id '2147483648'", 'id 2**31')
    call read_bad(join([character(L) :: '*NODE', '1, 0, 0', '1, 1, 0']), &
         'inline.deck:3: error: duplicate node id 1 in substructure MAIN (also defined at inline.deck:2)', &
         'duplicate node')
    call read_bad(join([character(L) :: '*NODE', '1, 0, 0', '2, 1, 0', '*ELEMENT, TYPE=T2D2', '4, 1, 2', &
         '4, 2, 1']), 'inline.deck:6: error: duplicate element id 4', 'duplicate element')
    call read_bad(join([character(L) :: '*NODE', '1, 0, 0', '*ELEMENT, TYPE=T2D2', '4, 1, 2']), &
         'inline.deck:4: error: element 4 refers to undefined node 2 of substructure MAIN', 'undefined element node')
    call read_bad(join([character(L) :: '*NODE', '1, 0, 0', '*ELEMENT, TYPE=CPS4', '4, 1, 2, 3']), &
         'inline.deck:4: error: wrong number of fields on *ELEMENT data line: expected id and 4 nodes', &
         'element node count')
    call read_bad(join([character(L) :: '*NODE', '1, 0, 0', '*ELEMENT, TYPE=C3D27', '4, 1, 2, 3']), &
         'inline.deck:3: error: unsupported element type C3D27', 'element type')
    call read_bad(join([character(L) :: '*NODE', '1, 0, 0, 0, 0, 0, 1, 2', '']), 'wrong number of fields on *NODE data line', &
         'node field count')
    call read_bad(join([character(L) :: '1, 0, 0']), 'inline.deck:1: error: data line without a keyword', &
         'data before any keyword')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*MATERIAL, NAME=M', '1, 2']), &
         'inline.deck:4: error: *MATERIAL takes no data lines', 'data after a card without data')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*FROB']), 'inline.deck:3: error: unknown keyword *FROB', &
         'unknown keyword')
    call read_bad(join([character(L) :: '*NODE, COLOR=RED', '1,0,0']), &
         'inline.deck:1: error: unknown parameter COLOR on *NODE', 'unknown parameter')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*MATERIAL']), &
         'inline.deck:3: error: *MATERIAL needs parameter NAME=', 'missing parameter')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*MATERIAL, NAME=']), 'parameter NAME= has no value', &
         'empty parameter value')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*NSET, NSET=A, NSET=B']), 'parameter NSET given twice', &
         'duplicate parameter')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*MATERIAL, NAME=a.b']), "invalid name 'a.b'", &
         'name with a dot')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*MATERIAL, NAME=M']), &
         'inline.deck:3: error: material M has no *ELASTIC', 'material without elastic')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*ELASTIC', '1, 0.3']), &
         '*ELASTIC must follow a *MATERIAL card', 'elastic alone')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*MATERIAL, NAME=M', '*ELASTIC', '1, 0.5']), &
         'inline.deck:5: error: Poisson''s ratio must be between -1 and 0.5', 'nu = 0.5')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*MATERIAL, NAME=M', '*ELASTIC', '0, 0.3']), &
         'Young''s modulus E must be positive', 'E = 0')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', MAT, '*MATERIAL, NAME=steel', '*ELASTIC', '1,0']), &
         'duplicate material name STEEL', 'duplicate material')
    call read_bad(join([character(L) :: '*SUBSTRUCTURE, NAME=A', '*NODE', '1,0,0', '*END SUBSTRUCTURE', &
         '*SUBSTRUCTURE, NAME=a', '*NODE', '1,0,0', '*END SUBSTRUCTURE']), &
         'inline.deck:5: error: duplicate substructure name A (first defined at inline.deck:1)', 'duplicate sub')
    call read_bad(join([character(L) :: '*SUBSTRUCTURE, NAME=A', '*NODE', '1,0,0']), &
         'inline.deck:1: error: *SUBSTRUCTURE A has no *END SUBSTRUCTURE', 'unclosed substructure')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*END SUBSTRUCTURE']), &
         '*END SUBSTRUCTURE without *SUBSTRUCTURE', 'end without begin')
    call read_bad(join([character(L) :: '*SUBSTRUCTURE, NAME=A', '*SUBSTRUCTURE, NAME=B', '*NODE', '1,0,0', &
         '*END SUBSTRUCTURE']), '*SUBSTRUCTURE inside *SUBSTRUCTURE A', 'nested substructure')
    call read_bad(join([character(L) :: '** nothing']), 'inline.deck:1: error: the deck defines no nodes', 'empty deck')
    call read_bad(join([character(L) :: '*NODE', '1,0,0', '*', '']), 'empty keyword', 'lone star')
    ! missing file
    call read_deck('no/such/dir/deck.deck', m, error)
    call check(allocated(error), 'missing deck file')
    if (allocated(error)) call check(error%code == EXIT_IO .and. &
         index(error%message, 'no/such/dir/deck.deck: error: cannot open') == 1, 'missing deck: EXIT_IO message')
    ! several errors in one run, each on its own line
    call read_deck_string(join([character(L) :: '*NODE', '1, x, 0', '2, 0, y', '3, 0, 0', '*FROB']), 'inline.deck', m, error)
    call check(allocated(error), 'several errors')
    if (allocated(error)) then
       call check(count_lines(error%message) == 3, 'three error lines')
       call check(index(error%message, 'inline.deck:2: error:') == 1, 'first error first')
    end if
  end subroutine test_errors

  subroutine test_error_cap()
    type(model_t) :: m
    type(error_t), allocatable :: error
    character(:), allocatable :: text
    integer :: i
    text = '*NODE'//LF
    do i = 1, 200
       text = text//'1, x, 0'//LF
    end do
    call read_deck_string(text, 'inline.deck', m, error)
    call check(allocated(error), 'many errors')
    if (.not. allocated(error)) return
    call check(count_lines(error%message) == 51, '50 messages and one more line')
    call check(index(error%message, LF//'... too many errors') == len(error%message) - len('... too many errors'), &
         'last line says too many errors')
  end subroutine test_error_cap
end program test_deck
