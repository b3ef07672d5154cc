module superjoin_elements_quadrature
  !! Integration rules on the reference cells, one place for all of them:
  !!
  !! - Gauss-Legendre on the line -1..1 (1 to 4 points) and its tensor
  !!   products on the square and the cube, ξ fastest, then η, then ζ; the
  !!   weight of a point is the product of its line weights in that order;
  !! - the unit triangle (0,0), (1,0), (0,1): the centroid, the three points
  !!   (1/6, 1/6), (2/3, 1/6), (1/6, 2/3), and Dunavant's degree-5 rule of
  !!   seven points; the weights sum to the triangle's area 1/2.
  !!
  !! The points and weights are the same floating-point numbers the elements
  !! built by hand before this module (each operation correctly rounded), so
  !! results do not move by a bit.
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  public :: quad_rule_t, gauss_line, gauss_square, gauss_cube, triangle_rule

  type :: quad_rule_t
    !! Integration points (natural coordinates) and weights.
     real(wp), allocatable :: xi(:, :)   !! (dimension, npoint)
     real(wp), allocatable :: w(:)       !! (npoint)
  end type quad_rule_t

  integer, parameter, public :: TRI_CENTROID = 1, TRI_THREE = 3, TRI_DUNAVANT5 = 7
    !! The triangle rules, by their number of points.

  real(wp), parameter :: D_A1 = 0.059715871789770_wp, D_B1 = 0.470142064105115_wp, &
       D_A2 = 0.797426985353087_wp, D_B2 = 0.101286507323456_wp
  real(wp), parameter :: D_W0 = 0.225_wp, D_W1 = 0.132394152788506_wp, D_W2 = 0.125939180544827_wp
    !! Dunavant's degree-5 rule (weights relative to the area).
  real(wp), parameter :: G4_P1 = 0.3399810435848563_wp, G4_P2 = 0.8611363115940526_wp, &
       G4_W1 = 0.6521451548625461_wp, G4_W2 = 0.3478548451374538_wp
    !! The 4-point Gauss-Legendre rule.

contains

  pure subroutine gauss_line(m, p, w)
    !! The m-point Gauss-Legendre rule on -1..1 (m = 1 to 4; larger m gives
    !! the 4-point rule): points p and weights w, ascending.
    integer, intent(in) :: m
    real(wp), allocatable, intent(out) :: p(:), w(:)
    select case (m)
    case (1)
       p = [0.0_wp]
       w = [2.0_wp]
    case (2)
       p = [-1.0_wp, 1.0_wp]/sqrt(3.0_wp)
       w = [1.0_wp, 1.0_wp]
    case (3)
       p = [-sqrt(0.6_wp), 0.0_wp, sqrt(0.6_wp)]
       w = [5.0_wp, 8.0_wp, 5.0_wp]/9.0_wp
    case default
       p = [-G4_P2, -G4_P1, G4_P1, G4_P2]
       w = [G4_W2, G4_W1, G4_W1, G4_W2]
    end select
  end subroutine gauss_line

  pure function gauss_square(m) result(r)
    !! The m×m Gauss rule on the square -1..1 (m = 1, 2, 3), ξ fastest.
    integer, intent(in) :: m
    type(quad_rule_t) :: r
    real(wp), allocatable :: p(:), w(:)
    integer :: i, j, g
    call gauss_line(m, p, w)
    allocate (r%xi(2, size(w)**2), r%w(size(w)**2))
    g = 0
    do j = 1, size(w)
       do i = 1, size(w)
          g = g + 1
          r%xi(:, g) = [p(i), p(j)]
          r%w(g) = w(i)*w(j)
       end do
    end do
  end function gauss_square

  pure function gauss_cube(m) result(r)
    !! The m×m×m Gauss rule on the cube -1..1 (m = 1, 2, 3), ξ fastest.
    integer, intent(in) :: m
    type(quad_rule_t) :: r
    real(wp), allocatable :: p(:), w(:)
    integer :: i, j, k, g
    call gauss_line(m, p, w)
    allocate (r%xi(3, size(w)**3), r%w(size(w)**3))
    g = 0
    do k = 1, size(w)
       do j = 1, size(w)
          do i = 1, size(w)
             g = g + 1
             r%xi(:, g) = [p(i), p(j), p(k)]
             r%w(g) = w(i)*w(j)*w(k)
          end do
       end do
    end do
  end function gauss_cube

  pure function triangle_rule(npoint) result(r)
    !! A rule on the unit triangle: TRI_CENTROID (exact for degree 1),
    !! TRI_THREE (degree 2) or TRI_DUNAVANT5 (degree 5); weights sum to 1/2.
    integer, intent(in) :: npoint
    type(quad_rule_t) :: r
    select case (npoint)
    case (TRI_CENTROID)
       r%xi = reshape([1.0_wp, 1.0_wp]/3.0_wp, [2, 1])
       r%w = [0.5_wp]
    case (TRI_THREE)
       r%xi = reshape([1.0_wp, 1.0_wp, 4.0_wp, 1.0_wp, 1.0_wp, 4.0_wp]/6.0_wp, [2, 3])
       r%w = [1.0_wp, 1.0_wp, 1.0_wp]/6.0_wp
    case default
       r%xi = reshape([1.0_wp/3.0_wp, 1.0_wp/3.0_wp, D_A1, D_B1, D_B1, D_A1, D_B1, D_B1, &
            D_A2, D_B2, D_B2, D_A2, D_B2, D_B2], [2, 7])
       r%w = 0.5_wp*[D_W0, D_W1, D_W1, D_W1, D_W2, D_W2, D_W2]
    end select
  end function triangle_rule

end module superjoin_elements_quadrature
