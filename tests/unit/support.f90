module verification_support
  !! Helpers for tests that solve decks: look up results by names and ids.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, find_node, section_t, material_t, SEC_SHELL
  use superjoin_deck_reader, only: read_deck, read_deck_string
  use superjoin_analysis, only: solve_model
  use superjoin_model_results, only: results_t, run_options_t
  implicit none (type, external)
  private

  public :: solve_file, solve_text, disp, reaction, link_force, link_delta, equilibrium_error, fail
  public :: shell_data

contains

  subroutine solve_file(path, model, res, solver, formulation)
    !! Read and solve a deck file; any error stops the test program.
    character(*), intent(in) :: path
    type(model_t), intent(out) :: model
    type(results_t), intent(out) :: res
    character(*), intent(in), optional :: solver
    integer, intent(in), optional :: formulation
    type(error_t), allocatable :: error
    call read_deck(path, model, error)
    call fail(error, path)
    call solve(model, res, solver, formulation)
  end subroutine solve_file

  subroutine solve_text(text, model, res, solver, formulation, error)
    !! Read and solve a deck given as text.
    character(*), intent(in) :: text
    type(model_t), intent(out) :: model
    type(results_t), intent(out) :: res
    character(*), intent(in), optional :: solver
    integer, intent(in), optional :: formulation
    type(error_t), allocatable, intent(out), optional :: error
    type(error_t), allocatable :: err
    type(run_options_t) :: opts
    call read_deck_string(text, 'inline.deck', model, err)
    call fail(err, 'inline.deck')
    opts%quiet = .true.
    opts%solver = 'auto'
    if (present(solver)) opts%solver = solver
    if (present(formulation)) opts%formulation = formulation
    call solve_model(model, opts, res, err)
    if (present(error)) then
       if (allocated(err)) call move_alloc(err, error)
       return
    end if
    call fail(err, 'inline.deck')
  end subroutine solve_text

  subroutine solve(model, res, solver, formulation)
    type(model_t), intent(in) :: model
    type(results_t), intent(out) :: res
    character(*), intent(in), optional :: solver
    integer, intent(in), optional :: formulation
    type(run_options_t) :: opts
    type(error_t), allocatable :: error
    opts%quiet = .true.
    opts%solver = 'auto'
    if (present(solver)) opts%solver = solver
    if (present(formulation)) opts%formulation = formulation
    call solve_model(model, opts, res, error)
    call fail(error, 'solve')
  end subroutine solve

  subroutine fail(error, what)
    !! Stop the test program with 'FAIL: what: message' when error is set.
    type(error_t), allocatable, intent(in) :: error
    character(*), intent(in) :: what
    if (.not. allocated(error)) return
    write (*, '(a)') 'FAIL: '//what//': '//error%message
    error stop 1
  end subroutine fail

  integer function sub_index(model, name) result(isub)
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    do isub = 1, size(model%subs)
       if (model%subs(isub)%name == name) return
    end do
    write (*, '(a)') 'FAIL: no substructure '//name
    error stop 1
  end function sub_index

  function disp(model, res, sub, id, dof, step) result(u)
    !! Displacement DOF `dof` of node `id` of substructure `sub` in step `step`.
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    character(*), intent(in) :: sub
    integer, intent(in) :: id, dof, step
    real(wp) :: u
    integer :: isub
    integer(ip) :: n
    isub = sub_index(model, sub)
    n = find_node(model%subs(isub), int(id, ip))
    u = res%fields%u(6*(res%fields%vertex_offset(isub) + n - 1) + dof, step)
  end function disp

  function reaction(model, res, sub, id, dof, step) result(f)
    !! Support reaction (0 when the DOF has none).
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    character(*), intent(in) :: sub
    integer, intent(in) :: id, dof, step
    real(wp) :: f
    integer :: isub, k
    isub = sub_index(model, sub)
    f = 0.0_wp
    do k = 1, size(res%fields%steps(step)%reactions)
       associate (rc => res%fields%steps(step)%reactions(k))
         if (rc%sub == isub .and. model%subs(isub)%node_id(rc%node) == id .and. rc%dof == dof) f = f + rc%force
       end associate
    end do
  end function reaction

  function link_force(model, res, name, dof, step) result(f)
    !! Force on the master of the first contact element of card `name`.
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    character(*), intent(in) :: name
    integer, intent(in) :: dof, step
    real(wp) :: f
    f = res%fields%steps(step)%link_force(dof, first_link(model, name))
  end function link_force

  function link_delta(model, res, name, dof, step) result(d)
    !! Relative displacement of the first contact element of card `name`.
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    character(*), intent(in) :: name
    integer, intent(in) :: dof, step
    real(wp) :: d
    d = res%fields%steps(step)%link_delta(dof, first_link(model, name))
  end function link_delta

  integer function first_link(model, name) result(il)
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    do il = 1, size(model%links)
       if (model%contacts(model%links(il)%contact)%name == name) return
    end do
    write (*, '(a)') 'FAIL: no contact '//name
    error stop 1
  end function first_link

  function equilibrium_error(res, step) result(e)
    !! max |applied + reactions| / max(|applied|, |reactions|) over the six directions.
    type(results_t), intent(in) :: res
    integer, intent(in) :: step
    real(wp) :: e, scale
    associate (st => res%fields%steps(step))
      scale = max(maxval(abs(st%applied)), maxval(abs(st%reaction)), tiny(1.0_wp))
      e = maxval(abs(st%applied + st%reaction))/scale
    end associate
  end function equilibrium_error

  subroutine shell_data(t, e, nu, sec, mat)
    !! An isotropic shell section of thickness t, its material E, nu.
    real(wp), intent(in) :: t, e, nu
    type(section_t), intent(out) :: sec
    type(material_t), intent(out) :: mat
    mat%e = e
    mat%nu = nu
    sec%kind = SEC_SHELL
    sec%thickness = t
  end subroutine shell_data
end module verification_support
