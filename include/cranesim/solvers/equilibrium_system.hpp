#pragma once
// The static equilibrium equations as a square system in x = [q, λ]: the dq rows and the Φ
// rows of the GGL residual at dq = 0, d(dq)/dt = 0,
//   F(q, 0, t) + Gᵀ(q) λ = 0,   Φ(q, t) = 0,
// with its sparse Jacobian. Used by the Newton statics and by sweeps of many equilibria (the
// static map of crane-opt). Not thread-safe: one system per thread; the model is shared.

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <vector>

#include "cranesim/assembly/assembler.hpp"

namespace cranesim {

class EquilibriumSystem {
 public:
  EquilibriumSystem(const Model& model, double t);

  const Model& model() const { return model_; }
  int size() const { return model_.nq + model_.m; }
  void setLoadFactor(double f) { assembler_.setLoadFactor(f); }
  /// Drives, loads and element parameters (rope lengths) are evaluated at this time.
  void setTime(double t) { t_ = t; }
  double time() const { return t_; }

  VecX residual(const VecX& x);
  Eigen::SparseMatrix<double> jacobian(const VecX& x);

 private:
  void load(const VecX& x);

  const Model& model_;
  Assembler assembler_;
  double t_;
  VecX y_, yp_;
  std::vector<double> values_;
};

/// Factorises J, shifting the diagonal of its first `coordinates` rows when it is singular: a
/// body free to spin about its hanging rope (the load about the vertical) has no stiffness in
/// that direction, and its residual there stays zero. The shift changes the steps, not the
/// equations solved. False when even a shift of 1e-4 of J's largest entry does not help.
bool factoriseShifted(Eigen::SparseMatrix<double> J, int coordinates, Eigen::SparseLU<Eigen::SparseMatrix<double>>& lu);

/// Maps every node's rotation vector of x = [q, …] back into the first turn (|φ| ≤ π).
void reparameteriseRotations(const Model& model, VecX& x);

}  // namespace cranesim
