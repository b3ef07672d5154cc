program test_plate
  !! Unit tests of the DKT/DKQ plate bending elements (superjoin_elements_plate):
  !! data checks, symmetry, rigid-body modes and rank, invariance under an
  !! in-plane rotation, constant-curvature moments, pressure loads, the
  !! MacNeal-Harder patch test, and the convergence of the centre deflection of
  !! simply supported and clamped square plates against series solutions.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_elements_plate, only: plate_stiffness, plate_moments, plate_pressure_load
  use superjoin_testing, only: check, check_close, check_rel, finish
  use test_lapack, only: dsyev, dgesv, dposv, dpbsv
  use test_random, only: set_seed, rnd, rnd_in
  implicit none (type, external)


  real(wp), parameter :: PI = acos(-1.0_wp)
  real(wp), parameter :: TOL = 1.0e-12_wp          !! round-off on one element, relative
  real(wp), parameter :: TOL_EXACT = 1.0e-10_wp    !! exact discrete answers after a solve, relative
  integer, parameter :: NDN = 3                    !! DOFs per node: w, θx, θy
  real(wp), parameter :: E_MOD = 2.1e5_wp, NU = 0.3_wp, THICK = 0.05_wp

  ! Square plates: side 1, E chosen so that D = 1, unit load: w_centre is the coefficient.
  real(wp), parameter :: SQ_T = 0.01_wp, SQ_NU = 0.3_wp
  real(wp), parameter :: SQ_E = 12*(1 - SQ_NU**2)/SQ_T**3
  integer, parameter :: NMESH = 5
  integer, parameter :: MESHES(NMESH) = [2, 4, 8, 16, 32]   !! elements per side of the quarter model
  integer, parameter :: SERIES_TERMS = 400                  !! odd terms in the clamped-plate series
  real(wp), parameter :: ZETA3 = 1.2020569031595942854_wp   !! Riemann ζ(3)
  ! Timoshenko & Woinowsky-Krieger, centre deflection coefficients (ν-independent)
  real(wp), parameter :: TIM_SS_UNIFORM = 0.00406_wp, TIM_SS_POINT = 0.01160_wp, &
       TIM_CL_UNIFORM = 0.00126_wp, TIM_CL_POINT = 0.00560_wp
  real(wp), parameter :: TIM_ROUNDING = 0.5e-5_wp           !! SS values: 3 significant digits, rounded
  real(wp), parameter :: TIM_CLAMPED_REL = 0.005_wp         !! clamped values: approximate (0.4 %, 0.2 % low)
  real(wp), parameter :: DKQ_TOL_32 = 0.005_wp              !! DKQ within 0.5 % on the 32x32 quarter
  real(wp), parameter :: DKT_TOL_32 = 0.005_wp              !! DKT within 0.5 % on the 32x32 quarter
  real(wp), parameter :: ORDER_MIN = 1.8_wp, ORDER_MAX = 2.2_wp   !! observed order between n = 16 and 32
  real(wp), parameter :: RAW_ORDER_MIN_POINT = 1.6_wp       !! point loads: h² log(a/h) gives about 1.8
  integer, parameter :: NAVIER_TERMS = 500                  !! odd terms per direction in the Navier check


  call set_seed(19800101)
  call test_errors()
  call test_symmetry_and_rigid_modes()
  call test_rotation_invariance()
  call test_constant_curvature_moments()
  call test_pressure_load()
  call test_patch(.false.)
  call test_patch(.true.)
  call test_square_plates()
  call finish()

