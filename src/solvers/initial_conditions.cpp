#include "cranesim/solvers/initial_conditions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <numbers>

#include "cranesim/math/rotation.hpp"
#include "cranesim/model/node_graph.hpp"
#include "cranesim/solvers/drive_posing.hpp"

namespace cranesim {
namespace {

constexpr double kProjectionTolerance = 1e-12;
constexpr int kMaxProjectionIterations = 25;

std::string rowLabel(const Model& model, int row) {
  for (const Constraint& c : model.constraints)
    if (row >= c.row && row < c.row + c.rows) return c.row_labels[row - c.row];
  return fmt::format("row {}", row);
}

const Constraint& constraintOfRow(const Model& model, int row) {
  for (const Constraint& c : model.constraints)
    if (row >= c.row && row < c.row + c.rows) return c;
  throw std::logic_error("constraint row out of range");
}

/// Minimum-norm correction x = Aᵀ (A Aᵀ)⁻¹ b.
VecX minimumNormSolution(const Eigen::SparseMatrix<double>& A, const VecX& b) {
  const MatX AAt = MatX(A * A.transpose());
  return A.transpose() * AAt.ldlt().solve(b);
}

/// The largest joint displacement and turn between two states, and the drawing's size.
AssemblyMove assemblyMove(const Model& model, const VecX& q_drawn, const VecX& q) {
  AssemblyMove move;
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    const Frame drawn = model.jointFrame(q_drawn.data(), j), closed = model.jointFrame(q.data(), j);
    low = low.cwiseMin(drawn.r);
    high = high.cwiseMax(drawn.r);
    const double displacement = (closed.r - drawn.r).norm();
    const double rotation = rotationVector(drawn.R.transpose() * closed.R).norm();
    if (displacement > move.displacement || move.displaced_joint.empty())
      move.displacement = displacement, move.displaced_joint = model.joints[j].name;
    if (rotation > move.rotation || move.rotated_joint.empty())
      move.rotation = rotation, move.rotated_joint = model.joints[j].name;
  }
  move.scene_size = std::max((high - low).norm(), std::numeric_limits<double>::min());
  return move;
}

}  // namespace

void requireIndependentConstraints(const Assembler& assembler, const VecX& q, double t) {
  const Model& model = assembler.model();
  if (model.m == 0) return;
  const VecX v = VecX::Zero(model.nv);
  const MatX Gt = MatX(assembler.constraints(t, q.data(), v.data()).G).transpose();
  Eigen::ColPivHouseholderQR<MatX> qr(Gt);
  qr.setThreshold(1e-10);
  const int rank = static_cast<int>(qr.rank());
  if (rank == model.m) return;
  std::string redundant;
  for (int k = rank; k < model.m; ++k) redundant += (redundant.empty() ? "" : ", ") + rowLabel(model, qr.colsPermutation().indices()(k));
  const Constraint& first = constraintOfRow(model, qr.colsPermutation().indices()(rank));
  const std::string what = fmt::format("the constraints are redundant: {} equations but rank {}; dependent equations: {}",
                                       model.m, rank, redundant);
  // A loop: the constraint's two sides are joined already, through elements and the others.
  NodeGraph others(model, static_cast<int>(&first - model.constraints.data()));
  if (others.connected(others.nodeOf(model, first.joint1), others.nodeOf(model, first.joint2)))
    throw SceneError(first.where, what + ". Replace a revolute or fixed constraint in the closed loop by a spherical one.");
  // No loop: the constraint's own equations are singular in this pose, e.g. a fixed constraint
  // between joint frames the drawing turns by 90° against each other.
  const Frame j1 = model.jointFrame(q.data(), first.joint1), j2 = model.jointFrame(q.data(), first.joint2);
  const double turn = rotationVector(Mat3(j1.R.transpose() * j2.R)).norm() * 180.0 / std::numbers::pi;
  throw SceneError(first.where,
                   fmt::format("{}. '{}' closes no loop: its equations are singular where its joint frames stand "
                               "(turned by {:.3g}° against each other){}",
                               what, first.name, turn,
                               first.type == ConstraintType::Fixed
                                   ? "; a fixed constraint makes them coincide: draw the joints with the same axes, or "
                                     "give it pose: drawn to keep the drawing's relative rotation"
                                   : ""));
}

double jumpVelocities(const Assembler& assembler, DynamicState& s, const ConstraintState& C) {
  return AccelerationSolver().jump(assembler, s, C);
}

