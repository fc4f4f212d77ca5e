#pragma once
// Small-vibration modes about a static equilibrium (modal analysis of any model).
//
// The equations M(q) d(dq)/dt + F(q, dq, t) + Gᵀλ − Q = 0, Φ(q, t) = 0 of the assembler are
// linearised about an equilibrium (q_eq, dq = 0, λ_eq) along a perturbation δx in velocity
// coordinates (δr, body-frame rotation δθ, …; q = q_eq + H(q_eq) δx with q̇ = H(q) dq):
//   M(q_eq) δẍ + K δx = Gᵀ δλ,   G δx = 0,
//   K = ∂(F + Gᵀλ_eq − Q)/∂q · H   (elastic, gravity and load stiffness, and the geometric
//                                   stiffness of the constraint forces, λ_eq · ∂G/∂q).
// Damping (∂F/∂dq) is ignored. Writing δx = N ξ with N an orthonormal basis of the null space
// of G gives the generalized symmetric eigenproblem Nᵀ K N ξ = ω² Nᵀ M N ξ.
//
// At an equilibrium of conservative forces K is symmetric on that null space; what is left
// (follower loads, an imperfectly converged equilibrium) is reported and the symmetric part used.
//
// Dense linear algebra throughout (QR of Gᵀ, the reduced matrices, Eigen's
// GeneralizedSelfAdjointEigenSolver, all modes): O(nv³) time and O(nv²) memory, meant for
// models up to ~2000 velocity coordinates (a 300-segment cantilever, nv = 1800: 45 s wall,
// 230 MB, on a loaded 2-core machine; 60 coordinates: 5 ms). Larger models want a sparse
// shift-invert Lanczos for the lowest modes only.

#include <vector>

#include "cranesim/model/model.hpp"

namespace cranesim {

struct ModalResult {
  /// ω² (rad²/s²) of the lowest modes, ascending. Negative: the equilibrium is unstable in
  /// that mode (the perturbation grows as e^{√−ω² t}).
  VecX omega_squared;
  /// sign(ω²) √|ω²| / 2π, Hz; exactly 0 for rigid-body modes.
  VecX frequencies;
  /// Mode shapes in velocity coordinates (nv × modes), mass-normalised: φᵀ M φ = 1.
  MatX shapes;
  /// Rigid-body (zero-frequency) modes: |ω²| within round-off of zero (see zero_threshold).
  std::vector<bool> rigid;
  int rigid_modes = 0;  // among all free_dofs modes, not only the ones returned
  /// Degrees of freedom: nv − rank(G).
  int free_dofs = 0;
  /// |ω²| below this is zero to the eigen-solver's round-off: 1e-12 · max |ω²| over all modes.
  double zero_threshold = 0.0;
  /// ‖K_r − K_rᵀ‖_F / ‖K_r‖_F of the reduced stiffness before symmetrisation.
  double stiffness_asymmetry = 0.0;
  /// Multipliers of the equilibrium: least-squares solution of F − Q + Gᵀλ = 0 at dq = 0.
  VecX lambda;
  /// max |F − Q + Gᵀλ| at q_eq: how far q_eq is from an equilibrium (the linearisation assumes 0).
  double force_residual = 0.0;
};

enum class ModeShapes { Computed, Skipped };

/// The `count` lowest modes (all of them when count ≤ 0 or count ≥ free_dofs) of `model` about
/// the equilibrium q_eq (e.g. solveStatics(model, q, t).q) at time t; with ModeShapes::Skipped
/// only their frequencies (`shapes` has no columns), about half the work. Throws
/// std::runtime_error when the mass matrix is not positive definite on the constraint null space
/// (a massless degree of freedom).
ModalResult computeModes(const Model& model, const VecX& q_eq, double t, int count, ModeShapes shapes = ModeShapes::Computed);

}  // namespace cranesim
