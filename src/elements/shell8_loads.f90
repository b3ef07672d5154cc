module superjoin_elements_shell8_loads
  !! The loads of an S8R that need its section and material beyond the
  !! pressure: self weight of a tapered section (ρ t(ξ, η) per unit area),
  !! thermal strains (uniform α ΔT and the gradient α ∂T/∂n through the
  !! thickness) and the centrifugal load (consistent mass ∫ ρ t N_i N_j dA
  !! times the nodal distance vectors from the axis, exact because that
  !! vector is linear in x). The element itself is superjoin_elements_shell8;
  !! this module is the glue from section_t / material_t / dload_t, in the
  !! element frame of superjoin_elements_shell (lamina e1 along its local x).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, dload_t, ELEMENT_NODE_COUNT, ET_S8R, ET_S6, has_nodal
  use superjoin_elements_shell, only: shell_frame, shell8_props
  use superjoin_elements_traits, only: is_shell8
  use superjoin_elements_shell8, only: shell8_volume_shares, shell8_mass, shell8_thermal_load, &
       shell8_thermal_resultants
  use superjoin_elements_centrif, only: axis_distance
  implicit none (type, external)
  private

  integer, parameter :: NDN = 6   !! DOFs per S8R node
  integer, parameter :: NN8 = 8   !! nodes of an S8R
  integer, parameter :: NN6 = 6   !! nodes of an S6

  public :: s8r_is_tapered, s8r_gravity_load, s8r_thermal_load, s8r_thermal_resultants, s8r_centrif_load
  public :: s8r_thermal_terms

