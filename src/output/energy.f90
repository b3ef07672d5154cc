module superjoin_output_energy
  !! Strain energies of a solved step (output variable ENER of *EL PRINT and
  !! *EL FILE): per element ½ u_eᵀ K_e u_e (the element facade's
  !! element_strain_energy), or under thermal strains the energy of the
  !! mechanical strains ½ ∫ (ε - ε_th)ᵀ D (ε - ε_th) dV (element_thermal_energy;
  !! where it is not implemented, the energies are not available), per substructure (part) the sum of
  !! its elements, per contact element ½ Σ F·δ over its DOFs (½ g δ² for a
  !! finite DOF; a RIGID DOF has δ = 0 and no energy), per *CONTACT card the sum
  !! of its contact elements, and the spring supports ½ g u².
  !!
  !! The balance printed with them (Clapeyron's theorem for the linear model):
  !!   Σ elements + Σ contacts + Σ spring supports = ½ fᵀu + ½ Σ R ū
  !! with f the applied loads (concentrated and consistent distributed loads),
  !! u the displacements, and the second term the work of the reactions R of the
  !! rigid supports on their prescribed displacements ū (zero without them).
  !! Both sides come from independent sums (element matrices, contact forces,
  !! loads and reactions), so their difference measures the solution's
  !! consistency; it is printed relative to the larger side.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t, add_error_line, EXIT_DECK
  use superjoin_model_types, only: model_t, output_request_t, NDOF_NODE, &
       LINK_FINITE, loc_text, DLOAD_THERMAL, support_t
  use superjoin_elements, only: element_strain_energy, element_displacements, element_thermal_energy
  use superjoin_elements, only: distributed_load
  use superjoin_model_results, only: result_fields_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop
  implicit none (type, external)
  private


  type, public :: energy_t
    !! Strain energies of one step and the two sides of the balance.
     real(wp), allocatable :: element(:)   !! (nelem_total) numbered as fields%elem_offset
     real(wp), allocatable :: part(:)      !! (nsub)
     real(wp), allocatable :: link(:)      !! (nlink) contact elements
     real(wp), allocatable :: contact(:)   !! (ncontact) *CONTACT cards
     real(wp) :: supports = 0.0_wp         !! spring supports (finite *BOUNDARY / SPRING1)
     real(wp) :: internal = 0.0_wp         !! elements + contacts + spring supports
     real(wp) :: load_work = 0.0_wp        !! ½ fᵀu
     real(wp) :: prescribed_work = 0.0_wp  !! ½ Σ R ū over the rigid supports
     character(:), allocatable :: no_balance  !! why the balance does not apply to this step (unallocated: it does)
  end type energy_t

  public :: compute_energies, write_energy_request, requests_name

contains

  subroutine compute_energies(model, fields, is, en, error)
    !! Every strain energy of step `is` and both sides of the balance.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(energy_t), intent(out) :: en
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: inner
    real(wp), allocatable :: ue(:), fe(:)
    real(wp) :: ql(3)
    integer :: isub, il, k
    integer(ip) :: e
    integer(i8) :: iel

    allocate (en%element(fields%elem_offset(size(model%subs) + 1)), source=0.0_wp)
    allocate (en%part(size(model%subs)), source=0.0_wp)
    allocate (en%link(size(model%links)), en%contact(size(model%contacts)), source=0.0_wp)
    do isub = 1, size(model%subs)
       associate (sub => model%subs(isub))
         do e = 1, sub%nelem
            if (sub%elem_section(e) <= 0) cycle
            iel = fields%elem_offset(isub) + e
            call element_strain_energy(model, fields, is, isub, e, en%element(iel), inner)
            if (allocated(inner)) then
               call add_error_line(error, EXIT_DECK, loc_text(model, sub%elem_loc(e))//': error: '//inner%message)
               return
            end if
         end do
       end associate
    end do

    ! Contact elements: ½ F·δ per DOF in the contact's axes (F on the master).
    do il = 1, size(model%links)
       en%link(il) = 0.5_wp*dot_product(fields%steps(is)%link_force(:, il), fields%steps(is)%link_delta(:, il))
       associate (c => model%links(il)%contact)
         en%contact(c) = en%contact(c) + en%link(il)
       end associate
    end do

    call support_terms(model, fields, is, en)

    ! ½ fᵀu: concentrated loads and the consistent loads of distributed loads.
    associate (st => model%steps(is))
      do k = 1, size(st%cloads)
         associate (cl => st%cloads(k))
           en%load_work = en%load_work + 0.5_wp*cl%value*node_u(fields, is, cl%sub, cl%node, cl%dof)
         end associate
      end do
      if (allocated(st%dloads)) then
         do k = 1, size(st%dloads)
            call distributed_load(model, st%dloads(k), fe, ql, inner)
            if (allocated(inner)) then
               call add_error_line(error, EXIT_DECK, loc_text(model, st%dloads(k)%loc)//': error: '// &
                    inner%message)
               return
            end if
            call element_displacements(model, fields, is, st%dloads(k)%sub, st%dloads(k)%elem, ue)
            en%load_work = en%load_work + 0.5_wp*dot_product(fe, ue)
            if (st%dloads(k)%kind /= DLOAD_THERMAL) cycle
            ! thermal strains: the element's energy is that of its mechanical strains ε - ε_th
            call element_thermal_energy(model, fields, is, st%dloads(k), &
                 en%element(fields%elem_offset(st%dloads(k)%sub) + st%dloads(k)%elem), inner)
            if (allocated(inner)) then
               call add_error_line(error, EXIT_DECK, loc_text(model, st%dloads(k)%loc)//': error: '// &
                    inner%message)
               return
            end if
         end do
      end if
    end associate
    do isub = 1, size(model%subs)
       do e = 1, model%subs(isub)%nelem
          en%part(isub) = en%part(isub) + en%element(fields%elem_offset(isub) + e)
       end do
    end do
    en%internal = sum(en%part) + sum(en%contact) + en%supports
    ! Clapeyron's balance holds for a solved step of mechanical loads only.
    if (model%steps(is)%combination > 0) then
       en%no_balance = 'a load combination: energies do not superpose'
    else if (heated(model, is)) then
       en%no_balance = 'thermal strains: the strain energy is not 1/2 f.u'
    end if
  end subroutine compute_energies

  subroutine support_terms(model, fields, is, en)
    !! Energy of the spring supports (½ g u², global DOFs) and the work ½ R ū of
    !! the reactions of the rigid supports. A DOF with a rigid support is rigid
    !! whatever springs it also has; several springs on one DOF add up.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(energy_t), intent(inout) :: en
    real(wp), allocatable :: g(:, :), ubar(:, :)
    logical, allocatable :: rigid(:, :)
    integer :: k
    integer(i8) :: vx, nv
    nv = size(fields%has_dof, 2, kind=i8)
    allocate (g(NDOF_NODE, nv), source=0.0_wp)
    allocate (rigid(NDOF_NODE, nv), source=.false.)
    allocate (ubar(NDOF_NODE, nv), source=0.0_wp)
    if (allocated(model%steps(is)%supports)) then
       call mark_supports(model%steps(is)%supports)
    else
       call mark_supports(model%supports)
    end if
    do vx = 1, nv
       do k = 1, NDOF_NODE
          if (rigid(k, vx) .or. g(k, vx) == 0.0_wp) cycle
          en%supports = en%supports + 0.5_wp*g(k, vx)*fields%u(NDOF_NODE*(vx - 1) + k, is)**2
       end do
    end do
    do k = 1, size(fields%steps(is)%reactions)
       associate (rc => fields%steps(is)%reactions(k))
         vx = fields%vertex_offset(rc%sub) + rc%node
         if (.not. rigid(rc%dof, vx)) cycle
         ! ū: the support's prescribed value, along the reaction's own axis (the
         ! nodal system of a *TRANSFORM, where reaction and support are local)
         en%prescribed_work = en%prescribed_work + 0.5_wp*rc%force*ubar(rc%dof, vx)
       end associate
    end do
  contains
    subroutine mark_supports(list)
      !! Spring stiffness and rigidity per DOF from the supports in effect.
      type(support_t), intent(in) :: list(:)
      do k = 1, size(list)
         associate (sp => list(k))
           vx = fields%vertex_offset(sp%sub) + sp%node
           if (sp%state == LINK_FINITE) then
              g(sp%dof, vx) = g(sp%dof, vx) + sp%g
           else
              rigid(sp%dof, vx) = .true.
              ubar(sp%dof, vx) = sp%value
           end if
         end associate
      end do
    end subroutine mark_supports
  end subroutine support_terms

  pure logical function heated(model, is)
    !! Does step is have thermal strains?
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    heated = .false.
    if (allocated(model%steps(is)%dloads)) heated = any(model%steps(is)%dloads(:)%kind == DLOAD_THERMAL)
  end function heated

  pure real(wp) function node_u(fields, is, isub, node, dof) result(v)
    !! Displacement component `dof` of a node in step `is` (global axes).
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub, dof
    integer(ip), intent(in) :: node
    v = fields%u(NDOF_NODE*(fields%vertex_offset(isub) + node - 1) + dof, is)
  end function node_u

  pure logical function requests_name(r, name)
    !! Does request r name the output variable `name`?
    type(output_request_t), intent(in) :: r
    character(*), intent(in) :: name
    integer :: k
    requests_name = .false.
    if (.not. allocated(r%vars)) return
    do k = 1, size(r%vars)
       if (r%vars(k)%s == name) requests_name = .true.
    end do
  end function requests_name

  subroutine write_energy_request(lu, model, fields, is, subs, elems)
    !! The ENER block of an *EL PRINT request: the energy of the set's elements,
    !! then per substructure, per *CONTACT card and the balance of the model
    !! (an element that cannot be evaluated, which a solved model cannot have,
    !! gives a line saying why instead).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    type(energy_t) :: en
    type(error_t), allocatable :: error
    real(wp) :: scale, big
    integer :: i
    character(len=120) :: hline

    call compute_energies(model, fields, is, en, error)
    if (allocated(error)) then
       call lu%line('    ENER not available: '//error%message)
       return
    end if
    if (heated(model, is)) then
       call lu%line('    ENER strain energy (elements: 1/2 (eps - eps_th):D:(eps - eps_th), thermal strains; '// &
            'contact elements: 1/2 F.delta; spring supports: 1/2 g u^2)')
    else
       call lu%line('    ENER strain energy (elements: 1/2 u^T K u; contact elements: 1/2 F.delta; '// &
            'spring supports: 1/2 g u^2)')
    end if
    write (hline, '(4x,a20,a10,a6,a15)') 'substructure        ', '   element', '  type', '         energy'
    call lu%line(trim(hline))
    scale = 0.0_wp
    if (size(en%element) > 0) scale = maxval(abs(en%element))
    do i = 1, size(elems)
       call element_prefix(lu, model, subs(i), elems(i), 4)
       call lu%put_es(chop(en%element(fields%elem_offset(subs(i)) + elems(i)), scale))
       call lu%newline()
    end do
    call lu%line('    strain energy per substructure')
    do i = 1, size(model%subs)
       call lu%put('      ')
       call lu%put_field(model%subs(i)%name, 34)
       call lu%put_es(chop(en%part(i), scale))
       call lu%newline()
    end do
    if (size(model%contacts) > 0) then
       call lu%line('    strain energy per *CONTACT (joint)')
       do i = 1, size(model%contacts)
          call lu%put('      ')
          call lu%put_field(model%contacts(i)%name, 34)
          call lu%put_es(chop(en%contact(i), en%internal))
          call lu%newline()
       end do
    end if
    big = max(abs(en%internal), abs(en%load_work + en%prescribed_work))
    call lu%line('    energy balance (Clapeyron): elements + contacts + spring supports = '// &
         '1/2 f.u + 1/2 R.u(prescribed)')
    call energy_line('elements', sum(en%part))
    call energy_line('contacts', sum(en%contact))
    call energy_line('spring supports', en%supports)
    call energy_line('total strain energy', en%internal)
    call energy_line('1/2 f.u (loads)', en%load_work)
    call energy_line('1/2 R.u (prescribed supports)', en%prescribed_work)
    call lu%put('      ')
    call lu%put_field('relative difference', 34)
    if (allocated(en%no_balance)) then
       call lu%put('  not checked: '//en%no_balance)
    else if (big > 0.0_wp) then
       call lu%put_es(abs(en%internal - en%load_work - en%prescribed_work)/big)
    else
       call lu%put_es(0.0_wp)
    end if
    call lu%newline()
  contains
    subroutine energy_line(label, value)
      character(*), intent(in) :: label
      real(wp), intent(in) :: value
      call lu%put('      ')
      call lu%put_field(label, 34)
      call lu%put_es(chop(value, big))
      call lu%newline()
    end subroutine energy_line
  end subroutine write_energy_request
end module superjoin_output_energy
