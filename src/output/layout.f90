module superjoin_output_layout
  !! Which columns and rows of the listing's standard tables can carry a value
  !! (issue 12, readable results):
  !! - a planar model, whose elements are all T2D2, B21, B23, CPS3, CPS4, CPE3
  !!   or CPE4 (and which has at least one element), has no u3, ur1, ur2: its
  !!   DISPLACEMENTS table shows u1, u2, ur3;
  !! - a node has the DOFs that its elements carry (element_dof_mask) and those
  !!   of the contact elements on it (the DOF itself; every DOF of its block,
  !!   translations or rotations, for a contact with an orientation); a support
  !!   on any other DOF gives no row of SUPPORT REACTIONS;
  !! - trusses (T2D2, T3D2) print one axial force per bar (TRUSS AXIAL FORCES)
  !!   instead of rows of ELEMENT END FORCES.
  use, intrinsic :: iso_fortran_env, only: int8
  use superjoin_kinds, only: i8, ip
  use superjoin_model_types, only: model_t, frame_of_node, NDOF_NODE, LINK_NONE, ELEMENT_NODE_COUNT, NUM_ELEMENT_TYPES
  use superjoin_elements, only: element_dof_mask
  use superjoin_elements_traits, only: element_traits_t, element_traits, is_family, FAMILY_TRUSS
  implicit none (type, external)
  private

  integer, parameter :: BLOCK = 3
    !! DOFs per block (translations 1-3, rotations 4-6).

  public :: is_planar_model, node_dof_mask, is_truss, displacement_columns
  public :: has_node_frames, in_node_frame, REACTION_FRAME_NOTE, FRAME_MARK

  character(*), parameter :: REACTION_FRAME_NOTE = &
       'global axes; rows marked L: the node''s *TRANSFORM system'
    !! How a reactions table of a model with nodal systems names its axes.
  character(*), parameter :: FRAME_MARK = '  L'
    !! The mark after a reaction row in a node's *TRANSFORM system.

contains

  pure logical function is_planar_model(model)
    !! True when every element of the model is T2D2, B21, B23, CPS3, CPS4,
    !! CPE3 or CPE4 (and there is at least one): planar and first order (the
    !! second-order plane elements do not count).
    type(model_t), intent(in) :: model
    type(element_traits_t) :: t
    integer :: isub, k
    integer(ip) :: e
    logical :: any_element, planar(NUM_ELEMENT_TYPES)
    do k = 1, NUM_ELEMENT_TYPES
       t = element_traits(k)
       planar(k) = t%planar .and. .not. t%quadratic
    end do
    is_planar_model = .true.
    any_element = .false.
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          any_element = .true.
          if (.not. planar(model%subs(isub)%elem_type(e))) then
             is_planar_model = .false.
             return
          end if
       end do
    end do
    is_planar_model = any_element
  end function is_planar_model

  pure subroutine displacement_columns(model, cols, ncol)
    !! The DOFs of the DISPLACEMENTS table, cols(1:ncol): 1, 2, 6 in a planar
    !! model, else 1-6.
    type(model_t), intent(in) :: model
    integer, intent(out) :: cols(NDOF_NODE)
    integer, intent(out) :: ncol
    integer :: d
    cols = [(d, d=1, NDOF_NODE)]
    ncol = NDOF_NODE
    if (is_planar_model(model)) then
       cols(1:3) = [1, 2, 6]
       ncol = 3
    end if
  end subroutine displacement_columns

  elemental logical function is_truss(etype)
    !! T2D2 and T3D2.
    integer, intent(in) :: etype
    is_truss = is_family(etype, FAMILY_TRUSS)
  end function is_truss

  pure subroutine node_dof_mask(model, vertex_offset, mask)
    !! Bit d - 1 of mask(v): node v (numbered by vertex_offset over the
    !! substructures) has DOF d from an element or a contact element.
    type(model_t), intent(in) :: model
    integer(i8), intent(in) :: vertex_offset(:)
    integer(int8), allocatable, intent(out) :: mask(:)
    integer :: isub, a, il, d, b, k
    integer(ip) :: e
    integer(i8) :: nv, vm, vs
    integer(int8) :: m(NUM_ELEMENT_TYPES), bits
    nv = vertex_offset(size(model%subs) + 1)
    allocate (mask(nv), source=0_int8)
    do k = 1, NUM_ELEMENT_TYPES
       m(k) = dof_bits(element_dof_mask(k))
    end do
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub), v0 => vertex_offset(isub))
         do e = 1, sub%nelem
            bits = m(sub%elem_type(e))
            do a = 1, ELEMENT_NODE_COUNT(sub%elem_type(e))
               mask(v0 + sub%elem_nodes(a, e)) = ior(mask(v0 + sub%elem_nodes(a, e)), bits)
            end do
         end do
       end associate
    end do
    do il = 1, size(model%links)
       associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
         vm = vertex_offset(ct%master_sub) + lk%master_node
         vs = vertex_offset(ct%slave_sub) + lk%slave_node
         do d = 1, NDOF_NODE
            if (lk%state(d) == LINK_NONE) cycle
            if (ct%orientation > 0) then
               b = (d - 1)/BLOCK
               bits = int(shiftl(7, b*BLOCK), int8)   ! the DOFs of its block
            else
               bits = int(shiftl(1, d - 1), int8)
            end if
            mask(vm) = ior(mask(vm), bits)
            mask(vs) = ior(mask(vs), bits)
         end do
       end associate
    end do
  end subroutine node_dof_mask

  pure integer(int8) function dof_bits(dofs) result(bits)
    !! dofs(1:NDOF_NODE) as bits 0 .. NDOF_NODE - 1.
    logical, intent(in) :: dofs(NDOF_NODE)
    integer :: d
    bits = 0_int8
    do d = 1, NDOF_NODE
       if (dofs(d)) bits = ibset(bits, d - 1)
    end do
  end function dof_bits

  pure logical function has_node_frames(model)
    !! True when some node of the model has a nodal system (*TRANSFORM): its
    !! supports and so its reactions are along that system's axes.
    type(model_t), intent(in) :: model
    has_node_frames = .false.
    if (allocated(model%frames)) has_node_frames = size(model%frames) > 0
  end function has_node_frames

  pure logical function in_node_frame(model, isub, node)
    !! True when node `node` of substructure isub has a nodal system.
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: node
    in_node_frame = frame_of_node(model, isub, node) > 0
  end function in_node_frame
end module superjoin_output_layout
