program test_shell8_taper
  !! Unit tests of the S8R with a thickness per node (section_t%node_thickness)
  !! and of its body loads (superjoin_elements_shell8_loads): equal nodal
  !! thicknesses give the untapered element bit for bit (stiffness,
  !! resultants, self weight); a tapered element (flat and curved) has the
  !! zero-energy modes of the untapered one; its self weight and
  !! consistent mass integrate ρ t(ξ, η) exactly (total = ρ g × volume of a
  !! linearly tapered parallelogram, Σ_ij M_ij = volume); the thermal load of
  !! the untapered element equals K u_free of the free expansion; CENTRIF
  !! of a rigid rotation about an axis in the element gives the total
  !! ρ ω² ∫ r dV (closed form for a flat rectangle).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: section_t, material_t, dload_t, ET_S8R, SEC_SHELL, DLOAD_CENTRIF, &
       DLOAD_THERMAL
  use superjoin_elements, only: element_stiffness, shell_resultants, element_gravity_load, element_material_load
  use superjoin_elements_shell, only: shell8_props
  use superjoin_elements_shell8, only: shell8_mass
  use superjoin_testing, only: check, check_rel, finish
  use test_lapack, only: eigenvalues
  implicit none (type, external)

  integer, parameter :: NN = 8, NDOF = 48
  real(wp), parameter :: ZERO_EIG = 1.0e-13_wp   !! a zero eigenvalue (round-off), relative to the largest
  real(wp), parameter :: TOL = 1.0e-12_wp        !! round-off of sums over one element, relative
  real(wp), parameter :: E_MOD = 2.1e5_wp, NU = 0.3_wp, RHO = 7.8e-9_wp
  real(wp), parameter :: CORNERS(2, 4) = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
  real(wp), parameter :: XI_NODE(NN) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp]
  real(wp), parameter :: ETA_NODE(NN) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]

  call test_equal_thickness_is_untapered()
  call test_rigid_modes(.false.)
  call test_rigid_modes(.true.)
  call test_weight_and_mass()
  call test_thermal_free_field()
  call test_centrif_total()
  call finish()

