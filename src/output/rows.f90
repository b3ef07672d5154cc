module superjoin_output_rows
  !! The long tables of the listing formatted on two threads. A table is a
  !! row_source_t: items 1..count (nodes, elements) whose rows it can format
  !! into any text buffer, a range at a time, each row depending on its item
  !! alone. write_rows formats pairs of chunks side by side, the first into
  !! the listing's own buffer and the second into a buffer kept in memory,
  !! which the listing then takes: the bytes are those of one thread, in the
  !! same order.
  !!
  !! A table's put_rows runs on either thread, beside itself: it writes
  !! nothing but its buffer (no module or SAVE variable), and calls no
  !! function whose result is a deferred-length text (itoa, trim of an
  !! allocatable, ...): gfortran 12 keeps such a result's length in a static
  !! variable, which both threads then share (rows lost or cut short, found
  !! while this was written; the listing's formatters (text_buffer_t's put_*,
  !! format_es, int_field) have none).
  use superjoin_kinds, only: i8, ip
  use superjoin_model_types, only: model_t
  use superjoin_model_results, only: results_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_utils_process, only: second_thread_allowed
  use superjoin_utils_blas_core, only: blas_threads_rest
  implicit none (type, external)
  private

  integer(i8), parameter :: CHUNK_ITEMS = 2048
    !! items formatted by each thread per turn: 0.2 to 1 MB of text (a
    !! contact element's six rows the most; the memory buffer keeps blocks of
    !! 1 MB and grows beyond), a turn of about a millisecond against the few
    !! microseconds of starting one

  type, abstract, public :: row_source_t
    !! A table whose items can be formatted a range at a time, into any buffer.
  contains
     procedure(put_rows_i), deferred :: put_rows
  end type row_source_t

  abstract interface
     subroutine put_rows_i(self, tb, model, res, first, last)
       !! The rows of items first..last, in order, appended to tb.
       import :: row_source_t, text_buffer_t, model_t, results_t, i8
       class(row_source_t), intent(in) :: self
       type(text_buffer_t), intent(inout) :: tb
       type(model_t), intent(in) :: model
       type(results_t), intent(in) :: res
       integer(i8), intent(in) :: first, last
     end subroutine put_rows_i
  end interface

  public :: write_rows, owner_of, step_owner

contains

  subroutine write_rows(lu, source, model, res, count)
    !! The rows of items 1..count of source, in order, appended to lu. Where a
    !! second thread may run (second_thread_allowed) and there is more than one
    !! chunk, each turn formats two chunks side by side; else, or when the
    !! memory buffer cannot be had, one thread formats them all.
    type(text_buffer_t), intent(inout) :: lu
    class(row_source_t), intent(in) :: source
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: count
    type(text_buffer_t), allocatable :: side
    integer(i8) :: first, mid, last
    integer :: stat

    if (count <= CHUNK_ITEMS) then
       call source%put_rows(lu, model, res, 1_i8, count)
       return
    end if
    stat = 1
    if (second_thread_allowed()) allocate (side, stat=stat)
    if (stat == 0) then
       call side%open_memory()
       if (side%failed) stat = 1
    end if
    if (stat /= 0) then
       call source%put_rows(lu, model, res, 1_i8, count)
       return
    end if
    call blas_threads_rest()   ! OpenBLAS's idle workers would spin on the second CPU
    first = 1
    do while (first <= count)
       mid = min(first + CHUNK_ITEMS - 1, count)
       last = min(mid + CHUNK_ITEMS, count)
       call format_pair(lu, side, source, model, res, [first, mid, last])
       if (side%failed) then   ! no memory for the second chunk's text: formatted again here
          call side%open_memory()
          call source%put_rows(lu, model, res, mid + 1, last)
       else
          call lu%take(side)
       end if
       first = last + 1
    end do
  end subroutine write_rows

  subroutine format_pair(lu, side, source, model, res, bounds)
    !! Items bounds(1)..bounds(2) into lu and bounds(2)+1..bounds(3) into side,
    !! side by side on two threads. The buffers are plain dummies here: with
    !! the caller's allocatable buffer named in the region itself, gfortran 12
    !! left it empty.
    type(text_buffer_t), intent(inout) :: lu, side
    class(row_source_t), intent(in) :: source
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: bounds(3)
    !$omp parallel sections num_threads(2) default(none) shared(lu, side, source, model, res, bounds)
    !$omp section
    call source%put_rows(lu, model, res, bounds(1), bounds(2))
    !$omp section
    if (bounds(3) > bounds(2)) call source%put_rows(side, model, res, bounds(2) + 1, bounds(3))
    !$omp end parallel sections
  end subroutine format_pair

  pure integer function owner_of(offsets, item) result(k)
    !! The k with offsets(k) < item <= offsets(k + 1): the substructure of a
    !! vertex or element in the results' numberings over the substructures
    !! (offsets ascending; an empty substructure's interval is empty).
    integer(i8), intent(in) :: offsets(:)
    integer(i8), intent(in) :: item
    integer :: lo, hi, m
    lo = 1
    hi = size(offsets) - 1
    do while (lo < hi)   ! the last k with offsets(k) < item
       m = (lo + hi + 1)/2
       if (offsets(m) < item) then
          lo = m
       else
          hi = m - 1
       end if
    end do
    k = lo
  end function owner_of

  pure subroutine step_owner(offsets, item, k, local)
    !! For items taken in increasing order: k moved on to the substructure of
    !! item (k at most that on entry: owner_of of the range's first item, or
    !! the previous item's) and local, item's number within it.
    integer(i8), intent(in) :: offsets(:)
    integer(i8), intent(in) :: item
    integer, intent(inout) :: k
    integer(ip), intent(out) :: local
    do while (item > offsets(k + 1))
       k = k + 1
    end do
    local = int(item - offsets(k), ip)
  end subroutine step_owner
end module superjoin_output_rows
