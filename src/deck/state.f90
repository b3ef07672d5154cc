module superjoin_deck_state
  !! Working state of the deck reader: what the parser has collected so far
  !! (still by user ids and names), the card being read, and the error list
  !! (capped). The validation pass turns this state into a model_t.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_error, only: error_t, add_error_line, EXIT_DECK, EXIT_IO
  use superjoin_utils_memory, only: oom_message, BYTES_REAL, BYTES_INT
  use superjoin_model_types, only: string_t, source_loc_t, material_t, orientation_t, section_print_t, &
       controls_t, MAX_ELEMENT_NODES, NDOF_NODE, LINK_NONE, DIALECT_NONE
  use superjoin_deck_lexer, only: itoa, fields_t, load_file
  use superjoin_utils_grow, only: grow
  use superjoin_utils_huge_pages, only: advise_huge
  use superjoin_deck_records, only: SHAPE_GENERAL, BEAM_2D_VALUES, BEAM_3D_VALUES, CH_IDS, CH_GEN, &
       CH_RANGE, CH_REF, chunk_t, set_b_t, sub_b_t, ref_t, sec_b_t, contact_b_t, cline_b_t, &
       equation_b_t, transform_b_t, nthick_b_t, support_b_t, load_b_t, SUBK_PLAIN, SUBK_PART, &
       SUBK_INSTANCE, SUBK_NESTED, MAIN_NAME, instance_b_t, override_b_t, step_b_t, temp_b_t, surface_b_t, tie_b_t, pretension_b_t, &
       combo_b_t, &
       OP_DEFAULT, OP_MOD, OP_NEW, request_b_t, SPRING_1, SPRING_2, SPRING_A, ASSEMBLY_SPRINGS, spring_elem_b_t, &
       spring_card_b_t, given_b_t, export_b_t, amplitude_b_t, amp_use_b_t, sec_controls_b_t
  use superjoin_deck_coupling_records, only: coupling_b_t
  implicit none (type, external)
  private

  public :: grow
  interface grow
     !! Make room for element n + 1 of an allocatable array (grow_template.inc).
     module procedure grow_sub_b, grow_set_b, grow_chunk, grow_string, grow_material, grow_orientation, grow_sec_b, grow_contact_b, grow_cline_b, grow_step_b, grow_load_b, grow_request_b, grow_spring_elem_b, grow_spring_card_b, grow_nthick_b, grow_transform_b, grow_equation_b, grow_temp_b, grow_surface_b, grow_combo_b, grow_instance_b, grow_override_b, grow_source_loc, grow_amp_use_b, grow_sec_controls_b
  end interface grow

  integer, parameter, public :: MAX_ERRORS = 50          !! messages before '... too many errors'
  integer, parameter, public :: MAX_INCLUDE_DEPTH = 16   !! nested *INCLUDE levels
  integer, parameter :: INITIAL_CAPACITY = 16

  ! the records of the cards (superjoin_deck_records), passed on to the users of the state
  public :: SHAPE_GENERAL, BEAM_2D_VALUES, BEAM_3D_VALUES, CH_IDS, CH_GEN, CH_RANGE, CH_REF, &
       chunk_t, set_b_t, sub_b_t, ref_t, sec_b_t, contact_b_t, cline_b_t, equation_b_t, &
       transform_b_t, nthick_b_t, support_b_t, load_b_t, SUBK_PLAIN, SUBK_PART, SUBK_INSTANCE, &
       SUBK_NESTED, MAIN_NAME, instance_b_t, override_b_t, step_b_t, temp_b_t, surface_b_t, tie_b_t, combo_b_t, OP_DEFAULT, OP_MOD, &
       OP_NEW, request_b_t, SPRING_1, SPRING_2, SPRING_A, ASSEMBLY_SPRINGS, spring_elem_b_t, spring_card_b_t, given_b_t, &
       export_b_t, amplitude_b_t, amp_use_b_t, sec_controls_b_t

  type, public :: deck_state_t
    !! Everything the reader has collected, and the card being read.
     type(error_t), allocatable :: error
     integer :: nerr = 0
     logical :: aborted = .false.
     logical :: restart_read = .false.   !! *RESTART, READ: the model is in another run's restart data (refused)
     ! files
     integer :: nfile = 0
     type(string_t), allocatable :: files(:)
     type(string_t), allocatable :: norm_files(:)   !! normalized, for cycle detection
     integer :: depth = 0
     integer :: stack(0:MAX_INCLUDE_DEPTH) = 0      !! open files, outermost first
     ! model data
     integer :: nheading = 0
     type(string_t), allocatable :: heading(:)
     integer :: nmat = 0
     type(material_t), allocatable :: materials(:)
     integer :: nsub = 0
     type(sub_b_t), allocatable :: subs(:)
     integer :: norient = 0
     type(orientation_t), allocatable :: orientations(:)
     integer :: nsec = 0
     type(sec_b_t), allocatable :: sections(:)
     integer :: nsec_controls = 0
     type(sec_controls_b_t), allocatable :: sec_controls(:)   !! *SECTION CONTROLS cards (Abaqus)
     integer :: ncontact = 0
     type(contact_b_t), allocatable :: contacts(:)
     integer :: ncline = 0
     type(cline_b_t), allocatable :: clines(:)
     integer :: nsupport = 0
     type(support_b_t), allocatable :: supports(:)
     integer :: ntransform = 0
     type(transform_b_t), allocatable :: transforms(:) !! *TRANSFORM cards as read
     integer :: nnthick = 0
     type(nthick_b_t), allocatable :: nthicks(:)       !! *NODAL THICKNESS data lines as read
     integer :: nequation = 0
     type(equation_b_t), allocatable :: equations(:)   !! *EQUATION constraints as read
     type(coupling_b_t), allocatable :: couplings(:)   !! *COUPLING, *RIGID BODY, *MPC as read (unallocated: none)
     integer :: open_coupling = 0                      !! the *COUPLING card just read (0: the last keyword was another)
     character(:), allocatable :: dcoup_set            !! the element set of the DCOUP3D card being read
     integer :: nstep = 0
     type(step_b_t), allocatable :: steps(:)
     type(controls_t) :: controls
     integer :: implied_dialect = 0            !! DIALECT_* of the run where the deck declares none (0: none)
     type(string_t), allocatable :: notes(:)   !! notes for the listing met before the model exists
     character(:), allocatable :: vtk_path          !! *OUTPUT, VTK= resolved against its file's directory
     type(source_loc_t) :: vtk_loc
     integer :: nreq = 0                            !! output request cards
     type(request_b_t), allocatable :: requests(:)
     integer :: step_procedure = 0                  !! procedure card of the open step (0: none yet)
     type(source_loc_t) :: step_procedure_loc
     integer :: nspring_elem = 0, nspring_card = 0  !! spring elements and *SPRING cards
     type(spring_elem_b_t), allocatable :: spring_elems(:)
     type(spring_card_b_t), allocatable :: spring_cards(:)
     character(:), allocatable :: spring_elset      !! ELSET= of the open spring *ELEMENT card
     integer :: nelem_cards = 0
     integer :: ninst = 0
     integer :: nassembly_sets = 0   !! assembly-level sets (*NSET or *ELSET with INSTANCE=) begun so far (set_b_t%order)
     type(instance_b_t), allocatable :: instances(:)
     integer :: ntemp = 0                           !! temperature lines
     type(temp_b_t), allocatable :: temps(:)
     integer :: ncombo = 0                          !! *LOAD COMBINATION cards
     integer :: nsurface = 0                        !! *SURFACE cards
     type(surface_b_t), allocatable :: surfaces(:)
     type(section_print_t), allocatable :: section_prints(:)  !! *SECTION PRINT cards (faces resolved later)
     type(tie_b_t), allocatable :: ties(:)          !! *TIE cards (unallocated: none)
     type(pretension_b_t), allocatable :: pretensions(:)  !! *PRE-TENSION SECTION cards (unallocated: none)
     type(combo_b_t), allocatable :: combos(:)
     logical :: section_rejected(3) = .false.  !! a *SOLID, *BEAM or *SHELL SECTION card (SEC_* index) was rejected
     logical :: elements_refused = .false.
       !! an *ELEMENT card of an unsupported type was refused: the element sets
       !! and sections it leaves empty are not reported again
     ! block and card state
     integer :: cur_inst = 0               !! open *INSTANCE block
     logical :: in_assembly = .false.      !! inside *ASSEMBLY ... *END ASSEMBLY
     type(source_loc_t) :: assembly_loc
     integer :: cur_sub = 0                !! open *SUBSTRUCTURE block
     integer :: cur_step = 0               !! open *STEP block
     integer :: cur_mat = 0                !! material that *ELASTIC applies to
     integer :: cur_beam_sec = 0           !! *BEAM SECTION that *TRANSVERSE SHEAR STIFFNESS applies to
     integer :: loose_step = 0             !! step collecting loads outside *STEP
     type(source_loc_t) :: loose_loc
     logical :: mix_reported = .false.
     integer :: nstep_cards = 0
     integer :: card = 0                   !! CARD_* of the parser
     character(:), allocatable :: card_name
     type(source_loc_t) :: card_loc
     integer :: card_ndata = 0
     integer :: card_sub = 0
     integer :: card_set = 0
     integer :: card_chunk = 0
     integer :: card_etype = 0
     character(:), allocatable :: elem_pending  !! *ELEMENT: a data line ended by a comma, continued on the next
     integer :: card_item = 0              !! section, contact, material or orientation index
     integer :: card_home = 0
     logical :: card_generate = .false.
     logical :: card_fixed = .false.       !! *BOUNDARY, FIXED: its DOFs held at the previous step's displacements
     character(:), allocatable :: card_amp !! AMPLITUDE= of the load or *BOUNDARY card being read (unallocated: none)
     type(amplitude_b_t), allocatable :: amps(:)      !! *AMPLITUDE cards (unallocated: none)
     type(amp_use_b_t), allocatable :: amp_uses(:)    !! data lines of cards with AMPLITUDE= (superjoin_deck_amplitudes)
     integer :: namp_use = 0
     type(override_b_t) :: change_card     !! *CHANGE CONTACT being read: what its data lines share
     type(fields_t) :: f                   !! fields of the current data line (reused)
     type(export_b_t), allocatable :: exports(:)  !! *SUBSTRUCTURE MATRIX OUTPUT cards (unallocated: none)
  end type deck_state_t

  public :: register_file, load_deck_file
  public :: report, report_loc, report_oom, memory_ok, new_sub, find_sub, instance_part, find_set, new_set, add_chunk, push_pool
  public :: add_node, add_element, add_heading, add_material, add_orientation, add_section, add_sec_controls
  public :: add_contact, add_cline, add_support, add_step, add_load, file_of
  public :: add_request, add_request_var, add_spring_elem, add_spring_card
  public :: reading_dialect

