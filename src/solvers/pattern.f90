module superjoin_solvers_pattern
  !! Sparsity patterns of symmetric matrices assembled from items (elements,
  !! springs, superelements): the upper-triangle CSC pattern, and the position
  !! of an entry in it.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL, BYTES_I8
  use superjoin_utils_huge_pages, only: advise_huge
  implicit none (type, external)
  private

  public :: build_pattern, find_entry, items_of_columns, zero_values

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
    call advise_huge(col_item)
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

  subroutine build_pattern(ncol, item_ptr, item_col, col_ptr, col_item, k, error, values)
    !! Pattern of the upper triangle from items (elements, springs) and their
    !! columns: column j holds every column i <= j that shares an item with it,
    !! and always j itself. item_col(item_ptr(it):item_ptr(it+1)-1) are the
    !! sorted columns of item it; col_item(col_ptr(j):col_ptr(j+1)-1) the items
    !! of column j. Values are zero. Two passes over the items of each column,
    !! no intermediate copy: the first counts the rows of each column, the
    !! second writes row i into the columns j > i that share an item with it,
    !! i increasing, so each column's rows come out sorted with the diagonal
    !! last. values = .false.: k%val is left unallocated (zero_values later:
    !! the analysis of the pattern need not wait for nnz zeros).
    integer(i8), intent(in) :: ncol
    integer(i8), intent(in) :: item_ptr(:), item_col(:), col_ptr(:), col_item(:)
    type(sparse_sym_t), intent(out) :: k
    type(error_t), allocatable, intent(out) :: error
    logical, intent(in), optional :: values
    integer(i8), allocatable :: mark(:), fill(:)
    integer(i8) :: i, j, it, pos, q, nnz
    integer :: stat

    k%n = ncol
    allocate (mark(ncol), source=0_i8, stat=stat)
    if (stat == 0) allocate (k%colptr(ncol + 1), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the matrix pattern', (2*ncol + 1)*BYTES_I8)
       return
    end if
    ! Rows of column j: j and the distinct i < j sharing an item with it.
    k%colptr(1) = 1
    do j = 1, ncol
       nnz = 1
       mark(j) = j
       do q = col_ptr(j), col_ptr(j + 1) - 1
          it = col_item(q)
          do pos = item_ptr(it), item_ptr(it + 1) - 1
             i = item_col(pos)
             if (i >= j) exit          ! item columns are sorted
             if (mark(i) == j) cycle
             mark(i) = j
             nnz = nnz + 1
          end do
       end do
       k%colptr(j + 1) = k%colptr(j) + nnz
    end do
    nnz = k%colptr(ncol + 1) - 1

    allocate (k%rowind(nnz), fill(ncol), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the stiffness matrix ('//itoa(nnz)//' nonzeros)', &
            (2*ncol + 1 + nnz)*BYTES_I8 + nnz*BYTES_REAL)
       return
    end if
    call advise_huge(k%rowind)
    if (.not. present(values)) then
       call zero_values(k, error)
    else if (values) then
       call zero_values(k, error)
    end if
    if (allocated(error)) return
    ! Row i into column i (its last row) and into each column j > i it shares an item with.
    fill(:) = k%colptr(1:ncol)   ! allocated above with stat= (an assignment's allocation is not checked)
    mark(:) = 0
    do i = 1, ncol
       k%rowind(fill(i)) = i
       mark(i) = i
       do q = col_ptr(i), col_ptr(i + 1) - 1
          it = col_item(q)
          do pos = item_ptr(it + 1) - 1, item_ptr(it), -1
             j = item_col(pos)
             if (j <= i) exit          ! item columns are sorted
             if (mark(j) == i) cycle
             mark(j) = i
             k%rowind(fill(j)) = i
             fill(j) = fill(j) + 1
          end do
       end do
    end do
  end subroutine build_pattern

  subroutine zero_values(k, error)
    !! The values of pattern k, all zero.
    type(sparse_sym_t), intent(inout) :: k
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: nnz
    integer :: stat
    nnz = k%colptr(k%n + 1) - 1
    allocate (k%val(nnz), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the stiffness matrix ('//itoa(nnz)//' nonzeros)', nnz*BYTES_REAL)
       return
    end if
    call advise_huge(k%val)
    k%val(:) = 0.0_wp
  end subroutine zero_values

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
