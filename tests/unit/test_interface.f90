program test_interface
  !! The interface layer below the deck level: the forest, the Δu transform's
  !! operations and a condensation, on a small model with every kind of unit
  !! (a rigid and a compliant oriented contact, an elastic and a prescribed
  !! support, a loop closed by a RIGID contact):
  !! - forest: one tree edge per vertex that has a parent, the stiffest units in
  !!   the trees, every tree unit's child is one of its two vertices;
  !! - expand and reduce are adjoint: fᵀ(T q) = (Tᵀ f)ᵀ q;
  !! - expand of a δ column: the slave moves by qsᵀ e_k against its master;
  !! - assembly (scatter of every element, superelement and spring) equals the
  !!   explicit Tᵀ K_phys T + diag(g) formed from expand of unit vectors;
!! - two terms of K_red (each substructure in one, the terms of no
!!   substructure in one only: plan%shared) sum to K_red and f_u0;
  !! - a condensation's K* equals k_bb − k_bi k_ii⁻¹ k_ib formed densely;
  !! - recovery: contact δ = Q (u_slave − u_master), finite force g δ, and the
  !!   recovered forces of the rigid contacts and supports hold part B in
  !!   equilibrium (forces and moments) with its load, on every backend.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, LINK_RIGID
  use superjoin_deck_reader, only: read_deck_string
  use superjoin_assembly_dofs, only: dof_table_t, build_dof_table, GROUND, block_dof
  use superjoin_assembly_forest, only: forest_t, build_forest, unit_weight
  use superjoin_assembly_transform, only: transform_t, build_transform, COL_DELTA, ROLE_TREE
  use superjoin_assembly_assemble, only: assemble_stiffness, assembly_plan_t, element_matrix, element_pdofs, &
       unit_pdofs, unit_plain_stiffness
  use superjoin_substructure_local_system, only: boundary_dofs
  use superjoin_substructure_cache, only: part_cache_t, part_view_t, acquire_view, release_cache, k_holder
  use superjoin_solvers, only: sparse_sym_t
  use superjoin_testing, only: check, check_close, finish
  use superjoin_analysis, only: solve_model
  use superjoin_model_results, only: results_t, run_options_t
  use verification_support, only: disp, reaction
  use test_lapack, only: dgesv
  implicit none (type, external)

  character(*), parameter :: NL = new_line('a')
  character(*), parameter :: DECK = &
       '*MATERIAL, NAME=S'//NL//'*ELASTIC'//NL//'2.0e11, 0.3'//NL// &
       '*SUBSTRUCTURE, NAME=A'//NL//'*NODE'//NL//'1, 0, 0, 0'//NL//'2, 1, 0, 0'//NL//'3, 2, 0, 0'//NL// &
       '4, 3, 0.5, 0'//NL// &
       '*ELEMENT, TYPE=B33, ELSET=E'//NL//'1, 1, 2'//NL//'2, 2, 3'//NL//'3, 3, 4'//NL// &
       '*BEAM SECTION, ELSET=E, MATERIAL=S'//NL//'1e-2, 2e-5, 3e-5, 1e-5'//NL//'*END SUBSTRUCTURE'//NL// &
       '*SUBSTRUCTURE, NAME=B'//NL//'*NODE'//NL//'1, 3, 0.5, 0'//NL//'2, 4, 0.5, 0'//NL//'3, 5, 1, 0.5'//NL// &
       '*ELEMENT, TYPE=B33, ELSET=E'//NL//'1, 1, 2'//NL//'2, 2, 3'//NL// &
       '*BEAM SECTION, ELSET=E, MATERIAL=S'//NL//'1e-2, 2e-5, 3e-5, 1e-5'//NL//'*END SUBSTRUCTURE'//NL// &
       '*ORIENTATION, NAME=O'//NL//'1, 1, 0, -1, 1, 0.5'//NL// &
       '*CONTACT, NAME=J, MASTER=A, SLAVE=B, ORIENTATION=O'//NL//'4, 1, 1, 3, RIGID'//NL// &
       '4, 1, 4, 6, 3.0e5'//NL// &
       '*CONTACT, NAME=L, MASTER=A, SLAVE=B'//NL//'2, 3, 1, 6, RIGID'//NL// &
       '*SUPPORT'//NL//'A.1, 1, 6'//NL//'B.2, 3, 3, 5.0e6'//NL// &
       '*BOUNDARY'//NL//'A.3, 2, 2, 1.0e-3'//NL// &
       '*CLOAD'//NL//'B.3, 2, -1000.0'//NL
  type(model_t) :: model
  type(error_t), allocatable :: error
  type(dof_table_t) :: table
  type(forest_t) :: forest
  type(transform_t) :: tr

  call read_deck_string(DECK, 'interface.deck', model, error)
  call check(.not. allocated(error), 'the deck reads')
  if (allocated(error)) call finish()
  call build_dof_table(model, table, error)
  call check(.not. allocated(error), 'DOF table')
  call build_forest(table, .true., forest, error)
  call check(.not. allocated(error), 'forest')
  call build_transform(model, table, forest, tr, error)
  call check(.not. allocated(error), 'transform')
  if (allocated(error)) call finish()

  call forest_checks()
  call adjoint_check()
  call delta_column_check()
  call assembly_check()
  call shared_terms_check()
  call condensation_check()
  call recovery_check('lapack')
  call recovery_check('cholmod')
  call recovery_check('umfpack')
  call recovery_check('cholmod', condensed=.true.)
  call finish()

