module superjoin_deck_ccx_cards
  !! Tables of the CalculiX/Abaqus analysis cards that the deck reader knows
  !! without doing: procedures and material or contact behaviour that linear
  !! statics does not have (refused with one clear message each), the output
  !! request cards and their variables (produced, known but not produced, or
  !! unknown). Pure look-ups; the parser reports.
  use superjoin_model_types, only: REQ_NODE_PRINT, REQ_EL_PRINT, REQ_NODE_FILE, REQ_EL_FILE
  use superjoin_utils_strings, only: without_blanks
  implicit none (type, external)
  private

  public :: refused_card_reason, request_kind, is_node_request, classify_variable
  public :: canonical_keyword, variable_hint

  integer, parameter, public :: VAR_UNKNOWN = 0, VAR_PRODUCED = 1, VAR_NOT_PRODUCED = 2
    !! What superjoin does with an output variable.

  integer, parameter :: KW_LEN = 40, REASON_LEN = 60, VAR_LEN = 5

  integer, parameter :: NUM_REFUSED = 32
  character(len=KW_LEN), parameter :: REFUSED_KEYWORDS(NUM_REFUSED) = [character(len=KW_LEN) :: &
       'FREQUENCY', 'BUCKLE', 'DYNAMIC', 'MODAL DYNAMIC', 'STEADY STATE DYNAMICS', &
       'COMPLEX FREQUENCY', 'HEAT TRANSFER', 'COUPLED TEMPERATURE-DISPLACEMENT', &
       'UNCOUPLED TEMPERATURE-DISPLACEMENT', 'VISCO', 'GREEN', 'SENSITIVITY', 'ELECTROMAGNETICS', &
       'CFD', 'SUBSTRUCTURE GENERATE', &
       'PLASTIC', 'HYPERELASTIC', 'HYPERFOAM', 'CREEP', 'DEFORMATION PLASTICITY', 'USER MATERIAL', &
       'CYCLIC HARDENING', 'CONTACT PAIR', 'SURFACE INTERACTION', 'SURFACE BEHAVIOR', 'FRICTION', &
       'GAP', 'GAP CONDUCTANCE', 'TEMPERATURE', 'INITIAL CONDITIONS', 'MODAL DAMPING', &
       'CONTACT DAMPING']
  integer, parameter :: NUM_KNOWN = 70
  character(len=KW_LEN), parameter :: KNOWN_KEYWORDS(NUM_KNOWN) = [character(len=KW_LEN) :: &
       'AMPLITUDE', 'ASSEMBLY', 'BEAM GENERAL SECTION', 'BEAM SECTION', 'BOUNDARY', 'CHANGE CONTACT', 'CLOAD', &
       'CONTACT', 'CONTACT FILE', 'CONTACT OUTPUT', 'CONTACT PRINT', 'CONTROLS', 'COUPLING', 'DENSITY', &
       'DISTRIBUTING', 'DISTRIBUTING COUPLING', 'KINEMATIC', 'MPC', 'RIGID BODY', &
       'DLOAD', 'DSLOAD', 'EL FILE', 'EL PRINT', 'ELASTIC', &
       'ELEMENT', 'ELEMENT OUTPUT', 'ELSET', 'END ASSEMBLY', 'END INSTANCE', 'END PART', &
       'END STEP', 'END SUBSTRUCTURE', 'EQUATION', 'EXPANSION', 'HEADING', 'INCLUDE', &
       'INITIAL CONDITIONS', 'INSTANCE', 'INTERFACE', 'LOAD COMBINATION', 'MATERIAL', 'MATRIX INPUT', 'MATRIX LOAD', &
       'NODAL THICKNESS', 'NODE', 'NODE FILE', 'NODE OUTPUT', 'NODE PRINT', 'NSET', 'ORIENTATION', &
       'OUTPUT', 'PART', 'PRE-TENSION SECTION', 'PREPRINT', 'RESTART', 'SECTION CONTROLS', 'SECTION PRINT', 'SHELL SECTION', 'SOLID SECTION', 'SPRING', 'STATIC', 'STEP', &
       'SUBSTRUCTURE', 'SUBSTRUCTURE MATRIX OUTPUT', 'SUPPORT', 'SURFACE', 'TEMPERATURE', 'TIE', 'TRANSFORM', &
       'TRANSVERSE SHEAR STIFFNESS']
    !! Every keyword the reader dispatches (kept complete by
    !! tests/check_cards_documented.sh), as canonical_keyword spells it.
  character(len=REASON_LEN), parameter :: REFUSED_REASONS(NUM_REFUSED) = [character(len=REASON_LEN) :: &
       'natural frequencies', 'linear buckling', 'dynamics', 'modal dynamics', &
       'steady-state dynamics', 'complex frequencies', 'heat transfer', &
       'coupled thermomechanics', 'thermomechanics', 'viscoplasticity', &
       'Green functions', 'sensitivities', 'electromagnetics', 'fluid dynamics', &
       'superelement generation', &
       'plasticity', 'hyperelasticity', 'hyperelastic foams', 'creep', 'deformation plasticity', &
       'user materials', 'plastic hardening', 'nonlinear contact', 'nonlinear contact', &
       'nonlinear contact', 'friction', 'gap elements', 'heat transfer', 'thermal loads', &
       'initial conditions', 'dynamics', 'dynamics']

  integer, parameter :: NUM_NODE_PRODUCED = 4, NUM_EL_PRODUCED = 4
  character(len=VAR_LEN), parameter :: NODE_PRODUCED(NUM_NODE_PRODUCED) = ['U    ', 'RF   ', 'CF   ', 'S    ']
  character(len=VAR_LEN), parameter :: EL_PRODUCED(NUM_EL_PRODUCED) = ['S    ', 'E    ', 'SF   ', 'ENER ']
  integer, parameter :: NUM_NODE_KNOWN = 44
  character(len=VAR_LEN), parameter :: NODE_KNOWN(NUM_NODE_KNOWN) = [character(len=VAR_LEN) :: &
       'NT', 'TS', 'RFL', 'PN', 'PS', 'PT', 'TT', 'TTF', 'MF', 'V', 'VF', 'DEPF', 'TURB', 'MACH', 'CP', &
       'SEN', 'POT', 'PU', 'PNT', 'PHS', 'MAXU', 'HCRI', 'CONC', 'SLIP', 'UR', &
       'PSF', 'TSF', 'PTF', 'DEPT', 'PRF', 'DTF', &
       'UT', 'RT', 'RM', 'CM', 'TF', 'VT', 'VR', 'A', 'AT', 'AR', 'COORD', 'TEMP', 'POR']
    !! CalculiX's nodal variables (ccx 2.21, nodeprints.f and noelfiles.f) and Abaqus's common ones
    !! (translations, reactions, moments, velocities, accelerations, coordinates, temperatures, pore
    !! pressure as separate identifiers) superjoin does not produce
  integer, parameter :: NUM_EL_KNOWN = 66
  character(len=VAR_LEN), parameter :: EL_KNOWN(NUM_EL_KNOWN) = [character(len=VAR_LEN) :: &
       'ME', 'PEEQ', 'CEEQ', 'SDV', 'HFL', 'HFLF', 'COORD', 'ELSE', 'ELKE', 'EVOL', 'EMAS', &
       'EBHE', 'CENT', 'ZZS', 'ERR', 'HER', 'MAXS', 'MAXE', 'SVF', 'ESE', 'THE', 'PHS', 'EMFE', 'EMFB', &
       'MF', 'DEPF', 'CELS', 'CDIS', 'CSTR', &
       'NOE', 'SNEG', 'SMID', 'SPOS', 'KEQ', 'PCON', 'ECD', 'DTF', 'CE', 'PE', 'COOR', &
       'LE', 'NE', 'EE', 'IE', 'PEMAG', 'SE', 'SK', 'SM', 'ELEN', 'ELPD', 'ELCD', 'ELVD', 'ELASE', 'IVOL', &
       'SENER', 'MISES', 'TRESC', 'PRESS', 'SINV', 'SP', 'TRIAX', 'STH', 'TEMP', 'NFORC', 'BF', 'ALPHA']
    !! CalculiX's element variables (ccx 2.21, elprints.f and noelfiles.f; NOE: no
    !! error estimator, SNEG/SMID/SPOS: shell stresses at the faces) and Abaqus's common ones
    !! (Abaqus/CAE's field output lists: LE, PEMAG, ...; energies, invariants, section
    !! quantities as separate identifiers) superjoin does not produce

