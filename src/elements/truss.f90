module superjoin_elements_truss
  !! Two-node trusses T2D2 (XY plane, DOFs 1,2) and T3D2 (DOFs 1,2,3):
  !! axial stiffness EA/L only, linear displacement along the bar.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, ET_T2D2, ET_T3D2
  use superjoin_elements_frame, only: beam_frame, require_positive
  implicit none (type, external)
  private

  integer, parameter :: NNODE = 2

  public :: truss_stiffness, truss_end_forces, truss_distributed_load

contains

  pure integer function truss_ndim(etype)
    !! Number of translational DOFs per node of a truss type (2 or 3).
    integer, intent(in) :: etype
    if (etype == ET_T2D2) then
       truss_ndim = 2
    else
       truss_ndim = 3
    end if
  end function truss_ndim

  pure subroutine truss_setup(etype, x, sec, mat, e, length, ea_l, error)
    !! Bar direction, length and axial stiffness EA/L, with the data checks.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: e(3), length, ea_l
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3)
    e = 0.0_wp
    ea_l = 0.0_wp
    call beam_frame(etype, x, sec, r, length, error)
    if (allocated(error)) return
    call require_positive(sec%area, 'cross-section area A', error)
    call require_positive(mat%e, 'Young''s modulus E', error)
    if (allocated(error)) return
    e = r(1, :)
    ea_l = mat%e*sec%area/length
  end subroutine truss_setup

  pure subroutine truss_stiffness(etype, x, sec, mat, ke, error)
    !! Global stiffness of a T2D2/T3D2 bar, node-major (ux, uy[, uz] per node):
    !! EA/L [e eᵀ, -e eᵀ; -e eᵀ, e eᵀ] with e the unit bar direction.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: e(3), length, ea_l
    real(wp), allocatable :: b(:, :)
    integer :: nd, i, j

    call truss_setup(etype, x, sec, mat, e, length, ea_l, error)
    if (allocated(error)) return
    nd = truss_ndim(etype)
    allocate (b(nd, nd))
    do j = 1, nd
       do i = 1, nd
          b(i, j) = ea_l*e(i)*e(j)
       end do
    end do
    allocate (ke(NNODE*nd, NNODE*nd))
    ke(1:nd, 1:nd) = b
    ke(nd + 1:2*nd, nd + 1:2*nd) = b
    ke(1:nd, nd + 1:2*nd) = -b
    ke(nd + 1:2*nd, 1:nd) = -b
  end subroutine truss_stiffness

  pure subroutine truss_end_forces(etype, x, sec, mat, ue, q_local, f, error)
    !! End forces of a bar: f(1, end) = n, the axial force node `end` exerts on
    !! the bar along local x (tension: n < 0 at end 1, n > 0 at end 2), minus
    !! the consistent share qx L/2 of an axial distributed load; a load across
    !! the bar (self weight) goes to its nodes as f(2:3, end) = -q(2:3) L/2
    !! (the nodes hold it up); f(4:6, :) = 0.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(in) :: q_local(3)
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: e(3), length, ea_l, elong
    integer :: nd

    f = 0.0_wp
    nd = truss_ndim(etype)
    if (size(ue) /= NNODE*nd) then
       call fatal_error(error, EXIT_DECK, 'wrong number of element DOF values')
       return
    end if
    call truss_setup(etype, x, sec, mat, e, length, ea_l, error)
    if (allocated(error)) return
    elong = dot_product(e(1:nd), ue(nd + 1:2*nd) - ue(1:nd))
    f(1, 1) = -ea_l*elong - q_local(1)*length/2
    f(1, 2) = ea_l*elong - q_local(1)*length/2
    f(2:3, 1) = -q_local(2:3)*length/2
    f(2:3, 2) = -q_local(2:3)*length/2
  end subroutine truss_end_forces

  pure subroutine truss_distributed_load(etype, x, sec, w, fe, q_local, error)
    !! Nodal loads of a uniform load per unit length `w` (global axes) on a bar:
    !! w L/2 on the translations of each node (consistent for linear shape
    !! functions). q_local = the load in the bar's local frame. T2D2 rejects a
    !! load along global Z.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: w(3)
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: q_local(3)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), length
    integer :: nd

    q_local = 0.0_wp
    call beam_frame(etype, x, sec, r, length, error)
    if (allocated(error)) return
    nd = truss_ndim(etype)
    if (nd == 2 .and. w(3) /= 0.0_wp) then
       call fatal_error(error, EXIT_DECK, 'load along global Z on a 2D element')
       return
    end if
    allocate (fe(NNODE*nd))
    fe(1:nd) = w(1:nd)*length/2
    fe(nd + 1:2*nd) = w(1:nd)*length/2
    q_local = matmul(r, w)
  end subroutine truss_distributed_load
end module superjoin_elements_truss
