module superjoin_substructure_twins
  !! Parts identical without being declared instances (issue 26): two
  !! substructures with the same elements in the same local order (types,
  !! connectivity by local node, sections, drilling masks), the same sections
  !! and materials, the same condensation boundary, and nodes that differ by
  !! a rigid motion x_s = R x_c + t (other names, other node and element
  !! numbers, moved and turned) have the same condensation turned by R:
  !! K*_s = R̂_b K*_c R̂_bᵀ with R̂ = diag(R) per node block, as the instances
  !! of one part (superjoin_substructure_cache turns it; the loads stay each
  !! part's own).
  !!
  !! Found in two stages:
  !!   - the fingerprint (twin_print, one pass over the part's arrays): the
  !!     SHA-256 of the discrete content (node and element counts, element
  !!     types, connectivity, section of every element, drilling masks,
  !!     every section but its orientation vector and material axes, the
  !!     materials whole) and six lengths that a rigid motion keeps (the
  !!     largest, mean and root-mean-square distance of the nodes to their
  !!     centroid; the distances between the first, middle and last node).
  !!     Parts whose hashes differ, or whose lengths differ by more than
  !!     LENGTH_TOL of the part's size, are not compared further. The
  !!     lengths are compared, not hashed: a hash of rounded lengths would
  !!     miss twins whose lengths straddle a rounding boundary.
  !!   - the exact check (twin_turn): R and t from three non-collinear nodes
  !!     (the same local nodes of both parts; a part whose nodes lie on one
  !!     line: two nodes and the first orientation vector given on a section,
  !!     which fixes the turn about the line), then every node within
  !!     NODE_TOL of the part's size, every beam orientation vector turned by
  !!     R, and, where an element's stiffness reads the global axes (beams
  !!     with the default orientation vector, global Z or X; materials that
  !!     are not isotropic), that element's stiffness turned by R. Plane
  !!     elements (XY plane) take turns about Z only; axisymmetric elements
  !!     none (their axis is global y): such parts are not matched, nor are
  !!     parts on one line without an orientation vector.
  !! The node and section checks are what the element stiffness reads beside
  !! the element code, which is covariant (frames of shells and solids from
  !! their nodes): K* of the twin equals the turned K* to round-off.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, MAT_ISO
  use superjoin_elements_traits, only: element_traits, element_traits_t, FAMILY_BEAM
  use superjoin_elements_frame, only: cross
  use superjoin_assembly_assemble, only: element_matrix
  use superjoin_substructure_library_key, only: hash_section, hash_material
  use superjoin_utils_sha256, only: sha256_t, update, digest
  implicit none (type, external)
  private

  real(wp), parameter :: NODE_TOL = 1.0e-12_wp
    !! Twins' nodes agree within NODE_TOL × the part's size (its largest
    !! distance of a node to the centroid), after the rigid motion.
  real(wp), parameter :: LENGTH_TOL = 1.0e-6_wp
    !! The fingerprint's lengths agree within LENGTH_TOL × the part's size (loose: it
    !! only spares the exact check of parts that differ plainly).
  real(wp), parameter :: COLLINEAR_TOL = 1.0e-3_wp
    !! The third node that fixes R lies at least COLLINEAR_TOL × the size off
    !! the line of the first two (a part on one line: R is not fixed, no twin).
  real(wp), parameter :: KE_TOL = 1.0e-9_wp
    !! Element stiffnesses agree, turned, within KE_TOL × their largest entry.
  integer, parameter :: NLEN = 6
    !! Lengths in a fingerprint.

  type, public :: twin_print_t
    !! A substructure's fingerprint (twin_print).
     logical :: done = .false.          !! computed
     logical :: eligible = .false.      !! may have twins: elements, no given stiffness, no axisymmetric
                                        !! element, not on one line unless line_sec
     integer :: line_sec = 0            !! a part on one line: the section whose orientation vector fixes
                                        !! the turn about the line (the first given one not along it)
     character(len=64) :: key = ''      !! SHA-256 of the discrete content
     real(wp) :: lengths(NLEN) = 0.0_wp !! lengths a rigid motion keeps
     real(wp) :: size = 0.0_wp          !! largest distance of a node to the centroid
     real(wp) :: centroid(3) = 0.0_wp
     integer(ip) :: pick(3) = 0         !! the three nodes that fix R (this part's choice)
     logical :: planar = .false.        !! has plane elements (XY plane: turns about Z only)
  end type twin_print_t

  public :: twin_print, twin_turn

contains

  subroutine twin_print(model, isub, fp)
    !! The fingerprint of substructure isub (module comment).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(twin_print_t), intent(out) :: fp
    type(sha256_t) :: s
    type(element_traits_t) :: t
    integer(ip) :: e
    integer :: i
    fp%done = .true.
    associate (sub => model%subs(isub))
      if (sub%nnode < 3 .or. sub%nelem < 1 .or. allocated(sub%given) .or. .not. allocated(sub%sections)) return
      if (any(sub%elem_section(1:sub%nelem) < 1)) return
      do e = 1, sub%nelem
         if (e > 1) then
            if (sub%elem_type(e) == sub%elem_type(e - 1)) cycle   ! the traits of a run of one type once
         end if
         t = element_traits(sub%elem_type(e))
         if (t%axisymmetric) return
         fp%planar = fp%planar .or. t%planar
      end do
      call update(s, 'SJTWIN|')
      call update(s, [int(sub%nnode), int(sub%nelem), size(sub%elem_nodes, 1), size(sub%sections)])
      call update(s, sub%elem_type(1:sub%nelem))
      call update(s, int(reshape(sub%elem_nodes(:, 1:sub%nelem), [size(sub%elem_nodes, 1)*sub%nelem])))
      call update(s, sub%elem_section(1:sub%nelem))
      call update(s, [merge(1, 0, allocated(sub%elem_drill))])
      if (allocated(sub%elem_drill)) call update(s, [size(sub%elem_drill), sub%elem_drill])
      do i = 1, size(sub%sections)
         call hash_section(s, sub%sections(i), placed=.false.)
         if (sub%sections(i)%material >= 1 .and. sub%sections(i)%material <= size(model%materials)) &
              call hash_material(s, model%materials(sub%sections(i)%material))
      end do
      fp%key = digest(s)
      call shape_of(sub%x(:, 1:sub%nnode), fp)
      if (fp%eligible .or. .not. fp%size > 0.0_wp) return
      ! On one line: the turn about it is fixed by an orientation vector, if one is given.
      do i = 1, size(sub%sections)
         if (.not. sub%sections(i)%has_v) cycle
         associate (d => line_of(sub%x, fp%pick), v => sub%sections(i)%v)
           if (norm2(cross(d, v)) < COLLINEAR_TOL*norm2(d)*norm2(v)) cycle
         end associate
         fp%line_sec = i
         fp%eligible = .true.
         return
      end do
    end associate
  end subroutine twin_print

  pure subroutine shape_of(x, fp)
    !! The fingerprint's lengths, the centroid, the size and the three nodes
    !! that fix R: the node farthest from the centroid, the node farthest
    !! from it, the node farthest from their line (eligible only if that is
    !! at least COLLINEAR_TOL × the size).
    real(wp), intent(in) :: x(:, :)
    type(twin_print_t), intent(inout) :: fp
    real(wp), allocatable :: r(:)
    real(wp) :: e1(3), d(3), h, hmax
    integer(ip) :: i, n, mid
    n = size(x, 2, kind=ip)
    allocate (r(n))
    fp%centroid = sum(x, dim=2)/real(n, wp)
    do i = 1, n
       r(i) = norm2(x(:, i) - fp%centroid)
    end do
    fp%size = maxval(r)
    if (.not. fp%size > 0.0_wp) return
    mid = (n + 1)/2
    fp%lengths = [fp%size, sum(r)/real(n, wp), sqrt(sum(r**2)/real(n, wp)), norm2(x(:, 1) - x(:, mid)), &
         norm2(x(:, 1) - x(:, n)), norm2(x(:, mid) - x(:, n))]
    fp%pick(1) = maxloc(r, dim=1)
    do i = 1, n
       r(i) = norm2(x(:, i) - x(:, fp%pick(1)))
    end do
    fp%pick(2) = maxloc(r, dim=1)
    e1 = (x(:, fp%pick(2)) - x(:, fp%pick(1)))/r(fp%pick(2))
    hmax = -1.0_wp
    do i = 1, n
       d = x(:, i) - x(:, fp%pick(1))
       h = norm2(d - dot_product(d, e1)*e1)
       if (h > hmax) then
          hmax = h
          fp%pick(3) = i
       end if
    end do
    fp%eligible = hmax >= COLLINEAR_TOL*fp%size
  end subroutine shape_of

  subroutine twin_turn(model, ic, is, pc, ps, q, found)
    !! Whether substructure is is a twin of substructure ic (fingerprints pc,
    !! ps: twin_print), and then the rotation q with x_s = q x_c + t (proper:
    !! det q = +1). The two have the same condensation boundary (checked by
    !! the caller).
    type(model_t), intent(in) :: model
    integer, intent(in) :: ic, is
    type(twin_print_t), intent(in) :: pc, ps
    real(wp), intent(out) :: q(3, 3)
    logical, intent(out) :: found
    q = 0.0_wp
    found = pc%eligible .and. ps%eligible
    if (.not. found) return
    found = pc%key == ps%key .and. all(abs(pc%lengths - ps%lengths) <= LENGTH_TOL*pc%size)
    if (.not. found) return
    found = pc%line_sec == ps%line_sec   ! (not so: one is on a line, the other not quite)
    if (.not. found) return
    associate (xc => model%subs(ic)%x, xs => model%subs(is)%x)
      if (pc%line_sec > 0) then
         q = matmul(frame_of(line_of(xs, pc%pick), model%subs(is)%sections(pc%line_sec)%v), &
              transpose(frame_of(line_of(xc, pc%pick), model%subs(ic)%sections(pc%line_sec)%v)))
      else
         q = matmul(frame_of(line_of(xs, pc%pick), xs(:, pc%pick(3)) - xs(:, pc%pick(1))), &
              transpose(frame_of(line_of(xc, pc%pick), xc(:, pc%pick(3)) - xc(:, pc%pick(1)))))
      end if
    end associate
    ! A proper rotation only: a mirror image is not the same part. Its nodes
    ! may be placed alike (a flat part mirrored is the part turned), but
    ! where they are not, its elements' local frames (right-handed, from
    ! the node order and the orientation vectors) are the mirrored part's,
    ! and so is its condensation. frame_of gives right-handed frames, hence
    ! det q = +1 by construction: the check guards it.
    found = det3(q) > 0.5_wp
    if (found) found = nodes_agree(model, ic, is, pc, q)
    if (found .and. pc%planar) found = abs(q(3, 3) - 1.0_wp) <= NODE_TOL
    if (found) found = orientations_agree(model, ic, is, q)
    if (found) found = elements_agree(model, ic, is, q)
  end subroutine twin_turn

  pure function line_of(x, pick) result(d)
    !! From the first node that fixes R to the second.
    real(wp), intent(in) :: x(:, :)
    integer(ip), intent(in) :: pick(3)
    real(wp) :: d(3)
    d = x(:, pick(2)) - x(:, pick(1))
  end function line_of

  pure function frame_of(d1, d2) result(f)
    !! The right-handed orthonormal frame (columns) of two directions that
    !! are not parallel: e1 along d1, e2 towards d2, e3 = e1 × e2 (d1: from
    !! the first node that fixes R to the second; d2: to the third, or a
    !! part on one line the orientation vector of its line_sec).
    real(wp), intent(in) :: d1(3), d2(3)
    real(wp) :: f(3, 3)
    f(:, 1) = d1/norm2(d1)
    f(:, 2) = d2 - dot_product(d2, f(:, 1))*f(:, 1)
    f(:, 2) = f(:, 2)/norm2(f(:, 2))
    f(:, 3) = cross(f(:, 1), f(:, 2))
  end function frame_of

  pure real(wp) function det3(a)
    !! Determinant of a 3×3 matrix.
    real(wp), intent(in) :: a(3, 3)
    det3 = a(1, 1)*(a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)) - a(1, 2)*(a(2, 1)*a(3, 3) - a(2, 3)*a(3, 1)) &
         + a(1, 3)*(a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1))
  end function det3

  pure logical function nodes_agree(model, ic, is, pc, q)
    !! Every node of is at q (x_c - x_c,a) + x_s,a, within NODE_TOL × the
    !! size (a: the first node that fixes q, near both; not the centroids,
    !! whose sums gather the round-off of coordinates far from the origin).
    type(model_t), intent(in) :: model
    integer, intent(in) :: ic, is
    type(twin_print_t), intent(in) :: pc
    real(wp), intent(in) :: q(3, 3)
    integer(ip) :: i
    real(wp) :: tol, ac(3), as(3)
    tol = NODE_TOL*pc%size
    nodes_agree = .false.
    associate (xc => model%subs(ic)%x, xs => model%subs(is)%x)
      ac = xc(:, pc%pick(1))
      as = xs(:, pc%pick(1))
      do i = 1, model%subs(ic)%nnode
         if (any(abs(matmul(q, xc(:, i) - ac) + as - xs(:, i)) > tol)) return
      end do
    end associate
    nodes_agree = .true.
  end function nodes_agree

  pure logical function orientations_agree(model, ic, is, q)
    !! Every beam orientation vector given on a section of is is that of ic
    !! turned by q (within NODE_TOL of its length).
    type(model_t), intent(in) :: model
    integer, intent(in) :: ic, is
    real(wp), intent(in) :: q(3, 3)
    integer :: k
    orientations_agree = .false.
    associate (sc => model%subs(ic)%sections, ss => model%subs(is)%sections)
      do k = 1, size(sc)
         if (.not. sc(k)%has_v) cycle
         if (any(abs(matmul(q, sc(k)%v) - ss(k)%v) > NODE_TOL*norm2(sc(k)%v))) return
      end do
    end associate
    orientations_agree = .true.
  end function orientations_agree

  logical function elements_agree(model, ic, is, q)
    !! The stiffness of every element that reads the global axes (a beam
    !! with the default orientation vector, an element of a material that
    !! is not isotropic) is, in is, that of ic turned by q.
    type(model_t), intent(in) :: model
    integer, intent(in) :: ic, is
    real(wp), intent(in) :: q(3, 3)
    real(wp), allocatable :: kc(:, :), ks(:, :)
    type(error_t), allocatable :: error
    type(element_traits_t) :: t
    integer(ip) :: e
    logical :: axes
    elements_agree = .false.
    associate (sub => model%subs(ic))
      do e = 1, sub%nelem
         t = element_traits(sub%elem_type(e))
         associate (sec => sub%sections(sub%elem_section(e)))
           axes = t%family == FAMILY_BEAM .and. .not. sec%has_v
           if (.not. axes .and. sec%material >= 1) axes = model%materials(sec%material)%kind /= MAT_ISO
         end associate
         if (.not. axes) cycle
         call element_matrix(model, ic, e, kc, error)
         if (allocated(error)) return
         call element_matrix(model, is, e, ks, error)
         if (allocated(error)) return
         if (.not. turned_equal(kc, ks, q, t)) return
      end do
    end associate
    elements_agree = .true.
  end function elements_agree

  pure logical function turned_equal(kc, ks, q, t)
    !! ks = R̂ kc R̂ᵀ within KE_TOL × max |kc|, R̂ = diag(q) per block of three
    !! DOFs of each node (the element's DOFs spread over six per node, so
    !! that a turn onto a DOF the element lacks is a difference).
    real(wp), intent(in) :: kc(:, :), ks(:, :), q(3, 3)
    type(element_traits_t), intent(in) :: t
    real(wp), allocatable :: fc(:, :), fs(:, :), r(:, :)
    integer, allocatable :: at(:)
    integer :: a, d, n, m, b
    m = 6*t%nodes
    turned_equal = .false.
    allocate (at(size(kc, 1)), source=0)
    n = 0
    do a = 1, t%nodes
       do d = 1, 6
          if (.not. t%dofs(d)) cycle
          n = n + 1
          if (n > size(at)) return
          at(n) = 6*(a - 1) + d
       end do
    end do
    if (n /= size(at) .or. any(shape(ks) /= shape(kc))) return
    allocate (fc(m, m), fs(m, m), r(m, m), source=0.0_wp)
    fc(at, at) = kc
    fs(at, at) = ks
    do b = 0, m - 3, 3
       r(b + 1:b + 3, b + 1:b + 3) = q
    end do
    fc = matmul(r, matmul(fc, transpose(r)))
    turned_equal = all(abs(fc - fs) <= KE_TOL*maxval(abs(kc)))
  end function turned_equal
end module superjoin_substructure_twins
