module superjoin_model_material_table
  !! Temperature-dependent materials: *ELASTIC and *EXPANSION with several
  !! data lines, the last field of each the temperature (Abaqus, CalculiX).
  !! A value is interpolated linearly between the lines and constant outside
  !! the table, as CalculiX does. With a table of α, the thermal strain is the
  !! secant one of *EXPANSION, ZERO=Z: α(T) (T - Z) - α(T0) (T0 - Z) from the
  !! initial temperature T0 to T (CalculiX, Abaqus); with a constant α it is
  !! α (T - T0), which ZERO= does not change.
  use superjoin_kinds, only: wp
  use superjoin_model_types, only: material_t
  implicit none (type, external)
  private

  public :: table_value, material_at, thermal_strain, has_table, point_material, point_thermal_strain

contains

  pure real(wp) function table_value(table, row, t) result(v)
    !! Row `row` of table(:, n) (its last row the temperatures, increasing) at
    !! temperature t: linear between the lines, constant outside.
    real(wp), intent(in) :: table(:, :), t
    integer, intent(in) :: row
    integer :: n, k, nt
    real(wp) :: w
    nt = size(table, 1)
    n = size(table, 2)
    if (t <= table(nt, 1)) then
       v = table(row, 1)
       return
    end if
    do k = 2, n
       if (t <= table(nt, k)) then
          w = (t - table(nt, k - 1))/(table(nt, k) - table(nt, k - 1))
          v = table(row, k - 1) + w*(table(row, k) - table(row, k - 1))
          return
       end if
    end do
    v = table(row, n)
  end function table_value

  pure logical function has_table(mat)
    !! Whether a material has a temperature-dependent *ELASTIC or *EXPANSION.
    type(material_t), intent(in) :: mat
    has_table = varies(mat%elastic_table) .or. varies(mat%expansion_table)
  end function has_table

  pure logical function varies(table)
    !! A table of two lines or more (one line: a constant, its temperature any value).
    real(wp), allocatable, intent(in) :: table(:, :)
    varies = .false.
    if (allocated(table)) varies = size(table, 2) > 1
  end function varies

  pure function material_at(mat, t) result(m)
    !! The material with its E, ν and α at temperature t (its tables kept).
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: t
    type(material_t) :: m
    m = mat
    if (varies(mat%elastic_table)) then
       m%e = table_value(mat%elastic_table, 1, t)
       m%nu = table_value(mat%elastic_table, 2, t)
    end if
    if (varies(mat%expansion_table)) m%alpha = table_value(mat%expansion_table, 1, t)
  end function material_at

  pure function point_material(mat, n) result(m)
    !! The material at a point of a solid element with shape functions n: its
    !! values at the temperature there (Σ N_a T_a, mat%at_nodes), or mat.
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: n(:)
    type(material_t) :: m
    if (.not. allocated(mat%at_nodes)) then
       m = mat
       return
    end if
    m = material_at(mat, dot_product(n, mat%at_nodes(2, :)))
  end function point_material

  pure real(wp) function point_thermal_strain(mat, n, eth) result(e)
    !! The thermal strain at a point of a solid element with shape functions
    !! n: Σ N_a eth_a of its nodal strains eth, or with a table of α (and the
    !! element's temperatures, mat%at_nodes) the secant strain between the
    !! temperatures interpolated to the point, as CalculiX.
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: n(:), eth(:)
    if (allocated(mat%at_nodes) .and. varies(mat%expansion_table)) then
       e = thermal_strain(mat, dot_product(n, mat%at_nodes(2, :)), dot_product(n, mat%at_nodes(1, :)))
    else
       e = dot_product(n, eth)
    end if
  end function point_thermal_strain

  pure real(wp) function thermal_strain(mat, t, t0) result(e)
    !! The thermal strain from the initial temperature t0 to t: α (t - t0), or
    !! with a table of α the secant α(t) (t - Z) - α(t0) (t0 - Z), Z = ZERO=.
    type(material_t), intent(in) :: mat
    real(wp), intent(in) :: t, t0
    if (.not. varies(mat%expansion_table)) then
       e = mat%alpha*(t - t0)
       return
    end if
    e = table_value(mat%expansion_table, 1, t)*(t - mat%zero) - table_value(mat%expansion_table, 1, t0)*(t0 - mat%zero)
  end function thermal_strain
end module superjoin_model_material_table
