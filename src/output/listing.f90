module superjoin_output_listing
  !! The fixed-format listing: the same bytes for the same deck on every run.
  !! Written to a temporary name and renamed only when complete.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE, LINK_RIGID, &
       RIGID_ELIMINATE, ET_CPS3, ET_CPS4, ET_CPE3, ET_CPE4
  use superjoin_elements, only: is_plate_type
  use superjoin_analysis_results, only: results_t
  use superjoin_utils_process, only: temp_register, temp_unregister
  use superjoin_output_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop
  use superjoin_config, only: SUPERJOIN_VERSION
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory
  use superjoin_output_requests, only: write_print_requests
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
       call write_print_requests(lu, model, res, is)
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
    call count_line(lu, 'active DOFs', res%nphys)
    call count_line(lu, 'reduced unknowns', res%ncol)
    call count_line(lu, '  of which relative (delta)', res%ndelta)
    call count_line(lu, 'equations', res%neq)
    call count_line(lu, 'matrix nonzeros (upper)', res%matrix_nnz)
    call count_line(lu, 'factor nonzeros', res%factor_nnz)
    write (hline, '(2x,a34,1x,a)') field('formulation', 34), res%formulation// &
         merge(' (RIGID eliminated exactly)', ' (RIGID as LARGE stiffness)', &
         model%controls%rigid == RIGID_ELIMINATE .and. res%formulation == 'TRANSFORM')
    call lu%line(trim(hline))
    write (hline, '(2x,a34,1x,a)') field('solver', 34), res%solver_name
    call lu%line(trim(hline))
    write (hline, '(2x,a34,1x,a)') field('ordering', 34), res%ordering
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
         write (hline, '(2x,a20,6i10)') field(s%name, 20), s%nnode, s%nelem, nsets, res%sub_dofs(isub), &
              res%sub_dofs(isub) - res%sub_boundary(isub), res%sub_boundary(isub)
         call lu%line(trim(hline))
       end associate
    end do
    call lu%line('')

    call lu%line('CONTACT ELEMENTS AND SUPPORTS')
    call count_line(lu, 'contact units transformed', int(res%n_tree, i8))
    call count_line(lu, 'contact units assembled plainly', int(res%n_plain, i8))
    call count_line(lu, 'support units', int(res%n_support_units, i8))
    if (allocated(res%notes)) then
       do i = 1, size(res%notes)
          call lu%line('  '//res%notes(i)%s)
       end do
    end if
    call lu%line('')
  end subroutine header

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

  subroutine step_block(lu, model, res, is)
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: is
    integer :: isub, d, k, il, ie, dirs
    integer(ip) :: n
    integer(i8) :: v, iel
    real(wp) :: scale, dscale, vals(NDOF_NODE)
    character(len=300) :: hline
    character(len=3), parameter :: DIR_NAMES(6) = ['FX ', 'FY ', 'FZ ', 'MX ', 'MY ', 'MZ ']
    logical :: has_bars, has_plates

    has_bars = .false.
    has_plates = .false.
    do isub = 1, size(model%subs)
       do ie = 1, model%subs(isub)%nelem
          if (is_plate_type(model%subs(isub)%elem_type(ie))) then
             has_plates = .true.
          else
             has_bars = .true.
          end if
       end do
    end do

    associate (st => res%steps(is))
      call lu%line(RULE)
      call lu%line('STEP '//itoa(is)//'  '//model%steps(is)%name)
      call lu%line(RULE)

      call lu%line('DISPLACEMENTS (global axes)')
      write (hline, '(2x,a20,a10,6a15)') 'substructure        ', '      node', '             u1', &
           '             u2', '             u3', '            ur1', '            ur2', '            ur3'
      call lu%line(trim(hline))
      scale = max(0.0_wp, maxval(abs(res%u(:, is))))
      do isub = 1, size(model%subs)
         do n = 1, model%subs(isub)%nnode
            v = res%vertex_offset(isub) + n
            if (.not. any(res%has_dof(:, v))) cycle
            do d = 1, NDOF_NODE
               vals(d) = chop(res%u(NDOF_NODE*(v - 1) + d, is), scale)
            end do
            call lu%put('  ')
            call lu%put_field(model%subs(isub)%name, 20)
            call lu%put_int(int(model%subs(isub)%node_id(n), i8), 10)
            do d = 1, NDOF_NODE
               call lu%put_es(vals(d))
            end do
            call lu%newline()
         end do
      end do
      call lu%line('')

      call lu%line('SUPPORT REACTIONS (force the support exerts on the structure)')
      write (hline, '(2x,a20,a10,a6,a15)') 'substructure        ', '      node', '   dof', '          force'
      call lu%line(trim(hline))
      scale = max(0.0_wp, maxval(abs(st%reactions(:)%force)))
      do k = 1, size(st%reactions)
         associate (rc => st%reactions(k))
           call lu%put('  ')
           call lu%put_field(model%subs(rc%sub)%name, 20)
           call lu%put_int(int(model%subs(rc%sub)%node_id(rc%node), i8), 10)
           call lu%put_int(int(rc%dof, i8), 6)
           call lu%put_es(chop(rc%force, scale))
           call lu%newline()
         end associate
      end do
      call lu%line('')

      call lu%line('CONTACT FORCES (contact frame; delta = u_slave - u_master, force on the master)')
      write (hline, '(2x,a16,2a10,a6,2a15)') 'contact         ', '    master', '     slave', '   dof', &
           '          delta', '          force'
      call lu%line(trim(hline))
      scale = max(0.0_wp, maxval(abs(st%link_force)))
      dscale = max(0.0_wp, maxval(abs(st%link_delta)))
      do il = 1, size(model%links)
         associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
           do d = 1, NDOF_NODE
              if (.not. res%link_used(d, il)) cycle
              call lu%put('  ')
              call lu%put_field(ct%name, 16)
              call lu%put_int(int(model%subs(ct%master_sub)%node_id(lk%master_node), i8), 10)
              call lu%put_int(int(model%subs(ct%slave_sub)%node_id(lk%slave_node), i8), 10)
              call lu%put_int(int(d, i8), 6)
              call lu%put_es(chop(st%link_delta(d, il), dscale))
              call lu%put_es(chop(st%link_force(d, il), scale))
              if (lk%state(d) == LINK_RIGID) call lu%put('   RIGID')
              call lu%newline()
           end do
         end associate
      end do
      call lu%line('')

      if (has_bars) then
         call lu%line('ELEMENT END FORCES (local axes; forces the nodes exert on the element)')
         write (hline, '(2x,a20,a10,a6,a4,6a15)') 'substructure        ', '   element', '  type', ' end', &
              '              n', '             vy', '             vz', '              t', '             my', &
              '             mz'
         call lu%line(trim(hline))
         scale = max(0.0_wp, maxval(abs(res%elem_force(:, :, :, is))))
         do isub = 1, size(model%subs)
            do ie = 1, model%subs(isub)%nelem
               if (is_plate_type(model%subs(isub)%elem_type(ie))) cycle
               iel = res%elem_offset(isub) + ie
               do k = 1, 2
                  call element_prefix(lu, model, isub, ie, 2)
                  call lu%put_int(int(k, i8), 4)
                  do d = 1, 6
                     call lu%put_es(chop(res%elem_force(d, k, iel, is), scale))
                  end do
                  call lu%newline()
               end do
            end do
         end do
         call lu%line('')
      end if
      if (has_plates) call plate_block(lu, model, res, is)

      call lu%line('EQUILIBRIUM (resultants about the origin)')
      write (hline, '(2x,a10,4a15)') 'direction ', '        applied', '      reactions', '            sum', &
           '       relative'
      call lu%line(trim(hline))
      scale = max(maxval(abs(st%applied)), maxval(abs(st%reaction)))
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
      write (hline, '(2x,a30,es10.2e3,a)') 'MAXRATIO                      ', res%maxratio, '  at '//res%maxratio_at
      call lu%line(trim(hline))
      write (hline, '(2x,a30,es10.2e3)') 'condition estimate (1-norm)   ', res%cond_est
      call lu%line(trim(hline))
      do k = 1, size(res%warnings)
         call lu%line('  '//'WARNING: '//res%warnings(k)%s)
      end do
      call lu%line('')
    end associate
  end subroutine step_block

  subroutine plate_block(lu, model, res, is)
    !! Resultants per unit length of the plane and shell elements at their
    !! centroids, and the stresses at the top and bottom surfaces (plane stress:
    !! mid-surface only), element frame.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: is
    integer :: isub, ie, d, k, nsurf
    integer(i8) :: iel
    logical :: plane_strain
    real(wp) :: scale(2), t, sig(4)
    character(len=300) :: hline
    character(len=6), parameter :: SURFACES(3) = ['top   ', 'bottom', 'mid   ']

    call lu%line('PLATE AND SHELL RESULTANTS (element frame, per unit length, at the centroid)')
    write (hline, '(2x,a20,a10,a6,6a15)') 'substructure        ', '   element', '  type', &
         '             nx', '             ny', '            nxy', '             mx', '             my', &
         '            mxy'
    call lu%line(trim(hline))
    scale(1) = max(0.0_wp, maxval(abs(res%plate(1:3, :, is))))
    scale(2) = max(0.0_wp, maxval(abs(res%plate(4:6, :, is))))
    do isub = 1, size(model%subs)
       do ie = 1, model%subs(isub)%nelem
          if (.not. is_plate_type(model%subs(isub)%elem_type(ie))) cycle
          iel = res%elem_offset(isub) + ie
          call element_prefix(lu, model, isub, ie, 2)
          do d = 1, 6
             call lu%put_es(chop(res%plate(d, iel, is), scale((d + 2)/3)))
          end do
          call lu%newline()
       end do
    end do
    call lu%line('')

    call lu%line('PLATE AND SHELL STRESSES (element frame, at the centroid; top is +t/2 along the normal)')
    write (hline, '(2x,a20,a10,a6,a8,4a15)') 'substructure        ', '   element', '  type', ' surface', &
         '             sx', '             sy', '            sxy', '     von Mises'
    call lu%line(trim(hline))
    do isub = 1, size(model%subs)
       do ie = 1, model%subs(isub)%nelem
          if (.not. is_plate_type(model%subs(isub)%elem_type(ie))) cycle
          iel = res%elem_offset(isub) + ie
          t = model%subs(isub)%sections(model%subs(isub)%elem_section(ie))%thickness
          nsurf = 2
          if (model%subs(isub)%elem_type(ie) == ET_CPS3 .or. model%subs(isub)%elem_type(ie) == ET_CPS4) nsurf = 1
          plane_strain = model%subs(isub)%elem_type(ie) == ET_CPE3 .or. model%subs(isub)%elem_type(ie) == ET_CPE4
          if (plane_strain) nsurf = 1
          do k = 1, nsurf
             sig(1:3) = res%plate(1:3, iel, is)/t
             ! (m/t)/t: no t**2 to underflow
             if (nsurf == 2) sig(1:3) = sig(1:3) + merge(1.0_wp, -1.0_wp, k == 1)*6.0_wp*(res%plate(4:6, iel, is)/t)/t
             sig(4) = von_mises(sig(1:3))
             if (plane_strain) then   ! with sz = nu (sx + sy)
                associate (sec => model%subs(isub)%sections(model%subs(isub)%elem_section(ie)))
                  sig(4) = von_mises_3(sig(1:3), model%materials(sec%material)%nu*(sig(1) + sig(2)))
                end associate
             end if
             call element_prefix(lu, model, isub, ie, 2)
             if (nsurf == 1) then
                call lu%put_field('  '//SURFACES(3), 8)
             else
                call lu%put_field('  '//SURFACES(k), 8)
             end if
             do d = 1, 4
                call lu%put_es(chop(sig(d), maxval(abs(sig))))
             end do
             call lu%newline()
          end do
       end do
    end do
    call lu%line('')
  end subroutine plate_block

  pure function von_mises(sig) result(vm)
    !! Von Mises stress of a plane stress state (sx, sy, sxy), scaled so that
    !! the squares cannot overflow.
    real(wp), intent(in) :: sig(3)
    real(wp) :: vm, sc, a(3)
    sc = maxval(abs(sig))
    vm = 0.0_wp
    if (sc == 0.0_wp) return
    a = sig/sc
    vm = sc*sqrt(max(0.0_wp, a(1)**2 - a(1)*a(2) + a(2)**2 + 3.0_wp*a(3)**2))
  end function von_mises

  pure function von_mises_3(sig, sz) result(vm)
    !! Von Mises stress of (sx, sy, sxy) with a normal stress sz (plane strain),
    !! scaled so that the squares cannot overflow.
    real(wp), intent(in) :: sig(3), sz
    real(wp) :: vm, sc, a(3), c
    sc = max(maxval(abs(sig)), abs(sz))
    vm = 0.0_wp
    if (sc == 0.0_wp) return
    a = sig/sc
    c = sz/sc
    vm = sc*sqrt(max(0.0_wp, ((a(1) - a(2))**2 + (a(2) - c)**2 + (c - a(1))**2)/2 + 3.0_wp*a(3)**2))
  end function von_mises_3

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
