module superjoin_deck_element_removal
  !! Removing one element from a built model (CalculiX's beam bolt of
  !! *PRE-TENSION SECTION, ELEMENT=: the element is replaced by an equation).
  !! Every local element index after it moves down by one: the element arrays,
  !! the element sets, the distributed loads of the steps, the element output
  !! requests and the *SECTION PRINT faces; the element's own loads and set
  !! entries go with it.
  use superjoin_kinds, only: ip
  use superjoin_model_types, only: model_t, step_t, dload_t, REQ_EL_PRINT, REQ_EL_FILE
  implicit none (type, external)
  private

  public :: remove_element

contains

  subroutine remove_element(model, s, e, ndropped)
    !! Remove local element e of substructure s from the model; ndropped: the
    !! distributed loads of e in the steps, which went with it.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: s
    integer(ip), intent(in) :: e
    integer, intent(out) :: ndropped
    logical, allocatable :: keep(:)
    integer :: k
    associate (sub => model%subs(s))
      allocate (keep(sub%nelem), source=.true.)
      keep(e) = .false.
      sub%elem_id = pack(sub%elem_id, keep)
      sub%elem_type = pack(sub%elem_type, keep)
      sub%elem_nodes = sub%elem_nodes(:, pack([(k, k = 1, size(keep))], keep))
      sub%elem_loc = pack(sub%elem_loc, keep)
      if (allocated(sub%elem_section)) sub%elem_section = pack(sub%elem_section, keep)
      if (allocated(sub%elem_drill)) sub%elem_drill = pack(sub%elem_drill, keep)
      sub%nelem = sub%nelem - 1
      call drop_index(sub%elem_order, e)
      do k = 1, size(sub%elsets)
         call drop_index(sub%elsets(k)%items, e)
      end do
    end associate
    ndropped = 0
    if (allocated(model%steps)) then
       do k = 1, size(model%steps)
          if (allocated(model%steps(k)%dloads)) call drop_dloads(model%steps(k), s, e, ndropped)
       end do
    end if
    if (allocated(model%requests)) then
       do k = 1, size(model%requests)
          associate (r => model%requests(k))
            if (r%kind /= REQ_EL_PRINT .and. r%kind /= REQ_EL_FILE) cycle
            if (r%sub == s .and. allocated(r%items)) call drop_index(r%items, e)
          end associate
       end do
    end if
    if (allocated(model%section_prints)) then
       do k = 1, size(model%section_prints)
          associate (sp => model%section_prints(k))
            where (sp%subs == s .and. sp%elems > e) sp%elems = sp%elems - 1
          end associate
       end do
    end if
  end subroutine remove_element

  pure subroutine drop_index(items, e)
    !! Local element indices: e left out, those after it one lower.
    integer(ip), allocatable, intent(inout) :: items(:)
    integer(ip), intent(in) :: e
    if (.not. allocated(items)) return
    items = pack(items, items /= e)
    where (items > e) items = items - 1
  end subroutine drop_index

  subroutine drop_dloads(step, s, e, ndropped)
    !! A step's distributed loads: those of element e of s left out (and from
    !! the count continued from the previous step; ndropped counts the ones
    !! the step itself gave), the others renumbered.
    type(step_t), intent(inout) :: step
    integer, intent(in) :: s
    integer(ip), intent(in) :: e
    integer, intent(inout) :: ndropped
    logical, allocatable :: keep(:)
    type(dload_t), allocatable :: kept(:)
    integer :: k
    allocate (keep(size(step%dloads)))
    keep = .not. (step%dloads(:)%sub == s .and. step%dloads(:)%elem == e)
    ndropped = ndropped + count(.not. keep(min(step%kept_dloads, size(keep)) + 1:))
    step%kept_dloads = step%kept_dloads - count(.not. keep(1:min(step%kept_dloads, size(keep))))
    kept = pack(step%dloads, keep)
    do k = 1, size(kept)
       if (kept(k)%sub == s .and. kept(k)%elem > e) kept(k)%elem = kept(k)%elem - 1
    end do
    call move_alloc(kept, step%dloads)
  end subroutine drop_dloads
end module superjoin_deck_element_removal
