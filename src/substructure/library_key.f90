module superjoin_substructure_library_key
  !! The keys of the condensation library (issue 26): what a part's
  !! condensation depends on, hashed without assembling its stiffness.
  !!
  !! The input key is the SHA-256 of everything the stiffness assembly of a
  !! part reads (build_local_system → element_matrix → element_stiffness,
  !! a pure function of the element type, its node coordinates, its section,
  !! its material and its drilling edge mask) and of what the condensation
  !! adds (the local numbering, the solver):
  !!   - the program version, FORMULATION_VERSION and the solver's name;
  !!   - the local numbering: interior and boundary DOF counts and the local
  !!     node and DOF number of every local DOF, interior first (the boundary
  !!     is where contacts, supports, equations and exports touch: a support
  !!     moved inside the part changes it);
  !!   - the node coordinates as the elements see them (the substructure's
  !!     own, placement applied), element types (reduced integration,
  !!     incompatible modes are types), connectivity, section index and
  !!     drilling edge mask of every element (the masks depend on supports
  !!     and contacts: superjoin_elements_drill_mask);
  !!   - every section of the part, whole: kind, area, inertias, torsion,
  !!     thickness, beam orientation vector, shear stiffnesses and factor,
  !!     fibre points, nodal thicknesses, the material axes (*ORIENTATION of
  !!     a solid section);
  !!   - the material of each section, whole: E, ν, kind and the
  !!     orthotropic/anisotropic constants and stiffness, density, expansion,
  !!     temperature tables and the nodal temperatures of a temperature-
  !!     dependent copy (temperatures enter k only there; otherwise loads);
  !!   - a given stiffness (*MATRIX INPUT): rows and values.
  !! Not hashed, because k and the stored fields do not depend on them: loads
  !! (each load set has its own key inside the entry), *TRANSFORM (applied
  !! to the physical DOFs by the reduced transform, after K*), contact
  !! stiffnesses. Names and deck locations are not hashed (only messages).
  !!
  !! The sample hash (checked on every load, cheap) is the SHA-256 of the
  !! element stiffnesses of a few elements: the first of every element type
  !! of the part, its middle one and its last. It catches element code that
  !! changed without FORMULATION_VERSION being bumped, for the types the part
  !! uses. The stiffness hash is the former key, the SHA-256 of the assembled
  !! k (pattern and values, local numbering): stored in every entry and
  !! compared on load under --library-verify, which then assembles k.
  use superjoin_kinds, only: wp, ip, i8
  use superjoin_config, only: SUPERJOIN_VERSION
  use superjoin_error, only: error_t
  use superjoin_model_types, only: model_t, section_t, material_t
  use superjoin_assembly_dofs, only: dof_table_t
  use superjoin_assembly_assemble, only: element_matrix
  use superjoin_elements_traits, only: element_traits, element_traits_t
  use superjoin_substructure_local_system, only: local_system_t
  use superjoin_utils_sha256, only: sha256_t, update, digest
  implicit none (type, external)
  private

  integer, parameter, public :: FORMULATION_VERSION = 2
    !! Version of the element formulations. BUMP IT whenever code under
    !! src/elements/ (or element_matrix) changes what an element stiffness is:
    !! every library key changes with it, so no entry of older code is used.
    !! (The sample hash catches a forgotten bump for the sampled types only.)
  integer, parameter, public :: KEY_LEN = 64
    !! Hexadecimal digits of a key.

  public :: input_key, copy_key, sample_hash, stiffness_hash, hash_section, hash_material

