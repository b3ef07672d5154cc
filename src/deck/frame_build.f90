module superjoin_deck_frame_build
  !! Validation side of `*TRANSFORM`: the nodal system of every node of the
  !! sets (rectangular, or cylindrical from the node's position), and the
  !! `*CLOAD` components of those nodes turned from the nodal system into
  !! global axes. Supports keep their local DOFs: the DOF table builds them as
  !! oblique contact units to the ground (superjoin_assembly_dofs).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, node_frame_t, cload_t, node_label, frame_of_node
  use superjoin_deck_state, only: deck_state_t, report_loc, file_of
  use superjoin_deck_build_common, only: resolve_items, resolve_sub
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  integer, parameter :: INITIAL_FRAMES = 8   !! nodal-system slots before the first doubling

  interface grow
     !! Make room for element n + 1 of an allocatable array (grow_template.inc).
     module procedure grow_node_frame
  end interface grow

  real(wp), parameter :: AXIS_TOL = 1.0e-9_wp
    !! A node closer to a cylindrical system's axis than this x the axis
    !! points' distance has no radial direction.
  integer, parameter :: BLOCK = 3

  public :: build_frames, cylinder_frame, link_frames

contains

  subroutine build_frames(st, model)
    !! model%frames from the *TRANSFORM cards; *CLOAD on their nodes to global axes.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(node_frame_t), allocatable :: list(:)
    integer(ip), allocatable :: nodes(:)
    integer :: k, isub, n, j
    integer(ip) :: i
    logical :: ok, twice
    real(wp) :: q(3, 3)

    allocate (list(INITIAL_FRAMES))
    n = 0
    do k = 1, st%ntransform
       associate (t => st%transforms(k))
         if (.not. t%has_data) cycle
         isub = resolve_sub(st, model, t%nset, t%loc, 'node')
         if (isub == 0) cycle
         call resolve_items(st, model, isub, t%nset, .false., t%loc, nodes, ok)
         if (.not. ok) cycle
         do i = 1, size(nodes, kind=ip)
            if (t%cylindrical) then
               if (.not. axis_defined(t%a, t%b)) exit   ! a = b: reported at the card
               if (.not. cylinder_frame(t%a, t%b, model%subs(isub)%x(:, nodes(i)), q)) then
                  call report_loc(st, t%loc, '*TRANSFORM, TYPE=C: node '//node_label(model, isub, nodes(i))// &
                       ' lies on the cylinder''s axis (no radial direction)')
                  cycle
               end if
            else
               q = rect_frame(t%a, t%b)
            end if
            twice = .false.
            do j = 1, n
               if (list(j)%sub == isub .and. list(j)%node == nodes(i)) then
                  call report_loc(st, t%loc, '*TRANSFORM: node '//node_label(model, isub, nodes(i))// &
                       ' already has a nodal system (from '//file_of(st, list(j)%loc%file)//':'// &
                       itoa(list(j)%loc%line)//')')
                  twice = .true.
               end if
            end do
            if (twice) cycle
            call grow(list, n, INITIAL_FRAMES)
            n = n + 1
            list(n)%sub = isub
            list(n)%node = nodes(i)
            list(n)%q = q
            list(n)%loc = t%loc
         end do
       end associate
    end do
    model%frames = list(1:n)
    if (n > 0) call loads_to_global(model)
  end subroutine build_frames

  subroutine link_frames(st, model)
    !! The frame of every link of a *CONTACT whose orientation is cylindrical
    !! (*ORIENTATION, SYSTEM=CYLINDRICAL): radial, tangential and axial at the
    !! midpoint of its two nodes, as CalculiX evaluates a cylindrical system
    !! where it is used.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: il, io
    real(wp) :: mid(3)
    if (.not. allocated(model%links)) return
    do il = 1, size(model%links)
       associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
         io = ct%orientation
         if (io <= 0) cycle
         if (.not. model%orientations(io)%cylindrical) cycle
         ! no axis (no data line, or a = b): reported at the *ORIENTATION card
         if (.not. axis_defined(model%orientations(io)%a, model%orientations(io)%b)) cycle
         mid = (model%subs(ct%master_sub)%x(:, lk%master_node) + model%subs(ct%slave_sub)%x(:, lk%slave_node))/2
         if (.not. cylinder_frame(model%orientations(io)%a, model%orientations(io)%b, mid, lk%q)) then
            call report_loc(st, lk%loc, '*CONTACT '//ct%name//', ORIENTATION='//model%orientations(io)%name// &
                 ': the pair '//node_label(model, ct%master_sub, lk%master_node)//' - '// &
                 node_label(model, ct%slave_sub, lk%slave_node)//' lies on the cylinder''s axis (no radial direction)')
            cycle
         end if
         lk%has_q = .true.
       end associate
    end do
  end subroutine link_frames

  pure function rect_frame(a, b) result(q)
    !! Rows: local 1 along a, 2 in the a-b plane, 3 = 1 x 2.
    real(wp), intent(in) :: a(3), b(3)
    real(wp) :: q(3, 3), e1(3), e2(3)
    e1 = a/norm2(a)
    e2 = b - dot_product(b, e1)*e1
    e2 = e2/norm2(e2)
    q(1, :) = e1
    q(2, :) = e2
    q(3, :) = cross(e1, e2)
  end function rect_frame

  pure logical function axis_defined(a, b)
    !! The points a and b of a cylindrical system are distinct (they define its axis).
    real(wp), intent(in) :: a(3), b(3)
    axis_defined = norm2(b - a) > 0.0_wp
  end function axis_defined

  logical function cylinder_frame(a, b, x, q) result(ok)
    !! Rows: radial (from the axis a-b to x), tangential, axial (a to b).
    real(wp), intent(in) :: a(3), b(3), x(3)
    real(wp), intent(out) :: q(3, 3)
    real(wp) :: e3(3), d(3)
    e3 = (b - a)/norm2(b - a)
    d = (x - a) - dot_product(x - a, e3)*e3
    ok = norm2(d) > AXIS_TOL*max(norm2(b - a), norm2(x - a))
    q = 0.0_wp
    if (.not. ok) return
    d = d/norm2(d)
    q(1, :) = d
    q(3, :) = e3
    q(2, :) = cross(e3, d)
  end function cylinder_frame

  pure function cross(u, v) result(w)
    real(wp), intent(in) :: u(3), v(3)
    real(wp) :: w(3)
    w = [u(2)*v(3) - u(3)*v(2), u(3)*v(1) - u(1)*v(3), u(1)*v(2) - u(2)*v(1)]
  end function cross

  subroutine loads_to_global(model)
    !! A *CLOAD component on a node with a nodal system is along that system's
    !! axis: split it into its global components (exact zeros left out).
    type(model_t), intent(inout) :: model
    type(cload_t), allocatable :: out(:)
    integer :: s, k, m, f, b, kl, c
    do s = 1, size(model%steps)
       if (.not. allocated(model%steps(s)%cloads)) cycle
       associate (cl => model%steps(s)%cloads)
         allocate (out(BLOCK*size(cl)))
         m = 0
         do k = 1, size(cl)
            f = frame_of_node(model, cl(k)%sub, cl(k)%node)
            if (f == 0) then
               m = m + 1
               out(m) = cl(k)
               cycle
            end if
            b = (cl(k)%dof - 1)/BLOCK
            kl = cl(k)%dof - BLOCK*b
            do c = 1, BLOCK
               if (model%frames(f)%q(kl, c) == 0.0_wp) cycle
               m = m + 1
               out(m) = cl(k)
               out(m)%dof = BLOCK*b + c
               out(m)%value = model%frames(f)%q(kl, c)*cl(k)%value
            end do
         end do
       end associate
       model%steps(s)%cloads = out(1:m)
       deallocate (out)
    end do
  end subroutine loads_to_global

  ! ------------------------------------------------------------------ growing arrays

#define GROW_NAME grow_node_frame
#define GROW_TYPE type(node_frame_t)
#include "grow_template.inc"

end module superjoin_deck_frame_build
