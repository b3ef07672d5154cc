module superjoin_assembly_dofs
  !! Active DOFs, physical DOF numbering and contact units.
  !!
  !! A contact unit is one contact element (or the supports of one node) restricted
  !! to one DOF block (translations 1-3 or rotations 4-6):
  !!     delta = qs (u_b(C) - u_a(C)),   delta_k with stiffness g_k, RIGID or free,
  !! where C are the global components it acts on and the rows of qs are the local
  !! components. Side a is the master node (or the ground), side b the slave node.
  use superjoin_kinds, only: wp, ip, i8
  use, intrinsic :: iso_fortran_env, only: int8
  use superjoin_error, only: error_t, add_error_line, EXIT_DECK
  use superjoin_model_types, only: model_t, frame_of_node, NDOF_NODE, LINK_NONE, LINK_FINITE, LINK_RIGID, &
       ELEMENT_NODE_COUNT, loc_text, node_label
  use superjoin_elements, only: element_dof_mask
  use superjoin_utils_sorting, only: sort_index
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory, BYTES_INT, BYTES_I8
  implicit none (type, external)
  private

  integer, parameter :: INITIAL_UNITS = 16   !! unit table slots before the first doubling

  interface grow
     !! Make room for element n + 1 of an allocatable array (grow_template.inc).
     module procedure grow_unit
  end interface grow

  integer, parameter, public :: NBLOCK = 2          !! translations, rotations
  integer, parameter, public :: BLOCK_SIZE = 3
  integer, parameter, public :: UNIT_LINK = 1, UNIT_SUPPORT = 2
  integer, parameter, public :: GROUND = 0          !! the ground vertex
  real(wp), parameter :: ORIENT_ZERO = 1.0e-12_wp
    !! Orientation entries below this are treated as exact zeros when deciding
    !! which global components an oriented contact couples.

  type, public :: unit_t
    !! One contact element (or the supports of one node) on one DOF block.
     integer :: block = 0                  !! 1: DOFs 1-3, 2: DOFs 4-6
     integer :: kind = 0                   !! UNIT_LINK or UNIT_SUPPORT
     integer :: source = 0                 !! link index (UNIT_LINK) or support index of its first DOF
     integer(i8) :: va = GROUND            !! vertex of side a (master; GROUND for supports)
     integer(i8) :: vb = 0                 !! vertex of side b (slave / supported node)
     integer :: n = 0                      !! number of components
     integer :: comp(BLOCK_SIZE) = 0       !! global components in the block (1..3)
     integer :: lcomp(BLOCK_SIZE) = 0      !! local components (1..3) of the rows of qs
     real(wp) :: qs(BLOCK_SIZE, BLOCK_SIZE) = 0.0_wp  !! (n, n) used
     integer :: state(BLOCK_SIZE) = LINK_NONE
     real(wp) :: g(BLOCK_SIZE) = 0.0_wp
     real(wp) :: value(BLOCK_SIZE) = 0.0_wp  !! prescribed delta of rigid components
     integer :: src(BLOCK_SIZE) = 0          !! support index per component (supports only)
     logical :: eccentric = .false.          !! OFFSET=RIGID translations: side b hangs on a rigid arm
     real(wp) :: arm(3) = 0.0_wp             !! r = x_b - x_a; delta = qs (u_b - u_a - theta_a x r)
  end type unit_t

  type, public :: equation_terms_t
    !! An *EQUATION on physical DOFs: sum_i a(i) u(p(i)) = 0, p(1) the dependent DOF.
     integer(i8), allocatable :: p(:)
     real(wp), allocatable :: a(:)
     integer :: source = 0                 !! index into model%equations
  end type equation_terms_t

  type, public :: dof_table_t
    !! Physical DOFs: every active (node, dof) pair, numbered node by node.
     integer(i8) :: nvertex = 0                !! nodes over all substructures
     integer(i8), allocatable :: vertex_offset(:)   !! (nsub+1): vertex = offset(sub) + node
     integer(i8) :: np = 0                     !! physical DOFs
     integer(i8), allocatable :: dof_block(:)  !! (0:(nvertex-1)/DOF_BLOCK) DOFs before a block's first vertex
     integer(int8), allocatable :: dof_off(:)  !! (nvertex) DOFs before the vertex in its block
     integer(int8), allocatable :: dof_mask(:) !! (nvertex) the vertex's DOFs: bit d-1 for DOF d
       !! A vertex's DOFs are consecutive, in DOF order: dof(d, v) reads them (about 2 bytes
       !! per vertex instead of a table of NDOF_NODE 8-byte indices).
     integer, allocatable :: p_sub(:)          !! (np) substructure of each physical DOF
     integer(ip), allocatable :: p_node(:)     !! (np) local node
     integer(int8), allocatable :: p_dof(:)    !! (np) DOF number 1..6
     type(unit_t), allocatable :: units(:)
     integer :: nunit = 0
     integer, allocatable :: ignored_links(:)  !! links with named DOFs that no node carries
     type(equation_terms_t), allocatable :: equations(:)  !! *EQUATION constraints (empty: none)
  contains
     procedure :: make_finite
     procedure :: dof => table_dof
  end type dof_table_t

  integer, parameter :: NMASK = 2**NDOF_NODE   !! DOF masks of a vertex: bit d-1 for DOF d
  integer, parameter :: DOF_SHIFT = 4           !! 2**DOF_SHIFT vertices per block of the DOF table
  integer, parameter :: DOF_BLOCK = 2**DOF_SHIFT !! (at most 15*NDOF_NODE DOFs before a vertex in its block)
  integer :: slot_d, slot_m                     !! the implied-do indices of SLOT (no other use)
  integer, parameter :: SLOT(NDOF_NODE, 0:NMASK - 1) = reshape([((merge(popcnt(ibits(slot_m, 0, slot_d - 1)) + 1, 0, &
       btest(slot_m, slot_d - 1)), slot_d = 1, NDOF_NODE), slot_m = 0, NMASK - 1)], [NDOF_NODE, NMASK])
    !! SLOT(d, mask): place of DOF d among the DOFs of a vertex with that mask (1 for its first), 0 if absent.

  integer, parameter, public :: MAX_UNIT_TERMS = 3*BLOCK_SIZE
    !! Physical DOFs one unit touches: side a, side b, and side a's rotations (arm).

  public :: refresh_link_springs, link_signature
  public :: build_dof_table, vertex_of, vertex_dofs, block_dof, unit_terms, unit_dofs, arm_matrix, unit_where, unit_nodes

