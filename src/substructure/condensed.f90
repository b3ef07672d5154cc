module superjoin_substructure_condensed
  !! Static condensation of one substructure in its physical boundary numbering:
  !!     K* = k_bb − k_bi k_ii⁻¹ k_ib,   f* = f_b − k_bi k_ii⁻¹ f_i,
  !!     u_i = k_ii⁻¹ (f_i − k_ib u_b)   (recovery).
  !! k_ii is factored once and kept for the load
  !! condensation and the recovery of every step. K* holds no contact
  !! stiffness: the Δu transform is applied to it afterwards, as to an element.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR
  use superjoin_model_types, only: model_t
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_assembly_assemble, only: superelement_t
  use superjoin_substructure_local_system, only: local_system_t, dof_label
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver, mumps_solver_t
  use superjoin_solvers_solver, only: subtract_bi, subtract_ib
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  use superjoin_utils_strings, only: itoa
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none (type, external)
  private

  type, public :: condensed_t
    !! A condensed substructure: its local system, the factor of k_ii and K*.
     type(local_system_t) :: sys
     class(linear_solver_t), allocatable :: solver   !! holds the factor of k_ii
     type(superelement_t) :: se                      !! K* on the physical boundary DOFs
     real(wp) :: maxratio = 0.0_wp                   !! max k_jj / D_jj over k_ii
     integer(i8), allocatable :: spc(:)              !! interior DOFs without stiffness (physical), dropped
     integer(i8) :: maxratio_at = 0                  !! its local DOF (1..ni)
     real(wp), allocatable :: memo_f(:, :)           !! the loads of the last condense_loads (local)
     real(wp), allocatable :: memo_fstar(:, :)       !! and their f*: a joint study's next set of
                                                     !! contact stiffnesses has the same loads
     real(wp), allocatable :: memo_y(:, :)
       !! the forward half of memo_f's solve (solver%half_loads), for a
       !! recovery with the other half only; not allocated where the solver
       !! has no such halves
  end type condensed_t

  public :: condense, condense_loads, recover_interior

