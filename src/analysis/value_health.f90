module superjoin_analysis_value_health
  !! The condensed interiors of one solve and the health of the whole
  !! system (analysis/health: full_health). A joint study's further value
  !! that took the previous value's condensations unchanged (take_views:
  !! the same K*, f* and recovery operators, which the value that formed
  !! them checked against the parts' own k in its whole-system health)
  !! checks what it computed itself: the interface system K_red q = f_red
  !! and the interiors it recovers, those of the parts an output request
  !! reads (parts_read); the reactions and contact forces of a part left
  !! unrecovered come from K* u_b − f* (boundary_ku: equal to (k u − f)_b in
  !! exact arithmetic). Its listing says what its residual and EPSILON
  !! cover (step_results_t%health_scope). When the interface check is
  !! doubtful (interface_doubt, residual_doubt) the value falls back to the
  !! whole check and its listing says why.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, LINK_FINITE, REQ_NODE_PRINT, REQ_NODE_FILE
  use superjoin_model_results, only: results_t, run_options_t
  use superjoin_model_request_masks, only: has_requests, request_mask
  use superjoin_substructure_cache, only: part_view_t
  use superjoin_analysis_condensation, only: solve_context_t, condensed_strategy_t, recover_parts, parts_ku
  use superjoin_analysis_health, only: full_health, MAXRATIO_WARN
  use superjoin_analysis_solve_state, only: solve_state_t
  implicit none (type, external)
  private

  real(wp), parameter, public :: SCOPE_DOUBT = 1.0e-9_wp
    !! A further value whose interface residual or |EPSILON|, or whose
    !! interface-and-interiors residual or |EPSILON|, exceeds this is checked
    !! whole (a thousandth of RESIDUAL_WARN: far above round-off, far below a
    !! residual the listing would flag).

  public :: recover_interiors_of_value

