module superjoin_elements_traits
  !! What every element type is, in one table: the answers the deck reader,
  !! the analysis and the output ask of an element type (family, nodes, DOFs
  !! per node, whether it lies in the x-y plane, the section card it needs,
  !! the loads it takes, the VTK cell). The rest of the program asks this
  !! table (or the element routines) and never branches on an ET_* constant.
  !!
  !! A new element type: its ET_* number, name and node count in
  !! superjoin_model_types, one row here, its stiffness and loads behind the
  !! facade superjoin_elements.
  use superjoin_model_types, only: NUM_ELEMENT_TYPES, ELEMENT_TYPE_NAMES, ELEMENT_NODE_COUNT, &
       SEC_SOLID, SEC_BEAM, SEC_SHELL, &
       ET_T2D2, ET_T3D2, ET_B23, ET_B33, ET_CPS3, ET_CPS4, ET_S3, ET_S4, ET_B21, ET_B31, &
       ET_CPE3, ET_CPE4, ET_S4R, ET_S3R, ET_S8R, ET_CPS6, ET_CPS8, ET_CPE6, ET_CPE8, &
       ET_CPS8R, ET_CPE8R, ET_B32, ET_C3D8, ET_C3D20, ET_C3D20R, ET_C3D4, ET_C3D10, ET_C3D8I, &
       ET_C3D6, ET_C3D15, ET_S8, ET_C3D8R, ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R, &
       ET_S6, DLOAD_PX, DLOAD_PY, DLOAD_PZ, DLOAD_P, DLOAD_GRAV, DLOAD_BX, DLOAD_BY, DLOAD_BZ, DLOAD_P1, DLOAD_P2, DLOAD_P3, &
       DLOAD_P4, DLOAD_CENTRIF, DLOAD_P5, DLOAD_P6, DLOAD_TRVEC, DLOAD_TRSHR
  implicit none (type, external)
  private

  integer, parameter, public :: FAMILY_NONE = 0, FAMILY_TRUSS = 1, FAMILY_BEAM = 2, &
                                FAMILY_PLANE = 3, FAMILY_SHELL = 4, FAMILY_SOLID = 5
    !! Element families (FAMILY_SOLID: the 3D solids C3D*, DOFs 1..3).
  character(len=6), parameter, public :: FAMILY_NAMES(0:5) = &
       ['none  ', 'truss ', 'beam  ', 'plane ', 'shell ', 'solid ']

  integer, parameter, public :: VTK_VERTEX = 1, VTK_LINE = 3, VTK_POLY_LINE = 4, &
                                VTK_TRIANGLE = 5, VTK_QUAD = 9, &
                                VTK_QUADRATIC_TRIANGLE = 22, VTK_QUADRATIC_QUAD = 23, &
                                VTK_TETRA = 10, VTK_HEXAHEDRON = 12, VTK_QUADRATIC_TETRA = 24, &
                                VTK_QUADRATIC_HEXAHEDRON = 25, VTK_WEDGE = 13, VTK_QUADRATIC_WEDGE = 26
    !! VTK cell type numbers (VTK's file format; its node order is Abaqus's for these cells,
    !! the 20-node hexahedron and 10-node tetrahedron included: VTK's mid-edge points 8..19
    !! lie on the edges (0,1), (1,2), (2,3), (3,0), (4,5), (5,6), (6,7), (7,4), (0,4), (1,5),
    !! (2,6), (3,7), Abaqus's nodes 9..20 on 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6,
    !! 3-7, 4-8; the tetrahedron's 4..9 on (0,1), (1,2), (0,2), (0,3), (1,3), (2,3) as C3D10's
    !! 5..10; the wedge's 0..5 as C3D6's 1..6, its mid-edge points 6..14 on (0,1), (1,2), (2,0),
    !! (3,4), (4,5), (5,3), (0,3), (1,4), (2,5) as C3D15's 7..15. CalculiX's .frd order, which
    !! differs, plays no part here).

  type, public :: element_traits_t
    !! One element type, as the rest of the program sees it.
     character(len=6) :: name = ''        !! deck name (T2D2, CPS4, S8R, C3D20R, …)
     integer :: family = FAMILY_NONE      !! FAMILY_*
     integer :: nodes = 0                 !! nodes per element
     integer :: corners = 0               !! corner nodes (the first ones); the rest are mid-side nodes
     logical :: planar = .false.          !! a 2D element of the x-y plane (T2D2, B21, B23, CPS*, CPE*)
     logical :: quadratic = .false.       !! mid-side nodes (CPS6, CPS8(R), CPE6, CPE8(R), S8R, B32)
     logical :: plane_strain = .false.    !! CPE*
     logical :: shear_flexible = .false.  !! Timoshenko beams (B21, B31, B32), thick shells (S3R, S4R, S8R)
     logical :: reduced = .false.         !! reduced integration named by the type (CPS8R, CPE8R, S4R, S3R, S8R)
     integer :: edges = 0                 !! faces of a plane element (P1..Pn), edges of a shell, faces of a solid
     logical :: dofs(6) = .false.         !! DOFs 1..6 (ux, uy, uz, rx, ry, rz) carried by each node
     integer :: section = 0               !! SEC_* kind of the section card that covers it
     integer :: vtk_cell = VTK_VERTEX     !! VTK cell type
     logical :: axisymmetric = .false.    !! CAX*: a solid of revolution about y, r = x (FAMILY_SOLID, DOFs 1, 2)
  end type element_traits_t

  logical, parameter :: D2(6) = [.true., .true., .false., .false., .false., .false.]
  logical, parameter :: D3(6) = [.true., .true., .true., .false., .false., .false.]
  logical, parameter :: D126(6) = [.true., .true., .false., .false., .false., .true.]
  logical, parameter :: D6(6) = .true.

  public :: element_traits, all_element_traits, element_family, is_family, accepts_dload, section_card_name
  public :: valid_element_type, element_vtk_cell
  public :: shell_of_plane, element_type_of_name, dload_face
  public :: is_shell8

