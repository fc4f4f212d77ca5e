#include "cranesim/solvers/equilibrium_system.hpp"

#include "cranesim/math/rotation.hpp"

namespace cranesim {

EquilibriumSystem::EquilibriumSystem(const Model& model, double t)
    : model_(model), assembler_(model, Formulation::GGL), t_(t) {
  y_ = VecX::Zero(assembler_.size());
  yp_ = VecX::Zero(assembler_.size());
  values_.resize(assembler_.pattern().nonZeros());
  assembler_.setCoordinateJacobianOnly(true);
  assembler_.setParametersHeld(true);
}

VecX EquilibriumSystem::residual(const VecX& x) {
  load(x);
  VecX r(assembler_.size());
  assembler_.residual(t_, y_.data(), yp_.data(), r.data());
  VecX out(size());
  out << r.segment(assembler_.vOffset(), model_.nv), r.segment(assembler_.muOffset(), model_.m);
  return out;
}

Eigen::SparseMatrix<double> EquilibriumSystem::jacobian(const VecX& x) {
  load(x);
  assembler_.jacobian(t_, 0.0, y_.data(), yp_.data(), values_.data());
  const auto& cp = assembler_.pattern().columnPointers();
  const auto& ri = assembler_.pattern().rowIndices();
  std::vector<Eigen::Triplet<double>> triplets;
  const auto unknown = [&](int col) {  // column of y → column of x, or −1
    if (col < model_.nq) return col;
    if (col >= assembler_.lambdaOffset() && col < assembler_.muOffset()) return col - assembler_.lambdaOffset() + model_.nq;
    return -1;
  };
  const auto equation = [&](int row) {  // row of the residual → row of the system, or −1
    if (row >= assembler_.vOffset() && row < assembler_.lambdaOffset()) return row - assembler_.vOffset();
    if (row >= assembler_.muOffset()) return row - assembler_.muOffset() + model_.nv;
    return -1;
  };
  for (int c = 0; c < assembler_.size(); ++c) {
    const int cx = unknown(c);
    if (cx < 0) continue;
    for (int k = cp[c]; k < cp[c + 1]; ++k) {
      const int rx = equation(ri[k]);
      if (rx >= 0) triplets.emplace_back(rx, cx, values_[k]);
    }
  }
  Eigen::SparseMatrix<double> J(size(), size());
  J.setFromTriplets(triplets.begin(), triplets.end());
  return J;
}

void EquilibriumSystem::load(const VecX& x) {
  y_.head(model_.nq) = x.head(model_.nq);
  y_.segment(assembler_.lambdaOffset(), model_.m) = x.tail(model_.m);
}

bool factoriseShifted(Eigen::SparseMatrix<double> J, int coordinates, Eigen::SparseLU<Eigen::SparseMatrix<double>>& lu) {
  lu.compute(J);
  const double magnitude = J.coeffs().cwiseAbs().maxCoeff();
  for (double shift = 1e-12 * magnitude, applied = 0.0; lu.info() != Eigen::Success && shift < 1e-4 * magnitude;
       shift *= 100.0) {
    for (int k = 0; k < coordinates; ++k) J.coeffRef(k, k) += shift - applied;
    applied = shift;
    lu.compute(J);
  }
  return lu.info() == Eigen::Success;
}

void reparameteriseRotations(const Model& model, VecX& x) {
  for (const Node& n : model.nodes) {
    if (!n.hasRotation()) continue;
    Vec3 phi = x.segment<3>(n.q + 3);
    if (reparameterise(phi)) x.segment<3>(n.q + 3) = phi;
  }
}

}  // namespace cranesim
