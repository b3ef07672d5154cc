program test_quadrature
  !! The integration rules (superjoin_elements_quadrature) against exact
  !! integrals: the m-point Gauss line rule integrates x^k exactly for
  !! k <= 2m - 1 and misses x^(2m); the square and cube rules their tensor
  !! monomials up to the same degree per direction; the triangle rules
  !! x^a y^b on the unit triangle (a! b! / (a + b + 2)!) up to degree 1, 2
  !! and 5, and miss the next degree (so a wrong point or weight cannot pass).
  use superjoin_kinds, only: wp
  use superjoin_elements_quadrature, only: quad_rule_t, gauss_line, gauss_square, gauss_cube, triangle_rule, &
       TRI_CENTROID, TRI_THREE, TRI_DUNAVANT5
  use superjoin_testing, only: check, check_close, finish
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-14_wp
    !! Round-off of sums of a few terms of order one.
  real(wp), parameter :: DUNAVANT_TOL = 1.0e-14_wp
    !! Dunavant's points and weights are given to 15 digits.

  call lines()
  call squares_and_cubes()
  call triangles()
  call finish()

contains

  pure real(wp) function line_exact(k)
    !! ∫_{-1}^{1} x^k dx.
    integer, intent(in) :: k
    line_exact = merge(2.0_wp/real(k + 1, wp), 0.0_wp, mod(k, 2) == 0)
  end function line_exact

  pure real(wp) function triangle_exact(a, b)
    !! ∫ x^a y^b over the unit triangle = a! b! / (a + b + 2)!.
    integer, intent(in) :: a, b
    triangle_exact = gamma(real(a + 1, wp))*gamma(real(b + 1, wp))/gamma(real(a + b + 3, wp))
  end function triangle_exact

  subroutine lines()
    real(wp), allocatable :: p(:), w(:)
    integer :: m, k
    character(len=60) :: what
    do m = 1, 4
       call gauss_line(m, p, w)
       call check(size(p) == m .and. size(w) == m, 'gauss_line: m points')
       do k = 0, 2*m - 1
          write (what, '(a, i0, a, i0)') 'gauss_line m = ', m, ': exact for x^', k
          call check_close(sum(w*p**k), line_exact(k), TOL, trim(what))
       end do
       write (what, '(a, i0, a, i0)') 'gauss_line m = ', m, ': not exact for x^', 2*m
       call check(abs(sum(w*p**(2*m)) - line_exact(2*m)) > 1.0e-3_wp, trim(what))
    end do
  end subroutine lines

  subroutine squares_and_cubes()
    type(quad_rule_t) :: r
    integer :: m, i, j, k
    character(len=60) :: what
    do m = 1, 3
       r = gauss_square(m)
       call check(size(r%xi, 1) == 2 .and. size(r%w) == m**2, 'gauss_square: m² points in 2D')
       if (m > 1) call check(r%xi(1, 2) > r%xi(1, 1) .and. r%xi(2, 2) == r%xi(2, 1), 'gauss_square: ξ fastest')
       do j = 0, 2*m - 1
          do i = 0, 2*m - 1
             write (what, '(a, i0, a, i0, a, i0)') 'gauss_square m = ', m, ': x^', i, ' y^', j
             call check_close(sum(r%w*r%xi(1, :)**i*r%xi(2, :)**j), line_exact(i)*line_exact(j), TOL, trim(what))
          end do
       end do
       r = gauss_cube(m)
       call check(size(r%xi, 1) == 3 .and. size(r%w) == m**3, 'gauss_cube: m³ points in 3D')
       do k = 0, 2*m - 1
          do j = 0, 2*m - 1
             do i = 0, 2*m - 1
                write (what, '(a, i0, a, 3(i0, 1x))') 'gauss_cube m = ', m, ': powers ', i, j, k
                call check_close(sum(r%w*r%xi(1, :)**i*r%xi(2, :)**j*r%xi(3, :)**k), &
                     line_exact(i)*line_exact(j)*line_exact(k), TOL, trim(what))
             end do
          end do
       end do
    end do
  end subroutine squares_and_cubes

  subroutine triangles()
    integer, parameter :: RULES(3) = [TRI_CENTROID, TRI_THREE, TRI_DUNAVANT5]
    integer, parameter :: DEGREE(3) = [1, 2, 5]
    type(quad_rule_t) :: r
    integer :: q, a, b
    real(wp) :: miss
    character(len=60) :: what
    do q = 1, size(RULES)
       r = triangle_rule(RULES(q))
       call check(size(r%w) == RULES(q), 'triangle_rule: its number of points')
       do a = 0, DEGREE(q)
          do b = 0, DEGREE(q) - a
             write (what, '(a, i0, a, i0, a, i0)') 'triangle_rule ', RULES(q), ': x^', a, ' y^', b
             call check_close(sum(r%w*r%xi(1, :)**a*r%xi(2, :)**b), triangle_exact(a, b), DUNAVANT_TOL, trim(what))
          end do
       end do
       miss = 0.0_wp
       do a = 0, DEGREE(q) + 1
          b = DEGREE(q) + 1 - a
          miss = max(miss, abs(sum(r%w*r%xi(1, :)**a*r%xi(2, :)**b) - triangle_exact(a, b)))
       end do
       write (what, '(a, i0, a)') 'triangle_rule ', RULES(q), ': not exact one degree higher'
       call check(miss > 1.0e-6_wp, trim(what))
    end do
  end subroutine triangles

end program test_quadrature
