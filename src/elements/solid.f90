module superjoin_elements_solid
  !! Isoparametric 3D solid elements, linear elasticity (isotropic, orthotropic or
  !! anisotropic in the section's material axes: superjoin_elements_materials), DOFs 1..3
  !! per node, node numbering as Abaqus and CalculiX:
  !!
  !! - C3D8: trilinear hexahedron, full 2×2×2 Gauss rule;
  !! - C3D8I: the same with three incompatible modes 1 - ξ², 1 - η², 1 - ζ² per
  !!   displacement component (Wilson et al. 1973), their gradients taken with
  !!   the centre Jacobian J0 and scaled by det J0 / det J (Taylor, Beresford &
  !!   Wilson 1976), so that ∫ G dV = 0 and the element passes the patch test on
  !!   any shape; the nine mode amplitudes are condensed per element;
  !! - C3D8R: one point, the mean strain of Flanagan & Belytschko and the
  !!   hourglass stiffness of superjoin_elements_solid_reduced (C3D8I's, in the
  !!   hourglass modes); its consistent body loads take the 2×2×2 rule;
  !! - C3D20: serendipity hexahedron (corners 1..8, mid-side nodes 9..12 on
  !!   the edges 1-2, 2-3, 3-4, 4-1, 13..16 on 5-6, 6-7, 7-8, 8-5, 17..20 on
  !!   1-5, 2-6, 3-7, 4-8), full 3×3×3 rule; C3D20R: the same with 2×2×2;
  !! - C3D4: linear tetrahedron, one point; C3D10: quadratic tetrahedron
  !!   (mid-side nodes 5..10 on the edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4),
  !!   four-point rule (exact for its quadratic stiffness on a straight-sided
  !!   element);
  !! - C3D6: linear wedge (corners 1-2-3 at ζ = -1, 4-5-6 above them at ζ = 1),
  !!   two points (the triangle's centroid at ζ = ∓1/√3); C3D15: quadratic
  !!   wedge (mid-side nodes 7..9 on 1-2, 2-3, 3-1, 10..12 on 4-5, 5-6, 6-4,
  !!   13..15 on 1-4, 2-5, 3-6), nine points (the triangle's three points at
  !!   L = 2/3, 1/6, 1/6 times Gauss's three in ζ): CalculiX's rules (ccx 2.20,
  !!   whose .dat prints 2 and 9 points).
  !!
  !! K_e = Σ_g Bᵀ D B det J w_g (Zienkiewicz & Taylor, vol. 1, ch. 6 and 8;
  !! Hughes, ch. 3). Strain order: εxx, εyy, εzz, γxy, γxz, γyz.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: material_t, orientation_t, MAT_ISO, ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, &
       ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, ET_C3D8R
  use superjoin_elements_solid_reduced, only: hourglass_stiffness
  use superjoin_elements_quadrature, only: quad_rule_t, gauss_cube, gauss_line, triangle_rule, TRI_CENTROID, TRI_THREE
  use superjoin_elements_materials, only: elasticity, material_stiffness, spd_solve
  use superjoin_model_material_table, only: point_material, point_thermal_strain
  implicit none (type, external)
  private

  public :: is_solid_type, solid_stiffness, solid_body_load, solid_shape, solid_forces
  public :: solid_rule, point_gradients, elasticity, strain_matrix, solid_node_coordinates
  public :: spd_solve, mode_strains, mean_gradients, solid_thermal_load, thermal_point_stress, point_elasticity

  integer, parameter, public :: WEDGE_EDGES(2, 9) = reshape([1, 2, 2, 3, 3, 1, 4, 5, 5, 6, 6, 4, 1, 4, 2, 5, 3, 6], &
       [2, 9])
    !! The edges of a wedge, in the order of C3D15's mid-side nodes 7..15.


contains

  elemental logical function is_solid_type(etype)
    !! etype is one of the solid element types of this module.
    integer, intent(in) :: etype
    is_solid_type = any(etype == [ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, &
         ET_C3D8R])
  end function is_solid_type

  pure subroutine solid_shape(etype, xi, n, dn)
    !! Shape functions n(nnode) and their derivatives dn(3, nnode) with
    !! respect to the natural coordinates xi(3) (hexahedra: -1..1 each;
    !! tetrahedra: volume coordinates L2 = ξ, L3 = η, L4 = ζ, L1 = 1 - ξ - η - ζ;
    !! wedges: the triangle's L2 = ξ, L3 = η, L1 = 1 - ξ - η, and ζ -1..1).
    integer, intent(in) :: etype
    real(wp), intent(in) :: xi(3)
    real(wp), allocatable, intent(out) :: n(:), dn(:, :)
    select case (etype)
    case (ET_C3D8, ET_C3D8I, ET_C3D8R)
       call hex8(xi, n, dn)
    case (ET_C3D20, ET_C3D20R)
       call hex20(xi, n, dn)
    case (ET_C3D4)
       allocate (n(4), dn(3, 4))
       n = [1.0_wp - sum(xi), xi(1), xi(2), xi(3)]
       dn = reshape([-1.0_wp, -1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, &
            0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 4])
    case (ET_C3D6, ET_C3D15)
       call wedge(etype == ET_C3D15, xi, n, dn)
    case default
       call tet10(xi, n, dn)
    end select
  end subroutine solid_shape

  pure subroutine hex8(xi, n, dn)
    !! Trilinear hexahedron: N_a = (1 + ξ ξa)(1 + η ηa)(1 + ζ ζa)/8.
    real(wp), intent(in) :: xi(3)
    real(wp), allocatable, intent(out) :: n(:), dn(:, :)
    real(wp) :: c(3, 8), f(3)
    integer :: a, d
    c = hex_corners()
    allocate (n(8), dn(3, 8))
    do a = 1, 8
       f = 1.0_wp + c(:, a)*xi
       n(a) = product(f)/8.0_wp
       do d = 1, 3
          dn(d, a) = c(d, a)*product(f, mask=[1, 2, 3] /= d)/8.0_wp
       end do
    end do
  end subroutine hex8

  pure subroutine hex20(xi, n, dn)
    !! Serendipity hexahedron: corners N = (1+ξξa)(1+ηηa)(1+ζζa)(ξξa+ηηa+ζζa-2)/8;
    !! a mid-side node with ξa = 0: N = (1-ξ²)(1+ηηa)(1+ζζa)/4 (likewise η, ζ).
    real(wp), intent(in) :: xi(3)
    real(wp), allocatable, intent(out) :: n(:), dn(:, :)
    real(wp) :: c(3, 20), f(3), s
    integer :: a, d, k
    c = hex20_nodes()
    allocate (n(20), dn(3, 20))
    do a = 1, 8
       f = 1.0_wp + c(:, a)*xi
       s = sum(c(:, a)*xi) - 2.0_wp
       n(a) = product(f)*s/8.0_wp
       do d = 1, 3
          dn(d, a) = c(d, a)*product(f, mask=[1, 2, 3] /= d)*(s + f(d))/8.0_wp
       end do
    end do
    do a = 9, 20
       k = minloc(abs(c(:, a)), 1)          ! the direction along the node's edge
       f = 1.0_wp + c(:, a)*xi
       f(k) = 1.0_wp - xi(k)**2
       n(a) = product(f)/4.0_wp
       do d = 1, 3
          if (d == k) then
             dn(d, a) = -2.0_wp*xi(k)*product(f, mask=[1, 2, 3] /= d)/4.0_wp
          else
             dn(d, a) = c(d, a)*product(f, mask=[1, 2, 3] /= d)/4.0_wp
          end if
       end do
    end do
  end subroutine hex20

  pure subroutine tet10(xi, n, dn)
    !! Quadratic tetrahedron: corners L(2L - 1), mid-side nodes 4 Li Lj.
    real(wp), intent(in) :: xi(3)
    real(wp), allocatable, intent(out) :: n(:), dn(:, :)
    integer, parameter :: EDGE(2, 6) = reshape([1, 2, 2, 3, 3, 1, 1, 4, 2, 4, 3, 4], [2, 6])
    real(wp) :: l(4), dl(3, 4)
    integer :: a, i, j
    l = [1.0_wp - sum(xi), xi(1), xi(2), xi(3)]
    dl = reshape([-1.0_wp, -1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, &
         0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 4])
    allocate (n(10), dn(3, 10))
    do a = 1, 4
       n(a) = l(a)*(2.0_wp*l(a) - 1.0_wp)
       dn(:, a) = (4.0_wp*l(a) - 1.0_wp)*dl(:, a)
    end do
    do a = 1, 6
       i = EDGE(1, a)
       j = EDGE(2, a)
       n(4 + a) = 4.0_wp*l(i)*l(j)
       dn(:, 4 + a) = 4.0_wp*(l(i)*dl(:, j) + l(j)*dl(:, i))
    end do
  end subroutine tet10

  pure subroutine wedge(quadratic, xi, n, dn)
    !! Wedges: C3D6 N_a = L_a (1 + ζ ζa)/2; C3D15 corners
    !! N_a = L_a (1 + ζ ζa)(2 L_a + ζ ζa - 2)/2, mid-side nodes of the triangles
    !! 2 L_a L_b (1 + ζ ζc), of the vertical edges L_a (1 - ζ²).
    logical, intent(in) :: quadratic
    real(wp), intent(in) :: xi(3)
    real(wp), allocatable, intent(out) :: n(:), dn(:, :)
    integer, parameter :: TRI(2, 3) = reshape([1, 2, 2, 3, 3, 1], [2, 3])
    real(wp) :: l(3), dl(3, 3), z, s, f
    integer :: a, k, i, j
    l = [1.0_wp - xi(1) - xi(2), xi(1), xi(2)]
    dl = reshape([-1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], [3, 3])
    allocate (n(merge(15, 6, quadratic)), dn(3, merge(15, 6, quadratic)))
    do a = 1, 6
       k = mod(a - 1, 3) + 1                      ! the corner's triangle vertex
       z = merge(-1.0_wp, 1.0_wp, a <= 3)         ! its ζ
       s = 1.0_wp + z*xi(3)
       if (.not. quadratic) then
          n(a) = 0.5_wp*l(k)*s
          dn(:, a) = 0.5_wp*s*dl(:, k)
          dn(3, a) = 0.5_wp*l(k)*z
          cycle
       end if
       f = 2.0_wp*l(k) + z*xi(3) - 2.0_wp
       n(a) = 0.5_wp*l(k)*s*f
       dn(:, a) = 0.5_wp*s*(f + 2.0_wp*l(k))*dl(:, k)
       dn(3, a) = 0.5_wp*l(k)*z*(f + s)
    end do
    if (.not. quadratic) return
    do a = 1, 6
       i = TRI(1, mod(a - 1, 3) + 1)
       j = TRI(2, mod(a - 1, 3) + 1)
       z = merge(-1.0_wp, 1.0_wp, a <= 3)
       s = 1.0_wp + z*xi(3)
       n(6 + a) = 2.0_wp*l(i)*l(j)*s
       dn(:, 6 + a) = 2.0_wp*s*(l(i)*dl(:, j) + l(j)*dl(:, i))
       dn(3, 6 + a) = 2.0_wp*l(i)*l(j)*z
    end do
    do k = 1, 3
       n(12 + k) = l(k)*(1.0_wp - xi(3)**2)
       dn(:, 12 + k) = (1.0_wp - xi(3)**2)*dl(:, k)
       dn(3, 12 + k) = -2.0_wp*l(k)*xi(3)
    end do
  end subroutine wedge

  pure function wedge_nodes(nn) result(c)
    !! Natural coordinates c(3, nn) of the nodes of a wedge with nn = 6 or 15 nodes.
    integer, intent(in) :: nn
    real(wp) :: c(3, nn)
    integer :: a
    c(:, 1:6) = reshape([0, 0, -1, 1, 0, -1, 0, 1, -1, 0, 0, 1, 1, 0, 1, 0, 1, 1]*1.0_wp, [3, 6])
    do a = 7, nn
       c(:, a) = 0.5_wp*(c(:, WEDGE_EDGES(1, a - 6)) + c(:, WEDGE_EDGES(2, a - 6)))
    end do
  end function wedge_nodes

  pure function hex_corners() result(c)
    !! Natural coordinates of the corners of a hexahedron (Abaqus order).
    real(wp) :: c(3, 8)
    c = reshape([-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, &
         -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1]*1.0_wp, [3, 8])
  end function hex_corners

  pure function hex20_nodes() result(c)
    !! Natural coordinates of the 20 nodes of a serendipity hexahedron (Abaqus order).
    real(wp) :: c(3, 20)
    c(:, 1:8) = hex_corners()
    c(:, 9:20) = reshape([0, -1, -1, 1, 0, -1, 0, 1, -1, -1, 0, -1, &
         0, -1, 1, 1, 0, 1, 0, 1, 1, -1, 0, 1, &
         -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]*1.0_wp, [3, 12])
  end function hex20_nodes

  pure function solid_node_coordinates(etype) result(c)
    !! Natural coordinates c(3, nnode) of the nodes of a solid element type
    !! (tetrahedra: ξ, η, ζ = L2, L3, L4; mid-side nodes halfway along their edges).
    integer, intent(in) :: etype
    real(wp), allocatable :: c(:, :)
    integer, parameter :: EDGE(2, 6) = reshape([1, 2, 2, 3, 3, 1, 1, 4, 2, 4, 3, 4], [2, 6])
    integer :: a
    select case (etype)
    case (ET_C3D8, ET_C3D8I, ET_C3D8R)
       c = hex_corners()
    case (ET_C3D20, ET_C3D20R)
       c = hex20_nodes()
    case (ET_C3D6)
       c = wedge_nodes(6)
    case (ET_C3D15)
       c = wedge_nodes(15)
    case default
       allocate (c(3, merge(4, 10, etype == ET_C3D4)), source=0.0_wp)
       c(:, 2:4) = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1]*1.0_wp, [3, 3])
       do a = 5, size(c, 2)
          c(:, a) = 0.5_wp*(c(:, EDGE(1, a - 4)) + c(:, EDGE(2, a - 4)))
       end do
    end select
  end function solid_node_coordinates

  pure function solid_rule(etype, for_load) result(r)
    !! The integration rule of element type etype (for_load: the full rule of
    !! the reduced C3D20R and C3D8R, for consistent body loads).
    integer, intent(in) :: etype
    logical, intent(in) :: for_load
    type(quad_rule_t) :: r
    real(wp), parameter :: A = 0.5854101966249685_wp, B = 0.1381966011250105_wp
    select case (etype)
    case (ET_C3D8, ET_C3D8I)
       r = gauss_cube(2)
    case (ET_C3D8R)
       r = gauss_cube(2)
       if (for_load) return
       r%xi = reshape([0.0_wp, 0.0_wp, 0.0_wp], [3, 1])
       r%w = [8.0_wp]
    case (ET_C3D20R)
       r = gauss_cube(merge(3, 2, for_load))
    case (ET_C3D20)
       r = gauss_cube(3)
    case (ET_C3D4)
       r%xi = reshape([0.25_wp, 0.25_wp, 0.25_wp], [3, 1])
       r%w = [1.0_wp/6.0_wp]
    case (ET_C3D6, ET_C3D15)
       r = gauss_wedge(etype == ET_C3D15)
    case default
       r%xi = reshape([B, B, B, A, B, B, B, A, B, B, B, A], [3, 4])
       r%w = spread(1.0_wp/24.0_wp, 1, 4)
    end select
  end function solid_rule


  pure function gauss_wedge(quadratic) result(r)
    !! The wedges' rules, the triangle's rule times the line's in ζ, triangle
    !! fastest: C3D6 the centroid at ζ = ∓1/√3; C3D15 the three points
    !! (1/6, 1/6), (2/3, 1/6), (1/6, 2/3) at ζ = -√0.6, 0, √0.6.
    logical, intent(in) :: quadratic
    type(quad_rule_t) :: r
    type(quad_rule_t) :: tri
    real(wp), allocatable :: zp(:), zw(:)
    integer :: i, k, g
    if (quadratic) then
       tri = triangle_rule(TRI_THREE)
       call gauss_line(3, zp, zw)
    else
       tri = triangle_rule(TRI_CENTROID)
       call gauss_line(2, zp, zw)
    end if
    allocate (r%xi(3, size(tri%w)*size(zw)), r%w(size(tri%w)*size(zw)))
    g = 0
    do k = 1, size(zw)
       do i = 1, size(tri%w)
          g = g + 1
          r%xi(:, g) = [tri%xi(:, i), zp(k)]
          r%w(g) = tri%w(i)*zw(k)
       end do
    end do
  end function gauss_wedge

  pure subroutine point_gradients(etype, x, xi, n, dx, detj, error)
    !! Shape functions n and their gradients dx(3, nnode) in x, y, z at xi;
    !! detj: the Jacobian determinant (an error when it is not positive).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), xi(3)
    real(wp), allocatable, intent(out) :: n(:), dx(:, :)
    real(wp), intent(out) :: detj
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: dn(:, :)
    real(wp) :: jac(3, 3), inv(3, 3)
    call solid_shape(etype, xi, n, dn)
    jac = matmul(dn, transpose(x))          ! jac(i, j) = ∂x_j/∂ξ_i
    detj = jac(1, 1)*(jac(2, 2)*jac(3, 3) - jac(2, 3)*jac(3, 2)) &
         - jac(1, 2)*(jac(2, 1)*jac(3, 3) - jac(2, 3)*jac(3, 1)) &
         + jac(1, 3)*(jac(2, 1)*jac(3, 2) - jac(2, 2)*jac(3, 1))
    if (.not. (detj > 0.0_wp)) then
       call fatal_error(error, EXIT_DECK, 'solid element with a non-positive Jacobian '// &
            '(nodes out of order, or the element is inverted or too distorted)')
       return
    end if
    inv = adjugate(jac)
    dx = matmul(inv/detj, dn)
  end subroutine point_gradients

  pure function adjugate(jac) result(inv)
    !! The adjugate of a 3×3 matrix (its inverse times its determinant).
    real(wp), intent(in) :: jac(3, 3)
    real(wp) :: inv(3, 3)
    inv(1, 1) = jac(2, 2)*jac(3, 3) - jac(2, 3)*jac(3, 2)
    inv(1, 2) = jac(1, 3)*jac(3, 2) - jac(1, 2)*jac(3, 3)
    inv(1, 3) = jac(1, 2)*jac(2, 3) - jac(1, 3)*jac(2, 2)
    inv(2, 1) = jac(2, 3)*jac(3, 1) - jac(2, 1)*jac(3, 3)
    inv(2, 2) = jac(1, 1)*jac(3, 3) - jac(1, 3)*jac(3, 1)
    inv(2, 3) = jac(1, 3)*jac(2, 1) - jac(1, 1)*jac(2, 3)
    inv(3, 1) = jac(2, 1)*jac(3, 2) - jac(2, 2)*jac(3, 1)
    inv(3, 2) = jac(1, 2)*jac(3, 1) - jac(1, 1)*jac(3, 2)
    inv(3, 3) = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
  end function adjugate

  pure subroutine mode_matrices(x, mat, kua, kaa, g, error, axes)
    !! C3D8I: the coupling kua(24, 9) and mode stiffness kaa(9, 9) of the
    !! incompatible modes, and their strain matrices g(6, 9, point) at the
    !! 2×2×2 points: ∂P_k/∂x = J0⁻¹ ∂P_k/∂ξ det J0 / det J (Taylor's centre
    !! Jacobian), P_k = 1 - ξ_k², modes ordered (P1: ux, uy, uz), (P2: …), (P3: …).
    !! mat, axes: the material and its axes (superjoin_elements_materials).
    real(wp), intent(in) :: x(:, :)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: kua(24, 9), kaa(9, 9), g(6, 9, 8)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:), dn(:, :), dx(:, :)
    real(wp) :: jac0(3, 3), inv0(3, 3), det0, detj, gx(3, 3), b(6, 24), d(6, 6)
    integer :: ig, k
    kua = 0.0_wp
    kaa = 0.0_wp
    g = 0.0_wp
    call solid_shape(ET_C3D8, [0.0_wp, 0.0_wp, 0.0_wp], n, dn)
    jac0 = matmul(dn, transpose(x))
    inv0 = adjugate(jac0)
    det0 = dot_product(jac0(1, :), inv0(:, 1))
    r = solid_rule(ET_C3D8I, .false.)
    do ig = 1, size(r%w)
       call point_gradients(ET_C3D8I, x, r%xi(:, ig), n, dx, detj, error)
       if (allocated(error)) return
       do k = 1, 3
          gx(:, k) = -2.0_wp*r%xi(k, ig)*inv0(:, k)/detj      ! (adj J0 / det J0) det J0 / det J
       end do
       g(:, :, ig) = strain_matrix(gx)
       b = strain_matrix(dx)
       d = point_elasticity(mat, n, x, axes)
       kua = kua + matmul(transpose(b), matmul(d, g(:, :, ig)))*(detj*r%w(ig))
       kaa = kaa + matmul(transpose(g(:, :, ig)), matmul(d, g(:, :, ig)))*(detj*r%w(ig))
    end do
  end subroutine mode_matrices

  pure subroutine mode_strains(x, mat, ue, eps, error, axes, eth)
    !! C3D8I: the strains eps(6, 8) of the condensed incompatible modes at the
    !! 2×2×2 points for the DOF values ue(24) (their amplitudes -kaa⁻¹ kauᵀ ue;
    !! with the nodal thermal strains eth(8), kaa⁻¹ (fα - kauᵀ ue), fα the
    !! modes' share of the thermal load, mode_thermal_force).
    real(wp), intent(in) :: x(:, :), ue(:)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: eps(6, 8)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    real(wp), intent(in), optional :: eth(:)
    real(wp) :: kua(24, 9), kaa(9, 9), g(6, 9, 8), alpha(9, 1), fa(9)
    integer :: ig
    eps = 0.0_wp
    call mode_matrices(x, mat, kua, kaa, g, error, axes)
    if (allocated(error)) return
    fa = 0.0_wp
    if (present(eth)) call mode_thermal_force(x, mat, g, eth, fa, error, axes)
    if (allocated(error)) return
    alpha = spd_solve(kaa, reshape(fa, [9, 1]) - matmul(transpose(kua), reshape(ue, [24, 1])))
    do ig = 1, 8
       eps(:, ig) = matmul(g(:, :, ig), alpha(:, 1))
    end do
  end subroutine mode_strains

  pure subroutine solid_stiffness(etype, x, mat, ke, error, axes)
    !! Stiffness ke(3 nnode, 3 nnode) of a solid element with node
    !! coordinates x(3, nnode), node-major (ux, uy, uz of node 1, then node 2 …);
    !! axes: the material axes of the section's *ORIENTATION (absent: global),
    !! D taken at each integration point (superjoin_elements_materials).
    !! Errors: E not positive, ν outside (-1, 0.5), a non-positive Jacobian.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:), dx(:, :), k1(:, :)
    real(wp) :: d(6, 6), detj
    integer :: g, nn
    nn = size(x, 2)
    if (mat%kind == MAT_ISO .and. (.not. (mat%e > 0.0_wp) .or. .not. (mat%nu > -1.0_wp .and. mat%nu < 0.5_wp))) then
       call fatal_error(error, EXIT_DECK, 'a solid element needs E > 0 and -1 < nu < 0.5')
       return
    end if
    r = solid_rule(merge(ET_C3D8I, etype, etype == ET_C3D8R), .false.)   ! C3D8R: C3D8I's, then reduced
    allocate (ke(3*nn, 3*nn))
    ke = 0.0_wp
    do g = 1, size(r%w)
       call point_gradients(etype, x, r%xi(:, g), n, dx, detj, error)
       if (allocated(error)) return
       d = point_elasticity(mat, n, x, axes)
       call add_btdb(dx, d, detj*r%w(g), ke)
    end do
    call mirror_upper(ke)
    if (etype == ET_C3D8I .or. etype == ET_C3D8R) call condense_modes(x, mat, ke, error, axes)
    if (allocated(error) .or. etype /= ET_C3D8R) return
    call mean_gradients(x, dx, detj, error)
    if (allocated(error)) return
    d = point_elasticity(mat, spread(1.0_wp/size(x, 2), 1, size(x, 2)), x, axes)   ! C3D8R: D at the centre
    allocate (k1(3*nn, 3*nn), source=0.0_wp)
    call add_btdb(dx, d, detj, k1)
    call mirror_upper(k1)
    ke = k1 + hourglass_stiffness(x, dx, ke)
  end subroutine solid_stiffness

  pure subroutine add_btdb(dx, d, s, ke)
    !! ke += s Bᵀ D B at one point, B = strain_matrix(dx), its upper triangle
    !! only (the node blocks a ≤ b; mirror_upper completes ke). Each column of B
    !! has three nonzeros, so D B is formed from three columns of D and each
    !! entry of Bᵀ (D B) from three products: about a quarter of the
    !! multiplications of the dense product, and no temporaries.
    real(wp), intent(in) :: dx(:, :), d(6, 6), s
    real(wp), intent(inout) :: ke(:, :)
    real(wp) :: db(6, 3, size(dx, 2))
    integer :: a, b, j, c
    do b = 1, size(dx, 2)
       db(:, 1, b) = s*(d(:, 1)*dx(1, b) + d(:, 4)*dx(2, b) + d(:, 5)*dx(3, b))
       db(:, 2, b) = s*(d(:, 2)*dx(2, b) + d(:, 4)*dx(1, b) + d(:, 6)*dx(3, b))
       db(:, 3, b) = s*(d(:, 3)*dx(3, b) + d(:, 5)*dx(1, b) + d(:, 6)*dx(2, b))
    end do
    do b = 1, size(dx, 2)
       do j = 1, 3
          c = 3*(b - 1) + j
          do a = 1, b
             ke(3*a - 2, c) = ke(3*a - 2, c) + dx(1, a)*db(1, j, b) + dx(2, a)*db(4, j, b) + dx(3, a)*db(5, j, b)
             ke(3*a - 1, c) = ke(3*a - 1, c) + dx(2, a)*db(2, j, b) + dx(1, a)*db(4, j, b) + dx(3, a)*db(6, j, b)
             ke(3*a, c) = ke(3*a, c) + dx(3, a)*db(3, j, b) + dx(1, a)*db(5, j, b) + dx(2, a)*db(6, j, b)
          end do
       end do
    end do
  end subroutine add_btdb

  pure subroutine mirror_upper(k)
    !! k(j, i) = k(i, j) for i < j: a matrix whose upper triangle was formed.
    real(wp), intent(inout) :: k(:, :)
    integer :: i, j
    do j = 2, size(k, 2)
       do i = 1, j - 1
          k(j, i) = k(i, j)
       end do
    end do
  end subroutine mirror_upper

  pure subroutine mean_gradients(x, bbar, vol, error)
    !! C3D8R: the mean gradients bbar(3, 8) = (1/V) ∫ ∂N/∂x dV of the trilinear
    !! hexahedron with corners x(3, 8) and its volume vol (2×2×2 Gauss, exact).
    real(wp), intent(in) :: x(:, :)
    real(wp), allocatable, intent(out) :: bbar(:, :)
    real(wp), intent(out) :: vol
    type(error_t), allocatable, intent(out) :: error
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:), dx(:, :)
    real(wp) :: detj
    integer :: g
    r = gauss_cube(2)
    allocate (bbar(3, 8), source=0.0_wp)
    vol = 0.0_wp
    do g = 1, size(r%w)
       call point_gradients(ET_C3D8, x, r%xi(:, g), n, dx, detj, error)
       if (allocated(error)) return
       bbar = bbar + dx*(detj*r%w(g))
       vol = vol + detj*r%w(g)
    end do
    bbar = bbar/vol
  end subroutine mean_gradients

  pure subroutine condense_modes(x, mat, ke, error, axes)
    !! C3D8I: ke -= kua kaa⁻¹ kauᵀ, the incompatible modes condensed.
    real(wp), intent(in) :: x(:, :)
    type(material_t), intent(in) :: mat
    real(wp), intent(inout) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    real(wp) :: kua(24, 9), kaa(9, 9), g(6, 9, 8)
    call mode_matrices(x, mat, kua, kaa, g, error, axes)
    if (allocated(error)) return
    ke = ke - matmul(kua, spd_solve(kaa, transpose(kua)))
  end subroutine condense_modes

  pure function strain_matrix(dx) result(b)
    !! The strain-displacement matrix b(6, 3 nnode) of the gradients dx(3, nnode):
    !! ε = b u_e, engineering shear strains γxy, γxz, γyz.
    real(wp), intent(in) :: dx(:, :)
    real(wp) :: b(6, 3*size(dx, 2))
    integer :: a
    b = 0.0_wp
    do a = 1, size(dx, 2)
       b(1, 3*a - 2) = dx(1, a)
       b(2, 3*a - 1) = dx(2, a)
       b(3, 3*a) = dx(3, a)
       b(4, 3*a - 2:3*a - 1) = [dx(2, a), dx(1, a)]
       b(5, [3*a - 2, 3*a]) = [dx(3, a), dx(1, a)]
       b(6, 3*a - 1:3*a) = [dx(3, a), dx(2, a)]
    end do
  end function strain_matrix

  pure subroutine solid_forces(etype, x, mat, ue, fg, error, axes)
    !! The forces the nodes exert on a solid element, K_e u_e, for the
    !! displacements ue(3 nnode, nstep) of every step, with one element matrix
    !! (axes: the material axes, as solid_stiffness).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:, :)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: fg(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    real(wp), allocatable :: ke(:, :)
    fg = 0.0_wp
    call solid_stiffness(etype, x, mat, ke, error, axes)
    if (allocated(error)) return
    fg = matmul(ke, ue)
  end subroutine solid_forces

  pure function thermal_point_stress(mat, n, eth, d) result(s0)
    !! The stress D ε_th of the thermal strain ε_th = (Σ N_a eth_a)(1, 1, 1, 0,
    !! 0, 0) at a point with shape functions n, nodal thermal strains eth (α ΔT;
    !! a table of α: the secant strain at the point, point_thermal_strain), D
    !! the point's elasticity in global axes (an isotropic expansion is the same
    !! in every axes).
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: n(:), eth(:), d(6, 6)
    real(wp) :: s0(6)
    s0 = point_thermal_strain(mat, n, eth)*(d(:, 1) + d(:, 2) + d(:, 3))
  end function thermal_point_stress

  pure function point_elasticity(mat, n, x, axes) result(d)
    !! D in global axes at the point with shape functions n of the element with
    !! nodes x: the material's (turned into the section's material axes there,
    !! superjoin_elements_materials), or for a copy of a material with a
    !! temperature table and its element's temperatures, at the point's
    !! temperature (superjoin_model_material_table, point_material: isotropic).
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: n(:), x(:, :)
    type(orientation_t), intent(in), optional :: axes
    real(wp) :: d(6, 6)
    if (allocated(mat%at_nodes)) then
       d = elasticity(point_material(mat, n))
    else
       d = material_stiffness(mat, matmul(x, n), axes)
    end if
  end function point_elasticity

  pure subroutine mode_thermal_force(x, mat, g, eth, fa, error, axes)
    !! C3D8I: the incompatible modes' share fα(9) = ∫ Gᵀ D ε_th dV of the thermal
    !! load (g: the modes' strain matrices at the 2×2×2 points, mode_matrices).
    real(wp), intent(in) :: x(:, :), g(:, :, :), eth(:)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: fa(9)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:), dx(:, :)
    real(wp) :: detj
    integer :: ig
    fa = 0.0_wp
    r = solid_rule(ET_C3D8I, .false.)
    do ig = 1, size(r%w)
       call point_gradients(ET_C3D8I, x, r%xi(:, ig), n, dx, detj, error)
       if (allocated(error)) return
       fa = fa + matmul(thermal_point_stress(mat, n, eth, point_elasticity(mat, n, x, axes)), g(:, :, ig))* &
            (detj*r%w(ig))
    end do
  end subroutine mode_thermal_force

  pure subroutine solid_thermal_load(etype, x, mat, eth, fe, error, axes)
    !! Consistent nodal loads fe(3 nnode) = ∫ Bᵀ D ε_th dV of the thermal
    !! strain ε_th = α ΔT (1, 1, 1, 0, 0, 0) interpolated from its nodal values
    !! eth(nnode) with the shape functions, with the stiffness rule (as
    !! CalculiX). C3D8I: the modes' share fα is condensed as the stiffness is,
    !! fe - kua kaa⁻¹ fα (zero for a uniform ΔT: ∫ G dV = 0). C3D8R: its
    !! mean strain, D and ε_th at the centre (one point).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), eth(:)
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:), dx(:, :)
    real(wp) :: detj, kua(24, 9), kaa(9, 9), g(6, 9, 8), fa(9, 1)
    integer :: ig
    allocate (fe(3*size(x, 2)), source=0.0_wp)
    if (etype == ET_C3D8R) then
       call mean_gradients(x, dx, detj, error)
       if (allocated(error)) return
       n = spread(1.0_wp/size(x, 2), 1, size(x, 2))
       fe = matmul(thermal_point_stress(mat, n, eth, point_elasticity(mat, n, x, axes)), strain_matrix(dx))*detj
       return
    end if
    r = solid_rule(etype, .false.)
    do ig = 1, size(r%w)
       call point_gradients(etype, x, r%xi(:, ig), n, dx, detj, error)
       if (allocated(error)) return
       fe = fe + matmul(thermal_point_stress(mat, n, eth, point_elasticity(mat, n, x, axes)), strain_matrix(dx))* &
            (detj*r%w(ig))
    end do
    if (etype /= ET_C3D8I) return
    call mode_matrices(x, mat, kua, kaa, g, error, axes)
    if (allocated(error)) return
    call mode_thermal_force(x, mat, g, eth, fa(:, 1), error, axes)
    if (allocated(error)) return
    fe = fe - reshape(matmul(kua, spd_solve(kaa, fa)), [24])
  end subroutine solid_thermal_load

  pure subroutine solid_body_load(etype, x, force, fe, error)
    !! Consistent nodal loads fe(3 nnode) of a uniform force per unit volume
    !! force(3) (ρ g for the self weight): fe_a = ∫ N_a dV force, with the
    !! full rule (exact on straight-sided elements).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), force(3)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    type(quad_rule_t) :: r
    real(wp), allocatable :: n(:), dx(:, :)
    real(wp) :: detj
    integer :: g, a
    allocate (fe(3*size(x, 2)))
    fe = 0.0_wp
    r = solid_rule(etype, .true.)
    do g = 1, size(r%w)
       call point_gradients(etype, x, r%xi(:, g), n, dx, detj, error)
       if (allocated(error)) return
       do a = 1, size(x, 2)
          fe(3*a - 2:3*a) = fe(3*a - 2:3*a) + n(a)*detj*r%w(g)*force
       end do
    end do
  end subroutine solid_body_load
end module superjoin_elements_solid
