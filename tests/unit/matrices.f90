module test_matrices
  !! Sparse test matrices shared by the unit tests.
  use superjoin_kinds, only: wp, i8
  use superjoin_solvers, only: sparse_sym_t
  implicit none (type, external)
  private

  public :: grid_laplacian

contains

  subroutine grid_laplacian(m, ndim, a)
    !! Laplacian on an m^ndim grid (ndim = 1, 2 or 3; 2 ndim on the diagonal, -1
    !! to each neighbour), upper triangle with rows sorted in every column.
    integer(i8), intent(in) :: m
    integer, intent(in) :: ndim
    type(sparse_sym_t), intent(out) :: a
    integer(i8) :: j, k, n, stride(3), pos(3)
    integer :: d
    n = m**ndim
    stride = [1_i8, m, m*m]
    a%n = n
    allocate (a%colptr(n + 1), a%rowind((ndim + 1)*n), a%val((ndim + 1)*n))
    k = 0
    a%colptr(1) = 1
    do j = 1, n
       pos = mod((j - 1)/stride, m)
       do d = ndim, 1, -1
          if (pos(d) > 0) then
             k = k + 1
             a%rowind(k) = j - stride(d)
             a%val(k) = -1.0_wp
          end if
       end do
       k = k + 1
       a%rowind(k) = j
       a%val(k) = real(2*ndim, wp)
       a%colptr(j + 1) = k + 1
    end do
    a%rowind = a%rowind(1:k)
    a%val = a%val(1:k)
  end subroutine grid_laplacian
end module test_matrices
