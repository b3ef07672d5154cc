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
  !!
  !! A temperature that varies over a plane element (CPS*, CPE*) is
  !! interpolated from its nodes to the integration points with the shape
  !! functions, as CalculiX does: the element mean ε̄ is taken as above, and the
  !! nodal remainder δᵢ = α ΔTᵢ - ε̄ adds the load ∫ Bᵀ D (Σ Nᵢ δᵢ) dA
  !! (thermal_plane_nodal_load) and is taken off the strains at every point
  !! (σ = D (ε - ε̄ - Σ Nᵢ δᵢ)): in all, the consistent ∫ Bᵀ D ε0(ξ) dA. A
  !! uniform temperature has no remainder and takes the mean path alone.
  !! Shells do the same with their own parts (superjoin_elements_shell,
  !! shell_thermal_nodal_load: the membrane's and the plate's rows, the nodal
  !! remainders of α ΔT and α ∂T/∂n), S8R at its own points
  !! (superjoin_elements_shell8); B32 interpolates along its three nodes
  !! (superjoin_elements_beam3, beam3_thermal_load).
  !!
  !! Beams: a temperature gradient across the section, α ∂T/∂y and α ∂T/∂z
  !! (local axes), is the thermal curvature of the free beam: fibres at +y
  !! grow by α (∂T/∂y) y, so v'' = -α ∂T/∂y and w'' = -α ∂T/∂z, linear along
  !! the element between its nodes' values. Its free bending
  !! (thermal_beam_free_field: a cubic v, w, which the Hermite and the exact
  !! Timoshenko elements hold) has no shear, for Euler-Bernoulli and
  !! Timoshenko beams alike, and the consistent load is K_e u_free: the end
  !! moments ∓E I α ∂T (and, if the gradient varies, the shear pair of its
  !! slope); the end forces are those of u - u_free.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t
  use superjoin_elements_frame, only: beam_frame
  use superjoin_model_types, only: material_t
  use superjoin_elements_shell, only: shell_frame, shell_stiffness, shell_resultants, is_plane_type, &
       is_plane_strain_type
  use superjoin_elements_shell, only: is_quadratic_plane_type, quadratic_props
  use superjoin_elements_membrane, only: membrane_thermal_load, membrane_resultants, plane_strain_resultants, &
       membrane_centroid_weights
  use superjoin_elements_quadratic, only: quadratic_thermal_load, quadratic_resultants, quadratic_centroid_weights
  use superjoin_elements_beam, only: beam_stiffness, beam_end_forces
  use superjoin_model_types, only: ET_B23, ET_B21, ET_B33, ET_B31
  implicit none (type, external)
  private

  public :: thermal_axial_load, thermal_free_field, thermal_plate_load, thermal_plate_resultants
  public :: thermal_plane_nodal_load, plane_initial_strains, plane_centroid_remainder
  public :: thermal_beam_free_field, thermal_beam_load, thermal_beam_end_forces

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

  pure subroutine thermal_plate_resultants(etype, x, sec, mat, strain, curvature, res, error, nodal)
    !! The resultants (nx, ny, nxy, mx, my, mxy, element frame) of the free
    !! thermal expansion: what K_e u gives and the element does not carry, to
    !! be taken off the resultants of the solution (N = D (ε - ε0)). With
    !! nodal (a plane element: α ΔT at its nodes minus the mean strain), also
    !! what the remainder takes off at the centroid.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: strain, curvature
    real(wp), intent(out) :: res(6)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: nodal(:)
    real(wp), allocatable :: u(:), z(:), e0(:)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), rd(3)
    res = 0.0_wp
    call thermal_free_field(etype, x, mat%nu, strain, curvature, u, error)
    if (allocated(error)) return
    call shell_resultants(etype, x, sec, mat, u, res, error)
    if (allocated(error) .or. .not. present(nodal)) return
    if (.not. is_plane_type(etype) .or. all(nodal == 0.0_wp)) return
    ! the remainder alone (u = 0): t D (B_a α - ε0) at the centroid; res takes it off
    call shell_frame(x, r, xl, h, error)
    if (allocated(error)) return
    call plane_initial_strains(etype, mat%nu, nodal, e0)
    allocate (z(2*size(x, 2)), source=0.0_wp)
    if (is_quadratic_plane_type(etype)) then
       call quadratic_resultants(xl, quadratic_props(etype, sec, mat), z, rd, error, e0)
    else if (is_plane_strain_type(etype)) then
       call plane_strain_resultants(xl, sec%thickness, mat%e, mat%nu, z, rd, error, e0)
    else
       call membrane_resultants(xl, sec%thickness, mat%e, mat%nu, z, rd, error, e0)
    end if
    if (allocated(error)) return
    res(1:3) = res(1:3) - rd
  end subroutine thermal_plate_resultants

  pure real(wp) function plane_centroid_remainder(etype, x, nodal) result(v)
    !! The nodal remainder nodal(n) of the thermal strain of a plane element
    !! interpolated to the area centroid, where its resultants and element
    !! values are taken (0 if the element cannot be evaluated: reported elsewhere).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(in) :: nodal(:)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), w(size(x, 2))
    type(error_t), allocatable :: error
    v = 0.0_wp
    if (.not. is_plane_type(etype) .or. all(nodal == 0.0_wp)) return
    call shell_frame(x, r, xl, h, error)
    if (allocated(error)) return
    if (is_quadratic_plane_type(etype)) then
       call quadratic_centroid_weights(xl, w)
    else
       call membrane_centroid_weights(xl, w)
    end if
    v = dot_product(w, nodal)
  end function plane_centroid_remainder

  pure subroutine plane_initial_strains(etype, nu, nodal, e0)
    !! The in-plane initial strains e0 of a plane element from its nodal
    !! thermal strains α ΔT: the same (plane stress), (1 + ν) times (plane
    !! strain: the expansion across the plane is held).
    integer, intent(in) :: etype
    real(wp), intent(in) :: nu, nodal(:)
    real(wp), allocatable, intent(out) :: e0(:)
    e0 = nodal
    if (is_plane_strain_type(etype)) e0 = (1.0_wp + nu)*nodal
  end subroutine plane_initial_strains

  pure subroutine thermal_plane_nodal_load(etype, x, sec, mat, nodal, fe, error, self_energy)
    !! Consistent nodal loads fe (global axes, node-major ux, uy) ∫ Bᵀ D ε0 dA
    !! of a thermal strain interpolated from its nodal values nodal(n) (α ΔT
    !! of each node, or their remainder after the mean) on a plane element;
    !! self_energy: the constant of the element's energy of its mechanical
    !! strains, ½ uᵀ K u - uᵀ fe + self_energy (membrane_thermal_load,
    !! quadratic_thermal_load; the in-plane part of a plane strain element's).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: nodal(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(out), optional :: self_energy
    real(wp), allocatable :: fl(:), e0(:)
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2))
    integer :: i
    if (.not. is_plane_type(etype)) then
       call fatal_error(error, EXIT_DECK, 'nodal thermal strains on an element that is not a plane element')
       return
    end if
    call shell_frame(x, r, xl, h, error)
    if (allocated(error)) return
    call plane_initial_strains(etype, mat%nu, nodal, e0)
    if (is_quadratic_plane_type(etype)) then
       call quadratic_thermal_load(xl, quadratic_props(etype, sec, mat), e0, fl, error, self_energy)
    else
       call membrane_thermal_load(xl, sec%thickness, mat%e, mat%nu, is_plane_strain_type(etype), e0, fl, error, &
            self_energy)
    end if
    if (allocated(error)) return
    allocate (fe(size(fl)))
    do i = 1, size(x, 2)   ! element frame -> global: f_g = r(1:2, 1:2)ᵀ f_l
       fe(2*i - 1:2*i) = matmul(transpose(r(1:2, 1:2)), fl(2*i - 1:2*i))
    end do
  end subroutine thermal_plane_nodal_load

  pure subroutine thermal_beam_free_field(etype, x, sec, gradient, u, error)
    !! Nodal displacements u (global axes, node-major with the beam's DOFs:
    !! B23, B21 ux, uy, rz; B33, B31 all six) of the free bending of a beam
    !! under the thermal curvatures gradient(:, node) = (α ∂T/∂y, α ∂T/∂z)
    !! at its two nodes, local axes (planar beams: the first only), linear in
    !! between, node 1 held: v'' = -κy, θz = v'; w'' = -κz, θy = -w', so at
    !! node 2 v = -L² (2 κy1 + κy2)/6, θz = -L (κy1 + κy2)/2 and the same for
    !! w, -θy with κz.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: gradient(2, 2)
    real(wp), allocatable, intent(out) :: u(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), length, d(3), t(3), defl(2), turn(2)
    call beam_frame(etype, x, sec, r, length, error)
    if (allocated(error)) return
    defl = -length**2*(2*gradient(:, 1) + gradient(:, 2))/6
    turn = -length*(gradient(:, 1) + gradient(:, 2))/2
    d = [0.0_wp, defl(1), defl(2)]
    t = [0.0_wp, -turn(2), turn(1)]
    select case (etype)
    case (ET_B23, ET_B21)
       ! (ux, uy, rz) = rᵀ (u, v, θz): the planar frame has r(3, :) = Z
       u = [0.0_wp, 0.0_wp, 0.0_wp, matmul(transpose(r), [d(1), d(2), t(3)])]
    case (ET_B33, ET_B31)
       u = [spread(0.0_wp, 1, 6), matmul(transpose(r), d), matmul(transpose(r), t)]
    case default
       call fatal_error(error, EXIT_DECK, 'a temperature gradient across the section applies to beams only')
    end select
  end subroutine thermal_beam_free_field

  pure subroutine thermal_beam_load(etype, x, sec, mat, gradient, fe, error)
    !! Consistent nodal loads fe = K_e u_free (global axes, node-major) of the
    !! thermal curvatures gradient of a beam (thermal_beam_free_field): the end
    !! moments ∓E I α ∂T, no shear.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: gradient(2, 2)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: u(:), ke(:, :)
    call thermal_beam_free_field(etype, x, sec, gradient, u, error)
    if (allocated(error)) return
    call beam_stiffness(etype, x, sec, mat, ke, error)
    if (allocated(error)) return
    fe = matmul(ke, u)
  end subroutine thermal_beam_load

  pure subroutine thermal_beam_end_forces(etype, x, sec, mat, gradient, f, error)
    !! The end forces f(6, 2) (local axes, as beam_end_forces) of the free
    !! thermal bending: what K u gives and the beam does not carry, taken off
    !! its end forces (M = E I (κ - κ0)).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: gradient(2, 2)
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: u(:)
    f = 0.0_wp
    call thermal_beam_free_field(etype, x, sec, gradient, u, error)
    if (allocated(error)) return
    call beam_end_forces(etype, x, sec, mat, u, [0.0_wp, 0.0_wp, 0.0_wp], f, error)
  end subroutine thermal_beam_end_forces
end module superjoin_elements_thermal
