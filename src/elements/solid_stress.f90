module superjoin_elements_solid_stress
  !! Stresses and strains of the 3D solid elements (superjoin_elements_solid)
  !! at their integration points and extrapolated to their nodes, as
  !! CalculiX's .dat (points) and .frd (nodes) give them:
  !!
  !! - points in the order of the element's stiffness rule, which is
  !!   CalculiX's: hexahedra ξ fastest, then η, then ζ (2×2×2 at ±1/√3 for
  !!   C3D8 and C3D20R, 3×3×3 at -√0.6, 0, √0.6 for C3D20); C3D4 its centroid;
  !!   C3D10 four points, point k nearest corner k; C3D6 two points, ζ < 0
  !!   first; C3D15 nine, the triangle's points nearest corners 1, 2, 3 fastest,
  !!   then ζ = -√0.6, 0, √0.6; C3D8R its centre (its mean strain);
  !! - nodes: the polynomial through the points of the rule evaluated at the
  !!   nodes: trilinear through 2×2×2 points (a mid-side node gets the mean of
  !!   its two corners), linear through C3D10's four points, constant for
  !!   C3D4; C3D20's 27 points: the least-squares fit of the element's own
  !!   20-node serendipity field to the 27 values (as CalculiX's .frd: checked
  !!   against ccx 2.20 on distorted meshes, tests/solids/verify_solids.py).
  !!
  !! Tensors in global axes, Voigt order xx, yy, zz, xy, xz, yz; strains with
  !! tensor shear components (γ/2), as CalculiX prints them.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: material_t, orientation_t, ET_C3D8I, ET_C3D6, ET_C3D15, ET_C3D8R
  use superjoin_elements_quadrature, only: quad_rule_t
  use superjoin_model_material_table, only: point_thermal_strain
  use superjoin_elements_solid, only: solid_rule, point_gradients, strain_matrix, &
       solid_node_coordinates, solid_shape, spd_solve, mode_strains, WEDGE_EDGES, mean_gradients, &
       thermal_point_stress, point_elasticity
  implicit none (type, external)
  private

  public :: solid_point_tensors, solid_extrapolation, von_mises_tensor, principal_stresses, solid_thermal_energy, solid_thermal_points

