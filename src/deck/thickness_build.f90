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
  use superjoin_model_types, only: model_t, section_t, ELEMENT_NODE_COUNT, node_label
  use superjoin_model_types, only: ET_S8R
  use superjoin_elements, only: is_plate_type
  use superjoin_deck_state, only: deck_state_t, report_loc
  use superjoin_deck_validate, only: resolve_items, resolve_sub
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  real(wp), parameter :: THICK_TOL = 1.0e-12_wp
    !! Nodal thicknesses of one element closer than this (relative) are equal.

  public :: apply_nodal_thickness

contains

  subroutine apply_nodal_thickness(st, model)
    !! Give every plane or shell element whose nodes carry a *NODAL THICKNESS that thickness.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    real(wp), allocatable :: t(:)
    integer, allocatable :: line(:)
    integer(ip), allocatable :: nodes(:)
    integer, allocatable :: lsub(:)
    integer(ip) :: i, e
    integer :: k, isub, nn, a, s
    logical :: ok
    real(wp) :: te
    integer(ip), allocatable :: tapered(:)   ! S8R elements whose nodes differ
    integer(ip) :: ntaper, nmiss, first_miss
    if (st%nnthick == 0 .and. .not. any_nodal_thickness_section(model)) return
    allocate (lsub(st%nnthick))
    do k = 1, st%nnthick
       lsub(k) = resolve_sub(st, model, st%nthicks(k)%node, st%nthicks(k)%loc, 'node')
    end do
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         allocate (t(sub%nnode), line(sub%nnode))
         t = 0.0_wp
         line = 0
         ntaper = 0
         nmiss = 0
         first_miss = 0
         allocate (tapered(0))
         ! the thickness of each node of this substructure (a later line wins)
         do k = 1, st%nnthick
            associate (d => st%nthicks(k))
              if (lsub(k) /= isub) cycle
              call resolve_items(st, model, isub, d%node, .false., d%loc, nodes, ok)
              if (.not. ok) cycle
              do i = 1, size(nodes, kind=ip)
                 t(nodes(i)) = d%t
                 line(nodes(i)) = k
              end do
            end associate
         end do
         do e = 1, sub%nelem
            if (.not. is_plate_type(sub%elem_type(e)) .or. sub%elem_section(e) <= 0) cycle
            nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
            ! an element with a node the deck does not define is an error reported already
            if (any(sub%elem_nodes(1:nn, e) < 1 .or. sub%elem_nodes(1:nn, e) > sub%nnode)) cycle
            if (sub%sections(sub%elem_section(e))%nodal_thickness) then
               ! *SHELL SECTION, NODAL THICKNESS: every node needs one (CalculiX)
               if (any(line(sub%elem_nodes(1:nn, e)) == 0)) then
                  nmiss = nmiss + 1
                  if (nmiss == 1) first_miss = e
                  cycle
               end if
            end if
            if (all(line(sub%elem_nodes(1:nn, e)) == 0)) cycle
            if (sub%elem_type(e) == ET_S8R) then
               call s8r_thickness(e)
               cycle
            end if
            te = 0.0_wp
            do a = 1, nn
               associate (n => sub%elem_nodes(a, e))
                 if (line(n) == 0) then
                    call report_loc(st, st%nthicks(first_line(e))%loc, '*NODAL THICKNESS: node '// &
                         node_label(model, isub, n)//' of element '//itoa(sub%elem_id(e))//' has none '// &
                         '(superjoin''s elements have one thickness: give it at all their nodes)')
                    te = -1.0_wp
                    exit
                 end if
                 if (a == 1) then
                    te = t(n)
                 else if (abs(t(n) - te) > THICK_TOL*te) then
                    call report_loc(st, st%nthicks(first_line(e))%loc, '*NODAL THICKNESS: the nodes of element '// &
                         itoa(sub%elem_id(e))//' have different thicknesses (superjoin''s elements have one '// &
                         'thickness)')
                    te = -1.0_wp
                    exit
                 end if
               end associate
            end do
            if (te <= 0.0_wp) cycle
            s = section_with_thickness(sub%sections, sub%elem_section(e), te)
            sub%elem_section(e) = s
         end do
         if (nmiss > 0) call report_missing(first_miss, nmiss)
         if (ntaper > 0) call add_tapered_sections(sub%sections, sub%elem_section, tapered(1:ntaper), &
              sub%elem_nodes, t, line)
         deallocate (t, line, tapered)
       end associate
    end do
  contains
    subroutine report_missing(e, n)
      !! Elements of a *SHELL SECTION, NODAL THICKNESS with a node without one.
      integer(ip), intent(in) :: e, n
      integer :: a
      character(:), allocatable :: more
      more = ''
      if (n > 1) more = ' (and '//itoa(n - 1)//' more elements)'
      associate (sub => model%subs(isub))
        do a = 1, ELEMENT_NODE_COUNT(sub%elem_type(e))
           if (line(sub%elem_nodes(a, e)) == 0) exit
        end do
        call report_loc(st, sub%sections(sub%elem_section(e))%loc, '*SHELL SECTION, NODAL THICKNESS: node '// &
             node_label(model, isub, sub%elem_nodes(a, e))//' of element '//itoa(sub%elem_id(e))// &
             ' has no *NODAL THICKNESS'//more)
      end associate
    end subroutine report_missing

    subroutine s8r_thickness(e)
      !! An S8R with a nodal thickness at some node: one thickness (a shared
      !! section copy) when its nodes agree, else listed as tapered.
      integer(ip), intent(in) :: e
      real(wp) :: tn(ELEMENT_NODE_COUNT(ET_S8R))
      associate (sub => model%subs(isub))
        tn = node_thicknesses(sub%elem_nodes(1:size(tn), e), t, line, &
             sub%sections(sub%elem_section(e))%thickness)
        if (all(abs(tn - tn(1)) <= THICK_TOL*abs(tn(1)))) then
           if (tn(1) <= 0.0_wp) return   ! a bad thickness is reported by the element checks
           sub%elem_section(e) = section_with_thickness(sub%sections, sub%elem_section(e), tn(1))
        else
           if (ntaper == size(tapered, kind=ip)) tapered = [tapered, spread(0_ip, 1, int(max(16_ip, ntaper)))]
           ntaper = ntaper + 1
           tapered(ntaper) = e
        end if
      end associate
    end subroutine s8r_thickness

    integer function first_line(e) result(k)
      !! The *NODAL THICKNESS data line of the first node of element e that has one.
      integer(ip), intent(in) :: e
      integer :: b
      k = 0
      associate (sub => model%subs(isub))
        do b = 1, ELEMENT_NODE_COUNT(sub%elem_type(e))
           k = line(sub%elem_nodes(b, e))
           if (k > 0) return
        end do
      end associate
    end function first_line
  end subroutine apply_nodal_thickness

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

  subroutine add_tapered_sections(sections, elem_section, elems, elem_nodes, t, line)
    !! Give each of the tapered S8R elems a copy of its section with its
    !! nodal thicknesses (thickness: their mean), appended in one go.
    type(section_t), allocatable, intent(inout) :: sections(:)
    integer, intent(inout) :: elem_section(:)
    integer(ip), intent(in) :: elems(:)
    integer(ip), intent(in) :: elem_nodes(:, :)
    real(wp), intent(in) :: t(:)
    integer, intent(in) :: line(:)
    type(section_t), allocatable :: tmp(:)
    integer :: n, k, nn
    n = size(sections)
    nn = ELEMENT_NODE_COUNT(ET_S8R)
    allocate (tmp(n + size(elems)))
    tmp(1:n) = sections
    do k = 1, size(elems)
       associate (e => elems(k))
         tmp(n + k) = sections(elem_section(e))
         tmp(n + k)%node_thickness = node_thicknesses(elem_nodes(1:nn, e), t, line, sections(elem_section(e))%thickness)
         tmp(n + k)%thickness = sum(tmp(n + k)%node_thickness)/nn
         elem_section(e) = n + k
       end associate
    end do
    call move_alloc(tmp, sections)
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
