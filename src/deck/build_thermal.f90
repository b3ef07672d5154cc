module superjoin_deck_build_thermal
  !! Thermal loads of the steps, from *INITIAL CONDITIONS, TYPE=TEMPERATURE and
  !! *TEMPERATURE.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, dload_t, source_loc_t, ELEMENT_TYPE_NAMES, &
       ELEMENT_NODE_COUNT, DLOAD_THERMAL, MAX_ELEMENT_NODES, material_t, section_t
  use superjoin_model_material_table, only: has_table, thermal_strain, material_at
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_TRUSS, FAMILY_BEAM, &
       FAMILY_PLANE, FAMILY_SHELL, FAMILY_SOLID
  use superjoin_deck_lexer, only: itoa
  use superjoin_utils_halting, only: halting_t, halting_off, halting_restore
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use superjoin_model_notes, only: note
  use superjoin_deck_state, only: deck_state_t, report_loc, grow
  use superjoin_deck_build_common, only: ref_subs, resolve_items, keeps_previous, more_text
  implicit none (type, external)
  private

  public :: build_thermal

  type :: real_list_t
    !! A real value per node of one substructure (temperatures).
     real(wp), allocatable :: v(:)
  end type real_list_t

  type :: temp_field_t
    !! Nodal temperatures T and the gradients across the section (g: the third
    !! field of the temperature lines, h: the fourth) of every substructure.
     type(real_list_t), allocatable :: t(:), g(:), h(:)
  end type temp_field_t

  type :: element_change_t
    !! The change of temperature (dtn) and of the third-field gradient (dgn) at
    !! the nodes of an element, and the means of the changes dt, dg, dh; the
    !! thermal strains at the nodes (eth: α ΔT, or the secant strain of a table
    !! of α, tabled) and their mean.
     real(wp) :: dt = 0.0_wp, dg = 0.0_wp, dh = 0.0_wp
     real(wp) :: dtn(MAX_ELEMENT_NODES) = 0.0_wp, dgn(MAX_ELEMENT_NODES) = 0.0_wp
     real(wp) :: eth(MAX_ELEMENT_NODES) = 0.0_wp, eth_mean = 0.0_wp
     logical :: tabled = .false.
  end type element_change_t

  type :: copies_t
    !! The copies of the materials with a temperature table while they are made.
     type(material_t), allocatable :: m(:)
     integer :: n = 0
  end type copies_t

  type :: thermal_step_t
    !! The thermal loads of one step while they are collected.
     type(dload_t), allocatable :: extra(:)   !! extra(1:n) are the loads (the rest is room to grow)
     integer :: n = 0
     type(source_loc_t) :: loc        !! the step's first *TEMPERATURE line
     integer :: nplate = 0            !! elements of a type without thermal loads (in one substructure)
     integer(ip) :: first_plate = 0
  end type thermal_step_t