contains

  pure subroutine solid_point_tensors(etype, x, mat, ue, strain, points, nodes, error, axes, eth)
    !! Stresses (strain false) or strains (strain true) of a solid element with
    !! node coordinates x(3, nnode) and DOF values ue(3 nnode): points(6, npoint)
    !! at its integration points, nodes(6, nnode) extrapolated to its nodes;
    !! global axes (axes: the material axes of the section, as solid_stiffness).
    !! eth(nnode): the nodal thermal strains α ΔT, interpolated to the points
    !! and taken off the strains there: σ = D (ε - ε_th); the strains are the
    !! total ones (ε_th included, as CalculiX prints them; solid_thermal_points
    !! gives ε_th at the points, for the mechanical ones).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:)
    type(material_t), intent(in) :: mat
    logical, intent(in) :: strain
    real(wp), allocatable, intent(out) :: points(:, :), nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    real(wp), intent(in), optional :: eth(:)
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:)
    real(wp) :: eps(6), dv, modes(6, 8), d(6, 6)
    integer :: g
    r = solid_rule(etype, .false.)
    call element_modes(etype, x, mat, ue, modes, error, axes, eth)
    if (allocated(error)) return
    allocate (points(6, size(r%w)))
    do g = 1, size(r%w)
       call point_strain(etype, x, r, g, ue, modes, n, eps, dv, error)
       if (allocated(error)) return
       if (strain) then
          points(:, g) = [eps(1:3), 0.5_wp*eps(4:6)]
       else
          d = point_elasticity(mat, n, x, axes)
          points(:, g) = matmul(d, eps)
          ! loads: a temperature change, σ = D (ε - ε_th)
          if (present(eth)) points(:, g) = points(:, g) - thermal_point_stress(mat, n, eth, d)
       end if
    end do
    nodes = matmul(points, transpose(solid_extrapolation(etype)))
  end subroutine solid_point_tensors

  pure subroutine solid_thermal_energy(etype, x, mat, ue, eth, energy, error, axes)
    !! The strain energy ∫ ½ (ε - ε_th)ᵀ D (ε - ε_th) dV of a solid element
    !! with nodal thermal strains eth(nnode), with its stiffness rule (C3D8R:
    !! its mean strain times its volume, no hourglass share; C3D8I: with its
    !! modes' strains).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:), eth(:)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: energy
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:)
    real(wp) :: eps(6), dv, modes(6, 8)
    integer :: g
    energy = 0.0_wp
    r = solid_rule(etype, .false.)
    call element_modes(etype, x, mat, ue, modes, error, axes, eth)
    if (allocated(error)) return
    do g = 1, size(r%w)
       call point_strain(etype, x, r, g, ue, modes, n, eps, dv, error)
       if (allocated(error)) return
       eps(1:3) = eps(1:3) - point_thermal_strain(mat, n, eth)
       energy = energy + 0.5_wp*dot_product(eps, matmul(point_elasticity(mat, n, x, axes), eps))*dv
    end do
  end subroutine solid_thermal_energy

  pure subroutine solid_thermal_points(etype, x, mat, eth, e, error)
    !! The thermal strains e(npoint) at the stiffness points of a solid with
    !! nodal thermal strains eth(nnode) (C3D8R: at its centre).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), eth(:)
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: e(:)
    type(error_t), allocatable, intent(out) :: error
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:)
    real(wp) :: eps(6), dv, modes(6, 8)
    integer :: g
    r = solid_rule(etype, .false.)
    modes = 0.0_wp
    allocate (e(size(r%w)), source=0.0_wp)
    do g = 1, size(r%w)
       call point_strain(etype, x, r, g, spread(0.0_wp, 1, 3*size(x, 2)), modes, n, eps, dv, error)
       if (allocated(error)) return
       e(g) = point_thermal_strain(mat, n, eth)
    end do
  end subroutine solid_thermal_points

  pure subroutine element_modes(etype, x, mat, ue, modes, error, axes, eth)
    !! The condensed incompatible modes' strains modes(6, 8) of a C3D8I at its points (0 for other types).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: modes(6, 8)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    real(wp), intent(in), optional :: eth(:)
    modes = 0.0_wp
    if (etype == ET_C3D8I) call mode_strains(x, mat, ue, modes, error, axes, eth)
  end subroutine element_modes

  pure subroutine point_strain(etype, x, r, g, ue, modes, n, eps, dv, error)
    !! The strain eps (engineering shears) at point g of rule r, its shape
    !! functions n and volume dv (C3D8R: its mean strain at the centre, its volume).
    integer, intent(in) :: etype, g
    real(wp), intent(in) :: x(:, :), ue(:), modes(6, 8)
    type(quad_rule_t), intent(in) :: r
    real(wp), allocatable, intent(out) :: n(:)
    real(wp), intent(out) :: eps(6), dv
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: dx(:, :)
    real(wp) :: detj
    if (etype == ET_C3D8R) then      ! its mean strain, at the centre
       call mean_gradients(x, dx, detj, error)
       n = spread(1.0_wp/size(x, 2), 1, size(x, 2))
       dv = detj
    else
       call point_gradients(etype, x, r%xi(:, g), n, dx, detj, error)
       dv = detj*r%w(g)
    end if
    eps = 0.0_wp
    if (allocated(error)) return
    eps = matmul(strain_matrix(dx), ue)
    if (etype == ET_C3D8I) eps = eps + modes(:, g)
  end subroutine point_strain

  pure function solid_extrapolation(etype) result(e)
    !! e(nnode, npoint): the nodal values of the field through (or fitted to,
    !! 27 points) the values at the integration points of the stiffness rule.
    integer, intent(in) :: etype
    real(wp), allocatable :: e(:, :)
    type(quad_rule_t) :: r
    real(wp), allocatable :: c(:, :)
    real(wp) :: q, l0, l1
    integer :: a, g
    r = solid_rule(etype, .false.)
    if (size(r%w) == 27) then
       e = least_squares_fit(etype, r)
       return
    end if
    if (etype == ET_C3D6 .or. etype == ET_C3D15) then
       e = wedge_extrapolation(etype, r)
       return
    end if
    allocate (c, source=solid_node_coordinates(etype))
    allocate (e(size(c, 2), size(r%w)))
    do g = 1, size(r%w)
       do a = 1, size(c, 2)
          select case (size(r%w))
          case (1)
             e(a, g) = 1.0_wp
          case (4)         ! linear through the points: volume coordinate of corner g
             l0 = minval(r%xi(:, 1))
             l1 = 1.0_wp - 3.0_wp*l0
             q = 1.0_wp - sum(c(:, a))
             if (g > 1) q = c(g - 1, a)
             e(a, g) = (q - l0)/(l1 - l0)
          case default     ! trilinear through (±1/√3)³
             q = abs(r%xi(1, g))
             e(a, g) = product(0.5_wp*(1.0_wp + r%xi(:, g)*c(:, a)/q**2))
          end select
       end do
    end do
  end function solid_extrapolation

  pure function wedge_extrapolation(etype, r) result(e)
    !! e(nnode, npoint) of the wedges: the product of the Lagrange polynomials
    !! in ζ through the layers of points and (C3D15) the linear ones in the
    !! triangle through its three points (volume coordinate of the point's
    !! corner, 2/3 at it and 1/6 at the others), at the corners; C3D15's
    !! mid-side nodes take the mean of the two corners of their edge.
    integer, intent(in) :: etype
    type(quad_rule_t), intent(in) :: r
    real(wp), allocatable :: e(:, :)
    real(wp), allocatable :: c(:, :)
    real(wp) :: zc, tri
    integer :: a, g, k, nz
    allocate (c, source=solid_node_coordinates(etype))
    allocate (e(size(c, 2), size(r%w)))
    nz = merge(2, 3, etype == ET_C3D6)
    do g = 1, size(r%w)
       k = (g - 1)/(size(r%w)/nz) + 1                  ! the point's layer in ζ
       do a = 1, 6
          zc = c(3, a)
          e(a, g) = lagrange(r%xi(3, ::size(r%w)/nz), k, zc)
          if (etype == ET_C3D6) cycle
          tri = 1.0_wp - c(1, a) - c(2, a)                ! volume coordinate of corner 1
          if (mod(g - 1, 3) > 0) tri = c(mod(g - 1, 3), a)
          e(a, g) = e(a, g)*(tri - 1.0_wp/6.0_wp)*2.0_wp
       end do
       do a = 7, size(c, 2)
          e(a, g) = 0.5_wp*(e(WEDGE_EDGES(1, a - 6), g) + e(WEDGE_EDGES(2, a - 6), g))
       end do
    end do
  end function wedge_extrapolation

  pure real(wp) function lagrange(z, k, x) result(v)
    !! The Lagrange polynomial through the abscissae z that is 1 at z(k), at x.
    real(wp), intent(in) :: z(:), x
    integer, intent(in) :: k
    integer :: j
    v = 1.0_wp
    do j = 1, size(z)
       if (j /= k) v = v*(x - z(j))/(z(k) - z(j))
    end do
  end function lagrange

  pure function least_squares_fit(etype, r) result(e)
    !! e(nnode, npoint) = (Nᵀ N)⁻¹ Nᵀ, N(npoint, nnode) the shape functions at
    !! the points of rule r: the nodal values whose field fits the point values
    !! best (Nᵀ N is symmetric positive definite).
    integer, intent(in) :: etype
    type(quad_rule_t), intent(in) :: r
    real(wp), allocatable :: e(:, :)
    real(wp), allocatable :: n(:), dn(:, :), nm(:, :)
    integer :: g
    do g = 1, size(r%w)
       call solid_shape(etype, r%xi(:, g), n, dn)
       if (g == 1) allocate (nm(size(r%w), size(n)))
       nm(g, :) = n
    end do
    e = spd_solve(matmul(transpose(nm), nm), transpose(nm))
  end function least_squares_fit

  pure real(wp) function von_mises_tensor(s) result(vm)
    !! Von Mises stress of a tensor s (Voigt order, tensor shears), scaled so
    !! that the squares cannot overflow.
    real(wp), intent(in) :: s(6)
    real(wp) :: a(6), sc
    vm = 0.0_wp
    sc = maxval(abs(s))
    if (sc == 0.0_wp) return
    a = s/sc
    vm = sc*sqrt(max(0.0_wp, 0.5_wp*((a(1) - a(2))**2 + (a(2) - a(3))**2 + (a(3) - a(1))**2) &
         + 3.0_wp*sum(a(4:6)**2)))
  end function von_mises_tensor

  pure function principal_stresses(s) result(p)
    !! The principal values p(3) of a symmetric tensor s (Voigt order, tensor
    !! shears), largest first: cyclic Jacobi rotations of the scaled tensor,
    !! accurate to the round-off of its largest component for every value,
    !! repeated ones included (the cubic's trigonometric solution loses half
    !! the digits there: a uniaxial stress's two zeros came out as ±4e-9 of it).
    real(wp), intent(in) :: s(6)
    real(wp) :: p(3), a(3, 3), g(3, 3), sc, theta, t, c, sn, off
    integer :: sweep, k, i, j
    integer, parameter :: PAIRS(2, 3) = reshape([1, 2, 1, 3, 2, 3], [2, 3])
    integer, parameter :: MAX_SWEEPS = 30
      !! Jacobi converges quadratically: a handful of sweeps reach round-off
    real(wp), parameter :: OFF_TOL = (0.01_wp*epsilon(1.0_wp))**2
      !! off-diagonal sum of squares, relative to the scaled tensor's, left as converged
    p = 0.0_wp
    sc = maxval(abs(s))
    if (sc == 0.0_wp) return
    a = reshape([s(1), s(4), s(5), s(4), s(2), s(6), s(5), s(6), s(3)], [3, 3])/sc
    do sweep = 1, MAX_SWEEPS
       off = a(1, 2)**2 + a(1, 3)**2 + a(2, 3)**2
       if (off <= OFF_TOL*(sum([(a(k, k)**2, k = 1, 3)]) + 2.0_wp*off)) exit
       do k = 1, 3
          i = PAIRS(1, k)
          j = PAIRS(2, k)
          if (a(i, j) == 0.0_wp) cycle
          theta = (a(j, j) - a(i, i))/(2.0_wp*a(i, j))
          t = sign(1.0_wp, theta)/(abs(theta) + sqrt(theta**2 + 1.0_wp))
          c = 1.0_wp/sqrt(t**2 + 1.0_wp)
          sn = t*c
          g = 0.0_wp
          g(1, 1) = 1.0_wp
          g(2, 2) = 1.0_wp
          g(3, 3) = 1.0_wp
          g(i, i) = c
          g(j, j) = c
          g(i, j) = sn
          g(j, i) = -sn
          a = matmul(transpose(g), matmul(a, g))
          a(i, j) = 0.0_wp
          a(j, i) = 0.0_wp
       end do
    end do
    p = sc*[(a(k, k), k = 1, 3)]
    p = [maxval(p), p(1) + p(2) + p(3) - maxval(p) - minval(p), minval(p)]
  end function principal_stresses
end module superjoin_elements_solid_stress
