module superjoin_deck_build_steps
  !! Steps of the model: concentrated and distributed loads, boundary
  !! conditions and their history over the steps, thermal loads, combinations.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: model_t, cload_t, dload_t, ELEMENT_TYPE_NAMES, DLOAD_PX, DLOAD_PY, &
       DLOAD_PZ, DLOAD_P, DLOAD_GRAV, DLOAD_NAMES, DLOAD_BX, DLOAD_BY, DLOAD_BZ, DLOAD_P1, DLOAD_P2, DLOAD_P3, DLOAD_P4, DLOAD_CENTRIF, &
       DLOAD_P5, DLOAD_P6, DLOAD_TRVEC, DLOAD_TRSHR
  use superjoin_elements_traits, only: accepts_dload, is_family, FAMILY_PLANE, element_traits, element_traits_t
  use superjoin_deck_lexer, only: itoa
  use superjoin_deck_state, only: deck_state_t, load_b_t, report_loc, report_oom, OP_NEW
  use superjoin_model_history, only: support_list_t, step_ops_t, apply_boundary_history, &
       apply_load_history
  use superjoin_utils_grow, only: grow
  use superjoin_deck_build_common, only: ref_subs, resolve_items, keeps_previous, more_text, &
       where, INITIAL_CAPACITY
  use superjoin_deck_build_contacts, only: support_list
  use superjoin_model_notes, only: note
  use superjoin_deck_amplitudes, only: apply_amplitudes
  use superjoin_deck_build_thermal, only: build_thermal
  implicit none (type, external)
  private

  interface grow
     !! Make room for element n + 1 of an allocatable array (grow_template.inc).
     module procedure grow_cload
  end interface grow

  public :: build_steps

  type :: kept_t
    !! The elements the distributed-load lines keep after their checks, in
    !! line order: chunk c is line(c) on substructure sub(c), its elements
    !! ids(last(c-1)+1 : last(c)) (4 bytes each where a dload_t is hundreds).
     integer :: nid = 0
     integer :: nchunk = 0
     integer(ip), allocatable :: ids(:)
     integer, allocatable :: line(:), sub(:), last(:)
  end type kept_t

