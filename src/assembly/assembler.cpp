#include "cranesim/assembly/assembler.hpp"

#include <algorithm>
#include <array>

#include "cranesim/assembly/constraint_evaluation.hpp"
#include "cranesim/assembly/constraint_second_derivatives.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/wind_elements.hpp"

namespace cranesim {
namespace {

/// The parts of the DAE's y = [q, v, λ, …] and ẏ = [q̇, a, …].
struct DaeState {
  const double *q, *v, *lambda, *qdot, *a;
};
DaeState daeState(const double* y, const double* yp, int nq, int lambda_offset) {
  return {y, y + nq, y + lambda_offset, yp, yp + nq};
}

std::vector<int> range(int first, int count) {
  std::vector<int> out(count);
  for (int k = 0; k < count; ++k) out[k] = first + k;
  return out;
}

/// The node of each side of a constraint (−1 for the ground) and the active twist directions.
struct ConstraintSides {
  int node[2] = {-1, -1};
  int direction[12];  // subset of 0..11, the first `count`
  int count = 0;
  const int* begin() const { return direction; }
  const int* end() const { return direction + count; }
};

ConstraintSides sidesOf(const Model& model, const Constraint& c) {
  ConstraintSides s;
  s.node[0] = model.joints[c.joint1].node;
  s.node[1] = model.joints[c.joint2].node;
  for (int side = 0; side < 2; ++side) {
    if (s.node[side] < 0) continue;
    const int count = model.nodes[s.node[side]].hasRotation() ? 6 : 3;
    for (int k = 0; k < count; ++k) s.direction[s.count++] = 6 * side + k;
  }
  return s;
}

int vIndex(const Model& model, const ConstraintSides& s, int direction) {
  return model.nodes[s.node[direction / 6]].v + direction % 6;
}
int qIndex(const Model& model, const ConstraintSides& s, int direction) {
  return model.nodes[s.node[direction / 6]].q + direction % 6;
}

/// Local coordinates [q₁, q₂] of a constraint's nodes, or their rates, extended by 1 for time.
Eigen::Matrix<double, kConstraintDirections, 1> localExtended(const Model& model,
                                                               const ConstraintSides& s,
                                                               const double* x, bool q_layout) {
  Eigen::Matrix<double, kConstraintDirections, 1> out = Eigen::Matrix<double, kConstraintDirections, 1>::Zero();
  for (int d : s) out(d) = x[q_layout ? qIndex(model, s, d) : vIndex(model, s, d)];
  out(kTimeDirection) = 1.0;
  return out;
}

/// The rows × pattern.size() matrix of `pattern` with the values laid out by it.
Eigen::SparseMatrix<double> patternedMatrix(const SparsityPattern& pattern, int rows, const VecX& values) {
  Eigen::SparseMatrix<double> A(rows, pattern.size());
  A.resizeNonZeros(pattern.nonZeros());
  std::copy(pattern.columnPointers().begin(), pattern.columnPointers().end(), A.outerIndexPtr());
  std::copy(pattern.rowIndices().begin(), pattern.rowIndices().end(), A.innerIndexPtr());
  std::copy(values.data(), values.data() + values.size(), A.valuePtr());
  return A;
}

}  // namespace

Assembler::Assembler(const Model& model, Formulation formulation) : model_(model), formulation_(formulation) {
  size_ = model.nq + model.nv + model.m * (ggl() ? 2 : 1);
  element_scratch_.resize(model.elements.size());
  buildPattern();
}

void Assembler::buildPattern() {
  const int nq = model_.nq;
  for (const Node& n : model_.nodes) {
    NodeBlocks b;
    b.qq = pattern_.addBlock(range(n.q, n.size()), range(n.q, n.size()), !n.hasRotation());
    b.qv = pattern_.addBlock(range(n.q, n.size()), range(nq + n.v, n.size()), true);
    node_blocks_.push_back(b);
  }
  for (const auto& e : model_.elements) {
    const std::vector<int>& q = e->coordinateIndices();
    const std::vector<int>& v = e->velocityIndices();
    std::vector<std::vector<int>> blocks = e->jacobianBlocks();
    sparse_element_.push_back(!blocks.empty());
    if (blocks.empty()) blocks.push_back(range(0, static_cast<int>(v.size())));
    std::vector<int>& ids = element_blocks_.emplace_back();
    for (const std::vector<int>& block : blocks) {
      std::vector<int> rows, cols;
      for (int i : block) rows.push_back(nq + v[i]);
      if (sparse_element_.back()) for (int i : block) cols.push_back(q[i]);
      else cols = q;
      for (int i : block) cols.push_back(nq + v[i]);
      ids.push_back(pattern_.addBlock(rows, cols));
    }
    mass_blocks_.push_back(mass_pattern_.addBlock(v, v, sparse_element_.back()));
  }
  mass_pattern_.finalize(model_.nv);
  for (const Load& l : model_.loads) {
    const Node& n = model_.nodes[model_.joints[l.joint].node];
    if (n.hasRotation()) load_blocks_.push_back(pattern_.addBlock(range(nq + n.v, 6), range(n.q, 6)));
  }
  for (const Constraint& c : model_.constraints) {
    const ConstraintSides s = sidesOf(model_, c);
    ConstraintBlocks b;
    std::vector<int> q_rows, v_directions;
    for (int d : s) {
      v_directions.push_back(vIndex(model_, s, d));
      b.v_rows.push_back(nq + vIndex(model_, s, d));
      b.q_cols.push_back(qIndex(model_, s, d));
      b.v_cols.push_back(nq + vIndex(model_, s, d));
      q_rows.push_back(qIndex(model_, s, d));
    }
    const std::vector<int> lambda = range(lambdaOffset() + c.row, c.rows);
    b.g = constraint_pattern_.addBlock(range(c.row, c.rows), v_directions);
    b.phi_q = coordinate_pattern_.addBlock(range(c.row, c.rows), q_rows);
    b.vq = pattern_.addBlock(b.v_rows, b.q_cols);
    b.vl = pattern_.addBlock(b.v_rows, lambda);
    b.lq = pattern_.addBlock(lambda, b.q_cols);
    b.lv = pattern_.addBlock(lambda, b.v_cols);
    if (ggl()) {
      const std::vector<int> mu = range(muOffset() + c.row, c.rows);
      b.qm = pattern_.addBlock(q_rows, mu);
      b.qq = pattern_.addBlock(q_rows, b.q_cols);
      b.mq = pattern_.addBlock(mu, b.q_cols);
    }
    constraint_blocks_.push_back(std::move(b));
  }
  pattern_.finalize(size_);
  constraint_pattern_.finalize(model_.nv);
  coordinate_pattern_.finalize(model_.nq);
  listJacobianBlocks();
}

void Assembler::listJacobianBlocks() {
  const auto list = [&](int block) { return jacobian_gather_.add(pattern_, block); };
  const auto end = [&] { return jacobian_gather_.bufferSize(); };
  std::vector<std::size_t> qv_at;
  for (NodeBlocks& b : node_blocks_) {
    qv_at.push_back(list(b.qv));
    b.qq_at = list(b.qq);
  }
  node_range_ = {0, end()};
  for (const std::vector<int>& blocks : element_blocks_) {
    BufferRange range{end(), 0};
    for (int block : blocks) list(block);
    range.end = end();
    element_range_.push_back(range);
  }
  load_range_.begin = end();
  for (int block : load_blocks_) load_at_.push_back(list(block));
  load_range_.end = end();
  for (const ConstraintBlocks& b : constraint_blocks_) {
    const std::array<int, 7> order{b.qm, b.qq, b.mq, b.vq, b.vl, b.lq, b.lv};
    BufferRange range{end(), 0};
    for (auto id = order.begin() + (ggl() ? 0 : 3); id != order.end(); ++id) list(*id);
    range.end = end();
    constraint_range_.push_back(range);
  }
  jacobian_gather_.finalize(pattern_);
  jacobian_buffer_.assign(jacobian_gather_.bufferSize(), 0.0);
  for (std::size_t n = 0; n < node_blocks_.size(); ++n)  // q̇ − K(q) v: ∂/∂v = −K(q) with K's diagonal of 1
    std::fill_n(jacobian_buffer_.begin() + qv_at[n], model_.nodes[n].size(), -1.0);
}

template <class S>
Eigen::Matrix<S, 6, 1> Assembler::loadVector(const Load& load, const double* q, double t,
                                             bool seed, Limit limit) const {
  const Joint& J = model_.joints[load.joint];
  const Node& N = model_.nodes[J.node];
  const double s = load_factor_ * load.scale(t, limit);
  if (!N.hasRotation()) {  // a point: the force acts on r, torques are rejected by the compiler
    Eigen::Matrix<S, 6, 1> Q = Eigen::Matrix<S, 6, 1>::Zero();
    Q.template head<3>() = (s * load.force).cast<S>();
    return Q;
  }
  Vec3T<S> phi;
  for (int k = 0; k < 3; ++k) {
    if constexpr (std::is_same_v<S, double>) {
      phi(k) = q[N.q + 3 + k];
    } else {
      phi(k) = seed ? seeded<double, 6>(q[N.q + 3 + k], 3 + k) : S(q[N.q + 3 + k]);
    }
  }
  const Mat3T<S> R = rotationMatrix<S>(phi);
  Vec3T<S> F = (s * load.force).cast<S>(), M = (s * load.torque).cast<S>();
  if (load.frame == LoadFrame::Joint) {
    const Mat3T<S> RJ = R * J.rotation.cast<S>();
    F = (RJ * F).eval();
    M = (RJ * M).eval();
  }
  // (4-8, 4-9): power F·ṙ_J + M·ω with ṙ_J = ṙ − R r̃_BJ ω.
  Eigen::Matrix<S, 6, 1> Q;
  Q.template head<3>() = F;
  Q.template tail<3>() = J.offset.cast<S>().cross(R.transpose() * F) + R.transpose() * M;
  return Q;
}

void Assembler::residual(double t, const double* y, const double* yp, double* res) const {
  const int nq = model_.nq;
  const auto [q, v, lambda, qdot, a] = daeState(y, yp, nq, lambdaOffset());
  std::fill(res, res + size_, 0.0);
  double* res_v = res + nq;

  for (const Node& n : model_.nodes) {
    for (int k = 0; k < n.size(); ++k) res[n.q + k] = qdot[n.q + k] - v[n.v + k];
    if (!n.hasRotation()) continue;
    const Vec3 w = angularVelocityMap<double>(Vec3(q + n.q + 3)) * Vec3(qdot + n.q + 3);
    for (int k = 0; k < 3; ++k) res[n.q + 3 + k] = w(k) - v[n.v + 3 + k];
  }

  const ElementInput in{q, v, a, t, gravity(), mass_damping_, rates(Limit::Left), load_factor_};
  residual_loop_.run(model_.elements.size(), [&](std::size_t e) {
    element_scratch_[e].resize(model_.elements[e]->size());
    model_.elements[e]->residual(in, element_scratch_[e].data());
  });
  for (std::size_t e = 0; e < model_.elements.size(); ++e) {
    const auto& idx = model_.elements[e]->velocityIndices();
    for (std::size_t k = 0; k < idx.size(); ++k) res_v[idx[k]] += element_scratch_[e][k];
  }

  for (const Load& l : model_.loads) {
    const Node& n = model_.nodes[model_.joints[l.joint].node];
    const auto Q = loadVector<double>(l, q, t, false);
    for (int k = 0; k < (n.hasRotation() ? 6 : 3); ++k) res_v[n.v + k] -= Q(k);
  }

  const SolverSpec& sv = model_.solver;
  for (const Constraint& c : model_.constraints) {
    const ConstraintSides s = sidesOf(model_, c);
    const auto vloc = localExtended(model_, s, v, false);
    double* res_l = res + lambdaOffset() + c.row;
    if (ggl()) {
      const auto C = evaluateConstraint<double>(model_, c, q, t);
      const double* mu = y + muOffset() + c.row;
      for (int i = 0; i < c.rows; ++i) {
        res_l[i] = (C.G.row(i) * vloc).value();
        res[muOffset() + c.row + i] = C.phi(i);
        for (int d : s) {
          res_v[vIndex(model_, s, d)] += C.G(i, d) * lambda[c.row + i];
          res[qIndex(model_, s, d)] += C.G(i, d) * mu[i];
        }
      }
    } else {
      const auto qdloc = localExtended(model_, s, qdot, true);
      const auto C = evaluateConstraint<ConstraintRateDual>(model_, c, q, t, Limit::Left, qdloc.data());
      const auto aloc = localExtended(model_, s, a, false);
      const double alpha = sv.baumgarte_alpha, beta = sv.baumgarte_beta;
      for (int i = 0; i < c.rows; ++i) {
        double phidot = 0.0, g_a = 0.0, gamma = 0.0;
        for (int j = 0; j < kConstraintDirections; ++j) {
          phidot += C.G(i, j).value() * vloc(j);
          if (j != kTimeDirection) g_a += C.G(i, j).value() * aloc(j);
          gamma += C.G(i, j).derivatives()(0) * vloc(j);  // (4-27): Γ = Ġ dq + Φ̇_t
        }
        res_l[i] = g_a + gamma + 2.0 * alpha * beta * phidot + alpha * alpha * C.phi(i).value();
        for (int d : s) res_v[vIndex(model_, s, d)] += C.G(i, d).value() * lambda[c.row + i];
      }
    }
  }
}

void Assembler::jacobian(double t, double cj, const double* y, const double* yp,
                         double* values) const {
  const auto [q, v, lambda, qdot, a] = daeState(y, yp, model_.nq, lambdaOffset());
  double* buffer = jacobian_buffer_.data();
  // The elements', the constraints' and, as one more item, the nodes' and loads' blocks, each
  // into its own places in the buffer and on into the values that it alone reaches; then the
  // values that several reach, gathered from their blocks.
  const ElementInput in{q, v, a, t, gravity(), mass_damping_, rates(Limit::Left), load_factor_};
  const std::size_t elements = model_.elements.size(), constraints = model_.constraints.size();
  const auto write = [&](const BufferRange& r) { jacobian_gather_.writeExclusive(r.begin, r.end, buffer, values); };
  jacobian_loop_.run(elements + constraints + 1, [&](std::size_t item) {
    if (item == elements + constraints) {
      nodeAndLoadTangents(t, cj, q, qdot, buffer);
      write(node_range_), write(load_range_);
      return;
    }
    if (item >= elements) {
      const BufferRange& r = constraint_range_[item - elements];
      constraintTangent(item - elements, t, cj, y, yp, buffer + r.begin);
      write(r);
      return;
    }
    const auto& el = *model_.elements[item];
    const BufferRange& r = element_range_[item];
    double* out = buffer + r.begin;
    if (sparse_element_[item]) {
      el.blockJacobian(in, cj, coordinate_jacobian_only_, out);
    } else if (coordinate_jacobian_only_) {
      const std::size_t coordinates = el.size() * el.coordinateIndices().size();
      el.coordinateJacobian(in, out);
      std::fill(out + coordinates, buffer + r.end, 0.0);
    } else {
      el.jacobian(in, cj, out);
    }
    write(r);
  });
  jacobian_gather_.gatherShared(buffer, values);
}

void Assembler::nodeAndLoadTangents(double t, double cj, const double* q, const double* qdot, double* buffer) const {
  using NodeBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxNodeSize, kMaxNodeSize>;
  for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
    const Node& node = model_.nodes[n];
    double* out = buffer + node_blocks_[n].qq_at;
    if (!node.hasRotation()) {
      std::fill_n(out, node.size(), cj);
      continue;
    }
    // ∂/∂q (K(q) q̇) + cj K(q) with K = diag(I, T(φ), 1…)
    using D = Dual<double, 3>;
    Vec3T<D> phi;
    for (int k = 0; k < 3; ++k) phi(k) = seeded<double, 3>(q[node.q + 3 + k], k);
    const Vec3T<D> w = angularVelocityMap<D>(phi) * Vec3(qdot + node.q + 3).cast<D>();
    const int size = node.size();
    Eigen::Map<NodeBlock> J(out, size, size);
    J = cj * NodeBlock::Identity(size, size);
    J.block<3, 3>(3, 3) = cj * angularVelocityMap<double>(Vec3(q + node.q + 3));
    for (int k = 0; k < 3; ++k) J.block<1, 3>(3 + k, 3) += w(k).derivatives().transpose();
  }
  for (std::size_t l = 0, block = 0; l < model_.loads.size(); ++l) {
    if (!model_.nodes[model_.joints[model_.loads[l].joint].node].hasRotation()) continue;  // constant force
    const auto Q = loadVector<Dual<double, 6>>(model_.loads[l], q, t, true);
    Eigen::Map<Eigen::Matrix<double, 6, 6>> J(buffer + load_at_[block++]);
    for (int k = 0; k < 6; ++k) J.row(k) = -Q(k).derivatives().transpose();
  }
}

