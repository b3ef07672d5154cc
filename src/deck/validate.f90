module superjoin_deck_validate
  !! Validation pass of the deck reader: resolves the names and user ids that the
  !! parser collected into indices, checks the model (duplicates, undefined
  !! nodes, sets, sections, contacts, supports, loads) and fills model_t.
  !! build_model runs the builders in order: superjoin_deck_build_subs,
  !! _build_sections, _assembly (instances), _build_contacts (and supports),
  !! _build_interfaces, _build_steps, _assembly (*CHANGE CONTACT), then the
  !! combinations and output requests (helpers shared by the builders:
  !! _build_common).
  use superjoin_model_types, only: model_t
  use superjoin_deck_state, only: deck_state_t, report, report_loc, SUBK_INSTANCE, SUBK_NESTED
  use superjoin_deck_nesting, only: unfold_nested
  use superjoin_deck_path_sets, only: place_path_sets
  use superjoin_deck_part_copies, only: copy_part_constraints
  use superjoin_deck_requests, only: build_requests
  use superjoin_deck_build_section_prints, only: build_section_prints
  use superjoin_deck_combinations, only: build_combinations
  use superjoin_deck_eccentric, only: check_offset_masters
  use superjoin_deck_build_subs, only: build_sub
  use superjoin_deck_assembly, only: empty_sub, place_instances, build_overrides
  use superjoin_deck_build_interfaces, only: build_interfaces
  use superjoin_deck_build_sections, only: build_sections, check_unassigned
  use superjoin_deck_build_contacts, only: build_contacts, build_supports
  use superjoin_deck_build_steps, only: build_steps
  use superjoin_deck_matrix_input, only: build_exports, build_given
  implicit none (type, external)
  private

  public :: build_model

contains

  subroutine build_model(st, model)
    !! Resolve everything collected in `st` and fill `model`. Errors go to st%error.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(out) :: model
    integer :: k

    model%files = st%files(1:st%nfile)
    if (st%nheading > 0) then
       model%heading = st%heading(1:st%nheading)
    else
       allocate (model%heading(0))
    end if
    model%controls = st%controls
    if (allocated(st%vtk_path)) model%vtk_path = st%vtk_path

    ! materials
    if (st%nmat > 0) then
       model%materials = st%materials(1:st%nmat)
    else
       allocate (model%materials(0))
    end if
    do k = 1, st%nmat
       if (.not. st%materials(k)%has_elastic) call report_loc(st, st%materials(k)%loc, &
            'material '//st%materials(k)%name//' has no *ELASTIC')
    end do

    ! orientations
    if (st%norient > 0) then
       model%orientations = st%orientations(1:st%norient)
    else
       allocate (model%orientations(0))
    end if

    ! substructures (parts made of parts unfolded into instances first)
    call unfold_nested(st)
    if (st%aborted) return
    call place_path_sets(st)   ! *NSET/*ELSET, INSTANCE=B.F3.BAY2: to the unfolded instance
    call copy_part_constraints(st)
    allocate (model%subs(st%nsub))
    if (st%nsub == 0) call report(st, 1, 1, 'the deck defines no nodes')
    do k = 1, st%nsub
       if (st%subs(k)%kind == SUBK_INSTANCE .or. st%subs(k)%kind == SUBK_NESTED) then
          call empty_sub(st%subs(k), model%subs(k))
          cycle
       end if
       call build_sub(st, st%subs(k), model%subs(k))
       if (st%aborted) return
       if (allocated(st%subs(k)%given)) call build_given(st, st%subs(k)%given, model%subs(k))
    end do
    call build_sections(st, model)
    if (st%aborted) return
    call check_unassigned(st, model)
    call place_instances(st, model)
    if (st%aborted) return
    call build_exports(st, model)
    call build_contacts(st, model)
    if (st%aborted) return
    call build_interfaces(st, model)
    if (st%aborted) return
    call build_supports(st, model)
    if (st%aborted) return
    call check_offset_masters(st, model)
    call build_steps(st, model)
    if (st%aborted) return
    call build_overrides(st, model)
    call build_combinations(st, model)
    call build_requests(st, model)
    call build_section_prints(st, model)
  end subroutine build_model
end module superjoin_deck_validate
