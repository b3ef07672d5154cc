module superjoin_assembly_scatter_map
  !! Where each item's entries go in the values of K_red: for every item of the
  !! assembly (its sorted reduced columns c(1..nc)) and every pair a <= b, the
  !! offset of row c(a) in column c(b) of the upper-triangle CSC pattern,
  !! computed once from the pattern and the items of each column (one pass
  !! over the columns with a dense row-to-offset table), so the values pass
  !! adds without a search. The item scatter applies the map of reduced
  !! columns M of the item's physical DOFs as a sparse matrix; it sums every
  !! entry's terms in the order of the dense product Mᵀ (ke M), skipping only
  !! terms that are exactly zero, so the values are the same to the bit.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_solvers_sparse, only: sparse_sym_t
  use superjoin_assembly_transform, only: transform_t
  use superjoin_assembly_column_terms, only: locate
  use superjoin_utils_memory, only: out_of_memory, BYTES_INT, BYTES_I8
  use superjoin_utils_huge_pages, only: advise_huge
  implicit none (type, external)
  private

  type, public :: scatter_map_t
    !! Offsets of every item's upper-triangle entries (b = 1..nc, a = 1..b,
    !! packed by columns from start(it) + 1) within their columns of K.
     integer(i8), allocatable :: start(:)     !! (items + 1)
     integer, allocatable :: off(:)           !! offset from k%colptr(column)
  end type scatter_map_t

  public :: build_scatter_map, scatter_item

