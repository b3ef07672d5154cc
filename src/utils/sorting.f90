module superjoin_utils_sorting
  !! Sorting helpers.
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  public :: stable_argsort, sort_unique_i8

contains

  subroutine stable_argsort(key, order)
    !! Reorder the indices `order` so that key(order) ascends; equal keys keep
    !! their relative order (merge sort, deterministic).
    real(wp), intent(in) :: key(:)
    integer, intent(inout) :: order(:)
    integer, allocatable :: tmp(:)
    integer :: width, lo, mid, hi, i, j, k, n
    n = size(order)
    allocate (tmp(n))
    width = 1
    do while (width < n)
       lo = 1
       do while (lo <= n)
          mid = min(lo + width - 1, n)
          hi = min(lo + 2*width - 1, n)
          i = lo; j = mid + 1; k = lo
          do while (i <= mid .and. j <= hi)
             if (key(order(j)) < key(order(i))) then
                tmp(k) = order(j); j = j + 1
             else
                tmp(k) = order(i); i = i + 1
             end if
             k = k + 1
          end do
          tmp(k:k + mid - i) = order(i:mid)
          k = k + mid - i + 1
          tmp(k:k + hi - j) = order(j:hi)
          lo = hi + 1
       end do
       order = tmp
       width = 2*width
    end do
  end subroutine stable_argsort

  pure subroutine sort_unique_i8(a, n)
    !! Sort a short integer list in place (insertion sort) and drop repeats;
    !! n returns the number of distinct entries, kept in a(1:n).
    integer(i8), intent(inout) :: a(:)
    integer, intent(out) :: n
    integer :: i, j
    integer(i8) :: t
    do i = 2, size(a)
       t = a(i)
       j = i - 1
       do while (j >= 1)
          if (a(j) <= t) exit
          a(j + 1) = a(j)
          j = j - 1
       end do
       a(j + 1) = t
    end do
    n = 0
    do i = 1, size(a)
       if (n > 0) then
          if (a(i) == a(n)) cycle
       end if
       n = n + 1
       a(n) = a(i)
    end do
  end subroutine sort_unique_i8
end module superjoin_utils_sorting
