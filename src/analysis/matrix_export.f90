module superjoin_analysis_matrix_export
  !! *SUBSTRUCTURE MATRIX OUTPUT: a condensed substructure's K*, its condensed
  !! loads f* (one vector per step of the solve) and its boundary DOF map,
  !! written as the condensation produced them (the part_view_t of the solve:
  !! K* on the physical boundary DOFs, in the substructure's placed frame).
  !! Boundary DOFs are listed by the substructure's user node ids and DOF
  !! numbers 1..6, in the physical order (node by node, DOF by DOF).
  !!
  !! FORMAT=ABAQUS: FILE.mtx, Abaqus's matrix input text layout, one line
  !!   `row node, row DOF, column node, column DOF, value` per entry of the
  !!   lower triangle (exact zeros off the diagonal left out), 17 digits (0 as `0`);
  !!   FILE_<step>.load per step: `node, DOF, value` (the data lines of *CLOAD).
  !! FORMAT=CALCULIX: FILE.mtx in the layout of CalculiX's *SUBSTRUCTURE
  !!   GENERATE (*USER ELEMENT with one position per boundary DOF, the
  !!   ** ELEMENT NODES comment, *MATRIX, TYPE=STIFFNESS lower triangle by rows,
  !!   4 values a line); loads as ABAQUS.
  !! FORMAT=DMIG: FILE.dmig, Nastran bulk data in large-field fixed format
  !!   (DMIG* entries, 16-column fields, TIN=2, values D-exponent with 10
  !!   significant digits): K<name> symmetric (IFO=6, lower triangle by
  !!   columns: each column GJ,CJ then its rows Gi,Ci,Ai, i >= j) for K2GG=,
  !!   P<name> rectangular (IFO=9, NCOL = steps in field 9; column k is the
  !!   k-th step of the solve, GJ = k, CJ = 0) for P2G= (and *MATRIX LOAD); <name>: the substructure's name,
  !!   letters and digits only, at most 7 characters.
  !! FORMAT=MATRIX MARKET: FILE.mtx (coordinate real symmetric, lower
  !!   triangle, rows and columns numbered as the DOF map), FILE_loads.mtx
  !!   (array real general, boundary DOFs × steps), FILE_dofs.csv
  !!   (`index,node,dof`).
  use superjoin_kinds, only: wp, i8
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, matrix_export_t, EXPORT_ABAQUS, EXPORT_DMIG, &
       EXPORT_MATRIX_MARKET, EXPORT_CALCULIX
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_substructure_cache, only: part_view_t
  use superjoin_utils_text_buffer, only: text_buffer_t
  use superjoin_utils_process, only: temp_register
  use superjoin_utils_strings, only: itoa, full_real
  implicit none (type, external)
  private

  public :: export_condensed

  character(*), parameter :: TMP_EXT = '.tmp'
  integer, parameter :: CCX_PER_LINE = 4, CCX_NODES_PER_LINE = 10
  integer, parameter :: DMIG_NAME_LEN = 7

  type :: dof_map_t
    !! The boundary DOFs of the exported substructure.
     integer(i8), allocatable :: node(:)     !! user node id
     integer, allocatable :: dof(:)          !! DOF 1..6
  end type dof_map_t

contains

  subroutine export_condensed(model, table, view, kstar, fstar, error)
    !! Write every export that model%exports asks for substructure view%isub
    !! (kstar: its K*, the view's own or the one it shares).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    type(part_view_t), intent(in) :: view
    real(wp), intent(in) :: kstar(:, :)      !! (nb, nb)
    real(wp), intent(in) :: fstar(:, :)      !! (nb, nstep)
    type(error_t), allocatable, intent(out) :: error
    type(dof_map_t) :: map
    integer :: k, j
    if (.not. allocated(model%exports)) return
    if (.not. any(model%exports(:)%sub == view%isub)) return
    allocate (map%node(size(view%se%pdof)), map%dof(size(view%se%pdof)))
    do j = 1, size(view%se%pdof)
       map%node(j) = model%subs(view%isub)%node_id(table%p_node(view%se%pdof(j)))
       map%dof(j) = table%p_dof(view%se%pdof(j))
    end do
    do k = 1, size(model%exports)
       if (model%exports(k)%sub /= view%isub) cycle
       associate (x => model%exports(k), kk => kstar)
         select case (x%format)
         case (EXPORT_ABAQUS)
            call write_abaqus(x%path//'.mtx', model%subs(view%isub)%name, map, kk, error)
         case (EXPORT_CALCULIX)
            call write_calculix(x%path//'.mtx', map, kk, error)
         case (EXPORT_DMIG)
            call write_dmig(x%path//'.dmig', model, view%isub, map, kk, fstar, error)
         case (EXPORT_MATRIX_MARKET)
            call write_mm(x%path, map, kk, fstar, error)
         end select
         if (allocated(error)) return
         if (x%format == EXPORT_ABAQUS .or. x%format == EXPORT_CALCULIX) then
            call write_loads(x%path, model, map, fstar, error)
            if (allocated(error)) return
         end if
       end associate
    end do
  end subroutine export_condensed

  subroutine start(tb, path, error)
    !! Open path's temporary file.
    type(text_buffer_t), intent(inout) :: tb
    character(*), intent(in) :: path
    type(error_t), allocatable, intent(out) :: error
    call temp_register(path//TMP_EXT)
    call tb%open(path//TMP_EXT, error)
  end subroutine start

  subroutine write_abaqus(path, name, map, k, error)
    !! K* in Abaqus's matrix input text layout (lower triangle).
    character(*), intent(in) :: path, name
    type(dof_map_t), intent(in) :: map
    real(wp), intent(in) :: k(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    integer :: i, j
    allocate (tb)
    call start(tb, path, error)
    if (allocated(error)) return
    call tb%line('** superjoin: K* of substructure '//name//', '//itoa(size(map%dof))//' boundary DOFs')
    call tb%line('** row node, row DOF, column node, column DOF, value (lower triangle)')
    do i = 1, size(map%dof)
       do j = 1, i
          if (i /= j .and. k(i, j) == 0.0_wp) cycle
          call tb%line(itoa(map%node(i))//', '//itoa(map%dof(i))//', '//itoa(map%node(j))//', '// &
               itoa(map%dof(j))//', '//full_real(k(i, j)))
       end do
    end do
    call tb%commit(path//TMP_EXT, path, '', error)
  end subroutine write_abaqus

  subroutine write_calculix(path, map, k, error)
    !! K* as CalculiX's *SUBSTRUCTURE GENERATE writes it.
    character(*), intent(in) :: path
    type(dof_map_t), intent(in) :: map
    real(wp), intent(in) :: k(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    integer :: i, j, n
    character(len=11) :: f
    allocate (tb)
    call start(tb, path, error)
    if (allocated(error)) return
    n = size(map%dof)
    call tb%line('**')
    call tb%line('** GENERATION OF SUBSTRUCTURE (superjoin)')
    call tb%line('*USER ELEMENT,NODES='//itoa(n)//',LINEAR')
    call tb%line('** ELEMENT NODES')
    do i = 1, n
       if (mod(i - 1, CCX_NODES_PER_LINE) == 0) call tb%put('**')
       write (f, '(i10,a)') map%node(i), ','
       call tb%put(f)
       if (mod(i, CCX_NODES_PER_LINE) == 0 .or. i == n) call tb%newline()
    end do
    call tb%line(itoa(map%dof(1)))
    do i = 2, n
       call tb%line(itoa(i)//', '//itoa(map%dof(i)))
    end do
    call tb%line('*MATRIX,TYPE=STIFFNESS')
    do i = 1, n
       do j = 1, i
          call tb%put(full_real(k(i, j))//',')
          if (mod(j, CCX_PER_LINE) == 0 .or. j == i) call tb%newline()
       end do
    end do
    call tb%commit(path//TMP_EXT, path, '', error)
  end subroutine write_calculix

  subroutine write_loads(base, model, map, fstar, error)
    !! base_<step>.load: `node, DOF, value` of f* for each step of the solve.
    character(*), intent(in) :: base
    type(model_t), intent(in) :: model
    type(dof_map_t), intent(in) :: map
    real(wp), intent(in) :: fstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    character(:), allocatable :: path
    integer :: s, i
    allocate (tb)
    do s = 1, size(fstar, 2)
       path = base//'_'//step_tag(model%steps(s)%name)//'.load'
       call start(tb, path, error)
       if (allocated(error)) return
       call tb%line('** superjoin: f* of step '//model%steps(s)%name//' (node, DOF, value: *CLOAD data lines)')
       do i = 1, size(map%dof)
          call tb%line(itoa(map%node(i))//', '//itoa(map%dof(i))//', '//full_real(fstar(i, s)))
       end do
       call tb%commit(path//TMP_EXT, path, '', error)
       if (allocated(error)) return
    end do
  end subroutine write_loads

  pure function step_tag(name) result(t)
    !! A step name as part of a file name: characters other than letters,
    !! digits, '-' and '_' become '_'.
    character(*), intent(in) :: name
    character(:), allocatable :: t
    integer :: i
    t = name
    do i = 1, len(t)
       select case (t(i:i))
       case ('A':'Z', 'a':'z', '0':'9', '-', '_')
       case default
          t(i:i) = '_'
       end select
    end do
  end function step_tag

  pure function dmig_name(prefix, name) result(t)
    !! prefix and the letters and digits of name, at most 8 characters.
    character(*), intent(in) :: prefix, name
    character(:), allocatable :: t
    integer :: i
    t = prefix
    do i = 1, len(name)
       if (len(t) > DMIG_NAME_LEN) exit
       select case (name(i:i))
       case ('A':'Z', 'a':'z', '0':'9')
          t = t//name(i:i)
       end select
    end do
  end function dmig_name

  function f16(s) result(t)
    !! s right-aligned in a 16-column field.
    character(*), intent(in) :: s
    character(len=16) :: t
    t = adjustr(s)
  end function f16

  function d16(x) result(t)
    !! x in 16 columns, double precision exponent (D), 10 significant digits.
    real(wp), intent(in) :: x
    character(len=16) :: t
    write (t, '(es16.9e2)') x
    t(index(t, 'E'):index(t, 'E')) = 'D'
  end function d16

  subroutine write_dmig(path, model, isub, map, k, fstar, error)
    !! K* and f* as Nastran DMIG bulk data (large field, see the module comment).
    character(*), intent(in) :: path
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(dof_map_t), intent(in) :: map
    real(wp), intent(in) :: k(:, :), fstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    character(len=8), parameter :: HEAD = 'DMIG*   ', CONT = '*       '
    character(:), allocatable :: kn, pn
    integer :: i, j, s
    allocate (tb)
    call start(tb, path, error)
    if (allocated(error)) return
    kn = dmig_name('K', model%subs(isub)%name)
    pn = dmig_name('P', model%subs(isub)%name)
    call tb%line('$ superjoin: K* and f* of substructure '//model%subs(isub)%name//': K2GG = '//kn// &
         ', P2G = '//pn)
    call tb%line(HEAD//f16(kn)//f16('0')//f16('6')//f16('2'))
    call tb%line(CONT//f16('0'))
    do j = 1, size(map%dof)
       call tb%line(HEAD//f16(kn)//f16(itoa(map%node(j)))//f16(itoa(map%dof(j))))
       do i = j, size(map%dof)
          if (i /= j .and. k(i, j) == 0.0_wp) cycle
          call tb%line(CONT//f16(itoa(map%node(i)))//f16(itoa(map%dof(i)))//d16(k(i, j)))
       end do
    end do
    call tb%line(HEAD//f16(pn)//f16('0')//f16('9')//f16('2'))
    call tb%line(CONT//f16('0')//f16('')//f16('')//f16(itoa(size(fstar, 2))))   ! TOUT, POLAR, -, NCOL
    do s = 1, size(fstar, 2)
       call tb%line('$ column '//itoa(s)//': step '//model%steps(s)%name)
       call tb%line(HEAD//f16(pn)//f16(itoa(s))//f16('0'))
       do i = 1, size(map%dof)
          if (fstar(i, s) == 0.0_wp) cycle
          call tb%line(CONT//f16(itoa(map%node(i)))//f16(itoa(map%dof(i)))//d16(fstar(i, s)))
       end do
    end do
    call tb%commit(path//TMP_EXT, path, '', error)
  end subroutine write_dmig

  subroutine write_mm(base, map, k, fstar, error)
    !! K* and f* as Matrix Market files with a CSV DOF map.
    character(*), intent(in) :: base
    type(dof_map_t), intent(in) :: map
    real(wp), intent(in) :: k(:, :), fstar(:, :)
    type(error_t), allocatable, intent(out) :: error
    type(text_buffer_t), allocatable :: tb
    integer :: i, j, n, nnz
    allocate (tb)
    n = size(map%dof)
    call start(tb, base//'.mtx', error)
    if (allocated(error)) return
    nnz = 0
    do j = 1, n
       nnz = nnz + 1 + count(k(j + 1:n, j) /= 0.0_wp)
    end do
    call tb%line('%%MatrixMarket matrix coordinate real symmetric')
    call tb%line('% superjoin: K* (lower triangle); rows and columns: '//basename(base)//'_dofs.csv')
    call tb%line(itoa(n)//' '//itoa(n)//' '//itoa(nnz))
    do j = 1, n
       do i = j, n
          if (i /= j .and. k(i, j) == 0.0_wp) cycle
          call tb%line(itoa(i)//' '//itoa(j)//' '//full_real(k(i, j)))
       end do
    end do
    call tb%commit(base//'.mtx'//TMP_EXT, base//'.mtx', '', error)
    if (allocated(error)) return
    call start(tb, base//'_loads.mtx', error)
    if (allocated(error)) return
    call tb%line('%%MatrixMarket matrix array real general')
    call tb%line('% superjoin: f*, one column per step; rows: '//basename(base)//'_dofs.csv')
    call tb%line(itoa(n)//' '//itoa(size(fstar, 2)))
    do j = 1, size(fstar, 2)
       do i = 1, n
          call tb%line(full_real(fstar(i, j)))
       end do
    end do
    call tb%commit(base//'_loads.mtx'//TMP_EXT, base//'_loads.mtx', '', error)
    if (allocated(error)) return
    call start(tb, base//'_dofs.csv', error)
    if (allocated(error)) return
    call tb%line('index,node,dof')
    do i = 1, n
       call tb%line(itoa(i)//','//itoa(map%node(i))//','//itoa(map%dof(i)))
    end do
    call tb%commit(base//'_dofs.csv'//TMP_EXT, base//'_dofs.csv', '', error)
  end subroutine write_mm

  pure function basename(path) result(b)
    character(*), intent(in) :: path
    character(:), allocatable :: b
    b = path(index(path, '/', back=.true.) + 1:)
  end function basename
end module superjoin_analysis_matrix_export
