module superjoin_output_vtk
  !! VTK XML output for ParaView: one unstructured grid (.vtu, ASCII) per step
  !! and a ParaView collection (.pvd) naming them. Points are the nodes of all
  !! substructures; cells are the elements (lines, triangles, quads), the
  !! contact elements (a line from the master to the slave node) and the
  !! supports (a vertex per supported node). Every file is written to a
  !! temporary name; the names are switched only when all files are complete,
  !! the collection last, so a failed run leaves no file that looks finished.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE, ELEMENT_NODE_COUNT
  use superjoin_elements_traits, only: element_vtk_cell, VTK_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_QUAD, &
       VTK_QUADRATIC_TRIANGLE, VTK_QUADRATIC_QUAD, VTK_POLY_LINE
  use superjoin_model_results, only: result_fields_t
  use superjoin_output_file_selection, only: file_selection_t, select_file_output, FILE_DISPLACEMENTS, &
       FILE_REACTIONS, FILE_ELEMENT_FORCES
  use superjoin_utils_posix, only: rename_file, remove_file, make_directory
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_config, only: SUPERJOIN_VERSION
  use superjoin_utils_strings, only: itoa, full_real, to_lower
  use superjoin_model_output_paths, only: vtk_base, vtk_piece_path, vtk_path_problem, PVD_EXT
  implicit none (type, external)
  private

  public :: write_vtk, vtk_base, vtk_piece_path, vtk_path_problem
  public :: open_array, close_array, point_ids, model_connectivity, model_offsets, model_cell_types
    !! The pieces of a .vtu file that the mechanism file shares (superjoin_output_mechanism).

  public :: VTK_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_QUAD, VTK_QUADRATIC_TRIANGLE, VTK_QUADRATIC_QUAD, VTK_POLY_LINE
    !! VTK cell type codes (superjoin_elements_traits).
  integer, parameter, public :: CELL_ELEMENT = 1, CELL_CONTACT = 2, CELL_SUPPORT = 3
    !! Values of the cell array `kind`.
  character(*), parameter :: TMP_EXT = '.tmp'
  integer, parameter :: NCOMP = 6
    !! Components of the 6-vectors (element end forces, resultants, contact Δ and F, reactions).
  character(*), parameter :: FORCE_NAMES = ' ComponentName0="n" ComponentName1="vy" ComponentName2="vz"'// &
       ' ComponentName3="t" ComponentName4="my" ComponentName5="mz"'
  character(*), parameter :: PLATE_NAMES = ' ComponentName0="nx" ComponentName1="ny" ComponentName2="nxy"'// &
       ' ComponentName3="mx" ComponentName4="my" ComponentName5="mxy"'
  character(*), parameter :: DOF_NAMES = ' ComponentName0="dof1" ComponentName1="dof2" ComponentName2="dof3"'// &
       ' ComponentName3="dof4" ComponentName4="dof5" ComponentName5="dof6"'

  type :: grid_t
    !! The cells of the grid (the same for every step).
     integer(i8) :: npoint = 0
     integer(i8) :: ncell = 0
     integer(i8) :: nelem = 0                      !! element cells come first (in elem_offset order)
     integer(i8) :: nsupport = 0                   !! support cells come last
     integer(i8), allocatable :: support_vertex(:) !! (nsupport) vertex of each support cell
     integer(i8), allocatable :: vertex_support(:) !! (npoint) support cell of a vertex, 0 if none
  end type grid_t

