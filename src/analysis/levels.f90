module superjoin_analysis_levels
  !! Parts made of parts, level by level: the variables of each group (an
  !! instance of a part made of parts, `B.F3`: the substructures whose name
  !! starts with `B.F3.` and the contacts unfolded from it, `B.F3.J1`), in the
  !! reduced unknowns z of the flat model (root u's and tree contacts' Δu, u = T z),
  !! as doc/design superelements.md sets them out for a condensation by level:
  !!
  !! - own z: the columns of its nodes' roots and of its contacts' Δu;
  !! - exported: own z that something outside the group sees (the map T of a
  !!   DOF outside it, a contact outside it assembled as an element or as a
  !!   spring on a form, a support spring);
  !! - attachments: its DOFs that hang on a node or contact outside it
  !!   (w_b = u_b, the top of each such subtree);
  !! - interior: own z not exported, the only variables a group's K* could
  !!   eliminate (its boundary: exported + attachments);
  !! - kinds: groups of one depth with the same counts and the same rotation
  !!   (a proxy for groups alike, which one condensation could serve).
  !!
  !! This module reports, by level, what a condensation by level eliminates, in
  !! one listing note, and plans it (level_plan_t): per group, deepest first, the
  !! interior columns not already eliminated by a group inside it. The
  !! elimination itself is analysis/level_solver's, on the assembled K_red (the
  !! condensed leaves' K* mapped through T, the contacts' g on their own Δu
  !! diagonals): nothing is assembled here.
  use superjoin_kinds, only: wp, i8
  use superjoin_model_types, only: model_t, string_t
  use superjoin_assembly_dofs, only: dof_table_t, unit_t, vertex_of, unit_dofs, MAX_UNIT_TERMS, UNIT_LINK
  use superjoin_assembly_forest, only: forest_t
  use superjoin_assembly_transform, only: transform_t, form_spring_t, COL_PHYS, COL_DELTA, ROLE_PLAIN
  use superjoin_model_notes, only: note, append_string
  use superjoin_utils_strings, only: itoa
  implicit none (type, external)
  private

  type, public :: group_vars_t
    !! The variables of one group (see the module).
     character(:), allocatable :: path     !! instance path (`B.F3`)
     integer :: depth = 0                  !! 1 for a top instance (`B`), 2 inside it (`B.F3`), ...
     integer(i8) :: own = 0
     integer(i8) :: exported = 0
     integer(i8) :: attached = 0
     integer(i8) :: interior = 0
     real(wp) :: rot(3, 3) = 0.0_wp        !! placement of its first substructure (groups alike turn alike)
     integer(i8), allocatable :: inner(:)  !! the interior columns, ascending
  end type group_vars_t

  type, public :: level_group_t
    !! One group of a condensation by level: the columns it eliminates.
     character(:), allocatable :: path
     integer :: depth = 0
     integer(i8), allocatable :: inner(:)  !! its interior columns that no group inside it eliminated, ascending
     integer :: source = 0                 !! its place among the groups' variables (group_vars_t)
  end type level_group_t

  type, public :: level_plan_t
    !! A condensation by level: the groups, deepest first (analysis/level_solver).
     type(level_group_t), allocatable :: groups(:)
  end type level_plan_t

  type, public :: levels_request_t
    !! What the run asks of a condensation by level (analysis/analysis).
     character(:), allocatable :: refusal  !! why not (--levels no, several processes), blank: it may be
     logical :: auto = .false.             !! --levels auto: as the counts say (auto_choice)
  end type levels_request_t

  integer, parameter :: AUTO_INTERIOR = 2, AUTO_SHARE = 2, AUTO_MEMBERS = 3
    !! --levels auto's thresholds (auto_choice): interiors at least AUTO_INTERIOR x the boundaries and
    !! 1 / AUTO_SHARE of all reduced unknowns, at least AUTO_MEMBERS groups per kind (doc/performance.md).
  real(wp), parameter :: MAX_SCAN = 2.0e8_wp
    !! Groups times (DOFs + reduced unknowns) above which the analysis (one pass per group) is skipped.

  type :: scan_t
    !! One group's scan: which columns are its own, which are seen from outside.
     logical, allocatable :: own(:)
     logical, allocatable :: seen(:)
     logical, allocatable :: sub_in(:)     !! (nsub) the substructure belongs to the group
     logical, allocatable :: unit_in(:)    !! (nunit) the unit is a contact of the group
     integer(i8), allocatable :: col(:)    !! work: the columns of one row of T
     real(wp), allocatable :: coef(:)
  end type scan_t

  public :: group_paths, group_variables, describe_levels

