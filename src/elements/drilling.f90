module superjoin_elements_drilling
  !! Membranes with true drilling rotations (u, v, θz per node) for the flat
  !! shells: the Allman (1984) triangle and the Ibrahimbegovic-Taylor-Wilson
  !! (1990) quadrilateral, in the hierarchical form both papers share.
  !!
  !! Displacement field: the linear (triangle) or bilinear (quadrilateral)
  !! interpolation of the nodal (u, v) plus, on every edge k from node i to node
  !! j (counter-clockwise), a quadratic edge bubble P_k (4 Lᵢ Lⱼ on the triangle,
  !! the serendipity midside function on the quadrilateral, 1 at the midside)
  !! times the midside correction that the nodal rotations imply for a normal
  !! displacement quadratic along the edge whose slopes at the ends are θᵢ, θⱼ:
  !!   Δu_k = (l_k/8)(θⱼ - θᵢ) n_k = (θⱼ - θᵢ)/8 (yⱼ - yᵢ, -(xⱼ - xᵢ)),
  !! n_k the outward normal, l_k the edge length. A constant θ adds nothing, so
  !! without more the element has a fourth zero-energy mode (equal θ, u = v = 0),
  !! which the Hughes-Brezzi penalty on the skew-symmetric part of the
  !! displacement gradient removes:
  !!   ½ γ t ∫ (ω - θ)² dA,  ω = (∂v/∂x - ∂u/∂y)/2 of the full field (edge
  !!   bubbles included),  θ = Σ Nᵢ θᵢ (corner functions),  γ = DRILL_PENALTY G.
  !!
  !! Triangle (Allman): strains linear, stiffness exact with the three midside
  !! points; the penalty acts on the element means, ½ γ t A (θ̄ - ω̄)² (an
  !! independent skew-symmetric stress constant in the element).
  !! Quadrilateral (Ibrahimbegovic-Taylor-Wilson): 2×2 Gauss for the strains and
  !! the penalty (γ = G as in their paper), plus the incompatible modes
  !! 1 - ξ², 1 - η² of QM6 (superjoin_elements_membrane) in u and v with Taylor's
  !! correction, condensed statically. Measured on the MacNeal-Harder straight
  !! cantilever (6 × 1, in-plane shear, tip / 0.1081; regular, trapezoidal,
  !! parallelogram) and the 48 × 4 mesh, with tests/shells/verify_drilling.py
  !! for the shells:
  !!   without modes, mean penalty (γ = G):  0.904 0.811 0.898, 48×4 0.992
  !!   without modes, 2×2 penalty:           0.904 0.785 0.799
  !!   modes, mean penalty:                  0.993 0.910 0.984, 48×4 1.201 (a
  !!                                         spurious mode: 4 zero eigenvalues)
  !!   modes, 2×2 penalty (this element):    0.993 0.888 0.962, 48×4 0.9994
  !! (γ = 0.01 G: the same on the cantilever, the twisted beam 1.04 / 1.09 and
  !! Scordelis-Lo 4 × 4 1.21 too flexible, so γ = G.) For the triangle the mean
  !! penalty with γ = G: 0.158 0.161 0.110, 48×4 0.894 (γ = 0.01 G: 0.218, 0.922).
  !!
  !! Edge masks (the optional `edges` arguments): an edge without its bubble
  !! stays straight; superjoin_elements_drill_mask keeps the bubbles of S4/S4R
  !! on flat regions only (an edge's two nodes flat and not restraining its
  !! in-plane normal translation), so the mask is a property of the edge and
  !! the two elements sharing it agree. The quadrilateral's 2×2 penalty holds
  !! θz under any mask (three zero eigenvalues); the triangle's mean penalty
  !! does not, so it is used with all its bubbles only.
  !!
  !! Patch test: a linear displacement field with θ equal to its (constant)
  !! rotation makes every Δu_k vanish and the penalty zero; the incompatible
  !! modes have zero mean strain on any shape; the integrals of the bubble
  !! derivatives are exact with the rules above. A shared edge has the same Δu_k
  !! in both its elements (normal and θⱼ - θᵢ both change sign): the nodal field
  !! is conforming. Boundary edges under a traction carry consistent edge moments
  !! (±σnn l²/12 at the ends) that superjoin's loads do not apply (as Abaqus and
  !! CalculiX apply none to drilling rotations): the loss is of higher order.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_membrane, only: plane_stress, check_membrane_element, spd_solve
  implicit none (type, external)
  private

  public :: drilling_stiffness, drilling_resultants, drilling_point_stresses, drilling_result_operator
  public :: drilling_thermal_load, drilling_thermal_stresses

  real(wp), parameter, public :: DRILL_PENALTY = 1.0_wp
    !! γ / G of the skew-symmetric penalty (Ibrahimbegovic-Taylor-Wilson: γ = G).
  integer, parameter :: NSTRAIN = 3
  real(wp), parameter :: GP = 1/sqrt(3.0_wp)
  real(wp), parameter :: XI_NODE(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]
  real(wp), parameter :: ETA_NODE(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
  integer, parameter :: NPOINT_QUAD = 4, NPOINT_TRI = 3
  integer, parameter :: NMODE = 4
  real(wp), parameter :: ISOTROPIC_STRAIN(NSTRAIN) = [1.0_wp, 1.0_wp, 0.0_wp]
    !! an isotropic in-plane strain of unit size (εx, εy, γxy)
    !! incompatible modes of the quadrilateral (QM6's 1 - ξ², 1 - η² in u and v)
    !! the quadrilateral with the incompatible modes (see the module header)

  type :: point_t
     !! Strain and rotation rows of the element at one point.
     real(wp), allocatable :: b(:, :)
       !! (εx, εy, γxy) = b d, d = (u, v, θz) node-major
     real(wp), allocatable :: w(:)
       !! ω - θ = w . d, θ interpolated by the corner functions
     real(wp) :: weight = 0.0_wp
       !! integration weight (area share)
     real(wp) :: ba(NSTRAIN, NMODE) = 0.0_wp
       !! strains of the incompatible modes (quadrilateral)
  end type point_t

contains

  pure subroutine drilling_stiffness(xl, t, e, nu, ke, error, edges)
    !! Stiffness ke(3n, 3n) of the Allman triangle (n = 3) or the
    !! Ibrahimbegovic-Taylor-Wilson quadrilateral (n = 4), node-major (u, v, θz),
    !! in the local frame xl(2, n) (nodes counter-clockwise), thickness t.
    !! edges(k) (optional, default all true): edge k (node k to k + 1) has its
    !! bubble; without it the edge stays straight (u, v linear along it).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    type(point_t), allocatable :: pts(:)
    real(wp), allocatable :: g(:), kda(:, :)
    real(wp) :: d(NSTRAIN, NSTRAIN), area, kaa(NMODE, NMODE)
    integer :: n, k, j
    logical :: ed(size(xl, 2))

    call check_membrane_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    n = size(xl, 2)
    d = t*plane_stress(e, nu)
    ed = .true.
    if (present(edges)) ed = edges(1:n)
    call points(xl, ed, pts)
    allocate (ke(3*n, 3*n), g(3*n), kda(3*n, NMODE), source=0.0_wp)
    kaa = 0.0_wp
    area = 0.0_wp
    do k = 1, size(pts)
       ke = ke + pts(k)%weight*matmul(transpose(pts(k)%b), matmul(d, pts(k)%b))
       kda = kda + pts(k)%weight*matmul(transpose(pts(k)%b), matmul(d, pts(k)%ba))
       kaa = kaa + pts(k)%weight*matmul(transpose(pts(k)%ba), matmul(d, pts(k)%ba))
       g = g + pts(k)%weight*pts(k)%w
       area = area + pts(k)%weight
    end do
    g = g/area
    if (n == 4) then
       ke = ke - matmul(kda, spd_solve(kaa, transpose(kda)))
       do k = 1, size(pts)
          do j = 1, 3*n
             ke(:, j) = ke(:, j) + DRILL_PENALTY*e/(2*(1 + nu))*t*pts(k)%weight*pts(k)%w(j)*pts(k)%w
          end do
       end do
    else
       do j = 1, 3*n
          ke(:, j) = ke(:, j) + DRILL_PENALTY*e/(2*(1 + nu))*t*area*g(j)*g
       end do
    end if
    ke = 0.5_wp*(ke + transpose(ke))
  end subroutine drilling_stiffness

  pure subroutine drilling_resultants(xl, t, e, nu, ue, nres, error, edges)
    !! Membrane resultants nres = (nx, ny, nxy) = t σ at the centroid of the
    !! natural coordinates (triangle: area centroid; quadrilateral: ξ = η = 0)
    !! from ue(3n) = (u, v, θz) node-major; edges as drilling_stiffness.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: nres(NSTRAIN)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    type(point_t) :: p
    logical :: ed(size(xl, 2))
    nres = 0.0_wp
    call check_membrane_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    if (size(ue) /= 3*size(xl, 2)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    ed = .true.
    if (present(edges)) ed = edges(1:size(xl, 2))
    if (size(xl, 2) == 3) then
       p = point_tri(xl, [1.0_wp, 1.0_wp, 1.0_wp]/3, 0.0_wp, ed)
       nres = t*matmul(plane_stress(e, nu), matmul(p%b, ue))
    else
       p = point_quad(xl, 0.0_wp, 0.0_wp, 0.0_wp, ed)
       nres = t*matmul(plane_stress(e, nu), matmul(p%b, ue) + matmul(p%ba, modes(xl, e, nu, ue, ed)))
    end if
  end subroutine drilling_resultants

  pure subroutine drilling_result_operator(xl, t, e, nu, op, error, edges)
    !! The operator op(3, 3n) of drilling_resultants: nres = op ue for every
    !! ue(3n) = (u, v, θz) node-major, op = t D b at the centroid of the
    !! natural coordinates. The quadrilateral's incompatible modes drop out
    !! there (their strains, from -2ξ and -2η, vanish at ξ = η = 0:
    !! drilling_resultants adds b_a α = 0). Formed once, it serves every step
    !! and every instance of a part; edges as drilling_stiffness.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: op(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    type(point_t) :: p
    logical :: ed(size(xl, 2))
    call check_membrane_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    ed = .true.
    if (present(edges)) ed = edges(1:size(xl, 2))
    if (size(xl, 2) == 3) then
       p = point_tri(xl, [1.0_wp, 1.0_wp, 1.0_wp]/3, 0.0_wp, ed)
    else
       p = point_quad(xl, 0.0_wp, 0.0_wp, 0.0_wp, ed)
    end if
    op = t*matmul(plane_stress(e, nu), p%b)
  end subroutine drilling_result_operator

  pure subroutine drilling_point_stresses(xl, e, nu, ue, sig_points, sig_nodes, error, edges)
    !! Stresses (σx, σy, τxy) from ue(3n) = (u, v, θz): the triangle's
    !! centroid (sig_points(3, 1)), the quadrilateral's 2×2 Gauss points in the
    !! order of superjoin_elements_membrane's membrane_point_stresses (the point
    !! next to node k k-th); sig_nodes(3, n) at the nodes (the strain field of
    !! the element evaluated there: it is linear on the triangle, and on the
    !! quadrilateral the bilinear field through the Gauss values extrapolated,
    !! as membrane_point_stresses does); edges as drilling_stiffness.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), allocatable, intent(out) :: sig_points(:, :), sig_nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    logical :: ed(size(xl, 2))
    type(point_t) :: p
    real(wp) :: d(NSTRAIN, NSTRAIN), lc(3), alpha(NMODE)
    integer :: k, n
    call check_membrane_element(xl, 1.0_wp, e, nu, 'plane stress', error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(ue) /= 3*n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    d = plane_stress(e, nu)
    ed = .true.
    if (present(edges)) ed = edges(1:n)
    if (n == 3) then
       allocate (sig_points(NSTRAIN, 1), sig_nodes(NSTRAIN, 3))
       p = point_tri(xl, [1.0_wp, 1.0_wp, 1.0_wp]/3, 0.0_wp, ed)
       sig_points(:, 1) = matmul(d, matmul(p%b, ue))
       do k = 1, 3
          lc = 0.0_wp
          lc(k) = 1.0_wp
          p = point_tri(xl, lc, 0.0_wp, ed)
          sig_nodes(:, k) = matmul(d, matmul(p%b, ue))
       end do
       return
    end if
    allocate (sig_points(NSTRAIN, 4), sig_nodes(NSTRAIN, 4))
    alpha = modes(xl, e, nu, ue, ed)
    do k = 1, 4
       p = point_quad(xl, GP*XI_NODE(k), GP*ETA_NODE(k), 0.0_wp, ed)
       sig_points(:, k) = matmul(d, matmul(p%b, ue) + matmul(p%ba, alpha))
    end do
    do k = 1, 4
       sig_nodes(:, k) = matmul(sig_points, bilinear(sqrt(3.0_wp)*XI_NODE(k), sqrt(3.0_wp)*ETA_NODE(k)))
    end do
  end subroutine drilling_point_stresses

  pure subroutine drilling_thermal_load(xl, t, e, nu, eps0, fe, error, edges, self_energy)
    !! Consistent nodal loads fe(3n) = ∫ Bᵀ t D ε0 dA (node-major u, v, θz) of
    !! an isotropic initial strain ε0 (1, 1, 0) whose nodal values eps0(n) are
    !! interpolated with the corner functions to the points of the stiffness;
    !! the quadrilateral's incompatible modes take their share before they are
    !! condensed (f_d - K_da K_aa⁻¹ f_a); the penalty has no initial strain.
    !! edges as drilling_stiffness. self_energy: the constant of the element's
    !! energy ½ uᵀ K u - uᵀ fe + self_energy, ½ ∫ ε0ᵀ t D ε0 dA by the same points
    !! less the modes' share ½ f_aᵀ K_aa⁻¹ f_a.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: eps0(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    real(wp), intent(out), optional :: self_energy
    type(point_t), allocatable :: pts(:)
    real(wp), allocatable :: kda(:, :)
    real(wp) :: d(NSTRAIN, NSTRAIN), kaa(NMODE, NMODE), fa(NMODE, 1), s0(NSTRAIN), ma(NMODE, 1), e0, sum_e0
    integer :: n, k
    logical :: ed(size(xl, 2))
    call check_membrane_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(eps0) /= n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodal initial strains')
       return
    end if
    d = t*plane_stress(e, nu)
    ed = .true.
    if (present(edges)) ed = edges(1:n)
    call points(xl, ed, pts)
    allocate (fe(3*n), kda(3*n, NMODE), source=0.0_wp)
    kaa = 0.0_wp
    fa = 0.0_wp
    sum_e0 = 0.0_wp
    do k = 1, size(pts)
       e0 = point_strain(xl, k, eps0)
       s0 = pts(k)%weight*e0*matmul(d, ISOTROPIC_STRAIN)
       fe = fe + matmul(transpose(pts(k)%b), s0)
       fa(:, 1) = fa(:, 1) + matmul(transpose(pts(k)%ba), s0)
       kda = kda + pts(k)%weight*matmul(transpose(pts(k)%b), matmul(d, pts(k)%ba))
       kaa = kaa + pts(k)%weight*matmul(transpose(pts(k)%ba), matmul(d, pts(k)%ba))
       sum_e0 = sum_e0 + pts(k)%weight*e0**2
    end do
    if (present(self_energy)) self_energy = 0.5_wp*sum_e0*dot_product(ISOTROPIC_STRAIN, matmul(d, ISOTROPIC_STRAIN))
    if (n /= 4) return
    ma = spd_solve(kaa, fa)
    fe = fe - reshape(matmul(kda, ma), [3*n])
    if (present(self_energy)) self_energy = self_energy - 0.5_wp*dot_product(fa(:, 1), ma(:, 1))
  end subroutine drilling_thermal_load

  pure subroutine drilling_thermal_stresses(xl, t, e, nu, eps0, nres, sig_points, sig_nodes, error, edges)
    !! What an isotropic initial strain with the nodal values eps0(n) adds to
    !! the results of drilling_resultants and drilling_point_stresses at zero
    !! nodal displacements (σ = D (ε - ε0), the quadrilateral's modes α =
    !! K_aa⁻¹ f_a): nres = t σ at the centre, sig_points and sig_nodes at the
    !! points and nodes of drilling_point_stresses; edges as drilling_stiffness.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: eps0(:)
    real(wp), intent(out) :: nres(NSTRAIN)
    real(wp), allocatable, intent(out) :: sig_points(:, :), sig_nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    type(point_t), allocatable :: pts(:)
    type(point_t) :: p
    real(wp) :: d(NSTRAIN, NSTRAIN), kaa(NMODE, NMODE), fa(NMODE, 1), alpha(NMODE, 1)
    integer :: n, k
    logical :: ed(size(xl, 2))
    nres = 0.0_wp
    call check_membrane_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    n = size(xl, 2)
    if (size(eps0) /= n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodal initial strains')
       return
    end if
    d = plane_stress(e, nu)
    ed = .true.
    if (present(edges)) ed = edges(1:n)
    if (n == 3) then   ! no modes: σ = -D ε0 wherever it is taken
       allocate (sig_points(NSTRAIN, 1), sig_nodes(NSTRAIN, 3))
       sig_points(:, 1) = -sum(eps0)/3*matmul(d, ISOTROPIC_STRAIN)
       do k = 1, 3
          sig_nodes(:, k) = -eps0(k)*matmul(d, ISOTROPIC_STRAIN)
       end do
       nres = t*sig_points(:, 1)
       return
    end if
    call points(xl, ed, pts)
    kaa = 0.0_wp
    fa = 0.0_wp
    do k = 1, size(pts)
       fa(:, 1) = fa(:, 1) + pts(k)%weight*point_strain(xl, k, eps0)*matmul(transpose(pts(k)%ba), &
            matmul(d, ISOTROPIC_STRAIN))
       kaa = kaa + pts(k)%weight*matmul(transpose(pts(k)%ba), matmul(d, pts(k)%ba))
    end do
    alpha = spd_solve(kaa, fa)
    allocate (sig_points(NSTRAIN, 4), sig_nodes(NSTRAIN, 4))
    do k = 1, 4
       sig_points(:, k) = matmul(d, matmul(pts(k)%ba, alpha(:, 1)) - point_strain(xl, k, eps0)*ISOTROPIC_STRAIN)
    end do
    do k = 1, 4
       sig_nodes(:, k) = matmul(sig_points, bilinear(sqrt(3.0_wp)*XI_NODE(k), sqrt(3.0_wp)*ETA_NODE(k)))
    end do
    p = point_quad(xl, 0.0_wp, 0.0_wp, 0.0_wp, ed)
    nres = t*matmul(d, matmul(p%ba, alpha(:, 1)) - dot_product(bilinear(0.0_wp, 0.0_wp), eps0)*ISOTROPIC_STRAIN)
  end subroutine drilling_thermal_stresses

  pure real(wp) function point_strain(xl, k, eps0) result(v)
    !! The nodal values eps0(n) interpolated to integration point k of points
    !! (triangle: midside point opposite node k; quadrilateral: Gauss point
    !! next to node k).
    real(wp), intent(in) :: xl(:, :)
    integer, intent(in) :: k
    real(wp), intent(in) :: eps0(:)
    real(wp) :: lc(3)
    if (size(xl, 2) == 3) then
       lc = 0.5_wp
       lc(k) = 0.0_wp
       v = dot_product(lc, eps0)
    else
       v = dot_product(bilinear(GP*XI_NODE(k), GP*ETA_NODE(k)), eps0)
    end if
  end function point_strain

  pure function modes(xl, e, nu, ue, ed) result(alpha)
    !! Incompatible-mode amplitudes of a quadrilateral from its nodal values
    !! (static condensation undone): α = -Kaa⁻¹ Kad ue; ed the edges with bubbles.
    real(wp), intent(in) :: xl(:, :), e, nu, ue(:)
    logical, intent(in) :: ed(:)
    real(wp) :: alpha(NMODE)
    type(point_t), allocatable :: pts(:)
    real(wp) :: d(NSTRAIN, NSTRAIN), kaa(NMODE, NMODE), rhs(NMODE, 1), x(NMODE, 1)
    integer :: k
    d = plane_stress(e, nu)
    call points(xl, ed, pts)
    kaa = 0.0_wp
    rhs = 0.0_wp
    do k = 1, size(pts)
       kaa = kaa + pts(k)%weight*matmul(transpose(pts(k)%ba), matmul(d, pts(k)%ba))
       rhs(:, 1) = rhs(:, 1) + pts(k)%weight*matmul(transpose(pts(k)%ba), matmul(d, matmul(pts(k)%b, ue)))
    end do
    x = spd_solve(kaa, rhs)
    alpha = -x(:, 1)
  end function modes

  ! ----------------------------------------------------------------- points

  pure subroutine points(xl, ed, pts)
    !! The integration points of a checked element with their rows (ed: the
    !! edges with bubbles).
    real(wp), intent(in) :: xl(:, :)
    logical, intent(in) :: ed(:)
    type(point_t), allocatable, intent(out) :: pts(:)
    real(wp) :: lc(3)
    integer :: k
    if (size(xl, 2) == 3) then
       allocate (pts(NPOINT_TRI))
       do k = 1, NPOINT_TRI
          ! midside points: L_k = 0, the other two 1/2
          lc = 0.5_wp
          lc(k) = 0.0_wp
          pts(k) = point_tri(xl, lc, triangle_area(xl)/NPOINT_TRI, ed)
       end do
    else
       allocate (pts(NPOINT_QUAD))
       do k = 1, NPOINT_QUAD
          ! Gauss weight 1, times det J inside point_quad
          pts(k) = point_quad(xl, GP*XI_NODE(k), GP*ETA_NODE(k), 1.0_wp, ed)
       end do
    end if
  end subroutine points

  pure function point_tri(xl, lc, weight, ed) result(p)
    !! Rows at the point of area coordinates lc of a triangle (ed: the edges
    !! with bubbles).
    real(wp), intent(in) :: xl(2, 3), lc(3), weight
    logical, intent(in) :: ed(3)
    type(point_t) :: p
    real(wp) :: dl(2, 3), dp(2, 3), area, pe(3)
    integer :: i, j, k
    area = triangle_area(xl)
    do i = 1, 3
       j = modulo(i, 3) + 1
       k = modulo(j, 3) + 1
       dl(1, i) = (xl(2, j) - xl(2, k))/(2*area)
       dl(2, i) = (xl(1, k) - xl(1, j))/(2*area)
    end do
    ! edge i runs from node i to node j = i + 1: bubble 4 Lᵢ Lⱼ
    do i = 1, 3
       j = modulo(i, 3) + 1
       pe(i) = 4*lc(i)*lc(j)
       dp(:, i) = 4*(lc(j)*dl(:, i) + lc(i)*dl(:, j))
    end do
    p = assemble(xl, lc, dl, dp, weight, ed)
  end function point_tri

  pure function point_quad(xl, xi, eta, weight, ed) result(p)
    !! Rows at (ξ, η) of a quadrilateral; weight multiplied by det J (ed: the
    !! edges with bubbles).
    real(wp), intent(in) :: xl(2, 4), xi, eta, weight
    logical, intent(in) :: ed(4)
    type(point_t) :: p
    real(wp) :: dn(2, 4), dpn(2, 4), jm(2, 2), inv(2, 2), jac, j0(2, 2), adj0(2, 2), dm(2, 2)
    integer :: i
    ! natural derivatives of the corners
    dn(1, :) = XI_NODE*(1 + eta*ETA_NODE)/4
    dn(2, :) = ETA_NODE*(1 + xi*XI_NODE)/4
    ! edge bubbles: 1-2 at η = -1, 2-3 at ξ = 1, 3-4 at η = 1, 4-1 at ξ = -1
    dpn(:, 1) = [-xi*(1 - eta), -(1 - xi**2)/2]
    dpn(:, 2) = [(1 - eta**2)/2, -eta*(1 + xi)]
    dpn(:, 3) = [-xi*(1 + eta), (1 - xi**2)/2]
    dpn(:, 4) = [-(1 - eta**2)/2, -eta*(1 - xi)]
    jm = matmul(dn, transpose(xl))
    jac = jm(1, 1)*jm(2, 2) - jm(1, 2)*jm(2, 1)
    inv(1, :) = [jm(2, 2), -jm(1, 2)]
    inv(2, :) = [-jm(2, 1), jm(1, 1)]
    inv = inv/jac
    p = assemble(xl, bilinear(xi, eta), matmul(inv, dn), matmul(inv, dpn), weight*jac, ed)
    ! Incompatible modes 1 - ξ², 1 - η² with Taylor's correction (derivatives
    ! mapped by the centre's J₀ and scaled by j₀/j, i.e. adj(J₀)/j): their
    ! integral over the element vanishes, the patch test holds on any shape.
    dn(1, :) = XI_NODE/4
    dn(2, :) = ETA_NODE/4
    j0 = matmul(dn, transpose(xl))
    adj0(1, :) = [j0(2, 2), -j0(1, 2)]
    adj0(2, :) = [-j0(2, 1), j0(1, 1)]
    dm(:, 1) = [-2*xi, 0.0_wp]
    dm(:, 2) = [0.0_wp, -2*eta]
    dm = matmul(adj0, dm)/jac
    p%ba = 0.0_wp
    do i = 1, 2
       p%ba(1, i) = dm(1, i)
       p%ba(3, i) = dm(2, i)
       p%ba(2, 2 + i) = dm(2, i)
       p%ba(3, 2 + i) = dm(1, i)
    end do
  end function point_quad

  pure function assemble(xl, nc, dn, dp, weight, ed) result(p)
    !! Rows from the corner functions nc(n) and their Cartesian derivatives
    !! dn(2, n), and the edge-bubble derivatives dp(2, n) (edge k from node k to
    !! k + 1) of the edges with ed(k).
    real(wp), intent(in) :: xl(:, :), nc(:), dn(:, :), dp(:, :), weight
    logical, intent(in) :: ed(:)
    type(point_t) :: p
    real(wp) :: cu, cv
    integer :: n, a, i, j, k
    n = size(xl, 2)
    allocate (p%b(NSTRAIN, 3*n), p%w(3*n), source=0.0_wp)
    p%weight = weight
    do a = 1, n
       p%b(1, 3*a - 2) = dn(1, a)
       p%b(2, 3*a - 1) = dn(2, a)
       p%b(3, 3*a - 2) = dn(2, a)
       p%b(3, 3*a - 1) = dn(1, a)
       p%w(3*a - 2) = -dn(2, a)/2
       p%w(3*a - 1) = dn(1, a)/2
       p%w(3*a) = -nc(a)
    end do
    do k = 1, n
       if (.not. ed(k)) cycle
       i = k
       j = modulo(k, n) + 1
       ! Δu_k = (θⱼ - θᵢ)(cu, cv)
       cu = (xl(2, j) - xl(2, i))/8
       cv = -(xl(1, j) - xl(1, i))/8
       call add_theta(p, j, 1.0_wp)
       call add_theta(p, i, -1.0_wp)
    end do
  contains
    pure subroutine add_theta(p, node, s)
      type(point_t), intent(inout) :: p
      integer, intent(in) :: node
      real(wp), intent(in) :: s
      integer :: c
      c = 3*node
      p%b(1, c) = p%b(1, c) + s*dp(1, k)*cu
      p%b(2, c) = p%b(2, c) + s*dp(2, k)*cv
      p%b(3, c) = p%b(3, c) + s*(dp(2, k)*cu + dp(1, k)*cv)
      p%w(c) = p%w(c) + s*(dp(1, k)*cv - dp(2, k)*cu)/2
    end subroutine add_theta
  end function assemble

  pure function bilinear(xi, eta) result(n)
    !! Bilinear shape functions at (ξ, η).
    real(wp), intent(in) :: xi, eta
    real(wp) :: n(4)
    n = (1 + xi*XI_NODE)*(1 + eta*ETA_NODE)/4
  end function bilinear

  pure real(wp) function triangle_area(xl) result(area)
    !! Area of a counter-clockwise triangle.
    real(wp), intent(in) :: xl(2, 3)
    area = 0.5_wp*((xl(1, 2) - xl(1, 1))*(xl(2, 3) - xl(2, 1)) - (xl(1, 3) - xl(1, 1))*(xl(2, 2) - xl(2, 1)))
  end function triangle_area
end module superjoin_elements_drilling
