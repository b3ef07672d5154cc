module superjoin_elements_materials
  !! The elasticity of a material at a point: the 6×6 stiffness D (Voigt order
  !! 11, 22, 33, 12, 13, 23, engineering shear strains) in global axes.
  !!
  !! - Isotropic (*ELASTIC, TYPE=ISO): from E and ν.
  !! - Orthotropic and anisotropic (TYPE=ORTHO, ENGINEERING CONSTANTS, ANISO):
  !!   the material's D in its material axes, turned into global axes by the
  !!   section's *ORIENTATION: D = Tᵀ D' T, T the strain transformation
  !!   (ε' = T ε, Voigt, engineering shears) of the frame whose rows are the
  !!   local axes. A rectangular system has one frame; a cylindrical one
  !!   (radial, tangential, axial about the axis a→b) is evaluated at each
  !!   integration point, as CalculiX does (transformatrix at the point's
  !!   global coordinates). Without an orientation the material axes are the
  !!   global ones.
  !!
  !! Also the input side: D of the engineering constants (the compliance
  !! inverted), Abaqus's packed orders of ORTHO (9) and ANISO (21) constants,
  !! and the positive-definiteness test of the deck's checks.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: material_t, orientation_t, MAT_ISO
  implicit none (type, external)
  private

  public :: elasticity, material_stiffness, material_frame, rotate_stiffness
  public :: ortho_stiffness, aniso_stiffness, engineering_compliance, leading_minor_failure, spd_solve

  real(wp), parameter :: AXIS_TOL = 1.0e-10_wp
    !! A point closer to a cylindrical system's axis than this (relative) takes
    !! an arbitrary radial direction normal to the axis (as CalculiX).

contains

  pure function elasticity(mat) result(d)
    !! The stiffness of material mat in its material axes: isotropic from E
    !! and ν (engineering shear strains), otherwise the material's d.
    type(material_t), intent(in) :: mat
    real(wp) :: d(6, 6), lam, g
    integer :: i
    if (mat%kind /= MAT_ISO) then
       d = mat%d
       return
    end if
    lam = mat%e*mat%nu/((1.0_wp + mat%nu)*(1.0_wp - 2.0_wp*mat%nu))
    g = mat%e/(2.0_wp*(1.0_wp + mat%nu))
    d = 0.0_wp
    d(1:3, 1:3) = lam
    do i = 1, 3
       d(i, i) = lam + 2.0_wp*g
       d(i + 3, i + 3) = g
    end do
  end function elasticity

  pure function material_stiffness(mat, x, axes) result(d)
    !! D of material mat in global axes at the point x(3): its material axes
    !! are those of axes (absent: the global axes; an isotropic material
    !! ignores them).
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: x(3)
    type(orientation_t), intent(in), optional :: axes
    real(wp) :: d(6, 6)
    d = elasticity(mat)
    if (mat%kind == MAT_ISO .or. .not. present(axes)) return
    d = rotate_stiffness(d, material_frame(axes, x))
  end function material_stiffness

  pure function material_frame(axes, x) result(q)
    !! The rows of q are the local axes of system axes at the point x:
    !! rectangular its q; cylindrical radial (from the axis a→b to x),
    !! tangential, axial (CalculiX's transformatrix, with its choice of a
    !! radial direction for a point on the axis).
    type(orientation_t), intent(in) :: axes
    real(wp), intent(in) :: x(3)
    real(wp) :: q(3, 3), e1(3), e3(3)
    if (.not. axes%cylindrical) then
       q = axes%q
       return
    end if
    e3 = (axes%b - axes%a)/norm2(axes%b - axes%a)
    e1 = (x - axes%a) - dot_product(x - axes%a, e3)*e3
    if (norm2(e1) < AXIS_TOL) then
       if (abs(e3(1)) > AXIS_TOL) then
          e1 = [-e3(2)/e3(1), 1.0_wp, 0.0_wp]
       else if (abs(e3(2)) > AXIS_TOL) then
          e1 = [0.0_wp, -e3(3)/e3(2), 1.0_wp]
       else
          e1 = [1.0_wp, 0.0_wp, -e3(1)/e3(3)]
       end if
    end if
    e1 = e1/norm2(e1)
    q(1, :) = e1
    q(2, :) = [e3(2)*e1(3) - e3(3)*e1(2), e3(3)*e1(1) - e3(1)*e1(3), e3(1)*e1(2) - e3(2)*e1(1)]
    q(3, :) = e3
  end function material_frame

  pure function rotate_stiffness(dl, q) result(d)
    !! D = Tᵀ dl T: the stiffness dl of local axes (rows of q) in global
    !! axes; column k of T is the local Voigt strain of the global unit
    !! strain k (engineering shears).
    real(wp), intent(in) :: dl(6, 6), q(3, 3)
    real(wp) :: d(6, 6), t(6, 6), eps(3, 3), loc(3, 3)
    integer, parameter :: VI(6) = [1, 2, 3, 1, 1, 2], VJ(6) = [1, 2, 3, 2, 3, 3]
    integer :: k, m
    do k = 1, 6
       eps = 0.0_wp
       if (k <= 3) then
          eps(k, k) = 1.0_wp
       else
          eps(VI(k), VJ(k)) = 0.5_wp
          eps(VJ(k), VI(k)) = 0.5_wp
       end if
       loc = matmul(q, matmul(eps, transpose(q)))
       do m = 1, 6
          t(m, k) = merge(1.0_wp, 2.0_wp, m <= 3)*loc(VI(m), VJ(m))
       end do
    end do
    d = matmul(transpose(t), matmul(dl, t))
  end function rotate_stiffness

  pure function ortho_stiffness(c) result(d)
    !! D of TYPE=ORTHO: c = D1111, D1122, D2222, D1133, D2233, D3333, D1212,
    !! D1313, D2323 (Abaqus and CalculiX).
    real(wp), intent(in) :: c(9)
    real(wp) :: d(6, 6)
    d = 0.0_wp
    d(1, 1) = c(1)
    d(1, 2) = c(2)
    d(2, 2) = c(3)
    d(1, 3) = c(4)
    d(2, 3) = c(5)
    d(3, 3) = c(6)
    d(4, 4) = c(7)
    d(5, 5) = c(8)
    d(6, 6) = c(9)
    d(2, 1) = d(1, 2)
    d(3, 1) = d(1, 3)
    d(3, 2) = d(2, 3)
  end function ortho_stiffness

  pure function aniso_stiffness(c) result(d)
    !! D of TYPE=ANISO: the upper triangle by columns, c = D1111, D1122,
    !! D2222, D1133, D2233, D3333, D1112, D2212, D3312, D1212, D1113, …,
    !! D2323 (Abaqus and CalculiX; Voigt order 11, 22, 33, 12, 13, 23).
    real(wp), intent(in) :: c(21)
    real(wp) :: d(6, 6)
    integer :: i, j, k
    k = 0
    do j = 1, 6
       do i = 1, j
          k = k + 1
          d(i, j) = c(k)
          d(j, i) = c(k)
       end do
    end do
  end function aniso_stiffness

  pure function engineering_compliance(c) result(s)
    !! The compliance of TYPE=ENGINEERING CONSTANTS c = E1, E2, E3, ν12, ν13,
    !! ν23, G12, G13, G23 (ν_ij: the contraction along j of a stress along i,
    !! ν_ij/E_i = ν_ji/E_j).
    real(wp), intent(in) :: c(9)
    real(wp) :: s(6, 6)
    s = 0.0_wp
    s(1, 1) = 1.0_wp/c(1)
    s(2, 2) = 1.0_wp/c(2)
    s(3, 3) = 1.0_wp/c(3)
    s(1, 2) = -c(4)/c(1)
    s(1, 3) = -c(5)/c(1)
    s(2, 3) = -c(6)/c(2)
    s(2, 1) = s(1, 2)
    s(3, 1) = s(1, 3)
    s(3, 2) = s(2, 3)
    s(4, 4) = 1.0_wp/c(7)
    s(5, 5) = 1.0_wp/c(8)
    s(6, 6) = 1.0_wp/c(9)
  end function engineering_compliance

  pure integer function leading_minor_failure(a) result(k)
    !! 0 when the symmetric a is positive definite, else the order of its
    !! first leading minor that is not positive (Cholesky's pivots, relative
    !! to the diagonal: a pivot below 1e-12 of its diagonal term counts as 0).
    real(wp), intent(in) :: a(:, :)
    real(wp) :: l(size(a, 1), size(a, 1)), p
    integer :: j
    l = 0.0_wp
    do j = 1, size(a, 1)
       p = a(j, j) - dot_product(l(j, 1:j - 1), l(j, 1:j - 1))
       if (.not. (p > 1.0e-12_wp*abs(a(j, j)))) then
          k = j
          return
       end if
       l(j, j) = sqrt(p)
       l(j + 1:, j) = (a(j + 1:, j) - matmul(l(j + 1:, 1:j - 1), l(j, 1:j - 1)))/l(j, j)
    end do
    k = 0
  end function leading_minor_failure

  pure function spd_solve(m, b) result(x)
    !! x = m⁻¹ b for a symmetric positive definite m (Gauss-Jordan
    !! elimination; no pivoting is needed).
    real(wp), intent(in) :: m(:, :), b(:, :)
    real(wp) :: x(size(b, 1), size(b, 2))
    real(wp) :: a(size(m, 1), size(m, 2)), f
    integer :: i, k
    a = m
    x = b
    do i = 1, size(a, 1)
       f = a(i, i)
       a(i, :) = a(i, :)/f
       x(i, :) = x(i, :)/f
       do k = 1, size(a, 1)
          if (k == i) cycle
          f = a(k, i)
          a(k, :) = a(k, :) - f*a(i, :)
          x(k, :) = x(k, :) - f*x(i, :)
       end do
    end do
  end function spd_solve
end module superjoin_elements_materials
