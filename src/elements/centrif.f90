module superjoin_elements_centrif
  !! Centrifugal loads (*DLOAD, CENTRIF, as CalculiX: ω², a point p of the
  !! axis, the axis direction a): the body force ρ ω² r(x) per unit volume,
  !! r(x) = (x - p) - ((x - p)·a) a the distance vector from the axis. r is
  !! linear in x, so on an isoparametric element it is interpolated exactly
  !! from its nodal values r_j, and the consistent nodal loads are those of the
  !! consistent mass: f_i = ρ ω² Σ_j M_ij r_j, M_ij = ∫ N_i N_j dV.
  !!
  !! Bars and two-node beams (mass ρ A per unit length): the load per unit
  !! length varies linearly from q1 to q2 (local axes) along the element; bars
  !! take L (2 q1 + q2)/6 and L (q1 + 2 q2)/6 on each component; beams take
  !! these along their axis and the cubic (Hermite) shares across it: forces
  !! L (7 q1 + 3 q2)/20, L (3 q1 + 7 q2)/20 and fixed-end moments
  !! ± L² (3 q1 + 2 q2)/60, ∓ L² (2 q1 + 3 q2)/60 (Euler-Bernoulli values, used
  !! for the Timoshenko beams too). Plane and shell elements (mass ρ t per unit
  !! area): the mass matrix of the element's shape functions (3, 4, 6 or 8
  !! nodes), integrated with a degree-5 rule (7-point triangle, 3×3 Gauss).
  !! Solids (C3D*, mass ρ per unit volume): f_a = ρ ω² ∫ N_a r dV, with
  !! r(x(ξ)) = Σ_b N_b r_b, integrated with 4 Gauss points per direction of the
  !! cube (hexahedra, 64 points), of the collapsed cube (tetrahedra: x = a,
  !! y = b (1 - a), z = c (1 - a)(1 - b), weight (1 - a)²(1 - b); wedges: the
  !! triangle collapsed likewise times 4 points in ζ): exact for the
  !! quadratic elements' N_a N_b (degree 4) on straight-sided elements, more
  !! points than any element's stiffness rule (C3D20R's 2×2×2 reduced rule is
  !! not exact for it).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, dload_t, ET_T2D2, ET_T3D2, ET_B23, ET_B33, &
       ET_B21, ET_B31
  use superjoin_elements_frame, only: beam_frame
  use superjoin_elements_shell, only: shell_frame, is_plate_type, is_plane_type
  use superjoin_elements_traits, only: element_traits, element_traits_t, FAMILY_SOLID
  use superjoin_elements_solid, only: point_gradients
  use superjoin_elements_quadrature, only: quad_rule_t, gauss_line, gauss_square, triangle_rule, TRI_DUNAVANT5
  implicit none (type, external)
  private

  public :: centrif_load, axis_distance

  real(wp), parameter :: PLANE_Z_TOL = 1.0e-12_wp
    !! Largest out-of-plane share of the load on a plane element (relative).

