program test_epsilon
  !! EPSILON, the energy error of the listing, recomputed independently of the
  !! transform: EPSILON = uᵀ(K u - f) / uᵀf with K the physical stiffness
  !! (element matrices, contact and elastic support springs), u the returned
  !! displacements and f the applied loads, summed in quadruple precision.
  !! For a model without prescribed values this equals qᵀ(K_red q - f_red) /
  !! qᵀf_red of the reduced system, because u = T q, K_red = Tᵀ K T and
  !! f_red = Tᵀ f (rigid supports hold u = 0, so their rows do not count).
  !!
  !! The printed value is computed in double precision from the reduced system,
  !! so it agrees with the recomputation within the rounding error of evaluating
  !! K q - f: bound = ε (Σ|u|ᵀ|K||u| + |f|ᵀ|u|) / |uᵀf| (measured: at most 0.04
  !! of it). Where refinement is rejected the residual IS at that rounding level
  !! (a backward-stable solve), so the EPSILON of the discarded iterate is
  !! within the same bound: this test cannot tell the two apart (measured:
  !! 0.08 of the bound for the discarded iterate), see doc/testing.md. It does
  !! catch a wrong formula, sign, scaling or vector.
  !!
  !! The decks are a two-part cantilever whose joint is 1 to 1e-9 times the
  !! beam's stiffness (down to near-mechanisms), solved with every backend; in
  !! the softer ones the residual stays above the refinement target, so
  !! iterative refinement is tried and rejected.
  use, intrinsic :: iso_fortran_env, only: real128
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, LINK_FINITE, ELEMENT_NODE_COUNT
  use superjoin_model_results, only: results_t
  use superjoin_elements, only: element_stiffness, element_node_dofs
  use superjoin_error, only: error_t
  use superjoin_testing, only: check, check_close, finish
  use verification_support, only: solve_text
  implicit none (type, external)
  integer, parameter :: qp = real128
  real(wp), parameter :: JOINTS(4) = [1.0_wp, 1.0e-3_wp, 1.0e-6_wp, 1.0e-9_wp]
  character(len=8), parameter :: SOLVERS(3) = [character(len=8) :: 'lapack', 'cholmod', 'umfpack']
  type(model_t) :: model
  type(results_t) :: res
  integer :: ij, is, st, rejected, compared
  real(wp) :: eps_phys, bound, worst
  character(len=120) :: what
  character(len=*), parameter :: NL = new_line('a')

  rejected = 0
  compared = 0
  worst = 0.0_wp
  do ij = 1, size(JOINTS)
     do is = 1, size(SOLVERS)
        call solve_text(cantilever(JOINTS(ij)), model, res, trim(SOLVERS(is)))
        do st = 1, size(res%fields%steps)
           eps_phys = physical_epsilon(model, res, st, bound)
           worst = max(worst, abs(res%fields%steps(st)%epsilon - eps_phys)/bound)
           write (what, '(a,es8.1,a,i0)') 'EPSILON, joint ', JOINTS(ij), ' '//trim(SOLVERS(is))//' step ', st
           if (res%fields%steps(st)%refine_tried > res%fields%steps(st)%refinements) rejected = rejected + 1
           if (abs(eps_phys) > 1.0e-12_wp) compared = compared + 1
           call check_close(res%fields%steps(st)%epsilon, eps_phys, bound, trim(what))
        end do
     end do
  end do
  ! The cases must exercise what they are for: a rejected refinement step, and
  ! EPSILON well above round-off.
  call check(rejected >= 3, 'at least 3 of the runs reject a refinement step')
  call check(compared >= 12, 'at least 12 of the runs have an EPSILON above 1e-12')
  write (*, '(a,i0,a,i0,a,f6.3,a)') 'runs with a rejected refinement step: ', rejected, &
       ', EPSILON above 1e-12: ', compared, ', largest difference ', worst, ' x the rounding bound'
  call finish()

