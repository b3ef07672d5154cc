module schur_parts_gen
  !! The synthetic parts of bench/schur_parts.f90.
  use superjoin_kinds, only: wp, i8
  use superjoin_solvers, only: sparse_sym_t
  use superjoin_utils_sorting, only: sort_unique_i8
  implicit none (type, external)
  private
  public :: grid_part

contains

  subroutine grid_part(m, h, d, diagonals, bolts, a, nb)
    !! The part: nodes (i, j, l), i, j = 1..m, l = 1..h (h = 1: a plane grid),
    !! d DOFs a node; neighbours along i, j, l, and with diagonals along the
    !! two diagonals of each cell of a plane grid. The boundary: the last j
    !! line for h = 1 (with bolts: 3 nodes on each of the 4 edges), the top
    !! floor l = h otherwise; interior nodes numbered first (l, then j
    !! slowest), the boundary last. Upper triangle, CSC.
    integer(i8), intent(in) :: m, h, d
    logical, intent(in) :: diagonals, bolts
    type(sparse_sym_t), intent(out) :: a
    integer(i8), intent(out) :: nb
    integer(i8) :: nn, p, pn, q, c, c2, k, nq, qs(13), deg, idx(3)
    integer(i8), allocatable :: newof(:), oldof(:)
    integer :: di, dj, dl, nu
    nn = m*m*h
    call numbering()
    a%n = nn*d
    allocate (a%colptr(a%n + 1), a%rowind(14*a%n*d), a%val(14*a%n*d))
    k = 0
    a%colptr(1) = 1
    do pn = 1, nn
       p = oldof(pn)
       idx = node_ijl(p)
       nq = 0
       deg = 0
       do dl = -1, 1
          do dj = -1, 1
             do di = -1, 1
                if (.not. linked(di, dj, dl)) cycle
                if (.not. inside(idx + [di, dj, dl])) cycle
                deg = deg + 1
                q = newof(node_of(idx + [di, dj, dl]))
                if (q < pn) then
                   nq = nq + 1
                   qs(nq) = q
                end if
             end do
          end do
       end do
       call sort_unique_i8(qs(1:nq), nu)
       do c = 1, d
          do q = 1, nq
             do c2 = 1, d
                k = k + 1
                a%rowind(k) = (qs(q) - 1)*d + c2
                a%val(k) = -coupling(c2, c)
             end do
          end do
          do c2 = 1, c
             k = k + 1
             a%rowind(k) = (pn - 1)*d + c2
             a%val(k) = real(deg, wp)*coupling(c2, c)
          end do
          a%colptr((pn - 1)*d + c + 1) = k + 1
       end do
    end do
  contains
    subroutine numbering()
      !! newof, oldof: interior nodes first, boundary last; nb.
      logical :: on(nn)
      integer(i8) :: x(3), n1, n2, quarter(3)
      quarter = [m/4 + 1, m/2 + 1, (3*m)/4 + 1]
      do p = 1, nn
         x = node_ijl(p)
         if (h > 1) then
            on(p) = x(3) == h
         else if (bolts) then
            on(p) = ((x(1) == 1 .or. x(1) == m) .and. any(x(2) == quarter)) .or. &
                 ((x(2) == 1 .or. x(2) == m) .and. any(x(1) == quarter))
         else
            on(p) = x(2) == m
         end if
      end do
      allocate (newof(nn), oldof(nn))
      n1 = 0
      n2 = count(.not. on, kind=i8)
      nb = (nn - n2)*d
      do p = 1, nn
         if (on(p)) then
            n2 = n2 + 1
            newof(p) = n2
         else
            n1 = n1 + 1
            newof(p) = n1
         end if
         oldof(newof(p)) = p
      end do
    end subroutine numbering
    pure function coupling(c1, c2) result(v)
      !! C = I + 0.3 J / d.
      integer(i8), intent(in) :: c1, c2
      real(wp) :: v
      v = 0.3_wp/real(d, wp)
      if (c1 == c2) v = v + 1.0_wp
    end function coupling
    pure logical function linked(di, dj, dl)
      !! Is the offset a neighbour?
      integer, intent(in) :: di, dj, dl
      integer :: nz
      nz = abs(di) + abs(dj) + abs(dl)
      linked = nz == 1 .or. (diagonals .and. dl == 0 .and. abs(di) == 1 .and. abs(dj) == 1)
    end function linked
    pure logical function inside(x)
      !! Within the grid?
      integer(i8), intent(in) :: x(3)
      inside = all(x >= 1) .and. x(1) <= m .and. x(2) <= m .and. x(3) <= h
    end function inside
    pure function node_ijl(p) result(x)
      !! (i, j, l) of node p.
      integer(i8), intent(in) :: p
      integer(i8) :: x(3)
      if (h == 1) then
         x = [mod(p - 1, m) + 1, (p - 1)/m + 1, 1_i8]
      else
         x = [mod(p - 1, m) + 1, mod((p - 1)/m, m) + 1, (p - 1)/(m*m) + 1]
      end if
    end function node_ijl
    pure function node_of(x) result(p)
      !! Node number of (i, j, l).
      integer(i8), intent(in) :: x(3)
      integer(i8) :: p
      p = x(1) + (x(2) - 1)*m + (x(3) - 1)*m*m
    end function node_of
  end subroutine grid_part
end module schur_parts_gen

