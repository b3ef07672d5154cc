module superjoin_output_requests
  !! The listing section of the print requests (*NODE PRINT, *EL PRINT): per
  !! step, after the standard tables, the requested variables for the
  !! requested sets, as CalculiX writes them to its .dat file. A deck without
  !! print requests gets no such section (its listing is unchanged).
  !!
  !! CalculiX scoping: the requests of one kind written in a step replace those
  !! of earlier steps; a step without one keeps the previous step's; requests
  !! written outside *STEP (superjoin) are the default of every step.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t, output_request_t, NDOF_NODE, REQ_NODE_PRINT, REQ_EL_PRINT, &
       REQ_KIND_NAMES, TOTALS_YES, TOTALS_ONLY
  use superjoin_elements, only: is_plate_type, element_tensor, NTENSOR, is_solid_type
  use superjoin_model_results, only: result_fields_t, reaction_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_sorting, only: sort_index
  use superjoin_output_energy, only: write_energy_request
  use superjoin_output_stresses, only: write_point_stress_table, write_nodal_stress_table, &
       write_fibre_stress_table
  use superjoin_output_solid_stresses, only: write_solid_point_table, solid_elements
  implicit none (type, external)
  private

  public :: write_print_requests, effective_requests, selected_items, node_frames, rotate_rows
  public :: node_values, add_reactions, add_cloads, add_node_forces

  character(len=15), parameter :: TENSOR_HEAD(NTENSOR) = ['             xx', '             yy', &
       '             zz', '             xy', '             xz', '             yz']
  character(len=15), parameter :: NODE_HEAD(NDOF_NODE) = ['              1', '              2', &
       '              3', '              4', '              5', '              6']

