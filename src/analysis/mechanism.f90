module superjoin_analysis_mechanism
  !! The mechanism of a singular stiffness: a null vector of the reduced
  !! stiffness K, found by inverse iteration with a factorization of K + s I
  !! (s a small shift relative to the largest diagonal), expanded to the
  !! physical DOFs and ranked. The same vector comes out of every backend:
  !! each iteration multiplies the null-space part of the start vector by 1/s
  !! and every other part by 1/(λ + s) ≪ 1/s, so after a few iterations the
  !! vector is the projection of a fixed start vector on the null space, up to
  !! round-off; the report rounds amplitudes to MODE_DIGITS decimals (ties in
  !! the order of the model) so that listings and messages do not depend on
  !! the backend.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, NDOF_NODE
  use superjoin_assembly_dofs, only: dof_table_t, UNIT_SUPPORT
  use superjoin_assembly_transform, only: transform_t
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, mumps_solver_t
  use superjoin_analysis_summed_matrix, only: summed_diagonal, summed_nonzero, holds_shared_terms
  use superjoin_utils_sorting, only: sort_index
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  real(wp), parameter, public :: MECH_SHIFT = 1.0e-10_wp
    !! s = MECH_SHIFT x the median diagonal of K (the unknowns taken out of the
    !! factorization, identity columns, left aside): far below any real
    !! stiffness, far above the round-off of a null eigenvalue (eps x ‖K‖) while
    !! the diagonal spans less than 1e5 around its median. The median, not the
    !! largest: a few PENALTY springs must not set the scale.
  real(wp), parameter, public :: MECH_ACCEPT = 0.5_wp
    !! A mode is a mechanism when the last solve grew it by at least
    !! MECH_ACCEPT / s, i.e. its stiffness λ is at most about s: a structure
    !! that is only ill-conditioned (PENALTY with a huge g) has λ ≫ s and keeps
    !! the breakdown message instead.
  integer, parameter, public :: MECH_ITERATIONS = 4
    !! Inverse iterations (each damps a mode of stiffness λ by s / (λ + s)).
  integer, parameter, public :: MODE_DIGITS = 3
    !! Decimals of the relative amplitudes reported (and ranked on).
  integer, parameter :: MAX_PER_PART = 6    !! DOFs listed per substructure
  integer, parameter :: MAX_PARTS = 10      !! substructures listed

  type, public :: mechanism_t
    !! A mechanism mode and its report.
     logical :: found = .false.
     real(wp), allocatable :: mode(:, :)        !! (NDOF_NODE, nvertex), global axes, largest |value| = 1
     character(:), allocatable :: location      !! "substructure S node N DOF d" of the largest entry
     character(:), allocatable :: details       !! report lines, each starting with two blanks
     logical :: no_support = .false.            !! the model has no support at all
  end type mechanism_t

  public :: find_mechanism, mechanism_message, mechanism_error

