module superjoin_analysis_distributed
  !! The distributed pipeline of a run on several MPI processes: which process
  !! owns which substructure (superjoin_parallel_partition) and the PARTITION
  !! block of the listing. On one process (and in the serial build) nothing
  !! is done and the listing has no PARTITION block.
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t
  use superjoin_analysis_results, only: run_summary_t, run_log_t
  use superjoin_parallel_comm, only: comm_t, comm_world
  use superjoin_parallel_partition, only: part_graph_t, partition_t, build_part_graph, partition_parts, &
       partition_report
  implicit none (type, external)
  private

  public :: plan_distribution

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
end module superjoin_analysis_distributed
