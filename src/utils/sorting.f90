module superjoin_utils_sorting
  !! Sorting and searching: one stable index sort and one binary search for
  !! integer (default and i8) and real keys, so that integer keys are
  !! compared as integers (a conversion to real is inexact above 2**53).
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  public :: sort_index, find_sorted, sort_unique_i8

  interface sort_index
    !! Stable ascending index sort: call sort_index(key, order) reorders the
    !! indices `order` so that key(order) ascends, ties in their order.
     module procedure sort_index_int, sort_index_i8, sort_index_real
  end interface sort_index

  interface find_sorted
    !! find_sorted(keys, order, key): an index i with keys(i) == key, where
    !! keys(order) ascends, or 0.
     module procedure find_sorted_int, find_sorted_i8
  end interface find_sorted

contains

#define SORT_NAME sort_index_int
#define SORT_TYPE integer
#define SORT_INTEGER
#include "sort_index_template.inc"

#define SORT_NAME sort_index_i8
#define SORT_TYPE integer(i8)
#define SORT_INTEGER
#include "sort_index_template.inc"

#define SORT_NAME sort_index_real
#define SORT_TYPE real(wp)
#include "sort_index_template.inc"

#define FIND_NAME find_sorted_int
#define FIND_TYPE integer
#include "find_sorted_template.inc"

#define FIND_NAME find_sorted_i8
#define FIND_TYPE integer(i8)
#include "find_sorted_template.inc"

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
