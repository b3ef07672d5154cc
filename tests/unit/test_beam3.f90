program test_beam3
  !! Unit tests of the three-node beam B32 (superjoin_elements_beam3): symmetry,
  !! the six rigid-body modes without force, exactly six zero eigenvalues for a
  !! straight and a curved element (no spurious mode of the 2-point rule), the
  !! nodal forces rebuilt from the end forces equal K u, data checks.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t
  use superjoin_elements_beam3, only: beam3_stiffness, beam3_end_forces, beam3_nodal_forces, beam3_load
  use superjoin_elements_frame, only: cross
  use superjoin_testing, only: check, finish
  use test_lapack, only: eigenvalues
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)

  real(wp), parameter :: TOL_EXACT = 1.0e-11_wp    !! relative, exact discrete answers
  real(wp), parameter :: TOL_ZERO_EIG = 1.0e-11_wp !! zero eigenvalue, relative to the largest
  real(wp), parameter :: MIN_POSITIVE = 1.0e-8_wp  !! smallest non-zero eigenvalue / largest, at least
  ! A straight element (oblique in space) and a curved one (middle node off the chord).
  real(wp), parameter :: STRAIGHT(3, 3) = reshape([0.0_wp, 0.0_wp, 0.0_wp, 0.5_wp, 0.3_wp, 0.2_wp, &
       1.0_wp, 0.6_wp, 0.4_wp], [3, 3])
  real(wp), parameter :: CURVED(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.7071_wp, 0.7071_wp, 0.1_wp, &
       0.0_wp, 1.0_wp, 0.3_wp], [3, 3])

  type(section_t) :: sec
  type(material_t) :: mat

  sec%area = 0.02_wp
  sec%iy = 2.0e-4_wp
  sec%iz = 3.0e-4_wp
  sec%j = 1.0e-4_wp
  mat%e = 2.1e5_wp
  mat%nu = 0.3_wp
  call test_element(STRAIGHT, 'straight')
  call test_element(CURVED, 'curved')
  call test_errors()
  call finish()

contains

  subroutine test_element(x, what)
    real(wp), intent(in) :: x(3, 3)
    character(*), intent(in) :: what
    real(wp), allocatable :: ke(:, :), w(:)
    real(wp) :: u(18, 6), kmax, ue(18), f(6, 2), fg(18), ku(18)
    real(wp), allocatable :: fe(:)
    real(wp), parameter :: WLOAD(3) = [0.3_wp, -0.2_wp, 0.5_wp]
    type(error_t), allocatable :: error
    integer :: m, i, nzero

    call beam3_stiffness(x, sec, mat, ke, error)
    call check(.not. allocated(error), what//': stiffness without error')
    if (allocated(error)) return
    kmax = maxval(abs(ke))
    call check(maxval(abs(ke - transpose(ke))) <= 1.0e-15_wp*kmax, what//': symmetric')
    ! rigid modes: translations e_m; rotations θ = e_m with u = θ × x
    u = 0.0_wp
    do m = 1, 3
       do i = 1, 3
          u(6*(i - 1) + m, m) = 1.0_wp
          u(6*(i - 1) + 1:6*(i - 1) + 3, 3 + m) = cross(unit(m), x(:, i))
          u(6*(i - 1) + 3 + m, 3 + m) = 1.0_wp
       end do
    end do
    do m = 1, 6
       call check(maxval(abs(matmul(ke, u(:, m)))) <= TOL_EXACT*kmax*maxval(abs(u(:, m))), &
            what//': rigid mode '//itoa(m)//' has no force')
    end do
    w = eigenvalues(ke)
    nzero = count(abs(w) <= TOL_ZERO_EIG*w(18))
    call check(nzero == 6, what//': exactly 6 zero eigenvalues (got '//itoa(nzero)//')')
    call check(w(7) >= MIN_POSITIVE*w(18), what//': the other eigenvalues clearly positive')
    ! nodal forces from the end forces (middle node by equilibrium) equal K u - f_eq
    ue = [(sin(0.7_wp*i) * 1.0e-3_wp, i=1, 18)]
    call beam3_end_forces(x, sec, mat, ue, WLOAD, f, error)
    call check(.not. allocated(error), what//': end forces without error')
    call beam3_nodal_forces(x, sec, f, WLOAD, fg, error)
    call check(.not. allocated(error), what//': nodal forces without error')
    call beam3_load(x, WLOAD, fe, error)
    ku = matmul(ke, ue) - fe
    call check(maxval(abs(fg - ku)) <= TOL_EXACT*maxval(abs(ku)), what//': nodal forces from end forces equal K u - f_eq')
    ! the consistent load of a uniform w sums to w times the arc length (3-point
    ! Gauss on the parabola: exact for the straight element)
    if (what == 'straight') then
       call check(maxval(abs(fe(1:3) + fe(7:9) + fe(13:15) - WLOAD*norm2(x(:, 3) - x(:, 1)))) <= &
            TOL_EXACT*maxval(abs(WLOAD))*norm2(x(:, 3) - x(:, 1)), what//': load sums to w L')
       call check(maxval(abs(fe(7:9) - 4*fe(1:3))) <= TOL_EXACT*maxval(abs(fe)), what//': shares L/6, 2L/3, L/6')
    end if
  end subroutine test_element

  pure function unit(m) result(e)
    integer, intent(in) :: m
    real(wp) :: e(3)
    e = 0.0_wp
    e(m) = 1.0_wp
  end function unit

  subroutine test_errors()
    !! Coincident nodes, a folded element (middle node beyond an end), nonpositive data.
    real(wp) :: x(3, 3)
    real(wp), allocatable :: ke(:, :)
    type(error_t), allocatable :: error
    type(section_t) :: bad
    x = STRAIGHT
    x(:, 2) = x(:, 1)
    call beam3_stiffness(x, sec, mat, ke, error)
    call check(allocated(error), 'coincident nodes refused')
    if (allocated(error)) call check(index(error%message, 'coincident') > 0 .and. error%code == EXIT_DECK, &
         'coincident nodes: message')
    x = STRAIGHT
    x(:, 2) = [2.0_wp, 1.2_wp, 0.8_wp]      ! beyond node 3: the map folds back
    call beam3_stiffness(x, sec, mat, ke, error)
    call check(allocated(error), 'folded element refused')
    bad = sec
    bad%j = 0.0_wp
    call beam3_stiffness(STRAIGHT, bad, mat, ke, error)
    call check(allocated(error), 'zero J refused')
    if (allocated(error)) call check(index(error%message, 'torsion constant') > 0, 'zero J: message')
  end subroutine test_errors
end program test_beam3
