module superjoin_output_columns
  !! Pieces of the listing's tables shared by its sections: the element
  !! columns of a row, and round-off noise printed as zero.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t, ELEMENT_TYPE_NAMES
  use superjoin_utils_text_buffer, only: text_buffer_t
  implicit none (type, external)
  private

  real(wp), parameter, public :: CHOP_FRACTION = 1.0e-13_wp
    !! Values below this fraction of the largest value of their table print as zero.

  public :: element_prefix, chop

contains

  subroutine element_prefix(lu, model, isub, ie, indent)
    !! Substructure, element id and type columns of an element row, after
    !! `indent` blanks.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: ie
    integer, intent(in) :: indent
    call lu%put(repeat(' ', indent))
    call lu%put_field(model%subs(isub)%name, 20)
    call lu%put_int(int(model%subs(isub)%elem_id(ie), i8), 10)
    ! a five-letter type (CPS8R) takes one of the two blanks: the columns stay in place
    ! (a six-letter one, C3D20R, shifts the rest of its row by one)
    associate (name => ELEMENT_TYPE_NAMES(model%subs(isub)%elem_type(ie)))
      if (len_trim(name) > 5) then
         call lu%put(' ')
         call lu%put_field(name, 6)
      else if (len_trim(name) > 4) then
         call lu%put(' ')
         call lu%put_field(name, 5)
      else
         call lu%put('  ')
         call lu%put_field(name, 4)
      end if
    end associate
  end subroutine element_prefix

  elemental function chop(x, scale) result(y)
    !! Round-off noise relative to the table's scale prints as zero.
    real(wp), intent(in) :: x, scale
    real(wp) :: y
    y = x
    if (abs(x) <= CHOP_FRACTION*scale) y = 0.0_wp
  end function chop
end module superjoin_output_columns
