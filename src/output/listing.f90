module superjoin_output_listing
  !! The fixed-format listing: the same bytes for the same deck on every run.
  !! Written to a temporary name and renamed only when complete.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE, LINK_RIGID, ELEMENT_TYPE_NAMES, &
       RIGID_ELIMINATE
  use superjoin_analysis_results, only: results_t
  use superjoin_output_posix, only: rename_file, remove_file
  use superjoin_config, only: SUPERJOIN_VERSION
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  real(wp), parameter, public :: CHOP_FRACTION = 1.0e-13_wp
    !! Values below this fraction of the largest value of their table print as zero.
  character(*), parameter :: RULE = repeat('=', 100)
  character(*), parameter :: FMT_REAL = '(1x,es14.6e3)'

  public :: write_listing

contains

  subroutine write_listing(path, model, res, error)
    !! Write the listing of a solved model to path (atomically).
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    integer :: lu, ios, is
    character(:), allocatable :: tmp

    tmp = path//'.tmp'
    open (newunit=lu, file=tmp, status='replace', action='write', iostat=ios)
    if (ios /= 0) then
       call fatal_error(error, EXIT_IO, 'error: cannot write listing '//path)
       return
    end if
    call header(lu, model, res)
    do is = 1, size(model%steps)
       call step_block(lu, model, res, is)
    end do
    write (lu, '(a)', iostat=ios) RULE
    write (lu, '(a)', iostat=ios) 'END OF LISTING'
    close (lu, iostat=ios)
    if (ios /= 0) then
       call remove_file(tmp)
       call fatal_error(error, EXIT_IO, 'error: failed writing listing '//path)
       return
    end if
    call rename_file(tmp, path, error)
  end subroutine write_listing

  subroutine header(lu, model, res)
    integer, intent(in) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer :: i, isub, nnode, nelem, nsets
    character(len=200) :: line

    write (lu, '(a)') RULE
    write (lu, '(a)') 'superjoin '//SUPERJOIN_VERSION//'  linear statics of substructures joined by contact elements'
    write (lu, '(a)') RULE
    write (lu, '(a)') 'TITLE'
    if (allocated(model%heading)) then
       do i = 1, size(model%heading)
          write (lu, '(2x,a)') model%heading(i)%s
       end do
    end if
    write (lu, '(a)') ''
    nnode = 0
    nelem = 0
    do isub = 1, size(model%subs)
       nnode = nnode + model%subs(isub)%nnode
       nelem = nelem + model%subs(isub)%nelem
    end do
    write (lu, '(a)') 'MODEL'
    call count_line(lu, 'substructures', int(size(model%subs), i8))
    call count_line(lu, 'nodes', int(nnode, i8))
    call count_line(lu, 'elements', int(nelem, i8))
    call count_line(lu, 'contact cards', int(size(model%contacts), i8))
    call count_line(lu, 'contact elements', int(size(model%links), i8))
    call count_line(lu, 'supported DOFs', int(size(model%supports), i8))
    call count_line(lu, 'load steps', int(size(model%steps), i8))
    call count_line(lu, 'active DOFs', res%nphys)
    call count_line(lu, 'reduced unknowns', res%ncol)
    call count_line(lu, '  of which relative (delta)', res%ndelta)
    call count_line(lu, 'equations', res%neq)
    call count_line(lu, 'matrix nonzeros (upper)', res%matrix_nnz)
    call count_line(lu, 'factor nonzeros', res%factor_nnz)
    write (lu, '(2x,a34,1x,a)') field('formulation', 34), res%formulation// &
         merge(' (RIGID eliminated exactly)', ' (RIGID as LARGE stiffness)', &
         model%controls%rigid == RIGID_ELIMINATE .and. res%formulation == 'TRANSFORM')
    write (lu, '(2x,a34,1x,a)') field('solver', 34), res%solver_name
    write (lu, '(2x,a34,1x,a)') field('ordering', 34), res%ordering
    write (lu, '(a)') ''

    write (lu, '(a)') 'SUBSTRUCTURES'
    write (lu, '(2x,a20,6a10)') 'name                ', '     nodes', '  elements', '      sets', '      DOFs', &
         '  interior', '  boundary'
    do isub = 1, size(model%subs)
       associate (s => model%subs(isub))
         nsets = 0
         if (allocated(s%nsets)) nsets = nsets + size(s%nsets)
         if (allocated(s%elsets)) nsets = nsets + size(s%elsets)
         write (line, '(2x,a20,6i10)') field(s%name, 20), s%nnode, s%nelem, nsets, res%sub_dofs(isub), &
              res%sub_dofs(isub) - res%sub_boundary(isub), res%sub_boundary(isub)
         write (lu, '(a)') trim(line)
       end associate
    end do
    write (lu, '(a)') ''

    write (lu, '(a)') 'CONTACT ELEMENTS AND SUPPORTS'
    call count_line(lu, 'contact units transformed', int(res%n_tree, i8))
    call count_line(lu, 'contact units assembled plainly', int(res%n_plain, i8))
    call count_line(lu, 'support units', int(res%n_support_units, i8))
    if (allocated(res%notes)) then
       do i = 1, size(res%notes)
          write (lu, '(2x,a)') res%notes(i)%s
       end do
    end if
    write (lu, '(a)') ''
  end subroutine header

  subroutine count_line(lu, label, n)
    integer, intent(in) :: lu
    character(*), intent(in) :: label
    integer(i8), intent(in) :: n
    character(len=34) :: lab
    lab = label
    write (lu, '(2x,a34,1x,i0)') lab, n
  end subroutine count_line

  subroutine step_block(lu, model, res, is)
    integer, intent(in) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: is
    integer :: isub, d, k, il, ie, dirs
    integer(ip) :: n
    integer(i8) :: v, iel
    real(wp) :: scale, vals(NDOF_NODE)
    character(len=300) :: line
    character(len=3), parameter :: DIR_NAMES(6) = ['FX ', 'FY ', 'FZ ', 'MX ', 'MY ', 'MZ ']

    associate (st => res%steps(is))
      write (lu, '(a)') RULE
      write (lu, '(a)') 'STEP '//itoa(is)//'  '//model%steps(is)%name
      write (lu, '(a)') RULE

      write (lu, '(a)') 'DISPLACEMENTS (global axes)'
      write (lu, '(2x,a20,a10,6a15)') 'substructure        ', '      node', '             u1', &
           '             u2', '             u3', '            ur1', '            ur2', '            ur3'
      scale = max(0.0_wp, maxval(abs(res%u(:, is))))
      do isub = 1, size(model%subs)
         do n = 1, model%subs(isub)%nnode
            v = res%vertex_offset(isub) + n
            if (.not. any(res%has_dof(:, v))) cycle
            do d = 1, NDOF_NODE
               vals(d) = chop(res%u(NDOF_NODE*(v - 1) + d, is), scale)
            end do
            write (line, '(2x,a20,i10,6'//FMT_REAL//')') field(model%subs(isub)%name, 20), model%subs(isub)%node_id(n), vals
            write (lu, '(a)') trim(line)
         end do
      end do
      write (lu, '(a)') ''

      write (lu, '(a)') 'SUPPORT REACTIONS (force the support exerts on the structure)'
      write (lu, '(2x,a20,a10,a6,a15)') 'substructure        ', '      node', '   dof', '          force'
      scale = max(0.0_wp, maxval(abs(st%reactions(:)%force)))
      do k = 1, size(st%reactions)
         associate (rc => st%reactions(k))
           write (line, '(2x,a20,i10,i6,'//FMT_REAL//')') field(model%subs(rc%sub)%name, 20), &
                model%subs(rc%sub)%node_id(rc%node), rc%dof, chop(rc%force, scale)
           write (lu, '(a)') trim(line)
         end associate
      end do
      write (lu, '(a)') ''

      write (lu, '(a)') 'CONTACT FORCES (contact frame; delta = u_slave - u_master, force on the master)'
      write (lu, '(2x,a16,2a10,a6,2a15)') 'contact         ', '    master', '     slave', '   dof', &
           '          delta', '          force'
      scale = max(0.0_wp, maxval(abs(st%link_force)))
      do il = 1, size(model%links)
         associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
           do d = 1, NDOF_NODE
              if (.not. res%link_used(d, il)) cycle
              write (line, '(2x,a16,2i10,i6,2'//FMT_REAL//',a8)') field(ct%name, 16), &
                   model%subs(ct%master_sub)%node_id(lk%master_node), &
                   model%subs(ct%slave_sub)%node_id(lk%slave_node), d, &
                   chop(st%link_delta(d, il), max(0.0_wp, maxval(abs(st%link_delta)))), &
                   chop(st%link_force(d, il), scale), merge('  RIGID', '       ', lk%state(d) == LINK_RIGID)
              write (lu, '(a)') trim(line)
           end do
         end associate
      end do
      write (lu, '(a)') ''

      write (lu, '(a)') 'ELEMENT END FORCES (local axes; forces the nodes exert on the element)'
      write (lu, '(2x,a20,a10,a6,a4,6a15)') 'substructure        ', '   element', '  type', ' end', &
           '              n', '             vy', '             vz', '              t', '             my', &
           '             mz'
      scale = max(0.0_wp, maxval(abs(res%elem_force(:, :, :, is))))
      do isub = 1, size(model%subs)
         do ie = 1, model%subs(isub)%nelem
            iel = res%elem_offset(isub) + ie
            do k = 1, 2
               write (line, '(2x,a20,i10,a6,i4,6'//FMT_REAL//')') field(model%subs(isub)%name, 20), &
                    model%subs(isub)%elem_id(ie), ELEMENT_TYPE_NAMES(model%subs(isub)%elem_type(ie)), k, &
                    (chop(res%elem_force(d, k, iel, is), scale), d=1, 6)
               write (lu, '(a)') trim(line)
            end do
         end do
      end do
      write (lu, '(a)') ''

      write (lu, '(a)') 'EQUILIBRIUM (resultants about the origin)'
      write (lu, '(2x,a10,4a15)') 'direction ', '        applied', '      reactions', '            sum', &
           '       relative'
      scale = max(maxval(abs(st%applied)), maxval(abs(st%reaction)))
      do dirs = 1, 6
         write (line, '(2x,a10,3'//FMT_REAL//',1x,es13.2e3)') field(DIR_NAMES(dirs), 10), chop(st%applied(dirs), scale), &
              chop(st%reaction(dirs), scale), chop(st%applied(dirs) + st%reaction(dirs), scale), &
              rel(st%applied(dirs) + st%reaction(dirs), scale)
         write (lu, '(a)') trim(line)
      end do
      write (lu, '(a)') ''

      write (lu, '(a)') 'NUMERICAL HEALTH'
      write (lu, '(2x,a30,es10.2e3)') 'relative residual             ', st%residual
      if (st%refinements > 0) then
         write (lu, '(2x,a30,es10.2e3,a)') 'residual before refinement    ', st%residual0, &
              ' ('//itoa(st%refinements)//' refinement steps)'
      end if
      write (lu, '(2x,a30,es10.2e3)') 'EPSILON (energy error)        ', st%epsilon
      write (lu, '(2x,a30,es10.2e3,a)') 'MAXRATIO                      ', res%maxratio, '  at '//res%maxratio_at
      write (lu, '(2x,a30,es10.2e3)') 'condition estimate (1-norm)   ', res%cond_est
      do k = 1, size(res%warnings)
         write (lu, '(2x,a)') 'WARNING: '//res%warnings(k)%s
      end do
      write (lu, '(a)') ''
    end associate
  end subroutine step_block

  elemental function chop(x, scale) result(y)
    !! Round-off noise relative to the table's scale prints as zero.
    real(wp), intent(in) :: x, scale
    real(wp) :: y
    y = x
    if (abs(x) <= CHOP_FRACTION*scale) y = 0.0_wp
  end function chop

  pure function field(text, n) result(f)
    !! Text left-justified in a field of width n (cut if longer).
    character(*), intent(in) :: text
    integer, intent(in) :: n
    character(len=n) :: f
    f = text
  end function field

  pure function rel(x, scale) result(y)
    real(wp), intent(in) :: x, scale
    real(wp) :: y
    y = 0.0_wp
    if (scale > 0.0_wp) y = abs(x)/scale
  end function rel
end module superjoin_output_listing
