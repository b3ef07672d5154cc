module superjoin_output_stresses
  !! Stresses of the plane elements (CPS3, CPS4, CPE3, CPE4; second order CPS6,
  !! CPS8, CPS8R, CPE6, CPE8, CPE8R) and of the shells (S3, S4: bottom and top
  !! surface, σ = n/t ∓ 6 m/t²; S3R, S4R, S8R: also the mid-surface with the
  !! transverse shear 1.5 q/t) where benchmarks quote them: at the integration points (*EL PRINT S, as CalculiX's .dat)
  !! and at the nodes (*NODE PRINT S / *NODE FILE S): extrapolated from the
  !! integration points of each element (superjoin_elements_membrane,
  !! membrane_point_stresses; superjoin_elements_quadratic,
  !! quadratic_point_stresses; superjoin_elements_shell, shell_surface_stresses
  !! and thick_shell_stresses; S8R: superjoin_elements_shell8, shell8_stresses,
  !! at its 2×2 points, corners extrapolated bilinearly, mid-side nodes the
  !! mean of their corners)
  !! and averaged over the plane and shell elements of the same
  !! substructure (part) that share the node. Tensors in global axes, Voigt
  !! order xx, yy, zz, xy, xz, yz; plane strain has σzz = ν (σxx + σyy).
  !!
  !! Beams with a library section (*BEAM SECTION, SECTION=RECT, CIRC, PIPE,
  !! BOX, I) also get the axial fibre stress at the extreme points of the
  !! section (superjoin_deck_beam_sections, section_fibres) at both ends:
  !!   σ = N/A - Mz y/Iz + My z/Iy
  !! with the section forces of the sign convention of the user manual: the
  !! force and moment that the part of the beam beyond the cut (+x side) exerts
  !! on the part before it, in local axes, so S(end 1) = -f(end 1) and
  !! S(end 2) = +f(end 2) for the end forces f (forces the nodes exert on the
  !! element); N > 0 in tension, Mz > 0 stretches the -y fibres.
  use superjoin_kinds, only: wp, i8, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, ELEMENT_NODE_COUNT
  use superjoin_elements, only: element_stresses, NTENSOR
  use superjoin_elements_traits, only: element_traits_t, element_traits, FAMILY_PLANE, FAMILY_SHELL, FAMILY_BEAM, &
       FAMILY_SOLID, is_family
  use superjoin_model_results, only: result_fields_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  integer, parameter, public :: NSURF = 3
    !! Section points of a shell: 1 bottom (z = -t/2), 2 top (z = +t/2, along the
    !! element normal), 3 the mid-surface (thick shells only).
  integer, parameter :: THIN_SURFACES = 2
  integer, parameter :: SOLID_KIND = 1, SHELL8_KIND = 2, SHELL6_KIND = 3
    !! Element kinds of nodes_of_kind: solids, the eight-node shells S8R and S8, the S6.
  character(len=3), parameter :: SURF_NAMES(NSURF) = ['bot', 'top', 'mid']
  character(len=15), parameter :: TENSOR_HEAD(NTENSOR) = ['             xx', '             yy', &
       '             zz', '             xy', '             xz', '             yz']

  type :: real_block_t
    !! One table of reals of a list of tables.
     real(wp), allocatable :: v(:, :, :)
  end type real_block_t

  type :: int_block_t
    !! One list of counts of a list of lists.
     integer, allocatable :: n(:)
  end type int_block_t

  public :: NTENSOR
  public :: nodal_stresses, write_point_stress_table, write_nodal_stress_table
  public :: fibre_stresses, write_fibre_stress_table, list_types

contains

  subroutine nodal_stresses(model, fields, is, isub, avg, nel, npoint)
    !! Nodal stresses of substructure isub in step is: avg(6, nnode, NSURF) the
    !! mean of the values extrapolated to the node by each plane or shell
    !! element of isub that has it, per section point (plane elements count on
    !! all three, thin shells count (bottom + top)/2 on the mid-surface),
    !! nel(nnode) how many (0: none, avg = 0), npoint(nnode) the section points
    !! worth reporting: 1 (plane elements only), 2 (bottom and top: a thin shell
    !! is among them) or 3 (bottom, top, mid-surface: a thick shell is).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    real(wp), allocatable, intent(out) :: avg(:, :, :)
    integer, allocatable, intent(out) :: nel(:)
    integer, allocatable, intent(out) :: npoint(:)
    real(wp), allocatable :: points(:, :, :), nodes(:, :, :)
    integer(ip) :: e, node
    integer :: a, k
    logical :: ok
    associate (sub => model%subs(isub))
      allocate (avg(NTENSOR, sub%nnode, NSURF), source=0.0_wp)
      allocate (nel(sub%nnode), source=0)
      allocate (npoint(sub%nnode), source=1)
      do e = 1, sub%nelem
         call element_stresses(model, fields, is, isub, e, points, nodes, ok)
         if (.not. ok) cycle
         do a = 1, size(nodes, 2)
            node = sub%elem_nodes(a, e)
            select case (size(nodes, 3))
            case (1)
               do k = 1, NSURF
                  avg(:, node, k) = avg(:, node, k) + nodes(:, a, 1)
               end do
            case (THIN_SURFACES)
               avg(:, node, 1:2) = avg(:, node, 1:2) + nodes(:, a, 1:2)
               avg(:, node, 3) = avg(:, node, 3) + 0.5_wp*(nodes(:, a, 1) + nodes(:, a, 2))
            case default
               avg(:, node, :) = avg(:, node, :) + nodes(:, a, :)
            end select
            nel(node) = nel(node) + 1
            npoint(node) = max(npoint(node), size(nodes, 3))
         end do
      end do
      do node = 1, sub%nnode
         if (nel(node) > 0) avg(:, node, :) = avg(:, node, :)/real(nel(node), wp)
      end do
    end associate
  end subroutine nodal_stresses

  pure function newer_family(model, subs, elems) result(yes)
    !! Per element of the list: a second-order plane element or a thick shell
    !! (their integration points get a note under the table's header).
    type(model_t), intent(in) :: model
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    logical :: yes(size(elems))
    type(element_traits_t) :: t
    integer :: i
    do i = 1, size(elems)
       t = element_traits(model%subs(subs(i))%elem_type(elems(i)))
       yes(i) = (t%family == FAMILY_PLANE .and. t%quadratic) .or. &
            (t%family == FAMILY_SHELL .and. t%shear_flexible .and. .not. t%quadratic)
    end do
  end function newer_family

  pure function is_s8r(model, subs, elems) result(yes)
    !! Per element of the list: an S8R (its points get a note under the table's header).
    type(model_t), intent(in) :: model
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    logical :: yes(size(elems))
    yes = is_eight_node_shell(list_types(model, subs, elems))
  end function is_s8r

  pure function list_types(model, subs, elems) result(types)
    !! The element type (ET_*) of each element of the list (elements elems of substructures subs).
    type(model_t), intent(in) :: model
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    integer :: types(size(elems))
    integer :: i
    do i = 1, size(elems)
       types(i) = model%subs(subs(i))%elem_type(elems(i))
    end do
  end function list_types

  pure function nodes_of_kind(model, subs, nodes, kind) result(yes)
    !! Per node of the list (of substructures subs): a node of an element with
    !! a section that is of kind SOLID_KIND, SHELL8_KIND (S8R, S8) or SHELL6_KIND (S6).
    type(model_t), intent(in) :: model
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    integer, intent(in) :: kind
    logical :: yes(size(nodes))
    logical, allocatable :: mask(:), pick(:)
    integer(ip) :: e
    integer :: isub, i
    yes = .false.
    do isub = 1, size(model%subs)
       if (.not. any(subs == isub)) cycle
       associate (sub => model%subs(isub))
         select case (kind)
         case (SOLID_KIND)
            pick = is_family(sub%elem_type, FAMILY_SOLID)
         case (SHELL8_KIND)
            pick = is_eight_node_shell(sub%elem_type)
         case default
            pick = is_six_node_shell(sub%elem_type)
         end select
         if (.not. any(pick)) cycle
         allocate (mask(sub%nnode), source=.false.)
         do e = 1, sub%nelem
            if (pick(e) .and. sub%elem_section(e) > 0) &
                 mask(sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e)) = .true.
         end do
         do i = 1, size(nodes)
            if (subs(i) == isub) yes(i) = mask(nodes(i))
         end do
         deallocate (mask)
       end associate
    end do
  end function nodes_of_kind

  elemental logical function is_eight_node_shell(etype)
    !! The S8R, S8: a quadrilateral shell with mid-side nodes.
    integer, intent(in) :: etype
    type(element_traits_t) :: t
    t = element_traits(etype)
    is_eight_node_shell = t%family == FAMILY_SHELL .and. t%quadratic .and. t%corners == 4
  end function is_eight_node_shell

  elemental logical function is_six_node_shell(etype)
    !! The S6: a triangular shell with mid-side nodes.
    integer, intent(in) :: etype
    type(element_traits_t) :: t
    t = element_traits(etype)
    is_six_node_shell = t%family == FAMILY_SHELL .and. t%quadratic .and. t%corners == 3
  end function is_six_node_shell

  pure function surface_label(nsurface, k) result(label)
    !! '-' for a plane element's single surface, 'bot' / 'top' / 'mid' for shells.
    integer, intent(in) :: nsurface, k
    character(len=3) :: label
    label = '  -'
    if (nsurface > 1) label = SURF_NAMES(k)
  end function surface_label

  subroutine write_point_stress_table(lu, model, fields, is, subs, elems)
    !! *EL PRINT S: the stresses at the integration points of the plane and
    !! shell elements among `elems` (nothing if there are none).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    type(real_block_t), allocatable :: vals(:)
    real(wp), allocatable :: nodes(:, :, :)
    logical, allocatable :: ok(:)
    character(len=200) :: hline
    real(wp) :: scale
    integer :: i, k, d, m
    allocate (vals(size(elems)), ok(size(elems)))
    scale = 0.0_wp
    do i = 1, size(elems)
       ok(i) = .not. is_family(model%subs(subs(i))%elem_type(elems(i)), FAMILY_SOLID)   ! their own table
       if (ok(i)) call element_stresses(model, fields, is, subs(i), elems(i), vals(i)%v, nodes, ok(i))
       if (ok(i)) scale = max(scale, maxval(abs(vals(i)%v)))
    end do
    if (.not. any(ok)) return
    call lu%line('    S   at the integration points of the plane and shell elements (global axes; CPS3/CPE3/S3: 1, '// &
         'the centroid; CPS4/CPE4/S4: 2x2 Gauss, point k next to node k; shells: bottom and top surface)')
    if (any(ok .and. newer_family(model, subs, elems))) call lu%line('    (CPS6/CPE6: 3 points, point k next '// &
         'to corner k; CPS8/CPE8: 3x3 Gauss, xi fastest from corner 1; CPS8R/CPE8R, S4R: 2x2 Gauss, point k next '// &
         'to node k; S3R: the centroid; S4R/S3R: bottom, top and mid-surface, xz/yz = 1.5 q/t at mid)')
    if (any(ok .and. is_s8r(model, subs, elems))) call lu%line('    (S8R: 2x2 Gauss of the reduced rule, point k '// &
         'next to corner k; bottom, top and mid-surface, xz/yz = 1.5 q/t at mid)')
    if (any(ok .and. is_six_node_shell(list_types(model, subs, elems)))) call lu%line('    (S6: 3 points (1/6, '// &
         '1/6), (2/3, 1/6), (1/6, 2/3), point k next to corner k; bottom, top and mid-surface, xz/yz = 1.5 q/t at mid)')
    write (hline, '(4x,a20,a10,a6,a4,a5,6a15)') 'substructure        ', '   element', '  type', '  ip', ' surf', &
         TENSOR_HEAD
    call lu%line(trim(hline))
    do i = 1, size(elems)
       if (.not. ok(i)) cycle
       do m = 1, size(vals(i)%v, 3)
          do k = 1, size(vals(i)%v, 2)
             call element_prefix(lu, model, subs(i), elems(i), 4)
             call lu%put_int(int(k, i8), 4)
             call lu%put('  '//surface_label(size(vals(i)%v, 3), m))
             do d = 1, NTENSOR
                call lu%put_es(chop(vals(i)%v(d, k, m), scale))
             end do
             call lu%newline()
          end do
       end do
    end do
  end subroutine write_point_stress_table

  subroutine write_nodal_stress_table(lu, model, fields, is, subs, nodes)
    !! *NODE PRINT S: the averaged nodal stresses of the requested nodes that
    !! belong to plane or shell elements (the others are counted in a note);
    !! nodes of shells get a row per surface.
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: nodes(:)
    type(real_block_t), allocatable :: avg(:)
    type(int_block_t), allocatable :: nel(:)
    type(int_block_t), allocatable :: npoint(:)
    logical, allocatable :: done(:), s8r(:), s6(:)
    character(len=200) :: hline
    real(wp) :: scale
    integer :: i, d, nskip, k, ns
    allocate (avg(size(model%subs)), nel(size(model%subs)), npoint(size(model%subs)))
    allocate (done(size(model%subs)), source=.false.)
    do i = 1, size(nodes)
       if (done(subs(i))) cycle
       call nodal_stresses(model, fields, is, subs(i), avg(subs(i))%v, nel(subs(i))%n, npoint(subs(i))%n)
       done(subs(i)) = .true.
    end do
    call lu%line('    S   nodal stresses: extrapolated from the integration points, averaged over the plane '// &
         'and shell elements of the substructure that share the node (global axes; shells: bottom and top surface)')
    s8r = nodes_of_kind(model, subs, nodes, SHELL8_KIND)
    s6 = nodes_of_kind(model, subs, nodes, SHELL6_KIND)
    if (any([(npoint(subs(i))%n(nodes(i)) == NSURF .and. .not. (s8r(i) .or. s6(i)), i=1, size(nodes))])) &
         call lu%line('    (nodes of S4R/S3R: '// &
         'also the mid-surface, with xz/yz = 1.5 q/t; thin shells count (bot + top)/2 there)')
    if (any(s8r)) call lu%line('    (nodes of S8R: also the '// &
         'mid-surface; corners extrapolated bilinearly from the 2x2 points, mid-side nodes the mean of their two corners)')
    if (any(s6)) call lu%line('    (nodes of S6: also the mid-surface; corners extrapolated linearly from the 3 '// &
         'points, mid-side nodes the mean of their two corners)')
    if (any(nodes_of_kind(model, subs, nodes, SOLID_KIND))) call lu%line('    (nodes of solid elements: the solids count among '// &
         'the elements averaged; each extrapolates from its integration points as CalculiX: 2x2x2 trilinear, C3D20 '// &
         'the least-squares fit of its 20-node field to its 27 points, C3D10 linear, C3D4 constant)')
    write (hline, '(4x,a20,a10,a6,a5,6a15)') 'substructure        ', '      node', ' elems', ' surf', TENSOR_HEAD
    call lu%line(trim(hline))
    scale = 0.0_wp
    do i = 1, size(nodes)
       if (nel(subs(i))%n(nodes(i)) > 0) scale = max(scale, maxval(abs(avg(subs(i))%v(:, nodes(i), :))))
    end do
    nskip = 0
    do i = 1, size(nodes)
       if (nel(subs(i))%n(nodes(i)) == 0) then
          nskip = nskip + 1
          cycle
       end if
       ns = npoint(subs(i))%n(nodes(i))
       do k = 1, ns
          call lu%put('    ')
          call lu%put_field(model%subs(subs(i))%name, 20)
          call lu%put_int(int(model%subs(subs(i))%node_id(nodes(i)), i8), 10)
          call lu%put_int(int(nel(subs(i))%n(nodes(i)), i8), 6)
          call lu%put('  '//surface_label(ns, k))
          do d = 1, NTENSOR
             call lu%put_es(chop(avg(subs(i))%v(d, nodes(i), k), scale))
          end do
          call lu%newline()
       end do
    end do
    if (nskip > 0) call lu%line('    ('//itoa(nskip)//' nodes of the set belong to no plane or shell element)')
  end subroutine write_nodal_stress_table

  subroutine fibre_stresses(model, fields, is, isub, ie, sig, n)
    !! Axial fibre stresses sig(point, end) of beam ie of substructure isub in
    !! step is at the n extreme points of its library section (n = 0: not a
    !! beam, or a section given by its constants only).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    real(wp), intent(out) :: sig(4, 2)
    integer, intent(out) :: n
    real(wp) :: sf(6), y, z
    type(element_traits_t) :: t
    integer(i8) :: iel
    integer :: k, ends
    sig = 0.0_wp
    n = 0
    associate (sub => model%subs(isub))
      t = element_traits(sub%elem_type(ie))
      if (t%family /= FAMILY_BEAM .or. t%quadratic) return   ! the two-node beams
      if (sub%elem_section(ie) <= 0) return
      associate (sec => sub%sections(sub%elem_section(ie)))
        n = sec%nfibre
        iel = fields%elem_offset(isub) + ie
        do ends = 1, 2
           sf = fields%elem_force(:, ends, iel, is)
           if (ends == 1) sf = -sf
           do k = 1, n
              y = sec%fibre(1, k)
              z = sec%fibre(2, k)
              sig(k, ends) = sf(1)/sec%area - sf(6)*y/sec%iz
              if (sec%iy > 0.0_wp) sig(k, ends) = sig(k, ends) + sf(5)*z/sec%iy
           end do
        end do
      end associate
    end associate
  end subroutine fibre_stresses

  subroutine write_fibre_stress_table(lu, model, fields, is, subs, elems)
    !! *EL PRINT S: the fibre stresses of the beams with a library section
    !! among `elems` (nothing if there are none).
    type(text_buffer_t), intent(inout) :: lu
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    integer, intent(in) :: subs(:)
    integer(ip), intent(in) :: elems(:)
    real(wp), allocatable :: sig(:, :, :)
    integer, allocatable :: n(:)
    character(len=200) :: hline
    real(wp) :: scale, ymax
    integer :: i, k, ends
    allocate (sig(4, 2, size(elems)), n(size(elems)))
    scale = 0.0_wp
    do i = 1, size(elems)
       call fibre_stresses(model, fields, is, subs(i), elems(i), sig(:, :, i), n(i))
       if (n(i) > 0) scale = max(scale, maxval(abs(sig(1:n(i), :, i))))
    end do
    if (all(n == 0)) return
    call lu%line('    S   beam fibre stresses sxx = N/A - Mz y/Iz + My z/Iy at the extreme points of the '// &
         'library sections (local y, z; section forces: see the user manual)')
    write (hline, '(4x,a20,a10,a6,a4,a6,3a15)') 'substructure        ', '   element', '  type', ' end', ' point', &
         '              y', '              z', '            sxx'
    call lu%line(trim(hline))
    do i = 1, size(elems)
       if (n(i) == 0) cycle
       associate (sec => model%subs(subs(i))%sections(model%subs(subs(i))%elem_section(elems(i))))
         ymax = maxval(abs(sec%fibre))
         do ends = 1, 2
            do k = 1, n(i)
               call element_prefix(lu, model, subs(i), elems(i), 4)
               call lu%put_int(int(ends, i8), 4)
               call lu%put_int(int(k, i8), 6)
               call lu%put_es(chop(sec%fibre(1, k), ymax))
               call lu%put_es(chop(sec%fibre(2, k), ymax))
               call lu%put_es(chop(sig(k, ends, i), scale))
               call lu%newline()
            end do
         end do
       end associate
    end do
  end subroutine write_fibre_stress_table
end module superjoin_output_stresses
