module superjoin_analysis_recover
  !! Recovery of physical results from the reduced solution: displacements,
  !! element end forces, contact Δ and F, support reactions, equilibrium.
  !!
  !! Rigid components carry the forces that balance r = K_phys u - f (elements
  !! and finite contacts as elements, minus loads). A rigid tree unit pushes on
  !! its child with the sum of r over the child's subtree; a rigid component that
  !! closed a loop gets its force from the equation of the column it eliminated.
  use, intrinsic :: iso_c_binding, only: c_int, c_size_t
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: MAX_ELEMENT_DOFS, MAX_ELEMENT_NODES
  use superjoin_error, only: error_t, add_error_line, EXIT_DECK
  use superjoin_model_types, only: model_t, DLOAD_THERMAL, ELEMENT_NODE_COUNT, LINK_NONE, LINK_FINITE, LINK_RIGID, &
       NDOF_NODE, loc_text, substructure_t
  use superjoin_elements, only: element_end_forces, element_nodal_forces, &
       is_plate_type, shell_forces, is_solid_type, solid_forces, shell_result_operator, is_plane_type
  use superjoin_assembly_dofs, only: dof_table_t, vertex_dofs, unit_t, NBLOCK, GROUND, UNIT_LINK, UNIT_SUPPORT, block_dof, &
       unit_terms, arm_matrix, MAX_UNIT_TERMS
  use superjoin_assembly_forest, only: forest_t
  use superjoin_assembly_transform, only: transform_t, form_spring_t, constraint_t, ROLE_TREE, CONS_ELIMINATED
  use superjoin_assembly_assemble, only: element_pdofs
  use superjoin_elements, only: distributed_load
  use superjoin_model_results, only: results_t, reaction_t
  use superjoin_analysis_body_loads, only: plate_thermal_strains, line_centrif_forces
  use superjoin_elements, only: take_thermal_resultants
  use superjoin_analysis_body_loads, only: plane_thermal_nodal, line_thermal_forces
  use superjoin_analysis_body_loads, only: shell_thermal_curvature_nodal
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL, BYTES_INT
  use superjoin_utils_huge_pages, only: advise_huge
  use superjoin_elements, only: element_drill, ring_nodes
  use superjoin_analysis_solve_state, only: solve_state_t
  implicit none (type, external)
  private

  integer, parameter :: MAX_ELEM_DOFS = MAX_ELEMENT_DOFS
  real(wp), parameter :: TURN_TOL = 1.0e-12_wp
    !! |Q33 - 1| below which a relative turn of two instances keeps Z.

  public :: recover_results

  interface
     function malloc_trim(pad) bind(c, name='malloc_trim') result(released)
       !! glibc: the heap's free pages back to the system (1 when some were).
       import :: c_int, c_size_t
       integer(c_size_t), value :: pad
       integer(c_int) :: released
     end function malloc_trim
  end interface

  type :: closing_t
    !! The closing forces of the eliminated constraints (rclose, physical DOFs
    !! × steps) held sparsely: row slot(p) of val for a DOF p some constraint
    !! acts on, zero for every other DOF (a dense np × nsteps array was the
    !! run's peak on the 1e6 frame).
     integer, allocatable :: slot(:)          !! (np) 0: no closing force
     integer(i8), allocatable :: dof(:)       !! (n) the DOF of each row
     real(wp), allocatable :: val(:, :)       !! (capacity, nstep)
     integer :: n = 0
  end type closing_t

  type :: node_flags_t
    !! One logical per node of a substructure.
     logical, allocatable :: on(:)
  end type node_flags_t

contains

  subroutine recover_results(st, model, wanted, res, error)
    !! Fill res%fields%u, res%fields%elem_force and res%fields%steps(:) from the reduced solution st%q
    !! and the physical displacements st%u (T q + u0, with condensed interiors).
    !! With st%ku (physical DOFs × steps: k u of the substructures in
    !! res%summary%sub_condensed, from their own assembled stiffness), the elements of
    !! those substructures give only their results, not k_e u_e again.
    !! wanted (elements numbered over the substructures): the elements whose
    !! results somebody reads; the others are left at zero and skipped unless
    !! their k_e u_e is needed (a node of theirs carries a contact or support).
    type(solve_state_t), intent(in) :: st
    type(model_t), intent(in) :: model
    logical, intent(in) :: wanted(:)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: r(:, :), delta(:, :, :), acc(:, :)
    type(closing_t) :: rclose
    real(wp), allocatable :: rigid_force(:, :, :)  ! (3, nunit, nstep): rigid force on child / λ, local
    real(wp), allocatable :: req(:, :)             ! (np, nstep): *EQUATION forces on the structure
    integer :: nstep, is, stat, i
    integer(c_int) :: trimmed

    associate (table => st%table, forest => st%forest, tr => st%tr, q => st%q, u => st%u, f_phys => st%f_phys)
      nstep = size(q, 2)
      call store_displacements(table, u, res, error)
      if (allocated(error)) return
      allocate (r(table%np, nstep), rclose%slot(table%np), rclose%dof(16), rclose%val(16, nstep), &
           rigid_force(3, table%nunit, nstep), acc(3, 0:table%nvertex), stat=stat)
      if (stat /= 0) then
         call out_of_memory(error, 'the recovery of forces', (table%np*nstep + 3*table%nunit*nstep + &
              3*(table%nvertex + 1))*BYTES_REAL + table%np*BYTES_INT)
         return
      end if
      r = -f_phys
      if (allocated(st%ku)) r = r + st%ku
      call element_results(model, table, u, r, res, error, allocated(st%ku), wanted)
      if (allocated(error)) return
      call unit_deltas(table, tr, q, u, delta)
      call add_spring_forces(table, delta, r)

      rigid_force = 0.0_wp
      rclose%slot = 0
      call closer_forces(table, tr, r, rigid_force, rclose, req)
      do i = 1, rclose%n   ! r - rclose: the DOFs without a closing force keep r (r - 0 = r)
         r(rclose%dof(i), :) = r(rclose%dof(i), :) - rclose%val(i, :)
      end do
      deallocate (rclose%slot, rclose%val)
      do is = 1, nstep
         call tree_forces(table, forest, r(:, is), acc, rigid_force(:, :, is))
      end do
      ! The run's peak can be here (1e6 frame: the factor and K are still
      ! held): r and acc are freed before the link results, and given back
      ! (they sit in the heap once glibc's mmap threshold has grown, where
      ! free alone would keep them resident). Not in the values of a joint
      ! study (st%give_back): each next value would fault in and clear those
      ! pages again (20-value study of CPS4 panels: 61 000 of 144 000 page
      ! faults fewer). Its peaks are its solves': the first value's
      ! condensations, or with CHOLMOD on the interface or without
      ! condensation each value's factorization, which gives the heap back
      ! itself first (solvers/cholmod_shim.c).
      deallocate (r, acc)
      if (st%give_back) trimmed = malloc_trim(0_c_size_t)
      call link_and_support_results(model, table, delta, rigid_force, f_phys, res)
      if (allocated(req)) call add_equation_resultants(model, table, req, res)
    end associate
  end subroutine recover_results

  subroutine add_equation_resultants(model, table, req, res)
    !! *EQUATION forces on the structure join the reactions of the equilibrium
    !! check (an equation whose coefficients do not cancel per direction, a
    !! lever u_a = 2 u_b, acts partly as a support), and are kept per node
    !! (CalculiX's "forces" of a node in an equation include them).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    real(wp), intent(in) :: req(:, :)
    type(results_t), intent(inout) :: res
    integer(i8) :: p
    integer :: is, n
    type(node_flags_t), allocatable :: rot(:)
    call rotation_node_flags(model, rot)
    do is = 1, size(req, 2)
       n = count(req(:, is) /= 0.0_wp)
       allocate (res%fields%steps(is)%equation_forces(n))
       n = 0
       do p = 1, table%np
          if (req(p, is) == 0.0_wp) cycle
          call add_resultant(res%fields%steps(is)%reaction, model%subs(table%p_sub(p))%x(:, table%p_node(p)), &
               moment_dof(int(table%p_dof(p)), rot(table%p_sub(p))%on(table%p_node(p))), req(p, is))
          n = n + 1
          res%fields%steps(is)%equation_forces(n) = reaction_t(table%p_sub(p), int(table%p_node(p)), &
               table%p_dof(p), req(p, is))
       end do
    end do
  end subroutine add_equation_resultants

  subroutine store_displacements(table, u, res, error)
    !! Displacements per vertex (global axes) and which DOFs each vertex has.
    type(dof_table_t), intent(in) :: table
    real(wp), intent(in) :: u(:, :)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(inout) :: error
    integer(i8) :: v, p(NDOF_NODE)
    integer :: d, stat
    allocate (res%fields%u(NDOF_NODE*table%nvertex, size(u, 2)), res%fields%has_dof(NDOF_NODE, table%nvertex), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the displacement results', &
            int(NDOF_NODE, i8)*table%nvertex*(size(u, 2)*BYTES_REAL + BYTES_INT))
       return
    end if
    res%fields%u = 0.0_wp
    res%fields%vertex_offset = table%vertex_offset
    do v = 1, table%nvertex
       call vertex_dofs(table, v, p)
       res%fields%has_dof(:, v) = p > 0
       do d = 1, NDOF_NODE
          if (p(d) > 0) res%fields%u(NDOF_NODE*(v - 1) + d, :) = u(p(d), :)
       end do
    end do
  end subroutine store_displacements

  subroutine element_results(model, table, u, r, res, error, parts_done, wanted)
    !! Element end forces of every step and r += K_e u_e (but for the
    !! condensed substructures when parts_done: r already holds their k u).
    !! An element not wanted is skipped when its k_e u_e is not needed either:
    !! r is read only at the nodes of contact and support units (subtree sums,
    !! loop closures), so an element none of whose nodes is in a unit, or one of
    !! a condensed substructure, contributes nothing anybody reads.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    real(wp), intent(in) :: u(:, :)
    real(wp), intent(inout) :: r(:, :)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(inout) :: error
    logical, intent(in) :: parts_done
    logical, intent(in) :: wanted(:)
    logical, allocatable :: own_ku(:), in_unit(:), done(:)
    real(wp), allocatable :: ql(:, :, :), nt(:, :), f0(:, :, :, :)
    real(wp) :: f(6, 2), fg(MAX_ELEM_DOFS), ue(MAX_ELEM_DOFS), xe(3, MAX_ELEMENT_NODES)
    real(wp), allocatable :: fg2(:, :)
    integer(i8) :: pd(MAX_ELEM_DOFS), ie
    logical :: heated, skip_plates, plate
    integer :: isub, n, is, nstep, nn, i
    integer(ip) :: e
    type(error_t), allocatable :: inner

    nstep = size(u, 2)
    call allocate_element_results(model, nstep, res, ql, nt, error)
    if (allocated(error)) return
    allocate (fg2(MAX_ELEM_DOFS, nstep), own_ku(size(model%subs)))
    own_ku = .false.
    if (parts_done) own_ku = res%summary%sub_condensed
    call unit_vertices(table, in_unit)
    call body_load_fields(model, nstep, res, f0)
    ! Distributed loads in element axes, per element and step.
    call add_dload_terms(model, table, own_ku, res%fields%elem_offset, ql, nt, r)
    call solid_reactions(model, table, own_ku, u, r, error)
    call instance_plate_results(model, table, own_ku, wanted, u, res, done, error)
    if (allocated(error)) return
    heated = allocated(res%fields%thermal) .or. allocated(res%fields%thermal_nodal) .or. &
         allocated(res%fields%thermal_curvature_nodal)
    do isub = 1, size(model%subs)
       associate (s => model%subs(isub))
         ! the plate-type elements of an instance served by instance_plate_results
         ! whose k u r holds already: nothing is left to do for them without heat
         skip_plates = done(isub) .and. own_ku(isub) .and. .not. heated
         do e = 1, s%nelem
            plate = is_plate_type(s%elem_type(e))
            if (plate .and. skip_plates) cycle
            nn = ELEMENT_NODE_COUNT(s%elem_type(e))
            ie = res%fields%elem_offset(isub) + e
            if (.not. wanted(ie)) then
               if (own_ku(isub)) cycle
               if (.not. any(in_unit(table%vertex_offset(isub) + s%elem_nodes(1:nn, e)))) cycle
            end if
            associate (sec => s%sections(s%elem_section(e)))
              call element_pdofs(model, table, isub, e, pd, n)
              if (.not. plate .and. is_solid_type(s%elem_type(e))) cycle   ! solid_reactions, above
              if (plate) then
                 ! r takes K_e u_e (the distributed loads of these elements are left out of r above)
                 if (.not. done(isub)) call shell_forces(s%elem_type(e), s%x(:, s%elem_nodes(1:nn, e)), sec, &
                      model%materials(sec%material), u(pd(1:n), :), res%fields%plate(:, ie, :), fg2(1:n, :), inner, &
                      with_forces=.not. own_ku(isub), drill=element_drill(s, e))
                 if (passed_on(inner, error)) return
                 if (.not. own_ku(isub)) r(pd(1:n), :) = r(pd(1:n), :) + fg2(1:n, :)
                 ! loads: N = D (eps - eps0), the free thermal expansion's resultants taken off
                 call thermal_resultants(model, isub, e, ie, res)
                 cycle
              end if
              ! coordinates and displacements copied into xe, ue: no temporary per call
              xe(:, 1:nn) = s%x(:, s%elem_nodes(1:nn, e))
              do is = 1, nstep
                 ue(1:n) = u(pd(1:n), is)
                 call element_end_forces(s%elem_type(e), xe(:, 1:nn), sec, &
                      model%materials(sec%material), ue(1:n), ql(:, ie, is), f, inner)
                 if (passed_on(inner, error)) return
                 ! loads: N = E A (eps - alpha dT), the thermal force off the axial end forces
                 f(1, :) = f(1, :) + [nt(ie, is), -nt(ie, is)]
                 ! loads: CENTRIF, the consistent end loads of its linearly varying load
                 if (allocated(f0)) f = f - f0(:, :, ie, is)
                 res%fields%elem_force(:, :, ie, is) = f
                 if (own_ku(isub)) cycle
                 ! r += K_e u_e - f_eq (the consistent load is added back below)
                 call element_nodal_forces(s%elem_type(e), xe(:, 1:nn), sec, f, &
                      fg(1:n), inner, q_local=ql(:, ie, is))
                 if (passed_on(inner, error)) return
                 do i = 1, n
                    r(pd(i), is) = r(pd(i), is) + fg(i)
                 end do
              end do
            end associate
         end do
       end associate
    end do
  end subroutine element_results

  subroutine instance_plate_results(model, table, own_ku, wanted, u, res, done, error)
    !! The plate-type resultants of the condensed instances of one part
    !! (placed alike: same part, same elements and drilling masks, turned
    !! any way): each element's operator (shell_result_operator) is formed
    !! once, from the first instance's placement, and applied to the element
    !! displacements of all these instances and steps side by side, one
    !! product, each instance's displacements turned into the first one's
    !! axes node block by node block (the resultants are in the element's
    !! own frame, which turns with it); done(isub) marks the substructures so
    !! served. Nothing is done when error is already set.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: own_ku(:), wanted(:)
    real(wp), intent(in) :: u(:, :)
    type(results_t), intent(inout) :: res
    logical, allocatable, intent(out) :: done(:)
    type(error_t), allocatable, intent(inout) :: error
    integer, allocatable :: like(:)
    real(wp), allocatable :: turns(:, :, :)
    logical, allocatable :: turned(:), shifted(:)
    logical :: every
    integer(i8), allocatable :: shift(:)
    integer :: isub, j, k, n, n1, nstep
    integer(i8) :: pd(MAX_ELEM_DOFS), pd1(MAX_ELEM_DOFS)
    integer(ip) :: e

    allocate (done(size(model%subs)), source=.false.)
    if (allocated(error)) return
    nstep = size(u, 2)
    do isub = 1, size(model%subs)
       if (done(isub) .or. .not. own_ku(isub) .or. model%subs(isub)%part == 0) cycle
       like = pack([(j, j = 1, size(model%subs))], [(j >= isub .and. own_ku(j) .and. .not. done(j) .and. &
            placed_alike(model%subs(isub), model%subs(j)), j = 1, size(model%subs))])
       if (size(like) < 2) cycle
       done(like) = .true.
       call instance_turns(model, like, turns, turned)
       call instance_shifts(model, table, like, shift, shifted)
       associate (s => model%subs(isub), off => res%fields%elem_offset)
         do e = 1, s%nelem
            if (.not. is_plate_type(s%elem_type(e)) .or. .not. any(wanted(off(like) + e))) cycle
            block
              real(wp), allocatable :: op(:, :), ue(:, :), rs(:, :)
              type(error_t), allocatable :: inner
              call shell_result_operator(s%elem_type(e), s%x(:, s%elem_nodes(1:ELEMENT_NODE_COUNT(s%elem_type(e)), e)), &
                   s%sections(s%elem_section(e)), model%materials(s%sections(s%elem_section(e))%material), op, inner, &
                   drill=element_drill(s, e))
              if (passed_on(inner, error)) return
              allocate (ue(size(op, 2), nstep*size(like)))
              call element_pdofs(model, table, like(1), e, pd1, n1)
              every = all(pd1(1:n1) > 0)   ! no DOF missing: shifting each is exact
              do k = 1, size(like)
                 if (shifted(k) .and. every) then   ! the first instance's DOFs, shifted
                    n = n1
                    pd(1:n) = pd1(1:n) + shift(k)
                 else
                    call element_pdofs(model, table, like(k), e, pd, n)
                 end if
                 ue(:, nstep*(k - 1) + 1:nstep*k) = u(pd(1:n), :)
                 if (turned(k)) call turn_node_blocks(turns(:, :, k), n/ELEMENT_NODE_COUNT(s%elem_type(e)), &
                      ue(:, nstep*(k - 1) + 1:nstep*k))
              end do
              rs = matmul(op, ue)
              do k = 1, size(like)
                 if (wanted(off(like(k)) + e)) res%fields%plate(:, off(like(k)) + e, :) = &
                      rs(:, nstep*(k - 1) + 1:nstep*k)
              end do
            end block
         end do
       end associate
    end do
  end subroutine instance_plate_results

  subroutine instance_shifts(model, table, like, shift, shifted)
    !! shifted(k): every DOF of every node of instance like(k) is the same DOF
    !! of instance like(1) plus shift(k) (the same DOFs on every node, numbered
    !! alike: the usual case of identical instances), so that an element's
    !! DOFs are the first instance's shifted (instance_plate_results) instead
    !! of looked up again per instance.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: like(:)
    integer(i8), allocatable, intent(out) :: shift(:)
    logical, allocatable, intent(out) :: shifted(:)
    integer(i8) :: p1(NDOF_NODE), pk(NDOF_NODE)
    integer(ip) :: n
    integer :: k
    logical :: have
    allocate (shift(size(like)), source=0_i8)
    allocate (shifted(size(like)), source=.true.)   ! like(1) is itself, shift 0
    do k = 2, size(like)
       shifted(k) = model%subs(like(k))%nnode == model%subs(like(1))%nnode
       if (.not. shifted(k)) cycle
       have = .false.
       do n = 1, model%subs(like(1))%nnode
          call vertex_dofs(table, table%vertex_offset(like(1)) + n, p1)
          call vertex_dofs(table, table%vertex_offset(like(k)) + n, pk)
          shifted(k) = .not. any((p1 > 0) .neqv. (pk > 0))   ! the same DOFs at this node
          if (.not. shifted(k)) exit
          if (.not. any(p1 > 0)) cycle
          if (.not. have) shift(k) = maxval(pk) - maxval(p1)   ! the first node with DOFs sets it
          have = .true.
          shifted(k) = all(pk - p1 == shift(k) .or. p1 == 0)
          if (.not. shifted(k)) exit
       end do
    end do
  end subroutine instance_shifts

  subroutine instance_turns(model, like, turns, turned)
    !! turns(:, :, k) = R_1 R_kᵀ: instance like(k)'s global axes to those of
    !! instance like(1) (whose placement the shared operators are formed
    !! for); turned(k) false where that is the identity (nothing to turn).
    type(model_t), intent(in) :: model
    integer, intent(in) :: like(:)
    real(wp), allocatable, intent(out) :: turns(:, :, :)
    logical, allocatable, intent(out) :: turned(:)
    integer :: k
    allocate (turns(3, 3, size(like)), turned(size(like)))
    do k = 1, size(like)
       turns(:, :, k) = matmul(model%subs(like(1))%rot, transpose(model%subs(like(k))%rot))
       turned(k) = any(model%subs(like(k))%rot /= model%subs(like(1))%rot)
    end do
  end subroutine instance_turns

  pure subroutine turn_node_blocks(q, m, x)
    !! x ← diag(q) x for element displacement columns with m DOFs per node:
    !! each node's translations (and rotations, m = 6) turned by q; a plane
    !! element's in-plane pair (m = 2) by q's XY block (its turns keep Z).
    real(wp), intent(in) :: q(3, 3)
    integer, intent(in) :: m
    real(wp), intent(inout) :: x(:, :)
    real(wp) :: z(3)
    integer :: b, i, c
    b = min(m, 3)
    do c = 1, size(x, 2)
       do i = 0, size(x, 1) - b, b
          z(1:b) = x(i + 1:i + b, c)
          x(i + 1, c) = q(1, 1)*z(1) + q(1, 2)*z(2)
          x(i + 2, c) = q(2, 1)*z(1) + q(2, 2)*z(2)
          if (b < 3) cycle
          x(i + 1, c) = x(i + 1, c) + q(1, 3)*z(3)
          x(i + 2, c) = x(i + 2, c) + q(2, 3)*z(3)
          x(i + 3, c) = q(3, 1)*z(1) + q(3, 2)*z(2) + q(3, 3)*z(3)
       end do
    end do
  end subroutine turn_node_blocks

  pure logical function placed_alike(a, b)
    !! Two instances of one part whose element results share one operator:
    !! the same part, the same elements with the same drilling edge masks
    !! (they depend on the supports, not only on the part), and a relative
    !! turn R_a R_bᵀ that keeps Z where the part has plane elements (always,
    !! once the deck is checked).
    type(substructure_t), intent(in) :: a, b
    real(wp) :: q(3, 3)
    placed_alike = a%part == b%part .and. a%nelem == b%nelem
    if (.not. placed_alike) return
    placed_alike = allocated(a%elem_drill) .eqv. allocated(b%elem_drill)
    if (placed_alike .and. allocated(a%elem_drill)) placed_alike = all(a%elem_drill == b%elem_drill)
    if (.not. placed_alike .or. a%nelem == 0) return
    if (.not. any(is_plane_type(a%elem_type(1:a%nelem)))) return
    q = matmul(a%rot, transpose(b%rot))
    placed_alike = abs(q(3, 3) - 1.0_wp) <= TURN_TOL
  end function placed_alike

  subroutine solid_reactions(model, table, own_ku, u, r, error)
    !! r += K_e u_e of the solid elements (no end forces; their body loads are
    !! left out of r in add_dload_terms) but for the substructures whose k u r
    !! holds already (own_ku).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: own_ku(:)
    real(wp), intent(in) :: u(:, :)
    real(wp), intent(inout) :: r(:, :)
    type(error_t), allocatable, intent(inout) :: error
    real(wp) :: fg(MAX_ELEM_DOFS, size(u, 2))
    integer(i8) :: pd(MAX_ELEM_DOFS)
    integer :: isub, n, nn
    integer(ip) :: e
    type(error_t), allocatable :: inner
    do isub = 1, size(model%subs)
       if (own_ku(isub)) cycle
       associate (s => model%subs(isub))
         do e = 1, s%nelem
            if (.not. is_solid_type(s%elem_type(e))) cycle
            nn = ELEMENT_NODE_COUNT(s%elem_type(e))
            call element_pdofs(model, table, isub, e, pd, n)
            call solid_forces(s%elem_type(e), s%x(:, s%elem_nodes(1:nn, e)), &
                 model%materials(s%sections(s%elem_section(e))%material), u(pd(1:n), :), fg(1:n, :), inner, &
                 s%sections(s%elem_section(e))%axes)
            if (passed_on(inner, error)) return
            r(pd(1:n), :) = r(pd(1:n), :) + fg(1:n, :)
         end do
       end associate
    end do
  end subroutine solid_reactions

  subroutine body_load_fields(model, nstep, res, f0)
    !! What the element results take off for body loads (analysis/body_loads).
    type(model_t), intent(in) :: model
    integer, intent(in) :: nstep
    type(results_t), intent(inout) :: res
    real(wp), allocatable, intent(out) :: f0(:, :, :, :)
    ! loads: thermal strains of plane and shell elements, centrifugal end loads of bars and beams
    call plate_thermal_strains(model, res%fields%elem_offset, nstep, res%fields%thermal)
    call line_centrif_forces(model, res%fields%elem_offset, nstep, f0)
    ! loads: temperatures that vary over plane elements, gradients across beams
    call plane_thermal_nodal(model, res%fields%elem_offset, nstep, res%fields%thermal_nodal)
    call shell_thermal_curvature_nodal(model, res%fields%elem_offset, nstep, res%fields%thermal_curvature_nodal)
    call line_thermal_forces(model, res%fields%elem_offset, nstep, f0)
  end subroutine body_load_fields

  subroutine set_elem_offsets(model, res)
    !! res%fields%elem_offset: the elements numbered over the substructures.
    type(model_t), intent(in) :: model
    type(results_t), intent(inout) :: res
    integer :: isub
    allocate (res%fields%elem_offset(size(model%subs) + 1))
    res%fields%elem_offset(1) = 0
    do isub = 1, size(model%subs)
       res%fields%elem_offset(isub + 1) = res%fields%elem_offset(isub) + model%subs(isub)%nelem
    end do
  end subroutine set_elem_offsets

  subroutine allocate_element_results(model, nstep, res, ql, nt, error)
    !! The element results of nstep steps, zero: plate resultants; end forces,
    !! element-axis loads ql and thermal axial forces nt only where some
    !! element is not a plate type (a model of plane and shell elements has none).
    type(model_t), intent(in) :: model
    integer, intent(in) :: nstep
    type(results_t), intent(inout) :: res
    real(wp), allocatable, intent(out) :: ql(:, :, :), nt(:, :)
    type(error_t), allocatable, intent(inout) :: error
    integer(i8) :: ntot, nbar
    integer :: stat
    call set_elem_offsets(model, res)
    ntot = res%fields%elem_offset(size(model%subs) + 1)
    nbar = merge(ntot, 0_i8, any_bar(model))
    allocate (res%fields%plate(6, ntot, nstep), ql(3, nbar, nstep), stat=stat)
    if (stat == 0) allocate (nt(nbar, nstep), stat=stat)   ! loads: thermal axial force E A alpha dT
    if (stat == 0 .and. nbar > 0) allocate (res%fields%elem_force(6, 2, nbar, nstep), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the element results', (6*ntot + 16*nbar)*nstep*BYTES_REAL)
       return
    end if
    call advise_huge(res%fields%plate)
    call advise_huge(ql)
    call advise_huge(nt)
    res%fields%plate = 0.0_wp
    nt = 0.0_wp
    if (allocated(res%fields%elem_force)) then
       call advise_huge(res%fields%elem_force)
       res%fields%elem_force = 0.0_wp
    end if
  end subroutine allocate_element_results

  logical function any_bar(model)
    !! True when some element of the model is not a plate type (a line or a
    !! solid element: the ones with end forces in res%fields%elem_force).
    type(model_t), intent(in) :: model
    integer :: isub
    any_bar = .false.
    do isub = 1, size(model%subs)
       associate (s => model%subs(isub))
         if (s%nelem > 0) any_bar = any_bar .or. any(.not. is_plate_type(s%elem_type(1:s%nelem)))
       end associate
    end do
  end function any_bar

  subroutine add_dload_terms(model, table, own_ku, elem_offset, ql, nt, r)
    !! The distributed loads of line elements in element axes (ql), their
    !! thermal axial forces (nt), and r += their consistent loads (f_phys
    !! holds them; element_nodal_forces leaves them out) but for the
    !! substructures whose k u r holds already (own_ku).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: own_ku(:)
    integer(i8), intent(in) :: elem_offset(:)
    real(wp), intent(inout) :: ql(:, :, :), nt(:, :), r(:, :)
    real(wp), allocatable :: fe(:)
    real(wp) :: qloc(3)
    integer(i8) :: pd(MAX_ELEM_DOFS), ie
    integer :: is, i, n
    type(error_t), allocatable :: inner
    ql = 0.0_wp
    do is = 1, size(r, 2)
       if (.not. allocated(model%steps(is)%dloads)) cycle
       do i = 1, size(model%steps(is)%dloads)
          associate (dl => model%steps(is)%dloads(i), s => model%subs(model%steps(is)%dloads(i)%sub))
            ! Plane and shell elements: r gets K_e u_e itself (shell_forces below).
            if (is_plate_type(s%elem_type(dl%elem)) .or. is_solid_type(s%elem_type(dl%elem))) cycle
            call distributed_load(model, dl, fe, qloc, inner)
            if (allocated(inner)) deallocate (inner)
            ie = elem_offset(dl%sub) + dl%elem
            ql(:, ie, is) = ql(:, ie, is) + qloc
            if (dl%kind == DLOAD_THERMAL) nt(ie, is) = nt(ie, is) + dl%value   ! loads: thermal
            ! f_phys holds this consistent load; element_nodal_forces leaves it out.
            if (own_ku(dl%sub)) cycle
            call element_pdofs(model, table, dl%sub, dl%elem, pd, n)
            r(pd(1:n), is) = r(pd(1:n), is) + fe
          end associate
       end do
    end do
  end subroutine add_dload_terms

  subroutine thermal_resultants(model, isub, e, ie, res)
    !! Plane and shell element ie (element e of substructure isub): the free
    !! thermal expansion's resultants taken off its plate resultants.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    integer(i8), intent(in) :: ie
    type(results_t), intent(inout) :: res
    integer :: nn
    associate (s => model%subs(isub))
      associate (sec => s%sections(s%elem_section(e)))
        nn = ELEMENT_NODE_COUNT(s%elem_type(e))
        if (allocated(res%fields%thermal_curvature_nodal)) then   ! shells whose temperature varies
           call take_thermal_resultants(s%elem_type(e), &
                s%x(:, s%elem_nodes(1:nn, e)), sec, model%materials(sec%material), &
                res%fields%thermal(:, ie, :), res%fields%plate(:, ie, :), res%fields%thermal_nodal(:, ie, :), &
                res%fields%thermal_curvature_nodal(:, ie, :), element_drill(s, e))
        else if (allocated(res%fields%thermal_nodal)) then
           call take_thermal_resultants(s%elem_type(e), &
                s%x(:, s%elem_nodes(1:nn, e)), sec, model%materials(sec%material), &
                res%fields%thermal(:, ie, :), res%fields%plate(:, ie, :), res%fields%thermal_nodal(:, ie, :))
        else if (allocated(res%fields%thermal)) then
           call take_thermal_resultants(s%elem_type(e), &
                s%x(:, s%elem_nodes(1:nn, e)), sec, model%materials(sec%material), &
                res%fields%thermal(:, ie, :), res%fields%plate(:, ie, :))
        end if
      end associate
    end associate
  end subroutine thermal_resultants

  subroutine unit_vertices(table, in_unit)
    !! in_unit(v): vertex v is a side of a contact or support unit.
    type(dof_table_t), intent(in) :: table
    logical, allocatable, intent(out) :: in_unit(:)
    integer :: iu
    allocate (in_unit(table%nvertex), source=.false.)
    do iu = 1, table%nunit
       associate (un => table%units(iu))
         if (un%va /= GROUND) in_unit(un%va) = .true.
         in_unit(un%vb) = .true.
       end associate
    end do
  end subroutine unit_vertices


  subroutine unit_deltas(table, tr, q, u, delta)
    !! δ of every unit component (local axes): a column of its own, the rigid
    !! value, the expression that replaced an eliminated column, or, for a unit
    !! assembled plainly and for a released component (g = 0), qs (u_b - u_a).
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    real(wp), intent(in) :: q(:, :), u(:, :)
    real(wp), allocatable, intent(out) :: delta(:, :, :)
    integer :: iu, k, c, i
    type(form_spring_t) :: fs

    allocate (delta(3, table%nunit, size(q, 2)), source=0.0_wp)
    do iu = 1, table%nunit
       associate (un => table%units(iu))
         if (tr%unit_role(iu) == ROLE_TREE) then
            do k = 1, un%n
               if (tr%delta_column(k, iu) > 0) then
                  delta(k, iu, :) = q(tr%delta_column(k, iu), :)
               else if (un%state(k) == LINK_RIGID) then
                  delta(k, iu, :) = un%value(k)
               else
                  ! Released (g = 0): no column of its own, δ from u.
                  call unit_delta_from_u(table, un, k, u, delta(k, iu, :))
               end if
            end do
         else
            do k = 1, un%n
               call unit_delta_from_u(table, un, k, u, delta(k, iu, :))
            end do
         end if
       end associate
    end do
    ! δ columns eliminated by a loop constraint: evaluate their expression.
    do i = 1, tr%nforms()
       fs = tr%form(i)
       if (fs%unit == 0) cycle
       delta(fs%k, fs%unit, :) = fs%const
       do c = 1, size(fs%col)
          delta(fs%k, fs%unit, :) = delta(fs%k, fs%unit, :) + fs%coef(c)*q(fs%col(c), :)
       end do
    end do
  end subroutine unit_deltas

  subroutine unit_delta_from_u(table, un, k, u, delta)
    !! δ_k of unit un from the physical displacements u (every step): qs (u_b - u_a)
    !! and the arm terms of an eccentric unit.
    type(dof_table_t), intent(in) :: table
    type(unit_t), intent(in) :: un
    integer, intent(in) :: k
    real(wp), intent(in) :: u(:, :)
    real(wp), intent(out) :: delta(:)
    integer(i8) :: pt(MAX_UNIT_TERMS)
    real(wp) :: wt(MAX_UNIT_TERMS)
    integer :: i, nt
    delta = 0.0_wp
    call unit_terms(table, un, k, pt, wt, nt)
    do i = 1, nt
       delta = delta + wt(i)*u(pt(i), :)
    end do
  end subroutine unit_delta_from_u

  subroutine add_spring_forces(table, delta, r)
    !! r += internal forces of the finite contact components: qsᵀ g δ on side b,
    !! the opposite on side a.
    type(dof_table_t), intent(in) :: table
    real(wp), intent(in) :: delta(:, :, :)
    real(wp), intent(inout) :: r(:, :)
    integer :: iu, k, i, nt
    integer(i8) :: pt(MAX_UNIT_TERMS)
    real(wp) :: wt(MAX_UNIT_TERMS)
    do iu = 1, table%nunit
       associate (un => table%units(iu))
         do k = 1, un%n
            if (un%state(k) /= LINK_FINITE) cycle
            call unit_terms(table, un, k, pt, wt, nt)
            do i = 1, nt
               r(pt(i), :) = r(pt(i), :) + wt(i)*un%g(k)*delta(k, iu, :)
            end do
         end do
       end associate
    end do
  end subroutine add_spring_forces

  subroutine closer_forces(table, tr, r, rigid_force, rclose, req)
    !! Force of each eliminated loop constraint, λ = -(Σ T(p,j*) r_p) / a_j*,
    !! stored as the force on the master (local) and as nodal forces rclose;
    !! those of *EQUATION constraints also in req (allocated when there are any).
    !! Last eliminated first: the footprint T(., j*) of a column is taken when
    !! it is eliminated, so the constraints eliminated after it may still act
    !! on it (a coupled node held by a support), and r includes their forces.
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    real(wp), intent(in) :: r(:, :)
    real(wp), intent(inout) :: rigid_force(:, :, :)
    type(closing_t), intent(inout) :: rclose
    real(wp), allocatable, intent(inout) :: req(:, :)
    integer :: i, c, is, nt
    integer(i8) :: pt(MAX_UNIT_TERMS)
    real(wp) :: wt(MAX_UNIT_TERMS)
    real(wp) :: lambda, e
    type(constraint_t) :: cs
    do i = tr%nconstraints(), 1, -1
       cs = tr%constraint(i)
         if (cs%status /= CONS_ELIMINATED) cycle
         if (cs%equation > 0) then
            ! *EQUATION sum a_i u_i = 0: forces -λ a_i on its DOFs.
            associate (te => table%equations(cs%equation))
              do is = 1, size(r, 2)
                 lambda = -sum(cs%fp_c*(r(cs%fp_p, is) - closing(rclose, cs%fp_p, is)))/cs%pivot
                 if (.not. allocated(req)) allocate (req(size(r, 1), size(r, 2)), source=0.0_wp)
                 do c = 1, size(te%p)
                    call add_closing(rclose, te%p(c), is, lambda*te%a(c))
                    req(te%p(c), is) = req(te%p(c), is) - lambda*te%a(c)
                 end do
              end do
            end associate
            cycle
         end if
         associate (un => table%units(cs%unit))
           do is = 1, size(r, 2)
              e = sum(cs%fp_c*(r(cs%fp_p, is) - closing(rclose, cs%fp_p, is)))
              lambda = -e/cs%pivot
              ! Force on the master; for a support, the reaction on the node.
              if (un%kind == UNIT_SUPPORT) then
                 rigid_force(cs%k, cs%unit, is) = -lambda
              else
                 rigid_force(cs%k, cs%unit, is) = lambda
              end if
              call unit_terms(table, un, cs%k, pt, wt, nt)
              do c = 1, nt
                 call add_closing(rclose, pt(c), is, lambda*wt(c))
              end do
           end do
         end associate
    end do
  end subroutine closer_forces

  logical function passed_on(inner, error)
    !! True when an element routine failed (inner): its message is added to error.
    type(error_t), allocatable, intent(in) :: inner
    type(error_t), allocatable, intent(inout) :: error
    passed_on = allocated(inner)
    if (passed_on) call add_error_line(error, EXIT_DECK, inner%message)
  end function passed_on

  pure function closing(rclose, p, is) result(v)
    !! rclose(p, is) of the dense array it stands for.
    type(closing_t), intent(in) :: rclose
    integer(i8), intent(in) :: p(:)
    integer, intent(in) :: is
    real(wp) :: v(size(p))
    integer :: k
    do k = 1, size(p)
       v(k) = 0.0_wp
       if (rclose%slot(p(k)) > 0) v(k) = rclose%val(rclose%slot(p(k)), is)
    end do
  end function closing

  subroutine add_closing(rclose, p, is, x)
    !! rclose(p, is) = rclose(p, is) - x (a row for p when it has none yet).
    type(closing_t), intent(inout) :: rclose
    integer(i8), intent(in) :: p
    integer, intent(in) :: is
    real(wp), intent(in) :: x
    integer(i8), allocatable :: dof(:)
    real(wp), allocatable :: val(:, :)
    integer :: k
    k = rclose%slot(p)
    if (k == 0) then
       if (rclose%n == size(rclose%dof)) then
          allocate (dof(2*rclose%n), val(2*rclose%n, size(rclose%val, 2)))
          dof(1:rclose%n) = rclose%dof
          val(1:rclose%n, :) = rclose%val
          call move_alloc(dof, rclose%dof)
          call move_alloc(val, rclose%val)
       end if
       rclose%n = rclose%n + 1
       k = rclose%n
       rclose%slot(p) = k
       rclose%dof(k) = p
       rclose%val(k, :) = 0.0_wp
    end if
    rclose%val(k, is) = rclose%val(k, is) - x
  end subroutine add_closing

  subroutine tree_forces(table, forest, rt, acc, rigid_force)
    !! Subtree sums: the force each rigid tree unit exerts on its child, then
    !! turned into the force on the master (or the reaction) in local axes.
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    real(wp), intent(in) :: rt(:)
    real(wp), intent(inout) :: acc(:, 0:)
    real(wp), intent(inout) :: rigid_force(:, :)
    integer :: b, c, k, pu
    integer(i8) :: io, v, w, p, pv(NDOF_NODE)
    real(wp) :: fk
    real(wp), allocatable :: mom(:, :)

    ! Moments that eccentric (OFFSET=RIGID) translations put on their master's
    ! rotations: the translation block comes first and fills them (kept only
    ! when some unit is eccentric).
    if (table%nunit > 0) then
       if (any(table%units(1:table%nunit)%eccentric)) allocate (mom(3, 0:table%nvertex), source=0.0_wp)
    end if
    do b = 1, NBLOCK
       ! Only the vertices with a parent and their parents are read or
       ! written below: seeded with r (and the moments), the others left.
       do io = 1, forest%norder(b)
          call seed(forest%order(b, io))
          call seed(parent(io))
       end do
       do io = forest%norder(b), 1, -1
          v = forest%order(b, io)
          pu = forest%order_unit(b, io)
          associate (un => table%units(pu))
            w = parent(io)
            acc(:, w) = acc(:, w) + acc(:, v)
            if (un%eccentric) call arm_moment(un, acc(:, v), forest%child_is_a(pu), mom(:, un%va))
            do k = 1, un%n
               if (un%state(k) /= LINK_RIGID) cycle
               fk = 0.0_wp
               do c = 1, un%n
                  fk = fk + un%qs(k, c)*acc(un%comp(c), v)
               end do
               ! fk: local force on the child. Store the force on side a
               ! (master, or for supports the reaction on the node).
               if (un%kind == UNIT_SUPPORT) then
                  rigid_force(k, pu) = fk
               else if (forest%child_is_a(pu)) then
                  rigid_force(k, pu) = fk
               else
                  rigid_force(k, pu) = -fk
               end if
            end do
          end associate
       end do
    end do
  contains
    integer(i8) function parent(io)
      !! The parent of the io-th vertex of block b's order.
      integer(i8), intent(in) :: io
      associate (un => table%units(forest%order_unit(b, io)))
        parent = merge(un%vb, un%va, forest%child_is_a(forest%order_unit(b, io)))
      end associate
    end function parent
    subroutine seed(x)
      !! acc(:, x): r at vertex x's DOFs of block b (0 where it has none),
      !! plus the moments of eccentric translations in the rotation block.
      integer(i8), intent(in) :: x
      acc(:, x) = 0.0_wp
      if (x /= GROUND) then
         call vertex_dofs(table, x, pv)
         do c = 1, 3
            p = pv(block_dof(b, c))
            if (p > 0) acc(c, x) = rt(p)
         end do
      end if
      if (b == 2 .and. allocated(mom)) acc(:, x) = acc(:, x) + mom(:, x)
    end subroutine seed
  end subroutine tree_forces

  pure subroutine arm_moment(un, f, child_is_master, m)
    !! Moment the subtree force f (translations) of an eccentric tree unit puts on
    !! the master's rotations: u_child = u_parent ± θ_master × r gives ±(r × f)
    !! over the unit's components (+ when the child is the slave).
    type(unit_t), intent(in) :: un
    real(wp), intent(in) :: f(3)
    logical, intent(in) :: child_is_master
    real(wp), intent(inout) :: m(3)
    real(wp) :: a(3, 3), sgn
    integer :: c, d
    a = arm_matrix(un%arm)
    sgn = merge(-1.0_wp, 1.0_wp, child_is_master)
    do d = 1, 3
       do c = 1, un%n
          m(d) = m(d) + sgn*a(un%comp(c), d)*f(un%comp(c))
       end do
    end do
  end subroutine arm_moment

  subroutine link_and_support_results(model, table, delta, rigid_force, f_phys, res)
    !! Contact Δ and F per link (local axes), reactions, resultants.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    real(wp), intent(in) :: delta(:, :, :), rigid_force(:, :, :), f_phys(:, :)
    type(results_t), intent(inout) :: res
    integer :: nstep, is, iu, k, ld, nr, isub, c
    real(wp) :: force
    type(reaction_t), allocatable :: reac(:)
    integer(i8) :: p
    type(node_flags_t), allocatable :: ring(:), rot(:)

    nstep = size(delta, 3)
    allocate (ring(size(model%subs)))
    do isub = 1, size(model%subs)
       ring(isub)%on = ring_nodes(model%subs(isub))
    end do
    call rotation_node_flags(model, rot)
    allocate (res%fields%link_used(NDOF_NODE, size(model%links)), source=.false.)
    do iu = 1, table%nunit
       associate (un => table%units(iu))
         if (un%kind /= UNIT_LINK) cycle
         do k = 1, un%n
            ! Every DOF the contact names, released ones (g = 0) too: their true δ, force 0.
            ld = block_dof(un%block, un%lcomp(k))
            if (model%links(un%source)%state(ld) /= LINK_NONE) res%fields%link_used(ld, un%source) = .true.
         end do
       end associate
    end do
    do is = 1, nstep
       allocate (res%fields%steps(is)%link_delta(NDOF_NODE, size(model%links)), source=0.0_wp)
       allocate (res%fields%steps(is)%link_force(NDOF_NODE, size(model%links)), source=0.0_wp)
       allocate (reac(3*table%nunit + 1))
       nr = 0
       do iu = 1, table%nunit
          associate (un => table%units(iu))
            do k = 1, un%n
               select case (un%state(k))
               case (LINK_FINITE)
                  force = un%g(k)*delta(k, iu, is)
               case (LINK_RIGID)
                  force = rigid_force(k, iu, is)
               case default
                  force = 0.0_wp
               end select
               if (un%kind == UNIT_LINK) then
                  ld = block_dof(un%block, un%lcomp(k))
                  res%fields%steps(is)%link_delta(ld, un%source) = delta(k, iu, is)
                  res%fields%steps(is)%link_force(ld, un%source) = force
               else if (un%state(k) /= LINK_NONE) then
                  ! Reaction: the force the support exerts on the structure.
                  if (un%state(k) == LINK_FINITE) force = -force
                  nr = nr + 1
                  reac(nr)%sub = model%supports(un%src(k))%sub
                  reac(nr)%node = model%supports(un%src(k))%node
                  reac(nr)%dof = block_dof(un%block, un%lcomp(k))   ! nodal system (*TRANSFORM) if any
                  reac(nr)%force = force
               end if
            end do
          end associate
       end do
       ! Support units are built in (substructure, node, DOF) order.
       res%fields%steps(is)%reactions = reac(1:nr)
       deallocate (reac)

       ! Resultants about the origin.
       res%fields%steps(is)%applied = 0.0_wp
       do p = 1, table%np
          if (f_phys(p, is) == 0.0_wp) cycle
          isub = table%p_sub(p)
          call add_resultant(res%fields%steps(is)%applied, model%subs(isub)%x(:, table%p_node(p)), &
               moment_dof(int(table%p_dof(p)), rot(isub)%on(table%p_node(p))), f_phys(p, is), ring(isub)%on(table%p_node(p)))
       end do
       res%fields%steps(is)%reaction = 0.0_wp
       nr = 0
       do iu = 1, table%nunit
          associate (un => table%units(iu))
            if (un%kind == UNIT_LINK) cycle
            do k = 1, un%n
               if (un%state(k) == LINK_NONE) cycle
               nr = nr + 1
               associate (rc => res%fields%steps(is)%reactions(nr))
                 ! Along the support's axis: qsᵀ e_k (the identity without *TRANSFORM).
                 do c = 1, un%n
                    if (un%qs(k, c) == 0.0_wp) cycle
                    call add_resultant(res%fields%steps(is)%reaction, model%subs(rc%sub)%x(:, rc%node), &
                         moment_dof(block_dof(un%block, un%comp(c)), rot(rc%sub)%on(rc%node)), un%qs(k, c)*rc%force, &
                         ring(rc%sub)%on(rc%node))
                 end do
               end associate
            end do
          end associate
       end do
    end do
  end subroutine link_and_support_results

  subroutine rotation_node_flags(model, rot)
    !! rot(isub)%on(node): the node is a *RIGID BODY's ROT NODE (its DOFs 1-3 the body's rotations).
    type(model_t), intent(in) :: model
    type(node_flags_t), allocatable, intent(out) :: rot(:)
    integer :: isub, k
    allocate (rot(size(model%subs)))
    do isub = 1, size(model%subs)
       allocate (rot(isub)%on(model%subs(isub)%nnode), source=.false.)
    end do
    if (.not. allocated(model%rot_node)) return
    do k = 1, size(model%rot_node)
       rot(model%rot_sub(k))%on(model%rot_node(k)) = .true.
    end do
  end subroutine rotation_node_flags

  pure integer function moment_dof(dof, rot_node)
    !! The resultant row of a nodal force on dof: on a *RIGID BODY's ROT NODE
    !! (rot_node), whose DOFs 1-3 are the body's rotations, the moment 4-6.
    integer, intent(in) :: dof
    logical, intent(in) :: rot_node
    moment_dof = dof
    if (rot_node .and. dof <= 3) moment_dof = dof + 3
  end function moment_dof

  pure subroutine add_resultant(total, x, dof, value, ring)
    !! Add a force (dof 1-3) or moment (dof 4-6) at x to a resultant about the origin.
    !! ring (present and true): a node of an axisymmetric element, whose force is a ring around the y
    !! axis (the whole circumference): its resultant is its axial force alone.
    real(wp), intent(inout) :: total(6)
    real(wp), intent(in) :: x(3)
    integer, intent(in) :: dof
    real(wp), intent(in) :: value
    logical, intent(in), optional :: ring
    real(wp) :: f(3)
    logical :: on_ring
    on_ring = .false.
    if (present(ring)) on_ring = ring
    if (on_ring) then
       if (dof == 2) total(2) = total(2) + value
    else if (dof <= 3) then
       f = 0.0_wp
       f(dof) = value
       total(dof) = total(dof) + value
       total(4) = total(4) + x(2)*f(3) - x(3)*f(2)
       total(5) = total(5) + x(3)*f(1) - x(1)*f(3)
       total(6) = total(6) + x(1)*f(2) - x(2)*f(1)
    else
       total(dof) = total(dof) + value
    end if
  end subroutine add_resultant

end module superjoin_analysis_recover
