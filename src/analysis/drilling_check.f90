module superjoin_analysis_drilling_check
  !! Rotations prescribed on some but not all of DOFs 4-6 of a shell node
  !! (issue 25 item 4, CalculiX's shell7rot): superjoin's shells keep the
  !! rotation about their normal (drilling) as a DOF held only by a small
  !! penalty. A prescribed rotation about an axis oblique to the normal mixes
  !! it with the shell's own (bending) rotations, so the answer hangs on the
  !! penalty (the plate of shell7 turned 45°, θx and θy prescribed: the node
  !! turns 0.0173 instead of 0.01). CalculiX applies the condition to the
  !! shell's own rotations. Such nodes are warned, once per substructure with
  !! a count and the first node; an axis along the normal or in the shell's
  !! plane (every untilted plate) is clean.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, node_label, frame_of_node, string_t, support_t, LINK_RIGID, NUM_ELEMENT_TYPES
  use superjoin_elements_traits, only: element_traits_t, all_element_traits, FAMILY_SHELL
  use superjoin_elements_frame, only: cross
  use superjoin_utils_strings, only: itoa
  use superjoin_model_notes, only: append_string
  implicit none (type, external)
  private

  public :: check_partial_rotations

  real(wp), parameter :: OBLIQUE_TOL = 1.0e-6_wp
    !! |axis · normal| above this and below 1 - this: the axis is oblique

contains

  subroutine check_partial_rotations(model, warnings)
    !! Append one warning per substructure whose shell nodes have rotations
    !! prescribed (rigid supports, *BOUNDARY) on one or two of DOFs 4-6 about
    !! an axis oblique to the shell's normal there (the node's *TRANSFORM axes
    !! where it has one).
    type(model_t), intent(in) :: model
    type(string_t), allocatable, intent(inout) :: warnings(:)
    real(wp), allocatable :: normal(:, :)
    integer, allocatable :: held(:)
    integer :: isub, nbad
    integer(ip) :: n, first
    do isub = 1, size(model%subs)
       call node_normals(model, isub, normal)
       if (.not. any(normal /= 0.0_wp)) cycle
       allocate (held(model%subs(isub)%nnode))
       held = 0
       call held_rotations(model, isub, held)
       nbad = 0
       first = 0
       do n = 1, model%subs(isub)%nnode
          if (popcnt(held(n)) == 0 .or. popcnt(held(n)) == 3) cycle
          if (.not. oblique(axes_of(model, isub, n), held(n), normal(:, n))) cycle
          nbad = nbad + 1
          if (first == 0) first = n
       end do
       deallocate (held)
       if (nbad == 0) cycle
       call append_string(warnings, 'rotations prescribed on only some of DOFs 4-6 at '//itoa(nbad)// &
            ' shell node(s), the first '//node_label(model, isub, first)//', about axes oblique to the '// &
            'shell''s normal: each mixes the drilling rotation, held only by its penalty, with the shell''s '// &
            'own rotations, so the answer depends on the drilling penalty (CalculiX applies the condition '// &
            'to the shell''s own rotations); prescribe all three rotations, or turn the node''s axes with '// &
            '*TRANSFORM so that one is the normal')
    end do
  end subroutine check_partial_rotations

  subroutine node_normals(model, isub, normal)
    !! Sum of the unit normals of the shell elements at each node (0: no shell).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    real(wp), allocatable, intent(out) :: normal(:, :)
    type(element_traits_t) :: tr, traits(NUM_ELEMENT_TYPES)
    real(wp) :: a(3), b(3), c(3)
    integer(ip) :: e
    integer :: k
    traits = all_element_traits()   ! once per type, not per element
    associate (sub => model%subs(isub))
      allocate (normal(3, sub%nnode))
      normal = 0.0_wp
      do e = 1, sub%nelem
         if (traits(sub%elem_type(e))%family /= FAMILY_SHELL) cycle
         tr = traits(sub%elem_type(e))
         associate (x => sub%x(:, sub%elem_nodes(1:tr%corners, e)))
           if (tr%corners == 3) then
              a = x(:, 2) - x(:, 1)
              b = x(:, 3) - x(:, 1)
           else
              a = x(:, 3) - x(:, 1)
              b = x(:, 4) - x(:, 2)
           end if
         end associate
         c = cross(a, b)
         if (norm2(c) == 0.0_wp) cycle
         do k = 1, tr%nodes
            normal(:, sub%elem_nodes(k, e)) = normal(:, sub%elem_nodes(k, e)) + c/norm2(c)
         end do
      end do
    end associate
  end subroutine node_normals

  subroutine held_rotations(model, isub, held)
    !! Bits 0-2 of held(n): rotation 4, 5, 6 of node n rigidly prescribed in
    !! the model's supports or in those of some step.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer, intent(inout) :: held(:)
    integer :: s
    call mark(model%supports)
    if (.not. allocated(model%steps)) return
    do s = 1, size(model%steps)
       if (allocated(model%steps(s)%supports)) call mark(model%steps(s)%supports)
    end do
  contains
    subroutine mark(sups)
      type(support_t), intent(in) :: sups(:)
      integer :: k
      do k = 1, size(sups)
         if (sups(k)%sub /= isub .or. sups(k)%dof < 4 .or. sups(k)%state /= LINK_RIGID) cycle
         held(sups(k)%node) = ior(held(sups(k)%node), ishft(1, sups(k)%dof - 4))
      end do
    end subroutine mark
  end subroutine held_rotations

  pure function axes_of(model, isub, n) result(q)
    !! Rows: the axes of node n's DOFs (its *TRANSFORM, or the global axes).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: n
    real(wp) :: q(3, 3)
    integer :: k
    q = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
    k = frame_of_node(model, isub, n)
    if (k > 0) q = model%frames(k)%q
  end function axes_of

  pure logical function oblique(q, held, normal)
    !! Some held axis (row of q) is neither along the normal nor normal to it.
    real(wp), intent(in) :: q(3, 3), normal(3)
    integer, intent(in) :: held
    real(wp) :: c
    integer :: i
    oblique = .false.
    if (norm2(normal) == 0.0_wp) return
    do i = 1, 3
       if (.not. btest(held, i - 1)) cycle
       c = abs(dot_product(q(i, :), normal))/(norm2(q(i, :))*norm2(normal))
       if (c > OBLIQUE_TOL .and. c < 1.0_wp - OBLIQUE_TOL) oblique = .true.
    end do
  end function oblique
end module superjoin_analysis_drilling_check
