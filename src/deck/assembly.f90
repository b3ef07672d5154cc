module superjoin_deck_assembly
  !! Validation side of parts, instances and joint studies (see
  !! superjoin_deck_cards_assembly for the cards):
  !!
  !! - every *INSTANCE becomes a substructure: a copy of its part's nodes (placed,
  !!   x' = rot x + shift), elements, sets and sections; the orientation vectors of
  !!   3D beam sections turn with the instance, so a rotated instance is the same
  !!   structure turned; then the parts leave model%subs;
  !! - PAIR=NEAREST on *CONTACT: each slave node takes the nearest master node;
  !! - *CHANGE CONTACT: per-step link overrides, SWEEP steps expanded.
  use superjoin_deck_matrix_input, only: turn_given
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, substructure_t, index_set_t, source_loc_t, &
       ELEMENT_TYPE_NAMES, SEC_BEAM, LINK_FINITE, section_t, MAX_ELEMENT_NODES, link_override_t, &
       step_t, node_label, ELEMENT_NODE_COUNT
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_BEAM
  use superjoin_deck_lexer, only: itoa, plural
  use superjoin_deck_state, only: deck_state_t, sub_b_t, report, report_loc, SUBK_INSTANCE, &
       step_b_t, SUBK_PART, SUBK_NESTED, SUBK_PLAIN, MAIN_NAME, instance_b_t, override_b_t, find_set, find_sub, instance_part
  use superjoin_elements_frame, only: DEFAULT_V_SWITCH_TOL, cross, real_text
  use superjoin_utils_sorting, only: sort_index
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use superjoin_deck_build_common, only: resolve_items, where
  use superjoin_deck_build_subs, only: resolve_sets
  use superjoin_utils_strings, only: pick
  implicit none (type, external)
  private

  public :: empty_sub, place_instances, pair_nearest, build_overrides

  type :: override_work_t
    !! What the *CHANGE CONTACT lines of the steps are resolved against.
     integer, allocatable :: first_link(:), last_link(:)   !! links of each contact
     type(index_set_t), allocatable :: line_links(:)       !! links of each line of the current step
  end type override_work_t

  real(wp), parameter :: IDENTITY(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
       0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  real(wp), parameter :: GLOBAL_X(3) = [1.0_wp, 0.0_wp, 0.0_wp], GLOBAL_Z(3) = [0.0_wp, 0.0_wp, 1.0_wp]
  real(wp), parameter :: PLANE_ROT_TOL = 1.0e-12_wp
    !! A part with 2D elements may only turn about an axis parallel to Z: |R33 - 1| <= this.

contains

  subroutine empty_sub(b, m)
    !! An *INSTANCE entry before its part is copied in: a substructure with no nodes.
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(out) :: m
    m%name = b%name
    m%loc = b%loc
    m%nnode = 0
    m%nelem = 0
    allocate (m%node_id(0), m%x(3, 0), m%elem_id(0), m%elem_type(0), m%elem_nodes(MAX_ELEMENT_NODES, 0), &
         m%elem_section(0), m%elem_loc(0), m%nsets(0), m%elsets(0), m%sections(0), m%node_order(0), &
         m%elem_order(0))
  end subroutine empty_sub

  subroutine place_instances(st, model)
    !! Copy every part into its instances (placed), then drop the parts from
    !! model%subs (references by index are renumbered).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(halting_t) :: saved
    call halting_off(saved)
    call place_all(st, model)
    call halting_restore(saved)
  end subroutine place_instances

  subroutine place_all(st, model)
    !! place_instances with floating-point halting off (overflow is reported).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, allocatable :: part_ord(:), new_index(:)
    type(substructure_t), allocatable :: subs(:)
    integer :: k, p, nparts, nkeep

    nparts = count(st%subs(1:st%nsub)%kind == SUBK_PART)
    allocate (model%parts(nparts), part_ord(st%nsub))
    part_ord = 0
    nparts = 0
    do k = 1, st%nsub
       if (st%subs(k)%kind /= SUBK_PART) cycle
       nparts = nparts + 1
       part_ord(k) = nparts
       model%parts(nparts)%s = st%subs(k)%name
    end do
    if (nparts == 0 .and. st%ninst == 0) return

    ! the parts leave the model; indices of the remaining substructures shift
    allocate (new_index(st%nsub))
    nkeep = 0
    do k = 1, st%nsub
       new_index(k) = 0
       if (st%subs(k)%kind == SUBK_PART .or. st%subs(k)%kind == SUBK_NESTED) cycle   ! nested: unfolded
       nkeep = nkeep + 1
       new_index(k) = nkeep
    end do
    if (nkeep == 0) then
       call report(st, 1, 1, 'the deck defines parts but places no instance of them (*ASSEMBLY, *INSTANCE)')
       return
    end if
    ! each instance is placed straight into its slot of the new list (one copy of its part)
    allocate (subs(nkeep))
    do k = 1, st%nsub
       if (new_index(k) == 0) cycle
       if (st%subs(k)%kind /= SUBK_INSTANCE) then
          subs(new_index(k)) = model%subs(k)
          cycle
       end if
       associate (inst => st%instances(st%subs(k)%inst), m => subs(new_index(k)))
         p = instance_part(st, k)
         if (p == 0) then
            call report_loc(st, inst%loc, '*INSTANCE '//st%subs(k)%name//' of undefined part '//inst%part)
            st%subs(k)%broken = .true.   ! references into it are not reported again
            m = model%subs(k)
            cycle
         end if
         ! an instance whose data lines were refused is placed as far as they were
         ! read, so that its nodes exist for the references (no second error)
         m%name = model%subs(k)%name
         m%loc = model%subs(k)%loc
         call place_copy(st, model%subs(p), inst, m)
         m%part = part_ord(p)
         call add_assembly_sets(st, st%subs(k), st%subs(p), m)
       end associate
       if (st%aborted) return
    end do
    call move_alloc(subs, model%subs)
    call renumber_blocks(st, new_index)
  end subroutine place_all

  subroutine renumber_blocks(st, new_index)
    !! The substructure blocks of the records read there (supports,
    !! temperatures, the steps' loads, output requests, equations, nodal
    !! thicknesses, transforms, surfaces, couplings, ties, pretension
    !! sections), which are built after the parts leave the list: new_index
    !! maps each old index to the new (0: a part, whose records were copied
    !! to its instances, or an instance that was not placed).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: new_index(:)
    integer :: k, t, s
    do k = 1, st%nsupport
       call renumber(st%supports(k)%ref%home)
    end do
    do k = 1, st%ntemp
       call renumber(st%temps(k)%ref%home)
    end do
    do k = 1, st%nreq   ! a part's requests were copied per instance: one left in a part (-1) is of a refused deck
       associate (home => st%requests(k)%set%home)
         if (home > 0) then
            home = new_index(home)
            if (home == 0) home = -1
         end if
       end associate
    end do
    do s = 1, st%nstep
       do t = 1, st%steps(s)%ncload
          call renumber(st%steps(s)%cloads(t)%ref%home)
          call renumber(st%steps(s)%cloads(t)%home)
       end do
       do t = 1, st%steps(s)%ndload
          call renumber(st%steps(s)%dloads(t)%ref%home)
          call renumber(st%steps(s)%dloads(t)%home)
       end do
    end do
    do k = 1, st%nequation
       if (.not. allocated(st%equations(k)%node)) cycle
       do t = 1, size(st%equations(k)%node)
          call renumber(st%equations(k)%node(t)%home)
       end do
    end do
    do k = 1, st%nnthick
       call renumber(st%nthicks(k)%node%home)
    end do
    do k = 1, st%ntransform
       call renumber(st%transforms(k)%nset%home)
    end do
    do k = 1, st%nsurface
       if (.not. allocated(st%surfaces(k)%refs)) cycle
       do t = 1, size(st%surfaces(k)%refs)
          call renumber(st%surfaces(k)%refs(t)%home)
       end do
    end do
    if (allocated(st%couplings)) then
       do k = 1, size(st%couplings)
          associate (c => st%couplings(k))
            call renumber(c%home)
            call renumber(c%ref_node%home)
            call renumber(c%rot_node%home)
            call renumber(c%nodes%home)
            if (allocated(c%list)) then
               do t = 1, size(c%list)
                  call renumber(c%list(t)%home)
               end do
            end if
          end associate
       end do
    end if
    if (allocated(st%ties)) then
       do k = 1, size(st%ties)
          call renumber(st%ties(k)%home)
       end do
    end if
    if (allocated(st%pretensions)) then
       do k = 1, size(st%pretensions)
          call renumber(st%pretensions(k)%element%home)
       end do
    end if
  contains
    subroutine renumber(home)
      integer, intent(inout) :: home
      if (home > 0) home = new_index(home)
    end subroutine renumber
  end subroutine renumber_blocks

  subroutine add_assembly_sets(st, b, part, m)
    !! The sets that *NSET/*ELSET, INSTANCE= define on instance m (Abaqus
    !! assembly-level sets), after the sets copied from its part (b: the
    !! instance's entry, with those sets; part: its part's entry).
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b, part
    type(substructure_t), intent(inout) :: m
    if (b%nnset > 0) call add_kind(.false.)
    if (st%aborted) return
    if (b%nelset > 0) call add_kind(.true.)
  contains
    subroutine add_kind(elem)
      logical, intent(in) :: elem
      type(index_set_t), allocatable :: keep(:), all(:)
      integer :: i, j, n1, n2
      if (elem) then
         call move_alloc(m%elsets, keep)
      else
         call move_alloc(m%nsets, keep)
      end if
      call resolve_sets(st, b, m, elem)
      if (elem) then
         call move_alloc(m%elsets, all)
      else
         call move_alloc(m%nsets, all)
      end if
      n1 = size(keep)
      n2 = size(all)
      do j = 1, n2
         do i = 1, n1
            if (keep(i)%name == all(j)%name) call report_clash(st, b, part, m%name, j, elem)
         end do
         call report_main_clash(st, b, m%name, j, elem)
      end do
      ! explicit growth (an array constructor of a type with allocatable components leaks with gfortran 12)
      block
        type(index_set_t), allocatable :: joined(:)
        allocate (joined(n1 + n2))
        do i = 1, n1
           call move_alloc(keep(i)%name, joined(i)%name)
           call move_alloc(keep(i)%items, joined(i)%items)
        end do
        do j = 1, n2
           call move_alloc(all(j)%name, joined(n1 + j)%name)
           call move_alloc(all(j)%items, joined(n1 + j)%items)
        end do
        if (elem) then
           call move_alloc(joined, m%elsets)
        else
           call move_alloc(joined, m%nsets)
        end if
      end block
    end subroutine add_kind
  end subroutine add_assembly_sets

  subroutine report_clash(st, b, part, inst, j, elem)
    !! Assembly-level set j of instance inst (entry b) has the name of a set
    !! of its part: superjoin keeps an assembly set with INSTANCE= as a set
    !! of the instance, so the two would merge (Abaqus keeps the assembly set
    !! S apart from the part's, inst.S): reported at the assembly set's card,
    !! naming the part's set and where it is defined.
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b, part
    character(*), intent(in) :: inst
    integer, intent(in) :: j
    logical, intent(in) :: elem
    character(:), allocatable :: what, name, at, other
    type(source_loc_t) :: loc, part_loc
    integer :: jpart
    what = set_word(elem)
    call set_card(b, j, elem, name, loc)
    at = ''   ! the part's sets are those of its entry (resolve_sets), so found: the guard is defensive
    jpart = find_set(part, name, elem)
    if (jpart > 0) then
       call set_card(part, jpart, elem, other, part_loc)
       at = ' ('//where(st, part_loc)//')'
    end if
    call report_loc(st, loc, 'assembly-level '//what//' '//name//' (INSTANCE='//inst//') has the name of '// &
         what//' '//name//' of part '//part%name//at//': both would be '//inst//'.'//name// &
         ' and superjoin would merge them (Abaqus keeps them apart); rename the assembly-level set')
  end subroutine report_clash

  subroutine report_main_clash(st, b, inst, j, elem)
    !! Assembly-level set j of instance inst (entry b) has the name of a set
    !! of the same kind written in the assembly without INSTANCE= (MAIN's):
    !! Abaqus makes the two cards one assembly set; superjoin keeps MAIN's
    !! apart from the instance's, and a plain name would take MAIN's alone.
    !! Reported at the INSTANCE= card, naming MAIN's set and where it is.
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b
    character(*), intent(in) :: inst
    integer, intent(in) :: j
    logical, intent(in) :: elem
    character(:), allocatable :: what, name, other
    type(source_loc_t) :: loc, main_loc
    integer :: kmain, jmain
    kmain = find_sub(st, MAIN_NAME)
    if (kmain == 0) return
    if (st%subs(kmain)%kind /= SUBK_PLAIN) return
    what = set_word(elem)
    call set_card(b, j, elem, name, loc)
    jmain = find_set(st%subs(kmain), name, elem)
    if (jmain == 0) return
    call set_card(st%subs(kmain), jmain, elem, other, main_loc)
    call report_loc(st, loc, 'assembly-level '//what//' '//name//' (INSTANCE='//inst//') has the name of the '// &
         'assembly''s own '//what//' '//name//' ('//where(st, main_loc)//'): Abaqus makes them one set, '// &
         'superjoin keeps them apart and a plain '//name//' would name the assembly''s alone; rename one of them')
  end subroutine report_main_clash

  subroutine set_card(sub, j, elem, name, loc)
    !! Name and card of element set (elem) or node set j of entry sub.
    type(sub_b_t), intent(in) :: sub
    integer, intent(in) :: j
    logical, intent(in) :: elem
    character(:), allocatable, intent(out) :: name
    type(source_loc_t), intent(out) :: loc
    if (elem) then
       name = sub%elsets(j)%name
       loc = sub%elsets(j)%loc
    else
       name = sub%nsets(j)%name
       loc = sub%nsets(j)%loc
    end if
  end subroutine set_card

  pure function set_word(elem) result(s)
    !! 'element set' or 'node set', for the messages.
    logical, intent(in) :: elem
    character(:), allocatable :: s
    s = pick(elem, 'element set', 'node set')
  end function set_word

  subroutine place_copy(st, part, inst, m)
    !! m = part placed by inst (m keeps its name and location).
    type(deck_state_t), intent(inout) :: st
    type(substructure_t), intent(in) :: part
    type(instance_b_t), intent(in) :: inst
    type(substructure_t), intent(inout) :: m
    character(:), allocatable :: name
    type(source_loc_t) :: loc
    integer(ip) :: i, e
    integer :: s, nsec, nx
    type(section_t), allocatable :: secs(:)

    name = m%name
    loc = m%loc
    m = part
    m%name = name
    m%loc = loc
    m%rot = inst%rot
    m%shift = inst%shift
    if (allocated(m%given) .and. .not. all(inst%rot == IDENTITY)) call turn_given(st, inst, m)
    do i = 1, m%nnode
       m%x(:, i) = matmul(inst%rot, part%x(:, i)) + inst%shift
    end do
    if (.not. all(ieee_is_finite(m%x))) then
       call report_loc(st, inst%loc, '*INSTANCE '//name//': placed coordinates overflow the floating-point range')
       m%x = 0.0_wp
       return
    end if
    do s = 1, size(m%sections)          ! material axes (*SOLID SECTION, ORIENTATION=) move with the instance
       if (.not. allocated(m%sections(s)%axes)) cycle
       associate (ax => m%sections(s)%axes)
         ax%q = matmul(ax%q, transpose(inst%rot))
         ax%a = matmul(inst%rot, ax%a) + inst%shift
         ax%b = matmul(inst%rot, ax%b) + inst%shift
       end associate
    end do
    if (all(inst%rot == IDENTITY)) return

    if (abs(inst%rot(3, 3) - 1.0_wp) > PLANE_ROT_TOL) then
       do e = 1, m%nelem
          if (must_stay_in_plane(m%elem_type(e))) then
             call report_loc(st, inst%loc, '*INSTANCE '//name//' turns element '//itoa(m%elem_id(e))//' ('// &
                  trim(ELEMENT_TYPE_NAMES(m%elem_type(e)))//') of its part out of the XY plane '// &
                  '(2D parts turn only about an axis parallel to Z)')
             return
          end if
       end do
    end if

    ! 3D beam sections: v turns with the instance; the default v (global Z, or
    ! global X for a member parallel to Z) is the part's, so it becomes explicit.
    nsec = size(m%sections)
    secs = m%sections
    do s = 1, nsec
       if (m%sections(s)%kind /= SEC_BEAM) cycle
       if (m%sections(s)%has_v) then
          secs(s)%v = matmul(inst%rot, m%sections(s)%v)
          cycle
       end if
       nx = 0
       do e = 1, m%nelem
          if (m%elem_section(e) /= s .or. .not. beam_in_space(m%elem_type(e))) cycle
          if (default_is_x(e)) nx = nx + 1
       end do
       secs(s)%has_v = .true.
       secs(s)%v = matmul(inst%rot, GLOBAL_Z)
       if (nx == 0) cycle
       ! members parallel to Z get a section of their own with v = R X
       secs = [secs, secs(s)]
       secs(size(secs))%v = matmul(inst%rot, GLOBAL_X)
       do e = 1, m%nelem
          if (m%elem_section(e) /= s .or. .not. beam_in_space(m%elem_type(e))) cycle
          if (default_is_x(e)) m%elem_section(e) = size(secs)
       end do
    end do
    call move_alloc(secs, m%sections)
  contains
    logical function default_is_x(e)
      !! The default orientation of beam e of the part is global X (as superjoin_elements_frame):
      !! its ends (the first and last node) lie on a line parallel to Z.
      integer(ip), intent(in) :: e
      real(wp) :: d(3)
      integer :: last
      default_is_x = .false.
      last = ELEMENT_NODE_COUNT(part%elem_type(e))
      if (part%elem_nodes(1, e) == 0 .or. part%elem_nodes(last, e) == 0) return   ! undefined node, reported
      d = part%x(:, part%elem_nodes(last, e)) - part%x(:, part%elem_nodes(1, e))
      if (norm2(d) == 0.0_wp) return
      default_is_x = norm2(cross(d/norm2(d), GLOBAL_Z)) <= DEFAULT_V_SWITCH_TOL
    end function default_is_x
  end subroutine place_copy

  pure logical function must_stay_in_plane(etype)
    !! An element of type etype that a turned instance may not take out of the
    !! XY plane: the planar types (B21 included; it was left out and then
    !! refused later as a 2D element out of the XY plane).
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    must_stay_in_plane = tr%planar
  end function must_stay_in_plane

  pure logical function beam_in_space(etype)
    !! A beam in space (B33, B31, B32), whose default orientation vector a turned
    !! instance makes explicit (B31 and B32 were left out: a vertical B31 column
    !! of a turned part got v = R Z along its own axis and was refused).
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    beam_in_space = tr%family == FAMILY_BEAM .and. .not. tr%planar
  end function beam_in_space

  subroutine pair_nearest(st, model, icontact, loc, ms, ss, ok)
    !! PAIR=NEAREST: ms becomes, for each slave node ss(j), its nearest master node.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: icontact
    type(source_loc_t), intent(in) :: loc
    integer(ip), allocatable, intent(inout) :: ms(:)
    integer(ip), intent(in) :: ss(:)
    logical, intent(out) :: ok
    type(halting_t) :: saved
    call halting_off(saved)
    call pair_by_distance(st, model, icontact, loc, ms, ss, ok)
    call halting_restore(saved)
  end subroutine pair_nearest

  subroutine pair_by_distance(st, model, icontact, loc, ms, ss, ok)
    !! pair_nearest with floating-point halting off (an overflowing distance pairs nothing).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: icontact
    type(source_loc_t), intent(in) :: loc
    integer(ip), allocatable, intent(inout) :: ms(:)
    integer(ip), intent(in) :: ss(:)
    logical, intent(out) :: ok
    integer, allocatable :: order(:), taken(:)
    integer(ip), allocatable :: paired(:)
    real(wp), allocatable :: key(:)
    real(wp) :: tol, xs(3), d, best
    integer :: nm, j, lo, hi, mid, i, ib
    ok = .false.
    tol = st%contacts(icontact)%tol
    associate (c => model%contacts(icontact), msub => model%subs(model%contacts(icontact)%master_sub), &
         ssub => model%subs(model%contacts(icontact)%slave_sub))
      nm = size(ms)
      allocate (order(nm), key(nm), taken(nm), paired(size(ss)))
      do i = 1, nm
         order(i) = i
         key(i) = msub%x(1, ms(i))
      end do
      call sort_index(key, order)
      taken = 0
      do j = 1, size(ss)
         xs = ssub%x(:, ss(j))
         ! first master with x >= xs(1) - tol
         lo = 1
         hi = nm + 1
         do while (lo < hi)
            mid = lo + (hi - lo)/2
            if (key(order(mid)) < xs(1) - tol) then
               lo = mid + 1
            else
               hi = mid
            end if
         end do
         ib = 0
         best = huge(best)
         do i = lo, nm
            if (key(order(i)) > xs(1) + tol) exit
            d = norm2(msub%x(:, ms(order(i))) - xs)
            if (d > tol) cycle
            ! nearest; equal distances: the master node first in the master set
            if (d < best .or. (d == best .and. order(i) < ib)) then
               best = d
               ib = order(i)
            end if
         end do
         if (ib == 0) then
            call report_loc(st, loc, 'PAIR=NEAREST of contact '//c%name//': slave node '// &
                 node_label(model, c%slave_sub, ss(j))//' at '//point_text(xs)//' has no master node within TOL='// &
                 real_text(tol))
            return
         end if
         if (taken(ib) > 0) then
            call report_loc(st, loc, 'PAIR=NEAREST of contact '//c%name//': master node '// &
                 node_label(model, c%master_sub, ms(ib))//' at '//point_text(msub%x(:, ms(ib)))// &
                 ' is the nearest to two slave nodes, '//node_label(model, c%slave_sub, ss(taken(ib)))// &
                 ' and '//node_label(model, c%slave_sub, ss(j)))
            return
         end if
         taken(ib) = j
         paired(j) = ms(ib)
      end do
    end associate
    call move_alloc(paired, ms)
    ok = .true.
  end subroutine pair_by_distance

  pure function point_text(x) result(s)
    !! (x, y, z) for messages.
    real(wp), intent(in) :: x(3)
    character(:), allocatable :: s
    s = '('//real_text(x(1))//', '//real_text(x(2))//', '//real_text(x(3))//')'
  end function point_text

  subroutine build_overrides(st, model)
    !! *CHANGE CONTACT: per-step link overrides; SWEEP steps expanded.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(step_t), allocatable :: steps(:)
    type(override_work_t) :: w
    integer :: s, n, i, nout
    logical :: any_change
    logical, allocatable :: expanded(:)

    any_change = .false.
    do s = 1, st%nstep
       if (st%steps(s)%noverride > 0) any_change = .true.
    end do
    if (.not. any_change) return
    call contact_link_ranges(model, w)
    nout = 0
    do s = 1, st%nstep
       nout = nout + max(1, st%steps(s)%nsweep)
    end do
    allocate (steps(nout), expanded(nout))
    nout = 0
    do s = 1, st%nstep
       n = st%steps(s)%nsweep
       do i = 1, max(1, n)
          nout = nout + 1
          steps(nout) = model%steps(s)
          expanded(nout) = n > 0
          if (n > 0) steps(nout)%name = model%steps(s)%name//'-'//itoa(i)
          call step_overrides(st, model, w, st%steps(s), i, steps(nout))
          if (st%aborted) return
       end do
    end do
    call check_expanded_names(st, steps, expanded)
    call move_alloc(steps, model%steps)
  end subroutine build_overrides

  subroutine contact_link_ranges(model, w)
    !! The links of each contact: w%first_link(c) to w%last_link(c) (the links
    !! of one contact are contiguous: build_contacts reads the lines card by card).
    type(model_t), intent(in) :: model
    type(override_work_t), intent(inout) :: w
    integer :: l
    allocate (w%first_link(size(model%contacts)), w%last_link(size(model%contacts)))
    w%first_link = 1
    w%last_link = 0
    do l = size(model%links), 1, -1
       w%first_link(model%links(l)%contact) = l
    end do
    do l = 1, size(model%links)
       w%last_link(model%links(l)%contact) = l
    end do
  end subroutine contact_link_ranges

  subroutine check_expanded_names(st, steps, expanded)
    !! Report a step name that a SWEEP expansion repeats.
    type(deck_state_t), intent(inout) :: st
    type(step_t), intent(in) :: steps(:)
    logical, intent(in) :: expanded(:)
    integer :: s, j
    do s = 2, size(steps)
       do j = 1, s - 1
          if (.not. (expanded(j) .or. expanded(s))) cycle
          if (steps(j)%name == steps(s)%name) then
             call report_loc(st, steps(s)%loc, 'duplicate step name '//steps(s)%name// &
                  ' (first at '//where(st, steps(j)%loc)//')')
             exit
          end if
       end do
    end do
  end subroutine check_expanded_names

  subroutine step_overrides(st, model, w, sb, ivalue, step)
    !! The overrides of value ivalue of step sb's *CHANGE CONTACT lines (the
    !! node pairs are resolved, and their errors reported, for the first value only).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(override_work_t), intent(inout) :: w
    type(step_b_t), intent(in) :: sb
    integer, intent(in) :: ivalue
    type(step_t), intent(inout) :: step
    type(link_override_t), allocatable :: list(:)
    integer :: k, nl, v, d, jj
    integer(ip) :: p
    if (ivalue == 1) call resolve_override_links(st, model, w, sb)
    allocate (list(0))
    nl = 0
    do k = 1, sb%noverride
       associate (o => sb%overrides(k))
         if (.not. allocated(w%line_links(k)%items)) cycle
         v = min(ivalue, size(o%gs))
         do p = 1, size(w%line_links(k)%items, kind=ip)
            ! one override per link and step; later lines change it further
            jj = 0
            do d = 1, nl
               if (list(d)%link == w%line_links(k)%items(p)) jj = d
            end do
            if (jj == 0) then
               list = [list, link_override_t(link=int(w%line_links(k)%items(p)))]
               nl = nl + 1
               jj = nl
            end if
            do d = o%first, o%last
               list(jj)%dofs(d) = .true.
               list(jj)%state(d) = o%states(v)
               list(jj)%g(d) = merge(o%gs(v), 0.0_wp, o%states(v) == LINK_FINITE)
            end do
         end do
       end associate
    end do
    call move_alloc(list, step%link_overrides)
  end subroutine step_overrides

  subroutine resolve_override_links(st, model, w, sb)
    !! w%line_links(k): the links that line k of the step's *CHANGE CONTACT names
    !! (unallocated when the line is in error, reported).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(override_work_t), intent(inout) :: w
    type(step_b_t), intent(in) :: sb
    integer(ip), allocatable :: ms(:), ss(:)
    integer :: k, il, l
    integer(ip) :: p
    logical :: ok1, ok2
    if (allocated(w%line_links)) deallocate (w%line_links)
    allocate (w%line_links(sb%noverride))
    lines: do k = 1, sb%noverride
       associate (o => sb%overrides(k))
         if (o%contact == 0) cycle   ! a part's contact, reported by unfold_nested
         associate (c => model%contacts(o%contact))
           if (c%master_sub == 0 .or. c%slave_sub == 0) cycle
           if (o%whole) then
              call whole_contact_links(st, w, o, c%name, w%line_links(k))
              cycle
           end if
           call resolve_items(st, model, c%master_sub, o%master, .false., o%loc, ms, ok1)
           call resolve_items(st, model, c%slave_sub, o%slave, .false., o%loc, ss, ok2)
           if (.not. (ok1 .and. ok2)) cycle
           if (st%contacts(o%contact)%nearest) then
              call pair_nearest(st, model, o%contact, o%loc, ms, ss, ok1)
              if (.not. ok1) cycle
           end if
           if (size(ms) /= size(ss)) then
              call report_loc(st, o%loc, '*CHANGE CONTACT '//c%name//': '//plural(size(ms), 'master node')// &
                   ' against '//plural(size(ss), 'slave node')//' (they pair in order, as on *CONTACT)')
              cycle
           end if
           allocate (w%line_links(k)%items(size(ms)))
           do p = 1, size(ms, kind=ip)
              il = 0
              do l = w%first_link(o%contact), w%last_link(o%contact)
                 if (model%links(l)%master_node == ms(p) .and. model%links(l)%slave_node == ss(p)) then
                    il = l
                    exit
                 end if
              end do
              if (il == 0) then
                 call report_loc(st, o%loc, '*CHANGE CONTACT '//c%name//': nodes '// &
                      node_label(model, c%master_sub, ms(p))//' and '//node_label(model, c%slave_sub, ss(p))// &
                      ' are not a pair of contact '//c%name)
                 deallocate (w%line_links(k)%items)
                 cycle lines
              end if
              w%line_links(k)%items(p) = il
           end do
         end associate
       end associate
    end do lines
  end subroutine resolve_override_links

  subroutine whole_contact_links(st, w, o, name, links)
    !! The links of a *CHANGE CONTACT line that names its contact: every pair of
    !! it (unallocated, reported, when a DOF of the line is one that no line of
    !! the *CONTACT card names).
    type(deck_state_t), intent(inout) :: st
    type(override_work_t), intent(in) :: w
    type(override_b_t), intent(in) :: o
    character(*), intent(in) :: name
    type(index_set_t), intent(out) :: links
    integer :: d, l
    logical :: named
    do d = o%first, o%last
       named = .false.
       do l = 1, st%ncline
          associate (cl => st%clines(l))
            if (cl%contact == o%contact .and. cl%first <= d .and. d <= cl%last) named = .true.
          end associate
       end do
       if (.not. named) then
          call report_loc(st, o%loc, '*CHANGE CONTACT: contact '//name//' has no DOF '//itoa(d)// &
               ' (no data line of its *CONTACT card names it)')
          return
       end if
    end do
    allocate (links%items(max(0, w%last_link(o%contact) - w%first_link(o%contact) + 1)))
    do l = 1, size(links%items)
       links%items(l) = w%first_link(o%contact) + l - 1
    end do
  end subroutine whole_contact_links
end module superjoin_deck_assembly
