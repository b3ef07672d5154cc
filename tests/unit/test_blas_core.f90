program test_blas_core
  !! The rule by which superjoin asks OpenBLAS for other kernels
  !! (superjoin_utils_blas_core, blas_core.c): only a core without AVX2
  !! kernels is replaced, by SkylakeX on a CPU with AVX-512 and by Haswell on
  !! one with AVX2 and FMA; a newer or unknown-to-the-rule core, or a CPU
  !! without these instructions, is kept. OpenBLAS's names in any case.
  use superjoin_utils_blas_core, only: blas_core_choice
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  call expect('Prescott', .true., .true., 'SkylakeX')    ! Debian 12's OpenBLAS on a family 6 model 207 Xeon
  call expect('PRESCOTT', .true., .true., 'SkylakeX')
  call expect('Prescott', .false., .true., 'Haswell')
  call expect('Prescott', .false., .false., '')
  call expect('Nehalem', .false., .true., 'Haswell')
  call expect('Sandybridge', .true., .true., 'SkylakeX')
  call expect('Core2', .true., .false., 'SkylakeX')
  call expect('Haswell', .true., .true., '')              ! never another core for one with AVX2 kernels
  call expect('SkylakeX', .true., .true., '')
  call expect('Cooperlake', .true., .true., '')
  call expect('Zen', .true., .true., '')
  call expect('Excavator', .false., .true., '')
  call expect('', .true., .true., '')
  call finish()

contains

  subroutine expect(current, avx512, avx2fma, want)
    character(*), intent(in) :: current, want
    logical, intent(in) :: avx512, avx2fma
    character(:), allocatable :: got
    got = blas_core_choice(current, avx512, avx2fma)
    call check(got == want, 'core '''//current//''' (AVX-512 '//merge('yes', 'no ', avx512)//', AVX2+FMA '// &
         merge('yes', 'no ', avx2fma)//'): '''//got//''', expected '''//want//'''')
  end subroutine expect
end program test_blas_core
