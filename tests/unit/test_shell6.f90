program test_shell6
  !! Unit tests of the six-node triangular thick shell S6 (superjoin_elements_shell8,
  !! through the element facade): exactly six zero-energy modes of one flat
  !! and one curved element in an oblique position, K r = 0 for the rigid
  !! motions; the assumed transverse shear does not lock: as t -> 0 seven
  !! modes (the 15 bending modes less the 8 tying conditions) scale as t^3,
  !! the bending stiffness, where a locking element would have one; the
  !! consistent pressure and self-weight loads (resultant p A, corners 0 and
  !! mid-side nodes A/3 on a flat element); and a distorted S6 refused.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: section_t, material_t, ET_S6, SEC_SHELL, DLOAD_P
  use superjoin_elements, only: element_stiffness, element_distributed_load, element_gravity_load
  use superjoin_elements_frame, only: cross
  use verification_support, only: shell_data
  use superjoin_testing, only: check, check_rel, finish
  use test_lapack, only: eigenvalues
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-12_wp          !! round-off on one element, relative
  real(wp), parameter :: ZERO_EIG = 1.0e-13_wp     !! a zero eigenvalue (round-off), relative to the largest
  real(wp), parameter :: E_MOD = 2.1e5_wp, NU = 0.3_wp
  integer, parameter :: NN = 6, NDOF = 36
  real(wp), parameter :: THIN(2) = [1.0e-3_wp, 1.0e-4_wp]   !! two thicknesses of a unit element
  integer, parameter :: KIRCHHOFF_MODES = 7
  real(wp) :: xf(3, NN), xc(3, NN), rot(3, 3)
  integer :: i

  ! a flat triangle (0,0), (1,0.1), (0.3,0.9) and its mid-side nodes, turned into an oblique plane
  xf(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
  xf(:, 2) = [1.0_wp, 0.1_wp, 0.0_wp]
  xf(:, 3) = [0.3_wp, 0.9_wp, 0.0_wp]
  call mid_sides(xf)
  rot = reshape([2.0_wp, 1.0_wp, 2.0_wp, -2.0_wp, 2.0_wp, 1.0_wp, 1.0_wp, 2.0_wp, -2.0_wp]/3.0_wp, [3, 3])
  xf = matmul(rot, xf)
  ! a curved one: the same triangle on a sphere of radius 2 (z lifted), then turned
  xc(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
  xc(:, 2) = [1.0_wp, 0.1_wp, 0.0_wp]
  xc(:, 3) = [0.3_wp, 0.9_wp, 0.0_wp]
  call mid_sides(xc)
  do i = 1, NN
     xc(3, i) = 2.0_wp - sqrt(4.0_wp - xc(1, i)**2 - xc(2, i)**2)
  end do
  xc = matmul(rot, xc)

  call test_modes(xf, 'flat')
  call test_modes(xc, 'curved')
  call test_no_locking(xf)
  call test_loads(xf)
  call test_distorted()
  call finish()

contains

  subroutine mid_sides(x)
    !! The mid-side nodes 4 (1-2), 5 (2-3), 6 (3-1) at the edges' midpoints.
    real(wp), intent(inout) :: x(3, NN)
    x(:, 4) = (x(:, 1) + x(:, 2))/2
    x(:, 5) = (x(:, 2) + x(:, 3))/2
    x(:, 6) = (x(:, 3) + x(:, 1))/2
  end subroutine mid_sides


  subroutine test_modes(x, tag)
    !! Symmetry, K r = 0 for the rigid motions, exactly six zero eigenvalues
    !! at a thick and a thin section.
    real(wp), intent(in) :: x(3, NN)
    character(*), intent(in) :: tag
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp), allocatable :: ke(:, :), w(:)
    real(wp) :: r(NDOF), omega(3)
    integer :: k, a, it
    do it = 1, 2
       call shell_data(merge(0.2_wp, 0.002_wp, it == 1), E_MOD, NU, sec, mat)
       call element_stiffness(ET_S6, x, sec, mat, ke, error)
       call check(.not. allocated(error), tag//': stiffness')
       if (allocated(error)) return
       call check(maxval(abs(ke - transpose(ke))) <= TOL*maxval(abs(ke)), tag//': symmetric')
       do k = 1, 6   ! three translations, three rotations about the origin
          r = 0.0_wp
          do a = 1, NN
             if (k <= 3) then
                r(6*(a - 1) + k) = 1.0_wp
             else
                omega = 0.0_wp
                omega(k - 3) = 1.0_wp
                r(6*(a - 1) + 1:6*(a - 1) + 3) = [omega(2)*x(3, a) - omega(3)*x(2, a), &
                     omega(3)*x(1, a) - omega(1)*x(3, a), omega(1)*x(2, a) - omega(2)*x(1, a)]
                r(6*(a - 1) + 4:6*(a - 1) + 6) = omega
             end if
          end do
          call check(maxval(abs(matmul(ke, r))) <= 1.0e-10_wp*maxval(abs(ke)), tag//': K r = 0 for a rigid motion')
       end do
       w = eigenvalues(ke)
       call check(count(w < ZERO_EIG*w(NDOF)) == 6, tag//': exactly six zero eigenvalues')
       call check(w(1) > -ZERO_EIG*w(NDOF), tag//': no negative eigenvalue')
    end do
  end subroutine test_modes

  subroutine test_no_locking(x)
    !! At t and t/10 (thin): the 7th..13th eigenvalues scale as t^3 (Kirchhoff
    !! bending modes, ratio 1000 within 1 %) and the 14th as t: the shear
    !! constraints leave the bending modes free.
    real(wp), intent(in) :: x(3, NN)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp), allocatable :: ke(:, :), w1(:), w2(:)
    integer :: k
    call shell_data(THIN(1), E_MOD, NU, sec, mat)
    call element_stiffness(ET_S6, x, sec, mat, ke, error)
    w1 = eigenvalues(ke)
    call shell_data(THIN(2), E_MOD, NU, sec, mat)
    call element_stiffness(ET_S6, x, sec, mat, ke, error)
    w2 = eigenvalues(ke)
    do k = 7, 6 + KIRCHHOFF_MODES
       call check_rel(w1(k)/w2(k), 1000.0_wp, 1.0e-2_wp, 'thin S6: a bending mode scales as t^3')
    end do
    call check_rel(w1(7 + KIRCHHOFF_MODES)/w2(7 + KIRCHHOFF_MODES), 10.0_wp, 1.0e-2_wp, &
         'thin S6: the next mode scales as t (membrane, shear, drilling)')
  end subroutine test_no_locking

  subroutine test_loads(x)
    !! Pressure p on a flat S6 of area A: resultant p A against the normal,
    !! corner shares 0 and mid-side shares A/3; self weight ρ t g A.
    real(wp), intent(in) :: x(3, NN)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp), allocatable :: fe(:)
    real(wp) :: nrm(3), area, q(3), f(3)
    integer :: a
    nrm = cross(x(:, 2) - x(:, 1), x(:, 3) - x(:, 1))
    area = norm2(nrm)/2
    nrm = nrm/norm2(nrm)
    call shell_data(0.01_wp, E_MOD, NU, sec, mat)
    call element_distributed_load(ET_S6, x, sec, DLOAD_P, 3.0_wp, fe, q, error)
    call check(.not. allocated(error), 'S6 pressure loads')
    f = [sum(fe(1::6)), sum(fe(2::6)), sum(fe(3::6))]
    call check(maxval(abs(f + 3.0_wp*area*nrm)) <= TOL*3.0_wp*area, 'S6 pressure: resultant p A against the normal')
    do a = 1, 3
       call check(maxval(abs(fe(6*(a - 1) + 1:6*(a - 1) + 3))) <= TOL*3.0_wp*area, 'S6 pressure: a corner carries 0')
       call check_rel(norm2(fe(6*(a + 2) + 1:6*(a + 2) + 3)), 3.0_wp*area/3, TOL, 'S6 pressure: a mid-side node A/3')
    end do
    mat%density = 7.0_wp
    call element_gravity_load(ET_S6, x, sec, mat, [0.0_wp, 0.0_wp, -9.0_wp], fe, q, error)
    call check_rel(sum(fe(3::6)), -9.0_wp*7.0_wp*0.01_wp*area, TOL, 'S6 self weight: rho t g A')
  end subroutine test_loads

  subroutine test_distorted()
    !! A mid-side node pulled across the opposite corner: refused.
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp), allocatable :: ke(:, :)
    real(wp) :: x(3, NN)
    x = 0.0_wp
    x(1:2, 2) = [1.0_wp, 0.0_wp]
    x(1:2, 3) = [0.0_wp, 1.0_wp]
    call mid_sides(x)
    x(1:2, 4) = [0.5_wp, 1.2_wp]
    call shell_data(0.01_wp, E_MOD, NU, sec, mat)
    call element_stiffness(ET_S6, x, sec, mat, ke, error)
    call check(allocated(error), 'distorted S6 refused')
  end subroutine test_distorted
end program test_shell6
