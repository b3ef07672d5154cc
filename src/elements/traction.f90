module superjoin_elements_traction
  !! Surface loads at an integration point of a face, one rule for solids'
  !! faces, plane elements' edges and shells' surfaces: a pressure (*DLOAD
  !! Pk, *DSLOAD P) and Abaqus's tractions (*DSLOAD TRVEC, TRSHR).
  !!
  !! At a point with the weighted area vector a = w n dA (n the face's normal
  !! on the side a positive pressure pushes towards, |a| the weighted area)
  !! the force is
  !!   pressure:  p a;
  !!   TRVEC:     t |a| d            (d the unit direction, global axes);
  !!   TRSHR:     t |a| s / |s|,     s = d - (d·n̂) n̂, the direction's
  !!                                 projection onto the surface at the point.
  !! The loads act on the undeformed surface (a linear analysis), which is
  !! what Abaqus's FOLLOWER= and CONSTANT RESULTANT= of *DSLOAD choose between
  !! in a geometrically nonlinear one.
  use superjoin_kinds, only: wp
  use superjoin_error, only: error_t, fatal_error, EXIT_DECK
  implicit none (type, external)
  private

  integer, parameter, public :: LOAD_PRESSURE = 0, LOAD_TRACTION = 1, LOAD_SHEAR = 2
    !! What a surface load is: a pressure, a traction along d (TRVEC), a shear traction (TRSHR).
  real(wp), parameter :: NORMAL_TOL = 1.0e-8_wp
    !! A TRSHR direction within this (sine of the angle) of the normal has no shear part.

  type, public :: surface_load_t
    !! A uniform surface load.
     integer :: mode = LOAD_PRESSURE
     real(wp) :: value = 0.0_wp            !! the pressure, or the traction's magnitude per unit area
     real(wp) :: dir(3) = 0.0_wp           !! traction: unit direction, global axes
  end type surface_load_t

  public :: point_force

contains

  pure subroutine point_force(ld, a, f, error)
    !! The force f(3) of the surface load ld at a point with weighted area
    !! vector a (see the module header). A TRSHR whose direction is normal to
    !! the surface there is an error.
    type(surface_load_t), intent(in) :: ld
    real(wp), intent(in) :: a(3)
    real(wp), intent(out) :: f(3)
    type(error_t), allocatable, intent(out) :: error
    real(wp) :: area, s(3)
    f = 0.0_wp
    if (ld%mode == LOAD_PRESSURE) then
       f = ld%value*a
       return
    end if
    area = norm2(a)
    if (ld%mode == LOAD_TRACTION) then
       f = ld%value*area*ld%dir
       return
    end if
    if (area == 0.0_wp) return
    s = ld%dir - dot_product(ld%dir, a)/area**2*a
    if (norm2(s) <= NORMAL_TOL) then
       call fatal_error(error, EXIT_DECK, 'TRSHR: the direction is normal to the surface (a shear traction '// &
            'needs a direction with a part along the surface)')
       return
    end if
    f = ld%value*area*s/norm2(s)
  end subroutine point_force
end module superjoin_elements_traction
