module superjoin_parallel_comm
  !! The communication layer: which process this is among how many, and the
  !! few collective operations superjoin needs (agreeing on a status, sending
  !! the solution to every process, summing counters).
  !!
  !! The procedures bind to C functions with one implementation per build:
  !! src/parallel/comm_mpi.c over MPI_COMM_WORLD (cmake -DSUPERJOIN_MPI=ON)
  !! and src/parallel/comm_serial.c for one process (the default build, every
  !! collective the identity), so both builds compile and run the same code.
  !!
  !! Errors on any process reach every process through agree(): each process
  !! contributes its status (0, or the exit status it would end with) and all
  !! learn the largest one and the lowest process that reported it, which is
  !! the one that prints the message. The protocol: every collective MUMPS
  !! call is preceded by an agreement at which every process says whether it
  !! is ready; a process that failed elsewhere makes no further collective
  !! call except the one agreement of its ending (app/main.f90 fail_on), which
  !! meets the others at their next agreement. A procedure that returns an
  !! agreed failure records it (note_agreed_failure), so that the ending does
  !! not agree a second time, and only the process that failed first prints.
  use, intrinsic :: iso_c_binding, only: c_int, c_int64_t, c_double
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  type, public :: comm_t
    !! This process's place in the run (MPI_COMM_WORLD, or one process).
     integer :: rank = 0        !! 0 .. size-1
     integer :: size = 1        !! number of processes
     logical :: parallel_build = .false.  !! built with MPI (even when size = 1)
   contains
     procedure :: is_root => comm_is_root
  end type comm_t

  public :: comm_world, agree, failure_agreed, note_agreed_failure, agreed_first, broadcast, sum_counts, &
       max_reals, sum_reals, fortran_handle, fortran_self_handle, bytes_moved
  public :: gather_counts

  integer(i8) :: moved = 0             !! bytes this process passed to broadcast/sum_reals/sum_counts/max_reals

  logical :: failure_noted = .false.   !! an agreement returned a failure to the caller
  integer :: failure_first = 0         !! the lowest process that reported it

  interface
     function sj_comm_rank() bind(c, name='sj_comm_rank') result(r)
       import :: c_int
       integer(c_int) :: r
     end function sj_comm_rank
     function sj_comm_size() bind(c, name='sj_comm_size') result(s)
       import :: c_int
       integer(c_int) :: s
     end function sj_comm_size
     function sj_comm_is_parallel_build() bind(c, name='sj_comm_is_parallel_build') result(p)
       import :: c_int
       integer(c_int) :: p
     end function sj_comm_is_parallel_build
     function sj_comm_self_fortran() bind(c, name='sj_comm_self_fortran') result(h)
       import :: c_int
       integer(c_int) :: h
     end function sj_comm_self_fortran
     function sj_comm_fortran() bind(c, name='sj_comm_fortran') result(h)
       import :: c_int
       integer(c_int) :: h
     end function sj_comm_fortran
     function sj_comm_agree(status, first) bind(c, name='sj_comm_agree') result(worst)
       import :: c_int
       integer(c_int), value :: status
       integer(c_int), intent(out) :: first
       integer(c_int) :: worst
     end function sj_comm_agree
     function sj_comm_bcast_real(x, n, root) bind(c, name='sj_comm_bcast_real') result(status)
       import :: c_int, c_int64_t, c_double
       real(c_double), intent(inout) :: x(*)
       integer(c_int64_t), value :: n
       integer(c_int), value :: root
       integer(c_int) :: status
     end function sj_comm_bcast_real
     function sj_comm_sum_i8(x, n) bind(c, name='sj_comm_sum_i8') result(status)
       import :: c_int, c_int64_t
       integer(c_int64_t), intent(inout) :: x(*)
       integer(c_int64_t), value :: n
       integer(c_int) :: status
     end function sj_comm_sum_i8
     function sj_comm_sum_real(x, n) bind(c, name='sj_comm_sum_real') result(status)
       import :: c_int, c_int64_t, c_double
       real(c_double), intent(inout) :: x(*)
       integer(c_int64_t), value :: n
       integer(c_int) :: status
     end function sj_comm_sum_real
     function sj_comm_max_real(x, n) bind(c, name='sj_comm_max_real') result(status)
       import :: c_int, c_int64_t, c_double
       real(c_double), intent(inout) :: x(*)
       integer(c_int64_t), value :: n
       integer(c_int) :: status
     end function sj_comm_max_real
     function sj_comm_gather_i8(x, n, out, counts, displs, root) bind(c, name='sj_comm_gather_i8') result(status)
       import :: c_int, c_int64_t
       integer(c_int64_t), intent(in) :: x(*)
       integer(c_int64_t), value :: n
       integer(c_int64_t), intent(inout) :: out(*)
       integer(c_int), intent(in) :: counts(*), displs(*)
       integer(c_int), value :: root
       integer(c_int) :: status
     end function sj_comm_gather_i8
  end interface