contains

  subroutine element(curved, x)
    !! A 2 × 1 rectangle (flat) or the same wrapped on a cylinder of radius 3
    !! about the y axis (curved), nodes in the Abaqus order.
    logical, intent(in) :: curved
    real(wp), intent(out) :: x(3, NN)
    integer :: i
    do i = 1, NN
       x(:, i) = [1.0_wp + XI_NODE(i), 0.5_wp + 0.5_wp*ETA_NODE(i), 0.0_wp]
       if (curved) x(:, i) = [3*sin(x(1, i)/3), x(2, i), 3*cos(x(1, i)/3) - 3]
    end do
  end subroutine element

  subroutine data(tn, sec, mat)
    !! Section (thickness per node tn, or one when size(tn) == 1) and material.
    real(wp), intent(in) :: tn(:)
    type(section_t), intent(out) :: sec
    type(material_t), intent(out) :: mat
    mat%e = E_MOD
    mat%nu = NU
    mat%density = RHO
    mat%has_density = .true.
    mat%alpha = 1.2e-5_wp
    mat%has_expansion = .true.
    sec%kind = SEC_SHELL
    sec%thickness = sum(tn)/size(tn)
    if (size(tn) == NN) sec%node_thickness = tn
  end subroutine data

  function linear_t(x) result(tn)
    !! t = 0.1 + 0.05 x - 0.02 y at the nodes (linear: the serendipity
    !! interpolation reproduces it).
    real(wp), intent(in) :: x(3, NN)
    real(wp) :: tn(NN)
    tn = 0.1_wp + 0.05_wp*x(1, :) - 0.02_wp*x(2, :)
  end function linear_t

  subroutine test_equal_thickness_is_untapered()
    real(wp) :: x(3, NN), ue(NDOF), r1(6), r2(6), q(3)
    real(wp), allocatable :: k1(:, :), k2(:, :), f1(:), f2(:)
    type(section_t) :: s1, s2
    type(material_t) :: mat
    type(error_t), allocatable :: error
    integer :: i
    call element(.true., x)
    call data([0.07_wp], s1, mat)
    call data(spread(0.07_wp, 1, NN), s2, mat)
    s2%thickness = 0.07_wp
    call element_stiffness(ET_S8R, x, s1, mat, k1, error)
    call element_stiffness(ET_S8R, x, s2, mat, k2, error)
    call check(all(k1 == k2), 'equal nodal thicknesses: the stiffness of the untapered S8R, bit for bit')
    ! one node thicker by 1e-13: the tapered formulas, within round-off of the untapered ones
    s2%node_thickness(3) = 0.07_wp*(1 + 1.0e-13_wp)
    call element_stiffness(ET_S8R, x, s2, mat, k2, error)
    call check(maxval(abs(k1 - k2)) <= 1.0e-11_wp*maxval(abs(k1)), &
         'nodal thicknesses equal to 1e-13: the tapered formulas agree with the untapered ones (1e-11)')
    s2%node_thickness(3) = 0.07_wp
    do i = 1, NDOF
       ue(i) = sin(1.7_wp*i)
    end do
    call shell_resultants(ET_S8R, x, s1, mat, ue, r1, error)
    call shell_resultants(ET_S8R, x, s2, mat, ue, r2, error)
    call check(all(r1 == r2), 'equal nodal thicknesses: the resultants of the untapered S8R, bit for bit')
    call element_gravity_load(ET_S8R, x, s1, mat, [0.0_wp, 0.0_wp, -9.81e3_wp], f1, q, error)
    call element_gravity_load(ET_S8R, x, s2, mat, [0.0_wp, 0.0_wp, -9.81e3_wp], f2, q, error)
    call check_rel(sum(f2), sum(f1), TOL, 'equal nodal thicknesses: the self weight of the untapered S8R')
  end subroutine test_equal_thickness_is_untapered

  subroutine test_rigid_modes(curved)
    !! The zero-energy modes of the tapered element are those of the
    !! untapered one: the six rigid motions, and on the flat rectangle the
    !! membrane hourglass of the 2×2 rule (CPS8R's; on a rectangle the
    !! drilling penalty does not hold it, see test_shell8 for distorted ones).
    logical, intent(in) :: curved
    real(wp) :: x(3, NN), w(NDOF)
    integer :: nzero
    real(wp), allocatable :: ke(:, :)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    call element(curved, x)
    call data([0.1_wp], sec, mat)
    call element_stiffness(ET_S8R, x, sec, mat, ke, error)
    w = eigenvalues(ke)
    nzero = count(w <= ZERO_EIG*w(NDOF))
    call check(nzero == merge(6, 7, curved), merge('curved', 'flat  ', curved)//' untapered S8R: zero modes')
    call data(linear_t(x), sec, mat)
    call element_stiffness(ET_S8R, x, sec, mat, ke, error)
    call check(.not. allocated(error), 'tapered S8R stiffness without error')
    if (allocated(error)) return
    call check(maxval(abs(ke - transpose(ke))) == 0.0_wp, 'tapered S8R: exactly symmetric')
    w = eigenvalues(ke)
    call check(count(w <= ZERO_EIG*w(NDOF)) == nzero, merge('curved', 'flat  ', curved)// &
         ' tapered S8R: the zero modes of the untapered one')
    call check(w(nzero + 1) > 1.0e-8_wp*w(NDOF), merge('curved', 'flat  ', curved)// &
         ' tapered S8R: a clear gap above them')
    call check(w(1) > -ZERO_EIG*w(NDOF), 'tapered S8R: no negative eigenvalue')
  end subroutine test_rigid_modes

  subroutine test_weight_and_mass()
    !! Flat 2 × 1 rectangle, t = 0.1 + 0.05 x - 0.02 y: volume = area × t at
    !! the centroid (1, 0.5) = 2 × 0.14 = 0.28.
    real(wp), parameter :: VOLUME = 2.0_wp*(0.1_wp + 0.05_wp - 0.01_wp), G = 9.81e3_wp
    real(wp) :: x(3, NN), m(NN, NN), q(3), mom
    real(wp), allocatable :: fe(:)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    integer :: i
    call element(.false., x)
    call data(linear_t(x), sec, mat)
    call element_gravity_load(ET_S8R, x, sec, mat, [0.0_wp, 0.0_wp, -G], fe, q, error)
    call check(.not. allocated(error), 'tapered S8R self weight without error')
    if (allocated(error)) return
    call check_rel(sum(fe(3:NDOF:6)), -RHO*G*VOLUME, TOL, 'tapered S8R self weight: rho g times the volume')
    ! first moment about y: ∫ x t dA = ∫∫ x (0.1 + 0.05 x - 0.02 y) = 0.1*2*1 + 0.05*8/3 - 0.02*2*0.5 ... per x
    mom = 0.0_wp
    do i = 1, NN
       mom = mom + fe(6*i - 3)*x(1, i)
    end do
    call check_rel(mom, -RHO*G*(0.1_wp*2 + 0.05_wp*8/3 - 0.02_wp*2*0.5_wp), TOL, &
         'tapered S8R self weight: its moment about the y axis (centre of gravity of the taper)')
    call shell8_mass(x, shell8_props(sec, mat), m, error)
    call check_rel(sum(m), VOLUME, TOL, 'tapered S8R consistent mass: sum M_ij = volume')
    call check(maxval(abs(m - transpose(m))) <= TOL*maxval(abs(m)), 'tapered S8R consistent mass: symmetric')
  end subroutine test_weight_and_mass

  subroutine test_thermal_free_field()
    !! Untapered flat element: the thermal load of α ΔT and α ∂T/∂n equals
    !! K_e u_free, u_free = ε0 (x - c) in the plane, w = -κ (x² + y²)/2 with
    !! the rotations θx = ∂w/∂y, θy = -∂w/∂x.
    real(wp), parameter :: STRAIN = 6.0e-4_wp, KAPPA = 4.0e-3_wp
    real(wp) :: x(3, NN), u(NDOF), c(3)
    real(wp), allocatable :: ke(:, :), fe(:)
    type(section_t) :: sec
    type(material_t) :: mat
    type(dload_t) :: dl
    type(error_t), allocatable :: error
    integer :: i
    call element(.false., x)
    call data([0.05_wp], sec, mat)
    c = [1.0_wp, 0.5_wp, 0.0_wp]
    do i = 1, NN
       associate (d => x(:, i) - c)
         u(6*i - 5:6*i) = [STRAIN*d(1), STRAIN*d(2), -KAPPA*(d(1)**2 + d(2)**2)/2, -KAPPA*d(2), KAPPA*d(1), 0.0_wp]
       end associate
    end do
    call element_stiffness(ET_S8R, x, sec, mat, ke, error)
    dl%kind = DLOAD_THERMAL
    dl%value = STRAIN
    dl%curvature = KAPPA
    call element_material_load(ET_S8R, x, sec, mat, dl, fe, error)
    call check(.not. allocated(error), 'S8R thermal load without error')
    if (allocated(error)) return
    call check(maxval(abs(fe - matmul(ke, u))) <= TOL*maxval(abs(fe)), &
         'S8R thermal load (strain and gradient) = K u of the free expansion')
  end subroutine test_thermal_free_field

  subroutine test_centrif_total()
    !! Flat 2 × 1 rectangle of uniform t = 0.05 spinning about the y axis
    !! (x = 0): the total force along x is ρ ω² t ∫ x dA = ρ ω² t × 2, the
    !! moment about y of the forces along x is zero, the total along z 0.
    real(wp), parameter :: OMEGA2 = 1.0e4_wp
    real(wp) :: x(3, NN)
    real(wp), allocatable :: fe(:)
    type(section_t) :: sec
    type(material_t) :: mat
    type(dload_t) :: dl
    type(error_t), allocatable :: error
    call element(.false., x)
    call data([0.05_wp], sec, mat)
    dl%kind = DLOAD_CENTRIF
    dl%value = OMEGA2
    dl%point = [0.0_wp, 0.0_wp, 0.0_wp]
    dl%dir = [0.0_wp, 1.0_wp, 0.0_wp]
    call element_material_load(ET_S8R, x, sec, mat, dl, fe, error)
    call check(.not. allocated(error), 'S8R CENTRIF without error')
    if (allocated(error)) return
    call check_rel(sum(fe(1:NDOF:6)), RHO*OMEGA2*0.05_wp*2, TOL, 'S8R CENTRIF: total rho omega^2 t int x dA')
    call check(abs(sum(fe(2:NDOF:6))) + abs(sum(fe(3:NDOF:6))) <= TOL*sum(fe(1:NDOF:6)), &
         'S8R CENTRIF: nothing along the axis or normal to the plane of rotation')
  end subroutine test_centrif_total
end program test_shell8_taper
