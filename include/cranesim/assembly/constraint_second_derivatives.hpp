#pragma once
// A constraint's equations, its velocity Jacobian G and the derivatives of G with respect to the
// node coordinates and time, which the DAE Jacobian needs (∂(Gᵀλ)/∂q, ∂(G dq + Φ_t)/∂q), in
// closed form through the equations' primitives (model/constraint_equations.hpp).
//
// Each joint frame moves with its node: r_J = r + R o, R_J = R R_rel. The twist δ = [δr, δθ] of
// G (constraint_evaluation.hpp) moves it to r + δr + R(I + δθ̃) o, R(I + δθ̃) R_rel, and a change
// of the node's coordinates dq = [dr, dφ] to the same with δ = [dr, T(φ) dφ] to first order
// (R(φ + dφ) = R(I + (T dφ)~), 2-10). Every vector x of the equations is therefore affine in δ,
//     x = x₀ + J_x δ,   J_x = [I, −R õ] for r_J,  [0, −R ũ] for e = R u (u = R_rel g_k),
// and the second derivative of G along dq comes from R(I + ã)(I + b̃) u alone:
//     ∂²(x·y)/∂b_j ∂a_l = (J_xᵀ J_y + J_yᵀ J_x)_jl + W_x(y)_jl + W_y(x)_jl,
//     W_x(y) = w uᵀ − (w·u) I   on x's rotation block, w = Rᵀ y   (w·(e_l × (e_j × u))).
// With Φ = h(p, t), h's first and second derivatives (forward AD over h alone, a handful of
// operations):  G = Σ h_a ∇p_a,  ∂G/∂a = Σ h_a ∇²p_a + Σ h_ac ∇p_a ∇p_cᵀ  (+ h's time terms),
// and ∂/∂φ = ∂/∂a T(φ). Checked against nested forward AD of the equations (tests).

#include <array>

#include "cranesim/assembly/constraint_evaluation.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

struct ConstraintSecondDerivatives {
  using Mat13 = Eigen::Matrix<double, kConstraintDirections, kConstraintDirections>;
  int rows = 0;
  Eigen::Matrix<double, kMaxConstraintRows, 1> phi;
  /// G: ∂Φ/∂[δ₁, δ₂] and Φ_t (column kTimeDirection), as ConstraintDerivatives::G.
  Eigen::Matrix<double, kMaxConstraintRows, kConstraintDirections> G;
  /// Φ_q: ∂Φ/∂[q₁, q₂], the nodes' coordinates [r, φ].
  Eigen::Matrix<double, kMaxConstraintRows, 12> phi_q;
  /// dG[i](j, k) = ∂G_ij/∂[q₁, q₂, t]_k (j over the directions of G, time included).
  std::array<Mat13, kMaxConstraintRows> dG;
};

ConstraintSecondDerivatives constraintSecondDerivatives(const Model& model, const Constraint& c, const double* q,
                                                        double t);

}  // namespace cranesim
