module superjoin_model_output_paths
  !! The names of the VTK output that a deck (*OUTPUT, VTK=) and the command
  !! line (--vtk) give: FILE names FILE.pvd and FILE_<step>.vtu. Here, below
  !! the deck reader and the writers, so both check a name the same way.
  use superjoin_utils_strings, only: itoa, to_lower
  implicit none (type, external)
  private

  public :: vtk_base, vtk_piece_path, vtk_path_problem, has_control_char

  character(*), parameter, public :: PVD_EXT = '.pvd', VTU_EXT = '.vtu'
    !! Extensions of the collection and of the per-step pieces.

contains

  pure function vtk_base(path) result(base)
    !! The name the files are made of: path without a trailing .pvd.
    character(*), intent(in) :: path
    character(:), allocatable :: base
    integer :: n
    n = len(path)
    base = path
    if (n >= len(PVD_EXT)) then
       if (to_lower(path(n - len(PVD_EXT) + 1:n)) == PVD_EXT) base = path(1:n - len(PVD_EXT))
    end if
  end function vtk_base

  pure function vtk_piece_path(path, step) result(piece)
    !! Path of the .vtu file of step number `step`: BASE_step.vtu.
    character(*), intent(in) :: path
    integer, intent(in) :: step
    character(:), allocatable :: piece
    piece = vtk_base(path)//'_'//itoa(step)//VTU_EXT
  end function vtk_piece_path

  pure function vtk_path_problem(path) result(msg)
    !! Why `path` cannot name the VTK output ('' when it can).
    character(*), intent(in) :: path
    character(:), allocatable :: msg
    character(:), allocatable :: base, last
    integer :: slash
    msg = ''
    if (has_control_char(path)) then
       msg = 'the VTK file name contains a control character'
       return
    end if
    base = vtk_base(path)
    slash = index(base, '/', back=.true.)
    last = base(slash + 1:)
    if (len(last) == 0 .or. last == '.' .or. last == '..') &
         msg = 'the VTK output needs a file name (FILE gives FILE.pvd and FILE_<step>.vtu), not '''//path//''''
  end function vtk_path_problem

  pure logical function has_control_char(path)
    !! Whether a file name holds a character below blank.
    character(*), intent(in) :: path
    integer :: k
    has_control_char = .false.
    do k = 1, len(path)
       if (iachar(path(k:k)) < iachar(' ')) has_control_char = .true.
    end do
  end function has_control_char
end module superjoin_model_output_paths
