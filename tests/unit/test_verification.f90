program test_verification
  !! Verification decks with closed-form answers, solved through the whole
  !! pipeline (deck → transform → solver → recovery) and checked to round-off.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: model_t
  use superjoin_model_results, only: results_t
  use superjoin_testing, only: check, check_rel, check_close, finish
  use verification_support, only: disp, reaction, link_force, link_delta, solve_file, equilibrium_error
  use superjoin_elements_frame, only: cross
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-10_wp

  call cantilever_joint()
  call springs_series()
  call hinge_beam()
  call propped_spring()
  call oriented_joint()
  call prescribed_truss()
  call rigid_loop()
  call mixed_loop()
  call l_frame()
  call timoshenko_frame()
  call finish()

contains

  subroutine cantilever_joint()
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: ei = 2.0e11_wp*1.0e-4_wp, ea = 2.0e11_wp*1.0e-2_wp, p = -1000.0_wp, n = 5000.0_wp
    real(wp) :: v, th
    call solve_file('decks/cantilever_joint.deck', m, r)
    v = p*4.0_wp**3/(3*ei) + p/1.0e9_wp + p*2.0_wp**2/2.0e7_wp
    th = p*4.0_wp**2/(2*ei) + p*2.0_wp/2.0e7_wp
    call check_rel(disp(m, r, 'II', 15, 2, 1), v, TOL, 'cantilever_joint: tip deflection')
    call check_rel(disp(m, r, 'II', 15, 6, 1), th, TOL, 'cantilever_joint: tip rotation')
    call check_rel(disp(m, r, 'II', 15, 1, 2), n*4.0_wp/ea, TOL, 'cantilever_joint: axial tip')
    call check_rel(link_delta(m, r, 'J', 6, 1), p*2.0_wp/2.0e7_wp, TOL, 'cantilever_joint: joint kink delta')
    call check_rel(link_force(m, r, 'J', 6, 1), p*2.0_wp, TOL, 'cantilever_joint: joint moment g*delta')
    call check_rel(link_force(m, r, 'J', 2, 1), p, TOL, 'cantilever_joint: joint shear g*delta')
    call check_rel(link_force(m, r, 'J', 1, 2), n, TOL, 'cantilever_joint: RIGID axial force from equilibrium')
    call check_rel(reaction(m, r, 'I', 1, 2, 1), -p, TOL, 'cantilever_joint: support shear')
    call check_rel(reaction(m, r, 'I', 1, 6, 1), -4.0_wp*p, TOL, 'cantilever_joint: support moment')
    call check_rel(reaction(m, r, 'I', 1, 1, 2), -n, TOL, 'cantilever_joint: support axial')
    call check(equilibrium_error(r, 1) < TOL, 'cantilever_joint: equilibrium TIP')
    call check(equilibrium_error(r, 2) < TOL, 'cantilever_joint: equilibrium AXIAL')
  end subroutine cantilever_joint

  subroutine springs_series()
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: ea = 7.0e10_wp*1.0e-4_wp, p = 1000.0_wp
    real(wp) :: u
    call solve_file('decks/springs_series.deck', m, r)
    u = p*(1.0_wp/ea + 1/2.0e6_wp + 2.0_wp/ea + 1/5.0e6_wp + 0.5_wp/ea + 1/1.0e7_wp)
    call check_rel(disp(m, r, 'C', 2, 1, 1), u, TOL, 'springs_series: end displacement')
    call check_rel(disp(m, r, 'A', 1, 1, 1), p/1.0e7_wp, TOL, 'springs_series: elastic support')
    call check_rel(reaction(m, r, 'A', 1, 1, 1), -p, TOL, 'springs_series: elastic reaction')
    call check_rel(link_force(m, r, 'AB', 1, 1), p, TOL, 'springs_series: spring force AB')
    call check_rel(link_delta(m, r, 'BC', 1, 1), p/5.0e6_wp, TOL, 'springs_series: spring delta BC')
    call check(equilibrium_error(r, 1) < TOL, 'springs_series: equilibrium')
  end subroutine springs_series

  subroutine hinge_beam()
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: ei = 2.0e11_wp*8.0e-5_wp, p = -20000.0_wp, l = 6.0_wp, k = 4.0e6_wp
    call solve_file('decks/hinge_beam.deck', m, r)
    call check_rel(disp(m, r, 'LEFT', 4, 2, 1), p*l**3/(48*ei) + p*l**2/(16*k), TOL, 'hinge_beam: mid-span')
    call check_rel(disp(m, r, 'RIGHT', 4, 2, 1), disp(m, r, 'LEFT', 4, 2, 1), TOL, 'hinge_beam: RIGID shear')
    call check_rel(link_delta(m, r, 'SPLICE', 6, 1), -p*l/4/k, TOL, 'hinge_beam: kink = M/k')
    call check_rel(reaction(m, r, 'RIGHT', 7, 2, 1), -p/2, TOL, 'hinge_beam: right reaction')
    call check(equilibrium_error(r, 1) < TOL, 'hinge_beam: equilibrium')
  end subroutine hinge_beam

  subroutine propped_spring()
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: ei = 2.1e11_wp*2.0e-5_wp, l = 3.0_wp, k = 5.0e5_wp, p = -1000.0_wp, q = -2000.0_wp
    real(wp) :: v
    call solve_file('decks/propped_spring.deck', m, r)
    call check_rel(disp(m, r, 'MAIN', 4, 2, 1), p/(k + 3*ei/l**3), TOL, 'propped_spring: tip load')
    v = (q*l**4/(8*ei))/(1 + k*l**3/(3*ei))
    call check_rel(disp(m, r, 'MAIN', 4, 2, 2), v, TOL, 'propped_spring: uniform load')
    call check_rel(reaction(m, r, 'MAIN', 4, 2, 2), -k*v, TOL, 'propped_spring: spring reaction')
    call check(equilibrium_error(r, 1) < TOL, 'propped_spring: equilibrium TIP')
    call check(equilibrium_error(r, 2) < TOL, 'propped_spring: equilibrium UDL')
  end subroutine propped_spring

  subroutine oriented_joint()
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: e = 2.0e11_wp, g = e/2.5_wp, iy = 2.0e-5_wp, iz = 3.0e-5_wp, j = 1.5e-5_wp
    real(wp), parameter :: t = 100.0_wp, l = 4.0_wp, k1 = 3.0e5_wp, k2 = 2.0e6_wp
    real(wp) :: e2(3), mom(3), phi(3), f(3), arm(3), du(3), c, s
    call solve_file('decks/oriented_joint.deck', m, r)
    call check_rel(disp(m, r, 'II', 3, 4, 1), t*l/(g*j) + t/k1, TOL, 'oriented_joint: twist')
    call check_rel(link_force(m, r, 'JOINT', 4, 1), t, TOL, 'oriented_joint: torsion moment')
    ! Shear step: beam bending plus the kink about local axis 2 of the joint.
    c = sqrt(3.0_wp)/2
    s = 0.5_wp
    e2 = [0.0_wp, c, s]
    f = [0.0_wp, 500.0_wp, -300.0_wp]
    arm = [2.0_wp, 0.0_wp, 0.0_wp]
    mom = cross(arm, f)
    phi = dot_product(mom, e2)/k2*e2
    du = cross(phi, arm)
    ! global Y bends with Iy (local z = -Y), global Z with Iz (local y = Z)
    call check_rel(disp(m, r, 'II', 3, 2, 2), f(2)*l**3/(3*e*iy) + du(2), TOL, 'oriented_joint: tip Y')
    call check_rel(disp(m, r, 'II', 3, 3, 2), f(3)*l**3/(3*e*iz) + du(3), TOL, 'oriented_joint: tip Z')
    call check_rel(link_delta(m, r, 'JOINT', 5, 2), dot_product(mom, e2)/k2, TOL, 'oriented_joint: local kink')
    call check_close(link_delta(m, r, 'JOINT', 6, 2), 0.0_wp, 1.0e-18_wp, 'oriented_joint: RIGID local 3')
    call check(equilibrium_error(r, 1) < TOL, 'oriented_joint: equilibrium TORQUE')
    call check(equilibrium_error(r, 2) < TOL, 'oriented_joint: equilibrium SHEAR')
  end subroutine oriented_joint

  subroutine prescribed_truss()
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: ea = 2.0e11_wp*2.0e-4_wp, len = 2.5_wp
    real(wp) :: c1(2), c2(2), k1(2, 2), k2(2, 2), a(2, 2), b(2), u(2), u2(2), det
    call solve_file('decks/prescribed_truss.deck', m, r)
    c1 = [0.8_wp, 0.6_wp]
    c2 = [-0.8_wp, 0.6_wp]
    k1 = ea/len*spread(c1, 2, 2)*spread(c1, 1, 2)
    k2 = ea/len*spread(c2, 2, 2)*spread(c2, 1, 2)
    u2 = [0.001_wp, 0.0_wp]
    a = k1 + k2
    b = [0.0_wp, -10000.0_wp] + matmul(k2, u2)
    det = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
    u = [a(2, 2)*b(1) - a(1, 2)*b(2), -a(2, 1)*b(1) + a(1, 1)*b(2)]/det
    call check_rel(disp(m, r, 'MAIN', 3, 1, 1), u(1), TOL, 'prescribed_truss: ux')
    call check_rel(disp(m, r, 'MAIN', 3, 2, 1), u(2), TOL, 'prescribed_truss: uy')
    call check_close(disp(m, r, 'MAIN', 2, 1, 1), 0.001_wp, 1.0e-18_wp, 'prescribed_truss: prescribed value')
    call check(equilibrium_error(r, 1) < TOL, 'prescribed_truss: equilibrium')
  end subroutine prescribed_truss

  subroutine rigid_loop()
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: ei = 2.0e11_wp*1.0e-4_wp, p = -1000.0_wp
    real(wp) :: th
    call solve_file('decks/rigid_loop.deck', m, r)
    call check_rel(disp(m, r, 'B', 3, 2, 1), p*4.0_wp**3/(3*ei), TOL, 'rigid_loop: tip deflection')
    th = disp(m, r, 'A', 3, 6, 1)
    call check_rel(th, p*(4.0_wp**2 - 2.0_wp**2)/(2*ei), TOL, 'rigid_loop: rotation at the loop')
    call check_rel(disp(m, r, 'C', 2, 1, 1), disp(m, r, 'A', 3, 1, 1) - th, TOL, 'rigid_loop: stub moves rigidly')
    call check_close(link_delta(m, r, 'AB', 6, 1), 0.0_wp, 1.0e-14_wp*abs(th), 'rigid_loop: bypassed spring')
    call check(equilibrium_error(r, 1) < TOL, 'rigid_loop: equilibrium')
  end subroutine rigid_loop

  subroutine mixed_loop()
    type(model_t) :: m1, m2
    type(results_t) :: r1, r2
    call solve_file('decks/mixed_loop.deck', m1, r1)
    call solve_file('decks/mixed_loop_reordered.deck', m2, r2)
    call check_rel(disp(m1, r1, 'P', 2, 1, 1), disp(m2, r2, 'P', 2, 1, 1), TOL, 'mixed_loop: order-free ux')
    call check_rel(disp(m1, r1, 'P', 2, 2, 1), disp(m2, r2, 'P', 2, 2, 1), TOL, 'mixed_loop: order-free uy')
    call check_rel(disp(m1, r1, 'R', 1, 2, 1), disp(m1, r1, 'P', 2, 2, 1), TOL, 'mixed_loop: closer holds')
    call check_rel(disp(m1, r1, 'Q', 1, 1, 1), disp(m1, r1, 'P', 2, 1, 1), TOL, 'mixed_loop: tree holds')
    call check_rel(link_force(m1, r1, 'RP', 2, 1), link_force(m2, r2, 'RP', 2, 1), 1.0e-8_wp, &
         'mixed_loop: closer force independent of order')
    call check(equilibrium_error(r1, 1) < TOL, 'mixed_loop: equilibrium')
    call check(equilibrium_error(r2, 1) < TOL, 'mixed_loop: equilibrium reordered')
  end subroutine mixed_loop

  subroutine l_frame()
    !! Column and girder with a semi-rigid knee: virtual work closed form.
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: e = 2.1e11_wp, eic = e*8.0e-5_wp, eib = e*5.0e-5_wp, eac = e*6.0e-3_wp
    real(wp), parameter :: h = 3.0_wp, b = 4.0_wp, k = 1.5e7_wp, p = 5000.0_wp
    real(wp) :: v
    call solve_file('decks/l_frame.deck', m, r)
    v = -p*(b**3/(3*eib) + (b*h/eic + b/k)*b + h/eac)
    call check_rel(disp(m, r, 'GIRDER', 3, 2, 1), v, TOL, 'l_frame: tip deflection')
    call check_rel(disp(m, r, 'COLUMN', 3, 1, 1), p*b*h**2/(2*eic), TOL, 'l_frame: knee sway')
    call check_rel(link_delta(m, r, 'KNEE', 6, 1), -p*b/k, TOL, 'l_frame: knee kink')
    call check_rel(reaction(m, r, 'COLUMN', 1, 6, 1), p*b, TOL, 'l_frame: base moment')
    call check(equilibrium_error(r, 1) < TOL, 'l_frame: equilibrium')
  end subroutine l_frame

  subroutine timoshenko_frame()
    !! 3D L-frame of B31 beams with a compliant knee: tip load along Y (girder
    !! and column bend with shear, column twists), PZ on the girder, tip torque.
    !! Column: v = X, so local y = X, z = Y; default K = G A. Girder: default
    !! v, local y = Z, z = -Y; K13 = 2.5e9 (along y), K23 = 3.0e9 (along z).
    type(model_t) :: m
    type(results_t) :: r
    real(wp), parameter :: e = 2.1e11_wp, g = e/(2*(1 + 0.3_wp)), h = 2.0_wp, b = 1.5_wp, k = 4.0e8_wp
    real(wp), parameter :: ac = 0.05_wp, iyc = 4.0e-4_wp, izc = 6.0e-4_wp, jc = 5.0e-4_wp
    real(wp), parameter :: iyg = 3.0e-4_wp, izg = 5.0e-4_wp, jg = 2.5e-4_wp, k13 = 2.5e9_wp, k23 = 3.0e9_wp
    real(wp), parameter :: p = 2.0e4_wp, q = -3.0e4_wp, t = 1.0e4_wp
    real(wp) :: v, mk
    call solve_file('decks/timoshenko_frame.deck', m, r)
    v = p*h**3/(3*e*iyc) + p*h/(g*ac) + p*b**3/(3*e*iyg) + p*b/k23 + (p*b*h/(g*jc) + p*b/k)*b
    call check_rel(disp(m, r, 'GIRDER', 3, 2, 1), v, TOL, 'timoshenko_frame: tip Y')
    call check_rel(disp(m, r, 'COLUMN', 3, 2, 1), p*h**3/(3*e*iyc) + p*h/(g*ac), TOL, 'timoshenko_frame: knee Y')
    call check_rel(link_delta(m, r, 'KNEE', 6, 1), p*b/k, TOL, 'timoshenko_frame: knee kink about Z')
    call check_rel(reaction(m, r, 'COLUMN', 1, 6, 1), -p*b, TOL, 'timoshenko_frame: base torque')
    call check(equilibrium_error(r, 1) < TOL, 'timoshenko_frame: equilibrium, tip load')
    mk = q*b**2/2
    v = q*b**4/(8*e*izg) + q*b**2/(2*k13) + q*b*h/(e*ac) + mk*(h/(e*izc) + 1/k)*b
    call check_rel(disp(m, r, 'GIRDER', 3, 3, 2), v, TOL, 'timoshenko_frame: tip Z under PZ')
    call check_rel(disp(m, r, 'COLUMN', 3, 3, 2), q*b*h/(e*ac), TOL, 'timoshenko_frame: column shortening')
    call check(equilibrium_error(r, 2) < TOL, 'timoshenko_frame: equilibrium, PZ')
    call check_rel(disp(m, r, 'GIRDER', 3, 4, 3), t*b/(g*jg) + t/k + t*h/(e*iyc), TOL, &
         'timoshenko_frame: tip twist')
    call check(equilibrium_error(r, 3) < TOL, 'timoshenko_frame: equilibrium, torque')
  end subroutine timoshenko_frame

end program test_verification
