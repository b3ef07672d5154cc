module superjoin_output_mechanism
  !! The mechanism mode of a run that cannot be solved (exit status 3), so the
  !! user can see it: BASE_mechanism.vtu next to the --vtk files (ParaView: warp
  !! by the "mechanism" vector) and DIR/mechanism.csv next to the CSV results.
  !! Both written to a temporary name and renamed when complete.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE, ELEMENT_NODE_COUNT, ET_B32
  use superjoin_output_posix, only: rename_file, remove_file, make_directory
  use superjoin_output_text_buffer, only: text_buffer_t
  use superjoin_output_vtk, only: vtk_base, VTK_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_QUAD, &
       VTK_QUADRATIC_TRIANGLE, VTK_QUADRATIC_QUAD, VTK_POLY_LINE
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
    integer(i8) :: ncell, off
    integer :: isub, j, il, first, nn
    integer(ip) :: n, e

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
    call lu%line('      <PointData Vectors="mechanism">')
    do first = 1, 4, 3
       if (first == 1) then
          call open_array('Float64', 'mechanism', 3)
       else
          call open_array('Float64', 'mechanism_rotation', 3)
       end if
       do j = 1, size(mode, 2)
          call lu%line(full_real(mode(first, j))//' '//full_real(mode(first + 1, j))//' '// &
               full_real(mode(first + 2, j)))
       end do
       call lu%line('        </DataArray>')
    end do
    call open_array('Int32', 'substructure', 1)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call lu%line(itoa(isub))
       end do
    end do
    call lu%line('        </DataArray>')
    call open_array('Int32', 'node', 1)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call lu%line(itoa(int(model%subs(isub)%node_id(n))))
       end do
    end do
    call lu%line('        </DataArray>')
    call lu%line('      </PointData>')
    call lu%line('      <Points>')
    call open_array('Float64', 'coordinates', 3)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          call lu%line(full_real(model%subs(isub)%x(1, n))//' '//full_real(model%subs(isub)%x(2, n))//' '// &
               full_real(model%subs(isub)%x(3, n)))
       end do
    end do
    call lu%line('        </DataArray>')
    call lu%line('      </Points>')
    call lu%line('      <Cells>')
    call open_array('Int64', 'connectivity', 1)
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          nn = ELEMENT_NODE_COUNT(model%subs(isub)%elem_type(e))
          do j = 1, nn
             if (j > 1) call lu%put(' ')
             call lu%put(itoa(offset(isub) + model%subs(isub)%elem_nodes(j, e) - 1))
          end do
          call lu%newline()
       end do
    end do
    do il = 1, size(model%links)
       associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
         call lu%line(itoa(offset(ct%master_sub) + lk%master_node - 1)//' '// &
              itoa(offset(ct%slave_sub) + lk%slave_node - 1))
       end associate
    end do
    call lu%line('        </DataArray>')
    call open_array('Int64', 'offsets', 1)
    off = 0
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          off = off + ELEMENT_NODE_COUNT(model%subs(isub)%elem_type(e))
          call lu%line(itoa(off))
       end do
    end do
    do il = 1, size(model%links)
       off = off + 2
       call lu%line(itoa(off))
    end do
    call lu%line('        </DataArray>')
    call open_array('UInt8', 'types', 1)
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          if (model%subs(isub)%elem_type(e) == ET_B32) then
             call lu%line(itoa(VTK_POLY_LINE))     ! a three-node beam, not a triangle
          else
             call lu%line(itoa(cell_of(ELEMENT_NODE_COUNT(model%subs(isub)%elem_type(e)))))
          end if
       end do
    end do
    do il = 1, size(model%links)
       call lu%line(itoa(VTK_LINE))
    end do
    call lu%line('        </DataArray>')
    call lu%line('      </Cells>')
    call lu%line('    </Piece>')
    call lu%line('  </UnstructuredGrid>')
    call lu%line('</VTKFile>')
    call finish(lu, file, error)
  contains
    subroutine open_array(vtype, name, ncomp)
      character(*), intent(in) :: vtype, name
      integer, intent(in) :: ncomp
      call lu%put('        <DataArray type="'//vtype//'" Name="'//name//'"')
      if (ncomp > 1) call lu%put(' NumberOfComponents="'//itoa(ncomp)//'"')
      call lu%line(' format="ascii">')
    end subroutine open_array
  end subroutine write_mechanism_vtk

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

  pure integer function cell_of(nnode)
    !! VTK cell type of an element with nnode nodes.
    integer, intent(in) :: nnode
    select case (nnode)
    case (2)
       cell_of = VTK_LINE
    case (3)
       cell_of = VTK_TRIANGLE
    case (4)
       cell_of = VTK_QUAD
    case (6)
       cell_of = VTK_QUADRATIC_TRIANGLE
    case (8)
       cell_of = VTK_QUADRATIC_QUAD
    case default
       cell_of = VTK_VERTEX
    end select
  end function cell_of
end module superjoin_output_mechanism
