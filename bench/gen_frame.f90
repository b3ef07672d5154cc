!> gen_frame: writes a superjoin deck for a multi-storey 3D steel building frame,
!> used to benchmark superjoin from 1e3 to 1e6 degrees of freedom.
!>
!> Build:  gfortran -O2 bench/gen_frame.f90 -o build/gen_frame
!> Usage:  gen_frame NX NY NZ [DECK]        explicit grid (DECK default: stdout)
!>         gen_frame --dofs N [--shape tower|block|long] [DECK]
!>                                          pick a grid of about N equations
!>
!> The model (units N, m):
!>   - NX x NY column lines, NZ storeys of height 3.5 m, bays of 6 m in X and Y.
!>   - Substructure COLUMNS: every column line is one vertical B33 member,
!>     COL_ELEMS elements per storey (node at every floor level and in between);
!>     section HEB 300 (strong axis bends in X), orientation v = X.
!>   - Substructure BEAMS: every girder in X and Y at every floor, one bay long,
!>     BEAM_ELEMS elements per bay, own end nodes; section IPE 400 (strong axis
!>     in the vertical plane), orientation v = Z. Girders are not connected to
!>     each other inside BEAMS: they meet only through the columns.
!>   - *CONTACT JOINTS (MASTER=COLUMNS, SLAVE=BEAMS): every girder end sits at
!>     the coordinates of a column floor node; translations RIGID, rotations
!>     semi-rigid: G_BEND on the two bending rotations, G_TORS on the rotation
!>     about the girder axis. Four pairs of node sets (X girder start/end,
!>     Y girder start/end), listed in matching (and ascending) order.
!>   - *SUPPORT: column bases fixed (DOFs 1-6).
!>   - Step GRAVITY: *DLOAD PZ = Q_GRAVITY on all girders.
!>     Step WIND: *CLOAD in X of F_WIND on every floor node of the facade x = 0.
!>
!> Size (TRANSFORM formulation, RIGID eliminated, supports removed):
!>   equations = 6*COL_ELEMS*NX*NY*NZ + 6*BEAM_ELEMS*NZ*((NX-1)*NY + NX*(NY-1))
!> (the 3 rotational Delta-u of every girder end stay as equations; its 3
!> translations are eliminated). The program prints this on stderr.
!>
!> Shapes for --dofs N (--shape, default tower; gen_frame --help lists the
!> grids it picks for 1e3 .. 1e6). Sparse Cholesky of a fat 3D grid costs
!> about n^2 flops (fill ~ n^(4/3)); slender shapes keep the separators small:
!>   tower  square plan p x p, about 12 p storeys (slender: separators are
!>          storey cross-sections of p^2 columns); 1e6 -> 12 x 12 x 154
!>   block  square plan, as many storeys as bays per side; 1e6 -> 28 x 28 x 27
!>   long   long low building, 5 x 4 bays cross-section; 1e6 -> 1127 x 5 x 4
!> Measured on 2 cores (doc/performance.md), CHOLMOD analyze + factorize +
!> solve of 1e6 equations: long 2.5 s / 0.8 GB, tower 7 s / 1.3 GB, block
!> 13 s / 2.3 GB. The beams' intermediate nodes are chains, so even the block
!> stays cheap; tower is the benchmark's default (a 539 m, 154-storey tower
!> at 1e6 is extreme but buildable; the long shape is a 6.8 km shed).
program gen_frame
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit, int64, real64
  implicit none

  integer, parameter :: dp = real64
  integer, parameter :: i8 = int64

  ! geometry
  real(dp), parameter :: STOREY_H = 3.5_dp      !< storey height [m]
  real(dp), parameter :: BAY = 6.0_dp           !< bay width in X and Y [m]
  integer, parameter :: COL_ELEMS = 2           !< B33 elements per column per storey
  integer, parameter :: BEAM_ELEMS = 3          !< B33 elements per girder (one bay)

  ! material: structural steel S355
  real(dp), parameter :: E_STEEL = 2.1e11_dp, NU_STEEL = 0.3_dp

  ! column HEB 300: A, Iy, Iz, J. With v = X, local y = global X, and bending
  ! along local y uses Iz: the strong axis resists sway in X (wind).
  real(dp), parameter :: COL_A = 1.491e-2_dp, COL_IY = 8.563e-5_dp, &
       COL_IZ = 2.517e-4_dp, COL_J = 1.850e-6_dp
  ! girder IPE 400. With v = Z, local y is vertical: the strong axis is Iz.
  real(dp), parameter :: BEAM_A = 8.446e-3_dp, BEAM_IY = 1.318e-5_dp, &
       BEAM_IZ = 2.313e-4_dp, BEAM_J = 5.108e-7_dp

  ! semi-rigid beam-column joints [N m/rad]
  real(dp), parameter :: G_BEND = 5.0e7_dp      !< bending rotations
  real(dp), parameter :: G_TORS = 2.0e7_dp      !< rotation about the girder axis

  ! loads
  real(dp), parameter :: Q_GRAVITY = -20.0e3_dp !< line load on girders [N/m], global Z
  real(dp), parameter :: F_WIND = 20.0e3_dp     !< force per facade floor node [N], global X

  ! --dofs mode (see shape_for). Equations per column line per storey are
  ! about 6*COL_ELEMS + 2*6*BEAM_ELEMS = 48, hence the factors below.
  real(dp), parameter :: TOWER_FACTOR = 576.0_dp  !< 48 * 12: storeys = 12 x plan side
  real(dp), parameter :: BLOCK_FACTOR = 48.0_dp   !< storeys = plan side
  integer, parameter :: LONG_NY = 5, LONG_NZ = 4  !< cross-section of the long building
  integer, parameter :: SMALL_NY = 2, SMALL_NZ = 2 !< ... for targets too small for it
  integer, parameter :: MAX_NX = 100000000  !< search bound of --dofs

  integer :: nx, ny, nz, u
  integer(i8) :: neq, ndof
  character(len=:), allocatable :: out_path
  character(len=512) :: arg
  integer :: nargs, ios, iarg
  character(len=:), allocatable :: shape
  real(dp) :: target

  nargs = command_argument_count()
  if (nargs < 1) call usage(2)
  call get_command_argument(1, arg)
  if (arg == '--help' .or. arg == '-h') call usage(0)
  if (arg == '--dofs') then
     if (nargs < 2) call usage(2)
     call get_command_argument(2, arg)
     read (arg, *, iostat=ios) target
     if (ios /= 0 .or. target < 100.0_dp) call die('--dofs needs a number >= 100, got '//trim(arg))
     shape = 'tower'
     iarg = 3
     if (nargs >= 4) then
        call get_command_argument(3, arg)
        if (arg == '--shape') then
           call get_command_argument(4, arg)
           shape = trim(arg)
           iarg = 5
        end if
     end if
     if (shape /= 'tower' .and. shape /= 'block' .and. shape /= 'long') &
          call die('unknown shape '//shape//' (tower, block or long)')
     if (nargs > iarg) call usage(2)
     call shape_for(target, shape, nx, ny, nz)
  else
     if (nargs < 3 .or. nargs > 4) call usage(2)
     nx = int_arg(1)
     ny = int_arg(2)
     nz = int_arg(3)
     iarg = 4
  end if
  if (nargs == iarg) then
     call get_command_argument(iarg, arg)
     out_path = trim(arg)
  end if
  if (nx < 1 .or. ny < 1 .or. nz < 1) call die('NX, NY, NZ must be >= 1')
  if (nx * ny < 2) call die('need at least two column lines (NX*NY >= 2) to have girders')

  neq = equations(nx, ny, nz)
  ndof = 6_i8 * (int(nx, i8) * ny * (nz * COL_ELEMS + 1) + &
       int(nz, i8) * girders_per_floor(nx, ny) * (BEAM_ELEMS + 1))
  write (error_unit, '(a,3(i0,a),i0,a,i0,a)') 'gen_frame: ', nx, ' x ', ny, ' x ', nz, &
       ' frame: ', neq, ' equations (', ndof, ' nodal DOFs before elimination)'

  if (allocated(out_path)) then
     open (newunit=u, file=out_path, status='replace', action='write', form='formatted', &
          iostat=ios)
     if (ios /= 0) call die('cannot open '//out_path//' for writing')
  else
     u = output_unit
  end if
  call write_deck(u, nx, ny, nz)
  if (allocated(out_path)) close (u)
  ! freed before the end: LeakSanitizer (the sanitize build's tests run this
  ! generator) counts a main program's allocatables still held at exit
  if (allocated(out_path)) deallocate (out_path)
  if (allocated(shape)) deallocate (shape)

contains

  !> Number of girders (bays) on one floor.
  pure integer(i8) function girders_per_floor(nx, ny)
    integer, intent(in) :: nx, ny
    girders_per_floor = int(nx - 1, i8) * ny + int(nx, i8) * (ny - 1)
  end function girders_per_floor

  !> Equations of the reduced system (see header).
  pure integer(i8) function equations(nx, ny, nz)
    integer, intent(in) :: nx, ny, nz
    equations = 6_i8 * COL_ELEMS * nx * ny * nz + &
         6_i8 * BEAM_ELEMS * nz * girders_per_floor(nx, ny)
  end function equations

  !> Shape of about `target` equations in one of the families:
  !>   tower: square plan of p x p column lines, p = nint((target/576)^(1/3))
  !>          (at least 2), so that the height is about 12 plan sides in
  !>          storeys; the number of storeys is then fitted to the target.
  !>   block: square plan, as many storeys as column lines per side (a cube of
  !>          bays): the fattest 3D shape, largest separators.
  !>   long:  long low building, cross-section LONG_NY x LONG_NZ (SMALL_NY x
  !>          SMALL_NZ for small targets), the length NX fitted to the target.
  subroutine shape_for(target, shape, nx, ny, nz)
    real(dp), intent(in) :: target
    character(*), intent(in) :: shape
    integer, intent(out) :: nx, ny, nz
    integer :: n, p
    real(dp) :: best, err
    select case (shape)
    case ('tower', 'block')
       if (shape == 'tower') then
          p = max(2, nint((target / TOWER_FACTOR)**(1.0_dp / 3.0_dp)))
       else
          p = max(2, nint((target / BLOCK_FACTOR)**(1.0_dp / 3.0_dp)))
       end if
       nx = p
       ny = p
       nz = max(1, nint(target / real(equations(p, p, 1), dp)))
    case default ! long
       ny = LONG_NY
       nz = LONG_NZ
       if (real(equations(2, ny, nz), dp) > target) then
          ny = SMALL_NY
          nz = SMALL_NZ
       end if
       nx = 2
       best = huge(1.0_dp)
       do n = 2, MAX_NX
          err = abs(real(equations(n, ny, nz), dp) - target)
          if (err < best) then
             best = err
             nx = n
          else
             exit ! the error grows from here on
          end if
       end do
    end select
  end subroutine shape_for

  !> Column node id: column line (i, j), level k = 0 .. nz*COL_ELEMS (0 = base).
  pure integer function col_node(i, j, k, nx, nz)
    integer, intent(in) :: i, j, k, nx, nz
    col_node = ((j - 1) * nx + (i - 1)) * (nz * COL_ELEMS + 1) + k + 1
  end function col_node

  subroutine write_deck(u, nx, ny, nz)
    integer, intent(in) :: u, nx, ny, nz
    integer :: i, j, k, f, e, n0, nlev, node, elem
    real(dp) :: x, y, z
    integer, allocatable :: xs_beam(:), xe_beam(:), ys_beam(:), ye_beam(:)
    integer, allocatable :: xs_col(:), xe_col(:), ys_col(:), ye_col(:)
    integer :: nxg, nyg, cx, cy

    nlev = nz * COL_ELEMS
    nxg = (nx - 1) * ny * nz          ! X girders, all floors
    nyg = nx * (ny - 1) * nz          ! Y girders, all floors
    allocate (xs_beam(nxg), xe_beam(nxg), xs_col(nxg), xe_col(nxg))
    allocate (ys_beam(nyg), ye_beam(nyg), ys_col(nyg), ye_col(nyg))

    ! Girder node numbering runs over (j, i, floor), X girders first, each
    ! girder's BEAM_ELEMS+1 nodes consecutive; the joint lists follow the same
    ! order, so the column and girder node lists of every joint set are both
    ! ascending (they pair up whether or not the reader sorts sets).
    node = 0
    cx = 0
    do j = 1, ny
       do i = 1, nx - 1
          do f = 1, nz
             cx = cx + 1
             xs_beam(cx) = node + 1
             xe_beam(cx) = node + BEAM_ELEMS + 1
             xs_col(cx) = col_node(i, j, f * COL_ELEMS, nx, nz)
             xe_col(cx) = col_node(i + 1, j, f * COL_ELEMS, nx, nz)
             node = node + BEAM_ELEMS + 1
          end do
       end do
    end do
    cy = 0
    do j = 1, ny - 1
       do i = 1, nx
          do f = 1, nz
             cy = cy + 1
             ys_beam(cy) = node + 1
             ye_beam(cy) = node + BEAM_ELEMS + 1
             ys_col(cy) = col_node(i, j, f * COL_ELEMS, nx, nz)
             ye_col(cy) = col_node(i, j + 1, f * COL_ELEMS, nx, nz)
             node = node + BEAM_ELEMS + 1
          end do
       end do
    end do

    write (u, '(a)') '*HEADING'
    write (u, '(a,3(i0,a))') 'gen_frame: 3D steel frame, ', nx, ' x ', ny, ' column lines, ', &
         nz, ' storeys, semi-rigid beam-column joints'
    write (u, '(a)') '** generated by bench/gen_frame.f90; units N, m'
    write (u, '(a)') '*MATERIAL, NAME=S355'
    write (u, '(a)') '*ELASTIC'
    write (u, '(es12.5,a,f0.2)') E_STEEL, ', ', NU_STEEL

    ! ------------------------------------------------------------------ columns
    write (u, '(a)') '*SUBSTRUCTURE, NAME=COLUMNS'
    write (u, '(a)') '*NODE'
    do j = 1, ny
       do i = 1, nx
          x = (i - 1) * BAY
          y = (j - 1) * BAY
          do k = 0, nlev
             z = k * (STOREY_H / COL_ELEMS)
             write (u, '(i0,3(a,f0.4))') col_node(i, j, k, nx, nz), ', ', x, ', ', y, ', ', z
          end do
       end do
    end do
    write (u, '(a)') '*ELEMENT, TYPE=B33, ELSET=COLS'
    elem = 0
    do j = 1, ny
       do i = 1, nx
          n0 = col_node(i, j, 0, nx, nz)
          do k = 0, nlev - 1
             elem = elem + 1
             write (u, '(i0,2(a,i0))') elem, ', ', n0 + k, ', ', n0 + k + 1
          end do
       end do
    end do
    write (u, '(a)') '*BEAM SECTION, ELSET=COLS, MATERIAL=S355'
    write (u, '(es12.5,3(a,es12.5))') COL_A, ', ', COL_IY, ', ', COL_IZ, ', ', COL_J
    write (u, '(a)') '1.0, 0.0, 0.0'
    write (u, '(a)') '*NSET, NSET=BASE'
    do j = 1, ny
       do i = 1, nx
          write (u, '(i0)') col_node(i, j, 0, nx, nz)
       end do
    end do
    write (u, '(a)') '*NSET, NSET=WINDWARD'
    do j = 1, ny
       do f = 1, nz
          write (u, '(i0)') col_node(1, j, f * COL_ELEMS, nx, nz)
       end do
    end do

    ! joint node sets of the columns (same order as the girder end sets)
    call write_set(u, 'J_XS', xs_col)
    call write_set(u, 'J_XE', xe_col)
    call write_set(u, 'J_YS', ys_col)
    call write_set(u, 'J_YE', ye_col)
    write (u, '(a)') '*END SUBSTRUCTURE'

    ! ------------------------------------------------------------------ girders
    write (u, '(a)') '*SUBSTRUCTURE, NAME=BEAMS'
    write (u, '(a)') '*NODE'
    node = 0
    do j = 1, ny
       do i = 1, nx - 1
          do f = 1, nz
             do e = 0, BEAM_ELEMS
                node = node + 1
                write (u, '(i0,3(a,f0.4))') node, ', ', (i - 1 + real(e, dp) / BEAM_ELEMS) * BAY, &
                     ', ', (j - 1) * BAY, ', ', f * STOREY_H
             end do
          end do
       end do
    end do
    do j = 1, ny - 1
       do i = 1, nx
          do f = 1, nz
             do e = 0, BEAM_ELEMS
                node = node + 1
                write (u, '(i0,3(a,f0.4))') node, ', ', (i - 1) * BAY, ', ', &
                     (j - 1 + real(e, dp) / BEAM_ELEMS) * BAY, ', ', f * STOREY_H
             end do
          end do
       end do
    end do
    ! elements: each girder's nodes are consecutive
    write (u, '(a)') '*ELEMENT, TYPE=B33, ELSET=GIRDERS'
    elem = 0
    do k = 1, cx + cy
       if (k <= cx) then
          n0 = xs_beam(k)
       else
          n0 = ys_beam(k - cx)
       end if
       do e = 0, BEAM_ELEMS - 1
          elem = elem + 1
          write (u, '(i0,2(a,i0))') elem, ', ', n0 + e, ', ', n0 + e + 1
       end do
    end do
    write (u, '(a)') '*BEAM SECTION, ELSET=GIRDERS, MATERIAL=S355'
    write (u, '(es12.5,3(a,es12.5))') BEAM_A, ', ', BEAM_IY, ', ', BEAM_IZ, ', ', BEAM_J
    write (u, '(a)') '0.0, 0.0, 1.0'
    call write_set(u, 'E_XS', xs_beam)
    call write_set(u, 'E_XE', xe_beam)
    call write_set(u, 'E_YS', ys_beam)
    call write_set(u, 'E_YE', ye_beam)
    write (u, '(a)') '*END SUBSTRUCTURE'

    ! ------------------------------------------------------------------ joints
    write (u, '(a)') '** beam-column joints: translations rigid, rotations semi-rigid'
    write (u, '(a)') '** X girders: DOF 4 (rx) is torsion; Y girders: DOF 5 (ry) is torsion'
    write (u, '(a)') '*CONTACT, NAME=JOINTS, MASTER=COLUMNS, SLAVE=BEAMS'
    if (cx > 0) then
       call write_joint(u, 'J_XS', 'E_XS', 4)
       call write_joint(u, 'J_XE', 'E_XE', 4)
    end if
    if (cy > 0) then
       call write_joint(u, 'J_YS', 'E_YS', 5)
       call write_joint(u, 'J_YE', 'E_YE', 5)
    end if
    write (u, '(a)') '*SUPPORT'
    write (u, '(a)') ' COLUMNS.BASE, 1, 6'

    ! ------------------------------------------------------------------ loads
    write (u, '(a)') '*STEP, NAME=GRAVITY'
    write (u, '(a)') '*DLOAD'
    write (u, '(a,es12.5)') ' BEAMS.GIRDERS, PZ, ', Q_GRAVITY
    write (u, '(a)') '*END STEP'
    write (u, '(a)') '*STEP, NAME=WIND'
    write (u, '(a)') '*CLOAD'
    write (u, '(a,es12.5)') ' COLUMNS.WINDWARD, 1, ', F_WIND
    write (u, '(a)') '*END STEP'
  end subroutine write_deck

  !> *NSET card, 16 ids per line; nothing for an empty set.
  subroutine write_set(u, name, ids)
    integer, intent(in) :: u
    character(*), intent(in) :: name
    integer, intent(in) :: ids(:)
    integer, parameter :: PER_LINE = 16
    integer :: k, last
    character(len=16) :: buf
    character(len=:), allocatable :: line
    if (size(ids) == 0) return
    write (u, '(a)') '*NSET, NSET='//name
    do k = 1, size(ids), PER_LINE
       last = min(k + PER_LINE - 1, size(ids))
       line = ''
       block
         integer :: m
         do m = k, last
            write (buf, '(i0)') ids(m)
            if (m < last) then
               line = line//trim(buf)//', '
            else
               line = line//trim(buf)
            end if
         end do
       end block
       write (u, '(a)') line
    end do
  end subroutine write_set

  !> Contact lines of one pair of sets; `tors` is the DOF of the girder's axis rotation.
  subroutine write_joint(u, master, slave, tors)
    integer, intent(in) :: u, tors
    character(*), intent(in) :: master, slave
    integer :: d
    write (u, '(a)') ' '//master//', '//slave//', 1, 3, RIGID'
    do d = 4, 6
       if (d == tors) then
          write (u, '(a,2(i0,a),es10.3)') ' '//master//', '//slave//', ', d, ', ', d, ', ', G_TORS
       else
          write (u, '(a,2(i0,a),es10.3)') ' '//master//', '//slave//', ', d, ', ', d, ', ', G_BEND
       end if
    end do
  end subroutine write_joint

  integer function int_arg(k)
    integer, intent(in) :: k
    character(len=64) :: a
    integer :: ios
    call get_command_argument(k, a)
    read (a, *, iostat=ios) int_arg
    if (ios /= 0) call die('not an integer: '//trim(a))
  end function int_arg

  subroutine die(msg)
    character(*), intent(in) :: msg
    write (error_unit, '(a)') 'gen_frame: '//msg
    stop 2, quiet=.true.
  end subroutine die

  subroutine usage(code)
    integer, intent(in) :: code
    integer :: unit, p, q, nx, ny, nz
    real(dp), parameter :: sizes(4) = [1.0e3_dp, 1.0e4_dp, 1.0e5_dp, 1.0e6_dp]
    character(len=5), parameter :: shapes(3) = ['tower', 'block', 'long ']
    unit = merge(output_unit, error_unit, code == 0)
    write (unit, '(a)') 'usage: gen_frame NX NY NZ [DECK]   NX x NY column lines, NZ storeys'
    write (unit, '(a)') '       gen_frame --dofs N [--shape tower|block|long] [DECK]'
    write (unit, '(a)') '                                   a grid of about N equations (default tower)'
    write (unit, '(a)') 'writes a superjoin deck (stdout without DECK); its size goes to stderr.'
    write (unit, '(a)') 'grids chosen by --dofs:'
    do q = 1, size(shapes)
       do p = 1, size(sizes)
          call shape_for(sizes(p), trim(shapes(q)), nx, ny, nz)
          write (unit, '(a,es8.1,a,3(i0,a),i0,a)') '  --dofs ', sizes(p), ' --shape '//shapes(q)//' -> ', &
               nx, ' x ', ny, ' x ', nz, '  (', equations(nx, ny, nz), ' equations)'
       end do
    end do
    if (code == 0) stop
    stop 2, quiet=.true.
  end subroutine usage

end program gen_frame
