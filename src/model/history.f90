module superjoin_model_history
  !! The load history of a deck's steps (Abaqus/CalculiX semantics of OP=).
  !!
  !! Boundary conditions: *BOUNDARY written as model data holds in every step;
  !! a *BOUNDARY written inside a step holds in that step and in the later ones
  !! (OP=MOD, the default: a DOF that already has a prescribed value gets the
  !! new one, or with FIXED is held at the previous step's displacement);
  !! OP=NEW first removes every earlier *BOUNDARY condition, model
  !! data included (as ccx 2.20 does). *SUPPORT (superjoin's contact elements to
  !! the ground) is part of the structure and stays.
  !!
  !! Loads: a superjoin step is a load case of its own (the deck contract). A
  !! *CLOAD or *DLOAD card with OP=MOD, or with no OP= in a step that has a
  !! procedure card (*STATIC, CalculiX's and Abaqus's rule), continues the loads
  !! of that kind of the previous step, replacing those on the same node and
  !! DOF (element and load type); OP=NEW, or no OP= in a step without a
  !! procedure card, starts from nothing. Thermal loads are not continued
  !! here: they follow from the nodal temperatures of each step.
  use superjoin_kinds, only: i8, ip
  use superjoin_model_types, only: model_t, support_t, cload_t, dload_t, DLOAD_THERMAL
  use superjoin_utils_sorting, only: sort_index
  implicit none (type, external)
  private

  public :: support_list_t, apply_boundary_history, apply_load_history, cload_replaced, dload_replaced

  type, public :: step_ops_t
    !! What a step's cards say about the history (from the deck reader).
     logical :: bc_new = .false.           !! a *BOUNDARY, OP=NEW stands in the step
     logical :: cload_mod = .false.        !! a *CLOAD, OP=MOD (and no OP=NEW)
     logical :: dload_mod = .false.        !! a *DLOAD, OP=MOD (and no OP=NEW)
  end type step_ops_t

  type :: support_list_t
    !! The *BOUNDARY conditions a step writes itself (resolved to DOFs, in order).
     type(support_t), allocatable :: items(:)
  end type support_list_t

contains

  subroutine apply_boundary_history(model, own, ops)
    !! Set model%steps(s)%supports, the supports in effect in step s, from the
    !! model's supports and the steps' own *BOUNDARY lines own(s).
    type(model_t), intent(inout) :: model
    type(support_list_t), intent(in) :: own(:)
    type(step_ops_t), intent(in) :: ops(:)
    type(support_t), allocatable :: cur(:)
    integer :: s
    allocate (cur, source=model%supports)   ! source=: no -Wuninitialized false positive
    do s = 1, size(model%steps)
       if (ops(s)%bc_new) cur = pack(cur, .not. cur%from_boundary)
       if (size(own(s)%items) > 0) call merge_boundaries(cur, own(s)%items)
       model%steps(s)%supports = cur
    end do
  end subroutine apply_boundary_history

  subroutine merge_boundaries(cur, add)
    !! cur followed by add, where a *BOUNDARY condition of add on a DOF that a
    !! *BOUNDARY condition of cur (or an earlier one of add) holds replaces its
    !! value in place (OP=MOD); *SUPPORT entries are never merged. Sorted by
    !! substructure, node and DOF (stable), so O(n log n).
    type(support_t), allocatable, intent(inout) :: cur(:)
    type(support_t), intent(in) :: add(:)
    type(support_t), allocatable :: merged(:)
    integer, allocatable :: order(:), key(:)
    integer(ip), allocatable :: key8(:)
    logical, allocatable :: keep(:)
    integer :: i, j, first
    allocate (merged(size(cur) + size(add)))   ! not [cur, add]: gfortran's -Wuninitialized false positive
    merged(1:size(cur)) = cur
    merged(size(cur) + 1:) = add
    order = [(i, i=1, size(merged))]
    allocate (key(size(merged)), key8(size(merged)))   ! copies: component sections would go through temporaries
    key(:) = merged(:)%dof
    call sort_index(key, order)
    key8(:) = merged(:)%node
    call sort_index(key8, order)
    key(:) = merged(:)%sub
    call sort_index(key, order)
    allocate (keep(size(merged)), source=.true.)
    i = 1
    do while (i <= size(merged))
       ! the run of equal keys order(i:j), in their original order
       j = i
       do while (j < size(merged))
          if (.not. same_dof(merged(order(i)), merged(order(j + 1)))) exit
          j = j + 1
       end do
       first = 0
       do while (i <= j)
          if (merged(order(i))%from_boundary) then
             if (first == 0) then
                first = order(i)
             else
                merged(first)%value = merged(order(i))%value
                merged(first)%held_from = merged(order(i))%held_from
                merged(first)%loc = merged(order(i))%loc
                keep(order(i)) = .false.
             end if
          end if
          i = i + 1
       end do
    end do
    cur = pack(merged, keep)
  end subroutine merge_boundaries

  pure logical function same_dof(a, b)
    type(support_t), intent(in) :: a, b
    same_dof = a%sub == b%sub .and. a%node == b%node .and. a%dof == b%dof
  end function same_dof

  subroutine apply_load_history(model, ops)
    !! Continue the loads of the previous step into the steps whose *CLOAD or
    !! *DLOAD keeps them (step_ops_t; the step's own loads replace those on the
    !! same DOF or the same element and load type); count them in the step.
    type(model_t), intent(inout) :: model
    type(step_ops_t), intent(in) :: ops(:)
    type(cload_t), allocatable :: kc(:)
    type(dload_t), allocatable :: kd(:)
    integer :: s
    do s = 2, size(model%steps)
       associate (prev => model%steps(s - 1), now => model%steps(s))
         if (ops(s)%cload_mod) then
            kc = pack(prev%cloads, .not. cload_replaced(prev%cloads, now%cloads))
            now%kept_cloads = size(kc)
            if (size(kc) > 0) now%kept_from = prev%name
            now%cloads = [kc, now%cloads]
         end if
         if (ops(s)%dload_mod) then
            kd = pack(prev%dloads, prev%dloads%kind /= DLOAD_THERMAL .and. &
                 .not. dload_replaced(prev%dloads, now%dloads))
            now%kept_dloads = size(kd)
            if (size(kd) > 0) now%kept_from = prev%name
            now%dloads = [kd, now%dloads]
         end if
       end associate
    end do
  end subroutine apply_load_history

  function cload_replaced(prev, own) result(hit)
    !! Which loads of prev act on a node and DOF that own loads too.
    type(cload_t), intent(in) :: prev(:), own(:)
    logical :: hit(size(prev))
    integer :: i
    hit = tuples_found(reshape([(int([prev(i)%sub, int(prev(i)%node), prev(i)%dof], i8), i = 1, size(prev))], &
         [3, size(prev)]), reshape([(int([own(i)%sub, int(own(i)%node), own(i)%dof], i8), i = 1, size(own))], &
         [3, size(own)]))
  end function cload_replaced

  function dload_replaced(prev, own) result(hit)
    !! Which loads of prev act on an element with a load type (and, for a
    !! traction, on a face) that own loads too.
    type(dload_t), intent(in) :: prev(:), own(:)
    logical :: hit(size(prev))
    integer :: i
    hit = tuples_found(reshape([(int([prev(i)%sub, int(prev(i)%elem), prev(i)%kind, prev(i)%face], i8), &
         i = 1, size(prev))], [4, size(prev)]), &
         reshape([(int([own(i)%sub, int(own(i)%elem), own(i)%kind, own(i)%face], i8), i = 1, size(own))], &
         [4, size(own)]))
  end function dload_replaced

  function tuples_found(want, have) result(hit)
    !! hit(j): the tuple want(:, j) is one of the columns of have. The columns
    !! of have are sorted (stable passes, last component first) and searched by
    !! bisection: O((m + n) log n), as decks with many loads per step need.
    integer(i8), intent(in) :: want(:, :), have(:, :)
    logical :: hit(size(want, 2))
    integer, allocatable :: order(:)
    integer :: j, c, lo, hi, mid
    allocate (order(size(have, 2)))
    order = [(j, j = 1, size(have, 2))]
    do c = size(have, 1), 1, -1
       call sort_index(have(c, :), order)
    end do
    do j = 1, size(want, 2)
       lo = 1
       hi = size(order)
       hit(j) = .false.
       do while (lo <= hi)
          mid = (lo + hi)/2
          c = compare(have(:, order(mid)), want(:, j))
          if (c == 0) then
             hit(j) = .true.
             exit
          else if (c < 0) then
             lo = mid + 1
          else
             hi = mid - 1
          end if
       end do
    end do
  end function tuples_found

  pure integer function compare(a, b)
    !! Lexicographic order of two tuples: -1, 0 or 1.
    integer(i8), intent(in) :: a(:), b(:)
    integer :: k
    compare = 0
    do k = 1, size(a)
       if (a(k) /= b(k)) then
          compare = merge(-1, 1, a(k) < b(k))
          return
       end if
    end do
  end function compare
end module superjoin_model_history
