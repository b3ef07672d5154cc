module superjoin_solvers_blas
  !! Explicit interfaces of the BLAS routines that more than one solver calls.
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  public :: dsyrk

  interface
     subroutine dsyrk(uplo, trans, n, k, alpha, a, lda, beta, c, ldc)
       !! c = alpha a aᵀ + beta c (trans 'N') or alpha aᵀ a + beta c ('T'),
       !! c symmetric, its uplo triangle referenced.
       import :: wp
       character(len=1), intent(in) :: uplo, trans
       integer, intent(in) :: n, k, lda, ldc
       real(wp), intent(in) :: alpha, beta, a(lda, *)
       real(wp), intent(inout) :: c(ldc, *)
     end subroutine dsyrk
  end interface
end module superjoin_solvers_blas
