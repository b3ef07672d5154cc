module superjoin_analysis_body_loads
  !! What the element results need of the loads that are not the element's
  !! own distributed-load forms: the thermal strains of plane and shell
  !! elements (their resultants and stresses are D (ε - ε0), taken off by the
  !! element facade's take_thermal_resultants) and the consistent end loads
  !! of a centrifugal load on bars and beams (their end forces are K u - f_eq
  !! with a load that varies along the element).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, DLOAD_THERMAL, DLOAD_CENTRIF, &
       ELEMENT_NODE_COUNT, combination_t
  use superjoin_elements, only: is_plate_type, is_solid_type, element_body_end_forces
  use superjoin_model_types, only: MAX_ELEMENT_NODES, has_nodal, has_curvature_nodal, has_line_nodal
  implicit none (type, external)
  private

  public :: plate_thermal_strains, line_centrif_forces, superpose_thermal
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
    !! tn(1:n, element, step): α ΔT at the n nodes of every element whose
    !! temperature varies over it, a plane or shell element's minus its mean,
    !! a solid's whole (model-wide element numbering elem_offset);
    !! unallocated when no step has one.
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: nstep
    real(wp), allocatable, intent(out) :: tn(:, :, :)
    integer :: is, i, n
    do is = 1, nstep
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i))
            if (dl%kind /= DLOAD_THERMAL .or. .not. has_nodal(dl)) cycle
            if (.not. allocated(tn)) allocate (tn(MAX_ELEMENT_NODES, elem_offset(size(elem_offset)), nstep), &
                 source=0.0_wp)
            n = size(dl%nodes%nodal)
            tn(1:n, elem_offset(dl%sub) + dl%elem, is) = tn(1:n, elem_offset(dl%sub) + dl%elem, is) + dl%nodes%nodal
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
            if (dl%kind /= DLOAD_THERMAL .or. .not. has_curvature_nodal(dl)) cycle
            if (.not. allocated(cn)) allocate (cn(MAX_ELEMENT_NODES, elem_offset(size(elem_offset)), nstep), &
                 source=0.0_wp)
            n = size(dl%nodes%curvature_nodal)
            cn(1:n, elem_offset(dl%sub) + dl%elem, is) = cn(1:n, elem_offset(dl%sub) + dl%elem, is) + &
                 dl%nodes%curvature_nodal
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
            if (all(dl%gradient == 0.0_wp) .and. .not. has_line_nodal(dl)) cycle
            etype = s%elem_type(dl%elem)
            nn = ELEMENT_NODE_COUNT(etype)
            associate (sec => s%sections(s%elem_section(dl%elem)))
              ! errors were reported when the loads were assembled
              call element_body_end_forces(etype, s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                   model%materials(sec%material), dl, f, error)
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
    real(wp) :: f(6, 2)
    integer :: is, i, nn, etype
    integer(i8) :: ie
    type(error_t), allocatable :: error
    do is = 1, nstep
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i), s => model%subs(model%steps(is)%dloads(i)%sub))
            if (dl%kind /= DLOAD_CENTRIF) cycle
            etype = s%elem_type(dl%elem)
            if (is_plate_type(etype) .or. is_solid_type(etype)) cycle   ! no end forces
            nn = ELEMENT_NODE_COUNT(etype)
            associate (sec => s%sections(s%elem_section(dl%elem)))
              ! errors were reported when the loads were assembled
              call element_body_end_forces(etype, s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                   model%materials(sec%material), dl, f, error)
              if (allocated(error)) cycle
            end associate
            if (.not. allocated(f0)) allocate (f0(6, 2, elem_offset(size(elem_offset)), nstep), source=0.0_wp)
            ie = elem_offset(dl%sub) + dl%elem
            f0(:, :, ie, is) = f0(:, :, ie, is) + f
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
end module superjoin_analysis_body_loads
