module superjoin_elements_quadratic
  !! Second-order plane elements in a 2D local frame (isoparametric, sides may
  !! be curved): the 6-node triangle (CPS6, CPE6) and the 8-node serendipity
  !! quadrilateral (CPS8, CPE8 with 3×3 Gauss points; CPS8R, CPE8R with 2×2
  !! reduced integration, as Abaqus), plane stress or plane strain.
  !!
  !! Node order (Abaqus): corners counter-clockwise, then the mid-side nodes,
  !! node 4 (triangle) or 5 (quadrilateral) between corners 1 and 2 and so on.
  !! Natural coordinates: triangle (ξ, η) = area coordinates L₂, L₃ of the
  !! corners 2 and 3; quadrilateral ξ, η in [-1, 1], corner 1 at (-1, -1).
  !! Element vectors and matrices are node-major (u, v per node).
  !!
  !! Integration: the triangle's stiffness with the 3-point rule of degree 2
  !! (Abaqus CPS6; exact for straight sides), its area, centroid and consistent
  !! area loads with the 6-point rule of degree 4. The quadrilateral's
  !! stiffness 3×3 or 2×2; area, centroid and loads 3×3.
  !!
  !! The 2×2 rule leaves one spurious zero-energy mode in a single CPS8R (the
  !! "hourglass" of the serendipity element, which adjacent elements suppress);
  !! as in Abaqus no control is added.
  !!
  !! Resultants (nx, ny, nxy = t σ) are evaluated at the centroid of the element
  !! area, mapped back to natural coordinates by Newton's method, as CPS4 does.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_membrane, only: plane_stress, plane_strain, check_plane_material, initial_strain_t, held_factor
  implicit none (type, external)
  private

  type, public :: plane_props_t
    !! Data of one second-order plane element.
     real(wp) :: t = 0.0_wp               !! thickness
     real(wp) :: e = 0.0_wp               !! Young's modulus
     real(wp) :: nu = 0.0_wp              !! Poisson's ratio
     logical :: strain = .false.          !! plane strain (else plane stress)
     logical :: reduced = .false.         !! 8-node: 2×2 Gauss points instead of 3×3
  end type plane_props_t

  real(wp), parameter, public :: QUAD_AREA_TOL = 1.0e-12_wp
    !! An element is degenerate when its area <= QUAD_AREA_TOL × (longest corner-to-corner
    !! distance)², and two nodes coincide when closer than QUAD_AREA_TOL × that distance.
  real(wp), parameter, public :: QUAD_JACOBIAN_TOL = 1.0e-12_wp
    !! det J must exceed QUAD_JACOBIAN_TOL × (area / reference area) at every integration
    !! point of the full rule and at the centre.

  integer, parameter :: NSTRAIN = 3
  real(wp), parameter :: ISOTROPIC(NSTRAIN) = [1.0_wp, 1.0_wp, 0.0_wp]   !! an isotropic in-plane strain
  integer, parameter :: NEWTON_MAX = 50            !! iterations of the inverse map to the centroid
  real(wp), parameter :: NEWTON_TOL = 1.0e-14_wp   !! on the natural coordinates
  real(wp), parameter :: XI_NODE(8) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp]
  real(wp), parameter :: ETA_NODE(8) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]
  real(wp), parameter :: G2 = 1/sqrt(3.0_wp)            !! 2-point Gauss abscissa
  real(wp), parameter :: G3 = sqrt(0.6_wp)              !! 3-point Gauss abscissa
  real(wp), parameter :: W3(3) = [5.0_wp, 8.0_wp, 5.0_wp]/9   !! 3-point Gauss weights
  ! Triangle rules (natural coordinates ξ = L₂, η = L₃; weights sum to 1/2, the reference area).
  real(wp), parameter :: TRI3_A = 1.0_wp/6, TRI3_B = 2.0_wp/3
  real(wp), parameter :: TRI6_A = 0.445948490915965_wp, TRI6_WA = 0.223381589678011_wp
  real(wp), parameter :: TRI6_B = 0.091576213509771_wp, TRI6_WB = 0.109951743655322_wp
  integer, parameter :: RULE_STIFFNESS = 1, RULE_FULL = 2   !! which rule: stiffness, or area and loads

  public :: quadratic_stiffness, quadratic_resultants, quadratic_shape_integrals, quadratic_shape
  public :: quadratic_point_stresses, quadratic_stress_points
  public :: quadratic_thermal_load, quadratic_centroid_weights

