module superjoin_analysis_level_solver
  !! The condensation by level of parts made of parts, as a direct solver of
  !! K_red (a linear_solver_t: the health checks, the refinement and a kept
  !! factor use it as any other). K_red is the condensed run's interface
  !! system, assembled as always from the leaves' K* mapped through T, the
  !! contacts' g on their own Δu diagonals and what is not condensed. The plan
  !! (analysis/levels) gives per group, deepest first, the reduced unknowns it
  !! eliminates: its interior, which nothing outside the group sees, so that
  !! the rows of K_red there hold only the group's own contributions.
  !!
  !! factorize, level by level (the groups of one depth at once):
  !! - a group's matrix on its variables: its interior columns I, then its
  !!   boundary B (the columns the current matrix couples to I: its exported and
  !!   attached unknowns), taken from the current matrix (K_red, plus the Schur
  !!   complements of the levels below on their boundaries);
  !! - groups alike (the same matrix in this local numbering, interior and
  !!   coupling: a signature of the pattern and values, then compared value
  !!   by value) share one kind: one factorization of a_II and one Schur
  !!   complement C = −a_BI a_II⁻¹ a_IB (the solver's schur, then a_BB taken
  !!   off again);
  !! - the next level's matrix: the current one without the eliminated
  !!   columns, each group's C added on its boundary;
  !! - the columns left (the top system) are factored by the solver asked for.
  !! solve: the loads condensed bottom-up (f_B −= a_BI a_II⁻¹ f_I, all members
  !! of a kind in one multi-column solve with the shared factor), the top
  !! system solved, the interiors recovered top-down (x_I = a_II⁻¹ (f_I − a_IB
  !! x_B)). A contact's g stays on the diagonal of its own Δu: the levels only
  !! order the elimination. A level whose groups' interiors touch each other
  !! (never for groups from the plan) gives up: K_red is factored whole.
  use superjoin_utils_huge_pages, only: advise_huge
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, EXIT_SINGULAR
  use superjoin_model_types, only: string_t
  use superjoin_model_notes, only: note
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, cholmod_solver_t, move_sparse
  use superjoin_solvers_solver, only: boundary_block, subtract_bi, subtract_ib
  use superjoin_utils_strings, only: itoa
  use superjoin_analysis_levels, only: level_plan_t
  implicit none (type, external)
  private

  type :: member_t
    !! One group in the solver: its columns and its kind.
     integer(i8), allocatable :: inner(:)   !! eliminated columns, ascending
     integer(i8), allocatable :: bnd(:)     !! boundary columns, ascending
     integer :: kind = 0
  end type member_t

  type :: touch_t
    !! Per column c: the groups whose boundary holds it, grp(ptr(c):ptr(c+1)-1),
    !! and its place in each group's boundary, at(...).
     integer(i8), allocatable :: ptr(:), at(:)
     integer, allocatable :: grp(:)
  end type touch_t

  type :: kind_t
    !! Groups alike: one local matrix, one factor of its interior, one Schur complement.
     type(sparse_sym_t) :: a                 !! interior first, then boundary (upper triangle)
     integer(i8) :: ni = 0, nb = 0
     real(wp) :: sig(5) = 0.0_wp            !! interior_signature
     class(linear_solver_t), allocatable :: solver   !! of a_II
     real(wp), allocatable :: corr(:, :)     !! −a_BI a_II⁻¹ a_IB (nb, nb)
     integer, allocatable :: members(:)
  end type kind_t

  type, extends(linear_solver_t), public :: level_solver_t
    !! A direct solver of K_red by level (see the module).
     type(level_plan_t) :: plan
     character(:), allocatable :: inner_name      !! the solver asked for (kinds and top)
     integer(i8) :: n = 0
     type(member_t), allocatable :: g(:)
     type(kind_t), allocatable :: kinds(:)
     integer :: nkind = 0
     class(linear_solver_t), allocatable :: top
     integer(i8), allocatable :: top_cols(:)
     character(:), allocatable :: summary         !! the listing note (factorize)
  contains
     procedure :: analyze => level_analyze
     procedure :: factorize => level_factorize
     procedure :: solve => level_solve
     procedure :: pivots => level_pivots
     procedure :: release => level_release
  end type level_solver_t

  public :: make_solver, level_note, cholesky_pivots

