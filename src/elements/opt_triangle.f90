module superjoin_elements_opt_triangle
  !! Felippa's optimal ANDES membrane triangle OPT ("A study of optimal
  !! membrane triangles with drilling freedoms", CMAME 192 (2003) 2125-2168),
  !! with (u, v, θz) per node: the membrane of S3/S3R on flat regions.
  !!
  !! Assumed strain field, linear in the area coordinates Lᵢ:
  !!   ε = B_b d + β̃₀ T_e (Σᵢ Lᵢ Qᵢ) T_θu d,   β̃₀ = (3/2) √β₀,
  !! - B_b = Lᵀ/(A t): the mean strain from the force-lumping matrix L of a
  !!   constant stress over the boundary whose displacement is linear along
  !!   every edge plus the Allman quadratic normal term α_b (θⱼ - θᵢ) l/8 at the
  !!   midside (α_b = 3/2). Built edge by edge: edge k from node i to j adds
  !!   ±α_b t/12 (Δy², Δx², -2 Δx Δy) to the rows of θⱼ (+) and θᵢ (-)
  !!   (Δx = xⱼ - xᵢ, Δy = yⱼ - yᵢ), so an edge masked out (held straight,
  !!   as superjoin_elements_drill_mask decides) simply omits its term;
  !! - T_θu: the deviatoric corner rotations θ̃ᵢ = θᵢ - ω₀, ω₀ the CST's
  !!   rotation (∂v/∂x - ∂u/∂y)/2 of the nodal u, v;
  !! - Qᵢ: the natural (side-direction) strains at corner i from θ̃,
  !!   (2A/3) βⱼ/l²ₖ with OPT's nine β = (1, 2, 1, 0, 1, -1, -1, -1, -2);
  !! - T_e: natural strains (along sides 1-2, 2-3, 3-1) to Cartesian strains;
  !! - β₀ = max((1 - 4ν²)/2, 0.01).
  !! Σ Qᵢ = 0 for OPT's β, so the higher-order strains have zero mean and are
  !! energy-orthogonal to the basic ones; the stiffness t ∫ εᵀ D ε dA is exact
  !! with the three midside points. A linear field with θ = its rotation has
  !! θ̃ = 0 and no bubble term: the patch test holds under any edge mask, and
  !! the rigid modes are force-free.
  !!
  !! Edge masks: a corner none of whose two edges carries its α_b term (a
  !! curved or held node) keeps its θ̃ out of the higher-order strains (that
  !! stiffness ties θz of a curved node, part of the neighbouring facets'
  !! bending rotation, to the facet's in-plane rotation: the coarse pinched
  !! hemisphere locks) and gets the CST's soft drilling springs instead, so the
  !! element keeps exactly three zero-energy modes under any mask.
  !! superjoin_elements_shell uses the CST with springs for a triangle without
  !! any qualifying edge (doc/verification.md, "The OPT triangle for S3/S3R").
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_membrane, only: plane_stress, check_membrane_element, DRILL_ROTATION_FACTOR, &
       DRILL_NODE_FACTOR
  implicit none (type, external)
  private

  public :: opt_stiffness, opt_resultants, opt_point_stresses, opt_thermal_load

  real(wp), parameter, public :: OPT_ALPHA_B = 1.5_wp
    !! α_b of OPT: the weight of the Allman boundary term in the basic stiffness.
  real(wp), parameter, public :: OPT_BETA(9) = [1.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, -1.0_wp, &
       -1.0_wp, -1.0_wp, -2.0_wp]
    !! β₁ … β₉ of OPT (the higher-order natural-strain modes).
  real(wp), parameter :: BETA0_FLOOR = 0.01_wp
    !! Lower bound of β₀ (Felippa: keeps the higher-order stiffness positive near ν = 1/2).
  integer, parameter :: NSTRAIN = 3, NDOF = 9, NNODE = 3
  integer, parameter :: QPATTERN(3, 3, 3) = reshape([ &
       1, 4, 7, 2, 5, 8, 3, 6, 9, &
       9, 3, 6, 7, 1, 4, 8, 2, 5, &
       5, 8, 2, 6, 9, 3, 4, 7, 1], [3, 3, 3])
    !! QPATTERN(row, col, i): the β index of entry (row, col) of Qᵢ (column-major).

  type :: opt_t
     !! The strain field of one element: ε(L) = (bb + Σᵢ Lᵢ bh(:, :, i)) d.
     real(wp) :: bb(NSTRAIN, NDOF) = 0.0_wp
       !! mean (basic) strain rows
     real(wp) :: bh(NSTRAIN, NDOF, NNODE) = 0.0_wp
       !! higher-order strain rows at the corners (zero sum)
     real(wp) :: area = 0.0_wp
     real(wp) :: omega(NDOF) = 0.0_wp
       !! ω₀ = omega . d, the CST rotation of the nodal u, v
     logical :: active(NNODE) = .true.
       !! corners whose θ̃ the higher-order strains carry (an adjacent edge has its α_b term)
  end type opt_t

