module superjoin_substructure_cache
  !! Condensations kept for reuse: by the instances of one part (turned by
  !! their placements) and by the solves of a joint study (same substructure,
  !! other contact stiffnesses).
  !!
  !! A condensation is computed for one substructure, in its own placement.
  !! Another substructure may use it when it has the same local DOFs (same
  !! local nodes and DOF numbers, interior and boundary alike) and either is the
  !! same substructure or is an instance of the same part whose placement
  !! differs by a rotation Q = R_s R_cᵀ that maps every node's active DOFs onto
  !! themselves. With R̂ = diag(Q) per node and DOF block:
  !!     k_s = R̂ k_c R̂ᵀ,  K*_s = R̂_b K*_c R̂_bᵀ,  f*_s = R̂_b f*_c(R̂ᵀ f_s),
  !!     u_i,s = R̂_i u_i,c(R̂ᵀ f_s, R̂_bᵀ u_b,s).
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, string_t
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_assembly_assemble, only: superelement_t
  use superjoin_substructure_local_system, only: local_system_t, build_local_system, local_numbering
  use superjoin_substructure_condensed, only: condensed_t, condense, condense_loads, recover_interior
  use superjoin_substructure_twins, only: twin_print_t, twin_print, twin_turn
  use superjoin_model_notes, only: note
  use superjoin_substructure_library, only: library_t, stored_t, library_enabled, library_condense, &
       library_need_loads, library_loads, library_recover, library_stiffness, library_ku
  implicit none (type, external)
  private

  real(wp), parameter :: ROT_ZERO = 1.0e-12_wp
    !! Entries of Q below this couple no DOFs (for the active-DOF check).
  integer, parameter :: BLOCK = 3
    !! Components of a node's DOF block (translations, rotations).

  type :: entry_t
    !! One computed condensation and what it is valid for.
     type(condensed_t) :: cond
     integer :: part = 0                      !! model%subs(isub)%part (0: not an instance)
     integer(ip), allocatable :: lnode(:)     !! local node of each local DOF
     integer, allocatable :: ldof(:)          !! DOF number 1..6 of each local DOF
     real(wp) :: rot(3, 3) = 0.0_wp           !! placement rotation of its substructure
     integer, allocatable :: drill(:)         !! its elements' drilling edge masks (elem_drill; they
                                              !! depend on supports and contacts, not only on the part)
     type(stored_t), allocatable :: stored    !! its library entry (--library)
     type(twin_print_t) :: print              !! its fingerprint, once a candidate twin needed it
  end type entry_t

  type :: entry_box_t
    !! An entry behind an allocatable, so that growing the list moves entries
    !! (their factors are C objects) instead of copying them.
     type(entry_t), allocatable :: e
  end type entry_box_t

  type, public :: part_view_t
    !! A condensed substructure in one solve: a cache entry, turned if need be.
     integer :: isub = 0
     integer :: entry = 0
     logical :: rotated = .false.
     logical :: reused = .false.
     real(wp) :: q(3, 3) = 0.0_wp
     integer(i8) :: ni = 0, nb = 0
     integer(i8), allocatable :: pdof(:)      !! physical DOF of each local DOF (this substructure)
     integer, allocatable :: grp(:, :)        !! (BLOCK, ngroup) local DOFs of each node block (0: absent)
     type(superelement_t) :: se               !! K* of this substructure on its physical boundary DOFs
     integer :: k_of = 0
       !! > 0: se%k is not held here but is that view's of the same array (an
       !! earlier view of the same entry, both unturned: acquire_view's before)
     ! A remote view (entry = 0): the substructure is condensed by another MPI
     ! process, which sent K* and what follows (analysis/distributed).
     real(wp) :: ratio = 0.0_wp               !! remote: MAXRATIO of the interior factor
     integer(i8) :: ratio_at = 0              !! remote: its physical DOF (0: none)
     integer(i8), allocatable :: spc(:)       !! remote: physical interior DOFs without stiffness
     real(wp), allocatable :: ku0(:)          !! remote: k u0 (prescribed boundary values), local order
     type(string_t), allocatable :: notes(:)  !! the library's notes on a condensation computed or loaded here
  end type part_view_t

  type, public :: part_cache_t
    !! Condensations computed so far in this run.
     type(entry_box_t), allocatable :: entries(:)
     integer :: n = 0
     integer :: computed = 0                  !! condensations computed
     integer :: reused = 0                    !! uses of an existing one
     type(library_t) :: library               !! the condensation library across runs (--library)
     logical :: twins = .true.                !! identical parts found by their geometry share (--twins)
     integer, allocatable :: twin_pairs(:)    !! twins found, for twins_note: (isub, source isub, turned) each
     ! A joint study's views kept from one value for the next (take_views).
     logical :: same_numbering = .false.      !! this value has the previous value's DOF table and boundaries
     logical :: keep_views = .false.          !! a later value may take this value's views
     logical :: views_taken = .false.         !! this value took the previous value's views (take_views)
     type(part_view_t), allocatable :: kept(:)   !! the previous value's views
     integer :: kept_n = -1, kept_computed = -1  !! n and computed when they were kept
  end type part_cache_t

  public :: view_ku, twin_copies, k_holder
  public :: release_cache, forget_load_memos, acquire_view, view_condense_loads, view_recover, view_stiffness_times, &
       view_maxratio, view_spc, view_spc_loads, remote_view, view_turn, entry_recover, entry_condense_loads, entry_ku, &
       entry_ku_reads_loads, &
       view_need_stiffness, take_views, keep_views, twins_note