contains


  subroutine write_vtk(path, model, fields, error)
    !! Write BASE.pvd and BASE_1.vtu ... BASE_<nstep>.vtu (BASE: path without
    !! .pvd); the directory of BASE is created if needed.
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    character(:), allocatable :: base, dir
    type(grid_t) :: grid
    type(file_selection_t) :: sel
    integer :: is, nstep, slash

    base = vtk_base(path)
    if (len(vtk_path_problem(path)) > 0) then
       call fatal_error(error, EXIT_IO, 'error: '//vtk_path_problem(path))
       return
    end if
    slash = index(base, '/', back=.true.)
    if (slash > 1) then
       dir = base(1:slash - 1)
       call make_directory(dir, error)
       if (allocated(error)) then
          error%message = 'error: '//error%message
          return
       end if
    end if
    nstep = size(model%steps)
    call build_grid(model, fields, grid)
    call select_file_output(model, sel)
    do is = 1, nstep
       call write_piece(vtk_piece_path(path, is), model, fields, grid, sel, is, error)
       if (allocated(error)) then
          call remove_temporaries(is)
          return
       end if
    end do
    call write_collection(base//PVD_EXT, base, model, error)
    if (allocated(error)) then
       call remove_temporaries(nstep)
       return
    end if
    do is = 1, nstep
       call rename_file(vtk_piece_path(path, is)//TMP_EXT, vtk_piece_path(path, is), error)
       if (allocated(error)) then
          error%message = 'error: '//error%message
          call remove_temporaries(nstep)
          return
       end if
    end do
    call rename_file(base//PVD_EXT//TMP_EXT, base//PVD_EXT, error)
    if (allocated(error)) then
       error%message = 'error: '//error%message
       call remove_file(base//PVD_EXT//TMP_EXT)
    end if

  contains

    subroutine remove_temporaries(upto)
      integer, intent(in) :: upto
      integer :: k
      do k = 1, upto
         call remove_file(vtk_piece_path(path, k)//TMP_EXT)
      end do
      call remove_file(base//PVD_EXT//TMP_EXT)
    end subroutine remove_temporaries
  end subroutine write_vtk

  subroutine build_grid(model, fields, grid)
    !! Count the cells; the support cells are the nodes with a reaction, in
    !! vertex order.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(grid_t), intent(out) :: grid
    integer :: k, isub
    integer(i8) :: v
    grid%npoint = fields%vertex_offset(size(model%subs) + 1)
    grid%nelem = fields%elem_offset(size(model%subs) + 1)
    allocate (grid%vertex_support(grid%npoint), source=0_i8)
    if (size(model%steps) > 0) then
       do k = 1, size(fields%steps(1)%reactions)
          associate (rc => fields%steps(1)%reactions(k))
            v = fields%vertex_offset(rc%sub) + rc%node
            grid%vertex_support(v) = 1
          end associate
       end do
    end if
    grid%nsupport = count(grid%vertex_support > 0, kind=i8)
    allocate (grid%support_vertex(grid%nsupport))
    grid%nsupport = 0
    do isub = 1, size(model%subs)
       do v = fields%vertex_offset(isub) + 1, fields%vertex_offset(isub + 1)
          if (grid%vertex_support(v) == 0) cycle
          grid%nsupport = grid%nsupport + 1
          grid%support_vertex(grid%nsupport) = v
          grid%vertex_support(v) = grid%nsupport
       end do
    end do
    grid%ncell = grid%nelem + size(model%links, kind=i8) + grid%nsupport
  end subroutine build_grid

  subroutine write_collection(final, base, model, error)
    !! The .pvd collection (written to final.tmp): one data set per step,
    !! timestep = step number.
    character(*), intent(in) :: final, base
    type(model_t), intent(in) :: model
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    integer :: is, slash
    logical :: ok
    allocate (lu)
    call lu%open(final//TMP_EXT, error)
    if (allocated(error)) then
       call fatal_error(error, EXIT_IO, 'error: cannot write '//final//' (as '//final//TMP_EXT//')')
       return
    end if
    slash = index(base, '/', back=.true.)
    call lu%line('<?xml version="1.0"?>')
    call lu%line('<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">')
    call lu%line('  <Collection>')
    do is = 1, size(model%steps)
       call lu%line('    <DataSet timestep="'//itoa(is)//'" group="" part="0" name="'// &
            xml_escape(model%steps(is)%name)//'" file="'// &
            xml_escape(vtk_piece_path(base(slash + 1:), is))//'"/>')
    end do
    call lu%line('  </Collection>')
    call lu%line('</VTKFile>')
    call lu%close(ok)
    if (.not. ok) then
       call remove_file(final//TMP_EXT)
       call fatal_error(error, EXIT_IO, 'error: failed writing '//final//' (as '//final//TMP_EXT//')')
    end if
  end subroutine write_collection

  subroutine write_piece(final, model, fields, grid, sel, is, error)
    !! The .vtu file of step is (written to final.tmp): the arrays the file
    !! requests select (all without them).
    character(*), intent(in) :: final
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(grid_t), intent(in) :: grid
    type(file_selection_t), intent(in) :: sel
    integer, intent(in) :: is
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    logical :: ok
    integer :: isub, k
    allocate (lu)
    call lu%open(final//TMP_EXT, error)
    if (allocated(error)) then
       call fatal_error(error, EXIT_IO, 'error: cannot write '//final//' (as '//final//TMP_EXT//')')
       return
    end if

    call lu%line('<?xml version="1.0"?>')
    call lu%line('<!-- superjoin '//SUPERJOIN_VERSION//': step '//itoa(is)//' '//xml_comment(model%steps(is)%name)//' -->')
    do isub = 1, size(model%subs)
       call lu%line('<!-- substructure '//itoa(isub)//' '//xml_comment(model%subs(isub)%name)//' -->')
    end do
    do k = 1, size(model%contacts)
       call lu%line('<!-- contact '//itoa(k)//' '//xml_comment(model%contacts(k)%name)//' -->')
    end do
    call lu%line('<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">')
    call lu%line('  <UnstructuredGrid>')
    call lu%line('    <FieldData>')
    call lu%line('      <DataArray type="Float64" Name="TimeValue" NumberOfTuples="1" format="ascii">'// &
         itoa(is)//'</DataArray>')
    call lu%line('    </FieldData>')
    call lu%line('    <Piece NumberOfPoints="'//itoa(grid%npoint)//'" NumberOfCells="'//itoa(grid%ncell)//'">')
    call point_data(lu, model, fields, sel, is)
    call cell_data(lu, model, fields, grid, sel, is)
    call points(lu, model)
    call cells(lu, model, fields, grid)
    call lu%line('    </Piece>')
    call lu%line('  </UnstructuredGrid>')
    call lu%line('</VTKFile>')
    call lu%close(ok)
    if (.not. ok) then
       call remove_file(final//TMP_EXT)
       call fatal_error(error, EXIT_IO, 'error: failed writing '//final//' (as '//final//TMP_EXT//')')
    end if
  end subroutine write_piece

  subroutine point_data(lu, model, fields, sel, is)
    !! displacement and rotation (global axes; when selected), substructure
    !! index and node id. When a node set narrows the node results, the other
    !! points hold zeros and the point array `results` says which hold results (1).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(file_selection_t), intent(in) :: sel
    integer, intent(in) :: is
    integer :: d, first
    integer(i8) :: v
    if (.not. sel%kind(FILE_DISPLACEMENTS)) then
       call lu%line('      <PointData>')
    else
       call lu%line('      <PointData Vectors="displacement">')
    end if
    do first = 1, 4, 3
       if (.not. sel%kind(FILE_DISPLACEMENTS)) exit
       if (first == 1) then
          call open_array(lu, 'Float64', 'displacement', 3)
       else
          call open_array(lu, 'Float64', 'rotation', 3)
       end if
       do v = 1, size(fields%has_dof, 2, kind=i8)
          do d = first, first + 2
             if (d > first) call lu%put(' ')
             call lu%put(full_real(merge(fields%u(NDOF_NODE*(v - 1) + d, is), 0.0_wp, sel%node(v))))
          end do
          call lu%newline()
       end do
       call close_array(lu)
    end do
    if (.not. all(sel%node)) then
       ! a node set narrows the node results: say which points hold them
       call open_array(lu, 'Int32', 'results', 1)
       do v = 1, size(sel%node, kind=i8)
          call lu%line(itoa(merge(1, 0, sel%node(v))))
       end do
       call close_array(lu)
    end if
    call point_ids(lu, model)
    call lu%line('      </PointData>')
  end subroutine point_data

  subroutine cell_data(lu, model, fields, grid, sel, is)
    !! Per cell: kind, substructure, element id and type, contact index, element
    !! end forces, shell/plane resultants, contact Δ and F, support reaction.
    !! The element results and the reactions only when selected; when the
    !! element results are selected for some elements only, the others hold
    !! zeros and the cell array `results` says which hold results (1).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(grid_t), intent(in) :: grid
    type(file_selection_t), intent(in) :: sel
    integer, intent(in) :: is
    integer :: k, il
    integer(i8) :: c
    real(wp) :: zero(NCOMP)
    real(wp), allocatable :: reac(:, :)
    zero = 0.0_wp

    call lu%line('      <CellData Scalars="kind">')
    call cell_ids(lu, model, fields, grid)

    if (sel%kind(FILE_ELEMENT_FORCES)) then
       if (.not. all(sel%elem)) then
          call open_array(lu, 'Int32', 'results', 1)
          do c = 1, grid%nelem
             call lu%line(itoa(merge(1, 0, sel%elem(c))))
          end do
          call zeros(lu, size(model%links, kind=i8) + grid%nsupport, 1)
          call close_array(lu)
       end if
       do k = 1, 2
          call open_array(lu, 'Float64', 'end'//itoa(k), NCOMP, FORCE_NAMES)
          do c = 1, grid%nelem
             if (.not. allocated(fields%elem_force)) then   ! plane and shell elements only: no end forces
                call put_tuple(lu, zero)
             else
                call put_tuple(lu, merge(fields%elem_force(:, k, c, is), zero, sel%elem(c)))
             end if
          end do
          call zeros(lu, size(model%links, kind=i8) + grid%nsupport, NCOMP)
          call close_array(lu)
       end do

       call open_array(lu, 'Float64', 'plate', NCOMP, PLATE_NAMES)
       do c = 1, grid%nelem
          call put_tuple(lu, merge(fields%plate(:, c, is), zero, sel%elem(c)))
       end do
       call zeros(lu, size(model%links, kind=i8) + grid%nsupport, NCOMP)
       call close_array(lu)
    end if

    call contact_array('delta', fields%steps(is)%link_delta)
    call contact_array('force', fields%steps(is)%link_force)

    if (.not. sel%kind(FILE_REACTIONS)) then
       call lu%line('      </CellData>')
       return
    end if
    call open_array(lu, 'Float64', 'reaction', NCOMP, DOF_NAMES)
    call zeros(lu, grid%nelem + size(model%links, kind=i8), NCOMP)
    allocate (reac(NCOMP, grid%nsupport), source=0.0_wp)
    do k = 1, size(fields%steps(is)%reactions)
       associate (rc => fields%steps(is)%reactions(k))
         c = grid%vertex_support(fields%vertex_offset(rc%sub) + rc%node)
         if (c > 0 .and. sel%node(fields%vertex_offset(rc%sub) + rc%node)) reac(rc%dof, c) = reac(rc%dof, c) + rc%force
       end associate
    end do
    do c = 1, grid%nsupport
       call put_tuple(lu, reac(:, c))
    end do
    call close_array(lu)
    call lu%line('      </CellData>')
  contains
    subroutine contact_array(name, values)
      !! A cell array that only the contact cells carry (values(6, nlink), the
      !! components a contact does not connect written as 0).
      character(*), intent(in) :: name
      real(wp), intent(in) :: values(:, :)
      call open_array(lu, 'Float64', name, NCOMP, DOF_NAMES)
      call zeros(lu, grid%nelem, NCOMP)
      do il = 1, size(model%links)
         call put_tuple(lu, merge(values(:, il), zero, fields%link_used(:, il)))
      end do
      call zeros(lu, grid%nsupport, NCOMP)
      call close_array(lu)
    end subroutine contact_array
  end subroutine cell_data

  subroutine cell_ids(lu, model, fields, grid)
    !! The cell arrays that say what each cell is: kind, substructure, element
    !! id and type, contact index.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(grid_t), intent(in) :: grid
    integer :: isub, il
    integer(ip) :: e
    integer(i8) :: c
    call open_array(lu, 'Int32', 'kind', 1)
    do c = 1, grid%nelem
       call lu%line(itoa(CELL_ELEMENT))
    end do
    do il = 1, size(model%links)
       call lu%line(itoa(CELL_CONTACT))
    end do
    do c = 1, grid%nsupport
       call lu%line(itoa(CELL_SUPPORT))
    end do
    call close_array(lu)

    ! substructure: of the element, of the contact's master node, of the supported node
    call open_array(lu, 'Int32', 'substructure', 1)
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          call lu%line(itoa(isub))
       end do
    end do
    do il = 1, size(model%links)
       call lu%line(itoa(model%contacts(model%links(il)%contact)%master_sub))
    end do
    do c = 1, grid%nsupport
       call lu%line(itoa(vertex_sub(model, fields, grid%support_vertex(c))))
    end do
    call close_array(lu)

    call open_array(lu, 'Int32', 'element', 1)
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          call lu%line(itoa(int(model%subs(isub)%elem_id(e))))
       end do
    end do
    call zeros(lu, size(model%links, kind=i8) + grid%nsupport, 1)
    call close_array(lu)

    call open_array(lu, 'Int32', 'element_type', 1)
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          call lu%line(itoa(model%subs(isub)%elem_type(e)))
       end do
    end do
    call zeros(lu, size(model%links, kind=i8) + grid%nsupport, 1)
    call close_array(lu)

    call open_array(lu, 'Int32', 'contact', 1)
    call zeros(lu, grid%nelem, 1)
    do il = 1, size(model%links)
       call lu%line(itoa(model%links(il)%contact))
    end do
    call zeros(lu, grid%nsupport, 1)
    call close_array(lu)
  end subroutine cell_ids

  subroutine points(lu, model)
    !! Node coordinates, substructure after substructure.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer :: isub
    integer(ip) :: n
    call lu%line('      <Points>')
    call open_array(lu, 'Float64', 'coordinates', 3)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call put_tuple(lu, model%subs(isub)%x(:, n))
       end do
    end do
    call close_array(lu)
    call lu%line('      </Points>')
  end subroutine points

  subroutine cells(lu, model, fields, grid)
    !! Connectivity (0-based point indices), offsets and cell types.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(grid_t), intent(in) :: grid
    integer(i8) :: c, offset
    call lu%line('      <Cells>')
    call open_array(lu, 'Int64', 'connectivity', 1)
    call model_connectivity(lu, model, fields%vertex_offset)
    do c = 1, grid%nsupport
       call lu%line(itoa(grid%support_vertex(c) - 1))
    end do
    call close_array(lu)

    call open_array(lu, 'Int64', 'offsets', 1)
    offset = 0
    call model_offsets(lu, model, offset)
    do c = 1, grid%nsupport
       offset = offset + 1
       call lu%line(itoa(offset))
    end do
    call close_array(lu)

    call open_array(lu, 'UInt8', 'types', 1)
    call model_cell_types(lu, model)
    do c = 1, grid%nsupport
       call lu%line(itoa(VTK_VERTEX))
    end do
    call close_array(lu)
    call lu%line('      </Cells>')
  end subroutine cells

  subroutine model_connectivity(lu, model, vertex_offset)
    !! The connectivity rows of the element cells, then of the contact cells
    !! (master node, slave node): 0-based point indices, the points of
    !! substructure isub after vertex_offset(isub).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: vertex_offset(:)
    integer :: isub, il, j, nn
    integer(ip) :: e
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          nn = ELEMENT_NODE_COUNT(model%subs(isub)%elem_type(e))
          do j = 1, nn
             if (j > 1) call lu%put(' ')
             call lu%put(itoa(vertex_offset(isub) + model%subs(isub)%elem_nodes(j, e) - 1))
          end do
          call lu%newline()
       end do
    end do
    do il = 1, size(model%links)
       associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
         call lu%line(itoa(vertex_offset(ct%master_sub) + lk%master_node - 1)//' '// &
              itoa(vertex_offset(ct%slave_sub) + lk%slave_node - 1))
       end associate
    end do
  end subroutine model_connectivity

  subroutine model_offsets(lu, model, offset)
    !! The offsets rows of the element cells, then of the contact cells,
    !! counting on from offset (which returns the last).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer(i8), intent(inout) :: offset
    integer :: isub, il
    integer(ip) :: e
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          offset = offset + ELEMENT_NODE_COUNT(model%subs(isub)%elem_type(e))
          call lu%line(itoa(offset))
       end do
    end do
    do il = 1, size(model%links)
       offset = offset + 2
       call lu%line(itoa(offset))
    end do
  end subroutine model_offsets

  subroutine model_cell_types(lu, model)
    !! The VTK cell types of the element cells (their element type's,
    !! superjoin_elements_traits), then of the contact cells (lines).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer :: isub, il
    integer(ip) :: e
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          call lu%line(itoa(element_vtk_cell(model%subs(isub)%elem_type(e))))
       end do
    end do
    do il = 1, size(model%links)
       call lu%line(itoa(VTK_LINE))
    end do
  end subroutine model_cell_types

  subroutine point_ids(lu, model)
    !! The point arrays substructure (index) and node (id).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer :: isub
    integer(ip) :: n
    call open_array(lu, 'Int32', 'substructure', 1)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call lu%line(itoa(isub))
       end do
    end do
    call close_array(lu)
    call open_array(lu, 'Int32', 'node', 1)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call lu%line(itoa(int(model%subs(isub)%node_id(n))))
       end do
    end do
    call close_array(lu)
  end subroutine point_ids

  pure integer function vertex_sub(model, fields, v) result(isub)
    !! Substructure of vertex v.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer(i8), intent(in) :: v
    do isub = 1, size(model%subs)
       if (v <= fields%vertex_offset(isub + 1)) return
    end do
    isub = size(model%subs)
  end function vertex_sub

  subroutine open_array(lu, vtype, name, ncomp, extra)
    !! The opening tag of an ASCII data array of ncomp components (extra: more attributes).
    type(text_buffer_t), intent(inout) :: lu
    character(*), intent(in) :: vtype, name
    integer, intent(in) :: ncomp
    character(*), intent(in), optional :: extra
    call lu%put('        <DataArray type="'//vtype//'" Name="'//name//'"')
    if (ncomp > 1) call lu%put(' NumberOfComponents="'//itoa(ncomp)//'"')
    if (present(extra)) call lu%put(extra)
    call lu%line(' format="ascii">')
  end subroutine open_array

  subroutine close_array(lu)
    !! The closing tag of a data array.
    type(text_buffer_t), intent(inout) :: lu
    call lu%line('        </DataArray>')
  end subroutine close_array

  subroutine put_tuple(lu, x)
    !! One tuple on one line, 17 significant digits.
    type(text_buffer_t), intent(inout) :: lu
    real(wp), intent(in) :: x(:)
    integer :: d
    do d = 1, size(x)
       if (d > 1) call lu%put(' ')
       call lu%put(full_real(x(d)))
    end do
    call lu%newline()
  end subroutine put_tuple

  subroutine zeros(lu, ntuple, ncomp)
    !! ntuple tuples of ncomp zeros.
    type(text_buffer_t), intent(inout) :: lu
    integer(i8), intent(in) :: ntuple
    integer, intent(in) :: ncomp
    integer(i8) :: t
    character(:), allocatable :: row
    row = '0'//repeat(' 0', ncomp - 1)
    do t = 1, ntuple
       call lu%line(row)
    end do
  end subroutine zeros

  pure function xml_escape(s) result(t)
    !! s with the XML special characters replaced by entities (for attribute values).
    character(*), intent(in) :: s
    character(:), allocatable :: t
    integer :: k
    t = ''
    do k = 1, len(s)
       select case (s(k:k))
       case ('&')
          t = t//'&amp;'
       case ('<')
          t = t//'&lt;'
       case ('>')
          t = t//'&gt;'
       case ('"')
          t = t//'&quot;'
       case ("'")
          t = t//'&apos;'
       case default
          t = t//s(k:k)
       end select
    end do
  end function xml_escape

  pure function xml_comment(s) result(t)
    !! s made safe inside an XML comment (no '--').
    character(*), intent(in) :: s
    character(:), allocatable :: t
    integer :: k
    t = s
    do k = 2, len(t)
       if (t(k - 1:k) == '--') t(k:k) = '_'
    end do
  end function xml_comment

end module superjoin_output_vtk
