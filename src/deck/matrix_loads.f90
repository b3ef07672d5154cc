module superjoin_deck_matrix_loads
  !! Condensed loads that travel with an imported matrix (issue 26):
  !!
  !! `*MATRIX LOAD[, OP=NEW|MOD]` in a step, data lines `substructure or
  !! instance, load name, magnitude` (as Abaqus's *SLOAD: element, load case,
  !! magnitude): the named load vector of the block's *MATRIX INPUT, times the
  !! magnitude, on the instance's nodes, turned by its placement as its matrix
  !! is (f' = R̂ f). The load is read from the files beside the matrix:
  !!
  !! - ABAQUS, CALCULIX (`f.mtx`): the file `f_<name>.load` (`node, DOF,
  !!   value` lines, as the export writes one per step: <name> is the step);
  !! - DMIG: a load matrix (IFO=9, Nastran's P2G=) of the same file: `NAME(k)`
  !!   its column k, `NAME` a matrix of one column, `k` column k of the file's
  !!   one load matrix (OptiStruct's P2GSUB = NAME(k));
  !! - MATRIX MARKET: `k`, column k of `f_loads.mtx` (rows: `f_dofs.csv`).
  !!
  !! Step rules as *CLOAD's (CalculiX): OP=NEW drops the matrix loads of the
  !! previous step, OP=MOD keeps them (the default in a *STATIC step, not in a
  !! step without a procedure card), a line naming the same substructure and
  !! load again replaces its magnitude (Abaqus's *SLOAD, OP=MOD); matrix loads
  !! and *CLOAD lines are kept or dropped apart. In effect, a load is a set
  !! of concentrated loads on the DOFs of the matrix.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: model_t, cload_t, substructure_t, source_loc_t
  use superjoin_deck_lexer, only: to_upper, split_fields, drop_trailing_empty, fields_t, itoa, clip
  use superjoin_deck_state, only: deck_state_t, report, report_loc, register_file, load_deck_file, given_b_t, &
       SUBK_INSTANCE
  use superjoin_deck_records, only: mload_b_t
  use superjoin_deck_cards_common, only: field_count, fld, get_real
  use superjoin_deck_matrix_formats, only: read_dmig_load, read_market_load, push_entry, id_of, value_of, &
       new_given, next_nonblank, text_lines_t
  use superjoin_deck_matrix_input, only: turn_coefficient, matrix_base
  use superjoin_deck_build_common, only: keeps_previous
  use superjoin_utils_sorting, only: sort_index, find_sorted
  implicit none (type, external)
  private

  public :: data_matrix_load, build_matrix_loads, CARD_MATRIX_LOAD

  integer, parameter :: CARD_MATRIX_LOAD = 209
    !! *MATRIX LOAD data lines (superjoin_deck_parser)
  integer, parameter :: NDOF = 6, KEY_BASE = 8, LOAD_FIELDS = 3, INITIAL_LINES = 4
  character(*), parameter :: LOAD_EXT = '.load', LOADS_TAIL = '_loads.mtx', &
       DOF_MAP_TAIL = '_dofs.csv'

  type :: active_t
    !! A matrix load in effect in a step.
     integer :: isub = 0                   !! the loaded substructure (model%subs)
     integer :: c = 0                      !! its load vector (the cache of build_matrix_loads)
     real(wp) :: scale = 1.0_wp
     type(source_loc_t) :: loc             !! the *MATRIX LOAD line
  end type active_t

  type :: load_vec_t
    !! A load read for a block: its values on the rows of the block's matrix.
     character(:), allocatable :: key      !! block name // '|' // load name (upper case)
     logical :: ok = .false.               !! read without error
     real(wp), allocatable :: f(:)
  end type load_vec_t

contains

  subroutine data_matrix_load(st, line, loc)
    !! A data line of *MATRIX LOAD: substructure or instance, load name, magnitude.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(mload_b_t) :: ml
    type(mload_b_t), allocatable :: grown(:)
    if (.not. field_count(st, loc, LOAD_FIELDS, LOAD_FIELDS, 'substructure or instance, load name, magnitude')) &
         return
    ml%sub = to_upper(trim(adjustl(fld(st, line, 1))))
    ml%load = trim(adjustl(fld(st, line, 2)))
    if (len(ml%sub) == 0 .or. len(ml%load) == 0) then
       call report_loc(st, loc, '*MATRIX LOAD needs a substructure or instance and a load name')
       return
    end if
    if (.not. get_real(st, line, loc, 3, ml%scale)) return
    ml%loc = loc
    associate (s => st%steps(st%card_item))
      if (.not. allocated(s%mloads)) allocate (s%mloads(INITIAL_LINES))
      if (s%nmload == size(s%mloads)) then
         allocate (grown(2*s%nmload))
         grown(1:s%nmload) = s%mloads
         call move_alloc(grown, s%mloads)
      end if
      s%nmload = s%nmload + 1
      s%mloads(s%nmload) = ml
    end associate
  end subroutine data_matrix_load

  subroutine build_matrix_loads(st, model)
    !! The *MATRIX LOAD lines of every step as concentrated loads of the step
    !! (after its *CLOAD ones, whose history and nodal systems are done: the
    !! matrix loads have their own history and are global components). A step
    !! that keeps the previous step's loads (OP=MOD, or a *STATIC step by
    !! default: keeps_previous) keeps its matrix
    !! loads too, but for those its own lines name again (same substructure
    !! and load: the new magnitude replaces the old).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(load_vec_t), allocatable :: cache(:)
    type(active_t), allocatable :: active(:), own(:)
    type(cload_t), allocatable :: add(:)
    logical, allocatable :: keep(:)
    integer :: s, k
    allocate (cache(0), active(0))
    do s = 1, st%nstep
       if (.not. keeps_previous(st%steps(s), st%steps(s)%mload_op)) active = active(1:0)
       allocate (own(0))
       do k = 1, st%steps(s)%nmload
          call resolve_line(st, model, st%steps(s)%mloads(k), cache, own)
          if (st%aborted) return
       end do
       keep = [(.not. any(own%isub == active(k)%isub .and. own%c == active(k)%c), k=1, size(active))]
       model%steps(s)%kept_mloads = count(keep)
       if (count(keep) > 0) model%steps(s)%kept_from = model%steps(s - 1)%name
       active = [pack(active, keep), own]
       deallocate (own)
       if (size(active) == 0) cycle
       allocate (add(0))
       do k = 1, size(active)
          call expand(model%subs(active(k)%isub), active(k), cache(active(k)%c)%f, add)
       end do
       model%steps(s)%cloads = [model%steps(s)%cloads, add]
       deallocate (add)
    end do
  end subroutine build_matrix_loads

  subroutine resolve_line(st, model, ml, cache, own)
    !! One *MATRIX LOAD line: its substructure and its load (read once per
    !! block and load name), appended to own when both are good.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(mload_b_t), intent(in) :: ml
    type(load_vec_t), allocatable, intent(inout) :: cache(:)
    type(active_t), allocatable, intent(inout) :: own(:)
    integer :: isub, iblock, c, r
    character(:), allocatable :: key
    isub = loaded_sub(st, model, ml)
    if (isub == 0) return
    iblock = block_of(st, model, isub)
    if (iblock == 0) return                       ! its *MATRIX INPUT failed: reported there
    key = st%subs(iblock)%name//'|'//to_upper(ml%load)
    c = 0
    do r = 1, size(cache)
       if (cache(r)%key == key) c = r
    end do
    if (c == 0) then
       call grow_cache(cache, key)
       c = size(cache)
       call read_load(st, st%subs(iblock)%given, model%subs(isub), ml, cache(c))
    end if
    if (cache(c)%ok) call grow_active(own, active_t(isub=isub, c=c, scale=ml%scale, loc=ml%loc))
  end subroutine resolve_line

  subroutine grow_cache(cache, key)
    !! One more load vector, keyed `key`, at the end of cache (grown by hand: an
    !! array constructor of a type with a deferred-length component leaks it in gfortran 12).
    type(load_vec_t), allocatable, intent(inout) :: cache(:)
    character(*), intent(in) :: key
    type(load_vec_t), allocatable :: more(:)
    integer :: k
    allocate (more(size(cache) + 1))
    do k = 1, size(cache)
       call move_alloc(cache(k)%key, more(k)%key)
       more(k)%ok = cache(k)%ok
       if (allocated(cache(k)%f)) call move_alloc(cache(k)%f, more(k)%f)
    end do
    more(size(more))%key = key
    call move_alloc(more, cache)
  end subroutine grow_cache

  subroutine grow_active(own, a)
    !! a appended to own (grown by hand, as grow_cache).
    type(active_t), allocatable, intent(inout) :: own(:)
    type(active_t), intent(in) :: a
    type(active_t), allocatable :: more(:)
    integer :: k
    allocate (more(size(own) + 1))
    do k = 1, size(own)
       more(k) = own(k)
    end do
    more(size(more)) = a
    call move_alloc(more, own)
  end subroutine grow_active

  subroutine expand(m, a, f0, add)
    !! The concentrated loads of an active matrix load on substructure m:
    !! scale * R̂ f0 on every row of its matrix, appended to add.
    type(substructure_t), intent(in) :: m
    type(active_t), intent(in) :: a
    real(wp), intent(in) :: f0(:)
    type(cload_t), allocatable, intent(inout) :: add(:)
    real(wp) :: f(size(f0))
    type(cload_t), allocatable :: more(:)
    integer :: r, e, i, j
    f = 0.0_wp
    r = 1
    do while (r <= size(f))                       ! rows r..e: the DOFs of one node
       e = r
       do while (e < size(f))
          if (m%given%node(e + 1) /= m%given%node(r)) exit
          e = e + 1
       end do
       do i = r, e
          do j = r, e
             f(i) = f(i) + turn_coefficient(m%rot, m%given%dof(i), m%given%dof(j))*f0(j)
          end do
       end do
       r = e + 1
    end do
    f = a%scale*f
    allocate (more(size(f)))
    do r = 1, size(f)
       more(r) = cload_t(sub=a%isub, node=m%given%node(r), dof=m%given%dof(r), value=f(r), loc=a%loc)
    end do
    add = [add, more]
  end subroutine expand

  integer function loaded_sub(st, model, ml) result(isub)
    !! The substructure or instance a line names, with a matrix of its own (0
    !! and reported otherwise).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(mload_b_t), intent(in) :: ml
    integer :: k
    isub = 0
    do k = 1, size(model%subs)
       if (model%subs(k)%name == ml%sub) isub = k
    end do
    if (isub == 0) then
       if (allocated(model%parts)) then
          if (any([(model%parts(k)%s == ml%sub, k=1, size(model%parts))])) then
             call report_loc(st, ml%loc, '*MATRIX LOAD: '//ml%sub//' is a part: its instances are loaded')
             return
          end if
       end if
       call report_loc(st, ml%loc, '*MATRIX LOAD: '//ml%sub//' names no substructure or instance')
    else if (.not. allocated(model%subs(isub)%given)) then
       call report_loc(st, ml%loc, '*MATRIX LOAD on '//ml%sub//', whose stiffness is not an imported matrix '// &
            '(no *MATRIX INPUT; its loads are *CLOAD and *DLOAD lines)')
       isub = 0
    end if
  end function loaded_sub

  integer function block_of(st, model, isub) result(j)
    !! The block of the deck (a part or a substructure) whose *MATRIX INPUT
    !! substructure isub took (0 when it has none).
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    character(:), allocatable :: name
    integer :: k
    name = model%subs(isub)%name
    if (model%subs(isub)%part > 0) name = model%parts(model%subs(isub)%part)%s
    j = 0
    do k = 1, st%nsub
       if (st%subs(k)%kind == SUBK_INSTANCE .or. st%subs(k)%name /= name) cycle
       if (allocated(st%subs(k)%given)) j = k
    end do
  end function block_of

  subroutine read_load(st, g, m, ml, vec)
    !! Load ml%load of the matrix g (the *MATRIX INPUT of m's block) on the
    !! rows of m's matrix, in the block's own frame.
    type(deck_state_t), intent(inout) :: st
    type(given_b_t), intent(in) :: g
    type(substructure_t), intent(in) :: m
    type(mload_b_t), intent(in) :: ml
    type(load_vec_t), intent(inout) :: vec
    type(given_b_t) :: v
    character(:), allocatable :: path, text
    logical :: found
    integer :: nerr0
    nerr0 = st%nerr
    path = st%files(g%file)%s
    call new_given(v)
    select case (g%format)
    case ('DMIG')
       v%file = g%file
       call load_deck_file(st, ml%loc, path, 'matrix', text, found)
       if (found) call read_dmig_load(st, text, g%file, ml%load, ml%loc, v, found)
    case ('MATRIX MARKET')
       call market_load(st, matrix_base(path), ml, v, found)
    case default
       call text_load(st, matrix_base(path), ml, v, found)
    end select
    if (.not. found .or. st%nerr /= nerr0) return
    call load_on_rows(st, m, ml, v, vec)
  end subroutine read_load

  subroutine market_load(st, base, ml, v, found)
    !! Column k (the load name) of base_loads.mtx.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: base
    type(mload_b_t), intent(in) :: ml
    type(given_b_t), intent(inout) :: v
    logical, intent(out) :: found
    character(:), allocatable :: text, map_text
    integer :: col, map_file, nerr0
    logical :: there
    found = .false.
    col = column_number(ml%load)
    inquire (file=base//LOADS_TAIL, exist=there)
    if (.not. there) then
       call report_loc(st, ml%loc, 'unknown load '//ml%load//': no file '//base//LOADS_TAIL//' beside the matrix')
       return
    else if (col == 0) then
       call report_loc(st, ml%loc, 'unknown load '//ml%load//': a Matrix Market load is a column number of '// &
            base//LOADS_TAIL)
       return
    end if
    call load_deck_file(st, ml%loc, base//LOADS_TAIL, 'load', text, found)
    if (found) call load_deck_file(st, ml%loc, base//DOF_MAP_TAIL, 'DOF map', map_text, found)
    if (.not. found) return
    call register_file(st, base//LOADS_TAIL, base//LOADS_TAIL, v%file)
    call register_file(st, base//DOF_MAP_TAIL, base//DOF_MAP_TAIL, map_file)
    nerr0 = st%nerr
    call read_market_load(st, text, v%file, map_text, map_file, col, v, found)
    if (.not. found .and. st%nerr == nerr0) call report_loc(st, ml%loc, 'unknown load '//ml%load//': '// &
         base//LOADS_TAIL//' has fewer columns')
  end subroutine market_load

  pure integer function column_number(s) result(n)
    !! The positive integer s (0 if it is none).
    character(*), intent(in) :: s
    integer :: k
    n = 0
    if (len_trim(s) == 0 .or. len_trim(s) > 9 .or. verify(trim(s), '0123456789') /= 0) return
    do k = 1, len_trim(s)
       n = 10*n + (iachar(s(k:k)) - iachar('0'))
    end do
  end function column_number

  subroutine text_load(st, base, ml, v, found)
    !! base_<name>.load (name as written, else in upper case): `node, DOF,
    !! value` lines, `**` comments.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: base
    type(mload_b_t), intent(in) :: ml
    type(given_b_t), intent(inout) :: v
    logical, intent(out) :: found
    character(:), allocatable :: path, text
    logical :: there
    integer(i8) :: first, last
    type(text_lines_t) :: lines
    path = base//'_'//ml%load//LOAD_EXT
    inquire (file=path, exist=there)
    if (.not. there) then
       path = base//'_'//to_upper(ml%load)//LOAD_EXT
       inquire (file=path, exist=there)
    end if
    found = .false.
    if (.not. there) then
       call report_loc(st, ml%loc, 'unknown load '//ml%load//': no file '//path//' beside the matrix')
       return
    end if
    call load_deck_file(st, ml%loc, path, 'load', text, found)
    if (.not. found) return
    call register_file(st, path, path, v%file)
    do while (next_nonblank(lines, text, first, last))
       call load_line(st, v, lines%line, text(first:last))
    end do
  end subroutine text_load

  subroutine load_line(st, v, line, s)
    !! `node, DOF, value` (a `**` comment skipped).
    type(deck_state_t), intent(inout) :: st
    type(given_b_t), intent(inout) :: v
    integer, intent(in) :: line
    character(*), intent(in) :: s
    type(fields_t) :: f
    integer(ip) :: node, dof
    real(wp) :: x
    if (index(adjustl(s), '**') == 1) return
    call split_fields(s, f)
    call drop_trailing_empty(f)
    if (f%n /= LOAD_FIELDS) then
       call report(st, v%file, line, 'a load line has 3 fields (node, DOF, value), not '//itoa(f%n))
       return
    end if
    if (.not. id_of(st, v%file, line, s(f%first(1):f%last(1)), 'node', node)) return
    if (.not. id_of(st, v%file, line, s(f%first(2):f%last(2)), 'DOF', dof)) return
    if (dof > NDOF) then
       call report(st, v%file, line, 'DOF '//itoa(int(dof))//' is not 1 to 6')
       return
    end if
    if (.not. value_of(st, v%file, line, s(f%first(3):f%last(3)), x)) return
    call push_entry(v, node, int(dof), 0_ip, 0, x, line)
  end subroutine load_line

  subroutine load_on_rows(st, m, ml, v, vec)
    !! The entries v on the rows of m's matrix; an entry on a DOF the matrix
    !! does not have, or given twice, is reported at its line.
    type(deck_state_t), intent(inout) :: st
    type(substructure_t), intent(in) :: m
    type(mload_b_t), intent(in) :: ml
    type(given_b_t), intent(in) :: v
    type(load_vec_t), intent(inout) :: vec
    integer(i8), allocatable :: key(:)
    integer, allocatable :: order(:)
    logical, allocatable :: set(:)
    integer :: n, e, r, nerr0
    n = size(m%given%dof)
    allocate (key(n), set(n), vec%f(n))
    key = int(m%node_id(m%given%node), i8)*KEY_BASE + m%given%dof
    order = [(r, r=1, n)]
    call sort_index(key, order)
    set = .false.
    vec%f = 0.0_wp
    nerr0 = st%nerr
    do e = 1, v%n
       r = find_sorted(key, order, int(v%rnode(e), i8)*KEY_BASE + v%rdof(e))
       if (r == 0) then
          call report(st, v%file, v%line(e), 'load '//ml%load//': node '//itoa(int(v%rnode(e)))//' DOF '// &
               itoa(v%rdof(e))//' is not a DOF of the matrix of '//clip(m%given%file))
       else if (set(r)) then
          call report(st, v%file, v%line(e), 'load '//ml%load//': node '//itoa(int(v%rnode(e)))//' DOF '// &
               itoa(v%rdof(e))//' is given twice')
       else
          set(r) = .true.
          vec%f(r) = v%val(e)
       end if
    end do
    vec%ok = st%nerr == nerr0
  end subroutine load_on_rows
end module superjoin_deck_matrix_loads
