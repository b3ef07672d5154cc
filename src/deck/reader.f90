module superjoin_deck_reader
  !! Deck reader facade: read, parse and validate a superjoin deck (see
  !! doc/deck.md and the deck contract) into a model_t. Every problem found is
  !! reported as one `path:line: error: message` line of the returned error
  !! (exit status EXIT_DECK), up to a cap; library code never stops.
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_kinds, only: i8
  use superjoin_utils_memory, only: oom_message
  use superjoin_model_types, only: model_t
  use superjoin_deck_lexer, only: load_file, path_normalize
  use superjoin_deck_state, only: deck_state_t
  use superjoin_deck_parser, only: parse_source, finish_parse, register_file
  use superjoin_deck_validate, only: build_model
  use superjoin_deck_axisym_supports, only: check_axisymmetric_supports
  use superjoin_deck_equation_build, only: build_equations, equations_to_global
  use superjoin_deck_tie_build, only: build_ties
  use superjoin_deck_coupling_build, only: build_couplings
  use superjoin_deck_pretension, only: build_pretensions
  use superjoin_deck_frame_build, only: build_frames, link_frames
  use superjoin_deck_matrix_loads, only: build_matrix_loads
  use superjoin_elements_drill_mask, only: mark_drilling_edges
  use superjoin_deck_thickness_build, only: apply_nodal_thickness
  implicit none (type, external)
  private

  public :: read_deck, read_deck_string

contains

  subroutine read_deck(path, model, error, dialect)
    !! Read, parse and validate a deck file into a model; all deck errors
    !! collected in error (code EXIT_DECK; EXIT_IO when the file cannot be read).
    !! dialect (DIALECT_*): whose reading holds where Abaqus and CalculiX
    !! differ when the deck declares none (*CONTROLS, DIALECT=); ccx -i JOB
    !! reads a CalculiX deck.
    character(*), intent(in) :: path
    type(model_t), intent(out) :: model
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: dialect
    character(:), allocatable :: text
    logical :: ok
    integer(i8) :: need
    call load_file(path, text, ok, need)
    if (need > 0) then
       call fatal_error(error, EXIT_IO, path//': '//oom_message('reading the deck', need))
       return
    end if
    if (.not. ok) then
       call fatal_error(error, EXIT_IO, path//': error: cannot open deck file')
       return
    end if
    call read_deck_string(text, path, model, error, dialect)
  end subroutine read_deck

  subroutine read_deck_string(text, name, model, error, dialect)
    !! Same as read_deck but from text in memory (lines separated by LF, CR LF or
    !! CR); `name` is the file name used in messages and for resolving *INCLUDE
    !! relative paths (relative to the directory of name).
    character(*), intent(in) :: text, name
    type(model_t), intent(out) :: model
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: dialect
    type(deck_state_t) :: st
    integer :: file
    if (present(dialect)) st%implied_dialect = dialect
    call register_file(st, name, path_normalize(name), file)
    st%depth = 0
    st%stack(0) = file
    call parse_source(st, text, file)
    if (.not. st%aborted) call finish_parse(st)
    if (st%restart_read .and. allocated(st%error)) then   ! *RESTART, READ (refused): the model is not in the deck
       call move_alloc(st%error, error)
       return
    end if
    if (.not. st%aborted) call build_model(st, model)
    if (.not. st%aborted) call check_axisymmetric_supports(st, model)
    if (.not. st%aborted) call build_equations(st, model)
    if (.not. st%aborted) call build_ties(st, model)
    if (.not. st%aborted) call build_couplings(st, model)
    if (.not. st%aborted) call build_pretensions(st, model)
    if (.not. st%aborted) call build_frames(st, model)
    ! global components, as the matrix: after build_frames turned the *CLOAD lines
    if (.not. st%aborted) call build_matrix_loads(st, model)
    if (.not. st%aborted) call equations_to_global(model)
    if (.not. st%aborted) call link_frames(st, model)
    if (.not. st%aborted) call apply_nodal_thickness(st, model)
    if (.not. st%aborted .and. .not. allocated(st%error)) call mark_drilling_edges(model)
    if (allocated(st%error)) call move_alloc(st%error, error)
  end subroutine read_deck_string
end module superjoin_deck_reader
