program test_materials
  !! Unit tests of the material stiffness (superjoin_elements_materials):
  !! - ENGINEERING CONSTANTS: D, the inverse of the compliance, equals the
  !!   closed form CalculiX writes in elastics.f (D1111 = E1 (1 - ν23 ν32) γ,
  !!   D1122 = E1 (ν21 + ν31 ν23) γ, …, γ = 1/(1 - ν12 ν21 - ν23 ν32 - ν31 ν13
  !!   - 2 ν21 ν32 ν13)), and its shear terms are G12, G13, G23;
  !! - ANISO's packing: the diagonal terms at 1, 3, 6, 10, 15, 21; ORTHO's nine;
  !! - turning D: an isotropic D is unchanged by any frame; a quarter turn about
  !!   z swaps D1111 and D2222, D1313 and D2323; turning by q and back by qᵀ
  !!   gives D again; the strain energy of a strain is the same in both frames;
  !! - the cylindrical frame at a point: radial, tangential, axial, orthonormal
  !!   and right-handed, CalculiX's choice on the axis;
  !! - positive definiteness: the first failing leading minor.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: material_t, orientation_t, MAT_ORTHO
  use superjoin_elements_materials, only: elasticity, material_stiffness, material_frame, rotate_stiffness, &
       ortho_stiffness, aniso_stiffness, engineering_compliance, leading_minor_failure, spd_solve
  use superjoin_testing, only: check, check_close, check_rel, finish
  implicit none (type, external)

  real(wp), parameter :: TOL = 1.0e-12_wp
  real(wp), parameter :: C(9) = [200000.0_wp, 100000.0_wp, 50000.0_wp, 0.3_wp, 0.2_wp, 0.25_wp, &
       40000.0_wp, 30000.0_wp, 20000.0_wp]

  call test_engineering()
  call test_packing()
  call test_turning()
  call test_cylinder()
  call finish()

