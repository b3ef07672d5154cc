module superjoin_elements_face_projection
  !! Geometry of element faces for constraints between surfaces (*TIE): the
  !! nodes of a face, its shape functions, and the projection of a point onto
  !! it. A face is a face S1..S6 of a solid (superjoin_elements_solid_faces:
  !! 3-node or 6-node triangle, 4-node or 8-node quadrilateral) or the
  !! surface of a shell (face 0: its own nodes, the element's shape).
  !!
  !! The projection finds the local coordinates ξ = (s, t) of the point of
  !! the face nearest to p: Gauss-Newton on |x(ξ) − p|², x(ξ) = Σ N_k(ξ) x_k,
  !! from the face's centre; a ξ outside the face is brought back onto its
  !! boundary (quadrilateral: −1 ≤ s, t ≤ 1; triangle: s, t ≥ 0, s + t ≤ 1),
  !! so the weights N_k(ξ) always sum to one. A point that falls on a node
  !! (a weight within SNAP of 1) takes that node's weights exactly (1 and 0):
  !! matching meshes then tie node to node, with no round-off in the weights.
  use superjoin_kinds, only: wp
  use superjoin_elements_traits, only: element_traits, FAMILY_SHELL, FAMILY_SOLID
  use superjoin_elements_solid_faces, only: solid_face_nodes, face_shape
  implicit none (type, external)
  private

  public :: element_face_nodes, face_shape_values, project_to_face, face_size

  type, public :: face_point_t
    !! The point of a face nearest to a given point.
     real(wp) :: xi(2) = 0.0_wp            !! its local coordinates (s, t)
     real(wp) :: x(3) = 0.0_wp             !! its position
     real(wp) :: distance = huge(1.0_wp)   !! from the given point
     real(wp), allocatable :: n(:)         !! the face's shape functions there (sum 1)
  end type face_point_t

  integer, parameter :: MAX_ITER = 30
  real(wp), parameter :: SNAP = 1.0e-9_wp
    !! a weight this close to 1 puts the point on that node
  real(wp), parameter :: STEP_TOL = 1.0e-14_wp

contains

  pure subroutine element_face_nodes(etype, face, nodes, ncorner)
    !! The element's local node numbers of face `face` (corners first, then
    !! mid-side nodes, as face_shape_values orders them): faces 1..6 of a
    !! solid, face 0 of a shell (its nodes); nodes is empty for a face the
    !! type does not have.
    integer, intent(in) :: etype, face
    integer, allocatable, intent(out) :: nodes(:)
    integer, intent(out) :: ncorner
    integer :: k
    associate (tr => element_traits(etype))
      if (tr%family == FAMILY_SOLID .and. face >= 1) then
         call solid_face_nodes(etype, face, nodes, ncorner)
      else if (tr%family == FAMILY_SHELL .and. face == 0 .and. (tr%nodes == tr%corners .or. tr%corners == 4)) then
         nodes = [(k, k = 1, tr%nodes)]
         ncorner = tr%corners
      else
         allocate (nodes(0))
         ncorner = 0
      end if
    end associate
  end subroutine element_face_nodes

  pure subroutine face_shape_values(nc, nn, xi, n, dn)
    !! Shape functions n(nn) and their derivatives dn(2, nn) at ξ of a face
    !! with nc corners and nn nodes (3, 4, 6 or 8).
    integer, intent(in) :: nc, nn
    real(wp), intent(in) :: xi(2)
    real(wp), allocatable, intent(out) :: n(:), dn(:, :)
    call face_shape(nc, nn, xi(1), xi(2), n, dn)
  end subroutine face_shape_values

  pure function project_to_face(x, nc, p) result(fp)
    !! The point of the face with node coordinates x(3, nn) and nc corners
    !! nearest to p (its local coordinates, position, distance and weights).
    real(wp), intent(in) :: x(:, :), p(3)
    integer, intent(in) :: nc
    type(face_point_t) :: fp
    real(wp), allocatable :: n(:), dn(:, :)
    real(wp) :: a1(3), a2(3), r(3), g(2, 2), b(2), det, d(2)
    integer :: it, k
    fp%xi = 0.0_wp
    if (nc == 3) fp%xi = 1.0_wp/3.0_wp
    do it = 1, MAX_ITER
       call face_shape(nc, size(x, 2), fp%xi(1), fp%xi(2), n, dn)
       a1 = matmul(x, dn(1, :))
       a2 = matmul(x, dn(2, :))
       r = p - matmul(x, n)
       g = reshape([dot_product(a1, a1), dot_product(a1, a2), dot_product(a1, a2), dot_product(a2, a2)], [2, 2])
       b = [dot_product(a1, r), dot_product(a2, r)]
       det = g(1, 1)*g(2, 2) - g(1, 2)*g(2, 1)
       if (.not. (abs(det) > 0.0_wp)) exit
       d = [g(2, 2)*b(1) - g(1, 2)*b(2), g(1, 1)*b(2) - g(2, 1)*b(1)]/det
       fp%xi = clamp(nc, fp%xi + d)
       if (maxval(abs(d)) <= STEP_TOL) exit
    end do
    call face_shape(nc, size(x, 2), fp%xi(1), fp%xi(2), n, dn)
    k = maxloc(n, 1)
    if (n(k) >= 1.0_wp - SNAP) then
       n = 0.0_wp
       n(k) = 1.0_wp
    end if
    fp%n = n
    fp%x = matmul(x, n)
    fp%distance = norm2(p - fp%x)
  end function project_to_face

  pure function clamp(nc, xi) result(c)
    !! ξ brought back into the face (its nearest point of the parameter domain).
    integer, intent(in) :: nc
    real(wp), intent(in) :: xi(2)
    real(wp) :: c(2), excess
    if (nc == 4) then
       c = max(-1.0_wp, min(1.0_wp, xi))
       return
    end if
    c = max(0.0_wp, xi)
    excess = c(1) + c(2) - 1.0_wp
    if (excess > 0.0_wp) then
       c = c - excess/2.0_wp
       c = max(0.0_wp, c)
       c = c/max(c(1) + c(2), 1.0_wp)
    end if
  end function clamp

  pure real(wp) function face_size(x, nc) result(h)
    !! A typical size of the face with corner coordinates x(3, 1:nc): its
    !! area over its half perimeter (the inradius of a triangle, half the
    !! width of a square).
    real(wp), intent(in) :: x(:, :)
    integer, intent(in) :: nc
    real(wp) :: area, perim, c(3), e1(3), e2(3)
    integer :: k
    c = sum(x(:, 1:nc), 2)/nc
    area = 0.0_wp
    perim = 0.0_wp
    do k = 1, nc
       e1 = x(:, k) - c
       e2 = x(:, mod(k, nc) + 1) - c
       area = area + 0.5_wp*norm2([e1(2)*e2(3) - e1(3)*e2(2), e1(3)*e2(1) - e1(1)*e2(3), e1(1)*e2(2) - e1(2)*e2(1)])
       perim = perim + norm2(x(:, mod(k, nc) + 1) - x(:, k))
    end do
    h = 0.0_wp
    if (perim > 0.0_wp) h = 2.0_wp*area/perim
  end function face_size
end module superjoin_elements_face_projection
