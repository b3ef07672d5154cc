module superjoin_elements_mindlin
  !! Thick (Reissner-Mindlin) plate bending in a 2D local frame, the bending
  !! part of the thick shells S4R and S3R: MITC4 (Bathe & Dvorkin 1985) on the
  !! 4-node quadrilateral and MITC3 (Lee & Bathe 2004) on the 3-node triangle.
  !!
  !! Nodes xl(2, n), n = 3 or 4, counter-clockwise; local DOFs per node,
  !! node-major, (w, θx, θy) as in superjoin_elements_plate: θx, θy are
  !! right-hand rotations about the local x, y axes, and the rotations of the
  !! normal β (u = z βx, v = z βy) are βx = θy, βy = -θx.
  !!
  !! Displacement fields: w and β linear (triangle) or bilinear (quadrilateral)
  !! in the corners. Bending: curvatures κ = (∂βx/∂x, ∂βy/∂y, ∂βx/∂y + ∂βy/∂x)
  !! and moments m = D_b κ (D_b of superjoin_elements_plate, the same signs as
  !! the thin elements). Transverse shear: γ = (γxz, γyz) = ∇w + β, shear forces
  !! q = D_s γ with D_s = diag(ks) per unit length (ks = 5/6 G t unless the
  !! section says otherwise).
  !!
  !! Shear locking is removed by assumed covariant shear strains,
  !! e_ξ = ∂w/∂ξ + β·∂x/∂ξ and e_η = ∂w/∂η + β·∂x/∂η, tied to the displacement
  !! field at points on the sides:
  !! - MITC4: e_ξ is interpolated linearly in η between the midpoints of the
  !!   sides η = ±1, e_η linearly in ξ between the midpoints of ξ = ±1;
  !!   2x2 Gauss for bending and shear.
  !! - MITC3 (natural coordinates r, s, corners (0,0), (1,0), (0,1)):
  !!   e_r = e_r⁽¹⁾ + c s, e_s = e_s⁽²⁾ - c r, c = e_r⁽³⁾ - e_r⁽¹⁾ - e_s⁽³⁾ + e_s⁽²⁾,
  !!   with the tying points (1) = (1/2, 0), (2) = (0, 1/2), (3) = (1/2, 1/2):
  !!   the tangential shear strain along each side is the one of the
  !!   displacement field at its midpoint. 3-point rule (exact).
  !! The Cartesian strains are γ = J⁻ᵀ (e_ξ, e_η), J(a, b) = ∂x_a/∂ξ_b.
  !! MITC3 alone still locks in the thin limit on structured meshes (its shear
  !! space, rotated Raviart-Thomas of lowest order, is too rich for linear
  !! rotations without bubbles; measured: S3R/S3 = 0.36 on a 16x16 simply
  !! supported plate at a/t = 1000). The triangle therefore takes the
  !! stabilization of Lyly, Stenberg & Vihinen (Comput. Mech. 11, 1993) and
  !! Pitkäranta: the shear stiffness is scaled by t²/(t² + α h²), h the longest
  !! side, α = 0.1, which keeps the consistency error O(h²) and removes the
  !! locking (tests/shells/verify_thick.py).
  !! Both elements have exactly the three rigid modes of a plate (w, θx, θy),
  !! pass the constant-curvature and constant-shear patch tests and do not lock
  !! as t → 0 (tests/unit/test_mindlin.f90).
  !!
  !! Errors come back as error_t (code EXIT_DECK) with a message without
  !! file:line; the caller prefixes it.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_frame, only: require_positive
  use superjoin_elements_plate, only: plate_check, bending_rigidity, integration_rule
  use superjoin_elements_plate, only: corner_functions
  implicit none (type, external)
  private

  integer, parameter :: NDN = 3          !! DOFs per node: w, θx, θy
  integer, parameter :: NTRI = 3, NQUAD = 4
  real(wp), parameter :: SHEAR_CORRECTION = 5.0_wp/6.0_wp
    !! κ of the default transverse shear stiffness κ G t (a homogeneous section)
  real(wp), parameter :: QUAD_XI(NQUAD) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]
  real(wp), parameter :: QUAD_ETA(NQUAD) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    !! 3-point rule on the unit triangle (degree 2)
  real(wp), parameter :: ONE_THIRD = 1.0_wp/3.0_wp
  real(wp), parameter :: TRI_STABILIZATION = 0.1_wp
    !! α of the MITC3 shear stiffness scaling t²/(t² + α h²) (see the module header)

  public :: mindlin_stiffness, mindlin_resultants, default_shear_stiffness, SHEAR_CORRECTION
  public :: mindlin_point_resultants
  public :: mindlin_thermal_load

