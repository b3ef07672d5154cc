module test_lapack
  !! LAPACK interfaces shared by the unit tests (eigenvalues and dense or banded
  !! solves of small test systems).
  use superjoin_kinds, only: wp
  use superjoin_testing, only: check
  implicit none (type, external)
  private
  public :: dsyev, dposv, dpbsv, dgesv, eigenvalues

  interface
     subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
       !! LAPACK: eigenvalues (and vectors) of a real symmetric matrix.
       import :: wp
       character, intent(in) :: jobz, uplo
       integer, intent(in) :: n, lda, lwork
       real(wp), intent(inout) :: a(lda, *)
       real(wp), intent(out) :: w(*), work(*)
       integer, intent(out) :: info
     end subroutine dsyev
     subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
       !! LAPACK: solve a symmetric positive definite system (Cholesky).
       import :: wp
       character, intent(in) :: uplo
       integer, intent(in) :: n, nrhs, lda, ldb
       real(wp), intent(inout) :: a(lda, *), b(ldb, *)
       integer, intent(out) :: info
     end subroutine dposv
     subroutine dpbsv(uplo, n, kd, nrhs, ab, ldab, b, ldb, info)
       !! LAPACK: solve a symmetric positive definite banded system (Cholesky).
       import :: wp
       character, intent(in) :: uplo
       integer, intent(in) :: n, kd, nrhs, ldab, ldb
       real(wp), intent(inout) :: ab(ldab, *), b(ldb, *)
       integer, intent(out) :: info
     end subroutine dpbsv
     subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
       !! LAPACK: solve a general linear system.
       import :: wp
       integer, intent(in) :: n, nrhs, lda, ldb
       real(wp), intent(inout) :: a(lda, *), b(ldb, *)
       integer, intent(out) :: ipiv(*), info
     end subroutine dgesv
  end interface

contains

  function eigenvalues(a) result(w)
    !! Eigenvalues of a symmetric matrix (ascending).
    real(wp), intent(in) :: a(:, :)
    real(wp), allocatable :: w(:)
    real(wp), allocatable :: b(:, :), work(:)
    integer :: n, info
    n = size(a, 1)
    allocate (b, source=a)
    allocate (w(n), work(max(1, 3*n*8)))
    call dsyev('N', 'U', n, b, n, w, work, size(work), info)
    call check(info == 0, 'dsyev info')
  end function eigenvalues
end module test_lapack
