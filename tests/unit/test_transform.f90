program test_transform
  !! The Δu transform's promise: exact to round-off for every joint stiffness g,
  !! with every backend (every elimination order), and equal to the plain
  !! penalty assembly where that one is still accurate.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: model_t, FORM_TRANSFORM, FORM_PENALTY
  use superjoin_model_results, only: results_t
  use superjoin_testing, only: check, check_rel, finish
  use verification_support, only: solve_text, disp, equilibrium_error
  implicit none (type, external)

  integer, parameter :: NEL = 8                 ! elements per part
  real(wp), parameter :: E = 2.0e11_wp, A = 1.0e-2_wp, I = 1.0e-4_wp, LEN = 4.0_wp, P = -1000.0_wp
  real(wp), parameter :: EI = E*I
  real(wp), parameter :: FACTORS(*) = [1.0_wp, 1.0e4_wp, 1.0e8_wp, 1.0e12_wp, 1.0e14_wp, &
       1.0e16_wp, 1.0e26_wp, 1.0e50_wp, 1.0e100_wp, 1.0e200_wp]
  character(len=7), parameter :: SOLVERS(3) = ['cholmod', 'umfpack', 'lapack ']
  real(wp), parameter :: TOL = 1.0e-10_wp
  integer :: k, s
  real(wp) :: g, v, vp, vt
  character(len=80) :: what

  do s = 1, size(SOLVERS)
     do k = 1, size(FACTORS)
        g = FACTORS(k)*EI/LEN
        v = tip(g, trim(SOLVERS(s)), FORM_TRANSFORM)
        write (what, '(a,a,es8.1)') trim(SOLVERS(s)), ' TRANSFORM g/(EI/L) = ', FACTORS(k)
        call check_rel(v, exact(g), TOL, trim(what))
     end do
     v = tip(-1.0_wp, trim(SOLVERS(s)), FORM_TRANSFORM)
     call check_rel(v, exact(huge(1.0_wp)), TOL, trim(SOLVERS(s))//' TRANSFORM RIGID')
  end do

  ! PENALTY agrees where it has digits to spare.
  do k = 1, 2
     g = FACTORS(k)*EI/LEN
     vp = tip(g, 'cholmod', FORM_PENALTY)
     vt = tip(g, 'cholmod', FORM_TRANSFORM)
     write (what, '(a,es8.1)') 'PENALTY = TRANSFORM at g/(EI/L) = ', FACTORS(k)
     call check_rel(vp, vt, 1.0e-8_wp, trim(what))
  end do
  call soft_joint()
  call zero_joint()
  call finish()

contains

  pure function exact(g) result(v)
    !! v_tip of the two-part cantilever: P L^3/(3EI) + P/g + P a^2/g with a = L/2.
    real(wp), intent(in) :: g
    real(wp) :: v
    v = P*LEN**3/(3*EI)
    if (g < huge(1.0_wp)) v = v + P/g + P*(LEN/2)**2/g
  end function exact

  function tip(g, solver, formulation) result(v)
    !! Solve the two-part cantilever with joint stiffness g on DOFs 1, 2, 6 (g < 0: RIGID).
    real(wp), intent(in) :: g
    character(*), intent(in) :: solver
    integer, intent(in) :: formulation
    real(wp) :: v
    type(model_t) :: m
    type(results_t) :: r
    call solve_text(deck(g), m, r, solver=solver, formulation=formulation)
    v = disp(m, r, 'II', NEL + 1, 2, 1)
    call check(equilibrium_error(r, 1) < 1.0e-9_wp, 'equilibrium '//solver)
  end function tip

  function deck(g) result(text)
    real(wp), intent(in) :: g
    character(:), allocatable :: text
    character(len=64) :: line, gtext
    character, parameter :: nl = new_line('a')
    integer :: j, part
    if (g < 0.0_wp) then
       gtext = 'RIGID'
    else
       write (gtext, '(es25.17e3)') g
    end if
    text = '*MATERIAL, NAME=M'//nl//'*ELASTIC'//nl
    write (line, '(es25.17e3,a)') E, ', 0.3'
    text = text//trim(line)//nl
    do part = 1, 2
       text = text//'*SUBSTRUCTURE, NAME='//merge('I ', 'II', part == 1)//nl//'*NODE'//nl
       do j = 1, NEL + 1
          write (line, '(i0,a,es25.17e3,a)') j, ', ', (part - 1)*LEN/2 + (j - 1)*LEN/2/NEL, ', 0.0'
          text = text//trim(line)//nl
       end do
       text = text//'*ELEMENT, TYPE=B23, ELSET=B'//nl
       do j = 1, NEL
          write (line, '(i0,a,i0,a,i0)') j, ', ', j, ', ', j + 1
          text = text//trim(line)//nl
       end do
       write (line, '(es25.17e3,a,es25.17e3)') A, ', ', I
       text = text//'*BEAM SECTION, ELSET=B, MATERIAL=M'//nl//trim(line)//nl//'*END SUBSTRUCTURE'//nl
    end do
    write (line, '(i0,a)') NEL + 1, ', 1, 1, 2, '
    text = text//'*CONTACT, NAME=J, MASTER=I, SLAVE=II'//nl//trim(line)//' '//trim(adjustl(gtext))//nl
    write (line, '(i0,a)') NEL + 1, ', 1, 6, 6, '
    text = text//trim(line)//' '//trim(adjustl(gtext))//nl
    text = text//'*SUPPORT'//nl//'I.1, 1, 2'//nl//'I.1, 6, 6'//nl
    write (line, '(a,i0,a,es25.17e3)') '*CLOAD'//nl//'II.', NEL + 1, ', 2, ', P
    text = text//trim(line)//nl
  end function deck

  subroutine soft_joint()
    !! A joint 1e6 times softer than the beam is a near-mechanism: the answer
    !! loses digits whatever the formulation, and the health block must say so.
    type(model_t) :: m
    type(results_t) :: r
    real(wp) :: g
    g = 1.0e-6_wp*EI/LEN
    call solve_text(deck(g), m, r)
    call check_rel(disp(m, r, 'II', NEL + 1, 2, 1), exact(g), 1.0e-4_wp, 'soft joint: still close')
    call check(size(r%log%warnings) > 0, 'soft joint: MAXRATIO warning')
    call check(r%summary%maxratio > 1.0e7_wp, 'soft joint: MAXRATIO flags the near-mechanism')
  end subroutine soft_joint

  subroutine zero_joint()
    !! g = 0 on the rotation: the joint is a hinge. Part II (simply supported on
    !! the tip of cantilever I and on a roller) carries P at its middle:
    !! v_mid = v_hinge/2 + P l^3/(48 EI), v_hinge = (P/2) a^3/(3 EI), a = l = L/2.
    type(model_t) :: m
    type(results_t) :: r
    character(:), allocatable :: text
    integer :: at
    real(wp) :: vh
    text = deck(-1.0_wp)
    ! rotation joint 0, add a roller at the tip of II
    at = index(text, ', 1, 6, 6, ')
    text = text(1:at + 10)//' 0'//text(index(text(at:), new_line('a')) + at - 1:)
    at = index(text, '*SUPPORT'//new_line('a'))
    text = text(1:at + 8)//'II.9, 2, 2'//new_line('a')//text(at + 9:)
    text = text(1:index(text, '*CLOAD') - 1)//'*CLOAD'//new_line('a')//'II.5, 2, -1000.0'//new_line('a')
    call solve_text(text, m, r)
    vh = (P/2)*(LEN/2)**3/(3*EI)
    call check_rel(disp(m, r, 'II', 5, 2, 1), vh/2 + P*(LEN/2)**3/(48*EI), TOL, 'hinge (g = 0): mid-span of II')
    call check_rel(disp(m, r, 'I', NEL + 1, 2, 1), vh, TOL, 'hinge (g = 0): hinge deflection')
    call check(equilibrium_error(r, 1) < 1.0e-10_wp, 'hinge equilibrium')
  end subroutine zero_joint
end program test_transform
