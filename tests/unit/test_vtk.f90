program test_vtk
  !! Unit tests of the VTK writer (superjoin_output_vtk): file names, the *OUTPUT
  !! card, and the cells of plane/shell elements, which no solvable deck has yet
  !! (a hand-made model and results). The files are left in vtk_unit/ next to the
  !! test executable for the format check of the ctest vtk.plate_cells.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, EXIT_IO
  use superjoin_model_types, only: model_t, ET_CPS4, ET_S3, ET_B33, NDOF_NODE
  use superjoin_model_results, only: results_t
  use superjoin_deck_reader, only: read_deck_string
  use superjoin_output_vtk, only: write_vtk, vtk_base, vtk_piece_path, vtk_path_problem, &
       VTK_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_QUAD
  use superjoin_utils_strings, only: itoa, full_real
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  character(*), parameter :: NL = new_line('a')

  call names()
  call output_card()
  call plate_cells()
  call finish()

contains

  subroutine names()
    call check(vtk_base('out/frame.pvd') == 'out/frame', 'vtk_base drops .pvd')
    call check(vtk_base('out/frame.PVD') == 'out/frame', 'vtk_base drops .PVD')
    call check(vtk_base('out/frame') == 'out/frame', 'vtk_base keeps a name without .pvd')
    call check(vtk_base('a.b/frame.vtu') == 'a.b/frame.vtu', 'vtk_base keeps other extensions')
    call check(vtk_piece_path('a/b.pvd', 12) == 'a/b_12.vtu', 'piece path')
    call check(len(vtk_path_problem('res/frame')) == 0, 'a file name is fine')
    call check(len(vtk_path_problem('res/')) > 0, 'a directory is refused')
    call check(len(vtk_path_problem('.pvd')) > 0, 'an empty name is refused')
    call check(len(vtk_path_problem('res/..')) > 0, '.. is refused')
    call check(len(vtk_path_problem('a'//char(9)//'b')) > 0, 'a control character is refused')
  end subroutine names

  subroutine output_card()
    character(*), parameter :: DECK = '*MATERIAL, NAME=S'//NL//'*ELASTIC'//NL//'2.1e11, 0.3'//NL// &
         '*NODE'//NL//'1, 0, 0'//NL//'2, 1, 0'//NL//'*ELEMENT, TYPE=T2D2, ELSET=B'//NL//'1, 1, 2'//NL// &
         '*SOLID SECTION, ELSET=B, MATERIAL=S'//NL//'1e-4'//NL
    type(model_t) :: model
    type(error_t), allocatable :: error
    call read_deck_string(DECK//'*OUTPUT, VTK=res/x'//NL, 'dir/in.deck', model, error)
    call check(.not. allocated(error), '*OUTPUT read')
    if (allocated(model%vtk_path)) then
       call check(model%vtk_path == 'dir/res/x', '*OUTPUT path relative to the deck: '//model%vtk_path)
    else
       call check(.false., '*OUTPUT sets the VTK path')
    end if
    call read_deck_string(DECK, 'in.deck', model, error)
    call check(.not. allocated(model%vtk_path), 'no *OUTPUT, no VTK path')
    call read_deck_string(DECK//'*OUTPUT, VTK=/abs/x.pvd'//NL, 'dir/in.deck', model, error)
    call check(.not. allocated(error), 'absolute *OUTPUT path read')
    if (allocated(model%vtk_path)) call check(model%vtk_path == '/abs/x.pvd', 'absolute path kept')
  end subroutine output_card

  subroutine plate_cells()
    !! PLATE: a CPS4 (nodes 1 2 3 4) and an S3 (2 5 3); BEAM: a B33; a contact
    !! between PLATE.3 and BEAM.1; a support at PLATE.1.
    type(model_t) :: model
    type(results_t) :: res
    type(error_t), allocatable :: error
    character(:), allocatable :: dir, base, text
    real(wp), parameter :: PLATE2(6) = [1.5_wp, -2.25_wp, 0.125_wp, 3.0e-7_wp, -4.0e5_wp, 1.0_wp/3]
    integer :: k
    logical :: exists

    allocate (model%subs(2), model%contacts(1), model%links(1), model%steps(1))
    model%steps(1)%name = 'LOAD'
    associate (s => model%subs(1))
      s%name = 'PLATE'
      s%nnode = 5
      s%node_id = [1_ip, 2_ip, 3_ip, 4_ip, 5_ip]
      s%x = reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, &
           0.0_wp, 1.0_wp, 0.0_wp, 2.0_wp, 0.5_wp, 0.0_wp], [3, 5])
      s%nelem = 2
      s%elem_id = [10_ip, 20_ip]
      s%elem_type = [ET_CPS4, ET_S3]
      s%elem_nodes = reshape([1_ip, 2_ip, 3_ip, 4_ip, 2_ip, 5_ip, 3_ip, 0_ip], [4, 2])
    end associate
    associate (s => model%subs(2))
      s%name = 'BEAM'
      s%nnode = 2
      s%node_id = [7_ip, 8_ip]
      s%x = reshape([1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 2.0_wp], [3, 2])
      s%nelem = 1
      s%elem_id = [30_ip]
      s%elem_type = [ET_B33]
      s%elem_nodes = reshape([1_ip, 2_ip, 0_ip, 0_ip], [4, 1])
    end associate
    model%contacts(1)%name = 'JOINT'
    model%contacts(1)%master_sub = 1
    model%contacts(1)%slave_sub = 2
    model%links(1)%contact = 1
    model%links(1)%master_node = 3
    model%links(1)%slave_node = 1

    res%fields%vertex_offset = [0_i8, 5_i8, 7_i8]
    res%fields%elem_offset = [0_i8, 2_i8, 3_i8]
    allocate (res%fields%u(NDOF_NODE*7, 1), source=0.0_wp)
    res%fields%u(NDOF_NODE*4 + 3, 1) = -0.25_wp             ! PLATE.5 u3
    allocate (res%fields%has_dof(NDOF_NODE, 7), source=.true.)
    allocate (res%fields%elem_force(6, 2, 3, 1), source=0.0_wp)
    res%fields%elem_force(1, 2, 3, 1) = 42.0_wp              ! BEAM.30 end 2 n
    allocate (res%fields%plate(6, 3, 1), source=0.0_wp)
    res%fields%plate(:, 2, 1) = PLATE2
    allocate (res%fields%steps(1))
    allocate (res%fields%steps(1)%reactions(2))
    res%fields%steps(1)%reactions(:)%sub = 1
    res%fields%steps(1)%reactions(:)%node = 1
    res%fields%steps(1)%reactions(1)%dof = 1
    res%fields%steps(1)%reactions(2)%dof = 2
    res%fields%steps(1)%reactions(1)%force = -5.0_wp
    res%fields%steps(1)%reactions(2)%force = 6.0_wp
    allocate (res%fields%steps(1)%link_delta(NDOF_NODE, 1), res%fields%steps(1)%link_force(NDOF_NODE, 1), source=0.0_wp)
    res%fields%steps(1)%link_delta(4, 1) = 1.0e-3_wp
    res%fields%steps(1)%link_force(4, 1) = 2.0e3_wp
    allocate (res%fields%link_used(NDOF_NODE, 1), source=.false.)
    res%fields%link_used(4, 1) = .true.

    dir = executable_dir()//'vtk_unit'
    base = dir//'/plates'
    call write_vtk(base//'.pvd', model, res%fields, error)
    call check(.not. allocated(error), 'write_vtk succeeds')
    if (allocated(error)) return
    inquire (file=base//'_1.vtu.tmp', exist=exists)
    call check(.not. exists, 'no temporary left')
    text = slurp(base//'.pvd')
    call check(index(text, 'name="LOAD" file="plates_1.vtu"') > 0, 'collection names the piece')
    text = slurp(base//'_1.vtu')
    call check(index(text, '<Piece NumberOfPoints="7" NumberOfCells="5">') > 0, 'counts: 7 points, 5 cells')
    call check(index(text, 'Name="connectivity" format="ascii">'//NL//'0 1 2 3'//NL//'1 4 2'//NL// &
         '5 6'//NL//'2 5'//NL//'0'//NL) > 0, 'connectivity: quad, triangle, beam, contact, support')
    call check(index(text, 'Name="offsets" format="ascii">'//NL//'4'//NL//'7'//NL//'9'//NL//'11'//NL// &
         '12'//NL) > 0, 'offsets')
    call check(index(text, 'Name="types" format="ascii">'//NL//itoa(VTK_QUAD)//NL//itoa(VTK_TRIANGLE)//NL// &
         itoa(VTK_LINE)//NL//itoa(VTK_LINE)//NL//itoa(VTK_VERTEX)//NL) > 0, 'cell types 9 5 3 3 1')
    text = array_text(text, 'plate')
    call check(index(text, NL//'0 0 0 0 0 0'//NL//row(PLATE2)//NL//'0 0 0 0 0 0'//NL) > 0, &
         'plate resultants of the S3 in full precision')
    text = slurp(base//'_1.vtu')
    call check(index(array_text(text, 'reaction'), NL//row([-5.0_wp, 6.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp])//NL) > 0, &
         'reaction of the support cell')
    call check(index(array_text(text, 'delta'), NL//row([0.0_wp, 0.0_wp, 0.0_wp, 1.0e-3_wp, 0.0_wp, 0.0_wp])//NL) > 0, &
         'delta of the contact cell')
    call check(index(array_text(text, 'end2'), NL//row([42.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp])//NL) > 0, &
         'end forces of the beam cell')
    call check(index(array_text(text, 'displacement'), NL//'0 0 '//full_real(-0.25_wp)//NL) > 0, &
         'displacement of PLATE.5')
    k = index(text, '<!-- substructure 2 BEAM -->')
    call check(k > 0, 'substructure names in comments')

    ! a directory that cannot be created: EXIT_IO, nothing written
    call write_vtk('/proc/superjoin-no-such-dir/x', model, res%fields, error)
    call check(allocated(error), 'unwritable directory is an error')
    if (allocated(error)) call check(error%code == EXIT_IO, 'unwritable directory: EXIT_IO')
  end subroutine plate_cells

  function row(x) result(s)
    real(wp), intent(in) :: x(:)
    character(:), allocatable :: s
    integer :: d
    s = full_real(x(1))
    do d = 2, size(x)
       s = s//' '//full_real(x(d))
    end do
  end function row

  function array_text(text, name) result(s)
    !! The values of the DataArray called name.
    character(*), intent(in) :: text, name
    character(:), allocatable :: s
    integer :: a, b
    a = index(text, 'Name="'//name//'"')
    s = ''
    if (a == 0) return
    a = a + index(text(a:), '>')
    b = a + index(text(a:), '</DataArray>') - 2
    s = NL//text(a:b)
  end function array_text

  function slurp(path) result(text)
    character(*), intent(in) :: path
    character(:), allocatable :: text
    integer :: lu, ios, n
    open (newunit=lu, file=path, access='stream', form='unformatted', action='read', iostat=ios)
    if (ios /= 0) then
       text = ''
       return
    end if
    inquire (unit=lu, size=n)
    allocate (character(len=n) :: text)
    read (lu, iostat=ios) text
    close (lu)
  end function slurp

  function executable_dir() result(dir)
    !! Directory of this program (with a trailing '/'), or '' if unknown.
    character(:), allocatable :: dir
    character(len=4096) :: arg0
    integer :: k
    call get_command_argument(0, arg0)
    k = index(arg0, '/', back=.true.)
    dir = arg0(1:k)
  end function executable_dir
end program test_vtk
