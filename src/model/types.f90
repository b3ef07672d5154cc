module superjoin_model_types
  !! The structural model read from a deck: substructures, materials, sections,
  !! sets, contact elements, supports, load steps and controls.
  !!
  !! Everything is resolved to indices by the deck reader: a node is named by its
  !! substructure index and its local index inside that substructure (1..nnode, in
  !! order of definition); user ids are kept for output only.
  use superjoin_kinds, only: wp, ip
  use superjoin_utils_sorting, only: find_sorted
  implicit none (type, external)
  private

  integer, parameter, public :: ET_T2D2 = 1, ET_T3D2 = 2, ET_B23 = 3, ET_B33 = 4, &
                                ET_CPS3 = 5, ET_CPS4 = 6, ET_S3 = 7, ET_S4 = 8, &
                                ET_B21 = 9, ET_B31 = 10, ET_CPE3 = 11, ET_CPE4 = 12, &
                                ET_S4R = 13, ET_S3R = 14, ET_S8R = 15
    !! Element types (B21, B31: two-node Timoshenko beams; CPE3, CPE4: plane strain;
    !! S4R, S3R, S8R: thick (Reissner-Mindlin) shells).
  integer, parameter, public :: ET_CPS6 = 16, ET_CPS8 = 17, ET_CPE6 = 18, ET_CPE8 = 19, &
                                ET_CPS8R = 20, ET_CPE8R = 21
    !! Second-order plane elements: 6-node triangles, 8-node quadrilaterals (…R: 2×2 reduced integration).
  integer, parameter, public :: ET_B32 = 22
    !! Three-node Timoshenko beam (end, middle, end), curved geometry allowed.
  integer, parameter, public :: ET_C3D8 = 23, ET_C3D20 = 24, ET_C3D20R = 25, ET_C3D4 = 26, ET_C3D10 = 27
    !! 3D solids (superjoin_elements_solid): hexahedra with 8 and 20 nodes (C3D20R: 2×2×2
    !! reduced integration), tetrahedra with 4 and 10 nodes; Abaqus node numbering.
  integer, parameter, public :: ET_C3D8I = 28
    !! The 8-node hexahedron with incompatible modes (Wilson-Taylor, condensed per element).
  integer, parameter, public :: ET_C3D6 = 29, ET_C3D15 = 30
    !! Wedges (triangular prisms) with 6 and 15 nodes; Abaqus node numbering.
  integer, parameter, public :: ET_S8 = 31
    !! The eight-node thick shell with full 3×3 in-plane integration (S8R's nodes and formulation).
  integer, parameter, public :: ET_C3D8R = 32
    !! The 8-node hexahedron with one point and hourglass stiffness (superjoin_elements_solid_reduced).
  integer, parameter, public :: ET_CAX3 = 33, ET_CAX4 = 34, ET_CAX6 = 35, ET_CAX8 = 36, ET_CAX8R = 37
    !! Axisymmetric solids (superjoin_elements_axisym): r = x, axis y; triangles with 3 and 6
    !! nodes, quadrilaterals with 4 and 8 (CAX8R: 2×2 reduced integration).
  integer, parameter, public :: ET_S6 = 38
    !! The six-node triangular thick shell (CalculiX's S6; superjoin_elements_shell8, MITC shear).
  integer, parameter, public :: NUM_ELEMENT_TYPES = 38
  character(len=6), parameter, public :: ELEMENT_TYPE_NAMES(NUM_ELEMENT_TYPES) = &
       ['T2D2  ', 'T3D2  ', 'B23   ', 'B33   ', 'CPS3  ', 'CPS4  ', 'S3    ', 'S4    ', &
        'B21   ', 'B31   ', 'CPE3  ', 'CPE4  ', &
        'S4R   ', 'S3R   ', 'S8R   ', &
        'CPS6  ', 'CPS8  ', 'CPE6  ', 'CPE8  ', 'CPS8R ', 'CPE8R ', 'B32   ', &
        'C3D8  ', 'C3D20 ', 'C3D20R', 'C3D4  ', 'C3D10 ', 'C3D8I ', &
        'C3D6  ', 'C3D15 ', 'S8    ', 'C3D8R ', &
        'CAX3  ', 'CAX4  ', 'CAX6  ', 'CAX8  ', 'CAX8R ', 'S6    ']
    !! A blank name would be a reserved number without an element.
  integer, parameter, public :: ELEMENT_NODE_COUNT(NUM_ELEMENT_TYPES) = [2, 2, 2, 2, 3, 4, 3, 4, &
       2, 2, 3, 4, &
       4, 3, 8, &
       6, 8, 6, 8, 8, 8, 3, &
       8, 20, 20, 4, 10, 8, 6, 15, 8, 8, &
       3, 4, 6, 8, 8, 6]
  integer, parameter, public :: MAX_ELEMENT_NODES = 20
  integer, parameter, public :: MAX_ELEMENT_DOFS = 60
    !! DOFs of the largest element (C3D20: 20 nodes x 3; S8R has 8 x 6).

  integer, parameter, public :: NDOF_NODE = 6
    !! DOFs per node (Abaqus numbering 1 ux, 2 uy, 3 uz, 4 rx, 5 ry, 6 rz).

  integer, parameter, public :: SEC_SOLID = 1, SEC_BEAM = 2, SEC_SHELL = 3
    !! Section kinds.

  integer, parameter, public :: LINK_NONE = 0, LINK_FINITE = 1, LINK_RIGID = 2
    !! State of one DOF of a contact element or support.

  integer, parameter, public :: DLOAD_PX = 1, DLOAD_PY = 2, DLOAD_PZ = 3, DLOAD_P = 4, DLOAD_GRAV = 5
  integer, parameter, public :: DLOAD_P1 = 6, DLOAD_P2 = 7, DLOAD_P3 = 8, DLOAD_P4 = 9
  integer, parameter, public :: DLOAD_THERMAL = 10
    !! Thermal load of a truss or beam (uniform temperature change): value = E A α ΔT, the
    !! axial force it would take to hold the element at its length (from *TEMPERATURE);
    !! of a plane or shell element: value = α ΔT, the free thermal strain (shells: of the
    !! mid-surface, with curvature = α ∂T/∂n through the thickness).
    !! Distributed load kinds (P1..P4: pressure on face k of a plane element; P1, P2 on
    !! beams: load per unit length along local y (n1) and local z (n2), CalculiX's forms).
  integer, parameter, public :: DLOAD_CENTRIF = 11
    !! *DLOAD CENTRIF: value = ω², dir = the unit axis, point = a point of the axis; the load
    !! is ρ ω² r per unit volume, r the distance vector from the axis (consistent mass).
  integer, parameter, public :: DLOAD_P5 = 12, DLOAD_P6 = 13
    !! Pressure on faces 5 and 6 of a solid hexahedron (P1..P4: also its faces 1..4).
  integer, parameter, public :: DLOAD_BX = 14, DLOAD_BY = 15, DLOAD_BZ = 16
    !! Abaqus's body force per unit volume along global x, y, z (value; dir the axis): the
    !! self weight's loads with density 1 (per unit length A, per unit area t).
  integer, parameter, public :: DLOAD_TRVEC = 17, DLOAD_TRSHR = 18
    !! Abaqus's surface tractions (*DSLOAD TRVEC, TRSHR) on face `face` of a solid or a plane
    !! element (0: a shell's surface): value = the traction per unit area, dir = the unit
    !! direction (global axes); TRSHR: dir projected onto the surface at each point, then
    !! made unit (a shear traction).
  character(len=7), parameter, public :: DLOAD_NAMES(18) = ['PX     ', 'PY     ', 'PZ     ', 'P      ', &
       'GRAV   ', 'P1     ', 'P2     ', 'P3     ', 'P4     ', 'TEMP   ', 'CENTRIF', 'P5     ', 'P6     ', &
       'BX     ', 'BY     ', 'BZ     ', 'TRVEC  ', 'TRSHR  ']

  integer, parameter, public :: FORM_TRANSFORM = 1, FORM_PENALTY = 2
    !! Formulation and rigid-link controls.
  integer, parameter, public :: RIGID_ELIMINATE = 1, RIGID_LARGE = 2
  real(wp), parameter, public :: DEFAULT_LARGE = 1.0e12_wp
  real(wp), parameter, public :: DEFAULT_POSITION_TOLERANCE = 1.0e-3_wp
    !! Contact node pairs farther apart than this x the model's size are warned.
  real(wp), parameter, public :: DEFAULT_PENALTY_LARGE = 1.0_wp/sqrt(epsilon(1.0_wp))
    !! LARGE under FORMULATION=PENALTY unless *CONTROLS sets it: 1/sqrt(eps) = 6.7e7, the classic
    !! penalty choice (constraint error and round-off both about sqrt(eps): half the digits survive).

  integer, parameter, public :: CONDENSE_AUTO = 0, CONDENSE_YES = 1, CONDENSE_NO = 2
    !! Static condensation of a substructure's interior DOFs (*SUBSTRUCTURE, CONDENSE=).

  type, public :: string_t
    !! A character string of any length (for arrays of strings).
     character(:), allocatable :: s
  end type string_t

  type, public :: source_loc_t
    !! Where something was written: file index (into model%files) and line.
     integer :: file = 0
     integer :: line = 0
  end type source_loc_t

  type, public :: orientation_t
    !! A local system (*ORIENTATION) of oriented contacts and of the material
    !! axes of solid sections: rows of q are the local axes (rectangular).
     character(:), allocatable :: name
     real(wp) :: q(3, 3) = 0.0_wp
     logical :: cylindrical = .false.      !! SYSTEM=CYLINDRICAL: each link takes its own frame (link_t%q)
     real(wp) :: a(3) = 0.0_wp             !! cylindrical: two points a, b of the axis
     real(wp) :: b(3) = 0.0_wp
     type(source_loc_t) :: loc
  end type orientation_t

  integer, parameter, public :: MAT_ISO = 0, MAT_ORTHO = 1, MAT_ENGINEERING = 2, MAT_ANISO = 3
    !! material_t%kind: *ELASTIC, TYPE=ISO, ORTHO, ENGINEERING CONSTANTS, ANISO.

  type, public :: material_t
    !! Linear elastic material: isotropic (E, nu) or, kind /= MAT_ISO, the
    !! stiffness d in its material axes (Voigt order 11, 22, 33, 12, 13, 23,
    !! engineering shear strains, as Abaqus's D1111 .. D2323).
     character(:), allocatable :: name     !! upper case
     real(wp) :: e = 0.0_wp
     real(wp) :: nu = 0.0_wp
     integer :: kind = MAT_ISO             !! MAT_*
     real(wp) :: given(21) = 0.0_wp        !! anisotropic: the constants as written (9 or 21)
     real(wp) :: d(6, 6) = 0.0_wp          !! anisotropic: the stiffness in material axes
     real(wp) :: density = 0.0_wp         !! mass per unit volume (*DENSITY)
     logical :: has_elastic = .false.
     logical :: has_density = .false.
     real(wp) :: alpha = 0.0_wp           !! thermal expansion coefficient (*EXPANSION)
     logical :: has_expansion = .false.
     type(source_loc_t) :: loc
     real(wp), allocatable :: elastic_table(:, :)    !! (3, n) E, nu, temperature of a temperature-dependent
                                                    !! *ELASTIC (unallocated: e, nu constant); see model/material_table
     real(wp), allocatable :: expansion_table(:, :)  !! (2, n) alpha, temperature of a temperature-dependent *EXPANSION
     real(wp) :: zero = 0.0_wp            !! *EXPANSION, ZERO=: the temperature of no thermal strain (with a table)
     real(wp), allocatable :: at_nodes(:, :)  !! (2, nnode) initial and step temperatures at the nodes of the one
                                              !! solid element of this copy of a material with a table (its
                                              !! values taken at each integration point)
  end type material_t

  type, public :: section_t
    !! A section card assigned to an element set.
     integer :: kind = 0                   !! SEC_SOLID, SEC_BEAM or SEC_SHELL
     integer :: material = 0               !! index into model%materials
     integer :: elset = 0                  !! index into the substructure's elsets
     real(wp) :: area = 0.0_wp             !! trusses and beams
     real(wp) :: iy = 0.0_wp               !! 3D beams (2D beams: I stored in iz)
     real(wp) :: iz = 0.0_wp
     real(wp) :: j = 0.0_wp                !! torsion constant
     real(wp) :: thickness = 0.0_wp        !! plane and shell elements
     real(wp) :: v(3) = [0.0_wp, 0.0_wp, 1.0_wp]  !! beam orientation vector
     logical :: has_v = .false.            !! v given on the card
     real(wp) :: shear_k(2) = 0.0_wp       !! Timoshenko beams: transverse shear stiffness (force) for
                                           !! deflection along local y, z (*TRANSVERSE SHEAR STIFFNESS);
                                           !! 0 = shear_factor × G × A
     real(wp) :: shear_factor = 1.0_wp     !! k of the default shear stiffness k G A
     integer :: nfibre = 0                 !! library beam sections: extreme points for fibre stresses
     real(wp) :: fibre(2, 4) = 0.0_wp      !! their local (y, z) about the centroid
     type(source_loc_t) :: loc
     logical :: nodal_thickness = .false.  !! *SHELL SECTION, NODAL THICKNESS: every node of its elements
                                           !! must have a *NODAL THICKNESS (thickness: 0 until then)
     real(wp), allocatable :: node_thickness(:)  !! S8R with a *NODAL THICKNESS that varies: the
                                           !! thickness at each node of the one element this copy
                                           !! of the section belongs to (element node order);
                                           !! unallocated: `thickness` everywhere
     type(orientation_t), allocatable :: axes  !! *SOLID SECTION, ORIENTATION=: the material axes
                                           !! (unallocated: global axes)
  end type section_t

  type, public :: index_set_t
    !! A named node or element set: local indices in order of definition.
     character(:), allocatable :: name     !! upper case
     integer(ip), allocatable :: items(:)
     integer(ip), allocatable :: print_ranges(:, :)
       !! a node set whose GENERATE ranges pass over undefined ids: the ids
       !! CalculiX's .dat prints for it (every id of a range up to the largest
       !! node id, defined or not), in order, as ranges (first, last, step) in
       !! columns, one id as (id, id, 1), so that a huge sparse range costs one
       !! column; unallocated otherwise
  end type index_set_t

  type, public :: given_matrix_t
    !! A reduced stiffness read from a file (*MATRIX INPUT): dense, symmetric,
    !! on the (node, DOF) pairs listed; in the substructure's own frame (an
    !! instance's copy is turned by its placement). Such a substructure enters
    !! the solution as a condensed part with no interior: K* = k.
     integer(ip), allocatable :: node(:)      !! local node of each matrix row
     integer, allocatable :: dof(:)           !! its DOF 1..6
     real(wp), allocatable :: k(:, :)         !! (n, n)
     character(:), allocatable :: file        !! where it was read (for messages)
  end type given_matrix_t

  type, public :: substructure_t
    !! One substructure: an ordinary finite element model with its own numbering.
     character(:), allocatable :: name     !! upper case; MAIN for the implicit one
     integer(ip) :: nnode = 0
     integer(ip), allocatable :: node_id(:)         !! user id of local node i
     real(wp), allocatable :: x(:, :)               !! (3, nnode) coordinates
     integer(ip) :: nelem = 0
     integer(ip), allocatable :: elem_id(:)         !! user id of local element e
     integer, allocatable :: elem_type(:)           !! ET_* per element
     integer(ip), allocatable :: elem_nodes(:, :)   !! (nodes of its largest element, nelem) local node indices, 0 in unused slots
     integer, allocatable :: elem_section(:)        !! index into sections (0: none)
     integer, allocatable :: elem_drill(:)          !! drilling-membrane edge mask (superjoin_elements_drill_mask)
     type(source_loc_t), allocatable :: elem_loc(:) !! where each element was defined
     type(index_set_t), allocatable :: nsets(:)
     type(index_set_t), allocatable :: elsets(:)
     type(section_t), allocatable :: sections(:)
     integer(ip), allocatable :: node_order(:)      !! local indices sorted by user id
     integer(ip), allocatable :: elem_order(:)      !! local indices sorted by user id
     integer :: condense = CONDENSE_AUTO            !! CONDENSE_* from *SUBSTRUCTURE
     type(source_loc_t) :: loc
     integer :: part = 0                            !! *INSTANCE: index into model%parts (0: plain substructure)
     real(wp) :: rot(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
          0.0_wp, 0.0_wp, 1.0_wp], [3, 3])          !! *INSTANCE placement: x = rot x_part + shift
     real(wp) :: shift(3) = 0.0_wp
     type(given_matrix_t), allocatable :: given     !! *MATRIX INPUT: a stiffness given on its nodes
  end type substructure_t

  type, public :: matrix_export_t
    !! A *SUBSTRUCTURE MATRIX OUTPUT card: write K*, f* of every step and the
    !! boundary DOF map of one condensed substructure.
     integer :: sub = 0                       !! index into model%subs
     integer :: format = 0                    !! EXPORT_* (superjoin_model_types)
     character(:), allocatable :: path        !! FILE NAME= joined to the deck's directory, no extension
     type(source_loc_t) :: loc
     integer(ip), allocatable :: retain(:)    !! RETAIN=: local nodes kept on the boundary (unallocated: none)
  end type matrix_export_t

  integer, parameter, public :: EXPORT_ABAQUS = 1, EXPORT_DMIG = 2, EXPORT_MATRIX_MARKET = 3, &
       EXPORT_CALCULIX = 4
    !! FORMAT= of *SUBSTRUCTURE MATRIX OUTPUT and *MATRIX INPUT.

  type, public :: contact_t
    !! One *CONTACT card.
     character(:), allocatable :: name     !! upper case
     integer :: master_sub = 0             !! substructure indices
     integer :: slave_sub = 0
     integer :: orientation = 0            !! index into model%orientations, 0 = global axes
     logical :: remote = .false.           !! joins nodes at different places on purpose (springs)
     logical :: rigid_offset = .false.     !! OFFSET=RIGID: the slave hangs on a rigid arm from the master
     type(source_loc_t) :: loc
  end type contact_t

  type, public :: link_t
    !! One contact element: a node pair of a *CONTACT card with all its DOFs merged
    !! (several lines for the same pair add up: finite g add, RIGID wins).
    !! DOFs are in the contact frame when the card has an orientation.
     integer :: contact = 0                !! index into model%contacts
     integer(ip) :: master_node = 0        !! local node index in contact%master_sub
     integer(ip) :: slave_node = 0         !! local node index in contact%slave_sub
     integer :: state(NDOF_NODE) = LINK_NONE
     real(wp) :: g(NDOF_NODE) = 0.0_wp
     type(source_loc_t) :: loc             !! first line that defined it
     logical :: has_q = .false.            !! its own frame q (cylindrical orientation), not the card's
     real(wp) :: q(3, 3) = 0.0_wp          !! rows: radial, tangential, axial at the pair's midpoint
  end type link_t

  type, public :: support_t
    !! One supported DOF of one node (a contact element to the ground).
     integer :: sub = 0
     integer(ip) :: node = 0
     integer :: dof = 0
     integer :: state = LINK_RIGID         !! LINK_RIGID or LINK_FINITE
     real(wp) :: g = 0.0_wp                !! stiffness when finite
     real(wp) :: value = 0.0_wp            !! prescribed displacement when rigid
     type(source_loc_t) :: loc
     logical :: from_boundary = .false.    !! written on *BOUNDARY (OP=NEW in a step removes it), not *SUPPORT
     integer :: held_from = 0
       !! *BOUNDARY, FIXED in a later step: value is the displacement of step held_from, along the
       !! DOF's own axis (analysis/driver fills it in once that step is solved); 0: value as written
  end type support_t

  type, public :: equation_t
    !! One *EQUATION: sum_i coef(i) u(node(i), dof(i)) = 0; the first term's DOF is
    !! the dependent one (eliminated).
     integer, allocatable :: sub(:)
     integer(ip), allocatable :: node(:)
     integer, allocatable :: dof(:)
     real(wp), allocatable :: coef(:)
     type(source_loc_t) :: loc             !! the line with the number of terms
     integer :: tie = 0                    !! made by *TIE number tie (0: an *EQUATION): dropped, not an
                                           !! error, where its dependent DOF is already dependent
     logical :: coupling = .false.
       !! written by *COUPLING, *RIGID BODY or *MPC (superjoin_deck_coupling_build): its DOFs are
       !! activated, and when its first DOF is already dependent another of its columns is eliminated
     logical :: torque_node = .false.
       !! an *MPC MEANROT: its last term is the extra node's DOF 1 (the mean rotation), whose CalculiX
       !! "forces" are its support reaction alone (the torque)
  end type equation_t

  type, public :: node_frame_t
    !! A nodal system (*TRANSFORM): rows of q are the local axes of the node;
    !! its *BOUNDARY/*SUPPORT DOFs and *CLOAD components are in these axes.
     integer :: sub = 0
     integer(ip) :: node = 0
     real(wp) :: q(3, 3) = 0.0_wp
     type(source_loc_t) :: loc             !! the *TRANSFORM card
  end type node_frame_t

  type, public :: cload_t
    !! A concentrated load on one DOF of one node.
     integer :: sub = 0
     integer(ip) :: node = 0
     integer :: dof = 0
     real(wp) :: value = 0.0_wp
     type(source_loc_t) :: loc
  end type cload_t

  type, public :: dload_nodes_t
    !! The nodal values of a thermal load (TEMP) that varies over its element.
     real(wp), allocatable :: nodal(:)     !! TEMP: α ΔT at each node, interpolated to the points; on a plane
                                           !! or shell element minus value (the element mean), on a solid whole
     real(wp), allocatable :: curvature_nodal(:)  !! TEMP on a shell whose nodes differ: α ∂T/∂n at each node
                                           !! minus curvature (allocated with nodal, which a shell then has too)
     real(wp), allocatable :: line_nodal(:, :)  !! TEMP on a B32: α ΔT, α ∂T/∂y, α ∂T/∂z (local axes) at each
                                           !! of its three nodes (rows 1:3, columns nodes; value = 0)
  end type dload_nodes_t

  type, public :: dload_t
    !! A distributed load on one element. A model holds one per loaded element
    !! and step (121 656 on the 1e6 `long` frame): the nodal values of the rare
    !! varying TEMP sit behind one allocatable component (8 bytes where the
    !! three arrays' descriptors took 216 in every load).
     integer :: sub = 0
     integer(ip) :: elem = 0
     integer :: kind = 0                   !! DLOAD_*
     real(wp) :: value = 0.0_wp            !! GRAV: the acceleration
     real(wp) :: dir(3) = 0.0_wp           !! GRAV, TRVEC, TRSHR: unit direction, global axes
     real(wp) :: point(3) = 0.0_wp         !! CENTRIF: a point of the axis (dir: the unit axis)
     integer :: face = 0                   !! TRVEC, TRSHR: the face (solids), edge (plane elements), 0 on shells
     real(wp) :: curvature = 0.0_wp        !! TEMP on a shell: α ∂T/∂n, the thermal curvature
     real(wp) :: gradient(2, 2) = 0.0_wp   !! TEMP on a beam: α ∂T/∂y, α ∂T/∂z (local axes), the thermal
                                           !! curvatures, at its node 1 and node 2 (linear in between)
     type(dload_nodes_t), allocatable :: nodes  !! TEMP varying over the element (unallocated: uniform)
     type(source_loc_t) :: loc
  end type dload_t

  type, public :: link_override_t
    !! *CHANGE CONTACT in a step: new states of some DOFs of one link, for that step only.
     integer :: link = 0                   !! index into model%links
     logical :: dofs(NDOF_NODE) = .false.  !! DOFs that change
     integer :: state(NDOF_NODE) = LINK_NONE
     real(wp) :: g(NDOF_NODE) = 0.0_wp
  end type link_override_t

  type, public :: node_values_t
    !! One value per node of a substructure.
     real(wp), allocatable :: v(:)
  end type node_values_t

  type, public :: step_t
    !! A load case.
     character(:), allocatable :: name     !! as written (upper-cased)
     type(cload_t), allocatable :: cloads(:)
     type(dload_t), allocatable :: dloads(:)
     type(source_loc_t) :: loc
     type(link_override_t), allocatable :: link_overrides(:)  !! *CHANGE CONTACT (unallocated or empty: none)
     integer :: combination = 0            !! results of model%combinations(k), no solve (0: a solved step)
     type(support_t), allocatable :: supports(:)  !! supports in effect in this step when some step has a
                                                  !! *BOUNDARY of its own (unallocated: model%supports)
     logical :: procedure_card = .false.   !! the step has *STATIC (written for CalculiX/Abaqus: its
                                           !! loads continue the previous step's, shell P along the normal)
     integer :: kept_cloads = 0            !! concentrated loads continued from the previous step
     integer :: kept_dloads = 0            !! distributed loads continued from the previous step
     integer :: kept_mloads = 0            !! *MATRIX LOAD lines continued from the previous step
     logical :: kept_temperatures = .false.  !! nodal temperatures continued from the previous step
     character(:), allocatable :: kept_from  !! the step whose loads or temperatures it continues
     type(node_values_t), allocatable :: temperature(:)  !! per substructure: the nodal temperatures of
                                           !! the step (*INITIAL CONDITIONS / *TEMPERATURE; unallocated: none
                                           !! in the model, all 0), for *NODE PRINT NT
     real(wp) :: period = 1.0_wp           !! its time period (*STATIC's data line; 1 without one)
     real(wp) :: total_time = 0.0_wp       !! the total time at its end (0: not set, a combination)
  end type step_t

  type, public :: combination_t
    !! *LOAD COMBINATION (superjoin): results as Σ factor × results of solved steps.
     character(:), allocatable :: name     !! upper case
     integer, allocatable :: steps(:)      !! indices into model%steps (solved steps)
     real(wp), allocatable :: factors(:)
     type(source_loc_t) :: loc
  end type combination_t

  integer, parameter, public :: REQ_NODE_PRINT = 1, REQ_EL_PRINT = 2, REQ_NODE_FILE = 3, REQ_EL_FILE = 4
    !! Kinds of output requests (CalculiX groups: *NODE OUTPUT counts as *NODE FILE,
    !! *ELEMENT OUTPUT as *EL FILE).
  integer, parameter, public :: NUM_REQ_KINDS = 4
  character(len=11), parameter, public :: REQ_KIND_NAMES(NUM_REQ_KINDS) = &
       ['*NODE PRINT', '*EL PRINT  ', '*NODE FILE ', '*EL FILE   ']
  integer, parameter, public :: TOTALS_NO = 0, TOTALS_YES = 1, TOTALS_ONLY = 2
    !! TOTALS= of a print request.

  type, public :: output_request_t
    !! One output request card (*NODE PRINT, *EL PRINT, *NODE FILE, *EL FILE,
    !! *NODE OUTPUT, *ELEMENT OUTPUT). CalculiX scoping: the requests of a kind
    !! written in a step replace those of earlier steps; a step without a request
    !! of that kind keeps the previous step's (step 0: written outside *STEP,
    !! the default of every step).
     integer :: kind = 0                   !! REQ_*
     character(:), allocatable :: card     !! the keyword as written (upper case, with '*')
     integer :: step = 0                   !! index into model%steps; 0: outside *STEP
     integer :: sub = 0                    !! substructure of the set; 0: the whole model
     character(:), allocatable :: set_name !! NSET= / ELSET= (upper case), unallocated: all
     integer(ip), allocatable :: items(:)  !! local node or element indices in sub (with a set)
     integer(ip), allocatable :: print_ranges(:, :)  !! the node set's index_set_t%print_ranges (CalculiX's .dat rows)
     integer :: totals = TOTALS_NO         !! TOTALS_*
     type(string_t), allocatable :: vars(:)     !! variables superjoin produces (upper case)
     type(string_t), allocatable :: ignored(:)  !! variables it knows but cannot produce (thermal, plastic...)
     logical :: global = .false.           !! *NODE PRINT, GLOBAL=YES: nodes with a *TRANSFORM in global axes too
     type(source_loc_t) :: loc
  end type output_request_t

  type, public :: section_print_t
    !! One *SECTION PRINT card: the resultant of the stresses over the element
    !! faces of a *SURFACE (solids), CalculiX's SOF, SOM, SOAREA. Scoped as the
    !! print requests (a step's cards replace those of earlier steps).
     character(:), allocatable :: name     !! NAME= (upper case)
     character(:), allocatable :: surface  !! SURFACE= (upper case)
     integer :: step = 0                   !! index into model%steps
     integer, allocatable :: subs(:)       !! per face: substructure,
     integer(ip), allocatable :: elems(:)  !! local element index,
     integer, allocatable :: faces(:)      !! face number (S1..S6 as 1..6)
     type(source_loc_t) :: loc
  end type section_print_t

  integer, parameter, public :: DIALECT_NONE = 0, DIALECT_ABAQUS = 1, DIALECT_CALCULIX = 2
    !! *CONTROLS, DIALECT=: none declared (Abaqus's reading, with a note), ABAQUS or CALCULIX.

  type, public :: controls_t
    !! Analysis controls from *CONTROLS.
     integer :: formulation = FORM_TRANSFORM
     integer :: rigid = RIGID_ELIMINATE
     real(wp) :: large = DEFAULT_LARGE
     logical :: large_given = .false.      !! LARGE= given on *CONTROLS
     real(wp) :: position_tolerance = DEFAULT_POSITION_TOLERANCE  !! POSITION TOLERANCE= (relative)
     integer :: dialect = DIALECT_NONE     !! DIALECT= (DIALECT_*): whose reading where Abaqus and CalculiX differ
  end type controls_t

  type, public :: model_t
    !! The whole model.
     type(string_t), allocatable :: files(:)        !! deck and included files, as given
     type(string_t), allocatable :: heading(:)
     type(material_t), allocatable :: materials(:)
     type(substructure_t), allocatable :: subs(:)
     type(orientation_t), allocatable :: orientations(:)
     type(contact_t), allocatable :: contacts(:)
     type(link_t), allocatable :: links(:)
     type(support_t), allocatable :: supports(:)
     type(step_t), allocatable :: steps(:)
     type(controls_t) :: controls
     character(:), allocatable :: vtk_path          !! *OUTPUT, VTK= joined to its deck file's directory, or unallocated
     type(string_t), allocatable :: parts(:)        !! *PART names; subs(i)%part indexes this list
     type(output_request_t), allocatable :: requests(:)  !! output request cards in order (empty: full output)
     type(combination_t), allocatable :: combinations(:) !! *LOAD COMBINATION cards (unallocated: none)
     type(section_print_t), allocatable :: section_prints(:)  !! *SECTION PRINT cards (unallocated: none)
     type(equation_t), allocatable :: equations(:)  !! *EQUATION constraints (unallocated or empty: none)
     type(node_frame_t), allocatable :: frames(:)   !! *TRANSFORM nodal systems (unallocated or empty: none)
     type(matrix_export_t), allocatable :: exports(:)  !! *SUBSTRUCTURE MATRIX OUTPUT cards (unallocated: none)
     type(string_t), allocatable :: notes(:)        !! the reader's notes for the listing (which reading of a
                                                    !! card it took where Abaqus and CalculiX differ)
     integer, allocatable :: rot_sub(:)             !! *RIGID BODY, ROT NODE=: the substructure of each (unallocated: none)
     integer(ip), allocatable :: rot_node(:)        !! and its local node, whose DOFs 1-3 are the body's rotations
                                                    !! (a force there is a moment, superjoin_analysis_recover)
  end type model_t

  public :: find_node, find_elem, node_label, loc_text, step_total_time, frame_of_node
  public :: has_nodal, has_curvature_nodal, has_line_nodal

contains

  pure logical function has_nodal(dl)
    !! dl carries α ΔT at each node of its element (dl%nodes%nodal).
    type(dload_t), intent(in) :: dl
    has_nodal = .false.
    if (allocated(dl%nodes)) has_nodal = allocated(dl%nodes%nodal)
  end function has_nodal

  pure logical function has_curvature_nodal(dl)
    !! dl carries α ∂T/∂n at each node of its shell (dl%nodes%curvature_nodal).
    type(dload_t), intent(in) :: dl
    has_curvature_nodal = .false.
    if (allocated(dl%nodes)) has_curvature_nodal = allocated(dl%nodes%curvature_nodal)
  end function has_curvature_nodal

  pure logical function has_line_nodal(dl)
    !! dl carries a B32's nodal thermal strains and curvatures (dl%nodes%line_nodal).
    type(dload_t), intent(in) :: dl
    has_line_nodal = .false.
    if (allocated(dl%nodes)) has_line_nodal = allocated(dl%nodes%line_nodal)
  end function has_line_nodal

  pure function find_node(sub, id) result(k)
    !! Local index of the node with user id `id` in `sub`, or 0.
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: id
    integer(ip) :: k
    k = id_at_own_place(sub%node_id, id)
    if (k == 0) k = find_sorted(sub%node_id, sub%node_order, id)
  end function find_node

  pure function find_elem(sub, id) result(k)
    !! Local index of the element with user id `id` in `sub`, or 0.
    type(substructure_t), intent(in) :: sub
    integer(ip), intent(in) :: id
    integer(ip) :: k
    k = id_at_own_place(sub%elem_id, id)
    if (k == 0) k = find_sorted(sub%elem_id, sub%elem_order, id)
  end function find_elem

  pure function id_at_own_place(ids, id) result(k)
    !! `id` when entry id of `ids` holds it (ids numbered 1, 2, ... in the order
    !! they are defined, as generated decks write them: no search), else 0.
    !! Ids are unique in a model that is solved, so this is the entry the
    !! search would find.
    integer(ip), intent(in) :: ids(:)
    integer(ip), intent(in) :: id
    integer(ip) :: k
    k = 0
    if (id < 1 .or. id > size(ids, kind=ip)) return
    if (ids(id) == id) k = id
  end function id_at_own_place

  pure real(wp) function step_total_time(model, is) result(t)
    !! The total time at the end of step is, as CalculiX prints it (.dat,
    !! .frd, .sta): the time periods of the steps so far (*STATIC, TIME RESET:
    !! not advanced); a step without one (a combination) its number.
    type(model_t), intent(in) :: model
    integer, intent(in) :: is
    t = model%steps(is)%total_time
    if (.not. (t > 0.0_wp)) t = real(is, wp)
  end function step_total_time

  pure integer function frame_of_node(model, isub, node) result(k)
    !! Index of the nodal system (*TRANSFORM) of node `node` of substructure
    !! isub in model%frames, 0 if it has none (a node has at most one:
    !! superjoin_deck_frame_build refuses a second).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: node
    if (allocated(model%frames)) then
       do k = 1, size(model%frames)
          if (model%frames(k)%sub == isub .and. model%frames(k)%node == node) return
       end do
    end if
    k = 0
  end function frame_of_node

  pure function node_label(model, isub, inode) result(label)
    !! "SUB.id" label of a node for messages (plain id in MAIN).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer(ip), intent(in) :: inode
    character(:), allocatable :: label
    character(len=12) :: buf
    write (buf, '(i0)') model%subs(isub)%node_id(inode)
    if (model%subs(isub)%name == 'MAIN') then
       label = trim(buf)
    else
       label = model%subs(isub)%name//'.'//trim(buf)
    end if
  end function node_label

  pure function loc_text(model, loc) result(text)
    !! "file:line" of a source location.
    type(model_t), intent(in) :: model
    type(source_loc_t), intent(in) :: loc
    character(:), allocatable :: text
    character(len=12) :: buf
    write (buf, '(i0)') loc%line
    if (loc%file >= 1 .and. loc%file <= size(model%files)) then
       text = model%files(loc%file)%s//':'//trim(buf)
    else
       text = '<input>:'//trim(buf)
    end if
  end function loc_text
end module superjoin_model_types
