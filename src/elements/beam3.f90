module superjoin_elements_beam3
  !! B32: three-node Timoshenko beam in space (DOFs 1..6 per node), isoparametric
  !! and quadratic in displacement, rotation and geometry, so the member may be
  !! curved. Node order as in Abaqus and CalculiX: end, middle, end (ξ = -1, 0, 1).
  !!
  !! Linear strains at a point with the local frame e1 (tangent), e2, e3:
  !!   ε = e1·u',  γy = e2·u' - e3·θ,  γz = e3·u' + e2·θ,  κ = (e1, e2, e3)·θ'
  !! (' = d/ds along the axis), with the rigidities EA, Ky, Kz (transverse shear
  !! stiffness: *TRANSVERSE SHEAR STIFFNESS or k G A, as B31), GJ, EIy, EIz; γy
  !! and κz belong to deflection along local y (Iz), γz and κy to local z (Iy).
  !! Two Gauss points along the axis (reduced integration, as Abaqus B32): no
  !! shear or membrane locking, and exactly the six rigid-body modes (12
  !! strain samples for 12 deformation modes).
  !!
  !! The local frame at a point is the B31 frame of the tangent: local y in the
  !! plane of the tangent and the section's orientation vector v (default global
  !! Z, global X for a tangent along Z), z = x × y.
  !!
  !! End forces are K_e u_e - f_eq at the end nodes (1 and 3) in the frame of
  !! the tangent there, as the other beams report them; the middle node's share
  !! follows from the element's equilibrium. Distributed loads w per unit length
  !! (global axes, along the curved axis) have the consistent nodal forces
  !! ∫ Nᵢ w ds (no nodal moments: the rotations are interpolated on their own);
  !! a B32 keeps its load in global axes where other beams use local ones.
  !!
  !! Thermal load (beam3_thermal_load): the nodal values of α ΔT and of the
  !! thermal curvatures α ∂T/∂y, α ∂T/∂z (local axes) are interpolated with the
  !! shape functions to the two Gauss points of the stiffness, where they are
  !! the initial strains ε0 = α ΔT, κy0 = α ∂T/∂z, κz0 = -α ∂T/∂y (fibres at +y
  !! grow by α (∂T/∂y) y: v'' = κz = -α ∂T/∂y; at +z: -w'' = κy = α ∂T/∂z), and
  !! the load is ∫ Bᵀ D ε0 ds by the same rule: a free element whose thermal
  !! strains its displacements can take (a uniform ΔT, a gradient constant or
  !! linear along a straight element) gets exactly K_e u_free, so it deforms
  !! freely without force. The end forces take its end-node shares off
  !! (beam3_thermal_end_forces): N = E A (ε - α ΔT), M = E I (κ - κ0).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, ET_B31
  use superjoin_elements_frame, only: beam_frame, require_positive, cross, ZERO_LENGTH_TOL
  implicit none (type, external)
  private

  integer, parameter :: NNODE = 3, NDOF = 6, NSTRAIN = 6
  real(wp), parameter :: G2 = 1/sqrt(3.0_wp)     !! 2-point Gauss abscissa (weights 1)
  real(wp), parameter :: XI_CHECK(5) = [-1.0_wp, -G2, 0.0_wp, G2, 1.0_wp]
    !! points where the tangent must point along the chord (node 1 to node 3)

  type :: beam3_props_t
    !! Rigidities of one B32 (diagonal of the section matrix).
     real(wp) :: d(NSTRAIN) = 0.0_wp     !! EA, Ky, Kz, GJ, EIy, EIz
  end type beam3_props_t

  public :: beam3_stiffness, beam3_end_forces, beam3_nodal_forces, beam3_load
  public :: beam3_thermal_load, beam3_thermal_end_forces, beam3_middle_section, beam3_thermal_energy
  public :: beam3_spin_load, beam3_spin_halves, beam3_end_shares

