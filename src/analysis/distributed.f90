module superjoin_analysis_distributed
  !! The distributed pipeline of a run on several MPI processes.
  !!
  !! plan_distribution: which process owns which substructure
  !! (superjoin_parallel_partition) and the PARTITION block of the listing.
  !! condense_distributed: each process condenses only the condensed
  !! substructures it owns; the owner then sends every process K*, f*, the
  !! interior DOFs without stiffness, MAXRATIO and k u0 of each, so that the
  !! interface system is assembled, factored (MUMPS, distributed input) and
  !! checked as on one process. recover_distributed and parts_ku_distributed:
  !! each process recovers the interiors (and k u) of its own substructures,
  !! and a sum over the processes gives every process the whole field, so the
  !! rest of the pipeline (element results, health, listing on rank 0) runs
  !! unchanged. On one process (and in the serial build) none of this runs.
  !!
  !! Owner terms (owner_terms: the MUMPS backend, the default on several
  !! processes): K* is not sent. Each process assembles its own term of
  !! K_red (owner_plan) and hands it to MUMPS as it is (local_input,
  !! ICNTL(18) = 3, duplicates summed by MUMPS); what the pipeline needs of
  !! the whole matrix is computed from the terms (analysis/summed_matrix).
  !!
  !! Errors: a process whose condensation or recovery fails returns at once
  !! (its ending agrees, app/main.f90); the others learn it at the agreement
  !! that precedes each exchange (superjoin_parallel_comm's protocol).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, add_error_line, EXIT_SINGULAR, EXIT_IO
  use superjoin_model_types, only: model_t, string_t
  use superjoin_assembly_transform, only: transform_t
  use superjoin_assembly_assemble, only: max_element_diagonal, assembly_plan_t
  use superjoin_substructure_local_system, only: dof_label
  use superjoin_substructure_cache, only: part_cache_t, part_view_t, acquire_view, remote_view, &
       view_condense_loads, view_recover, view_stiffness_times, view_spc, view_maxratio, view_ku
  use superjoin_model_results, only: run_summary_t, run_log_t, run_options_t
  use superjoin_model_notes, only: note, append_string
  use superjoin_analysis_condensation, only: part_solver, library_options, acquire_part
  use superjoin_parallel_comm, only: comm_t, comm_world, agree, note_agreed_failure, broadcast, sum_reals, &
       sum_counts, bytes_moved
  use superjoin_parallel_stats, only: mumps_stats_t, mumps_stats, mumps_order_stats_t, mumps_order_stats
  use, intrinsic :: iso_fortran_env, only: error_unit
  use superjoin_parallel_partition, only: part_graph_t, partition_t, build_part_graph, partition_parts, &
       partition_report
  use superjoin_utils_strings, only: itoa
  use superjoin_analysis_solve_state, only: solve_state_t, plain_strategy_t
  use superjoin_analysis_condensation, only: condensed_strategy_t
  use superjoin_analysis_summed_matrix, only: summed_matvec, summed_diagonal, summed_norm1
  use superjoin_solvers, only: sparse_sym_t, norm1_sym
  implicit none (type, external)
  private

  integer, parameter :: NHEAD = 6
    !! Header of an owner's message: reused, rotated, MAXRATIO, its DOF, number of DOFs without
    !! stiffness, whether k u0 follows (it is sent only when some prescribed value is nonzero).

  type, extends(condensed_strategy_t), public :: distributed_strategy_t
    !! Several MPI processes, each condensing the substructures it owns
    !! (analysis/solve_state's solve_strategy_t). With owned (owner terms,
    !! see owner_terms) each process assembles and hands MUMPS only its own
    !! term of K_red, and what needs the whole matrix is computed from the
    !! terms (analysis/summed_matrix).
     logical :: owned = .false.
  contains
     procedure :: set_plan => distributed_plan
     procedure :: condense => condense_distributed
     procedure :: combine => combine_terms
     procedure :: recover_interiors => recover_own
     procedure :: summed => owner_summed
     procedure :: matvec => terms_matvec
     procedure :: diagonal => terms_diagonal
     procedure :: norm1 => terms_norm1
  end type distributed_strategy_t

  public :: plan_distribution, is_distributed, mpi_summary, owner_terms

  integer, parameter :: BYTES_MUMPS_ENTRY = 16
    !! One entry of MUMPS's distributed assembled input: value (8 bytes), row and column (4 each).
  integer, parameter :: NSTAT = 6
    !! Figures per process in the MPI summary.

contains

  subroutine plan_distribution(model, summary, log, error)
    !! With more than one process: the owner of every substructure
    !! (summary%sub_owner) and the PARTITION block (log%partition), the same
    !! on every process (the partition is deterministic and every process
    !! holds the whole model). Needs summary%sub_dofs and sub_boundary.
    type(model_t), intent(in) :: model
    type(run_summary_t), intent(inout) :: summary
    type(run_log_t), intent(inout) :: log
    type(error_t), allocatable, intent(out) :: error
    type(comm_t) :: comm
    type(part_graph_t) :: graph
    type(partition_t) :: part
    comm = comm_world()
    if (comm%size <= 1) return
    call build_part_graph(model, summary%sub_dofs, summary%sub_boundary, graph)
    call partition_parts(graph, comm%size, part, error)
    if (allocated(error)) return
    summary%sub_owner = part%owner
    call partition_report(model, graph, part, log%partition)
  end subroutine plan_distribution

  pure function is_distributed(summary) result(yes)
    !! Are the substructures shared out over several processes (plan_distribution)?
    type(run_summary_t), intent(in) :: summary
    logical :: yes
    yes = allocated(summary%sub_owner)
  end function is_distributed

  function owner_terms(summary, opts) result(yes)
    !! Does each process hand MUMPS only its own term of the reduced matrix
    !! (several processes, the MUMPS backend)? Then nobody assembles K_red:
    !! see analysis/summed_matrix for what is computed from the terms.
    !! For measurements only (doc/performance.md), the environment variable
    !! SUPERJOIN_BROADCAST_KSTAR=1 (the same on every process) keeps the
    !! pipeline of the previous increment: every K* sent to every process,
    !! which assembles the whole K_red and hands MUMPS a block of its columns.
    type(run_summary_t), intent(in) :: summary
    type(run_options_t), intent(in) :: opts
    logical :: yes
    character(len=8) :: env
    integer :: stat
    yes = is_distributed(summary)
    if (.not. yes) return
    yes = .false.
    if (allocated(opts%solver)) yes = index(opts%solver, 'mumps') == 1
    call get_environment_variable('SUPERJOIN_BROADCAST_KSTAR', env, status=stat)
    if (stat == 0 .and. env == '1') yes = .false.
  end function owner_terms

  subroutine owner_plan(model, summary, parts, plan)
    !! The assembly plan of this process's term of K_red: the elements of its
    !! own substructures that are not condensed, the K* of its own condensed
    !! ones, and on process 0 the terms of no substructure (plan%shared).
    type(model_t), intent(in) :: model
    type(run_summary_t), intent(in) :: summary
    type(part_view_t), intent(in) :: parts(:)
    type(assembly_plan_t), intent(out) :: plan
    type(comm_t) :: comm
    integer :: i, n, isub
    comm = comm_world()
    allocate (plan%skip_sub(size(model%subs)))
    do isub = 1, size(model%subs)
       plan%skip_sub(isub) = summary%sub_owner(isub) /= comm%rank
       if (allocated(summary%sub_condensed)) plan%skip_sub(isub) = plan%skip_sub(isub) .or. summary%sub_condensed(isub)
    end do
    n = count(parts(:)%entry > 0)
    allocate (plan%supers(n))
    n = 0
    do i = 1, size(parts)
       if (parts(i)%entry == 0) cycle
       n = n + 1
       plan%supers(n) = parts(i)%se
    end do
    plan%shared = comm%is_root()
  end subroutine owner_plan

  subroutine sum_owner_loads(f_u0, error)
    !! f_u0 (the reduced load of the prescribed values) of the processes'
    !! terms, summed.
    real(wp), intent(inout) :: f_u0(:)
    type(error_t), allocatable, intent(out) :: error
    logical :: ok
    call sum_reals(f_u0, ok)
    if (.not. ok) call fatal_error(error, EXIT_IO, 'error: MPI sum of the prescribed values'' loads failed')
  end subroutine sum_owner_loads

  subroutine condense_distributed(self, st, model, opts, cache, summary, notes, error)
    !! condense_parts (analysis/condensation) over several processes: each
    !! condenses its own substructures and sends the others what the
    !! interface needs. st%parts and st%f_eff end equal on every process, and
    !! so do the notes (AUTOSPC per substructure in order; the condensations
    !! computed and reused summed over the processes). With owned (owner
    !! terms, see owner_terms) K* stays with its owner: the others get the
    !! loads f*, the AUTOSPC list, MAXRATIO and k u0 (when nonzero) only.
    class(distributed_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(part_cache_t), intent(inout) :: cache
    type(run_summary_t), intent(inout) :: summary
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    type(comm_t) :: comm
    character(:), allocatable :: solver_name
    real(wp), allocatable :: fstar(:, :)
    integer(i8) :: counts(2)
    integer :: isub, ip_, i, nrot, computed0, reused0
    logical :: ok
    real(wp) :: dmax
    comm = comm_world()
    ! as condense_parts: the elements kept in the interface checked first
    if (cache%n == 0) then
       call max_element_diagonal(model, st%table, dmax, error, only=.not. summary%sub_condensed)
       if (allocated(error)) return
    end if
    solver_name = part_solver(opts)   ! a part is condensed by one process alone (MUMPS: on MPI_COMM_SELF)
    call library_options(cache, opts)  ! each owner loads and stores its own parts' entries
    allocate (st%parts(summary%n_condensed))
    st%f_eff = st%f_phys
    computed0 = cache%computed
    reused0 = cache%reused
    ! 1. this process's own condensations (a failure returns at once)
    ip_ = 0
    do isub = 1, size(model%subs)
       if (.not. summary%sub_condensed(isub)) cycle
       ip_ = ip_ + 1
       if (summary%sub_owner(isub) == comm%rank) then
          call acquire_part(cache, st, model, isub, solver_name, st%parts(ip_), error)
          if (allocated(error)) return
       else
          call remote_view(st%table, isub, st%bnd_c, st%parts(ip_))
       end if
    end do
    call agreed(error)
    if (allocated(error)) return
    ! 2. every condensed substructure from its owner, in order
    nrot = 0
    ip_ = 0
    do isub = 1, size(model%subs)
       if (.not. summary%sub_condensed(isub)) cycle
       ip_ = ip_ + 1
       call exchange_part(st, cache, summary%sub_owner(isub), ip_, self%owned, fstar, error)
       if (allocated(error)) return
       call exchange_notes(st%parts(ip_), summary%sub_owner(isub), error)
       if (allocated(error)) return
       associate (v => st%parts(ip_), f_phys => st%f_phys, table => st%table)
         if (allocated(v%notes)) then
            do i = 1, size(v%notes)
               call append_string(notes, v%notes(i)%s)
            end do
         end if
         if (v%rotated) nrot = nrot + 1
         ! as condense_parts: AUTOSPC notes and loads on DOFs without stiffness
         do i = 1, size(v%spc)
            if (any(f_phys(v%spc(i), :) /= 0.0_wp)) then
               call add_error_line(error, EXIT_SINGULAR, 'error: load on a DOF without stiffness: '// &
                    dof_label(model, table, v%spc(i)))
            else if (.not. v%reused) then
               call note(notes, 'AUTOSPC: '//dof_label(model, table, v%spc(i))//' has no stiffness and no load: dropped')
            end if
         end do
         if (allocated(error)) return   ! the same on every process: the ending agrees, rank 0 prints
         st%f_eff(v%se%pdof, :) = fstar
       end associate
       deallocate (fstar)
    end do
    counts = [int(cache%computed - computed0, i8), int(cache%reused - reused0, i8)]
    call sum_counts(counts, ok)
    call note(notes, 'condensations: '//itoa(counts(1))//' computed, '//itoa(counts(2))//' reused ('// &
         itoa(nrot)//' turned by their instance''s placement) on '//itoa(comm%size)//' processes')
  end subroutine condense_distributed

  subroutine exchange_notes(v, owner, error)
    !! The owner's notes on condensed part v (the library's: loaded, stored,
    !! not used) to every process, so that rank 0 lists them in the order of
    !! the parts, as one process does.
    type(part_view_t), intent(inout) :: v
    integer, intent(in) :: owner
    type(error_t), allocatable, intent(out) :: error
    type(comm_t) :: comm
    real(wp), allocatable :: codes(:)
    real(wp) :: head(1)
    logical :: ok
    integer :: n
    comm = comm_world()
    head = 0.0_wp
    if (owner == comm%rank) then
       if (.not. allocated(v%notes)) allocate (v%notes(0))
       call pack_strings(v%notes, codes)
       head(1) = real(size(codes), wp)
    end if
    call broadcast(head, owner, ok)
    if (ok) then
       n = nint(head(1))
       if (owner /= comm%rank) allocate (codes(n))
       if (n > 0) call broadcast(codes, owner, ok)
    end if
    if (.not. ok) call fatal_error(error, EXIT_IO, 'error: MPI broadcast of a condensation failed')
    if (allocated(error) .or. owner == comm%rank) return
    call unpack_strings(codes, v%notes)
  end subroutine exchange_notes

  subroutine pack_strings(list, codes)
    !! Strings as reals for a broadcast: each one's length, then its character codes.
    type(string_t), intent(in) :: list(:)
    real(wp), allocatable, intent(out) :: codes(:)
    integer :: i, j, at, n
    n = 0
    do i = 1, size(list)
       n = n + 1 + len(list(i)%s)
    end do
    allocate (codes(n))
    at = 0
    do i = 1, size(list)
       at = at + 1
       codes(at) = real(len(list(i)%s), wp)
       do j = 1, len(list(i)%s)
          codes(at + j) = real(iachar(list(i)%s(j:j)), wp)
       end do
       at = at + len(list(i)%s)
    end do
  end subroutine pack_strings

  subroutine unpack_strings(codes, list)
    !! The strings pack_strings packed, appended to list.
    real(wp), intent(in) :: codes(:)
    type(string_t), allocatable, intent(inout) :: list(:)
    character(:), allocatable :: text
    integer :: at, j, n
    at = 0
    do while (at < size(codes))
       n = nint(codes(at + 1))
       allocate (character(n) :: text)
       do j = 1, n
          text(j:j) = achar(nint(codes(at + 1 + j)))
       end do
       call append_string(list, text)
       deallocate (text)
       at = at + 1 + n
    end do
  end subroutine unpack_strings

  subroutine exchange_part(st, cache, owner, ip_, owned, fstar, error)
    !! Condensed part st%parts(ip_) from its owner to every process: its
    !! reuse and rotation flags, MAXRATIO, DOFs without stiffness, K* (but
    !! under owner terms, owned), k u0 when nonzero, and its loads f*.
    type(solve_state_t), intent(inout) :: st
    type(part_cache_t), intent(inout) :: cache
    integer, intent(in) :: owner, ip_
    logical, intent(in) :: owned
    real(wp), allocatable, intent(out) :: fstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(comm_t) :: comm
    real(wp), allocatable :: head(:), body(:)
    integer(i8) :: nkk, nb, ni, nspc, at, nku0
    integer :: nstep
    logical :: ok, mine
    comm = comm_world()
    mine = owner == comm%rank
    nstep = size(st%f_phys, 2)
    associate (v => st%parts(ip_), f_phys => st%f_phys, tr => st%tr)
      ni = v%ni
      nb = v%nb
      allocate (head(NHEAD), fstar(nb, nstep), source=0.0_wp)
      if (mine) then
         call view_spc(cache, v, v%spc)
         call view_maxratio(cache, v, v%ratio, v%ratio_at)
         call owner_ku0(cache, tr, v)
         call view_condense_loads(cache, v, f_phys(v%pdof, :), fstar, error)
         if (allocated(error)) return   ! a load condensation does not fail in practice; see module notes
         head = [merge(1.0_wp, 0.0_wp, v%reused), merge(1.0_wp, 0.0_wp, v%rotated), v%ratio, &
              real(v%ratio_at, wp), real(size(v%spc), wp), merge(1.0_wp, 0.0_wp, any(v%ku0 /= 0.0_wp))]
      end if
      call broadcast(head, owner, ok)
      if (.not. ok) call fatal_error(error, EXIT_IO, 'error: MPI broadcast of a condensation failed')
      if (allocated(error)) return
      nspc = nint(head(5), i8)
      nku0 = merge(ni + nb, 0_i8, head(6) /= 0.0_wp)
      nkk = merge(0_i8, nb*nb, owned)   ! owner terms: K* stays with its owner
      allocate (body(nspc + nkk + nb*nstep + nku0))
      if (mine) then
         body(1:nspc) = real(v%spc, wp)
         at = nspc
         if (.not. owned) body(at + 1:at + nkk) = reshape(v%se%k, [nkk])
         at = at + nkk
         body(at + 1:at + nb*nstep) = reshape(fstar, [nb*nstep])
         at = at + nb*nstep
         if (nku0 > 0) body(at + 1:) = v%ku0
      end if
      call broadcast(body, owner, ok)
      if (.not. ok) call fatal_error(error, EXIT_IO, 'error: MPI broadcast of a condensation failed')
      if (allocated(error)) return
      if (.not. mine) then
         v%reused = head(1) /= 0.0_wp
         v%rotated = head(2) /= 0.0_wp
         v%ratio = head(3)
         v%ratio_at = nint(head(4), i8)
         v%spc = nint(body(1:nspc), i8)
         at = nspc
         if (.not. owned) v%se%k = reshape(body(at + 1:at + nkk), [nb, nb])
         at = at + nkk
         fstar = reshape(body(at + 1:at + nb*nstep), [nb, int(nstep, i8)])
         at = at + nb*nstep
         if (nku0 > 0) then
            v%ku0 = body(at + 1:)
         else
            allocate (v%ku0(ni + nb), source=0.0_wp)
         end if
      end if
    end associate
  end subroutine exchange_part

  subroutine distributed_plan(self, st, model, summary)
    !! Owner terms: this process's own substructures and K* (owner_plan);
    !! else the whole K_red, as on one process.
    class(distributed_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_summary_t), intent(in) :: summary
    type(plain_strategy_t) :: plain
    if (self%owned) then
       if (.not. allocated(st%parts)) allocate (st%parts(0))
       call owner_plan(model, summary, st%parts, st%plan)
    else if (summary%n_condensed > 0) then
       call self%condensed_strategy_t%set_plan(st, model, summary)
    else
       call plain%set_plan(st, model, summary)
    end if
  end subroutine distributed_plan

  subroutine combine_terms(self, st, error)
    !! Owner terms: the processes agree on the assembly's outcome, and the
    !! reduced load of the prescribed values is summed over their terms.
    class(distributed_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(error_t), allocatable, intent(inout) :: error
    if (.not. self%owned) return
    call agreed(error)
    if (allocated(error)) return
    call sum_owner_loads(st%f_u0, error)
  end subroutine combine_terms

  subroutine recover_own(self, st, cache, error)
    !! The interiors (and k u) of this process's own substructures, summed
    !! over the processes (recover_distributed, parts_ku_distributed).
    class(distributed_strategy_t), intent(in) :: self
    type(solve_state_t), intent(inout) :: st
    type(part_cache_t), intent(inout) :: cache
    type(error_t), allocatable, intent(out) :: error
    associate (no_use => self)   ! owner terms or not, every process recovers its own
    end associate
    call recover_distributed(cache, st%parts, st%f_phys, st%u, error)
    if (allocated(error)) return
    call parts_ku_distributed(cache, st%parts, st%f_phys, st%u, st%ku, error)
  end subroutine recover_own

  logical function owner_summed(self)
    !! Owner terms: st%k is only this process's term of K_red.
    class(distributed_strategy_t), intent(in) :: self
    owner_summed = self%owned
  end function owner_summed

  subroutine terms_matvec(self, k, x, y, error)
    !! y = K x, K the sum of the processes' terms under owner terms.
    class(distributed_strategy_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: y(:, :)
    type(error_t), allocatable, intent(inout) :: error
    if (self%owned) then
       call summed_matvec(k, x, y, error)
    else
       call k%matvec(x, y)
    end if
  end subroutine terms_matvec

  subroutine terms_diagonal(self, k, d, error)
    !! The diagonal of K, the sum of the processes' terms under owner terms.
    class(distributed_strategy_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(out) :: d(:)
    type(error_t), allocatable, intent(inout) :: error
    if (self%owned) then
       call summed_diagonal(k, d, error)
    else
       call k%diagonal(d)
    end if
  end subroutine terms_diagonal

  subroutine terms_norm1(self, k, knorm, error)
    !! ‖K‖₁, K the sum of the processes' terms under owner terms.
    class(distributed_strategy_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(out) :: knorm
    type(error_t), allocatable, intent(inout) :: error
    if (self%owned) then
       call summed_norm1(k, knorm, error)
    else
       knorm = norm1_sym(k)
    end if
  end subroutine terms_norm1

  subroutine owner_ku0(cache, tr, v)
    !! k u0 of an own substructure: its stiffness times the prescribed values
    !! of its boundary (what full_health needs of every substructure).
    type(part_cache_t), intent(in) :: cache
    type(transform_t), intent(in) :: tr
    type(part_view_t), intent(inout) :: v
    real(wp), allocatable :: u0l(:, :), w(:, :)
    allocate (u0l(v%ni + v%nb, 1), w(v%ni + v%nb, 1), source=0.0_wp)
    u0l(v%ni + 1:, 1) = tr%prescribed(v%pdof(v%ni + 1:))
    if (any(u0l /= 0.0_wp)) call view_stiffness_times(cache, v, u0l, w)
    v%ku0 = w(:, 1)
  end subroutine owner_ku0

  subroutine recover_distributed(cache, parts, f_phys, u, error)
    !! recover_with_ku's recovery over several processes: each process recovers the
    !! interiors of its own substructures (the views that are not remote);
    !! the sum over the processes fills in the others.
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), intent(in) :: parts(:)
    real(wp), intent(in) :: f_phys(:, :)
    real(wp), intent(inout) :: u(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ul(:, :), buf(:)
    integer(i8) :: at, n
    integer :: i, nstep
    logical :: ok
    nstep = size(u, 2)
    n = 0
    do i = 1, size(parts)
       n = n + parts(i)%ni*nstep
    end do
    allocate (buf(n), source=0.0_wp)
    at = 0
    do i = 1, size(parts)
       associate (v => parts(i))
         if (v%entry > 0) then
            ul = u(v%pdof, :)
            call view_recover(cache, v, f_phys(v%pdof, :), ul, error)
            if (allocated(error)) return
            buf(at + 1:at + v%ni*nstep) = reshape(ul(1:v%ni, :), [v%ni*nstep])
         end if
         at = at + v%ni*nstep
       end associate
    end do
    call agreed(error)
    if (allocated(error)) return
    call sum_reals(buf, ok)
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, 'error: MPI sum of the recovered interiors failed')
       return
    end if
    at = 0
    do i = 1, size(parts)
       associate (v => parts(i))
         u(v%pdof(1:v%ni), :) = reshape(buf(at + 1:at + v%ni*nstep), [v%ni, int(nstep, i8)])
         at = at + v%ni*nstep
       end associate
    end do
  end subroutine recover_distributed

  subroutine parts_ku_distributed(cache, parts, f_phys, u, ku, error)
    !! recover_with_ku's k u over several processes: k u of each condensed substructure by
    !! its owner (a library entry: from the entry, view_ku), summed over the
    !! processes (zero off the condensed DOFs).
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: parts(:)
    real(wp), intent(in) :: f_phys(:, :), u(:, :)
    real(wp), allocatable, intent(out) :: ku(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: y(:, :), buf(:)
    integer(i8) :: at, n, m
    integer :: i, nstep
    logical :: ok
    nstep = size(u, 2)
    n = 0
    do i = 1, size(parts)
       n = n + size(parts(i)%pdof, kind=i8)*nstep
    end do
    allocate (buf(n), source=0.0_wp)
    at = 0
    do i = 1, size(parts)
       m = size(parts(i)%pdof, kind=i8)
       if (parts(i)%entry > 0) then
          allocate (y(m, nstep))
          call view_ku(cache, parts(i), f_phys(parts(i)%pdof, :), u(parts(i)%pdof, :), y, error)
          if (allocated(error)) return   ! a library entry's k u does not fail in practice
          buf(at + 1:at + m*nstep) = reshape(y, [m*nstep])
          deallocate (y)
       end if
       at = at + m*nstep
    end do
    call sum_reals(buf, ok)
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, 'error: MPI sum of the substructures'' k u failed')
       return
    end if
    allocate (ku(size(u, 1), nstep), source=0.0_wp)
    at = 0
    do i = 1, size(parts)
       m = size(parts(i)%pdof, kind=i8)
       ku(parts(i)%pdof, :) = ku(parts(i)%pdof, :) + reshape(buf(at + 1:at + m*nstep), [m, int(nstep, i8)])
       at = at + m*nstep
    end do
  end subroutine parts_ku_distributed

  subroutine mpi_summary(quiet, error)
    !! Collective, once the solve has ended on every process (it agrees
    !! first, so that a process that failed meets it): per process the bytes
    !! it passed to collectives (broadcasts of condensations, sums of
    !! interiors, the solution), the matrix entries it handed MUMPS and their
    !! bytes, and MUMPS's memory (INFO(16); INFOG(18) the largest process,
    !! INFOG(19) all), and the entries of the reduced matrix it assembled
    !! (the whole K_red, or with owner terms only its own term). Rank 0 prints
    !! them on stderr unless quiet. On one process only the MUMPS ordering
    !! line (order_summary), if MUMPS factored.
    logical, intent(in) :: quiet
    type(error_t), allocatable, intent(out) :: error
    type(comm_t) :: comm
    type(mumps_stats_t) :: ms
    integer(i8), allocatable :: v(:)
    integer(i8) :: moved
    integer :: r
    logical :: ok
    character(len=200) :: line
    comm = comm_world()
    if (comm%size <= 1) then
       if (.not. quiet) call order_summary()
       return
    end if
    call agreed(error)
    if (allocated(error)) return
    moved = bytes_moved()
    ms = mumps_stats()
    allocate (v(NSTAT*comm%size), source=0_i8)
    v(NSTAT*comm%rank + 1:NSTAT*comm%rank + NSTAT) = [moved, ms%entries, ms%mb_here, ms%mb_max, ms%mb_total, ms%held]
    call sum_counts(v, ok)
    if (.not. ok .or. quiet .or. .not. comm%is_root()) return
    do r = 0, comm%size - 1
       associate (x => v(NSTAT*r + 1:NSTAT*r + NSTAT))
         write (line, '(a,i0,a,i0,a,i0,a,i0,a,i0,a,i0,a)') 'superjoin: MPI process ', r, ': collectives ', x(1), &
              ' bytes, matrix assembled ', x(6), ' entries, MUMPS input ', x(2), ' entries (', &
              x(2)*BYTES_MUMPS_ENTRY, ' bytes), MUMPS memory ', x(3), ' MB'
       end associate
       write (error_unit, '(a)') trim(line)
    end do
    write (error_unit, '(a,i0,a,i0,a)') 'superjoin: MUMPS memory over the processes (INFOG(18), INFOG(19)): largest ', &
         v(4), ' MB, all ', v(5), ' MB'
    call order_summary()
  end subroutine mpi_summary

  subroutine order_summary()
    !! The ordering and factor of the run's largest MUMPS factorization on
    !! stderr (issue 14, orderings compared): INFOG(29) factor entries and
    !! the analysis's estimate INFOG(20), RINFOG(3) flops, the estimated
    !! memory INFOG(21) (largest process) and INFOG(22) (all), and for
    !! superjoin's own METIS ordering the host's seconds and the pattern
    !! gathered to it. Nothing if MUMPS did not factor.
    type(mumps_order_stats_t) :: os
    character(len=40) :: flops
    os = mumps_order_stats()
    if (os%factor_entries < 0) return
    write (flops, '(es10.3)') os%flops
    write (error_unit, '(a)') 'superjoin: MUMPS ordering '//os%ordering//': factor entries '// &
         itoa(os%factor_entries)//' (estimate '//itoa(os%estimate)//'), flops '//trim(adjustl(flops))// &
         ', estimated memory largest '//itoa(os%mb_estimate_max)//' MB, all '//itoa(os%mb_estimate_total)//' MB'
    if (os%host_seconds > 0.0_wp .or. os%gathered_bytes > 0) then
       write (flops, '(f10.3)') os%host_seconds
       write (error_unit, '(a)') 'superjoin: METIS ordering by superjoin: '//trim(adjustl(flops))// &
            ' s on the host, pattern gathered '//itoa(os%gathered_bytes)//' bytes'
    end if
  end subroutine order_summary

  subroutine agreed(error)
    !! Collective: every process says whether it failed (error allocated). A
    !! process that failed keeps its own error; the others get a silent one
    !! with the agreed status (the failing process prints).
    type(error_t), allocatable, intent(inout) :: error
    integer :: worst, first, mine
    mine = 0
    if (allocated(error)) mine = error%code
    call agree(mine, worst, first)
    if (worst == 0) return
    call note_agreed_failure(first)
    if (allocated(error)) then
       error%code = worst
    else
       call fatal_error(error, worst, 'error: process '//itoa(first)//' failed')
    end if
  end subroutine agreed
end module superjoin_analysis_distributed
