program test_schur
  !! Static condensation by the backends' own schur (CHOLMOD: the boundary
  !! ordered last and read off the factor; LAPACK: forward solves only)
  !! against the default route (a_ii factored, 2 nb solves): K*, the interior
  !! solves and pivots after it, and the column of a breakdown in the interior;
  !! a condensation's loads and interior recovery (condense_loads,
  !! recover_interior: CHOLMOD's halves of one solve with the whole part's
  !! factor, the others' solves with a_ii) against dense arithmetic.
  !! Two plates in one part give a block-diagonal L_bb (several supernodes).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, EXIT_SINGULAR
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, cholmod_solver_t
  use superjoin_solvers_solver, only: schur_by_solves
  use superjoin_substructure_condensed, only: condensed_t, condense_loads, recover_interior
  use superjoin_testing, only: check, check_close, finish
  implicit none (type, external)

  character(len=*), parameter :: BACKENDS(2) = [character(len=7) :: 'cholmod', 'lapack']
  integer :: ib

  do ib = 1, size(BACKENDS)
     write (*, '(a)') '--- '//trim(BACKENDS(ib))
     call test_floating(trim(BACKENDS(ib)), 30, 1, 'floating plate, boundary on two edges')
     call test_floating(trim(BACKENDS(ib)), 24, 2, 'two floating plates in one part')
     call test_floating(trim(BACKENDS(ib)), 4, 1, 'small plate')
     call test_small_interior(trim(BACKENDS(ib)))
     call test_no_boundary(trim(BACKENDS(ib)))
     call test_breakdown(trim(BACKENDS(ib)))
  end do
  call finish()

