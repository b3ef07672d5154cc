module superjoin_utils_union_find
  !! Disjoint sets over 0..n stored as a parent array.
  use superjoin_kinds, only: i8
  implicit none (type, external)
  private

  public :: find_root

contains

  function find_root(parent, v) result(r)
    !! Root of v's set, halving the path on the way.
    integer(i8), intent(inout) :: parent(0:)
    integer(i8), intent(in) :: v
    integer(i8) :: r
    r = v
    do while (parent(r) /= r)
       parent(r) = parent(parent(r))
       r = parent(r)
    end do
  end function find_root
end module superjoin_utils_union_find
