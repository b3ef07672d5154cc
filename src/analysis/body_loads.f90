module superjoin_analysis_body_loads
  !! What the element results need of the loads that are not the element's
  !! own distributed-load forms: the thermal strains of plane and shell
  !! elements (their resultants and stresses are D (ε - ε0)) and the
  !! consistent end loads of a centrifugal load on bars and beams (their end
  !! forces are K u - f_eq with a load that varies along the element).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, section_t, material_t, DLOAD_THERMAL, DLOAD_CENTRIF, &
       ELEMENT_NODE_COUNT, combination_t
  use superjoin_elements, only: is_plate_type, element_material_load, element_node_dofs, beam_frame
  use superjoin_elements_thermal, only: thermal_plate_resultants
  use superjoin_elements_shell8_loads, only: s8r_thermal_resultants
  use superjoin_model_types, only: ET_S8R
  use superjoin_elements_thermal, only: thermal_beam_end_forces
  use superjoin_elements_beam3, only: beam3_thermal_end_forces
  use superjoin_elements_shell, only: shell_thermal_nodal_resultants, is_plane_type
  use superjoin_model_types, only: MAX_ELEMENT_NODES
  use superjoin_elements_drill_mask, only: element_drill
  implicit none (type, external)
  private

  public :: plate_thermal_strains, line_centrif_forces, take_thermal_resultants, superpose_thermal
  public :: plane_thermal_nodal, line_thermal_forces, shell_thermal_curvature_nodal