contains

  subroutine test_engineering()
    real(wp) :: d(6, 6), eye(6, 6), e1, e2, e3, n12, n13, n23, n21, n31, n32, g
    integer :: i
    eye = 0.0_wp
    do i = 1, 6
       eye(i, i) = 1.0_wp
    end do
    d = spd_solve(engineering_compliance(C), eye)
    e1 = C(1); e2 = C(2); e3 = C(3); n12 = C(4); n13 = C(5); n23 = C(6)
    n21 = n12*e2/e1; n31 = n13*e3/e1; n32 = n23*e3/e2
    g = 1.0_wp/(1.0_wp - n12*n21 - n23*n32 - n31*n13 - 2.0_wp*n21*n32*n13)
    call check_rel(d(1, 1), e1*(1.0_wp - n23*n32)*g, TOL, 'engineering D1111 (CalculiX elastics.f)')
    call check_rel(d(1, 2), e1*(n21 + n31*n23)*g, TOL, 'engineering D1122')
    call check_rel(d(2, 2), e2*(1.0_wp - n13*n31)*g, TOL, 'engineering D2222')
    call check_rel(d(1, 3), e1*(n31 + n21*n32)*g, TOL, 'engineering D1133')
    call check_rel(d(2, 3), e2*(n32 + n12*n31)*g, TOL, 'engineering D2233')
    call check_rel(d(3, 3), e3*(1.0_wp - n12*n21)*g, TOL, 'engineering D3333')
    call check_rel(d(4, 4), C(7), TOL, 'engineering D1212 = G12')
    call check_rel(d(5, 5), C(8), TOL, 'engineering D1313 = G13')
    call check_rel(d(6, 6), C(9), TOL, 'engineering D2323 = G23')
    call check(leading_minor_failure(d) == 0, 'engineering D positive definite')
  end subroutine test_engineering

  subroutine test_packing()
    real(wp) :: v(21), d(6, 6)
    integer :: k
    v = [(real(k, wp), k = 1, 21)]
    d = aniso_stiffness(v)
    call check(all([d(1, 1), d(2, 2), d(3, 3), d(4, 4), d(5, 5), d(6, 6)] == [1, 3, 6, 10, 15, 21]*1.0_wp), &
         'ANISO diagonal at 1, 3, 6, 10, 15, 21')
    call check(d(1, 4) == 7.0_wp .and. d(4, 1) == 7.0_wp .and. d(3, 4) == 9.0_wp .and. d(5, 6) == 20.0_wp, &
         'ANISO D1112 = 7, D3312 = 9, D1323 = 20, symmetric')
    d = ortho_stiffness(C)
    call check(d(1, 2) == C(2) .and. d(2, 1) == C(2) .and. d(1, 3) == C(4) .and. d(2, 3) == C(5) .and. &
         d(4, 4) == C(7) .and. d(6, 6) == C(9) .and. d(1, 4) == 0.0_wp, 'ORTHO nine terms in place')
    d(2, 2) = 0.5_wp*d(1, 2)**2/d(1, 1)
    call check(leading_minor_failure(d) == 2, 'D1122 too large: the 2x2 minor fails')
  end subroutine test_packing

  subroutine test_turning()
    type(material_t) :: iso
    real(wp) :: d(6, 6), q(3, 3), dt(6, 6), eps(6), epsl(6)
    iso%e = 210000.0_wp
    iso%nu = 0.3_wp
    q = turned_frame()
    dt = rotate_stiffness(elasticity(iso), q)
    call check_close(maxval(abs(dt - elasticity(iso))), 0.0_wp, TOL*iso%e, 'isotropic D unchanged by a frame')
    d = ortho_stiffness(C)
    q = reshape([0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])  ! rows e1 = Y, e2 = -X
    dt = rotate_stiffness(d, q)
    call check_rel(dt(2, 2), d(1, 1), TOL, 'quarter turn about z: D2222 = D1111 of the material')
    call check_rel(dt(1, 1), d(2, 2), TOL, 'quarter turn about z: D1111 = D2222 of the material')
    call check_rel(dt(6, 6), d(5, 5), TOL, 'quarter turn about z: D2323 = D1313 of the material')
    q = turned_frame()
    dt = rotate_stiffness(rotate_stiffness(d, q), transpose(q))
    call check_close(maxval(abs(dt - d)), 0.0_wp, TOL*d(1, 1), 'turned by q and back: D again')
    eps = [1.0e-3_wp, -2.0e-4_wp, 3.0e-4_wp, 5.0e-4_wp, -1.0e-4_wp, 2.0e-4_wp]
    epsl = local_strain(q, eps)
    call check_rel(dot_product(eps, matmul(rotate_stiffness(d, q), eps)), dot_product(epsl, matmul(d, epsl)), &
         TOL, 'strain energy the same in global and material axes')
  end subroutine test_turning

  subroutine test_cylinder()
    type(orientation_t) :: ax
    type(material_t) :: mat
    real(wp) :: q(3, 3), d(6, 6)
    ax%cylindrical = .true.
    ax%a = [1.0_wp, 1.0_wp, 0.0_wp]
    ax%b = [1.0_wp, 1.0_wp, 2.0_wp]
    q = material_frame(ax, [1.0_wp, 3.0_wp, 5.0_wp])
    call check_close(maxval(abs(q(1, :) - [0.0_wp, 1.0_wp, 0.0_wp])), 0.0_wp, TOL, 'cylindrical: radial axis')
    call check_close(maxval(abs(q(2, :) - [-1.0_wp, 0.0_wp, 0.0_wp])), 0.0_wp, TOL, 'cylindrical: tangential axis')
    call check_close(maxval(abs(q(3, :) - [0.0_wp, 0.0_wp, 1.0_wp])), 0.0_wp, TOL, 'cylindrical: axial axis')
    q = material_frame(ax, [1.0_wp, 1.0_wp, 7.0_wp])
    call check_close(maxval(abs(matmul(q, transpose(q)) - identity())), 0.0_wp, TOL, &
         'cylindrical: a point on the axis takes an orthonormal frame')
    call check_close(maxval(abs(q(1, :) - [1.0_wp, 0.0_wp, 0.0_wp])), 0.0_wp, TOL, &
         'cylindrical: on the axis CalculiX''s radial direction (axis along z: (1, 0, 0))')
    mat%kind = MAT_ORTHO
    mat%d = ortho_stiffness(C)
    d = material_stiffness(mat, [1.0_wp, 3.0_wp, 5.0_wp], ax)
    call check_rel(d(2, 2), C(1), TOL, 'cylindrical: at (1, 3) radial is global y, D2222 = D1111 of the material')
    d = material_stiffness(mat, [1.0_wp, 3.0_wp, 5.0_wp])
    call check_rel(d(1, 1), C(1), TOL, 'no axes: the material axes are the global ones')
  end subroutine test_cylinder

  pure function turned_frame() result(q)
    !! Rows (1, 2, 2)/3, (-2, -1, 2)/3, (2, -2, 1)/3: a right-handed frame.
    real(wp) :: q(3, 3)
    q = transpose(reshape([1.0_wp, 2.0_wp, 2.0_wp, -2.0_wp, -1.0_wp, 2.0_wp, 2.0_wp, -2.0_wp, 1.0_wp], [3, 3]))/3.0_wp
  end function turned_frame

  pure function identity() result(m)
    real(wp) :: m(3, 3)
    m = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
  end function identity

  pure function local_strain(q, eps) result(epsl)
    !! The Voigt strain (engineering shears) eps in the frame whose rows are q.
    real(wp), intent(in) :: q(3, 3), eps(6)
    real(wp) :: epsl(6), t(3, 3), l(3, 3)
    t = reshape([eps(1), 0.5_wp*eps(4), 0.5_wp*eps(5), 0.5_wp*eps(4), eps(2), 0.5_wp*eps(6), &
         0.5_wp*eps(5), 0.5_wp*eps(6), eps(3)], [3, 3])
    l = matmul(q, matmul(t, transpose(q)))
    epsl = [l(1, 1), l(2, 2), l(3, 3), 2.0_wp*l(1, 2), 2.0_wp*l(1, 3), 2.0_wp*l(2, 3)]
  end function local_strain
end program test_materials
