module superjoin_output_columns
  !! Pieces of the listing's tables shared by its sections: the element
  !! columns of a row, and round-off noise printed as zero.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t, ELEMENT_TYPE_NAMES, NUM_ELEMENT_TYPES
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_elements, only: is_plate_type, is_plane_type, is_plane_strain_type
  use superjoin_output_layout, only: is_truss
  implicit none (type, external)
  private

  real(wp), parameter, public :: CHOP_FRACTION = 1.0e-13_wp
    !! Values below this fraction of the largest value of their table print as zero.

  type, public :: element_kinds_t
    !! What the tables ask of each element type, looked up once for all types
    !! instead of once per element row.
     logical :: plate(NUM_ELEMENT_TYPES) = .false.         !! plane and shell types
     logical :: plane(NUM_ELEMENT_TYPES) = .false.         !! CPS*, CPE*
     logical :: plane_strain(NUM_ELEMENT_TYPES) = .false.  !! CPE*
     logical :: truss(NUM_ELEMENT_TYPES) = .false.         !! T2D2, T3D2
  end type element_kinds_t

  ! The type column of an element row: a five-letter type (CPS8R) takes one of
  ! the two blanks, so the columns stay in place (a six-letter one, C3D20R,
  ! shifts the rest of its row by one); the names are 6 characters, blank-padded.
  logical, parameter :: SIX_LETTERS(NUM_ELEMENT_TYPES) = ELEMENT_TYPE_NAMES(:)(6:6) /= ' '
    !! the types whose names have six letters
  character(len=7), parameter :: TYPE_TAIL(NUM_ELEMENT_TYPES) = merge(' '//ELEMENT_TYPE_NAMES, &
       merge(' '//ELEMENT_TYPE_NAMES(:)(1:5)//' ', '  '//ELEMENT_TYPE_NAMES(:)(1:4)//' ', &
       ELEMENT_TYPE_NAMES(:)(5:5) /= ' '), SIX_LETTERS)
    !! the type column of each element type, its first TYPE_TAIL_LEN characters
  integer, parameter :: TYPE_TAIL_LEN(NUM_ELEMENT_TYPES) = merge(7, 6, SIX_LETTERS)
    !! the width of each type's column: 7 for a six-letter name, else 6

  public :: element_prefix, chop, element_kinds

contains

  subroutine element_prefix(lu, model, isub, ie, indent)
    !! Substructure, element id and type columns of an element row, after
    !! `indent` blanks.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: ie
    integer, intent(in) :: indent
    integer(i8) :: id
    integer :: t
    id = int(model%subs(isub)%elem_id(ie), i8)
    t = model%subs(isub)%elem_type(ie)
    call lu%put_row_head(indent, model%subs(isub)%name, 20, id, 10, TYPE_TAIL(t)(1:TYPE_TAIL_LEN(t)))
  end subroutine element_prefix

  pure function element_kinds() result(k)
    !! The element_kinds_t of every element type.
    type(element_kinds_t) :: k
    integer :: t
    do t = 1, NUM_ELEMENT_TYPES
       k%plate(t) = is_plate_type(t)
       k%plane(t) = is_plane_type(t)
       k%plane_strain(t) = is_plane_strain_type(t)
       k%truss(t) = is_truss(t)
    end do
  end function element_kinds

  elemental function chop(x, scale) result(y)
    !! Round-off noise relative to the table's scale prints as zero.
    real(wp), intent(in) :: x, scale
    real(wp) :: y
    y = x
    if (abs(x) <= CHOP_FRACTION*scale) y = 0.0_wp
  end function chop
end module superjoin_output_columns
