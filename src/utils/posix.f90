module superjoin_utils_posix
  !! Tiny bindings to the C library: renaming and removing files, and fast,
  !! correctly rounded number scanning (strtod/strtoll) over a character buffer.
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_ptr, c_loc, &
       c_double, c_long_long, c_intptr_t, c_associated
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  implicit none (type, external)
  private

  public :: rename_file, remove_file, make_directory, scan_int, scan_real, output_target, size_unknown

  integer, parameter, public :: PATH_ABSENT = 0, PATH_REGULAR = 1, PATH_LINK = 2, PATH_DIRECTORY = 3, &
       PATH_OTHER = 4
    !! What a path names (sj_path_kind in pathinfo.c).
  integer, parameter :: REAL_PATH_CAP = 4096
    !! longest resolved path

  integer(c_int), parameter :: DECIMAL = 10            !! base for strtoll
  integer(c_int), parameter :: DIR_MODE = int(o'777', c_int)  !! mkdir mode (before umask)

  interface
     function sj_path_kind(path, follow) bind(c, name='sj_path_kind') result(kind)
       import :: c_int, c_char
       character(kind=c_char), intent(in) :: path(*)
       integer(c_int), value :: follow
       integer(c_int) :: kind
     end function sj_path_kind

     function sj_real_path(path, out, cap) bind(c, name='sj_real_path') result(n)
       import :: c_int, c_char
       character(kind=c_char), intent(in) :: path(*)
       character(kind=c_char), intent(out) :: out(*)
       integer(c_int), value :: cap
       integer(c_int) :: n
     end function sj_real_path

     function c_rename(from, to) bind(c, name='rename') result(status)
       import :: c_int, c_char
       character(kind=c_char), intent(in) :: from(*), to(*)
       integer(c_int) :: status
     end function c_rename

     function c_remove(path) bind(c, name='remove') result(status)
       import :: c_int, c_char
       character(kind=c_char), intent(in) :: path(*)
       integer(c_int) :: status
     end function c_remove

     function c_mkdir(path, mode) bind(c, name='mkdir') result(status)
       import :: c_int, c_char
       character(kind=c_char), intent(in) :: path(*)
       integer(c_int), value :: mode
       integer(c_int) :: status
     end function c_mkdir

     function c_opendir(path) bind(c, name='opendir') result(dir)
       import :: c_char, c_ptr
       character(kind=c_char), intent(in) :: path(*)
       type(c_ptr) :: dir
     end function c_opendir

     function c_closedir(dir) bind(c, name='closedir') result(status)
       import :: c_ptr, c_int
       type(c_ptr), value :: dir
       integer(c_int) :: status
     end function c_closedir

     function c_strtod(str, endptr) bind(c, name='strtod') result(v)
       import :: c_char, c_ptr, c_double
       character(kind=c_char), intent(in) :: str(*)
       type(c_ptr), intent(out) :: endptr
       real(c_double) :: v
     end function c_strtod

     function c_strtoll(str, endptr, base) bind(c, name='strtoll') result(v)
       import :: c_char, c_ptr, c_int, c_long_long
       character(kind=c_char), intent(in) :: str(*)
       type(c_ptr), intent(out) :: endptr
       integer(c_int), value :: base
       integer(c_long_long) :: v
     end function c_strtoll
  end interface

