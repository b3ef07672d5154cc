module superjoin_utils_grow
  !! `grow(a, n, initial)`: the growing-array idiom (allocate, double when full,
  !! keep the first n elements) for the intrinsic element types. Derived types
  !! instantiate the same template (grow_template.inc) in their own module and
  !! add it to their module's `grow` generic.
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  public :: grow

  interface grow
     !! Make room for element n + 1 of an allocatable array.
     module procedure grow_int, grow_i8, grow_real, grow_logical
  end interface grow

contains

#define GROW_NAME grow_int
#define GROW_TYPE integer
#include "grow_template.inc"

#define GROW_NAME grow_i8
#define GROW_TYPE integer(i8)
#include "grow_template.inc"

#define GROW_NAME grow_real
#define GROW_TYPE real(wp)
#include "grow_template.inc"

#define GROW_NAME grow_logical
#define GROW_TYPE logical
#include "grow_template.inc"

end module superjoin_utils_grow
