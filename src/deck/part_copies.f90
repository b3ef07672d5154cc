module superjoin_deck_part_copies
  !! Surfaces and constraint cards written inside a `*PART`, copied to each
  !! instance (Abaqus applies a part's constraints to every instance of it):
  !!
  !! - a part surface S gets one copy `I.S` per instance I of the part (its
  !!   elements, nodes and sets taken in I); an assembly-level *COUPLING or
  !!   *TIE may name it so, and a *DSLOAD (instance_surface: it is resolved as
  !!   it is read, before these copies are made);
  !! - a part's `*COUPLING` (+ `*KINEMATIC` / `*DISTRIBUTING`), `*RIGID BODY`
  !!   and `*MPC` become one record per instance, every plain node, set and
  !!   element reference taken in that instance (`I.n`) and its SURFACE=S the
  !!   instance's copy `I.S`; placement needs nothing more, since the copies
  !!   name the instance's placed nodes;
  !! - a part's `*TIE` likewise, between I's copies of its surfaces, named I.N
  !!   when it has a NAME=N; a part's `*EQUATION` (its first term's node a
  !!   plain one of the part) likewise, its nodes taken in I;
  !! - a part's `*TRANSFORM` likewise, its system turned with I (Abaqus: a
  !!   part's transform moves with the instance), its `*NODAL THICKNESS`,
  !!   `*INITIAL CONDITIONS, TYPE=TEMPERATURE`, the output requests naming a
  !!   set (`*NODE PRINT`, `*EL FILE`, ...) and the `*SECTION PRINT` of a part
  !!   surface (named I.N), a `*PRE-TENSION SECTION` of a part surface (its
  !!   normal turned with I); these named the part's substructure entry, which
  !!   is gone once the instances are placed (a stale number).
  !!
  !! The copies come first, instance by instance in the order of the
  !! *INSTANCE entries, each instance's in the order written; the part's own
  !! records leave. Not copied (refused where they are read or here):
  !! `*DISTRIBUTING COUPLING` / DCOUP3D elements, and couplings, ties and
  !! equations inside a part made of parts (one holding *INSTANCE cards).
  use superjoin_deck_state, only: deck_state_t, report_loc, grow, instance_part, ref_t, surface_b_t, tie_b_t, equation_b_t, &
       transform_b_t, nthick_b_t, request_b_t, temp_b_t, SUBK_PART, SUBK_NESTED, SUBK_INSTANCE
  use superjoin_deck_records, only: pretension_b_t
  use superjoin_deck_coupling_records, only: coupling_b_t
  use superjoin_model_types, only: source_loc_t, section_print_t
  implicit none (type, external)
  private

  public :: copy_part_constraints, instance_surface

  integer, parameter :: INITIAL_COPIES = 4   !! surfaces before the first doubling

