module superjoin_analysis_penalty
  !! The default penalty stiffness of RIGID contacts under FORMULATION=PENALTY.
  !!
  !! The classic choice: g = (1/sqrt(eps)) x the stiffness scale of the DOFs it
  !! joins. The constraint is then violated by about sqrt(eps) relative and the
  !! factorization loses about log10(1/sqrt(eps)) = 8 digits: half the digits
  !! survive. The scale is taken per contact component: the element stiffness
  !! of each of its two nodes along that direction (the diagonal), the smaller
  !! of the two, so that g / (stiffness that resists the relative motion) stays
  !! near 1/sqrt(eps): a rotation is not joined by a spring scaled on an axial
  !! stiffness, nor a bending direction by one scaled on the axial direction.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_model_types, only: MAX_ELEMENT_DOFS
  use superjoin_error, only: error_t, add_error_line, EXIT_DECK
  use superjoin_model_types, only: model_t, ELEMENT_NODE_COUNT, LINK_RIGID, loc_text
  use superjoin_elements, only: element_stiffness
  use superjoin_elements_drill_mask, only: element_drill
  use superjoin_assembly_dofs, only: dof_table_t, GROUND, UNIT_LINK, BLOCK_SIZE, block_dof
  use superjoin_assembly_assemble, only: element_pdofs
  use superjoin_utils_strings, only: itoa
  use superjoin_utils_memory, only: out_of_memory, BYTES_REAL
  implicit none (type, external)
  private

  integer, parameter :: MAX_ITEM_DOFS = MAX_ELEMENT_DOFS   !! physical DOFs of the largest element

  public :: apply_penalty_default, penalty_default_note

contains

  subroutine apply_penalty_default(model, table, factor, gmin, gmax, error)
    !! Every RIGID component of a contact unit becomes finite with
    !! g = factor x (the smaller of its two nodes' element stiffness along it);
    !! a component without element stiffness at either node takes the largest
    !! diagonal of its block (translations or rotations) in the model, then the
    !! largest of all, then 1. gmin, gmax: the range of g used (0 if none).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(inout) :: table
    real(wp), intent(in) :: factor
    real(wp), intent(out) :: gmin, gmax
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: diag(:)
    real(wp) :: block_max(2), scale, g
    integer :: iu, c
    integer(i8) :: p

    gmin = 0.0_wp
    gmax = 0.0_wp
    call element_diagonal(model, table, diag, error)
    if (allocated(error)) return
    block_max = 0.0_wp
    do p = 1, table%np
       c = (table%p_dof(p) - 1)/BLOCK_SIZE + 1
       block_max(c) = max(block_max(c), diag(p))
    end do
    do iu = 1, table%nunit
       if (table%units(iu)%kind /= UNIT_LINK) cycle
       if (.not. any(table%units(iu)%state(1:table%units(iu)%n) == LINK_RIGID)) cycle
       do c = 1, table%units(iu)%n
          if (table%units(iu)%state(c) /= LINK_RIGID) cycle
          associate (u => table%units(iu))
            scale = side_min(direction_diag(u%va, c), direction_diag(u%vb, c))
            if (scale <= 0.0_wp) scale = block_max(u%block)
          end associate
          if (scale <= 0.0_wp) scale = maxval(block_max)
          if (scale <= 0.0_wp) scale = 1.0_wp
          g = factor*scale
          call table%make_finite(iu, c, g)
          if (gmax == 0.0_wp) then
             gmin = g
             gmax = g
          else
             gmin = min(gmin, g)
             gmax = max(gmax, g)
          end if
       end do
    end do
  contains
    function direction_diag(v, k) result(m)
      !! Element stiffness of vertex v along the unit's local direction k:
      !! sum over the global components c of qs(k, c)**2 K_cc.
      integer(i8), intent(in) :: v
      integer, intent(in) :: k
      real(wp) :: m
      integer :: c
      integer(i8) :: q
      m = 0.0_wp
      if (v == GROUND) return
      associate (u => table%units(iu))
        do c = 1, u%n
           q = table%dof(block_dof(u%block, u%comp(c)), v)
           if (q > 0) m = m + u%qs(k, c)**2*diag(q)
        end do
      end associate
    end function direction_diag
    pure function side_min(a, b) result(m)
      !! The smaller positive of a and b (0 if neither is positive).
      real(wp), intent(in) :: a, b
      real(wp) :: m
      if (a > 0.0_wp .and. b > 0.0_wp) then
         m = min(a, b)
      else
         m = max(a, b, 0.0_wp)
      end if
    end function side_min
  end subroutine apply_penalty_default

  function penalty_default_note(gmin, gmax) result(text)
    !! The listing note on the default penalty stiffness and its range.
    real(wp), intent(in) :: gmin, gmax
    character(:), allocatable :: text
    character(len=32) :: b1, b2
    write (b1, '(es10.3)') gmin
    write (b2, '(es10.3)') gmax
    text = 'RIGID contacts use g = 1/sqrt(epsilon) x the element stiffness along each DOF they join '// &
         '(the smaller side) (PENALTY default, *CONTROLS LARGE= overrides): g from '//trim(adjustl(b1))// &
         ' to '//trim(adjustl(b2))
  end function penalty_default_note

  subroutine element_diagonal(model, table, diag, error)
    !! Diagonal of the physical stiffness of the elements alone.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    real(wp), allocatable, intent(out) :: diag(:)
    type(error_t), allocatable, intent(out) :: error
    type(error_t), allocatable :: inner
    real(wp), allocatable :: ke(:, :)
    integer(i8) :: pd(MAX_ITEM_DOFS)
    integer :: isub, n, a, nn, stat
    integer(ip) :: e
    allocate (diag(table%np), source=0.0_wp, stat=stat)
    if (stat /= 0) then
       call out_of_memory(error, 'the element diagonal', table%np*BYTES_REAL)
       return
    end if
    do isub = 1, size(model%subs)
       associate (s => model%subs(isub))
         do e = 1, s%nelem
            nn = ELEMENT_NODE_COUNT(s%elem_type(e))
            call element_stiffness(s%elem_type(e), s%x(:, s%elem_nodes(1:nn, e)), &
                 s%sections(s%elem_section(e)), model%materials(s%sections(s%elem_section(e))%material), &
                 ke, inner, element_drill(s, e))
            if (allocated(inner)) then
               call add_error_line(error, EXIT_DECK, loc_text(model, s%loc)// &
                    ': error: element '//itoa(int(s%elem_id(e)))//': '//inner%message)
               return
            end if
            call element_pdofs(model, table, isub, e, pd, n)
            do a = 1, n
               if (pd(a) > 0) diag(pd(a)) = diag(pd(a)) + ke(a, a)
            end do
         end do
       end associate
    end do
  end subroutine element_diagonal
end module superjoin_analysis_penalty
