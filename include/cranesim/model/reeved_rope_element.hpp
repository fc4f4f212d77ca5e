#pragma once
// A massless reeved rope (elements/reeved_rope.hpp) as an element on the nodes its path runs
// over: each path point is a joint (a sheave's centre, the winch, the dead end) on a body or
// member node, or fixed on the ground. Its forces go to the nodes as [f, p × Rᵀ f] (the
// force at the point p on a node's [ṙ, ω]). Its tension ratios depend on the direction the rope
// runs, not a polynomial in the velocities, so both tangents come from forward AD of the same
// code, one node at a time (a node's coordinates or velocities seeded, at most 7 directions).
//   residual   r = F(q, dq, t): the rope's forces on the nodes (no mass)

#include <string>
#include <vector>

#include "cranesim/elements/reeved_rope.hpp"
#include "cranesim/model/element.hpp"

namespace cranesim {

struct Model;

class ReevedRopeElement final : public Element {
 public:
  /// Nodes one rope may run over; their coordinates sit on the stack in every call.
  static constexpr int kMaxNodes = 6;
  static constexpr int kMaxLocal = kMaxNodes * 7;
  template <class S> using Local = Eigen::Matrix<S, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxLocal, 1>;

  /// One of the element's nodes: where its values start in the local vectors, how many, and
  /// whether values 3…5 are a rotation (vector; body angular velocity).
  struct Slot {
    int at = 0;
    int size = 3;
    bool rotates = false;
  };
  /// A path point: `offset` in the axes of the node in `slot`, or with slot < 0 the point itself,
  /// fixed.
  struct PathPoint {
    int slot = -1;
    Vec3 offset = Vec3::Zero();
  };

  ReevedRopeElement(std::string name, ReevedRopeKernel kernel, std::vector<PathPoint> path, std::vector<Slot> slots,
                    std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);

  /// The rope member's name.
  const std::string& name() const { return name_; }
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

  /// The tensions of the rope's parts, from the winch to the dead end (kernel().parts() values), N.
  void partTensions(const ElementInput& in, double* tension) const;
  /// The positions of the path points, winch to dead end.
  std::vector<Vec3> pathPositions(const ElementInput& in) const;

 private:
  template <class S> struct Path {
    ReevedRopeKernel::Points<S> x, xd;
    std::array<Mat3T<S>, kMaxNodes> R;
  };
  template <class S> Path<S> path(const Local<S>& q, const Local<S>& v) const;
  template <class S> Local<S> force(const Local<S>& q, const Local<S>& v, double t, ParameterRates rates) const;
  /// ∂F/∂q (or ∂F/∂dq with `velocities`) into J, column-major, size() × size().
  void tangent(const ElementInput& in, bool velocities, double* J) const;
  Local<double> gather(const double* x, const std::vector<int>& at) const;

  std::string name_;
  ReevedRopeKernel kernel_;
  std::vector<PathPoint> path_;
  std::vector<Slot> slots_;
  std::vector<int> nodes_, q_, v_;
};

/// The index in Model::reeved_ropes of the reeved rope named `rope`, −1 for none.
int findReevedRope(const Model& model, const std::string& rope);
/// Model::reeved_ropes[index]'s element.
const ReevedRopeElement& reevedRope(const Model& model, int index);

}  // namespace cranesim