contains

  pure logical function valid_element_type(etype)
    !! etype names an implemented element type.
    integer, intent(in) :: etype
    valid_element_type = etype >= 1 .and. etype <= NUM_ELEMENT_TYPES
    if (valid_element_type) valid_element_type = len_trim(ELEMENT_TYPE_NAMES(etype)) > 0
  end function valid_element_type

  pure function element_traits(etype) result(t)
    !! The traits of element type etype (FAMILY_NONE and no DOFs for an unknown number).
    integer, intent(in) :: etype
    type(element_traits_t) :: t
    if (.not. valid_element_type(etype)) return
    t%name = ELEMENT_TYPE_NAMES(etype)
    t%nodes = ELEMENT_NODE_COUNT(etype)
    t%corners = t%nodes
    select case (etype)
    case (ET_T2D2)
       t = with(t, FAMILY_TRUSS, D2, SEC_SOLID, VTK_LINE, planar=.true.)
    case (ET_T3D2)
       t = with(t, FAMILY_TRUSS, D3, SEC_SOLID, VTK_LINE)
    case (ET_B23)
       t = with(t, FAMILY_BEAM, D126, SEC_BEAM, VTK_LINE, planar=.true.)
    case (ET_B21)
       t = with(t, FAMILY_BEAM, D126, SEC_BEAM, VTK_LINE, planar=.true., shear=.true.)
    case (ET_B33)
       t = with(t, FAMILY_BEAM, D6, SEC_BEAM, VTK_LINE)
    case (ET_B31)
       t = with(t, FAMILY_BEAM, D6, SEC_BEAM, VTK_LINE, shear=.true.)
    case (ET_B32)
       t = with(t, FAMILY_BEAM, D6, SEC_BEAM, VTK_POLY_LINE, shear=.true., corners=2)
    case (ET_CPS3, ET_CPE3)
       t = with(t, FAMILY_PLANE, D2, SEC_SOLID, VTK_TRIANGLE, planar=.true., edges=3)
    case (ET_CPS4, ET_CPE4)
       t = with(t, FAMILY_PLANE, D2, SEC_SOLID, VTK_QUAD, planar=.true., edges=4)
    case (ET_CPS6, ET_CPE6)
       t = with(t, FAMILY_PLANE, D2, SEC_SOLID, VTK_QUADRATIC_TRIANGLE, planar=.true., edges=3, corners=3)
    case (ET_CPS8, ET_CPE8)
       t = with(t, FAMILY_PLANE, D2, SEC_SOLID, VTK_QUADRATIC_QUAD, planar=.true., edges=4, corners=4)
    case (ET_CPS8R, ET_CPE8R)
       t = with(t, FAMILY_PLANE, D2, SEC_SOLID, VTK_QUADRATIC_QUAD, planar=.true., edges=4, corners=4, &
                reduced=.true.)
    case (ET_S3)
       t = with(t, FAMILY_SHELL, D6, SEC_SHELL, VTK_TRIANGLE, edges=3)
    case (ET_S4)
       t = with(t, FAMILY_SHELL, D6, SEC_SHELL, VTK_QUAD, edges=4)
    case (ET_S3R)
       t = with(t, FAMILY_SHELL, D6, SEC_SHELL, VTK_TRIANGLE, edges=3, shear=.true., reduced=.true.)
    case (ET_S4R)
       t = with(t, FAMILY_SHELL, D6, SEC_SHELL, VTK_QUAD, edges=4, shear=.true., reduced=.true.)
    case (ET_S8R)
       t = with(t, FAMILY_SHELL, D6, SEC_SHELL, VTK_QUADRATIC_QUAD, edges=4, corners=4, shear=.true., &
                reduced=.true.)
    case (ET_S8)
       t = with(t, FAMILY_SHELL, D6, SEC_SHELL, VTK_QUADRATIC_QUAD, edges=4, corners=4, shear=.true.)
    case (ET_S6)
       t = with(t, FAMILY_SHELL, D6, SEC_SHELL, VTK_QUADRATIC_TRIANGLE, edges=3, corners=3, shear=.true.)
    case (ET_C3D8, ET_C3D8I)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_HEXAHEDRON, edges=6)
    case (ET_C3D8R)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_HEXAHEDRON, edges=6, reduced=.true.)
    case (ET_C3D20)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_QUADRATIC_HEXAHEDRON, edges=6, corners=8)
    case (ET_C3D20R)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_QUADRATIC_HEXAHEDRON, edges=6, corners=8, reduced=.true.)
    case (ET_C3D4)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_TETRA, edges=4)
    case (ET_C3D10)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_QUADRATIC_TETRA, edges=4, corners=4)
    case (ET_C3D6)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_WEDGE, edges=5)
    case (ET_C3D15)
       t = with(t, FAMILY_SOLID, D3, SEC_SOLID, VTK_QUADRATIC_WEDGE, edges=5, corners=6)
    case (ET_CAX3)
       t = with(t, FAMILY_SOLID, D2, SEC_SOLID, VTK_TRIANGLE, planar=.true., edges=3)
    case (ET_CAX4)
       t = with(t, FAMILY_SOLID, D2, SEC_SOLID, VTK_QUAD, planar=.true., edges=4)
    case (ET_CAX6)
       t = with(t, FAMILY_SOLID, D2, SEC_SOLID, VTK_QUADRATIC_TRIANGLE, planar=.true., edges=3, corners=3)
    case (ET_CAX8)
       t = with(t, FAMILY_SOLID, D2, SEC_SOLID, VTK_QUADRATIC_QUAD, planar=.true., edges=4, corners=4)
    case (ET_CAX8R)
       t = with(t, FAMILY_SOLID, D2, SEC_SOLID, VTK_QUADRATIC_QUAD, planar=.true., edges=4, corners=4, reduced=.true.)
    end select
    t%axisymmetric = any(etype == [ET_CAX3, ET_CAX4, ET_CAX6, ET_CAX8, ET_CAX8R])
    t%quadratic = t%corners < t%nodes
    t%plane_strain = any(etype == [ET_CPE3, ET_CPE4, ET_CPE6, ET_CPE8, ET_CPE8R])
  end function element_traits

  pure function all_element_traits() result(t)
    !! The traits of every element type (t(etype)), for loops over elements
    !! that look them up once per type instead of once per element.
    type(element_traits_t) :: t(NUM_ELEMENT_TYPES)
    integer :: k
    do k = 1, NUM_ELEMENT_TYPES
       t(k) = element_traits(k)
    end do
  end function all_element_traits

  pure function with(t0, family, dofs, section, vtk_cell, planar, shear, reduced, edges, corners) result(t)
    !! t0 with the given traits (one row of the table).
    type(element_traits_t), intent(in) :: t0
    integer, intent(in) :: family, section, vtk_cell
    logical, intent(in) :: dofs(6)
    logical, intent(in), optional :: planar, shear, reduced
    integer, intent(in), optional :: edges, corners
    type(element_traits_t) :: t
    t = t0
    t%family = family
    t%dofs = dofs
    t%section = section
    t%vtk_cell = vtk_cell
    if (present(planar)) t%planar = planar
    if (present(shear)) t%shear_flexible = shear
    if (present(reduced)) t%reduced = reduced
    if (present(edges)) t%edges = edges
    if (present(corners)) t%corners = corners
  end function with

  elemental integer function element_family(etype)
    !! FAMILY_* of element type etype.
    integer, intent(in) :: etype
    type(element_traits_t) :: t
    t = element_traits(etype)
    element_family = t%family
  end function element_family

  elemental logical function is_family(etype, family)
    !! Element type etype belongs to FAMILY_* family.
    integer, intent(in) :: etype, family
    is_family = element_family(etype) == family
  end function is_family

  pure function section_card_name(etype) result(card)
    !! The section card that covers element type etype.
    integer, intent(in) :: etype
    character(:), allocatable :: card
    type(element_traits_t) :: t
    t = element_traits(etype)
    select case (t%section)
    case (SEC_BEAM)
       card = '*BEAM SECTION'
    case (SEC_SHELL)
       card = '*SHELL SECTION'
    case default
       card = '*SOLID SECTION'
    end select
  end function section_card_name

  elemental logical function accepts_dload(kind, etype)
    !! Whether a distributed load of kind DLOAD_* applies to element type etype:
    !! PX, PY on beams (per unit length), PZ on beams in space, P on shells,
    !! GRAV and CENTRIF on every element, P1..Pn on the faces of a
    !! plane element and of a solid (P1..P6 on hexahedra, P1..P4 on tetrahedra, P1..P3 or P1..P4
    !! on the edges of an axisymmetric element); on beams P1
    !! (local y) in space and P2 (local z) also on planar two-node beams;
    !! the tractions TRVEC, TRSHR on plane, axisymmetric, shell and solid elements.
    integer, intent(in) :: kind, etype
    type(element_traits_t) :: t
    logical :: beam2
    t = element_traits(etype)
    beam2 = t%family == FAMILY_BEAM .and. .not. t%quadratic
    select case (kind)
    case (DLOAD_PX, DLOAD_PY)
       accepts_dload = t%family == FAMILY_BEAM
    case (DLOAD_PZ)
       accepts_dload = t%family == FAMILY_BEAM .and. .not. t%planar
    case (DLOAD_P)
       accepts_dload = t%family == FAMILY_SHELL
    case (DLOAD_GRAV)
       accepts_dload = .true.
    case (DLOAD_BX, DLOAD_BY, DLOAD_BZ)   ! Abaqus's axisymmetric elements take BR and BZ instead
       accepts_dload = .not. t%axisymmetric
    case (DLOAD_CENTRIF)
       accepts_dload = .true.
    case (DLOAD_P1)
       accepts_dload = t%family == FAMILY_PLANE .or. (beam2 .and. .not. t%planar) .or. t%family == FAMILY_SOLID
    case (DLOAD_P2)
       accepts_dload = t%family == FAMILY_PLANE .or. beam2 .or. t%family == FAMILY_SOLID
    case (DLOAD_P3)
       accepts_dload = t%family == FAMILY_PLANE .or. t%family == FAMILY_SOLID
    case (DLOAD_P4)
       accepts_dload = ((t%family == FAMILY_PLANE .or. t%axisymmetric) .and. t%edges >= 4) .or. &
            (t%family == FAMILY_SOLID .and. .not. t%axisymmetric)
    case (DLOAD_P5, DLOAD_P6)
       accepts_dload = t%family == FAMILY_SOLID .and. t%edges >= dload_face(kind)
    case (DLOAD_TRVEC, DLOAD_TRSHR)   ! the face is checked with the *SURFACE that names it
       accepts_dload = t%family == FAMILY_PLANE .or. t%family == FAMILY_SHELL .or. t%family == FAMILY_SOLID
    case default
       accepts_dload = .false.
    end select
  end function accepts_dload

  elemental integer function element_vtk_cell(etype)
    !! VTK cell type of element type etype (VTK_VERTEX for an unknown number).
    integer, intent(in) :: etype
    type(element_traits_t) :: t
    t = element_traits(etype)
    element_vtk_cell = t%vtk_cell
  end function element_vtk_cell

  elemental integer function shell_of_plane(etype)
    !! The shell type with the nodes of plane element type etype, that a
    !! *SHELL SECTION turns it into (gmsh writes every 2D mesh as CPS3, CPS4):
    !! S3 for CPS3, S4 for CPS4; 0 for the others.
    integer, intent(in) :: etype
    select case (etype)
    case (ET_CPS3)
       shell_of_plane = ET_S3
    case (ET_CPS4)
       shell_of_plane = ET_S4
    case default
       shell_of_plane = 0
    end select
  end function shell_of_plane

  pure integer function element_type_of_name(name) result(etype)
    !! The element type a deck names (upper case), 0 when superjoin has none.
    !! CalculiX's B32R (reduced integration) is superjoin's B32, which has the
    !! reduced two-point rule (doc/verification.md, CalculiX test decks).
    character(*), intent(in) :: name
    integer :: k
    etype = 0
    do k = 1, NUM_ELEMENT_TYPES
       if (len_trim(ELEMENT_TYPE_NAMES(k)) > 0 .and. trim(ELEMENT_TYPE_NAMES(k)) == name) etype = k
    end do
    if (name == 'B32R') etype = ET_B32
  end function element_type_of_name

  elemental integer function dload_face(kind)
    !! The face (or edge) number k of a *DLOAD Pk (DLOAD_P1 .. DLOAD_P6), 0 for other kinds.
    integer, intent(in) :: kind
    select case (kind)
    case (DLOAD_P1, DLOAD_P2, DLOAD_P3, DLOAD_P4)
       dload_face = kind - DLOAD_P1 + 1
    case (DLOAD_P5, DLOAD_P6)
       dload_face = kind - DLOAD_P5 + 5
    case default
       dload_face = 0
    end select
  end function dload_face

  elemental logical function is_shell8(etype)
    !! The second-order thick shells of superjoin_elements_shell8: S8R (2×2
    !! reduced in-plane rule), S8 (full 3×3 rule) and the triangle S6.
    integer, intent(in) :: etype
    is_shell8 = etype == ET_S8R .or. etype == ET_S8 .or. etype == ET_S6
  end function is_shell8
end module superjoin_elements_traits