contains

  subroutine acquire_view(cache, model, table, isub, bnd, solver_name, view, error, f_phys, before)
    !! The condensation of substructure isub: an existing one when one fits
    !! (find_entry), otherwise computed now (or loaded from the library) and
    !! kept. f_phys: the loads (physical DOFs), which a library entry must be
    !! able to condense. before: the views of the same array so far; an
    !! unturned view whose entry an unturned one of them holds shares that
    !! one's K* (view%k_of) instead of a copy of its own.
    type(part_cache_t), intent(inout) :: cache
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    logical, intent(in) :: bnd(:)
    character(*), intent(in) :: solver_name
    type(part_view_t), intent(out) :: view
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: f_phys(:, :)
    type(part_view_t), intent(in), optional :: before(:)
    integer(ip), allocatable :: lnode(:)
    integer, allocatable :: ldof(:)
    integer(i8) :: ni

    view%isub = isub
    call local_numbering(table, isub, bnd, view%pdof, ni)
    view%ni = ni
    view%nb = size(view%pdof, kind=i8) - ni
    allocate (lnode(size(view%pdof)), ldof(size(view%pdof)))
    lnode = table%p_node(view%pdof)
    ldof = table%p_dof(view%pdof)
    call node_groups(lnode, ldof, view%grp)

    call find_entry(cache, model, isub, lnode, ldof, view)
    if (view%entry == 0) then
       call add_entry(cache, model, table, isub, bnd, solver_name, error)
       if (allocated(error)) return
       associate (en => cache%entries(cache%n)%e)
         en%lnode = lnode
         en%ldof = ldof
       end associate
       view%entry = cache%n
       cache%computed = cache%computed + 1
    else
       view%reused = .true.
       cache%reused = cache%reused + 1
    end if
    if (allocated(cache%entries(view%entry)%e%stored) .and. present(f_phys)) then
       call library_view_loads(cache%entries(view%entry)%e, view, model, table, bnd, solver_name, f_phys, error)
       if (allocated(error)) return
    end if

    ! K* in this substructure's frame, on its physical boundary DOFs.
    allocate (view%se%pdof, source=view%pdof(ni + 1:))   ! view is intent(out): not reallocated by assignment
    if (present(before) .and. .not. view%rotated) view%k_of = holder_of(before, view%entry)
    if (view%k_of > 0) return   ! the same K* as an earlier view's: not copied (20 floors of 16 bays: 120 MB)
    associate (kc => cache%entries(view%entry)%e%cond%se%k)
      allocate (view%se%k, source=kc)
      if (view%rotated) then
         call rotate_boundary_columns(view, view%se%k, .true.)
         view%se%k = transpose(view%se%k)
         call rotate_boundary_columns(view, view%se%k, .true.)
      end if
    end associate
  end subroutine acquire_view

  pure integer function holder_of(views, entry) result(j)
    !! The first of views that holds its own unturned K* of cache entry entry (0: none).
    type(part_view_t), intent(in) :: views(:)
    integer, intent(in) :: entry
    do j = 1, size(views)
       if (views(j)%entry == entry .and. .not. views(j)%rotated .and. views(j)%k_of == 0) return
    end do
    j = 0
  end function holder_of

  pure integer function k_holder(views, i) result(j)
    !! The view of views whose se%k is views(i)'s K* (i itself, or its k_of).
    type(part_view_t), intent(in) :: views(:)
    integer, intent(in) :: i
    j = i
    if (views(i)%k_of > 0) j = views(i)%k_of
  end function k_holder

  subroutine find_entry(cache, model, isub, lnode, ldof, view)
    !! The cache entry that serves substructure isub (view%entry, 0: none;
    !! view%rotated, view%q): one with the same local DOFs (lnode, ldof,
    !! view%ni) that is isub's own (an earlier solve of a joint study), or
    !! an instance of the same part, or a twin (an identical part found by
    !! its geometry, superjoin_substructure_twins; unless cache%twins is
    !! off), turned by a rotation that keeps every node block's DOFs.
    type(part_cache_t), intent(inout) :: cache
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: lnode(:)
    integer, intent(in) :: ldof(:)
    type(part_view_t), intent(inout) :: view
    type(twin_print_t) :: mine
    real(wp) :: q(3, 3)
    logical :: fits, twin
    integer :: e
    do e = 1, cache%n
       associate (en => cache%entries(e)%e)
         if (en%cond%sys%ni /= view%ni .or. size(en%ldof) /= size(ldof)) cycle
         if (any(en%lnode /= lnode) .or. any(en%ldof /= ldof)) cycle
         if (en%cond%sys%isub == isub) then
            view%entry = e
            return
         end if
         twin = en%part == 0 .or. en%part /= model%subs(isub)%part
         if (.not. twin) then
            q = matmul(model%subs(isub)%rot, transpose(en%rot))
            fits = model%subs(en%cond%sys%isub)%nelem == model%subs(isub)%nelem   ! a bolt element removed
            if (fits) fits = same_masks(en%drill, model%subs(isub)%elem_drill)
         else
            fits = cache%twins
            if (fits .and. .not. mine%done) call twin_print(model, isub, mine)
            if (fits .and. .not. en%print%done) call twin_print(model, en%cond%sys%isub, en%print)
            if (fits) call twin_turn(model, en%cond%sys%isub, isub, en%print, mine, q, fits)
         end if
         if (fits) fits = keeps_dofs(q, view%grp)
         if (fits .and. .not. all(abs(q - identity()) <= ROT_ZERO)) fits = .not. mixed_blocks(view%grp, view%ni)
         if (.not. fits) cycle
         view%entry = e
         view%rotated = .not. all(abs(q - identity()) <= ROT_ZERO)
         view%q = q
         if (.not. twin) return
         if (.not. allocated(cache%twin_pairs)) allocate (cache%twin_pairs(0))
         cache%twin_pairs = [cache%twin_pairs, isub, en%cond%sys%isub, merge(1, 0, view%rotated)]
         return
       end associate
    end do
  end subroutine find_entry

  subroutine add_entry(cache, model, table, isub, bnd, solver_name, error)
    !! A new cache entry (the last): substructure isub condensed now, or
    !! loaded from the library (its k then assembled only if not loaded).
    type(part_cache_t), intent(inout) :: cache
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    logical, intent(in) :: bnd(:)
    character(*), intent(in) :: solver_name
    type(error_t), allocatable, intent(out) :: error
    type(entry_box_t), allocatable :: tmp(:)
    integer :: i
    if (.not. allocated(cache%entries)) allocate (cache%entries(4))
    if (cache%n == size(cache%entries)) then
       allocate (tmp(2*cache%n))
       do i = 1, cache%n
          call move_alloc(cache%entries(i)%e, tmp(i)%e)
       end do
       call move_alloc(tmp, cache%entries)
    end if
    cache%n = cache%n + 1
    allocate (cache%entries(cache%n)%e)
    associate (en => cache%entries(cache%n)%e)
      if (library_enabled(cache%library)) then
         allocate (en%stored)
         call library_condense(cache%library, model, table, isub, bnd, solver_name, en%cond, en%stored, error)
      else
         call build_local_system(model, table, isub, bnd, en%cond%sys, error)
         if (.not. allocated(error)) call condense(model, table, solver_name, en%cond, error)
      end if
      if (.not. allocated(error)) then
         en%part = model%subs(isub)%part
         en%rot = model%subs(isub)%rot
         if (allocated(model%subs(isub)%elem_drill)) en%drill = model%subs(isub)%elem_drill
      end if
    end associate
    ! A condensation that failed is no entry: find_entry of a later group of
    ! steps (a joint study's next value) would read its unset numbering.
    if (allocated(error)) then
       if (allocated(cache%entries(cache%n)%e%cond%solver)) call cache%entries(cache%n)%e%cond%solver%release()
       deallocate (cache%entries(cache%n)%e)
       cache%n = cache%n - 1
    end if
  end subroutine add_entry

  subroutine twins_note(cache, model, notes)
    !! One line of the listing's notes naming the twins found since the last
    !! call (find_entry), if any: which substructure took whose condensation.
    type(part_cache_t), intent(inout) :: cache
    type(model_t), intent(in) :: model
    type(string_t), allocatable, intent(inout) :: notes(:)
    character(:), allocatable :: text
    integer :: k
    if (.not. allocated(cache%twin_pairs)) return
    text = 'identical parts share a condensation (found by their geometry; --twins no: each its own):'
    do k = 1, size(cache%twin_pairs), 3
       associate (p => cache%twin_pairs(k:k + 2))
         if (k > 1) text = text//','
         text = text//' '//model%subs(p(1))%name//' as '//model%subs(p(2))%name
         if (p(3) == 1) text = text//' turned'
       end associate
    end do
    call note(notes, text)
    deallocate (cache%twin_pairs)
  end subroutine twins_note

  subroutine take_views(cache, subs, views, taken)
    !! The previous value's views of a joint study (taken), when this value
    !! has the same DOF table and condensation boundaries (same_numbering)
    !! and no condensation was computed or dropped since: acquire_view would
    !! find the same entries, numberings and K* (reused, without notes). Not
    !! with a library (its entries condense each value's loads). subs: the
    !! condensed substructures of this value, in order.
    type(part_cache_t), intent(inout) :: cache
    integer, intent(in) :: subs(:)
    type(part_view_t), allocatable, intent(out) :: views(:)
    logical, intent(out) :: taken
    taken = cache%same_numbering .and. allocated(cache%kept) .and. cache%n == cache%kept_n &
         .and. cache%computed == cache%kept_computed .and. .not. library_enabled(cache%library)
    if (taken) taken = size(cache%kept) == size(subs)
    if (taken) taken = all(cache%kept%isub == subs)
    cache%views_taken = taken
    if (.not. taken) then
       if (allocated(cache%kept)) deallocate (cache%kept)
       return
    end if
    call move_alloc(cache%kept, views)
    cache%reused = cache%reused + size(views)
  end subroutine take_views

  subroutine keep_views(cache, views)
    !! This value's views, once the solve is done with them: kept for the
    !! next value of a joint study (keep_views set; as acquire_view would give
    !! them again: reused, without notes), else freed. Moved, not copied.
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), allocatable, intent(inout) :: views(:)
    integer :: i
    if (.not. (cache%keep_views .and. all(views%entry > 0))) then   ! entry 0: condensed by another process
       deallocate (views)
       return
    end if
    call move_alloc(views, cache%kept)
    do i = 1, size(cache%kept)
       cache%kept(i)%reused = .true.
       if (allocated(cache%kept(i)%notes)) deallocate (cache%kept(i)%notes)
    end do
    cache%kept_n = cache%n
    cache%kept_computed = cache%computed
  end subroutine keep_views

  subroutine library_view_loads(en, view, model, table, bnd, solver_name, f_phys, error)
    !! A library entry able to condense this view's loads (in the entry's
    !! frame); the entry's notes passed to the view for the listing.
    type(entry_t), intent(inout) :: en
    type(part_view_t), intent(inout) :: view
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    character(*), intent(in) :: solver_name
    real(wp), intent(in) :: f_phys(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fc(:, :)
    allocate (fc, source=f_phys(view%pdof, :))
    if (view%rotated) call rotate_local(view, fc, forward=.false.)
    call library_need_loads(model, table, bnd, solver_name, en%cond, en%stored, fc, error)
    if (allocated(en%stored%notes)) call move_alloc(en%stored%notes, view%notes)
  end subroutine library_view_loads

  subroutine remote_view(table, isub, bnd, view)
    !! The numbering of a substructure that another process condenses
    !! (entry 0): its physical DOFs, interior first; K* and the rest are
    !! filled from that process's message.
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    logical, intent(in) :: bnd(:)
    type(part_view_t), intent(out) :: view
    integer(i8) :: ni
    view%isub = isub
    call local_numbering(table, isub, bnd, view%pdof, ni)
    view%ni = ni
    view%nb = size(view%pdof, kind=i8) - ni
    view%se%pdof = view%pdof(ni + 1:)
  end subroutine remote_view

  subroutine release_cache(cache)
    !! Free every factor the cache holds.
    type(part_cache_t), intent(inout) :: cache
    integer :: i
    do i = 1, cache%n
       if (.not. allocated(cache%entries(i)%e)) cycle
       if (allocated(cache%entries(i)%e%cond%solver)) call cache%entries(i)%e%cond%solver%release()
    end do
    if (allocated(cache%entries)) deallocate (cache%entries)
    if (allocated(cache%kept)) deallocate (cache%kept)
    cache%n = 0
  end subroutine release_cache

  subroutine forget_load_memos(cache)
    !! Drop the loads each condensation keeps for the next solve of a joint
    !! study (condense_loads): the last solve has no next one. Where the
    !! forward half of their solve is kept (memo_y), the loads stay until the
    !! recovery, which checks them before it takes the backward half alone.
    type(part_cache_t), intent(inout) :: cache
    integer :: i
    do i = 1, cache%n
       if (.not. allocated(cache%entries(i)%e)) cycle
       if (allocated(cache%entries(i)%e%cond%memo_f) .and. .not. allocated(cache%entries(i)%e%cond%memo_y)) &
            deallocate (cache%entries(i)%e%cond%memo_f)
       if (allocated(cache%entries(i)%e%cond%memo_fstar)) deallocate (cache%entries(i)%e%cond%memo_fstar)
    end do
  end subroutine forget_load_memos

  subroutine view_condense_loads(cache, view, f_local, fstar, error)
    !! f* of this substructure from its local loads (this frame).
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), intent(in) :: view
    real(wp), intent(in) :: f_local(:, :)
    real(wp), intent(out) :: fstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fc(:, :)
    allocate (fc, source=f_local)
    call view_turn(view, fc, .false.)
    call entry_condense_loads(cache, view%entry, fc, fstar, size(fc, 2), error)
    if (allocated(error)) return
    call view_turn(view, fstar, .true., view%ni)
  end subroutine view_condense_loads

  subroutine entry_condense_loads(cache, ientry, fc, fstar, chunk, error)
    !! f* with cache entry ientry from local loads in its frame, for any
    !! number of columns: chunk columns per substructure (a library entry
    !! keeps its load sets per substructure).
    type(part_cache_t), intent(inout) :: cache
    integer, intent(in) :: ientry
    real(wp), contiguous, intent(in) :: fc(:, :)
    real(wp), intent(out) :: fstar(:, :)
    integer, intent(in) :: chunk
    type(error_t), allocatable, intent(out) :: error
    integer :: c
    associate (en => cache%entries(ientry)%e)
      if (.not. allocated(en%stored)) then
         call condense_loads(en%cond, fc, fstar, error)
         return
      end if
      do c = 1, size(fc, 2), max(chunk, 1)
         call library_loads(en%cond, en%stored, fc(:, c:c + chunk - 1), fstar(:, c:c + chunk - 1), error)
         if (allocated(error)) return
      end do
    end associate
  end subroutine entry_condense_loads

  subroutine view_recover(cache, view, f_local, u_local, error)
    !! Interior displacements from the boundary ones (local arrays, this frame).
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), intent(in) :: view
    real(wp), intent(in) :: f_local(:, :)
    real(wp), intent(inout) :: u_local(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fc(:, :)
    allocate (fc, source=f_local)
    call view_turn(view, fc, .false.)
    call view_turn(view, u_local, .false.)
    call entry_recover(cache, view%entry, fc, u_local, size(fc, 2), error)
    call view_turn(view, u_local, .true.)
  end subroutine view_recover

  subroutine view_turn(view, x, forward, offset)
    !! x ← R̂ x (forward: from the condensation's frame to this
    !! substructure's) or R̂ᵀ x, rows in local numbering (row r of x: local
    !! DOF r + offset; offset ni: the boundary rows alone); x unchanged where
    !! the view is not turned.
    type(part_view_t), intent(in) :: view
    real(wp), intent(inout) :: x(:, :)
    logical, intent(in) :: forward
    integer(i8), intent(in), optional :: offset
    integer(i8) :: off
    off = 0
    if (present(offset)) off = offset
    if (view%rotated) call rotate_rows(view, x, off, forward)
  end subroutine view_turn

  subroutine entry_recover(cache, ientry, fc, u_local, chunk, error)
    !! Interior displacements from the boundary ones with cache entry ientry,
    !! in that entry's frame, for any number of columns (the instances that
    !! share it recovered as one solve): chunk columns per substructure (a
    !! library entry finds its load sets per substructure). fc's interior
    !! rows may be overwritten where the factor recovers (recover_interior
    !! works in them); a library entry leaves fc as it was (its entry_ku
    !! reads it).
    type(part_cache_t), intent(inout) :: cache
    integer, intent(in) :: ientry
    real(wp), contiguous, intent(inout) :: fc(:, :)
    real(wp), contiguous, intent(inout) :: u_local(:, :)
    integer, intent(in) :: chunk
    type(error_t), allocatable, intent(out) :: error
    integer :: c
    if (.not. allocated(cache%entries(ientry)%e%stored)) then
       call recover_interior(cache%entries(ientry)%e%cond, fc, u_local, error)
       return
    end if
    do c = 1, size(fc, 2), max(chunk, 1)
       call library_recover(cache%entries(ientry)%e%stored, fc(:, c:c + chunk - 1), u_local(:, c:c + chunk - 1), error)
       if (allocated(error)) return
    end do
  end subroutine entry_recover

  subroutine view_stiffness_times(cache, view, x_local, y_local)
    !! y = k x with the substructure's element stiffness (this frame).
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: view
    real(wp), intent(in) :: x_local(:, :)
    real(wp), intent(out) :: y_local(:, :)
    real(wp), allocatable :: xc(:, :)
    allocate (xc, source=x_local)
    if (view%rotated) call rotate_local(view, xc, .false.)
    call cache%entries(view%entry)%e%cond%sys%k%matvec(xc, y_local)
    if (view%rotated) call rotate_local(view, y_local, .true.)
  end subroutine view_stiffness_times

  subroutine entry_ku(cache, ientry, fc, uc, y, chunk, error)
    !! y = k u with cache entry ientry, in that entry's frame, for any number
    !! of columns (the instances that share it side by side): one product
    !! with its element stiffness; a library entry (library_ku) chunk columns
    !! per substructure, with the loads fc it was condensed with.
    type(part_cache_t), intent(in) :: cache
    integer, intent(in) :: ientry
    real(wp), intent(in) :: fc(:, :), uc(:, :)
    real(wp), intent(out) :: y(:, :)
    integer, intent(in) :: chunk
    type(error_t), allocatable, intent(out) :: error
    integer :: c
    associate (en => cache%entries(ientry)%e)
      if (.not. allocated(en%stored)) then
         call en%cond%sys%k%matvec(uc, y)
         return
      end if
      do c = 1, size(uc, 2), max(chunk, 1)
         call library_ku(en%cond, en%stored, fc(:, c:c + chunk - 1), uc(:, c:c + chunk - 1), y(:, c:c + chunk - 1), error)
         if (allocated(error)) return
      end do
    end associate
  end subroutine entry_ku

  logical function entry_ku_reads_loads(cache, ientry)
    !! Whether entry_ku reads the loads fc (a library entry's k u does; the
    !! others' is their element stiffness times u alone).
    type(part_cache_t), intent(in) :: cache
    integer, intent(in) :: ientry
    entry_ku_reads_loads = allocated(cache%entries(ientry)%e%stored)
  end function entry_ku_reads_loads

  subroutine view_ku(cache, view, f_local, u_local, y_local, error)
    !! y = k u of one substructure (this frame) for the loads f_local it was
    !! condensed with (entry_ku: its element stiffness, or a library entry's
    !! k u without it); the distributed recovery's k u of a process's own part.
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: view
    real(wp), intent(in) :: f_local(:, :), u_local(:, :)
    real(wp), intent(out) :: y_local(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fc(:, :), uc(:, :)
    allocate (fc, source=f_local)
    allocate (uc, source=u_local)
    call view_turn(view, fc, .false.)
    call view_turn(view, uc, .false.)
    call entry_ku(cache, view%entry, fc, uc, y_local, size(uc, 2), error)
    if (allocated(error)) return
    call view_turn(view, y_local, .true.)
  end subroutine view_ku

  subroutine view_need_stiffness(cache, view, model, table, bnd, error)
    !! Make sure the view's element stiffness is assembled (a library entry
    !! is loaded without it) for view_stiffness_times.
    type(part_cache_t), intent(inout) :: cache
    type(part_view_t), intent(in) :: view
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    type(error_t), allocatable, intent(out) :: error
    call library_stiffness(model, table, bnd, cache%entries(view%entry)%e%cond, error)
  end subroutine view_need_stiffness

  subroutine view_maxratio(cache, view, ratio, p)
    !! MAXRATIO of the interior factor and its physical DOF in this substructure.
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: view
    real(wp), intent(out) :: ratio
    integer(i8), intent(out) :: p
    if (view%entry == 0) then   ! remote
       ratio = view%ratio
       p = view%ratio_at
       return
    end if
    ratio = cache%entries(view%entry)%e%cond%maxratio
    p = 0
    if (cache%entries(view%entry)%e%cond%maxratio_at > 0) p = view%pdof(cache%entries(view%entry)%e%cond%maxratio_at)
  end subroutine view_maxratio

  subroutine view_spc(cache, view, p, local)
    !! Physical DOFs of this substructure's interior that have no stiffness;
    !! local: their local DOFs (not for a remote view).
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: view
    integer(i8), allocatable, intent(out) :: p(:)
    integer(i8), allocatable, intent(out), optional :: local(:)
    integer(i8), allocatable :: l(:)
    integer(i8) :: i
    if (view%entry == 0) then   ! remote
       p = view%spc
       return
    end if
    associate (c => cache%entries(view%entry)%e%cond)
      allocate (l(size(c%spc)))
      do i = 1, size(c%spc, kind=i8)
         l(i) = findloc(c%sys%pdof, c%spc(i), dim=1, kind=i8)
      end do
    end associate
    p = view%pdof(l)
    if (present(local)) call move_alloc(l, local)
  end subroutine view_spc

  subroutine view_spc_loads(cache, view, f_phys, p, loaded)
    !! The physical DOFs of this substructure's interior that have no
    !! stiffness (view_spc) and whether the loads f_phys act on each. A
    !! turned view (an instance or a twin placed by a rotation) has them in
    !! the condensation's frame: the direction without stiffness of a turned
    !! node is the turned one, not the same global component, so its loads
    !! are read turned into that frame, where a component of round-off size
    !! (TURN_ROUNDOFF of the part's largest load) is no load; p then names
    !! the node by the component of the condensation's frame.
    type(part_cache_t), intent(in) :: cache
    type(part_view_t), intent(in) :: view
    real(wp), intent(in) :: f_phys(:, :)
    integer(i8), allocatable, intent(out) :: p(:)
    logical, allocatable, intent(out) :: loaded(:)
    real(wp), parameter :: TURN_ROUNDOFF = 1.0e-13_wp
    real(wp), allocatable :: x(:, :)
    real(wp) :: tol
    integer(i8), allocatable :: l(:)
    integer(i8) :: i
    call view_spc(cache, view, p, l)
    allocate (loaded(size(p)))
    if (view%entry == 0 .or. .not. view%rotated) then
       do i = 1, size(p, kind=i8)
          loaded(i) = any(f_phys(p(i), :) /= 0.0_wp)
       end do
       return
    end if
    x = f_phys(view%pdof, :)
    tol = TURN_ROUNDOFF*maxval(abs(x))
    call view_turn(view, x, .false.)
    do i = 1, size(p, kind=i8)
       loaded(i) = any(abs(x(l(i), :)) > tol)
    end do
  end subroutine view_spc_loads

  pure logical function same_masks(a, b)
    !! Two instances' drilling edge masks agree (both absent, or equal).
    integer, allocatable, intent(in) :: a(:), b(:)
    same_masks = allocated(a) .eqv. allocated(b)
    if (.not. same_masks .or. .not. allocated(a)) return
    same_masks = size(a) == size(b)
    if (same_masks) same_masks = all(a == b)
  end function same_masks

  pure function identity() result(q)
    real(wp) :: q(3, 3)
    q = 0.0_wp
    q(1, 1) = 1.0_wp
    q(2, 2) = 1.0_wp
    q(3, 3) = 1.0_wp
  end function identity

  function twin_copies(model, table, bnd, candidate) result(copies)
    !! For each candidate substructure, how many candidates (itself included)
    !! would share its condensation as twins (find_entry's tests: the same
    !! local DOFs, identical up to a rigid motion that keeps every node
    !! block's DOFs); 0 for the others. CONDENSE=AUTO's count of copies.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:), candidate(:)
    integer :: copies(size(candidate))
    type :: rep_t
       integer :: isub = 0
       integer(i8) :: ni = 0
       integer(ip), allocatable :: lnode(:)
       integer, allocatable :: ldof(:)
       type(twin_print_t) :: print
    end type rep_t
    type(rep_t), allocatable :: reps(:)
    integer, allocatable :: cls(:), grp(:, :), ldof(:)
    integer(ip), allocatable :: lnode(:)
    integer(i8), allocatable :: pdof(:)
    integer(i8) :: ni
    type(twin_print_t) :: mine
    real(wp) :: q(3, 3)
    logical :: fits
    integer :: isub, r, nrep
    allocate (reps(count(candidate)))
    allocate (cls(size(candidate)), source=0)
    nrep = 0
    do isub = 1, size(candidate)
       if (.not. candidate(isub)) cycle
       call local_numbering(table, isub, bnd, pdof, ni)
       lnode = table%p_node(pdof)
       ldof = table%p_dof(pdof)
       call node_groups(lnode, ldof, grp)
       call twin_print(model, isub, mine)
       do r = 1, nrep
          fits = reps(r)%ni == ni .and. size(reps(r)%ldof) == size(ldof)
          if (fits) fits = all(reps(r)%lnode == lnode) .and. all(reps(r)%ldof == ldof)
          if (fits) call twin_turn(model, reps(r)%isub, isub, reps(r)%print, mine, q, fits)
          if (fits) fits = keeps_dofs(q, grp)
          if (fits .and. .not. all(abs(q - identity()) <= ROT_ZERO)) fits = .not. mixed_blocks(grp, ni)
          if (.not. fits) cycle
          cls(isub) = r
          exit
       end do
       if (cls(isub) > 0) cycle
       nrep = nrep + 1
       cls(isub) = nrep
       reps(nrep)%isub = isub
       reps(nrep)%ni = ni
       reps(nrep)%lnode = lnode
       reps(nrep)%ldof = ldof
       reps(nrep)%print = mine
    end do
    copies = 0
    do isub = 1, size(candidate)
       if (cls(isub) > 0) copies(isub) = count(cls == cls(isub))
    end do
  end function twin_copies

  subroutine node_groups(lnode, ldof, grp)
    !! The local DOFs of each (node, block): grp(c, g) is the local DOF of
    !! component c of group g, 0 where the node lacks it.
    integer(ip), intent(in) :: lnode(:)
    integer, intent(in) :: ldof(:)
    integer, allocatable, intent(out) :: grp(:, :)
    integer(ip) :: nmax
    integer :: l, b, g, ng
    integer, allocatable :: gid(:, :)
    nmax = 0
    if (size(lnode) > 0) nmax = maxval(lnode)
    allocate (gid(2, nmax), source=0)
    ng = 0
    do l = 1, size(lnode)
       b = (ldof(l) - 1)/BLOCK + 1
       if (gid(b, lnode(l)) == 0) then
          ng = ng + 1
          gid(b, lnode(l)) = ng
       end if
    end do
    allocate (grp(BLOCK, ng), source=0)
    do l = 1, size(lnode)
       b = (ldof(l) - 1)/BLOCK + 1
       g = gid(b, lnode(l))
       grp(ldof(l) - (b - 1)*BLOCK, g) = l
    end do
  end subroutine node_groups

  pure logical function mixed_blocks(grp, ni)
    !! Whether some node block has interior and boundary DOFs at once (then a
    !! turned K* cannot be formed from the boundary rows alone).
    integer, intent(in) :: grp(:, :)
    integer(i8), intent(in) :: ni
    integer :: g
    mixed_blocks = .false.
    do g = 1, size(grp, 2)
       if (any(grp(:, g) > 0 .and. grp(:, g) <= ni) .and. any(grp(:, g) > ni)) then
          mixed_blocks = .true.
          return
       end if
    end do
  end function mixed_blocks

  pure logical function keeps_dofs(q, grp)
    !! Whether Q maps every node block's active components onto themselves.
    real(wp), intent(in) :: q(3, 3)
    integer, intent(in) :: grp(:, :)
    integer :: g, a, b
    keeps_dofs = .true.
    do g = 1, size(grp, 2)
       do a = 1, BLOCK
          do b = 1, BLOCK
             if ((grp(a, g) > 0) .eqv. (grp(b, g) > 0)) cycle
             if (abs(q(a, b)) > ROT_ZERO) then
                keeps_dofs = .false.
                return
             end if
          end do
       end do
    end do
  end function keeps_dofs

  subroutine rotate_local(view, x, forward)
    !! x ← R̂ x (forward) or R̂ᵀ x, rows in local numbering.
    type(part_view_t), intent(in) :: view
    real(wp), intent(inout) :: x(:, :)
    logical, intent(in) :: forward
    call rotate_rows(view, x, 0_i8, forward)
  end subroutine rotate_local

  subroutine rotate_rows(view, x, offset, forward)
    !! Rotate the rows of x that hold local DOFs offset+1.. (the boundary rows
    !! alone with offset = ni: row r of x is local DOF r + offset). A node
    !! block's absent components enter as zeros (the same sums as leaving
    !! them out: y starts at +0) and are not written.
    type(part_view_t), intent(in) :: view
    real(wp), intent(inout) :: x(:, :)
    integer(i8), intent(in) :: offset
    logical, intent(in) :: forward
    real(wp) :: q(3, 3), y(BLOCK), z(BLOCK)
    integer(i8), allocatable :: rows(:, :)
    logical, allocatable :: on(:, :)
    integer :: g, a, c, n
    q = view%q
    if (.not. forward) q = transpose(q)
    allocate (rows(BLOCK, size(view%grp, 2)), on(BLOCK, size(view%grp, 2)))
    n = 0
    do g = 1, size(view%grp, 2)
       if (any(view%grp(:, g) > 0 .and. view%grp(:, g) <= offset)) cycle
       n = n + 1
       on(:, n) = view%grp(:, g) > 0
       rows(:, n) = merge(view%grp(:, g) - offset, 1_i8, on(:, n))
    end do
    do c = 1, size(x, 2)
       do g = 1, n
          z = merge(x(rows(:, g), c), 0.0_wp, on(:, g))
          do a = 1, BLOCK
             y(a) = 0.0_wp + q(a, 1)*z(1) + q(a, 2)*z(2) + q(a, 3)*z(3)
          end do
          do a = 1, BLOCK
             if (on(a, g)) x(rows(a, g), c) = y(a)
          end do
       end do
    end do
  end subroutine rotate_rows

  subroutine rotate_boundary_columns(view, k, forward)
    !! k(:, :) rows are boundary DOFs: k ← R̂_b k (forward) or R̂_bᵀ k.
    type(part_view_t), intent(in) :: view
    real(wp), intent(inout) :: k(:, :)
    logical, intent(in) :: forward
    call rotate_rows(view, k, view%ni, forward)
  end subroutine rotate_boundary_columns
end module superjoin_substructure_cache
