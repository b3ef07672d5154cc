module superjoin_deck_records
  !! The records of the deck reader's state: each card as the parser read it
  !! (still by user ids and names), with the constants that describe them.
  !! superjoin_deck_state collects them (and passes them on to its users).
  use superjoin_kinds, only: wp, ip
  use superjoin_model_types, only: string_t, source_loc_t, NDOF_NODE, LINK_NONE
  implicit none (type, external)
  private

  integer, parameter, public :: SHAPE_GENERAL = 100
    !! sec_b_t%shape of *BEAM GENERAL SECTION, SECTION=GENERAL (A, I11, I12, I22, J).
  integer, parameter, public :: BEAM_2D_VALUES = 2, BEAM_3D_VALUES = 4
    !! Numbers on the first data line of *BEAM SECTION: A, I (2D) or A, Iy, Iz, J (3D).

  integer, parameter, public :: CH_IDS = 1    !! explicit ids: pool(start:start+count-1)
    !! Kinds of set chunks (one data line or one card's worth of set members).
  integer, parameter, public :: CH_GEN = 2    !! GENERATE first, last, inc
  integer, parameter, public :: CH_RANGE = 3  !! local indices start..start+count-1 (*NODE, NSET= / *ELEMENT, ELSET=)
  integer, parameter, public :: CH_REF = 4    !! all members of another set of the same kind

  type, public :: chunk_t
    !! Part of the definition of a node or element set, in order of definition.
     integer :: set = 0                    !! index into nsets or elsets
     logical :: elem = .false.             !! an element set chunk
     integer :: kind = 0                   !! CH_*
     integer :: start = 0
     integer :: count = 0
     integer(ip) :: gen(3) = 0             !! first, last, increment
     character(:), allocatable :: ref      !! referenced set name (CH_REF)
     type(source_loc_t) :: loc
  end type chunk_t

  type, public :: set_b_t
    !! A named set of a substructure (its members are in chunks).
     character(:), allocatable :: name
     type(source_loc_t) :: loc
     integer :: order = 0   !! rank of its first card among the assembly-level (INSTANCE=) set cards; 0: other sets
  end type set_b_t

  type, public :: given_b_t
    !! A *MATRIX INPUT as read (superjoin_deck_matrix_input): its entries by
    !! user node ids, each with the line of the matrix file that gave it.
     integer :: file = 0                            !! the matrix file (index into the deck's files)
     character(:), allocatable :: format            !! FORMAT= (ABAQUS, CALCULIX, DMIG, MATRIX MARKET)
     type(source_loc_t) :: loc                      !! the card
     integer :: n = 0
     integer(ip), allocatable :: rnode(:), cnode(:)
     integer, allocatable :: rdof(:), cdof(:), line(:)
     real(wp), allocatable :: val(:)
  end type given_b_t

  type, public :: export_b_t
    !! A *SUBSTRUCTURE MATRIX OUTPUT card as read.
     character(:), allocatable :: sub               !! SUBSTRUCTURE= (upper case)
     integer :: format = 0                          !! EXPORT_* (model types)
     character(:), allocatable :: path              !! FILE NAME= joined to its file's directory
     type(source_loc_t) :: loc
     character(:), allocatable :: retain            !! RETAIN= node set (upper case; unallocated: none)
  end type export_b_t

  type, public :: sub_b_t
    !! A substructure as read: user ids, coordinates, element connectivity by user ids.
     character(:), allocatable :: name
     type(source_loc_t) :: loc
     integer :: condense = 0                        !! CONDENSE_* (model types)
     integer(ip) :: nnode = 0
     integer :: node_lines = 0                      !! *NODE data lines seen (valid or not)
     integer(ip), allocatable :: node_id(:)
     real(wp), allocatable :: x(:, :)
     type(source_loc_t), allocatable :: node_loc(:)
     integer(ip) :: nelem = 0
     integer(ip), allocatable :: elem_id(:)
     integer, allocatable :: elem_type(:)
     integer(ip), allocatable :: elem_nid(:, :)    !! user node ids
     type(source_loc_t), allocatable :: elem_loc(:)
     integer, allocatable :: elem_card(:)          !! which *ELEMENT card (global counter)
     integer :: nnset = 0, nelset = 0
     type(set_b_t), allocatable :: nsets(:), elsets(:)
     integer :: nchunk = 0
     type(chunk_t), allocatable :: chunks(:)
     integer :: npool = 0
     integer(ip), allocatable :: pool(:)
     integer :: kind = 0                            !! SUBK_PLAIN, SUBK_PART or SUBK_INSTANCE
     integer :: inst = 0                            !! SUBK_INSTANCE: index into instances
     logical :: broken = .false.
       !! an instance of an undefined part: references into it are not reported again
     type(given_b_t), allocatable :: given          !! *MATRIX INPUT of the block
  end type sub_b_t


  type, public :: ref_t
    !! A node/element reference as written: `id`, `set`, `SUB.id` or `SUB.set`.
     character(:), allocatable :: scope    !! substructure name when written with a dot
     integer :: home = 0                   !! substructure of a plain reference (0: MAIN by name)
     logical :: is_set = .false.
     integer(ip) :: id = 0
     character(:), allocatable :: set
  end type ref_t

  type, public :: sec_b_t
    !! A section card.
     integer :: kind = 0
     type(ref_t) :: elset                  !! is_set, set = elset name
     character(:), allocatable :: material
     integer :: nval = 0
     real(wp) :: val(4) = 0.0_wp
     logical :: has_v = .false.
     real(wp) :: v(3) = [0.0_wp, 0.0_wp, 1.0_wp]
     logical :: has_ks = .false.           !! *TRANSVERSE SHEAR STIFFNESS given
     integer :: nks = 0                    !! values given (K23 [, K13])
     real(wp) :: ks(2) = 0.0_wp            !! K23, K13 as written
     type(source_loc_t) :: ks_loc
     integer :: ndata = 0
     logical :: data_ok = .true.
     logical :: nodal_thickness = .false.  !! *SHELL SECTION, NODAL THICKNESS: every node has a *NODAL THICKNESS
     type(source_loc_t) :: loc, data_loc
     integer :: shape = 0                  !! SHAPE_* of superjoin_deck_beam_sections, SHAPE_GENERAL, 0: A, I data
     real(wp) :: sp(5) = 0.0_wp            !! its A, I11, I22, I12, J (section axes 1, 2)
     integer :: ndims = 0                  !! library shape: number of dimensions on its data line
     real(wp) :: dims(7) = 0.0_wp          !! library shape: the dimensions (for the fibre points)
     logical :: five_general = .false.     !! *BEAM SECTION, SECTION=GENERAL with CalculiX's five values
     character(:), allocatable :: orientation  !! *SOLID SECTION, ORIENTATION= (upper case; unallocated: none)
     character(:), allocatable :: controls     !! CONTROLS= (a *SECTION CONTROLS name, upper case; unallocated: none)
  end type sec_b_t

  type, public :: sec_controls_b_t
    !! A *SECTION CONTROLS card (Abaqus): its name and where it stands.
     character(:), allocatable :: name
     type(source_loc_t) :: loc
  end type sec_controls_b_t

  type, public :: contact_b_t
    !! A *CONTACT card.
     character(:), allocatable :: name, master, slave, orientation
     type(source_loc_t) :: loc
     logical :: nearest = .false.          !! PAIR=NEAREST: slave nodes take the nearest master node
     logical :: remote = .false.           !! joins nodes at different places on purpose (springs)
     logical :: rigid_offset = .false.     !! OFFSET=RIGID (eccentric contact)
     real(wp) :: tol = 0.0_wp              !! TOL= of PAIR=NEAREST (*INTERFACE: < 0 until set)
     logical :: is_interface = .false.     !! an *INTERFACE card (Goodman joint)
     real(wp) :: kn = 0.0_wp, kt = 0.0_wp  !! *INTERFACE: stiffness per unit length or area
     type(ref_t) :: iface_master, iface_slave   !! *INTERFACE: its data line (master nset, slave nset)
     type(source_loc_t) :: iface_loc       !! *INTERFACE: the data line (line 0: none)
     integer :: owner = 0                  !! the *PART holding it (index in subs; 0: none)
  end type contact_b_t

  type, public :: cline_b_t
    !! One data line of a *CONTACT card.
     integer :: contact = 0
     type(ref_t) :: master, slave
     integer :: first = 0, last = 0
     integer :: state = LINK_NONE
     real(wp) :: g = 0.0_wp
     type(source_loc_t) :: loc
  end type cline_b_t

  type, public :: equation_b_t
    !! One *EQUATION as read: the number of terms, then (node, dof, coefficient) terms.
     integer :: nterm = 0                  !! terms announced
     integer :: n = 0                      !! terms read
     type(ref_t), allocatable :: node(:)
     integer, allocatable :: dof(:)
     real(wp), allocatable :: coef(:)
     type(source_loc_t), allocatable :: term_loc(:)
     type(source_loc_t) :: loc             !! the line with the number of terms
     logical :: ok = .true.                !! every term was read
  end type equation_b_t

  type, public :: transform_b_t
    !! A *TRANSFORM card: nodal systems of a node set.
     type(ref_t) :: nset
     logical :: cylindrical = .false.      !! TYPE=C (else TYPE=R)
     real(wp) :: a(3) = 0.0_wp, b(3) = 0.0_wp
     logical :: has_data = .false.
     type(source_loc_t) :: loc
  end type transform_b_t

  type, public :: nthick_b_t
    !! One data line of *NODAL THICKNESS: node or node set, thickness.
     type(ref_t) :: node
     real(wp) :: t = 0.0_wp
     type(source_loc_t) :: loc
  end type nthick_b_t

  type, public :: support_b_t
    !! One data line of *SUPPORT or *BOUNDARY.
     type(ref_t) :: ref
     logical :: dofs(NDOF_NODE) = .false.
     integer :: state = 0
     real(wp) :: g = 0.0_wp
     real(wp) :: value = 0.0_wp
     type(source_loc_t) :: loc
     integer :: step = 0                   !! *BOUNDARY inside *STEP: the step (0: model data)
     logical :: boundary = .false.         !! written on *BOUNDARY (not *SUPPORT)
     logical :: held = .false.             !! *BOUNDARY, FIXED: held at the previous step's displacements
  end type support_b_t

  type, public :: load_b_t
    !! One data line of *CLOAD (node) or *DLOAD (element).
     type(ref_t) :: ref
     integer :: dof = 0                    !! *CLOAD
     integer :: kind = 0                   !! *DLOAD
     real(wp) :: value = 0.0_wp
     real(wp) :: dir(3) = 0.0_wp           !! *DLOAD GRAV: unit direction (CENTRIF: unit axis)
     real(wp) :: point(3) = 0.0_wp         !! *DLOAD CENTRIF: a point of the axis
     integer :: face = 0                   !! *DSLOAD TRVEC, TRSHR: the face (solids), edge (plane elements), 0 on shells
     logical :: surface = .false.          !! from a *DSLOAD on a *SURFACE (for messages)
     logical :: whole_model = .false.      !! *DLOAD GRAV with an empty first field
     integer :: home = 0                   !! its substructure block (0: the whole model)
     type(source_loc_t) :: loc
  end type load_b_t

  character(*), parameter, public :: MAIN_NAME = 'MAIN'
    !! The substructure that holds what a deck writes outside *SUBSTRUCTURE and *PART blocks
    !! (an *ASSEMBLY's own nodes, elements and sets).
  integer, parameter, public :: SUBK_PLAIN = 0, SUBK_PART = 1, SUBK_INSTANCE = 2, SUBK_NESTED = 3
    !! SUBK_NESTED: an *INSTANCE inside a *PART (a template, flattened by superjoin_deck_nesting)
    !! or an instance of a part that holds only instances (no substructure of its own).
    !! Kinds of entries of deck_state_t%subs: a substructure, a *PART (a mesh that
    !! is only placed through instances), an *INSTANCE (filled from its part).

  type, public :: instance_b_t
    !! An *INSTANCE card: the part it places and the placement x' = rot x + shift.
     character(:), allocatable :: part      !! part name (upper case)
     integer :: sub = 0                     !! its entry in subs
     integer :: owner = 0                   !! the *PART holding it (index in subs; 0: the assembly)
     integer :: ndata = 0                   !! data lines read (translation, rotation)
     logical :: ok = .true.                 !! data lines valid
     real(wp) :: rot(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
          0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
     real(wp) :: shift(3) = 0.0_wp
     type(source_loc_t) :: loc
  end type instance_b_t

  type, public :: override_b_t
    !! One data line of *CHANGE CONTACT in a step: master, slave, first dof, last
    !! dof and one stiffness (several in a SWEEP: one per expanded step).
     integer :: contact = 0                 !! index into contacts (0: unknown, reported, or not resolved yet)
     logical :: whole = .false.             !! the line names the contact: every pair of it (no master, slave)
     character(:), allocatable :: path      !! the contact by instance path (`B.F3.J1`), or a part's contact
                                            !! by its own name: resolved once the parts are unfolded
                                            !! (superjoin_deck_change_paths; contact = 0 until then)
     character(:), allocatable :: part      !! PART=: path is the part's own, changed in each instance of the part
     logical :: named = .false.             !! path comes from the card's NAME= (reported at card_loc, once)
     type(source_loc_t) :: card_loc         !! the *CHANGE CONTACT keyword line
     type(ref_t) :: master, slave
     integer :: first = 0, last = 0
     integer, allocatable :: states(:)      !! LINK_* per value
     real(wp), allocatable :: gs(:)         !! g per value
     type(source_loc_t) :: loc
  end type override_b_t

  type, public :: mload_b_t
    !! One data line of *MATRIX LOAD: substructure or instance, load name, magnitude.
     character(:), allocatable :: sub      !! substructure or instance (upper case)
     character(:), allocatable :: load     !! load name as written
     real(wp) :: scale = 1.0_wp
     type(source_loc_t) :: loc
  end type mload_b_t

  type, public :: step_b_t
    !! A step as read.
     character(:), allocatable :: name
     type(source_loc_t) :: loc
     integer :: ncload = 0, ndload = 0
     type(load_b_t), allocatable :: cloads(:), dloads(:)
     integer :: nmload = 0
     type(mload_b_t), allocatable :: mloads(:)         !! *MATRIX LOAD lines (superjoin_deck_matrix_loads)
     integer :: noverride = 0
     type(override_b_t), allocatable :: overrides(:)   !! *CHANGE CONTACT lines
     integer :: nsweep = 0                             !! SWEEP: number of values (0: no sweep)
     type(source_loc_t) :: sweep_loc
     logical :: has_boundary = .false.                 !! a *BOUNDARY card stands in the step
     integer :: bc_op = 0, cload_op = 0, dload_op = 0  !! OP= of its *BOUNDARY, *CLOAD, *DLOAD cards (OP_*)
     integer :: temp_op = 0                            !! OP= of its *TEMPERATURE cards (OP_*)
     integer :: mload_op = 0                           !! OP= of its *MATRIX LOAD cards (OP_*)
     logical :: has_procedure = .false.               !! a procedure card (*STATIC) stands in the step
     logical :: perturbation = .false.                !! *STEP, PERTURBATION (its loads are its own)
     real(wp) :: period = 1.0_wp                      !! time period of *STATIC's data line (amplitudes)
     logical :: time_reset = .false.                  !! *STATIC, TIME RESET: the total time does not advance
  end type step_b_t

  integer, parameter, public :: AMP_TABULAR = 1, AMP_EQUALLY_SPACED = 2, AMP_SMOOTH_STEP = 3
    !! DEFINITION= of *AMPLITUDE.

  type, public :: amplitude_b_t
    !! An *AMPLITUDE: a function of time a(t) by which the cards that name it
    !! (AMPLITUDE= on *CLOAD, *DLOAD, *DSLOAD, *BOUNDARY) scale their values;
    !! a linear static step takes its value at the end of the step.
     character(:), allocatable :: name
     integer :: definition = AMP_TABULAR
     logical :: total_time = .false.       !! TIME=TOTAL TIME (else the step time)
     real(wp) :: interval = 0.0_wp         !! EQUALLY SPACED: FIXED INTERVAL=
     real(wp) :: begin = 0.0_wp            !! EQUALLY SPACED: BEGIN=
     real(wp), allocatable :: t(:), a(:)   !! the points (EQUALLY SPACED: t from interval and begin)
     integer :: nlines = 0                 !! its data lines, those with a mistake included
     type(source_loc_t) :: loc
  end type amplitude_b_t

  type, public :: amp_use_b_t
    !! A data line of a card with AMPLITUDE=: what it writes is scaled by that amplitude.
     type(source_loc_t) :: line
     type(source_loc_t) :: card
     character(:), allocatable :: name
  end type amp_use_b_t

  type, public :: temp_b_t
    !! A data line of *INITIAL CONDITIONS, TYPE=TEMPERATURE (step 0) or of
    !! *TEMPERATURE in a step: node or nset, temperature[, gradient along the shell normal
    !! or a beam's 2-direction[, gradient along a beam's 1-direction]].
     type(ref_t) :: ref
     real(wp) :: value = 0.0_wp
     real(wp) :: grad = 0.0_wp
     real(wp) :: grad1 = 0.0_wp     !! the fourth field: ∂T along a beam's 1-direction (local y)
     integer :: step = 0
     type(source_loc_t) :: loc
  end type temp_b_t

  type, public :: surface_b_t
    !! A *SURFACE, TYPE=ELEMENT as read: per data line an element or elset and
    !! the load form of its face (DLOAD_P1..P4 for the edges S1..S4 of plane
    !! elements, DLOAD_P with sign +1 / -1 for the faces SPOS / SNEG of shells).
     character(:), allocatable :: name     !! upper case
     integer :: n = 0
     type(ref_t), allocatable :: refs(:)
     integer, allocatable :: kinds(:)
     real(wp), allocatable :: signs(:)
     type(source_loc_t) :: loc
     logical :: nodal = .false.            !! TYPE=NODE: refs are nodes or node sets (kinds, signs unused)
  end type surface_b_t

  type, public :: pretension_b_t
    !! A *PRE-TENSION SECTION card as read (superjoin_deck_pretension).
     character(:), allocatable :: surface  !! SURFACE= (upper case; '' with ELEMENT=)
     logical :: by_element = .false.       !! ELEMENT= (a beam bolt) instead of SURFACE=
     type(ref_t) :: element                !! ELEMENT=: the bolt element (id or a set of one element)
     integer(ip) :: node = 0               !! NODE=: the pretension node's user id
     logical :: has_normal = .false.       !! the data line gave the normal
     real(wp) :: normal(3) = 0.0_wp
     type(source_loc_t) :: loc
  end type pretension_b_t

  type, public :: tie_b_t
    !! A *TIE card as read: its slave and master surfaces by name.
     character(:), allocatable :: name     !! NAME= (upper case; '' without)
     character(:), allocatable :: slave, master  !! surface names (upper case)
     real(wp) :: tolerance = 0.0_wp        !! POSITION TOLERANCE= (0: the default)
     logical :: adjust = .true.            !! ADJUST=YES (the default): slave nodes move onto the master surface
     logical :: has_line = .false.
     integer :: home = 0                   !! the substructure block it stands in
     type(source_loc_t) :: loc, line_loc
  end type tie_b_t

  type, public :: combo_b_t
    !! A *LOAD COMBINATION card as read: steps by name, factors.
     character(:), allocatable :: name
     integer :: n = 0
     type(string_t), allocatable :: steps(:)
     real(wp), allocatable :: factors(:)
     type(source_loc_t), allocatable :: line_loc(:)
     type(source_loc_t) :: loc
  end type combo_b_t

  integer, parameter, public :: OP_DEFAULT = 0, OP_MOD = 1, OP_NEW = 2
    !! OP= of the step's load and boundary cards (OP_DEFAULT: none written).

  type, public :: request_b_t
    !! An output request card as read (set still by name).
     integer :: kind = 0                   !! REQ_* of the model
     character(:), allocatable :: card     !! '*NODE PRINT', ... as written (upper case)
     integer :: step = 0                   !! step index, 0 outside *STEP
     logical :: has_set = .false.
     type(ref_t) :: set                    !! NSET= / ELSET= as written
     integer :: totals = 0
     logical :: global = .false.           !! GLOBAL=YES
     integer :: nvar = 0, nignored = 0
     type(string_t), allocatable :: vars(:), ignored(:)
     type(source_loc_t) :: loc
  end type request_b_t

  integer, parameter, public :: SPRING_1 = 1, SPRING_2 = 2, SPRING_A = 3
    !! Spring element types (*ELEMENT, TYPE=SPRING1 | SPRING2 | SPRINGA).
  integer, parameter, public :: ASSEMBLY_SPRINGS = -1
    !! spring_elem_b_t%sub of springs outside any block before MAIN exists
    !! (Abaqus's assembly joining instances' nodes I.n): they create no MAIN.

  type, public :: spring_elem_b_t
    !! A spring element: not a finite element of the model but a support
    !! (SPRING1) or a contact element (SPRING2, SPRINGA) once its *SPRING is read.
     integer(ip) :: id = 0
     integer :: kind = 0                   !! SPRING_*
     integer(ip) :: nid(2) = 0             !! user node ids (SPRING1: nid(1) only)
     type(string_t) :: scope(2)            !! I of a node written I.n (an instance's node; Abaqus's assembly
                                           !! springs), '' for a node of the element's own substructure
     integer :: sub = 0                    !! its substructure
     character(:), allocatable :: elset    !! ELSET= of its *ELEMENT card ('' without)
     logical :: bad = .false.              !! a node reference was refused (reported): the element makes nothing
     type(source_loc_t) :: loc
  end type spring_elem_b_t

  type, public :: spring_card_b_t
    !! A *SPRING card: its ELSET= and the numbers of its (at most two) data lines.
     character(:), allocatable :: elset
     integer :: sub = 0
     integer :: ndata = 0
     integer :: nfield(2) = 0
     real(wp) :: v(2, 2) = 0.0_wp          !! (field, line)
     logical :: refused = .false.          !! reported on its keyword line: its elements get no other message
     type(source_loc_t) :: loc
     type(source_loc_t) :: data_loc(2)
  end type spring_card_b_t
end module superjoin_deck_records
