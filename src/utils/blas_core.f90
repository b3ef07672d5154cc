module superjoin_utils_blas_core
  !! OpenBLAS's kernels for the CPU the run is on (blas_core.c holds the
  !! why): blas_core_setup, the first call of the program, starts it once
  !! more with OPENBLAS_CORETYPE set where OpenBLAS fell back to kernels
  !! older than the CPU's instructions; blas_core_note says which kernels
  !! run (for -v); blas_core_choice is the rule, for its unit test;
  !! blas_threads_rest lets OpenBLAS's idle workers go before the program's
  !! own two-thread work.
  use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_size_t, c_null_char, c_associated, c_f_pointer
  implicit none (type, external)
  private

  public :: blas_core_setup, blas_core_note, blas_core_choice, blas_threads_rest

  interface
     subroutine blas_core_setup() bind(c, name='sj_blas_core_setup')
       !! Before anything else: the program again with OPENBLAS_CORETYPE
       !! set, where blas_core.c's conditions hold; otherwise nothing.
     end subroutine blas_core_setup
     subroutine blas_threads_rest() bind(c, name='sj_blas_threads_rest')
       !! OpenBLAS's worker threads end (blas_core.c): their spin after a
       !! threaded call no longer takes a CPU from the program's own threads.
       !! OpenBLAS starts them again when it needs them. Only where no BLAS
       !! call runs on another thread.
     end subroutine blas_threads_rest
     function sj_blas_core_note() bind(c, name='sj_blas_core_note') result(p)
       import :: c_ptr
       type(c_ptr) :: p
     end function sj_blas_core_note
     function sj_blas_core_choice(current, avx512, avx2fma) bind(c, name='sj_blas_core_choice') result(p)
       import :: c_ptr, c_char, c_int
       character(kind=c_char), intent(in) :: current(*)
       integer(c_int), value :: avx512, avx2fma
       type(c_ptr) :: p
     end function sj_blas_core_choice
     function c_strlen(p) bind(c, name='strlen') result(n)
       import :: c_ptr, c_size_t
       type(c_ptr), value :: p
       integer(c_size_t) :: n
     end function c_strlen
  end interface

contains

  function blas_core_note() result(text)
    !! The BLAS kernels in use ('' when the BLAS is not OpenBLAS).
    character(:), allocatable :: text
    text = c_text(sj_blas_core_note())
  end function blas_core_note

  function blas_core_choice(current, avx512, avx2fma) result(core)
    !! The OpenBLAS core asked for instead of current on a CPU with AVX-512
    !! or with AVX2 and FMA ('' to keep current).
    character(*), intent(in) :: current
    logical, intent(in) :: avx512, avx2fma
    character(:), allocatable :: core
    core = c_text(sj_blas_core_choice(current//c_null_char, merge(1_c_int, 0_c_int, avx512), &
         merge(1_c_int, 0_c_int, avx2fma)))
  end function blas_core_choice

  function c_text(p) result(text)
    !! A NUL-terminated C string as Fortran text ('' for a null pointer).
    type(c_ptr), intent(in) :: p
    character(:), allocatable :: text
    character(kind=c_char), pointer :: chars(:)
    integer :: n
    n = 0
    if (c_associated(p)) n = int(c_strlen(p))
    allocate (character(n) :: text)
    if (n == 0) return
    call c_f_pointer(p, chars, [n])
    do n = 1, len(text)
       text(n:n) = chars(n)
    end do
  end function c_text
end module superjoin_utils_blas_core
