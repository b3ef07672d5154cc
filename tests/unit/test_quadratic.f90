program test_quadratic
  !! Unit tests of the second-order plane elements (superjoin_elements_quadratic):
  !! shape functions, data checks, matrix properties (symmetry, rigid modes, zero
  !! eigenvalues: 3 for CPS6/CPS8, 4 for the single CPS8R with its spurious mode),
  !! consistent area loads, and exact resultants of a constant strain state on
  !! elements with curved sides (plane stress and plane strain); stresses at the
  !! integration points and extrapolated to the nodes: exact for constant stress
  !! on curved elements and for linear stress (a complete quadratic displacement
  !! field: bending) on a parallelogram and a straight-sided triangle. Patch tests on
  !! meshes, MacNeal-Harder and convergence run through the whole program in
  !! tests/plane/verify_plane.py.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_elements_quadratic, only: plane_props_t, quadratic_stiffness, quadratic_resultants, &
       quadratic_shape_integrals, quadratic_shape, quadratic_point_stresses, quadratic_stress_points
  use superjoin_testing, only: check, check_close, check_rel, finish
  use test_lapack, only: eigenvalues
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)

  real(wp), parameter :: TOL_EXACT = 1.0e-12_wp    !! exact discrete answers, relative
  real(wp), parameter :: TOL_ZERO_EIG = 1.0e-11_wp !! a zero eigenvalue, relative to the largest
  real(wp), parameter :: MIN_POSITIVE = 1.0e-6_wp  !! smallest non-zero eigenvalue / largest, at least
  real(wp), parameter :: T = 0.2_wp, E = 2.1e5_wp, NU = 0.3_wp

  ! A 6-node triangle with one curved side and an 8-node quadrilateral with two
  ! curved sides and a skewed shape (counter-clockwise, Abaqus node order).
  real(wp), parameter :: TRI6(2, 6) = reshape([ &
       0.0_wp, 0.0_wp, 2.0_wp, 0.3_wp, 0.5_wp, 1.6_wp, &
       1.0_wp, -0.1_wp, 1.35_wp, 1.05_wp, 0.2_wp, 0.85_wp], [2, 6])
  real(wp), parameter :: QUAD8(2, 8) = reshape([ &
       0.0_wp, 0.0_wp, 2.0_wp, 0.2_wp, 2.4_wp, 1.5_wp, -0.2_wp, 1.0_wp, &
       1.0_wp, -0.1_wp, 2.3_wp, 0.8_wp, 1.1_wp, 1.35_wp, -0.05_wp, 0.5_wp], [2, 8])

  ! u = Σ a_k m_k(x, y), v = Σ b_k m_k(x, y) with m = (1, x, y, x², x y, y²)
  real(wp), parameter :: AU(6) = [1.0e-3_wp, 2.0e-3_wp, -1.0e-3_wp, 3.0e-4_wp, -5.0e-4_wp, 7.0e-4_wp]
  real(wp), parameter :: BV(6) = [-2.0e-3_wp, 5.0e-4_wp, 1.5e-3_wp, -6.0e-4_wp, 4.0e-4_wp, 2.0e-4_wp]

  call test_shape_functions()
  call test_errors()
  call test_matrix_properties()
  call test_area_loads()
  call test_constant_strain()
  call test_point_stresses()
  call finish()