/// Constraint `ci`'s blocks of the DAE Jacobian, flat in the order listJacobianBlocks lists them:
/// with GGL qm, qq, mq, then vq, vl, lq, lv.
void Assembler::constraintTangent(std::size_t ci, double t, double cj, const double* y, const double* yp,
                                  double* out) const {
  const auto [q, v, lambda, qdot, a] = daeState(y, yp, model_.nq, lambdaOffset());
  const auto append = [&](const auto& block) { out = std::copy(block.data(), block.data() + block.size(), out); };
  const SolverSpec& sv = model_.solver;
  const double alpha = sv.baumgarte_alpha, beta = sv.baumgarte_beta;
  using Rows12 = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraintRows, 12>;
  using Square12 = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 12, 12>;
  using Columns12 = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 12, kMaxConstraintRows>;
  const Constraint& c = model_.constraints[ci];
  const ConstraintSides s = sidesOf(model_, c);
  const ConstraintSecondDerivatives C(model_, c, q, t);
  const int nd = s.count;
  const int m = c.rows;
  // Σ wᵢ ∂Gᵢ/∂q over the constraint's directions: the Jacobian of Gᵀw for w = λ or μ.
  const auto weightedSecondDerivative = [&](const double* w) {
    const ConstraintSecondDerivatives::Mat13 full = C.weighted(w);
    Square12 sum(nd, nd);
    for (int kk = 0; kk < nd; ++kk)
      for (int jj = 0; jj < nd; ++jj) sum(jj, kk) = full(s.direction[jj], s.direction[kk]);
    return sum;
  };
  // Over the constraint's directions: G (vl = Gᵀ, lv), λᵀ∂G/∂q (vq), ∂(G dq + Φ_t)/∂q (dGv), Φ_q.
  const Square12 vq = weightedSecondDerivative(lambda + c.row);
  const ConstraintSecondDerivatives::Rows13 dG_v = C.directionContractions(localExtended(model_, s, v, false));
  Columns12 vl(nd, m);
  Rows12 lq(m, nd), lv(m, nd), dGv(m, nd), phi_q(m, nd);
  for (int i = 0; i < m; ++i) {
    for (int jj = 0; jj < nd; ++jj) {
      const int j = s.direction[jj];
      vl(jj, i) = lv(i, jj) = C.G(i, j);
      phi_q(i, jj) = C.phi_q(i, j);
      dGv(i, jj) = dG_v(i, j);
    }
  }
  if (ggl()) {
    lq = dGv;
    const Square12 qq = weightedSecondDerivative(y + muOffset() + c.row);
    append(vl), append(qq), append(phi_q);
  } else {
    // Exact except for ∂Γ/∂q, which needs third derivatives and only slows Newton slightly.
    auto aloc = localExtended(model_, s, a, false);
    aloc(kTimeDirection) = 0.0;
    const ConstraintSecondDerivatives::Rows13 dG_a = C.directionContractions(aloc);
    const ConstraintSecondDerivatives::Rows13 G_rate = C.coordinateContractions(localExtended(model_, s, qdot, true));
    for (int i = 0; i < m; ++i) {
      for (int kk = 0; kk < nd; ++kk) {
        const int k = s.direction[kk];
        lq(i, kk) = dG_a(i, k) + (2.0 * alpha * beta + cj) * dGv(i, kk) + alpha * alpha * phi_q(i, kk);
        lv(i, kk) = (cj + 2.0 * alpha * beta) * C.G(i, k) + G_rate(i, k);
      }
    }
  }
  append(vq), append(vl), append(lq), append(lv);
}

