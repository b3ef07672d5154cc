program test_mindlin
  !! Unit tests of the thick plates MITC4/MITC3 (superjoin_elements_mindlin) and
  !! the thick shells S4R/S3R built on them: the eigenvalues of one element
  !! (exactly six rigid modes, no spurious zero-energy mode, at thick and thin
  !! thicknesses), that the null space is the rigid motions, exact energy and
  !! resultants for constant-curvature and constant-shear fields on distorted
  !! elements, the constant-curvature patch test on a distorted mesh, data checks,
  !! and the section's transverse shear stiffness; moments at the 2×2 points of
  !! MITC4 and extrapolated to its nodes, exact for a linear curvature field.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, ET_S4R, ET_S3R, SEC_SHELL
  use superjoin_elements, only: element_stiffness, shell_resultants
  use superjoin_elements_mindlin, only: mindlin_stiffness, mindlin_resultants, default_shear_stiffness
  use superjoin_elements_mindlin, only: mindlin_point_resultants
  use superjoin_elements_plate, only: bending_rigidity
  use superjoin_testing, only: check, check_close, check_rel, finish
  use test_lapack, only: eigenvalues, dgesv
  use test_random, only: set_seed, rnd_in
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-12_wp          !! round-off on one element, relative
  real(wp), parameter :: TOL_SOLVE = 1.0e-10_wp    !! exact discrete answers after a solve, relative
  real(wp), parameter :: ZERO_EIG = 1.0e-12_wp     !! a zero eigenvalue, relative to the largest
  real(wp), parameter :: MIN_EIG = 1.0e-11_wp      !! the smallest deformation eigenvalue must exceed this × largest
  integer, parameter :: NDN = 3
  real(wp), parameter :: E_MOD = 2.1e5_wp, NU = 0.3_wp
  integer, parameter :: NRANDOM = 20               !! random elements per check
  real(wp), parameter :: THICKNESSES(3) = [0.5_wp, 0.05_wp, 0.002_wp]   !! relative to a unit element

  call set_seed(20261124)
  call test_plate_eigenvalues(3)
  call test_plate_eigenvalues(4)
  call test_shell_eigenvalues(ET_S3R, 3)
  call test_shell_eigenvalues(ET_S4R, 4)
  call test_constant_fields(3)
  call test_constant_fields(4)
  call test_patch(.false.)
  call test_patch(.true.)
  call test_errors()
  call test_section_shear()
  call test_point_moments()
  call finish()

