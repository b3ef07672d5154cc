program test_shell8
  !! Unit tests of the eight-node thick shell S8R (superjoin_elements_shell8,
  !! through the element facade): rigid motions of flat and curved elements,
  !! the zero-energy modes of one element and of a mesh, the membrane and
  !! bending patch tests on a distorted five-element mesh in an oblique plane,
  !! resultants of constant fields, the consistent pressure and area loads on
  !! curved elements, the section's transverse shear stiffness, and data checks.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, ET_S8R, ET_S8, SEC_SHELL, DLOAD_P, ELEMENT_TYPE_NAMES
  use superjoin_elements, only: element_stiffness, shell_resultants, element_distributed_load, &
       element_gravity_load
  use superjoin_elements_plate, only: bending_rigidity
  use superjoin_elements_membrane, only: plane_stress
  use verification_support, only: shell_data
  use superjoin_testing, only: check, check_close, check_rel, finish
  use test_lapack, only: eigenvalues, dgesv
  use test_random, only: set_seed, rnd_in
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-12_wp          !! round-off on one element, relative
  real(wp), parameter :: TOL_SOLVE = 1.0e-10_wp    !! exact discrete answers after a solve, relative
  real(wp), parameter :: ZERO_EIG = 1.0e-13_wp     !! a zero eigenvalue (round-off), relative to the largest
  real(wp), parameter :: WEAK_EIG = 1.0e-7_wp      !! below this (relative): a mode held by the drilling penalty only
  real(wp), parameter :: PHYS_EIG = 1.0e-6_wp      !! the softest deformation mode of a thick (t/L = 0.5) element is above
  real(wp), parameter :: E_MOD = 2.1e5_wp, NU = 0.3_wp
  integer, parameter :: NN = 8, NDOF = 48
  integer, parameter :: NRANDOM = 10
  real(wp), parameter :: THICKNESSES(3) = [0.5_wp, 0.05_wp, 0.002_wp]   !! relative to a unit element
  real(wp), parameter :: XI_NODE(NN) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp]
  real(wp), parameter :: ETA_NODE(NN) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]
  real(wp), parameter :: PI = acos(-1.0_wp)
  integer, parameter :: MEMBRANE_PART = 1, BENDING_PART = 2, BOTH_PARTS = 3   !! of patch_field
  real(wp), parameter :: DISTORTED_BENDING_TOL(3) = [1.0e-2_wp, 6.0e-2_wp, 1.5_wp]
    !! Constant curvature on the distorted patch at the three PATCH_T: not
    !! exact (the serendipity space lacks x², xy, y² on a non-parallelogram,
    !! and the 2×2 shear constraints lock as t → 0); measured 7.3e-3, 4.7e-2,
    !! 1.16 (a known failure, reported in doc/verification.md; the bounds only
    !! guard against a regression)

  integer :: et = ET_S8R   !! the element type under test (S8R; test_full switches to S8)

  call set_seed(20261124)
  call test_single_element(.false.)
  call test_single_element(.true.)
  call test_patch()
  call test_free_patch()
  call test_constant_resultants()
  call test_loads()
  call test_errors()
  call test_full()
  call finish()