Eigen::SparseMatrix<double> Assembler::massMatrix(double t, const double* q) const {
  VecX values = VecX::Zero(mass_pattern_.nonZeros());
  const ElementInput in{q, nullptr, nullptr, t, gravity()};
  std::vector<double> local;
  for (std::size_t k = 0; k < model_.elements.size(); ++k) {
    const Element& e = *model_.elements[k];
    local.resize(e.size() * e.size());
    e.mass(in, local.data());
    const std::vector<int>& slots = mass_pattern_.slots(mass_blocks_[k]);
    const std::size_t stride = sparse_element_[k] ? e.size() + 1 : 1;  // a sparse element's diagonal
    for (std::size_t i = 0; i < slots.size(); ++i) values[slots[i]] += local[i * stride];
  }
  return patternedMatrix(mass_pattern_, model_.nv, values);
}

VecX Assembler::appliedForces(double t, const double* q, const double* v, Limit limit) const {
  VecX zero_a = VecX::Zero(model_.nv);
  VecX F = VecX::Zero(model_.nv);
  const ElementInput in{q, v, zero_a.data(), t, gravity(), mass_damping_, rates(limit), load_factor_};
  std::vector<double> local;
  for (const auto& e : model_.elements) {
    local.resize(e->size());
    e->residual(in, local.data());
    const auto& idx = e->velocityIndices();
    for (std::size_t k = 0; k < idx.size(); ++k) F(idx[k]) += local[k];
  }
  for (const Load& l : model_.loads) {
    const Node& n = model_.nodes[model_.joints[l.joint].node];
    const auto Q = loadVector<double>(l, q, t, false, limit);
    for (int k = 0; k < (n.hasRotation() ? 6 : 3); ++k) F(n.v + k) -= Q(k);
  }
  return F;
}

