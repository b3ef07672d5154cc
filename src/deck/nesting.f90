module superjoin_deck_nesting
  !! Parts made of parts (a bay -> a floor -> a building), unfolded (a
  !! condensed run then eliminates them by level: analysis/level_solver).
  !!
  !! A `*PART` may hold `*INSTANCE` cards of other parts and `*CONTACT` cards
  !! between those inner instances (MASTER=F3.BAY2, nodes `F3.BAY2.12`). Before
  !! the model is built, every instance of such a part is unfolded into the
  !! instances of the leaf parts (those with a mesh), each named by its instance
  !! path (`B.F3.BAY2`) and placed by the composed placement
  !! x' = R_outer (R_inner x + t_inner) + t_outer; the part's contacts are copied
  !! for each of its instances with their names and substructures prefixed by the
  !! instance's path (`B.F3.J1` between `B.F3.BAY1` and `B.F3.BAY2`). The unfolded
  !! model is then an ordinary one-level assembly (a *CHANGE CONTACT of a copy,
  !! `NAME=B.F3.J1` or `PART=FLOOR`, is resolved against it:
  !! superjoin_deck_change_paths): a condensation, if asked, is
  !! computed once per leaf part, and the interface system of the condensed
  !! leaves is then eliminated level by level (analysis/levels plans it, per
  !! group: own, boundary and interior reduced unknowns; analysis/level_solver
  !! does it).
  !!
  !! Errors (file:line of the inner *INSTANCE): a part of no definition, a part
  !! that contains itself (directly or through others).
  use superjoin_kinds, only: wp
  use superjoin_deck_lexer, only: plural
  use superjoin_model_types, only: source_loc_t
  use superjoin_model_notes, only: note
  use superjoin_deck_state, only: deck_state_t, report_loc, grow, SUBK_PART, SUBK_INSTANCE, SUBK_NESTED, &
       contact_b_t, cline_b_t, ref_t
  use superjoin_deck_cards_assembly, only: find_part, new_instance
  use superjoin_deck_change_paths, only: resolve_change_paths
  implicit none (type, external)
  private

  public :: unfold_nested

  type :: unfold_t
    !! The work of unfold_nested.
     integer, allocatable :: part_of(:)          !! per nested template (index in subs): its part (0: unknown)
     type(contact_b_t), allocatable :: contacts(:)   !! the contacts held by parts (templates)
     type(cline_b_t), allocatable :: clines(:)       !! their data lines (contact = index in contacts)
     integer :: nleaf = 0                        !! instances with a mesh made (leaf parts, parts with their own mesh)
     integer :: ncontact = 0                     !! contacts made
  end type unfold_t