void solveAccelerations(const Assembler& assembler, DynamicState& s, Limit limit) {
  solveAccelerations(assembler, s, assembler.constraints(s.t, s.q.data(), s.v.data(), limit), limit);
}

void solveAccelerations(const Assembler& assembler, DynamicState& s, const ConstraintState& C, Limit limit) {
  AccelerationSolver().solve(assembler, s, C, limit);
}

void AccelerationSolver::solve(const Assembler& assembler, DynamicState& s, const ConstraintState& C, Limit limit) {
  solve(assembler, s, C, assembler.massMatrix(s.t, s.q.data()), limit);
}

void AccelerationSolver::solve(const Assembler& assembler, DynamicState& s, const ConstraintState& C,
                               const Eigen::SparseMatrix<double>& M, Limit limit) {
  const int nv = assembler.model().nv, m = assembler.model().m;
  const VecX F = assembler.appliedForces(s.t, s.q.data(), s.v.data(), limit);
  factorise(M, C.G, s.t, "");
  VecX x(nv + m);
  x << -F, -C.gamma;
  lu_.solve(x.data());
  s.a = x.head(nv);
  s.lambda = x.tail(m);
  s.qdot = assembler.coordinateRates(s.q.data(), s.v.data());
}

double AccelerationSolver::jump(const Assembler& assembler, DynamicState& s, const ConstraintState& C) {
  const int nv = assembler.model().nv, m = assembler.model().m;
  const Eigen::SparseMatrix<double> M = assembler.massMatrix(s.t, s.q.data());
  factorise(M, C.G, s.t, " at a drive's velocity jump");
  VecX x = VecX::Zero(nv + m);
  x.tail(m) = -C.phi_dot;
  lu_.solve(x.data());
  const double before = 0.5 * s.v.dot(M * s.v);
  s.v += x.head(nv);
  return 0.5 * s.v.dot(M * s.v) - before;
}

void AccelerationSolver::factorise(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& G, double t,
                                   const char* where) {
  const int nv = static_cast<int>(M.rows()), m = static_cast<int>(G.rows());
  if (!samePattern(M, G)) buildPattern(M, G);
  double* values = matrix_.valuePtr();
  for (std::size_t k = 0; k < mass_slots_.size(); ++k) values[mass_slots_[k]] = M.valuePtr()[k];
  for (std::size_t k = 0; k < constraint_slots_.size(); ++k) {
    values[constraint_slots_[k]] = G.valuePtr()[k];
    values[transposed_slots_[k]] = G.valuePtr()[k];
  }
  if (!lu_.factorise(nv + m, matrix_.outerIndexPtr(), matrix_.innerIndexPtr(), matrix_.valuePtr()))
    throw std::runtime_error(fmt::format("t = {} s: the saddle-point matrix [M Gᵀ; G 0] is singular{} "
                                         "(a body without mass or inertia in a free direction?)", t, where));
}

bool AccelerationSolver::samePattern(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& G) const {
  const auto same = [](const Eigen::SparseMatrix<double>& A, const std::vector<int>& outer, const std::vector<int>& inner) {
    return A.isCompressed() && static_cast<std::size_t>(A.outerSize()) + 1 == outer.size() &&
           std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) && static_cast<std::size_t>(A.nonZeros()) == inner.size() &&
           std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
  };
  return matrix_.rows() == M.rows() + G.rows() && same(M, mass_outer_, mass_inner_) && same(G, constraint_outer_, constraint_inner_);
}

void AccelerationSolver::buildPattern(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& G) {
  const int nv = static_cast<int>(M.rows()), m = static_cast<int>(G.rows());
  std::vector<Eigen::Triplet<double>> pattern;
  for (int k = 0; k < M.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, k); it; ++it) pattern.emplace_back(it.row(), it.col(), 0.0);
  for (int k = 0; k < G.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(G, k); it; ++it) {
      pattern.emplace_back(nv + it.row(), it.col(), 0.0);
      pattern.emplace_back(it.col(), nv + it.row(), 0.0);
    }
  matrix_.resize(nv + m, nv + m);
  matrix_.setFromTriplets(pattern.begin(), pattern.end());
  matrix_.makeCompressed();
  // Position of entry (r, c) in matrix_'s value array.
  const auto slot = [&](int r, int c) {
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[c];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[c + 1];
    return static_cast<int>(std::lower_bound(begin, end, r) - matrix_.innerIndexPtr());
  };
  mass_slots_.clear();
  for (int k = 0; k < M.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, k); it; ++it) mass_slots_.push_back(slot(it.row(), it.col()));
  constraint_slots_.clear();
  transposed_slots_.clear();
  for (int k = 0; k < G.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(G, k); it; ++it) {
      constraint_slots_.push_back(slot(nv + it.row(), it.col()));
      transposed_slots_.push_back(slot(it.col(), nv + it.row()));
    }
  mass_outer_.assign(M.outerIndexPtr(), M.outerIndexPtr() + M.outerSize() + 1);
  mass_inner_.assign(M.innerIndexPtr(), M.innerIndexPtr() + M.nonZeros());
  constraint_outer_.assign(G.outerIndexPtr(), G.outerIndexPtr() + G.outerSize() + 1);
  constraint_inner_.assign(G.innerIndexPtr(), G.innerIndexPtr() + G.nonZeros());
}