contains

  subroutine find_mechanism(k, solver_name, model, table, tr, mech, summed)
    !! Null vector of the reduced stiffness k (inverse iteration on k + s I with
    !! the backend solver_name), expanded to the physical DOFs and ranked into
    !! mech. mech%found stays false when the shifted matrix cannot be factored
    !! or there is nothing to report (the caller keeps its own message).
    !! summed: k is this MPI process's term of K_red (analysis/summed_matrix;
    !! MUMPS local input): the diagonal is the sum's, process 0 adds the shift.
    type(sparse_sym_t), intent(in) :: k
    character(*), intent(in) :: solver_name
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(mechanism_t), intent(out) :: mech
    logical, intent(in), optional :: summed
    type(sparse_sym_t) :: ks
    class(linear_solver_t), allocatable :: solver
    type(error_t), allocatable :: error
    real(wp), allocatable :: x(:, :), y(:, :), d(:)
    real(wp) :: s, xmax, growth
    integer(i8) :: j
    integer :: it, stat
    logical :: terms
    logical, allocatable :: nz(:), offdiag(:)

    terms = .false.
    if (present(summed)) terms = summed
    if (k%n <= 0) return
    allocate (d(k%n), x(k%n, 1), y(k%n, 1), stat=stat)
    if (stat /= 0) return   ! (with summed, every process has the same n: an allocation this small does not differ)
    if (terms) then
       allocate (nz(k%n), offdiag(k%n))
       call summed_diagonal(k, d, error)
       if (.not. allocated(error)) call summed_nonzero(k, nz, offdiag, error)
       if (allocated(error)) return
       s = MECH_SHIFT*median_diagonal(k, d, offdiag)
    else
       call k%diagonal(d)
       s = MECH_SHIFT*median_diagonal(k, d)
    end if
    if (.not. (s > 0.0_wp)) return
    ks = k
    if (.not. terms .or. holds_shared_terms()) then
       do j = 1, k%n
          ks%val(ks%colptr(j + 1) - 1) = ks%val(ks%colptr(j + 1) - 1) + s
       end do
    end if
    call new_solver(solver_name, ks%n, solver, error)
    if (allocated(error)) return
    if (terms) then
       select type (solver)
       type is (mumps_solver_t)
          solver%local_input = .true.
       end select
    end if
    call solver%analyze(ks, error)
    if (allocated(error)) return
    call solver%factorize(ks, error)
    if (allocated(error)) then
       call solver%release()
       return
    end if
    do j = 1, k%n
       x(j, 1) = start_value(j)
    end do
    growth = 0.0_wp
    do it = 1, MECH_ITERATIONS
       call solver%solve(x, y, error)
       if (allocated(error)) exit
       xmax = maxval(abs(y))
       if (.not. (xmax > 0.0_wp .and. xmax <= huge(xmax))) exit
       growth = xmax/maxval(abs(x))
       x = y/xmax
    end do
    call solver%release()
    if (allocated(error) .or. it <= MECH_ITERATIONS) return
    if (growth*s < MECH_ACCEPT) return
    call expand(x(:, 1), table, tr, mech%mode)
    mech%no_support = .not. any(table%units(1:table%nunit)%kind == UNIT_SUPPORT)
    call rank_report(model, table, mech)
  end subroutine find_mechanism

  function median_diagonal(k, d, offdiag) result(m)
    !! Median of |K_jj| over the columns that are not identity columns (the
    !! unknowns dropped or skipped before factoring); 0 if there are none.
    !! offdiag (MPI terms): whether column j of the sum has a nonzero above
    !! the diagonal (else k's own entries tell).
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(in) :: d(:)
    logical, intent(in), optional :: offdiag(:)
    real(wp) :: m
    real(wp), allocatable :: a(:)
    integer, allocatable :: order(:)
    integer(i8) :: j
    integer :: n, i
    allocate (a(size(d)))
    n = 0
    do j = 1, k%n
       if (d(j) == 1.0_wp) then
          if (present(offdiag)) then
             if (.not. offdiag(j)) cycle
          else if (all(k%val(k%colptr(j):k%colptr(j + 1) - 2) == 0.0_wp)) then
             cycle
          end if
       end if
       if (d(j) == 0.0_wp) cycle
       n = n + 1
       a(n) = abs(d(j))
    end do
    m = 0.0_wp
    if (n == 0) return
    order = [(i, i=1, n)]
    call sort_index(a(1:n), order)
    m = a(order((n + 1)/2))
  end function median_diagonal

  pure function start_value(j) result(v)
    !! A fixed start vector with no symmetry a mechanism could be orthogonal to.
    integer(i8), intent(in) :: j
    real(wp) :: v
    v = 1.0_wp + 0.5_wp*sin(real(j, wp))
  end function start_value

  subroutine expand(q, table, tr, mode)
    !! Physical DOFs u = T q, per vertex and DOF, scaled to largest |u| = 1.
    real(wp), intent(in) :: q(:)
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    real(wp), allocatable, intent(out) :: mode(:, :)
    integer(i8) :: p, v
    real(wp) :: umax
    real(wp), allocatable :: u(:, :)
    allocate (mode(NDOF_NODE, table%nvertex), source=0.0_wp)
    allocate (u(table%np, 1))
    call tr%expand(reshape(q, [size(q), 1]), u, linear=.true.)
    do p = 1, table%np
       v = table%vertex_offset(table%p_sub(p)) + table%p_node(p)
       mode(table%p_dof(p), v) = u(p, 1)
    end do
    umax = maxval(abs(mode))
    if (umax > 0.0_wp) mode = mode/umax
  end subroutine expand

  subroutine rank_report(model, table, mech)
    !! Rank the moving DOFs by rounded amplitude (ties: model order), fix the
    !! sign so that the first is positive, and write the report grouped by
    !! substructure (substructures in the order of their largest DOF).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(mechanism_t), intent(inout) :: mech
    real(wp), parameter :: SCALE = 10.0_wp**MODE_DIGITS
    integer, allocatable :: order(:), v_of(:), d_of(:), listed(:), moving(:)
    real(wp), allocatable :: key(:)
    integer :: n, i, isub, nparts, m, ip0
    integer(i8) :: v
    logical, allocatable :: part_seen(:)
    integer, allocatable :: part_order(:)
    character(:), allocatable :: text, line
    real(wp) :: sgn

    n = count(nint(abs(mech%mode)*SCALE) > 0)
    if (n == 0) return
    allocate (v_of(n), d_of(n), key(n), order(n))
    n = 0
    do v = 1, table%nvertex
       do i = 1, NDOF_NODE
          if (nint(abs(mech%mode(i, v))*SCALE) == 0) cycle
          n = n + 1
          v_of(n) = int(v)
          d_of(n) = i
          key(n) = -real(nint(abs(mech%mode(i, v))*SCALE), wp)
       end do
    end do
    order = [(i, i=1, n)]
    call sort_index(key, order)
    ! the sign of the largest first, and every amplitude rounded as reported:
    ! the mode written to VTK and CSV is the same for every backend too
    sgn = sign(1.0_wp, mech%mode(d_of(order(1)), v_of(order(1))))
    mech%mode = sgn*real(nint(mech%mode*SCALE), wp)/SCALE
    mech%location = dof_label(model, table, v_of(order(1)), d_of(order(1)))
    mech%found = .true.

    ! substructures in the order of their first (largest) entry
    allocate (part_seen(size(model%subs)), source=.false.)
    allocate (part_order(0))
    do i = 1, n
       isub = sub_of(table, v_of(order(i)))
       if (.not. part_seen(isub)) then
          part_seen(isub) = .true.
          part_order = [part_order, isub]
       end if
    end do
    nparts = size(part_order)
    if (mech%no_support) then
       text = '  no support at all: the whole model is free to move as a rigid body '// &
            '(add *SUPPORT or *BOUNDARY lines)'//new_line('a')
    else
       text = ''
    end if
    text = text//'  mechanism mode ('//itoa(n)//' DOFs in '//itoa(nparts)// &
         ' substructure(s) move; amplitudes relative to the largest, largest first):'
    do ip0 = 1, min(nparts, MAX_PARTS)
       isub = part_order(ip0)
       moving = pack(order, [(sub_of(table, v_of(order(i))) == isub, i=1, n)])
       line = '    substructure '//model%subs(isub)%name//':'
       listed = moving(1:min(size(moving), MAX_PER_PART))
       do m = 1, size(listed)
          if (m > 1) line = line//','
          line = line//' node '//itoa(int(model%subs(isub)%node_id(node_of(table, v_of(listed(m)), isub))))// &
               ' DOF '//itoa(d_of(listed(m)))//' '//amplitude(mech%mode(d_of(listed(m)), v_of(listed(m))))
       end do
       if (size(moving) > MAX_PER_PART) line = line//', ... ('//itoa(size(moving) - MAX_PER_PART)//' more)'
       text = text//new_line('a')//line
    end do
    if (nparts > MAX_PARTS) text = text//new_line('a')//'    ... ('//itoa(nparts - MAX_PARTS)// &
         ' more substructures)'
    mech%details = text
  end subroutine rank_report

  subroutine mechanism_error(k, solver_name, model, table, tr, hint, mode, error, summed)
    !! For a factorization that failed: the EXIT_SINGULAR error naming the
    !! mechanism of k (hint appended to its first line) and its mode, or
    !! neither when k has no mechanism (the caller keeps its own message).
    !! summed: k is this MPI process's term of K_red (see find_mechanism).
    type(sparse_sym_t), intent(in) :: k
    character(*), intent(in) :: solver_name
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    character(*), intent(in) :: hint
    real(wp), allocatable, intent(out) :: mode(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: summed
    type(mechanism_t) :: mech
    call find_mechanism(k, solver_name, model, table, tr, mech, summed)
    if (.not. mech%found) return
    call fatal_error(error, EXIT_SINGULAR, mechanism_message(mech, hint))
    call move_alloc(mech%mode, mode)
  end subroutine mechanism_error

  function mechanism_message(mech, hint) result(text)
    !! The exit-3 message of a found mechanism: location, hint, report lines.
    type(mechanism_t), intent(in) :: mech
    character(*), intent(in) :: hint
    character(:), allocatable :: text
    text = 'error: the structure cannot be solved: mechanism at '//mech%location//hint// &
         new_line('a')//mech%details
  end function mechanism_message

  function amplitude(a) result(s)
    !! Signed relative amplitude with MODE_DIGITS decimals.
    real(wp), intent(in) :: a
    character(:), allocatable :: s
    character(len=16) :: buf
    write (buf, '(sp,f7.3)') real(nint(a*10.0_wp**MODE_DIGITS), wp)/10.0_wp**MODE_DIGITS
    s = trim(adjustl(buf))
  end function amplitude

  pure integer function sub_of(table, v) result(isub)
    !! Substructure of a vertex.
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: v
    do isub = 1, size(table%vertex_offset) - 1
       if (v <= table%vertex_offset(isub + 1)) return
    end do
  end function sub_of

  pure function node_of(table, v, isub) result(inode)
    !! Local node of vertex v in substructure isub.
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: v, isub
    integer(ip) :: inode
    inode = int(v - table%vertex_offset(isub), ip)
  end function node_of

  function dof_label(model, table, v, d) result(label)
    !! "substructure S node N DOF d" (as the other messages name a DOF).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: v, d
    character(:), allocatable :: label
    integer :: isub
    isub = sub_of(table, v)
    label = 'substructure '//model%subs(isub)%name//' node '// &
         itoa(int(model%subs(isub)%node_id(node_of(table, v, isub))))//' DOF '//itoa(d)
  end function dof_label
end module superjoin_analysis_mechanism