contains

  subroutine test_shape_functions()
    !! Partition of unity, Kronecker property at the nodes, derivatives summing to
    !! zero, and derivatives against central differences.
    real(wp), parameter :: NODES6(2, 6) = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
         0.5_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp, 0.5_wp], [2, 6])
    real(wp), parameter :: NODES8(2, 8) = reshape([-1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, &
         -1.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp], [2, 8])
    real(wp), parameter :: H = 1.0e-6_wp, TOL_FD = 1.0e-8_wp
    real(wp) :: p(2), nf8(8), dn8(2, 8), nf6(6), dn6(2, 6), np(8), nm(8), dum(2, 8), id(8)
    integer :: i, k
    do i = 1, 8
       call quadratic_shape(8, NODES8(:, i), nf8, dn8)
       id = 0.0_wp
       id(i) = 1.0_wp
       call check(maxval(abs(nf8 - id)) <= TOL_EXACT, 'Q8 shape function '//itoa(i)//': 1 at its node, 0 at others')
    end do
    do i = 1, 6
       call quadratic_shape(6, NODES6(:, i), nf6, dn6)
       id = 0.0_wp
       id(i) = 1.0_wp
       call check(maxval(abs(nf6 - id(1:6))) <= TOL_EXACT, 'T6 shape function '//itoa(i)//': 1 at its node, 0 at others')
    end do
    p = [0.3_wp, -0.45_wp]
    call quadratic_shape(8, p, nf8, dn8)
    call check_close(sum(nf8), 1.0_wp, TOL_EXACT, 'Q8 partition of unity')
    call check(maxval(abs(sum(dn8, 2))) <= TOL_EXACT, 'Q8 derivatives sum to zero')
    do k = 1, 2
       call quadratic_shape(8, p + H*merge([1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], k == 1), np, dum)
       call quadratic_shape(8, p - H*merge([1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], k == 1), nm, dum)
       call check(maxval(abs((np - nm)/(2*H) - dn8(k, :))) <= TOL_FD, 'Q8 derivative '//itoa(k)//' by differences')
    end do
    p = [0.2_wp, 0.35_wp]
    call quadratic_shape(6, p, nf6, dn6)
    call check_close(sum(nf6), 1.0_wp, TOL_EXACT, 'T6 partition of unity')
    call check(maxval(abs(sum(dn6, 2))) <= TOL_EXACT, 'T6 derivatives sum to zero')
    do k = 1, 2
       call quadratic_shape(6, p + H*merge([1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], k == 1), np(1:6), dum(:, 1:6))
       call quadratic_shape(6, p - H*merge([1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], k == 1), nm(1:6), dum(:, 1:6))
       call check(maxval(abs((np(1:6) - nm(1:6))/(2*H) - dn6(k, :))) <= TOL_FD, &
            'T6 derivative '//itoa(k)//' by differences')
    end do
  end subroutine test_shape_functions

  subroutine expect_error(xl, props, text, what)
    !! The stiffness and the resultants must both refuse the element with text.
    real(wp), intent(in) :: xl(:, :)
    type(plane_props_t), intent(in) :: props
    character(*), intent(in) :: text, what
    real(wp), allocatable :: ke(:, :)
    real(wp) :: nres(3)
    type(error_t), allocatable :: error
    integer :: k
    call quadratic_stiffness(xl, props, ke, error)
    call check(allocated(error), what//': stiffness refused')
    if (.not. allocated(error)) return
    call check(error%code == EXIT_DECK, what//': code EXIT_DECK')
    call check(index(error%message, text) > 0, what//': message contains "'//text//'"')
    if (index(error%message, text) == 0) write (*, '(a)') '  message: '//error%message
    call quadratic_resultants(xl, props, [(0.0_wp, k=1, 2*size(xl, 2))], nres, error)
    call check(allocated(error), what//': resultants refused')
  end subroutine expect_error

  subroutine test_errors()
    !! Wrong node count, material data, clockwise nodes, coincident nodes, a
    !! mid-side node pushed across the element (negative Jacobian).
    type(plane_props_t) :: props
    real(wp), allocatable :: xl(:, :)
    props = plane_props_t(t=T, e=E, nu=NU)
    call expect_error(QUAD8(:, 1:7), props, '6 or 8 nodes', 'seven nodes')
    call expect_error(QUAD8, plane_props_t(t=0.0_wp, e=E, nu=NU), 'thickness', 'zero thickness')
    call expect_error(QUAD8, plane_props_t(t=T, e=-1.0_wp, nu=NU), 'Young', 'negative E')
    call expect_error(QUAD8, plane_props_t(t=T, e=E, nu=0.5_wp, strain=.true.), 'plane strain', 'nu = 0.5')
    xl = QUAD8(:, [4, 3, 2, 1, 7, 6, 5, 8])
    call expect_error(xl, props, 'negative area', 'clockwise quadrilateral')
    xl = TRI6(:, [1, 3, 2, 6, 5, 4])
    call expect_error(xl, props, 'negative area', 'clockwise triangle')
    xl = QUAD8
    xl(:, 6) = xl(:, 2)
    call expect_error(xl, props, 'coincident', 'mid-side node on a corner')
    xl = QUAD8
    xl(:, 5) = [1.1_wp, 1.6_wp]        ! mid-side of the bottom edge above the top edge
    call expect_error(xl, props, 'Jacobian', 'mid-side node across the element')
  end subroutine test_errors

  function rigid_modes(xl) result(u)
    !! Translations along x, y and the rotation about the origin.
    real(wp), intent(in) :: xl(:, :)
    real(wp) :: u(2*size(xl, 2), 3)
    integer :: i
    u = 0.0_wp
    do i = 1, size(xl, 2)
       u(2*i - 1, 1) = 1.0_wp
       u(2*i, 2) = 1.0_wp
       u(2*i - 1, 3) = -xl(2, i)
       u(2*i, 3) = xl(1, i)
    end do
  end function rigid_modes

  subroutine test_matrix_properties()
    !! Symmetric, rigid modes without force, eigenvalues: CPS6, CPS8, CPE8 three
    !! zero modes; CPS8R four (the spurious mode of 2×2 integration), the rest
    !! clearly positive.
    real(wp), allocatable :: ke(:, :), w(:), xl(:, :)
    real(wp) :: u(16, 3), kmax
    type(plane_props_t) :: props
    type(error_t), allocatable :: error
    integer :: k, m, nzero, n, want
    character(:), allocatable :: what
    allocate (xl(0, 0))   ! (quiets a spurious gfortran -Wuninitialized)
    do k = 1, 4
       select case (k)
       case (1)
          xl = TRI6
          props = plane_props_t(t=T, e=E, nu=NU)
          what = 'CPS6'
          want = 3
       case (2)
          xl = QUAD8
          props = plane_props_t(t=T, e=E, nu=NU)
          what = 'CPS8'
          want = 3
       case (3)
          xl = QUAD8
          props = plane_props_t(t=T, e=E, nu=NU, strain=.true.)
          what = 'CPE8'
          want = 3
       case default
          xl = QUAD8
          props = plane_props_t(t=T, e=E, nu=NU, reduced=.true.)
          what = 'CPS8R'
          want = 4
       end select
       n = 2*size(xl, 2)
       call quadratic_stiffness(xl, props, ke, error)
       call check(.not. allocated(error), what//': stiffness without error')
       if (allocated(error)) cycle
       kmax = maxval(abs(ke))
       call check(maxval(abs(ke - transpose(ke))) <= 1.0e-15_wp*kmax, what//': symmetric')
       u(1:n, :) = rigid_modes(xl)
       do m = 1, 3
          call check(maxval(abs(matmul(ke, u(1:n, m)))) <= TOL_EXACT*kmax*maxval(abs(u(1:n, m))), &
               what//': rigid mode '//itoa(m)//' has no force')
       end do
       w = eigenvalues(ke)
       nzero = count(abs(w) <= TOL_ZERO_EIG*w(n))
       call check(nzero == want, what//': '//itoa(want)//' zero eigenvalues (got '//itoa(nzero)//')')
       call check(w(want + 1) >= MIN_POSITIVE*w(n), what//': the other eigenvalues clearly positive')
    end do
  end subroutine test_matrix_properties

  subroutine test_area_loads()
    !! ∫ Nᵢ dA: straight-sided 8-node rectangle corners -A/12, mid-sides A/3;
    !! straight triangle corners 0, mid-sides A/3; curved elements: the shares
    !! sum to the area (Gauss area of the curved quadrilateral against the
    !! Green's-theorem area of its boundary parabolas).
    real(wp) :: xl8(2, 8), xl6(2, 6), w8(8), w6(6), area
    xl8(:, 1:4) = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, 3.0_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 4])
    xl8(:, 5) = (xl8(:, 1) + xl8(:, 2))/2
    xl8(:, 6) = (xl8(:, 2) + xl8(:, 3))/2
    xl8(:, 7) = (xl8(:, 3) + xl8(:, 4))/2
    xl8(:, 8) = (xl8(:, 4) + xl8(:, 1))/2
    call quadratic_shape_integrals(xl8, w8)
    call check(maxval(abs(w8(1:4) + 6.0_wp/12))/6 <= TOL_EXACT, 'Q8 rectangle: corner shares -A/12')
    call check(maxval(abs(w8(5:8) - 6.0_wp/3))/6 <= TOL_EXACT, 'Q8 rectangle: mid-side shares A/3')
    xl6(:, 1:3) = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.5_wp, 0.4_wp, 1.5_wp], [2, 3])
    xl6(:, 4) = (xl6(:, 1) + xl6(:, 2))/2
    xl6(:, 5) = (xl6(:, 2) + xl6(:, 3))/2
    xl6(:, 6) = (xl6(:, 3) + xl6(:, 1))/2
    area = 0.5_wp*((xl6(1, 2) - xl6(1, 1))*(xl6(2, 3) - xl6(2, 1)) - (xl6(1, 3) - xl6(1, 1))*(xl6(2, 2) - xl6(2, 1)))
    call quadratic_shape_integrals(xl6, w6)
    call check(maxval(abs(w6(1:3)))/area <= TOL_EXACT, 'T6 straight: corner shares 0')
    call check(maxval(abs(w6(4:6) - area/3))/area <= TOL_EXACT, 'T6 straight: mid-side shares A/3')
    call quadratic_shape_integrals(QUAD8, w8)
    call check_rel(sum(w8), boundary_area(QUAD8, 4), TOL_EXACT, 'Q8 curved: shares sum to the area')
    call quadratic_shape_integrals(TRI6, w6)
    call check_rel(sum(w6), boundary_area(TRI6, 3), TOL_EXACT, 'T6 curved: shares sum to the area')
  end subroutine test_area_loads

  pure real(wp) function boundary_area(xl, nc) result(area)
    !! Area inside the closed chain of parabolic sides (corner i, mid-side nc + i,
    !! corner i + 1): ½ ∮ (x dy - y dx), exact by Simpson's rule on each side
    !! (the integrand is a polynomial of degree 2 in the side parameter).
    real(wp), intent(in) :: xl(:, :)
    integer, intent(in) :: nc
    real(wp) :: a(2), m(2), b(2), s, x(2), dx(2)
    real(wp), parameter :: S3(3) = [-1.0_wp, 0.0_wp, 1.0_wp], W(3) = [1.0_wp, 4.0_wp, 1.0_wp]/3
    integer :: i, k
    area = 0.0_wp
    do i = 1, nc
       a = xl(:, i)
       m = xl(:, nc + i)
       b = xl(:, modulo(i, nc) + 1)
       do k = 1, 3
          s = S3(k)
          x = a*s*(s - 1)/2 + m*(1 - s*s) + b*s*(s + 1)/2
          dx = a*(2*s - 1)/2 - 2*m*s + b*(2*s + 1)/2
          area = area + W(k)*(x(1)*dx(2) - x(2)*dx(1))/2
       end do
    end do
  end function boundary_area

  subroutine test_constant_strain()
    !! A linear displacement field on the curved elements: resultants t D ε at the
    !! centroid exactly, plane stress and plane strain, full and reduced integration;
    !! and K u of the field equals the consistent boundary tractions in total
    !! (no net force).
    real(wp), parameter :: EPS(3) = [1.0e-3_wp, -4.0e-4_wp, 6.0e-4_wp]
    real(wp), allocatable :: xl(:, :), ue(:), ke(:, :)
    real(wp) :: nres(3), expect(3), c, f(2)
    type(plane_props_t) :: props
    type(error_t), allocatable :: error
    integer :: k, i
    character(:), allocatable :: what
    allocate (xl(0, 0))   ! (quiets a spurious gfortran -Wuninitialized)
    do k = 1, 4
       if (k == 1) then
          xl = TRI6
       else
          xl = QUAD8
       end if
       props = plane_props_t(t=T, e=E, nu=NU, strain=k == 3, reduced=k == 4)
       what = trim(merge('CPS6 ', 'CPS8 ', k == 1))
       if (k == 3) what = 'CPE8'
       if (k == 4) what = 'CPS8R'
       allocate (ue(2*size(xl, 2)))
       do i = 1, size(xl, 2)
          ue(2*i - 1) = EPS(1)*xl(1, i) + EPS(3)/2*xl(2, i)
          ue(2*i) = EPS(2)*xl(2, i) + EPS(3)/2*xl(1, i)
       end do
       if (props%strain) then
          c = E/((1 + NU)*(1 - 2*NU))
          expect = T*[c*((1 - NU)*EPS(1) + NU*EPS(2)), c*(NU*EPS(1) + (1 - NU)*EPS(2)), E/(2*(1 + NU))*EPS(3)]
       else
          c = E/(1 - NU**2)
          expect = T*[c*(EPS(1) + NU*EPS(2)), c*(NU*EPS(1) + EPS(2)), c*(1 - NU)/2*EPS(3)]
       end if
       call quadratic_resultants(xl, props, ue, nres, error)
       call check(.not. allocated(error), what//': resultants without error')
       call check(maxval(abs(nres - expect)) <= TOL_EXACT*maxval(abs(expect)), what//': constant strain resultants exact')
       call quadratic_stiffness(xl, props, ke, error)
       call check(.not. allocated(error), what//': stiffness without error')
       f = [sum(matmul(ke(1::2, :), ue)), sum(matmul(ke(2::2, :), ue))]
       call check(maxval(abs(f)) <= TOL_EXACT*maxval(abs(matmul(ke, ue))), what//': constant strain, no net force')
       deallocate (ue)
    end do
  end subroutine test_constant_strain

  subroutine test_point_stresses()
    !! quadratic_point_stresses against D ε(x) of an exact displacement field at
    !! every integration point and every node: a linear field (constant stress)
    !! on the curved elements, and a complete quadratic field (linear stress:
    !! bending and more) on a parallelogram and a straight-sided triangle, for
    !! CPS6, CPS8, CPS8R, CPE6, CPE8, CPE8R.
    real(wp), parameter :: PARA8(2, 8) = reshape([ &
         0.0_wp, 0.0_wp, 2.0_wp, 0.4_wp, 2.6_wp, 1.9_wp, 0.6_wp, 1.5_wp, &
         1.0_wp, 0.2_wp, 2.3_wp, 1.15_wp, 1.6_wp, 1.7_wp, 0.3_wp, 0.75_wp], [2, 8])
    real(wp), parameter :: TRI6S(2, 6) = reshape([ &
         0.1_wp, -0.2_wp, 2.0_wp, 0.3_wp, 0.5_wp, 1.6_wp, &
         1.05_wp, 0.05_wp, 1.25_wp, 0.95_wp, 0.3_wp, 0.7_wp], [2, 6])
    real(wp), allocatable :: xl(:, :), ue(:), sp(:, :), sn(:, :), pts(:, :)
    real(wp) :: nf(8), dn(2, 8), xp(2), smax, err
    type(plane_props_t) :: props
    type(error_t), allocatable :: error
    character(len=5), parameter :: NAMES(6) = ['CPS6 ', 'CPS8 ', 'CPS8R', 'CPE6 ', 'CPE8 ', 'CPE8R']
    integer :: etype, field, i, n, nq
    character(:), allocatable :: what
    allocate (xl(0, 0))
    do field = 1, 2
       do etype = 1, 6
          n = merge(6, 8, etype == 1 .or. etype == 4)
          if (field == 1 .and. n == 6) xl = TRI6
          if (field == 1 .and. n == 8) xl = QUAD8
          if (field == 2 .and. n == 6) xl = TRI6S
          if (field == 2 .and. n == 8) xl = PARA8
          nq = merge(2, 6, field == 1)
          props = plane_props_t(t=T, e=E, nu=NU, strain=etype > 3, reduced=etype == 3 .or. etype == 6)
          what = trim(NAMES(etype))// &
               trim(merge(' constant stress', ' linear stress  ', field == 1))
          allocate (ue(2*n))
          do i = 1, n
             ue(2*i - 1) = dot_product(AU(2:nq), monomials(xl(:, i), nq))
             ue(2*i) = dot_product(BV(2:nq), monomials(xl(:, i), nq))
          end do
          call quadratic_point_stresses(xl, props, ue, sp, sn, error)
          call check(.not. allocated(error), what//': stresses without error')
          if (allocated(error)) return
          call quadratic_stress_points(n, props%reduced, pts)
          call check(size(sp, 2) == size(pts, 2), what//': one stress per integration point')
          smax = max(maxval(abs(sp)), tiny(1.0_wp))
          err = 0.0_wp
          do i = 1, size(pts, 2)
             call quadratic_shape(n, pts(:, i), nf(1:n), dn(:, 1:n))
             xp = matmul(xl, nf(1:n))
             err = max(err, maxval(abs(sp(:, i) - exact_stress(xp, props%strain, nq))))
          end do
          call check(err <= TOL_EXACT*smax, what//': exact at the integration points')
          err = 0.0_wp
          do i = 1, n
             err = max(err, maxval(abs(sn(:, i) - exact_stress(xl(:, i), props%strain, nq))))
          end do
          call check(err <= TOL_EXACT*smax, what//': exact at the nodes (extrapolated)')
          if (field == 2) call check(maxval(sn(1, :)) - minval(sn(1, :)) > 0.1_wp*smax, &
               what//': the stress does vary over the element')
          deallocate (ue)
       end do
    end do
  end subroutine test_point_stresses

    pure function monomials(x, nq) result(m)
      !! The non-constant monomials x, y, x², x y, y² of a field with nq terms.
      real(wp), intent(in) :: x(2)
      integer, intent(in) :: nq
      real(wp) :: m(nq - 1)
      real(wp) :: mm(5)
      mm = [x(1), x(2), x(1)**2, x(1)*x(2), x(2)**2]
      m = mm(1:nq - 1)
    end function monomials
    pure function exact_stress(x, strain, nq) result(sig)
      !! D ε of the field at x (closed form derivatives of the monomials).
      real(wp), intent(in) :: x(2)
      logical, intent(in) :: strain
      integer, intent(in) :: nq
      real(wp) :: sig(3), a(6), b(6), ex, ey, gxy, c
      a = 0.0_wp
      b = 0.0_wp
      a(2:nq) = AU(2:nq)
      b(2:nq) = BV(2:nq)
      ex = a(2) + 2*a(4)*x(1) + a(5)*x(2)
      ey = b(3) + b(5)*x(1) + 2*b(6)*x(2)
      gxy = a(3) + a(5)*x(1) + 2*a(6)*x(2) + b(2) + 2*b(4)*x(1) + b(5)*x(2)
      if (strain) then
         c = E/((1 + NU)*(1 - 2*NU))
         sig = [c*((1 - NU)*ex + NU*ey), c*(NU*ex + (1 - NU)*ey), E/(2*(1 + NU))*gxy]
      else
         c = E/(1 - NU**2)
         sig = [c*(ex + NU*ey), c*(NU*ex + ey), c*(1 - NU)/2*gxy]
      end if
    end function exact_stress
end program test_quadratic
