module superjoin_deck_validate
  !! Validation pass of the deck reader: resolves the names and user ids that the
  !! parser collected into indices, checks the model (duplicates, undefined
  !! nodes, sets, sections, contacts, supports, loads) and fills model_t.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: model_t, substructure_t, index_set_t, &
       link_t, support_t, cload_t, dload_t, source_loc_t, find_node, find_elem, &
       ELEMENT_TYPE_NAMES, ELEMENT_NODE_COUNT, NDOF_NODE, SEC_SOLID, SEC_BEAM, SEC_SHELL, &
       LINK_FINITE, LINK_RIGID, ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_CPS3, ET_CPS4, &
       ET_S3, ET_S4, ET_B21, ET_B31, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, &
       ET_B32, DLOAD_PX, DLOAD_PY, DLOAD_PZ, DLOAD_P, DLOAD_GRAV, DLOAD_NAMES
  use superjoin_model_types, only: ET_S4R, ET_S3R
  use superjoin_model_types, only: ET_S8R
  use superjoin_model_types, only: DLOAD_P1, DLOAD_P2, DLOAD_P3, DLOAD_P4, DLOAD_THERMAL, DLOAD_CENTRIF
  use superjoin_deck_lexer, only: itoa, plural
  use superjoin_deck_state, only: deck_state_t, sub_b_t, ref_t, load_b_t, report, report_loc, report_oom, find_set, &
       CH_IDS, CH_GEN, CH_RANGE, CH_REF, BEAM_2D_VALUES, BEAM_3D_VALUES, SUBK_INSTANCE
  use superjoin_utils_strings, only: pick
  use superjoin_deck_requests, only: build_requests
  use superjoin_deck_state, only: sec_b_t, step_b_t
  use superjoin_model_types, only: section_t
  use superjoin_model_types, only: MAX_ELEMENT_NODES
  use superjoin_deck_beam_sections, only: section_fibres, MAX_FIBRES
  use superjoin_deck_state, only: OP_NEW, OP_MOD, OP_DEFAULT
  use superjoin_deck_combinations, only: build_combinations
  use superjoin_model_history, only: support_list_t, step_ops_t, apply_boundary_history, apply_load_history
  use superjoin_deck_eccentric, only: check_offset_masters
  use superjoin_elements, only: is_plane_type
  use superjoin_utils_grow, only: grow
  implicit none (type, external)
  private

  interface grow
     !! Make room for element n + 1 of an allocatable array (grow_template.inc).
     module procedure grow_cload, grow_dload
  end interface grow

  public :: build_model
  public :: resolve_items, where, ref_text, resolve_sets, resolve_sub
    !! Public only because the submodule superjoin_deck_assembly calls them:
    !! gfortran 12 does not export private module procedures to submodules.

  character(*), parameter :: MAIN_NAME = 'MAIN'
  integer, parameter :: INITIAL_CAPACITY = 16
  integer, parameter :: INITIAL_HASH = 64
  integer(i8), parameter :: HASH_MUL1 = 2654435761_i8, HASH_MUL2 = 40503_i8
    !! Multipliers of the link hash (products stay below 2**63).
  integer(i8), parameter :: PAIR_SHIFT = 2147483648_i8   !! 2**31: key = master*2**31 + slave
  integer(i8), parameter :: EMPTY_KEY = -1_i8

  type :: pair_map_t
    !! Open-addressing map from a (master, slave) pair key to a link index.
     integer :: n = 0
     integer(i8), allocatable :: keys(:)
     integer, allocatable :: vals(:)
  end type pair_map_t

  type :: real_list_t
    !! A real value per node of one substructure (temperatures).
     real(wp), allocatable :: v(:)
  end type real_list_t

  type :: link_list_t
    !! Growing list of links / supports while they are generated.
     integer :: n = 0
     type(link_t), allocatable :: a(:)
  end type link_list_t

  interface
    !! Parts, instances, PAIR=NEAREST and *CHANGE CONTACT: submodule superjoin_deck_assembly (assembly.f90).
     module subroutine empty_sub(b, m)
       !! An *INSTANCE entry before its part is copied in: a substructure with no nodes.
       type(sub_b_t), intent(in) :: b
       type(substructure_t), intent(out) :: m
     end subroutine empty_sub
     module subroutine place_instances(st, model)
       !! Copy every part into its instances (placed), then drop the parts from
       !! model%subs (references by index are renumbered).
       type(deck_state_t), intent(inout) :: st
       type(model_t), intent(inout) :: model
     end subroutine place_instances
     module subroutine pair_nearest(st, model, icontact, loc, ms, ss, ok)
       !! PAIR=NEAREST: ms becomes, for each slave node ss(j), its nearest master node.
       type(deck_state_t), intent(inout) :: st
       type(model_t), intent(in) :: model
       integer, intent(in) :: icontact
       type(source_loc_t), intent(in) :: loc
       integer(ip), allocatable, intent(inout) :: ms(:)
       integer(ip), intent(in) :: ss(:)
       logical, intent(out) :: ok
     end subroutine pair_nearest
     module function part_hint(model, name) result(s)
       !! ' (NAME is a part: name one of its instances)' when NAME is a part, else ''.
       type(model_t), intent(in) :: model
       character(*), intent(in) :: name
       character(:), allocatable :: s
     end function part_hint
     module integer function assembly_set_owner(model, name, elem, main) result(k)
       !! Substructure of an unscoped set name: MAIN when MAIN has it, else the one
       !! instance that has it (an assembly-level *NSET or *ELSET, INSTANCE=), else main.
       type(model_t), intent(in) :: model
       character(*), intent(in) :: name
       logical, intent(in) :: elem
       integer, intent(in) :: main
     end function assembly_set_owner
     module subroutine build_interfaces(st, model)
       !! *INTERFACE: Goodman joints lumped to contact elements by tributary length or area.
       type(deck_state_t), intent(inout) :: st
       type(model_t), intent(inout) :: model
     end subroutine build_interfaces
     module subroutine build_overrides(st, model)
       !! *CHANGE CONTACT: per-step link overrides; SWEEP steps expanded.
       type(deck_state_t), intent(inout) :: st
       type(model_t), intent(inout) :: model
     end subroutine build_overrides
  end interface

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

    ! substructures
    allocate (model%subs(st%nsub))
    if (st%nsub == 0) call report(st, 1, 1, 'the deck defines no nodes')
    do k = 1, st%nsub
       if (st%subs(k)%kind == SUBK_INSTANCE) then
          call empty_sub(st%subs(k), model%subs(k))
          cycle
       end if
       call build_sub(st, st%subs(k), model%subs(k))
       if (st%aborted) return
    end do
    call build_sections(st, model)
    if (st%aborted) return
    call check_unassigned(st, model)
    call place_instances(st, model)
    if (st%aborted) return
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
  end subroutine build_model

  ! ================================================================== substructures

  subroutine build_sub(st, b, m)
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(inout) :: b
    type(substructure_t), intent(out) :: m
    integer(ip) :: n, i, j, k, e
    integer :: a

    m%name = b%name
    m%condense = b%condense
    m%loc = b%loc
    n = b%nnode
    m%nnode = n
    m%node_id = b%node_id(1:n)
    m%x = b%x(:, 1:n)
    allocate (m%node_order(n))
    call argsort_ids(m%node_id, m%node_order)
    if (b%node_lines == 0) call report_loc(st, b%loc, 'substructure '//b%name//' has no nodes')
    do i = 2, n
       if (m%node_id(m%node_order(i)) == m%node_id(m%node_order(i - 1))) then
          call report_loc(st, b%node_loc(m%node_order(i)), 'duplicate node id '// &
               itoa(m%node_id(m%node_order(i)))//' in substructure '//b%name//' (also defined at '// &
               where(st, b%node_loc(m%node_order(i - 1)))//')')
          if (st%aborted) return
       end if
    end do

    n = b%nelem
    m%nelem = n
    m%elem_id = b%elem_id(1:n)
    m%elem_type = b%elem_type(1:n)
    m%elem_loc = b%elem_loc(1:n)
    allocate (m%elem_order(n), m%elem_nodes(size(b%elem_nid, 1), n), m%elem_section(n))
    m%elem_section = 0
    m%elem_nodes = 0
    call argsort_ids(m%elem_id, m%elem_order)
    do i = 2, n
       if (m%elem_id(m%elem_order(i)) == m%elem_id(m%elem_order(i - 1))) then
          call report_loc(st, b%elem_loc(m%elem_order(i)), 'duplicate element id '// &
               itoa(m%elem_id(m%elem_order(i)))//' in substructure '//b%name//' (also defined at '// &
               where(st, b%elem_loc(m%elem_order(i - 1)))//')')
          if (st%aborted) return
       end if
    end do
    do e = 1, n
       do a = 1, ELEMENT_NODE_COUNT(m%elem_type(e))
          k = find_node(m, b%elem_nid(a, e))
          if (k == 0) then
             call report_loc(st, b%elem_loc(e), 'element '//itoa(m%elem_id(e))// &
                  ' refers to undefined node '//itoa(b%elem_nid(a, e))//' of substructure '//b%name)
             if (st%aborted) return
          end if
          m%elem_nodes(a, e) = k
       end do
       do a = 2, ELEMENT_NODE_COUNT(m%elem_type(e))
          do j = 1, a - 1
             if (b%elem_nid(a, e) == b%elem_nid(j, e)) then
                call report_loc(st, b%elem_loc(e), 'element '//itoa(m%elem_id(e))//' uses node '// &
                     itoa(b%elem_nid(a, e))//' twice')
             end if
          end do
       end do
    end do

    call resolve_sets(st, b, m, .false.)
    if (st%aborted) return
    call resolve_sets(st, b, m, .true.)
    allocate (m%sections(0))
    ! the builder's copies are no longer needed
    deallocate (b%node_id, b%x, b%elem_id, b%elem_type, b%elem_nid, b%pool)
  end subroutine build_sub

  subroutine resolve_sets(st, b, m, elem)
    !! Resolve the node sets (elem false) or element sets of one substructure:
    !! members in order of definition, repeats dropped, set references followed.
    type(deck_state_t), intent(inout) :: st
    type(sub_b_t), intent(in) :: b
    type(substructure_t), intent(inout) :: m
    logical, intent(in) :: elem
    integer, allocatable :: head(:), list(:), state(:), stack_set(:), stack_pos(:), mark(:)
    type(index_set_t), allocatable :: sets(:)
    integer :: nset, c, s, t, r, sp, stamp, nitem, n
    integer(ip), allocatable :: items(:)
    logical :: pushed
    integer, parameter :: UNVISITED = 0, BUSY = 1, DONE = 2
    character(:), allocatable :: kind_name

    kind_name = pick(elem, 'element set', 'node set')
    if (elem) then
       nset = b%nelset
       nitem = m%nelem
    else
       nset = b%nnset
       nitem = m%nnode
    end if
    allocate (sets(nset), head(nset + 1), list(b%nchunk), state(nset), stack_set(nset), &
         stack_pos(nset), mark(nitem))
    head = 0
    do c = 1, b%nchunk
       if (b%chunks(c)%elem .eqv. elem) head(b%chunks(c)%set + 1) = head(b%chunks(c)%set + 1) + 1
    end do
    head(1) = 1
    do s = 1, nset
       head(s + 1) = head(s + 1) + head(s)
    end do
    stack_pos(1:nset) = head(1:nset)
    do c = 1, b%nchunk
       if (b%chunks(c)%elem .eqv. elem) then
          s = b%chunks(c)%set
          list(stack_pos(s)) = c
          stack_pos(s) = stack_pos(s) + 1
       end if
    end do
    do s = 1, nset
       if (elem) then
          sets(s)%name = b%elsets(s)%name
       else
          sets(s)%name = b%nsets(s)%name
       end if
    end do
    state = UNVISITED
    mark = 0
    stamp = 0

    do s = 1, nset
       if (state(s) /= UNVISITED) cycle
       sp = 1
       stack_set(1) = s
       stack_pos(1) = head(s)
       state(s) = BUSY
       do while (sp > 0)
          t = stack_set(sp)
          pushed = .false.
          do while (stack_pos(sp) < head(t + 1))
             c = list(stack_pos(sp))
             stack_pos(sp) = stack_pos(sp) + 1
             if (b%chunks(c)%kind /= CH_REF) cycle
             r = find_set(b, b%chunks(c)%ref, elem)
             if (r == 0) then
                call report_loc(st, b%chunks(c)%loc, kind_name//' '//sets(t)%name//' refers to unknown '// &
                     kind_name//' '//b%chunks(c)%ref//' of substructure '//b%name)
             else if (state(r) == BUSY) then
                call report_loc(st, b%chunks(c)%loc, kind_name//' '//sets(t)%name//' refers to '// &
                     kind_name//' '//sets(r)%name//', which refers back to it (cycle)')
             else if (state(r) == UNVISITED) then
                sp = sp + 1
                stack_set(sp) = r
                stack_pos(sp) = head(r)
                state(r) = BUSY
                pushed = .true.
                exit
             end if
          end do
          if (pushed) cycle
          call build_items(t)
          state(t) = DONE
          sp = sp - 1
       end do
    end do
    if (elem) then
       call move_alloc(sets, m%elsets)
    else
       call move_alloc(sets, m%nsets)
    end if

  contains

    subroutine build_items(t)
      integer, intent(in) :: t
      integer :: p, c, r, nbad, k, ngen
      integer(ip) :: id, bad_id, i
      if (.not. allocated(items)) allocate (items(INITIAL_CAPACITY))
      n = 0
      stamp = stamp + 1
      do p = head(t), head(t + 1) - 1
         c = list(p)
         associate (ch => b%chunks(c))
           select case (ch%kind)
           case (CH_IDS)
              nbad = 0
              bad_id = 0
              do k = ch%start, ch%start + ch%count - 1
                 id = b%pool(k)
                 if (elem) then
                    i = find_elem(m, id)
                 else
                    i = find_node(m, id)
                 end if
                 if (i == 0) then
                    nbad = nbad + 1
                    if (nbad == 1) bad_id = id
                 else
                    call add(i)
                 end if
              end do
              if (nbad > 0) call report_loc(st, ch%loc, kind_name//' '//sets(t)%name// &
                   ': undefined '//pick(elem, 'element', 'node')//' '//itoa(bad_id)// &
                   more_text(nbad - 1))
           case (CH_GEN)
              ngen = 0
              call walk_range(ch%gen, ngen)
              if (ngen == 0) call report_loc(st, ch%loc, kind_name//' '//sets(t)%name// &
                   ': GENERATE '//itoa(ch%gen(1))//', '//itoa(ch%gen(2))//', '//itoa(ch%gen(3))// &
                   ' matches no defined id')
           case (CH_RANGE)
              do k = ch%start, ch%start + ch%count - 1
                 call add(int(k, ip))
              end do
           case (CH_REF)
              r = find_set(b, ch%ref, elem)
              if (r > 0) then
                 if (state(r) == DONE) then
                    do k = 1, size(sets(r)%items)
                       call add(sets(r)%items(k))
                    end do
                 end if
              end if
           end select
         end associate
      end do
      sets(t)%items = items(1:n)
    end subroutine build_items

    subroutine add(i)
      integer(ip), intent(in) :: i
      if (mark(i) == stamp) return
      mark(i) = stamp
      call grow(items, n, INITIAL_CAPACITY)
      n = n + 1
      items(n) = i
    end subroutine add

    subroutine walk_range(gen, count)
      !! Members with ids first, first+inc, ... <= last that exist (walks the
      !! sorted ids, so sparse huge ranges cost nothing).
      integer(ip), intent(in) :: gen(3)
      integer, intent(inout) :: count
      integer(ip) :: lo, hi, mid, nn, idv
      if (elem) then
         nn = m%nelem
      else
         nn = m%nnode
      end if
      lo = 1
      hi = nn + 1
      do while (lo < hi)
         mid = lo + (hi - lo)/2
         if (sorted_id(mid) < gen(1)) then
            lo = mid + 1
         else
            hi = mid
         end if
      end do
      do while (lo <= nn)
         idv = sorted_id(lo)
         if (idv > gen(2)) exit
         if (mod(int(idv, i8) - gen(1), int(gen(3), i8)) == 0) then
            count = count + 1
            if (elem) then
               call add(m%elem_order(lo))
            else
               call add(m%node_order(lo))
            end if
         end if
         lo = lo + 1
      end do
    end subroutine walk_range

    integer(ip) function sorted_id(k)
      integer(ip), intent(in) :: k
      if (elem) then
         sorted_id = m%elem_id(m%elem_order(k))
      else
         sorted_id = m%node_id(m%node_order(k))
      end if
    end function sorted_id
  end subroutine resolve_sets

  ! ================================================================== sections

  subroutine build_sections(st, model)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, allocatable :: sub_of(:), count(:)
    integer :: g, isub, k

    allocate (sub_of(st%nsec), count(size(model%subs)))
    count = 0
    do g = 1, st%nsec
       sub_of(g) = resolve_sub(st, model, st%sections(g)%elset, st%sections(g)%loc, 'element set')
       if (sub_of(g) > 0) count(sub_of(g)) = count(sub_of(g)) + 1
    end do
    do isub = 1, size(model%subs)
       deallocate (model%subs(isub)%sections)
       allocate (model%subs(isub)%sections(count(isub)))
    end do
    count = 0
    do g = 1, st%nsec
       isub = sub_of(g)
       if (isub == 0) cycle
       count(isub) = count(isub) + 1
       k = count(isub)
       call build_section(st, model, isub, k, g)
       if (st%aborted) return
    end do
  end subroutine build_sections

  subroutine build_section(st, model, isub, k, g)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, intent(in) :: isub, k, g
    integer :: imat, iset, ntruss, ncps, nb23, nb33, nshell, nbad, nover, other
    integer(ip) :: e, i, first_bad, first_over
    character(:), allocatable :: card

    associate (sb => st%sections(g), sec => model%subs(isub)%sections(k), sub => model%subs(isub))
      select case (sb%kind)
      case (SEC_SOLID)
         card = '*SOLID SECTION'
      case (SEC_BEAM)
         card = '*BEAM SECTION'
      case default
         card = '*SHELL SECTION'
      end select
      sec%kind = sb%kind
      sec%loc = sb%loc
      imat = 0
      do i = 1, size(model%materials)
         if (model%materials(i)%name == sb%material) imat = int(i)
      end do
      if (imat == 0) call report_loc(st, sb%loc, 'unknown material '//sb%material)
      sec%material = imat
      iset = 0
      do i = 1, size(sub%elsets)
         if (sub%elsets(i)%name == sb%elset%set) iset = int(i)
      end do
      sec%elset = iset
      if (iset == 0) then
         call report_loc(st, sb%loc, 'unknown element set '//sb%elset%set//' in substructure '//sub%name)
         st%section_rejected(sb%kind) = .true.   ! its elements are not reported again
         return
      end if

      ntruss = 0; ncps = 0; nb23 = 0; nb33 = 0; nshell = 0; nbad = 0; nover = 0
      first_bad = 0; first_over = 0; other = 0
      do i = 1, size(sub%elsets(iset)%items)
         e = sub%elsets(iset)%items(i)
         select case (sub%elem_type(e))
         case (ET_T2D2, ET_T3D2)
            ntruss = ntruss + 1
            if (sb%kind /= SEC_SOLID) call bad(e)
         case (ET_CPS3, ET_CPS4)
            if (sb%kind == SEC_SHELL) then
               ! Extension: a shell section turns plane elements (as gmsh writes
               ! every 2D mesh) into the shells with the same nodes.
               nshell = nshell + 1
               sub%elem_type(e) = merge(ET_S3, ET_S4, sub%elem_type(e) == ET_CPS3)
            else
               ncps = ncps + 1
               if (sb%kind /= SEC_SOLID) call bad(e)
            end if
         case (ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R)
            ncps = ncps + 1
            if (sb%kind /= SEC_SOLID) call bad(e)
         case (ET_B23, ET_B21)
            nb23 = nb23 + 1
            if (sb%kind /= SEC_BEAM) call bad(e)
         case (ET_B33, ET_B31, ET_B32)
            nb33 = nb33 + 1
            if (sb%kind /= SEC_BEAM) call bad(e)
         case (ET_S3, ET_S4, ET_S4R, ET_S3R, ET_S8R)
            nshell = nshell + 1
            if (sb%kind /= SEC_SHELL) call bad(e)
         end select
         if (sub%elem_section(e) == 0) then
            sub%elem_section(e) = k
         else if (sub%elem_section(e) /= k) then
            nover = nover + 1
            if (nover == 1) then
               first_over = e
               other = sub%elem_section(e)
            end if
         end if
      end do
      if (nbad > 0) call report_loc(st, sb%loc, card//' on element set '//sb%elset%set//': element '// &
           itoa(sub%elem_id(first_bad))//' is of type '//trim(ELEMENT_TYPE_NAMES(sub%elem_type(first_bad)))// &
           ', which needs '//needed_card(sub%elem_type(first_bad))//more_text(nbad - 1))
      if (nover > 0) call report_loc(st, sb%loc, 'element '//itoa(sub%elem_id(first_over))// &
           ' of element set '//sb%elset%set//' already has a section (at '// &
           where(st, sub%sections(other)%loc)//'); an element may have only one section'//more_text(nover - 1))

      if (sb%kind == SEC_BEAM .and. nb23 > 0 .and. nb33 > 0) then
         call report_loc(st, sb%loc, '*BEAM SECTION on element set '//sb%elset%set// &
              ' mixes B23 and B33 elements')
         return
      end if
      if (.not. sb%data_ok) return
      select case (sb%kind)
      case (SEC_SOLID)
         if (sb%nval == 0) then
            ! No data line: plane elements take the thickness 1 (Abaqus's
            ! default); trusses need their area.
            if (ntruss > 0 .or. ncps == 0) then
               call report_loc(st, sb%loc, card//' needs a data line (the cross-section area of the trusses)')
               return
            end if
            sec%thickness = 1.0_wp
            return
         end if
         if (ntruss > 0 .or. ncps == 0) sec%area = sb%val(1)
         if (ncps > 0 .or. ntruss == 0) sec%thickness = sb%val(1)
      case (SEC_SHELL)
         sec%thickness = sb%val(1)
         sec%nodal_thickness = sb%nodal_thickness
         ! *TRANSVERSE SHEAR STIFFNESS K11, K22 [, K12]: per unit length along
         ! the element's local x, y; only the thick shells have shear flexibility.
         if (sb%has_ks) then
            if (sb%nks < 2) then
               call report_loc(st, sb%ks_loc, '*TRANSVERSE SHEAR STIFFNESS of shells needs K11, K22')
               return
            end if
            sec%shear_k = sb%ks
         end if
      case (SEC_BEAM)
         if (sb%shape /= 0) then    ! library shape or Abaqus general section: constants in sb%sp
            sec%area = sb%sp(1)
            call beam_fibres(sb, nb23 > 0, sec)
            if (nb23 > 0) then
               sec%iz = sb%sp(2)    ! a 2D beam bends about section axis 1, normal to its plane
            else
               sec%iy = sb%sp(2)    ! local y = section axis 1 (along v), local z = axis 2
               sec%iz = sb%sp(3)
               sec%j = sb%sp(5)
               sec%has_v = sb%has_v
               if (sb%has_v) sec%v = sb%v
            end if
            return
         end if
         if (nb23 > 0 .and. sb%nval /= BEAM_2D_VALUES) then
            call report_loc(st, sb%data_loc, '*BEAM SECTION of 2D beams (B23) needs A, I')
            return
         end if
         if (nb33 > 0 .and. sb%nval /= BEAM_3D_VALUES) then
            call report_loc(st, sb%data_loc, '*BEAM SECTION of 3D beams (B33) needs A, Iy, Iz, J')
            return
         end if
         sec%area = sb%val(1)
         if (sb%nval == BEAM_2D_VALUES) then
            sec%iz = sb%val(2)
         else
            sec%iy = sb%val(2)
            sec%iz = sb%val(3)
            sec%j = sb%val(4)
         end if
         sec%has_v = sb%has_v
         if (sb%has_v) sec%v = sb%v
         ! *TRANSVERSE SHEAR STIFFNESS K23, K13 (Abaqus cross-section axes 1, 2):
         ! a planar beam deflects along axis 2 (local y), a 3D beam's local y, z
         ! are axes 1, 2.
         if (sb%has_ks) then
            if (sb%nval == BEAM_2D_VALUES) then
               sec%shear_k(1) = sb%ks(1)
            else if (sb%nks < 2) then
               call report_loc(st, sb%ks_loc, '*TRANSVERSE SHEAR STIFFNESS of 3D beams needs K23, K13')
               return
            else
               sec%shear_k = sb%ks([2, 1])
            end if
         end if
      end select
    end associate
  contains
    subroutine bad(e)
      integer(ip), intent(in) :: e
      nbad = nbad + 1
      if (nbad == 1) first_bad = e
    end subroutine bad
  end subroutine build_section

  pure function needed_card(etype) result(card)
    integer, intent(in) :: etype
    character(:), allocatable :: card
    select case (etype)
    case (ET_B23, ET_B33, ET_B21, ET_B31, ET_B32)
       card = '*BEAM SECTION'
    case (ET_S3, ET_S4, ET_S4R, ET_S3R, ET_S8R)
       card = '*SHELL SECTION'
    case default
       card = '*SOLID SECTION'
    end select
  end function needed_card

  pure logical function section_card_rejected(st, etype)
    !! A section card that could have covered an element of type etype was
    !! rejected (already reported): the element is not reported again.
    type(deck_state_t), intent(in) :: st
    integer, intent(in) :: etype
    select case (etype)
    case (ET_B23, ET_B33)
       section_card_rejected = st%section_rejected(SEC_BEAM)
    case (ET_S3, ET_S4, ET_S4R, ET_S3R, ET_S8R)
       section_card_rejected = st%section_rejected(SEC_SHELL)
    case default
       section_card_rejected = st%section_rejected(SEC_SOLID) .or. st%section_rejected(SEC_SHELL)
    end select
  end function section_card_rejected

  subroutine check_unassigned(st, model)
    !! Elements without a section: one message per *ELEMENT card.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, allocatable :: count(:), first_sub(:)
    integer(ip), allocatable :: first_elem(:)
    integer :: isub, c
    integer(ip) :: e
    allocate (count(st%nelem_cards), first_sub(st%nelem_cards), first_elem(st%nelem_cards))
    count = 0
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         do e = 1, sub%nelem
            if (sub%elem_section(e) /= 0) cycle
            if (section_card_rejected(st, sub%elem_type(e))) cycle
            c = st%subs(isub)%elem_card(e)
            count(c) = count(c) + 1
            if (count(c) == 1) then
               first_sub(c) = isub
               first_elem(c) = e
            end if
         end do
       end associate
    end do
    do c = 1, st%nelem_cards
       if (count(c) == 0) cycle
       associate (sub => model%subs(first_sub(c)))
         call report_loc(st, sub%elem_loc(first_elem(c)), 'element '//itoa(sub%elem_id(first_elem(c)))// &
              ' ('//trim(ELEMENT_TYPE_NAMES(sub%elem_type(first_elem(c))))//') has no section: no '// &
              needed_card(sub%elem_type(first_elem(c)))//' covers it'//more_text(count(c) - 1, &
              ' of this *ELEMENT card'))
       end associate
    end do
  end subroutine check_unassigned

  ! ================================================================== references

  integer function resolve_sub(st, model, ref, loc, what) result(isub)
    !! Substructure a reference points to (0 and reported when there is none).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(ref_t), intent(in) :: ref
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: what
    if (allocated(ref%scope)) then
       isub = sub_index(model, ref%scope)
       if (isub == 0) call report_loc(st, loc, 'unknown substructure '//ref%scope//' in '// &
            ref_text(ref)//part_hint(model, ref%scope))
    else if (ref%home > 0) then
       isub = ref%home
    else
       isub = sub_index(model, MAIN_NAME)
       if (ref%is_set) isub = assembly_set_owner(model, ref%set, what /= 'node', isub)
       if (isub == 0) call report_loc(st, loc, what//' '//ref_text(ref)// &
            ' is not in a substructure: outside *SUBSTRUCTURE blocks write SUB.id or SUB.set '// &
            '(no nodes were defined outside the blocks, so there is no substructure MAIN)')
    end if
  end function resolve_sub

  pure integer function sub_index(model, name) result(k)
    !! Index of the substructure named `name` (0 if none).
    type(model_t), intent(in) :: model
    character(*), intent(in) :: name
    do k = size(model%subs), 1, -1
       if (model%subs(k)%name == name) return
    end do
    k = 0
  end function sub_index

  pure function ref_text(ref) result(s)
    !! A reference as the user wrote it (upper case).
    type(ref_t), intent(in) :: ref
    character(:), allocatable :: s
    if (ref%is_set) then
       s = ref%set
    else
       s = itoa(ref%id)
    end if
    if (allocated(ref%scope)) s = ref%scope//'.'//s
  end function ref_text

  subroutine resolve_items(st, model, isub, ref, elem, loc, items, ok)
    !! Local node (elem false) or element indices a reference names in substructure isub.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(ref_t), intent(in) :: ref
    logical, intent(in) :: elem
    type(source_loc_t), intent(in) :: loc
    integer(ip), allocatable, intent(out) :: items(:)
    logical, intent(out) :: ok
    integer :: k
    integer(ip) :: i
    character(:), allocatable :: what
    what = pick(elem, 'element', 'node')
    ok = .false.
    associate (sub => model%subs(isub))
      if (ref%is_set) then
         k = 0
         if (elem) then
            do i = 1, size(sub%elsets)
               if (sub%elsets(i)%name == ref%set) k = int(i)
            end do
            if (k > 0) items = sub%elsets(k)%items
         else
            do i = 1, size(sub%nsets)
               if (sub%nsets(i)%name == ref%set) k = int(i)
            end do
            if (k > 0) items = sub%nsets(k)%items
         end if
         if (k == 0) then
            call report_loc(st, loc, 'unknown '//what//' set '//ref%set//' in substructure '//sub%name)
            return
         end if
      else
         if (elem) then
            i = find_elem(sub, ref%id)
         else
            i = find_node(sub, ref%id)
         end if
         if (i == 0) then
            call report_loc(st, loc, 'undefined '//what//' '//itoa(ref%id)//' in substructure '//sub%name)
            return
         end if
         items = [i]
      end if
    end associate
    ok = .true.
  end subroutine resolve_items

  ! ================================================================== contacts

  subroutine build_contacts(st, model)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(link_list_t) :: links
    type(pair_map_t) :: map
    integer(ip), allocatable :: ms(:), ss(:)
    integer :: k, l, cur, il, nself
    integer(ip) :: p, np, mnode, snode
    logical :: ok1, ok2, added
    logical, allocatable :: usable(:)
    integer(i8) :: failed_bytes

    allocate (model%contacts(st%ncontact), usable(st%ncontact))
    do k = 1, st%ncontact
       associate (cb => st%contacts(k), c => model%contacts(k))
         c%name = cb%name
         c%loc = cb%loc
         c%master_sub = sub_index(model, cb%master)
         c%remote = cb%remote
         c%rigid_offset = cb%rigid_offset
         c%slave_sub = sub_index(model, cb%slave)
         if (c%master_sub == 0) call report_loc(st, cb%loc, 'unknown substructure '//cb%master//' in MASTER='// &
              part_hint(model, cb%master))
         if (c%slave_sub == 0) call report_loc(st, cb%loc, 'unknown substructure '//cb%slave//' in SLAVE='// &
              part_hint(model, cb%slave))
         c%orientation = 0
         if (allocated(cb%orientation)) then
            if (len(cb%orientation) > 0) then
               do l = 1, size(model%orientations)
                  if (model%orientations(l)%name == cb%orientation) c%orientation = l
               end do
               if (c%orientation == 0) call report_loc(st, cb%loc, 'unknown orientation '//cb%orientation)
            end if
         end if
         usable(k) = c%master_sub > 0 .and. c%slave_sub > 0
       end associate
    end do

    allocate (links%a(INITIAL_CAPACITY))
    cur = 0
    do l = 1, st%ncline
       if (st%aborted) return
       associate (cl => st%clines(l))
         if (.not. usable(cl%contact)) cycle
         if (cl%contact /= cur) then
            cur = cl%contact
            call map_reset(map)
         end if
         associate (c => model%contacts(cur))
           call resolve_items(st, model, c%master_sub, cl%master, .false., cl%loc, ms, ok1)
           call resolve_items(st, model, c%slave_sub, cl%slave, .false., cl%loc, ss, ok2)
           if (.not. (ok1 .and. ok2)) cycle
           if (st%contacts(cur)%nearest) then
              call pair_nearest(st, model, cur, cl%loc, ms, ss, ok1)
              if (.not. ok1) cycle
           end if
           if (size(ms) /= size(ss)) then
              if (.not. cl%master%is_set .or. .not. cl%slave%is_set) then
                 call report_loc(st, cl%loc, 'node '//ref_text(pick_node(cl%master, cl%slave))// &
                      ' is paired with node set '//pick_set_name(cl%master, cl%slave)//' of '// &
                      plural(max(size(ms), size(ss)), 'node')//' (a single node pairs only with a one-node set)')
              else
                 call report_loc(st, cl%loc, 'node sets '//cl%master%set//' ('//plural(size(ms), 'node')// &
                      ') and '//cl%slave%set//' ('//plural(size(ss), 'node')//') differ in size')
              end if
              cycle
           end if
           np = size(ms, kind=ip)
           nself = 0
           do p = 1, np
              mnode = ms(p)
              snode = ss(p)
              if (c%master_sub == c%slave_sub .and. mnode == snode) then
                 nself = nself + 1
                 if (nself == 1) call report_loc(st, cl%loc, 'node '//itoa(model%subs(c%master_sub)%node_id(mnode))// &
                      ' of substructure '//model%subs(c%master_sub)%name//' is in contact with itself')
                 cycle
              end if
              call map_get_or_add(map, int(mnode, i8)*PAIR_SHIFT + snode, links%n + 1, il, added)
              if (added) then
                 call push_link(links, failed_bytes)
                 if (failed_bytes > 0) then
                    call report_oom(st, cl%loc, 'the contact elements ('//itoa(2*links%n)//')', failed_bytes)
                    return
                 end if
                 links%a(il)%contact = cur
                 links%a(il)%master_node = mnode
                 links%a(il)%slave_node = snode
                 links%a(il)%loc = cl%loc
              end if
              call merge_dofs(links%a(il), cl%first, cl%last, cl%state, cl%g)
           end do
         end associate
       end associate
    end do
    model%links = links%a(1:links%n)
  end subroutine build_contacts

  pure function pick_node(a, b) result(r)
    type(ref_t), intent(in) :: a, b
    type(ref_t) :: r
    if (.not. a%is_set) then
       r = a
    else
       r = b
    end if
  end function pick_node

  pure function pick_set_name(a, b) result(s)
    type(ref_t), intent(in) :: a, b
    character(:), allocatable :: s
    if (a%is_set) then
       s = a%set
    else
       s = b%set
    end if
  end function pick_set_name

  pure subroutine merge_dofs(link, first, last, state, g)
    !! Add one contact line's DOFs to a link: finite g add up, RIGID wins, 0 adds nothing.
    type(link_t), intent(inout) :: link
    integer, intent(in) :: first, last, state
    real(wp), intent(in) :: g
    integer :: d
    do d = first, last
       select case (state)
       case (LINK_RIGID)
          link%state(d) = LINK_RIGID
          link%g(d) = 0.0_wp
       case (LINK_FINITE)
          if (link%state(d) /= LINK_RIGID) then
             link%state(d) = LINK_FINITE
             link%g(d) = link%g(d) + g
          end if
       end select
    end do
  end subroutine merge_dofs

  subroutine push_link(list, failed_bytes)
    type(link_list_t), intent(inout) :: list
    integer(i8), intent(out) :: failed_bytes
    type(link_t), allocatable :: tmp(:)
    integer :: stat
    failed_bytes = 0
    if (list%n == size(list%a)) then
       allocate (tmp(2*list%n), stat=stat)
       if (stat /= 0) then
          failed_bytes = 2*int(list%n, i8)*storage_size(list%a(1))/8
          return
       end if
       tmp(1:list%n) = list%a(1:list%n)
       call move_alloc(tmp, list%a)
    end if
    list%n = list%n + 1
    list%a(list%n) = link_t()
  end subroutine push_link

  ! ------------------------------------------------------------------ pair map

  subroutine map_reset(map)
    type(pair_map_t), intent(inout) :: map
    if (allocated(map%keys)) deallocate (map%keys, map%vals)
    allocate (map%keys(0:INITIAL_HASH - 1), map%vals(0:INITIAL_HASH - 1))
    map%keys = EMPTY_KEY
    map%n = 0
  end subroutine map_reset

  pure integer function slot_of(key, mask) result(h)
    integer(i8), intent(in) :: key
    integer, intent(in) :: mask
    integer(i8) :: m, s, x
    m = key/PAIR_SHIFT
    s = mod(key, PAIR_SHIFT)
    x = ieor(m*HASH_MUL1, s*HASH_MUL2 + ishft(m, 7))
    x = ieor(x, ishft(x, -29))
    h = int(iand(x, int(mask, i8)))
  end function slot_of

  subroutine map_get_or_add(map, key, newval, val, added)
    !! Value stored for `key`; when absent, `newval` is stored and `added` is true.
    type(pair_map_t), intent(inout) :: map
    integer(i8), intent(in) :: key
    integer, intent(in) :: newval
    integer, intent(out) :: val
    logical, intent(out) :: added
    integer :: h, mask
    if (2*(map%n + 1) > size(map%keys)) call rehash
    mask = size(map%keys) - 1
    h = slot_of(key, mask)
    do
       if (map%keys(h) == key) then
          val = map%vals(h)
          added = .false.
          return
       end if
       if (map%keys(h) == EMPTY_KEY) exit
       h = iand(h + 1, mask)
    end do
    map%keys(h) = key
    map%vals(h) = newval
    map%n = map%n + 1
    val = newval
    added = .true.
  contains
    subroutine rehash
      integer(i8), allocatable :: ok(:)
      integer, allocatable :: ov(:)
      integer :: i, nmask, j
      call move_alloc(map%keys, ok)
      call move_alloc(map%vals, ov)
      allocate (map%keys(0:2*size(ok) - 1), map%vals(0:2*size(ok) - 1))
      map%keys = EMPTY_KEY
      nmask = size(map%keys) - 1
      do i = 0, size(ok) - 1
         if (ok(i) == EMPTY_KEY) cycle
         j = slot_of(ok(i), nmask)
         do while (map%keys(j) /= EMPTY_KEY)
            j = iand(j + 1, nmask)
         end do
         map%keys(j) = ok(i)
         map%vals(j) = ov(i)
      end do
    end subroutine rehash
  end subroutine map_get_or_add

  ! ================================================================== supports and loads

  subroutine build_supports(st, model)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    call support_list(st, model, 0, model%supports)
  end subroutine build_supports

  subroutine support_list(st, model, step, out)
    !! The supported DOFs of the *SUPPORT and *BOUNDARY lines of a step (0: model data).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: step
    type(support_t), allocatable, intent(out) :: out(:)
    type(support_t), allocatable :: list(:), tmp(:)
    integer(ip), allocatable :: nodes(:)
    integer :: k, n, isub, d, stat
    integer(ip) :: i
    logical :: ok
    allocate (list(INITIAL_CAPACITY))
    n = 0
    do k = 1, st%nsupport
       if (st%aborted) return
       if (st%supports(k)%step /= step) cycle
       associate (sb => st%supports(k))
         isub = resolve_sub(st, model, sb%ref, sb%loc, 'node')
         if (isub == 0) cycle
         call resolve_items(st, model, isub, sb%ref, .false., sb%loc, nodes, ok)
         if (.not. ok) cycle
         do i = 1, size(nodes, kind=ip)
            do d = 1, NDOF_NODE
               if (.not. sb%dofs(d)) cycle
               if (n == size(list)) then
                  allocate (tmp(2*n), stat=stat)
                  if (stat /= 0) then
                     call report_oom(st, sb%loc, 'the supported DOFs ('//itoa(2*n)//')', &
                          2*int(n, i8)*storage_size(list(1))/8)
                     return
                  end if
                  tmp(1:n) = list(1:n)
                  call move_alloc(tmp, list)
               end if
               n = n + 1
               list(n)%sub = isub
               list(n)%node = nodes(i)
               list(n)%dof = d
               list(n)%state = sb%state
               list(n)%g = sb%g
               list(n)%value = sb%value
               list(n)%loc = sb%loc
               list(n)%from_boundary = sb%boundary
            end do
         end do
       end associate
    end do
    ! explicit allocation: an assignment's reallocation would not report failure
    allocate (out(n), stat=stat)
    if (stat /= 0) then
       call report_oom(st, st%supports(st%nsupport)%loc, 'the supported DOFs ('//itoa(n)//')', &
            int(n, i8)*storage_size(list(1))/8)
       return
    end if
    out(1:n) = list(1:n)
  end subroutine support_list

  subroutine build_thermal(st, model)
    !! Thermal loads from *INITIAL CONDITIONS, TYPE=TEMPERATURE and the steps'
    !! *TEMPERATURE lines: a truss or beam whose material has *EXPANSION gets,
    !! in each step with temperatures, the load of its uniform temperature
    !! change ΔT (the mean of its nodes' T - T0; nodes without a step
    !! temperature keep T0, or the previous step's temperature where the step
    !! continues it (keeps_previous), nodes without an initial one start at 0), a
    !! DLOAD_THERMAL entry of value E A α ΔT; a beam also the thermal
    !! curvatures α ∂T/∂y, α ∂T/∂z of the gradients across its section at its
    !! two nodes (linear in between)
    !! (CalculiX's third field: along the 2-direction, local z of B31/B33,
    !! local y of the planar B21/B23; the fourth: along the 1-direction, local
    !! y). A plane or shell element gets the entry of its thermal strain α ΔT
    !! (the mean over its nodes; an element whose nodes differ also the
    !! nodal remainders, interpolated to its integration points) and, on shells,
    !! of its curvature α ∂T/∂n (the mean of its nodes' gradients, the third
    !! field of the temperature lines, with the nodal remainders likewise); a B32 gets α ΔT and both gradients at
    !! its three nodes (line_nodal, interpolated along it); a gradient on any
    !! other element is refused.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(real_list_t), allocatable :: t0(:), t(:), g0(:), g(:), h0(:), h(:), tp(:), gp(:), hp(:)
    type(dload_t), allocatable :: extra(:)
    logical :: kept
    integer :: s, isub, nn, nplate
    integer(ip) :: e, i, first_plate
    integer(ip), allocatable :: nodes(:)
    logical :: ok
    real(wp) :: dt, dg, dh, dtn(MAX_ELEMENT_NODES), dgn(MAX_ELEMENT_NODES)
    type(source_loc_t) :: plate_loc
    if (st%ntemp == 0) return
    allocate (t0(size(model%subs)), t(size(model%subs)), g0(size(model%subs)), h0(size(model%subs)))
    do isub = 1, size(model%subs)
       allocate (t0(isub)%v(model%subs(isub)%nnode), source=0.0_wp)
       allocate (g0(isub)%v(model%subs(isub)%nnode), source=0.0_wp)
       allocate (h0(isub)%v(model%subs(isub)%nnode), source=0.0_wp)
    end do
    call apply_lines(0, t0, g0, h0)
    tp = t0
    gp = g0
    hp = h0
    do s = 1, size(model%steps)
       ! the step's temperatures start from the previous step's (OP=MOD, or
       ! CalculiX's rule in a step with *STATIC) or from the initial ones
       kept = .false.
       if (s > 1 .and. keeps_previous(st%steps(s), st%steps(s)%temp_op)) &
            kept = differ(tp, t0) .or. differ(gp, g0) .or. differ(hp, h0)
       model%steps(s)%kept_temperatures = kept
       if (kept) model%steps(s)%kept_from = model%steps(s - 1)%name
       if (.not. kept .and. .not. any(st%temps(1:st%ntemp)%step == s)) then
          call keep_temperatures(s, t0)
          tp = t0
          gp = g0
          hp = h0
          cycle
       end if
       if (kept) then
          t = tp
          g = gp
          h = hp
       else
          t = t0
          g = g0
          h = h0
       end if
       call apply_lines(s, t, g, h)
       if (st%aborted) return
       call keep_temperatures(s, t)
       tp = t
       gp = g
       hp = h
       allocate (extra(0))
       nplate = 0
       do isub = 1, size(model%subs)
          associate (sub => model%subs(isub))
            do e = 1, sub%nelem
               if (sub%elem_section(e) == 0) cycle
               ! an undefined material or node has been reported already
               if (sub%sections(sub%elem_section(e))%material <= 0) cycle
               associate (sec => sub%sections(sub%elem_section(e)))
                 associate (mat => model%materials(sec%material))
                   if (.not. mat%has_expansion .or. mat%alpha == 0.0_wp) cycle
                   nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
                   ! an element with an undefined node has been reported already
                   if (nn == 0 .or. any(sub%elem_nodes(1:nn, e) <= 0)) cycle
                   associate (en => sub%elem_nodes(1:nn, e))
                     dtn(1:nn) = t(isub)%v(en) - t0(isub)%v(en)
                     dgn(1:nn) = g(isub)%v(en) - g0(isub)%v(en)
                     dt = sum(t(isub)%v(en) - t0(isub)%v(en))/nn
                     dg = sum(g(isub)%v(en) - g0(isub)%v(en))/nn
                     dh = sum(h(isub)%v(en) - h0(isub)%v(en))/nn
                   end associate
                   if (dt == 0.0_wp .and. dg == 0.0_wp .and. dh == 0.0_wp .and. all(dtn(1:nn) == 0.0_wp) &
                        .and. all(dgn(1:nn) == 0.0_wp)) cycle
                   select case (sub%elem_type(e))
                   case (ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_B21, ET_B31)
                      if (dg /= 0.0_wp .and. any(sub%elem_type(e) == [ET_T2D2, ET_T3D2])) then
                         call refuse('the gradients (third and fourth fields) apply to shells and beams only')
                         return
                      end if
                      if (dh /= 0.0_wp .and. any(sub%elem_type(e) == [ET_T2D2, ET_T3D2, ET_B23, ET_B21])) then
                         call refuse('the fourth field, the gradient along the 1-direction of a beam in space, '// &
                              'acts normal to the plane of a planar element')
                         return
                      end if
                      extra = [extra, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, &
                           value=mat%e*sec%area*mat%alpha*dt, loc=first_line(s))]
                      if (any(sub%elem_type(e) == [ET_B23, ET_B21])) then
                         extra(size(extra))%gradient(1, :) = mat%alpha*(g(isub)%v(sub%elem_nodes(1:2, e)) - &
                              g0(isub)%v(sub%elem_nodes(1:2, e)))
                      else if (any(sub%elem_type(e) == [ET_B33, ET_B31])) then
                         extra(size(extra))%gradient(1, :) = mat%alpha*(h(isub)%v(sub%elem_nodes(1:2, e)) - &
                              h0(isub)%v(sub%elem_nodes(1:2, e)))
                         extra(size(extra))%gradient(2, :) = mat%alpha*(g(isub)%v(sub%elem_nodes(1:2, e)) - &
                              g0(isub)%v(sub%elem_nodes(1:2, e)))
                      end if
                   case (ET_B32)
                      ! the three-node beam: α ΔT and both gradients (fourth field: local y,
                      ! third: local z) at each node, interpolated along it
                      extra = [extra, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, value=0.0_wp, &
                           loc=first_line(s))]
                      associate (en => sub%elem_nodes(1:3, e))
                        extra(size(extra))%line_nodal = mat%alpha*transpose(reshape([ &
                             t(isub)%v(en) - t0(isub)%v(en), h(isub)%v(en) - h0(isub)%v(en), &
                             g(isub)%v(en) - g0(isub)%v(en)], [3, 3]))
                      end associate
                   case (ET_CPS3, ET_CPS4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, &
                        ET_CPE8R, ET_S3, ET_S4, ET_S4R, ET_S3R, ET_S8R)
                      if ((dg /= 0.0_wp .and. .not. any(sub%elem_type(e) == [ET_S3, ET_S4, ET_S4R, ET_S3R, ET_S8R])) &
                           .or. dh /= 0.0_wp) then
                         call refuse('the gradient (third field) applies to shells and beams only, the fourth '// &
                              'field to beams only')
                         return
                      end if
                      extra = [extra, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, &
                           value=mat%alpha*dt, curvature=mat%alpha*dg, loc=first_line(s))]
                      ! a plane element whose nodes differ: the nodal values, interpolated to its points
                      if (is_plane_type(sub%elem_type(e)) .and. any(dtn(1:nn) /= dtn(1))) &
                           extra(size(extra))%nodal = mat%alpha*dtn(1:nn) - mat%alpha*dt
                      ! a shell whose nodes differ: both nodal remainders, interpolated to its points
                      if (.not. is_plane_type(sub%elem_type(e)) .and. &
                           (any(dtn(1:nn) /= dtn(1)) .or. any(dgn(1:nn) /= dgn(1)))) then
                         extra(size(extra))%nodal = mat%alpha*dtn(1:nn) - mat%alpha*dt
                         extra(size(extra))%curvature_nodal = mat%alpha*dgn(1:nn) - mat%alpha*dg
                      end if
                   case default
                      nplate = nplate + 1
                      if (nplate == 1) then
                         first_plate = e
                         plate_loc = first_line(s)
                      end if
                   end select
                 end associate
               end associate
            end do
            if (nplate > 0) then
               call report_loc(st, plate_loc, 'temperature change on element '//itoa(sub%elem_id(first_plate))// &
                    ' of type '//trim(ELEMENT_TYPE_NAMES(sub%elem_type(first_plate)))//' of substructure '// &
                    sub%name//': thermal loads are implemented for trusses, beams, plane elements and S3, S4, S3R, S4R, S8R shells only'// &
                    more_text(nplate - 1))
               nplate = 0
            end if
          end associate
       end do
       model%steps(s)%dloads = [model%steps(s)%dloads, extra]
       deallocate (extra)
    end do
  contains
    subroutine keep_temperatures(step, field)
      !! The nodal temperatures of a step, for *NODE PRINT NT.
      integer, intent(in) :: step
      type(real_list_t), intent(in) :: field(:)
      integer :: k
      if (model%steps(step)%combination > 0) return
      if (.not. allocated(model%steps(step)%temperature)) allocate (model%steps(step)%temperature(size(field)))
      do k = 1, size(field)
         model%steps(step)%temperature(k)%v = field(k)%v
      end do
    end subroutine keep_temperatures

    pure logical function differ(a, b)
      !! Whether two nodal fields (per substructure) differ anywhere.
      type(real_list_t), intent(in) :: a(:), b(:)
      integer :: k
      differ = .false.
      do k = 1, size(a)
         if (any(a(k)%v /= b(k)%v)) differ = .true.
      end do
    end function differ

    subroutine refuse(why)
      !! Refuse a gradient on element e of substructure isub of step s.
      character(*), intent(in) :: why
      call report_loc(st, first_line(s), 'temperature gradient on element '// &
           itoa(model%subs(isub)%elem_id(e))//' of type '// &
           trim(ELEMENT_TYPE_NAMES(model%subs(isub)%elem_type(e)))//': '//why)
    end subroutine refuse
    subroutine apply_lines(step, field, grad, grad1)
      !! Set the temperatures and gradients the lines of step (0: initial conditions) give.
      integer, intent(in) :: step
      type(real_list_t), intent(inout) :: field(:), grad(:), grad1(:)
      integer :: j, js
      do j = 1, st%ntemp
         if (st%temps(j)%step /= step) cycle
         js = resolve_sub(st, model, st%temps(j)%ref, st%temps(j)%loc, 'node')
         if (js == 0) cycle
         call resolve_items(st, model, js, st%temps(j)%ref, .false., st%temps(j)%loc, nodes, ok)
         if (.not. ok) cycle
         do i = 1, size(nodes, kind=ip)
            field(js)%v(nodes(i)) = st%temps(j)%value
            grad(js)%v(nodes(i)) = st%temps(j)%grad
            grad1(js)%v(nodes(i)) = st%temps(j)%grad1
         end do
      end do
    end subroutine apply_lines
    function first_line(step) result(loc)
      !! The first *TEMPERATURE line of a step (where its thermal loads come from).
      integer, intent(in) :: step
      type(source_loc_t) :: loc
      integer :: j
      loc = model%steps(step)%loc
      do j = 1, st%ntemp
         if (st%temps(j)%step == step) then
            loc = st%temps(j)%loc
            return
         end if
      end do
    end function first_line
  end subroutine build_thermal

  subroutine build_history(st, model)
    !! The steps' boundary conditions and the loads continued by OP=MOD
    !! (superjoin_model_history).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(support_list_t), allocatable :: own(:)
    type(step_ops_t), allocatable :: ops(:)
    integer :: s
    allocate (own(st%nstep), ops(st%nstep))
    do s = 1, st%nstep
       ops(s)%bc_new = st%steps(s)%bc_op == OP_NEW
       ops(s)%cload_mod = keeps_previous(st%steps(s), st%steps(s)%cload_op)
       ops(s)%dload_mod = keeps_previous(st%steps(s), st%steps(s)%dload_op)
    end do
    call apply_load_history(model, ops)
    if (.not. any(st%steps(1:st%nstep)%has_boundary)) return
    do s = 1, st%nstep
       call support_list(st, model, s, own(s)%items)
       if (st%aborted) return
    end do
    call apply_boundary_history(model, own, ops)
  end subroutine build_history

  pure logical function keeps_previous(step, op)
    !! Whether a step's loads of one kind (*CLOAD, *DLOAD or *TEMPERATURE,
    !! whose cards say op) continue those of the previous step: with OP=MOD,
    !! and by default in a step with a procedure card (*STATIC) that is not a
    !! PERTURBATION step, as ccx 2.20 does (checked on two-step decks); a
    !! superjoin step without a procedure card is a load case of its own.
    type(step_b_t), intent(in) :: step
    integer, intent(in) :: op
    keeps_previous = op == OP_MOD .or. (op == OP_DEFAULT .and. step%has_procedure .and. .not. step%perturbation)
  end function keeps_previous

  subroutine build_steps(st, model)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: s, j
    type(cload_t), allocatable :: cl(:)
    type(dload_t), allocatable :: dl(:)
    type(load_b_t), allocatable :: own(:)
    allocate (model%steps(st%nstep))
    do s = 1, st%nstep
       model%steps(s)%name = st%steps(s)%name
       model%steps(s)%loc = st%steps(s)%loc
       model%steps(s)%procedure_card = st%steps(s)%has_procedure
       do j = 1, s - 1
          if (st%steps(j)%name == st%steps(s)%name) then
             call report_loc(st, st%steps(s)%loc, 'duplicate step name '//st%steps(s)%name// &
                  ' (first at '//where(st, st%steps(j)%loc)//')')
             exit
          end if
       end do
       call build_cloads(st, model, st%steps(s)%cloads(1:st%steps(s)%ncload), cl)
       call move_alloc(cl, model%steps(s)%cloads)
       if (st%aborted) return
       own = st%steps(s)%dloads(1:st%steps(s)%ndload)
       ! CalculiX rules (a step with *STATIC): *DLOAD P pushes along the shell
       ! normal; superjoin's own P (and the load of a *SURFACE SPOS face)
       ! pushes against it
       if (st%steps(s)%has_procedure) where (own%kind == DLOAD_P .and. .not. own%surface) own%value = -own%value
       call build_dloads(st, model, own, dl)
       call move_alloc(dl, model%steps(s)%dloads)
       if (st%aborted) return
    end do
    call build_thermal(st, model)
    if (st%aborted) return
    call build_history(st, model)
  end subroutine build_steps

  subroutine build_cloads(st, model, loads, out)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(load_b_t), intent(in) :: loads(:)
    type(cload_t), allocatable, intent(out) :: out(:)
    type(cload_t), allocatable :: tmp(:)
    integer(ip), allocatable :: nodes(:)
    integer :: k, n, isub, stat
    integer(ip) :: i
    logical :: ok
    allocate (out(INITIAL_CAPACITY))
    n = 0
    do k = 1, size(loads)
       isub = resolve_sub(st, model, loads(k)%ref, loads(k)%loc, 'node')
       if (isub == 0) cycle
       call resolve_items(st, model, isub, loads(k)%ref, .false., loads(k)%loc, nodes, ok)
       if (.not. ok) cycle
       do i = 1, size(nodes, kind=ip)
          call grow(out, n, INITIAL_CAPACITY, stat)
          if (stat /= 0) then
             call report_oom(st, loads(k)%loc, 'the concentrated loads', &
                  int(max(2*n, INITIAL_CAPACITY), i8)*storage_size(out)/8)
             return
          end if
          n = n + 1
          out(n)%sub = isub
          out(n)%node = nodes(i)
          out(n)%dof = loads(k)%dof
          out(n)%value = loads(k)%value
          out(n)%loc = loads(k)%loc
       end do
    end do
    allocate (tmp(n), stat=stat)
    if (stat /= 0) then
       call report_oom(st, loads(size(loads))%loc, 'the concentrated loads', int(n, i8)*storage_size(out)/8)
       return
    end if
    tmp(:) = out(1:n)
    call move_alloc(tmp, out)
  end subroutine build_cloads

  subroutine build_dloads(st, model, loads, out)
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(load_b_t), intent(in) :: loads(:)
    type(dload_t), allocatable, intent(out) :: out(:)
    type(dload_t), allocatable :: tmp(:)
    integer(ip), allocatable :: elems(:)
    integer :: k, n, isub, nbad, et, stat
    integer(ip) :: i, first_bad
    logical :: ok
    allocate (out(INITIAL_CAPACITY))
    n = 0
    do k = 1, size(loads)
       if (loads(k)%whole_model) then
          ! GRAV with an empty element field: every element of the model, or of
          ! the substructure whose block the line stands in
          do isub = 1, size(model%subs)
             if (loads(k)%home /= 0 .and. isub /= loads(k)%home) cycle
             elems = [(i, i=1, model%subs(isub)%nelem)]
             call add_elements()
             if (st%aborted) return
          end do
          cycle
       end if
       isub = resolve_sub(st, model, loads(k)%ref, loads(k)%loc, 'element')
       if (isub == 0) cycle
       call resolve_items(st, model, isub, loads(k)%ref, .true., loads(k)%loc, elems, ok)
       if (.not. ok) cycle
       call add_elements()
       if (st%aborted) return
    end do
    allocate (tmp(n), stat=stat)
    if (stat /= 0) then
       call report_oom(st, loads(size(loads))%loc, 'the distributed loads', int(n, i8)*storage_size(out)/8)
       return
    end if
    tmp(:) = out(1:n)
    call move_alloc(tmp, out)
  contains
    subroutine add_elements()
      !! The loads of line k on elems of substructure isub, with the checks.
       integer :: nodens
       integer(ip) :: first_nodens
       logical :: plane_ok
       nbad = 0
       first_bad = 0
       nodens = 0
       first_nodens = 0
       ! CENTRIF keeps the XY plane in itself: axis along Z, or in the plane
       plane_ok = loads(k)%kind /= DLOAD_CENTRIF .or. abs(loads(k)%dir(3)) == 1.0_wp .or. &
            (loads(k)%dir(3) == 0.0_wp .and. loads(k)%point(3) == 0.0_wp)
       do i = 1, size(elems, kind=ip)
          et = model%subs(isub)%elem_type(elems(i))
          if (.not. dload_fits(loads(k)%kind, et)) then
             nbad = nbad + 1
             if (nbad == 1) first_bad = elems(i)
             cycle
          end if
          if (loads(k)%kind == DLOAD_CENTRIF .and. .not. plane_ok) then
             if (any(et == [ET_CPS3, ET_CPS4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, &
                  ET_CPE8R])) then
                call report_loc(st, loads(k)%loc, 'CENTRIF loads a plane element out of the XY plane '// &
                     '(the axis must be parallel to Z, or lie in the XY plane)')
                plane_ok = .true.   ! reported once
                cycle
             end if
          end if
          if (loads(k)%kind == DLOAD_GRAV .or. loads(k)%kind == DLOAD_CENTRIF) then
             associate (sub => model%subs(isub))
               if (sub%elem_section(elems(i)) == 0) cycle
               if (.not. model%materials(sub%sections(sub%elem_section(elems(i)))%material)%has_density) then
                  nodens = nodens + 1
                  if (nodens == 1) first_nodens = elems(i)
                  cycle
               end if
             end associate
          end if
          call grow(out, n, INITIAL_CAPACITY, stat)
          if (stat /= 0) then
             call report_oom(st, loads(k)%loc, 'the distributed loads', &
                  int(max(2*n, INITIAL_CAPACITY), i8)*storage_size(out)/8)
             return
          end if
          n = n + 1
          out(n)%sub = isub
          out(n)%elem = elems(i)
          out(n)%kind = loads(k)%kind
          out(n)%value = loads(k)%value
          out(n)%dir = loads(k)%dir
          out(n)%point = loads(k)%point
          out(n)%loc = loads(k)%loc
       end do
       if (nodens > 0) then
          associate (sub => model%subs(isub))
            call report_loc(st, loads(k)%loc, '*DLOAD '//trim(DLOAD_NAMES(loads(k)%kind))//' on element '// &
                 itoa(sub%elem_id(first_nodens))// &
                 ' of substructure '//sub%name//', whose material '// &
                 model%materials(sub%sections(sub%elem_section(first_nodens))%material)%name// &
                 ' has no *DENSITY'//more_text(nodens - 1))
          end associate
       end if
       if (nbad > 0) then
          associate (sub => model%subs(isub))
            call report_loc(st, loads(k)%loc, trim(merge('*DSLOAD: face', '*DLOAD       ', loads(k)%surface))// &
                 ' '//trim(surface_face(loads(k)))//' does not apply to element '//itoa(sub%elem_id(first_bad))//' of type '// &
                 trim(ELEMENT_TYPE_NAMES(sub%elem_type(first_bad)))//' ('// &
                 dload_targets(loads(k)%kind)//')'//more_text(nbad - 1))
          end associate
       end if
    end subroutine add_elements
  end subroutine build_dloads

  pure function surface_face(ld) result(name)
    !! The load form as the deck wrote it: a *DLOAD type, or the face of a
    !! *SURFACE line (S1 to S4, SPOS / SNEG) for a *DSLOAD.
    type(load_b_t), intent(in) :: ld
    character(:), allocatable :: name
    name = trim(DLOAD_NAMES(ld%kind))
    if (.not. ld%surface) return
    if (ld%kind >= DLOAD_P1 .and. ld%kind <= DLOAD_P4) then
       name = 'S'//name(2:2)//' (edge '//name(2:2)//')'
    else if (ld%kind == DLOAD_P) then
       name = 'SPOS or SNEG'
    end if
  end function surface_face

  pure logical function dload_fits(kind, etype)
    !! Whether a distributed load kind applies to an element type.
    integer, intent(in) :: kind, etype
    select case (kind)
    case (DLOAD_PX, DLOAD_PY)
       dload_fits = etype == ET_B23 .or. etype == ET_B33 .or. etype == ET_B21 .or. etype == ET_B31 .or. &
            etype == ET_B32
    case (DLOAD_PZ)
       dload_fits = etype == ET_B33 .or. etype == ET_B31 .or. etype == ET_B32
    case (DLOAD_P)
       dload_fits = etype == ET_S3 .or. etype == ET_S4 .or. etype == ET_S4R .or. etype == ET_S3R .or. &
            etype == ET_S8R
    case (DLOAD_GRAV)
       dload_fits = .true.
    case (DLOAD_CENTRIF)
       dload_fits = etype /= ET_B32
    case (DLOAD_P1)
       dload_fits = is_plane_type(etype) .or. etype == ET_B33 .or. etype == ET_B31
    case (DLOAD_P2)
       dload_fits = is_plane_type(etype) .or. etype == ET_B23 .or. etype == ET_B33 .or. etype == ET_B21 .or. etype == ET_B31
    case (DLOAD_P3)
       dload_fits = is_plane_type(etype)
    case (DLOAD_P4)
       dload_fits = is_plane_type(etype) .and. .not. any(etype == [ET_CPS3, ET_CPE3, ET_CPS6, ET_CPE6])
    case default
       dload_fits = .false.
    end select
  end function dload_fits

  pure function dload_targets(kind) result(s)
    integer, intent(in) :: kind
    character(:), allocatable :: s
    select case (kind)
    case (DLOAD_PX, DLOAD_PY)
       s = 'PX and PY apply to beams B23, B33, B21, B31 and B32'
    case (DLOAD_PZ)
       s = 'PZ applies to 3D beams B33, B31 and B32'
    case (DLOAD_P1)
       s = 'P1 applies to the first edge of plane elements and to 3D beams B33 and B31'
    case (DLOAD_P2)
       s = 'P2 applies to the second edge of plane elements and to beams'
    case (DLOAD_P3)
       s = 'P3 applies to the third edge of plane elements'
    case (DLOAD_P4)
       s = 'P4 applies to the fourth edge of quadrilaterals CPS4, CPS8, CPS8R, CPE4, CPE8 and CPE8R'
    case (DLOAD_CENTRIF)
       s = 'CENTRIF applies to trusses, two-node beams, plane and shell elements'
    case default
       s = 'P applies to shells S3 and S4'
    end select
  end function dload_targets

  ! ================================================================== helpers

  pure function more_text(n, suffix) result(s)
    !! ' (and N more)' text for counts of repeated problems.
    integer, intent(in) :: n
    character(*), intent(in), optional :: suffix
    character(:), allocatable :: s
    if (n <= 0) then
       s = ''
    else
       s = ' (and '//itoa(n)//' more'
       if (present(suffix)) s = s//suffix
       s = s//')'
    end if
  end function more_text


  function where(st, loc) result(s)
    !! "file:line" of a location.
    type(deck_state_t), intent(in) :: st
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: s
    if (loc%file >= 1 .and. loc%file <= st%nfile) then
       s = st%files(loc%file)%s//':'//itoa(loc%line)
    else
       s = '<input>:'//itoa(loc%line)
    end if
  end function where

  subroutine argsort_ids(ids, order)
    !! order = permutation sorting ids ascending (stable merge sort; O(n) when already sorted).
    integer(ip), intent(in) :: ids(:)
    integer(ip), intent(out) :: order(:)
    integer(ip), allocatable :: tmp(:)
    integer(ip) :: n, width, lo, mid, hi, i, j, k
    logical :: sorted
    n = size(ids, kind=ip)
    do i = 1, n
       order(i) = i
    end do
    sorted = .true.
    do i = 2, n
       if (ids(i) < ids(i - 1)) then
          sorted = .false.
          exit
       end if
    end do
    if (sorted) return
    allocate (tmp(n))
    width = 1
    do while (width < n)
       lo = 1
       do while (lo <= n)
          mid = min(lo + width - 1, n)
          hi = min(lo + 2*width - 1, n)
          i = lo
          j = mid + 1
          k = lo
          do while (i <= mid .and. j <= hi)
             if (ids(order(j)) < ids(order(i))) then
                tmp(k) = order(j)
                j = j + 1
             else
                tmp(k) = order(i)
                i = i + 1
             end if
             k = k + 1
          end do
          do while (i <= mid)
             tmp(k) = order(i)
             i = i + 1
             k = k + 1
          end do
          do while (j <= hi)
             tmp(k) = order(j)
             j = j + 1
             k = k + 1
          end do
          lo = hi + 1
       end do
       order = tmp
       if (width > n/2) exit
       width = 2*width
    end do
  end subroutine argsort_ids
  pure subroutine beam_fibres(sb, plane, sec)
    !! The fibre points of a library beam section in the beam's local (y, z):
    !! 3D beams have y along section axis 1 and z along axis 2; a 2D beam (plane)
    !! bends in its plane about axis 1, so its local y is axis 2 (and z = -axis 1,
    !! Abaqus's n1 = -Z of planar beams).
    type(sec_b_t), intent(in) :: sb
    logical, intent(in) :: plane
    type(section_t), intent(inout) :: sec
    real(wp) :: pts(2, MAX_FIBRES)
    if (sb%ndims == 0) return
    call section_fibres(sb%shape, sb%dims(1:sb%ndims), pts, sec%nfibre)
    if (plane) then
       sec%fibre(1, :) = pts(2, :)
       sec%fibre(2, :) = -pts(1, :)
    else
       sec%fibre = pts
    end if
  end subroutine beam_fibres

  ! ------------------------------------------------------------------ growing arrays

#define GROW_NAME grow_cload
#define GROW_TYPE type(cload_t)
#include "grow_template.inc"

#define GROW_NAME grow_dload
#define GROW_TYPE type(dload_t)
#include "grow_template.inc"

end module superjoin_deck_validate
