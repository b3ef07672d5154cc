module superjoin_elements
  !! Element library facade: DOFs per node, stiffness in global axes, end forces
  !! and distributed loads of every element type (ET_* in superjoin_model_types),
  !! and what the analysis and the output ask of one element of a solved step
  !! (thermal resultants and end forces, stresses, strains, strain energy).
  !! The rest of the program asks this module (or the traits table,
  !! superjoin_elements_traits), not the element modules behind it.
  !!
  !! Ordering of element vectors and matrices: node-major; the DOFs of one node
  !! in the order of element_node_dofs. Errors come back as error_t (code
  !! EXIT_DECK) with a message without file:line; the caller prefixes it.
  use superjoin_kinds, only: wp, ip
  use superjoin_model_results, only: result_fields_t
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  use superjoin_model_types, only: section_t, material_t, ET_T2D2, ET_T3D2, ET_B23, ET_B33, &
       ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_B21, ET_B31, ET_CPE3, ET_CPE4, NUM_ELEMENT_TYPES, ELEMENT_TYPE_NAMES, &
       ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, ET_B32, &
       ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, ET_C3D8R, &
       DLOAD_PX, DLOAD_PY, DLOAD_PZ, DLOAD_P
  use superjoin_model_types, only: ET_S4R, ET_S3R, orientation_t
  use superjoin_model_types, only: ET_S8R, ET_S8, ET_S6
  use superjoin_elements_solid, only: solid_stiffness, solid_body_load, is_3d_solid => is_solid_type, &
       solid_3d_forces => solid_forces, solid_thermal_load
  use superjoin_elements_axisym, only: axisym_thermal_load, axisym_thermal_energy
  use superjoin_elements_solid_stress, only: solid_thermal_energy
  use superjoin_elements_thermal, only: thermal_free_field, thermal_beam_free_field
  use superjoin_elements_traits, only: element_traits, element_traits_t, FAMILY_TRUSS, FAMILY_BEAM, FAMILY_PLANE, FAMILY_SHELL, &
       element_family
  use superjoin_elements_axisym, only: is_axisym_type, axisym_stiffness, axisym_forces, axisym_body_load, &
       ccx_wedge_tensor, CCX_AXIAL_SEGMENTS
  use superjoin_model_types, only: ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R, substructure_t
  use superjoin_model_types, only: DLOAD_P1, DLOAD_P2, DLOAD_P3, DLOAD_P4, DLOAD_THERMAL, DLOAD_P5, DLOAD_P6
  use superjoin_elements_solid_faces, only: solid_pressure_load, solid_surface_load
  use superjoin_elements_traction, only: surface_load_t, LOAD_TRACTION, LOAD_SHEAR
  use superjoin_elements_traits, only: dload_face, is_shell8
  use superjoin_elements_edge_load, only: plane_edge_load
  use superjoin_elements_thermal, only: thermal_axial_load, thermal_plate_load
  use superjoin_elements_thermal, only: thermal_plane_nodal_load, thermal_beam_load
  use superjoin_model_types, only: dload_t, DLOAD_CENTRIF, model_t, ELEMENT_NODE_COUNT, DLOAD_GRAV, DLOAD_BX, &
       DLOAD_BY, DLOAD_BZ, DLOAD_TRVEC, DLOAD_TRSHR
  use superjoin_model_types, only: has_nodal, has_curvature_nodal, has_line_nodal
  use superjoin_elements_drill_mask, only: element_drill
  use superjoin_elements_centrif, only: centrif_load
  use superjoin_elements_shell8_loads, only: s8r_is_tapered, s8r_gravity_load, s8r_thermal_load, s8r_centrif_load, &
       s8r_thermal_terms
  use superjoin_elements_frame, only: beam_frame
  use superjoin_elements_truss, only: truss_stiffness, truss_end_forces, truss_distributed_load
  use superjoin_elements_beam, only: beam_stiffness, beam_end_forces, beam_load
  use superjoin_elements_beam3, only: beam3_stiffness, beam3_end_forces, beam3_nodal_forces, beam3_load, &
       beam3_middle_section
  use superjoin_elements_beam3, only: beam3_thermal_load, beam3_thermal_end_forces, beam3_thermal_energy, &
       beam3_spin_load, beam3_spin_halves, beam3_end_shares
  use superjoin_elements_thermal, only: thermal_plate_resultants, thermal_beam_end_forces, plane_centroid_remainder
  use superjoin_elements_shell8_loads, only: s8r_thermal_resultants
  use superjoin_elements_shell, only: shell_thermal_nodal_resultants
  use superjoin_elements_stresses, only: NTENSOR, element_state_t, element_state, element_displacements, &
       element_stresses, element_tensor
  use superjoin_elements_solid_stress, only: von_mises_tensor, principal_stresses
  use superjoin_elements_shell, only: shell_thermal_nodal_load
  use superjoin_elements_shell, only: is_plate_type, is_plane_type, is_plane_strain_type, shell_stiffness, shell_resultants, shell_pressure_load, &
       shell_area_load, shell_forces, shell_result_operator, shell_traction_load
  implicit none (type, external)
  private

  public :: element_node_dofs, element_dof_mask, element_stiffness, element_end_forces, beam_distributed_load, &
       element_nodal_forces, element_distributed_load, element_gravity_load
  public :: element_material_load, distributed_load, beam_middle_section, beam_centrif_halves
  public :: take_thermal_resultants, element_body_end_forces
  public :: element_drill, plane_centroid_remainder
    !! element_drill(sub, e): the drilling edge mask of element e of sub
    !! (superjoin_elements_drill_mask); plane_centroid_remainder(etype, x,
    !! nodal): the centroid value of a plane element's nodal thermal remainders
    !! (superjoin_elements_thermal).
  public :: NTENSOR, element_state_t, element_state, element_displacements, element_stresses, element_tensor
    !! The stresses and strains of one element of a solved step: see
    !! superjoin_elements_stresses.
  public :: von_mises_tensor, principal_stresses
    !! Von Mises stress and principal values (largest first) of a tensor in
    !! Voigt order (superjoin_elements_solid_stress).
  public :: element_strain_energy, element_thermal_energy
  public :: is_plate_type, shell_resultants, shell_forces, shell_result_operator
  public :: is_plane_type, is_plane_strain_type
    !! is_plane_type(etype): plane stress and plane strain types (CPS*, CPE*);
    !! is_plane_strain_type(etype): CPE*.
    !! is_plate_type(etype): the plane types (CPS*, CPE*), S3, S4, S3R, S4R. shell_resultants(etype, x, sec,
    !! mat, ue, res, error): nx, ny, nxy, mx, my, mxy at the centroid, element
    !! frame; shell_forces(etype, x, sec, mat, ue(:, nstep), res(6, nstep),
    !! fg(:, nstep), error): resultants and K_e u_e of every step with one
    !! element matrix; shell_result_operator(etype, x, sec, mat, op, error,
    !! drill): op(6, ndof) with res = op ue, formed once for every step and
    !! instance; see superjoin_elements_shell.
  public :: is_solid_type, solid_forces
    !! is_solid_type(etype): the solids, 3D (C3D*) and axisymmetric (CAX*); solid_forces(etype, x, mat,
    !! ue(:, nstep), fg(:, nstep), error): K_e u_e of every step (superjoin_elements_solid,
    !! superjoin_elements_axisym).
  public :: has_axisymmetric, ccx_wedge_tensor, CCX_AXIAL_SEGMENTS, ring_nodes
    !! has_axisymmetric(model): the model has axisymmetric elements (CAX*), whose forces are totals
    !! around the circumference; ccx_wedge_tensor(s, zeta), CCX_AXIAL_SEGMENTS: CalculiX's 2° wedge
    !! of such a model (superjoin_elements_axisym); ring_nodes(sub): per node of substructure sub, whether
    !! it belongs to an axisymmetric element (its forces are rings around the y axis).
  public :: beam_frame
    !! beam_frame(etype, x, sec, r, length, error): local frame of a truss or beam
    !! (rows of r = local x, y, z axes); see superjoin_elements_frame.

