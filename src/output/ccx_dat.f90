module superjoin_output_ccx_dat
  !! CalculiX's .dat file (superjoin -i JOB writes JOB.dat): every *NODE PRINT
  !! and *EL PRINT request of every solved step in the layout of ccx 2.20, so
  !! that a .dat.ref of CalculiX's test suite compares number by number:
  !!
  !!   (blank line)
  !!    displacements (vx,vy,vz) for set NALL and time  0.1000000E+01
  !!   (blank line)
  !!            1  0.000000E+00  1.857143E-04  0.000000E+00
  !!
  !! Blocks: U "displacements", RF "forces" (CalculiX's internal nodal forces:
  !! the support reaction plus the *CLOAD of the node), NT "temperatures", S
  !! "stresses", E "strains", ENER "internal energy density" (½ σ:(ε - ε_th) at the
  !! points of solids and trusses, ½ σ:C⁻¹:σ at those of plane elements and
  !! shells, a beam's mean), ELSE "internal energy" (an axisymmetric
  !! model: that of CalculiX's 2° wedge, 1/180); TOTALS=YES adds the sum
  !! (RF, ELSE), TOTALS=ONLY writes the sum alone. A node with a nodal system
  !! (*TRANSFORM) prints U and RF in it, its row ending in L, unless the card
  !! says GLOBAL=YES. A node set given by GENERATE ranges over undefined ids
  !! prints U and RF rows for every id of the ranges up to the largest node
  !! id, zeros for the undefined ones, as ccx. A model with axisymmetric elements
  !! (CAX*) prints the forces of CalculiX's 2° wedge: superjoin's totals around
  !! the circumference divided by 180. The time of a step is the total time
  !! at its end, as ccx prints it: the time periods of the steps so far (1 each
  !! without *STATIC's data line; TIME RESET does not advance it).
  !!
  !! Element values at integration points follow CalculiX's expansion of a
  !! one- or two-dimensional element into a brick (ccx_point_map): a truss
  !! (C3D20R) has 8 points of its one tensor; a plane element its own points
  !! in the brick's order (xi fastest), repeated through the thickness; a
  !! shell its bottom, top (and mid) surface values interpolated to the
  !! brick's Gauss points through the thickness; a solid its own points,
  !! which are CalculiX's in CalculiX's order (S and E); an axisymmetric
  !! element its points as the plane element with its nodes, each tensor at
  !! its angle in CalculiX's 2° wedge (S and E). Beams (CalculiX's
  !! brick stresses are not a beam's) print no S or E rows; strains of plane
  !! elements are the element's centroid tensor at each point, shells have
  !! none (doc/calculix-dropin.md).
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, step_total_time, output_request_t, substructure_t, orientation_t, find_node, NDOF_NODE, &
       REQ_NODE_PRINT, REQ_EL_PRINT, TOTALS_YES, TOTALS_ONLY, MAT_ISO
  use superjoin_model_results, only: result_fields_t, reaction_t
  use superjoin_elements, only: element_tensor, element_stresses, NTENSOR, has_axisymmetric, ccx_wedge_tensor, &
       CCX_AXIAL_SEGMENTS
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_TRUSS, FAMILY_PLANE, FAMILY_SHELL, &
       FAMILY_SOLID, FAMILY_BEAM
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_requests, only: effective_requests, selected_items, node_frames, rotate_rows, node_values, &
       add_reactions, add_cloads, add_node_forces
  use superjoin_output_energy, only: energy_t, compute_energies
  use superjoin_elements_materials, only: material_frame
  use superjoin_elements_solid, only: solid_rule, solid_shape
  use superjoin_elements_quadrature, only: quad_rule_t
  use superjoin_output_section_print, only: write_ccx_sections
  use superjoin_utils_process, only: temp_register, temp_unregister
  implicit none (type, external)
  private

  public :: write_ccx_dat, write_ccx_sta, c_real, node_forces, open_output

  character(*), parameter :: FMT_NODE = '(i10,3(1x,a13))'
  integer, parameter :: ORIENT_NAME_LEN = 20
    !! CalculiX writes the first 20 characters of an orientation's name after an oriented element's row
  integer, parameter :: MAX_CCX_POINTS = 27
    !! Integration points of the largest brick (C3D20, 3x3x3).

contains

  pure function c_real(x, w, d) result(s)
    !! x as C's %w.dE (CalculiX's number format): Fortran's ESw.d, a negative
    !! zero written as zero.
    real(wp), intent(in) :: x
    integer, intent(in) :: w, d
    character(len=w) :: s
    character(len=16) :: f
    real(wp) :: y
    y = x
    if (y == 0.0_wp) y = 0.0_wp
    write (f, '(a,i0,a,i0,a)') '(es', w, '.', d, ')'
    write (s, f) y
  end function c_real

  subroutine open_output(lu, path, error)
    !! A new buffer on path.tmp (registered for removal on a signal), to be
    !! committed over path.
    type(text_buffer_t), allocatable, intent(out) :: lu
    character(*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    allocate (lu)
    call temp_register(path//'.tmp')
    call lu%open(path//'.tmp', error)
    if (allocated(error)) call temp_unregister()
  end subroutine open_output

  subroutine write_ccx_dat(path, model, fields, error)
    !! JOB.dat: the print requests of every solved step (an empty file for a
    !! deck without any, as ccx writes).
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    integer, allocatable :: nodes(:), elems(:)
    integer :: is, k
    call open_output(lu, path, error)
    if (allocated(error)) return
    do is = 1, size(model%steps)
       if (allocated(fields%steps(is)%failure)) cycle
       call effective_requests(model, is, REQ_NODE_PRINT, nodes)
       call effective_requests(model, is, REQ_EL_PRINT, elems)
       do k = 1, size(nodes)
          call node_print(lu, model, fields, is, model%requests(nodes(k)))
       end do
       do k = 1, size(elems)
          call el_print(lu, model, fields, is, model%requests(elems(k)))
       end do
       call write_ccx_sections(lu, model, fields, is)
    end do
    call lu%commit(path//'.tmp', path, '.dat file ', error)
  end subroutine write_ccx_dat

  subroutine block_header(lu, what, r, time, fallback)
    !! The blank line, the title " what for set NAME and time  T" and a blank line.
    type(text_buffer_t), intent(inout) :: lu
    character(*), intent(in) :: what, fallback
    type(output_request_t), intent(in) :: r
    real(wp), intent(in) :: time
    character(len=14) :: t
    character(:), allocatable :: set
    write (t, '(e14.7)') time
    set = fallback
    if (allocated(r%set_name)) set = r%set_name
    call lu%line('')
    call lu%line(' '//what//' for set '//set//' and time '//t)
    call lu%line('')
  end subroutine block_header

  subroutine node_print(lu, model, fields, is, r)
    !! One *NODE PRINT card: U, RF, NT blocks in the card's order.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(output_request_t), intent(in) :: r
    integer, allocatable :: subs(:), frame(:)
    integer(ip), allocatable :: nodes(:)
    real(wp), allocatable :: vals(:, :), gvals(:, :)
    logical :: local
    integer :: iv
    call selected_items(r, model%subs(:)%nnode, subs, nodes)
    call node_frames(model, subs, nodes, frame)
    local = .not. r%global .and. any(frame > 0)
    do iv = 1, size(r%vars)
       select case (r%vars(iv)%s)
       case ('U')
          vals = node_values(fields%u(:, is), fields%vertex_offset, subs, nodes)
          gvals = vals
          if (local) call rotate_rows(model, frame, .false., vals)
          if (r%totals /= TOTALS_ONLY) call block_header(lu, 'displacements (vx,vy,vz)', r, step_total_time(model, is), 'NALL')
          if (r%totals /= TOTALS_ONLY) call node_rows(lu, model, r, subs, nodes, vals, local .and. frame > 0)
       case ('RF')
          call node_forces(model, fields, is, subs, nodes, gvals)
          vals = gvals
          if (local) call rotate_rows(model, frame, .false., vals)
          if (r%totals /= TOTALS_ONLY) call block_header(lu, 'forces (fx,fy,fz)', r, step_total_time(model, is), 'NALL')
          if (r%totals /= TOTALS_ONLY) call node_rows(lu, model, r, subs, nodes, vals, local .and. frame > 0)
          if (r%totals == TOTALS_YES .or. r%totals == TOTALS_ONLY) then
             call block_header(lu, 'total force (fx,fy,fz)', r, step_total_time(model, is), 'NALL')
             call total_row(lu, [sum(gvals(1, :)), sum(gvals(2, :)), sum(gvals(3, :))])
          end if
       case ('NT')
          ! as ccx: no block for a model without temperatures
          if (.not. allocated(model%steps(is)%temperature)) cycle
          call block_header(lu, 'temperatures', r, step_total_time(model, is), 'NALL')
          call temperature_rows(lu, model, is, subs, nodes)
       end select
    end do
  end subroutine node_print

  subroutine node_forces(model, fields, is, subs, nodes, v)
    !! CalculiX's "forces" of the listed nodes in step is: the support
    !! reactions plus the concentrated loads (*CLOAD) on the node plus the
    !! forces of the *EQUATION constraints on it (not on the extra node of an
    !! *MPC MEANROT: ccx 2.20 prints its torque), global axes (the reactions
    !! of a node with a *TRANSFORM are along its nodal system).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), allocatable, intent(out) :: v(:, :)
    integer, allocatable :: frame(:)
    real(wp), allocatable :: cf(:, :), mask(:, :)
    type(reaction_t), allocatable :: held(:)
    allocate (v(NDOF_NODE, size(nodes)), cf(NDOF_NODE, size(nodes)), mask(NDOF_NODE, size(nodes)))
    call add_reactions(fields, is, subs, nodes, v)
    call node_frames(model, subs, nodes, frame)
    call rotate_rows(model, frame, .true., v)
    call add_cloads(model, is, subs, nodes, cf)
    v = v + cf
    if (allocated(fields%steps(is)%equation_forces)) then
       call add_node_forces(fields%steps(is)%equation_forces, subs, nodes, cf)
       ! the extra node of an *MPC MEANROT prints its reaction alone, the torque (as ccx 2.20)
       call torque_nodes(model, held)
       call add_node_forces(held, subs, nodes, mask)
       where (mask /= 0.0_wp) cf = 0.0_wp
       v = cf + v
    end if
    ! an axisymmetric model: CalculiX's forces are those of its 2° wedge (superjoin's: the whole circumference)
    if (has_axisymmetric(model)) v = v/real(CCX_AXIAL_SEGMENTS, wp)
  end subroutine node_forces

  subroutine torque_nodes(model, list)
    !! The DOFs (force 1) of the extra nodes of the *MPC MEANROT equations.
    type(model_t), intent(in) :: model
    type(reaction_t), allocatable, intent(out) :: list(:)
    integer :: k, n
    allocate (list(0))
    if (.not. allocated(model%equations)) return
    do k = 1, size(model%equations)
       associate (e => model%equations(k))
         if (.not. e%torque_node) cycle
         n = size(e%coef)
         list = [list, reaction_t(e%sub(n), int(e%node(n)), e%dof(n), 1.0_wp)]
       end associate
    end do
  end subroutine torque_nodes

  subroutine node_rows(lu, model, r, subs, nodes, vals, marked)
    !! One row per node: its user id and vals(1:3, node); ' L' when `marked`.
    !! A set with print ranges prints their ids, as ccx (an undefined id: zeros).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(output_request_t), intent(in) :: r
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    real(wp), intent(in) :: vals(:, :)
    logical, intent(in) :: marked(:)
    integer(ip), allocatable :: pos(:)
    integer(ip) :: id, n, j
    integer :: i, k
    if (.not. allocated(r%print_ranges)) then
       do i = 1, size(nodes)
          call node_row(lu, model%subs(subs(i))%node_id(nodes(i)), vals(:, i), marked(i))
       end do
       return
    end if
    associate (sub => model%subs(r%sub))
      allocate (pos(sub%nnode), source=0_ip)   ! pos(node): its place in nodes (0: none)
      do i = 1, size(nodes)
         pos(nodes(i)) = i
      end do
      do k = 1, size(r%print_ranges, 2)
         ! counted, not stepped: first + step past the last id may exceed huge(id)
         do j = 0, (r%print_ranges(2, k) - r%print_ranges(1, k))/r%print_ranges(3, k)
            id = r%print_ranges(1, k) + j*r%print_ranges(3, k)
            n = find_node(sub, id)
            if (n > 0) n = pos(n)
            if (n > 0) then
               call node_row(lu, id, vals(:, n), marked(n))
            else
               call node_row(lu, id, [0.0_wp, 0.0_wp, 0.0_wp], .false.)
            end if
         end do
      end do
    end associate
  end subroutine node_rows

  subroutine node_row(lu, id, v, marked)
    !! The row of node id: v(1:3); ' L' when `marked`.
    type(text_buffer_t), intent(inout) :: lu
    integer(ip), intent(in) :: id
    real(wp), intent(in) :: v(:)
    logical, intent(in) :: marked
    character(len=60) :: row
    write (row, FMT_NODE) id, c_real(v(1), 13, 6), c_real(v(2), 13, 6), c_real(v(3), 13, 6)
    if (marked) then
       call lu%line(trim(row)//' L')
    else
       call lu%line(trim(row))
    end if
  end subroutine node_row

  subroutine total_row(lu, v)
    !! The row of a TOTALS block.
    type(text_buffer_t), intent(inout) :: lu
    real(wp), intent(in) :: v(:)
    integer :: d
    call lu%put('      ')
    do d = 1, size(v)
       call lu%put(' '//c_real(v(d), 13, 6))
    end do
    call lu%newline()
  end subroutine total_row

  subroutine temperature_rows(lu, model, is, subs, nodes)
    !! The temperature of each listed node in step is.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    character(len=30) :: row
    real(wp) :: t
    integer :: i
    do i = 1, size(nodes)
       t = model%steps(is)%temperature(subs(i))%v(nodes(i))
       write (row, '(i10,1x,a13)') model%subs(subs(i))%node_id(nodes(i)), c_real(t, 13, 6)
       call lu%line(trim(row))
    end do
  end subroutine temperature_rows

  ! ------------------------------------------------------------------ elements

  subroutine el_print(lu, model, fields, is, r)
    !! One *EL PRINT card: S and E blocks in the card's order, then ELSE.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(output_request_t), intent(in) :: r
    integer, allocatable :: subs(:)
    integer(ip), allocatable :: elems(:)
    integer :: iv
    call selected_items(r, model%subs(:)%nelem, subs, elems)
    do iv = 1, size(r%vars)
       select case (r%vars(iv)%s)
       case ('S')
          call block_header(lu, 'stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz)', r, step_total_time(model, is), 'EALL')
          call point_rows(lu, model, fields, is, r, subs, elems, 'S')
       case ('E')
          call block_header(lu, 'strains (elem, integ.pnt.,exx,eyy,ezz,exy,exz,eyz)', r, step_total_time(model, is), 'EALL')
          call point_rows(lu, model, fields, is, r, subs, elems, 'E')
       case ('ENER')
          call block_header(lu, 'internal energy density (elem, integ.pnt.,energy)', r, step_total_time(model, is), 'EALL')
          call point_rows(lu, model, fields, is, r, subs, elems, 'ENER')
       end select
    end do
    ! ELSE (the element's strain energy) is not among the listing's variables
    if (any([(r%ignored(iv)%s == 'ELSE', iv=1, size(r%ignored))])) &
         call energy_rows(lu, model, fields, is, r, subs, elems)
  end subroutine el_print

  subroutine point_rows(lu, model, fields, is, r, subs, elems, var)
    !! Rows "element point values" at CalculiX's integration points: var S or
    !! E (six components), ENER (point_energy). A solid whose section has an
    !! *ORIENTATION prints its tensors in the material axes, the orientation's
    !! name (20 characters) ending the row, unless the card says GLOBAL=YES
    !! (as ccx 2.20).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(output_request_t), intent(in) :: r
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    character(*), intent(in) :: var
    real(wp), allocatable :: vals(:, :)
    type(energy_t) :: en
    type(error_t), allocatable :: error
    character(len=120) :: row
    character(len=ORIENT_NAME_LEN) :: name
    type(element_traits_t) :: t
    integer :: i, k, d, isec
    logical :: ok, local
    if (var == 'ENER') then
       call compute_energies(model, fields, is, en, error)
       if (allocated(error)) return
    end if
    do i = 1, size(elems)
       if (var == 'ENER') then
          call point_energy(model, fields, is, subs(i), elems(i), en, vals, ok)
       else
          call ccx_point_values(model, fields, is, subs(i), elems(i), var == 'E', vals, ok)
       end if
       if (.not. ok) cycle
       associate (sub => model%subs(subs(i)))
         isec = sub%elem_section(elems(i))
         local = .false.
         t = element_traits(sub%elem_type(elems(i)))
         if (isec > 0 .and. .not. r%global .and. t%family == FAMILY_SOLID .and. var /= 'ENER') local = allocated(sub%sections(isec)%axes)
         if (local) then
            call to_material_axes(sub, elems(i), sub%sections(isec)%axes, vals)
            name = sub%sections(isec)%axes%name
         end if
         do k = 1, size(vals, 2)
            write (row, '(i10,i4,6(1x,a13))') sub%elem_id(elems(i)), k, (c_real(vals(d, k), 13, 6), &
                 d=1, size(vals, 1))
            if (local) then
               call lu%line(trim(row)//' '//name)
            else
               call lu%line(trim(row))
            end if
         end do
       end associate
    end do
  end subroutine point_rows

  subroutine to_material_axes(sub, ie, axes, vals)
    !! The tensors vals(:, point) of solid element ie turned into its material
    !! axes at each point (a cylindrical system's axes at the point's position,
    !! the element's centre where its rule does not give the printed points).
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: ie
    type(orientation_t), intent(in) :: axes
    real(wp), intent(inout) :: vals(:, :)
    type(quad_rule_t) :: rule
    real(wp), allocatable :: n(:), dn(:, :), x(:, :)
    real(wp) :: at(3)
    integer :: k, etype
    type(element_traits_t) :: t
    etype = sub%elem_type(ie)
    t = element_traits(etype)
    allocate (x(3, t%nodes))
    do k = 1, t%nodes
       x(:, k) = sub%x(:, sub%elem_nodes(k, ie))
    end do
    rule = solid_rule(etype, .false.)
    do k = 1, size(vals, 2)
       at = sum(x, dim=2)/size(x, 2)
       if (axes%cylindrical .and. size(rule%w) == size(vals, 2)) then
          call solid_shape(etype, rule%xi(:, k), n, dn)
          at = matmul(x, n)
       end if
       vals(:, k) = tensor_in_axes(material_frame(axes, at), vals(:, k))
    end do
  end subroutine to_material_axes

  pure function tensor_in_axes(q, v) result(w)
    !! A symmetric tensor v (xx, yy, zz, xy, xz, yz) in the axes that are the rows of q: q t qᵀ.
    real(wp), intent(in) :: q(3, 3), v(NTENSOR)
    real(wp) :: w(NTENSOR), t(3, 3), qt(3, 3), a(3, 3)
    t = reshape([v(1), v(4), v(5), v(4), v(2), v(6), v(5), v(6), v(3)], [3, 3])
    qt = transpose(q)
    a = matmul(t, qt)
    t = matmul(q, a)
    w = [t(1, 1), t(2, 2), t(3, 3), t(1, 2), t(1, 3), t(2, 3)]
  end function tensor_in_axes

  subroutine point_energy(model, fields, is, isub, ie, en, vals, ok)
    !! ENER of element ie: vals(1, point), the strain energy density at
    !! CalculiX's points: ½ σ:ε (tensor shears counted twice) for the elements
    !! with both tensors at their points (solids, axisymmetric elements,
    !! trusses); ½ σ:C⁻¹:σ from the stresses at the points for plane elements
    !! and shells of an isotropic material (their strain rows hold the
    !! element's mean strain); a beam's mean, its energy en over A L, at the 8
    !! points of CalculiX's C3D20R (27 of its C3D20 for B32). ok false when
    !! there are no rows (plane elements and shells of anisotropic materials).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    type(energy_t), intent(in) :: en
    real(wp), allocatable, intent(out) :: vals(:, :)
    logical, intent(out) :: ok
    real(wp), allocatable :: s(:, :), e(:, :)
    type(element_traits_t) :: t
    integer :: k
    t = element_traits(model%subs(isub)%elem_type(ie))
    if (t%family == FAMILY_BEAM) then
       call beam_energy_density(model, isub, ie, en%element(fields%elem_offset(isub) + ie), vals, ok)
       return
    end if
    call ccx_point_values(model, fields, is, isub, ie, .false., s, ok)
    if (.not. ok) return
    allocate (vals(1, size(s, 2)))
    if ((t%family == FAMILY_PLANE .or. t%family == FAMILY_SHELL) .and. .not. t%axisymmetric) then
       ok = model%subs(isub)%elem_section(ie) > 0
       if (.not. ok) return
       associate (mat => model%materials(model%subs(isub)%sections(model%subs(isub)%elem_section(ie))%material))
         ok = mat%kind == MAT_ISO .and. .not. allocated(mat%elastic_table) .and. mat%e > 0.0_wp
         if (.not. ok) return
         do k = 1, size(s, 2)
            vals(1, k) = isotropic_energy(s(:, k), mat%e, mat%nu)
         end do
       end associate
       return
    end if
    ! the mechanical strains ε - ε_th: the energy of a heated solid is ½ σ:(ε - ε_th)
    call ccx_point_values(model, fields, is, isub, ie, .true., e, ok, mechanical=.true.)
    if (.not. ok) return
    do k = 1, size(s, 2)
       vals(1, k) = 0.5_wp*(sum(s(1:3, k)*e(1:3, k)) + 2.0_wp*sum(s(4:6, k)*e(4:6, k)))
    end do
  end subroutine point_energy

  pure real(wp) function isotropic_energy(s, e, nu) result(w)
    !! ½ σ:C⁻¹:σ of an isotropic material (Voigt xx, yy, zz, xy, xz, yz).
    real(wp), intent(in) :: s(6), e, nu
    w = (sum(s(1:3)**2) - 2.0_wp*nu*(s(1)*s(2) + s(2)*s(3) + s(3)*s(1)) + &
         2.0_wp*(1.0_wp + nu)*sum(s(4:6)**2))/(2.0_wp*e)
  end function isotropic_energy

  subroutine beam_energy_density(model, isub, ie, energy, vals, ok)
    !! vals(1, point): a beam's mean energy density energy/(A L) (L along its
    !! nodes) at the points of CalculiX's brick: 8 (C3D20R), 27 for a
    !! quadratic beam with full integration (C3D20).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: ie
    real(wp), intent(in) :: energy
    real(wp), allocatable, intent(out) :: vals(:, :)
    logical, intent(out) :: ok
    type(element_traits_t) :: t
    real(wp) :: length
    integer :: k
    associate (sub => model%subs(isub))
      t = element_traits(sub%elem_type(ie))
      ok = sub%elem_section(ie) > 0
      if (.not. ok) return
      ok = sub%sections(sub%elem_section(ie))%area > 0.0_wp
      if (.not. ok) return
      length = 0.0_wp
      do k = 2, t%nodes
         length = length + norm2(sub%x(:, sub%elem_nodes(k, ie)) - sub%x(:, sub%elem_nodes(k - 1, ie)))
      end do
      allocate (vals(1, merge(27, 8, t%quadratic .and. .not. t%reduced)), &
           source=energy/(sub%sections(sub%elem_section(ie))%area*length))
    end associate
  end subroutine beam_energy_density

  subroutine energy_rows(lu, model, fields, is, r, subs, elems)
    !! ELSE: the strain energy of each element of the set, and its total.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(output_request_t), intent(in) :: r
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    type(energy_t) :: en
    type(error_t), allocatable :: error
    character(len=30) :: row
    real(wp) :: total
    integer :: i
    call compute_energies(model, fields, is, en, error)
    if (allocated(error)) return
    total = 0.0_wp
    if (r%totals /= TOTALS_ONLY) call block_header(lu, 'internal energy (element, energy)', r, step_total_time(model, is), 'EALL')
    ! an axisymmetric model: CalculiX's energies are those of its 2° wedge (superjoin's: the whole ring)
    if (has_axisymmetric(model)) en%element = en%element/real(CCX_AXIAL_SEGMENTS, wp)
    do i = 1, size(elems)
       associate (e => en%element(fields%elem_offset(subs(i)) + elems(i)))
         total = total + e
         write (row, '(i10,1x,a13)') model%subs(subs(i))%elem_id(elems(i)), c_real(e, 13, 6)
       end associate
       if (r%totals /= TOTALS_ONLY) call lu%line(trim(row))
    end do
    if (r%totals /= TOTALS_YES .and. r%totals /= TOTALS_ONLY) return
    call block_header(lu, 'total internal energy', r, step_total_time(model, is), 'EALL')
    call total_row(lu, [total])
  end subroutine energy_rows

  pure subroutine ccx_point_map(t, map, npoint)
    !! CalculiX's integration points of the brick it expands element type t
    !! into, in-plane points fastest: map(1:npoint) the index of superjoin's
    !! point at each (0: the mean of all of superjoin's points; npoint 0: the
    !! element prints none). Layers through the thickness: ccx_layers.
    type(element_traits_t), intent(in) :: t
    integer, intent(out) :: map(MAX_CCX_POINTS), npoint
    integer :: layer(9), n, k
    map = 1
    npoint = 0
    select case (t%family)
    case (FAMILY_TRUSS)
       npoint = 8                                       ! C3D20R, one tensor
       return
    case (FAMILY_PLANE, FAMILY_SHELL)
       if (t%corners == 3 .and. .not. t%quadratic) then
          layer(1:1) = [1]                              ! C3D6: the centroid, 2 layers
          n = 1
       else if (t%corners == 3) then
          layer(1:3) = [1, 2, 3]                        ! C3D15: 3 points, 3 layers
          n = 3
       else if (t%family == FAMILY_SHELL .and. t%reduced .and. .not. t%quadratic) then
          map(1) = 0                                    ! S4R -> C3D8R: one point
          npoint = 1
          return
       else if (t%quadratic .and. .not. t%reduced .and. t%family /= FAMILY_SHELL) then
          layer = [1, 2, 3, 4, 5, 6, 7, 8, 9]           ! C3D20: 3x3, 3 layers (S8: its 2x2 stress points below)
          n = 9
       else
          layer(1:4) = [1, 2, 4, 3]                     ! C3D8, C3D20R: 2x2, xi fastest, 2 layers
          n = 4
       end if
       npoint = ccx_layers(2*n)*n
       do k = 1, npoint
          map(k) = layer(mod(k - 1, n) + 1)
       end do
    end select
  end subroutine ccx_point_map

  pure integer function ccx_layers(npoint)
    !! Layers of integration points through the thickness of CalculiX's brick
    !! with npoint points (a 3-point or 9-point layer: 3 layers).
    integer, intent(in) :: npoint
    select case (npoint)
    case (1)
       ccx_layers = 1
    case (6, 9, 18, 27)
       ccx_layers = 3
    case default
       ccx_layers = 2
    end select
  end function ccx_layers

  pure function layer_zeta(nlayer) result(z)
    !! Gauss abscissae through the thickness of CalculiX's brick.
    integer, intent(in) :: nlayer
    real(wp) :: z(nlayer)
    select case (nlayer)
    case (1)
       z = 0.0_wp
    case (2)
       z = [-1.0_wp, 1.0_wp]/sqrt(3.0_wp)
    case default
       z = [-sqrt(0.6_wp), 0.0_wp, sqrt(0.6_wp)]
    end select
  end function layer_zeta

  subroutine ccx_point_values(model, fields, is, isub, ie, strain, vals, ok, mechanical)
    !! vals(6, point) at CalculiX's points (ccx_point_map) of element ie of
    !! substructure isub; ok false when there are none to print. mechanical
    !! (present and true): a solid's strains less its thermal strains.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    logical, intent(in) :: strain
    real(wp), allocatable, intent(out) :: vals(:, :)
    logical, intent(out) :: ok
    logical, intent(in), optional :: mechanical
    type(element_traits_t) :: t
    real(wp), allocatable :: points(:, :, :), nodes(:, :, :), z(:)
    real(wp) :: one(NTENSOR)
    integer :: map(MAX_CCX_POINTS), npoint
    integer :: k, nper, nlayer
    t = element_traits(model%subs(isub)%elem_type(ie))
    if (t%family == FAMILY_SOLID .and. .not. t%axisymmetric) then
       ! a solid's own points are CalculiX's, in its order (superjoin_elements_solid_stress)
       call element_stresses(model, fields, is, isub, ie, points, nodes, ok, strain, mechanical)
       if (ok) vals = points(:, :, 1)
       return
    end if
    ! an axisymmetric element: the points and layers of the plane element with its nodes
    if (t%axisymmetric) t%family = FAMILY_PLANE
    call ccx_point_map(t, map, npoint)
    ok = npoint > 0
    if (.not. ok) return
    allocate (vals(NTENSOR, npoint))
    if (t%family == FAMILY_TRUSS .or. (strain .and. t%family == FAMILY_PLANE .and. .not. t%axisymmetric)) then
       call element_tensor(model, fields, is, isub, ie, strain, one, ok)
       do k = 1, npoint
          vals(:, k) = one
       end do
       return
    end if
    ok = .not. strain .or. t%axisymmetric
    if (.not. ok) return
    call element_stresses(model, fields, is, isub, ie, points, nodes, ok, strain, mechanical)
    if (.not. ok) return
    nlayer = ccx_layers(npoint)
    nper = npoint/nlayer
    z = layer_zeta(nlayer)
    do k = 1, npoint
       if (t%axisymmetric) then   ! turned to the point's angle in CalculiX's 2° wedge
          vals(:, k) = ccx_wedge_tensor(points(:, map(k), 1), z((k - 1)/nper + 1), .not. t%quadratic)
       else
          vals(:, k) = through_thickness(points, map(k), z((k - 1)/nper + 1))
       end if
    end do
  end subroutine ccx_point_values

  pure function through_thickness(points, ip, zeta) result(v)
    !! The stress at point ip (0: the mean of all points) and height zeta in
    !! [-1, 1] of the thickness: the quadratic through the bottom, mid and top
    !! values of a shell (thin shells: the mid value is the mean, so linear);
    !! a plane element's single value.
    real(wp), intent(in) :: points(:, :, :)
    integer, intent(in) :: ip
    real(wp), intent(in) :: zeta
    real(wp) :: v(NTENSOR), s(NTENSOR, 3)
    integer :: m
    do m = 1, min(3, size(points, 3))
       if (ip == 0) then
          s(:, m) = sum(points(:, :, m), dim=2)/real(size(points, 2), wp)
       else
          s(:, m) = points(:, ip, m)
       end if
    end do
    select case (size(points, 3))
    case (1)
       v = s(:, 1)
    case (2)
       v = 0.5_wp*(s(:, 1) + s(:, 2)) + 0.5_wp*zeta*(s(:, 2) - s(:, 1))
    case default
       v = s(:, 3) + 0.5_wp*zeta*(s(:, 2) - s(:, 1)) + &
            0.5_wp*zeta**2*(s(:, 1) + s(:, 2) - 2.0_wp*s(:, 3))
    end select
  end function through_thickness

  subroutine write_ccx_sta(path, model, fields, error)
    !! JOB.sta: CalculiX's job summary, one line per solved step (increment
    !! 1, one attempt, one iteration; the total time at its end, its period).
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: lu
    character(len=80) :: row
    integer :: is
    call open_output(lu, path, error)
    if (allocated(error)) return
    call lu%line('SUMMARY OF JOB INFORMATION')
    call lu%line('  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME')
    do is = 1, size(model%steps)
       if (allocated(fields%steps(is)%failure)) cycle
       write (row, '(i6,i11,i6,i6,3e14.6)') is, 1, 1, 1, step_total_time(model, is), model%steps(is)%period, &
            model%steps(is)%period
       call lu%line(trim(row))
    end do
    call lu%commit(path//'.tmp', path, '.sta file ', error)
  end subroutine write_ccx_sta
end module superjoin_output_ccx_dat
