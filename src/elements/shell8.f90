module superjoin_elements_shell8
  !! S8R: the eight-node thick (Reissner-Mindlin) shell, a degenerated-solid
  !! (Ahmad-Irons-Zienkiewicz) element with serendipity interpolation and the
  !! 2×2 reduced in-plane integration of Abaqus's S8R; the surface may be curved.
  !!
  !! Node order (Abaqus): corners 1-4 counter-clockwise, then the mid-side
  !! nodes 5 (between 1 and 2), 6, 7, 8; natural coordinates ξ, η in [-1, 1],
  !! ζ in [-1, 1] through the thickness t. DOFs per node (global axes):
  !! ux, uy, uz, rx, ry, rz.
  !!
  !! Geometry and displacement (directors n_i, unit normals of the element's
  !! own isoparametric surface at its nodes):
  !!   X = Σ N_i (x_i + ζ t/2 n_i),   U = Σ N_i (u_i + ζ t/2 θ_i × n_i).
  !! Strains in the lamina frame (e3 normal to the surface at the point, e1 the
  !! projection of the element's local x onto the tangent plane, e2 = e3 × e1):
  !! ε11, ε22, γ12 (plane stress, E, ν) and γ13, γ23 (transverse shear, modulus
  !! ks/t from the section's K11, K22, default 5/6 G t). Two Gauss points
  !! through the thickness. In the plane, as Abaqus's S8R, the membrane strains
  !! (the mean of the two thickness points) and the transverse shear take the
  !! reduced 2×2 rule (no membrane or shear locking on regular meshes); the
  !! bending strains (∂ε/∂ζ) take the full 3×3 rule, which removes the
  !! bending hourglass that a 2×2 rule leaves in a single element.
  !! S8 (props%full) is the same element with the full 3×3 rule for the
  !! membrane strains and the transverse shear as well (Abaqus's S8): no
  !! hourglass mode, shear locking on thin meshes (tests/decks/s8_cantilever.deck);
  !! its stresses are taken at the same 2×2 points as S8R's.
  !!
  !! S6 (CalculiX's six-node triangular shell, FreeCAD's tria6 shell mesh) is
  !! the same degenerated solid on the 6-node triangle (corners 1-3, mid-side
  !! nodes 4 (1-2), 5 (2-3), 6 (3-1); natural coordinates ξ, η on the unit
  !! triangle), every in-plane integral with Dunavant's 7-point rule (degree
  !! 5). Its transverse shear is assumed, not taken from the displacements
  !! (a mixed interpolation of the covariant components e_ξζ, e_ηζ as in
  !! Bathe's MITC triangles; the displacement-based one locks as t → 0): the
  !! field (e_ξζ, e_ηζ) = (a1 + b1 ξ + c1 η + η (d ξ + e η), a2 + b2 ξ + c2 η
  !! - ξ (d ξ + e η)), whose tangential component is linear along each edge,
  !! tied to the displacements' tangential covariant shear at the two Gauss
  !! points of each edge and to both components at the centroid (eight
  !! conditions, eight coefficients), at the same ζ; the lamina shears are the
  !! displacements' ones corrected by the difference, so an element whose
  !! shear field the space holds is the displacement-based one exactly. Its
  !! stresses are taken at the three points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3)
  !! (point k next to corner k) and extrapolated linearly to the corners.
  !! superjoin_elements_shell8 serves the three types: the node count (6 or
  !! 8) chooses the shape functions and the rules.
  !!
  !! Drilling: θ·n produces no strain; the element adds the penalty
  !!   ½ DRILL_FACTOR G t ∫ (θ·e3 - ω)² dA,   ω = ½ (∂u2/∂x1 - ∂u1/∂x2),
  !! the in-plane rotation of the mid-surface (Hughes-Brezzi), with the 3×3
  !! rule so that the eight normal rotations are all held. Rigid rotations
  !! have θ·e3 = ω: the element keeps exactly six rigid modes.
  !!
  !! Spurious modes (tests/unit/test_shell8.f90): a single flat element has
  !! exactly six zero eigenvalues and one near-zero mode, the membrane
  !! hourglass of the 2×2 rule (CPS8R's), held only by the drilling penalty;
  !! a curved element has none (bending holds it), and in a patch of elements
  !! it is not communicable (no near-zero mode). No hourglass control is added.
  !! Known limitation: on distorted (non-parallelogram) elements the element
  !! does not pass the constant-curvature patch test; the error grows as
  !! t → 0 (shear locking of the 2×2 shear constraints; measured in the unit
  !! test and doc/verification.md). Constant membrane strain passes on
  !! distorted meshes, constant curvature on parallelograms.
  !!
  !! Tapered sections (*NODAL THICKNESS varying inside the element): the
  !! director of node i has the length t_i (X = Σ N_i (x_i + ζ t_i/2 n_i),
  !! U = Σ N_i (u_i + ζ t_i/2 θ_i × n_i)), so the thickness is interpolated
  !! with the shape functions, t(ξ, η) = Σ N_i t_i, in the Jacobian and
  !! everywhere through it (stiffness, resultants, thermal strains); the
  !! transverse shear modulus ks/t of the section and the drilling modulus
  !! per unit thickness are constants, the mass per unit area is ρ t(ξ, η)
  !! (shell8_volume_shares, shell8_mass). With equal t_i the element is the
  !! untapered one, bit for bit (the untapered formulas are kept).
  !!
  !! Thermal strains (shell8_thermal_load): ε0(ζ) = α ΔT + α ∂T/∂n z,
  !! z = ζ t/2 along e3, in the plane (ε11 = ε22, γ12 = 0), integrated with
  !! the same rules as the stiffness (membrane 2×2, bending 3×3), so a free
  !! element that can follow ε0 exactly is stress-free to round-off.
  !!
  !! Errors come back as error_t (code EXIT_DECK) with a message without
  !! file:line; the caller prefixes it.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_frame, only: cross, require_positive
  use superjoin_elements_membrane, only: plane_stress, check_plane_material
  use superjoin_elements_quadratic, only: quadratic_shape
  use superjoin_elements_quadrature, only: quad_rule_t, gauss_square, triangle_rule, TRI_THREE, TRI_DUNAVANT5
  use superjoin_elements_traction, only: surface_load_t, point_force, LOAD_PRESSURE
  implicit none (type, external)
  private

  integer, parameter :: NN = 8              !! nodes of the quadrilaterals S8R, S8 (the most)
  integer, parameter :: NN_TRI = 6          !! nodes of the triangle S6
  integer, parameter :: NDN = 6             !! DOFs per node
  integer, parameter :: NDOF = NN*NDN
  integer, parameter :: NSTR = 5            !! ε11, ε22, γ12, γ13, γ23
  real(wp), parameter :: XI_NODE(NN) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp]
  real(wp), parameter :: ETA_NODE(NN) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]
  real(wp), parameter :: TRI_XI(NN_TRI) = [0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp]
  real(wp), parameter :: TRI_ETA(NN_TRI) = [0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, 0.5_wp]
  real(wp), parameter :: G2 = 1/sqrt(3.0_wp)                    !! 2-point Gauss abscissa
  real(wp), parameter, public :: S8R_DRILL_FACTOR = 1.0e-2_wp
    !! Drilling penalty as a fraction of G t (see the module header).
  real(wp), parameter :: JACOBIAN_TOL = 1.0e-10_wp
    !! det J at a point of the surface rule must exceed this × (element size)² × t.
  real(wp), parameter :: TIE_A = 0.5_wp - 0.5_wp/sqrt(3.0_wp), TIE_B = 0.5_wp + 0.5_wp/sqrt(3.0_wp)
    !! S6: the two Gauss points of an edge (fractions of its length), where the shear is tied.
  integer, parameter :: NTIE = 8
    !! S6: tying conditions and coefficients of the assumed transverse shear.
  real(wp), parameter :: TIE_POINTS(2, NTIE) = reshape([TIE_A, 0.0_wp, TIE_B, 0.0_wp, TIE_B, TIE_A, TIE_A, TIE_B, &
       0.0_wp, TIE_B, 0.0_wp, TIE_A, 1.0_wp/3, 1.0_wp/3, 1.0_wp/3, 1.0_wp/3], [2, NTIE])
    !! S6: the tying points (ξ, η): edge 1-2, edge 2-3, edge 3-1 (two each), the centroid (twice).
  real(wp), parameter :: TIE_FORMS(2, NTIE) = reshape([1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, &
       0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, NTIE])
    !! S6: the tied functional at each point (weights of e_ξζ, e_ηζ): the edge's tangential shear, then each component.

  type :: point_t
    !! Geometry of one point (ξ, η, ζ).
     real(wp) :: nf(NN) = 0.0_wp            !! shape functions (1:n)
     real(wp) :: dn(2, NN) = 0.0_wp         !! ∂N/∂(ξ, η)
     real(wp) :: jinv(3, 3) = 0.0_wp        !! ∂(ξ, η, ζ)/∂x
     real(wp) :: detj = 0.0_wp
     real(wp) :: r(3, 3) = 0.0_wp           !! rows: lamina axes e1, e2, e3
  end type point_t

  type, public :: shell8_props_t
    !! Section and material of one S8R, S8 or S6.
     real(wp) :: t = 0.0_wp                 !! thickness
     real(wp) :: e = 0.0_wp                 !! Young's modulus
     real(wp) :: nu = 0.0_wp                !! Poisson's ratio
     real(wp) :: ks(2) = 0.0_wp             !! transverse shear stiffness per unit length (local x, y)
     logical :: tapered = .false.           !! the thickness varies: tn at the nodes
     real(wp) :: tn(NN) = 0.0_wp            !! tapered: thickness at each node (t is then a mean, ks/t the shear modulus)
     logical :: full = .false.              !! S8: membrane and transverse shear with the full 3×3 rule too
  end type shell8_props_t

  public :: shell8_stiffness, shell8_resultants, shell8_area_shares, shell8_pressure_load, shell8_surface_load
  public :: shell8_stresses, shell8_stress_points

  integer, parameter, public :: S8R_STRESS_POINTS = 4
    !! Stress points of shell8_stresses on a quadrilateral: the 2×2 reduced rule (S6: 3).
  integer, parameter, public :: S8R_SECTION_POINTS = 3
    !! Section points of shell8_stresses: 1 bottom, 2 top, 3 mid-surface.
  integer, parameter :: NTENSOR = 6          !! global tensor xx, yy, zz, xy, xz, yz
  real(wp), parameter :: SHEAR_PEAK = 1.5_wp
    !! τ(z = 0) = 1.5 q / t, the peak of the parabolic transverse shear of a homogeneous section.
  public :: shell8_volume_shares, shell8_mass, shell8_thermal_load, shell8_thermal_resultants

contains

  pure integer function shell8_stress_points(nnode) result(n)
    !! Stress points of shell8_stresses of an element with nnode nodes: 4 (S8R, S8), 3 (S6).
    integer, intent(in) :: nnode
    n = merge(3, S8R_STRESS_POINTS, nnode == NN_TRI)
  end function shell8_stress_points

  pure subroutine shell8_stiffness(x, ex, props, ke, error)
    !! Stiffness ke(6n, 6n) in global axes (ux, uy, uz, rx, ry, rz per node,
    !! node-major) of an S8R, S8 or S6 with nodes x(3, n), n = 8 or 6; ex is
    !! the element's local x axis (its projection on the tangent plane is the
    !! lamina e1).
    real(wp), intent(in) :: x(:, :), ex(3)
    type(shell8_props_t), intent(in) :: props
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: dir(3, size(x, 2)), d(NSTR, NSTR), b(NSTR, NDN*size(x, 2)), dr(NDN*size(x, 2)), gmod, kd, tp
    real(wp) :: bm(3, NDN*size(x, 2)), bb(3, NDN*size(x, 2)), detj(2)
    real(wp), allocatable :: ties(:, :, :)
    type(quad_rule_t) :: full, inplane
    type(point_t) :: pt
    integer :: i, k, ndof

    call check(x, props, dir, error)
    if (allocated(error)) return
    ndof = NDN*size(x, 2)
    ties = shear_ties(x, dir, props)
    d = material(props)
    full = surface_rule(size(x, 2))
    inplane = in_plane_rule(props, size(x, 2))
    allocate (ke(ndof, ndof), source=0.0_wp)
    ! in-plane strains: the membrane part (mean of the two ζ points) with the
    ! in-plane rule (S8R 2×2), the bending part (their difference) with the full one (3×3)
    do i = 1, size(full%w)
       call in_plane_parts(x, dir, ex, props, full%xi(:, i), bm, bb, detj)
       ke = ke + (2*full%w(i)*G2**2)*sum(detj)/2*matmul(transpose(bb), matmul(d(1:3, 1:3), bb))
    end do
    do i = 1, size(inplane%w)
       call in_plane_parts(x, dir, ex, props, inplane%xi(:, i), bm, bb, detj)
       ke = ke + (inplane%w(i)*sum(detj))*matmul(transpose(bm), matmul(d(1:3, 1:3), bm))
    end do
    ! transverse shear: the in-plane rule (S6: the full one), ×2 through the thickness
    if (size(x, 2) == NN_TRI) inplane = full
    do i = 1, size(inplane%w)
       do k = 1, 2
          call point(x, dir, ex, props, [inplane%xi(:, i), gauss2(k)], pt)
          b = shell_strain_rows(x, dir, props, pt, [inplane%xi(:, i), gauss2(k)], ties(:, :, k))
          ke = ke + (inplane%w(i)*pt%detj)*matmul(transpose(b(4:5, :)), matmul(d(4:5, 4:5), b(4:5, :)))
       end do
    end do
    ! drilling penalty: the full rule on the mid-surface (ζ = 0; ∫ dζ = 2, det J ≈ t/2 dA)
    gmod = props%e/(2*(1 + props%nu))
    do i = 1, size(full%w)
       call point(x, dir, ex, props, [full%xi(:, i), 0.0_wp], pt)
       dr = drill_row(pt, dir, nodal_thickness(props, size(x, 2)))
       tp = thickness_at(props, pt%nf(1:size(x, 2)))
       kd = S8R_DRILL_FACTOR*gmod*tp
       do k = 1, ndof
          ke(:, k) = ke(:, k) + (kd*full%w(i)*2*pt%detj/tp)*dr(k)*dr
       end do
    end do
    ke = 0.5_wp*(ke + transpose(ke))
  end subroutine shell8_stiffness

  pure subroutine shell8_resultants(x, ex, props, ue, res, q, error)
    !! Resultants per unit length at the element centre (ξ = η = 0; S6 its
    !! centroid) in the lamina frame there (e1 along the projection of ex):
    !! res = nx, ny, nxy, mx, my, mxy (m = ∫ σ z dz, the signs of the other
    !! shells) and the transverse shear forces q = qx, qy; ue(6n) in global axes.
    real(wp), intent(in) :: x(:, :), ex(3)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: res(6), q(2)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: dir(3, size(x, 2)), d(NSTR, NSTR), s(NSTR), z, tc, c(2)
    real(wp), allocatable :: ties(:, :, :)
    type(point_t) :: pt
    integer :: k

    res = 0.0_wp
    q = 0.0_wp
    call check(x, props, dir, error)
    if (allocated(error)) return
    if (size(ue) /= NDN*size(x, 2)) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    d = material(props)
    c = centre(size(x, 2))
    ties = shear_ties(x, dir, props)
    do k = 1, 2
       call point(x, dir, ex, props, [c, gauss2(k)], pt)
       s = matmul(d, matmul(shell_strain_rows(x, dir, props, pt, [c, gauss2(k)], ties(:, :, k)), ue))
       tc = thickness_at(props, pt%nf(1:size(x, 2)))
       z = gauss2(k)*tc/2
       ! 2-point rule through the thickness: weight 1 each, dz = t/2 dζ
       res(1:3) = res(1:3) + s(1:3)*tc/2
       res(4:6) = res(4:6) + s(1:3)*z*tc/2
       q = q + s(4:5)*tc/2
    end do
  end subroutine shell8_resultants

  pure subroutine shell8_stresses(x, ex, props, ue, sig_points, sig_nodes, error, thermal, thermal_nodal)
    !! Stress tensors (global axes, Voigt order xx, yy, zz, xy, xz, yz) of an
    !! S8R, S8 or S6 from its displacements ue(6n) (global axes):
    !! sig_points(6, np, 3) at its stress points (shell8_stress_points: the
    !! 2×2 points of the reduced rule, point k next to corner k (ξ, η = ±1/√3
    !! with the signs of corner k); S6 the three points (1/6, 1/6), (2/3,
    !! 1/6), (1/6, 2/3)), sig_nodes(6, n, 3) at the nodes; the last index is
    !! the section point: 1 bottom (ζ = -1, z = -t/2), 2 top (ζ = +1, along
    !! the surface normal a_ξ × a_η), 3 mid-surface.
    !! In-plane: ε(ζ) = εm + ζ εb with the membrane and bending parts of the
    !! stiffness (in_plane_parts, lamina frame), σ = D (ε - ε0(ζ)); the thermal
    !! strain ε0(ζ) = thermal(1) + ζ t/2 thermal(2) (α ΔT and α ∂T/∂n, the
    !! layout of the thermal fields of the other shells; isotropic in the
    !! plane, absent = 0) is the single thermal hook; thermal_nodal(2, n), the
    !! nodes' remainders of both (a temperature varying over the element), are
    !! interpolated to each point and added. So n = t σ_mid and
    !! m = t² (σ_top - σ_bot)/12 are the resultants of shell8_resultants.
    !! Transverse shear: 0 on the faces, 1.5 q/t on the mid-surface with q the
    !! shear force of the stiffness (mean of the two thickness points).
    !! Nodes: the point values of each component extrapolated to the corners,
    !! bilinearly from the 2×2 points (linearly from S6's three); a mid-side
    !! node takes the mean of its two corners, which is that field's value
    !! there (four points fix no quadratic field; CalculiX does the same for
    !! its reduced quadratic elements). Components are extrapolated in global
    !! axes, so the result does not depend on the lamina frame of a curved element.
    real(wp), intent(in) :: x(:, :), ex(3)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: sig_points(:, :, :)
    real(wp), intent(out) :: sig_nodes(:, :, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: thermal(2)
    real(wp), intent(in), optional :: thermal_nodal(:, :)
    real(wp) :: dir(3, size(x, 2)), d(NSTR, NSTR), bm(3, NDN*size(x, 2)), bb(3, NDN*size(x, 2)), detj(2)
    real(wp) :: b(NSTR, NDN*size(x, 2)), em(3), eb(3), gam(2), e0(2), s(NSTR), zeta, pp(2)
    real(wp), allocatable :: w(:), ties(:, :, :)
    real(wp), parameter :: SECTION_ZETA(S8R_SECTION_POINTS) = [-1.0_wp, 1.0_wp, 0.0_wp]
    type(point_t) :: pt
    integer :: k, kz, m, i, n, nc
    type(quad_rule_t) :: sp

    sig_points = 0.0_wp
    sig_nodes = 0.0_wp
    call check(x, props, dir, error)
    if (allocated(error)) return
    n = size(x, 2)
    if (size(ue) /= NDN*n) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    e0 = 0.0_wp
    d = material(props)
    sp = stress_rule(n)
    ties = shear_ties(x, dir, props)
    do k = 1, size(sp%w)
       pp = sp%xi(:, k)
       call in_plane_parts(x, dir, ex, props, pp, bm, bb, detj)
       em = matmul(bm, ue)
       eb = matmul(bb, ue)
       gam = 0.0_wp
       do kz = 1, 2
          call point(x, dir, ex, props, [pp, gauss2(kz)], pt)
          b = shell_strain_rows(x, dir, props, pt, [pp, gauss2(kz)], ties(:, :, kz))
          gam = gam + matmul(b(4:5, :), ue)/2
       end do
       call point(x, dir, ex, props, [pp, 0.0_wp], pt)
       ! the thickness at the point (Σ N_i t_i when tapered) scales the gradient's strain
       if (present(thermal)) e0 = [thermal(1), thermal(2)*thickness_at(props, pt%nf(1:n))/2]
       if (present(thermal_nodal)) e0 = e0 + [dot_product(pt%nf(1:n), thermal_nodal(1, 1:n)), &
            dot_product(pt%nf(1:n), thermal_nodal(2, 1:n))*thickness_at(props, pt%nf(1:n))/2]
       do m = 1, S8R_SECTION_POINTS
          zeta = SECTION_ZETA(m)
          s = 0.0_wp
          s(1:3) = matmul(d(1:3, 1:3), em + zeta*eb - (e0(1) + zeta*e0(2))*[1.0_wp, 1.0_wp, 0.0_wp])
          if (m == 3) s(4:5) = SHEAR_PEAK*matmul(d(4:5, 4:5), gam)
          sig_points(:, k, m) = lamina_to_global(s, pt%r)
       end do
    end do
    nc = size(sp%w)   ! corners: 4 or 3, each next to its point
    do i = 1, nc
       w = corner_weights(n, i)
       do m = 1, S8R_SECTION_POINTS
          sig_nodes(:, i, m) = matmul(sig_points(:, 1:nc, m), w)
       end do
    end do
    do i = nc + 1, n
       sig_nodes(:, i, :) = (sig_nodes(:, i - nc, :) + sig_nodes(:, mod(i - nc, nc) + 1, :))/2
    end do
  end subroutine shell8_stresses

  pure subroutine shell8_area_shares(x, shares, error)
    !! shares(i) = ∫ N_i dA over the mid-surface (3×3 rule; S6 7 points): the
    !! nodal loads of a unit load per unit area (the corner shares of a flat
    !! S8R are negative, -1/12 of its area, the mid-side ones 1/3; of a flat
    !! S6 0 and 1/3).
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: shares(:)
    type(error_t), allocatable, intent(out) :: error
    call surface_shares(x, shares, error)
  end subroutine shell8_area_shares

  pure subroutine shell8_pressure_load(x, p, fe, error)
    !! Consistent nodal loads fe(6n) (global axes) of a uniform pressure p,
    !! positive against the normal a_ξ × a_η of the surface (the right-hand
    !! rule on the node order): f_i = -p ∫ N_i (a_ξ × a_η) dξ dη, 3×3 rule (S6 7 points).
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(in) :: p
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    call shell8_surface_load(x, surface_load_t(LOAD_PRESSURE, p), fe, error)
  end subroutine shell8_pressure_load

  pure subroutine shell8_surface_load(x, ld, fe, error)
    !! Consistent nodal loads fe(6n) (global axes) of the uniform surface load
    !! ld on the mid-surface, the surface rule: a pressure as
    !! shell8_pressure_load, or a traction (superjoin_elements_traction; TRSHR
    !! projected onto the tangent plane at each point of a curved element).
    real(wp), intent(in) :: x(:, :)
    type(surface_load_t), intent(in) :: ld
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: nf(size(x, 2)), dn(2, size(x, 2)), a(3, 2), nv(3), f(3)
    type(quad_rule_t) :: rl
    integer :: i, k
    call check_node_count(x, error)
    if (allocated(error)) return
    allocate (fe(NDN*size(x, 2)), source=0.0_wp)
    rl = surface_rule(size(x, 2))
    do i = 1, size(rl%w)
       call quadratic_shape(size(x, 2), rl%xi(:, i), nf, dn)
       a = matmul(x, transpose(dn))
       nv = cross(a(:, 1), a(:, 2))
       call point_force(ld, -rl%w(i)*nv, f, error)   ! a positive pressure pushes against a_ξ × a_η
       if (allocated(error)) return
       do k = 1, size(x, 2)
          fe(NDN*(k - 1) + 1:NDN*(k - 1) + 3) = fe(NDN*(k - 1) + 1:NDN*(k - 1) + 3) + nf(k)*f
       end do
    end do
  end subroutine shell8_surface_load

  pure subroutine shell8_volume_shares(x, props, shares, error)
    !! shares(i) = ∫ N_i t dA over the mid-surface (the surface rule, exact
    !! for a parallelogram and a straight-sided triangle): the nodal loads of a
    !! unit load per unit volume through the thickness (self weight / ρ g)
    !! with t = Σ N_j t_j.
    real(wp), intent(in) :: x(:, :)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(out) :: shares(:)
    type(error_t), allocatable, intent(out) :: error
    call surface_shares(x, shares, error, props)
  end subroutine shell8_volume_shares

  pure subroutine surface_shares(x, shares, error, props)
    !! shares(i) = ∫ N_i w dA over the mid-surface (the surface rule) with the
    !! weight w = the thickness t = Σ N_j t_j when props is present, else 1.
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: shares(:)
    type(error_t), allocatable, intent(out) :: error
    type(shell8_props_t), intent(in), optional :: props
    real(wp) :: nf(size(x, 2)), dn(2, size(x, 2)), a(3, 2), w
    type(quad_rule_t) :: rl
    integer :: i
    shares = 0.0_wp
    call check_node_count(x, error)
    if (allocated(error)) return
    rl = surface_rule(size(x, 2))
    do i = 1, size(rl%w)
       call quadratic_shape(size(x, 2), rl%xi(:, i), nf, dn)
       a = matmul(x, transpose(dn))
       w = 1.0_wp
       if (present(props)) w = thickness_at(props, nf)
       shares = shares + rl%w(i)*norm2(cross(a(:, 1), a(:, 2)))*w*nf
    end do
  end subroutine surface_shares

  pure subroutine shell8_mass(x, props, m, error)
    !! m(i, j) = ∫ N_i N_j t dA over the mid-surface (the consistent mass per
    !! unit density), t = Σ N_k t_k; 4×4 rule (exact for a tapered
    !! parallelogram: degree 6 in each direction); S6 7 points (degree 5:
    !! exact for a straight-sided triangle of one thickness).
    real(wp), intent(in) :: x(:, :)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(out) :: m(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: nf(size(x, 2)), dn(2, size(x, 2)), a(3, 2), w
    type(quad_rule_t) :: rl
    integer :: i, k
    m = 0.0_wp
    call check_node_count(x, error)
    if (allocated(error)) return
    if (size(x, 2) == NN_TRI) then
       rl = triangle_rule(TRI_DUNAVANT5)
    else
       rl = gauss_square(4)
    end if
    do i = 1, size(rl%w)
       call quadratic_shape(size(x, 2), rl%xi(:, i), nf, dn)
       a = matmul(x, transpose(dn))
       w = rl%w(i)*norm2(cross(a(:, 1), a(:, 2)))*thickness_at(props, nf)
       do k = 1, size(x, 2)
          m(:, k) = m(:, k) + w*nf(k)*nf
       end do
    end do
  end subroutine shell8_mass

  pure subroutine shell8_thermal_load(x, ex, props, strain, curvature, fe, error, strain_nodal, curvature_nodal, &
       self_energy)
    !! Consistent nodal loads fe(6n) (global axes) of the thermal strain
    !! ε0 = strain + curvature z in the plane of the lamina (z = ζ t/2 along
    !! e3; strain = α ΔT, curvature = α ∂T/∂n): ∫ Bᵀ D ε0 dV with the rules
    !! of the stiffness (membrane part 2×2, S8 3×3, bending part 3×3; S6 7
    !! points). With strain_nodal(n), curvature_nodal(n) (a temperature
    !! varying over the element: the nodes' remainders after strain and
    !! curvature) these are interpolated with the shape functions and added
    !! at every point. self_energy: ½ ∫ ε0ᵀ D ε0 dV by the same rules (the
    !! energy of the mechanical strains is ½ uᵀ K u - uᵀ fe + self_energy).
    real(wp), intent(in) :: x(:, :), ex(3)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(in) :: strain, curvature
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: strain_nodal(:), curvature_nodal(:)
    real(wp), intent(out), optional :: self_energy
    real(wp) :: dir(3, size(x, 2)), d(NSTR, NSTR), bm(3, NDN*size(x, 2)), bb(3, NDN*size(x, 2)), detj(2)
    real(wp) :: nf(size(x, 2)), dn(2, size(x, 2)), sn(size(x, 2)), cn(size(x, 2)), e0(3), wt, w0
    real(wp), parameter :: IN_PLANE(3) = [1.0_wp, 1.0_wp, 0.0_wp]
    type(quad_rule_t) :: rl
    integer :: i, n

    call check(x, props, dir, error)
    if (allocated(error)) return
    n = size(x, 2)
    sn = 0.0_wp
    cn = 0.0_wp
    if (present(strain_nodal)) sn = strain_nodal(1:n)
    if (present(curvature_nodal)) cn = curvature_nodal(1:n)
    d = material(props)
    allocate (fe(NDN*n), source=0.0_wp)
    w0 = 0.0_wp
    ! bending: dε0/dζ = curvature t/2 at the point
    if (curvature /= 0.0_wp .or. any(cn /= 0.0_wp)) then
       rl = surface_rule(n)
       do i = 1, size(rl%w)
          call in_plane_parts(x, dir, ex, props, rl%xi(:, i), bm, bb, detj)
          call quadratic_shape(n, rl%xi(:, i), nf, dn)
          wt = (2*rl%w(i)*G2**2)*sum(detj)/2
          e0 = (curvature + dot_product(nf, cn))*thickness_at(props, nf)/2*IN_PLANE
          fe = fe + wt*matmul(transpose(bb), matmul(d(1:3, 1:3), e0))
          w0 = w0 + 0.5_wp*wt*dot_product(e0, matmul(d(1:3, 1:3), e0))
       end do
    end if
    if (strain /= 0.0_wp .or. any(sn /= 0.0_wp)) then
       rl = in_plane_rule(props, n)
       do i = 1, size(rl%w)
          call in_plane_parts(x, dir, ex, props, rl%xi(:, i), bm, bb, detj)
          call quadratic_shape(n, rl%xi(:, i), nf, dn)
          e0 = (strain + dot_product(nf, sn))*IN_PLANE
          fe = fe + (rl%w(i)*sum(detj))*matmul(transpose(bm), matmul(d(1:3, 1:3), e0))
          w0 = w0 + 0.5_wp*rl%w(i)*sum(detj)*dot_product(e0, matmul(d(1:3, 1:3), e0))
       end do
    end if
    if (present(self_energy)) self_energy = w0
  end subroutine shell8_thermal_load

  pure subroutine shell8_thermal_resultants(props, strain, curvature, res, nnode)
    !! The resultants (nx, ny, nxy, mx, my, mxy, lamina frame) of the thermal
    !! strain at the element centre, as shell8_resultants integrates them:
    !! n = D ε0 t, m = D κ0 t³/12 (in-plane, equal biaxial): what K u gives
    !! and the element does not carry (N = D (ε - ε0)). nnode: 6 for an S6
    !! (its centroid; absent: 8).
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(in) :: strain, curvature
    real(wp), intent(out) :: res(6)
    integer, intent(in), optional :: nnode
    real(wp) :: d(NSTR, NSTR), tc
    real(wp), allocatable :: nf(:), dn(:, :)
    real(wp), parameter :: IN_PLANE(3) = [1.0_wp, 1.0_wp, 0.0_wp]
    integer :: n
    n = NN
    if (present(nnode)) n = nnode
    allocate (nf(n), dn(2, n))
    d = material(props)
    call quadratic_shape(n, centre(n), nf, dn)
    tc = thickness_at(props, nf)
    res(1:3) = matmul(d(1:3, 1:3), strain*IN_PLANE)*tc
    res(4:6) = matmul(d(1:3, 1:3), curvature*IN_PLANE)*tc**3/12
  end subroutine shell8_thermal_resultants

  ! ------------------------------------------------------------------ internals

  pure real(wp) function gauss2(i)
    !! Abscissa i (1, 2) of the 2-point Gauss rule.
    integer, intent(in) :: i
    gauss2 = merge(-G2, G2, i == 1)
  end function gauss2

  pure function centre(n) result(c)
    !! The natural coordinates of the centre of an element with n nodes (S6: its centroid).
    integer, intent(in) :: n
    real(wp) :: c(2)
    c = 0.0_wp
    if (n == NN_TRI) c = [1.0_wp, 1.0_wp]/3.0_wp
  end function centre

  pure function node_xi(n, i) result(c)
    !! The natural coordinates of node i of an element with n nodes.
    integer, intent(in) :: n, i
    real(wp) :: c(2)
    if (n == NN_TRI) then
       c = [TRI_XI(i), TRI_ETA(i)]
    else
       c = [XI_NODE(i), ETA_NODE(i)]
    end if
  end function node_xi

  pure function surface_rule(n) result(r)
    !! The rule of the surface integrals (bending, drilling, loads, the
    !! Jacobian's check): 3×3 Gauss on the quadrilateral, Dunavant's 7 points
    !! on the triangle (n = 6).
    integer, intent(in) :: n
    type(quad_rule_t) :: r
    if (n == NN_TRI) then
       r = triangle_rule(TRI_DUNAVANT5)
    else
       r = gauss_square(3)
    end if
  end function surface_rule

  pure function in_plane_rule(props, n) result(r)
    !! The in-plane rule of the membrane strains and the transverse shear:
    !! S8R's reduced 2×2 (unit weights) or, with props%full (S8), the 3×3
    !! Gauss rule; S6 (n = 6) the three points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3).
    type(shell8_props_t), intent(in) :: props
    integer, intent(in) :: n
    type(quad_rule_t) :: r
    if (n == NN_TRI) then
       r = triangle_rule(TRI_THREE)
    else
       r = gauss_square(merge(3, 2, props%full))
    end if
  end function in_plane_rule

  pure function stress_rule(n) result(r)
    !! The stress points, point k next to corner k: the 2×2 Gauss points
    !! (ξ, η = ±1/√3 with the signs of corner k), S6's three points (1/6, 1/6),
    !! (2/3, 1/6), (1/6, 2/3).
    integer, intent(in) :: n
    type(quad_rule_t) :: r
    integer :: k
    if (n == NN_TRI) then
       r = triangle_rule(TRI_THREE)
       return
    end if
    allocate (r%xi(2, S8R_STRESS_POINTS), r%w(S8R_STRESS_POINTS))
    do k = 1, S8R_STRESS_POINTS
       r%xi(:, k) = G2*[XI_NODE(k), ETA_NODE(k)]
    end do
    r%w = 1.0_wp
  end function stress_rule

  pure function corner_weights(n, i) result(w)
    !! Weights of the stress points' values (stress_rule) whose bilinear (S6:
    !! linear) field gives the value at corner i.
    integer, intent(in) :: n, i
    real(wp), allocatable :: w(:)
    integer :: k
    if (n == NN_TRI) then
       ! the linear field through the points of area coordinates 2/3, 1/6, 1/6: 2 L_k - 1/3
       w = [(-1.0_wp/3.0_wp, k = 1, 3)]
       w(i) = 5.0_wp/3.0_wp
       return
    end if
    allocate (w(S8R_STRESS_POINTS))
    do k = 1, S8R_STRESS_POINTS
       w(k) = (1 + sqrt(3.0_wp)*XI_NODE(i)*XI_NODE(k))*(1 + sqrt(3.0_wp)*ETA_NODE(i)*ETA_NODE(k))/4
    end do
  end function corner_weights

  pure subroutine check_node_count(x, error)
    !! An error unless x(3, n) has the nodes of an S8R, S8 (8) or S6 (6).
    real(wp), intent(in) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    if (size(x, 1) /= 3 .or. (size(x, 2) /= NN .and. size(x, 2) /= NN_TRI)) &
         call fatal_error(error, EXIT_DECK, 'an S8R or S8 needs 8 nodes, an S6 6')
  end subroutine check_node_count

  pure function nodal_thickness(props, n) result(tn)
    !! The thickness at the n nodes: tn of a tapered element, else t at each.
    type(shell8_props_t), intent(in) :: props
    integer, intent(in) :: n
    real(wp) :: tn(n)
    if (props%tapered) then
       tn = props%tn(1:n)
    else
       tn = props%t
    end if
  end function nodal_thickness

  pure real(wp) function thickness_at(props, nf)
    !! The thickness at a point with shape functions nf: Σ N_i t_i (tapered), else t.
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(in) :: nf(:)
    if (props%tapered) then
       thickness_at = dot_product(nf, props%tn(1:size(nf)))
    else
       thickness_at = props%t
    end if
  end function thickness_at

  pure function material(props) result(d)
    !! Lamina elasticity (ε11, ε22, γ12, γ13, γ23) -> stresses.
    type(shell8_props_t), intent(in) :: props
    real(wp) :: d(NSTR, NSTR)
    d = 0.0_wp
    d(1:3, 1:3) = plane_stress(props%e, props%nu)
    d(4, 4) = props%ks(1)/props%t
    d(5, 5) = props%ks(2)/props%t
  end function material

  pure subroutine check(x, props, dir, error)
    !! Data checks (node count, t, E, ν, ks, a positive Jacobian at the points
    !! of the surface rule) and the nodal directors dir(3, n).
    real(wp), intent(in) :: x(:, :)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(out) :: dir(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: nf(size(x, 2)), dn(2, size(x, 2)), a(3, 2), nv(3), size_e, ref(3), c(3)
    type(quad_rule_t) :: rl
    character(len=3) :: name
    integer :: i, n
    dir = 0.0_wp
    call check_node_count(x, error)
    if (allocated(error)) return
    n = size(x, 2)
    name = merge('S6 ', 'S8R', n == NN_TRI)
    call check_plane_material(props%t, props%e, props%nu, 'shells', error)
    if (allocated(error)) return
    call require_positive(minval(props%ks), 'transverse shear stiffness', error)
    if (allocated(error)) return
    if (props%tapered) then
       call require_positive(minval(props%tn(1:n)), 'nodal thickness', error)
       if (allocated(error)) return
    end if
    c = sum(x, dim=2)/n
    size_e = maxval(norm2(x - spread(c, 2, n), dim=1))
    if (n == NN_TRI) then
       ref = cross(x(:, 2) - x(:, 1), x(:, 3) - x(:, 1))
    else
       ref = cross(x(:, 3) - x(:, 1), x(:, 4) - x(:, 2))
    end if
    if (size_e <= 0.0_wp .or. norm2(ref) <= epsilon(1.0_wp)*size_e**2) then
       call fatal_error(error, EXIT_DECK, 'zero area (collinear or coincident nodes)')
       return
    end if
    rl = surface_rule(n)
    do i = 1, size(rl%w)
       call quadratic_shape(n, rl%xi(:, i), nf, dn)
       a = matmul(x, transpose(dn))
       nv = cross(a(:, 1), a(:, 2))
       if (dot_product(nv, ref)/norm2(ref) <= JACOBIAN_TOL*size_e**2) then
          call fatal_error(error, EXIT_DECK, 'distorted '//trim(name)//' (the surface Jacobian is not positive '// &
               'everywhere; check the node order and the mid-side nodes)')
          return
       end if
    end do
    do i = 1, n
       call quadratic_shape(n, node_xi(n, i), nf, dn)
       a = matmul(x, transpose(dn))
       nv = cross(a(:, 1), a(:, 2))
       if (norm2(nv) <= JACOBIAN_TOL*size_e**2) then
          call fatal_error(error, EXIT_DECK, 'distorted '//trim(name)//' (no normal at a node)')
          return
       end if
       dir(:, i) = nv/norm2(nv)
    end do
  end subroutine check

  pure subroutine point(x, dir, ex, props, p, pt)
    !! Geometry at p = (ξ, η, ζ): shape functions, inverse Jacobian, det J and
    !! the lamina frame.
    real(wp), intent(in) :: x(:, :), dir(:, :), ex(3), p(3)
    type(shell8_props_t), intent(in) :: props
    type(point_t), intent(out) :: pt
    real(wp) :: jac(3, 3), e1(3), e3(3)
    integer :: n
    n = size(x, 2)
    call jacobian(x, dir, props, p, pt%nf(1:n), pt%dn(:, 1:n), jac)
    pt%detj = det3(jac)
    pt%jinv = inv3(jac, pt%detj)
    e3 = cross(jac(:, 1), jac(:, 2))
    e3 = e3/norm2(e3)
    e1 = ex - dot_product(ex, e3)*e3
    if (norm2(e1) < 0.1_wp) e1 = jac(:, 1) - dot_product(jac(:, 1), e3)*e3   ! ex nearly normal
    e1 = e1/norm2(e1)
    pt%r(1, :) = e1
    pt%r(2, :) = cross(e3, e1)
    pt%r(3, :) = e3
  end subroutine point

  pure subroutine jacobian(x, dir, props, p, nf, dn, jac)
    !! jac(a, b) = ∂X_a/∂ξ_b at p = (ξ, η, ζ) (columns the covariant base
    !! vectors g_ξ, g_η, g_ζ), with the shape functions nf and their
    !! derivatives dn there.
    real(wp), intent(in) :: x(:, :), dir(:, :), p(3)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(out) :: nf(:), dn(:, :), jac(3, 3)
    real(wp) :: tn(size(x, 2))
    call quadratic_shape(size(x, 2), p(1:2), nf, dn)
    tn = nodal_thickness(props, size(x, 2))
    jac(:, 1:2) = matmul(x + spread(p(3)*tn/2, 1, 3)*dir, transpose(dn))
    if (props%tapered) then
       jac(:, 3) = matmul(dir, nf*tn)/2
    else
       jac(:, 3) = (props%t/2)*matmul(dir, nf)
    end if
  end subroutine jacobian

  pure function shell_strain_rows(x, dir, props, pt, p, tie) result(b)
    !! The strain rows b(5, 6n) at p = (ξ, η, ζ) with the geometry pt there:
    !! the displacements' (strain_rows); an S6's transverse shear rows the
    !! assumed field's (see the module header) from its tying values tie at
    !! that ζ (shear_ties; empty for the quadrilaterals).
    real(wp), intent(in) :: x(:, :), dir(:, :), p(3), tie(:, :)
    type(shell8_props_t), intent(in) :: props
    type(point_t), intent(in) :: pt
    real(wp) :: b(NSTR, NDN*size(x, 2))
    real(wp) :: ed(2, NDN*size(x, 2)), ea(2, NDN*size(x, 2)), c(3, 3)
    integer :: a, i
    b = strain_rows(pt, dir, nodal_thickness(props, size(x, 2)), p(3))
    if (size(x, 2) /= NN_TRI) return
    ed = covariant_shear(x, dir, props, p)
    ea = assumed_shear(p, tie)
    ! γ_a3 = 2 Σ_ij C(a, i) e_ij C(3, j), C(a, i) = e_a · g^i: the transverse
    ! covariant components' part replaced by the assumed ones
    c = matmul(pt%r, transpose(pt%jinv))
    do a = 1, 2
       do i = 1, 2
          b(3 + a, :) = b(3 + a, :) + 2*(c(a, i)*c(3, 3) + c(a, 3)*c(3, i))*(ea(i, :) - ed(i, :))
       end do
    end do
  end function shell_strain_rows

  pure function covariant_shear(x, dir, props, p) result(e)
    !! Rows e(2, 6n): the covariant transverse shear strains e_ξζ, e_ηζ
    !! (tensor components, ½ (g_i·U,ζ + g_ζ·U,i)) of the displacements at
    !! p = (ξ, η, ζ).
    real(wp), intent(in) :: x(:, :), dir(:, :), p(3)
    type(shell8_props_t), intent(in) :: props
    real(wp) :: e(2, NDN*size(x, 2))
    real(wp) :: nf(size(x, 2)), dn(2, size(x, 2)), jac(3, 3), tn(size(x, 2)), v(3), ev(3)
    integer :: i, k, col
    call jacobian(x, dir, props, p, nf, dn, jac)
    tn = nodal_thickness(props, size(x, 2))
    do i = 1, size(x, 2)
       do k = 1, 3
          col = NDN*(i - 1) + k
          ! a translation: U = N_i e_k, U,ζ = 0
          e(:, col) = 0.5_wp*jac(k, 3)*dn(:, i)
          ! a rotation: U = N_i ζ v, v = (t_i/2) e_k × n_i
          ev = 0.0_wp
          ev(k) = 1.0_wp
          v = (tn(i)/2)*cross(ev, dir(:, i))
          e(1, col + 3) = 0.5_wp*(nf(i)*dot_product(jac(:, 1), v) + p(3)*dn(1, i)*dot_product(jac(:, 3), v))
          e(2, col + 3) = 0.5_wp*(nf(i)*dot_product(jac(:, 2), v) + p(3)*dn(2, i)*dot_product(jac(:, 3), v))
       end do
    end do
  end function covariant_shear

  pure function shear_ties(x, dir, props) result(tie)
    !! An S6's tying values tie(8, 6n, 2): the displacements' functional of
    !! each tying condition (TIE_POINTS, TIE_FORMS) at the two thickness
    !! points ζ = ∓1/√3, formed once per element (they do not depend on the
    !! in-plane point); empty (0, 0, 2) for the quadrilaterals.
    real(wp), intent(in) :: x(:, :), dir(:, :)
    type(shell8_props_t), intent(in) :: props
    real(wp), allocatable :: tie(:, :, :)
    integer :: k, kz
    if (size(x, 2) /= NN_TRI) then
       allocate (tie(0, 0, 2))
       return
    end if
    allocate (tie(NTIE, NDN*size(x, 2), 2))
    do kz = 1, 2
       do k = 1, NTIE
          tie(k, :, kz) = matmul(TIE_FORMS(:, k), covariant_shear(x, dir, props, [TIE_POINTS(:, k), gauss2(kz)]))
       end do
    end do
  end function shear_ties

  pure function assumed_shear(p, tie) result(e)
    !! Rows e(2, 6n) of an S6's assumed covariant transverse shear (e_ξζ,
    !! e_ηζ) at p = (ξ, η, ζ): the field of the module header whose eight
    !! coefficients meet the tying conditions with the values tie(8, 6n) at
    !! the same ζ (shear_ties): along each edge the tangential component at
    !! its two Gauss points (edge 1-2 e_ξζ, edge 2-3 e_ηζ - e_ξζ, edge 3-1
    !! e_ηζ), and both components at the centroid.
    real(wp), intent(in) :: p(3), tie(:, :)
    real(wp) :: e(2, size(tie, 2))
    real(wp) :: pm(NTIE, NTIE), w(2, NTIE)
    integer :: k
    do k = 1, NTIE
       pm(k, :) = matmul(TIE_FORMS(:, k), shear_basis(TIE_POINTS(:, k)))
    end do
    ! e(p) = Φ(p) P⁻¹ T: w = Φ(p) P⁻¹, i.e. Pᵀ wᵀ = Φ(p)ᵀ
    w = transpose(solve8(transpose(pm), transpose(shear_basis(p(1:2)))))
    e = matmul(w, tie)
  end function assumed_shear

  pure function shear_basis(p) result(phi)
    !! The eight fields of the assumed shear at p = (ξ, η): rows e_ξζ, e_ηζ.
    real(wp), intent(in) :: p(2)
    real(wp) :: phi(2, NTIE)
    phi = 0.0_wp
    phi(1, 1:3) = [1.0_wp, p(1), p(2)]
    phi(2, 4:6) = [1.0_wp, p(1), p(2)]
    phi(:, 7) = [p(1)*p(2), -p(1)**2]
    phi(:, 8) = [p(2)**2, -p(1)*p(2)]
  end function shear_basis

  pure function solve8(a, b) result(x)
    !! x = a⁻¹ b for the small nonsingular a (Gaussian elimination with partial pivoting).
    real(wp), intent(in) :: a(:, :), b(:, :)
    real(wp) :: x(size(b, 1), size(b, 2))
    real(wp) :: m(size(a, 1), size(a, 2)), row(size(a, 2)), rrow(size(b, 2)), f
    integer :: i, k, piv, n
    n = size(a, 1)
    m = a
    x = b
    do k = 1, n
       piv = k - 1 + maxloc(abs(m(k:n, k)), dim=1)
       if (piv /= k) then
          row = m(k, :)
          m(k, :) = m(piv, :)
          m(piv, :) = row
          rrow = x(k, :)
          x(k, :) = x(piv, :)
          x(piv, :) = rrow
       end if
       do i = k + 1, n
          f = m(i, k)/m(k, k)
          m(i, k:n) = m(i, k:n) - f*m(k, k:n)
          x(i, :) = x(i, :) - f*x(k, :)
       end do
    end do
    do k = n, 1, -1
       x(k, :) = (x(k, :) - matmul(m(k, k + 1:n), x(k + 1:n, :)))/m(k, k)
    end do
  end function solve8

  pure function strain_rows(pt, dir, tn, zeta) result(b)
    !! Rows b(5, 6n) with (ε11, ε22, γ12, γ13, γ23) = b u in the lamina frame;
    !! tn: the thickness at the nodes.
    type(point_t), intent(in) :: pt
    real(wp), intent(in) :: dir(:, :), tn(:), zeta
    real(wp) :: b(NSTR, NDN*size(dir, 2))
    real(wp) :: g(3), h(3), a(3), qv(3), ev(3)
    integer :: i, k, col
    do i = 1, size(dir, 2)
       ! ∂U/∂X of the node's u: u ⊗ g; of its θ: (-(t/2) n × θ) ⊗ h
       g = matmul(pt%dn(:, i), pt%jinv(1:2, :))
       h = zeta*g + pt%nf(i)*pt%jinv(3, :)
       do k = 1, 3
          col = NDN*(i - 1) + k
          ev = 0.0_wp
          ev(k) = 1.0_wp
          a = matmul(pt%r, ev)
          qv = matmul(pt%r, g)
          b(:, col) = voigt(a, qv)
          a = matmul(pt%r, -(tn(i)/2)*cross(dir(:, i), ev))
          qv = matmul(pt%r, h)
          b(:, col + 3) = voigt(a, qv)
       end do
    end do
  end function strain_rows

  pure subroutine in_plane_parts(x, dir, ex, props, p, bm, bb, detj)
    !! In-plane strain rows (ε11, ε22, γ12) at p = (ξ, η) split into the
    !! membrane part bm (the mean of the two Gauss points through the
    !! thickness, ζ = ±1/√3) and the bending part bb = ∂ε/∂ζ (their
    !! difference over 2/√3); detj at the two points. With ε(ζ) = bm + ζ bb
    !! the energy density through the thickness is 2 bmᵀ D bm + (2/3) bbᵀ D bb
    !! times the mean det J (the cross term vanishes where det J does not vary
    !! through the thickness, i.e. on a flat element; on a curved one it is of
    !! relative order t/R and dropped).
    real(wp), intent(in) :: x(:, :), dir(:, :), ex(3), p(2)
    type(shell8_props_t), intent(in) :: props
    real(wp), intent(out) :: bm(:, :), bb(:, :), detj(2)
    type(point_t) :: pt
    real(wp) :: b(NSTR, NDN*size(x, 2), 2)
    integer :: k
    do k = 1, 2
       call point(x, dir, ex, props, [p, gauss2(k)], pt)
       b(:, :, k) = strain_rows(pt, dir, nodal_thickness(props, size(x, 2)), gauss2(k))
       detj(k) = pt%detj
    end do
    bm = (b(1:3, :, 1) + b(1:3, :, 2))/2
    bb = (b(1:3, :, 2) - b(1:3, :, 1))/(2*G2)
  end subroutine in_plane_parts

  pure function drill_row(pt, dir, tn) result(dr)
    !! Row dr(6n) with θ·e3 - ω = dr u at the point (ζ = 0); tn: the
    !! thickness at the nodes.
    type(point_t), intent(in) :: pt
    real(wp), intent(in) :: dir(:, :), tn(:)
    real(wp) :: dr(NDN*size(dir, 2))
    real(wp) :: g(3), h(3), a(3), qv(3), ev(3)
    integer :: i, k, col
    do i = 1, size(dir, 2)
       g = matmul(pt%dn(:, i), pt%jinv(1:2, :))
       h = pt%nf(i)*pt%jinv(3, :)
       do k = 1, 3
          col = NDN*(i - 1) + k
          ev = 0.0_wp
          ev(k) = 1.0_wp
          a = matmul(pt%r, ev)
          qv = matmul(pt%r, g)
          dr(col) = -0.5_wp*(a(2)*qv(1) - a(1)*qv(2))
          a = matmul(pt%r, -(tn(i)/2)*cross(dir(:, i), ev))
          qv = matmul(pt%r, h)
          dr(col + 3) = pt%nf(i)*pt%r(3, k) - 0.5_wp*(a(2)*qv(1) - a(1)*qv(2))
       end do
    end do
  end function drill_row

  pure function lamina_to_global(s, r) result(t)
    !! Lamina stresses s = (σ11, σ22, τ12, τ13, τ23) in the frame with rows
    !! r = e1, e2, e3 as a global tensor, Voigt order xx, yy, zz, xy, xz, yz.
    real(wp), intent(in) :: s(NSTR), r(3, 3)
    real(wp) :: t(NTENSOR)
    real(wp) :: sl(3, 3), m(3, 3)
    sl = reshape([s(1), s(3), s(4), s(3), s(2), s(5), s(4), s(5), 0.0_wp], [3, 3])
    m = matmul(transpose(r), matmul(sl, r))
    t = [m(1, 1), m(2, 2), m(3, 3), m(1, 2), m(1, 3), m(2, 3)]
  end function lamina_to_global

  pure function voigt(a, q) result(s)
    !! Strains of the displacement gradient a ⊗ q (lamina frame).
    real(wp), intent(in) :: a(3), q(3)
    real(wp) :: s(NSTR)
    s = [a(1)*q(1), a(2)*q(2), a(1)*q(2) + a(2)*q(1), a(1)*q(3) + a(3)*q(1), a(2)*q(3) + a(3)*q(2)]
  end function voigt

  pure real(wp) function det3(m)
    !! Determinant of a 3 x 3 matrix.
    real(wp), intent(in) :: m(3, 3)
    det3 = dot_product(m(:, 1), cross(m(:, 2), m(:, 3)))
  end function det3

  pure function inv3(m, det) result(v)
    !! Inverse of a 3 x 3 matrix with determinant det (rows: the cofactors).
    real(wp), intent(in) :: m(3, 3), det
    real(wp) :: v(3, 3)
    v(1, :) = cross(m(:, 2), m(:, 3))/det
    v(2, :) = cross(m(:, 3), m(:, 1))/det
    v(3, :) = cross(m(:, 1), m(:, 2))/det
  end function inv3
end module superjoin_elements_shell8
