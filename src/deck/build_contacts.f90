module superjoin_deck_build_contacts
  !! Contacts and supports of the model: *CONTACT lines resolved to node pairs
  !! (PAIR=NEAREST included), merged per pair, and *SUPPORT lines to nodes.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: model_t, link_t, support_t, NDOF_NODE, LINK_FINITE, LINK_RIGID
  use superjoin_deck_lexer, only: itoa, plural
  use superjoin_deck_state, only: deck_state_t, ref_t, report_loc, report_oom
  use superjoin_deck_build_common, only: ref_subs, sub_index, ref_text, resolve_items, part_hint, &
       INITIAL_CAPACITY, where
  use superjoin_deck_assembly, only: pair_nearest
  implicit none (type, external)
  private

  public :: build_contacts, build_supports, support_list

  integer, parameter :: INITIAL_HASH = 64
  integer(i8), parameter :: HASH_MUL1 = 2654435761_i8, HASH_MUL2 = 40503_i8
    !! Multipliers of the link hash (products stay below 2**63).
  integer(i8), parameter :: PAIR_SHIFT = 2147483648_i8   !! 2**31: key = master*2**31 + slave
  integer(i8), parameter :: EMPTY_KEY = -1_i8
  type :: pair_map_t
    !! Open-addressing map from a (master, slave) pair key to a link index.
     integer :: n = 0
     integer(i8), allocatable :: keys(:)
     integer, allocatable :: vals(:)
  end type pair_map_t
  type :: link_list_t
    !! Growing list of links / supports while they are generated.
     integer :: n = 0
     type(link_t), allocatable :: a(:)
     integer, allocatable :: first_line(:, :)   !! (NDOF_NODE, capacity): *CONTACT line that gave each DOF, 0 none
  end type link_list_t

