module superjoin_output_mechanism
  !! The mechanism mode of a run that cannot be solved (exit status 3), so the
  !! user can see it: BASE_mechanism.vtu next to the --vtk files (ParaView: warp
  !! by the "mechanism" vector) and DIR/mechanism.csv next to the CSV results.
  !! Both written to a temporary name and renamed when complete.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE
  use superjoin_utils_posix, only: rename_file, remove_file, make_directory
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_vtk, only: vtk_base, open_array, close_array, point_ids, model_connectivity, model_offsets, &
       model_cell_types
  use superjoin_config, only: SUPERJOIN_VERSION
  use superjoin_utils_strings, only: itoa, full_real
  implicit none (type, external)
  private

  character(*), parameter :: TMP_EXT = '.tmp'
  character(*), parameter, public :: MECHANISM_VTU_SUFFIX = '_mechanism.vtu'
  character(*), parameter, public :: MECHANISM_CSV = 'mechanism.csv'

  public :: write_mechanism_vtk, write_mechanism_csv, mechanism_vtk_path

contains

  pure function mechanism_vtk_path(path) result(file)
    !! BASE_mechanism.vtu for the --vtk path (BASE: path without .pvd).
    character(*), intent(in) :: path
    character(:), allocatable :: file
    file = vtk_base(path)//MECHANISM_VTU_SUFFIX
  end function mechanism_vtk_path

  subroutine write_mechanism_vtk(path, model, mode, error)
    !! BASE_mechanism.vtu: the nodes, the elements and the contacts as cells,
    !! point arrays "mechanism" (translations) and "mechanism_rotation"
    !! (relative amplitudes, largest 1), "substructure" and "node".
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: mode(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    character(:), allocatable :: file
    integer(i8), allocatable :: offset(:)
    integer(i8) :: ncell
    integer :: isub, j
    integer(ip) :: n

    file = mechanism_vtk_path(path)
    j = index(file, '/', back=.true.)
    if (j > 1) then
       call make_directory(file(1:j - 1), error)
       if (allocated(error)) then
          error%message = 'error: '//error%message
          return
       end if
    end if
    allocate (offset(size(model%subs) + 1))
    offset(1) = 0
    ncell = size(model%links, kind=i8)
    do isub = 1, size(model%subs)
       offset(isub + 1) = offset(isub) + model%subs(isub)%nnode
       ncell = ncell + model%subs(isub)%nelem
    end do
    allocate (lu)
    call lu%open(file//TMP_EXT, error)
    if (allocated(error)) then
       call fatal_error(error, EXIT_IO, 'error: cannot write '//file//' (as '//file//TMP_EXT//')')
       return
    end if
    call lu%line('<?xml version="1.0"?>')
    call lu%line('<!-- superjoin '//SUPERJOIN_VERSION//': mechanism mode (relative amplitudes) -->')
    call lu%line('<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">')
    call lu%line('  <UnstructuredGrid>')
    call lu%line('    <Piece NumberOfPoints="'//itoa(offset(size(model%subs) + 1))//'" NumberOfCells="'// &
         itoa(ncell)//'">')
    call mechanism_point_data(lu, model, mode)
    call lu%line('      <Points>')
    call open_array(lu, 'Float64', 'coordinates', 3)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call lu%line(full_real(model%subs(isub)%x(1, n))//' '//full_real(model%subs(isub)%x(2, n))//' '// &
               full_real(model%subs(isub)%x(3, n)))
       end do
    end do
    call close_array(lu)
    call lu%line('      </Points>')
    call mechanism_cells(lu, model, offset)
    call lu%line('    </Piece>')
    call lu%line('  </UnstructuredGrid>')
    call lu%line('</VTKFile>')
    call finish(lu, file, error)
  end subroutine write_mechanism_vtk

  subroutine mechanism_point_data(lu, model, mode)
    !! The point arrays of the mechanism file: the mode's translations and
    !! rotations, the substructure and the node id.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: mode(:, :)
    integer :: j, first
    call lu%line('      <PointData Vectors="mechanism">')
    do first = 1, 4, 3
       if (first == 1) then
          call open_array(lu, 'Float64', 'mechanism', 3)
       else
          call open_array(lu, 'Float64', 'mechanism_rotation', 3)
       end if
       do j = 1, size(mode, 2)
          call lu%line(full_real(mode(first, j))//' '//full_real(mode(first + 1, j))//' '// &
               full_real(mode(first + 2, j)))
       end do
       call close_array(lu)
    end do
    call point_ids(lu, model)
    call lu%line('      </PointData>')
  end subroutine mechanism_point_data

  subroutine mechanism_cells(lu, model, offset)
    !! The cells of the mechanism file (elements, then contacts), the points
    !! of substructure isub numbered from offset(isub).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: offset(:)
    integer(i8) :: off
    call lu%line('      <Cells>')
    call open_array(lu, 'Int64', 'connectivity', 1)
    call model_connectivity(lu, model, offset)
    call close_array(lu)
    call open_array(lu, 'Int64', 'offsets', 1)
    off = 0
    call model_offsets(lu, model, off)
    call close_array(lu)
    call open_array(lu, 'UInt8', 'types', 1)
    call model_cell_types(lu, model)
    call close_array(lu)
    call lu%line('      </Cells>')
  end subroutine mechanism_cells

  subroutine write_mechanism_csv(dir, model, mode, error)
    !! DIR/mechanism.csv: substructure, node, u1..ur3 of the mode (relative
    !! amplitudes, largest 1), every node with a DOF, 17 digits.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: mode(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    character(:), allocatable :: file
    integer :: isub, d
    integer(ip) :: n
    integer(i8) :: v
    call make_directory(dir, error)
    if (allocated(error)) then
       error%message = 'error: '//error%message
       return
    end if
    file = dir//'/'//MECHANISM_CSV
    allocate (lu)
    call lu%open(file//TMP_EXT, error)
    if (allocated(error)) then
       call fatal_error(error, EXIT_IO, 'error: cannot write '//file//' (as '//file//TMP_EXT//')')
       return
    end if
    call lu%line('substructure,node,u1,u2,u3,ur1,ur2,ur3')
    v = 0
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          v = v + 1
          call lu%put(model%subs(isub)%name//','//itoa(int(model%subs(isub)%node_id(n))))
          do d = 1, NDOF_NODE
             call lu%put(','//full_real(mode(d, v)))
          end do
          call lu%newline()
       end do
    end do
    call finish(lu, file, error)
  end subroutine write_mechanism_csv

  subroutine finish(lu, file, error)
    !! Close the temporary file and rename it over file.
    type(text_buffer_t), intent(inout) :: lu
    character(*), intent(in) :: file
    type(error_t), allocatable, intent(out) :: error
    logical :: ok
    call lu%close(ok)
    if (.not. ok) then
       call remove_file(file//TMP_EXT)
       call fatal_error(error, EXIT_IO, 'error: failed writing '//file//' (as '//file//TMP_EXT//')')
       return
    end if
    call rename_file(file//TMP_EXT, file, error)
    if (allocated(error)) then
       error%message = 'error: '//error%message
       call remove_file(file//TMP_EXT)
    end if
  end subroutine finish
end module superjoin_output_mechanism
