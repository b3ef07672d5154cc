module superjoin_deck_beam_sections
  !! The beam cross-section library of *BEAM SECTION / *BEAM GENERAL SECTION,
  !! SECTION=RECT | CIRC | PIPE | BOX | I | L: the section constants A, I11,
  !! I22, I12 (about the centroid, section axes 1 and 2 as in Abaqus) and the
  !! torsion constant J computed from the Abaqus/CalculiX data lines.
  !!
  !! Formulas (axis 1 along the first dimension, axis 2 along the second;
  !! I11 = ∫ x2² dA bends about axis 1, I22 = ∫ x1² dA about axis 2):
  !! - Areas and inertias of RECT, BOX, I and L are exact: sums of rectangles
  !!   with the parallel-axis theorem about the centroid.
  !! - RECT a, b: J of Saint-Venant's series for a rectangle c ≥ d
  !!   (Timoshenko & Goodier, Theory of Elasticity, 3rd ed., §109):
  !!   J = c d³/3 [1 − (192/π⁵)(d/c) Σ_{n odd} tanh(nπc/2d)/n⁵], summed as
  !!   (31/32)ζ(5) − Σ_{n odd} (1 − tanh(nπc/2d))/n⁵ to round-off.
  !! - CIRC r (Abaqus) or d1, d2 (CalculiX: the axes of an ellipse): exact,
  !!   J = π a³ b³/(a² + b²) for semi-axes a, b (π r⁴/2 for a circle).
  !! - PIPE r, t (outer radius, wall): exact, J = π (r⁴ − rᵢ⁴)/2.
  !! - BOX a, b, t1, t2, t3, t4 (outer dimensions; walls t1 at +1, t2 at +2,
  !!   t3 at −1, t4 at −2 as in Abaqus): Bredt's thin-walled closed section,
  !!   J = 4 Am² / ∮ ds/t on the wall mid-lines.
  !! - I l, h, b1, b2, t1, t2, t3 (Abaqus: origin l above the bottom, height,
  !!   bottom and top flange widths and thicknesses, web thickness): open
  !!   thin-walled, J = (b1 t1³ + b2 t2³ + (h − t1 − t2) t3³)/3.
  !! - L a, b, t1, t2 (Abaqus: legs along 1 and 2, their thicknesses, origin
  !!   at the outer corner): open thin-walled, J = (a t1³ + (b − t1) t2³)/3.
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  integer, parameter, public :: SHAPE_NONE = 0, SHAPE_RECT = 1, SHAPE_CIRC = 2, SHAPE_PIPE = 3, &
       SHAPE_BOX = 4, SHAPE_I = 5, SHAPE_L = 6
    !! Section shapes.
  integer, parameter, public :: NUM_SHAPES = 6
  character(len=4), parameter, public :: SHAPE_NAMES(NUM_SHAPES) = ['RECT', 'CIRC', 'PIPE', 'BOX ', 'I   ', 'L   ']
  integer, parameter, public :: SHAPE_DIMS_MIN(NUM_SHAPES) = [2, 1, 2, 6, 7, 4]
  integer, parameter, public :: SHAPE_DIMS_MAX(NUM_SHAPES) = [2, 2, 2, 6, 7, 4]
    !! Numbers of values on the first data line.
  character(len=40), parameter, public :: SHAPE_DATA(NUM_SHAPES) = [character(len=40) :: &
       'a, b', 'r (or d1, d2: an ellipse)', 'r, t', 'a, b, t1, t2, t3, t4', 'l, h, b1, b2, t1, t2, t3', &
       'a, b, t1, t2']
  integer, parameter, public :: MAX_SHAPE_DIMS = 7
  real(wp), parameter, public :: SHAPE_SHEAR_K(NUM_SHAPES) = [0.85_wp, 0.89_wp, 0.53_wp, 0.44_wp, 0.44_wp, &
       0.44_wp]
    !! Shear factor k of the default transverse shear stiffness k G A of the
    !! shear-flexible beams (B21, B31, B32), per shape as Abaqus takes them
    !! ("Transverse shear stiffness in beams", Abaqus Analysis User's Guide:
    !! Cowper's 1966 factors at nu = 0.3): solid rectangle 0.85 (10(1+nu)/(12+11nu)),
    !! solid circle 0.89 (6(1+nu)/(7+6nu)), thin-walled tube 0.53
    !! (2(1+nu)/(4+3nu)), thin-walled box, I and L 0.44 (box: 20(1+nu)/(48+39nu)).

  type, public :: section_props_t
    !! Constants of a cross-section about its centroid, section axes 1 and 2.
     real(wp) :: area = 0.0_wp
     real(wp) :: i11 = 0.0_wp              !! ∫ x2² dA
     real(wp) :: i22 = 0.0_wp              !! ∫ x1² dA
     real(wp) :: i12 = 0.0_wp              !! ∫ x1 x2 dA
     real(wp) :: j = 0.0_wp                !! torsion constant
     real(wp) :: c(2) = 0.0_wp             !! centroid in the section's own axes (origin of its data)
  end type section_props_t

  public :: shape_index, section_properties, rect_torsion, shape_shear_factor
  public :: section_fibres

  integer, parameter, public :: MAX_FIBRES = 4
    !! Extreme points of a library section at which fibre stresses are reported.

  real(wp), parameter :: PI = acos(-1.0_wp)
  real(wp), parameter :: ZETA5 = 1.0369277551433699263_wp   !! Riemann ζ(5)
  real(wp), parameter :: SERIES_TOL = 1.0e-17_wp
  integer, parameter :: MAX_TERMS = 100000

contains

  pure integer function shape_index(name) result(k)
    !! SHAPE_* of a SECTION= value (upper case); SHAPE_NONE if not in the library.
    character(*), intent(in) :: name
    do k = 1, NUM_SHAPES
       if (trim(SHAPE_NAMES(k)) == name) return
    end do
    k = SHAPE_NONE
  end function shape_index

  pure real(wp) function shape_shear_factor(shape) result(k)
    !! SHAPE_SHEAR_K of a library shape; 1 for anything else (a general
    !! section keeps the k = 1 of superjoin's own constants).
    integer, intent(in) :: shape
    k = 1.0_wp
    if (shape >= 1 .and. shape <= NUM_SHAPES) k = SHAPE_SHEAR_K(shape)
  end function shape_shear_factor

  pure real(wp) function rect_torsion(a, b) result(j)
    !! Saint-Venant torsion constant of a solid a × b rectangle.
    real(wp), intent(in) :: a, b
    real(wp) :: c, d, s, term, x
    integer :: n
    c = max(a, b)
    d = min(a, b)
    s = 0.0_wp
    do n = 1, 2*MAX_TERMS, 2
       x = n*PI*c/(2.0_wp*d)
       term = 2.0_wp/(exp(min(2.0_wp*x, 700.0_wp)) + 1.0_wp)/real(n, wp)**5   ! (1 - tanh x)/n⁵
       s = s + term
       if (term < SERIES_TOL) exit
    end do
    s = 31.0_wp/32.0_wp*ZETA5 - s
    j = c*d**3/3.0_wp*(1.0_wp - 192.0_wp/PI**5*(d/c)*s)
  end function rect_torsion

  pure subroutine section_properties(shape, dims, p, problem)
    !! Constants of a library section from its data line `dims`; `problem` is
    !! '' or what is wrong with the dimensions.
    integer, intent(in) :: shape
    real(wp), intent(in) :: dims(:)
    type(section_props_t), intent(out) :: p
    character(:), allocatable, intent(out) :: problem
    real(wp) :: a, b, r, t, ri, rect(4, 4), am, loop
    problem = ''
    if (any(.not. (dims > 0.0_wp))) then
       problem = 'section dimensions must be positive'
       return
    end if
    select case (shape)
    case (SHAPE_RECT)
       a = dims(1)
       b = dims(2)
       rect(:, 1) = [-a/2, a/2, -b/2, b/2]
       call rectangles(rect(:, 1:1), p)
       p%j = rect_torsion(a, b)
    case (SHAPE_CIRC)
       if (size(dims) == 1) then
          a = dims(1)
          b = dims(1)
       else
          a = dims(1)/2.0_wp
          b = dims(2)/2.0_wp
       end if
       p%area = PI*a*b
       p%i11 = PI*a*b**3/4.0_wp
       p%i22 = PI*a**3*b/4.0_wp
       p%j = PI*a**3*b**3/(a**2 + b**2)
    case (SHAPE_PIPE)
       r = dims(1)
       t = dims(2)
       if (t > r) then
          problem = 'PIPE wall thickness t must not exceed the outer radius r'
          return
       end if
       ri = r - t
       p%area = PI*(r**2 - ri**2)
       p%i11 = PI*(r**4 - ri**4)/4.0_wp
       p%i22 = p%i11
       p%j = PI*(r**4 - ri**4)/2.0_wp
    case (SHAPE_BOX)
       a = dims(1)
       b = dims(2)
       associate (t1 => dims(3), t2 => dims(4), t3 => dims(5), t4 => dims(6))
         if (t1 + t3 >= a .or. t2 + t4 >= b) then
            problem = 'BOX walls fill the section: t1 + t3 must be < a and t2 + t4 < b'
            return
         end if
         rect(:, 1) = [a/2 - t1, a/2, -b/2, b/2]               ! wall at +1
         rect(:, 2) = [-a/2, -a/2 + t3, -b/2, b/2]             ! wall at -1
         rect(:, 3) = [-a/2 + t3, a/2 - t1, b/2 - t2, b/2]     ! wall at +2
         rect(:, 4) = [-a/2 + t3, a/2 - t1, -b/2, -b/2 + t4]   ! wall at -2
         call rectangles(rect, p)
         am = (a - (t1 + t3)/2)*(b - (t2 + t4)/2)
         loop = (b - (t2 + t4)/2)*(1/t1 + 1/t3) + (a - (t1 + t3)/2)*(1/t2 + 1/t4)
         p%j = 4*am**2/loop
       end associate
    case (SHAPE_I)
       associate (l => dims(1), h => dims(2), b1 => dims(3), b2 => dims(4), t1 => dims(5), t2 => dims(6), &
            t3 => dims(7))
         if (t1 + t2 >= h) then
            problem = 'I section flanges fill the height: t1 + t2 must be < h'
            return
         end if
         if (t3 > min(b1, b2)) then
            problem = 'I section web t3 is wider than a flange'
            return
         end if
         rect(:, 1) = [-b1/2, b1/2, -l, -l + t1]                 ! bottom flange
         rect(:, 2) = [-t3/2, t3/2, -l + t1, -l + h - t2]        ! web
         rect(:, 3) = [-b2/2, b2/2, -l + h - t2, -l + h]         ! top flange
         call rectangles(rect(:, 1:3), p)
         p%j = (b1*t1**3 + b2*t2**3 + (h - t1 - t2)*t3**3)/3.0_wp
       end associate
    case (SHAPE_L)
       associate (a => dims(1), b => dims(2), t1 => dims(3), t2 => dims(4))
         if (t1 >= b .or. t2 >= a) then
            problem = 'L section legs: t1 must be < b and t2 < a'
            return
         end if
         rect(:, 1) = [0.0_wp, a, 0.0_wp, t1]       ! leg along 1
         rect(:, 2) = [0.0_wp, t2, t1, b]           ! leg along 2
         call rectangles(rect(:, 1:2), p)
         p%j = (a*t1**3 + (b - t1)*t2**3)/3.0_wp
       end associate
    case default
       problem = 'unknown section shape'
    end select
  end subroutine section_properties

  pure subroutine rectangles(rect, p)
    !! Area, centroid and centroidal inertias of a union of disjoint rectangles
    !! rect(:, k) = [x1 min, x1 max, x2 min, x2 max].
    real(wp), intent(in) :: rect(:, :)
    type(section_props_t), intent(inout) :: p
    real(wp) :: ar(size(rect, 2)), cx(size(rect, 2)), cy(size(rect, 2)), w, h
    integer :: k
    do k = 1, size(rect, 2)
       w = rect(2, k) - rect(1, k)
       h = rect(4, k) - rect(3, k)
       ar(k) = w*h
       cx(k) = (rect(1, k) + rect(2, k))/2
       cy(k) = (rect(3, k) + rect(4, k))/2
    end do
    p%area = sum(ar)
    p%c = [sum(ar*cx), sum(ar*cy)]/p%area
    p%i11 = 0.0_wp
    p%i22 = 0.0_wp
    p%i12 = 0.0_wp
    do k = 1, size(rect, 2)
       w = rect(2, k) - rect(1, k)
       h = rect(4, k) - rect(3, k)
       p%i11 = p%i11 + w*h**3/12 + ar(k)*(cy(k) - p%c(2))**2
       p%i22 = p%i22 + h*w**3/12 + ar(k)*(cx(k) - p%c(1))**2
       p%i12 = p%i12 + ar(k)*(cx(k) - p%c(1))*(cy(k) - p%c(2))
    end do
  end subroutine rectangles

  pure subroutine section_fibres(shape, dims, pts, n)
    !! The extreme points of a library section (section axes 1 and 2, origin at
    !! the section's data origin, which the beams require at the centroid):
    !! RECT and BOX: the corners (+a/2, +b/2), (-a/2, +b/2), (-a/2, -b/2),
    !! (+a/2, -b/2); CIRC and PIPE: the ends of the axes (+r1, 0), (0, +r2),
    !! (-r1, 0), (0, -r2); I: the flange tips, top (+b2/2, h - l), (-b2/2, h - l),
    !! bottom (-b1/2, -l), (+b1/2, -l). n = 0 for other shapes (L, general).
    integer, intent(in) :: shape
    real(wp), intent(in) :: dims(:)
    real(wp), intent(out) :: pts(2, MAX_FIBRES)
    integer, intent(out) :: n
    real(wp) :: a, b
    pts = 0.0_wp
    n = 0
    select case (shape)
    case (SHAPE_RECT, SHAPE_BOX)
       a = dims(1)/2
       b = dims(2)/2
       pts = reshape([a, b, -a, b, -a, -b, a, -b], [2, MAX_FIBRES])
       n = 4
    case (SHAPE_CIRC, SHAPE_PIPE)
       a = dims(1)
       b = dims(1)
       if (shape == SHAPE_CIRC .and. size(dims) == 2) then
          a = dims(1)/2
          b = dims(2)/2
       end if
       pts = reshape([a, 0.0_wp, 0.0_wp, b, -a, 0.0_wp, 0.0_wp, -b], [2, MAX_FIBRES])
       n = 4
    case (SHAPE_I)
       associate (l => dims(1), h => dims(2), b1 => dims(3), b2 => dims(4))
         pts = reshape([b2/2, h - l, -b2/2, h - l, -b1/2, -l, b1/2, -l], [2, MAX_FIBRES])
       end associate
       n = 4
    end select
  end subroutine section_fibres
end module superjoin_deck_beam_sections
