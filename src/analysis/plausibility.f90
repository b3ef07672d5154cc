module superjoin_analysis_plausibility
  !! Plausibility of a solved linear analysis: displacements that exceed a
  !! sizeable fraction of the model's size are outside small-displacement
  !! theory and almost always a units mix-up (E in MPa with lengths in m gives
  !! a million times too much), a load or a support missing. Warned, with what
  !! to check; the run still exits 0 (the answer is the exact one of the deck).
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t, NDOF_NODE, node_label, string_t
  use superjoin_model_results, only: results_t
  use superjoin_utils_strings, only: itoa
  use superjoin_model_notes, only: add_warning
  implicit none (type, external)
  private

  real(wp), parameter, public :: DISPLACEMENT_FRACTION = 0.1_wp
    !! Warn when a translation exceeds this fraction of the model's size (the
    !! diagonal of the box around all nodes): far beyond the span/200 of a
    !! serviceable structure, well inside what linear theory can represent.

  public :: check_plausibility

contains

  subroutine check_plausibility(model, res)
    !! Append a warning to res%log%warnings for every step whose largest translation
    !! exceeds DISPLACEMENT_FRACTION x the model's size (listed in that step's block).
    type(model_t), intent(in) :: model
    type(results_t), intent(inout) :: res
    real(wp) :: lo(3), hi(3), size_model, umax, t
    integer :: isub, is, at_sub, k
    integer(ip) :: n, at_node
    integer(i8) :: v
    character(len=16) :: b1, b2, b3

    if (.not. allocated(res%fields%u) .or. size(model%steps) == 0) return
    lo = huge(1.0_wp)
    hi = -huge(1.0_wp)
    do isub = 1, size(model%subs)
       do n = 1, model%subs(isub)%nnode
          lo = min(lo, model%subs(isub)%x(:, n))
          hi = max(hi, model%subs(isub)%x(:, n))
       end do
    end do
    size_model = norm2(hi - lo)
    if (.not. (size_model > 0.0_wp)) return
    do is = 1, size(res%fields%u, 2)
       umax = 0.0_wp
       at_sub = 0
       at_node = 0
       v = 0
       do isub = 1, size(model%subs)
          do n = 1, model%subs(isub)%nnode
             v = v + 1
             t = norm2(res%fields%u(NDOF_NODE*(v - 1) + 1:NDOF_NODE*(v - 1) + 3, is))
             if (t > umax) then
                umax = t
                at_sub = isub
                at_node = n
             end if
          end do
       end do
       if (umax <= DISPLACEMENT_FRACTION*size_model) cycle
       write (b1, '(es10.2e3)') umax
       write (b2, '(es10.2e3)') size_model
       write (b3, '(es10.2e3)') umax/size_model
       call add_warning(res%log%warnings, 'step '//model%steps(is)%name//': displacement '//trim(adjustl(b1))// &
            ' at '//node_label(model, at_sub, at_node)//' is '//trim(adjustl(b3))//' times the model''s size '// &
            trim(adjustl(b2))//': beyond small-displacement (linear) theory. Check the units (E in MPa or '// &
            'N/mm2 with lengths in m?), the magnitude of the loads and that the supports hold the structure', &
            [(k == is, k=1, size(model%steps))])
    end do
  end subroutine check_plausibility
end module superjoin_analysis_plausibility
