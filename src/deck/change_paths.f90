module superjoin_deck_change_paths
  !! *CHANGE CONTACT of a contact declared inside a part made of parts, resolved
  !! once the parts are unfolded (superjoin_deck_nesting names each placed copy
  !! of a part's contact by its instance path: `B.F3.J1`):
  !!
  !! - `NAME=B.F3.J1`, or `B.F3.J1` as the first field of a line without
  !!   NAME=: that contact in that one placed instance (Abaqus's
  !!   instance-qualified name). Every name of the path but the last is a
  !!   placed instance: the first an *INSTANCE of *ASSEMBLY, each next one an
  !!   *INSTANCE inside the part of the previous. The node pairs of a NAME=
  !!   card are written as in the part's *CONTACT (`BAY1.E`) or by their whole
  !!   path (`B.F3.BAY1.E`).
  !! - `PART=FLOOR` with `NAME=J1` (or lines `J1, ...`): contact J1 of part
  !!   FLOOR in every placed instance of FLOOR, as Abaqus changes a part's
  !!   definition (one line per instance, in the order of the instances; the
  !!   name may be a path inside the part: `PART=BUILDING, NAME=F3.J1`).
  !! - a part's contact by its own name (`NAME=J1`, J1 declared inside *PART
  !!   FLOOR and not in *ASSEMBLY) is an error that says how to name one
  !!   instance's copy or every instance's.
  !!
  !! Errors (file:line of the card for NAME= and PART=, once per card; of the
  !! data line for a line's own contact): an instance the path does not reach,
  !! a path through something that is not a placed instance (a *PART, a
  !! *SUBSTRUCTURE, an *INSTANCE inside a part), an instance without that
  !! contact, a part's contact by its own name (the parts that declare it), a
  !! part path that ends more than one contact's path, PART= of no part or of
  !! a part placed by no instance, a node outside the contact's substructures.
  use superjoin_model_types, only: source_loc_t
  use superjoin_deck_lexer, only: itoa, plural
  use superjoin_deck_build_common, only: ref_text
  use superjoin_deck_state, only: deck_state_t, report_loc, grow, contact_b_t, override_b_t, ref_t, &
       SUBK_PART
  use superjoin_deck_cards_assembly, only: find_part
  use superjoin_utils_strings, only: pick
  implicit none (type, external)
  private

  public :: resolve_change_paths

  type :: card_targets_t
    !! The contacts of the last NAME= card resolved (its data lines share them).
     type(source_loc_t) :: card_loc          !! that card (line 0: none yet)
     integer, allocatable :: contacts(:)     !! indices in st%contacts (none: in error, reported)
  end type card_targets_t

  integer, parameter :: MAX_LISTED = 3       !! names listed in a message before `...`

contains

  subroutine resolve_change_paths(st, templates)
    !! Every *CHANGE CONTACT line of the steps that names its contact by path,
    !! by a part's own name or with PART= (o%path): one line per contact it
    !! reaches (o%contact set), or none when in error (reported). templates:
    !! the contacts declared inside parts (owner: the part), for the messages.
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: templates(:)
    type(override_b_t), allocatable :: lines(:), out(:)
    type(card_targets_t) :: last
    integer :: s, j, n
    integer, parameter :: INITIAL_LINES = 4
    do s = 1, st%nstep
       if (st%steps(s)%noverride == 0) cycle
       lines = st%steps(s)%overrides(1:st%steps(s)%noverride)
       if (.not. any([(allocated(lines(j)%path), j=1, size(lines))])) cycle
       n = 0
       allocate (out(INITIAL_LINES))
       do j = 1, size(lines)
          if (allocated(lines(j)%path)) then
             call resolve_line(st, templates, lines(j), last, out, n)
          else
             call grow(out, n, INITIAL_LINES)
             n = n + 1
             out(n) = lines(j)
          end if
       end do
       st%steps(s)%noverride = n
       call move_alloc(out, st%steps(s)%overrides)
    end do
  end subroutine resolve_change_paths

  subroutine resolve_line(st, templates, o, last, out, n)
    !! Line o: one line per contact it reaches appended to out(1:n), its node
    !! scopes written as the contact's substructures (errors reported once).
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: templates(:)
    type(override_b_t), intent(in) :: o
    type(card_targets_t), intent(inout) :: last
    type(override_b_t), allocatable, intent(inout) :: out(:)
    integer, intent(inout) :: n
    integer, allocatable :: ks(:)
    type(override_b_t) :: one
    logical :: ok
    integer :: i
    if (o%named) then   ! the lines of one NAME= card share its contacts (reported once)
       if (.not. same_loc(last%card_loc, o%card_loc)) then
          last%card_loc = o%card_loc
          call targets(st, templates, o, o%card_loc, last%contacts)
       end if
       ks = last%contacts
    else
       call targets(st, templates, o, o%loc, ks)
    end if
    do i = 1, size(ks)
       one = o
       deallocate (one%path)
       if (allocated(one%part)) deallocate (one%part)
       one%contact = ks(i)
       if (.not. o%whole) then
          call rescope(st, one%master, ks(i), 'master', o%loc, i == 1, allocated(o%part), ok)
          if (ok) call rescope(st, one%slave, ks(i), 'slave', o%loc, i == 1, allocated(o%part), ok)
          if (.not. ok) return
       end if
       call grow(out, n, size(ks))
       n = n + 1
       out(n) = one
    end do
  end subroutine resolve_line

  subroutine targets(st, templates, o, at, ks)
    !! The contacts that line o names (reported at `at` when none).
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: templates(:)
    type(override_b_t), intent(in) :: o
    type(source_loc_t), intent(in) :: at
    integer, allocatable, intent(out) :: ks(:)
    integer :: k
    allocate (ks(0))
    if (allocated(o%part)) then
       call part_targets(st, templates, o%part, o%path, at, ks)
    else if (index(o%path, '.') == 0) then
       call report_part_contact(st, templates, o%path, at)
    else
       k = path_contact(st, o%path, at, .true.)
       if (k > 0) ks = [k]
    end if
  end subroutine targets

  subroutine part_targets(st, templates, part, name, at, ks)
    !! PART=part: contact `name` (the part's own name, or a path inside the
    !! part) in every placed instance of the part, in their order.
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: templates(:)
    character(*), intent(in) :: part, name
    type(source_loc_t), intent(in) :: at
    integer, allocatable, intent(inout) :: ks(:)
    integer, allocatable :: insts(:)
    integer :: p, i, k
    p = find_part(st, part)
    if (p == 0) then
       call report_loc(st, at, '*CHANGE CONTACT, PART='//part//': no *PART '//part//what_else(st, part))
       return
    end if
    if (index(name, '.') == 0 .and. .not. declares(templates, p, name)) then
       call report_loc(st, at, '*CHANGE CONTACT, PART='//part//': *PART '//part//' has no contact '//name// &
            part_contacts(templates, p))
       return
    end if
    insts = placed_of(st, part)
    if (size(insts) == 0) then
       call report_loc(st, at, '*CHANGE CONTACT, PART='//part//': no *INSTANCE places *PART '//part// &
            ' (the card would change nothing)')
       return
    end if
    do i = 1, size(insts)
       k = path_contact(st, st%subs(insts(i))%name//'.'//name, at, i == 1)
       if (k == 0) then
          deallocate (ks)
          allocate (ks(0))
          return
       end if
       ks = [ks, k]
    end do
  end subroutine part_targets

  integer function path_contact(st, path, at, loud) result(k)
    !! The contact of instance path `path` (`B.F3.J1`): every name before the
    !! last a placed instance, each inside the previous one's part (0 when not;
    !! reported at `at` when loud).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: path
    type(source_loc_t), intent(in) :: at
    logical, intent(in) :: loud
    integer :: a, dot, prev, j
    character(:), allocatable :: near
    prev = 0
    a = 1
    k = 0
    do
       dot = index(path(a:), '.')
       if (dot == 0) exit
       j = placed(st, path(1:a + dot - 2))
       if (j == 0) then
          if (loud) call report_loc(st, at, '*CHANGE CONTACT of contact '//path//': '// &
               missing_instance(st, path, a, dot, prev))
          return
       end if
       prev = j
       a = a + dot
    end do
    do k = 1, st%ncontact
       if (st%contacts(k)%owner == 0 .and. st%contacts(k)%name == path) return
    end do
    k = 0
    if (.not. loud) return
    near = hint(st, path(a:), path(1:a - 1))   ! inside the instance first
    if (len(near) == 0) near = hint(st, path(a:), '')
    call report_loc(st, at, '*CHANGE CONTACT of contact '//path//': instance '//st%subs(prev)%name// &
         ' (*PART '//st%instances(st%subs(prev)%inst)%part//') has no contact '//path(a:)//near)
  end function path_contact

  function missing_instance(st, path, a, dot, prev) result(msg)
    !! Why path(1:a+dot-2) is not a placed instance (prev: the instance before it, 0: none).
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: path
    integer, intent(in) :: a, dot, prev
    character(:), allocatable :: msg, name
    integer :: j
    name = path(a:a + dot - 2)
    if (prev > 0) then
       msg = 'instance '//st%subs(prev)%name//' (*PART '//st%instances(st%subs(prev)%inst)%part// &
            ') has no instance '//name
       return
    end if
    msg = 'no *INSTANCE '//name//' in *ASSEMBLY'
    do j = 1, st%nsub
       if (st%subs(j)%name /= name) cycle
       if (st%subs(j)%kind == SUBK_PART) then
          msg = name//' is a *PART, not an instance (an instance path starts at an *INSTANCE of *ASSEMBLY; '// &
               'to change the contact in every instance of the part: PART='//name//', NAME='//path(a + dot:)//')'
          return
       else if (st%subs(j)%inst == 0) then
          msg = name//' is a *SUBSTRUCTURE, not an instance (its contacts are the assembly''s, named '// &
               'without a path)'
          return
       else if (st%instances(st%subs(j)%inst)%owner > 0) then
          msg = msg//' ('//name//' is an *INSTANCE inside *PART '// &
               st%subs(st%instances(st%subs(j)%inst)%owner)%name//', whose copies are named by their whole '// &
               'instance path'//copies(st, name)//')'//hint(st, path, '')
          return
       end if
    end do
    msg = msg//hint(st, path, '')
  end function missing_instance

  function hint(st, tail, under) result(s)
    !! The contacts whose instance path ends with `.tail` (and starts with
    !! `under`): one (`; did you mean X?`), several (ambiguous: the first of
    !! them), or none (empty).
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: tail, under
    character(:), allocatable :: s
    integer :: k, n
    s = ''
    n = 0
    do k = 1, st%ncontact
       if (st%contacts(k)%owner > 0 .or. index(st%contacts(k)%name, under) /= 1) cycle
       if (ends_with(st%contacts(k)%name, '.'//tail)) call add_listed(s, n, st%contacts(k)%name)
    end do
    if (n == 1) s = '; did you mean '//s//'?'
    if (n > 1) s = '; '//plural(n, 'contact')//' end so, the path is ambiguous: '//s//' (write the whole path)'
  end function hint

  function copies(st, name) result(s)
    !! The placed instances whose path ends with `.name` (the copies of an
    !! *INSTANCE inside a part): ` (B.F1, B.F2, ...)`, or empty.
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    character(:), allocatable :: s
    integer :: j, n
    s = ''
    n = 0
    do j = 1, st%nsub
       if (placed(st, st%subs(j)%name) == j .and. ends_with(st%subs(j)%name, '.'//name)) &
            call add_listed(s, n, st%subs(j)%name)
    end do
    if (n > 0) s = ': '//s
  end function copies

  subroutine add_listed(s, n, name)
    !! name appended to the list s of n names (after MAX_LISTED of them: `...`, once).
    character(:), allocatable, intent(inout) :: s
    integer, intent(inout) :: n
    character(*), intent(in) :: name
    n = n + 1
    if (n == 1) then
       s = name
    else if (n <= MAX_LISTED) then
       s = s//', '//name
    else if (n == MAX_LISTED + 1) then
       s = s//', ...'
    end if
  end subroutine add_listed

  pure logical function ends_with(s, tail)
    !! s ends with tail and is longer.
    character(*), intent(in) :: s, tail
    ends_with = len(s) > len(tail)
    if (ends_with) ends_with = s(len(s) - len(tail) + 1:) == tail
  end function ends_with

  subroutine report_part_contact(st, templates, name, at)
    !! A part's contact named by its own name: which parts declare it, and how
    !! to name one instance's copy or every instance's.
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: templates(:)
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: at
    character(:), allocatable :: parts, example
    integer, allocatable :: owners(:), insts(:)
    integer :: j
    allocate (owners(0))
    do j = 1, size(templates)
       if (templates(j)%name == name .and. .not. any(owners == templates(j)%owner)) &
            owners = [owners, templates(j)%owner]
    end do
    do j = 1, st%ncontact   ! parts that are not made of parts keep theirs
       if (st%contacts(j)%owner > 0 .and. st%contacts(j)%name == name .and. &
            .not. any(owners == st%contacts(j)%owner)) owners = [owners, st%contacts(j)%owner]
    end do
    if (size(owners) == 0) then   ! (the parser defers only names that a part's contact has)
       call report_loc(st, at, '*CHANGE CONTACT of unknown contact '//name)
       return
    end if
    parts = st%subs(owners(1))%name
    do j = 2, size(owners)
       parts = parts//', '//st%subs(owners(j))%name
    end do
    example = ''
    insts = placed_of(st, st%subs(owners(1))%name)
    if (size(insts) > 0) example = ', as '//st%subs(insts(1))%name//'.'//name
    if (size(owners) == 1) then
       call report_loc(st, at, '*CHANGE CONTACT of contact '//name//', which is declared inside *PART '//parts// &
            ': name the copy of one instance by its instance path'//example//', or change it in every instance '// &
            'of the part with PART='//parts)
    else
       call report_loc(st, at, '*CHANGE CONTACT of contact '//name//', which is declared inside '// &
            itoa(size(owners))//' parts ('//parts//'), not in *ASSEMBLY: name the copy of one instance by its '// &
            'instance path'//example//', or choose the part with PART=')
    end if
  end subroutine report_part_contact

  subroutine rescope(st, ref, k, role, at, loud, part_form, ok)
    !! A node of a NAME= line: its scope, as in the part's *CONTACT (`BAY1`) or
    !! whole (`B.F3.BAY1`), made the contact's master or slave substructure; any
    !! other scope reported (when loud). part_form (PART=, every instance's
    !! copy): only the part's own scope; a whole path names one copy and is
    !! reported (it would change that copy only).
    type(deck_state_t), intent(inout) :: st
    type(ref_t), intent(inout) :: ref
    integer, intent(in) :: k
    character(*), intent(in) :: role
    type(source_loc_t), intent(in) :: at
    logical, intent(in) :: loud, part_form
    logical, intent(out) :: ok
    character(:), allocatable :: sub, inst, name
    type(ref_t) :: in_part
    ok = .true.
    if (.not. allocated(ref%scope)) return
    name = st%contacts(k)%name
    sub = pick(role == 'master', st%contacts(k)%master, st%contacts(k)%slave)
    inst = name(1:index(name, '.', back=.true.) - 1)
    if (ref%scope == sub .and. part_form) then
       ok = .false.
       in_part = ref
       in_part%scope = sub(len(inst) + 2:)
       if (loud) call report_loc(st, at, 'node '''//ref_text(ref)//''' names the copy of one instance by its '// &
            'whole path, but PART= changes the contact in every instance: write it as the part''s *CONTACT '// &
            'does, '//ref_text(in_part))
       return
    end if
    if (ref%scope == sub) return
    ok = inst//'.'//ref%scope == sub
    if (ok) then
       ref%scope = sub
    else if (loud) then
       in_part = ref
       in_part%scope = sub(len(inst) + 2:)
       call report_loc(st, at, 'node '''//ref_text(ref)//''' is not in the '//role//' substructure '//sub// &
            ' of contact '//name//' (write it as the part''s *CONTACT does, '//ref_text(in_part)// &
            ', or by its whole path)')
    end if
  end subroutine rescope

  function placed_of(st, part) result(insts)
    !! The placed instances of `part` (entries of st%subs, in order).
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: part
    integer, allocatable :: insts(:)
    integer :: j
    allocate (insts(0))
    do j = 1, st%nsub
       if (st%subs(j)%inst == 0) cycle
       if (st%instances(st%subs(j)%inst)%owner > 0) cycle
       if (st%instances(st%subs(j)%inst)%part == part) insts = [insts, j]
    end do
  end function placed_of

  integer function placed(st, name) result(j)
    !! The placed instance named `name` (an *INSTANCE of *ASSEMBLY or an
    !! unfolded copy, `B.F3`; not an *INSTANCE inside a part): its entry in st%subs, 0 if none.
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    do j = 1, st%nsub
       if (st%subs(j)%inst == 0 .or. st%subs(j)%name /= name) cycle
       if (st%instances(st%subs(j)%inst)%owner == 0) return
    end do
    j = 0
  end function placed

  function what_else(st, name) result(s)
    !! What `name` is when it is not a part (for PART=).
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    character(:), allocatable :: s
    integer :: j
    s = ''
    do j = 1, st%nsub
       if (st%subs(j)%name /= name) cycle
       s = pick(st%subs(j)%inst > 0, ' ('//name//' is an *INSTANCE: to change the contact in that '// &
            'instance only, NAME='//name//'.<contact>)', ' ('//name//' is a *SUBSTRUCTURE)')
       return
    end do
  end function what_else

  function part_contacts(templates, p) result(s)
    !! ` (its contacts: J1, J2, ...)` for part p, or ` (it declares no *CONTACT)`.
    type(contact_b_t), intent(in) :: templates(:)
    integer, intent(in) :: p
    character(:), allocatable :: s
    integer :: j, n
    s = ''
    n = 0
    do j = 1, size(templates)
       if (templates(j)%owner == p) call add_listed(s, n, templates(j)%name)
    end do
    s = pick(n == 0, ' (it declares no *CONTACT)', ' (its contacts: '//s//')')
  end function part_contacts

  pure logical function declares(templates, p, name)
    !! Part p declares a contact `name`.
    type(contact_b_t), intent(in) :: templates(:)
    integer, intent(in) :: p
    character(*), intent(in) :: name
    integer :: j
    declares = .false.
    do j = 1, size(templates)
       if (templates(j)%owner == p .and. templates(j)%name == name) declares = .true.
    end do
  end function declares

  pure logical function same_loc(a, b)
    !! The same file and line.
    type(source_loc_t), intent(in) :: a, b
    same_loc = a%file == b%file .and. a%line == b%line
  end function same_loc
end module superjoin_deck_change_paths
