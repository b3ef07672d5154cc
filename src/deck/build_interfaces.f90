module superjoin_deck_build_interfaces
  !! *INTERFACE: Goodman joints between two faces, lumped to contact elements
  !! by tributary length or area.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, substructure_t, link_t, source_loc_t, ELEMENT_TYPE_NAMES, &
       ELEMENT_NODE_COUNT, LINK_FINITE, node_label, orientation_t
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_TRUSS, FAMILY_BEAM, &
       FAMILY_PLANE, FAMILY_SHELL
  use superjoin_deck_lexer, only: itoa
  use superjoin_deck_state, only: deck_state_t, contact_b_t, report_loc
  use superjoin_elements_frame, only: cross
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use superjoin_deck_build_common, only: ref_text, resolve_items
  use superjoin_deck_assembly, only: pair_nearest
  implicit none (type, external)
  private

  public :: build_interfaces

  real(wp), parameter :: FLAT_TOL = 1.0e-8_wp
    !! Edges (faces) of one joint are parallel when |t_e × t_1| (|n_e × n_1|) <= this.
  real(wp), parameter :: DEFAULT_TOL = 1.0e-6_wp
    !! Default TOL: this times the size of the master node set.

  type :: joint_frame_t
    !! The directions of a joint while its edges or faces are walked.
     logical :: first = .true.     !! no edge or face with a direction yet
     logical :: planar = .true.    !! every edge on an element of the XY plane (edge joints)
     real(wp) :: n(3) = 0.0_wp     !! normal
     real(wp) :: t(3) = 0.0_wp     !! tangential direction (along the edges)
     real(wp) :: w(3) = 0.0_wp     !! normal of the plane of the first edge's element
     real(wp) :: ref(3) = 0.0_wp   !! from the first edge's element to the edge
  end type joint_frame_t