contains

  subroutine condense(model, table, solver_name, cond, error)
    !! Form K* (dense, symmetric) and keep the factor of k_ii: the solver's
    !! schur (one factorization of the whole part where the backend can, else
    !! k_ii factored and 2 n_b solves). A breakdown names the substructure,
    !! node and DOF where it occurred (an interior mechanism).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: nb
    integer :: stat
    nb = cond%sys%nb
    allocate (cond%se%k(nb, nb), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the condensed stiffness of substructure '// &
            model%subs(cond%sys%isub)%name//' ('//itoa(nb)//' boundary DOFs)', nb*nb*BYTES_REAL)
       return
    end if
    cond%se%pdof = cond%sys%pdof(cond%sys%ni + 1:cond%sys%ni + nb)
    if (allocated(cond%memo_f)) deallocate (cond%memo_f)   ! a new factor: no load memo is its
    if (allocated(cond%memo_fstar)) deallocate (cond%memo_fstar)
    if (allocated(cond%memo_y)) deallocate (cond%memo_y)
    call drop_free_interior(cond)
    call new_solver(solver_name, cond%sys%ni, cond%solver, error)
    if (allocated(error)) return
    select type (s => cond%solver)
    type is (mumps_solver_t)
       s%alone = .true.   ! a part is condensed by one process: MUMPS on that process alone
    end select
    call cond%solver%schur(cond%sys%k, nb, cond%se%k, error)
    if (allocated(error)) then
       call name_breakdown(model, table, cond, error)
       return
    end if
    if (cond%sys%ni == 0) return
    call interior_maxratio(cond)
    if (.not. all(ieee_is_finite(cond%se%k))) call fatal_error(error, EXIT_SINGULAR, 'error: the condensed '// &
         'stiffness of substructure '//model%subs(cond%sys%isub)%name//' overflows the floating-point range: '// &
         'check the magnitudes and units of the stiffnesses')
  end subroutine condense

  subroutine name_breakdown(model, table, cond, error)
    !! A breakdown of the interior factor (EXIT_SINGULAR) named by the node
    !! and DOF of the failed column, or by the substructure; other errors pass.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(condensed_t), intent(in) :: cond
    type(error_t), allocatable, intent(inout) :: error
    integer(i8) :: j
    if (error%code /= EXIT_SINGULAR) return
    j = cond%solver%info%failed_column
    deallocate (error)
    if (j >= 1 .and. j <= cond%sys%ni) then
       call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: '// &
            'mechanism inside condensed '//dof_label(model, table, cond%sys%pdof(j))// &
            ' (the substructure moves with its boundary held)')
    else
       call fatal_error(error, EXIT_SINGULAR, 'error: the structure cannot be solved: the interior '// &
            'stiffness of condensed substructure '//model%subs(cond%sys%isub)%name//' is singular')
    end if
  end subroutine name_breakdown

  subroutine interior_maxratio(cond)
    !! MAXRATIO of the interior factor: max k_jj / D_jj and its local DOF.
    type(condensed_t), intent(inout) :: cond
    real(wp), allocatable :: d(:), kd(:)
    integer(i8) :: j, ni
    ni = cond%sys%ni
    allocate (d(ni), kd(cond%sys%k%n))
    call cond%solver%pivots(d)
    call cond%sys%k%diagonal(kd)
    do j = 1, ni
       if (d(j) == 0.0_wp) cycle
       if (abs(kd(j)/d(j)) > cond%maxratio) then
          cond%maxratio = abs(kd(j)/d(j))
          cond%maxratio_at = j
       end if
    end do
  end subroutine interior_maxratio

  subroutine drop_free_interior(cond)
    !! Interior DOFs that no element stiffens (no nonzero in their row or
    !! column, e.g. an underflowed bending stiffness) are dropped as AUTOSPC
    !! does: diagonal 1 in k_ii (in cond%sys%k), zero solution; listed in cond%spc.
    type(condensed_t), intent(inout) :: cond
    logical, allocatable :: nz(:)
    integer(i8) :: j, pos, r, ni, nspc
    ni = cond%sys%ni
    allocate (nz(ni), source=.false.)
    associate (k => cond%sys%k)
      do j = 1, k%n
         do pos = k%colptr(j), k%colptr(j + 1) - 1
            r = k%rowind(pos)
            if (k%val(pos) == 0.0_wp) cycle
            if (r <= ni) nz(r) = .true.
            if (j <= ni) nz(j) = .true.
         end do
      end do
    end associate
    nspc = count(.not. nz, kind=i8)
    allocate (cond%spc(nspc))
    nspc = 0
    do j = 1, ni
       if (nz(j)) cycle
       nspc = nspc + 1
       cond%spc(nspc) = cond%sys%pdof(j)
       cond%sys%k%val(cond%sys%k%colptr(j + 1) - 1) = 1.0_wp
    end do
  end subroutine drop_free_interior

  subroutine condense_loads(cond, f_local, fstar, error)
    !! f* = f_b − k_bi k_ii⁻¹ f_i for every step (f_local: local numbering).
    !! The same loads as the previous call (the next set of contact
    !! stiffnesses of a joint study) give the previous f* without a solve.
    type(condensed_t), intent(inout) :: cond
    real(wp), contiguous, intent(in) :: f_local(:, :)      !! (ni+nb, nstep)
    real(wp), intent(out) :: fstar(:, :)       !! (nb, nstep)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:, :)
    integer(i8) :: ni, nb
    logical :: done
    ni = cond%sys%ni
    nb = cond%sys%nb
    if (allocated(cond%memo_fstar) .and. same_loads(cond, f_local)) then
       fstar = cond%memo_fstar
       return
    end if
    fstar = f_local(ni + 1:ni + nb, :)
    if (ni == 0) return
    if (allocated(cond%memo_y)) deallocate (cond%memo_y)
    call cond%solver%half_loads(f_local, cond%memo_y, fstar, done, error)
    if (allocated(error)) return
    if (.not. done) then
       allocate (x(ni, size(f_local, 2)))
       call cond%solver%solve_leading(ni, f_local, x, error)
       if (allocated(error)) return
       call subtract_bi(cond%sys%k, nb, x, fstar)
    end if
    cond%memo_f = f_local
    cond%memo_fstar = fstar
  end subroutine condense_loads

  subroutine recover_interior(cond, f_local, u_local, error)
    !! u_i = k_ii⁻¹ (f_i − k_ib u_b): u_local holds u_b on entry (rows ni+1..),
    !! and gets u_i (rows 1..ni). f_local's interior rows may be overwritten
    !! (with f_i − k_ib u_b: no copy of the columns). For the loads of the
    !! last condense_loads, whose forward half the solver kept (memo_y), the
    !! backward half alone.
    type(condensed_t), intent(inout) :: cond
    real(wp), contiguous, intent(inout) :: f_local(:, :)
    real(wp), contiguous, intent(inout) :: u_local(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ub(:, :)
    integer(i8) :: ni
    logical :: done
    ni = cond%sys%ni
    if (ni == 0) return
    if (allocated(cond%memo_y) .and. same_loads(cond, f_local)) then
       ub = u_local(ni + 1:ni + cond%sys%nb, :)
       call cond%solver%half_recover(cond%memo_y, ub, u_local, done, error)
       if (done .or. allocated(error)) return
    end if
    call subtract_ib(cond%sys%k, cond%sys%nb, u_local(ni + 1:, :), f_local)
    call cond%solver%solve_leading(ni, f_local, u_local, error)
  end subroutine recover_interior

  logical function same_loads(cond, f_local)
    !! f_local are the loads of the last condense_loads (memo_f), value by value.
    type(condensed_t), intent(in) :: cond
    real(wp), intent(in) :: f_local(:, :)
    same_loads = .false.
    if (.not. allocated(cond%memo_f)) return
    if (any(shape(cond%memo_f) /= shape(f_local))) return
    same_loads = all(cond%memo_f == f_local)
  end function same_loads
end module superjoin_substructure_condensed
