module superjoin_analysis_held_supports
  !! *BOUNDARY, FIXED: supports held at the displacements of an earlier step
  !! (support_t%held_from), whose values are known only once that step is
  !! solved. The driver solves the groups of steps in their order of first
  !! appearance (a group's steps all come after the step they hold to) and
  !! fills each group's held values from the results merged so far, along
  !! each DOF's own axis (the nodal system of a *TRANSFORM, as *BOUNDARY reads
  !! its DOFs).
  use superjoin_kinds, only: wp, i8
  use superjoin_model_types, only: model_t, support_t, NDOF_NODE, frame_of_node
  use superjoin_model_results, only: results_t
  implicit none (type, external)
  private

  public :: has_held, held_sources, fill_held

  integer, parameter :: NTRANS = 3   !! translations (then as many rotations) of a node

contains

  pure logical function has_held(model)
    !! Whether some step holds DOFs at an earlier step's displacements.
    type(model_t), intent(in) :: model
    integer :: s
    has_held = .false.
    if (.not. allocated(model%steps)) return
    do s = 1, size(model%steps)
       if (.not. allocated(model%steps(s)%supports)) cycle
       if (any(model%steps(s)%supports%held_from > 0)) has_held = .true.
    end do
  end function has_held

  pure function held_sources(list) result(steps)
    !! The steps whose displacements the supports of list hold (ascending, each once).
    type(support_t), intent(in) :: list(:)
    integer, allocatable :: steps(:)
    logical, allocatable :: named(:)
    integer :: k, s
    allocate (named(max(0, maxval(list%held_from))), source=.false.)   ! maxval of none: -huge
    do k = 1, size(list)
       if (list(k)%held_from > 0) named(list(k)%held_from) = .true.
    end do
    steps = pack([(s, s=1, size(named))], named)
  end function held_sources

  subroutine fill_held(model, members, res)
    !! The held values of the supports of the steps members, from the
    !! displacements res holds (global axes) of the steps they name: each
    !! along its DOF's axis, the nodal system's where the node has one.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: members(:)
    type(results_t), intent(in) :: res
    integer :: m, k
    do m = 1, size(members)
       if (.not. allocated(model%steps(members(m))%supports)) cycle
       associate (list => model%steps(members(m))%supports)
         do k = 1, size(list)
            if (list(k)%held_from <= 0) cycle
            list(k)%value = held_value(model, res, list(k))
         end do
       end associate
    end do
  end subroutine fill_held

  real(wp) function held_value(model, res, sp) result(v)
    !! Component sp%dof of the displacement of sp's node in step sp%held_from,
    !! along the node's nodal system where it has one (the last *TRANSFORM, as
    !! the DOF table takes it).
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(support_t), intent(in) :: sp
    real(wp) :: u(NDOF_NODE)
    integer :: f, base
    integer(i8) :: vx
    vx = res%fields%vertex_offset(sp%sub) + sp%node
    u = res%fields%u(NDOF_NODE*(vx - 1) + 1:NDOF_NODE*vx, sp%held_from)
    f = frame_of_node(model, sp%sub, sp%node)
    if (f == 0) then
       v = u(sp%dof)
       return
    end if
    base = 0
    if (sp%dof > NTRANS) base = NTRANS
    v = dot_product(model%frames(f)%q(sp%dof - base, :), u(base + 1:base + NTRANS))
  end function held_value
end module superjoin_analysis_held_supports