contains

  pure function axis_distance(dl, x) result(r)
    !! Distance vector from the axis of a CENTRIF load to the point x.
    type(dload_t), intent(in) :: dl
    real(wp), intent(in) :: x(3)
    real(wp) :: r(3)
    r = x - dl%point
    r = r - dot_product(r, dl%dir)*dl%dir
  end function axis_distance

  pure subroutine centrif_load(etype, x, sec, mat, dl, dofs, fe, error)
    !! Consistent nodal loads fe (global axes, node-major with the DOFs `dofs`
    !! of each node) of the centrifugal load dl (value ω²) on an element with
    !! nodes x(3, n), density from mat.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    integer, intent(in) :: dofs(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    select case (etype)
    case (ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_B21, ET_B31)
       call line_load(etype, x, sec, mat, dl, dofs, fe, error)
    case default
       if (is_plate_type(etype)) then
          call area_load(etype, x, sec, mat, dl, fe, error)
       else if (is_solid(etype)) then
          call solid_load(etype, x, mat, dl, fe, error)
       else
          call fatal_error(error, EXIT_DECK, 'CENTRIF applies to trusses, two-node beams, plane, shell and '// &
               'solid elements')
       end if
    end select
  end subroutine centrif_load

  pure logical function is_solid(etype)
    !! etype is a 3D solid (FAMILY_SOLID).
    integer, intent(in) :: etype
    type(element_traits_t) :: t
    t = element_traits(etype)
    is_solid = t%family == FAMILY_SOLID
  end function is_solid

  pure subroutine solid_load(etype, x, mat, dl, fe, error)
    !! Solids: f_a = ρ ω² ∫ N_a r dV (see the module header).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: pts(:, :), wts(:), n(:), dx(:, :)
    real(wp) :: rn(3, size(x, 2)), detj, r(3)
    integer :: a, g, nn
    nn = size(x, 2)
    do a = 1, nn
       rn(:, a) = axis_distance(dl, x(:, a))
    end do
    call solid_points(element_traits(etype), pts, wts)
    allocate (fe(3*nn), source=0.0_wp)
    do g = 1, size(wts)
       call point_gradients(etype, x, pts(:, g), n, dx, detj, error)
       if (allocated(error)) return
       r = matmul(rn, n)*(mat%density*dl%value*detj*wts(g))
       do a = 1, nn
          fe(3*a - 2:3*a) = fe(3*a - 2:3*a) + n(a)*r
       end do
    end do
  end subroutine solid_load

  pure subroutine solid_points(t, pts, wts)
    !! The 4-point-per-direction rule of the module header in the natural
    !! coordinates of solid t (hexahedron -1..1; tetrahedron ξ, η, ζ = L2,
    !! L3, L4; wedge: the triangle's ξ, η and ζ -1..1): points pts(3, 64), weights wts(64).
    type(element_traits_t), intent(in) :: t
    real(wp), allocatable, intent(out) :: pts(:, :), wts(:)
    real(wp), allocatable :: gp(:), gw(:)
    real(wp) :: u(3), w
    integer :: i, j, k, g
    call gauss_line(4, gp, gw)
    allocate (pts(3, 64), wts(64))
    g = 0
    do k = 1, 4
       do j = 1, 4
          do i = 1, 4
             g = g + 1
             w = gw(i)*gw(j)*gw(k)
             u = 0.5_wp*(1.0_wp + [gp(i), gp(j), gp(k)])      ! the unit cube
             if (t%edges == 6) then                           ! hexahedron
                pts(:, g) = [gp(i), gp(j), gp(k)]
             else if (t%edges == 4) then                      ! tetrahedron
                pts(:, g) = [u(1), u(2)*(1 - u(1)), u(3)*(1 - u(1))*(1 - u(2))]
                w = w*(1 - u(1))**2*(1 - u(2))/8
             else                                             ! wedge
                pts(:, g) = [u(1), u(2)*(1 - u(1)), gp(k)]
                w = w*(1 - u(1))/4
             end if
             wts(g) = w
          end do
       end do
    end do
  end subroutine solid_points

  pure subroutine line_load(etype, x, sec, mat, dl, dofs, fe, error)
    !! Bars and two-node beams (see the module header).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    integer, intent(in) :: dofs(:)
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), length, q1(3), q2(3), fl(6, 2), g(6)
    integer :: a, k, nd
    logical :: beam
    call beam_frame(etype, x, sec, r, length, error)
    if (allocated(error)) return
    q1 = matmul(r, mat%density*sec%area*dl%value*axis_distance(dl, x(:, 1)))
    q2 = matmul(r, mat%density*sec%area*dl%value*axis_distance(dl, x(:, 2)))
    beam = .not. (etype == ET_T2D2 .or. etype == ET_T3D2)
    fl = 0.0_wp
    fl(1:3, 1) = length*(2*q1 + q2)/6
    fl(1:3, 2) = length*(q1 + 2*q2)/6
    if (beam) then
       fl(2:3, 1) = length*(7*q1(2:3) + 3*q2(2:3))/20
       fl(2:3, 2) = length*(3*q1(2:3) + 7*q2(2:3))/20
       ! load along local y: moment about local z; along local z: about -y
       fl(6, 1) = length**2*(3*q1(2) + 2*q2(2))/60
       fl(6, 2) = -length**2*(2*q1(2) + 3*q2(2))/60
       fl(5, 1) = -length**2*(3*q1(3) + 2*q2(3))/60
       fl(5, 2) = length**2*(2*q1(3) + 3*q2(3))/60
    end if
    nd = size(dofs)
    allocate (fe(2*nd), source=0.0_wp)
    do a = 1, 2
       g(1:3) = matmul(transpose(r), fl(1:3, a))
       g(4:6) = matmul(transpose(r), fl(4:6, a))
       do k = 1, nd
          fe(nd*(a - 1) + k) = g(dofs(k))
       end do
    end do
    ! a planar element must not be loaded out of its plane
    do a = 1, 2
       g(1:3) = matmul(transpose(r), fl(1:3, a))
       g(4:6) = matmul(transpose(r), fl(4:6, a))
       do k = 1, 6
          if (any(dofs == k)) cycle
          if (abs(g(k)) > PLANE_Z_TOL*max(maxval(abs(fe)), tiny(1.0_wp))) then
             call fatal_error(error, EXIT_DECK, 'CENTRIF loads this planar element out of its plane '// &
                  '(the axis must be normal to the XY plane, or lie in it)')
             return
          end if
       end do
    end do
  end subroutine line_load

  pure subroutine area_load(etype, x, sec, mat, dl, fe, error)
    !! Plane and shell elements (see the module header).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), xl(2, size(x, 2)), h(size(x, 2)), rn(3, size(x, 2)), m(size(x, 2), size(x, 2)), f(3)
    integer :: n, i, j
    n = size(x, 2)
    call shell_frame(x, r, xl, h, error)
    if (allocated(error)) return
    call mass_matrix(xl, m, error)
    if (allocated(error)) return
    do j = 1, n
       rn(:, j) = axis_distance(dl, x(:, j))
    end do
    m = mat%density*sec%thickness*dl%value*m
    if (is_plane_type(etype)) then
       allocate (fe(2*n))
       do i = 1, n
          f = matmul(rn, m(i, :))
          if (abs(f(3)) > PLANE_Z_TOL*max(norm2(f), tiny(1.0_wp))) then
             call fatal_error(error, EXIT_DECK, 'CENTRIF loads a plane element out of the XY plane '// &
                  '(the axis must be parallel to Z, or lie in the XY plane)')
             return
          end if
          fe(2*i - 1:2*i) = f(1:2)
       end do
    else
       allocate (fe(6*n), source=0.0_wp)
       do i = 1, n
          fe(6*i - 5:6*i - 3) = matmul(rn, m(i, :))
       end do
    end if
  end subroutine area_load

  pure subroutine mass_matrix(xl, m, error)
    !! M_ij = ∫ N_i N_j dA of a 3-, 4-, 6- or 8-node element with local
    !! coordinates xl(2, n).
    real(wp), intent(in) :: xl(:, :)
    real(wp), intent(out) :: m(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(quad_rule_t) :: r
    real(wp) :: nf(size(xl, 2)), dn(2, size(xl, 2)), jm(2, 2), detj
    integer :: n, g, j
    n = size(xl, 2)
    m = 0.0_wp
    if (n == 3 .or. n == 6) then
       r = triangle_rule(TRI_DUNAVANT5)
    else if (n == 4 .or. n == 8) then
       r = gauss_square(3)
    else
       call fatal_error(error, EXIT_DECK, 'CENTRIF: an area element has 3, 4, 6 or 8 nodes')
       return
    end if
    do g = 1, size(r%w)
       call shape(n, r%xi(:, g), nf, dn)
       jm = matmul(dn, transpose(xl))
       detj = abs(jm(1, 1)*jm(2, 2) - jm(1, 2)*jm(2, 1))
       do j = 1, n
          m(:, j) = m(:, j) + r%w(g)*detj*nf*nf(j)
       end do
    end do
  end subroutine mass_matrix

  pure subroutine shape(n, p, nf, dn)
    !! Shape functions nf(n) and derivatives dn(2, n) at the natural point p
    !! of the linear and quadratic triangles (area coordinates ξ, η) and the
    !! bilinear and serendipity quadrilaterals (corners, then the mid-side node
    !! of edge k = corner k to k+1).
    integer, intent(in) :: n
    real(wp), intent(in) :: p(2)
    real(wp), intent(out) :: nf(n), dn(2, n)
    real(wp), parameter :: XI(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], ETA(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    real(wp) :: l(3), dl(2, 3), s, t
    integer :: i, j, k
    select case (n)
    case (3, 6)
       l = [1.0_wp - p(1) - p(2), p(1), p(2)]
       dl = reshape([-1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 3])
       if (n == 3) then
          nf = l
          dn = dl
       else
          do i = 1, 3
             nf(i) = l(i)*(2*l(i) - 1)
             dn(:, i) = (4*l(i) - 1)*dl(:, i)
             j = modulo(i, 3) + 1
             nf(3 + i) = 4*l(i)*l(j)
             dn(:, 3 + i) = 4*(dl(:, i)*l(j) + l(i)*dl(:, j))
          end do
       end if
    case (4)
       do i = 1, 4
          nf(i) = 0.25_wp*(1 + XI(i)*p(1))*(1 + ETA(i)*p(2))
          dn(:, i) = 0.25_wp*[XI(i)*(1 + ETA(i)*p(2)), ETA(i)*(1 + XI(i)*p(1))]
       end do
    case default
       s = p(1)
       t = p(2)
       do i = 1, 4
          nf(i) = 0.25_wp*(1 + XI(i)*s)*(1 + ETA(i)*t)*(XI(i)*s + ETA(i)*t - 1)
          dn(1, i) = 0.25_wp*XI(i)*(1 + ETA(i)*t)*(2*XI(i)*s + ETA(i)*t)
          dn(2, i) = 0.25_wp*ETA(i)*(1 + XI(i)*s)*(XI(i)*s + 2*ETA(i)*t)
       end do
       do k = 1, 4
          i = k
          j = modulo(k, 4) + 1
          if (ETA(i) == ETA(j)) then      ! edge along ξ: node at ξ = 0
             nf(4 + k) = 0.5_wp*(1 - s*s)*(1 + ETA(i)*t)
             dn(:, 4 + k) = [-s*(1 + ETA(i)*t), 0.5_wp*ETA(i)*(1 - s*s)]
          else                            ! edge along η: node at η = 0
             nf(4 + k) = 0.5_wp*(1 + XI(i)*s)*(1 - t*t)
             dn(:, 4 + k) = [0.5_wp*XI(i)*(1 - t*t), -t*(1 + XI(i)*s)]
          end if
       end do
    end select
  end subroutine shape
end module superjoin_elements_centrif