contains

  subroutine test_floating(name, m, npieces, what)
    !! npieces m x m membranes, free (a singular K*), with every second DOF
    !! scaled by 1e3 (translations and rotations differ by orders of magnitude);
    !! boundary: the first and last grid column of each piece; one interior
    !! DOF without stiffness (diagonal 1, as condensation drops it) and one
    !! boundary DOF without stiffness (a zero row).
    character(*), intent(in) :: name, what
    integer, intent(in) :: m, npieces
    real(wp), allocatable :: ad(:, :)
    integer, allocatable :: order(:)
    integer :: nb, ni, n, p, i, j, k
    logical, allocatable :: isb(:)
    n = npieces*m*m + 2
    allocate (ad(n, n), isb(n))
    ad = 0.0_wp
    isb = .false.
    do p = 0, npieces - 1
       do j = 1, m
          do i = 1, m
             k = p*m*m + (j - 1)*m + i
             if (i < m) call spring(ad, k, k + 1, 1.0_wp + 0.1_wp*p)
             if (j < m) call spring(ad, k, k + m, 2.0_wp)
             isb(k) = (j == 1 .or. j == m)
          end do
       end do
    end do
    do k = 2, n, 2
       ad(:, k) = 1.0e3_wp*ad(:, k)
       ad(k, :) = 1.0e3_wp*ad(k, :)
    end do
    ad(n - 1, n - 1) = 1.0_wp     ! a free interior DOF (dropped: diagonal 1)
    isb(n) = .true.               ! a boundary DOF without stiffness
    nb = count(isb)
    ni = n - nb
    order = [pack([(k, k=1, n)], .not. isb), pack([(k, k=1, n)], isb)]
    call compare_routes(name, ad(order, order), int(nb, i8), what)
  end subroutine test_floating

  subroutine test_small_interior(name)
    !! ni = 1 and ni = 2: a short chain of springs, the ends on the boundary.
    character(*), intent(in) :: name
    real(wp) :: ad(4, 4)
    ad = 0.0_wp
    call spring(ad, 1, 3, 5.0_wp)
    call spring(ad, 1, 4, 2.0_wp)
    call compare_routes(name, ad(1:3, 1:3), 2_i8, 'ni = 1')
    ad = 0.0_wp
    call spring(ad, 1, 2, 5.0_wp)
    call spring(ad, 1, 3, 2.0_wp)
    call spring(ad, 2, 4, 7.0_wp)
    call compare_routes(name, ad, 2_i8, 'ni = 2')
  end subroutine test_small_interior

  subroutine test_no_boundary(name)
    !! nb = 0: K* is empty and the solver holds the factor of the whole part.
    character(*), intent(in) :: name
    real(wp) :: ad(5, 5)
    integer :: i
    ad = 0.0_wp
    do i = 1, 4
       call spring(ad, i, i + 1, real(i, wp))
    end do
    ad(1, 1) = ad(1, 1) + 1.0_wp
    call compare_routes(name, ad, 0_i8, 'nb = 0')
  end subroutine test_no_boundary

  subroutine test_breakdown(name)
    !! An interior mechanism: interior DOFs 4..6 a free chain joined to
    !! nothing; the breakdown is reported at an interior column of the
    !! chain, 4..6, as by the default route.
    character(*), intent(in) :: name
    real(wp) :: ad(9, 9)
    class(linear_solver_t), allocatable :: s1, s2
    type(sparse_sym_t) :: a
    type(error_t), allocatable :: error
    real(wp) :: k1(3, 3), k2(3, 3)
    ad = 0.0_wp
    call spring(ad, 1, 2, 1.0_wp)
    call spring(ad, 2, 3, 1.0_wp)
    call spring(ad, 3, 7, 1.0_wp)
    call spring(ad, 1, 8, 1.0_wp)
    call spring(ad, 4, 5, 3.0_wp)
    call spring(ad, 5, 6, 3.0_wp)
    call spring(ad, 2, 9, 1.0_wp)
    call from_dense(ad, a)
    call new_solver(name, 6_i8, s1, error)
    call new_solver(name, 6_i8, s2, error)
    call s1%schur(a, 3_i8, k1, error)
    call check(allocated(error), name//' breakdown: reported')
    if (.not. allocated(error)) return
    call check(error%code == EXIT_SINGULAR, name//' breakdown: EXIT_SINGULAR')
    deallocate (error)
    call schur_by_solves(s2, a, 3_i8, k2, error)
    call check(allocated(error), name//' breakdown: reported by the default route')
    call check(s2%info%failed_column >= 4 .and. s2%info%failed_column <= 6, name//' breakdown: default route')
    call check(s1%info%failed_column >= 4 .and. s1%info%failed_column <= 6, name//' breakdown: an interior column')
    call s1%release()
    call s2%release()
  end subroutine test_breakdown

  subroutine compare_routes(name, ad, nb, what)
    !! K*, an interior solve and the interior pivots of the backend's schur
    !! against the default route; K* entries to 1e-13 of sqrt(k_ii k_jj).
    character(*), intent(in) :: name, what
    real(wp), intent(in) :: ad(:, :)
    integer(i8), intent(in) :: nb
    class(linear_solver_t), allocatable :: s1, s2
    type(sparse_sym_t) :: a
    type(error_t), allocatable :: error
    real(wp), allocatable :: k1(:, :), k2(:, :), b(:, :), x1(:, :), x2(:, :), d1(:), d2(:), sc(:)
    integer(i8) :: n, ni, i, j
    real(wp) :: worst
    n = size(ad, 1, i8)
    ni = n - nb
    call from_dense(ad, a)
    allocate (k1(nb, nb), k2(nb, nb), b(ni, 2), x1(ni, 2), x2(ni, 2), d1(ni), d2(ni))
    call new_solver(name, ni, s1, error)
    call new_solver(name, ni, s2, error)
    call s1%schur(a, nb, k1, error)
    call check(.not. allocated(error), name//' '//what//': schur')
    if (allocated(error)) return
    call schur_by_solves(s2, a, nb, k2, error)
    call check(.not. allocated(error), name//' '//what//': default schur')
    if (allocated(error)) return
    sc = [(sqrt(max(ad(ni + i, ni + i), tiny(1.0_wp))), i=1, nb)]
    worst = 0.0_wp
    do j = 1, nb
       do i = 1, nb
          worst = max(worst, abs(k1(i, j) - k2(i, j))/(sc(i)*sc(j)))
       end do
    end do
    call check(worst < 1.0e-13_wp, name//' '//what//': K* as the default route')
    call check(all(k1 == transpose(k1)), name//' '//what//': K* symmetric')
    if (nb > 0) then
       if (ad(n, n) == 0.0_wp) call check(all(k1(nb, :) == 0.0_wp) .and. all(k1(:, nb) == 0.0_wp), &
            name//' '//what//': a boundary DOF without stiffness has a zero row')
    end if
    do i = 1, ni
       b(i, 1) = real(i, wp)
       b(i, 2) = 1.0_wp/real(i, wp)
    end do
    call s1%solve(b, x1, error)
    call check(.not. allocated(error), name//' '//what//': solve')
    if (allocated(error)) return
    call s2%solve(b, x2, error)
    call check_close(maxval(abs(x1 - x2))/max(maxval(abs(x2)), tiny(1.0_wp)), 0.0_wp, 1.0e-12_wp, &
         name//' '//what//': interior solve')
    ! pivots depend on the elimination order (the boundary-last route may
    ! order the interior otherwise): their product, det a_ii, does not
    call s1%pivots(d1)
    call s2%pivots(d2)
    call check(all(d1 > 0.0_wp), name//' '//what//': interior pivots all set')
    call check_close(sum(log(d1)) - sum(log(d2)), 0.0_wp, 1.0e-10_wp*max(1.0_wp, sum(abs(log(d2)))), &
         name//' '//what//': product of the interior pivots')
    call s1%release()
    call s2%release()
    call check_halves(name, ad, a, nb, what, .true.)
    if (name == 'cholmod') call check_halves(name, ad, a, nb, what//' (interior ordered first)', .false.)
  end subroutine compare_routes

  subroutine check_halves(name, ad, a, nb, what, camd_first)
    !! condense_loads and recover_interior of a condensation by name's schur
    !! against f* = f_b - a_bi x and u_i = a_ii^-1 (f_i - a_ib u_b), x =
    !! a_ii^-1 f_i (LAPACK's solves): loads f1, its recovery, the recovery of
    !! other loads f2 (the kept forward half is f1's: it must not be used),
    !! f1 condensed again (the memo) and recovered. camd_first: CHOLMOD's
    !! boundary-last ordering by CAMD alone where its fill is low (else the
    !! interior's own ordering, the boundary appended, compared with CAMD's).
    character(*), intent(in) :: name, what
    logical, intent(in) :: camd_first
    real(wp), intent(in) :: ad(:, :)
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    type(condensed_t) :: cond
    class(linear_solver_t), allocatable :: ref
    type(error_t), allocatable :: error
    real(wp), allocatable :: kstar(:, :), f1(:, :), f2(:, :), fs(:, :), ub(:, :), x(:, :)
    integer(i8) :: n, ni, i
    integer :: pass
    n = size(ad, 1, i8)
    ni = n - nb
    if (ni == 0 .or. nb == 0) return
    cond%sys%ni = ni
    cond%sys%nb = nb
    cond%sys%k = a
    allocate (kstar(nb, nb), f1(n, 3), fs(nb, 3), ub(nb, 3), x(ni, 3))
    call new_solver(name, ni, cond%solver, error)
    select type (s => cond%solver)
    type is (cholmod_solver_t)
       s%camd_first = camd_first
    end select
    call cond%solver%schur(a, nb, kstar, error)
    if (allocated(error)) return
    call new_solver('lapack', ni, ref, error)
    call ref%schur(a, nb, kstar, error)
    call check(.not. allocated(error), name//' '//what//': reference schur')
    if (allocated(error)) return
    do i = 1, n
       f1(i, 1) = real(i, wp)
       f1(i, 2) = (-1.0_wp)**i/real(i, wp)
       f1(i, 3) = merge(1.0_wp, 0.0_wp, i <= ni)
    end do
    do i = 1, nb
       ub(i, :) = [1.0_wp/real(i, wp), real(mod(i, 5_i8), wp), -1.0_wp]
    end do
    f2 = 2.0_wp*f1 + 1.0_wp
    do pass = 1, 2   ! the second: f1 condensed again (the memo)
       call condense_loads(cond, f1, fs, error)
       call check(.not. allocated(error), name//' '//what//': condense_loads')
       if (allocated(error)) return
       call check(allocated(cond%memo_y) .eqv. name == 'cholmod', &
            name//' '//what//': the forward half kept (CHOLMOD) or not (the others)')
       call ref%solve(f1(1:ni, :), x, error)
       call check_close(worst(fs, f1(ni + 1:, :) - matmul(transpose(ad(1:ni, ni + 1:)), x)), 0.0_wp, 1.0e-11_wp, &
            name//' '//what//': f* of f1')
       call check_recovery(cond, ref, ad, f1, ub, name//' '//what//': u_i of f1')
       if (pass == 1) call check_recovery(cond, ref, ad, f2, ub, &
            name//' '//what//': u_i of other loads than the condensed ones')
    end do
    call cond%solver%release()
    call ref%release()
  end subroutine check_halves

  subroutine check_recovery(cond, ref, ad, f, ub, what)
    !! recover_interior(cond, f) with boundary values ub against ref's
    !! a_ii^-1 (f_i - a_ib u_b), to 1e-11 of its largest entry.
    type(condensed_t), intent(inout) :: cond
    class(linear_solver_t), intent(inout) :: ref
    real(wp), intent(in) :: ad(:, :), f(:, :), ub(:, :)
    character(*), intent(in) :: what
    real(wp), allocatable :: u(:, :), fw(:, :), r(:, :)
    type(error_t), allocatable :: error
    integer(i8) :: ni
    ni = cond%sys%ni
    allocate (u(size(f, 1), size(f, 2)), r(ni, size(f, 2)))
    u = 0.0_wp
    u(ni + 1:, :) = ub
    fw = f
    call recover_interior(cond, fw, u, error)
    call check(.not. allocated(error), what//': recover_interior')
    call ref%solve(f(1:ni, :) - matmul(ad(1:ni, ni + 1:), ub), r, error)
    call check_close(worst(u(1:ni, :), r), 0.0_wp, 1.0e-11_wp, what)
  end subroutine check_recovery

  real(wp) function worst(x, y)
    !! Largest difference relative to y's largest entry.
    real(wp), intent(in) :: x(:, :), y(:, :)
    worst = maxval(abs(x - y))/max(maxval(abs(y)), tiny(1.0_wp))
  end function worst

  subroutine spring(ad, i, j, k)
    !! Add a spring of stiffness k between DOFs i and j.
    real(wp), intent(inout) :: ad(:, :)
    integer, intent(in) :: i, j
    real(wp), intent(in) :: k
    ad(i, i) = ad(i, i) + k
    ad(j, j) = ad(j, j) + k
    ad(i, j) = ad(i, j) - k
    ad(j, i) = ad(j, i) - k
  end subroutine spring

  subroutine from_dense(ad, a)
    !! Upper-triangle CSC of a dense symmetric matrix (zeros dropped except the diagonal).
    real(wp), intent(in) :: ad(:, :)
    type(sparse_sym_t), intent(out) :: a
    integer(i8) :: n, i, j, k
    n = size(ad, 1, i8)
    a%n = n
    k = count([((ad(i, j) /= 0.0_wp .or. i == j, i=1, j), j=1, n)], kind=i8)
    allocate (a%colptr(n + 1), a%rowind(k), a%val(k))
    k = 0
    a%colptr(1) = 1
    do j = 1, n
       do i = 1, j
          if (ad(i, j) /= 0.0_wp .or. i == j) then
             k = k + 1
             a%rowind(k) = i
             a%val(k) = ad(i, j)
          end if
       end do
       a%colptr(j + 1) = k + 1
    end do
  end subroutine from_dense
end program test_schur
