module superjoin_kinds
  !! Numeric kinds used throughout superjoin.
  use, intrinsic :: iso_fortran_env, only: real64, int32, int64
  implicit none (type, external)
  private

  integer, parameter, public :: wp = real64   !! working precision
  integer, parameter, public :: ip = int32    !! local ids and indices inside one substructure
  integer, parameter, public :: i8 = int64    !! global equation numbers, nonzero counts
end module superjoin_kinds
