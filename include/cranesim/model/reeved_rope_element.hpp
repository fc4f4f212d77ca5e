#pragma once
// A massless reeved rope (elements/reeved_rope.hpp) as an element on the nodes its path runs
// over: each path point is a joint (a sheave's centre, the winch, the dead end) on a body or
// member node, or fixed on the ground (model/rope_path.hpp). Its forces go to the nodes as
// [f, p × Rᵀ f] (the force at the point p on a node's [ṙ, ω]). Its tension ratios depend on the
// direction the rope runs, not a polynomial in the velocities, so both tangents come from
// forward AD of the same code, one node at a time (a node's coordinates or velocities seeded, at
// most 7 directions). Its sheaves' grips (pre-sliding memory) are held at each accepted step.
//   residual   r = F(q, dq, t): the rope's forces on the nodes (no mass)

#include <string>
#include <vector>

#include "cranesim/elements/reeved_rope.hpp"
#include "cranesim/model/reeved_rope.hpp"
#include "cranesim/model/rope_path.hpp"

namespace cranesim {

struct Model;

class ReevedRopeElement final : public ReevedRope {
 public:
  /// The nodes' coordinates sit on the stack in every call.
  static constexpr int kMaxLocal = RopePath::kMaxNodes * 7;
  template <class S> using Local = Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxLocal, 1>;

  /// `path`'s slots are the local vectors.
  ReevedRopeElement(std::string name, ReevedRopeKernel kernel, RopePath path, std::vector<int> nodes,
                    std::vector<int> q_indices, std::vector<int> v_indices);

  const std::string& name() const override { return name_; }
  int parts() const override { return kernel_.parts(); }
  const ReevedRopeKernel& kernel() const { return kernel_; }
  const std::vector<int>& nodes() const override { return nodes_; }
  int size() const override { return static_cast<int>(v_.size()); }
  const std::vector<int>& velocityIndices() const override { return v_; }
  const std::vector<int>& coordinateIndices() const override { return q_; }
  void residual(const ElementInput& in, double* r) const override;
  void jacobian(const ElementInput& in, double cj, double* J) const override;
  void coordinateJacobian(const ElementInput& in, double* J) const override;
  void mass(const ElementInput& in, double* M) const override;
  double kineticEnergy(const ElementInput&) const override { return 0.0; }
  double potentialEnergy(const ElementInput& in) const override;
  double explicitTimePower(const ElementInput& in) const override;
  double dissipatedPower(const ElementInput& in) const override;
  void hold(const ElementInput& in) const override;
  std::vector<double> memory() const override;
  void setMemory(const double* memory) const override;
  void forgetMemory() const override { kernel_.grip = {}; }

  void partTensions(const ElementInput& in, double* tension) const override;
  std::vector<Vec3> pathPositions(const ElementInput& in) const override;
  double hoistingLinePull(const double* tension) const override {
    return cranesim::hoistingLinePull(tension, kernel_.friction_exponent.data(), kernel_.parts());
  }

 private:
  template <class S> struct Path {
    ReevedRopeKernel::Points<S> x, xd;
    RopePath::Rotations<S> R;
  };
  template <class S> Path<S> path(const Local<S>& q, const Local<S>& v) const;
  template <class S> Local<S> force(const Local<S>& q, const Local<S>& v, double t, ParameterRates rates) const;
  /// ∂F/∂q (or ∂F/∂dq with `velocities`) into J, column-major, size() × size().
  void tangent(const ElementInput& in, bool velocities, double* J) const;
  Local<double> gather(const double* x, const std::vector<int>& at) const;

  std::string name_;
  mutable ReevedRopeKernel kernel_;  // its sheaves' grips move as the run goes (hold)
  RopePath path_;
  std::vector<int> nodes_, q_, v_;
};

}  // namespace cranesim
