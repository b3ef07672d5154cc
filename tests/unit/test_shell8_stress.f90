program test_shell8_stress
  !! Unit tests of the S8R stresses (superjoin_elements_shell8,
  !! shell8_stresses): the thermal hook (the free thermal expansion and
  !! curvature of a parallelogram element in an oblique position is stress
  !! free with the hook, and E/(1-ν) (α ΔT + z α ∂T/∂n) in the plane without
  !! it), the section-point layout (σ_mid the mean of bottom and top), the
  !! extrapolation of a random field (the bilinear field of the four points at
  !! the corners, the mean of the corners at the mid-side nodes), and the data
  !! checks.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_elements_shell8, only: shell8_props_t, shell8_stresses, S8R_STRESS_POINTS, S8R_SECTION_POINTS
  use superjoin_testing, only: check, check_close, finish
  use test_random, only: set_seed, rnd_in
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-10_wp         !! round-off, relative to the stress scale
  real(wp), parameter :: E_MOD = 2.1e5_wp, NU = 0.3_wp, T = 0.05_wp
  real(wp), parameter :: EPS0 = 1.0e-3_wp         !! α ΔT
  real(wp), parameter :: KAPPA = 4.0e-2_wp        !! α ∂T/∂n (1/length): κ t/2 = EPS0
  integer, parameter :: NN = 8, NDOF = 48, NT = 6
  real(wp), parameter :: XI_NODE(NN) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp]
  real(wp), parameter :: ETA_NODE(NN) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]
  real(wp), parameter :: SECTION_Z(S8R_SECTION_POINTS) = [-1.0_wp, 1.0_wp, 0.0_wp]

  call set_seed(20261124)
  call test_thermal_hook()
  call test_layout()
  call test_errors()
  call finish()

