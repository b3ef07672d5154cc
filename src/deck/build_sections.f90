module superjoin_deck_build_sections
  !! Sections of the model: each section card resolved to its material and
  !! element set and checked against the element types it covers; elements
  !! left without a section reported.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, substructure_t, ELEMENT_TYPE_NAMES, SEC_SOLID, SEC_BEAM, &
       SEC_SHELL, section_t, DIALECT_NONE, DIALECT_CALCULIX, MAT_ISO
  use superjoin_model_notes, only: note
  use superjoin_elements, only: has_axisymmetric
  use superjoin_elements_traits, only: element_traits_t, element_traits, section_card_name, &
       shell_of_plane, FAMILY_NONE, FAMILY_TRUSS, FAMILY_BEAM, FAMILY_PLANE, FAMILY_SHELL, FAMILY_SOLID
  use superjoin_deck_lexer, only: itoa
  use superjoin_deck_state, only: deck_state_t, report_loc, reading_dialect, BEAM_2D_VALUES, BEAM_3D_VALUES, sec_b_t
  use superjoin_deck_beam_sections, only: section_fibres, MAX_FIBRES, section_properties, section_props_t, &
       shape_shear_factor, SHAPE_CIRC
  use superjoin_deck_build_common, only: resolve_sub, more_text, where
  use superjoin_deck_cards_materials, only: ELASTIC_TYPE_NAMES
  use superjoin_deck_coupling_records, only: COUPLE_DCOUP
  use superjoin_utils_strings, only: to_upper
  implicit none (type, external)
  private

  public :: build_sections, check_unassigned

  type :: member_tally_t
    !! The elements of a section card's element set, by kind.
     integer :: ntruss = 0, ncps = 0, nb23 = 0, nb33 = 0, nshell = 0, nsolid = 0
       !! trusses, plane elements, 2D beams, 3D beams, shells, solids
     integer :: nbad = 0, nover = 0, other = 0
       !! members the card does not fit, members with another section (the first's section)
     integer(ip) :: first_bad = 0, first_over = 0
  end type member_tally_t

contains

  subroutine build_sections(st, model)
    !! The sections of every substructure, from the section cards.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, allocatable :: sub_of(:), count(:)
    integer :: g, isub, k

    call dialect_readings(st, model)
    if (allocated(st%notes)) then     ! the set builder's (undefined ids CalculiX passes over)
       do g = 1, size(st%notes)
          call note(model%notes, st%notes(g)%s)
       end do
    end if
    call check_section_controls(st)
    allocate (sub_of(st%nsec), count(size(model%subs)))
    count = 0
    do g = 1, st%nsec
       sub_of(g) = resolve_sub(st, model, st%sections(g)%elset, st%sections(g)%loc, 'element set')
       if (sub_of(g) > 0) count(sub_of(g)) = count(sub_of(g)) + 1
    end do
    do isub = 1, size(model%subs)
       deallocate (model%subs(isub)%sections)
       allocate (model%subs(isub)%sections(count(isub)))
    end do
    count = 0
    do g = 1, st%nsec
       isub = sub_of(g)
       if (isub == 0) cycle
       count(isub) = count(isub) + 1
       k = count(isub)
       call build_section(st, model, isub, k, g)
       if (st%aborted) return
    end do
    if (has_axisymmetric(model)) call note(model%notes, 'axisymmetric elements (CAX*): r = x, axis y; *CLOAD, '// &
         'reactions and the EQUILIBRIUM resultants are totals around the whole circumference (a ring''s '// &
         'resultant is its axial force FY); stresses xx = r, yy = z, zz = hoop, xy = rz')
  end subroutine build_sections

  subroutine check_section_controls(st)
    !! CONTROLS=c of a section card names a *SECTION CONTROLS card (Abaqus:
    !! an error otherwise); it may stand anywhere in the deck.
    type(deck_state_t), intent(inout) :: st
    integer :: g, k
    logical :: found
    do g = 1, st%nsec
       if (.not. allocated(st%sections(g)%controls)) cycle
       found = .false.
       do k = 1, st%nsec_controls
          if (st%sec_controls(k)%name == st%sections(g)%controls) found = .true.
       end do
       if (.not. found) call report_loc(st, st%sections(g)%loc, 'CONTROLS='//st%sections(g)%controls// &
            ': no *SECTION CONTROLS, NAME='//st%sections(g)%controls//' in the deck')
    end do
  end subroutine check_section_controls

  subroutine dialect_readings(st, model)
    !! Where Abaqus and CalculiX read a beam section differently, the deck's
    !! *CONTROLS, DIALECT= decides (when none is declared: CalculiX's reading
    !! in a ccx -i run, st%implied_dialect, else Abaqus's),
    !! and a note of the listing says which reading was taken: SECTION=CIRC
    !! with one value is Abaqus's radius r, CalculiX's diameter (ccx 2.20
    !! with 2.0 deflects as r = 1), the circle of its two-value ellipse d, d.
    !! *BEAM SECTION, SECTION=GENERAL with five values is CalculiX's A, I11,
    !! I12, I22, J (four are superjoin's A, Iy, Iz, J): noted too.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(section_props_t) :: p
    character(:), allocatable :: problem, text
    integer :: g
    do g = 1, st%nsec
       associate (sb => st%sections(g))
         if (sb%five_general) then
            text = 'SECTION=GENERAL at '//where(st, sb%data_loc)//': five values, read as CalculiX''s '// &
                 'A, I11, I12, I22, J (four values are superjoin''s A, Iy, Iz, J)'
         else if (sb%shape == SHAPE_CIRC .and. sb%ndims == 1) then
            text = 'SECTION=CIRC at '//where(st, sb%data_loc)//': one value, read as '
            select case (reading_dialect(st))
            case (DIALECT_CALCULIX)
               sb%ndims = 2
               sb%dims(2) = sb%dims(1)
               call section_properties(SHAPE_CIRC, sb%dims(1:2), p, problem)
               sb%sp = [p%area, p%i11, p%i22, p%i12, p%j]
               if (st%controls%dialect == DIALECT_CALCULIX) then
                  text = text//'the diameter (DIALECT=CALCULIX; Abaqus reads the radius)'
               else
                  text = text//'the diameter (ccx -i reads a CalculiX deck; Abaqus reads the radius: '// &
                       '*CONTROLS, DIALECT=ABAQUS)'
               end if
            case (DIALECT_NONE)
               text = text//'the radius (Abaqus; CalculiX reads the diameter: *CONTROLS, DIALECT=CALCULIX)'
            case default
               text = text//'the radius (DIALECT=ABAQUS; CalculiX reads the diameter)'
            end select
         else
            cycle
         end if
       end associate
       if (.not. noted(model, text)) call note(model%notes, text)
    end do
  end subroutine dialect_readings

  pure logical function noted(model, text)
    !! The model already has this note (a section card of a part, met once per instance).
    type(model_t), intent(in) :: model
    character(*), intent(in) :: text
    integer :: i
    noted = .false.
    if (.not. allocated(model%notes)) return
    do i = 1, size(model%notes)
       if (model%notes(i)%s == text) noted = .true.
    end do
  end function noted

  subroutine build_section(st, model, isub, k, g)
    !! Section k of substructure isub from section card g: its material and
    !! element set, the element types it covers checked, its values.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, intent(in) :: isub, k, g
    integer :: iset
    type(member_tally_t) :: tally
    character(:), allocatable :: card

    associate (sb => st%sections(g), sec => model%subs(isub)%sections(k), sub => model%subs(isub))
      select case (sb%kind)
      case (SEC_SOLID)
         card = '*SOLID SECTION'
      case (SEC_BEAM)
         card = '*BEAM SECTION'
      case default
         card = '*SHELL SECTION'
      end select
      sec%kind = sb%kind
      sec%loc = sb%loc
      sec%material = material_index(model, sb%material)
      if (sec%material == 0) call report_loc(st, sb%loc, 'unknown material '//sb%material)
      iset = elset_index(sub, sb%elset%set)
      sec%elset = iset
      if (iset == 0) then
         call report_loc(st, sb%loc, 'unknown element set '//sb%elset%set//' in substructure '//sub%name)
         st%section_rejected(sb%kind) = .true.   ! its elements are not reported again
         return
      end if
      call tally_members(sb, sub, iset, k, tally)
      call report_members(st, sb, sub, card, tally)
      if (sb%kind == SEC_BEAM .and. tally%nb23 > 0 .and. tally%nb33 > 0) then
         call report_loc(st, sb%loc, '*BEAM SECTION on element set '//sb%elset%set// &
              ' mixes B23 and B33 elements')
         return
      end if
      call material_axes(st, model, sb, tally, sec)
      if (.not. sb%data_ok) return
      sec%nodal_thickness = sb%nodal_thickness   ! *SHELL / *SOLID SECTION, NODAL THICKNESS
      select case (sb%kind)
      case (SEC_SOLID)
         call solid_values(st, sb, card, tally, sec)
      case (SEC_SHELL)
         call shell_values(st, sb, sec)
      case (SEC_BEAM)
         call beam_values(st, sb, tally%nb23 > 0, tally%nb33 > 0, sec)
      end select
    end associate
  end subroutine build_section

  subroutine material_axes(st, model, sb, tally, sec)
    !! The material axes of a *SOLID SECTION (ORIENTATION=: a copy of the
    !! *ORIENTATION in sec%axes), and the element kinds an orthotropic or
    !! anisotropic material may not cover: only solids take one (reported
    !! once, on the section card).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(sec_b_t), intent(in) :: sb
    type(member_tally_t), intent(in) :: tally
    type(section_t), intent(inout) :: sec
    integer :: k, others
    if (allocated(sb%orientation)) then
       if (len(sb%orientation) > 0) then
          do k = 1, st%norient
             if (st%orientations(k)%name == sb%orientation) sec%axes = st%orientations(k)
          end do
          if (.not. allocated(sec%axes)) call report_loc(st, sb%loc, 'unknown orientation '//sb%orientation)
       end if
    end if
    if (sec%material == 0) return
    associate (mat => model%materials(sec%material))
      others = tally%ntruss + tally%ncps + tally%nb23 + tally%nb33 + tally%nshell
      if (mat%kind == MAT_ISO .or. others == 0) return
      call report_loc(st, sb%loc, 'material '//mat%name//' (at '//where(st, mat%loc)//') is not isotropic '// &
           '(*ELASTIC, TYPE='//trim(ELASTIC_TYPE_NAMES(mat%kind))//'): superjoin takes it on solid '// &
           'elements (C3D*) only, and element set '//sb%elset%set//' holds '//itoa(others)//' element'// &
           trim(merge('s ', '  ', others > 1))//' of another kind')
    end associate
  end subroutine material_axes

  integer function material_index(model, name) result(imat)
    !! Index of material name (the last of that name; 0: none).
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    integer(ip) :: i
    imat = 0
    do i = 1, size(model%materials)
       if (model%materials(i)%name == name) imat = int(i)
    end do
  end function material_index

  integer function elset_index(sub, name) result(iset)
    !! Index of element set name of sub (the last of that name; 0: none).
    type(substructure_t), intent(in) :: sub
    character(*), intent(in) :: name
    integer(ip) :: i
    iset = 0
    do i = 1, size(sub%elsets)
       if (sub%elsets(i)%name == name) iset = int(i)
    end do
  end function elset_index

  subroutine tally_members(sb, sub, iset, k, tally)
    !! Give the elements of element set iset section k (those that have none),
    !! counting them by kind, the ones the section card does not fit and the
    !! ones that already have a section. A *SHELL SECTION turns the plane
    !! elements that have a shell twin (CPS3, CPS4, as gmsh writes every 2D
    !! mesh) into that shell (an extension).
    type(sec_b_t), intent(in) :: sb
    type(substructure_t), intent(inout) :: sub
    integer, intent(in) :: iset, k
    type(member_tally_t), intent(out) :: tally
    type(element_traits_t) :: tr
    integer(ip) :: e, i
    do i = 1, size(sub%elsets(iset)%items)
       e = sub%elsets(iset)%items(i)
       tr = element_traits(sub%elem_type(e))
       select case (tr%family)
       case (FAMILY_TRUSS)
          tally%ntruss = tally%ntruss + 1
       case (FAMILY_PLANE)
          if (sb%kind == SEC_SHELL .and. shell_of_plane(sub%elem_type(e)) /= 0) then
             tally%nshell = tally%nshell + 1
             sub%elem_type(e) = shell_of_plane(sub%elem_type(e))
             tr = element_traits(sub%elem_type(e))
          else
             tally%ncps = tally%ncps + 1
          end if
       case (FAMILY_BEAM)
          if (tr%planar) then
             tally%nb23 = tally%nb23 + 1
          else
             tally%nb33 = tally%nb33 + 1
          end if
       case (FAMILY_SHELL)
          tally%nshell = tally%nshell + 1
       case (FAMILY_SOLID)
          tally%nsolid = tally%nsolid + 1
       end select
       if (tr%family /= FAMILY_NONE .and. sb%kind /= tr%section) then
          tally%nbad = tally%nbad + 1
          if (tally%nbad == 1) tally%first_bad = e
       end if
       if (sub%elem_section(e) == 0) then
          sub%elem_section(e) = k
       else if (sub%elem_section(e) /= k) then
          tally%nover = tally%nover + 1
          if (tally%nover == 1) then
             tally%first_over = e
             tally%other = sub%elem_section(e)
          end if
       end if
    end do
  end subroutine tally_members

  subroutine report_members(st, sb, sub, card, tally)
    !! Report the members of a section card that it does not fit and those
    !! that already have a section (the first of each, and how many more).
    type(deck_state_t), intent(inout) :: st
    type(sec_b_t), intent(in) :: sb
    type(substructure_t), intent(in) :: sub
    character(*), intent(in) :: card
    type(member_tally_t), intent(in) :: tally
    if (tally%nbad > 0) call report_loc(st, sb%loc, card//' on element set '//sb%elset%set//': element '// &
         itoa(sub%elem_id(tally%first_bad))//' is of type '// &
         trim(ELEMENT_TYPE_NAMES(sub%elem_type(tally%first_bad)))// &
         ', which needs '//section_card_name(sub%elem_type(tally%first_bad))//more_text(tally%nbad - 1))
    if (tally%nover > 0) call report_loc(st, sb%loc, 'element '//itoa(sub%elem_id(tally%first_over))// &
         ' of element set '//sb%elset%set//' already has a section (at '// &
         where(st, sub%sections(tally%other)%loc)//'); an element may have only one section'// &
         more_text(tally%nover - 1))
  end subroutine report_members

  subroutine solid_values(st, sb, card, tally, sec)
    !! Area (trusses) or thickness (plane elements) of a *SOLID SECTION. With no
    !! data line plane elements take the thickness 1 (Abaqus's default);
    !! trusses need their area; solids need nothing (a value is ignored).
    type(deck_state_t), intent(inout) :: st
    type(sec_b_t), intent(in) :: sb
    character(*), intent(in) :: card
    type(member_tally_t), intent(in) :: tally
    type(section_t), intent(inout) :: sec
    if (sb%nval == 0) then
       ! an element set left empty by a refused *ELEMENT card (reported), or of DCOUP3D elements (a
       ! coupling, no element), needs nothing more
       if (tally%ntruss + tally%ncps + tally%nsolid + tally%nbad == 0 .and. (st%elements_refused .or. &
            dcoup_set(st, sb%elset%set))) return
       if (tally%ntruss > 0 .or. (tally%ncps == 0 .and. tally%nsolid == 0)) then
          call report_loc(st, sb%loc, card//' needs a data line (the cross-section area of the trusses)')
          return
       end if
       sec%thickness = 1.0_wp
       return
    end if
    if (tally%ntruss > 0 .or. tally%ncps == 0) sec%area = sb%val(1)
    if (tally%ncps > 0 .or. tally%ntruss == 0) sec%thickness = sb%val(1)
  end subroutine solid_values

  pure logical function dcoup_set(st, name)
    !! name is the element set of DCOUP3D elements.
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    integer :: k
    dcoup_set = .false.
    if (.not. allocated(st%couplings)) return
    do k = 1, size(st%couplings)
       if (st%couplings(k)%kind /= COUPLE_DCOUP) cycle
       if (st%couplings(k)%name == to_upper(name)) dcoup_set = .true.
    end do
  end function dcoup_set

  subroutine shell_values(st, sb, sec)
    !! Thickness of a *SHELL SECTION and its *TRANSVERSE SHEAR STIFFNESS K11,
    !! K22 [, K12]: per unit length along the element's local x, y; only the
    !! thick shells have shear flexibility.
    type(deck_state_t), intent(inout) :: st
    type(sec_b_t), intent(in) :: sb
    type(section_t), intent(inout) :: sec
    sec%thickness = sb%val(1)
    if (sb%has_ks) then
       if (sb%nks < 2) then
          call report_loc(st, sb%ks_loc, '*TRANSVERSE SHEAR STIFFNESS of shells needs K11, K22')
          return
       end if
       sec%shear_k = sb%ks
    end if
  end subroutine shell_values

  subroutine beam_values(st, sb, has_2d, has_3d, sec)
    !! Constants of a *BEAM SECTION on 2D beams (has_2d) or 3D beams (has_3d):
    !! from a library shape or general section, or A, I (2D) / A, Iy, Iz, J (3D).
    type(deck_state_t), intent(inout) :: st
    type(sec_b_t), intent(in) :: sb
    logical, intent(in) :: has_2d, has_3d
    type(section_t), intent(inout) :: sec
    if (sb%shape /= 0) then    ! library shape or Abaqus general section: constants in sb%sp
       sec%area = sb%sp(1)
       sec%shear_factor = shape_shear_factor(sb%shape)
       call beam_shear_stiffness(st, sb, has_2d, sec)
       call beam_fibres(sb, has_2d, sec)
       if (has_2d) then
          sec%iz = sb%sp(2)    ! a 2D beam bends about section axis 1, normal to its plane
       else
          sec%iy = sb%sp(2)    ! local y = section axis 1 (along v), local z = axis 2
          sec%iz = sb%sp(3)
          sec%j = sb%sp(5)
          sec%has_v = sb%has_v
          if (sb%has_v) sec%v = sb%v
       end if
       return
    end if
    if (has_2d .and. sb%nval /= BEAM_2D_VALUES) then
       call report_loc(st, sb%data_loc, '*BEAM SECTION of 2D beams (B23) needs A, I')
       return
    end if
    if (has_3d .and. sb%nval /= BEAM_3D_VALUES) then
       call report_loc(st, sb%data_loc, '*BEAM SECTION of 3D beams (B33) needs A, Iy, Iz, J')
       return
    end if
    sec%area = sb%val(1)
    if (sb%nval == BEAM_2D_VALUES) then
       sec%iz = sb%val(2)
    else
       sec%iy = sb%val(2)
       sec%iz = sb%val(3)
       sec%j = sb%val(4)
    end if
    sec%has_v = sb%has_v
    if (sb%has_v) sec%v = sb%v
    call beam_shear_stiffness(st, sb, sb%nval == BEAM_2D_VALUES, sec)
  end subroutine beam_values

  subroutine beam_shear_stiffness(st, sb, plane, sec)
    !! *TRANSVERSE SHEAR STIFFNESS K23, K13 (Abaqus cross-section axes 1, 2) of
    !! a beam section: a planar beam deflects along axis 2 (local y), a 3D
    !! beam's local y, z are axes 1, 2.
    type(deck_state_t), intent(inout) :: st
    type(sec_b_t), intent(in) :: sb
    logical, intent(in) :: plane
    type(section_t), intent(inout) :: sec
    if (.not. sb%has_ks) return
    if (plane) then
       sec%shear_k(1) = sb%ks(1)
    else if (sb%nks < 2) then
       call report_loc(st, sb%ks_loc, '*TRANSVERSE SHEAR STIFFNESS of 3D beams needs K23, K13')
    else
       sec%shear_k = sb%ks([2, 1])
    end if
  end subroutine beam_shear_stiffness

  pure subroutine beam_fibres(sb, plane, sec)
    !! The fibre points of a library beam section in the beam's local (y, z):
    !! 3D beams have y along section axis 1 and z along axis 2; a 2D beam (plane)
    !! bends in its plane about axis 1, so its local y is axis 2 (and z = -axis 1,
    !! Abaqus's n1 = -Z of planar beams).
    type(sec_b_t), intent(in) :: sb
    logical, intent(in) :: plane
    type(section_t), intent(inout) :: sec
    real(wp) :: pts(2, MAX_FIBRES)
    if (sb%ndims == 0) return
    call section_fibres(sb%shape, sb%dims(1:sb%ndims), pts, sec%nfibre)
    if (plane) then
       sec%fibre(1, :) = pts(2, :)
       sec%fibre(2, :) = -pts(1, :)
    else
       sec%fibre = pts
    end if
  end subroutine beam_fibres

  pure logical function section_card_rejected(st, etype)
    !! A section card that could have covered an element of type etype was
    !! rejected (already reported): the element is not reported again. Only
    !! the Euler-Bernoulli beams (B23, B33) count as beams here: the
    !! shear-flexible ones (B21, B31, B32) fall to the solid and shell cards.
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: etype
    type(element_traits_t) :: tr
    tr = element_traits(etype)
    if (tr%family == FAMILY_BEAM .and. .not. tr%shear_flexible) then
       section_card_rejected = st%section_rejected(SEC_BEAM)
    else if (tr%family == FAMILY_SHELL) then
       section_card_rejected = st%section_rejected(SEC_SHELL)
    else
       section_card_rejected = st%section_rejected(SEC_SOLID) .or. st%section_rejected(SEC_SHELL)
    end if
  end function section_card_rejected

  subroutine check_unassigned(st, model)
    !! Elements without a section: one message per *ELEMENT card.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, allocatable :: count(:), first_sub(:)
    integer(ip), allocatable :: first_elem(:)
    integer :: isub, c
    integer(ip) :: e
    allocate (count(st%nelem_cards), first_sub(st%nelem_cards), first_elem(st%nelem_cards))
    count = 0
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         do e = 1, sub%nelem
            if (sub%elem_section(e) /= 0) cycle
            if (section_card_rejected(st, sub%elem_type(e))) cycle
            c = st%subs(isub)%elem_card(e)
            count(c) = count(c) + 1
            if (count(c) == 1) then
               first_sub(c) = isub
               first_elem(c) = e
            end if
         end do
       end associate
    end do
    do c = 1, st%nelem_cards
       if (count(c) == 0) cycle
       associate (sub => model%subs(first_sub(c)))
         call report_loc(st, sub%elem_loc(first_elem(c)), 'element '//itoa(sub%elem_id(first_elem(c)))// &
              ' ('//trim(ELEMENT_TYPE_NAMES(sub%elem_type(first_elem(c))))//') has no section: no '// &
              section_card_name(sub%elem_type(first_elem(c)))//' covers it'//more_text(count(c) - 1, &
              ' of this *ELEMENT card'))
       end associate
    end do
  end subroutine check_unassigned
end module superjoin_deck_build_sections
