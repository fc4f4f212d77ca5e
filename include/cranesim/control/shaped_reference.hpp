#pragma once
// An operator's speed command along one axis, shaped so that it leaves a pendulum still: the
// zero-vibration (ZV) shaper passes half of each command at once and half T/2 later (T the
// pendulum's period), and the reference speed follows the shaped command within the drive's
// acceleration limit. The pendulum's swing under the reference's acceleration rides along as the
// swing the feedback should see: while the head accelerates the load lags behind it on purpose,
// and the feedback acts only on the difference.
//
// With the head's acceleration a along the axis, the reference pendulum of length L = g (T/2π)²
// swings as  θ̈ = −(g/L) θ − a/L  (the design model of control/sway_axis.hpp).

#include <cstddef>
#include <deque>

namespace cranesim {

class ShapedReference {
 public:
  /// period: T (s, > 0); acceleration_limit: the drive's (in the command's units per s², may be
  /// infinite); start: the reference position at rest.
  ShapedReference(double period, double acceleration_limit, double sample_time, double start, double gravity = 9.81);

  struct Sample {
    double position = 0.0, speed = 0.0;  // the command's units and per second
    double angle = 0.0, angle_rate = 0.0;  // rad, rad/s
  };

  /// The reference at the start of this sample, then advances it over the sample under
  /// `command` (the operator's speed). `metres_per_unit`: the head's displacement along the axis
  /// per unit of the command's drive (the slewing radius in m/rad, the head's radius per metre
  /// of luffing rope).
  Sample advance(double command, double metres_per_unit);

  /// The time the shaped reference lags the operator's command by: T/2 rounded to samples.
  double delay() const { return static_cast<double>(delay_samples_) * sample_time_; }

 private:
  double period_, acceleration_limit_, sample_time_, gravity_, length_;
  std::size_t delay_samples_;
  std::deque<double> commands_;  // the last delay_samples_ commands, the oldest first
  Sample now_;
};

}  // namespace cranesim
