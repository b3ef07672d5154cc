module superjoin_deck_build_subs
  !! The substructures of the model: nodes and elements with their ids sorted,
  !! node and element sets resolved (references followed, cycles reported).
  use superjoin_kinds, only: ip, i8
  use superjoin_utils_memory, only: BYTES_INT, BYTES_REAL
  use superjoin_model_types, only: substructure_t, index_set_t, find_node, find_elem, &
       ELEMENT_NODE_COUNT, DIALECT_CALCULIX
  use superjoin_model_notes, only: append_string
  use superjoin_deck_lexer, only: itoa
  use superjoin_deck_state, only: deck_state_t, sub_b_t, chunk_t, report_loc, reading_dialect, find_set, CH_IDS, CH_GEN, memory_ok, &
       CH_RANGE, CH_REF, report_oom
  use superjoin_utils_strings, only: pick
  use superjoin_utils_grow, only: grow
  use superjoin_utils_sorting, only: sort_index
  use superjoin_deck_build_common, only: more_text, where, INITIAL_CAPACITY
  implicit none (type, external)
  private

  public :: build_sub, resolve_sets

  integer, parameter :: UNVISITED = 0, BUSY = 1, DONE = 2
    !! States of a set while the sets are resolved.

  type :: set_work_t
    !! The sets of one kind of one substructure while they are resolved.
     logical :: elem = .false.                 !! element sets (else node sets)
     character(:), allocatable :: kind_name    !! 'element set' or 'node set'
     integer :: nset = 0
     integer, allocatable :: head(:), list(:)  !! chunks of set s: list(head(s):head(s + 1) - 1)
     integer, allocatable :: state(:)          !! UNVISITED, BUSY or DONE
     integer, allocatable :: stack_set(:), stack_pos(:)
       !! depth-first stack: a set, the position in its chunk list
     integer, allocatable :: mark(:)           !! stamp of the set an item was last added to
     integer :: stamp = 0
     type(index_set_t), allocatable :: sets(:)
     integer(ip), allocatable :: items(:)      !! members of the set being built: items(1:n)
     integer :: n = 0
     integer(i8) :: failed_bytes = 0           !! > 0: items could not grow (that many bytes)
  end type set_work_t

