module superjoin_utils_process
  !! Process set-up (signals, see process.c) and the registration of the
  !! temporary output file that SIGINT/SIGTERM/SIGHUP must not leave behind.
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_long, c_int64_t
  use superjoin_kinds, only: i8
  implicit none (type, external)
  private

  public :: process_setup, temp_register, temp_unregister, quick_exit, second_thread_allowed

  interface
     function sj_process_setup(blas_bytes) bind(c, name='sj_process_setup') result(status)
       import :: c_int, c_int64_t
       integer(c_int64_t), intent(out) :: blas_bytes
       integer(c_int) :: status
     end function sj_process_setup

     function sj_temp_register(path, len) bind(c, name='sj_temp_register') result(status)
       import :: c_int, c_char, c_long
       character(kind=c_char), intent(in) :: path(*)
       integer(c_long), value :: len
       integer(c_int) :: status
     end function sj_temp_register
     function sj_second_thread() bind(c, name='sj_second_thread') result(yes)
       import :: c_int
       integer(c_int) :: yes
     end function sj_second_thread
     subroutine sj_quick_exit(status) bind(c, name='sj_quick_exit')
       import :: c_int
       integer(c_int), value :: status
     end subroutine sj_quick_exit
  end interface

contains

  subroutine quick_exit(status)
    !! Flush standard error and end the process with status at once, without
    !! the libraries' exit handlers (OpenBLAS can hang in its own after a
    !! failed buffer allocation).
    use, intrinsic :: iso_fortran_env, only: error_unit
    integer, intent(in) :: status
    flush (error_unit)
    call sj_quick_exit(int(status, c_int))
  end subroutine quick_exit

  subroutine process_setup(ok, blas_bytes)
    !! Ignore SIGXFSZ (writes past ulimit -f fail with an I/O status), remove
    !! the registered temporary file on SIGINT/SIGTERM/SIGHUP, allocate the
    !! BLAS work buffer. ok is false if a handler could not be installed;
    !! blas_bytes > 0: the BLAS buffer (that many bytes) could not be allocated.
    logical, intent(out) :: ok
    integer(i8), intent(out) :: blas_bytes
    integer(c_int64_t) :: nbytes
    ok = sj_process_setup(nbytes) == 0
    blas_bytes = int(nbytes, i8)
  end subroutine process_setup

  logical function second_thread_allowed()
    !! Whether work may run on a second thread beside the main one: not under
    !! OMP_NUM_THREADS=1, nor when the process may run on one CPU only
    !! (process.c, sj_second_thread).
    second_thread_allowed = sj_second_thread() /= 0
  end function second_thread_allowed

  subroutine temp_register(path)
    !! path is the temporary file being written: removed if a signal ends the run.
    character(*), intent(in) :: path
    integer(c_int) :: status
    status = sj_temp_register(path, int(len(path), c_long))
  end subroutine temp_register

  subroutine temp_unregister()
    !! No temporary file is being written any more.
    integer(c_int) :: status
    status = sj_temp_register('', 0_c_long)
  end subroutine temp_unregister
end module superjoin_utils_process
