program test_solids
  !! Unit tests of the 3D solid elements (superjoin_elements_solid): partition
  !! of unity and nodal interpolation of the shape functions, symmetry of the
  !! element matrix, the six rigid-body modes in its null space, the number of
  !! zero eigenvalues (6 for C3D8, C3D20, C3D4, C3D10, C3D15; 12 for the single C3D20R:
  !! six spurious modes of the 2×2×2 rule, not communicable in a mesh; 7 for the
  !! single C3D6: one of its two points on the triangle's centroid, as CalculiX's), the
  !! volume from the consistent body load, K u = 0 rows for a linear field
  !! (constant strain: Σ K u equals the nodal forces of a constant stress),
  !! and the refusals (inverted element, ν = 0.5). Patch tests on meshes, the
  !! cantilever and the CalculiX cross-check run through the whole program in
  !! tests/solids/verify_solids.py. C3D8R (one point, hourglass stiffness):
  !! exactly 6 zero eigenvalues on the distorted element, the forces of a
  !! linear field those of C3D8 (the constant stress, to round-off), and on a
  !! parallelepiped the stiffness of C3D8I.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: material_t, ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, &
       ET_C3D6, ET_C3D15, ET_C3D8R
  use superjoin_elements_solid, only: solid_stiffness, solid_body_load, solid_shape, solid_rule
  use superjoin_elements_quadrature, only: quad_rule_t
  use superjoin_elements_solid_faces, only: solid_pressure_load, solid_face_nodes
  use superjoin_elements_solid_stress, only: solid_extrapolation, principal_stresses, von_mises_tensor
  use superjoin_testing, only: check, check_close, check_rel, finish
  use test_lapack, only: eigenvalues
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)

  real(wp), parameter :: TOL_EXACT = 1.0e-12_wp    !! exact discrete answers, relative
  real(wp), parameter :: TOL_ZERO_EIG = 1.0e-10_wp !! a zero eigenvalue, relative to the largest
  real(wp), parameter :: MIN_POSITIVE = 1.0e-6_wp  !! smallest non-zero eigenvalue / largest, at least
  integer, parameter :: TYPES(9) = [ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, &
       ET_C3D8R]
  character(len=6), parameter :: NAMES(9) = ['C3D8  ', 'C3D20 ', 'C3D20R', 'C3D4  ', 'C3D10 ', 'C3D8I ', &
       'C3D6  ', 'C3D15 ', 'C3D8R ']
  integer, parameter :: ZERO_EIGS(9) = [6, 6, 12, 6, 6, 6, 7, 6, 6]
  type(material_t) :: mat
  integer :: k

  mat%e = 2.1e5_wp
  mat%nu = 0.3_wp
  do k = 1, size(TYPES)
     call test_shapes(TYPES(k), NAMES(k))
     call test_matrix(TYPES(k), NAMES(k), ZERO_EIGS(k))
     call test_volume(TYPES(k), NAMES(k))
     call test_faces(TYPES(k), NAMES(k))
     call test_extrapolation(TYPES(k), NAMES(k))
  end do
  call test_reduced()
  call test_invariants()
  call test_errors()
  call finish()

