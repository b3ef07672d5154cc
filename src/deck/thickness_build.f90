module superjoin_deck_thickness_build
  !! Validation side of `*NODAL THICKNESS` (CalculiX): a plane or shell element
  !! all of whose nodes have a nodal thickness takes it in place of its
  !! section's thickness (CalculiX: the nodal thickness has precedence).
  !! superjoin's elements have one thickness, so the element's nodes must
  !! agree (relative difference below THICK_TOL); an element with a nodal
  !! thickness at some nodes only, or different ones, is a deck error at the
  !! data line of its first node. Elements of other types ignore the card.
  !! Each distinct (section, thickness) pair becomes a copy of the section.
  !!
  !! S8R (degenerated solid, the director length per node is natural) takes a
  !! thickness per node, as CalculiX: a node without a nodal thickness has
  !! the section's; an S8R whose nodes differ gets a copy of its section of
  !! its own with node_thickness (superjoin_elements_shell8 interpolates it).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, substructure_t, section_t, ELEMENT_NODE_COUNT, node_label, SEC_SOLID
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_SHELL
  use superjoin_elements, only: is_plate_type
  use superjoin_deck_state, only: deck_state_t, report_loc
  use superjoin_deck_build_common, only: resolve_items, resolve_sub
  use superjoin_utils_strings, only: itoa, pick
  implicit none (type, external)
  private

  real(wp), parameter :: THICK_TOL = 1.0e-12_wp
    !! Nodal thicknesses of one element closer than this (relative) are equal.

  public :: apply_nodal_thickness

  type :: thickness_work_t
    !! The nodal thicknesses of one substructure while its elements take them.
     real(wp), allocatable :: t(:)           !! thickness of each node
     integer, allocatable :: line(:)         !! its *NODAL THICKNESS line (0: none)
     integer(ip), allocatable :: tapered(:)  !! S8R elements whose nodes differ: tapered(1:ntaper)
     integer(ip) :: ntaper = 0
     integer(ip) :: nmiss = 0, first_miss = 0
       !! elements of a NODAL THICKNESS section with a node without one, the first of them
  end type thickness_work_t

