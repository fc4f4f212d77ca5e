#pragma once
// The velocity tangent ∂(M a + F)/∂dq of material riding on an interpolated section
// (timoshenko_beam.hpp: section map H(q, ξ), its rate Ḣ along the motion), in closed form: the
// Jacobian's velocity columns at the cost of about one residual, instead of 24 residuals by
// polarization (element.hpp).
//
// A mass station on the section at ξ carries mass m, first moment s and inertia J (section
// frame, about the axis point). Its share of M a + F is r = H_xᵀ f + H_Ωᵀ τ with
//   f = m (ẍ − g) + R_c (Ω̇ × s + Ω × (Ω × s)),   τ = s × R_cᵀ (ẍ − g) + J Ω̇ + Ω × J Ω,
//   ẍ = H_x a + Ḣ_x dq,   Ω̇ = H_Ω a + Ḣ_Ω dq,   Ω = H_Ω dq.
// Ḣ dq is quadratic in dq, but its derivative is not 2Ḣ: the rotational velocities are twists
// (R + δR = R (I + δθ̃)), whose directional derivatives do not commute, D_u D_w − D_w D_u = D_[u,w]
// with [u, w] = u_ω × w_ω node by node (the bracket of left-invariant fields on SO(3)). Writing
// C(dq) u = [dq, u] (the blocks ω̃ⁿ on each node's rotation, zero on its translation):
//   ∂(Ḣ_x dq)/∂dq = 2Ḣ_x − H_x C,
//   ∂(Ḣ_Ω dq)/∂dq = 2Ḣ_Ω − H_Ω C + Ω̃ H_Ω,
// the second because R_cᵀ D_u R_c = (H_Ω u)~ gives D_u(H_Ω w) − D_w(H_Ω u) = H_Ω [u, w] − H_Ω u × H_Ω w.
// The terms in C add up over the stations to −M C (they are M's own products), so
//   ∂r/∂dq = −M C + Σ H_xᵀ (2 (m Ḣ_x − R_c s̃ Ḣ_Ω) − R_c ((Ω × s)~ + Ω̃ s̃ + s̃ Ω̃) H_Ω)
//                 + H_Ωᵀ (2 (s̃ R_cᵀ Ḣ_x + J Ḣ_Ω) + (J Ω̃ + Ω̃ J − (J Ω)~) H_Ω),
//   M = Σ H_xᵀ (m H_x − R_c s̃ H_Ω) + H_Ωᵀ (s̃ R_cᵀ H_x + J H_Ω).
// The sum G = ∂r/∂dq + M C is formed like the mass matrix (section_mass_matrix.hpp), from
// station sums in the axes of end 1 with everything that does not depend on ξ left outside.
// With E_R = exp(ψ̃), E_T = T(ψ), ψ = ξφ (they commute, E_R E_T = E_Tᵀ), ω_E = E_T ψ̇ (so
// Ė_R = E_R ω̃_E), Ω = E_Rᵀ ω¹ + ω_E, the maps split into station factors and per-call selectors
//   R¹ᵀ H_x = Σ N_j R¹ᵀB_j,   R¹ᵀ Ḣ_x = N₁ Ẏ₁ + N₃ Ẏ₃,   Ẏ₁ = [0, −ω̃¹ẽ_x, 0, 0],  Ẏ₃ = [0, 0, 0, −R_rel ω̃² ẽ_x],
//   H_Ω = E_Rᵀ P₁ + ξ E_T P_φ,   Ḣ_Ω = −ω̃_E E_Rᵀ P₁ + ξ Ė_T P_φ + ξ E_T Ṗ_φ,
//   P₁ = [0, I, 0, 0],  P_φ = ∂φ̇/∂dq = [0, −T(φ)⁻¹R_relᵀ, 0, T(φ)⁻¹],  Ṗ_φ its rate,
// and with the mass matrix's sums μ_jk, U_k, S_k, A₀₁, A₁₁ and these:
//   Q₁ = E_R (2 s̃ ω̃_E − K) E_Rᵀ,  Q₂ = −ξ E_R (2 s̃ Ė_T + K E_T),  K = (Ω × s)~ + Ω̃ s̃ + s̃ Ω̃,
//   Y = (g_τ − 2 J ω̃_E) E_Rᵀ,  Z = 2 J Ė_T + g_τ E_T,  g_τ = J Ω̃ + Ω̃ J − (J Ω)~,
//   F_j = Σ N_j Q₁,  Φ_j = Σ N_j Q₂,  A_11 = Σ E_R Y,  A_φ1 = Σ ξ E_Tᵀ Y,  A_1φ = Σ ξ E_R Z,  A_φφ = Σ ξ² E_Tᵀ Z,
// G = Σ_j L_j (2 μ_j1 Ẏ₁ + 2 μ_j3 Ẏ₃ + F_j P₁ + Φ_j P_φ − 2 S_j Ṗ_φ)
//   + P₁ᵀ (2 Ũ₁ Ẏ₁ + 2 Ũ₃ Ẏ₃ + A_11 P₁ + A_1φ P_φ + 2 A₀₁ Ṗ_φ)
//   + P_φᵀ (−2 S₁ᵀ Ẏ₁ − 2 S₃ᵀ Ẏ₃ + A_φ1 P₁ + A_φφ P_φ + 2 A₁₁ Ṗ_φ),
// L_j = B_jᵀ R¹ the rows [R¹; 0; 0; 0], [0; ẽ_x; 0; 0], [0; 0; R¹; 0], [0; 0; 0; ẽ_x R_relᵀ] (the
// terms m Ḣ_x, s̃ R_cᵀ Ḣ_x and J Ṗ_φ need no sums of their own: E_R s̃ E_Rᵀ = ũ, ξ E_Tᵀ s̃ E_Rᵀ =
// ξ E_T ũ, E_R s̃ E_T = ũ E_Tᵀ). A station costs the mass matrix's five 3 × 3 products and about
// a dozen more (≈ 2 600 instructions with a first moment and a full inertia, mass matrix
// included); the kernel then subtracts M C once (subtractTwistBracket).
//
// The coordinate columns ∂r/∂q come from end 2's by frame indifference (objective_tangent.hpp);
// the inertial and gravity forces of an interpolation whose centre-line tangents and section
// rotations follow the end rotations alone (x = Σ Nᵢ rⁱ + N' Rⁱ e_x, R_c = R¹ exp(ξ φ̃)) do not
// depend on the end positions, so of those only end 2's three rotation directions are
// differentiated.