contains

  pure function element_node_dofs(etype) result(dofs)
    !! DOF numbers (1..6: ux, uy, uz, rx, ry, rz) carried by each node of an
    !! element type: T2D2 [1,2]; T3D2 [1,2,3]; B23, B21 [1,2,6]; B33, B31 [1..6];
    !! CPS3/CPS4/CPE3/CPE4 and CPS6/CPS8/CPS8R/CPE6/CPE8/CPE8R [1,2]; S3/S4/S3R/S4R/S8R/S8 [1..6];
    !! the solids C3D* [1,2,3]; the axisymmetric CAX* [1,2] (u_r, u_z); an unknown type gives an empty array.
    integer, intent(in) :: etype
    integer, allocatable :: dofs(:)
    integer :: i
    select case (etype)
    case (ET_T2D2, ET_CPS3, ET_CPS4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, &
         ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R)
       dofs = [1, 2]
    case (ET_T3D2)
       dofs = [1, 2, 3]
    case (ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, ET_C3D8R)
       dofs = [1, 2, 3]
    case (ET_B23, ET_B21)
       dofs = [1, 2, 6]
    case (ET_B33, ET_B31, ET_S3, ET_S4, ET_B32, ET_S4R, ET_S3R, ET_S8R, ET_S8, ET_S6)
       dofs = [(i, i=1, 6)]
    case default
       allocate (dofs(0))
    end select
  end function element_node_dofs

  pure function element_dof_mask(etype) result(mask)
    !! Which of the DOFs 1..6 each node of an element type carries (the set of
    !! element_node_dofs, without allocating).
    integer, intent(in) :: etype
    logical :: mask(6)
    mask = .false.
    select case (etype)
    case (ET_T2D2, ET_CPS3, ET_CPS4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, &
         ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R)
       mask(1:2) = .true.
    case (ET_T3D2, ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, &
         ET_C3D8R)
       mask(1:3) = .true.
    case (ET_B23, ET_B21)
       mask([1, 2, 6]) = .true.
    case (ET_B33, ET_B31, ET_S3, ET_S4, ET_B32, ET_S4R, ET_S3R, ET_S8R, ET_S8, ET_S6)
       mask = .true.
    end select
  end function element_dof_mask

  pure subroutine element_nodal_forces(etype, x, sec, f, fg, error, q_local)
    !! The forces the nodes exert on the element in global axes, element
    !! ordering (as ke), from its local end forces f(6, 2) (element_end_forces):
    !! fg = K_e u_e - f_eq, without forming K_e. B32 needs its distributed load
    !! q_local (as beam_distributed_load returns it; absent: none) for the
    !! middle node.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: f(6, 2)
    real(wp), intent(out) :: fg(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: q_local(3)
    real(wp) :: r(3, 3), length, g(6)
    integer :: a, k, d
    logical :: mask(6)
    fg = 0.0_wp
    mask = element_dof_mask(etype)
    select case (etype)
    case (ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_B21, ET_B31)
       call beam_frame(etype, x, sec, r, length, error)
       if (allocated(error)) return
       k = 0
       do a = 1, 2
          do d = 1, 3   ! Rᵀ f, written out: matmul(transpose(r), ...) was a library call per end
             g(d) = r(1, d)*f(1, a) + r(2, d)*f(2, a) + r(3, d)*f(3, a)
             g(d + 3) = r(1, d)*f(4, a) + r(2, d)*f(5, a) + r(3, d)*f(6, a)
          end do
          do d = 1, 6
             if (.not. mask(d)) cycle
             k = k + 1
             fg(k) = g(d)
          end do
       end do
    case (ET_B32)
       if (present(q_local)) then
          call beam3_nodal_forces(x, sec, f, q_local, fg, error)
       else
          call beam3_nodal_forces(x, sec, f, [0.0_wp, 0.0_wp, 0.0_wp], fg, error)
       end if
    case default
       call unsupported(etype, error)
    end select
  end subroutine element_nodal_forces

  pure subroutine beam_middle_section(etype, x, sec, f, q_local, s, error, extra)
    !! The section forces s(6) = n, vy, vz, t, my, mz at the middle node of a
    !! three-node beam (local axes there, signed as the end forces of its last
    !! node), from its end forces f(6, 2) (element_end_forces), its load per
    !! unit length q_local (as beam_distributed_load returns it) and extra(6, 2)
    !! the loads on its halves that vary along it (beam_centrif_halves). Other
    !! types: an error.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: f(6, 2)
    real(wp), intent(in) :: q_local(3)
    real(wp), intent(out) :: s(6)
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: extra(6, 2)
    s = 0.0_wp
    select case (etype)
    case (ET_B32)
       call beam3_middle_section(x, sec, f, q_local, s, error, extra)
    case default
       call unsupported(etype, error)
    end select
  end subroutine beam_middle_section

  pure function beam_centrif_halves(etype, x, sec, mat, dl) result(h)
    !! h(6, 2): the resultant and the moment about the middle node of the
    !! centrifugal load dl on each half of a three-node beam (0 for another
    !! load or element), for beam_middle_section's extra.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp) :: h(6, 2)
    h = 0.0_wp
    if (etype == ET_B32 .and. dl%kind == DLOAD_CENTRIF) h = beam3_spin_halves(x, b32_spin(sec, mat, dl))
  end function beam_centrif_halves

  pure function b32_spin(sec, mat, dl) result(spin)
    !! The centrifugal load of dl on a B32 as beam3_spin_load takes it: ρ A ω², the axis' point and direction.
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp) :: spin(7)
    spin = [mat%density*sec%area*dl%value, dl%point, dl%dir]
  end function b32_spin

  pure subroutine element_stiffness(etype, x, sec, mat, ke, error, drill)
    !! Element stiffness in global axes, node-major ordering (node 1 DOFs in
    !! element_node_dofs order, then node 2 ...; B32: end, middle, end). x(3, nnode) are the node
    !! coordinates. Errors: zero-length element, orientation vector parallel to
    !! beam axis, nonpositive A, I, J, t or E, plane-stress element out of the
    !! XY plane, zero area, distorted (non-convex) quadrilateral. drill: the
    !! element's drilling-membrane edge mask (superjoin_elements_drill_mask;
    !! absent: every edge).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), allocatable, intent(out) :: ke(:, :)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    select case (etype)
    case (ET_T2D2, ET_T3D2)
       call truss_stiffness(etype, x, sec, mat, ke, error)
    case (ET_B23, ET_B33, ET_B21, ET_B31)
       call beam_stiffness(etype, x, sec, mat, ke, error)
    case (ET_B32)
       call beam3_stiffness(x, sec, mat, ke, error)
    case (ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, ET_S4R, ET_S3R, &
         ET_S8R, ET_S8, ET_S6)
       call shell_stiffness(etype, x, sec, mat, ke, error, drill)
    case (ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, ET_C3D8R)
       call solid_stiffness(etype, x, mat, ke, error, sec%axes)
    case (ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R)
       call axisym_stiffness(etype, x, mat, ke, error)
    case default
       call unsupported(etype, error)
    end select
  end subroutine element_stiffness

  pure subroutine element_end_forces(etype, x, sec, mat, ue, q_local, f, error)
    !! Forces and moments the nodes exert on the element, in its local axes,
    !! per end: f(1:6, end) = n, vy, vz, t, my, mz, computed as
    !! f_local = k_local u_local - f_eq_local (f_eq: consistent nodal loads of the
    !! distributed load q_local, given per unit length in local axes). A bar in
    !! tension has n < 0 at end 1 and n > 0 at end 2. ue holds the element DOF
    !! values in global axes, same ordering as element_stiffness. Components a
    !! type lacks are 0 (trusses: n, and vy, vz under a load across the bar such
    !! as self weight; B23, B21: n, vy, mz). Plane, shell and solid
    !! elements have no end forces: f = 0 and no error.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: ue(:)
    real(wp), intent(in) :: q_local(3)
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    f = 0.0_wp
    select case (etype)
    case (ET_T2D2, ET_T3D2)
       call truss_end_forces(etype, x, sec, mat, ue, q_local, f, error)
    case (ET_B23, ET_B33, ET_B21, ET_B31)
       call beam_end_forces(etype, x, sec, mat, ue, q_local, f, error)
    case (ET_B32)
       call beam3_end_forces(x, sec, mat, ue, q_local, f, error)
    case (ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, ET_S4R, ET_S3R, &
         ET_S8R, ET_S8, ET_S6, ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, &
         ET_C3D8R, ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R)
       continue
    case default
       call unsupported(etype, error)
    end select
  end subroutine element_end_forces

  pure subroutine beam_distributed_load(etype, x, sec, wglobal, fe, q_local, error)
    !! Consistent nodal load vector fe (global axes, same ordering as
    !! element_stiffness) of a uniform load per unit length wglobal(3) given in
    !! global axes, with the fixed-end moments for beams (trusses: wL/2 on the
    !! translations of each node); q_local returns the load in the element's
    !! local axes, for element_end_forces. A load along global Z on T2D2/B23 is
    !! an error; other element types return an error as well.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    real(wp), intent(in) :: wglobal(3)
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: q_local(3)
    type(error_t), allocatable, intent(out) :: error
    q_local = 0.0_wp
    select case (etype)
    case (ET_T2D2, ET_T3D2)
       call truss_distributed_load(etype, x, sec, wglobal, fe, q_local, error)
    case (ET_B23, ET_B33, ET_B21, ET_B31)
       call beam_load(etype, x, sec, wglobal, fe, q_local, error)
    case (ET_B32)
       call beam3_load(x, wglobal, fe, error)     ! B32: q_local holds the load in global axes
       q_local = wglobal
    case default
       if (etype >= 1 .and. etype <= NUM_ELEMENT_TYPES) then
          call fatal_error(error, EXIT_DECK, 'load per unit length on element type '// &
               trim(ELEMENT_TYPE_NAMES(etype))//' (only trusses and beams take PX, PY, PZ)')
       else
          call unsupported(etype, error)
       end if
    end select
  end subroutine beam_distributed_load

  pure subroutine element_distributed_load(etype, x, sec, kind, value, fe, q_local, error)
    !! Consistent nodal loads fe (global axes, element ordering) of a distributed
    !! load of kind DLOAD_PX/PY/PZ (per unit length, global axes, trusses and
    !! beams) or DLOAD_P (pressure on shells, positive against the normal), and
    !! the load in element axes q_local (per unit length for beams; for shells
    !! q_local(3) is the load per unit area along the local normal).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    integer, intent(in) :: kind
    real(wp), intent(in) :: value
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: q_local(3)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: w(3)
    q_local = 0.0_wp
    select case (kind)
    case (DLOAD_PX, DLOAD_PY, DLOAD_PZ)
       w = 0.0_wp
       w(kind) = value
       call beam_distributed_load(etype, x, sec, w, fe, q_local, error)
    case (DLOAD_P)
       call shell_pressure_load(etype, x, value, fe, q_local(3), error)
    case (DLOAD_P1, DLOAD_P2, DLOAD_P3, DLOAD_P4, DLOAD_P5, DLOAD_P6)
       if (is_3d_solid(etype)) then
          call solid_pressure_load(etype, x, dload_face(kind), value, fe, error)
       else
          call face_load(etype, x, sec, dload_face(kind), value, fe, q_local, error)
       end if
    case (DLOAD_THERMAL)
       select case (etype)
       case (ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_B21, ET_B31)
          call thermal_axial_load(etype, x, sec, element_node_dofs(etype), value, fe, error)
       case default
          call fatal_error(error, EXIT_DECK, 'thermal loads are implemented for trusses and beams only')
       end select
    case default
       call fatal_error(error, EXIT_DECK, 'unknown distributed load kind')
    end select
  end subroutine element_distributed_load

  pure subroutine element_traction_load(etype, x, sec, dl, fe, error)
    !! Consistent nodal loads fe (global axes, element ordering) of Abaqus's
    !! surface traction dl (*DSLOAD TRVEC, TRSHR: superjoin_elements_traction)
    !! on face dl%face of a solid, edge dl%face of a plane or axisymmetric
    !! element (over its thickness, or the whole circumference), or the
    !! surface of a shell (dl%face = 0).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    type(surface_load_t) :: ld
    type(element_traits_t) :: t
    ld = surface_load_t(merge(LOAD_SHEAR, LOAD_TRACTION, dl%kind == DLOAD_TRSHR), dl%value, dl%dir)
    t = element_traits(etype)
    if (t%family == FAMILY_SHELL) then
       call shell_traction_load(etype, x, ld, fe, error)
    else if (is_3d_solid(etype)) then
       call solid_surface_load(etype, x, dl%face, ld, fe, error)
    else if (t%axisymmetric) then
       call plane_edge_load(x, t%corners, dl%face, 0.0_wp, 1.0_wp, fe, error, axisymmetric=.true., ld=ld)
    else if (t%family == FAMILY_PLANE) then
       call plane_edge_load(x, t%corners, dl%face, 0.0_wp, sec%thickness, fe, error, ld=ld)
    else
       call fatal_error(error, EXIT_DECK, 'a traction applies to the faces of solids, plane elements and shells')
    end if
  end subroutine element_traction_load

  pure subroutine face_load(etype, x, sec, face, value, fe, q_local, error)
    !! CalculiX's numbered *DLOAD forms: Pk, pressure on face k of a plane
    !! element (superjoin_elements_edge_load); on beams P1 and P2, a load per
    !! unit length along the local y (Abaqus n1) and local z (n2) axes. A planar
    !! beam (B21, B23) takes P2 only: its n1 is normal to the XY plane.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    integer, intent(in) :: face
    real(wp), intent(in) :: value
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: q_local(3)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: r(3, 3), length, ql(3)
    integer, parameter :: TRIANGLE_CORNERS = 3, QUAD_CORNERS = 4
    q_local = 0.0_wp
    select case (etype)
    case (ET_CPS3, ET_CPE3, ET_CPS6, ET_CPE6)
       call plane_edge_load(x, TRIANGLE_CORNERS, face, value, sec%thickness, fe, error)
    case (ET_CPS4, ET_CPE4, ET_CPS8, ET_CPE8, ET_CPS8R, ET_CPE8R)
       call plane_edge_load(x, QUAD_CORNERS, face, value, sec%thickness, fe, error)
    case (ET_CAX3, ET_CAX6)   ! the whole circumference: 2π r per unit length of edge
       call plane_edge_load(x, TRIANGLE_CORNERS, face, value, 1.0_wp, fe, error, axisymmetric=.true.)
    case (ET_CAX4, ET_CAX8, ET_CAX8R)
       call plane_edge_load(x, QUAD_CORNERS, face, value, 1.0_wp, fe, error, axisymmetric=.true.)
    case (ET_B23, ET_B33, ET_B21, ET_B31)
       if (face > 2) then
          call fatal_error(error, EXIT_DECK, 'a beam takes P1 and P2 (per unit length in local axes)')
          return
       end if
       if ((etype == ET_B23 .or. etype == ET_B21) .and. face == 1) then
          call fatal_error(error, EXIT_DECK, 'P1 on a planar beam acts normal to its plane (use P2, along local y)')
          return
       end if
       call beam_frame(etype, x, sec, r, length, error)
       if (allocated(error)) return
       ql = 0.0_wp
       if (etype == ET_B23 .or. etype == ET_B21) then
          ql(2) = value
       else
          ql(face + 1) = value
       end if
       call beam_distributed_load(etype, x, sec, matmul(transpose(r), ql), fe, q_local, error)
    case default
       call fatal_error(error, EXIT_DECK, 'face loads P1 to P4 apply to plane elements and beams')
    end select
  end subroutine face_load

  pure function unit_density(mat) result(m)
    !! mat with density 1: a body force per unit volume (BX, BY, BZ) is the
    !! self weight's load of a unit density under that "acceleration".
    type(material_t), intent(in) :: mat
    type(material_t) :: m
    m = mat
    m%density = 1.0_wp
    m%has_density = .true.
  end function unit_density

  pure subroutine element_gravity_load(etype, x, sec, mat, accel, fe, q_local, error)
    !! Consistent nodal loads fe (global axes, element ordering) of the self
    !! weight under the acceleration vector accel (global axes): density × A per
    !! unit length on trusses and beams (q_local as for beam_distributed_load),
    !! density × t per unit area on plane and shell elements, density per unit
    !! volume on solids (q_local = 0).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: accel(3)
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: q_local(3)
    type(error_t), allocatable, intent(out) :: error
    q_local = 0.0_wp
    if (s8r_is_tapered(etype, sec)) then
       call s8r_gravity_load(x, sec, mat, accel, fe, error)   ! ρ t(ξ, η) per unit area
       return
    end if
    select case (etype)
    case (ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_B21, ET_B31, ET_B32)
       call beam_distributed_load(etype, x, sec, mat%density*sec%area*accel, fe, q_local, error)
    case (ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_CPE3, ET_CPE4, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, ET_CPS8R, ET_CPE8R, ET_S4R, ET_S3R, &
         ET_S8R, ET_S8, ET_S6)
       call shell_area_load(etype, x, mat%density*sec%thickness*accel, fe, error)
    case (ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, ET_C3D6, ET_C3D15, ET_C3D8R)
       call solid_body_load(etype, x, mat%density*accel, fe, error)   ! ρ g per unit volume
    case (ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R)
       if (accel(1) /= 0.0_wp .or. accel(3) /= 0.0_wp) then
          call fatal_error(error, EXIT_DECK, 'GRAV on an axisymmetric element must act along its axis (y)')
          return
       end if
       call axisym_body_load(etype, x, mat%density*accel(1:2), 0.0_wp, fe, error)
    case default
       call unsupported(etype, error)
    end select
  end subroutine element_gravity_load

  pure subroutine element_material_load(etype, x, sec, mat, dl, fe, error, drill)
    !! Consistent nodal loads fe (global axes, element ordering) of the loads
    !! that need the material: the thermal strain of a plane or shell element
    !! (DLOAD_THERMAL, superjoin_elements_thermal) and the centrifugal load
    !! (DLOAD_CENTRIF, superjoin_elements_centrif). drill as element_stiffness.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in), optional :: drill
    real(wp), allocatable :: f2(:)
    select case (dl%kind)
    case (DLOAD_THERMAL)
       if (etype == ET_B32) then
          ! the three-node beam: its nodal strains and curvatures, interpolated
          if (.not. has_line_nodal(dl)) then
             call fatal_error(error, EXIT_DECK, 'thermal load on a B32 without its nodal values')
             return
          end if
          call beam3_thermal_load(x, sec, mat, dl%nodes%line_nodal, fe, error)
          return
       end if
       if (any(etype == [ET_B23, ET_B33, ET_B21, ET_B31])) then
          ! a beam: the axial force E A α ΔT and the end moments of its thermal curvatures
          call thermal_axial_load(etype, x, sec, element_node_dofs(etype), dl%value, fe, error)
          if (allocated(error)) return
          call thermal_beam_load(etype, x, sec, mat, dl%gradient, f2, error)
          if (allocated(error)) return
          fe = fe + f2
          return
       end if
       if (is_solid_type(etype)) then
          ! a solid: α ΔT at its nodes, interpolated to its points
          if (.not. has_nodal(dl)) then
             call fatal_error(error, EXIT_DECK, 'thermal load on a solid without its nodal values')
          else if (is_axisym_type(etype)) then
             call axisym_thermal_load(etype, x, mat, dl%nodes%nodal, fe, error)
          else
             call solid_thermal_load(etype, x, mat, dl%nodes%nodal, fe, error, sec%axes)
          end if
          return
       end if
       if (.not. is_plate_type(etype)) then
          call fatal_error(error, EXIT_DECK, 'thermal strain load on an element that is not a plane or shell element')
          return
       end if
       if (is_shell8(etype)) then
          if (has_nodal(dl)) then   ! varying over the element: its nodal values, interpolated
             call s8r_thermal_load(etype, x, sec, mat, dl%value, dl%curvature, fe, error, dl%nodes%nodal, &
                  dl%nodes%curvature_nodal)
          else
             call s8r_thermal_load(etype, x, sec, mat, dl%value, dl%curvature, fe, error)
          end if
          return
       end if
       call thermal_plate_load(etype, x, sec, mat, dl%value, dl%curvature, fe, error, drill)
       if (allocated(error) .or. .not. has_nodal(dl)) return
       ! a temperature that varies over the element: the nodal remainder, interpolated
       if (is_plane_type(etype)) then
          call thermal_plane_nodal_load(etype, x, sec, mat, dl%nodes%nodal, f2, error)
       else
          call shell_thermal_nodal_load(etype, x, sec, mat, dl%nodes%nodal, dl%nodes%curvature_nodal, f2, error, drill)
       end if
       if (allocated(error)) return
       fe = fe + f2
    case (DLOAD_CENTRIF)
       if (is_axisym_type(etype)) then
          call axisym_centrif_load(etype, x, mat, dl, fe, error)
          return
       end if
       if (is_shell8(etype)) then
          call s8r_centrif_load(x, sec, mat, dl, fe, error)
          return
       end if
       if (etype == ET_B32) then
          fe = beam3_spin_load(x, b32_spin(sec, mat, dl))
          return
       end if
       call centrif_load(etype, x, sec, mat, dl, element_node_dofs(etype), fe, error)
    case default
       call fatal_error(error, EXIT_DECK, 'unknown distributed load kind')
    end select
  end subroutine element_material_load

  subroutine distributed_load(model, dl, fe, q_local, error)
    !! Nodal loads (global axes, element ordering) and local load of one
    !! distributed load of the model: PX/PY/PZ, P, GRAV, CENTRIF, TEMP or a traction (TRVEC, TRSHR).
    type(model_t), intent(in) :: model
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    real(wp), intent(out) :: q_local(3)
    type(error_t), allocatable, intent(out) :: error
    integer :: nn
    associate (s => model%subs(dl%sub))
      nn = ELEMENT_NODE_COUNT(s%elem_type(dl%elem))
      associate (sec => s%sections(s%elem_section(dl%elem)))
        if (dl%kind == DLOAD_GRAV) then
           call element_gravity_load(s%elem_type(dl%elem), s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                model%materials(sec%material), dl%value*dl%dir, fe, q_local, error)
        else if (any(dl%kind == [DLOAD_BX, DLOAD_BY, DLOAD_BZ])) then   ! a force per unit volume: density 1
           call element_gravity_load(s%elem_type(dl%elem), s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                unit_density(model%materials(sec%material)), dl%value*dl%dir, fe, q_local, error)
        else if (dl%kind == DLOAD_CENTRIF .or. (dl%kind == DLOAD_THERMAL .and. (is_plate_type(s%elem_type(dl%elem)) &
             .or. is_solid_type(s%elem_type(dl%elem)) .or. any(dl%gradient /= 0.0_wp) &
             .or. has_line_nodal(dl)))) then   ! TEMP: a beam with a gradient, a B32 need E I
           q_local = 0.0_wp   ! CENTRIF on a bar or beam: its end forces take fe itself (superjoin_analysis_recover)
           call element_material_load(s%elem_type(dl%elem), s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                model%materials(sec%material), dl, fe, error, element_drill(s, dl%elem))
        else if (dl%kind == DLOAD_TRVEC .or. dl%kind == DLOAD_TRSHR) then
           q_local = 0.0_wp
           call element_traction_load(s%elem_type(dl%elem), s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, dl, fe, error)
        else
           call element_distributed_load(s%elem_type(dl%elem), s%x(:, s%elem_nodes(1:nn, dl%elem)), sec, &
                dl%kind, dl%value, fe, q_local, error)
        end if
      end associate
    end associate
  end subroutine distributed_load

  pure subroutine take_thermal_resultants(etype, x, sec, mat, th, plate, tn, cn, drill)
    !! Take the resultants of the free thermal expansion th(1:2, step) off the
    !! resultants plate(6, step) of a plane or shell element (N = D (ε - ε0));
    !! tn(:, step): the nodal remainders of a varying temperature (plane and
    !! shell elements, plane_thermal_nodal), cn(:, step) those of the
    !! gradient of a shell (shell_thermal_curvature_nodal), if any; drill:
    !! the shell's drilling edge mask.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: th(:, :)
    real(wp), intent(inout) :: plate(:, :)
    real(wp), intent(in), optional :: tn(:, :), cn(:, :)
    integer, intent(in), optional :: drill
    real(wp) :: res0(6), rem(2, size(x, 2))
    type(error_t), allocatable :: error
    integer :: is, n
    logical :: varying
    n = size(x, 2)
    do is = 1, size(th, 2)
       rem = 0.0_wp
       if (present(tn)) rem(1, :) = tn(1:n, is)
       if (present(cn)) rem(2, :) = cn(1:n, is)
       varying = any(rem /= 0.0_wp)
       if (all(th(:, is) == 0.0_wp) .and. .not. varying) cycle
       ! an element that cannot be evaluated has been reported by shell_forces
       if (is_shell8(etype)) then
          if (varying) then
             call s8r_thermal_resultants(sec, mat, th(1, is), th(2, is), res0, n, rem)
          else
             call s8r_thermal_resultants(sec, mat, th(1, is), th(2, is), res0, n)
          end if
       else if (present(tn)) then
          call thermal_plate_resultants(etype, x, sec, mat, th(1, is), th(2, is), res0, error, tn(1:n, is))
          if (allocated(error)) return
       else
          call thermal_plate_resultants(etype, x, sec, mat, th(1, is), th(2, is), res0, error)
          if (allocated(error)) return
       end if
       plate(:, is) = plate(:, is) - res0
       if (is_shell8(etype) .or. is_plane_type(etype) .or. .not. varying) cycle
       ! a shell whose temperature varies: the nodal remainders, interpolated
       call shell_thermal_nodal_resultants(etype, x, sec, mat, rem(1, :), rem(2, :), res0, error, drill)
       if (allocated(error)) return
       plate(:, is) = plate(:, is) - res0
    end do
  end subroutine take_thermal_resultants

  pure subroutine element_body_end_forces(etype, x, sec, mat, dl, f, error)
    !! The end forces f(6, 2) (local axes, per end) of a body load dl on a
    !! bar or beam that its end forces K u - f_eq take off: DLOAD_THERMAL, the
    !! free thermal bending of a beam with a gradient across its section, or
    !! the whole thermal load of a B32 (given by its nodal values
    !! dl%nodes%line_nodal); DLOAD_CENTRIF, the consistent nodal loads of the
    !! centrifugal load in the element's local axes.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), intent(out) :: f(6, 2)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fe(:)
    real(wp) :: r(3, 3), length, g(6)
    integer, allocatable :: dofs(:)
    integer :: a, nd
    f = 0.0_wp
    if (dl%kind == DLOAD_THERMAL) then
       if (has_line_nodal(dl)) then   ! a B32: its whole thermal load
          call beam3_thermal_end_forces(x, sec, mat, dl%nodes%line_nodal, f, error)
       else
          call thermal_beam_end_forces(etype, x, sec, mat, dl%gradient, f, error)
       end if
       return
    end if
    call element_material_load(etype, x, sec, mat, dl, fe, error)
    if (allocated(error)) return
    if (etype == ET_B32) then   ! each end in the frame of its tangent
       call beam3_end_shares(x, sec, fe, f, error)
       return
    end if
    call beam_frame(etype, x, sec, r, length, error)
    if (allocated(error)) return
    dofs = element_node_dofs(etype)
    nd = size(dofs)
    do a = 1, 2
       g = 0.0_wp
       g(dofs) = fe(nd*(a - 1) + 1:nd*a)
       f(1:3, a) = matmul(r, g(1:3))
       f(4:6, a) = matmul(r, g(4:6))
    end do
  end subroutine element_body_end_forces

  subroutine element_strain_energy(model, fields, is, isub, ie, energy, error)
    !! The strain energy ½ u_eᵀ K_e u_e of element ie of substructure isub in
    !! step is (K_e: element_stiffness with the element's drilling mask);
    !! errors as element_stiffness.
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is, isub
    integer(ip), intent(in) :: ie
    real(wp), intent(out) :: energy
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ke(:, :), ue(:)
    integer :: nn
    energy = 0.0_wp
    associate (sub => model%subs(isub))
      nn = ELEMENT_NODE_COUNT(sub%elem_type(ie))
      associate (sec => sub%sections(sub%elem_section(ie)))
        call element_stiffness(sub%elem_type(ie), sub%x(:, sub%elem_nodes(1:nn, ie)), sec, &
             model%materials(sec%material), ke, error, element_drill(sub, ie))
      end associate
    end associate
    if (allocated(error)) return
    call element_displacements(model, fields, is, isub, ie, ue)
    energy = 0.5_wp*dot_product(ue, matmul(ke, ue))
  end subroutine element_strain_energy

  subroutine element_thermal_energy(model, fields, is, dl, energy, error)
    !! The strain energy ½ ∫ (ε - ε_th)ᵀ D (ε - ε_th) dV of the element of the
    !! thermal load dl (DLOAD_THERMAL) in step is, the energy of its mechanical
    !! strains (½ u_eᵀ K_e u_e is not, under thermal strains): a solid by its
    !! stiffness rule with ε_th interpolated from its nodes (solid_thermal_energy,
    !! axisym_thermal_energy); a truss, a two-node beam, a plane or shell
    !! element with a uniform thermal strain (and curvature, gradients) by
    !! ½ (u_e - u_0)ᵀ K_e (u_e - u_0), u_0 the free thermal field, whose strains are ε_th
    !! (plane strain: plus ½ E (α ΔT)² V of the held expansion across the plane).
    !! A B32 by its stiffness rule (beam3_thermal_energy), an S8R or S8 as
    !! ½ u_eᵀ K_e u_e - u_eᵀ f_th + ½ ∫ ε0ᵀ D ε0 dV, all three by the element's own
    !! rules (s8r_thermal_energy), and a plane or other shell element whose
    !! temperature varies over it the same way (area_thermal_energy).
    type(model_t), intent(in) :: model
    type(result_fields_t), intent(in) :: fields
    integer, intent(in) :: is
    type(dload_t), intent(in) :: dl
    real(wp), intent(out) :: energy
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ue(:), u0(:), ke(:, :)
    type(element_traits_t) :: t
    integer :: nn, etype
    energy = 0.0_wp
    etype = model%subs(dl%sub)%elem_type(dl%elem)
    nn = ELEMENT_NODE_COUNT(etype)
    t = element_traits(etype)
    call element_displacements(model, fields, is, dl%sub, dl%elem, ue)
    associate (s => model%subs(dl%sub), x => model%subs(dl%sub)%x(:, model%subs(dl%sub)%elem_nodes(1:nn, dl%elem)))
      associate (sec => s%sections(s%elem_section(dl%elem)))
        associate (mat => model%materials(sec%material))
          if (is_solid_type(etype) .and. .not. has_nodal(dl)) then
             call fatal_error(error, EXIT_DECK, 'thermal load on a solid without its nodal values')
          else if (is_axisym_type(etype)) then
             call axisym_thermal_energy(etype, x, mat, ue, dl%nodes%nodal, energy, error)
          else if (is_3d_solid(etype)) then
             call solid_thermal_energy(etype, x, mat, ue, dl%nodes%nodal, energy, error, sec%axes)
          else if (has_line_nodal(dl)) then
             call beam3_thermal_energy(x, sec, mat, dl%nodes%line_nodal, ue, energy, error)
          else if (is_shell8(etype)) then
             call s8r_thermal_energy(etype, x, sec, mat, dl, ue, energy, error)
          else if ((has_nodal(dl) .or. has_curvature_nodal(dl)) .and. &
               (t%family == FAMILY_PLANE .or. t%family == FAMILY_SHELL)) then
             call area_thermal_energy(etype, x, sec, mat, dl, ue, energy, error, element_drill(s, dl%elem))
          else if (has_nodal(dl) .or. has_curvature_nodal(dl)) then
             call fatal_error(error, EXIT_DECK, 'the strain energy under thermal strains is not implemented for '// &
                  'element type '//trim(t%name)//' with a temperature that varies over it')
          else
             if (t%family == FAMILY_TRUSS .or. t%family == FAMILY_BEAM) then
                call line_free_field(etype, x, sec, mat, dl, u0, error)
             else
                call thermal_free_field(etype, x, mat%nu, dl%value, dl%curvature, u0, error)
             end if
             if (allocated(error)) return
             call element_stiffness(etype, x, sec, mat, ke, error, element_drill(s, dl%elem))
             if (allocated(error)) return
             energy = 0.5_wp*dot_product(ue - u0, matmul(ke, ue - u0))
             ! plane strain: the held expansion across the plane, σ_z = -E α ΔT, adds ½ E (α ΔT)² V,
             ! (1 - 2ν)/(2 (1 + ν)) times the energy ½ u_0ᵀ K_e u_0 of the in-plane free field
             if (t%plane_strain) energy = energy + (1.0_wp - 2.0_wp*mat%nu)/(2.0_wp*(1.0_wp + mat%nu))* &
                  0.5_wp*dot_product(u0, matmul(ke, u0))
          end if
        end associate
      end associate
    end associate
  end subroutine element_thermal_energy

  pure subroutine area_thermal_energy(etype, x, sec, mat, dl, ue, energy, error, drill)
    !! The energy of the mechanical strains of a plane or shell element (S3,
    !! S4, S3R, S4R) whose temperature varies over it (dl%value the mean α ΔT,
    !! dl%curvature the mean α ∂T/∂n, dl%nodes%nodal and %curvature_nodal the nodal
    !! remainders): ½ u_eᵀ K_e u_e - u_eᵀ f_th + c, f_th the consistent load of
    !! the whole nodal field and c its constant (thermal_plane_nodal_load,
    !! shell_thermal_nodal_load), by the rules of the element's stiffness;
    !! drill: the element's drilling mask.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), intent(in) :: ue(:)
    real(wp), intent(out) :: energy
    type(error_t), allocatable, intent(out) :: error
    integer, intent(in) :: drill
    real(wp), allocatable :: fth(:), ke(:, :), strain(:), curvature(:)
    real(wp) :: c
    energy = 0.0_wp
    strain = spread(dl%value, 1, size(x, 2))
    if (has_nodal(dl)) strain = strain + dl%nodes%nodal
    if (element_family(etype) == FAMILY_PLANE) then
       call thermal_plane_nodal_load(etype, x, sec, mat, strain, fth, error, c)
    else
       curvature = spread(dl%curvature, 1, size(x, 2))
       if (has_curvature_nodal(dl)) curvature = curvature + dl%nodes%curvature_nodal
       call shell_thermal_nodal_load(etype, x, sec, mat, strain, curvature, fth, error, drill, c)
    end if
    if (allocated(error)) return
    call element_stiffness(etype, x, sec, mat, ke, error, drill)
    if (allocated(error)) return
    energy = 0.5_wp*dot_product(ue, matmul(ke, ue)) - dot_product(ue, fth) + c
  end subroutine area_thermal_energy

  pure subroutine line_free_field(etype, x, sec, mat, dl, u0, error)
    !! The free thermal field u0 (element ordering) of a truss or two-node beam
    !! under dl: node 2 moved from node 1 by ε_th (x2 - x1), ε_th = dl%value/(E A)
    !! (dl%value = E A α ΔT), and on a beam the free bending of its gradients.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: u0(:)
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: ub(:)
    logical :: mask(6)
    integer :: d, k, nd
    mask = element_dof_mask(etype)
    nd = count(mask)
    allocate (u0(2*nd), source=0.0_wp)
    if (mat%e*sec%area == 0.0_wp) then
       call fatal_error(error, EXIT_DECK, 'thermal strain energy of a bar or beam without E A')
       return
    end if
    k = 0
    do d = 1, 3
       if (.not. mask(d)) cycle
       k = k + 1
       u0(nd + k) = dl%value/(mat%e*sec%area)*(x(d, 2) - x(d, 1))
    end do
    if (element_family(etype) /= FAMILY_BEAM .or. all(dl%gradient == 0.0_wp)) return
    call thermal_beam_free_field(etype, x, sec, dl%gradient, ub, error)
    if (allocated(error)) return
    u0 = u0 + ub
  end subroutine line_free_field

  pure subroutine s8r_thermal_energy(etype, x, sec, mat, dl, ue, energy, error)
    !! The energy of the mechanical strains of a heated S8R or S8 (etype):
    !! ½ u_eᵀ K_e u_e - u_eᵀ f_th + ½ ∫ ε0ᵀ D ε0 dV, the three by the rules of
    !! the stiffness (superjoin_elements_shell8): ½ ∫ (ε - ε0)ᵀ D (ε - ε0) dV.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:)
    type(section_t), intent(in) :: sec
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), intent(out) :: energy
    type(error_t), allocatable, intent(out) :: error
    real(wp), allocatable :: fe(:), ke(:, :)
    real(wp) :: w0
    energy = 0.0_wp
    call s8r_thermal_terms(etype, x, sec, mat, dl, fe, w0, error)
    if (allocated(error)) return
    call element_stiffness(etype, x, sec, mat, ke, error)
    if (allocated(error)) return
    energy = 0.5_wp*dot_product(ue, matmul(ke, ue)) - dot_product(ue, fe) + w0
  end subroutine s8r_thermal_energy

  pure subroutine axisym_centrif_load(etype, x, mat, dl, fe, error)
    !! CENTRIF on an axisymmetric element: the spin axis must be its axis y
    !! (through x = z = 0); the body force ρ ω² r along r.
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :)
    type(material_t), intent(in) :: mat
    type(dload_t), intent(in) :: dl
    real(wp), allocatable, intent(out) :: fe(:)
    type(error_t), allocatable, intent(out) :: error
    if (dl%dir(1) /= 0.0_wp .or. dl%dir(3) /= 0.0_wp .or. dl%point(1) /= 0.0_wp .or. dl%point(3) /= 0.0_wp) then
       call fatal_error(error, EXIT_DECK, 'CENTRIF on an axisymmetric element must spin about its axis '// &
            '(the y axis through x = z = 0)')
       return
    end if
    call axisym_body_load(etype, x, [0.0_wp, 0.0_wp], mat%density*dl%value, fe, error)
  end subroutine axisym_centrif_load

  pure logical function has_axisymmetric(model)
    !! The model has axisymmetric elements (CAX*).
    type(model_t), intent(in) :: model
    integer :: isub
    has_axisymmetric = .false.
    do isub = 1, size(model%subs)
       associate (s => model%subs(isub))
         if (any(is_axisym_type(s%elem_type(1:s%nelem)))) has_axisymmetric = .true.
       end associate
    end do
  end function has_axisymmetric

  pure function ring_nodes(sub) result(on)
    !! Per node of sub: it belongs to an axisymmetric element (CAX*).
    type(substructure_t), intent(in) :: sub
    logical :: on(sub%nnode)
    integer(ip) :: e
    on = .false.
    do e = 1, sub%nelem
       if (is_axisym_type(sub%elem_type(e))) on(sub%elem_nodes(1:ELEMENT_NODE_COUNT(sub%elem_type(e)), e)) = .true.
    end do
  end function ring_nodes

  elemental logical function is_solid_type(etype)
    !! The solids: 3D (C3D*, superjoin_elements_solid) and axisymmetric (CAX*).
    integer, intent(in) :: etype
    is_solid_type = is_3d_solid(etype) .or. is_axisym_type(etype)
  end function is_solid_type

  pure subroutine solid_forces(etype, x, mat, ue, fg, error, axes)
    !! fg(:, step) = K_e ue(:, step) of a solid, 3D or axisymmetric, every step with one element matrix
    !! (axes: the material axes of the section's *ORIENTATION, 3D solids).
    integer, intent(in) :: etype
    real(wp), intent(in) :: x(:, :), ue(:, :)
    type(material_t), intent(in) :: mat
    real(wp), intent(out) :: fg(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(orientation_t), intent(in), optional :: axes
    if (is_axisym_type(etype)) then
       call axisym_forces(etype, x, mat, ue, fg, error)
    else
       call solid_3d_forces(etype, x, mat, ue, fg, error, axes)
    end if
  end subroutine solid_forces

  pure subroutine unsupported(etype, error)
    !! Error for an element type without an implementation.
    integer, intent(in) :: etype
    type(error_t), allocatable, intent(out) :: error
    character(len=12) :: buf
    if (etype >= 1 .and. etype <= NUM_ELEMENT_TYPES) then
       call fatal_error(error, EXIT_DECK, 'element type '//trim(ELEMENT_TYPE_NAMES(etype))// &
            ' is not implemented yet')
    else
       write (buf, '(i0)') etype
       call fatal_error(error, EXIT_DECK, 'unknown element type '//trim(buf))
    end if
  end subroutine unsupported
end module superjoin_elements
