module superjoin_output_frd
  !! CalculiX's ASCII result file .frd (superjoin -i JOB writes JOB.frd), as
  !! CalculiX GraphiX (cgx) and FreeCAD read it: the nodes (block 2C), the
  !! elements in superjoin's own types (block 3C; frd types 11 beam2, 12
  !! beam3, 7 tria3, 8 tria6, 9 quad4, 10 quad8, 1 hexa8, 4 hexa20, 3 tet4, 6
  !! tet10: frd_type), then per solved step the result blocks that *NODE FILE
  !! and *EL FILE ask for, as ccx writes them:
  !!   U -> DISP (D1..D3), RF -> FORC (F1..F3: reaction plus *CLOAD, as the
  !!   .dat's forces), S -> STRESS (SXX SYY SZZ SXY SYZ SZX), E -> TOSTRAIN;
  !!   S in a model with contact elements also -> FJOINT (F1..F3: link_forces);
  !!   SF -> SECTFORC (beam section forces in the columns of ccx's SECTION FORCES).
  !! Stresses and strains are nodal values averaged over the elements at the
  !! node: plane and shell elements extrapolated from their points (shells:
  !! the mid-surface, the mean of bottom and top for thin shells; output's
  !! nodal_stresses), solids extrapolated from their points, trusses their
  !! one tensor; strains of plane elements and trusses their centroid
  !! tensor, of solids extrapolated from their points; a node without such
  !! an element gets 0 (beams, shell strains). A deck without *NODE FILE or *EL FILE
  !! gets the mesh alone, as with ccx.
  !!
  !! Numbers: a model of one substructure keeps its node and element ids;
  !! with several substructures (whose ids may repeat) the nodes and elements
  !! are numbered on through the substructures in order (fields%vertex_offset,
  !! elem_offset). The file carries no date: the same bytes on every run.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, step_total_time, substructure_t, NDOF_NODE, REQ_NODE_FILE, REQ_EL_FILE, LINK_NONE, &
       DLOAD_CENTRIF, DLOAD_THERMAL, dload_t
  use superjoin_model_results, only: result_fields_t
  use superjoin_elements, only: element_tensor, element_stresses, NTENSOR, beam_middle_section, distributed_load, &
       beam_centrif_halves
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_TRUSS, FAMILY_BEAM, &
       FAMILY_PLANE, FAMILY_SHELL, FAMILY_SOLID
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_requests, only: effective_requests, selected_items
  use superjoin_output_stresses, only: nodal_stresses
  use superjoin_output_ccx_dat, only: c_real, node_forces, open_output
  implicit none (type, external)
  private

  public :: write_frd, frd_type

  integer, parameter :: FRD_LINE2 = 11
    !! frd type of a two-node line element (beam2), which contact elements are written as.
  integer, parameter :: LINK_MATERIAL = 1000
    !! Material number of contact elements: this plus their *CONTACT card's index.
  integer, parameter :: MID = 3
    !! The mid-surface among nodal_stresses' section points.
  integer, parameter :: VOIGT_TO_FRD(NTENSOR) = [1, 2, 3, 4, 6, 5]
    !! frd's order xx, yy, zz, xy, yz, zx from superjoin's xx, yy, zz, xy, xz, yz.

  type :: numbering_t
    !! The numbers the file gives nodes and elements.
     logical :: own_ids = .true.                  !! one substructure: its user ids
     integer(i8), allocatable :: vertex_offset(:), elem_offset(:)
  end type numbering_t

contains

  pure integer function frd_type(t)
    !! The frd element type of an element with traits t (0: none).
    type(element_traits_t), intent(in) :: t
    frd_type = 0
    ! an axisymmetric element: the cell of the plane element with its nodes (cgx draws the section)
    select case (merge(FAMILY_PLANE, t%family, t%axisymmetric))
    case (FAMILY_TRUSS, FAMILY_BEAM)
       frd_type = merge(12, 11, t%nodes == 3)
    case (FAMILY_PLANE, FAMILY_SHELL)
       if (t%corners == 3) frd_type = merge(8, 7, t%nodes == 6)
       if (t%corners == 4) frd_type = merge(10, 9, t%nodes == 8)
    case (FAMILY_SOLID)
       if (t%corners == 8) frd_type = merge(4, 1, t%nodes == 20)
       if (t%corners == 4) frd_type = merge(6, 3, t%nodes == 10)
       if (t%corners == 6) frd_type = merge(5, 2, t%nodes == 15)
    end select
  end function frd_type

  pure function frd_node_order(nodes) result(order)
    !! The element's node positions in frd order: a 20-node brick lists its
    !! mid-side nodes 13..16 (between the faces) after 17..20, as cgx expects;
    !! a 15-node wedge likewise its 13..15 before 10..12 (as ccx 2.20 writes them).
    integer, intent(in) :: nodes
    integer :: order(nodes)
    integer :: k
    order = [(k, k=1, nodes)]
    if (nodes == 20) order = [(k, k=1, 12), (k, k=17, 20), (k, k=13, 16)]
    if (nodes == 15) order = [(k, k=1, 9), (k, k=13, 15), (k, k=10, 12)]
  end function frd_node_order

  subroutine write_frd(path, model, fields, error)
    !! JOB.frd: mesh, then the requested results of every solved step.
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    type(numbering_t) :: num
    integer :: is, nblock
    num%own_ids = size(model%subs) == 1
    num%vertex_offset = fields%vertex_offset
    num%elem_offset = fields%elem_offset
    call open_output(lu, path, error)
    if (allocated(error)) return
    call lu%line('    1C')
    call lu%line(pad('    1UPGM               superjoin'))
    call node_block(lu, model, num)
    call element_block(lu, model, num)
    nblock = 0
    do is = 1, size(model%steps)
       if (allocated(fields%steps(is)%failure)) cycle
       call step_blocks(lu, model, fields, num, is, nblock)
    end do
    call lu%line(' 9999')
    call lu%commit(path//'.tmp', path, '.frd file ', error)
  end subroutine write_frd

  pure function pad(text) result(s)
    !! text padded with blanks to the 72 columns of an frd user record.
    character(*), intent(in) :: text
    character(len=max(72, len(text))) :: s
    s = text
  end function pad

  pure integer(i8) function node_number(model, num, isub, n)
    !! The number of node n of substructure isub in the file.
    type(model_t), intent(in) :: model
    type(numbering_t), intent(in) :: num
    integer, intent(in) :: isub
    integer(ip), intent(in) :: n
    if (num%own_ids) then
       node_number = model%subs(isub)%node_id(n)
    else
       node_number = num%vertex_offset(isub) + n
    end if
  end function node_number

  subroutine node_block(lu, model, num)
    !! Block 2C: every node and its coordinates.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(numbering_t), intent(in) :: num
    character(len=80) :: row
    integer :: isub
    integer(ip) :: n
    write (row, '(a6,18x,i12,37x,i1)') '    2C', sum(int(model%subs(:)%nnode, i8)), 1
    call lu%line(row(1:74))
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          write (row, '(a3,i10,3a12)') ' -1', node_number(model, num, isub, n), &
               c_real(model%subs(isub)%x(1, n), 12, 5), c_real(model%subs(isub)%x(2, n), 12, 5), &
               c_real(model%subs(isub)%x(3, n), 12, 5)
          call lu%line(trim(row))
       end do
    end do
    call lu%line(' -3')
  end subroutine node_block

  subroutine element_block(lu, model, num)
    !! Block 3C: every element with an frd type, its nodes ten to a line.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(numbering_t), intent(in) :: num
    type(element_traits_t) :: t
    character(len=120) :: row
    integer(i8) :: id, count
    integer(i8), allocatable :: ids(:)
    integer, allocatable :: order(:)
    integer :: isub, k, first
    integer(ip) :: e
    count = 0
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          if (frd_type(element_traits(model%subs(isub)%elem_type(e))) > 0) count = count + 1
       end do
    end do
    write (row, '(a6,18x,i12,37x,i1)') '    3C', count + count_links(model), 1
    call lu%line(row(1:74))
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         do e = 1, sub%nelem
            t = element_traits(sub%elem_type(e))
            if (frd_type(t) == 0) cycle
            id = num%elem_offset(isub) + e
            if (num%own_ids) id = sub%elem_id(e)
            write (row, '(a3,i10,3i5)') ' -1', id, frd_type(t), 0, max(1, sub%elem_section(e))
            call lu%line(trim(row))
            order = frd_node_order(t%nodes)
            ids = [(node_number(model, num, isub, sub%elem_nodes(order(k), e)), k=1, t%nodes)]
            do first = 1, t%nodes, 10
               write (row, '(a3,10i10)') ' -2', ids(first:min(first + 9, t%nodes))
               call lu%line(trim(row))
            end do
         end do
       end associate
    end do
    call link_elements(lu, model, num)
    call lu%line(' -3')
  end subroutine element_block

  pure integer(i8) function count_links(model)
    !! Contact elements with at least one linked DOF (written as two-node elements).
    type(model_t), intent(in) :: model
    integer :: k
    count_links = 0
    if (.not. allocated(model%links)) return
    do k = 1, size(model%links)
       if (any(model%links(k)%state /= LINK_NONE)) count_links = count_links + 1
    end do
  end function count_links

  subroutine link_elements(lu, model, num)
    !! The contact elements (and springs) with a linked DOF, as two-node
    !! elements of frd type 11 (cgx and FreeCAD draw them as lines), numbered
    !! on after the largest element number, material 1000 + the *CONTACT card's
    !! index, so a viewer can show the joints apart from the parts.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(numbering_t), intent(in) :: num
    character(len=120) :: row
    integer(i8) :: id
    integer :: k, isub
    if (count_links(model) == 0) return
    id = 0
    do isub = 1, size(model%subs)
       if (model%subs(isub)%nelem == 0) cycle
       if (num%own_ids) then
          id = max(id, int(maxval(model%subs(isub)%elem_id(1:model%subs(isub)%nelem)), i8))
       else
          id = max(id, num%elem_offset(isub) + model%subs(isub)%nelem)
       end if
    end do
    do k = 1, size(model%links)
       associate (ln => model%links(k), c => model%contacts(model%links(k)%contact))
         if (all(ln%state == LINK_NONE)) cycle
         id = id + 1
         write (row, '(a3,i10,3i5)') ' -1', id, FRD_LINE2, 0, LINK_MATERIAL + ln%contact
         call lu%line(trim(row))
         write (row, '(a3,2i10)') ' -2', node_number(model, num, c%master_sub, ln%master_node), &
              node_number(model, num, c%slave_sub, ln%slave_node)
         call lu%line(trim(row))
       end associate
    end do
  end subroutine link_elements

  subroutine step_blocks(lu, model, fields, num, is, nblock)
    !! The result blocks of step is that its *NODE FILE and *EL FILE ask for.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(numbering_t), intent(in) :: num
    integer, intent(in) :: is
    integer, intent(inout) :: nblock
    logical, allocatable :: mask(:)
    real(wp), allocatable :: vals(:, :)
    call requested_nodes(model, is, REQ_NODE_FILE, 'U', mask)
    if (any(mask)) then
       call displacements(fields, is, vals)
       call result_block(lu, model, num, is, nblock, 'DISP', vals(1:3, :), mask)
    end if
    call requested_nodes(model, is, REQ_EL_FILE, 'S', mask)
    if (any(mask)) then
       call nodal_tensors(model, fields, is, .false., vals)
       call result_block(lu, model, num, is, nblock, 'STRESS', vals(VOIGT_TO_FRD, :), mask)
    end if
    call requested_nodes(model, is, REQ_EL_FILE, 'E', mask)
    if (any(mask)) then
       call nodal_tensors(model, fields, is, .true., vals)
       call result_block(lu, model, num, is, nblock, 'TOSTRAIN', vals(VOIGT_TO_FRD, :), mask)
    end if
    call requested_nodes(model, is, REQ_NODE_FILE, 'RF', mask)
    if (any(mask)) then
       call forces(model, fields, is, vals)
       call result_block(lu, model, num, is, nblock, 'FORC', vals(1:3, :), mask)
    end if
    call requested_nodes(model, is, REQ_EL_FILE, 'SF', mask)
    if (any(mask)) then
       call beam_section_forces(model, fields, is, vals)
       call result_block(lu, model, num, is, nblock, 'SECTFORC', vals, mask)
    end if
    call requested_nodes(model, is, REQ_EL_FILE, 'S', mask)
    if (any(mask) .and. count_links(model) > 0) then
       call link_forces(model, fields, is, vals, mask)
       call result_block(lu, model, num, is, nblock, 'FJOINT', vals, mask)
    end if
  end subroutine step_blocks

  subroutine beam_section_forces(model, fields, is, vals)
    !! vals(6, vertex): the section forces of the beams at their nodes in the
    !! columns of CalculiX's *EL FILE, SECTION FORCES (its STRESS block,
    !! measured with ccx 2.20): SXX, SYY shear forces along the section's 1-
    !! and 2-directions (superjoin's local y, z), SZZ normal force, SXY torque,
    !! SYZ, SZX moments about the 1- and 2-directions; the resultant of the
    !! stresses on the face whose normal is the beam's axis (the end forces of
    !! the last node, of node 1 negated); a three-node beam's middle node: from
    !! the equilibrium of its halves under its load per unit length
    !! (beam_middle_section; the mean of the ends missed q L²/8 under a uniform
    !! q); the mean where beams meet, 0 at other nodes.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    real(wp), allocatable, intent(out) :: vals(:, :)
    integer, parameter :: TO_CCX(6) = [2, 3, 1, 4, 5, 6]   ! from superjoin's N, Vy, Vz, T, My, Mz
    integer, allocatable :: cnt(:)
    type(element_traits_t) :: t
    real(wp) :: cut(NTENSOR, 3)
    real(wp), allocatable :: ql(:, :), halves(:, :, :)
    integer(i8) :: v
    integer :: isub, k
    integer(ip) :: e
    allocate (vals(NTENSOR, fields%vertex_offset(size(model%subs) + 1)), source=0.0_wp)
    allocate (cnt(size(vals, 2)), source=0)
    call line_loads(model, fields%elem_offset, is, ql, halves)
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         do e = 1, sub%nelem
            t = element_traits(sub%elem_type(e))
            if (t%family /= FAMILY_BEAM .or. sub%elem_section(e) <= 0) cycle
            cut(:, 1) = -fields%elem_force(TO_CCX, 1, fields%elem_offset(isub) + e, is)
            cut(:, 3) = fields%elem_force(TO_CCX, 2, fields%elem_offset(isub) + e, is)
            if (t%nodes == 3) call middle_cut(sub, e, fields%elem_force(:, :, fields%elem_offset(isub) + e, is), &
                 ql(:, fields%elem_offset(isub) + e), halves(:, :, fields%elem_offset(isub) + e), cut(:, 2))
            do k = 1, t%nodes   ! the ends are nodes 1 and t%nodes
               v = fields%vertex_offset(isub) + sub%elem_nodes(k, e)
               vals(:, v) = vals(:, v) + cut(:, merge(3, k, k == t%nodes))
               cnt(v) = cnt(v) + 1
            end do
         end do
       end associate
    end do
    do k = 1, NTENSOR
       vals(k, :) = vals(k, :)/real(max(cnt, 1), wp)
    end do
  contains
    subroutine middle_cut(sub, e, f, q, h, c)
      !! c: the section forces of three-node beam e at its middle node, in ccx's columns.
      type(substructure_t), intent(in) :: sub
      integer(ip), intent(in) :: e
      real(wp), intent(in) :: f(6, 2), q(3), h(6, 2)
      real(wp), intent(out) :: c(NTENSOR)
      real(wp) :: sm(6)
      type(error_t), allocatable :: inner
      call beam_middle_section(sub%elem_type(e), sub%x(:, sub%elem_nodes(1:3, e)), &
           sub%sections(sub%elem_section(e)), f, q, sm, inner, h)
      c = sm(TO_CCX)   ! an error (a degenerate element) was reported by the recovery
    end subroutine middle_cut
  end subroutine beam_section_forces

  subroutine line_loads(model, elem_offset, is, ql, halves)
    !! ql(3, element): the load per unit length of each line element in step
    !! is, as the recovery takes it (distributed_load: PX, PY, PZ, GRAV; a
    !! load combination superposes those of its steps); halves(6, 2, element):
    !! the CENTRIF loads on the halves of the three-node beams, which vary along
    !! them (beam_centrif_halves). TEMP is no load on a half: the end forces
    !! carry its effect.
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: is
    real(wp), allocatable, intent(out) :: ql(:, :), halves(:, :, :)
    integer :: c, k
    allocate (ql(3, elem_offset(size(elem_offset))), source=0.0_wp)
    allocate (halves(6, 2, elem_offset(size(elem_offset))), source=0.0_wp)
    c = model%steps(is)%combination
    if (c == 0) then
       call add_line_loads(model, elem_offset, is, 1.0_wp, ql, halves)
       return
    end if
    do k = 1, size(model%combinations(c)%steps)
       call add_line_loads(model, elem_offset, model%combinations(c)%steps(k), model%combinations(c)%factors(k), &
            ql, halves)
    end do
  end subroutine line_loads

  subroutine add_line_loads(model, elem_offset, is, factor, ql, halves)
    !! ql, halves += factor × the loads of the three-node beams in solved step is (line_loads).
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: elem_offset(:)
    integer, intent(in) :: is
    real(wp), intent(in) :: factor
    real(wp), intent(inout) :: ql(:, :), halves(:, :, :)
    real(wp), allocatable :: fe(:)
    real(wp) :: q(3)
    type(element_traits_t) :: t
    type(error_t), allocatable :: inner
    integer :: i
    if (.not. allocated(model%steps(is)%dloads)) return
    do i = 1, size(model%steps(is)%dloads)
       associate (dl => model%steps(is)%dloads(i))
         if (dl%kind == DLOAD_THERMAL) cycle
         t = element_traits(model%subs(dl%sub)%elem_type(dl%elem))
         if (t%family /= FAMILY_BEAM .or. t%nodes /= 3) cycle
         if (dl%kind == DLOAD_CENTRIF) then
            call add_centrif_halves(model, dl, factor, halves(:, :, elem_offset(dl%sub) + dl%elem))
            cycle
         end if
         call distributed_load(model, dl, fe, q, inner)
         if (allocated(inner)) cycle   ! reported when the loads were assembled
         ql(:, elem_offset(dl%sub) + dl%elem) = ql(:, elem_offset(dl%sub) + dl%elem) + factor*q
       end associate
    end do
  end subroutine add_line_loads

  subroutine add_centrif_halves(model, dl, factor, h)
    !! h += factor × the CENTRIF load dl on the halves of its three-node beam (beam_centrif_halves).
    type(model_t), intent(in) :: model
    type(dload_t), intent(in) :: dl
    real(wp), intent(in) :: factor
    real(wp), intent(inout) :: h(6, 2)
    associate (s => model%subs(dl%sub))
      associate (sec => s%sections(s%elem_section(dl%elem)))
        h = h + factor*beam_centrif_halves(s%elem_type(dl%elem), s%x(:, s%elem_nodes(1:3, dl%elem)), sec, &
             model%materials(sec%material), dl)
      end associate
    end associate
  end subroutine add_centrif_halves

  subroutine link_forces(model, fields, is, vals, mask)
    !! vals(3, vertex): the force of the contact elements (frd type 11,
    !! material 1000 + card) at both of their nodes, in the contact's axes,
    !! on the master (the listing's CONTACT FORCES F1..F3); the mean where a
    !! node has several, 0 at the other nodes; mask (the nodes of the *EL FILE
    !! elements) gains the nodes of contact elements with a linked DOF.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    real(wp), allocatable, intent(out) :: vals(:, :)
    logical, intent(inout) :: mask(:)
    integer, allocatable :: cnt(:)
    integer(i8) :: v(2)
    integer :: k
    allocate (vals(3, fields%vertex_offset(size(model%subs) + 1)), source=0.0_wp)
    allocate (cnt(size(vals, 2)), source=0)
    do k = 1, size(model%links)
       associate (ln => model%links(k), c => model%contacts(model%links(k)%contact))
         if (all(ln%state == LINK_NONE)) cycle
         v = [fields%vertex_offset(c%master_sub) + ln%master_node, fields%vertex_offset(c%slave_sub) + ln%slave_node]
         vals(:, v(1)) = vals(:, v(1)) + fields%steps(is)%link_force(1:3, k)
         vals(:, v(2)) = vals(:, v(2)) + fields%steps(is)%link_force(1:3, k)
         cnt(v) = cnt(v) + 1
       end associate
    end do
    mask = mask .or. cnt > 0
    do k = 1, 3
       vals(k, :) = vals(k, :)/real(max(cnt, 1), wp)
    end do
  end subroutine link_forces

  subroutine requested_nodes(model, is, kind, var, mask)
    !! mask(vertex): the nodes whose `var` the requests of `kind` in step is
    !! ask for (element requests: the nodes of their elements).
    type(model_t), intent(in) :: model
    integer, intent(in) :: is, kind
    character(*), intent(in) :: var
    logical, allocatable, intent(out) :: mask(:)
    integer(i8), allocatable :: offset(:)
    integer, allocatable :: idx(:), subs(:)
    integer(ip), allocatable :: items(:)
    integer :: k, i, isub
    allocate (offset(size(model%subs) + 1))
    offset(1) = 0
    do isub = 1, size(model%subs)
       offset(isub + 1) = offset(isub) + model%subs(isub)%nnode
    end do
    allocate (mask(offset(size(offset))), source=.false.)
    call effective_requests(model, is, kind, idx)
    do k = 1, size(idx)
       associate (r => model%requests(idx(k)))
         if (.not. any([(r%vars(i)%s == var, i=1, size(r%vars))])) cycle
         if (kind == REQ_NODE_FILE) then
            call selected_items(r, model%subs(:)%nnode, subs, items)
            mask(offset(subs) + items) = .true.
         else
            call selected_items(r, model%subs(:)%nelem, subs, items)
            do i = 1, size(items)
               associate (sub => model%subs(subs(i)))
                 mask(offset(subs(i)) + pack(sub%elem_nodes(:, items(i)), sub%elem_nodes(:, items(i)) > 0)) = .true.
               end associate
            end do
         end if
       end associate
    end do
  end subroutine requested_nodes

  subroutine result_block(lu, model, num, is, nblock, name, vals, mask)
    !! One result block: its headers and a row per node of mask.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(numbering_t), intent(in) :: num
    integer, intent(in) :: is
    integer, intent(inout) :: nblock
    character(*), intent(in) :: name
    real(wp), intent(in) :: vals(:, :)
    logical, intent(in) :: mask(:)
    character(len=4), parameter :: COMPS(6) = ['XX', 'YY', 'ZZ', 'XY', 'YZ', 'ZX']
    integer, parameter :: II(6) = [1, 2, 3, 1, 2, 3], JJ(6) = [1, 2, 3, 2, 3, 1]
    character(len=120) :: row
    character(len=2) :: letter
    character(len=8) :: label
    integer :: isub, d, nv
    integer(ip) :: n
    nblock = nblock + 1
    nv = size(vals, 1)
    write (row, '(a10,i26,2i12,10x)') '    1PSTEP', nblock, 1, is
    call lu%line(row(1:70))
    write (row, '(a7,i5,f12.9,i12,a20,i2,i5,10x,i2)') '  100CL', 100 + is, step_total_time(model, is), count(mask), '', 0, is, 1
    call lu%line(trim(row))
    label = name    ! left-justified in its 8 columns (an A8 edit right-justifies a shorter string)
    write (row, '(a3,2x,a8,2i5)') ' -4', label, nv + merge(1, 0, nv == 3), 1
    call lu%line(trim(row))
    letter = name(1:1)
    if (name == 'TOSTRAIN') letter = 'E'
    do d = 1, nv
       if (nv == 3) then
          label = trim(letter)//achar(iachar('0') + d)
          write (row, '(a3,2x,a8,4i5)') ' -5', label, 1, 2, d, 0
       else
          label = trim(letter)//COMPS(d)
          write (row, '(a3,2x,a8,4i5)') ' -5', label, 1, 4, II(d), JJ(d)
       end if
       call lu%line(trim(row))
    end do
    if (nv == 3) call lu%line(' -5  ALL         1    2    0    0    1ALL')
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          if (.not. mask(num%vertex_offset(isub) + n)) cycle
          write (row, '(a3,i10,6a12)') ' -1', node_number(model, num, isub, n), &
               (c_real(vals(d, num%vertex_offset(isub) + n), 12, 5), d=1, nv)
          call lu%line(trim(row))
       end do
    end do
    call lu%line(' -3')
  end subroutine result_block

  subroutine displacements(fields, is, vals)
    !! vals(6, vertex): the displacements of step is.
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    real(wp), allocatable, intent(out) :: vals(:, :)
    vals = reshape(fields%u(:, is), [NDOF_NODE, size(fields%u, 1)/NDOF_NODE])
  end subroutine displacements

  subroutine forces(model, fields, is, vals)
    !! vals(6, vertex): reaction plus concentrated load of every node in step is.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    real(wp), allocatable, intent(out) :: vals(:, :)
    real(wp), allocatable :: v(:, :)
    integer, allocatable :: subs(:)
    integer(ip), allocatable :: nodes(:)
    integer :: isub
    integer(ip) :: n
    allocate (vals(NDOF_NODE, fields%vertex_offset(size(model%subs) + 1)), source=0.0_wp)
    do isub = 1, size(model%subs)
       nodes = [(n, n=1, model%subs(isub)%nnode)]
       allocate (subs(size(nodes)), source=isub)
       call node_forces(model, fields, is, subs, nodes, v)
       vals(:, fields%vertex_offset(isub) + 1:fields%vertex_offset(isub + 1)) = v
       deallocate (subs)
    end do
  end subroutine forces

  subroutine nodal_tensors(model, fields, is, strain, vals)
    !! vals(6, vertex): the averaged nodal stress (or strain) of step is.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    logical, intent(in) :: strain
    real(wp), allocatable, intent(out) :: vals(:, :)
    real(wp), allocatable :: avg(:, :, :), sums(:, :), points(:, :, :), nodes(:, :, :)
    integer, allocatable :: nel(:), npoint(:), cnt(:)
    type(element_traits_t) :: t
    real(wp) :: one(NTENSOR)
    integer(i8) :: base
    integer(ip) :: e, n
    integer :: isub
    logical :: ok
    allocate (vals(NTENSOR, fields%vertex_offset(size(model%subs) + 1)), source=0.0_wp)
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         base = fields%vertex_offset(isub)
         allocate (sums(NTENSOR, sub%nnode), source=0.0_wp)
         allocate (cnt(sub%nnode), source=0)
         if (.not. strain) then
            call nodal_stresses(model, fields, is, isub, avg, nel, npoint)
            sums = avg(:, :, MID)*spread(real(nel, wp), 1, NTENSOR)
            cnt = nel
         end if
         do e = 1, sub%nelem
            t = element_traits(sub%elem_type(e))
            if (strain .and. t%family == FAMILY_SOLID) then
               ! a solid's strains extrapolated to its nodes (its stresses come with nodal_stresses)
               call element_stresses(model, fields, is, isub, e, points, nodes, ok, strain)
               if (ok) call add_to_nodes(sub%elem_nodes(1:t%nodes, e), nodes(:, :, 1), sums, cnt)
               cycle
            end if
            if (t%family /= FAMILY_TRUSS .and. .not. (strain .and. t%family == FAMILY_PLANE)) cycle
            call element_tensor(model, fields, is, isub, e, strain, one, ok)
            if (ok) call add_to_nodes(sub%elem_nodes(1:t%nodes, e), spread(one, 2, t%nodes), sums, cnt)
         end do
         do n = 1, sub%nnode
            if (cnt(n) > 0) vals(:, base + n) = sums(:, n)/real(cnt(n), wp)
         end do
         deallocate (sums, cnt)
       end associate
    end do
  end subroutine nodal_tensors

  pure subroutine add_to_nodes(enodes, v, sums, cnt)
    !! Adds v(6, a) to the sum of node enodes(a) and counts it.
    integer(ip), intent(in) :: enodes(:)
    real(wp), intent(in) :: v(:, :)
    real(wp), intent(inout) :: sums(:, :)
    integer, intent(inout) :: cnt(:)
    integer :: a
    do a = 1, size(enodes)
       sums(:, enodes(a)) = sums(:, enodes(a)) + v(:, a)
       cnt(enodes(a)) = cnt(enodes(a)) + 1
    end do
  end subroutine add_to_nodes
end module superjoin_output_frd