contains

  pure subroutine setup(x, sec, mat, p, error)
    !! Rigidities with the data checks (as B31), and the node geometry.
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(beam3_props_t), intent(out) :: p
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: g, ks(2), scale
    integer :: i, j

    if (size(x, 1) /= 3 .or. size(x, 2) /= NNODE) then
       call fatal_error(error, EXIT_DECK, 'a B32 element needs 3 nodes')
       return
    end if
    scale = maxval(abs(x))
    do j = 1, NNODE
       do i = 1, j - 1
          if (norm2(x(:, j) - x(:, i)) <= ZERO_LENGTH_TOL*scale) then
             call fatal_error(error, EXIT_DECK, 'coincident nodes')
             return
          end if
       end do
    end do
    ! the tangent must keep running from node 1 towards node 3 (ends, middle, Gauss points)
    do i = 1, size(XI_CHECK)
       if (.not. (dot_product(matmul(x, [XI_CHECK(i) - 0.5_wp, -2*XI_CHECK(i), XI_CHECK(i) + 0.5_wp]), &
            x(:, 3) - x(:, 1)) > 0.0_wp)) then
          call fatal_error(error, EXIT_DECK, 'folded element: the middle node is misplaced, or the '// &
               'element turns through 180 degrees or more')
          return
       end if
    end do
    call require_positive(sec%area, 'cross-section area A', error)
    call require_positive(sec%iy, 'moment of inertia Iy', error)
    call require_positive(sec%iz, 'moment of inertia Iz', error)
    call require_positive(sec%j, 'torsion constant J', error)
    call require_positive(mat%e, 'Young''s modulus E', error)
    call require_positive(sec%shear_factor, 'shear factor k', error)
    if (allocated(error)) return
    if (.not. (mat%nu > -1.0_wp)) then
       call fatal_error(error, EXIT_DECK, 'Poisson''s ratio nu must be greater than -1 for a beam')
       return
    end if
    g = mat%e/(2*(1 + mat%nu))
    ks = merge(sec%shear_k, sec%shear_factor*g*sec%area, sec%shear_k > 0.0_wp)
    p%d = [mat%e*sec%area, ks(1), ks(2), g*sec%j, mat%e*sec%iy, mat%e*sec%iz]
  end subroutine setup

  pure subroutine point(x, sec, xi, r, jac, nf, ds, error)
    !! At ξ: frame r (rows e1, e2, e3), jac = ds/dξ, shape functions nf and
    !! their derivatives along the axis ds = dN/ds.
    real(wp), intent(in) :: x(3, NNODE), xi
    type(section_t), intent(in) :: sec
    real(wp), intent(out) :: r(3, 3), jac, nf(NNODE), ds(NNODE)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: dn(NNODE), t(3), ends(3, 2), length
    nf = [xi*(xi - 1)/2, 1 - xi**2, xi*(xi + 1)/2]
    dn = [xi - 0.5_wp, -2*xi, xi + 0.5_wp]
    t = matmul(x, dn)
    jac = norm2(t)
    r = 0.0_wp
    ds = 0.0_wp
    if (.not. (jac > ZERO_LENGTH_TOL*max(maxval(abs(x)), norm2(x(:, 3) - x(:, 1))))) then
       call fatal_error(error, EXIT_DECK, 'zero-length or folded element (middle node misplaced)')
       return
    end if
    ds = dn/jac
    ends(:, 1) = 0.0_wp
    ends(:, 2) = t/jac
    call beam_frame(ET_B31, ends, sec, r, length, error)
  end subroutine point

  pure subroutine b_matrix(r, nf, ds, b)
    !! Strains (ε, γy, γz, κx, κy, κz) = b (u, θ per node).
    real(wp), intent(in) :: r(3, 3), nf(NNODE), ds(NNODE)
    real(wp), intent(out) :: b(NSTRAIN, NDOF*NNODE)
    integer :: i, o
    b = 0.0_wp
    do i = 1, NNODE
       o = NDOF*(i - 1)
       b(1, o + 1:o + 3) = ds(i)*r(1, :)
       b(2, o + 1:o + 3) = ds(i)*r(2, :)
       b(2, o + 4:o + 6) = -nf(i)*r(3, :)
       b(3, o + 1:o + 3) = ds(i)*r(3, :)
       b(3, o + 4:o + 6) = nf(i)*r(2, :)
       b(4, o + 4:o + 6) = ds(i)*r(1, :)
       b(5, o + 4:o + 6) = ds(i)*r(2, :)
       b(6, o + 4:o + 6) = ds(i)*r(3, :)
    end do
  end subroutine b_matrix

  pure subroutine beam3_stiffness(x, sec, mat, ke, error)
    !! Stiffness ke(18, 18) in global axes, node-major (u, θ per node), of a B32
    !! with nodes x(3, 3) (end, middle, end).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(beam3_props_t) :: p
    real(wp) :: r(3, 3), jac, nf(NNODE), ds(NNODE), b(NSTRAIN, NDOF*NNODE), xi
    integer :: k, i

    call setup(x, sec, mat, p, error)
    if (allocated(error)) return
    allocate (ke(NDOF*NNODE, NDOF*NNODE), source=0.0_wp)
    do k = 1, 2
       xi = merge(-G2, G2, k == 1)
       call point(x, sec, xi, r, jac, nf, ds, error)
       if (allocated(error)) return
       call b_matrix(r, nf, ds, b)
       do i = 1, NSTRAIN
          ke = ke + (jac*p%d(i))*spread(b(i, :), 2, NDOF*NNODE)*spread(b(i, :), 1, NDOF*NNODE)
       end do
    end do
    ke = 0.5_wp*(ke + transpose(ke))
  end subroutine beam3_stiffness

  pure subroutine beam3_load(x, w, fe, error)
    !! Consistent nodal loads fe(18) (global axes, node-major) of a load w(3)
    !! per unit length along the axis, global axes: ∫ Nᵢ w ds by 3 Gauss points.
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(in) :: w(3)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), parameter :: G3 = sqrt(0.6_wp), W3(3) = [5.0_wp, 8.0_wp, 5.0_wp]/9
    real(wp) :: xi, nf(NNODE), dn(NNODE)
    integer :: k, i

    allocate (fe(NDOF*NNODE), source=0.0_wp)
    if (size(x, 1) /= 3 .or. size(x, 2) /= NNODE) then
       call fatal_error(error, EXIT_DECK, 'a B32 element needs 3 nodes')
       return
    end if
    do k = 1, 3
       xi = G3*(k - 2)
       nf = [xi*(xi - 1)/2, 1 - xi**2, xi*(xi + 1)/2]
       dn = [xi - 0.5_wp, -2*xi, xi + 0.5_wp]
       do i = 1, NNODE
          fe(NDOF*(i - 1) + 1:NDOF*(i - 1) + 3) = fe(NDOF*(i - 1) + 1:NDOF*(i - 1) + 3) + &
               W3(k)*norm2(matmul(x, dn))*nf(i)*w
       end do
    end do
  end subroutine beam3_load

  pure subroutine beam3_end_forces(x, sec, mat, ue, w, f, error)
    !! Forces and moments the end nodes (1 and 3) exert on the element, each in
    !! the local frame of the tangent at that node: f(1:6, end) = n, vy, vz, t,
    !! my, mz (K_e u_e - f_eq with f_eq the consistent loads of w(3) per unit
    !! length, global axes).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(in) :: w(3)
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ke(:, :), fe(:)
    real(wp) :: fg(NDOF*NNODE), r(3, 3), jac, nf(NNODE), ds(NNODE)
    integer :: a, o

    f = 0.0_wp
    call beam3_stiffness(x, sec, mat, ke, error)
    if (allocated(error)) return
    if (size(ue) /= NDOF*NNODE) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    call beam3_load(x, w, fe, error)
    if (allocated(error)) return
    fg = matmul(ke, ue) - fe
    do a = 1, 2
       call point(x, sec, merge(-1.0_wp, 1.0_wp, a == 1), r, jac, nf, ds, error)
       if (allocated(error)) return
       o = merge(0, 2*NDOF, a == 1)
       f(1:3, a) = matmul(r, fg(o + 1:o + 3))
       f(4:6, a) = matmul(r, fg(o + 4:o + 6))
    end do
  end subroutine beam3_end_forces

  pure subroutine beam3_nodal_forces(x, sec, f, w, fg, error)
    !! K_e u_e - f_eq in global axes, node-major, from the end forces f(6, 2) of
    !! beam3_end_forces and the load w(3) per unit length (global axes): the ends
    !! rotated back, the middle node from the element's equilibrium (the forces
    !! sum to -∫ w ds, the moments about node 2 to -Σ (xᵢ - x₂) × f_eq,ᵢ).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: f(6, 2)
    real(wp), intent(in) :: w(3)
    real(wp), intent(out) :: fg(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: g(6, 2)
    real(wp), allocatable :: fe(:)

    fg = 0.0_wp
    if (size(x, 2) /= NNODE .or. size(fg) /= NDOF*NNODE) then
       call fatal_error(error, EXIT_DECK, 'a B32 element needs 3 nodes')
       return
    end if
    call global_end_forces(x, sec, f, g, error)
    if (allocated(error)) return
    call beam3_load(x, w, fe, error)
    if (allocated(error)) return
    fg(1:6) = g(:, 1)
    fg(13:18) = g(:, 2)
    fg(7:9) = -g(1:3, 1) - g(1:3, 2) - (fe(1:3) + fe(7:9) + fe(13:15))
    fg(10:12) = -g(4:6, 1) - g(4:6, 2) - cross(x(:, 1) - x(:, 2), g(1:3, 1) + fe(1:3)) &
         - cross(x(:, 3) - x(:, 2), g(1:3, 2) + fe(13:15))
  end subroutine beam3_nodal_forces

  pure subroutine beam3_thermal_load(x, sec, mat, th, fe, error)
    !! Consistent nodal loads fe(18) (global axes, node-major) ∫ Bᵀ D ε0 ds of
    !! the thermal strains of a B32 with the nodal values th(1:3, node) = α ΔT,
    !! α ∂T/∂y, α ∂T/∂z (local axes), interpolated to the two Gauss points of
    !! the stiffness (module header).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: th(3, NNODE)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    type(beam3_props_t) :: p
    real(wp) :: r(3, 3), jac, nf(NNODE), ds(NNODE), b(NSTRAIN, NDOF*NNODE), e0(NSTRAIN)
    integer :: k

    call setup(x, sec, mat, p, error)
    if (allocated(error)) return
    allocate (fe(NDOF*NNODE), source=0.0_wp)
    do k = 1, 2
       call point(x, sec, merge(-G2, G2, k == 1), r, jac, nf, ds, error)
       if (allocated(error)) return
       call b_matrix(r, nf, ds, b)
       e0 = initial_strain(th, nf)
       fe = fe + jac*matmul(p%d*e0, b)
    end do
  end subroutine beam3_thermal_load

  pure subroutine beam3_thermal_energy(x, sec, mat, th, ue, energy, error)
    !! The strain energy of the mechanical strains of a heated B32,
    !! ½ ∫ (B u_e - ε0)ᵀ D (B u_e - ε0) ds by the two Gauss points of the
    !! stiffness (th as beam3_thermal_load): ½ u_eᵀ K_e u_e - u_eᵀ f_th + ½ ∫ ε0ᵀ D ε0
    !! with the element's own rule, 0 for an element free to follow ε0.
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: th(3, NNODE), ue(:)
    real(wp), intent(out) :: energy
    type(error_t), allocatable, intent(out) :: error
    type(beam3_props_t) :: p
    real(wp) :: r(3, 3), jac, nf(NNODE), ds(NNODE), b(NSTRAIN, NDOF*NNODE), e(NSTRAIN)
    integer :: k
    energy = 0.0_wp
    call setup(x, sec, mat, p, error)
    if (allocated(error)) return
    do k = 1, 2
       call point(x, sec, merge(-G2, G2, k == 1), r, jac, nf, ds, error)
       if (allocated(error)) return
       call b_matrix(r, nf, ds, b)
       e = matmul(b, ue(1:NDOF*NNODE)) - initial_strain(th, nf)
       energy = energy + 0.5_wp*jac*sum(p%d*e**2)
    end do
  end subroutine beam3_thermal_energy

  pure function initial_strain(th, nf) result(e0)
    !! The initial strains ε0 = (α ΔT, 0, 0, 0, κy0, κz0) at a point with shape
    !! functions nf of the nodal values th (beam3_thermal_load; module header).
    real(wp), intent(in) :: th(3, NNODE), nf(NNODE)
    real(wp) :: e0(NSTRAIN), tp(3)
    tp = matmul(th, nf)
    e0 = [tp(1), 0.0_wp, 0.0_wp, 0.0_wp, tp(3), -tp(2)]
  end function initial_strain

  pure subroutine beam3_thermal_end_forces(x, sec, mat, th, f, error)
    !! The end-node shares f(6, 2) (local axes of the tangent at nodes 1 and 3,
    !! as beam3_end_forces) of the thermal load of beam3_thermal_load: what the
    !! end forces K_e u_e take off (N = E A (ε - α ΔT), M = E I (κ - κ0)).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: th(3, NNODE)
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fe(:)
    f = 0.0_wp
    call beam3_thermal_load(x, sec, mat, th, fe, error)
    if (allocated(error)) return
    call beam3_end_shares(x, sec, fe, f, error)
  end subroutine beam3_thermal_end_forces

  pure subroutine beam3_end_shares(x, sec, fe, f, error)
    !! The end-node shares f(6, 2) of nodal loads fe(18) (global axes), each in
    !! the local axes of the tangent at its node (1 and 3), as beam3_end_forces.
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: fe(:)
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), jac, nf(NNODE), ds(NNODE)
    integer :: a, o
    f = 0.0_wp
    do a = 1, 2
       call point(x, sec, merge(-1.0_wp, 1.0_wp, a == 1), r, jac, nf, ds, error)
       if (allocated(error)) return
       o = merge(0, 2*NDOF, a == 1)
       f(1:3, a) = matmul(r, fe(o + 1:o + 3))
       f(4:6, a) = matmul(r, fe(o + 4:o + 6))
    end do
  end subroutine beam3_end_shares

  pure function beam3_spin_load(x, spin) result(fe)
    !! Consistent nodal loads fe(18) (global axes, no nodal moments, as the
    !! B32's other line loads) of the centrifugal load per unit length
    !! q = c r, spin = (c = ρ A ω², a point p of the axis, its unit direction
    !! a), r the distance vector from the axis: ∫ Nᵢ q ds by 3 Gauss points
    !! (exact on a straight element: q and Nᵢ are quadratic in ξ).
    real(wp), intent(in) :: x(:, :), spin(7)
    real(wp) :: fe(NDOF*NNODE)
    real(wp), parameter :: G3 = sqrt(0.6_wp), W3(3) = [5.0_wp, 8.0_wp, 5.0_wp]/9
    real(wp) :: xi, nf(NNODE), dn(NNODE), q(3)
    integer :: k, a
    fe = 0.0_wp
    do k = 1, 3
       xi = G3*(k - 2)
       nf = [xi*(xi - 1)/2, 1 - xi**2, xi*(xi + 1)/2]
       dn = [xi - 0.5_wp, -2*xi, xi + 0.5_wp]
       q = W3(k)*norm2(matmul(x, dn))*spin_load(spin, matmul(x, nf))
       do a = 1, NNODE
          fe(NDOF*(a - 1) + 1:NDOF*(a - 1) + 3) = fe(NDOF*(a - 1) + 1:NDOF*(a - 1) + 3) + nf(a)*q
       end do
    end do
  end function beam3_spin_load

  pure function beam3_spin_halves(x, spin) result(h)
    !! h(1:3, k): the resultant of the centrifugal load (spin as
    !! beam3_spin_load) on half k of the element (1: ξ in [-1, 0], 2: [0, 1]),
    !! h(4:6, k) its moment about the middle node: what beam3_middle_section
    !! takes as `extra`.
    real(wp), intent(in) :: x(:, :), spin(7)
    real(wp) :: h(6, 2)
    integer :: a
    do a = 1, 2
       h(:, a) = half_load(x, [0.0_wp, 0.0_wp, 0.0_wp], merge(-1.0_wp, 1.0_wp, a == 1), spin)
    end do
  end function beam3_spin_halves

  pure function spin_load(spin, xp) result(q)
    !! The centrifugal load per unit length c r at the point xp (spin as beam3_spin_load).
    real(wp), intent(in) :: spin(7), xp(3)
    real(wp) :: q(3), r(3)
    r = xp - spin(2:4)
    r = r - dot_product(r, spin(5:7))*spin(5:7)
    q = spin(1)*r
  end function spin_load
  pure subroutine beam3_middle_section(x, sec, f, w, s, error, extra)
    !! The section forces at the middle node (ξ = 0), in the local frame of the
    !! tangent there: s = n, vy, vz, t, my, mz, signed as the end forces of
    !! node 3 (the force the part beyond the section exerts on the part before
    !! it). From the equilibrium of each half, with the end node's forces f(6, 2)
    !! (beam3_end_forces) and the load w(3) per unit length (global axes) on the
    !! half; the mean of the two (they differ by a load on the middle node). A
    !! simply supported member under q: M = q L²/8 there, where the mean of the
    !! end values is 0. extra(6, 2): the resultants and moments about the
    !! middle node of other loads on each half (beam3_spin_halves: CENTRIF).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: f(6, 2)
    real(wp), intent(in) :: w(3)
    real(wp), intent(out) :: s(6)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: extra(6, 2)
    real(wp) :: r(3, 3), jac, nf(NNODE), ds(NNODE), g(6, 2), half(6, 2), sf(3), sm(3)
    integer :: a
    s = 0.0_wp
    if (size(x, 1) /= 3 .or. size(x, 2) /= NNODE) then
       call fatal_error(error, EXIT_DECK, 'a B32 element needs 3 nodes')
       return
    end if
    call global_end_forces(x, sec, f, g, error)
    if (allocated(error)) return
    do a = 1, 2
       half(:, a) = half_load(x, w, merge(-1.0_wp, 1.0_wp, a == 1))
    end do
    if (present(extra)) half = half + extra
    ! before: S = -(g1 + W), M = -(m1 + (x1 - xm) x g1 + Mw); beyond: S = g3 + W, M = m3 + (x3 - xm) x g3 + Mw
    sf = 0.5_wp*(g(1:3, 2) + half(1:3, 2) - g(1:3, 1) - half(1:3, 1))
    sm = 0.5_wp*(g(4:6, 2) + cross(x(:, 3) - x(:, 2), g(1:3, 2)) + half(4:6, 2) &
         - g(4:6, 1) - cross(x(:, 1) - x(:, 2), g(1:3, 1)) - half(4:6, 1))
    call point(x, sec, 0.0_wp, r, jac, nf, ds, error)
    if (allocated(error)) return
    s(1:3) = matmul(r, sf)
    s(4:6) = matmul(r, sm)
  end subroutine beam3_middle_section

  pure subroutine global_end_forces(x, sec, f, g, error)
    !! The end forces f(6, 2) of beam3_end_forces (each in the frame of the
    !! tangent at its node) turned to global axes: g(6, 2).
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: f(6, 2)
    real(wp), intent(out) :: g(6, 2)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), jac, nf(NNODE), ds(NNODE)
    integer :: a
    g = 0.0_wp
    do a = 1, 2
       call point(x, sec, merge(-1.0_wp, 1.0_wp, a == 1), r, jac, nf, ds, error)
       if (allocated(error)) return
       g(1:3, a) = matmul(transpose(r), f(1:3, a))
       g(4:6, a) = matmul(transpose(r), f(4:6, a))
    end do
  end subroutine global_end_forces

  pure function half_load(x, w, side, spin) result(h)
    !! The resultant h(1:3) of the load w(3) per unit length (global axes) on
    !! the half ξ in [0, side] of the element, and its moment h(4:6) about the
    !! middle node, by 3 Gauss points; with spin, the centrifugal load too
    !! (beam3_spin_load).
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(in) :: w(3), side
    real(wp), intent(in), optional :: spin(7)
    real(wp) :: h(6)
    real(wp), parameter :: G3 = sqrt(0.6_wp), W3(3) = [5.0_wp, 8.0_wp, 5.0_wp]/9
    real(wp) :: xi, nf(NNODE), dn(NNODE), dw(3)
    integer :: k
    h = 0.0_wp
    do k = 1, 3
       xi = 0.5_wp*side*(1 + G3*(k - 2))
       nf = [xi*(xi - 1)/2, 1 - xi**2, xi*(xi + 1)/2]
       dn = [xi - 0.5_wp, -2*xi, xi + 0.5_wp]
       dw = w
       if (present(spin)) dw = dw + spin_load(spin, matmul(x, nf))
       dw = 0.5_wp*W3(k)*norm2(matmul(x, dn))*dw
       h(1:3) = h(1:3) + dw
       h(4:6) = h(4:6) + cross(matmul(x, nf) - x(:, 2), dw)
    end do
  end function half_load
end module superjoin_elements_beam3