ConstraintState Assembler::constraints(double t, const double* q, const double* v, Limit limit) const {
  ConstraintState out;
  const int m = model_.m;
  out.phi = VecX::Zero(m);
  out.phi_dot = VecX::Zero(m);
  out.gamma = VecX::Zero(m);
  out.phi_t = VecX::Zero(m);
  const VecX qdot = coordinateRates(q, v);
  VecX g = VecX::Zero(constraint_pattern_.nonZeros()), pq = VecX::Zero(coordinate_pattern_.nonZeros());
  for (std::size_t n = 0; n < model_.constraints.size(); ++n) {
    const Constraint& c = model_.constraints[n];
    const std::vector<int>& v_slots = constraint_pattern_.slots(constraint_blocks_[n].g);
    const std::vector<int>& q_slots = coordinate_pattern_.slots(constraint_blocks_[n].phi_q);
    const ConstraintSides s = sidesOf(model_, c);
    const auto vloc = localExtended(model_, s, v, false);
    const auto qdloc = localExtended(model_, s, qdot.data(), true);
    const auto C = evaluateConstraint<ConstraintRateDual>(model_, c, q, t, limit, qdloc.data());
    // Φ_q from G: a node's rotation-vector rates φ̇ turn it by the body-frame twist T(φ) φ̇ (2-10).
    std::array<Mat3, 2> twist_per_phi;
    for (int side = 0; side < 2; ++side) {
      const int first = 6 * side + 3;
      if (std::find(s.begin(), s.end(), first) != s.end())
        twist_per_phi[side] = angularVelocityMap<double>(Vec3(q + qIndex(model_, s, first)));
    }
    for (int i = 0; i < c.rows; ++i) {
      const int row = c.row + i;
      out.phi(row) = C.phi(i).value();
      out.phi_t(row) = C.G(i, kTimeDirection).value();
      for (int j = 0; j < kConstraintDirections; ++j) {
        out.phi_dot(row) += C.G(i, j).value() * vloc(j);
        out.gamma(row) += C.G(i, j).derivatives()(0) * vloc(j);
      }
      for (int j = 0; j < s.count; ++j) {
        const int d = s.direction[j], entry = j * c.rows + i;  // column-major in the block
        g(v_slots[entry]) += C.G(i, d).value();
        const int side = d / 6, k = d % 6;
        double dphi = C.G(i, d).value();  // ∂Φ/∂r = ∂Φ/∂δr
        if (k >= 3) {
          dphi = 0.0;
          for (int l = 0; l < 3; ++l) dphi += C.G(i, 6 * side + 3 + l).value() * twist_per_phi[side](l, k - 3);
        }
        pq(q_slots[entry]) += dphi;
      }
    }
  }
  out.G = patternedMatrix(constraint_pattern_, m, g);
  out.Phi_q = patternedMatrix(coordinate_pattern_, m, pq);
  return out;
}

