#pragma once
// Aerodynamic drag of the air's velocity relative to a part (aerodynamic damping included):
//   bluff body (a load):          F = ½ ρ c A |u| u,      u = w − v
//   cylinder (rope, tube, beam):  f = ½ ρ c d |u⊥| u⊥,    u⊥ = (I − e eᵀ)(w − v), per unit length
// with w the wind's and v the part's velocity, A the wind area, d the diameter and e the
// cylinder's axis: the component of the flow along a cylinder's axis exerts no pressure drag
// (the cross-flow principle).

#include <cmath>

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/types.hpp"

namespace cranesim {

/// |u| u times `coefficient`; zero at u = 0, where it is flat (its derivative vanishes).
template <class S> Vec3T<S> quadraticDrag(const Vec3T<S>& u, double coefficient) {
  using std::sqrt;
  const S u2 = u.squaredNorm();
  if (valueOf(u2) == 0.0) return Vec3T<S>::Zero();
  return u * (coefficient * sqrt(u2));
}

/// ∂(|u| u)/∂u = |u| I + u uᵀ/|u|, 0 at u = 0.
inline Mat3 quadraticDragTangent(const Vec3& u) {
  const double n = u.norm();
  if (n == 0.0) return Mat3::Zero();
  return n * Mat3::Identity() + u * u.transpose() / n;
}

/// u − e (e · u): the part of u normal to the unit axis e.
template <class S> Vec3T<S> normalPart(const Vec3T<S>& u, const Vec3T<S>& e) { return u - e * e.dot(u); }

}  // namespace cranesim
