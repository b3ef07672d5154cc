module superjoin_elements_plate
  !! Thin (Kirchhoff) plate bending elements in a 2D local frame: DKT, the
  !! discrete Kirchhoff triangle (Batoz, Bathe & Ho 1980), and DKQ, the discrete
  !! Kirchhoff quadrilateral (Batoz & Ben Tahar 1982). Isotropic material,
  !! bending rigidity D = E t³ / (12 (1 - ν²)).
  !!
  !! Nodes: xl(2, n), n = 3 (DKT) or 4 (DKQ), counter-clockwise. Local DOFs per
  !! node, node-major: (w, θx, θy), θx and θy right-hand rotations about the
  !! local x and y axes, so for a Kirchhoff plate θx = ∂w/∂y and θy = -∂w/∂x
  !! (the rx, ry of a 6-DOF shell node).
  !!
  !! Formulation. The rotations of the normal β = (βx, βy), defined by the
  !! in-plane displacements u = z βx, v = z βy (so βx = θy and βy = -θx), are
  !! interpolated quadratically: 6-node triangle or 8-node serendipity
  !! functions on the corners and the side midpoints, with the geometry linear
  !! (bilinear) in the corners. The midside rotations are eliminated by the
  !! discrete Kirchhoff conditions on each side i -> j (d = x_j - x_i, L = |d|,
  !! s = d/L): w is cubic along the side (Hermite in w and ∂w/∂s = -β·s at the
  !! ends), the normal rotation β·n is linear and the transverse shear
  !! ∂w/∂s + β·s vanishes at the ends and at the midpoint k, which gives
  !!   β_k = (β_i + β_j)/2 - 3/(2L) (w_j - w_i) s - 3/4 ((β_i + β_j)·s) s.
  !! Curvatures κ = (∂βx/∂x, ∂βy/∂y, ∂βx/∂y + ∂βy/∂x) (for Kirchhoff fields
  !! κ = -(w_xx, w_yy, 2 w_xy)), moments m = D_b κ with
  !! D_b = D [1 ν 0; ν 1 0; 0 0 (1-ν)/2], stiffness K = ∫ Bᵀ D_b B dA with the
  !! 3-point rule (DKT, exact) or 2×2 Gauss (DKQ). Both elements represent
  !! constant curvature exactly and pass the patch test.
  !!
  !! Moments are per unit length, mx = ∫ σx z dz over the thickness with z along
  !! the local normal (+t/2 is the top surface): top-surface stress σx = 6 mx / t².
  !!
  !! Errors come back as error_t (code EXIT_DECK) with a message without
  !! file:line; the caller prefixes it.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_frame, only: require_positive, real_text
  implicit none (type, external)
  private

  integer, parameter :: NDN = 3          !! DOFs per node: w, θx, θy
  integer, parameter :: NSTRAIN = 3      !! curvatures κx, κy, κxy
  integer, parameter :: NTRI = 3, NQUAD = 4
  real(wp), parameter :: NU_MIN = -1.0_wp, NU_MAX = 0.5_wp   !! open range of Poisson's ratio
  real(wp), parameter :: GEOMETRY_TOL = 1.0e-12_wp
    !! Degenerate element: area or Jacobian determinant at a Gauss point
    !! <= GEOMETRY_TOL × h² (triangle: twice the area), or a side <= GEOMETRY_TOL × h
    !! (h: longest side).
  real(wp), parameter :: ONE_THIRD = 1.0_wp/3.0_wp
  real(wp), parameter :: GAUSS2 = 0.57735026918962576451_wp    !! 1/√3, 2-point Gauss abscissa
  real(wp), parameter :: QUAD_XI(NQUAD) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]   !! corners in (ξ, η)
  real(wp), parameter :: QUAD_ETA(NQUAD) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
  real(wp), parameter :: TRI_RULE_A = 1.0_wp/6.0_wp, TRI_RULE_B = 2.0_wp/3.0_wp, TRI_WEIGHT = 1.0_wp/6.0_wp
    !! 3-point rule on the unit triangle: (a, a), (b, a), (a, b), weights 1/6 (exact for degree 2)

  public :: plate_stiffness, plate_moments, plate_pressure_load, plate_moment_operator
  public :: plate_point_moments
  public :: plate_check, bending_rigidity, integration_rule
  public :: plate_thermal_load, corner_functions

