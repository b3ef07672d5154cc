module superjoin_substructure_library
  !! The condensation library across runs (--library DIR, issue 26): every
  !! condensed part is kept in DIR as one file named by a content key, and a
  !! later run whose part has the same key loads it instead of condensing.
  !!
  !! The key is the SHA-256 of everything the condensation depends on, its
  !! inputs (superjoin_substructure_library_key: coordinates, elements,
  !! sections, materials, drilling masks, boundary DOF map, solver, program
  !! and formulation versions), so that a hit does not assemble the part's
  !! stiffness. A load set is matched by the SHA-256 of the part's local loads
  !! (interior and boundary, every step) inside the entry. Safety net: the
  !! entry keeps the hash of a few sample element stiffnesses, recomputed and
  !! compared on every load, and the hash of the assembled k, compared on
  !! load under --library-verify (which then assembles k): a mismatch is a
  !! stale entry, condensed anew.
  !!
  !! An entry holds K*, MAXRATIO of the interior factor, the interior DOFs
  !! without stiffness, the recovery operator T = k_ii⁻¹ k_ib (dense ni × nb)
  !! and, per load set, x = k_ii⁻¹ f_i and f* = f_b − k_bi x. Recovery is then
  !! u_i = x − T u_b, without a factor, and k u = [f_i; f_b − f* + K* u_b]
  !! (library_ku: the element forces and reactions), without k: a library hit
  !! costs the key, the sample elements and the reading. Runs with a
  !! library recover with T and form k u so whether they stored or loaded the
  !! entry, so their results are the same to the byte. Loads never seen by the
  !! entry need the factor: the part is condensed anew and the entry rewritten.
  !! k is assembled after a hit only where it is asked for (library_stiffness:
  !! prescribed displacements on the part, whose k u0 the health check needs).
  !!
  !! File: magic, format version, key, payload, then the SHA-256 of all that
  !! precedes it, written and read field by field (one unformatted stream
  !! transfer per array, hashed in place in the same pass). A file whose
  !! checksum, magic, version or key does not match, or whose counts do not
  !! fit its size, is never used (the listing says so once) and is replaced.
  !! Entries are written to a temporary name in DIR and renamed, so a killed
  !! run leaves no half entry under a key's name.
  !!
  !! Translated copies (identical parts found by their geometry, --twins):
  !! a run condenses one part of each group of copies (the cache turns it for
  !! the others), so its entry is stored under that part's key; a later run
  !! may condense another member of the group (the first one changed), whose
  !! own key has no entry. Every stored entry of a part a translation does
  !! not change (copy_key) therefore gets a pointer file DIR/<copy key>.<n>.sjg
  !! holding the entry's key and its part's node coordinates; a part whose
  !! own key has no entry reads the pointers of its copy key (header first:
  !! node count and extents) and takes an entry
  !! whose part's nodes are its own translated (within COPY_TOL of the part's
  !! size), once the entry's key is recomputed from the part with those
  !! coordinates (so nothing but the coordinates differs, to the bit) and its
  !! sample elements are recomputed on them. K* and the stored loads'
  !! solutions of a translated copy are its own to round-off. A part
  !! whose own key has an entry that cannot be used (damaged, stale) is
  !! condensed and that entry replaced, no copy looked for. A part that
  !! needs loads such an entry has not seen is condensed anew and stored
  !! under its own key. Not looked for under --twins no (pointers are still
  !! written) or --library-verify (it compares the part's own assembled k
  !! with the entry's to the bit), nor for turned copies.
  !! Pointers are created exclusively (open status 'new'): concurrent runs
  !! never overwrite one; a lost or damaged pointer costs a later run a
  !! condensation, never a wrong entry.
  use, intrinsic :: iso_c_binding, only: c_int
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, string_t
  use superjoin_model_notes, only: note
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_substructure_local_system, only: build_local_system, local_numbering
  use superjoin_substructure_library_key, only: input_key, copy_key, sample_hash, stiffness_hash, KEY_LEN
  use superjoin_substructure_condensed, only: condensed_t, condense
  use superjoin_solvers_solver, only: subtract_bi
  use superjoin_utils_sha256, only: sha256_t, update, digest
  use superjoin_utils_posix, only: rename_file, remove_file
  use superjoin_utils_process, only: temp_register, temp_unregister
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  integer(i8), parameter :: FORMAT_VERSION = 2
    !! Layout of an entry file (2: the sample and stiffness hashes after MAXRATIO).
  integer, parameter :: MAGIC_LEN = 8
  character(len=MAGIC_LEN), parameter :: MAGIC = 'SJCONDLB'
  character(len=*), parameter :: SUFFIX = '.sjc'
  character(len=MAGIC_LEN), parameter :: POINTER_MAGIC = 'SJCONDLG'
  character(len=*), parameter :: POINTER_SUFFIX = '.sjg'
  integer(i8), parameter :: POINTER_VERSION = 1
  integer(i8), parameter :: POINTER_HEAD = MAGIC_LEN + 8 + 2*KEY_LEN + 8 + 24
    !! Bytes of a pointer file before its coordinates: magic, version, copy
    !! key, entry key, node count, the nodes' extents along x, y, z.
  integer, parameter :: MAX_POINTERS = 100000
    !! Pointer files of one copy key looked at, at most.
  real(wp), parameter :: COPY_TOL = 1.0e-12_wp
    !! A translated copy's nodes agree within COPY_TOL × the part's size (its
    !! largest extent along an axis), as the twins of one run.
  integer, parameter :: HEX = KEY_LEN
  integer(i8), parameter :: HEX_I8 = HEX, MAGIC_I8 = len(MAGIC)
  integer, parameter :: DRAIN_BYTES = 1048576
    !! Bytes read at a time when the rest of an unusable entry is only hashed.

  type :: load_set_t
    !! One set of local loads the entry has condensed.
     character(len=HEX) :: key = ''
     real(wp), allocatable :: x(:, :)        !! k_ii⁻¹ f_i (ni, nstep)
     real(wp), allocatable :: fstar(:, :)    !! f* (nb, nstep)
  end type load_set_t

  type, public :: stored_t
    !! What the library adds to one condensation of this run.
     character(len=HEX) :: key = ''
     character(:), allocatable :: file          !! the entry's path
     real(wp), allocatable :: t(:, :)           !! k_ii⁻¹ k_ib (ni, nb)
     type(load_set_t), allocatable :: sets(:)
     type(string_t), allocatable :: notes(:)    !! the listing's notes on this part
     real(wp) :: maxratio = 0.0_wp              !! as read from the entry
     integer(i8) :: maxratio_at = 0
     character(len=HEX) :: samples = ''         !! sample_hash of the part
     character(len=HEX) :: stiffness = ''       !! stiffness_hash of its assembled k
     character(len=HEX) :: own = ''             !! the part's own key (key differs: a translated copy's entry)
     character(len=HEX) :: copies = ''          !! its copy key (blank: a translation may change the part)
     character(:), allocatable :: dir           !! the library's directory
  end type stored_t

  type, public :: library_t
    !! The library of this run (dir unallocated: none).
     character(:), allocatable :: dir
     logical :: verify = .false.              !! --library-verify: assemble k on a hit and compare its hash
     logical :: copies = .true.               !! entries of translated copies looked for (--twins)
  end type library_t

  type :: sink_t
    !! An entry file being written, hashed as it goes.
     integer :: unit = -1
     integer :: iostat = 0
     integer(i8) :: bytes = 0                !! bytes handed to the I/O library
     type(sha256_t) :: sha
  end type sink_t

  type :: source_t
    !! An entry file being read, field by field into its arrays (large
    !! unformatted stream reads), hashed in the same pass.
     integer :: unit = -1
     integer :: iostat = 0
     integer(i8) :: left = 0                 !! bytes before the checksum not yet read
     logical :: ok = .true.                  !! every field was there
     type(sha256_t) :: sha
  end type source_t

  interface take
    !! The next field of an entry: text, integers, reals or a matrix.
     module procedure take_text, take_i8, take_real, take_real_2d
  end interface take

  interface
     function c_getpid() bind(c, name='getpid') result(pid)
       import :: c_int
       integer(c_int) :: pid
     end function c_getpid
  end interface

  public :: library_condense, library_need_loads, library_loads, library_recover, library_enabled, &
       library_stiffness, library_ku

