module superjoin_elements_beam
  !! Two-node Euler-Bernoulli beams with axial stiffness: B23 (XY plane, DOFs
  !! 1,2,6 per node, bending about Z with I in sec%iz) and B33 (DOFs 1..6 per node,
  !! St. Venant torsion GJ/L with G = E/(2(1+nu))). Bending with displacement
  !! along local y uses Iz, along local z uses Iy. Cubic Hermite bending, linear
  !! axial and twist fields: nodal results are exact for end loads and, with the
  !! consistent loads of beam_load_local, for uniform distributed loads.
  !!
  !! B21 and B31 are the Timoshenko counterparts of B23 and B33: the exact
  !! stiffness of a prismatic member with transverse shear flexibility
  !! (interdependent interpolation, phi = 12 EI/(K L²), K = sec%shear_k or
  !! shear_factor G A per direction), exact for end loads and uniform loads,
  !! free of shear locking, equal to B23/B33 as phi -> 0.
  !!
  !! Local DOFs per node: B23, B21 (u, v, θz); B33, B31 (u, v, w, θx, θy, θz),
  !! node-major.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, ET_B23, ET_B21, ET_B31
  use superjoin_elements_frame, only: beam_frame, require_positive
  implicit none (type, external)
  private

  integer, parameter :: NNODE = 2
  integer, parameter :: ND_B23 = 3, ND_B33 = 6
  real(wp), parameter :: one = 1.0_wp

  type :: beam_props_t
    !! Properties of one beam element, gathered and checked once.
     real(wp) :: r(3, 3) = 0.0_wp   !! rows: local axes
     real(wp) :: length = 0.0_wp
     real(wp) :: ea = 0.0_wp, eiy = 0.0_wp, eiz = 0.0_wp, gj = 0.0_wp
     real(wp) :: phiy = 0.0_wp      !! Timoshenko: 12 EIz/(Ky L²), bending in the x-y plane
     real(wp) :: phiz = 0.0_wp      !! Timoshenko: 12 EIy/(Kz L²), bending in the x-z plane
  end type beam_props_t

  public :: beam_stiffness, beam_end_forces, beam_load

