program test_elements
  !! Unit tests of the truss and beam element library (superjoin_elements).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, SEC_SOLID, SEC_BEAM, SEC_SHELL, &
       ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_B21, ET_B31, ET_CPE3, ET_CPE4
  use superjoin_elements, only: element_node_dofs, element_stiffness, element_end_forces, &
       beam_distributed_load, beam_frame
  use superjoin_testing, only: check, check_close, check_rel, finish
  use test_lapack, only: dsyev, dgesv, eigenvalues
  use superjoin_utils_strings, only: itoa
  use test_random, only: set_seed, rnd, rnd_in
  use superjoin_elements_frame, only: cross
  implicit none (type, external)


  real(wp), parameter :: PI = acos(-1.0_wp)
  real(wp), parameter :: TOL = 1.0e-12_wp          !! round-off, relative
  real(wp), parameter :: TOL_SOLVE = 1.0e-11_wp    !! results of a small linear solve, relative
  real(wp), parameter :: E_MOD = 2.1e5_wp, NU = 0.3_wp
  real(wp), parameter :: AREA = 3.0_wp, IY = 2.0_wp, IZ = 5.0_wp, TJ = 1.5_wp
  real(wp), parameter :: G_MOD = E_MOD/(2*(1 + NU))
  integer, parameter :: NORIENT = 6
  integer, parameter :: LINE_TYPES(6) = [ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_B21, ET_B31]
  character(len=4), parameter :: LINE_NAMES(6) = ['T2D2', 'T3D2', 'B23 ', 'B33 ', 'B21 ', 'B31 ']
  real(wp), parameter :: KSY = 0.6_wp*G_MOD*AREA, KSZ = 0.9_wp*G_MOD*AREA
    !! Transverse shear stiffness of the B31 test section along local y, z
    !! (B21 uses the default G A).
  real(wp), parameter :: EX(3) = [1.0_wp, 0.0_wp, 0.0_wp], EY(3) = [0.0_wp, 1.0_wp, 0.0_wp], &
       EZ(3) = [0.0_wp, 0.0_wp, 1.0_wp]

  type(material_t) :: mat

  mat%name = 'STEEL'
  mat%e = E_MOD
  mat%nu = NU
  mat%has_elastic = .true.

  call set_seed(20240611)
  call test_node_dofs()
  call test_matrix_properties()
  call test_frames()
  call test_errors()
  call test_truss_sign()
  call test_end_forces_are_nodal_forces()
  call test_cantilever_b33()
  call test_cantilever_b23()
  call test_rotation_invariance()
  call test_distributed_fixed_fixed()
  call test_distributed_cantilever()
  call test_distributed_truss()
  call test_timoshenko_cantilever()
  call test_timoshenko_slender_limit()
  call test_timoshenko_errors()
  call finish()