contains

  function oblique_frame() result(r)
    !! A fixed oblique rotation (rows: local x, y, z in global coordinates).
    real(wp) :: r(3, 3), a(3), b(3)
    a = [0.3_wp, -0.4_wp, 0.866_wp]
    a = a/norm2(a)
    b = [0.8_wp, 0.5_wp, 0.1_wp]
    b = b - dot_product(a, b)*a
    b = b/norm2(b)
    r(1, :) = b
    r(2, :) = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
    r(3, :) = a
  end function oblique_frame

  subroutine parallelogram(r, xl, x)
    !! A flat parallelogram element (local coordinates xl(2, 8)) placed in the frame r: x(3, 8).
    real(wp), intent(in) :: r(3, 3)
    real(wp), intent(out) :: xl(2, NN), x(3, NN)
    real(wp) :: a(2), b(2)
    integer :: i
    a = [0.6_wp, 0.1_wp]       ! half of side 1-2
    b = [0.15_wp, 0.45_wp]     ! half of side 1-4
    do i = 1, NN
       xl(:, i) = [0.2_wp, -0.1_wp] + XI_NODE(i)*a + ETA_NODE(i)*b
       x(:, i) = xl(1, i)*r(1, :) + xl(2, i)*r(2, :)
    end do
  end subroutine parallelogram

  function props() result(p)
    type(shell8_props_t) :: p
    p = shell8_props_t(t=T, e=E_MOD, nu=NU, ks=5.0_wp/6*E_MOD/(2*(1 + NU))*T*[1.0_wp, 1.0_wp])
  end function props

  subroutine test_thermal_hook()
    !! u = ε0 (x, y), w = -κ (x² + y²)/2, θx = -κ y, θy = κ x (local): the free
    !! expansion of ε0 + κ z, exactly in the serendipity space of a parallelogram.
    real(wp) :: r(3, 3), xl(2, NN), x(3, NN), ue(NDOF), ul(3), th(3)
    real(wp) :: sp(NT, S8R_STRESS_POINTS, S8R_SECTION_POINTS), sn(NT, NN, S8R_SECTION_POINTS)
    real(wp) :: sp0(NT, S8R_STRESS_POINTS, S8R_SECTION_POINTS), sn0(NT, NN, S8R_SECTION_POINTS)
    real(wp) :: scale, m(3, 3), want(NT), s
    type(error_t), allocatable :: error
    integer :: i, k, l
    r = oblique_frame()
    call parallelogram(r, xl, x)
    do i = 1, NN
       ul = [EPS0*xl(1, i), EPS0*xl(2, i), -KAPPA*(xl(1, i)**2 + xl(2, i)**2)/2]
       th = [-KAPPA*xl(2, i), KAPPA*xl(1, i), 0.0_wp]
       ue(6*i - 5:6*i - 3) = matmul(ul, r)
       ue(6*i - 2:6*i) = matmul(th, r)
    end do
    scale = E_MOD*(EPS0 + KAPPA*T/2)/(1 - NU)
    call shell8_stresses(x, r(1, :), props(), ue, sp, sn, error, [EPS0, KAPPA])
    call check(.not. allocated(error), 'thermal hook: no error')
    call check(maxval(abs(sp)) <= TOL*scale, 'thermal hook: the free expansion is stress free at the points')
    call check(maxval(abs(sn)) <= TOL*scale, 'thermal hook: the free expansion is stress free at the nodes')
    call shell8_stresses(x, r(1, :), props(), ue, sp0, sn0, error)
    call check(.not. allocated(error), 'no hook: no error')
    m = spread(r(1, :), 2, 3)*spread(r(1, :), 1, 3) + spread(r(2, :), 2, 3)*spread(r(2, :), 1, 3)
    do l = 1, S8R_SECTION_POINTS
       s = E_MOD/(1 - NU)*(EPS0 + SECTION_Z(l)*KAPPA*T/2)
       want = s*[m(1, 1), m(2, 2), m(3, 3), m(1, 2), m(1, 3), m(2, 3)]
       do k = 1, S8R_STRESS_POINTS
          call check(maxval(abs(sp0(:, k, l) - want)) <= TOL*scale, 'no hook: E/(1-nu) (eps0 + z kappa) at a point')
       end do
       do k = 1, NN
          call check(maxval(abs(sn0(:, k, l) - want)) <= TOL*scale, 'no hook: E/(1-nu) (eps0 + z kappa) at a node')
       end do
    end do
  end subroutine test_thermal_hook

  subroutine test_layout()
    !! Random displacements of a parallelogram: σ_mid = (σ_bot + σ_top)/2 in
    !! the plane, no transverse shear on the faces; nodes: the bilinear field
    !! of the four points (point k next to corner k) at the corners, the mean
    !! of the corners at the mid-side nodes.
    real(wp) :: r(3, 3), xl(2, NN), x(3, NN), ue(NDOF)
    real(wp) :: sp(NT, S8R_STRESS_POINTS, S8R_SECTION_POINTS), sn(NT, NN, S8R_SECTION_POINTS)
    real(wp) :: scale, f(NT), w, a, b
    type(error_t), allocatable :: error
    integer :: i, k, l
    r = oblique_frame()
    call parallelogram(r, xl, x)
    do i = 1, NDOF
       ue(i) = rnd_in(-1.0e-3_wp, 1.0e-3_wp)
    end do
    call shell8_stresses(x, r(1, :), props(), ue, sp, sn, error)
    call check(.not. allocated(error), 'layout: no error')
    scale = maxval(abs(sp))
    call check(scale > 0.0_wp, 'layout: random displacements stress the element')
    ! in-plane components of the lamina (the tensor less its transverse shear) are linear through the thickness
    do k = 1, S8R_STRESS_POINTS
       call check(maxval(abs(in_plane(sp(:, k, 3), r) - (in_plane(sp(:, k, 1), r) + in_plane(sp(:, k, 2), r))/2)) &
            <= TOL*scale, 'layout: mid-surface membrane stress is the mean of bottom and top')
       call check(maxval(abs(sp(:, k, 1) - in_plane(sp(:, k, 1), r))) <= TOL*scale, &
            'layout: no transverse shear on the bottom face')
    end do
    do l = 1, S8R_SECTION_POINTS
       do i = 1, 4
          f = 0.0_wp
          do k = 1, S8R_STRESS_POINTS
             a = sqrt(3.0_wp)*XI_NODE(i)*XI_NODE(k)
             b = sqrt(3.0_wp)*ETA_NODE(i)*ETA_NODE(k)
             w = (1 + a)*(1 + b)/4
             f = f + w*sp(:, k, l)
          end do
          call check(maxval(abs(sn(:, i, l) - f)) <= TOL*scale, 'layout: corner = bilinear extrapolation')
       end do
       do i = 5, NN
          f = (sn(:, i - 4, l) + sn(:, mod(i - 4, 4) + 1, l))/2
          call check(maxval(abs(sn(:, i, l) - f)) <= TOL*scale, 'layout: mid-side node = mean of its corners')
       end do
    end do
  end subroutine test_layout

  function in_plane(s, r) result(p)
    !! The tensor s (Voigt, global) projected on the plane of the rows r(1:2, :): P s P.
    real(wp), intent(in) :: s(NT), r(3, 3)
    real(wp) :: p(NT)
    real(wp) :: m(3, 3), pr(3, 3)
    m = reshape([s(1), s(4), s(5), s(4), s(2), s(6), s(5), s(6), s(3)], [3, 3])
    pr = spread(r(1, :), 2, 3)*spread(r(1, :), 1, 3) + spread(r(2, :), 2, 3)*spread(r(2, :), 1, 3)
    m = matmul(pr, matmul(m, pr))
    p = [m(1, 1), m(2, 2), m(3, 3), m(1, 2), m(1, 3), m(2, 3)]
  end function in_plane

  subroutine test_errors()
    !! Wrong DOF count, zero thickness: an error, not a crash.
    real(wp) :: r(3, 3), xl(2, NN), x(3, NN), ue(NDOF)
    real(wp) :: sp(NT, S8R_STRESS_POINTS, S8R_SECTION_POINTS), sn(NT, NN, S8R_SECTION_POINTS)
    type(shell8_props_t) :: p
    type(error_t), allocatable :: error
    r = oblique_frame()
    call parallelogram(r, xl, x)
    ue = 0.0_wp
    call shell8_stresses(x, r(1, :), props(), ue(1:NDOF - 1), sp, sn, error)
    call check(allocated(error), 'errors: wrong number of DOF values')
    p = props()
    p%t = 0.0_wp
    call shell8_stresses(x, r(1, :), p, ue, sp, sn, error)
    call check(allocated(error), 'errors: zero thickness')
    call check_close(maxval(abs(sp)), 0.0_wp, 0.0_wp, 'errors: stresses zeroed')
  end subroutine test_errors
end program test_shell8_stress