contains

  subroutine build_thermal(st, model)
    !! Thermal loads from *INITIAL CONDITIONS, TYPE=TEMPERATURE and the steps'
    !! *TEMPERATURE lines: a truss or beam whose material has *EXPANSION gets,
    !! in each step with temperatures, the load of its uniform temperature
    !! change ΔT (the mean of its nodes' T - T0; nodes without a step
    !! temperature keep T0, or the previous step's temperature where the step
    !! continues it (keeps_previous), nodes without an initial one start at 0), a
    !! DLOAD_THERMAL entry of value E A α ΔT; a beam also the thermal
    !! curvatures α ∂T/∂y, α ∂T/∂z of the gradients across its section at its
    !! two nodes (linear in between)
    !! (CalculiX's third field: along the 2-direction, local z of B31/B33,
    !! local y of the planar B21/B23; the fourth: along the 1-direction, local
    !! y). A plane or shell element gets the entry of its thermal strain α ΔT
    !! (the mean over its nodes; an element whose nodes differ also the
    !! nodal remainders, interpolated to its integration points) and, on shells,
    !! of its curvature α ∂T/∂n (the mean of its nodes' gradients, the third
    !! field of the temperature lines, with the nodal remainders likewise); a B32 gets α ΔT and both gradients at
    !! its three nodes (line_nodal, interpolated along it); a gradient on any
    !! other element is refused. A solid gets α ΔT at each of its nodes
    !! (nodal, the whole value: solids have no mean part), interpolated to its
    !! integration points (superjoin_elements_solid, solid_thermal_load).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer :: m
    do m = 1, size(model%materials)
       if (.not. has_table(model%materials(m))) cycle
       call table_materials(st, model)
       exit
    end do
    if (st%aborted .or. st%ntemp == 0) return
    call temperature_pass(st, model, .true.)
  end subroutine build_thermal

  subroutine temperature_pass(st, model, loads)
    !! The temperatures of every step (kept for *NODE PRINT NT) and, with
    !! loads, the thermal loads they give.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    logical, intent(in) :: loads
    type(temp_field_t) :: init, prev, cur
    logical :: kept, ok
    integer :: s
    call zero_field(model, init)
    call apply_lines(st, model, 0, init)
    prev = init
    do s = 1, size(model%steps)
       ! the step's temperatures start from the previous step's (OP=MOD, or
       ! CalculiX's rule in a step with *STATIC) or from the initial ones
       kept = .false.
       if (s > 1 .and. keeps_previous(st%steps(s), st%steps(s)%temp_op)) kept = differ(prev, init)
       model%steps(s)%kept_temperatures = kept
       if (kept) model%steps(s)%kept_from = model%steps(s - 1)%name
       if (.not. kept .and. .not. any(st%temps(1:st%ntemp)%step == s)) then
          call keep_temperatures(model, s, init%t)
          prev = init
          cycle
       end if
       if (kept) then
          cur = prev
       else
          cur = init
       end if
       call apply_lines(st, model, s, cur)
       if (st%aborted) return
       call keep_temperatures(model, s, cur%t)
       prev = cur
       if (.not. loads) cycle
       call step_thermal_loads(st, model, s, init, cur, ok)
       if (.not. ok) return
    end do
  end subroutine temperature_pass

  subroutine table_materials(st, model)
    !! Temperature tables of *ELASTIC and *EXPANSION: every element of such a
    !! material gets it at its mean temperature (the mean over its nodes of the
    !! steps' temperature, which must be the same in every step: the stiffness
    !! is built once; no temperatures: 0, as CalculiX), a copy of the material
    !! and of its section per distinct value (superjoin_model_material_table).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(deck_state_t) :: scratch
    type(real_list_t), allocatable :: field(:)
    type(temp_field_t) :: init
    type(copies_t) :: cp
    integer :: isub, nmat0
    call zero_field_list(model, field)
    call zero_field(model, init)
    if (st%ntemp > 0) then
       scratch = st          ! the temperatures alone; their lines are reported in the real pass
       call temperature_pass(scratch, model, .false.)
       if (.not. common_field(st, model, field)) return
       call apply_lines(scratch, model, 0, init)
    end if
    nmat0 = size(model%materials)
    do isub = 1, size(model%subs)
       call table_sub(model, isub, reshape([init%t(isub)%v, field(isub)%v], [size(field(isub)%v), 2]), nmat0, cp)
    end do
    if (cp%n > 0) model%materials = [model%materials, cp%m(1:cp%n)]
    if (size(model%materials) > nmat0) call note(model%notes, 'temperature tables (*ELASTIC, *EXPANSION): E, nu '// &
         'and alpha taken at each integration point of the solids, at the mean temperature of each other element ('// &
         itoa(size(model%materials) - nmat0)//' copies of the materials)')
  end subroutine table_materials

  subroutine zero_field_list(model, field)
    !! A temperature 0 at every node.
    type(model_t), intent(in) :: model
    type(real_list_t), allocatable, intent(out) :: field(:)
    integer :: isub
    allocate (field(size(model%subs)))
    do isub = 1, size(model%subs)
       allocate (field(isub)%v(model%subs(isub)%nnode), source=0.0_wp)
    end do
  end subroutine zero_field_list

  logical function common_field(st, model, field) result(ok)
    !! field: the temperatures of the steps (they must be the same in all;
    !! reported if not, ok false).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(real_list_t), intent(inout) :: field(:)
    integer :: s, first, k
    ok = .true.
    first = 0
    do s = 1, size(model%steps)
       if (.not. allocated(model%steps(s)%temperature)) cycle
       if (first == 0) then
          first = s
          do k = 1, size(field)
             field(k)%v = model%steps(s)%temperature(k)%v
          end do
       else if (any([(any(model%steps(s)%temperature(k)%v /= field(k)%v), k=1, size(field))])) then
          call report_loc(st, first_line(st, model, s), 'a material with a temperature table (*ELASTIC or '// &
               '*EXPANSION with several lines) takes its values at the temperature of the steps, which must be '// &
               'the same in every step (superjoin builds one stiffness): step '//model%steps(s)%name// &
               ' differs from step '//model%steps(first)%name)
          ok = .false.
          return
       end if
    end do
  end function common_field

  subroutine table_sub(model, isub, t, nmat0, cp)
    !! The elements of substructure isub whose material has a table: a copy of
    !! the material at the element's mean temperature (nodal temperatures
    !! t(:, 1) initial, t(:, 2) of the steps), shared by the elements where it
    !! is the same (cp: the copies, to be materials nmat0+1..), and a copy of
    !! the section with it; a solid gets a copy of its own that holds its
    !! nodes' temperatures (at_nodes: its values taken at each integration point).
    type(model_t), intent(inout) :: model
    integer, intent(in) :: isub, nmat0
    real(wp), intent(in) :: t(:, :)
    type(copies_t), intent(inout) :: cp
    type(material_t) :: m
    type(element_traits_t) :: tr
    type(section_t), allocatable :: secs(:)
    integer, allocatable :: origin(:)
    integer :: nsec0, k, im, is, nn, ns
    integer(ip) :: e
    logical :: solid
    associate (sub => model%subs(isub))
      nsec0 = size(sub%sections)
      allocate (origin(16), secs(16))
      ns = 0
      do e = 1, sub%nelem
         k = sub%elem_section(e)
         if (k <= 0) cycle
         if (sub%sections(k)%material <= 0) cycle
         if (.not. has_table(model%materials(sub%sections(k)%material))) cycle
         nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
         if (nn == 0 .or. any(sub%elem_nodes(1:nn, e) <= 0)) cycle
         m = material_at(model%materials(sub%sections(k)%material), sum(t(sub%elem_nodes(1:nn, e), 2))/nn)
         tr = element_traits(sub%elem_type(e))
         solid = tr%family == FAMILY_SOLID
         im = 0
         if (solid) then
            m%at_nodes = transpose(t(sub%elem_nodes(1:nn, e), :))
         else
            if (cp%n > 0) im = find_material(cp%m(1:cp%n), m)
         end if
         if (im == 0) then
            call grow(cp%m, cp%n, 16)
            cp%n = cp%n + 1
            cp%m(cp%n) = m
            im = cp%n
         end if
         im = nmat0 + im
         is = ns + 1
         if (.not. solid) then   ! a solid's copy is its own: no section to share
            do is = 1, ns
               if (origin(is) == k .and. secs(is)%material == im) exit
            end do
         end if
         if (is > ns) then
            if (ns == size(secs)) then
               secs = [secs, secs]
               origin = [origin, origin]
            end if
            ns = ns + 1
            origin(ns) = k
            secs(ns) = sub%sections(k)
            secs(ns)%material = im
         end if
         sub%elem_section(e) = nsec0 + is
      end do
      if (ns > 0) sub%sections = [sub%sections, secs(1:ns)]
    end associate
  end subroutine table_sub

  pure integer function find_material(list, m) result(k)
    !! The index in list of a material of m's name with m's E, nu and alpha
    !! (0: none; a solid's own copy is never shared).
    type(material_t), intent(in) :: list(:), m
    do k = 1, size(list)
       if (allocated(list(k)%at_nodes)) cycle
       if (list(k)%name == m%name .and. list(k)%e == m%e .and. list(k)%nu == m%nu .and. &
            list(k)%alpha == m%alpha) return
    end do
    k = 0
  end function find_material

  subroutine zero_field(model, f)
    !! Temperatures and gradients 0 at every node of the model.
    type(model_t), intent(in) :: model
    type(temp_field_t), intent(out) :: f
    integer :: isub
    allocate (f%t(size(model%subs)), f%g(size(model%subs)), f%h(size(model%subs)))
    do isub = 1, size(model%subs)
       allocate (f%t(isub)%v(model%subs(isub)%nnode), source=0.0_wp)
       allocate (f%g(isub)%v(model%subs(isub)%nnode), source=0.0_wp)
       allocate (f%h(isub)%v(model%subs(isub)%nnode), source=0.0_wp)
    end do
  end subroutine zero_field

  subroutine apply_lines(st, model, step, f)
    !! Set the temperatures and gradients the lines of step (0: initial conditions) give.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: step
    type(temp_field_t), intent(inout) :: f
    integer(ip), allocatable :: nodes(:)
    integer(ip) :: i
    integer :: j, js, m
    integer, allocatable :: subs(:)
    logical :: ok
    do j = 1, st%ntemp
       if (st%temps(j)%step /= step) cycle
       call ref_subs(st, model, st%temps(j)%ref, st%temps(j)%loc, 'node', subs)   ! several: a set over instances
       do m = 1, size(subs)
          js = subs(m)
          call resolve_items(st, model, js, st%temps(j)%ref, .false., st%temps(j)%loc, nodes, ok)
          if (.not. ok) cycle
          do i = 1, size(nodes, kind=ip)
             f%t(js)%v(nodes(i)) = st%temps(j)%value
             f%g(js)%v(nodes(i)) = st%temps(j)%grad
             f%h(js)%v(nodes(i)) = st%temps(j)%grad1
          end do
       end do
    end do
  end subroutine apply_lines

  pure logical function differ(a, b)
    !! Whether two temperature fields differ anywhere (temperatures or gradients).
    type(temp_field_t), intent(in) :: a, b
    differ = lists_differ(a%t, b%t) .or. lists_differ(a%g, b%g) .or. lists_differ(a%h, b%h)
  end function differ

  pure logical function lists_differ(a, b)
    !! Whether two nodal fields (per substructure) differ anywhere.
    type(real_list_t), intent(in) :: a(:), b(:)
    integer :: k
    lists_differ = .false.
    do k = 1, size(a)
       if (any(a(k)%v /= b(k)%v)) lists_differ = .true.
    end do
  end function lists_differ

  subroutine keep_temperatures(model, step, field)
    !! The nodal temperatures of a step, for *NODE PRINT NT.
    type(model_t), intent(inout) :: model
    integer, intent(in) :: step
    type(real_list_t), intent(in) :: field(:)
    integer :: k
    if (model%steps(step)%combination > 0) return
    if (.not. allocated(model%steps(step)%temperature)) allocate (model%steps(step)%temperature(size(field)))
    do k = 1, size(field)
       model%steps(step)%temperature(k)%v = field(k)%v
    end do
  end subroutine keep_temperatures

  function first_line(st, model, step) result(loc)
    !! The first *TEMPERATURE line of a step (where its thermal loads come from).
    type(deck_state_t), intent(in) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: step
    type(source_loc_t) :: loc
    integer :: j
    loc = model%steps(step)%loc
    do j = 1, st%ntemp
       if (st%temps(j)%step == step) then
          loc = st%temps(j)%loc
          return
       end if
    end do
  end function first_line

  subroutine step_thermal_loads(st, model, s, init, cur, ok)
    !! The thermal loads of step s (temperatures cur, from init), added to its
    !! distributed loads; not ok (nothing added) when a gradient is refused or
    !! a load leaves the floating-point range (formed with halting off, then
    !! checked: the first such element reported at the step's first
    !! temperature line).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    integer, intent(in) :: s
    type(temp_field_t), intent(in) :: init, cur
    logical, intent(out) :: ok
    type(thermal_step_t) :: ts
    type(halting_t) :: saved
    integer :: k
    allocate (ts%extra(0))
    ts%loc = first_line(st, model, s)
    call halting_off(saved)
    call elements_thermal(st, model, init, cur, ts, ok)
    call halting_restore(saved)
    if (.not. ok) return
    do k = 1, ts%n
       if (load_finite(ts%extra(k))) cycle
       associate (sub => model%subs(ts%extra(k)%sub))
         call report_loc(st, ts%loc, 'the thermal load of element '//itoa(sub%elem_id(ts%extra(k)%elem))// &
              ' of substructure '//sub%name//' overflows the floating-point range (beyond 1.8E+308 or '// &
              'undefined): check the expansion coefficient, the temperatures and their units')
       end associate
       ok = .false.
       return
    end do
    model%steps(s)%dloads = [model%steps(s)%dloads, ts%extra(1:ts%n)]
  end subroutine step_thermal_loads

  pure logical function load_finite(d) result(ok)
    !! Every number of the thermal load d is finite.
    type(dload_t), intent(in) :: d
    ok = all(ieee_is_finite([d%value, d%curvature, d%gradient]))
    if (.not. (ok .and. allocated(d%nodes))) return
    if (allocated(d%nodes%nodal)) ok = all(ieee_is_finite(d%nodes%nodal))
    if (ok .and. allocated(d%nodes%curvature_nodal)) ok = all(ieee_is_finite(d%nodes%curvature_nodal))
    if (ok .and. allocated(d%nodes%line_nodal)) ok = all(ieee_is_finite(d%nodes%line_nodal))
  end function load_finite

  subroutine elements_thermal(st, model, init, cur, ts, ok)
    !! The thermal loads of every element into ts (step_thermal_loads); not ok
    !! when a gradient is refused.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(temp_field_t), intent(in) :: init, cur
    type(thermal_step_t), intent(inout) :: ts
    logical, intent(out) :: ok
    integer :: isub
    integer(ip) :: e
    ok = .true.
    do isub = 1, size(model%subs)
       ts%nplate = 0
       do e = 1, model%subs(isub)%nelem
          call element_thermal(st, model, isub, e, init, cur, ts, ok)
          if (.not. ok) return
       end do
       if (ts%nplate > 0) then
          associate (sub => model%subs(isub))
            call report_loc(st, ts%loc, 'temperature change on element '//itoa(sub%elem_id(ts%first_plate))// &
                 ' of type '//trim(ELEMENT_TYPE_NAMES(sub%elem_type(ts%first_plate)))//' of substructure '// &
                 sub%name//': thermal loads are implemented for trusses, beams, plane elements, solids and S3, S4, S3R, S4R, S8R shells only'// &
                 more_text(ts%nplate - 1))
          end associate
       end if
    end do
  end subroutine elements_thermal

  subroutine element_thermal(st, model, isub, e, init, cur, ts, ok)
    !! The thermal load of element e of substructure isub, if its material
    !! expands and its temperatures changed; not ok when a gradient is refused.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    type(temp_field_t), intent(in) :: init, cur
    type(thermal_step_t), intent(inout) :: ts
    logical, intent(out) :: ok
    type(element_change_t) :: c
    type(element_traits_t) :: tr
    integer :: nn
    ok = .true.
    associate (sub => model%subs(isub))
      if (sub%elem_section(e) == 0) return
      ! an undefined material or node has been reported already
      if (sub%sections(sub%elem_section(e))%material <= 0) return
      associate (mat => model%materials(sub%sections(sub%elem_section(e))%material))
        if (.not. mat%has_expansion .or. (mat%alpha == 0.0_wp .and. .not. has_table(mat))) return
        nn = ELEMENT_NODE_COUNT(sub%elem_type(e))
        ! an element with an undefined node has been reported already
        if (nn == 0 .or. any(sub%elem_nodes(1:nn, e) <= 0)) return
        c = element_change(sub%elem_nodes(1:nn, e), isub, init, cur, mat)
        if (c%dt == 0.0_wp .and. c%dg == 0.0_wp .and. c%dh == 0.0_wp .and. all(c%dtn(1:nn) == 0.0_wp) &
             .and. all(c%dgn(1:nn) == 0.0_wp)) return
        tr = element_traits(sub%elem_type(e))
        select case (tr%family)
        case (FAMILY_TRUSS, FAMILY_BEAM)
           if (tr%quadratic) then
              ! the three-node beam: α ΔT and both gradients (fourth field: local y,
              ! third: local z) at each node, interpolated along it
              call add_load(ts, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, value=0.0_wp, loc=ts%loc))
              associate (en => sub%elem_nodes(1:3, e))
                allocate (ts%extra(ts%n)%nodes)   ! (gfortran 12 garbles a constructor of this transpose)
                ts%extra(ts%n)%nodes%line_nodal = transpose(reshape([c%eth(1:3), &
                     mat%alpha*(cur%h(isub)%v(en) - init%h(isub)%v(en)), &
                     mat%alpha*(cur%g(isub)%v(en) - init%g(isub)%v(en))], [3, 3]))
              end associate
           else
              call line_thermal(st, model, isub, e, tr, c, init, cur, ts, ok)
           end if
        case (FAMILY_PLANE, FAMILY_SHELL)
           call area_thermal(st, model, isub, e, tr, c, ts, ok)
        case (FAMILY_SOLID)
           ! a solid: α ΔT at every node (interpolated to its points), the mean as its value
           if (c%dg /= 0.0_wp .or. c%dh /= 0.0_wp) then
              call refuse(st, model, isub, e, ts%loc, 'the gradient fields (third and fourth) apply to shells and '// &
                   'beams only: give a solid its nodal temperatures')
              ok = .false.
              return
           end if
           call add_load(ts, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, value=c%eth_mean, loc=ts%loc))
           allocate (ts%extra(ts%n)%nodes)
           ts%extra(ts%n)%nodes%nodal = c%eth(1:nn)
        case default
           ts%nplate = ts%nplate + 1
           if (ts%nplate == 1) ts%first_plate = e
        end select
      end associate
    end associate
  end subroutine element_thermal

  subroutine add_load(ts, load)
    !! Append load to ts%extra(1:ts%n), doubling its room when full (one load
    !! per element: appending by array constructor copied them all each time).
    type(thermal_step_t), intent(inout) :: ts
    type(dload_t), intent(in) :: load
    type(dload_t), allocatable :: grown(:)
    if (ts%n == size(ts%extra)) then
       allocate (grown(max(16, 2*ts%n)))
       grown(1:ts%n) = ts%extra(1:ts%n)
       call move_alloc(grown, ts%extra)
    end if
    ts%n = ts%n + 1
    ts%extra(ts%n) = load
  end subroutine add_load

  pure function element_change(en, isub, init, cur, mat) result(c)
    !! The changes of temperature and gradients at the nodes en of an element
    !! of substructure isub of material mat, their means, and the thermal strains.
    integer(ip), intent(in) :: en(:)
    integer, intent(in) :: isub
    type(temp_field_t), intent(in) :: init, cur
    type(material_t), intent(in) :: mat
    type(element_change_t) :: c
    integer :: nn, a
    nn = size(en)
    c%dtn(1:nn) = cur%t(isub)%v(en) - init%t(isub)%v(en)
    c%dgn(1:nn) = cur%g(isub)%v(en) - init%g(isub)%v(en)
    c%dt = sum(cur%t(isub)%v(en) - init%t(isub)%v(en))/nn
    c%dg = sum(cur%g(isub)%v(en) - init%g(isub)%v(en))/nn
    c%dh = sum(cur%h(isub)%v(en) - init%h(isub)%v(en))/nn
    c%tabled = has_table(mat)
    if (.not. c%tabled) then
       c%eth(1:nn) = mat%alpha*c%dtn(1:nn)
       c%eth_mean = mat%alpha*c%dt
       return
    end if
    do a = 1, nn   ! a table of α: the secant strain from ZERO=
       c%eth(a) = thermal_strain(mat, cur%t(isub)%v(en(a)), init%t(isub)%v(en(a)))
    end do
    c%eth_mean = sum(c%eth(1:nn))/nn
  end function element_change

  subroutine line_thermal(st, model, isub, e, tr, c, init, cur, ts, ok)
    !! Truss or two-node beam e: the axial load E A α ΔT, and on a beam the
    !! curvatures of the gradients at its nodes (planar beams: the third field;
    !! beams in space: the fourth field along local y, the third along local z).
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    type(element_traits_t), intent(in) :: tr
    type(element_change_t), intent(in) :: c
    type(temp_field_t), intent(in) :: init, cur
    type(thermal_step_t), intent(inout) :: ts
    logical, intent(out) :: ok
    ok = .false.
    if (c%dg /= 0.0_wp .and. tr%family == FAMILY_TRUSS) then
       call refuse(st, model, isub, e, ts%loc, 'the gradients (third and fourth fields) apply to shells and beams only')
       return
    end if
    if (c%dh /= 0.0_wp .and. (tr%family == FAMILY_TRUSS .or. tr%planar)) then
       call refuse(st, model, isub, e, ts%loc, 'the fourth field, the gradient along the 1-direction of a beam in space, '// &
            'acts normal to the plane of a planar element')
       return
    end if
    ok = .true.
    associate (sub => model%subs(isub), n2 => model%subs(isub)%elem_nodes(1:2, e))
      associate (sec => sub%sections(sub%elem_section(e)))
        associate (mat => model%materials(sec%material))
          if (c%tabled) then
             call add_load(ts, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, &
                  value=mat%e*sec%area*c%eth_mean, loc=ts%loc))
          else
             call add_load(ts, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, &
                  value=mat%e*sec%area*mat%alpha*c%dt, loc=ts%loc))
          end if
          if (tr%family /= FAMILY_BEAM) return
          if (tr%planar) then
             ts%extra(ts%n)%gradient(1, :) = mat%alpha*(cur%g(isub)%v(n2) - init%g(isub)%v(n2))
          else
             ts%extra(ts%n)%gradient(1, :) = mat%alpha*(cur%h(isub)%v(n2) - init%h(isub)%v(n2))
             ts%extra(ts%n)%gradient(2, :) = mat%alpha*(cur%g(isub)%v(n2) - init%g(isub)%v(n2))
          end if
        end associate
      end associate
    end associate
  end subroutine line_thermal

  subroutine area_thermal(st, model, isub, e, tr, c, ts, ok)
    !! Plane or shell element e: the thermal strain α ΔT and (shells) the
    !! curvature α ∂T/∂n, with the nodal remainders where its nodes differ.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    type(element_traits_t), intent(in) :: tr
    type(element_change_t), intent(in) :: c
    type(thermal_step_t), intent(inout) :: ts
    logical, intent(out) :: ok
    integer :: nn
    ok = .false.
    if ((c%dg /= 0.0_wp .and. tr%family /= FAMILY_SHELL) .or. c%dh /= 0.0_wp) then
       call refuse(st, model, isub, e, ts%loc, 'the gradient (third field) applies to shells and beams only, the fourth '// &
            'field to beams only')
       return
    end if
    ok = .true.
    nn = tr%nodes
    associate (sub => model%subs(isub))
      associate (mat => model%materials(sub%sections(sub%elem_section(e))%material))
        call add_load(ts, dload_t(sub=isub, elem=e, kind=DLOAD_THERMAL, &
             value=c%eth_mean, curvature=mat%alpha*c%dg, loc=ts%loc))
        ! a plane element whose nodes differ: the nodal values, interpolated to its points
        if (tr%family == FAMILY_PLANE .and. any(c%eth(1:nn) /= c%eth(1))) then
           allocate (ts%extra(ts%n)%nodes)
           ts%extra(ts%n)%nodes%nodal = c%eth(1:nn) - c%eth_mean
        end if
        ! a shell whose nodes differ: both nodal remainders, interpolated to its points
        if (tr%family /= FAMILY_PLANE .and. &
             (any(c%eth(1:nn) /= c%eth(1)) .or. any(c%dgn(1:nn) /= c%dgn(1)))) then
           allocate (ts%extra(ts%n)%nodes)
           ts%extra(ts%n)%nodes%nodal = c%eth(1:nn) - c%eth_mean
           ts%extra(ts%n)%nodes%curvature_nodal = mat%alpha*c%dgn(1:nn) - mat%alpha*c%dg
        end if
      end associate
    end associate
  end subroutine area_thermal

  subroutine refuse(st, model, isub, e, loc, why)
    !! Refuse a gradient on element e of substructure isub.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: e
    type(source_loc_t), intent(in) :: loc
    character(*), intent(in) :: why
    call report_loc(st, loc, 'temperature gradient on element '// &
         itoa(model%subs(isub)%elem_id(e))//' of type '// &
         trim(ELEMENT_TYPE_NAMES(model%subs(isub)%elem_type(e)))//': '//why)
  end subroutine refuse
end module superjoin_deck_build_thermal