contains

  ! ---------------------------------------------------------------- helpers

  pure function rot_z(a) result(q)
    !! Rotation about Z by angle a.
    real(wp), intent(in) :: a
    real(wp) :: q(3, 3)
    q = reshape([cos(a), sin(a), 0.0_wp, -sin(a), cos(a), 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  end function rot_z

  pure function rot_y(a) result(q)
    !! Rotation about Y by angle a.
    real(wp), intent(in) :: a
    real(wp) :: q(3, 3)
    q = reshape([cos(a), 0.0_wp, -sin(a), 0.0_wp, 1.0_wp, 0.0_wp, sin(a), 0.0_wp, cos(a)], [3, 3])
  end function rot_y

  pure function rot_x(a) result(q)
    !! Rotation about X by angle a.
    real(wp), intent(in) :: a
    real(wp) :: q(3, 3)
    q = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, cos(a), sin(a), 0.0_wp, -sin(a), cos(a)], [3, 3])
  end function rot_x

  function random_rotation(two_d) result(q)
    !! A random rotation (3D) or a random rotation about Z (2D).
    logical, intent(in) :: two_d
    real(wp) :: q(3, 3)
    q = rot_z(rnd_in(-PI, PI))
    if (.not. two_d) q = matmul(q, matmul(rot_y(rnd_in(-PI, PI)), rot_x(rnd_in(-PI, PI))))
  end function random_rotation

  logical function is_2d(etype)
    integer, intent(in) :: etype
    is_2d = etype == ET_T2D2 .or. etype == ET_B23 .or. etype == ET_B21
  end function is_2d

  logical function is_beam(etype)
    integer, intent(in) :: etype
    is_beam = etype == ET_B23 .or. etype == ET_B33 .or. etype == ET_B21 .or. etype == ET_B31
  end function is_beam

  function make_section(etype) result(sec)
    !! Section for an element type (beam data for beams, A for trusses).
    integer, intent(in) :: etype
    type(section_t) :: sec
    sec%area = AREA
    if (is_beam(etype)) then
       sec%kind = SEC_BEAM
       sec%iz = IZ
       if (etype == ET_B33 .or. etype == ET_B31) then
          sec%iy = IY
          sec%j = TJ
       end if
       if (etype == ET_B31) sec%shear_k = [KSY, KSZ]
    else
       sec%kind = SEC_SOLID
    end if
  end function make_section

  subroutine oriented_element(etype, len, q, x, sec)
    !! A random element of length len whose local axes are the columns of q
    !! (for B33 the orientation vector is set so that this holds; 2D: q about Z).
    integer, intent(in) :: etype
    real(wp), intent(in) :: len, q(3, 3)
    real(wp), intent(out) :: x(3, 2)
    type(section_t), intent(out) :: sec
    sec = make_section(etype)
    x(:, 1) = [rnd_in(-10.0_wp, 10.0_wp), rnd_in(-10.0_wp, 10.0_wp), rnd_in(-10.0_wp, 10.0_wp)]
    if (is_2d(etype)) x(3, 1) = 0.0_wp
    x(:, 2) = x(:, 1) + len*q(:, 1)
    if (etype == ET_B33 .or. etype == ET_B31) then
       sec%has_v = .true.
       sec%v = 2.5_wp*q(:, 2) + rnd_in(-3.0_wp, 3.0_wp)*q(:, 1)
    end if
  end subroutine oriented_element

  pure function block_diag(b, nblk) result(t)
    !! Block-diagonal matrix with nblk copies of the 3x3 block b.
    real(wp), intent(in) :: b(3, 3)
    integer, intent(in) :: nblk
    real(wp) :: t(3*nblk, 3*nblk)
    integer :: i
    t = 0.0_wp
    do i = 0, nblk - 1
       t(3*i + 1:3*i + 3, 3*i + 1:3*i + 3) = b
    end do
  end function block_diag

  function dof_rotation(etype, q) result(t)
    !! Rotation acting on the element DOF vector of a type (global -> global).
    integer, intent(in) :: etype
    real(wp), intent(in) :: q(3, 3)
    real(wp), allocatable :: t(:, :)
    select case (etype)
    case (ET_T2D2)
       allocate (t(4, 4), source=0.0_wp)
       t(1:2, 1:2) = q(1:2, 1:2)
       t(3:4, 3:4) = q(1:2, 1:2)
    case (ET_T3D2)
       t = block_diag(q, 2)
    case (ET_B23, ET_B21)
       t = block_diag(q, 2)      ! per node (ux, uy, rz); q is a rotation about Z
    case default
       t = block_diag(q, 4)
    end select
  end function dof_rotation

  function rigid_modes(etype, x) result(u)
    !! Rigid-body displacement fields of an element (columns): translations and
    !! rotations about the element midpoint.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(3, 2)
    real(wp), allocatable :: u(:, :)
    real(wp) :: xc(3), d(3)
    integer :: nd, i, k, o
    xc = 0.5_wp*(x(:, 1) + x(:, 2))
    nd = size(element_node_dofs(etype))
    if (is_2d(etype)) then
       allocate (u(2*nd, 3), source=0.0_wp)
       do i = 1, 2
          o = (i - 1)*nd
          d = x(:, i) - xc
          u(o + 1, 1) = 1.0_wp
          u(o + 2, 2) = 1.0_wp
          u(o + 1, 3) = -d(2)
          u(o + 2, 3) = d(1)
          if (nd == 3) u(o + 3, 3) = 1.0_wp
       end do
    else
       allocate (u(2*nd, 6), source=0.0_wp)
       do i = 1, 2
          o = (i - 1)*nd
          d = x(:, i) - xc
          do k = 1, 3
             u(o + k, k) = 1.0_wp
          end do
          u(o + 1:o + 3, 4) = cross(EX, d)
          u(o + 1:o + 3, 5) = cross(EY, d)
          u(o + 1:o + 3, 6) = cross(EZ, d)
          if (nd == 6) then
             u(o + 4:o + 6, 4) = EX
             u(o + 4:o + 6, 5) = EY
             u(o + 4:o + 6, 6) = EZ
          end if
       end do
    end if
  end function rigid_modes

  function solve(a, b) result(x)
    !! Solve a x = b for a small dense system.
    real(wp), intent(in) :: a(:, :), b(:)
    real(wp), allocatable :: x(:)
    real(wp), allocatable :: m(:, :), y(:, :)
    integer, allocatable :: ipiv(:)
    integer :: n, info
    n = size(a, 1)
    allocate (m, source=a)
    allocate (y(n, 1), ipiv(n))
    y(:, 1) = b
    call dgesv(n, 1, m, n, ipiv, y, n, info)
    call check(info == 0, 'dgesv info')
    x = y(:, 1)
  end function solve

  function stiffness(etype, x, sec, what) result(ke)
    !! Stiffness that must succeed.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    character(*), intent(in) :: what
    real(wp), allocatable :: ke(:, :)
    type(error_t), allocatable :: error
    call element_stiffness(etype, x, sec, mat, ke, error)
    call check(.not. allocated(error), what//': element_stiffness without error')
    if (allocated(error)) then
       write (*, '(a)') '  message: '//error%message
       allocate (ke(0, 0))
    end if
  end function stiffness

  subroutine check_error(error, text, what)
    !! Check that error is allocated with code EXIT_DECK and a message containing text.
    type(error_t), allocatable, intent(in) :: error
    character(*), intent(in) :: text, what
    call check(allocated(error), what//': error reported')
    if (.not. allocated(error)) return
    call check(error%code == EXIT_DECK, what//': code EXIT_DECK')
    call check(index(error%message, text) > 0, what//': message contains "'//text//'"')
    if (index(error%message, text) == 0) write (*, '(a)') '  message: '//error%message
    call check(index(error%message, 'error:') == 0, what//': message without an "error:" prefix')
  end subroutine check_error

  ! ---------------------------------------------------------------- tests

  subroutine test_node_dofs()
    integer, allocatable :: d(:)
    allocate (d(0))   ! (quiets a spurious gfortran -Wuninitialized)
    d = element_node_dofs(ET_T2D2)
    call check(size(d) == 2 .and. all(d == [1, 2]), 'dofs T2D2')
    d = element_node_dofs(ET_T3D2)
    call check(size(d) == 3 .and. all(d == [1, 2, 3]), 'dofs T3D2')
    d = element_node_dofs(ET_B23)
    call check(size(d) == 3 .and. all(d == [1, 2, 6]), 'dofs B23')
    d = element_node_dofs(ET_B33)
    call check(size(d) == 6 .and. all(d == [1, 2, 3, 4, 5, 6]), 'dofs B33')
    d = element_node_dofs(ET_CPS3)
    call check(size(d) == 2 .and. all(d == [1, 2]), 'dofs CPS3')
    d = element_node_dofs(ET_CPS4)
    call check(size(d) == 2 .and. all(d == [1, 2]), 'dofs CPS4')
    d = element_node_dofs(ET_S3)
    call check(size(d) == 6 .and. all(d == [1, 2, 3, 4, 5, 6]), 'dofs S3')
    d = element_node_dofs(ET_S4)
    call check(size(d) == 6 .and. all(d == [1, 2, 3, 4, 5, 6]), 'dofs S4')
    d = element_node_dofs(ET_B21)
    call check(size(d) == 3 .and. all(d == [1, 2, 6]), 'dofs B21')
    d = element_node_dofs(ET_B31)
    call check(size(d) == 6 .and. all(d == [1, 2, 3, 4, 5, 6]), 'dofs B31')
    d = element_node_dofs(ET_CPE3)
    call check(size(d) == 2 .and. all(d == [1, 2]), 'dofs CPE3')
    d = element_node_dofs(ET_CPE4)
    call check(size(d) == 2 .and. all(d == [1, 2]), 'dofs CPE4')
    d = element_node_dofs(0)
    call check(size(d) == 0, 'dofs of an unknown type: none')
  end subroutine test_node_dofs

  subroutine test_matrix_properties()
    !! Symmetry, rigid-body modes, positive semi-definiteness and rank.
    integer, parameter :: RANKS(6) = [1, 1, 3, 6, 3, 6]
    real(wp) :: x(3, 2), q(3, 3), kmax, umax
    real(wp), allocatable :: ke(:, :), u(:, :), w(:), ku(:)
    type(section_t) :: sec
    integer :: it, io, etype, nd, m, nrank
    character(:), allocatable :: what

    allocate (ke(0, 0))   ! defined bounds before the first reallocation (gfortran -Wuninitialized)
    do it = 1, size(LINE_TYPES)
       etype = LINE_TYPES(it)
       nd = size(element_node_dofs(etype))
       do io = 1, NORIENT
          what = trim(LINE_NAMES(it))//' orientation '//itoa(io)
          q = random_rotation(is_2d(etype))
          call oriented_element(etype, rnd_in(0.5_wp, 5.0_wp), q, x, sec)
          if (io == NORIENT) sec%has_v = .false.     ! default orientation too
          ke = stiffness(etype, x, sec, what)
          if (size(ke, 1) /= 2*nd) then
             call check(.false., what//': size of ke')
             cycle
          end if
          call check(size(ke, 2) == 2*nd, what//': ke square')
          kmax = maxval(abs(ke))
          call check(maxval(abs(ke - transpose(ke))) <= TOL*kmax, what//': ke symmetric')

          u = rigid_modes(etype, x)
          do m = 1, size(u, 2)
             ku = matmul(ke, u(:, m))
             umax = maxval(abs(u(:, m)))
             call check(maxval(abs(ku)) <= TOL*kmax*umax, what//': rigid mode '//itoa(m)//' has no force')
          end do

          w = eigenvalues(ke)
          call check(w(1) >= -TOL*w(2*nd), what//': positive semi-definite')
          nrank = count(w > 1.0e-9_wp*w(2*nd))
          call check(nrank == RANKS(it), what//': rank '//itoa(RANKS(it))//' (got '//itoa(nrank)//')')
          call check(count(abs(w) <= TOL*w(2*nd)*10) == 2*nd - RANKS(it), what//': null space at round-off')
       end do
    end do
  end subroutine test_matrix_properties

  subroutine test_frames()
    !! The local frame rule of deck.md.
    real(wp) :: x(3, 2), r(3, 3), length, q(3, 3), s2
    type(section_t) :: sec
    type(error_t), allocatable :: error
    integer :: io, it, etype

    sec = make_section(ET_B33)
    x(:, 1) = [1.0_wp, 2.0_wp, 3.0_wp]

    ! Default v = global Z.
    x(:, 2) = x(:, 1) + 4.0_wp*EX
    call beam_frame(ET_B33, x, sec, r, length, error)
    call check(.not. allocated(error), 'frame along X: no error')
    call check_close(length, 4.0_wp, TOL*4, 'frame along X: length')
    call check(maxval(abs(r(1, :) - EX)) <= TOL .and. maxval(abs(r(2, :) - EZ)) <= TOL .and. &
         maxval(abs(r(3, :) + EY)) <= TOL, 'frame along X, default v: y = Z, z = -Y')
    x(:, 2) = x(:, 1) + 2.0_wp*EY
    call beam_frame(ET_B33, x, sec, r, length, error)
    call check(maxval(abs(r(1, :) - EY)) <= TOL .and. maxval(abs(r(2, :) - EZ)) <= TOL .and. &
         maxval(abs(r(3, :) - EX)) <= TOL, 'frame along Y, default v: y = Z, z = X')

    ! Parallel to Z: v = global X.
    x(:, 2) = x(:, 1) + 3.0_wp*EZ
    call beam_frame(ET_B33, x, sec, r, length, error)
    call check(.not. allocated(error), 'frame along Z: no error')
    call check(maxval(abs(r(1, :) - EZ)) <= TOL .and. maxval(abs(r(2, :) - EX)) <= TOL .and. &
         maxval(abs(r(3, :) - EY)) <= TOL, 'frame along Z, default v: y = X, z = Y')
    x(:, 2) = x(:, 1) - 3.0_wp*EZ
    call beam_frame(ET_B33, x, sec, r, length, error)
    call check(maxval(abs(r(1, :) + EZ)) <= TOL .and. maxval(abs(r(2, :) - EX)) <= TOL .and. &
         maxval(abs(r(3, :) + EY)) <= TOL, 'frame along -Z, default v: y = X, z = -Y')
    ! A column off vertical by round-off still takes v = X.
    x(:, 2) = x(:, 1) + 3.0_wp*EZ + [1.0e-12_wp, -2.0e-12_wp, 0.0_wp]
    call beam_frame(ET_B33, x, sec, r, length, error)
    call check(.not. allocated(error), 'frame nearly along Z: no error')
    call check(maxval(abs(r(2, :) - EX)) <= 1.0e-11_wp, 'frame nearly along Z: y = X')
    ! A T3D2 bar uses the default rule and ignores v.
    sec%has_v = .true.
    sec%v = EZ
    call beam_frame(ET_T3D2, x, sec, r, length, error)
    call check(.not. allocated(error), 'T3D2 frame ignores v parallel to the bar')

    ! User v.
    x(:, 2) = x(:, 1) + 4.0_wp*EX
    sec%v = [0.0_wp, 1.0_wp, 1.0_wp]
    call beam_frame(ET_B33, x, sec, r, length, error)
    s2 = sqrt(0.5_wp)
    call check(.not. allocated(error), 'frame user v: no error')
    call check(maxval(abs(r(2, :) - [0.0_wp, s2, s2])) <= TOL .and. &
         maxval(abs(r(3, :) - [0.0_wp, -s2, s2])) <= TOL, 'frame user v = (0,1,1) along X')
    ! v given along Z on a beam along Z is an error, even though it is the default value.
    x(:, 2) = x(:, 1) + 3.0_wp*EZ
    sec%v = EZ
    call beam_frame(ET_B33, x, sec, r, length, error)
    call check_error(error, 'orientation vector parallel to beam axis', 'frame user v = Z along Z')

    ! Random orientations with v: r = transpose(q); orthonormal and right-handed.
    do io = 1, NORIENT
       q = random_rotation(.false.)
       call oriented_element(ET_B33, rnd_in(0.5_wp, 5.0_wp), q, x, sec)
       call beam_frame(ET_B33, x, sec, r, length, error)
       call check(.not. allocated(error), 'random frame '//itoa(io)//': no error')
       call check(maxval(abs(r - transpose(q))) <= 1.0e-13_wp, 'random frame '//itoa(io)//' from v')
       sec%has_v = .false.
       call beam_frame(ET_B33, x, sec, r, length, error)
       call check(maxval(abs(matmul(r, transpose(r)) - identity3())) <= 1.0e-14_wp, &
            'default frame '//itoa(io)//' orthonormal')
       call check(abs(det3(r) - 1) <= 1.0e-14_wp, 'default frame '//itoa(io)//' right-handed')
       call check(abs(dot_product(r(3, :), EZ)) <= 1.0e-14_wp .and. dot_product(r(2, :), EZ) > 0, &
            'default frame '//itoa(io)//': y in the plane of x and Z, toward Z')
    end do

    ! 2D elements: x in the XY plane, z = Z, y = z × x; v is ignored.
    do it = 1, 2
       etype = ET_T2D2
       if (it == 2) etype = ET_B23
       sec = make_section(etype)
       sec%has_v = .true.
       sec%v = [1.0_wp, 1.0_wp, 0.0_wp]
       x(:, 1) = [1.0_wp, 1.0_wp, 0.0_wp]
       x(:, 2) = x(:, 1) + [-3.0_wp, 4.0_wp, 0.0_wp]
       call beam_frame(etype, x, sec, r, length, error)
       call check(.not. allocated(error), '2D frame: no error')
       call check_close(length, 5.0_wp, TOL*5, '2D frame: length')
       call check(maxval(abs(r(1, :) - [-0.6_wp, 0.8_wp, 0.0_wp])) <= TOL .and. &
            maxval(abs(r(2, :) - [-0.8_wp, -0.6_wp, 0.0_wp])) <= TOL .and. &
            maxval(abs(r(3, :) - EZ)) <= TOL, '2D frame rule '//itoa(it))
    end do
  end subroutine test_frames

  function identity3() result(a)
    real(wp) :: a(3, 3)
    integer :: i
    a = 0.0_wp
    do i = 1, 3
       a(i, i) = 1.0_wp
    end do
  end function identity3

  real(wp) function det3(a)
    real(wp), intent(in) :: a(3, 3)
    det3 = dot_product(a(:, 1), cross(a(:, 2), a(:, 3)))
  end function det3

  subroutine test_errors()
    !! Data errors.
    real(wp) :: x(3, 2), r(3, 3), length, f(6, 2), ql(3)
    real(wp), allocatable :: ke(:, :), fe(:), ue(:)
    type(section_t) :: sec
    type(material_t) :: bad
    type(error_t), allocatable :: error
    integer :: it, etype, nd
    character(:), allocatable :: name

    do it = 1, size(LINE_TYPES)
       etype = LINE_TYPES(it)
       name = trim(LINE_NAMES(it))
       nd = size(element_node_dofs(etype))
       sec = make_section(etype)
       allocate (ue(2*nd), source=0.0_wp)

       x(:, 1) = [1.0_wp, 2.0_wp, 0.0_wp]
       x(:, 2) = x(:, 1)
       call element_stiffness(etype, x, sec, mat, ke, error)
       call check_error(error, 'zero-length element', name//' coincident nodes')
       call element_end_forces(etype, x, sec, mat, ue, [0.0_wp, 0.0_wp, 0.0_wp], f, error)
       call check_error(error, 'zero-length element', name//' end forces, coincident nodes')
       call beam_distributed_load(etype, x, sec, [0.0_wp, 1.0_wp, 0.0_wp], fe, ql, error)
       call check_error(error, 'zero-length element', name//' distributed load, coincident nodes')
       x = 0.0_wp
       call element_stiffness(etype, x, sec, mat, ke, error)
       call check_error(error, 'zero-length element', name//' both nodes at the origin')
       ! Length at round-off of the coordinates: zero; small but real: fine.
       x(:, 1) = [1.0e3_wp, 0.0_wp, 0.0_wp]
       x(:, 2) = [1.0e3_wp, 2.0e-13_wp, 0.0_wp]
       call element_stiffness(etype, x, sec, mat, ke, error)
       call check_error(error, 'zero-length element', name//' length at round-off')
       x(:, 1) = [1.0_wp, 0.0_wp, 0.0_wp]
       x(:, 2) = [1.0_wp, 1.0e-9_wp, 0.0_wp]
       call element_stiffness(etype, x, sec, mat, ke, error)
       call check(.not. allocated(error), name//' short element is no error')

       x(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
       x(:, 2) = [2.0_wp, 1.0_wp, 0.0_wp]
       sec%area = 0.0_wp
       call element_stiffness(etype, x, sec, mat, ke, error)
       call check_error(error, 'nonpositive cross-section area', name//' A = 0')
       sec%area = -1.0_wp
       call element_stiffness(etype, x, sec, mat, ke, error)
       call check_error(error, 'nonpositive cross-section area', name//' A < 0')
       sec = make_section(etype)
       bad = mat
       bad%e = 0.0_wp
       call element_stiffness(etype, x, sec, bad, ke, error)
       call check_error(error, 'nonpositive Young''s modulus', name//' E = 0')
       bad%e = -2.0e5_wp
       call element_stiffness(etype, x, sec, bad, ke, error)
       call check_error(error, 'nonpositive Young''s modulus', name//' E < 0')
       call element_end_forces(etype, x, sec, bad, ue, [0.0_wp, 0.0_wp, 0.0_wp], f, error)
       call check_error(error, 'nonpositive Young''s modulus', name//' end forces, E < 0')
       deallocate (ue)
    end do

    x(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
    x(:, 2) = [2.0_wp, 1.0_wp, 0.0_wp]
    sec = make_section(ET_B23)
    sec%iz = 0.0_wp
    call element_stiffness(ET_B23, x, sec, mat, ke, error)
    call check_error(error, 'nonpositive moment of inertia', 'B23 I = 0')
    sec = make_section(ET_B33)
    sec%iy = -1.0_wp
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check_error(error, 'nonpositive moment of inertia Iy', 'B33 Iy < 0')
    sec = make_section(ET_B33)
    sec%iz = 0.0_wp
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check_error(error, 'nonpositive moment of inertia Iz', 'B33 Iz = 0')
    sec = make_section(ET_B33)
    sec%j = 0.0_wp
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check_error(error, 'nonpositive torsion constant J', 'B33 J = 0')
    ! A truss needs no I or J.
    sec = make_section(ET_T3D2)
    call element_stiffness(ET_T3D2, x, sec, mat, ke, error)
    call check(.not. allocated(error), 'T3D2 without I and J: no error')

    ! Orientation vector parallel to the axis (any sign, any length, to 1e-10).
    sec = make_section(ET_B33)
    sec%has_v = .true.
    x(:, 1) = [1.0_wp, 1.0_wp, 1.0_wp]
    x(:, 2) = [3.0_wp, 3.0_wp, 3.0_wp]
    sec%v = [-2.0_wp, -2.0_wp, -2.0_wp]
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check_error(error, 'orientation vector parallel to beam axis', 'B33 v = -axis')
    sec%v = [5.0_wp, 5.0_wp, 5.0_wp*(1 + 1.0e-12_wp)]
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check_error(error, 'orientation vector parallel to beam axis', 'B33 v within 1e-12 of the axis')
    call beam_distributed_load(ET_B33, x, sec, [0.0_wp, 0.0_wp, -1.0_wp], fe, ql, error)
    call check_error(error, 'orientation vector parallel to beam axis', 'B33 distributed load, v parallel')
    sec%v = [5.0_wp, 5.0_wp, 5.0_wp*(1 + 1.0e-6_wp)]
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check(.not. allocated(error), 'B33 v 1e-6 off the axis: no error')
    sec%v = 0.0_wp
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check_error(error, 'orientation vector', 'B33 v = 0')
    call beam_frame(ET_B33, x, sec, r, length, error)
    call check_error(error, 'orientation vector', 'beam_frame with v = 0')

    ! 2D elements must lie in the XY plane.
    x(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
    x(:, 2) = [1.0_wp, 1.0_wp, 0.5_wp]
    call element_stiffness(ET_B23, x, make_section(ET_B23), mat, ke, error)
    call check_error(error, 'XY plane', 'B23 out of plane')
    call element_stiffness(ET_T2D2, x, make_section(ET_T2D2), mat, ke, error)
    call check_error(error, 'XY plane', 'T2D2 out of plane')
    x(3, :) = 7.0_wp
    call element_stiffness(ET_T2D2, x, make_section(ET_T2D2), mat, ke, error)
    call check(.not. allocated(error), 'T2D2 in a plane z = const: no error')
    x(3, :) = 0.0_wp
    call beam_distributed_load(ET_B23, x, make_section(ET_B23), [0.0_wp, 0.0_wp, 1.0_wp], fe, ql, error)
    call check_error(error, 'global Z', 'B23 load along Z')
    call beam_distributed_load(ET_T2D2, x, make_section(ET_T2D2), [0.0_wp, 0.0_wp, 1.0_wp], fe, ql, error)
    call check_error(error, 'global Z', 'T2D2 load along Z')

    ! Plane and shell elements: degenerate and misplaced elements are refused.
    sec%kind = SEC_SOLID
    sec%thickness = 1.0_wp
    call element_stiffness(ET_CPS3, reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, &
         2.0_wp, 0.0_wp, 0.0_wp], [3, 3]), sec, mat, ke, error)
    call check_error(error, 'zero area', 'CPS3 collinear')
    call element_stiffness(ET_CPS4, reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, &
         1.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], [3, 4]), sec, mat, ke, error)
    call check_error(error, 'XY plane', 'CPS4 out of plane')
    sec%kind = SEC_SHELL
    call element_stiffness(ET_S3, reshape([0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
         0.0_wp, 1.0_wp, 0.0_wp], [3, 3]), sec, mat, ke, error)
    call check_error(error, 'zero area', 'S3 coincident nodes')
    call element_stiffness(ET_S4, reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, &
         1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], [3, 4]), sec, mat, ke, error)
    call check_error(error, 'zero area', 'S4 collapsed')
    call element_stiffness(99, x, sec, mat, ke, error)
    call check_error(error, 'unknown element type 99', 'unknown type')
  end subroutine test_errors

  subroutine test_truss_sign()
    !! A bar in tension has n < 0 at end 1 and n > 0 at end 2 (any orientation,
    !! plus an arbitrary rigid translation).
    real(wp) :: x(3, 2), q(3, 3), len, delta, f(6, 2), t(3)
    real(wp), allocatable :: ue(:)
    type(section_t) :: sec
    type(error_t), allocatable :: error
    integer :: it, io, etype, nd
    character(:), allocatable :: what

    do it = 1, size(LINE_TYPES)
       etype = LINE_TYPES(it)
       nd = size(element_node_dofs(etype))
       do io = 1, NORIENT
          what = trim(LINE_NAMES(it))//' tension '//itoa(io)
          q = random_rotation(is_2d(etype))
          len = rnd_in(0.5_wp, 5.0_wp)
          call oriented_element(etype, len, q, x, sec)
          delta = rnd_in(1.0e-3_wp, 1.0e-2_wp)
          t = [rnd(), rnd(), rnd()]
          if (is_2d(etype)) t(3) = 0.0_wp
          allocate (ue(2*nd), source=0.0_wp)
          ue(1:min(nd, 3)) = t(1:min(nd, 3))
          ue(nd + 1:nd + min(nd, 3)) = t(1:min(nd, 3)) + delta*q(1:min(nd, 3), 1)
          call element_end_forces(etype, x, sec, mat, ue, [0.0_wp, 0.0_wp, 0.0_wp], f, error)
          call check(.not. allocated(error), what//': no error')
          call check(f(1, 1) < 0 .and. f(1, 2) > 0, what//': n < 0 at end 1, n > 0 at end 2')
          call check_rel(f(1, 2), E_MOD*AREA*delta/len, TOL*10, what//': n = EA delta / L')
          call check_rel(f(1, 1), -E_MOD*AREA*delta/len, TOL*10, what//': n1 = -n2')
          call check(maxval(abs(f(2:6, :))) <= TOL*10*abs(f(1, 2)), what//': only n')
          ! Compression flips the signs.
          ue = -ue
          call element_end_forces(etype, x, sec, mat, ue, [0.0_wp, 0.0_wp, 0.0_wp], f, error)
          call check(f(1, 1) > 0 .and. f(1, 2) < 0, what//': compression n > 0 at end 1')
          deallocate (ue)
       end do
    end do
  end subroutine test_truss_sign

  subroutine test_end_forces_are_nodal_forces()
    !! End forces are the nodal forces k u rotated to local axes (no load).
    real(wp) :: x(3, 2), q(3, 3), f(6, 2), r(3, 3), length, fl(6, 2), fmax
    real(wp), allocatable :: ke(:, :), ue(:), ku(:)
    type(section_t) :: sec
    type(error_t), allocatable :: error
    integer :: it, io, etype, nd, i, k
    character(:), allocatable :: what

    do it = 1, size(LINE_TYPES)
       etype = LINE_TYPES(it)
       nd = size(element_node_dofs(etype))
       do io = 1, NORIENT
          what = trim(LINE_NAMES(it))//' end forces = local k u '//itoa(io)
          q = random_rotation(is_2d(etype))
          call oriented_element(etype, rnd_in(0.5_wp, 5.0_wp), q, x, sec)
          ke = stiffness(etype, x, sec, what)
          allocate (ue(2*nd))
          do i = 1, 2*nd
             ue(i) = rnd_in(-1.0e-3_wp, 1.0e-3_wp)
          end do
          ku = matmul(ke, ue)
          call beam_frame(etype, x, sec, r, length, error)
          fl = 0.0_wp
          do k = 1, 2
             select case (nd)
             case (2)
                fl(1, k) = dot_product(r(1, 1:2), ku((k - 1)*nd + 1:(k - 1)*nd + 2))
             case (3)
                if (etype == ET_B23 .or. etype == ET_B21) then
                   fl([1, 2], k) = matmul(r(1:2, 1:2), ku((k - 1)*nd + 1:(k - 1)*nd + 2))
                   fl(6, k) = ku(k*nd)
                else
                   fl(1, k) = dot_product(r(1, :), ku((k - 1)*nd + 1:k*nd))
                end if
             case (6)
                fl(1:3, k) = matmul(r, ku((k - 1)*nd + 1:(k - 1)*nd + 3))
                fl(4:6, k) = matmul(r, ku((k - 1)*nd + 4:k*nd))
             end select
          end do
          call element_end_forces(etype, x, sec, mat, ue, [0.0_wp, 0.0_wp, 0.0_wp], f, error)
          call check(.not. allocated(error), what//': no error')
          fmax = maxval(abs(ke))*maxval(abs(ue))
          call check(maxval(abs(f - fl)) <= TOL*10*fmax, what)
          ! Trusses: the nodal force is along the bar.
          if (.not. is_beam(etype)) then
             do k = 1, 2
                call check(maxval(abs(ku((k - 1)*nd + 1:k*nd) - fl(1, k)*r(1, 1:nd))) <= TOL*10*fmax, &
                     what//': truss force along the bar')
             end do
          end if
          deallocate (ue)
       end do
    end do
  end subroutine test_end_forces_are_nodal_forces

  subroutine cantilever_tip(etype, x, sec, q, load_local, tip, f)
    !! Tip displacements of one B33 cantilever (node 1 clamped) under tip loads in
    !! local axes; exact for Hermite cubics. Returns local tip translations and rotations.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(3, 2), q(3, 3), load_local(:)
    type(section_t), intent(in) :: sec
    real(wp), intent(out) :: tip(:), f(6, 2)
    real(wp), allocatable :: ke(:, :), u2(:), fg(:), ue(:)
    type(error_t), allocatable :: error
    integer :: nd
    nd = size(element_node_dofs(etype))
    allocate (ke(0, 0))   ! (quiets a spurious gfortran -Wuninitialized)
    ke = stiffness(etype, x, sec, 'cantilever')
    allocate (fg(nd))
    if (nd == 6) then
       fg(1:3) = matmul(q, load_local(1:3))
       fg(4:6) = matmul(q, load_local(4:6))
    else   ! B23: (fx, fy, mz) local; q rotation about Z
       fg(1:2) = matmul(q(1:2, 1:2), load_local(1:2))
       fg(3) = load_local(3)
    end if
    u2 = solve(ke(nd + 1:2*nd, nd + 1:2*nd), fg)
    if (nd == 6) then
       tip(1:3) = matmul(transpose(q), u2(1:3))
       tip(4:6) = matmul(transpose(q), u2(4:6))
    else
       tip(1:2) = matmul(transpose(q(1:2, 1:2)), u2(1:2))
       tip(3) = u2(3)
    end if
    allocate (ue(2*nd), source=0.0_wp)
    ue(nd + 1:) = u2
    call element_end_forces(etype, x, sec, mat, ue, [0.0_wp, 0.0_wp, 0.0_wp], f, error)
    call check(.not. allocated(error), 'cantilever end forces: no error')
  end subroutine cantilever_tip

  subroutine check_tip(tip, want, what)
    !! Compare a local tip vector against the exact values (relative to the largest).
    real(wp), intent(in) :: tip(:), want(:)
    character(*), intent(in) :: what
    call check(maxval(abs(tip - want)) <= TOL_SOLVE*maxval(abs(want)), what)
    if (maxval(abs(tip - want)) > TOL_SOLVE*maxval(abs(want))) then
       write (*, '(a,6es12.4)') '  got  ', tip
       write (*, '(a,6es12.4)') '  want ', want
    end if
  end subroutine check_tip

  subroutine check_forces(f, want, what)
    real(wp), intent(in) :: f(6, 2), want(6, 2)
    character(*), intent(in) :: what
    call check(maxval(abs(f - want)) <= TOL_SOLVE*maxval(abs(want)), what)
    if (maxval(abs(f - want)) > TOL_SOLVE*maxval(abs(want))) then
       write (*, '(a,12es11.3)') '  got  ', f
       write (*, '(a,12es11.3)') '  want ', want
    end if
  end subroutine check_forces

  subroutine test_cantilever_b33()
    real(wp) :: x(3, 2), q(3, 3), len, p, tip(6), f(6, 2), want(6, 2)
    type(section_t) :: sec
    integer :: io
    character(:), allocatable :: what

    do io = 1, NORIENT
       what = 'B33 cantilever '//itoa(io)
       q = random_rotation(.false.)
       len = rnd_in(1.0_wp, 4.0_wp)
       p = rnd_in(10.0_wp, 100.0_wp)
       call oriented_element(ET_B33, len, q, x, sec)

       call cantilever_tip(ET_B33, x, sec, q, [0.0_wp, p, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, p*len**3/(3*E_MOD*IZ), 0.0_wp, 0.0_wp, 0.0_wp, &
            p*len**2/(2*E_MOD*IZ)], what//': P along y: PL^3/(3EIz), PL^2/(2EIz)')
       want = 0.0_wp
       want(2, :) = [-p, p]
       want(6, 1) = -p*len
       call check_forces(f, want, what//': P along y: end forces')

       call cantilever_tip(ET_B33, x, sec, q, [0.0_wp, 0.0_wp, p, 0.0_wp, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, 0.0_wp, p*len**3/(3*E_MOD*IY), 0.0_wp, -p*len**2/(2*E_MOD*IY), &
            0.0_wp], what//': P along z: PL^3/(3EIy), -PL^2/(2EIy)')
       want = 0.0_wp
       want(3, :) = [-p, p]
       want(5, 1) = p*len
       call check_forces(f, want, what//': P along z: end forces')

       call cantilever_tip(ET_B33, x, sec, q, [p, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [p*len/(E_MOD*AREA), 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
            what//': axial PL/(EA)')
       want = 0.0_wp
       want(1, :) = [-p, p]
       call check_forces(f, want, what//': axial end forces (tension)')

       call cantilever_tip(ET_B33, x, sec, q, [0.0_wp, 0.0_wp, 0.0_wp, p, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, 0.0_wp, 0.0_wp, p*len/(G_MOD*TJ), 0.0_wp, 0.0_wp], &
            what//': torsion TL/(GJ)')
       want = 0.0_wp
       want(4, :) = [-p, p]
       call check_forces(f, want, what//': torsion end forces')

       call cantilever_tip(ET_B33, x, sec, q, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, p], tip, f)
       call check_tip(tip, [0.0_wp, p*len**2/(2*E_MOD*IZ), 0.0_wp, 0.0_wp, 0.0_wp, p*len/(E_MOD*IZ)], &
            what//': moment about z: ML^2/(2EIz), ML/(EIz)')
       want = 0.0_wp
       want(6, :) = [-p, p]
       call check_forces(f, want, what//': moment about z: end forces')

       call cantilever_tip(ET_B33, x, sec, q, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, p, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, 0.0_wp, -p*len**2/(2*E_MOD*IY), 0.0_wp, p*len/(E_MOD*IY), 0.0_wp], &
            what//': moment about y: -ML^2/(2EIy), ML/(EIy)')
       want = 0.0_wp
       want(5, :) = [-p, p]
       call check_forces(f, want, what//': moment about y: end forces')
    end do
  end subroutine test_cantilever_b33

  subroutine test_cantilever_b23()
    real(wp) :: x(3, 2), q(3, 3), len, p, tip(3), f(6, 2), want(6, 2)
    type(section_t) :: sec
    integer :: io
    character(:), allocatable :: what

    do io = 1, NORIENT
       what = 'B23 cantilever '//itoa(io)
       q = random_rotation(.true.)
       len = rnd_in(1.0_wp, 4.0_wp)
       p = rnd_in(10.0_wp, 100.0_wp)
       call oriented_element(ET_B23, len, q, x, sec)

       call cantilever_tip(ET_B23, x, sec, q, [0.0_wp, p, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, p*len**3/(3*E_MOD*IZ), p*len**2/(2*E_MOD*IZ)], &
            what//': P along y: PL^3/(3EI), PL^2/(2EI)')
       want = 0.0_wp
       want(2, :) = [-p, p]
       want(6, 1) = -p*len
       call check_forces(f, want, what//': P along y: end forces')

       call cantilever_tip(ET_B23, x, sec, q, [p, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [p*len/(E_MOD*AREA), 0.0_wp, 0.0_wp], what//': axial PL/(EA)')
       want = 0.0_wp
       want(1, :) = [-p, p]
       call check_forces(f, want, what//': axial end forces')

       call cantilever_tip(ET_B23, x, sec, q, [0.0_wp, 0.0_wp, p], tip, f)
       call check_tip(tip, [0.0_wp, p*len**2/(2*E_MOD*IZ), p*len/(E_MOD*IZ)], &
            what//': moment: ML^2/(2EI), ML/(EI)')
    end do
  end subroutine test_cantilever_b23

  subroutine test_rotation_invariance()
    !! Rotating an element (with its orientation vector) and its load rotates
    !! the stiffness, the nodal loads and the solution.
    real(wp) :: x(3, 2), xr(3, 2), q(3, 3), qb(3, 3), w(3), ql(3), qlr(3)
    real(wp), allocatable :: ke(:, :), ker(:, :), t(:, :), fe(:), fer(:), fg(:), u(:), ur(:)
    type(section_t) :: sec, secr
    type(error_t), allocatable :: error
    integer :: it, io, etype, nd
    character(:), allocatable :: what

    allocate (ke(0, 0), ker(0, 0), t(0, 0))   ! (quiets a spurious gfortran -Wuninitialized)
    do it = 1, size(LINE_TYPES)
       etype = LINE_TYPES(it)
       nd = size(element_node_dofs(etype))
       do io = 1, NORIENT
          what = trim(LINE_NAMES(it))//' rotated '//itoa(io)
          qb = random_rotation(is_2d(etype))
          call oriented_element(etype, rnd_in(0.5_wp, 5.0_wp), qb, x, sec)
          q = random_rotation(is_2d(etype))
          xr = matmul(q, x)
          secr = sec
          secr%v = matmul(q, sec%v)
          ke = stiffness(etype, x, sec, what)
          ker = stiffness(etype, xr, secr, what)
          t = dof_rotation(etype, q)
          call check(maxval(abs(ker - matmul(t, matmul(ke, transpose(t))))) <= TOL*maxval(abs(ke)), &
               what//': k(Q x) = T k(x) T^T')

          w = [rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp)]
          if (is_2d(etype)) w(3) = 0.0_wp
          call beam_distributed_load(etype, x, sec, w, fe, ql, error)
          call check(.not. allocated(error), what//': load no error')
          call beam_distributed_load(etype, xr, secr, matmul(q, w), fer, qlr, error)
          call check(.not. allocated(error), what//': rotated load no error')
          call check(maxval(abs(fer - matmul(t, fe))) <= TOL*maxval(abs(fe)), what//': f_eq(Q x, Q w) = T f_eq')
          if (etype == ET_T3D2) then   ! a bar has only a local x axis that rotates with it
             call check(abs(qlr(1) - ql(1)) <= TOL*maxval(abs(w)), what//': same axial load')
          else
             call check(maxval(abs(qlr - ql)) <= TOL*maxval(abs(w)), what//': same local load')
          end if

          if (is_beam(etype)) then
             ! Clamped at node 1, loaded at node 2 by an arbitrary force: u(Q) = T u.
             allocate (fg(nd))
             call random_vector(fg)
             if (is_2d(etype)) fg(3) = fg(3)*2
             u = solve(ke(nd + 1:, nd + 1:), fg)
             ur = solve(ker(nd + 1:, nd + 1:), matmul(t(nd + 1:, nd + 1:), fg))
             call check(maxval(abs(ur - matmul(t(nd + 1:, nd + 1:), u))) <= TOL_SOLVE*maxval(abs(u)), &
                  what//': rotated load gives rotated displacements')
             deallocate (fg)
          end if
       end do
    end do
  end subroutine test_rotation_invariance

  subroutine random_vector(v)
    real(wp), intent(out) :: v(:)
    integer :: i
    do i = 1, size(v)
       v(i) = rnd_in(-1.0_wp, 1.0_wp)
    end do
  end subroutine random_vector

  subroutine test_distributed_fixed_fixed()
    !! Fixed-fixed beam under a uniform load: end forces -f_eq, i.e. shears qL/2
    !! and end moments ±qL^2/12 with the signs of the nodes acting on the beam.
    real(wp) :: x(3, 2), q(3, 3), len, qq, ql(3), qin(3), f(6, 2), want(6, 2), fl(12)
    real(wp), allocatable :: fe(:), ue(:)
    type(section_t) :: sec
    type(error_t), allocatable :: error
    integer :: io, k
    character(:), allocatable :: what

    do io = 1, NORIENT
       what = 'B33 fixed-fixed uniform load '//itoa(io)
       q = random_rotation(.false.)
       len = rnd_in(1.0_wp, 4.0_wp)
       qq = rnd_in(1.0_wp, 10.0_wp)
       call oriented_element(ET_B33, len, q, x, sec)
       ! Downward along local y and local z (q > 0 means load toward -y, -z), plus axial.
       qin = [0.3_wp*qq, -qq, -2*qq]
       call beam_distributed_load(ET_B33, x, sec, matmul(q, qin), fe, ql, error)
       call check(.not. allocated(error), what//': no error')
       call check(maxval(abs(ql - qin)) <= TOL*maxval(abs(qin)), what//': load in local axes')
       ! Consistent loads back in local axes.
       do k = 0, 3
          fl(3*k + 1:3*k + 3) = matmul(transpose(q), fe(3*k + 1:3*k + 3))
       end do
       call check(maxval(abs(fl - [qin*len/2, 0.0_wp, 2*qq*len**2/12, -qq*len**2/12, &
            qin*len/2, 0.0_wp, -2*qq*len**2/12, qq*len**2/12])) <= TOL*qq*len**2, &
            what//': consistent loads qL/2 and fixed-end moments')
       allocate (ue(12), source=0.0_wp)
       call element_end_forces(ET_B33, x, sec, mat, ue, ql, f, error)
       call check(.not. allocated(error), what//': end forces no error')
       want(:, 1) = [-0.3_wp*qq*len/2, qq*len/2, qq*len, 0.0_wp, -2*qq*len**2/12, qq*len**2/12]
       want(:, 2) = [-0.3_wp*qq*len/2, qq*len/2, qq*len, 0.0_wp, 2*qq*len**2/12, -qq*len**2/12]
       call check(maxval(abs(f - want)) <= TOL*qq*len**2, &
            what//': shears qL/2 up, moments +qL^2/12 at end 1, -qL^2/12 at end 2 (about z)')
       call check(f(2, 1) > 0 .and. f(6, 1) > 0 .and. f(6, 2) < 0, what//': signs about z')
       deallocate (ue)
    end do

    do io = 1, NORIENT
       what = 'B23 fixed-fixed uniform load '//itoa(io)
       q = random_rotation(.true.)
       len = rnd_in(1.0_wp, 4.0_wp)
       qq = rnd_in(1.0_wp, 10.0_wp)
       call oriented_element(ET_B23, len, q, x, sec)
       qin = [0.5_wp*qq, -qq, 0.0_wp]
       call beam_distributed_load(ET_B23, x, sec, matmul(q, qin), fe, ql, error)
       call check(.not. allocated(error), what//': no error')
       call check(size(fe) == 6, what//': size of f_eq')
       call check(maxval(abs(ql - qin)) <= TOL*qq, what//': load in local axes')
       call check(maxval(abs(fe([3, 6]) - [-qq*len**2/12, qq*len**2/12])) <= TOL*qq*len**2, &
            what//': fixed-end moments')
       call check(maxval(abs(fe([1, 2]) - matmul(q(1:2, 1:2), qin(1:2))*len/2)) <= TOL*qq*len, &
            what//': nodal forces wL/2')
       allocate (ue(6), source=0.0_wp)
       call element_end_forces(ET_B23, x, sec, mat, ue, ql, f, error)
       want = 0.0_wp
       want([1, 2, 6], 1) = [-0.5_wp*qq*len/2, qq*len/2, qq*len**2/12]
       want([1, 2, 6], 2) = [-0.5_wp*qq*len/2, qq*len/2, -qq*len**2/12]
       call check(maxval(abs(f - want)) <= TOL*qq*len**2, what//': end forces qL/2, +-qL^2/12')
       deallocate (ue)
    end do
  end subroutine test_distributed_fixed_fixed

  subroutine test_distributed_cantilever()
    !! Cantilever under a uniform load: nodal values are exact with consistent loads.
    real(wp) :: x(3, 2), q(3, 3), len, qq, ql(3), qin(3), f(6, 2), want(6, 2), tip(6)
    real(wp), allocatable :: fe(:), ue(:), ke(:, :)
    type(section_t) :: sec
    type(error_t), allocatable :: error
    integer :: io
    character(:), allocatable :: what

    do io = 1, NORIENT
       what = 'B33 cantilever uniform load '//itoa(io)
       q = random_rotation(.false.)
       len = rnd_in(1.0_wp, 4.0_wp)
       qq = rnd_in(1.0_wp, 10.0_wp)
       call oriented_element(ET_B33, len, q, x, sec)
       qin = [0.7_wp*qq, -qq, 1.5_wp*qq]
       call beam_distributed_load(ET_B33, x, sec, matmul(q, qin), fe, ql, error)
       ke = stiffness(ET_B33, x, sec, what)
       allocate (ue(12), source=0.0_wp)
       ue(7:12) = solve(ke(7:12, 7:12), fe(7:12))
       tip(1:3) = matmul(transpose(q), ue(7:9))
       tip(4:6) = matmul(transpose(q), ue(10:12))
       call check_tip(tip, [qin(1)*len**2/(2*E_MOD*AREA), qin(2)*len**4/(8*E_MOD*IZ), &
            qin(3)*len**4/(8*E_MOD*IY), 0.0_wp, -qin(3)*len**3/(6*E_MOD*IY), qin(2)*len**3/(6*E_MOD*IZ)], &
            what//': qL^4/(8EI), qL^3/(6EI), qL^2/(2EA)')
       call element_end_forces(ET_B33, x, sec, mat, ue, ql, f, error)
       call check(.not. allocated(error), what//': end forces no error')
       want = 0.0_wp
       want(:, 1) = [-qin(1)*len, -qin(2)*len, -qin(3)*len, 0.0_wp, qin(3)*len**2/2, -qin(2)*len**2/2]
       call check_forces(f, want, what//': root reactions, free tip')
       deallocate (ue)
    end do

    do io = 1, NORIENT
       what = 'B23 cantilever uniform load '//itoa(io)
       q = random_rotation(.true.)
       len = rnd_in(1.0_wp, 4.0_wp)
       qq = rnd_in(1.0_wp, 10.0_wp)
       call oriented_element(ET_B23, len, q, x, sec)
       qin = [-0.4_wp*qq, -qq, 0.0_wp]
       call beam_distributed_load(ET_B23, x, sec, matmul(q, qin), fe, ql, error)
       ke = stiffness(ET_B23, x, sec, what)
       allocate (ue(6), source=0.0_wp)
       ue(4:6) = solve(ke(4:6, 4:6), fe(4:6))
       tip(1:2) = matmul(transpose(q(1:2, 1:2)), ue(4:5))
       tip(3) = ue(6)
       call check_tip(tip(1:3), [qin(1)*len**2/(2*E_MOD*AREA), qin(2)*len**4/(8*E_MOD*IZ), &
            qin(2)*len**3/(6*E_MOD*IZ)], what//': qL^4/(8EI), qL^3/(6EI), qL^2/(2EA)')
       call element_end_forces(ET_B23, x, sec, mat, ue, ql, f, error)
       want = 0.0_wp
       want([1, 2, 6], 1) = [-qin(1)*len, -qin(2)*len, -qin(2)*len**2/2]
       call check_forces(f, want, what//': root reactions, free tip')
       deallocate (ue)
    end do
  end subroutine test_distributed_cantilever

  subroutine test_timoshenko_cantilever()
    !! B31 and B21 cantilevers (one element, random orientation): tip load
    !! P L^3/(3EI) + P L/K along local y and z, rotation P L^2/(2EI), torsion,
    !! and a uniform load q L^4/(8EI) + q L^2/(2K): the element is exact.
    real(wp) :: x(3, 2), q(3, 3), len, p, tip(6), tip2(3), f(6, 2), want(6, 2), w, ql(3)
    real(wp), allocatable :: ke(:, :), fe(:), u2(:)
    type(section_t) :: sec
    type(error_t), allocatable :: error
    integer :: io
    character(:), allocatable :: what

    do io = 1, NORIENT
       what = 'B31 cantilever '//itoa(io)
       q = random_rotation(.false.)
       len = rnd_in(0.3_wp, 4.0_wp)
       p = rnd_in(10.0_wp, 100.0_wp)
       call oriented_element(ET_B31, len, q, x, sec)
       call cantilever_tip(ET_B31, x, sec, q, [0.0_wp, p, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, p*len**3/(3*E_MOD*IZ) + p*len/KSY, 0.0_wp, 0.0_wp, 0.0_wp, &
            p*len**2/(2*E_MOD*IZ)], what//': P along y: PL^3/(3EIz) + PL/Ky')
       want = 0.0_wp
       want(2, :) = [-p, p]
       want(6, 1) = -p*len
       call check_forces(f, want, what//': P along y: end forces')
       call cantilever_tip(ET_B31, x, sec, q, [0.0_wp, 0.0_wp, p, 0.0_wp, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, 0.0_wp, p*len**3/(3*E_MOD*IY) + p*len/KSZ, 0.0_wp, &
            -p*len**2/(2*E_MOD*IY), 0.0_wp], what//': P along z: PL^3/(3EIy) + PL/Kz')
       want = 0.0_wp
       want(3, :) = [-p, p]
       want(5, 1) = p*len
       call check_forces(f, want, what//': P along z: end forces')
       call cantilever_tip(ET_B31, x, sec, q, [0.0_wp, 0.0_wp, 0.0_wp, p, 0.0_wp, 0.0_wp], tip, f)
       call check_tip(tip, [0.0_wp, 0.0_wp, 0.0_wp, p*len/(G_MOD*TJ), 0.0_wp, 0.0_wp], &
            what//': torsion TL/(GJ)')
       ! A pure end moment bends without shear: the Euler-Bernoulli values.
       call cantilever_tip(ET_B31, x, sec, q, [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, p], tip, f)
       call check_tip(tip, [0.0_wp, p*len**2/(2*E_MOD*IZ), 0.0_wp, 0.0_wp, 0.0_wp, p*len/(E_MOD*IZ)], &
            what//': moment about z: ML^2/(2EIz), ML/(EIz)')

       ! Uniform load along local z, clamped at node 1.
       w = rnd_in(10.0_wp, 100.0_wp)
       call beam_distributed_load(ET_B31, x, sec, w*q(:, 3), fe, ql, error)
       call check(.not. allocated(error), what//': load without error')
       ke = stiffness(ET_B31, x, sec, what)
       u2 = solve_tip(ke, fe(7:12), 6)
       tip(1:3) = matmul(transpose(q), u2(1:3))
       tip(4:6) = matmul(transpose(q), u2(4:6))
       call check_rel(tip(3), w*len**4/(8*E_MOD*IY) + w*len**2/(2*KSZ), TOL_SOLVE, &
            what//': uniform load along z: qL^4/(8EIy) + qL^2/(2Kz)')
       call check_rel(tip(5), -w*len**3/(6*E_MOD*IY), TOL_SOLVE, what//': uniform load along z: rotation')
    end do

    do io = 1, NORIENT
       what = 'B21 cantilever '//itoa(io)
       q = random_rotation(.true.)
       len = rnd_in(0.3_wp, 4.0_wp)
       p = rnd_in(10.0_wp, 100.0_wp)
       call oriented_element(ET_B21, len, q, x, sec)
       call cantilever_tip(ET_B21, x, sec, q, [0.0_wp, p, 0.0_wp], tip2, f)
       call check_tip(tip2, [0.0_wp, p*len**3/(3*E_MOD*IZ) + p*len/(G_MOD*AREA), p*len**2/(2*E_MOD*IZ)], &
            what//': P along y: PL^3/(3EI) + PL/(GA), default K = G A')
       sec%shear_factor = 5.0_wp/6
       call cantilever_tip(ET_B21, x, sec, q, [0.0_wp, p, 0.0_wp], tip2, f)
       call check_tip(tip2, [0.0_wp, p*len**3/(3*E_MOD*IZ) + p*len/(5*G_MOD*AREA/6), p*len**2/(2*E_MOD*IZ)], &
            what//': P along y, k = 5/6: PL^3/(3EI) + PL/(kGA)')
       sec%shear_k(1) = KSZ
       call cantilever_tip(ET_B21, x, sec, q, [0.0_wp, p, 0.0_wp], tip2, f)
       call check_tip(tip2, [0.0_wp, p*len**3/(3*E_MOD*IZ) + p*len/KSZ, p*len**2/(2*E_MOD*IZ)], &
            what//': P along y, K given: PL^3/(3EI) + PL/K')
       want = 0.0_wp
       want(2, :) = [-p, p]
       want(6, 1) = -p*len
       call check_forces(f, want, what//': P along y: end forces')
    end do
  end subroutine test_timoshenko_cantilever

  function solve_tip(ke, f, nd) result(u)
    !! Displacements of node 2 of a two-node element clamped at node 1.
    real(wp), intent(in) :: ke(:, :), f(:)
    integer, intent(in) :: nd
    real(wp), allocatable :: u(:)
    u = solve(ke(nd + 1:, nd + 1:), f)
  end function solve_tip

  subroutine test_timoshenko_slender_limit()
    !! A slender B31 (phi = 12EI/(K L^2) small) tends to B33: the tip
    !! deflection ratio is exactly 1 + phi/4 and |k_T - k_EB| = O(phi) |k_EB|
    !! (no shear locking: the element stays exact however slender).
    real(wp) :: x(3, 2), q(3, 3), len, phi, tip_t(6), tip_b(6), f(6, 2)
    real(wp), allocatable :: kt(:, :), kb(:, :)
    type(section_t) :: sec
    integer :: io, is
    real(wp), parameter :: SLENDER(3) = [1.0e1_wp, 1.0e2_wp, 1.0e3_wp]
    character(:), allocatable :: what

    do io = 1, 2
       do is = 1, size(SLENDER)
          what = 'B31 slender limit '//itoa(io)//' L = '//itoa(nint(SLENDER(is)))//' sqrt(I/A)'
          q = random_rotation(.false.)
          len = SLENDER(is)*sqrt(IZ/AREA)
          call oriented_element(ET_B31, len, q, x, sec)
          sec%shear_k = 0.0_wp           ! default K = G A in both directions
          phi = 12*E_MOD*IZ/(G_MOD*AREA*len**2)
          call cantilever_tip(ET_B31, x, sec, q, [0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], tip_t, f)
          call cantilever_tip(ET_B33, x, sec, q, [0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], tip_b, f)
          ! (round-off grows with the condition number, ~ (L/r)^2)
          call check_close(tip_t(2)/tip_b(2), 1 + phi/4, 1.0e-14_wp*SLENDER(is)**2, &
               what//': v_T / v_EB = 1 + phi/4')
          kt = stiffness(ET_B31, x, sec, what)
          kb = stiffness(ET_B33, x, sec, what)
          call check(maxval(abs(kt - kb)) <= 2*max(phi, 12*E_MOD*IY/(G_MOD*AREA*len**2))*maxval(abs(kb)), &
               what//': |k_T - k_EB| <= 2 phi |k_EB|')
          call check(maxval(abs(kt - kb)) > 0.0_wp, what//': k_T differs from k_EB')
       end do
    end do
  end subroutine test_timoshenko_slender_limit

  subroutine test_timoshenko_errors()
    !! Shear data the Timoshenko beams refuse.
    real(wp) :: x(3, 2)
    real(wp), allocatable :: ke(:, :)
    type(section_t) :: sec
    type(material_t) :: bad
    type(error_t), allocatable :: error
    x(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
    x(:, 2) = [2.0_wp, 1.0_wp, 0.0_wp]
    sec = make_section(ET_B21)
    sec%shear_factor = 0.0_wp
    call element_stiffness(ET_B21, x, sec, mat, ke, error)
    call check_error(error, 'nonpositive shear factor k', 'B21 k = 0')
    sec = make_section(ET_B31)
    bad = mat
    bad%nu = -1.0_wp
    call element_stiffness(ET_B31, x, sec, bad, ke, error)
    call check_error(error, 'Poisson''s ratio', 'B31 nu = -1')
    call element_stiffness(ET_B21, x, make_section(ET_B21), bad, ke, error)
    call check_error(error, 'Poisson''s ratio', 'B21 nu = -1')
    ! B23 and B33 ignore the shear data.
    sec = make_section(ET_B33)
    sec%shear_factor = 0.0_wp
    call element_stiffness(ET_B33, x, sec, mat, ke, error)
    call check(.not. allocated(error), 'B33 ignores the shear factor')
  end subroutine test_timoshenko_errors

  subroutine test_distributed_truss()
    !! Trusses: a uniform load gives wL/2 on each node; axial part in n.
    real(wp) :: x(3, 2), q(3, 3), len, w(3), ql(3), f(6, 2), delta
    real(wp), allocatable :: fe(:), ue(:)
    type(section_t) :: sec
    type(error_t), allocatable :: error
    integer :: it, io, etype, nd
    character(:), allocatable :: what

    do it = 1, 2
       etype = LINE_TYPES(it)
       nd = size(element_node_dofs(etype))
       do io = 1, NORIENT
          what = trim(LINE_NAMES(it))//' uniform load '//itoa(io)
          q = random_rotation(is_2d(etype))
          len = rnd_in(0.5_wp, 5.0_wp)
          call oriented_element(etype, len, q, x, sec)
          w = [rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp)]
          if (is_2d(etype)) w(3) = 0.0_wp
          call beam_distributed_load(etype, x, sec, w, fe, ql, error)
          call check(.not. allocated(error), what//': no error')
          call check(size(fe) == 2*nd, what//': size')
          call check(maxval(abs(fe(1:nd) - w(1:nd)*len/2)) <= TOL*len .and. &
               maxval(abs(fe(nd + 1:) - w(1:nd)*len/2)) <= TOL*len, what//': wL/2 per node')
          call check_close(ql(1), dot_product(q(:, 1), w), TOL, what//': axial load in local axes')
          allocate (ue(2*nd), source=0.0_wp)
          delta = 1.0e-3_wp
          ue(nd + 1:) = delta*q(1:nd, 1)
          call element_end_forces(etype, x, sec, mat, ue, ql, f, error)
          call check(.not. allocated(error), what//': end forces no error')
          call check_close(f(1, 1), -E_MOD*AREA*delta/len - ql(1)*len/2, TOL*E_MOD*AREA*delta/len, &
               what//': n1 = -EA delta/L - qx L/2')
          call check_close(f(1, 2), E_MOD*AREA*delta/len - ql(1)*len/2, TOL*E_MOD*AREA*delta/len, &
               what//': n2 = EA delta/L - qx L/2')
          deallocate (ue)
       end do
    end do
  end subroutine test_distributed_truss
end program test_elements
