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
// The sum in ∂r/∂dq, G = ∂r/∂dq + M C, is accumulated station by station (addStationTangent), M
// by section_mass_matrix.hpp; the kernel then subtracts M C once (subtractTwistBracket).
//
// The coordinate columns ∂r/∂q come from end 2's by frame indifference (objective_tangent.hpp);
// the inertial and gravity forces of an interpolation whose centre-line tangents and section
// rotations follow the end rotations alone (x = Σ Nᵢ rⁱ + N' Rⁱ e_x, R_c = R¹ exp(ξ φ̃)) do not
// depend on the end positions, so of those only end 2's three rotation directions are
// differentiated.

#include <Eigen/Dense>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

/// Adds one station's share to G = Σ Hᵀ(…) of the file comment: its rotation columns (G has no
/// translation columns: Ḣ and H_Ω have none). `map`: the section map H at the station (blocks
/// a[n] I, X[n] of H_x and W[n] of H_Ω, section rotation Rc); `rate`: Ḣ along the motion (blocks
/// X[n], W[n]); `omega`: Ω = H_Ω dq. Every column block is Hᵀ [P_f; P_τ] for a 3 × 3 force and
/// torque pair, 3 × 3 products node by node (no products with H's zero blocks).
template <class Map, class Rate>
[[gnu::flatten]] void addStationTangent(const Map& map, const Rate& rate, const Vec3& omega, double mass, const Vec3& first_moment,
                                        const Mat3& inertia, Eigen::Matrix<double, 12, 12>& G) {
  const Mat3& Rc = map.Rc;
  const Mat3& J = inertia;
  const Mat3 S = skew<double>(first_moment), W = skew<double>(omega);
  const Mat3 RcS = Rc * S;             // R_c s̃
  const Mat3 SRcT = -RcS.transpose();  // s̃ R_cᵀ
  const Mat3 gyro_f = -Rc * (skew<double>(Vec3(omega.cross(first_moment))) + W * S + S * W);
  const Mat3 gyro_t = J * W + W * J - skew<double>(Vec3(J * omega));
  for (int n = 0; n < 2; ++n) {
    const Mat3 Pf = 2.0 * (mass * rate.X[n] - RcS * rate.W[n]) + gyro_f * map.W[n],
               Pt = 2.0 * (SRcT * rate.X[n] + J * rate.W[n]) + gyro_t * map.W[n];
    for (int k = 0; k < 2; ++k) {
      G.block<3, 3>(6 * k, 6 * n + 3).noalias() += map.a[k] * Pf;
      G.block<3, 3>(6 * k + 3, 6 * n + 3).noalias() += map.X[k].transpose() * Pf;
      G.block<3, 3>(6 * k + 3, 6 * n + 3).noalias() += map.W[k].transpose() * Pt;
    }
  }
}

/// G − M C(dq) in place: C has the blocks ω̃ⁿ (ωⁿ = dq's rotational velocity of node n) on the
/// diagonal of each node's rotation.
inline void subtractTwistBracket(const Eigen::Matrix<double, 12, 12>& M, const Eigen::Matrix<double, 12, 1>& v,
                                 Eigen::Matrix<double, 12, 12>& G) {
  for (int n = 0; n < 2; ++n)
    G.middleCols<3>(6 * n + 3).noalias() -= M.middleCols<3>(6 * n + 3) * skew<double>(Vec3(v.segment<3>(6 * n + 3)));
}

}  // namespace cranesim