contains

  subroutine unfold_nested(st)
    !! Unfold every instance of a part made of parts (see the module); no-op
    !! when no part holds an *INSTANCE.
    type(deck_state_t), intent(inout) :: st
    type(unfold_t) :: w
    integer :: k, n0
    character(:), allocatable :: name
    real(wp) :: rot(3, 3), shift(3)
    if (count(st%subs(1:st%nsub)%kind == SUBK_NESTED) == 0) then
       call resolve_change_paths(st, [contact_b_t ::])   ! paths that reach no part made of parts: reported
       return
    end if
    call link_templates(st, w)
    if (st%aborted) return
    call take_part_contacts(st, w)
    call report_meshed_part_contacts(st, w)
    if (st%aborted) return
    n0 = st%nsub
    do k = 1, n0
       if (st%subs(k)%kind /= SUBK_INSTANCE) cycle
       name = st%subs(k)%name   ! copies: unfold grows st%subs and st%instances
       rot = st%instances(st%subs(k)%inst)%rot
       shift = st%instances(st%subs(k)%inst)%shift
       call unfold(st, w, find_part(st, st%instances(st%subs(k)%inst)%part), name, rot, shift, k)
       if (st%aborted) return
    end do
    call resolve_change_paths(st, w%contacts)   ! *CHANGE CONTACT of the copies (B.F3.J1, PART=)
    ! a part made of parts only is no mesh: it leaves the model with its templates
    do k = 1, n0
       if (st%subs(k)%kind == SUBK_PART .and. st%subs(k)%node_lines == 0 .and. any(owners(st) == k)) &
            st%subs(k)%kind = SUBK_NESTED
    end do
    call note(st%notes, 'parts made of parts: unfolded into '//plural(w%nleaf, 'instance')// &
         ' of parts with a mesh and '//plural(w%ncontact, 'contact')//' of parts (named by instance path; '// &
         'condensed: by level)')
  end subroutine unfold_nested

  subroutine link_templates(st, w)
    !! w%part_of: the part of each inner *INSTANCE; unknown parts and parts that
    !! contain themselves reported (at the inner *INSTANCE).
    type(deck_state_t), intent(inout) :: st
    type(unfold_t), intent(inout) :: w
    integer :: k
    integer, allocatable :: path(:)
    logical :: quiet
    allocate (w%part_of(st%nsub))
    w%part_of = 0
    do k = 1, st%nsub
       if (st%subs(k)%kind /= SUBK_NESTED) cycle
       associate (inst => st%instances(st%subs(k)%inst))
         w%part_of(k) = find_part(st, inst%part)
         if (w%part_of(k) == 0) call report_loc(st, inst%loc, '*INSTANCE '//st%subs(k)%name//' inside part '// &
              st%subs(inst%owner)%name//' of undefined part '//inst%part)
       end associate
    end do
    ! every template that leads into a cycle is cut (unfold would not end),
    ! the first cycle reported: one message is enough
    quiet = .false.
    do k = 1, st%nsub
       if (st%subs(k)%kind /= SUBK_NESTED .or. w%part_of(k) == 0) cycle
       path = [st%instances(st%subs(k)%inst)%owner]
       if (contains_itself(k, path)) then
          w%part_of(k) = 0
          quiet = .true.
       end if
    end do
  contains
    recursive logical function contains_itself(t, path) result(bad)
      !! Template t (inside the last part of path) leads back to a part on path:
      !! reported unless quiet.
      integer, intent(in) :: t
      integer, intent(in) :: path(:)
      integer :: j, p
      character(:), allocatable :: chain
      p = w%part_of(t)
      bad = .false.
      if (p == 0) return
      if (any(path == p)) then
         bad = .true.
         if (quiet) return
         chain = ''
         do j = 1, size(path)
            chain = chain//st%subs(path(j))%name//' -> '
         end do
         call report_loc(st, st%instances(st%subs(t)%inst)%loc, '*INSTANCE '//st%subs(t)%name//' places part '// &
              st%subs(p)%name//', which contains it: a part may not contain itself ('//chain//st%subs(p)%name//')')
         return
      end if
      do j = 1, st%nsub
         if (st%subs(j)%kind /= SUBK_NESTED) cycle
         if (st%instances(st%subs(j)%inst)%owner /= p) cycle
         bad = contains_itself(j, [path, p])
         if (bad) return
      end do
    end function contains_itself
  end subroutine link_templates

  subroutine take_part_contacts(st, w)
    !! Move the contacts held by parts (and their data lines) out of st into w;
    !! the indices of the remaining contacts (data lines, *CHANGE CONTACT) follow.
    type(deck_state_t), intent(inout) :: st
    type(unfold_t), intent(inout) :: w
    integer, allocatable :: new_index(:)
    integer :: k, nkeep, ntake, s, j
    allocate (new_index(st%ncontact), w%contacts(count(st%contacts(1:st%ncontact)%owner > 0)))
    nkeep = 0
    ntake = 0
    do k = 1, st%ncontact
       if (st%contacts(k)%owner > 0) then
          ntake = ntake + 1
          w%contacts(ntake) = st%contacts(k)
          new_index(k) = -ntake
       else
          nkeep = nkeep + 1
          new_index(k) = nkeep
          if (nkeep < k) st%contacts(nkeep) = st%contacts(k)
       end if
    end do
    st%ncontact = nkeep
    allocate (w%clines(count(new_index(st%clines(1:st%ncline)%contact) < 0)))
    nkeep = 0
    ntake = 0
    do k = 1, st%ncline
       j = new_index(st%clines(k)%contact)
       if (j < 0) then
          ntake = ntake + 1
          w%clines(ntake) = st%clines(k)
          w%clines(ntake)%contact = -j
       else
          nkeep = nkeep + 1
          st%clines(nkeep) = st%clines(k)
          st%clines(nkeep)%contact = j
       end if
    end do
    st%ncline = nkeep
    do s = 1, st%nstep   ! *CHANGE CONTACT names only the assembly's contacts by index (else o%path)
       do j = 1, st%steps(s)%noverride
          associate (o => st%steps(s)%overrides(j))
            if (o%contact > 0) o%contact = max(0, new_index(o%contact))
          end associate
       end do
    end do
  end subroutine take_part_contacts

  recursive subroutine unfold(st, w, p, path, rot, shift, isub)
    !! Instance isub (named path) of part p, placed by x' = rot x + shift: its
    !! inner instances and contacts made (recursively); isub leaves the model
    !! when p has no mesh of its own.
    type(deck_state_t), intent(inout) :: st
    type(unfold_t), intent(inout) :: w
    integer, intent(in) :: p, isub
    character(*), intent(in) :: path
    real(wp), intent(in) :: rot(3, 3), shift(3)
    integer :: t, k
    real(wp) :: r(3, 3), s(3)
    type(source_loc_t) :: loc
    character(:), allocatable :: child, part
    if (p == 0) return
    if (.not. any(owners(st) == p)) then
       w%nleaf = w%nleaf + 1
       return
    end if
    if (st%subs(p)%nnode == 0) then
       st%subs(isub)%kind = SUBK_NESTED   ! no substructure of its own
    else
       w%nleaf = w%nleaf + 1              ! a mesh of its own beside its inner instances
    end if
    do t = 1, size(w%part_of)
       if (st%subs(t)%kind /= SUBK_NESTED .or. w%part_of(t) == 0) cycle
       if (st%instances(st%subs(t)%inst)%owner /= p) cycle
       ! x' = rot (r_inner x + t_inner) + shift (copied: new_instance grows st%instances)
       r = matmul(rot, st%instances(st%subs(t)%inst)%rot)
       s = matmul(rot, st%instances(st%subs(t)%inst)%shift) + shift
       loc = st%instances(st%subs(t)%inst)%loc
       child = path//'.'//st%subs(t)%name   ! copies: new_instance grows st%subs
       part = st%subs(w%part_of(t))%name
       call new_instance(st, child, part, loc, 0, k)
       st%instances(st%ninst)%rot = r
       st%instances(st%ninst)%shift = s
       call unfold(st, w, w%part_of(t), child, r, s, k)
       if (st%aborted) return
    end do
    call copy_contacts(st, w, p, path)
  end subroutine unfold

  subroutine report_meshed_part_contacts(st, w)
    !! A *CONTACT inside a part that holds no *INSTANCE joins nothing (a
    !! contact joins two instances: a part's own *INSTANCEs, or the
    !! assembly's): reported at the card, as the flat reading does, instead
    !! of being left out of every copy of the part.
    type(deck_state_t), intent(inout) :: st
    type(unfold_t), intent(in) :: w
    integer :: j, o(st%nsub)
    o = owners(st)
    do j = 1, size(w%contacts)
       if (any(o == w%contacts(j)%owner)) cycle
       call report_loc(st, w%contacts(j)%loc, '*CONTACT '//w%contacts(j)%name//' inside part '// &
            st%subs(w%contacts(j)%owner)%name//', which holds no *INSTANCE: a contact joins two instances '// &
            '(inside a part, two of its own *INSTANCEs; else write it in *ASSEMBLY between instances of '// &
            st%subs(w%contacts(j)%owner)%name//')')
    end do
  end subroutine report_meshed_part_contacts

  function owners(st) result(o)
    !! The owning part of each entry of st%subs (0: not an inner *INSTANCE).
    type(deck_state_t), intent(in) :: st
    integer :: o(st%nsub)
    integer :: k
    o = 0
    do k = 1, st%nsub
       if (st%subs(k)%kind == SUBK_NESTED .and. st%subs(k)%inst > 0) o(k) = st%instances(st%subs(k)%inst)%owner
    end do
  end function owners

  subroutine copy_contacts(st, w, p, path)
    !! The contacts of part p for its instance `path`: names, substructures and
    !! scoped node references prefixed by `path.`.
    type(deck_state_t), intent(inout) :: st
    type(unfold_t), intent(inout) :: w
    integer, intent(in) :: p
    character(*), intent(in) :: path
    type(contact_b_t) :: c
    type(cline_b_t) :: cl
    integer :: j, l, k
    integer, parameter :: INITIAL_CONTACTS = 16
    do j = 1, size(w%contacts)
       if (w%contacts(j)%owner /= p) cycle
       c = w%contacts(j)
       c%owner = 0
       c%name = path//'.'//c%name
       c%master = path//'.'//c%master
       c%slave = path//'.'//c%slave
       call grow(st%contacts, st%ncontact, INITIAL_CONTACTS)
       st%ncontact = st%ncontact + 1
       k = st%ncontact
       st%contacts(k) = c
       w%ncontact = w%ncontact + 1
       do l = 1, size(w%clines)
          if (w%clines(l)%contact /= j) cycle
          cl = w%clines(l)
          cl%contact = k
          call prefix(cl%master)
          call prefix(cl%slave)
          call grow(st%clines, st%ncline, INITIAL_CONTACTS)
          st%ncline = st%ncline + 1
          st%clines(st%ncline) = cl
       end do
    end do
  contains
    subroutine prefix(ref)
      type(ref_t), intent(inout) :: ref
      if (allocated(ref%scope)) ref%scope = path//'.'//ref%scope
    end subroutine prefix
  end subroutine copy_contacts
end module superjoin_deck_nesting
