module superjoin_output_listing_tables
  !! The listing's long tables of a step: DISPLACEMENTS and SUPPORT REACTIONS,
  !! CONTACT FORCES, TRUSS AXIAL FORCES, ELEMENT END FORCES, PLATE AND SHELL RESULTANTS and
  !! STRESSES. The rows of a table over the nodes or the elements are a
  !! table_rows_t, which write_rows (output/rows) formats on two threads
  !! where it may: each row depends on its node, element or contact element
  !! alone.
  use, intrinsic :: iso_fortran_env, only: int8
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t, NDOF_NODE, ELEMENT_NODE_COUNT, LINK_RIGID
  use superjoin_model_results, only: results_t
  use superjoin_elements, only: plane_centroid_remainder
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop, element_kinds_t, element_kinds
  use superjoin_output_layout, only: displacement_columns, node_dof_mask, &
       has_node_frames, in_node_frame, REACTION_FRAME_NOTE, FRAME_MARK
  use superjoin_output_rows, only: row_source_t, write_rows, owner_of, step_owner
  implicit none (type, external)
  private

  integer, parameter :: TABLE_DISPLACEMENTS = 1, TABLE_END_FORCES = 2, TABLE_TRUSSES = 3, &
       TABLE_RESULTANTS = 4, TABLE_STRESSES = 5, TABLE_CONTACTS = 6
    !! the tables formatted a range of items at a time (table_rows_t%table)

  type, extends(row_source_t) :: table_rows_t
    !! One table of step `is`: what its rows need beyond the model and results.
     integer :: table = 0                       !! TABLE_DISPLACEMENTS, ...
     integer :: is = 0                          !! the step
     real(wp) :: scale(2) = 0.0_wp              !! the table's scales of chop
     integer :: cols(NDOF_NODE) = 0             !! TABLE_DISPLACEMENTS: the DOF of each column
     integer :: ncol = 0                        !! TABLE_DISPLACEMENTS: columns printed
     type(element_kinds_t) :: kinds             !! the element tables: what each type is
   contains
     procedure :: put_rows => table_put_rows
  end type table_rows_t

  public :: node_tables, element_tables, contact_table

