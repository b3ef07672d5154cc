module superjoin_elements_solid_faces
  !! Pressure on the faces of the 3D solid elements (*DLOAD P1..P6, *DSLOAD on
  !! the faces S1..S6 of a *SURFACE) and Abaqus's tractions on them (*DSLOAD
  !! TRVEC, TRSHR), face numbering as Abaqus and CalculiX:
  !!
  !! - hexahedra (C3D8, C3D8I, C3D8R, C3D20, C3D20R): S1 1-2-3-4, S2 5-8-7-6, S3 1-5-6-2,
  !!   S4 2-6-7-3, S5 3-7-8-4, S6 4-8-5-1;
  !! - tetrahedra (C3D4, C3D10): S1 1-2-3, S2 1-4-2, S3 2-4-3, S4 3-4-1;
  !! - wedges (C3D6, C3D15): S1 1-2-3, S2 4-6-5, S3 1-4-5-2, S4 2-5-6-3, S5 3-6-4-1
  !!   (CalculiX's faces 1-2-3, 4-5-6, 1-2-5-4, 2-3-6-5, 3-1-4-6, turned inwards);
  !!
  !! the quadratic types add the mid-side node of each edge of the face. Each
  !! face's corners run so that the right-hand normal points into the
  !! element, the direction a positive pressure pushes. The consistent nodal
  !! loads f_a = ∫ N_a p n dA use the face's own shape functions (bilinear or
  !! 8-node serendipity quadrilateral, linear or 6-node triangle) and n dA =
  !! ∂x/∂s × ∂x/∂t: 3×3 Gauss on quadrilaterals, the collapsed 3×3 Gauss rule
  !! on triangles (exact on flat faces, and for polynomials of degree 4).
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D8R, &
       ET_C3D6, ET_C3D15
  use superjoin_elements_solid, only: WEDGE_EDGES
  use superjoin_elements_quadrature, only: quad_rule_t, gauss_square, triangle_rule, TRI_CENTROID, TRI_THREE
  use superjoin_elements_traction, only: surface_load_t, point_force, LOAD_PRESSURE
  implicit none (type, external)
  private

  integer, parameter :: HEX_FACES(4, 6) = reshape([1, 2, 3, 4, 5, 8, 7, 6, 1, 5, 6, 2, 2, 6, 7, 3, &
       3, 7, 8, 4, 4, 8, 5, 1], [4, 6])
  integer, parameter :: TET_FACES(3, 4) = reshape([1, 2, 3, 1, 4, 2, 2, 4, 3, 3, 4, 1], [3, 4])
  integer, parameter :: WEDGE_TRI(3, 2) = reshape([1, 2, 3, 4, 6, 5], [3, 2])
  integer, parameter :: WEDGE_QUAD(4, 3) = reshape([1, 4, 5, 2, 2, 5, 6, 3, 3, 6, 4, 1], [4, 3])
  integer, parameter :: HEX_EDGES(2, 12) = reshape([1, 2, 2, 3, 3, 4, 4, 1, 5, 6, 6, 7, 7, 8, 8, 5, &
       1, 5, 2, 6, 3, 7, 4, 8], [2, 12])
  integer, parameter :: TET_EDGES(2, 6) = reshape([1, 2, 2, 3, 3, 1, 1, 4, 2, 4, 3, 4], [2, 6])
  ! The faces' nodes in CalculiX's order (its tables ifaceq, ifacet, ifacew1/ifacew2: corners
  ! with the outward normal, then the mid-side nodes; 0 pads a wedge's triangles), the order in
  ! which its *PRE-TENSION SECTION numbers the copies of a cut's nodes (checked with ccx 2.20).
  integer, parameter :: CCX_HEX_FACES(8, 6) = reshape([4, 3, 2, 1, 11, 10, 9, 12, 5, 6, 7, 8, 13, 14, 15, 16, &
       1, 2, 6, 5, 9, 18, 13, 17, 2, 3, 7, 6, 10, 19, 14, 18, 3, 4, 8, 7, 11, 20, 15, 19, &
       4, 1, 5, 8, 12, 17, 16, 20], [8, 6])
  integer, parameter :: CCX_TET_FACES(6, 4) = reshape([1, 3, 2, 7, 6, 5, 1, 2, 4, 5, 9, 8, 2, 3, 4, 6, 10, 9, &
       1, 4, 3, 8, 10, 7], [6, 4])
  integer, parameter :: CCX_WEDGE_FACES(8, 5) = reshape([1, 3, 2, 9, 8, 7, 0, 0, 4, 5, 6, 10, 11, 12, 0, 0, &
       1, 2, 5, 4, 7, 14, 10, 13, 2, 3, 6, 5, 8, 15, 11, 14, 3, 1, 4, 6, 9, 13, 12, 15], [8, 5])

  public :: solid_face_nodes, solid_face_nodes_ccx, solid_pressure_load, solid_surface_load, solid_face_points, face_shape

contains

  pure subroutine solid_face_nodes(etype, face, nodes, ncorner)
    !! The element's local node numbers of face `face` (corners in the face's
    !! order, then the mid-side nodes of its edges corner 1-2, 2-3, …); nodes
    !! is empty for a face the type does not have.
    integer, intent(in) :: etype, face
    integer, allocatable, intent(out) :: nodes(:)
    integer, intent(out) :: ncorner
    integer :: k, a, b
    allocate (nodes(0))
    ncorner = 0
    select case (etype)
    case (ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D8I, ET_C3D8R)
       if (face < 1 .or. face > 6) return
       nodes = HEX_FACES(:, face)
    case (ET_C3D4, ET_C3D10)
       if (face < 1 .or. face > 4) return
       nodes = TET_FACES(:, face)
    case (ET_C3D6, ET_C3D15)
       if (face < 1 .or. face > 5) return
       if (face <= 2) nodes = WEDGE_TRI(:, face)
       if (face >= 3) nodes = WEDGE_QUAD(:, face - 2)
    case default
       return
    end select
    ncorner = size(nodes)
    if (any(etype == [ET_C3D8, ET_C3D4, ET_C3D8I, ET_C3D6, ET_C3D8R])) return
    do k = 1, ncorner
       a = nodes(k)
       b = nodes(mod(k, ncorner) + 1)
       nodes = [nodes, edge_node(etype, a, b)]
    end do
  end subroutine solid_face_nodes

  pure subroutine solid_face_nodes_ccx(etype, face, nodes)
    !! The element's local node numbers of face `face` in CalculiX's order
    !! (the nodes of solid_face_nodes, ordered as ccx's face tables; empty
    !! for a face the type does not have).
    integer, intent(in) :: etype, face
    integer, allocatable, intent(out) :: nodes(:)
    integer :: ncorner
    call solid_face_nodes(etype, face, nodes, ncorner)
    if (ncorner == 0) return
    select case (etype)
    case (ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D8I, ET_C3D8R)
       nodes = CCX_HEX_FACES(1:size(nodes), face)
    case (ET_C3D4, ET_C3D10)
       nodes = CCX_TET_FACES(1:size(nodes), face)
    case (ET_C3D6, ET_C3D15)
       nodes = CCX_WEDGE_FACES(1:size(nodes), face)
    end select
  end subroutine solid_face_nodes_ccx

  pure integer function edge_node(etype, a, b) result(m)
    !! The mid-side node of the edge a-b of a quadratic solid.
    integer, intent(in) :: etype, a, b
    if (etype == ET_C3D10) then
       m = 4 + edge_index(TET_EDGES, a, b)
    else if (etype == ET_C3D15) then
       m = 6 + edge_index(WEDGE_EDGES, a, b)
    else
       m = 8 + edge_index(HEX_EDGES, a, b)
    end if
  end function edge_node

  pure integer function edge_index(edges, a, b) result(m)
    !! The column of the edge a-b (either way round) in edges(2, :); 0 if none.
    integer, intent(in) :: edges(:, :), a, b
    integer :: k
    m = 0
    do k = 1, size(edges, 2)
       if (all(edges(:, k) == [a, b]) .or. all(edges(:, k) == [b, a])) m = k
    end do
  end function edge_index

  pure subroutine solid_pressure_load(etype, x, face, p, fe, error)
    !! Consistent nodal loads fe(3 nnode) of a pressure p (positive: pushing
    !! into the element) on face `face` of a solid with node coordinates x(3, nnode).
    integer, intent(in) :: etype, face
    real(wp), intent(in) :: x(:, :), p
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    call solid_surface_load(etype, x, face, surface_load_t(LOAD_PRESSURE, p), fe, error)
  end subroutine solid_pressure_load

  pure subroutine solid_surface_load(etype, x, face, ld, fe, error)
    !! Consistent nodal loads fe(3 nnode) of the uniform surface load ld (a
    !! pressure, or a traction: superjoin_elements_traction) on face `face` of
    !! a solid with node coordinates x(3, nnode): f_a = ∫ N_a f dA.
    integer, intent(in) :: etype, face
    real(wp), intent(in) :: x(:, :)
    type(surface_load_t), intent(in) :: ld
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: nodes(:)
    real(wp), allocatable :: n(:), dn(:, :)
    real(wp) :: gp(3), gw(3), s, t, w, a1(3), a2(3), nda(3), f(3)
    integer :: nc, i, j, k
    allocate (fe(3*size(x, 2)), source=0.0_wp)
    call solid_face_nodes(etype, face, nodes, nc)
    if (nc == 0) then
       call fatal_error(error, EXIT_DECK, 'a surface load on a face the solid element does not have')
       return
    end if
    gp = [-sqrt(0.6_wp), 0.0_wp, sqrt(0.6_wp)]
    gw = [5.0_wp, 8.0_wp, 5.0_wp]/9.0_wp
    do j = 1, 3
       do i = 1, 3
          if (nc == 4) then
             s = gp(i)
             t = gp(j)
             w = gw(i)*gw(j)
          else            ! the collapsed rule: the square onto the triangle s, t >= 0, s + t <= 1
             s = 0.5_wp*(1.0_wp + gp(i))
             t = 0.5_wp*(1.0_wp - s)*(1.0_wp + gp(j))
             w = gw(i)*gw(j)*(1.0_wp - s)/4.0_wp
          end if
          call face_shape(nc, size(nodes), s, t, n, dn)
          a1 = matmul(x(:, nodes), dn(1, :))
          a2 = matmul(x(:, nodes), dn(2, :))
          nda = [a1(2)*a2(3) - a1(3)*a2(2), a1(3)*a2(1) - a1(1)*a2(3), a1(1)*a2(2) - a1(2)*a2(1)]
          call point_force(ld, w*nda, f, error)
          if (allocated(error)) return
          do k = 1, size(nodes)
             fe(3*nodes(k) - 2:3*nodes(k)) = fe(3*nodes(k) - 2:3*nodes(k)) + n(k)*f
          end do
       end do
    end do
  end subroutine solid_surface_load

  pure subroutine solid_face_points(etype, x, face, nodes, shp, nda, xg)
    !! CalculiX's integration points of face `face` of a solid with node
    !! coordinates x(3, nnode), as its *SECTION PRINT uses them: nodes the
    !! element's local node numbers of the face (solid_face_nodes, empty for a
    !! face the type does not have), per point k the face's shape functions
    !! shp(:, k) at it, its weighted outward area vector nda(:, k) = w n dA
    !! (out of the element) and its position xg(:, k). Points: C3D8, C3D8I,
    !! C3D20R, the quadrilaterals of C3D15 2×2 Gauss; C3D20 3×3; C3D4 and C3D6
    !! (all faces) one point; the triangles of C3D10 and C3D15 three.
    integer, intent(in) :: etype, face
    real(wp), intent(in) :: x(:, :)
    integer, allocatable, intent(out) :: nodes(:)
    real(wp), allocatable, intent(out) :: shp(:, :), nda(:, :), xg(:, :)
    real(wp), allocatable :: st(:, :), w(:), n(:), dn(:, :)
    real(wp) :: a1(3), a2(3)
    integer :: nc, k
    call solid_face_nodes(etype, face, nodes, nc)
    allocate (shp(size(nodes), 0), nda(3, 0), xg(3, 0))
    if (nc == 0) return
    if (etype == ET_C3D4 .or. etype == ET_C3D6) then
       call face_rule(nc, 1, st, w)
    else if (etype == ET_C3D20) then
       call face_rule(nc, 3, st, w)
    else
       call face_rule(nc, 2, st, w)
    end if
    deallocate (shp, nda, xg)
    allocate (shp(size(nodes), size(w)), nda(3, size(w)), xg(3, size(w)))
    do k = 1, size(w)
       call face_shape(nc, size(nodes), st(1, k), st(2, k), n, dn)
       a1 = matmul(x(:, nodes), dn(1, :))
       a2 = matmul(x(:, nodes), dn(2, :))
       shp(:, k) = n
       nda(:, k) = -w(k)*[a1(2)*a2(3) - a1(3)*a2(2), a1(3)*a2(1) - a1(1)*a2(3), a1(1)*a2(2) - a1(2)*a2(1)]
       xg(:, k) = matmul(x(:, nodes), n)
    end do
  end subroutine solid_face_points

  pure subroutine face_rule(nc, order, st, w)
    !! Points st(2, :) and weights of a face with nc corners: order² Gauss
    !! points on a quadrilateral (order 1, 2, 3); on a triangle the centroid
    !! (order 1) or three points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3) (otherwise).
    integer, intent(in) :: nc, order
    real(wp), allocatable, intent(out) :: st(:, :), w(:)
    type(quad_rule_t) :: r
    if (nc == 3) then
       r = triangle_rule(merge(TRI_CENTROID, TRI_THREE, order == 1))
    else
       r = gauss_square(order)
    end if
    call move_alloc(r%xi, st)
    call move_alloc(r%w, w)
  end subroutine face_rule

  pure subroutine face_shape(nc, nn, s, t, n, dn)
    !! Shape functions n(nn) and derivatives dn(2, nn) of a face with nc
    !! corners and nn nodes: bilinear or 8-node serendipity quadrilateral on
    !! -1..1 (corners (-1,-1), (1,-1), (1,1), (-1,1)), linear or 6-node
    !! triangle in s, t (corners (0,0), (1,0), (0,1)).
    integer, intent(in) :: nc, nn
    real(wp), intent(in) :: s, t
    real(wp), allocatable, intent(out) :: n(:), dn(:, :)
    real(wp), parameter :: SC(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], TC(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
    real(wp) :: l(3), dl(2, 3)
    integer :: a, b
    allocate (n(nn), dn(2, nn))
    if (nc == 4) then
       do a = 1, 4
          n(a) = (1.0_wp + SC(a)*s)*(1.0_wp + TC(a)*t)/4.0_wp
          dn(:, a) = [SC(a)*(1.0_wp + TC(a)*t), TC(a)*(1.0_wp + SC(a)*s)]/4.0_wp
          if (nn == 8) then
             dn(:, a) = dn(:, a)*(SC(a)*s + TC(a)*t - 1.0_wp) + n(a)*[SC(a), TC(a)]
             n(a) = n(a)*(SC(a)*s + TC(a)*t - 1.0_wp)
          end if
       end do
       if (nn == 8) then
          n(5:8) = [(1.0_wp - s*s)*(1.0_wp - t), (1.0_wp + s)*(1.0_wp - t*t), &
               (1.0_wp - s*s)*(1.0_wp + t), (1.0_wp - s)*(1.0_wp - t*t)]/2.0_wp
          dn(:, 5) = [-2.0_wp*s*(1.0_wp - t), -(1.0_wp - s*s)]/2.0_wp
          dn(:, 6) = [1.0_wp - t*t, -2.0_wp*t*(1.0_wp + s)]/2.0_wp
          dn(:, 7) = [-2.0_wp*s*(1.0_wp + t), 1.0_wp - s*s]/2.0_wp
          dn(:, 8) = [-(1.0_wp - t*t), -2.0_wp*t*(1.0_wp - s)]/2.0_wp
       end if
       return
    end if
    l = [1.0_wp - s - t, s, t]
    dl = reshape([-1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 3])
    if (nn == 3) then
       n = l
       dn = dl
       return
    end if
    do a = 1, 3
       n(a) = l(a)*(2.0_wp*l(a) - 1.0_wp)
       dn(:, a) = (4.0_wp*l(a) - 1.0_wp)*dl(:, a)
       b = mod(a, 3) + 1
       n(3 + a) = 4.0_wp*l(a)*l(b)
       dn(:, 3 + a) = 4.0_wp*(l(a)*dl(:, b) + l(b)*dl(:, a))
    end do
  end subroutine face_shape
end module superjoin_elements_solid_faces
