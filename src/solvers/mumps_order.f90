module superjoin_solvers_mumps_order
  !! The ordering of MUMPS's analysis (issue 14), chosen for measurement by
  !! the environment variable SUPERJOIN_MUMPS_ORDERING (rank 0's value holds
  !! for every process):
  !!  - `amd` (the default): sequential analysis (ICNTL(28) = 1) with AMD
  !!    (ICNTL(7) = 0), MUMPS gathers the distributed input on the host;
  !!  - `ptscotch`: MUMPS's parallel analysis (ICNTL(28) = 2) with PT-SCOTCH
  !!    (ICNTL(29) = 1), the graph stays distributed;
  !!  - `metis`: METIS nested dissection computed by superjoin on the host
  !!    from the pattern of the matrix (with several processes' terms: their
  !!    patterns gathered to the host, whose union is the pattern of the sum)
  !!    and handed in (ICNTL(7) = 1, PERM_IN).
  !! (MUMPS's own METIS, ICNTL(7) = 5, is not offered: Debian's
  !! libmumps-ptscotch has no METIS and falls back to SCOTCH.)
  !! doc/performance.md has the measurements behind the default.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_USAGE
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_parallel_comm, only: comm_t, comm_world, broadcast, gather_counts, agree
  implicit none (type, external)
  private

  public :: ordering_choice, host_nested_dissection

  integer, parameter, public :: ORDER_AMD = 1          !! sequential analysis, AMD
  integer, parameter, public :: ORDER_PTSCOTCH = 2     !! parallel analysis, PT-SCOTCH
  integer, parameter, public :: ORDER_METIS = 3        !! METIS by superjoin on the host, handed in
  integer, parameter, public :: ORDER_DEFAULT = ORDER_AMD
    !! chosen on the measurements of doc/performance.md (orderings compared)
  integer, parameter :: ORDER_UNKNOWN = -1
  character(*), parameter :: ENV_NAME = 'SUPERJOIN_MUMPS_ORDERING'
  integer, parameter :: ENV_LEN = 32
  integer, parameter :: PAIR = 2
    !! A pattern entry sent to the host: row, column.
  integer, parameter, public :: ORDERING_FAILED = -1    !! host_nested_dissection: METIS or the gather failed
  integer, parameter, public :: ORDERING_NO_MEMORY = -2 !! host_nested_dissection: an allocation failed

  interface
     function sj_metis_nested_dissection(n, xadj, adjncy, iperm) bind(c, name='sj_metis_nested_dissection') &
          result(status)
       use, intrinsic :: iso_c_binding, only: c_int, c_int64_t
       integer(c_int64_t), value :: n
       integer(c_int64_t), intent(in) :: xadj(*), adjncy(*)
       integer(c_int64_t), intent(out) :: iperm(*)
       integer(c_int) :: status
     end function sj_metis_nested_dissection
  end interface

