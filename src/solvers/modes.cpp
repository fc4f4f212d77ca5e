#include "cranesim/solvers/modes.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Sparse>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "cranesim/assembly/assembler.hpp"
#include "cranesim/math/rotation.hpp"

namespace cranesim {
namespace {

/// ∂(F + Gᵀλ − Q)/∂q at dq = 0 (nv × nq): the q columns of the assembler's
/// equation-of-motion rows, with d(dq)/dt = 0 so that the mass matrix drops out.
MatX equationsOfMotionJacobian(const Assembler& assembler, double t, const VecX& q, const VecX& lambda) {
  const Model& model = assembler.model();
  VecX y = VecX::Zero(assembler.size());
  const VecX yp = VecX::Zero(assembler.size());
  y.head(model.nq) = q;
  y.segment(assembler.lambdaOffset(), model.m) = lambda;
  std::vector<double> values(assembler.pattern().nonZeros());
  assembler.jacobian(t, 0.0, y.data(), yp.data(), values.data());
  const auto& column_pointers = assembler.pattern().columnPointers();
  const auto& row_indices = assembler.pattern().rowIndices();
  MatX J = MatX::Zero(model.nv, model.nq);
  for (int c = 0; c < model.nq; ++c) {
    for (int k = column_pointers[c]; k < column_pointers[c + 1]; ++k) {
      const int row = row_indices[k] - assembler.vOffset();
      if (row >= 0 && row < model.nv) J(row, c) += values[k];
    }
  }
  return J;
}

/// H(q) with q̇ = H(q) dq (2-10): identity except T(φ)⁻¹ on the rotation vectors.
Eigen::SparseMatrix<double> coordinateRateMap(const Model& model, const VecX& q) {
  std::vector<Eigen::Triplet<double>> triplets;
  for (const Node& n : model.nodes) {
    for (int k = 0; k < n.size(); ++k)
      if (!n.hasRotation() || k < 3 || k > 5) triplets.emplace_back(n.q + k, n.v + k, 1.0);
    if (!n.hasRotation()) continue;
    const Mat3 T_inverse = angularVelocityMapInverse<double>(Vec3(q.segment<3>(n.q + 3)));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) triplets.emplace_back(n.q + 3 + i, n.v + 3 + j, T_inverse(i, j));
  }
  Eigen::SparseMatrix<double> H(model.nq, model.nv);
  H.setFromTriplets(triplets.begin(), triplets.end());
  return H;
}

}  // namespace

ModalResult computeModes(const Model& model, const VecX& q_eq, double t, int count, ModeShapes shapes) {
  Assembler assembler(model, Formulation::GGL);
  assembler.setParametersHeld(true);
  const int nv = model.nv;
  const VecX zero_v = VecX::Zero(nv);
  ModalResult result;

  // Constraint null space and equilibrium multipliers from one QR of Gᵀ (nv × m).
  const MatX Gt = MatX(assembler.constraints(t, q_eq.data(), zero_v.data()).G.transpose());
  const VecX applied = assembler.appliedForces(t, q_eq.data(), zero_v.data());
  MatX N;
  if (model.m > 0) {
    const Eigen::ColPivHouseholderQR<MatX> qr(Gt);
    result.lambda = qr.solve(-applied);
    N = MatX(qr.householderQ()).rightCols(nv - qr.rank());
  } else {
    result.lambda = VecX::Zero(0);
    N = MatX::Identity(nv, nv);
  }
  result.force_residual = nv > 0 ? (applied + Gt * result.lambda).cwiseAbs().maxCoeff() : 0.0;
  result.free_dofs = static_cast<int>(N.cols());

  const MatX K = equationsOfMotionJacobian(assembler, t, q_eq, result.lambda) * coordinateRateMap(model, q_eq);
  const Eigen::SparseMatrix<double> M = assembler.massMatrix(t, q_eq.data());
  const MatX K_reduced = N.transpose() * (K * N);
  const MatX M_reduced = N.transpose() * (M * N);
  const double K_norm = K_reduced.norm();
  result.stiffness_asymmetry = K_norm > 0.0 ? (K_reduced - K_reduced.transpose()).norm() / K_norm : 0.0;

  const int modes = count <= 0 ? result.free_dofs : std::min(count, result.free_dofs);
  result.omega_squared = VecX::Zero(modes);
  result.frequencies = VecX::Zero(modes);
  const bool with_shapes = shapes == ModeShapes::Computed;
  result.shapes = MatX::Zero(nv, with_shapes ? modes : 0);
  result.rigid.assign(modes, false);
  if (result.free_dofs == 0) return result;

  if (Eigen::LLT<MatX>(M_reduced).info() != Eigen::Success)
    throw std::runtime_error(fmt::format("modes: the mass matrix is not positive definite on the {} degrees of "
                                         "freedom left by the constraints (a massless coordinate?)",
                                         result.free_dofs));
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> eigen(0.5 * (K_reduced + K_reduced.transpose()), M_reduced,
                                                             (with_shapes ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly) |
                                                                 Eigen::Ax_lBx);
  if (eigen.info() != Eigen::Success) throw std::runtime_error("modes: the eigen-solver did not converge");

  const VecX& all = eigen.eigenvalues();
  result.zero_threshold = 1e-12 * all.cwiseAbs().maxCoeff();
  result.rigid_modes = static_cast<int>((all.array().abs() <= result.zero_threshold).count());
  for (int k = 0; k < modes; ++k) {
    const double w2 = all(k);
    result.omega_squared(k) = w2;
    result.rigid[k] = std::abs(w2) <= result.zero_threshold;
    if (!result.rigid[k]) result.frequencies(k) = std::copysign(std::sqrt(std::abs(w2)), w2) / (2.0 * std::numbers::pi);
    if (!with_shapes) continue;
    VecX shape = N * eigen.eigenvectors().col(k);
    Eigen::Index largest = 0;
    shape.cwiseAbs().maxCoeff(&largest);
    if (shape(largest) < 0.0) shape = -shape;  // a reproducible sign: largest component positive
    result.shapes.col(k) = shape;
  }
  return result;
}

}  // namespace cranesim
