module superjoin_elements_membrane
  !! Plane-stress membrane elements in a 2D local frame: the constant-strain
  !! triangle (3 nodes) and the bilinear quadrilateral with Wilson-Taylor
  !! incompatible modes in the Taylor-Beresford-Wilson form QM6 (4 nodes), plus
  !! the membrane of a flat shell with a drilling rotation; the same two
  !! elements with the plane-strain elasticity matrix (CPE3, CPE4).
  !!
  !! Input: xl(2, nnode) local coordinates, nnode = 3 or 4, nodes counter-clockwise;
  !! t thickness, e Young's modulus, nu Poisson's ratio. Element vectors and
  !! matrices are node-major: (u, v) per node, (u, v, θz) with the drilling rotation.
  !!
  !! QM6: u = Σ Nᵢ uᵢ + (1 - ξ²) a₁ + (1 - η²) a₂ (the same for v with a₃, a₄). The
  !! Cartesian derivatives of the incompatible modes use the Jacobian J₀ at the
  !! centre, scaled by j₀/j, so that their integral over the element vanishes
  !! exactly and the element passes the patch test on any shape. 2×2 Gauss; the
  !! modes are condensed statically. Exact for pure bending of a rectangle.
  !!
  !! Resultants (nx, ny, nxy = t σ) are evaluated at the centroid of the element
  !! area (mapped back to (ξ, η) by Newton's method for the quadrilateral), with the
  !! incompatible-mode amplitudes recovered from the nodal displacements.
  !!
  !! Drilling rotation (membrane_drill_stiffness, the membrane of S3/S3R, and of
  !! S4/S4R elements without any flat edge; flat regions of S4/S4R take the true
  !! drilling rotations of superjoin_elements_drilling): membrane_stiffness plus
  !!   ½ kr (θ̄ - ω̄)² + ½ kn Σᵢ (θᵢ - θ̄)²,   kr = DRILL_ROTATION_FACTOR G t A,
  !!                                          kn = DRILL_NODE_FACTOR G t A,
  !! with θ̄ the mean nodal θz and ω̄ = (1/A) ∫ (∂v/∂x - ∂u/∂y)/2 dA the mean
  !! in-plane rotation of the compatible displacement field (the Hughes-Brezzi
  !! penalty reduced to one point, and a spring between the nodal θz that removes
  !! the n - 1 remaining θz modes). The element keeps exactly three zero-energy
  !! modes: two translations and the rigid rotation u = -θ y, v = θ x, θz = θ.
  !! Choice of the constants (measured in tests/unit/test_membrane.f90 on the
  !! MacNeal-Harder straight cantilever, the coarsest usual bending test):
  !! - kn is what a membrane answer feels: the rotation of the displacement field
  !!   differs between neighbouring elements, so the θz cannot be equal within every
  !!   element. DRILL_NODE_FACTOR = 1e-6 moves the tip deflection by at most 1.2e-4
  !!   (6×1 meshes, regular, trapezoidal, parallelogram, QM6 and CST, root θz free or
  !!   fixed; 1.8e-6 and 7.9e-6 on a 48×4 mesh of QM6 and CST), the test allows 1e-3.
  !!   The smallest θz eigenvalue of one element stays above 8e-9 of the largest
  !!   (a 10:1 sliver triangle; zero modes come out below 4e-16).
  !! - kr ties θ̄ to ω̄. With triangles there are about two elements per node, so
  !!   θ̄ = ω̄ cannot hold in every element and a stiff kr constrains the membrane:
  !!   on the 48×4 CST mesh kr = 1 (Hughes-Brezzi's γ = G) moves the tip by 7e-3,
  !!   0.1 by 7e-4, 1e-2 by 7e-5, 1e-3 by 8e-6; QM6 meshes are insensitive.
  !!   Too soft a kr, though, decouples the membrane of one facet from the bending
  !!   of its neighbour where flat facets meet at an angle: the MacNeal-Harder
  !!   twisted beam (24 x 4 S4, every element warped) is 1.32 / 1.26 times too
  !!   flexible at kr = 1e-3, 1.03 at 1e-2 and 0.9996 / 1.0018 at 0.1 (measured
  !!   with tests/shells/verify_shells.py). DRILL_ROTATION_FACTOR = 0.1.
  !! Being soft, the springs leave θz about 1e-8 relative accuracy where u, v have
  !! round-off (the membrane's round-off is amplified by the stiffness ratio).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_frame, only: require_positive
  implicit none (type, external)
  private

  real(wp), parameter, public :: DRILL_ROTATION_FACTOR = 1.0e-1_wp
    !! kr / (G t A): penalty on the mean θz minus the mean in-plane rotation.
  real(wp), parameter, public :: DRILL_NODE_FACTOR = 1.0e-6_wp
    !! kn / (G t A): spring on the differences of θz between the nodes of an element.
  real(wp), parameter, public :: AREA_TOL = 1.0e-12_wp
    !! An element is degenerate when its area <= AREA_TOL × (longest edge)², and two
    !! nodes coincide when an edge is <= AREA_TOL × the longest edge.
  real(wp), parameter, public :: JACOBIAN_TOL = 1.0e-12_wp
    !! A quadrilateral is rejected when det J <= JACOBIAN_TOL × A/4 at a Gauss point
    !! or at the centre (A/4 is det J of a parallelogram).

  integer, parameter :: NSTRAIN = 3           !! εx, εy, γxy
  integer, parameter :: NMODE = 4             !! incompatible-mode amplitudes of QM6
  integer, parameter :: NGAUSS = 4            !! 2×2 Gauss points, weight 1 each
  real(wp), parameter :: GP = 1/sqrt(3.0_wp)    !! 2×2 Gauss abscissa
  real(wp), parameter :: XI_GAUSS(NGAUSS) = [-GP, GP, GP, -GP]
  real(wp), parameter :: ETA_GAUSS(NGAUSS) = [-GP, -GP, GP, GP]
  real(wp), parameter :: XI_NODE(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]
  real(wp), parameter :: ETA_NODE(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
  integer, parameter :: NEWTON_MAX = 50       !! iterations of the inverse map to the centroid
  real(wp), parameter :: NEWTON_TOL = 1.0e-15_wp   !! on the natural coordinates
  real(wp), parameter :: NU_MIN = -1.0_wp, NU_MAX = 0.5_wp   !! open interval of Poisson's ratio
  real(wp), parameter :: ISOTROPIC(NSTRAIN) = [1.0_wp, 1.0_wp, 0.0_wp]   !! an isotropic in-plane strain

  public :: membrane_stiffness, membrane_resultants, membrane_drill_stiffness, membrane_forces
  public :: plane_strain_stiffness, plane_strain_resultants
  public :: plane_stress, plane_strain, check_plane_material
  public :: membrane_point_stresses

  type, public :: initial_strain_t
    !! An isotropic initial strain ε0 (a thermal strain) of a plane element's
    !! stresses (membrane_point_stresses): its nodal values in, the values at
    !! the integration points and extrapolated to the nodes out.
     real(wp), allocatable :: nodal(:)    !! (n) ε0 at the nodes
     real(wp), allocatable :: points(:)   !! ε0 at the integration points
     real(wp), allocatable :: nodes(:)    !! ε0 extrapolated to the nodes as σ is
  end type initial_strain_t
  public :: membrane_thermal_load, membrane_centroid_weights, membrane_result_operator
  public :: check_membrane_element, spd_solve, make_symmetric, held_factor

contains

  pure subroutine membrane_stiffness(xl, t, e, nu, ke, error)
    !! Plane-stress stiffness ke(2n, 2n) of a CST (n = 3) or QM6 quadrilateral (n = 4).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    call check_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    ke = stiffness_of(xl, t*plane_stress(e, nu))
  end subroutine membrane_stiffness

  pure subroutine plane_strain_stiffness(xl, t, e, nu, ke, error)
    !! Plane-strain stiffness ke(2n, 2n) of a CST (n = 3) or QM6 quadrilateral
    !! (n = 4) of thickness t: the same elements with the plane-strain
    !! elasticity matrix (εz = 0).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    call check_element(xl, t, e, nu, 'plane strain', error)
    if (allocated(error)) return
    ke = stiffness_of(xl, t*plane_strain(e, nu))
  end subroutine plane_strain_stiffness

  pure function stiffness_of(xl, d) result(ke)
    !! Stiffness of a checked CST or QM6 element with the matrix d = t D.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: d(NSTRAIN, NSTRAIN)
    real(wp), allocatable :: ke(:, :)
    real(wp) :: kuu(8, 8), kua(8, NMODE), kaa(NMODE, NMODE), x(2, 4), l(NMODE, NMODE)
    if (size(xl, 2) == 3) then
       ke = cst_stiffness(xl, d)
       call make_symmetric(ke)
    else
       x = xl
       call qm6_matrices(x, d, kuu, kua, kaa)
       call qm6_condensed(kuu, kua, kaa, l, ke)
    end if
  end function stiffness_of

  pure subroutine qm6_condensed(kuu, kua, kaa, l, ke)
    !! The condensed QM6 stiffness ke = kuu - kua kaa⁻¹ kau, made exactly
    !! symmetric, and the Cholesky factor l of kaa (for the modes' recovery).
    real(wp), intent(in) :: kuu(8, 8), kua(8, NMODE), kaa(NMODE, NMODE)
    real(wp), intent(out) :: l(NMODE, NMODE)
    real(wp), allocatable, intent(out) :: ke(:, :)
    real(wp) :: s(NMODE, 8), c
    integer :: i, j, k
    call cholesky(kaa, l)
    s = transpose(kua)
    call modes_solve(l, s)
    allocate (ke(8, 8))
    do j = 1, 8
       do i = 1, 8
          c = 0.0_wp
          do k = 1, NMODE
             c = c + kua(i, k)*s(k, j)
          end do
          ke(i, j) = kuu(i, j) - c
       end do
    end do
    call make_symmetric(ke)
  end subroutine qm6_condensed

  pure subroutine membrane_forces(xl, t, e, nu, strain_state, ue, ke, nres, error)
    !! A plane element's stiffness ke(2n, 2n) (membrane_stiffness, or
    !! plane_strain_stiffness when strain_state) and its resultants nres(3,
    !! step) at the centroid (membrane_resultants, plane_strain_resultants) of
    !! every column of ue (element-frame displacements, node-major u, v), the
    !! element checked and its QM6 matrices formed once: the same numbers.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    logical, intent(in) :: strain_state
    real(wp), intent(in) :: ue(:, :)
    real(wp), allocatable, intent(out) :: ke(:, :)
    real(wp), intent(out) :: nres(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: d(NSTRAIN, NSTRAIN), kuu(8, 8), kua(8, NMODE), kaa(NMODE, NMODE), x(2, 4), l(NMODE, NMODE)
    real(wp) :: alpha(NMODE, 1), bc(NSTRAIN, 8), ba(NSTRAIN, NMODE), xi, eta, area, c
    integer :: is, m, i

    nres = 0.0_wp
    call checked_rigidity(xl, t, e, nu, strain_state, d, error)
    if (allocated(error)) return
    if (size(xl, 2) == 3 .or. size(ue, 1) /= 8) then
       ke = stiffness_of(xl, d)
       do is = 1, size(ue, 2)
          call resultants_of(xl, d, ue(:, is), nres(:, is), error)
          if (allocated(error)) return
       end do
       return
    end if
    x = xl
    call qm6_matrices(x, d, kuu, kua, kaa)
    call qm6_condensed(kuu, kua, kaa, l, ke)
    call centroid_natural(x, xi, eta)
    call qm6_b(x, xi, eta, bc, ba, area)
    do is = 1, size(ue, 2)
       do m = 1, NMODE
          c = 0.0_wp
          do i = 1, 8
             c = c + kua(i, m)*ue(i, is)
          end do
          alpha(m, 1) = c
       end do
       call modes_solve(l, alpha)
       alpha = -alpha
       nres(:, is) = matmul(d, matmul(bc, ue(:, is)) + matmul(ba, alpha(:, 1)))
    end do
  end subroutine membrane_forces

  pure subroutine membrane_resultants(xl, t, e, nu, ue, nres, error, eps0)
    !! Membrane resultants nres = (nx, ny, nxy) = t σ at the centroid from the
    !! element displacements ue(2n) (node-major u, v); with eps0(n), an
    !! isotropic initial strain ε0 (1, 1, 0) interpolated from its nodal values
    !! (see membrane_thermal_load), t D (ε - ε0).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: nres(NSTRAIN)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: eps0(:)
    nres = 0.0_wp
    call check_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    call resultants_of(xl, t*plane_stress(e, nu), ue, nres, error, eps0)
  end subroutine membrane_resultants

  pure subroutine plane_strain_resultants(xl, t, e, nu, ue, nres, error, eps0)
    !! In-plane resultants (nx, ny, nxy) = t σ at the centroid of a plane-strain
    !! element (σz = ν (σx + σy) is not returned); eps0 as for membrane_resultants.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: nres(NSTRAIN)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: eps0(:)
    nres = 0.0_wp
    call check_element(xl, t, e, nu, 'plane strain', error)
    if (allocated(error)) return
    call resultants_of(xl, t*plane_strain(e, nu), ue, nres, error, eps0)
  end subroutine plane_strain_resultants

  pure subroutine resultants_of(xl, d, ue, nres, error, eps0)
    !! Resultants d (B u - ε0) at the centroid of a checked element, d = t D
    !! (eps0: nodal values of an isotropic initial strain, absent: none).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: d(NSTRAIN, NSTRAIN)
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: nres(NSTRAIN)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: eps0(:)
    real(wp) :: kua(8, NMODE), kaa(NMODE, NMODE), x(2, 4), fu(8), fa(NMODE)
    real(wp) :: alpha(NMODE, 1), bc(NSTRAIN, 8), ba(NSTRAIN, NMODE), b3(NSTRAIN, 6), xi, eta, area
    real(wp) :: kuu(8, 8)

    nres = 0.0_wp
    if (size(ue) /= 2*size(xl, 2)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    if (size(xl, 2) == 3) then
       call cst_b(xl, b3, area)
       nres = matmul(d, matmul(b3, ue))
       ! the CST's strain is its mean: ε0 at the centroid, the mean of the nodes
       if (present(eps0)) nres = nres - sum(eps0)/3*matmul(d, ISOTROPIC)
       return
    end if
    x = xl
    call qm6_matrices(x, d, kuu, kua, kaa)
    alpha = -spd_solve(kaa, matmul(transpose(kua), reshape(ue, [8, 1])))
    call centroid_natural(x, xi, eta)
    if (present(eps0)) then
       ! the modes carry their share of the initial strain: α = kaa⁻¹ (f_a - kau u)
       call qm6_initial_strain(x, d, eps0, fu, fa)
       alpha = alpha + spd_solve(kaa, reshape(fa, [NMODE, 1]))
    end if
    call qm6_b(x, xi, eta, bc, ba, area)
    nres = matmul(d, matmul(bc, ue) + matmul(ba, alpha(:, 1)))
    if (present(eps0)) nres = nres - dot_product(shape4(xi, eta), eps0(1:4))*matmul(d, ISOTROPIC)
  end subroutine resultants_of

  pure subroutine membrane_thermal_load(xl, t, e, nu, strain_state, eps0, fe, error, self_energy)
    !! Consistent nodal loads fe(2n) = ∫ Bᵀ t D ε0 dA (element frame, node-major
    !! u, v) of an isotropic initial strain ε0 (1, 1, 0) whose nodal values
    !! eps0(n) are interpolated with the shape functions, as CalculiX
    !! interpolates nodal temperatures to the integration points. CST: its
    !! constant B takes the mean; QM6: 2×2 Gauss, the incompatible modes'
    !! share condensed (f_u - kua kaa⁻¹ f_a). Plane strain (strain_state): eps0
    !! is the in-plane strain, (1 + ν) α ΔT. self_energy: the constant of the
    !! element's energy ½ uᵀ K u - uᵀ fe + self_energy of the mechanical
    !! strains, ½ ∫ ε0ᵀ t D ε0 dA by the same rule (plane strain: times
    !! 1 + held_share(ν), the held expansion across the plane) less what the
    !! incompatible modes take up, ½ f_aᵀ kaa⁻¹ f_a (their minimum over the modes).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    logical, intent(in) :: strain_state
    real(wp), intent(in) :: eps0(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(out), optional :: self_energy
    real(wp) :: d(NSTRAIN, NSTRAIN), kua(8, NMODE), kaa(NMODE, NMODE), x(2, 4), fu(8), fa(NMODE)
    real(wp) :: b3(NSTRAIN, 6), area, ma(NMODE)
    real(wp) :: kuu(8, 8)
    call checked_rigidity(xl, t, e, nu, strain_state, d, error)
    if (allocated(error)) return
    if (size(eps0) /= size(xl, 2)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodal initial strains')
       return
    end if
    if (size(xl, 2) == 3) then
       call cst_b(xl, b3, area)
       fe = area*sum(eps0)/3*matmul(transpose(b3), matmul(d, ISOTROPIC))
       if (present(self_energy)) self_energy = 0.5_wp*area*(sum(eps0)/3)**2* &
            dot_product(ISOTROPIC, matmul(d, ISOTROPIC))*held_factor(strain_state, nu)
       return
    end if
    x = xl
    call qm6_matrices(x, d, kuu, kua, kaa)
    call qm6_initial_strain(x, d, eps0, fu, fa, self_energy)
    ma = reshape(spd_solve(kaa, reshape(fa, [NMODE, 1])), [NMODE])
    fe = fu - matmul(kua, ma)
    if (present(self_energy)) self_energy = self_energy*held_factor(strain_state, nu) - 0.5_wp*dot_product(fa, ma)
  end subroutine membrane_thermal_load

  pure subroutine membrane_result_operator(xl, t, e, nu, strain_state, op, error)
    !! The resultants' operator op(3, 2n) of a CST or QM6 (plane stress, or
    !! plane strain when strain_state): (nx, ny, nxy) at the centroid = op ue
    !! for element-frame displacements ue (node-major u, v), the incompatible
    !! modes condensed: op = t D (bc - ba kaa⁻¹ kuaᵀ). Formed once, it serves
    !! every step and every instance of a part (membrane_resultants without
    !! an initial strain, as one product).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    logical, intent(in) :: strain_state
    real(wp), allocatable, intent(out) :: op(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: d(NSTRAIN, NSTRAIN), kua(8, NMODE), kaa(NMODE, NMODE), x(2, 4)
    real(wp) :: bc(NSTRAIN, 8), ba(NSTRAIN, NMODE), b3(NSTRAIN, 6), xi, eta, area
    real(wp) :: kuu(8, 8)
    call checked_rigidity(xl, t, e, nu, strain_state, d, error)
    if (allocated(error)) return
    if (size(xl, 2) == 3) then
       call cst_b(xl, b3, area)
       op = matmul(d, b3)
       return
    end if
    x = xl
    call qm6_matrices(x, d, kuu, kua, kaa)
    call centroid_natural(x, xi, eta)
    call qm6_b(x, xi, eta, bc, ba, area)
    op = matmul(d, bc - matmul(ba, spd_solve(kaa, transpose(kua))))
  end subroutine membrane_result_operator

  pure subroutine checked_rigidity(xl, t, e, nu, strain_state, d, error)
    !! The element's checks and its rigidity d = t D, plane strain when
    !! strain_state, plane stress otherwise.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    logical, intent(in) :: strain_state
    real(wp), intent(out) :: d(NSTRAIN, NSTRAIN)
    type(error_t), allocatable, intent(out) :: error
    if (strain_state) then
       call check_element(xl, t, e, nu, 'plane strain', error)
       d = t*plane_strain(e, nu)
    else
       call check_element(xl, t, e, nu, 'plane stress', error)
       d = t*plane_stress(e, nu)
    end if
  end subroutine checked_rigidity

  pure subroutine membrane_centroid_weights(xl, w)
    !! The shape functions w(n) of a CST (1/3 each) or of the bilinear
    !! quadrilateral at the area centroid, where the resultants are evaluated.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(out) :: w(:)
    real(wp) :: x(2, 4), xi, eta
    if (size(xl, 2) == 3) then
       w = 1.0_wp/3
       return
    end if
    x = xl
    call centroid_natural(x, xi, eta)
    w = shape4(xi, eta)
  end subroutine membrane_centroid_weights

  pure real(wp) function held_factor(strain_state, nu) result(f)
    !! 1, or under plane strain 1 + (1 - 2ν)/(2 (1 + ν)): the energy of the
    !! expansion held across the plane (σ_z = ν (σ_x + σ_y) - E α ΔT) against the
    !! in-plane ½ ε0ᵀ D ε0 of ε0 = (1 + ν) α ΔT, at every point.
    logical, intent(in) :: strain_state
    real(wp), intent(in) :: nu
    f = 1.0_wp
    if (strain_state) f = 1.0_wp + (1.0_wp - 2.0_wp*nu)/(2.0_wp*(1.0_wp + nu))
  end function held_factor

  pure subroutine qm6_initial_strain(x, d, eps0, fu, fa, self_energy)
    !! ∫ [bc ba]ᵀ d ε0 dA by 2×2 Gauss of QM6 for the isotropic initial strain
    !! ε0 (1, 1, 0) interpolated bilinearly from eps0(4): fu on the nodal (u, v),
    !! fa on the incompatible modes; self_energy: ½ ∫ ε0ᵀ d ε0 dA by the same rule.
    real(wp), intent(in) :: x(2, 4), d(NSTRAIN, NSTRAIN), eps0(:)
    real(wp), intent(out) :: fu(8), fa(NMODE)
    real(wp), intent(out), optional :: self_energy
    real(wp) :: bc(NSTRAIN, 8), ba(NSTRAIN, NMODE), jac, s0(NSTRAIN), e0, sum_e0
    integer :: k
    fu = 0.0_wp
    fa = 0.0_wp
    sum_e0 = 0.0_wp
    do k = 1, NGAUSS
       call qm6_b(x, XI_GAUSS(k), ETA_GAUSS(k), bc, ba, jac)
       e0 = dot_product(shape4(XI_GAUSS(k), ETA_GAUSS(k)), eps0(1:4))
       s0 = jac*e0*matmul(d, ISOTROPIC)
       fu = fu + matmul(transpose(bc), s0)
       fa = fa + matmul(transpose(ba), s0)
       sum_e0 = sum_e0 + jac*e0**2
    end do
    if (present(self_energy)) self_energy = 0.5_wp*sum_e0*dot_product(ISOTROPIC, matmul(d, ISOTROPIC))
  end subroutine qm6_initial_strain

  pure subroutine membrane_drill_stiffness(xl, t, e, nu, ke, error)
    !! Stiffness ke(3n, 3n) of a membrane with drilling rotation (u, v, θz per node):
    !! membrane_stiffness plus the drilling penalty described in the module header.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: km(:, :), g(:)
    real(wp) :: w(8), area, gmod, kr, kn
    integer :: n, i, j

    call membrane_stiffness(xl, t, e, nu, km, error)
    if (allocated(error)) return
    n = size(xl, 2)
    allocate (ke(3*n, 3*n), source=0.0_wp)
    do j = 1, n
       do i = 1, n
          ke(3*i - 2:3*i - 1, 3*j - 2:3*j - 1) = km(2*i - 1:2*i, 2*j - 1:2*j)
       end do
    end do

    call mean_rotation(xl, w(1:2*n), area)
    gmod = e/(2*(1 + nu))
    kr = DRILL_ROTATION_FACTOR*gmod*t*area
    kn = DRILL_NODE_FACTOR*gmod*t*area
    ! g . (u, v, θz) = θ̄ - ω̄
    allocate (g(3*n))
    do i = 1, n
       g(3*i - 2) = -w(2*i - 1)
       g(3*i - 1) = -w(2*i)
       g(3*i) = 1.0_wp/n
    end do
    do j = 1, 3*n
       ke(:, j) = ke(:, j) + kr*g(j)*g
    end do
    ! kn (I - 1 1ᵀ/n) on the θz.
    do j = 1, n
       do i = 1, n
          ke(3*i, 3*j) = ke(3*i, 3*j) - kn/n
       end do
       ke(3*j, 3*j) = ke(3*j, 3*j) + kn
    end do
    call make_symmetric(ke)
  end subroutine membrane_drill_stiffness

  ! ------------------------------------------------------------------ checks

  pure subroutine check_membrane_element(xl, t, e, nu, state, error)
    !! The data checks of the membrane elements (check_element) for the other
    !! membrane formulations (superjoin_elements_drilling).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    character(*), intent(in) :: state
    type(error_t), allocatable, intent(out) :: error
    call check_element(xl, t, e, nu, state, error)
  end subroutine check_membrane_element

  pure subroutine check_element(xl, t, e, nu, state, error)
    !! Data checks: node count, t > 0, E > 0, -1 < nu < 0.5, positive area,
    !! distinct nodes, and for the quadrilateral det J > 0 at the Gauss points.
    !! `state` ('plane stress' or 'plane strain') goes into the nu message.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    character(*), intent(in) :: state
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: area, edge2, lmax2, x(2, 4), jm(2, 2), dn(2, 4), jac
    integer :: n, i, k

    n = size(xl, 2)
    if (size(xl, 1) /= 2 .or. (n /= 3 .and. n /= 4)) then
       call fatal_error(error, EXIT_DECK, 'a membrane element needs 3 or 4 nodes in a 2D frame')
       return
    end if
    call check_plane_material(t, e, nu, state, error)
    if (allocated(error)) return

    area = polygon_area(xl)
    lmax2 = 0.0_wp
    do i = 1, n
       lmax2 = max(lmax2, sum((xl(:, modulo(i, n) + 1) - xl(:, i))**2))
    end do
    if (.not. (area > AREA_TOL*lmax2)) then
       call fatal_error(error, EXIT_DECK, 'zero or negative area (nodes clockwise or coincident)')
       return
    end if
    do i = 1, n
       edge2 = sum((xl(:, modulo(i, n) + 1) - xl(:, i))**2)
       if (edge2 <= AREA_TOL**2*lmax2) then
          call fatal_error(error, EXIT_DECK, 'coincident nodes')
          return
       end if
    end do
    if (n == 3) return

    x = xl
    do k = 0, NGAUSS
       if (k == 0) then
          call jacobian(x, 0.0_wp, 0.0_wp, jm, dn)
       else
          call jacobian(x, XI_GAUSS(k), ETA_GAUSS(k), jm, dn)
       end if
       jac = jm(1, 1)*jm(2, 2) - jm(1, 2)*jm(2, 1)
       if (.not. (jac > JACOBIAN_TOL*area/4)) then
          call fatal_error(error, EXIT_DECK, 'non-positive Jacobian (re-entrant or crossed quadrilateral)')
          return
       end if
    end do
  end subroutine check_element

  pure subroutine check_plane_material(t, e, nu, state, error)
    !! Data checks of a plane element: t > 0, E > 0, -1 < nu < 0.5; `state`
    !! ('plane stress' or 'plane strain') goes into the nu message.
    real(wp), intent(in) :: t, e, nu
    character(*), intent(in) :: state
    type(error_t), allocatable, intent(out) :: error
    call require_positive(t, 'thickness t', error)
    call require_positive(e, 'Young''s modulus E', error)
    if (allocated(error)) return
    if (.not. (nu > NU_MIN .and. nu < NU_MAX)) then
       call fatal_error(error, EXIT_DECK, 'Poisson''s ratio nu must lie in (-1, 0.5) for '//state)
    end if
  end subroutine check_plane_material

  pure real(wp) function polygon_area(xl) result(area)
    !! Signed area of the polygon xl(2, n) (positive counter-clockwise).
    real(wp), intent(in) :: xl(:, :)
    integer :: i, j, n
    n = size(xl, 2)
    area = 0.0_wp
    do i = 1, n
       j = modulo(i, n) + 1
       area = area + (xl(1, i) - xl(1, 1))*(xl(2, j) - xl(2, 1)) - (xl(1, j) - xl(1, 1))*(xl(2, i) - xl(2, 1))
    end do
    area = 0.5_wp*area
  end function polygon_area

  ! ---------------------------------------------------------------- material

  pure function plane_stress(e, nu) result(d)
    !! Plane-stress elasticity matrix (εx, εy, γxy) -> (σx, σy, τxy).
    real(wp), intent(in) :: e, nu
    real(wp) :: d(NSTRAIN, NSTRAIN)
    real(wp) :: c
    c = e/(1 - nu**2)
    d(:, 1) = [c, c*nu, 0.0_wp]
    d(:, 2) = [c*nu, c, 0.0_wp]
    d(:, 3) = [0.0_wp, 0.0_wp, c*(1 - nu)/2]
  end function plane_stress

  pure function plane_strain(e, nu) result(d)
    !! Plane-strain elasticity matrix (εx, εy, γxy) -> (σx, σy, τxy), εz = 0.
    real(wp), intent(in) :: e, nu
    real(wp) :: d(NSTRAIN, NSTRAIN)
    real(wp) :: c
    c = e/((1 + nu)*(1 - 2*nu))
    d(:, 1) = [c*(1 - nu), c*nu, 0.0_wp]
    d(:, 2) = [c*nu, c*(1 - nu), 0.0_wp]
    d(:, 3) = [0.0_wp, 0.0_wp, e/(2*(1 + nu))]
  end function plane_strain

  ! -------------------------------------------------------------------- CST

  pure subroutine cst_b(xl, b, area)
    !! Constant strain-displacement matrix b of a triangle and its area.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(out) :: b(NSTRAIN, 6), area
    real(wp) :: bi(3), ci(3)
    integer :: i, j, k
    area = polygon_area(xl)
    do i = 1, 3
       j = modulo(i, 3) + 1
       k = modulo(j, 3) + 1
       bi(i) = (xl(2, j) - xl(2, k))/(2*area)
       ci(i) = (xl(1, k) - xl(1, j))/(2*area)
    end do
    b = 0.0_wp
    do i = 1, 3
       b(1, 2*i - 1) = bi(i)
       b(2, 2*i) = ci(i)
       b(3, 2*i - 1) = ci(i)
       b(3, 2*i) = bi(i)
    end do
  end subroutine cst_b

  pure function cst_stiffness(xl, d) result(ke)
    !! Stiffness A Bᵀ d B of a constant-strain triangle (d includes t).
    real(wp), intent(in) :: xl(:, :), d(NSTRAIN, NSTRAIN)
    real(wp), allocatable :: ke(:, :)
    real(wp) :: b(NSTRAIN, 6), area
    call cst_b(xl, b, area)
    ke = area*matmul(transpose(b), matmul(d, b))
  end function cst_stiffness

  ! -------------------------------------------------------------------- QM6

  pure subroutine jacobian(x, xi, eta, jm, dn)
    !! Jacobian jm = [x,ξ y,ξ; x,η y,η] of the bilinear map and dn(2, 4) = ∂Nᵢ/∂(ξ, η).
    real(wp), intent(in) :: x(2, 4), xi, eta
    real(wp), intent(out) :: jm(2, 2), dn(2, 4)
    dn(1, :) = XI_NODE*(1 + eta*ETA_NODE)/4
    dn(2, :) = ETA_NODE*(1 + xi*XI_NODE)/4
    jm = matmul(dn, transpose(x))
  end subroutine jacobian

  pure function adjugate(a) result(b)
    !! Adjugate of a 2×2 matrix (inverse times determinant).
    real(wp), intent(in) :: a(2, 2)
    real(wp) :: b(2, 2)
    b(1, 1) = a(2, 2)
    b(2, 2) = a(1, 1)
    b(1, 2) = -a(1, 2)
    b(2, 1) = -a(2, 1)
  end function adjugate

  pure subroutine qm6_b(x, xi, eta, bc, ba, jac)
    !! Strain-displacement matrices of QM6 at (ξ, η): bc for the nodal (u, v),
    !! ba for the incompatible modes (a₁..a₄: u with 1-ξ², 1-η², then v), and det J.
    real(wp), intent(in) :: x(2, 4), xi, eta
    real(wp), intent(out) :: bc(NSTRAIN, 8), ba(NSTRAIN, NMODE), jac
    real(wp) :: gx(6), gy(6)
    integer :: i

    call qm6_gradients(x, centre_jacobian(x), xi, eta, gx, gy, jac)
    bc = 0.0_wp
    ba = 0.0_wp
    if (.not. (jac > 0.0_wp)) return
    do i = 1, 4
       bc(1, 2*i - 1) = gx(i)
       bc(2, 2*i) = gy(i)
       bc(3, 2*i - 1) = gy(i)
       bc(3, 2*i) = gx(i)
    end do
    do i = 1, 2
       ba(1, i) = gx(4 + i)
       ba(3, i) = gy(4 + i)
       ba(2, 2 + i) = gy(4 + i)
       ba(3, 2 + i) = gx(4 + i)
    end do
  end subroutine qm6_b

  pure function centre_jacobian(x) result(j0)
    !! The Jacobian J₀ of the bilinear map at the centre (ξ = η = 0).
    real(wp), intent(in) :: x(2, 4)
    real(wp) :: j0(2, 2), dn(2, 4)
    call jacobian(x, 0.0_wp, 0.0_wp, j0, dn)
  end function centre_jacobian

  pure subroutine qm6_gradients(x, j0, xi, eta, gx, gy, jac)
    !! The Cartesian derivatives (gx, gy) at (ξ, η) of the four bilinear shape
    !! functions (1..4) and of the incompatible modes 1 - ξ², 1 - η² (5, 6:
    !! natural derivatives mapped with J₀ and scaled by j₀/j, i.e. adj(J₀)/j),
    !! and det J; zero derivatives where det J <= 0. The entries of qm6_b's
    !! bc and ba in closed form: the same operations, the products by zero left out.
    real(wp), intent(in) :: x(2, 4), j0(2, 2), xi, eta
    real(wp), intent(out) :: gx(6), gy(6), jac
    real(wp) :: jm(2, 2), dn(2, 4)
    integer :: i

    call jacobian(x, xi, eta, jm, dn)
    jac = jm(1, 1)*jm(2, 2) - jm(1, 2)*jm(2, 1)
    gx = 0.0_wp
    gy = 0.0_wp
    if (.not. (jac > 0.0_wp)) return
    do i = 1, 4
       gx(i) = (jm(2, 2)*dn(1, i) - jm(1, 2)*dn(2, i))/jac
       gy(i) = (jm(1, 1)*dn(2, i) - jm(2, 1)*dn(1, i))/jac
    end do
    gx(5) = (j0(2, 2)*(-2*xi))/jac
    gy(5) = -(j0(2, 1)*(-2*xi))/jac
    gx(6) = -(j0(1, 2)*(-2*eta))/jac
    gy(6) = (j0(1, 1)*(-2*eta))/jac
  end subroutine qm6_gradients

  pure subroutine qm6_matrices(x, d, kuu, kua, kaa)
    !! Uncondensed QM6 stiffness blocks by 2×2 Gauss (d = t D, isotropic:
    !! d(1:2, 3) = d(3, 1:2) = 0), from the gradients of qm6_gradients: the
    !! u columns of B are (gx, 0, gy), the v columns (0, gy, gx), so that each
    !! entry of Bᵀ d B is a sum of two products, accumulated point by point as
    !! Bᵀ (jac d B) was (the same numbers, without the products by zero).
    real(wp), intent(in) :: x(2, 4), d(NSTRAIN, NSTRAIN)
    real(wp), intent(out) :: kuu(8, 8), kua(8, NMODE), kaa(NMODE, NMODE)
    real(wp) :: gx(6), gy(6), jac, j0(2, 2), du(3, 6), dv(3, 6), k(12, 12)
    integer :: g, p, q

    j0 = centre_jacobian(x)
    k = 0.0_wp
    do g = 1, NGAUSS
       call qm6_gradients(x, j0, XI_GAUSS(g), ETA_GAUSS(g), gx, gy, jac)
       do q = 1, 6
          du(1, q) = jac*(d(1, 1)*gx(q))
          du(2, q) = jac*(d(2, 1)*gx(q))
          du(3, q) = jac*(d(3, 3)*gy(q))
          dv(1, q) = jac*(d(1, 2)*gy(q))
          dv(2, q) = jac*(d(2, 2)*gy(q))
          dv(3, q) = jac*(d(3, 3)*gx(q))
       end do
       do q = 1, 6
          do p = 1, 6
             k(p, q) = k(p, q) + (gx(p)*du(1, q) + gy(p)*du(3, q))
             k(p, 6 + q) = k(p, 6 + q) + (gx(p)*dv(1, q) + gy(p)*dv(3, q))
             k(6 + p, q) = k(6 + p, q) + (gy(p)*du(2, q) + gx(p)*du(3, q))
             k(6 + p, 6 + q) = k(6 + p, 6 + q) + (gy(p)*dv(2, q) + gx(p)*dv(3, q))
          end do
       end do
    end do
    ! rows and columns of k: u of nodes 1..4 (1:4) and of the modes (5:6), then v (7:10, 11:12)
    kuu(1:7:2, 1:7:2) = k(1:4, 1:4)
    kuu(2:8:2, 1:7:2) = k(7:10, 1:4)
    kuu(1:7:2, 2:8:2) = k(1:4, 7:10)
    kuu(2:8:2, 2:8:2) = k(7:10, 7:10)
    kua(1:7:2, 1:2) = k(1:4, 5:6)
    kua(2:8:2, 1:2) = k(7:10, 5:6)
    kua(1:7:2, 3:4) = k(1:4, 11:12)
    kua(2:8:2, 3:4) = k(7:10, 11:12)
    kaa(1:2, 1:2) = k(5:6, 5:6)
    kaa(3:4, 1:2) = k(11:12, 5:6)
    kaa(1:2, 3:4) = k(5:6, 11:12)
    kaa(3:4, 3:4) = k(11:12, 11:12)
  end subroutine qm6_matrices

  pure subroutine centroid_natural(x, xi, eta)
    !! Natural coordinates of the area centroid of a quadrilateral (Newton's method
    !! on the bilinear map, from the centre).
    real(wp), intent(in) :: x(2, 4)
    real(wp), intent(out) :: xi, eta
    real(wp) :: xc(2), r(2), jm(2, 2), dn(2, 4), dxi(2), c, area
    integer :: i, j, it

    area = polygon_area(x)
    xc = 0.0_wp
    do i = 1, 4
       j = modulo(i, 4) + 1
       c = x(1, i)*x(2, j) - x(1, j)*x(2, i)
       xc = xc + (x(:, i) + x(:, j))*c
    end do
    xc = xc/(6*area)
    xi = 0.0_wp
    eta = 0.0_wp
    do it = 1, NEWTON_MAX
       r = matmul(x, shape4(xi, eta)) - xc
       call jacobian(x, xi, eta, jm, dn)
       ! x(ξ) - xc = 0: Jᵀ dξ = -r.
       dxi = -matmul(transpose(adjugate(jm)), r)/(jm(1, 1)*jm(2, 2) - jm(1, 2)*jm(2, 1))
       xi = xi + dxi(1)
       eta = eta + dxi(2)
       if (maxval(abs(dxi)) <= NEWTON_TOL) exit
    end do
  end subroutine centroid_natural

  pure function shape4(xi, eta) result(n)
    !! Bilinear shape functions at (ξ, η).
    real(wp), intent(in) :: xi, eta
    real(wp) :: n(4)
    n = (1 + xi*XI_NODE)*(1 + eta*ETA_NODE)/4
  end function shape4

  pure subroutine mean_rotation(xl, w, area)
    !! Row w(2n) with w . (u, v) = ω̄ = (1/A) ∫ (∂v/∂x - ∂u/∂y)/2 dA for the
    !! compatible field, and the area A.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(out) :: w(:), area
    real(wp) :: b3(NSTRAIN, 6), bc(NSTRAIN, 8), ba(NSTRAIN, NMODE), x(2, 4), jac
    integer :: i, k

    w = 0.0_wp
    if (size(xl, 2) == 3) then
       call cst_b(xl, b3, area)
       do i = 1, 3
          w(2*i - 1) = -b3(2, 2*i)/2      ! -∂Nᵢ/∂y / 2
          w(2*i) = b3(1, 2*i - 1)/2       !  ∂Nᵢ/∂x / 2
       end do
       return
    end if
    x = xl
    area = 0.0_wp
    do k = 1, NGAUSS
       call qm6_b(x, XI_GAUSS(k), ETA_GAUSS(k), bc, ba, jac)
       area = area + jac
       do i = 1, 4
          w(2*i - 1) = w(2*i - 1) - jac*bc(2, 2*i)/2
          w(2*i) = w(2*i) + jac*bc(1, 2*i - 1)/2
       end do
    end do
    w = w/area
  end subroutine mean_rotation

  ! ---------------------------------------------------------------- algebra

  pure function spd_solve(a, b) result(x)
    !! Solve a x = b for a small symmetric positive definite a (Cholesky).
    real(wp), intent(in) :: a(:, :), b(:, :)
    real(wp) :: x(size(b, 1), size(b, 2))
    real(wp) :: l(size(a, 1), size(a, 1))
    integer :: n, i
    n = size(a, 1)
    call cholesky(a, l)
    x = b
    do i = 1, n            ! L y = b
       x(i, :) = (x(i, :) - matmul(l(i, 1:i - 1), x(1:i - 1, :)))/l(i, i)
    end do
    do i = n, 1, -1        ! Lᵀ x = y
       x(i, :) = (x(i, :) - matmul(l(i + 1:n, i), x(i + 1:n, :)))/l(i, i)
    end do
  end function spd_solve

  pure subroutine make_symmetric(k)
    !! k ← (k + kᵀ)/2 entry by entry, without a temporary (the diagonal as
    !! it is: (d + d)/2 = d exactly).
    real(wp), intent(inout) :: k(:, :)
    real(wp) :: c
    integer :: i, j
    do j = 2, size(k, 2)
       do i = 1, j - 1
          c = 0.5_wp*(k(i, j) + k(j, i))
          k(i, j) = c
          k(j, i) = c
       end do
    end do
  end subroutine make_symmetric

  pure subroutine cholesky(a, l)
    !! The lower Cholesky factor l of a small symmetric positive definite a
    !! (its lower triangle read), each sum accumulated from the first term on.
    real(wp), intent(in) :: a(:, :)
    real(wp), intent(out) :: l(:, :)
    real(wp) :: c
    integer :: n, i, j, k
    n = size(a, 1)
    l = 0.0_wp
    do j = 1, n
       c = 0.0_wp
       do k = 1, j - 1
          c = c + l(j, k)**2
       end do
       l(j, j) = sqrt(a(j, j) - c)
       do i = j + 1, n
          c = 0.0_wp
          do k = 1, j - 1
             c = c + l(i, k)*l(j, k)
          end do
          l(i, j) = (a(i, j) - c)/l(j, j)
       end do
    end do
  end subroutine cholesky

  pure subroutine modes_solve(l, x)
    !! x ← kaa⁻¹ x for QM6's four modes, l the Cholesky factor of kaa, column
    !! by column (L y = x, then Lᵀ x = y): spd_solve's operations in the same
    !! order, the size known to the compiler (its loops unrolled; 3× fewer
    !! instructions than the general solve).
    real(wp), intent(in) :: l(NMODE, NMODE)
    real(wp), intent(inout) :: x(:, :)
    real(wp) :: c
    integer :: i, j, k
    do j = 1, size(x, 2)
       do i = 1, NMODE
          c = 0.0_wp
          do k = 1, i - 1
             c = c + l(i, k)*x(k, j)
          end do
          x(i, j) = (x(i, j) - c)/l(i, i)
       end do
       do i = NMODE, 1, -1
          c = 0.0_wp
          do k = i + 1, NMODE
             c = c + l(k, i)*x(k, j)
          end do
          x(i, j) = (x(i, j) - c)/l(i, i)
       end do
    end do
  end subroutine modes_solve

  ! ------------------------------------------------ stresses at points and nodes

  pure subroutine membrane_point_stresses(xl, e, nu, strain_state, ue, sig_points, sig_nodes, error, eps0)
    !! Stresses (σx, σy, τxy) in the element frame from the element
    !! displacements ue(2n) (node-major u, v), plane stress or (strain_state)
    !! plane strain: sig_points at the integration points, the CST's single
    !! point (sig_points(3, 1)) or the quadrilateral's 2×2 Gauss points
    !! (sig_points(3, 4) at (ξ, η) = (-g, -g), (g, -g), (g, g), (-g, g), g = 1/√3,
    !! the point next to node k first), incompatible modes recovered as for
    !! the resultants; sig_nodes(3, n) extrapolated to the nodes: the CST's
    !! constant, the bilinear field through the four Gauss values evaluated at
    !! the corners (ξ, η = ±1, i.e. ±√3 in the Gauss points' own coordinates).
    !! With eps0 (eps0%nodal(n), the nodal values of an isotropic initial
    !! strain, membrane_thermal_load), σ = D (ε - ε0) with ε0 interpolated to
    !! each point, and eps0%points, eps0%nodes the ε0 there (extrapolated as
    !! σ is).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: e, nu
    logical, intent(in) :: strain_state
    real(wp), intent(in) :: ue(:)
    real(wp), allocatable, intent(out) :: sig_points(:, :), sig_nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(initial_strain_t), intent(inout), optional :: eps0
    real(wp) :: d(NSTRAIN, NSTRAIN), kua(8, NMODE), kaa(NMODE, NMODE), x(2, 4), fu(8), fa(NMODE)
    real(wp) :: alpha(NMODE, 1), bc(NSTRAIN, 8), ba(NSTRAIN, NMODE), b3(NSTRAIN, 6), jac, area
    real(wp) :: ep(NGAUSS)
    real(wp) :: kuu(8, 8)
    integer :: k, n

    n = size(xl, 2)
    if (strain_state) then
       call check_element(xl, 1.0_wp, e, nu, 'plane strain', error)
       d = plane_strain(e, nu)
    else
       call check_element(xl, 1.0_wp, e, nu, 'plane stress', error)
       d = plane_stress(e, nu)
    end if
    if (allocated(error)) return
    if (size(ue) /= 2*n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    if (n == 3) then
       call cst_b(xl, b3, area)
       allocate (sig_points(NSTRAIN, 1), sig_nodes(NSTRAIN, 3))
       sig_points(:, 1) = matmul(d, matmul(b3, ue))
       if (present(eps0)) then   ! the CST's one point: the mean of the nodal ε0
          sig_points(:, 1) = sig_points(:, 1) - sum(eps0%nodal)/3*matmul(d, ISOTROPIC)
          eps0%points = [sum(eps0%nodal)/3]
          eps0%nodes = spread(sum(eps0%nodal)/3, 1, 3)
       end if
       sig_nodes = spread(sig_points(:, 1), 2, 3)
       return
    end if
    x = xl
    call qm6_matrices(x, d, kuu, kua, kaa)
    alpha = -spd_solve(kaa, matmul(transpose(kua), reshape(ue, [8, 1])))
    ep = 0.0_wp
    if (present(eps0)) then   ! α = kaa⁻¹ (f_a - kau u), σ = D (ε - ε0)
       call qm6_initial_strain(x, d, eps0%nodal, fu, fa)
       alpha = alpha + spd_solve(kaa, reshape(fa, [NMODE, 1]))
       do k = 1, NGAUSS
          ep(k) = dot_product(shape4(XI_GAUSS(k), ETA_GAUSS(k)), eps0%nodal(1:4))
       end do
    end if
    allocate (sig_points(NSTRAIN, NGAUSS), sig_nodes(NSTRAIN, 4))
    do k = 1, NGAUSS
       call qm6_b(x, XI_GAUSS(k), ETA_GAUSS(k), bc, ba, jac)
       sig_points(:, k) = matmul(d, matmul(bc, ue) + matmul(ba, alpha(:, 1)) - ep(k)*ISOTROPIC)
    end do
    ! The Gauss points are the corners of a square of half-side g in (ξ, η), in the
    ! order of the nodes: node k sits at (ξ_k/g, η_k/g) = √3 (ξ_k, η_k) of that square.
    do k = 1, 4
       sig_nodes(:, k) = matmul(sig_points, shape4(sqrt(3.0_wp)*XI_NODE(k), sqrt(3.0_wp)*ETA_NODE(k)))
    end do
    if (.not. present(eps0)) return
    eps0%points = ep
    if (allocated(eps0%nodes)) deallocate (eps0%nodes)
    allocate (eps0%nodes(4))
    do k = 1, 4
       eps0%nodes(k) = dot_product(ep, shape4(sqrt(3.0_wp)*XI_NODE(k), sqrt(3.0_wp)*ETA_NODE(k)))
    end do
  end subroutine membrane_point_stresses
end module superjoin_elements_membrane
