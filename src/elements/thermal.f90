module superjoin_elements_thermal
  !! Thermal loads of line elements: a uniform temperature change ΔT of a
  !! truss or beam of axial stiffness E A and expansion coefficient α is the
  !! initial strain α ΔT; its consistent nodal loads are the pair of axial
  !! forces N_T = E A α ΔT that push the two nodes apart, and the end forces
  !! of the element are K u minus them: N = E A (ε - α ΔT), so a heated bar
  !! held at both ends is compressed by N_T. No bending (uniform through the
  !! section).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: section_t
  use superjoin_elements_frame, only: beam_frame
  implicit none (type, external)
  private

  public :: thermal_axial_load

contains

  pure subroutine thermal_axial_load(etype, x, sec, dofs, nt, fe, error)
    !! Consistent nodal loads fe (global axes, node-major with the DOFs `dofs`
    !! of each node, as element_node_dofs) of the thermal axial force nt =
    !! E A α ΔT on a two-node truss or beam.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    integer, intent(in) :: dofs(:)
    real(wp), intent(in) :: nt
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), length
    integer :: k, nd
    call beam_frame(etype, x, sec, r, length, error)
    if (allocated(error)) return
    nd = size(dofs)
    allocate (fe(2*nd), source=0.0_wp)
    do k = 1, nd
       if (dofs(k) > 3) cycle
       fe(k) = -nt*r(1, dofs(k))
       fe(nd + k) = nt*r(1, dofs(k))
    end do
  end subroutine thermal_axial_load
end module superjoin_elements_thermal
