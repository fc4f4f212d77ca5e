#pragma once
// The DAE residual of the multibody system and its sparse Jacobian, in the unknowns
// y = [q, dq, λ] (+ μ for the stabilised index-2 form):
//
//   K(q) q̇ − dq (+ Gᵀμ)                 = 0   kinematics, K = diag(I, T(φ)) per node (2-10)
//   M(q) d(dq)/dt + F(q, dq, t) + Gᵀλ − Q = 0   Lagrange's equations of the first kind (4-3)
//   GGL:        G dq + Φ_t = 0,  Φ = 0   (Gear–Gupta–Leimkuhler, index 2)
//   Baumgarte:  G d(dq)/dt + Γ + 2αβ Φ̇ + α² Φ = 0   (4-27, index 1)
//
// G = Bᵀ is the velocity Jacobian of Φ and Q the applied nodal loads (4-8, 4-9).

#include <Eigen/Sparse>

#include "cranesim/assembly/block_gather.hpp"
#include "cranesim/assembly/constraint_evaluation.hpp"
#include "cranesim/assembly/constraint_second_derivatives.hpp"
#include "cranesim/assembly/element_loop.hpp"
#include "cranesim/assembly/sparsity.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

/// Constraint quantities at one state, for initial conditions, restarts and output.
struct ConstraintState {
  VecX phi;                       // Φ
  VecX phi_dot;                   // G dq + Φ_t
  VecX gamma;                     // Γ = Ġ dq + dΦ_t/dt with q̇ = H dq
  Eigen::SparseMatrix<double> G;  // m × nv
  Eigen::SparseMatrix<double> Phi_q;  // m × nq
  VecX phi_t;                     // Φ_t
};

/// The works of the energy balance, each integrated from the run's start (J), or their powers
/// (W). The equations of motion give dE/dt = P_drive + P_load + P_winch − P_dissipated for
/// E = T + V (element.hpp), so E(t) − E(t0) − drive − load − winch + dissipated stays 0.
struct WorkTerms {
  static constexpr int kCount = 4;
  double drive = 0.0;       // rheonomic drives, λ·Φ_t
  double load = 0.0;        // applied nodal forces and torques, Q·dq, and the wind's power
  double winch = 0.0;       // elements' explicit time dependence: ropes reeled in and out
  double dissipated = 0.0;  // material damping, ≥ 0
  /// To and from kCount values in the order of the members (IDAS' quadrature vector).
  static WorkTerms fromArray(const double* w) { return {w[0], w[1], w[2], w[3]}; }
  void toArray(double* w) const { w[0] = drive, w[1] = load, w[2] = winch, w[3] = dissipated; }
};

class Assembler {
 public:
  explicit Assembler(const Model& model) : Assembler(model, model.solver.formulation) {}
  /// With a formulation other than the scene's (statics always uses the GGL rows).
  Assembler(const Model& model, Formulation formulation);

  const Model& model() const { return model_; }
  bool ggl() const { return formulation_ == Formulation::GGL; }
  /// Scales gravity and applied loads (statics ramps them from 0 to 1).
  void setLoadFactor(double factor) { load_factor_ = factor; }
  double loadFactor() const { return load_factor_; }
  /// Adds α M(q) dq to the equations of motion: the artificial damping of static relaxation.
  void setMassDamping(double alpha) { mass_damping_ = alpha; }
  /// Holds the elements' time-dependent parameters at their values at t, their rates 0
  /// (ElementInput::rates): statics and modes.
  void setParametersHeld(bool held) { parameters_held_ = held; }
  /// jacobian() then computes the elements' ∂r/∂q only and leaves their velocity columns zero:
  /// all that statics reads (the equilibrium system's unknowns are q and λ), at the cost of
  /// nq_local instead of nq_local + nv_local AD directions.
  void setCoordinateJacobianOnly(bool only) { coordinate_jacobian_only_ = only; }
  /// Size of y and offsets of its parts.
  int size() const { return size_; }
  int vOffset() const { return model_.nq; }
  int lambdaOffset() const { return model_.nq + model_.nv; }
  int muOffset() const { return model_.nq + model_.nv + model_.m; }
  const SparsityPattern& pattern() const { return pattern_; }

  /// F(t, y, ẏ) of the DAE.
  void residual(double t, const double* y, const double* yp, double* res) const;
  /// ∂F/∂y + cj ∂F/∂ẏ into `values`, laid out by pattern().
  void jacobian(double t, double cj, const double* y, const double* yp, double* values) const;