contains

  function ordering_choice(error) result(choice)
    !! The ordering asked for by SUPERJOIN_MUMPS_ORDERING on rank 0 (unset or
    !! empty: ORDER_DEFAULT), the same on every process. Collective. An
    !! unknown name is a usage error on every process.
    type(error_t), allocatable, intent(out) :: error
    integer :: choice
    character(len=ENV_LEN) :: env
    type(comm_t) :: comm
    real(wp) :: code(1)
    integer :: stat, length
    logical :: ok
    comm = comm_world()
    code = ORDER_DEFAULT
    env = ''
    if (comm%is_root()) then
       call get_environment_variable(ENV_NAME, env, length=length, status=stat)
       if (stat == 0 .or. stat == -1) then
          if (stat == -1) then
             code = ORDER_UNKNOWN
          else
             code = real(named(env), wp)
          end if
       end if
    end if
    call broadcast(code, 0, ok)
    choice = nint(code(1))
    if (choice == ORDER_UNKNOWN .or. .not. ok) then
       call fatal_error(error, EXIT_USAGE, 'error: '//ENV_NAME//': unknown ordering (amd, ptscotch, metis)')
       choice = ORDER_DEFAULT
    end if
  contains
    pure function named(text) result(c)
      !! The code of an ordering name (blank: the default).
      character(*), intent(in) :: text
      integer :: c
      select case (trim(adjustl(text)))
      case ('')
         c = ORDER_DEFAULT
      case ('amd')
         c = ORDER_AMD
      case ('ptscotch')
         c = ORDER_PTSCOTCH
      case ('metis')
         c = ORDER_METIS
      case default
         c = ORDER_UNKNOWN
      end select
    end function named
  end function ordering_choice

  subroutine host_nested_dissection(a, gathered, iperm, gathered_bytes, seconds, status)
    !! METIS nested dissection of the graph of a's pattern (off-diagonal
    !! entries, both directions), on process 0: iperm(i) the position of
    !! unknown i in the pivot order (MUMPS's PERM_IN); size 0 elsewhere. With
    !! gathered, a is this process's term of a sum over the processes: every
    !! process's off-diagonal pattern is gathered to process 0 (rows and
    !! columns, 16 bytes an entry: gathered_bytes, the total received) and
    !! the graph is that of the union, the pattern of the sum. seconds: the
    !! host's time for the graph and METIS. status 0, ORDERING_FAILED or
    !! ORDERING_NO_MEMORY (the same on every process only for the gather;
    !! the caller agrees on it). Collective when gathered.
    type(sparse_sym_t), intent(in) :: a
    logical, intent(in) :: gathered
    integer(i8), allocatable, intent(out) :: iperm(:)
    integer(i8), intent(out) :: gathered_bytes
    real(wp), intent(out) :: seconds
    integer, intent(out) :: status
    type(comm_t) :: comm
    integer(i8), allocatable :: mine(:), pairs(:), xadj(:), adj(:)
    integer(i8) :: n
    integer(i8) :: t0, t1, rate
    integer :: stat
    logical :: ok, gather
    comm = comm_world()
    gather = gathered .and. comm%size > 1
    n = a%n
    gathered_bytes = 0
    seconds = 0.0_wp
    call pattern_pairs(a, gather, mine, status)
    if (status /= 0) then
       allocate (iperm(0))
       return
    end if
    if (gather) then
       call gather_counts(mine, 0, pairs, ok)
       if (.not. ok) then
          status = ORDERING_FAILED
          allocate (iperm(0))
          return
       end if
       if (comm%is_root()) gathered_bytes = (size(pairs, kind=i8) - size(mine, kind=i8))*8
       deallocate (mine)
    else
       call move_alloc(mine, pairs)
    end if
    if (.not. comm%is_root()) then
       allocate (iperm(0))
       return
    end if
    call system_clock(t0, rate)
    call pair_graph(n, pairs, xadj, adj, stat)
    if (stat == 0) allocate (iperm(n), stat=stat)
    if (stat /= 0) then
       status = ORDERING_NO_MEMORY
       if (.not. allocated(iperm)) allocate (iperm(0))
       return
    end if
    if (n > 0) then
       if (sj_metis_nested_dissection(n, xadj, adj, iperm) /= 0) status = ORDERING_FAILED
    end if
    call system_clock(t1)
    seconds = real(t1 - t0, wp)/real(max(rate, 1_i8), wp)
  end subroutine host_nested_dissection

  subroutine pattern_pairs(a, gather, mine, status)
    !! The off-diagonal pattern of a as (row, column) pairs, PAIR integers
    !! each. status 0 or ORDERING_NO_MEMORY; with gather, the processes agree
    !! on it first (collective: the gather that follows needs them all).
    type(sparse_sym_t), intent(in) :: a
    logical, intent(in) :: gather
    integer(i8), allocatable, intent(out) :: mine(:)
    integer, intent(out) :: status
    integer(i8) :: j, pos, m, at
    integer :: stat, worst, first
    status = 0
    m = 0
    do j = 1, a%n
       m = m + count(a%rowind(a%colptr(j):a%colptr(j + 1) - 1) /= j)
    end do
    allocate (mine(PAIR*m), stat=stat)
    if (gather) then
       ! the gather is collective: every process must reach it ready
       call agree(stat, worst, first)
       stat = worst
    end if
    if (stat /= 0) then
       status = ORDERING_NO_MEMORY
       return
    end if
    at = 0
    do j = 1, a%n
       do pos = a%colptr(j), a%colptr(j + 1) - 1
          if (a%rowind(pos) == j) cycle
          mine(at + 1:at + PAIR) = [a%rowind(pos), j]
          at = at + PAIR
       end do
    end do
  end subroutine pattern_pairs

  subroutine pair_graph(n, pairs, xadj, adj, stat)
    !! Adjacency (1-based CSR) of the n nodes joined by pairs (PAIR integers
    !! each), in both directions, repeats (entries several terms hold)
    !! dropped; pairs is deallocated. stat: nonzero when an allocation failed.
    integer(i8), intent(in) :: n
    integer(i8), allocatable, intent(inout) :: pairs(:)
    integer(i8), allocatable, intent(out) :: xadj(:), adj(:)
    integer, intent(out) :: stat
    integer(i8), allocatable :: fill(:), mark(:)
    integer(i8) :: m, k, i, j, v, w, pos, at
    m = size(pairs, kind=i8)/PAIR
    allocate (xadj(n + 1), source=0_i8, stat=stat)
    if (stat == 0) allocate (adj(max(2*m, 1_i8)), fill(n), mark(n), stat=stat)
    if (stat /= 0) return
    do k = 1, m
       i = pairs(PAIR*k - 1)
       j = pairs(PAIR*k)
       xadj(i + 1) = xadj(i + 1) + 1
       xadj(j + 1) = xadj(j + 1) + 1
    end do
    xadj(1) = 1
    do v = 1, n
       xadj(v + 1) = xadj(v + 1) + xadj(v)
    end do
    fill = xadj(1:n)
    do k = 1, m
       i = pairs(PAIR*k - 1)
       j = pairs(PAIR*k)
       adj(fill(i)) = j
       fill(i) = fill(i) + 1
       adj(fill(j)) = i
       fill(j) = fill(j) + 1
    end do
    deallocate (pairs, fill)
    mark = 0
    at = 0
    do v = 1, n
       pos = xadj(v)
       xadj(v) = at + 1
       do k = pos, xadj(v + 1) - 1
          w = adj(k)
          if (mark(w) == v) cycle
          mark(w) = v
          at = at + 1
          adj(at) = w
       end do
    end do
    xadj(n + 1) = at + 1
  end subroutine pair_graph
end module superjoin_solvers_mumps_order