contains

  subroutine make_solver(plan, name, n, solver, error)
    !! The solver of K_red (order n): by level when plan is allocated, else
    !! the solver called name (solvers/factory's new_solver).
    type(level_plan_t), allocatable, intent(in) :: plan
    character(*), intent(in) :: name
    integer(i8), intent(in) :: n
    class(linear_solver_t), allocatable, intent(out) :: solver
    type(error_t), allocatable, intent(out) :: error
    type(level_solver_t), allocatable :: s
    if (.not. allocated(plan)) then
       call new_solver(name, n, solver, error)
       return
    end if
    allocate (s)
    s%plan = plan
    s%inner_name = name
    s%n = n
    call move_alloc(s, solver)
  end subroutine make_solver

  subroutine level_note(solver, notes)
    !! The level solver's note (groups, kinds, interior eliminated, top system); none for another solver.
    class(linear_solver_t), intent(in) :: solver
    type(string_t), allocatable, intent(inout) :: notes(:)
    select type (solver)
    type is (level_solver_t)
       if (allocated(solver%summary)) call note(notes, solver%summary)
    end select
  end subroutine level_note

  recursive logical function cholesky_pivots(solver) result(yes)
    !! The solver's pivots are those of a CHOLMOD LL^T elimination ((A^-1)_jj
    !! >= 1 / D_jj: health's free lower bound of the condition): CHOLMOD, or
    !! by level with CHOLMOD for the top system and every kind (a group's
    !! interior pivots are those of a partial elimination, no smaller).
    class(linear_solver_t), intent(in) :: solver
    integer :: q
    yes = .false.
    select type (solver)
    type is (cholmod_solver_t)
       yes = .true.
    type is (level_solver_t)
       if (.not. allocated(solver%top)) return
       yes = cholesky_pivots(solver%top)
       do q = 1, solver%nkind
          if (yes) yes = cholesky_pivots(solver%kinds(q)%solver)
       end do
    end select
  end function cholesky_pivots

  subroutine level_analyze(self, a, error)
    !! Nothing but the order: the boundaries of a level follow from the values
    !! below it (factorize does all).
    class(level_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    self%n = a%n
    self%info%ordering = 'by level'
    associate (no_error => allocated(error))
    end associate
  end subroutine level_analyze

  subroutine level_factorize(self, a, error)
    !! The levels bottom-up, then the top system (see the module).
    class(level_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    type(sparse_sym_t) :: m, prev
    logical, allocatable :: gone(:)
    integer :: lo, hi
    logical :: ok
    integer(i8) :: j
    call level_release(self)
    allocate (gone(a%n), source=.false.)
    allocate (self%g(size(self%plan%groups)), self%kinds(size(self%plan%groups)))
    self%nkind = 0
    ok = .true.
    lo = 1
    do while (lo <= size(self%g) .and. ok)
       hi = lo
       do while (hi < size(self%g))
          if (self%plan%groups(hi + 1)%depth /= self%plan%groups(lo)%depth) exit
          hi = hi + 1
       end do
       if (lo == 1) then   ! K_red itself, not a copy
          call eliminate_level(self, [lo, hi], a, m, gone, ok, error)
       else
          call move_sparse(m, prev)
          call eliminate_level(self, [lo, hi], prev, m, gone, ok, error)
       end if
       if (allocated(error)) return
       lo = hi + 1
    end do
    if (.not. ok) then   ! interiors that touch: K_red whole
       call level_release(self)
       m = a
       gone = .false.
    end if
    self%top_cols = pack([(j, j=1_i8, a%n)], .not. gone)   ! m: on these (the last level compacts it)
    call factor_top(self, m, error)
    if (allocated(error)) return
    call describe(self, ok)
  end subroutine level_factorize

  subroutine eliminate_level(self, range, m, next, gone, ok, error)
    !! Groups range(1)..range(2) (one depth) of the matrix m: boundaries,
    !! kinds, their factors and Schur complements, and next, the matrix of
    !! the next level (after the last level: on the columns left only, the top
    !! system). ok = .false. when the interiors of two groups touch (nothing done).
    class(level_solver_t), intent(inout) :: self
    integer, intent(in) :: range(2)
    type(sparse_sym_t), intent(in) :: m
    type(sparse_sym_t), intent(out) :: next
    logical, intent(inout) :: gone(:)
    logical, intent(out) :: ok
    type(error_t), allocatable, intent(out) :: error
    integer, allocatable :: owner(:)
    integer :: k, first_kind, lo, hi
    lo = range(1)
    hi = range(2)
    allocate (owner(m%n), source=0)
    do k = lo, hi
       owner(self%plan%groups(k)%inner) = k
    end do
    call level_boundaries(self, range, m, owner, ok)
    if (.not. ok) return
    first_kind = self%nkind + 1
    do k = lo, hi
       call assign_kind(self, m, k, first_kind)
    end do
    do k = first_kind, self%nkind
       call factor_kind(self%kinds(k), self%inner_name, self%g(self%kinds(k)%members(1))%inner, &
            self%info%failed_column, error)
       if (allocated(error)) return
    end do
    call next_matrix(self, range, m, next, gone, hi == size(self%g))
  end subroutine eliminate_level

  subroutine level_boundaries(self, range, m, owner, ok)
    !! The boundary of each group range(1)..range(2): the columns m couples to
    !! its interior outside it (ascending), from one pass over m (owner: the
    !! group of each interior column, 0 elsewhere). ok = .false. when the
    !! interiors of two groups touch. A column is listed once per run of
    !! couplings to one group (last: the group that listed it last), not once
    !! per coupling entry: the lists stay near the boundaries' sizes instead
    !! of the couplings' count (on the 20-floor building, millions of
    !! entries written into fresh pages).
    class(level_solver_t), intent(inout) :: self
    integer, intent(in) :: range(2)
    type(sparse_sym_t), intent(in) :: m
    integer, intent(in) :: owner(:)
    logical, intent(out) :: ok
    integer(i8), allocatable :: ptr(:), col(:), at(:)
    integer, allocatable :: last(:)
    logical, allocatable :: mark(:)
    integer(i8) :: j, p, r
    integer :: k, pass
    ok = .true.
    allocate (ptr(range(1):range(2) + 1), source=0_i8)
    allocate (last(m%n))
    do pass = 1, 2   ! count the couplings per group, then list them (the same calls: the same skips)
       last = 0
       do j = 1, m%n
          do p = m%colptr(j), m%colptr(j + 1) - 1
             r = m%rowind(p)
             if (owner(r) == owner(j)) cycle
             if (owner(r) /= 0 .and. owner(j) /= 0) ok = .false.
             if (owner(r) /= 0) call couple(owner(r), j)
             if (owner(j) /= 0) call couple(owner(j), r)
          end do
       end do
       if (pass == 1) then
          call starts_from_counts(ptr)
          allocate (col(ptr(range(2) + 1) - 1))
          at = ptr
       end if
    end do
    if (.not. ok) return
    allocate (mark(m%n), source=.false.)
    do k = range(1), range(2)
       self%g(k)%inner = self%plan%groups(k)%inner
       mark(col(ptr(k):ptr(k + 1) - 1)) = .true.
       self%g(k)%bnd = pack([(r, r=1_i8, m%n)], mark)
       mark(col(ptr(k):ptr(k + 1) - 1)) = .false.
    end do
  contains
    subroutine couple(k, c)
      !! Column c is coupled to group k's interior.
      integer, intent(in) :: k
      integer(i8), intent(in) :: c
      if (last(c) == k) return   ! listed for k already
      last(c) = k
      if (pass == 1) then
         ptr(k + 1) = ptr(k + 1) + 1
      else
         col(at(k)) = c
         at(k) = at(k) + 1
      end if
    end subroutine couple
  end subroutine level_boundaries

  subroutine local_matrix(m, g, with_bb, a)
    !! a: m on g's columns, interior first then boundary (upper triangle),
    !! both in ascending global order: a_II and a_IB, and a_BB if with_bb
    !! (else its diagonal zero). Built in place from m's columns of the group
    !! alone: a boundary column b holds the interior rows above b (m's column
    !! b), then the interior columns after b (their rows b, met while the
    !! interior columns are taken in order), then a_BB; the local numbering
    !! keeps the global order, so every column's rows ascend.
    type(sparse_sym_t), intent(in) :: m
    type(member_t), intent(in) :: g
    logical, intent(in) :: with_bb
    type(sparse_sym_t), intent(out) :: a
    integer(i8), allocatable :: loc(:), at(:)
    integer(i8) :: t, ni, nloc, p, r, c
    ni = size(g%inner, kind=i8)
    nloc = ni + size(g%bnd, kind=i8)
    allocate (loc(m%n), source=0_i8)
    loc(g%inner) = [(t, t=1_i8, ni)]
    loc(g%bnd) = [(t, t=ni + 1_i8, nloc)]
    a%n = nloc
    allocate (a%colptr(nloc + 1), source=0_i8)
    do t = 1, nloc   ! count: a%colptr(t + 1) = the entries of column t
       c = column_of(t)
       do p = m%colptr(c), m%colptr(c + 1) - 1
          r = loc(m%rowind(p))
          if (r == 0) cycle
          if (r <= ni .or. (t > ni .and. with_bb)) then
             a%colptr(t + 1) = a%colptr(t + 1) + 1
          else if (t <= ni) then   ! (row b, interior column c): boundary column r
             a%colptr(r + 1) = a%colptr(r + 1) + 1
          end if
       end do
       if (.not. has_diagonal(c) .or. (t > ni .and. .not. with_bb)) a%colptr(t + 1) = a%colptr(t + 1) + 1
    end do
    call starts_from_counts(a%colptr)
    allocate (a%rowind(a%colptr(nloc + 1) - 1), a%val(a%colptr(nloc + 1) - 1))
    call advise_huge(a%rowind)
    call advise_huge(a%val)
    at = a%colptr(1:nloc)
    do t = ni + 1, nloc   ! boundary columns: the interior rows above them
       c = column_of(t)
       do p = m%colptr(c), m%colptr(c + 1) - 1
          r = loc(m%rowind(p))
          if (r >= 1 .and. r <= ni) call put(r, t, m%val(p))
       end do
    end do
    do t = 1, ni   ! interior columns, in order: a_II, and the boundary columns' interior rows below
       c = column_of(t)
       do p = m%colptr(c), m%colptr(c + 1) - 1
          r = loc(m%rowind(p))
          if (r >= 1 .and. r <= ni) call put(r, t, m%val(p))
          if (r > ni) call put(t, r, m%val(p))
       end do
       if (.not. has_diagonal(c)) call put(t, t, 0.0_wp)
    end do
    do t = ni + 1, nloc   ! a_BB (or the boundary's zero diagonal)
       c = column_of(t)
       if (with_bb) then
          do p = m%colptr(c), m%colptr(c + 1) - 1
             if (loc(m%rowind(p)) > ni) call put(loc(m%rowind(p)), t, m%val(p))
          end do
       end if
       if (.not. has_diagonal(c) .or. .not. with_bb) call put(t, t, 0.0_wp)
    end do
  contains
    integer(i8) function column_of(t)
      !! The global column of local column t.
      integer(i8), intent(in) :: t
      if (t <= ni) then
         column_of = g%inner(t)
      else
         column_of = g%bnd(t - ni)
      end if
    end function column_of
    logical function has_diagonal(col)
      !! m's column col ends on its diagonal.
      integer(i8), intent(in) :: col
      has_diagonal = m%colptr(col + 1) > m%colptr(col)
      if (has_diagonal) has_diagonal = m%rowind(m%colptr(col + 1) - 1) == col
    end function has_diagonal
    subroutine put(row, col, v)
      !! The next entry of local column col.
      integer(i8), intent(in) :: row, col
      real(wp), intent(in) :: v
      a%rowind(at(col)) = row
      a%val(at(col)) = v
      at(col) = at(col) + 1
    end subroutine put
  end subroutine local_matrix

  pure integer(i8) function interior_rows(a, j, ni) result(n)
    !! The entries of a's column j in rows 1..ni: a prefix of the column (its
    !! rows ascend, the interior numbered first). a_BB, which a group's
    !! surroundings change, is not part of what groups alike share.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: j, ni
    n = 0
    do while (a%colptr(j) + n < a%colptr(j + 1))
       if (a%rowind(a%colptr(j) + n) > ni) exit
       n = n + 1
    end do
  end function interior_rows

  function interior_signature(a, ni) result(sig)
    !! A cheap signature of a's interior part (interior_rows): its order,
    !! interior size, entries, and sums of its rows and values. Groups alike
    !! have the same; same_interior then compares them value by value.
    type(sparse_sym_t), intent(in) :: a
    integer(i8), intent(in) :: ni
    real(wp) :: sig(5)
    logical, allocatable :: inside(:)
    allocate (inside(size(a%rowind)))
    inside = a%rowind <= ni
    sig = [real(a%n, wp), real(ni, wp), real(count(inside), wp), real(sum(a%rowind, mask=inside), wp), &
         sum(a%val, mask=inside)]
  end function interior_signature

  logical function same_interior(a, b, ni)
    !! a and b (of interior size ni) have the same interior part (a_II and
    !! a_IB, column by column: interior_rows), value by value.
    type(sparse_sym_t), intent(in) :: a, b
    integer(i8), intent(in) :: ni
    integer(i8) :: j, n, pa, pb
    same_interior = a%n == b%n
    do j = 1, a%n
       if (.not. same_interior) return
       n = interior_rows(a, j, ni)
       pa = a%colptr(j)
       pb = b%colptr(j)
       same_interior = n == interior_rows(b, j, ni)
       if (same_interior) same_interior = all(a%rowind(pa:pa + n - 1) == b%rowind(pb:pb + n - 1))
       if (same_interior) same_interior = all(a%val(pa:pa + n - 1) == b%val(pb:pb + n - 1))
    end do
  end function same_interior

  subroutine assign_kind(self, m, k, first_kind)
    !! Group k's kind: an earlier kind of its level whose local matrix equals
    !! its own (signature, then value by value), or a new one (its local
    !! matrix kept, a_BB included for the factorization).
    class(level_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: m
    integer, intent(in) :: k, first_kind
    type(sparse_sym_t) :: a
    real(wp) :: sig(5)
    integer(i8) :: ni
    integer :: q
    call local_matrix(m, self%g(k), .false., a)
    ni = size(self%g(k)%inner, kind=i8)
    sig = interior_signature(a, ni)
    do q = first_kind, self%nkind
       if (any(self%kinds(q)%sig /= sig) .or. self%kinds(q)%ni /= ni) cycle
       if (.not. same_interior(self%kinds(q)%a, a, ni)) cycle
       self%g(k)%kind = q
       self%kinds(q)%members = [self%kinds(q)%members, k]
       return
    end do
    self%nkind = self%nkind + 1
    call local_matrix(m, self%g(k), .true., a)
    associate (kd => self%kinds(self%nkind))
      call move_sparse(a, kd%a)
      kd%ni = ni
      kd%nb = kd%a%n - ni
      kd%sig = sig
      kd%members = [k]
    end associate
    self%g(k)%kind = self%nkind
  end subroutine assign_kind

  subroutine factor_kind(kd, name, inner, failed, error)
    !! The factor of a kind's a_II and its Schur complement: the solver's
    !! schur on the local matrix (a_BB included, so that its route through one
    !! factorization of the whole stays positive definite), then a_BB taken
    !! off: corr = −a_BI a_II⁻¹ a_IB. failed: K_red's column where a_II breaks down.
    type(kind_t), intent(inout) :: kd
    character(*), intent(in) :: name
    integer(i8), intent(in) :: inner(:)
    integer(i8), intent(inout) :: failed
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: kbb(:, :)
    integer(i8) :: jf
    call new_solver(name, kd%a%n, kd%solver, error)
    if (allocated(error)) return
    allocate (kd%corr(kd%nb, kd%nb), kbb(kd%nb, kd%nb))
    if (kd%nb == 0) then
       call kd%solver%analyze(kd%a, error)
       if (.not. allocated(error)) call kd%solver%factorize(kd%a, error)
    else
       call kd%solver%schur(kd%a, kd%nb, kd%corr, error)
    end if
    if (allocated(error)) then
       jf = kd%solver%info%failed_column
       if (error%code == EXIT_SINGULAR .and. jf >= 1 .and. jf <= kd%ni) failed = inner(jf)
       return
    end if
    call boundary_block(kd%a, kd%nb, kbb)
    kd%corr = kd%corr - kbb
  end subroutine factor_kind

  subroutine next_matrix(self, range, m, next, gone, compact)
    !! next: m without the interiors of groups range(1)..range(2), each
    !! group's corr added on its boundary; compact: numbered on the columns
    !! left only (else the eliminated ones keep an empty place). Built column
    !! by column in place (no triplets): per column the entries of m left,
    !! then each group's corr in the order of the groups, summed in that order.
    class(level_solver_t), intent(in) :: self
    integer, intent(in) :: range(2)
    type(sparse_sym_t), intent(in) :: m
    type(sparse_sym_t), intent(out) :: next
    logical, intent(inout) :: gone(:)
    logical, intent(in) :: compact
    type(touch_t) :: t
    integer(i8), allocatable :: new(:), slot(:)
    integer(i8) :: j, n, nz
    integer :: k, pass
    do k = range(1), range(2)
       gone(self%g(k)%inner) = .true.
    end do
    allocate (new(m%n))
    n = 0
    do j = 1, m%n
       if (.not. gone(j) .or. .not. compact) n = n + 1
       new(j) = n
    end do
    call touches(self, range, m%n, t)
    next%n = n
    allocate (next%colptr(n + 1), slot(m%n), source=0_i8)
    allocate (next%rowind(0), next%val(0))
    do pass = 1, 2   ! count, then fill
       nz = 0
       next%colptr(1) = 1
       do j = 1, m%n
          if (gone(j) .and. compact) cycle
          call next_column(self, m, t, gone, new, j, pass == 2, slot, next, nz)
          next%colptr(new(j) + 1) = nz + 1
       end do
       if (pass == 1) then
          deallocate (next%rowind, next%val)
          allocate (next%rowind(nz), next%val(nz))
          call advise_huge(next%rowind)
          call advise_huge(next%val)
       end if
    end do
  end subroutine next_matrix

  subroutine merge_runs(row, val)
    !! Sort row ascending (val alongside) when it is made of a few ascending
    !! runs (a column of the next matrix: m's rows, then each group's new
    !! ones): adjacent runs merged pairwise until one is left.
    integer(i8), intent(inout) :: row(:)
    real(wp), intent(inout) :: val(:)
    integer(i8), allocatable :: rt(:)
    real(wp), allocatable :: vt(:)
    integer(i8) :: n, lo, mid, hi, i, j, k
    n = size(row, kind=i8)
    mid = run_end(1_i8)
    if (mid >= n) return
    allocate (rt(n), vt(n))
    do while (mid < n)   ! runs 1..mid and mid+1..hi merged into one
       hi = run_end(mid + 1)
       lo = 1
       i = lo
       j = mid + 1
       k = lo
       do while (i <= mid .and. j <= hi)
          if (row(j) < row(i)) then
             rt(k) = row(j); vt(k) = val(j); j = j + 1
          else
             rt(k) = row(i); vt(k) = val(i); i = i + 1
          end if
          k = k + 1
       end do
       rt(k:k + mid - i) = row(i:mid); vt(k:k + mid - i) = val(i:mid)
       k = k + mid - i + 1
       rt(k:k + hi - j) = row(j:hi); vt(k:k + hi - j) = val(j:hi)
       row(1:hi) = rt(1:hi)
       val(1:hi) = vt(1:hi)
       mid = hi
    end do
  contains
    integer(i8) function run_end(from)
      !! The last place of the ascending run starting at from.
      integer(i8), intent(in) :: from
      run_end = from
      do while (run_end < n)
         if (row(run_end + 1) < row(run_end)) exit
         run_end = run_end + 1
      end do
    end function run_end
  end subroutine merge_runs

  pure subroutine starts_from_counts(ptr)
    !! ptr(i + 1) holds the count of list i (ptr(1) ignored): on return ptr(i)
    !! is where list i starts, ptr(size) one past the end (CSC column pointers).
    integer(i8), intent(inout) :: ptr(:)
    integer :: i
    ptr(1) = 1
    do i = 1, size(ptr) - 1
       ptr(i + 1) = ptr(i + 1) + ptr(i)
    end do
  end subroutine starts_from_counts

  subroutine touches(self, range, n, t)
    !! t: per column of the current matrix, the groups of range(1)..range(2)
    !! whose boundary holds it (in the order of the groups) and its place there.
    class(level_solver_t), intent(in) :: self
    integer, intent(in) :: range(2)
    integer(i8), intent(in) :: n
    type(touch_t), intent(out) :: t
    integer(i8), allocatable :: fill(:)
    integer(i8) :: c, b
    integer :: k
    allocate (t%ptr(n + 1), source=0_i8)
    do k = range(1), range(2)
       do c = 1, size(self%g(k)%bnd, kind=i8)
          b = self%g(k)%bnd(c)
          t%ptr(b + 1) = t%ptr(b + 1) + 1
       end do
    end do
    call starts_from_counts(t%ptr)
    allocate (t%grp(t%ptr(n + 1) - 1), t%at(t%ptr(n + 1) - 1))
    fill = t%ptr(1:n)
    do k = range(1), range(2)
       do c = 1, size(self%g(k)%bnd, kind=i8)
          b = self%g(k)%bnd(c)
          t%grp(fill(b)) = k
          t%at(fill(b)) = c
          fill(b) = fill(b) + 1
       end do
    end do
  end subroutine touches

  subroutine next_column(self, m, t, gone, new, j, fill, slot, next, nz)
    !! Column j of the next matrix (next_matrix): its diagonal, m's entries
    !! on rows left, each touching group's corr on the boundary rows up to j;
    !! counted (nz advanced), and with fill its rows ascending and values
    !! stored. slot: work, zero on entry and on return.
    class(level_solver_t), intent(in) :: self
    type(sparse_sym_t), intent(in) :: m
    type(touch_t), intent(in) :: t
    logical, intent(in) :: gone(:)
    integer(i8), intent(in) :: new(:), j
    logical, intent(in) :: fill
    integer(i8), intent(inout) :: slot(:)
    type(sparse_sym_t), intent(inout) :: next
    integer(i8), intent(inout) :: nz
    integer(i8) :: p, first, r, q
    first = nz + 1
    do p = m%colptr(j), m%colptr(j + 1) - 1   ! (an eliminated column keeps its empty diagonal only)
       if (.not. (gone(m%rowind(p)) .or. gone(j))) call add(m%rowind(p), m%val(p))
    end do
    do q = t%ptr(j), t%ptr(j + 1) - 1
       associate (b => self%g(t%grp(q))%bnd, corr => self%kinds(self%g(t%grp(q))%kind)%corr, c => t%at(q))
         do r = 1, c
            call add(b(r), corr(r, c))
         end do
       end associate
    end do
    if (slot(j) == 0) call add(j, 0.0_wp)   ! the diagonal, present even when empty
    do p = first, nz   ! slot back to zero
       if (fill) slot(next%rowind(p)) = 0
    end do
    if (.not. fill) then
       slot(m%rowind(m%colptr(j):m%colptr(j + 1) - 1)) = 0
       do q = t%ptr(j), t%ptr(j + 1) - 1
          slot(self%g(t%grp(q))%bnd(1:t%at(q))) = 0
       end do
       slot(j) = 0
       return
    end if
    call merge_runs(next%rowind(first:nz), next%val(first:nz))
    next%rowind(first:nz) = new(next%rowind(first:nz))
  contains
    subroutine add(row, v)
      !! One entry (row, j): a new place in the column, or summed onto its place.
      integer(i8), intent(in) :: row
      real(wp), intent(in) :: v
      if (slot(row) == 0) then
         nz = nz + 1
         slot(row) = nz
         if (fill) then
            next%rowind(nz) = row
            next%val(nz) = v
         end if
      else if (fill) then
         next%val(slot(row)) = next%val(slot(row)) + v
      end if
    end subroutine add
  end subroutine next_column

  subroutine factor_top(self, a, error)
    !! The top system a (on self%top_cols), factored by the solver asked for.
    class(level_solver_t), intent(inout) :: self
    type(sparse_sym_t), intent(in) :: a
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: jf
    call new_solver(self%inner_name, a%n, self%top, error)
    if (allocated(error)) return
    if (allocated(self%group_first)) then   ! the node graph ordered (no minimum: the top is dense by blocks)
       call self%top%set_groups(top_groups(self%group_first, self%top_cols))
       select type (top => self%top)
       type is (cholmod_solver_t)
          top%node_graph_min = 0
          top%node_metis_only = .true.   ! no AMD candidate: its passes over the Schur blocks cost more than it finds
       end select
    end if
    call self%top%analyze(a, error)
    if (.not. allocated(error)) call self%top%factorize(a, error)
    if (allocated(error)) then
       jf = self%top%info%failed_column
       if (error%code == EXIT_SINGULAR .and. jf >= 1 .and. jf <= a%n) self%info%failed_column = self%top_cols(jf)
    end if
  end subroutine factor_top

  function top_groups(first, cols) result(top)
    !! The column groups of K_red (first(g): the first column of group g, one
    !! past the last at the end) on the columns cols (ascending) left at the
    !! top, numbered there: each group keeps its columns left, empty ones go.
    integer(i8), intent(in) :: first(:), cols(:)
    integer(i8), allocatable :: top(:)
    integer(i8) :: g, t, n
    allocate (top(size(first)))
    n = 1
    top(1) = 1
    t = 1
    do g = 1, size(first, kind=i8) - 1
       do while (t <= size(cols, kind=i8))
          if (cols(t) >= first(g + 1)) exit
          t = t + 1
       end do
       if (t > top(n)) then
          n = n + 1
          top(n) = t
       end if
    end do
    top = top(1:n)
  end function top_groups

  subroutine describe(self, ok)
    !! self%info (the top solver's, with every factor's size) and the note.
    class(level_solver_t), intent(inout) :: self
    logical, intent(in) :: ok
    integer :: q
    integer(i8) :: ninner
    self%info%name = self%top%info%name
    self%info%ordering = self%top%info%ordering
    self%info%factor_nnz = self%top%info%factor_nnz
    self%info%factor_mbytes = self%top%info%factor_mbytes
    if (.not. ok) then
       self%summary = 'condensation by level: given up (the interiors of two groups of one depth touch in K_red); '// &
            'K_red factored whole'
       return
    end if
    ninner = 0
    do q = 1, self%nkind
       self%info%factor_nnz = self%info%factor_nnz + self%kinds(q)%solver%info%factor_nnz
       self%info%factor_mbytes = self%info%factor_mbytes + self%kinds(q)%solver%info%factor_mbytes + &
            8.0_wp*real(size(self%kinds(q)%corr, kind=i8), wp)/1048576.0_wp
    end do
    do q = 1, size(self%g)
       ninner = ninner + size(self%g(q)%inner, kind=i8)
    end do
    self%summary = 'condensation by level: '//itoa(size(self%g))//' group'// &
         trim(merge('s', ' ', size(self%g) /= 1))//' in '//itoa(self%nkind)//' kind'// &
         trim(merge('s', ' ', self%nkind /= 1))//' (groups alike share one factorization and one Schur '// &
         'complement), '//itoa(ninner)//' interior reduced unknowns eliminated, boundaries '// &
         itoa(minval([(size(self%g(q)%bnd), q=1, size(self%g))]))//'..'// &
         itoa(maxval([(size(self%g(q)%bnd), q=1, size(self%g))]))//'; top system '// &
         itoa(size(self%top_cols, kind=i8))//' of '//itoa(self%n)//' equations'
  end subroutine describe

  subroutine level_solve(self, b, x, error)
    !! x = K_red⁻¹ b: loads condensed bottom-up, the top solved, interiors recovered top-down.
    class(level_solver_t), intent(inout) :: self
    real(wp), intent(in) :: b(:, :)
    real(wp), intent(out) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: f(:, :), xt(:, :)
    integer :: q
    allocate (f, source=b)
    x = 0.0_wp
    do q = 1, self%nkind
       call condense_kind(self, q, f, error)
       if (allocated(error)) return
    end do
    allocate (xt(size(self%top_cols), size(b, 2)))
    call self%top%solve(f(self%top_cols, :), xt, error)
    if (allocated(error)) return
    x(self%top_cols, :) = xt
    do q = self%nkind, 1, -1
       call recover_kind(self, q, f, x, error)
       if (allocated(error)) return
    end do
  end subroutine level_solve

  subroutine condense_kind(self, q, f, error)
    !! f_B −= a_BI a_II⁻¹ f_I for every member of kind q (one multi-column solve).
    class(level_solver_t), intent(inout) :: self
    integer, intent(in) :: q
    real(wp), intent(inout) :: f(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: r(:, :), y(:, :), fb(:, :)
    integer :: i, ns, c0
    call gather_interiors(self, q, f, r, y)
    associate (kd => self%kinds(q))
      ns = size(f, 2)
      call kd%solver%solve(r, y, error)
      if (allocated(error)) return
      allocate (fb(kd%nb, size(y, 2)), source=0.0_wp)
      call subtract_bi(kd%a, kd%nb, y, fb)   ! all members at once: −a_BI y, member by member in its columns
      do i = 1, size(kd%members)   ! added in turn: members alike may share boundary columns
         c0 = (i - 1)*ns
         associate (bnd => self%g(kd%members(i))%bnd)
           f(bnd, :) = f(bnd, :) + fb(:, c0 + 1:c0 + ns)
         end associate
      end do
    end associate
  end subroutine condense_kind

  subroutine recover_kind(self, q, f, x, error)
    !! x_I = a_II⁻¹ (f_I − a_IB x_B) for every member of kind q (one multi-column solve).
    class(level_solver_t), intent(inout) :: self
    integer, intent(in) :: q
    real(wp), intent(in) :: f(:, :)
    real(wp), intent(inout) :: x(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: r(:, :), y(:, :), xb(:, :)
    integer :: i, ns, c0
    call gather_interiors(self, q, f, r, y)
    associate (kd => self%kinds(q))
      ns = size(f, 2)
      call gather_boundaries(self, q, x, xb)
      call subtract_ib(kd%a, kd%nb, xb, r)   ! all members at once: each column as alone
      call kd%solver%solve(r, y, error)
      if (allocated(error)) return
      do i = 1, size(kd%members)
         c0 = (i - 1)*ns
         x(self%g(kd%members(i))%inner, :) = y(:, c0 + 1:c0 + ns)
      end do
    end associate
  end subroutine recover_kind

  subroutine gather_interiors(self, q, f, r, y)
    !! r: the rows of f at the interior of each member of kind q, side by
    !! side (member i: columns (i-1) ns + 1 .. i ns); y: as large.
    class(level_solver_t), intent(in) :: self
    integer, intent(in) :: q
    real(wp), intent(in) :: f(:, :)
    real(wp), allocatable, intent(out) :: r(:, :), y(:, :)
    integer :: i, ns, c0
    associate (kd => self%kinds(q))
      ns = size(f, 2)
      allocate (r(kd%ni, ns*size(kd%members)), y(kd%ni, ns*size(kd%members)))
      do i = 1, size(kd%members)
         c0 = (i - 1)*ns
         r(:, c0 + 1:c0 + ns) = f(self%g(kd%members(i))%inner, :)
      end do
    end associate
  end subroutine gather_interiors

  subroutine gather_boundaries(self, q, f, fb)
    !! fb: the rows of f at the boundary of each member of kind q, side by
    !! side (member i: columns (i-1) ns + 1 .. i ns).
    class(level_solver_t), intent(in) :: self
    integer, intent(in) :: q
    real(wp), intent(in) :: f(:, :)
    real(wp), allocatable, intent(out) :: fb(:, :)
    integer :: i, ns, c0
    associate (kd => self%kinds(q))
      ns = size(f, 2)
      allocate (fb(kd%nb, ns*size(kd%members)))
      do i = 1, size(kd%members)
         c0 = (i - 1)*ns
         fb(:, c0 + 1:c0 + ns) = f(self%g(kd%members(i))%bnd, :)
      end do
    end associate
  end subroutine gather_boundaries

  subroutine level_pivots(self, d)
    !! The pivot of each column of K_red: a group's interior from its kind's
    !! factor of a_II, the others from the top system's.
    class(level_solver_t), intent(inout) :: self
    real(wp), intent(out) :: d(:)
    real(wp), allocatable :: dk(:)
    integer :: q, i
    d = 0.0_wp
    if (.not. allocated(self%top)) return
    allocate (dk(size(self%top_cols)))
    call self%top%pivots(dk)
    d(self%top_cols) = dk
    do q = 1, self%nkind
       deallocate (dk)
       allocate (dk(self%kinds(q)%ni))
       call self%kinds(q)%solver%pivots(dk)
       do i = 1, size(self%kinds(q)%members)
          d(self%g(self%kinds(q)%members(i))%inner) = dk
       end do
    end do
  end subroutine level_pivots

  subroutine level_release(self)
    !! Free the factors and the levels' matrices (the plan stays).
    class(level_solver_t), intent(inout) :: self
    integer :: q
    if (allocated(self%top)) then
       call self%top%release()
       deallocate (self%top)
    end if
    if (allocated(self%kinds)) then
       do q = 1, self%nkind
          if (allocated(self%kinds(q)%solver)) call self%kinds(q)%solver%release()
       end do
       deallocate (self%kinds)
    end if
    if (allocated(self%g)) deallocate (self%g)
    self%nkind = 0
  end subroutine level_release
end module superjoin_analysis_level_solver
