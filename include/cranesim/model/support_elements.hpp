#pragma once
// A crane's support on an elastic bed: a pad, or a crawler track, of the supported body standing
// on Winkler springs of the soil at its points (a pad's centre; the middle of each stretch of a
// track), each
//   k = k_s · A   (k_s the modulus of subgrade reaction, A the bed area the point bears on),
// one-sided and smoothed as the ground's contacts are (elements/penalty_contact.hpp), so that a
// point lifts off and sets down again; its settlement δ = level − up · P. Per point, summed over
// the support's points:
//   Q = [F, p × Rᵀ F],  F = up N,  N = (f(δ) + c h(δ) δ̇)₊,
// with the energy Σ V(δ). One element per support computes the body's rotation once. The bed's
// shear springs across it (k_h, c_h), which hold the carriage in the plane within friction, are
// an AnchoredSupportElement's (model/anchored_support_element.hpp: friction with memory).

#include "cranesim/model/contact_elements.hpp"

namespace cranesim {

struct SupportBed {
  Vec3 up = Vec3::UnitZ();
  double level = 0.0;          // m along up: the point settles δ = level − up · P
  Vec3 anchor = Vec3::Zero();  // the point's drawn position, inertial
  PenaltyLaw law;              // the vertical spring, damper and smoothing
  double shear_stiffness = 0.0;  // k_h, N/m (model/anchored_support_element.hpp)
  double shear_damping = 0.0;    // c_h, N·s/m
  double friction = 0.5;         // μ between the support and the bed
};

/// A point of the supported body, in the body node's axes from its origin, on its bed.
struct SupportPoint {
  Vec3 point = Vec3::Zero();
  SupportBed bed;
};

class SupportElement final : public ContactElement {
 public:
  /// The node's [r, φ] are the coordinates.
  SupportElement(std::vector<SupportPoint> points, int node, std::vector<int> q_indices, std::vector<int> v_indices);

  /// Each point's vertical force (N, ≥ 0) now, in the order given.
  std::vector<double> pointForces(const ElementInput& in) const;
  /// Each point's position (inertial) now, in the order given.
  std::vector<Vec3> pointPositions(const ElementInput& in) const;

 private:
  template <class S> Eigen::Matrix<S, 6, 1> generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<S, 6, 1>& v) const;
  void force(const Local& q, const Local& v, double* Q) const override;
  void tangents(const Local& q, const Local& v, double* Qq, double* Qv) const override;
  double energy(const Local& q) const override;
  /// The deepest settlement of its points.
  double closureAt(const Local& q) const override;
  /// The vertical force of all its points.
  double normalForceAt(const Local& q, const Local& v) const override;

  std::vector<SupportPoint> points_;
};

}  // namespace cranesim
