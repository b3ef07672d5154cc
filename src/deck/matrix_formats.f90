module superjoin_deck_matrix_formats
  !! Condensed parts that travel, the readers of `*MATRIX INPUT, FORMAT=DMIG`
  !! and `FORMAT=MATRIX MARKET` (superjoin_deck_matrix_input reads ABAQUS and
  !! CALCULIX and builds the block's matrix from the entries gathered here).
  !!
  !! - DMIG: Nastran bulk data. Small field (8-column fields in columns 9-72),
  !!   large field (`DMIG*`, 16-column fields, a continuation line starting
  !!   with `*` holds the next four fields) and free field (comma separated,
  !!   continuation lines starting with `+`, `*` or `,`); columns 73-80 (the
  !!   continuation field) ignored; `$` comments, `BEGIN BULK` and `ENDDATA`
  !!   skipped. Header `DMIG, NAME, 0, IFO, TIN, TOUT, POLAR, , NCOL`; column
  !!   `DMIG, NAME, GJ, CJ, , G1, C1, A1, B1` and `G, C, A, B` groups after it.
  !!   The stiffness is the matrix named by NAME= or else the one square
  !!   matrix of the file: IFO=6 (symmetric, one triangle) or IFO=1 (square,
  !!   checked symmetric); TIN=1 or 2 (real). read_dmig_load: one column of
  !!   a load matrix (IFO=9, the P2G= matrix; column entries `NAME, k, 0|blank,
  !!   , G1, C1, A1, ...`, NCOL in the header's field 9), for *MATRIX LOAD.
  !! - MATRIX MARKET: `f.mtx`, `%%MatrixMarket matrix coordinate real
  !!   symmetric|general`, rows and columns numbered as the DOF map
  !!   `f_dofs.csv` beside it (`index,node,dof`, as the export writes them).
  !!   read_market_load: one column of `f_loads.mtx` (`%%MatrixMarket matrix
  !!   array real general`, rows numbered as the DOF map), for *MATRIX LOAD.
  !!
  !! A bad field, a DOF outside 1..6, an entry given twice or a matrix that is
  !! not symmetric is reported at its line.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: source_loc_t
  use superjoin_deck_lexer, only: next_line, split_fields, to_upper, clip, itoa, fields_t, parse_real, &
       parse_id, TOK_OK
  use superjoin_deck_state, only: deck_state_t, report, report_loc, given_b_t
  use superjoin_utils_sorting, only: sort_index, find_sorted
  implicit none (type, external)
  private

  public :: read_dmig, read_market, push_entry, id_of, value_of, new_given, next_nonblank, read_dmig_load, &
       read_market_load

  integer, parameter :: NDOF = 6
  integer, parameter :: KEY_BASE = 8               !! (node, DOF) key: node*KEY_BASE + DOF
  integer, parameter :: INITIAL_ENTRIES = 64
  integer, parameter :: FIELD_LEN = 40             !! longest field kept
  integer, parameter :: SMALL_W = 8, LARGE_W = 16  !! fixed field widths
  integer, parameter :: FIRST_COL = 9, LAST_COL = 72
  integer, parameter :: SMALL_N = 8, LARGE_N = 4   !! data fields of a line
  integer, parameter :: IFO_SQUARE = 1, IFO_RECT = 2, IFO_SYM = 6, IFO_NCOL = 9
  integer, parameter :: TIN_REAL = 1, TIN_DOUBLE = 2
  integer, parameter :: GROUP = 4                  !! G, C, A, B of a column term
  integer, parameter :: FIRST_TERM = 5             !! the first G of a column entry
  integer, parameter :: MM_WORDS = 5               !! words of the %%MatrixMarket line
  integer, parameter :: NCOL_FIELD = 8             !! NCOL in the header's data fields (field 9 of the entry)
  real(wp), parameter :: SYM_TOL = 1.0e-9_wp
    !! a square matrix is symmetric when each pair agrees to this, relative

  type :: bulk_entry_t
    !! One bulk data entry being gathered: its data fields (2, 3, ...) over
    !! its continuation lines, each with its line.
     character(len=FIELD_LEN) :: card = ''
     logical :: large = .false.
     integer :: nf = 0
     character(len=FIELD_LEN), allocatable :: f(:)
     integer, allocatable :: line(:)
  end type bulk_entry_t

  type :: dmig_t
    !! The DMIG matrices of a file (pass 1: headers) and the one read.
     integer :: ifile = 0
     integer :: pass = 1
     integer :: nmat = 0
     character(len=FIELD_LEN), allocatable :: name(:)
     integer, allocatable :: ifo(:), line(:)
     integer, allocatable :: ncol(:)               !! NCOL of each header (0: not given)
     logical :: load = .false.                     !! reading a load matrix (columns by number)
     integer :: maxcol = 0                         !! load: the largest column number met
     integer :: col = 0                            !! load: the column read (0: every column)
     character(len=FIELD_LEN) :: chosen = ''
     type(given_b_t) :: terms                      !! the chosen matrix's terms as given
  end type dmig_t

  type, public :: text_lines_t
    !! The walk over the non-blank lines of a text (line: the number of the
    !! last one, blank lines counted).
     integer(i8) :: pos = 1
     integer :: line = 0
  end type text_lines_t

  type :: dof_map_t
    !! The Matrix Market DOF map (`index,node,dof`).
     integer :: n = 0
     integer(ip), allocatable :: node(:)
     integer, allocatable :: dof(:), line(:)
  end type dof_map_t

contains

  subroutine new_given(g)
    !! Empty entry arrays of a given matrix being read.
    type(given_b_t), intent(inout) :: g
    g%n = 0
    allocate (g%rnode(INITIAL_ENTRIES), g%cnode(INITIAL_ENTRIES), g%rdof(INITIAL_ENTRIES), &
         g%cdof(INITIAL_ENTRIES), g%line(INITIAL_ENTRIES), g%val(INITIAL_ENTRIES))
  end subroutine new_given

  subroutine read_dmig(st, text, g, name)
    !! The stiffness of a DMIG file into g (g%file: the file; g%loc: the card);
    !! name: NAME= of the card ('' when absent).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text, name
    type(given_b_t), intent(inout) :: g
    type(dmig_t) :: d
    integer :: nerr0
    d%ifile = g%file
    allocate (d%name(0), d%ifo(0), d%line(0), d%ncol(0))
    nerr0 = st%nerr
    call bulk_entries(st, text, d)
    if (st%nerr /= nerr0) return
    call choose_matrix(st, g, d, name)
    if (len_trim(d%chosen) == 0) return
    call new_given(d%terms)
    d%pass = 2
    call bulk_entries(st, text, d)
    if (d%ifo(name_index(d, d%chosen)) == IFO_SYM) then
       call fold_terms(st, d%terms, g, .true., 'matrix '//trim(d%chosen)//' (IFO=6, declared symmetric)')
    else
       call fold_terms(st, d%terms, g, .false., 'matrix '//trim(d%chosen)//' (IFO=1)')
    end if
  end subroutine read_dmig

  subroutine choose_matrix(st, g, d, name)
    !! The matrix read: NAME= or the one square matrix of the file.
    type(deck_state_t), intent(inout) :: st
    type(given_b_t), intent(in) :: g
    type(dmig_t), intent(inout) :: d
    character(*), intent(in) :: name
    integer :: k, nsq
    character(:), allocatable :: names
    if (len(name) > 0) then
       k = name_index(d, name)
       if (k == 0) then
          call report_loc(st, g%loc, 'NAME='//name//' names no DMIG matrix of the file')
       else if (d%ifo(k) /= IFO_SYM .and. d%ifo(k) /= IFO_SQUARE) then
          call report(st, d%ifile, d%line(k), 'DMIG matrix '//name//' is not square (IFO='//itoa(d%ifo(k))// &
               '): *MATRIX INPUT reads a stiffness (IFO=6 or 1); loads enter as *CLOAD lines')
       else
          d%chosen = name
       end if
       return
    end if
    nsq = 0
    names = ''
    do k = 1, d%nmat
       if (d%ifo(k) /= IFO_SYM .and. d%ifo(k) /= IFO_SQUARE) cycle
       nsq = nsq + 1
       names = names//', '//trim(d%name(k))
       d%chosen = d%name(k)
    end do
    if (nsq /= 1) then
       d%chosen = ''
       if (nsq == 0) call report_loc(st, g%loc, 'the DMIG file has no square matrix (IFO=6 or 1)')
       if (nsq > 1) call report_loc(st, g%loc, 'the DMIG file has '//itoa(nsq)//' square matrices ('// &
            names(3:)//'): choose one with NAME=')
    end if
  end subroutine choose_matrix

  subroutine bulk_entries(st, text, d)
    !! Every bulk data entry of the text to dmig_entry.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text
    type(dmig_t), intent(inout) :: d
    integer(i8) :: first, last
    type(text_lines_t) :: lines
    integer :: line
    type(bulk_entry_t) :: e
    character(:), allocatable :: t
    allocate (e%f(INITIAL_ENTRIES), e%line(INITIAL_ENTRIES))
    do while (next_nonblank(lines, text, first, last))
       line = lines%line
       associate (s => text(first:last))
         if (s(1:1) == '$') cycle
         t = to_upper(adjustl(s))
         if (index(t, 'BEGIN') == 1 .or. index(t, 'ENDDATA') == 1) then
            call dmig_entry(st, e, d)
            cycle
         end if
         call bulk_line(st, d, line, s, e)
       end associate
    end do
    call dmig_entry(st, e, d)
  end subroutine bulk_entries

  subroutine bulk_line(st, d, line, s, e)
    !! One line of bulk data: a new entry (the previous one done) or a
    !! continuation; its data fields appended to e.
    type(deck_state_t), intent(inout) :: st
    type(dmig_t), intent(inout) :: d
    integer, intent(in) :: line
    character(*), intent(in) :: s
    type(bulk_entry_t), intent(inout) :: e
    type(fields_t) :: f
    character(:), allocatable :: f1
    logical :: free
    integer :: k, n, w
    free = index(s, ',') > 0
    if (free) then
       call split_fields(s, f)
       f1 = to_upper(s(f%first(1):f%last(1)))
    else
       f1 = to_upper(trim(adjustl(s(1:min(len(s), FIRST_COL - 1)))))
    end if
    if (len(f1) == 0 .or. index(f1, '+') == 1 .or. index(f1, '*') == 1) then
       if (len_trim(e%card) == 0) then
          call report(st, d%ifile, line, 'a continuation line with no bulk data entry before it')
          return
       end if
    else
       call dmig_entry(st, e, d)
       e%large = f1(len(f1):) == '*'
       e%card = f1
       if (e%large) e%card = f1(:len(f1) - 1)
    end if
    n = SMALL_N
    if (e%large) n = LARGE_N
    if (free .and. f%n > n + 2) then
       call report(st, d%ifile, line, 'a free-field line of '//trim(e%card)//' holds '//itoa(n)// &
            ' data fields between its first and its tenth, not '//itoa(f%n - 2))
       return
    end if
    w = SMALL_W
    if (e%large) w = LARGE_W
    do k = 1, n
       if (free) then
          if (k + 1 <= f%n) then
             call add_field(st, d, line, e, s(f%first(k + 1):f%last(k + 1)))
          else
             call add_field(st, d, line, e, '')
          end if
       else
          call add_field(st, d, line, e, s(min(FIRST_COL + (k - 1)*w, len(s) + 1): &
               min(FIRST_COL - 1 + k*w, LAST_COL, len(s))))
       end if
    end do
  end subroutine bulk_line

  subroutine add_field(st, d, line, e, s)
    type(deck_state_t), intent(inout) :: st
    type(dmig_t), intent(in) :: d
    integer, intent(in) :: line
    type(bulk_entry_t), intent(inout) :: e
    character(*), intent(in) :: s
    character(len=FIELD_LEN), allocatable :: fields(:)
    if (len_trim(adjustl(s)) > FIELD_LEN) call report(st, d%ifile, line, 'a field longer than '// &
         itoa(FIELD_LEN)//' characters: '''//clip(s)//'''')
    if (e%nf == size(e%f)) then
       allocate (fields(2*size(e%f)))
       fields(1:size(e%f)) = e%f
       call move_alloc(fields, e%f)
       e%line = [e%line, e%line]
    end if
    e%nf = e%nf + 1
    e%f(e%nf) = to_upper(trim(adjustl(s)))
    e%line(e%nf) = line
  end subroutine add_field

  subroutine dmig_entry(st, e, d)
    !! A complete entry: a DMIG header (pass 1) or column (pass 2); e is
    !! emptied.
    type(deck_state_t), intent(inout) :: st
    type(bulk_entry_t), intent(inout) :: e
    type(dmig_t), intent(inout) :: d
    if (len_trim(e%card) == 0) return
    if (e%card /= 'DMIG') then
       if (d%pass == 1) call report(st, d%ifile, e%line(1), 'a DMIG file holds DMIG entries, not '// &
            clip(e%card))
    else if (len_trim(e%f(1)) == 0) then
       if (d%pass == 1) call report(st, d%ifile, e%line(1), 'a DMIG entry without a matrix name')
    else if (e%f(2) == '0') then
       if (d%pass == 1) call dmig_header(st, e, d)
    else if (d%pass == 1) then
       if (name_index(d, e%f(1)) == 0) call report(st, d%ifile, e%line(1), 'a column of DMIG matrix '// &
            trim(e%f(1))//' before its header entry (NAME, 0, IFO, TIN)')
    else if (e%f(1) == d%chosen) then
       call dmig_column(st, e, d)
    end if
    e%card = ''
    e%nf = 0
  end subroutine dmig_entry

  subroutine dmig_header(st, e, d)
    !! `NAME, 0, IFO, TIN, TOUT, POLAR, , NCOL`: a real matrix.
    type(deck_state_t), intent(inout) :: st
    type(bulk_entry_t), intent(in) :: e
    type(dmig_t), intent(inout) :: d
    integer(ip) :: ifo, tin
    integer :: stat
    character(len=FIELD_LEN), allocatable :: names(:)
    if (name_index(d, e%f(1)) > 0) then
       call report(st, d%ifile, e%line(1), 'DMIG matrix '//trim(e%f(1))//' has a header entry already')
       return
    end if
    call parse_id(trim(e%f(3)), ifo, stat)
    if (stat /= TOK_OK .or. all(ifo /= [IFO_SQUARE, IFO_RECT, IFO_SYM, IFO_NCOL])) then
       call report(st, d%ifile, e%line(3), 'invalid IFO '''//clip(trim(e%f(3)))//''' of DMIG matrix '// &
            trim(e%f(1))//' (1, 2, 6 or 9)')
       ifo = 0
    else
       call parse_id(trim(e%f(4)), tin, stat)
       if (stat /= TOK_OK .or. all(tin /= [TIN_REAL, TIN_DOUBLE])) then
          call report(st, d%ifile, e%line(4), 'DMIG matrix '//trim(e%f(1))//' has TIN='//clip(trim(e%f(4)))// &
               ': a real matrix has TIN=1 or 2 (complex ones are not read)')
          ifo = 0
       end if
    end if
    d%nmat = d%nmat + 1
    ! grown by hand: gfortran's -fcheck=bounds misreads the length of a character
    ! component in an array constructor ([d%name, e%f(1)] stops the Debug build)
    allocate (names(d%nmat))
    names(1:d%nmat - 1) = d%name
    names(d%nmat) = e%f(1)
    call move_alloc(names, d%name)
    d%ifo = [d%ifo, int(ifo)]
    d%line = [d%line, e%line(1)]
    ifo = 0
    if (e%nf >= NCOL_FIELD) then
       if (len_trim(e%f(NCOL_FIELD)) > 0) then
          call parse_id(trim(e%f(NCOL_FIELD)), ifo, stat)
          if (stat /= TOK_OK) then
             call report(st, d%ifile, e%line(NCOL_FIELD), 'invalid NCOL '''//clip(trim(e%f(NCOL_FIELD)))// &
                  ''' of DMIG matrix '//trim(e%f(1)))
             ifo = 0
          end if
       end if
    end if
    d%ncol = [d%ncol, int(ifo)]
  end subroutine dmig_header

  subroutine dmig_column(st, e, d)
    !! `NAME, GJ, CJ, , G1, C1, A1, B1, G2, ...`: the terms (Gi, Ci; GJ, CJ) = Ai.
    type(deck_state_t), intent(inout) :: st
    type(bulk_entry_t), intent(in) :: e
    type(dmig_t), intent(inout) :: d
    integer(ip) :: gj, gi
    integer :: cj, ci, k
    real(wp) :: a
    if (d%load) then
       if (.not. load_column(st, d, e, gj)) return
       if (d%col > 0 .and. gj /= d%col) return       ! its values are read with their own column
       cj = 0
    else if (.not. grid_comp(st, d%ifile, e, 2, gj, cj)) then
       return
    end if
    do k = FIRST_TERM, e%nf - GROUP + 1, GROUP
       if (all(e%f(k:k + GROUP - 1) == '')) cycle
       if (.not. grid_comp(st, d%ifile, e, k, gi, ci)) cycle
       if (.not. nastran_real(st, d%ifile, e%line(k + 2), e%f(k + 2), a)) cycle
       if (len_trim(e%f(k + 3)) > 0) then
          call report(st, d%ifile, e%line(k + 3), 'an imaginary part '''//clip(trim(e%f(k + 3)))// &
               ''' in real DMIG matrix '//trim(d%chosen))
          cycle
       end if
       call push_entry(d%terms, gi, ci, gj, cj, a, e%line(k + 2))
    end do
  end subroutine dmig_column

  pure integer function name_index(d, name) result(k)
    !! The header of matrix `name` among d's (0: none). A loop, not findloc:
    !! gfortran's findloc missed the names of dmig_t once it held the NCOL array.
    type(dmig_t), intent(in) :: d
    character(*), intent(in) :: name
    do k = 1, d%nmat
       if (d%name(k) == name) return
    end do
    k = 0
  end function name_index

  logical function load_column(st, d, e, col) result(ok)
    !! `NAME, k, CJ`: column k of a load matrix (CJ blank or 0).
    type(deck_state_t), intent(inout) :: st
    type(dmig_t), intent(inout) :: d
    type(bulk_entry_t), intent(in) :: e
    integer(ip), intent(out) :: col
    ok = id_of(st, d%ifile, e%line(2), trim(e%f(2)), 'column', col)
    if (.not. ok) return
    if (len_trim(e%f(3)) > 0 .and. e%f(3) /= '0') then
       call report(st, d%ifile, e%line(3), 'a column of load matrix '//trim(d%chosen)//' has CJ blank or 0, not '// &
            clip(trim(e%f(3))))
       ok = .false.
       return
    end if
    d%maxcol = max(d%maxcol, int(col))
  end function load_column

  subroutine read_dmig_load(st, text, ifile, load, loc, v, found)
    !! Column `load` of a DMIG load matrix (IFO=9) of the file ifile (text):
    !! `NAME(k)`, `NAME` (a matrix of one column) or `k` (the file's one load
    !! matrix). v: its terms (rnode, rdof, val, line); found false (reported at
    !! loc, the *MATRIX LOAD line) when the file has no such load.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text, load
    integer, intent(in) :: ifile
    type(source_loc_t), intent(in) :: loc
    type(given_b_t), intent(inout) :: v
    logical, intent(out) :: found
    type(dmig_t) :: d
    character(:), allocatable :: name
    integer :: col, k, ncol, nerr0
    found = .false.
    d%ifile = ifile
    d%load = .true.
    allocate (d%name(0), d%ifo(0), d%line(0), d%ncol(0))
    nerr0 = st%nerr
    call bulk_entries(st, text, d)
    if (st%nerr /= nerr0) return
    call split_load_name(load, name, col)
    if (col < 0) then
       call report_loc(st, loc, 'load '//load//': a DMIG load is NAME, NAME(column) or a column number')
       return
    end if
    if (len(name) == 0) then
       if (count(d%ifo == IFO_NCOL) /= 1) then
          call report_loc(st, loc, 'load '//load//': the DMIG file has '//itoa(count(d%ifo == IFO_NCOL))// &
               ' load matrices (IFO=9): name one, NAME('//load//')')
          return
       end if
       k = findloc(d%ifo, IFO_NCOL, 1)
    else
       k = name_index(d, name)
       if (k == 0) then
          call report_loc(st, loc, 'unknown load '//load//': the DMIG file has no matrix '//name)
          return
       else if (d%ifo(k) /= IFO_NCOL) then
          call report_loc(st, loc, 'load '//load//': DMIG matrix '//name//' is not a load matrix (IFO=9)')
          return
       end if
    end if
    d%chosen = d%name(k)
    d%col = col
    ncol = d%ncol(k)
    if (col == 0 .and. ncol <= 1) then
       call new_given(d%terms)
       d%pass = 2
       call bulk_entries(st, text, d)
       ncol = max(ncol, d%maxcol)
    end if
    if (col == 0 .and. ncol > 1) then
       call report_loc(st, loc, 'load '//load//': DMIG load matrix '//trim(d%chosen)//' has '//itoa(ncol)// &
            ' columns: name one, '//trim(d%chosen)//'(1) to '//trim(d%chosen)//'('//itoa(ncol)//')')
       return
    end if
    if (col > 0) then
       call new_given(d%terms)
       d%pass = 2
       call bulk_entries(st, text, d)
       ncol = max(ncol, d%maxcol)
    end if
    col = max(col, 1)
    if (col > ncol) then
       call report_loc(st, loc, 'unknown load '//load//': DMIG load matrix '//trim(d%chosen)//' has '// &
            itoa(ncol)//' columns')
       return
    end if
    do k = 1, d%terms%n
       if (d%terms%cnode(k) == col) call push_entry(v, d%terms%rnode(k), d%terms%rdof(k), 0_ip, 0, &
            d%terms%val(k), d%terms%line(k))
    end do
    found = .true.
  end subroutine read_dmig_load

  pure subroutine split_load_name(load, name, col)
    !! `NAME(k)` -> NAME, k; `k` -> '', k; `NAME` -> NAME, 0; col < 0: neither.
    character(*), intent(in) :: load
    character(:), allocatable, intent(out) :: name
    integer, intent(out) :: col
    integer :: k
    character(:), allocatable :: t
    t = to_upper(trim(adjustl(load)))
    k = index(t, '(')
    name = t
    col = 0
    if (k > 0) then
       name = trim(t(:k - 1))
       col = -1
       if (t(len(t):) /= ')' .or. len(name) == 0) return
       col = digits_value(t(k + 1:len(t) - 1))
    else if (verify(t, '0123456789') == 0 .and. len(t) > 0) then
       name = ''
       col = digits_value(t)
    end if
  end subroutine split_load_name

  pure integer function digits_value(s) result(n)
    !! The positive integer s (blanks around it allowed); -1 if it is none.
    character(*), intent(in) :: s
    integer :: k
    character(:), allocatable :: t
    t = trim(adjustl(s))
    n = -1
    if (len(t) == 0 .or. len(t) > 9 .or. verify(t, '0123456789') /= 0) return
    n = 0
    do k = 1, len(t)
       n = 10*n + (iachar(t(k:k)) - iachar('0'))
    end do
    if (n == 0) n = -1
  end function digits_value

  logical function grid_comp(st, ifile, e, k, g, c) result(ok)
    !! Fields k, k+1 of e: a GRID id and its component 1..6.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, k
    type(bulk_entry_t), intent(in) :: e
    integer(ip), intent(out) :: g
    integer, intent(out) :: c
    integer(ip) :: v
    integer :: stat
    c = 0
    ok = id_of(st, ifile, e%line(k), trim(e%f(k)), 'GRID', g)
    if (.not. ok) return
    call parse_id(trim(e%f(k + 1)), v, stat)
    if (stat /= TOK_OK .and. e%f(k + 1) /= '0') then
       call report(st, ifile, e%line(k + 1), 'invalid component '''//clip(trim(e%f(k + 1)))//'''')
       ok = .false.
    else if (e%f(k + 1) == '0' .or. v > NDOF) then
       call report(st, ifile, e%line(k + 1), 'component '//trim(e%f(k + 1))//' of GRID '//itoa(int(g))// &
            ' is not a DOF 1 to 6 (scalar points are not read)')
       ok = .false.
    else
       c = int(v)
    end if
  end function grid_comp

  logical function nastran_real(st, ifile, line, s, v) result(ok)
    !! A Nastran real field: Fortran forms and the exponent without its
    !! letter (`1.5+3`, `-2.-4`).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    real(wp), intent(out) :: v
    integer :: stat, k
    character(:), allocatable :: t
    t = trim(s)
    call parse_real(t, v, stat)
    if (stat /= TOK_OK) then
       k = max(scan(t(2:), '+-', back=.true.) + 1, 2)
       if (k > 2 .and. scan(t(k - 1:k - 1), 'ED') == 0) then
          call parse_real(t(:k - 1)//'E'//t(k:), v, stat)
       end if
    end if
    ok = stat == TOK_OK
    if (.not. ok) call report(st, ifile, line, 'invalid matrix value '''//clip(trim(s))//'''')
  end function nastran_real

  subroutine read_market(st, text, csv_file, csv_text, g)
    !! The stiffness of a Matrix Market file (g%file) with its DOF map
    !! (csv_file, csv_text).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text, csv_text
    integer, intent(in) :: csv_file
    type(given_b_t), intent(inout) :: g
    type(dof_map_t) :: map
    type(given_b_t) :: terms
    integer(i8) :: first, last
    logical :: symmetric, banner
    type(text_lines_t) :: lines
    integer :: line, size_line, nnz, nerr0
    type(fields_t) :: w
    nerr0 = st%nerr
    call read_dof_map(st, csv_file, csv_text, map)
    call new_given(terms)
    size_line = 0
    symmetric = .false.
    banner = .false.
    do while (next_nonblank(lines, text, first, last))
       line = lines%line
       associate (s => text(first:last))
         if (.not. banner) then
            banner = .true.
            call market_banner(st, g%file, line, s, symmetric)
            cycle
         end if
         if (index(adjustl(s), '%') == 1) cycle
         call split_words(s, w)
         if (size_line == 0) then
            size_line = line
            call market_size(st, g%file, line, s, w, map, nnz)
         else
            call market_entry(st, g%file, line, s, w, map, terms)
         end if
       end associate
    end do
    if (size_line == 0) then
       call report_loc(st, g%loc, 'the Matrix Market file has no size line')
    else if (st%nerr == nerr0 .and. terms%n /= nnz) then
       call report(st, g%file, size_line, 'the Matrix Market file gives '//itoa(terms%n)//' entries, not '// &
            itoa(nnz))
    end if
    if (symmetric) then
       call fold_terms(st, terms, g, .true., 'the matrix (declared symmetric)')
    else
       call fold_terms(st, terms, g, .false., 'the matrix')
    end if
  end subroutine read_market

  subroutine read_market_load(st, text, ifile, map_text, map_file, col, v, found)
    !! Column col of a Matrix Market load array (text, file ifile) whose rows
    !! are those of the DOF map (map_text, map_file). found false when the
    !! array has fewer columns (the caller reports the load as unknown).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text, map_text
    integer, intent(in) :: ifile, map_file, col
    type(given_b_t), intent(inout) :: v
    logical, intent(out) :: found
    type(dof_map_t) :: map
    integer(i8) :: first, last
    type(text_lines_t) :: lines
    integer :: line, size_line, nval, ncol, row
    logical :: banner
    real(wp) :: x
    found = .false.
    banner = .false.
    call read_dof_map(st, map_file, map_text, map)
    size_line = 0
    nval = 0
    ncol = 0
    do while (next_nonblank(lines, text, first, last))
       line = lines%line
       associate (s => text(first:last))
         if (.not. banner) then
            banner = .true.
            if (.not. array_banner(st, ifile, line, s)) return
            cycle
         end if
         if (index(adjustl(s), '%') == 1) cycle
         if (size_line == 0) then
            size_line = line
            if (.not. array_size(st, ifile, line, s, map%n, ncol)) return
            if (col > ncol) return
            cycle
         end if
         nval = nval + 1
         if ((nval - 1)/map%n + 1 /= col) cycle        ! the other columns' values are read with them
         if (.not. value_of(st, ifile, line, trim(adjustl(s)), x)) cycle
         row = mod(nval - 1, map%n) + 1
         if (map%node(row) == 0) cycle
         call push_entry(v, map%node(row), map%dof(row), 0_ip, 0, x, line)
       end associate
    end do
    if (size_line == 0) then
       call report(st, ifile, max(lines%line, 1), 'the Matrix Market load array has no size line')
    else if (nval /= map%n*ncol) then
       call report(st, ifile, size_line, 'the load array gives '//itoa(nval)//' values, not '//itoa(map%n*ncol)// &
            ' ('//itoa(map%n)//' rows x '//itoa(ncol)//' columns)')
    else
       found = .true.
    end if
  end subroutine read_market_load

  logical function array_size(st, ifile, line, s, nrow, ncol) result(ok)
    !! `rows columns` of a load array: rows as the DOF map's nrow.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line, nrow
    character(*), intent(in) :: s
    integer, intent(out) :: ncol
    type(fields_t) :: w
    integer(ip) :: dims(2)
    ncol = 0
    ok = .false.
    call split_words(s, w)
    if (w%n /= 2) then
       call report(st, ifile, line, 'the size line of a Matrix Market load array has 2 numbers (rows, '// &
            'columns), not '//itoa(w%n))
       return
    end if
    if (.not. id_of(st, ifile, line, s(w%first(1):w%last(1)), 'size', dims(1))) return
    if (.not. id_of(st, ifile, line, s(w%first(2):w%last(2)), 'size', dims(2))) return
    if (dims(1) /= nrow) then
       call report(st, ifile, line, 'the load array has '//itoa(int(dims(1)))//' rows; its DOF map lists '// &
            itoa(nrow)//' DOFs')
       return
    end if
    ncol = int(dims(2))
    ok = .true.
  end function array_size

  logical function array_banner(st, ifile, line, s) result(ok)
    !! `%%MatrixMarket matrix array real|integer general`.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    type(fields_t) :: w
    character(:), allocatable :: t
    t = to_upper(s)
    call split_words(t, w)
    ok = .false.
    if (w%n == MM_WORDS) ok = t(w%first(1):w%last(1)) == '%%MATRIXMARKET' .and. &
         t(w%first(2):w%last(2)) == 'MATRIX' .and. t(w%first(3):w%last(3)) == 'ARRAY' .and. &
         any(t(w%first(4):w%last(4)) == ['REAL   ', 'INTEGER']) .and. t(w%first(5):w%last(5)) == 'GENERAL'
    if (.not. ok) call report(st, ifile, line, 'a Matrix Market load array starts with ''%%MatrixMarket '// &
         'matrix array real general'', not '''//clip(s)//'''')
  end function array_banner

  subroutine market_banner(st, ifile, line, s, symmetric)
    !! `%%MatrixMarket matrix coordinate real|integer symmetric|general`.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    logical, intent(out) :: symmetric
    type(fields_t) :: w
    character(:), allocatable :: t
    t = to_upper(s)
    call split_words(t, w)
    symmetric = .false.
    if (w%n == MM_WORDS) then
       if (t(w%first(1):w%last(1)) == '%%MATRIXMARKET' .and. t(w%first(2):w%last(2)) == 'MATRIX' .and. &
            t(w%first(3):w%last(3)) == 'COORDINATE' .and. any(t(w%first(4):w%last(4)) == ['REAL   ', &
            'INTEGER']) .and. any(t(w%first(5):w%last(5)) == ['SYMMETRIC', 'GENERAL  '])) then
          symmetric = t(w%first(5):w%last(5)) == 'SYMMETRIC'
          return
       end if
    end if
    call report(st, ifile, line, 'a Matrix Market stiffness starts with ''%%MatrixMarket matrix coordinate '// &
         'real symmetric'' (or general), not '''//clip(s)//'''')
  end subroutine market_banner

  subroutine market_size(st, ifile, line, s, w, map, nnz)
    !! `rows columns entries`: square, rows as the DOF map's.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    type(fields_t), intent(in) :: w
    type(dof_map_t), intent(in) :: map
    integer, intent(out) :: nnz
    integer(ip) :: v(3)
    integer :: k
    nnz = 0
    if (w%n /= 3) then
       call report(st, ifile, line, 'the Matrix Market size line has 3 numbers (rows, columns, entries), not '// &
            itoa(w%n))
       return
    end if
    do k = 1, 3
       if (.not. id_of(st, ifile, line, s(w%first(k):w%last(k)), 'size', v(k))) return
    end do
    nnz = int(v(3))
    if (v(1) /= v(2)) then
       call report(st, ifile, line, 'the matrix is '//itoa(int(v(1)))//' x '//itoa(int(v(2)))//', not square')
    else if (v(1) /= map%n) then
       call report(st, ifile, line, 'the matrix has '//itoa(int(v(1)))//' rows; its DOF map lists '// &
            itoa(map%n)//' DOFs')
    end if
  end subroutine market_size

  subroutine market_entry(st, ifile, line, s, w, map, terms)
    !! `row column value` of the coordinate format.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    type(fields_t), intent(in) :: w
    type(dof_map_t), intent(in) :: map
    type(given_b_t), intent(inout) :: terms
    integer(ip) :: i, j
    real(wp) :: v
    if (w%n /= 3) then
       call report(st, ifile, line, 'a Matrix Market entry has 3 fields (row, column, value), not '//itoa(w%n))
       return
    end if
    if (.not. id_of(st, ifile, line, s(w%first(1):w%last(1)), 'row', i)) return
    if (.not. id_of(st, ifile, line, s(w%first(2):w%last(2)), 'column', j)) return
    if (.not. value_of(st, ifile, line, s(w%first(3):w%last(3)), v)) return
    if (max(i, j) > map%n) then
       call report(st, ifile, line, 'entry ('//itoa(int(i))//', '//itoa(int(j))//') is outside the '// &
            itoa(map%n)//' DOFs of the DOF map')
       return
    end if
    if (map%node(i) == 0 .or. map%node(j) == 0) return     ! its DOF map line is reported
    call push_entry(terms, map%node(i), map%dof(i), map%node(j), map%dof(j), v, line)
  end subroutine market_entry

  subroutine read_dof_map(st, ifile, text, map)
    !! `index,node,dof` lines (a header line first), indices 1, 2, ... in
    !! order, each (node, DOF) once.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile
    character(*), intent(in) :: text
    type(dof_map_t), intent(inout) :: map
    integer(i8) :: first, last
    type(text_lines_t) :: lines
    integer :: line
    integer(ip) :: v(3)
    type(fields_t) :: f
    allocate (map%node(0), map%dof(0), map%line(0))
    do while (next_nonblank(lines, text, first, last))
       line = lines%line
       associate (s => text(first:last))
         if (scan(adjustl(s), '0123456789') /= 1) cycle     ! the header
         call split_fields(s, f)
         if (f%n /= 3) then
            call report(st, ifile, line, 'a DOF map line has 3 fields (index, node, dof), not '//itoa(f%n))
            cycle
         end if
         ! a bad line keeps its place (node 0: its entries are not read)
         if (map%n == size(map%node)) then
            map%node = [map%node, map%node, 0_ip]
            map%dof = [map%dof, map%dof, 0]
            map%line = [map%line, map%line, 0]
         end if
         map%n = map%n + 1
         map%node(map%n) = 0
         map%dof(map%n) = 0
         map%line(map%n) = line
         if (.not. id_of(st, ifile, line, s(f%first(1):f%last(1)), 'index', v(1))) cycle
         if (.not. id_of(st, ifile, line, s(f%first(2):f%last(2)), 'node', v(2))) cycle
         if (.not. id_of(st, ifile, line, s(f%first(3):f%last(3)), 'DOF', v(3))) cycle
         if (v(1) /= map%n) then
            call report(st, ifile, line, 'DOF map index '//itoa(int(v(1)))//' out of order ('// &
                 itoa(map%n)//' expected)')
         else if (v(3) > NDOF) then
            call report(st, ifile, line, 'DOF '//itoa(int(v(3)))//' is not 1 to 6')
         else
            map%node(map%n) = v(2)
            map%dof(map%n) = int(v(3))
         end if
       end associate
    end do
    call map_repeats(st, ifile, map)
  end subroutine read_dof_map

  logical function next_nonblank(r, text, first, last) result(found)
    !! The next non-blank line of text, text(first:last); false at its end.
    type(text_lines_t), intent(inout) :: r
    character(*), intent(in) :: text
    integer(i8), intent(out) :: first, last
    do
       call next_line(text, r%pos, first, last, found)
       if (.not. found) return
       r%line = r%line + 1
       if (len_trim(text(first:last)) > 0) return
    end do
  end function next_nonblank

  subroutine map_repeats(st, ifile, map)
    !! A (node, DOF) listed twice in the DOF map.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile
    type(dof_map_t), intent(in) :: map
    integer(i8), allocatable :: key(:)
    integer, allocatable :: order(:)
    integer :: k
    allocate (key(map%n))
    key(:) = int(map%node(1:map%n), i8)*KEY_BASE + map%dof(1:map%n)
    order = [(k, k=1, map%n)]
    call sort_index(key, order)
    do k = 2, map%n
       if (key(order(k)) /= key(order(k - 1)) .or. map%node(order(k)) == 0) cycle
       call report(st, ifile, map%line(max(order(k), order(k - 1))), 'node '//itoa(int(map%node(order(k))))// &
            ' DOF '//itoa(map%dof(order(k)))//' is in the DOF map twice (also line '// &
            itoa(map%line(min(order(k), order(k - 1))))//')')
    end do
  end subroutine map_repeats

  pure subroutine split_words(s, w)
    !! The blank separated words of s.
    character(*), intent(in) :: s
    type(fields_t), intent(inout) :: w
    integer :: k
    logical :: inword
    if (.not. allocated(w%first)) allocate (w%first(0), w%last(0))
    w%n = 0
    inword = .false.
    do k = 1, len(s)
       if (s(k:k) == ' ' .or. iachar(s(k:k)) == 9 .or. iachar(s(k:k)) == 13) then
          if (inword) w%last(w%n) = k - 1
          inword = .false.
       else if (.not. inword) then
          if (w%n == size(w%first)) then
             w%first = [w%first, w%first, 0]
             w%last = [w%last, w%last, 0]
          end if
          w%n = w%n + 1
          w%first(w%n) = k
          w%last(w%n) = len(s)
          inword = .true.
       end if
    end do
  end subroutine split_words

  subroutine fold_terms(st, t, g, symmetric, what)
    !! The terms t as entries of g, one per pair: a term given twice is
    !! reported; a pair given in both triangles must agree (to SYM_TOL) and
    !! counts once; in a matrix not declared symmetric each off-diagonal term
    !! needs its transposed one.
    type(deck_state_t), intent(inout) :: st
    type(given_b_t), intent(in) :: t
    type(given_b_t), intent(inout) :: g
    logical, intent(in) :: symmetric
    character(*), intent(in) :: what
    integer, allocatable :: ir(:), ic(:), order(:)
    integer(i8), allocatable :: pair(:)
    logical, allocatable :: twice(:)
    integer :: e, tr, n
    call dof_ranks(t, ir, ic, n)
    pair = int(ir - 1, i8)*n + ic
    order = [(e, e=1, t%n)]
    call sort_index(pair, order)
    allocate (twice(t%n), source=.false.)
    do e = 2, t%n
       if (pair(order(e)) /= pair(order(e - 1))) cycle
       twice(order(e)) = .true.
       call report(st, g%file, t%line(order(e)), entry_text(t, order(e))//' is given twice')
    end do
    do e = 1, t%n
       if (twice(e)) cycle
       if (ir(e) == ic(e)) then
          call push_entry(g, t%rnode(e), t%rdof(e), t%cnode(e), t%cdof(e), t%val(e), t%line(e))
          cycle
       end if
       tr = find_sorted(pair, order, int(ic(e) - 1, i8)*n + ir(e))
       if (tr == 0) then
          if (symmetric) then
             call push_entry(g, t%rnode(e), t%rdof(e), t%cnode(e), t%cdof(e), t%val(e), t%line(e))
          else if (t%val(e) /= 0.0_wp) then
             call report(st, g%file, t%line(e), what//' is not symmetric: '//entry_text(t, e)//' is '// &
                  real_text(t%val(e))//' and its transposed entry is not given')
          end if
       else if (ir(e) > ic(e)) then
          if (abs(t%val(e) - t%val(tr)) > SYM_TOL*max(abs(t%val(e)), abs(t%val(tr)))) then
             call report(st, g%file, max(t%line(e), t%line(tr)), what//' is not symmetric: '// &
                  entry_text(t, e)//' is '//real_text(t%val(e))//', the transposed one '//real_text(t%val(tr)))
          else
             call push_entry(g, t%rnode(e), t%rdof(e), t%cnode(e), t%cdof(e), &
                  0.5_wp*(t%val(e) + t%val(tr)), t%line(e))
          end if
       end if
    end do
  end subroutine fold_terms

  subroutine dof_ranks(t, ir, ic, n)
    !! The rank of each term's row and column (node, DOF) among the n
    !! distinct ones.
    type(given_b_t), intent(in) :: t
    integer, allocatable, intent(out) :: ir(:), ic(:)
    integer, intent(out) :: n
    integer(i8), allocatable :: key(:)
    integer, allocatable :: order(:), rank(:)
    integer :: k
    allocate (key(2*t%n))
    key(1:t%n) = int(t%rnode(1:t%n), i8)*KEY_BASE + t%rdof(1:t%n)
    key(t%n + 1:) = int(t%cnode(1:t%n), i8)*KEY_BASE + t%cdof(1:t%n)
    order = [(k, k=1, size(key))]
    call sort_index(key, order)
    allocate (rank(size(key)))
    n = 0
    do k = 1, size(key)
       if (k == 1) then
          n = 1
       else if (key(order(k)) /= key(order(k - 1))) then
          n = n + 1
       end if
       rank(order(k)) = n
    end do
    ir = rank(1:t%n)
    ic = rank(t%n + 1:)
  end subroutine dof_ranks

  pure function real_text(x) result(s)
    !! x with 10 significant digits.
    real(wp), intent(in) :: x
    character(:), allocatable :: s
    character(len=24) :: buf
    write (buf, '(es17.9e3)') x
    s = trim(adjustl(buf))
  end function real_text

  function entry_text(t, e) result(s)
    !! `the matrix entry of node a DOF b, node c DOF d` of entry e.
    type(given_b_t), intent(in) :: t
    integer, intent(in) :: e
    character(:), allocatable :: s
    s = 'the matrix entry of node '//itoa(int(t%rnode(e)))//' DOF '//itoa(t%rdof(e))//', node '// &
         itoa(int(t%cnode(e)))//' DOF '//itoa(t%cdof(e))
  end function entry_text

  logical function id_of(st, ifile, line, s, what, id) result(ok)
    !! A positive integer field, else reported at the file's line.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s, what
    integer(ip), intent(out) :: id
    integer :: stat
    call parse_id(s, id, stat)
    ok = stat == TOK_OK
    if (.not. ok) call report(st, ifile, line, 'invalid '//what//' '''//clip(s)//'''')
  end function id_of

  logical function value_of(st, ifile, line, s, v) result(ok)
    !! A finite real, else reported.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    real(wp), intent(out) :: v
    integer :: stat
    call parse_real(s, v, stat)
    ok = stat == TOK_OK
    if (.not. ok) call report(st, ifile, line, 'invalid matrix value '''//clip(s)//'''')
  end function value_of

  subroutine push_entry(g, rn, rd, cn, cd, v, line)
    !! Append an entry (row node, DOF; column node, DOF) = v given at line.
    type(given_b_t), intent(inout) :: g
    integer(ip), intent(in) :: rn, cn
    integer, intent(in) :: rd, cd, line
    real(wp), intent(in) :: v
    if (g%n == size(g%val)) then
       g%rnode = [g%rnode, g%rnode]
       g%cnode = [g%cnode, g%cnode]
       g%rdof = [g%rdof, g%rdof]
       g%cdof = [g%cdof, g%cdof]
       g%line = [g%line, g%line]
       g%val = [g%val, g%val]
    end if
    g%n = g%n + 1
    g%rnode(g%n) = rn
    g%cnode(g%n) = cn
    g%rdof(g%n) = rd
    g%cdof(g%n) = cd
    g%line(g%n) = line
    g%val(g%n) = v
  end subroutine push_entry
end module superjoin_deck_matrix_formats