  // Pieces used by initial conditions, restarts and output.
  /// M(q), scattered into a pattern built once (every element's velocity block).
  Eigen::SparseMatrix<double> massMatrix(double t, const double* q) const;
  /// F(q, dq, t) − Q(q, t): everything but inertia and constraint forces.
  /// `limit`: at a drive or load breakpoint, the one-sided values to use (Right when
  /// (re)starting from it).
  VecX appliedForces(double t, const double* q, const double* v, Limit limit = Limit::Left) const;
  ConstraintState constraints(double t, const double* q, const double* v, Limit limit = Limit::Left) const;
  /// q̇ = H(q) dq.
  VecX coordinateRates(const double* q, const double* v) const;
  double kineticEnergy(double t, const double* q, const double* v) const;
  /// Gravity potential plus strain energy.
  double potentialEnergy(double t, const double* q) const;
  /// Power of the applied loads, Q·dq.
  double loadPower(double t, const double* q, const double* v) const;
  /// Power of the wind on the parts exposed to it (WindElement::power); part of WorkTerms::load.
  double windPower(double t, const double* q, const double* v) const;
  /// max |Φ(q, t)| over all constraint equations, for y = [q, …].
  double constraintResidual(double t, const double* y) const;
  /// Power of the rheonomic drives on the system, λ·Φ_t (constraint forces −Gᵀλ, G dq = −Φ_t).
  double drivePower(double t, const double* q, const double* lambda) const;
  /// The same of one constraint's drive (0 for a constraint without one).
  double drivePower(const Constraint& constraint, double t, const double* q, const double* lambda) const;
  /// The powers of WorkTerms at y = [q, dq, λ, …], WorkTerms::kCount values into `out` in the
  /// order of its members: the integrands of the energy balance's quadratures.
  void workPowers(double t, const double* y, double* out) const;
  /// Every element's memory (model/element.hpp) moved to y = [q, dq, …], a step accepted at t.
  void hold(double t, const double* y) const;
  /// The elements' memories one after the other, and back; forgotten: as compiled.
  std::vector<double> memory() const;
  void setMemory(const std::vector<double>& memory) const;
  void forgetMemory() const;

 private:
  struct ConstraintBlocks {
    std::vector<int> v_rows, q_cols, v_cols;
    int vq = -1, vl = -1, lq = -1, lv = -1, qm = -1, qq = -1, mq = -1, la = -1;
    int g = -1, phi_q = -1;  // its rows of G and Φ_q (constraint_pattern_, coordinate_pattern_)
  };
  struct NodeBlocks {
    int qq = -1, qv = -1;
    std::size_t qq_at = 0;  // the qq block in jacobian_buffer_
  };

  void buildPattern();
  /// Lists the DAE Jacobian's blocks in jacobian_gather_ in the order their entries are summed.
  void listJacobianBlocks();
  void constraintTangent(std::size_t ci, double t, double cj, const double* y, const double* yp, double* out) const;
  /// The nodes' kinematic blocks ∂/∂q (K(q) q̇) + cj K(q) and the loads' −∂Q/∂q.
  void nodeAndLoadTangents(double t, double cj, const double* q, const double* qdot, double* buffer) const;
  template <class S> Eigen::Matrix<S, 6, 1> loadVector(const Load& load, const double* q, double t,
                                                       bool seed, Limit limit = Limit::Left) const;

  Vec3 gravity() const { return load_factor_ * model_.gravity; }
  ParameterRates rates(Limit limit) const {
    if (parameters_held_) return ParameterRates::Held;
    return limit == Limit::Right ? ParameterRates::Right : ParameterRates::Left;
  }

  const Model& model_;
  Formulation formulation_;
  double load_factor_ = 1.0;
  double mass_damping_ = 0.0;
  bool parameters_held_ = false;
  bool coordinate_jacobian_only_ = false;
  int size_ = 0;
  SparsityPattern pattern_;
  std::vector<NodeBlocks> node_blocks_;
  /// Each element's blocks of the DAE Jacobian: one, or a sparse element's (Element::jacobianBlocks).
  std::vector<std::vector<int>> element_blocks_;
  std::vector<bool> sparse_element_;
  // Places in jacobian_buffer_: each element's block, each constraint's blocks (in
  // constraintTangent's order), all nodes' blocks and all loads' blocks; the qq block of each
  // node and the block of each load with a torque.
  struct BufferRange {
    std::size_t begin = 0, end = 0;
  };
  std::vector<BufferRange> element_range_, constraint_range_;
  BufferRange node_range_, load_range_;
  std::vector<std::size_t> load_at_;
  // Patterns of M (nv × nv, a block per element: mass_blocks_), G (m × nv) and Φ_q (m × nq).
  SparsityPattern mass_pattern_, constraint_pattern_, coordinate_pattern_;
  std::vector<int> mass_blocks_;
  std::vector<int> load_blocks_;
  std::vector<ConstraintBlocks> constraint_blocks_;
  // Per-element residuals written in parallel and summed in a fixed order.
  mutable std::vector<std::vector<double>> element_scratch_;
  // Every block of the DAE Jacobian side by side, written in parallel; jacobian_gather_ puts
  // them into the values.
  BlockGather jacobian_gather_;
  mutable std::vector<double> jacobian_buffer_;
  mutable ElementLoop residual_loop_, jacobian_loop_;
};

}  // namespace cranesim