contains

  pure integer function reading_dialect(st)
    !! DIALECT_* whose reading the deck takes where Abaqus and CalculiX differ:
    !! its *CONTROLS, DIALECT=, else the run's (CalculiX for ccx -i), else none.
    type(deck_state_t), intent(in) :: st
    reading_dialect = st%controls%dialect
    if (reading_dialect == DIALECT_NONE) reading_dialect = st%implied_dialect
  end function reading_dialect

  ! ------------------------------------------------------------------ errors

  subroutine register_file(st, path, norm, k)
    !! Index of file `path` in the state's file list (added if new); `norm` is
    !! the normalized path used to detect include cycles.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: path, norm
    integer, intent(out) :: k
    integer, parameter :: INITIAL_FILES = 4
    do k = 1, st%nfile
       if (st%norm_files(k)%s == norm) return
    end do
    call grow(st%files, st%nfile, INITIAL_FILES)
    call grow(st%norm_files, st%nfile, INITIAL_FILES)
    st%nfile = st%nfile + 1
    k = st%nfile
    st%files(k)%s = path
    st%norm_files(k)%s = norm
  end subroutine register_file

  subroutine load_deck_file(st, loc, path, what, text, ok)
    !! The whole of file `path` that the card at loc names (an include or a
    !! matrix file); a file that cannot be opened or held is reported at loc.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: path, what
    character(:), allocatable, intent(out) :: text
    logical, intent(out) :: ok
    integer(i8) :: need
    call load_file(path, text, ok, need)
    if (need > 0) then
       call report_oom(st, loc, 'reading '//what//' file '''//path//'''', need)
       ok = .false.
    else if (.not. ok) then
       call report_loc(st, loc, 'cannot open '//what//' file '''//path//'''')
    end if
  end subroutine load_deck_file

  subroutine report(st, file, line, message)
    !! Add `path:line: error: message` (at most MAX_ERRORS messages; after that
    !! one '... too many errors' line and the reader stops).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: file, line
    character(*), intent(in) :: message
    if (st%aborted) return
    st%nerr = st%nerr + 1
    if (st%nerr > MAX_ERRORS) then
       call add_error_line(st%error, EXIT_DECK, '... too many errors')
       st%aborted = .true.
       return
    end if
    call add_error_line(st%error, EXIT_DECK, file_of(st, file)//':'//itoa(line)//': error: '//message)
  end subroutine report

  subroutine report_oom(st, loc, what, nbytes)
    !! Out of memory while reading: `path:line: error: out of memory: ...`,
    !! exit status EXIT_IO, and the reader stops.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: what
    integer(i8), intent(in) :: nbytes
    if (st%aborted) return
    call add_error_line(st%error, EXIT_IO, file_of(st, loc%file)//':'//itoa(loc%line)//': '// &
         oom_message(what, nbytes))
    st%error%code = EXIT_IO
    st%aborted = .true.
  end subroutine report_oom

  logical function memory_ok(st, stat, loc, what, nbytes) result(ok)
    !! The stat= of a checked allocation: nonzero is reported as out of memory
    !! at loc (report_oom: exit status EXIT_IO, the reader stops).
    type(deck_state_t), intent(inout) :: st
    integer, intent(in) :: stat
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: what
    integer(i8), intent(in) :: nbytes
    ok = stat == 0
    if (.not. ok) call report_oom(st, loc, what, nbytes)
  end function memory_ok

  subroutine report_loc(st, loc, message)
    !! report() at a source location.
    type(deck_state_t), intent(inout) :: st
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: message
    call report(st, loc%file, loc%line, message)
  end subroutine report_loc

  function file_of(st, file) result(path)
    !! Path of file index `file` as used in messages.
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: file
    character(:), allocatable :: path
    if (file >= 1 .and. file <= st%nfile) then
       path = st%files(file)%s
    else
       path = '<input>'
    end if
  end function file_of

  ! ------------------------------------------------------------------ substructures and sets

  integer function instance_part(st, k) result(p)
    !! The part (index in subs) that entry k places (0: k is no instance or its part is unknown).
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: k
    integer :: j
    p = 0
    if (st%subs(k)%kind /= SUBK_INSTANCE .or. st%subs(k)%inst <= 0) return
    do j = 1, st%nsub   ! the last part of that name, as the placement takes it
       if (st%subs(j)%kind == SUBK_PART .and. st%subs(j)%name == st%instances(st%subs(k)%inst)%part) p = j
    end do
  end function instance_part

  integer function find_sub(st, name) result(k)
    !! Index of the substructure named `name` (0 if none; the last one if repeated).
    type(deck_state_t), intent(in) :: st
    character(*), intent(in) :: name
    do k = st%nsub, 1, -1
       if (st%subs(k)%kind == SUBK_PART .or. st%subs(k)%kind == SUBK_NESTED) cycle
       if (st%subs(k)%name == name) return
    end do
    k = 0
  end function find_sub

  subroutine new_sub(st, name, loc, k)
    !! Append a new, empty substructure.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    call grow(st%subs, st%nsub, INITIAL_CAPACITY)
    st%nsub = st%nsub + 1
    k = st%nsub
    st%subs(k)%name = name
    st%subs(k)%loc = loc
    allocate (st%subs(k)%node_id(INITIAL_CAPACITY), st%subs(k)%x(3, INITIAL_CAPACITY), &
         st%subs(k)%node_loc(INITIAL_CAPACITY))
    allocate (st%subs(k)%elem_id(INITIAL_CAPACITY), st%subs(k)%elem_type(INITIAL_CAPACITY), &
         st%subs(k)%elem_nid(MAX_ELEMENT_NODES, INITIAL_CAPACITY), &
         st%subs(k)%elem_loc(INITIAL_CAPACITY), st%subs(k)%elem_card(INITIAL_CAPACITY))
    allocate (st%subs(k)%nsets(INITIAL_CAPACITY), st%subs(k)%elsets(INITIAL_CAPACITY))
    allocate (st%subs(k)%chunks(INITIAL_CAPACITY), st%subs(k)%pool(INITIAL_CAPACITY))
  end subroutine new_sub

  integer function find_set(sub, name, elem) result(k)
    !! Index of the node set (elem = .false.) or element set named `name` in a substructure (0 if none).
    type(sub_b_t), intent(in) :: sub
    character(*), intent(in) :: name
    logical, intent(in) :: elem
    if (elem) then
       do k = 1, sub%nelset
          if (sub%elsets(k)%name == name) return
       end do
    else
       do k = 1, sub%nnset
          if (sub%nsets(k)%name == name) return
       end do
    end if
    k = 0
  end function find_set

  subroutine new_set(sub, name, elem, loc, k)
    !! Append a new, empty set to a substructure.
    type(sub_b_t), intent(inout) :: sub
    character(*), intent(in) :: name
    logical, intent(in) :: elem
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    if (elem) then
       call grow(sub%elsets, sub%nelset, INITIAL_CAPACITY)
       sub%nelset = sub%nelset + 1
       k = sub%nelset
       sub%elsets(k)%name = name
       sub%elsets(k)%loc = loc
    else
       call grow(sub%nsets, sub%nnset, INITIAL_CAPACITY)
       sub%nnset = sub%nnset + 1
       k = sub%nnset
       sub%nsets(k)%name = name
       sub%nsets(k)%loc = loc
    end if
  end subroutine new_set

  subroutine add_chunk(sub, set, elem, kind, loc, k)
    !! Append a chunk to a substructure; `k` is its index.
    type(sub_b_t), intent(inout) :: sub
    integer, intent(in) :: set, kind
    logical, intent(in) :: elem
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    call grow(sub%chunks, sub%nchunk, INITIAL_CAPACITY)
    sub%nchunk = sub%nchunk + 1
    k = sub%nchunk
    sub%chunks(k)%set = set
    sub%chunks(k)%elem = elem
    sub%chunks(k)%kind = kind
    sub%chunks(k)%loc = loc
    sub%chunks(k)%start = 0
    sub%chunks(k)%count = 0
  end subroutine add_chunk

  subroutine push_pool(sub, id)
    !! Append an id to the pool of explicit set members.
    type(sub_b_t), intent(inout) :: sub
    integer(ip), intent(in) :: id
    call grow(sub%pool, sub%npool, INITIAL_CAPACITY)
    sub%npool = sub%npool + 1
    sub%pool(sub%npool) = id
  end subroutine push_pool

  subroutine add_node(sub, id, x, loc, failed_bytes)
    !! Append a node. failed_bytes > 0: the arrays could not grow (that many bytes).
    type(sub_b_t), intent(inout) :: sub
    integer(ip), intent(in) :: id
    real(wp), intent(in) :: x(3)
    type(source_loc_t), intent(in) :: loc
    integer(i8), intent(out) :: failed_bytes
    integer(ip) :: n
    integer :: stat
    failed_bytes = 0
    n = sub%nnode
    if (n == huge(n)) then
       failed_bytes = huge(failed_bytes)
       return
    end if
    if (n == size(sub%node_id)) then
       block
         integer(ip), allocatable :: ti(:)
         real(wp), allocatable :: tx(:, :)
         type(source_loc_t), allocatable :: tl(:)
         integer(ip) :: cap
         cap = int(min(2_i8*n, int(huge(n), i8)), ip)
         allocate (ti(cap), tx(3, cap), tl(cap), stat=stat)
         if (stat /= 0) then
            failed_bytes = cap*(BYTES_INT + 3*BYTES_REAL + storage_size(loc)/8)
            return
         end if
         call advise_huge(tx)   ! before its first write (large decks: fewer page faults)
         ti(1:n) = sub%node_id(1:n)
         tx(:, 1:n) = sub%x(:, 1:n)
         tl(1:n) = sub%node_loc(1:n)
         call move_alloc(ti, sub%node_id)
         call move_alloc(tx, sub%x)
         call move_alloc(tl, sub%node_loc)
       end block
    end if
    n = n + 1
    sub%nnode = n
    sub%node_id(n) = id
    sub%x(:, n) = x
    sub%node_loc(n) = loc
  end subroutine add_node

  subroutine add_element(sub, id, etype, nid, loc, card, failed_bytes)
    !! Append an element (nodes by user id). failed_bytes > 0: the arrays
    !! could not grow (that many bytes).
    type(sub_b_t), intent(inout) :: sub
    integer(ip), intent(in) :: id
    integer, intent(in) :: etype, card
    integer(ip), intent(in) :: nid(MAX_ELEMENT_NODES)
    type(source_loc_t), intent(in) :: loc
    integer(i8), intent(out) :: failed_bytes
    integer(ip) :: n
    integer :: stat
    failed_bytes = 0
    n = sub%nelem
    if (n == huge(n)) then
       failed_bytes = huge(failed_bytes)
       return
    end if
    if (n == size(sub%elem_id)) then
       block
         integer(ip), allocatable :: ti(:), tn(:, :)
         integer, allocatable :: tt(:), tc(:)
         type(source_loc_t), allocatable :: tl(:)
         integer(ip) :: cap
         cap = int(min(2_i8*n, int(huge(n), i8)), ip)
         allocate (ti(cap), tn(MAX_ELEMENT_NODES, cap), tt(cap), tc(cap), tl(cap), stat=stat)
         if (stat /= 0) then
            failed_bytes = cap*((3 + MAX_ELEMENT_NODES)*BYTES_INT + storage_size(loc)/8)
            return
         end if
         call advise_huge(tn)   ! before its first write (large decks: fewer page faults)
         ti(1:n) = sub%elem_id(1:n)
         tn(:, 1:n) = sub%elem_nid(:, 1:n)
         tt(1:n) = sub%elem_type(1:n)
         tc(1:n) = sub%elem_card(1:n)
         tl(1:n) = sub%elem_loc(1:n)
         call move_alloc(ti, sub%elem_id)
         call move_alloc(tn, sub%elem_nid)
         call move_alloc(tt, sub%elem_type)
         call move_alloc(tc, sub%elem_card)
         call move_alloc(tl, sub%elem_loc)
       end block
    end if
    n = n + 1
    sub%nelem = n
    sub%elem_id(n) = id
    sub%elem_type(n) = etype
    sub%elem_nid(:, n) = nid
    sub%elem_loc(n) = loc
    sub%elem_card(n) = card
  end subroutine add_element

  ! ------------------------------------------------------------------ model-level lists

  subroutine add_heading(st, text)
    !! Append a heading line.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: text
    call grow(st%heading, st%nheading, INITIAL_CAPACITY)
    st%nheading = st%nheading + 1
    st%heading(st%nheading)%s = text
  end subroutine add_heading

  subroutine add_material(st, name, loc, k)
    !! Append a material; `k` is its index.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    call grow(st%materials, st%nmat, INITIAL_CAPACITY)
    st%nmat = st%nmat + 1
    k = st%nmat
    st%materials(k)%name = name
    st%materials(k)%loc = loc
  end subroutine add_material

  subroutine add_orientation(st, name, loc, k)
    !! Append an orientation; `k` is its index.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    call grow(st%orientations, st%norient, INITIAL_CAPACITY)
    st%norient = st%norient + 1
    k = st%norient
    st%orientations(k)%name = name
    st%orientations(k)%loc = loc
  end subroutine add_orientation

  subroutine add_section(st, sec, k)
    !! Append a section; `k` is its index.
    type(deck_state_t), intent(inout) :: st
    type(sec_b_t), intent(in) :: sec
    integer, intent(out) :: k
    call grow(st%sections, st%nsec, INITIAL_CAPACITY)
    st%nsec = st%nsec + 1
    k = st%nsec
    st%sections(k) = sec
  end subroutine add_section

  subroutine add_sec_controls(st, c)
    !! Append a *SECTION CONTROLS card.
    type(deck_state_t), intent(inout) :: st
    type(sec_controls_b_t), intent(in) :: c
    call grow(st%sec_controls, st%nsec_controls, INITIAL_CAPACITY)
    st%nsec_controls = st%nsec_controls + 1
    st%sec_controls(st%nsec_controls) = c
  end subroutine add_sec_controls

  subroutine add_contact(st, c, k)
    !! Append a contact card; `k` is its index.
    type(deck_state_t), intent(inout) :: st
    type(contact_b_t), intent(in) :: c
    integer, intent(out) :: k
    call grow(st%contacts, st%ncontact, INITIAL_CAPACITY)
    st%ncontact = st%ncontact + 1
    k = st%ncontact
    st%contacts(k) = c
  end subroutine add_contact

  subroutine add_cline(st, c)
    !! Append a contact data line.
    type(deck_state_t), intent(inout) :: st
    type(cline_b_t), intent(in) :: c
    call grow(st%clines, st%ncline, INITIAL_CAPACITY)
    st%ncline = st%ncline + 1
    st%clines(st%ncline) = c
  end subroutine add_cline

  subroutine add_support(st, s)
    !! Append a support data line (out of memory: reported, reader stops).
    type(deck_state_t), intent(inout) :: st
    type(support_b_t), intent(in) :: s
    type(support_b_t), allocatable :: tmp(:)
    integer :: stat
    if (.not. allocated(st%supports)) allocate (st%supports(INITIAL_CAPACITY))
    if (st%nsupport == size(st%supports)) then
       allocate (tmp(2*st%nsupport), stat=stat)
       if (stat /= 0) then
          call report_oom(st, s%loc, 'the support lines ('//itoa(2*st%nsupport)//')', &
               2*int(st%nsupport, i8)*storage_size(s)/8)
          return
       end if
       tmp(1:st%nsupport) = st%supports(1:st%nsupport)
       call move_alloc(tmp, st%supports)
    end if
    st%nsupport = st%nsupport + 1
    st%supports(st%nsupport) = s
  end subroutine add_support

  subroutine add_step(st, name, loc, k)
    !! Append a step; `k` is its index.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name
    type(source_loc_t), intent(in) :: loc
    integer, intent(out) :: k
    call grow(st%steps, st%nstep, INITIAL_CAPACITY)
    st%nstep = st%nstep + 1
    k = st%nstep
    st%steps(k)%name = name
    st%steps(k)%loc = loc
    allocate (st%steps(k)%cloads(INITIAL_CAPACITY), st%steps(k)%dloads(INITIAL_CAPACITY))
  end subroutine add_step

  subroutine add_load(step, load, dload)
    !! Append a concentrated (dload = .false.) or distributed load to a step.
    type(step_b_t), intent(inout) :: step
    type(load_b_t), intent(in) :: load
    logical, intent(in) :: dload
    if (dload) then
       call grow(step%dloads, step%ndload, INITIAL_CAPACITY)
       step%ndload = step%ndload + 1
       step%dloads(step%ndload) = load
    else
       call grow(step%cloads, step%ncload, INITIAL_CAPACITY)
       step%ncload = step%ncload + 1
       step%cloads(step%ncload) = load
    end if
  end subroutine add_load

  ! ------------------------------------------------------------------ output requests

  subroutine add_request(st, r, k)
    !! Append an output request card; `k` is its index.
    type(deck_state_t), intent(inout) :: st
    type(request_b_t), intent(in) :: r
    integer, intent(out) :: k
    call grow(st%requests, st%nreq, INITIAL_CAPACITY)
    st%nreq = st%nreq + 1
    k = st%nreq
    st%requests(k) = r
    allocate (st%requests(k)%vars(INITIAL_CAPACITY), st%requests(k)%ignored(INITIAL_CAPACITY))
  end subroutine add_request

  subroutine add_request_var(r, name, produced)
    !! Add a variable to a request (kept once): to vars when superjoin produces
    !! it, else to ignored.
    type(request_b_t), intent(inout) :: r
    character(*), intent(in) :: name
    logical, intent(in) :: produced
    if (produced) then
       call push_name(r%vars, r%nvar)
    else
       call push_name(r%ignored, r%nignored)
    end if
  contains
    subroutine push_name(list, n)
      type(string_t), allocatable, intent(inout) :: list(:)
      integer, intent(inout) :: n
      integer :: i
      do i = 1, n
         if (list(i)%s == name) return
      end do
      call grow(list, n, INITIAL_CAPACITY)
      n = n + 1
      list(n)%s = name
    end subroutine push_name
  end subroutine add_request_var

  ! ------------------------------------------------------------------ springs

  subroutine add_spring_elem(st, e)
    !! Append a spring element.
    type(deck_state_t), intent(inout) :: st
    type(spring_elem_b_t), intent(in) :: e
    call grow(st%spring_elems, st%nspring_elem, INITIAL_CAPACITY)
    st%nspring_elem = st%nspring_elem + 1
    st%spring_elems(st%nspring_elem) = e
  end subroutine add_spring_elem

  subroutine add_spring_card(st, c, k)
    !! Append a *SPRING card; `k` is its index.
    type(deck_state_t), intent(inout) :: st
    type(spring_card_b_t), intent(in) :: c
    integer, intent(out) :: k
    call grow(st%spring_cards, st%nspring_card, INITIAL_CAPACITY)
    st%nspring_card = st%nspring_card + 1
    k = st%nspring_card
    st%spring_cards(k) = c
  end subroutine add_spring_card

  ! ------------------------------------------------------------------ growing arrays

#define GROW_NAME grow_sub_b
#define GROW_TYPE type(sub_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_set_b
#define GROW_TYPE type(set_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_chunk
#define GROW_TYPE type(chunk_t)
#include "grow_template.inc"

#define GROW_NAME grow_string
#define GROW_TYPE type(string_t)
#include "grow_template.inc"

#define GROW_NAME grow_material
#define GROW_TYPE type(material_t)
#include "grow_template.inc"

#define GROW_NAME grow_orientation
#define GROW_TYPE type(orientation_t)
#include "grow_template.inc"

#define GROW_NAME grow_sec_b
#define GROW_TYPE type(sec_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_sec_controls_b
#define GROW_TYPE type(sec_controls_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_contact_b
#define GROW_TYPE type(contact_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_cline_b
#define GROW_TYPE type(cline_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_step_b
#define GROW_TYPE type(step_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_load_b
#define GROW_TYPE type(load_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_request_b
#define GROW_TYPE type(request_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_spring_elem_b
#define GROW_TYPE type(spring_elem_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_spring_card_b
#define GROW_TYPE type(spring_card_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_nthick_b
#define GROW_TYPE type(nthick_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_transform_b
#define GROW_TYPE type(transform_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_equation_b
#define GROW_TYPE type(equation_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_temp_b
#define GROW_TYPE type(temp_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_surface_b
#define GROW_TYPE type(surface_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_combo_b
#define GROW_TYPE type(combo_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_instance_b
#define GROW_TYPE type(instance_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_override_b
#define GROW_TYPE type(override_b_t)
#include "grow_template.inc"

#define GROW_NAME grow_source_loc
#define GROW_TYPE type(source_loc_t)
#include "grow_template.inc"

#define GROW_NAME grow_amp_use_b
#define GROW_TYPE type(amp_use_b_t)
#include "grow_template.inc"

end module superjoin_deck_state
