module superjoin_output_stresses
  !! Stresses of the plane elements (CPS3, CPS4, CPE3, CPE4) and of the shells
  !! (S3, S4: bottom and top surface, σ = n/t ∓ 6 m/t²) where benchmarks quote them: at the integration points (*EL PRINT S, as CalculiX's .dat)
  !! and at the nodes (*NODE PRINT S / *NODE FILE S): extrapolated from the
  !! integration points of each element (superjoin_elements_membrane,
  !! membrane_point_stresses; superjoin_elements_shell, shell_surface_stresses)
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
  use superjoin_model_types, only: model_t, ELEMENT_NODE_COUNT, ET_CPE3, ET_CPE4, ET_B23, ET_B33, ET_B21, ET_B31
  use superjoin_elements_shell, only: shell_frame, is_plane_type, is_plate_type, shell_surface_stresses
  use superjoin_elements_membrane, only: membrane_point_stresses
  use superjoin_analysis_results, only: result_fields_t
  use superjoin_output_energy, only: element_displacements
  use superjoin_output_text_buffer, only: text_buffer_t
  use superjoin_output_columns, only: element_prefix, chop
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  integer, parameter, public :: NTENSOR = 6
  integer, parameter, public :: NSURF = 2
    !! Surfaces of a shell: 1 bottom (z = -t/2), 2 top (z = +t/2, along the element normal).
  character(len=3), parameter :: SURF_NAMES(NSURF) = ['bot', 'top']
  character(len=15), parameter :: TENSOR_HEAD(NTENSOR) = ['             xx', '             yy', &
       '             zz', '             xy', '             xz', '             yz']

  type :: real_block_t
    !! One table of reals of a list of tables.
     real(wp), allocatable :: v(:, :, :)
  end type real_block_t

  type :: logical_block_t
    !! One list of flags of a list of lists.
     logical, allocatable :: b(:)
  end type logical_block_t

  type :: int_block_t
    !! One list of counts of a list of lists.
     integer, allocatable :: n(:)
  end type int_block_t

  public :: plane_stresses, nodal_stresses, write_point_stress_table, write_nodal_stress_table
  public :: fibre_stresses, write_fibre_stress_table

contains

  subroutine plane_stresses(model, fields, is, isub, ie, points, nodes, ok)
    !! Stress tensors of plane or shell element ie of substructure isub in
    !! step is: points(6, npoint, nsurf) at its integration points,
    !! nodes(6, nnode, nsurf) extrapolated to its nodes; nsurf = 1 for plane
    !! elements, 2 for shells (1: bottom surface z = -t/2, 2: top, z along the
    !! element normal). ok false (and empty arrays) for other element types or
    !! an element that cannot be evaluated.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    real(wp), allocatable, intent(out) :: points(:, :, :), nodes(:, :, :)
    logical, intent(out) :: ok
    real(wp) :: x(3, 4), r(3, 3), xl(2, 4), h(4), nu
    real(wp), allocatable :: ue(:), ul(:), sp(:, :), sn(:, :), sp3(:, :, :), sn3(:, :, :)
    type(error_t), allocatable :: error
    integer :: etype, nn, a, k
    logical :: strain
    ok = .false.
    allocate (points(NTENSOR, 0, 1), nodes(NTENSOR, 0, 1))
    associate (sub => model%subs(isub))
      etype = sub%elem_type(ie)
      if (.not. is_plate_type(etype) .or. sub%elem_section(ie) <= 0) return
      nn = ELEMENT_NODE_COUNT(etype)
      ! second-order plane elements (CPS6/CPS8/CPE6/CPE8...) have no integration-point table here
      if (nn > size(x, 2)) return
      do a = 1, nn
         x(:, a) = sub%x(:, sub%elem_nodes(a, ie))
      end do
      call element_displacements(model, fields, is, isub, ie, ue)
      strain = etype == ET_CPE3 .or. etype == ET_CPE4
      associate (sec => sub%sections(sub%elem_section(ie)), mat => model%materials(sub%sections(sub%elem_section(ie))%material))
        nu = mat%nu
        if (is_plane_type(etype)) then
           call shell_frame(x(:, 1:nn), r, xl(:, 1:nn), h(1:nn), error)
           if (allocated(error)) return
           allocate (ul(2*nn))
           do a = 1, nn
              ul(2*a - 1) = r(1, 1)*ue(2*a - 1) + r(1, 2)*ue(2*a)
              ul(2*a) = r(2, 1)*ue(2*a - 1) + r(2, 2)*ue(2*a)
           end do
           call membrane_point_stresses(xl(:, 1:nn), mat%e, mat%nu, strain, ul, sp, sn, error)
           if (allocated(error)) return
           sp3 = reshape(sp, [3, size(sp, 2), 1])
           sn3 = reshape(sn, [3, size(sn, 2), 1])
        else
           call shell_surface_stresses(x(:, 1:nn), sec, mat, ue, r, sp3, sn3, error)
           if (allocated(error)) return
        end if
      end associate
    end associate
    deallocate (points, nodes)
    allocate (points(NTENSOR, size(sp3, 2), size(sp3, 3)), nodes(NTENSOR, size(sn3, 2), size(sn3, 3)))
    do k = 1, size(sp3, 3)
       do a = 1, size(sp3, 2)
          points(:, a, k) = to_global(sp3(:, a, k))
       end do
       do a = 1, size(sn3, 2)
          nodes(:, a, k) = to_global(sn3(:, a, k))
       end do
    end do
    ok = .true.
  contains
    pure function to_global(s) result(t)
      !! (σx, σy, τxy) of the element frame as a global tensor, Voigt order.
      real(wp), intent(in) :: s(3)
      real(wp) :: t(NTENSOR)
      real(wp) :: m(3, 3), szz
      szz = 0.0_wp
      if (strain) szz = nu*(s(1) + s(2))
      m = s(1)*outer(r(1, :), r(1, :)) + s(2)*outer(r(2, :), r(2, :)) + &
           s(3)*(outer(r(1, :), r(2, :)) + outer(r(2, :), r(1, :))) + szz*outer(r(3, :), r(3, :))
      t = [m(1, 1), m(2, 2), m(3, 3), m(1, 2), m(1, 3), m(2, 3)]
    end function to_global
    pure function outer(p, q) result(o)
      real(wp), intent(in) :: p(3), q(3)
      real(wp) :: o(3, 3)
      o = spread(p, 2, 3)*spread(q, 1, 3)
    end function outer
  end subroutine plane_stresses

  subroutine nodal_stresses(model, fields, is, isub, avg, nel, shell)
    !! Nodal stresses of substructure isub in step is: avg(6, nnode, 2) the
    !! mean of the values extrapolated to the node by each plane or shell
    !! element of isub that has it, per surface (plane elements count on
    !! both), nel(nnode) how many (0: none, avg = 0), shell(nnode) whether a
    !! shell is among them (then the two surfaces differ).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    real(wp), allocatable, intent(out) :: avg(:, :, :)
    integer, allocatable, intent(out) :: nel(:)
    logical, allocatable, intent(out) :: shell(:)
    real(wp), allocatable :: points(:, :, :), nodes(:, :, :)
    integer(ip) :: e, node
    integer :: a, k
    logical :: ok
    associate (sub => model%subs(isub))
      allocate (avg(NTENSOR, sub%nnode, NSURF), source=0.0_wp)
      allocate (nel(sub%nnode), source=0)
      allocate (shell(sub%nnode), source=.false.)
      do e = 1, sub%nelem
         call plane_stresses(model, fields, is, isub, e, points, nodes, ok)
         if (.not. ok) cycle
         do a = 1, size(nodes, 2)
            node = sub%elem_nodes(a, e)
            do k = 1, NSURF
               avg(:, node, k) = avg(:, node, k) + nodes(:, a, min(k, size(nodes, 3)))
            end do
            nel(node) = nel(node) + 1
            if (size(nodes, 3) == NSURF) shell(node) = .true.
         end do
      end do
      do node = 1, sub%nnode
         if (nel(node) > 0) avg(:, node, :) = avg(:, node, :)/real(nel(node), wp)
      end do
    end associate
  end subroutine nodal_stresses

  pure function surface_label(nsurface, k) result(label)
    !! '-' for a plane element's single surface, 'bot' / 'top' for shells.
    integer, intent(in) :: nsurface, k
    character(len=3) :: label
    label = '  -'
    if (nsurface == NSURF) label = SURF_NAMES(k)
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
       call plane_stresses(model, fields, is, subs(i), elems(i), vals(i)%v, nodes, ok(i))
       if (ok(i)) scale = max(scale, maxval(abs(vals(i)%v)))
    end do
    if (.not. any(ok)) return
    call lu%line('    S   at the integration points of the plane and shell elements (global axes; CPS3/CPE3/S3: 1, '// &
         'the centroid; CPS4/CPE4/S4: 2x2 Gauss, point k next to node k; shells: bottom and top surface)')
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
    type(logical_block_t), allocatable :: shell(:)
    logical, allocatable :: done(:)
    character(len=200) :: hline
    real(wp) :: scale
    integer :: i, d, nskip, k, ns
    allocate (avg(size(model%subs)), nel(size(model%subs)), shell(size(model%subs)))
    allocate (done(size(model%subs)), source=.false.)
    do i = 1, size(nodes)
       if (done(subs(i))) cycle
       call nodal_stresses(model, fields, is, subs(i), avg(subs(i))%v, nel(subs(i))%n, shell(subs(i))%b)
       done(subs(i)) = .true.
    end do
    call lu%line('    S   nodal stresses: extrapolated from the integration points, averaged over the plane '// &
         'and shell elements of the substructure that share the node (global axes; shells: bottom and top surface)')
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
       ns = 1
       if (shell(subs(i))%b(nodes(i))) ns = NSURF
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
    integer(i8) :: iel
    integer :: k, ends
    sig = 0.0_wp
    n = 0
    associate (sub => model%subs(isub))
      select case (sub%elem_type(ie))
      case (ET_B23, ET_B33, ET_B21, ET_B31)
      case default
         return
      end select
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
