module superjoin_analysis_contact_gaps
  !! Contact elements join two nodes that are meant to coincide (the contact
  !! element has zero length: u_slave = u_master + Δu). A pair farther apart
  !! than a tolerance is almost always a numbering mistake (the wrong node of
  !! the other part); it is warned, once per contact card with a count and the
  !! farthest pair. The tolerance is relative to the model's size (the diagonal
  !! of the box around all nodes), *CONTROLS, POSITION TOLERANCE= sets it.
  !! Contacts with OFFSET=RIGID join distant nodes on purpose and are exempt.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t, node_label, string_t
  use superjoin_utils_strings, only: itoa
  use superjoin_model_notes, only: append_string
  implicit none (type, external)
  private

  public :: check_contact_gaps

contains

  subroutine check_contact_gaps(model, warnings)
    !! Append one warning per *CONTACT card with node pairs farther apart than
    !! model%controls%position_tolerance x the model's size.
    type(model_t), intent(in) :: model
    type(string_t), allocatable, intent(inout) :: warnings(:)
    real(wp) :: lo(3), hi(3), size_model, tol, dist, far
    integer :: isub, ic, il, nfar, npair, ifar
    integer(ip) :: n
    character(len=16) :: b1, b2, b3

    if (size(model%links) == 0) return
    lo = huge(1.0_wp)
    hi = -huge(1.0_wp)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          lo = min(lo, model%subs(isub)%x(:, n))
          hi = max(hi, model%subs(isub)%x(:, n))
       end do
    end do
    size_model = norm2(hi - lo)
    tol = model%controls%position_tolerance*size_model
    do ic = 1, size(model%contacts)
       if (model%contacts(ic)%remote) cycle
       if (model%contacts(ic)%rigid_offset) cycle   ! eccentric on purpose: the arm is the distance
       nfar = 0
       npair = 0
       far = -1.0_wp
       ifar = 0
       do il = 1, size(model%links)
          if (model%links(il)%contact /= ic) cycle
          npair = npair + 1
          dist = pair_distance(model, il)
          if (dist <= tol) cycle
          nfar = nfar + 1
          if (dist > far) then
             far = dist
             ifar = il
          end if
       end do
       if (nfar == 0) cycle
       write (b1, '(es10.2e3)') far
       write (b2, '(es10.2e3)') tol
       write (b3, '(es8.1e3)') model%controls%position_tolerance
       associate (ct => model%contacts(ic), lk => model%links(ifar))
         call append_string(warnings, 'contact '//ct%name//': '//itoa(nfar)//' of '//itoa(npair)// &
              ' node pair(s) farther apart than '//trim(adjustl(b2))//' ('//trim(adjustl(b3))// &
              ' x the model''s size), the farthest '//node_label(model, ct%master_sub, lk%master_node)//' - '// &
              node_label(model, ct%slave_sub, lk%slave_node)//' at '//trim(adjustl(b1))// &
              ': a contact element joins coincident nodes; check the node numbers (*CONTROLS, '// &
              'POSITION TOLERANCE= sets the tolerance)')
       end associate
    end do
  end subroutine check_contact_gaps

  pure function pair_distance(model, il) result(d)
    !! Distance between the two nodes of link il.
    type(model_t), intent(in) :: model
    integer, intent(in) :: il
    real(wp) :: d
    associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
      d = norm2(model%subs(ct%slave_sub)%x(:, lk%slave_node) - model%subs(ct%master_sub)%x(:, lk%master_node))
    end associate
  end function pair_distance
end module superjoin_analysis_contact_gaps