contains

  ! ---------------------------------------------------------------- helpers

  subroutine distorted_element(n, xl)
    !! A randomly distorted, shifted and scaled triangle (n = 3) or convex quadrilateral (n = 4).
    integer, intent(in) :: n
    real(wp), allocatable, intent(out) :: xl(:, :)
    real(wp) :: scale, shift(2)
    integer :: i
    allocate (xl(2, n))
    if (n == 3) then
       xl = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.2_wp, 0.3_wp, 0.9_wp], [2, 3])
    else
       xl = reshape([0.0_wp, 0.0_wp, 1.6_wp, 0.3_wp, 1.2_wp, 1.1_wp, 0.1_wp, 0.8_wp], [2, 4])
    end if
    do i = 1, n
       xl(:, i) = xl(:, i) + [rnd_in(-0.15_wp, 0.15_wp), rnd_in(-0.15_wp, 0.15_wp)]
    end do
    scale = 10.0_wp**rnd_in(-2.0_wp, 1.0_wp)
    shift = [rnd_in(-5.0_wp, 5.0_wp), rnd_in(-5.0_wp, 5.0_wp)]
    do i = 1, n
       xl(:, i) = scale*(xl(:, i) + shift)
    end do
  end subroutine distorted_element

  pure function quadratic_field(c, xl) result(u)
    !! Nodal DOFs (w, θx = ∂w/∂y, θy = -∂w/∂x) of w = c1 + c2 x + c3 y + c4 x²/2 + c5 x y + c6 y²/2.
    real(wp), intent(in) :: c(6), xl(:, :)
    real(wp) :: u(NDN*size(xl, 2))
    real(wp) :: x, y
    integer :: i
    do i = 1, size(xl, 2)
       x = xl(1, i)
       y = xl(2, i)
       u(NDN*i - 2) = c(1) + c(2)*x + c(3)*y + 0.5_wp*c(4)*x**2 + c(5)*x*y + 0.5_wp*c(6)*y**2
       u(NDN*i - 1) = c(3) + c(5)*x + c(6)*y
       u(NDN*i) = -(c(2) + c(4)*x + c(5)*y)
    end do
  end function quadratic_field

  pure function kirchhoff_moments(c, d, nu_) result(m)
    !! Exact moments (mx, my, mxy) of the quadratic field c (see quadratic_field) for rigidity d.
    real(wp), intent(in) :: c(6), d, nu_
    real(wp) :: m(3)
    m = -d*[c(4) + nu_*c(6), c(6) + nu_*c(4), (1 - nu_)*c(5)]
  end function kirchhoff_moments

  pure real(wp) function rigidity(e, t, nu_)
    !! Plate bending rigidity D = E t³ / (12 (1 - ν²)).
    real(wp), intent(in) :: e, t, nu_
    rigidity = e*t**3/(12*(1 - nu_**2))
  end function rigidity

  function symmetric_eigenvalues(a) result(w)
    !! Eigenvalues (ascending) of a symmetric matrix.
    real(wp), intent(in) :: a(:, :)
    real(wp) :: w(size(a, 1))
    real(wp), allocatable :: c(:, :), work(:)
    integer :: n, info
    n = size(a, 1)
    allocate (c, source=a)
    allocate (work(max(1, 3*n*4)))
    call dsyev('N', 'U', n, c, n, w, work, size(work), info)
    call check(info == 0, 'dsyev info')
  end function symmetric_eigenvalues

  subroutine expect_error(error, fragment, what)
    !! The error is allocated, has code EXIT_DECK and contains fragment.
    type(error_t), allocatable, intent(in) :: error
    character(*), intent(in) :: fragment, what
    if (.not. allocated(error)) then
       call check(.false., what//': no error')
       return
    end if
    call check(error%code == EXIT_DECK, what//': code')
    call check(index(error%message, fragment) > 0, what//': message "'//error%message//'"')
  end subroutine expect_error

  ! ---------------------------------------------------------------- tests

  subroutine test_errors()
    !! Every data check of the element routines.
    real(wp), allocatable :: kb(:, :), fe(:)
    real(wp) :: m(3), tri(2, 3), quad(2, 4), bad(2, 4)
    type(error_t), allocatable :: error
    integer :: i

    tri = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 3])
    quad = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])

    call plate_stiffness(tri, THICK, E_MOD, NU, kb, error)
    call check(.not. allocated(error), 'valid triangle accepted')
    call plate_stiffness(quad, THICK, E_MOD, NU, kb, error)
    call check(.not. allocated(error), 'valid quadrilateral accepted')

    call plate_stiffness(tri, 0.0_wp, E_MOD, NU, kb, error)
    call expect_error(error, 'nonpositive shell thickness', 't = 0')
    call check(.not. allocated(kb), 't = 0: no matrix')
    call plate_stiffness(quad, -THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'nonpositive shell thickness', 't < 0')
    call plate_stiffness(quad, THICK, 0.0_wp, NU, kb, error)
    call expect_error(error, 'nonpositive Young', 'E = 0')
    call plate_stiffness(tri, THICK, -E_MOD, NU, kb, error)
    call expect_error(error, 'nonpositive Young', 'E < 0')
    call plate_stiffness(tri, THICK, E_MOD, 0.5_wp, kb, error)
    call expect_error(error, 'Poisson', 'nu = 0.5')
    call plate_stiffness(quad, THICK, E_MOD, -1.0_wp, kb, error)
    call expect_error(error, 'Poisson', 'nu = -1')
    call plate_stiffness(quad, THICK, E_MOD, -0.99_wp, kb, error)
    call check(.not. allocated(error), 'nu = -0.99 accepted')
    call plate_stiffness(quad, THICK, E_MOD, 0.49_wp, kb, error)
    call check(.not. allocated(error), 'nu = 0.49 accepted')

    call plate_stiffness(tri(:, [1, 3, 2]), THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'zero or negative element area', 'clockwise triangle')
    call plate_stiffness(tri(:, [1, 2, 2]), THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'zero or negative element area', 'coincident triangle nodes')
    call plate_stiffness(reshape([0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 2.0_wp, 2.0_wp], [2, 3]), &
         THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'zero or negative element area', 'collinear triangle')
    call plate_stiffness(quad(:, [4, 3, 2, 1]), THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'zero or negative element area', 'clockwise quadrilateral')
    call plate_stiffness(quad(:, [1, 3, 2, 4]), THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'zero or negative element area', 'self-crossing quadrilateral')
    bad = quad
    bad(:, 4) = bad(:, 3)
    call plate_stiffness(bad, THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'coincident nodes', 'quadrilateral with two coincident nodes')
    bad = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.3_wp, 0.3_wp, 0.0_wp, 2.0_wp], [2, 4])
    call plate_stiffness(bad, THICK, E_MOD, NU, kb, error)
    call expect_error(error, 'non-positive Jacobian', 'concave quadrilateral')
    call plate_stiffness(reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp, 1.5_wp, 0.0_wp, 1.0_wp], &
         [2, 5]), THICK, E_MOD, NU, kb, error)
    call expect_error(error, '3 or 4 nodes', 'five nodes')
    call plate_stiffness(reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], &
         [3, 3]), THICK, E_MOD, NU, kb, error)
    call expect_error(error, '3 or 4 nodes', 'three coordinates')

    call plate_moments(quad, THICK, E_MOD, NU, [1.0_wp, 2.0_wp], m, error)
    call expect_error(error, 'wrong number of element DOF values', 'moments: short ue')
    call plate_moments(quad(:, [4, 3, 2, 1]), THICK, E_MOD, NU, [(1.0_wp, i=1, 12)], m, error)
    call expect_error(error, 'zero or negative element area', 'moments: clockwise')
    call plate_moments(tri, THICK, E_MOD, 0.6_wp, [(1.0_wp, i=1, 9)], m, error)
    call expect_error(error, 'Poisson', 'moments: nu')

    call plate_pressure_load(reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], [2, 2]), 1.0_wp, fe)
    call check(size(fe) == 0, 'pressure load on two nodes: empty')
  end subroutine test_errors

  subroutine test_symmetry_and_rigid_modes()
    !! Distorted elements: kb exactly symmetric, rigid-body fields w = a + b x + c y
    !! (θx = c, θy = -b) give zero forces, exactly 3 zero eigenvalues, no negative one.
    !! The eigenvalues are those of the stiffness in the DOFs (w/L, θx, θy), L the longest
    !! side, so that their ratios do not depend on the size of the element.
    integer, parameter :: NTRIAL = 20
    real(wp), parameter :: ZERO_EIG = 1.0e-12_wp    !! rigid-mode eigenvalue / largest: round-off (3e-16 seen)
    real(wp), parameter :: MIN_EIG = 1.0e-4_wp      !! smallest deformation mode / largest (3e-3 seen)
    real(wp), allocatable :: kb(:, :), xl(:, :), lam(:)
    real(wp) :: c(6), r(12), knorm, sc(12), l
    type(error_t), allocatable :: error
    integer :: n, trial, mode, i
    character(len=40) :: tag

    do n = 3, 4
       do trial = 1, NTRIAL
          write (tag, '(a,i0,a,i0)') 'rigid modes n=', n, ' trial ', trial
          call distorted_element(n, xl)
          call plate_stiffness(xl, THICK, E_MOD, rnd_in(-0.5_wp, 0.45_wp), kb, error)
          call check(.not. allocated(error), trim(tag)//': accepted')
          if (allocated(error)) cycle
          call check(all(shape(kb) == [3*n, 3*n]), trim(tag)//': shape')
          call check(all(kb == transpose(kb)), trim(tag)//': exactly symmetric')
          knorm = maxval(sum(abs(kb), dim=1))
          do mode = 1, 4
             c = 0.0_wp
             if (mode <= 3) then
                c(mode) = 1.0_wp
             else
                c(1:3) = [rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp)]
             end if
             r(1:3*n) = matmul(kb, quadratic_field(c, xl))
             call check(maxval(abs(r(1:3*n))) <= TOL_EXACT*knorm*maxval(abs(quadratic_field(c, xl))), &
                  trim(tag)//': rigid-body forces')
          end do
          l = maxval([(norm2(xl(:, mod(i, n) + 1) - xl(:, i)), i=1, n)])
          sc = 1.0_wp
          sc(1::3) = l
          do i = 1, 3*n
             kb(:, i) = kb(:, i)*sc(i)*sc(1:3*n)
          end do
          lam = symmetric_eigenvalues(kb)
          call check(count(abs(lam) <= ZERO_EIG*lam(3*n)) == 3, trim(tag)//': 3 zero eigenvalues')
          call check(lam(4) >= MIN_EIG*lam(3*n), trim(tag)//': 4th eigenvalue positive')
          call check(lam(1) >= -ZERO_EIG*lam(3*n), trim(tag)//': no negative eigenvalue')
       end do
    end do
  end subroutine test_symmetry_and_rigid_modes

  subroutine test_rotation_invariance()
    !! Rotating an element in its plane by φ rotates the vector (θx, θy) at each
    !! node: K' = T K Tᵀ and the moment tensor M' = R M Rᵀ.
    real(wp), allocatable :: kb(:, :), kr(:, :), xl(:, :), tr(:, :)
    real(wp) :: rot(2, 2), phi, c(6), m(3), mr(3), mt(2, 2), u(12)
    type(error_t), allocatable :: error
    integer :: n, trial, i

    do n = 3, 4
       do trial = 1, 5
          call distorted_element(n, xl)
          phi = rnd_in(-PI, PI)
          rot = reshape([cos(phi), sin(phi), -sin(phi), cos(phi)], [2, 2])
          call plate_stiffness(xl, THICK, E_MOD, NU, kb, error)
          call plate_stiffness(matmul(rot, xl), THICK, E_MOD, NU, kr, error)
          allocate (tr(3*n, 3*n), source=0.0_wp)
          do i = 0, n - 1
             tr(3*i + 1, 3*i + 1) = 1.0_wp
             tr(3*i + 2:3*i + 3, 3*i + 2:3*i + 3) = rot
          end do
          call check(maxval(abs(kr - matmul(tr, matmul(kb, transpose(tr))))) <= TOL*maxval(abs(kb)), &
               'rotation invariance of K')
          c = [(rnd_in(-1.0_wp, 1.0_wp), i=1, 6)]
          u(1:3*n) = quadratic_field(c, xl)
          call plate_moments(xl, THICK, E_MOD, NU, u(1:3*n), m, error)
          call plate_moments(matmul(rot, xl), THICK, E_MOD, NU, matmul(tr, u(1:3*n)), mr, error)
          mt = matmul(rot, matmul(reshape([m(1), m(3), m(3), m(2)], [2, 2]), transpose(rot)))
          call check(maxval(abs([mt(1, 1), mt(2, 2), mt(1, 2)] - mr)) <= TOL_EXACT*maxval(abs(m)), &
               'rotation invariance of the moments')
          deallocate (tr)
       end do
    end do
  end subroutine test_rotation_invariance

  subroutine test_constant_curvature_moments()
    !! A quadratic w on one distorted element: the centre moments are the exact Kirchhoff moments
    !! (signs: mx = -D (w_xx + ν w_yy), mxy = -D (1-ν) w_xy), and the unit-curvature cases by hand.
    real(wp), allocatable :: xl(:, :)
    real(wp) :: c(6), m(3), mref(3), d
    type(error_t), allocatable :: error
    integer :: n, trial, i

    d = rigidity(E_MOD, THICK, NU)
    do n = 3, 4
       do trial = 1, 10
          call distorted_element(n, xl)
          c = [(rnd_in(-1.0_wp, 1.0_wp), i=1, 6)]
          call plate_moments(xl, THICK, E_MOD, NU, quadratic_field(c, xl), m, error)
          call check(.not. allocated(error), 'moments: accepted')
          mref = kirchhoff_moments(c, d, NU)
          call check(maxval(abs(m - mref)) <= TOL_EXACT*maxval(abs(mref)), 'moments of a quadratic field')
       end do
       ! w = x²/2: mx = -D, my = -ν D, mxy = 0 (the top surface is in compression).
       call distorted_element(n, xl)
       call plate_moments(xl, THICK, E_MOD, NU, quadratic_field([0, 0, 0, 1, 0, 0]*1.0_wp, xl), m, error)
       call check_rel(m(1), -d, TOL_EXACT, 'w = x²/2: mx')
       call check_rel(m(2), -NU*d, TOL_EXACT, 'w = x²/2: my')
       call check_close(m(3), 0.0_wp, TOL_EXACT*d, 'w = x²/2: mxy')
       ! w = x y: mxy = -D (1 - ν).
       call plate_moments(xl, THICK, E_MOD, NU, quadratic_field([0, 0, 0, 0, 1, 0]*1.0_wp, xl), m, error)
       call check_close(m(1), 0.0_wp, TOL_EXACT*d, 'w = x y: mx')
       call check_close(m(2), 0.0_wp, TOL_EXACT*d, 'w = x y: my')
       call check_rel(m(3), -(1 - NU)*d, TOL_EXACT, 'w = x y: mxy')
    end do
  end subroutine test_constant_curvature_moments

  subroutine test_pressure_load()
    !! Pressure loads: translations only; triangle p A/3 per node; a rectangle p A/4;
    !! on a distorted quadrilateral the total is p A and the first moments p A x_c.
    real(wp), parameter :: P = -3.5_wp
    real(wp), allocatable :: fe(:), xl(:, :)
    real(wp) :: area, xc(2), a2
    integer :: i, j, trial

    do trial = 1, 5
       call distorted_element(3, xl)
       area = 0.5_wp*((xl(1, 2) - xl(1, 1))*(xl(2, 3) - xl(2, 1)) - (xl(1, 3) - xl(1, 1))*(xl(2, 2) - xl(2, 1)))
       call plate_pressure_load(xl, P, fe)
       call check(size(fe) == 9, 'triangle pressure: size')
       do i = 1, 3
          call check_rel(fe(3*i - 2), P*area/3, TOL, 'triangle pressure: p A/3')
          call check(fe(3*i - 1) == 0.0_wp .and. fe(3*i) == 0.0_wp, 'triangle pressure: no moments')
       end do
    end do

    xl = reshape([1.0_wp, 2.0_wp, 4.0_wp, 2.0_wp, 4.0_wp, 3.5_wp, 1.0_wp, 3.5_wp], [2, 4])
    call plate_pressure_load(xl, P, fe)
    do i = 1, 4
       call check_rel(fe(3*i - 2), P*4.5_wp/4, TOL, 'rectangle pressure: p A/4')
    end do

    do trial = 1, 5
       call distorted_element(4, xl)
       call plate_pressure_load(xl, P, fe)
       call check(size(fe) == 12, 'quadrilateral pressure: size')
       ! Area and centroid of the polygon.
       area = 0.0_wp
       xc = 0.0_wp
       do i = 1, 4
          j = mod(i, 4) + 1
          a2 = xl(1, i)*xl(2, j) - xl(1, j)*xl(2, i)
          area = area + 0.5_wp*a2
          xc = xc + a2*(xl(:, i) + xl(:, j))/6
       end do
       xc = xc/area
       call check_rel(sum(fe(1::3)), P*area, TOL, 'quadrilateral pressure: total p A')
       call check_rel(sum(fe(1::3)*xl(1, :)), P*area*xc(1), TOL, 'quadrilateral pressure: moment about y')
       call check_rel(sum(fe(1::3)*xl(2, :)), P*area*xc(2), TOL, 'quadrilateral pressure: moment about x')
       call check(all(fe(2::3) == 0.0_wp) .and. all(fe(3::3) == 0.0_wp), 'quadrilateral pressure: no moments')
    end do
  end subroutine test_pressure_load

  subroutine test_patch(triangles)
    !! MacNeal-Harder patch (0.24 x 0.12, 5 quadrilaterals, or each split into 2 triangles),
    !! w = 1e-3 (x² + x y + y²)/2 imposed on the 4 corner nodes: the interior DOFs and every
    !! element's moments are exact.
    logical, intent(in) :: triangles
    real(wp), parameter :: T = 0.001_wp, E = 1.0e6_wp, PNU = 0.25_wp, CURV = 1.0e-3_wp
    real(wp), parameter :: XN(2, 8) = reshape([0.0_wp, 0.0_wp, 0.24_wp, 0.0_wp, 0.24_wp, 0.12_wp, 0.0_wp, 0.12_wp, &
         0.04_wp, 0.02_wp, 0.18_wp, 0.03_wp, 0.16_wp, 0.08_wp, 0.08_wp, 0.08_wp], [2, 8])
    integer, parameter :: QUADS(4, 5) = reshape([1, 2, 6, 5, 2, 3, 7, 6, 3, 4, 8, 7, 4, 1, 5, 8, 5, 6, 7, 8], [4, 5])
    integer, parameter :: NFIXED = 4, NDOF = 3*8
    real(wp) :: c(6), uex(NDOF), k(NDOF, NDOF), f(NDOF - 3*NFIXED, 1), m(3), mref(3)
    real(wp), allocatable :: kb(:, :), kff(:, :)
    integer, allocatable :: conn(:, :), dofs(:)
    type(error_t), allocatable :: error
    integer :: el, i, info, nf
    character(len=3) :: name

    c = [0.0_wp, 0.0_wp, 0.0_wp, CURV, 0.5_wp*CURV, CURV]    ! w = 1e-3 (x² + x y + y²)/2
    uex = quadratic_field(c, XN)
    if (triangles) then
       name = 'DKT'
       allocate (conn(3, 10))
       do el = 1, 5
          conn(:, 2*el - 1) = QUADS([1, 2, 3], el)
          conn(:, 2*el) = QUADS([1, 3, 4], el)
       end do
    else
       name = 'DKQ'
       conn = QUADS
    end if

    k = 0.0_wp
    do el = 1, size(conn, 2)
       call plate_stiffness(XN(:, conn(:, el)), T, E, PNU, kb, error)
       call check(.not. allocated(error), name//' patch: element accepted')
       if (allocated(error)) return
       dofs = [(3*(conn((i + 2)/3, el) - 1) + mod(i - 1, 3) + 1, i=1, 3*size(conn, 1))]
       k(dofs, dofs) = k(dofs, dofs) + kb
    end do
    ! Free DOFs: the interior nodes 5..8; the corners carry the exact field.
    nf = NDOF - 3*NFIXED
    kff = k(3*NFIXED + 1:, 3*NFIXED + 1:)
    f(:, 1) = -matmul(k(3*NFIXED + 1:, 1:3*NFIXED), uex(1:3*NFIXED))
    call dposv('U', nf, 1, kff, nf, f, nf, info)
    call check(info == 0, name//' patch: dposv')
    do i = 1, nf
       call check_rel(f(i, 1), uex(3*NFIXED + i), TOL_EXACT, name//' patch: interior DOF')
    end do
    uex(3*NFIXED + 1:) = f(:, 1)
    mref = kirchhoff_moments(c, rigidity(E, T, PNU), PNU)
    do el = 1, size(conn, 2)
       dofs = [(3*(conn((i + 2)/3, el) - 1) + mod(i - 1, 3) + 1, i=1, 3*size(conn, 1))]
       call plate_moments(XN(:, conn(:, el)), T, E, PNU, uex(dofs), m, error)
       call check(.not. allocated(error), name//' patch: moments')
       call check_rel(m(1), mref(1), TOL_EXACT, name//' patch: mx')
       call check_rel(m(2), mref(2), TOL_EXACT, name//' patch: my')
       call check_rel(m(3), mref(3), TOL_EXACT, name//' patch: mxy')
    end do
  end subroutine test_patch

  ! ------------------------------------------------------- square plates

  pure real(wp) function sech(x)
    !! 1/cosh(x) without overflow for large x.
    real(wp), intent(in) :: x
    sech = 2*exp(-x)/(1 + exp(-2*x))
  end function sech

  pure real(wp) function ss_uniform_levy()
    !! Centre deflection of a simply supported unit square, uniform unit load, D = 1:
    !! Lévy single series (Timoshenko & Woinowsky-Krieger §30), terms decay like e^(-mπ/2)/m⁵.
    integer :: m
    real(wp) :: al, yp
    ss_uniform_levy = 0.0_wp
    do m = 1, 2*SERIES_TERMS - 1, 2
       al = m*PI
       yp = 4/(m*PI*al**4)
       ss_uniform_levy = ss_uniform_levy + (-1)**((m - 1)/2)*yp* &
            (1 - 0.5_wp*(2 + 0.5_wp*al*tanh(0.5_wp*al))*sech(0.5_wp*al))
    end do
  end function ss_uniform_levy

  pure real(wp) function ss_uniform_navier(nterm)
    !! The same by the Navier double series 16/π⁶ Σ ±1/(m n (m² + n²)²) (m, n odd),
    !! truncated at m, n < 2 nterm (tail ~ nterm⁻⁴).
    integer, intent(in) :: nterm
    integer :: m, n
    ss_uniform_navier = 0.0_wp
    do n = 2*nterm - 1, 1, -2
       do m = 2*nterm - 1, 1, -2
          ss_uniform_navier = ss_uniform_navier + (-1)**((m + n - 2)/2)/(real(m, wp)*n*(real(m, wp)**2 + n**2)**2)
       end do
    end do
    ss_uniform_navier = 16*ss_uniform_navier/PI**6
  end function ss_uniform_navier

  pure real(wp) function ss_point_levy()
    !! Centre deflection of a simply supported unit square under a unit centre load, D = 1:
    !! 1/(2π³) Σ (tanh α - α/cosh² α)/m³, α = mπ/2 (Timoshenko §35), written as
    !! 7ζ(3)/8 minus exponentially small terms.
    integer :: m
    real(wp) :: al
    ss_point_levy = 7*ZETA3/8/(2*PI**3)
    do m = 1, 2*SERIES_TERMS - 1, 2
       al = m*PI
       ss_point_levy = ss_point_levy - (1 - tanh(0.5_wp*al) + 0.5_wp*al*sech(0.5_wp*al)**2)/(2*al**3)
    end do
  end function ss_point_levy

  subroutine clamped_references(nterm, w_uniform, w_point)
    !! Centre deflections of a clamped unit square (D = 1, unit load) by superposition
    !! (Timoshenko §44): the simply supported plate plus edge moments Σ c_k sin(kπx) on the
    !! four edges (symmetric), c from zero edge slope, k odd < 2 nterm. The slope at y = 0 of
    !! the moment field with w_yy = sin(α x) on y = 0, 1 is Y'(-h) sin(α x),
    !! Y'(-h) = -(tanh(αh)/(2α) + h/(2 cosh² αh)), h = 1/2; the perpendicular edges give
    !! α_m Y_m(x - h) = -4 α_m Σ_k α_k/(α_m² + α_k²)² sin(α_k x).
    integer, intent(in) :: nterm
    real(wp), intent(out) :: w_uniform, w_point
    real(wp), parameter :: H = 0.5_wp
    real(wp), allocatable :: a(:, :), rhs(:, :), al(:), sg(:)
    integer, allocatable :: ipiv(:)
    integer :: i, j, info
    real(wp) :: th, yp, y0

    allocate (a(nterm, nterm), rhs(nterm, 2), al(nterm), sg(nterm), ipiv(nterm))
    do i = 1, nterm
       al(i) = (2*i - 1)*PI
       sg(i) = (-1)**(i - 1)
    end do
    do i = 1, nterm
       do j = 1, nterm
          a(i, j) = -4*al(j)*al(i)/(al(j)**2 + al(i)**2)**2
       end do
       th = tanh(al(i)*H)
       a(i, i) = a(i, i) - (th/(2*al(i)) + H*sech(al(i)*H)**2/2)
       ! Edge slopes of the simply supported plate: uniform load, centre point load.
       yp = 4/((2*i - 1)*PI*al(i)**4)
       rhs(i, 1) = -yp*al(i)/2*(th - al(i)*H*sech(al(i)*H)**2)
       rhs(i, 2) = -sg(i)*H*th*sech(al(i)*H)/(2*al(i))
    end do
    call dgesv(nterm, 2, a, nterm, ipiv, rhs, nterm, info)
    call check(info == 0, 'clamped plate series: dgesv')
    w_uniform = ss_uniform_levy()
    w_point = ss_point_levy()
    do j = 1, nterm
       y0 = -H*tanh(al(j)*H)*sech(al(j)*H)/(2*al(j))     ! Y_j(0): the moment field at the centre
       w_uniform = w_uniform + 2*rhs(j, 1)*sg(j)*y0
       w_point = w_point + 2*rhs(j, 2)*sg(j)*y0
    end do
  end subroutine clamped_references

  real(wp) function quarter_plate(n, triangles, clamped, point) result(wc)
    !! Centre deflection of the unit square plate (D = 1) on a quarter model [0, 1/2]² with
    !! n x n quadrilaterals (or each split into 2 triangles along the diagonal towards the
    !! centre). Edges x = 0 and y = 0: w = 0 (simply supported, rotations free) or w = θx = θy = 0
    !! (clamped); symmetry x = 1/2: θy = 0, y = 1/2: θx = 0. Load: uniform unit pressure, or a
    !! unit point load at the centre (1/4 on the quarter). Banded Cholesky (dpbsv).
    integer, intent(in) :: n
    logical, intent(in) :: triangles, clamped, point
    real(wp), allocatable :: ab(:, :), f(:, :), kb(:, :), fe(:), xl(:, :)
    integer, allocatable :: eq(:), conn(:, :), dofs(:), edofs(:)
    type(error_t), allocatable :: error
    real(wp) :: h
    integer :: nn, i, j, node, el, a, b, kd, neq, info, ii, jj, cell(4)

    h = 0.5_wp/n
    nn = (n + 1)**2
    ! Equation numbers, node-major, 0 for a constrained DOF.
    allocate (eq(3*nn), source=1)
    do j = 0, n
       do i = 0, n
          node = j*(n + 1) + i + 1
          if (i == 0 .or. j == 0) then
             eq(3*node - 2) = 0
             if (clamped) eq(3*node - 1:3*node) = 0
          end if
          if (i == n) eq(3*node) = 0
          if (j == n) eq(3*node - 1) = 0
       end do
    end do
    neq = 0
    do a = 1, 3*nn
       if (eq(a) /= 0) then
          neq = neq + 1
          eq(a) = neq
       end if
    end do
    ! Elements.
    if (triangles) then
       allocate (conn(3, 2*n*n))
    else
       allocate (conn(4, n*n))
    end if
    el = 0
    do j = 0, n - 1
       do i = 0, n - 1
          cell = [j*(n + 1) + i + 1, j*(n + 1) + i + 2, (j + 1)*(n + 1) + i + 2, (j + 1)*(n + 1) + i + 1]
          if (triangles) then
             conn(:, el + 1) = cell([1, 2, 3])
             conn(:, el + 2) = cell([1, 3, 4])
             el = el + 2
          else
             el = el + 1
             conn(:, el) = cell
          end if
       end do
    end do
    ! Half bandwidth.
    kd = 0
    do el = 1, size(conn, 2)
       edofs = [(3*(conn((a + 2)/3, el) - 1) + mod(a - 1, 3) + 1, a=1, 3*size(conn, 1))]
       dofs = pack(eq(edofs), eq(edofs) > 0)
       kd = max(kd, maxval(dofs) - minval(dofs))
    end do
    allocate (ab(kd + 1, neq), source=0.0_wp)
    allocate (f(neq, 1), source=0.0_wp)
    allocate (xl(2, size(conn, 1)))
    do el = 1, size(conn, 2)
       do a = 1, size(conn, 1)
          node = conn(a, el)
          xl(:, a) = h*[real(mod(node - 1, n + 1), wp), real((node - 1)/(n + 1), wp)]
       end do
       call plate_stiffness(xl, SQ_T, SQ_E, SQ_NU, kb, error)
       call check(.not. allocated(error), 'square plate: element accepted')
       if (allocated(error)) return
       edofs = [(3*(conn((a + 2)/3, el) - 1) + mod(a - 1, 3) + 1, a=1, 3*size(conn, 1))]
       do b = 1, size(edofs)
          jj = eq(edofs(b))
          if (jj == 0) cycle
          do a = 1, size(edofs)
             ii = eq(edofs(a))
             if (ii == 0 .or. ii > jj) cycle
             ab(kd + 1 + ii - jj, jj) = ab(kd + 1 + ii - jj, jj) + kb(a, b)
          end do
       end do
       if (.not. point) then
          call plate_pressure_load(xl, 1.0_wp, fe)
          do a = 1, size(edofs)
             if (eq(edofs(a)) > 0) f(eq(edofs(a)), 1) = f(eq(edofs(a)), 1) + fe(a)
          end do
       end if
    end do
    if (point) f(eq(3*nn - 2), 1) = 0.25_wp
    call dpbsv('U', neq, kd, 1, ab, kd + 1, f, neq, info)
    call check(info == 0, 'square plate: dpbsv')
    wc = f(eq(3*nn - 2), 1)
  end function quarter_plate

  subroutine test_square_plates()
    !! Centre deflection of simply supported and clamped square plates under uniform and
    !! centre point loads, DKQ and DKT, quarter models n x n: references from series
    !! (exact to round-off), checked against Timoshenko's coefficients; the error on the
    !! finest mesh, monotone convergence and the observed order between n = 16 and 32.
    !! Under a point load the exact w has an r² log r singularity and the error behaves as
    !! h² log(a/h): its order is checked after removing the log factor, the raw order
    !! (about 1.8 at n = 32) must only be above RAW_ORDER_MIN_POINT.
    character(len=*), parameter :: CASE_NAMES(4) = [character(len=16) :: 'SS, uniform', 'SS, point', &
         'clamped, uniform', 'clamped, point']
    real(wp) :: ref(4), tim(4), w(NMESH), err(NMESH), order(NMESH), order_log(NMESH), cl_u, cl_p, cl_u2, cl_p2, h
    integer :: ic, it, im
    logical :: tri, point
    character(len=3) :: ename
    character(len=120) :: line

    ! References.
    call clamped_references(SERIES_TERMS, cl_u, cl_p)
    call clamped_references(SERIES_TERMS/2, cl_u2, cl_p2)
    call check_rel(cl_u2, cl_u, TOL, 'clamped series converged (uniform)')
    call check_rel(cl_p2, cl_p, TOL, 'clamped series converged (point)')
    ref = [ss_uniform_levy(), ss_point_levy(), cl_u, cl_p]
    tim = [TIM_SS_UNIFORM, TIM_SS_POINT, TIM_CL_UNIFORM, TIM_CL_POINT]
    call check_rel(ss_uniform_navier(NAVIER_TERMS), ref(1), TOL_EXACT, 'SS uniform: Navier and Levy series agree')
    do ic = 1, 2
       call check_close(ref(ic), tim(ic), TIM_ROUNDING, trim(CASE_NAMES(ic))//': series vs Timoshenko')
    end do
    do ic = 3, 4
       call check_rel(ref(ic), tim(ic), TIM_CLAMPED_REL, trim(CASE_NAMES(ic))//': series vs Timoshenko')
    end do

    write (*, '(a)') 'Centre deflection of a square plate, quarter model n x n (h = a/(2n)):'
    write (*, '(a)') '  e = w/w_ref - 1; p = log2(e(n/2)/e(n)); point loads: p_log = the same for e/log(a/h)'
    do ic = 1, 4
       point = mod(ic, 2) == 0
       write (*, '(a,a,es21.14)') trim(CASE_NAMES(ic)), ': w_ref D/(load a^k) = ', ref(ic)
       do it = 1, 2
          tri = it == 2
          ename = merge('DKT', 'DKQ', tri)
          do im = 1, NMESH
             w(im) = quarter_plate(MESHES(im), tri, ic >= 3, point)
             err(im) = w(im)/ref(ic) - 1
             if (im == 1) then
                write (line, '(2x,a,i4,es12.3)') ename, MESHES(im), err(im)
             else
                h = 0.5_wp/MESHES(im)
                order(im) = log(abs(err(im - 1)/err(im)))/log(2.0_wp)
                order_log(im) = order(im) + log(log(1/h)/log(0.5_wp/h))/log(2.0_wp)
                if (point) then
                   write (line, '(2x,a,i4,es12.3,2(a,f6.3))') ename, MESHES(im), err(im), '  p ', order(im), &
                        '  p_log ', order_log(im)
                else
                   write (line, '(2x,a,i4,es12.3,a,f6.3)') ename, MESHES(im), err(im), '  p ', order(im)
                end if
             end if
             write (*, '(a)') trim(line)
          end do
          line = trim(CASE_NAMES(ic))//', '//ename
          call check(all(abs(err(2:)) < abs(err(:NMESH - 1))), trim(line)//': monotone convergence')
          if (point) then
             call check(order_log(NMESH) >= ORDER_MIN .and. order_log(NMESH) <= ORDER_MAX, &
                  trim(line)//': order of e/log(a/h) close to 2')
             call check(order(NMESH) >= RAW_ORDER_MIN_POINT, trim(line)//': raw order')
          else
             call check(order(NMESH) >= ORDER_MIN .and. order(NMESH) <= ORDER_MAX, trim(line)//': order close to 2')
          end if
          call check(abs(err(NMESH)) <= merge(DKT_TOL_32, DKQ_TOL_32, tri), trim(line)//': 32 x 32 within tolerance')
       end do
    end do
  end subroutine test_square_plates
end program test_plate
