#pragma once
// Linear-quadratic regulators for sampled controllers: a continuous linear model held over each
// sample (zero-order hold) and the discrete LQR gain of the result.

#include <Eigen/Dense>

namespace cranesim {

/// x⁺ = A x + B u: a linear model from one sample to the next.
struct DiscreteSystem {
  Eigen::MatrixXd A, B;
};

/// The exact discretisation of ẋ = A x + B u with u held constant over each step h: the blocks of
/// exp([A B; 0 0] h).
DiscreteSystem zeroOrderHold(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double h);

struct LqrDesign {
  Eigen::MatrixXd K;  // u = −K x
  Eigen::MatrixXd P;  // the Riccati solution: the cost to go from x is xᵀ P x
  int doublings = 0;
};

/// The gain that minimises Σ xᵀQx + uᵀRu along x⁺ = A x + B u, from the stabilising solution of
/// the discrete algebraic Riccati equation P = AᵀPA − AᵀPB (R + BᵀPB)⁻¹ BᵀPA + Q, found by the
/// structure-preserving doubling algorithm (quadratic convergence; each doubling squares the
/// horizon). Throws std::runtime_error when it does not converge (the system is not stabilisable
/// or the cost does not see an unstable mode).
LqrDesign discreteLqr(const DiscreteSystem& system, const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R);

}  // namespace cranesim