std::string AssemblyMove::describe() const {
  const std::string distance = displacement >= 1.0    ? fmt::format("{:.4g} m", displacement)
                               : displacement >= 1e-6 ? fmt::format("{:.3g} mm", 1e3 * displacement)
                                                      : fmt::format("{:.3g} m", displacement);
  std::string text = fmt::format("{} at joint '{}' ({:.2g} % of the scene's {:.4g} m)", distance, displaced_joint,
                                 100.0 * displacement / scene_size, scene_size);
  if (rotation > 1e-12) text += fmt::format("; turn {:.3g} rad at '{}'", rotation, rotated_joint);
  return text;
}

DynamicState consistentInitialState(const Assembler& assembler, double t, VecX q, VecX v, double tolerance,
                                    AssemblyMove* move) {
  const Model& model = assembler.model();
  DynamicState s;
  s.t = t;
  if (model.m > 0) {
    requireIndependentConstraints(assembler, q, t);
    ConstraintState C = assembler.constraints(t, q.data(), v.data(), Limit::Right);
    int worst = 0;
    const double violation = C.phi.cwiseAbs().maxCoeff(&worst);
    const Constraint& most_violated = constraintOfRow(model, worst);
    const VecX q_drawn = q;
    int it = 0;
    for (; it < kMaxProjectionIterations && C.phi.cwiseAbs().maxCoeff() > kProjectionTolerance; ++it) {
      q -= minimumNormSolution(C.Phi_q, C.phi);
      C = assembler.constraints(t, q.data(), v.data(), Limit::Right);
    }
    if (!(C.phi.cwiseAbs().maxCoeff() <= kProjectionTolerance))
      throw SceneError(most_violated.where,
                       fmt::format("the drawing cannot be assembled: |Φ| = {:.3g} in '{}' is left {:.3g} after {} "
                                   "least-change steps; correct the initial positions or rotations of the parts it "
                                   "connects", violation, rowLabel(model, worst), C.phi.cwiseAbs().maxCoeff(), it));
    const AssemblyMove moved = assemblyMove(model, q_drawn, q);
    if (moved.displacement > tolerance * moved.scene_size || moved.rotation > tolerance) {
      // A fixed constraint whose joints the drawing turns against each other: most likely
      // members meeting at an angle on purpose.
      const std::string hint =
          most_violated.type == ConstraintType::Fixed && worst - most_violated.row >= 3
              ? fmt::format(" (or, if the parts meet at an angle on purpose, give '{}' pose: drawn)", most_violated.name)
              : "";
      throw SceneError(most_violated.where,
                       fmt::format("the drawing is off: |Φ| = {:.3g} in '{}', and closing it moves {}, more than "
                                   "solver.assembly_tolerance = {:g} (of the scene's size, or rad) allows; correct "
                                   "the initial positions or rotations of the parts it connects{}",
                                   violation, rowLabel(model, worst), moved.describe(), tolerance, hint));
    }
    if (move) *move = moved;
    v -= minimumNormSolution(C.G, C.phi_dot);
  }
  s.q = std::move(q);
  s.v = std::move(v);
  solveAccelerations(assembler, s, Limit::Right);
  return s;
}

DynamicState assembledInitialState(const Assembler& assembler, double t, VecX q, VecX v, double tolerance,
                                   AssemblyMove* move) {
  poseAtDrives(assembler.model(), t, q, &v);
  return consistentInitialState(assembler, t, std::move(q), std::move(v), tolerance, move);
}

}  // namespace cranesim
