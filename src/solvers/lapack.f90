module superjoin_solvers_lapack
  !! Dense or banded Cholesky (LAPACK) behind the linear_solver_t interface,
  !! for small systems.
  !!
  !! Storage rule (decided in analyze): the matrix is renumbered with reverse
  !! Cuthill-McKee; with half-bandwidth bw after that renumbering, banded
  !! storage (dpbtrf/dpbtrs, (bw+1) x n) is used when (bw+1)*n < n*n/4, i.e.
  !! when the band holds less than a quarter of the dense array; otherwise the
  !! dense upper triangle in the natural order (dpotrf/dpotrs, n x n).
  !! Dense storage is refused above DENSE_MAX_N unknowns, and banded storage
  !! above BAND_MAX_ENTRIES stored entries (memory), with EXIT_IO.
  use superjoin_kinds, only: wp, i8
  use superjoin_solvers_blas, only: dsyrk
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR, EXIT_IO
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_solvers_node_graph, only: node_graph
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  use superjoin_utils_strings, only: itoa
  use superjoin_solvers_solver, only: linear_solver_t, interior_block, boundary_block, &
       boundary_shift, unshift, schur_by_solves
  implicit none (type, external)
  private

  integer(i8), parameter, public :: DENSE_MAX_N = 20000_i8           !! largest n for dense storage
  integer(i8), parameter, public :: BAND_MAX_ENTRIES = 100000000_i8  !! largest (bw+1)*n for banded storage (800 MB)
  integer(i8), parameter :: BAND_FRACTION = 4                        !! band used if (bw+1)*n < n*n/BAND_FRACTION
  real(wp), parameter :: MBYTE = 1048576.0_wp                        !! bytes per MiB

  type, extends(linear_solver_t), public :: lapack_solver_t
    !! LAPACK Cholesky, dense (natural order) or banded (RCM order).
     private
     integer(i8) :: n = -1               !! order of the analyzed matrix (-1: none)
     logical :: banded = .false.
     integer :: kd = 0                   !! half-bandwidth (banded storage)
     integer(i8), allocatable :: perm(:)   !! perm(new) = original index
     integer(i8), allocatable :: iperm(:)  !! iperm(original) = new index
     real(wp), allocatable :: f(:, :)      !! factor: (n, n) dense or (kd+1, n) band
     logical :: factored = .false.
     integer(i8) :: nfactored = 0        !! columns (new order) completed by the factorization
   contains
     procedure :: analyze => lapack_analyze
     procedure :: factorize => lapack_factorize
     procedure :: solve => lapack_solve
     procedure :: pivots => lapack_pivots
     procedure :: release => lapack_release
     procedure :: bandwidth => lapack_bandwidth
     procedure :: schur => lapack_schur
  end type lapack_solver_t

  public :: rcm_ordering

  type :: rcm_graph_t
    !! The graph and work arrays of the reverse Cuthill-McKee ordering.
     integer(i8), allocatable :: xadj(:), adj(:)   !! adjacency (CSR, no self loops)
     integer(i8), allocatable :: deg(:)            !! degree of each node
     integer(i8), allocatable :: level(:)          !! breadth-first level (-1: not reached)
     integer(i8), allocatable :: queue(:)          !! breadth-first queue
     logical, allocatable :: done(:)               !! numbered already
  end type rcm_graph_t

  interface
     subroutine dpotrf(uplo, n, a, lda, info)
       import :: wp
       character(len=1), intent(in) :: uplo
       integer, intent(in) :: n, lda
       real(wp), intent(inout) :: a(lda, *)
       integer, intent(out) :: info
     end subroutine dpotrf

     subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
       import :: wp
       character(len=1), intent(in) :: uplo
       integer, intent(in) :: n, nrhs, lda, ldb
       real(wp), intent(in) :: a(lda, *)
       real(wp), intent(inout) :: b(ldb, *)
       integer, intent(out) :: info
     end subroutine dpotrs

     subroutine dpbtrf(uplo, n, kd, ab, ldab, info)
       import :: wp
       character(len=1), intent(in) :: uplo
       integer, intent(in) :: n, kd, ldab
       real(wp), intent(inout) :: ab(ldab, *)
       integer, intent(out) :: info
     end subroutine dpbtrf

     subroutine dpbtrs(uplo, n, kd, nrhs, ab, ldab, b, ldb, info)
       import :: wp
       character(len=1), intent(in) :: uplo
       integer, intent(in) :: n, kd, nrhs, ldab, ldb
       real(wp), intent(in) :: ab(ldab, *)
       real(wp), intent(inout) :: b(ldb, *)
       integer, intent(out) :: info
     end subroutine dpbtrs

     subroutine dtbsv(uplo, trans, diag, n, k, a, lda, x, incx)
       import :: wp
       character(len=1), intent(in) :: uplo, trans, diag
       integer, intent(in) :: n, k, lda, incx
       real(wp), intent(in) :: a(lda, *)
       real(wp), intent(inout) :: x(*)
     end subroutine dtbsv
  end interface

