module superjoin_output_section_print
  !! *SECTION PRINT (CalculiX's SOF, SOM, SOAREA): the resultant of the
  !! stresses over the element faces of a *SURFACE, computed as ccx 2.20 does
  !! (printoutface): at CalculiX's integration points of each face
  !! (superjoin_elements_solid_faces, solid_face_points) the stress tensor is
  !! interpolated from the nodal stresses (extrapolated from each element's
  !! integration points and averaged over the elements of the substructure
  !! that share the node, superjoin_output_stresses, nodal_stresses) and
  !! integrated with the outward normal of the face's element:
  !!
  !!   F = Σ σ n dA,   M = Σ x × (σ n dA)   (about the origin),
  !!
  !! the force (and moment) that the material on the other side of the faces
  !! exerts on the faces' elements. Also the area A = Σ dA, the centre of
  !! gravity c = Σ x dA / A, the mean normal n̄ = Σ n dA / A, the moment about
  !! c, M - c × F, the normal force F·n̄ (+ = tension), the shear force
  !! |F - (F·n̄) n̄|, the torque M_c·n̄ and the bending moment |M_c - (M_c·n̄) n̄|.
  !! The faces are the undeformed ones (linear theory; ccx 2.20 too: its
  !! area and centre of gravity are those of the undeformed faces).
  !! Being an integral of smoothed stresses, F equals the load carried across
  !! the section only up to the discretisation error of the stresses (exact
  !! for a uniform stress); the listing and the CSV also give the resultant of
  !! the nodal forces of the faces' elements (nodal_force_result), which is
  !! in exact equilibrium with the loads.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, step_total_time, section_print_t, ELEMENT_NODE_COUNT
  use superjoin_model_results, only: result_fields_t
  use superjoin_elements_solid_faces, only: solid_face_points, solid_face_nodes
  use superjoin_elements, only: element_state_t, element_state, element_stiffness
  use superjoin_elements_frame, only: cross
  use superjoin_output_stresses, only: nodal_stresses
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_utils_strings, only: itoa, full_real
  use superjoin_utils_posix, only: remove_file
  use superjoin_utils_process, only: temp_register, temp_unregister
  implicit none (type, external)
  private

  type, public :: section_result_t
    !! The resultant over a section (see the module's comment).
     real(wp) :: force(3) = 0.0_wp     !! F
     real(wp) :: moment(3) = 0.0_wp    !! M about the origin
     real(wp) :: cg(3) = 0.0_wp        !! centre of gravity c
     real(wp) :: normal(3) = 0.0_wp    !! mean normal n̄
     real(wp) :: area = 0.0_wp
  end type section_result_t

  character(*), parameter, public :: SECTION_CSV = 'section_forces.csv'
  integer, parameter :: LABEL_WIDTH = 42   !! width of the row labels of the listing's table

  public :: effective_sections, section_result, write_section_prints, write_ccx_sections, write_section_csv
  public :: cg_moment, normal_shear, nodal_force_result

contains

  subroutine effective_sections(model, is, idx)
    !! Indices into model%section_prints of the cards that apply to step is
    !! (those of the latest step <= is that has some, as the print requests).
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    integer, allocatable, intent(out) :: idx(:)
    integer :: s, k
    allocate (idx(0))
    if (.not. allocated(model%section_prints)) return
    do s = is, 0, -1
       do k = 1, size(model%section_prints)
          if (model%section_prints(k)%step == s) idx = [idx, k]
       end do
       if (size(idx) > 0) return
    end do
  end subroutine effective_sections

  subroutine section_result(model, fields, is, sp, r)
    !! The resultant of section sp in step is.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(section_print_t), intent(in) :: sp
    type(section_result_t), intent(out) :: r
    real(wp), allocatable :: avg(:, :, :)
    integer, allocatable :: nel(:), npoint(:)
    integer :: isub, f
    real(wp) :: nsum(3)
    nsum = 0.0_wp
    do isub = 1, size(model%subs)
       if (.not. any(sp%subs == isub)) cycle
       call nodal_stresses(model, fields, is, isub, avg, nel, npoint)
       do f = 1, size(sp%elems)
          if (sp%subs(f) == isub) call add_face(model, isub, sp%elems(f), sp%faces(f), avg(:, :, 1), &
               r, nsum)
       end do
    end do
    if (r%area > 0.0_wp) then
       r%cg = r%cg/r%area
       r%normal = nsum/r%area
    end if
  end subroutine section_result

  subroutine add_face(model, isub, ie, face, stn, r, nsum)
    !! One face's contribution: r%force, r%moment, r%area, r%cg (Σ x dA) and nsum (Σ n dA).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub, face
    integer(ip), intent(in) :: ie
    real(wp), intent(in) :: stn(:, :)
    type(section_result_t), intent(inout) :: r
    real(wp), intent(inout) :: nsum(3)
    real(wp), allocatable :: x(:, :), shp(:, :), nda(:, :), xg(:, :)
    integer, allocatable :: nodes(:)
    real(wp) :: s(6), df(3), da
    integer :: k, nn
    associate (sub => model%subs(isub))
      nn = ELEMENT_NODE_COUNT(sub%elem_type(ie))
      allocate (x(3, nn))
      x(:, :) = sub%x(:, sub%elem_nodes(1:nn, ie))
      call solid_face_points(sub%elem_type(ie), x, face, nodes, shp, nda, xg)
      do k = 1, size(nda, 2)
         s = matmul(stn(:, sub%elem_nodes(nodes, ie)), shp(:, k))
         df = [s(1)*nda(1, k) + s(4)*nda(2, k) + s(5)*nda(3, k), s(4)*nda(1, k) + s(2)*nda(2, k) + s(6)*nda(3, k), &
              s(5)*nda(1, k) + s(6)*nda(2, k) + s(3)*nda(3, k)]
         r%force = r%force + df
         r%moment = r%moment + cross(xg(:, k), df)
         da = norm2(nda(:, k))
         r%area = r%area + da
         r%cg = r%cg + xg(:, k)*da
         nsum = nsum + nda(:, k)
      end do
    end associate
  end subroutine add_face

  subroutine nodal_force_result(model, fields, is, sp, f, m)
    !! The exact-equilibrium counterpart: f (and m, about the origin) = Σ K_e u_e
    !! of the faces' elements at the nodes of the section's faces, the forces
    !! these nodes exert on the faces' side (the elements' own distributed and
    !! thermal loads not subtracted). It is the load carried across the
    !! section when every element of that side that touches the section has a
    !! face in it (a mesh of bricks cut along element faces; a tetrahedron
    !! touching it by an edge only is missed).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(section_print_t), intent(in) :: sp
    real(wp), intent(out) :: f(3), m(3)
    type(element_state_t) :: el
    type(error_t), allocatable :: error
    real(wp), allocatable :: ke(:, :), fe(:)
    logical, allocatable :: cut(:)
    integer, allocatable :: nodes(:)
    integer :: k, a, nc, isub
    logical :: ok
    f = 0.0_wp
    m = 0.0_wp
    do isub = 1, size(model%subs)
       if (.not. any(sp%subs == isub)) cycle
       associate (sub => model%subs(isub))
         allocate (cut(sub%nnode), source=.false.)
         do k = 1, size(sp%elems)
            if (sp%subs(k) /= isub) cycle
            call solid_face_nodes(sub%elem_type(sp%elems(k)), sp%faces(k), nodes, nc)
            cut(sub%elem_nodes(nodes, sp%elems(k))) = .true.
         end do
         do k = 1, size(sp%elems)
            if (sp%subs(k) /= isub) cycle
            if (any(sp%subs(1:k - 1) == isub .and. sp%elems(1:k - 1) == sp%elems(k))) cycle   ! counted once
            call element_state(model, fields, is, isub, sp%elems(k), el, ok)
            if (.not. ok) cycle
            call element_stiffness(el%etype, el%x, el%sec, el%mat, ke, error)
            if (allocated(error)) cycle
            fe = matmul(ke, el%ue)
            do a = 1, size(el%x, 2)
               if (.not. cut(sub%elem_nodes(a, sp%elems(k)))) cycle
               f = f + fe(3*a - 2:3*a)
               m = m + cross(el%x(:, a), fe(3*a - 2:3*a))
            end do
         end do
         deallocate (cut)
       end associate
    end do
  end subroutine nodal_force_result

  pure function cg_moment(r) result(m)
    !! The moment about the centre of gravity, M - c × F.
    type(section_result_t), intent(in) :: r
    real(wp) :: m(3)
    m = r%moment - cross(r%cg, r%force)
  end function cg_moment

  pure function normal_shear(v, n) result(ns)
    !! ns(1) = v·n, ns(2) = |v - (v·n) n|: the normal and tangential parts of v.
    real(wp), intent(in) :: v(3), n(3)
    real(wp) :: ns(2)
    ns(1) = dot_product(v, n)
    ns(2) = norm2(v - ns(1)*n)
  end function normal_shear

  subroutine write_section_prints(lu, model, fields, is)
    !! The SECTION PRINT tables of step is in the listing (nothing without cards).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, allocatable :: idx(:)
    type(section_result_t) :: r
    real(wp) :: fn(3), mn(3)
    integer :: k
    call effective_sections(model, is, idx)
    if (size(idx) == 0) return
    call lu%line('SECTION PRINT of step '//itoa(is)//' (resultant of the nodal stresses over the faces, '// &
         'the force the other side exerts on the faces'' elements)')
    do k = 1, size(idx)
       associate (sp => model%section_prints(idx(k)))
         call section_result(model, fields, is, sp, r)
         call lu%line('  section '//sp%name//' (surface '//sp%surface//', '//itoa(size(sp%elems))//' faces)')
         call lu%line(repeat(' ', LABEL_WIDTH)//'              x              y              z')
         call vector_row('force', r%force)
         call vector_row('moment about the origin', r%moment)
         call vector_row('centre of gravity', r%cg)
         call vector_row('mean normal', r%normal)
         call vector_row('moment about the centre', cg_moment(r))
         call nodal_force_result(model, fields, is, sp, fn, mn)
         call vector_row('force from the nodal forces', fn)
         call vector_row('moment about the centre, nodal forces', mn - cross(r%cg, fn))
         call lu%line(repeat(' ', LABEL_WIDTH)//'           area   normal force    shear force         torque'// &
              ' bending moment')
         call lu%put(repeat(' ', LABEL_WIDTH))
         call put_row([r%area, normal_shear(r%force, r%normal), normal_shear(cg_moment(r), r%normal)])
       end associate
    end do
  contains
    subroutine vector_row(label, v)
      character(*), intent(in) :: label
      real(wp), intent(in) :: v(3)
      character(len=LABEL_WIDTH) :: head
      head = '    '//label
      call lu%put(head)
      call put_row(v)
    end subroutine vector_row
    subroutine put_row(v)
      real(wp), intent(in) :: v(:)
      integer :: j
      do j = 1, size(v)
         call lu%put_es(v(j))
      end do
      call lu%newline()
    end subroutine put_row
  end subroutine write_section_prints

  subroutine write_ccx_sections(lu, model, fields, is)
    !! The *SECTION PRINT blocks of step is in ccx 2.20's .dat layout.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, allocatable :: idx(:)
    type(section_result_t) :: r
    character(len=14) :: t
    integer :: k
    call effective_sections(model, is, idx)
    write (t, '(e14.7)') step_total_time(model, is)
    do k = 1, size(idx)
       associate (sp => model%section_prints(idx(k)))
         call section_result(model, fields, is, sp, r)
         call lu%line('')
         call lu%line('')
         call lu%line('')
         call lu%line(' statistics for surface set '//sp%surface//' and time '//t)
         call lu%line('')
         call lu%line('   total surface force (fx,fy,fz) and moment about the origin(mx,my,mz)')
         call lu%line('')
         call lu%line('  '//ccx_row([r%force, r%moment]))
         call lu%line('')
         call lu%line('   center of gravity and mean normal')
         call lu%line('')
         call lu%line('  '//ccx_row([r%cg, r%normal]))
         call lu%line('')
         call lu%line('   moment about the center of gravity(mx,my,mz)')
         call lu%line('')
         call lu%line('  '//ccx_row(cg_moment(r)))
         call lu%line('')
         call lu%line('   area, normal force (+ = tension), shear force (size), torque and bending moment (size)')
         call lu%line('')
         call lu%line('  '//ccx_row([r%area, normal_shear(r%force, r%normal), normal_shear(cg_moment(r), r%normal)]))
       end associate
    end do
  end subroutine write_ccx_sections

  pure function ccx_row(v) result(s)
    !! Values as ccx's 1p,e13.6 each after a blank, a negative zero as zero.
    real(wp), intent(in) :: v(:)
    character(:), allocatable :: s
    character(len=14) :: c
    integer :: k
    s = ''
    do k = 1, size(v)
       write (c, '(1x,es13.6)') merge(0.0_wp, v(k), v(k) == 0.0_wp)
       s = s//c
    end do
  end function ccx_row

  subroutine write_section_csv(dir, model, fields, error)
    !! DIR/section_forces.csv: step,section,surface,faces,fx,fy,fz,mx,my,mz (about
    !! the origin),cx,cy,cz (centre of gravity),nx,ny,nz (mean normal),area,
    !! and the nodal-force resultant fx_nodal..mz_nodal (nodal_force_result,
    !! moment about the origin), full precision; removed when the deck has no *SECTION PRINT.
    character(*), intent(in) :: dir
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    type(section_result_t) :: r
    integer, allocatable :: idx(:)
    character(:), allocatable :: path, row
    real(wp) :: v(19), fn(3), mn(3)
    integer :: is, k, j
    path = dir//'/'//SECTION_CSV
    if (.not. allocated(model%section_prints)) then
       call remove_file(path)
       return
    end if
    allocate (tb)
    call temp_register(path//'.tmp')
    call tb%open(path//'.tmp', error)
    if (allocated(error)) then
       call temp_unregister()
       return
    end if
    call tb%line('step,section,surface,faces,fx,fy,fz,mx,my,mz,cx,cy,cz,nx,ny,nz,area,'// &
         'fx_nodal,fy_nodal,fz_nodal,mx_nodal,my_nodal,mz_nodal')
    do is = 1, size(model%steps)
       if (allocated(fields%steps(is)%failure)) cycle
       call effective_sections(model, is, idx)
       do k = 1, size(idx)
          associate (sp => model%section_prints(idx(k)))
            call section_result(model, fields, is, sp, r)
            row = itoa(is)//','//sp%name//','//sp%surface//','//itoa(size(sp%elems))
            call nodal_force_result(model, fields, is, sp, fn, mn)
            v = [r%force, r%moment, r%cg, r%normal, r%area, fn, mn]
            do j = 1, size(v)
               row = row//','//full_real(v(j))
            end do
            call tb%line(row)
          end associate
       end do
    end do
    call tb%commit(path//'.tmp', path, 'CSV file ', error)
  end subroutine write_section_csv
end module superjoin_output_section_print
