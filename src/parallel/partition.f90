module superjoin_parallel_partition
  !! Which process owns which substructure in a run on several processes.
  !!
  !! The part graph has one vertex per substructure (a plain substructure or
  !! an *INSTANCE) weighted by its active DOFs and by an estimated cost of its
  !! condensation, and one edge per pair of substructures that contact
  !! elements (or *EQUATION terms) join, weighted by their number. METIS
  !! (k-way, fixed seed) cuts it into one share per process, balancing both
  !! weights and keeping the contact elements between processes few. With
  !! fewer than MIN_PARTS_PER_RANK substructures per process the graph is too
  !! small for that to pay, and a deterministic greedy rule is used instead:
  !! the substructures by decreasing cost, each to the process with the least
  !! cost so far (the lowest such process on a tie). The greedy rule is also
  !! the fallback when METIS fails or leaves a process without work while
  !! another has several substructures.
  !!
  !! Estimated cost of a substructure with n_i interior and n_b boundary DOFs
  !! (floating-point operations, up to a common factor): n_i^(3/2) for the
  !! sparse factor of its interior (nested dissection of a two-dimensional
  !! mesh), 2 n_i n_b for the n_b solves that form its Schur complement, n_b^2
  !! for the complement itself. Instances of one *PART share one condensation
  !! on one process: on a process that owns several, the second and later pay
  !! only n_b^2 (the turned copy); the report counts it so.
  use, intrinsic :: iso_c_binding, only: c_int
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, string_t
  use superjoin_utils_sorting, only: sort_index
  use superjoin_utils_strings, only: itoa
  use superjoin_model_notes, only: append_string
  implicit none (type, external)
  private

  integer, parameter, public :: MIN_PARTS_PER_RANK = 4
    !! Below this many substructures per process the greedy rule is used.
  integer, parameter :: NCON = 2
    !! METIS balance constraints: estimated cost, DOFs.
  integer, parameter :: METIS_WEIGHT_MAX = 2**24
    !! Vertex weights are scaled so that their sum stays below this (idx_t is 32-bit).
  integer, parameter :: MAX_NAMES = 12
    !! Substructure names listed per process in the report.

  type, public :: part_graph_t
    !! The substructures as a weighted graph (CSR, 1-based, both directions).
     integer :: n = 0
     integer(i8), allocatable :: dofs(:)       !! (n) active DOFs
     integer(i8), allocatable :: boundary(:)   !! (n) of which boundary (contacts, supports)
     real(wp), allocatable :: cost(:)          !! (n) estimated condensation cost
     integer, allocatable :: xadj(:)           !! (n+1)
     integer, allocatable :: adjncy(:)         !! neighbours
     integer(i8), allocatable :: ewgt(:)       !! contact elements on each edge
     integer, allocatable :: family(:)         !! (n) *PART index of an instance, 0 for a plain substructure
  end type part_graph_t

  type, public :: partition_t
    !! The owner of every substructure, and how good the split is.
     integer :: nrank = 1
     integer, allocatable :: owner(:)          !! (n) process 0 .. nrank-1
     character(:), allocatable :: method       !! how it was made (for the report)
     integer(i8) :: cut = 0                    !! contact elements between processes
     real(wp), allocatable :: rank_cost(:)     !! (0:nrank-1) estimated cost, shared condensations counted once
  end type partition_t

  public :: build_part_graph, estimated_cost, partition_parts, partition_report

  interface
     function sj_metis_partition(n, ncon, xadj, adjncy, vwgt, adjwgt, nparts, part, cut) &
          bind(c, name='sj_metis_partition') result(status)
       import :: c_int
       integer(c_int), value :: n, ncon, nparts
       integer(c_int), intent(in) :: xadj(*), adjncy(*), vwgt(*), adjwgt(*)
       integer(c_int), intent(out) :: part(*), cut
       integer(c_int) :: status
     end function sj_metis_partition
  end interface