VecX Assembler::coordinateRates(const double* q, const double* v) const {
  VecX qdot(model_.nq);
  for (const Node& n : model_.nodes) {
    for (int k = 0; k < n.size(); ++k) qdot(n.q + k) = v[n.v + k];
    if (n.hasRotation())
      qdot.segment<3>(n.q + 3) = angularVelocityMapInverse<double>(Vec3(q + n.q + 3)) * Vec3(v + n.v + 3);
  }
  return qdot;
}

double Assembler::kineticEnergy(double t, const double* q, const double* v) const {
  const ElementInput in{q, v, nullptr, t, gravity()};
  double sum = 0.0;
  for (const auto& e : model_.elements) sum += e->kineticEnergy(in);
  return sum;
}

double Assembler::potentialEnergy(double t, const double* q) const {
  const ElementInput in{q, nullptr, nullptr, t, gravity()};
  double sum = 0.0;
  for (const auto& e : model_.elements) sum += e->potentialEnergy(in);
  return sum;
}

double Assembler::loadPower(double t, const double* q, const double* v) const {
  double p = 0.0;
  for (const Load& l : model_.loads) {
    const Node& n = model_.nodes[model_.joints[l.joint].node];
    const auto Q = loadVector<double>(l, q, t, false);
    for (int k = 0; k < (n.hasRotation() ? 6 : 3); ++k) p += Q(k) * v[n.v + k];
  }
  return p;
}