contains

  pure function refused_card_reason(keyword) result(reason)
    !! For a card that linear statics does not have, what it is ('natural
    !! frequencies' for FREQUENCY); '' for any other keyword.
    character(*), intent(in) :: keyword
    character(:), allocatable :: reason
    integer :: k
    reason = ''
    do k = 1, NUM_REFUSED
       if (trim(REFUSED_KEYWORDS(k)) == keyword) then
          reason = trim(REFUSED_REASONS(k))
          return
       end if
    end do
  end function refused_card_reason

  pure function canonical_keyword(keyword) result(canon)
    !! The keyword as the reader spells it (upper case, words separated by one
    !! blank: 'SOLID SECTION', 'CLOAD') for a keyword written with its blanks
    !! left out or put elsewhere ('SOLIDSECTION', 'C LOAD'): CalculiX and
    !! Abaqus ignore blanks in keywords. `keyword` is upper case. A keyword
    !! that matches no known card comes back unchanged (so its error message
    !! names it as written).
    character(*), intent(in) :: keyword
    character(:), allocatable :: canon
    character(:), allocatable :: key
    integer :: k
    key = without_blanks(keyword)
    do k = 1, NUM_KNOWN
       if (without_blanks(KNOWN_KEYWORDS(k)) == key) then
          canon = trim(KNOWN_KEYWORDS(k))
          return
       end if
    end do
    do k = 1, NUM_REFUSED
       if (without_blanks(REFUSED_KEYWORDS(k)) == key) then
          canon = trim(REFUSED_KEYWORDS(k))
          return
       end if
    end do
    canon = keyword
  end function canonical_keyword

  pure integer function request_kind(keyword) result(kind)
    !! REQ_* of an output request keyword (0 for any other keyword).
    character(*), intent(in) :: keyword
    select case (keyword)
    case ('NODE PRINT')
       kind = REQ_NODE_PRINT
    case ('EL PRINT')
       kind = REQ_EL_PRINT
    case ('NODE FILE', 'NODE OUTPUT')
       kind = REQ_NODE_FILE
    case ('EL FILE', 'ELEMENT OUTPUT')
       kind = REQ_EL_FILE
    case default
       kind = 0
    end select
  end function request_kind

  pure logical function is_node_request(kind)
    !! Does a request of this kind name nodes (NSET=) rather than elements (ELSET=)?
    integer, intent(in) :: kind
    is_node_request = kind == REQ_NODE_PRINT .or. kind == REQ_NODE_FILE
  end function is_node_request

  pure function variable_hint(name) result(hint)
    !! What an unknown output variable name (upper case) most likely is, for
    !! its error message ('' when nothing is known). S1 to S6 are element type
    !! names of CalculiX (shells), not variables: ccx 2.20 stops on *EL PRINT
    !! S6 ("label not applicable") and ignores it under *EL FILE.
    character(*), intent(in) :: name
    character(:), allocatable :: hint
    hint = ''
    select case (name)
    case ('S3', 'S4', 'S6', 'S8')
       hint = '; '//name//' is CalculiX''s shell element type, not an output variable (ccx 2.20 refuses it '// &
            'too: label not applicable); the stresses of any element: S'
    end select
  end function variable_hint

  pure integer function classify_variable(kind, name) result(what)
    !! VAR_PRODUCED, VAR_NOT_PRODUCED or VAR_UNKNOWN for variable `name` (upper
    !! case) of a request of this kind.
    integer, intent(in) :: kind
    character(*), intent(in) :: name
    what = VAR_UNKNOWN
    if (len(name) > VAR_LEN) return
    if (kind == REQ_NODE_PRINT .and. name == 'NT') then
       what = VAR_PRODUCED   ! the nodal temperatures in the listing (not in the CSV of *NODE FILE)
       return
    end if
    if (is_node_request(kind)) then
       if (any(NODE_PRODUCED == name)) then
          what = VAR_PRODUCED
       else if (any(NODE_KNOWN == name)) then
          what = VAR_NOT_PRODUCED
       end if
    else
       if (any(EL_PRODUCED == name)) then
          what = VAR_PRODUCED
       else if (any(EL_KNOWN == name)) then
          what = VAR_NOT_PRODUCED
       end if
    end if
  end function classify_variable
end module superjoin_deck_ccx_cards
