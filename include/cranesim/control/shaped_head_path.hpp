#pragma once
// An operator's slewing and luffing speeds turned into a path of the boom head that leaves the
// load still when the lever stops. The lever's head position p_L(t) (on the slewing circle, the
// drives' acceleration limits applied) is shaped in the horizontal plane by the zero-vibration
// shaper, p(t) = ½ p_L(t) + ½ p_L(t − T/2): each change of the head's velocity comes in two
// halves half a sway period apart, and the swings they give a pendulum of period T cancel.
// Shaping the position, not the slewing angle, keeps the two halves in the same horizontal
// direction: half a period later the crane has turned (by 13° after a 3 °/s slew's half-step),
// and halves along the boom's tangent at each instant would no longer cancel (they left 0.39 m
// of swing on the thesis crane where the position's halves leave 9 cm).
//
// The pendulum of period T (length L = g (T/2π)²) under the shaped head's acceleration a rides
// along as the swing the load should have:  θ̈ = −(g/L) θ − a/L  (θ the load's horizontal offset
// from below the head over L, in both horizontal directions). It is at rest again after each
// stop, so the feedback's reference ends at rest too.

#include <cstddef>
#include <deque>

#include <Eigen/Dense>

namespace cranesim {

class ShapedHeadPath {
 public:
  struct Limits {
    double slewing_acceleration;  // rad/s², may be infinite
    double radial_acceleration;   // m/s² of the head's radius, may be infinite
  };
  /// head: the boom head's horizontal position now, from the slewing axis (m); period: the sway
  /// period T at the start (s); the path begins at rest there.
  ShapedHeadPath(const Eigen::Vector2d& head, double period, const Limits& limits, double sample_time,
                 double gravity = 9.81);

  struct Sample {
    double slewing = 0.0, slewing_speed = 0.0;  // rad from the start, rad/s over the coming sample
    double radius = 0.0, radius_speed = 0.0;    // m, m/s
    // The reference pendulum's angles (rad) and rates (rad/s), radial (> 0 outward) and across
    // (> 0 in the sense of a positive slew), in the shaped head's axes.
    double radial = 0.0, across = 0.0, radial_rate = 0.0, across_rate = 0.0;
  };

  /// The path at the start of this sample, then advances it under the lever's slewing speed
  /// (rad/s) and head radius speed (m/s). `period`: the sway period now (s; it follows the hoist),
  /// which sets the shaper's delay and the reference pendulum's stiffness.
  Sample advance(double slewing_speed, double radius_speed, double period);

  /// The shaper's delay now: T/2 (s).
  double delay() const { return delay_samples_ * sample_time_; }

 private:
  Eigen::Vector2d leverPosition() const;
  Eigen::Vector2d delayedLeverPosition() const;

  Limits limits_;
  double sample_time_, gravity_, azimuth_;
  double lever_slewing_ = 0.0, lever_slewing_speed_ = 0.0, lever_radius_, lever_radius_speed_ = 0.0;
  double delay_samples_;  // T/2 in samples, not rounded: the delayed half moves smoothly as T follows the hoist
  std::deque<Eigen::Vector2d> lever_history_;  // p_L at the last samples, the newest last
  Eigen::Vector2d shaped_, shaped_velocity_ = Eigen::Vector2d::Zero();
  double slewing_ = 0.0;  // the shaped head's azimuth from the start, unwrapped
  Eigen::Vector2d angle_ = Eigen::Vector2d::Zero(), angle_rate_ = Eigen::Vector2d::Zero();  // θ, θ̇ (world x, y)
};

}  // namespace cranesim
