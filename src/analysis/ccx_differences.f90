module superjoin_analysis_ccx_differences
  !! Where a deck's answers would differ from CalculiX's for a reason of
  !! convention or method, the run says so (stderr and the health block)
  !! instead of differing without a word:
  !! - Plane elements interpolate a temperature that varies between their
  !!   nodes to their integration points, as CalculiX does; the shells (S3, S4,
  !!   S3R, S4R, S8R) take each element's mean temperature change and mean
  !!   gradient: a step with shells whose nodal values differ is warned.
  use superjoin_model_types, only: model_t, string_t, loc_text
  use superjoin_utils_strings, only: itoa
  use superjoin_analysis_notes, only: append_string
  implicit none (type, external)
  private

  public :: check_ccx_differences

contains

  subroutine check_ccx_differences(model, warnings)
    !! Append the warnings of this module for every step.
    type(model_t), intent(in) :: model
    type(string_t), allocatable, intent(inout) :: warnings(:)
    call check_shell_temperatures(model, warnings)
  end subroutine check_ccx_differences

  subroutine check_shell_temperatures(model, warnings)
    !! Append a warning for every step in which some shell element's nodal
    !! temperature changes (or gradients) differ (validation counts them).
    type(model_t), intent(in) :: model
    type(string_t), allocatable, intent(inout) :: warnings(:)
    integer :: s
    do s = 1, size(model%steps)
       associate (step => model%steps(s))
         if (step%shell_mean_temperatures == 0) cycle
         call append_string(warnings, 'step '//step%name//' ('//loc_text(model, step%loc)//'): '// &
              itoa(step%shell_mean_temperatures)//' shell element(s) have nodal temperatures (or gradients) '// &
              'that differ between their nodes; superjoin applies each shell element''s mean, CalculiX '// &
              'interpolates them to the integration points. Refine the mesh where the temperature varies '// &
              '(plane elements interpolate, as CalculiX)')
       end associate
    end do
  end subroutine check_shell_temperatures
end module superjoin_analysis_ccx_differences
