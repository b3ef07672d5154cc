program test_sorting
  !! Unit tests of the sorting and searching helpers (superjoin_utils_sorting)
  !! and of the lower-case conversion (superjoin_utils_strings); the growing
  !! array (superjoin_utils_grow) and the id lookups of a substructure
  !! (find_node, find_elem).
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_utils_grow, only: grow
  use superjoin_model_types, only: substructure_t, find_node, find_elem
  use superjoin_utils_sorting, only: sort_index, find_sorted, sort_unique_i8
  use superjoin_utils_strings, only: to_lower, to_upper
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  call integer_keys()
  call large_keys()
  call real_keys()
  call passes()
  call searches()
  call unique()
  call lower_case()
  call growing()
  call id_lookups()
  call finish()

contains

  subroutine integer_keys()
    integer :: order(8), one(1), none(0)
    integer :: i
    order = [(i, i = 1, 8)]
    call sort_index([5, 3, 5, 1, 3, 9, 1, 5], order)
    call check(all(order == [4, 7, 2, 5, 1, 3, 8, 6]), 'default integers: ascending, ties in input order')
    order = [8, 7, 6, 5, 4, 3, 2, 1]
    call sort_index([5, 3, 5, 1, 3, 9, 1, 5], order)
    call check(all(order == [7, 4, 5, 2, 8, 3, 1, 6]), 'ties keep the order given, not the index order')
    order = [3, 2, 1, 4, 5, 6, 7, 8]
    call sort_index([2, 1, 1, 3, 4, 4, 5, 6], order)
    call check(all(order == [3, 2, 1, 4, 5, 6, 7, 8]), 'keys already ascending along order: nothing moves')
    order = [(i, i = 1, 8)]
    call sort_index([1, 2, 3, 4, 5, 6, 8, 7], order)
    call check(all(order == [1, 2, 3, 4, 5, 6, 8, 7]), 'one pair out of order at the end: sorted')
    call sort_index([integer ::], none)
    call check(size(none) == 0, 'empty list')
    one = 1
    call sort_index([42], one)
    call check(all(one == [1]), 'one entry')
  end subroutine integer_keys

  subroutine large_keys()
    !! Keys above 2**53 that a conversion to real would make equal.
    integer(i8), parameter :: BIG = 2_i8**53
    integer :: order(4), three(3)
    order = [1, 2, 3, 4]
    call sort_index([BIG + 3, BIG + 1, BIG + 2, BIG], order)
    call check(all(order == [4, 2, 3, 1]), 'i8 keys above 2**53 ordered exactly')
    call check(find_sorted([BIG + 3, BIG + 1, BIG + 2, BIG], order, BIG + 1) == 2, 'i8 key above 2**53 found')
    call check(find_sorted([BIG + 3, BIG + 1, BIG + 2, BIG], order, BIG + 5) == 0, 'i8 key above 2**53 absent')
    three = [1, 2, 3]
    call sort_index([-huge(1_i8), huge(1_i8), 0_i8], three)
    call check(all(three == [1, 3, 2]), 'i8 extremes')
  end subroutine large_keys

  subroutine real_keys()
    integer :: order(6), three(3), two(2)
    integer :: i
    order = [(i, i = 1, 6)]
    call sort_index([2.5_wp, -1.0_wp, 2.5_wp, 0.0_wp, -1.0_wp, 1.0e300_wp], order)
    call check(all(order == [2, 5, 4, 1, 3, 6]), 'reals: ascending, ties in input order')
    three = [(i, i = 1, 3)]
    call sort_index(-[1.0_wp, 3.0_wp, 2.0_wp], three)
    call check(all(three == [2, 3, 1]), 'descending through negated keys')
    two = [1, 3]
    call sort_index([9.0_wp, 0.0_wp, 1.0_wp], two)
    call check(all(two == [3, 1]), 'a subset of the indices')
  end subroutine real_keys

  subroutine passes()
    !! Stable passes, last key first: the lexicographic order of (a, b).
    integer, parameter :: A(7) = [2, 1, 2, 1, 3, 1, 2], B(7) = [1, 2, 1, 1, 0, 2, 0]
    integer :: order(7)
    integer :: i
    order = [(i, i = 1, 7)]
    call sort_index(B, order)
    call sort_index(A, order)
    call check(all(order == [4, 2, 6, 7, 1, 3, 5]), 'two stable passes: lexicographic order, ties in input order')
  end subroutine passes

  subroutine searches()
    integer, parameter :: IDS(6) = [40, 10, 30, 20, 60, 50]
    integer :: order(6), none(0)
    integer :: i
    logical :: ok
    order = [(i, i = 1, 6)]
    call sort_index(IDS, order)
    ok = .true.
    do i = 1, 6
       ok = ok .and. find_sorted(IDS, order, IDS(i)) == i
    end do
    call check(ok, 'every key found at its index')
    call check(find_sorted(IDS, order, 5) == 0, 'below the smallest: absent')
    call check(find_sorted(IDS, order, 35) == 0, 'between two keys: absent')
    call check(find_sorted(IDS, order, 70) == 0, 'above the largest: absent')
    call check(find_sorted([integer ::], none, 1) == 0, 'empty list: absent')
  end subroutine searches

  subroutine unique()
    integer(i8) :: a(6)
    integer :: n
    a = [5_i8, 2_i8, 5_i8, 7_i8, 2_i8, 1_i8]
    call sort_unique_i8(a, n)
    call check(n == 4, 'distinct entries counted')
    call check(all(a(1:n) == [1_i8, 2_i8, 5_i8, 7_i8]), 'distinct entries sorted')
  end subroutine unique

  subroutine lower_case()
    call check(to_lower('CHOLMOD') == 'cholmod', 'upper case letters lowered')
    call check(to_lower('MuMpS-LdLt 1_Z@[') == 'mumps-ldlt 1_z@[', 'other characters kept')
    call check(len(to_lower('AB  ')) == 4, 'length kept')
    call check(to_upper('cholmod') == 'CHOLMOD', 'lower case letters raised')
    call check(to_upper('MuMpS-LdLt 1_z@`{') == 'MUMPS-LDLT 1_Z@`{', 'other characters kept by to_upper')
  end subroutine lower_case
  subroutine growing()
    integer, allocatable :: a(:)
    integer :: i, stat
    allocate (a(16))
    a(1:10) = [(i, i = 1, 10)]
    call grow(a, 10, 16, more=100)
    call check(size(a) == 110 .and. all(a(1:10) == [(i, i = 1, 10)]), &
         'grow, more=100: room for n + more at once, the first n kept')
    call grow(a, 10, 16, more=100)
    call check(size(a) == 110, 'grow, more: the room is there already, nothing reallocated')
    call grow(a, 110, 16)
    call check(size(a) == 220 .and. all(a(1:10) == [(i, i = 1, 10)]), 'grow without more: doubled as before')
    deallocate (a)
    call grow(a, 0, 16, more=50)
    call check(size(a) == 50, 'grow, more: an absent array gets n + more slots')
    deallocate (a)
    call grow(a, 0, 16, more=3)
    call check(size(a) == 16, 'grow, more: never below the initial size')
    a(:) = 7
    call grow(a, 16, 16, stat, more=40)
    call check(stat == 0 .and. size(a) == 56 .and. all(a(1:16) == 7), &
         'grow, more: n + more when that beats doubling (stat 0)')
  end subroutine growing

  subroutine id_lookups()
    type(substructure_t) :: sub
    integer(ip) :: i
    sub%node_id = [1_ip, 5_ip, 3_ip, 2_ip]
    sub%node_order = [(i, i = 1_ip, 4_ip)]
    call sort_index(sub%node_id, sub%node_order)
    call check(find_node(sub, 1_ip) == 1 .and. find_node(sub, 3_ip) == 3, &
         'find_node: ids at their own place')
    call check(find_node(sub, 2_ip) == 4, 'find_node: id 2 is not entry 2 (which holds 5): found by the search')
    call check(find_node(sub, 5_ip) == 2, 'find_node: id beyond the count found by the search')
    call check(find_node(sub, 4_ip) == 0 .and. find_node(sub, 0_ip) == 0 .and. find_node(sub, -3_ip) == 0, &
         'find_node: absent ids (4, 0, -3)')
    sub%elem_id = [2_ip, 1_ip]
    sub%elem_order = [1_ip, 2_ip]
    call sort_index(sub%elem_id, sub%elem_order)
    call check(find_elem(sub, 1_ip) == 2 .and. find_elem(sub, 2_ip) == 1, 'find_elem: swapped ids found by the search')
  end subroutine id_lookups

end program test_sorting
