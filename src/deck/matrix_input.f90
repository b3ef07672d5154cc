module superjoin_deck_matrix_input
  !! Condensed parts that travel, deck side:
  !!
  !! - `*MATRIX INPUT, INPUT=file[, FORMAT=ABAQUS|CALCULIX|DMIG|MATRIX MARKET]
  !!   [, NAME=n]` inside a `*PART`
  !!   or `*SUBSTRUCTURE` block (or in MAIN): the block's stiffness is the
  !!   symmetric matrix of the file, on the (node, DOF) pairs it names (nodes of
  !!   the block, by user id). ABAQUS: Abaqus's matrix input text layout, one
  !!   entry per line `row node, row DOF, column node, column DOF, value`, either
  !!   triangle (each off-diagonal pair once). CALCULIX: the `.mtx` file that
  !!   CalculiX's `*SUBSTRUCTURE GENERATE` writes (`*USER ELEMENT` with the node
  !!   of each position in the `** ELEMENT NODES` comment, the DOF lines, then
  !!   `*MATRIX, TYPE=STIFFNESS`: the lower triangle row by row). DMIG (the
  !!   matrix NAME=n or the file's one square matrix) and MATRIX MARKET (`f.mtx`
  !!   with its DOF map `f_dofs.csv`): superjoin_deck_matrix_formats. The
  !!   condensed loads beside the matrix are read when a step's *MATRIX LOAD
  !!   names them (superjoin_deck_matrix_loads).
  !!   An instance's copy of the matrix is turned by its placement
  !!   (k' = R̂ k R̂ᵀ, R̂ = diag(R) on each node's translations and rotations;
  !!   given_turn: R̂).
  !! - `*SUBSTRUCTURE MATRIX OUTPUT, SUBSTRUCTURE=s, FILE NAME=f[, FORMAT=...]`:
  !!   write K*, f* and the boundary DOF map of s (analysis/matrix_export).
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: source_loc_t, substructure_t, model_t, given_matrix_t, matrix_export_t, &
       find_node, EXPORT_ABAQUS, EXPORT_DMIG, EXPORT_MATRIX_MARKET, EXPORT_CALCULIX
  use superjoin_deck_lexer, only: keyword_line_t, split_fields, drop_trailing_empty, &
       parse_real, parse_id, path_dirname, path_join, path_normalize, to_upper, clip, itoa, fields_t, TOK_OK
  use superjoin_deck_state, only: deck_state_t, report, report_loc, register_file, load_deck_file, given_b_t, &
       export_b_t, instance_b_t
  use superjoin_deck_cards_common, only: outside_step, check_params, get_param, get_name_param, target_sub, &
       NAME_LEN
  use superjoin_model_output_paths, only: has_control_char
  use superjoin_deck_matrix_formats, only: read_dmig, read_market, push_entry, id_of, value_of, new_given, &
       next_nonblank, text_lines_t
  implicit none (type, external)
  private

  public :: kw_matrix_input, kw_matrix_output, build_given, turn_given, build_exports, given_turn, turn_coefficient, &
       matrix_base

  integer, parameter :: NDOF = 6, BLOCK = 3
  integer, parameter :: ABAQUS_FIELDS = 5
  integer, parameter :: INITIAL_ENTRIES = 64
  character(*), parameter :: MTX_EXT = '.mtx', DOF_MAP_TAIL = '_dofs.csv'
  real(wp), parameter :: ROT_ZERO = 1.0e-12_wp
    !! Entries of an instance's rotation below this couple no DOFs.

  type :: ccx_reader_t
    !! The state of a CalculiX .mtx being read.
     integer :: section = 0                    !! 0 before *USER ELEMENT, 1: DOF lines, 2: matrix
     logical :: in_nodes = .false.            !! inside the ** ELEMENT NODES comment
     integer(ip), allocatable :: node(:)      !! node of each position
     integer :: nnode = 0
     integer :: npos = -1                     !! NODES= of *USER ELEMENT
     integer, allocatable :: first_pos(:)     !! DOF lines: the position each starts at
     type(dofs_t), allocatable :: dofs(:)     !! and its DOFs
     integer :: ndofline = 0
     real(wp), allocatable :: val(:)          !! the matrix values in order
     integer, allocatable :: vline(:)
     integer :: nval = 0
     integer :: matrix_line = 0
  end type ccx_reader_t

  type :: dofs_t
     integer, allocatable :: d(:)
  end type dofs_t

