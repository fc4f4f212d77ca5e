#pragma once
// Evaluates a constraint and its derivatives at the generalized coordinates q.
//
// The equations are written in joint frames (model/constraint_equations.hpp). Each of the two
// joints sits on a node whose frame is perturbed by a body-frame twist δ = [δr, δθ]:
// r + δr, R (I + δθ̃). Differentiating with respect to δ at δ = 0 gives the velocity Jacobian
// G = Bᵀ with Φ̇ = G dq + Φ_t (4-11), because dq holds [ṙ, ω_body]. Direction 12 is time.
//
// With Q = double this yields Φ, G and Φ_t. With Q = Dual<double, 1> the node coordinates
// [r, φ] of both nodes and time are seeded along given rates (q̇, 1): every entry of G carries
// its rate along the motion, Ġ, which is all Γ (4-27) needs. With Q = Dual<double, 13> they are
// seeded in their own directions, so every entry of G carries its derivatives with respect to q
// and t: the reference the DAE Jacobian's closed form (constraint_second_derivatives.hpp) is
// tested against.

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/rotation.hpp"
#include "cranesim/model/model.hpp"

namespace cranesim {

inline constexpr int kConstraintDirections = 13;  // twists of two nodes + time
inline constexpr int kTimeDirection = 12;
inline constexpr int kMaxConstraintRows = 6;

using ConstraintQDual = Dual<double, kConstraintDirections>;
using ConstraintRateDual = Dual<double, 1>;

template <class Q> struct ConstraintDerivatives {
  int rows = 0;
  Eigen::Matrix<Q, kMaxConstraintRows, 1> phi;
  /// [∂Φ/∂δ₁ (6), ∂Φ/∂δ₂ (6), Φ_t]
  Eigen::Matrix<Q, kMaxConstraintRows, kConstraintDirections> G;
};

namespace detail {
/// A node coordinate or time as Q: plain, seeded in its own direction (ConstraintQDual), or
/// seeded with its rate rates[direction] (ConstraintRateDual).
template <class Q> Q seedCoordinate(double value, int direction, const double* rates) {
  if constexpr (std::is_same_v<Q, double>) {
    return value;
  } else if constexpr (std::is_same_v<Q, ConstraintRateDual>) {
    Q x(value);
    x.derivatives()(0) = rates[direction];
    return x;
  } else {
    return seeded<double, kConstraintDirections>(value, direction);
  }
}

/// The joint frame of `joint`, perturbed by the twist directions of `side` (0 or 1). The
/// perturbation is linear in δ, so its derivatives are written down directly:
/// ∂r_J/∂δr = I, ∂r_J/∂δθ_k = R (e_k × r_BJ), ∂R_J/∂δθ_k = R ẽ_k R_BJ (4-5, 4-7).
template <class Q>
FrameT<Dual<Q, kConstraintDirections>> perturbedJointFrame(const Model& model, int joint, const double* q, int side,
                                                           const double* rates) {
  using D = Dual<Q, kConstraintDirections>;
  const Joint& J = model.joints[joint];
  FrameT<D> f;
  if (J.node < 0) {
    for (int k = 0; k < 3; ++k) f.r(k) = constant<Q, kConstraintDirections>(Q(J.offset(k)));
    for (int k = 0; k < 9; ++k) f.R(k) = constant<Q, kConstraintDirections>(Q(J.rotation(k)));
    return f;
  }
  const Node& N = model.nodes[J.node];
  Vec3T<Q> r, phi = Vec3T<Q>::Zero();
  for (int k = 0; k < 3; ++k) {
    r(k) = seedCoordinate<Q>(q[N.q + k], 6 * side + k, rates);
    if (N.hasRotation()) phi(k) = seedCoordinate<Q>(q[N.q + 3 + k], 6 * side + 3 + k, rates);
  }
  const Mat3T<Q> R = N.hasRotation() ? rotationMatrix<Q>(phi) : Mat3T<Q>::Identity();
  const Vec3T<Q> offset = J.offset.cast<Q>();
  const Mat3T<Q> rotation = J.rotation.cast<Q>();
  const Vec3T<Q> rJ = r + R * offset;
  const Mat3T<Q> RJ = R * rotation;
  for (int i = 0; i < 3; ++i) f.r(i) = constant<Q, kConstraintDirections>(rJ(i));
  for (int i = 0; i < 9; ++i) f.R(i) = constant<Q, kConstraintDirections>(RJ(i));
  for (int i = 0; i < 3; ++i) f.r(i).derivatives()(6 * side + i) = Q(1.0);
  if (!N.hasRotation()) return f;  // a point: its joint frame only translates
  for (int k = 0; k < 3; ++k) {
    const Vec3T<Q> dr = R * Vec3::Unit(k).cast<Q>().cross(offset);
    const Mat3T<Q> dR = R * skew<Q>(Vec3::Unit(k).cast<Q>()) * rotation;
    for (int i = 0; i < 3; ++i) f.r(i).derivatives()(6 * side + 3 + k) = dr(i);
    for (int i = 0; i < 9; ++i) f.R(i).derivatives()(6 * side + 3 + k) = dR(i);
  }
  return f;
}
}  // namespace detail

/// `rates`: with Q = ConstraintRateDual, the rates of the constraint's 13 local coordinates
/// (both nodes' [r, φ] and time, as the directions of G).
template <class Q>
ConstraintDerivatives<Q> evaluateConstraint(const Model& model, const Constraint& c, const double* q, double t,
                                            Limit limit = Limit::Left, const double* rates = nullptr) {
  using D = Dual<Q, kConstraintDirections>;
  const FrameT<D> j1 = detail::perturbedJointFrame<Q>(model, c.joint1, q, 0, rates);
  const FrameT<D> j2 = detail::perturbedJointFrame<Q>(model, c.joint2, q, 1, rates);
  const D time = seeded<Q, kConstraintDirections>(detail::seedCoordinate<Q>(t, kTimeDirection, rates),
                                                  kTimeDirection);
  D phi[kMaxConstraintRows];
  constraintEquations<D>(c.law(limit), j1, j2, time, phi);
  ConstraintDerivatives<Q> out;
  out.rows = c.rows;
  for (int i = 0; i < c.rows; ++i) {
    out.phi(i) = phi[i].value();
    out.G.row(i) = phi[i].derivatives().transpose();
  }
  return out;
}

}  // namespace cranesim
