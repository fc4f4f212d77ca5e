#pragma once
// A crane's supports on an elastic bed: a point of the supported body (an outrigger pad's
// centre, or the middle of one stretch of a crawler track) on a Winkler spring of the soil,
//   k = k_s · A   (k_s the modulus of subgrade reaction, A the bed area the point bears on),
// one-sided and smoothed as the ground's contacts are (elements/penalty_contact.hpp), so that a
// pad lifts off and sets down again; its settlement δ = level − up · P. A horizontal spring k_h
// ties the point to where it was drawn (the bed's shear stiffness under the pad, which holds the
// carriage in the plane: without it a free carriage on vertical springs has no static stiffness
// across them). A horizontal damper of the same damping ratio as the vertical one goes with it.
//   Q = [F, p × Rᵀ F],  F = up (f(δ) + c h(δ) δ̇)₊ − k_h u_h − c_h u̇_h,
// u_h the point's horizontal displacement from its drawn position. The energy is V(δ) + ½ k_h |u_h|².

#include "cranesim/model/contact_elements.hpp"

namespace cranesim {

struct SupportBed {
  Vec3 up = Vec3::UnitZ();
  double level = 0.0;       // m along up: the point settles δ = level − up · P
  Vec3 anchor = Vec3::Zero();  // the point's drawn position, inertial
  PenaltyLaw law;           // the vertical spring, damper and smoothing
  double shear_stiffness = 0.0;  // k_h, N/m
  double shear_damping = 0.0;    // c_h, N·s/m
};

class SupportPointElement final : public ContactElement {
 public:
  /// `point` in the body node's axes from its origin; the node's [r, φ] are the coordinates.
  SupportPointElement(const SupportBed& bed, const Vec3& point, int node, std::vector<int> q_indices, std::vector<int> v_indices);

 private:
  template <class S> Eigen::Matrix<S, 6, 1> generalizedForce(const Eigen::Matrix<S, 6, 1>& q, const Eigen::Matrix<S, 6, 1>& v) const;
  Vec3 pointAt(const Local& q) const;
  void force(const Local& q, const Local& v, double* Q) const override;
  void tangents(const Local& q, const Local& v, double* Qq, double* Qv) const override;
  double energy(const Local& q) const override;
  double closureAt(const Local& q) const override;
  double normalForceAt(const Local& q, const Local& v) const override;

  SupportBed bed_;
  Vec3 point_;
};

}  // namespace cranesim
