module superjoin_elements_frame
  !! Local frames of two-node line elements (trusses and beams) and the checks
  !! shared by the element families (positive section and material data).
  !!
  !! Rule (deck.md, section 2): local x runs from node 1 to node 2; local y lies in
  !! the plane of x and the orientation vector v (default global Z, global X when
  !! the element is parallel to Z); local z = x × y. 2D elements (T2D2, B23) lie
  !! in the XY plane: x in that plane, z = global Z, y = z × x. B21 and B31
  !! (Timoshenko beams) follow the rules of B23 and B33.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_B21, ET_B31
  implicit none (type, external)
  private

  real(wp), parameter, public :: ZERO_LENGTH_TOL = 1.0e-14_wp
    !! An element is of zero length when L <= ZERO_LENGTH_TOL × (largest coordinate magnitude).
  real(wp), parameter, public :: PARALLEL_TOL = 1.0e-10_wp
    !! A user orientation vector v is parallel to the axis when |x × v| <= PARALLEL_TOL |x| |v|.
  real(wp), parameter, public :: DEFAULT_V_SWITCH_TOL = 1.0e-6_wp
    !! The default v (global Z) is replaced by global X when |x × Z| <= DEFAULT_V_SWITCH_TOL |x|:
    !! a column whose coordinates differ by round-off from a vertical line still gets y = X
    !! instead of an axis set by the round-off.
  real(wp), parameter, public :: PLANE_TOL = 1.0e-10_wp
    !! A 2D element lies in the XY plane when |z2 - z1| <= PLANE_TOL × L.

  real(wp), parameter :: GLOBAL_X(3) = [1.0_wp, 0.0_wp, 0.0_wp]
  real(wp), parameter :: GLOBAL_Z(3) = [0.0_wp, 0.0_wp, 1.0_wp]

  public :: beam_frame, cross, require_positive, real_text

contains

  pure subroutine beam_frame(etype, x, sec, r, length, error)
    !! Local frame of a two-node truss or beam element.
    !!
    !! `x(3, 2)` are the node coordinates; on return the rows of `r` are the
    !! local x, y, z axes in global components (so u_local = r u_global) and
    !! `length` is the element length. T2D2, B23 and B21 use the 2D rule (z = global Z;
    !! their nodes must share the same z); T3D2 uses the default v rule (a truss
    !! has no orientation, `sec%v` is ignored); B33 and B31 use `sec%v` when
    !! `sec%has_v`, else the default. Errors (code EXIT_DECK): zero-length
    !! element, 2D element out of the XY plane, zero orientation vector,
    !! orientation vector parallel to beam axis, element type without a line frame.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(out) :: r(3, 3)
    real(wp), intent(out) :: length
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: d(3), scale, ex(3), v(3), z(3), zn, vn

    r = 0.0_wp
    length = 0.0_wp
    if (etype /= ET_T2D2 .and. etype /= ET_T3D2 .and. etype /= ET_B23 .and. etype /= ET_B33 .and. &
        etype /= ET_B21 .and. etype /= ET_B31) then
       call fatal_error(error, EXIT_DECK, 'element type has no line-element frame')
       return
    end if
    if (size(x, 1) < 3 .or. size(x, 2) < 2) then
       call fatal_error(error, EXIT_DECK, 'element needs the coordinates of 2 nodes')
       return
    end if
    d = x(:, 2) - x(:, 1)
    scale = max(maxval(abs(x(:, 1))), maxval(abs(x(:, 2))))

    if (etype == ET_T2D2 .or. etype == ET_B23 .or. etype == ET_B21) then
       length = norm2(d(1:2))
       if (length <= ZERO_LENGTH_TOL*scale) then   ! also catches length = 0
          call fatal_error(error, EXIT_DECK, 'zero-length element')
          return
       end if
       if (abs(d(3)) > PLANE_TOL*length) then
          call fatal_error(error, EXIT_DECK, '2D element not in the XY plane (its nodes differ in z)')
          return
       end if
       r(1, :) = [d(1)/length, d(2)/length, 0.0_wp]
       r(3, :) = GLOBAL_Z
       r(2, :) = [-r(1, 2), r(1, 1), 0.0_wp]
       return
    end if

    length = norm2(d)
    if (length <= ZERO_LENGTH_TOL*scale) then   ! also catches length = 0
       call fatal_error(error, EXIT_DECK, 'zero-length element')
       return
    end if
    ex = d/length

    if ((etype == ET_B33 .or. etype == ET_B31) .and. sec%has_v) then
       v = sec%v
       vn = norm2(v)
       if (vn == 0.0_wp) then
          call fatal_error(error, EXIT_DECK, 'zero orientation vector')
          return
       end if
       z = cross(ex, v)
       zn = norm2(z)
       if (zn <= PARALLEL_TOL*vn) then
          call fatal_error(error, EXIT_DECK, 'orientation vector parallel to beam axis')
          return
       end if
    else
       v = GLOBAL_Z
       z = cross(ex, v)
       zn = norm2(z)
       if (zn <= DEFAULT_V_SWITCH_TOL) then
          v = GLOBAL_X
          z = cross(ex, v)
          zn = norm2(z)
       end if
    end if
    z = z/zn
    r(1, :) = ex
    r(2, :) = cross(z, ex)
    r(3, :) = z
  end subroutine beam_frame

  pure function cross(a, b) result(c)
    !! Vector product a × b.
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross

  pure subroutine require_positive(value, what, error)
    !! Set error (EXIT_DECK, "nonpositive <what> (<value>)") unless value > 0.
    !! Does nothing when error is already allocated, so checks can be chained.
    real(wp), intent(in) :: value
    character(*), intent(in) :: what
    type(error_t), allocatable, intent(inout) :: error
    if (allocated(error)) return
    if (.not. (value > 0.0_wp)) then
       allocate (error)
       error%code = EXIT_DECK
       error%message = 'nonpositive '//what//' ('//real_text(value)//')'
    end if
  end subroutine require_positive

  pure function real_text(value) result(text)
    !! A real number as short text for messages.
    real(wp), intent(in) :: value
    character(:), allocatable :: text
    character(len=32) :: buf
    write (buf, '(es12.5)') value
    text = trim(adjustl(buf))
  end function real_text
end module superjoin_elements_frame