contains

  subroutine lapack_analyze(self, a, error)
    !! Choose the storage: RCM renumbering and its bandwidth; banded when the
    !! band is small relative to n (see the module comment), dense otherwise.
    class(lapack_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: n, bw, i
    character(len=80) :: buf

    call lapack_release(self)
    self%info%failed_column = 0
    self%info%factor_nnz = 0
    self%info%factor_mbytes = 0.0_wp
    n = a%n
    if (n < 0 .or. .not. allocated(a%colptr)) then
       call fatal_error(error, EXIT_IO, 'LAPACK: invalid matrix')
       return
    end if
    if (n > huge(1)) then
       call fatal_error(error, EXIT_IO, 'LAPACK: matrix too large for LAPACK (use cholmod)')
       return
    end if
    allocate (self%perm(n), self%iperm(n))
    call rcm_ordering(a, self%perm)
    do i = 1, n
       self%iperm(self%perm(i)) = i
    end do
    bw = band_of(a, self%iperm)
    if ((bw + 1)*n < n*n/BAND_FRACTION) then
       if ((bw + 1)*n > BAND_MAX_ENTRIES) then
          write (buf, '(a,i0,a,i0,a)') ' (n = ', n, ', band = ', bw, ')'
          call fatal_error(error, EXIT_IO, 'LAPACK: banded matrix too large'//trim(buf)//': use cholmod')
          call lapack_release(self)
          return
       end if
       self%banded = .true.
       self%kd = int(bw)
       write (buf, '(a,i0,a)') 'LAPACK dpbtrf (band ', bw, ')'
       self%info%name = trim(buf)
       self%info%ordering = 'RCM'
       self%info%factor_nnz = (bw + 1)*n - bw*(bw + 1)/2
       self%info%factor_mbytes = real(bw + 1, wp)*real(n, wp)*storage_size(1.0_wp)/8/MBYTE
    else
       if (n > DENSE_MAX_N) then
          write (buf, '(a,i0,a,i0,a)') ' (n = ', n, ', band = ', bw, ')'
          call fatal_error(error, EXIT_IO, 'LAPACK: matrix too large for dense storage'//trim(buf)//': use cholmod')
          call lapack_release(self)
          return
       end if
       self%banded = .false.
       self%kd = int(max(n - 1, 0_i8))
       do i = 1, n
          self%perm(i) = i
          self%iperm(i) = i
       end do
       self%info%name = 'LAPACK dpotrf'
       self%info%ordering = 'natural'
       self%info%factor_nnz = n*(n + 1)/2
       self%info%factor_mbytes = real(n, wp)*real(n, wp)*storage_size(1.0_wp)/8/MBYTE
    end if
    self%n = n
  end subroutine lapack_analyze

  subroutine lapack_factorize(self, a, error)
    !! Cholesky factorization (dpotrf or dpbtrf) of a in the analyzed storage.
    !! Not positive definite: EXIT_SINGULAR, info%failed_column = original column.
    class(lapack_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: n, j, k, p, q, r, c
    integer :: info, stat
    character(len=24) :: buf

    self%factored = .false.
    self%nfactored = 0
    self%info%failed_column = 0
    n = self%n
    if (n < 0) then
       call fatal_error(error, EXIT_IO, 'LAPACK: factorize called before analyze')
       return
    end if
    if (a%n /= n) then
       call fatal_error(error, EXIT_IO, 'LAPACK: matrix order differs from the analyzed one')
       return
    end if
    if (.not. allocated(self%f)) then
       if (self%banded) then
          allocate (self%f(self%kd + 1, n), stat=stat)
       else
          allocate (self%f(n, n), stat=stat)
       end if
       if (stat /= 0) then
          if (self%banded) then
             call out_of_memory(error, 'the LAPACK band factor ('//itoa(self%kd + 1)//' x '//itoa(n)//')', &
                  (self%kd + 1)*n*BYTES_REAL)
          else
             call out_of_memory(error, 'the LAPACK dense factor ('//itoa(n)//' x '//itoa(n)//')', &
                  n*n*BYTES_REAL)
          end if
          return
       end if
    end if
    self%f = 0.0_wp
    if (n == 0) then
       self%factored = .true.
       return
    end if
    do j = 1, n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          p = self%iperm(a%rowind(k))
          q = self%iperm(j)
          r = min(p, q)
          c = max(p, q)
          if (self%banded) then
             if (c - r > self%kd) then
                call fatal_error(error, EXIT_IO, 'LAPACK: matrix pattern differs from the analyzed one')
                return
             end if
             self%f(self%kd + 1 + r - c, c) = a%val(k)
          else
             self%f(r, c) = a%val(k)
          end if
       end do
    end do
    if (self%banded) then
       call dpbtrf('U', int(n), self%kd, self%f, self%kd + 1, info)
    else
       call dpotrf('U', int(n), self%f, int(n), info)
    end if
    if (info > 0) then
       self%nfactored = info - 1
       self%info%failed_column = self%perm(info)
       write (buf, '(i0)') self%info%failed_column
       call fatal_error(error, EXIT_SINGULAR, 'matrix is not positive definite at column '//trim(buf))
       return
    else if (info < 0) then
       write (buf, '(i0)') info
       call fatal_error(error, EXIT_IO, 'LAPACK factorization failed: info '//trim(buf))
       return
    end if
    self%nfactored = n
    self%factored = .true.
  end subroutine lapack_factorize

  subroutine lapack_solve(self, b, x, error)
    !! x = A^-1 b (dpotrs or dpbtrs on all right-hand sides at once).
    class(lapack_solver_t), intent(inout) :: self
    real(wp), intent(in) :: b(:, :)
    real(wp), intent(out) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: y(:, :)
    integer(i8) :: n, i
    integer :: nrhs, info, stat
    character(len=24) :: buf

    if (.not. self%factored) then
       call fatal_error(error, EXIT_IO, 'LAPACK: solve called without a valid factorization')
       return
    end if
    n = self%n
    if (size(b, 1, i8) /= n .or. size(x, 1, i8) /= n .or. size(b, 2) /= size(x, 2)) then
       call fatal_error(error, EXIT_IO, 'LAPACK: right-hand side and solution shapes do not match the matrix')
       return
    end if
    nrhs = size(b, 2)
    if (n == 0 .or. nrhs == 0) return
    allocate (y(n, nrhs), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the LAPACK solve', n*nrhs*BYTES_REAL)
       return
    end if
    do i = 1, n
       y(i, :) = b(self%perm(i), :)
    end do
    if (self%banded) then
       call dpbtrs('U', int(n), self%kd, nrhs, self%f, self%kd + 1, y, int(n), info)
    else
       call dpotrs('U', int(n), nrhs, self%f, int(n), y, int(n), info)
    end if
    if (info /= 0) then
       write (buf, '(i0)') info
       call fatal_error(error, EXIT_IO, 'LAPACK solve failed: info '//trim(buf))
       return
    end if
    do i = 1, n
       x(self%perm(i), :) = y(i, :)
    end do
  end subroutine lapack_solve

  subroutine lapack_pivots(self, d)
    !! d(j) = L_jj^2 of original column j (0 for columns a failed factorization
    !! did not reach, including the failing one).
    class(lapack_solver_t), intent(inout) :: self
    real(wp), intent(out) :: d(:)
    integer(i8) :: i
    d = 0.0_wp
    if (self%n <= 0 .or. .not. allocated(self%f)) return
    if (size(d, kind=i8) < self%n) return
    do i = 1, self%nfactored
       if (self%banded) then
          d(self%perm(i)) = self%f(self%kd + 1, i)**2
       else
          d(self%perm(i)) = self%f(i, i)**2
       end if
    end do
  end subroutine lapack_pivots

  subroutine lapack_release(self)
    !! Free the factor and the ordering.
    class(lapack_solver_t), intent(inout) :: self
    if (allocated(self%f)) deallocate (self%f)
    if (allocated(self%perm)) deallocate (self%perm)
    if (allocated(self%iperm)) deallocate (self%iperm)
    self%n = -1
    self%banded = .false.
    self%kd = 0
    self%factored = .false.
    self%nfactored = 0
  end subroutine lapack_release

  pure function lapack_bandwidth(self) result(bw)
    !! Half-bandwidth of the storage in use (n-1 for dense, -1 before analyze).
    class(lapack_solver_t), intent(in) :: self
    integer :: bw
    bw = -1
    if (self%n >= 0) bw = self%kd
  end function lapack_bandwidth

  pure function band_of(a, iperm) result(bw)
    !! Half-bandwidth of a after renumbering with iperm (iperm(old) = new).
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: iperm(:)
    integer(i8) :: bw, j, k
    bw = 0
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          bw = max(bw, abs(iperm(a%rowind(k)) - iperm(j)))
       end do
    end do
  end function band_of

  subroutine rcm_ordering(a, perm)
    !! Reverse Cuthill-McKee ordering of the graph of a: perm(new) = original.
    !! Each connected component is started from a pseudo-peripheral node
    !! (George-Liu: repeated breadth-first searches from a node of minimum
    !! degree in the last level), neighbours are visited by increasing degree,
    !! and the whole Cuthill-McKee sequence is reversed at the end.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(out) :: perm(:)
    type(rcm_graph_t) :: g
    integer(i8) :: n, i, nnext, root, start

    n = a%n
    if (n == 0) return
    call adjacency(a, g%xadj, g%adj)
    allocate (g%deg(n), g%level(n), g%queue(n), g%done(n))
    do i = 1, n
       g%deg(i) = g%xadj(i + 1) - g%xadj(i)
    end do
    g%done = .false.
    g%level = -1
    nnext = 0
    do start = 1, n
       if (g%done(start)) cycle
       ! the component of start: its minimum-degree node is the first guess
       call pseudo_peripheral(g, start, root)
       call cuthill_mckee(g, root, perm, nnext)
    end do
    ! reverse
    perm(1:n) = perm(n:1:-1)
  end subroutine rcm_ordering

  subroutine cuthill_mckee(g, root, perm, nnext)
    !! Cuthill-McKee breadth-first numbering of the component of root after
    !! the nnext nodes numbered so far: perm(nnext+1:) gets its nodes, the
    !! neighbours of each node by increasing degree; nnext the new count.
    type(rcm_graph_t), intent(inout) :: g
    integer(i8), intent(in) :: root
    integer(i8), intent(inout) :: perm(:)
    integer(i8), intent(inout) :: nnext
    integer(i8) :: head, tail, v, w, m, k, i, j, t
    head = nnext + 1
    tail = nnext + 1
    perm(tail) = root
    g%done(root) = .true.
    do while (head <= tail)
       v = perm(head)
       head = head + 1
       m = tail
       do k = g%xadj(v), g%xadj(v + 1) - 1
          w = g%adj(k)
          if (g%done(w)) cycle
          g%done(w) = .true.
          tail = tail + 1
          perm(tail) = w
       end do
       ! the nodes just added (m+1:tail) in increasing degree (insertion sort)
       do i = m + 2, tail
          t = perm(i)
          j = i - 1
          do while (j > m)
             if (g%deg(perm(j)) <= g%deg(t)) exit
             perm(j + 1) = perm(j)
             j = j - 1
          end do
          perm(j + 1) = t
       end do
    end do
    nnext = tail
  end subroutine cuthill_mckee

  subroutine pseudo_peripheral(g, s, r)
    !! r: a pseudo-peripheral node of the component holding s (among the
    !! nodes not yet numbered).
    type(rcm_graph_t), intent(inout) :: g
    integer(i8), intent(in) :: s
    integer(i8), intent(out) :: r
    integer(i8) :: ecc, new_ecc, last_first, last_end, u, kk, best
    integer :: iter
    integer, parameter :: MAX_SWEEPS = 10
    ! start from a node of minimum degree in the component
    call bfs(g, s, ecc, last_first, last_end)
    r = s
    do kk = 1, last_end
       if (g%deg(g%queue(kk)) < g%deg(r)) r = g%queue(kk)
    end do
    call bfs(g, r, ecc, last_first, last_end)
    do iter = 1, MAX_SWEEPS
       best = g%queue(last_first)
       do kk = last_first, last_end
          u = g%queue(kk)
          if (g%deg(u) < g%deg(best)) best = u
       end do
       call bfs(g, best, new_ecc, last_first, last_end)
       if (new_ecc <= ecc) exit
       r = best
       ecc = new_ecc
    end do
  end subroutine pseudo_peripheral

  subroutine bfs(g, s, ecc, last_first, last_end)
    !! Breadth-first search from s over the nodes not yet numbered; queue(1:last_end)
    !! holds the component, queue(last_first:last_end) its last level; ecc the depth.
    type(rcm_graph_t), intent(inout) :: g
    integer(i8), intent(in) :: s
    integer(i8), intent(out) :: ecc, last_first, last_end
    integer(i8) :: h, tl, u, kk, x
    g%level(s) = 0
    g%queue(1) = s
    h = 1
    tl = 1
    do while (h <= tl)
       u = g%queue(h)
       h = h + 1
       do kk = g%xadj(u), g%xadj(u + 1) - 1
          x = g%adj(kk)
          if (g%done(x) .or. g%level(x) >= 0) cycle
          tl = tl + 1
          g%queue(tl) = x
          g%level(x) = g%level(u) + 1
       end do
    end do
    ecc = g%level(g%queue(tl))
    last_end = tl
    last_first = tl
    do while (last_first > 1)
       if (g%level(g%queue(last_first - 1)) /= ecc) exit
       last_first = last_first - 1
    end do
    do kk = 1, tl
       g%level(g%queue(kk)) = -1
    end do
  end subroutine bfs

  subroutine adjacency(a, xadj, adj)
    !! Symmetric adjacency (no self loops) of the upper-triangle pattern of a, CSR:
    !! the node graph with one column per node.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), allocatable, intent(out) :: xadj(:), adj(:)
    integer(i8) :: j
    call node_graph(a, [(j, j=1, a%n + 1)], xadj, adj)
  end subroutine adjacency

  subroutine lapack_schur(self, a, nb, kstar, error)
    !! K* = a_bb − a_bi a_ii⁻¹ a_ib in the storage analyze chooses for a_ii
    !! (the contract of linear_solver_t%schur; self then holds the factor of
    !! a_ii). Dense: the whole part factored with the boundary last and
    !! boundary_shift's D on its diagonal, K* = U_bbᵀ U_bb − D (as CHOLMOD's
    !! schur), U_ii kept. Banded: W = U⁻ᵀ P a_ib (dtbsv), K* = a_bb − WᵀW.
    !! Either way one triangular solve's work per boundary column, half the
    !! default route's.
    class(lapack_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(out) :: kstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(sparse_sym_t) :: aii
    integer(i8) :: ni
    ni = a%n - nb
    call interior_block(a, nb, aii)
    call self%analyze(aii, error)
    if (allocated(error)) return
    if (.not. self%banded .and. ni > 0 .and. nb > 0) then
       call dense_schur(self, a, nb, kstar, error)
       return
    end if
    call boundary_block(a, nb, kstar)
    call self%factorize(aii, error)
    if (allocated(error) .or. ni == 0 .or. nb == 0) return
    call band_schur(self, a, nb, kstar, error)
  end subroutine lapack_schur

  subroutine dense_schur(self, a, nb, kstar, error)
    !! The dense route of lapack_schur (natural order, a_ii analyzed dense).
    !! A breakdown in the boundary block (a not semi-definite) falls back to
    !! the default route.
    class(lapack_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(out) :: kstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: full(:, :), val(:), shift(:)
    integer(i8) :: n, ni, j, k
    integer :: stat, info
    n = a%n
    ni = n - nb
    call boundary_shift(a, nb, val, shift)
    if (.not. allocated(val)) then
       call schur_by_solves(self, a, nb, kstar, error)
       return
    end if
    allocate (full(n, n), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the LAPACK dense factor ('//itoa(n)//' x '//itoa(n)//')', n*n*BYTES_REAL)
       return
    end if
    full = 0.0_wp
    do j = 1, n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          full(a%rowind(k), j) = val(k)
       end do
    end do
    call dpotrf('U', int(n), full, int(n), info)
    if (info > ni .or. info < 0) then
       call schur_by_solves(self, a, nb, kstar, error)
       return
    end if
    self%f = full(1:ni, 1:ni)
    if (info > 0) then
       self%nfactored = info - 1
       self%info%failed_column = info
       call fatal_error(error, EXIT_SINGULAR, 'matrix is not positive definite at column '//itoa(info))
       return
    end if
    self%nfactored = ni
    self%factored = .true.
    kstar = 0.0_wp
    call dsyrk('L', 'T', int(nb), int(nb), 1.0_wp, full(ni + 1:, ni + 1:), int(nb), 0.0_wp, kstar, int(nb))
    call unshift(shift, kstar)
  end subroutine dense_schur

  subroutine band_schur(self, a, nb, kstar, error)
    !! kstar −= WᵀW, W = U⁻ᵀ P a_ib with the band factor of a_ii.
    class(lapack_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: nb
    real(wp), intent(inout) :: kstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: w(:, :)
    integer(i8) :: ni, j, pos, r
    integer :: stat
    ni = a%n - nb
    allocate (w(ni, nb), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the LAPACK condensation', ni*nb*BYTES_REAL)
       return
    end if
    w = 0.0_wp
    do j = 1, nb
       do pos = a%colptr(ni + j), a%colptr(ni + j + 1) - 1
          r = a%rowind(pos)
          if (r > ni) exit
          w(self%iperm(r), j) = a%val(pos)
       end do
    end do
    do j = 1, nb
       call dtbsv('U', 'T', 'N', int(ni), self%kd, self%f, self%kd + 1, w(:, j), 1)
    end do
    call dsyrk('U', 'T', int(nb), int(ni), -1.0_wp, w, int(ni), 1.0_wp, kstar, int(nb))
    do j = 1, nb
       kstar(j + 1:, j) = kstar(j, j + 1:)
    end do
  end subroutine band_schur
end module superjoin_solvers_lapack