contains

  pure function vertex_of(table, isub, inode) result(v)
    !! Vertex index of (substructure, local node).
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    integer(ip), intent(in) :: inode
    integer(i8) :: v
    v = table%vertex_offset(isub) + inode
  end function vertex_of

  elemental function table_dof(table, d, v) result(p)
    !! Physical index of DOF d (1..NDOF_NODE) of vertex v, 0 when the vertex has no such DOF.
    class(dof_table_t), intent(in) :: table
    integer, intent(in) :: d
    integer(i8), intent(in) :: v
    integer(i8) :: p
    integer :: k
    k = SLOT(d, int(table%dof_mask(v)))
    p = 0
    if (k > 0) p = table%dof_block(ishft(v - 1, -DOF_SHIFT)) + table%dof_off(v) + k
  end function table_dof

  pure subroutine vertex_dofs(table, v, p)
    !! The physical index of every DOF 1..NDOF_NODE of vertex v (0 where it has none):
    !! table%dof for a whole vertex, for loops over the vertices.
    type(dof_table_t), intent(in) :: table
    integer(i8), intent(in) :: v
    integer(i8), intent(out) :: p(NDOF_NODE)
    integer(i8) :: k
    integer :: d, m
    m = table%dof_mask(v)
    k = table%dof_block(ishft(v - 1, -DOF_SHIFT)) + table%dof_off(v)
    do d = 1, NDOF_NODE
       p(d) = 0
       if (btest(m, d - 1)) then
          k = k + 1
          p(d) = k
       end if
    end do
  end subroutine vertex_dofs

  subroutine make_finite(table, iu, c, g)
    !! Component c of contact unit iu becomes a finite spring of stiffness g
    !! (a RIGID one under PENALTY or RIGID=LARGE, analysis/policy).
    class(dof_table_t), intent(inout) :: table
    integer, intent(in) :: iu, c
    real(wp), intent(in) :: g
    table%units(iu)%g(c) = g
    table%units(iu)%state(c) = LINK_FINITE
  end subroutine make_finite

  elemental function block_dof(b, c) result(d)
    !! DOF number (1..6) of component c of block b.
    integer, intent(in) :: b, c
    integer :: d
    d = (b - 1)*BLOCK_SIZE + c
  end function block_dof

  subroutine build_dof_table(model, table, error)
    !! Activate DOFs, build contact units and number the physical DOFs.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(out) :: table
    type(error_t), allocatable, intent(out) :: error
    logical, allocatable :: has(:, :)        ! DOFs given by elements and supports
    integer :: isub
    integer(i8) :: v, p
    integer :: d, m, stat

    allocate (table%vertex_offset(size(model%subs) + 1))
    table%vertex_offset(1) = 0
    do isub = 1, size(model%subs)
       table%vertex_offset(isub + 1) = table%vertex_offset(isub) + model%subs(isub)%nnode
    end do
    table%nvertex = table%vertex_offset(size(model%subs) + 1)

    allocate (has(NDOF_NODE, table%nvertex), source=.false., stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the DOF table', NDOF_NODE*table%nvertex*BYTES_INT)
       return
    end if
    call activate_elements(model, table, has)
    call activate_given(model, table, has)
    call activate_supports(model, table, has)
    call activate_couplings(model, table, has)

    call build_link_units(model, table, has, error)
    call build_support_units(model, table, has, error)
    if (allocated(error)) return

    ! Unit components are active on both of their nodes.
    call activate_units(table, has)

    table%np = count(has, kind=i8)
    allocate (table%dof_block(0:(table%nvertex - 1)/DOF_BLOCK), table%dof_off(table%nvertex), &
         table%dof_mask(table%nvertex), stat=stat)
    if (stat == 0) allocate (table%p_sub(table%np), table%p_node(table%np), table%p_dof(table%np), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the DOF numbering', 3*table%nvertex + (table%nvertex/DOF_BLOCK + 1)*BYTES_I8 + &
            table%np*(2*BYTES_INT + 1))
       return
    end if
    p = 0
    do isub = 1, size(model%subs)
       do v = table%vertex_offset(isub) + 1, table%vertex_offset(isub + 1)
          if (mod(v - 1, int(DOF_BLOCK, i8)) == 0) table%dof_block(ishft(v - 1, -DOF_SHIFT)) = p
          table%dof_off(v) = int(p - table%dof_block(ishft(v - 1, -DOF_SHIFT)), int8)
          m = 0
          do d = 1, NDOF_NODE
             if (.not. has(d, v)) cycle
             m = ibset(m, d - 1)
             p = p + 1
             table%p_sub(p) = isub
             table%p_node(p) = int(v - table%vertex_offset(isub), ip)
             table%p_dof(p) = int(d, int8)
          end do
          table%dof_mask(v) = int(m, int8)
       end do
    end do
    call build_equation_terms(model, table, error)
  end subroutine build_dof_table

  pure function link_signature(model) result(sig)
    !! What shapes the links' units besides their finite g's: the state of
    !! every DOF of every link and whether its g is zero (link_unit). Two
    !! models with the same elements, supports and signature have DOF
    !! tables that differ only in the g's of their links' units.
    type(model_t), intent(in) :: model
    integer, allocatable :: sig(:, :)
    integer :: il
    allocate (sig(NDOF_NODE, size(model%links)))
    do il = 1, size(model%links)
       sig(:, il) = 2*model%links(il)%state + merge(1, 0, model%links(il)%g == 0.0_wp)
    end do
  end function link_signature

  subroutine refresh_link_springs(model, table)
    !! The g's of the links' units taken again from model (as link_unit
    !! takes them), for a table built from a model of the same
    !! link_signature: a joint study's next value.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    integer :: iu, k, d
    do iu = 1, table%nunit
       associate (u => table%units(iu))
         if (u%kind /= UNIT_LINK) cycle
         do k = 1, u%n
            d = block_dof(u%block, u%lcomp(k))
            u%state(k) = model%links(u%source)%state(d)
            u%g(k) = model%links(u%source)%g(d)
            if (u%state(k) == LINK_FINITE .and. u%g(k) == 0.0_wp) u%state(k) = LINK_NONE
         end do
       end associate
    end do
  end subroutine refresh_link_springs

  subroutine build_equation_terms(model, table, error)
    !! The *EQUATION terms on physical DOFs; a DOF that its node does not carry
    !! (no element or support gives it) is a deck error.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    type(error_t), allocatable, intent(inout) :: error
    integer :: ie, t, n
    n = 0
    if (allocated(model%equations)) n = size(model%equations)
    allocate (table%equations(n))
    do ie = 1, n
       associate (e => model%equations(ie), te => table%equations(ie))
         te%source = ie
         allocate (te%p(size(e%coef)), te%a(size(e%coef)))
         te%a = e%coef
         do t = 1, size(e%coef)
            te%p(t) = table%dof(e%dof(t), table%vertex_offset(e%sub(t)) + e%node(t))
            if (te%p(t) == 0) call add_error_line(error, EXIT_DECK, loc_text(model, e%loc)// &
                 ': error: *EQUATION: node '//node_label(model, e%sub(t), e%node(t))//' has no DOF '// &
                 itoa(e%dof(t))//' (no element or support of that node carries it)')
         end do
       end associate
    end do
  end subroutine build_equation_terms

  subroutine activate_elements(model, table, has)
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(inout) :: has(:, :)
    integer :: isub, k
    integer(ip) :: e
    integer(i8) :: v
    logical :: mask(NDOF_NODE)
    do isub = 1, size(model%subs)
       associate (s => model%subs(isub))
         do e = 1, s%nelem
            mask = element_dof_mask(s%elem_type(e))
            do k = 1, ELEMENT_NODE_COUNT(s%elem_type(e))
               v = table%vertex_offset(isub) + s%elem_nodes(k, e)
               has(:, v) = has(:, v) .or. mask
            end do
         end do
       end associate
    end do
  end subroutine activate_elements

  subroutine activate_given(model, table, has)
    !! The DOFs of a stiffness given by *MATRIX INPUT are active on its nodes.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(inout) :: has(:, :)
    integer :: isub, r
    do isub = 1, size(model%subs)
       if (.not. allocated(model%subs(isub)%given)) cycle
       associate (g => model%subs(isub)%given)
         do r = 1, size(g%dof)
            has(g%dof(r), table%vertex_offset(isub) + g%node(r)) = .true.
         end do
       end associate
    end do
  end subroutine activate_given

  subroutine activate_supports(model, table, has)
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(inout) :: has(:, :)
    integer :: i
    do i = 1, size(model%supports)
       associate (sp => model%supports(i))
         has(sp%dof, table%vertex_offset(sp%sub) + sp%node) = .true.
       end associate
    end do
  end subroutine activate_supports

  subroutine activate_couplings(model, table, has)
    !! The DOFs of coupling constraints are active (a reference node's rotations).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    logical, intent(inout) :: has(:, :)
    integer :: i, t
    if (.not. allocated(model%equations)) return
    do i = 1, size(model%equations)
       associate (e => model%equations(i))
         if (.not. e%coupling) cycle
         do t = 1, size(e%coef)
            has(e%dof(t), table%vertex_offset(e%sub(t)) + e%node(t)) = .true.
         end do
       end associate
    end do
  end subroutine activate_couplings

  subroutine activate_units(table, has)
    type(dof_table_t), intent(in) :: table
    logical, intent(inout) :: has(:, :)
    integer :: i, c
    do i = 1, table%nunit
       associate (u => table%units(i))
         do c = 1, u%n
            if (u%va /= GROUND) has(block_dof(u%block, u%comp(c)), u%va) = .true.
            has(block_dof(u%block, u%comp(c)), u%vb) = .true.
         end do
       end associate
    end do
  end subroutine activate_units

  subroutine build_link_units(model, table, has, error)
    !! One unit per link and block with any connected DOF that a node carries.
    !! The translations of an OFFSET=RIGID contact carry the arm x_slave - x_master.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    logical, intent(in) :: has(:, :)
    type(error_t), allocatable, intent(inout) :: error
    integer :: il, b
    integer(i8) :: va, vb
    type(unit_t) :: u
    logical :: ignored
    real(wp) :: q(3, 3)
    integer, allocatable :: ign(:)
    integer :: nign

    allocate (table%units(max(INITIAL_UNITS, 2*size(model%links) + size(model%supports))))
    allocate (ign(size(model%links)))
    nign = 0
    do il = 1, size(model%links)
       associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
         va = table%vertex_offset(ct%master_sub) + lk%master_node
         vb = table%vertex_offset(ct%slave_sub) + lk%slave_node
         if (lk%has_q) then
            q = lk%q
         else if (ct%orientation > 0) then
            q = model%orientations(ct%orientation)%q
         else
            q = 0.0_wp
            q(1, 1) = 1.0_wp; q(2, 2) = 1.0_wp; q(3, 3) = 1.0_wp
         end if
         ignored = .false.
         do b = 1, NBLOCK
            call link_unit(lk%state((b - 1)*3 + 1:b*3), lk%g((b - 1)*3 + 1:b*3), q, &
                 has((b - 1)*3 + 1:b*3, va) .or. has((b - 1)*3 + 1:b*3, vb), u, ignored)
            if (u%n == 0) cycle
            u%block = b
            u%kind = UNIT_LINK
            u%source = il
            u%va = va
            u%vb = vb
            if (b == 1 .and. ct%rigid_offset) then
               call set_arm(model, il, has(4:6, va), u, error)
            end if
            call push_unit(table, u)
         end do
         if (ignored) then
            nign = nign + 1
            ign(nign) = il
         end if
       end associate
    end do
    table%ignored_links = ign(1:nign)
  end subroutine build_link_units

  subroutine set_arm(model, il, rot, u, error)
    !! Arm of the translation unit of OFFSET=RIGID link il; the master must carry
    !! every rotation the arm couples (rot: its rotational DOFs 4-6).
    type(model_t), intent(in) :: model
    integer, intent(in) :: il
    logical, intent(in) :: rot(3)
    type(unit_t), intent(inout) :: u
    type(error_t), allocatable, intent(inout) :: error
    real(wp) :: a(3, 3)
    integer :: c, d
    logical :: need(3)
    associate (lk => model%links(il), ct => model%contacts(model%links(il)%contact))
      u%eccentric = .true.
      u%arm = model%subs(ct%slave_sub)%x(:, lk%slave_node) - model%subs(ct%master_sub)%x(:, lk%master_node)
      a = arm_matrix(u%arm)
      need = .false.
      do d = 1, 3
         do c = 1, u%n
            if (a(u%comp(c), d) /= 0.0_wp) need(d) = .true.
         end do
      end do
      if (.not. any(rot) .or. any(need .and. .not. rot)) then
         call add_error_line(error, EXIT_DECK, loc_text(model, lk%loc)//': error: contact '//ct%name// &
              ', OFFSET=RIGID: master node '//node_label(model, ct%master_sub, lk%master_node)// &
              ' has no rotational DOFs to carry the rigid arm to slave node '// &
              node_label(model, ct%slave_sub, lk%slave_node)//' (join it to a beam or shell node)')
      end if
    end associate
  end subroutine set_arm

  pure function arm_matrix(r) result(a)
    !! A with (theta x r)_c = sum_d A(c, d) theta_d.
    real(wp), intent(in) :: r(3)
    real(wp) :: a(3, 3)
    a = 0.0_wp
    a(1, 2) = r(3)
    a(1, 3) = -r(2)
    a(2, 1) = -r(3)
    a(2, 3) = r(1)
    a(3, 1) = r(2)
    a(3, 2) = -r(1)
  end function arm_matrix

  pure subroutine unit_terms(table, u, k, p, w, n)
    !! delta_k of unit u as a linear form of physical DOFs: delta_k = sum_i w(i) u(p(i)) - value(k),
    !! side a first, then side b, then side a's rotations (eccentric units).
    type(dof_table_t), intent(in) :: table
    type(unit_t), intent(in) :: u
    integer, intent(in) :: k
    integer(i8), intent(out) :: p(MAX_UNIT_TERMS)
    real(wp), intent(out) :: w(MAX_UNIT_TERMS)
    integer, intent(out) :: n
    real(wp) :: a(3, 3), t
    integer :: c, d
    n = 0
    if (u%va /= GROUND) then
       do c = 1, u%n
          n = n + 1
          p(n) = table%dof(block_dof(u%block, u%comp(c)), u%va)
          w(n) = -u%qs(k, c)
       end do
    end if
    do c = 1, u%n
       n = n + 1
       p(n) = table%dof(block_dof(u%block, u%comp(c)), u%vb)
       w(n) = u%qs(k, c)
    end do
    if (.not. u%eccentric) return
    a = arm_matrix(u%arm)
    do d = 1, 3
       if (table%dof(3 + d, u%va) == 0) cycle
       t = 0.0_wp
       do c = 1, u%n
          t = t + u%qs(k, c)*a(u%comp(c), d)
       end do
       n = n + 1
       p(n) = table%dof(3 + d, u%va)
       w(n) = -t
    end do
  end subroutine unit_terms

  pure subroutine unit_dofs(table, u, p, n)
    !! The physical DOFs unit u touches, in unit_terms order.
    type(dof_table_t), intent(in) :: table
    type(unit_t), intent(in) :: u
    integer(i8), intent(out) :: p(MAX_UNIT_TERMS)
    integer, intent(out) :: n
    real(wp) :: w(MAX_UNIT_TERMS)
    call unit_terms(table, u, 1, p, w, n)
  end subroutine unit_dofs

  subroutine link_unit(state, g, q, present, u, ignored)
    !! Components of one link on one block. `present(c)` tells whether either node
    !! carries global component c from an element or a support.
    integer, intent(in) :: state(3)
    real(wp), intent(in) :: g(3), q(3, 3)
    logical, intent(in) :: present(3)
    type(unit_t), intent(out) :: u
    logical, intent(inout) :: ignored
    logical :: named(3), inc(3), rowin(3)
    integer :: k, c, nk, nc
    integer :: ks(3), cs(3)
    real(wp) :: scale

    named = state /= LINK_NONE
    u%n = 0
    if (.not. any(named)) return
    ! Global components coupled by the named local components.
    inc = .false.
    do k = 1, 3
       if (.not. named(k)) cycle
       scale = maxval(abs(q(k, :)))
       do c = 1, 3
          if (abs(q(k, c)) > ORIENT_ZERO*scale) inc(c) = .true.
       end do
    end do
    ! A component that neither node carries is not connected.
    if (any(inc .and. .not. present)) ignored = .true.
    inc = inc .and. present
    if (.not. any(inc)) return
    ! Local components whose axis lies within the included global components.
    do k = 1, 3
       rowin(k) = all(abs(q(k, :)) <= ORIENT_ZERO*maxval(abs(q(k, :))) .or. inc)
    end do
    if (count(rowin) /= count(inc)) then
       ! Oblique frame: the unit acts on the whole block.
       inc = .true.
       rowin = .true.
    end if
    nc = 0
    do c = 1, 3
       if (inc(c)) then
          nc = nc + 1
          cs(nc) = c
       end if
    end do
    nk = 0
    do k = 1, 3
       if (rowin(k)) then
          nk = nk + 1
          ks(nk) = k
       end if
    end do
    u%n = nc
    u%comp(1:nc) = cs(1:nc)
    u%lcomp(1:nk) = ks(1:nk)
    do k = 1, nk
       do c = 1, nc
          u%qs(k, c) = q(ks(k), cs(c))
       end do
       u%state(k) = state(ks(k))
       u%g(k) = g(ks(k))
       if (u%state(k) == LINK_FINITE .and. u%g(k) == 0.0_wp) u%state(k) = LINK_NONE
    end do
  end subroutine link_unit

  subroutine build_support_units(model, table, has, error)
    !! Merge the supports per node and DOF (finite g add up, RIGID wins, two
    !! RIGID values must agree) into one unit per node and block. The DOFs of a
    !! node with a nodal system (*TRANSFORM) are in that system.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    logical, intent(in) :: has(:, :)
    type(error_t), allocatable, intent(inout) :: error
    integer(i8), allocatable :: key(:)
    integer, allocatable :: order(:)
    integer :: i, j, n, c, b
    integer(i8) :: v, vprev
    integer :: bprev
    type(unit_t) :: u
    real(wp), parameter :: VALUE_TOL = 1.0e-12_wp

    n = size(model%supports)
    if (n == 0) return
    allocate (key(n), order(n))
    do i = 1, n
       associate (sp => model%supports(i))
         v = table%vertex_offset(sp%sub) + sp%node
         key(i) = v*NDOF_NODE + (sp%dof - 1)
       end associate
       order(i) = i
    end do
    call sort_index(key, order)

    vprev = -1
    bprev = 0
    u%n = 0
    do j = 1, n
       i = order(j)
       associate (sp => model%supports(i))
         v = table%vertex_offset(sp%sub) + sp%node
         b = (sp%dof - 1)/3 + 1
         c = sp%dof - (b - 1)*3
         if (v /= vprev .or. b /= bprev) then
            if (u%n > 0) call push_support_unit(model, table, has, u, error)
            u = unit_t()
            u%block = b
            u%kind = UNIT_SUPPORT
            u%source = i
            u%va = GROUND
            u%vb = v
            vprev = v
            bprev = b
         end if
         if (u%n == 0 .or. u%comp(max(u%n, 1)) /= c) then
            u%n = u%n + 1
            u%comp(u%n) = c
            u%lcomp(u%n) = c
            u%qs(u%n, u%n) = 1.0_wp
            u%src(u%n) = i
         end if
         select case (sp%state)
         case (LINK_RIGID)
            if (u%state(u%n) == LINK_RIGID) then
               if (abs(u%value(u%n) - sp%value) > VALUE_TOL*max(abs(sp%value), abs(u%value(u%n)))) then
                  call add_error_line(error, EXIT_DECK, loc_text(model, sp%loc)//': error: node '// &
                       node_label(model, sp%sub, sp%node)//' DOF '//itoa(sp%dof)// &
                       ' has two rigid supports with different prescribed values (other at '// &
                       loc_text(model, model%supports(u%src(u%n))%loc)//')')
               end if
            else
               u%state(u%n) = LINK_RIGID
               u%value(u%n) = sp%value
               u%g(u%n) = 0.0_wp
               u%src(u%n) = i
            end if
         case (LINK_FINITE)
            if (u%state(u%n) /= LINK_RIGID .and. sp%g > 0.0_wp) then
               u%state(u%n) = LINK_FINITE
               u%g(u%n) = u%g(u%n) + sp%g
            end if
         end select
       end associate
    end do
    if (u%n > 0) call push_support_unit(model, table, has, u, error)
  end subroutine build_support_units

  subroutine push_support_unit(model, table, has, u, error)
    !! Push a support unit; on a node with a nodal system its components are
    !! local axes: the unit becomes delta = Q u over the global components they
    !! couple (an oblique support, free local components as free delta).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    logical, intent(in) :: has(:, :)
    type(unit_t), intent(in) :: u
    type(error_t), allocatable, intent(inout) :: error
    type(unit_t) :: w
    integer :: f, isub, i, k, state(3), src(3)
    real(wp) :: g(3), value(3)
    logical :: ignored
    integer(ip) :: node

    isub = 1
    do while (u%vb > table%vertex_offset(isub + 1))
       isub = isub + 1
    end do
    node = int(u%vb - table%vertex_offset(isub), ip)
    f = frame_of_node(model, isub, node)
    if (f == 0) then
       call push_unit(table, u)
       return
    end if
    state = LINK_NONE
    g = 0.0_wp
    value = 0.0_wp
    src = 0
    do i = 1, u%n
       state(u%comp(i)) = u%state(i)
       g(u%comp(i)) = u%g(i)
       value(u%comp(i)) = u%value(i)
       src(u%comp(i)) = u%src(i)
    end do
    ignored = .false.
    call link_unit(state, g, model%frames(f)%q, has((u%block - 1)*3 + 1:u%block*3, u%vb), w, ignored)
    if (ignored) then
       call add_error_line(error, EXIT_DECK, loc_text(model, model%supports(u%source)%loc)// &
            ': error: node '//node_label(model, isub, node)//': its nodal system (*TRANSFORM at '// &
            loc_text(model, model%frames(f)%loc)//') turns a supported DOF onto a global DOF the node '// &
            'does not carry')
       return
    end if
    if (w%n == 0) return
    w%block = u%block
    w%kind = UNIT_SUPPORT
    w%source = u%source
    w%va = GROUND
    w%vb = u%vb
    do k = 1, w%n
       w%value(k) = value(w%lcomp(k))
       w%src(k) = src(w%lcomp(k))
       if (w%src(k) == 0) w%src(k) = u%source
    end do
    call push_unit(table, w)
  end subroutine push_support_unit

  subroutine push_unit(table, u)
    type(dof_table_t), intent(inout) :: table
    type(unit_t), intent(in) :: u
    call grow(table%units, table%nunit, INITIAL_UNITS)
    table%nunit = table%nunit + 1
    table%units(table%nunit) = u
  end subroutine push_unit
  function unit_where(model, u) result(text)
    !! file:line of the card that defined a unit.
    type(model_t), intent(in) :: model
    type(unit_t), intent(in) :: u
    character(:), allocatable :: text
    if (u%kind == UNIT_LINK) then
       text = loc_text(model, model%links(u%source)%loc)
    else
       text = loc_text(model, model%supports(u%source)%loc)
    end if
  end function unit_where

  function unit_nodes(model, table, u, k) result(text)
    !! "SUB.id - SUB.id DOF d" (or "SUB.id DOF d" for a support) of component k of a unit.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(unit_t), intent(in) :: u
    integer, intent(in) :: k
    character(:), allocatable :: text
    character(len=12) :: buf
    write (buf, '(i0)') block_dof(u%block, u%lcomp(k))
    text = vertex_name(u%vb)//' DOF '//trim(buf)
    if (u%va /= GROUND) text = vertex_name(u%va)//' - '//text
  contains
    function vertex_name(v) result(name)
      integer(i8), intent(in) :: v
      character(:), allocatable :: name
      integer :: isub
      do isub = 1, size(model%subs)
         if (v <= table%vertex_offset(isub + 1)) exit
      end do
      name = node_label(model, isub, int(v - table%vertex_offset(isub), kind(model%subs(1)%nnode)))
    end function vertex_name
  end function unit_nodes

  ! ------------------------------------------------------------------ growing arrays

#define GROW_NAME grow_unit
#define GROW_TYPE type(unit_t)
#include "grow_template.inc"

end module superjoin_assembly_dofs