contains

  pure logical function library_enabled(lib)
    !! Whether this run keeps condensations in a library.
    type(library_t), intent(in) :: lib
    library_enabled = allocated(lib%dir)
  end function library_enabled

  subroutine library_condense(lib, model, table, isub, bnd, solver_name, cond, st, error)
    !! The condensation of substructure isub (boundary bnd) into cond: loaded
    !! from the library when its input key has a sound entry (k not
    !! assembled), else k assembled, condensed (condense), its recovery
    !! operator formed and the entry stored. st%notes say which.
    type(library_t), intent(in) :: lib
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    logical, intent(in) :: bnd(:)
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(out) :: st
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: why, name
    logical :: own_seen, found

    name = model%subs(isub)%name
    cond%sys%isub = isub
    call local_numbering(table, isub, bnd, cond%sys%pdof, cond%sys%ni)
    cond%sys%nb = size(cond%sys%pdof, kind=i8) - cond%sys%ni
    st%dir = lib%dir
    st%own = input_key(model, table, isub, cond%sys%pdof, cond%sys%ni, solver_name)
    st%copies = copy_key(model, table, isub, cond%sys%pdof, cond%sys%ni, solver_name)
    call point_at(st, st%own)
    inquire (file=st%file, exist=own_seen)
    if (own_seen) then
       why = ''
       call read_entry(st, cond, why)
       if (len(why) == 0) call check_loaded(lib, model, table, bnd, solver_name, cond, st, why)
       if (len(why) == 0) then
          call note(st%notes, 'library: substructure '//name//' loaded from library (key '//st%key//')')
          return
       end if
       call forget_entry(cond, st)
       call note(st%notes, 'library: entry '//st%key//' not used ('//why//'): condensed anew')
    end if
    ! A damaged or stale entry of the part's own key is replaced, not passed over.
    if (len_trim(st%copies) > 0 .and. lib%copies .and. .not. lib%verify .and. .not. own_seen) then
       call find_copy(lib, model, table, bnd, solver_name, cond, st, found)
       if (found) return
    end if
    if (.not. allocated(cond%sys%k%val)) call build_local_system(model, table, isub, bnd, cond%sys, error)
    if (allocated(error)) return
    call store_own(model, table, solver_name, cond, st, found, error)
    if (allocated(error)) return
    if (found) then
       call note(st%notes, 'library: substructure '//name//' condensed and stored (key '//st%key//')')
    else
       call note(st%notes, 'library: substructure '//name//' condensed, not stored (key '//st%key//')')
    end if
  end subroutine library_condense

  subroutine store_own(model, table, solver_name, cond, st, stored, error)
    !! The part condensed (unless its factor is there) with its own key, its
    !! recovery operator formed and its entry stored (stored: written), with
    !! no load set yet, and its pointer (translated copies). Its k is
    !! assembled in cond%sys.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(inout) :: st
    logical, intent(out) :: stored
    type(error_t), allocatable, intent(out) :: error
    stored = .false.
    call point_at(st, st%own)
    st%stiffness = stiffness_hash(cond%sys, solver_name)
    st%samples = sample_hash(model, cond%sys%isub, error)
    if (allocated(error)) return
    if (.not. allocated(cond%solver)) call condense(model, table, solver_name, cond, error)
    if (allocated(error)) return
    if (allocated(st%t)) deallocate (st%t)
    call recovery_operator(cond, st, error)
    if (allocated(error)) return
    if (allocated(st%sets)) deallocate (st%sets)
    allocate (st%sets(0))
    call write_entry(st, cond, stored)
    associate (sub => model%subs(cond%sys%isub))
      if (stored .and. len_trim(st%copies) > 0) call write_pointer(st, sub%x(:, 1:sub%nnode))
    end associate
  end subroutine store_own

  subroutine point_at(st, key)
    !! st names the entry of this key (key and file).
    type(stored_t), intent(inout) :: st
    character(len=HEX), intent(in) :: key
    st%key = key
    st%file = st%dir//'/'//key//SUFFIX
  end subroutine point_at

  subroutine forget_entry(cond, st)
    !! What an entry that is not used left in cond and st dropped.
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(inout) :: st
    if (allocated(cond%se%k)) deallocate (cond%se%k)
    if (allocated(cond%spc)) deallocate (cond%spc)
    if (allocated(st%t)) deallocate (st%t)
    if (allocated(st%sets)) deallocate (st%sets)
  end subroutine forget_entry

  subroutine find_copy(lib, model, table, bnd, solver_name, cond, st, found)
    !! The entry of a translated copy of the part, through the pointers of its
    !! copy key (module comment): found, then cond and st hold it (st%key its
    !! key); else st names the part's own entry again.
    type(library_t), intent(in) :: lib
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(inout) :: st
    logical, intent(out) :: found
    real(wp), allocatable :: xref(:, :)
    character(len=HEX) :: key
    character(:), allocatable :: why
    logical :: exists, ok
    integer :: n
    found = .false.
    associate (sub => model%subs(cond%sys%isub))
      do n = 1, MAX_POINTERS
         inquire (file=pointer_path(st, n), exist=exists)
         if (.not. exists) exit
         call read_pointer(pointer_path(st, n), st%copies, key, ok, sub%x(:, 1:sub%nnode), xref)
         if (.not. ok) cycle
         if (key == st%own) cycle
         if (.not. translated(sub%x(:, 1:sub%nnode), xref)) cycle
         if (input_key(model, table, cond%sys%isub, cond%sys%pdof, cond%sys%ni, solver_name, xref) /= key) cycle
         call point_at(st, key)
         inquire (file=st%file, exist=exists)
         if (.not. exists) cycle
         why = ''
         call read_entry(st, cond, why)
         if (len(why) == 0) call check_loaded(lib, model, table, bnd, solver_name, cond, st, why, xref)
         if (len(why) == 0) then
            found = .true.
            call note(st%notes, 'library: substructure '//sub%name//' loaded from library, the entry of a '// &
                 'translated copy (key '//st%key//')')
            return
         end if
         call forget_entry(cond, st)
         call note(st%notes, 'library: entry '//st%key//' of a translated copy not used ('//why//')')
      end do
    end associate
    call point_at(st, st%own)
  end subroutine find_copy

  pure logical function translated(x, xref) result(yes)
    !! Whether the nodes x are the nodes xref translated, within COPY_TOL ×
    !! the largest extent of xref along an axis.
    real(wp), intent(in) :: x(:, :), xref(:, :)
    real(wp) :: t(3), tol
    integer :: i
    yes = size(x, 1) == 3 .and. size(xref, 1) == 3 .and. size(x, 2) == size(xref, 2) .and. size(x, 2) > 0
    if (.not. yes) return
    tol = COPY_TOL*maxval(extents(xref))
    t = x(:, 1) - xref(:, 1)
    do i = 2, size(x, 2)
       if (any(abs(x(:, i) - xref(:, i) - t) > tol)) then
          yes = .false.
          return
       end if
    end do
  end function translated

  function pointer_path(st, n) result(path)
    !! The n-th pointer file of st's copy key.
    type(stored_t), intent(in) :: st
    integer, intent(in) :: n
    character(:), allocatable :: path
    path = st%dir//'/'//st%copies//'.'//itoa(n)//POINTER_SUFFIX
  end function pointer_path

  subroutine read_pointer(path, copies, key, ok, x, xref)
    !! The entry key a pointer file names (ok: a pointer of this copy key,
    !! whole) and, given the nodes x of a part, whether they may be that
    !! entry's nodes translated: ok only if their count and extents are the
    !! pointer's (within COPY_TOL), and then the pointer's coordinates in xref.
    character(*), intent(in) :: path
    character(len=HEX), intent(in) :: copies
    character(len=HEX), intent(out) :: key
    logical, intent(out) :: ok
    real(wp), intent(in), optional :: x(:, :)
    real(wp), allocatable, intent(out), optional :: xref(:, :)
    character(len=MAGIC_LEN) :: stamp
    character(len=HEX) :: group
    integer(i8) :: ver, nnode, bytes
    real(wp) :: ext(3)
    integer :: unit, iostat
    ok = .false.
    key = ''
    open (newunit=unit, file=path, access='stream', form='unformatted', status='old', action='read', &
         iostat=iostat)
    if (iostat /= 0) return
    inquire (unit=unit, size=bytes)
    read (unit, iostat=iostat) stamp, ver, group, key, nnode, ext
    if (iostat == 0) then
       ok = stamp == POINTER_MAGIC .and. ver == POINTER_VERSION .and. group == copies
       if (ok) ok = nnode > 0 .and. nnode <= (bytes - POINTER_HEAD)/24 .and. bytes == POINTER_HEAD + 24*nnode
    end if
    if (ok .and. present(x)) then
       ok = size(x, 2, kind=i8) == nnode .and. &
            all(abs(extents(x) - ext) <= COPY_TOL*max(maxval(ext), maxval(extents(x))))
       if (ok .and. present(xref)) then
          allocate (xref(3, nnode))
          read (unit, iostat=iostat) xref
          ok = iostat == 0
       end if
    end if
    if (.not. ok) key = ''
    close (unit)
  end subroutine read_pointer

  pure function extents(x) result(e)
    !! The extents of the nodes x along x, y and z.
    real(wp), intent(in) :: x(:, :)
    real(wp) :: e(3)
    e = maxval(x, dim=2) - minval(x, dim=2)
  end function extents

  subroutine write_pointer(st, x)
    !! The pointer from st's copy key to its entry, with the part's nodes x:
    !! the first free number (created exclusively), unless one points there
    !! already. A failure leaves at most a pointer that is never taken.
    type(stored_t), intent(in) :: st
    real(wp), intent(in) :: x(:, :)
    character(len=HEX) :: key
    logical :: exists, ok
    integer :: n, unit, iostat
    do n = 1, MAX_POINTERS
       inquire (file=pointer_path(st, n), exist=exists)
       if (exists) then
          call read_pointer(pointer_path(st, n), st%copies, key, ok)
          if (ok .and. key == st%key) return
          cycle
       end if
       open (newunit=unit, file=pointer_path(st, n), access='stream', form='unformatted', status='new', &
            action='write', iostat=iostat)
       if (iostat /= 0) then
          inquire (file=pointer_path(st, n), exist=exists)
          if (exists) cycle   ! another run took this number meanwhile
          return              ! the library cannot be written: no pointer
       end if
       write (unit, iostat=iostat) POINTER_MAGIC, POINTER_VERSION, st%copies, st%key, size(x, 2, kind=i8), &
            extents(x), x
       close (unit)
       if (iostat /= 0) call remove_file(pointer_path(st, n))
       return
    end do
  end subroutine write_pointer

  subroutine check_loaded(lib, model, table, bnd, solver_name, cond, st, why, x)
    !! The safety net on a sound entry: its sample element stiffnesses
    !! recomputed (always; x: on these coordinates of the part's nodes, a
    !! translated copy's), its assembled k (under --library-verify, which
    !! keeps k assembled; never with x); why says what differs (empty: none).
    type(library_t), intent(in) :: lib
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(in) :: st
    character(:), allocatable, intent(inout) :: why
    real(wp), intent(in), optional :: x(:, :)
    type(error_t), allocatable :: error
    character(len=HEX) :: h
    h = sample_hash(model, cond%sys%isub, error, x)
    if (allocated(error) .or. h /= st%samples) then
       why = 'its sample element stiffnesses differ: stale'
       return
    end if
    if (.not. lib%verify) return
    call rebuild_local_system(model, table, bnd, cond, error)
    if (allocated(error)) then
       why = 'its stiffness cannot be assembled'
    else if (stiffness_hash(cond%sys, solver_name) /= st%stiffness) then
       why = 'its assembled stiffness differs (--library-verify): stale'
    else
       call unit_spc_diagonal(cond)
    end if
  end subroutine check_loaded

  subroutine library_stiffness(model, table, bnd, cond, error)
    !! Assemble k of a condensation loaded without it (the interior DOFs
    !! without stiffness given their unit diagonal, as condense does).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    type(condensed_t), intent(inout) :: cond
    type(error_t), allocatable, intent(out) :: error
    if (allocated(cond%sys%k%val)) return
    call rebuild_local_system(model, table, bnd, cond, error)
    if (allocated(error)) return
    call unit_spc_diagonal(cond)
  end subroutine library_stiffness

  subroutine rebuild_local_system(model, table, bnd, cond, error)
    !! cond's local system assembled anew for its own substructure (isub passed
    !! by value: build_local_system's sys is intent(out), and passing
    !! cond%sys%isub beside cond%sys would alias the number it resets).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    type(condensed_t), intent(inout) :: cond
    type(error_t), allocatable, intent(out) :: error
    integer :: isub
    isub = cond%sys%isub
    call build_local_system(model, table, isub, bnd, cond%sys, error)
  end subroutine rebuild_local_system

  subroutine library_ku(cond, st, f_local, u_local, y, error)
    !! y = k u of a library part from its entry, without k: the interior rows
    !! are f_i (k_ii u_i + k_ib u_b with u_i = k_ii⁻¹ (f_i − k_ib u_b)), the
    !! boundary rows f_b − f* + K* u_b; f* of the load set of f_local.
    type(condensed_t), intent(in) :: cond
    type(stored_t), intent(in) :: st
    real(wp), intent(in) :: f_local(:, :), u_local(:, :)
    real(wp), intent(out) :: y(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer :: s
    integer(i8) :: ni
    ni = cond%sys%ni
    call seen_set(st, f_local, s, error)
    if (allocated(error)) return
    y(1:ni, :) = f_local(1:ni, :)
    y(ni + 1:, :) = f_local(ni + 1:, :) - st%sets(s)%fstar + matmul(cond%se%k, u_local(ni + 1:, :))
  end subroutine library_ku

  subroutine library_need_loads(model, table, bnd, solver_name, cond, st, f_local, error)
    !! Make sure f* of the local loads f_local can be had: the entry has them,
    !! or the factor is there; an entry loaded without the factor is condensed
    !! anew (the same K*) when these loads are new to it.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(in) :: bnd(:)
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(inout) :: st
    real(wp), intent(in) :: f_local(:, :)
    type(error_t), allocatable, intent(out) :: error
    logical :: stored
    if (allocated(cond%solver)) return
    if (find_set(st, loads_key(f_local)) > 0) return
    deallocate (cond%se%k, cond%spc)
    call rebuild_local_system(model, table, bnd, cond, error)
    if (allocated(error)) return
    if (st%key /= st%own) then
       ! A translated copy's entry: the part's own entry from now on.
       call store_own(model, table, solver_name, cond, st, stored, error)
    else
       call condense(model, table, solver_name, cond, error)
    end if
    if (allocated(error)) return
    call note(st%notes, 'library: substructure '//model%subs(cond%sys%isub)%name// &
         ' has loads its entry has not seen: condensed anew')
  end subroutine library_need_loads

  subroutine library_loads(cond, st, f_local, fstar, error)
    !! f* of the local loads f_local: from the entry's load set with their key,
    !! else computed with the factor and added to the entry.
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(inout) :: st
    real(wp), intent(in) :: f_local(:, :)
    real(wp), intent(out) :: fstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(load_set_t), allocatable :: grown(:)
    character(len=HEX) :: key
    integer :: s
    key = loads_key(f_local)
    s = find_set(st, key)
    if (s > 0) then
       fstar = st%sets(s)%fstar
       return
    end if
    allocate (grown(size(st%sets) + 1))
    grown(1:size(st%sets)) = st%sets
    s = size(grown)
    grown(s)%key = key
    allocate (grown(s)%x(cond%sys%ni, size(f_local, 2)))
    if (cond%sys%ni > 0) then
       call cond%solver%solve(f_local(1:cond%sys%ni, :), grown(s)%x, error)
       if (allocated(error)) return
    end if
    grown(s)%fstar = f_local(cond%sys%ni + 1:, :)
    call subtract_bi(cond%sys%k, cond%sys%nb, grown(s)%x, grown(s)%fstar)
    call move_alloc(grown, st%sets)
    fstar = st%sets(s)%fstar
    call write_entry(st, cond)
  end subroutine library_loads

  subroutine library_recover(st, f_local, u_local, error)
    !! u_i = x − T u_b with x of the load set of f_local (u_local holds u_b in
    !! rows ni+1.. on entry and gets u_i in rows 1..ni).
    type(stored_t), intent(in) :: st
    real(wp), intent(in) :: f_local(:, :)
    real(wp), intent(inout) :: u_local(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer :: s
    integer :: ni
    ni = size(st%t, 1)
    call seen_set(st, f_local, s, error)
    if (allocated(error)) return
    if (ni == 0) return
    u_local(1:ni, :) = st%sets(s)%x
    if (size(st%t, 2) > 0) u_local(1:ni, :) = u_local(1:ni, :) - matmul(st%t, u_local(ni + 1:, :))
  end subroutine library_recover

  ! ---- keys

  function loads_key(f) result(key)
    !! The SHA-256 of a load set (shape and values).
    real(wp), intent(in) :: f(:, :)
    character(len=HEX) :: key
    type(sha256_t) :: s
    call update(s, [size(f, 1, kind=i8), size(f, 2, kind=i8)])
    call update(s, f)
    key = digest(s)
  end function loads_key

  subroutine seen_set(st, f_local, s, error)
    !! The load set of f_local, which the entry must have (an internal error if not).
    type(stored_t), intent(in) :: st
    real(wp), intent(in) :: f_local(:, :)
    integer, intent(out) :: s
    type(error_t), allocatable, intent(out) :: error
    s = find_set(st, loads_key(f_local))
    if (s > 0) return
    allocate (error)
    error%message = 'error: internal: the library entry '//st%key//' has no condensation of these loads'
  end subroutine seen_set

  pure integer function find_set(st, key) result(s)
    !! The load set with this key (0: none).
    type(stored_t), intent(in) :: st
    character(len=HEX), intent(in) :: key
    s = 0
    if (.not. allocated(st%sets)) return
    do s = size(st%sets), 1, -1
       if (st%sets(s)%key == key) return
    end do
    s = 0
  end function find_set

  ! ---- recovery operator

  subroutine recovery_operator(cond, st, error)
    !! T = k_ii⁻¹ k_ib, one solve with the nb columns of k_ib.
    type(condensed_t), intent(inout) :: cond
    type(stored_t), intent(inout) :: st
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: kib(:, :)
    integer(i8) :: ni, nb, j, pos, r
    ni = cond%sys%ni
    nb = cond%sys%nb
    allocate (st%t(ni, nb), source=0.0_wp)
    if (ni == 0 .or. nb == 0) return
    allocate (kib(ni, nb), source=0.0_wp)
    associate (k => cond%sys%k)
      do j = 1, nb
         do pos = k%colptr(ni + j), k%colptr(ni + j + 1) - 1
            r = k%rowind(pos)
            if (r > ni) exit
            kib(r, j) = k%val(pos)
         end do
      end do
    end associate
    call cond%solver%solve(kib, st%t, error)
  end subroutine recovery_operator

  ! ---- entry files

  subroutine write_entry(st, cond, stored)
    !! Write the entry to a temporary name in the library and rename it to
    !! its key's name (stored: done). A failure leaves no entry (the run goes on).
    type(stored_t), intent(inout) :: st
    type(condensed_t), intent(in) :: cond
    logical, intent(out), optional :: stored
    type(sink_t) :: w
    type(error_t), allocatable :: error
    character(:), allocatable :: tmp
    integer(i8) :: size_on_disk
    integer :: s
    if (present(stored)) stored = .false.
    tmp = st%file//'.'//itoa(int(c_getpid()))//'.tmp'
    call temp_register(tmp)
    open (newunit=w%unit, file=tmp, access='stream', form='unformatted', status='replace', &
         action='write', iostat=w%iostat)
    if (w%iostat /= 0) then
       call temp_unregister()
       call note(st%notes, 'library: cannot write '//tmp//': entry not stored')
       return
    end if
    call put(w, MAGIC)
    call put_i8(w, [FORMAT_VERSION])
    call put(w, st%key)
    call put_i8(w, [cond%sys%ni, cond%sys%nb, size(cond%spc, kind=i8), cond%maxratio_at, &
         size(st%sets, kind=i8)])
    call put_real(w, [cond%maxratio])
    call put(w, st%samples)
    call put(w, st%stiffness)
    call put_i8(w, spc_local(cond))
    call put_real_2d(w, cond%se%k)
    call put_real_2d(w, st%t)
    do s = 1, size(st%sets)
       call put(w, st%sets(s)%key)
       call put_i8(w, [size(st%sets(s)%x, 2, kind=i8)])
       call put_real_2d(w, st%sets(s)%x)
       call put_real_2d(w, st%sets(s)%fstar)
    end do
    call put(w, digest(w%sha))
    close (w%unit)
    ! gfortran drops an error of the last flush on close: the size tells.
    inquire (file=tmp, size=size_on_disk)
    if (size_on_disk /= w%bytes) w%iostat = -1
    if (w%iostat == 0) call rename_file(tmp, st%file, error)
    if (w%iostat /= 0 .or. allocated(error)) then
       call remove_file(tmp)
       call note(st%notes, 'library: cannot write '//st%file//': entry not stored')
    else if (present(stored)) then
       stored = .true.
    end if
    call temp_unregister()
  end subroutine write_entry

  function spc_local(cond) result(l)
    !! The local DOFs of cond%spc (interior DOFs without stiffness).
    type(condensed_t), intent(in) :: cond
    integer(i8), allocatable :: l(:)
    integer(i8) :: i
    allocate (l(size(cond%spc)))
    do i = 1, size(cond%spc, kind=i8)
       l(i) = findloc(cond%sys%pdof, cond%spc(i), dim=1, kind=i8)
    end do
  end function spc_local

  subroutine put(w, text)
    !! Append bytes to the entry (and to its checksum).
    type(sink_t), intent(inout) :: w
    character(*), intent(in) :: text
    if (w%iostat /= 0) return
    write (w%unit, iostat=w%iostat) text
    w%bytes = w%bytes + len(text, kind=i8)
    call update(w%sha, text)
  end subroutine put

  subroutine put_i8(w, a)
    !! Append integers.
    type(sink_t), intent(inout) :: w
    integer(i8), intent(in) :: a(:)
    if (w%iostat /= 0) return
    write (w%unit, iostat=w%iostat) a
    w%bytes = w%bytes + 8*size(a, kind=i8)
    call update(w%sha, a)
  end subroutine put_i8

  subroutine put_real(w, a)
    !! Append reals.
    type(sink_t), intent(inout) :: w
    real(wp), intent(in) :: a(:)
    if (w%iostat /= 0) return
    write (w%unit, iostat=w%iostat) a
    w%bytes = w%bytes + 8*size(a, kind=i8)
    call update(w%sha, a)
  end subroutine put_real

  subroutine put_real_2d(w, a)
    !! Append a matrix (column by column), in one write.
    type(sink_t), intent(inout) :: w
    real(wp), intent(in) :: a(:, :)
    if (w%iostat /= 0) return
    write (w%unit, iostat=w%iostat) a
    w%bytes = w%bytes + 8*size(a, kind=i8)
    call update(w%sha, a)
  end subroutine put_real_2d

  subroutine read_entry(st, cond, why)
    !! Load the entry st%file into cond and st; why is empty when it is sound,
    !! else says why it is not used. One pass: each field is read into its
    !! array and hashed; the checksum is checked at the end (and its
    !! mismatch is the reason given before any other).
    type(stored_t), intent(inout) :: st
    type(condensed_t), intent(inout) :: cond
    character(:), allocatable, intent(out) :: why
    type(source_t) :: r
    character(len=HEX) :: stored_sum
    integer(i8) :: n
    integer(i8), allocatable :: spc(:)
    why = ''
    open (newunit=r%unit, file=st%file, access='stream', form='unformatted', status='old', action='read', &
         iostat=r%iostat)
    if (r%iostat /= 0) then
       why = 'cannot be read'
       return
    end if
    inquire (unit=r%unit, size=n)
    if (n < MAGIC_I8 + 8 + 2*HEX_I8) then
       close (r%unit)
       why = 'truncated'
       return
    end if
    r%left = n - HEX_I8
    call read_fields(r, st, cond, spc, why)
    call drain(r)
    if (r%iostat == 0) read (r%unit, iostat=r%iostat) stored_sum
    close (r%unit)
    if (r%iostat /= 0) then
       why = 'cannot be read'
    else if (digest(r%sha) /= stored_sum) then
       why = 'checksum mismatch: corrupt'
    else if (len(why) == 0 .and. (.not. r%ok .or. r%left /= 0 .or. any(spc < 1 .or. spc > cond%sys%ni))) then
       why = 'malformed'
    end if
    if (len(why) > 0) return
    cond%maxratio = st%maxratio
    cond%maxratio_at = st%maxratio_at
    call set_loaded(cond, spc)
  end subroutine read_entry

  subroutine read_fields(r, st, cond, spc, why)
    !! The fields of an entry after its magic, as far as they are sound
    !! (why says where they stop being so; r%ok false: one was cut short).
    !! No array is allocated larger than the bytes left in the file.
    type(source_t), intent(inout) :: r
    type(stored_t), intent(inout) :: st
    type(condensed_t), intent(inout) :: cond
    integer(i8), allocatable, intent(out) :: spc(:)
    character(:), allocatable, intent(inout) :: why
    character(len=MAGIC_I8) :: stamp
    character(len=HEX) :: key
    integer(i8) :: head(5), ver(1), nstep(1), ni, nb, s
    real(wp) :: ratio(1)
    allocate (spc(0))
    call take(r, stamp)
    call take(r, ver)
    call take(r, key)
    if (stamp /= MAGIC) then
       why = 'not a library entry'
    else if (ver(1) /= FORMAT_VERSION) then
       why = 'format version '//itoa(ver(1))//', not '//itoa(FORMAT_VERSION)//': stale'
    else if (key /= st%key) then
       why = 'key mismatch'
    end if
    if (len(why) > 0) return
    call take(r, head)
    ni = head(1)
    nb = head(2)
    if (ni /= cond%sys%ni .or. nb /= cond%sys%nb .or. any(head < 0)) then
       why = 'sizes differ'
       return
    end if
    call take(r, ratio)
    st%maxratio = ratio(1)
    call take(r, st%samples)
    call take(r, st%stiffness)
    st%maxratio_at = head(4)
    if (.not. (fits(r, head(3), 1_i8) .and. fits(r, head(5), 9_i8))) return   ! a load set: at least 72 bytes
    if (.not. fits(r, 1_i8, head(3) + nb*nb + ni*nb + 9*head(5))) return
    deallocate (spc)
    allocate (spc(head(3)), cond%se%k(nb, nb), st%t(ni, nb), st%sets(head(5)))
    call take(r, spc)
    call take(r, cond%se%k)
    call take(r, st%t)
    do s = 1, head(5)
       call take(r, st%sets(s)%key)
       call take(r, nstep)
       if (.not. fits(r, nstep(1), ni + nb)) return
       allocate (st%sets(s)%x(ni, nstep(1)), st%sets(s)%fstar(nb, nstep(1)))
       call take(r, st%sets(s)%x)
       call take(r, st%sets(s)%fstar)
    end do
  end subroutine read_fields

  logical function fits(r, count, each) result(ok)
    !! Whether count times each 8-byte values (count, each >= 0) are left
    !! before the checksum, asked without forming a product that could
    !! overflow (r%ok false if not).
    type(source_t), intent(inout) :: r
    integer(i8), intent(in) :: count, each
    ok = r%ok .and. count >= 0 .and. each >= 0
    if (ok .and. each > 0) ok = count <= r%left/8/each
    r%ok = ok
  end function fits

  subroutine set_loaded(cond, spc)
    !! What condense leaves beside K*: the boundary's physical DOFs and the
    !! interior DOFs without stiffness (spc: local; their unit diagonal in k,
    !! as condense sets, where k is assembled).
    type(condensed_t), intent(inout) :: cond
    integer(i8), intent(in) :: spc(:)
    cond%se%pdof = cond%sys%pdof(cond%sys%ni + 1:cond%sys%ni + cond%sys%nb)
    cond%spc = cond%sys%pdof(spc)
    call unit_spc_diagonal(cond)
  end subroutine set_loaded

  subroutine unit_spc_diagonal(cond)
    !! Diagonal 1 in k (if assembled) at the interior DOFs without stiffness.
    type(condensed_t), intent(inout) :: cond
    integer(i8) :: i, j
    if (.not. allocated(cond%sys%k%val)) return
    do i = 1, size(cond%spc, kind=i8)
       j = findloc(cond%sys%pdof, cond%spc(i), dim=1, kind=i8)
       cond%sys%k%val(cond%sys%k%colptr(j + 1) - 1) = 1.0_wp
    end do
  end subroutine unit_spc_diagonal

  subroutine drain(r)
    !! Hash the bytes of r left before the checksum (an entry read only in
    !! part still has its checksum checked).
    type(source_t), intent(inout) :: r
    character(:), allocatable :: buf
    integer(i8) :: take_now
    if (r%left <= 0 .or. r%iostat /= 0) return
    allocate (character(len=int(min(r%left, int(DRAIN_BYTES, i8)))) :: buf)
    do while (r%left > 0 .and. r%iostat == 0)
       take_now = min(r%left, int(DRAIN_BYTES, i8))
       read (r%unit, iostat=r%iostat) buf(1:take_now)
       call update(r%sha, buf(1:take_now))
       r%left = r%left - take_now
    end do
    r%ok = .false.
  end subroutine drain

  logical function room(r, bytes)
    !! Whether the next field (bytes) can be read: r sound so far and the
    !! bytes there before the checksum (r%ok false if not).
    type(source_t), intent(inout) :: r
    integer(i8), intent(in) :: bytes
    room = r%ok .and. r%iostat == 0 .and. bytes <= r%left
    if (.not. room) r%ok = .false.
    if (room) r%left = r%left - bytes
  end function room

  subroutine take_text(r, text)
    !! The next len(text) bytes (blanks if they are not there).
    type(source_t), intent(inout) :: r
    character(*), intent(out) :: text
    text = ''
    if (.not. room(r, len(text, kind=i8))) return
    read (r%unit, iostat=r%iostat) text
    call update(r%sha, text)
  end subroutine take_text

  subroutine take_i8(r, a)
    !! The next size(a) integers (zeros if they are not there).
    type(source_t), intent(inout) :: r
    integer(i8), intent(out) :: a(:)
    a = 0
    if (.not. room(r, 8*size(a, kind=i8))) return
    read (r%unit, iostat=r%iostat) a
    call update(r%sha, a)
  end subroutine take_i8

  subroutine take_real(r, a)
    !! The next size(a) reals (zeros if they are not there).
    type(source_t), intent(inout) :: r
    real(wp), intent(out) :: a(:)
    a = 0.0_wp
    if (.not. room(r, 8*size(a, kind=i8))) return
    read (r%unit, iostat=r%iostat) a
    call update(r%sha, a)
  end subroutine take_real

  subroutine take_real_2d(r, a)
    !! The next size(a) reals, column by column, in one read.
    type(source_t), intent(inout) :: r
    real(wp), intent(out) :: a(:, :)
    a = 0.0_wp
    if (.not. room(r, 8*size(a, kind=i8))) return
    read (r%unit, iostat=r%iostat) a
    call update(r%sha, a)
  end subroutine take_real_2d
end module superjoin_substructure_library
