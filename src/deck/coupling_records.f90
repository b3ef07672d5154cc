module superjoin_deck_coupling_records
  !! Parse records of the coupling cards (*COUPLING with *KINEMATIC or
  !! *DISTRIBUTING, *RIGID BODY, *MPC, DCOUP3D elements with *DISTRIBUTING
  !! COUPLING), by user ids and names as written;
  !! superjoin_deck_coupling_build turns them into exact constraint equations.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: source_loc_t, NDOF_NODE
  use superjoin_deck_records, only: ref_t
  implicit none (type, external)
  private

  integer, parameter, public :: COUPLE_NONE = 0, COUPLE_KINEMATIC = 1, COUPLE_DISTRIBUTING = 2, &
       COUPLE_RIGID_BODY = 3, COUPLE_MPC_BEAM = 4, COUPLE_MPC_PLANE = 5, COUPLE_MPC_STRAIGHT = 6, &
       COUPLE_DCOUP = 7, COUPLE_MPC_MEANROT = 8
    !! What a coupling record is (COUPLE_NONE: a *COUPLING still without its *KINEMATIC/*DISTRIBUTING;
    !! COUPLE_DCOUP: a DCOUP3D element, its nodes and weights from *DISTRIBUTING COUPLING;
    !! COUPLE_MPC_MEANROT: *MPC MEANROT, the mean rotation of its nodes).

  type, public :: coupling_b_t
    !! One coupling as read: a reference node and its coupled nodes (a surface,
    !! a node set or an element set), or the two nodes of an *MPC BEAM.
     integer :: kind = COUPLE_NONE
     character(:), allocatable :: name          !! CONSTRAINT NAME= (upper case; may be empty);
                                                !! DCOUP3D: its element set
     character(:), allocatable :: surface       !! SURFACE= of *COUPLING (upper case)
     type(ref_t) :: ref_node                    !! REF NODE= (or the first node of *MPC BEAM)
     type(ref_t) :: rot_node                    !! ROT NODE= of *RIGID BODY (has_rot)
     logical :: has_rot = .false.
     type(ref_t) :: nodes                       !! NSET= / ELSET= of *RIGID BODY
     type(ref_t), allocatable :: list(:)        !! the nodes and node sets of an *MPC, in order
                                                !! (of a *DISTRIBUTING COUPLING, with weights)
     real(wp), allocatable :: weights(:)        !! *DISTRIBUTING COUPLING: the weight of each list item
     logical :: by_elements = .false.           !! nodes is an element set (*RIGID BODY, ELSET=)
     logical :: dofs(NDOF_NODE) = .false.       !! DOFs of *KINEMATIC / *DISTRIBUTING data lines
     logical :: dofs_given = .false.
     type(source_loc_t) :: loc                  !! the card (the *MPC data line)
     type(source_loc_t) :: weights_loc          !! DCOUP3D: its *DISTRIBUTING COUPLING card (nodes and weights)
     logical :: ok = .true.
     integer :: home = 0                        !! the substructure block it was written in (0: the
                                                !! assembly; DCOUP3D: always 0); a part's: copied per instance
  end type coupling_b_t

end module superjoin_deck_coupling_records