contains

  subroutine table_put_rows(self, tb, model, res, first, last)
    !! The rows of nodes or elements first..last of self's table.
    class(table_rows_t), intent(in) :: self
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    select case (self%table)
    case (TABLE_DISPLACEMENTS)
       call displacement_rows(self, tb, model, res, first, last)
    case (TABLE_END_FORCES)
       call end_force_rows(self, tb, model, res, first, last)
    case (TABLE_TRUSSES)
       call truss_rows(self, tb, model, res, first, last)
    case (TABLE_RESULTANTS)
       call resultant_rows(self, tb, model, res, first, last)
    case (TABLE_STRESSES)
       call stress_rows(self, tb, model, res, first, last)
    case (TABLE_CONTACTS)
       call contact_rows(self, tb, model, res, first, last)
    end select
  end subroutine table_put_rows

  subroutine node_tables(lu, model, res, is)
    !! DISPLACEMENTS and SUPPORT REACTIONS of step is.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: is
    integer :: k
    real(wp) :: scale
    character(len=300) :: hline
    character(len=3), parameter :: DISP_NAMES(NDOF_NODE) = ['u1 ', 'u2 ', 'u3 ', 'ur1', 'ur2', 'ur3']
    integer(int8), allocatable :: has(:)
    type(table_rows_t) :: rows

    call node_dof_mask(model, res%fields%vertex_offset, has)
    associate (st => res%fields%steps(is))
      call lu%line('DISPLACEMENTS (global axes)')
      rows%table = TABLE_DISPLACEMENTS
      rows%is = is
      call displacement_columns(model, rows%cols, rows%ncol)
      hline = ''
      write (hline, '(2x,a20,a10)') 'substructure        ', '      node'
      do k = 1, rows%ncol
         hline = trim(hline)//repeat(' ', 15 - len_trim(DISP_NAMES(rows%cols(k))))//trim(DISP_NAMES(rows%cols(k)))
      end do
      call lu%line(trim(hline))
      rows%scale(1) = max(0.0_wp, maxval(abs(res%fields%u(:, is))))
      call write_rows(lu, rows, model, res, res%fields%vertex_offset(size(model%subs) + 1))
      call lu%line('')

      if (has_node_frames(model)) then
         call lu%line('SUPPORT REACTIONS (force the support exerts on the structure; '//REACTION_FRAME_NOTE//')')
      else
         call lu%line('SUPPORT REACTIONS (force the support exerts on the structure)')
      end if
      write (hline, '(2x,a20,a10,a6,a15)') 'substructure        ', '      node', '   dof', '          force'
      call lu%line(trim(hline))
      scale = max(0.0_wp, maxval(abs(st%reactions(:)%force)))
      do k = 1, size(st%reactions)
         associate (rc => st%reactions(k))
           if (.not. btest(has(res%fields%vertex_offset(rc%sub) + rc%node), rc%dof - 1)) cycle
           call lu%put('  ')
           call lu%put_field(model%subs(rc%sub)%name, 20)
           call lu%put_int(int(model%subs(rc%sub)%node_id(rc%node), i8), 10)
           call lu%put_int(int(rc%dof, i8), 6)
           call lu%put_es(chop(rc%force, scale))
           if (in_node_frame(model, rc%sub, rc%node)) call lu%put(FRAME_MARK)
           call lu%newline()
         end associate
      end do
      call lu%line('')
    end associate
  end subroutine node_tables

  subroutine displacement_rows(rows, tb, model, res, first, last)
    !! DISPLACEMENTS: the rows of vertices first..last (those with DOFs).
    type(table_rows_t), intent(in) :: rows
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    integer :: isub, d, k
    integer(i8) :: v
    integer(ip) :: n
    real(wp) :: vals(NDOF_NODE), row(NDOF_NODE)
    isub = owner_of(res%fields%vertex_offset, first)
    do v = first, last
       call step_owner(res%fields%vertex_offset, v, isub, n)
       if (.not. any(res%fields%has_dof(:, v))) cycle
       do d = 1, NDOF_NODE
          vals(d) = chop(res%fields%u(NDOF_NODE*(v - 1) + d, rows%is), rows%scale(1))
       end do
       call tb%put('  ')
       call tb%put_field(model%subs(isub)%name, 20)
       call tb%put_int(int(model%subs(isub)%node_id(n), i8), 10)
       do k = 1, rows%ncol
          row(k) = vals(rows%cols(k))
       end do
       call tb%put_es_row(row(1:rows%ncol))
       call tb%newline()
    end do
  end subroutine displacement_rows

  subroutine contact_table(lu, model, res, is)
    !! CONTACT FORCES of step is: each used DOF of each contact element.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: is
    character(len=100) :: hline
    type(table_rows_t) :: rows
    call lu%line('CONTACT FORCES (contact frame; delta = u_slave - u_master, force on the master)')
    write (hline, '(2x,a16,2a10,a6,2a15)') 'contact         ', '    master', '     slave', '   dof', &
         '          delta', '          force'
    call lu%line(trim(hline))
    rows%table = TABLE_CONTACTS
    rows%is = is
    rows%scale(1) = max(0.0_wp, maxval(abs(res%fields%steps(is)%link_force)))
    rows%scale(2) = max(0.0_wp, maxval(abs(res%fields%steps(is)%link_delta)))
    call write_rows(lu, rows, model, res, int(size(model%links), i8))
    call lu%line('')
  end subroutine contact_table

  subroutine contact_rows(rows, tb, model, res, first, last)
    !! CONTACT FORCES: the rows of contact elements first..last, one per used DOF.
    type(table_rows_t), intent(in) :: rows
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    integer(i8) :: il
    integer :: d
    associate (st => res%fields%steps(rows%is))
      do il = first, last
         associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
           do d = 1, NDOF_NODE
              if (.not. res%fields%link_used(d, il)) cycle
              call tb%put('  ')
              call tb%put_field(ct%name, 16)
              call tb%put_int(int(model%subs(ct%master_sub)%node_id(lk%master_node), i8), 10)
              call tb%put_int(int(model%subs(ct%slave_sub)%node_id(lk%slave_node), i8), 10)
              call tb%put_int(int(d, i8), 6)
              call tb%put_es(chop(st%link_delta(d, il), rows%scale(2)))
              call tb%put_es(chop(st%link_force(d, il), rows%scale(1)))
              if (lk%state(d) == LINK_RIGID) call tb%put('   RIGID')
              call tb%newline()
           end do
         end associate
      end do
    end associate
  end subroutine contact_rows

  subroutine element_tables(lu, model, res, is)
    !! TRUSS AXIAL FORCES, ELEMENT END FORCES of the beams and the plate and
    !! shell resultants of step is.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: is
    integer :: isub, ie
    character(len=300) :: hline
    logical :: has_bars, has_plates, has_trusses
    type(table_rows_t) :: rows
    integer(i8) :: nel

    rows%kinds = element_kinds()
    rows%is = is
    has_bars = .false.
    has_plates = .false.
    has_trusses = .false.
    do isub = 1, size(model%subs)
       do ie = 1, model%subs(isub)%nelem
          associate (t => model%subs(isub)%elem_type(ie), kinds => rows%kinds)
            has_plates = has_plates .or. kinds%plate(t)
            has_trusses = has_trusses .or. (kinds%truss(t) .and. .not. kinds%plate(t))
            has_bars = has_bars .or. .not. (kinds%plate(t) .or. kinds%truss(t))
          end associate
       end do
    end do
    nel = res%fields%elem_offset(size(model%subs) + 1)
    if (has_trusses) call truss_block(lu, model, res, rows, nel)
    if (has_bars) then
       call lu%line('ELEMENT END FORCES (local axes; forces the nodes exert on the element)')
       write (hline, '(2x,a20,a10,a6,a4,6a15)') 'substructure        ', '   element', '  type', ' end', &
            '              n', '             vy', '             vz', '              t', '             my', &
            '             mz'
       call lu%line(trim(hline))
       rows%table = TABLE_END_FORCES
       rows%scale(1) = max(0.0_wp, maxval(abs(res%fields%elem_force(:, :, :, is))))
       call write_rows(lu, rows, model, res, nel)
       call lu%line('')
    end if
    if (has_plates) call plate_block(lu, model, res, rows, nel)
  end subroutine element_tables

  subroutine end_force_rows(rows, tb, model, res, first, last)
    !! ELEMENT END FORCES: the two rows of each beam among elements first..last.
    type(table_rows_t), intent(in) :: rows
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    integer :: isub, k
    integer(i8) :: iel
    integer(ip) :: ie
    real(wp) :: row(6)
    isub = owner_of(res%fields%elem_offset, first)
    do iel = first, last
       call step_owner(res%fields%elem_offset, iel, isub, ie)
       if (rows%kinds%plate(model%subs(isub)%elem_type(ie))) cycle
       if (rows%kinds%truss(model%subs(isub)%elem_type(ie))) cycle
       do k = 1, 2
          call element_prefix(tb, model, isub, ie, 2)
          call tb%put_int(int(k, i8), 4)
          row = chop(res%fields%elem_force(:, k, iel, rows%is), rows%scale(1))
          call tb%put_es_row(row)
          call tb%newline()
       end do
    end do
  end subroutine end_force_rows

  subroutine truss_block(lu, model, res, rows, nel)
    !! One axial force per truss, tension positive: N = (n2 - n1)/2 of the end
    !! forces, the force at mid-length (n2 = -n1 = N without an axial load
    !! along the bar; element_forces.csv keeps both ends).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(table_rows_t), intent(in) :: rows
    integer(i8), intent(in) :: nel
    character(len=100) :: hline
    type(table_rows_t) :: truss
    integer :: isub
    integer(ip) :: ie
    integer(i8) :: iel
    call lu%line('TRUSS AXIAL FORCES (tension positive)')
    write (hline, '(2x,a20,a10,a6,a15)') 'substructure        ', '   element', '  type', '              N'
    call lu%line(trim(hline))
    truss = rows
    truss%table = TABLE_TRUSSES
    truss%scale(1) = 0.0_wp
    do isub = 1, size(model%subs)
       do ie = 1, model%subs(isub)%nelem
          if (.not. rows%kinds%truss(model%subs(isub)%elem_type(ie))) cycle
          iel = res%fields%elem_offset(isub) + ie
          truss%scale(1) = max(truss%scale(1), abs(axial(res, iel, rows%is)))
       end do
    end do
    call write_rows(lu, truss, model, res, nel)
    call lu%line('')
  end subroutine truss_block

  subroutine truss_rows(rows, tb, model, res, first, last)
    !! TRUSS AXIAL FORCES: the row of each truss among elements first..last.
    type(table_rows_t), intent(in) :: rows
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    integer :: isub
    integer(i8) :: iel
    integer(ip) :: ie
    isub = owner_of(res%fields%elem_offset, first)
    do iel = first, last
       call step_owner(res%fields%elem_offset, iel, isub, ie)
       if (.not. rows%kinds%truss(model%subs(isub)%elem_type(ie))) cycle
       call element_prefix(tb, model, isub, ie, 2)
       call tb%put_es(chop(axial(res, iel, rows%is), rows%scale(1)))
       call tb%newline()
    end do
  end subroutine truss_rows

  pure real(wp) function axial(res, iel, is) result(n)
    !! The axial force of truss iel in step is, tension positive.
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: iel
    integer, intent(in) :: is
    n = 0.5_wp*(res%fields%elem_force(1, 2, iel, is) - res%fields%elem_force(1, 1, iel, is))
  end function axial

  subroutine plate_block(lu, model, res, rows, nel)
    !! Resultants per unit length of the plane and shell elements at their
    !! centroids, and the stresses at the top and bottom surfaces (plane stress:
    !! mid-surface only), element frame.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(table_rows_t), intent(in) :: rows
    integer(i8), intent(in) :: nel
    type(table_rows_t) :: plates
    character(len=300) :: hline

    call lu%line('PLATE AND SHELL RESULTANTS (element frame, per unit length, at the centroid)')
    write (hline, '(2x,a20,a10,a6,6a15)') 'substructure        ', '   element', '  type', &
         '             nx', '             ny', '            nxy', '             mx', '             my', &
         '            mxy'
    call lu%line(trim(hline))
    plates = rows
    plates%table = TABLE_RESULTANTS
    plates%scale(1) = max(0.0_wp, maxval(abs(res%fields%plate(1:3, :, rows%is))))
    plates%scale(2) = max(0.0_wp, maxval(abs(res%fields%plate(4:6, :, rows%is))))
    call write_rows(lu, plates, model, res, nel)
    call lu%line('')

    call lu%line('PLATE AND SHELL STRESSES (element frame, at the centroid; top is +t/2 along the normal)')
    write (hline, '(2x,a20,a10,a6,a8,4a15)') 'substructure        ', '   element', '  type', ' surface', &
         '             sx', '             sy', '            sxy', '     von Mises'
    call lu%line(trim(hline))
    plates%table = TABLE_STRESSES
    call write_rows(lu, plates, model, res, nel)
    call lu%line('')
  end subroutine plate_block

  subroutine resultant_rows(rows, tb, model, res, first, last)
    !! PLATE AND SHELL RESULTANTS: the row of each plate-type element among
    !! elements first..last.
    type(table_rows_t), intent(in) :: rows
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    integer :: isub
    integer(i8) :: iel
    integer(ip) :: ie
    real(wp) :: row(6)
    isub = owner_of(res%fields%elem_offset, first)
    do iel = first, last
       call step_owner(res%fields%elem_offset, iel, isub, ie)
       if (.not. rows%kinds%plate(model%subs(isub)%elem_type(ie))) cycle
       call element_prefix(tb, model, isub, ie, 2)
       row(1:3) = chop(res%fields%plate(1:3, iel, rows%is), rows%scale(1))
       row(4:6) = chop(res%fields%plate(4:6, iel, rows%is), rows%scale(2))
       call tb%put_es_row(row)
       call tb%newline()
    end do
  end subroutine resultant_rows

  subroutine stress_rows(rows, tb, model, res, first, last)
    !! PLATE AND SHELL STRESSES: the rows (top and bottom, or mid) of each
    !! plate-type element among elements first..last.
    type(table_rows_t), intent(in) :: rows
    type(text_buffer_t), intent(inout) :: tb
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer(i8), intent(in) :: first, last
    integer :: isub, k, nsurf, is
    integer(i8) :: iel
    integer(ip) :: ie
    logical :: plane_strain
    real(wp) :: t, sig(4)
    character(len=6), parameter :: SURFACES(3) = ['top   ', 'bottom', 'mid   ']

    is = rows%is
    isub = owner_of(res%fields%elem_offset, first)
    do iel = first, last
       call step_owner(res%fields%elem_offset, iel, isub, ie)
       if (.not. rows%kinds%plate(model%subs(isub)%elem_type(ie))) cycle
       t = model%subs(isub)%sections(model%subs(isub)%elem_section(ie))%thickness
       nsurf = 2
       if (rows%kinds%plane(model%subs(isub)%elem_type(ie))) nsurf = 1
       plane_strain = rows%kinds%plane_strain(model%subs(isub)%elem_type(ie))
       if (plane_strain) nsurf = 1
       do k = 1, nsurf
          sig(1:3) = res%fields%plate(1:3, iel, is)/t
          ! (m/t)/t: no t**2 to underflow
          if (nsurf == 2) sig(1:3) = sig(1:3) + merge(1.0_wp, -1.0_wp, k == 1)*6.0_wp*(res%fields%plate(4:6, iel, is)/t)/t
          sig(4) = von_mises(sig(1:3))
          if (plane_strain) then   ! with sz = nu (sx + sy)
             associate (sec => model%subs(isub)%sections(model%subs(isub)%elem_section(ie)))
               sig(4) = von_mises_3(sig(1:3), model%materials(sec%material)%nu*(sig(1) + sig(2)))
               ! loads: a thermal strain adds -E alpha dT to sz
               if (allocated(res%fields%thermal)) sig(4) = von_mises_3(sig(1:3), &
                    model%materials(sec%material)%nu*(sig(1) + sig(2)) - &
                    model%materials(sec%material)%e*(res%fields%thermal(1, iel, is) + centroid_remainder()))
             end associate
          end if
          call element_prefix(tb, model, isub, ie, 2)
          call tb%put_blanks(2)
          if (nsurf == 1) then
             call tb%put_field(SURFACES(3), 6)
          else
             call tb%put_field(SURFACES(k), 6)
          end if
          sig = chop(sig, maxval(abs(sig)))
          call tb%put_es_row(sig)
          call tb%newline()
       end do
    end do
  contains
    real(wp) function centroid_remainder()
      !! A temperature varying over plane element ie of isub: its remainder at the centroid.
      integer :: nn
      centroid_remainder = 0.0_wp
      if (.not. allocated(res%fields%thermal_nodal)) return
      associate (sub => model%subs(isub))
        nn = ELEMENT_NODE_COUNT(sub%elem_type(ie))
        centroid_remainder = plane_centroid_remainder(sub%elem_type(ie), sub%x(:, sub%elem_nodes(1:nn, ie)), &
             res%fields%thermal_nodal(1:nn, iel, is))
      end associate
    end function centroid_remainder
  end subroutine stress_rows

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
end module superjoin_output_listing_tables
