module superjoin_analysis_step_groups
  !! Steps grouped by a relation between them (the same contact stiffnesses,
  !! the same supports): the steps of one group share one solve.
  implicit none (type, external)
  private

  public :: group_steps

contains

  pure subroutine group_steps(related, group, ngroup)
    !! group(s) for every step s: the group of the first earlier step t with
    !! related(s, t), or a new group (numbered in order of first appearance).
    !! Only related(s, t) with t < s is read.
    logical, intent(in) :: related(:, :)
    integer, allocatable, intent(out) :: group(:)
    integer, intent(out) :: ngroup
    integer :: s, t
    allocate (group(size(related, 1)), source=0)
    ngroup = 0
    do s = 1, size(group)
       do t = 1, s - 1
          if (related(s, t)) then
             group(s) = group(t)
             exit
          end if
       end do
       if (group(s) == 0) then
          ngroup = ngroup + 1
          group(s) = ngroup
       end if
    end do
  end subroutine group_steps
end module superjoin_analysis_step_groups
