module superjoin_deck_build_common
  !! What the builders of the validation pass share: references resolved to
  !! substructures and to node or element indices, the part hint of their
  !! messages, file:line and '(and N more)' texts.
  use superjoin_kinds, only: ip, i8
  use superjoin_model_types, only: model_t, source_loc_t, find_node, find_elem
  use superjoin_deck_lexer, only: itoa
  use superjoin_deck_state, only: deck_state_t, ref_t, report_loc, report_oom, step_b_t, OP_MOD, OP_DEFAULT, MAIN_NAME, &
       find_set, SUBK_INSTANCE, SUBK_NESTED
  use superjoin_utils_strings, only: pick
  implicit none (type, external)
  private

  public :: resolve_sub, ref_subs, plain_set_subs, sub_index, ref_text, resolve_items, broken_sub, part_hint, keeps_previous, more_text, &
       where, instances_hint, INITIAL_CAPACITY

  integer, parameter :: INITIAL_CAPACITY = 16

contains

  integer function resolve_sub(st, model, ref, loc, what) result(isub)
    !! The one substructure a reference points to (ref_subs); 0 and reported
    !! when there is none, or when it names an assembly-level set over several
    !! instances (the caller's members must lie in one substructure).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(ref_t), intent(in) :: ref
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: what
    integer, allocatable :: subs(:)
    character(:), allocatable :: names
    integer :: k
    call ref_subs(st, model, ref, loc, what, subs)
    isub = 0
    if (size(subs) == 1) isub = subs(1)
    if (size(subs) < 2) return
    names = model%subs(subs(1))%name
    do k = 2, size(subs)
       names = names//', '//model%subs(subs(k))%name
    end do
    call report_loc(st, loc, pick(what == 'node', 'node set ', 'element set ')//ref%set//' spans '// &
         itoa(size(subs))//' substructures ('//names// &
         ': an assembly-level set over several instances); here its members must lie in one: name one '// &
         'instance''s, as '//model%subs(subs(1))%name//'.'//ref%set)
  end function resolve_sub

  subroutine ref_subs(st, model, ref, loc, what, subs)
    !! The substructures a reference covers (loads, supports, temperatures;
    !! the output requests resolve their own through plain_set_subs too): its
    !! scope's (SUB.x), its home's (a card in
    !! a block), else MAIN, for a plain set name as plain_set_subs says (the
    !! members of an assembly-level set over several instances, in card
    !! order); empty and reported when it is in none.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(ref_t), intent(in) :: ref
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: what
    integer, allocatable, intent(out) :: subs(:)
    character(:), allocatable :: hint
    integer :: isub
    allocate (subs(0))
    if (allocated(ref%scope)) then
       isub = sub_index(model, ref%scope)
       if (isub == 0) call report_loc(st, loc, 'unknown substructure '//ref%scope//' in '// &
            ref_text(ref)//part_hint(model, ref%scope))
       if (isub > 0) subs = [isub]
    else if (ref%home > 0) then
       subs = [ref%home]
    else
       isub = sub_index(model, MAIN_NAME)
       if (ref%is_set) then
          subs = plain_set_subs(st, model, ref%set, what /= 'node', isub)
       else if (isub > 0) then
          subs = [isub]
       end if
       if (size(subs) > 0) return
       hint = ''
       if (ref%is_set) hint = instances_hint(model, ref%set, what /= 'node')   ! a part's set, named plainly
       call report_loc(st, loc, what//' '//ref_text(ref)// &
            ' is not in a substructure: outside *SUBSTRUCTURE blocks write SUB.id or SUB.set '// &
            '(no nodes were defined outside the blocks, so there is no substructure MAIN)'//hint)
    end if
  end subroutine ref_subs

  function plain_set_subs(st, model, name, elem, main) result(subs)
    !! Substructures of a set named plainly at model level (main: MAIN, 0 if
    !! none), as Abaqus reads an assembly's set names: MAIN's set (the
    !! assembly's own); else an assembly-level set (*NSET/*ELSET, INSTANCE=),
    !! the union of its members, instance by instance in the order of their
    !! first cards (assembly scope before the part sets of the instances);
    !! else the one instance that has a set of that name (a part's set);
    !! else [main] (its set is reported unknown there), empty without MAIN.
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    logical, intent(in) :: elem
    integer, intent(in) :: main
    integer, allocatable :: subs(:)
    integer :: i, nfound, owner
    if (main > 0) then
       if (sub_has_set(model, main, name, elem)) then
          subs = [main]
          return
       end if
    end if
    subs = assembly_members(st, model, name, elem)
    if (size(subs) > 0) return
    nfound = 0
    owner = 0
    do i = 1, size(model%subs)
       if (model%subs(i)%part == 0) cycle
       if (sub_has_set(model, i, name, elem)) then
          nfound = nfound + 1
          if (nfound == 1) owner = i
       end if
    end do
    if (nfound /= 1) owner = main   ! none, or several instances' part sets: MAIN's (reported there)
    if (owner > 0) subs = [owner]
  end function plain_set_subs

  function assembly_members(st, model, name, elem) result(subs)
    !! Substructures that an assembly-level set `name` (element set: elem) has
    !! members in: the instances whose entries define it (an instance's entry
    !! holds only the sets of INSTANCE= cards: kw_set, place_path_sets), in
    !! the order of their first cards (set_b_t%order).
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    logical, intent(in) :: elem
    integer, allocatable :: subs(:), rank(:)
    integer :: k, j, isub, order, n
    allocate (subs(0), rank(0))
    do k = 1, st%nsub
       if (st%subs(k)%kind /= SUBK_INSTANCE .and. st%subs(k)%kind /= SUBK_NESTED) cycle
       j = find_set(st%subs(k), name, elem)
       if (j == 0) cycle
       if (elem) then
          order = st%subs(k)%elsets(j)%order
       else
          order = st%subs(k)%nsets(j)%order
       end if
       isub = sub_index(model, st%subs(k)%name)
       if (isub == 0) cycle   ! not placed (an instance of a part made of parts only: reported; a part's entry)
       ! insertion by rank: the first card of each instance's part of the set
       n = count(rank < order)
       rank = [rank(1:n), order, rank(n + 1:)]
       subs = [subs(1:n), isub, subs(n + 1:)]
    end do
  end function assembly_members

  pure integer function sub_index(model, name) result(k)
    !! Index of the substructure named `name` (0 if none).
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    do k = size(model%subs), 1, -1
       if (model%subs(k)%name == name) return
    end do
    k = 0
  end function sub_index

  pure function ref_text(ref) result(s)
    !! A reference as the user wrote it (upper case).
    type(ref_t), intent(in) :: ref
    character(:), allocatable :: s
    if (ref%is_set) then
       s = ref%set
    else
       s = itoa(ref%id)
    end if
    if (allocated(ref%scope)) s = ref%scope//'.'//s
  end function ref_text

  subroutine resolve_items(st, model, isub, ref, elem, loc, items, ok)
    !! Local node (elem false) or element indices a reference names in substructure isub.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(ref_t), intent(in) :: ref
    logical, intent(in) :: elem
    type(source_loc_t), intent(in) :: loc
    integer(ip), allocatable, intent(out) :: items(:)
    logical, intent(out) :: ok
    integer :: k
    integer(ip) :: i
    character(:), allocatable :: what, hint
    what = pick(elem, 'element', 'node')
    ok = .false.
    if (broken_sub(st, model%subs(isub)%name)) return   ! its *INSTANCE error was the one message
    associate (sub => model%subs(isub))
      if (ref%is_set) then
         k = 0
         if (elem) then
            do i = 1, size(sub%elsets)
               if (sub%elsets(i)%name == ref%set) k = int(i)
            end do
            if (k > 0) call copy_items(sub%elsets(k)%items)
         else
            do i = 1, size(sub%nsets)
               if (sub%nsets(i)%name == ref%set) k = int(i)
            end do
            if (k > 0) call copy_items(sub%nsets(k)%items)
         end if
         if (st%aborted) return
         if (k == 0) then
            hint = ''   ! a plain name looked for in MAIN that several instances hold: say so
            if (.not. allocated(ref%scope) .and. ref%home == 0 .and. sub%name == MAIN_NAME) &
                 hint = instances_hint(model, ref%set, elem)
            call report_loc(st, loc, 'unknown '//what//' set '//ref%set//' in substructure '//sub%name//hint)
            return
         end if
      else
         if (elem) then
            i = find_elem(sub, ref%id)
         else
            i = find_node(sub, ref%id)
         end if
         if (i == 0) then
            ! an element of a refused *ELEMENT card (reported) is not reported again
            if (.not. (elem .and. st%elements_refused)) call report_loc(st, loc, &
                 'undefined '//what//' '//itoa(ref%id)//' in substructure '//sub%name)
            return
         end if
         items = [i]
      end if
    end associate
    ok = .true.
  contains
    subroutine copy_items(set_items)
      !! items = set_items, the allocation checked (out of memory: reported).
      integer(ip), intent(in) :: set_items(:)
      integer :: stat
      allocate (items(size(set_items)), stat=stat)
      if (stat /= 0) then
         call report_oom(st, loc, 'the members of '//what//' set '//ref%set, &
              size(set_items, kind=i8)*storage_size(set_items)/8)
         return
      end if
      items(:) = set_items
    end subroutine copy_items
  end subroutine resolve_items

  pure logical function broken_sub(st, name)
    !! Is `name` an instance of an undefined part (reported once, at its *INSTANCE)?
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    integer :: k
    broken_sub = .false.
    do k = 1, st%nsub
       if (st%subs(k)%broken .and. st%subs(k)%name == name) broken_sub = .true.
    end do
  end function broken_sub

  function part_hint(model, name) result(s)
    !! ' (NAME is a part: name one of its instances)' when NAME is a part, else ''.
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    character(:), allocatable :: s
    integer :: k
    s = ''
    if (.not. allocated(model%parts)) return
    do k = 1, size(model%parts)
       if (model%parts(k)%s == name) s = ' ('//name//' is a part: name one of its instances)'
    end do
  end function part_hint

  pure logical function sub_has_set(model, isub, name, elem) result(has)
    !! Substructure isub has an element set (elem) or a node set named name.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    character(*), intent(in) :: name
    logical, intent(in) :: elem
    integer :: j
    has = .false.
    if (elem) then
       do j = 1, size(model%subs(isub)%elsets)
          if (model%subs(isub)%elsets(j)%name == name) has = .true.
       end do
    else
       do j = 1, size(model%subs(isub)%nsets)
          if (model%subs(isub)%nsets(j)%name == name) has = .true.
       end do
    end if
  end function sub_has_set

  function instances_hint(model, name, elem) result(s)
    !! ' (NAME is a set of each of the instances A, B, kept apart: name the ones meant, A.NAME and B.NAME)'
    !! when several instances hold a set of that name (a part's set: an
    !! assembly-level one over several instances is their union,
    !! plain_set_subs), else ''.
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    logical, intent(in) :: elem
    character(:), allocatable :: s, first, each
    integer :: i
    s = ''
    each = ''
    do i = 1, size(model%subs)
       if (model%subs(i)%part == 0) cycle
       if (.not. sub_has_set(model, i, name, elem)) cycle
       if (len(s) == 0) then
          first = model%subs(i)%name
          s = first
          each = first//'.'//name
       else
          s = s//', '//model%subs(i)%name
          each = each//' and '//model%subs(i)%name//'.'//name
       end if
    end do
    if (len(s) == 0) return
    if (s == first) then
       s = ''
       return
    end if
    s = ' ('//name//' is a set of each of the instances '//s//', kept apart: name the ones meant, '//each//')'
  end function instances_hint

  pure logical function keeps_previous(step, op)
    !! Whether a step's loads of one kind (*CLOAD, *DLOAD or *TEMPERATURE,
    !! whose cards say op) continue those of the previous step: with OP=MOD,
    !! and by default in a step with a procedure card (*STATIC) that is not a
    !! PERTURBATION step, as ccx 2.20 does (checked on two-step decks); a
    !! superjoin step without a procedure card is a load case of its own.
    type(step_b_t), intent(in) :: step
    integer, intent(in) :: op
    keeps_previous = op == OP_MOD .or. (op == OP_DEFAULT .and. step%has_procedure .and. .not. step%perturbation)
  end function keeps_previous

  pure function more_text(n, suffix) result(s)
    !! ' (and N more)' text for counts of repeated problems.
    integer, intent(in) :: n
    character(*), intent(in), optional :: suffix
    character(:), allocatable :: s
    if (n <= 0) then
       s = ''
    else
       s = ' (and '//itoa(n)//' more'
       if (present(suffix)) s = s//suffix
       s = s//')'
    end if
  end function more_text

  function where(st, loc) result(s)
    !! "file:line" of a location.
    type(deck_state_t), intent(in) :: st
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: s
    if (loc%file >= 1 .and. loc%file <= st%nfile) then
       s = st%files(loc%file)%s//':'//itoa(loc%line)
    else
       s = '<input>:'//itoa(loc%line)
    end if
  end function where
end module superjoin_deck_build_common
