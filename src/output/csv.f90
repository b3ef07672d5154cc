module superjoin_output_csv
  !! Full-precision CSV results (17 significant digits), one file per table,
  !! each written to a temporary name and renamed when complete.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, fatal_error, EXIT_IO
  use superjoin_model_types, only: model_t, NDOF_NODE, ELEMENT_TYPE_NAMES, ET_T2D2, ET_T3D2, &
       ET_B23, ET_B33
  use superjoin_analysis_results, only: results_t
  use superjoin_elements, only: is_plate_type
  use superjoin_output_posix, only: rename_file, remove_file, make_directory
  use superjoin_utils_process, only: temp_register, temp_unregister
  use superjoin_output_text_buffer, only: check_file_size
  use superjoin_utils_strings, only: itoa, full_real
  implicit none (type, external)
  private

  public :: write_csv

  integer, parameter :: IOMSG_LEN = 256   !! length of an I/O error message

contains

  subroutine write_csv(dir, model, res, error)
    !! Write displacements.csv, reactions.csv, contact_forces.csv and
    !! element_forces.csv into dir (created if needed), and plate_results.csv
    !! when the model has plane-stress or shell elements.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    call make_directory(dir, error)
    if (allocated(error)) return
    call write_table(dir//'/displacements.csv', 1, model, res, error)
    if (allocated(error)) return
    call write_table(dir//'/reactions.csv', 2, model, res, error)
    if (allocated(error)) return
    call write_table(dir//'/contact_forces.csv', 3, model, res, error)
    if (allocated(error)) return
    call write_table(dir//'/element_forces.csv', 4, model, res, error)
    if (allocated(error)) return
    if (any_plates(model)) call write_table(dir//'/plate_results.csv', 5, model, res, error)
  end subroutine write_csv

  pure logical function any_plates(model)
    !! True when the model has plane-stress or shell elements.
    type(model_t), intent(in) :: model
    integer :: isub
    any_plates = .false.
    do isub = 1, size(model%subs)
       if (model%subs(isub)%nelem == 0) cycle
       if (any(is_plate_type(model%subs(isub)%elem_type(1:model%subs(isub)%nelem)))) any_plates = .true.
    end do
  end function any_plates

  subroutine write_table(path, which, model, res, error)
    character(*), intent(in) :: path
    integer, intent(in) :: which
    type(model_t), intent(in) :: model
    type(results_t), intent(in) :: res
    type(error_t), allocatable, intent(out) :: error
    integer :: lu, ios, is, isub, d, k, il, e
    integer(ip) :: n
    integer(i8) :: v, iel
    character(:), allocatable :: tmp, sname, line
    character(len=IOMSG_LEN) :: why
    logical :: failed
    integer(i8) :: written

    tmp = path//'.tmp'
    call temp_register(tmp)
    open (newunit=lu, file=tmp, status='replace', action='write', iostat=ios)
    if (ios /= 0) then
       call temp_unregister()
       call fatal_error(error, EXIT_IO, 'error: cannot write '//path)
       return
    end if
    failed = .false.
    written = 0
    select case (which)
    case (1)
       call put('step,substructure,node,u1,u2,u3,ur1,ur2,ur3')
       do is = 1, size(model%steps)
          sname = model%steps(is)%name
          do isub = 1, size(model%subs)
             do n = 1, model%subs(isub)%nnode
                v = res%vertex_offset(isub) + n
                if (.not. any(res%has_dof(:, v))) cycle
                line = sname//','//model%subs(isub)%name//','//itoa(int(model%subs(isub)%node_id(n)))
                do d = 1, NDOF_NODE
                   line = line//','//full_real(res%u(NDOF_NODE*(v - 1) + d, is))
                end do
                call put(line)
             end do
          end do
       end do
    case (2)
       call put('step,substructure,node,dof,force')
       do is = 1, size(model%steps)
          do k = 1, size(res%steps(is)%reactions)
             associate (rc => res%steps(is)%reactions(k))
               call put(model%steps(is)%name//','//model%subs(rc%sub)%name//','// &
                    itoa(int(model%subs(rc%sub)%node_id(rc%node)))//','//itoa(rc%dof)//','//full_real(rc%force))
             end associate
          end do
       end do
    case (3)
       call put('step,contact,master_node,slave_node,dof,delta,force')
       do is = 1, size(model%steps)
          do il = 1, size(model%links)
             associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
               do d = 1, NDOF_NODE
                  if (.not. res%link_used(d, il)) cycle
                  call put(model%steps(is)%name//','//ct%name//','// &
                       itoa(int(model%subs(ct%master_sub)%node_id(lk%master_node)))//','// &
                       itoa(int(model%subs(ct%slave_sub)%node_id(lk%slave_node)))//','//itoa(d)//','// &
                       full_real(res%steps(is)%link_delta(d, il))//','//full_real(res%steps(is)%link_force(d, il)))
               end do
             end associate
          end do
       end do
    case (4)
       call put('step,substructure,element,type,end,n,vy,vz,t,my,mz')
       do is = 1, size(model%steps)
          do isub = 1, size(model%subs)
             do e = 1, model%subs(isub)%nelem
                select case (model%subs(isub)%elem_type(e))
                case (ET_T2D2, ET_T3D2, ET_B23, ET_B33)
                case default
                   cycle
                end select
                iel = res%elem_offset(isub) + e
                do k = 1, 2
                   line = model%steps(is)%name//','//model%subs(isub)%name//','// &
                        itoa(int(model%subs(isub)%elem_id(e)))//','// &
                        trim(ELEMENT_TYPE_NAMES(model%subs(isub)%elem_type(e)))//','//itoa(k)
                   do d = 1, 6
                      line = line//','//full_real(res%elem_force(d, k, iel, is))
                   end do
                   call put(line)
                end do
             end do
          end do
       end do
    case (5)
       call put('step,substructure,element,nx,ny,nxy,mx,my,mxy')
       do is = 1, size(model%steps)
          do isub = 1, size(model%subs)
             do e = 1, model%subs(isub)%nelem
                if (.not. is_plate_type(model%subs(isub)%elem_type(e))) cycle
                iel = res%elem_offset(isub) + e
                line = model%steps(is)%name//','//model%subs(isub)%name//','// &
                     itoa(int(model%subs(isub)%elem_id(e)))
                do d = 1, 6
                   line = line//','//full_real(res%plate(d, iel, is))
                end do
                call put(line)
             end do
          end do
       end do
    end select
    if (failed) then
       close (lu, iostat=ios)
    else
       close (lu, iostat=ios, iomsg=why)
       failed = ios /= 0
       if (.not. failed) call check_file_size(tmp, written, failed, why)
    end if
    if (failed) then
       call remove_file(tmp)
       call temp_unregister()
       call fatal_error(error, EXIT_IO, 'error: failed writing '//path//': '//trim(why))
       return
    end if
    call rename_file(tmp, path, error)
    if (allocated(error)) call remove_file(tmp)
    call temp_unregister()

  contains

    subroutine put(text)
      !! One line; after the first failed write nothing more is written.
      character(*), intent(in) :: text
      if (failed) return
      write (lu, '(a)', iostat=ios, iomsg=why) text
      failed = ios /= 0
      written = written + len(text) + 1
    end subroutine put
  end subroutine write_table
end module superjoin_output_csv