contains

  pure logical function is_2d(etype)
    !! Whether a beam type is planar (B23, B21).
    integer, intent(in) :: etype
    is_2d = etype == ET_B23 .or. etype == ET_B21
  end function is_2d

  pure logical function is_timoshenko(etype)
    !! Whether a beam type has transverse shear flexibility (B21, B31).
    integer, intent(in) :: etype
    is_timoshenko = etype == ET_B21 .or. etype == ET_B31
  end function is_timoshenko

  pure integer function beam_ndof(etype)
    !! DOFs per node of a beam type.
    integer, intent(in) :: etype
    if (is_2d(etype)) then
       beam_ndof = ND_B23
    else
       beam_ndof = ND_B33
    end if
  end function beam_ndof

  pure subroutine beam_setup(etype, x, sec, mat, p, error)
    !! Frame and rigidities of a beam, with the data checks.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(beam_props_t), intent(out) :: p
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: g, ks(2)

    call beam_frame(etype, x, sec, p%r, p%length, error)
    if (allocated(error)) return
    call require_positive(sec%area, 'cross-section area A', error)
    if (is_2d(etype)) then
       call require_positive(sec%iz, 'moment of inertia I', error)
    else
       call require_positive(sec%iy, 'moment of inertia Iy', error)
       call require_positive(sec%iz, 'moment of inertia Iz', error)
       call require_positive(sec%j, 'torsion constant J', error)
    end if
    call require_positive(mat%e, 'Young''s modulus E', error)
    if (allocated(error)) return
    p%ea = mat%e*sec%area
    p%eiz = mat%e*sec%iz
    if (etype == ET_B23) return
    if (.not. (mat%nu > -1.0_wp)) then
       call fatal_error(error, EXIT_DECK, 'Poisson''s ratio nu must be greater than -1 for a beam')
       return
    end if
    g = mat%e/(2*(1 + mat%nu))
    if (.not. is_2d(etype)) then
       p%eiy = mat%e*sec%iy
       p%gj = g*sec%j
    end if
    if (.not. is_timoshenko(etype)) return
    ! Transverse shear stiffness K (force units) per direction: given, or k G A.
    call require_positive(sec%shear_factor, 'shear factor k', error)
    if (allocated(error)) return
    ks = merge(sec%shear_k, sec%shear_factor*g*sec%area, sec%shear_k > 0.0_wp)
    p%phiy = 12*p%eiz/(ks(1)*p%length**2)
    if (.not. is_2d(etype)) p%phiz = 12*p%eiy/(ks(2)*p%length**2)
  end subroutine beam_setup

  pure subroutine local_stiffness(etype, p, k)
    !! Local stiffness (node-major local DOFs) of a beam in k(1:n, 1:n), n =
    !! 2 beam_ndof(etype) (the rest of k zero).
    integer, intent(in) :: etype
    type(beam_props_t), intent(in) :: p
    real(wp), intent(out) :: k(2*ND_B33, 2*ND_B33)
    real(wp) :: l, a, bz(4, 4), by(4, 4)
    integer :: iv(4), iw(4)

    l = p%length
    if (is_timoshenko(etype)) then
       bz = timoshenko_block(p%eiz, l, p%phiy)
    else
       bz = hermite_block(p%eiz, l)
    end if
    k = 0.0_wp
    if (is_2d(etype)) then
       a = p%ea/l
       k(1, 1) = a; k(4, 4) = a; k(1, 4) = -a; k(4, 1) = -a
       iv = [2, 3, 5, 6]                ! v1, θz1, v2, θz2
       k(iv, iv) = bz
       return
    end if

    a = p%ea/l
    k(1, 1) = a; k(7, 7) = a; k(1, 7) = -a; k(7, 1) = -a
    a = p%gj/l
    k(4, 4) = a; k(10, 10) = a; k(4, 10) = -a; k(10, 4) = -a
    ! Bending in the x-y plane: v and θz = dv/dx, rigidity EIz.
    iv = [2, 6, 8, 12]
    k(iv, iv) = bz
    ! Bending in the x-z plane: w and θy = -dw/dx, rigidity EIy; the block in
    ! (w1, -θy1, w2, -θy2) is the same Hermite block.
    if (is_timoshenko(etype)) then
       by = timoshenko_block(p%eiy, l, p%phiz)
    else
       by = hermite_block(p%eiy, l)
    end if
    by(:, [2, 4]) = -by(:, [2, 4])
    by([2, 4], :) = -by([2, 4], :)
    iw = [3, 5, 9, 11]
    k(iw, iw) = by
  end subroutine local_stiffness

  pure function hermite_block(ei, l) result(b)
    !! Euler-Bernoulli bending stiffness in (v1, θ1, v2, θ2) with θ = dv/dx.
    real(wp), intent(in) :: ei, l
    real(wp) :: b(4, 4)
    real(wp) :: c1, c2, c3
    c3 = 12*ei/l**3
    c2 = 6*ei/l**2
    c1 = 2*ei/l
    b(:, 1) = [c3, c2, -c3, c2]
    b(:, 2) = [c2, 2*c1, -c2, c1]
    b(:, 3) = [-c3, -c2, c3, -c2]
    b(:, 4) = [c2, c1, -c2, 2*c1]
  end function hermite_block

  pure function timoshenko_block(ei, l, phi) result(b)
    !! Bending stiffness of a prismatic Timoshenko member in (v1, θ1, v2, θ2),
    !! θ the rotation of the section, phi = 12 EI/(K L²) (K: transverse shear
    !! stiffness): the exact stiffness (interdependent interpolation), which
    !! tends to hermite_block as phi -> 0 and does not lock as L/h grows.
    real(wp), intent(in) :: ei, l, phi
    real(wp) :: b(4, 4)
    real(wp) :: c
    c = ei/((1 + phi)*l**3)
    b(:, 1) = c*[12*one, 6*l, -12*one, 6*l]
    b(:, 2) = c*[6*l, (4 + phi)*l**2, -6*l, (2 - phi)*l**2]
    b(:, 3) = c*[-12*one, -6*l, 12*one, -6*l]
    b(:, 4) = c*[6*l, (2 - phi)*l**2, -6*l, (4 + phi)*l**2]
  end function timoshenko_block

  pure function beam_load_local(etype, length, q) result(fq)
    !! Consistent nodal loads (local axes, node-major local DOFs) of a uniform
    !! load per unit length q (local axes), with the fixed-end moments. They
    !! hold for the Timoshenko types as well: the fixed-end forces of a uniform
    !! load do not depend on the shear flexibility (symmetric load, the end
    !! moments are set by bending alone), and they are the consistent loads of
    !! the interdependent interpolation.
    integer, intent(in) :: etype
    real(wp), intent(in) :: length, q(3)
    real(wp), allocatable :: fq(:)
    real(wp) :: h, m
    h = length/2
    m = length**2/12
    if (is_2d(etype)) then
       fq = [q(1)*h, q(2)*h, q(2)*m, q(1)*h, q(2)*h, -q(2)*m]
    else
       fq = [q(1)*h, q(2)*h, q(3)*h, 0.0_wp, -q(3)*m, q(2)*m, &
             q(1)*h, q(2)*h, q(3)*h, 0.0_wp, q(3)*m, -q(2)*m]
    end if
  end function beam_load_local

  pure subroutine beam_stiffness(etype, x, sec, mat, ke, error)
    !! Global stiffness of a B23/B33/B21/B31 beam, node-major (exactly symmetric).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(beam_props_t) :: p
    real(wp) :: kl(2*ND_B33, 2*ND_B33), blk(3, 3)
    integer :: ib, jb, nb

    call beam_setup(etype, x, sec, mat, p, error)
    if (allocated(error)) return
    ! ke = Tᵀ kl T with T block diagonal in r: rotate 3x3 blocks.
    call local_stiffness(etype, p, kl)
    nb = 2*beam_ndof(etype)/3
    allocate (ke(3*nb, 3*nb))
    do jb = 0, nb - 1
       do ib = 0, jb
          call turn_block(kl, 3*ib, 3*jb, p%r, blk)
          if (ib == jb) then
             blk = 0.5_wp*(blk + transpose(blk))
          else
             ke(3*jb + 1:3*jb + 3, 3*ib + 1:3*ib + 3) = transpose(blk)
          end if
          ke(3*ib + 1:3*ib + 3, 3*jb + 1:3*jb + 3) = blk
       end do
    end do
  end subroutine beam_stiffness

  pure subroutine turn_block(kl, i0, j0, r, blk)
    !! blk = rᵀ kl(i0+1:i0+3, j0+1:j0+3) r, each sum accumulated from the first
    !! term on in the order of the two matrix products.
    real(wp), intent(in) :: kl(:, :), r(3, 3)
    integer, intent(in) :: i0, j0
    real(wp), intent(out) :: blk(3, 3)
    real(wp) :: t(3, 3), c
    integer :: a, b, k
    do b = 1, 3
       do a = 1, 3
          c = 0.0_wp
          do k = 1, 3
             c = c + kl(i0 + a, j0 + k)*r(k, b)
          end do
          t(a, b) = c
       end do
    end do
    do b = 1, 3
       do a = 1, 3
          c = 0.0_wp
          do k = 1, 3
             c = c + r(k, a)*t(k, b)
          end do
          blk(a, b) = c
       end do
    end do
  end subroutine turn_block

  pure subroutine beam_end_forces(etype, x, sec, mat, ue, q_local, f, error)
    !! End forces of a beam in local axes: f = k_local u_local - f_eq_local,
    !! f(1:6, end) = n, vy, vz, t, my, mz (B23: n, vy, mz; the rest 0).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(in) :: q_local(3)
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    type(beam_props_t) :: p
    real(wp) :: ql(3), kl(2*ND_B33, 2*ND_B33), ul(2*ND_B33), fl(2*ND_B33), fq(2*ND_B33), c
    integer :: nd, b, i, j

    f = 0.0_wp
    nd = beam_ndof(etype)
    if (size(ue) /= NNODE*nd) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    call beam_setup(etype, x, sec, mat, p, error)
    if (allocated(error)) return
    ql = q_local
    if (is_2d(etype)) ql(3) = 0.0_wp
    ! u_local = T u_global with T block diagonal in r: rotate 3-vectors.
    do b = 0, size(ue)/3 - 1
       ul(3*b + 1:3*b + 3) = matmul(p%r, ue(3*b + 1:3*b + 3))
    end do
    call local_stiffness(etype, p, kl)
    fq(1:2*nd) = beam_load_local(etype, p%length, ql)
    do i = 1, 2*nd
       c = 0.0_wp
       do j = 1, 2*nd
          c = c + kl(i, j)*ul(j)
       end do
       fl(i) = c - fq(i)
    end do
    if (is_2d(etype)) then
       f([1, 2, 6], 1) = fl(1:3)
       f([1, 2, 6], 2) = fl(4:6)
    else
       f(:, 1) = fl(1:6)
       f(:, 2) = fl(7:12)
    end if
  end subroutine beam_end_forces

  pure subroutine beam_load(etype, x, sec, w, fe, q_local, error)
    !! Consistent nodal loads (global axes, node-major) of a uniform load per
    !! unit length w (global axes) on a beam, and the load in local axes.
    !! B23 and B21 reject a load along global Z.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: w(3)
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: q_local(3)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), length, g(3), c
    integer :: a, b, k

    q_local = 0.0_wp
    call beam_frame(etype, x, sec, r, length, error)
    if (allocated(error)) return
    if (is_2d(etype) .and. w(3) /= 0.0_wp) then
       call fatal_error(error, EXIT_DECK, 'load along global Z on a 2D element')
       return
    end if
    q_local = matmul(r, w)
    ! fe = Tᵀ f_local, T block diagonal in r: each node block rᵀ f (the sums
    ! of the full product without its products by zero)
    fe = beam_load_local(etype, length, q_local)
    do b = 0, size(fe)/3 - 1
       do a = 1, 3
          c = 0.0_wp
          do k = 1, 3
             c = c + r(k, a)*fe(3*b + k)
          end do
          g(a) = c
       end do
       fe(3*b + 1:3*b + 3) = g
    end do
  end subroutine beam_load
end module superjoin_elements_beam
