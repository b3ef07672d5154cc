module superjoin_elements_solid_reduced
  !! C3D8R, the 8-node hexahedron with one integration point and hourglass
  !! stiffness:
  !!
  !!   K = V B̄ᵀ D B̄ + Γ (Hᵀ K_I H) Γᵀ.
  !!
  !! - B̄: the uniform (mean) strain operator of Flanagan & Belytschko (1981),
  !!   b̄_a = (1/V) ∫ ∂N_a/∂x dV, V = ∫ dV (2×2×2 Gauss: exact for the
  !!   trilinear hexahedron); the stress is D B̄ u_e, reported at the centre;
  !! - H(24, 12): the hourglass base vectors h_1..h_4 = ξη, ηζ, ζξ, ξηζ at the
  !!   nodes, for each displacement component; Γ(24, 12) Flanagan and
  !!   Belytschko's γ vectors γ_α = (h_α - Σ_j (h_α·x_j) b̄_j)/8, orthogonal to
  !!   every linear field (γ_α·1 = 0, γ_α·x_j = 0): the hourglass term never
  !!   acts on a constant strain, so the element passes the patch test on any
  !!   shape, and Γ has rank 12, so K has exactly the six rigid-body zero
  !!   energies;
  !! - K_I: the stiffness of the same element as C3D8I (incompatible modes,
  !!   superjoin_elements_solid); Hᵀ K_I H is its stiffness in the hourglass
  !!   modes. On a parallelepiped (B̄ h_α = 0, Γᵀ H = I) K equals K_I exactly:
  !!   the hourglass modes get the physical stiffness of the enhanced element,
  !!   bending included (no user coefficient). This is a physical stabilization
  !!   in the spirit of Abaqus's default "enhanced" hourglass control (based on
  !!   enhanced assumed strains); CalculiX (ccx ≥ 2.3, shape8hr/hgstiffness)
  !!   uses Flanagan and Belytschko's scalar stiffness form instead,
  !!   0.0005 E (Σ B:B)/V γγᵀ (B = V b̄) with unnormalized γ: on MacNeal and
  !!   Harder's cantilever 0.657 of beam theory, ours 0.979
  !!   (doc/verification.md, "C3D8R").
  use superjoin_kinds, only: wp
  implicit none (type, external)
  private

  public :: hourglass_stiffness

contains

  pure function hourglass_bases() result(h)
    !! The hourglass base vectors h(8, 4) = ξη, ηζ, ζξ, ξηζ at the corners (Abaqus order).
    real(wp) :: h(8, 4)
    real(wp), parameter :: C(3, 8) = reshape([-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, &
         -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1]*1.0_wp, [3, 8])
    h(:, 1) = C(1, :)*C(2, :)
    h(:, 2) = C(2, :)*C(3, :)
    h(:, 3) = C(3, :)*C(1, :)
    h(:, 4) = C(1, :)*C(2, :)*C(3, :)
  end function hourglass_bases

  pure function hourglass_stiffness(x, bbar, ke_i) result(khg)
    !! Γ (Hᵀ K_I H) Γᵀ (see the module header) of the hexahedron with corners
    !! x(3, 8), mean gradients bbar(3, 8) and incompatible-mode stiffness
    !! ke_i(24, 24) (node-major DOFs).
    real(wp), intent(in) :: x(3, 8), bbar(3, 8), ke_i(24, 24)
    real(wp) :: khg(24, 24)
    real(wp) :: h(8, 4), gam(8, 4), hm(24, 12), gm(24, 12)
    integer :: a, i, k
    h = hourglass_bases()
    do k = 1, 4
       gam(:, k) = (h(:, k) - matmul(matmul(x, h(:, k)), bbar))/8.0_wp
    end do
    hm = 0.0_wp
    gm = 0.0_wp
    do k = 1, 4
       do i = 1, 3
          do a = 1, 8
             hm(3*(a - 1) + i, 3*(k - 1) + i) = h(a, k)
             gm(3*(a - 1) + i, 3*(k - 1) + i) = gam(a, k)
          end do
       end do
    end do
    khg = matmul(gm, matmul(matmul(transpose(hm), matmul(ke_i, hm)), transpose(gm)))
  end function hourglass_stiffness
end module superjoin_elements_solid_reduced
