module superjoin_analysis_labels
  !! Human names of reduced unknowns and vertices for messages and the listing.
  use superjoin_kinds, only: i8
  use superjoin_model_types, only: model_t, node_label
  use superjoin_assembly_dofs, only: dof_table_t, UNIT_LINK, GROUND, block_dof
  use superjoin_assembly_transform, only: transform_t, COL_PHYS, COL_DELTA
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  public :: column_label, vertex_label, block_name, local_name

contains

  function column_label(model, table, tr, j) result(label)
    !! Human name of a reduced unknown: substructure, node and DOF, or the
    !! contact/support and the component of its Δ.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    integer(i8), intent(in) :: j
    character(:), allocatable :: label
    integer(i8) :: p
    integer :: iu, k
    select case (tr%column_kind(j))
    case (COL_PHYS)
       p = tr%column_ref(j)
       label = 'substructure '//model%subs(table%p_sub(p))%name//' node '// &
            itoa(int(model%subs(table%p_sub(p))%node_id(table%p_node(p))))//' DOF '//itoa(int(table%p_dof(p)))
    case (COL_DELTA)
       iu = int(tr%column_ref(j))
       k = tr%column_comp(j)
       associate (u => table%units(iu))
         if (u%kind == UNIT_LINK) then
            label = 'contact '//model%contacts(model%links(u%source)%contact)%name//' ('// &
                 vertex_label(model, table, u%va)//' - '//vertex_label(model, table, u%vb)//') relative DOF '// &
                 itoa(block_dof(u%block, u%lcomp(k)))
         else
            label = 'elastic support at '//vertex_label(model, table, u%vb)//' DOF '// &
                 itoa(block_dof(u%block, u%comp(k)))
         end if
       end associate
    case default
       label = 'unknown '//itoa(int(j))
    end select
  end function column_label

  function vertex_label(model, table, v) result(label)
    !! "SUB.id" of a vertex (ground: "ground").
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer(i8), intent(in) :: v
    character(:), allocatable :: label
    integer :: isub
    if (v == GROUND) then
       label = 'ground'
       return
    end if
    do isub = 1, size(model%subs)
       if (v <= table%vertex_offset(isub + 1)) exit
    end do
    label = node_label(model, isub, int(v - table%vertex_offset(isub), kind(model%subs(1)%nnode)))
  end function vertex_label

  pure function block_name(b) result(s)
    integer, intent(in) :: b
    character(:), allocatable :: s
    if (b == 1) then
       s = 'translations'
    else
       s = 'rotations'
    end if
  end function block_name

  pure function local_name(b, c) result(s)
    integer, intent(in) :: b, c
    character(:), allocatable :: s
    s = 'DOF '//itoa(block_dof(b, c))
  end function local_name
end module superjoin_analysis_labels
