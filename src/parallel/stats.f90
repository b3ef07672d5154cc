module superjoin_parallel_stats
  !! What this process contributed to a run on several processes, for the
  !! MPI summary on stderr (analysis/distributed, mpi_summary): the entries
  !! of the reduced matrix it assembled, the matrix entries it handed MUMPS, and MUMPS's memory figures of the last
  !! factorization (INFO(16): this process, INFOG(18): the largest process,
  !! INFOG(19): all processes, in MB). The bytes passed to collectives are
  !! counted by superjoin_parallel_comm (bytes_moved).
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  type, public :: mumps_stats_t
    !! MUMPS figures of this process.
     integer(i8) :: entries = 0       !! matrix entries handed to MUMPS (distributed assembled input)
     integer(i8) :: mb_here = 0       !! INFO(16): MB MUMPS allocated here in the factorization
     integer(i8) :: mb_max = 0        !! INFOG(18): the largest INFO(16) over the processes
     integer(i8) :: mb_total = 0      !! INFOG(19): the sum over the processes
     integer :: factorizations = 0
     integer(i8) :: held = 0          !! entries of the largest reduced matrix (or term of it) this process assembled
  end type mumps_stats_t

  type, public :: mumps_order_stats_t
    !! The ordering and the factor of the largest MUMPS factorization of the
    !! run (the one with the most factor entries), for the ordering line on
    !! stderr (issue 14: orderings compared, doc/performance.md).
     character(:), allocatable :: ordering   !! as the listing's ordering line names it
     integer(i8) :: factor_entries = -1      !! INFOG(29): entries of the factor (-1: no factorization yet)
     integer(i8) :: estimate = 0             !! INFOG(20): the analysis's estimate of them
     real(wp) :: flops = 0.0_wp              !! RINFOG(3): flops of the factorization, all processes
     integer(i8) :: mb_estimate_max = 0      !! INFOG(21): estimated MB of the largest process (in core)
     integer(i8) :: mb_estimate_total = 0    !! INFOG(22): the estimated sum over the processes
     integer(i8) :: gathered_bytes = 0       !! pattern gathered to the host for superjoin's METIS ordering
     real(wp) :: host_seconds = 0.0_wp       !! superjoin's ordering on the host: graph and METIS_NodeND
  end type mumps_order_stats_t

  type(mumps_order_stats_t) :: order_stats
  integer(i8) :: pending_bytes = 0
  real(wp) :: pending_seconds = 0.0_wp

  type(mumps_stats_t) :: stats

  public :: record_mumps_input, record_mumps_memory, record_matrix_held, mumps_stats
  public :: record_host_ordering, record_mumps_factor, mumps_order_stats

contains

  subroutine record_mumps_input(entries)
    !! Count the entries this process hands MUMPS (the largest of the run's factorizations).
    integer(i8), intent(in) :: entries
    stats%entries = max(stats%entries, entries)
  end subroutine record_mumps_input

  subroutine record_matrix_held(entries)
    !! Count the entries of the reduced matrix this process assembled (the
    !! whole K_red, or with owner terms its own term; the largest of the run).
    integer(i8), intent(in) :: entries
    stats%held = max(stats%held, entries)
  end subroutine record_matrix_held

  subroutine record_mumps_memory(mb_here, mb_max, mb_total)
    !! Keep MUMPS's memory figures (the largest of the run's factorizations).
    integer(i8), intent(in) :: mb_here, mb_max, mb_total
    stats%mb_here = max(stats%mb_here, mb_here)
    stats%mb_max = max(stats%mb_max, mb_max)
    stats%mb_total = max(stats%mb_total, mb_total)
    stats%factorizations = stats%factorizations + 1
  end subroutine record_mumps_memory

  function mumps_stats() result(s)
    !! This process's MUMPS figures so far.
    type(mumps_stats_t) :: s
    s = stats
  end function mumps_stats

  subroutine record_host_ordering(gathered_bytes, seconds)
    !! Keep what superjoin's own ordering of the analysis just made cost: the
    !! bytes of pattern gathered to the host and the host's seconds (graph
    !! and METIS); they go with the factorization that follows.
    integer(i8), intent(in) :: gathered_bytes
    real(wp), intent(in) :: seconds
    pending_bytes = gathered_bytes
    pending_seconds = seconds
  end subroutine record_host_ordering

  subroutine record_mumps_factor(figures)
    !! Keep the figures of a factorization if it has the most factor entries so far.
    type(mumps_order_stats_t), intent(in) :: figures
    if (figures%factor_entries <= order_stats%factor_entries) return
    order_stats = figures
    order_stats%gathered_bytes = pending_bytes
    order_stats%host_seconds = pending_seconds
  end subroutine record_mumps_factor

  function mumps_order_stats() result(s)
    !! The ordering and factor figures of the run's largest MUMPS factorization.
    type(mumps_order_stats_t) :: s
    s = order_stats
  end function mumps_order_stats
end module superjoin_parallel_stats
