#pragma once
// The unstretched length of a rope that a winch may reel in or out, shared by the rope kernels
// (spline_rope.hpp, cable.hpp): L(t) = length(t)/segments per element and its exact rate.

#include "cranesim/math/autodiff.hpp"
#include "cranesim/math/profile.hpp"

namespace cranesim {

struct ReeledLength {
  Profile total_length = Profile(ConstantProfile{1.0});  // unstretched length of the whole rope
  int segments = 1;                                        // elements the rope is divided into

  double segmentLength(double t) const { return total_length(t) / segments; }

  /// L̇ = d/dt length(t)/segments, exact: forward AD through the profile; one-sided at a
  /// breakpoint, or 0 with the length held (statics).
  double segmentRate(double t, ParameterRates rates = ParameterRates::Left) const {
    if (rates == ParameterRates::Held) return 0.0;
    const Limit side = rates == ParameterRates::Right ? Limit::Right : Limit::Left;
    return total_length(seeded<double, 1>(t, 0), side).derivatives()(0) / segments;
  }
};

}  // namespace cranesim