contains

  pure function default_shear_stiffness(t, e, nu) result(ks)
    !! Transverse shear stiffness per unit length κ G t, κ = 5/6, G = E/(2(1 + ν)), in both directions.
    real(wp), intent(in) :: t, e, nu
    real(wp) :: ks(2)
    ks = SHEAR_CORRECTION*e/(2*(1 + nu))*t
  end function default_shear_stiffness

  pure subroutine mindlin_stiffness(xl, t, e, nu, ks, kb, error)
    !! Bending and transverse shear stiffness kb(3n, 3n) of a MITC3 (n = 3) or
    !! MITC4 (n = 4) plate, local DOFs (w, θx, θy per node), exactly symmetric;
    !! ks(2) the shear stiffness per unit length along local x and y.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu, ks(2)
    real(wp), allocatable, intent(out) :: kb(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: xi(:), eta(:), wt(:)
    real(wp) :: db(3, 3), bb(3, NDN*size(xl, 2)), bs(2, NDN*size(xl, 2)), detj, kse(2)
    integer :: n, g

    call check(xl, t, e, nu, ks, error)
    if (allocated(error)) return
    n = size(xl, 2)
    db = bending_rigidity(t, e, nu)
    kse = ks*shear_scaling(xl, t)
    call integration_rule(n, xi, eta, wt)
    allocate (kb(NDN*n, NDN*n), source=0.0_wp)
    do g = 1, size(wt)
       call strain_matrices(xl, xi(g), eta(g), bb, bs, detj)
       kb = kb + (wt(g)*detj)*(matmul(transpose(bb), matmul(db, bb)) + &
            matmul(transpose(bs), spread(kse, 2, NDN*n)*bs))
    end do
    kb = 0.5_wp*(kb + transpose(kb))
  end subroutine mindlin_stiffness

  pure subroutine mindlin_resultants(xl, t, e, nu, ks, ue, m, q, error)
    !! Moments m = (mx, my, mxy) and transverse shear forces q = (qx, qy) per
    !! unit length at the element centre (centroid of the triangle, ξ = η = 0
    !! of the quadrilateral) from the local DOF values ue(3n).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu, ks(2)
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: m(3), q(2)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: bb(3, NDN*size(xl, 2)), bs(2, NDN*size(xl, 2)), detj, xi

    m = 0.0_wp
    q = 0.0_wp
    call check(xl, t, e, nu, ks, error)
    if (allocated(error)) return
    if (size(ue) /= NDN*size(xl, 2)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    xi = merge(ONE_THIRD, 0.0_wp, size(xl, 2) == NTRI)
    call strain_matrices(xl, xi, xi, bb, bs, detj)
    m = matmul(bending_rigidity(t, e, nu), matmul(bb, ue))
    q = ks*shear_scaling(xl, t)*matmul(bs, ue)
  end subroutine mindlin_resultants

  pure subroutine mindlin_point_resultants(xl, t, e, nu, ks, ue, r_points, r_nodes, error)
    !! Resultants per unit length (mx, my, mxy, qx, qy) from the local DOF values
    !! ue(3n) at the points where stresses are reported, r_points(5, k), and at
    !! the nodes, r_nodes(5, n): MITC4 at its 2×2 Gauss points ((ξ, η) = (-g, -g),
    !! (g, -g), (g, g), (-g, g), g = 1/√3, point k next to node k), extrapolated
    !! to the corners by the bilinear field through the four values (exact for
    !! the element's bilinear moments and shear forces); MITC3 at its centroid,
    !! the value at every node (constant curvature; its assumed shear varies
    !! linearly but is reported, as the resultants, at the centroid).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu, ks(2)
    real(wp), intent(in) :: ue(:)
    real(wp), allocatable, intent(out) :: r_points(:, :), r_nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), parameter :: G = 1/sqrt(3.0_wp)
    real(wp) :: bb(3, NDN*size(xl, 2)), bs(2, NDN*size(xl, 2)), detj, db(3, 3), kse(2), sf(NQUAD), dsf(NQUAD, 2)
    integer :: n, k

    call check(xl, t, e, nu, ks, error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(ue) /= NDN*n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    db = bending_rigidity(t, e, nu)
    kse = ks*shear_scaling(xl, t)
    allocate (r_nodes(5, n))
    if (n == NTRI) then
       allocate (r_points(5, 1))
       call strain_matrices(xl, ONE_THIRD, ONE_THIRD, bb, bs, detj)
       r_points(1:3, 1) = matmul(db, matmul(bb, ue))
       r_points(4:5, 1) = kse*matmul(bs, ue)
       r_nodes = spread(r_points(:, 1), 2, n)
       return
    end if
    allocate (r_points(5, NQUAD))
    do k = 1, NQUAD
       call strain_matrices(xl, G*QUAD_XI(k), G*QUAD_ETA(k), bb, bs, detj)
       r_points(1:3, k) = matmul(db, matmul(bb, ue))
       r_points(4:5, k) = kse*matmul(bs, ue)
    end do
    ! node k sits at (ξ_k/g, η_k/g) = √3 (ξ_k, η_k) of the square of the Gauss points
    do k = 1, NQUAD
       call shape(NQUAD, QUAD_XI(k)/G, QUAD_ETA(k)/G, sf, dsf)
       r_nodes(:, k) = matmul(r_points, sf)
    end do
  end subroutine mindlin_point_resultants

  pure subroutine mindlin_thermal_load(xl, t, e, nu, ks, kappa0, fe, error, self_energy)
    !! Consistent nodal loads fe(3n) = ∫ Bbᵀ D_b κ0 dA (local w, θx, θy per
    !! node) of an isotropic initial curvature κ0 (1, 1, 0) whose nodal values
    !! kappa0(n) are interpolated with the corner functions to the points of
    !! the stiffness; the transverse shear takes no initial strain.
    !! self_energy: ½ ∫ κ0ᵀ D_b κ0 dA by the same points (the constant of the
    !! element's energy ½ uᵀ K u - uᵀ fe + self_energy).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu, ks(2)
    real(wp), intent(in) :: kappa0(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(out), optional :: self_energy
    real(wp), allocatable :: xi(:), eta(:), wt(:)
    real(wp) :: db(3, 3), bb(3, NDN*size(xl, 2)), bs(2, NDN*size(xl, 2)), detj, k0, sum_k0
    integer :: n, g
    call check(xl, t, e, nu, ks, error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(kappa0) /= n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodal initial curvatures')
       return
    end if
    db = bending_rigidity(t, e, nu)
    call integration_rule(n, xi, eta, wt)
    allocate (fe(NDN*n), source=0.0_wp)
    sum_k0 = 0.0_wp
    do g = 1, size(wt)
       call strain_matrices(xl, xi(g), eta(g), bb, bs, detj)
       k0 = dot_product(corner_functions(n, xi(g), eta(g)), kappa0)
       fe = fe + (wt(g)*detj*k0)*matmul(transpose(bb), matmul(db, [1.0_wp, 1.0_wp, 0.0_wp]))
       sum_k0 = sum_k0 + wt(g)*detj*k0**2
    end do
    if (present(self_energy)) self_energy = 0.5_wp*sum_k0*(2.0_wp*db(1, 1) + 2.0_wp*db(1, 2))
  end subroutine mindlin_thermal_load

  pure real(wp) function shear_scaling(xl, t) result(f)
    !! Factor on the shear stiffness: t²/(t² + α h²) on the triangle (h its
    !! longest side, α = TRI_STABILIZATION), 1 on the quadrilateral.
    real(wp), intent(in) :: xl(:, :), t
    real(wp) :: h2
    integer :: i
    f = 1.0_wp
    if (size(xl, 2) /= NTRI) return
    h2 = 0.0_wp
    do i = 1, NTRI
       h2 = max(h2, sum((xl(:, mod(i, NTRI) + 1) - xl(:, i))**2))
    end do
    f = t**2/(t**2 + TRI_STABILIZATION*h2)
  end function shear_scaling

  ! ------------------------------------------------------------------ internals

  pure subroutine check(xl, t, e, nu, ks, error)
    !! The plate's checks (material, thickness, geometry) and ks > 0.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu, ks(2)
    type(error_t), allocatable, intent(out) :: error
    call plate_check(xl, t, e, nu, error)
    if (allocated(error)) return
    call require_positive(minval(ks), 'transverse shear stiffness', error)
  end subroutine check

  pure subroutine shape(n, xi, eta, sf, dsf)
    !! Corner functions sf(i) and their derivatives dsf(i, 1:2) = ∂N_i/∂(ξ, η):
    !! linear on the unit triangle (n = 3), bilinear on the square (n = 4).
    integer, intent(in) :: n
    real(wp), intent(in) :: xi, eta
    real(wp), intent(out) :: sf(:), dsf(:, :)
    if (n == NTRI) then
       sf(1:NTRI) = [1 - xi - eta, xi, eta]
       dsf(1:NTRI, 1) = [-1.0_wp, 1.0_wp, 0.0_wp]
       dsf(1:NTRI, 2) = [-1.0_wp, 0.0_wp, 1.0_wp]
    else
       sf(1:NQUAD) = 0.25_wp*(1 + QUAD_XI*xi)*(1 + QUAD_ETA*eta)
       dsf(1:NQUAD, 1) = 0.25_wp*QUAD_XI*(1 + QUAD_ETA*eta)
       dsf(1:NQUAD, 2) = 0.25_wp*QUAD_ETA*(1 + QUAD_XI*xi)
    end if
  end subroutine shape

  pure function covariant_shear(xl, xi, eta) result(ec)
    !! Rows ec(1:2, :) with ec u = (e_ξ, e_η) = (∂w/∂ξ + β·∂x/∂ξ, ∂w/∂η + β·∂x/∂η)
    !! of the displacement field at (ξ, η).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: xi, eta
    real(wp) :: ec(2, NDN*size(xl, 2))
    real(wp) :: sf(size(xl, 2)), dsf(size(xl, 2), 2), jac(2, 2)
    integer :: i, b, o
    call shape(size(xl, 2), xi, eta, sf, dsf)
    jac = matmul(xl, dsf)
    do i = 1, size(xl, 2)
       o = NDN*(i - 1)
       do b = 1, 2
          ec(b, o + 1) = dsf(i, b)
          ! β·x_,b with βx = θy, βy = -θx
          ec(b, o + 2) = -sf(i)*jac(2, b)
          ec(b, o + 3) = sf(i)*jac(1, b)
       end do
    end do
  end function covariant_shear

  pure subroutine strain_matrices(xl, xi, eta, bb, bs, detj)
    !! Curvature rows bb(3, 3n) (κ = bb u), assumed Cartesian shear rows
    !! bs(2, 3n) (γ = bs u) and the Jacobian determinant at (ξ, η).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: xi, eta
    real(wp), intent(out) :: bb(:, :), bs(:, :)
    real(wp), intent(out) :: detj
    real(wp) :: sf(size(xl, 2)), dsf(size(xl, 2), 2), dx(size(xl, 2), 2)
    real(wp) :: jac(2, 2), jinv(2, 2), ea(2, size(bs, 2))
    real(wp), dimension(2, size(bs, 2)) :: t1, t2, t3, t4
    real(wp) :: c(size(bs, 2))
    integer :: n, i

    n = size(xl, 2)
    call shape(n, xi, eta, sf, dsf)
    jac = matmul(xl, dsf)
    detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
    jinv(1, :) = [jac(2, 2), -jac(1, 2)]
    jinv(2, :) = [-jac(2, 1), jac(1, 1)]
    jinv = jinv/detj                   ! jinv(b, a) = ∂ξ_b/∂x_a
    dx = matmul(dsf, jinv)             ! dx(i, a) = ∂N_i/∂x_a

    bb = 0.0_wp
    do i = 1, n
       bb(1, NDN*i) = dx(i, 1)
       bb(2, NDN*i - 1) = -dx(i, 2)
       bb(3, NDN*i) = dx(i, 2)
       bb(3, NDN*i - 1) = -dx(i, 1)
    end do

    if (n == NQUAD) then
       t1 = covariant_shear(xl, 0.0_wp, -1.0_wp)    ! C: e_ξ on side η = -1
       t2 = covariant_shear(xl, 0.0_wp, 1.0_wp)     ! A: e_ξ on side η = +1
       t3 = covariant_shear(xl, -1.0_wp, 0.0_wp)    ! D: e_η on side ξ = -1
       t4 = covariant_shear(xl, 1.0_wp, 0.0_wp)     ! B: e_η on side ξ = +1
       ea(1, :) = 0.5_wp*(1 - eta)*t1(1, :) + 0.5_wp*(1 + eta)*t2(1, :)
       ea(2, :) = 0.5_wp*(1 - xi)*t3(2, :) + 0.5_wp*(1 + xi)*t4(2, :)
    else
       t1 = covariant_shear(xl, 0.5_wp, 0.0_wp)     ! (1)
       t2 = covariant_shear(xl, 0.0_wp, 0.5_wp)     ! (2)
       t3 = covariant_shear(xl, 0.5_wp, 0.5_wp)     ! (3)
       c = t3(1, :) - t1(1, :) - t3(2, :) + t2(2, :)
       ea(1, :) = t1(1, :) + c*eta
       ea(2, :) = t2(2, :) - c*xi
    end if
    bs = matmul(transpose(jinv), ea)   ! γ_a = Σ_b ∂ξ_b/∂x_a e_b
  end subroutine strain_matrices
end module superjoin_elements_mindlin
