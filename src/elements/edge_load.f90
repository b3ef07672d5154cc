module superjoin_elements_edge_load
  !! Pressure on an edge (a face, in CalculiX's words) of a plane element:
  !! *DLOAD P1 ... P4 on CPS3/CPS4/CPE3/CPE4, and on any plane element whose
  !! nodes are the corners (counter-clockwise or clockwise) followed by one
  !! mid-side node per edge (CPS6/CPS8 and their plane-strain twins).
  !!
  !! Faces as CalculiX numbers them: face k runs from corner k to corner k+1
  !! (the last face back to corner 1), with the mid-side node ncorner + k of a
  !! quadratic element between them. The pressure p (force per unit area,
  !! positive into the element, against the outward normal) acts on the face of
  !! thickness t: the force per unit length of edge is -p t n_out. The nodal
  !! loads are ∫ N_i (-p t n_out) ds with the 1D shape functions of the edge's
  !! nodes (linear on two nodes, quadratic on three), Gauss-Legendre with three
  !! points: exact for straight and curved (quadratic) edges alike. Abaqus's
  !! tractions TRVEC and TRSHR (a force per unit area along a direction of the
  !! XY plane; TRSHR along the edge) take the same points.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_elements_traction, only: surface_load_t, point_force, LOAD_PRESSURE
  implicit none (type, external)
  private

  public :: plane_edge_load, edge_node_list

  integer, parameter :: NGAUSS = 3
  real(wp), parameter :: GAUSS_S(NGAUSS) = [-sqrt(0.6_wp), 0.0_wp, sqrt(0.6_wp)]
  real(wp), parameter :: GAUSS_W(NGAUSS) = [5.0_wp/9.0_wp, 8.0_wp/9.0_wp, 5.0_wp/9.0_wp]

contains

  pure subroutine edge_node_list(ncorner, nnode, face, nodes, error)
    !! Local node numbers of face `face` of a plane element with ncorner corners
    !! (3 or 4) and nnode nodes (ncorner, or 2 ncorner with mid-side nodes):
    !! the two corners, then the mid-side node when there is one.
    integer, intent(in) :: ncorner, nnode, face
    integer, allocatable, intent(out) :: nodes(:)
    type(error_t), allocatable, intent(out) :: error
    character(len=12) :: buf
    if ((ncorner /= 3 .and. ncorner /= 4) .or. (nnode /= ncorner .and. nnode /= 2*ncorner)) then
       call fatal_error(error, EXIT_DECK, 'edge pressure on an element that is not a plane element')
       return
    end if
    if (face < 1 .or. face > ncorner) then
       write (buf, '(i0)') ncorner
       call fatal_error(error, EXIT_DECK, 'an element with '//trim(buf)//' edges has faces P1 to P'//trim(buf))
       return
    end if
    if (nnode == ncorner) then
       nodes = [face, modulo(face, ncorner) + 1]
    else
       nodes = [face, modulo(face, ncorner) + 1, ncorner + face]
    end if
  end subroutine edge_node_list

  pure subroutine plane_edge_load(x, ncorner, face, p, t, fe, error, axisymmetric, ld)
    !! Nodal loads fe (node-major, (fx, fy) per node, global X and Y) of a
    !! pressure p on face `face` of a plane element of thickness t with nodes
    !! x(3, nnode) in the XY plane (see the module header for the numbering).
    !! axisymmetric (present and true): the face of a solid of revolution about
    !! y, r = x: the thickness is 2π r along the edge (the whole circumference).
    !! ld (present): the surface load ld (superjoin_elements_traction: a
    !! traction TRVEC or TRSHR, direction in the XY plane) instead of p.
    real(wp), intent(in) :: x(:, :)
    integer, intent(in) :: ncorner, face
    real(wp), intent(in) :: p, t
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: axisymmetric
    type(surface_load_t), intent(in), optional :: ld
    integer, allocatable :: nodes(:)
    real(wp) :: orient, n(3), dn(3), dxds(2), s, tw, f(3)
    type(surface_load_t) :: load
    integer :: nnode, g, a
    nnode = size(x, 2)
    call edge_node_list(ncorner, nnode, face, nodes, error)
    if (allocated(error)) return
    load = surface_load_t(LOAD_PRESSURE, p)
    if (present(ld)) then
       load = ld
       if (ld%dir(3) /= 0.0_wp) then
          call fatal_error(error, EXIT_DECK, 'a traction along Z on a plane element (its direction must lie in the '// &
               'XY plane)')
          return
       end if
    end if
    orient = sign(1.0_wp, signed_area(x(1:2, 1:ncorner)))
    if (signed_area(x(1:2, 1:ncorner)) == 0.0_wp) then
       call fatal_error(error, EXIT_DECK, 'edge pressure on an element of zero area')
       return
    end if
    allocate (fe(2*nnode), source=0.0_wp)
    do g = 1, NGAUSS
       s = GAUSS_S(g)
       call edge_shape(size(nodes), s, n, dn)
       dxds = 0.0_wp
       tw = t
       do a = 1, size(nodes)
          dxds = dxds + dn(a)*x(1:2, nodes(a))
       end do
       if (present(axisymmetric)) then
          if (axisymmetric) tw = 8.0_wp*atan(1.0_wp)*dot_product(n(1:size(nodes)), x(1, nodes))
       end if
       ! outward normal times |dx/ds|: (dy, -dx) orient; a positive pressure pushes against it
       call point_force(load, -GAUSS_W(g)*tw*orient*[dxds(2), -dxds(1), 0.0_wp], f, error)
       if (allocated(error)) return
       do a = 1, size(nodes)
          fe(2*nodes(a) - 1:2*nodes(a)) = fe(2*nodes(a) - 1:2*nodes(a)) + n(a)*f(1:2)
       end do
    end do
  end subroutine plane_edge_load

  pure subroutine edge_shape(nn, s, n, dn)
    !! 1D shape functions of an edge with nn = 2 (linear) or 3 (corner, corner,
    !! middle; quadratic) nodes at s in [-1, 1], and their derivatives.
    integer, intent(in) :: nn
    real(wp), intent(in) :: s
    real(wp), intent(out) :: n(3), dn(3)
    n = 0.0_wp
    dn = 0.0_wp
    if (nn == 2) then
       n(1:2) = [0.5_wp*(1.0_wp - s), 0.5_wp*(1.0_wp + s)]
       dn(1:2) = [-0.5_wp, 0.5_wp]
    else
       n = [0.5_wp*s*(s - 1.0_wp), 0.5_wp*s*(s + 1.0_wp), 1.0_wp - s*s]
       dn = [s - 0.5_wp, s + 0.5_wp, -2.0_wp*s]
    end if
  end subroutine edge_shape

  pure real(wp) function signed_area(xy)
    !! Signed area of the polygon of the corners xy(2, n) (> 0 counter-clockwise).
    real(wp), intent(in) :: xy(:, :)
    integer :: i, j
    signed_area = 0.0_wp
    do i = 1, size(xy, 2)
       j = modulo(i, size(xy, 2)) + 1
       signed_area = signed_area + xy(1, i)*xy(2, j) - xy(1, j)*xy(2, i)
    end do
    signed_area = 0.5_wp*signed_area
  end function signed_area
end module superjoin_elements_edge_load
