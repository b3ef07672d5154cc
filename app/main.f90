program superjoin_main
  !! superjoin: command-line driver. Reads a deck, solves every step, writes the
  !! listing (and CSV results on request). The only place that stops.
  !!
  !! Under MPI (cmake -DSUPERJOIN_MPI=ON, mpirun -np N) every process runs this
  !! same program on the same deck; the solver is MUMPS over all of them
  !! (--solver auto means mumps when N > 1); rank 0 alone prints progress and
  !! warnings and writes the outputs. Every stop goes through finish() or
  !! fail_on(), which agree on the exit status across the processes
  !! (superjoin_parallel_comm): an error on any process ends every process
  !! with the same status and one message, from the process that had it.
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, EXIT_OK, EXIT_USAGE, EXIT_IO, EXIT_INACCURATE
  use superjoin_model_types, only: model_t, string_t, DIALECT_CALCULIX, FORM_TRANSFORM, FORM_PENALTY, CONDENSE_YES, CONDENSE_NO, &
       CONDENSE_AUTO
  use superjoin_utils_huge_pages, only: huge_pages_enable, reuse_memory_enable, apply_memory_policy
  use superjoin_utils_blas_core, only: blas_core_setup, blas_core_note
  use superjoin_deck_reader, only: read_deck
  use superjoin_analysis_driver, only: solve_steps, partial_results
  use superjoin_analysis_combinations, only: add_combinations
  use superjoin_analysis_plausibility, only: check_plausibility
  use superjoin_analysis_contact_gaps, only: check_contact_gaps
  use superjoin_analysis_drilling_check, only: check_partial_rotations
  use superjoin_model_results, only: results_t, run_options_t, PH_READ, PH_WRITE, LEVELS_YES, LEVELS_NO, LEVELS_AUTO
  use superjoin_model_notes, only: model_warnings_first
  use superjoin_output_listing, only: write_listing
  use superjoin_output_csv, only: write_csv
  use superjoin_output_nodes_csv, only: write_nodes_csv
  use superjoin_output_requested_csv, only: write_requested_csv
  use superjoin_output_vtk, only: write_vtk, vtk_path_problem
  use superjoin_output_ccx_dat, only: write_ccx_dat, write_ccx_sta
  use superjoin_output_frd, only: write_frd
  use superjoin_utils_posix, only: output_target, make_directory
  use superjoin_output_mechanism, only: write_mechanism_vtk, write_mechanism_csv, mechanism_vtk_path, MECHANISM_CSV
  use superjoin_config, only: SUPERJOIN_VERSION, DEMO_DECK_SOURCE, DEMO_DECK_INSTALLED
  use superjoin_utils_strings, only: to_lower
  use superjoin_utils_clock, only: stopwatch_t, report_phase
  use superjoin_utils_process, only: process_setup, quick_exit
  use superjoin_utils_memory, only: oom_message
  use superjoin_solvers, only: mumps_available
  use superjoin_parallel_comm, only: comm_t, comm_world, agree, failure_agreed, agreed_first
  use superjoin_analysis_distributed, only: mpi_summary
  implicit none (type, external)

  type(run_options_t) :: opts
  type(model_t) :: model
  type(results_t) :: res
  type(error_t), allocatable :: error, unsolved
  type(string_t), allocatable :: deck_warnings(:)
  character(:), allocatable :: deck, listing, csv_dir, vtk_file, target, job
  logical :: check_only, demo
  type(stopwatch_t) :: clock
  real(wp) :: t_read
  integer :: i, msg_unit, cli_status
  integer(i8) :: blas_bytes
  logical :: ok
  type(comm_t) :: comm

  call blas_core_setup()   ! first: it may start the program again (OpenBLAS's kernels, utils/blas_core.c)
  comm = comm_world()
  call parse_command_line(opts, deck, listing, csv_dir, check_only, vtk_file, demo, job, cli_status)
  if (cli_status >= 0) stop cli_status, quiet=.true.
  ! As ccx -i JOB: warnings and the job's progress on stdout, so that a
  ! front-end reads a silent stderr and status 0 as success (FreeCAD does).
  msg_unit = error_unit
  if (allocated(job)) then
     msg_unit = output_unit
     opts%quiet = .true.
     if (comm%is_root()) call start_ccx_job(job)
  end if
  if (comm%size > 1) then
     if (.not. allocated(opts%solver)) opts%solver = 'auto'
     if (opts%solver == 'auto') opts%solver = 'mumps'
     ! each process condenses the parts it owns (analysis/distributed)
     if (opts%condense < 0) opts%condense = CONDENSE_YES
     ! with MUMPS each process holds only its own term of the matrix
     if (allocated(opts%export_matrix) .and. index(opts%solver, 'mumps') == 1) then
        if (.not. comm%is_root()) stop EXIT_USAGE, quiet=.true.
        call usage_error('--export-matrix is not available on several MPI processes with MUMPS: no process '// &
             'assembles the matrix (run on one process, or with --solver cholmod)')
     end if
  end if
  if (.not. comm%is_root()) then
     ! one voice: progress, warnings and every output file come from rank 0
     opts%quiet = .true.
     if (allocated(opts%export_matrix)) deallocate (opts%export_matrix)
  end if
  if (comm%size == 1) call apply_memory_policy()   ! under MPI the allocator is left to the MPI library
  call process_setup(ok, blas_bytes)
  if (.not. ok) write (error_unit, '(a)') 'superjoin: warning: signal handlers not installed'
  if (opts%verbose .and. .not. opts%quiet .and. comm%is_root()) call say_blas_kernels()
  if (blas_bytes > 0 .and. .not. check_only) then
     write (error_unit, '(a)') deck//': '//oom_message('the BLAS work buffer', blas_bytes)
     call quick_exit(EXIT_IO)
  end if

  ! Outputs are written as NAME.tmp and renamed over NAME: never over a
  ! device or a FIFO (-o /dev/stdout), and through a symbolic link to its file.
  call output_target(listing, target, error)
  call fail_on(error, deck)
  listing = target
  if (allocated(opts%export_matrix)) then
     call output_target(opts%export_matrix, target, error)
     call fail_on(error, deck)
     opts%export_matrix = target
  end if
  if (allocated(opts%library)) then
     call make_directory(opts%library, error)
     call fail_on(error, deck)
  end if

  call clock%start()
  if (allocated(job)) then
     call read_deck(deck, model, error, DIALECT_CALCULIX)   ! ccx -i JOB reads a CalculiX deck
  else
     call read_deck(deck, model, error)
  end if
  call fail_on(error, deck)
  t_read = clock%seconds()
  call report_phase(opts%quiet, 'read', t_read, deck)
  ! Warnings on the deck itself come first, so that they accompany a failure too
  ! (a wrong node number in a contact often makes a mechanism).
  allocate (deck_warnings(0))
  call check_contact_gaps(model, deck_warnings)
  call check_partial_rotations(model, deck_warnings)
  if (comm%is_root()) then
     do i = 1, size(deck_warnings)
        write (msg_unit, '(a)') deck//': warning: '//deck_warnings(i)%s
     end do
  end if
  if (check_only) then
     if (.not. opts%quiet) write (error_unit, '(a)') 'superjoin: '//deck//': deck is valid'
     call finish(EXIT_OK)
  end if

  if (.not. allocated(vtk_file) .and. allocated(model%vtk_path)) vtk_file = model%vtk_path
  opts%csv = allocated(csv_dir)
  opts%vtk = allocated(vtk_file)
  opts%frd = allocated(job)
  call solve_steps(model, opts, res, error)
  if (allocated(error) .and. allocated(res%fields%mechanism) .and. comm%is_root()) call write_mechanism(error)
  ! Some steps solved, others not (exit 3): the solved ones are written first.
  if (allocated(error) .and. partial_results(res)) call move_alloc(error, unsolved)
  call fail_on(error, deck)
  call add_combinations(model, res, error)
  call fail_on(error, deck)
  call check_plausibility(model, res)
  call mpi_summary(opts%quiet, error)   ! several MPI processes: communication and memory per process
  call fail_on(error, deck)
  res%log%phase_seconds(PH_READ) = t_read
  ! Warnings are printed also under -q (it silences progress only).
  if (comm%is_root()) then
     do i = 1, size(res%log%warnings)
        write (msg_unit, '(a)') deck//': warning: '//res%log%warnings(i)%s
     end do
  end if
  call model_warnings_first(deck_warnings, res%log%warnings)

  call clock%start()
  if (comm%is_root()) then
     call write_listing(listing, model, res, error)
     call fail_on(error, deck)
     if (allocated(csv_dir)) then
        call write_csv(csv_dir, model, res%fields, error)
        call fail_on(error, deck)
        call write_nodes_csv(csv_dir, model, error)
        call fail_on(error, deck)
        call write_requested_csv(csv_dir, model, res%fields, error)
        call fail_on(error, deck)
     end if
     if (allocated(vtk_file)) then
        call write_vtk(vtk_file, model, res%fields, error)
        call fail_on(error, deck)
     end if
     if (allocated(job)) call write_ccx_files(job)
  end if
  res%log%phase_seconds(PH_WRITE) = clock%seconds()
  call report_phase(opts%quiet, 'write', res%log%phase_seconds(PH_WRITE), listing)
  if (demo .and. .not. opts%quiet) write (error_unit, '(a)') 'superjoin: listing written to '//listing
  if (allocated(unsolved)) then
     unsolved%message = unsolved%message//new_line('a')//'  the listing is written with the results of '// &
          'the steps solved (the others are marked NOT SOLVED)'
     call fail_on(unsolved, deck)
  end if
  if (res%log%inaccurate .and. .not. opts%accept_inaccurate) then
     if (comm%is_root()) write (error_unit, '(a)') deck//': error: the results are judged inaccurate '// &
          '(see the warnings above); the listing is written, exit status 5 (--accept-inaccurate: exit 0)'
     call finish(EXIT_INACCURATE)
  end if
  if (allocated(job) .and. comm%is_root()) write (output_unit, '(a)') '', ' Job finished', ''
  call finish(EXIT_OK)

contains

  subroutine say_blas_kernels()
    !! -v: the BLAS kernels in use (nothing when the BLAS is not OpenBLAS).
    character(:), allocatable :: kernels
    kernels = blas_core_note()
    if (len(kernels) > 0) write (error_unit, '(a)') 'superjoin: BLAS: '//kernels
  end subroutine say_blas_kernels

  subroutine start_ccx_job(job)
    !! The banner of a ccx -i run, and JOB.dat, .frd, .sta emptied as ccx
    !! does at its start (a failed run leaves no results of an earlier one).
    character(*), intent(in) :: job
    character(len=4), parameter :: EXTS(3) = ['.dat', '.frd', '.sta']
    integer :: k, lu, stat
    write (output_unit, '(a)') '', 'superjoin '//SUPERJOIN_VERSION//': linear statics, a drop-in for '// &
         'CalculiX (ccx -i '//job//'): '//job//'.inp -> '//job//'.dat, .frd, .sta and the listing '// &
         job//'.lst', ''
    do k = 1, size(EXTS)
       open (newunit=lu, file=job//trim(EXTS(k)), status='replace', action='write', iostat=stat)
       if (stat == 0) close (lu)
    end do
  end subroutine start_ccx_job

  subroutine write_ccx_files(job)
    !! JOB.dat, JOB.frd and JOB.sta, as ccx -i JOB writes them.
    character(*), intent(in) :: job
    call write_ccx_dat(job//'.dat', model, res%fields, error)
    call fail_on(error, deck)
    call write_frd(job//'.frd', model, res%fields, error)
    call fail_on(error, deck)
    call write_ccx_sta(job//'.sta', model, res%fields, error)
    call fail_on(error, deck)
  end subroutine write_ccx_files

  subroutine write_mechanism(error)
    !! The mechanism mode into the VTK and CSV outputs asked for; the files
    !! written (or why not) are added to the error's message.
    type(error_t), intent(inout) :: error
    type(error_t), allocatable :: werr
    character(:), allocatable :: written
    written = ''
    if (allocated(vtk_file)) then
       call write_mechanism_vtk(vtk_file, model, res%fields%mechanism, werr)
       if (allocated(werr)) then
          error%message = error%message//new_line('a')//werr%message
          deallocate (werr)
       else
          written = ' '//mechanism_vtk_path(vtk_file)
       end if
    end if
    if (allocated(csv_dir)) then
       call write_mechanism_csv(csv_dir, model, res%fields%mechanism, werr)
       if (allocated(werr)) then
          error%message = error%message//new_line('a')//werr%message
       else
          written = written//' '//csv_dir//'/'//MECHANISM_CSV
       end if
    end if
    if (len(written) > 0) then
       error%message = error%message//new_line('a')//'  the mode is written to'//written
    else
       error%message = error%message//new_line('a')//'  (--vtk FILE or --csv DIR write the mode, to see it)'
    end if
  end subroutine write_mechanism

  subroutine finish(status)
    !! Stop with status, agreed with every other process: the largest status
    !! of all (a process that failed late, while writing, is heard here).
    integer, intent(in) :: status
    integer :: worst, first
    call agree(status, worst, first)
    stop worst, quiet=.true.
  end subroutine finish

  subroutine fail_on(error, deck)
    !! Print the error's lines on stderr and stop with its exit status. Under
    !! MPI: if the error came from an agreement (another process failed),
    !! stop silently with the agreed status; otherwise agree now, and the
    !! lowest process with the worst status prints.
    type(error_t), allocatable, intent(in) :: error
    character(*), intent(in) :: deck
    integer :: start, nl, worst, first
    character(:), allocatable :: line
    if (.not. allocated(error)) return
    if (failure_agreed()) then
       ! every process knows already: only the one that failed first prints
       if (agreed_first() /= comm%rank) stop error%code, quiet=.true.
    else
       call agree(error%code, worst, first)
       if (first /= comm%rank) stop worst, quiet=.true.
    end if
    start = 1
    do
       nl = index(error%message(start:), new_line('a'))
       if (nl == 0) then
          line = error%message(start:)
       else
          line = error%message(start:start + nl - 2)
       end if
       if (index(line, 'error:') == 1) line = deck//': '//line
       write (error_unit, '(a)') line
       if (nl == 0) exit
       start = start + nl
    end do
    stop error%code, quiet=.true.
  end subroutine fail_on

  logical function yes_no(val, option, status)
    !! The value of a yes | no option (anything else: a usage error, said,
    !! status EXIT_USAGE; status unchanged otherwise).
    character(*), intent(in) :: val, option
    integer, intent(inout) :: status
    yes_no = .false.
    select case (to_lower(val))
    case ('yes')
       yes_no = .true.
    case ('no')
    case default
       call usage_problem(status, 'unknown '//option//' '''//val//''' (yes, no)')
    end select
  end function yes_no

  subroutine usage_error(message)
    !! A usage error: said, and the run stops with EXIT_USAGE.
    character(*), intent(in) :: message
    call usage_message(message)
    stop EXIT_USAGE, quiet=.true.
  end subroutine usage_error

  subroutine usage_problem(status, message)
    !! A usage error found while parsing: said, status EXIT_USAGE (the caller stops).
    integer, intent(out) :: status
    character(*), intent(in) :: message
    call usage_message(message)
    status = EXIT_USAGE
  end subroutine usage_problem

  subroutine usage_message(message)
    !! A usage error said on standard error, with the usage line.
    character(*), intent(in) :: message
    write (error_unit, '(a)') 'superjoin: '//message
    write (error_unit, '(a)') 'usage: superjoin [options] [DECK]   (superjoin --help for more)'
  end subroutine usage_message

  subroutine print_help()
    write (output_unit, '(a)') &
         'superjoin '//SUPERJOIN_VERSION//': linear statics of substructures joined by contact elements', &
         '', &
         'usage: superjoin [options] [DECK]      (no DECK: solves the bundled demo deck)', &
         '', &
         '  -i JOB             as CalculiX''s ccx -i JOB: reads JOB.inp, writes JOB.dat, JOB.frd, JOB.sta', &
         '                     (*NODE/*EL PRINT and FILE requests) beside the listing JOB.lst', &
         '  -o FILE            listing path (default: DECK with extension .lst)', &
         '  --csv DIR          full-precision CSV results in DIR (created if needed)', &
         '  --solver NAME      auto | cholmod | umfpack | lapack | mumps | mumps-ldlt (default auto)', &
         '  --formulation F    transform | penalty   (overrides *CONTROLS)', &
         '  --condense C       yes | no | auto: static condensation of every substructure', &
         '                     (overrides CONDENSE= of *SUBSTRUCTURE)', &
         '  --levels L         yes | no | auto: condensed parts made of parts eliminated by level, flat,', &
         '                     or by level when the counts promise a gain (default auto)', &
         '  --check            read and validate the deck only', &
         '  --export-matrix F  also write the assembled stiffness matrix (Matrix Market)', &
         '  --library DIR      keep condensed parts in DIR and load unchanged ones from it', &
         '  --library-verify   with --library: check a loaded part against its assembled stiffness', &
         '  --twins T          yes | no: condensed parts identical up to a rigid motion share one', &
         '                     condensation, turned (default yes)', &
         '  --huge-pages H     yes | no: large arrays ask the kernel for transparent huge pages', &
         '                     (default yes; fewer page faults, the same results)', &
         '  --reuse-memory R   yes | no: freed blocks under 32 MiB stay with superjoin for its next', &
         '                     ones instead of going back to the kernel (default yes; the same results)', &
         '  --vtk FILE         VTK files for ParaView: FILE.pvd and FILE_<step>.vtu', &
         '                     (overrides *OUTPUT, VTK= of the deck)', &
         '  --accept-inaccurate  exit 0 even when the results are judged inaccurate', &
         '  -q, --quiet        no progress on stderr (warnings are still printed)', &
         '  -v, --verbose      more detail on stderr', &
         '  --help             this text', &
         '  --version          version', &
         '', &
         'exit status: 0 solved; 1 deck error; 2 usage error; 3 structure cannot be solved', &
         '             (mechanism, singular); 4 input/output or resource failure;', &
         '             5 solved and listing written, but the results are judged inaccurate'
  end subroutine print_help

  subroutine parse_command_line(opts, deck, listing, csv_dir, check_only, vtk_file, demo, job, status)
    !! Options and file names from the command line. status: -1 go on; else the
    !! exit status the caller stops with (EXIT_OK after --help or --version,
    !! EXIT_USAGE after a usage error, EXIT_IO without the deck; the message is
    !! written). The run stops in the caller, never here: the allocations of a
    !! procedure left by STOP looked leaked to LeakSanitizer.
    !! demo: no deck given, the bundled demo deck is solved. job: -i JOB (as
    !! ccx: the deck JOB.inp, CalculiX's result files JOB.dat, .frd, .sta).
    type(run_options_t), intent(out) :: opts
    character(:), allocatable, intent(out) :: deck, listing, csv_dir, vtk_file, job
    logical, intent(out) :: check_only, demo
    integer, intent(out) :: status
    integer :: i, n
    character(:), allocatable :: arg, val
    logical :: exists

    status = -1
    check_only = .false.
    opts%solver = 'auto'
    n = command_argument_count()
    i = 0
    do while (i < n)
       i = i + 1
       arg = get_arg(i)
       select case (arg)
       case ('-h', '--help')
          call print_help()
          status = EXIT_OK
          return
       case ('--version')
          write (output_unit, '(a)') 'superjoin '//SUPERJOIN_VERSION
          status = EXIT_OK
          return
       case ('-q', '--quiet')
          opts%quiet = .true.
       case ('-v', '--verbose')
          opts%verbose = .true.
       case ('--check')
          check_only = .true.
       case ('--accept-inaccurate')
          opts%accept_inaccurate = .true.
       case ('--library-verify')
          opts%library_verify = .true.
       case ('-i')
          ! also "-i " with a trailing blank, as FreeCAD passes it (a blank-padded compare)
          if (i == n) then
             call usage_problem(status, 'option -i needs a job name (as ccx -i JOB: reads JOB.inp)')
             return
          end if
          i = i + 1
          if (allocated(deck)) then
             call usage_problem(status, 'more than one deck given')
             return
          end if
          job = job_name(get_arg(i))
          deck = job//'.inp'
       case ('-o', '--csv', '--solver', '--formulation', '--export-matrix', '--vtk', '--condense', '--library', &
            '--levels', '--twins', '--huge-pages', '--reuse-memory')
          if (i == n) then
             call usage_problem(status, 'option '//arg//' needs a value')
             return
          end if
          i = i + 1
          val = get_arg(i)
          select case (arg)
          case ('-o')
             listing = val
          case ('--csv')
             csv_dir = val
          case ('--solver')
             select case (to_lower(val))
             case ('auto', 'cholmod', 'umfpack', 'lapack', 'mumps', 'mumps-ldlt')
                opts%solver = to_lower(val)
                if (index(opts%solver, 'mumps') == 1 .and. .not. mumps_available()) then
                   call usage_problem(status, 'solver '//opts%solver//': this superjoin is built without MUMPS '// &
                        '(cmake -DSUPERJOIN_MUMPS=ON or -DSUPERJOIN_MPI=ON, doc/user-manual.md)')
                   return
                end if
             case default
                call usage_problem(status, 'unknown solver '''//val//''' (auto, cholmod, umfpack, lapack, mumps, mumps-ldlt)')
                return
             end select
          case ('--formulation')
             select case (to_lower(val))
             case ('transform')
                opts%formulation = FORM_TRANSFORM
             case ('penalty')
                opts%formulation = FORM_PENALTY
             case default
                call usage_problem(status, 'unknown formulation '''//val//''' (transform, penalty)')
                return
             end select
          case ('--condense')
             select case (to_lower(val))
             case ('yes')
                opts%condense = CONDENSE_YES
             case ('no')
                opts%condense = CONDENSE_NO
             case ('auto')
                opts%condense = CONDENSE_AUTO
             case default
                call usage_problem(status, 'unknown condensation '''//val//''' (yes, no, auto)')
                return
             end select
          case ('--levels')
             select case (to_lower(val))
             case ('yes')
                opts%levels = LEVELS_YES
             case ('no')
                opts%levels = LEVELS_NO
             case ('auto')
                opts%levels = LEVELS_AUTO
             case default
                call usage_problem(status, 'unknown --levels '''//val//''' (yes, no, auto)')
                return
             end select
          case ('--twins')
             opts%twins = yes_no(val, '--twins', status)
             if (status >= 0) return
          case ('--huge-pages')
             call huge_pages_enable(yes_no(val, '--huge-pages', status))
             if (status >= 0) return
          case ('--reuse-memory')
             call reuse_memory_enable(yes_no(val, '--reuse-memory', status))
             if (status >= 0) return
          case ('--export-matrix')
             opts%export_matrix = val
          case ('--library')
             opts%library = val
          case ('--vtk')
             if (len(vtk_path_problem(val)) > 0) then
                call usage_problem(status, vtk_path_problem(val))
                return
             end if
             vtk_file = val
          end select
       case default
          if (len(arg) > 1) then
             if (arg(1:1) == '-') then
                call usage_problem(status, 'unknown option '//arg)
                return
             end if
          end if
          if (allocated(deck)) then
             call usage_problem(status, 'more than one deck given')
             return
          end if
          deck = arg
       end select
    end do
    demo = .not. allocated(deck)
    if (demo) then
       inquire (file=DEMO_DECK_SOURCE, exist=exists)
       if (exists) then
          deck = DEMO_DECK_SOURCE
       else
          deck = DEMO_DECK_INSTALLED
       end if
       if (.not. allocated(listing)) listing = 'demo.lst'
       write (output_unit, '(a)') 'superjoin '//SUPERJOIN_VERSION//': linear statics; a drop-in for CalculiX: '// &
            'superjoin -i JOB reads JOB.inp and writes JOB.dat, JOB.frd, JOB.sta (superjoin --help)'
       if (.not. opts%quiet) write (error_unit, '(a)') 'superjoin: no deck given: solving the bundled demo deck '// &
            deck//'; listing: '//listing//' (relative to the current directory)'
    end if
    inquire (file=deck, exist=exists)
    if (.not. exists .and. .not. allocated(job)) then
       ! ccx JOB, CalculiX's form without -i (PrePoMax runs it so): JOB.inp when JOB is no file
       inquire (file=deck//'.inp', exist=exists)
       if (exists) then
          job = job_name(deck)
          deck = job//'.inp'
       end if
    end if
    if (.not. exists) then
       write (error_unit, '(a)') deck//': error: cannot open deck'
       status = EXIT_IO
       return
    end if
    if (.not. allocated(listing)) listing = default_listing(deck)
  end subroutine parse_command_line

  function get_arg(i) result(arg)
    integer, intent(in) :: i
    character(:), allocatable :: arg
    integer :: length
    call get_command_argument(i, length=length)
    allocate (character(len=length) :: arg)
    if (length > 0) call get_command_argument(i, arg)
  end function get_arg

  function job_name(arg) result(job)
    !! The job of -i JOB: without blanks around it and without a trailing .inp.
    character(*), intent(in) :: arg
    character(:), allocatable :: job
    job = trim(adjustl(arg))
    if (len(job) > 4) then
       if (to_lower(job(len(job) - 3:)) == '.inp') job = job(1:len(job) - 4)
    end if
  end function job_name

  function default_listing(path) result(lst)
    !! DECK with its extension replaced by .lst.
    character(*), intent(in) :: path
    character(:), allocatable :: lst
    integer :: dot, slash
    dot = index(path, '.', back=.true.)
    slash = index(path, '/', back=.true.)
    if (dot > slash + 1) then
       lst = path(1:dot - 1)//'.lst'
    else
       lst = path//'.lst'
    end if
  end function default_listing

end program superjoin_main