contains

  subroutine recover_interiors_of_value(st, model, opts, ctx, wanted, res, error)
    !! The condensed interiors, their k u and the health block's residual and
    !! EPSILON of one solve (see the module): the whole system, or for a
    !! joint study's further value the interface and the interiors read.
    !! wanted: the elements whose results are listed (policy's wanted_elements).
    type(solve_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    type(solve_context_t), intent(inout) :: ctx
    logical, intent(in) :: wanted(:)
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: read(:)
    character(:), allocatable :: doubt
    if (.not. further_value(ctx, st)) then
       call whole_check(st, ctx, res, error)
       return
    end if
    doubt = interface_doubt(model, res)
    if (len(doubt) == 0) then
       read = parts_read(model, opts, wanted, st%parts)
       call recover_parts(ctx%cache, st%parts, st%f_phys, st%u, error, read)
       if (allocated(error)) return
       call parts_ku(ctx%cache, st%parts, st%f_phys, st%u, st%ku, error, read)
       if (allocated(error)) return
       call boundary_ku(st, .not. read)
       call full_health(st, ctx%cache, res, error, covered=read)
       if (allocated(error)) return
       doubt = residual_doubt(res, 'interface and interiors')
       if (len(doubt) == 0) then
          call set_scope(res, covered_text(model, st%parts, read))
          return
       end if
       call recover_parts(ctx%cache, st%parts, st%f_phys, st%u, error, .not. read)   ! the rest, then all
       if (allocated(error)) return
       call parts_ku(ctx%cache, st%parts, st%f_phys, st%u, st%ku, error)
       if (allocated(error)) return
       call full_health(st, ctx%cache, res, error)
    else
       call whole_check(st, ctx, res, error)
    end if
    if (allocated(error)) return
    call set_scope(res, 'the whole system (a further joint value reusing the condensations, checked whole: '// &
         doubt//')')
  end subroutine recover_interiors_of_value

  subroutine whole_check(st, ctx, res, error)
    !! Every condensed interior, the parts' k u and the whole system's
    !! residual and EPSILON, as for every solve that is not a further value.
    type(solve_state_t), intent(inout) :: st
    type(solve_context_t), intent(inout) :: ctx
    type(results_t), intent(inout) :: res
    type(error_t), allocatable, intent(out) :: error
    call st%strategy%recover_interiors(st, ctx%cache, error)
    if (allocated(error)) return
    if (st%tr%ncol() > 0) call full_health(st, ctx%cache, res, error)
  end subroutine whole_check

  logical function further_value(ctx, st)
    !! A joint study's value that took the previous value's views of its
    !! condensed parts (take_views: the same condensations, loads and
    !! numbering), solved by one process with unknowns to check.
    type(solve_context_t), intent(in) :: ctx
    type(solve_state_t), intent(in) :: st
    type(condensed_strategy_t) :: condensed
    further_value = ctx%joint_study .and. ctx%cache%views_taken
    if (further_value) further_value = same_type_as(st%strategy, condensed) .and. st%tr%ncol() > 0
  end function further_value

  function interface_doubt(model, res) result(doubt)
    !! Why the interface solve of a further value is not trusted alone
    !! ('' when it is): a released contact DOF (g = 0: a hinge the interface
    !! cannot see), a warning of the interface's health (inaccurate, MAXRATIO
    !! above MAXRATIO_WARN), or its residual or EPSILON above SCOPE_DOUBT.
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    character(:), allocatable :: doubt
    integer :: il
    do il = 1, size(model%links)
       if (any(model%links(il)%state == LINK_FINITE .and. model%links(il)%g == 0.0_wp)) then
          doubt = 'a released contact DOF (g = 0)'
          return
       end if
    end do
    if (res%log%inaccurate .or. size(res%log%warnings) > 0 .or. res%summary%maxratio > MAXRATIO_WARN) then
       doubt = 'the interface solve has a warning'
       return
    end if
    doubt = residual_doubt(res, 'interface')
  end function interface_doubt

  function residual_doubt(res, what) result(doubt)
    !! 'residual of what above SCOPE_DOUBT' when a step's relative residual
    !! or |EPSILON| exceeds SCOPE_DOUBT, else ''.
    type(results_t), intent(in) :: res
    character(*), intent(in) :: what
    character(:), allocatable :: doubt
    character(len=32) :: buf
    doubt = ''
    if (maxval(res%fields%steps(:)%residual) <= SCOPE_DOUBT .and. &
         maxval(abs(res%fields%steps(:)%epsilon)) <= SCOPE_DOUBT) return
    write (buf, '(es10.2e3)') SCOPE_DOUBT
    doubt = 'residual or EPSILON of the '//what//' above '//trim(adjustl(buf))
  end function residual_doubt

  function parts_read(model, opts, wanted, parts) result(read)
    !! Whether an output reads each condensed part's interior: every part
    !! when the deck has no requests, writes result files (CSV, VTK, .frd),
    !! has *SECTION PRINT cards or load combinations (their envelope); else
    !! the parts with a wanted element or a node a *NODE PRINT or *NODE FILE
    !! request names. (The reactions and contact forces every value lists
    !! lie on the condensation boundaries: boundary_ku.)
    type(model_t), intent(in) :: model
    type(run_options_t), intent(in) :: opts
    logical, intent(in) :: wanted(:)
    type(part_view_t), intent(in) :: parts(:)
    logical, allocatable :: read(:), nodes(:)
    integer(i8) :: e0, n0
    integer :: i, isub, i_
    allocate (read(size(parts)), source=.true.)
    if (.not. has_requests(model) .or. opts%csv .or. opts%vtk .or. opts%frd .or. &
         any(model%steps%combination > 0)) return
    if (allocated(model%section_prints)) then
       if (size(model%section_prints) > 0) return
    end if
    call request_mask(model, [REQ_NODE_PRINT, REQ_NODE_FILE], .true., nodes)
    do i = 1, size(parts)
       isub = parts(i)%isub
       e0 = sum([(int(model%subs(i_)%nelem, i8), i_ = 1, isub - 1)])
       n0 = sum([(int(model%subs(i_)%nnode, i8), i_ = 1, isub - 1)])
       read(i) = any(wanted(e0 + 1:e0 + model%subs(isub)%nelem)) .or. any(nodes(n0 + 1:n0 + model%subs(isub)%nnode))
    end do
  end function parts_read

  subroutine boundary_ku(st, rows)
    !! For each part where rows is true (its interior not recovered): the
    !! boundary rows of st%ku such that (k u − f)_b = K* u_b − f*, the
    !! reactions and contact forces the recovery reads there.
    type(solve_state_t), intent(inout) :: st
    logical, intent(in) :: rows(:)
    integer :: i, is
    do i = 1, size(st%parts)
       if (.not. rows(i)) cycle
       associate (v => st%parts(i), b => st%parts(i)%pdof(st%parts(i)%ni + 1:))
         do is = 1, size(st%u, 2)
            st%ku(b, is) = matmul(v%se%k, st%u(b, is)) - st%f_eff(b, is) + st%f_phys(b, is)
         end do
       end associate
    end do
  end subroutine boundary_ku

  function covered_text(model, parts, read) result(text)
    !! What a further value's residual and EPSILON cover.
    type(model_t), intent(in) :: model
    type(part_view_t), intent(in) :: parts(:)
    logical, intent(in) :: read(:)
    character(:), allocatable :: text, names
    integer :: i
    names = ''
    do i = 1, size(parts)
       if (.not. read(i)) cycle
       if (len(names) > 0) names = names//', '
       names = names//model%subs(parts(i)%isub)%name
    end do
    if (len(names) == 0) then
       text = 'the interface system alone'
    else
       text = 'the interface system and the interiors of '//names
    end if
    text = text//' (a further joint value: K*, f* reused unchanged, checked whole by the value that formed them)'
  end function covered_text

  subroutine set_scope(res, text)
    !! Every step of the solve: its residual and EPSILON cover text.
    type(results_t), intent(inout) :: res
    character(*), intent(in) :: text
    integer :: is
    do is = 1, size(res%fields%steps)
       res%fields%steps(is)%health_scope = text
    end do
  end subroutine set_scope
end module superjoin_analysis_value_health