contains

  subroutine plate_thermal_strains(model, elem_offset, nstep, th)
    !! th(1:2, element, step): the thermal strain α ΔT and curvature α ∂T/∂n
    !! of every plane and shell element (model-wide element numbering
    !! elem_offset); unallocated when no step heats one.
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: nstep
    real(wp), allocatable, intent(out) :: th(:, :, :)
    integer :: is, i
    do is = 1, nstep
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i))
            if (dl%kind /= DLOAD_THERMAL) cycle
            if (.not. is_plate_type(model%subs(dl%sub)%elem_type(dl%elem))) cycle
            if (.not. allocated(th)) allocate (th(2, elem_offset(size(elem_offset)), nstep), source=0.0_wp)
            th(:, elem_offset(dl%sub) + dl%elem, is) = th(:, elem_offset(dl%sub) + dl%elem, is) + &
                 [dl%value, dl%curvature]
          end associate
       end do
    end do
  end subroutine plate_thermal_strains

  subroutine plane_thermal_nodal(model, elem_offset, nstep, tn)
    !! tn(1:n, element, step): α ΔT at the n nodes of every plane or shell
    !! element whose temperature varies, minus its mean (model-wide element
    !! numbering elem_offset); unallocated when no step has one.
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: nstep
    real(wp), allocatable, intent(out) :: tn(:, :, :)
    integer :: is, i, n
    do is = 1, nstep
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i))
            if (dl%kind /= DLOAD_THERMAL .or. .not. allocated(dl%nodal)) cycle
            if (.not. allocated(tn)) allocate (tn(MAX_ELEMENT_NODES, elem_offset(size(elem_offset)), nstep), &
                 source=0.0_wp)
            n = size(dl%nodal)
            tn(1:n, elem_offset(dl%sub) + dl%elem, is) = tn(1:n, elem_offset(dl%sub) + dl%elem, is) + dl%nodal
          end associate
       end do
    end do
  end subroutine plane_thermal_nodal

  subroutine shell_thermal_curvature_nodal(model, elem_offset, nstep, cn)
    !! cn(1:n, element, step): α ∂T/∂n at the n nodes of every shell whose
    !! temperature or gradient varies, minus its mean (model-wide element
    !! numbering elem_offset); unallocated when no step has one.
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: nstep
    real(wp), allocatable, intent(out) :: cn(:, :, :)
    integer :: is, i, n
    do is = 1, nstep
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i))
            if (dl%kind /= DLOAD_THERMAL .or. .not. allocated(dl%curvature_nodal)) cycle
            if (.not. allocated(cn)) allocate (cn(MAX_ELEMENT_NODES, elem_offset(size(elem_offset)), nstep), &
                 source=0.0_wp)
            n = size(dl%curvature_nodal)
            cn(1:n, elem_offset(dl%sub) + dl%elem, is) = cn(1:n, elem_offset(dl%sub) + dl%elem, is) + &
                 dl%curvature_nodal
          end associate
       end do
    end do
  end subroutine shell_thermal_curvature_nodal

  subroutine line_thermal_forces(model, elem_offset, nstep, f0)
    !! Add to f0(1:6, end, element, step) (allocated here if need be) the end
    !! forces of the free thermal bending of every beam with a temperature
    !! gradient across its section, and the end shares of the whole thermal
    !! load of a B32 (what their end forces K u - f_eq take off).
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: nstep
    real(wp), allocatable, intent(inout) :: f0(:, :, :, :)
    real(wp) :: f(6, 2)
    integer :: is, i, nn, etype
    integer(i8) :: ie
    type(error_t), allocatable :: error
    do is = 1, nstep
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i), s => model%subs(model%steps(is)%dloads(i)%sub))
            if (dl%kind /= DLOAD_THERMAL) cycle
            if (all(dl%gradient == 0.0_wp) .and. .not. allocated(dl%line_nodal)) cycle
            etype = s%elem_type(dl%elem)
            nn = ELEMENT_NODE_COUNT(etype)
            associate (sec => s%sections(s%elem_section(dl%elem)))
              ! errors were reported when the loads were assembled
              if (allocated(dl%line_nodal)) then   ! a B32: its whole thermal load
                 call beam3_thermal_end_forces(s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                      model%materials(sec%material), dl%line_nodal, f, error)
              else
                 call thermal_beam_end_forces(etype, s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                      model%materials(sec%material), dl%gradient, f, error)
              end if
              if (allocated(error)) cycle
            end associate
            if (.not. allocated(f0)) allocate (f0(6, 2, elem_offset(size(elem_offset)), nstep), source=0.0_wp)
            ie = elem_offset(dl%sub) + dl%elem
            f0(:, :, ie, is) = f0(:, :, ie, is) + f
          end associate
       end do
    end do
  end subroutine line_thermal_forces

  subroutine line_centrif_forces(model, elem_offset, nstep, f0)
    !! f0(1:6, end, element, step): the consistent nodal loads of the
    !! centrifugal loads on bars and beams in their local axes (what their end
    !! forces K u - f_eq take off); unallocated when there is none.
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: nstep
    real(wp), allocatable, intent(out) :: f0(:, :, :, :)
    real(wp), allocatable :: fe(:)
    real(wp) :: r(3, 3), length, g(6)
    integer, allocatable :: dofs(:)
    integer :: is, i, a, nn, nd, etype
    integer(i8) :: ie
    type(error_t), allocatable :: error
    do is = 1, nstep
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i), s => model%subs(model%steps(is)%dloads(i)%sub))
            if (dl%kind /= DLOAD_CENTRIF) cycle
            etype = s%elem_type(dl%elem)
            if (is_plate_type(etype)) cycle
            nn = ELEMENT_NODE_COUNT(etype)
            associate (sec => s%sections(s%elem_section(dl%elem)))
              ! errors were reported when the loads were assembled
              call element_material_load(etype, s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                   model%materials(sec%material), dl, fe, error, element_drill(s, dl%elem))
              if (allocated(error)) cycle
              call beam_frame(etype, s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, r, length, error)
              if (allocated(error)) cycle
            end associate
            if (.not. allocated(f0)) allocate (f0(6, 2, elem_offset(size(elem_offset)), nstep), source=0.0_wp)
            dofs = element_node_dofs(etype)
            nd = size(dofs)
            ie = elem_offset(dl%sub) + dl%elem
            do a = 1, 2
               g = 0.0_wp
               g(dofs) = fe(nd*(a - 1) + 1:nd*a)
               f0(1:3, a, ie, is) = f0(1:3, a, ie, is) + matmul(r, g(1:3))
               f0(4:6, a, ie, is) = f0(4:6, a, ie, is) + matmul(r, g(4:6))
            end do
          end associate
       end do
    end do
  end subroutine line_centrif_forces

  subroutine superpose_thermal(combos, ns, th)
    !! Append to the thermal strains th(2, nelem, ns) of the ns solved steps
    !! those of the load combinations (the stresses of a combination are
    !! D (ε - ε0) of its superposed strains); nothing when th is unallocated.
    type(combination_t), intent(in) :: combos(:)
    integer, intent(in) :: ns
    real(wp), allocatable, intent(inout) :: th(:, :, :)
    real(wp), allocatable :: all(:, :, :)
    integer :: c, k
    if (.not. allocated(th)) return
    allocate (all(size(th, 1), size(th, 2), ns + size(combos)), source=0.0_wp)
    all(:, :, 1:ns) = th(:, :, 1:ns)
    do c = 1, size(combos)
       do k = 1, size(combos(c)%steps)
          all(:, :, ns + c) = all(:, :, ns + c) + combos(c)%factors(k)*th(:, :, combos(c)%steps(k))
       end do
    end do
    call move_alloc(all, th)
  end subroutine superpose_thermal

  pure subroutine take_thermal_resultants(etype, x, sec, mat, th, plate, tn, cn, drill)
    !! Take the resultants of the free thermal expansion th(1:2, step) off the
    !! resultants plate(6, step) of a plane or shell element (N = D (ε - ε0));
    !! tn(:, step): the nodal remainders of a varying temperature (plane and
    !! shell elements, plane_thermal_nodal), cn(:, step) those of the
    !! gradient of a shell (shell_thermal_curvature_nodal), if any; drill:
    !! the shell's drilling edge mask.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: th(:, :)
    real(wp), intent(inout) :: plate(:, :)
    real(wp), intent(in), optional :: tn(:, :), cn(:, :)
    integer, intent(in), optional :: drill
    real(wp) :: res0(6), rem(2, size(x, 2))
    type(error_t), allocatable :: error
    integer :: is, n
    logical :: varying
    n = size(x, 2)
    do is = 1, size(th, 2)
       rem = 0.0_wp
       if (present(tn)) rem(1, :) = tn(1:n, is)
       if (present(cn)) rem(2, :) = cn(1:n, is)
       varying = any(rem /= 0.0_wp)
       if (all(th(:, is) == 0.0_wp) .and. .not. varying) cycle
       ! an element that cannot be evaluated has been reported by shell_forces
       if (etype == ET_S8R) then
          if (varying) then
             call s8r_thermal_resultants(sec, mat, th(1, is), th(2, is), res0, rem)
          else
             call s8r_thermal_resultants(sec, mat, th(1, is), th(2, is), res0)
          end if
       else if (present(tn)) then
          call thermal_plate_resultants(etype, x, sec, mat, th(1, is), th(2, is), res0, error, tn(1:n, is))
          if (allocated(error)) return
       else
          call thermal_plate_resultants(etype, x, sec, mat, th(1, is), th(2, is), res0, error)
          if (allocated(error)) return
       end if
       plate(:, is) = plate(:, is) - res0
       if (etype == ET_S8R .or. is_plane_type(etype) .or. .not. varying) cycle
       ! a shell whose temperature varies: the nodal remainders, interpolated
       call shell_thermal_nodal_resultants(etype, x, sec, mat, rem(1, :), rem(2, :), res0, error, drill)
       if (allocated(error)) return
       plate(:, is) = plate(:, is) - res0
    end do
  end subroutine take_thermal_resultants
end module superjoin_analysis_body_loads