contains

  function comm_world() result(comm)
    !! This process in MPI_COMM_WORLD (starting MPI on first use), or the one
    !! process of the serial build.
    type(comm_t) :: comm
    comm%rank = sj_comm_rank()
    comm%size = sj_comm_size()
    comm%parallel_build = sj_comm_is_parallel_build() /= 0
  end function comm_world

  pure function comm_is_root(self) result(root)
    !! Is this the process that writes the outputs (rank 0)?
    class(comm_t), intent(in) :: self
    logical :: root
    root = self%rank == 0
  end function comm_is_root

  subroutine agree(status, worst, first)
    !! Collective: every process contributes status (0: fine); worst is the
    !! largest status of all, first the lowest rank that reported it (0 when
    !! all are fine). Every process must call it at the same point.
    integer, intent(in) :: status
    integer, intent(out) :: worst, first
    integer(c_int) :: f
    worst = sj_comm_agree(int(status, c_int), f)
    first = f
  end subroutine agree

  function failure_agreed() result(yes)
    !! Has an agreement already returned a failure as an error (so that every
    !! process knows, and none may wait for another agreement)?
    logical :: yes
    yes = failure_noted
  end function failure_agreed

  function agreed_first() result(rank)
    !! The process that failed first in the agreed failure (failure_agreed()).
    integer :: rank
    rank = failure_first
  end function agreed_first

  subroutine note_agreed_failure(first)
    !! Record that an agreement returned a failure to the caller, reported
    !! first by process first.
    integer, intent(in) :: first
    failure_noted = .true.
    failure_first = first
  end subroutine note_agreed_failure

  subroutine broadcast(x, root, ok)
    !! Collective: x on every process becomes x of process root.
    real(wp), intent(inout), contiguous :: x(:)
    integer, intent(in) :: root
    logical, intent(out) :: ok
    ok = sj_comm_bcast_real(x, size(x, kind=c_int64_t), int(root, c_int)) == 0
    call count_moved(size(x, kind=i8)*8)
  end subroutine broadcast

  subroutine sum_counts(x, ok)
    !! Collective: each entry of x becomes its sum over the processes.
    integer(i8), intent(inout), contiguous :: x(:)
    logical, intent(out) :: ok
    ok = sj_comm_sum_i8(x, size(x, kind=c_int64_t)) == 0
    call count_moved(size(x, kind=i8)*8)
  end subroutine sum_counts

  subroutine max_reals(x, ok)
    !! Collective: each entry of x becomes its largest value over the processes.
    real(wp), intent(inout), contiguous :: x(:)
    logical, intent(out) :: ok
    ok = sj_comm_max_real(x, size(x, kind=c_int64_t)) == 0
    call count_moved(size(x, kind=i8)*8)
  end subroutine max_reals

  subroutine sum_reals(x, ok)
    !! Collective: each entry of x becomes its sum over the processes.
    real(wp), intent(inout), contiguous :: x(:)
    logical, intent(out) :: ok
    ok = sj_comm_sum_real(x, size(x, kind=c_int64_t)) == 0
    call count_moved(size(x, kind=i8)*8)
  end subroutine sum_reals

  subroutine gather_counts(x, root, all, ok)
    !! Collective: every process's x, in rank order, into all on process root
    !! (size 0 elsewhere). ok is the same on every process: false if a
    !! process's share exceeds MPI's counts (2^31 - 1 values) or root cannot
    !! allocate all. Counts the bytes each process sends (root: receives).
    integer(i8), intent(in), contiguous :: x(:)
    integer, intent(in) :: root
    integer(i8), allocatable, intent(out) :: all(:)
    logical, intent(out) :: ok
    integer(i8), allocatable :: sizes(:)
    integer(c_int), allocatable :: counts(:), displs(:)
    integer(i8) :: total
    integer :: rank, nproc, r, stat, worst, first
    rank = sj_comm_rank()
    nproc = sj_comm_size()
    allocate (sizes(0:nproc - 1), source=0_i8)
    sizes(rank) = size(x, kind=i8)
    call sum_counts(sizes, ok)
    if (.not. ok) return
    total = sum(sizes)
    if (maxval(sizes) > huge(0_c_int) .or. total > huge(0_c_int)) then
       ok = .false.
       return
    end if
    stat = 0
    if (rank == root) then
       allocate (all(total), counts(0:nproc - 1), displs(0:nproc - 1), stat=stat)
       if (stat == 0) then
          counts = int(sizes, c_int)
          displs(0) = 0
          do r = 1, nproc - 1
             displs(r) = displs(r - 1) + counts(r - 1)
          end do
       end if
    else
       allocate (all(0), counts(1), displs(1))
       counts = 0
       displs = 0
    end if
    call agree(stat, worst, first)
    ok = worst == 0
    if (.not. ok) return
    ok = sj_comm_gather_i8(x, size(x, kind=c_int64_t), all, counts, displs, int(root, c_int)) == 0
    if (rank == root) then
       call count_moved((total - sizes(rank))*8)
    else
       call count_moved(sizes(rank)*8)
    end if
    call agree(merge(0, 1, ok), worst, first)
    ok = worst == 0
  end subroutine gather_counts

  subroutine count_moved(nbytes)
    !! Add to the bytes this process passed to collectives (on several processes only).
    integer(i8), intent(in) :: nbytes
    if (sj_comm_size() > 1) moved = moved + nbytes
  end subroutine count_moved

  function bytes_moved() result(n)
    !! Bytes this process has passed to the collectives so far (the size of
    !! each broadcast or reduction buffer; 0 on one process). The MUMPS input
    !! is counted by the MUMPS backend.
    integer(i8) :: n
    n = moved
  end function bytes_moved

  function fortran_handle() result(h)
    !! The Fortran handle of MPI_COMM_WORLD (MUMPS's COMM), or MUMPS's
    !! USE_COMM_WORLD placeholder in the serial build.
    integer :: h
    h = sj_comm_fortran()
  end function fortran_handle

  function fortran_self_handle() result(h)
    !! The Fortran handle of MPI_COMM_SELF (a MUMPS instance of this process
    !! alone), or MUMPS's placeholder in the serial build.
    integer :: h
    h = sj_comm_self_fortran()
  end function fortran_self_handle
end module superjoin_parallel_comm