double Assembler::windPower(double t, const double* q, const double* v) const {
  if (model_.wind_parts.empty()) return 0.0;
  const ElementInput in{q, v, nullptr, t, gravity(), 0.0, ParameterRates::Left, load_factor_};
  double p = 0.0;
  for (const WindPart& part : model_.wind_parts)
    for (int e : part.elements) p += dynamic_cast<const WindElement&>(*model_.elements[e]).power(in);
  return p;
}

double Assembler::constraintResidual(double t, const double* y) const {
  double worst = 0.0;
  double phi[kMaxConstraintRows];
  for (const Constraint& c : model_.constraints) {
    constraintEquations<double>(c.law(), model_.jointFrame(y, c.joint1), model_.jointFrame(y, c.joint2), t, phi);
    for (int i = 0; i < c.rows; ++i) worst = std::max(worst, std::abs(phi[i]));
  }
  return worst;
}

void Assembler::workPowers(double t, const double* y, double* out) const {
  const double* q = y;
  const double* v = y + vOffset();
  const ElementInput in{q, v, nullptr, t, gravity()};
  double winch = 0.0, dissipated = 0.0;
  for (const auto& e : model_.elements) {
    winch += e->explicitTimePower(in);
    dissipated += e->dissipatedPower(in);
  }
  WorkTerms{drivePower(t, q, y + lambdaOffset()), loadPower(t, q, v) + windPower(t, q, v), winch, dissipated}.toArray(out);
}

