#pragma once
// A tangential force held within friction: a spring-and-damper force T across a contact (the
// bed's shear stiffness and damping under a support) bounded by B = μ N, N the contact's normal
// force, with the square-root regularisation of the ground's friction (model/contact_elements.hpp)
// taken in force instead of speed:
//   F = T B / √(B² + |T|²)
// F ≈ T while |T| ≪ B (the bed's shear stiffness holds), |F| < B always, |F| → B as |T| grows:
// the contact slides when it must carry more than μ N, and not before (a statics pushed past
// μ N has no equilibrium). A contact off the ground (N = 0) carries nothing. The law keeps no
// memory of a slide: a contact that slid springs back as its push goes.
// For the spring alone (T = −k u), F = −∂Φ/∂u at fixed B, with
//   Φ(u; B) = (B √(B² + k²|u|²) − B²) / k
// (½ k |u|² while k|u| ≪ B, B |u| beyond); the work of F as B changes with N, −∂Φ/∂B · Ḃ, is
// not stored in Φ and goes into the element's dissipated power.

#include "cranesim/math/autodiff.hpp"

namespace cranesim {

/// The tangential force T held within the bound B ≥ 0 (zero where B = 0).
template <class S> Vec3T<S> frictionBounded(const Vec3T<S>& trial, const S& bound) {
  using std::sqrt;
  if (valueOf(bound) <= 0.0) return Vec3T<S>::Zero();
  return trial * (bound / sqrt(bound * bound + trial.squaredNorm()));
}

/// Φ(u; B) of a spring of stiffness k displaced by |u| = `displacement` under the bound B.
inline double frictionBoundedEnergy(double displacement, double stiffness, double bound) {
  if (bound <= 0.0 || stiffness <= 0.0) return 0.0;
  const double ku = stiffness * displacement;
  return (bound * std::sqrt(bound * bound + ku * ku) - bound * bound) / stiffness;
}

/// ∂Φ/∂B of the same spring.
inline double frictionBoundedEnergyPerBound(double displacement, double stiffness, double bound) {
  if (stiffness <= 0.0) return 0.0;
  if (bound <= 0.0) return displacement;
  const double ku = stiffness * displacement, root = std::sqrt(bound * bound + ku * ku);
  return (root + bound * bound / root - 2.0 * bound) / stiffness;
}

}  // namespace cranesim
