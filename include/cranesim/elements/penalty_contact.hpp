#pragma once
// A compliant unilateral contact (a penalty law): a spring k that pushes only while the contact
// is closed by δ > 0 (penetration, or a stop's compression), and a damper c that acts only then.
// The spring's force is smoothed over the first `smoothing` ε of closure so that the force is
// continuously differentiable where the contact closes (the integrator's Newton iterations
// converge across it):
//   f(δ) = 0                 δ ≤ 0
//          k δ² / (2ε)       0 < δ < ε
//          k (δ − ε/2)       δ ≥ ε
//   V(δ) = ∫₀^δ f            its energy, so that the force is conservative
//   h(δ) = clamp(δ/ε, 0, 1)  the damper's share: it engages as the spring does
// The contact force f(δ) + c h(δ) δ̇ is never a pull: a contact opening faster than its spring
// relaxes carries no force (the caller clamps it at 0).

#include <algorithm>

#include "cranesim/math/autodiff.hpp"

namespace cranesim {

struct PenaltyLaw {
  double stiffness = 0.0;  // k: N/m, or N·m/rad for a rotational stop
  double damping = 0.0;    // c: N·s/m, or N·m·s/rad
  double smoothing = 0.0;  // ε: m, or rad; > 0
};

template <class S> S penaltySpringForce(const S& closure, const PenaltyLaw& law) {
  const double d = valueOf(closure), eps = law.smoothing;
  if (d <= 0.0) return S(0.0);
  if (d < eps) return closure * closure * (law.stiffness / (2.0 * eps));
  return (closure - 0.5 * eps) * law.stiffness;
}

inline double penaltyEnergy(double closure, const PenaltyLaw& law) {
  const double eps = law.smoothing;
  if (closure <= 0.0) return 0.0;
  if (closure < eps) return law.stiffness * closure * closure * closure / (6.0 * eps);
  return law.stiffness * (0.5 * closure * closure - 0.5 * eps * closure + eps * eps / 6.0);
}

template <class S> S penaltyDamperShare(const S& closure, const PenaltyLaw& law) {
  const double d = valueOf(closure);
  if (d <= 0.0) return S(0.0);
  if (d < law.smoothing) return closure / law.smoothing;
  return S(1.0);
}

/// The contact's force at closure δ closing at rate δ̇: spring plus damper, never negative.
template <class S> S penaltyForce(const S& closure, const S& closing_rate, const PenaltyLaw& law) {
  const S f = penaltySpringForce(closure, law) + closing_rate * penaltyDamperShare(closure, law) * law.damping;
  return valueOf(f) > 0.0 ? f : S(0.0);
}

}  // namespace cranesim