contains

  subroutine forest_checks()
    integer :: iu, b, ntree, nwith
    integer(i8) :: v
    real(wp) :: wmin_tree, wmax_loop
    ntree = count(forest%tree)
    nwith = 0
    do b = 1, 2
       do v = 1, table%nvertex
          if (forest%parent_unit(b, v) > 0) nwith = nwith + 1
       end do
    end do
    call check(ntree == nwith, 'forest: one tree unit per vertex with a parent')
    do iu = 1, table%nunit
       if (.not. forest%tree(iu)) cycle
       associate (u => table%units(iu))
         if (forest%child_is_a(iu)) then
            call check(u%va /= GROUND .and. forest%parent_unit(u%block, u%va) == iu, 'forest: child a has the unit above it')
         else
            call check(forest%parent_unit(u%block, u%vb) == iu, 'forest: child b has the unit above it')
         end if
       end associate
    end do
    ! The RIGID link L closes a loop with J through the beams: the loop's plain
    ! unit is never stiffer than the tree units of its block.
    wmin_tree = huge(1.0_wp)
    wmax_loop = 0.0_wp
    do iu = 1, table%nunit
       if (table%units(iu)%kind /= 1) cycle
       if (forest%tree(iu)) then
          wmin_tree = min(wmin_tree, unit_weight(table%units(iu)))
       else
          wmax_loop = max(wmax_loop, unit_weight(table%units(iu)))
       end if
    end do
    call check(wmax_loop <= wmin_tree, 'forest: the units left out are not stiffer than the tree units')
  end subroutine forest_checks

  subroutine adjoint_check()
    real(wp), allocatable :: q(:, :), u(:, :), f(:, :), fr(:, :)
    integer(i8) :: j, p
    allocate (q(tr%ncol(), 1), u(table%np, 1), f(table%np, 1), fr(tr%ncol(), 1))
    do j = 1, tr%ncol()
       q(j, 1) = sin(1.3_wp*j) + 0.1_wp
    end do
    do p = 1, table%np
       f(p, 1) = cos(0.7_wp*p) - 0.2_wp
    end do
    call tr%expand(q, u, linear=.true.)
    call tr%reduce(f, fr)
    call check_close(sum(f*u), sum(fr*q), 1.0e-13_wp*sum(abs(f))*maxval(abs(u)), 'expand and reduce are adjoint')
    ! with u0: expand = linear part + u0
    call tr%expand(q, f)
    call check(maxval(abs(f(:, 1) - u(:, 1) - tr%prescribed([(p, p=1, table%np)]))) <= 1.0e-14_wp, &
         'expand = T q + u0')
    call check(any(tr%prescribed([(p, p=1, table%np)]) /= 0.0_wp), 'the prescribed value is in u0')
  end subroutine adjoint_check

  subroutine delta_column_check()
    !! For each δ column of a tree link: the slave (child) side moves by
    !! ±qs(k, c) on component c, the master side not at all.
    real(wp), allocatable :: q(:, :), u(:, :)
    integer(i8) :: j, pa, pb
    integer :: iu, k, c, nchecked
    real(wp) :: sgn
    allocate (q(tr%ncol(), 1), u(table%np, 1))
    nchecked = 0
    do j = 1, tr%ncol()
       if (tr%column_kind(j) /= COL_DELTA) cycle
       iu = int(tr%column_ref(j))
       if (tr%unit_role(iu) /= ROLE_TREE .or. table%units(iu)%va == GROUND) cycle
       k = tr%column_comp(j)
       q = 0.0_wp
       q(j, 1) = 1.0_wp
       call tr%expand(q, u, linear=.true.)
       associate (un => table%units(iu))
         sgn = merge(-1.0_wp, 1.0_wp, forest%child_is_a(iu))
         do c = 1, un%n
            pa = table%dof(block_dof(un%block, un%comp(c)), un%va)
            pb = table%dof(block_dof(un%block, un%comp(c)), un%vb)
            if (forest%child_is_a(iu)) then
               call check_close(u(pa, 1), sgn*un%qs(k, c), 1.0e-15_wp, 'delta column moves the child (a)')
               call check_close(u(pb, 1), 0.0_wp, 1.0e-15_wp, 'delta column leaves the parent (b)')
            else
               call check_close(u(pb, 1) - u(pa, 1), un%qs(k, c), 1.0e-15_wp, 'u_b - u_a = qsT e_k')
            end if
         end do
       end associate
       nchecked = nchecked + 1
    end do
    call check(nchecked >= 3, 'the compliant oriented contact has its delta columns')
  end subroutine delta_column_check

  subroutine assembly_check()
    !! K_red from assemble_stiffness against Tᵀ K_phys T + diag(g) formed
    !! explicitly (T from expand of unit vectors, K_phys from the element and
    !! plain unit matrices), and f_u0 against −Tᵀ K_phys u0.
    type(assembly_plan_t) :: plan
    type(sparse_sym_t) :: k
    real(wp), allocatable :: f_u0(:), t(:, :), kphys(:, :), kred(:, :), e(:, :), u0(:), ke(:, :), want(:, :)
    real(wp) :: kmax
    integer(i8) :: j, pd(24), n8
    integer :: isub, n, a, b, iu
    integer(i8) :: ncol, np, pos
    ncol = tr%ncol()
    np = table%np
    allocate (plan%skip_sub(size(model%subs)), source=.false.)
    allocate (plan%supers(0))
    call assemble_stiffness(model, table, tr, plan, k, f_u0, error)
    call check(.not. allocated(error), 'assembly')
    allocate (t(np, ncol), e(ncol, 1), kphys(np, np), kred(ncol, ncol))
    do j = 1, ncol
       e = 0.0_wp
       e(j, 1) = 1.0_wp
       call tr%expand(e, t(:, j:j), linear=.true.)
    end do
    kphys = 0.0_wp
    do isub = 1, size(model%subs)
       do n8 = 1, model%subs(isub)%nelem
          call element_matrix(model, isub, int(n8, ip), ke, error)
          call element_pdofs(model, table, isub, int(n8, ip), pd, n)
          do b = 1, n
             do a = 1, n
                kphys(pd(a), pd(b)) = kphys(pd(a), pd(b)) + ke(a, b)
             end do
          end do
       end do
    end do
    if (allocated(ke)) deallocate (ke)
    allocate (ke(6, 6))
    do iu = 1, table%nunit
       if (tr%unit_role(iu) == ROLE_TREE) cycle
       call unit_pdofs(table, iu, pd, n)
       call unit_plain_stiffness(table, iu, ke, n)
       do b = 1, n
          do a = 1, n
             kphys(pd(a), pd(b)) = kphys(pd(a), pd(b)) + ke(a, b)
          end do
       end do
    end do
    want = matmul(transpose(t), matmul(kphys, t))
    do j = 1, ncol
       want(j, j) = want(j, j) + tr%column_g(j)
    end do
    call check(tr%nforms() == 0, 'no loop springs in this model (the loop is RIGID on RIGID)')
    kred = 0.0_wp
    do j = 1, ncol
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          kred(k%rowind(pos), j) = k%val(pos)
          kred(j, k%rowind(pos)) = k%val(pos)
       end do
    end do
    kmax = maxval(abs(want))
    call check(maxval(abs(kred - want)) <= 1.0e-13_wp*kmax, 'scatter = T^T K_phys T + diag(g)')
    u0 = tr%prescribed([(j, j=1, np)])
    call check(maxval(abs(f_u0 + matmul(transpose(t), matmul(kphys, u0)))) <= 1.0e-13_wp*kmax*maxval(abs(u0)), &
         'f_u0 = -T^T K_phys u0')
  end subroutine assembly_check

  subroutine shared_terms_check()
    !! The terms of two processes (substructure A with the shared terms, B
    !! without them: plan%shared) sum to the whole K_red and f_u0.
    type(assembly_plan_t) :: plan
    type(sparse_sym_t) :: k
    real(wp), allocatable :: f_u0(:), f_sum(:), f_all(:), whole(:, :), summed(:, :)
    integer :: iterm
    integer(i8) :: ncol
    ncol = tr%ncol()
    allocate (whole(ncol, ncol), summed(ncol, ncol), f_sum(ncol), source=0.0_wp)
    allocate (plan%skip_sub(size(model%subs)), source=.false.)
    allocate (plan%supers(0))
    call assemble_stiffness(model, table, tr, plan, k, f_all, error)
    call check(.not. allocated(error), 'whole assembly')
    call densify(k, whole)
    call check(size(model%subs) == 2, 'two substructures')
    do iterm = 1, 2
       plan%skip_sub = [iterm /= 1, iterm /= 2]
       plan%shared = iterm == 1
       call assemble_stiffness(model, table, tr, plan, k, f_u0, error)
       call check(.not. allocated(error), 'assembly of a term')
       call densify(k, summed)
       f_sum = f_sum + f_u0
    end do
    call check(maxval(abs(summed - whole)) <= 1.0e-13_wp*maxval(abs(whole)), 'terms sum to K_red')
    call check(maxval(abs(f_sum - f_all)) <= 1.0e-13_wp*maxval(abs(f_all)), 'terms sum to f_u0')
    call check(maxval(abs(f_all)) > 0.0_wp, 'f_u0 is not zero (a prescribed value)')
  end subroutine shared_terms_check

  subroutine densify(k, dense)
    !! dense += the symmetric matrix whose upper triangle is k.
    type(sparse_sym_t), intent(in) :: k
    real(wp), intent(inout) :: dense(:, :)
    integer(i8) :: j, pos
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          dense(k%rowind(pos), j) = dense(k%rowind(pos), j) + k%val(pos)
          if (k%rowind(pos) /= j) dense(j, k%rowind(pos)) = dense(j, k%rowind(pos)) + k%val(pos)
       end do
    end do
  end subroutine densify

  subroutine condensation_check()
    !! K* of substructure B (its boundary: the contact and support DOFs)
    !! against k_bb − k_bi k_ii⁻¹ k_ib formed densely from its element matrices.
    type(part_cache_t) :: cache
    type(part_view_t) :: view
    logical, allocatable :: bnd(:)
    real(wp), allocatable :: kl(:, :), ke(:, :), kii(:, :), kib(:, :), kbb(:, :), x(:, :), want(:, :)
    integer(i8), allocatable :: loc(:)
    integer(i8) :: pd(24), l, ni, nb, nl
    integer :: n, a, b, info, isub
    integer(ip) :: e
    integer, allocatable :: ipiv(:)
    isub = 2
    call boundary_dofs(table, bnd)
    call acquire_view(cache, model, table, isub, bnd, 'lapack', view, error)
    call check(.not. allocated(error), 'condensation of B')
    if (allocated(error)) return
    ni = view%ni
    nb = view%nb
    nl = ni + nb
    allocate (kl(nl, nl), source=0.0_wp)
    allocate (loc(table%np), source=0_i8)
    do l = 1, nl
       loc(view%pdof(l)) = l
    end do
    do e = 1, model%subs(isub)%nelem
       call element_matrix(model, isub, e, ke, error)
       call element_pdofs(model, table, isub, e, pd, n)
       do b = 1, n
          do a = 1, n
             kl(loc(pd(a)), loc(pd(b))) = kl(loc(pd(a)), loc(pd(b))) + ke(a, b)
          end do
       end do
    end do
    kii = kl(1:ni, 1:ni)
    kib = kl(1:ni, ni + 1:nl)
    kbb = kl(ni + 1:nl, ni + 1:nl)
    x = kib
    allocate (ipiv(ni))
    call dgesv(int(ni), int(nb), kii, int(ni), ipiv, x, int(ni), info)
    call check(info == 0, 'dense k_ii solve')
    want = kbb - matmul(transpose(kib), x)
    call check(ni > 0 .and. nb > 0, 'B has interior and boundary DOFs')
    call check(maxval(abs(view%se%k - want)) <= 1.0e-10_wp*maxval(abs(kbb)), 'K* = k_bb - k_bi k_ii^-1 k_ib')
    call check(all(view%se%pdof == view%pdof(ni + 1:)), 'K* on the physical boundary DOFs')
    call shared_view_check(cache, bnd, isub, view)
    call release_cache(cache)
  end subroutine condensation_check

  subroutine shared_view_check(cache, bnd, isub, first)
    !! A second view of the same condensation, given the first as an earlier
    !! view of its array, holds no copy of K*: it names the first (k_of),
    !! which k_holder resolves; without before it holds its own equal copy.
    type(part_cache_t), intent(inout) :: cache
    logical, intent(in) :: bnd(:)
    integer, intent(in) :: isub
    type(part_view_t), intent(in) :: first
    type(part_view_t) :: views(2), own
    views(1) = first
    call acquire_view(cache, model, table, isub, bnd, 'lapack', views(2), error, before=views(1:1))
    call check(.not. allocated(error), 'a second view of B')
    if (allocated(error)) return
    call check(views(2)%entry == first%entry .and. views(2)%k_of == 1, 'the second view shares the first''s K*')
    call check(.not. allocated(views(2)%se%k), 'the second view holds no copy of K*')
    call check(k_holder(views, 2) == 1 .and. k_holder(views, 1) == 1, 'k_holder resolves a shared K*')
    call check(all(views(2)%se%pdof == first%se%pdof), 'the shared view keeps its own boundary DOFs')
    call acquire_view(cache, model, table, isub, bnd, 'lapack', own, error)
    call check(.not. allocated(error) .and. own%k_of == 0 .and. allocated(own%se%k), &
         'without before a view holds its own K*')
    if (allocated(own%se%k)) call check(all(own%se%k == first%se%k), 'its own K* is the same')
  end subroutine shared_view_check

  subroutine recovery_check(solver, condensed)
    !! Contact J (oriented, DOFs 1-3 RIGID, 4-6 g) and L (RIGID, global axes)
    !! hold part B with the elastic support at B.2 against the load at B.3.
    character(*), intent(in) :: solver
    logical, intent(in), optional :: condensed
    type(model_t) :: m
    type(results_t) :: res
    type(run_options_t) :: opts
    real(wp) :: q(3, 3), du(6), dl(6), fglob(6), ftot(3), mtot(3), x(3), fl(3), ml(3), scale
    integer :: il, k, d
    character(:), allocatable :: tag
    tag = solver
    if (present(condensed)) tag = tag//' condensed'
    call read_deck_string(DECK, 'interface.deck', m, error)
    opts%quiet = .true.
    opts%solver = solver
    if (present(condensed)) opts%condense = 1
    call solve_model(m, opts, res, error)
    call check(.not. allocated(error), 'solve '//tag)
    if (allocated(error)) then
       deallocate (error)
       return
    end if
    q = m%orientations(1)%q
    ftot = 0.0_wp
    mtot = 0.0_wp
    do il = 1, size(m%links)
       associate (lk => m%links(il), ct => m%contacts(m%links(il)%contact))
         do d = 1, 6
            du(d) = disp(m, res, 'B', int(m%subs(ct%slave_sub)%node_id(lk%slave_node)), d, 1) - &
                 disp(m, res, 'A', int(m%subs(ct%master_sub)%node_id(lk%master_node)), d, 1)
         end do
         if (ct%orientation > 0) then
            dl(1:3) = matmul(q, du(1:3))
            dl(4:6) = matmul(q, du(4:6))
         else
            dl = du
         end if
         scale = maxval(abs(du)) + tiny(1.0_wp)
         do k = 1, 6
            call check_close(res%fields%steps(1)%link_delta(k, il), dl(k), 1.0e-12_wp*scale, &
                 'delta = Q (u_s - u_m), '//ct%name//', '//tag)
            if (lk%state(k) == LINK_RIGID) then
               call check_close(res%fields%steps(1)%link_delta(k, il), 0.0_wp, 1.0e-12_wp*scale, 'rigid delta 0, '//tag)
            else
               call check_close(res%fields%steps(1)%link_force(k, il), lk%g(k)*dl(k), &
                    1.0e-12_wp*abs(lk%g(k)*dl(k)) + 1.0e-12_wp, 'force = g delta, '//tag)
            end if
         end do
         ! force of the contact on the slave node = minus the force on the master, global axes
         if (ct%orientation > 0) then
            fglob(1:3) = -matmul(transpose(q), res%fields%steps(1)%link_force(1:3, il))
            fglob(4:6) = -matmul(transpose(q), res%fields%steps(1)%link_force(4:6, il))
         else
            fglob = -res%fields%steps(1)%link_force(:, il)
         end if
         x = m%subs(ct%slave_sub)%x(:, lk%slave_node)
         ftot = ftot + fglob(1:3)
         mtot = mtot + fglob(4:6) + cross3(x, fglob(1:3))
       end associate
    end do
    ! the load at B.3 and the elastic support at B.2
    fl = [0.0_wp, -1000.0_wp, 0.0_wp]
    x = m%subs(2)%x(:, 3)
    ftot = ftot + fl
    mtot = mtot + cross3(x, fl)
    fl = [0.0_wp, 0.0_wp, reaction(m, res, 'B', 2, 3, 1)]
    call check(abs(fl(3)) > 0.0_wp, 'the elastic support carries load, '//tag)
    x = m%subs(2)%x(:, 2)
    ftot = ftot + fl
    mtot = mtot + cross3(x, fl)
    ml = 0.0_wp
    call check(maxval(abs(ftot)) <= 1.0e-9_wp*1000.0_wp, 'part B: forces balance, '//tag)
    call check(maxval(abs(mtot + ml)) <= 1.0e-9_wp*1000.0_wp*5.0_wp, 'part B: moments balance, '//tag)
  end subroutine recovery_check

  pure function cross3(a, b) result(c)
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross3
end program test_interface