contains

  pure subroutine opt_stiffness(xl, t, e, nu, ke, error, edges)
    !! Stiffness ke(9, 9) of the OPT triangle, node-major (u, v, θz), in the
    !! local frame xl(2, 3) (nodes counter-clockwise), thickness t. edges(k)
    !! (optional, default all true): edge k (node k to k + 1) carries its α_b
    !! boundary term; without it the edge stays straight.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    type(opt_t) :: s
    real(wp) :: d(NSTRAIN, NSTRAIN), b(NSTRAIN, NDOF)
    integer :: k
    call setup(xl, t, e, nu, s, error, edges)
    if (allocated(error)) return
    d = t*plane_stress(e, nu)
    allocate (ke(NDOF, NDOF), source=0.0_wp)
    ! midside points (L_k = 0, the other two 1/2): exact for the quadratic integrand
    do k = 1, NNODE
       b = s%bb + 0.5_wp*(sum(s%bh, dim=3) - s%bh(:, :, k))
       ke = ke + s%area/NNODE*matmul(transpose(b), matmul(d, b))
    end do
    if (.not. all(s%active)) call add_springs(s, t*e/(2*(1 + nu)), ke)
    ke = 0.5_wp*(ke + transpose(ke))
  end subroutine opt_stiffness

  pure subroutine opt_resultants(xl, t, e, nu, ue, nres, error, edges)
    !! Membrane resultants nres = (nx, ny, nxy) = t σ at the centroid (the
    !! element's mean stress: the higher-order strains vanish there) from
    !! ue(9) = (u, v, θz) node-major; edges as opt_stiffness.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: nres(NSTRAIN)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    type(opt_t) :: s
    nres = 0.0_wp
    call setup(xl, t, e, nu, s, error, edges)
    if (allocated(error)) return
    call check_size(ue, error)
    if (allocated(error)) return
    nres = t*matmul(plane_stress(e, nu), matmul(s%bb, ue))
  end subroutine opt_resultants

  pure subroutine opt_point_stresses(xl, e, nu, ue, sig_points, sig_nodes, error, edges)
    !! Stresses (σx, σy, τxy) from ue(9) = (u, v, θz): at the centroid
    !! (sig_points(3, 1)) and at the corners (sig_nodes(3, 3): the linear
    !! assumed strain field evaluated there); edges as opt_stiffness.
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: e, nu
    real(wp), intent(in) :: ue(:)
    real(wp), allocatable, intent(out) :: sig_points(:, :), sig_nodes(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    type(opt_t) :: s
    real(wp) :: d(NSTRAIN, NSTRAIN)
    integer :: k
    call setup(xl, 1.0_wp, e, nu, s, error, edges)
    if (allocated(error)) return
    call check_size(ue, error)
    if (allocated(error)) return
    d = plane_stress(e, nu)
    allocate (sig_points(NSTRAIN, 1), sig_nodes(NSTRAIN, NNODE))
    sig_points(:, 1) = matmul(d, matmul(s%bb, ue))
    do k = 1, NNODE
       sig_nodes(:, k) = matmul(d, matmul(s%bb + s%bh(:, :, k), ue))
    end do
  end subroutine opt_point_stresses

  pure subroutine opt_thermal_load(xl, t, e, nu, eps0, fe, error, edges, self_energy)
    !! Consistent nodal load fe(9) = t ∫ Bᵀ D ε0 dA of an isotropic initial
    !! strain ε0 (1, 1, 0) whose nodal values eps0(3) are interpolated
    !! linearly, with the element's own strain rows (basic and higher-order:
    !! midside points, exact for the quadratic integrand); edges as
    !! opt_stiffness. Equal nodal values give t A B_bᵀ D ε0 (the higher-order
    !! rows sum to zero), K times the free expansion. self_energy: ½ ∫ ε0ᵀ t D ε0 dA
    !! by the same midside points (the constant of ½ uᵀ K u - uᵀ fe + self_energy).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(in) :: t, e, nu
    real(wp), intent(in) :: eps0(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    real(wp), intent(out), optional :: self_energy
    type(opt_t) :: s
    real(wp) :: d(NSTRAIN, NSTRAIN), b(NSTRAIN, NDOF), e0, sum_e0
    integer :: k
    if (size(eps0) /= NNODE) then
       call fatal_error(error, EXIT_DECK, 'wrong number of nodal initial strains')
       return
    end if
    call setup(xl, t, e, nu, s, error, edges)
    if (allocated(error)) return
    d = t*plane_stress(e, nu)
    allocate (fe(NDOF), source=0.0_wp)
    sum_e0 = 0.0_wp
    do k = 1, NNODE
       b = s%bb + 0.5_wp*(sum(s%bh, dim=3) - s%bh(:, :, k))
       e0 = 0.5_wp*(sum(eps0) - eps0(k))
       fe = fe + s%area/NNODE*e0*matmul(transpose(b), matmul(d, [1.0_wp, 1.0_wp, 0.0_wp]))
       sum_e0 = sum_e0 + s%area/NNODE*e0**2
    end do
    if (present(self_energy)) self_energy = 0.5_wp*sum_e0*(2.0_wp*d(1, 1) + 2.0_wp*d(1, 2))
  end subroutine opt_thermal_load

  pure subroutine check_size(ue, error)
    !! Nine element DOF values or an error.
    real(wp), intent(in) :: ue(:)
    type(error_t), allocatable, intent(out) :: error
    if (size(ue) /= NDOF) call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
  end subroutine check_size

  pure subroutine setup(xl, t, e, nu, s, error, edges)
    !! The strain rows of a checked three-node element (edges: the edges with
    !! their α_b term, default all).
    real(wp), intent(in) :: xl(:, :), t, e, nu
    type(opt_t), intent(out) :: s
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: edges(:)
    logical :: ed(NNODE)
    real(wp) :: dx(NNODE), dy(NNODE), len2(NNODE), te(NSTRAIN, NSTRAIN), q(NSTRAIN, NSTRAIN)
    real(wp) :: tt(NNODE, NDOF), a, beta0
    integer :: i, j, k, r, c

    call check_membrane_element(xl, t, e, nu, 'plane stress', error)
    if (allocated(error)) return
    if (size(xl, 2) /= NNODE) then
       call fatal_error(error, EXIT_DECK, 'the OPT membrane has three nodes')
       return
    end if
    ed = .true.
    if (present(edges)) ed = edges(1:NNODE)
    ! side k from node k to j = k + 1: (dx, dy) = x_j - x_k
    do k = 1, NNODE
       j = modulo(k, NNODE) + 1
       dx(k) = xl(1, j) - xl(1, k)
       dy(k) = xl(2, j) - xl(2, k)
       len2(k) = dx(k)**2 + dy(k)**2
    end do
    a = 0.5_wp*(dx(3)*dy(1) - dx(1)*dy(3))
    s%area = a
    ! basic strains: the CST rows plus the α_b boundary terms (B_b = Lᵀ/(A t))
    do i = 1, NNODE
       j = modulo(i, NNODE) + 1
       k = modulo(j, NNODE) + 1
       ! CST: ∂Nᵢ/∂x = (y_j - y_k)/(2A) = -dy(j)/(2A), ∂Nᵢ/∂y = (x_k - x_j)/(2A) = dx(j)/(2A)
       s%bb(1, 3*i - 2) = -dy(j)/(2*a)
       s%bb(2, 3*i - 1) = dx(j)/(2*a)
       s%bb(3, 3*i - 2) = dx(j)/(2*a)
       s%bb(3, 3*i - 1) = -dy(j)/(2*a)
    end do
    do k = 1, NNODE
       if (.not. ed(k)) cycle
       j = modulo(k, NNODE) + 1
       call add_edge(s%bb, 3*j, 1.0_wp, dx(k), dy(k), a)
       call add_edge(s%bb, 3*k, -1.0_wp, dx(k), dy(k), a)
    end do
    ! deviatoric corner rotations θ̃ = tt d: θᵢ minus the CST rotation
    ! (ω₀ = Σ (∂Nᵢ/∂x vᵢ - ∂Nᵢ/∂y uᵢ)/2 = -Σ (dx(j) uᵢ + dy(j) vᵢ)/(4A))
    tt = 0.0_wp
    do i = 1, NNODE
       j = modulo(i, NNODE) + 1
       tt(:, 3*i - 2) = dx(j)/(4*a)
       tt(:, 3*i - 1) = dy(j)/(4*a)
       tt(i, 3*i) = 1.0_wp
    end do
    s%omega = -tt(1, :)
    s%omega(3*[1, 2, 3]) = 0.0_wp
    ! a corner none of whose edges carries its α_b term (a curved or held
    ! node) keeps its θz out of the higher-order strains
    do i = 1, NNODE
       k = modulo(i + 1, NNODE) + 1
       s%active(i) = ed(i) .or. ed(k)
       if (.not. s%active(i)) tt(i, :) = 0.0_wp
    end do
    ! natural strains to Cartesian strains (columns: sides 1-2, 2-3, 3-1)
    te = rosette(dx, dy, len2, a)
    beta0 = max((1 - 4*nu**2)/2, BETA0_FLOOR)
    do i = 1, NNODE
       do c = 1, NSTRAIN
          do r = 1, NSTRAIN
             q(r, c) = 2*a/3*OPT_BETA(QPATTERN(r, c, i))/len2(r)
          end do
       end do
       s%bh(:, :, i) = 1.5_wp*sqrt(beta0)*matmul(te, matmul(q, tt))
    end do
  end subroutine setup

  pure subroutine add_springs(s, gt, ke)
    !! The soft drilling springs of the CST (superjoin_elements_membrane's
    !! membrane_drill_stiffness) for an element with inactive corners:
    !! ½ kr (θ̄ - ω₀)² + ½ kn Σᵢ (θᵢ - θ̄)², kr, kn = DRILL_ROTATION_FACTOR,
    !! DRILL_NODE_FACTOR times G t A (gt = G t); both vanish for a linear field
    !! with θ = its rotation.
    type(opt_t), intent(in) :: s
    real(wp), intent(in) :: gt
    real(wp), intent(inout) :: ke(:, :)
    real(wp) :: g(NDOF), kr, kn
    integer :: i, j
    kr = DRILL_ROTATION_FACTOR*gt*s%area
    kn = DRILL_NODE_FACTOR*gt*s%area
    g = -s%omega
    g(3*[1, 2, 3]) = 1.0_wp/NNODE
    do j = 1, NDOF
       ke(:, j) = ke(:, j) + kr*g(j)*g
    end do
    do j = 1, NNODE
       do i = 1, NNODE
          ke(3*i, 3*j) = ke(3*i, 3*j) - kn/NNODE
       end do
       ke(3*j, 3*j) = ke(3*j, 3*j) + kn
    end do
  end subroutine add_springs

  pure subroutine add_edge(bb, col, sgn, dx, dy, a)
    !! The α_b term of one edge (dx, dy its side vector) in the θz column col
    !! of the basic strain rows: sgn α_b (Δy², Δx², -2 Δx Δy)/(12 A).
    real(wp), intent(inout) :: bb(:, :)
    integer, intent(in) :: col
    real(wp), intent(in) :: sgn, dx, dy, a
    bb(:, col) = bb(:, col) + sgn*OPT_ALPHA_B/(12*a)*[dy**2, dx**2, -2*dx*dy]
  end subroutine add_edge

  pure function rosette(dx, dy, len2, a) result(te)
    !! T_e: Cartesian strains (εx, εy, γxy) from the direct strains along the
    !! sides 1-2, 2-3, 3-1 (the inverse of the strain-gauge rosette
    !! εₖ = (Δx² εx + Δy² εy + Δx Δy γxy)/l²ₖ).
    real(wp), intent(in) :: dx(3), dy(3), len2(3), a
    real(wp) :: te(3, 3)
    integer :: k, i, j
    ! column k: side k; the sides meeting it at its ends are i (before) and j (after)
    do k = 1, 3
       j = modulo(k, 3) + 1
       i = modulo(k + 1, 3) + 1
       te(1, k) = -dy(i)*dy(j)
       te(2, k) = -dx(i)*dx(j)
       te(3, k) = dx(i)*dy(j) + dy(i)*dx(j)
       te(:, k) = te(:, k)*len2(k)/(4*a**2)
    end do
  end function rosette
end module superjoin_elements_opt_triangle
