module superjoin_substructure_condensed
  !! Static condensation of one substructure in its physical boundary numbering:
  !!     K* = k_bb − k_bi k_ii⁻¹ k_ib,   f* = f_b − k_bi k_ii⁻¹ f_i,
  !!     u_i = k_ii⁻¹ (f_i − k_ib u_b)   (recovery).
  !! k_ii is factored once (symbolic, numeric) and kept for the load
  !! condensation and the recovery of every step. K* holds no contact
  !! stiffness: the Δu transform is applied to it afterwards, as to an element.
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t, fatal_error, EXIT_SINGULAR
  use superjoin_model_types, only: model_t
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_assembly_assemble, only: superelement_t
  use superjoin_substructure_local_system, only: local_system_t, dof_label
  use superjoin_solvers, only: linear_solver_t, sparse_sym_t, new_solver
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  use superjoin_utils_strings, only: itoa
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  implicit none (type, external)
  private

  integer(i8), parameter :: RHS_BLOCK = 64
    !! Columns of k_ib solved together when forming K*.

  type, public :: condensed_t
    !! A condensed substructure: its local system, the factor of k_ii and K*.
     type(local_system_t) :: sys
     type(sparse_sym_t) :: kii                       !! leading block of sys%k
     class(linear_solver_t), allocatable :: solver   !! holds the factor of k_ii
     type(superelement_t) :: se                      !! K* on the physical boundary DOFs
     real(wp) :: maxratio = 0.0_wp                   !! max k_jj / D_jj over k_ii
     integer(i8), allocatable :: spc(:)              !! interior DOFs without stiffness (physical), dropped
     integer(i8) :: maxratio_at = 0                  !! its local DOF (1..ni)
     real(wp), allocatable :: memo_f(:, :)           !! the loads of the last condense_loads (local)
     real(wp), allocatable :: memo_fstar(:, :)       !! and their f*: a joint study's next set of
                                                     !! contact stiffnesses has the same loads
  end type condensed_t

  public :: condense, condense_loads, recover_interior

