module superjoin_analysis_summed_matrix
  !! The reduced stiffness as a sum of the MPI processes' terms (issue 14):
  !! with several processes and MUMPS each process holds only its own term of
  !! K_red (the K* of the substructures it owns, the elements of its
  !! substructures that are not condensed and, on process 0, the terms of no
  !! substructure: plain contact units, loop springs, g of the δ columns) and
  !! hands it to MUMPS (local_input); nobody assembles the sum. What the
  !! analysis needs of the whole matrix is computed from the terms here:
  !! products (each process's product, summed), the diagonal, the columns
  !! with some nonzero entry, the connected groups of unknowns and the 1-norm.
  !! Every procedure is collective (all processes call it in the same order);
  !! on one process it is the plain operation on k. A value that cancels to
  !! exactly zero in the sum of two terms is counted as nonzero here (the
  !! serial code, which adds them first, would see a zero): with stiffness
  !! terms of different substructures that does not happen in practice.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_solvers, only: sparse_sym_t
  use superjoin_parallel_comm, only: comm_t, comm_world, broadcast, sum_reals, sum_counts, max_reals
  use superjoin_utils_sorting, only: sort_index
  implicit none (type, external)
  private

  public :: summed_matvec, summed_diagonal, summed_norm1, summed_nonzero, summed_groups, holds_shared_terms

  integer, parameter :: NFIELD = 3
    !! An entry sent for the norm: row, column, value.

contains

  function holds_shared_terms() result(yes)
    !! Does this process hold the terms of no substructure (process 0), the
    !! one that also puts 1 on the diagonal of the unknowns taken out?
    logical :: yes
    type(comm_t) :: comm
    comm = comm_world()
    yes = comm%is_root()
  end function holds_shared_terms

  subroutine summed_matvec(k, x, y, error)
    !! y = (Σ_p K_p) x: each process's product, summed over the processes.
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: y(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: buf(:)
    logical :: ok
    call k%matvec(x, y)
    if (comm_world_size() <= 1) return
    buf = reshape(y, [size(y, kind=i8)])
    call sum_reals(buf, ok)
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, 'error: MPI sum of a matrix product failed')
       return
    end if
    y = reshape(buf, shape(y))
  end subroutine summed_matvec

  subroutine summed_diagonal(k, d, error)
    !! The diagonal of Σ_p K_p.
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(out) :: d(:)
    type(error_t), allocatable, intent(out) :: error
    logical :: ok
    call k%diagonal(d)
    if (comm_world_size() <= 1) return
    call sum_reals(d, ok)
    if (.not. ok) call fatal_error(error, EXIT_IO, 'error: MPI sum of the diagonal failed')
  end subroutine summed_diagonal

  subroutine summed_nonzero(k, nz, offdiag, error)
    !! nz(j): some term has a nonzero entry in column or row j; offdiag(j):
    !! some term has a nonzero entry above the diagonal in column j.
    type(sparse_sym_t), intent(in) :: k
    logical, intent(out) :: nz(:)
    logical, intent(out) :: offdiag(:)
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: c(:)
    integer(i8) :: j, pos, n
    logical :: ok
    n = k%n
    nz = .false.
    offdiag = .false.
    do j = 1, n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) == 0.0_wp) cycle
          nz(j) = .true.
          nz(k%rowind(pos)) = .true.
          if (k%rowind(pos) /= j) offdiag(j) = .true.
       end do
    end do
    if (comm_world_size() <= 1) return
    allocate (c(2*n))
    c(1:n) = merge(1_i8, 0_i8, nz(1:n))
    c(n + 1:2*n) = merge(1_i8, 0_i8, offdiag(1:n))
    call sum_counts(c, ok)
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, 'error: MPI sum of the matrix pattern failed')
       return
    end if
    nz(1:n) = c(1:n) > 0
    offdiag(1:n) = c(n + 1:2*n) > 0
  end subroutine summed_nonzero

  subroutine summed_groups(k, root, error)
    !! root(j): the smallest unknown connected to j through nonzero entries of
    !! Σ_p K_p (the same on every process). Each process joins the groups
    !! along its own entries; the smallest label over the processes is
    !! exchanged until no label changes (as many rounds as the chain of
    !! processes a group spans, plus one).
    type(sparse_sym_t), intent(in) :: k
    integer(i8), intent(out) :: root(:)
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: up(:), lab(:), prev(:)
    real(wp), allocatable :: buf(:)
    integer(i8) :: j, pos
    logical :: ok
    allocate (up(k%n))
    do j = 1, k%n
       up(j) = j
    end do
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) == 0.0_wp) cycle
          call join(k%rowind(pos), j)
       end do
    end do
    do j = 1, k%n
       root(j) = find(j)
    end do
    if (comm_world_size() <= 1) return
    do
       ! the smallest label over the processes (as the largest of -label: exact below 2^53)
       buf = -real(root(1:k%n), wp)
       call max_reals(buf, ok)
       if (.not. ok) then
          call fatal_error(error, EXIT_IO, 'error: MPI exchange of the connected groups failed')
          return
       end if
       lab = nint(-buf, i8)
       ! stop when a round changes no label: lab and prev are the same on
       ! every process, so every process stops at the same round
       if (allocated(prev)) then
          if (all(lab == prev)) exit
       end if
       prev = lab
       do j = 1, k%n
          call join(j, lab(j))
       end do
       do j = 1, k%n
          root(j) = find(j)
       end do
    end do
    root(1:k%n) = lab
  contains
    function find(i) result(r)
      !! Root of i's group (paths halved on the way).
      integer(i8), intent(in) :: i
      integer(i8) :: r
      r = i
      do while (up(r) /= r)
         up(r) = up(up(r))
         r = up(r)
      end do
    end function find
    subroutine join(a, b)
      !! Merge the groups of a and b under the smaller root.
      integer(i8), intent(in) :: a, b
      integer(i8) :: ra, rb
      ra = find(a)
      rb = find(b)
      if (ra /= rb) up(max(ra, rb)) = min(ra, rb)
    end subroutine join
  end subroutine summed_groups

  subroutine summed_norm1(k, anorm, error)
    !! ‖Σ_p K_p‖₁ exactly (max column sum of |entries|; K is symmetric and k
    !! holds the upper triangle). An entry can be held by several processes
    !! only where both its row and its column are touched by several: those
    !! entries (the cut between the processes' terms) are sent to every
    !! process and summed before the absolute value; every other entry is
    !! counted where it lives. (MUMPS's own RINFOG(4) sums the absolute values
    !! of duplicate entries: an upper bound, not the norm.)
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(out) :: anorm
    type(error_t), allocatable, intent(out) :: error
    type(comm_t) :: comm
    integer(i8), allocatable :: touch(:)
    real(wp), allocatable :: colsum(:), mine(:), all_(:)
    integer(i8) :: j, pos, n
    logical :: ok
    comm = comm_world()
    n = k%n
    anorm = 0.0_wp
    if (n <= 0) return
    allocate (colsum(n), source=0.0_wp)
    if (comm%size <= 1) then
       do j = 1, n
          do pos = k%colptr(j), k%colptr(j + 1) - 1
             call add_entry(colsum, k%rowind(pos), j, abs(k%val(pos)))
          end do
       end do
       anorm = maxval(colsum)
       return
    end if
    call shared_columns(k, touch, ok)
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, 'error: MPI sum of the matrix pattern failed')
       return
    end if
    call split_cut(k, touch, colsum, mine)
    ! column sums of the entries counted where they live, summed
    call sum_reals(colsum, ok)
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, 'error: MPI sum of the column sums failed')
       return
    end if
    call share_cut(mine, all_, ok)
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, 'error: MPI exchange of the matrix cut failed')
       return
    end if
    call add_cut(all_, n, colsum)
    anorm = maxval(colsum)
  end subroutine summed_norm1

  subroutine shared_columns(k, touch, ok)
    !! touch(j): the number of processes with nonzero entries in row or
    !! column j (every term stores the whole diagonal: its zeros count for
    !! nothing). ok: the MPI sum succeeded.
    type(sparse_sym_t), intent(in) :: k
    integer(i8), allocatable, intent(out) :: touch(:)
    logical, intent(out) :: ok
    integer(i8) :: j, pos
    allocate (touch(k%n), source=0_i8)
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) == 0.0_wp) cycle
          touch(j) = 1
          touch(k%rowind(pos)) = 1
       end do
    end do
    call sum_counts(touch, ok)
  end subroutine shared_columns

  subroutine split_cut(k, touch, colsum, mine)
    !! The nonzero entries of k whose row and column several processes touch
    !! (the cut) into mine, NFIELD reals each (row, column, value); every
    !! other entry's absolute value into colsum.
    type(sparse_sym_t), intent(in) :: k
    integer(i8), intent(in) :: touch(:)
    real(wp), intent(inout) :: colsum(:)
    real(wp), allocatable, intent(out) :: mine(:)
    integer(i8) :: j, pos, nmine, at
    nmine = 0
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) == 0.0_wp) cycle
          if (touch(j) > 1 .and. touch(k%rowind(pos)) > 1) then
             nmine = nmine + 1
          else
             call add_entry(colsum, k%rowind(pos), j, abs(k%val(pos)))
          end if
       end do
    end do
    allocate (mine(NFIELD*nmine))
    at = 0
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) == 0.0_wp) cycle
          if (touch(j) > 1 .and. touch(k%rowind(pos)) > 1) then
             mine(at + 1:at + NFIELD) = [real(k%rowind(pos), wp), real(j, wp), k%val(pos)]
             at = at + NFIELD
          end if
       end do
    end do
  end subroutine split_cut

  subroutine share_cut(mine, all_, ok)
    !! Every process's cut entries (mine) to every process, in rank order.
    real(wp), intent(in) :: mine(:)
    real(wp), allocatable, intent(out) :: all_(:)
    logical, intent(out) :: ok
    type(comm_t) :: comm
    real(wp), allocatable :: head(:), got(:)
    integer :: r
    comm = comm_world()
    allocate (all_(0))
    ok = .true.
    do r = 0, comm%size - 1
       head = [real(size(mine, kind=i8)/NFIELD, wp)]
       call broadcast(head, r, ok)
       if (.not. ok) exit
       if (r == comm%rank) then
          got = mine
       else
          allocate (got(NFIELD*nint(head(1), i8)))
       end if
       call broadcast(got, r, ok)
       if (.not. ok) exit
       all_ = [all_, got]
       deallocate (got)
    end do
  end subroutine share_cut

  subroutine add_cut(all_, n, colsum)
    !! The cut entries of all processes (all_, the same list on every
    !! process): duplicates summed, then their absolute values into colsum
    !! (so the same sums on every process).
    real(wp), intent(in) :: all_(:)
    integer(i8), intent(in) :: n
    real(wp), intent(inout) :: colsum(:)
    integer(i8), allocatable :: key(:)
    integer, allocatable :: order(:)
    integer(i8) :: i, j, kij
    integer :: m, a
    real(wp) :: v
    m = int(size(all_, kind=i8)/NFIELD)
    allocate (key(m), order(m))
    do a = 1, m
       key(a) = nint(all_(NFIELD*(a - 1) + 1), i8)*(n + 1) + nint(all_(NFIELD*(a - 1) + 2), i8)
       order(a) = a
    end do
    call sort_index(key, order)
    a = 1
    do while (a <= m)
       v = 0.0_wp
       i = nint(all_(NFIELD*(order(a) - 1) + 1), i8)
       j = nint(all_(NFIELD*(order(a) - 1) + 2), i8)
       kij = key(order(a))
       do while (a <= m)
          if (key(order(a)) /= kij) exit
          v = v + all_(NFIELD*(order(a) - 1) + 3)
          a = a + 1
       end do
       call add_entry(colsum, i, j, abs(v))
    end do
  end subroutine add_cut

  pure subroutine add_entry(colsum, i, j, x)
    !! |entry (i, j)| = x into the sums of its column and (symmetric) row.
    real(wp), intent(inout) :: colsum(:)
    integer(i8), intent(in) :: i, j
    real(wp), intent(in) :: x
    colsum(j) = colsum(j) + x
    if (i /= j) colsum(i) = colsum(i) + x
  end subroutine add_entry

  function comm_world_size() result(n)
    !! Number of processes of the run.
    integer :: n
    type(comm_t) :: comm
    comm = comm_world()
    n = comm%size
  end function comm_world_size
end module superjoin_analysis_summed_matrix
