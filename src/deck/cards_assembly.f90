module superjoin_deck_cards_assembly
  !! Parser side of parts, assemblies and joint studies:
  !!
  !! - `*PART, NAME=p` ... `*END PART`: a mesh (nodes, elements, sets, sections)
  !!   that is not part of the structure by itself;
  !! - `*ASSEMBLY` ... `*END ASSEMBLY` with `*INSTANCE, NAME=i, PART=p` ...
  !!   `*END INSTANCE`: places a copy of part p as substructure i. Optional data
  !!   lines as Abaqus: a translation `tx, ty, tz`, then a rotation
  !!   `ax, ay, az, bx, by, bz, angle` (degrees, right hand about the axis from
  !!   point a to point b). The translation is applied first, then the rotation
  !!   about the axis through a and b (assembly coordinates):
  !!   x' = a + R (x + t - a);
  !! - `PAIR=NEAREST, TOL=t` on `*CONTACT`;
  !! - `*CHANGE CONTACT, NAME=j[, SWEEP]` inside `*STEP`;
  !! - the joints themselves: `*CONTACT` and `*SUPPORT` (with `*INTERFACE`).
  !!
  !! The placement itself (copying the part into its instances) is done by the
  !! validation pass (superjoin_deck_assembly).
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: source_loc_t, LINK_NONE, LINK_RIGID
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, parse_real, itoa, clip, plural, TOK_OK, is_path
  use superjoin_deck_state, only: deck_state_t, contact_b_t, cline_b_t, support_b_t, ref_t, &
       report_loc, new_sub, find_sub, override_b_t, SUBK_PART, SUBK_INSTANCE, SUBK_NESTED, add_contact, &
       add_cline, add_support, grow, instance_b_t
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use superjoin_utils_strings, only: pick
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use superjoin_deck_cards_common, only: get_reals, axis_rotation
  use superjoin_deck_cards_common, only: outside_step, check_params, param_index, get_param, &
       get_name_param, target_sub, field_count, fld, get_real, real_message, get_dof_range, &
       get_stiffness, parse_ref, loc_string, CARD_SKIP, CARD_CONTACT, CARD_SUPPORT, CARD_INSTANCE, &
       CARD_CHANGE_CONTACT, CARD_INTERFACE, NAME_LEN, CONTACT_FIELDS
  implicit none (type, external)
  private

  public :: find_part, new_instance
  public :: assembly_allows, set_home, finish_assembly, kw_assembly, data_instance, kw_interface, &
       data_interface, kw_change_contact, data_change_contact, kw_contact, data_contact, kw_support, &
       data_support

  integer, parameter :: SUPPORT_FIELDS_MIN = 3, SUPPORT_FIELDS_MAX = 4
  integer, parameter :: TRANSLATION_FIELDS = 3, ROTATION_FIELDS = 7
  real(wp), parameter :: AXIS_TOL = 1.0e-12_wp
    !! The rotation axis is degenerate when |b - a| <= AXIS_TOL max(|a|, |b|) (or 0).
  integer, parameter :: CHANGE_FIELDS_MIN = 5
    !! master, slave, first dof, last dof, g (a SWEEP adds more values of g).
  integer, parameter :: CHANGE_LIST_FIELDS_MIN = 4
    !! The card without NAME=: contact, first dof, last dof, g (every pair of the contact).