contains

  subroutine condense(model, table, solver_name, cond, error)
    !! Factor k_ii of cond%sys and form K* (dense, symmetric), in blocks of
    !! RHS_BLOCK columns of k_ib. A breakdown names the substructure, node
    !! and DOF where it occurred (an interior mechanism).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(error_t), allocatable, intent(out) :: error

    call split_blocks(model, cond, error)
    if (allocated(error)) return
    if (cond%sys%ni == 0) return
    call factor_interior(model, table, solver_name, cond, error)
    if (allocated(error)) return
    call interior_maxratio(cond)
    call subtract_interior(model, cond, error)
    if (allocated(error)) return
    ! Symmetric in exact arithmetic: take the mean of the two triangles.
    cond%se%k = 0.5_wp*(cond%se%k + transpose(cond%se%k))
    if (.not. all(ieee_is_finite(cond%se%k))) call fatal_error(error, EXIT_SINGULAR, 'error: the condensed '// &
         'stiffness of substructure '//model%subs(cond%sys%isub)%name//' overflows the floating-point range: '// &
         'check the magnitudes and units of the stiffnesses')
  end subroutine condense

  subroutine split_blocks(model, cond, error)
    !! k_ii (the first ni columns of cond%sys%k, whose rows are <= ni in the
    !! upper triangle) into cond%kii, its free DOFs dropped; K* = k_bb, both
    !! triangles, on the physical boundary DOFs.
    type(model_t), intent(in) :: model
    type(condensed_t), intent(inout) :: cond
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: ni, nb, j, pos, r
    integer :: stat
    ni = cond%sys%ni
    nb = cond%sys%nb
    associate (k => cond%sys%k)
      cond%kii%n = ni
      cond%kii%colptr = k%colptr(1:ni + 1)
      cond%kii%rowind = k%rowind(1:k%colptr(ni + 1) - 1)
      cond%kii%val = k%val(1:k%colptr(ni + 1) - 1)

      call drop_free_interior(cond)

      allocate (cond%se%k(nb, nb), stat=stat)
      if (stat /= 0) then
         call out_of_memory(error, 'the condensed stiffness of substructure '// &
              model%subs(cond%sys%isub)%name//' ('//itoa(nb)//' boundary DOFs)', nb*nb*BYTES_REAL)
         return
      end if
      cond%se%pdof = cond%sys%pdof(ni + 1:ni + nb)
      cond%se%k = 0.0_wp
      do j = ni + 1, ni + nb
         do pos = k%colptr(j), k%colptr(j + 1) - 1
            r = k%rowind(pos)
            if (r <= ni) cycle
            cond%se%k(r - ni, j - ni) = k%val(pos)
            cond%se%k(j - ni, r - ni) = k%val(pos)
         end do
      end do
    end associate
  end subroutine split_blocks

  subroutine factor_interior(model, table, solver_name, cond, error)
    !! cond%solver: the factor of k_ii; a breakdown (EXIT_SINGULAR) names the
    !! node and DOF of the failed column, or the substructure.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    character(*), intent(in) :: solver_name
    type(condensed_t), intent(inout) :: cond
    type(error_t), allocatable, intent(out) :: error
    integer(i8) :: j
    call new_solver(solver_name, cond%sys%ni, cond%solver, error)
    if (allocated(error)) return
    call cond%solver%analyze(cond%kii, error)
    if (allocated(error)) return
    call cond%solver%factorize(cond%kii, error)
    if (.not. allocated(error)) return
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
  end subroutine factor_interior

  subroutine interior_maxratio(cond)
    !! MAXRATIO of the interior factor: max k_jj / D_jj and its local DOF.
    type(condensed_t), intent(inout) :: cond
    real(wp), allocatable :: d(:), kd(:)
    integer(i8) :: j, ni
    ni = cond%sys%ni
    allocate (d(ni), kd(ni))
    call cond%solver%pivots(d)
    call cond%kii%diagonal(kd)
    do j = 1, ni
       if (d(j) == 0.0_wp) cycle
       if (abs(kd(j)/d(j)) > cond%maxratio) then
          cond%maxratio = abs(kd(j)/d(j))
          cond%maxratio_at = j
       end if
    end do
  end subroutine interior_maxratio

  subroutine subtract_interior(model, cond, error)
    !! K* -= k_ibᵀ k_ii⁻¹ k_ib, RHS_BLOCK boundary columns at a time.
    type(model_t), intent(in) :: model
    type(condensed_t), intent(inout) :: cond
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: rhs(:, :), x(:, :)
    integer(i8) :: ni, nb, j0, j1, nblk, pos, r, c
    integer :: stat
    ni = cond%sys%ni
    nb = cond%sys%nb
    allocate (rhs(ni, min(RHS_BLOCK, max(nb, 1_i8))), x(ni, min(RHS_BLOCK, max(nb, 1_i8))), stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the condensation of substructure '//model%subs(cond%sys%isub)%name, &
            2*ni*RHS_BLOCK*BYTES_REAL)
       return
    end if
    associate (k => cond%sys%k)
      do j0 = 1, nb, RHS_BLOCK
         j1 = min(nb, j0 + RHS_BLOCK - 1)
         nblk = j1 - j0 + 1
         rhs(:, 1:nblk) = 0.0_wp
         do c = j0, j1
            do pos = k%colptr(ni + c), k%colptr(ni + c + 1) - 1
               r = k%rowind(pos)
               if (r > ni) exit
               rhs(r, c - j0 + 1) = k%val(pos)
            end do
         end do
         call cond%solver%solve(rhs(:, 1:nblk), x(:, 1:nblk), error)
         if (allocated(error)) return
         ! K*(:, j0:j1) -= k_ibᵀ x
         call sub_kbi(k, ni, nb, x(:, 1:nblk), cond%se%k(:, j0:j1))
      end do
    end associate
  end subroutine subtract_interior

  subroutine drop_free_interior(cond)
    !! Interior DOFs that no element stiffens (no nonzero in their row or
    !! column, e.g. an underflowed bending stiffness) are dropped as AUTOSPC
    !! does: diagonal 1 in k_ii, zero solution; listed in cond%spc.
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
       cond%kii%val(cond%kii%colptr(j + 1) - 1) = 1.0_wp
    end do
  end subroutine drop_free_interior

  subroutine condense_loads(cond, f_local, fstar, error)
    !! f* = f_b − k_bi k_ii⁻¹ f_i for every step (f_local: local numbering).
    !! The same loads as the previous call (the next set of contact
    !! stiffnesses of a joint study) give the previous f* without a solve.
    type(condensed_t), intent(inout) :: cond
    real(wp), intent(in) :: f_local(:, :)      !! (ni+nb, nstep)
    real(wp), intent(out) :: fstar(:, :)       !! (nb, nstep)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: x(:, :)
    integer(i8) :: ni, nb
    ni = cond%sys%ni
    nb = cond%sys%nb
    if (allocated(cond%memo_f)) then
       if (all(shape(cond%memo_f) == shape(f_local))) then
          if (all(cond%memo_f == f_local)) then
             fstar = cond%memo_fstar
             return
          end if
       end if
    end if
    fstar = f_local(ni + 1:ni + nb, :)
    if (ni == 0) return
    allocate (x(ni, size(f_local, 2)))
    call cond%solver%solve(f_local(1:ni, :), x, error)
    if (allocated(error)) return
    call sub_kbi(cond%sys%k, ni, nb, x, fstar)
    cond%memo_f = f_local
    cond%memo_fstar = fstar
  end subroutine condense_loads

  subroutine recover_interior(cond, f_local, u_local, error)
    !! u_i = k_ii⁻¹ (f_i − k_ib u_b): u_local holds u_b on entry (rows ni+1..),
    !! and gets u_i (rows 1..ni).
    type(condensed_t), intent(inout) :: cond
    real(wp), intent(in) :: f_local(:, :)
    real(wp), intent(inout) :: u_local(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: rhs(:, :)
    integer(i8) :: ni, nb, j, pos, r
    ni = cond%sys%ni
    nb = cond%sys%nb
    if (ni == 0) return
    rhs = f_local(1:ni, :)
    associate (k => cond%sys%k)
      do j = 1, nb
         do pos = k%colptr(ni + j), k%colptr(ni + j + 1) - 1
            r = k%rowind(pos)
            if (r > ni) exit
            rhs(r, :) = rhs(r, :) - k%val(pos)*u_local(ni + j, :)
         end do
      end do
    end associate
    call cond%solver%solve(rhs, u_local(1:ni, :), error)
  end subroutine recover_interior

  subroutine sub_kbi(k, ni, nb, x, y)
    !! y -= k_bi x (k_bi = k_ibᵀ, read from the boundary columns of k).
    type(sparse_sym_t), intent(in) :: k
    integer(i8), intent(in) :: ni, nb
    real(wp), intent(in) :: x(:, :)
    real(wp), intent(inout) :: y(:, :)
    integer(i8) :: j, pos, r
    do j = 1, nb
       do pos = k%colptr(ni + j), k%colptr(ni + j + 1) - 1
          r = k%rowind(pos)
          if (r > ni) exit
          y(j, :) = y(j, :) - k%val(pos)*x(r, :)
       end do
    end do
  end subroutine sub_kbi
end module superjoin_substructure_condensed
