module superjoin_output_requested_csv
  !! CSV tables of the derived results that only exist on request (--csv DIR
  !! and an output request of a step naming the variable, *EL PRINT / *EL FILE
  !! or *NODE PRINT / *NODE FILE, with CalculiX's scoping of requests):
  !!   energies.csv        ENER (*EL PRINT, *EL FILE): strain energies and the energy balance
  !!   point_stresses.csv  S (*EL PRINT, *EL FILE): plane, shell and solid elements, at the integration points
  !!   fibre_stresses.csv  S (*EL PRINT, *EL FILE): beams with a library section, extreme points
  !!   nodal_stresses.csv  S (*NODE PRINT, *NODE FILE, *EL FILE): plane, shell and solid elements, at the nodes,
  !!                       averaged over the elements of the substructure
  !! Without such a request (or without the elements a stress table is about)
  !! the table of an earlier run into DIR is removed.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, REQ_EL_PRINT, REQ_EL_FILE, REQ_NODE_PRINT, REQ_NODE_FILE, &
       ELEMENT_TYPE_NAMES
  use superjoin_output_stresses, only: nodal_stresses, fibre_stresses
  use superjoin_elements, only: element_stresses
  use superjoin_elements, only: is_plate_type, is_solid_type
  use superjoin_model_results, only: result_fields_t
  use superjoin_output_requests, only: effective_requests
  use superjoin_output_energy, only: energy_t, compute_energies, requests_name
  use superjoin_output_section_print, only: write_section_csv
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_utils_posix, only: remove_file
  use superjoin_utils_process, only: temp_register, temp_unregister
  use superjoin_utils_strings, only: itoa, full_real
  implicit none (type, external)
  private

  character(*), parameter, public :: ENERGY_CSV = 'energies.csv', POINT_STRESS_CSV = 'point_stresses.csv', &
       NODAL_STRESS_CSV = 'nodal_stresses.csv', FIBRE_STRESS_CSV = 'fibre_stresses.csv'

  public :: write_requested_csv, step_requests

contains

  subroutine write_requested_csv(dir, model, fields, error)
    !! The requested derived tables into DIR (which exists).
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    call write_energy_csv(dir, model, fields, error)
    if (allocated(error)) return
    call write_point_stress_csv(dir, model, fields, error)
    if (allocated(error)) return
    call write_nodal_stress_csv(dir, model, fields, error)
    if (allocated(error)) return
    call write_fibre_stress_csv(dir, model, fields, error)
    if (allocated(error)) return
    call write_section_csv(dir, model, fields, error)
  end subroutine write_requested_csv

  logical function step_requests(model, is, kinds, name)
    !! Does a request of one of `kinds` that applies to step `is` name `name`?
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    integer, intent(in) :: kinds(:)
    character(*), intent(in) :: name
    integer, allocatable :: idx(:)
    integer :: k, j
    step_requests = .false.
    do k = 1, size(kinds)
       call effective_requests(model, is, kinds(k), idx)
       do j = 1, size(idx)
          if (requests_name(model%requests(idx(j)), name)) step_requests = .true.
       end do
    end do
  end function step_requests

  subroutine start_table(path, model, kinds, name, applies, header, wanted, tb, tmp, error)
    !! The steps whose requests of `kinds` name `name`; when there are none or
    !! the table does not apply to the model, the table is removed (one of an
    !! earlier run must not survive) and tb is left unallocated; else its
    !! temporary file is opened with the header line.
    character(*), intent(in) :: path, name, header
    type(model_t), intent(in) :: model
    integer, intent(in) :: kinds(:)
    logical, intent(in) :: applies
    logical, allocatable, intent(out) :: wanted(:)
    type(text_buffer_t), allocatable, intent(out) :: tb
    character(:), allocatable, intent(out) :: tmp
    type(error_t), allocatable, intent(out) :: error
    integer :: is
    allocate (wanted(size(model%steps)))
    do is = 1, size(model%steps)
       wanted(is) = step_requests(model, is, kinds, name)
    end do
    if (.not. any(wanted) .or. .not. applies) then
       call remove_file(path)
       return
    end if
    allocate (tb)
    call open_table(path, tmp, tb, error)
    if (allocated(error)) then
       deallocate (tb)
       return
    end if
    call tb%line(header)
  end subroutine start_table

  subroutine open_table(path, tmp, tb, error)
    !! Open the temporary file of a table (registered for removal on a signal).
    character(*), intent(in) :: path
    character(:), allocatable, intent(out) :: tmp
    type(text_buffer_t), intent(inout) :: tb
    type(error_t), allocatable, intent(out) :: error
    tmp = path//'.tmp'
    call temp_register(tmp)
    call tb%open(tmp, error)
    if (allocated(error)) call temp_unregister()
  end subroutine open_table

  subroutine write_energy_csv(dir, model, fields, error)
    !! DIR/energies.csv: step,kind,name,id,energy with kind element (name: its
    !! substructure, id: its id), substructure, contact_element (name: the
    !! *CONTACT card, id: the slave node id), contact (the card), and the model's
    !! spring_supports, total, load_work (½ fᵀu), prescribed_work (½ Σ R ū), and
    !! balance_not_checked (name: why) in a step the balance does not apply to;
    !! a step whose energies are not available (thermal strains on an element
    !! type without their energy) has the one row not_available.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    type(energy_t) :: en
    character(:), allocatable :: path, tmp
    logical, allocatable :: wanted(:)
    integer :: is, isub, il
    integer(ip) :: e
    path = dir//'/'//ENERGY_CSV
    call start_table(path, model, [REQ_EL_PRINT, REQ_EL_FILE], 'ENER', .true., &
         'step,kind,name,id,energy', wanted, tb, tmp, error)
    if (.not. allocated(tb) .or. allocated(error)) return
    do is = 1, size(model%steps)
       if (.not. wanted(is)) cycle
       if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
       call compute_energies(model, fields, is, en, error)
       if (allocated(error)) then   ! thermal strains on an element without their energy: said in the listing
          deallocate (error)
          call row(model%steps(is)%name, 'not_available', 'see the listing', '', 0.0_wp)
          cycle
       end if
       associate (sn => model%steps(is)%name)
         do isub = 1, size(model%subs)
            do e = 1, model%subs(isub)%nelem
               call row(sn, 'element', model%subs(isub)%name, itoa(int(model%subs(isub)%elem_id(e))), &
                    en%element(fields%elem_offset(isub) + e))
            end do
         end do
         do isub = 1, size(model%subs)
            call row(sn, 'substructure', model%subs(isub)%name, '', en%part(isub))
         end do
         do il = 1, size(model%links)
            associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
              call row(sn, 'contact_element', ct%name, &
                   itoa(int(model%subs(ct%slave_sub)%node_id(lk%slave_node))), en%link(il))
            end associate
         end do
         do il = 1, size(model%contacts)
            call row(sn, 'contact', model%contacts(il)%name, '', en%contact(il))
         end do
         call row(sn, 'spring_supports', '', '', en%supports)
         call row(sn, 'total', '', '', en%internal)
         call row(sn, 'load_work', '', '', en%load_work)
         call row(sn, 'prescribed_work', '', '', en%prescribed_work)
         if (allocated(en%no_balance)) call row(sn, 'balance_not_checked', en%no_balance, '', 0.0_wp)
       end associate
    end do
    call tb%commit(tmp, path, '', error)
  contains
    subroutine row(step, kind, name, id, value)
      character(*), intent(in) :: step, kind, name, id
      real(wp), intent(in) :: value
      call tb%line(step//','//kind//','//name//','//id//','//full_real(value))
    end subroutine row
  end subroutine write_energy_csv

  subroutine write_point_stress_csv(dir, model, fields, error)
    !! DIR/point_stresses.csv:
    !! step,substructure,element,type,point,surface,sxx,syy,szz,sxy,sxz,syz for
    !! every plane (surface mid) and shell element (surfaces bottom and top), in
    !! the steps whose element requests name S.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    character(:), allocatable :: path, tmp
    real(wp), allocatable :: points(:, :, :), nodes(:, :, :)
    logical, allocatable :: wanted(:)
    logical :: ok
    integer :: is, isub, k, d, m
    integer(ip) :: e
    path = dir//'/'//POINT_STRESS_CSV
    call start_table(path, model, [REQ_EL_PRINT, REQ_EL_FILE], 'S', any_plane(model), &
         'step,substructure,element,type,point,surface,sxx,syy,szz,sxy,sxz,syz', wanted, tb, tmp, error)
    if (.not. allocated(tb) .or. allocated(error)) return
    do is = 1, size(model%steps)
       if (.not. wanted(is)) cycle
       if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
       do isub = 1, size(model%subs)
          do e = 1, model%subs(isub)%nelem
             call element_stresses(model, fields, is, isub, e, points, nodes, ok)
             if (.not. ok) cycle
             do m = 1, size(points, 3)
                do k = 1, size(points, 2)
                   call tb%put(model%steps(is)%name//','//model%subs(isub)%name//','// &
                        itoa(int(model%subs(isub)%elem_id(e)))//','// &
                        trim(ELEMENT_TYPE_NAMES(model%subs(isub)%elem_type(e)))//','//itoa(k)//','// &
                        surface_name(size(points, 3), m))
                   do d = 1, size(points, 1)
                      call tb%put(','//full_real(points(d, k, m)))
                   end do
                   call tb%newline()
                end do
             end do
          end do
       end do
    end do
    call tb%commit(tmp, path, '', error)
  end subroutine write_point_stress_csv

  pure function surface_name(nsurf, k) result(name)
    !! mid (plane elements), bottom, top or mid (shells: section points 1, 2, 3).
    integer, intent(in) :: nsurf, k
    character(:), allocatable :: name
    if (nsurf == 1 .or. k == 3) then
       name = 'mid'
    else if (k == 1) then
       name = 'bottom'
    else
       name = 'top'
    end if
  end function surface_name

  subroutine write_nodal_stress_csv(dir, model, fields, error)
    !! DIR/nodal_stresses.csv: step,substructure,node,elements,surface,sxx,syy,szz,sxy,sxz,syz
    !! for every node of a plane or shell element (elements: how many were
    !! averaged; surface mid, or bottom and top at a node of a shell), in the
    !! steps whose node requests, or *EL FILE requests, name S.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    character(:), allocatable :: path, tmp
    real(wp), allocatable :: avg(:, :, :)
    integer, allocatable :: nel(:)
    logical, allocatable :: wanted(:)
    integer, allocatable :: nsurf(:)
    integer :: is, isub, d, k, ns
    integer(ip) :: n
    path = dir//'/'//NODAL_STRESS_CSV
    call start_table(path, model, [REQ_NODE_PRINT, REQ_NODE_FILE, REQ_EL_FILE], 'S', any_plane(model), &
         'step,substructure,node,elements,surface,sxx,syy,szz,sxy,sxz,syz', wanted, tb, tmp, error)
    if (.not. allocated(tb) .or. allocated(error)) return
    do is = 1, size(model%steps)
       if (.not. wanted(is)) cycle
       if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
       do isub = 1, size(model%subs)
          call nodal_stresses(model, fields, is, isub, avg, nel, nsurf)
          do n = 1, model%subs(isub)%nnode
             if (nel(n) == 0) cycle
             ns = nsurf(n)
             do k = 1, ns
                call tb%put(model%steps(is)%name//','//model%subs(isub)%name//','// &
                     itoa(int(model%subs(isub)%node_id(n)))//','//itoa(nel(n))//','//surface_name(ns, k))
                do d = 1, size(avg, 1)
                   call tb%put(','//full_real(avg(d, n, k)))
                end do
                call tb%newline()
             end do
          end do
       end do
    end do
    call tb%commit(tmp, path, '', error)
  end subroutine write_nodal_stress_csv

  subroutine write_fibre_stress_csv(dir, model, fields, error)
    !! DIR/fibre_stresses.csv: step,substructure,element,type,end,point,y,z,sxx for
    !! every beam with a library section, in the steps whose element requests name S.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    character(:), allocatable :: path, tmp
    real(wp) :: sig(4, 2)
    logical, allocatable :: wanted(:)
    integer :: is, isub, k, ends, n
    integer(ip) :: e
    path = dir//'/'//FIBRE_STRESS_CSV
    call start_table(path, model, [REQ_EL_PRINT, REQ_EL_FILE], 'S', any_fibres(model), &
         'step,substructure,element,type,end,point,y,z,sxx', wanted, tb, tmp, error)
    if (.not. allocated(tb) .or. allocated(error)) return
    do is = 1, size(model%steps)
       if (.not. wanted(is)) cycle
       if (allocated(fields%steps(is)%failure)) cycle   ! not solved: no rows
       do isub = 1, size(model%subs)
          do e = 1, model%subs(isub)%nelem
             call fibre_stresses(model, fields, is, isub, e, sig, n)
             associate (sub => model%subs(isub))
               do ends = 1, 2
                  do k = 1, n
                     associate (sec => sub%sections(sub%elem_section(e)))
                       call tb%line(model%steps(is)%name//','//sub%name//','//itoa(int(sub%elem_id(e)))//','// &
                            trim(ELEMENT_TYPE_NAMES(sub%elem_type(e)))//','//itoa(ends)//','//itoa(k)//','// &
                            full_real(sec%fibre(1, k))//','//full_real(sec%fibre(2, k))//','//full_real(sig(k, ends)))
                     end associate
                  end do
               end do
             end associate
          end do
       end do
    end do
    call tb%commit(tmp, path, '', error)
  end subroutine write_fibre_stress_csv

  pure logical function any_plane(model)
    !! Does the model have plane, shell or solid elements (the elements with stresses at points)?
    type(model_t), intent(in) :: model
    integer :: isub
    any_plane = .false.
    do isub = 1, size(model%subs)
       if (model%subs(isub)%nelem == 0) cycle
       associate (types => model%subs(isub)%elem_type(1:model%subs(isub)%nelem))
         if (any(is_plate_type(types) .or. is_solid_type(types))) any_plane = .true.
       end associate
    end do
  end function any_plane

  pure logical function any_fibres(model)
    !! Does some section of the model have fibre points (library beam sections)?
    type(model_t), intent(in) :: model
    integer :: isub, k
    any_fibres = .false.
    do isub = 1, size(model%subs)
       if (.not. allocated(model%subs(isub)%sections)) cycle
       do k = 1, size(model%subs(isub)%sections)
          if (model%subs(isub)%sections(k)%nfibre > 0) any_fibres = .true.
       end do
    end do
  end function any_fibres
end module superjoin_output_requested_csv
