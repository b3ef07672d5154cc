module superjoin_elements_thermal
  !! Thermal loads of line elements: a uniform temperature change ΔT of a
  !! truss or beam of axial stiffness E A and expansion coefficient α is the
  !! initial strain α ΔT; its consistent nodal loads are the pair of axial
  !! forces N_T = E A α ΔT that push the two nodes apart, and the end forces
  !! of the element are K u minus them: N = E A (ε - α ΔT), so a heated bar
  !! held at both ends is compressed by N_T. No bending (uniform through the
  !! section).
  !!
  !! Plane and shell elements: a uniform thermal strain ε0 = α ΔT in the
  !! plane of the element (plane strain: (1 + ν) α ΔT, the out-of-plane
  !! expansion being held) and, on shells, a thermal curvature κ0 = α ∂T/∂n
  !! through the thickness. Both are the strains of a displacement field the
  !! elements reproduce exactly (patch test): the free expansion
  !!   u = ε0 (x - c) in the plane,  w = -κ0 ((x-c)² + (y-c)²)/2,
  !!   θx = ∂w/∂y, θy = -∂w/∂x  (element frame, c the centroid of the nodes).
  !! So the consistent load ∫ Bᵀ D ε0 dA is K_e u_free, and the stresses
  !! D (B u - ε0) are those of u - u_free: no element needs a thermal
  !! routine of its own, and a free element heated uniformly is stress-free
  !! to round-off whatever its shape.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: section_t
  use superjoin_elements_frame, only: beam_frame
  use superjoin_model_types, only: material_t
  use superjoin_elements_shell, only: shell_frame, shell_stiffness, shell_resultants, is_plane_type, &
       is_plane_strain_type
  implicit none (type, external)
  private

  public :: thermal_axial_load, thermal_free_field, thermal_plate_load, thermal_plate_resultants

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

  pure subroutine thermal_free_field(etype, x, nu, strain, curvature, u, error)
    !! Nodal displacements u (global axes, element ordering) of the free
    !! thermal expansion of a plane or shell element with nodes x(3, n): the
    !! mid-surface strain `strain` (α ΔT; plane strain elements expand by
    !! (1 + nu) α ΔT in the plane) and, on shells, the curvature `curvature`
    !! (α ∂T/∂n: the surface at +t/2 along the normal is the longer one).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(in) :: nu, strain, curvature
    real(wp), allocatable, intent(out) :: u(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), c(3), e, dl(3), tl(3)
    integer :: n, i
    n = size(x, 2)
    if (is_plane_type(etype)) then
       e = strain
       if (is_plane_strain_type(etype)) e = (1.0_wp + nu)*strain
       c = sum(x, dim=2)/real(n, wp)
       allocate (u(2*n))
       do i = 1, n
          u(2*i - 1:2*i) = e*(x(1:2, i) - c(1:2))
       end do
       return
    end if
    call shell_frame(x, r, xl, h, error)
    if (allocated(error)) return
    allocate (u(6*n))
    do i = 1, n
       ! element frame: the rotations and the translations of the projected point
       tl = [-curvature*xl(2, i), curvature*xl(1, i), 0.0_wp]
       dl = [strain*xl(1, i), strain*xl(2, i), -0.5_wp*curvature*(xl(1, i)**2 + xl(2, i)**2)]
       ! the node is offset by h along the normal: u_p = u + θ × (-h e_z)
       dl(1) = dl(1) + h(i)*tl(2)
       dl(2) = dl(2) - h(i)*tl(1)
       u(6*i - 5:6*i - 3) = matmul(transpose(r), dl)
       u(6*i - 2:6*i) = matmul(transpose(r), tl)
    end do
  end subroutine thermal_free_field

  pure subroutine thermal_plate_load(etype, x, sec, mat, strain, curvature, fe, error, drill)
    !! Consistent nodal loads fe = K_e u_free (global axes, element ordering)
    !! of the thermal strain and curvature of a plane or shell element (see
    !! the module header and thermal_free_field); drill: the drilling edge
    !! mask of shell_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain, curvature
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp), allocatable :: ke(:, :), u(:)
    call thermal_free_field(etype, x, mat%nu, strain, curvature, u, error)
    if (allocated(error)) return
    call shell_stiffness(etype, x, sec, mat, ke, error, drill)
    if (allocated(error)) return
    fe = matmul(ke, u)
  end subroutine thermal_plate_load

  pure subroutine thermal_plate_resultants(etype, x, sec, mat, strain, curvature, res, error)
    !! The resultants (nx, ny, nxy, mx, my, mxy, element frame) of the free
    !! thermal expansion: what K_e u gives and the element does not carry, to
    !! be taken off the resultants of the solution (N = D (ε - ε0)).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain, curvature
    real(wp), intent(out) :: res(6)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: u(:)
    res = 0.0_wp
    call thermal_free_field(etype, x, mat%nu, strain, curvature, u, error)
    if (allocated(error)) return
    call shell_resultants(etype, x, sec, mat, u, res, error)
  end subroutine thermal_plate_resultants
end module superjoin_elements_thermal
