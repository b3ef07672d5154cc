program test_beam_sections
  !! Unit tests of the beam cross-section library (superjoin_deck_beam_sections)
  !! against hand formulas and published values.
  use superjoin_kinds, only: wp
  use superjoin_deck_beam_sections, only: section_props_t, section_properties, rect_torsion, shape_index, &
       SHAPE_RECT, SHAPE_CIRC, SHAPE_PIPE, SHAPE_BOX, SHAPE_I, SHAPE_L, SHAPE_NONE
  use superjoin_testing, only: check, check_rel, finish
  implicit none (type, external)

  real(wp), parameter :: PI = acos(-1.0_wp)
  real(wp), parameter :: TOL_EXACT = 1.0e-13_wp   !! closed forms evaluated two ways
  real(wp), parameter :: TOL_SERIES = 1.0e-12_wp  !! J of a rectangle against a brute-force sum
  real(wp), parameter :: TOL_TABLE = 0.5e-3_wp    !! Timoshenko's table, 3 digits (absolute on k1)
  type(section_props_t) :: p
  character(:), allocatable :: problem
  real(wp) :: a, b, t, ri, h, bf, tf, tw, hw, am, loop
  integer :: k
  ! Saint-Venant J = k1 c d^3 of a c x d rectangle: Timoshenko & Goodier, Theory
  ! of Elasticity (3rd ed., section 109, table) c/d = 1, 2, 3, 4, 5, 10 ...
  real(wp), parameter :: RATIO(6) = [1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp, 10.0_wp]
  real(wp), parameter :: K1_TABLE(6) = [0.141_wp, 0.229_wp, 0.263_wp, 0.281_wp, 0.291_wp, 0.312_wp]
  ! ... and the same series summed directly in double precision with 1e5 terms
  ! (tanh, no acceleration; the tail is below 1e-20).
  real(wp), parameter :: K1_SERIES(6) = [0.14057701495515554_wp, 0.22868167711957246_wp, &
       0.2633169310015012_wp, 0.2808129583076782_wp, 0.2913167541879895_wp, 0.3123250374572057_wp]

  do k = 1, size(RATIO)
     call check(abs(rect_torsion(RATIO(k), 1.0_wp)/RATIO(k) - K1_TABLE(k)) <= TOL_TABLE, &
          'rectangle J against Timoshenko''s table, c/d = '//trim(num(RATIO(k))))
     call check_rel(rect_torsion(RATIO(k), 1.0_wp)/RATIO(k), K1_SERIES(k), TOL_SERIES, &
          'rectangle J against the brute-force series, c/d = '//trim(num(RATIO(k))))
     call check_rel(rect_torsion(1.0_wp, RATIO(k)), rect_torsion(RATIO(k), 1.0_wp), TOL_EXACT, &
          'rectangle J symmetric in a, b')
  end do
  ! a very slender strip tends to c d^3/3 (1 - 0.630 d/c)
  call check_rel(rect_torsion(1000.0_wp, 1.0_wp), 1000.0_wp/3.0_wp*(1.0_wp - 192.0_wp/PI**5*31.0_wp/32.0_wp* &
       1.0369277551433699_wp/1000.0_wp), TOL_EXACT, 'strip c/d = 1000: c d^3/3 (1 - (186/pi^5) zeta(5) d/c)')

  ! RECT a, b: a along axis 1, b along axis 2
  a = 0.05_wp
  b = 0.08_wp
  call props(SHAPE_RECT, [a, b])
  call check_rel(p%area, a*b, TOL_EXACT, 'RECT A')
  call check_rel(p%i11, a*b**3/12, TOL_EXACT, 'RECT I11 = a b^3/12')
  call check_rel(p%i22, b*a**3/12, TOL_EXACT, 'RECT I22 = b a^3/12')
  call check(abs(p%i12) <= TOL_EXACT*p%i11, 'RECT I12 = 0')
  call check_rel(p%j, rect_torsion(a, b), TOL_EXACT, 'RECT J')

  ! CIRC r (Abaqus) and d1, d2 (CalculiX ellipse)
  call props(SHAPE_CIRC, [0.1_wp])
  call check_rel(p%area, PI*0.01_wp, TOL_EXACT, 'CIRC A')
  call check_rel(p%i11, PI*0.1_wp**4/4, TOL_EXACT, 'CIRC I')
  call check_rel(p%j, PI*0.1_wp**4/2, TOL_EXACT, 'CIRC J = pi r^4/2')
  call props(SHAPE_CIRC, [0.2_wp, 0.2_wp])
  call check_rel(p%j, PI*0.1_wp**4/2, TOL_EXACT, 'CIRC with equal diameters = circle')
  call props(SHAPE_CIRC, [0.4_wp, 0.2_wp])
  call check_rel(p%area, PI*0.2_wp*0.1_wp, TOL_EXACT, 'ellipse A = pi a b')
  call check_rel(p%i11, PI*0.2_wp*0.1_wp**3/4, TOL_EXACT, 'ellipse I11 = pi a b^3/4')
  call check_rel(p%i22, PI*0.2_wp**3*0.1_wp/4, TOL_EXACT, 'ellipse I22 = pi a^3 b/4')
  call check_rel(p%j, PI*0.2_wp**3*0.1_wp**3/(0.2_wp**2 + 0.1_wp**2), TOL_EXACT, 'ellipse J')

  ! PIPE r, t (CalculiX example: r = 0.11, t = 0.01)
  call props(SHAPE_PIPE, [0.11_wp, 0.01_wp])
  ri = 0.1_wp
  call check_rel(p%area, PI*(0.11_wp**2 - ri**2), TOL_EXACT, 'PIPE A')
  call check_rel(p%i11, PI*(0.11_wp**4 - ri**4)/4, TOL_EXACT, 'PIPE I')
  call check_rel(p%j, 2*p%i11, TOL_EXACT, 'PIPE J = 2 I (exact)')
  call props(SHAPE_PIPE, [0.1_wp, 0.1_wp])
  call check_rel(p%j, PI*0.1_wp**4/2, TOL_EXACT, 'PIPE with t = r is the solid circle')

  ! BOX 50 x 50, walls 3 (CalculiX boxprofile.inp)
  call props(SHAPE_BOX, [50.0_wp, 50.0_wp, 3.0_wp, 3.0_wp, 3.0_wp, 3.0_wp])
  call check_rel(p%area, 50.0_wp**2 - 44.0_wp**2, TOL_EXACT, 'BOX A = 50^2 - 44^2')
  call check_rel(p%i11, (50.0_wp**4 - 44.0_wp**4)/12, TOL_EXACT, 'BOX I = (50^4 - 44^4)/12')
  call check_rel(p%i22, p%i11, TOL_EXACT, 'square BOX I22 = I11')
  ! Bredt, square tube: J = 2 t (a-t)^2 (b-t)^2 / ((a-t) + (b-t))
  call check_rel(p%j, 2*3.0_wp*47.0_wp**4/94.0_wp, TOL_EXACT, 'BOX J (Bredt) = 311469')
  ! unequal walls, symmetric: 100 x 60, side walls 4, flanges 6
  a = 100.0_wp
  b = 60.0_wp
  call props(SHAPE_BOX, [a, b, 4.0_wp, 6.0_wp, 4.0_wp, 6.0_wp])
  call check_rel(p%i11, (a*b**3 - (a - 8)*(b - 12)**3)/12, TOL_EXACT, 'BOX 100 x 60 I11')
  call check_rel(p%i22, (b*a**3 - (b - 12)*(a - 8)**3)/12, TOL_EXACT, 'BOX 100 x 60 I22')
  am = (a - 4)*(b - 6)
  loop = 2*(b - 6)/4 + 2*(a - 4)/6
  call check_rel(p%j, 4*am**2/loop, TOL_EXACT, 'BOX 100 x 60 J (Bredt)')
  call check(norm2(p%c) <= TOL_EXACT*a, 'BOX centroid at its centre')
  ! unequal opposite walls move the centroid: t1 = 8 at +1, t3 = 2 at -1
  call props(SHAPE_BOX, [a, b, 8.0_wp, 6.0_wp, 2.0_wp, 6.0_wp])
  call check(p%c(1) > 0.0_wp, 'BOX with a thicker +1 wall: centroid moves towards +1')

  ! I: IPE 300 without fillets, l = h/2 (symmetric), hand formula
  h = 0.3_wp
  bf = 0.15_wp
  tf = 0.0107_wp
  tw = 0.0071_wp
  call props(SHAPE_I, [h/2, h, bf, bf, tf, tf, tw])
  hw = h - 2*tf
  call check_rel(p%area, 2*bf*tf + hw*tw, TOL_EXACT, 'I A')
  call check_rel(p%i11, (bf*h**3 - (bf - tw)*hw**3)/12, TOL_EXACT, 'I I11 = (b h^3 - (b - tw) hw^3)/12')
  call check_rel(p%i22, (2*tf*bf**3 + hw*tw**3)/12, TOL_EXACT, 'I I22')
  call check_rel(p%j, (2*bf*tf**3 + hw*tw**3)/3, TOL_EXACT, 'I J = sum b t^3/3')
  call check(norm2(p%c) <= TOL_EXACT*h, 'symmetric I with l = h/2: centroid at the origin')
  ! unequal flanges: centroid above the middle of the height
  call props(SHAPE_I, [h/2, h, 0.1_wp, 0.2_wp, tf, tf, tw])
  call check(p%c(2) > 0.0_wp, 'I with the wider top flange: centroid above l')

  ! L 0.1 x 0.1 x 0.01: legs are not principal axes
  t = 0.01_wp
  call props(SHAPE_L, [0.1_wp, 0.1_wp, t, t])
  call check_rel(p%area, 0.1_wp*t + 0.09_wp*t, TOL_EXACT, 'L A')
  call check_rel(p%j, (0.1_wp*t**3 + 0.09_wp*t**3)/3, TOL_EXACT, 'L J = sum b t^3/3')
  call check(p%i12 < 0.0_wp .or. p%i12 > 0.0_wp, 'L I12 /= 0')

  ! bad dimensions
  call section_properties(SHAPE_PIPE, [0.1_wp, 0.2_wp], p, problem)
  call check(index(problem, 'must not exceed') > 0, 'PIPE t > r refused')
  call section_properties(SHAPE_BOX, [10.0_wp, 10.0_wp, 6.0_wp, 1.0_wp, 5.0_wp, 1.0_wp], p, problem)
  call check(index(problem, 'fill') > 0, 'BOX walls filling the width refused')
  call section_properties(SHAPE_RECT, [1.0_wp, -1.0_wp], p, problem)
  call check(index(problem, 'positive') > 0, 'negative dimension refused')
  call section_properties(SHAPE_I, [0.15_wp, 0.3_wp, 0.1_wp, 0.1_wp, 0.16_wp, 0.16_wp, 0.01_wp], p, problem)
  call check(index(problem, 'flanges fill') > 0, 'I flanges filling the height refused')
  call check(shape_index('RECT') == SHAPE_RECT .and. shape_index('HEX') == SHAPE_NONE, 'shape names')
  deallocate (problem)    ! the main program's variables are not freed at its end (LeakSanitizer)
  call finish()

contains

  subroutine props(shape, dims)
    integer, intent(in) :: shape
    real(wp), intent(in) :: dims(:)
    call section_properties(shape, dims, p, problem)
    call check(len(problem) == 0, 'section accepted: '//problem)
  end subroutine props

  function num(x) result(s)
    real(wp), intent(in) :: x
    character(len=16) :: s
    write (s, '(g0.4)') x
  end function num
end program test_beam_sections