#include <Eigen/Dense>

#include "cranesim/elements/parts/section_mass_matrix.hpp"
#include "cranesim/math/hermite.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

/// M and G = ∂r/∂dq + M C(dq) of mass stations riding on the section interpolation (file
/// comment), from the end frames and their rates along the motion.
class SectionInertiaTangent : public SectionMassMatrix<double> {
 public:
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  /// End rotation R¹, R_rel = R¹ᵀR², φ = log(R_rel), its rate φ̇, T(φ)⁻¹ and T(φ)⁻¹R_relᵀ with
  /// their rates, the end velocities dq and the length that scales the Hermite slopes.
  SectionInertiaTangent(const Mat3& R1, const Mat3& Rrel, const Vec3& phi, const Vec3& phi_dot, const Mat3& Tinv,
                        const Mat3& TinvRrelT, const Mat3& Tinv_dot, const Mat3& TinvRrelT_dot,
                        const Eigen::Matrix<double, 12, 1>& v, double length)
      : SectionMassMatrix<double>(R1, Rrel, phi, Tinv, length),
        phi_dot_(phi_dot),
        omega1_(v.segment<3>(3)),
        omega2_(v.segment<3>(9)),
        TinvRrelT_(TinvRrelT),
        Tinv_dot_(Tinv_dot),
        TinvRrelT_dot_(TinvRrelT_dot) {
    for (int j = 0; j < 4; ++j) F_[j].setZero(), Phi_[j].setZero();
    A_11_.setZero(), A_phi1_.setZero(), A_1phi_.setZero(), A_phiphi_.setZero();
  }

  /// Adds a mass station: mass m, first moment s and inertia J about the axis point (section
  /// axes) on the section at ξ.
  [[gnu::flatten]] void add(double xi, double mass, const Vec3& first_moment, const Mat3& inertia);

  /// G = ∂r/∂dq + M C of the stations added (file comment); its translation columns are zero.
  /// Without first moments (a beam's Gauss points) F_j, Φ_j, S_j and U_k vanish.
  Mat12 velocityTangent() const;

 private:
  Vec3 phi_dot_, omega1_, omega2_;
  Mat3 TinvRrelT_, Tinv_dot_, TinvRrelT_dot_;
  Mat3 F_[4], Phi_[4];  // Σ N_j Q₁, Σ N_j Q₂
  Mat3 A_11_, A_phi1_, A_1phi_, A_phiphi_;
  bool first_moments_ = false;  // a station with s ≠ 0 was added
};

/// G − M C(dq) in place: C has the blocks ω̃ⁿ (ωⁿ = dq's rotational velocity of node n) on the
/// diagonal of each node's rotation.
void subtractTwistBracket(const Eigen::Matrix<double, 12, 12>& M, const Eigen::Matrix<double, 12, 1>& v,
                          Eigen::Matrix<double, 12, 12>& G);

}  // namespace cranesim