contains

  subroutine build_contacts(st, model)
    !! The contact elements of the model: every *CONTACT line resolved to node pairs, one link per pair and DOF range.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(link_list_t) :: links
    type(pair_map_t) :: map
    integer(ip), allocatable :: ms(:), ss(:)
    integer :: l, cur, il, nself, stat
    integer(ip) :: p, np, mnode, snode
    logical :: ok1, ok2, added
    logical, allocatable :: usable(:)
    integer(i8) :: failed_bytes

    call contact_cards(st, model, usable)

    allocate (links%a(INITIAL_CAPACITY), links%first_line(NDOF_NODE, INITIAL_CAPACITY))
    cur = 0
    do l = 1, st%ncline
       if (st%aborted) return
       associate (cl => st%clines(l))
         if (.not. usable(cl%contact)) cycle
         if (cl%contact /= cur) then
            cur = cl%contact
            call map_reset(map)
         end if
         associate (c => model%contacts(cur))
           call resolve_items(st, model, c%master_sub, cl%master, .false., cl%loc, ms, ok1)
           call resolve_items(st, model, c%slave_sub, cl%slave, .false., cl%loc, ss, ok2)
           if (.not. (ok1 .and. ok2)) cycle
           if (st%contacts(cur)%nearest) then
              call pair_nearest(st, model, cur, cl%loc, ms, ss, ok1)
              if (.not. ok1) cycle
           end if
           if (size(ms) /= size(ss)) then
              if (.not. cl%master%is_set .or. .not. cl%slave%is_set) then
                 call report_loc(st, cl%loc, 'node '//ref_text(pick_node(cl%master, cl%slave))// &
                      ' is paired with node set '//pick_set_name(cl%master, cl%slave)//' of '// &
                      plural(max(size(ms), size(ss)), 'node')//' (a single node pairs only with a one-node set)')
              else
                 call report_loc(st, cl%loc, 'node sets '//cl%master%set//' ('//plural(size(ms), 'node')// &
                      ') and '//cl%slave%set//' ('//plural(size(ss), 'node')//') differ in size')
              end if
              cycle
           end if
           np = size(ms, kind=ip)
           nself = 0
           do p = 1, np
              mnode = ms(p)
              snode = ss(p)
              if (c%master_sub == c%slave_sub .and. mnode == snode) then
                 nself = nself + 1
                 if (nself == 1) call report_loc(st, cl%loc, 'node '//itoa(model%subs(c%master_sub)%node_id(mnode))// &
                      ' of substructure '//model%subs(c%master_sub)%name//' is in contact with itself')
                 cycle
              end if
              call map_get_or_add(map, int(mnode, i8)*PAIR_SHIFT + snode, links%n + 1, il, added, failed_bytes)
              if (failed_bytes > 0) then
                 call report_oom(st, cl%loc, 'the node pairs of contact '//c%name, failed_bytes)
                 return
              end if
              if (added) then
                 call push_link(links, int(np - p + 1), failed_bytes)
                 if (failed_bytes > 0) then
                    call report_oom(st, cl%loc, 'the contact elements ('// &
                         itoa(max(2*links%n, links%n + int(np - p + 1)))//')', failed_bytes)
                    return
                 end if
                 links%a(il)%contact = cur
                 links%a(il)%master_node = mnode
                 links%a(il)%slave_node = snode
                 links%a(il)%loc = cl%loc
              end if
              if (.not. first_definition(st, links, il, l)) exit
              call merge_dofs(links%a(il), cl%first, cl%last, cl%state, cl%g)
           end do
         end associate
       end associate
    end do
    if (links%n == size(links%a)) then   ! filled exactly: no copy
       call move_alloc(links%a, model%links)
       return
    end if
    allocate (model%links(links%n), stat=stat)
    if (stat /= 0) then
       call report_oom(st, st%contacts(max(cur, 1))%loc, 'the contact elements ('//itoa(links%n)//')', &
            links%n*int(storage_size(links%a(1))/8, i8))
       return
    end if
    model%links(:) = links%a(1:links%n)
  end subroutine build_contacts

  subroutine contact_cards(st, model, usable)
    !! model%contacts from the *CONTACT cards (substructures and orientation
    !! resolved); usable(k): both substructures of card k exist.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    logical, allocatable, intent(out) :: usable(:)
    integer :: k, l
    allocate (model%contacts(st%ncontact), usable(st%ncontact))
    do k = 1, st%ncontact
       associate (cb => st%contacts(k), c => model%contacts(k))
         c%name = cb%name
         c%loc = cb%loc
         c%master_sub = sub_index(model, cb%master)
         c%remote = cb%remote
         c%rigid_offset = cb%rigid_offset
         c%slave_sub = sub_index(model, cb%slave)
         if (c%master_sub == 0) call report_loc(st, cb%loc, 'unknown substructure '//cb%master//' in MASTER='// &
              part_hint(model, cb%master))
         if (c%slave_sub == 0) call report_loc(st, cb%loc, 'unknown substructure '//cb%slave//' in SLAVE='// &
              part_hint(model, cb%slave))
         c%orientation = 0
         if (allocated(cb%orientation)) then
            if (len(cb%orientation) > 0) then
               do l = 1, size(model%orientations)
                  if (model%orientations(l)%name == cb%orientation) c%orientation = l
               end do
               if (c%orientation == 0) call report_loc(st, cb%loc, 'unknown orientation '//cb%orientation)
            end if
         end if
         usable(k) = c%master_sub > 0 .and. c%slave_sub > 0
       end associate
    end do
  end subroutine contact_cards

  logical function first_definition(st, links, il, l) result(ok)
    !! Whether *CONTACT line l is the first to give its DOFs to link il (then
    !! they are recorded as its); a DOF given twice in one *CONTACT is an error
    !! naming the line of its first definition.
    type(deck_state_t), intent(inout) :: st
    type(link_list_t), intent(inout) :: links
    integer, intent(in) :: il, l
    integer :: d
    associate (cl => st%clines(l))
      do d = cl%first, cl%last
         ok = links%first_line(d, il) == 0
         if (ok) cycle
         call report_loc(st, cl%loc, 'DOF '//itoa(d)//' of contact '//st%contacts(cl%contact)%name// &
              ' is given twice between the same nodes (first at '//where(st, st%clines(links%first_line(d, il))%loc)// &
              '): one line per DOF')
         return
      end do
      links%first_line(cl%first:cl%last, il) = l
    end associate
    ok = .true.
  end function first_definition

  pure function pick_node(a, b) result(r)
    type(ref_t), intent(in) :: a, b
    type(ref_t) :: r
    if (.not. a%is_set) then
       r = a
    else
       r = b
    end if
  end function pick_node

  pure function pick_set_name(a, b) result(s)
    type(ref_t), intent(in) :: a, b
    character(:), allocatable :: s
    if (a%is_set) then
       s = a%set
    else
       s = b%set
    end if
  end function pick_set_name

  pure subroutine merge_dofs(link, first, last, state, g)
    !! Add one contact line's DOFs to a link (each DOF comes from one line: first_definition).
    type(link_t), intent(inout) :: link
    integer, intent(in) :: first, last, state
    real(wp), intent(in) :: g
    integer :: d
    do d = first, last
       select case (state)
       case (LINK_RIGID)
          link%state(d) = LINK_RIGID
          link%g(d) = 0.0_wp
       case (LINK_FINITE)
          if (link%state(d) /= LINK_RIGID) then
             link%state(d) = LINK_FINITE
             link%g(d) = link%g(d) + g
          end if
       end select
    end do
  end subroutine merge_dofs

  subroutine push_link(list, left, failed_bytes)
    !! Append a fresh link. When the list is full it grows to twice its size,
    !! or to room for the `left` pairs still to come of the current line
    !! when that is more (one copy for a long line instead of one per doubling).
    type(link_list_t), intent(inout) :: list
    integer, intent(in) :: left
    integer(i8), intent(out) :: failed_bytes
    type(link_t), allocatable :: tmp(:)
    integer, allocatable :: lines(:, :)
    integer :: stat, cap
    failed_bytes = 0
    if (list%n == size(list%a)) then
       cap = max(2*list%n, list%n + left)
       allocate (tmp(cap), lines(NDOF_NODE, cap), stat=stat)
       if (stat /= 0) then
          failed_bytes = int(cap, i8)*(storage_size(list%a(1)) + NDOF_NODE*storage_size(stat))/8
          return
       end if
       tmp(1:list%n) = list%a(1:list%n)
       call move_alloc(tmp, list%a)
       if (allocated(list%first_line)) lines(:, 1:list%n) = list%first_line(:, 1:list%n)
       call move_alloc(lines, list%first_line)
    end if
    list%n = list%n + 1
    list%a(list%n) = link_t()
    if (allocated(list%first_line)) list%first_line(:, list%n) = 0
  end subroutine push_link

  subroutine map_reset(map)
    type(pair_map_t), intent(inout) :: map
    if (allocated(map%keys)) deallocate (map%keys, map%vals)
    allocate (map%keys(0:INITIAL_HASH - 1), map%vals(0:INITIAL_HASH - 1))
    map%keys = EMPTY_KEY
    map%n = 0
  end subroutine map_reset

  pure integer function slot_of(key, mask) result(h)
    integer(i8), intent(in) :: key
    integer, intent(in) :: mask
    integer(i8) :: m, s, x
    m = key/PAIR_SHIFT
    s = mod(key, PAIR_SHIFT)
    x = ieor(m*HASH_MUL1, s*HASH_MUL2 + ishft(m, 7))
    x = ieor(x, ishft(x, -29))
    h = int(iand(x, int(mask, i8)))
  end function slot_of

  subroutine map_get_or_add(map, key, newval, val, added, failed_bytes)
    !! Value stored for `key`; when absent, `newval` is stored and `added` is true.
    !! failed_bytes > 0: the map could not grow (that many bytes), nothing stored.
    type(pair_map_t), intent(inout) :: map
    integer(i8), intent(in) :: key
    integer, intent(in) :: newval
    integer, intent(out) :: val
    logical, intent(out) :: added
    integer(i8), intent(out) :: failed_bytes
    integer :: h, mask
    failed_bytes = 0
    val = 0
    added = .false.
    if (2*(map%n + 1) > size(map%keys)) call rehash
    if (failed_bytes > 0) return
    mask = size(map%keys) - 1
    h = slot_of(key, mask)
    do
       if (map%keys(h) == key) then
          val = map%vals(h)
          added = .false.
          return
       end if
       if (map%keys(h) == EMPTY_KEY) exit
       h = iand(h + 1, mask)
    end do
    map%keys(h) = key
    map%vals(h) = newval
    map%n = map%n + 1
    val = newval
    added = .true.
  contains
    subroutine rehash
      integer(i8), allocatable :: ok(:), nk(:)
      integer, allocatable :: ov(:), nv(:)
      integer :: i, nmask, j, stat
      allocate (nk(0:2*size(map%keys) - 1), nv(0:2*size(map%keys) - 1), stat=stat)
      if (stat /= 0) then
         failed_bytes = 2*size(map%keys, kind=i8)*(storage_size(key) + storage_size(val))/8
         return
      end if
      call move_alloc(map%keys, ok)
      call move_alloc(map%vals, ov)
      call move_alloc(nk, map%keys)
      call move_alloc(nv, map%vals)
      map%keys = EMPTY_KEY
      nmask = size(map%keys) - 1
      do i = 0, size(ok) - 1
         if (ok(i) == EMPTY_KEY) cycle
         j = slot_of(ok(i), nmask)
         do while (map%keys(j) /= EMPTY_KEY)
            j = iand(j + 1, nmask)
         end do
         map%keys(j) = ok(i)
         map%vals(j) = ov(i)
      end do
    end subroutine rehash
  end subroutine map_get_or_add

  subroutine build_supports(st, model)
    !! The supports of the model, from the *SUPPORT lines.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    call support_list(st, model, 0, model%supports)
  end subroutine build_supports

  subroutine support_list(st, model, step, out)
    !! The supported DOFs of the *SUPPORT and *BOUNDARY lines of a step (0: model data).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: step
    type(support_t), allocatable, intent(out) :: out(:)
    type(support_t), allocatable :: list(:), tmp(:)
    integer(ip), allocatable :: nodes(:)
    integer :: k, n, isub, d, stat, m
    integer(ip) :: i
    integer, allocatable :: subs(:)
    logical :: ok
    allocate (list(INITIAL_CAPACITY))
    n = 0
    do k = 1, st%nsupport
       if (st%aborted) return
       if (st%supports(k)%step /= step) cycle
       associate (sb => st%supports(k))
         call ref_subs(st, model, sb%ref, sb%loc, 'node', subs)   ! several: a set over instances
         do m = 1, size(subs)
            isub = subs(m)
            call resolve_items(st, model, isub, sb%ref, .false., sb%loc, nodes, ok)
            if (.not. ok) cycle
            do i = 1, size(nodes, kind=ip)
               do d = 1, NDOF_NODE
                  if (.not. sb%dofs(d)) cycle
                  if (n == size(list)) then
                     allocate (tmp(2*n), stat=stat)
                     if (stat /= 0) then
                        call report_oom(st, sb%loc, 'the supported DOFs ('//itoa(2*n)//')', &
                             2*int(n, i8)*storage_size(list(1))/8)
                        return
                     end if
                     tmp(1:n) = list(1:n)
                     call move_alloc(tmp, list)
                  end if
                  n = n + 1
                  list(n)%sub = isub
                  list(n)%node = nodes(i)
                  list(n)%dof = d
                  list(n)%state = sb%state
                  list(n)%g = sb%g
                  list(n)%value = sb%value
                  list(n)%loc = sb%loc
                  list(n)%from_boundary = sb%boundary
                  ! FIXED: the previous step's displacement, filled in by the driver; in the
                  ! first step and in model data the initial state's, 0 (as ccx 2.20)
                  if (sb%held .and. step > 1) list(n)%held_from = step - 1
               end do
            end do
         end do
       end associate
    end do
    ! explicit allocation: an assignment's reallocation would not report failure
    allocate (out(n), stat=stat)
    if (stat /= 0) then
       call report_oom(st, st%supports(st%nsupport)%loc, 'the supported DOFs ('//itoa(n)//')', &
            int(n, i8)*storage_size(list(1))/8)
       return
    end if
    out(1:n) = list(1:n)
  end subroutine support_list

end module superjoin_deck_build_contacts