contains

  elemental function estimated_cost(dofs, boundary) result(c)
    !! Estimated condensation cost of a substructure (see the module notes).
    integer(i8), intent(in) :: dofs, boundary
    real(wp) :: c
    real(wp) :: ni, nb
    ni = real(max(dofs - boundary, 0_i8), wp)
    nb = real(boundary, wp)
    c = ni*sqrt(ni) + 2.0_wp*ni*nb + nb*nb
  end function estimated_cost

  subroutine build_part_graph(model, sub_dofs, sub_boundary, graph)
    !! The part graph of a model, from the active and boundary DOFs of each
    !! substructure (run_summary_t%sub_dofs, sub_boundary).
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: sub_dofs(:), sub_boundary(:)
    type(part_graph_t), intent(out) :: graph
    integer, allocatable :: ea(:), eb(:), order(:), fill(:)
    integer(i8), allocatable :: key(:)
    integer :: n, ne, i, j, k, a, b
    n = size(model%subs)
    graph%n = n
    graph%dofs = sub_dofs
    graph%boundary = sub_boundary
    graph%cost = estimated_cost(sub_dofs, sub_boundary)
    allocate (graph%family(n))
    do i = 1, n
       graph%family(i) = model%subs(i)%part
    end do
    ! every joining as an (a, b) pair, a < b
    call joined_pairs(model, ea, eb)
    ne = size(ea)
    allocate (key(ne), order(ne))
    do k = 1, ne
       key(k) = int(ea(k) - 1, i8)*n + (eb(k) - 1)
       order(k) = k
    end do
    call sort_index(key, order)
    ! count distinct pairs and their multiplicity, both directions
    allocate (graph%xadj(n + 1), source=0)
    k = 1
    do while (k <= ne)
       j = k
       do while (j < ne)
          if (key(order(j + 1)) /= key(order(k))) exit
          j = j + 1
       end do
       graph%xadj(ea(order(k)) + 1) = graph%xadj(ea(order(k)) + 1) + 1
       graph%xadj(eb(order(k)) + 1) = graph%xadj(eb(order(k)) + 1) + 1
       k = j + 1
    end do
    graph%xadj(1) = 1
    do i = 1, n
       graph%xadj(i + 1) = graph%xadj(i + 1) + graph%xadj(i)
    end do
    allocate (graph%adjncy(graph%xadj(n + 1) - 1), graph%ewgt(graph%xadj(n + 1) - 1))
    allocate (fill(n))
    fill = graph%xadj(1:n)
    k = 1
    do while (k <= ne)
       j = k
       do while (j < ne)
          if (key(order(j + 1)) /= key(order(k))) exit
          j = j + 1
       end do
       a = ea(order(k))
       b = eb(order(k))
       graph%adjncy(fill(a)) = b
       graph%ewgt(fill(a)) = j - k + 1
       fill(a) = fill(a) + 1
       graph%adjncy(fill(b)) = a
       graph%ewgt(fill(b)) = j - k + 1
       fill(b) = fill(b) + 1
       k = j + 1
    end do
  end subroutine build_part_graph

  subroutine joined_pairs(model, ea, eb)
    !! The pairs of distinct substructures that a contact element or an
    !! *EQUATION joins, one entry per joining (a < b).
    type(model_t), intent(in) :: model
    integer, allocatable, intent(out) :: ea(:), eb(:)
    integer :: nl, ne, i, j, k, a, b
    nl = 0
    if (allocated(model%links)) nl = size(model%links)
    ne = nl
    if (allocated(model%equations)) then
       do i = 1, size(model%equations)
          ne = ne + max(size(model%equations(i)%sub) - 1, 0)
       end do
    end if
    allocate (ea(ne), eb(ne))
    k = 0
    do i = 1, nl
       a = model%contacts(model%links(i)%contact)%master_sub
       b = model%contacts(model%links(i)%contact)%slave_sub
       call add(a, b)
    end do
    if (allocated(model%equations)) then
       do i = 1, size(model%equations)
          do j = 2, size(model%equations(i)%sub)
             call add(model%equations(i)%sub(1), model%equations(i)%sub(j))
          end do
       end do
    end if
    ea = ea(1:k)
    eb = eb(1:k)
  contains
    subroutine add(p, q)
      integer, intent(in) :: p, q
      if (p == q .or. p < 1 .or. q < 1) return
      k = k + 1
      ea(k) = min(p, q)
      eb(k) = max(p, q)
    end subroutine add
  end subroutine joined_pairs

  subroutine partition_parts(graph, nrank, part, error)
    !! Owner of every substructure among nrank processes (see the module notes).
    type(part_graph_t), intent(in) :: graph
    integer, intent(in) :: nrank
    type(partition_t), intent(out) :: part
    type(error_t), allocatable, intent(out) :: error
    logical :: metis_ok
    part%nrank = max(nrank, 1)
    allocate (part%owner(graph%n), source=0)
    metis_ok = .false.
    if (part%nrank > 1 .and. graph%n >= MIN_PARTS_PER_RANK*part%nrank) then
       call metis_owner(graph, part%nrank, part%owner, metis_ok)
       if (metis_ok) metis_ok = no_idle_rank(part%owner, part%nrank)
       if (metis_ok) then
          part%method = 'METIS k-way on the part graph'
       else
          part%method = 'greedy by estimated cost (METIS gave an unusable split)'
       end if
    else if (part%nrank > 1) then
       part%method = 'greedy by estimated cost (fewer than '//itoa(MIN_PARTS_PER_RANK)// &
            ' substructures per process)'
    else
       part%method = 'one process'
    end if
    if (.not. metis_ok .and. part%nrank > 1) call greedy_owner(graph, part%nrank, part%owner)
    call score(graph, part)
    if (graph%n > 0 .and. (minval(part%owner) < 0 .or. maxval(part%owner) >= part%nrank)) &
         call fatal_error(error, EXIT_IO, 'error: internal: partition of the substructures out of range')
  end subroutine partition_parts

  subroutine metis_owner(graph, nrank, owner, ok)
    !! METIS k-way with cost and DOFs as balance constraints, contact counts
    !! as edge weights; weights scaled into METIS's 32-bit range.
    type(part_graph_t), intent(in) :: graph
    integer, intent(in) :: nrank
    integer, intent(inout) :: owner(:)
    logical, intent(out) :: ok
    integer(c_int), allocatable :: vwgt(:), adjwgt(:), p(:)
    integer(c_int) :: cut
    real(wp) :: s_cost, s_dofs, s_edge
    integer :: i
    s_cost = scale_for(sum(graph%cost))
    s_dofs = scale_for(real(sum(graph%dofs), wp))
    s_edge = scale_for(real(sum(graph%ewgt), wp))
    allocate (vwgt(NCON*graph%n), adjwgt(size(graph%adjncy)), p(graph%n))
    do i = 1, graph%n
       vwgt(NCON*(i - 1) + 1) = int(max(1.0_wp, graph%cost(i)*s_cost), c_int)
       vwgt(NCON*(i - 1) + 2) = int(max(1.0_wp, real(graph%dofs(i), wp)*s_dofs), c_int)
    end do
    do i = 1, size(graph%adjncy)
       adjwgt(i) = int(max(1.0_wp, real(graph%ewgt(i), wp)*s_edge), c_int)
    end do
    ok = sj_metis_partition(int(graph%n, c_int), int(NCON, c_int), int(graph%xadj, c_int), &
         int(graph%adjncy, c_int), vwgt, adjwgt, int(nrank, c_int), p, cut) == 0
    if (ok) owner = int(p)
  end subroutine metis_owner

  pure function scale_for(total) result(s)
    !! Factor that brings a sum of weights below METIS_WEIGHT_MAX (1 when it is already).
    real(wp), intent(in) :: total
    real(wp) :: s
    s = 1.0_wp
    if (total > real(METIS_WEIGHT_MAX, wp)) s = real(METIS_WEIGHT_MAX, wp)/total
  end function scale_for

  pure function no_idle_rank(owner, nrank) result(ok)
    !! Does every process own at least one substructure (there being enough)?
    integer, intent(in) :: owner(:), nrank
    logical :: ok
    integer :: r
    ok = .true.
    if (size(owner) < nrank) return
    do r = 0, nrank - 1
       if (.not. any(owner == r)) ok = .false.
    end do
  end function no_idle_rank

  subroutine greedy_owner(graph, nrank, owner)
    !! Largest estimated cost first (input order on a tie), each to the least
    !! loaded process (the lowest on a tie).
    type(part_graph_t), intent(in) :: graph
    integer, intent(in) :: nrank
    integer, intent(inout) :: owner(:)
    integer, allocatable :: order(:)
    real(wp), allocatable :: load(:)
    integer :: k, i, r
    allocate (order(graph%n), load(0:nrank - 1))
    order = [(i, i=1, graph%n)]
    call sort_index(-graph%cost, order)
    load = 0.0_wp
    do k = 1, graph%n
       i = order(k)
       r = minloc(load, dim=1) - 1
       load(r) = load(r) + graph%cost(i)
       owner(i) = r
    end do
  end subroutine greedy_owner

  subroutine score(graph, part)
    !! Contact elements between processes, and the estimated cost per process
    !! with one condensation per *PART and process.
    type(part_graph_t), intent(in) :: graph
    type(partition_t), intent(inout) :: part
    logical, allocatable :: seen(:, :)
    integer :: i, k, r, nfam
    allocate (part%rank_cost(0:part%nrank - 1), source=0.0_wp)
    nfam = 0
    if (graph%n > 0) nfam = maxval(graph%family)
    allocate (seen(max(nfam, 1), 0:part%nrank - 1), source=.false.)
    do i = 1, graph%n
       r = part%owner(i)
       if (graph%family(i) > 0) then
          if (seen(graph%family(i), r)) then
             part%rank_cost(r) = part%rank_cost(r) + real(graph%boundary(i), wp)**2
             cycle
          end if
          seen(graph%family(i), r) = .true.
       end if
       part%rank_cost(r) = part%rank_cost(r) + graph%cost(i)
    end do
    part%cut = 0
    do i = 1, graph%n
       do k = graph%xadj(i), graph%xadj(i + 1) - 1
          if (graph%adjncy(k) > i .and. part%owner(graph%adjncy(k)) /= part%owner(i)) &
               part%cut = part%cut + graph%ewgt(k)
       end do
    end do
  end subroutine score

  subroutine partition_report(model, graph, part, lines)
    !! The PARTITION block of the listing: per process its substructures,
    !! DOFs, boundary DOFs and estimated cost; the contact elements between
    !! processes; the imbalance (largest estimated cost over the mean).
    type(model_t), intent(in) :: model
    type(part_graph_t), intent(in) :: graph
    type(partition_t), intent(in) :: part
    type(string_t), allocatable, intent(out) :: lines(:)
    character(len=120) :: buf
    character(:), allocatable :: names
    real(wp) :: mean
    integer :: r, i, nnames
    allocate (lines(0))
    call add('PARTITION ('//itoa(part%nrank)//' processes; '//part%method//')')
    write (buf, '(a9,a15,a14,a15,a16)') '  process', 'substructures', 'DOFs', 'boundary DOFs', 'estimated cost'
    call add(trim(buf))
    do r = 0, part%nrank - 1
       write (buf, '(i9,i15,i14,i15,es16.3)') r, count(part%owner == r), sum(graph%dofs, mask=part%owner == r), &
            sum(graph%boundary, mask=part%owner == r), part%rank_cost(r)
       call add(trim(buf))
    end do
    do r = 0, part%nrank - 1
       names = ''
       nnames = 0
       do i = 1, graph%n
          if (part%owner(i) /= r) cycle
          nnames = nnames + 1
          if (nnames <= MAX_NAMES) names = names//' '//model%subs(i)%name
       end do
       if (nnames > MAX_NAMES) names = names//' and '//itoa(nnames - MAX_NAMES)//' more'
       if (nnames == 0) names = ' (none)'
       call add('  process '//itoa(r)//':'//names)
    end do
    write (buf, '(a,i0)') '  contact elements between processes   ', part%cut
    call add(trim(buf))
    mean = sum(part%rank_cost)/real(part%nrank, wp)
    if (mean > 0.0_wp) then
       write (buf, '(a,f0.3)') '  imbalance (largest cost / mean)     ', maxval(part%rank_cost)/mean
    else
       buf = '  imbalance (largest cost / mean)     n/a (no cost)'
    end if
    call add(trim(buf))
  contains
    subroutine add(s)
      character(*), intent(in) :: s
      call append_string(lines, s)
    end subroutine add
  end subroutine partition_report
end module superjoin_parallel_partition
