module superjoin_analysis_policy
  !! Decisions the pipeline takes before it solves: RIGID as a large number,
  !! what the transform did, column groups, boundaries, which substructures are
  !! condensed, AUTOSPC, the unknowns coupled to no load, and the elements whose
  !! results somebody reads.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, add_error_line, EXIT_SINGULAR
  use superjoin_model_types, only: model_t, string_t, FORM_TRANSFORM, FORM_PENALTY, RIGID_LARGE, &
       DEFAULT_PENALTY_LARGE, LINK_RIGID, CONDENSE_YES, CONDENSE_NO, CONDENSE_AUTO, &
       REQ_EL_PRINT, REQ_EL_FILE
  use superjoin_model_request_masks, only: has_requests, any_request_of, request_mask
  use superjoin_assembly_dofs, only: dof_table_t, UNIT_LINK, UNIT_SUPPORT
  use superjoin_assembly_forest, only: forest_t
  use superjoin_assembly_transform, only: transform_t, constraint_t, COL_PHYS, ROLE_TREE, ROLE_PLAIN, &
       CONS_REDUNDANT, CONS_ELIMINATED
  use superjoin_assembly_assemble, only: max_element_diagonal
  use superjoin_solvers, only: sparse_sym_t
  use superjoin_model_results, only: run_summary_t, run_options_t
  use superjoin_analysis_penalty, only: apply_penalty_default, penalty_default_note
  use superjoin_analysis_labels, only: column_label, vertex_label, block_name, local_name
  use superjoin_model_notes, only: note
  use superjoin_analysis_condensation, only: solve_context_t
  use superjoin_substructure_cache, only: twin_copies
  use superjoin_utils_union_find, only: find_root
  use superjoin_analysis_summed_matrix, only: summed_nonzero, summed_groups, holds_shared_terms
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: BYTES_REAL
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_SOLID, FAMILY_PLANE, FAMILY_SHELL
  implicit none (type, external)
  private

  real(wp), parameter :: AUTO_KSTAR_BYTES = 2.0_wp*2.0_wp**30
    !! CONDENSE=AUTO condenses no part whose dense K* would exceed this (2 GiB).
  real(wp), parameter :: FILL_3D = 16.0_wp, FILL_2D = 8.0_wp, FILL_1D = 6.0_wp
    !! Estimated entries of a part's sparse factor with n interior DOFs
    !! (nested dissection's growth): FILL_3D n^(4/3) for solids (CHOLMOD on
    !! this project's C3D10 and C3D20R blocks of 1e5 DOFs: 16 and 22),
    !! FILL_2D n log2 n for plane, axisymmetric and shell parts, FILL_1D n for
    !! frames and trusses.

  integer, parameter :: AUTO_TWIN_COPIES = 2
  integer(i8), parameter :: AUTO_TWIN_INTERIOR = 1000_i8, AUTO_TWIN_RATIO = 10_i8
    !! CONDENSE=AUTO counts identical parts found by their geometry (twins,
    !! --twins yes) as instances of one part when there are at least
    !! AUTO_TWIN_COPIES of them and each has at least AUTO_TWIN_INTERIOR
    !! interior DOFs, AUTO_TWIN_RATIO times its boundary: where one
    !! condensation shared beats the one sparse matrix (bench/twins.py
    !! --monolithic, doc/performance.md); the identical cantilevers of small
    !! verification decks (tens of DOFs) stay in the sparse matrix.

  public :: apply_large, describe_transform, column_groups, count_boundary, choose_condensation, autospc, &
       skip_unloaded_parts, wanted_elements

contains

  subroutine wanted_elements(model, opts, wanted, notes)
    !! The elements whose results somebody reads (numbered over the
    !! substructures): every one in a deck without output requests, or when
    !! result files (CSV, VTK) are written and the deck has no *EL FILE
    !! request; else those that *EL PRINT (and, with result files or the .frd
    !! of superjoin -i, *EL FILE) requests cover. Says in a note for how many
    !! elements the listing holds results when the deck has requests and that is
    !! not all: the deck alone decides it, so the listing is the same with and
    !! without result files (it said "computed for 0 of N" without --csv, and
    !! nothing with it, for a deck whose only request was *NODE PRINT).
    !! Every element with load combinations: their envelope lists every
    !! element's end forces and resultants.
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    logical, allocatable, intent(out) :: wanted(:)
    type(string_t), allocatable, intent(inout) :: notes(:)
    integer :: isub
    integer(i8) :: nelem, nprint
    nelem = 0
    do isub = 1, size(model%subs)
       nelem = nelem + model%subs(isub)%nelem
    end do
    if (.not. has_requests(model)) then
       allocate (wanted(nelem), source=.true.)
       return
    end if
    call request_mask(model, [REQ_EL_PRINT], .false., wanted)
    nprint = count(wanted, kind=i8)
    if (nprint < nelem) call note(notes, 'element results listed for '//itoa(nprint)//' of '//itoa(nelem)// &
         ' elements (those the *EL PRINT requests name)')
    if ((opts%csv .or. opts%vtk) .and. .not. any_request_of(model, [REQ_EL_FILE])) then
       wanted = .true.
    else if (opts%csv .or. opts%vtk .or. opts%frd) then
       call request_mask(model, [REQ_EL_PRINT, REQ_EL_FILE], .false., wanted)
    end if
    if (allocated(model%combinations)) then
       if (size(model%combinations) > 0) wanted = .true.   ! the envelope lists every element
    end if
  end subroutine wanted_elements

  subroutine apply_large(model, table, form, notes, error)
    !! RIGID contacts become g = LARGE × (largest element diagonal) under
    !! RIGID=LARGE, and under PENALTY (which has no exact elimination).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    integer, intent(in) :: form
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: dmax, glarge
    integer :: iu, c
    logical :: any_rigid
    character(len=32) :: buf

    if (model%controls%rigid /= RIGID_LARGE .and. form /= FORM_PENALTY) return
    any_rigid = .false.
    do iu = 1, table%nunit
       if (table%units(iu)%kind == UNIT_LINK) any_rigid = any_rigid .or. &
            any(table%units(iu)%state(1:table%units(iu)%n) == LINK_RIGID)
    end do
    if (.not. any_rigid) return
    if (form == FORM_PENALTY .and. .not. model%controls%large_given) then
       call apply_penalty_default(model, table, DEFAULT_PENALTY_LARGE, dmax, glarge, error)
       if (.not. allocated(error)) call note(notes, penalty_default_note(dmax, glarge))
       return
    end if
    call max_element_diagonal(model, table, dmax, error)
    if (allocated(error)) return
    if (dmax <= 0.0_wp) dmax = 1.0_wp
    glarge = model%controls%large*dmax
    do iu = 1, table%nunit
       if (table%units(iu)%kind /= UNIT_LINK) cycle
       do c = 1, table%units(iu)%n
          if (table%units(iu)%state(c) == LINK_RIGID) call table%make_finite(iu, c, glarge)
       end do
    end do
    write (buf, '(es10.3)') glarge
    call note(notes, 'RIGID contacts use g = LARGE x largest element diagonal = '//trim(adjustl(buf)))
  end subroutine apply_large

  subroutine describe_transform(model, table, tr, form, summary, notes)
    !! Notes on what was transformed and what was assembled plainly.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    integer, intent(in) :: form
    type(run_summary_t), intent(inout) :: summary
    type(string_t), allocatable, intent(inout) :: notes(:)
    integer :: iu, i
    type(constraint_t) :: cs
    summary%n_tree = 0
    summary%n_plain = 0
    summary%n_support_units = 0
    do iu = 1, table%nunit
       associate (u => table%units(iu))
         if (u%kind == UNIT_SUPPORT) then
            summary%n_support_units = summary%n_support_units + 1
            if (tr%unit_role(iu) == ROLE_PLAIN) call note(notes, 'support at '//vertex_label(model, table, u%vb)// &
                 ' '//block_name(u%block)//' closes a loop through the ground: assembled plainly')
         else if (tr%unit_role(iu) == ROLE_TREE) then
            summary%n_tree = summary%n_tree + 1
         else
            summary%n_plain = summary%n_plain + 1
            if (form == FORM_TRANSFORM) call note(notes, 'contact '//model%contacts(model%links(u%source)%contact)%name// &
                 ' '//vertex_label(model, table, u%va)//' - '//vertex_label(model, table, u%vb)//' '// &
                 block_name(u%block)//': closes a loop, assembled plainly')
         end if
       end associate
       do i = 1, tr%nconstraints()
          cs = tr%constraint(i)
          if (cs%unit /= iu) cycle
          associate (u => table%units(iu))
            if (cs%status == CONS_REDUNDANT) then
               call note(notes, '  RIGID '//local_name(u%block, u%lcomp(cs%k))//' of that unit is redundant '// &
                    '(already implied by the tree); its force is carried by the tree')
            else if (cs%status == CONS_ELIMINATED) then
               call note(notes, '  RIGID '//local_name(u%block, u%lcomp(cs%k))//' of that unit is enforced exactly '// &
                    'by eliminating one unknown')
            end if
          end associate
       end do
    end do
  end subroutine describe_transform

  subroutine column_groups(table, forest, tr, first)
    !! Columns grouped by node (a node's own DOFs and the δ of the contact
    !! above it are numbered together): first(g) is the first column of group g.
    !! Unallocated when the columns of a node are not consecutive.
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(in) :: tr
    integer(i8), allocatable, intent(out) :: first(:)
    integer(i8), allocatable :: vert(:)
    integer(i8) :: j, p, ng
    integer :: iu
    allocate (vert(tr%ncol()))
    do j = 1, tr%ncol()
       if (tr%column_kind(j) == COL_PHYS) then
          p = tr%column_ref(j)
          vert(j) = table%vertex_offset(table%p_sub(p)) + table%p_node(p)
       else
          iu = int(tr%column_ref(j))
          if (forest%child_is_a(iu)) then
             vert(j) = table%units(iu)%va
          else
             vert(j) = table%units(iu)%vb
          end if
       end if
       if (j > 1) then
          if (vert(j) < vert(j - 1)) return
       end if
    end do
    ng = 0
    do j = 1, tr%ncol()
       if (j == 1) then
          ng = 1
       else if (vert(j) /= vert(j - 1)) then
          ng = ng + 1
       end if
    end do
    allocate (first(ng + 1))
    ng = 0
    do j = 1, tr%ncol()
       if (j == 1) then
          ng = 1
          first(1) = 1
       else if (vert(j) /= vert(j - 1)) then
          ng = ng + 1
          first(ng) = j
       end if
    end do
    first(ng + 1) = tr%ncol() + 1
  end subroutine column_groups

  subroutine count_boundary(model, table, bnd, summary)
    !! Active and boundary DOFs per substructure: the boundary DOFs (those a
    !! contact or support touches) form k_bb, the others k_ii.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    type(run_summary_t), intent(inout) :: summary
    integer(i8) :: p
    integer :: isub
    allocate (summary%sub_dofs(size(model%subs)), summary%sub_boundary(size(model%subs)), source=0_i8)
    do p = 1, table%np
       isub = table%p_sub(p)
       summary%sub_dofs(isub) = summary%sub_dofs(isub) + 1
       if (bnd(p)) summary%sub_boundary(isub) = summary%sub_boundary(isub) + 1
    end do
  end subroutine count_boundary

  subroutine choose_condensation(model, table, opts, ctx, bnd, summary, notes)
    !! Which substructures are condensed. CONDENSE=YES (deck or --condense)
    !! condenses a substructure that has both interior and boundary DOFs.
    !! AUTO condenses where a condensation is reused: an instance of a part
    !! placed more than once (one condensation for all its instances), and
    !! every substructure of a joint study (the parts are condensed once, each
    !! further set of contact stiffnesses factors only the interface), provided
    !! its K* (n_b² doubles) stays within AUTO_KSTAR_BYTES and its boundary is
    !! smaller than its interior. Otherwise AUTO keeps the part in the one
    !! sparse matrix: for a single factorization a fill-reducing ordering of
    !! the whole model already exploits the cut. NO never condenses.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(in) :: ctx
    logical, intent(in) :: bnd(:)              !! condensation boundary
    type(run_summary_t), intent(inout) :: summary
    type(string_t), allocatable, intent(inout) :: notes(:)
    integer :: isub, mode
    integer(i8) :: nb, ni, p
    integer(i8), allocatable :: nbs(:)
    integer, allocatable :: copies(:)
    character(:), allocatable :: why, small
    small = ''
    allocate (summary%sub_condensed(size(model%subs)), source=.false.)
    allocate (nbs(size(model%subs)), source=0_i8)
    do p = 1, table%np
       if (bnd(p)) nbs(table%p_sub(p)) = nbs(table%p_sub(p)) + 1
    end do
    copies = auto_twins(model, table, opts, ctx, bnd, nbs, summary)
    summary%n_condensed = 0
    do isub = 1, size(model%subs)
       mode = model%subs(isub)%condense
       if (opts%condense >= 0) mode = opts%condense
       nb = nbs(isub)
       ni = summary%sub_dofs(isub) - nb
       if (must_condense(model, isub) .and. nb > 0) then
          call force_condensed(model, isub, ni, nb, summary, notes)
          cycle
       end if
       if (mode == CONDENSE_NO) cycle
       if (mode == CONDENSE_AUTO) then
          if (.not. auto_condenses(model, ctx, isub, ni, nb, copies(isub), why, small, notes)) cycle
       else
          why = 'CONDENSE=YES'
       end if
       if (nb == 0) then
          call note(notes, 'substructure '//model%subs(isub)%name//' not condensed: no contact or support '// &
               'touches it (a separate system)')
       else if (ni == 0) then
          call note(notes, 'substructure '//model%subs(isub)%name//' not condensed: every DOF is on its boundary')
       else
          summary%sub_condensed(isub) = .true.
          summary%n_condensed = summary%n_condensed + 1
          call note(notes, 'substructure '//model%subs(isub)%name//' condensed ('//why//'): '// &
               itoa(ni)//' interior DOFs eliminated, '//kstar_text(nb))
       end if
    end do
    if (len(small) > 0) call note(notes, 'CONDENSE=AUTO: not condensed, the boundary being no smaller '// &
         'than the interior:'//small)
  end subroutine choose_condensation

  function auto_twins(model, table, opts, ctx, bnd, nbs, summary) result(copies)
    !! For each substructure that CONDENSE=AUTO would count twins of (AUTO,
    !! not an instance of a part placed more than once, no joint study,
    !! --twins yes, an interior of AUTO_TWIN_INTERIOR DOFs or more and
    !! AUTO_TWIN_RATIO times its boundary), how many identical copies it has
    !! (itself included; superjoin_substructure_cache's twin_copies); 0 for the others.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(in) :: ctx
    logical, intent(in) :: bnd(:)
    integer(i8), intent(in) :: nbs(:)
    type(run_summary_t), intent(in) :: summary
    integer, allocatable :: copies(:)
    logical, allocatable :: candidate(:)
    integer :: isub, mode
    integer(i8) :: ni
    allocate (copies(size(model%subs)), source=0)
    allocate (candidate(size(model%subs)), source=.false.)
    if (.not. opts%twins .or. ctx%joint_study) return
    do isub = 1, size(model%subs)
       mode = model%subs(isub)%condense
       if (opts%condense >= 0) mode = opts%condense
       if (mode /= CONDENSE_AUTO .or. must_condense(model, isub) .or. nbs(isub) == 0) cycle
       if (model%subs(isub)%part > 0) then
          if (count(model%subs(:)%part == model%subs(isub)%part) > 1) cycle
       end if
       ni = summary%sub_dofs(isub) - nbs(isub)
       candidate(isub) = ni >= AUTO_TWIN_INTERIOR .and. ni >= AUTO_TWIN_RATIO*nbs(isub)
    end do
    if (count(candidate) >= AUTO_TWIN_COPIES) copies = twin_copies(model, table, bnd, candidate)
  end function auto_twins

  logical function must_condense(model, isub)
    !! A substructure whose stiffness is given (*MATRIX INPUT) or whose K* is
    !! exported (*SUBSTRUCTURE MATRIX OUTPUT) is condensed whatever CONDENSE says.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    must_condense = allocated(model%subs(isub)%given)
    if (must_condense .or. .not. allocated(model%exports)) return
    must_condense = any(model%exports(:)%sub == isub)
  end function must_condense

  subroutine force_condensed(model, isub, ni, nb, summary, notes)
    !! Mark substructure isub condensed (must_condense) and say why.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(i8), intent(in) :: ni, nb
    type(run_summary_t), intent(inout) :: summary
    type(string_t), allocatable, intent(inout) :: notes(:)
    summary%sub_condensed(isub) = .true.
    summary%n_condensed = summary%n_condensed + 1
    if (allocated(model%subs(isub)%given)) then
       call note(notes, 'substructure '//model%subs(isub)%name//': stiffness given by *MATRIX INPUT '// &
            model%subs(isub)%given%file//', '//kstar_text(nb))
    else
       call note(notes, 'substructure '//model%subs(isub)%name//' condensed (*SUBSTRUCTURE MATRIX OUTPUT): '// &
            itoa(ni)//' interior DOFs eliminated, '//kstar_text(nb))
    end if
  end subroutine force_condensed

  logical function auto_condenses(model, ctx, isub, ni, nb, copies, why, small, notes)
    !! CONDENSE=AUTO's choice for substructure isub (ni interior, nb boundary
    !! DOFs): condensed where the condensation is reused (an instance of a
    !! part placed more than once, a joint study, one of `copies` twins that
    !! auto_twins found large enough) and its dense K* (nb²
    !! doubles) costs no more memory than the part's own sparse factor
    !! (estimated_factor_entries) and stays within AUTO_KSTAR_BYTES. why: the
    !! reason for the listing; small gathers the parts whose boundary is no
    !! smaller than their interior; the other refusals get a note each.
    type(model_t), intent(in) :: model
    type(solve_context_t), intent(in) :: ctx
    integer, intent(in) :: isub
    integer(i8), intent(in) :: ni, nb
    integer, intent(in) :: copies
    character(:), allocatable, intent(out) :: why
    character(:), allocatable, intent(inout) :: small
    type(string_t), allocatable, intent(inout) :: notes(:)
    integer :: ninst
    real(wp) :: kstar_bytes, factor_bytes
    auto_condenses = .false.
    ninst = 0
    if (model%subs(isub)%part > 0) ninst = count(model%subs(:)%part == model%subs(isub)%part)
    if (ninst > 1) then
       why = 'AUTO: one of '//itoa(ninst)//' instances of part '//model%parts(model%subs(isub)%part)%s
    else if (ctx%joint_study) then
       why = 'AUTO: joint study'
    else if (copies >= AUTO_TWIN_COPIES) then
       why = 'AUTO: one of '//itoa(copies)//' identical parts (twins, found by their geometry)'
    else
       return
    end if
    if (nb == 0 .or. ni == 0) return
    if (nb >= ni) then
       small = small//' '//model%subs(isub)%name
       return
    end if
    kstar_bytes = real(nb, wp)**2*BYTES_REAL
    factor_bytes = estimated_factor_entries(model, isub, ni)*BYTES_REAL
    if (kstar_bytes > AUTO_KSTAR_BYTES) then
       call note(notes, 'substructure '//model%subs(isub)%name//' not condensed ('//why// &
            '): its K* would take '//itoa(nb*nb*BYTES_REAL/2**20)//' MiB')
    else if (kstar_bytes > factor_bytes) then
       call note(notes, 'substructure '//model%subs(isub)%name//' not condensed ('//why//'): its dense K* ('// &
            itoa(nb)//' boundary DOFs, '//mb_text(kstar_bytes)//') would outweigh the sparse factor of its '// &
            itoa(ni)//' interior DOFs (about '//mb_text(factor_bytes)//')')
    else
       auto_condenses = .true.
    end if
  end function auto_condenses

  real(wp) function estimated_factor_entries(model, isub, ni) result(nnz)
    !! Entries of the sparse factor of substructure isub's ni interior DOFs,
    !! estimated by the growth of nested dissection in the part's dimension
    !! (FILL_3D, FILL_2D, FILL_1D): the largest of its elements' families.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(i8), intent(in) :: ni
    type(element_traits_t) :: t
    integer :: e, dim
    real(wp) :: n
    dim = 1
    do e = 1, model%subs(isub)%nelem
       if (e > 1) then   ! a run of one type: its traits are judged already
          if (model%subs(isub)%elem_type(e) == model%subs(isub)%elem_type(e - 1)) cycle
       end if
       t = element_traits(model%subs(isub)%elem_type(e))
       if (t%family == FAMILY_SOLID .and. .not. t%axisymmetric) then
          dim = 3
          exit
       else if (t%family == FAMILY_PLANE .or. t%family == FAMILY_SHELL .or. t%family == FAMILY_SOLID) then
          dim = 2
       end if
    end do
    n = real(ni, wp)
    select case (dim)
    case (3)
       nnz = FILL_3D*n**(4.0_wp/3.0_wp)
    case (2)
       nnz = FILL_2D*n*max(1.0_wp, log(n)/log(2.0_wp))
    case default
       nnz = FILL_1D*n
    end select
  end function estimated_factor_entries

  pure function kstar_text(nb) result(s)
    !! `K* of order NB on its boundary (X.XX MB dense)`: the listing's size of a condensed part's K*.
    integer(i8), intent(in) :: nb
    character(:), allocatable :: s
    s = 'K* of order '//itoa(nb)//' on its boundary ('//mb_text(real(nb, wp)**2*BYTES_REAL)//' dense)'
  end function kstar_text

  pure function mb_text(bytes) result(s)
    !! `X.XX MB` (MB = 2^20 bytes).
    real(wp), intent(in) :: bytes
    character(:), allocatable :: s
    character(len=32) :: buf
    write (buf, '(f0.2)') bytes/2.0_wp**20
    if (buf(1:1) == '.') buf = '0'//buf(1:len(buf) - 1)
    s = trim(buf)//' MB'
  end function mb_text

  subroutine autospc(model, table, tr, k, f_red, spc, notes, error, summed)
    !! Unknowns with no stiffness at all: dropped (diagonal 1, load 0) when
    !! unloaded, reported; a loaded one is an error (exit 3). summed: k is
    !! this MPI process's term of K_red (analysis/summed_matrix): the columns
    !! without stiffness are those of no process, and process 0 puts the 1.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(inout) :: f_red(:, :)
    logical, allocatable, intent(out) :: spc(:)
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: summed
    logical, allocatable :: nz(:), offdiag(:)
    integer(i8) :: j, pos
    logical :: terms
    terms = .false.
    if (present(summed)) terms = summed
    allocate (nz(tr%ncol()), source=.false.)
    allocate (spc(tr%ncol()), source=.false.)
    if (terms) then
       allocate (offdiag(tr%ncol()))
       call summed_nonzero(k, nz, offdiag, error)
       if (allocated(error)) return
    end if
    do j = 1, merge(0_i8, k%n, terms)
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) /= 0.0_wp) then
             nz(j) = .true.
             nz(k%rowind(pos)) = .true.
          end if
       end do
    end do
    do j = 1, tr%ncol()
       if (nz(j)) cycle
       if (any(f_red(j, :) /= 0.0_wp)) then
          call add_error_line(error, EXIT_SINGULAR, 'error: load on a DOF without stiffness: '// &
               column_label(model, table, tr, j))
          cycle
       end if
       spc(j) = .true.
       if (.not. terms .or. holds_shared_terms()) k%val(k%colptr(j + 1) - 1) = 1.0_wp
       call note(notes, 'AUTOSPC: '//column_label(model, table, tr, j)//' has no stiffness and no load: dropped')
    end do
  end subroutine autospc

  subroutine skip_unloaded_parts(model, table, tr, k, f_red, spc, notes, summed, error, roots)
    !! Groups of unknowns coupled to nothing else and loaded in no step have a
    !! zero solution: they are taken out of the factorization (identity rows)
    !! and reported, so an unloaded free part is not a mechanism. summed: k is
    !! this MPI process's term of K_red (the groups are those of the sum,
    !! analysis/summed_matrix; process 0 puts the 1s); error is then present.
    !! roots (one process): the groups (each column's root) found in a K_red
    !! with the same off-diagonal entries, used as given; unallocated, they
    !! are found here and returned. The groups come from the off-diagonal
    !! nonzeros alone (a diagonal entry joins a column to itself), so a K_red
    !! that differs only on its diagonal (a joint study's next value with the
    !! previous value's K_red and other g's: analysis/build_reuse, take_matrix)
    !! has the same groups, whichever g is zero.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(in) :: f_red(:, :)
    logical, intent(inout) :: spc(:)
    type(string_t), allocatable, intent(inout) :: notes(:)
    logical, intent(in), optional :: summed
    type(error_t), allocatable, intent(out), optional :: error
    integer(i8), allocatable, intent(inout), optional :: roots(:)
    integer(i8), allocatable :: root(:)
    logical, allocatable :: loaded(:), skip(:), named(:)
    integer(i8) :: j, pos, nskip
    integer :: isub
    character(:), allocatable :: subs

    logical :: terms

    terms = .false.
    if (present(summed)) terms = summed
    if (k%n == 0) return
    if (terms .or. .not. present(roots)) then
       call column_groups_of(k, terms, root, error)
    else if (allocated(roots)) then
       root = roots
    else
       call column_groups_of(k, terms, root, error)
       roots = root
    end if
    if (present(error)) then
       if (allocated(error)) return
    end if
    allocate (loaded(k%n), source=.false.)
    do j = 1, k%n
       if (any(f_red(j, :) /= 0.0_wp)) loaded(root(j)) = .true.
    end do
    allocate (skip(k%n))
    nskip = 0
    do j = 1, k%n
       skip(j) = .not. loaded(root(j)) .and. .not. spc(j)
       if (skip(j)) nskip = nskip + 1
    end do
    if (nskip == 0) return
    allocate (named(size(model%subs)), source=.false.)
    do j = 1, k%n
       if (.not. skip(j)) cycle
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          k%val(pos) = 0.0_wp
       end do
       if (.not. terms .or. holds_shared_terms()) k%val(k%colptr(j + 1) - 1) = 1.0_wp
       spc(j) = .true.
       if (tr%column_kind(j) == COL_PHYS) named(table%p_sub(tr%column_ref(j))) = .true.
    end do
    ! Entries above the diagonal in other columns that belong to skipped rows.
    do j = 1, k%n
       do pos = k%colptr(j), k%colptr(j + 1) - 2
          if (skip(k%rowind(pos))) k%val(pos) = 0.0_wp
       end do
    end do
    subs = ''
    do isub = 1, size(model%subs)
       if (named(isub)) subs = subs//' '//model%subs(isub)%name
    end do
    if (len(subs) == 0) subs = ' (contact and support unknowns)'
    if (subs(1:2) /= ' (') subs = ' (in substructures'//subs//')'
    call note(notes, itoa(int(nskip))//' unknowns'//subs//' are coupled to no load: zero displacement, not solved')
  end subroutine skip_unloaded_parts

  subroutine column_groups_of(k, terms, root, error)
    !! The groups of skip_unloaded_parts: root(j) the root of column j's group
    !! (a union-find over the nonzeros of k; terms: of the summed K_red,
    !! analysis/summed_matrix, error then present).
    type(sparse_sym_t), intent(in) :: k
    logical, intent(in) :: terms
    integer(i8), allocatable, intent(out) :: root(:)
    type(error_t), allocatable, intent(out), optional :: error
    integer(i8) :: j, pos, a, b
    allocate (root(0:k%n))
    do j = 0, k%n
       root(j) = j
    end do
    if (terms) then
       call summed_groups(k, root(1:), error)
       if (allocated(error)) return
    end if
    do j = 1, merge(0_i8, k%n, terms)
       do pos = k%colptr(j), k%colptr(j + 1) - 1
          if (k%val(pos) == 0.0_wp) cycle
          a = find_root(root, k%rowind(pos))
          b = find_root(root, j)
          if (a /= b) root(max(a, b)) = min(a, b)
       end do
    end do
    do j = 1, merge(0_i8, k%n, terms)
       root(j) = find_root(root, j)
    end do
  end subroutine column_groups_of
end module superjoin_analysis_policy