contains

  subroutine build_scatter_map(k, item_ptr, item_col, col_ptr, col_item, mapped, map, error)
    !! The scatter map of the items (item_col(item_ptr(it):item_ptr(it+1)-1):
    !! sorted columns of item it; col_item(col_ptr(j):col_ptr(j+1)-1): the
    !! items of column j) in the pattern of k; an item not mapped(it) (a
    !! superelement, scattered entry by entry) gets no offsets.
    type(sparse_sym_t), intent(in) :: k
    integer(i8), intent(in) :: item_ptr(:), item_col(:), col_ptr(:), col_item(:)
    logical, intent(in) :: mapped(:)
    type(scatter_map_t), intent(out) :: map
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: where(:)
    integer(i8) :: nitem, it, j, p, q, nc, base, f
    integer :: a, b, stat
    nitem = size(item_ptr, kind=i8) - 1
    allocate (map%start(nitem + 1), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the scatter map', (nitem + 1)*BYTES_I8)
       return
    end if
    map%start(1) = 0
    do it = 1, nitem
       nc = merge(item_ptr(it + 1) - item_ptr(it), 0_i8, mapped(it))
       map%start(it + 1) = map%start(it) + nc*(nc + 1)/2
    end do
    allocate (map%off(max(1_i8, map%start(nitem + 1))), where(k%n), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the scatter map', map%start(nitem + 1)*BYTES_INT + k%n*BYTES_INT)
       return
    end if
    call advise_huge(map%off)
    do j = 1, k%n
       do p = k%colptr(j), k%colptr(j + 1) - 1
          where(k%rowind(p)) = int(p - k%colptr(j))
       end do
       do q = col_ptr(j), col_ptr(j + 1) - 1
          it = col_item(q)
          if (.not. mapped(it)) cycle
          f = item_ptr(it)
          b = locate(item_col(f:item_ptr(it + 1) - 1), j)
          base = map%start(it) + (b*(b - 1_i8))/2
          do a = 1, b
             map%off(base + a) = where(item_col(f + a - 1))
          end do
       end do
    end do
  end subroutine build_scatter_map

  subroutine scatter_item(tr, pd, ke, cols, it, map, k, f_u0)
    !! Add Mᵀ ke M to k over the item's columns cols (item it), and
    !! -Mᵀ ke u0 to f_u0 (M: the reduced columns of the physical DOFs pd).
    type(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: pd(:)
    real(wp), intent(in) :: ke(:, :)
    integer(i8), intent(in) :: cols(:)
    integer(i8), intent(in) :: it   !! the item's number
    type(scatter_map_t), intent(in) :: map
    type(sparse_sym_t), intent(inout) :: k
    real(wp), intent(inout) :: f_u0(:)
    real(wp) :: m(size(pd), size(cols)), u0e(size(pd))
    integer :: idx(size(pd)), row(size(pd))
    integer :: n, nc, a, b, nmax
    logical :: simple

    n = size(pd)
    nc = size(cols)
    nmax = max(1, nc)   ! the map of each DOF is among the item's columns
    call fill_m(nmax)
    if (simple) then
       ! Every DOF is its own column: ke's entries go straight in.
       row(idx) = [(a, a = 1, n)]
       call scatter_picked(ke, row, cols, it, map, k)
       return
    end if
    call scatter_general(ke, m, cols, it, map, k)
    if (any(u0e /= 0.0_wp)) call add_prescribed(ke, m, u0e, cols, f_u0)
  contains
    subroutine fill_m(nmax)
      !! m (the item's M), u0e, idx (the column of each DOF) and simple (every
      !! DOF its own column with coefficient 1 and no prescribed part).
      integer, intent(in) :: nmax
      integer(i8) :: col(nmax)
      real(wp) :: coef(nmax)
      integer :: l, nm
      simple = nc == n
      m = 0.0_wp
      do a = 1, n
         call tr%columns_of(pd(a), col, coef, nm)
         u0e(a) = tr%prescribed(pd(a))
         if (nm /= 1 .or. u0e(a) /= 0.0_wp) simple = .false.
         do l = 1, nm
            b = 1          ! a short list: a linear scan beats a search call
            do while (cols(b) /= col(l))
               b = b + 1
            end do
            idx(a) = b
            if (coef(l) /= 1.0_wp) simple = .false.
            m(a, b) = m(a, b) + coef(l)
         end do
      end do
    end subroutine fill_m
  end subroutine scatter_item

  subroutine scatter_general(ke, m, cols, it, map, k)
    !! Add Mᵀ ke M (upper triangle) to k: km = ke M, then Mᵀ km, each sum in
    !! increasing index order over the nonzero terms of M only (the terms left
    !! out are exact zeros, so every sum is that of the dense product). Where
    !! every column of M holds one 1 (the usual Δu transform: a slave DOF on
    !! its master's column and its own Δu column), entry (a, b) is ke's entry
    !! of those rows, the same number (scatter_picked).
    real(wp), intent(in) :: ke(:, :), m(:, :)
    integer(i8), intent(in) :: cols(:)
    integer(i8), intent(in) :: it   !! the item's number
    type(scatter_map_t), intent(in) :: map
    type(sparse_sym_t), intent(inout) :: k
    real(wp) :: km(size(m, 1), size(m, 2)), kab
    integer :: rows(size(m, 1), size(m, 2)), nrow(size(m, 2))
    integer :: n, nc, a, b, i, r
    integer(i8) :: pos, cb, mb
    logical :: picked
    n = size(m, 1)
    nc = size(m, 2)
    picked = .true.
    do b = 1, nc
       nrow(b) = 0
       do i = 1, n
          if (m(i, b) == 0.0_wp) cycle
          nrow(b) = nrow(b) + 1
          rows(nrow(b), b) = i
       end do
       picked = picked .and. nrow(b) == 1
       if (picked) picked = m(rows(1, b), b) == 1.0_wp
    end do
    if (picked) then
       call scatter_picked(ke, rows(1, :), cols, it, map, k)
       return
    end if
    do b = 1, nc
       km(:, b) = 0.0_wp
       do r = 1, nrow(b)
          km(:, b) = km(:, b) + ke(:, rows(r, b))*m(rows(r, b), b)
       end do
    end do
    do b = 1, nc
       cb = k%colptr(cols(b))
       mb = map%start(it) + (b*(b - 1_i8))/2
       do a = 1, b
          kab = 0.0_wp
          do r = 1, nrow(a)
             i = rows(r, a)
             kab = kab + m(i, a)*km(i, b)
          end do
          pos = cb + map%off(mb + a)
          k%val(pos) = k%val(pos) + kab
       end do
    end do
  end subroutine scatter_general

  subroutine scatter_picked(ke, row, cols, it, map, k)
    !! Add Mᵀ ke M (upper triangle) to k where column b of M is the unit vector
    !! of DOF row(b): entry (a, b) is ke(row(a), row(b)) (also an item whose
    !! every DOF is its own column, scatter_item's simple case). scatter_general's
    !! sum 0 + 1·(ke(row(a), row(b))·1) is the same number (a -0 entry gives
    !! +0 there and -0 here, which k's sum, started at +0, turns to +0 alike).
    real(wp), intent(in) :: ke(:, :)
    integer, intent(in) :: row(:)
    integer(i8), intent(in) :: cols(:)
    integer(i8), intent(in) :: it   !! the item's number
    type(scatter_map_t), intent(in) :: map
    type(sparse_sym_t), intent(inout) :: k
    integer :: a, b
    integer(i8) :: pos, cb, mb
    do b = 1, size(row)
       cb = k%colptr(cols(b))
       mb = map%start(it) + (b*(b - 1_i8))/2
       do a = 1, b
          pos = cb + map%off(mb + a)
          k%val(pos) = k%val(pos) + ke(row(a), row(b))
       end do
    end do
  end subroutine scatter_picked

  subroutine add_prescribed(ke, m, u0e, cols, f_u0)
    !! f_u0(cols) -= Mᵀ ke u0e (the load of the prescribed values).
    real(wp), intent(in) :: ke(:, :), m(:, :), u0e(:)
    integer(i8), intent(in) :: cols(:)
    real(wp), intent(inout) :: f_u0(:)
    real(wp) :: fe(size(cols))
    integer :: a
    fe = matmul(transpose(m), matmul(ke, u0e))
    do a = 1, size(cols)
       f_u0(cols(a)) = f_u0(cols(a)) - fe(a)
    end do
  end subroutine add_prescribed
end module superjoin_assembly_scatter_map
