module superjoin_deck_build_section_prints
  !! *SECTION PRINT, SURFACE=s: the faces of the *SURFACE, TYPE=ELEMENT named
  !! s, resolved to (substructure, element, face) of solid elements, into
  !! model%section_prints. Faces of plane elements (edges) and shells (SPOS,
  !! SNEG) are refused: CalculiX integrates solid faces only.
  use superjoin_kinds, only: ip
  use superjoin_model_types, only: model_t, section_print_t, DLOAD_P1, DLOAD_P4, DLOAD_P5, DLOAD_P6
  use superjoin_deck_state, only: deck_state_t, report_loc
  use superjoin_deck_build_common, only: resolve_sub, resolve_items
  use superjoin_elements_solid_faces, only: solid_face_nodes
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  public :: build_section_prints

contains

  subroutine build_section_prints(st, model)
    !! Resolve every *SECTION PRINT card of `st` (errors to st).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: k, j
    if (.not. allocated(st%section_prints)) return
    model%section_prints = st%section_prints
    do k = 1, size(model%section_prints)
       associate (sp => model%section_prints(k))
         allocate (sp%subs(0), sp%elems(0), sp%faces(0))
         do j = 1, st%nsurface
            if (st%surfaces(j)%name == sp%surface) exit
         end do
         if (j > st%nsurface) then
            call report_loc(st, sp%loc, '*SECTION PRINT: unknown surface '//sp%surface// &
                 ' (define it with *SURFACE, TYPE=ELEMENT)')
         else
            call add_faces(st, model, j, sp)
         end if
       end associate
    end do
  end subroutine build_section_prints

  subroutine add_faces(st, model, j, sp)
    !! The faces of surface j, each checked to be a face of a solid element.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: j
    type(section_print_t), intent(inout) :: sp
    integer(ip), allocatable :: items(:)
    integer, allocatable :: nodes(:)
    integer :: i, isub, face, nc, m
    logical :: ok
    associate (sf => st%surfaces(j))
      if (sf%nodal) then
         call report_loc(st, sp%loc, '*SECTION PRINT: surface '//sp%surface//' is a node surface (TYPE=NODE): '// &
              'a section is made of faces S1 to S6 of solid elements (*SURFACE, TYPE=ELEMENT)')
         return
      end if
      do i = 1, sf%n
         face = face_number(sf%kinds(i))
         if (face == 0) then
            call report_loc(st, sp%loc, '*SECTION PRINT: surface '//sp%surface//' has faces of shells or '// &
                 'plane elements (SPOS, SNEG, edges); a section is made of faces S1 to S6 of solid elements')
            return
         end if
         isub = resolve_sub(st, model, sf%refs(i), sf%loc, 'element')
         if (isub == 0) return
         call resolve_items(st, model, isub, sf%refs(i), .true., sf%loc, items, ok)
         if (.not. ok) return
         do m = 1, size(items)
            call solid_face_nodes(model%subs(isub)%elem_type(items(m)), face, nodes, nc)
            if (nc == 0) then
               call report_loc(st, sp%loc, '*SECTION PRINT: surface '//sp%surface//': element '// &
                    itoa(model%subs(isub)%elem_id(items(m)))//' is not a solid element with a face S'// &
                    itoa(face))
               return
            end if
         end do
         sp%subs = [sp%subs, spread(isub, 1, size(items))]
         sp%elems = [sp%elems, items]
         sp%faces = [sp%faces, spread(face, 1, size(items))]
      end do
    end associate
  end subroutine add_faces

  pure integer function face_number(kind) result(face)
    !! The face (1..6) of a surface line's load form; 0 for SPOS / SNEG.
    integer, intent(in) :: kind
    face = 0
    if (kind >= DLOAD_P1 .and. kind <= DLOAD_P4) face = kind - DLOAD_P1 + 1
    if (kind == DLOAD_P5) face = 5
    if (kind == DLOAD_P6) face = 6
  end function face_number
end module superjoin_deck_build_section_prints