contains

  subroutine copy_part_constraints(st)
    !! Copy the surfaces, constraints, transforms, thicknesses, requests and temperatures of every part
    !! to its instances (see the module).
    type(deck_state_t), intent(inout) :: st
    integer, allocatable :: part_of(:)
    integer :: k
    if (count(st%subs(1:st%nsub)%kind == SUBK_PART) == 0) return
    allocate (part_of(st%nsub))
    do k = 1, st%nsub
       part_of(k) = instance_part(st, k)
       if (part_of(k) > 0) then
          if (any(st%instances(1:st%ninst)%owner == part_of(k))) part_of(k) = 0   ! made of parts: refused
       end if
    end do
    call copy_surfaces(st, part_of)
    if (allocated(st%couplings)) call copy_couplings(st, part_of)
    if (allocated(st%ties)) call copy_ties(st, part_of)
    if (st%nequation > 0) call copy_equations(st, part_of)
    if (st%ntransform > 0) call copy_transforms(st, part_of)
    if (st%nnthick > 0) call copy_thicknesses(st, part_of)
    if (st%nreq > 0) call copy_requests(st, part_of)
    if (st%ntemp > 0) call copy_temperatures(st, part_of)
    if (allocated(st%section_prints)) call copy_section_prints(st, part_of)
    if (allocated(st%pretensions)) call copy_pretensions(st, part_of)
  end subroutine copy_part_constraints

  elemental logical function is_part(st, p)
    !! Whether entry p of subs is a part (or a part made of parts).
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: p
    is_part = .false.
    if (p > 0) is_part = st%subs(p)%kind == SUBK_PART .or. st%subs(p)%kind == SUBK_NESTED
  end function is_part

  integer function surface_part(st, sf) result(p)
    !! The part a surface was written in (0: none): its plain references' substructure.
    type(deck_state_t), intent(in) :: st
    type(surface_b_t), intent(in) :: sf
    p = 0
    if (sf%n < 1) return
    if (allocated(sf%refs(1)%scope)) return
    if (is_part(st, sf%refs(1)%home)) p = sf%refs(1)%home
  end function surface_part

  subroutine in_instance(ref, p, inst)
    !! A plain reference of part p taken in the instance named inst.
    type(ref_t), intent(inout) :: ref
    integer, intent(in) :: p
    character(*), intent(in) :: inst
    if (allocated(ref%scope) .or. ref%home /= p) return
    ref%scope = inst
    ref%home = 0
  end subroutine in_instance

  subroutine copy_surfaces(st, part_of)
    !! A copy I.S of each part surface S for each instance I of its part.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    integer :: n0, j, k, p
    n0 = st%nsurface
    do k = 1, size(part_of)
       if (part_of(k) == 0) cycle
       do j = 1, n0
          p = surface_part(st, st%surfaces(j))
          if (p /= part_of(k)) cycle
          call grow(st%surfaces, st%nsurface, INITIAL_COPIES)
          st%nsurface = st%nsurface + 1
          st%surfaces(st%nsurface) = surface_copy(st, j, k)
       end do
    end do
  end subroutine copy_surfaces

  function surface_copy(st, j, k) result(c)
    !! Instance k's copy of part surface j: named I.S, its references taken in I.
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: j, k
    type(surface_b_t) :: c
    integer :: i, p
    p = surface_part(st, st%surfaces(j))
    c = st%surfaces(j)
    c%name = st%subs(k)%name//'.'//st%surfaces(j)%name
    do i = 1, c%n
       call in_instance(c%refs(i), p, st%subs(k)%name)
    end do
  end function surface_copy

  subroutine instance_surface(st, name, c, found)
    !! The surface `I.S` as read so far (a *DSLOAD in a step): instance I's copy
    !! of the surface S of its part (found false when I is no instance placed
    !! before, or its part has no surface S). The copies of copy_part_constraints
    !! are made only when the whole deck is read.
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    type(surface_b_t), intent(out) :: c
    logical, intent(out) :: found
    integer :: dot, k, j, p
    found = .false.
    dot = index(name, '.', back=.true.)
    if (dot <= 1) return
    do k = st%nsub, 1, -1
       if (st%subs(k)%kind == SUBK_INSTANCE .and. st%subs(k)%name == name(1:dot - 1)) exit
    end do
    if (k < 1) return
    p = instance_part(st, k)
    if (p == 0) return
    do j = st%nsurface, 1, -1
       if (st%surfaces(j)%name /= name(dot + 1:)) cycle
       if (surface_part(st, st%surfaces(j)) /= p) cycle
       c = surface_copy(st, j, k)
       found = .true.
       return
    end do
  end subroutine instance_surface

  subroutine plan_copies(st, homes, locs, card, part_of, src, inst)
    !! The new order of the records whose blocks are homes(:): first the copies
    !! of the parts' records, instance by instance, then the others as read;
    !! src(i) is the record, inst(i) the instance entry it is taken in (0: kept
    !! as read). Records of parts made of parts are dropped and reported.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: homes(:), part_of(:)
    type(source_loc_t), intent(in) :: locs(:)
    character(*), intent(in) :: card
    integer, allocatable, intent(out) :: src(:), inst(:)
    integer :: j, k, n
    n = count(.not. is_part(st, homes))
    do k = 1, size(part_of)
       if (part_of(k) > 0) n = n + count(homes == part_of(k))
    end do
    allocate (src(n), inst(n))
    n = 0
    do k = 1, size(part_of)
       if (part_of(k) == 0) cycle
       do j = 1, size(homes)
          if (homes(j) /= part_of(k)) cycle
          n = n + 1
          src(n) = j
          inst(n) = k
       end do
    end do
    do j = 1, size(homes)
       if (is_part(st, homes(j))) then
          call refuse_in_nested(st, homes(j), locs(j), card)
          cycle
       end if
       n = n + 1
       src(n) = j
       inst(n) = 0
    end do
  end subroutine plan_copies

  subroutine copy_couplings(st, part_of)
    !! The coupling records of parts replaced by their copies per instance (plan_copies).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(coupling_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:)
    integer :: i, p
    if (.not. any(is_part(st, st%couplings(:)%home))) return
    call plan_copies(st, st%couplings(:)%home, st%couplings(:)%loc, 'a coupling card', part_of, src, inst)
    allocate (all(size(src)))
    do i = 1, size(src)
       all(i) = st%couplings(src(i))
       if (inst(i) == 0) cycle
       p = part_of(inst(i))
       call couple_in_instance(st, all(i), p, st%subs(inst(i))%name)
    end do
    call move_alloc(all, st%couplings)
  end subroutine copy_couplings

  subroutine couple_in_instance(st, c, p, inst)
    !! A coupling record of part p taken in the instance named inst.
    type(deck_state_t), intent(in) :: st
    type(coupling_b_t), intent(inout) :: c
    integer, intent(in) :: p
    character(*), intent(in) :: inst
    integer :: i
    c%home = 0
    call in_instance(c%ref_node, p, inst)
    call in_instance(c%rot_node, p, inst)
    call in_instance(c%nodes, p, inst)
    if (allocated(c%list)) then
       do i = 1, size(c%list)
          call in_instance(c%list(i), p, inst)
       end do
    end if
    if (allocated(c%surface)) call surface_in_instance(st, c%surface, p, inst)
  end subroutine couple_in_instance

  subroutine surface_in_instance(st, name, p, inst)
    !! A surface name written in part p: the instance's copy inst.name when p holds that surface.
    type(deck_state_t), intent(in) :: st
    character(:), allocatable, intent(inout) :: name
    integer, intent(in) :: p
    character(*), intent(in) :: inst
    integer :: i
    do i = 1, st%nsurface
       if (st%surfaces(i)%name == name .and. surface_part(st, st%surfaces(i)) == p) then
          name = inst//'.'//name
          return
       end if
    end do
  end subroutine surface_in_instance

  subroutine copy_ties(st, part_of)
    !! The *TIE cards of parts replaced by their copies per instance I
    !! (plan_copies): the part's surfaces S taken as I.S, a name N as I.N.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(tie_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:)
    integer :: i
    if (.not. any(is_part(st, st%ties(:)%home))) return
    call plan_copies(st, st%ties(:)%home, st%ties(:)%loc, '*TIE', part_of, src, inst)
    allocate (all(size(src)))
    do i = 1, size(src)
       all(i) = st%ties(src(i))
       if (inst(i) == 0) cycle
       associate (t => all(i), name => st%subs(inst(i))%name)
         t%home = 0
         if (len(t%name) > 0) t%name = name//'.'//t%name
         if (allocated(t%slave)) call surface_in_instance(st, t%slave, part_of(inst(i)), name)
         if (allocated(t%master)) call surface_in_instance(st, t%master, part_of(inst(i)), name)
       end associate
    end do
    call move_alloc(all, st%ties)
  end subroutine copy_ties

  subroutine copy_equations(st, part_of)
    !! The *EQUATION constraints of parts (their first term's node in the part)
    !! replaced by their copies per instance (plan_copies), nodes taken in it.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(equation_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:), homes(:)
    type(source_loc_t), allocatable :: locs(:)
    integer :: i, t
    allocate (homes(st%nequation), locs(st%nequation))
    do i = 1, st%nequation
       homes(i) = 0
       locs(i) = st%equations(i)%loc
       if (st%equations(i)%n < 1) cycle
       if (.not. allocated(st%equations(i)%node(1)%scope)) homes(i) = st%equations(i)%node(1)%home
    end do
    if (.not. any(is_part(st, homes))) return
    call plan_copies(st, homes, locs, '*EQUATION', part_of, src, inst)
    allocate (all(size(src)))
    do i = 1, size(src)
       all(i) = st%equations(src(i))
       if (inst(i) == 0) cycle
       do t = 1, all(i)%n
          call in_instance(all(i)%node(t), part_of(inst(i)), st%subs(inst(i))%name)
       end do
    end do
    call move_alloc(all, st%equations)
    st%nequation = size(st%equations)
  end subroutine copy_equations

  elemental integer function ref_home(ref) result(home)
    !! The substructure block of a plain reference (0: one written SUB.x).
    type(ref_t), intent(in) :: ref
    home = 0
    if (.not. allocated(ref%scope)) home = ref%home
  end function ref_home

  subroutine copy_transforms(st, part_of)
    !! The *TRANSFORM cards of parts replaced by their copies per instance
    !! (plan_copies), the node set taken in it and the system turned with it,
    !! as Abaqus turns a part's transform with the instance (CalculiX has no
    !! parts): TYPE=R the directions a, b by the instance's rotation, TYPE=C
    !! the axis points by its placement.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(transform_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:)
    integer :: i
    associate (list => st%transforms(1:st%ntransform))
      if (.not. any(is_part(st, ref_home(list%nset)))) return
      call plan_copies(st, ref_home(list%nset), list%loc, '*TRANSFORM', part_of, src, inst)
      allocate (all(size(src)))
      do i = 1, size(src)
         all(i) = list(src(i))
      end do
    end associate
    do i = 1, size(src)
       if (inst(i) == 0) cycle
       call in_instance(all(i)%nset, part_of(inst(i)), st%subs(inst(i))%name)
       associate (t => all(i), pl => st%instances(st%subs(inst(i))%inst))
         t%a = matmul(pl%rot, t%a)
         t%b = matmul(pl%rot, t%b)
         if (t%cylindrical) then
            t%a = t%a + pl%shift
            t%b = t%b + pl%shift
         end if
       end associate
    end do
    call move_alloc(all, st%transforms)
    st%ntransform = size(st%transforms)
  end subroutine copy_transforms

  subroutine copy_thicknesses(st, part_of)
    !! The *NODAL THICKNESS lines of parts replaced by their copies per instance, nodes taken in it.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(nthick_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:)
    integer :: i
    associate (list => st%nthicks(1:st%nnthick))
      if (.not. any(is_part(st, ref_home(list%node)))) return
      call plan_copies(st, ref_home(list%node), list%loc, '*NODAL THICKNESS', part_of, src, inst)
      allocate (all(size(src)))
      do i = 1, size(src)
         all(i) = list(src(i))
         if (inst(i) > 0) call in_instance(all(i)%node, part_of(inst(i)), st%subs(inst(i))%name)
      end do
    end associate
    call move_alloc(all, st%nthicks)
    st%nnthick = size(st%nthicks)
  end subroutine copy_thicknesses

  subroutine copy_requests(st, part_of)
    !! The output requests (*NODE PRINT, *EL FILE, ...) of parts naming a set
    !! replaced by their copies per instance, the set taken in it.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(request_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:), homes(:)
    integer :: i
    allocate (homes(st%nreq))
    associate (list => st%requests(1:st%nreq))
      homes(:) = merge(ref_home(list%set), 0, list%has_set)
      if (.not. any(is_part(st, homes))) return
      call plan_copies(st, homes, list%loc, list(1)%card, part_of, src, inst)
      allocate (all(size(src)))
      do i = 1, size(src)
         all(i) = list(src(i))
         if (inst(i) > 0) call in_instance(all(i)%set, part_of(inst(i)), st%subs(inst(i))%name)
      end do
    end associate
    call move_alloc(all, st%requests)
    st%nreq = size(st%requests)
  end subroutine copy_requests

  subroutine copy_temperatures(st, part_of)
    !! The temperature lines (*INITIAL CONDITIONS, TYPE=TEMPERATURE) of parts
    !! replaced by their copies per instance, nodes taken in it.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(temp_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:)
    integer :: i
    associate (list => st%temps(1:st%ntemp))
      if (.not. any(is_part(st, ref_home(list%ref)))) return
      call plan_copies(st, ref_home(list%ref), list%loc, '*INITIAL CONDITIONS', part_of, src, inst)
      allocate (all(size(src)))
      do i = 1, size(src)
         all(i) = list(src(i))
         if (inst(i) > 0) call in_instance(all(i)%ref, part_of(inst(i)), st%subs(inst(i))%name)
      end do
    end associate
    call move_alloc(all, st%temps)
    st%ntemp = size(st%temps)
  end subroutine copy_temperatures

  subroutine copy_section_prints(st, part_of)
    !! The *SECTION PRINT cards that name a part's surface S (written in the
    !! part) replaced by their copies per instance I: surface I.S, name I.N.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(section_print_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:), homes(:)
    integer :: i
    allocate (homes(size(st%section_prints)))
    do i = 1, size(homes)
       homes(i) = named_surface_part(st, st%section_prints(i)%surface)
    end do
    if (.not. any(is_part(st, homes))) return
    call plan_copies(st, homes, st%section_prints(:)%loc, '*SECTION PRINT', part_of, src, inst)
    allocate (all(size(src)))
    do i = 1, size(src)
       all(i) = st%section_prints(src(i))
       if (inst(i) == 0) cycle
       all(i)%name = st%subs(inst(i))%name//'.'//all(i)%name
       call surface_in_instance(st, all(i)%surface, part_of(inst(i)), st%subs(inst(i))%name)
    end do
    call move_alloc(all, st%section_prints)
  end subroutine copy_section_prints

  integer function named_surface_part(st, name) result(p)
    !! The part that the first surface named `name` (as the builders take it) was written in (0: none).
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    integer :: j
    p = 0
    do j = 1, st%nsurface
       if (st%surfaces(j)%name /= name) cycle
       p = surface_part(st, st%surfaces(j))
       return
    end do
  end function named_surface_part

  subroutine copy_pretensions(st, part_of)
    !! The *PRE-TENSION SECTION cards that name a part's surface S (written in
    !! the part) replaced by their copies per instance I: surface I.S, the
    !! pretension node taken in I (the surface's substructure), a given normal
    !! turned with I.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: part_of(:)
    type(pretension_b_t), allocatable :: all(:)
    integer, allocatable :: src(:), inst(:), homes(:)
    integer :: i
    allocate (homes(size(st%pretensions)))
    do i = 1, size(homes)
       homes(i) = named_surface_part(st, st%pretensions(i)%surface)
    end do
    if (.not. any(is_part(st, homes))) return
    call plan_copies(st, homes, st%pretensions(:)%loc, '*PRE-TENSION SECTION', part_of, src, inst)
    allocate (all(size(src)))
    do i = 1, size(src)
       all(i) = st%pretensions(src(i))
       if (inst(i) == 0) cycle
       call surface_in_instance(st, all(i)%surface, part_of(inst(i)), st%subs(inst(i))%name)
       all(i)%normal = matmul(st%instances(st%subs(inst(i))%inst)%rot, all(i)%normal)
    end do
    call move_alloc(all, st%pretensions)
  end subroutine copy_pretensions

  subroutine refuse_in_nested(st, p, loc, card)
    !! A card of part p that is not copied when p is made of parts: reported.
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: p
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: card
    if (st%ninst == 0) return   ! no instance at all: the part is reported unplaced
    if (.not. any(st%instances(1:st%ninst)%owner == p)) return
    call report_loc(st, loc, card//' inside *PART '//st%subs(p)%name//', a part made of parts, is not '// &
         'supported (write it in the assembly, with the instances'' nodes I.n and a *SURFACE of their elements I.e)')
  end subroutine refuse_in_nested

end module superjoin_deck_part_copies