contains

  subroutine rename_file(from, to, error)
    !! Rename (atomically on POSIX file systems) the file from to the path to,
    !! replacing it. Failure: EXIT_IO naming both paths.
    character(*), intent(in) :: from, to
    type(error_t), allocatable, intent(out) :: error
    if (c_rename(from//c_null_char, to//c_null_char) /= 0) &
         call fatal_error(error, EXIT_IO, "cannot rename '"//from//"' to '"//to//"'")
  end subroutine rename_file

  logical function size_unknown(path)
    !! path (its links followed) names a FIFO, a pipe (a shell's <(...),
    !! /dev/fd/N) or a device: something to read to its end, whose size is
    !! not known beforehand (a stream read of its "size" would read nothing).
    character(*), intent(in) :: path
    size_unknown = sj_path_kind(path//c_null_char, 1_c_int) == PATH_OTHER
  end function size_unknown

  subroutine output_target(path, target, error)
    !! The file an output named path must be written to, as NAME.tmp renamed
    !! over NAME: path itself when it is absent or a regular file, the file a
    !! symbolic link points to (the link stays), and an EXIT_IO error for a
    !! directory, a device or a FIFO (a rename would replace it).
    character(*), intent(in) :: path
    character(:), allocatable, intent(out) :: target
    type(error_t), allocatable, intent(out) :: error
    character(kind=c_char) :: buf(REAL_PATH_CAP)
    integer(c_int) :: n
    integer :: i
    target = path
    select case (sj_path_kind(path//c_null_char, 0_c_int))
    case (PATH_ABSENT, PATH_REGULAR)
       return
    case (PATH_LINK)
       n = sj_real_path(path//c_null_char, buf, REAL_PATH_CAP)
       if (n > 0) then
          deallocate (target)
          allocate (character(len=n) :: target)
          do i = 1, n
             target(i:i) = buf(i)
          end do
          if (sj_path_kind(target//c_null_char, 0_c_int) == PATH_REGULAR) return
       end if
       ! a dangling link or one to something that is not a regular file
       call fatal_error(error, EXIT_IO, 'error: '//path//' is a link to something that is not a '// &
            'regular file (results are written to a temporary file and renamed)')
    case default
       call fatal_error(error, EXIT_IO, 'error: '//path//' is not a regular file (results are written '// &
            'to a temporary file and renamed, which would replace it)')
    end select
  end subroutine output_target

  subroutine remove_file(path, stat)
    !! Remove the file path; stat (optional) is 0 on success, non-zero otherwise.
    character(*), intent(in) :: path
    integer, intent(out), optional :: stat
    integer(c_int) :: status
    status = c_remove(path//c_null_char)
    if (present(stat)) stat = int(status)
  end subroutine remove_file

  subroutine make_directory(path, error)
    !! Create the directory path and its missing parents (like mkdir -p); an
    !! existing directory is fine. Failure: EXIT_IO naming the path.
    character(*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    integer :: i
    if (len_trim(path) == 0) return
    if (is_directory(path)) return
    do i = 2, len_trim(path)
       if (path(i:i) == '/' .and. path(i - 1:i - 1) /= '/') then
          if (.not. is_directory(path(1:i - 1))) then
             if (c_mkdir(path(1:i - 1)//c_null_char, DIR_MODE) /= 0) then
                if (.not. is_directory(path(1:i - 1))) then
                   call fatal_error(error, EXIT_IO, "cannot create directory '"//path(1:i - 1)//"'")
                   return
                end if
             end if
          end if
       end if
    end do
    if (c_mkdir(trim(path)//c_null_char, DIR_MODE) /= 0) then
       if (.not. is_directory(trim(path))) &
            call fatal_error(error, EXIT_IO, "cannot create directory '"//trim(path)//"'")
    end if
  end subroutine make_directory

  function is_directory(path) result(yes)
    !! Whether path names an existing directory that can be opened.
    character(*), intent(in) :: path
    logical :: yes
    type(c_ptr) :: dir
    integer(c_int) :: status
    dir = c_opendir(path//c_null_char)
    yes = c_associated(dir)
    if (yes) status = c_closedir(dir)
  end function is_directory

  subroutine scan_int(buf, pos, value, ok)
    !! Read a decimal integer at buf(pos:) (leading white space skipped, as
    !! strtoll); pos moves past it. ok is false when no digits were found.
    !! buf must contain a NUL character after the text.
    character(len=1), intent(in), target, contiguous :: buf(:)
    integer(i8), intent(inout) :: pos
    integer(i8), intent(out) :: value
    logical, intent(out) :: ok
    type(c_ptr) :: endptr
    integer(c_intptr_t) :: start, finish
    value = 0
    ok = .false.
    if (pos < 1 .or. pos > size(buf, kind=i8)) return
    value = int(c_strtoll(buf(pos:), endptr, DECIMAL), i8)
    if (.not. c_associated(endptr)) return
    start = transfer(c_loc(buf(pos)), start)
    finish = transfer(endptr, finish)
    ok = finish > start
    pos = pos + int(finish - start, i8)
  end subroutine scan_int

  subroutine scan_real(buf, pos, value, ok)
    !! Read a real number at buf(pos:) (strtod: correctly rounded, accepts
    !! 1.5, -2e-3, inf, nan, ...); pos moves past it. ok is false when no
    !! number was found. buf must contain a NUL character after the text.
    character(len=1), intent(in), target, contiguous :: buf(:)
    integer(i8), intent(inout) :: pos
    real(wp), intent(out) :: value
    logical, intent(out) :: ok
    type(c_ptr) :: endptr
    integer(c_intptr_t) :: start, finish
    value = 0.0_wp
    ok = .false.
    if (pos < 1 .or. pos > size(buf, kind=i8)) return
    value = real(c_strtod(buf(pos:), endptr), wp)
    if (.not. c_associated(endptr)) return
    start = transfer(c_loc(buf(pos)), start)
    finish = transfer(endptr, finish)
    ok = finish > start
    pos = pos + int(finish - start, i8)
  end subroutine scan_real
end module superjoin_utils_posix
