module superjoin_solvers_sparse
  !! Symmetric sparse matrix in compressed sparse column form, upper triangle.
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  type, public :: sparse_sym_t
    !! Upper triangle (row <= column) of a symmetric matrix, 1-based CSC:
    !! column j holds rows rowind(colptr(j):colptr(j+1)-1), sorted ascending,
    !! the diagonal always present and last in its column.
     integer(i8) :: n = 0
     integer(i8), allocatable :: colptr(:)   !! (n+1)
     integer(i8), allocatable :: rowind(:)   !! (nnz)
     real(wp), allocatable :: val(:)         !! (nnz)
  contains
     procedure :: nnz => sparse_nnz
     procedure :: diagonal => sparse_diagonal
     procedure :: matvec => sparse_matvec
  end type sparse_sym_t

contains

  pure function sparse_nnz(a) result(nz)
    !! Stored nonzeros (upper triangle with diagonal).
    class(sparse_sym_t), intent(in) :: a
    integer(i8) :: nz
    nz = 0
    if (allocated(a%colptr)) nz = a%colptr(a%n + 1) - 1
  end function sparse_nnz

  pure subroutine sparse_diagonal(a, d)
    !! Diagonal entries.
    class(sparse_sym_t), intent(in) :: a
    real(wp), intent(out) :: d(:)
    integer(i8) :: j
    do j = 1, a%n
       d(j) = a%val(a%colptr(j + 1) - 1)
    end do
  end subroutine sparse_diagonal

  pure subroutine sparse_matvec(a, x, y)
    !! y = A x for the full symmetric matrix (x, y of shape (n, nrhs)). One
    !! column: matvec_column; several: side by side (one pass over A). Each
    !! y(i, c) sums the same terms in the same order either way.
    class(sparse_sym_t), intent(in) :: a
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: y(:, :)
    real(wp), allocatable :: xt(:, :), yt(:, :)
    integer(i8) :: j, k, i
    if (size(x, 2) == 1) then
       call matvec_column(a, x(:, 1), y(:, 1))
       return
    end if
    xt = transpose(x)
    allocate (yt(size(x, 2), a%n), source=0.0_wp)
    do j = 1, a%n
       do k = a%colptr(j), a%colptr(j + 1) - 1
          i = a%rowind(k)
          yt(:, i) = yt(:, i) + a%val(k)*xt(:, j)
          if (i /= j) yt(:, j) = yt(:, j) + a%val(k)*xt(:, i)
       end do
    end do
    y = transpose(yt)
  end subroutine sparse_matvec

  pure subroutine matvec_column(a, x, y)
    !! y = A x for one right-hand side. Column j's own row y(j) is zero when
    !! column j is reached (earlier columns touch only rows above j), so its
    !! terms from column j are summed in a scalar first.
    type(sparse_sym_t), intent(in) :: a
    real(wp), intent(in) :: x(:)
    real(wp), intent(out) :: y(:)
    integer(i8) :: j, k, i
    real(wp) :: xj, yj
    y = 0.0_wp
    do j = 1, a%n
       xj = x(j)
       yj = 0.0_wp
       do k = a%colptr(j), a%colptr(j + 1) - 1
          i = a%rowind(k)
          if (i == j) then
             yj = yj + a%val(k)*xj
          else
             y(i) = y(i) + a%val(k)*xj
             yj = yj + a%val(k)*x(i)
          end if
       end do
       y(j) = y(j) + yj
    end do
  end subroutine matvec_column
end module superjoin_solvers_sparse
