program test_edge_load
  !! Unit tests of the edge pressure of plane elements (superjoin_elements_edge_load):
  !! face numbering, orientation, the consistent shares on linear and quadratic
  !! edges, the resultant on a curved (parabolic) edge, and the errors.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t
  use superjoin_elements_edge_load, only: plane_edge_load, edge_node_list
  use superjoin_testing, only: check, check_close, check_rel, finish
  implicit none (type, external)
  real(wp), parameter :: TOL = 1.0e-14_wp
  real(wp), parameter :: P = 3.0_wp, T = 0.25_wp
  real(wp) :: x4(3, 4), x8(3, 8), x6(3, 6), xcw(3, 4)
  real(wp), allocatable :: fe(:)
  integer, allocatable :: nodes(:)
  type(error_t), allocatable :: error
  integer :: k

  ! unit-spaced rectangle 2 x 1, counter-clockwise
  x4 = 0.0_wp
  x4(1:2, 1) = [0.0_wp, 0.0_wp]
  x4(1:2, 2) = [2.0_wp, 0.0_wp]
  x4(1:2, 3) = [2.0_wp, 1.0_wp]
  x4(1:2, 4) = [0.0_wp, 1.0_wp]

  ! face 2 (x = 2, length 1): p t into the element (-x), half to nodes 2 and 3
  call plane_edge_load(x4, 4, 2, P, T, fe, error)
  call check(.not. allocated(error), 'CPS4 face 2 loads')
  call check_close(fe(3), -0.5_wp*P*T, TOL, 'face 2: node 2 fx')
  call check_close(fe(5), -0.5_wp*P*T, TOL, 'face 2: node 3 fx')
  call check_close(sum(abs(fe)) - P*T, 0.0_wp, TOL, 'face 2: nothing else')
  ! face 1 (y = 0, length 2): +y, P T each to nodes 1 and 2
  call plane_edge_load(x4, 4, 1, P, T, fe, error)
  call check_close(fe(2), P*T, TOL, 'face 1: node 1 fy')
  call check_close(fe(4), P*T, TOL, 'face 1: node 2 fy')
  ! face 4 (x = 0, from node 4 to node 1): +x
  call plane_edge_load(x4, 4, 4, P, T, fe, error)
  call check_close(fe(1) + fe(7), P*T, TOL, 'face 4: total fx')
  ! the same element numbered clockwise: the load still points into it
  xcw = x4(:, [1, 4, 3, 2])
  call plane_edge_load(xcw, 4, 2, P, T, fe, error)   ! face 2: nodes 4-3 of x4, y = 1
  call check_close(fe(4) + fe(6), -2.0_wp*P*T, TOL, 'clockwise: face 2 pushes down')

  ! CPS8 (mid-side nodes 5..8): straight face 2, shares 1/6, 1/6, 2/3
  x8(:, 1:4) = x4
  x8(:, 5) = 0.5_wp*(x4(:, 1) + x4(:, 2))
  x8(:, 6) = 0.5_wp*(x4(:, 2) + x4(:, 3))
  x8(:, 7) = 0.5_wp*(x4(:, 3) + x4(:, 4))
  x8(:, 8) = 0.5_wp*(x4(:, 4) + x4(:, 1))
  call plane_edge_load(x8, 4, 2, P, T, fe, error)
  call check(.not. allocated(error), 'CPS8 face 2 loads')
  call check_close(fe(3), -P*T/6.0_wp, TOL, 'CPS8 face 2: corner 2')
  call check_close(fe(5), -P*T/6.0_wp, TOL, 'CPS8 face 2: corner 3')
  call check_close(fe(11), -2.0_wp*P*T/3.0_wp, TOL, 'CPS8 face 2: mid-side node 6')
  ! curved face 2: mid-side node pushed out to x = 2.3 (a parabola): the
  ! resultant of a uniform pressure is p t times the chord turned by 90 degrees
  x8(1, 6) = 2.3_wp
  call plane_edge_load(x8, 4, 2, P, T, fe, error)
  call check_close(sum(fe(1::2)), -P*T, TOL, 'curved face: resultant x = -p t chord')
  call check_close(sum(fe(2::2)), 0.0_wp, TOL, 'curved face: resultant y = 0')
  ! ... and its moment about the chord's midpoint vanishes by symmetry
  call check_close(sum(fe(2::2)*(x8(1, :) - 2.0_wp) - fe(1::2)*(x8(2, :) - 0.5_wp)), 0.0_wp, TOL, &
       'curved face: no moment about the chord midpoint')

  ! CPS6: face 3 runs from corner 3 to corner 1 through node 6
  x6 = 0.0_wp
  x6(1:2, 1) = [0.0_wp, 0.0_wp]
  x6(1:2, 2) = [1.0_wp, 0.0_wp]
  x6(1:2, 3) = [0.0_wp, 1.0_wp]
  x6(:, 4) = 0.5_wp*(x6(:, 1) + x6(:, 2))
  x6(:, 5) = 0.5_wp*(x6(:, 2) + x6(:, 3))
  x6(:, 6) = 0.5_wp*(x6(:, 3) + x6(:, 1))
  call edge_node_list(3, 6, 3, nodes, error)
  call check(all(nodes == [3, 1, 6]), 'CPS6 face 3 nodes')
  call plane_edge_load(x6, 3, 3, P, T, fe, error)
  call check_close(fe(11), 2.0_wp*P*T/3.0_wp, TOL, 'CPS6 face 3 (x = 0): +x on node 6')
  call check_close(sum(fe(1::2)), P*T, TOL, 'CPS6 face 3: total')
  ! the hypotenuse (face 2, length sqrt 2): resultant p t (-1, -1)
  call plane_edge_load(x6, 3, 2, P, T, fe, error)
  call check_rel(sum(fe(1::2)), -P*T, TOL, 'CPS6 face 2: resultant x')
  call check_rel(sum(fe(2::2)), -P*T, TOL, 'CPS6 face 2: resultant y')

  ! errors
  call plane_edge_load(x6(:, 1:3), 3, 4, P, T, fe, error)
  call check(allocated(error), 'a triangle has no face 4')
  if (allocated(error)) call check(index(error%message, 'P1 to P3') > 0, 'message names P1 to P3')
  call edge_node_list(4, 5, 1, nodes, error)
  call check(allocated(error), '5 nodes is not a plane element')
  do k = 1, 4
     x4(1:2, k) = 0.0_wp
  end do
  call plane_edge_load(x4, 4, 1, P, T, fe, error)
  call check(allocated(error), 'zero area is refused')
  if (allocated(error)) deallocate (error)
  call finish()
end program test_edge_load