contains

  pure subroutine plate_stiffness(xl, t, e, nu, kb, error)
    !! Bending stiffness kb(3n, 3n) of a DKT (n = 3) or DKQ (n = 4) element, local DOFs (exactly symmetric).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: kb(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: xi(:), eta(:), wt(:), b(:, :)
    real(wp) :: db(NSTRAIN, NSTRAIN), detj
    integer :: n, g

    call check_element(xl, t, e, nu, error)
    if (allocated(error)) return
    n = size(xl, 2)
    db = bending_rigidity(t, e, nu)
    call integration_rule(n, xi, eta, wt)
    allocate (b(NSTRAIN, NDN*n))
    allocate (kb(NDN*n, NDN*n), source=0.0_wp)
    do g = 1, size(wt)
       call curvature_matrix(xl, xi(g), eta(g), b, detj)
       kb = kb + (wt(g)*detj)*matmul(transpose(b), matmul(db, b))
    end do
    kb = 0.5_wp*(kb + transpose(kb))
  end subroutine plate_stiffness

  pure subroutine plate_moments(xl, t, e, nu, ue, m, error)
    !! Moments per unit length m = (mx, my, mxy) at the element centre from the local DOF values ue(3n).
    !!
    !! The centre is the centroid of the triangle and the point ξ = η = 0 of the
    !! quadrilateral (its centroid when it is a parallelogram). Kirchhoff signs:
    !! mx = -D (w_xx + ν w_yy), my = -D (w_yy + ν w_xx), mxy = -D (1 - ν) w_xy.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: m(3)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: b(:, :)
    real(wp) :: xi, eta, detj

    m = 0.0_wp
    call check_element(xl, t, e, nu, error)
    if (allocated(error)) return
    if (size(ue) /= NDN*size(xl, 2)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    if (size(xl, 2) == NTRI) then
       xi = ONE_THIRD
       eta = ONE_THIRD
    else
       xi = 0.0_wp
       eta = 0.0_wp
    end if
    allocate (b(NSTRAIN, size(ue)))
    call curvature_matrix(xl, xi, eta, b, detj)
    m = matmul(bending_rigidity(t, e, nu), matmul(b, ue))
  end subroutine plate_moments

  pure subroutine plate_moment_operator(xl, t, e, nu, op, error)
    !! The operator op(3, 3n) of plate_moments: m = op ue for every local
    !! ue(3n), op = D_b b at the element centre. Formed once, it serves every
    !! step and every instance of a part.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: op(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: b(:, :)
    real(wp) :: detj, c
    call check_element(xl, t, e, nu, error)
    if (allocated(error)) return
    c = merge(ONE_THIRD, 0.0_wp, size(xl, 2) == NTRI)
    allocate (b(NSTRAIN, NDN*size(xl, 2)))
    call curvature_matrix(xl, c, c, b, detj)
    op = matmul(bending_rigidity(t, e, nu), b)
  end subroutine plate_moment_operator

  pure subroutine plate_pressure_load(xl, p, fe)
    !! Nodal loads fe(3n) of a uniform pressure p along the local +z: translations only.
    !!
    !! Node i gets p ∫ N_i dA with the linear (triangle: A/3 each) or bilinear
    !! (quadrilateral, 2×2 Gauss, exact) corner functions; the moment entries are
    !! zero (the rotational terms of the consistent DKT/DKQ load vector are left
    !! out, which does not change the convergence of the elements). xl is
    !! expected to be a valid element (plate_stiffness checks it); a node count
    !! other than 3 or 4 gives an empty fe.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: p
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), allocatable :: xi(:), eta(:), wt(:)
    real(wp) :: area, jac(2, 2), dg(NQUAD, 2), detj
    integer :: n, g, i

    n = size(xl, 2)
    if (size(xl, 1) /= 2 .or. (n /= NTRI .and. n /= NQUAD)) then
       allocate (fe(0))
       return
    end if
    allocate (fe(NDN*n), source=0.0_wp)
    if (n == NTRI) then
       area = 0.5_wp*twice_triangle_area(xl)
       fe(1::NDN) = p*area*ONE_THIRD
       return
    end if
    call integration_rule(n, xi, eta, wt)
    do g = 1, size(wt)
       call geometry_derivatives(n, xi(g), eta(g), dg)
       jac = matmul(xl, dg)
       detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
       do i = 1, n
          fe(NDN*(i - 1) + 1) = fe(NDN*(i - 1) + 1) + &
               p*wt(g)*detj*0.25_wp*(1 + QUAD_XI(i)*xi(g))*(1 + QUAD_ETA(i)*eta(g))
       end do
    end do
  end subroutine plate_pressure_load

  pure subroutine plate_thermal_load(xl, t, e, nu, kappa0, fe, error, self_energy)
    !! Consistent nodal loads fe(3n) = ∫ Bᵀ D_b κ0 dA (local w, θx, θy per
    !! node) of an isotropic initial curvature κ0 (1, 1, 0) (α ∂T/∂n: the top
    !! surface the longer one) whose nodal values kappa0(n) are interpolated
    !! with the corner functions to the points of the stiffness (DKT 3-point,
    !! DKQ 2×2 Gauss) and integrated with the element's own curvature matrix.
    !! self_energy: ½ ∫ κ0ᵀ D_b κ0 dA by the same points (the constant of the
    !! element's energy ½ uᵀ K u - uᵀ fe + self_energy).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: kappa0(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(out), optional :: self_energy
    real(wp), allocatable :: xi(:), eta(:), wt(:), b(:, :)
    real(wp) :: db(NSTRAIN, NSTRAIN), detj, k0, sum_k0
    integer :: n, g
    call check_element(xl, t, e, nu, error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(kappa0) /= n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodal initial curvatures')
       return
    end if
    db = bending_rigidity(t, e, nu)
    call integration_rule(n, xi, eta, wt)
    allocate (b(NSTRAIN, NDN*n), fe(NDN*n), source=0.0_wp)
    sum_k0 = 0.0_wp
    do g = 1, size(wt)
       call curvature_matrix(xl, xi(g), eta(g), b, detj)
       k0 = dot_product(corner_functions(n, xi(g), eta(g)), kappa0)
       fe = fe + (wt(g)*detj*k0)*matmul(transpose(b), matmul(db, [1.0_wp, 1.0_wp, 0.0_wp]))
       sum_k0 = sum_k0 + wt(g)*detj*k0**2
    end do
    if (present(self_energy)) self_energy = 0.5_wp*sum_k0*(2.0_wp*db(1, 1) + 2.0_wp*db(1, 2))
  end subroutine plate_thermal_load

  pure function corner_functions(n, xi, eta) result(nf)
    !! The linear (n = 3, unit triangle) or bilinear (n = 4) corner functions at (ξ, η).
    integer, intent(in) :: n
    real(wp), intent(in) :: xi, eta
    real(wp) :: nf(n)
    if (n == NTRI) then
       nf = [1 - xi - eta, xi, eta]
    else
       nf = 0.25_wp*(1 + QUAD_XI*xi)*(1 + QUAD_ETA*eta)
    end if
  end function corner_functions

  pure subroutine plate_check(xl, t, e, nu, error)
    !! The checks of plate_stiffness (t, E, ν, node count, area, sides, Jacobian at the 2×2 Gauss points),
    !! for other plate formulations on the same geometry (superjoin_elements_mindlin).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    type(error_t), allocatable, intent(out) :: error
    call check_element(xl, t, e, nu, error)
  end subroutine plate_check

  ! ------------------------------------------------------------------ internals

  pure subroutine check_element(xl, t, e, nu, error)
    !! Data checks shared by the plate procedures: material, thickness, geometry.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: h, area, dg(NQUAD, 2), jac(2, 2), detj
    real(wp), allocatable :: xi(:), eta(:), wt(:)
    integer :: n, k, g

    call require_positive(t, 'shell thickness t', error)
    call require_positive(e, 'Young''s modulus E', error)
    if (allocated(error)) return
    if (.not. (nu > NU_MIN .and. nu < NU_MAX)) then
       call fatal_error(error, EXIT_DECK, 'Poisson''s ratio nu ('//real_text(nu)// &
            ') must lie between -1 and 0.5 (both excluded) for a plate')
       return
    end if
    n = size(xl, 2)
    if (size(xl, 1) /= 2 .or. (n /= NTRI .and. n /= NQUAD)) then
       call fatal_error(error, EXIT_DECK, 'plate element needs 3 or 4 nodes with 2 local coordinates')
       return
    end if
    h = 0.0_wp
    do k = 1, n
       h = max(h, norm2(side_vector(xl, k)))
    end do
    if (n == NTRI) then
       area = 0.5_wp*twice_triangle_area(xl)
    else
       area = 0.5_wp*(twice_triangle_area(xl(:, [1, 2, 3])) + twice_triangle_area(xl(:, [1, 3, 4])))
    end if
    if (.not. (area > GEOMETRY_TOL*h**2)) then   ! also catches NaN coordinates
       call fatal_error(error, EXIT_DECK, 'zero or negative element area (clockwise or coincident nodes)')
       return
    end if
    if (n == NTRI) return
    do k = 1, n
       if (norm2(side_vector(xl, k)) <= GEOMETRY_TOL*h) then
          call fatal_error(error, EXIT_DECK, 'zero-length element side (coincident nodes)')
          return
       end if
    end do
    call integration_rule(n, xi, eta, wt)
    do g = 1, size(wt)
       call geometry_derivatives(n, xi(g), eta(g), dg)
       jac = matmul(xl, dg)
       detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
       if (.not. (detj > GEOMETRY_TOL*h**2)) then
          call fatal_error(error, EXIT_DECK, &
               'non-positive Jacobian at a Gauss point (concave or badly distorted quadrilateral)')
          return
       end if
    end do
  end subroutine check_element

  pure function bending_rigidity(t, e, nu) result(db)
    !! Moment-curvature matrix D_b = D [1 ν 0; ν 1 0; 0 0 (1-ν)/2], D = E t³ / (12 (1 - ν²)).
    real(wp), intent(in) :: t, e, nu
    real(wp) :: db(NSTRAIN, NSTRAIN)
    real(wp) :: d
    d = e*t**3/(12*(1 - nu**2))
    db = 0.0_wp
    db(1, 1) = d
    db(2, 2) = d
    db(1, 2) = nu*d
    db(2, 1) = nu*d
    db(3, 3) = 0.5_wp*(1 - nu)*d
  end function bending_rigidity

  pure function twice_triangle_area(x) result(a2)
    !! Twice the signed area of the triangle x(2, 3) (positive counter-clockwise).
    real(wp), intent(in) :: x(:, :)
    real(wp) :: a2
    a2 = (x(1, 2) - x(1, 1))*(x(2, 3) - x(2, 1)) - (x(1, 3) - x(1, 1))*(x(2, 2) - x(2, 1))
  end function twice_triangle_area

  pure function side_vector(xl, k) result(d)
    !! Vector of side k, from corner k to the next corner.
    real(wp), intent(in) :: xl(:, :)
    integer, intent(in) :: k
    real(wp) :: d(2)
    d = xl(:, mod(k, size(xl, 2)) + 1) - xl(:, k)
  end function side_vector

  pure subroutine integration_rule(n, xi, eta, wt)
    !! Points and weights: 3-point rule on the unit triangle (n = 3), 2×2 Gauss (n = 4).
    integer, intent(in) :: n
    real(wp), allocatable, intent(out) :: xi(:), eta(:), wt(:)
    if (n == NTRI) then
       xi = [TRI_RULE_A, TRI_RULE_B, TRI_RULE_A]
       eta = [TRI_RULE_A, TRI_RULE_A, TRI_RULE_B]
       wt = [TRI_WEIGHT, TRI_WEIGHT, TRI_WEIGHT]
    else
       xi = GAUSS2*QUAD_XI
       eta = GAUSS2*QUAD_ETA
       wt = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]
    end if
  end subroutine integration_rule

  pure subroutine geometry_derivatives(n, xi, eta, dg)
    !! Derivatives dg(i, 1:2) = ∂N_i/∂(ξ, η) of the linear (n = 3) or bilinear (n = 4) corner functions.
    integer, intent(in) :: n
    real(wp), intent(in) :: xi, eta
    real(wp), intent(out) :: dg(:, :)
    integer :: i
    if (n == NTRI) then
       dg(1:NTRI, 1) = [-1.0_wp, 1.0_wp, 0.0_wp]
       dg(1:NTRI, 2) = [-1.0_wp, 0.0_wp, 1.0_wp]
    else
       do i = 1, NQUAD
          dg(i, 1) = 0.25_wp*QUAD_XI(i)*(1 + QUAD_ETA(i)*eta)
          dg(i, 2) = 0.25_wp*QUAD_ETA(i)*(1 + QUAD_XI(i)*xi)
       end do
    end if
  end subroutine geometry_derivatives

  pure subroutine rotation_derivatives(n, xi, eta, dq)
    !! Derivatives dq(i, 1:2) = ∂N_i/∂(ξ, η) of the quadratic rotation functions:
    !! corners 1..n, then the midpoints of the sides (n+k on side k -> k+1).
    !! 6-node triangle (area coordinates L1 = 1 - ξ - η, L2 = ξ, L3 = η) or
    !! 8-node serendipity quadrilateral.
    integer, intent(in) :: n
    real(wp), intent(in) :: xi, eta
    real(wp), intent(out) :: dq(:, :)
    real(wp) :: l1, l2, l3, a, b
    integer :: i
    if (n == NTRI) then
       l1 = 1 - xi - eta
       l2 = xi
       l3 = eta
       dq(1, :) = [-(4*l1 - 1), -(4*l1 - 1)]
       dq(2, :) = [4*l2 - 1, 0.0_wp]
       dq(3, :) = [0.0_wp, 4*l3 - 1]
       dq(4, :) = [4*(l1 - l2), -4*l2]        ! 4 L1 L2
       dq(5, :) = [4*l3, 4*l2]                ! 4 L2 L3
       dq(6, :) = [-4*l3, 4*(l1 - l3)]        ! 4 L3 L1
       return
    end if
    do i = 1, NQUAD
       ! (1 + ξ ξi)(1 + η ηi)(ξ ξi + η ηi - 1)/4
       a = QUAD_XI(i)
       b = QUAD_ETA(i)
       dq(i, 1) = 0.25_wp*a*(1 + b*eta)*(2*a*xi + b*eta)
       dq(i, 2) = 0.25_wp*b*(1 + a*xi)*(a*xi + 2*b*eta)
    end do
    ! Midpoints of sides 1-2 and 3-4: (1 - ξ²)(1 + η ηk)/2, ηk = -1, +1
    dq(5, :) = [-xi*(1 - eta), -0.5_wp*(1 - xi**2)]
    dq(7, :) = [-xi*(1 + eta), 0.5_wp*(1 - xi**2)]
    ! Midpoints of sides 2-3 and 4-1: (1 + ξ ξk)(1 - η²)/2, ξk = +1, -1
    dq(6, :) = [0.5_wp*(1 - eta**2), -eta*(1 + xi)]
    dq(8, :) = [-0.5_wp*(1 - eta**2), -eta*(1 - xi)]
  end subroutine rotation_derivatives

  pure function midside_rotation(xl, k) result(tk)
    !! Rotation β = (βx, βy) at the midpoint of side k in terms of the element DOFs: β_k = tk u.
    real(wp), intent(in) :: xl(:, :)
    integer, intent(in) :: k
    real(wp) :: tk(2, NDN*size(xl, 2))
    real(wp) :: d(2), l2, p(2, 2)
    integer :: nodes(2), a, o
    nodes = [k, mod(k, size(xl, 2)) + 1]
    d = side_vector(xl, k)
    l2 = dot_product(d, d)
    ! β_k = P (β_i + β_j) - 3/(2 L²) (w_j - w_i) d with P = I/2 - 3/4 s sᵀ.
    p(1, :) = [0.5_wp - 0.75_wp*d(1)*d(1)/l2, -0.75_wp*d(1)*d(2)/l2]
    p(2, :) = [-0.75_wp*d(2)*d(1)/l2, 0.5_wp - 0.75_wp*d(2)*d(2)/l2]
    tk = 0.0_wp
    tk(:, NDN*(nodes(1) - 1) + 1) = 1.5_wp*d/l2
    tk(:, NDN*(nodes(2) - 1) + 1) = -1.5_wp*d/l2
    do a = 1, 2
       o = NDN*(nodes(a) - 1)
       ! β = (θy, -θx) at a corner.
       tk(:, o + 2) = -p(:, 2)
       tk(:, o + 3) = p(:, 1)
    end do
  end function midside_rotation

  pure subroutine curvature_matrix(xl, xi, eta, b, detj)
    !! Curvature-displacement matrix b(3, 3n) (κ = b u) and Jacobian determinant at (ξ, η).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: xi, eta
    real(wp), intent(out) :: b(:, :)
    real(wp), intent(out) :: detj
    real(wp) :: dg(size(xl, 2), 2), dq(2*size(xl, 2), 2), dx(2*size(xl, 2), 2)
    real(wp) :: jac(2, 2), jinv(2, 2), tk(2, NDN*size(xl, 2))
    integer :: n, i, k

    n = size(xl, 2)
    call geometry_derivatives(n, xi, eta, dg)
    call rotation_derivatives(n, xi, eta, dq)
    jac = matmul(xl, dg)               ! jac(a, b) = ∂x_a/∂ξ_b
    detj = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
    jinv(1, :) = [jac(2, 2), -jac(1, 2)]
    jinv(2, :) = [-jac(2, 1), jac(1, 1)]
    jinv = jinv/detj                   ! jinv(b, a) = ∂ξ_b/∂x_a
    dx = matmul(dq, jinv)              ! dx(i, a) = ∂N_i/∂x_a

    b = 0.0_wp
    do i = 1, n
       ! Corner i: βx = θy, βy = -θx.
       b(1, NDN*i) = dx(i, 1)
       b(2, NDN*i - 1) = -dx(i, 2)
       b(3, NDN*i) = dx(i, 2)
       b(3, NDN*i - 1) = -dx(i, 1)
    end do
    do k = 1, n
       tk = midside_rotation(xl, k)
       b(1, :) = b(1, :) + dx(n + k, 1)*tk(1, :)
       b(2, :) = b(2, :) + dx(n + k, 2)*tk(2, :)
       b(3, :) = b(3, :) + dx(n + k, 2)*tk(1, :) + dx(n + k, 1)*tk(2, :)
    end do
  end subroutine curvature_matrix

  pure subroutine plate_point_moments(xl, t, e, nu, ue, m_points, m_nodes, error)
    !! Moments per unit length (mx, my, mxy) from the local DOF values ue(3n) at
    !! the points where stresses are reported and at the nodes: DKT one point,
    !! the centroid (m_points(3, 1)), and the corners themselves (its curvature
    !! is linear, so this is the extrapolation of any points); DKQ the 2×2 Gauss
    !! points (m_points(3, 4), (ξ, η) = (-g, -g), (g, -g), (g, g), (-g, g),
    !! g = 1/√3, point k next to node k) and the corners by the bilinear
    !! extrapolation of the four values.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), allocatable, intent(out) :: m_points(:, :), m_nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: b(:, :)
    real(wp) :: db(NSTRAIN, NSTRAIN), detj, w(NQUAD)
    real(wp), parameter :: TRI_XI(NTRI) = [0.0_wp, 1.0_wp, 0.0_wp], TRI_ETA(NTRI) = [0.0_wp, 0.0_wp, 1.0_wp]
    integer :: n, k
    call check_element(xl, t, e, nu, error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(ue) /= NDN*n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    db = bending_rigidity(t, e, nu)
    allocate (b(NSTRAIN, size(ue)))
    allocate (m_nodes(NSTRAIN, n))
    if (n == NTRI) then
       allocate (m_points(NSTRAIN, 1))
       call curvature_matrix(xl, ONE_THIRD, ONE_THIRD, b, detj)
       m_points(:, 1) = matmul(db, matmul(b, ue))
       do k = 1, NTRI
          call curvature_matrix(xl, TRI_XI(k), TRI_ETA(k), b, detj)
          m_nodes(:, k) = matmul(db, matmul(b, ue))
       end do
       return
    end if
    allocate (m_points(NSTRAIN, NQUAD))
    do k = 1, NQUAD
       call curvature_matrix(xl, GAUSS2*QUAD_XI(k), GAUSS2*QUAD_ETA(k), b, detj)
       m_points(:, k) = matmul(db, matmul(b, ue))
    end do
    do k = 1, NQUAD
       ! bilinear functions of the Gauss points (corners of a square of half-side g) at node k
       w = (1 + sqrt(3.0_wp)*QUAD_XI(k)*QUAD_XI)*(1 + sqrt(3.0_wp)*QUAD_ETA(k)*QUAD_ETA)/4
       m_nodes(:, k) = matmul(m_points, w)
    end do
  end subroutine plate_point_moments
end module superjoin_elements_plate
