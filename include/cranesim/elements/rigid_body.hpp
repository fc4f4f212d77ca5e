#pragma once
// Rigid body kernel (thesis 3.1, C.1). Generalized coordinates q = [r⁰, φ] and velocities
// dq = [ṙ⁰ (inertial), ω (body frame)] (3-1). The origin may lie anywhere: the centroid sits
// at r⁰ᶜ in body axes. Equations of motion: M(q) d(dq)/dt + F(q, dq) = generalized forces.

#include "cranesim/math/rotation.hpp"

namespace cranesim {

struct RigidBodyKernel {
  static constexpr int kNodes = 1;
  static constexpr int kNq = 6;
  static constexpr int kNv = 6;
  template <class S> using Q = Eigen::Matrix<S, kNq, 1>;
  template <class S> using V = Eigen::Matrix<S, kNv, 1>;

  double mass = 1.0;
  Vec3 centroid = Vec3::Zero();             // r⁰ᶜ, body axes
  Mat3 inertia_origin = Mat3::Identity();   // Θ⁰ about the origin, body axes

  /// Θ⁰ from the inertia about the centroid (parallel-axis theorem).
  static Mat3 inertiaAboutOrigin(double m, const Vec3& c, const Mat3& inertia_centroid) {
    return inertia_centroid - m * skew(c) * skew(c);
  }

  /// Mass matrix (3-4): [[m I, −m R r̃ᶜ], [m r̃ᶜ Rᵀ, Θ⁰]].
  template <class S> Eigen::Matrix<S, 6, 6> massMatrix(const Q<S>& q, double = 0.0) const {
    const Mat3T<S> R = rotationMatrix<S>(q.template tail<3>());
    const Mat3T<S> c = skew<S>(centroid.cast<S>());
    Eigen::Matrix<S, 6, 6> M;
    M.template topLeftCorner<3, 3>() = Mat3T<S>::Identity() * S(mass);
    M.template topRightCorner<3, 3>() = -mass * (R * c);
    M.template bottomLeftCorner<3, 3>() = mass * (c * R.transpose());
    M.template bottomRightCorner<3, 3>() = inertia_origin.cast<S>();
    return M;
  }

  /// F = quadratic-velocity terms (3-4: D·dq) + gravity (3-5), on the left-hand side:
  /// [m R ω̃ ω̃ r⁰ᶜ − m g, ω̃ Θ⁰ ω − m r̃⁰ᶜ Rᵀ g].
  template <class S> V<S> force(const Q<S>& q, const V<S>& v, double, const Vec3& gravity) const {
    const Mat3T<S> R = rotationMatrix<S>(q.template tail<3>());
    const Vec3T<S> w = v.template tail<3>();
    const Vec3T<S> c = centroid.cast<S>();
    const Vec3T<S> g = gravity.cast<S>();
    V<S> F;
    F.template head<3>() = mass * (R * w.cross(w.cross(c))) - mass * g;
    F.template tail<3>() = w.cross(inertia_origin.cast<S>() * w) - mass * c.cross(R.transpose() * g);
    return F;
  }

  double kineticEnergy(const Q<double>& q, const V<double>& v, double = 0.0) const {
    return 0.5 * v.dot(massMatrix<double>(q) * v);
  }

  /// −m g·rᶜ: zero at the inertial origin.
  double potentialEnergy(const Q<double>& q, double, const Vec3& gravity) const {
    const Vec3 rc = q.head<3>() + rotationMatrix<double>(q.tail<3>()) * centroid;
    return -mass * gravity.dot(rc);
  }
};

}  // namespace cranesim