contains

  subroutine kw_matrix_input(st, kw, loc)
    !! *MATRIX INPUT: read the file now (its lines are reported by number).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: rel, path, fmt, typ, name
    logical :: found
    integer :: isub, nerr0
    type(given_b_t) :: g
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'INPUT', 'NAME', 'FORMAT', 'TYPE'], &
         [character(NAME_LEN) ::])
    call get_param(st, kw, loc, 'INPUT', .true., rel, found)
    if (.not. found) return
    call get_param(st, kw, loc, 'FORMAT', .false., fmt, found)
    if (.not. found) fmt = 'ABAQUS'
    fmt = to_upper(fmt)
    if (fmt == 'NASTRAN') fmt = 'DMIG'
    if (fmt == 'MATRIXMARKET' .or. fmt == 'MM') fmt = 'MATRIX MARKET'
    if (all(fmt /= [character(13) :: 'ABAQUS', 'CALCULIX', 'DMIG', 'MATRIX MARKET'])) then
       call report_loc(st, loc, '*MATRIX INPUT: FORMAT must be ABAQUS, CALCULIX, DMIG or MATRIX MARKET, not '// &
            clip(fmt))
       return
    end if
    call get_name_param(st, kw, loc, 'TYPE', .false., typ, found)
    if (found .and. typ /= 'STIFFNESS') then
       call report_loc(st, loc, '*MATRIX INPUT: only TYPE=STIFFNESS (linear statics), not '//clip(typ))
       return
    end if
    call get_param(st, kw, loc, 'NAME', .false., name, found)
    if (fmt /= 'DMIG' .or. .not. found) name = ''
    path = path_normalize(path_join(path_dirname(st%files(loc%file)%s), rel))
    isub = target_sub(st, loc)
    if (allocated(st%subs(isub)%given)) then
       call report_loc(st, loc, 'substructure '//st%subs(isub)%name//' has a *MATRIX INPUT already')
       return
    end if
    nerr0 = st%nerr
    g%loc = loc
    g%format = fmt
    call new_given(g)
    if (.not. read_matrix(st, fmt, path, to_upper(name), g)) return
    if (g%n == 0 .and. st%nerr == nerr0) call report_loc(st, loc, 'matrix file '''//path//''' gives no entry')
    call move_alloc_given(g, st%subs(isub)%given)
  end subroutine kw_matrix_input

  logical function read_matrix(st, fmt, path, name, g) result(ok)
    !! The entries of the matrix file `path` in format fmt into g (false when
    !! a file cannot be read); Matrix Market's DOF map is `f_dofs.csv` beside
    !! `f.mtx`.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: fmt, path, name
    type(given_b_t), intent(inout) :: g
    character(:), allocatable :: text, csv_text, base
    integer :: csv_file
    call load_deck_file(st, g%loc, path, 'matrix', text, ok)
    if (.not. ok) return
    call register_file(st, path, path, g%file)
    select case (fmt)
    case ('DMIG')
       call read_dmig(st, text, g, name)
    case ('MATRIX MARKET')
       base = matrix_base(path)
       call load_deck_file(st, g%loc, base//DOF_MAP_TAIL, 'DOF map', csv_text, ok)
       if (.not. ok) return
       call register_file(st, base//DOF_MAP_TAIL, base//DOF_MAP_TAIL, csv_file)
       call read_market(st, text, csv_file, csv_text, g)
    case default
       call read_lines(st, text, g, fmt == 'CALCULIX')
    end select
  end function read_matrix

  pure function matrix_base(path) result(base)
    !! A matrix file's path without its .mtx extension: the start of the names
    !! of the files beside it (f_dofs.csv, f_loads.mtx, f_<step>.load).
    character(*), intent(in) :: path
    character(:), allocatable :: base
    base = path
    if (len(base) > len(MTX_EXT)) then
       if (to_upper(base(len(base) - len(MTX_EXT) + 1:)) == to_upper(MTX_EXT)) base = base(:len(base) - len(MTX_EXT))
    end if
  end function matrix_base

  subroutine move_alloc_given(g, dest)
    type(given_b_t), intent(inout) :: g
    type(given_b_t), allocatable, intent(out) :: dest
    allocate (dest)
    dest%file = g%file
    dest%format = g%format
    dest%loc = g%loc
    dest%n = g%n
    call move_alloc(g%rnode, dest%rnode)
    call move_alloc(g%cnode, dest%cnode)
    call move_alloc(g%rdof, dest%rdof)
    call move_alloc(g%cdof, dest%cdof)
    call move_alloc(g%line, dest%line)
    call move_alloc(g%val, dest%val)
  end subroutine move_alloc_given

  subroutine read_lines(st, text, g, calculix)
    !! Every line of a matrix file to its reader (blank lines skipped).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text
    type(given_b_t), intent(inout) :: g
    logical, intent(in) :: calculix
    integer(i8) :: first, last
    integer :: line
    type(fields_t) :: f
    type(ccx_reader_t) :: r
    type(text_lines_t) :: lines
    if (calculix) allocate (r%node(INITIAL_ENTRIES), r%first_pos(INITIAL_ENTRIES), r%dofs(INITIAL_ENTRIES), &
         r%val(INITIAL_ENTRIES), r%vline(INITIAL_ENTRIES))
    do while (next_nonblank(lines, text, first, last))
       line = lines%line
       associate (s => text(first:last))
         call split_fields(s, f)
         call drop_trailing_empty(f)
         if (calculix) then
            call ccx_line(st, g%file, line, s, f, r)
         else
            call abaqus_line(st, g, line, s, f)
         end if
       end associate
    end do
    if (calculix) call ccx_entries(st, g, r)
  end subroutine read_lines

  subroutine abaqus_line(st, g, line, s, f)
    !! `row node, row DOF, column node, column DOF, value`; `**` comments skipped.
    type(deck_state_t), intent(inout) :: st
    type(given_b_t), intent(inout) :: g
    integer, intent(in) :: line
    character(*), intent(in) :: s
    type(fields_t), intent(in) :: f
    integer(ip) :: rn, cn
    integer :: rd, cd
    real(wp) :: v
    logical :: ok
    if (index(adjustl(s), '**') == 1) return
    if (f%n /= ABAQUS_FIELDS) then
       call report(st, g%file, line, 'a matrix line has 5 fields (row node, row DOF, column node, '// &
            'column DOF, value), not '//itoa(f%n))
       return
    end if
    ok = node_dof(st, g%file, line, fld_of(s, f, 1), fld_of(s, f, 2), rn, rd)
    if (ok) ok = node_dof(st, g%file, line, fld_of(s, f, 3), fld_of(s, f, 4), cn, cd)
    if (ok) ok = value_of(st, g%file, line, fld_of(s, f, 5), v)
    if (ok) call push_entry(g, rn, rd, cn, cd, v, line)
  end subroutine abaqus_line

  subroutine ccx_line(st, ifile, line, s, f, r)
    !! One line of a CalculiX .mtx.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    type(fields_t), intent(in) :: f
    type(ccx_reader_t), intent(inout) :: r
    character(:), allocatable :: t
    integer :: k, n0
    integer(ip) :: id
    real(wp) :: v
    t = to_upper(adjustl(s))
    if (index(t, '**') == 1) then
       if (index(t, 'ELEMENT NODES') > 0) then
          r%in_nodes = .true.
       else if (r%in_nodes) then
          do k = 1, f%n
             n0 = f%first(k)
             if (k == 1) n0 = index(s, '**') + 2
             if (.not. id_of(st, ifile, line, trim(adjustl(s(n0:f%last(k)))), 'node', id)) return
             call push_int(r%node, r%nnode, id)
          end do
       end if
       return
    end if
    r%in_nodes = .false.
    if (index(t, '*USER ELEMENT') == 1) then
       r%section = 1
       k = index(t, 'NODES=')
       if (k > 0) r%npos = leading_int(t(k + len('NODES='):))
       return
    else if (index(t, '*MATRIX') == 1) then
       r%section = 2
       r%matrix_line = line
       return
    else if (index(t, '*') == 1) then
       call report(st, ifile, line, 'unexpected keyword in a CalculiX matrix file: '//clip(s))
       return
    end if
    select case (r%section)
    case (1)
       call ccx_dof_line(st, ifile, line, s, f, r)
    case (2)
       do k = 1, f%n
          if (.not. value_of(st, ifile, line, s(f%first(k):f%last(k)), v)) return
          if (r%nval == size(r%val)) then
             r%val = [r%val, r%val]
             r%vline = [r%vline, r%vline]
          end if
          r%nval = r%nval + 1
          r%val(r%nval) = v
          r%vline(r%nval) = line
       end do
    case default
       call report(st, ifile, line, 'a data line before *USER ELEMENT in a CalculiX matrix file')
    end select
  end subroutine ccx_line

  subroutine ccx_dof_line(st, ifile, line, s, f, r)
    !! A DOF line of *USER ELEMENT: the first lists the DOFs of position 1,
    !! the next ones `position, DOF, ...` (from that position on).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: s
    type(fields_t), intent(in) :: f
    type(ccx_reader_t), intent(inout) :: r
    integer :: k, k0, p
    integer(ip) :: id
    type(dofs_t), allocatable :: tmp(:)
    p = 1
    k0 = 1
    if (r%ndofline > 0) then
       if (.not. id_of(st, ifile, line, s(f%first(1):f%last(1)), 'position', id)) return
       p = int(id)
       k0 = 2
    end if
    if (r%ndofline == size(r%first_pos)) then
       r%first_pos = [r%first_pos, r%first_pos]
       allocate (tmp(2*r%ndofline))
       tmp(1:r%ndofline) = r%dofs(1:r%ndofline)
       call move_alloc(tmp, r%dofs)
    end if
    r%ndofline = r%ndofline + 1
    r%first_pos(r%ndofline) = p
    allocate (r%dofs(r%ndofline)%d(0))
    do k = k0, f%n
       if (.not. id_of(st, ifile, line, s(f%first(k):f%last(k)), 'DOF', id)) return
       if (id > NDOF) then
          call report(st, ifile, line, 'DOF '//itoa(int(id))//' is not 1 to 6')
          return
       end if
       r%dofs(r%ndofline)%d = [r%dofs(r%ndofline)%d, int(id)]
    end do
  end subroutine ccx_dof_line

  subroutine ccx_entries(st, g, r)
    !! The entries of a CalculiX .mtx: one row per (position, DOF), the lower
    !! triangle row by row.
    type(deck_state_t), intent(inout) :: st
    type(given_b_t), intent(inout) :: g
    type(ccx_reader_t), intent(in) :: r
    integer(ip), allocatable :: rn(:)
    integer, allocatable :: rd(:)
    integer :: p, l, j, i, c
    integer(i8) :: need
    if (r%npos < 0 .or. r%matrix_line == 0) then
       call report_loc(st, g%loc, 'the CalculiX matrix file has no *USER ELEMENT, NODES= or no *MATRIX')
       return
    end if
    if (r%nnode /= r%npos) then
       call report_loc(st, g%loc, 'the CalculiX matrix file lists '//itoa(r%nnode)//' nodes in its '// &
            '** ELEMENT NODES comment for NODES='//itoa(r%npos))
       return
    end if
    allocate (rn(0), rd(0))
    l = 0
    do p = 1, r%npos
       do while (l < r%ndofline)
          if (r%first_pos(l + 1) > p) exit
          l = l + 1
       end do
       if (l == 0) cycle
       rn = [rn, [(r%node(p), j=1, size(r%dofs(l)%d))]]
       rd = [rd, r%dofs(l)%d]
    end do
    need = size(rd, kind=i8)*(size(rd, kind=i8) + 1)/2
    if (r%nval /= need) then
       call report(st, g%file, r%matrix_line, 'the matrix has '//itoa(r%nval)//' values; the lower '// &
            'triangle of its '//itoa(size(rd))//' DOFs has '//itoa(need))
       return
    end if
    c = 0
    do i = 1, size(rd)
       do j = 1, i
          c = c + 1
          call push_entry(g, rn(i), rd(i), rn(j), rd(j), r%val(c), r%vline(c))
       end do
    end do
  end subroutine ccx_entries

  pure integer function leading_int(s) result(n)
    !! The integer at the start of s (blanks skipped; -1 if none).
    character(*), intent(in) :: s
    integer :: k
    character(:), allocatable :: t
    t = adjustl(s)
    n = -1
    do k = 1, len_trim(t)
       if (t(k:k) < '0' .or. t(k:k) > '9') exit
       if (n < 0) n = 0
       n = 10*n + (iachar(t(k:k)) - iachar('0'))
    end do
  end function leading_int

  pure function fld_of(s, f, k) result(t)
    character(*), intent(in) :: s
    type(fields_t), intent(in) :: f
    integer, intent(in) :: k
    character(:), allocatable :: t
    t = s(f%first(k):f%last(k))
  end function fld_of


  logical function node_dof(st, ifile, line, sn, sd, node, dof) result(ok)
    !! A node id and a DOF 1..6.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: ifile, line
    character(*), intent(in) :: sn, sd
    integer(ip), intent(out) :: node
    integer, intent(out) :: dof
    integer(ip) :: d
    dof = 0
    ok = id_of(st, ifile, line, sn, 'node', node)
    if (.not. id_of(st, ifile, line, sd, 'DOF', d)) then
       ok = .false.
    else if (d > NDOF) then
       call report(st, ifile, line, 'DOF '//itoa(int(d))//' is not 1 to 6')
       ok = .false.
    else
       dof = int(d)
    end if
  end function node_dof


  subroutine push_int(a, n, v)
    integer(ip), allocatable, intent(inout) :: a(:)
    integer, intent(inout) :: n
    integer(ip), intent(in) :: v
    if (n == size(a)) a = [a, a]
    n = n + 1
    a(n) = v
  end subroutine push_int


  subroutine build_given(st, b, m)
    !! The given stiffness of substructure m from its *MATRIX INPUT: rows in
    !! the order of node id, then DOF. A node the block does not define, or an
    !! entry given twice, is reported at its line of the matrix file.
    type(deck_state_t), intent(inout) :: st
    type(given_b_t), intent(in) :: b
    type(substructure_t), intent(inout) :: m
    integer, allocatable :: row(:, :)     ! (6, nnode): matrix row of each node DOF
    logical, allocatable :: set(:, :)
    integer(ip) :: rl(b%n), cl(b%n)
    integer :: e, n, d
    integer(ip) :: i, v
    logical :: bad
    integer(ip), allocatable :: missing(:)   ! the nodes reported (each once)
    allocate (row(NDOF, m%nnode), source=0)
    allocate (missing(0))
    bad = .false.
    do e = 1, b%n
       rl(e) = find_node(m, b%rnode(e))
       cl(e) = find_node(m, b%cnode(e))
       if (rl(e) == 0 .or. cl(e) == 0) then
          v = b%rnode(e)
          if (rl(e) /= 0) v = b%cnode(e)
          bad = .true.
          if (any(missing == v)) cycle
          missing = [missing, v]
          call report(st, b%file, b%line(e), 'node '//itoa(int(v))//' of the matrix is not a node of '// &
               'substructure '//m%name)
          cycle
       end if
       row(b%rdof(e), rl(e)) = 1
       row(b%cdof(e), cl(e)) = 1
    end do
    if (bad) return
    allocate (m%given)
    m%given%file = st%files(b%file)%s
    n = count(row > 0)
    allocate (m%given%node(n), m%given%dof(n), m%given%k(n, n), set(n, n))
    m%given%k = 0.0_wp
    set = .false.
    n = 0
    do i = 1, m%nnode
       v = m%node_order(i)
       do d = 1, NDOF
          if (row(d, v) == 0) cycle
          n = n + 1
          row(d, v) = n
          m%given%node(n) = v
          m%given%dof(n) = d
       end do
    end do
    do e = 1, b%n
       associate (r => row(b%rdof(e), rl(e)), c => row(b%cdof(e), cl(e)))
         if (set(r, c)) then
            call report(st, b%file, b%line(e), 'the matrix entry of node '//itoa(int(b%rnode(e)))//' DOF '// &
                 itoa(b%rdof(e))//', node '//itoa(int(b%cnode(e)))//' DOF '//itoa(b%cdof(e))//' is given twice')
            cycle
         end if
         m%given%k(r, c) = b%val(e)
         m%given%k(c, r) = b%val(e)
         set(r, c) = .true.
         set(c, r) = .true.
       end associate
    end do
  end subroutine build_given

  subroutine turn_given(st, inst, m)
    !! An instance's copy of a given stiffness, turned by its placement:
    !! k ← T k Tᵀ with T = R on each node's translations and rotations. A
    !! node whose matrix lacks a component that the rotation mixes in is
    !! reported (the turned matrix would need it).
    type(deck_state_t), intent(inout) :: st
    type(instance_b_t), intent(in) :: inst
    type(substructure_t), intent(inout) :: m
    real(wp) :: t(size(m%given%dof), size(m%given%dof))
    integer :: r, a
    t = given_turn(m%given, inst%rot)
    do r = 1, size(t, 1)
       a = m%given%dof(r)
       if (abs(sum(t(r, :)**2) - 1.0_wp) > ROT_ZERO) then
          call report_loc(st, inst%loc, '*INSTANCE '//m%name//': the placement turns DOF '//itoa(a)// &
               ' of node '//itoa(int(m%node_id(m%given%node(r))))//' into DOFs that its *MATRIX INPUT '// &
               'does not give')
          return
       end if
    end do
    m%given%k = matmul(t, matmul(m%given%k, transpose(t)))
  end subroutine turn_given

  pure function given_turn(given, rot) result(t)
    !! R̂ of a given matrix's rows: rot on each node's translations and on its
    !! rotations (k' = R̂ k R̂ᵀ, f' = R̂ f).
    type(given_matrix_t), intent(in) :: given
    real(wp), intent(in) :: rot(3, 3)
    real(wp), allocatable :: t(:, :)
    integer :: n, r, c
    n = size(given%dof)
    allocate (t(n, n), source=0.0_wp)
    do r = 1, n
       do c = 1, n
          if (given%node(c) == given%node(r)) t(r, c) = turn_coefficient(rot, given%dof(r), given%dof(c))
       end do
    end do
  end function given_turn

  pure real(wp) function turn_coefficient(rot, a, b) result(x)
    !! The entry of R̂ that turns DOF b of a node into its DOF a: rot's entry
    !! when both are translations or both rotations, else 0.
    real(wp), intent(in) :: rot(3, 3)
    integer, intent(in) :: a, b
    x = 0.0_wp
    if ((a - 1)/BLOCK == (b - 1)/BLOCK) x = rot(a - (a - 1)/BLOCK*BLOCK, b - (b - 1)/BLOCK*BLOCK)
  end function turn_coefficient

  subroutine kw_matrix_output(st, kw, loc)
    !! *SUBSTRUCTURE MATRIX OUTPUT, SUBSTRUCTURE=s, FILE NAME=f[, FORMAT=...]
    !! (outside steps; the substructure is resolved after the instances).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(export_b_t) :: e
    character(:), allocatable :: value, problem
    logical :: found
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'SUBSTRUCTURE', 'FILE NAME', 'FORMAT', &
         'STIFFNESS', 'OUTPUT FILE', 'RETAIN'], [character(NAME_LEN) ::])
    call get_name_param(st, kw, loc, 'SUBSTRUCTURE', .true., e%sub, found)
    if (.not. found) return
    call get_param(st, kw, loc, 'FILE NAME', .true., value, found)
    if (.not. found) return
    problem = export_path_problem(value)
    if (len(problem) > 0) then
       call report_loc(st, loc, problem)
       return
    end if
    e%path = path_join(path_dirname(st%files(loc%file)%s), value)
    e%loc = loc
    call get_name_param(st, kw, loc, 'RETAIN', .false., value, found)
    if (found) e%retain = value
    e%format = EXPORT_ABAQUS
    call get_param(st, kw, loc, 'FORMAT', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('ABAQUS')
          e%format = EXPORT_ABAQUS
       case ('CALCULIX')
          e%format = EXPORT_CALCULIX
       case ('DMIG', 'NASTRAN')
          e%format = EXPORT_DMIG
       case ('MATRIX MARKET', 'MATRIXMARKET', 'MM')
          e%format = EXPORT_MATRIX_MARKET
       case default
          call report_loc(st, loc, '*SUBSTRUCTURE MATRIX OUTPUT: FORMAT must be ABAQUS, CALCULIX, DMIG or '// &
               'MATRIX MARKET, not '//clip(value))
          return
       end select
    end if
    if (.not. allocated(st%exports)) allocate (st%exports(0))
    st%exports = [st%exports, e]
  end subroutine kw_matrix_output

  pure function export_path_problem(path) result(msg)
    !! Why `path` cannot name the exported files ('' when it can).
    character(*), intent(in) :: path
    character(:), allocatable :: msg
    character(:), allocatable :: last
    msg = ''
    if (has_control_char(path)) then
       msg = 'the FILE NAME of *SUBSTRUCTURE MATRIX OUTPUT contains a control character'
       return
    end if
    last = path(index(path, '/', back=.true.) + 1:)
    if (len(last) == 0 .or. last == '.' .or. last == '..') msg = '*SUBSTRUCTURE MATRIX OUTPUT needs a file '// &
         'name (FILE NAME=f gives f.mtx, f.dmig or f.mtx with f_dofs.csv), not '''//path//''''
  end function export_path_problem

  subroutine retained_nodes(st, e, m, x)
    !! RETAIN=: the nodes of a node set of the exported substructure.
    type(deck_state_t), intent(inout) :: st
    type(export_b_t), intent(in) :: e
    type(substructure_t), intent(in) :: m
    type(matrix_export_t), intent(inout) :: x
    integer :: k
    do k = 1, size(m%nsets)
       if (m%nsets(k)%name /= e%retain) cycle
       x%retain = m%nsets(k)%items
       return
    end do
    call report_loc(st, e%loc, 'RETAIN='//e%retain//' names no node set of substructure '//m%name)
  end subroutine retained_nodes

  subroutine build_exports(st, model)
    !! model%exports from the *SUBSTRUCTURE MATRIX OUTPUT cards: the substructure
    !! by name (a plain one or an instance; a part is no substructure).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: i, k, j
    if (.not. allocated(st%exports)) return
    allocate (model%exports(size(st%exports)))
    do i = 1, size(st%exports)
       associate (e => st%exports(i), x => model%exports(i))
         x%format = e%format
         x%path = e%path
         x%loc = e%loc
         do k = 1, size(model%subs)
            if (model%subs(k)%name == e%sub) x%sub = k
         end do
         if (x%sub == 0) then
            call report_loc(st, e%loc, 'SUBSTRUCTURE='//e%sub//' names no substructure or '// &
                 'instance (a part is exported through one of its instances)')
         else if (allocated(e%retain)) then
            call retained_nodes(st, e, model%subs(x%sub), x)
         end if
         do j = 1, i - 1
            if (model%exports(j)%sub == x%sub .and. model%exports(j)%path == x%path .and. &
                 model%exports(j)%format == x%format) call report_loc(st, e%loc, 'the same export is asked twice')
         end do
       end associate
    end do
  end subroutine build_exports
end module superjoin_deck_matrix_input