contains

  subroutine apply_nodal_thickness(st, model)
    !! Give every plane or shell element whose nodes carry a *NODAL THICKNESS that thickness.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, allocatable :: lsub(:)
    integer :: k, isub
    if (st%nnthick == 0 .and. .not. any_nodal_thickness_section(model)) return
    allocate (lsub(st%nnthick))
    do k = 1, st%nnthick
       lsub(k) = resolve_sub(st, model, st%nthicks(k)%node, st%nthicks(k)%loc, 'node')
    end do
    do isub = 1, size(model%subs)
       call sub_nodal_thickness(st, model, isub, lsub)
    end do
  end subroutine apply_nodal_thickness

  subroutine sub_nodal_thickness(st, model, isub, lsub)
    !! The nodal thicknesses of substructure isub (lsub: the substructure of
    !! each *NODAL THICKNESS line) given to its elements.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, intent(in) :: isub, lsub(:)
    type(thickness_work_t) :: w
    integer(ip), allocatable :: nodes(:)
    integer(ip) :: i, e
    integer :: k
    logical :: ok
    associate (sub => model%subs(isub))
      allocate (w%t(sub%nnode), w%line(sub%nnode))
      w%t = 0.0_wp
      w%line = 0
      allocate (w%tapered(0))
      ! the thickness of each node of this substructure (a later line wins)
      do k = 1, st%nnthick
         associate (d => st%nthicks(k))
           if (lsub(k) /= isub) cycle
           call resolve_items(st, model, isub, d%node, .false., d%loc, nodes, ok)
           if (.not. ok) cycle
           do i = 1, size(nodes, kind=ip)
              w%t(nodes(i)) = d%t
              w%line(nodes(i)) = k
           end do
         end associate
      end do
      do e = 1, sub%nelem
         call element_thickness(st, model, isub, e, w)
      end do
      if (w%nmiss > 0) call report_missing(st, model, isub, w)
      if (w%ntaper > 0) call add_tapered_sections(sub, w%tapered(1:w%ntaper), w%t, w%line)
    end associate
  end subroutine sub_nodal_thickness

  subroutine element_thickness(st, model, isub, e, w)
    !! Element e of substructure isub takes the nodal thickness of its nodes
    !! (a copy of its section of that thickness), if it is a plane or shell
    !! element with a section and its nodes have one.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    type(thickness_work_t), intent(inout) :: w
    integer :: nn
    real(wp) :: te
    associate (sub => model%subs(isub))
      if (.not. is_plate_type(sub%elem_type(e)) .or. sub%elem_section(e) <= 0) return
      nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
      ! an element with a node the deck does not define is an error reported already
      if (any(sub%elem_nodes(1:nn, e) < 1 .or. sub%elem_nodes(1:nn, e) > sub%nnode)) return
      if (sub%sections(sub%elem_section(e))%nodal_thickness) then
         ! *SHELL SECTION, NODAL THICKNESS: every node needs one (CalculiX)
         if (any(w%line(sub%elem_nodes(1:nn, e)) == 0)) then
            w%nmiss = w%nmiss + 1
            if (w%nmiss == 1) w%first_miss = e
            return
         end if
      end if
      if (all(w%line(sub%elem_nodes(1:nn, e)) == 0)) return
      if (thickness_per_node(sub%elem_type(e))) then
         call s8r_thickness(model, isub, e, w)
         return
      end if
      te = uniform_thickness(st, model, isub, e, w)
      if (te <= 0.0_wp) return
      sub%elem_section(e) = section_with_thickness(sub%sections, sub%elem_section(e), te)
    end associate
  end subroutine element_thickness

  real(wp) function uniform_thickness(st, model, isub, e, w) result(te)
    !! The one nodal thickness of the nodes of element e (-1, reported, when a
    !! node has none or the nodes differ: superjoin's elements have one).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    type(thickness_work_t), intent(in) :: w
    integer :: a
    te = 0.0_wp
    associate (sub => model%subs(isub))
      do a = 1, ELEMENT_NODE_COUNT(sub%elem_type(e))
         associate (n => sub%elem_nodes(a, e))
           if (w%line(n) == 0) then
              call report_loc(st, st%nthicks(first_line(sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e), w%line))%loc, &
                   '*NODAL THICKNESS: node '// &
                   node_label(model, isub, n)//' of element '//itoa(sub%elem_id(e))//' has none '// &
                   '(superjoin''s elements have one thickness: give it at all their nodes)')
              te = -1.0_wp
              return
           end if
           if (a == 1) then
              te = w%t(n)
           else if (abs(w%t(n) - te) > THICK_TOL*te) then
              call report_loc(st, st%nthicks(first_line(sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e), w%line))%loc, &
                   '*NODAL THICKNESS: the nodes of element '// &
                   itoa(sub%elem_id(e))//' have different thicknesses (superjoin''s elements have one '// &
                   'thickness)')
              te = -1.0_wp
              return
           end if
         end associate
      end do
    end associate
  end function uniform_thickness

  subroutine report_missing(st, model, isub, w)
    !! Elements of a *SHELL SECTION, NODAL THICKNESS with a node without one.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(thickness_work_t), intent(in) :: w
    integer :: a
    character(:), allocatable :: more
    more = ''
    if (w%nmiss > 1) more = ' (and '//itoa(w%nmiss - 1)//' more elements)'
    associate (sub => model%subs(isub), e => w%first_miss)
      do a = 1, ELEMENT_NODE_COUNT(sub%elem_type(e))
         if (w%line(sub%elem_nodes(a, e)) == 0) exit
      end do
      call report_loc(st, sub%sections(sub%elem_section(e))%loc, &
           pick(sub%sections(sub%elem_section(e))%kind == SEC_SOLID, '*SOLID', '*SHELL')//' SECTION, NODAL THICKNESS: node '// &
           node_label(model, isub, sub%elem_nodes(a, e))//' of element '//itoa(sub%elem_id(e))// &
           ' has no *NODAL THICKNESS'//more)
    end associate
  end subroutine report_missing

  subroutine s8r_thickness(model, isub, e, w)
    !! An S8R with a nodal thickness at some node: one thickness (a shared
    !! section copy) when its nodes agree, else listed as tapered.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    type(thickness_work_t), intent(inout) :: w
    real(wp), allocatable :: tn(:)
    associate (sub => model%subs(isub))
      allocate (tn(ELEMENT_NODE_COUNT(sub%elem_type(e))))
      tn = node_thicknesses(sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e), w%t, w%line, &
           sub%sections(sub%elem_section(e))%thickness)
      if (all(abs(tn - tn(1)) <= THICK_TOL*abs(tn(1)))) then
         if (tn(1) <= 0.0_wp) return   ! a bad thickness is reported by the element checks
         sub%elem_section(e) = section_with_thickness(sub%sections, sub%elem_section(e), tn(1))
      else
         if (w%ntaper == size(w%tapered, kind=ip)) w%tapered = [w%tapered, spread(0_ip, 1, int(max(16_ip, w%ntaper)))]
         w%ntaper = w%ntaper + 1
         w%tapered(w%ntaper) = e
      end if
    end associate
  end subroutine s8r_thickness

  pure integer function first_line(nodes, line) result(k)
    !! The *NODAL THICKNESS data line of the first of an element's nodes that has one.
    integer(ip), intent(in) :: nodes(:)
    integer, intent(in) :: line(:)
    integer :: b
    k = 0
    do b = 1, size(nodes)
       k = line(nodes(b))
       if (k > 0) return
    end do
  end function first_line

  pure logical function thickness_per_node(etype)
    !! Element type etype takes a thickness per node (the degenerated-solid
    !! shell S8R, the one second-order shell).
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    thickness_per_node = tr%family == FAMILY_SHELL .and. tr%quadratic
  end function thickness_per_node

  pure logical function any_nodal_thickness_section(model)
    !! Has some substructure a *SHELL SECTION, NODAL THICKNESS?
    type(model_t), intent(in) :: model
    integer :: isub
    any_nodal_thickness_section = .false.
    do isub = 1, size(model%subs)
       if (.not. allocated(model%subs(isub)%sections)) cycle
       if (any(model%subs(isub)%sections(:)%nodal_thickness)) any_nodal_thickness_section = .true.
    end do
  end function any_nodal_thickness_section

  pure function node_thicknesses(nodes, t, line, t_section) result(tn)
    !! The thickness at each of an element's nodes: its *NODAL THICKNESS, or
    !! the section's where it has none (CalculiX).
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(in) :: t(:)
    integer, intent(in) :: line(:)
    real(wp), intent(in) :: t_section
    real(wp) :: tn(size(nodes))
    tn = merge(t(nodes), t_section, line(nodes) > 0)
  end function node_thicknesses

  subroutine add_tapered_sections(sub, elems, t, line)
    !! Give each of the tapered S8R elems of sub a copy of its section with its
    !! nodal thicknesses (thickness: their mean), appended in one go.
    type(substructure_t), intent(inout) :: sub
    integer(ip), intent(in) :: elems(:)
    real(wp), intent(in) :: t(:)
    integer, intent(in) :: line(:)
    type(section_t), allocatable :: tmp(:)
    integer :: n, k, nn
    n = size(sub%sections)
    allocate (tmp(n + size(elems)))
    tmp(1:n) = sub%sections
    do k = 1, size(elems)
       associate (e => elems(k))
         nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
         tmp(n + k) = sub%sections(sub%elem_section(e))
         tmp(n + k)%node_thickness = node_thicknesses(sub%elem_nodes(1:nn, e), t, line, &
              sub%sections(sub%elem_section(e))%thickness)
         tmp(n + k)%thickness = sum(tmp(n + k)%node_thickness)/nn
         sub%elem_section(e) = n + k
       end associate
    end do
    call move_alloc(tmp, sub%sections)
  end subroutine add_tapered_sections

  integer function section_with_thickness(sections, isec, t) result(k)
    !! Index of a section equal to sections(isec) but of thickness t (appended when new).
    type(section_t), allocatable, intent(inout) :: sections(:)
    integer, intent(in) :: isec
    real(wp), intent(in) :: t
    type(section_t), allocatable :: tmp(:)
    integer :: n
    if (sections(isec)%thickness == t) then
       k = isec
       return
    end if
    n = size(sections)
    do k = 1, n
       if (allocated(sections(k)%node_thickness)) cycle
       if (sections(k)%thickness == t .and. same_but_thickness(sections(k), sections(isec))) return
    end do
    allocate (tmp(n + 1))
    tmp(1:n) = sections
    tmp(n + 1) = sections(isec)
    tmp(n + 1)%thickness = t
    call move_alloc(tmp, sections)
    k = n + 1
  end function section_with_thickness

  pure logical function same_but_thickness(a, b)
    !! Two sections that differ at most in their thickness (a copy made here).
    type(section_t), intent(in) :: a, b
    same_but_thickness = a%material == b%material .and. a%kind == b%kind .and. &
         a%loc%file == b%loc%file .and. a%loc%line == b%loc%line
  end function same_but_thickness
end module superjoin_deck_thickness_build
