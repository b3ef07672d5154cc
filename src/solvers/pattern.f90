module superjoin_solvers_pattern
  !! Sparsity patterns of symmetric matrices assembled from items (elements,
  !! springs, superelements): the upper-triangle CSC pattern, and the position
  !! of an entry in it.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL, BYTES_I8
  implicit none (type, external)
  private

  public :: build_pattern, find_entry, items_of_columns

contains

  subroutine items_of_columns(ncol, item_ptr, item_col, col_ptr, col_item, error)
    !! Transpose of the item lists: the items of each column.
    integer(i8), intent(in) :: ncol
    integer(i8), intent(in) :: item_ptr(:), item_col(:)
    integer(i8), allocatable, intent(out) :: col_ptr(:), col_item(:)
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: nitem, s_total, pos, j, it
    integer(i8), allocatable :: fill(:)
    integer :: stat
    nitem = size(item_ptr, kind=i8) - 1
    s_total = item_ptr(nitem + 1) - 1
    allocate (col_ptr(ncol + 1), source=0_i8, stat=stat)
    if (stat == 0) allocate (col_item(max(s_total, 1_i8)), fill(ncol), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the item lists of the columns', (2*ncol + 1 + s_total)*BYTES_I8)
       return
    end if
    do pos = 1, s_total
       col_ptr(item_col(pos) + 1) = col_ptr(item_col(pos) + 1) + 1
    end do
    col_ptr(1) = 1
    do j = 1, ncol
       col_ptr(j + 1) = col_ptr(j + 1) + col_ptr(j)
    end do
    fill(:) = col_ptr(1:ncol)   ! allocated above with stat= (an assignment's allocation is not checked)
    do it = 1, nitem
       do pos = item_ptr(it), item_ptr(it + 1) - 1
          j = item_col(pos)
          col_item(fill(j)) = it
          fill(j) = fill(j) + 1
       end do
    end do
  end subroutine items_of_columns

  subroutine build_pattern(ncol, item_ptr, item_col, col_ptr, col_item, k, error)
    !! Pattern of the upper triangle from items (elements, springs) and their
    !! columns: column j holds every column i <= j that shares an item with it,
    !! and always j itself. item_col(item_ptr(it):item_ptr(it+1)-1) are the
    !! sorted columns of item it; col_item(col_ptr(j):col_ptr(j+1)-1) the items
    !! of column j. Values are zero. Built as the lower pattern
    !! row by row (unsorted), whose transpose comes out sorted by construction.
    integer(i8), intent(in) :: ncol
    integer(i8), intent(in) :: item_ptr(:), item_col(:), col_ptr(:), col_item(:)
    type(sparse_sym_t), intent(out) :: k
    type(error_t), allocatable, intent(out) :: error
    integer(i8), allocatable :: mark(:), low_ptr(:), low_col(:), tmp(:), fill(:)
    integer(i8) :: i, j, it, pos, q, cap, nnz
    integer :: stat

    ! Lower pattern: for each i, the columns j >= i sharing an item with i.
    cap = max(16_i8, 4*size(item_col, kind=i8))
    allocate (mark(ncol), source=0_i8, stat=stat)
    if (stat == 0) allocate (low_ptr(ncol + 1), low_col(cap), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the matrix pattern', (2*ncol + 1 + cap)*BYTES_I8)
       return
    end if
    nnz = 0
    low_ptr(1) = 1
    do i = 1, ncol
       if (nnz + 1 > cap) call grow(low_col, cap, nnz + 1)
       if (allocated(error)) return
       nnz = nnz + 1
       low_col(nnz) = i
       mark(i) = i
       do q = col_ptr(i), col_ptr(i + 1) - 1
          it = col_item(q)
          do pos = item_ptr(it + 1) - 1, item_ptr(it), -1
             j = item_col(pos)
             if (j <= i) exit          ! item columns are sorted
             if (mark(j) == i) cycle
             mark(j) = i
             if (nnz + 1 > cap) call grow(low_col, cap, nnz + 1)
             if (allocated(error)) return
             nnz = nnz + 1
             low_col(nnz) = j
          end do
       end do
       low_ptr(i + 1) = nnz + 1
    end do
    deallocate (mark)

    ! Transpose: rows of each column arrive in increasing order, the diagonal last.
    k%n = ncol
    allocate (k%colptr(ncol + 1), source=0_i8, stat=stat)
    if (stat == 0) allocate (k%rowind(nnz), fill(ncol), stat=stat)
    if (stat == 0) allocate (k%val(nnz), source=0.0_wp, stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the stiffness matrix ('//itoa(nnz)//' nonzeros)', &
            (2*ncol + 1 + nnz)*BYTES_I8 + nnz*BYTES_REAL)
       return
    end if
    do pos = 1, nnz
       k%colptr(low_col(pos) + 1) = k%colptr(low_col(pos) + 1) + 1
    end do
    k%colptr(1) = 1
    do j = 1, ncol
       k%colptr(j + 1) = k%colptr(j + 1) + k%colptr(j)
    end do
    fill = k%colptr(1:ncol)
    do i = 1, ncol
       do pos = low_ptr(i), low_ptr(i + 1) - 1
          j = low_col(pos)
          k%rowind(fill(j)) = i
          fill(j) = fill(j) + 1
       end do
    end do
  contains
    subroutine grow(a, cap, need)
      integer(i8), allocatable, intent(inout) :: a(:)
      integer(i8), intent(inout) :: cap
      integer(i8), intent(in) :: need
      cap = max(2*cap, need)
      allocate (tmp(cap), stat=stat)
      if (stat /= 0) then
         call out_of_memory(error, 'the matrix pattern', cap*BYTES_I8)
         return
      end if
      tmp(1:size(a, kind=i8)) = a
      call move_alloc(tmp, a)
    end subroutine grow
  end subroutine build_pattern

  pure function find_entry(k, i, j) result(pos)
    !! Position of row i in column j of k (0 when not in the pattern).
    type(sparse_sym_t), intent(in) :: k
    integer(i8), intent(in) :: i, j
    integer(i8) :: pos, lo, hi
    lo = k%colptr(j)
    hi = k%colptr(j + 1) - 1
    do while (lo <= hi)
       pos = lo + (hi - lo)/2
       if (k%rowind(pos) == i) return
       if (k%rowind(pos) < i) then
          lo = pos + 1
       else
          hi = pos - 1
       end if
    end do
    pos = 0
  end function find_entry
end module superjoin_solvers_pattern
