program test_partition
  !! Unit tests of the partition of the substructures over MPI processes
  !! (superjoin_parallel_partition), in any build (METIS is always linked):
  !! the estimated cost against its formula, the part graph's edges and
  !! weights, the greedy rule against a hand-worked assignment, METIS on a
  !! grid of parts (balanced, the straight cut found), determinism, more
  !! processes than parts, and one condensation per *PART and process in the
  !! cost per process.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, string_t
  use superjoin_parallel_partition, only: part_graph_t, partition_t, build_part_graph, estimated_cost, &
       partition_parts, partition_report, MIN_PARTS_PER_RANK
  use superjoin_testing, only: check, check_close, finish
  implicit none (type, external)

  call test_cost()
  call test_graph()
  call test_greedy()
  call test_metis_grid()
  call test_idle_ranks()
  call test_instances()
  call finish()

contains

  subroutine chain_model(nsub, pairs, model)
    !! nsub substructures; contact elements joining pairs(1,k) and pairs(2,k)
    !! (one contact card per element, as far as the graph cares).
    integer, intent(in) :: nsub, pairs(:, :)
    type(model_t), intent(out) :: model
    integer :: k
    allocate (model%subs(nsub), model%contacts(size(pairs, 2)), model%links(size(pairs, 2)))
    do k = 1, nsub
       model%subs(k)%name = 'S'//achar(iachar('0') + mod(k, 10))
    end do
    do k = 1, size(pairs, 2)
       model%contacts(k)%master_sub = pairs(1, k)
       model%contacts(k)%slave_sub = pairs(2, k)
       model%links(k)%contact = k
    end do
  end subroutine chain_model

  subroutine test_cost()
    ! n_i = 2, n_b = 10: 2 sqrt(2) + 2*2*10 + 100
    call check_close(estimated_cost(12_i8, 10_i8), 2.0_wp*sqrt(2.0_wp) + 140.0_wp, 1.0e-12_wp, 'cost formula')
    ! no interior: only the boundary block
    call check_close(estimated_cost(6_i8, 6_i8), 36.0_wp, 1.0e-12_wp, 'cost without interior')
    ! no boundary: the interior factor alone, n^(3/2)
    call check_close(estimated_cost(100_i8, 0_i8), 1000.0_wp, 1.0e-12_wp, 'cost without boundary')
  end subroutine test_cost

  subroutine test_graph()
    type(model_t) :: model
    type(part_graph_t) :: g
    integer :: k
    ! 1-2 twice, 2-3 once (written 3-2), a self contact on 3 (no edge)
    call chain_model(3, reshape([1, 2, 2, 1, 3, 2, 3, 3], [2, 4]), model)
    call build_part_graph(model, [10_i8, 20_i8, 30_i8], [2_i8, 4_i8, 6_i8], g)
    call check(g%n == 3, 'graph vertices')
    call check(all(g%xadj == [1, 2, 4, 5]), 'graph degrees 1 2 1')
    call check(g%adjncy(1) == 2 .and. g%ewgt(1) == 2, '1-2 carries two contact elements')
    k = g%xadj(3)
    call check(g%adjncy(k) == 2 .and. g%ewgt(k) == 1, '3-2 carries one contact element')
    call check(sum(g%ewgt) == 6, 'both directions stored (2*(2+1))')
    call check_close(g%cost(2), estimated_cost(20_i8, 4_i8), 1.0e-12_wp, 'vertex cost')
  end subroutine test_graph

  subroutine test_greedy()
    ! costs 100, 90, 50, 40, 30 (no interior, n_b = 10, sqrt(90) ...): take
    ! boundary-only parts so cost = n_b^2 exactly: n_b = 10, 9, 7, 6, 5 ->
    ! 100, 81, 49, 36, 25. Greedy on 2: 100->0, 81->1, 49->1 (130), 36->0
    ! (136), 25->1 (155): owners 0 1 1 0 1; costs 136, 155.
    type(model_t) :: model
    type(part_graph_t) :: g
    type(partition_t) :: p
    type(error_t), allocatable :: error
    integer(i8), parameter :: nb(5) = [10_i8, 9_i8, 7_i8, 6_i8, 5_i8]
    call chain_model(5, reshape([1, 2, 2, 3, 3, 4, 4, 5], [2, 4]), model)
    call build_part_graph(model, nb, nb, g)
    call partition_parts(g, 2, p, error)
    call check(.not. allocated(error), 'greedy: no error')
    call check(index(p%method, 'greedy') == 1, 'greedy below '//'MIN_PARTS_PER_RANK per process')
    call check(all(p%owner == [0, 1, 1, 0, 1]), 'greedy owners 0 1 1 0 1')
    call check_close(p%rank_cost(0), 136.0_wp, 1.0e-12_wp, 'greedy cost of process 0')
    call check_close(p%rank_cost(1), 155.0_wp, 1.0e-12_wp, 'greedy cost of process 1')
    ! contact elements between processes: 1-2, 3-4, 4-5 (2-3 inside process 1)
    call check(p%cut == 3, 'greedy cut 3')
  end subroutine test_greedy

  subroutine test_metis_grid()
    ! 8 x 8 parts, each joined to its right and upper neighbour by 3 contact
    ! elements: 2 processes must get 32 equal parts each, and the straight
    ! cut (8 neighbour pairs, 24 contact elements) is the optimum METIS finds.
    integer, parameter :: m = 8
    type(model_t) :: model
    type(part_graph_t) :: g
    type(partition_t) :: p, p2
    type(error_t), allocatable :: error
    type(string_t), allocatable :: lines(:)
    integer, allocatable :: pairs(:, :)
    integer :: i, j, k, np, r
    allocate (pairs(2, 3*2*m*(m - 1)))
    k = 0
    do j = 1, m
       do i = 1, m
          do r = 1, 3
             if (i < m) then
                k = k + 1
                pairs(:, k) = [(j - 1)*m + i, (j - 1)*m + i + 1]
             end if
             if (j < m) then
                k = k + 1
                pairs(:, k) = [(j - 1)*m + i, j*m + i]
             end if
          end do
       end do
    end do
    call chain_model(m*m, pairs, model)
    call build_part_graph(model, [(100_i8, i=1, m*m)], [(20_i8, i=1, m*m)], g)
    call check(m*m >= MIN_PARTS_PER_RANK*2, 'grid large enough for METIS')
    call partition_parts(g, 2, p, error)
    call check(.not. allocated(error), 'METIS: no error')
    call check(index(p%method, 'METIS') == 1, 'METIS used on the grid')
    call check(count(p%owner == 0) == 32 .and. count(p%owner == 1) == 32, 'METIS: 32 parts each')
    call check(p%cut == 3*m, 'METIS: the straight cut (24 contact elements)')
    call partition_parts(g, 2, p2, error)
    call check(all(p%owner == p2%owner), 'METIS: deterministic')
    do np = 3, 4
       call partition_parts(g, np, p, error)
       call check(.not. allocated(error), 'METIS on more processes: no error')
       call check(maxval(p%rank_cost)/(sum(p%rank_cost)/np) < 1.1_wp, 'METIS: imbalance below 1.1')
       call check(p%cut < 3*2*m*(m - 1)/2, 'METIS: cuts fewer than half the contact elements')
    end do
    call partition_parts(g, 2, p, error)
    call partition_report(model, g, p, lines)
    call check(size(lines) == 8, 'report: title, header, 2 processes, 2 name lines, cut, imbalance')
    call check(lines(1)%s(1:24) == 'PARTITION (2 processes; ', 'report title')
    call check(index(lines(5)%s, ' and 20 more') > 0, 'report: names cut after 12')
    call check(lines(8)%s == '  imbalance (largest cost / mean)     1.000', 'report: imbalance 1.000')
  end subroutine test_metis_grid

  subroutine test_idle_ranks()
    ! two parts, four processes: processes 2 and 3 own nothing
    type(model_t) :: model
    type(part_graph_t) :: g
    type(partition_t) :: p
    type(error_t), allocatable :: error
    call chain_model(2, reshape([1, 2], [2, 1]), model)
    call build_part_graph(model, [30_i8, 40_i8], [3_i8, 4_i8], g)
    call partition_parts(g, 4, p, error)
    call check(.not. allocated(error), 'idle ranks: no error')
    call check(all(p%owner == [1, 0]), 'idle ranks: larger part to process 0')
    call check(all(p%rank_cost(2:3) == 0.0_wp), 'idle ranks: no cost on 2, 3')
  end subroutine test_idle_ranks

  subroutine test_instances()
    ! three instances of one *PART and a plain substructure, greedy on 2:
    ! same cost c for all; owners 0 1 0 1; process 0 holds instances 1 and
    ! 3: one condensation (c) and one turned copy (n_b^2).
    type(model_t) :: model
    type(part_graph_t) :: g
    type(partition_t) :: p
    type(error_t), allocatable :: error
    real(wp) :: c
    call chain_model(4, reshape([1, 2, 2, 3, 3, 4], [2, 3]), model)
    model%subs(1:3)%part = 1
    call build_part_graph(model, [50_i8, 50_i8, 50_i8, 50_i8], [5_i8, 5_i8, 5_i8, 5_i8], g)
    call partition_parts(g, 2, p, error)
    c = estimated_cost(50_i8, 5_i8)
    call check(all(p%owner == [0, 1, 0, 1]), 'instances: owners 0 1 0 1')
    call check_close(p%rank_cost(0), c + 25.0_wp, 1.0e-12_wp, 'instances: one condensation per process')
    call check_close(p%rank_cost(1), 2*c, 1.0e-12_wp, 'plain substructure counted in full')
  end subroutine test_instances
end program test_partition
