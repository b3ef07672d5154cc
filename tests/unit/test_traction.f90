program test_traction
  !! Unit tests of Abaqus's surface tractions (*DSLOAD TRVEC, TRSHR;
  !! superjoin_elements_traction): the force at a point, and the resultants
  !! of the consistent nodal loads on a planar but non-rectangular solid face
  !! (C3D8), a quadratic triangle face (C3D10), a tilted flat S4 and S8R and a
  !! plane element's edge: magnitude × area × the (projected) unit direction,
  !! with no part along the normal for TRSHR; the errors.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_model_types, only: ET_C3D8, ET_C3D10, ET_S4, ET_S8R
  use superjoin_elements_traction, only: surface_load_t, point_force, LOAD_PRESSURE, LOAD_TRACTION, LOAD_SHEAR
  use superjoin_elements_solid_faces, only: solid_surface_load, solid_pressure_load
  use superjoin_elements_shell, only: shell_traction_load
  use superjoin_elements_edge_load, only: plane_edge_load
  use superjoin_testing, only: check, check_close, finish
  implicit none (type, external)
  real(wp), parameter :: TOL = 1.0e-13_wp
  real(wp), parameter :: T = 2.5_wp
  real(wp) :: f(3), x8(3, 8), x10(3, 10), xs4(3, 4), xs8(3, 8), xq(3, 4), d(3), e1(3), e2(3), nrm(3)
  real(wp), allocatable :: fe(:), fp(:)
  type(error_t), allocatable :: error
  integer :: k

  ! ---- the force at a point: area vector (0, 0, 2)
  call point_force(surface_load_t(LOAD_PRESSURE, T), [0.0_wp, 0.0_wp, 2.0_wp], f, error)
  call check(all(abs(f - [0.0_wp, 0.0_wp, 2*T]) <= TOL), 'pressure: p a')
  call point_force(surface_load_t(LOAD_TRACTION, T, [0.6_wp, 0.0_wp, 0.8_wp]), [0.0_wp, 0.0_wp, 2.0_wp], f, error)
  call check(all(abs(f - 2*T*[0.6_wp, 0.0_wp, 0.8_wp]) <= TOL), 'TRVEC: t |a| d')
  call point_force(surface_load_t(LOAD_SHEAR, T, [0.6_wp, 0.0_wp, 0.8_wp]), [0.0_wp, 0.0_wp, -2.0_wp], f, error)
  call check(all(abs(f - 2*T*[1.0_wp, 0.0_wp, 0.0_wp]) <= TOL), 'TRSHR: the projection, made unit, either side')
  call point_force(surface_load_t(LOAD_SHEAR, T, [0.0_wp, 0.0_wp, 1.0_wp]), [0.0_wp, 0.0_wp, 2.0_wp], f, error)
  call check(allocated(error), 'TRSHR along the normal: an error')
  if (allocated(error)) deallocate (error)

  ! ---- C3D8, face S4 (nodes 2, 6, 7, 3) in the plane x = 1, a trapezoid of area 1.5
  x8(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
  x8(:, 2) = [1.0_wp, 0.0_wp, 0.0_wp]
  x8(:, 3) = [1.0_wp, 1.0_wp, 0.0_wp]
  x8(:, 4) = [0.0_wp, 1.0_wp, 0.0_wp]
  x8(:, 5) = [0.0_wp, 0.0_wp, 1.0_wp]
  x8(:, 6) = [1.0_wp, 0.0_wp, 1.0_wp]
  x8(:, 7) = [1.0_wp, 2.0_wp, 1.0_wp]
  x8(:, 8) = [0.0_wp, 2.0_wp, 1.0_wp]
  d = [0.0_wp, 1.0_wp, 1.0_wp]/sqrt(2.0_wp)
  call solid_surface_load(ET_C3D8, x8, 4, surface_load_t(LOAD_TRACTION, T, d), fe, error)
  call check(.not. allocated(error), 'C3D8 TRVEC loads')
  call check(all(abs(resultant(fe, 3) - T*1.5_wp*d) <= TOL), 'C3D8 TRVEC: t A d')
  call check(all(fe([1, 4, 5, 8]*3 - 2) == 0.0_wp .and. fe([1, 4, 5, 8]*3) == 0.0_wp), &
       'C3D8 TRVEC: nothing on the nodes off the face')
  d = [3.0_wp, 4.0_wp, 0.0_wp]/5.0_wp
  call solid_surface_load(ET_C3D8, x8, 4, surface_load_t(LOAD_SHEAR, T, d), fe, error)
  call check(all(abs(resultant(fe, 3) - T*1.5_wp*[0.0_wp, 1.0_wp, 0.0_wp]) <= TOL), 'C3D8 TRSHR: t A, along y')
  call check(maxval(abs(fe(1::3))) == 0.0_wp, 'C3D8 TRSHR: no part along the normal x')
  ! the pressure through the same loop: unchanged, t A into the element (-x)
  call solid_pressure_load(ET_C3D8, x8, 4, T, fp, error)
  call check(all(abs(resultant(fp, 3) - T*1.5_wp*[-1.0_wp, 0.0_wp, 0.0_wp]) <= TOL), 'C3D8 pressure: t A inwards')
  d = [1.0_wp, 0.0_wp, 0.0_wp]
  call solid_surface_load(ET_C3D8, x8, 4, surface_load_t(LOAD_SHEAR, T, d), fe, error)
  call check(allocated(error), 'C3D8 TRSHR along the face normal: an error')
  if (allocated(error)) deallocate (error)

  ! ---- C3D10, face S1 (1-2-3) in z = 0 with area 3, mid-side nodes at the midpoints
  x10(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp]
  x10(:, 2) = [2.0_wp, 0.0_wp, 0.0_wp]
  x10(:, 3) = [0.0_wp, 3.0_wp, 0.0_wp]
  x10(:, 4) = [0.0_wp, 0.0_wp, 1.0_wp]
  x10(:, 5) = (x10(:, 1) + x10(:, 2))/2
  x10(:, 6) = (x10(:, 2) + x10(:, 3))/2
  x10(:, 7) = (x10(:, 3) + x10(:, 1))/2
  x10(:, 8) = (x10(:, 1) + x10(:, 4))/2
  x10(:, 9) = (x10(:, 2) + x10(:, 4))/2
  x10(:, 10) = (x10(:, 3) + x10(:, 4))/2
  d = [2.0_wp, -1.0_wp, 2.0_wp]/3.0_wp
  call solid_surface_load(ET_C3D10, x10, 1, surface_load_t(LOAD_TRACTION, T, d), fe, error)
  call check(all(abs(resultant(fe, 3) - T*3.0_wp*d) <= TOL), 'C3D10 TRVEC: t A d')
  call check(all(abs(fe(3*1 - 2:3*3) ) <= TOL), 'C3D10 TRVEC: quadratic face, corners carry nothing')
  call solid_surface_load(ET_C3D10, x10, 1, surface_load_t(LOAD_SHEAR, T, d), fe, error)
  call check(all(abs(resultant(fe, 3) - T*3.0_wp*[2.0_wp, -1.0_wp, 0.0_wp]/sqrt(5.0_wp)) <= TOL), &
       'C3D10 TRSHR: t A along the projection (2, -1, 0)/sqrt(5)')

  ! ---- shells in a tilted plane spanned by e1, e2 (normal nrm): a 2 x 1 rectangle
  e1 = [1.0_wp, 2.0_wp, 2.0_wp]/3.0_wp
  e2 = [2.0_wp, 1.0_wp, -2.0_wp]/3.0_wp
  nrm = [e1(2)*e2(3) - e1(3)*e2(2), e1(3)*e2(1) - e1(1)*e2(3), e1(1)*e2(2) - e1(2)*e2(1)]
  xs4(:, 1) = 0.0_wp
  xs4(:, 2) = 2*e1
  xs4(:, 3) = 2*e1 + e2
  xs4(:, 4) = e2
  xs8(:, 1:4) = xs4
  do k = 1, 4
     xs8(:, 4 + k) = (xs4(:, k) + xs4(:, mod(k, 4) + 1))/2
  end do
  d = 3*nrm + 4*e2   ! projection onto the plane: e2
  d = d/norm2(d)
  call shell_traction_load(ET_S4, xs4, surface_load_t(LOAD_SHEAR, T, d), fe, error)
  call check(.not. allocated(error), 'S4 TRSHR loads')
  call check(all(abs(resultant(fe, 6) - T*2.0_wp*e2) <= TOL), 'S4 TRSHR: t A e2')
  call check(all(fe(4::6) == 0.0_wp .and. fe(5::6) == 0.0_wp .and. fe(6::6) == 0.0_wp), 'S4 TRSHR: no moments')
  call shell_traction_load(ET_S8R, xs8, surface_load_t(LOAD_SHEAR, T, d), fe, error)
  call check(.not. allocated(error), 'S8R TRSHR loads')
  call check(all(abs(resultant(fe, 6) - T*2.0_wp*e2) <= TOL), 'S8R TRSHR: t A e2')
  call shell_traction_load(ET_S8R, xs8, surface_load_t(LOAD_TRACTION, T, d), fe, error)
  call check(all(abs(resultant(fe, 6) - T*2.0_wp*d) <= TOL), 'S8R TRVEC: t A d')
  call shell_traction_load(ET_S4, xs4, surface_load_t(LOAD_SHEAR, T, nrm), fe, error)
  call check(allocated(error), 'S4 TRSHR along the normal: an error')
  if (allocated(error)) deallocate (error)

  ! ---- a plane element's edge: CPS4 2 x 1, thickness 0.5, edge 2 (x = 2, length 1)
  xq = 0.0_wp
  xq(1:2, 2) = [2.0_wp, 0.0_wp]
  xq(1:2, 3) = [2.0_wp, 1.0_wp]
  xq(1:2, 4) = [0.0_wp, 1.0_wp]
  call plane_edge_load(xq, 4, 2, 0.0_wp, 0.5_wp, fe, error, ld=surface_load_t(LOAD_SHEAR, T, [0.6_wp, -0.8_wp, &
       0.0_wp]))
  call check(abs(sum(fe(2::2)) + T*0.5_wp) <= TOL .and. maxval(abs(fe(1::2))) == 0.0_wp, &
       'CPS4 edge TRSHR: t h along -y, nothing along the normal')
  call plane_edge_load(xq, 4, 2, 0.0_wp, 0.5_wp, fe, error, ld=surface_load_t(LOAD_TRACTION, T, [0.0_wp, 0.0_wp, &
       1.0_wp]))
  call check(allocated(error), 'CPS4 edge traction along z: an error')
  deallocate (error, fp)   ! the main program's arrays, for the leak checker
  if (allocated(fe)) deallocate (fe)
  call finish()

contains

  function resultant(fe, ndn) result(r)
    !! The sum of the nodal forces (the first three of each node's ndn values).
    real(wp), intent(in) :: fe(:)
    integer, intent(in) :: ndn
    real(wp) :: r(3)
    integer :: c
    do c = 1, 3
       r(c) = sum(fe(c::ndn))
    end do
  end function resultant
end program test_traction
