module superjoin_deck_path_sets
  !! Assembly-level sets of inner instances: `*NSET, NSET=S, INSTANCE=B.F3.BAY2`
  !! (and `*ELSET`) name an instance of a part made of parts by its path. The
  !! card is read before the parts are unfolded, so superjoin_deck_cards_assembly's
  !! set_home keeps the set in the assembly's instance B under the name
  !! `F3.BAY2.S` (a set name has no dot otherwise); once unfolded, the set moves
  !! to the instance B.F3.BAY2 as its set S, as `INSTANCE=` of a top-level
  !! instance does (`B.F3.BAY2.S`, or plainly `S`). Errors (file:line of the set
  !! card): a path that names no instance, or one of a part made of parts only
  !! (no mesh of its own to take nodes or elements from; also INSTANCE=B for
  !! such a top-level instance B); a name that a set of
  !! the instance's part has is reported when the instance is placed
  !! (superjoin_deck_assembly, as for a top-level instance).
  use superjoin_deck_state, only: deck_state_t, report_loc, find_sub, find_set, new_set, add_chunk, push_pool, &
       sub_b_t, set_b_t, chunk_t, SUBK_INSTANCE, SUBK_NESTED, CH_IDS
  implicit none (type, external)
  private

  public :: place_path_sets

contains

  subroutine place_path_sets(st)
    !! Move every set kept under an inner path to its unfolded instance (see the
    !! module); paths that name no instance with a mesh reported.
    type(deck_state_t), intent(inout) :: st
    integer :: k, n0
    n0 = st%nsub
    do k = 1, n0
       if (st%subs(k)%kind /= SUBK_INSTANCE .and. st%subs(k)%kind /= SUBK_NESTED) cycle
       if (st%subs(k)%nnset > 0) call move_kind(st, k, .false.)
       if (st%subs(k)%nelset > 0) call move_kind(st, k, .true.)
       if (st%subs(k)%kind == SUBK_NESTED .and. st%subs(k)%inst > 0) call report_meshless(st, k)   ! not a part's entry
    end do
  end subroutine place_path_sets

  subroutine report_meshless(st, k)
    !! The sets left in entry k, an instance of a part made of parts only (no
    !! substructure of its own: *NSET, INSTANCE=B without a path), reported at
    !! their cards; they would take nothing (a set over several instances
    !! would lose those members silently).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: k
    integer :: i
    do i = 1, st%subs(k)%nnset
       call report_loc(st, st%subs(k)%nsets(i)%loc, 'INSTANCE='//st%subs(k)%name//' of *NSET names '// &
            what_path_is(st, st%subs(k)%name))
    end do
    do i = 1, st%subs(k)%nelset
       call report_loc(st, st%subs(k)%elsets(i)%loc, 'INSTANCE='//st%subs(k)%name//' of *ELSET names '// &
            what_path_is(st, st%subs(k)%name))
    end do
  end subroutine report_meshless

  subroutine move_kind(st, k, elem)
    !! The node (or element: elem) sets of entry k held for inner paths: moved
    !! to their instances, then dropped from k.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: k
    logical, intent(in) :: elem
    logical, allocatable :: moved(:)
    type(set_b_t), allocatable :: sets(:)
    integer :: i, at, target
    character(:), allocatable :: path, name
    if (elem) then
       sets = st%subs(k)%elsets(1:st%subs(k)%nelset)
    else
       sets = st%subs(k)%nsets(1:st%subs(k)%nnset)
    end if
    allocate (moved(size(sets)), source=.false.)
    do i = 1, size(sets)
       at = index(sets(i)%name, '.', back=.true.)
       if (at == 0) cycle
       moved(i) = .true.
       path = st%subs(k)%name//'.'//sets(i)%name(1:at - 1)
       name = sets(i)%name(at + 1:)
       target = find_sub(st, path)   ! an unfolded instance with a mesh (find_sub skips parts made of parts)
       if (target == 0) then
          call report_loc(st, sets(i)%loc, 'INSTANCE='//path//' of *'//trim(merge('ELSET', 'NSET ', elem))// &
               ' names '//what_path_is(st, path))
          cycle
       end if
       call copy_set(st%subs(k), i, elem, name, sets(i), st%subs(target))
    end do
    if (any(moved)) call drop_sets(st%subs(k), moved, elem)
  end subroutine move_kind

  function what_path_is(st, path) result(text)
    !! What an instance path that takes no set names, for the message.
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: path
    character(:), allocatable :: text
    integer :: j
    text = 'no instance (an inner instance is named by its path from the assembly''s instance, as B.F3.BAY2)'
    do j = 1, st%nsub
       if (st%subs(j)%kind /= SUBK_NESTED .or. st%subs(j)%name /= path) cycle
       text = 'an instance of part '//st%instances(st%subs(j)%inst)%part//', which is made of parts only: '// &
            'name one of its instances with a mesh ('//path//'.name)'
       return
    end do
  end function what_path_is

  subroutine copy_set(from, iset, elem, name, set, to)
    !! Set iset of `from` (its chunks, explicit ids with them) appended to
    !! `to` as its set `name` (joined to a set of that name it has already:
    !! another assembly-level card of that path; the part's sets come later).
    type(sub_b_t), intent(in) :: from
    integer, intent(in) :: iset
    logical, intent(in) :: elem
    character(*), intent(in) :: name
    type(set_b_t), intent(in) :: set
    type(sub_b_t), intent(inout) :: to
    integer :: j, c, k, jset
    jset = find_set(to, name, elem)
    if (jset == 0) then
       call new_set(to, name, elem, set%loc, jset)
       if (elem) then
          to%elsets(jset)%order = set%order
       else
          to%nsets(jset)%order = set%order
       end if
    end if
    do c = 1, from%nchunk
       if (from%chunks(c)%set /= iset .or. (from%chunks(c)%elem .neqv. elem)) cycle
       call add_chunk(to, jset, elem, from%chunks(c)%kind, from%chunks(c)%loc, k)
       to%chunks(k)%gen = from%chunks(c)%gen
       if (allocated(from%chunks(c)%ref)) to%chunks(k)%ref = from%chunks(c)%ref
       to%chunks(k)%count = from%chunks(c)%count
       if (from%chunks(c)%kind /= CH_IDS) cycle
       to%chunks(k)%start = to%npool + 1
       do j = from%chunks(c)%start, from%chunks(c)%start + from%chunks(c)%count - 1
          call push_pool(to, from%pool(j))
       end do
    end do
  end subroutine copy_set

  subroutine drop_sets(sub, moved, elem)
    !! The node (element: elem) sets marked moved and their chunks out of sub;
    !! the chunks of the others renumbered (their ids stay in the pool).
    type(sub_b_t), intent(inout) :: sub
    logical, intent(in) :: moved(:)
    logical, intent(in) :: elem
    integer :: new_index(size(moved)), i, n, c
    type(chunk_t), allocatable :: kept(:)
    n = 0
    do i = 1, size(moved)
       new_index(i) = 0
       if (moved(i)) cycle
       n = n + 1
       new_index(i) = n
       if (elem) then
          sub%elsets(n) = sub%elsets(i)
       else
          sub%nsets(n) = sub%nsets(i)
       end if
    end do
    if (elem) then
       sub%nelset = n
    else
       sub%nnset = n
    end if
    allocate (kept(sub%nchunk))
    n = 0
    do c = 1, sub%nchunk
       if (sub%chunks(c)%elem .eqv. elem) then
          if (new_index(sub%chunks(c)%set) == 0) cycle
          sub%chunks(c)%set = new_index(sub%chunks(c)%set)
       end if
       n = n + 1
       kept(n) = sub%chunks(c)
    end do
    sub%chunks(1:n) = kept(1:n)
    sub%nchunk = n
  end subroutine drop_sets
end module superjoin_deck_path_sets