contains

  subroutine distorted_element(n, xl, size_e)
    !! A randomly distorted triangle (n = 3) or convex quadrilateral (n = 4) of size about size_e.
    integer, intent(in) :: n
    real(wp), allocatable, intent(out) :: xl(:, :)
    real(wp), intent(in) :: size_e
    real(wp) :: shift(2)
    integer :: i
    if (n == 3) then
       xl = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.2_wp, 0.3_wp, 0.9_wp], [2, 3])
    else
       xl = reshape([0.0_wp, 0.0_wp, 1.6_wp, 0.3_wp, 1.2_wp, 1.1_wp, 0.1_wp, 0.8_wp], [2, 4])
    end if
    shift = [rnd_in(-2.0_wp, 2.0_wp), rnd_in(-2.0_wp, 2.0_wp)]
    do i = 1, n
       xl(:, i) = size_e*(xl(:, i) + [rnd_in(-0.15_wp, 0.15_wp), rnd_in(-0.15_wp, 0.15_wp)] + shift)
    end do
  end subroutine distorted_element

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

  subroutine count_modes(k, nzero, what)
    !! Check that k has exactly nzero eigenvalues below ZERO_EIG × the largest and
    !! the others above MIN_EIG × the largest.
    real(wp), intent(in) :: k(:, :)
    integer, intent(in) :: nzero
    character(*), intent(in) :: what
    real(wp), allocatable :: w(:)
    character(len=160) :: buf
    allocate (w(size(k, 1)))   ! before the assignment: gfortran warns of its bounds otherwise
    w = eigenvalues(k)
    write (buf, '(a,es10.2,a,es10.2)') ' eig(nzero)/max', abs(w(nzero))/w(size(w)), ' eig(nzero+1)/max', &
         w(nzero + 1)/w(size(w))
    call check(all(abs(w(1:nzero)) <= ZERO_EIG*w(size(w))), what//': zero eigenvalues'//trim(buf))
    call check(w(nzero + 1) > MIN_EIG*w(size(w)), what//': no spurious mode'//trim(buf))
  end subroutine count_modes

  subroutine test_plate_eigenvalues(n)
    !! The plate part alone: three rigid modes (w, θx, θy) and no other zero mode.
    integer, intent(in) :: n
    real(wp), allocatable :: xl(:, :), kb(:, :)
    type(error_t), allocatable :: error
    integer :: it, jt
    character(len=40) :: tag
    do jt = 1, size(THICKNESSES)
       do it = 1, NRANDOM
          call distorted_element(n, xl, 10.0_wp**rnd_in(-1.0_wp, 1.0_wp))
          call mindlin_stiffness(xl, THICKNESSES(jt)*maxval(abs(xl(:, 2) - xl(:, 1))), E_MOD, NU, &
               default_shear_stiffness(THICKNESSES(jt), E_MOD, NU), kb, error)
          call check(.not. allocated(error), 'plate stiffness without error')
          if (allocated(error)) return
          write (tag, '(a,i0,a,es8.1)') 'MITC', n, ' plate t/L ', THICKNESSES(jt)
          call check(maxval(abs(kb - transpose(kb))) == 0.0_wp, trim(tag)//': exactly symmetric')
          call count_modes(kb, NDN, trim(tag))
       end do
    end do
  end subroutine test_plate_eigenvalues

  subroutine test_shell_eigenvalues(etype, n)
    !! The whole shell element (membrane with drilling + thick plate) in an
    !! oblique plane: exactly six zero eigenvalues, and K r = 0 for the six
    !! rigid motions r (so the zero modes are the rigid ones).
    integer, intent(in) :: etype, n
    real(wp), allocatable :: xl(:, :), ke(:, :), x(:, :), r(:)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp) :: rot(3, 3), origin(3), u(3), th(3)
    integer :: it, jt, i, mode
    character(len=40) :: tag
    mat%e = E_MOD
    mat%nu = NU
    sec%kind = SEC_SHELL
    allocate (x(3, n), r(6*n))
    do jt = 1, size(THICKNESSES)
       do it = 1, NRANDOM
          call distorted_element(n, xl, 1.0_wp)
          rot = random_rotation()
          origin = [rnd_in(-3.0_wp, 3.0_wp), rnd_in(-3.0_wp, 3.0_wp), rnd_in(-3.0_wp, 3.0_wp)]
          do i = 1, n
             x(:, i) = origin + matmul(transpose(rot), [xl(1, i), xl(2, i), 0.0_wp])
          end do
          sec%thickness = THICKNESSES(jt)
          call element_stiffness(etype, x, sec, mat, ke, error)
          call check(.not. allocated(error), 'shell stiffness without error')
          if (allocated(error)) return
          write (tag, '(a,a,es8.1)') merge('S3R', 'S4R', n == 3), ' t/L ', THICKNESSES(jt)
          call count_modes(ke, 6, trim(tag))
          do mode = 1, 6
             th = 0.0_wp
             u = 0.0_wp
             if (mode <= 3) then
                u(mode) = 1.0_wp
             else
                th(mode - 3) = 1.0_wp
             end if
             do i = 1, n
                ! u = u0 + θ × (x - origin), rotations θ
                r(6*i - 5:6*i - 3) = u + [th(2)*(x(3, i) - origin(3)) - th(3)*(x(2, i) - origin(2)), &
                     th(3)*(x(1, i) - origin(1)) - th(1)*(x(3, i) - origin(3)), &
                     th(1)*(x(2, i) - origin(2)) - th(2)*(x(1, i) - origin(1))]
                r(6*i - 2:6*i) = th
             end do
             call check(norm2(matmul(ke, r)) <= TOL*maxval(abs(ke))*norm2(r)*10, trim(tag)//': rigid motion free')
          end do
       end do
    end do
  end subroutine test_shell_eigenvalues

  pure function field_dofs(c, beta, xl) result(u)
    !! Nodal (w, θx, θy) of w = c1 + c2 x + c3 y + c4 x²/2 + c5 x y + c6 y²/2 with
    !! the normal's rotation β = beta(1:2) + beta(3:4) x + beta(5:6) y (βx = θy, βy = -θx).
    real(wp), intent(in) :: c(6), beta(6), xl(:, :)
    real(wp) :: u(NDN*size(xl, 2))
    real(wp) :: x, y, b(2)
    integer :: i
    do i = 1, size(xl, 2)
       x = xl(1, i)
       y = xl(2, i)
       b = beta(1:2) + beta(3:4)*x + beta(5:6)*y
       u(NDN*i - 2) = c(1) + c(2)*x + c(3)*y + c(4)*x*x/2 + c(5)*x*y + c(6)*y*y/2
       u(NDN*i - 1) = -b(2)
       u(NDN*i) = b(1)
    end do
  end function field_dofs

  real(wp) function area_of(xl)
    !! Area of a triangle or quadrilateral (shoelace).
    real(wp), intent(in) :: xl(:, :)
    integer :: i, j
    area_of = 0.0_wp
    do i = 1, size(xl, 2)
       j = mod(i, size(xl, 2)) + 1
       area_of = area_of + 0.5_wp*(xl(1, i)*xl(2, j) - xl(1, j)*xl(2, i))
    end do
  end function area_of

  real(wp) function longest_side(xl)
    !! Longest side of a polygon.
    real(wp), intent(in) :: xl(:, :)
    integer :: i
    longest_side = 0.0_wp
    do i = 1, size(xl, 2)
       longest_side = max(longest_side, norm2(xl(:, mod(i, size(xl, 2)) + 1) - xl(:, i)))
    end do
  end function longest_side

  subroutine test_constant_fields(n)
    !! Constant curvature without shear (w quadratic, β = -∇w) and constant shear
    !! without curvature (w linear, β constant) on distorted elements: the energy
    !! is exactly A κᵀ D_b κ, resp. A γᵀ D_s γ, and the resultants are D_b κ, 0
    !! resp. 0, D_s γ.
    integer, intent(in) :: n
    real(wp), allocatable :: xl(:, :), kb(:, :)
    type(error_t), allocatable :: error
    real(wp) :: c(6), beta(6), kap(3), gam(2), ks(2), kse(2), db(3, 3), m(3), q(2), u(NDN*n), t, area
    integer :: it, k
    character(len=8) :: tag
    write (tag, '(a,i0)') 'MITC', n
    do it = 1, NRANDOM
       call distorted_element(n, xl, 10.0_wp**rnd_in(-1.0_wp, 1.0_wp))
       t = 0.1_wp*maxval(abs(xl(:, 2) - xl(:, 1)))
       ks = [rnd_in(0.5_wp, 2.0_wp), rnd_in(0.5_wp, 2.0_wp)]*default_shear_stiffness(t, E_MOD, NU)
       call mindlin_stiffness(xl, t, E_MOD, NU, ks, kb, error)
       if (allocated(error)) then
          call check(.false., tag//' stiffness')
          return
       end if
       db = bending_rigidity(t, E_MOD, NU)
       area = area_of(xl)
       ! constant curvature: β = -∇w = -(c2 + c4 x + c5 y, c3 + c5 x + c6 y)
       ! coefficients scaled so that every term is of the same size on the element
       ! (a dominant rigid part would only measure the round-off of its cancellation)
       c = [(rnd_in(-1.0_wp, 1.0_wp), k=1, 6)]
       c(1) = c(1)*maxval(abs(xl))**2
       c(2:3) = c(2:3)*maxval(abs(xl))
       beta = -[c(2), c(3), c(4), c(5), c(5), c(6)]
       kap = [beta(3), beta(6), beta(5) + beta(4)]
       u = field_dofs(c, beta, xl)
       ! the shear stiffness, ks L²/D times the bending one, cancels to its round-off
       call check_rel(dot_product(u, matmul(kb, u)), area*dot_product(kap, matmul(db, kap)), &
            TOL*max(1.0_wp, maxval(ks)*maxval(abs(xl))**2/db(1, 1)), tag//': constant-curvature energy')
       call mindlin_resultants(xl, t, E_MOD, NU, ks, u, m, q, error)
       call check(maxval(abs(m - matmul(db, kap))) <= TOL*10*maxval(abs(matmul(db, kap))), tag//': moments')
       call check(maxval(abs(q)) <= TOL*10*maxval(abs(matmul(db, kap)))/maxval(abs(xl)), tag//': no shear force')
       ! constant shear: w = c1 + c2 x + c3 y, β constant
       c(4:6) = 0.0_wp
       beta(3:6) = 0.0_wp
       beta(1:2) = [rnd_in(-1.0_wp, 1.0_wp), rnd_in(-1.0_wp, 1.0_wp)]
       gam = c(2:3) + beta(1:2)
       u = field_dofs(c, beta, xl)
       ! the triangle's shear stiffness is scaled by t²/(t² + 0.1 h²) (stabilized MITC3)
       kse = ks
       if (n == 3) kse = ks*t**2/(t**2 + 0.1_wp*longest_side(xl)**2)
       call check_rel(dot_product(u, matmul(kb, u)), area*sum(kse*gam**2), TOL*10, tag//': constant-shear energy')
       call mindlin_resultants(xl, t, E_MOD, NU, ks, u, m, q, error)
       call check(maxval(abs(q - kse*gam)) <= TOL*10*maxval(abs(kse*gam)), tag//': shear forces')
       call check(maxval(abs(m)) <= TOL*10*maxval(abs(ks*gam))*maxval(abs(xl)), tag//': no moments')
    end do
  end subroutine test_constant_fields

  subroutine test_patch(tri)
    !! MacNeal-Harder patch (0.24 x 0.12, five distorted quadrilaterals, or each
    !! split into two triangles): the boundary nodes prescribed to a
    !! constant-curvature field, the interior nodes must take it exactly.
    logical, intent(in) :: tri
    real(wp), parameter :: XP(2, 8) = reshape([0.0_wp, 0.0_wp, 0.24_wp, 0.0_wp, 0.24_wp, 0.12_wp, &
         0.0_wp, 0.12_wp, 0.04_wp, 0.02_wp, 0.18_wp, 0.03_wp, 0.16_wp, 0.08_wp, 0.08_wp, 0.08_wp], [2, 8])
    integer, parameter :: QUADS(4, 5) = reshape([1, 2, 6, 5, 2, 3, 7, 6, 3, 4, 8, 7, 4, 1, 5, 8, &
         5, 6, 7, 8], [4, 5])
    integer, parameter :: NNODE = 8, NINNER = 4
    real(wp) :: kg(NDN*NNODE, NDN*NNODE), ug(NDN*NNODE), c(6), beta(6), t, ks(2)
    real(wp), allocatable :: kb(:, :), a(:, :), b(:, :)
    integer, allocatable :: conn(:, :), ipiv(:)
    type(error_t), allocatable :: error
    integer :: e, i, j, info, ne
    integer :: dofs(NDN*4)
    if (tri) then
       allocate (conn(3, 10))
       do e = 1, 5
          conn(:, 2*e - 1) = QUADS([1, 2, 3], e)
          conn(:, 2*e) = QUADS([1, 3, 4], e)
       end do
    else
       conn = QUADS
    end if
    ne = size(conn, 1)
    t = 0.001_wp
    ks = default_shear_stiffness(t, E_MOD, NU)
    kg = 0.0_wp
    do e = 1, size(conn, 2)
       call mindlin_stiffness(XP(:, conn(:, e)), t, E_MOD, NU, ks, kb, error)
       if (allocated(error)) then
          call check(.false., 'patch element')
          return
       end if
       do i = 1, ne
          dofs(NDN*i - 2:NDN*i) = NDN*(conn(i, e) - 1) + [1, 2, 3]
       end do
       kg(dofs(1:NDN*ne), dofs(1:NDN*ne)) = kg(dofs(1:NDN*ne), dofs(1:NDN*ne)) + kb
    end do
    c = [1.0e-3_wp, 2.0e-3_wp, -1.0e-3_wp, 1.0e-3_wp, 0.5e-3_wp, -2.0e-3_wp]
    beta = -[c(2), c(3), c(4), c(5), c(5), c(6)]
    ug = field_dofs(c, beta, XP)
    ! unknowns: the inner nodes 5..8 (DOFs 13..24); right-hand side -K_ib u_b
    a = kg(13:24, 13:24)
    b = reshape(-matmul(kg(13:24, 1:12), ug(1:12)), [12, 1])
    allocate (ipiv(12))
    call dgesv(12, 1, a, 12, ipiv, b, 12, info)
    call check(info == 0, 'patch solve')
    do j = 1, 12
       call check_close(b(j, 1), ug(12 + j), TOL_SOLVE*maxval(abs(ug)), &
            merge('MITC3 patch', 'MITC4 patch', tri))
    end do
  end subroutine test_patch

  subroutine test_errors()
    !! Bad data: negative thickness, zero shear stiffness, a clockwise element.
    real(wp), allocatable :: kb(:, :)
    type(error_t), allocatable :: error
    real(wp) :: xl(2, 4)
    xl = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
    call mindlin_stiffness(xl, -0.1_wp, E_MOD, NU, [1.0_wp, 1.0_wp], kb, error)
    call check(allocated(error), 'negative thickness refused')
    if (allocated(error)) call check(error%code == EXIT_DECK, 'deck error code')
    deallocate (error)
    call mindlin_stiffness(xl, 0.1_wp, E_MOD, NU, [0.0_wp, 1.0_wp], kb, error)
    call check(allocated(error), 'zero shear stiffness refused')
    if (allocated(error)) deallocate (error)
    call mindlin_stiffness(xl(:, [1, 4, 3, 2]), 0.1_wp, E_MOD, NU, [1.0_wp, 1.0_wp], kb, error)
    call check(allocated(error), 'clockwise element refused')
  end subroutine test_errors

  subroutine test_section_shear()
    !! The shell takes the section's K11, K22 when given, else 5/6 G t: the
    !! energy of w = x (γxz = 1) on a 2 x 1 rectangle is 2 K11; its membrane
    !! forces and moments are zero.
    real(wp), allocatable :: ke(:, :)
    type(section_t) :: sec
    type(material_t) :: mat
    type(error_t), allocatable :: error
    real(wp) :: x(3, 4), u(24), res(6)
    integer :: i
    mat%e = E_MOD
    mat%nu = NU
    sec%kind = SEC_SHELL
    sec%thickness = 0.1_wp
    x = reshape([0.0_wp, 0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.0_wp, 2.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], &
         [3, 4])
    u = 0.0_wp
    do i = 1, 4
       u(6*i - 3) = x(1, i)     ! w = x: γxz = 1
    end do
    call element_stiffness(ET_S4R, x, sec, mat, ke, error)
    call check(.not. allocated(error), 'S4R stiffness')
    if (allocated(error)) return
    call check_rel(dot_product(u, matmul(ke, u)), 2.0_wp*sum(default_shear_stiffness(0.1_wp, E_MOD, NU))/2, TOL*10, &
         'default shear stiffness 5/6 G t')
    sec%shear_k = [123.0_wp, 456.0_wp]
    call element_stiffness(ET_S4R, x, sec, mat, ke, error)
    call check_rel(dot_product(u, matmul(ke, u)), 2.0_wp*123.0_wp, TOL*10, 'section K11')
    call shell_resultants(ET_S4R, x, sec, mat, u, res, error)
    call check(.not. allocated(error), 'S4R resultants')
    call check(maxval(abs(res)) <= TOL*123.0_wp, 'constant shear: no membrane forces or moments')
  end subroutine test_section_shear

  subroutine test_point_moments()
    !! mindlin_point_resultants on a rectangular MITC4 (x y is bilinear in ξ, η) with the bilinear
    !! rotation field βx = c1 x y + c2 x, βy = c3 x y + c4 y (w = 0): its
    !! curvatures (c1 y + c2, c3 x + c4, c1 x + c3 y) are linear, so the moments
    !! D_b κ are exact at the Gauss points and, extrapolated bilinearly, at the
    !! nodes.
    real(wp), parameter :: XQ(2, 4) = reshape([0.5_wp, 0.2_wp, 2.5_wp, 0.2_wp, 2.5_wp, 1.4_wp, 0.5_wp, 1.4_wp], [2, 4])
    real(wp), parameter :: C(4) = [1.0e-3_wp, -2.0e-3_wp, 1.5e-3_wp, 5.0e-4_wp]
    real(wp), parameter :: G = 1/sqrt(3.0_wp), T = 0.1_wp
    real(wp), parameter :: XIG(4) = [-G, G, G, -G], ETAG(4) = [-G, -G, G, G]
    real(wp), allocatable :: rp(:, :), rn(:, :)
    type(error_t), allocatable :: error
    real(wp) :: ue(12), db(3, 3), x(2), ex(3), err, scale, sf(4)
    integer :: k
    db = bending_rigidity(T, E_MOD, NU)
    do k = 1, 4
       ! (w, θx, θy) with βx = θy, βy = -θx
       ue(3*k - 2:3*k) = [0.0_wp, -(C(3)*XQ(1, k)*XQ(2, k) + C(4)*XQ(2, k)), C(1)*XQ(1, k)*XQ(2, k) + C(2)*XQ(1, k)]
    end do
    call mindlin_point_resultants(XQ, T, E_MOD, NU, default_shear_stiffness(T, E_MOD, NU), ue, rp, rn, error)
    call check(.not. allocated(error), 'MITC4 point moments without error')
    if (allocated(error)) return
    scale = maxval(abs(rn(1:3, :)))
    err = 0.0_wp
    do k = 1, 4
       sf = 0.25_wp*(1 + [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]*XIG(k))*(1 + [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]*ETAG(k))
       x = matmul(XQ, sf)
       err = max(err, maxval(abs(rp(1:3, k) - matmul(db, kappa(x, C)))))
    end do
    call check(err <= TOL*scale, 'MITC4 linear curvature: moments exact at the Gauss points')
    err = 0.0_wp
    do k = 1, 4
       ex = matmul(db, kappa(XQ(:, k), C))
       err = max(err, maxval(abs(rn(1:3, k) - ex)))
    end do
    call check(err <= TOL*scale, 'MITC4 linear curvature: moments exact at the nodes (extrapolated)')
    call check(maxval(rn(1, :)) - minval(rn(1, :)) > 0.1_wp*scale, 'MITC4 linear curvature: mx does vary')
  end subroutine test_point_moments

  pure function kappa(p, c) result(kp)
    !! Curvatures at p of βx = c1 x y + c2 x, βy = c3 x y + c4 y.
    real(wp), intent(in) :: p(2), c(4)
    real(wp) :: kp(3)
    kp = [c(1)*p(2) + c(2), c(3)*p(1) + c(4), c(1)*p(1) + c(3)*p(2)]
  end function kappa
end program test_mindlin
