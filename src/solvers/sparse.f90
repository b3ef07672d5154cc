module superjoin_solvers_sparse
  !! Symmetric sparse matrix in compressed sparse column form, upper triangle.
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private
  public :: move_sparse

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

  pure subroutine move_sparse(from, to)
    !! to = from by move (no copy of the arrays); from is left an empty
    !! matrix (n = 0, no arrays), not one whose n promises arrays it lacks.
    type(sparse_sym_t), intent(inout) :: from
    type(sparse_sym_t), intent(inout) :: to
    to%n = from%n
    call move_alloc(from%colptr, to%colptr)
    call move_alloc(from%rowind, to%rowind)
    call move_alloc(from%val, to%val)
    from%n = 0
  end subroutine move_sparse

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
    !! y = A x for the full symmetric matrix (x, y of shape (n, nrhs)): two
    !! columns at a time (matvec_pair, one pass over A for both), the last
    !! one of an odd count alone (matvec_column). Each y(i, c) sums the same
    !! terms in the same order either way.
    class(sparse_sym_t), intent(in) :: a
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(out) :: y(:, :)
    integer :: c
    do c = 1, size(x, 2) - 1, 2
       call matvec_pair(a, x(:, c), x(:, c + 1), y(:, c), y(:, c + 1))
    end do
    if (mod(size(x, 2), 2) == 1) call matvec_column(a, x(:, size(x, 2)), y(:, size(x, 2)))
  end subroutine sparse_matvec

  pure subroutine matvec_pair(a, x1, x2, y1, y2)
    !! y1 = A x1 and y2 = A x2 in one pass over A, each as matvec_column sums it.
    type(sparse_sym_t), intent(in) :: a
    real(wp), intent(in) :: x1(:), x2(:)
    real(wp), intent(out) :: y1(:), y2(:)
    integer(i8) :: j, k, i
    real(wp) :: xj1, xj2, yj1, yj2, v
    y1 = 0.0_wp
    y2 = 0.0_wp
    do j = 1, a%n
       xj1 = x1(j)
       xj2 = x2(j)
       yj1 = 0.0_wp
       yj2 = 0.0_wp
       do k = a%colptr(j), a%colptr(j + 1) - 1
          i = a%rowind(k)
          v = a%val(k)
          if (i == j) then
             yj1 = yj1 + v*xj1
             yj2 = yj2 + v*xj2
          else
             y1(i) = y1(i) + v*xj1
             y2(i) = y2(i) + v*xj2
             yj1 = yj1 + v*x1(i)
             yj2 = yj2 + v*x2(i)
          end if
       end do
       y1(j) = y1(j) + yj1
       y2(j) = y2(j) + yj2
    end do
  end subroutine matvec_pair

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