contains

  subroutine build_sub(st, b, m)
    !! Substructure m of the model from its parser record b: nodes, elements (ids sorted), sets.
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(inout) :: b
    type(substructure_t), intent(out) :: m
    integer(ip) :: n, i, j, k, e
    integer :: a, stat, width

    m%name = b%name
    m%condense = b%condense
    m%loc = b%loc
    n = b%nnode
    m%nnode = n
    allocate (m%node_id(n), m%x(3, n), m%node_order(n), stat=stat)
    if (.not. memory_ok(st, stat, b%loc, 'the nodes of substructure '//b%name//' ('//itoa(n)//')', &
         n*(2*BYTES_INT + 3*BYTES_REAL))) return
    m%node_id(:) = b%node_id(1:n)
    m%x(:, :) = b%x(:, 1:n)
    call argsort_ids(m%node_id, m%node_order)
    if (b%node_lines == 0) call report_loc(st, b%loc, 'substructure '//b%name//' has no nodes')
    do i = 2, n
       if (m%node_id(m%node_order(i)) == m%node_id(m%node_order(i - 1))) then
          call report_loc(st, b%node_loc(m%node_order(i)), 'duplicate node id '// &
               itoa(m%node_id(m%node_order(i)))//' in substructure '//b%name//' (also defined at '// &
               where(st, b%node_loc(m%node_order(i - 1)))//')')
          if (st%aborted) return
       end if
    end do

    n = b%nelem
    m%nelem = n
    ! as many node slots per element as the largest element of this substructure has
    width = 1
    if (n > 0) width = max(1, maxval(ELEMENT_NODE_COUNT(b%elem_type(1:n))))
    allocate (m%elem_id(n), m%elem_type(n), m%elem_loc(n), m%elem_order(n), &
         m%elem_nodes(width, n), m%elem_section(n), stat=stat)
    if (.not. memory_ok(st, stat, b%loc, 'the elements of substructure '//b%name//' ('//itoa(n)//')', &
         n*((4 + width)*BYTES_INT + storage_size(b%loc)/8))) return
    m%elem_id(:) = b%elem_id(1:n)
    m%elem_type(:) = b%elem_type(1:n)
    m%elem_loc(:) = b%elem_loc(1:n)
    m%elem_section = 0
    m%elem_nodes = 0
    call argsort_ids(m%elem_id, m%elem_order)
    do i = 2, n
       if (m%elem_id(m%elem_order(i)) == m%elem_id(m%elem_order(i - 1))) then
          call report_loc(st, b%elem_loc(m%elem_order(i)), 'duplicate element id '// &
               itoa(m%elem_id(m%elem_order(i)))//' in substructure '//b%name//' (also defined at '// &
               where(st, b%elem_loc(m%elem_order(i - 1)))//')')
          if (st%aborted) return
       end if
    end do
    do e = 1, n
       do a = 1, ELEMENT_NODE_COUNT(m%elem_type(e))
          k = find_node(m, b%elem_nid(a, e))
          if (k == 0) then
             call report_loc(st, b%elem_loc(e), 'element '//itoa(m%elem_id(e))// &
                  ' refers to undefined node '//itoa(b%elem_nid(a, e))//' of substructure '//b%name)
             if (st%aborted) return
          end if
          m%elem_nodes(a, e) = k
       end do
       do a = 2, ELEMENT_NODE_COUNT(m%elem_type(e))
          do j = 1, a - 1
             if (b%elem_nid(a, e) == b%elem_nid(j, e)) then
                call report_loc(st, b%elem_loc(e), 'element '//itoa(m%elem_id(e))//' uses node '// &
                     itoa(b%elem_nid(a, e))//' twice')
             end if
          end do
       end do
    end do

    call resolve_sets(st, b, m, .false.)
    if (st%aborted) return
    call resolve_sets(st, b, m, .true.)
    allocate (m%sections(0))
    ! the builder's copies are no longer needed
    deallocate (b%node_id, b%x, b%elem_id, b%elem_type, b%elem_nid, b%pool)
  end subroutine build_sub

  subroutine resolve_sets(st, b, m, elem)
    !! Resolve the node sets (elem false) or element sets of one substructure:
    !! members in order of definition, repeats dropped, set references followed.
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(inout) :: m
    logical, intent(in) :: elem
    type(set_work_t) :: w
    integer :: s

    call start_sets(b, m, elem, w)
    if (w%failed_bytes > 0) then
       call report_oom(st, b%loc, 'the '//w%kind_name//'s of substructure '//b%name, w%failed_bytes)
       if (.not. allocated(w%sets)) allocate (w%sets(0))
       w%nset = 0
    end if
    do s = 1, w%nset
       if (w%state(s) /= UNVISITED) cycle
       call visit_set(st, b, m, w, s)
       if (st%aborted) exit
    end do
    if (elem) then
       call move_alloc(w%sets, m%elsets)
    else
       call move_alloc(w%sets, m%nsets)
    end if
  end subroutine resolve_sets

  subroutine start_sets(b, m, elem, w)
    !! The sets of one kind named, their chunks listed set by set (list(head(s) :
    !! head(s + 1) - 1) are the chunks of set s, in order), nothing visited.
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(in) :: m
    logical, intent(in) :: elem
    type(set_work_t), intent(out) :: w
    integer :: c, s, nitem, stat
    w%elem = elem
    w%kind_name = pick(elem, 'element set', 'node set')
    if (elem) then
       w%nset = b%nelset
       nitem = m%nelem
    else
       w%nset = b%nnset
       nitem = m%nnode
    end if
    allocate (w%sets(w%nset), w%head(w%nset + 1), w%list(b%nchunk), w%state(w%nset), w%stack_set(w%nset), &
         w%stack_pos(w%nset), w%mark(nitem), stat=stat)
    if (stat /= 0) then
       w%failed_bytes = (nitem + 5_i8*w%nset + b%nchunk)*BYTES_INT
       return
    end if
    w%head = 0
    do c = 1, b%nchunk
       if (b%chunks(c)%elem .eqv. elem) w%head(b%chunks(c)%set + 1) = w%head(b%chunks(c)%set + 1) + 1
    end do
    w%head(1) = 1
    do s = 1, w%nset
       w%head(s + 1) = w%head(s + 1) + w%head(s)
    end do
    w%stack_pos(1:w%nset) = w%head(1:w%nset)
    do c = 1, b%nchunk
       if (b%chunks(c)%elem .eqv. elem) then
          s = b%chunks(c)%set
          w%list(w%stack_pos(s)) = c
          w%stack_pos(s) = w%stack_pos(s) + 1
       end if
    end do
    do s = 1, w%nset
       if (elem) then
          w%sets(s)%name = b%elsets(s)%name
       else
          w%sets(s)%name = b%nsets(s)%name
       end if
    end do
    w%state = UNVISITED
    w%mark = 0
    w%stamp = 0
  end subroutine start_sets

  subroutine visit_set(st, b, m, w, s)
    !! Build set s after the sets it refers to (depth first, without recursion);
    !! unknown sets and cycles are reported.
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(in) :: m
    type(set_work_t), intent(inout) :: w
    integer, intent(in) :: s
    integer :: sp, t, c, r
    logical :: pushed
    sp = 1
    w%stack_set(1) = s
    w%stack_pos(1) = w%head(s)
    w%state(s) = BUSY
    do while (sp > 0)
       t = w%stack_set(sp)
       pushed = .false.
       do while (w%stack_pos(sp) < w%head(t + 1))
          c = w%list(w%stack_pos(sp))
          w%stack_pos(sp) = w%stack_pos(sp) + 1
          if (b%chunks(c)%kind /= CH_REF) cycle
          r = find_set(b, b%chunks(c)%ref, w%elem)
          if (r == 0) then
             call report_loc(st, b%chunks(c)%loc, w%kind_name//' '//w%sets(t)%name//' refers to unknown '// &
                  w%kind_name//' '//b%chunks(c)%ref//' of substructure '//b%name)
          else if (w%state(r) == BUSY) then
             call report_loc(st, b%chunks(c)%loc, w%kind_name//' '//w%sets(t)%name//' refers to '// &
                  w%kind_name//' '//w%sets(r)%name//', which refers back to it (cycle)')
          else if (w%state(r) == UNVISITED) then
             sp = sp + 1
             w%stack_set(sp) = r
             w%stack_pos(sp) = w%head(r)
             w%state(r) = BUSY
             pushed = .true.
             exit
          end if
       end do
       if (pushed) cycle
       call build_items(st, b, m, w, t)
       w%state(t) = DONE
       sp = sp - 1
    end do
  end subroutine visit_set

  subroutine build_items(st, b, m, w, t)
    !! The members of set t from its chunks: ids, GENERATE ranges, internal
    !! ranges and the members of the sets it refers to (built before it).
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(in) :: m
    type(set_work_t), intent(inout) :: w
    integer, intent(in) :: t
    integer :: p, r, k, ngen
    integer :: stat
    logical :: gaps
    gaps = .false.
    if (.not. allocated(w%items)) allocate (w%items(INITIAL_CAPACITY))
    w%n = 0
    w%stamp = w%stamp + 1
    do p = w%head(t), w%head(t + 1) - 1
       associate (ch => b%chunks(w%list(p)))
         select case (ch%kind)
         case (CH_IDS)
            call add_ids(st, b, m, w, t, ch)
         case (CH_GEN)
            ngen = 0
            call walk_range(m, w, ch%gen, ngen)
            gaps = gaps .or. ngen < range_count(ch%gen, largest_node_id(m))
            ! an element set may be empty because its *ELEMENT card was refused (reported)
            if (ngen == 0 .and. .not. (w%elem .and. st%elements_refused)) call report_loc(st, ch%loc, w%kind_name//' '//w%sets(t)%name// &
                 ': GENERATE '//itoa(ch%gen(1))//', '//itoa(ch%gen(2))//', '//itoa(ch%gen(3))// &
                 ' matches no defined id')
         case (CH_RANGE)
            do k = ch%start, ch%start + ch%count - 1
               call add(w, int(k, ip))
            end do
         case (CH_REF)
            r = find_set(b, ch%ref, w%elem)
            if (r > 0) then
               if (w%state(r) == DONE) then
                  gaps = gaps .or. allocated(w%sets(r)%print_ranges)
                  do k = 1, size(w%sets(r)%items)
                     call add(w, w%sets(r)%items(k))
                  end do
               end if
            end if
         end select
       end associate
    end do
    if (w%failed_bytes == 0) then
       allocate (w%sets(t)%items(w%n), stat=stat)
       if (stat /= 0) w%failed_bytes = w%n*storage_size(w%items)/8
    end if
    if (w%failed_bytes > 0) then
       call report_oom(st, b%loc, 'the '//w%kind_name//' '//w%sets(t)%name, w%failed_bytes)
       return
    end if
    w%sets(t)%items(:) = w%items(1:w%n)
    if (gaps .and. .not. w%elem) call print_ranges(b, m, w, t)
  end subroutine build_items

  pure integer(ip) function largest_node_id(m)
    !! The largest node id of m (0: no nodes).
    type(substructure_t), intent(in) :: m
    largest_node_id = 0
    if (m%nnode > 0) largest_node_id = m%node_id(m%node_order(m%nnode))
  end function largest_node_id

  pure integer function range_count(gen, top)
    !! How many ids first, first+inc, ... <= last GENERATE range gen has up to id top.
    integer(ip), intent(in) :: gen(3), top
    range_count = 0
    if (top >= gen(1)) range_count = int((min(gen(2), top) - gen(1))/gen(3)) + 1
  end function range_count

  subroutine print_ranges(b, m, w, t)
    !! The ids CalculiX's .dat prints for node set t, whose GENERATE ranges (or
    !! a set it refers to) pass over undefined ids: as ccx, every id of a range
    !! up to the largest node id (an undefined one prints zeros), in order; kept
    !! as ranges, never expanded here.
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(in) :: m
    type(set_work_t), intent(inout) :: w
    integer, intent(in) :: t
    integer(ip), allocatable :: ranges(:, :)
    integer(ip) :: top
    integer :: p, k, n, r
    top = largest_node_id(m)
    allocate (ranges(3, INITIAL_CAPACITY))
    n = 0
    do p = w%head(t), w%head(t + 1) - 1
       associate (ch => b%chunks(w%list(p)))
         select case (ch%kind)
         case (CH_IDS)
            do k = ch%start, ch%start + ch%count - 1
               if (find_node(m, b%pool(k)) > 0) call push_range(ranges, n, [b%pool(k), b%pool(k), 1_ip])
            end do
         case (CH_GEN)
            if (ch%gen(1) <= min(ch%gen(2), top)) call push_range(ranges, n, [ch%gen(1), min(ch%gen(2), top), ch%gen(3)])
         case (CH_RANGE)
            do k = ch%start, ch%start + ch%count - 1
               call push_range(ranges, n, [m%node_id(k), m%node_id(k), 1_ip])
            end do
         case (CH_REF)
            r = find_set(b, ch%ref, .false.)
            if (r <= 0) cycle
            if (w%state(r) /= DONE) cycle
            if (allocated(w%sets(r)%print_ranges)) then
               do k = 1, size(w%sets(r)%print_ranges, 2)
                  call push_range(ranges, n, w%sets(r)%print_ranges(:, k))
               end do
            else
               do k = 1, size(w%sets(r)%items)
                  call push_range(ranges, n, [m%node_id(w%sets(r)%items(k)), m%node_id(w%sets(r)%items(k)), 1_ip])
               end do
            end if
         end select
       end associate
    end do
    w%sets(t)%print_ranges = ranges(:, 1:n)
  end subroutine print_ranges

  pure subroutine push_range(ranges, n, range)
    !! Appends column `range` (first, last, step) to ranges(:, 1:n); one id
    !! next after a step-1 range ending just before it extends that range.
    integer(ip), allocatable, intent(inout) :: ranges(:, :)
    integer, intent(inout) :: n
    integer(ip), intent(in) :: range(3)
    integer(ip), allocatable :: tmp(:, :)
    if (n > 0 .and. range(1) == range(2)) then
       if (ranges(3, n) == 1 .and. ranges(2, n) == range(1) - 1) then
          ranges(2, n) = range(1)
          return
       end if
    end if
    if (n == size(ranges, 2)) then
       allocate (tmp(3, 2*n))
       tmp(:, 1:n) = ranges(:, 1:n)
       call move_alloc(tmp, ranges)
    end if
    n = n + 1
    ranges(:, n) = range
  end subroutine push_range

  subroutine add_ids(st, b, m, w, t, ch)
    !! The members of a chunk of ids of set t (undefined ids reported).
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(in) :: m
    type(set_work_t), intent(inout) :: w
    integer, intent(in) :: t
    type(chunk_t), intent(in) :: ch
    integer :: nbad, k
    integer(ip) :: id, bad_id, i
    nbad = 0
    bad_id = 0
    do k = ch%start, ch%start + ch%count - 1
       id = b%pool(k)
       if (w%elem) then
          i = find_elem(m, id)
       else
          i = find_node(m, id)
       end if
       if (i == 0) then
          nbad = nbad + 1
          if (nbad == 1) bad_id = id
       else
          call add(w, i)
       end if
    end do
    if (nbad == 0 .or. (w%elem .and. st%elements_refused)) return
    if (reading_dialect(st) == DIALECT_CALCULIX) then
       ! ccx passes over them in silence (gmsh's .inp lists the faces of a physical surface,
       ! which users delete, in the surface's *ELSET): said in the listing, not an error.
       call append_string(st%notes, w%kind_name//' '//w%sets(t)%name//' at '//where(st, ch%loc)// &
            ': undefined '//pick(w%elem, 'element', 'node')//' '//itoa(bad_id)//more_text(nbad - 1)// &
            ' left out, as CalculiX does (Abaqus: an error)')
    else
       call report_loc(st, ch%loc, w%kind_name//' '//w%sets(t)%name//': undefined '// &
            pick(w%elem, 'element', 'node')//' '//itoa(bad_id)//more_text(nbad - 1))
    end if
  end subroutine add_ids

  subroutine add(w, i)
    !! Member i of the set being built (once).
    type(set_work_t), intent(inout) :: w
    integer(ip), intent(in) :: i
    integer :: stat
    if (w%mark(i) == w%stamp .or. w%failed_bytes > 0) return
    w%mark(i) = w%stamp
    call grow(w%items, w%n, INITIAL_CAPACITY, stat)
    if (stat /= 0) then
       w%failed_bytes = 2*size(w%items, kind=i8)*storage_size(w%items)/8
       return
    end if
    w%n = w%n + 1
    w%items(w%n) = i
  end subroutine add

  subroutine walk_range(m, w, gen, count)
    !! Members with ids first, first+inc, ... <= last that exist (walks the
    !! sorted ids, so sparse huge ranges cost nothing).
    type(substructure_t), intent(in) :: m
    type(set_work_t), intent(inout) :: w
    integer(ip), intent(in) :: gen(3)
    integer, intent(inout) :: count
    integer(ip) :: lo, hi, mid, nn, idv
    if (w%elem) then
       nn = m%nelem
    else
       nn = m%nnode
    end if
    lo = 1
    hi = nn + 1
    do while (lo < hi)
       mid = lo + (hi - lo)/2
       if (sorted_id(m, w%elem, mid) < gen(1)) then
          lo = mid + 1
       else
          hi = mid
       end if
    end do
    do while (lo <= nn)
       idv = sorted_id(m, w%elem, lo)
       if (idv > gen(2)) exit
       if (mod(int(idv, i8) - gen(1), int(gen(3), i8)) == 0) then
          count = count + 1
          if (w%elem) then
             call add(w, m%elem_order(lo))
          else
             call add(w, m%node_order(lo))
          end if
       end if
       lo = lo + 1
    end do
  end subroutine walk_range

  pure integer(ip) function sorted_id(m, elem, k)
    !! The k-th smallest element (elem) or node id of m.
    type(substructure_t), intent(in) :: m
    logical, intent(in) :: elem
    integer(ip), intent(in) :: k
    if (elem) then
       sorted_id = m%elem_id(m%elem_order(k))
    else
       sorted_id = m%node_id(m%node_order(k))
    end if
  end function sorted_id

  subroutine argsort_ids(ids, order)
    !! order = permutation sorting ids ascending (stable; O(n) when already sorted).
    integer(ip), intent(in) :: ids(:)
    integer(ip), intent(out) :: order(:)
    integer(ip) :: i
    do i = 1, size(ids, kind=ip)   ! a loop: an array constructor's temporary is not checked
       order(i) = i
    end do
    call sort_index(ids, order)
  end subroutine argsort_ids
end module superjoin_deck_build_subs