contains

  function input_key(model, table, isub, pdof, ni, solver_name, x) result(key)
    !! The library key of substructure isub with local DOFs pdof (ni interior
    !! first): the SHA-256 of its condensation's inputs (module comment).
    !! x: other coordinates of its nodes in place of its own (a translated
    !! copy's entry checked: copy_key).
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    integer(i8), intent(in) :: pdof(:)
    integer(i8), intent(in) :: ni
    character(*), intent(in) :: solver_name
    real(wp), intent(in), optional :: x(:, :)
    character(len=KEY_LEN) :: key
    key = part_key('input key', model, table, isub, pdof, ni, solver_name, .true., x)
  end function input_key

  function copy_key(model, table, isub, pdof, ni, solver_name) result(key)
    !! The key of the translated copies of substructure isub: what input_key
    !! hashes but the node coordinates (the parts that differ from it only by
    !! a translation share it: superjoin_substructure_library finds their
    !! entries through it and checks the translation). Blank where a
    !! translation may change the stiffness: a part with an axisymmetric
    !! element (its radius is x), a given stiffness, or a cylindrical system
    !! of material axes (its axis is fixed in space); and a part without
    !! nodes or elements.
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    integer(i8), intent(in) :: pdof(:)
    integer(i8), intent(in) :: ni
    character(*), intent(in) :: solver_name
    character(len=KEY_LEN) :: key
    key = ''
    if (.not. translatable(model, isub)) return
    key = part_key('copy key', model, table, isub, pdof, ni, solver_name, .false.)
  end function copy_key

  function part_key(tag, model, table, isub, pdof, ni, solver_name, placed, x) result(key)
    !! The SHA-256 of substructure isub's condensation inputs under tag; placed:
    !! with its node coordinates (x in place of its own, if given).
    character(*), intent(in) :: tag
    type(model_t), intent(in) :: model
    type(dof_table_t), intent(in) :: table
    integer, intent(in) :: isub
    integer(i8), intent(in) :: pdof(:)
    integer(i8), intent(in) :: ni
    character(*), intent(in) :: solver_name
    logical, intent(in) :: placed
    real(wp), intent(in), optional :: x(:, :)
    character(len=KEY_LEN) :: key
    type(sha256_t) :: s
    call update(s, 'SJCONDLB '//tag//'|'//SUPERJOIN_VERSION//'|'//solver_name//'|')
    call update(s, [int(FORMULATION_VERSION, i8), ni, size(pdof, kind=i8)])
    call update(s, int(table%p_node(pdof), ip))
    call update(s, int(table%p_dof(pdof)))
    associate (sub => model%subs(isub))
      call update(s, [int(sub%nnode, i8), int(sub%nelem, i8), int(size(sub%elem_nodes, 1), i8)])
      if (placed .and. present(x)) then
         call update(s, x)
      else if (placed .and. sub%nnode > 0) then
         call update(s, sub%x(:, 1:sub%nnode))
      end if
    end associate
    call hash_content(s, model, isub)
    key = digest(s)
  end function part_key

  logical function translatable(model, isub)
    !! Whether a translation of substructure isub keeps its stiffness
    !! (copy_key).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(element_traits_t) :: t
    integer(ip) :: e
    integer :: i
    translatable = .false.
    associate (sub => model%subs(isub))
      if (sub%nnode < 1 .or. sub%nelem < 1 .or. allocated(sub%given)) return
      do e = 1, sub%nelem
         if (e > 1) then
            if (sub%elem_type(e) == sub%elem_type(e - 1)) cycle   ! a run of one type once
         end if
         t = element_traits(sub%elem_type(e))
         if (t%axisymmetric) return
      end do
      if (allocated(sub%sections)) then
         do i = 1, size(sub%sections)
            if (.not. allocated(sub%sections(i)%axes)) cycle
            if (sub%sections(i)%axes%cylindrical) return
         end do
      end if
    end associate
    translatable = .true.
  end function translatable

  subroutine hash_content(s, model, isub)
    !! The keys' part after the coordinates: elements, drilling masks,
    !! sections and their materials, a given stiffness.
    type(sha256_t), intent(inout) :: s
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    integer :: i
    logical :: has
    associate (sub => model%subs(isub))
      if (sub%nelem > 0) then
         call update(s, sub%elem_type(1:sub%nelem))
         call update(s, reshape(sub%elem_nodes(:, 1:sub%nelem), [size(sub%elem_nodes, 1)*sub%nelem]))
         call update(s, sub%elem_section(1:sub%nelem))
      end if
      call update(s, [flag(allocated(sub%elem_drill))])
      if (allocated(sub%elem_drill)) call update(s, [size(sub%elem_drill), sub%elem_drill])
      call update(s, [flag(allocated(sub%sections))])
      if (allocated(sub%sections)) then
         call update(s, [size(sub%sections)])
         do i = 1, size(sub%sections)
            call hash_section(s, sub%sections(i))
            has = sub%sections(i)%material >= 1 .and. sub%sections(i)%material <= size(model%materials)
            call update(s, [flag(has)])   ! (the section's material index is not hashed)
            if (has) call hash_material(s, model%materials(sub%sections(i)%material))
         end do
      end if
      call update(s, [flag(allocated(sub%given))])
      if (allocated(sub%given)) then
         call update(s, [size(sub%given%node), size(sub%given%dof)])
         call update(s, sub%given%node)
         call update(s, sub%given%dof)
         call update(s, sub%given%k)
      end if
    end associate
  end subroutine hash_content

  subroutine hash_section(s, sec, placed)
    !! Every field of a section an element may read but the material's index
    !! (the caller hashes the material itself: equal materials of other names
    !! match). placed false (the identical parts of
    !! superjoin_substructure_twins): the beam orientation vector and the
    !! material axes left out too, as they turn with the part (zeros in v's
    !! place; the twins check them turned).
    type(sha256_t), intent(inout) :: s
    type(section_t), intent(in) :: sec
    logical, intent(in), optional :: placed
    logical :: with_place
    with_place = .true.
    if (present(placed)) with_place = placed
    call update(s, [sec%kind, 0, sec%nfibre, flag(sec%has_v), flag(sec%nodal_thickness), &
         flag(allocated(sec%node_thickness)), flag(allocated(sec%axes))])
    call update(s, [sec%area, sec%iy, sec%iz, sec%j, sec%thickness, merge(sec%v, 0.0_wp, with_place), sec%shear_k, &
         sec%shear_factor])
    call update(s, sec%fibre)
    if (allocated(sec%node_thickness)) call update(s, [real(size(sec%node_thickness), wp), sec%node_thickness])
    if (allocated(sec%axes) .and. with_place) then
       call update(s, [flag(sec%axes%cylindrical)])
       call update(s, sec%axes%q)
       call update(s, [sec%axes%a, sec%axes%b])
    end if
  end subroutine hash_section

  subroutine hash_material(s, mat)
    !! Every constant of a material (temperature tables and nodal
    !! temperatures of a temperature-dependent copy included).
    type(sha256_t), intent(inout) :: s
    type(material_t), intent(in) :: mat
    call update(s, [mat%kind, flag(mat%has_elastic), flag(mat%has_density), flag(mat%has_expansion), &
         flag(allocated(mat%elastic_table)), flag(allocated(mat%expansion_table)), flag(allocated(mat%at_nodes))])
    call update(s, [mat%e, mat%nu, mat%density, mat%alpha, mat%zero])
    call update(s, mat%given)
    call update(s, mat%d)
    if (allocated(mat%elastic_table)) call hash_table(s, mat%elastic_table)
    if (allocated(mat%expansion_table)) call hash_table(s, mat%expansion_table)
    if (allocated(mat%at_nodes)) call hash_table(s, mat%at_nodes)
  end subroutine hash_material

  subroutine hash_table(s, t)
    !! A table's shape and values.
    type(sha256_t), intent(inout) :: s
    real(wp), intent(in) :: t(:, :)
    call update(s, [size(t, 1), size(t, 2)])
    call update(s, t)
  end subroutine hash_table

  pure integer function flag(yes)
    !! 1 or 0.
    logical, intent(in) :: yes
    flag = merge(1, 0, yes)
  end function flag

  function sample_hash(model, isub, error, x) result(key)
    !! The SHA-256 of the element stiffnesses of the sample elements of
    !! substructure isub: the first element of each type, the middle one and
    !! the last one (module comment). x: its nodes at these coordinates
    !! instead (a translated copy's entry checked on that copy's nodes).
    type(model_t), intent(in) :: model
    integer, intent(in) :: isub
    type(error_t), allocatable, intent(out) :: error
    real(wp), intent(in), optional :: x(:, :)
    character(len=KEY_LEN) :: key
    type(sha256_t) :: s
    real(wp), allocatable :: ke(:, :)
    integer(ip) :: e, n
    integer, allocatable :: seen(:)
    logical :: new
    call update(s, 'SJCONDLB samples|')
    n = model%subs(isub)%nelem
    allocate (seen(0))
    do e = 1, n
       new = .not. any(seen == model%subs(isub)%elem_type(e))
       if (.not. (new .or. e == (n + 1)/2 .or. e == n)) cycle
       if (new) seen = [seen, model%subs(isub)%elem_type(e)]
       call element_matrix(model, isub, e, ke, error, x)
       if (allocated(error)) return
       call update(s, [int(e), size(ke, 1)])
       call update(s, ke)
    end do
    key = digest(s)
  end function sample_hash

  function stiffness_hash(sys, solver_name) result(key)
    !! The SHA-256 of the assembled k (pattern and values, local numbering)
    !! and the solver: what the key was before the input key.
    type(local_system_t), intent(in) :: sys
    character(*), intent(in) :: solver_name
    character(len=KEY_LEN) :: key
    type(sha256_t) :: s
    call update(s, 'SJCONDLB stiffness|'//solver_name//'|')
    call update(s, [int(FORMULATION_VERSION, i8), sys%ni, sys%nb, sys%k%n])
    call update(s, sys%k%colptr)
    call update(s, int(sys%k%rowind, ip))   ! row numbers of one part fit 32 bits
    call update(s, sys%k%val)
    key = digest(s)
  end function stiffness_hash
end module superjoin_substructure_library_key
