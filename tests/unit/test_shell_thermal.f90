program test_shell_thermal
  !! Unit tests of the thermal strains interpolated inside shells
  !! (shell_thermal_nodal_load, shell_thermal_nodal_resultants of
  !! superjoin_elements_shell, the nodal remainders of s8r_thermal_load):
  !! equal nodal values give exactly what the uniform path gives (K_e u_free,
  !! the resultants of the free expansion) for S3, S4, S3R, S4R under every
  !! drilling edge mask and for S8R, on distorted elements in a tilted plane;
  !! a field varying over the element gives a self-equilibrated load (forces
  !! and moments about the origin sum to 0), and one that differs from its
  !! mean gives a different load (the interpolation is not the mean) except
  !! on the S3R, whose CST membrane and MITC3 bending have constant strain
  !! rows (its load is the mean's; only its stresses change); on a
  !! rectangle the drilling quadrilateral with every bubble holds the free
  !! expansion of a temperature linear in x and y (quadratic u, v, θz the
  !! field's rotation), so K_e u_free equals the load to round-off (not on a
  !! skewed parallelogram: there the incompatible modes' share of the
  !! quadratic field rotates, which the drilling penalty, blind to the modes,
  !! resists).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: section_t, material_t, ET_S3, ET_S4, ET_S3R, ET_S4R, ET_S8R, SEC_SHELL
  use superjoin_elements_thermal, only: thermal_plate_load, thermal_plate_resultants
  use superjoin_elements_shell, only: shell_thermal_nodal_load, shell_thermal_nodal_resultants, shell_stiffness
  use superjoin_elements_shell8_loads, only: s8r_thermal_load
  use superjoin_elements_frame, only: cross
  use superjoin_testing, only: check, check_close, finish
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-12_wp      !! round-off on one element, relative
  real(wp), parameter :: STRAIN = 1.2e-3_wp, CURVATURE = 0.7e-2_wp
  type(section_t) :: sec
  type(material_t) :: mat
  integer :: m

  mat%e = 2.1e5_wp
  mat%nu = 0.3_wp
  mat%alpha = 1.0e-5_wp
  mat%has_expansion = .true.
  sec%kind = SEC_SHELL
  sec%thickness = 0.05_wp
  call uniform(ET_S3, 3, 15)
  call uniform(ET_S3R, 3, 15)
  do m = 0, 15, 5
     call uniform(ET_S4, 4, m)
     call uniform(ET_S4R, 4, m)
  end do
  call uniform(ET_S4, 4, 3)
  call uniform_s8r()
  do m = 0, 15, 15
     call varying(ET_S4, 4, m)
     call varying(ET_S4R, 4, m)
  end do
  call varying(ET_S3, 3, 15)
  call varying(ET_S3R, 3, 15)
  call varying(ET_S3R, 3, 0)
  call held_field(ET_S4)
  call held_field(ET_S4R)
  call finish()

contains

  function element(n) result(x)
    !! A distorted flat element with n corners in a tilted plane (8: an S8R with straight sides).
    integer, intent(in) :: n
    real(wp), allocatable :: x(:, :)
    real(wp) :: p(2, 4), e1(3), e2(3), o(3)
    integer :: i
    p = reshape([0.0_wp, 0.0_wp, 1.6_wp, 0.3_wp, 1.2_wp, 1.1_wp, 0.1_wp, 0.8_wp], [2, 4])
    if (n == 3) p(:, 3) = [0.5_wp, 0.9_wp]
    e1 = [0.8_wp, 0.6_wp, 0.0_wp]
    e2 = [-0.36_wp, 0.48_wp, 0.8_wp]
    o = [1.0_wp, -2.0_wp, 0.5_wp]
    allocate (x(3, n))
    do i = 1, min(n, 4)
       x(:, i) = o + p(1, i)*e1 + p(2, i)*e2
    end do
    do i = 5, n
       x(:, i) = (x(:, i - 4) + x(:, mod(i - 4, 4) + 1))/2
    end do
  end function element

  subroutine uniform(etype, n, drill)
    !! Equal nodal values: the load and resultants of the uniform path.
    integer, intent(in) :: etype, n, drill
    real(wp), allocatable :: x(:, :), f1(:), f2(:)
    real(wp) :: r1(6), r2(6)
    type(error_t), allocatable :: error
    character(len=40) :: what
    write (what, '(a,i0,a,i0)') 'uniform, type ', etype, ', mask ', drill
    x = element(n)
    call thermal_plate_load(etype, x, sec, mat, STRAIN, CURVATURE, f1, error, drill)
    call check(.not. allocated(error), trim(what)//': uniform load')
    call shell_thermal_nodal_load(etype, x, sec, mat, spread(STRAIN, 1, n), spread(CURVATURE, 1, n), f2, error, drill)
    call check(.not. allocated(error), trim(what)//': nodal load')
    if (allocated(error)) return
    call check_close(maxval(abs(f2 - f1)), 0.0_wp, TOL*maxval(abs(f1)), trim(what)//': load')
    call thermal_plate_resultants(etype, x, sec, mat, STRAIN, CURVATURE, r1, error)
    call shell_thermal_nodal_resultants(etype, x, sec, mat, spread(STRAIN, 1, n), spread(CURVATURE, 1, n), r2, error, &
         drill)
    call check(.not. allocated(error), trim(what)//': nodal resultants')
    call check_close(maxval(abs(r2(1:3) - r1(1:3))), 0.0_wp, TOL*maxval(abs(r1(1:3))), trim(what)//': n')
    call check_close(maxval(abs(r2(4:6) - r1(4:6))), 0.0_wp, TOL*maxval(abs(r1(4:6))), trim(what)//': m')
  end subroutine uniform

  subroutine uniform_s8r()
    !! S8R: the nodal remainders of equal values add to the uniform load as that load again.
    real(wp), allocatable :: x(:, :), f1(:), f2(:)
    type(error_t), allocatable :: error
    allocate (x(3, 8))   ! before the assignment: no -Wuninitialized false positive
    x = element(8)
    call s8r_thermal_load(ET_S8R, x, sec, mat, STRAIN, CURVATURE, f1, error)
    call check(.not. allocated(error), 'S8R uniform load')
    call s8r_thermal_load(ET_S8R, x, sec, mat, 0.0_wp, 0.0_wp, f2, error, spread(STRAIN, 1, 8), spread(CURVATURE, 1, 8))
    call check(.not. allocated(error), 'S8R nodal load')
    if (allocated(error)) return
    call check_close(maxval(abs(f2 - f1)), 0.0_wp, TOL*maxval(abs(f1)), 'S8R: nodal values equal = uniform')
  end subroutine uniform_s8r

  subroutine varying(etype, n, drill)
    !! A field varying over the element: self-equilibrated, and not the mean's load.
    integer, intent(in) :: etype, n, drill
    real(wp), allocatable :: x(:, :), f1(:), f2(:)
    real(wp) :: s(n), k(n), force(3), moment(3)
    type(error_t), allocatable :: error
    integer :: i
    character(len=40) :: what
    write (what, '(a,i0,a,i0)') 'varying, type ', etype, ', mask ', drill
    x = element(n)
    do i = 1, n
       s(i) = STRAIN*(1 + 0.5_wp*i)
       k(i) = CURVATURE*(2 - 0.7_wp*i)
    end do
    call shell_thermal_nodal_load(etype, x, sec, mat, s, k, f2, error, drill)
    call check(.not. allocated(error), trim(what)//': load')
    if (allocated(error)) return
    force = 0.0_wp
    moment = 0.0_wp
    do i = 1, n
       force = force + f2(6*i - 5:6*i - 3)
       moment = moment + f2(6*i - 2:6*i) + cross(x(:, i), f2(6*i - 5:6*i - 3))
    end do
    call check_close(norm2(force), 0.0_wp, TOL*maxval(abs(f2)), trim(what)//': forces sum to 0')
    call check_close(norm2(moment), 0.0_wp, TOL*maxval(abs(f2))*maxval(abs(x)), trim(what)//': moments sum to 0')
    call thermal_plate_load(etype, x, sec, mat, sum(s)/n, sum(k)/n, f1, error, drill)
    if (etype == ET_S3R .and. drill == 0) then
       ! CST and MITC3 have constant strain rows: a linear field loads them as its mean does
       ! (the OPT membrane of flat edges, drill /= 0, has linear higher-order rows)
       call check_close(maxval(abs(f2 - f1)), 0.0_wp, TOL*maxval(abs(f1)), trim(what)//': the mean''s load')
    else
       ! the DKT's curvature rows are linear, the quadrilaterals' bilinear: the load differs
       call check(maxval(abs(f2 - f1)) > 1.0e-5_wp*maxval(abs(f1)), trim(what)//': differs from the mean''s load')
    end if
  end subroutine varying

  subroutine held_field(etype)
    !! A rectangle in the XY plane, T = T0 + a x + b y at its nodes: the
    !! exact free expansion u = α (T0 x + a (x² - y²)/2 + b x y), v = α (T0 y +
    !! b (y² - x²)/2 + a x y), θz = α (a y - b x) at the nodes is in the drilling
    !! quadrilateral's space (bubbles and incompatible modes), so K_e u = f.
    integer, intent(in) :: etype
    real(wp), parameter :: T0 = 20.0_wp, A = 60.0_wp, B = -40.0_wp
    real(wp) :: x(3, 4), u(24), s(4), mean
    real(wp), allocatable :: ke(:, :), f1(:), f2(:), r(:)
    type(error_t), allocatable :: error
    integer :: i
    x = reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.2_wp, 0.0_wp, 0.0_wp, 1.2_wp, 0.9_wp, 0.0_wp, 0.0_wp, 0.9_wp, 0.0_wp], [3, 4])
    u = 0.0_wp
    do i = 1, 4
       associate (px => x(1, i), py => x(2, i))
         s(i) = mat%alpha*(T0 + A*px + B*py)
         u(6*i - 5) = mat%alpha*(T0*px + A*(px**2 - py**2)/2 + B*px*py)
         u(6*i - 4) = mat%alpha*(T0*py + B*(py**2 - px**2)/2 + A*px*py)
         u(6*i) = mat%alpha*(A*py - B*px)
       end associate
    end do
    mean = sum(s)/4
    call shell_stiffness(etype, x, sec, mat, ke, error, 15)
    call thermal_plate_load(etype, x, sec, mat, mean, 0.0_wp, f1, error, 15)
    call shell_thermal_nodal_load(etype, x, sec, mat, s - mean, spread(0.0_wp, 1, 4), f2, error, 15)
    call check(.not. allocated(error), 'held field: load')
    if (allocated(error)) return
    r = matmul(ke, u) - f1 - f2
    call check_close(maxval(abs(r)), 0.0_wp, TOL*maxval(abs(f1 + f2)), &
         'drilling quadrilateral holds the free expansion of a linear temperature: K u = f')
  end subroutine held_field
end program test_shell_thermal
