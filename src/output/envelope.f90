module superjoin_output_envelope
  !! The listing section ENVELOPE OF THE LOAD COMBINATIONS (only when the deck
  !! has *LOAD COMBINATION cards): for every displacement, support reaction,
  !! contact delta and force (contact frame), truss and beam end force and plate or shell resultant, the largest and the
  !! smallest value over the combinations and the combination that gives each
  !! (the first one on a tie).
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t, NDOF_NODE
  use superjoin_model_results, only: results_t, reaction_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop
  use superjoin_elements, only: is_plate_type
  use superjoin_output_layout, only: has_node_frames, in_node_frame, REACTION_FRAME_NOTE, FRAME_MARK
  implicit none (type, external)
  private

  public :: write_envelope

  character(*), parameter :: RULE = repeat('=', 100)
  integer, parameter :: NAME_WIDTH = 16
  character(len=3), parameter :: FORCE_NAMES(6) = ['n  ', 'vy ', 'vz ', 't  ', 'my ', 'mz ']
  character(len=3), parameter :: PLATE_NAMES(6) = ['nx ', 'ny ', 'nxy', 'mx ', 'my ', 'mxy']

contains

  subroutine write_envelope(lu, model, res)
    !! Write the envelope section (nothing without load combinations).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, allocatable :: cs(:)
    integer :: s
    character(:), allocatable :: names
    if (.not. allocated(model%combinations)) return
    if (size(model%combinations) == 0) return
    cs = pack([(s, s=1, size(model%steps))], model%steps%combination > 0)
    ! a combination of a step that was not solved (exit 3) has no results
    cs = pack(cs, [(.not. allocated(res%fields%steps(cs(s))%failure), s=1, size(cs))])
    if (size(cs) == 0) return
    names = ''
    do s = 1, size(cs)
       names = names//' '//model%steps(cs(s))%name
    end do
    call lu%line(RULE)
    call lu%line('ENVELOPE OF THE LOAD COMBINATIONS ('//names(2:)//')')
    call lu%line(RULE)
    call displacements(lu, model, res, cs)
    call reactions(lu, model, res, cs)
    call contact_forces(lu, model, res, cs)
    call end_forces(lu, model, res, cs)
    call plate_resultants(lu, model, res, cs)
  end subroutine write_envelope

  subroutine header_line(lu, first)
    type(text_buffer_t), intent(inout) :: lu
    character(*), intent(in) :: first
    call lu%line(first//'            max  combination                min  combination')
  end subroutine header_line

  subroutine put_extremes(lu, model, vals, cs, scale, marked)
    !! max, its combination, min, its combination of vals(k) over the
    !! combination steps cs(k); with `marked`, FRAME_MARK after them (a row in
    !! a node's *TRANSFORM system).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    real(wp), intent(in) :: vals(:), scale
    integer, intent(in) :: cs(:)
    logical, intent(in), optional :: marked
    real(wp) :: c(size(vals))
    integer :: imax, imin, k
    c = chop(vals, scale)    ! round-off ties go to the first combination
    imax = 1
    imin = 1
    do k = 2, size(c)
       if (c(k) > c(imax)) imax = k
       if (c(k) < c(imin)) imin = k
    end do
    call lu%put_es(c(imax))
    call lu%put('  ')
    call lu%put_field(model%steps(cs(imax))%name, NAME_WIDTH)
    call lu%put_es(c(imin))
    if (present(marked)) then
       if (marked) then
          call lu%put('  ')
          call lu%put_field(model%steps(cs(imin))%name, NAME_WIDTH)
          call lu%put(FRAME_MARK)
          call lu%newline()
          return
       end if
    end if
    call lu%put('  '//model%steps(cs(imin))%name)
    call lu%newline()
  end subroutine put_extremes

  subroutine displacements(lu, model, res, cs)
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: cs(:)
    integer :: isub, d
    integer(ip) :: n
    integer(i8) :: v, row
    real(wp) :: scale
    call lu%line('DISPLACEMENTS (global axes)')
    call header_line(lu, '  substructure              node   dof')
    scale = max(0.0_wp, maxval(abs(res%fields%u(:, cs))))
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          v = res%fields%vertex_offset(isub) + n
          do d = 1, NDOF_NODE
             if (.not. res%fields%has_dof(d, v)) cycle
             row = NDOF_NODE*(v - 1) + d
             call lu%put('  ')
             call lu%put_field(model%subs(isub)%name, 20)
             call lu%put_int(int(model%subs(isub)%node_id(n), i8), 10)
             call lu%put_int(int(d, i8), 6)
             call put_extremes(lu, model, res%fields%u(row, cs), cs, scale)
          end do
       end do
    end do
    call lu%line('')
  end subroutine displacements

  subroutine reactions(lu, model, res, cs)
    !! Over the union of the combinations' supported DOFs (0 where a
    !! combination has no support on that DOF).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: cs(:)
    type(reaction_t), allocatable :: keys(:)
    real(wp), allocatable :: vals(:, :)
    integer :: k, i, j
    real(wp) :: scale
    allocate (keys(0))
    do k = 1, size(cs)
       do i = 1, size(res%fields%steps(cs(k))%reactions)
          if (find(keys, res%fields%steps(cs(k))%reactions(i)) == 0) keys = [keys, res%fields%steps(cs(k))%reactions(i)]
       end do
    end do
    allocate (vals(size(keys), size(cs)), source=0.0_wp)
    do k = 1, size(cs)
       do i = 1, size(res%fields%steps(cs(k))%reactions)
          j = find(keys, res%fields%steps(cs(k))%reactions(i))
          vals(j, k) = res%fields%steps(cs(k))%reactions(i)%force
       end do
    end do
    if (has_node_frames(model)) then
       call lu%line('SUPPORT REACTIONS (force the support exerts on the structure; '//REACTION_FRAME_NOTE//')')
    else
       call lu%line('SUPPORT REACTIONS (force the support exerts on the structure)')
    end if
    call header_line(lu, '  substructure              node   dof')
    scale = 0.0_wp
    if (size(vals) > 0) scale = maxval(abs(vals))
    do i = 1, size(keys)
       call lu%put('  ')
       call lu%put_field(model%subs(keys(i)%sub)%name, 20)
       call lu%put_int(int(model%subs(keys(i)%sub)%node_id(keys(i)%node), i8), 10)
       call lu%put_int(int(keys(i)%dof, i8), 6)
       call put_extremes(lu, model, vals(i, :), cs, scale, in_node_frame(model, keys(i)%sub, keys(i)%node))
    end do
    call lu%line('')
  end subroutine reactions

  subroutine contact_forces(lu, model, res, cs)
    !! delta and force of every contact DOF that connects something, as the
    !! step's CONTACT FORCES table (contact frame); nothing without such DOFs.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: cs(:)
    real(wp) :: vals(size(cs)), fscale, dscale
    integer :: il, d, k
    if (.not. allocated(res%fields%link_used)) return
    if (.not. any(res%fields%link_used)) return
    fscale = 0.0_wp
    dscale = 0.0_wp
    do k = 1, size(cs)
       associate (st => res%fields%steps(cs(k)))
         if (.not. allocated(st%link_force)) return
         fscale = max(fscale, maxval(abs(st%link_force)))
         dscale = max(dscale, maxval(abs(st%link_delta)))
       end associate
    end do
    call lu%line('CONTACT FORCES (contact frame; delta = u_slave - u_master, force on the master)')
    call header_line(lu, '  contact         '//'    master     slave   dof  what')
    do il = 1, size(model%links)
       associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
         do d = 1, NDOF_NODE
            if (.not. res%fields%link_used(d, il)) cycle
            do k = 1, size(cs)
               vals(k) = res%fields%steps(cs(k))%link_delta(d, il)
            end do
            call contact_row('delta', vals, dscale)
            do k = 1, size(cs)
               vals(k) = res%fields%steps(cs(k))%link_force(d, il)
            end do
            call contact_row('force', vals, fscale)
         end do
       end associate
    end do
    call lu%line('')
  contains
    subroutine contact_row(what, v, scale)
      !! One row: the contact, its nodes, the DOF, what (delta or force) and the extremes.
      character(*), intent(in) :: what
      real(wp), intent(in) :: v(:), scale
      associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
        call lu%put('  ')
        call lu%put_field(ct%name, 16)
        call lu%put_int(int(model%subs(ct%master_sub)%node_id(lk%master_node), i8), 10)
        call lu%put_int(int(model%subs(ct%slave_sub)%node_id(lk%slave_node), i8), 10)
        call lu%put_int(int(d, i8), 6)
        call lu%put(' '//what)
        call put_extremes(lu, model, v, cs, scale)
      end associate
    end subroutine contact_row
  end subroutine contact_forces

  pure integer function find(keys, r) result(j)
    type(reaction_t), intent(in) :: keys(:), r
    integer :: i
    j = 0
    do i = 1, size(keys)
       if (keys(i)%sub == r%sub .and. keys(i)%node == r%node .and. keys(i)%dof == r%dof) then
          j = i
          return
       end if
    end do
  end function find

  subroutine end_forces(lu, model, res, cs)
    !! Trusses and beams: every end force component.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: cs(:)
    integer :: isub, k, d
    integer(ip) :: ie
    integer(i8) :: iel
    real(wp) :: scale
    logical :: any_bar
    if (.not. allocated(res%fields%elem_force)) return
    any_bar = .false.
    do isub = 1, size(model%subs)
       if (any(.not. is_plate_type(model%subs(isub)%elem_type(1:model%subs(isub)%nelem)))) any_bar = .true.
    end do
    if (.not. any_bar) return
    call lu%line('ELEMENT END FORCES (local axes; forces the nodes exert on the element)')
    call header_line(lu, '  substructure           element  type end  force')
    scale = max(0.0_wp, maxval(abs(res%fields%elem_force(:, :, :, cs))))
    do isub = 1, size(model%subs)
       do ie = 1, model%subs(isub)%nelem
          if (is_plate_type(model%subs(isub)%elem_type(ie))) cycle
          iel = res%fields%elem_offset(isub) + ie
          do k = 1, 2
             do d = 1, 6
                call element_prefix(lu, model, isub, ie, 2)
                call lu%put_int(int(k, i8), 4)
                call lu%put('  ')
                call lu%put_field(FORCE_NAMES(d), 5)
                call put_extremes(lu, model, res%fields%elem_force(d, k, iel, cs), cs, scale)
             end do
          end do
       end do
    end do
    call lu%line('')
  end subroutine end_forces

  subroutine plate_resultants(lu, model, res, cs)
    !! Plane and shell elements: every resultant per unit length at the centroid.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    integer, intent(in) :: cs(:)
    integer :: isub, d
    integer(ip) :: ie
    integer(i8) :: iel
    real(wp) :: scale
    logical :: any_plate
    if (.not. allocated(res%fields%plate)) return
    any_plate = .false.
    do isub = 1, size(model%subs)
       if (any(is_plate_type(model%subs(isub)%elem_type(1:model%subs(isub)%nelem)))) any_plate = .true.
    end do
    if (.not. any_plate) return
    call lu%line('PLATE AND SHELL RESULTANTS (element frame, per unit length, at the centroid)')
    call header_line(lu, '  substructure           element  type resultant')
    scale = max(0.0_wp, maxval(abs(res%fields%plate(:, :, cs))))
    do isub = 1, size(model%subs)
       do ie = 1, model%subs(isub)%nelem
          if (.not. is_plate_type(model%subs(isub)%elem_type(ie))) cycle
          iel = res%fields%elem_offset(isub) + ie
          do d = 1, 6
             call element_prefix(lu, model, isub, ie, 2)
             call lu%put('  ')
             call lu%put_field(PLATE_NAMES(d), 7)
             call put_extremes(lu, model, res%fields%plate(d, iel, cs), cs, scale)
          end do
       end do
    end do
    call lu%line('')
  end subroutine plate_resultants
end module superjoin_output_envelope
