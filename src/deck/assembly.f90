submodule (superjoin_deck_validate) superjoin_deck_assembly
  !! Validation side of parts, instances and joint studies (see
  !! superjoin_deck_cards_assembly for the cards):
  !!
  !! - every *INSTANCE becomes a substructure: a copy of its part's nodes (placed,
  !!   x' = rot x + shift), elements, sets and sections; the orientation vectors of
  !!   3D beam sections turn with the instance, so a rotated instance is the same
  !!   structure turned; then the parts leave model%subs;
  !! - PAIR=NEAREST on *CONTACT: each slave node takes the nearest master node;
  !! - *CHANGE CONTACT: per-step link overrides, SWEEP steps expanded.
  use superjoin_model_types, only: ET_S8R
  use superjoin_model_types, only: section_t, link_override_t, step_t, node_label, MAX_ELEMENT_NODES, &
       orientation_t
  use superjoin_deck_state, only: SUBK_PART, SUBK_INSTANCE, instance_b_t, step_b_t
  use superjoin_elements_frame, only: DEFAULT_V_SWITCH_TOL, cross, real_text
  use superjoin_utils_sorting, only: stable_argsort
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none (type, external)

  real(wp), parameter :: IDENTITY(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
       0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  real(wp), parameter :: GLOBAL_X(3) = [1.0_wp, 0.0_wp, 0.0_wp], GLOBAL_Z(3) = [0.0_wp, 0.0_wp, 1.0_wp]
  real(wp), parameter :: PLANE_ROT_TOL = 1.0e-12_wp
    !! A part with 2D elements may only turn about an axis parallel to Z: |R33 - 1| <= this.

contains

  ! ================================================================== instances

  module subroutine empty_sub(b, m)
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

  module subroutine place_instances(st, model)
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
    integer :: k, p, nparts, nkeep, s, j

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

    do k = 1, st%nsub
       if (st%subs(k)%kind /= SUBK_INSTANCE) cycle
       associate (inst => st%instances(st%subs(k)%inst))
         p = 0
         do j = 1, st%nsub
            if (st%subs(j)%kind == SUBK_PART .and. st%subs(j)%name == inst%part) p = j
         end do
         if (p == 0) then
            call report_loc(st, inst%loc, '*INSTANCE '//st%subs(k)%name//' of undefined part '//inst%part)
            cycle
         end if
         ! an instance whose data lines were refused is placed as far as they were
         ! read, so that its nodes exist for the references (no second error)
         call place_copy(st, model%subs(p), inst, model%subs(k))
         model%subs(k)%part = part_ord(p)
         call add_assembly_sets(st, st%subs(k), model%subs(k))
       end associate
       if (st%aborted) return
    end do

    ! the parts leave the model; indices of the remaining substructures shift
    allocate (new_index(st%nsub))
    nkeep = 0
    do k = 1, st%nsub
       new_index(k) = 0
       if (st%subs(k)%kind == SUBK_PART) cycle
       nkeep = nkeep + 1
       new_index(k) = nkeep
    end do
    if (nkeep == 0) then
       call report(st, 1, 1, 'the deck defines parts but places no instance of them (*ASSEMBLY, *INSTANCE)')
       return
    end if
    allocate (subs(nkeep))
    do k = 1, st%nsub
       if (new_index(k) > 0) subs(new_index(k)) = model%subs(k)
    end do
    call move_alloc(subs, model%subs)
    do k = 1, st%nsupport
       call renumber(st%supports(k)%ref%home)
    end do
    do k = 1, st%ntemp
       call renumber(st%temps(k)%ref%home)
    end do
    do s = 1, st%nstep
       do j = 1, st%steps(s)%ncload
          call renumber(st%steps(s)%cloads(j)%ref%home)
          call renumber(st%steps(s)%cloads(j)%home)
       end do
       do j = 1, st%steps(s)%ndload
          call renumber(st%steps(s)%dloads(j)%ref%home)
          call renumber(st%steps(s)%dloads(j)%home)
       end do
    end do
  contains
    subroutine renumber(home)
      integer, intent(inout) :: home
      if (home > 0) home = new_index(home)
    end subroutine renumber
  end subroutine place_all

  subroutine add_assembly_sets(st, b, m)
    !! The sets that *NSET/*ELSET, INSTANCE= define on instance m (Abaqus
    !! assembly-level sets), after the sets copied from its part.
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b
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
            if (keep(i)%name == all(j)%name) then
               if (elem) then
                  call report_loc(st, b%elsets(j)%loc, 'element set '//all(j)%name//' of instance '//m%name// &
                       ' is already a set of its part')
               else
                  call report_loc(st, b%nsets(j)%loc, 'node set '//all(j)%name//' of instance '//m%name// &
                       ' is already a set of its part')
               end if
            end if
         end do
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

  module integer function assembly_set_owner(model, name, elem, main) result(k)
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    logical, intent(in) :: elem
    integer, intent(in) :: main
    integer :: i, nfound
    k = main
    if (main > 0) then
       if (has_set(main)) return
    end if
    nfound = 0
    do i = 1, size(model%subs)
       if (model%subs(i)%part == 0) cycle
       if (has_set(i)) then
          nfound = nfound + 1
          if (nfound == 1) k = i
       end if
    end do
    if (nfound /= 1) k = main
  contains
    logical function has_set(isub)
      integer, intent(in) :: isub
      integer :: j
      has_set = .false.
      if (elem) then
         do j = 1, size(model%subs(isub)%elsets)
            if (model%subs(isub)%elsets(j)%name == name) has_set = .true.
         end do
      else
         do j = 1, size(model%subs(isub)%nsets)
            if (model%subs(isub)%nsets(j)%name == name) has_set = .true.
         end do
      end if
    end function has_set
  end function assembly_set_owner

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
    do i = 1, m%nnode
       m%x(:, i) = matmul(inst%rot, part%x(:, i)) + inst%shift
    end do
    if (.not. all(ieee_is_finite(m%x))) then
       call report_loc(st, inst%loc, '*INSTANCE '//name//': placed coordinates overflow the floating-point range')
       m%x = 0.0_wp
       return
    end if
    if (all(inst%rot == IDENTITY)) return

    if (abs(inst%rot(3, 3) - 1.0_wp) > PLANE_ROT_TOL) then
       do e = 1, m%nelem
          select case (m%elem_type(e))
          case (ET_T2D2, ET_B23, ET_CPS3, ET_CPS4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, &
               ET_CPS8R, ET_CPE8R)
             call report_loc(st, inst%loc, '*INSTANCE '//name//' turns element '//itoa(m%elem_id(e))//' ('// &
                  trim(ELEMENT_TYPE_NAMES(m%elem_type(e)))//') of its part out of the XY plane '// &
                  '(2D parts turn only about an axis parallel to Z)')
             return
          end select
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
          if (m%elem_section(e) /= s .or. m%elem_type(e) /= ET_B33) cycle
          if (default_is_x(e)) nx = nx + 1
       end do
       secs(s)%has_v = .true.
       secs(s)%v = matmul(inst%rot, GLOBAL_Z)
       if (nx == 0) cycle
       ! members parallel to Z get a section of their own with v = R X
       secs = [secs, secs(s)]
       secs(size(secs))%v = matmul(inst%rot, GLOBAL_X)
       do e = 1, m%nelem
          if (m%elem_section(e) /= s .or. m%elem_type(e) /= ET_B33) cycle
          if (default_is_x(e)) m%elem_section(e) = size(secs)
       end do
    end do
    call move_alloc(secs, m%sections)
  contains
    logical function default_is_x(e)
      !! The default orientation of beam e of the part is global X (as superjoin_elements_frame).
      integer(ip), intent(in) :: e
      real(wp) :: d(3)
      default_is_x = .false.
      if (any(part%elem_nodes(1:2, e) == 0)) return   ! undefined node, reported
      d = part%x(:, part%elem_nodes(2, e)) - part%x(:, part%elem_nodes(1, e))
      if (norm2(d) == 0.0_wp) return
      default_is_x = norm2(cross(d/norm2(d), GLOBAL_Z)) <= DEFAULT_V_SWITCH_TOL
    end function default_is_x
  end subroutine place_copy

  module function part_hint(model, name) result(s)
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

  ! ================================================================== PAIR=NEAREST

  module subroutine pair_nearest(st, model, icontact, loc, ms, ss, ok)
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
      call stable_argsort(key, order)
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


  ! ================================================================== *INTERFACE

  module subroutine build_interfaces(st, model)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: k
    type(halting_t) :: saved
    call halting_off(saved)
    call build_all_interfaces()
    call halting_restore(saved)
  contains
    subroutine build_all_interfaces()
    do k = 1, st%ncontact
       if (.not. st%contacts(k)%is_interface) cycle
       call build_interface(st, model, k)
       if (st%aborted) return
    end do
    end subroutine build_all_interfaces
  end subroutine build_interfaces

  subroutine build_interface(st, model, k)
    !! Contact elements of *INTERFACE k: node pairs by position, stiffness KN
    !! (normal) and KT (tangential) times the tributary length (edge joints) or
    !! area (face joints) of the master node, in the joint's frame.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, intent(in) :: k
    integer(ip), allocatable :: ms(:), ss(:)
    real(wp), allocatable :: trib(:)
    logical, allocatable :: inset(:)
    logical :: ok1, ok2, face, planar, first
    real(wp) :: q(3, 3), n(3), t(3), w(3), d(3), ref(3), cen(3), mid(3), len_e, lo(3), hi(3)
    integer(ip) :: e, a, b, p, i
    integer :: nn, j, m
    type(link_t), allocatable :: new(:)
    character(:), allocatable :: what
    real(wp), parameter :: FLAT_TOL = 1.0e-8_wp
      !! Edges (faces) of one joint are parallel when |t_e × t_1| (|n_e × n_1|) <= this.
    real(wp), parameter :: DEFAULT_TOL = 1.0e-6_wp
      !! Default TOL: this times the size of the master node set.

    associate (cb => st%contacts(k), c => model%contacts(k))
      if (c%master_sub == 0 .or. c%slave_sub == 0) return
      if (cb%iface_loc%line == 0) then
         call report_loc(st, cb%loc, '*INTERFACE '//cb%name//' needs a data line: master node set, slave node set')
         return
      end if
      call resolve_items(st, model, c%master_sub, cb%iface_master, .false., cb%iface_loc, ms, ok1)
      call resolve_items(st, model, c%slave_sub, cb%iface_slave, .false., cb%iface_loc, ss, ok2)
      if (.not. (ok1 .and. ok2)) return
      associate (sub => model%subs(c%master_sub))
        allocate (inset(sub%nnode), trib(sub%nnode))
        inset = .false.
        inset(ms) = .true.
        trib = 0.0_wp
        ! face joint: plane or shell elements with every node on the set
        face = .false.
        do e = 1, sub%nelem
           nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
           if (any(sub%elem_nodes(1:nn, e) == 0)) cycle   ! undefined node, reported
           select case (sub%elem_type(e))
           case (ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, ET_B32, ET_S8R)
              if (count(inset(sub%elem_nodes(1:nn, e))) >= 2) then
                 call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': element '//itoa(sub%elem_id(e))// &
                      ' ('//trim(ELEMENT_TYPE_NAMES(sub%elem_type(e)))//') on node set '// &
                      ref_text(cb%iface_master)//' is a second-order element; the tributary shares of '// &
                      'its mid-side nodes are not implemented: join it with *CONTACT lines')
                 return
              end if
           end select
           select case (sub%elem_type(e))
           case (ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_S4R, ET_S3R)
              if (all(inset(sub%elem_nodes(1:nn, e)))) face = .true.
           end select
        end do
        first = .true.
        planar = .true.
        if (face) then
           do e = 1, sub%nelem
              nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
              if (any(sub%elem_nodes(1:nn, e) == 0)) cycle
              select case (sub%elem_type(e))
              case (ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_S4R, ET_S3R)
                 if (.not. all(inset(sub%elem_nodes(1:nn, e)))) cycle
                 call face_share(sub%x(:, sub%elem_nodes(1:nn, e)), trib, sub%elem_nodes(1:nn, e), d)
                 if (norm2(d) == 0.0_wp) cycle   ! a degenerate face adds nothing
                 if (first) then
                    n = d
                    first = .false.
                 else if (norm2(cross(n, d)) > FLAT_TOL) then
                    call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the faces on node set '// &
                         ref_text(cb%iface_master)//' are not in one plane (element '//itoa(sub%elem_id(e))// &
                         '); split the joint into flat *INTERFACE cards')
                    return
                 end if
              end select
           end do
           what = 'area'
        else
           do e = 1, sub%nelem
              nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
              if (any(sub%elem_nodes(1:nn, e) == 0)) cycle
              select case (sub%elem_type(e))
              case (ET_T2D2, ET_T3D2, ET_B23, ET_B33)
                 m = 1
              case default
                 m = nn
              end select
              do j = 1, m
                 a = sub%elem_nodes(j, e)
                 b = sub%elem_nodes(mod(j, nn) + 1, e)
                 if (.not. (inset(a) .and. inset(b))) cycle
                 if (shared_edge(e, a, b)) cycle
                 d = sub%x(:, b) - sub%x(:, a)
                 len_e = norm2(d)
                 if (len_e == 0.0_wp) cycle
                 trib(a) = trib(a) + len_e/2
                 trib(b) = trib(b) + len_e/2
                 select case (sub%elem_type(e))
                 case (ET_T2D2, ET_B23, ET_CPS3, ET_CPS4)
                 case default
                    planar = .false.
                 end select
                 if (first) then
                    t = d/len_e
                    first = .false.
                    ! the normal points out of the master element
                    cen = sum(sub%x(:, sub%elem_nodes(1:nn, e)), dim=2)/nn
                    mid = (sub%x(:, a) + sub%x(:, b))/2
                    ref = mid - cen
                    if (nn == 2) ref = 0.0_wp
                    select case (sub%elem_type(e))
                    case (ET_S3, ET_S4, ET_S4R, ET_S3R)
                       w = face_normal(sub%x(:, sub%elem_nodes(1:nn, e)))
                    case default
                       w = [0.0_wp, 0.0_wp, 1.0_wp]
                    end select
                 else if (norm2(cross(t, d/len_e)) > FLAT_TOL) then
                    call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the edges on node set '// &
                         ref_text(cb%iface_master)//' are not on one straight line (element '// &
                         itoa(sub%elem_id(e))//'); split the joint into straight *INTERFACE cards')
                    return
                 end if
              end do
           end do
           what = 'length'
           if (.not. first) then
              if (.not. planar .and. all(w == [0.0_wp, 0.0_wp, 1.0_wp]) .and. norm2(ref) == 0.0_wp) then
                 call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': a joint along 3D beams or trusses has '// &
                      'no normal direction; use *CONTACT with an *ORIENTATION')
                 return
              end if
              n = cross(w, t)
              if (norm2(n) == 0.0_wp) then
                 call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the joint edges have no normal '// &
                      '(degenerate elements)')
                 return
              end if
              n = n/norm2(n)
              if (dot_product(n, ref) < 0.0_wp) n = -n
              ! tangential axis: w × n (in 2D the normal turned 90 degrees counterclockwise)
              t = cross(w, n)
              t = t/norm2(t)
           end if
        end if
        if (first .and. .not. face) then
           call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': no element edge or face of '// &
                model%subs(c%master_sub)%name//' lies on node set '//ref_text(cb%iface_master))
           return
        end if
        ! frame: 1 normal, 2 and 3 tangential
        if (face .and. first) then
           call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the faces on node set '// &
                ref_text(cb%iface_master)//' have no area (degenerate elements)')
           return
        end if
        n = n/norm2(n)
        if (face) then
           d = [1.0_wp, 0.0_wp, 0.0_wp]
           if (abs(n(1)) > 0.9_wp) d = [0.0_wp, 1.0_wp, 0.0_wp]
           t = d - dot_product(d, n)*n
           t = t/norm2(t)
        end if
        q(1, :) = n
        q(2, :) = t
        q(3, :) = cross(n, t)
        ! pairing by position
        if (cb%tol < 0.0_wp) then
           lo = sub%x(:, ms(1))
           hi = lo
           do i = 1, size(ms, kind=ip)
              lo = min(lo, sub%x(:, ms(i)))
              hi = max(hi, sub%x(:, ms(i)))
           end do
           cb%tol = DEFAULT_TOL*norm2(hi - lo)
        end if
        call pair_nearest(st, model, k, cb%iface_loc, ms, ss, ok1)
        if (.not. ok1) return
        allocate (new(size(ms)))
        do p = 1, size(ms, kind=ip)
           if (.not. (ieee_is_finite(cb%kn*trib(ms(p))) .and. ieee_is_finite(cb%kt*trib(ms(p))))) then
              call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the joint stiffness overflows the '// &
                   'floating-point range')
              return
           end if
           if (trib(ms(p)) == 0.0_wp) then
              call report_loc(st, cb%iface_loc, '*INTERFACE '//cb%name//': node '// &
                   node_label(model, c%master_sub, ms(p))//' lies on no edge or face of the joint '// &
                   '(no tributary '//what//')')
              return
           end if
           new(p)%contact = k
           new(p)%master_node = ms(p)
           new(p)%slave_node = ss(p)
           new(p)%loc = cb%iface_loc
           call set_dof(new(p), 1, cb%kn*trib(ms(p)))
           call set_dof(new(p), 2, cb%kt*trib(ms(p)))
           if (.not. (planar .and. .not. face)) call set_dof(new(p), 3, cb%kt*trib(ms(p)))
        end do
      end associate
      call add_orientation_frame(model, cb%name, q, cb%loc)
      c%orientation = size(model%orientations)
      model%links = [model%links, new]
    end associate
  contains
    logical function shared_edge(e, a, b)
      !! The edge a-b was counted already on an earlier element.
      integer(ip), intent(in) :: e, a, b
      integer(ip) :: f
      integer :: jj, nf, mm
      shared_edge = .false.
      associate (sub => model%subs(model%contacts(k)%master_sub))
        do f = 1, e - 1
           nf = ELEMENT_NODE_COUNT(sub%elem_type(f))
           mm = merge(1, nf, nf == 2)
           do jj = 1, mm
              if ((sub%elem_nodes(jj, f) == a .and. sub%elem_nodes(mod(jj, nf) + 1, f) == b) .or. &
                   (sub%elem_nodes(jj, f) == b .and. sub%elem_nodes(mod(jj, nf) + 1, f) == a)) then
                 shared_edge = .true.
                 return
              end if
           end do
        end do
      end associate
    end function shared_edge
    subroutine set_dof(l, dof, g)
      type(link_t), intent(inout) :: l
      integer, intent(in) :: dof
      real(wp), intent(in) :: g
      if (g > 0.0_wp) then
         l%state(dof) = LINK_FINITE
         l%g(dof) = g
      end if
    end subroutine set_dof
  end subroutine build_interface

  subroutine add_orientation_frame(model, name, q, loc)
    !! Append an orientation to model%orientations (explicit growth: an array
    !! constructor of a type with allocatable components leaks with gfortran 12).
    type(model_t), intent(inout) :: model
    character(*), intent(in) :: name
    real(wp), intent(in) :: q(3, 3)
    type(source_loc_t), intent(in) :: loc
    type(orientation_t), allocatable :: tmp(:)
    integer :: n
    n = size(model%orientations)
    allocate (tmp(n + 1))
    tmp(1:n) = model%orientations
    tmp(n + 1)%name = name
    tmp(n + 1)%q = q
    tmp(n + 1)%loc = loc
    call move_alloc(tmp, model%orientations)
  end subroutine add_orientation_frame

  pure function face_normal(x) result(normal)
    !! Unit normal of a 3- or 4-node face (right hand on the node order).
    real(wp), intent(in) :: x(:, :)
    real(wp) :: normal(3)
    if (size(x, 2) == 3) then
       normal = cross(x(:, 2) - x(:, 1), x(:, 3) - x(:, 1))
    else
       normal = cross(x(:, 3) - x(:, 1), x(:, 4) - x(:, 2))
    end if
    if (norm2(normal) > 0.0_wp) normal = normal/norm2(normal)
  end function face_normal

  subroutine face_share(x, trib, nodes, normal)
    !! Adds the tributary area of each node of a 3- or 4-node face to trib(nodes)
    !! (nodes 0: not added) and returns the unit normal (right hand on the node order).
    !! Triangles: A/3 per node; quadrilaterals: the integral of the bilinear shape
    !! function of the node (2x2 Gauss, exact).
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(inout) :: trib(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(out) :: normal(3)
    real(wp), parameter :: GP = 1.0_wp/sqrt(3.0_wp)
    real(wp), parameter :: XI(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], ETA(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    real(wp) :: v(3), dxi(3), deta(3), da, nsh
    integer :: i, g
    normal = 0.0_wp
    if (size(nodes) == 3) then
       v = cross(x(:, 2) - x(:, 1), x(:, 3) - x(:, 1))
       if (norm2(v) == 0.0_wp) return
       normal = v/norm2(v)
       do i = 1, 3
          if (nodes(i) > 0) trib(nodes(i)) = trib(nodes(i)) + norm2(v)/6.0_wp
       end do
       return
    end if
    v = cross(x(:, 3) - x(:, 1), x(:, 4) - x(:, 2))
    if (norm2(v) == 0.0_wp) return
    normal = v/norm2(v)
    do g = 1, 4
       dxi = 0.0_wp
       deta = 0.0_wp
       do i = 1, 4
          dxi = dxi + XI(i)*(1.0_wp + ETA(i)*ETA(g)*GP)/4.0_wp*x(:, i)
          deta = deta + ETA(i)*(1.0_wp + XI(i)*XI(g)*GP)/4.0_wp*x(:, i)
       end do
       da = norm2(cross(dxi, deta))
       do i = 1, 4
          nsh = (1.0_wp + XI(i)*XI(g)*GP)*(1.0_wp + ETA(i)*ETA(g)*GP)/4.0_wp
          if (nodes(i) > 0) trib(nodes(i)) = trib(nodes(i)) + nsh*da
       end do
    end do
  end subroutine face_share

  ! ================================================================== *CHANGE CONTACT

  module subroutine build_overrides(st, model)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(step_t), allocatable :: steps(:)
    integer, allocatable :: first_link(:), last_link(:)
    integer :: s, n, i, nout, l, j
    logical :: any_change
    logical, allocatable :: expanded(:)
    type(index_set_t), allocatable :: line_links(:)

    any_change = .false.
    do s = 1, st%nstep
       if (st%steps(s)%noverride > 0) any_change = .true.
    end do
    if (.not. any_change) return

    ! links of one contact are contiguous (build_contacts reads the lines card by card)
    allocate (first_link(size(model%contacts)), last_link(size(model%contacts)))
    first_link = 1
    last_link = 0
    do l = size(model%links), 1, -1
       first_link(model%links(l)%contact) = l
    end do
    do l = 1, size(model%links)
       last_link(model%links(l)%contact) = l
    end do

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
          call step_overrides(st%steps(s), i, steps(nout))
          if (st%aborted) return
       end do
    end do
    do s = 2, nout
       do j = 1, s - 1
          if (.not. (expanded(j) .or. expanded(s))) cycle
          if (steps(j)%name == steps(s)%name) then
             call report_loc(st, steps(s)%loc, 'duplicate step name '//steps(s)%name// &
                  ' (first at '//where(st, steps(j)%loc)//')')
             exit
          end if
       end do
    end do
    call move_alloc(steps, model%steps)
  contains
    subroutine step_overrides(sb, ivalue, step)
      !! The overrides of value ivalue of step sb's *CHANGE CONTACT lines (the
      !! node pairs are resolved, and their errors reported, for the first value only).
      type(step_b_t), intent(in) :: sb
      integer, intent(in) :: ivalue
      type(step_t), intent(inout) :: step
      type(link_override_t), allocatable :: list(:)
      integer :: k, nl, v, d, jj
      integer(ip) :: p
      if (ivalue == 1) call resolve_override_links(sb)
      allocate (list(0))
      nl = 0
      do k = 1, sb%noverride
         associate (o => sb%overrides(k))
           if (.not. allocated(line_links(k)%items)) cycle
           v = min(ivalue, size(o%gs))
           do p = 1, size(line_links(k)%items, kind=ip)
              ! one override per link and step; later lines change it further
              jj = 0
              do d = 1, nl
                 if (list(d)%link == line_links(k)%items(p)) jj = d
              end do
              if (jj == 0) then
                 list = [list, link_override_t(link=int(line_links(k)%items(p)))]
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

    subroutine resolve_override_links(sb)
      !! line_links(k): the links that line k of the step's *CHANGE CONTACT names
      !! (unallocated when the line is in error, reported).
      type(step_b_t), intent(in) :: sb
      integer(ip), allocatable :: ms(:), ss(:)
      integer :: k, il
      integer(ip) :: p
      logical :: ok1, ok2
      if (allocated(line_links)) deallocate (line_links)
      allocate (line_links(sb%noverride))
      lines: do k = 1, sb%noverride
         associate (o => sb%overrides(k))
           associate (c => model%contacts(o%contact))
             if (c%master_sub == 0 .or. c%slave_sub == 0) cycle
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
             allocate (line_links(k)%items(size(ms)))
             do p = 1, size(ms, kind=ip)
                il = 0
                do l = first_link(o%contact), last_link(o%contact)
                   if (model%links(l)%master_node == ms(p) .and. model%links(l)%slave_node == ss(p)) then
                      il = l
                      exit
                   end if
                end do
                if (il == 0) then
                   call report_loc(st, o%loc, '*CHANGE CONTACT '//c%name//': nodes '// &
                        node_label(model, c%master_sub, ms(p))//' and '//node_label(model, c%slave_sub, ss(p))// &
                        ' are not a pair of contact '//c%name)
                   deallocate (line_links(k)%items)
                   cycle lines
                end if
                line_links(k)%items(p) = il
             end do
           end associate
         end associate
      end do lines
    end subroutine resolve_override_links
  end subroutine build_overrides
end submodule superjoin_deck_assembly