contains

  subroutine effective_requests(model, is, kind, idx)
    !! Indices into model%requests of the requests of `kind` that apply to step `is`.
    type(model_t), intent(in) :: model
    integer, intent(in) :: is, kind
    integer, allocatable, intent(out) :: idx(:)
    integer :: s, k
    allocate (idx(0))
    if (.not. allocated(model%requests)) return
    do s = is, 0, -1
       do k = 1, size(model%requests)
          if (model%requests(k)%kind == kind .and. model%requests(k)%step == s) idx = [idx, k]
       end do
       if (size(idx) > 0) return
    end do
  end subroutine effective_requests

  subroutine write_print_requests(lu, model, fields, is)
    !! The REQUESTED OUTPUT section of step `is` (nothing without print requests).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, allocatable :: nodes(:), elems(:)
    integer :: k
    call effective_requests(model, is, REQ_NODE_PRINT, nodes)
    call effective_requests(model, is, REQ_EL_PRINT, elems)
    if (size(nodes) + size(elems) == 0) return
    call lu%line('REQUESTED OUTPUT (*NODE PRINT, *EL PRINT) of step '//itoa(is))
    do k = 1, size(nodes)
       call node_request(lu, model, fields, is, model%requests(nodes(k)))
    end do
    do k = 1, size(elems)
       call element_request(lu, model, fields, is, model%requests(elems(k)))
    end do
  end subroutine write_print_requests

  subroutine request_title(lu, model, r)
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(output_request_t), intent(in) :: r
    character(:), allocatable :: t
    integer :: k
    t = '  '//trim(REQ_KIND_NAMES(r%kind))
    if (allocated(r%set_name)) then
       if (r%kind == REQ_NODE_PRINT) then
          t = t//', NSET='//r%set_name
       else
          t = t//', ELSET='//r%set_name
       end if
    end if
    if (r%totals == TOTALS_YES) t = t//', TOTALS=YES'
    if (r%totals == TOTALS_ONLY) t = t//', TOTALS=ONLY'
    call lu%line(t//'   ('//card_place(model, r)//')')
    do k = 1, size(r%ignored)
       call lu%line('    '//r%ignored(k)%s//': not produced by superjoin (linear statics)')
    end do
  end subroutine request_title

  function card_place(model, r) result(s)
    type(model_t), intent(in) :: model
    type(output_request_t), intent(in) :: r
    character(:), allocatable :: s
    s = 'line '//itoa(r%loc%line)
    if (r%loc%file >= 1 .and. r%loc%file <= size(model%files)) s = model%files(r%loc%file)%s//':'//itoa(r%loc%line)
  end function card_place

  ! ------------------------------------------------------------------ nodes

  subroutine node_request(lu, model, fields, is, r)
    !! One *NODE PRINT card. As CalculiX's .dat file: a node with a nodal system
    !! (*TRANSFORM) prints U, RF and CF in that system, its row marked L, unless
    !! the card says GLOBAL=YES; totals are sums of the global components.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(output_request_t), intent(in) :: r
    integer :: iv
    integer(ip) :: nsel
    integer, allocatable :: subs(:), frame(:)
    integer(ip), allocatable :: nodes(:)
    real(wp), allocatable :: vals(:, :), gvals(:, :)
    logical :: local
    character(:), allocatable :: axes
    integer(ip), allocatable :: counts(:)
    allocate (counts(size(model%subs)))   ! a copy: the component section would go through a temporary
    counts(:) = model%subs(:)%nnode
    call request_title(lu, model, r)
    call selected_items(r, counts, subs, nodes)
    nsel = size(nodes, kind=ip)
    allocate (vals(NDOF_NODE, nsel))
    call node_frames(model, subs, nodes, frame)
    local = .not. r%global .and. any(frame > 0)
    axes = 'global axes'
    if (local) axes = 'global axes; rows marked L: the node''s *TRANSFORM system'
    do iv = 1, size(r%vars)
       select case (r%vars(iv)%s)
       case ('U')
          call lu%line('    U   displacements ('//axes//'; 4-6: rotations)')
          call fill_u(vals)
       case ('RF')
          call lu%line('    RF  reaction forces (sum of the support reactions on the node, '//axes//')')
          call fill_rf(vals)
          ! the reactions of a node with a nodal system are along its axes
          call rotate_rows(model, frame, .true., vals)
       case ('CF')
          call lu%line('    CF  concentrated loads (*CLOAD, '//axes//')')
          call fill_cf(vals)
       case ('S')
          call write_nodal_stress_table(lu, model, fields, is, subs, nodes)
          cycle
       case ('NT')
          call temperature_table(lu, model, r, is, subs, nodes)
          cycle
       case default
          cycle
       end select
       gvals = vals
       if (local) call rotate_rows(model, frame, .false., vals)
       call node_table(lu, model, r, subs, nodes, vals, gvals, local .and. frame > 0)
    end do
    call lu%line('')
  contains
    subroutine fill_u(v)
      real(wp), intent(out) :: v(:, :)
      v = node_values(fields%u(:, is), fields%vertex_offset, subs, nodes)
    end subroutine fill_u
    subroutine fill_rf(v)
      real(wp), intent(out) :: v(:, :)
      call add_reactions(fields, is, subs, nodes, v)
    end subroutine fill_rf
    subroutine fill_cf(v)
      real(wp), intent(out) :: v(:, :)
      call add_cloads(model, is, subs, nodes, v)
    end subroutine fill_cf
  end subroutine node_request

  pure function node_values(u, vertex_offset, subs, nodes) result(v)
    !! The six DOF values in u (6 per vertex, global axes) of the listed nodes.
    real(wp), intent(in) :: u(:)
    integer(i8), intent(in) :: vertex_offset(:)
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp) :: v(NDOF_NODE, size(nodes))
    integer(i8) :: vx
    integer :: i
    do i = 1, size(nodes)
       vx = vertex_offset(subs(i)) + nodes(i)
       v(:, i) = u(NDOF_NODE*(vx - 1) + 1:NDOF_NODE*vx)
    end do
  end function node_values

  subroutine add_reactions(fields, is, subs, nodes, v)
    !! v(dof, node): the sum of the support reactions of step is on each listed
    !! node (a node with a nodal system: along its axes), zero elsewhere.
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(out) :: v(:, :)
    call add_node_forces(fields%steps(is)%reactions, subs, nodes, v)
  end subroutine add_reactions

  subroutine add_node_forces(list, subs, nodes, v)
    !! v(dof, node): the sum of the forces of list on each listed node, zero elsewhere
    !! (the listed nodes sorted once, each force found by bisection: the lists of
    !! *EQUATION or *TIE forces may be as long as the model).
    type(reaction_t), intent(in) :: list(:)
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(out) :: v(:, :)
    integer(i8), allocatable :: keys(:)
    integer, allocatable :: order(:)
    integer(i8) :: key
    integer :: i, k, lo, hi, mid, n
    v = 0.0_wp
    n = size(nodes)
    if (size(list) == 0 .or. n == 0) return
    keys = [(node_key(subs(i), int(nodes(i), i8)), i=1, n)]
    order = [(i, i=1, n)]
    call sort_index(keys, order)
    do k = 1, size(list)
       associate (rc => list(k))
         key = node_key(rc%sub, int(rc%node, i8))
         lo = 1
         hi = n + 1
         do while (lo < hi)        ! the first of the sorted nodes with keys >= key
            mid = (lo + hi)/2
            if (keys(order(mid)) < key) then
               lo = mid + 1
            else
               hi = mid
            end if
         end do
         do i = lo, n              ! every listing of the node (a print set may name it twice)
            if (keys(order(i)) /= key) exit
            v(rc%dof, order(i)) = v(rc%dof, order(i)) + rc%force
         end do
       end associate
    end do
  end subroutine add_node_forces

  pure integer(i8) function node_key(sub, node)
    !! One sortable key of (substructure, node).
    integer, intent(in) :: sub
    integer(i8), intent(in) :: node
    integer(i8), parameter :: NODE_SPAN = 2_i8**32
    node_key = int(sub, i8)*NODE_SPAN + node
  end function node_key

  subroutine add_cloads(model, is, subs, nodes, v)
    !! v(dof, node): the concentrated loads (*CLOAD) of step is on each listed
    !! node, global axes, zero elsewhere.
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(out) :: v(:, :)
    integer :: i, k
    v = 0.0_wp
    do k = 1, size(model%steps(is)%cloads)
       associate (cl => model%steps(is)%cloads(k))
         do i = 1, size(nodes)
            if (subs(i) == cl%sub .and. nodes(i) == cl%node) v(cl%dof, i) = v(cl%dof, i) + cl%value
         end do
       end associate
    end do
  end subroutine add_cloads

  subroutine temperature_table(lu, model, r, is, subs, nodes)
    !! *NODE PRINT NT: the nodal temperatures of step `is` (as CalculiX's
    !! "temperatures" block: the *TEMPERATURE of the step, else the initial
    !! ones, 0 where none is given); a load combination has none.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(output_request_t), intent(in) :: r
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    character(len=200) :: hline
    real(wp) :: t
    integer :: i
    if (model%steps(is)%combination > 0) then
       call lu%line('    NT  temperatures: none for a load combination')
       return
    end if
    call lu%line('    NT  temperatures (*TEMPERATURE of the step, else *INITIAL CONDITIONS; 0 where none)')
    write (hline, '(4x,a20,a10,a15)') 'substructure        ', '      node', '              T'
    call lu%line(trim(hline))
    if (r%totals == TOTALS_ONLY) return
    do i = 1, size(nodes)
       t = 0.0_wp
       if (allocated(model%steps(is)%temperature)) t = model%steps(is)%temperature(subs(i))%v(nodes(i))
       call lu%put('    ')
       call lu%put_field(model%subs(subs(i))%name, 20)
       call lu%put_int(int(model%subs(subs(i))%node_id(nodes(i)), i8), 10)
       call lu%put_es(t)
       call lu%newline()
    end do
  end subroutine temperature_table

  subroutine node_frames(model, subs, nodes, frame)
    !! Index into model%frames of the nodal system of each node (0: none).
    type(model_t), intent(in) :: model
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    integer, allocatable, intent(out) :: frame(:)
    integer :: k
    allocate (frame(size(nodes)))
    frame = 0
    if (.not. allocated(model%frames)) return
    do k = size(model%frames), 1, -1
       associate (f => model%frames(k))
         where (subs == f%sub .and. nodes == f%node) frame = k
       end associate
    end do
  end subroutine node_frames

  subroutine rotate_rows(model, frame, to_global, vals)
    !! Turn the translations and rotations of every node with a nodal system
    !! from global axes into it (q v), or back (q^T v) when `to_global`.
    type(model_t), intent(in) :: model
    integer, intent(in) :: frame(:)
    logical, intent(in) :: to_global
    real(wp), intent(inout) :: vals(:, :)
    integer :: i, b
    do i = 1, size(frame)
       if (frame(i) == 0) cycle
       associate (q => model%frames(frame(i))%q)
         do b = 0, NDOF_NODE - 3, 3
            if (to_global) then
               vals(b + 1:b + 3, i) = matmul(transpose(q), vals(b + 1:b + 3, i))
            else
               vals(b + 1:b + 3, i) = matmul(q, vals(b + 1:b + 3, i))
            end if
         end do
       end associate
    end do
  end subroutine rotate_rows

  subroutine selected_items(r, counts, subs, items)
    !! The nodes or elements a request names: its set, or every one of the
    !! model (counts: nodes or elements per substructure).
    type(output_request_t), intent(in) :: r
    integer(ip), intent(in) :: counts(:)
    integer, allocatable, intent(out) :: subs(:)
    integer(ip), allocatable, intent(out) :: items(:)
    integer :: isub
    integer(ip) :: n, k
    if (r%sub > 0 .and. allocated(r%items)) then
       items = r%items
       allocate (subs(size(items)))
       subs = r%sub
       return
    end if
    allocate (subs(sum(counts)), items(sum(counts)))
    k = 0
    do isub = 1, size(counts)
       do n = 1, counts(isub)
          k = k + 1
          subs(k) = isub
          items(k) = n
       end do
    end do
  end subroutine selected_items

  subroutine node_table(lu, model, r, subs, nodes, vals, gvals, marked)
    !! Rows of vals (rows `marked` L: in the node's nodal system); totals: sums of gvals (global axes).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(output_request_t), intent(in) :: r
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(in) :: vals(:, :), gvals(:, :)
    logical, intent(in) :: marked(:)
    character(len=200) :: hline
    real(wp) :: scale
    integer :: i, d
    write (hline, '(4x,a20,a10,6a15)') 'substructure        ', '      node', NODE_HEAD
    call lu%line(trim(hline))
    scale = 0.0_wp
    if (size(vals) > 0) scale = max(maxval(abs(vals)), maxval(abs(gvals)))
    if (r%totals /= TOTALS_ONLY) then
       do i = 1, size(nodes)
          call lu%put('    ')
          call lu%put_field(model%subs(subs(i))%name, 20)
          call lu%put_int(int(model%subs(subs(i))%node_id(nodes(i)), i8), 10)
          do d = 1, NDOF_NODE
             call lu%put_es(chop(vals(d, i), scale))
          end do
          if (marked(i)) call lu%put('  L')
          call lu%newline()
       end do
    end if
    if (r%totals /= TOTALS_YES .and. r%totals /= TOTALS_ONLY) return
    call lu%put('    ')
    call lu%put_field('total', 30)
    do d = 1, NDOF_NODE
       call lu%put_es(chop(sum(gvals(d, :)), scale))
    end do
    call lu%newline()
  end subroutine node_table

  ! ------------------------------------------------------------------ elements

  subroutine element_request(lu, model, fields, is, r)
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(output_request_t), intent(in) :: r
    integer :: iv
    integer, allocatable :: subs(:)
    integer(ip), allocatable :: elems(:), counts(:)
    allocate (counts(size(model%subs)))   ! a copy: the component section would go through a temporary
    counts(:) = model%subs(:)%nelem
    call request_title(lu, model, r)
    call selected_items(r, counts, subs, elems)
    do iv = 1, size(r%vars)
       select case (r%vars(iv)%s)
       case ('S')
          call lu%line('    S   stresses (global axes; trusses: uniaxial N/A; CPS3/CPS4: at the centroid)')
          call tensor_table(lu, model, fields, is, subs, elems, .false.)
          call write_point_stress_table(lu, model, fields, is, subs, elems)
          call write_fibre_stress_table(lu, model, fields, is, subs, elems)
          call write_solid_point_table(lu, model, fields, is, subs, elems, .false.)
       case ('E')
          call lu%line('    E   strains (tensor components, global axes; trusses: uniaxial stress state; '// &
               'CPS3/CPS4: at the centroid)')
          call tensor_table(lu, model, fields, is, subs, elems, .true.)
          call write_solid_point_table(lu, model, fields, is, subs, elems, .true.)
       case ('SF')
          call lu%line('    SF  section forces (trusses and beams: end forces, local axes, as ELEMENT END FORCES; '// &
               'plates and shells: nx, ny, nxy, mx, my, mxy at the centroid, element frame)')
          call section_force_table(lu, model, fields, is, subs, elems)
       case ('ENER')
          call write_energy_request(lu, model, fields, is, subs, elems)
       end select
    end do
    call lu%line('')
  end subroutine element_request

  subroutine tensor_table(lu, model, fields, is, subs, elems, strain)
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    logical, intent(in) :: strain
    real(wp), allocatable :: t(:, :)
    logical, allocatable :: ok(:)
    character(len=200) :: hline
    real(wp) :: scale
    integer :: i, d, nskip
    logical, allocatable :: solid(:)
    allocate (solid, source=solid_elements(model, subs, elems))
    if (size(elems) > 0 .and. all(solid)) return   ! solids: their integration-point table
    allocate (t(NTENSOR, size(elems)), ok(size(elems)))
    do i = 1, size(elems)
       call element_tensor(model, fields, is, subs(i), elems(i), strain, t(:, i), ok(i))
    end do
    write (hline, '(4x,a20,a10,a6,6a15)') 'substructure        ', '   element', '  type', TENSOR_HEAD
    call lu%line(trim(hline))
    scale = 0.0_wp
    if (any(ok)) scale = maxval(abs(t))
    nskip = 0
    do i = 1, size(elems)
       if (solid(i)) cycle
       if (.not. ok(i)) then
          nskip = nskip + 1
          cycle
       end if
       call element_prefix(lu, model, subs(i), elems(i), 4)
       do d = 1, NTENSOR
          call lu%put_es(chop(t(d, i), scale))
       end do
       call lu%newline()
    end do
    if (nskip > 0) call lu%line('    ('//itoa(nskip)//' beam or shell elements of the set have no '// &
         'single tensor: see SF)')
  end subroutine tensor_table

  subroutine section_force_table(lu, model, fields, is, subs, elems)
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    character(len=200) :: hline
    real(wp) :: scale_bar, scale_plate
    integer(i8) :: iel
    integer :: i, d, k, nsolid
    scale_bar = 0.0_wp
    scale_plate = 0.0_wp
    do i = 1, size(elems)
       iel = fields%elem_offset(subs(i)) + elems(i)
       if (is_plate_type(model%subs(subs(i))%elem_type(elems(i)))) then
          scale_plate = max(scale_plate, maxval(abs(fields%plate(:, iel, is))))
       else
          scale_bar = max(scale_bar, maxval(abs(fields%elem_force(:, :, iel, is))))
       end if
    end do
    write (hline, '(4x,a20,a10,a6,a4,6a15)') 'substructure        ', '   element', '  type', ' end', &
         '         n / nx', '        vy / ny', '       vz / nxy', '         t / mx', '        my / my', &
         '       mz / mxy'
    call lu%line(trim(hline))
    nsolid = 0
    do i = 1, size(elems)
       iel = fields%elem_offset(subs(i)) + elems(i)
       if (is_solid_type(model%subs(subs(i))%elem_type(elems(i)))) then
          nsolid = nsolid + 1
       else if (is_plate_type(model%subs(subs(i))%elem_type(elems(i)))) then
          call element_prefix(lu, model, subs(i), elems(i), 4)
          call lu%put('   -')
          do d = 1, 6
             call lu%put_es(chop(fields%plate(d, iel, is), scale_plate))
          end do
          call lu%newline()
       else
          do k = 1, 2
             call element_prefix(lu, model, subs(i), elems(i), 4)
             call lu%put_int(int(k, i8), 4)
             do d = 1, 6
                call lu%put_es(chop(fields%elem_force(d, k, iel, is), scale_bar))
             end do
             call lu%newline()
          end do
       end if
    end do
    if (nsolid > 0) call lu%line(solid_note(nsolid))
  end subroutine section_force_table

  pure function solid_note(n) result(text)
    !! The note of a section force table for its n solid elements.
    integer, intent(in) :: n
    character(:), allocatable :: text
    text = '    ('//itoa(n)//' solid elements of the set: solids have no section forces; see S and E)'
  end function solid_note
end module superjoin_output_requests
