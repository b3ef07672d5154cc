module superjoin_elements_axisym
  !! Axisymmetric solids CAX3, CAX4, CAX6, CAX8, CAX8R (Abaqus's and CalculiX's
  !! conventions): the section lies in the x-y plane, r = x (coordinate 1, r >= 0),
  !! the axis of revolution is y (coordinate 2); each node carries u_r (DOF 1)
  !! and u_z (DOF 2). Strains ε_r = ∂u_r/∂r, ε_z = ∂u_z/∂z, the hoop strain
  !! ε_θ = u_r/r, γ_rz = ∂u_r/∂z + ∂u_z/∂r; isotropic elasticity.
  !!
  !! Everything is for the whole circumference (360°), as CalculiX's and
  !! Abaqus's axisymmetric elements: K = 2π ∫ Bᵀ D B r dA, so a *CLOAD is the
  !! total force around the circle through the node, and reactions are totals
  !! around the circumference too (CalculiX's manual, "Forces ... have to be
  !! defined for the complete circumference"); distributed loads are per unit
  !! area or volume as usual.
  !!
  !! Integration (the stiffness rule, whose points are the stress points):
  !! CAX3 its centroid; CAX4 (plain bilinear, no incompatible modes: Abaqus's
  !! CAX4) and CAX8R 2×2 Gauss, points counter-clockwise from (-,-); CAX8 3×3
  !! Gauss, ξ fastest; CAX6 three points, point k nearest corner k. Loads (GRAV,
  !! CENTRIF) use 3×3 Gauss on quadrilaterals and Dunavant's 7-point rule on
  !! triangles. Stresses: Voigt order xx = σ_r, yy = σ_z, zz = σ_θ (the hoop
  !! stress, as CalculiX and Abaqus print it), xy = τ_rz, xz = yz = 0.
  !!
  !! Thermal strains: α ΔT at the nodes, interpolated to the stiffness points
  !! with the shape functions, ε_th = (Σ N_a α ΔT_a)(1, 1, 1, 0) in (r, z, θ,
  !! rz); the consistent load 2π ∫ Bᵀ D ε_th r dA with the stiffness rule and
  !! the stresses D (ε - ε_th) there, so a uniform ΔT on a free body is its
  !! free expansion u_r = α ΔT r, u_z = α ΔT z (which every element holds
  !! exactly) without stress, to round-off.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: material_t, ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R
  use superjoin_elements_quadratic, only: quadratic_shape
  use superjoin_model_material_table, only: point_thermal_strain
  use superjoin_elements_solid, only: spd_solve
  use superjoin_elements_quadrature, only: quad_rule_t, gauss_square, triangle_rule, TRI_CENTROID, TRI_THREE, &
       TRI_DUNAVANT5
  implicit none (type, external)
  private

  public :: is_axisym_type, axisym_stiffness, axisym_forces, axisym_body_load, axisym_point_tensors
  public :: axisym_thermal_load, axisym_thermal_energy
  public :: ccx_wedge_tensor

  integer, parameter, public :: CCX_AXIAL_SEGMENTS = 180
    !! CalculiX expands an axisymmetric model into a 2° wedge of bricks (360°/180):
    !! its .dat prints the nodal forces of the wedge, the totals divided by 180.

  real(wp), parameter :: TWO_PI = 8.0_wp*atan(1.0_wp)
  real(wp), parameter :: G2 = 1.0_wp/sqrt(3.0_wp)


  type :: axi_point_t
    !! One integration point of an element: shape functions, B, r, weight 2π r |J| w.
     real(wp), allocatable :: n(:)
     real(wp), allocatable :: b(:, :)    !! (4, 2 nnode): ε_r, ε_z, ε_θ, γ_rz
     real(wp) :: r = 0.0_wp
     real(wp) :: dv = 0.0_wp
  end type axi_point_t

contains

  elemental logical function is_axisym_type(etype)
    !! etype is one of the axisymmetric types CAX3, CAX4, CAX6, CAX8, CAX8R.
    integer, intent(in) :: etype
    is_axisym_type = any(etype == [ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R])
  end function is_axisym_type

  pure subroutine axi_shape(n, p, nf, dn)
    !! Shape functions nf(n) and natural derivatives dn(2, n) at p = (ξ, η):
    !! the 3-node triangle (area coordinates 1 - ξ - η, ξ, η), the bilinear
    !! quadrilateral, and the 6- and 8-node elements of superjoin_elements_quadratic.
    integer, intent(in) :: n
    real(wp), intent(in) :: p(2)
    real(wp), intent(out) :: nf(n), dn(2, n)
    real(wp), parameter :: SX(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], SY(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    select case (n)
    case (3)
       nf = [1.0_wp - p(1) - p(2), p(1), p(2)]
       dn = reshape([-1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 3])
    case (4)
       nf = 0.25_wp*(1.0_wp + SX*p(1))*(1.0_wp + SY*p(2))
       dn(1, :) = 0.25_wp*SX*(1.0_wp + SY*p(2))
       dn(2, :) = 0.25_wp*SY*(1.0_wp + SX*p(1))
    case default
       call quadratic_shape(n, p, nf, dn)
    end select
  end subroutine axi_shape

  pure function axi_rule(etype, for_load) result(r)
    !! The stiffness rule of etype (module header), or (for_load) the load rule.
    integer, intent(in) :: etype
    logical, intent(in) :: for_load
    type(quad_rule_t) :: r
    logical :: tri
    tri = etype == ET_CAX3 .or. etype == ET_CAX6
    if (for_load .and. tri) then
       r = triangle_rule(TRI_DUNAVANT5)
    else if (for_load .or. etype == ET_CAX8) then
       r = gauss_square(3)
    else if (etype == ET_CAX3) then
       r = triangle_rule(TRI_CENTROID)
    else if (etype == ET_CAX6) then
       r = triangle_rule(TRI_THREE)
    else
       r%xi = reshape([-G2, -G2, G2, -G2, G2, G2, -G2, G2], [2, 4])   ! counter-clockwise
       r%w = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]
    end if
  end function axi_rule


  pure subroutine check_section(x, error)
    !! The nodes lie in the x-y plane (z = 0) at r = x >= 0.
    real(wp), intent(in) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    if (any(x(1, :) < 0.0_wp)) then
       call fatal_error(error, EXIT_DECK, 'axisymmetric element with a node at negative radius (x < 0; r = x, axis = y)')
    else if (any(x(3, :) /= 0.0_wp)) then
       call fatal_error(error, EXIT_DECK, 'axisymmetric element out of the x-y plane (z must be 0)')
    end if
  end subroutine check_section

  pure subroutine axi_points(x, rl, pts, error)
    !! Shape functions, B and volume weights 2π r |det J| w at the points of rule rl.
    !! Errors: a node off the half plane x >= 0, z = 0; a zero or sign-changing
    !! Jacobian (distorted element); a point on the axis (r = 0).
    real(wp), intent(in) :: x(:, :)
    type(quad_rule_t), intent(in) :: rl
    type(axi_point_t), allocatable, intent(out) :: pts(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: dn(2, size(x, 2)), jac(2, 2), inv(2, 2), dx(2, size(x, 2)), detj, sgn
    integer :: g, nn, a
    call check_section(x, error)
    if (allocated(error)) return
    nn = size(x, 2)
    allocate (pts(size(rl%w)))
    sgn = 0.0_wp
    do g = 1, size(rl%w)
       allocate (pts(g)%n(nn), pts(g)%b(4, 2*nn))
       call axi_shape(nn, rl%xi(:, g), pts(g)%n, dn)
       jac = matmul(dn, transpose(x(1:2, :)))          ! jac(i, j) = ∂x_j/∂ξ_i
       detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
       if (g == 1) sgn = sign(1.0_wp, detj)
       if (detj*sgn <= 0.0_wp) then
          call fatal_error(error, EXIT_DECK, 'axisymmetric element with a zero or negative Jacobian (distorted)')
          return
       end if
       inv = reshape([jac(2, 2), -jac(2, 1), -jac(1, 2), jac(1, 1)], [2, 2])/detj
       dx = matmul(inv, dn)                             ! dx(1, a) = ∂N_a/∂r, dx(2, a) = ∂N_a/∂z
       pts(g)%r = dot_product(pts(g)%n, x(1, :))
       if (pts(g)%r <= 0.0_wp) then
          call fatal_error(error, EXIT_DECK, 'axisymmetric element with an integration point on the axis (r = 0)')
          return
       end if
       pts(g)%dv = TWO_PI*pts(g)%r*abs(detj)*rl%w(g)
       pts(g)%b = 0.0_wp
       do a = 1, nn
          pts(g)%b(:, 2*a - 1) = [dx(1, a), 0.0_wp, pts(g)%n(a)/pts(g)%r, dx(2, a)]
          pts(g)%b(:, 2*a) = [0.0_wp, dx(2, a), 0.0_wp, dx(1, a)]
       end do
    end do
  end subroutine axi_points

  pure function axi_elasticity(mat) result(d)
    !! Isotropic D for (ε_r, ε_z, ε_θ, γ_rz).
    type(material_t), intent(in) :: mat
    real(wp) :: d(4, 4), c
    c = mat%e/((1.0_wp + mat%nu)*(1.0_wp - 2.0_wp*mat%nu))
    d = 0.0_wp
    d(1:3, 1:3) = c*mat%nu
    d(1, 1) = c*(1.0_wp - mat%nu)
    d(2, 2) = d(1, 1)
    d(3, 3) = d(1, 1)
    d(4, 4) = 0.5_wp*mat%e/(1.0_wp + mat%nu)
  end function axi_elasticity

  pure subroutine axisym_stiffness(etype, x, mat, ke, error)
    !! K = 2π ∫ Bᵀ D B r dA (whole circumference), node-major (u_r, u_z) per node.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(axi_point_t), allocatable :: pts(:)
    real(wp) :: d(4, 4)
    integer :: g
    if (mat%e <= 0.0_wp .or. mat%nu >= 0.5_wp .or. mat%nu <= -1.0_wp) then
       call fatal_error(error, EXIT_DECK, 'axisymmetric element needs E > 0 and -1 < nu < 0.5')
       return
    end if
    call axi_points(x, axi_rule(etype, .false.), pts, error)
    if (allocated(error)) return
    d = axi_elasticity(mat)
    allocate (ke(2*size(x, 2), 2*size(x, 2)), source=0.0_wp)
    do g = 1, size(pts)
       ke = ke + pts(g)%dv*matmul(transpose(pts(g)%b), matmul(d, pts(g)%b))
    end do
  end subroutine axisym_stiffness

  pure subroutine axisym_forces(etype, x, mat, ue, fg, error)
    !! fg(:, step) = K_e ue(:, step) of every step with one element matrix.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:, :)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: fg(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ke(:, :)
    call axisym_stiffness(etype, x, mat, ke, error)
    if (allocated(error)) return
    fg = matmul(ke, ue)
  end subroutine axisym_forces

  pure subroutine axisym_body_load(etype, x, force, radial, fe, error)
    !! Consistent nodal loads 2π ∫ N b r dA of the body force per unit volume
    !! b = force(1:2) + radial r (radial: ρ ω² of a spin about the y axis along r).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), force(2), radial
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    type(axi_point_t), allocatable :: pts(:)
    integer :: g, a
    call axi_points(x, axi_rule(etype, .true.), pts, error)
    if (allocated(error)) return
    allocate (fe(2*size(x, 2)), source=0.0_wp)
    do g = 1, size(pts)
       do a = 1, size(x, 2)
          fe(2*a - 1) = fe(2*a - 1) + pts(g)%dv*pts(g)%n(a)*(force(1) + radial*pts(g)%r)
          fe(2*a) = fe(2*a) + pts(g)%dv*pts(g)%n(a)*force(2)
       end do
    end do
  end subroutine axisym_body_load

  pure subroutine axisym_thermal_load(etype, x, mat, eth, fe, error)
    !! Consistent nodal loads fe(2 nnode) = 2π ∫ Bᵀ D ε_th r dA of the nodal
    !! thermal strains eth(nnode) (α ΔT), interpolated to the stiffness points.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), eth(:)
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    type(axi_point_t), allocatable :: pts(:)
    integer :: g
    call axi_points(x, axi_rule(etype, .false.), pts, error)
    if (allocated(error)) return
    allocate (fe(2*size(x, 2)), source=0.0_wp)
    do g = 1, size(pts)
       fe = fe + pts(g)%dv*matmul(axi_thermal_stress(mat, pts(g)%n, eth), pts(g)%b)
    end do
  end subroutine axisym_thermal_load

  pure function axi_thermal_stress(mat, n, eth) result(s0)
    !! D ε_th of the thermal strain (Σ N_a eth_a)(1, 1, 1, 0) at a point with
    !! shape functions n (a table of α: the secant strain there, point_thermal_strain).
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: n(:), eth(:)
    real(wp) :: s0(4), d(4, 4)
    d = axi_elasticity(mat)
    s0 = point_thermal_strain(mat, n, eth)*(d(:, 1) + d(:, 2) + d(:, 3))
  end function axi_thermal_stress

  pure subroutine axisym_point_tensors(etype, x, mat, ue, strain, points, nodes, error, eth, mechanical)
    !! Stresses (or, strain, strains with tensor shear γ_rz/2) at the stiffness
    !! points, points(6, npoint), and extrapolated to the nodes, nodes(6, nnode):
    !! Voigt xx = r, yy = z, zz = θ (hoop), xy = rz, xz = yz = 0. eth(nnode):
    !! the nodal thermal strains α ΔT, taken off the strains at the points:
    !! σ = D (ε - ε_th); the strains are the total ones (as CalculiX prints
    !! them), or with mechanical ε - ε_th.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:)
    type(material_t), intent(in) :: mat
    logical, intent(in) :: strain
    real(wp), allocatable, intent(out) :: points(:, :), nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: eth(:)
    logical, intent(in), optional :: mechanical
    type(axi_point_t), allocatable :: pts(:)
    real(wp) :: eps(4), s(4)
    integer :: g
    call axi_points(x, axi_rule(etype, .false.), pts, error)
    if (allocated(error)) return
    allocate (points(6, size(pts)), source=0.0_wp)
    do g = 1, size(pts)
       eps = matmul(pts(g)%b, ue)
       if (strain) then
          if (present(eth) .and. present(mechanical)) then
             if (mechanical) eps(1:3) = eps(1:3) - point_thermal_strain(mat, pts(g)%n, eth)
          end if
          points(1:4, g) = [eps(1:3), 0.5_wp*eps(4)]
       else
          s = matmul(axi_elasticity(mat), eps)
          ! loads: a temperature change, σ = D (ε - ε_th)
          if (present(eth)) s = s - axi_thermal_stress(mat, pts(g)%n, eth)
          points(1:4, g) = s
       end if
    end do
    nodes = matmul(points, transpose(axi_extrapolation(etype, size(x, 2))))
  end subroutine axisym_point_tensors

  pure subroutine axisym_thermal_energy(etype, x, mat, ue, eth, energy, error)
    !! The strain energy 2π ∫ ½ (ε - ε_th)ᵀ D (ε - ε_th) r dA of the whole
    !! ring with nodal thermal strains eth(nnode), with the stiffness rule.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:), eth(:)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: energy
    type(error_t), allocatable, intent(out) :: error
    type(axi_point_t), allocatable :: pts(:)
    real(wp) :: eps(4)
    integer :: g
    energy = 0.0_wp
    call axi_points(x, axi_rule(etype, .false.), pts, error)
    if (allocated(error)) return
    do g = 1, size(pts)
       eps = matmul(pts(g)%b, ue)
       eps(1:3) = eps(1:3) - point_thermal_strain(mat, pts(g)%n, eth)
       energy = energy + 0.5_wp*dot_product(eps, matmul(axi_elasticity(mat), eps))*pts(g)%dv
    end do
  end subroutine axisym_thermal_energy

  pure function axi_extrapolation(etype, nn) result(e)
    !! e(nnode, npoint): nodal values from the point values. One point: its
    !! value; 2×2 points: the bilinear field through them at the corners; the
    !! triangle's three points: the linear field through them; CAX8's 3×3: the
    !! least-squares fit of its 8-node field. Mid-side nodes of the linear
    !! fits: the mean of their corners.
    integer, intent(in) :: etype, nn
    real(wp), allocatable :: e(:, :)
    type(quad_rule_t) :: r
    real(wp), parameter :: SX(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], SY(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    real(wp) :: nf(8), dn(2, 8), nm(9, 8)
    integer :: a, g, nc
    r = axi_rule(etype, .false.)
    allocate (e(nn, size(r%w)), source=0.0_wp)
    nc = nn
    select case (etype)
    case (ET_CAX3)
       e = 1.0_wp
       return
    case (ET_CAX6)
       nc = 3
       do a = 1, 3
          e(a, :) = -1.0_wp/3.0_wp
          e(a, a) = 5.0_wp/3.0_wp
       end do
    case (ET_CAX8)
       do g = 1, 9
          call axi_shape(8, r%xi(:, g), nf, dn)
          nm(g, :) = nf
       end do
       e = spd_solve(matmul(transpose(nm), nm), transpose(nm))
       return
    case default
       nc = 4
       do a = 1, 4
          do g = 1, 4
             e(a, g) = 0.25_wp*(1.0_wp + 3.0_wp*SX(a)*r%xi(1, g))*(1.0_wp + 3.0_wp*SY(a)*r%xi(2, g))
          end do
       end do
    end select
    do a = nc + 1, nn
       e(a, :) = 0.5_wp*(e(a - nc, :) + e(modulo(a - nc, nc) + 1, :))
    end do
  end function axi_extrapolation

  pure function ccx_wedge_tensor(s, zeta, linear) result(t)
    !! The tensor s (Voigt; xx = r, yy = z, zz = θ, xy = rz) in the global axes
    !! of CalculiX's 2° wedge at the height zeta in [-1, 1] of its brick: the
    !! point lies at φ = zeta × 1° about the y axis, e_r = (cos φ, 0, sin φ),
    !! e_θ = (-sin φ, 0, cos φ). linear: the brick of a CAX3 or CAX4 (C3D6, C3D8)
    !! has two layers of nodes, and its xz component is half the turned tensor's
    !! (its u_x, equal at ±1°, gives no ∂u_x/∂z; measured against ccx 2.20).
    real(wp), intent(in) :: s(6), zeta
    logical, intent(in) :: linear
    real(wp) :: t(6), c, sn
    c = cos(zeta*TWO_PI/360.0_wp)
    sn = sin(zeta*TWO_PI/360.0_wp)
    t = [s(1)*c*c + s(3)*sn*sn, s(2), s(1)*sn*sn + s(3)*c*c, s(4)*c, (s(1) - s(3))*sn*c, s(4)*sn]
    if (linear) t(5) = 0.5_wp*t(5)
  end function ccx_wedge_tensor
end module superjoin_elements_axisym
