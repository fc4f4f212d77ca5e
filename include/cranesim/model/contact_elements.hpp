#pragma once
// Compliant unilateral contacts as elements without mass (elements/penalty_contact.hpp): a point
// of a part on the ground plane, and a boom on its backstop. They sit on the nodes they touch,
// so the Jacobian's pattern does not change whether a contact is open or closed, and obtain
// both tangents by forward AD of their force (friction is not a polynomial in the velocities,
// which KernelElement's polarization assumes).
//   residual   r = −Q(q, dq)  (the contact's generalized force Q on the right-hand side)
//   energy     the springs' V(δ) in the potential energy; the dampers' and friction's power,
//              (Q(q, 0) − Q(q, dq)) · dq ≥ 0, in the dissipated power
// Contacts are reactions, not applied loads: statics does not ramp them with its load factor.

#include <vector>

#include "cranesim/elements/penalty_contact.hpp"
#include "cranesim/model/element.hpp"

namespace cranesim {

class ContactElement : public Element {
 public:
  /// Local coordinates or velocities: at most two frame nodes' [r, φ], on the stack.
  using Local = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 12, 1>;

  ContactElement(std::vector<int> nodes, std::vector<int> q_indices, std::vector<int> v_indices);
  const std::vector<int>& nodes() const override { return nodes_; }
  int size() const override { return static_cast<int>(v_.size()); }
  const std::vector<int>& velocityIndices() const override { return v_; }
  const std::vector<int>& coordinateIndices() const override { return q_; }
  void residual(const ElementInput& in, double* r) const override;
  void jacobian(const ElementInput& in, double cj, double* J) const override;
  void coordinateJacobian(const ElementInput& in, double* J) const override;
  void mass(const ElementInput& in, double* M) const override;
  double kineticEnergy(const ElementInput&) const override { return 0.0; }
  double potentialEnergy(const ElementInput& in) const override { return energy(gather(in.q, q_)); }
  double dissipatedPower(const ElementInput& in) const override;

  /// How far the contact is closed now (penetration, m; a stop's compression, rad); ≤ 0 open.
  double closure(const ElementInput& in) const { return closureAt(gather(in.q, q_)); }
  /// The contact's normal force (N) or moment (N·m) now, ≥ 0.
  double contactForce(const ElementInput& in) const { return normalForceAt(gather(in.q, q_), gather(in.v, v_)); }

 protected:
  /// The generalized force Q (size() values) at the local q, dq.
  virtual void force(const Local& q, const Local& v, double* Q) const = 0;
  /// ∂Q/∂q and ∂Q/∂dq, column-major, size() × size() each.
  virtual void tangents(const Local& q, const Local& v, double* Qq, double* Qv) const = 0;
  virtual double energy(const Local& q) const = 0;
  virtual double closureAt(const Local& q) const = 0;
  virtual double normalForceAt(const Local& q, const Local& v) const = 0;
  Local gather(const double* x, const std::vector<int>& at) const;

 private:
  std::vector<int> nodes_, q_, v_;
};

/// The ground's surface: the plane at `height` along `up` (−gravity) through the inertial origin,
/// with a penalty law per contact point and regularized Coulomb friction
///   F_t = −μ N u_t / √(|u_t|² + v_s²),  u_t the point's velocity along the plane,
/// which acts like Coulomb's law above the friction speed v_s and like a viscous damper of
/// μ N / v_s below it (a resting part creeps at most at that rate's order under a tangential pull).
struct GroundSurface {
  double height = 0.0;  // m
  Vec3 up = Vec3::UnitZ();
  PenaltyLaw law;
  double friction = 0.0;        // μ
  double friction_speed = 0.05;  // v_s, m/s
};

/// A sphere of `radius` on a node against the ground: about the point r + R p of a node with a
/// rotation (a body: p its centroid), about the node's position otherwise. Penetration
/// δ = height + radius − P · up.
class GroundContactElement final : public ContactElement {
 public:
  GroundContactElement(const GroundSurface& ground, double radius, const Vec3& point, bool rotates, int node,
                       std::vector<int> q_indices, std::vector<int> v_indices);

 private:
  template <class S> Eigen::Matrix<S, 6, 1> generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<S, 6, 1>& v) const;
  template <class S> Vec3T<S> contactPoint(const Eigen::Matrix<S, 6, 1>& q) const;
  void force(const Local& q, const Local& v, double* Q) const override;
  void tangents(const Local& q, const Local& v, double* Qq, double* Qv) const override;
  double energy(const Local& q) const override;
  double closureAt(const Local& q) const override;
  double normalForceAt(const Local& q, const Local& v) const override;
  Eigen::Matrix<double, 6, 1> padded(const Local& x) const;

  GroundSurface ground_;
  double radius_;
  Vec3 point_;
  bool rotates_;
};

/// A boom's backstop: a rotational penalty law about the boom's foot hinge, acting where a
/// backstop strut does, at a point B up the boom. The boom's turn θ is that of the line from the
/// foot F (a point of the slewing body) to B about the hinge axis a (fixed in the slewing body),
/// from its drawn direction u: θ = atan2(a · (u × d), u · d), d = B − F. It closes as the boom
/// turns up by `engaged` (rad) in the direction `sense` (±1): δ = sense · θ − engaged. Its
/// moment M = f(δ) + c h(δ) sense · θ̇ pushes B back by the force M (a × d̂⊥)/|d⊥| · (−sense), d⊥
/// the part of d across a, and the slewing body at B the other way.
class BackstopElement final : public ContactElement {
 public:
  struct Hinge {
    Vec3 foot = Vec3::Zero();    // F, in the slewing body's node axes
    Vec3 axis = Vec3::UnitY();   // a, unit, in the slewing body's node axes
    Vec3 drawn = Vec3::UnitX();  // u, unit, across a, in the slewing body's node axes
    Vec3 point = Vec3::Zero();   // B, in the boom node's axes
    double sense = 1.0;
    double engaged = 0.0;  // rad
  };
  /// `slewing` and `boom`: frame nodes; their [r, φ] are the element's 12 coordinates.
  BackstopElement(const Hinge& hinge, const PenaltyLaw& law, int slewing, int boom, std::vector<int> q_indices,
                  std::vector<int> v_indices);

 private:
  template <class S> Eigen::Matrix<S, 12, 1> generalizedForce(const Eigen::Matrix<S, 12, 1>& q, const Eigen::Matrix<S, 12, 1>& v) const;
  template <class S> S turnOf(const Eigen::Matrix<S, 12, 1>& q) const;
  void force(const Local& q, const Local& v, double* Q) const override;
  void tangents(const Local& q, const Local& v, double* Qq, double* Qv) const override;
  double energy(const Local& q) const override;
  double closureAt(const Local& q) const override;
  double normalForceAt(const Local& q, const Local& v) const override;

  Hinge hinge_;
  PenaltyLaw law_;
};

}  // namespace cranesim