contains

  subroutine group_paths(model, paths)
    !! The instance paths of the groups: every proper prefix (ending before a
    !! `.`) of a substructure's name, once each, in order of first appearance.
    type(model_t), intent(in) :: model
    type(string_t), allocatable, intent(out) :: paths(:)
    integer :: isub, k, j
    character(:), allocatable :: name
    logical :: known
    allocate (paths(0))
    do isub = 1, size(model%subs)
       name = model%subs(isub)%name
       do k = 2, len(name) - 1
          if (name(k:k) /= '.') cycle
          known = .false.
          do j = 1, size(paths)
             known = known .or. paths(j)%s == name(1:k - 1)
          end do
          if (.not. known) call append_string(paths, name(1:k - 1))   ! grown by hand: no leak
       end do
    end do
  end subroutine group_paths

  pure logical function inside(path, name)
    !! name belongs to the group `path` (starts with `path.`).
    character(*), intent(in) :: path, name
    inside = len(name) > len(path) + 1
    if (inside) inside = name(1:len(path) + 1) == path//'.'
  end function inside

  logical function unit_inside(model, table, path, iu)
    !! Unit iu is a contact of the group `path` (supports belong to no group).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    character(*), intent(in) :: path
    integer, intent(in) :: iu
    unit_inside = .false.
    if (table%units(iu)%kind /= UNIT_LINK) return
    unit_inside = inside(path, model%contacts(model%links(table%units(iu)%source)%contact)%name)
  end function unit_inside

  subroutine group_variables(model, table, forest, tr, path, g)
    !! The variables of the group `path` (see the module).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(in) :: tr
    character(*), intent(in) :: path
    type(group_vars_t), intent(out) :: g
    type(scan_t) :: s
    integer(i8) :: j
    integer :: iu
    g%path = path
    g%depth = count([(path(iu:iu) == '.', iu=1, len(path))]) + 1
    allocate (s%own(tr%ncol()), s%seen(tr%ncol()), source=.false.)
    allocate (s%col(tr%ncol()), s%coef(tr%ncol()), s%sub_in(size(model%subs)), s%unit_in(table%nunit))
    do iu = size(model%subs), 1, -1
       s%sub_in(iu) = inside(path, model%subs(iu)%name)
       if (s%sub_in(iu)) g%rot = model%subs(iu)%rot
    end do
    do iu = 1, table%nunit
       s%unit_in(iu) = unit_inside(model, table, path, iu)
    end do
    do j = 1, tr%ncol()
       if (tr%column_kind(j) == COL_PHYS) then
          s%own(j) = s%sub_in(table%p_sub(tr%column_ref(j)))
       else if (tr%column_kind(j) == COL_DELTA) then
          s%own(j) = s%unit_in(tr%column_ref(j))
       end if
    end do
    call scan_rows(table, forest, tr, s, g)
    do iu = 1, table%nunit
       if (tr%unit_role(iu) /= ROLE_PLAIN .or. s%unit_in(iu)) cycle
       call see_unit(table, tr, table%units(iu), s)
    end do
    call see_forms(tr, s)
    g%own = count(s%own, kind=i8)
    g%exported = count(s%own .and. s%seen, kind=i8)
    g%interior = g%own - g%exported
    g%inner = pack([(j, j=1_i8, tr%ncol())], s%own .and. .not. s%seen)
  end subroutine group_variables

  subroutine scan_rows(table, forest, tr, s, g)
    !! The map T row by row: own columns in the row of a DOF outside the group
    !! are seen; a DOF of the group whose tree unit lies outside it is an
    !! attachment.
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(in) :: tr
    type(scan_t), intent(inout) :: s
    type(group_vars_t), intent(inout) :: g
    integer(i8) :: p, v
    integer :: n, iu
    do p = 1, table%np
       call tr%columns_of(p, s%col, s%coef, n)
       if (n == 0) cycle
       if (.not. s%sub_in(table%p_sub(p))) then
          s%seen(s%col(1:n)) = .true.
          cycle
       end if
       if (all(s%own(s%col(1:n)))) cycle
       v = vertex_of(table, table%p_sub(p), table%p_node(p))
       iu = forest%parent_unit((table%p_dof(p) - 1)/3 + 1, v)
       if (iu == 0) cycle
       if (.not. s%unit_in(iu)) g%attached = g%attached + 1
    end do
  end subroutine scan_rows

  subroutine see_unit(table, tr, u, s)
    !! The columns of the DOFs a unit assembled as an element touches: seen.
    type(dof_table_t), intent(in) :: table
    type(transform_t), intent(in) :: tr
    type(unit_t), intent(in) :: u
    type(scan_t), intent(inout) :: s
    integer(i8) :: p(MAX_UNIT_TERMS)
    integer :: n, k, m
    call unit_dofs(table, u, p, n)
    do k = 1, n
       if (p(k) <= 0) cycle
       call tr%columns_of(p(k), s%col, s%coef, m)
       s%seen(s%col(1:m)) = .true.
    end do
  end subroutine see_unit

  subroutine see_forms(tr, s)
    !! The columns of the springs on forms (left by loop eliminations) of
    !! contacts outside the group: seen.
    type(transform_t), intent(in) :: tr
    type(scan_t), intent(inout) :: s
    type(form_spring_t) :: fs
    integer :: k
    do k = 1, tr%nforms()
       fs = tr%form(k)
       if (fs%unit > 0) then
          if (s%unit_in(fs%unit)) cycle
       end if
       s%seen(fs%col) = .true.
    end do
  end subroutine see_forms

  subroutine describe_levels(model, table, forest, tr, levels, notes, plan)
    !! One listing note: the groups of parts made of parts by level, their
    !! variables (own, interior, boundary) in the flat model's reduced unknowns,
    !! and whether they are eliminated by level (see the module). plan: the
    !! groups that eliminate an interior, deepest first, unless levels%refusal
    !! (the reason a condensation by level is not done: --levels no, several
    !! processes) is not blank, no group has an interior and a boundary, or
    !! levels%auto and the counts promise no gain (auto_choice).
    !! No note and no plan when the model has no group.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(forest_t), intent(in) :: forest
    type(transform_t), intent(in) :: tr
    type(levels_request_t), intent(in) :: levels
    type(string_t), allocatable, intent(inout) :: notes(:)
    type(level_plan_t), allocatable, intent(out) :: plan
    type(string_t), allocatable :: paths(:)
    type(group_vars_t), allocatable :: g(:)
    character(:), allocatable :: text, auto
    logical :: by_level
    integer :: k, d
    call group_paths(model, paths)
    if (size(paths) == 0) return
    if (real(size(paths), wp)*real(table%np + tr%ncol(), wp) > MAX_SCAN) then
       call note(notes, 'condensation by level: not done (the condensed leaves'' K* form one interface system); '// &
            'the analysis of what each level could eliminate skipped ('//itoa(size(paths))//' groups, a pass '// &
            'over '//itoa(table%np)//' DOFs each)')
       return
    end if
    allocate (g(size(paths)))
    do k = 1, size(paths)
       call group_variables(model, table, forest, tr, paths(k)%s, g(k))
    end do
    auto = ''
    if (len_trim(levels%refusal) == 0) call plan_levels(g, tr%ncol(), plan)
    if (allocated(plan) .and. levels%auto) then
       call auto_choice(g, plan, tr%ncol(), by_level, auto)
       if (.not. by_level) deallocate (plan)
    end if
    if (allocated(plan)) then
       text = 'condensation by level: done ('//auto//'each group''s interior eliminated onto its boundary, '// &
            'deepest first, groups alike by their assembled matrix sharing one factorization: next note); '// &
            'in reduced unknowns:'
    else if (len(auto) > 0) then
       text = 'condensation by level: not done ('//auto//'the condensed leaves'' K* form one interface '// &
            'system); what each level could eliminate, in reduced unknowns:'
    else if (len_trim(levels%refusal) > 0) then
       text = 'condensation by level: not done ('//trim(levels%refusal)//'; the condensed leaves'' K* form one '// &
            'interface system); what each level could eliminate, in reduced unknowns:'
    else
       text = 'condensation by level: not done (no group has an interior and a boundary; the condensed leaves'' K* '// &
            'form one interface system); what each level could eliminate, in reduced unknowns:'
    end if
    do d = maxval(g%depth), 1, -1
       if (.not. any(g%depth == d)) cycle
       text = text//' '//level_line(pack(g, g%depth == d))//';'
    end do
    call note(notes, text(1:len(text) - 1))
  end subroutine describe_levels

  subroutine auto_choice(g, plan, ncol, by_level, why)
    !! --levels auto: by level when the counts promise a gain over the flat
    !! interface system (doc/performance.md, "Parts made of parts"), all three of
    !! - the eliminated interiors at least AUTO_INTERIOR times the groups'
    !!   boundaries (each group leaves a dense Schur complement on its boundary,
    !!   where the flat system stays sparse);
    !! - the eliminated interiors at least 1 / AUTO_SHARE of the reduced unknowns
    !!   (else the top system is the flat one, plus the levels' work);
    !! - at least AUTO_MEMBERS groups per kind (groups alike share one
    !!   factorization and one Schur complement: the gain).
    !! why: the figures and the choice, for the note (ends in '; ').
    type(group_vars_t), intent(in) :: g(:)
    type(level_plan_t), intent(in) :: plan
    integer(i8), intent(in) :: ncol
    logical, intent(out) :: by_level
    character(:), allocatable, intent(out) :: why
    integer(i8) :: interior, boundary
    integer :: k, d, nkind
    logical :: wide, share, alike
    interior = 0
    boundary = 0
    do k = 1, size(plan%groups)
       interior = interior + size(plan%groups(k)%inner, kind=i8)
       boundary = boundary + g(plan%groups(k)%source)%exported + g(plan%groups(k)%source)%attached
    end do
    nkind = 0
    do d = maxval(plan%groups%depth), 1, -1
       if (any(plan%groups%depth == d)) &
            nkind = nkind + kinds(g, pack(plan%groups%source, plan%groups%depth == d))
    end do
    wide = interior >= AUTO_INTERIOR*boundary
    share = AUTO_SHARE*interior >= ncol
    alike = size(plan%groups) >= AUTO_MEMBERS*nkind
    by_level = wide .and. share .and. alike
    why = '--levels auto: interiors '//itoa(interior)//relation(wide)//itoa(AUTO_INTERIOR)//' x boundaries '// &
         itoa(boundary)//', '//itoa(interior)//relation(share)//'1/'//itoa(AUTO_SHARE)//' of '//itoa(ncol)// &
         ' unknowns, '//counted(size(plan%groups), 'group')//relation(alike)//itoa(AUTO_MEMBERS)//' x '// &
         counted(nkind, 'kind')//': '//trim(merge('by level', 'flat    ', by_level))//'; '
  contains
    pure function relation(holds) result(r)
      !! ' >= ' when the criterion holds, else ' < '.
      logical, intent(in) :: holds
      character(:), allocatable :: r
      r = trim(merge(' >= ', ' <  ', holds))//' '
    end function relation
    pure function counted(n, noun) result(r)
      !! `n noun`, the noun with an s unless n is 1.
      integer, intent(in) :: n
      character(*), intent(in) :: noun
      character(:), allocatable :: r
      r = itoa(n)//' '//noun//trim(merge('s', ' ', n /= 1))
    end function counted
  end subroutine auto_choice

  subroutine plan_levels(g, ncol, plan)
    !! The groups that eliminate something, deepest first: a group with a
    !! boundary (exported or attached unknowns; without one it is a system of
    !! its own, left to the top) eliminates its interior columns that no group
    !! inside it eliminated. No plan when no group eliminates anything.
    type(group_vars_t), intent(in) :: g(:)
    integer(i8), intent(in) :: ncol
    type(level_plan_t), allocatable, intent(out) :: plan
    type(level_group_t), allocatable :: list(:)
    logical, allocatable :: taken(:)
    integer :: d, k, n
    allocate (taken(ncol), source=.false.)
    allocate (list(size(g)))
    n = 0
    do d = maxval(g%depth), 1, -1
       do k = 1, size(g)
          if (g(k)%depth /= d .or. g(k)%exported + g(k)%attached == 0) cycle
          if (all(taken(g(k)%inner))) cycle
          n = n + 1
          list(n)%path = g(k)%path
          list(n)%depth = d
          list(n)%source = k
          list(n)%inner = pack(g(k)%inner, .not. taken(g(k)%inner))
          taken(list(n)%inner) = .true.
       end do
    end do
    if (n == 0) return
    allocate (plan)
    plan%groups = list(1:n)
  end subroutine plan_levels

  function level_line(g) result(line)
    !! `depth D: N groups (first .. last), own a..b, boundary c..d (...), interior e..f (total t), kinds by counts and rotation: k`.
    type(group_vars_t), intent(in) :: g(:)
    character(:), allocatable :: line
    integer(i8) :: bnd(size(g))
    integer :: k
    bnd = g%exported + g%attached
    line = 'depth '//itoa(g(1)%depth)//': '//itoa(size(g))//' group'
    if (size(g) > 1) line = line//'s'
    line = line//' ('//g(1)%path
    if (size(g) > 1) line = line//' .. '//g(size(g))%path
    line = line//'), own '//span(g%own)//', boundary '//span(bnd)//' (exported '//span(g%exported)// &
         ', attached '//span(g%attached)//'), interior '//span(g%interior)//' (total '// &
         itoa(sum(g%interior))//'), kinds by counts and rotation: '//itoa(kinds(g, [(k, k = 1, size(g))]))
  end function level_line

  integer function kinds(g, members)
    !! The number of kinds among the groups g(members): alike are those of the
    !! same counts (own, exported, attached, interior) placed with the same
    !! rotation, which one condensation by level could serve (the others reuse
    !! it). Indices, not a section g(members): a vector-subscripted copy of
    !! these derived types leaked its components under gfortran's checks.
    type(group_vars_t), intent(in) :: g(:)
    integer, intent(in) :: members(:)
    integer :: i, j
    logical :: seen
    kinds = 0
    do i = 1, size(members)
       seen = .false.
       associate (gi => g(members(i)))
         do j = 1, i - 1
            associate (gj => g(members(j)))
              seen = seen .or. (gj%own == gi%own .and. gj%exported == gi%exported .and. &
                   gj%attached == gi%attached .and. gj%interior == gi%interior .and. &
                   all(abs(gj%rot - gi%rot) <= 1.0e-12_wp))
            end associate
         end do
       end associate
       if (.not. seen) kinds = kinds + 1
    end do
  end function kinds

  function span(x) result(s)
    !! `a` or `a..b`: the smallest and largest of x.
    integer(i8), intent(in) :: x(:)
    character(:), allocatable :: s
    s = itoa(minval(x))
    if (maxval(x) /= minval(x)) s = s//'..'//itoa(maxval(x))
  end function span
end module superjoin_analysis_levels