contains

  subroutine build_interfaces(st, model)
    !! *INTERFACE: Goodman joints lumped to contact elements by tributary length or area.
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
    logical :: ok1, ok2, face
    real(wp) :: q(3, 3)
    type(joint_frame_t) :: fr
    type(link_t), allocatable :: new(:)

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
        call scan_master_elements(st, cb, sub, inset, face, ok1)
        if (.not. ok1) return
        if (face) then
           call face_shares(st, cb, sub, inset, trib, fr, ok1)
        else
           call edge_shares(st, cb, sub, inset, trib, fr, ok1)
        end if
        if (.not. ok1) return
        call joint_frame(st, cb, sub, face, fr, q, ok1)
        if (.not. ok1) return
        ! pairing by position
        if (cb%tol < 0.0_wp) cb%tol = DEFAULT_TOL*set_size(sub, ms)
        call pair_nearest(st, model, k, cb%iface_loc, ms, ss, ok1)
        if (.not. ok1) return
        call interface_links(st, model, k, ms, ss, trib, face, fr%planar, new, ok1)
        if (.not. ok1) return
      end associate
      call add_orientation_frame(model, cb%name, q, cb%loc)
      c%orientation = size(model%orientations)
      model%links = [model%links, new]
    end associate
  end subroutine build_interface

  subroutine scan_master_elements(st, cb, sub, inset, face, ok)
    !! The elements of the master substructure on the node set: a face joint
    !! when a face element (CPS3, CPS4, S3, S4, S3R, S4R) has every node on it;
    !! a second-order element on it is refused (not ok, reported).
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: cb
    type(substructure_t), intent(in) :: sub
    logical, intent(in) :: inset(:)
    logical, intent(out) :: face, ok
    type(element_traits_t) :: tr
    integer(ip) :: e
    integer :: nn
    face = .false.
    ok = .true.
    do e = 1, sub%nelem
       nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
       if (any(sub%elem_nodes(1:nn, e) == 0)) cycle   ! undefined node, reported
       tr = element_traits(sub%elem_type(e))
       if (tr%quadratic) then
          if (count(inset(sub%elem_nodes(1:nn, e))) >= 2) then
             call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': element '//itoa(sub%elem_id(e))// &
                  ' ('//trim(ELEMENT_TYPE_NAMES(sub%elem_type(e)))//') on node set '// &
                  ref_text(cb%iface_master)//' is a second-order element; the tributary shares of '// &
                  'its mid-side nodes are not implemented: join it with *CONTACT lines')
             ok = .false.
             return
          end if
       end if
       if (is_face_element(sub%elem_type(e))) then
          if (all(inset(sub%elem_nodes(1:nn, e)))) face = .true.
       end if
    end do
  end subroutine scan_master_elements

  subroutine face_shares(st, cb, sub, inset, trib, fr, ok)
    !! Face joint: the tributary areas of the nodes of the faces on the set,
    !! and their common normal fr%n (faces not in one plane: not ok, reported).
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: cb
    type(substructure_t), intent(in) :: sub
    logical, intent(in) :: inset(:)
    real(wp), intent(inout) :: trib(:)
    type(joint_frame_t), intent(inout) :: fr
    logical, intent(out) :: ok
    integer(ip) :: e
    integer :: nn
    real(wp) :: d(3)
    ok = .true.
    do e = 1, sub%nelem
       nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
       if (any(sub%elem_nodes(1:nn, e) == 0)) cycle
       if (.not. is_face_element(sub%elem_type(e))) cycle
       if (.not. all(inset(sub%elem_nodes(1:nn, e)))) cycle
       call face_share(sub%x(:, sub%elem_nodes(1:nn, e)), trib, sub%elem_nodes(1:nn, e), d)
       if (norm2(d) == 0.0_wp) cycle   ! a degenerate face adds nothing
       if (fr%first) then
          fr%n = d
          fr%first = .false.
       else if (norm2(cross(fr%n, d)) > FLAT_TOL) then
          call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the faces on node set '// &
               ref_text(cb%iface_master)//' are not in one plane (element '//itoa(sub%elem_id(e))// &
               '); split the joint into flat *INTERFACE cards')
          ok = .false.
          return
       end if
    end do
  end subroutine face_shares

  subroutine edge_shares(st, cb, sub, inset, trib, fr, ok)
    !! Edge joint: the tributary lengths of the nodes of the element edges on
    !! the set (each edge once), their common direction fr%t, the normal fr%n
    !! (out of the master element) and whether the joint stays in the XY plane
    !! (edges not on one line, no normal: not ok, reported).
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: cb
    type(substructure_t), intent(in) :: sub
    logical, intent(in) :: inset(:)
    real(wp), intent(inout) :: trib(:)
    type(joint_frame_t), intent(inout) :: fr
    logical, intent(out) :: ok
    integer(ip) :: e, a, b
    integer :: nn, j, m
    real(wp) :: d(3), len_e
    ok = .true.
    do e = 1, sub%nelem
       nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
       if (any(sub%elem_nodes(1:nn, e) == 0)) cycle
       m = nn
       if (has_one_edge(sub%elem_type(e))) m = 1
       do j = 1, m
          a = sub%elem_nodes(j, e)
          b = sub%elem_nodes(mod(j, nn) + 1, e)
          if (.not. (inset(a) .and. inset(b))) cycle
          if (shared_edge(sub, e, a, b)) cycle
          d = sub%x(:, b) - sub%x(:, a)
          len_e = norm2(d)
          if (len_e == 0.0_wp) cycle
          trib(a) = trib(a) + len_e/2
          trib(b) = trib(b) + len_e/2
          if (.not. keeps_joint_planar(sub%elem_type(e))) fr%planar = .false.
          if (fr%first) then
             call first_edge(sub, e, a, b, d/len_e, fr)
          else if (norm2(cross(fr%t, d/len_e)) > FLAT_TOL) then
             call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the edges on node set '// &
                  ref_text(cb%iface_master)//' are not on one straight line (element '// &
                  itoa(sub%elem_id(e))//'); split the joint into straight *INTERFACE cards')
             ok = .false.
             return
          end if
       end do
    end do
    if (.not. fr%first) call edge_normal(st, cb, fr, ok)
  end subroutine edge_shares

  subroutine first_edge(sub, e, a, b, t, fr)
    !! The first edge a-b (unit direction t) of element e on the set: the
    !! joint's direction, where the master element lies (fr%ref) and the
    !! normal of its plane (fr%w: a shell's, else global Z).
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: e, a, b
    real(wp), intent(in) :: t(3)
    type(joint_frame_t), intent(inout) :: fr
    real(wp) :: cen(3), mid(3)
    integer :: nn
    nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
    fr%t = t
    fr%first = .false.
    ! the normal points out of the master element
    cen = sum(sub%x(:, sub%elem_nodes(1:nn, e)), dim=2)/nn
    mid = (sub%x(:, a) + sub%x(:, b))/2
    fr%ref = mid - cen
    if (nn == 2) fr%ref = 0.0_wp
    if (is_shell_face(sub%elem_type(e))) then
       fr%w = face_normal(sub%x(:, sub%elem_nodes(1:nn, e)))
    else
       fr%w = [0.0_wp, 0.0_wp, 1.0_wp]
    end if
  end subroutine first_edge

  subroutine edge_normal(st, cb, fr, ok)
    !! The normal of an edge joint, w × t pointing out of the master element,
    !! and its tangential axis w × n.
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: cb
    type(joint_frame_t), intent(inout) :: fr
    logical, intent(out) :: ok
    ok = .false.
    if (.not. fr%planar .and. all(fr%w == [0.0_wp, 0.0_wp, 1.0_wp]) .and. norm2(fr%ref) == 0.0_wp) then
       call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': a joint along 3D beams or trusses has '// &
            'no normal direction; use *CONTACT with an *ORIENTATION')
       return
    end if
    fr%n = cross(fr%w, fr%t)
    if (norm2(fr%n) == 0.0_wp) then
       call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the joint edges have no normal '// &
            '(degenerate elements)')
       return
    end if
    fr%n = fr%n/norm2(fr%n)
    if (dot_product(fr%n, fr%ref) < 0.0_wp) fr%n = -fr%n
    ! tangential axis: w × n (in 2D the normal turned 90 degrees counterclockwise)
    fr%t = cross(fr%w, fr%n)
    fr%t = fr%t/norm2(fr%t)
    ok = .true.
  end subroutine edge_normal

  subroutine joint_frame(st, cb, sub, face, fr, q, ok)
    !! The joint's frame q: 1 normal, 2 and 3 tangential (no edge or face on
    !! the set, faces without area: not ok, reported).
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: cb
    type(substructure_t), intent(in) :: sub
    logical, intent(in) :: face
    type(joint_frame_t), intent(inout) :: fr
    real(wp), intent(out) :: q(3, 3)
    logical, intent(out) :: ok
    real(wp) :: d(3)
    ok = .false.
    if (fr%first .and. .not. face) then
       call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': no element edge or face of '// &
            sub%name//' lies on node set '//ref_text(cb%iface_master))
       return
    end if
    if (face .and. fr%first) then
       call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the faces on node set '// &
            ref_text(cb%iface_master)//' have no area (degenerate elements)')
       return
    end if
    fr%n = fr%n/norm2(fr%n)
    if (face) then
       d = [1.0_wp, 0.0_wp, 0.0_wp]
       if (abs(fr%n(1)) > 0.9_wp) d = [0.0_wp, 1.0_wp, 0.0_wp]
       fr%t = d - dot_product(d, fr%n)*fr%n
       fr%t = fr%t/norm2(fr%t)
    end if
    q(1, :) = fr%n
    q(2, :) = fr%t
    q(3, :) = cross(fr%n, fr%t)
    ok = .true.
  end subroutine joint_frame

  pure real(wp) function set_size(sub, ms)
    !! The diagonal of the box around the nodes ms of sub.
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: ms(:)
    real(wp) :: lo(3), hi(3)
    integer(ip) :: i
    lo = sub%x(:, ms(1))
    hi = lo
    do i = 1, size(ms, kind=ip)
       lo = min(lo, sub%x(:, ms(i)))
       hi = max(hi, sub%x(:, ms(i)))
    end do
    set_size = norm2(hi - lo)
  end function set_size

  subroutine interface_links(st, model, k, ms, ss, trib, face, planar, new, ok)
    !! The links of *INTERFACE k between the paired nodes ms, ss: KN and KT
    !! times the tributary share of the master node (a planar edge joint has
    !! no third DOF); a node without a share, an overflow: not ok, reported.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: k
    integer(ip), intent(in) :: ms(:), ss(:)
    real(wp), intent(in) :: trib(:)
    logical, intent(in) :: face, planar
    type(link_t), allocatable, intent(out) :: new(:)
    logical, intent(out) :: ok
    integer(ip) :: p
    ok = .false.
    allocate (new(size(ms)))
    associate (cb => st%contacts(k), c => model%contacts(k))
      do p = 1, size(ms, kind=ip)
         if (.not. (ieee_is_finite(cb%kn*trib(ms(p))) .and. ieee_is_finite(cb%kt*trib(ms(p))))) then
            call report_loc(st, cb%loc, '*INTERFACE '//cb%name//': the joint stiffness overflows the '// &
                 'floating-point range')
            return
         end if
         if (trib(ms(p)) == 0.0_wp) then
            call report_loc(st, cb%iface_loc, '*INTERFACE '//cb%name//': node '// &
                 node_label(model, c%master_sub, ms(p))//' lies on no edge or face of the joint '// &
                 '(no tributary '//trim(merge('area  ', 'length', face))//')')
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
    ok = .true.
  end subroutine interface_links

  pure subroutine set_dof(l, dof, g)
    !! A finite stiffness g > 0 on DOF dof of link l.
    type(link_t), intent(inout) :: l
    integer, intent(in) :: dof
    real(wp), intent(in) :: g
    if (g > 0.0_wp) then
       l%state(dof) = LINK_FINITE
       l%g(dof) = g
    end if
  end subroutine set_dof

  pure logical function shared_edge(sub, e, a, b)
    !! The edge a-b was counted already on an earlier element.
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: e, a, b
    integer(ip) :: f
    integer :: jj, nf, mm
    shared_edge = .false.
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
  end function shared_edge

  pure logical function is_face_element(etype)
    !! The face elements of a face joint: the first-order plane-stress and
    !! shell elements (CPS3, CPS4, S3, S4, S3R, S4R; not the plane-strain CPE3, CPE4).
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    is_face_element = .not. tr%quadratic .and. (tr%family == FAMILY_SHELL .or. &
         (tr%family == FAMILY_PLANE .and. .not. tr%plane_strain))
  end function is_face_element

  pure logical function is_shell_face(etype)
    !! The first-order shells (S3, S4, S3R, S4R): an edge joint on them lies in their plane.
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    is_shell_face = tr%family == FAMILY_SHELL .and. .not. tr%quadratic
  end function is_shell_face

  pure logical function has_one_edge(etype)
    !! The two-node line elements (trusses and beams): their one edge is
    !! counted once (B21 and B31 were counted twice, both ways round).
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    has_one_edge = (tr%family == FAMILY_TRUSS .or. tr%family == FAMILY_BEAM) .and. tr%nodes == 2
  end function has_one_edge

  pure logical function keeps_joint_planar(etype)
    !! An edge on an element of type etype leaves the joint in the XY plane (two
    !! tangential DOFs only): T2D2, B23, B21, CPS3, CPS4.
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    keeps_joint_planar = tr%planar .and. .not. tr%quadratic .and. .not. tr%plane_strain
  end function keeps_joint_planar

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
end module superjoin_deck_build_interfaces