double Assembler::drivePower(double t, const double* q, const double* lambda) const {
  double p = 0.0;
  for (const Constraint& c : model_.constraints) p += drivePower(c, t, q, lambda);
  return p;
}

double Assembler::drivePower(const Constraint& c, double t, const double* q, const double* lambda) const {
  if (!c.drive || c.drive->isConstant()) return 0.0;
  const auto C = evaluateConstraint<double>(model_, c, q, t);
  double p = 0.0;
  for (int i = 0; i < c.rows; ++i) p += C.G(i, kTimeDirection) * lambda[c.row + i];
  return p;
}


void Assembler::hold(double t, const double* y) const {
  const ElementInput in{y, y + vOffset(), nullptr, t, gravity()};
  for (const auto& e : model_.elements) e->hold(in);
}

std::vector<double> Assembler::memory() const {
  std::vector<double> out;
  for (const auto& e : model_.elements) {
    const std::vector<double> own = e->memory();
    out.insert(out.end(), own.begin(), own.end());
  }
  return out;
}

void Assembler::setMemory(const std::vector<double>& memory) const {
  std::size_t at = 0;
  for (const auto& e : model_.elements) {
    const std::size_t size = e->memory().size();
    if (at + size > memory.size()) throw std::invalid_argument("the saved memory is not one of this model's elements");
    e->setMemory(memory.data() + at);
    at += size;
  }
}

void Assembler::forgetMemory() const {
  for (const auto& e : model_.elements) e->forgetMemory();
}

}  // namespace cranesim