program schur_parts
  !! What a condensation costs (issue 24): K* of one part by MUMPS's Schur
  !! complement (mumps_solver_t%schur, ICNTL(19)), by the default route of
  !! linear_solver_t (a_ii factored, 2 nb triangular solves), and a_ii only
  !! analyzed and factored, the three interleaved, REPS times each, medians
  !! in seconds on stdout. The part is synthetic, with the pattern of a
  !! meshed part: every pair of connected nodes couples its DOFs
  !! ([1 -1; -1 1] (x) C, C = I + 0.3 J / d, SPD), so the part floats (K* is
  !! singular, as for a part held only by its boundary):
  !!   plane M [bolts]  M x M nodes, 2 DOFs, 9-point connectivity (a CPS4
  !!             panel), boundary one edge (bolts: 3 nodes on each edge)
  !!   shell M [bolts]  M x M nodes, 6 DOFs, 9-point connectivity (an S4 panel), the same boundaries
  !!   frame M H M x M column lines, H storeys, 6 DOFs, columns and girders
  !!             (7-point lattice), boundary the top floor
  !! Up to INVERSE_DIAGONAL_MAX_N interior DOFs MUMPS's schur also computes
  !! the pivots of a_ii (a factorization of a_ii and the diagonal of its
  !! inverse), which the other two routes do not.
  !! Under mpirun every process condenses its own copy at the same time, on
  !! its own MUMPS instance (alone, as the distributed path condenses the parts
  !! it owns), after a barrier; each process prints its medians.
  !! usage: schur_parts SOLVER REPS plane|shell M [bolts] | frame M H
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, mumps_solver_t
  use superjoin_solvers_by_solves, only: by_solves_t
  use superjoin_utils_clock, only: stopwatch_t
  use superjoin_parallel_comm, only: comm_t, comm_world, agree
  use superjoin_utils_sorting, only: sort_index
  use schur_parts_gen, only: grid_part
  implicit none (type, external)

  integer, parameter :: ROUTES = 3
  character(*), parameter :: ROUTE_NAMES(ROUTES) = [character(8) :: 'schur', 'solves', 'a_ii']
  character(64) :: arg, solver_name, shape
  type(sparse_sym_t) :: a, aii
  integer(i8) :: nb, m, h
  real(wp) :: flops(ROUTES) = 0.0_wp
  integer :: reps, r, k
  real(wp), allocatable :: t(:, :)
  type(comm_t) :: comm

  call get_command_argument(1, solver_name)
  call get_command_argument(2, arg)
  read (arg, *) reps
  call get_command_argument(3, shape)
  call get_command_argument(4, arg)
  read (arg, *) m
  h = 1
  call get_command_argument(5, arg)
  select case (trim(shape))
  case ('plane')
     call grid_part(m, 1_i8, 2_i8, .true., arg == 'bolts', a, nb)
  case ('shell')
     call grid_part(m, 1_i8, 6_i8, .true., arg == 'bolts', a, nb)
  case default
     read (arg, *) h
     call grid_part(m, h, 6_i8, .false., .false., a, nb)
  end select
  aii%n = a%n - nb
  aii%colptr = a%colptr(1:aii%n + 1)
  aii%rowind = a%rowind(1:aii%colptr(aii%n + 1) - 1)
  aii%val = a%val(1:aii%colptr(aii%n + 1) - 1)
  comm = comm_world()
  allocate (t(reps, ROUTES))
  t(1, 1) = timed(3, flops(3))   ! warm-up: MPI's and MUMPS's start
  do r = 1, reps
     do k = 1, ROUTES
        t(r, k) = timed(k, flops(k))
     end do
  end do
  write (*, '(a,i0,a,i0,a,i0,a,i0,a,i0,a)') trim(solver_name)//' '//trim(shape)//': process ', comm%rank, &
       ' of ', comm%size, ', n = ', a%n, ', nb = ', nb, ', nnz = ', a%nnz(), ' (upper)'
  do k = 1, ROUTES
     write (*, '(2x,a8,a,f9.3,a,f9.3,a,f9.3,a,f7.2,a,es10.3)') ROUTE_NAMES(k), ' median', median(t(:, k)), &
          ' s  min', minval(t(:, k)), ' s  max', maxval(t(:, k)), ' s  / a_ii ', median(t(:, k))/median(t(:, 3)), &
          '  factor flops', flops(k)
  end do

contains

  function timed(route, fl) result(seconds)
    !! One condensation by the route, wall clock after a barrier; fl the
    !! flops of MUMPS's factorization (RINFOG(3)).
    integer, intent(in) :: route
    real(wp), intent(inout) :: fl
    real(wp) :: seconds
    class(linear_solver_t), allocatable :: s
    type(error_t), allocatable :: error
    type(stopwatch_t) :: clock
    real(wp), allocatable :: ks(:, :)
    integer :: worst, first
    type(by_solves_t) :: by_solves
    allocate (ks(nb, nb))
    call new_solver(trim(solver_name), a%n, s, error)
    select type (s)
    type is (mumps_solver_t)
       s%alone = .true.
    end select
    call agree(0, worst, first)
    call clock%start()
    select case (route)
    case (1)
       call s%schur(a, nb, ks, error)
    case (2)
       call move_alloc(s, by_solves%inner)
       call by_solves%schur(a, nb, ks, error)
       call move_alloc(by_solves%inner, s)
    case default
       call s%analyze(aii, error)
       if (.not. allocated(error)) call s%factorize(aii, error)
    end select
    seconds = clock%seconds()
    if (allocated(error)) then
       write (*, '(a)') 'schur_parts: '//error%message
       error stop 1
    end if
    select type (s)
    type is (mumps_solver_t)
       fl = s%flops()
    end select
    call s%release()
  end function timed

  function median(x) result(v)
    !! The median of x.
    real(wp), intent(in) :: x(:)
    real(wp) :: v
    integer :: order(size(x)), i
    order = [(i, i=1, size(x))]
    call sort_index(x, order)
    v = 0.5_wp*(x(order((size(x) + 1)/2)) + x(order(size(x)/2 + 1)))
  end function median
end program schur_parts