contains

  pure subroutine quadratic_stiffness(xl, props, ke, error)
    !! Stiffness ke(2n, 2n) of a 6- or 8-node plane element with nodes xl(2, n).
    real(wp), intent(in) :: xl(:, :)
    type(plane_props_t), intent(in) :: props
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: pts(:, :), wts(:), b(:, :)
    real(wp) :: d(NSTRAIN, NSTRAIN), jac
    integer :: k, n

    call check_element(xl, props, error)
    if (allocated(error)) return
    n = size(xl, 2)
    d = material(props)
    call rule(n, RULE_STIFFNESS, props%reduced, pts, wts)
    allocate (ke(2*n, 2*n), source=0.0_wp)
    allocate (b(NSTRAIN, 2*n))
    do k = 1, size(wts)
       call b_matrix(xl, pts(:, k), b, jac)
       ke = ke + (wts(k)*jac)*matmul(transpose(b), matmul(d, b))
    end do
    ke = 0.5_wp*(ke + transpose(ke))
  end subroutine quadratic_stiffness

  pure subroutine quadratic_resultants(xl, props, ue, nres, error, eps0)
    !! Resultants nres = (nx, ny, nxy) = t σ at the area centroid from the element
    !! displacements ue(2n) (node-major u, v). Plane strain: σz = ν (σx + σy) is
    !! not returned. With eps0(n), the nodal values of an isotropic initial
    !! strain (quadratic_thermal_load): t D (ε - ε0) at the centroid.
    real(wp), intent(in) :: xl(:, :)
    type(plane_props_t), intent(in) :: props
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: nres(NSTRAIN)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: eps0(:)
    real(wp), allocatable :: b(:, :)
    real(wp) :: p(2), jac, nf(size(xl, 2)), dn(2, size(xl, 2))

    nres = 0.0_wp
    call check_element(xl, props, error)
    if (allocated(error)) return
    if (size(ue) /= 2*size(xl, 2)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    p = centroid_natural(xl)
    allocate (b(NSTRAIN, 2*size(xl, 2)))
    call b_matrix(xl, p, b, jac)
    nres = matmul(material(props), matmul(b, ue))
    if (present(eps0)) then
       call quadratic_shape(size(xl, 2), p, nf, dn)
       nres = nres - dot_product(nf, eps0)*matmul(material(props), ISOTROPIC)
    end if
  end subroutine quadratic_resultants

  pure subroutine quadratic_centroid_weights(xl, w)
    !! The shape functions w(n) at the area centroid, where the resultants are evaluated.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(out) :: w(size(xl, 2))
    real(wp) :: dn(2, size(xl, 2))
    call quadratic_shape(size(xl, 2), centroid_natural(xl), w, dn)
  end subroutine quadratic_centroid_weights

  pure subroutine quadratic_thermal_load(xl, props, eps0, fe, error, self_energy)
    !! Consistent nodal loads fe(2n) = ∫ Bᵀ t D ε0 dA (element frame, node-major
    !! u, v) of an isotropic initial strain ε0 (1, 1, 0) whose nodal values
    !! eps0(n) are interpolated with the shape functions to the points of the
    !! stiffness rule, as CalculiX interpolates nodal temperatures (plane
    !! strain: eps0 is the in-plane strain (1 + ν) α ΔT). self_energy: ½ ∫ ε0ᵀ t D ε0 dA
    !! by the same rule, plane strain times held_factor (the constant of the
    !! element's energy ½ uᵀ K u - uᵀ fe + self_energy of its mechanical strains).
    real(wp), intent(in) :: xl(:, :)
    type(plane_props_t), intent(in) :: props
    real(wp), intent(in) :: eps0(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(out), optional :: self_energy
    real(wp), allocatable :: pts(:, :), wts(:), b(:, :)
    real(wp) :: s0(NSTRAIN), jac, nf(size(xl, 2)), dn(2, size(xl, 2)), e0, sum_e0
    integer :: k, n

    call check_element(xl, props, error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(eps0) /= n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodal initial strains')
       return
    end if
    s0 = matmul(material(props), ISOTROPIC)
    call rule(n, RULE_STIFFNESS, props%reduced, pts, wts)
    allocate (b(NSTRAIN, 2*n), fe(2*n), source=0.0_wp)
    sum_e0 = 0.0_wp
    do k = 1, size(wts)
       call b_matrix(xl, pts(:, k), b, jac)
       call quadratic_shape(n, pts(:, k), nf, dn)
       e0 = dot_product(nf, eps0)
       fe = fe + wts(k)*jac*e0*matmul(transpose(b), s0)
       sum_e0 = sum_e0 + wts(k)*jac*e0**2
    end do
    if (present(self_energy)) self_energy = 0.5_wp*sum_e0*dot_product(ISOTROPIC, s0)*held_factor(props%strain, props%nu)
  end subroutine quadratic_thermal_load

  pure subroutine quadratic_shape_integrals(xl, w)
    !! w(i) = ∫ Nᵢ dA over the element (consistent nodal shares of a uniform
    !! load per unit area; corners of a straight-sided 8-node element get
    !! -A/12, mid-side nodes A/3; of a 6-node triangle 0 and A/3).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(out) :: w(size(xl, 2))
    real(wp), allocatable :: pts(:, :), wts(:)
    real(wp) :: nf(size(xl, 2)), dn(2, size(xl, 2)), jm(2, 2)
    integer :: k, n

    n = size(xl, 2)
    w = 0.0_wp
    call rule(n, RULE_FULL, .false., pts, wts)
    do k = 1, size(wts)
       call quadratic_shape(n, pts(:, k), nf, dn)
       jm = matmul(dn, transpose(xl))
       w = w + wts(k)*det2(jm)*nf
    end do
  end subroutine quadratic_shape_integrals

  pure subroutine quadratic_shape(n, p, nf, dn)
    !! Shape functions nf(n) and their natural derivatives dn(2, n) at p = (ξ, η)
    !! of the 6-node triangle (n = 6) or the 8-node quadrilateral (n = 8).
    integer, intent(in) :: n
    real(wp), intent(in) :: p(2)
    real(wp), intent(out) :: nf(n), dn(2, n)
    real(wp) :: l(3), dl(2, 3), s, t
    integer :: i, j

    if (n == 6) then
       l = [1 - p(1) - p(2), p(1), p(2)]
       dl(:, 1) = [-1.0_wp, -1.0_wp]
       dl(:, 2) = [1.0_wp, 0.0_wp]
       dl(:, 3) = [0.0_wp, 1.0_wp]
       do i = 1, 3
          j = modulo(i, 3) + 1
          nf(i) = l(i)*(2*l(i) - 1)
          dn(:, i) = (4*l(i) - 1)*dl(:, i)
          nf(3 + i) = 4*l(i)*l(j)
          dn(:, 3 + i) = 4*(dl(:, i)*l(j) + l(i)*dl(:, j))
       end do
       return
    end if
    do i = 1, 8
       s = XI_NODE(i)
       t = ETA_NODE(i)
       if (i <= 4) then
          nf(i) = (1 + s*p(1))*(1 + t*p(2))*(s*p(1) + t*p(2) - 1)/4
          dn(1, i) = s*(1 + t*p(2))*(2*s*p(1) + t*p(2))/4
          dn(2, i) = t*(1 + s*p(1))*(s*p(1) + 2*t*p(2))/4
       else if (s == 0.0_wp) then
          nf(i) = (1 - p(1)**2)*(1 + t*p(2))/2
          dn(1, i) = -p(1)*(1 + t*p(2))
          dn(2, i) = t*(1 - p(1)**2)/2
       else
          nf(i) = (1 + s*p(1))*(1 - p(2)**2)/2
          dn(1, i) = s*(1 - p(2)**2)/2
          dn(2, i) = -p(2)*(1 + s*p(1))
       end if
    end do
  end subroutine quadratic_shape

  pure subroutine quadratic_point_stresses(xl, props, ue, sig_points, sig_nodes, error, eps0)
    !! Stresses (σx, σy, τxy) in the element frame from the element displacements
    !! ue(2n) (node-major u, v): sig_points(3, k) at the integration points of the
    !! stiffness rule (quadratic_stress_points: CPS6 3 points, CPS8 3×3, CPS8R 2×2,
    !! point k next to node k for the corner points), sig_nodes(3, n) extrapolated
    !! to the nodes as CalculiX and Abaqus do: the unique polynomial through the
    !! point values (linear through the triangle's 3 points, bilinear through 2×2,
    !! biquadratic through 3×3) evaluated at the nodes. The extrapolation is exact
    !! whenever the stress is such a polynomial (constant stress on any element,
    !! linear stress on straight-sided triangles and parallelograms). Plane strain:
    !! σz = ν (σx + σy) is added by the caller. With eps0 (eps0%nodal(n), the
    !! nodal values of an isotropic initial strain, quadratic_thermal_load),
    !! σ = D (ε - ε0) with ε0 interpolated to each point, and eps0%points,
    !! eps0%nodes the ε0 there (extrapolated as σ is).
    real(wp), intent(in) :: xl(:, :)
    type(plane_props_t), intent(in) :: props
    real(wp), intent(in) :: ue(:)
    real(wp), allocatable, intent(out) :: sig_points(:, :), sig_nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(initial_strain_t), intent(inout), optional :: eps0
    real(wp), allocatable :: pts(:, :), wts(:), b(:, :), ep(:)
    real(wp) :: d(NSTRAIN, NSTRAIN), jac, pn(2), nf(size(xl, 2)), dn(2, size(xl, 2))
    integer :: k, n

    call check_element(xl, props, error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(ue) /= 2*n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    d = material(props)/props%t
    call rule(n, RULE_STIFFNESS, props%reduced, pts, wts)
    allocate (b(NSTRAIN, 2*n), sig_points(NSTRAIN, size(wts)), sig_nodes(NSTRAIN, n))
    allocate (ep(size(wts)), source=0.0_wp)
    do k = 1, size(wts)
       call b_matrix(xl, pts(:, k), b, jac)
       ! σ = D (ε - ε₀): an initial strain interpolated from its nodal values
       if (present(eps0)) then
          call quadratic_shape(n, pts(:, k), nf, dn)
          ep(k) = dot_product(nf, eps0%nodal)
       end if
       sig_points(:, k) = matmul(d, matmul(b, ue) - ep(k)*ISOTROPIC)
    end do
    if (present(eps0)) then
       if (allocated(eps0%nodes)) deallocate (eps0%nodes)
       allocate (eps0%nodes(n))
    end if
    do k = 1, n
       pn = node_natural(n, k)
       sig_nodes(:, k) = matmul(sig_points, point_weights(n, props%reduced, pn))
       if (present(eps0)) eps0%nodes(k) = dot_product(ep, point_weights(n, props%reduced, pn))
    end do
    if (present(eps0)) eps0%points = ep
  end subroutine quadratic_point_stresses

  pure subroutine quadratic_stress_points(n, reduced, pts)
    !! Natural coordinates pts(2, k) of the points where quadratic_point_stresses
    !! reports stresses (the stiffness rule of a 6- or 8-node element).
    integer, intent(in) :: n
    logical, intent(in) :: reduced
    real(wp), allocatable, intent(out) :: pts(:, :)
    real(wp), allocatable :: wts(:)
    call rule(n, RULE_STIFFNESS, reduced, pts, wts)
  end subroutine quadratic_stress_points

  ! ------------------------------------------------------------ internals

  pure function node_natural(n, k) result(p)
    !! Natural coordinates of node k of the 6-node triangle or 8-node quadrilateral.
    integer, intent(in) :: n, k
    real(wp) :: p(2)
    real(wp), parameter :: TRI_XI(6) = [0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp]
    real(wp), parameter :: TRI_ETA(6) = [0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp]
    if (n == 6) then
       p = [TRI_XI(k), TRI_ETA(k)]
    else
       p = [XI_NODE(k), ETA_NODE(k)]
    end if
  end function node_natural

  pure function point_weights(n, reduced, p) result(w)
    !! Weights w(k) of the values at the stress points (quadratic_stress_points)
    !! of the polynomial through them, evaluated at the natural point p: the
    !! linear interpolant through the triangle's 3 points (1/6, 1/6), (2/3, 1/6),
    !! (1/6, 2/3); the bilinear one through 2×2 Gauss points, the biquadratic
    !! (Lagrange) one through 3×3, in the points' own coordinates ξ/g.
    integer, intent(in) :: n
    logical, intent(in) :: reduced
    real(wp), intent(in) :: p(2)
    real(wp), allocatable :: w(:)
    real(wp) :: a, b, la(3), lb(3)
    integer :: i, j
    if (n == 6) then
       ! the points are the corners of the triangle (1/6, 1/6) + (1/2) (reference triangle)
       a = (p(1) - TRI3_A)/(TRI3_B - TRI3_A)
       b = (p(2) - TRI3_A)/(TRI3_B - TRI3_A)
       w = [1 - a - b, a, b]
    else if (reduced) then
       a = p(1)/G2
       b = p(2)/G2
       w = [(1 - a)*(1 - b), (1 + a)*(1 - b), (1 + a)*(1 + b), (1 - a)*(1 + b)]/4
    else
       a = p(1)/G3
       b = p(2)/G3
       la = [a*(a - 1)/2, 1 - a**2, a*(a + 1)/2]
       lb = [b*(b - 1)/2, 1 - b**2, b*(b + 1)/2]
       allocate (w(9))
       do j = 1, 3
          do i = 1, 3
             w(i + 3*(j - 1)) = la(i)*lb(j)
          end do
       end do
    end if
  end function point_weights


  pure function material(props) result(d)
    !! t D for the element's state.
    type(plane_props_t), intent(in) :: props
    real(wp) :: d(NSTRAIN, NSTRAIN)
    if (props%strain) then
       d = props%t*plane_strain(props%e, props%nu)
    else
       d = props%t*plane_stress(props%e, props%nu)
    end if
  end function material

  pure subroutine rule(n, which, reduced, pts, wts)
    !! Integration points pts(2, k) and weights wts(k) in natural coordinates:
    !! RULE_STIFFNESS (triangle 3 points; quadrilateral 3×3, or 2×2 if reduced)
    !! or RULE_FULL (triangle 6 points of degree 4; quadrilateral 3×3).
    integer, intent(in) :: n, which
    logical, intent(in) :: reduced
    real(wp), allocatable, intent(out) :: pts(:, :), wts(:)
    real(wp) :: a(3)
    integer :: i, j, k

    if (n == 6) then
       if (which == RULE_STIFFNESS) then
          pts = reshape([TRI3_A, TRI3_A, TRI3_B, TRI3_A, TRI3_A, TRI3_B], [2, 3])
          wts = [1.0_wp, 1.0_wp, 1.0_wp]/6
       else
          pts = reshape([TRI6_A, TRI6_A, 1 - 2*TRI6_A, TRI6_A, TRI6_A, 1 - 2*TRI6_A, &
               TRI6_B, TRI6_B, 1 - 2*TRI6_B, TRI6_B, TRI6_B, 1 - 2*TRI6_B], [2, 6])
          wts = [TRI6_WA, TRI6_WA, TRI6_WA, TRI6_WB, TRI6_WB, TRI6_WB]/2
       end if
       return
    end if
    if (which == RULE_STIFFNESS .and. reduced) then
       pts = reshape([-G2, -G2, G2, -G2, G2, G2, -G2, G2], [2, 4])
       wts = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]
       return
    end if
    a = [-G3, 0.0_wp, G3]
    allocate (pts(2, 9), wts(9))
    k = 0
    do j = 1, 3
       do i = 1, 3
          k = k + 1
          pts(:, k) = [a(i), a(j)]
          wts(k) = W3(i)*W3(j)
       end do
    end do
  end subroutine rule

  pure real(wp) function det2(a)
    !! Determinant of a 2×2 matrix.
    real(wp), intent(in) :: a(2, 2)
    det2 = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
  end function det2

  pure subroutine b_matrix(xl, p, b, jac)
    !! Strain-displacement matrix b(3, 2n) (εx, εy, γxy) at p and det J
    !! (b = 0 where det J <= 0).
    real(wp), intent(in) :: xl(:, :), p(2)
    real(wp), intent(out) :: b(:, :), jac
    real(wp) :: nf(size(xl, 2)), dn(2, size(xl, 2)), dxy(2, size(xl, 2)), jm(2, 2), adj(2, 2)
    integer :: i

    call quadratic_shape(size(xl, 2), p, nf, dn)
    jm = matmul(dn, transpose(xl))        ! jm(a, b) = ∂x_b/∂ξ_a
    jac = det2(jm)
    b = 0.0_wp
    if (.not. (jac > 0.0_wp)) return
    adj(1, :) = [jm(2, 2), -jm(1, 2)]
    adj(2, :) = [-jm(2, 1), jm(1, 1)]
    dxy = matmul(adj, dn)/jac
    do i = 1, size(xl, 2)
       b(1, 2*i - 1) = dxy(1, i)
       b(2, 2*i) = dxy(2, i)
       b(3, 2*i - 1) = dxy(2, i)
       b(3, 2*i) = dxy(1, i)
    end do
  end subroutine b_matrix

  pure subroutine area_moments(xl, area, xc)
    !! Area and centroid of the element (full rule).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(out) :: area, xc(2)
    real(wp), allocatable :: pts(:, :), wts(:)
    real(wp) :: nf(size(xl, 2)), dn(2, size(xl, 2)), da
    integer :: k

    area = 0.0_wp
    xc = 0.0_wp
    call rule(size(xl, 2), RULE_FULL, .false., pts, wts)
    do k = 1, size(wts)
       call quadratic_shape(size(xl, 2), pts(:, k), nf, dn)
       da = wts(k)*det2(matmul(dn, transpose(xl)))
       area = area + da
       xc = xc + da*matmul(xl, nf)
    end do
    if (area > 0.0_wp) xc = xc/area
  end subroutine area_moments

  pure function centre(n) result(p)
    !! Natural coordinates of the centre of the reference element.
    integer, intent(in) :: n
    real(wp) :: p(2)
    p = 0.0_wp
    if (n == 6) p = 1.0_wp/3
  end function centre

  pure function centroid_natural(xl) result(p)
    !! Natural coordinates of the area centroid (Newton's method from the centre).
    real(wp), intent(in) :: xl(:, :)
    real(wp) :: p(2)
    real(wp) :: nf(size(xl, 2)), dn(2, size(xl, 2)), jm(2, 2), r(2), dp(2), area, xc(2)
    integer :: it

    call area_moments(xl, area, xc)
    p = centre(size(xl, 2))
    do it = 1, NEWTON_MAX
       call quadratic_shape(size(xl, 2), p, nf, dn)
       r = matmul(xl, nf) - xc
       jm = matmul(dn, transpose(xl))
       if (.not. (det2(jm) > 0.0_wp)) exit
       ! x(p) - xc = 0: Jᵀ dp = -r, (Jᵀ)⁻¹ = adj(J)ᵀ / det J
       dp = -[jm(2, 2)*r(1) - jm(2, 1)*r(2), -jm(1, 2)*r(1) + jm(1, 1)*r(2)]/det2(jm)
       p = p + dp
       if (maxval(abs(dp)) <= NEWTON_TOL) return
    end do
    ! no convergence (an element so distorted that its centroid maps badly): the centre
    p = centre(size(xl, 2))
  end function centroid_natural

  pure subroutine check_element(xl, props, error)
    !! Data checks: node count, material (t, E, nu), distinct nodes, positive
    !! area and det J > 0 at the points of the full rule and at the centre.
    real(wp), intent(in) :: xl(:, :)
    type(plane_props_t), intent(in) :: props
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: pts(:, :), wts(:), b(:, :)
    real(wp) :: area, xc(2), lmax2, jac, ref_area
    integer :: n, nc, i, j, k

    n = size(xl, 2)
    if (size(xl, 1) /= 2 .or. (n /= 6 .and. n /= 8)) then
       call fatal_error(error, EXIT_DECK, 'a second-order plane element needs 6 or 8 nodes in a 2D frame')
       return
    end if
    call check_plane_material(props%t, props%e, props%nu, merge('plane strain', 'plane stress', props%strain), &
         error)
    if (allocated(error)) return
    nc = n/2
    lmax2 = 0.0_wp
    do j = 1, nc
       do i = 1, j - 1
          lmax2 = max(lmax2, sum((xl(:, j) - xl(:, i))**2))
       end do
    end do
    do j = 1, n
       do i = 1, j - 1
          if (sum((xl(:, j) - xl(:, i))**2) <= QUAD_AREA_TOL**2*lmax2) then
             call fatal_error(error, EXIT_DECK, 'coincident nodes')
             return
          end if
       end do
    end do
    call area_moments(xl, area, xc)
    if (.not. (area > QUAD_AREA_TOL*lmax2)) then
       call fatal_error(error, EXIT_DECK, 'zero or negative area (nodes clockwise or coincident)')
       return
    end if
    ref_area = merge(0.5_wp, 4.0_wp, n == 6)
    call rule(n, RULE_FULL, .false., pts, wts)
    allocate (b(NSTRAIN, 2*n))
    do k = 0, size(wts)
       if (k == 0) then
          call b_matrix(xl, centre(n), b, jac)
       else
          call b_matrix(xl, pts(:, k), b, jac)
       end if
       if (.not. (jac > QUAD_JACOBIAN_TOL*area/ref_area)) then
          call fatal_error(error, EXIT_DECK, 'non-positive Jacobian (distorted element or misplaced mid-side node)')
          return
       end if
    end do
  end subroutine check_element
end module superjoin_elements_quadratic
