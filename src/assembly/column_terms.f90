module superjoin_assembly_column_terms
  !! Linear forms of the reduced unknowns as lists of (column, coefficient)
  !! terms: merged into ascending, unique columns, and looked up by column
  !! (superjoin_assembly_transform's maps, forms and eliminations).
  use superjoin_kinds, only: wp, i8
  implicit none (type, external)
  private

  public :: merge_terms, locate

contains

  subroutine merge_terms(col, coef)
    !! Sort terms by column, add repeats, drop exact zeros.
    integer(i8), allocatable, intent(inout) :: col(:)
    real(wp), allocatable, intent(inout) :: coef(:)
    integer :: i, j, n
    integer(i8) :: tc
    real(wp) :: tv
    do i = 2, size(col)
       tc = col(i)
       tv = coef(i)
       j = i - 1
       do while (j >= 1)
          if (col(j) <= tc) exit
          col(j + 1) = col(j)
          coef(j + 1) = coef(j)
          j = j - 1
       end do
       col(j + 1) = tc
       coef(j + 1) = tv
    end do
    n = 0
    do i = 1, size(col)
       if (n > 0) then
          if (col(n) == col(i)) then
             coef(n) = coef(n) + coef(i)
             cycle
          end if
       end if
       n = n + 1
       col(n) = col(i)
       coef(n) = coef(i)
    end do
    j = 0
    do i = 1, n
       if (coef(i) == 0.0_wp) cycle
       j = j + 1
       col(j) = col(i)
       coef(j) = coef(i)
    end do
    col = col(1:j)
    coef = coef(1:j)
  end subroutine merge_terms

  pure function locate(cols, j) result(b)
    !! Index b with cols(b) == j in the ascending list cols, 0 when absent (bisection).
    integer(i8), intent(in) :: cols(:), j
    integer :: b, lo, hi
    lo = 1
    hi = size(cols)
    b = 0
    do while (lo <= hi)
       b = lo + (hi - lo)/2
       if (cols(b) == j) return
       if (cols(b) < j) then
          lo = b + 1
       else
          hi = b - 1
       end if
    end do
    b = 0
  end function locate

end module superjoin_assembly_column_terms