contains

  function random_rotation() result(r)
    !! A random proper rotation (rows: local axes in global coordinates).
    real(wp) :: r(3, 3), a(3), b(3)
    a = [rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp)] + [0.0_wp, 0.0_wp, 2.0_wp]
    a = a/norm2(a)
    b = [rnd_in(-1.0_wp, 1.0_wp), 1.5_wp, rnd_in(-1.0_wp, 1.0_wp)]
    b = b - dot_product(a, b)*a
    b = b/norm2(b)
    r(1, :) = b
    r(2, :) = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
    r(3, :) = a
  end function random_rotation

  function element_nodes(curved) result(xl)
    !! Local coordinates xl(3, 8) of a distorted element of unit size: flat
    !! (z = 0, mid-side nodes off the chord midpoints) or on a cylinder of
    !! radius 2 about the local y axis (curved).
    logical, intent(in) :: curved
    real(wp) :: xl(3, NN)
    real(wp) :: c(2, 4), r
    integer :: i, j, k
    c = reshape([0.0_wp, 0.0_wp, 1.2_wp, 0.1_wp, 1.1_wp, 0.9_wp, -0.1_wp, 1.0_wp], [2, 4])
    do i = 1, 4
       c(:, i) = c(:, i) + [rnd_in(-0.1_wp, 0.1_wp), rnd_in(-0.1_wp, 0.1_wp)]
    end do
    xl = 0.0_wp
    xl(1:2, 1:4) = c
    do i = 1, 4
       j = mod(i, 4) + 1
       k = 4 + i
       xl(1:2, k) = (c(:, i) + c(:, j))/2 + [rnd_in(-0.05_wp, 0.05_wp), rnd_in(-0.05_wp, 0.05_wp)]
    end do
    if (curved) then
       r = 2.0_wp
       do i = 1, NN
          xl(:, i) = [r*sin(xl(1, i)/r), xl(2, i), r*cos(xl(1, i)/r) - r]
       end do
    end if
  end function element_nodes

  function rigid(x, origin, mode) result(u)
    !! Nodal DOFs (6 per node) of rigid motion `mode` (1-3 translations, 4-6 rotations about origin).
    real(wp), intent(in) :: x(:, :), origin(3)
    integer, intent(in) :: mode
    real(wp) :: u(6*size(x, 2))
    real(wp) :: th(3), u0(3), d(3)
    integer :: i
    th = 0.0_wp
    u0 = 0.0_wp
    if (mode <= 3) then
       u0(mode) = 1.0_wp
    else
       th(mode - 3) = 1.0_wp
    end if
    do i = 1, size(x, 2)
       d = x(:, i) - origin
       u(6*i - 5:6*i - 3) = u0 + [th(2)*d(3) - th(3)*d(2), th(3)*d(1) - th(1)*d(3), th(1)*d(2) - th(2)*d(1)]
       u(6*i - 2:6*i) = th
    end do
  end function rigid

  integer function modes_below(k, level)
    !! Number of eigenvalues of k below level × the largest (and a check that none is negative beyond round-off).
    real(wp), intent(in) :: k(:, :), level
    real(wp), allocatable :: w(:)
    allocate (w(size(k, 1)))
    w = eigenvalues(k)
    modes_below = count(w <= level*w(size(w)))
    call check(w(1) > -ZERO_EIG*w(size(w)), 'no negative eigenvalue')
  end function modes_below


  subroutine test_single_element(curved)
    !! One element in an oblique position: exact symmetry, K r = 0 for the six
    !! rigid motions, and the number of zero-energy modes of the 2×2 rule
    !! (six rigid plus the spurious ones, the same count at every thickness).
    logical, intent(in) :: curved
    real(wp), allocatable :: ke(:, :)
    real(wp) :: x(3, NN), xl(3, NN), rot(3, 3), origin(3), r(NDOF)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    integer :: it, jt, i, mode, nzero
    character(len=60) :: tag
    do jt = 1, size(THICKNESSES)
       do it = 1, NRANDOM
          xl = element_nodes(curved)
          rot = random_rotation()
          origin = [rnd_in(-3.0_wp, 3.0_wp), rnd_in(-3.0_wp, 3.0_wp), rnd_in(-3.0_wp, 3.0_wp)]
          do i = 1, NN
             x(:, i) = origin + matmul(transpose(rot), xl(:, i))
          end do
          call shell_data(THICKNESSES(jt), E_MOD, NU, sec, mat)
          call element_stiffness(ET_S8R, x, sec, mat, ke, error)
          call check(.not. allocated(error), 'S8R stiffness without error')
          if (allocated(error)) return
          write (tag, '(a,a,es8.1)') merge('curved S8R', 'flat S8R  ', curved), ' t/L ', THICKNESSES(jt)
          call check(maxval(abs(ke - transpose(ke))) == 0.0_wp, trim(tag)//': exactly symmetric')
          do mode = 1, 6
             r = rigid(x, origin, mode)
             call check(norm2(matmul(ke, r)) <= TOL*maxval(abs(ke))*norm2(r)*10, trim(tag)//': rigid motion free')
          end do
          call check(modes_below(ke, ZERO_EIG) == 6, trim(tag)//': exactly six zero eigenvalues')
          if (jt == 1) then
             ! the thick element: a flat one has one near-zero mode, the
             ! membrane hourglass of the 2×2 rule (as CPS8R's), held only by
             ! the drilling penalty; a curved one has none (bending holds it)
             nzero = modes_below(ke, WEAK_EIG)
             call check(nzero == merge(6, 7, curved), trim(tag)//': near-zero modes')
             call check(modes_below(ke, PHYS_EIG) == nzero, trim(tag)//': a clear gap above them')
             if (it == 1) write (*, '(a,i0,a)') trim(tag)//': ', nzero, ' modes below 1e-7 (6 rigid)'
          end if
       end do
    end do
  end subroutine test_single_element

  subroutine patch_mesh(x, conn, inner)
    !! The MacNeal-Harder patch (0.24 x 0.12, five distorted quadrilaterals) with
    !! mid-side nodes at the middle of every side: x(2, 20) local coordinates,
    !! conn(8, 5), inner(20) true for the nodes off the outer boundary.
    real(wp), allocatable, intent(out) :: x(:, :)
    integer, allocatable, intent(out) :: conn(:, :)
    logical, allocatable, intent(out) :: inner(:)
    real(wp), parameter :: XP(2, 8) = reshape([0.0_wp, 0.0_wp, 0.24_wp, 0.0_wp, 0.24_wp, 0.12_wp, &
         0.0_wp, 0.12_wp, 0.04_wp, 0.02_wp, 0.18_wp, 0.03_wp, 0.16_wp, 0.08_wp, 0.08_wp, 0.08_wp], [2, 8])
    integer, parameter :: QUADS(4, 5) = reshape([1, 2, 6, 5, 2, 3, 7, 6, 3, 4, 8, 7, 4, 1, 5, 8, &
         5, 6, 7, 8], [4, 5])
    integer :: sides(2, 20), nside, e, i, a, b, k, found
    allocate (x(2, 20), inner(20), conn(NN, 5))
    x(:, 1:8) = XP
    inner = .false.
    inner(5:8) = .true.
    nside = 0
    do e = 1, 5
       conn(1:4, e) = QUADS(:, e)
       do i = 1, 4
          a = QUADS(i, e)
          b = QUADS(mod(i, 4) + 1, e)
          found = 0
          do k = 1, nside
             if ((sides(1, k) == a .and. sides(2, k) == b) .or. (sides(1, k) == b .and. sides(2, k) == a)) found = k
          end do
          if (found == 0) then
             nside = nside + 1
             sides(:, nside) = [a, b]
             found = nside
             x(:, 8 + nside) = (XP(:, a) + XP(:, b))/2
             ! a side of the outer rectangle has both ends among its corners 1-4
             inner(8 + nside) = .not. (a <= 4 .and. b <= 4)
          end if
          conn(4 + i, e) = 8 + found
       end do
    end do
    call check(nside == 12, 'patch: twelve sides')
  end subroutine patch_mesh

  subroutine parallelogram_mesh(x, conn, inner)
    !! Six parallelograms (3 x 2, unequal spacing, x' = x + 0.4 y): each
    !! element an affine image of the square, where the serendipity space holds
    !! every quadratic field. x(2, 29) (the 6 block centres are not nodes).
    real(wp), allocatable, intent(out) :: x(:, :)
    integer, allocatable, intent(out) :: conn(:, :)
    logical, allocatable, intent(out) :: inner(:)
    real(wp), parameter :: XS(7) = [0.0_wp, 0.15_wp, 0.3_wp, 0.4_wp, 0.5_wp, 0.75_wp, 1.0_wp]
    real(wp), parameter :: YS(5) = [0.0_wp, 0.2_wp, 0.4_wp, 0.7_wp, 1.0_wp]
    integer :: id(7, 5), i, j, k, e
    allocate (x(2, 29), inner(29), conn(NN, 6))
    id = 0
    k = 0
    do j = 1, 5
       do i = 1, 7
          if (mod(i, 2) == 0 .and. mod(j, 2) == 0) cycle
          k = k + 1
          id(i, j) = k
          x(:, k) = [XS(i) + 0.4_wp*YS(j), YS(j)]
          inner(k) = i > 1 .and. i < 7 .and. j > 1 .and. j < 5
       end do
    end do
    e = 0
    do j = 1, 3, 2
       do i = 1, 5, 2
          e = e + 1
          conn(:, e) = [id(i, j), id(i + 2, j), id(i + 2, j + 2), id(i, j + 2), &
               id(i + 1, j), id(i + 2, j + 1), id(i + 1, j + 2), id(i, j + 1)]
       end do
    end do
  end subroutine parallelogram_mesh

  function patch_field(p, t, parts) result(u)
    !! Local DOFs (u, v, w, θx, θy, θz) at the point p(2) of a field with
    !! constant membrane strain (parts 1 or 3) and constant curvature, no
    !! transverse shear (parts 2 or 3), the drilling rotation equal to the
    !! in-plane rotation.
    real(wp), intent(in) :: p(2), t
    integer, intent(in) :: parts
    real(wp) :: u(6)
    real(wp), parameter :: A(3) = [1.0e-3_wp, 2.0e-3_wp, -1.5e-3_wp], B(3) = [-2.0e-3_wp, 0.5e-3_wp, 1.0e-3_wp]
    real(wp), parameter :: C(6) = [1.0e-3_wp, 2.0e-3_wp, -1.0e-3_wp, 1.0e-1_wp, 0.5e-1_wp, -2.0e-1_wp]
    real(wp) :: bx, by
    u(1) = A(1) + A(2)*p(1) + A(3)*p(2)
    u(2) = B(1) + B(2)*p(1) + B(3)*p(2)
    u(3) = (C(1) + C(2)*p(1) + C(3)*p(2) + C(4)*p(1)**2/2 + C(5)*p(1)*p(2) + C(6)*p(2)**2/2)*t
    bx = -(C(2) + C(4)*p(1) + C(5)*p(2))*t
    by = -(C(3) + C(5)*p(1) + C(6)*p(2))*t
    u(4) = -by
    u(5) = bx
    u(6) = (B(2) - A(3))/2
    if (parts == MEMBRANE_PART) u(3:5) = 0.0_wp
    if (parts == BENDING_PART) u([1, 2, 6]) = 0.0_wp
  end function patch_field

  subroutine test_free_patch()
    !! The patch scaled to unit size (4 x, 0.96 x 0.48, t = 0.25, comparable
    !! with the single thick element): six zero modes and no near-zero one
    !! (the flat element's hourglass is not communicable through shared nodes).
    real(wp), allocatable :: xl(:, :), ke(:, :), kg(:, :)
    logical, allocatable :: inner(:)
    integer, allocatable :: conn(:, :)
    integer :: e, i, nnode
    real(wp) :: x3(3, NN)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    integer :: dofs(NDOF)
    real(wp), parameter :: SCALE = 4.0_wp
    call patch_mesh(xl, conn, inner)
    nnode = size(xl, 2)
    call shell_data(0.25_wp, E_MOD, NU, sec, mat)
    allocate (kg(6*nnode, 6*nnode), source=0.0_wp)
    do e = 1, 5
       do i = 1, NN
          x3(:, i) = [SCALE*xl(:, conn(i, e)), 0.0_wp]
          dofs(6*i - 5:6*i) = 6*(conn(i, e) - 1) + [1, 2, 3, 4, 5, 6]
       end do
       call element_stiffness(et, x3, sec, mat, ke, error)
       if (allocated(error)) then
          call check(.false., 'free patch element: '//error%message)
          return
       end if
       kg(dofs, dofs) = kg(dofs, dofs) + ke
    end do
    call check(modes_below(kg, ZERO_EIG) == 6, 'unit free S8R patch: six zero modes')
    call check(modes_below(kg, WEAK_EIG) == 6, 'unit free S8R patch: no near-zero mode')
  end subroutine test_free_patch

  subroutine test_patch()
    !! Patch tests in an oblique plane, from thick to thin, the boundary nodes
    !! prescribed: constant membrane strain on the distorted MacNeal-Harder
    !! patch and constant membrane strain with constant curvature on the
    !! parallelogram patch are taken exactly by the inner nodes (round-off
    !! times the condition number); constant curvature on the distorted patch
    !! within DISTORTED_BENDING_TOL (the element does not pass it: measured).
    real(wp), allocatable :: xl(:, :)
    logical, allocatable :: inner(:)
    integer, allocatable :: conn(:, :)
    integer :: it
    real(wp), parameter :: PATCH_T(3) = [0.1_wp, 0.02_wp, 0.0002_wp]   !! the patches are about 0.24 and 1 long
    real(wp) :: err, tol
    character(len=48) :: tag
    do it = 1, size(PATCH_T)
       call patch_mesh(xl, conn, inner)
       call solve_patch(xl, conn, inner, PATCH_T(it), MEMBRANE_PART, err, tol)
       write (tag, '(a,es8.1)') trim(ELEMENT_TYPE_NAMES(et))//' distorted patch, membrane, t ', PATCH_T(it)
       call check(err <= tol, trim(tag))
       write (*, '(a,es10.2)') trim(tag)//': error ', err
       call solve_patch(xl, conn, inner, PATCH_T(it), BENDING_PART, err, tol)
       write (tag, '(a,es8.1)') trim(ELEMENT_TYPE_NAMES(et))//' distorted patch, bending, t ', PATCH_T(it)
       call check(err <= DISTORTED_BENDING_TOL(it), trim(tag))
       write (*, '(a,es10.2)') trim(tag)//': error ', err
       call parallelogram_mesh(xl, conn, inner)
       call solve_patch(xl, conn, inner, 4*PATCH_T(it), BOTH_PARTS, err, tol)
       write (tag, '(a,es8.1)') trim(ELEMENT_TYPE_NAMES(et))//' parallelogram patch, t ', 4*PATCH_T(it)
       call check(err <= tol, trim(tag))
       write (*, '(a,es10.2)') trim(tag)//': error ', err
    end do
  end subroutine test_patch

  subroutine solve_patch(xl, conn, inner, t, parts, err, tol)
    !! Assemble the patch (xl local coordinates, placed in a random oblique
    !! plane), prescribe patch_field on the boundary nodes, solve for the inner
    !! ones: err = largest error relative to the largest nodal value, tol the
    !! round-off bound 10 ε cond(K_inner).
    real(wp), intent(in) :: xl(:, :), t
    integer, intent(in) :: conn(:, :), parts
    logical, intent(in) :: inner(:)
    real(wp), intent(out) :: err, tol
    real(wp), allocatable :: ke(:, :), kg(:, :), a(:, :), b(:, :), ug(:), xg(:, :), w(:)
    integer, allocatable :: ipiv(:), free(:), fixed(:)
    integer :: e, i, j, info, nnode
    real(wp) :: rot(3, 3), origin(3), x3(3, NN)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    integer :: dofs(NDOF)
    err = huge(1.0_wp)
    tol = 0.0_wp
    nnode = size(xl, 2)
    call shell_data(t, E_MOD, NU, sec, mat)
    rot = random_rotation()
    origin = [rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp)]
    allocate (xg(3, nnode), kg(6*nnode, 6*nnode), ug(6*nnode))
    do i = 1, nnode
       xg(:, i) = origin + matmul(transpose(rot), [xl(1, i), xl(2, i), 0.0_wp])
       ug(6*i - 5:6*i) = patch_field(xl(:, i), t, parts)
       ug(6*i - 5:6*i - 3) = matmul(transpose(rot), ug(6*i - 5:6*i - 3))
       ug(6*i - 2:6*i) = matmul(transpose(rot), ug(6*i - 2:6*i))
    end do
    kg = 0.0_wp
    do e = 1, size(conn, 2)
       x3 = xg(:, conn(:, e))
       call element_stiffness(et, x3, sec, mat, ke, error)
       if (allocated(error)) then
          call check(.false., 'patch element: '//error%message)
          return
       end if
       do i = 1, NN
          dofs(6*i - 5:6*i) = 6*(conn(i, e) - 1) + [1, 2, 3, 4, 5, 6]
       end do
       kg(dofs, dofs) = kg(dofs, dofs) + ke
    end do
    call check(modes_below(kg, ZERO_EIG) == 6, 'free S8R patch: exactly six zero modes')
    allocate (free(0), fixed(0))
    do i = 1, nnode
       if (inner(i)) then
          free = [free, [(6*(i - 1) + j, j=1, 6)]]
       else
          fixed = [fixed, [(6*(i - 1) + j, j=1, 6)]]
       end if
    end do
    a = kg(free, free)
    allocate (w(size(free)))
    w = eigenvalues(a)
    tol = 10*epsilon(1.0_wp)*w(size(w))/w(1)
    b = reshape(-matmul(kg(free, fixed), ug(fixed)), [size(free), 1])
    allocate (ipiv(size(free)))
    call dgesv(size(free), 1, a, size(free), ipiv, b, size(free), info)
    call check(info == 0, 'patch solve')
    err = maxval(abs(b(:, 1) - ug(free)))/maxval(abs(ug))
  end subroutine solve_patch

  subroutine test_constant_resultants()
    !! A flat rectangle (2 x 1, local x from node 1 to 2) under the patch field:
    !! resultants n = t D ε, m = D_b κ in the element frame; and the pure shear
    !! field w = x (γxz = 1) has energy 2 K11 with the section's K11, K22.
    real(wp), allocatable :: ke(:, :)
    real(wp) :: x(3, NN), u(NDOF), res(6), eps(3), kap(3), t, want(6)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp), parameter :: A(3) = [1.0e-3_wp, 2.0e-3_wp, -1.5e-3_wp], B(3) = [-2.0e-3_wp, 0.5e-3_wp, 1.0e-3_wp]
    real(wp), parameter :: C(6) = [1.0e-3_wp, 2.0e-3_wp, -1.0e-3_wp, 1.0e-1_wp, 0.5e-1_wp, -2.0e-1_wp]
    integer :: i
    t = 0.05_wp
    call shell_data(t, E_MOD, NU, sec, mat)
    do i = 1, NN
       x(:, i) = [1.0_wp + XI_NODE(i), 0.5_wp*(1.0_wp + ETA_NODE(i)), 0.0_wp]
       u(6*i - 5:6*i) = patch_field(x(1:2, i), t, BOTH_PARTS)
    end do
    call shell_resultants(ET_S8R, x, sec, mat, u, res, error)
    call check(.not. allocated(error), 'resultants without error')
    eps = [A(2), B(3), A(3) + B(2)]
    ! β = -∇w t-scaled: κ = (∂βx/∂x, ∂βy/∂y, ∂βx/∂y + ∂βy/∂x)
    kap = -[C(4), C(6), 2*C(5)]*t
    want(1:3) = t*matmul(plane_stress(E_MOD, NU), eps)
    want(4:6) = matmul(bending_rigidity(t, E_MOD, NU), kap)
    do i = 1, 6
       call check_close(res(i), want(i), TOL*10*maxval(abs(want(4:6))) + TOL*10*maxval(abs(want(1:3))), &
            'S8R constant-field resultant')
    end do
    ! transverse shear: w = x, rotations 0; energy = ∫ K11 γ² dA = 2 K11
    sec%shear_k = [3.0e3_wp, 5.0e3_wp]
    call element_stiffness(ET_S8R, x, sec, mat, ke, error)
    u = 0.0_wp
    do i = 1, NN
       u(6*i - 3) = x(1, i)
    end do
    call check_rel(dot_product(u, matmul(ke, u)), 2*sec%shear_k(1), TOL*10, 'S8R shear energy with K11')
    u = 0.0_wp
    do i = 1, NN
       u(6*i - 3) = x(2, i)
    end do
    call check_rel(dot_product(u, matmul(ke, u)), 2*sec%shear_k(2), TOL*10, 'S8R shear energy with K22')
  end subroutine test_constant_resultants

  subroutine test_loads()
    !! Pressure on a curved element (a quarter of a cylinder of radius R, length
    !! L, from 0 to 90°): the resultant of the nodal loads is -p ∫ n dA =
    !! -p R L (1, 0, 1)-ish exactly (p R L along each of the two axes, within
    !! the geometry's interpolation error, which is also the area's); on a flat
    !! element the corner shares are -A/12 and the mid-side A/3 of p A.
    real(wp) :: x(3, NN), ang, fsum(3), area, q(3)
    real(wp), allocatable :: fe(:)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp), parameter :: P = 2.5_wp
    integer :: i
    call shell_data(0.1_wp, E_MOD, NU, sec, mat)
    mat%density = 3.0_wp
    ! flat 2 x 1 rectangle in the XY plane, normal +Z
    do i = 1, NN
       x(:, i) = [1.0_wp + XI_NODE(i), 0.5_wp*(1.0_wp + ETA_NODE(i)), 0.0_wp]
    end do
    call element_distributed_load(ET_S8R, x, sec, DLOAD_P, P, fe, q, error)
    call check(.not. allocated(error), 'S8R pressure without error')
    area = 2.0_wp
    do i = 1, NN
       call check_close(fe(6*i - 3), -P*area*merge(-1.0_wp/12, 1.0_wp/3, i <= 4), TOL*P*area, 'S8R flat pressure share')
       call check(all(fe(6*i - 5:6*i - 4) == 0.0_wp) .and. all(fe(6*i - 2:6*i) == 0.0_wp), 'S8R pressure along the normal')
    end do
    call element_gravity_load(ET_S8R, x, sec, mat, [0.0_wp, -9.0_wp, 0.0_wp], fe, q, error)
    call check(.not. allocated(error), 'S8R gravity without error')
    call check_rel(sum(fe(2::6)), -9.0_wp*3.0_wp*0.1_wp*area, TOL, 'S8R self weight total')
    ! a curved element: quarter cylinder, axis Y, radius 2, length 1, nodes counter-clockwise
    ! seen from outside (normal outward): x = R sin a, z = R cos a, a from 0 to 90°
    do i = 1, NN
       ang = (1.0_wp + XI_NODE(i))*PI/4
       x(:, i) = [2.0_wp*sin(ang), 0.5_wp*(1.0_wp + ETA_NODE(i)), 2.0_wp*cos(ang)]
    end do
    call element_distributed_load(ET_S8R, x, sec, DLOAD_P, P, fe, q, error)
    call check(.not. allocated(error), 'S8R curved pressure without error')
    fsum = [sum(fe(1::6)), sum(fe(2::6)), sum(fe(3::6))]
    ! the parabolic arc through the three nodes: ∫ n dA = (x, 0, z) extents × L exactly, = (R, 0, R) L
    call check_rel(fsum(1), -P*2.0_wp*1.0_wp, TOL*10, 'S8R curved pressure resultant x')
    call check_rel(fsum(3), -P*2.0_wp*1.0_wp, TOL*10, 'S8R curved pressure resultant z')
    call check(abs(fsum(2)) <= TOL*10*P, 'S8R curved pressure: none along the axis')
  end subroutine test_loads

  subroutine test_errors()
    !! Bad data: negative thickness, a mid-side node past the far corner (the
    !! Jacobian changes sign), coincident corners.
    real(wp), allocatable :: ke(:, :)
    real(wp) :: x(3, NN)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    integer :: i
    do i = 1, NN
       x(:, i) = [1.0_wp + XI_NODE(i), 0.5_wp*(1.0_wp + ETA_NODE(i)), 0.0_wp]
    end do
    call shell_data(-0.1_wp, E_MOD, NU, sec, mat)
    call element_stiffness(ET_S8R, x, sec, mat, ke, error)
    call check(allocated(error), 'negative thickness refused')
    if (allocated(error)) call check(error%code == EXIT_DECK, 'deck error code')
    if (allocated(error)) deallocate (error)
    call shell_data(0.1_wp, E_MOD, NU, sec, mat)
    x(:, 5) = [1.9_wp, 0.0_wp, 0.0_wp]
    call element_stiffness(ET_S8R, x, sec, mat, ke, error)
    call check(allocated(error), 'misplaced mid-side node refused')
    if (allocated(error)) then
       call check(index(error%message, 'distorted S8R') > 0, 'distorted S8R message')
       deallocate (error)
    end if
    x(:, 5) = [1.0_wp, 0.0_wp, 0.0_wp]
    x(:, 2) = x(:, 1)
    call element_stiffness(ET_S8R, x, sec, mat, ke, error)
    call check(allocated(error), 'coincident corners refused')
  end subroutine test_errors

  subroutine test_full()
    !! S8, the same element with the full 3×3 in-plane rule: one flat thick
    !! element has exactly six zero modes and no near-zero one (no hourglass);
    !! the patch tests (constant membrane strain on the distorted patch,
    !! membrane and curvature on the parallelograms) exact to round-off; the
    !! free patch has six zero modes; constant curvature on the distorted
    !! patch within S8R's bounds (measured 5.6e-3, 3.0e-2, 7.6e-2: not exact,
    !! the serendipity space). K_S8 - K_S8R of one element is not
    !! semi-definite (the two rules are not ordered element by element: its
    !! smallest eigenvalue is printed); that S8 is the stiffer on a mesh is
    !! stated by tests/decks/s8_cantilever.deck.
    real(wp), allocatable :: ke8(:, :), ker(:, :)
    real(wp) :: x(3, NN), w(NDOF)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    et = ET_S8
    x = element_nodes(.false.)
    call shell_data(THICKNESSES(1), E_MOD, NU, sec, mat)
    call element_stiffness(ET_S8, x, sec, mat, ke8, error)
    call check(.not. allocated(error), 'S8 stiffness without error')
    if (allocated(error)) return
    call check(modes_below(ke8, ZERO_EIG) == 6, 'flat S8: exactly six zero eigenvalues')
    call check(modes_below(ke8, WEAK_EIG) == 6, 'flat S8: no near-zero mode (no hourglass)')
    call element_stiffness(ET_S8R, x, sec, mat, ker, error)
    if (allocated(error)) return
    w = eigenvalues(ke8 - ker)
    write (*, '(a,es10.2)') 'S8 - S8R: smallest eigenvalue / max |K| ', w(1)/maxval(abs(ke8))
    call test_free_patch()
    call test_patch()
    et = ET_S8R
  end subroutine test_full
end program test_shell8
