module superjoin_elements_catalog
  !! Element type names that decks from Abaqus and CalculiX use and superjoin
  !! does not implement, with the reason and the nearest supported type, for
  !! the message that refuses them. A name is never mapped silently to another
  !! formulation: CPS4R (one-point integration with hourglass control) is not
  !! CPS4, S4R5 (thin shell with 5 DOFs per node) is not S4.
  use superjoin_model_types, only: ELEMENT_TYPE_NAMES, NUM_ELEMENT_TYPES
  implicit none (type, external)
  private

  type :: advice_t
     character(len=8) :: name
     character(len=160) :: text
  end type advice_t

  type(advice_t), parameter :: ADVICE(*) = [ &
       advice_t('CPS4R', 'one-point integration with hourglass control is not implemented; ' // &
                'nearest: CPS4 (incompatible modes, no hourglass modes)'), &
       advice_t('CPE4R', 'one-point integration with hourglass control is not implemented; ' // &
                'nearest: CPE4 (incompatible modes, no hourglass modes)'), &
       advice_t('CPS4I', 'nearest: CPS4, which has incompatible modes (QM6)'), &
       advice_t('CPE4I', 'nearest: CPE4, which has incompatible modes (QM6)'), &
       advice_t('CPE4H', 'hybrid (pressure) elements are not implemented; nearest: CPE4'), &
       advice_t('CPS6M', 'nearest: CPS6 (six-node triangle, 3-point integration)'), &
       advice_t('CPE6M', 'nearest: CPE6 (six-node triangle, 3-point integration)'), &
       advice_t('S4R5', 'nearest: S4 (thin shell) or S4R (thick shell)'), &
       advice_t('STRI3', 'nearest: S3 (thin shell)'), &
       advice_t('STRI65', 'nearest: S6 (the six-node triangular shell, thick, whose assumed shear does not ' // &
                'lock as the thickness goes to 0)'), &
       advice_t('B22', 'planar three-node beams are not implemented yet; nearest: B21 (two-node ' // &
                'Timoshenko beam) or B32 (three-node beam in space)'), &
       advice_t('B31H', 'hybrid beams are not implemented; nearest: B31'), &
       advice_t('B21H', 'hybrid beams are not implemented; nearest: B21'), &
       advice_t('B31OS', 'open-section warping beams are not implemented; nearest: B31'), &
       advice_t('T3D3', 'nearest: T3D2'), &
       advice_t('T2D3', 'nearest: T2D2'), &
       advice_t('C3D10M', 'nearest: C3D10 (four-point rule)'), &
       advice_t('C3D20H', 'hybrid (pressure) elements are not implemented; nearest: C3D20') &
       ]

  public :: unsupported_type_message

contains

  pure function unsupported_type_message(name) result(text)
    !! The message for an element type name that is not implemented: the name,
    !! the reason and nearest supported type when the name is known, and the
    !! list of supported types. `name` is upper case.
    character(*), intent(in) :: name
    character(:), allocatable :: text
    integer :: k
    text = 'unsupported element type '//name
    do k = 1, size(ADVICE)
       if (trim(ADVICE(k)%name) == name) then
          text = text//': '//trim(ADVICE(k)%text)
          exit
       end if
    end do
    text = text//' (supported: '//trim(ELEMENT_TYPE_NAMES(1))
    do k = 2, NUM_ELEMENT_TYPES
       if (len_trim(ELEMENT_TYPE_NAMES(k)) == 0) cycle   ! a reserved number
       text = text//', '//trim(ELEMENT_TYPE_NAMES(k))
    end do
    text = text//')'
  end function unsupported_type_message
end module superjoin_elements_catalog
