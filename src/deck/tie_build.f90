module superjoin_deck_tie_build
  !! Validation side of `*TIE`: each slave node (of a node surface, or the
  !! nodes of the faces of an element surface) is tied to the master face
  !! nearest to it, if that face lies within the POSITION TOLERANCE, by three
  !! exact constraint equations (DOFs 1, 2, 3)
  !!     u_slave = Σ_k N_k(ξ) u_k,
  !! N_k the master face's shape functions at the slave node's projection ξ
  !! (superjoin_elements_face_projection). They are appended to
  !! model%equations with their tie's number and eliminated by the transform
  !! like *EQUATION. As CalculiX's gentiedmpc:
  !! - the default tolerance (POSITION TOLERANCE absent or 0) is 2.5 % of a
  !!   typical master face size (here: the mean of area / half perimeter);
  !! - a slave node farther than the tolerance from every master face is not
  !!   tied (the listing's note counts them and names the first);
  !! - ADJUST=YES (the default) moves each tied slave node onto its projection
  !!   (an instance with a moved node is no longer a copy of its part: it
  !!   shares no condensation with the part's other instances);
  !! - a slave DOF that is already dependent gets no tie equation: here an
  !!   *EQUATION's dependent DOF or an earlier tie's slave DOF (dropped at
  !!   reading, counted in the note), and a DOF that a support or a contact
  !!   makes dependent (dropped by the transform, in the steps where it is).
  !! A slave node that is itself a node of the master surface is left as it is
  !! (it already belongs to both sides).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: model_t, source_loc_t, equation_t, node_label, DLOAD_P, DLOAD_P1, DLOAD_P4, &
       DLOAD_P5, DLOAD_P6, ELEMENT_TYPE_NAMES
  use superjoin_model_notes, only: note
  use superjoin_elements_face_projection, only: element_face_nodes, project_to_face, face_point_t, face_size
  use superjoin_deck_state, only: deck_state_t, report_loc, surface_b_t, tie_b_t
  use superjoin_deck_build_common, only: resolve_items, resolve_sub
  use superjoin_utils_strings, only: itoa, rtoa
  use superjoin_deck_lexer, only: plural
  implicit none (type, external)
  private

  public :: build_ties

  type :: master_face_t
    !! One face of the master surface.
     integer :: sub = 0
     integer :: nc = 0                       !! corners (3 or 4)
     integer(ip), allocatable :: nodes(:)    !! local nodes of sub, corners first
     real(wp) :: lo(3) = 0.0_wp, hi(3) = 0.0_wp   !! bounding box
  end type master_face_t

  type :: face_grid_t
    !! The master faces by cell of a uniform grid (the search for a slave node's face).
     real(wp) :: lo(3) = 0.0_wp, hi(3) = 0.0_wp   !! the grid's box
     real(wp) :: h = 1.0_wp                  !! cell size
     integer :: n(3) = 1                     !! cells per axis
     integer, allocatable :: start(:)        !! faces of cell c: list(start(c):start(c+1)-1)
     integer, allocatable :: list(:)
     real(wp), allocatable :: margin(:)      !! per face: how far its box is grown
  end type face_grid_t

  type :: node_mask_t
    !! One flag per (DOF 1..3, node) of a substructure.
     logical, allocatable :: m(:, :)
  end type node_mask_t

  type :: tie_tally_t
    !! What one tie did, for the listing's note.
     integer :: slaves = 0, tied = 0, far = 0, shared = 0, dropped = 0, moved = 0
     real(wp) :: max_move = 0.0_wp
     character(:), allocatable :: first_far
  end type tie_tally_t

  type :: tie_job_t
    !! The tie being resolved.
     integer :: tie = 0                      !! its number (equation_t%tie)
     real(wp) :: tol = 0.0_wp                !! its position tolerance (a length)
     logical :: adjust = .true.              !! ADJUST=YES
     type(source_loc_t) :: loc               !! its *TIE card
  end type tie_job_t

  real(wp), parameter :: DEFAULT_TOL_FRACTION = 0.025_wp
    !! CalculiX: the default POSITION TOLERANCE is 2.5 % of a typical element size

contains

  subroutine build_ties(st, model)
    !! Append the constraint equations of every *TIE to model%equations (after
    !! the *EQUATION ones) and note per tie what it tied.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(inout) :: model
    type(node_mask_t), allocatable :: dep(:), on_master(:)
    type(master_face_t), allocatable :: faces(:)
    type(equation_t), allocatable :: eqs(:)
    integer, allocatable :: ssub(:)
    integer(ip), allocatable :: snode(:)
    type(tie_tally_t) :: tally
    integer :: it, is, im, neq
    real(wp) :: tol
    logical :: ok
    if (.not. allocated(st%ties)) return
    if (size(st%ties) == 0) return
    if (.not. allocated(model%equations)) allocate (model%equations(0))
    call dependent_dofs(model, dep)
    allocate (eqs(0))
    neq = 0
    do it = 1, size(st%ties)
       associate (tie => st%ties(it))
         if (.not. tie%has_line) then
            call report_loc(st, tie%loc, '*TIE needs a data line: slave surface, master surface')
            cycle
         end if
         if (len(tie%slave) == 0) cycle
         is = surface_index(st, tie%slave, tie%line_loc, 'slave')
         im = surface_index(st, tie%master, tie%line_loc, 'master')
         if (is == 0 .or. im == 0) cycle
         if (st%surfaces(im)%nodal) then
            call report_loc(st, tie%line_loc, '*TIE: the master surface '//tie%master//' is a node surface '// &
                 '(TYPE=NODE): the master side must be element faces (*SURFACE, TYPE=ELEMENT)')
            cycle
         end if
         call master_faces(st, model, st%surfaces(im), faces, on_master, ok)
         if (.not. ok) cycle
         call slave_nodes(st, model, st%surfaces(is), ssub, snode, ok)
         if (.not. ok) cycle
         tol = tie%tolerance
         if (tol <= 0.0_wp) tol = default_tolerance(model, faces)
         tally = tie_tally_t()
         call tie_nodes(model, faces, on_master, tie_job_t(it, tol, tie%adjust, tie%loc), ssub, snode, dep, eqs, neq, tally)
         call note(model%notes, tie_note(tie, tol, size(faces), tally))
       end associate
    end do
    model%equations = [model%equations, eqs(1:neq)]
  end subroutine build_ties

  integer function surface_index(st, name, loc, side) result(k)
    !! The *SURFACE called name (0, reported, if none).
    type(deck_state_t), intent(inout) :: st
    character(*), intent(in) :: name, side
    type(source_loc_t), intent(in) :: loc
    do k = 1, st%nsurface
       if (st%surfaces(k)%name == name) return
    end do
    k = 0
    call report_loc(st, loc, '*TIE: unknown '//side//' surface '''//name//''' (define it with *SURFACE)')
  end function surface_index

  subroutine dependent_dofs(model, dep)
    !! The DOFs 1..3 that the *EQUATION cards already make dependent.
    type(model_t), intent(in) :: model
    type(node_mask_t), allocatable, intent(out) :: dep(:)
    integer :: k
    call new_masks(model, 3, dep)
    do k = 1, size(model%equations)
       associate (e => model%equations(k))
         if (e%dof(1) <= 3) dep(e%sub(1))%m(e%dof(1), e%node(1)) = .true.
       end associate
    end do
  end subroutine dependent_dofs

  subroutine new_masks(model, rows, masks)
    !! One mask (rows, nnode) per substructure, all false.
    type(model_t), intent(in) :: model
    integer, intent(in) :: rows
    type(node_mask_t), allocatable, intent(out) :: masks(:)
    integer :: k
    allocate (masks(size(model%subs)))
    do k = 1, size(model%subs)
       allocate (masks(k)%m(rows, model%subs(k)%nnode), source=.false.)
    end do
  end subroutine new_masks

  subroutine surface_items(st, model, sf, i, isub, items, ok)
    !! The substructure and the local elements (nodes: TYPE=NODE) of data line i of a surface.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(surface_b_t), intent(in) :: sf
    integer, intent(in) :: i
    integer, intent(out) :: isub
    integer(ip), allocatable, intent(out) :: items(:)
    logical, intent(out) :: ok
    ok = .false.
    isub = resolve_sub(st, model, sf%refs(i), sf%loc, trim(merge('node   ', 'element', sf%nodal)))
    if (isub == 0) return
    call resolve_items(st, model, isub, sf%refs(i), .not. sf%nodal, sf%loc, items, ok)
  end subroutine surface_items

  pure integer function face_of_kind(kind) result(face)
    !! The face number of a *SURFACE line's load form: S1..S6 of a solid (DLOAD_P1..P6),
    !! 0 for the face of a shell (DLOAD_P, SPOS or SNEG).
    integer, intent(in) :: kind
    face = 0
    if (kind >= DLOAD_P1 .and. kind <= DLOAD_P4) face = kind - DLOAD_P1 + 1
    if (kind == DLOAD_P5) face = 5
    if (kind == DLOAD_P6) face = 6
    if (kind == DLOAD_P) face = 0
  end function face_of_kind

  subroutine master_faces(st, model, sf, faces, on_face, ok)
    !! The faces of an element surface, and which nodes lie on them.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(surface_b_t), intent(in) :: sf
    type(master_face_t), allocatable, intent(out) :: faces(:)
    type(node_mask_t), allocatable, intent(out) :: on_face(:)
    logical, intent(out) :: ok
    integer(ip), allocatable :: items(:)
    integer, allocatable :: local(:)
    integer :: i, j, isub, nc, n
    logical :: good
    allocate (faces(16))
    call new_masks(model, 1, on_face)
    ok = .true.
    n = 0
    do i = 1, sf%n
       call surface_items(st, model, sf, i, isub, items, good)
       ok = ok .and. good
       if (.not. good) cycle
       associate (sub => model%subs(isub))
         do j = 1, size(items)
            call element_face_nodes(sub%elem_type(items(j)), face_of_kind(sf%kinds(i)), local, nc)
            if (nc == 0) then
               call report_loc(st, sf%loc, '*SURFACE '//sf%name//': element '//itoa(sub%elem_id(items(j)))// &
                    ' ('//trim(ELEMENT_TYPE_NAMES(sub%elem_type(items(j))))//') has no face a *TIE can use '// &
                    '(S1 to S6 of a solid, SPOS or SNEG of a shell)')
               ok = .false.
               exit
            end if
            if (any(sub%elem_nodes(local, items(j)) < 1)) then   ! an undefined node, reported
               ok = .false.
               cycle
            end if
            if (n == size(faces)) call grow_faces(faces)
            n = n + 1
            faces(n)%sub = isub
            faces(n)%nc = nc
            faces(n)%nodes = sub%elem_nodes(local, items(j))
            faces(n)%lo = minval(sub%x(:, faces(n)%nodes), 2)
            faces(n)%hi = maxval(sub%x(:, faces(n)%nodes), 2)
            on_face(isub)%m(1, faces(n)%nodes) = .true.
         end do
       end associate
    end do
    faces = faces(1:n)
  end subroutine master_faces

  subroutine grow_faces(faces)
    !! Twice the room, the faces moved (not copied).
    type(master_face_t), allocatable, intent(inout) :: faces(:)
    type(master_face_t), allocatable :: tmp(:)
    integer :: k
    allocate (tmp(2*size(faces)))
    do k = 1, size(faces)
       tmp(k)%sub = faces(k)%sub
       tmp(k)%nc = faces(k)%nc
       tmp(k)%lo = faces(k)%lo
       tmp(k)%hi = faces(k)%hi
       call move_alloc(faces(k)%nodes, tmp(k)%nodes)
    end do
    call move_alloc(tmp, faces)
  end subroutine grow_faces

  subroutine slave_nodes(st, model, sf, ssub, snode, ok)
    !! The nodes of the slave surface, each once, in order of appearance: its
    !! nodes and node sets (TYPE=NODE) or the nodes of its faces.
    type(deck_state_t), intent(inout) :: st
    type(model_t), intent(in) :: model
    type(surface_b_t), intent(in) :: sf
    integer, allocatable, intent(out) :: ssub(:)
    integer(ip), allocatable, intent(out) :: snode(:)
    logical, intent(out) :: ok
    type(master_face_t), allocatable :: faces(:)
    type(node_mask_t), allocatable :: on_face(:), taken(:)
    integer(ip), allocatable :: items(:)
    integer :: i, k, isub, n
    logical :: good
    call new_masks(model, 1, taken)
    n = sum([(int(model%subs(k)%nnode), k = 1, size(model%subs))])
    allocate (ssub(n), snode(n))
    n = 0
    ok = .true.
    if (.not. sf%nodal) then
       call master_faces(st, model, sf, faces, on_face, ok)
       do i = 1, size(faces)
          call take(faces(i)%sub, faces(i)%nodes)
       end do
    else
       do i = 1, sf%n
          call surface_items(st, model, sf, i, isub, items, good)
          ok = ok .and. good
          if (good) call take(isub, items)
       end do
    end if
    ssub = ssub(1:n)
    snode = snode(1:n)
  contains
    subroutine take(jsub, nodes)
      integer, intent(in) :: jsub
      integer(ip), intent(in) :: nodes(:)
      integer :: j
      do j = 1, size(nodes)
         if (taken(jsub)%m(1, nodes(j))) cycle
         taken(jsub)%m(1, nodes(j)) = .true.
         n = n + 1
         ssub(n) = jsub
         snode(n) = nodes(j)
      end do
    end subroutine take
  end subroutine slave_nodes

  real(wp) function default_tolerance(model, faces) result(tol)
    !! CalculiX's default POSITION TOLERANCE: 2.5 % of the mean size of the master faces.
    type(model_t), intent(in) :: model
    type(master_face_t), intent(in) :: faces(:)
    integer :: f
    tol = 0.0_wp
    do f = 1, size(faces)
       tol = tol + face_size(model%subs(faces(f)%sub)%x(:, faces(f)%nodes(1:faces(f)%nc)), faces(f)%nc)
    end do
    if (size(faces) > 0) tol = DEFAULT_TOL_FRACTION*tol/size(faces)
  end function default_tolerance

  subroutine tie_nodes(model, faces, on_master, job, ssub, snode, dep, eqs, neq, tally)
    !! Tie each slave node to its nearest master face: equations appended to eqs(1:neq).
    type(model_t), intent(inout) :: model
    type(master_face_t), intent(in) :: faces(:)
    type(node_mask_t), intent(in) :: on_master(:)
    type(tie_job_t), intent(in) :: job
    integer, intent(in) :: ssub(:)
    integer(ip), intent(in) :: snode(:)
    type(node_mask_t), intent(inout) :: dep(:)
    type(equation_t), allocatable, intent(inout) :: eqs(:)
    integer, intent(inout) :: neq
    type(tie_tally_t), intent(inout) :: tally
    type(face_point_t) :: fp
    type(face_grid_t) :: grid
    integer :: i, best, d
    real(wp) :: p(3)
    call build_grid(faces, job%tol, grid)
    do i = 1, size(ssub)
       tally%slaves = tally%slaves + 1
       if (on_master(ssub(i))%m(1, snode(i))) then
          tally%shared = tally%shared + 1
          cycle
       end if
       p = model%subs(ssub(i))%x(:, snode(i))
       call nearest_face(model, faces, grid, p, job%tol, best, fp)
       if (best == 0) then
          tally%far = tally%far + 1
          if (.not. allocated(tally%first_far)) tally%first_far = node_label(model, ssub(i), snode(i))
          cycle
       end if
       tally%tied = tally%tied + 1
       if (job%adjust .and. fp%distance > 0.0_wp) then
          model%subs(ssub(i))%x(:, snode(i)) = fp%x
          model%subs(ssub(i))%part = 0    ! no longer a copy of its part: no shared condensation
          tally%moved = tally%moved + 1
          tally%max_move = max(tally%max_move, fp%distance)
       end if
       do d = 1, 3
          if (dep(ssub(i))%m(d, snode(i))) then
             tally%dropped = tally%dropped + 1
             cycle
          end if
          dep(ssub(i))%m(d, snode(i)) = .true.
          if (neq == size(eqs)) call grow_equations(eqs)
          neq = neq + 1
          eqs(neq) = tie_equation(faces(best), fp%n, ssub(i), snode(i), d)
          eqs(neq)%tie = job%tie
          eqs(neq)%loc = job%loc
       end do
    end do
  end subroutine tie_nodes

  subroutine nearest_face(model, faces, grid, p, tol, best, fp)
    !! The master face nearest to p within tol (best 0: none) and the point of
    !! it: the faces of p's cell of the grid, in face order.
    type(model_t), intent(in) :: model
    type(master_face_t), intent(in) :: faces(:)
    type(face_grid_t), intent(in) :: grid
    real(wp), intent(in) :: p(3), tol
    integer, intent(out) :: best
    type(face_point_t), intent(out) :: fp
    type(face_point_t) :: trial
    integer :: k, f, c
    best = 0
    c = grid_cell(grid, p)
    if (c == 0) return
    do k = grid%start(c), grid%start(c + 1) - 1
       f = grid%list(k)
       if (any(p < faces(f)%lo - grid%margin(f)) .or. any(p > faces(f)%hi + grid%margin(f))) cycle
       trial = project_to_face(model%subs(faces(f)%sub)%x(:, faces(f)%nodes), faces(f)%nc, p)
       if (trial%distance > tol) cycle
       if (best > 0) then
          if (trial%distance >= fp%distance) cycle
       end if
       best = f
       fp = trial
    end do
  end subroutine nearest_face

  subroutine build_grid(faces, tol, grid)
    !! A uniform grid over the master faces: each face listed in every cell
    !! its box, grown by tol and a tenth of its size (a curved face's bulge),
    !! overlaps; cells about twice the mean face size, at most 8 per face.
    type(master_face_t), intent(in) :: faces(:)
    real(wp), intent(in) :: tol
    type(face_grid_t), intent(out) :: grid
    integer, allocatable :: fill(:)
    integer :: f, pass, i, j, k, c, lo(3), hi(3)
    allocate (grid%margin(size(faces)))
    if (size(faces) == 0) then
       allocate (grid%start(2), source=1)
       allocate (grid%list(0))
       grid%hi = -1.0_wp      ! below lo: no point is inside
       return
    end if
    do f = 1, size(faces)
       grid%margin(f) = tol + 0.1_wp*maxval(faces(f)%hi - faces(f)%lo)
    end do
    grid%lo = huge(1.0_wp)
    grid%hi = -huge(1.0_wp)
    do f = 1, size(faces)
       grid%lo = min(grid%lo, faces(f)%lo - grid%margin(f))
       grid%hi = max(grid%hi, faces(f)%hi + grid%margin(f))
    end do
    grid%h = 2.0_wp*sum([(maxval(faces(f)%hi - faces(f)%lo), f = 1, size(faces))])/max(size(faces), 1)
    grid%h = max(grid%h, maxval(grid%hi - grid%lo)/1000.0_wp, tiny(1.0_wp))
    do
       grid%n = max(1, ceiling((grid%hi - grid%lo)/grid%h))
       if (real(grid%n(1), wp)*grid%n(2)*grid%n(3) <= 8.0_wp*size(faces) + 64.0_wp) exit
       grid%h = 2.0_wp*grid%h
    end do
    allocate (grid%start(product(grid%n) + 1), source=0)
    do pass = 1, 2
       if (pass == 2) then
          do c = 2, size(grid%start)
             grid%start(c) = grid%start(c) + grid%start(c - 1)
          end do
          grid%start = grid%start + 1
          allocate (grid%list(grid%start(size(grid%start)) - 1), fill(size(grid%start) - 1))
          fill = grid%start(1:size(fill))
       end if
       do f = 1, size(faces)
          lo = axis_cells(grid, faces(f)%lo - grid%margin(f))
          hi = axis_cells(grid, faces(f)%hi + grid%margin(f))
          do k = lo(3), hi(3)
             do j = lo(2), hi(2)
                do i = lo(1), hi(1)
                   c = i + grid%n(1)*(j - 1 + grid%n(2)*(k - 1))
                   if (pass == 1) then
                      grid%start(c + 1) = grid%start(c + 1) + 1
                   else
                      grid%list(fill(c)) = f
                      fill(c) = fill(c) + 1
                   end if
                end do
             end do
          end do
       end do
    end do
  end subroutine build_grid

  pure function axis_cells(grid, x) result(i)
    !! The cell indices along each axis of the point x (clamped to the grid).
    type(face_grid_t), intent(in) :: grid
    real(wp), intent(in) :: x(3)
    integer :: i(3)
    i = min(grid%n, max(1, 1 + floor((x - grid%lo)/grid%h)))
  end function axis_cells

  pure integer function grid_cell(grid, p) result(c)
    !! The cell of p (0: outside the grid).
    type(face_grid_t), intent(in) :: grid
    real(wp), intent(in) :: p(3)
    integer :: i(3)
    c = 0
    if (any(p < grid%lo) .or. any(p > grid%hi)) return
    i = axis_cells(grid, p)
    c = i(1) + grid%n(1)*(i(2) - 1 + grid%n(2)*(i(3) - 1))
  end function grid_cell

  pure function tie_equation(face, n, isub, node, d) result(e)
    !! u(node, d) - Σ_k n_k u(face node k, d) = 0 (the terms with n_k = 0 left out).
    type(master_face_t), intent(in) :: face
    real(wp), intent(in) :: n(:)
    integer, intent(in) :: isub, d
    integer(ip), intent(in) :: node
    type(equation_t) :: e
    integer :: k, t, nt
    nt = 1 + count(n /= 0.0_wp)
    allocate (e%sub(nt), e%node(nt), e%dof(nt), e%coef(nt))
    e%sub = face%sub
    e%sub(1) = isub
    e%node(1) = node
    e%dof = d
    e%coef(1) = 1.0_wp
    t = 1
    do k = 1, size(n)
       if (n(k) == 0.0_wp) cycle
       t = t + 1
       e%node(t) = face%nodes(k)
       e%coef(t) = -n(k)
    end do
  end function tie_equation

  subroutine grow_equations(eqs)
    !! Twice the room (at least 64), the equations moved.
    type(equation_t), allocatable, intent(inout) :: eqs(:)
    type(equation_t), allocatable :: tmp(:)
    integer :: k
    allocate (tmp(max(64, 2*size(eqs))))
    do k = 1, size(eqs)
       call move_alloc(eqs(k)%sub, tmp(k)%sub)
       call move_alloc(eqs(k)%node, tmp(k)%node)
       call move_alloc(eqs(k)%dof, tmp(k)%dof)
       call move_alloc(eqs(k)%coef, tmp(k)%coef)
       tmp(k)%loc = eqs(k)%loc
       tmp(k)%tie = eqs(k)%tie
    end do
    call move_alloc(tmp, eqs)
  end subroutine grow_equations

  function tie_note(tie, tol, nfaces, tally) result(text)
    !! The listing's line on one tie.
    type(tie_b_t), intent(in) :: tie
    real(wp), intent(in) :: tol
    integer, intent(in) :: nfaces
    type(tie_tally_t), intent(in) :: tally
    character(:), allocatable :: text
    text = '*TIE'
    if (len(tie%name) > 0) text = text//' '//tie%name
    if (len(tie%name) == 0) text = text//' of line '//itoa(tie%loc%line)
    text = text//': '//itoa(tally%tied)//' of '//itoa(tally%slaves)// &
         ' slave nodes tied to '//plural(nfaces, 'master face')//' (POSITION TOLERANCE '//rtoa(tol)//')'
    if (tally%far > 0) text = text//'; '//itoa(tally%far)//' farther than the tolerance from the master '// &
         'surface are not tied (the first: node '//tally%first_far//')'
    if (tally%shared > 0) text = text//'; '//itoa(tally%shared)//' are nodes of the master surface '// &
         '(not tied: shared)'
    if (tally%dropped > 0) text = text//'; '//itoa(tally%dropped)//' slave DOFs already dependent (an '// &
         '*EQUATION or an earlier *TIE) are not tied'
    if (tally%moved > 0) text = text//'; ADJUST moved '//itoa(tally%moved)//' slave nodes onto the master '// &
         'surface, by up to '//rtoa(tally%max_move)
  end function tie_note
end module superjoin_deck_tie_build