contains

  function cantilever(joint) result(deck)
    !! A two-part B23 cantilever (8 + 8 elements, L = 4) whose mid-length joint
    !! has joint times the beam's end stiffnesses, under an end load.
    real(wp), intent(in) :: joint
    character(:), allocatable :: deck
    character(len=40) :: gt, gr
    write (gt, '(es23.15)') joint*3.0_wp*2.0e7_wp/8.0_wp   ! 3EI/L^3, EI = 2e7, L = 2 (each part)
    write (gr, '(es23.15)') joint*2.0e7_wp/2.0_wp           ! EI/L
    deck = '*MATERIAL, NAME=STEEL'//NL//'*ELASTIC'//NL//'2.0e11, 0.3'//NL
    deck = deck//part('I', 0.0_wp)//part('II', 2.0_wp)
    deck = deck//'*CONTACT, NAME=J, MASTER=I, SLAVE=II'//NL// &
         ' 9, 1, 1, 2, '//trim(adjustl(gt))//NL//' 9, 1, 6, 6, '//trim(adjustl(gr))//NL
    deck = deck//'*SUPPORT'//NL//' I.1, 1, 2'//NL//' I.1, 6, 6'//NL
    deck = deck//'*STEP, NAME=TIP'//NL//'*CLOAD'//NL//' II.9, 1, 5000.0'//NL//' II.9, 2, -1000.0'//NL// &
         '*END STEP'//NL
    deck = deck//'*STEP, NAME=MID'//NL//'*CLOAD'//NL//' II.5, 2, 800.0'//NL//' I.5, 6, 300.0'//NL//'*END STEP'//NL
  end function cantilever

  function part(name, x0) result(s)
    !! One half of the cantilever: 9 nodes from x0, 8 B23 elements.
    character(*), intent(in) :: name
    real(wp), intent(in) :: x0
    character(:), allocatable :: s
    character(len=40) :: buf
    integer :: k
    s = '*SUBSTRUCTURE, NAME='//name//NL//'*NODE'//NL
    do k = 1, 9
       write (buf, '(i0,a,f8.4,a)') k, ', ', x0 + 0.25_wp*(k - 1), ', 0.0'
       s = s//trim(buf)//NL
    end do
    s = s//'*ELEMENT, TYPE=B23, ELSET=BEAM'//NL
    do k = 1, 8
       write (buf, '(i0,a,i0,a,i0)') k, ', ', k, ', ', k + 1
       s = s//trim(buf)//NL
    end do
    s = s//'*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL'//NL//'0.01, 0.0001'//NL//'*END SUBSTRUCTURE'//NL
  end function part

  function physical_epsilon(model, res, st, bound) result(eps)
    !! uᵀ(K u - f) / uᵀf of step st in quadruple precision from element
    !! matrices, contact springs (global axes), elastic supports and point loads.
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: st
    real(wp) :: eps
    real(wp), intent(out) :: bound
    real(qp) :: energy, work, du, absum
    real(wp), allocatable :: ke(:, :)
    real(qp), allocatable :: ue(:)
    integer, allocatable :: dofs(:)
    type(error_t), allocatable :: error
    integer :: isub, a, d, k, il, nd, c
    integer(ip) :: e, n
    energy = 0.0_qp
    absum = 0.0_qp
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         do e = 1, sub%nelem
            dofs = element_node_dofs(sub%elem_type(e))
            nd = size(dofs)
            call element_stiffness(sub%elem_type(e), sub%x(:, sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e)), &
                 sub%sections(sub%elem_section(e)), model%materials(sub%sections(sub%elem_section(e))%material), ke, error)
            if (allocated(error)) error stop 'element stiffness'
            allocate (ue(nd*ELEMENT_NODE_COUNT(sub%elem_type(e))))
            do a = 1, ELEMENT_NODE_COUNT(sub%elem_type(e))
               n = sub%elem_nodes(a, e)
               do k = 1, nd
                  ue(nd*(a - 1) + k) = real(u_of(res, isub, n, dofs(k), st), qp)
               end do
            end do
            energy = energy + dot_product(ue, matmul(real(ke, qp), ue))
            absum = absum + dot_product(abs(ue), matmul(abs(real(ke, qp)), abs(ue)))
            deallocate (ue)
         end do
       end associate
    end do
    do il = 1, size(model%links)
       associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
         if (ct%orientation /= 0) error stop 'contacts in global axes only'
         do d = 1, 6
            if (lk%state(d) /= LINK_FINITE) cycle
            du = real(u_of(res, ct%slave_sub, lk%slave_node, d, st), qp) - &
                 real(u_of(res, ct%master_sub, lk%master_node, d, st), qp)
            energy = energy + real(lk%g(d), qp)*du*du
            absum = absum + real(lk%g(d), qp)*(abs(real(u_of(res, ct%slave_sub, lk%slave_node, d, st), qp)) + &
                 abs(real(u_of(res, ct%master_sub, lk%master_node, d, st), qp)))**2
         end do
       end associate
    end do
    do c = 1, size(model%supports)
       associate (sp => model%supports(c))
         if (sp%state == LINK_FINITE) energy = energy + real(sp%g, qp)*real(u_of(res, sp%sub, sp%node, sp%dof, st), qp)**2
       end associate
    end do
    work = 0.0_qp
    do c = 1, size(model%steps(st)%cloads)
       associate (cl => model%steps(st)%cloads(c))
         work = work + real(cl%value, qp)*real(u_of(res, cl%sub, cl%node, cl%dof, st), qp)
         absum = absum + abs(real(cl%value, qp)*real(u_of(res, cl%sub, cl%node, cl%dof, st), qp))
       end associate
    end do
    if (size(model%steps(st)%dloads) > 0) error stop 'point loads only'
    eps = real((energy - work)/work, wp)
    bound = epsilon(1.0_wp)*real(absum/abs(work), wp)
    ! (absum: Σ|u_e|ᵀ|K_e||u_e| + Σ g (|u_s| + |u_m|)² + Σ g u² + |f|ᵀ|u|)
  end function physical_epsilon

  real(wp) function u_of(res, isub, n, dof, st)
    type(results_t), intent(in) :: res
    integer, intent(in) :: isub, dof, st
    integer(ip), intent(in) :: n
    u_of = res%fields%u(6*(res%fields%vertex_offset(isub) + n - 1) + dof, st)
  end function u_of
end program test_epsilon
