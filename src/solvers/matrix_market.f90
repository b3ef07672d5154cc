module superjoin_solvers_matrix_market
  !! Matrix Market files for symmetric sparse matrices ("coordinate real
  !! symmetric": the lower triangle, 1-based, one entry per line).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_utils_posix, only: rename_file, remove_file, scan_int, scan_real
  use superjoin_utils_text_buffer, only: check_file_size
  use superjoin_utils_strings, only: to_lower
  implicit none (type, external)
  private

  public :: write_matrix_market, read_matrix_market, assemble_upper

  character(*), parameter :: MM_BANNER = '%%MatrixMarket'
  character(*), parameter :: MM_HEADER = '%%MatrixMarket matrix coordinate real symmetric'
  character(*), parameter :: ENTRY_FMT = '(i0,1x,i0,1x,es24.16e3)'   !! 17 significant digits
  character(*), parameter :: TMP_SUFFIX = '.tmp'
  integer, parameter :: LF = 10, CR = 13                             !! line-end characters

contains

  subroutine write_matrix_market(path, a, error)
    !! Write the symmetric matrix a (upper-triangle storage) to path as a Matrix
    !! Market "coordinate real symmetric" file: entries (row >= col) with 17
    !! significant digits. The file is written to path//'.tmp' and renamed to
    !! path on success, so path is never left half written. IO errors:
    !! EXIT_IO with the path in the message.
    character(*), intent(in) :: path
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer :: unit, ios
    integer(i8) :: j, k, expected
    character(len=256) :: msg
    character(:), allocatable :: tmp
    logical :: failed

    tmp = path//TMP_SUFFIX
    open (newunit=unit, file=tmp, status='replace', action='write', form='formatted', &
         iostat=ios, iomsg=msg)
    if (ios /= 0) then
       call fatal_error(error, EXIT_IO, "cannot open '"//tmp//"' for writing: "//trim(msg))
       return
    end if
    write (unit, '(a)', iostat=ios, iomsg=msg) MM_HEADER
    if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) '% written by superjoin (lower triangle)'
    if (ios == 0) write (unit, '(i0,1x,i0,1x,i0)', iostat=ios, iomsg=msg) a%n, a%n, a%nnz()
    if (ios == 0) then
       entries: do j = 1, a%n
          do k = a%colptr(j), a%colptr(j + 1) - 1
             ! upper entry (i, j), i <= j, is the lower entry (j, i)
             write (unit, ENTRY_FMT, iostat=ios, iomsg=msg) j, a%rowind(k), a%val(k)
             if (ios /= 0) exit entries
          end do
       end do entries
    end if
    if (ios /= 0) then
       close (unit, status='delete', iostat=ios)
       call fatal_error(error, EXIT_IO, "error writing '"//tmp//"': "//trim(msg))
       return
    end if
    ! the I/O library may drop the error of its final flush: compare sizes
    inquire (unit=unit, size=expected)
    close (unit, iostat=ios, iomsg=msg)
    if (ios == 0) then
       call check_file_size(tmp, expected, failed, msg)
       if (failed) ios = -1
    end if
    if (ios /= 0) then
       call remove_file(tmp)
       call fatal_error(error, EXIT_IO, "error closing '"//tmp//"': "//trim(msg))
       return
    end if
    call rename_file(tmp, path, error)
    if (allocated(error)) then
       call remove_file(tmp)
       error%message = "cannot write '"//path//"': "//error%message
    end if
  end subroutine write_matrix_market

  subroutine read_matrix_market(path, a, error)
    !! Read a Matrix Market "coordinate real|integer symmetric" file into a
    !! (upper-triangle CSC, rows sorted, duplicates summed, missing diagonal
    !! entries stored as zeros). Entries may be given in either triangle.
    !! Errors (missing file, bad header, malformed or out-of-range entries):
    !! EXIT_IO with the path in the message.
    character(*), intent(in) :: path
    type(sparse_sym_t), intent(out) :: a
    type(error_t), allocatable, intent(out) :: error
    character(len=1), allocatable, target :: buf(:)
    integer(i8) :: pos, nrow, ncol, nent, k, r, c
    integer(i8), allocatable :: rows(:), cols(:)
    real(wp), allocatable :: vals(:)
    character(:), allocatable :: line
    logical :: ok, ok2, ok3
    character(len=40) :: num

    call slurp(path, buf, error)
    if (allocated(error)) return
    pos = 1
    ! banner
    call next_line(buf, pos, line)
    if (.not. header_ok(line)) then
       call fatal_error(error, EXIT_IO, "'"//path//"': not a Matrix Market 'matrix coordinate real symmetric' file")
       return
    end if
    ! comments and blank lines, then the size line
    do
       if (pos > size(buf, kind=i8) - 1) then
          call fatal_error(error, EXIT_IO, "'"//path//"': size line missing")
          return
       end if
       if (buf(pos) == '%') then
          call next_line(buf, pos, line)
          cycle
       end if
       if (is_blank_line(buf, pos)) then
          call next_line(buf, pos, line)
          cycle
       end if
       exit
    end do
    call scan_int(buf, pos, nrow, ok)
    call scan_int(buf, pos, ncol, ok2)
    call scan_int(buf, pos, nent, ok3)
    if (.not. (ok .and. ok2 .and. ok3) .or. nrow < 0 .or. nent < 0) then
       call fatal_error(error, EXIT_IO, "'"//path//"': bad size line")
       return
    end if
    if (nrow /= ncol) then
       call fatal_error(error, EXIT_IO, "'"//path//"': a symmetric matrix must be square")
       return
    end if
    allocate (rows(nent), cols(nent), vals(nent))
    do k = 1, nent
       call scan_int(buf, pos, r, ok)
       call scan_int(buf, pos, c, ok2)
       call scan_real(buf, pos, vals(k), ok3)
       if (.not. (ok .and. ok2 .and. ok3)) then
          write (num, '(i0)') k
          call fatal_error(error, EXIT_IO, "'"//path//"': malformed or missing entry "//trim(num))
          return
       end if
       if (r < 1 .or. r > nrow .or. c < 1 .or. c > nrow) then
          write (num, '(i0)') k
          call fatal_error(error, EXIT_IO, "'"//path//"': entry "//trim(num)//" out of range")
          return
       end if
       ! upper storage: row = min, column = max
       rows(k) = min(r, c)
       cols(k) = max(r, c)
    end do
    deallocate (buf)
    call assemble_upper(nrow, rows, cols, vals, a)
  end subroutine read_matrix_market

  ! ---- helpers

  subroutine slurp(path, buf, error)
    !! The whole file as characters, followed by one NUL.
    character(*), intent(in) :: path
    character(len=1), allocatable, intent(out) :: buf(:)
    type(error_t), allocatable, intent(out) :: error
    integer :: unit, ios, stat
    integer(i8) :: fsize
    character(len=256) :: msg

    open (newunit=unit, file=path, status='old', action='read', access='stream', &
         form='unformatted', iostat=ios, iomsg=msg)
    if (ios /= 0) then
       call fatal_error(error, EXIT_IO, "cannot open '"//path//"': "//trim(msg))
       return
    end if
    inquire (unit=unit, size=fsize)
    if (fsize < 0) then
       close (unit)
       call fatal_error(error, EXIT_IO, "cannot determine the size of '"//path//"'")
       return
    end if
    allocate (buf(fsize + 1), stat=stat)
    if (stat /= 0) then
       close (unit)
       call fatal_error(error, EXIT_IO, "out of memory reading '"//path//"'")
       return
    end if
    if (fsize > 0) read (unit, iostat=ios, iomsg=msg) buf(1:fsize)
    close (unit)
    if (ios /= 0) then
       call fatal_error(error, EXIT_IO, "error reading '"//path//"': "//trim(msg))
       return
    end if
    buf(fsize + 1) = achar(0)
  end subroutine slurp

  pure subroutine next_line(buf, pos, line)
    !! The line starting at pos (without its end), and pos moved to the next line.
    character(len=1), intent(in) :: buf(:)
    integer(i8), intent(inout) :: pos
    character(:), allocatable, intent(out) :: line
    integer(i8) :: first, last, i
    first = pos
    last = size(buf, kind=i8) - 1            ! buf ends with NUL
    do i = first, last
       if (iachar(buf(i)) == LF) then
          last = i - 1
          exit
       end if
    end do
    pos = last + 2
    if (last >= first) then
       if (iachar(buf(last)) == CR) last = last - 1
    end if
    allocate (character(len=max(last - first + 1, 0_i8)) :: line)
    do i = first, last
       line(i - first + 1:i - first + 1) = buf(i)
    end do
  end subroutine next_line

  pure logical function is_blank_line(buf, pos)
    !! Whether the line starting at pos holds only blanks.
    character(len=1), intent(in) :: buf(:)
    integer(i8), intent(in) :: pos
    integer(i8) :: i
    is_blank_line = .true.
    do i = pos, size(buf, kind=i8) - 1
       if (iachar(buf(i)) == LF) return
       if (buf(i) /= ' ' .and. iachar(buf(i)) /= CR .and. iachar(buf(i)) /= 9) then
          is_blank_line = .false.
          return
       end if
    end do
  end function is_blank_line

  pure logical function header_ok(line)
    !! Banner: %%MatrixMarket matrix coordinate real|integer symmetric (any case).
    character(*), intent(in) :: line
    character(len=len(line)) :: low
    character(len=32) :: words(5)
    integer :: i, nw, first
    logical :: in_word
    low = to_lower(line)
    words = ''
    nw = 0
    in_word = .false.
    first = 1
    do i = 1, len(low) + 1
       if (i <= len(low)) then
          if (low(i:i) /= ' ' .and. iachar(low(i:i)) /= 9) then
             if (.not. in_word) first = i
             in_word = .true.
             cycle
          end if
       end if
       if (in_word) then
          nw = nw + 1
          if (nw <= size(words)) words(nw) = low(first:i - 1)
          in_word = .false.
       end if
    end do
    header_ok = nw == 5
    if (.not. header_ok) return
    header_ok = words(1) == to_lower(MM_BANNER) .and. words(2) == 'matrix' .and. &
         words(3) == 'coordinate' .and. (words(4) == 'real' .or. words(4) == 'integer') .and. &
         words(5) == 'symmetric'
  end function header_ok

  subroutine assemble_upper(n, rows, cols, vals, a)
    !! Upper CSC from coordinate triplets with rows <= cols: two stable counting
    !! sorts (by row, then by column), duplicates summed, missing diagonals added.
    integer(i8), intent(in) :: n
    integer(i8), intent(in) :: rows(:), cols(:)
    real(wp), intent(in) :: vals(:)
    type(sparse_sym_t), intent(out) :: a
    integer(i8), allocatable :: start(:), by_row(:), by_col(:)
    integer(i8) :: nent, k, e, j, i, nz, last_row, pos

    nent = size(rows, kind=i8)
    allocate (start(n + 1), by_row(nent), by_col(nent))
    ! stable counting sort by row
    start = 0
    do k = 1, nent
       start(rows(k) + 1) = start(rows(k) + 1) + 1
    end do
    start(1) = 1
    do i = 1, n
       start(i + 1) = start(i + 1) + start(i)
    end do
    do k = 1, nent
       by_row(start(rows(k))) = k
       start(rows(k)) = start(rows(k)) + 1
    end do
    ! stable counting sort by column: rows end up sorted within each column
    start = 0
    do k = 1, nent
       start(cols(k) + 1) = start(cols(k) + 1) + 1
    end do
    start(1) = 1
    do j = 1, n
       start(j + 1) = start(j + 1) + start(j)
    end do
    do k = 1, nent
       e = by_row(k)
       by_col(start(cols(e))) = e
       start(cols(e)) = start(cols(e)) + 1
    end do
    deallocate (by_row)
    ! start(j) is now the end (+1) of column j; count the merged entries
    a%n = n
    allocate (a%colptr(n + 1))
    nz = 0
    pos = 1
    do j = 1, n
       last_row = 0
       do k = pos, start(j) - 1
          i = rows(by_col(k))
          if (i /= last_row) nz = nz + 1
          last_row = i
       end do
       if (last_row /= j) nz = nz + 1      ! missing diagonal
       pos = start(j)
    end do
    allocate (a%rowind(nz), a%val(nz))
    nz = 0
    pos = 1
    a%colptr(1) = 1
    do j = 1, n
       last_row = 0
       do k = pos, start(j) - 1
          e = by_col(k)
          i = rows(e)
          if (i /= last_row) then
             nz = nz + 1
             a%rowind(nz) = i
             a%val(nz) = vals(e)
          else
             a%val(nz) = a%val(nz) + vals(e)
          end if
          last_row = i
       end do
       if (last_row /= j) then
          nz = nz + 1
          a%rowind(nz) = j
          a%val(nz) = 0.0_wp
       end if
       pos = start(j)
       a%colptr(j + 1) = nz + 1
    end do
  end subroutine assemble_upper
end module superjoin_solvers_matrix_market
