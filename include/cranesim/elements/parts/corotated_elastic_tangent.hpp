#pragma once
// The co-rotated beam's elastic and damping forces f = J_dᵀ s, s = K (d + η J_d dq)
// (timoshenko_beam.hpp: elasticForce), with their derivatives along end 2's translation δr² and
// twist δθ² (R² → R²(I + δθ̃²)): the six columns from which objective_tangent.hpp builds all
// twelve. In closed form but for one row of W, instead of forward AD in six directions through
// the whole co-rotation (three rotation logarithms, two T(ψ)⁻¹ and a dozen 3 × 3 products on
// dual numbers).
//
// With x = [δr¹, δθ¹, δr², δθ²], δω_B = W x, J_d's rows J_ψᵉ = T(ψᵉ)⁻¹ (S_e − Qᵉᵀ W)
// (Qᵉ = R_BᵀRᵉ, S_e picks δθᵉ) and b·(δr² − δr¹) (coRotation), and ω = W dq:
//   ∂f/∂x = J_dᵀ K (J_d + η Ĵ) + H,   Ĵ = ∂(J_d dq)/∂x,   H = ∂(J_dᵀ s)/∂x at s held,
// where, with N(ψ, y) = ∂(T(ψ)⁻¹ y)/∂ψ, N'(ψ, y) = ∂(T(ψ)⁻ᵀ y)/∂ψ (rotation.hpp) and
// δ(Qᵉᵀ y) = (Qᵉᵀ y)~ δθᵉ − Qᵉᵀ ỹ δω_B, δ(Qᵉ y) = (Qᵉ y)~ δω_B − Qᵉ ỹ δθᵉ:
//   Ĵ_ψᵉ = N(ψᵉ, hᵉ) J_ψᵉ − T(ψᵉ)⁻¹ ((Qᵉᵀω)~ S_e − Qᵉᵀ ω̃ W + Qᵉᵀ Ω),  hᵉ = dq_θᵉ − Qᵉᵀ ω,  Ω = ∂(W dq)/∂x,
//   Ĵ_u = (P_b dq_Δ)ᵀ (δr² − δr¹)/ℓ,  P_b = I − b bᵀ,  dq_Δ = ṙ² − ṙ¹;
//   J_dᵀ s = Σ S_eᵀ zᵉ − Wᵀ y + s_u [−b; 0; b; 0],  zᵉ = T(ψᵉ)⁻ᵀ s_ψᵉ,  y = Σ Qᵉ zᵉ,
//   H = Σ S_eᵀ N'(ψᵉ, s_ψᵉ) J_ψᵉ − Wᵀ ∂y/∂x − ∂(Wᵀ y)/∂x|_y + s_u [−P_b; 0; P_b; 0] (δr² − δr¹)/ℓ,
//   ∂y/∂x = Σ (Qᵉ zᵉ)~ W − Qᵉ z̃ᵉ S_e + Qᵉ N'(ψᵉ, s_ψᵉ) J_ψᵉ.
// W's rows y and z are ∓(R_B e_z), ±(R_B e_y) on δc/ℓ: with δ(R_B e) = −R_B ẽ δω_B and δℓ = b·δc
// their derivatives are closed products. Its row x (chordTwistRow: the twist about the chord
// through the mean frame) is differentiated by forward AD in the six directions, started from the
// mean frame's own derivatives: δφ = T(φ)⁻¹ δθ², δE = E (G δθ²)~ with G = ½ T(φ/2) T(φ)⁻¹,
// δR_rel = R_rel δθ̃², δb = P_b δr²/ℓ, δℓ = b·δr².

#include <array>

#include "cranesim/elements/parts/corotation.hpp"

namespace cranesim {

/// f and ∂f/∂[δr², δθ²] (file comment).
struct CoRotatedElasticTangent {
  Eigen::Matrix<double, 12, 1> force;
  Eigen::Matrix<double, 12, 6> second_end;  // columns δr², δθ² (twist of R² in its own axes)

  /// The rotation columns along end 2's rotation vector φ² of a frame R² = exp(φ̃²) O (δθ² = Oᵀ T(φ²) δφ²).
  void alongRotationVector(const Vec3& phi2, const Mat3& offset = Mat3::Identity()) {
    second_end.rightCols<3>() = (second_end.rightCols<3>() * (offset.transpose() * angularVelocityMap<double>(phi2))).eval();
  }
};

/// f = J_dᵀ K (d + η J_d dq) of a beam of length L with stiffness K and retardation time η
/// between the end frames (r¹, R¹), (r², R²) at velocities dq = [ṙ¹, ω¹, ṙ², ω²] (ω in the end
/// frames), with its derivatives along end 2's translation and twist.
CoRotatedElasticTangent coRotatedElasticTangent(double length, double eta, const Vec3& r1, const Mat3& R1,
                                                const Vec3& r2, const Mat3& R2, const Eigen::Matrix<double, 12, 1>& v,
                                                const Eigen::Matrix<double, 12, 12>& K);

}  // namespace cranesim
