program test_memory
  !! Unit tests of the out-of-memory messages (superjoin_utils_memory).
  use superjoin_kinds, only: i8
  use superjoin_error, only: error_t, EXIT_IO
  use superjoin_utils_memory, only: out_of_memory, oom_message, bytes_text
  use superjoin_testing, only: check, finish
  implicit none (type, external)

  type(error_t), allocatable :: error

  call check(bytes_text(0_i8) == '0 bytes (0.0 MiB)', 'zero bytes')
  call check(bytes_text(1048576_i8) == '1048576 bytes (1.0 MiB)', 'one MiB')
  call check(bytes_text(43296776_i8) == '43296776 bytes (41.3 MiB)', 'MiB rounded to 0.1')
  call check(bytes_text(3221225472_i8) == '3221225472 bytes (3.0 GiB)', 'GiB from 1 GiB on')
  call check(bytes_text(9223372036854775807_i8) == '9223372036854775807 bytes (8589934592.0 GiB)', &
       'largest count')
  call check(oom_message('the matrix pattern', 1024_i8) == &
       'error: out of memory: the matrix pattern needs 1024 bytes (0.0 MiB)', 'message layout')
  call out_of_memory(error, 'x', 2048_i8)
  call check(allocated(error), 'error allocated')
  if (allocated(error)) then
     call check(error%code == EXIT_IO, 'exit status 4')
     call check(error%message == 'error: out of memory: x needs 2048 bytes (0.0 MiB)', 'error message')
     deallocate (error)
  end if
  call finish()
end program test_memory
