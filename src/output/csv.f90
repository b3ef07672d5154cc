module superjoin_output_csv
  !! Full-precision CSV results (17 significant digits), one file per table,
  !! each written to a temporary name and renamed when complete.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE, ELEMENT_TYPE_NAMES
  use superjoin_output_file_selection, only: file_selection_t, select_file_output, NUM_FILE_RESULTS
  use superjoin_elements, only: is_plate_type
  use superjoin_elements_traits, only: is_family, FAMILY_TRUSS, FAMILY_BEAM
  use superjoin_model_results, only: result_fields_t
  use superjoin_utils_posix, only: remove_file, make_directory
  use superjoin_utils_process, only: temp_register, temp_unregister
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_utils_strings, only: itoa, full_real
  use superjoin_output_layout, only: has_node_frames, in_node_frame
  implicit none (type, external)
  private

  public :: write_csv

  character(len=18), parameter :: TABLE_FILES(NUM_FILE_RESULTS) = [character(len=18) :: 'displacements.csv', &
       'reactions.csv', 'contact_forces.csv', 'element_forces.csv', 'plate_results.csv']

contains

  subroutine write_csv(dir, model, fields, error)
    !! Write displacements.csv, reactions.csv, contact_forces.csv and
    !! element_forces.csv into dir (created if needed), and plate_results.csv
    !! when the model has plane-stress or shell elements. With *NODE FILE
    !! (*EL FILE) requests, the node (element) tables are those their variables
    !! name (U: displacements, RF: reactions; S, E, SF: element tables), for the
    !! nodes (elements) of their sets; contact forces are always written. A
    !! table not written is removed, so that one of an earlier run into the
    !! same directory does not survive.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(file_selection_t) :: sel
    integer :: k
    call make_directory(dir, error)
    if (allocated(error)) return
    call select_file_output(model, sel)
    do k = 1, NUM_FILE_RESULTS
       if (sel%kind(k)) then
          call write_table(dir//'/'//trim(TABLE_FILES(k)), k, model, fields, sel, error)
          if (allocated(error)) return
       else
          call remove_file(dir//'/'//trim(TABLE_FILES(k)))
       end if
    end do
  end subroutine write_csv

  subroutine write_table(path, which, model, fields, sel, error)
    !! One CSV table (which: 1 displacements, 2 reactions, 3 contact forces,
    !! 4 element forces, 5 plate results) of the selected nodes or elements,
    !! through the buffered writer.
    character(*), intent(in) :: path
    integer, intent(in) :: which
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(file_selection_t), intent(in) :: sel
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    integer :: is, isub, d, k, il
    integer(ip) :: n
    integer(i8) :: v
    character(:), allocatable :: tmp

    tmp = path//'.tmp'
    call temp_register(tmp)
    allocate (tb)
    call tb%open(tmp, error)
    if (allocated(error)) then
       call temp_unregister()
       return
    end if
    select case (which)
    case (1)
       call tb%line('step,substructure,node,u1,u2,u3,ur1,ur2,ur3')
       do is = 1, size(model%steps)
          if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
          do isub = 1, size(model%subs)
             do n = 1, model%subs(isub)%nnode
                v = fields%vertex_offset(isub) + n
                if (.not. any(fields%has_dof(:, v)) .or. .not. sel%node(v)) cycle
                call keys(tb, model%steps(is)%name, model%subs(isub)%name, int(model%subs(isub)%node_id(n), i8))
                call reals(tb, fields%u(NDOF_NODE*(v - 1) + 1:NDOF_NODE*v, is))
             end do
          end do
       end do
    case (2)
       ! A model with nodal systems says per row whose axes the force is along.
       if (has_node_frames(model)) then
          call tb%line('step,substructure,node,dof,force,axes')
       else
          call tb%line('step,substructure,node,dof,force')
       end if
       do is = 1, size(model%steps)
          if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
          do k = 1, size(fields%steps(is)%reactions)
             associate (rc => fields%steps(is)%reactions(k))
               if (.not. sel%node(fields%vertex_offset(rc%sub) + rc%node)) cycle
               call keys(tb, model%steps(is)%name, model%subs(rc%sub)%name, &
                    int(model%subs(rc%sub)%node_id(rc%node), i8), int(rc%dof, i8))
               if (has_node_frames(model)) then
                  call tb%put(','//full_real(rc%force))
                  if (in_node_frame(model, rc%sub, rc%node)) then
                     call tb%line(',transform')
                  else
                     call tb%line(',global')
                  end if
               else
                  call reals(tb, [rc%force])
               end if
             end associate
          end do
       end do
    case (3)
       call tb%line('step,contact,master_node,slave_node,dof,delta,force')
       do is = 1, size(model%steps)
          if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
          do il = 1, size(model%links)
             associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
               do d = 1, NDOF_NODE
                  if (.not. fields%link_used(d, il)) cycle
                  call keys(tb, model%steps(is)%name, ct%name, &
                       int(model%subs(ct%master_sub)%node_id(lk%master_node), i8), &
                       int(model%subs(ct%slave_sub)%node_id(lk%slave_node), i8), int(d, i8))
                  call reals(tb, [fields%steps(is)%link_delta(d, il), fields%steps(is)%link_force(d, il)])
               end do
             end associate
          end do
       end do
    case (4:5)
       call element_table(tb, which, model, fields, sel)
    end select
    call tb%commit(tmp, path, '', error)
  end subroutine write_table

  subroutine element_table(tb, which, model, fields, sel)
    !! The rows of an element table (which: 4 element forces of the trusses
    !! and beams, 5 plate results of the plane and shell elements) of the
    !! selected elements.
    type(text_buffer_t), intent(inout) :: tb
    integer, intent(in) :: which
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(file_selection_t), intent(in) :: sel
    integer :: is, isub, k, e
    integer(i8) :: iel
    select case (which)
    case (4)
       call tb%line('step,substructure,element,type,end,n,vy,vz,t,my,mz')
       do is = 1, size(model%steps)
          if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
          do isub = 1, size(model%subs)
             do e = 1, model%subs(isub)%nelem
                if (.not. any(is_family(model%subs(isub)%elem_type(e), [FAMILY_TRUSS, FAMILY_BEAM]))) cycle
                iel = fields%elem_offset(isub) + e
                if (.not. sel%elem(iel)) cycle
                do k = 1, 2
                   call keys(tb, model%steps(is)%name, model%subs(isub)%name, int(model%subs(isub)%elem_id(e), i8))
                   call tb%put(','//trim(ELEMENT_TYPE_NAMES(model%subs(isub)%elem_type(e)))//','//itoa(k))
                   call reals(tb, fields%elem_force(:, k, iel, is))
                end do
             end do
          end do
       end do
    case (5)
       call tb%line('step,substructure,element,nx,ny,nxy,mx,my,mxy')
       do is = 1, size(model%steps)
          if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
          do isub = 1, size(model%subs)
             do e = 1, model%subs(isub)%nelem
                if (.not. is_plate_type(model%subs(isub)%elem_type(e))) cycle
                iel = fields%elem_offset(isub) + e
                if (.not. sel%elem(iel)) cycle
                call keys(tb, model%steps(is)%name, model%subs(isub)%name, int(model%subs(isub)%elem_id(e), i8))
                call reals(tb, fields%plate(:, iel, is))
             end do
          end do
       end do
    end select
  end subroutine element_table

  subroutine keys(tb, a, b, i1, i2, i3)
    !! The leading columns of a row: two names and up to three integers.
    type(text_buffer_t), intent(inout) :: tb
    character(*), intent(in) :: a, b
    integer(i8), intent(in) :: i1
    integer(i8), intent(in), optional :: i2, i3
    call tb%put(a//','//b//',')
    call tb%put_int(i1, 0)
    if (present(i2)) then
       call tb%put(',')
       call tb%put_int(i2, 0)
    end if
    if (present(i3)) then
       call tb%put(',')
       call tb%put_int(i3, 0)
    end if
  end subroutine keys

  subroutine reals(tb, x)
    !! ',' and each value with 17 significant digits, then the end of the row.
    type(text_buffer_t), intent(inout) :: tb
    real(wp), intent(in) :: x(:)
    integer :: j
    do j = 1, size(x)
       call tb%put(',')
       call tb%put(full_real(x(j)))
    end do
    call tb%newline()
  end subroutine reals
end module superjoin_output_csv
