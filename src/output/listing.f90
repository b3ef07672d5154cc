module superjoin_output_listing
  !! The fixed-format listing: the same bytes for the same deck on every run.
  !! Written to a temporary name and renamed only when complete.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE, LINK_RIGID, &
       RIGID_ELIMINATE
  use superjoin_model_results, only: results_t, step_results_t
  use superjoin_utils_process, only: temp_register, temp_unregister
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: chop
  use superjoin_output_listing_tables, only: node_tables, element_tables, contact_table
  use superjoin_config, only: SUPERJOIN_VERSION
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory
  use superjoin_output_requests, only: write_print_requests
  use superjoin_output_section_print, only: write_section_prints
  use superjoin_model_request_masks, only: has_requests
  use superjoin_output_envelope, only: write_envelope
  implicit none (type, external)
  private

  character(*), parameter :: RULE = repeat('=', 100)
  character(*), parameter :: FMT_EQUILIBRIUM = '(2x,a10,3(1x,es14.6e3),1x,es13.2e3)'

  public :: write_listing

contains

  subroutine write_listing(path, model, res, error)
    !! Write the listing of a solved model to path (atomically).
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    integer :: is, stat
    character(:), allocatable :: tmp

    tmp = path//'.tmp'
    allocate (lu, stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the listing buffer', int(storage_size(lu)/8, i8))
       return
    end if
    call temp_register(tmp)
    call lu%open(tmp, error)
    if (allocated(error)) then
       call temp_unregister()
       return
    end if
    call header(lu, model, res)
    do is = 1, size(model%steps)
       call step_block(lu, model, res, is)
       if (allocated(res%fields%steps(is)%failure)) cycle
       call write_print_requests(lu, model, res%fields, is)
       call write_section_prints(lu, model, res%fields, is)
    end do
    call write_envelope(lu, model, res)
    call lu%line(RULE)
    call lu%line('END OF LISTING')
    call lu%commit(tmp, path, 'listing ', error)
  end subroutine write_listing

  subroutine header(lu, model, res)
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer :: i, isub, nnode, nelem, nsets
    character(len=200) :: hline

    call lu%line(RULE)
    call lu%line('superjoin '//SUPERJOIN_VERSION//'  linear statics of substructures joined by contact elements')
    call lu%line(RULE)
    call lu%line('TITLE')
    if (allocated(model%heading)) then
       do i = 1, size(model%heading)
          call lu%line('  '//model%heading(i)%s)
       end do
    end if
    call lu%line('')
    nnode = 0
    nelem = 0
    do isub = 1, size(model%subs)
       nnode = nnode + model%subs(isub)%nnode
       nelem = nelem + model%subs(isub)%nelem
    end do
    call lu%line('MODEL')
    call count_line(lu, 'substructures', int(size(model%subs), i8))
    call count_line(lu, 'nodes', int(nnode, i8))
    call count_line(lu, 'elements', int(nelem, i8))
    call count_line(lu, 'contact cards', int(size(model%contacts), i8))
    call count_line(lu, 'contact elements', int(size(model%links), i8))
    call count_line(lu, 'supported DOFs', int(size(model%supports), i8))
    call count_line(lu, 'load steps', int(count(model%steps%combination == 0), i8))
    if (any(model%steps%combination > 0)) &
         call count_line(lu, 'load combinations', int(count(model%steps%combination > 0), i8))
    if (any(model%steps%procedure_card)) &
         call count_line(lu, 'of which CalculiX rules (*STATIC)', int(count(model%steps%procedure_card), i8))
    call count_line(lu, 'active DOFs', res%summary%nphys)
    call count_line(lu, 'reduced unknowns', res%summary%ncol)
    call count_line(lu, '  of which relative (delta)', res%summary%ndelta)
    call count_line(lu, 'equations', res%summary%neq)
    if (res%summary%matrix_nnz >= 0) then
       call count_line(lu, 'matrix nonzeros (upper)', res%summary%matrix_nnz)
    else   ! several MPI processes, each handing MUMPS its own term (analysis/distributed)
       write (hline, '(2x,a34,1x,a)') field('matrix nonzeros (upper)', 34), 'n/a (summed by MUMPS from '// &
            'each MPI process''s own terms)'
       call lu%line(trim(hline))
    end if
    call count_line(lu, 'factor nonzeros', res%summary%factor_nnz)
    write (hline, '(2x,a34,1x,a)') field('formulation', 34), res%summary%formulation// &
         merge(' (RIGID eliminated exactly)', ' (RIGID as LARGE stiffness)', &
         model%controls%rigid == RIGID_ELIMINATE .and. res%summary%formulation == 'TRANSFORM')
    call lu%line(trim(hline))
    write (hline, '(2x,a34,1x,a)') field('solver', 34), res%summary%solver_name
    call lu%line(trim(hline))
    write (hline, '(2x,a34,1x,a)') field('ordering', 34), res%summary%ordering
    call lu%line(trim(hline))
    call lu%line('')

    call lu%line('SUBSTRUCTURES')
    write (hline, '(2x,a20,6a10)') 'name                ', '     nodes', '  elements', '      sets', '      DOFs', &
         '  interior', '  boundary'
    call lu%line(trim(hline))
    do isub = 1, size(model%subs)
       associate (s => model%subs(isub))
         nsets = 0
         if (allocated(s%nsets)) nsets = nsets + size(s%nsets)
         if (allocated(s%elsets)) nsets = nsets + size(s%elsets)
         write (hline, '(2x,a20,6i10)') field(s%name, 20), s%nnode, s%nelem, nsets, res%summary%sub_dofs(isub), &
              res%summary%sub_dofs(isub) - res%summary%sub_boundary(isub), res%summary%sub_boundary(isub)
         call lu%line(trim(hline))
       end associate
    end do
    call lu%line('')
    if (allocated(res%log%partition)) then   ! MPI runs on several processes only
       do i = 1, size(res%log%partition)
          call lu%line(res%log%partition(i)%s)
       end do
       call lu%line('')
    end if

    call lu%line('CONTACT ELEMENTS AND SUPPORTS')
    call count_line(lu, 'contact units transformed', int(res%summary%n_tree, i8))
    call count_line(lu, 'contact units assembled plainly', int(res%summary%n_plain, i8))
    call count_line(lu, 'support units', int(res%summary%n_support_units, i8))
    if (allocated(res%log%notes)) then
       do i = 1, size(res%log%notes)
          call lu%line('  '//res%log%notes(i)%s)
       end do
    end if
    call lu%line('')
    call model_warnings(lu, res)
  end subroutine header

  subroutine model_warnings(lu, res)
    !! The warnings on the model itself (the deck's checks, which arise in no
    !! step), once before the steps; a step's own are in its NUMERICAL HEALTH.
    type(text_buffer_t), intent(inout) :: lu
    type(results_t), intent(in) :: res
    integer :: k
    if (.not. allocated(res%log%warnings)) return
    if (all([(allocated(res%log%warnings(k)%steps), k=1, size(res%log%warnings))])) return
    call lu%line('WARNINGS ON THE MODEL (a step''s own warnings are in its NUMERICAL HEALTH block)')
    do k = 1, size(res%log%warnings)
       if (.not. allocated(res%log%warnings(k)%steps)) call lu%line('  '//'WARNING: '//res%log%warnings(k)%s)
    end do
    call lu%line('')
  end subroutine model_warnings

  subroutine count_line(lu, label, n)
    type(text_buffer_t), intent(inout) :: lu
    character(*), intent(in) :: label
    integer(i8), intent(in) :: n
    character(len=34) :: lab
    character(len=80) :: hline
    lab = label
    write (hline, '(2x,a34,1x,i0)') lab, n
    call lu%line(trim(hline))
  end subroutine count_line

  subroutine kept_line(lu, model, is)
    !! What step is continues of the step before it in the deck (OP=MOD, or
    !! CalculiX's rule in a step with *STATIC), when anything.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    character(:), allocatable :: what
    associate (step => model%steps(is))
      what = ''
      if (step%kept_cloads > 0) what = what//', '//itoa(step%kept_cloads)//' concentrated load(s)'
      if (step%kept_dloads > 0) what = what//', '//itoa(step%kept_dloads)//' distributed load(s)'
      if (step%kept_mloads > 0) what = what//', '//itoa(step%kept_mloads)//' matrix load(s)'
      if (step%kept_temperatures) what = what//', the nodal temperatures'
      if (len(what) == 0) return
      call lu%line('  kept from step '//step%kept_from//' (OP=MOD, the default in a step with '// &
           '*STATIC): '//what(3:))
      call lu%line('')
    end associate
  end subroutine kept_line

  subroutine step_block(lu, model, res, is)
    !! One step: the standard tables (not in a deck with output requests, whose
    !! REQUESTED OUTPUT section prints what they ask for), contact forces,
    !! equilibrium and health.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: is
    integer :: k, dirs
    real(wp) :: scale
    character(len=300) :: hline
    character(len=3), parameter :: DIR_NAMES(6) = ['FX ', 'FY ', 'FZ ', 'MX ', 'MY ', 'MZ ']
    logical :: tables

    tables = .not. has_requests(model)
    associate (st => res%fields%steps(is))
      call lu%line(RULE)
      call lu%line('STEP '//itoa(is)//'  '//model%steps(is)%name)
      call lu%line(RULE)
      call kept_line(lu, model, is)
      call stiffness_lines(lu, model, is)
      if (allocated(st%failure)) then
         call failure_lines(lu, st%failure)
         return
      end if

      if (tables) call node_tables(lu, model, res, is)

      call contact_table(lu, model, res, is)

      if (tables) call element_tables(lu, model, res, is)

      call lu%line('EQUILIBRIUM (resultants about the origin)')
      write (hline, '(2x,a10,4a15)') 'direction ', '        applied', '      reactions', '            sum', &
           '       relative'
      call lu%line(trim(hline))
      ! The scale of the table: the resultants, or the largest single support reaction when the
      ! reactions balance each other (a held, heated body; a pretension): their resultant is then
      ! round-off, and a sum relative to it would print noise as a relative error of order 1.
      scale = max(maxval(abs(st%applied)), maxval(abs(st%reaction)), largest_reaction(st))
      do dirs = 1, 6
         write (hline, FMT_EQUILIBRIUM) field(DIR_NAMES(dirs), 10), chop(st%applied(dirs), scale), &
              chop(st%reaction(dirs), scale), chop(st%applied(dirs) + st%reaction(dirs), scale), &
              rel(st%applied(dirs) + st%reaction(dirs), scale)
         call lu%line(trim(hline))
      end do
      call lu%line('')

      call lu%line('NUMERICAL HEALTH')
      write (hline, '(2x,a30,es10.2e3)') 'relative residual             ', st%residual
      call lu%line(trim(hline))
      if (st%refine_tried > 0) then
         write (hline, '(2x,a30,es10.2e3,a)') 'residual before refinement    ', st%residual0, &
              ' ('//itoa(st%refinements)//' refinement steps kept of '//itoa(st%refine_tried)//' tried)'
         call lu%line(trim(hline))
      end if
      write (hline, '(2x,a30,es10.2e3)') 'EPSILON (energy error)        ', st%epsilon
      call lu%line(trim(hline))
      ! of the matrix this step was solved with (each group of steps has its own)
      block
        character(:), allocatable :: at
        at = 'n/a'
        if (allocated(st%maxratio_at)) at = st%maxratio_at
        write (hline, '(2x,a30,es10.2e3,a)') 'MAXRATIO                      ', st%maxratio, '  at '//at
      end block
      call lu%line(trim(hline))
      write (hline, '(2x,a30,es10.2e3)') 'condition estimate (1-norm)   ', st%cond_est
      if (st%cond_bound) hline = trim(hline)//'  a lower bound only (notes)'
      call lu%line(trim(hline))
      do k = 1, size(res%log%warnings)
         if (.not. allocated(res%log%warnings(k)%steps)) cycle   ! the model's: in the header
         if (res%log%warnings(k)%steps(is)) call lu%line('  '//'WARNING: '//res%log%warnings(k)%s)
      end do
      call lu%line('')
    end associate
  end subroutine step_block

  subroutine stiffness_lines(lu, model, is)
    !! The contact stiffnesses step is sets (*CHANGE CONTACT, one step of a
    !! SWEEP each): contact, nodes, DOF and g (0: released) per changed DOF.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    character(len=300) :: hline
    integer :: i, d
    if (.not. allocated(model%steps(is)%link_overrides)) return
    if (size(model%steps(is)%link_overrides) == 0) return
    call lu%line('CONTACT STIFFNESSES OF THIS STEP (*CHANGE CONTACT; g = 0: released)')
    write (hline, '(2x,a16,2a10,a6,a15)') 'contact         ', '    master', '     slave', '   dof', '              g'
    call lu%line(trim(hline))
    do i = 1, size(model%steps(is)%link_overrides)
       associate (o => model%steps(is)%link_overrides(i), lk => model%links(model%steps(is)%link_overrides(i)%link))
         associate (ct => model%contacts(lk%contact))
           do d = 1, NDOF_NODE
              if (.not. o%dofs(d)) cycle
              call lu%put('  ')
              call lu%put_field(ct%name, 16)
              call lu%put_int(int(model%subs(ct%master_sub)%node_id(lk%master_node), i8), 10)
              call lu%put_int(int(model%subs(ct%slave_sub)%node_id(lk%slave_node), i8), 10)
              call lu%put_int(int(d, i8), 6)
              if (o%state(d) == LINK_RIGID) then
                 call lu%put('          RIGID')
              else
                 call lu%put_es(o%g(d))
              end if
              call lu%newline()
           end do
         end associate
       end associate
    end do
    call lu%line('')
  end subroutine stiffness_lines

  subroutine failure_lines(lu, message)
    !! A step that could not be solved (the run exits 3): its message, line by
    !! line, in place of its results.
    type(text_buffer_t), intent(inout) :: lu
    character(*), intent(in) :: message
    integer :: i, j
    call lu%line('NOT SOLVED (no results for this step; the run exits with status 3)')
    i = 1
    do
       j = index(message(i:), new_line('a'))
       if (j == 0) exit
       call lu%line('  '//message(i:i + j - 2))
       i = i + j
    end do
    call lu%line('  '//message(i:))
    call lu%line('')
  end subroutine failure_lines

  pure function field(text, n) result(f)
    !! Text left-justified in a field of width n (cut if longer).
    character(*), intent(in) :: text
    integer, intent(in) :: n
    character(len=n) :: f
    f = text
  end function field

  pure function largest_reaction(st) result(r)
    !! The largest magnitude of one support reaction of a step (0 without supports).
    type(step_results_t), intent(in) :: st
    real(wp) :: r
    integer :: k
    r = 0.0_wp
    if (.not. allocated(st%reactions)) return
    do k = 1, size(st%reactions)
       r = max(r, abs(st%reactions(k)%force))
    end do
  end function largest_reaction

  pure function rel(x, scale) result(y)
    !! |x| relative to scale (0 when scale is 0).
    real(wp), intent(in) :: x, scale
    real(wp) :: y
    y = 0.0_wp
    if (scale > 0.0_wp) y = abs(x)/scale
  end function rel
end module superjoin_output_listing