contains

  pure logical function s8r_is_tapered(etype, sec)
    !! An S8R or S8 whose section carries a thickness per node.
    integer, intent(in) :: etype
    type(section_t), intent(in) :: sec
    s8r_is_tapered = is_shell8(etype) .and. allocated(sec%node_thickness)
  end function s8r_is_tapered

  pure subroutine s8r_gravity_load(x, sec, mat, accel, fe, error)
    !! Consistent nodal loads fe(48) (global axes) of the self weight ρ t(ξ, η)
    !! per unit area under the acceleration accel(3) (global axes).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: accel(3)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: shares(size(x, 2))
    integer :: i
    if (size(x, 2) /= ELEMENT_NODE_COUNT(ET_S8R) .and. size(x, 2) /= ELEMENT_NODE_COUNT(ET_S6)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodes')
       return
    end if
    call shell8_volume_shares(x, shell8_props(sec, mat), shares, error)
    if (allocated(error)) return
    allocate (fe(NDN*size(x, 2)), source=0.0_wp)
    do i = 1, size(x, 2)
       fe(NDN*i - 5:NDN*i - 3) = shares(i)*mat%density*accel
    end do
  end subroutine s8r_gravity_load

  pure subroutine s8r_thermal_load(etype, x, sec, mat, strain, curvature, fe, error, strain_nodal, curvature_nodal)
    !! Consistent nodal loads fe(48) (global axes) of an S8R or S8 (etype) under the thermal strain
    !! strain = α ΔT and curvature = α ∂T/∂n (superjoin_elements_shell8); with
    !! strain_nodal(8), curvature_nodal(8) the nodes' remainders after them,
    !! interpolated to the integration points.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain, curvature
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: strain_nodal(:), curvature_nodal(:)
    real(wp) :: e1(3)
    call thermal_axis(x, e1, error)
    if (allocated(error)) return
    call shell8_thermal_load(x, e1, shell8_props(sec, mat, etype), strain, curvature, fe, error, strain_nodal, &
         curvature_nodal)
  end subroutine s8r_thermal_load

  pure subroutine thermal_axis(x, e1, error)
    !! The node count of an S8R or S8 at x checked, and the first axis e1 of
    !! its shell frame (what shell8_thermal_load takes).
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: e1(3)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    e1 = 0.0_wp
    if (size(x, 2) /= ELEMENT_NODE_COUNT(ET_S8R) .and. size(x, 2) /= ELEMENT_NODE_COUNT(ET_S6)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodes')
       return
    end if
    call shell_frame(x, r, xl, h, error)
    if (allocated(error)) return
    e1 = r(1, :)
  end subroutine thermal_axis

  pure subroutine s8r_thermal_terms(etype, x, sec, mat, dl, fe, self_energy, error)
    !! The thermal load dl (DLOAD_THERMAL) of an S8R or S8 (etype) as
    !! s8r_thermal_load (its nodal remainders when dl carries them, has_nodal), and
    !! self_energy = ½ ∫ ε0ᵀ D ε0 dV by the same rules (shell8_thermal_load):
    !! the energy of the mechanical strains is ½ uᵀ K u - uᵀ fe + self_energy.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: self_energy
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: e1(3)
    self_energy = 0.0_wp
    call thermal_axis(x, e1, error)
    if (allocated(error)) return
    if (has_nodal(dl)) then
       call shell8_thermal_load(x, e1, shell8_props(sec, mat, etype), dl%value, dl%curvature, fe, error, &
            dl%nodes%nodal, dl%nodes%curvature_nodal, self_energy)
    else
       call shell8_thermal_load(x, e1, shell8_props(sec, mat, etype), dl%value, dl%curvature, fe, error, &
            self_energy=self_energy)
    end if
  end subroutine s8r_thermal_terms

  pure subroutine s8r_thermal_resultants(sec, mat, strain, curvature, res, nnode, nodal)
    !! Resultants (nx .. mxy, lamina frame at the centre) of the free thermal
    !! strain of an element with nnode nodes (8: S8R, S8; 6: S6), to be taken
    !! off those of the solution; nodal(2, nnode): the nodes' remainders of
    !! both (a temperature varying over the element), taken at the centre
    !! ξ = η = 0 (serendipity: -1/4 of each corner, 1/2 of each mid-side
    !! node; S6 at its centroid: -1/9 and 4/9).
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain, curvature
    real(wp), intent(out) :: res(6)
    integer, intent(in) :: nnode
    real(wp), intent(in), optional :: nodal(:, :)
    real(wp), parameter :: CENTRE(NN8) = [-0.25_wp, -0.25_wp, -0.25_wp, -0.25_wp, 0.5_wp, 0.5_wp, 0.5_wp, 0.5_wp]
    real(wp), parameter :: CENTROID(NN6) = [-1.0_wp, -1.0_wp, -1.0_wp, 4.0_wp, 4.0_wp, 4.0_wp]/9
    real(wp) :: c(nnode)
    if (present(nodal)) then
       if (nnode == NN6) then
          c = CENTROID
       else
          c = CENTRE
       end if
       call shell8_thermal_resultants(shell8_props(sec, mat), strain + dot_product(c, nodal(1, 1:nnode)), &
            curvature + dot_product(c, nodal(2, 1:nnode)), res, nnode)
       return
    end if
    call shell8_thermal_resultants(shell8_props(sec, mat), strain, curvature, res, nnode)
  end subroutine s8r_thermal_resultants

  pure subroutine s8r_centrif_load(x, sec, mat, dl, fe, error)
    !! Consistent nodal loads fe(48) (global axes) of the centrifugal load dl
    !! (value ω², axis through dl%point along dl%dir): f_i = ρ ω² Σ_j M_ij r_j.
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: m(size(x, 2), size(x, 2)), rn(3, size(x, 2))
    integer :: i, n
    n = size(x, 2)
    if (n /= ELEMENT_NODE_COUNT(ET_S8R) .and. n /= ELEMENT_NODE_COUNT(ET_S6)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodes')
       return
    end if
    call shell8_mass(x, shell8_props(sec, mat), m, error)
    if (allocated(error)) return
    do i = 1, n
       rn(:, i) = axis_distance(dl, x(:, i))
    end do
    allocate (fe(NDN*n), source=0.0_wp)
    do i = 1, n
       fe(NDN*i - 5:NDN*i - 3) = mat%density*dl%value*matmul(rn, m(:, i))
    end do
  end subroutine s8r_centrif_load
end module superjoin_elements_shell8_loads
