module superjoin_deck_transforms
  !! Parser side of `*TRANSFORM, NSET=n[, TYPE=R|C]` (CalculiX): nodal systems
  !! in which the `*BOUNDARY`/`*SUPPORT` DOFs and the `*CLOAD` components of
  !! the set's nodes are written. Data line `ax, ay, az, bx, by, bz`:
  !! TYPE=R (default) local 1 along a, local 2 in the a-b plane, 3 = 1 x 2;
  !! TYPE=C a cylindrical system about the axis from point a to point b:
  !! local 1 radial, 2 tangential, 3 along the axis. The frames are computed
  !! per node by superjoin_deck_frame_build.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: source_loc_t
  use superjoin_deck_lexer, only: keyword_line_t, to_upper, clip
  use superjoin_deck_state, only: deck_state_t, report_loc, grow, transform_b_t
  use superjoin_utils_strings, only: pick
  use superjoin_deck_cards_common, only: get_reals
  use superjoin_deck_cards_common, only: outside_step, check_params, get_param, field_count, &
       get_real, parse_set_ref, CARD_SKIP, CARD_TRANSFORM, PARALLEL_TOL, NAME_LEN, ORIENT_VALUES
  implicit none (type, external)
  private

  public :: kw_transform, data_transform

contains

  subroutine kw_transform(st, kw, loc)
    !! *TRANSFORM, NSET=n[, TYPE=R|C]: nodal systems (CalculiX).
    type(deck_state_t), intent(inout) :: st
    type(keyword_line_t), intent(in) :: kw
    type(source_loc_t), intent(in) :: loc
    type(transform_b_t) :: t
    character(:), allocatable :: value
    logical :: found
    integer, parameter :: INITIAL_TRANSFORMS = 4
    if (.not. outside_step(st, kw, loc)) return
    call check_params(st, kw, loc, [character(NAME_LEN) :: 'NSET', 'TYPE'], [character(NAME_LEN) ::])
    st%card = CARD_SKIP
    call get_param(st, kw, loc, 'TYPE', .false., value, found)
    if (found) then
       select case (to_upper(value))
       case ('R')
          t%cylindrical = .false.
       case ('C')
          t%cylindrical = .true.
       case default
          call report_loc(st, loc, '*TRANSFORM TYPE must be R (rectangular) or C (cylindrical), not '//clip(value))
          return
       end select
    end if
    call get_param(st, kw, loc, 'NSET', .true., value, found)
    if (.not. found) return
    if (.not. parse_set_ref(st, value, .false., st%cur_sub, loc, t%nset)) return
    t%loc = loc
    call grow(st%transforms, st%ntransform, INITIAL_TRANSFORMS)
    st%ntransform = st%ntransform + 1
    st%transforms(st%ntransform) = t
    st%card = CARD_TRANSFORM
    st%card_item = st%ntransform
  end subroutine kw_transform

  subroutine data_transform(st, line, loc)
    !! The data line of *TRANSFORM: ax, ay, az, bx, by, bz.
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: line
    type(source_loc_t), intent(in) :: loc
    real(wp) :: v(ORIENT_VALUES)
    associate (t => st%transforms(st%card_item))
      if (st%card_ndata > 1) then
         call report_loc(st, loc, 'too many data lines for *TRANSFORM')
         st%card = CARD_SKIP
         return
      end if
      if (.not. field_count(st, loc, ORIENT_VALUES, ORIENT_VALUES, 'ax, ay, az, bx, by, bz')) return
      if (.not. get_reals(st, line, loc, v(1:ORIENT_VALUES))) return
      t%a = v(1:3)
      t%b = v(4:6)
      if (t%cylindrical) then
         if (norm2(t%b - t%a) == 0.0_wp) then
            call report_loc(st, loc, '*TRANSFORM, TYPE=C: points a and b coincide (they define the cylinder''s axis)')
            return
         end if
      else
         if (norm2(t%a) == 0.0_wp .or. norm2(t%b) == 0.0_wp) then
            call report_loc(st, loc, '*TRANSFORM, TYPE=R: vector '//pick(norm2(t%a) == 0.0_wp, 'a', 'b')//' is zero')
            return
         end if
         if (norm2(t%b - dot_product(t%b, t%a)/dot_product(t%a, t%a)*t%a) <= PARALLEL_TOL*norm2(t%b)) then
            call report_loc(st, loc, '*TRANSFORM, TYPE=R: vectors a and b are parallel')
            return
         end if
      end if
      t%has_data = .true.
    end associate
  end subroutine data_transform
end module superjoin_deck_transforms