contains

  subroutine build_steps(st, model)
    !! The steps of the model: loads, boundary conditions, thermal loads, output requests and combinations.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: s, j
    type(cload_t), allocatable :: cl(:)
    type(dload_t), allocatable :: dl(:)
    type(load_b_t), allocatable :: own(:)
    allocate (model%steps(st%nstep))
    do s = 1, st%nstep
       model%steps(s)%name = st%steps(s)%name
       model%steps(s)%loc = st%steps(s)%loc
       model%steps(s)%procedure_card = st%steps(s)%has_procedure
       do j = 1, s - 1
          if (st%steps(j)%name == st%steps(s)%name) then
             call report_loc(st, st%steps(s)%loc, 'duplicate step name '//st%steps(s)%name// &
                  ' (first at '//where(st, st%steps(j)%loc)//')')
             exit
          end if
       end do
       call build_cloads(st, model, st%steps(s)%cloads(1:st%steps(s)%ncload), cl)
       call move_alloc(cl, model%steps(s)%cloads)
       if (st%aborted) return
       own = st%steps(s)%dloads(1:st%steps(s)%ndload)
       ! *DLOAD P pushes along the shell normal in every deck (Abaqus, CalculiX,
       ! Nastran PLOAD2), with or without *STATIC; the element's value, like
       ! the pressure on a *SURFACE SPOS face, pushes against it
       where (own%kind == DLOAD_P .and. .not. own%surface) own%value = -own%value
       call build_dloads(st, model, own, dl)
       call move_alloc(dl, model%steps(s)%dloads)
       if (st%aborted) return
    end do
    call build_thermal(st, model)
    if (st%aborted) return
    call build_history(st, model)
    if (st%aborted) return
    call step_times(st, model)
    call apply_amplitudes(st, model)
  end subroutine build_steps

  subroutine step_times(st, model)
    !! Each step's time period (*STATIC's data line, 1 without one) and the
    !! total time at its end (the periods so far; *STATIC, TIME RESET does not
    !! advance it), as ccx 2.20 counts them (measured): amplitudes' times and
    !! CalculiX's time in the .dat, .frd and .sta files.
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(inout) :: model
    real(wp) :: total
    integer :: s
    total = 0.0_wp
    do s = 1, size(model%steps)
       model%steps(s)%period = st%steps(s)%period
       if (.not. st%steps(s)%time_reset) total = total + st%steps(s)%period
       model%steps(s)%total_time = total
    end do
  end subroutine step_times

  subroutine build_history(st, model)
    !! The steps' boundary conditions and the loads continued by OP=MOD
    !! (superjoin_model_history).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(support_list_t), allocatable :: own(:)
    type(step_ops_t), allocatable :: ops(:)
    integer :: s
    allocate (own(st%nstep), ops(st%nstep))
    do s = 1, st%nstep
       ops(s)%bc_new = st%steps(s)%bc_op == OP_NEW
       ops(s)%cload_mod = keeps_previous(st%steps(s), st%steps(s)%cload_op)
       ops(s)%dload_mod = keeps_previous(st%steps(s), st%steps(s)%dload_op)
    end do
    call apply_load_history(model, ops)
    call note_perturbation_stiffness(st, model)
    if (.not. any(st%steps(1:st%nstep)%has_boundary)) return
    do s = 1, st%nstep
       call support_list(st, model, s, own(s)%items)
       if (st%aborted) return
    end do
    call apply_boundary_history(model, own, ops)
    call note_held_perturbation(st, model)
  end subroutine build_history

  subroutine note_perturbation_stiffness(st, model)
    !! A PERTURBATION step after another step: ccx 2.20 solves it with the
    !! stress stiffness of the step before added (its stresses taken as
    !! initial stresses: measured, the difference scales with stress / E);
    !! superjoin, as Abaqus after a general step without NLGEOM, with the
    !! elastic stiffness alone. Said in the listing, once per such step.
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(inout) :: model
    integer :: s
    do s = 2, st%nstep
       if (.not. st%steps(s)%perturbation) cycle
       call note(model%notes, 'warning: step '//st%steps(s)%name//' (*STEP, PERTURBATION at '// &
            where(st, st%steps(s)%loc)//') is solved with the elastic stiffness alone, as Abaqus solves a '// &
            'perturbation of a step without NLGEOM; ccx 2.20 adds the stress stiffness of step '// &
            st%steps(s - 1)%name//'''s stresses, so its displacements differ by about the ratio of those '// &
            'stresses to E')
    end do
  end subroutine note_perturbation_stiffness

  subroutine note_held_perturbation(st, model)
    !! *BOUNDARY, FIXED in a PERTURBATION step or after one: CalculiX holds
    !! the DOFs at the previous step's displacements (ccx 2.20, measured on
    !! both), as superjoin does; Abaqus reads a perturbation step apart from
    !! its base state. Said in the listing, once per data line.
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(inout) :: model
    character(:), allocatable :: why
    integer :: k, s
    do k = 1, st%nsupport
       s = st%supports(k)%step
       if (.not. st%supports(k)%held .or. s < 2) cycle
       if (st%steps(s)%perturbation) then
          why = 'in a PERTURBATION step (Abaqus: its prescribed values are perturbations of its base state)'
       else if (st%steps(s - 1)%perturbation) then
          why = 'after a PERTURBATION step (Abaqus: the last general step''s; a perturbation step does not '// &
               'change the base state)'
       else
          cycle
       end if
       call note(model%notes, 'warning: *BOUNDARY, FIXED at '//where(st, st%supports(k)%loc)// &
            ': its DOFs are held at the displacements of step '//st%steps(s - 1)%name//', as CalculiX holds them '//why)
    end do
  end subroutine note_held_perturbation

  subroutine build_cloads(st, model, loads, out)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(load_b_t), intent(in) :: loads(:)
    type(cload_t), allocatable, intent(out) :: out(:)
    type(cload_t), allocatable :: tmp(:)
    integer(ip), allocatable :: nodes(:)
    integer :: k, n, isub, stat, m
    integer(ip) :: i
    integer, allocatable :: subs(:)
    logical :: ok
    allocate (out(INITIAL_CAPACITY))
    n = 0
    do k = 1, size(loads)
       call ref_subs(st, model, loads(k)%ref, loads(k)%loc, 'node', subs)   ! several: a set over instances
       do m = 1, size(subs)
          isub = subs(m)
          call resolve_items(st, model, isub, loads(k)%ref, .false., loads(k)%loc, nodes, ok)
          if (.not. ok) cycle
          call grow(out, n, INITIAL_CAPACITY, stat, more=size(nodes))
          if (stat /= 0) then
             call report_oom(st, loads(k)%loc, 'the concentrated loads', &
                  int(max(2*n, INITIAL_CAPACITY, n + size(nodes)), i8)*storage_size(out)/8)
             return
          end if
          do i = 1, size(nodes, kind=ip)
             n = n + 1
             out(n)%sub = isub
             out(n)%node = nodes(i)
             out(n)%dof = loads(k)%dof
             out(n)%value = loads(k)%value
             out(n)%loc = loads(k)%loc
          end do
       end do
    end do
    if (n == size(out)) return   ! filled exactly: no copy
    allocate (tmp(n), stat=stat)
    if (stat /= 0) then
       call report_oom(st, loads(size(loads))%loc, 'the concentrated loads', int(n, i8)*storage_size(out)/8)
       return
    end if
    tmp(:) = out(1:n)
    call move_alloc(tmp, out)
  end subroutine build_cloads

  subroutine build_dloads(st, model, loads, out)
    !! The distributed loads of the lines loads on the elements they name: the
    !! lines' elements resolved and checked first (kept_t, a few bytes each),
    !! then `out` allocated once at its exact size and filled (no growing list
    !! of the large dload_t entries, no trimming copy).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(load_b_t), intent(in) :: loads(:)
    type(dload_t), allocatable, intent(out) :: out(:)
    type(kept_t) :: kept
    integer(ip), allocatable :: elems(:)
    integer :: k, isub, stat, m, c, first
    integer(ip) :: i
    integer, allocatable :: subs(:)
    logical :: ok
    do k = 1, size(loads)
       if (loads(k)%whole_model) then
          ! GRAV with an empty element field: every element of the model, or of
          ! the substructure whose block the line stands in
          do isub = 1, size(model%subs)
             if (loads(k)%home /= 0 .and. isub /= loads(k)%home) cycle
             elems = [(i, i=1, model%subs(isub)%nelem)]
             call keep_elements(st, model, k, loads(k), isub, elems, kept)
             if (st%aborted) exit
          end do
          if (st%aborted) exit
          cycle
       end if
       call ref_subs(st, model, loads(k)%ref, loads(k)%loc, 'element', subs)   ! several: a set over instances
       do m = 1, size(subs)
          call resolve_items(st, model, subs(m), loads(k)%ref, .true., loads(k)%loc, elems, ok)
          if (.not. ok) cycle
          call keep_elements(st, model, k, loads(k), subs(m), elems, kept)
          if (st%aborted) exit
       end do
       if (st%aborted) exit
    end do
    if (st%aborted) then   ! the deck is not run: no loads to build
       allocate (out(0))
       return
    end if
    allocate (out(kept%nid), stat=stat)
    if (stat /= 0) then
       call report_oom(st, loads(size(loads))%loc, 'the distributed loads', int(kept%nid, i8)*storage_size(out)/8)
       allocate (out(0))
       return
    end if
    first = 1
    do c = 1, kept%nchunk
       associate (ld => loads(kept%line(c)))
         do m = first, kept%last(c)
            out(m)%sub = kept%sub(c)
            out(m)%elem = kept%ids(m)
            out(m)%kind = ld%kind
            out(m)%value = ld%value
            out(m)%dir = ld%dir
            out(m)%point = ld%point
            out(m)%face = ld%face
            out(m)%loc = ld%loc
         end do
       end associate
       first = kept%last(c) + 1
    end do
  end subroutine build_dloads

  subroutine keep_elements(st, model, k, ld, isub, elems, kept)
    !! The elements of elems (substructure isub) that line ld (the k-th) loads,
    !! with the checks: appended to kept as one chunk.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: k
    type(load_b_t), intent(in) :: ld
    integer, intent(in) :: isub
    integer(ip), intent(in) :: elems(:)
    type(kept_t), intent(inout) :: kept
    integer :: nodens, nbad, et, stat
    integer(ip) :: i, first_nodens, first_bad
    logical :: plane_ok
    nbad = 0
    first_bad = 0
    nodens = 0
    first_nodens = 0
    ! CENTRIF keeps the XY plane in itself: axis along Z, or in the plane; a traction: no Z part
    plane_ok = ld%kind /= DLOAD_CENTRIF .or. abs(ld%dir(3)) == 1.0_wp .or. &
         (ld%dir(3) == 0.0_wp .and. ld%point(3) == 0.0_wp)
    if (ld%kind == DLOAD_TRVEC .or. ld%kind == DLOAD_TRSHR) plane_ok = ld%dir(3) == 0.0_wp
    ! room for every element at once (one copy, not one per doubling)
    call grow(kept%ids, kept%nid, INITIAL_CAPACITY, stat, more=size(elems))
    if (stat == 0) call grow(kept%line, kept%nchunk, INITIAL_CAPACITY, stat)
    if (stat == 0) call grow(kept%sub, kept%nchunk, INITIAL_CAPACITY, stat)
    if (stat == 0) call grow(kept%last, kept%nchunk, INITIAL_CAPACITY, stat)
    if (stat /= 0) then
       call report_oom(st, ld%loc, 'the distributed loads', &
            int(max(2*kept%nid, INITIAL_CAPACITY, kept%nid + size(elems)), i8)*storage_size(kept%ids)/8)
       return
    end if
    do i = 1, size(elems, kind=ip)
       et = model%subs(isub)%elem_type(elems(i))
       if (.not. accepts_dload(ld%kind, et)) then
          nbad = nbad + 1
          if (nbad == 1) first_bad = elems(i)
          cycle
       end if
       if (.not. plane_ok) then
          if (out_of_plane(ld%kind, et)) then
             if (ld%kind == DLOAD_CENTRIF) then
                call report_loc(st, ld%loc, 'CENTRIF loads a plane element out of the XY plane '// &
                     '(the axis must be parallel to Z, or lie in the XY plane)')
             else
                call report_loc(st, ld%loc, 'a traction loads a plane element out of the XY plane '// &
                     '(its direction must lie in the XY plane)')
             end if
             plane_ok = .true.   ! reported once
             cycle
          end if
       end if
       if (ld%kind == DLOAD_GRAV .or. ld%kind == DLOAD_CENTRIF) then
          associate (sub => model%subs(isub))
            if (sub%elem_section(elems(i)) == 0) cycle
            if (sub%sections(sub%elem_section(elems(i)))%material == 0) cycle   ! an unknown material, reported
            if (.not. model%materials(sub%sections(sub%elem_section(elems(i)))%material)%has_density) then
               nodens = nodens + 1
               if (nodens == 1) first_nodens = elems(i)
               cycle
            end if
          end associate
       end if
       kept%nid = kept%nid + 1
       kept%ids(kept%nid) = elems(i)
    end do
    kept%nchunk = kept%nchunk + 1
    kept%line(kept%nchunk) = k
    kept%sub(kept%nchunk) = isub
    kept%last(kept%nchunk) = kept%nid
    associate (sub => model%subs(isub))
      if (nodens > 0) call report_loc(st, ld%loc, '*DLOAD '//trim(DLOAD_NAMES(ld%kind))//' on element '// &
           itoa(sub%elem_id(first_nodens))//' of substructure '//sub%name//', whose material '// &
           model%materials(sub%sections(sub%elem_section(first_nodens))%material)%name// &
           ' has no *DENSITY'//more_text(nodens - 1))
      if (nbad > 0) call report_loc(st, ld%loc, trim(merge('*DSLOAD: face', '*DLOAD       ', ld%surface))// &
           ' '//trim(surface_face(ld))//' does not apply to element '//itoa(sub%elem_id(first_bad))//' of type '// &
           trim(ELEMENT_TYPE_NAMES(sub%elem_type(first_bad)))//' ('//dload_targets(ld%kind)//')'//more_text(nbad - 1))
    end associate
  end subroutine keep_elements

  elemental logical function out_of_plane(kind, et)
    !! A load of kind DLOAD_* that leaves the XY plane cannot load element type
    !! et: CENTRIF a plane element, a traction a plane or axisymmetric one.
    integer, intent(in) :: kind, et
    type(element_traits_t) :: t
    t = element_traits(et)
    if (kind == DLOAD_CENTRIF) then
       out_of_plane = t%family == FAMILY_PLANE
    else
       out_of_plane = t%planar
    end if
  end function out_of_plane

  pure function surface_face(ld) result(name)
    !! The load form as the deck wrote it: a *DLOAD type, or the face of a
    !! *SURFACE line (S1 to S4, SPOS / SNEG) for a *DSLOAD.
    type(load_b_t), intent(in) :: ld
    character(:), allocatable :: name
    name = trim(DLOAD_NAMES(ld%kind))
    if (.not. ld%surface) return
    if (ld%kind >= DLOAD_P1 .and. ld%kind <= DLOAD_P4) then
       name = 'S'//name(2:2)//' (edge '//name(2:2)//')'
    else if (ld%kind == DLOAD_P5 .or. ld%kind == DLOAD_P6) then
       name = 'S'//name(2:2)//' (face '//name(2:2)//')'
    else if (ld%kind == DLOAD_P) then
       name = 'SPOS or SNEG'
    else if (ld%face > 0) then   ! TRVEC, TRSHR on a face or an edge
       name = name//' on S'//itoa(ld%face)
    else if (ld%kind == DLOAD_TRVEC .or. ld%kind == DLOAD_TRSHR) then
       name = name//' on SPOS or SNEG'
    end if
  end function surface_face

  pure function dload_targets(kind) result(s)
    integer, intent(in) :: kind
    character(:), allocatable :: s
    select case (kind)
    case (DLOAD_PX, DLOAD_PY)
       s = 'PX and PY apply to beams B23, B33, B21, B31 and B32'
    case (DLOAD_PZ)
       s = 'PZ applies to 3D beams B33, B31 and B32'
    case (DLOAD_P1)
       s = 'P1 applies to the first edge of plane elements, to 3D beams B33 and B31 and to face 1 of solids'
    case (DLOAD_P2)
       s = 'P2 applies to the second edge of plane elements, to beams and to face 2 of solids'
    case (DLOAD_P3)
       s = 'P3 applies to the third edge of plane elements and to face 3 of solids'
    case (DLOAD_P4)
       s = 'P4 applies to the fourth edge of quadrilaterals CPS4, CPS8, CPS8R, CPE4, CPE8 and CPE8R and to face 4 '// &
            'of solids'
    case (DLOAD_P5, DLOAD_P6)
       s = trim(DLOAD_NAMES(kind))//' applies to the faces of solid hexahedra C3D8, C3D20 and C3D20R'
    case (DLOAD_CENTRIF)
       s = 'CENTRIF applies to trusses, two-node beams, plane, shell and solid elements'
    case (DLOAD_BX, DLOAD_BY, DLOAD_BZ)
       s = 'BX, BY and BZ apply to trusses, beams, plane, shell and solid elements; Abaqus loads axisymmetric '// &
            'elements with BR and BZ, along the radius and the axis (GRAV along the axis y)'
    case (DLOAD_TRVEC, DLOAD_TRSHR)
       s = 'TRVEC and TRSHR apply to the faces of solids, the edges of plane and axisymmetric elements and the '// &
            'surfaces of shells'
    case default
       s = 'P applies to shells S3 and S4'
    end select
  end function dload_targets

  ! ------------------------------------------------------------------ growing arrays

#define GROW_NAME grow_cload
#define GROW_TYPE type(cload_t)
#include "grow_template.inc"

end module superjoin_deck_build_steps