contains

  logical function assembly_allows(st, kw, loc) result(ok)
    !! False (card skipped, reported) when a keyword may not stand where it stands
    !! (a load inside *PART, a card inside *INSTANCE, ...).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    ok = .true.
    if (st%cur_inst < 0) then
       ! the block of a refused *INSTANCE card: reported already
       if (kw%keyword == 'END INSTANCE') return
       st%cur_inst = 0
    else if (st%cur_inst > 0) then
       if (kw%keyword == 'END INSTANCE') return
       call report_loc(st, loc, '*'//kw%keyword//' inside *INSTANCE '// &
            st%subs(st%instances(st%cur_inst)%sub)%name//' (missing *END INSTANCE?)')
       st%cur_inst = 0
    end if
    if (in_part(st)) then
       select case (kw%keyword)
       case ('SUBSTRUCTURE', 'END SUBSTRUCTURE', 'ASSEMBLY', 'END ASSEMBLY', &
            'INTERFACE', 'SUPPORT', 'BOUNDARY', 'STEP', 'END STEP', 'CLOAD', 'DLOAD', 'MATRIX LOAD', &
            'CHANGE CONTACT', 'CONTROLS')
          call report_loc(st, loc, '*'//kw%keyword//' is not allowed inside *PART '// &
               st%subs(st%cur_sub)%name//' (a part holds nodes, elements, sets, sections, instances of '// &
               'other parts and contacts between them; '// &
               'close it with *END PART)')
          st%card = CARD_SKIP
          ok = .false.
       end select
       return
    end if
    if (st%in_assembly) then
       select case (kw%keyword)
       case ('STEP', 'PART')
          call report_loc(st, loc, '*'//kw%keyword//' inside *ASSEMBLY (missing *END ASSEMBLY?)')
          st%in_assembly = .false.
       end select
    end if
  end function assembly_allows

  logical function in_part(st)
    !! A *PART block is open.
    type(deck_state_t), intent(in) :: st
    in_part = .false.
    if (st%cur_sub > 0) in_part = st%subs(st%cur_sub)%kind == SUBK_PART
  end function in_part

  integer function find_part(st, name) result(k)
    !! Index in st%subs of the part named `name` (0 if none).
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    do k = 1, st%nsub
       if (st%subs(k)%kind /= SUBK_PART) cycle
       if (st%subs(k)%name == name) return
    end do
    k = 0
  end function find_part

  subroutine set_home(st, kw, loc, isub, prefix)
    !! Substructure a *NSET/*ELSET card writes to: the instance of INSTANCE=
    !! (Abaqus assembly-level sets), else the open block or MAIN (0: reported).
    !! INSTANCE= an instance path (`B.F3.BAY2`, parts made of parts): the
    !! assembly's instance B, with prefix `F3.BAY2.` for the set's name, until
    !! the unfolded instance B.F3.BAY2 takes the set (superjoin_deck_path_sets).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: isub
    character(:), allocatable, intent(out) :: prefix
    character(:), allocatable :: name, top
    logical :: found
    integer :: dot
    prefix = ''
    isub = 0
    if (param_index(kw, 'INSTANCE') == 0) then
       isub = target_sub(st, loc)
       return
    end if
    call get_path_param(st, kw, loc, 'INSTANCE', name, found)
    if (.not. found) return   ! invalid name, reported
    dot = index(name, '.')
    top = name
    if (dot > 0) then
       top = name(1:dot - 1)
       prefix = name(dot + 1:)//'.'
    end if
    isub = find_sub(st, top)
    if (isub > 0) then
       if (st%subs(isub)%kind /= SUBK_INSTANCE) isub = 0
    end if
    if (isub == 0) call report_loc(st, loc, 'INSTANCE='//name//' of *'//kw%keyword// &
         ' names no *INSTANCE defined before it')
  end subroutine set_home

  subroutine finish_assembly(st)
    !! End of input: report unclosed *PART, *INSTANCE and *ASSEMBLY blocks.
    type(deck_state_t), intent(inout) :: st
    if (st%cur_inst > 0) call report_loc(st, st%instances(st%cur_inst)%loc, '*INSTANCE '// &
         st%subs(st%instances(st%cur_inst)%sub)%name//' has no *END INSTANCE')
    st%cur_inst = 0
    if (in_part(st)) then
       call report_loc(st, st%subs(st%cur_sub)%loc, '*PART '//st%subs(st%cur_sub)%name//' has no *END PART')
       st%cur_sub = 0
    end if
    if (st%in_assembly) call report_loc(st, st%assembly_loc, '*ASSEMBLY has no *END ASSEMBLY')
    st%in_assembly = .false.
  end subroutine finish_assembly

  subroutine kw_assembly(st, kw, loc)
    !! *PART, *END PART, *ASSEMBLY, *END ASSEMBLY, *INSTANCE, *END INSTANCE.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    select case (kw%keyword)
    case ('PART')
       call kw_part(st, kw, loc)
    case ('END PART')
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
       if (.not. in_part(st)) then
          call report_loc(st, loc, '*END PART without *PART')
       else
          st%cur_sub = 0
       end if
    case ('ASSEMBLY')
       if (.not. outside_step(st, kw, loc)) return
       call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME'], [character(NAME_LEN) ::])
       if (st%cur_sub > 0) then
          call report_loc(st, loc, '*ASSEMBLY inside *SUBSTRUCTURE '//st%subs(st%cur_sub)%name// &
               ' (missing *END SUBSTRUCTURE?)')
          st%cur_sub = 0
       end if
       if (st%in_assembly) then
          call report_loc(st, loc, '*ASSEMBLY inside *ASSEMBLY (missing *END ASSEMBLY?)')
       else if (st%assembly_loc%line > 0) then
          call report_loc(st, loc, 'a deck has one *ASSEMBLY (first at '//loc_string(st, st%assembly_loc)//')')
       end if
       st%in_assembly = .true.
       st%assembly_loc = loc
    case ('END ASSEMBLY')
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
       if (.not. st%in_assembly) then
          call report_loc(st, loc, '*END ASSEMBLY without *ASSEMBLY')
       else
          if (st%cur_sub > 0) then
             call report_loc(st, loc, '*END ASSEMBLY inside *SUBSTRUCTURE '//st%subs(st%cur_sub)%name// &
                  ' (missing *END SUBSTRUCTURE?)')
             st%cur_sub = 0
          end if
          st%in_assembly = .false.
       end if
    case ('INSTANCE')
       call kw_instance(st, kw, loc)
    case ('END INSTANCE')
       call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
       if (st%cur_inst == 0) then
          call report_loc(st, loc, '*END INSTANCE without *INSTANCE')
       else
          st%cur_inst = 0
       end if
    end select
  end subroutine kw_assembly

  subroutine kw_part(st, kw, loc)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    logical :: found
    integer :: k
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME'], [character(NAME_LEN) ::])
    if (in_part(st)) then
       call report_loc(st, loc, '*PART inside *PART '//st%subs(st%cur_sub)%name//' (missing *END PART?)')
       st%cur_sub = 0
    else if (st%cur_sub > 0) then
       call report_loc(st, loc, '*PART inside *SUBSTRUCTURE '//st%subs(st%cur_sub)%name// &
            ' (missing *END SUBSTRUCTURE?)')
       st%cur_sub = 0
    end if
    call get_name_param(st, kw, loc, 'NAME', .true., name, found)
    if (.not. found) name = '?'
    k = find_part(st, name)
    if (k > 0 .and. found) call report_loc(st, loc, 'duplicate part name '//name// &
         ' (first defined at '//loc_string(st, st%subs(k)%loc)//')')
    call new_sub(st, name, loc, k)
    st%subs(k)%kind = SUBK_PART
    st%cur_sub = k
  end subroutine kw_part

  subroutine kw_instance(st, kw, loc)
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name, part
    logical :: f1, f2
    integer :: k, isub, owner
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'PART'], [character(NAME_LEN) ::])
    st%card = CARD_SKIP
    owner = 0
    if (in_part(st)) then
       owner = st%cur_sub   ! a part made of parts (superjoin_deck_nesting flattens it)
    else if (st%cur_sub > 0) then
       call report_loc(st, loc, '*INSTANCE inside *SUBSTRUCTURE '//st%subs(st%cur_sub)%name// &
            ' (missing *END SUBSTRUCTURE?)')
       st%cur_sub = 0
    end if
    if (.not. st%in_assembly .and. owner == 0) call report_loc(st, loc, &
         '*INSTANCE must stand inside *ASSEMBLY ... *END ASSEMBLY or inside a *PART')
    call get_name_param(st, kw, loc, 'NAME', .true., name, f1)
    call get_name_param(st, kw, loc, 'PART', .true., part, f2)
    st%cur_inst = -1
    if (.not. (f1 .and. f2)) return
    k = find_sub(st, name)
    if (owner > 0) k = find_inner(st, owner, name)
    if (k > 0) then
       call report_loc(st, loc, 'instance name '//name//' is already the name of '// &
            pick(owner > 0, 'an instance in part '//st%subs(max(owner, 1))%name, 'a substructure or instance')// &
            ' (defined at '//loc_string(st, st%subs(k)%loc)//')')
       return
    end if
    call new_instance(st, name, part, loc, owner, isub)
    st%cur_inst = st%ninst
    st%card = CARD_INSTANCE
    st%card_item = st%ninst
  end subroutine kw_instance

  subroutine new_instance(st, name, part, loc, owner, isub)
    !! A new *INSTANCE `name` of `part` (placed by the identity until its data lines)
    !! inside part `owner` (0: the assembly): entry isub of st%subs, the last of
    !! st%instances. name and part must not be pieces of st (st%subs grows).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name, part
    type(source_loc_t), intent(in) :: loc
    integer, intent(in) :: owner
    integer, intent(out) :: isub
    integer, parameter :: INITIAL_INSTANCES = 8
    call grow(st%instances, st%ninst, INITIAL_INSTANCES)
    call new_sub(st, name, loc, isub)
    st%ninst = st%ninst + 1
    st%subs(isub)%kind = merge(SUBK_NESTED, SUBK_INSTANCE, owner > 0)
    st%subs(isub)%inst = st%ninst
    associate (inst => st%instances(st%ninst))
      inst = instance_b_t()
      inst%part = part
      inst%sub = isub
      inst%loc = loc
      inst%owner = owner
    end associate
  end subroutine new_instance

  integer function find_inner(st, owner, name) result(k)
    !! The *INSTANCE named `name` inside part `owner` (index in st%subs; 0 if none).
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: owner
    character(*), intent(in) :: name
    do k = 1, st%nsub
       if (st%subs(k)%kind /= SUBK_NESTED) cycle
       if (st%instances(st%subs(k)%inst)%owner == owner .and. st%subs(k)%name == name) return
    end do
    k = 0
  end function find_inner

  subroutine data_instance(st, line, loc)
    !! Data lines of *INSTANCE: translation, then rotation (Abaqus form).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(halting_t) :: saved
    call halting_off(saved)
    call instance_line(st, line, loc)
    call halting_restore(saved)
  end subroutine data_instance

  subroutine instance_line(st, line, loc)
    !! data_instance with floating-point halting off (out-of-range placements are reported).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: v(ROTATION_FIELDS), a(3), b(3), n(3), nn, angle, q(3, 3)
    associate (inst => st%instances(st%card_item))
      inst%ndata = inst%ndata + 1
      if (inst%ndata > 2) then
         call report_loc(st, loc, 'too many data lines for *INSTANCE (a translation, then a rotation)')
         inst%ok = .false.
         st%card = CARD_SKIP
         return
      end if
      if (inst%ndata == 1) then
         if (.not. field_count(st, loc, TRANSLATION_FIELDS, TRANSLATION_FIELDS, 'tx, ty, tz')) then
            inst%ok = .false.
            return
         end if
         if (.not. get_reals(st, line, loc, v(1:TRANSLATION_FIELDS))) then
            inst%ok = .false.
            return
         end if
         inst%shift = v(1:3)
         return
      end if
      if (.not. field_count(st, loc, ROTATION_FIELDS, ROTATION_FIELDS, &
           'ax, ay, az, bx, by, bz, angle (the axis from point a to point b, degrees)')) then
         inst%ok = .false.
         return
      end if
      if (.not. get_reals(st, line, loc, v(1:ROTATION_FIELDS))) then
         inst%ok = .false.
         return
      end if
      a = v(1:3)
      b = v(4:6)
      angle = v(7)
      n = b - a
      nn = norm2(n)
      if (.not. (ieee_is_finite(nn) .and. ieee_is_finite(norm2(a)) .and. ieee_is_finite(norm2(b)))) then
         call report_loc(st, loc, 'rotation axis of *INSTANCE '//st%subs(inst%sub)%name// &
              ' out of the floating-point range')
         inst%ok = .false.
         return
      end if
      if (.not. (nn > AXIS_TOL*max(norm2(a), norm2(b)))) then
         call report_loc(st, loc, 'degenerate rotation axis of *INSTANCE '//st%subs(inst%sub)%name// &
              ': points a and b coincide')
         inst%ok = .false.
         return
      end if
      n = n/nn
      q = axis_rotation(n, angle)
      inst%rot = q
      ! x' = a + R (x + t - a) = R x + (a + R (t - a))
      inst%shift = a + matmul(q, inst%shift - a)
      if (.not. all(ieee_is_finite(inst%shift))) then
         call report_loc(st, loc, 'placement of *INSTANCE '//st%subs(inst%sub)%name// &
              ' out of the floating-point range')
         inst%shift = 0.0_wp
         inst%ok = .false.
      end if
    end associate
  end subroutine instance_line

  subroutine contact_pair_params(st, kw, loc, c)
    !! PAIR= and TOL= of *CONTACT.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(contact_b_t), intent(inout) :: c
    character(:), allocatable :: value
    logical :: found, has_tol
    integer :: stat
    real(wp) :: x
    call get_param(st, kw, loc, 'PAIR', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('NEAREST')
          c%nearest = .true.
       case ('ORDER')
          c%nearest = .false.
       case default
          call report_loc(st, loc, 'PAIR must be NEAREST or ORDER, not '//clip(value))
       end select
    end if
    call get_param(st, kw, loc, 'TOL', .false., value, has_tol)
    if (has_tol) then
       call parse_real(value, x, stat)
       if (stat /= TOK_OK) then
          call report_loc(st, loc, real_message(value, stat))
       else if (.not. (x >= 0.0_wp)) then
          call report_loc(st, loc, 'TOL must not be negative, not '//clip(value))
       else
          c%tol = x
       end if
       if (.not. c%nearest) call report_loc(st, loc, 'TOL= is for PAIR=NEAREST')
    else if (c%nearest) then
       call report_loc(st, loc, 'PAIR=NEAREST needs TOL= (the largest distance between paired nodes)')
    end if
  end subroutine contact_pair_params

  subroutine contact_offset_param(st, kw, loc, c)
    !! OFFSET=RIGID | NONE of *CONTACT.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(contact_b_t), intent(inout) :: c
    character(:), allocatable :: value
    logical :: found
    call get_param(st, kw, loc, 'OFFSET', .false., value, found)
    if (.not. found) return
    select case (to_upper(value))
    case ('RIGID')
       c%rigid_offset = .true.
    case ('NONE')
       c%rigid_offset = .false.
    case default
       call report_loc(st, loc, 'OFFSET must be RIGID or NONE, not '//clip(value))
    end select
  end subroutine contact_offset_param

  subroutine kw_interface(st, kw, loc)
    !! *INTERFACE, NAME=j, MASTER=s1, SLAVE=s2, KN=kn, KT=kt[, TOL=t].
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(contact_b_t) :: c
    logical :: f1, f2, f3
    integer :: k
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'MASTER', 'SLAVE', 'KN', 'KT', 'TOL'], &
         [character(NAME_LEN) ::])
    st%card = CARD_SKIP
    call get_name_param(st, kw, loc, 'NAME', .true., c%name, f1)
    call get_name_param(st, kw, loc, 'MASTER', .true., c%master, f2)
    call get_name_param(st, kw, loc, 'SLAVE', .true., c%slave, f3)
    if (.not. (f1 .and. f2 .and. f3)) return
    if (.not. stiffness_param('KN', c%kn)) return
    if (.not. stiffness_param('KT', c%kt)) return
    c%tol = -1.0_wp
    if (param_index(kw, 'TOL') > 0) then
       if (.not. real_param('TOL', c%tol)) return
       if (.not. (c%tol >= 0.0_wp)) then
          call report_loc(st, loc, 'TOL must not be negative')
          return
       end if
    end if
    do k = 1, st%ncontact
       if (st%contacts(k)%name == c%name) then
          call report_loc(st, loc, 'duplicate contact name '//c%name//' (first defined at '// &
               loc_string(st, st%contacts(k)%loc)//')')
          return
       end if
    end do
    c%is_interface = .true.
    c%nearest = .true.
    c%loc = loc
    call add_contact(st, c, st%card_item)
    st%card = CARD_INTERFACE
  contains
    logical function real_param(name, x) result(ok)
      character(*), intent(in) :: name
      real(wp), intent(out) :: x
      character(:), allocatable :: value
      logical :: found
      integer :: stat
      x = 0.0_wp
      call get_param(st, kw, loc, name, .true., value, found)
      ok = found
      if (.not. ok) return
      call parse_real(value, x, stat)
      ok = stat == TOK_OK
      if (.not. ok) call report_loc(st, loc, name//'=: '//real_message(value, stat))
    end function real_param
    logical function stiffness_param(name, x) result(ok)
      character(*), intent(in) :: name
      real(wp), intent(out) :: x
      ok = real_param(name, x)
      if (.not. ok) return
      ok = x >= 0.0_wp
      if (.not. ok) call report_loc(st, loc, name//' must be >= 0 (stiffness per unit length or area)')
    end function stiffness_param
  end subroutine kw_interface

  subroutine data_interface(st, line, loc)
    !! The data line of *INTERFACE: master nset, slave nset.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    associate (c => st%contacts(st%card_item))
      if (st%card_ndata > 1) then
         call report_loc(st, loc, 'too many data lines for *INTERFACE (one line: master nset, slave nset)')
         st%card = CARD_SKIP
         return
      end if
      if (.not. field_count(st, loc, 2, 2, 'master node set, slave node set')) return
      if (.not. parse_ref(st, fld(st, line, 1), .false., 0, loc, c%iface_master)) return
      if (.not. parse_ref(st, fld(st, line, 2), .false., 0, loc, c%iface_slave)) return
      c%iface_loc = loc
    end associate
  end subroutine data_interface

  subroutine kw_change_contact(st, kw, loc)
    !! *CHANGE CONTACT[, NAME=j][, PART=p][, SWEEP] inside *STEP (without NAME=
    !! each data line names its contact and changes every pair of it). A contact
    !! named by instance path (`B.F3.J1`), a part's contact named by its own name,
    !! and PART= are resolved once the parts are unfolded (card_item -1 with NAME=).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: name
    logical :: found
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'PART'], [character(NAME_LEN) :: 'SWEEP'])
    st%card = CARD_SKIP
    if (st%cur_step == 0) then
       call report_loc(st, loc, '*CHANGE CONTACT must stand inside *STEP')
       return
    end if
    st%card_item = 0
    st%card_generate = param_index(kw, 'SWEEP') > 0
    st%card_home = st%cur_step
    st%change_card = override_b_t(card_loc=loc)
    if (param_index(kw, 'PART') > 0) then
       call get_name_param(st, kw, loc, 'PART', .true., name, found)
       if (.not. found) return
       st%change_card%part = name
    end if
    if (param_index(kw, 'NAME') == 0) then
       st%card = CARD_CHANGE_CONTACT
       return
    end if
    call get_path_param(st, kw, loc, 'NAME', name, found)
    if (.not. found) return
    call name_contact(st, name, loc, st%change_card, st%card_item)
    if (allocated(st%change_card%path)) then
       st%change_card%named = .true.
       st%card_item = -1
    end if
    if (st%card_item /= 0) st%card = CARD_CHANGE_CONTACT
  end subroutine kw_change_contact

  subroutine name_contact(st, name, loc, o, k)
    !! The contact a *CHANGE CONTACT names: k, a contact of the assembly; or,
    !! for an instance path, a part's contact or with PART=, o%path (k = 0,
    !! resolved once the parts are unfolded); else reported (k = 0).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: loc
    type(override_b_t), intent(inout) :: o
    integer, intent(out) :: k
    integer :: j
    logical :: in_part
    k = 0
    in_part = .false.
    if (index(name, '.') == 0 .and. .not. allocated(o%part)) then
       do j = 1, st%ncontact
          if (st%contacts(j)%name /= name) cycle
          if (st%contacts(j)%owner == 0) k = j
          if (st%contacts(j)%owner > 0) in_part = .true.
       end do
       if (k > 0) return
       if (.not. in_part) then
          call report_loc(st, loc, '*CHANGE CONTACT of unknown contact '//name// &
               ' (the *CONTACT card must come before the step)')
          return
       end if
    end if
    o%path = name
  end subroutine name_contact

  subroutine data_change_contact(st, line, loc)
    !! A data line of *CHANGE CONTACT (the form of *CONTACT's).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(override_b_t) :: o
    integer :: nval, i, nmin
    integer, parameter :: INITIAL_OVERRIDES = 4
    o = st%change_card
    if (st%card_item == 0) then
       nmin = CHANGE_LIST_FIELDS_MIN
       if (.not. field_count(st, loc, nmin, merge(huge(1), nmin, st%card_generate), &
            pick(st%card_generate, 'contact, first dof, last dof, g1, g2, ... (SWEEP)', &
            'contact, first dof, last dof, g (several values of g need SWEEP; node pairs need NAME=)'))) return
       if (.not. contact_named(fld(st, line, 1))) return
       o%whole = .true.
    else if (st%card_item < 0) then   ! NAME='s contact resolved later, with the scopes of the nodes
       nmin = CHANGE_FIELDS_MIN
       if (.not. field_count(st, loc, nmin, merge(huge(1), nmin, st%card_generate), &
            pick(st%card_generate, 'master, slave, first dof, last dof, g1, g2, ... (SWEEP)', &
            'master, slave, first dof, last dof, g (several values of g need SWEEP)'))) return
       if (.not. parse_ref(st, fld(st, line, 1), .false., 0, loc, o%master)) return
       if (.not. parse_ref(st, fld(st, line, 2), .false., 0, loc, o%slave)) return
    else
       nmin = CHANGE_FIELDS_MIN
       if (.not. field_count(st, loc, nmin, merge(huge(1), nmin, st%card_generate), &
            pick(st%card_generate, 'master, slave, first dof, last dof, g1, g2, ... (SWEEP)', &
            'master, slave, first dof, last dof, g (several values of g need SWEEP)'))) return
       associate (c => st%contacts(st%card_item))
         if (.not. parse_ref(st, fld(st, line, 1), .false., 0, loc, o%master)) return
         if (.not. parse_ref(st, fld(st, line, 2), .false., 0, loc, o%slave)) return
         if (.not. scoped(o%master, c%master, 'master')) return
         if (.not. scoped(o%slave, c%slave, 'slave')) return
       end associate
       o%contact = st%card_item
    end if
    if (.not. get_dof_range(st, line, loc, nmin - 2, o%first, o%last)) return
    nval = st%f%n - (nmin - 1)
    allocate (o%states(nval), o%gs(nval))
    do i = 1, nval
       if (.not. get_stiffness(st, line, loc, nmin - 1 + i, o%states(i), o%gs(i))) return
    end do
    o%loc = loc
    associate (step => st%steps(st%card_home))
      if (st%card_generate) then
         if (step%nsweep == 0) then
            step%nsweep = nval
            step%sweep_loc = loc
         else if (step%nsweep /= nval) then
            call report_loc(st, loc, 'this SWEEP line has '//plural(nval, 'value')//', the step''s first has '// &
                 itoa(step%nsweep)//' (at '//loc_string(st, step%sweep_loc)//')')
            return
         end if
      end if
      call grow(step%overrides, step%noverride, INITIAL_OVERRIDES)
      step%noverride = step%noverride + 1
      step%overrides(step%noverride) = o
    end associate
  contains
    logical function contact_named(field) result(ok)
      !! o%contact or o%path: the *CONTACT named by field (an unknown or invalid name is reported).
      character(*), intent(in) :: field
      character(:), allocatable :: name
      name = to_upper(trim(adjustl(field)))
      ok = is_path(name)
      if (.not. ok) then
         call report_loc(st, loc, 'invalid contact name '''//clip(field)//''' on a *CHANGE CONTACT line '// &
              '(letters, digits, _, - and / only; an instance path joins names with .)')
         return
      end if
      call name_contact(st, name, loc, o, o%contact)
      ok = o%contact > 0 .or. allocated(o%path)
    end function contact_named
    logical function scoped(ref, subname, role) result(ok)
      !! A scoped reference must name the contact's own substructure.
      type(ref_t), intent(in) :: ref
      character(*), intent(in) :: subname, role
      ok = .true.
      if (.not. allocated(ref%scope)) return
      ok = ref%scope == subname
      if (.not. ok) call report_loc(st, loc, 'node '''//ref%scope//'.'//ref_name(ref)//''' is not in the '// &
           role//' substructure '//subname//' of contact '//st%contacts(st%card_item)%name)
    end function scoped
    function ref_name(ref) result(s)
      type(ref_t), intent(in) :: ref
      character(:), allocatable :: s
      if (ref%is_set) then
         s = ref%set
      else
         s = itoa(ref%id)
      end if
    end function ref_name
  end subroutine data_change_contact

  subroutine kw_contact(st, kw, loc)
    !! *CONTACT, NAME=j, MASTER=, SLAVE= (or PAIR=NEAREST): opens a joint.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(contact_b_t) :: c
    logical :: f1, f2, f3, f4
    integer :: k
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NAME', 'MASTER', 'SLAVE', 'ORIENTATION', &
         'PAIR', 'TOL', 'OFFSET'], [character(NAME_LEN) ::])
    call contact_pair_params(st, kw, loc, c)
    call contact_offset_param(st, kw, loc, c)
    call get_name_param(st, kw, loc, 'NAME', .true., c%name, f1)
    call get_path_param(st, kw, loc, 'MASTER', c%master, f2)
    call get_path_param(st, kw, loc, 'SLAVE', c%slave, f3)
    call get_name_param(st, kw, loc, 'ORIENTATION', .false., c%orientation, f4)
    st%card = CARD_SKIP
    if (.not. (f1 .and. f2 .and. f3)) return
    if (in_part(st)) c%owner = st%cur_sub   ! between the part's own instances (superjoin_deck_nesting)
    do k = 1, st%ncontact
       if (st%contacts(k)%name == c%name .and. st%contacts(k)%owner == c%owner) then
          call report_loc(st, loc, 'duplicate contact name '//c%name//' (first defined at '// &
               loc_string(st, st%contacts(k)%loc)//')')
          return
       end if
    end do
    c%loc = loc
    call add_contact(st, c, st%card_item)
    st%card = CARD_CONTACT
  end subroutine kw_contact

  subroutine get_path_param(st, kw, loc, name, value, found)
    !! A required parameter naming a substructure or an instance path (`B.F3.BAY2`), upper-cased.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: name
    character(:), allocatable, intent(out) :: value
    logical, intent(out) :: found
    call get_param(st, kw, loc, name, .true., value, found)
    if (.not. found) return
    if (.not. is_path(value)) then
       call report_loc(st, loc, 'invalid name '''//clip(value)//''' for '//name//'= (letters, digits, _, - and / only;'// &
            ' an instance path joins names with .)')
       found = .false.
       return
    end if
    value = to_upper(value)
  end subroutine get_path_param

  subroutine data_contact(st, line, loc)
    !! A data line of *CONTACT: master, slave, first DOF, last DOF, stiffness.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(cline_b_t) :: c
    character(:), allocatable :: master, slave
    if (.not. field_count(st, loc, CONTACT_FIELDS, CONTACT_FIELDS, 'master, slave, first dof, last dof, g')) return
    master = st%contacts(st%card_item)%master
    slave = st%contacts(st%card_item)%slave
    if (.not. contact_ref(master, 'master', 1, c%master)) return
    if (.not. contact_ref(slave, 'slave', 2, c%slave)) return
    if (.not. get_dof_range(st, line, loc, 3, c%first, c%last)) return
    if (.not. get_stiffness(st, line, loc, 5, c%state, c%g)) return
    c%contact = st%card_item
    c%loc = loc
    call add_cline(st, c)
  contains
    logical function contact_ref(subname, role, i, ref) result(ok)
      character(*), intent(in) :: subname, role
      integer, intent(in) :: i
      type(ref_t), intent(out) :: ref
      ok = parse_ref(st, fld(st, line, i), .false., 0, loc, ref)
      if (.not. ok) return
      if (allocated(ref%scope)) then
         if (ref%scope /= subname) then
            call report_loc(st, loc, 'node '''//clip(fld(st, line, i))//''' is not in the '//role// &
                 ' substructure '//subname)
            ok = .false.
         end if
      end if
    end function contact_ref
  end subroutine data_contact

  subroutine kw_support(st, kw, loc)
    !! *SUPPORT: its data lines tie nodes to the ground.
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) ::], [character(NAME_LEN) ::])
    st%card = CARD_SUPPORT
    st%card_home = st%cur_sub
  end subroutine kw_support

  subroutine data_support(st, line, loc)
    !! A data line of *SUPPORT: node, first DOF, last DOF[, stiffness].
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    type(support_b_t) :: s
    integer :: first, last
    if (.not. field_count(st, loc, SUPPORT_FIELDS_MIN, SUPPORT_FIELDS_MAX, 'node or nset, first dof, last dof[, g]')) return
    if (.not. parse_ref(st, fld(st, line, 1), .false., st%card_home, loc, s%ref)) return
    if (.not. get_dof_range(st, line, loc, 2, first, last)) return
    s%state = LINK_RIGID
    if (st%f%n == SUPPORT_FIELDS_MAX) then
       if (.not. get_stiffness(st, line, loc, 4, s%state, s%g)) return
       if (s%state == LINK_NONE) return
    end if
    s%dofs(first:last) = .true.
    s%loc = loc
    call add_support(st, s)
  end subroutine data_support
end module superjoin_deck_cards_assembly
