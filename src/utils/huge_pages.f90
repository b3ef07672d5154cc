module superjoin_utils_huge_pages
  !! Transparent huge pages for the run's large arrays (huge_pages.c holds
  !! the why): `call advise_huge(a)` right after `a` is allocated and before
  !! it is first written asks the kernel to back its whole 2 MiB pages with
  !! huge pages. Arrays under 4 MiB, and every array after
  !! `huge_pages_enable(.false.)` (--huge-pages no), are left as they are.
  !! Advice only: contents, results and listings do not depend on it.
  !! `reuse_memory_enable` (--reuse-memory) and `apply_memory_policy` (once,
  !! before the deck is read): freed blocks under 32 MiB stay in the heap for
  !! the next ones instead of going back to the kernel (fresh pages cleared
  !! again); the results do not depend on it either.
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none (type, external)
  private

  public :: advise_huge, huge_pages_enable, reuse_memory_enable, apply_memory_policy

  interface
     subroutine advise_huge(a) bind(c, name='sj_advise_huge_array')
       !! Ask for huge pages for an allocated (contiguous) array of any type
       !! and rank before its first write.
       type(*), dimension(..), intent(in) :: a
     end subroutine advise_huge
     subroutine sj_huge_pages_enable(on) bind(c, name='sj_huge_pages_enable')
       import :: c_int
       integer(c_int), value :: on
     end subroutine sj_huge_pages_enable
     subroutine sj_reuse_memory_enable(on) bind(c, name='sj_reuse_memory_enable')
       import :: c_int
       integer(c_int), value :: on
     end subroutine sj_reuse_memory_enable
     subroutine apply_memory_policy() bind(c, name='sj_memory_policy')
       !! The allocator's policy for freed blocks, as reuse_memory_enable set
       !! it (default: kept for reuse); once, before the run allocates.
     end subroutine apply_memory_policy
  end interface

contains

  subroutine huge_pages_enable(on)
    !! Whether large blocks ask for huge pages from now on (default yes).
    logical, intent(in) :: on
    call sj_huge_pages_enable(merge(1_c_int, 0_c_int, on))
  end subroutine huge_pages_enable

  subroutine reuse_memory_enable(on)
    !! Whether freed large blocks stay with the process (default yes); takes
    !! effect at apply_memory_policy.
    logical, intent(in) :: on
    call sj_reuse_memory_enable(merge(1_c_int, 0_c_int, on))
  end subroutine reuse_memory_enable
end module superjoin_utils_huge_pages
