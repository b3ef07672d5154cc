program test_deck_ccx
  !! Unit tests of the CalculiX/Abaqus analysis cards of the deck reader:
  !! refused cards give exactly one message (no cascade), *STEP/*STATIC
  !! parameters, *NODE with omitted coordinates, output requests stored in
  !! model%requests with CalculiX's scoping, springs translated into supports
  !! and contacts.
  use superjoin_kinds, only: wp, ip
  use superjoin_error, only: error_t, EXIT_DECK
  use superjoin_model_types, only: model_t, find_node, REQ_NODE_PRINT, REQ_EL_PRINT, REQ_NODE_FILE, &
       REQ_EL_FILE, TOTALS_YES, TOTALS_NO, LINK_FINITE
  use superjoin_deck_reader, only: read_deck_string
  use superjoin_output_requests, only: effective_requests
  use superjoin_testing, only: check, check_close, finish
  use superjoin_deck_ccx_cards, only: canonical_keyword
  implicit none (type, external)

  character, parameter :: LF = achar(10)
  integer, parameter :: L = 100
  character(*), parameter :: BAR = '*NODE'//LF//'1, 0, 0'//LF//'2, 1, 0'//LF//'*ELEMENT, TYPE=T2D2, ELSET=E'//LF// &
       '1, 1, 2'//LF//'*MATERIAL, NAME=M'//LF//'*ELASTIC'//LF//'1.0, 0.3'//LF// &
       '*SOLID SECTION, ELSET=E, MATERIAL=M'//LF//'1.0'//LF

  call test_one_message()
  call test_step_cards()
  call test_nodes()
  call test_requests()
  call test_springs()
  call test_keyword_blanks()
  call finish()

contains

  function join(lines) result(text)
    character(*), intent(in) :: lines(:)
    character(:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(lines)
       text = text//trim(lines(i))//LF
    end do
  end function join

  integer function count_lines(s) result(n)
    character(*), intent(in) :: s
    integer :: i
    n = 1
    do i = 1, len(s)
       if (s(i:i) == LF) n = n + 1
    end do
  end function count_lines

  subroutine one_error(text, expect, what)
    !! Exactly one error line, containing `expect`.
    character(*), intent(in) :: text, expect, what
    type(model_t) :: model
    type(error_t), allocatable :: error
    logical :: ok
    call read_deck_string(text, 'inline.deck', model, error)
    ok = allocated(error)
    if (ok) ok = index(error%message, expect) > 0 .and. error%code == EXIT_DECK .and. &
         count_lines(error%message) == 1
    call check(ok, what//': one error "'//expect//'"')
    if (.not. ok .and. allocated(error)) write (*, '(a)') '  got: '//error%message
  end subroutine one_error

  subroutine read_ok(text, model, what)
    character(*), intent(in) :: text, what
    type(model_t), intent(out) :: model
    type(error_t), allocatable :: error
    call read_deck_string(text, 'inline.deck', model, error)
    call check(.not. allocated(error), what//': reads without error')
    if (allocated(error)) write (*, '(a)') '  got: '//error%message
  end subroutine read_ok

  subroutine test_one_message()
    call one_error(BAR//join([character(L) :: '*STEP', '*FREQUENCY, SOLVER=ARPACK', '10', '*END STEP']), &
         'inline.deck:12: error: superjoin does linear statics; *FREQUENCY (natural frequencies)', 'frequency step')
    call one_error(BAR//join([character(L) :: '*STEP', '*BUCKLE', '5', '*CLOAD', '2, 1, 1.', '*END STEP']), &
         '*BUCKLE (linear buckling) is not supported', 'buckling step with a load')
    call one_error(join([character(L) :: '*MATERIAL, NAME=M', '*ELASTIC', '1., 0.3', '*PLASTIC', '1., 0.', &
         '2., 0.1', '*DENSITY', '7.8', '*NODE', '1, 0, 0']), 'inline.deck:4: error: superjoin does linear statics; '// &
         '*PLASTIC', 'plasticity between *ELASTIC and *DENSITY')
    call one_error(join([character(L) :: '*MATERIAL, NAME=M', '*ELASTIC, TYPE=ENGINEERING CONSTANTS', &
         '1., 2., 3., 0.3, 0.3, 0.3, 1., 1.', '1., 0.', '1., 2., 3., 0.3, 0.3, 0.3, 1., 1.', '1., 100.', &
         '*DENSITY', '7.8', '*NODE', '1, 0, 0']), &
         'too many data lines for *ELASTIC, TYPE=ENGINEERING CONSTANTS', 'orthotropic elastic, a temperature table')
    call one_error(BAR//join([character(L) :: '*STEP, NLGEOM=YES, INC=1000', '*STATIC', '0.1, 1.', '*END STEP']), &
         'inline.deck:11: error: superjoin does linear statics; *STEP, NLGEOM=YES', 'NLGEOM=YES')
    call one_error(BAR//join([character(L) :: '*CONTACT PAIR, INTERACTION=SI', 'S1, S2']), &
         '*CONTACT PAIR (nonlinear contact) is not supported', 'contact pair')
    call one_error(BAR//join([character(L) :: '*ELEMENT, TYPE=SPRINGA, ELSET=S', '5, 1, 2', &
         '*SPRING, ELSET=S, NONLINEAR', '0., 0.', '1., 10.']), '*SPRING, NONLINEAR', 'nonlinear spring')
  end subroutine test_one_message

  subroutine test_step_cards()
    type(model_t) :: model
    call read_ok(BAR//join([character(L) :: '*BOUNDARY', '1, 1, 2', '2, 2, 2', &
         '*STEP, NAME=S1, NLGEOM=NO, PERTURBATION, INC=100, INCF=20, AMPLITUDE=STEP', &
         '*STATIC, SOLVER=PARDISO, DIRECT', ', 1., , ', '*CLOAD', '2, 1, 1.', '*END STEP', &
         '*STEP', '*STATIC', '*CLOAD', '2, 1, 2.', '*END STEP']), model, 'step parameters and *STATIC')
    if (.not. allocated(model%steps)) return
    call check(size(model%steps) == 2, 'two steps')
    call check(model%steps(1)%name == 'S1' .and. model%steps(2)%name == '2', 'step names')
    call check(size(model%requests) == 0, 'no requests')
  end subroutine test_step_cards

  subroutine test_nodes()
    type(model_t) :: model
    integer(ip) :: n
    call read_ok(join([character(L) :: '*NODE', '1', '2, 5.', '3, , 2.', '4, 1., 2., 3., 0., 0., 1.', &
         '5, 1., , 3.']), model, 'omitted coordinates')
    if (.not. allocated(model%subs)) return
    associate (sub => model%subs(1))
      n = find_node(sub, 1_ip)
      call check(all(sub%x(:, n) == 0.0_wp), 'node "1": the origin')
      n = find_node(sub, 2_ip)
      call check(all(sub%x(:, n) == [5.0_wp, 0.0_wp, 0.0_wp]), 'node "2, 5.": y = z = 0')
      n = find_node(sub, 3_ip)
      call check(all(sub%x(:, n) == [0.0_wp, 2.0_wp, 0.0_wp]), 'node "3, , 2.": x = 0')
      n = find_node(sub, 4_ip)
      call check(all(sub%x(:, n) == [1.0_wp, 2.0_wp, 3.0_wp]), 'node with a normal: coordinates kept')
      n = find_node(sub, 5_ip)
      call check(all(sub%x(:, n) == [1.0_wp, 0.0_wp, 3.0_wp]), 'node "5, 1., , 3.": y = 0')
    end associate
  end subroutine test_nodes

  subroutine test_requests()
    type(model_t) :: model
    integer, allocatable :: idx(:)
    call read_ok(BAR//join([character(L) :: '*NSET, NSET=TIP', '2', '*BOUNDARY', '1, 1, 2', '2, 2, 2', &
         '*EL PRINT', 'SF', &
         '*STEP', '*STATIC', '*CLOAD', '2, 1, 1.', &
         '*NODE PRINT, NSET=TIP, TOTALS=YES', 'U, RF', 'NT, RFL', &
         '*NODE FILE', &
         '*END STEP', &
         '*STEP', '*STATIC', '*CLOAD', '2, 1, 2.', &
         '*EL PRINT, ELSET=E', 'S, E, ENER', &
         '*ELEMENT OUTPUT', 'S', &
         '*END STEP']), model, 'output requests')
    if (.not. allocated(model%requests)) return
    call check(size(model%requests) == 5, 'five request cards')
    if (size(model%requests) /= 5) return
    associate (r => model%requests)
      call check(r(1)%kind == REQ_EL_PRINT .and. r(1)%step == 0 .and. r(1)%sub == 0 .and. &
           .not. allocated(r(1)%set_name), 'global *EL PRINT, whole model')
      call check(size(r(1)%vars) == 1 .and. r(1)%vars(1)%s == 'SF', 'its variable SF')
      call check(r(2)%kind == REQ_NODE_PRINT .and. r(2)%step == 1 .and. r(2)%totals == TOTALS_YES, &
           '*NODE PRINT in step 1 with TOTALS=YES')
      call check(r(2)%set_name == 'TIP' .and. r(2)%sub == 1 .and. size(r(2)%items) == 1, 'NSET=TIP resolved')
      call check(size(r(2)%vars) == 3 .and. size(r(2)%ignored) == 1, 'U, RF, NT produced; RFL noted')
      if (size(r(2)%ignored) == 1) call check(r(2)%ignored(1)%s == 'RFL', 'RFL not produced')
      call check(r(3)%kind == REQ_NODE_FILE .and. size(r(3)%vars) == 1, '*NODE FILE')
      if (size(r(3)%vars) == 1) call check(r(3)%vars(1)%s == 'U', '*NODE FILE without data: U')
      call check(r(4)%kind == REQ_EL_PRINT .and. r(4)%step == 2 .and. r(4)%totals == TOTALS_NO, &
           '*EL PRINT in step 2')
      call check(r(5)%kind == REQ_EL_FILE .and. r(5)%card == '*ELEMENT OUTPUT', '*ELEMENT OUTPUT is an *EL FILE')
    end associate
    ! CalculiX scoping
    call effective_requests(model, 1, REQ_EL_PRINT, idx)
    call check(size(idx) == 1 .and. any(idx == 1), 'step 1: the global *EL PRINT')
    call effective_requests(model, 2, REQ_EL_PRINT, idx)
    call check(size(idx) == 1 .and. any(idx == 4), 'step 2: its own *EL PRINT replaces it')
    call effective_requests(model, 2, REQ_NODE_PRINT, idx)
    call check(size(idx) == 1 .and. any(idx == 2), 'step 2 keeps step 1''s *NODE PRINT')
    call effective_requests(model, 1, REQ_EL_FILE, idx)
    call check(size(idx) == 0, 'step 1 has no *EL FILE')
  end subroutine test_requests

  subroutine test_springs()
    type(model_t) :: model
    integer :: k
    call read_ok(BAR//join([character(L) :: '*NODE', '3, 2, 0', '*ELEMENT, TYPE=SPRING1, ELSET=G', '10, 2', &
         '*ELEMENT, TYPE=SPRINGA, ELSET=A', '11, 2, 3', '*SPRING, ELSET=G', '2', '50.', '*SPRING, ELSET=A', '', &
         '70.', '*BOUNDARY', '1, 1, 2', '3, 1, 2']), model, 'springs')
    if (.not. allocated(model%supports)) return
    call check(count(model%supports%state == LINK_FINITE) == 1, 'SPRING1: one elastic support')
    do k = 1, size(model%supports)
       if (model%supports(k)%state == LINK_FINITE) then
          call check(model%supports(k)%dof == 2, 'on DOF 2')
          call check_close(model%supports(k)%g, 50.0_wp, 0.0_wp, 'with g = k')
       end if
    end do
    call check(size(model%contacts) == 1 .and. size(model%links) == 1, 'SPRINGA: one contact element')
    if (size(model%links) /= 1) return
    call check(model%contacts(1)%name == 'SPRINGA_A_11' .and. model%contacts(1)%orientation == 1, &
         'named after its set and id, with its frame')
    call check(model%links(1)%state(1) == LINK_FINITE .and. all(model%links(1)%state(2:) == 0), &
         'on DOF 1 of the frame only')
    call check_close(model%links(1)%g(1), 70.0_wp, 0.0_wp, 'with g = k')
    call check(all(abs(model%orientations(1)%q(1, :) - [1.0_wp, 0.0_wp, 0.0_wp]) <= epsilon(1.0_wp)), &
         'frame axis 1 along node 2 -> node 3')
  end subroutine test_springs

  subroutine test_keyword_blanks()
    !! Keywords compare with their blanks removed (CalculiX, Abaqus); unknown
    !! keywords come back as written.
    call check(canonical_keyword('SOLIDSECTION') == 'SOLID SECTION', 'SOLIDSECTION')
    call check(canonical_keyword('NODE  PRINT') == 'NODE PRINT', 'NODE  PRINT')
    call check(canonical_keyword('C LOAD') == 'CLOAD', 'C LOAD')
    call check(canonical_keyword('ENDSTEP') == 'END STEP', 'ENDSTEP')
    call check(canonical_keyword('BEAMGENERALSECTION') == 'BEAM GENERAL SECTION', 'BEAMGENERALSECTION')
    call check(canonical_keyword('HEATTRANSFER') == 'HEAT TRANSFER', 'a refused card too')
    call check(canonical_keyword('STEP') == 'STEP', 'a keyword as it is')
    call check(canonical_keyword('SOLID SECTIONX') == 'SOLID SECTIONX', 'unknown: unchanged')
    call check(canonical_keyword('DISTRIBUTINGCOUPLING') == 'DISTRIBUTING COUPLING', 'DISTRIBUTINGCOUPLING')
    call check(canonical_keyword('DESIGNVARIABLES') == 'DESIGNVARIABLES', 'unknown without blanks: unchanged')
  end subroutine test_keyword_blanks
end program test_deck_ccx
