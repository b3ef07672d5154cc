program test_parts
  !! Unit tests of parts and joint studies: *INSTANCE placement (translation,
  !! then rotation about the axis through a and b), the turned beam orientation,
  !! the record of part and placement on the instance, *CHANGE CONTACT and SWEEP
  !! overrides, and the joint-study wrapper's plain path (without *CHANGE
  !! CONTACT it returns exactly what solve_model returns).
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, find_node, LINK_FINITE, LINK_RIGID, LINK_NONE
  use superjoin_deck_reader, only: read_deck, read_deck_string
  use superjoin_analysis, only: solve_model
  use superjoin_analysis_driver, only: solve_joint_steps => solve_steps, has_joint_changes
  use superjoin_model_results, only: results_t, run_options_t
  use superjoin_testing, only: check, check_close, finish
  implicit none (type, external)

  character, parameter :: LF = achar(10)

  call test_placement()
  call test_change_contact()
  call test_plain_path('decks/hinge_beam.deck')
  call test_plain_path('decks/rigid_loop.deck')
  call test_plain_path('decks/folded_plate.deck')
  call finish()

contains

  function join(lines) result(text)
    character(*), intent(in) :: lines(:)
    character(:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(lines)
       text = text//trim(lines(i))//LF
    end do
  end function join

  subroutine test_placement()
    !! A part node x lands at a + R (x + t - a); R turns 40 degrees about (1, 1, 2).
    type(model_t) :: model
    type(error_t), allocatable :: error
    character(len=80), parameter :: deck(*) = [character(len=80) :: &
         '*MATERIAL, NAME=S', '*ELASTIC', '2.1e11, 0.3', &
         '*PART, NAME=BAR', '*NODE', '1, 0.0, 0.0, 0.0', '2, 2.0, 0.5, -1.0', &
         '*ELEMENT, TYPE=B33, ELSET=B', '1, 1, 2', &
         '*BEAM SECTION, ELSET=B, MATERIAL=S', '1.0e-3, 2.0e-6, 5.0e-6, 3.0e-6', '0.0, 1.0, 1.0', &
         '*END PART', '*ASSEMBLY', &
         '*INSTANCE, NAME=P1, PART=BAR', '*END INSTANCE', &
         '*INSTANCE, NAME=P2, PART=BAR', '1.0, 2.0, 3.0', '1.0, -1.0, 2.0, 2.0, 0.0, 4.0, 40.0', '*END INSTANCE', &
         '*INSTANCE, NAME=P3, PART=BAR', '0.0, 0.0, 0.0', '5.0, 5.0, 0.0, 5.0, 5.0, 7.0, 90.0', '*END INSTANCE', &
         '*END ASSEMBLY', '*BOUNDARY', 'P1.1, ENCASTRE', 'P2.1, ENCASTRE', 'P3.1, ENCASTRE']
    real(wp) :: a(3), t(3), n(3), c, s, r(3, 3), x(3), want(3)
    integer :: i, k
    call read_deck_string(join(deck), 'inline.deck', model, error)
    call check(.not. allocated(error), 'placement deck reads')
    if (allocated(error)) then
       write (*, '(a)') error%message
       return
    end if
    call check(size(model%subs) == 3, 'three instances, no part left in model%subs')
    call check(size(model%parts) == 1, 'one part recorded')
    if (size(model%subs) /= 3 .or. size(model%parts) /= 1) return
    call check(model%parts(1)%s == 'BAR', 'part name')
    call check(all(model%subs%part == 1), 'every instance records its part')
    call check(all(model%subs(1)%rot == reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3])), 'P1: no rotation')
    ! Rodrigues by hand
    a = [1.0_wp, -1.0_wp, 2.0_wp]
    t = [1.0_wp, 2.0_wp, 3.0_wp]
    n = [1.0_wp, 1.0_wp, 2.0_wp]/sqrt(6.0_wp)
    c = cos(40.0_wp*acos(-1.0_wp)/180.0_wp)
    s = sin(40.0_wp*acos(-1.0_wp)/180.0_wp)
    do i = 1, 3
       r(:, i) = (1.0_wp - c)*n*n(i)
       r(i, i) = r(i, i) + c
    end do
    r(1, 2) = r(1, 2) - s*n(3); r(2, 1) = r(2, 1) + s*n(3)
    r(1, 3) = r(1, 3) + s*n(2); r(3, 1) = r(3, 1) - s*n(2)
    r(2, 3) = r(2, 3) - s*n(1); r(3, 2) = r(3, 2) + s*n(1)
    do k = 1, 3
       do i = 1, 3
          call check_close(model%subs(2)%rot(i, k), r(i, k), 1.0e-15_wp, 'P2: rotation matrix')
       end do
    end do
    call check_close(maxval(abs(matmul(transpose(r), r) - reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3]))), &
         0.0_wp, 1.0e-15_wp, 'R is orthogonal')
    x = [2.0_wp, 0.5_wp, -1.0_wp]
    want = a + matmul(r, x + t - a)
    k = int(find_node(model%subs(2), 2_ip))
    do i = 1, 3
       call check_close(model%subs(2)%x(i, k), want(i), 1.0e-14_wp, 'P2: node 2 at a + R (x + t - a)')
       call check_close(model%subs(2)%shift(i), a(i) + dot_product(r(i, :), t - a), 1.0e-14_wp, &
            'P2: shift = a + R (t - a)')
    end do
    ! beam orientation turns: v = R (0, 1, 1)
    want = matmul(r, [0.0_wp, 1.0_wp, 1.0_wp])
    do i = 1, 3
       call check_close(model%subs(2)%sections(1)%v(i), want(i), 1.0e-15_wp, 'P2: v = R v_part')
    end do
    ! quarter turn about the vertical axis through (5, 5): exact
    k = int(find_node(model%subs(3), 2_ip))
    call check(all(model%subs(3)%x(:, k) == [5.0_wp + 4.5_wp, 5.0_wp - 3.0_wp, -1.0_wp]), &
         'P3: a quarter turn is exact')
    call check(all(model%subs(3)%sections(1)%v == [-1.0_wp, 0.0_wp, 1.0_wp]), 'P3: v turned exactly')
  end subroutine test_placement

  subroutine test_change_contact()
    !! Overrides land on the right link and DOFs; SWEEP expands the step.
    type(model_t) :: model
    type(error_t), allocatable :: error
    character(len=80), parameter :: deck(*) = [character(len=80) :: &
         '*MATERIAL, NAME=S', '*ELASTIC', '2.1e11, 0.3', &
         '*SUBSTRUCTURE, NAME=A', '*NODE', '1, 0.0, 0.0', '2, 1.0, 0.0', &
         '*ELEMENT, TYPE=B23, ELSET=B', '1, 1, 2', '*BEAM SECTION, ELSET=B, MATERIAL=S', '1.0e-3, 1.0e-6', &
         '*END SUBSTRUCTURE', &
         '*SUBSTRUCTURE, NAME=C', '*NODE', '1, 1.0, 0.0', '2, 2.0, 0.0', &
         '*ELEMENT, TYPE=B23, ELSET=B', '1, 1, 2', '*BEAM SECTION, ELSET=B, MATERIAL=S', '1.0e-3, 1.0e-6', &
         '*END SUBSTRUCTURE', &
         '*CONTACT, NAME=J, MASTER=A, SLAVE=C', '2, 1, 1, 2, RIGID', '2, 1, 6, 6, 1.0e5', &
         '*BOUNDARY', 'A.1, ENCASTRE', &
         '*STEP, NAME=S', '*CLOAD', 'C.2, 2, -1.0', '*CHANGE CONTACT, NAME=J, SWEEP', &
         '2, 1, 6, 6, 1.0e3, RIGID, 0', '*END STEP', &
         '*STEP, NAME=T', '*CLOAD', 'C.2, 2, -1.0', '*END STEP']
    call read_deck_string(join(deck), 'inline.deck', model, error)
    call check(.not. allocated(error), 'sweep deck reads')
    if (allocated(error)) then
       write (*, '(a)') error%message
       return
    end if
    call check(size(model%steps) == 4, 'SWEEP of 3 values: 3 steps + 1')
    if (size(model%steps) /= 4) return
    call check(model%steps(1)%name == 'S-1' .and. model%steps(3)%name == 'S-3' .and. &
         model%steps(4)%name == 'T', 'sweep step names')
    call check(has_joint_changes(model), 'the model has joint changes')
    call check(size(model%steps(1)%link_overrides) == 1, 'S-1: one link changes')
    if (allocated(model%steps(4)%link_overrides)) then
       call check(size(model%steps(4)%link_overrides) == 0, 'T: no change')
    end if
    associate (o1 => model%steps(1)%link_overrides(1), o2 => model%steps(2)%link_overrides(1), &
         o3 => model%steps(3)%link_overrides(1))
      call check(o1%link == 1 .and. all(o1%dofs .eqv. [.false., .false., .false., .false., .false., .true.]), &
           'S-1: link 1, DOF 6')
      call check(o1%state(6) == LINK_FINITE .and. o1%g(6) == 1.0e3_wp, 'S-1: g = 1e3')
      call check(o2%state(6) == LINK_RIGID, 'S-2: RIGID')
      call check(o3%state(6) == LINK_NONE .and. o3%g(6) == 0.0_wp, 'S-3: g = 0')
    end associate
    call check(size(model%steps(1)%cloads) == 1 .and. size(model%steps(3)%cloads) == 1, &
         'every sweep step keeps the loads')
  end subroutine test_change_contact

  subroutine test_plain_path(path)
    !! Without *CHANGE CONTACT, solve_joint_steps is solve_model (same bits).
    character(*), intent(in) :: path
    type(model_t) :: model
    type(error_t), allocatable :: error
    type(results_t) :: r1, r2
    type(run_options_t) :: opts
    integer :: i
    logical :: same
    opts%solver = 'auto'
    opts%quiet = .true.
    call read_deck(path, model, error)
    call check(.not. allocated(error), path//': reads')
    if (allocated(error)) return
    call check(.not. has_joint_changes(model), path//': no joint changes')
    call solve_model(model, opts, r1, error)
    call check(.not. allocated(error), path//': solve_model')
    call solve_joint_steps(model, opts, r2, error)
    call check(.not. allocated(error), path//': solve_joint_steps')
    if (allocated(error)) return
    same = all(r1%fields%u == r2%fields%u) .and. same_forces(r1, r2) .and. size(r1%log%notes) == size(r2%log%notes) &
         .and. r1%summary%maxratio == r2%summary%maxratio .and. r1%summary%neq == r2%summary%neq .and. r1%summary%factor_nnz == r2%summary%factor_nnz
    do i = 1, min(size(r1%log%notes), size(r2%log%notes))
       same = same .and. r1%log%notes(i)%s == r2%log%notes(i)%s
    end do
    do i = 1, size(r1%fields%steps)
       same = same .and. r1%fields%steps(i)%residual == r2%fields%steps(i)%residual .and. &
            all(r1%fields%steps(i)%reaction == r2%fields%steps(i)%reaction)
    end do
    call check(same, path//': the same results, bit for bit, as solve_model')
  end subroutine test_plain_path

  logical function same_forces(r1, r2)
    !! The end forces of both runs are equal, or neither run has any (a model
    !! of plate-type elements only keeps none).
    type(results_t), intent(in) :: r1, r2
    same_forces = allocated(r1%fields%elem_force) .eqv. allocated(r2%fields%elem_force)
    if (same_forces .and. allocated(r1%fields%elem_force)) &
         same_forces = all(r1%fields%elem_force == r2%fields%elem_force)
  end function same_forces
end program test_parts
