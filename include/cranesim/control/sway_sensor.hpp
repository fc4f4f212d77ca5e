#pragma once
// What the anti-sway controller reads of the load's swing: the hoist rope's angles at the boom
// head and their rates as a real sensor gives them — late by a transport delay d and with white
// noise. Each sample k,
//   measured_k = truth(t_k − d) + n_k,   n_k ~ N(0, σ²), independent per sample and channel,
// with truth(t_k − d) interpolated linearly between the samples around it (before the first
// sample: the first sample). The drives' encoders and the rope's length stay exact.

#include <Eigen/Core>

#include <random>

#include "cranesim/control/delay_line.hpp"
#include "cranesim/model/sway_sensor_spec.hpp"
#include "cranesim/session/session.hpp"

namespace cranesim {

class SwaySensor {
 public:
  /// std::invalid_argument for a negative or non-finite noise or delay.
  SwaySensor(const SwaySensorSpec& spec, double sample_time);

  /// Takes this sample's true swing and returns what the controller reads.
  Session::Sway read(const Session::Sway& truth);

  /// s: how late a reading is.
  double delay() const { return spec_.delay; }

 private:
  SwaySensorSpec spec_;
  DelayLine<Eigen::Vector4d> delayed_;  // [radial, across, their rates]
  std::mt19937_64 random_;
  std::normal_distribution<double> normal_;
};

/// The swing now from a reading `delay` s old: the pendulum θ̈ = −(g/L) θ − v̇/L (sway_axis.hpp)
/// carried over the delay to first order in ω·delay (ω² = g/L), the head's change of speed since
/// the reading, [along (radial), across] in m/s, turning the rope at once. The error is of second
/// order: 0.0006 of the swing for a 17 s period and 0.1 s.
Session::Sway predictOverDelay(const Session::Sway& late, double delay, double gravity, double rope_length,
                               const Eigen::Vector2d& head_speed_change);

}  // namespace cranesim
