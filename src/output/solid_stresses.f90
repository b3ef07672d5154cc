module superjoin_output_solid_stresses
  !! *EL PRINT S and E of the 3D solid elements: the stress (with its von
  !! Mises value and principal stresses) or strain tensors at the integration
  !! points of each solid element of the set, as CalculiX's .dat prints them
  !! (points in CalculiX's order; superjoin_elements_solid_stress). The nodal
  !! values (*NODE PRINT S, nodal_stresses.csv) come with those of the plane
  !! and shell elements (superjoin_output_stresses, nodal_stresses).
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_model_types, only: model_t
  use superjoin_model_results, only: result_fields_t
  use superjoin_elements, only: element_stresses, von_mises_tensor, principal_stresses, NTENSOR
  use superjoin_elements_traits, only: is_family, FAMILY_SOLID
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop
  use superjoin_output_stresses, only: list_types
  implicit none (type, external)
  private

  character(len=15), parameter :: HEAD(NTENSOR + 4) = ['             xx', '             yy', &
       '             zz', '             xy', '             xz', '             yz', '      von Mises', &
       '             s1', '             s2', '             s3']

  type :: point_block_t
    !! The values at the points of one element.
     real(wp), allocatable :: v(:, :, :)
  end type point_block_t

  public :: write_solid_point_table, solid_elements

contains

  pure function solid_elements(model, subs, elems) result(yes)
    !! Per element of the list: a solid element.
    type(model_t), intent(in) :: model
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    logical :: yes(size(elems))
    yes = is_family(list_types(model, subs, elems), FAMILY_SOLID)
  end function solid_elements

  subroutine write_solid_point_table(lu, model, fields, is, subs, elems, strain)
    !! The stresses (strain false: with von Mises and the principal stresses
    !! s1 >= s2 >= s3) or strains at the integration points of the solid
    !! elements among `elems` (nothing if there are none).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    logical, intent(in) :: strain
    type(point_block_t), allocatable :: vals(:)
    real(wp), allocatable :: nodes(:, :, :)
    logical, allocatable :: ok(:)
    character(len=250) :: hline
    real(wp) :: scale, row(NTENSOR + 4)
    integer :: i, k, d, ncol
    character(:), allocatable :: axes
    allocate (ok, source=solid_elements(model, subs, elems))
    allocate (vals(size(elems)))
    scale = 0.0_wp
    do i = 1, size(elems)
       if (.not. ok(i)) cycle
       call element_stresses(model, fields, is, subs(i), elems(i), vals(i)%v, nodes, ok(i), strain)
       if (ok(i)) scale = max(scale, maxval(abs(vals(i)%v)))
    end do
    if (.not. any(ok)) return
    ncol = merge(NTENSOR, NTENSOR + 4, strain)
    axes = 'global axes'
    if (strain) axes = 'global axes, tensor shear strains'
    call lu%line('    '//merge('E', 'S', strain)//'   at the integration points of the solid elements ('//axes// &
         '; as CalculiX: C3D8, C3D20R 2x2x2 Gauss, C3D20 3x3x3, xi fastest from corner 1; C3D4 the centroid; '// &
         'C3D10 4 points, point k next to corner k)')
    write (hline, '(4x,a20,a10,a6,a4,10a15)') 'substructure        ', '   element', '  type', '  ip', HEAD(1:ncol)
    call lu%line(trim(hline))
    do i = 1, size(elems)
       if (.not. ok(i)) cycle
       do k = 1, size(vals(i)%v, 2)
          row(1:NTENSOR) = vals(i)%v(:, k, 1)
          if (.not. strain) row(NTENSOR + 1:) = [von_mises_tensor(row(1:NTENSOR)), principal_stresses(row(1:NTENSOR))]
          call element_prefix(lu, model, subs(i), elems(i), 4)
          call lu%put_int(int(k, i8), 4)
          do d = 1, ncol
             call lu%put_es(chop(row(d), scale))
          end do
          call lu%newline()
       end do
    end do
  end subroutine write_solid_point_table
end module superjoin_output_solid_stresses
