#pragma once
// The coordinate columns ∂r/∂q of a frame-indifferent element on two frame nodes, from the six
// of its second end and the tangents the Jacobian computes anyway: forward AD in six directions
// instead of twelve.
//
// q = [r¹, φ¹, r², φ²] (positions, rotation vectors, Rⁿ = exp(φ̃ⁿ)), dq = [ṙ¹, ω¹, ṙ², ω²] (ṙ in
// inertial axes, ω in body axes, ω = T(φ) φ̇), residual r(q; dq, a, g) = M(q) a + F(q, dq; g).
// An element whose forces come from co-rotated deformations and from material riding on it is
// - invariant under a rigid translation: r(r¹ + u, φ¹, r² + u, φ²) = r(q),
// - covariant under a rigid rotation Q about the origin (rⁿ → Q rⁿ, Rⁿ → Q Rⁿ):
//     r(Q q; dq, a, g) = P r(q; Pᵀ dq, Pᵀ a, Qᵀ g),   P = diag(Q, I, Q, I),
// - and gravity acts on the material the mass matrix moves: r depends on g and on the ends'
//   translational accelerations through M (a − [g, 0, g, 0]) alone.
// Differentiating the rotation at Q = I + δ̃, where the ends move by δ × rⁿ and twist by
// θⁿ = Rⁿᵀ δ, with A = ∂r/∂r² and B = ∂r/∂θ² = ∂r/∂φ² T(φ²)⁻¹ and c = r² − r¹:
//   ∂r/∂θ¹ = (X + A c̃ − B R²ᵀ) R¹,
//   X = −[r̃₁; 0; r̃₂; 0] + C_ṙ¹ ṙ̃¹ + C_ṙ² ṙ̃² + M_r¹ (a¹ − g)~ + M_r² (a² − g)~,
// r₁, r₂ the residual's translational rows, C = ∂r/∂dq and M_rⁿ, C_ṙⁿ their columns of end n's
// translation. Then ∂r/∂r¹ = −A and ∂r/∂φ¹ = ∂r/∂θ¹ T(φ¹).

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {

/// The element's state and what its Jacobian has computed there: M and the velocity tangent
/// C = ∂(M a + F)/∂dq (without the mass term's cj M).
struct ObjectiveTangentInput {
  using V12 = Eigen::Matrix<double, 12, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;
  const V12& q;
  const V12& v;
  const V12& a;  // with the mass damping's α dq when the residual has it (M (a + α dq))
  const Vec3& gravity;
  const Mat12& mass;
  const Mat12& velocity_tangent;
};

namespace objective_detail {
/// ∂r/∂q (12 × 12) from the residual r and its columns of end 2, ∂r/∂[r², φ²] (file comment).
Eigen::Matrix<double, 12, 12> fromSecondEnd(const ObjectiveTangentInput& in, const Eigen::Matrix<double, 12, 1>& residual,
                                            const Eigen::Matrix<double, 12, 6>& second_end);
}  // namespace objective_detail

/// ∂r/∂q of a frame-indifferent element whose residual r(q) is given templated on the scalar:
/// forward AD in end 2's six directions.
template <class Residual>
Eigen::Matrix<double, 12, 12> objectiveCoordinateTangent(const ObjectiveTangentInput& in, const Residual& residual) {
  Eigen::Matrix<double, 12, 1> r;
  const Eigen::Matrix<double, 12, 6> second_end = segmentDerivative<6>(in.q, 6, residual, r);
  return objective_detail::fromSecondEnd(in, r, second_end);
}

/// End 2's rotation vector φ² of q, seeded in three directions.
Vec3T<Dual<double, 3>> seededSecondRotation(const Eigen::Matrix<double, 12, 1>& q);

/// The same for a residual split into elastic forces, given with their columns of end 2
/// (corotated_elastic_tangent.hpp), and inertial and gravity forces that do not depend on the end
/// positions (material riding on an interpolation driven by the end rotations), given with their
/// derivatives in the directions of seededSecondRotation (section_inertia_coordinate_tangent.hpp).
Eigen::Matrix<double, 12, 12> objectiveCoordinateTangent(const ObjectiveTangentInput& in, Eigen::Matrix<double, 12, 1> r_elastic,
                                                         Eigen::Matrix<double, 12, 6> second_end,
                                                         const Eigen::Matrix<Dual<double, 3>, 12, 1>& inertial);

}  // namespace cranesim
