module superjoin_parallel_stats
  !! What this process contributed to a run on several processes, for the
  !! MPI summary on stderr (analysis/distributed, mpi_summary): the entries
  !! of the reduced matrix it assembled, the matrix entries it handed MUMPS, and MUMPS's memory figures of the last
  !! factorization (INFO(16): this process, INFOG(18): the largest process,
  !! INFOG(19): all processes, in MB). The bytes passed to collectives are
  !! counted by superjoin_parallel_comm (bytes_moved).
  use superjoin_kinds, only: i8
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

  type(mumps_stats_t) :: stats

  public :: record_mumps_input, record_mumps_memory, record_matrix_held, mumps_stats

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
end module superjoin_parallel_stats