contains

  subroutine element_nodes(etype, x)
    !! A distorted element of each type: the reference element mapped by a
    !! smooth non-affine map (curved sides for the quadratic types).
    integer, intent(in) :: etype
    real(wp), allocatable, intent(out) :: x(:, :)
    real(wp) :: r(3, 20)
    integer :: a, nn
    call reference_nodes(etype, r, nn)
    allocate (x(3, nn))
    do a = 1, nn
       x(:, a) = [2.0_wp*r(1, a) + 0.3_wp*r(2, a) + 0.1_wp*r(2, a)*r(3, a), &
            1.5_wp*r(2, a) - 0.2_wp*r(1, a) + 0.08_wp*r(1, a)**2, &
            r(3, a) + 0.15_wp*r(1, a) + 0.1_wp*r(1, a)*r(2, a)]
    end do
  end subroutine element_nodes

  subroutine reference_nodes(etype, r, nn)
    !! Natural coordinates r(:, 1:nn) of the nn nodes (Abaqus order).
    integer, intent(in) :: etype
    real(wp), intent(out) :: r(3, 20)
    integer, intent(out) :: nn
    real(wp), parameter :: HEX(3, 20) = reshape([ &
         -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1, &
         0, -1, -1, 1, 0, -1, 0, 1, -1, -1, 0, -1, 0, -1, 1, 1, 0, 1, 0, 1, 1, -1, 0, 1, &
         -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]*1.0_wp, [3, 20])
    real(wp), parameter :: TET(3, 10) = reshape([ &
         0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
         0.5_wp, 0.0_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp, 0.0_wp, 0.5_wp, 0.0_wp, &
         0.0_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp, 0.5_wp, 0.0_wp, 0.5_wp, 0.5_wp], [3, 10])
    real(wp), parameter :: WEDGE(3, 15) = reshape([ &
         0.0_wp, 0.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, -1.0_wp, &
         0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, &
         0.5_wp, 0.0_wp, -1.0_wp, 0.5_wp, 0.5_wp, -1.0_wp, 0.0_wp, 0.5_wp, -1.0_wp, &
         0.5_wp, 0.0_wp, 1.0_wp, 0.5_wp, 0.5_wp, 1.0_wp, 0.0_wp, 0.5_wp, 1.0_wp, &
         0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], [3, 15])
    r = 0.0_wp
    if (etype == ET_C3D6 .or. etype == ET_C3D15) then
       nn = merge(6, 15, etype == ET_C3D6)
       r(:, 1:nn) = WEDGE(:, 1:nn)
       return
    end if
    nn = merge(8, merge(20, merge(4, 10, etype == ET_C3D4), etype == ET_C3D20 .or. etype == ET_C3D20R), &
         etype == ET_C3D8 .or. etype == ET_C3D8I .or. etype == ET_C3D8R)
    if (etype == ET_C3D4 .or. etype == ET_C3D10) then
       r(:, 1:nn) = TET(:, 1:nn)
    else
       r(:, 1:nn) = HEX(:, 1:nn)
    end if
  end subroutine reference_nodes

  subroutine test_shapes(etype, name)
    !! N_a(ξ_b) = δ_ab, Σ N_a = 1 and Σ ∂N_a/∂ξ = 0 at an inner point.
    integer, intent(in) :: etype
    character(*), intent(in) :: name
    real(wp), allocatable :: n(:), dn(:, :), id(:, :)
    real(wp) :: r(3, 20)
    integer :: a, nn
    call reference_nodes(etype, r, nn)
    allocate (id(nn, nn))
    do a = 1, nn
       call solid_shape(etype, r(:, a), n, dn)
       id(:, a) = n
    end do
    do a = 1, nn
       id(a, a) = id(a, a) - 1.0_wp
    end do
    call check(maxval(abs(id)) < TOL_EXACT, trim(name)//': N_a(node b) = delta_ab')
    call solid_shape(etype, [0.21_wp, 0.13_wp, 0.37_wp], n, dn)
    call check_close(sum(n), 1.0_wp, TOL_EXACT, trim(name)//': partition of unity')
    call check(maxval(abs(sum(dn, 2))) < TOL_EXACT, trim(name)//': derivatives sum to zero')
  end subroutine test_shapes

  subroutine test_matrix(etype, name, nzero)
    !! Symmetry, rigid-body modes, zero eigenvalues, constant-strain forces.
    integer, intent(in) :: etype, nzero
    character(*), intent(in) :: name
    real(wp), allocatable :: x(:, :), ke(:, :), u(:), w(:), f(:)
    type(error_t), allocatable :: error
    real(wp) :: kmax, rot(3), c(3)
    integer :: a, m, nn, nz
    call element_nodes(etype, x)
    nn = size(x, 2)
    call solid_stiffness(etype, x, mat, ke, error)
    call check(.not. allocated(error), trim(name)//': stiffness')
    if (allocated(error)) return
    kmax = maxval(abs(ke))
    call check(maxval(abs(ke - transpose(ke))) < TOL_EXACT*kmax, trim(name)//': symmetric')
    allocate (u(3*nn))
    c = sum(x, 2)/nn
    do m = 1, 6                                   ! three translations, three rotations
       do a = 1, nn
          if (m <= 3) then
             u(3*a - 2:3*a) = 0.0_wp
             u(3*a - 3 + m) = 1.0_wp
          else
             rot = 0.0_wp
             rot(m - 3) = 1.0_wp
             u(3*a - 2:3*a) = cross(rot, x(:, a) - c)
          end if
       end do
       f = matmul(ke, u)
       call check(maxval(abs(f)) < TOL_EXACT*kmax*maxval(abs(u)), trim(name)//': rigid mode '//itoa(m)//' has no force')
    end do
    w = eigenvalues(ke)
    nz = count(abs(w) < TOL_ZERO_EIG*maxval(w))
    call check(nz == nzero, trim(name)//': '//itoa(nz)//' zero eigenvalues, expected '//itoa(nzero))
    call check(minval(w) > -TOL_ZERO_EIG*maxval(w), trim(name)//': no negative eigenvalue')
    call check(w(nzero + 1) > MIN_POSITIVE*maxval(w), trim(name)//': the other eigenvalues are positive')
  end subroutine test_matrix

  subroutine test_volume(etype, name)
    !! Σ_a of the consistent body load (1, 2, 3) per unit volume = (1, 2, 3) × volume;
    !! the volume of the affine image of the reference element is |det A| × its volume.
    integer, intent(in) :: etype
    character(*), intent(in) :: name
    real(wp), allocatable :: x(:, :), fe(:)
    real(wp) :: r(3, 20)
    type(error_t), allocatable :: error
    real(wp), parameter :: A(3, 3) = reshape([2.0_wp, 0.1_wp, 0.2_wp, 0.3_wp, 1.5_wp, -0.1_wp, &
         0.0_wp, 0.2_wp, 1.2_wp], [3, 3])
    real(wp) :: vol, deta
    integer :: d, nn
    call reference_nodes(etype, r, nn)
    x = matmul(A, r(:, 1:nn))
    deta = A(1, 1)*(A(2, 2)*A(3, 3) - A(2, 3)*A(3, 2)) - A(1, 2)*(A(2, 1)*A(3, 3) - A(2, 3)*A(3, 1)) &
         + A(1, 3)*(A(2, 1)*A(3, 2) - A(2, 2)*A(3, 1))
    vol = deta*merge(8.0_wp, 1.0_wp/6.0_wp, nn == 8 .or. nn == 20)
    if (nn == 6 .or. nn == 15) vol = deta           ! the reference wedge: a half square times 2
    call solid_body_load(etype, x, [1.0_wp, 2.0_wp, 3.0_wp], fe, error)
    call check(.not. allocated(error), trim(name)//': body load')
    if (allocated(error)) return
    do d = 1, 3
       call check_rel(sum(fe(d::3)), d*vol, TOL_EXACT, trim(name)//': body load sums to volume x force')
    end do
  end subroutine test_volume

  subroutine test_faces(etype, name)
    !! Pressure p on each face of the affine image of the reference element:
    !! the nodal loads sum to p × the face's area, along its inward normal
    !! (towards the element's centroid), and over all faces to zero.
    integer, intent(in) :: etype
    character(*), intent(in) :: name
    real(wp), allocatable :: x(:, :), fe(:)
    integer, allocatable :: nodes(:)
    real(wp) :: r(3, 20), res(3), total(3), area(3), c(3)
    type(error_t), allocatable :: error
    real(wp), parameter :: A(3, 3) = reshape([2.0_wp, 0.1_wp, 0.2_wp, 0.3_wp, 1.5_wp, -0.1_wp, &
         0.0_wp, 0.2_wp, 1.2_wp], [3, 3]), P = 3.0_wp
    integer :: f, nc, nn, d
    call reference_nodes(etype, r, nn)
    x = matmul(A, r(:, 1:nn))
    c = sum(x, 2)/nn
    total = 0.0_wp
    do f = 1, merge(6, merge(5, 4, nn == 6 .or. nn == 15), nn == 8 .or. nn == 20)
       call solid_pressure_load(etype, x, f, P, fe, error)
       call check(.not. allocated(error), trim(name)//': pressure on face '//itoa(f))
       if (allocated(error)) return
       call solid_face_nodes(etype, f, nodes, nc)
       res = [(sum(fe(d::3)), d=1, 3)]
       total = total + res
       if (nc == 4) then       ! a flat quadrilateral: half the cross product of its diagonals
          area = 0.5_wp*cross(x(:, nodes(3)) - x(:, nodes(1)), x(:, nodes(4)) - x(:, nodes(2)))
       else
          area = 0.5_wp*cross(x(:, nodes(2)) - x(:, nodes(1)), x(:, nodes(3)) - x(:, nodes(1)))
       end if
       call check_rel(norm2(res), P*norm2(area), TOL_EXACT, trim(name)//': face '//itoa(f)//' load = p area')
       call check(dot_product(res, c - sum(x(:, nodes(1:nc)), 2)/nc) > 0.0_wp, &
            trim(name)//': face '//itoa(f)//' pushed into the element')
    end do
    call check(maxval(abs(total)) < TOL_EXACT*P*maxval(abs(x))**2, trim(name)//': closed surface, no net force')
    call solid_pressure_load(etype, x, f, P, fe, error)
    call check(allocated(error), trim(name)//': face '//itoa(f)//' refused')
  end subroutine test_faces

  subroutine test_extrapolation(etype, name)
    !! The nodal extrapolation of the integration-point values: a constant
    !! field stays constant (rows sum to 1); where the points determine the
    !! element's own field (C3D8, C3D20), its values at the points give
    !! back its nodal values (E N = I).
    integer, intent(in) :: etype
    character(*), intent(in) :: name
    real(wp), allocatable :: e(:, :), nmat(:, :), n(:), dn(:, :), id(:, :)
    type(quad_rule_t) :: rl
    integer :: g, a
    allocate (e, source=solid_extrapolation(etype))
    call check(maxval(abs(sum(e, 2) - 1.0_wp)) < TOL_EXACT, trim(name)//': extrapolation keeps a constant')
    if (etype /= ET_C3D8 .and. etype /= ET_C3D20 .and. etype /= ET_C3D8I) return
    rl = solid_rule(etype, .false.)
    allocate (nmat(size(rl%w), size(e, 1)))
    do g = 1, size(rl%w)
       call solid_shape(etype, rl%xi(:, g), n, dn)
       nmat(g, :) = n
    end do
    allocate (id, source=matmul(e, nmat))
    do a = 1, size(id, 1)
       id(a, a) = id(a, a) - 1.0_wp
    end do
    call check(maxval(abs(id)) < 1.0e-10_wp, trim(name)//': extrapolation returns the element''s own field')
  end subroutine test_extrapolation

  subroutine test_reduced()
    !! C3D8R: on the distorted element, K u of a linear field u = G x equals
    !! C3D8's (both the consistent forces of the constant stress: the element
    !! patch test); on a parallelepiped its stiffness is C3D8I's.
    real(wp), allocatable :: x(:, :), kr(:, :), k8(:, :), u(:)
    type(error_t), allocatable :: error
    real(wp) :: g(3, 3)
    integer :: a
    call element_nodes(ET_C3D8R, x)
    call solid_stiffness(ET_C3D8R, x, mat, kr, error)
    if (.not. allocated(error)) call solid_stiffness(ET_C3D8, x, mat, k8, error)
    call check(.not. allocated(error), 'C3D8R: stiffness of the distorted element')
    if (allocated(error)) return
    g = reshape([0.3_wp, -0.2_wp, 0.5_wp, 0.7_wp, 0.1_wp, -0.4_wp, 0.25_wp, 0.6_wp, -0.15_wp], [3, 3])
    allocate (u(24))
    do a = 1, 8
       u(3*a - 2:3*a) = matmul(g, x(:, a)) + [0.1_wp, 0.2_wp, 0.3_wp]
    end do
    call check(maxval(abs(matmul(kr - k8, u))) < TOL_EXACT*maxval(abs(matmul(k8, u))), &
         'C3D8R: a linear field gives the forces of its constant stress (as C3D8), distorted element')
    do a = 1, 8                                   ! a parallelepiped: x = A ξ + c
       x(:, a) = matmul(reshape([2.0_wp, 0.3_wp, 0.1_wp, 0.4_wp, 1.5_wp, -0.2_wp, 0.3_wp, 0.2_wp, 1.0_wp], [3, 3]), &
            x_corner(a)) + [1.0_wp, 2.0_wp, 3.0_wp]
    end do
    call solid_stiffness(ET_C3D8R, x, mat, kr, error)
    if (.not. allocated(error)) call solid_stiffness(ET_C3D8I, x, mat, k8, error)
    call check(.not. allocated(error), 'C3D8R: stiffness of the parallelepiped')
    if (allocated(error)) return
    call check(maxval(abs(kr - k8)) < TOL_EXACT*maxval(abs(k8)), 'C3D8R: the stiffness of C3D8I on a parallelepiped')
  end subroutine test_reduced

  function x_corner(a) result(c)
    !! Natural coordinates of hexahedron corner a.
    integer, intent(in) :: a
    real(wp) :: c(3), r(3, 20)
    integer :: nn
    call reference_nodes(ET_C3D8, r, nn)
    c = r(:, a)
  end function x_corner

  subroutine test_invariants()
    !! Von Mises and principal stresses of known tensors.
    real(wp) :: p(3)
    p = principal_stresses([3.0_wp, -1.0_wp, 2.0_wp, 0.0_wp, 0.0_wp, 0.0_wp])
    call check(maxval(abs(p - [3.0_wp, 2.0_wp, -1.0_wp])) < TOL_EXACT, 'principal stresses of a diagonal tensor')
    p = principal_stresses([0.0_wp, 0.0_wp, 0.0_wp, 5.0_wp, 0.0_wp, 0.0_wp])
    call check(maxval(abs(p - [5.0_wp, 0.0_wp, -5.0_wp])) < TOL_EXACT, 'principal stresses of pure shear')
    ! a turned uniaxial stress: its two zero principal values to the round-off of the
    ! largest (the cubic's trigonometric solution gave them as 1e-9 of it)
    p = principal_stresses(turned([1.0e7_wp, 0.0_wp, 0.0_wp]))
    call check(abs(p(1) - 1.0e7_wp) < 1.0e7_wp*TOL_EXACT .and. maxval(abs(p(2:3))) < 1.0e7_wp*TOL_EXACT, &
         'principal stresses of a turned uniaxial stress: 1e7, 0, 0 to round-off')
    p = principal_stresses(turned([3.0_wp, 2.0_wp, -1.0_wp]))
    call check(maxval(abs(p - [3.0_wp, 2.0_wp, -1.0_wp])) < TOL_EXACT, 'principal stresses of a turned tensor')
    call check_close(von_mises_tensor([0.0_wp, 0.0_wp, 0.0_wp, 5.0_wp, 0.0_wp, 0.0_wp]), 5.0_wp*sqrt(3.0_wp), &
         TOL_EXACT*10, 'von Mises of pure shear = sqrt(3) tau')
    call check_close(von_mises_tensor([7.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]), 7.0_wp, TOL_EXACT*10, &
         'von Mises of uniaxial stress')
  end subroutine test_invariants

  pure function turned(d) result(v)
    !! The tensor diag(d) turned by a fixed rotation (30°, 40°, 50° about z, y, x), Voigt order.
    real(wp), intent(in) :: d(3)
    real(wp) :: v(6), r(3, 3), t(3, 3), ca, sa
    integer :: k
    real(wp), parameter :: ANG(3) = [30.0_wp, 40.0_wp, 50.0_wp]*acos(-1.0_wp)/180.0_wp
    r = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
    do k = 1, 3
       ca = cos(ANG(k))
       sa = sin(ANG(k))
       t = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
       select case (k)
       case (1)
          t(1:2, 1:2) = reshape([ca, sa, -sa, ca], [2, 2])
       case (2)
          t([1, 3], [1, 3]) = reshape([ca, -sa, sa, ca], [2, 2])
       case default
          t(2:3, 2:3) = reshape([ca, sa, -sa, ca], [2, 2])
       end select
       r = matmul(t, r)
    end do
    t = matmul(r, matmul(reshape([d(1), 0.0_wp, 0.0_wp, 0.0_wp, d(2), 0.0_wp, 0.0_wp, 0.0_wp, d(3)], [3, 3]), &
         transpose(r)))
    v = [t(1, 1), t(2, 2), t(3, 3), t(1, 2), t(1, 3), t(2, 3)]
  end function turned

  subroutine test_errors()
    !! An inverted element and an incompressible material are refused.
    real(wp), allocatable :: x(:, :), ke(:, :)
    type(error_t), allocatable :: error
    type(material_t) :: bad
    call element_nodes(ET_C3D8, x)
    x(:, [1, 2, 3, 4, 5, 6, 7, 8]) = x(:, [5, 6, 7, 8, 1, 2, 3, 4])   ! top and bottom swapped
    call solid_stiffness(ET_C3D8, x, mat, ke, error)
    call check(allocated(error), 'inverted C3D8 refused')
    bad = mat
    bad%nu = 0.5_wp
    call element_nodes(ET_C3D4, x)
    call solid_stiffness(ET_C3D4, x, bad, ke, error)
    call check(allocated(error), 'nu = 0.5 refused')
  end subroutine test_errors

  pure function cross(a, b) result(c)
    !! a × b.
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross
end program test_solids
