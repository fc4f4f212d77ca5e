#pragma once
// A massive reeved rope (elements/massive_reeving.hpp) as an element: its path points on the
// nodes of the bodies and members they sit on (model/rope_path.hpp), its parts' inner nodes
// (Point nodes) and its sheaves' material coordinates (Material nodes), local coordinates in
// that order. The element is sparse (model/element.hpp): its Jacobian is one small block per
// cable, the cable's two end nodes and the material coordinates of its part, both tangents by
// forward AD of the cable's share of the residual; so its cost grows with its cables, not with
// their square.
//   residual   r = M(σ) (a + α dq) + F(q, dq, t)

#include <array>
#include <string>
#include <vector>

#include "cranesim/elements/massive_reeving.hpp"
#include "cranesim/elements/reeved_rope.hpp"
#include "cranesim/model/reeved_rope.hpp"
#include "cranesim/model/rope_path.hpp"

namespace cranesim {

class MassiveReevedRopeElement final : public ReevedRope {
 public:
  /// `path`'s slots first in the local vectors, then the inner nodes (3 values each, part by
  /// part, winch to dead end), then the sheaves' material coordinates (1 value each).
  MassiveReevedRopeElement(std::string name, MassiveReevingKernel kernel, RopePath path, std::vector<int> nodes,
                           std::vector<int> q_indices, std::vector<int> v_indices);

  const std::string& name() const override { return name_; }
  int parts() const override { return kernel_.parts(); }
  const MassiveReevingKernel& kernel() const { return kernel_; }
  const std::vector<int>& nodes() const override { return nodes_; }
  int size() const override { return static_cast<int>(v_.size()); }
  const std::vector<int>& velocityIndices() const override { return v_; }
  const std::vector<int>& coordinateIndices() const override { return q_; }
  void residual(const ElementInput& in, double* r) const override;
  void jacobian(const ElementInput& in, double cj, double* J) const override;
  void coordinateJacobian(const ElementInput& in, double* J) const override;
  void mass(const ElementInput& in, double* M) const override;
  std::vector<std::vector<int>> jacobianBlocks() const override;
  void blockJacobian(const ElementInput& in, double cj, bool coordinates_only, double* values) const override;
  double kineticEnergy(const ElementInput& in) const override;
  double potentialEnergy(const ElementInput& in) const override;
  double explicitTimePower(const ElementInput& in) const override;
  double dissipatedPower(const ElementInput& in) const override;

  void partTensions(const ElementInput& in, double* tension) const override;
  std::vector<Vec3> pathPositions(const ElementInput& in) const override;
  double hoistingLinePull(const double* tension) const override {
    return cranesim::hoistingLinePull(tension, kernel_.friction_exponent.data(), kernel_.parts());
  }
  /// The tension of every element, part by part from the winch (parts × elements_per_part), N.
  std::vector<double> elementTensions(const ElementInput& in) const;
  /// The chain's node positions, winch to dead end (path points included).
  std::vector<Vec3> chainPositions(const ElementInput& in) const;
  /// Where chain node c sits: on a model node at an offset in its axes (a path point on a body or
  /// member node), the node itself (an inner node, offset 0), or with node −1 the point itself
  /// (a path point on the ground).
  struct ChainPoint {
    int node = -1;
    Vec3 offset = Vec3::Zero();
  };
  ChainPoint chainPoint(int c) const;
  /// The material coordinates σ_0 … σ_m (file comment of massive_reeving.hpp), m.
  std::vector<double> materialCoordinates(const ElementInput& in) const;

 private:
  using Local = Eigen::VectorXd;
  /// A cable's values: a path point's node (7 at most) at one end, an inner node at the other,
  /// two material coordinates.
  static constexpr int kMaxCableValues = RopePath::kMaxSlotValues + 3 + 2;
  using CableDual = Dual<double, kMaxCableValues>;
  template <class S> using CableValues = Eigen::Matrix<S, Eigen::Dynamic, 1, 0, kMaxCableValues, 1>;
  /// Element e of part k as a block of the local values (`locals`): each end a path point
  /// (`point`, its node's values from `end_at` in the block, none for the ground) or an inner
  /// node (point −1, its position from `end_at`); σ_k and σ_{k+1} at `sigma_at` (−1: the winch's
  /// σ_0, the dead end's σ_m, no coordinates).
  struct CableBlock {
    int k = 0, e = 0;
    std::array<int, 2> point{-1, -1}, end_at{0, 0}, sigma_at{-1, -1};
    std::vector<int> locals;
  };
  void listCables();
  /// Cable b's share of the residual on its block, from the block's q, v and a.
  template <class S> CableValues<S> cableForce(const CableBlock& b, const CableValues<S>& q, const CableValues<S>& v,
                                               const CableValues<double>& a, const ElementInput& in) const;
  template <class S> MassiveReevingKernel::State<S> state(const Eigen::Matrix<S, Eigen::Dynamic, 1>& q,
                                                          const Eigen::Matrix<S, Eigen::Dynamic, 1>& v,
                                                          const Local& a, const ElementInput& in) const;
  /// The blocks' Jacobians (blockJacobian) added into the dense J = [∂r/∂q | ∂r/∂dq + cj M],
  /// or its ∂r/∂q alone.
  void denseJacobian(const ElementInput& in, double cj, bool coordinates_only, double* J) const;
  static CableValues<double> gather(const Local& x, const std::vector<int>& at);
  Local gather(const double* x, const std::vector<int>& at) const;
  /// The local d(dq)/dt, zero where the input has none (a static state).
  Local accelerations(const ElementInput& in) const;
  int innerAt() const { return inner_at_; }
  int sheaveAt() const { return inner_at_ + 3 * innerNodes(); }
  int innerNodes() const { return kernel_.parts() * (kernel_.elements_per_part - 1); }

  std::string name_;
  MassiveReevingKernel kernel_;
  RopePath path_;
  int inner_at_ = 0;
  std::vector<int> nodes_, q_, v_;
  std::vector<CableBlock> cables_;
};

}  // namespace cranesim
